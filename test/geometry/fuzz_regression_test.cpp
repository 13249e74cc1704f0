// Regression tests of the findings of the fuzz targets (docs/reliability.md, section 5).
#include <gtest/gtest.h>

#include <cmath>

#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/signed_distance.h"

namespace fcl_quadric {
namespace {

// fuzz_static, seed corpus "tiny_huge": sizes 1e200 apart overflow the pencil; the pair is
// reported Touching (conservative, docs/tolerances.md), and the certificate used to carry
// psi = NaN. A flat disk of thickness 2e-100 at the origin and a cigar of half-length 1e100
// whose tip is the origin: their interiors meet (exactly: overlapping), so contact is right.
TEST(FuzzRegression, CertificateOfAnOverflowingPencilHasNoNaN) {
  const Ellipsoid a({1e-100, 1, 1}, Eigen::Matrix3d::Identity(), {0, 0, 0});
  const Ellipsoid b({1e100, 1, 1}, Eigen::Matrix3d::Identity(), {1e100, 0, 0});
  for (const auto& [x, y] : {std::make_pair(&a, &b), std::make_pair(&b, &a)}) {
    const SeparationCertificate c = classifyEllipsoids(*x, *y);
    EXPECT_NE(c.status, Separation::Separated);
    EXPECT_FALSE(std::isnan(c.psi));
    EXPECT_FALSE(std::isnan(c.mu));
    EXPECT_TRUE(c.witness.allFinite()) << c.witness.transpose();
    EXPECT_TRUE(c.normal.allFinite()) << c.normal.transpose();
    EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
    const SignedDistanceResult d = signedDistance(*x, *y);
    EXPECT_FALSE(std::isnan(d.distance));
    EXPECT_LE(d.distance, 0.0);
  }
}

}  // namespace
}  // namespace fcl_quadric
