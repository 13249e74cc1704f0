#include "fcl_quadric/geometry/ellipsoid_separation.h"

#include <cmath>

#include "fcl_quadric/tolerances.h"
#include "geometry/pencil.h"

namespace fcl_quadric {

const char* toString(Separation s) {
  switch (s) {
    case Separation::Separated: return "separate";
    case Separation::Touching: return "touching";
    case Separation::Overlapping: return "overlapping";
  }
  return "unknown";
}

namespace {

/// One precision stage of the certified decision (docs/algorithms.md §1). With x = x(mu) the
/// pencil witness and Q, r as in detail::WitnessValues:
///  - Separated   if Q - tau scale_Q - (|r| + tau |r|_scale)^2 / mu > 0: then psi(mu) > 0, i.e. the
///                positive combination mu q_A + (1-mu) q_B is positive everywhere, so no point is
///                in both solids (Theorem 4.1 via Remark 4.3 in the mu-form of pencil.h);
///  - Overlapping if q_A(x) < -tau scale_a and q_B(x) < -tau scale_b: x is inside both;
///  - otherwise undecided (returns false).
/// tau bounds the relative rounding of the stage's arithmetic (tolerances.h).
template <class T>
bool certify(const detail::Pencil<T>& p, const T& mu, double tau, SeparationCertificate* out, T x[3]) {
  detail::witness(p, mu, x);
  const detail::WitnessValues w = detail::witnessValues(p, mu, x);
  const double mud = toDouble(mu);
  out->mu = mud;
  out->psi = w.Q;
  if (mud > 0.0) {
    const double rn = std::sqrt(w.residual2) + tau * std::sqrt(w.residual_scale2);
    const double lower = w.Q - tau * w.scale_Q - rn * rn / mud;
    if (lower > 0.0) {
      out->status = Separation::Separated;
      return true;
    }
  }
  if (w.qa < -tau * w.scale_a && w.qb < -tau * w.scale_b) {
    out->status = Separation::Overlapping;
    return true;
  }
  return false;
}

}  // namespace

SeparationCertificate classifyEllipsoids(const Ellipsoid& a, const Ellipsoid& b) {
  const bool swap = detail::swapForCanonicalOrder(a, b);
  const Ellipsoid& A = swap ? b : a;
  const Ellipsoid& B = swap ? a : b;
  SeparationCertificate cert;

  // Stage 0: double.
  const detail::Pencil<double> p = detail::makePencil<double>(A, B);
  const double mu = detail::maximisePsi(p, 0.5, &cert.iterations);
  double x[3];
  if (certify<double>(p, mu, tolerance::kCertificateRelativeBoundDouble, &cert, x)) {
    cert.precision_stage = 0;
    cert.witness = detail::unitFrameToWorld(A, Eigen::Vector3d(x[0], x[1], x[2]));
    return cert;
  }

  // Stage 1: double-double, polishing the maximiser from the double estimate.
  const detail::Pencil<DoubleDouble> pd = detail::makePencil<DoubleDouble>(A, B);
  int it_dd = 0;
  const DoubleDouble mud = detail::maximisePsi(pd, mu, &it_dd);
  cert.iterations += it_dd;
  DoubleDouble xd[3];
  const bool decided =
      certify<DoubleDouble>(pd, mud, tolerance::kCertificateRelativeBoundDoubleDouble, &cert, xd);
  cert.precision_stage = decided ? 1 : 2;
  if (!decided) cert.status = Separation::Touching;  // within the band: err toward contact
  cert.witness = detail::unitFrameToWorld(A, Eigen::Vector3d(toDouble(xd[0]), toDouble(xd[1]), toDouble(xd[2])));
  return cert;
}

}  // namespace fcl_quadric
