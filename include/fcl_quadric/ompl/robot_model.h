#pragma once
/// \file robot_model.h
/// A robot for the OMPL layer (docs/ompl.md): a rigid body that moves in SE(2) or SE(3), or a
/// serial kinematic chain of revolute / prismatic joints on a fixed base. Each link carries FCL
/// collision geometries (ellipsoids and spheres are answered exactly by the QuadricSolver; boxes,
/// cylinders, cones, capsules and quadric shapes advance on certified lower bounds,
/// fcl_quadric::distanceLowerBound; see docs/ompl.md "Certification"). No OMPL types here.
///
/// Frames. Link 0 is the base. For a Planar or Free base its world pose is the configuration's
/// `base` (Planar: a rotation about z and a translation in the xy-plane). For a Fixed base it is
/// fixedBasePose() and the configuration holds one value per joint: joint i drives link i + 1,
/// whose frame is  X_link(i+1) = X_link(i) * origin_i * J_i(q_i)  with J_i the rotation by q_i
/// (radians) about the unit `axis` (revolute) or the translation q_i * axis (prismatic), both
/// expressed in the joint frame `origin_i`. A body sits at X_link * offset.
///
/// Example (a two-link planar arm of ellipsoids):
///   RobotModel arm(RobotModel::Base::Fixed);
///   arm.addBody(0, std::make_shared<fcl::Ellipsoidd>(0.1, 0.1, 0.1));
///   std::size_t l1 = arm.addJoint("shoulder", JointType::Revolute, Eigen::Isometry3d::Identity(),
///                                 Eigen::Vector3d::UnitZ(), -M_PI, M_PI);
///   arm.addBody(l1, std::make_shared<fcl::Ellipsoidd>(0.5, 0.08, 0.08), translation(0.5, 0, 0));
///   std::size_t l2 = arm.addJoint("elbow", JointType::Revolute, translation(1, 0, 0), ...);
/// examples/ompl_arm.json and examples/ompl_drone.json show the JSON form (robotModelFromJson).

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <fcl/geometry/collision_geometry.h>

namespace fcl_quadric {
namespace planning {

enum class JointType { Revolute, Prismatic };

struct Joint {
  std::string name;
  JointType type = JointType::Revolute;
  /// Parent link frame -> joint frame at q = 0.
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  /// Unit axis in the joint frame.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double lower = 0.0;
  double upper = 0.0;
};

struct Body {
  std::shared_ptr<fcl::CollisionGeometry<double>> geometry;
  /// Link frame -> geometry frame.
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
  /// A ball (centre in the link frame, radius) containing the posed geometry; computed by addBody
  /// (ellipsoid / sphere: centre = offset origin, radius = largest radius; other shapes: FCL's
  /// local AABB centre and radius).
  Eigen::Vector3d ball_centre = Eigen::Vector3d::Zero();
  double ball_radius = 0.0;
};

/// A configuration: the base pose (Planar / Free base) and the joint values (Fixed base).
struct Configuration {
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  std::vector<double> joints;
};

class RobotModel {
 public:
  enum class Base {
    Fixed,   ///< base at fixedBasePose(); the configuration is the joint vector (OMPL RealVector)
    Planar,  ///< rigid body in SE(2): x, y, yaw about z (OMPL SE2StateSpace)
    Free,    ///< rigid body in SE(3) (OMPL SE3StateSpace or RationalSE3StateSpace)
  };

  explicit RobotModel(Base base = Base::Free);

  Base base() const { return base_; }
  /// World pose of link 0 for a Fixed base. \throws std::invalid_argument if not finite or not rigid.
  void setFixedBasePose(const Eigen::Isometry3d& pose);
  const Eigen::Isometry3d& fixedBasePose() const { return fixed_base_pose_; }

