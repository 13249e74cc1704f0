#pragma once
/// \file quadric_contact_configuration.h
/// Contact configuration of two tangent quadric surfaces (Choi 2008 §6.3): how they touch at a
/// multiple root lambda0 of the characteristic polynomial f(lambda) = det(lambda A - B)
/// (§6.3.1, Lemma 6.2: rank of lambda0 A - B -> a single point / two points or a line / a conic)
/// and whether the touching point is a *genuine* contact (§6.3.2, Definition 6.3: the surfaces
/// do not cross in its neighbourhood), decided by the Procedure of §6.3.2 (Step 1: the n-th
/// derivative test of f at lambda0; Step 2: rank and signs at lambda0; Tables 7-10).
///
/// Quadrics are 4x4 symmetric matrices acting on homogeneous X = (x, y, z, w): the surface is
/// X^T Q X = 0 (projective: points with w = 0 are at infinity). Only std and Eigen are used.
///
/// Where this module deliberately departs from the letter of the thesis (each checked against
/// the representative pairs of Tables 7-9 in the tests):
///  1. Step 2 asks for the signs of "the non-zero eigenvalues of lambda0 I - A^-1 B". Read
///     literally these are lambda0 - lambda_i over the other roots lambda_i of f, which cannot
///     separate Case 21 from Case 22: their pairs have f = -lambda^3 and f = lambda^3, the same
///     roots {0, 0, 0, inf} (and A is singular: A^-1 does not exist). What is meant follows from
///     the canonical form of a regular real symmetric pencil under congruence X -> P X: each
///     real root lambda_i with a k x k Jordan block carries a sign characteristic eps_i = +-1
///     (A-block eps_i F_k, B-block eps_i (lambda_i F_k + G_k); F_k the exchange matrix, G_k its
///     shift), a root at infinity (A singular) has A-block eps G_k, B-block eps F_k. Hence
///     lambda0 A - B has the blocks eps_i ((lambda0 - lambda_i) F_k - G_k) for the other roots --
///     for k = 1 the eigenvalue lambda0 - lambda_i of lambda0 I - A^-1 B *times its sign
///     characteristic* --, -eps for a simple root at infinity, and -eps G_k (rank k - 1) for
///     the blocks of lambda0 itself. By Sylvester's law of inertia, the signs the Procedure needs
///     are those of the non-zero eigenvalues of the *symmetric* matrix lambda0 A - B, i.e. its
///     inertia (p, n), which is the bracket (p, n) of the signature sequences of Tu et al. (the
///     thesis's [66]): Case 21 (((1,1))) has lambda0 A - B = -B = diag(1,0,-1,0), Case 22
///     (((0,2))) has diag(-1,0,-1,0). It needs no inverse, its rank is rank(lambda0 I - A^-1 B)
///     (the thesis's footnote), and (p, n) vs (n, p) is only the sign of the pencil, so "of the
///     same sign" is implemented as "lambda0 A - B is semidefinite".
///  2. Step 1 reports every quadruple root with ellipsoids on both sides as not genuine
///     (Case 27), yet lists Case 33 -- also a quadruple root with ellipsoids on both sides,
///     ((((1,0)))) -- as genuine; a sphere resting on a plane (the plane as the double plane
///     P P^T of §6.2) is such a Case 33 contact. Table 10's differentiator is that Case 27 is
///     ((((1,1)))): lambda0 A - B indefinite. Implemented: a quadruple root with ellipsoids on
///     both sides is not genuine iff lambda0 A - B is indefinite (equivalently here: rank 2,
///     Segre [(31)], rather than rank 1, [(211)]; the inertia is used as in Step 2).
///  3. When lambda0 A - B has rank 1 and is (a multiple of) B itself (lambda0 = 0) or A itself
///     (lambda0 = inf) -- one quadric is a double plane P P^T -- the "conic of tangency" of Lemma
///     6.2 is just the plane section of the other quadric, counted twice; a plane cutting a
///     sphere has such a triple root. Only the singular points of that section are contact
///     points (Table 8: Case 19, a cylinder cut by a plane, has no real contact point; Cases
///     32, 33 have the vertex of the section). contact_points follows that.
///  4. The "n-th derivative test" n is, by definition, the multiplicity of lambda0 as a root of f.
///
/// Verdict implemented (m = multiplicity, "ellipsoid" = f < 0 there, "hyperboloid" = f > 0):
///  - hyperboloids on both sides (m even, f^(m)(lambda0) > 0): not genuine (Cases 5, 8, 9, 12,
///    13, 18, 23, 26, 28, 32, 35);
///  - ellipsoids on both sides (m even, f^(m)(lambda0) < 0): genuine (Cases 6, 7, 15, 24, 25,
///    30, 33), except m = 4 with lambda0 A - B indefinite (Case 27);
///  - one of each (m = 3): rank 3 -> not genuine (Case 11); otherwise genuine iff lambda0 A - B
///    is semidefinite (Case 22) and not genuine if it is indefinite (Case 21).
/// The §6.3.1 filter of the CCD (a root lambda0 >= 0 is an internal contact of two CQMs and is
/// rejected) is the caller's business and is not applied here.
///
/// Roots at infinity: det(lambda A - B) has degree < 4 when A is singular (cones, cylinders,
/// plane pairs: the leading coefficients vanish); the pencil's roots live on the projective
/// line and lambda = inf is a root of multiplicity 4 - deg f. It matters (Table 9, Case 30: the
/// real contact is at lambda0 = inf, where lambda0 A - B "is" A). multipleRoots() reports a
/// multiple root at infinity as +infinity and contactConfiguration() accepts lambda0 =
/// +-infinity; both work on the pencil det(nu B - A) = nu^4 f(1/nu) at nu = 0 there. Swapping A
/// and B maps lambda0 to 1/lambda0 and leaves the verdict, rank, multiplicity and contact points
/// unchanged.
///
/// Numerics. A and B are first scaled by powers of two (exact) to Frobenius norm in [1/2, 1);
/// f's coefficients are expanded exactly as the 24-term Leibniz sum of products of the linear
/// entries lambda a_ij - b_ij (so small-integer inputs give exact coefficients), together with
/// the same sum of absolute values, which bounds the rounding and perturbation scale of each
/// derivative of f. The projective line is covered by two charts, mu = lambda (scaled) and
/// nu = 1/mu, each searched on [-1.5, 1.5]. A multiple root of multiplicity m is located as a
/// simple root of f^(m-1) (well conditioned) at which f, ..., f^(m-2) vanish to tolerance; rank
/// and inertia come from the symmetric eigenvalues of lambda0 A - B at that refined root. See
/// tolerance_contact for the thresholds. The thresholds are relative to the matrices' scale, so
/// express the quadrics in a frame near the contact and a length unit comparable to their size
/// (matrix entries of comparable magnitude): eigenvalues of lambda0 A - B below 1e-6 of the
/// normalised scale count as zero. (In development runs, unit-size pairs under random rigid
/// motions kept every verdict for translations up to 20; at 50 some were lost.)

