#pragma once
/// \file ellipse_ccd.h
/// Continuous collision detection of moving ellipses: thesis ch.2 (elliptic disks moving in the
/// plane, algorithm CD-DISC and its three variants, §2.3 and §2.5.3) and ch.3 (ellipses moving in
/// 3D space, algorithm CD-DISC3D, Theorem 3.1, §3.3).
///
/// Conventions (as in the rest of the library, thesis Remark 4.2): a conic matrix A is
/// normalised so that X^T A X < 0 exactly for interior points X = (x, y, 1);
/// f(lambda) = det(lambda A - B) is the characteristic polynomial.
///
/// Continuous-collision layer: depends on the algebra and geometry layers only (no FCL).
///
/// Numerical policy (docs/tolerances.md applied to this layer). All polynomial work in t is
/// done in the Bernstein basis of [0, 1] (thesis §2.5.3): the coefficients g_k(t) of
/// f(lambda; t) are formed in power form from the motions (low degree), converted to Bernstein
/// form, and the discriminant Delta(t) (eq. 2.2) is formed by Bernstein products. Decisions
/// about the contact state at a given time use the static test of Theorem 2.6, evaluated on the
/// numeric conic matrices at that time, with a relative touching band: near tangency every
/// decision errs toward reporting contact. Every loop is bounded by the named caps below; when a
/// cap is reached the answer is conservative (a contact is reported, never dropped) and flagged.

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "fcl_quadric/algebra/bernstein_polynomial.h"
#include "fcl_quadric/algebra/polynomial_matrix.h"
#include "fcl_quadric/algebra/polynomial_matrix3.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"

