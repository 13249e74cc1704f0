#pragma once
/// \file quadric_shapes.h
/// FCL geometry for composite quadric models (Choi 2008 ch.6): fcl::ShapeBase<S> subclasses
///  - EllipticCylinder<S>: capped elliptic cylinder, semi-axes a (x), b (y), length lz along z,
///    centred (a = b agrees with fcl::Cylinder(a, lz));
///  - Quadric<S>: the solid X^T Q X <= 0 of a symmetric 4x4 Q (X = (x, 1)), optionally clipped
///    by half-spaces n.x <= d; named constructors for the common quadrics;
///  - QuadricCSG<S>: union / intersection / difference of posed QuadricShape children.
/// The geometry itself (regions, AABB, volume, boundary elements, static classification) is the
/// FCL-free fcl_quadric::QuadricRegion (geometry/quadric_region.h).
///
/// Dispatch (docs/fcl_integration.md, "Quadric shapes"): FCL 0.7's NODE_TYPE is closed, so these
/// shapes report fcl::BV_UNKNOWN, an index FCL's collision / distance tables leave empty. A plain
/// fcl::collide / fcl::distance with any stock solver prints FCL's "not supported" warning and
/// returns 0 contacts (no crash); fcl_quadric::collide and fcl_quadric::defaultCollisionFunction
/// (every broad-phase manager) recognise them before FCL's table and answer exactly.
///
/// Only S = double is instantiated (src/fcl/quadric_shapes.cpp).

#include <memory>
#include <optional>
#include <vector>

#include <fcl/common/types.h>
#include <fcl/geometry/shape/shape_base.h>

#include "fcl_quadric/geometry/convex_cover.h"
#include "fcl_quadric/geometry/convex_support.h"
#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {

/// Common base: a bounded (or, for CSG building blocks, unbounded) quadric region in the shape's
/// local frame, with its certified local AABB computed at construction (mass properties on first
/// use).
template <typename S>
class QuadricShape : public fcl::ShapeBase<S> {
 public:
  /// The solid in the local frame.
  const QuadricRegion& region() const { return region_; }
  /// False for an unclipped unbounded quadric: usable only as a CSG operand (computeLocalAABB
  /// and the mass properties throw std::invalid_argument).
  bool bounded() const { return bounded_; }
  /// Certified local AABB (outward; tight to tolerance_region::kRegionAabbRelative, exact for
  /// EllipticCylinder; a face through a cone's apex up to 1e-3 of the box, measured to 8e-4;
  /// far from the origin the rounding of the atoms loosens it, as for regionAabb).
  /// From the support mapping where the region is convex, a union's from its operands'
  /// (ConvexSupport::treeBox: microseconds to milliseconds), else by regionAabb's bisections
  /// started from a bound by weak duality (dualLinearBound: 0.7-8 ms for the benchmarks' rings,
  /// lenses and drilled blocks; where that bound is loose, milliseconds to seconds).
  /// \throws std::invalid_argument if unbounded.
  const Box3& localBox() const;
  /// Boundary elements (thesis §6.1-6.2, Definition 6.1). \throws std::invalid_argument if
  /// unbounded.
  BoundaryElements boundaryElements() const;
  /// The same, computed once per shape on first use (thread-safe; copies of the shape share
  /// it): the continuous solver by dimension reduction needs them on every query.
  /// \throws std::invalid_argument if unbounded.
  std::shared_ptr<const BoundaryElements> sharedBoundaryElements() const;
  /// Mass properties with the volume's error estimate: in closed form for an EllipticCylinder,
  /// else by certified cell classification (regionMassProperties), computed once per shape on
  /// first use (thread-safe; copies of the shape share it). \throws std::invalid_argument if
  /// unbounded.
  const MassProperties& massProperties() const;
  /// The solid as a support mapping (local frame), made once at construction: the closed form
  /// for an EllipticCylinder, ConvexSupport::fromRegion for another convex region (half-spaces and
  /// at most one curved atom, convex or a cone's or two-sheet hyperboloid's and clipped to one
  /// nappe or sheet); none for an unbounded or a non-convex shape. The front
  /// doors' GJK (screening, distance; docs/algorithms.md section 12) runs on it. No failure mode.
  const std::optional<ConvexSupport>& convexSupport() const { return convex_; }
  /// Convex pieces whose union contains the solid (convexCover(); exact for a union of convex
  /// solids, one piece for a convex shape), made once on first use (thread-safe; copies of the
  /// shape share it): the collide's GJK screening and the distance lower bound use it (the cover
  /// of docs/algorithms.md section 12 over the CSG formula of thesis §6.1).
  /// \throws std::invalid_argument if unbounded.
  std::shared_ptr<const ConvexCover> sharedConvexCover() const;

  /// fcl::BV_UNKNOWN: see the file comment.
  fcl::NODE_TYPE getNodeType() const override { return fcl::BV_UNKNOWN; }
  /// aabb_local, aabb_center, aabb_radius from localBox(). \throws std::invalid_argument if unbounded.
  void computeLocalAABB() override;
  S computeVolume() const override;
  fcl::Vector3<S> computeCOM() const override;
  /// Inertia about the local origin at unit density (FCL's convention).
  fcl::Matrix3<S> computeMomentofInertia() const override;
  /// The eight corners of localBox() posed by tf: what FCL's generic computeBV fits a bounding
  /// volume of any type to (fcl::detail::ComputeBVImpl), so FCL's traversal node templates can be
  /// instantiated with these shapes. \throws std::invalid_argument if unbounded.
  std::vector<fcl::Vector3<S>> getBoundVertices(const fcl::Transform3<S>& tf) const;

