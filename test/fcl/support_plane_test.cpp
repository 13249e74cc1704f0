// Distance between FCL's primitive shapes and planes / half-spaces through fcl_quadric's front door
// (QuadricPairKind::kSupportPlane). Stock FCL 0.7 segfaults on every one of these pairs (its GJK
// has no support function for a plane; docs/reliability.md, finding 5), so the oracle is an
// independent enumeration of the shape's boundary: box and convex vertices, capsule end caps,
// 2,048 points on each cylinder / cone rim, the sphere's closed form. Also checked: collision
// through the front door agrees with the sign (FCL's own closed forms for the sphere, box and
// capsule; ours for the cylinder, cone and convex, where FCL 0.7 reports contact at gaps up to 0.5
// or segfaults), both argument orders agree, the witness points lie on their solids, contacts
// carry the depth and the normal from o1 to o2, and bad shapes give the documented error.
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>

#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "support/random_ellipsoids.h"

namespace {

using Vec3 = Eigen::Vector3d;

struct Posed {
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  std::vector<Vec3> boundary;  // world points whose extremes along any direction are the shape's (to sampling)
  double sampling_error = 0.0;
};

std::vector<Vec3> rim(const fcl::Transform3d& tf, double r, double z, int n = 2048) {
  std::vector<Vec3> pts;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n;
    pts.push_back(tf * Vec3(r * std::cos(a), r * std::sin(a), z));
  }
  return pts;
}

// Shape kind k (0 sphere, 1 box, 2 capsule, 3 cylinder, 4 cone, 5 convex) with random size, posed.
Posed makeShape(int kind, const fcl::Transform3d& tf, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.3, 2.0);
  Posed s;
  const double r = u(rng), l = u(rng);
  if (kind == 0) {
    s.geometry = std::make_shared<fcl::Sphered>(r);
  } else if (kind == 1) {
    const double x = u(rng), y = u(rng), z = u(rng);
    s.geometry = std::make_shared<fcl::Boxd>(x, y, z);
    for (int v = 0; v < 8; ++v)
      s.boundary.push_back(tf * Vec3(v & 1 ? x / 2 : -x / 2, v & 2 ? y / 2 : -y / 2, v & 4 ? z / 2 : -z / 2));
  } else if (kind == 2) {
    s.geometry = std::make_shared<fcl::Capsuled>(r, l);
  } else if (kind == 3) {
    s.geometry = std::make_shared<fcl::Cylinderd>(r, l);
    s.boundary = rim(tf, r, l / 2);
    const std::vector<Vec3> bottom = rim(tf, r, -l / 2);
    s.boundary.insert(s.boundary.end(), bottom.begin(), bottom.end());
    s.sampling_error = r * (1.0 - std::cos(M_PI / 2048));
  } else if (kind == 4) {
    s.geometry = std::make_shared<fcl::Coned>(r, l);
    s.boundary = rim(tf, r, -l / 2);
    s.boundary.push_back(tf * Vec3(0, 0, l / 2));
    s.sampling_error = r * (1.0 - std::cos(M_PI / 2048));
  } else {
    // An irregular octahedron.
    auto verts = std::make_shared<std::vector<Vec3>>();
    for (int i = 0; i < 3; ++i) {
      Vec3 e = Vec3::Zero();
      e[i] = u(rng);
      verts->push_back(e);
      e[i] = -u(rng);
      verts->push_back(e);
    }
    // Faces (count, indices...): the 8 octants, outward order irrelevant for the vertex support.
    auto faces = std::make_shared<std::vector<int>>();
    for (int sx : {0, 1})
      for (int sy : {2, 3})
        for (int sz : {4, 5}) faces->insert(faces->end(), {3, sx, sy, sz});
    s.geometry = std::make_shared<fcl::Convexd>(verts, 8, faces);
    for (const Vec3& v : *verts) s.boundary.push_back(tf * v);
  }
  if (kind == 0) {
    s.boundary = {tf.translation()};  // the extremes are c +- r n: added per direction below
  } else if (kind == 2) {
    s.boundary = {tf * Vec3(0, 0, l / 2), tf * Vec3(0, 0, -l / 2)};  // end caps' centres, +- r below
  }
  return s;
}

double radiusOf(const fcl::CollisionGeometryd& g) {
  if (auto* s = dynamic_cast<const fcl::Sphered*>(&g)) return s->radius;
  if (auto* c = dynamic_cast<const fcl::Capsuled*>(&g)) return c->radius;
  return 0.0;
}

