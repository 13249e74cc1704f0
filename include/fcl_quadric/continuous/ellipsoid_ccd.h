#pragma once
/// \file ellipsoid_ccd.h
/// Continuous collision detection of two ellipsoids under rational rigid or affine motions
/// (Choi 2008, thesis ch.5; docs/algorithms.md section 8).
///
/// Pipeline of continuousCollideEllipsoids():
///  1. culling (thesis §5.4.1): moving bounding spheres (rigid motions: the squared centre distance
///     minus (r_a + r_b)^2, a polynomial in t, certified positive by its Bernstein coefficients),
///     then the separating plane of the two ellipsoids at t = 0 (Theorem 4.6) carried along with
///     b's motion: a moves through it iff the polynomial q(t)^T Q_a^{-1} q(t) (q the plane in a's
///     body frame, Q_a^{-1} a's dual quadric) reaches 0, certified negative by its Bernstein
///     coefficients;
///  2. the CCD function F(u, t) = det((u-1) A(t) - u B(t)) in Bernstein form (ccd_function.h);
///  3. the interval processing of §5.3.1: State(t) = sign of max_u F(u, t) (Theorem 5.1), Bezier
///     shoots from separated instants (each certifies a separation interval: F(u^, t) > 0 for a
///     fixed u^ and all t before the first root, found by certified firstRoot), candidate
///     overlap intervals certified by the sign of F or the monotonicity of F in t on u-slabs (no
///     loop of the zero set, §5.3.1 "Processing candidate overlapping intervals"), bisection
///     where neither applies.
/// Everything not certified separated is reported as colliding: the collision intervals are the
/// complement of the certified separation intervals, so near-tangent or unresolved instants err
/// toward contact (flagged in the result).
///
/// Part of the continuous-collision layer: standard library and Eigen only.

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "fcl_quadric/algebra/bivariate_bernstein.h"
#include "fcl_quadric/continuous/motion_matrix.h"
#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

/// An ellipsoid given in its body frame, carried by a motion (body -> world).
struct MovingEllipsoid {
  Ellipsoid body;  ///< the ellipsoid in body coordinates (often centred at the origin)
  PiecewiseMotion motion;
};

/// How the motion between the poses is interpolated.
enum class CcdInterpolation {
  /// The given rational motions, exactly.
  Rigid,
  /// Thesis §5.2: the relative motion of b in a's body frame is replaced by the affine
  /// interpolant B(t) = (1-t) B_0 + t B_1, c(t) = (1-t) c_0 + t c_1 between the end states of each
  /// piece (CCD function of degree 6 in t). An approximation of the rigid motion that may change
  /// b's shape in between; exact for the interpolant itself.
  Affine,
};

struct CcdOptions {
  /// Find every collision interval (true) or stop at the first contact (false).
  bool all_intervals = true;
  /// Only [0, t_max] is examined (the running minimum contact time t-bar of thesis §5.4.1).
  double t_max = 1.0;
  CcdInterpolation interpolation = CcdInterpolation::Rigid;
  /// Skip the sphere and separating-plane culls (thesis Table 5 "setup 2" measures without them).
  bool culling = true;
  /// Conditioning limit (docs/algorithms.md section 8): a pair whose condition estimate
  /// (aspect ratio x condition of the motion's linear part)^2 exceeds it is not decided, it is
  /// reported colliding throughout [0, t_max] and flagged unresolved. Every pair below it, rigid or
  /// affine, is decided with the extended-precision check (precision_checked flags those above
  /// tolerance::kCcdCheckedCondition).
  /// Must be positive (infinity disables the fallback).
  double max_condition = tolerance::kCcdMaxCondition;
};

/// A closed time interval [begin, end] (begin == end for an instant).
struct CcdInterval {
  double begin = 0.0;
  double end = 0.0;
};