 protected:
  /// `box`: a known exact local AABB (else computed, searched inside `hint` if given); `mass`:
  /// closed-form mass properties (else by quadrature). An unbounded region throws unless
  /// allow_unbounded; an empty one always throws.
  QuadricShape(QuadricRegion region, const std::optional<Box3>& box, const std::optional<Box3>& hint,
               const std::optional<MassProperties>& mass, bool allow_unbounded);
  /// A closed-form support mapping in place of the one fromRegion made (EllipticCylinder).
  void setConvexSupport(ConvexSupport support) { convex_ = std::move(support); }

 private:
  void requireBounded(const char* what) const;

  struct ElementsCache;  // once_flags + elements, convex cover, mass properties (quadric_shapes.cpp)

  QuadricRegion region_;
  std::shared_ptr<ElementsCache> elements_;
  bool bounded_ = true;
  Box3 box_;
  std::optional<ConvexSupport> convex_;
};

/// Capped elliptic cylinder { x^2/a^2 + y^2/b^2 <= 1, |z| <= lz/2 }.
template <typename S>
class EllipticCylinder : public QuadricShape<S> {
 public:
  /// \throws std::invalid_argument unless a, b, lz are finite and > 0 (the message names it).
  EllipticCylinder(S a, S b, S lz);
  S a() const { return a_; }
  S b() const { return b_; }
  S lz() const { return lz_; }

 private:
  S a_, b_, lz_;
};

/// A clipping half-space n.x <= d (n non-zero; need not be unit).
template <typename S>
struct HalfspaceClip {
  fcl::Vector3<S> n;
  S d;
};

/// The solid X^T Q X <= 0 clipped by half-spaces.
template <typename S>
class Quadric : public QuadricShape<S> {
 public:
  using Clips = std::vector<HalfspaceClip<S>>;
  /// \throws std::invalid_argument if Q is not finite / symmetric / is zero, a clip normal is
  /// zero or not finite, or the clipped solid is empty. An unbounded result is accepted (as a
  /// CSG operand) and flagged by bounded() == false.
  explicit Quadric(const Eigen::Matrix<S, 4, 4>& Q, const Clips& clips = {});

  // Named constructors (local frame; sizes must be finite and > 0, else std::invalid_argument).
  static Quadric ellipsoid(S a, S b, S c, const Clips& clips = {});
  /// x^2/a^2 + y^2/b^2 <= z (opening towards +z).
  static Quadric ellipticParaboloid(S a, S b, const Clips& clips = {});
  /// x^2/a^2 - y^2/b^2 <= z.
  static Quadric hyperbolicParaboloid(S a, S b, const Clips& clips = {});
  /// x^2/a^2 + y^2/b^2 - z^2/c^2 <= 1.
  static Quadric hyperboloidOneSheet(S a, S b, S c, const Clips& clips = {});
  /// x^2/a^2 + y^2/b^2 - z^2/c^2 <= -1 (both caps; clip z >= 0 for one).
  static Quadric hyperboloidTwoSheets(S a, S b, S c, const Clips& clips = {});
  /// x^2/a^2 + y^2/b^2 <= z^2/c^2 (both nappes; clip for one).
  static Quadric ellipticCone(S a, S b, S c, const Clips& clips = {});
  /// x^2/a^2 + y^2/b^2 <= 1 (infinite along z unless clipped).
  static Quadric ellipticCylinder(S a, S b, const Clips& clips = {});
  /// The slab |n.x - d| <= w (a pair of parallel planes), n unit after normalisation.
  static Quadric planePair(const fcl::Vector3<S>& n, S d, S w, const Clips& clips = {});
  /// The half-space n.x <= d (unbounded: a CSG operand).
  static Quadric halfspace(const fcl::Vector3<S>& n, S d);

  const Eigen::Matrix<S, 4, 4>& matrix() const { return Q_; }
  const Clips& clips() const { return clips_; }

 private:
  Eigen::Matrix<S, 4, 4> Q_;
  Clips clips_;
};

/// A CSG tree over posed quadric shapes (thesis ch.6 CQMs). Children are shared, immutable.
template <typename S>
class QuadricCSG : public QuadricShape<S> {
 public:
  using Op = QuadricRegion::Op;
  struct Child {
    std::shared_ptr<const QuadricShape<S>> shape;
    /// X_PC: the child's frame in this shape's frame (rigid).
    fcl::Transform3<S> pose = fcl::Transform3<S>::Identity();
  };
  /// Union / intersection of >= 1 children; difference: the first minus the others.
  /// \throws std::invalid_argument if op is Atom, there are no children, a child is null, a
  /// pose is not finite or not rigid, or the result is empty or unbounded.
  QuadricCSG(Op op, const std::vector<Child>& children);
  Op op() const { return op_; }
  const std::vector<Child>& children() const { return children_; }

 private:
  struct Build {
    QuadricRegion region;
    std::optional<Box3> hint;
  };
  static Build build(Op op, const std::vector<Child>& children);
  QuadricCSG(const Build& b, Op op, const std::vector<Child>& children);

  Op op_;
  std::vector<Child> children_;
};

extern template class QuadricShape<double>;
extern template class EllipticCylinder<double>;
extern template class Quadric<double>;
extern template class QuadricCSG<double>;

}  // namespace fcl_quadric
