#pragma once
// Private: the pieces the front doors' quadric-shape dispatch works on (quadric_shape_dispatch.cpp
// for collide and distance, distance_lower_bound.cpp for the certified bounds): FCL primitives and
// triangles as quadric regions, the convex support of a geometry, and the traversals of a BVH
// mesh's hierarchy and an OcTree's cells. docs/fcl_integration.md section 9.
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <queue>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>
#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>

#include "fcl/mesh_node_box.h"
#include "fcl_quadric/geometry/convex_support.h"
#include "fcl_quadric/geometry/quadric_region.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace detail {

/// A solid in its local frame with its local AABB (none: unbounded). `thin`: no interior (a
/// triangle), so the search stops at the first undecided box (contact within the band).
struct LocalSolid {
  QuadricRegion region;
  std::optional<Box3> box;
  bool thin = false;
  /// Set for FCL spheres and ellipsoids: the small-ellipsoid filter applies (collidePair).
  std::optional<Eigen::Vector3d> ellipsoid_radii = std::nullopt;
};

/// An axis-aligned box (mesh frame) that contains a BVH node's bounding volume: exact for AABB and
/// a k-DOP's axis slabs, the axis-aligned box of the node's oriented box (mesh_node_box.h) for
/// OBB, OBBRSS, kIOS and RSS. Culling needs only a superset.
inline Box3 obbBox(const fcl::OBB<double>& o) {
  const Eigen::Vector3d h = o.axis.cwiseAbs() * o.extent;
  return Box3{o.To - h, o.To + h};
}
template <typename BV>
Box3 nodeBox(const BV& bv) {
  if constexpr (NodeBox<BV>::kOriented) {
    return obbBox(NodeBox<BV>::box(bv));
  } else {
    Box3 b;
    NodeBox<BV>::corners(bv, &b.lo, &b.hi);
    return b;
  }
}

/// The shape's local bounding box posed in the mesh frame: the columns of `axes` are its axes.
struct PosedBox {
  Eigen::Matrix3d axes;
  Eigen::Vector3d center, half;
};

