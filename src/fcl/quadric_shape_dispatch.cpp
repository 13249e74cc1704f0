// Front-door dispatch for the quadric shapes: FCL primitives are converted to QuadricRegions and
// the pair is classified by collideRegions-style certified search (docs/algorithms.md section 9).
#include "fcl/quadric_shape_dispatch.h"

#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/contact.h>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/fcl/quadric_shapes.h"
#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {
namespace detail {

bool isQuadricShape(const fcl::CollisionGeometry<double>* g) {
  return dynamic_cast<const QuadricShape<double>*>(g) != nullptr;
}

namespace {

using Op = QuadricRegion::Op;

/// A solid in its local frame with its local AABB (none: unbounded).
struct LocalSolid {
  QuadricRegion region;
  std::optional<Box3> box;
};

Box3 symmetricBox(const Eigen::Vector3d& h) { return Box3{-h, h}; }

QuadricRegion slab(double half) {
  return QuadricRegion::combine(Op::Intersection, {QuadricRegion::halfspace({0, 0, 1}, half),
                                                   QuadricRegion::halfspace({0, 0, -1}, half)});
}

/// FCL's primitives as quadric regions (FCL's local conventions, fcl/geometry/shape/*.h).
LocalSolid localSolid(const fcl::CollisionGeometry<double>* g, const char* which) {
  if (const auto* q = dynamic_cast<const QuadricShape<double>*>(g)) {
    if (!q->bounded()) return {q->region(), std::nullopt};
    return {q->region(), q->localBox()};
  }
  switch (g->getNodeType()) {
    case fcl::GEOM_SPHERE: {
      const double r = static_cast<const fcl::Sphere<double>*>(g)->radius;
      return {QuadricRegion::atom(quadric::ellipsoid(Eigen::Vector3d::Constant(r))),
              symmetricBox(Eigen::Vector3d::Constant(r))};
    }
    case fcl::GEOM_ELLIPSOID: {
      const Eigen::Vector3d r = static_cast<const fcl::Ellipsoid<double>*>(g)->radii;
      return {QuadricRegion::atom(quadric::ellipsoid(r)), symmetricBox(r)};
    }
    case fcl::GEOM_BOX: {
      const Eigen::Vector3d h = 0.5 * static_cast<const fcl::Box<double>*>(g)->side;
      std::vector<QuadricRegion> planes;
      for (int i = 0; i < 3; ++i) {
        Eigen::Vector3d n = Eigen::Vector3d::Zero();
        n[i] = 1.0;
        planes.push_back(QuadricRegion::halfspace(n, h[i]));
        planes.push_back(QuadricRegion::halfspace(-n, h[i]));
      }
      return {QuadricRegion::combine(Op::Intersection, planes), symmetricBox(h)};
    }
    case fcl::GEOM_CYLINDER: {
      const auto* c = static_cast<const fcl::Cylinder<double>*>(g);
      return {QuadricRegion::combine(Op::Intersection, {QuadricRegion::atom(quadric::ellipticCylinder(c->radius, c->radius)),
                                                        slab(0.5 * c->lz)}),
              symmetricBox(Eigen::Vector3d(c->radius, c->radius, 0.5 * c->lz))};
    }
    case fcl::GEOM_CONE: {
      // Base disk of radius r at z = -L/2, apex at +L/2: x^2 + y^2 <= (r/L)^2 (z - L/2)^2 with
      // |z| <= L/2 selecting the nappe.
      const auto* c = static_cast<const fcl::Cone<double>*>(g);
      const double k = c->radius / c->lz, h = 0.5 * c->lz;
      Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
      Q(0, 0) = 1.0;
      Q(1, 1) = 1.0;
      Q(2, 2) = -k * k;
      Q(2, 3) = Q(3, 2) = k * k * h;
      Q(3, 3) = -k * k * h * h;
      return {QuadricRegion::combine(Op::Intersection, {QuadricRegion::atom(Q), slab(h)}),
              symmetricBox(Eigen::Vector3d(c->radius, c->radius, h))};
    }
    case fcl::GEOM_CAPSULE: {
      const auto* c = static_cast<const fcl::Capsule<double>*>(g);
      const double r = c->radius, h = 0.5 * c->lz;
      const Eigen::Vector3d rr = Eigen::Vector3d::Constant(r);
      return {QuadricRegion::combine(
                  Op::Union,
                  {QuadricRegion::combine(Op::Intersection,
                                          {QuadricRegion::atom(quadric::ellipticCylinder(r, r)), slab(h)}),
                   QuadricRegion::atom(quadric::posedEllipsoid(rr, Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, h))),
                   QuadricRegion::atom(quadric::posedEllipsoid(rr, Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -h)))}),
              symmetricBox(Eigen::Vector3d(r, r, h + r))};
    }
    case fcl::GEOM_HALFSPACE: {
      const auto* hs = static_cast<const fcl::Halfspace<double>*>(g);
      return {QuadricRegion::halfspace(hs->n, hs->d), std::nullopt};
    }
    default: break;
  }
  std::ostringstream os;
  os << "fcl_quadric::collide: " << which << " has node type " << g->getNodeType()
     << ", which is not supported against fcl_quadric quadric shapes (supported: quadric shapes, Sphere, "
        "Ellipsoid, Box, Cylinder, Cone, Capsule, Halfspace)";
  throw std::invalid_argument(os.str());
}

}  // namespace

