// Built against an installed fcl_quadric by test/install/run.sh.
#include <fcl_quadric/geometry/ellipsoid_separation.h>
#include <fcl_quadric/version.h>

#include <cstdio>

int main() {
  using fcl_quadric::Ellipsoid;
  const Ellipsoid a = Ellipsoid::sphere(1.0, {0, 0, 0});
  const Ellipsoid b = Ellipsoid::sphere(1.0, {3, 0, 0});
  const bool ok = !fcl_quadric::ellipsoidsCollide(a, b) &&
                  fcl_quadric::ellipsoidsCollide(a, Ellipsoid::sphere(1.0, {1.5, 0, 0}));
  std::printf("fcl_quadric %s downstream: %s\n", FCL_QUADRIC_VERSION_STRING, ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