#include <array>
#include <vector>

#include <Eigen/Core>

namespace fcl_quadric {

namespace tolerance_contact {
/// Input matrices must be symmetric to this relative tolerance (max |Q - Q^T| <= tol * max |Q|,
/// the library-wide quadric check); they are then symmetrised.
constexpr double kSymmetryRelative = 1e-12;
/// A derivative f^(k)(x)/k! of the normalised characteristic polynomial counts as zero when its
/// magnitude is at most this times the same derivative of the absolute-value expansion (the sum
/// over the 24 Leibniz terms of |products|) at |x|: rounding of the expansion and relative
/// perturbations eta of the entries move f^(k)/k! by ~(8u + 4 eta) times that scale, u = 1.1e-16,
/// so 1e-12 leaves three orders of magnitude above rounding while a double root split by a
/// relative 1e-6 (f ~ 1e-12) is still recognised. 2^-52 of the scale at |x| = 1 is added to
/// the scale, so that a scale vanishing at x itself (structural zeros) does not reject a root
/// found a rounding error away from an exact one. Also decides a singular pencil (f == 0: every
/// coefficient zero by this test) and the n-th derivative test; a caller's lambda0 at which the
/// test gives n >= 2 is refined to the multiple root found within kRootCluster.
constexpr double kDerivativeZeroRelative = 1e-12;
/// An eigenvalue sigma of lambda0 A - B (normalised A, B of Frobenius norm < 1, in the chart
/// where |lambda0| <= 1.5, see the file comment) counts as zero when |sigma| <= this times
/// (1 + |lambda0|). At a certified multiple root at least one eigenvalue is zero by definition
/// (the smallest is forced) and at most `multiplicity` (geometric <= algebraic multiplicity).
/// 1e-6 is the square root of kDerivativeZeroRelative: a semisimple double root split by
/// epsilon has f ~ epsilon^2 at the midpoint and two eigenvalues ~ epsilon, so the two tests
/// agree about the same near-tangent pairs. The eigenvalues c of the other quadric restricted
/// to the null space (which decide the contact points) count as zero when |c| <= this times
/// max(largest |c|, 1e-4): that restricted form shrinks as a whole when the contact is far from
/// the origin, and 1e-10 stays above the rounding of the form and of the null space.
constexpr double kRankRelative = 1e-6;
/// Candidate multiple roots closer than this chordal distance on the (normalised) projective
/// line are one root (the one of highest multiplicity is kept): noise splits an m-fold root
/// by ~eta^(1/m) in the lower derivatives (a quadruple root's f' has three roots ~1e-5 apart).
constexpr double kRootCluster = 1e-4;
/// A root of the chart nu = 1/mu with |nu| <= this is the root at infinity (normalised scale).
constexpr double kInfinitySnap = 1e-12;
/// Half-width of each chart's search interval (mu and nu = 1/mu in [-1.5, 1.5] overlap).
constexpr double kChartRadius = 1.5;
}  // namespace tolerance_contact

/// Lemma 6.2: how two tangent quadrics touch at the multiple root lambda0 of det(lambda A - B).
enum class TangencyKind {
  SinglePoint,      ///< rank(lambda0 A - B) = 3: one tangency point (the null vector), real
  TwoPointsOrLine,  ///< rank 2: the null-space line meets A in two points (or lies on it), in C^3
  Conic,            ///< rank 1: tangency along the conic (null plane) x A, in C^3
  Coincident,       ///< rank 0: B is a multiple of A (same surface); not a contact
  None,             ///< lambda0 is not a multiple root of f (or the pencil is singular)
};
const char* toString(TangencyKind k);

/// Everything the Procedure of §6.3.2 looks at, for one multiple root lambda0.
struct ContactConfiguration {
  /// The root examined: the caller's lambda0 refined to the nearby multiple root (the simple
  /// root of f^(m-1)) when it is one, otherwise the caller's value. +infinity for the root at
  /// infinity (A singular, deg f <= 2).
  double lambda0 = 0.0;
  /// Multiplicity of lambda0 as a root of f (0: not a root, 1: simple; 2..4: multiple). -1 for a
  /// singular pencil (f == 0: every lambda is a root).
  int multiplicity = 0;
  /// Numerical rank of lambda0 A - B (kRankRelative); for lambda0 = inf the rank of A.
  int rank = 4;
  /// Inertia of lambda0 A - B: numbers of positive / negative eigenvalues counted non-zero (for
  /// lambda0 = inf: of A, the limit of (lambda A - B) / lambda). The signature-sequence bracket
  /// (p, n) of Tables 7-9, up to order.
  int positive = 0;
  int negative = 0;
  TangencyKind kind = TangencyKind::None;
  /// n of the n-th derivative test: the smallest n with f^(n)(lambda0) != 0 (kDerivativeZero-
  /// Relative); equals multiplicity at a multiple root. -1 for a singular pencil.
  int first_nonzero_derivative = 0;
  /// Q(lambda0 -/+ eps) = lambda A - B near lambda0 is an "ellipsoid" (f < 0: inertia (3,1) or
  /// (1,3), an odd index) rather than a "hyperboloid" (f > 0: even index). For lambda0 = inf,
  /// "before" is lambda -> +inf and "after" lambda -> -inf. Meaningful when multiplicity >= 1.
  bool ellipsoid_before = false;
  bool ellipsoid_after = false;
  /// The Procedure's verdict (Definition 6.3, with the corrections of the file comment): the
  /// tangency at lambda0 is not on a real intersection curve along which the surfaces cross.
  /// False unless kind is SinglePoint, TwoPointsOrLine or Conic. It is a property of the pencil
  /// and lambda0: check real_contact too (see genuineRealContact()).
  bool genuine = false;
  /// Real tangency points (homogeneous, unit norm; w > 0 when |w| > 1e-12, otherwise the
  /// largest-magnitude coordinate is positive; w ~ 0 is a point at infinity):
  ///  - rank 3: the null vector of lambda0 A - B;
  ///  - rank 2: the real intersections of the null-space line with A (one point if the line is
  ///    tangent to A, none if they are imaginary; two points spanning the line if it lies on A);
  ///  - rank 1: one representative real point of the conic (null plane) x A, none if that conic
  ///    has no real point; when one quadric is a double plane (lambda0 = 0 or inf), the singular
  ///    point of the other's plane section, if it is singular (file comment, item 3).
  std::vector<Eigen::Vector4d> contact_points;
  /// The real contact set is a curve (a line on both quadrics, or a real conic / line) of which
  /// contact_points holds representatives only.
  bool contact_curve = false;
  /// contact_points is non-empty: the tangency is real (in PR^3).
  bool real_contact = false;
  /// The pencil is singular: det(lambda A - B) == 0 for every lambda (e.g. two cylinders with
  /// parallel axes, two cones with a common apex); Lemma 6.2 and the Procedure do not apply.
  bool singular_pencil = false;

