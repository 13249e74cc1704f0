#pragma once
/// \file ellipsoid_separation.h
/// Exact (certified) classification of two static ellipsoids: separate, touching, overlapping.
/// Choi 2008 Theorem 4.1 and Remark 4.3; Wang et al. 2004 Theorem 1.

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {

/// Relative position of two solids. Touching means "not separate, no common interior point" as
/// far as the certified arithmetic can tell (tolerance band: docs/tolerances.md); it counts as
/// contact (collision), so near tangency the library errs toward reporting contact.
enum class Separation { Separated, Touching, Overlapping };

/// "separate", "touching" or "overlapping"; "unknown" for a value outside the enum.
const char* toString(Separation s);

/// How a classification was decided (for tests, benchmarks and diagnostics).
struct SeparationCertificate {
  Separation status = Separation::Touching;
  /// Pencil parameter mu in [0,1] at which the certificate was evaluated (mu = nu/(1+nu) with
  /// nu = -lambda, lambda the parameter of f(lambda) = det(lambda A - B)).
  double mu = 0.5;
  /// psi(mu) = F(mu)/G(mu): the minimum over x of mu q_A(x) + (1-mu) q_B(x) in A's unit frame;
  /// > 0 certifies separation, < 0 at the maximiser means overlap.
  double psi = 0.0;
  /// Witness point (world frame): inside both for Overlapping; the contact point (Theorem 4.4)
  /// for Touching; the minimax point of the pencil for Separated.
  Eigen::Vector3d witness = Eigen::Vector3d::Zero();
  /// For Separated: a unit normal n pointing from the first argument to the second such that
  /// h_a(n) < -h_b(-n), i.e. some plane with this normal separates them (planeWithNormal()).
  /// For the other states: the normal of the first ellipsoid's level set at the witness, except
  /// for an Overlapping pair decided by a pre-test (precision_stage -1), where it is the direction
  /// of the line of centres, from the first centre to the second.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  /// -1: decided by a pre-test (bounding / inscribed spheres, or supports and radii along the
  /// line of centres); 0: decided in double; 1: decided in
  /// double-double; 2: undecided at double-double precision, reported as Touching.
  int precision_stage = 0;
  /// Iterations of the safeguarded Newton search for the pencil maximiser.
  int iterations = 0;
};

/// Classify ellipsoids a and b. Symmetric by construction: classify(a,b) and classify(b,a) run
/// the same computation (the pair is put in a canonical order first).
/// Cost: ~65 ns per random pair, 340-390 ns for the 3.4% the pencil decides (docs/benchmarks.md,
/// docs/algorithms.md §1). Never throws for valid Ellipsoid objects.
SeparationCertificate classifyEllipsoids(const Ellipsoid& a, const Ellipsoid& b);

/// classifyEllipsoids(a, b).status, always the same value (Choi 2008 Theorem 4.1 and Remark 4.3,
/// certified as there), without the certificate: when a pre-test decides (about 97% of random
/// pairs, docs/algorithms.md §1) the witness and normal are not computed. The boolean queries use
/// it. Never throws: an Ellipsoid is valid by construction (its constructor rejects bad input).
Separation separationStatus(const Ellipsoid& a, const Ellipsoid& b);

/// Shorthand: true unless the ellipsoids are separate (touching counts as collision).
inline bool ellipsoidsCollide(const Ellipsoid& a, const Ellipsoid& b) {
  return separationStatus(a, b) != Separation::Separated;
}

}  // namespace fcl_quadric
