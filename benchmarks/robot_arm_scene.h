#pragma once
/// \file robot_arm_scene.h
/// The thesis' robot-arm set-up (Choi 2008, §5.4.2, Table 6), rebuilt: a 3-joint arm of 10
/// ellipsoids (base 0 fixed; links 1-3 on joint 1, 4-5 on joint 2, 6-9 on joint 3) sweeping past
/// an I-beam of three ellipsoids (flanges U top and W bottom, web V). Each joint turns by theta(t)
/// with tan(theta/2) linear in t, so a joint's rotation is rational of degree 2 and a link on joint
/// j moves with degree 2j (the composition of the joints before it). 30 (obstacle, link) pairs.
/// Shared by bench_ccd.cpp and `fcl_quadric bench` (experiment arm); no FCL here.

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "fcl_quadric/algebra/polynomial.h"
#include "fcl_quadric/algebra/polynomial_matrix.h"
#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fcl_quadric/continuous/motion_matrix.h"
#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {
namespace bench {

/// Homogeneous rotation about axis (2 = z, 1 = y) by theta(t) with tan(theta/2) = s(t) linear in t:
/// [[(1 + s^2) R, 0], [0, 1 + s^2]], entries of degree 2.
inline PolynomialMatrix4 armJointRotation(int axis, double theta0, double theta1) {
  const double s0 = std::tan(0.5 * theta0), s1 = std::tan(0.5 * theta1);
  const Polynomial s{s0, s1 - s0};
  const Polynomial ss = s * s, one{1.0};
  const Polynomial c = one - ss, w = one + ss, sn = 2.0 * s;
  PolynomialMatrix4 H;
  if (axis == 2) {
    H(0, 0) = c;
    H(0, 1) = -sn;
    H(1, 0) = sn;
    H(1, 1) = c;
    H(2, 2) = w;
  } else {
    H(0, 0) = c;
    H(0, 2) = sn;
    H(2, 0) = -sn;
    H(2, 2) = c;
    H(1, 1) = w;
  }
  H(3, 3) = w;
  return H;
}

inline PolynomialMatrix4 armTranslation(const Eigen::Vector3d& d) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.block<3, 1>(0, 3) = d;
  return PolynomialMatrix4(T);
}

/// One (obstacle, link) pair of the set-up.
struct ArmScenePair {
  std::string name;  ///< obstacle letter and link number, e.g. "W-6"
  int link = 0;
  int motion_degree = 0;  ///< degree of the link's motion in t (0, 2, 4 or 6)
  MovingEllipsoid obstacle{Ellipsoid::sphere(1.0, Eigen::Vector3d::Zero()), PiecewiseMotion()};
  MovingEllipsoid link_e{Ellipsoid::sphere(1.0, Eigen::Vector3d::Zero()), PiecewiseMotion()};
};

/// The 30 pairs, obstacle-major (U-0 ... U-9, V-0 ..., W-9).
inline std::vector<ArmScenePair> makeArmScene() {
  // Joint 1: yaw about z at the base; joint 2: shoulder pitch about y, 0.7 m up; joint 3: elbow
  // pitch about y, 0.6 m along the upper arm. Positive pitch turns the arm down.
  const PolynomialMatrix4 J1 = armJointRotation(2, -1.1, 1.1);
  const PolynomialMatrix4 J2 = J1 * armTranslation({0.0, 0.0, 0.7}) * armJointRotation(1, -0.1, 0.35);
  const PolynomialMatrix4 J3 = J2 * armTranslation({0.6, 0.0, 0.0}) * armJointRotation(1, 0.2, 0.9);
  struct Link {
    int joint;
    Eigen::Vector3d radii, centre;
  };
  const Link links[10] = {
      {0, {0.25, 0.25, 0.15}, {0.0, 0.0, 0.15}},   // 0 base
      {1, {0.15, 0.15, 0.12}, {0.0, 0.0, 0.40}},   // 1 turret
      {1, {0.12, 0.18, 0.10}, {0.0, 0.0, 0.62}},   // 2 shoulder housing
      {1, {0.06, 0.06, 0.10}, {-0.12, 0.0, 0.7}},  // 3 counterweight
      {2, {0.30, 0.08, 0.08}, {0.30, 0.0, 0.0}},   // 4 upper arm
      {2, {0.09, 0.10, 0.09}, {0.60, 0.0, 0.0}},   // 5 elbow
      {3, {0.25, 0.06, 0.06}, {0.25, 0.0, 0.0}},   // 6 forearm
      {3, {0.06, 0.06, 0.06}, {0.52, 0.0, 0.0}},   // 7 wrist
      {3, {0.07, 0.02, 0.03}, {0.63, 0.04, 0.0}},  // 8 finger
      {3, {0.07, 0.02, 0.03}, {0.63, -0.04, 0.0}}  // 9 finger
  };
  const PolynomialMatrix4 joint_motion[4] = {PolynomialMatrix4(Eigen::Matrix4d::Identity()), J1, J2, J3};
  // The I-beam obstacle in front of the arm: flanges U (top), W (bottom), web V.
  const Eigen::Vector3d beam(1.0, 0.1, 0.0);
  const struct {
    const char* name;
    Eigen::Vector3d radii, centre;
  } obstacles[3] = {{"U", {0.12, 0.35, 0.06}, beam + Eigen::Vector3d(0, 0, 1.05)},
                    {"V", {0.06, 0.06, 0.45}, beam + Eigen::Vector3d(0, 0, 0.55)},
                    {"W", {0.12, 0.35, 0.06}, beam + Eigen::Vector3d(0, 0, 0.1)}};
  std::vector<ArmScenePair> pairs;
  for (const auto& o : obstacles) {
    for (int k = 0; k < 10; ++k) {
      ArmScenePair p;
      p.name = std::string(o.name) + "-" + std::to_string(k);
      p.link = k;
      p.motion_degree = 2 * links[k].joint;
      p.obstacle = MovingEllipsoid{Ellipsoid(o.radii, Eigen::Matrix3d::Identity(), o.centre),
                                   PiecewiseMotion(MotionMatrix::constant(Eigen::Matrix3d::Identity(),
                                                                          Eigen::Vector3d::Zero()))};
      p.link_e = MovingEllipsoid{Ellipsoid(links[k].radii, Eigen::Matrix3d::Identity(), links[k].centre),
                                 PiecewiseMotion(MotionMatrix::fromPolynomialMatrix(joint_motion[links[k].joint]))};
      pairs.push_back(std::move(p));
    }
  }
  return pairs;
}

/// The CCD options of the set-up: every collision interval, culling off (thesis Table 6 times the
/// whole solve).
inline CcdOptions armCcdOptions() {
  CcdOptions o;
  o.all_intervals = true;
  o.culling = false;
  return o;
}

}  // namespace bench
}  // namespace fcl_quadric