inline bool boxesOverlap(const Box3& a, const Box3& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

/// Euclidean gap between two boxes (0 when they overlap).
inline double boxGap(const Box3& a, const Box3& b) { return (a.lo - b.hi).cwiseMax(b.lo - a.hi).cwiseMax(0.0).norm(); }

/// Calls f(mesh) with g as its BVHModel type (the eight BV types FCL instantiates); false if g is
/// not a BVH mesh. Dispatched on the node type with a static_cast, as FCL's own tables do: a
/// dynamic_cast per candidate type would run on every query of every quadric shape.
template <typename F>
bool withMesh(const fcl::CollisionGeometry<double>* g, F&& f) {
  if (g->getObjectType() != fcl::OT_BVH) return false;
  switch (g->getNodeType()) {
    case fcl::BV_OBBRSS: f(static_cast<const fcl::BVHModel<fcl::OBBRSS<double>>&>(*g)); return true;
    case fcl::BV_OBB: f(static_cast<const fcl::BVHModel<fcl::OBB<double>>&>(*g)); return true;
    case fcl::BV_RSS: f(static_cast<const fcl::BVHModel<fcl::RSS<double>>&>(*g)); return true;
    case fcl::BV_AABB: f(static_cast<const fcl::BVHModel<fcl::AABB<double>>&>(*g)); return true;
    case fcl::BV_kIOS: f(static_cast<const fcl::BVHModel<fcl::kIOS<double>>&>(*g)); return true;
    case fcl::BV_KDOP16: f(static_cast<const fcl::BVHModel<fcl::KDOP<double, 16>>&>(*g)); return true;
    case fcl::BV_KDOP18: f(static_cast<const fcl::BVHModel<fcl::KDOP<double, 18>>&>(*g)); return true;
    case fcl::BV_KDOP24: f(static_cast<const fcl::BVHModel<fcl::KDOP<double, 24>>&>(*g)); return true;
    default: return false;
  }
}

/// The feature of a triangle a b c whose relative interior holds a point (closestPointOnTriangle).
enum class TriangleFeature { VertexA, VertexB, VertexC, EdgeAB, EdgeBC, EdgeCA, Face };

/// The point of the triangle a b c nearest to x (Ericson, Real-Time Collision Detection §5.1.5),
/// up to rounding, and (if `feature` is given) the feature it lies on, by Ericson's Voronoi
/// regions. A degenerate triangle (a repeated vertex) returns one of its vertices where a
/// division would be 0 / 0. (Used to pick a direction for a traversal's lower bound, and to
/// place and check the refined witnesses of a triangle.)
inline Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                              const Eigen::Vector3d& c, TriangleFeature* feature = nullptr) {
  TriangleFeature unused;
  TriangleFeature& f = feature ? *feature : unused;
  const Eigen::Vector3d ab = b - a, ac = c - a, ax = x - a;
  const double d1 = ab.dot(ax), d2 = ac.dot(ax);
  f = TriangleFeature::VertexA;
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bx = x - b;
  const double d3 = ab.dot(bx), d4 = ac.dot(bx);
  f = TriangleFeature::VertexB;
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    f = d1 - d3 > 0.0 ? TriangleFeature::EdgeAB : TriangleFeature::VertexA;
    return d1 - d3 > 0.0 ? Eigen::Vector3d(a + (d1 / (d1 - d3)) * ab) : a;
  }
  const Eigen::Vector3d cx = x - c;
  const double d5 = ab.dot(cx), d6 = ac.dot(cx);
  f = TriangleFeature::VertexC;
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    f = d2 - d6 > 0.0 ? TriangleFeature::EdgeCA : TriangleFeature::VertexA;
    return d2 - d6 > 0.0 ? Eigen::Vector3d(a + (d2 / (d2 - d6)) * ac) : a;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double den = (d4 - d3) + (d5 - d6);
    f = den > 0.0 ? TriangleFeature::EdgeBC : TriangleFeature::VertexB;
    return den > 0.0 ? Eigen::Vector3d(b + ((d4 - d3) / den) * (c - b)) : b;
  }
  const double denom = va + vb + vc;
  f = denom > 0.0 ? TriangleFeature::Face : TriangleFeature::VertexA;
  if (!(denom > 0.0)) return a;
  return a + (vb / denom) * ab + (vc / denom) * ac;
}

inline bool isMeshOrOcTree(const fcl::CollisionGeometry<double>* g) {
  return g->getObjectType() == fcl::OT_BVH || g->getObjectType() == fcl::OT_OCTREE;
}

/// A lower bound of the distance between the box of axes A, centre c and half-extents e and the
/// posed box s: the largest gap along the six face normals (each a unit axis: a projection does
/// not increase distances), less tolerance::kTraversalPruningPadding of the coordinates' scale
/// for the rounding; 0 when none is positive.
inline double boxesGap(const Eigen::Matrix3d& A, const Eigen::Vector3d& c, const Eigen::Vector3d& e,
                       const PosedBox& s) {
  const Eigen::Vector3d d = c - s.center;
  const double pad = tolerance::kTraversalPruningPadding *
                     (s.center.cwiseAbs().maxCoeff() + s.half.maxCoeff() + c.cwiseAbs().maxCoeff() + e.maxCoeff());
  const Eigen::Matrix3d B = (s.axes.transpose() * A).cwiseAbs();  // |shape axis j . node axis k|
  const Eigen::Vector3d gap_node = (A.transpose() * d).cwiseAbs() - e - B.transpose() * s.half;
  const Eigen::Vector3d gap_shape = (s.axes.transpose() * d).cwiseAbs() - s.half - B * e;
  return std::max(0.0, std::max(gap_node.maxCoeff(), gap_shape.maxCoeff()) - pad);
}

