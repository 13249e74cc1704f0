#pragma once
/// Small FCL fixtures shared by the fcl and ompl test suites: a pose from (R, p), and a thin
/// triangular pole (a prism along z) as triangles and as a BVH mesh.
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

namespace fcl_quadric {
namespace test {

inline fcl::Transform3d pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = R;
  tf.translation() = p;
  return tf;
}

/// The three vertices of the pole's cross-section: radius r about the z axis, at 0, 120, 240 deg.
inline std::array<Eigen::Vector3d, 3> poleRim(double r) {
  std::array<Eigen::Vector3d, 3> rim;
  for (int k = 0; k < 3; ++k) rim[k] = r * Eigen::Vector3d(std::cos(2 * M_PI * k / 3), std::sin(2 * M_PI * k / 3), 0);
  return rim;
}

/// The pole's side: two triangles per face of the prism rim x [-h, h].
inline std::vector<std::array<Eigen::Vector3d, 3>> poleTriangles(double r, double h) {
  const std::array<Eigen::Vector3d, 3> rim = poleRim(r);
  const Eigen::Vector3d up(0, 0, h);
  std::vector<std::array<Eigen::Vector3d, 3>> tris;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d a = rim[k], b = rim[(k + 1) % 3];
    tris.push_back({a - up, b - up, b + up});
    tris.push_back({a - up, b + up, a + up});
  }
  return tris;
}

inline std::shared_ptr<fcl::BVHModel<fcl::OBBRSS<double>>> meshOf(const std::vector<std::array<Eigen::Vector3d, 3>>& tris) {
  auto m = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  m->beginModel();
  for (const auto& t : tris) m->addTriangle(t[0], t[1], t[2]);
  m->endModel();
  return m;
}

}  // namespace test
}  // namespace fcl_quadric
