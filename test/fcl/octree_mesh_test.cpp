// Exact leaves inside FCL's traversals: an fcl::OcTree (built from an octomap::OcTree written to
// and read back from a .bt / .ot file) and BVH triangle meshes against ellipsoids, through
// fcl_quadric::collide / distance and fcl::collide with &solver, compared with brute force over
// every occupied leaf box (classifyEllipsoidBox) or every triangle (classifyEllipsoidTriangle).
// The near-tangent poses touch exactly one leaf / triangle, so a traversal that did not reach the
// exact branch (stock libccd) gets them wrong.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include <fcl/config.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/utility.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#if FCL_HAVE_OCTOMAP
#include <fcl/geometry/octree/octree.h>
#include <octomap/OcTree.h>
#endif

#include "fcl/exact_pairs_support.h"
#include "fcl/fcl_test_support.h"
#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/quadric_solver.h"
#include "fcl_quadric/geometry/ellipsoid_polytope.h"

namespace fcl_quadric {
namespace octree_mesh_test {
namespace {

/// An ellipsoid outside the plane through x0 with outward normal u (pointing towards the
/// ellipsoid), tangent to it at x0, then moved along u by signed_gap times its support distance:
/// < 0 pushes it through the plane (overlap), > 0 lifts it off.
Ellipsoid tangentEllipsoid(std::mt19937_64& rng, const Eigen::Vector3d& x0, const Eigen::Vector3d& u,
                           double min_radius, double max_radius, double signed_gap) {
  std::uniform_real_distribution<double> r(min_radius, max_radius);
  const Ellipsoid at_origin(Eigen::Vector3d(r(rng), r(rng), r(rng)), test::randomRotation(rng), Eigen::Vector3d::Zero());
  const double h = at_origin.support(-u);  // support distance towards the plane
  return Ellipsoid(at_origin.radii(), at_origin.rotation(), x0 - at_origin.supportPoint(-u) + signed_gap * h * u);
}

fcl::CollisionObjectd ellipsoidObject(const Ellipsoid& e) {
  return fcl::CollisionObjectd(std::make_shared<fcl::Ellipsoidd>(e.radii()), test::poseOf(e));
}

struct Counts {
  std::size_t collide_any_wrong = 0, count_wrong = 0;
};

/// The results of the front door's own traversal and of FCL's traversal (same solver) are the
/// same: contacts in the same order, with the same objects and primitive indices, and, for a
/// contact request, the same points, normals and depths (FCL leaves a boolean contact's geometry
/// uninitialised).
void expectSameContacts(const fcl::CollisionResultd& ours, const fcl::CollisionResultd& theirs, bool enable_contact,
                        const std::string& where) {
  ASSERT_EQ(ours.numContacts(), theirs.numContacts()) << where;
  for (std::size_t k = 0; k < ours.numContacts(); ++k) {
    const fcl::Contactd& a = ours.getContact(k);
    const fcl::Contactd& b = theirs.getContact(k);
    EXPECT_EQ(a.o1, b.o1) << where;
    EXPECT_EQ(a.o2, b.o2) << where;
    EXPECT_EQ(a.b1, b.b1) << where << ", contact " << k;
    EXPECT_EQ(a.b2, b.b2) << where;
    if (!enable_contact) continue;
    EXPECT_EQ(a.pos, b.pos) << where;
    EXPECT_EQ(a.normal, b.normal) << where;
    EXPECT_EQ(a.penetration_depth, b.penetration_depth) << where;
  }
}

/// query(order) (order 0: environment first, 1: shape first) throws std::invalid_argument whose
/// message contains `needle`, in both orders.
template <typename Query>
void expectThrowsNamingInBothOrders(Query&& query, const std::string& needle) {
  for (int order = 0; order < 2; ++order) {
    try {
      query(order);
      ADD_FAILURE() << "no exception for a bad " << needle << ", order " << order;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }
}

/// fcl_quadric::collide of `environment` (posed tf_env) and `shape` (posed tf_shape), in both
/// argument orders, throws std::invalid_argument whose message contains `needle`.
void expectCollideThrowsNaming(const fcl::CollisionGeometryd* environment, const fcl::Transform3d& tf_env,
                               const fcl::CollisionGeometryd* shape, const fcl::Transform3d& tf_shape,
                               const std::string& needle) {
  expectThrowsNamingInBothOrders(
      [&](int order) {
        fcl::CollisionResultd r;
        if (order == 0) fcl_quadric::collide(environment, tf_env, shape, tf_shape, fcl::CollisionRequestd(), r);
        else fcl_quadric::collide(shape, tf_shape, environment, tf_env, fcl::CollisionRequestd(), r);
      },
      needle);
}

/// fcl_quadric::distance of `environment` and `shape`, in both argument orders, throws
/// std::invalid_argument whose message contains `needle`.
void expectDistanceThrowsNaming(const fcl::CollisionGeometryd* environment, const fcl::Transform3d& tf_env,
                                const fcl::CollisionGeometryd* shape, const fcl::Transform3d& tf_shape,
                                const std::string& needle) {
  expectThrowsNamingInBothOrders(
      [&](int order) {
        fcl::DistanceResultd r;
        if (order == 0) fcl_quadric::distance(environment, tf_env, shape, tf_shape, fcl::DistanceRequestd(), r);
        else fcl_quadric::distance(shape, tf_shape, environment, tf_env, fcl::DistanceRequestd(), r);
      },
      needle);
}

// =============================================================================================
// OcTree
// =============================================================================================
#if FCL_HAVE_OCTOMAP

/// One leaf box exactly as FCL's OcTreeSolver builds it: the root box of getRootBV() halved with
/// computeChildBV along the leaf's key bits, then constructBox(bv, tf_tree) (octree_solver-inl.h).
struct LeafBox {
  Eigen::Vector3d half;
  Eigen::Matrix3d R;
  Eigen::Vector3d p;
};

std::vector<LeafBox> occupiedLeafBoxes(const fcl::OcTreed& fcl_tree, const octomap::OcTree& tree,
                                       const fcl::Transform3d& tf_tree) {
  std::vector<LeafBox> boxes;
  const unsigned tree_depth = tree.getTreeDepth();
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    // FCL's predicate (fcl::OcTree::isNodeOccupied: log-odds >= the occupancy threshold), the
    // same call FCL's traversal makes.
    if (!fcl_tree.isNodeOccupied(&*it)) continue;
    fcl::AABBd bv = fcl_tree.getRootBV();
    const octomap::OcTreeKey key = it.getKey();
    for (unsigned level = 0; level < it.getDepth(); ++level) {
      const unsigned pos = 1u << (tree_depth - level - 1);
      const unsigned child = ((key[0] & pos) ? 1u : 0u) | ((key[1] & pos) ? 2u : 0u) | ((key[2] & pos) ? 4u : 0u);
      fcl::AABBd child_bv;
      fcl::computeChildBV(bv, child, child_bv);
      bv = child_bv;
    }
    fcl::Boxd box;
    fcl::Transform3d box_tf;
    fcl::constructBox(bv, tf_tree, box, box_tf);
    boxes.push_back(LeafBox{0.5 * box.side, box_tf.linear(), box_tf.translation()});
  }
  return boxes;
}

struct BruteForce {
  std::size_t colliding = 0;
  std::size_t first = 0;  ///< index of a colliding leaf
};

BruteForce bruteForceBoxes(const Ellipsoid& e, const std::vector<LeafBox>& boxes) {
  BruteForce b;
  const double reach = e.maxRadius();
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    const LeafBox& box = boxes[k];
    if ((box.p - e.center()).norm() > reach + box.half.norm() + 1e-9) continue;  // cannot touch
    if (classifyEllipsoidBox(e, box.half, box.R, box.p).status != Separation::Separated) {
      if (b.colliding == 0) b.first = k;
      ++b.colliding;
    }
  }
  return b;
}

/// The scene: a floor, two walls and a sphere shell, plus a block of free cells. Each occupied
/// voxel is updated once: as occupied (binary scene) or by a log-odds in [-0.5, 3] (graded).
void fillScene(octomap::OcTree& tree, std::mt19937_64& rng, bool graded_occupancy) {
  const double res = tree.getResolution();
  octomap::KeySet keys;
  auto occupy = [&](double x, double y, double z) {
    keys.insert(tree.coordToKey(octomap::point3d(float(x), float(y), float(z))));
  };
  for (double a = -1.0; a <= 1.0; a += 0.5 * res) {
    for (double b = -1.0; b <= 1.0; b += 0.5 * res) {
      occupy(a, b, 0.5 * res);                    // floor: voxels z in [0, res)
      if (b >= 0) occupy(1.0 + 0.5 * res, a, b);  // wall x = 1
      if (b >= 0) occupy(a, -1.0 - 0.5 * res, b);  // wall y = -1
    }
  }
  for (const Eigen::Vector3d& d : test::fibonacciSphere(3000)) {
    const Eigen::Vector3d x = Eigen::Vector3d(0.2, 0.3, 0.6) + 0.35 * d;
    occupy(x.x(), x.y(), x.z());
  }
  std::vector<octomap::OcTreeKey> ordered(keys.begin(), keys.end());
  std::sort(ordered.begin(), ordered.end(), [](const octomap::OcTreeKey& p, const octomap::OcTreeKey& q) {
    return std::lexicographical_compare(&p[0], &p[0] + 3, &q[0], &q[0] + 3);
  });
  std::uniform_real_distribution<float> grade(-0.5f, 3.0f);
  for (const octomap::OcTreeKey& k : ordered) {
    if (graded_occupancy) tree.updateNode(k, grade(rng));
    else tree.updateNode(k, true);
  }
  for (double x = -0.6; x <= 0.6; x += res)
    for (double y = -0.6; y <= 0.6; y += res) tree.updateNode(octomap::point3d(float(x), float(y), 1.3f), false);
}

std::string tempFile(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("fcl_quadric_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

/// The comparison: >= 200 ellipsoid poses (random, and near-tangent to one exposed leaf face),
/// boolean collide and the number of contacts (one per colliding leaf, as FCL counts them), both
/// argument orders, against brute force; stock FCL's answers on the near-tangent poses.
void compareOcTree(const std::shared_ptr<const octomap::OcTree>& tree, double occupancy_threshold, unsigned seed,
                   const char* what) {
  auto fcl_tree = std::make_shared<fcl::OcTreed>(tree);
  if (occupancy_threshold > 0) fcl_tree->setOccupancyThres(occupancy_threshold);
  const fcl::Transform3d tf_tree =
      test::makePose(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix(),
                     Eigen::Vector3d(0.3, -0.2, 0.1));
  const fcl::CollisionObjectd octree(fcl_tree, tf_tree);
  const std::vector<LeafBox> boxes = occupiedLeafBoxes(*fcl_tree, *tree, tf_tree);
  ASSERT_GT(boxes.size(), 500u);

  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(-1.2, 1.2), uz(-0.2, 1.3), f(-0.4, 0.4);
  struct Pose {
    Ellipsoid e;
    int expected;  // near-tangent: 1 / 0; random: -1
  };
  std::vector<Pose> poses;
  for (int i = 0; i < 150; ++i) {
    std::uniform_real_distribution<double> r(0.05, 0.4);
    const Eigen::Vector3d c = tf_tree * Eigen::Vector3d(ux(rng), ux(rng), uz(rng));
    poses.push_back(Pose{Ellipsoid(Eigen::Vector3d(r(rng), r(rng), r(rng)), test::randomRotation(rng), c), -1});
  }
  // Near-tangent: an occupied leaf, one of its faces (outward normal u), a point x0 inside that
  // face; kept only if the ellipsoid touches no other leaf, so collision hinges on that leaf.
  int near_in = 0, near_out = 0, attempts = 0;
  while ((near_in < 50 || near_out < 50) && attempts < 20000) {
    ++attempts;
    const LeafBox& box = boxes[rng() % boxes.size()];
    const int axis = static_cast<int>(rng() % 3);
    const double side = (rng() % 2) ? 1.0 : -1.0;
    const Eigen::Vector3d u = side * box.R.col(axis);
    Eigen::Vector3d s_local(f(rng) * 2 * box.half[0], f(rng) * 2 * box.half[1], f(rng) * 2 * box.half[2]);
    s_local[axis] = side * box.half[axis];
    const Eigen::Vector3d x0 = box.p + box.R * s_local;
    const bool inward = near_in < 50 && (near_out >= 50 || rng() % 2);
    const Ellipsoid e = tangentEllipsoid(rng, x0, u, 0.05, 0.3, inward ? -1e-8 : 1e-8);
    if (bruteForceBoxes(e, boxes).colliding != (inward ? 1u : 0u)) continue;  // touches other leaves
    // ... and the near-tangent leaf is the one that decides.
    if (inward && classifyEllipsoidBox(e, box.half, box.R, box.p).status == Separation::Separated) continue;
    if (!inward) {
      const Ellipsoid pushed(e.radii(), e.rotation(), e.center() - 2e-8 * (e.support(-u) + u.dot(e.center())) * u);
      if (bruteForceBoxes(pushed, boxes).colliding != 1u) continue;
    }
    poses.push_back(Pose{e, inward ? 1 : 0});
    (inward ? near_in : near_out)++;
  }
  ASSERT_EQ(near_in, 50);
  ASSERT_EQ(near_out, 50);

  const QuadricSolverd solver;
  int wrong = 0, stock_wrong = 0, stock_wrong_in = 0, total_contacts = 0, colliding_poses = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Pose& pose = poses[i];
    const BruteForce truth = bruteForceBoxes(pose.e, boxes);
    if (pose.expected >= 0) {
      ASSERT_EQ(truth.colliding, static_cast<std::size_t>(pose.expected)) << "pose " << i;
    }
    const fcl::CollisionObjectd oe = ellipsoidObject(pose.e);
    colliding_poses += truth.colliding > 0;
    total_contacts += static_cast<int>(truth.colliding);
    for (int order = 0; order < 2; ++order) {
      const fcl::CollisionObjectd& a = order ? oe : octree;
      const fcl::CollisionObjectd& b = order ? octree : oe;
      fcl::CollisionResultd boolean, counted_boolean, with_contacts, via_fcl;
      fcl_quadric::collide(&a, &b, fcl::CollisionRequestd(), boolean);
      fcl_quadric::collide(&a, &b, fcl::CollisionRequestd(100000, false), counted_boolean);
      fcl_quadric::collide(&a, &b, fcl::CollisionRequestd(100000, true), with_contacts);
      fcl::collide(&a, &b, &solver, fcl::CollisionRequestd(100000, true), via_fcl);
      wrong += boolean.isCollision() != (truth.colliding > 0);
      EXPECT_EQ(boolean.isCollision(), truth.colliding > 0) << what << " pose " << i << " order " << order;
      EXPECT_EQ(counted_boolean.numContacts(), truth.colliding) << what << " pose " << i;
      EXPECT_EQ(with_contacts.numContacts(), truth.colliding) << what << " pose " << i;
      EXPECT_EQ(via_fcl.numContacts(), truth.colliding) << what << " pose " << i;
      for (std::size_t k = 0; k < with_contacts.numContacts(); ++k) {
        const fcl::Contactd& c = with_contacts.getContact(k);
        // FCL's OcTree traversal calls shapeIntersect(leaf box, shape) in both orders
        // (ShapeOcTreeCollisionTraversalNode::leafTesting swaps): o1 is the tree, the normal
        // points from the leaf box to the ellipsoid.
        EXPECT_EQ(c.o1, octree.collisionGeometry().get());
        EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
        EXPECT_GE(c.penetration_depth, 0.0);
      }
      if (pose.expected == 1) {
        // The single contact: depth ~ the 1e-8 gap, normal ~ the face normal (box -> ellipsoid).
        ASSERT_EQ(with_contacts.numContacts(), 1u);
        const LeafBox& box = boxes[truth.first];
        const SignedDistanceResult sd = signedDistanceEllipsoidBox(pose.e, box.half, box.R, box.p);
        const fcl::Contactd& c = with_contacts.getContact(0);
        EXPECT_EQ(c.normal, -sd.normal);
        EXPECT_EQ(c.penetration_depth, -sd.distance);
        EXPECT_LT(c.penetration_depth, 1e-7);
        EXPECT_GT(c.normal.dot((pose.e.center() - box.p).normalized()), 0.0);
      }
    }
    fcl::CollisionResultd stock;
    {
      const test::ScopedNoFpTraps no_traps;
      fcl::collide(&octree, &oe, fcl::CollisionRequestd(), stock);
    }
    if (stock.isCollision() != (truth.colliding > 0)) {
      ++stock_wrong;
      stock_wrong_in += pose.expected == 1;
    }
  }
  std::printf("[ info ] OcTree (%s): %zu occupied leaves, %zu poses (100 near-tangent, gap 1e-8), %d colliding, "
              "%d leaf contacts; disagreements with brute force: ours %d, stock FCL %d (%d of the 50 inward "
              "near-tangent poses missed)\n",
              what, boxes.size(), poses.size(), colliding_poses, total_contacts, wrong, stock_wrong, stock_wrong_in);
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(colliding_poses, 80);
  // The exact leaf test is what answers: stock libccd misses most inward near-tangent leaves.
  EXPECT_GT(stock_wrong_in, 10);

  // Distances (the traversal's shapeDistance(leaf box, ellipsoid)): the brute-force minimum over
  // occupied leaves for separated poses.
  int checked = 0;
  for (std::size_t i = 0; i < poses.size() && checked < 15; i += 7) {
    const Pose& pose = poses[i];
    if (bruteForceBoxes(pose.e, boxes).colliding) continue;
    double best = std::numeric_limits<double>::infinity();
    for (const LeafBox& box : boxes) {
      if ((box.p - pose.e.center()).norm() - box.half.norm() - pose.e.maxRadius() > best) continue;
      best = std::min(best, signedDistanceEllipsoidBox(pose.e, box.half, box.R, box.p).distance);
    }
    const fcl::CollisionObjectd oe = ellipsoidObject(pose.e);
    fcl::DistanceResultd r;
    fcl_quadric::distance(&octree, &oe, fcl::DistanceRequestd(true), r);
    EXPECT_NEAR(r.min_distance, best, 1e-12) << what << " pose " << i;
    EXPECT_NEAR(pose.e.implicit(r.nearest_points[1]), 0.0, 1e-9);  // o2's point on the ellipsoid
    ++checked;
  }
  EXPECT_GE(checked, 10);
}

TEST(ExactOcTree, BtFileRoundTripMatchesBruteForceOverOccupiedLeaves) {
  std::mt19937_64 rng(61);
  octomap::OcTree built(0.08);
  fillScene(built, rng, false);
  const std::string path = tempFile("scene.bt");
  ASSERT_TRUE(built.writeBinary(path));
  auto tree = std::make_shared<const octomap::OcTree>(path);  // octomap::OcTree(filename): .bt
  std::filesystem::remove_all(std::filesystem::path(path).parent_path());
  ASSERT_GT(tree->getNumLeafNodes(), 1000u);
  compareOcTree(tree, -1.0, 62, ".bt, threshold 0.5");
}

TEST(ExactOcTree, OtFileWithGradedOccupancyKeepsFclsThresholdSemantics) {
  // A full-probability .ot file: leaves span occupied, uncertain and free log-odds. With the
  // threshold raised to 0.7 on the fcl::OcTree, leaves with 0.5 <= p < 0.7 no longer count
  // (FCL's isNodeOccupied), and free leaves (log-odds <= 0) never do.
  std::mt19937_64 rng(63);
  octomap::OcTree built(0.08);
  fillScene(built, rng, true);
  const std::string path = tempFile("scene.ot");
  ASSERT_TRUE(built.write(path));
  std::unique_ptr<octomap::AbstractOcTree> read(octomap::AbstractOcTree::read(path));
  std::filesystem::remove_all(std::filesystem::path(path).parent_path());
  ASSERT_NE(read, nullptr);
  std::shared_ptr<const octomap::OcTree> tree(dynamic_cast<octomap::OcTree*>(read.release()));
  ASSERT_NE(tree, nullptr);
  const fcl::OcTreed probe(tree);
  std::size_t occupied_05 = 0, occupied_07 = 0, leaves = 0;
  fcl::OcTreed raised(tree);
  raised.setOccupancyThres(0.7);
  for (auto it = tree->begin_leafs(), end = tree->end_leafs(); it != end; ++it) {
    ++leaves;
    occupied_05 += probe.isNodeOccupied(&*it);
    occupied_07 += raised.isNodeOccupied(&*it);
  }
  ASSERT_GT(occupied_05, occupied_07 + 100);  // the threshold matters in this tree
  ASSERT_GT(leaves, occupied_05 + 100);       // so do free and uncertain leaves
  compareOcTree(tree, 0.7, 64, ".ot, threshold 0.7");
}

/// fcl_quadric::collide runs its own traversal for an OcTree against an ellipsoid or a sphere
/// (src/fcl/octree_collision.cpp); FCL's OcTreeSolver with the same solver is the oracle: every
/// request kind, both argument orders, graded occupancy with two thresholds, the shape's own
/// occupancy (cost_density), rotations with a small accepted defect, a result that is already
/// full. The contacts must be FCL's exactly:
/// same count, order, objects, leaf indices, and with enable_contact the same points, normals
/// and depths.
TEST(ExactOcTree, OwnTraversalGivesFclsTraversalResultExactly) {
  std::mt19937_64 rng(65);
  auto built = std::make_shared<octomap::OcTree>(0.08);
  fillScene(*built, rng, true);
  const std::shared_ptr<const octomap::OcTree> tree = built;
  const fcl::Transform3d tf_tree =
      test::makePose(Eigen::AngleAxisd(-0.7, Eigen::Vector3d(0.3, 1, 2).normalized()).toRotationMatrix(),
                     Eigen::Vector3d(-0.4, 0.25, 0.3));
  std::uniform_real_distribution<double> ux(-1.3, 1.3), uz(-0.3, 1.4), r_small(0.02, 0.3), r_large(0.3, 0.9);
  struct Request {
    fcl::CollisionRequestd request;
    const char* name;
  };
  std::vector<Request> requests = {{fcl::CollisionRequestd(), "boolean, 1 contact"},
                                   {fcl::CollisionRequestd(5, false), "boolean, 5 contacts"},
                                   {fcl::CollisionRequestd(1, true), "contacts, 1"},
                                   {fcl::CollisionRequestd(100000, true), "contacts, all"}};
  fcl::CollisionRequestd with_cost(10, false, 4, true);  // cost sources: FCL's own traversal
  requests.push_back({with_cost, "cost sources"});
  const QuadricSolverd solver;
  std::size_t compared = 0, colliding = 0, contacts = 0, cost_sources = 0;
  for (double threshold : {-1.0, 0.7}) {
    auto fcl_tree = std::make_shared<fcl::OcTreed>(tree);
    if (threshold > 0) fcl_tree->setOccupancyThres(threshold);
    for (int i = 0; i < 120; ++i) {
      const Eigen::Vector3d c = tf_tree * Eigen::Vector3d(ux(rng), ux(rng), uz(rng));
      std::shared_ptr<fcl::CollisionGeometryd> shape;
      if (i % 4 == 3) {
        shape = std::make_shared<fcl::Sphered>(r_small(rng));
      } else {
        const bool large = i % 4 == 2;
        std::uniform_real_distribution<double>& r = large ? r_large : r_small;
        shape = std::make_shared<fcl::Ellipsoidd>(r(rng), r(rng), r(rng));
      }
      // The shape's own occupancy: occupied (FCL's default), uncertain, free.
      shape->cost_density = i % 10 == 8 ? 0.5 : i % 10 == 9 ? 0.0 : 1.0;
      // Every fifth pose carries a rotation defect of up to ~6e-10 (accepted: below
      // tolerance::kRotationOrthogonality), which the pruning's padding must cover.
      Eigen::Matrix3d R = test::randomRotation(rng);
      if (i % 5 == 4) R += 1e-10 * Eigen::Matrix3d::NullaryExpr([&] { return ux(rng) / 1.3; });
      const fcl::Transform3d tf_shape = test::makePose(R, c);
      for (int order = 0; order < 2; ++order) {
        const fcl::CollisionGeometryd* g1 = order ? shape.get() : fcl_tree.get();
        const fcl::CollisionGeometryd* g2 = order ? fcl_tree.get() : shape.get();
        const fcl::Transform3d& tf1 = order ? tf_shape : tf_tree;
        const fcl::Transform3d& tf2 = order ? tf_tree : tf_shape;
        for (const Request& q : requests) {
          fcl::CollisionResultd ours, theirs;
          const std::size_t n_ours = fcl_quadric::collide(g1, tf1, g2, tf2, q.request, ours);
          const std::size_t n_theirs = fcl::collide(g1, tf1, g2, tf2, &solver, q.request, theirs);
          ++compared;
          const std::string where = std::string(q.name) + ", pose " + std::to_string(i) + ", order " +
                                    std::to_string(order) + ", threshold " + std::to_string(threshold);
          ASSERT_EQ(n_ours, n_theirs) << where;
          expectSameContacts(ours, theirs, q.request.enable_contact, where);
          colliding += ours.isCollision();
          contacts += ours.numContacts();
          std::vector<fcl::CostSourced> cs_ours, cs_theirs;
          ours.getCostSources(cs_ours);
          theirs.getCostSources(cs_theirs);
          ASSERT_EQ(cs_ours.size(), cs_theirs.size()) << where;
          cost_sources += cs_ours.size();
          // A result that is already full: both return at once, adding nothing.
          if (ours.isCollision() && !q.request.enable_cost && q.request.num_max_contacts == 1) {
            const std::size_t again = fcl_quadric::collide(g1, tf1, g2, tf2, q.request, ours);
            EXPECT_EQ(again, 1u) << where;
            EXPECT_EQ(ours.numContacts(), 1u) << where;
          }
        }
      }
    }
  }
  std::printf("[ info ] own OcTree traversal vs FCL's: %zu queries, %zu colliding, %zu contacts, %zu cost sources, "
              "all identical\n",
              compared, colliding, contacts, cost_sources);
  // The comparison is not vacuous: many queries collide, with many contacts, and cost sources
  // were produced on FCL's path.
  EXPECT_GT(colliding, compared / 5);
  EXPECT_GT(contacts, 5 * colliding);
  EXPECT_GT(cost_sources, 0u);
}


/// fcl_quadric::distance runs its own best-first traversal for an OcTree against an ellipsoid or a
/// sphere (src/fcl/octree_distance.cpp). Oracle: the exact leaf distance to every occupied leaf box,
/// built as FCL builds it (occupiedLeafBoxes), and on a subset FCL's own traversal with the same
/// solver. For each query, in both argument orders, plain, nearest-point and signed requests:
///  - the minimum is the brute-force minimum bit for bit, and so is the value returned;
///  - FCL's traversal gives the same value and the same min_distance (the signed fix-up
///    included);
///  - o1 the tree, o2 the ellipsoid; the nearest points are that far apart (separated queries).
TEST(ExactOcTree, OwnDistanceTraversalGivesTheBruteForceMinimum) {
  std::mt19937_64 rng(67);
  auto built = std::make_shared<octomap::OcTree>(0.08);
  fillScene(*built, rng, true);
  const std::shared_ptr<const octomap::OcTree> tree = built;
  const fcl::Transform3d tf_tree =
      test::makePose(Eigen::AngleAxisd(-0.7, Eigen::Vector3d(0.3, 1, 2).normalized()).toRotationMatrix(),
                     Eigen::Vector3d(-0.4, 0.25, 0.3));
  std::uniform_real_distribution<double> ux(-1.6, 1.6), uz(-0.6, 1.8), r_small(0.02, 0.3), r_large(0.3, 0.9);
  const QuadricSolverd solver;
  std::size_t compared = 0, fcl_compared = 0, overlapping = 0, spheres = 0;
  for (double threshold : {-1.0, 0.7}) {
    auto fcl_tree = std::make_shared<fcl::OcTreed>(tree);
    if (threshold > 0) fcl_tree->setOccupancyThres(threshold);
    const std::vector<LeafBox> boxes = occupiedLeafBoxes(*fcl_tree, *tree, tf_tree);
    for (int i = 0; i < 40; ++i) {
      const double x = ux(rng), y = ux(rng), z = uz(rng);
      std::uniform_real_distribution<double>& r = i % 4 == 2 ? r_large : r_small;
      const double r0 = r(rng), r1 = r(rng), r2 = r(rng);
      // Every fourth shape a sphere (its leaf test is FCL's box-sphere closed form).
      const auto ellipsoid = std::make_shared<fcl::Ellipsoidd>(r0, r1, r2);
      const auto sphere = std::make_shared<fcl::Sphered>(r0);
      const bool is_sphere = i % 4 == 3;
      spheres += is_sphere;
      const fcl::Transform3d tf_shape = test::makePose(test::randomRotation(rng), tf_tree * Eigen::Vector3d(x, y, z));
      double best = std::numeric_limits<double>::max();
      for (const LeafBox& b : boxes) {
        double d = std::numeric_limits<double>::quiet_NaN();
        const fcl::Boxd box(2.0 * b.half);
        const fcl::Transform3d tf_box = test::makePose(b.R, b.p);
        if (is_sphere)
          solver.shapeDistance(box, tf_box, *sphere, tf_shape, &d, static_cast<Eigen::Vector3d*>(nullptr),
                               static_cast<Eigen::Vector3d*>(nullptr));
        else
          solver.shapeDistance(box, tf_box, *ellipsoid, tf_shape, &d, static_cast<Eigen::Vector3d*>(nullptr),
                               static_cast<Eigen::Vector3d*>(nullptr));
        best = std::min(best, d);
      }
      overlapping += best < 0.0;
      const fcl::CollisionGeometryd* tree_geometry = fcl_tree.get();
      const fcl::CollisionGeometryd* shape_geometry =
          is_sphere ? static_cast<const fcl::CollisionGeometryd*>(sphere.get()) : ellipsoid.get();
      for (int order = 0; order < 2; ++order) {
        const fcl::CollisionGeometryd* g1 = order ? shape_geometry : tree_geometry;
        const fcl::CollisionGeometryd* g2 = order ? tree_geometry : shape_geometry;
        const fcl::Transform3d& tf1 = order ? tf_shape : tf_tree;
        const fcl::Transform3d& tf2 = order ? tf_tree : tf_shape;
        for (int variant = 0; variant < 3; ++variant) {
          const fcl::DistanceRequestd request(variant >= 1, variant == 2);
          const std::string where = "threshold " + std::to_string(threshold) + ", pose " + std::to_string(i) +
                                    ", order " + std::to_string(order) + ", request " + std::to_string(variant);
          fcl::DistanceResultd ours;
          const double value = fcl_quadric::distance(g1, tf1, g2, tf2, request, ours);
          ++compared;
          EXPECT_EQ(value, best) << where;
          EXPECT_EQ(ours.o1, tree_geometry) << where;
          EXPECT_EQ(ours.o2, shape_geometry) << where;
          if (!request.enable_signed_distance || best >= 0.0) {
            EXPECT_EQ(ours.min_distance, best) << where;
            if (request.enable_nearest_points && best > 0.0) {
              EXPECT_NEAR((ours.nearest_points[0] - ours.nearest_points[1]).norm(), best, 1e-12 * (1.0 + best))
                  << where;
            }
          }
          if (i % 8 == 0) {
            fcl::DistanceResultd theirs;
            const double fcl_value = fcl::distance(g1, tf1, g2, tf2, &solver, request, theirs);
            ++fcl_compared;
            EXPECT_EQ(fcl_value, value) << where;
            EXPECT_EQ(theirs.min_distance, ours.min_distance) << where;
          }
        }
      }
    }
  }
  std::printf("[ info ] own OcTree distance vs brute force: %zu queries (%zu shape poses overlapping), %zu also "
              "against FCL's traversal\n",
              compared, overlapping, fcl_compared);
  EXPECT_GT(overlapping, 5u);  // both regimes
  EXPECT_LT(overlapping, 70u);
  EXPECT_GT(fcl_compared, 50u);
  EXPECT_EQ(spheres, 20u);
}

/// Bad input through the own OcTree distance traversal, far from every cell: an invalid
/// ellipsoid or sphere, or a scaled tree pose, throws std::invalid_argument naming it.
TEST(ExactOcTree, OwnDistanceTraversalRejectsBadInput) {
  std::mt19937_64 rng(68);
  auto built = std::make_shared<octomap::OcTree>(0.08);
  fillScene(*built, rng, false);
  auto fcl_tree = std::make_shared<fcl::OcTreed>(std::shared_ptr<const octomap::OcTree>(built));
  const fcl::Transform3d far = test::makePose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(50, 50, 50));
  const fcl::Transform3d tree_pose = fcl::Transform3d::Identity();
  const fcl::Ellipsoidd good(0.2, 0.3, 0.4);
  {
    fcl::DistanceResultd r;
    EXPECT_GT(fcl_quadric::distance(fcl_tree.get(), tree_pose, &good, far, fcl::DistanceRequestd(), r), 40.0);
  }
  const fcl::Ellipsoidd negative(0.2, -0.3, 0.4);
  expectDistanceThrowsNaming(fcl_tree.get(), tree_pose, &negative, far, "radius");
  const fcl::Ellipsoidd not_a_number(0.2, std::numeric_limits<double>::quiet_NaN(), 0.4);
  expectDistanceThrowsNaming(fcl_tree.get(), tree_pose, &not_a_number, far, "radius");
  const fcl::Sphered negative_sphere(-0.2);
  expectDistanceThrowsNaming(fcl_tree.get(), tree_pose, &negative_sphere, far, "radius");
  fcl::Transform3d scaled = far;
  scaled.linear() *= 1.1;
  expectDistanceThrowsNaming(fcl_tree.get(), tree_pose, &good, scaled, "rotation");
  fcl::Transform3d tree_scaled = tree_pose;
  tree_scaled.linear() *= 1.1;
  expectDistanceThrowsNaming(fcl_tree.get(), tree_scaled, &good, far, "rotation");
}

/// Bad input through the own OcTree traversal: an invalid ellipsoid or sphere, or a tree pose
/// that is not a rotation, throws std::invalid_argument even where no leaf would be reached (the
/// shape far from every occupied cell), naming the bad value as the leaf test does.
TEST(ExactOcTree, OwnTraversalRejectsBadInputWhereNoLeafIsReached) {
  std::mt19937_64 rng(66);
  auto built = std::make_shared<octomap::OcTree>(0.08);
  fillScene(*built, rng, false);
  auto fcl_tree = std::make_shared<fcl::OcTreed>(std::shared_ptr<const octomap::OcTree>(built));
  const fcl::Transform3d far = test::makePose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(50, 50, 50));
  const fcl::Transform3d tree_pose = fcl::Transform3d::Identity();
  // A valid ellipsoid there collides with nothing and throws nothing.
  {
    const fcl::Ellipsoidd good(0.2, 0.3, 0.4);
    fcl::CollisionResultd r;
    EXPECT_EQ(fcl_quadric::collide(fcl_tree.get(), tree_pose, &good, far, fcl::CollisionRequestd(), r), 0u);
  }

