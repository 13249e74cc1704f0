#include "fcl_quadric/geometry/pair_coherence.h"

namespace fcl_quadric {

Separation PairCoherence::classifyAndRemember(const Ellipsoid& a, const Ellipsoid& b) {
  const SeparationCertificate cert = classifyEllipsoids(a, b);
  if (cert.status == Separation::Separated) {
    // Keep the certificate's normal placed midway between the solids. A pre-test's certificate
    // (precision_stage -1) already has its witness on that mid-plane, {n.x = n.w} (lineDecision()
    // and followUpTests() in ellipsoid_separation.cpp), which saves planeWithNormal()'s two
    // support functions; the pencil's witness is its minimax point, so those planes are placed by
    // planeWithNormal(). The plane is not re-certified here: every use certifies it against the
    // poses of that frame, so a plane spoilt by rounding can only cost a miss, never a wrong
    // answer.
    Plane plane;
    if (cert.precision_stage == -1) {
      plane.normal = cert.normal;
      plane.offset = cert.normal.dot(cert.witness);
    } else {
      plane = planeWithNormal(cert.normal, a, b);
    }
    candidate_ = CachedPlane::fromPlane(plane).value_or(CachedPlane());
  } else {
    candidate_ = CachedPlane();
  }
  return cert.status;
}

}  // namespace fcl_quadric