namespace fcl_quadric {

// ---------------------------------------------------------------------------------------------
// Named constants of this layer (tolerances.h belongs to the static layer; these are specific to
// the moving-ellipse algorithms).

/// Static touching band (Theorem 2.6): with lambda_1 the negative local minimiser of
/// f(lambda) = det(lambda A - B) (the candidate double root), the pair is reported as Touching
/// when |f(lambda_1)| <= this times sum_k s_k |lambda_1|^k, where s_k are the coefficients of the
/// permanent of lambda |A| + |B| (the absolute-value scale of the coefficient computation).
/// 2^-40 ~ 9.1e-13, the same relative bound as the static ellipsoid certificates
/// (tolerance::kCertificateRelativeBoundDouble). Dimensionless.
constexpr double kEllipseTouchingRelativeBand = 9.094947017729282e-13;  // 2^-40

/// Width (in t) below which root isolation of Delta and Delta' stops subdividing and reports
/// an Unresolved interval (possibly a multiple root or a cluster of rounding roots; its lower end
/// is used, never later than its roots). Simple roots are refined further (kEllipseRootTolerance).
/// 2^-30 ~ 9.3e-10: near a grazing contact the computed Delta has rounding sign changes over a
/// width ~sqrt(rounding / Delta''), so a finer width multiplies the subdivision nodes without
/// improving the answer (the extremum of Delta gives the time).
constexpr double kEllipseIsolationWidth = 9.313225746154785e-10;  // 2^-30

/// Absolute accuracy in t to which simple roots of Delta and of Delta' are refined.
constexpr double kEllipseRootTolerance = 1e-15;

/// A root of Delta within this distance (in t) of a local extremum of Delta (a root of Delta')
/// where the static test reports Touching or Separated belongs to the same near-tangency event and
/// is dropped: the extremum represents it. For a double root of Delta (a grazing contact) the
/// extremum is the well-conditioned location while the computed roots scatter by ~sqrt(rounding)
/// or vanish; the static test there decides contact (Touching) or near miss (Separated).
constexpr double kEllipseGrazingWindow = 1e-6;

/// Cap on the number of candidate event times (roots of Delta plus in-band extrema) examined
/// by one CD-DISC call. Delta has formal degree <= 4 * 12 k for degree-k motions, so the cap
/// (4096) is never reached by motions of degree <= 16. If it is reached, the call reports a
/// collision at the earliest candidate, flags `capped`, and stops (conservative).
constexpr int kMaxEllipseEvents = 4096;

/// Cap on the degree of the motion matrices accepted (Delta has degree 48 times it). Larger
/// motions throw std::invalid_argument.
constexpr int kMaxEllipseMotionDegree = 16;


/// Chapter 3: two containing planes are treated as parallel at time t when
/// |n_A x n_B| <= this times |n_A| |n_B| (normals from the motions). Dimensionless.
constexpr double kEllipseParallelPlanesRelative = 1e-12;

/// Chapter 3: a parallel pair of planes is treated as coincident when the distance between them is
/// at most this times the length scale (largest radius plus centre distance). Dimensionless.
constexpr double kEllipseCoplanarRelative = 1e-12;

// ---------------------------------------------------------------------------------------------
// Static test (Theorem 2.6).

/// Result of the static test for two elliptic disks.
struct EllipsePairState {
  /// Separated (two distinct negative roots of f), Touching (a negative double root, within the
  /// band kEllipseTouchingRelativeBand), Overlapping (no negative root).
  Separation status = Separation::Overlapping;
  /// The negative critical point lambda_1 of f (the double root when touching); 0 when f has no
  /// negative critical point.
  double lambda = 0.0;
  /// Contact point (x, y): the null vector of lambda_1 A - B (Lemma 2.5). Meaningful when
  /// status == Touching (for other states it is the singular point of that member of the pencil).
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  bool point_valid = false;
};

/// Classifies the elliptic disks X^T A X <= 0 and X^T B X <= 0 (Theorem 2.6): the number of
/// distinct negative roots of the cubic f(lambda) = det(lambda A - B) is counted with a Sturm
/// sequence over (-inf, 0); 2 -> Separated, 0 -> Overlapping, 1 -> Touching. The value of f at
/// its negative local minimiser lambda_1 (a double root iff touching) decides the band: if
/// |f(lambda_1)| is within kEllipseTouchingRelativeBand of its scale, or the Sturm count and the
/// sign of f(lambda_1) disagree, the answer is Touching (errs toward contact).
/// \throws std::invalid_argument if A or B is not finite, or not an ellipse matrix with the
///         interior-negative convention (upper 2x2 block positive definite and det < 0); the
///         message names the matrix.
EllipsePairState classifyEllipses(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B);

/// The matrix of the ellipse with semi-axes a (along the rotated x axis) and b, rotated by
/// `angle` and centred at c: X^T A X = |diag(1/a,1/b) R^T (x - c)|^2 - 1.
/// \throws std::invalid_argument if a or b is not finite and positive or angle/c not finite.
Eigen::Matrix3d ellipseMatrix(double a, double b, double angle, const Eigen::Vector2d& c);

// ---------------------------------------------------------------------------------------------
// Moving ellipses in the plane (thesis ch.2).

/// An elliptic disk with semi-axes (a, b) along the x and y axes of its body frame, moved by a
/// homogeneous polynomial motion M(t), t in [0, 1], mapping body to world coordinates:
///
///     M(t) = [ L(t)  v(t) ]      world point x = (L(t) u + v(t)) / w(t) for body point u.
///            [ 0 0   w(t) ]
///
/// Rational rigid motions (thesis §2.5.1, eq. 2.3) and affine (deforming) motions are both of
/// this form. The world conic is
///
///     A(t) = adj(M)^T A0 adj(M),   A0 = diag(1/a^2, 1/b^2, -1),
///
/// which equals det(M(t))^2 (M^-1)^T A0 M^-1: the adjugate avoids dividing by det M. Scaling a
/// conic matrix by a positive factor s(t) (here det(M)^2 > 0, since det M = w det L has no root
/// in [0,1]) never changes the root pattern of f(lambda; t): det(lambda sA A - sB B) =
/// sB^3 f(lambda sA / sB), so every root is multiplied by sB / sA > 0 and signs and
/// multiplicities are kept; Delta(t) is multiplied by a positive factor with no root in [0, 1].
///
/// Validation (each failure throws std::invalid_argument naming the bad item): the radii must be
/// finite and positive; the degree of M must be at most kMaxEllipseMotionDegree; the last row of
/// M must be exactly [0, 0, w(t)]; w(t) and det L(t) must have no root in [0, 1], certified by
/// Bernstein root exclusion (firstRoot() on [0, 1]; "may vanish" is rejected).
class MovingEllipse2 {
 public:
  MovingEllipse2(double a, double b, const PolynomialMatrix3& motion);

