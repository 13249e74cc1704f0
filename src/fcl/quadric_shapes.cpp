// FCL shape classes over QuadricRegion (quadric_shapes.h). No fcl::collide here: this TU only
// needs ShapeBase.
#include "fcl_quadric/fcl/quadric_shapes.h"

#include <cmath>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {

namespace {

constexpr double kPi = 3.14159265358979323846;

void checkPositiveSize(const char* shape, const char* what, double v) {
  if (!std::isfinite(v) || !(v > 0.0)) {
    std::ostringstream os;
    os << shape << ": " << what << " must be finite and > 0, got " << v;
    throw std::invalid_argument(os.str());
  }
}

bool isUnboundedError(const std::invalid_argument& e) {
  return std::string(e.what()).find("unbounded") != std::string::npos;
}

}  // namespace

// --- QuadricShape ---------------------------------------------------------------------------------

template <typename S>
struct QuadricShape<S>::ElementsCache {
  std::once_flag once;
  std::shared_ptr<const BoundaryElements> elements;
  std::once_flag cover_once;
  std::shared_ptr<const ConvexCover> cover;
  std::once_flag mass_once;
  MassProperties mass;
};

template <typename S>
QuadricShape<S>::QuadricShape(QuadricRegion region, const std::optional<Box3>& box, const std::optional<Box3>& hint,
                              const std::optional<MassProperties>& mass, bool allow_unbounded)
    : region_(std::move(region)), elements_(std::make_shared<ElementsCache>()) {
  if (box) {
    box_ = *box;
  } else {
    try {
      // A convex region's box from its support mapping, certified face by face (microseconds to
      // milliseconds), a union's from its operands'; else, and for the cases it leaves (unbounded,
      // empty), regionAabb's bisections (10 ms to seconds for paraboloids and cones;
      // docs/algorithms.md section 12).
      const Box3* h = hint ? &*hint : nullptr;
      if (std::optional<Box3> fast = ConvexSupport::treeBox(region_, h))
        box_ = *fast;
      else
        box_ = regionAabb(region_, h);
    } catch (const std::invalid_argument& e) {
      if (!allow_unbounded || !isUnboundedError(e)) throw;
      bounded_ = false;
    }
  }
  if (bounded_) {
    // Mass properties on first use (massProperties()), unless given in closed form: by cell
    // classification they took 2.5-29 ms of a Quadric's construction (session 41), which FCL's
    // CollisionObject never asks for.
    if (mass) std::call_once(elements_->mass_once, [&] { elements_->mass = *mass; });
    this->aabb_local.min_ = box_.lo.template cast<S>();
    this->aabb_local.max_ = box_.hi.template cast<S>();
    this->aabb_center = this->aabb_local.center();
    this->aabb_radius = (this->aabb_local.min_ - this->aabb_center).norm();
    convex_ = ConvexSupport::fromRegion(region_, box_, ConvexSupport::BoxRole::Contains);
  }
}

template <typename S>
void QuadricShape<S>::requireBounded(const char* what) const {
  if (!bounded_)
    throw std::invalid_argument(std::string(what) +
                                ": the quadric is unbounded (clip it with half-spaces; unbounded quadrics are CSG "
                                "operands only)");
}

template <typename S>
const Box3& QuadricShape<S>::localBox() const {
  requireBounded("QuadricShape::localBox");
  return box_;
}

template <typename S>
BoundaryElements QuadricShape<S>::boundaryElements() const {
  return *sharedBoundaryElements();
}

template <typename S>
std::shared_ptr<const BoundaryElements> QuadricShape<S>::sharedBoundaryElements() const {
  requireBounded("QuadricShape::boundaryElements");
  std::call_once(elements_->once, [this] {
    elements_->elements = std::make_shared<const BoundaryElements>(fcl_quadric::boundaryElements(region_, box_));
  });
  return elements_->elements;
}

template <typename S>
std::shared_ptr<const ConvexCover> QuadricShape<S>::sharedConvexCover() const {
  requireBounded("QuadricShape::sharedConvexCover");
  std::call_once(elements_->cover_once, [this] {
    if (convex_) {
      auto cover = std::make_shared<ConvexCover>();
      cover->pieces.push_back(*convex_);
      cover->exact = true;
      elements_->cover = std::move(cover);
    } else {
      elements_->cover = std::make_shared<const ConvexCover>(convexCover(region_, box_));
    }
  });
  return elements_->cover;
}

template <typename S>
const MassProperties& QuadricShape<S>::massProperties() const {
  requireBounded("QuadricShape::massProperties");
  std::call_once(elements_->mass_once, [this] { elements_->mass = regionMassProperties(region_, box_); });
  return elements_->mass;
}

template <typename S>
void QuadricShape<S>::computeLocalAABB() {
  requireBounded("QuadricShape::computeLocalAABB");
  this->aabb_local.min_ = box_.lo.template cast<S>();
  this->aabb_local.max_ = box_.hi.template cast<S>();
  this->aabb_center = this->aabb_local.center();
  this->aabb_radius = (this->aabb_local.min_ - this->aabb_center).norm();
}

