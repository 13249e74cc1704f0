#pragma once
/// \file convex_support.h
/// Convex solids described by their support mapping s(n) = a point of the solid maximising n.x,
/// in the solid's local frame: the input of the GJK / EPA distance of convex_distance.h, which
/// gives distance and penetration depth between the convex quadric shapes (quadric_shapes.h) and
/// FCL's convex primitives (docs/algorithms.md section 12). Pure geometry (std + Eigen).
///
/// Kinds:
///  - closed forms: ellipsoid (and sphere), box, capped elliptic cylinder (and fcl::Cylinder),
///    cone (fcl::Cone: base disk at z = -h, apex at z = +h), capsule, the convex hull of a few
///    points (a triangle); a sphere and a capsule also as a core (a point, a segment) grown by a
///    ball (radius(), coreSupport());
///  - `fromRegion`: a CSG formula (quadric_region.h) that is a conjunction of half-spaces and at
///    most one curved atom {x^T A x + 2 b.x + c <= 0} with A positive semidefinite (ellipsoid,
///    elliptic paraboloid, elliptic or parabolic cylinder, slab): such a set is convex (a sublevel
///    set of a convex function cut by half-spaces). Also an indefinite atom (one negative
///    eigenvalue) that is a cone or a two-sheet hyperboloid, when the half-spaces keep one of its
///    two convex components (one nappe, one sheet; docs/algorithms.md section 12). Its support is
///    found by enumerating the Karush-Kuhn-Tucker active sets of max n.x: the smooth point of the
///    curved atom with normal n, the smooth point of each planar section (a conic) of it, the
///    ends of each line where two planes meet, clipped by every other constraint (vertices
///    included), and a cone's apex. A box that clips the region is added as six more
///    half-spaces, so every maximum is attained at a finite candidate; a box certified to contain
///    the region (a shape's own box) is redundant, and the enumeration skips its faces
///    (BoxRole::Contains: GJK on a clipped cone 3.4 times faster). A candidate is accepted when it
///    satisfies the other constraints to kSupportFeasibilityRelative; the support value is then
///    exact to about that fraction of the solid's size.

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {

namespace tolerance_support {
/// A support candidate is feasible when every constraint it does not lie on is satisfied up to
/// this times the constraint's absolute-value expression at the candidate (|h||x| + |d| for a
/// plane; |x|^T|A||x| + 2|b||x| + |c| for the curved atom). Dimensionless. Rounding of the
/// candidates is ~1e-15 relative for well-conditioned sections; 1e-12 leaves a wide margin and
/// bounds how far outside the solid an accepted support point can be.
constexpr double kSupportFeasibilityRelative = 1e-12;
/// Eigenvalues of the curved atom's quadratic part (or of a section's) below this fraction of the
/// largest are treated as zero (null directions of cylinders and paraboloids).
constexpr double kSupportNullEigenRelative = 1e-12;
/// A quadratic part counts as positive semidefinite only when no eigenvalue is below -this times
/// the largest (a posed atom's null eigenvalue rounds to ~1e-16 of the largest). An atom with a
/// negative eigenvalue between -kSupportNullEigenRelative and -this times the largest is neither
/// (a cone or a two-sheet hyperboloid of aspect ratio >= 1e6, whose support the enumeration
/// cannot resolve): it is refused as convex, and answered as a non-convex shape.
constexpr double kSupportIndefiniteRelative = 1e-14;
}  // namespace tolerance_support

class ConvexSupport {
 public:
  enum class Kind { Ellipsoid, Box, EllipticCylinder, Cone, Capsule, Points, Region };

  /// \throws std::invalid_argument unless every size is finite and > 0 (>= 0 for a cylinder's,
  /// cone's or capsule's length), naming the value.
  static ConvexSupport ellipsoid(const Eigen::Vector3d& radii);
  static ConvexSupport box(const Eigen::Vector3d& half_sides);
  /// { x^2/a^2 + y^2/b^2 <= 1, |z| <= h } (fcl::Cylinder: a = b = radius, h = lz / 2).
  static ConvexSupport ellipticCylinder(double a, double b, double half_length);
  /// fcl::Cone(radius, 2h): base disk of radius r at z = -h, apex at z = +h.
  static ConvexSupport cone(double radius, double half_length);
  /// fcl::Capsule(radius, 2h): the segment z in [-h, h] grown by the radius.
  static ConvexSupport capsule(double radius, double half_length);
  /// Convex hull of 1..8 finite points (a triangle of a mesh). \throws std::invalid_argument if
  /// there are none, more than 8, or one is not finite.
  static ConvexSupport points(const std::vector<Eigen::Vector3d>& pts);
  /// What fromRegion()'s box is to the region.
  enum class BoxRole {
    /// The solid is the region cut by the box (a branch-and-bound node, a piece of a cover, a
    /// half-space): the box's faces are constraints of the enumeration.
    Clips,
    /// The box contains the region (QuadricShape::localBox(), regionBox(), regionAabb()), which
    /// is then bounded: the box's faces are redundant and the enumeration skips them (3-4 times
    /// faster GJK on a clipped cone). Checked at construction (2-3 us): the region cut by the box
    /// grown by its largest half-width must reach no farther than the box towards +-x, +-y, +-z
    /// (to 1e-9 of its size; the region is convex, so it then lies in the box). If not (a box
    /// that does not contain the region, or an unbounded region), the faces stay, as with Clips:
    /// never a wrong support, only the old speed. Not from the seed papers: constraints that a
    /// bounded convex set satisfies strictly inside them are redundant for its support function.
    Contains,
  };
  /// The region as a convex support mapping, or nullopt when its formula is not a conjunction of
  /// half-spaces and at most one positive-semidefinite curved atom (unions, differences other
  /// than of half-spaces, hyperboloids, cones' double nappes, two curved atoms). `box` bounds the
  /// enumeration and sets its length scale; `role` says whether it clips the region or contains
  /// it. \throws std::invalid_argument if the box is empty or not finite.
  static std::optional<ConvexSupport> fromRegion(const QuadricRegion& region, const Box3& box,
                                                 BoxRole role = BoxRole::Clips);
  /// A certified bounding box of a region that fromRegion() accepts, from the support values
  /// towards +-x, +-y, +-z (in stages from `hint`, a box known to contain the region, or from the
  /// +-kRegionMaxExtent cube). The region engine finds a point of the region inside the box; then
  /// every face must hold within the box grown by its half-widths (the region is connected), each
  /// certified by weak duality where the curved atom is convex (dualSupportBound()), else by the
  /// engine (findPoint: no point of the region beyond the face there). Tight to
  /// tolerance_region::kRegionAabbRelative of the box near the origin, except where the engine
  /// cannot certify that close (a cone's apex on the face: the face moves out by doubling steps,
  /// at most 1e-3 of the box); far from the origin the rounding of the atoms loosens it.
  /// Microseconds with duality, about 1-10 ms with the engine, where regionAabb's bisections take
  /// 10 ms to seconds (docs/algorithms.md section 12, "Bounding boxes of convex regions").
  /// nullopt when the region is a single atom (an ellipsoid: regionAabb's closed form), not
  /// convex in fromRegion()'s sense, unbounded or empty, or when a face is not certified: the
  /// caller then uses regionAabb, which also names the unbounded or empty case. A hint that is
  /// empty or not finite is ignored; one that does not contain the region gives a certified box
  /// or nullopt (the certificate checks it). No failure mode. Not from the seed papers: the
  /// support function of convex analysis, with the engine of thesis ch.6 as the certificate.
  static std::optional<Box3> regionBox(const QuadricRegion& region, const Box3* hint = nullptr);
  /// regionBox() extended over unions: a union's box is the union of its operands' (exact: the
  /// maximum of a linear function over a union is the largest of its operands'), each operand
  /// boxed by this function again, an ellipsoid atom by regionAabb's closed form. Any other
  /// region: regionBox(region, hint). nullopt when some operand is left to regionAabb (the
  /// caller then boxes the whole region with it). `hint` as for regionBox(), used at the root
  /// only. No failure mode.
  static std::optional<Box3> treeBox(const QuadricRegion& region, const Box3* hint = nullptr);
  /// A certified upper bound of max n.y over the solid's points y inside `outer`, by weak
  /// duality: non-negative multipliers of the region's own constraints (not the bounding box's)
  /// fitted at the point x, the fit's residual and every rounding charged to the bound
  /// (docs/algorithms.md section 12, "Bounding boxes of convex regions"). Valid for any x inside
  /// `outer`; tight (to ~1e-11 of the box) when x is the support point towards n. regionBox()
  /// certifies its faces with it. nullopt unless the kind is Region with a convex curved atom
  /// (a cone nappe or a hyperboloid sheet is convex only on one component: their faces are left
  /// to the region engine), or when n, x or `outer` is not finite, x is outside `outer`, or no
  /// multipliers fit. No failure mode. Not from the seed papers: weak Lagrangian duality (Boyd and
  /// Vandenberghe, Convex Optimization, section 5.2) with every rounding charged.
  std::optional<double> dualSupportBound(const Eigen::Vector3d& n, const Eigen::Vector3d& x, const Box3& outer) const;

  Kind kind() const { return kind_; }
  /// A point of the solid maximising n.x (local frame). n need not be unit; for n = 0 a point
  /// of the solid is returned. No failure mode for finite n (a Region whose enumeration finds no
  /// feasible candidate, which only a numerically empty region can cause, returns center()).
  /// \pre n finite: not checked (GJK's inner loop calls this; convexSignedDistance checks the
  /// poses its directions come from). A non-finite n gives a non-finite point.
  Eigen::Vector3d support(const Eigen::Vector3d& n) const;
  /// The solid as a core grown by a ball: { c + u : c in the core, |u| <= radius() }. A sphere
  /// (an ellipsoid with three equal radii) is its centre grown by its radius, a capsule its
  /// segment grown by its radius; every other kind is its own core, radius() 0. GJK and EPA run
  /// on the cores and add the radii (convex_distance.h): the cores' supports have no curvature
  /// to converge on, and an overlap of the grown solids is certified as soon as the cores come
  /// closer than the radii, without EPA. support() is that of the whole solid either way.
  /// (The Minkowski sum with a ball, docs/algorithms.md section 12 "Grown cores"; the
  /// swept-sphere shapes of Coal and of van den Bergen's GJK.) No failure mode.
  double radius() const { return radius_; }
  /// A point of the core maximising n.x (local frame): support(n) less radius() n / |n|. The
  /// centre for a sphere, the segment's end towards n for a capsule, support(n) otherwise.
  /// \pre n finite, as for support() (not checked; a non-finite n gives a non-finite point or a
  /// segment end, never a throw).
  Eigen::Vector3d coreSupport(const Eigen::Vector3d& n) const;
  /// The same solid as its own core (radius() 0): GJK and EPA then run on its whole support, as
  /// before session 31. For checks of the grown-core path against the whole solid. No failure
  /// mode.
  ConvexSupport whole() const {
    ConvexSupport s = *this;
    s.radius_ = 0.0;
    return s;
  }
  /// A point of the solid (for Region: the last feasible candidate's box centre is not used; the
  /// bounding-box centre, which need not be inside, serves only as GJK's first direction).
  Eigen::Vector3d center() const { return center_; }
  /// Half the diagonal of a bounding box: the length scale of the tolerances.
  double size() const { return size_; }
  /// A cone's apex (local frame): (0, 0, h) for the Cone kind, the apex of a Region whose curved
  /// atom is one nappe of a cone. The one point of the curved surface where its gradient
  /// vanishes, so a vertex that a Newton refinement through the curved atom cannot settle on
  /// (nearest_points.h); refined as a point of its own instead (docs/algorithms.md section 12c).
  /// A Region's planes may cut the apex off: callers check membership. None for the other kinds.
  /// No failure mode.
  std::optional<Eigen::Vector3d> apex() const;

 private:
  /// `found`, if given, receives whether any candidate was feasible (else the bounding-box
  /// centre is returned: fromRegion() refuses regions where that happens).
  Eigen::Vector3d regionSupport(const Eigen::Vector3d& n, bool* found = nullptr) const;

  Kind kind_ = Kind::Points;
  double radius_ = 0.0;  // radius(): the ball the core is grown by (a sphere's or a capsule's)
  Eigen::Vector3d dims_ = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> points_;
  // Region: the curved atom (if any), the planes h.x <= d, and their eigen-decompositions, made
  // once by fromRegion() and shared by copies (convex_support.cpp). A copy of any support
  // mapping is then a few words: the front doors make and copy them per query.
  struct RegionData;
  static bool acceptIndefinite(RegionData* g, double length);

  std::shared_ptr<const RegionData> region_;
  Eigen::Vector3d center_ = Eigen::Vector3d::Zero();
  double size_ = 0.0;
};

}  // namespace fcl_quadric
