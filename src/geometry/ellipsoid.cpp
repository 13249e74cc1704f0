#include "fcl_quadric/geometry/ellipsoid.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace {

// The error paths, out of line: the checks below run for every posed shape of every query (the
// FCL front doors build two Ellipsoids per ellipsoid pair), and an inlined ostringstream gave each
// of them a 0.5 KiB stack frame and a slower fast path (measured with perf).
[[noreturn, gnu::cold, gnu::noinline]] void throwNonFinite(const Eigen::Vector3d& v, const char* what) {
  std::ostringstream os;
  os << what << " must be finite, got [" << v[0] << ", " << v[1] << ", " << v[2] << "]";
  throw std::invalid_argument(os.str());
}

[[noreturn, gnu::cold, gnu::noinline]] void throwOutOfRange(const Eigen::Vector3d& v, const char* what) {
  std::ostringstream os;
  os << what << " coordinates must be within +-" << tolerance::kMaxLength << ", got [" << v[0] << ", " << v[1] << ", "
     << v[2] << "]";
  throw std::invalid_argument(os.str());
}

[[noreturn, gnu::cold, gnu::noinline]] void throwNotRotation(const Eigen::Matrix3d& R, const char* what, bool finite,
                                                             bool bounded) {
  std::ostringstream os;
  if (!finite) {
    os << what << " must be finite, got\n" << R;
  } else if (!bounded) {
    os << what << " is not a rotation (an entry of magnitude " << R.cwiseAbs().maxCoeff() << " > 1)";
  } else {
    const double defect = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    os << what << " is not a rotation (max |R^T R - I| = " << defect << ", det = " << R.determinant()
       << "; tolerance " << tolerance::kRotationOrthogonality << ")";
  }
  throw std::invalid_argument(os.str());
}

[[noreturn, gnu::cold, gnu::noinline]] void throwBadRadius(const Eigen::Vector3d& radii, int i) {
  std::ostringstream os;
  if (!std::isfinite(radii[i]) || !(radii[i] > 0.0)) {
    os << "ellipsoid radius " << "abc"[i] << " must be finite and > 0, got " << radii[i];
  } else {
    os << "ellipsoid radius " << "abc"[i] << " must be in [" << tolerance::kMinRadius << ", "
       << tolerance::kMaxLength << "], got " << radii[i];
  }
  throw std::invalid_argument(os.str());
}

}  // namespace

namespace detail {

void checkFinite(const Eigen::Vector3d& v, const char* what) {
  // std::isfinite per entry: Eigen's allFinite() computes x - x, which raises FE_INVALID on inf.
  if (!(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]))) throwNonFinite(v, what);
}

void checkPosition(const Eigen::Vector3d& v, const char* what) {
  checkFinite(v, what);
  if (!(std::fabs(v[0]) <= tolerance::kMaxLength && std::fabs(v[1]) <= tolerance::kMaxLength &&
        std::fabs(v[2]) <= tolerance::kMaxLength))
    throwOutOfRange(v, what);
}

void checkLength(double v, const char* what, const char* name, int index) {
  if (!std::isfinite(v) || !(v >= 0.0) || !(v <= tolerance::kMaxLength)) {
    std::ostringstream os;
    os << what;
    if (name) os << " " << name;
    if (index >= 0) os << " " << index;
    os << " must be finite and in [0, " << tolerance::kMaxLength << "], got " << v;
    throw std::invalid_argument(os.str());
  }
}