template <typename S>
std::vector<fcl::Vector3<S>> QuadricShape<S>::getBoundVertices(const fcl::Transform3<S>& tf) const {
  requireBounded("QuadricShape::getBoundVertices");
  std::vector<fcl::Vector3<S>> corners;
  corners.reserve(8);
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d c((i & 1) ? box_.hi.x() : box_.lo.x(), (i & 2) ? box_.hi.y() : box_.lo.y(),
                            (i & 4) ? box_.hi.z() : box_.lo.z());
    corners.push_back(tf * c.template cast<S>());
  }
  return corners;
}

template <typename S>
S QuadricShape<S>::computeVolume() const {
  return static_cast<S>(massProperties().volume);
}

template <typename S>
fcl::Vector3<S> QuadricShape<S>::computeCOM() const {
  return massProperties().centroid.template cast<S>();
}

template <typename S>
fcl::Matrix3<S> QuadricShape<S>::computeMomentofInertia() const {
  return massProperties().inertia.template cast<S>();
}

// --- EllipticCylinder -------------------------------------------------------------------------------

namespace {
QuadricRegion cappedEllipticCylinder(double a, double b, double lz) {
  checkPositiveSize("EllipticCylinder", "semi-axis a", a);
  checkPositiveSize("EllipticCylinder", "semi-axis b", b);
  checkPositiveSize("EllipticCylinder", "length lz", lz);
  return QuadricRegion::combine(QuadricRegion::Op::Intersection,
                                {QuadricRegion::atom(quadric::ellipticCylinder(a, b)),
                                 QuadricRegion::halfspace({0, 0, 1}, 0.5 * lz),
                                 QuadricRegion::halfspace({0, 0, -1}, 0.5 * lz)});
}
Box3 ellipticCylinderBox(double a, double b, double lz) {
  return Box3{Eigen::Vector3d(-a, -b, -0.5 * lz), Eigen::Vector3d(a, b, 0.5 * lz)};
}

// Closed form: V = pi a b lz; inertia at unit density about the centre: Ixx = V (b^2/4 +
// lz^2/12), Iyy = V (a^2/4 + lz^2/12), Izz = V (a^2 + b^2)/4 (for a = b, fcl::Cylinder's).
MassProperties ellipticCylinderMass(double a, double b, double lz) {
  MassProperties mp;
  mp.volume = kPi * a * b * lz;
  mp.volume_error = 0.0;
  mp.inertia = Eigen::Vector3d(mp.volume * (b * b / 4 + lz * lz / 12), mp.volume * (a * a / 4 + lz * lz / 12),
                               mp.volume * (a * a + b * b) / 4)
                   .asDiagonal();
  return mp;
}
}  // namespace

template <typename S>
EllipticCylinder<S>::EllipticCylinder(S a, S b, S lz)
    : QuadricShape<S>(cappedEllipticCylinder(a, b, lz), ellipticCylinderBox(a, b, lz), std::nullopt,
                      ellipticCylinderMass(a, b, lz), false),
      a_(a),
      b_(b),
      lz_(lz) {
  this->setConvexSupport(ConvexSupport::ellipticCylinder(a, b, 0.5 * lz));
}

// --- Quadric ----------------------------------------------------------------------------------------

namespace {
template <typename S>
QuadricRegion clippedRegion(const Eigen::Matrix<S, 4, 4>& Q, const typename Quadric<S>::Clips& clips) {
  QuadricRegion atom = QuadricRegion::atom(Q.template cast<double>());
  if (clips.empty()) return atom;
  std::vector<QuadricRegion> parts{atom};
  for (const HalfspaceClip<S>& c : clips) parts.push_back(QuadricRegion::halfspace(c.n.template cast<double>(), c.d));
  return QuadricRegion::combine(QuadricRegion::Op::Intersection, std::move(parts));
}
}  // namespace

template <typename S>
Quadric<S>::Quadric(const Eigen::Matrix<S, 4, 4>& Q, const Clips& clips)
    : QuadricShape<S>(clippedRegion<S>(Q, clips), std::nullopt, std::nullopt, std::nullopt, true), Q_(Q), clips_(clips) {}