  /// Adds a joint whose parent is the last link and returns the index of its new child link.
  /// \throws std::invalid_argument for a robot whose base is not Fixed, an empty or duplicate
  ///         name, a non-finite or non-rigid origin, a zero or non-finite axis (it is normalised),
  ///         or limits that are not finite with lower <= upper; the message names the value.
  std::size_t addJoint(const std::string& name, JointType type, const Eigen::Isometry3d& origin,
                       const Eigen::Vector3d& axis, double lower, double upper);

  /// Attaches a collision geometry to a link. An fcl::Sphere is stored as the fcl::Ellipsoid with
  /// equal radii (so that every pair with it takes the exact ellipsoid path of QuadricSolver).
  /// \throws std::invalid_argument for a link index out of range, a null geometry, a non-finite /
  /// non-rigid offset, a shape parameter that is not finite or not positive (the message names it),
  /// an unfinished BVH mesh, or an unsupported geometry (fcl::TriangleP: use a one-triangle mesh).
  void addBody(std::size_t link, std::shared_ptr<fcl::CollisionGeometry<double>> geometry,
               const Eigen::Isometry3d& offset = Eigen::Isometry3d::Identity());

  /// Excludes the link pair (a, b) from self-collision checking (adjacent links are always
  /// excluded). \throws std::invalid_argument for an index out of range or a == b.
  void allowCollision(std::size_t a, std::size_t b);

  std::size_t linkCount() const { return bodies_.size(); }
  std::size_t jointCount() const { return joints_.size(); }
  const Joint& joint(std::size_t i) const { return joints_.at(i); }
  const std::vector<Body>& bodies(std::size_t link) const { return bodies_.at(link); }
  /// The link pairs checked for self-collision: non-adjacent, not allowed, both with bodies.
  const std::vector<std::pair<std::size_t, std::size_t>>& selfCollisionPairs() const { return self_pairs_; }

  /// World pose of every link frame. \throws std::invalid_argument if the configuration has the
  /// wrong number of joint values or a non-finite entry.
  void linkPoses(const Configuration& q, std::vector<Eigen::Isometry3d>& poses) const;

  /// Upper bound, over all configurations within the joint limits, of the distance from the
  /// origin of joint j's frame (the point its rotation fixes) to the origin of `link`'s frame
  /// (link > j): the sum of |origin_i translation| + max(|lower_i|, |upper_i|) for prismatic
  /// joints i = j+1 .. link-1. The speed bound of a chain adds the body's reach
  /// |ball_centre| + ball_radius (docs/ompl.md). \throws std::invalid_argument unless j < link.
  double chainLength(std::size_t joint, std::size_t link) const;

  /// \throws std::invalid_argument if the robot has no body at all, or a Fixed base and no joint.
  void validate() const;

 private:
  void rebuildPairs();
  Base base_;
  Eigen::Isometry3d fixed_base_pose_ = Eigen::Isometry3d::Identity();
  std::vector<Joint> joints_;
  std::vector<std::vector<Body>> bodies_;  // per link
  std::vector<std::pair<std::size_t, std::size_t>> allowed_;
  std::vector<std::pair<std::size_t, std::size_t>> self_pairs_;
};

/// Reads a robot from JSON text (format in docs/ompl.md):
///   {"base": "fixed" | "planar" | "free",
///    "base_pose": {"translation": [x,y,z], "rpy": [r,p,y]},                (fixed only, optional)
///    "bodies": [{"link": 0, "shape": "ellipsoid", "radii": [a,b,c], "translation": [...], "rpy": [...]}],
///    "joints": [{"name": "j1", "type": "revolute" | "prismatic", "translation": [...], "rpy": [...],
///                "axis": [x,y,z], "limits": [lower, upper]}],
///    "allowed_collisions": [[a, b], ...]}
/// Shapes: "ellipsoid" (radii), "sphere" (radius), "box" (size), "capsule" / "cylinder"
/// (radius, length). \throws std::invalid_argument naming the JSON pointer of a bad value.
RobotModel robotModelFromJson(const std::string& json_text);

}  // namespace planning
}  // namespace fcl_quadric
