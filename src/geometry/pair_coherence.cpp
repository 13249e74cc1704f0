#include "fcl_quadric/geometry/pair_coherence.h"

namespace fcl_quadric {

Separation PairCoherence::classifyAndRemember(const Ellipsoid& a, const Ellipsoid& b) {
  const SeparationCertificate cert = classifyEllipsoids(a, b);
  if (cert.status == Separation::Separated) {
    // The certificate's normal placed midway between the solids (certificatePlane()). It is not
    // re-certified here: every use certifies it against the poses of that frame, so a plane
    // spoilt by rounding can only cost a miss, never a wrong answer.
    candidate_ = CachedPlane::fromPlane(certificatePlane(cert, a, b)).value_or(CachedPlane());
  } else {
    candidate_ = CachedPlane();
  }
  return cert.status;
}

}  // namespace fcl_quadric