std::size_t collideQuadricShapes(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                                 const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                                 const fcl::CollisionRequest<double>& request, fcl::CollisionResult<double>& result) {
  const LocalSolid a = localSolid(o1, "o1");
  const LocalSolid b = localSolid(o2, "o2");
  const Eigen::Matrix3d R1 = tf1.linear(), R2 = tf2.linear();
  const Eigen::Vector3d p1 = tf1.translation(), p2 = tf2.translation();
  const QuadricRegion wa = a.region.transformed(R1, p1);
  const QuadricRegion wb = b.region.transformed(R2, p2);
  // Search box: the intersection of the world AABBs of the bounded operands.
  std::optional<Box3> box;
  for (const auto& [solid, R, p] : {std::tuple(&a, R1, p1), std::tuple(&b, R2, p2)}) {
    if (!solid->box) continue;
    const Box3 w = transformBox(*solid->box, R, p);
    if (!box) {
      box = w;
    } else {
      box->lo = box->lo.cwiseMax(w.lo);
      box->hi = box->hi.cwiseMin(w.hi);
    }
  }
  if (!box)
    throw std::invalid_argument("fcl_quadric::collide: both operands are unbounded (half-spaces or unclipped quadrics)");
  if (box->empty()) return result.numContacts();
  const PointSearchResult s = findPoint(QuadricRegion::combine(Op::Intersection, {wa, wb}), *box);
  if (s.status == PointSearch::Empty) return result.numContacts();
  if (result.numContacts() < request.num_max_contacts) {
    // Normal: o1's atom with the smallest |f| / |grad f| at the point, outward (as used).
    Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::Matrix4d& Q : wa.signedAtoms()) {
      const Eigen::Vector4d X(s.point[0], s.point[1], s.point[2], 1.0);
      const Eigen::Vector4d QX = Q * X;
      const Eigen::Vector3d g = 2.0 * QX.head<3>();
      const double gn = g.norm();
      if (!(gn > 0.0)) continue;
      const double dist = std::fabs(X.dot(QX)) / gn;
      if (dist < best) {
        best = dist;
        normal = g / gn;
      }
    }
    result.addContact(fcl::Contact<double>(o1, o2, fcl::Contact<double>::NONE, fcl::Contact<double>::NONE, s.point,
                                           normal, 0.0));
  }
  return result.numContacts();
}

}  // namespace detail
}  // namespace fcl_quadric