struct EllipsoidCcdResult {
  /// Some instant of [0, t_max] is not certified separate.
  bool collide = false;
  /// Earliest such instant (the first contact time, or 0 if the pair already touches or
  /// overlaps at t = 0). Never later than the exact first contact (up to kCcdTimeTolerance).
  std::optional<double> first_contact_time;
  /// World point of the first contact (the centre of the pencil member at the maximising u,
  /// which is the tangency point at an external contact; a common interior point when the pair
  /// already overlaps at t = 0).
  Eigen::Vector3d contact_point = Eigen::Vector3d::Zero();
  /// Maximal collision (touching or overlapping) intervals, sorted; instants of grazing contact
  /// appear as intervals of width 0. With all_intervals = false only the first one is reported
  /// (its end may then be unknown and is set to its begin).
  std::vector<CcdInterval> collision_intervals;
  /// Maximal certified separation intervals (open in the thesis' sense), sorted.
  std::vector<CcdInterval> separation_intervals;
  /// Some reported collision interval contains no instant certified overlapping (max_u F below
  /// minus the band): it may be a touch within the touching band, or a near miss reported as
  /// contact. (First-contact mode: the contact instant is inside the band and the state just
  /// after it is not certified overlapping.)
  bool near_tangent = false;
  /// The work cap was reached: some interval was reported colliding without certification.
  bool unresolved = false;
  /// The pair was ill-conditioned (condition estimate above tolerance::kCcdCheckedCondition): the
  /// extended-precision rebuild of F(u, t) that every pair gets (docs/algorithms.md section
  /// 8, "precision check") widens its margins materially, so answers lean further toward contact.
  bool precision_checked = false;
  /// The pair was declared collision-free by a cull (0 = none, 1 = bounding spheres,
  /// 2 = separating plane).
  int culled_by = 0;
  /// Degree of F(u, t) in t (0 when culled).
  int degree_t = 0;
  /// State evaluations plus Bezier shoots plus overlap-certificate slabs spent, summed over all
  /// segments (saturating at INT_MAX); tolerance::kCcdMaxWork caps the work of each piece of the
  /// motions.
  int work = 0;
  /// Segments [0, t_max] was cut into and solved one by one: the breaks of piecewise motions
  /// plus the balance breaks (tolerance::kCcdBalanceRatio). 1 for two single-piece motions
  /// whose weights stay balanced (every motion from two poses).
  int segments = 0;
};

/// The degree in t of the CCD function F(u, t) = det((u - 1) A(t) - u B(t)) that the exact
/// (CcdInterpolation::Rigid) solver builds for the pair, structurally (leading coefficients that
/// cancel can make the computed one lower): 2 sum_j max(c_j^a, c_j^b), where c_j is the degree of
/// column j of a motion's inverse factor N(t) S, over all its pieces (thesis §5.1; S, the solver's
/// frame, mixes every column of N into the last). 18 for two motions from poses, 2 k for a
/// translation of degree k against a fixed body. No failure mode.
int ccdFunctionDegree(const MovingEllipsoid& a, const MovingEllipsoid& b);

/// Continuous collision of two moving ellipsoids over [0, options.t_max].
/// \throws std::invalid_argument if t_max is not in (0, 1], or if an intermediate polynomial
/// overflows (a non-finite coefficient; extreme magnitudes of radii or coordinates);
/// CcdDegreeError (a std::invalid_argument) if the interpolation is Rigid and
/// ccdFunctionDegree(a, b) exceeds tolerance::kCcdMaxDegree. The result never holds NaN.
EllipsoidCcdResult continuousCollideEllipsoids(const MovingEllipsoid& a, const MovingEllipsoid& b,
                                               const CcdOptions& options = CcdOptions());

/// The CCD function of one segment [t_begin, t_end] of [0, 1] (a piece of both motions; one segment
/// [0, 1] for single-piece motions) exactly as continuousCollideEllipsoids() builds and solves it:
/// F(u, s) = det((u - 1) A(s) - u B(s)) on [0, 1]^2 in the segment's local time
/// s = (t - t_begin) / (t_end - t_begin), with A and B in the solver's scaled, balanced coordinates
/// and F normalised to largest |coefficient| 1. The u scale (lambda = (u - 1) / u up to the
/// positive balancing factors) differs from one segment to the next.
struct CcdFunctionSegment {
  double t_begin = 0.0;
  double t_end = 1.0;
  BivariateBernstein F;
};

/// The CCD functions of the pair over [0, 1], one per segment the solver uses (the pieces' breaks
/// and the balance breaks, EllipsoidCcdResult::segments; for plots and tests; the culls are not
/// applied). \throws std::invalid_argument as continuousCollideEllipsoids().
std::vector<CcdFunctionSegment> ccdFunctionSegments(const MovingEllipsoid& a, const MovingEllipsoid& b,
                                                    CcdInterpolation interpolation = CcdInterpolation::Rigid);

/// The world ellipsoid of a moving ellipsoid at time t (affine image of the body ellipsoid, thesis
/// §5.1). \throws std::invalid_argument if t is not finite (t outside [0, 1] extrapolates).
Ellipsoid ellipsoidAt(const MovingEllipsoid& m, double t);

}  // namespace fcl_quadric
