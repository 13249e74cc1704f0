#pragma once
/// \file boxing_scene.h
/// The thesis' boxing set-up (Choi 2008, §5.4.1, Table 5), rebuilt synthetically: two characters
/// of 20 ellipsoids each (head, jaw, neck, chest, abdomen, pelvis, shoulders, upper arms, forearms,
/// gloves, thighs, shins, feet; radii 0.04-0.2 m), animated procedurally with fast periodic jabs,
/// torso twist and lean, sway, bobbing and a slow approach/retreat (seed kBoxingSeed draws each
/// character's periods and phases). Shared by bench_ccd.cpp and `fcl_quadric bench` (experiment
/// boxing); no FCL here.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {
namespace bench {

constexpr std::uint64_t kBoxingSeed = 2008;
constexpr int kParts = 20;

inline constexpr const char* kPartNames[kParts] = {"head",       "jaw",        "neck",     "chest",     "abdomen",
                                        "pelvis",     "shoulder_l", "shoulder_r", "upperarm_l", "upperarm_r",
                                        "forearm_l",  "forearm_r",  "glove_l",  "glove_r",   "thigh_l",
                                        "thigh_r",    "shin_l",     "shin_r",   "foot_l",    "foot_r"};

/// Radii of each part, long axis first: the part's body x axis runs along its bone.
inline const std::array<Eigen::Vector3d, kParts>& partRadii() {
  static const std::array<Eigen::Vector3d, kParts> r = {
      Eigen::Vector3d(0.10, 0.085, 0.12), Eigen::Vector3d(0.06, 0.06, 0.045), Eigen::Vector3d(0.055, 0.055, 0.07),
      Eigen::Vector3d(0.13, 0.19, 0.15),  Eigen::Vector3d(0.11, 0.15, 0.10),  Eigen::Vector3d(0.12, 0.17, 0.10),
      Eigen::Vector3d(0.07, 0.07, 0.06),  Eigen::Vector3d(0.07, 0.07, 0.06),  Eigen::Vector3d(0.15, 0.05, 0.05),
      Eigen::Vector3d(0.15, 0.05, 0.05),  Eigen::Vector3d(0.14, 0.045, 0.045), Eigen::Vector3d(0.14, 0.045, 0.045),
      Eigen::Vector3d(0.07, 0.06, 0.06),  Eigen::Vector3d(0.07, 0.06, 0.06),  Eigen::Vector3d(0.20, 0.08, 0.08),
      Eigen::Vector3d(0.20, 0.08, 0.08),  Eigen::Vector3d(0.20, 0.06, 0.06),  Eigen::Vector3d(0.20, 0.06, 0.06),
      Eigen::Vector3d(0.12, 0.05, 0.04),  Eigen::Vector3d(0.12, 0.05, 0.04)};
  return r;
}

/// Periods (frames) and phases of one character's motions, drawn from the seed.
struct Character {
  double side = 1.0;  ///< -1: stands at -x facing +x; +1: stands at +x facing -x
  double punch_period[2], punch_phase[2];
  double twist_phase, sway_period, sway_phase, bob_period, bob_phase, step_period, step_phase;
};

inline Character drawCharacter(std::mt19937_64& rng, double side) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Character c;
  c.side = side;
  for (int k = 0; k < 2; ++k) {
    c.punch_period[k] = 26.0 + 14.0 * u(rng);  // a jab out and back in about 9-14 frames
    c.punch_phase[k] = u(rng);
  }
  c.twist_phase = u(rng);
  c.sway_period = 40.0 + 30.0 * u(rng);
  c.sway_phase = u(rng);
  c.bob_period = 16.0 + 8.0 * u(rng);
  c.bob_phase = u(rng);
  c.step_period = 30.0 + 20.0 * u(rng);
  c.step_phase = u(rng);
  return c;
}

constexpr double kTwoPi = 6.283185307179586;

