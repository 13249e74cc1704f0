// Built against an installed fcl_quadric by test/install/run.sh: uses both exported targets.
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl_quadric/fcl/collision.h>
#include <fcl_quadric/geometry/ellipsoid_separation.h>
#include <fcl_quadric/version.h>

#include <cstdio>
#include <memory>

int main() {
  using fcl_quadric::Ellipsoid;
  const Ellipsoid a = Ellipsoid::sphere(1.0, {0, 0, 0});
  const Ellipsoid b = Ellipsoid::sphere(1.0, {3, 0, 0});
  bool ok = !fcl_quadric::ellipsoidsCollide(a, b) &&
            fcl_quadric::ellipsoidsCollide(a, Ellipsoid::sphere(1.0, {1.5, 0, 0}));
  // The FCL front door on two fcl::Ellipsoid objects.
  auto e1 = std::make_shared<fcl::Ellipsoidd>(1.0, 2.0, 3.0);
  auto e2 = std::make_shared<fcl::Ellipsoidd>(1.0, 1.0, 1.0);
  fcl::Transform3d t1 = fcl::Transform3d::Identity(), t2 = fcl::Transform3d::Identity();
  t2.translation() << 1.9, 0, 0;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl_quadric::collide(e1.get(), t1, e2.get(), t2, request, result);
  ok = ok && result.isCollision();
  std::printf("fcl_quadric %s downstream: %s\n", FCL_QUADRIC_VERSION_STRING, ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
