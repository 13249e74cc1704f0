// libFuzzer target: polynomial motions and continuous collision (docs/reliability.md).
// Input: a 4x4 polynomial motion matrix of degree up to kMaxDegree with raw-double coefficients
// (fuzz_common.h encoding: huge, tiny, subnormal, NaN and inf included), the radii of the body
// ellipsoid it carries, a second ellipsoid moving between two poses, and options. Properties:
//  - PolynomialMatrix4::fromCoefficients throws std::invalid_argument exactly for non-finite
//    coefficients; MotionMatrix::fromPolynomialMatrix accepts or throws std::invalid_argument,
//    and always rejects a last row that is not [0, 0, 0, w];
//  - continuousCollideEllipsoids never returns NaN; its times lie in [0, 1], its intervals are
//    sorted and well formed, first_contact_time is the start of the first collision interval;
//  - symmetry: a collision certified (not near_tangent) in one argument order is a collision in
//    the other;
//  - oracle: at 9 sample times, where the exact oracle says the world ellipsoids clearly overlap,
//    the instant lies in a reported collision interval (the solver errs toward contact, never
//    away from it).
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fuzz_common.h"

using namespace fcl_quadric;
using fcl_quadric::fuzz::Reader;

namespace {

constexpr int kMaxDegree = 6;

void checkResult(const EllipsoidCcdResult& r, const CcdOptions& o, const char* what) {
  FUZZ_CHECK(!r.contact_point.hasNaN(), "%s: NaN contact point", what);
  FUZZ_CHECK(r.collide == r.first_contact_time.has_value(), "%s: collide %d without a first contact time", what,
             r.collide);
  FUZZ_CHECK(r.collide == !r.collision_intervals.empty(), "%s: collide %d vs %zu intervals", what, r.collide,
             r.collision_intervals.size());
  if (r.first_contact_time) {
    const double t = *r.first_contact_time;
    FUZZ_CHECK(t >= 0 && t <= o.t_max, "%s: first contact time %g outside [0, t_max]", what, t);
    FUZZ_CHECK(t == r.collision_intervals.front().begin, "%s: first contact %.17g vs first interval %.17g", what, t,
               r.collision_intervals.front().begin);
  }
  for (const auto* list : {&r.collision_intervals, &r.separation_intervals}) {
    double last = -1;
    for (const CcdInterval& iv : *list) {
      FUZZ_CHECK(iv.begin >= 0 && iv.begin <= iv.end && iv.end <= 1, "%s: bad interval [%g, %g]", what, iv.begin,
                 iv.end);
      FUZZ_CHECK(iv.begin >= last, "%s: unsorted intervals", what);
      last = iv.end;
    }
  }
}

bool inCollisionInterval(const EllipsoidCcdResult& r, double t) {
  for (const CcdInterval& iv : r.collision_intervals)
    if (t >= iv.begin - 1e-9 && t <= iv.end + 1e-9) return true;
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Reader in(data, size);
  const int degree = in.byte() % (kMaxDegree + 1);
  const bool bad_last_row = in.byte() == 0xFF;  // rarely: a non-zero (3, j), j < 3
  std::vector<Eigen::Matrix4d> coefficients(degree + 1, Eigen::Matrix4d::Zero());
  bool finite = true;
  for (int k = 0; k <= degree; ++k) {
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        if (i == 3 && j < 3 && !bad_last_row) continue;
        coefficients[k](i, j) = in.value();
        finite = finite && std::isfinite(coefficients[k](i, j));
      }
    }
  }
  bool last_row_nonzero = false;
  for (const auto& C : coefficients) last_row_nonzero = last_row_nonzero || C.block<1, 3>(3, 0).any() ;

  PolynomialMatrix4 M;
  try {
    M = PolynomialMatrix4::fromCoefficients(coefficients);
    FUZZ_CHECK(finite, "non-finite coefficient accepted");
  } catch (const std::invalid_argument&) {
    FUZZ_CHECK(!finite, "finite coefficients rejected");
    return 0;
  }
  std::optional<MotionMatrix> motion;
  try {
    motion = MotionMatrix::fromPolynomialMatrix(M);
  } catch (const std::invalid_argument&) {
  }
  if (last_row_nonzero) FUZZ_CHECK(!motion, "last row not [0, 0, 0, w] accepted");
  if (!motion) return 0;

  // Named draws: the order in which function arguments are evaluated is unspecified (gcc and
  // clang differ), so an input must not decode through one expression with several reads.
  const double r0 = in.value(), r1 = in.value(), r2 = in.value();
  const Eigen::Vector3d ra(1e-3 + std::fabs(std::fmod(r0, 10.0)), 1e-3 + std::fabs(std::fmod(r1, 10.0)),
                           1e-3 + std::fabs(std::fmod(r2, 10.0)));
  if (!ra.allFinite()) return 0;
  const int b0 = in.byte() % 8, b1 = in.byte() % 8, b2 = in.byte() % 8;
  const Eigen::Vector3d rb(1 + b0, 1 + b1, 1 + b2);
  const Eigen::Isometry3d X0 = fuzz::rigidMotion(in), X1 = fuzz::rigidMotion(in);
  if (X0.translation().cwiseAbs().maxCoeff() > 1e6 || X1.translation().cwiseAbs().maxCoeff() > 1e6) return 0;

  CcdOptions options;
  const std::uint8_t flags = in.byte();
  options.all_intervals = (flags & 1) == 0;
  options.interpolation = (flags & 2) ? CcdInterpolation::Affine : CcdInterpolation::Rigid;
  options.culling = (flags & 4) == 0;

  const MovingEllipsoid a{Ellipsoid(ra, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), PiecewiseMotion(*motion)};
  const MovingEllipsoid b{Ellipsoid(rb, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                          PiecewiseMotion(MotionMatrix::fromPoses(X0, X1))};
  const EllipsoidCcdResult ab = continuousCollideEllipsoids(a, b, options);
  const EllipsoidCcdResult ba = continuousCollideEllipsoids(b, a, options);
  checkResult(ab, options, "ccd(a, b)");
  checkResult(ba, options, "ccd(b, a)");
  // Symmetry holds for the exact rational motions only: the affine interpolant (thesis section
  // 5.2) interpolates the relative motion in the first body's frame, so (a, b) and (b, a) solve
  // two different approximations (found by a gcc build of this target: the relative pose was the
  // same at both ends in b's frame, so that interpolant never moved).
  if (options.interpolation == CcdInterpolation::Affine) return 0;  // the oracle knows the rigid motions only
  if (ab.collide && !ab.near_tangent && !ab.unresolved)
    FUZZ_CHECK(ba.collide, "certified collision in (a, b) at %g but none in (b, a)", *ab.first_contact_time);
  if (ba.collide && !ba.near_tangent && !ba.unresolved)
    FUZZ_CHECK(ab.collide, "certified collision in (b, a) at %g but none in (a, b)", *ba.first_contact_time);

  for (int s = 0; s <= 8; ++s) {
    const double t = s / 8.0;
    std::optional<Ellipsoid> ea, eb;
    try {
      ea = ellipsoidAt(a, t);
      eb = ellipsoidAt(b, t);
    } catch (const std::invalid_argument&) {
      continue;  // the world map at t is too ill-conditioned to be an Ellipsoid (documented)
    }
    // World ellipsoids come from an eigen-decomposition (relative error ~1e-16 cond): margin to match.
    const std::optional<bool> exact =
        fuzz::clearExactCollision(*ea, *eb, std::max(1e-6, 1e3 * fuzz::rigidMargin(*ea, *eb)));
    if (exact && *exact) {
      if (options.all_intervals)
        FUZZ_CHECK(inCollisionInterval(ab, t), "the oracle clearly overlaps at t = %g, not in a collision interval", t);
      else
        FUZZ_CHECK(ab.collide && *ab.first_contact_time <= t + 1e-9, "the oracle clearly overlaps at t = %g", t);
    }
  }
  return 0;
}
