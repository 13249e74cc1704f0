#pragma once
// Private: argument checks of the FCL front doors (fcl_quadric::collide / distance). Each throws
// std::invalid_argument with a message naming the function and the argument.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include <fcl/common/types.h>
#include <fcl/narrowphase/collision_object.h>

namespace fcl_quadric {
namespace detail {

template <typename S>
void checkGeometry(const fcl::CollisionGeometry<S>* g, const char* where, const char* which) {
  if (g == nullptr) throw std::invalid_argument(std::string(where) + ": " + which + " is a null collision geometry");
}

template <typename S>
[[noreturn, gnu::cold, gnu::noinline]] void throwNonFinitePose(const fcl::Transform3<S>& tf, const char* where,
                                                              const char* which) {
  std::ostringstream os;
  os << where << ": transform " << which << " is not finite, [R | p] =\n" << tf.matrix().template topRows<3>();
  throw std::invalid_argument(os.str());
}

template <typename S>
void checkPose(const fcl::Transform3<S>& tf, const char* where, const char* which) {
  // std::isfinite raises no floating-point exception (the tests trap FE_INVALID). The message is
  // built out of line: this runs twice per front-door query.
  const auto& m = tf.matrix();
  bool finite = true;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) finite &= std::isfinite(m(r, c));
  if (!finite) throwNonFinitePose(tf, where, which);
}

/// The argument checks of the (geometry, pose) front doors, in the order o1, o2, tf1, tf2.
template <typename S>
void checkPosedPair(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                    const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2, const char* where) {
  checkGeometry(o1, where, "o1");
  checkGeometry(o2, where, "o2");
  checkPose(tf1, where, "tf1");
  checkPose(tf2, where, "tf2");
}

template <typename S>
void checkObject(const fcl::CollisionObject<S>* o, const char* where, const char* which) {
  if (o == nullptr) throw std::invalid_argument(std::string(where) + ": " + which + " is a null collision object");
  if (!o->collisionGeometry())
    throw std::invalid_argument(std::string(where) + ": " + which + " has no collision geometry (null)");
}

}  // namespace detail
}  // namespace fcl_quadric
