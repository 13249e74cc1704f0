#include "fcl_quadric/geometry/pair_coherence.h"

namespace fcl_quadric {

Separation PairCoherence::query(const Ellipsoid& a, const Ellipsoid& b) {
  ++queries_;
  if (candidate_ && planeSeparates(*candidate_, a, b)) {
    ++plane_hits_;
    return Separation::Separated;
  }
  const SeparationCertificate cert = classifyEllipsoids(a, b);
  if (cert.status == Separation::Separated) {
    // Cheapest plane first: the certificate's normal placed midway between the solids
    // (planeWithNormal() proves it separates); it comes with the classification and avoids
    // isolating the two roots of Theorem 4.6, which remains the fallback.
    const Plane p = planeWithNormal(cert.normal, a, b);
    if (planeSeparates(p, a, b)) {
      candidate_ = p;
    } else if (auto sp = separatingPlane(a, b); sp && sp->certified) {
      candidate_ = sp->plane;
    } else {
      candidate_.reset();
    }
  } else {
    candidate_.reset();
  }
  return cert.status;
}

}  // namespace fcl_quadric