  /// What a collision query wants: a real tangency point that is a genuine contact.
  bool genuineRealContact() const { return genuine && real_contact; }
};

/// Characteristic polynomial coefficients c0..c4 of det(lambda A - B) (ascending powers), for A
/// and B as given (not normalised). Leading coefficients are zero when A is singular (c4 =
/// det A). Exact for small-integer (or dyadic) entries.
/// \throws std::invalid_argument if A or B has a non-finite entry or is not symmetric
/// (kSymmetryRelative); the message names the matrix.
std::array<double, 5> characteristicQuartic(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B);

/// Multiple real roots of det(lambda A - B) (kDerivativeZeroRelative, kRootCluster), each once,
/// ascending; a multiple root at infinity (deg f <= 2) is last, as +infinity. Empty for a
/// singular pencil.
/// \throws std::invalid_argument as characteristicQuartic, or if A or B is zero.
std::vector<double> multipleRoots(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B);

/// Classify the contact at a given multiple root (e.g. one found by a CCD solver or by
/// multipleRoots). lambda0 may be +-infinity (the root at infinity). A lambda0 at which f does
/// not have a multiple root (n-th derivative test n <= 1) gives kind None, genuine false, no
/// contact points, multiplicity 0 or 1 and the rank / inertia of lambda0 A - B there.
/// \throws std::invalid_argument as multipleRoots, or if lambda0 is NaN.
ContactConfiguration contactConfiguration(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B, double lambda0);

}  // namespace fcl_quadric