  /// From N(t) proportional to the *inverse* motion M(t)^-1 by a nonzero polynomial factor, e.g.
  /// the matrix printed after eq. 2.3 (the kinematic-image form of degree 2n, which halves the
  /// degree of Delta compared with the adjugate of M). N is validated as a motion above (last row
  /// [0, 0, w'(t)], w' and det L' root-free on [0, 1]), which makes it invertible for every t.
  static MovingEllipse2 fromInverseMotion(double a, double b, const PolynomialMatrix3& inverse_motion);

  double a() const { return a_; }
  double b() const { return b_; }
  /// N(t) = adj(M(t)) (or the inverse motion given to fromInverseMotion()): world -> body up to a
  /// nonzero scalar factor.
  const PolynomialMatrix3& worldToBody() const { return n_; }
  /// The world conic A(t) = N^T A0 N as a polynomial matrix (scaled by a positive power of two
  /// so that its largest coefficient is in [1/2, 1)).
  const PolynomialMatrix3& conic() const { return conic_; }
  /// The same conic in the Bernstein basis of [0, 1] (row-major entries), computed from the
  /// Bernstein forms of the motion entries (adjugate and congruence by Bernstein products; this
  /// is the chain used by CD-DISC). Scaled by a positive power of two.
  const std::array<BernsteinPolynomial, 9>& conicBernstein() const { return conic_b_; }
  /// The conic matrix at time t computed numerically from N(t) (not from conic()).
  /// \throws std::invalid_argument if t is not finite (t outside [0, 1] extrapolates).
  Eigen::Matrix3d conicAt(double t) const;
  /// The centre of the ellipse at time t. \throws std::invalid_argument if t is not finite.
  Eigen::Vector2d centerAt(double t) const;

