#pragma once
/// \file fcl_fallback.h
/// Pairs the exact library does not handle yet (anything with a box), computed by FCL itself.
/// All FCL template instantiation of the program lives in fcl_fallback.cpp (it is slow to compile).

#include "fcl_quadric/pair_report.h"
#include "fcl_quadric/scene.h"

namespace fcl_quadric {
namespace cli {

/// Collision and signed distance of two scene objects by FCL 0.7 (libccd GJK/MPR):
/// fcl::collide() decides `status` (Overlapping or Separated; FCL cannot certify touching) and
/// `collide`; fcl::distance() with signed distance and nearest points enabled gives
/// `signed_distance` and the witness points. The normal is the unit vector between the witness
/// points (from a to b), falling back to FCL's contact normal and then to the direction between
/// the object origins when the points coincide. `method` is PairMethod::Fcl.
PairReport fclPairReport(const SceneObject& a, const SceneObject& b);

}  // namespace cli
}  // namespace fcl_quadric