/// Jab extension in [0, 1]: out and back during the first 35 % of each period, smooth (C^1).
inline double jab(double frame, double period, double phase, int* cycle) {
  const double x = frame / period + phase;
  *cycle = static_cast<int>(std::floor(x));
  const double f = x - std::floor(x);
  if (f >= 0.35) return 0.0;
  const double s = std::sin(M_PI * f / 0.35);
  return s * s;
}

/// Rotation taking the x axis to direction d (shortest arc; d never points along -x here). This is
/// Eigen's Quaternion::FromTwoVectors(UnitX, d / |d|), the same operations for d away from -x;
/// written out because FromTwoVectors instantiates a JacobiSVD for its antiparallel branch, about
/// 7 s of gcc in every file that includes this header (docs/reliability.md section 1, session 50).
/// Within 1e-12 of -x (Eigen's threshold for that branch) it turns by pi about an axis orthogonal
/// to d instead.
inline Eigen::Matrix3d alongBone(const Eigen::Vector3d& d) {
  const Eigen::Vector3d v0 = Eigen::Vector3d::UnitX().normalized();
  const Eigen::Vector3d v1 = d.normalized().normalized();
  const double c = v1.dot(v0);
  Eigen::Quaterniond q;
  if (c < -1.0 + 1e-12) {
    q.w() = 0.0;
    q.vec() = v1.unitOrthogonal();
  } else {
    const double s = std::sqrt((1.0 + c) * 2.0);
    q.vec() = v0.cross(v1) * (1.0 / s);
    q.w() = s * 0.5;
  }
  return q.toRotationMatrix();
}

inline Eigen::Isometry3d pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

/// Distance between the two characters' pelvis centres at a frame: 0.72-0.98 m, period 170 frames.
inline double separation(double frame) { return 0.85 + 0.13 * std::sin(kTwoPi * frame / 170.0 + 0.7); }