 private:
  MovingEllipse2(double a, double b, const PolynomialMatrix3& m, bool is_inverse);
  double a_;
  double b_;
  PolynomialMatrix3 n_;
  PolynomialMatrix3 conic_;
  std::array<BernsteinPolynomial, 9> conic_b_;
};

/// The three outputs of CD-DISC (thesis §2.5.3).
enum class EllipseCcdQuery {
  Collide,       ///< Variant 1: whether the disks collide (touch or overlap) for some t in [0, 1].
  FirstContact,  ///< Variant 2: and the time and point of first contact.
  AllContacts,   ///< Variant 3: and all external-contact instants and the collision intervals.
};

/// An external-contact instant (Theorem 2.6(1): f(lambda; t) has a negative double root).
struct EllipseContact {
  double t = 0.0;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< Lemma 2.5 contact point
  bool point_valid = false;
  /// True when the static test at t reported Touching (negative double root within the band);
  /// false for an instant kept conservatively (a root of Delta bounding a separate interval,
  /// Corollary 2.10, whose static value at the refined time is just outside the band).
  bool verified = false;
};

/// Result of CD-DISC.
struct EllipseCcdResult {
  bool collide = false;                 ///< touching or overlapping for some t in [0, 1]
  bool separate_at_start = true;        ///< Step 1: A(0), B(0) separate
  std::optional<double> first_contact;  ///< Variants 2, 3: first time of contact (0 if not separate at 0)
  Eigen::Vector2d first_contact_point = Eigen::Vector2d::Zero();
  bool first_contact_point_valid = false;  ///< false when the disks already overlap at t = 0
  /// Variant 3: every external-contact instant, increasing t.
  std::vector<EllipseContact> contacts;
  /// Variant 3: the maximal closed intervals of [0, 1] on which the disks touch or overlap
  /// (a single touching instant is a degenerate interval [t, t]); increasing, disjoint.
  std::vector<std::pair<double, double>> collision_intervals;
  int discriminant_degree = 0;  ///< formal degree of Delta(t)
  bool capped = false;          ///< kMaxEllipseEvents reached: conservative answer
};

/// Algorithm CD-DISC (thesis §2.3, Theorem 2.9, Corollary 2.10) with the variants of §2.5.3.
///
/// Step 1: the static test at t = 0. If the disks are not separate, the first contact is t = 0
/// (variants 1, 2 stop there; variant 3 tracks the intervals, the first one starting at 0).
/// Steps 2-4: Delta(t) by Bernstein products (see ellipseDiscriminant()).
/// Candidate event times are the roots of Delta (isolateRoots, refined) and the local extrema
/// of Delta (roots of Delta', each checked with the static test; roots of Delta near an extremum
/// are merged into it, see kEllipseGrazingWindow). Between consecutive candidates the state
/// (separate or not) is constant (Theorem 2.9); it is decided by the static test at the midpoint.
/// A candidate is a contact when the static test there reports Touching / Overlapping, when it
/// is a transversal root of Delta next to a separate interval (Corollary 2.10 / Theorem 2.9,
/// kept even if the static value is just outside the band: conservative), or when the state
/// changes there. Near-tangent decisions therefore err toward reporting contact.
///
/// Variant 1 and 2 stop at the first contact; Variant 3 processes all candidates.
/// Never throws for valid MovingEllipse2 objects (they were validated on construction).
EllipseCcdResult collideMovingEllipses(const MovingEllipse2& a, const MovingEllipse2& b,
                                       EllipseCcdQuery query = EllipseCcdQuery::FirstContact);

/// Characteristic polynomial f(lambda; t) = det(lambda A(t) - B(t)) of two moving disks, P(k, j)
/// = coefficient of lambda^k t^j (eq. 2.1; A(t), B(t) as MovingEllipse2::conic()). No failure
/// mode for valid MovingEllipse2 objects.
Eigen::MatrixXd characteristicPolynomial2(const MovingEllipse2& a, const MovingEllipse2& b);

/// The discriminant Delta(t) of f(lambda; t) with respect to lambda (eq. 2.2) in the Bernstein
/// basis of [0, 1], computed from the Bernstein forms of the g_k, which are themselves formed by
/// Bernstein products from the Bernstein forms of the motion entries (thesis §2.5.3 converts the
/// power-form g_k; with the adjugate the g_k of a degree-4 motion have degree 48 and their power
/// form loses Delta of Example 2.2 entirely to cancellation, so the conversion is done at the
/// motion entries, where the degree is lowest). Positive scale factors aside:
/// normalised so that its largest Bernstein coefficient is in [1/2, 1) in absolute value).
/// No failure mode for valid MovingEllipse2 objects.
BernsteinPolynomial ellipseDiscriminant(const MovingEllipse2& a, const MovingEllipse2& b);

// ---------------------------------------------------------------------------------------------
// Ellipses moving in 3D space (thesis ch.3).

/// A (filled) ellipse in 3D: the disk u^2/a^2 + v^2/b^2 <= 1 of the body xy-plane (z = 0) moved by
/// a homogeneous 4x4 polynomial motion M(t), t in [0, 1] (body -> world, last row
/// [0, 0, 0, w(t)], world point x = (L u + v) / w). Validation (std::invalid_argument naming the
/// item): radii finite positive; degree <= kMaxEllipseMotionDegree; last row [0, 0, 0, w(t)];
/// w(t) and det L(t) (3x3 linear part) root-free on [0, 1] (so the plane is never degenerate).
class MovingEllipse3 {
 public:
  MovingEllipse3(double a, double b, const PolynomialMatrix4& motion);

