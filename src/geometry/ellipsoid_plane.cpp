#include "fcl_quadric/geometry/ellipsoid_plane.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

const char* toString(PlaneRelation r) {
  switch (r) {
    case PlaneRelation::PositiveSide: return "positive side";
    case PlaneRelation::NegativeSide: return "negative side";
    case PlaneRelation::Touching: return "touching";
    case PlaneRelation::Transversal: return "transversal";
  }
  return "unknown";
}

namespace {
void checkPlane(const Eigen::Vector3d& n, double d) {
  if (!n.allFinite() || !(n.squaredNorm() > 0.0) || !std::isfinite(d)) {
    std::ostringstream os;
    os << "plane must have a finite non-zero normal and a finite offset, got n = [" << n.transpose() << "], d = " << d;
    throw std::invalid_argument(os.str());
  }
}
}  // namespace

std::array<double, 3> ellipsoidPlaneQuadratic(const Ellipsoid& e, const Eigen::Vector3d& n, double d) {
  checkPlane(n, d);
  const Eigen::Vector3d m = (e.rotation().transpose() * n).cwiseProduct(e.radii());
  return {0.25 * m.squaredNorm(), -(d - n.dot(e.center())), 1.0};
}

EllipsoidPlaneResult classifyEllipsoidPlane(const Ellipsoid& e, const Eigen::Vector3d& n, double d) {
  checkPlane(n, d);
  EllipsoidPlaneResult r;
  const double np = n.dot(e.center());
  r.centre_offset = np - d;
  r.half_width = (e.rotation().transpose() * n).cwiseProduct(e.radii()).norm();
  r.farthest_positive = e.supportPoint(n);
  r.farthest_negative = e.supportPoint(-n);
  // Corollary 14: transversal iff e^2 < |m|^2, i.e. |n.p - d| < |S R^T n|; the sign of n.p - d
  // gives the side. Rounding of each term is relative to |n||p| + |d| + |m| + |n|_1 sum(r): R^T n
  // is rounded absolutely (~eps |n|), which a long radius multiplies (tolerances.h,
  // kStoredRotationDefect).
  const double tau = tolerance::kCertificateRelativeBoundDouble;
  const double scale = n.cwiseAbs().dot(e.center().cwiseAbs()) + std::fabs(d) + r.half_width +
                       n.cwiseAbs().sum() * e.radii().sum();
  const double gap = std::fabs(r.centre_offset) - r.half_width;
  if (gap > tau * scale) {
    r.relation = r.centre_offset > 0.0 ? PlaneRelation::PositiveSide : PlaneRelation::NegativeSide;
  } else if (gap < -tau * scale) {
    r.relation = PlaneRelation::Transversal;
  } else {
    r.relation = PlaneRelation::Touching;
  }
  return r;
}

EllipsoidHalfspaceResult ellipsoidHalfspace(const Ellipsoid& e, const Eigen::Vector3d& n, double d) {
  const EllipsoidPlaneResult p = classifyEllipsoidPlane(e, n, d);
  EllipsoidHalfspaceResult h;
  h.collide = p.relation != PlaneRelation::PositiveSide;
  h.penetration_depth = p.half_width - p.centre_offset;
  h.deepest_point = p.farthest_negative;
  return h;
}

}  // namespace fcl_quadric