/// False when the box of axes A (columns, orthonormal), centre c and half-extents e is certainly
/// apart from the posed box s: a separating axis among the six face normals, i.e. boxesGap() > 0
/// (FCL's OBB test also tries the nine edge directions; without them the test prunes a little
/// less, never wrongly).
inline bool boxesMayMeet(const Eigen::Matrix3d& A, const Eigen::Vector3d& c, const Eigen::Vector3d& e,
                         const PosedBox& s) {
  return !(boxesGap(A, c, e, s) > 0.0);
}

/// The node's box as axes, centre and half-extents: its own box for oriented BVs, its axis-aligned
/// box (identity axes) otherwise; f(A, c, e) receives them.
template <typename BV, typename F>
auto withNodeBox(const BV& bv, F&& f) {
  if constexpr (NodeBox<BV>::kOriented) {
    const auto& box = NodeBox<BV>::box(bv);
    return f(box.axis, box.To, box.extent);
  } else {
    Eigen::Vector3d lo, hi;
    NodeBox<BV>::corners(bv, &lo, &hi);
    return f(Eigen::Matrix3d::Identity(), 0.5 * (lo + hi), 0.5 * (hi - lo));
  }
}

/// Does the node's BV meet the query: with the shape's posed box `shape`, the separating-axis test
/// of the node's box (oriented or axis-aligned, mesh_node_box.h) against it; otherwise the node's
/// axis-aligned box against `query` (a swept box, say).
template <typename BV>
bool nodeMeets(const BV& bv, const Box3& query, const PosedBox* shape) {
  if (shape == nullptr) return boxesOverlap(nodeBox(bv), query);
  return withNodeBox(bv, [&](const Eigen::Matrix3d& A, const Eigen::Vector3d& c, const Eigen::Vector3d& e) {
    return boxesMayMeet(A, c, e, *shape);
  });
}

/// A lower bound of the distance from the shape to the node's BV: the gap between the node's
/// axis-aligned box and `query` (the shape's box in the mesh frame), and with the shape's posed
/// box `shape`, the larger of that and the six-axis gap boxesGap().
template <typename BV>
double nodeGap(const BV& bv, const Box3& query, const PosedBox* shape) {
  const double aligned = boxGap(nodeBox(bv), query);
  if (shape == nullptr) return aligned;
  return std::max(aligned, withNodeBox(bv, [&](const Eigen::Matrix3d& A, const Eigen::Vector3d& c,
                                              const Eigen::Vector3d& e) { return boxesGap(A, c, e, *shape); }));
}

/// Depth-first over the BVH: visit(triangle index, p0, p1, p2) for each triangle whose leaf BV
/// meets `query` (mesh frame), or, if given, `shape` (the shape's box posed in the mesh frame),
/// until visit returns true. A model without a hierarchy (no BVs) is walked triangle by triangle.
template <typename BV, typename Visit>
void visitMeshTriangles(const fcl::BVHModel<BV>& m, const Box3& query, const PosedBox* shape, Visit&& visit) {
  auto tri = [&](int t) {
    const fcl::Triangle& f = m.tri_indices[t];
    return visit(t, m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]]);
  };
  if (m.getNumBVs() == 0) {
    for (int t = 0; t < m.num_tris; ++t)
      if (tri(t)) return;
    return;
  }
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    const fcl::BVNode<BV>& node = m.getBV(id);
    if (!nodeMeets(node.bv, query, shape)) continue;
    if (node.isLeaf()) {
      if (tri(node.primitiveId())) return;
    } else {
      stack.push_back(node.rightChild());
      stack.push_back(node.leftChild());
    }
  }
}