  double a() const { return a_; }
  double b() const { return b_; }
  const PolynomialMatrix4& motion() const { return m_; }

  /// Evaluated at t; each \throws std::invalid_argument if t is not finite.
  Eigen::Vector3d centerAt(double t) const;  ///< v(t) / w(t)
  Eigen::Vector3d axisUAt(double t) const;   ///< L(t) e_x / w(t)
  Eigen::Vector3d axisVAt(double t) const;   ///< L(t) e_y / w(t)
  Eigen::Vector3d normalAt(double t) const;  ///< (L e_x) x (L e_y), not normalised

 private:
  double a_;
  double b_;
  PolynomialMatrix4 m_;
};

/// Static state of two planar ellipses in 3D at one instant (Theorem 3.1 and Table 2, evaluated
/// numerically): planes parallel and distinct -> Separated; coincident -> the 2D test of
/// Theorem 2.6 in the common plane; otherwise the chords ("1D ellipses") that the intersection
/// line cuts from both disks: disjoint -> Separated, sharing only an end point -> Touching,
/// overlapping -> Overlapping (the solids then intersect along a segment). The touching band is
/// kEllipseTouchingRelativeBand relative to the chord scale.
/// \throws std::invalid_argument if t is not finite.
Separation classifyEllipses3(const MovingEllipse3& a, const MovingEllipse3& b, double t);

/// Result of CD-DISC3D.
struct Ellipse3CcdResult {
  bool collide = false;
  std::optional<double> first_contact;
  /// True if the two containing planes coincide (and are fixed) for all t: Step 1 reduced the
  /// problem to CD-DISC in that plane.
  bool coplanar = false;
  int discriminant_degree = 0;  ///< formal degree of Delta_f(t) (0 in the coplanar case)
  bool capped = false;          ///< kMaxEllipseEvents reached: conservative answer
};

/// Algorithm CD-DISC3D (thesis §3.3, Theorem 3.1, steps 1-8): first contact of two filled planar
/// ellipses moving in 3D.
///  Step 1: if the containing planes coincide for every t (normals parallel and B's centre in A's
///          plane, identically as Bernstein polynomials up to a relative 1e-12 of their scale) and
///          the common plane is fixed, CD-DISC runs in that plane (coplanar = true). A common plane
///          that moves is not reduced (Delta_f vanishes identically there): then every time is a
///          candidate and the answer is decided by the static test at the isolation leaves
///          (conservative, slow).
///  Steps 2-4: the intersection line is B's plane cut with A's plane, written in A's body plane
///          as p alpha + q beta + r = 0 (p, q, r polynomials); it is parametrised homogeneously as
///          X(s) = X0 + s D in A's body coordinates (no division), and mapped to B's body plane
///          by cross products with B's axes (again without division). The 1D ellipses are the
///          2x2 matrices A(t), B(t) of the restrictions h(s), g(s) of the two ellipse equations.
///  Steps 5-6: f(lambda; t) = det(lambda A(t) - B(t)) (quadratic) and Delta_f(t) = g1^2 - 4 g2 g0,
///          all by Bernstein products from the motion entries.
///  Step 7: every root of Delta_f (and every extremum, for grazing contacts as in CD-DISC) is
///          validated by classifyEllipses3(): parallel distinct planes are invalid; coincident
///          planes use Theorem 2.6; otherwise the chords decide (Theorem 3.1).
///  Step 8: the first valid candidate (or a state change between candidates) is the first
///          contact. t = 0 is checked first (Step 0 of CD-DISC).
Ellipse3CcdResult collideMovingEllipses3(const MovingEllipse3& a, const MovingEllipse3& b);

}  // namespace fcl_quadric