TEST(SupportPlane, DistancesToPlanesAndHalfspacesMatchBoundaryEnumeration) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int separated = 0, overlapping = 0;
  for (int kind = 0; kind < 6; ++kind) {
    for (int trial = 0; trial < 120; ++trial) {
      fcl::Transform3d tf = fcl::Transform3d::Identity();
      tf.linear() = fcl_quadric::test::randomRotation(rng);
      const double x = U(rng), y = U(rng), z = U(rng);
      tf.translation() = Vec3(x, y, z);
      const Posed shape = makeShape(kind, tf, rng);
      const Vec3 n = fcl_quadric::test::randomUnitVector(rng);
      const double d = 2.5 * U(rng);
      const bool halfspace = trial % 2 == 1;
      std::shared_ptr<fcl::CollisionGeometryd> plane;
      if (halfspace) plane = std::make_shared<fcl::Halfspaced>(n, d);
      else plane = std::make_shared<fcl::Planed>(n, d);

      // Oracle: extremes of n.x - d over the enumerated boundary.
      const double radius = radiusOf(*shape.geometry);
      double lo = INFINITY, hi = -INFINITY;
      for (const Vec3& p : shape.boundary) {
        lo = std::min(lo, n.dot(p) - d - radius);
        hi = std::max(hi, n.dot(p) - d + radius);
      }
      const double band = shape.sampling_error + 1e-9;
      const fcl::Transform3d I = fcl::Transform3d::Identity();
      for (int order = 0; order < 2; ++order) {
        const fcl::CollisionGeometryd* g1 = order ? plane.get() : shape.geometry.get();
        const fcl::CollisionGeometryd* g2 = order ? shape.geometry.get() : plane.get();
        const fcl::Transform3d& t1 = order ? I : tf;
        const fcl::Transform3d& t2 = order ? tf : I;
        const std::string what = "kind " + std::to_string(kind) + " trial " + std::to_string(trial) +
                                 (halfspace ? " halfspace" : " plane") + " order " + std::to_string(order);
        fcl::DistanceRequestd request(true);
        fcl::DistanceResultd result;
        const double dist = fcl_quadric::distance(g1, t1, g2, t2, request, result);
        const bool oracle_separate = lo > band || (!halfspace && hi < -band);
        const bool oracle_overlap = lo < -band && (halfspace || hi > band);
        fcl::CollisionRequestd creq;
        fcl::CollisionResultd cres;
        fcl_quadric::collide(g1, t1, g2, t2, creq, cres);
        if (oracle_separate) {
          ++separated;
          const double expected = lo > 0 ? lo : -hi;
          EXPECT_NEAR(dist, expected, band + 1e-12) << what;
          EXPECT_FALSE(cres.isCollision()) << what << " gap " << expected;
          const Vec3& on_shape = result.nearest_points[order];
          const Vec3& on_plane = result.nearest_points[1 - order];
          EXPECT_NEAR(n.dot(on_plane), d, 1e-9) << what;
          EXPECT_NEAR((on_shape - on_plane).norm(), dist, 1e-9) << what;
        } else if (oracle_overlap) {
          ++overlapping;
          EXPECT_EQ(dist, -1.0) << what << " (libccd's convention for overlapping shapes)";
          EXPECT_TRUE(cres.isCollision()) << what;
          // Signed: minus the depth, to the side of the shape's centre for a plane.
          fcl::DistanceRequestd srequest(true);
          srequest.enable_signed_distance = true;
          fcl::DistanceResultd sresult;
          const double sd = fcl_quadric::distance(g1, t1, g2, t2, srequest, sresult);
          const bool up = halfspace || n.dot(tf.translation()) - d >= 0.0;
          EXPECT_NEAR(sd, up ? lo : -hi, band + 1e-12) << what;
          EXPECT_LT(sd, 0.0) << what;
          if (kind >= 3) {  // cylinder, cone, convex: our contact (FCL's closed forms are wrong or crash)
            fcl::CollisionRequestd contact_request(1, true);
            fcl::CollisionResultd contact_result;
            fcl_quadric::collide(g1, t1, g2, t2, contact_request, contact_result);
            ASSERT_EQ(contact_result.numContacts(), 1u) << what;
            const fcl::Contactd& c = contact_result.getContact(0);
            EXPECT_NEAR(c.penetration_depth, -sd, 1e-12) << what;
            EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12) << what;
            // Normal from o1 to o2: moving o2 by the depth along it separates them.
            const Vec3 toward_plane = up ? Vec3(-n) : n;
            EXPECT_NEAR(c.normal.dot(order ? Vec3(-toward_plane) : toward_plane), 1.0, 1e-9) << what;
          }
        }
      }
    }
  }
  EXPECT_GT(separated, 200);
  EXPECT_GT(overlapping, 200);
}

TEST(SupportPlane, BadShapesGiveTheDocumentedError) {
  const fcl::Planed plane(Vec3::UnitZ(), 0.0);
  const fcl::Boxd box(-1.0, 1.0, 1.0);
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  try {
    fcl_quadric::distance(&box, I, &plane, I, request, result);
    ADD_FAILURE() << "a negative box side was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("o1"), std::string::npos) << e.what();
  }
  fcl::Transform3d sheared = I;
  sheared.linear()(0, 1) = 0.5;  // not a rotation
  const fcl::Cylinderd cylinder(1.0, 1.0);
  EXPECT_THROW(fcl_quadric::distance(&plane, I, &cylinder, sheared, request, result), std::invalid_argument);
  // Two planes / half-spaces: stock FCL segfaults; the front door throws, naming the pair.
  const fcl::Halfspaced halfspace(Vec3::UnitX(), 1.0);
  for (const fcl::CollisionGeometryd* other : {static_cast<const fcl::CollisionGeometryd*>(&plane),
                                               static_cast<const fcl::CollisionGeometryd*>(&halfspace)}) {
    try {
      fcl_quadric::distance(other, I, &halfspace, I, request, result);
      ADD_FAILURE() << "distance between two planes / half-spaces did not throw";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("two planes"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