namespace {

/// checkRotation()'s test without the throw: whether R's entries are finite, bounded by 2 (a
/// rotation's lie in [-1, 1]) and R a proper rotation within tolerance::kRotationOrthogonality,
/// with its defect max|R^T R - I| when so.
struct RotationTest {
  bool finite = true, bounded = false, rotation = false;
  double defect = 0.0;
};

__attribute__((always_inline)) inline RotationTest testRotation(const Eigen::Matrix3d& R) {
  // Hand-written and always inlined: this runs for every posed shape of every query. Columns
  // c0 = r[0..2], c1 = r[3..5], c2 = r[6..8]: the six entries of R^T R - I and
  // det R = c0 . (c1 x c2).
  // std::isfinite raises no FP exception. The identity passes exactly (defect 0, det 1).
  // Entries are bounded first (a rotation's lie in [-1, 1]), so that nothing below overflows:
  // inf - inf would raise FE_INVALID, which the tests trap. Comparisons only on finite values.
  RotationTest t;
  const double* r = R.data();
  for (int i = 0; i < 9; ++i) t.finite &= std::isfinite(r[i]);
  t.bounded = t.finite;
  for (int i = 0; i < 9 && t.bounded; ++i) t.bounded = std::fabs(r[i]) <= 2.0;
  if (t.bounded) {
    const double n0 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2] - 1.0;
    const double n1 = r[3] * r[3] + r[4] * r[4] + r[5] * r[5] - 1.0;
    const double n2 = r[6] * r[6] + r[7] * r[7] + r[8] * r[8] - 1.0;
    const double d01 = r[0] * r[3] + r[1] * r[4] + r[2] * r[5];
    const double d02 = r[0] * r[6] + r[1] * r[7] + r[2] * r[8];
    const double d12 = r[3] * r[6] + r[4] * r[7] + r[5] * r[8];
    t.defect = std::max(std::max(std::max(std::fabs(n0), std::fabs(n1)), std::max(std::fabs(n2), std::fabs(d01))),
                        std::max(std::fabs(d02), std::fabs(d12)));
    const double det = r[0] * (r[4] * r[8] - r[5] * r[7]) + r[1] * (r[5] * r[6] - r[3] * r[8]) +
                       r[2] * (r[3] * r[7] - r[4] * r[6]);
    t.rotation = t.defect <= tolerance::kRotationOrthogonality && det > 0.0;  // all finite: no FE_INVALID
  }
  return t;
}

}  // namespace

bool isRotation(const Eigen::Matrix3d& R) { return testRotation(R).rotation; }

double checkRotation(const Eigen::Matrix3d& R, const char* what) {
  const RotationTest t = testRotation(R);
  if (t.rotation) return t.defect;
  throwNotRotation(R, what, t.finite, t.bounded);
}

Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& R) {
  // Newton-Schulz for the polar factor: with R^T R = I + E, one step leaves a defect of
  // O(|E|^2) plus rounding, so a defect <= 1e-9 needs one step, two at most.
  Eigen::Matrix3d Q = R;
  for (int step = 0; step < 4; ++step) {
    Q = Q * (0.5 * (3.0 * Eigen::Matrix3d::Identity() - Q.transpose() * Q));
    const double defect = (Q.transpose() * Q - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (defect <= tolerance::kStoredRotationDefect) return Q;
  }
  return Eigen::Quaterniond(R).normalized().toRotationMatrix();  // documented fallback
}

Eigen::Matrix3d storedRotation(const Eigen::Matrix3d& R, const char* what) {
  // The rare rotation that is accepted but less orthogonal than 2^-48 (a drifted composition)
  // is replaced by its nearest rotation, so that supports |S R^T n| and the implicit form
  // |S^-1 R^T (x - p)| describe one solid (tolerances.h).
  return checkRotation(R, what) > tolerance::kStoredRotationDefect ? nearestRotation(R) : R;
}

double unitFrameRounding(const Ellipsoid& e, double world_l1) {
  return tolerance::kUnitFrameRoundingBound * world_l1 * e.inverseRadii().sum();
}

}  // namespace detail

// Two cache lines, the pose's rows and the shape each 32-byte aligned (the cached-plane kernel's
// loads, separating_plane.cpp).
static_assert(sizeof(Ellipsoid) == 128 && alignof(Ellipsoid) == 64, "Ellipsoid is two cache lines");

