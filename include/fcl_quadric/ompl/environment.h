#pragma once
/// \file environment.h
/// The static environment of the OMPL layer: any FCL collision geometries (boxes, meshes,
/// ellipsoids, spheres, planes, capsules, cylinders, an fcl::OcTree built from an octomap) at
/// fixed world poses, held by an FCL broad-phase manager (fcl::DynamicAABBTreeCollisionManager).
/// Queries go through fcl_quadric's front doors (collision.h, distance.h), so ellipsoid robot
/// bodies are answered by the exact QuadricSolver against every shape it supports (ellipsoid,
/// sphere, box and OcTree leaves, triangle meshes, plane, half-space, capsule, cylinder, cone).
/// Composite quadric models (quadric_shapes.h) are collision-checked exactly by the region engine;
/// their distance term against ellipsoid / convex bodies is a certified lower bound
/// (fcl_quadric::distanceLowerBound, distance.h).
/// No OMPL types here.
///
/// Not thread-safe to modify; const queries may run concurrently (the manager is read-only).

#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/collision_geometry.h>
#include <fcl/narrowphase/collision_object.h>

namespace octomap {
class OcTree;
}

namespace fcl_quadric {
namespace planning {

class Environment {
 public:
  Environment();
  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;

  /// Adds an obstacle at `pose`. \throws std::invalid_argument for a null geometry, a pose that
  /// is not finite or not rigid, a shape parameter that is not finite or not positive (named), an
  /// unfinished BVH mesh, or an unsupported geometry (fcl::TriangleP, which FCL 0.7 never finds
  /// in contact with most shapes: use a one-triangle BVH mesh).
  void add(std::shared_ptr<fcl::CollisionGeometry<double>> geometry,
           const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity());
  /// How addOcTree registers an octomap.
  enum class OcTreeMode {
    /// The occupied cells (FCL's occupancy test, fcl::OcTree::toBoxes) split into finest-level
    /// voxels and greedily merged into maximal axis-aligned boxes (x, then y, then z runs): the
    /// same solid as the occupied cells, so the same collisions and distances, with far fewer
    /// objects (a one-voxel wall with a window becomes a handful of boxes). Pruned leaves wider
    /// than 16 voxels are kept as one box each (not split).
    MergedBoxes,
    /// One fcl::Box per occupied leaf.
    LeafBoxes,
    /// One fcl::OcTree object. FCL's OcTree-shape distance recursion visits children in a fixed
    /// order and runs the exact leaf distance on far more leaves: slow for the advancement.
    WholeTree,
  };
  /// Adds the occupied cells of an octomap at `pose`; returns the number of objects added.
  /// \throws std::invalid_argument for a null tree or a bad pose.
  std::size_t addOcTree(std::shared_ptr<const octomap::OcTree> tree,
                        const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity(),
                        OcTreeMode mode = OcTreeMode::MergedBoxes);

  std::size_t size() const { return objects_.size(); }
  const fcl::BroadPhaseCollisionManager<double>& manager() const { return *manager_; }
  const std::vector<std::shared_ptr<fcl::CollisionObject<double>>>& objects() const { return objects_; }

 private:
  void registerObject(std::shared_ptr<fcl::CollisionGeometry<double>> geometry, const Eigen::Isometry3d& pose);
  std::unique_ptr<fcl::DynamicAABBTreeCollisionManager<double>> manager_;
  std::vector<std::shared_ptr<fcl::CollisionObject<double>>> objects_;
};

}  // namespace planning
}  // namespace fcl_quadric