  const fcl::Ellipsoidd negative(0.2, -0.3, 0.4);
  expectCollideThrowsNaming(fcl_tree.get(), tree_pose, &negative, far, "radius");
  const fcl::Ellipsoidd not_a_number(0.2, std::numeric_limits<double>::quiet_NaN(), 0.4);
  expectCollideThrowsNaming(fcl_tree.get(), tree_pose, &not_a_number, far, "radius");
  const fcl::Sphered bad_sphere(-1.0);
  expectCollideThrowsNaming(fcl_tree.get(), tree_pose, &bad_sphere, far, "radius");
  fcl::Transform3d scaled = far;
  scaled.linear() *= 1.1;  // not a rotation
  const fcl::Ellipsoidd good(0.2, 0.3, 0.4);
  expectCollideThrowsNaming(fcl_tree.get(), tree_pose, &good, scaled, "rotation");
  fcl::Transform3d tree_scaled = tree_pose;
  tree_scaled.linear() *= 1.1;
  expectCollideThrowsNaming(fcl_tree.get(), tree_scaled, &good, far, "rotation");
}

#endif  // FCL_HAVE_OCTOMAP

// =============================================================================================
// BVH meshes
// =============================================================================================

struct Mesh {
  std::vector<Eigen::Vector3d> v;
  std::vector<fcl::Triangle> t;
};

/// Icosphere of radius r (icosahedron subdivided `levels` times), outward winding.
Mesh icosphere(double r, int levels) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  Mesh m;
  m.v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
         {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  m.t = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
         {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
         {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (auto& p : m.v) p.normalize();
  for (int l = 0; l < levels; ++l) {
    std::vector<fcl::Triangle> next;
    for (const fcl::Triangle& tri : m.t) {
      int mid[3];
      for (int k = 0; k < 3; ++k) {
        m.v.push_back((m.v[tri[k]] + m.v[tri[(k + 1) % 3]]).normalized());
        mid[k] = static_cast<int>(m.v.size()) - 1;
      }
      next.emplace_back(tri[0], mid[0], mid[2]);
      next.emplace_back(tri[1], mid[1], mid[0]);
      next.emplace_back(tri[2], mid[2], mid[1]);
      next.emplace_back(mid[0], mid[1], mid[2]);
    }
    m.t = next;
  }
  for (auto& p : m.v) p *= r;
  return m;
}

/// The box [-h, h] (12 triangles, outward winding).
Mesh boxMesh(const Eigen::Vector3d& h) {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.v.emplace_back(i & 1 ? h[0] : -h[0], i & 2 ? h[1] : -h[1], i & 4 ? h[2] : -h[2]);
  m.t = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
         {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

/// The mesh as a BVHModel with `BV` nodes (FCL's default build).
template <typename BV>
std::shared_ptr<fcl::BVHModel<BV>> buildModel(const Mesh& mesh) {
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  model->beginModel();
  model->addSubModel(mesh.v, mesh.t);
  model->endModel();
  return model;
}

void compareMesh(const Mesh& mesh, unsigned seed, const char* what) {
  const auto model = buildModel<fcl::OBBRSSd>(mesh);
  const fcl::Transform3d tf_mesh =
      test::makePose(Eigen::AngleAxisd(-0.7, Eigen::Vector3d(0.3, 1, 0.2).normalized()).toRotationMatrix(),
                     Eigen::Vector3d(-0.4, 0.5, 0.2));
  const fcl::CollisionObjectd om(model, tf_mesh);
  // World triangles as the traversal's solver call computes them (tf * P).
  std::vector<std::array<Eigen::Vector3d, 3>> tris;
  for (const fcl::Triangle& t : mesh.t) tris.push_back({tf_mesh * mesh.v[t[0]], tf_mesh * mesh.v[t[1]], tf_mesh * mesh.v[t[2]]});
  const Eigen::Vector3d centre = tf_mesh.translation();
  auto brute = [&](const Ellipsoid& e, std::size_t* count) {
    *count = 0;
    for (const auto& t : tris) *count += classifyEllipsoidTriangle(e, t[0], t[1], t[2]).status != Separation::Separated;
  };

  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uc(-1.8, 1.8), r(0.1, 0.8), bary(0.2, 1.0);
  struct Pose {
    Ellipsoid e;
    int expected;
  };
  std::vector<Pose> poses;
  for (int i = 0; i < 150; ++i) {
    poses.push_back(Pose{Ellipsoid(Eigen::Vector3d(r(rng), r(rng), r(rng)), test::randomRotation(rng),
                                   centre + Eigen::Vector3d(uc(rng), uc(rng), uc(rng))),
                         -1});
  }
  for (int i = 0; i < 100; ++i) {
    // Tangent from outside to the interior of one triangle of the convex mesh.
    const auto& t = tris[rng() % tris.size()];
    const double l0 = bary(rng), l1 = bary(rng), l2 = bary(rng);
    const Eigen::Vector3d x0 = (l0 * t[0] + l1 * t[1] + l2 * t[2]) / (l0 + l1 + l2);
    Eigen::Vector3d u = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
    if (u.dot(x0 - centre) < 0) u = -u;
    const bool inward = i % 2 == 0;
    poses.push_back(Pose{tangentEllipsoid(rng, x0, u, 0.1, 0.8, inward ? -1e-8 : 1e-8), inward ? 1 : 0});
  }

  const QuadricSolverd solver;
  int wrong = 0, stock_wrong = 0, stock_wrong_in = 0, colliding = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Pose& pose = poses[i];
    std::size_t truth = 0;
    brute(pose.e, &truth);
    if (pose.expected >= 0) {
      ASSERT_EQ(truth, static_cast<std::size_t>(pose.expected)) << what << " pose " << i;
    }
    colliding += truth > 0;
    const fcl::CollisionObjectd oe = ellipsoidObject(pose.e);
    for (int order = 0; order < 2; ++order) {
      const fcl::CollisionObjectd& a = order ? oe : om;
      const fcl::CollisionObjectd& b = order ? om : oe;
      fcl::CollisionResultd boolean, counted, with_contacts, via_fcl;
      fcl_quadric::collide(&a, &b, fcl::CollisionRequestd(), boolean);
      fcl_quadric::collide(&a, &b, fcl::CollisionRequestd(100000, false), counted);
      fcl_quadric::collide(&a, &b, fcl::CollisionRequestd(100000, true), with_contacts);
      fcl::collide(&a, &b, &solver, fcl::CollisionRequestd(100000, true), via_fcl);
      wrong += boolean.isCollision() != (truth > 0);
      EXPECT_EQ(boolean.isCollision(), truth > 0) << what << " pose " << i;
      EXPECT_EQ(counted.numContacts(), truth) << what << " pose " << i;
      EXPECT_EQ(with_contacts.numContacts(), truth) << what << " pose " << i;
      EXPECT_EQ(via_fcl.numContacts(), truth) << what << " pose " << i;
      for (std::size_t k = 0; k < with_contacts.numContacts(); ++k) {
        // fcl::collide puts the mesh first in either order, and the mesh-shape node negates the
        // solver's shape->triangle normal: the normal points from the triangle to the ellipsoid.
        const fcl::Contactd& c = with_contacts.getContact(k);
        EXPECT_EQ(c.o1, om.collisionGeometry().get());
        // b1 is the primitive id: an index into the model's (possibly reordered) tri_indices.
        const fcl::Triangle& tri = model->tri_indices[c.b1];
        const SignedDistanceResult sd = signedDistanceEllipsoidTriangle(
            pose.e, tf_mesh * model->vertices[tri[0]], tf_mesh * model->vertices[tri[1]], tf_mesh * model->vertices[tri[2]]);
        EXPECT_EQ(c.normal, -sd.normal) << what << " pose " << i;
        EXPECT_EQ(c.penetration_depth, -sd.distance);
        EXPECT_EQ(c.pos, 0.5 * (sd.point_a + sd.point_b));
      }
    }
    fcl::CollisionResultd stock;
    {
      const test::ScopedNoFpTraps no_traps;
      fcl::collide(&om, &oe, fcl::CollisionRequestd(), stock);
    }
    if (stock.isCollision() != (truth > 0)) {
      ++stock_wrong;
      stock_wrong_in += pose.expected == 1;
    }
    // Distance for separated poses: the minimum over triangles (libccd's convention per triangle).
    if (truth == 0 && i % 3 == 0) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& t : tris) best = std::min(best, signedDistanceEllipsoidTriangle(pose.e, t[0], t[1], t[2]).distance);
      fcl::DistanceResultd dr;
      fcl_quadric::distance(&om, &oe, fcl::DistanceRequestd(true), dr);
      EXPECT_NEAR(dr.min_distance, best, 1e-12) << what << " pose " << i;
      EXPECT_NEAR(pose.e.implicit(dr.nearest_points[1]), 0.0, 1e-9);
    }
  }
  std::printf("[ info ] BVH<OBBRSS> %s: %zu triangles, %zu poses (100 near-tangent, gap 1e-8), %d colliding; "
              "disagreements with brute force: ours %d, stock FCL %d (%d of the 50 inward near-tangent poses "
              "missed)\n",
              what, tris.size(), poses.size(), colliding, wrong, stock_wrong, stock_wrong_in);
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(colliding, 60);
  EXPECT_GT(stock_wrong_in, 10);
}

TEST(ExactBvhMesh, IcosphereMatchesBruteForceOverTriangles) { compareMesh(icosphere(1.0, 3), 71, "icosphere"); }
TEST(ExactBvhMesh, BoxMeshMatchesBruteForceOverTriangles) {
  compareMesh(boxMesh(Eigen::Vector3d(0.9, 0.6, 0.4)), 72, "box mesh");
}

/// fcl_quadric::collide runs its own traversal for a triangle mesh with OBBRSS or OBB nodes
/// against an ellipsoid or a sphere (src/fcl/mesh_collision.cpp); FCL's traversal with the same
/// solver is the oracle. Two meshes (icosphere and box), both BV types, both argument orders,
/// ellipsoids (small and large) and spheres, the shape's own occupancy, rotations with a small
/// accepted defect, boolean and contact requests: the same contacts in the same order (objects,
/// triangle indices, and with enable_contact the points, normals and depths).
template <typename BV>
void compareMeshTraversal(const Mesh& mesh, unsigned seed, const char* what, std::size_t* compared,
                          std::size_t* colliding, std::size_t* contacts) {
  const auto model = buildModel<BV>(mesh);
  const fcl::Transform3d tf_mesh =
      test::makePose(Eigen::AngleAxisd(0.9, Eigen::Vector3d(-0.5, 1, 0.3).normalized()).toRotationMatrix(),
                     Eigen::Vector3d(0.3, -0.6, 0.4));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uc(-1.6, 1.6), r_small(0.05, 0.4), r_large(0.4, 1.2);
  const std::vector<fcl::CollisionRequestd> requests = {fcl::CollisionRequestd(), fcl::CollisionRequestd(4, false),
                                                        fcl::CollisionRequestd(1, true),
                                                        fcl::CollisionRequestd(100000, true)};
  const QuadricSolverd solver;
  for (int i = 0; i < 150; ++i) {
    std::shared_ptr<fcl::CollisionGeometryd> shape;
    if (i % 4 == 3) {
      shape = std::make_shared<fcl::Sphered>(r_small(rng));
    } else {
      std::uniform_real_distribution<double>& r = i % 4 == 2 ? r_large : r_small;
      shape = std::make_shared<fcl::Ellipsoidd>(r(rng), r(rng), r(rng));
    }
    shape->cost_density = i % 10 == 9 ? 0.0 : 1.0;  // a free shape collides with nothing
    Eigen::Matrix3d R = test::randomRotation(rng);
    if (i % 5 == 4) R += 1e-10 * Eigen::Matrix3d::NullaryExpr([&] { return uc(rng) / 1.6; });
    const fcl::Transform3d tf_shape = test::makePose(R, tf_mesh * Eigen::Vector3d(uc(rng), uc(rng), uc(rng)));
    for (int order = 0; order < 2; ++order) {
      const fcl::CollisionGeometryd* g1 = order ? shape.get() : model.get();
      const fcl::CollisionGeometryd* g2 = order ? model.get() : shape.get();
      const fcl::Transform3d& tf1 = order ? tf_shape : tf_mesh;
      const fcl::Transform3d& tf2 = order ? tf_mesh : tf_shape;
      for (const fcl::CollisionRequestd& request : requests) {
        fcl::CollisionResultd ours, theirs;
        const std::size_t n_ours = fcl_quadric::collide(g1, tf1, g2, tf2, request, ours);
        const std::size_t n_theirs = fcl::collide(g1, tf1, g2, tf2, &solver, request, theirs);
        ++*compared;
        const std::string where = std::string(what) + ", pose " + std::to_string(i) + ", order " +
                                  std::to_string(order) + ", max contacts " +
                                  std::to_string(request.num_max_contacts) + (request.enable_contact ? ", contacts" : "");
        ASSERT_EQ(n_ours, n_theirs) << where;
        expectSameContacts(ours, theirs, request.enable_contact, where);
        *colliding += ours.isCollision();
        *contacts += ours.numContacts();
      }
    }
  }
}

TEST(ExactBvhMesh, OwnTraversalGivesFclsTraversalResultExactly) {
  std::size_t compared = 0, colliding = 0, contacts = 0;
  compareMeshTraversal<fcl::OBBRSSd>(icosphere(1.0, 3), 81, "icosphere, OBBRSS", &compared, &colliding, &contacts);
  compareMeshTraversal<fcl::OBBd>(icosphere(1.0, 3), 82, "icosphere, OBB", &compared, &colliding, &contacts);
  compareMeshTraversal<fcl::OBBRSSd>(boxMesh(Eigen::Vector3d(0.9, 0.6, 0.4)), 83, "box mesh, OBBRSS", &compared,
                                     &colliding, &contacts);
  compareMeshTraversal<fcl::RSSd>(icosphere(1.0, 3), 84, "icosphere, RSS", &compared, &colliding, &contacts);
  compareMeshTraversal<fcl::kIOSd>(icosphere(1.0, 3), 85, "icosphere, kIOS", &compared, &colliding, &contacts);
  compareMeshTraversal<fcl::RSSd>(boxMesh(Eigen::Vector3d(0.9, 0.6, 0.4)), 86, "box mesh, RSS", &compared,
                                  &colliding, &contacts);
  std::printf("[ info ] own mesh traversal vs FCL's: %zu queries, %zu colliding, %zu contacts, all identical\n",
              compared, colliding, contacts);
  EXPECT_GT(colliding, compared / 5);  // not vacuous
  EXPECT_GT(contacts, 3 * colliding);
}

/// Axis-aligned BV types (AABB, k-DOPs). FCL copies the model on every query and rebuilds its
/// tree from the vertices mapped by the mesh's pose; fcl_quadric::collide traverses the model's
/// own tree (src/fcl/mesh_collision.cpp). Oracle: FCL's traversal with the same solver, once
/// with the caller's request and once without a contact limit (the full list). For every query,
/// in both argument orders, for boolean and contact requests, under three mesh poses (the
/// identity, a rigid pose, an affine one that FCL accepts too):
///  - the same number of contacts and the same collision flag;
///  - every contact is one of the full list's triangles (no triangle twice), with o1 the caller's
///    mesh (FCL's is its temporary copy), and for contact requests the same point, normal and
///    depth bit for bit;
///  - when the limit did not cut the list: the full list's triangles, all of them;
///  - under the identity pose, where FCL's rebuilt tree is the model's: FCL's order exactly.
template <typename BV>
void compareAlignedMeshTraversal(const Mesh& mesh, unsigned seed, const char* what, std::size_t* compared,
                                 std::size_t* colliding, std::size_t* contacts) {
  const auto model = buildModel<BV>(mesh);
  const fcl::Transform3d rigid =
      test::makePose(Eigen::AngleAxisd(0.9, Eigen::Vector3d(-0.5, 1, 0.3).normalized()).toRotationMatrix(),
                     Eigen::Vector3d(0.3, -0.6, 0.4));
  fcl::Transform3d affine = rigid;
  affine.linear() = affine.linear() * Eigen::Vector3d(1.3, 0.8, 1.1).asDiagonal();
  affine.linear()(0, 1) += 0.2;  // a shear as well
  const fcl::Transform3d mesh_poses[3] = {fcl::Transform3d::Identity(), rigid, affine};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uc(-1.6, 1.6), r_small(0.05, 0.4), r_large(0.4, 1.2);
  const std::vector<fcl::CollisionRequestd> requests = {fcl::CollisionRequestd(), fcl::CollisionRequestd(4, false),
                                                        fcl::CollisionRequestd(1, true),
                                                        fcl::CollisionRequestd(100000, true)};
  const QuadricSolverd solver;
  for (int pose_kind = 0; pose_kind < 3; ++pose_kind) {
    const fcl::Transform3d& tf_mesh = mesh_poses[pose_kind];
    for (int i = 0; i < 50; ++i) {
      std::shared_ptr<fcl::CollisionGeometryd> shape;
      if (i % 4 == 3) {
        shape = std::make_shared<fcl::Sphered>(r_small(rng));
      } else {
        std::uniform_real_distribution<double>& r = i % 4 == 2 ? r_large : r_small;
        const double r0 = r(rng), r1 = r(rng), r2 = r(rng);
        shape = std::make_shared<fcl::Ellipsoidd>(r0, r1, r2);
      }
      shape->cost_density = i % 10 == 9 ? 0.0 : 1.0;  // a free shape collides with nothing
      Eigen::Matrix3d R = test::randomRotation(rng);
      if (i % 5 == 4) R += 1e-10 * Eigen::Matrix3d::NullaryExpr([&] { return uc(rng) / 1.6; });
      const double x = uc(rng), y = uc(rng), z = uc(rng);
      const fcl::Transform3d tf_shape = test::makePose(R, tf_mesh * Eigen::Vector3d(x, y, z));
      for (int order = 0; order < 2; ++order) {
        const fcl::CollisionGeometryd* g1 = order ? shape.get() : model.get();
        const fcl::CollisionGeometryd* g2 = order ? model.get() : shape.get();
        const fcl::Transform3d& tf1 = order ? tf_shape : tf_mesh;
        const fcl::Transform3d& tf2 = order ? tf_mesh : tf_shape;
        for (const fcl::CollisionRequestd& request : requests) {
          const std::string where = std::string(what) + ", mesh pose " + std::to_string(pose_kind) + ", shape pose " +
                                    std::to_string(i) + ", order " + std::to_string(order) + ", max contacts " +
                                    std::to_string(request.num_max_contacts) +
                                    (request.enable_contact ? ", contacts" : "");
          fcl::CollisionResultd ours, theirs, full;
          const std::size_t n_ours = fcl_quadric::collide(g1, tf1, g2, tf2, request, ours);
          const std::size_t n_theirs = fcl::collide(g1, tf1, g2, tf2, &solver, request, theirs);
          fcl::CollisionRequestd unlimited = request;
          unlimited.num_max_contacts = 1000000;
          fcl::collide(g1, tf1, g2, tf2, &solver, unlimited, full);
          ++*compared;
          ASSERT_EQ(n_ours, n_theirs) << where;
          ASSERT_EQ(ours.isCollision(), theirs.isCollision()) << where;
          std::map<int, const fcl::Contactd*> by_triangle;
          for (std::size_t k = 0; k < full.numContacts(); ++k) by_triangle[full.getContact(k).b1] = &full.getContact(k);
          std::set<int> seen;
          for (std::size_t k = 0; k < ours.numContacts(); ++k) {
            const fcl::Contactd& a = ours.getContact(k);
            EXPECT_EQ(a.o1, model.get()) << where;
            EXPECT_EQ(a.o2, shape.get()) << where;
            EXPECT_EQ(a.b2, static_cast<int>(fcl::Contactd::NONE)) << where;
            EXPECT_TRUE(seen.insert(a.b1).second) << where << ": triangle " << a.b1 << " twice";
            const auto it = by_triangle.find(a.b1);
            ASSERT_NE(it, by_triangle.end()) << where << ": triangle " << a.b1 << " is not in FCL's list";
            if (request.enable_contact) {
              EXPECT_EQ(a.pos, it->second->pos) << where;
              EXPECT_EQ(a.normal, it->second->normal) << where;
              EXPECT_EQ(a.penetration_depth, it->second->penetration_depth) << where;
            }
            if (pose_kind == 0) {
              EXPECT_EQ(a.b1, theirs.getContact(k).b1) << where << ", contact " << k;
            }
          }
          if (n_ours < request.num_max_contacts) {
            EXPECT_EQ(seen.size(), by_triangle.size()) << where;
          }
          *colliding += ours.isCollision();
          *contacts += ours.numContacts();
        }
      }
    }
  }
}

TEST(ExactBvhMesh, OwnTraversalOfAxisAlignedNodesGivesFclsContacts) {
  std::size_t compared = 0, colliding = 0, contacts = 0;
  const Mesh sphere = icosphere(1.0, 2);
  compareAlignedMeshTraversal<fcl::AABBd>(sphere, 91, "icosphere, AABB", &compared, &colliding, &contacts);
  compareAlignedMeshTraversal<fcl::KDOPd<16>>(sphere, 92, "icosphere, KDOP16", &compared, &colliding, &contacts);
  compareAlignedMeshTraversal<fcl::KDOPd<18>>(sphere, 93, "icosphere, KDOP18", &compared, &colliding, &contacts);
  compareAlignedMeshTraversal<fcl::KDOPd<24>>(sphere, 94, "icosphere, KDOP24", &compared, &colliding, &contacts);
  compareAlignedMeshTraversal<fcl::AABBd>(boxMesh(Eigen::Vector3d(0.9, 0.6, 0.4)), 95, "box mesh, AABB", &compared,
                                          &colliding, &contacts);
  std::printf("[ info ] own axis-aligned mesh traversal vs FCL's: %zu queries, %zu colliding, %zu contacts\n",
              compared, colliding, contacts);
  EXPECT_GT(colliding, compared / 5);  // not vacuous
  EXPECT_GT(contacts, 3 * colliding);
}

/// The leaf distance of triangle t as the mesh-shape distance nodes call it: oriented BV types
/// pass the mesh-frame vertices and the mesh's pose, the others the world vertices (the raw ones
/// under FCL's identity test). Returns the distance, the point on the mesh and the one on the shape.
template <typename BV, typename Shape>
double leafDistance(const fcl::BVHModel<BV>& model, const fcl::Transform3d& tf_mesh, const Shape& shape,
                    const fcl::Transform3d& tf_shape, int t, Eigen::Vector3d* on_mesh, Eigen::Vector3d* on_shape) {
  const QuadricSolverd solver;
  const fcl::Triangle& tri = model.tri_indices[t];
  const Eigen::Vector3d &v1 = model.vertices[tri[0]], &v2 = model.vertices[tri[1]], &v3 = model.vertices[tri[2]];
  constexpr bool oriented = std::is_same_v<BV, fcl::OBBRSSd> || std::is_same_v<BV, fcl::OBBd> ||
                            std::is_same_v<BV, fcl::RSSd> || std::is_same_v<BV, fcl::kIOSd>;
  double d = std::numeric_limits<double>::quiet_NaN();  // the solver always writes it
  if (oriented) {
    solver.shapeTriangleDistance(shape, tf_shape, v1, v2, v3, tf_mesh, &d, on_shape, on_mesh);
  } else if (tf_mesh.matrix().isIdentity()) {
    solver.shapeTriangleDistance(shape, tf_shape, v1, v2, v3, &d, on_shape, on_mesh);
  } else {
    const Eigen::Vector3d w1 = tf_mesh * v1, w2 = tf_mesh * v2, w3 = tf_mesh * v3;
    solver.shapeTriangleDistance(shape, tf_shape, w1, w2, w3, &d, on_shape, on_mesh);
  }
  return d;
}

/// fcl_quadric::distance runs its own best-first traversal for a triangle mesh of any BV type
/// against an ellipsoid or a sphere (src/fcl/mesh_distance.cpp). Oracle: the leaf distance of
/// every triangle (brute force, the same solver call). For each query, in both argument orders,
/// with and without nearest points: the minimum is the brute-force minimum bit for bit (the
/// pruning only skips triangles that cannot lower it), attained by the reported triangle b1,
/// whose nearest points are reported; o1 the mesh. Where FCL has a distance for the BV type
/// (OBBRSS, RSS, kIOS), FCL's traversal with the same solver gives the same minimum, and with
/// enable_signed_distance the same signed value after the contact fix-up. A result that already
/// holds a smaller distance (a broad-phase search) is left as it is, as FCL leaves it.
template <typename BV>
void compareMeshDistance(const Mesh& mesh, unsigned seed, const char* what, std::size_t* compared,
                         std::size_t* overlapping, std::size_t* fcl_compared) {
  const auto model = buildModel<BV>(mesh);
  constexpr bool oriented = std::is_same_v<BV, fcl::OBBRSSd> || std::is_same_v<BV, fcl::OBBd> ||
                            std::is_same_v<BV, fcl::RSSd> || std::is_same_v<BV, fcl::kIOSd>;
  constexpr bool fcl_has_it = std::is_same_v<BV, fcl::OBBRSSd> || std::is_same_v<BV, fcl::RSSd> ||
                              std::is_same_v<BV, fcl::kIOSd>;
  const fcl::Transform3d rigid =
      test::makePose(Eigen::AngleAxisd(0.9, Eigen::Vector3d(-0.5, 1, 0.3).normalized()).toRotationMatrix(),
                     Eigen::Vector3d(0.3, -0.6, 0.4));
  fcl::Transform3d affine = rigid;
  affine.linear() = affine.linear() * Eigen::Vector3d(1.3, 0.8, 1.1).asDiagonal();
  affine.linear()(0, 1) += 0.2;
  std::vector<fcl::Transform3d> mesh_poses = {rigid, fcl::Transform3d::Identity()};
  if (!oriented) mesh_poses.push_back(affine);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uc(-2.2, 2.2), r_small(0.05, 0.4), r_large(0.4, 1.2);
  const QuadricSolverd solver;
  for (const fcl::Transform3d& tf_mesh : mesh_poses) {
    for (int i = 0; i < 40; ++i) {
      std::uniform_real_distribution<double>& r = i % 4 == 2 ? r_large : r_small;
      const double r0 = r(rng), r1 = r(rng), r2 = r(rng);
      // Every fourth shape a sphere (QuadricSolver: the ellipsoid of equal radii).
      std::shared_ptr<fcl::CollisionGeometryd> shape;
      if (i % 4 == 3) shape = std::make_shared<fcl::Sphered>(r0);
      else shape = std::make_shared<fcl::Ellipsoidd>(r0, r1, r2);
      const fcl::CollisionGeometryd* shape_geometry = shape.get();
      const fcl::CollisionGeometryd* mesh_geometry = model.get();
      const Eigen::Matrix3d R = test::randomRotation(rng);
      const double x = uc(rng), y = uc(rng), z = uc(rng);
      const fcl::Transform3d tf_shape = test::makePose(R, tf_mesh * Eigen::Vector3d(x, y, z));
      auto leaf = [&](int t, Eigen::Vector3d* pm, Eigen::Vector3d* ps) {
        if (i % 4 == 3) return leafDistance(*model, tf_mesh, static_cast<const fcl::Sphered&>(*shape), tf_shape, t, pm, ps);
        return leafDistance(*model, tf_mesh, static_cast<const fcl::Ellipsoidd&>(*shape), tf_shape, t, pm, ps);
      };
      // Brute force.
      double best = std::numeric_limits<double>::max();
      for (int t = 0; t < model->num_tris; ++t) {
        Eigen::Vector3d pm, ps;
        best = std::min(best, leaf(t, &pm, &ps));
      }
      *overlapping += best < 0.0;
      for (int order = 0; order < 2; ++order) {
        const fcl::CollisionGeometryd* g1 = order ? shape_geometry : mesh_geometry;
        const fcl::CollisionGeometryd* g2 = order ? mesh_geometry : shape_geometry;
        const fcl::Transform3d& tf1 = order ? tf_shape : tf_mesh;
        const fcl::Transform3d& tf2 = order ? tf_mesh : tf_shape;
        for (int variant = 0; variant < 3; ++variant) {
          const fcl::DistanceRequestd request(variant >= 1, variant == 2);
          const std::string where = std::string(what) + ", shape pose " + std::to_string(i) + ", order " +
                                    std::to_string(order) + ", request " + std::to_string(variant);
          fcl::DistanceResultd ours;
          const double value = fcl_quadric::distance(g1, tf1, g2, tf2, request, ours);
          ++*compared;
          EXPECT_EQ(value, best) << where;
          ASSERT_EQ(ours.o1, model.get()) << where;
          EXPECT_EQ(ours.o2, shape.get()) << where;
          ASSERT_GE(ours.b1, 0) << where;
          ASSERT_LT(ours.b1, model->num_tris) << where;
          Eigen::Vector3d pm, ps;
          const double at_b1 = leaf(ours.b1, &pm, &ps);
          EXPECT_EQ(at_b1, best) << where << ": the reported triangle does not attain the minimum";
          if (!request.enable_signed_distance || best >= 0.0) {
            EXPECT_EQ(ours.min_distance, best) << where;
            if (request.enable_nearest_points) {
              EXPECT_EQ(ours.nearest_points[0], pm) << where;
              EXPECT_EQ(ours.nearest_points[1], ps) << where;
              // World-frame points, as far apart as the distance (FCL's own sphere-triangle
              // distance returned them in the shapes' local frames).
              if (best > 0.0) {
                EXPECT_NEAR((ours.nearest_points[0] - ours.nearest_points[1]).norm(), best, 1e-12 * (1.0 + best))
                    << where;
              }
            }
          }
          if (fcl_has_it) {
            fcl::DistanceResultd theirs;
            const double fcl_value = fcl::distance(g1, tf1, g2, tf2, &solver, request, theirs);
            ++*fcl_compared;
            EXPECT_EQ(fcl_value, value) << where;
            EXPECT_EQ(theirs.min_distance, ours.min_distance) << where;
            if (request.enable_signed_distance && best < 0.0 && request.enable_nearest_points) {
              EXPECT_EQ(theirs.nearest_points[0], ours.nearest_points[0]) << where;
            }
          }
          // A result already holding a smaller distance stays as it is.
          fcl::DistanceResultd held;
          held.update(best - 1.0, nullptr, nullptr, -7, -7);
          fcl_quadric::distance(g1, tf1, g2, tf2, fcl::DistanceRequestd(), held);
          EXPECT_EQ(held.min_distance, best - 1.0) << where;
          EXPECT_EQ(held.b1, -7) << where;
        }
      }
    }
  }
}

TEST(ExactBvhMesh, OwnDistanceTraversalGivesTheBruteForceMinimum) {
  std::size_t compared = 0, overlapping = 0, fcl_compared = 0;
  const Mesh sphere = icosphere(1.0, 2);
  const Mesh box = boxMesh(Eigen::Vector3d(0.9, 0.6, 0.4));
  compareMeshDistance<fcl::OBBRSSd>(sphere, 101, "icosphere, OBBRSS", &compared, &overlapping, &fcl_compared);
  compareMeshDistance<fcl::RSSd>(sphere, 102, "icosphere, RSS", &compared, &overlapping, &fcl_compared);
  compareMeshDistance<fcl::kIOSd>(sphere, 103, "icosphere, kIOS", &compared, &overlapping, &fcl_compared);
  compareMeshDistance<fcl::OBBd>(sphere, 104, "icosphere, OBB", &compared, &overlapping, &fcl_compared);
  compareMeshDistance<fcl::AABBd>(sphere, 105, "icosphere, AABB", &compared, &overlapping, &fcl_compared);
  compareMeshDistance<fcl::KDOPd<16>>(sphere, 106, "icosphere, KDOP16", &compared, &overlapping, &fcl_compared);
  compareMeshDistance<fcl::KDOPd<24>>(sphere, 107, "icosphere, KDOP24", &compared, &overlapping, &fcl_compared);
  compareMeshDistance<fcl::OBBRSSd>(box, 108, "box mesh, OBBRSS", &compared, &overlapping, &fcl_compared);
  compareMeshDistance<fcl::AABBd>(box, 109, "box mesh, AABB", &compared, &overlapping, &fcl_compared);
  // Degenerate triangles (a repeated vertex: a segment; all three: a point), as meshes carry them.
  Mesh degenerate = box;
  degenerate.t.emplace_back(0, 0, 1);
  degenerate.t.emplace_back(2, 2, 2);
  compareMeshDistance<fcl::OBBRSSd>(degenerate, 110, "box mesh with degenerate triangles, OBBRSS", &compared,
                                    &overlapping, &fcl_compared);
  compareMeshDistance<fcl::AABBd>(degenerate, 111, "box mesh with degenerate triangles, AABB", &compared,
                                  &overlapping, &fcl_compared);
  std::printf("[ info ] own mesh distance vs brute force: %zu queries (%zu shape poses overlapping the mesh), %zu "
              "also against FCL's traversal\n",
              compared, overlapping, fcl_compared);
  EXPECT_GT(overlapping, 10u);  // both regimes are exercised
  EXPECT_GT(fcl_compared, compared / 4);
}

/// Bad input through the own mesh distance traversal, far from every triangle: an invalid
/// ellipsoid, or a scaled pose of a mesh with oriented nodes, throws std::invalid_argument naming
/// it; an AABB mesh takes any finite affine pose (FCL has no distance for AABB meshes at all).
TEST(ExactBvhMesh, OwnDistanceTraversalRejectsBadInput) {
  const Mesh mesh = icosphere(1.0, 2);
  const auto obbrss = buildModel<fcl::OBBRSSd>(mesh);
  const auto aabb = buildModel<fcl::AABBd>(mesh);
  const fcl::Transform3d far = test::makePose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(50, 50, 50));
  const fcl::Transform3d mesh_pose = fcl::Transform3d::Identity();
  fcl::Transform3d mesh_scaled = mesh_pose;
  mesh_scaled.linear() *= 1.1;
  const fcl::Ellipsoidd good(0.2, 0.3, 0.4);
  const fcl::Ellipsoidd negative(0.2, -0.3, 0.4);
  const fcl::Ellipsoidd not_a_number(0.2, std::numeric_limits<double>::quiet_NaN(), 0.4);
  for (const fcl::CollisionGeometryd* m : {static_cast<const fcl::CollisionGeometryd*>(obbrss.get()),
                                           static_cast<const fcl::CollisionGeometryd*>(aabb.get())}) {
    expectDistanceThrowsNaming(m, mesh_pose, &negative, far, "radius");
    expectDistanceThrowsNaming(m, mesh_pose, &not_a_number, far, "radius");
    fcl::Transform3d shape_scaled = far;
    shape_scaled.linear() *= 1.1;
    expectDistanceThrowsNaming(m, mesh_pose, &good, shape_scaled, "rotation");
  }
  expectDistanceThrowsNaming(obbrss.get(), mesh_scaled, &good, far, "rotation of the mesh's pose");
  // The AABB mesh under the scaled pose: the distance to the scaled icosphere (radius 1.1 about
  // the origin, up to its facets) from the far ellipsoid, within its extent.
  fcl::DistanceResultd r;
  const double d = fcl_quadric::distance(aabb.get(), mesh_scaled, &good, far, fcl::DistanceRequestd(true), r);
  const double centre_distance = far.translation().norm();
  EXPECT_GT(d, centre_distance - 1.1 - 0.4);
  EXPECT_LT(d, centre_distance - 1.0 - 0.2);
  EXPECT_EQ(r.o1, aabb.get());
}

/// Bad input through the own mesh traversal: an invalid ellipsoid or sphere, or a mesh pose
/// that is not rigid, throws std::invalid_argument even where no triangle would be reached,
/// naming the bad value.
TEST(ExactBvhMesh, OwnTraversalRejectsBadInputWhereNoTriangleIsReached) {
  const Mesh mesh = icosphere(1.0, 2);
  const auto model = buildModel<fcl::OBBRSSd>(mesh);
  const fcl::Transform3d far = test::makePose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(50, 50, 50));
  const fcl::Transform3d mesh_pose = fcl::Transform3d::Identity();
  {
    const fcl::Ellipsoidd good(0.2, 0.3, 0.4);
    fcl::CollisionResultd r;
    EXPECT_EQ(fcl_quadric::collide(model.get(), mesh_pose, &good, far, fcl::CollisionRequestd(), r), 0u);
  }