Ellipsoid::Ellipsoid(const Eigen::Vector3d& radii, const Eigen::Matrix3d& R_WE, const Eigen::Vector3d& p_WE)
    : shape_{radii[0], radii[1], radii[2], 0.0} {
  for (int i = 0; i < 3; ++i) {
    // std::isfinite before the ordered comparisons (a comparison with NaN raises FE_INVALID);
    // the message is built out of line.
    if (!(std::isfinite(radii[i]) && radii[i] >= tolerance::kMinRadius && radii[i] <= tolerance::kMaxLength))
      throwBadRadius(radii, i);
  }
  pose_.leftCols<3>() = detail::storedRotation(R_WE, "ellipsoid rotation");  // the pre-tests' supports need it
  detail::checkPosition(p_WE, "ellipsoid centre");
  pose_.col(3) = p_WE;
  shape_[3] = std::fabs(p_WE[0]) + std::fabs(p_WE[1]) + std::fabs(p_WE[2]) + radii[0] + radii[1] + radii[2];
}

Ellipsoid::Ellipsoid(const Eigen::Vector3d& radii, const Eigen::Isometry3d& X_WE)
    : Ellipsoid(radii, X_WE.linear(), X_WE.translation()) {}

Ellipsoid Ellipsoid::sphere(double r, const Eigen::Vector3d& p_WE) {
  return Ellipsoid(Eigen::Vector3d::Constant(r), Eigen::Matrix3d::Identity(), p_WE);
}

Ellipsoid Ellipsoid::fromAffine(const Eigen::Matrix3d& M, const Eigen::Vector3d& p) {
  if (!M.allFinite()) {
    std::ostringstream os;
    os << "affine map of an ellipsoid must be finite, got\n" << M;
    throw std::invalid_argument(os.str());
  }
  detail::checkFinite(p, "ellipsoid centre");
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(M * M.transpose());
  const Eigen::Vector3d ev = es.eigenvalues();  // ascending
  if (!(ev[0] > 0.0) || !(ev[0] >= 1e-24 * ev[2])) {
    std::ostringstream os;
    os << "affine map of an ellipsoid is singular or too ill-conditioned (squared singular values " << ev[0]
       << " .. " << ev[2] << ")";
    throw std::invalid_argument(os.str());
  }
  Eigen::Matrix3d R = es.eigenvectors();
  if (R.determinant() < 0.0) R.col(2) = -R.col(2);
  return Ellipsoid(ev.cwiseSqrt(), R, p);
}

Eigen::Matrix4d Ellipsoid::quadricMatrix() const { return quadric::posedEllipsoid(radii(), rotation(), center()); }

double Ellipsoid::implicit(const Eigen::Vector3d& x) const {
  const Eigen::Vector3d u = (rotation().transpose() * (x - center())).cwiseQuotient(radii());
  return u.squaredNorm() - 1.0;
}

Eigen::Vector3d Ellipsoid::normalAt(const Eigen::Vector3d& x) const {
  const Eigen::Vector3d u = (rotation().transpose() * (x - center())).cwiseQuotient(radii().cwiseProduct(radii()));
  return (rotation() * u).normalized();
}

double Ellipsoid::support(const Eigen::Vector3d& n) const {
  // h(n) = n.p + |S R^T n|
  return n.dot(center()) + (rotation().transpose() * n).cwiseProduct(radii()).norm();
}

Eigen::Vector3d Ellipsoid::supportPoint(const Eigen::Vector3d& n) const {
  // argmax: p + R S^2 R^T n / |S R^T n|
  Eigen::Vector3d m = (rotation().transpose() * n).cwiseProduct(radii());
  double norm = m.norm();
  if (norm == 0.0 || std::isinf(norm)) {  // n = 0, or |m|^2 under/overflows: rescale m first
    const double s = m.cwiseAbs().maxCoeff();
    if (s == 0.0) return center();  // n = 0: every point attains h(0) = 0 (was 0/0 = NaN)
    m /= s;
    norm = m.norm();
  }
  return center() + rotation() * (m.cwiseProduct(radii()) / norm);
}

}  // namespace fcl_quadric
