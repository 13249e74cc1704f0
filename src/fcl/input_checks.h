#pragma once
// Private: argument checks of the FCL front doors (fcl_quadric::collide / distance). Each throws
// std::invalid_argument with a message naming the function and the argument.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include <fcl/common/types.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>
#include <fcl/narrowphase/collision_object.h>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace detail {

template <typename S, typename BV>
void checkMeshModel(const fcl::CollisionGeometry<S>* g, const char* where, const char* which) {
  const auto& m = static_cast<const fcl::BVHModel<BV>&>(*g);
  const bool built = m.build_state == fcl::BVH_BUILD_STATE_PROCESSED || m.build_state == fcl::BVH_BUILD_STATE_UPDATED;
  if (built && m.getModelType() == fcl::BVH_MODEL_TRIANGLES && m.num_tris > 0) return;
  std::ostringstream os;
  os << where << ": " << which << " is a BVH model that is not a finished triangle mesh (" << m.num_tris
     << " triangles, model type " << int(m.getModelType()) << ", build state " << int(m.build_state)
     << "): FCL's traversal would read past it; add triangles and call endModel()";
  throw std::invalid_argument(os.str());
}

/// A null geometry, or a BVH model that is empty, unfinished (no endModel()) or a point cloud:
/// FCL's traversals read its missing BV tree and crash (an audit found SIGSEGV in collide and
/// distance for all three, as with stock fcl::collide; docs/reliability.md finding 34).
template <typename S>
void checkGeometry(const fcl::CollisionGeometry<S>* g, const char* where, const char* which) {
  if (g == nullptr) throw std::invalid_argument(std::string(where) + ": " + which + " is a null collision geometry");
  if (g->getObjectType() != fcl::OT_BVH) return;
  switch (g->getNodeType()) {
    case fcl::BV_AABB: return checkMeshModel<S, fcl::AABB<S>>(g, where, which);
    case fcl::BV_OBB: return checkMeshModel<S, fcl::OBB<S>>(g, where, which);
    case fcl::BV_RSS: return checkMeshModel<S, fcl::RSS<S>>(g, where, which);
    case fcl::BV_kIOS: return checkMeshModel<S, fcl::kIOS<S>>(g, where, which);
    case fcl::BV_OBBRSS: return checkMeshModel<S, fcl::OBBRSS<S>>(g, where, which);
    case fcl::BV_KDOP16: return checkMeshModel<S, fcl::KDOP<S, 16>>(g, where, which);
    case fcl::BV_KDOP18: return checkMeshModel<S, fcl::KDOP<S, 18>>(g, where, which);
    case fcl::BV_KDOP24: return checkMeshModel<S, fcl::KDOP<S, 24>>(g, where, which);
    default: return;
  }
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

/// Whether p passes checkPosition (ellipsoid.h): finite and within +-kMaxLength. std::isfinite
/// first: an ordered comparison with NaN would raise FE_INVALID.
inline bool isPosition(const Eigen::Vector3d& p) {
  for (int i = 0; i < 3; ++i)
    if (!(std::isfinite(p[i]) && std::fabs(p[i]) <= tolerance::kMaxLength)) return false;
  return true;
}

/// Both translations within +-kMaxLength (tolerances.h), as the quadric shapes' front doors
/// require: for an ellipsoid or a sphere against a mesh or an OcTree, collide used to return 0
/// for a mesh posed at x = 1e200 (its triangles were never reached) while distance threw for its
/// first triangle (docs/reliability.md finding 34 (4)); both now throw here, naming the pose.
/// (The message is built only for a translation out of range: this runs once per query.)
inline void checkTranslations(const fcl::Transform3<double>& tf1, const fcl::Transform3<double>& tf2, const char* where) {
  if (!isPosition(tf1.translation()))
    checkPosition(tf1.translation(), (std::string(where) + ": the translation of tf1").c_str());
  if (!isPosition(tf2.translation()))
    checkPosition(tf2.translation(), (std::string(where) + ": the translation of tf2").c_str());
}

/// Whether a pose passes checkRotation and checkPosition (ellipsoid.h). The front doors test this
/// first and build those checks' messages only when it fails (building them per query cost 8% of
/// a cone-sphere collide, session 43).
inline bool isRigidPose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) { return isPosition(p) && isRotation(R); }

template <typename S>
void checkObject(const fcl::CollisionObject<S>* o, const char* where, const char* which) {
  if (o == nullptr) throw std::invalid_argument(std::string(where) + ": " + which + " is a null collision object");
  if (!o->collisionGeometry())
    throw std::invalid_argument(std::string(where) + ": " + which + " has no collision geometry (null)");
}

}  // namespace detail
}  // namespace fcl_quadric