template <typename S>
Quadric<S> Quadric<S>::ellipsoid(S a, S b, S c, const Clips& clips) {
  return Quadric(quadric::ellipsoid(Eigen::Vector3d(a, b, c)).template cast<S>(), clips);
}
template <typename S>
Quadric<S> Quadric<S>::ellipticParaboloid(S a, S b, const Clips& clips) {
  return Quadric(quadric::ellipticParaboloid(a, b).template cast<S>(), clips);
}
template <typename S>
Quadric<S> Quadric<S>::hyperbolicParaboloid(S a, S b, const Clips& clips) {
  return Quadric(quadric::hyperbolicParaboloid(a, b).template cast<S>(), clips);
}
template <typename S>
Quadric<S> Quadric<S>::hyperboloidOneSheet(S a, S b, S c, const Clips& clips) {
  return Quadric(quadric::hyperboloidOneSheet(a, b, c).template cast<S>(), clips);
}
template <typename S>
Quadric<S> Quadric<S>::hyperboloidTwoSheets(S a, S b, S c, const Clips& clips) {
  return Quadric(quadric::hyperboloidTwoSheets(a, b, c).template cast<S>(), clips);
}
template <typename S>
Quadric<S> Quadric<S>::ellipticCone(S a, S b, S c, const Clips& clips) {
  return Quadric(quadric::ellipticCone(a, b, c).template cast<S>(), clips);
}
template <typename S>
Quadric<S> Quadric<S>::ellipticCylinder(S a, S b, const Clips& clips) {
  return Quadric(quadric::ellipticCylinder(a, b).template cast<S>(), clips);
}
template <typename S>
Quadric<S> Quadric<S>::planePair(const fcl::Vector3<S>& n, S d, S w, const Clips& clips) {
  if (!n.allFinite() || !(n.norm() > 0.0)) throw std::invalid_argument("Quadric::planePair: normal must be finite and non-zero");
  checkPositiveSize("Quadric::planePair", "half-width w", w);
  const double len = n.norm();
  return Quadric(quadric::planePair(n.template cast<double>() / len, d / len, w / len).template cast<S>(), clips);
}
template <typename S>
Quadric<S> Quadric<S>::halfspace(const fcl::Vector3<S>& n, S d) {
  return Quadric(QuadricRegion::halfspace(n.template cast<double>(), d).matrix().template cast<S>());
}

// --- QuadricCSG --------------------------------------------------------------------------------------

namespace {
template <typename S>
QuadricRegion csgRegion(QuadricRegion::Op op, const std::vector<typename QuadricCSG<S>::Child>& children, Box3* hint,
                        bool* have_hint) {
  if (op == QuadricRegion::Op::Atom)
    throw std::invalid_argument("QuadricCSG: op must be union, intersection or difference");
  if (children.empty()) throw std::invalid_argument("QuadricCSG: a CSG operation needs at least one child");
  std::vector<QuadricRegion> parts;
  std::vector<Box3> boxes;
  std::vector<bool> bounded;
  for (std::size_t i = 0; i < children.size(); ++i) {
    const auto& c = children[i];
    if (!c.shape) {
      std::ostringstream os;
      os << "QuadricCSG: child " << i << " is null";
      throw std::invalid_argument(os.str());
    }
    const Eigen::Matrix3d R = c.pose.linear().template cast<double>();
    const Eigen::Vector3d p = c.pose.translation().template cast<double>();
    const std::string what = "QuadricCSG child " + std::to_string(i) + " pose";
    detail::checkRotation(R, what.c_str());
    detail::checkPosition(p, what.c_str());
    parts.push_back(c.shape->region().transformed(R, p));
    bounded.push_back(c.shape->bounded());
    boxes.push_back(c.shape->bounded() ? transformBox(c.shape->localBox(), R, p) : Box3{});
  }
  // A box known to contain the result (the search of regionAabb starts there).
  *have_hint = false;
  switch (op) {
    case QuadricRegion::Op::Union: {
      bool all = true;
      for (bool b : bounded) all = all && b;
      if (all) {
        *hint = boxes[0];
        for (const Box3& b : boxes) {
          hint->lo = hint->lo.cwiseMin(b.lo);
          hint->hi = hint->hi.cwiseMax(b.hi);
        }
        *have_hint = true;
      }
      break;
    }
    case QuadricRegion::Op::Intersection:
      for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (!bounded[i]) continue;
        if (!*have_hint) {
          *hint = boxes[i];
          *have_hint = true;
        } else {
          hint->lo = hint->lo.cwiseMax(boxes[i].lo);
          hint->hi = hint->hi.cwiseMin(boxes[i].hi);
        }
      }
      if (*have_hint && hint->empty()) throw std::invalid_argument("QuadricCSG: the intersection is empty");
      break;
    case QuadricRegion::Op::Difference:
      if (bounded[0]) {
        *hint = boxes[0];
        *have_hint = true;
      }
      break;
    case QuadricRegion::Op::Atom: break;
  }
  return QuadricRegion::combine(op, std::move(parts));
}

}  // namespace

template <typename S>
typename QuadricCSG<S>::Build QuadricCSG<S>::build(Op op, const std::vector<Child>& children) {
  Box3 hint;
  bool have_hint = false;
  Build b{csgRegion<S>(op, children, &hint, &have_hint), std::nullopt};
  if (have_hint) b.hint = hint;
  return b;
}

template <typename S>
QuadricCSG<S>::QuadricCSG(Op op, const std::vector<Child>& children) : QuadricCSG(build(op, children), op, children) {}

template <typename S>
QuadricCSG<S>::QuadricCSG(const Build& b, Op op, const std::vector<Child>& children)
    : QuadricShape<S>(b.region, std::nullopt, b.hint, std::nullopt, false), op_(op), children_(children) {}

template class QuadricShape<double>;
template class EllipticCylinder<double>;
template class Quadric<double>;
template class QuadricCSG<double>;

}  // namespace fcl_quadric