/// Best first over the BVH: visit(t, p0, p1, p2) returns the triangle's distance; the search ends
/// at the first node whose box gap to `query` (mesh frame) is positive and not below the best
/// distance so far (nodes whose boxes meet it are all visited: they may hold a deeper overlap).
/// stop(best) ends it early. `best` starts at `cap` (nodes not closer than cap are skipped).
template <typename BV, typename Visit, typename Stop>
void nearestMeshTriangles(const fcl::BVHModel<BV>& m, const Box3& query, const PosedBox* shape, Visit&& visit,
                          Stop&& stop, double cap = std::numeric_limits<double>::infinity()) {
  double best = cap;
  auto tri = [&](int t) {
    const fcl::Triangle& f = m.tri_indices[t];
    best = std::min(best, visit(t, m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]]));
    return stop(best);
  };
  if (m.getNumBVs() == 0) {
    for (int t = 0; t < m.num_tris; ++t)
      if (tri(t)) return;
    return;
  }
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  queue.emplace(nodeGap(m.getBV(0).bv, query, shape), 0);
  while (!queue.empty()) {
    const auto [gap, id] = queue.top();
    queue.pop();
    if (gap > 0.0 && gap >= best) break;  // (boxes that meet may hold a deeper overlap)
    const fcl::BVNode<BV>& node = m.getBV(id);
    if (node.isLeaf()) {
      if (tri(node.primitiveId())) return;
    } else {
      for (int child : {node.leftChild(), node.rightChild()})
        queue.emplace(nodeGap(m.getBV(child).bv, query, shape), child);
    }
  }
}

/// The eight children of an octree cell box (FCL's computeChildBV order: bit 0 x, bit 1 y, bit 2 z).
inline Box3 octreeChildBox(const Box3& b, unsigned i) {
  const Eigen::Vector3d mid = 0.5 * (b.lo + b.hi);
  Box3 c = b;
  for (int k = 0; k < 3; ++k) {
    if (i & (1u << k)) c.lo[k] = mid[k];
    else c.hi[k] = mid[k];
  }
  return c;
}

/// The occupied leaves of an OcTree as (centre, half width) pairs, in the order of a traversal
/// that skips cells whose box misses `query` (tree frame) or, if given, `shape` (the shape's posed
/// box, boxesMayMeet()); visit returns true to stop. Leaves and occupancy as
/// fcl::OcTree::toBoxes (occupied = fcl::OcTree::isNodeOccupied).
template <typename Visit>
void visitOcTreeLeaves(const fcl::OcTree<double>& tree, const Box3& query, const PosedBox* shape, Visit&& visit) {
  const fcl::OcTree<double>::OcTreeNode* root = tree.getRoot();
  if (root == nullptr) return;
  const fcl::AABB<double> rb = tree.getRootBV();
  std::vector<std::pair<const fcl::OcTree<double>::OcTreeNode*, Box3>> stack{{root, Box3{rb.min_, rb.max_}}};
  while (!stack.empty()) {
    const auto [node, box] = stack.back();
    stack.pop_back();
    if (!boxesOverlap(box, query)) continue;
    if (shape && !boxesMayMeet(Eigen::Matrix3d::Identity(), box.center(), box.halfWidth(), *shape)) continue;
    bool leaf = true;
    for (unsigned i = 0; i < 8; ++i) {
      if (!tree.nodeChildExists(node, i)) continue;
      leaf = false;
      stack.emplace_back(tree.getNodeChild(node, i), octreeChildBox(box, i));
    }
    if (leaf && tree.isNodeOccupied(node) && visit(box.center(), box.halfWidth())) return;
  }
}