/// World poses of the 20 parts of a character at a (fractional) frame.
inline std::array<Eigen::Isometry3d, kParts> characterPoses(const Character& c, double frame) {
  std::array<Eigen::Isometry3d, kParts> X;
  int cycle[2];
  const double e[2] = {jab(frame, c.punch_period[0], c.punch_phase[0], &cycle[0]),
                       jab(frame, c.punch_period[1], c.punch_phase[1], &cycle[1])};
  // Upper body: twist toward the punching arm, lean forward with the punch, sway and bob.
  const double twist = 0.35 * (e[1] - e[0]) + 0.08 * std::sin(kTwoPi * (frame / 60.0 + c.twist_phase));
  const double lean = 0.08 + 0.12 * std::max(e[0], e[1]);
  const double sway = 0.07 * std::sin(kTwoPi * (frame / c.sway_period + c.sway_phase));
  const double bob = 0.025 * std::sin(kTwoPi * (frame / c.bob_period + c.bob_phase));
  // Character frame: x forward, y left, z up, pelvis centre above the origin.
  Eigen::Isometry3d world = Eigen::Isometry3d::Identity();
  world.translate(Eigen::Vector3d(c.side * 0.5 * separation(frame), 0.0, bob));
  if (c.side > 0) world.rotate(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d hip_centre(0.0, 0.0, 0.95);
  Eigen::Isometry3d upper = Eigen::Isometry3d::Identity();
  upper.translate(hip_centre + Eigen::Vector3d(0.0, sway, 0.0));
  upper.rotate(Eigen::AngleAxisd(twist, Eigen::Vector3d::UnitZ()));
  upper.rotate(Eigen::AngleAxisd(lean, Eigen::Vector3d::UnitY()));
  upper.translate(-hip_centre);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  auto place = [&](int part, const Eigen::Isometry3d& frame_of, const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
    X[part] = world * frame_of * pose(R, p);
  };
  const Eigen::Isometry3d id = Eigen::Isometry3d::Identity();
  place(0, upper, I, Eigen::Vector3d(0.01, 0.0, 1.66));
  place(1, upper, I, Eigen::Vector3d(0.05, 0.0, 1.58));
  place(2, upper, alongBone(Eigen::Vector3d(0, 0, 1)), Eigen::Vector3d(0.0, 0.0, 1.51));
  place(3, upper, I, Eigen::Vector3d(0.0, 0.0, 1.32));
  place(4, upper, I, Eigen::Vector3d(0.0, 0.0, 1.12));
  place(5, id, I, Eigen::Vector3d(0.0, 0.0, 0.95));
  for (int k = 0; k < 2; ++k) {  // k = 0 left, 1 right
    const double y = k == 0 ? 1.0 : -1.0;
    const Eigen::Vector3d shoulder(0.0, y * 0.22, 1.43);
    place(6 + k, upper, I, shoulder + Eigen::Vector3d(0.0, -y * 0.02, 0.0));
    // Guard: upper arm down and forward, forearm up to the chin. Jab: both straight ahead, at
    // the head on even cycles and at the body on odd ones.
    const double aim_z = (cycle[k] % 2 == 0) ? 0.12 : -0.12;
    const Eigen::Vector3d u_guard(0.35, -y * 0.2, -0.9), f_guard(0.5, -y * 0.25, 0.85);
    const Eigen::Vector3d punch(1.0, -y * 0.12, aim_z);
    const Eigen::Vector3d u = ((1 - e[k]) * u_guard.normalized() + e[k] * punch.normalized()).normalized();
    const Eigen::Vector3d f = ((1 - e[k]) * f_guard.normalized() + e[k] * punch.normalized()).normalized();
    const Eigen::Vector3d elbow = shoulder + 0.30 * u, wrist = elbow + 0.28 * f;
    place(8 + k, upper, alongBone(u), shoulder + 0.15 * u);
    place(10 + k, upper, alongBone(f), elbow + 0.14 * f);
    place(12 + k, upper, alongBone(f), wrist + 0.05 * f);
    // Legs: hips swing fore and aft out of phase, knees bend with the bob.
    const double swing = 0.18 * std::sin(kTwoPi * (frame / c.step_period + c.step_phase) + k * M_PI);
    const double knee = 0.25 + 0.1 * std::sin(kTwoPi * (frame / c.bob_period + c.bob_phase));
    const Eigen::Vector3d hip(0.0, y * 0.1, 0.9);
    const Eigen::Vector3d dt(std::sin(swing), 0.0, -std::cos(swing));
    const Eigen::Vector3d ds(std::sin(swing - knee), 0.0, -std::cos(swing - knee));
    const Eigen::Vector3d knee_p = hip + 0.42 * dt, ankle = knee_p + 0.42 * ds;
    place(14 + k, id, alongBone(dt), hip + 0.21 * dt);
    place(16 + k, id, alongBone(ds), knee_p + 0.21 * ds);
    place(18 + k, id, I, ankle + Eigen::Vector3d(0.06, 0.0, -0.04));
  }
  return X;
}

struct BoxingScene {
  int frames = 0;  ///< motion intervals; frames + 1 poses
  std::vector<std::array<Eigen::Isometry3d, kParts>> poses[2];
  std::vector<Ellipsoid> bodies;  ///< body-frame ellipsoids (centred at the origin, axes aligned)
};

inline BoxingScene makeBoxing(std::size_t frames) {
  BoxingScene s;
  s.frames = static_cast<int>(frames);
  std::mt19937_64 rng(kBoxingSeed);
  const Character ch[2] = {drawCharacter(rng, -1.0), drawCharacter(rng, 1.0)};
  for (int c = 0; c < 2; ++c)
    for (int k = 0; k <= s.frames; ++k) s.poses[c].push_back(characterPoses(ch[c], k));
  for (int p = 0; p < kParts; ++p)
    s.bodies.emplace_back(partRadii()[p], Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  return s;
}

}  // namespace bench
}  // namespace fcl_quadric