  const fcl::Ellipsoidd negative(0.2, -0.3, 0.4);
  expectCollideThrowsNaming(model.get(), mesh_pose, &negative, far, "radius");
  const fcl::Ellipsoidd not_a_number(0.2, std::numeric_limits<double>::quiet_NaN(), 0.4);
  expectCollideThrowsNaming(model.get(), mesh_pose, &not_a_number, far, "radius");
  const fcl::Sphered bad_sphere(-1.0);
  expectCollideThrowsNaming(model.get(), mesh_pose, &bad_sphere, far, "radius");
  fcl::Transform3d scaled = far;
  scaled.linear() *= 1.1;
  const fcl::Ellipsoidd good(0.2, 0.3, 0.4);
  expectCollideThrowsNaming(model.get(), mesh_pose, &good, scaled, "rotation");
  fcl::Transform3d mesh_scaled = mesh_pose;
  mesh_scaled.linear() *= 1.1;  // a scaled mesh pose: not rigid
  expectCollideThrowsNaming(model.get(), mesh_scaled, &good, far, "rotation of the mesh's pose");
  const auto rss = buildModel<fcl::RSSd>(mesh);
  expectCollideThrowsNaming(rss.get(), mesh_scaled, &good, far, "rotation of the mesh's pose");

  // Axis-aligned nodes: any finite affine mesh pose is accepted, as FCL does (compared with FCL
  // above); a non-finite one throws (fcl_quadric::collide checks both poses first, naming the
  // argument), even far from the shape, and so does a bad shape.
  const auto aabb = buildModel<fcl::AABBd>(mesh);
  {
    fcl::CollisionResultd r;
    EXPECT_EQ(fcl_quadric::collide(aabb.get(), mesh_scaled, &good, far, fcl::CollisionRequestd(), r), 0u);
  }
  expectCollideThrowsNaming(aabb.get(), mesh_pose, &negative, far, "radius");
  expectCollideThrowsNaming(aabb.get(), mesh_pose, &good, scaled, "rotation");
  fcl::Transform3d mesh_nan = mesh_pose;
  mesh_nan.translation()[1] = std::numeric_limits<double>::quiet_NaN();
  expectCollideThrowsNaming(aabb.get(), mesh_nan, &good, far, "is not finite");
  fcl::Transform3d mesh_inf = mesh_pose;
  mesh_inf.linear()(2, 0) = std::numeric_limits<double>::infinity();
  expectCollideThrowsNaming(aabb.get(), mesh_inf, &good, far, "is not finite");
}


}  // namespace
}  // namespace octree_mesh_test
}  // namespace fcl_quadric