/// Best first over an OcTree's cells, as nearestMeshTriangles over a BVH: visit(c, h) returns the
/// distance to the occupied leaf of centre c and half widths h (tree frame) and is called for the
/// same leaves as visitOcTreeLeaves() visits with an unbounded query, nearest bound first. A cell's
/// bound is the gap between its box and `query` (the shape's box in the tree frame), and with the
/// shape's posed box `shape`, the larger of that and boxesGap(); the search ends at the first cell
/// whose bound is positive and not below the best distance so far, or when stop(best) holds.
template <typename Visit, typename Stop>
void nearestOcTreeLeaves(const fcl::OcTree<double>& tree, const Box3& query, const PosedBox* shape, Visit&& visit,
                         Stop&& stop, double cap = std::numeric_limits<double>::infinity()) {
  const fcl::OcTree<double>::OcTreeNode* root = tree.getRoot();
  if (root == nullptr) return;
  auto gap = [&](const Box3& b) {
    const double aligned = boxGap(b, query);
    return shape ? std::max(aligned, boxesGap(Eigen::Matrix3d::Identity(), b.center(), b.halfWidth(), *shape))
                 : aligned;
  };
  struct Cell {
    double bound;
    const fcl::OcTree<double>::OcTreeNode* node;
    Box3 box;
    bool operator>(const Cell& o) const { return bound > o.bound; }
  };
  std::priority_queue<Cell, std::vector<Cell>, std::greater<Cell>> queue;
  const fcl::AABB<double> rb = tree.getRootBV();
  const Box3 root_box{rb.min_, rb.max_};
  queue.push({gap(root_box), root, root_box});
  double best = cap;
  while (!queue.empty()) {
    const Cell cell = queue.top();
    queue.pop();
    if (cell.bound > 0.0 && cell.bound >= best) break;  // (cells that meet may hold a deeper overlap)
    bool leaf = true;
    for (unsigned i = 0; i < 8; ++i) {
      if (!tree.nodeChildExists(cell.node, i)) continue;
      leaf = false;
      const Box3 child = octreeChildBox(cell.box, i);
      queue.push({gap(child), tree.getNodeChild(cell.node, i), child});
    }
    if (leaf && tree.isNodeOccupied(cell.node)) {
      best = std::min(best, visit(cell.box.center(), cell.box.halfWidth()));
      if (stop(best)) return;
    }
  }
}

/// The exact bounding box, in the frame (Rf, pf), of the convex piece s posed by (R, p): its six
/// support points along the frame's axes. Box gaps against it prune mesh and octree searches.
inline Box3 supportBoxIn(const ConvexSupport& s, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                         const Eigen::Matrix3d& Rf, const Eigen::Vector3d& pf) {
  Box3 b;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d e = Rf.col(i);  // the frame's axis i in the world
    const Eigen::Vector3d local = R.transpose() * e;
    b.hi[i] = e.dot(R * s.support(local) + p - pf);
    b.lo[i] = e.dot(R * s.support(-local) + p - pf);
  }
  return b;
}

/// A triangle as the region {n.x = d} intersected with its three edge half-spaces (in-plane),
/// with its AABB; none for a zero-area triangle (skipped: documented).
std::optional<LocalSolid> triangleSolid(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2);

/// The axis-aligned box c +- h as six half-spaces.
QuadricRegion boxRegion(const Eigen::Vector3d& c, const Eigen::Vector3d& h);

/// FCL's primitives and the quadric shapes as quadric regions (FCL's local conventions,
/// fcl/geometry/shape/*.h). \throws std::invalid_argument (message starting with `where`, naming
/// `which` and its node type) for any other geometry.
LocalSolid localSolid(const fcl::CollisionGeometry<double>* g, const char* which,
                      const char* where = "fcl_quadric::collide");

/// The static collide of two local solids posed by tf1, tf2 (certified region engine, with the
/// small-ellipsoid filter); adds one contact to result on contact. \return Empty (no contact),
/// Found (a certified common interior point: overlapping) or Undecided (touching within the band).
PointSearch collidePair(const LocalSolid& a, const fcl::Transform3<double>& tf1, const LocalSolid& b,
                 const fcl::Transform3<double>& tf2, const fcl::CollisionGeometry<double>* o1,
                 const fcl::CollisionGeometry<double>* o2, const fcl::CollisionRequest<double>& request,
                 fcl::CollisionResult<double>& result);

/// The radius of a ball about the local origin that the shape contains, for the convex shapes the
/// distance bound can scale (region_distance_bound.h); none otherwise.
std::optional<double> convexInradius(const fcl::CollisionGeometry<double>* g);

/// An FCL convex primitive or a convex quadric shape as a support mapping (local frame); none
/// for any other geometry. \throws std::invalid_argument for an unbounded quadric shape.
std::optional<ConvexSupport> convexSupportOf(const fcl::CollisionGeometry<double>* g, const char* which);

}  // namespace detail
}  // namespace fcl_quadric
