#pragma once
/// \file bench_fcl_support.h
/// Scenes of bench_fcl_scenes.cpp (issue 3's benchmarks of the FCL integration) and of
/// `fcl_quadric bench` (experiments broadphase and octree), built once, outside the timed loops,
/// from fixed seeds:
///  - MovingEllipsoids: n ellipsoids spinning and drifting (reflected at the walls of a cube) in a
///    DynamicAABBTreeCollisionManager; the pose of every object is a function of the frame number.
///    runFrame() runs one frame with one peer's callback, countMoving() counts each peer's wrong
///    pairs against classifyEllipsoids.
///  - terrainOcTree: an octomap::OcTree of a noisy terrain at resolution 0.05 (one column of
///    occupied voxels per cell, down to the lowest neighbour so the surface has no holes).
///  - torusMesh: a tessellated torus as fcl::BVHModel<OBBRSS>, with its triangles kept for the
///    exact oracle.
///  - exact oracles: classifyEllipsoidBox over the occupied leaves of an fcl::OcTree and
///    classifyEllipsoidTriangle over the triangles of a mesh (touching counts as collision).
/// Needs fcl_quadric_fcl (front doors, PairCache) and octomap (through FCL's CMake target).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision_object.h>
#include <octomap/OcTree.h>

#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/pair_cache.h"
#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "random_rotations.h"

namespace fcl_quadric {
namespace bench {

constexpr std::uint64_t kMovingSeed = 2003;
constexpr std::uint64_t kQuerySeed = 31;
constexpr std::size_t kAllContacts = std::size_t{1} << 30;  ///< collect every colliding pair

/// Radii log-uniform in [scale / aspect, scale].
inline Eigen::Vector3d randomRadii(std::mt19937_64& rng, double scale, double aspect) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::Vector3d r;
  for (int i = 0; i < 3; ++i) r[i] = scale * std::pow(aspect, -u(rng));
  return r;
}

inline fcl::Transform3d makePose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

/// The fcl_quadric ellipsoid of an fcl::Ellipsoid posed at X.
inline Ellipsoid ellipsoidOf(const fcl::Ellipsoidd& shape, const fcl::Transform3d& X) {
  return Ellipsoid(shape.radii, X.linear(), X.translation());
}

/// Half extents of the tight axis-aligned box of an ellipsoid.
inline Eigen::Vector3d ellipsoidHalfExtents(const Ellipsoid& e) {
  const Eigen::Matrix3d M = e.rotation() * e.radii().asDiagonal();
  return M.rowwise().norm();
}

/// "1.23 0.98 0.75" from /proc/loadavg (1, 5 and 15 minute load averages), or "unknown".
// ------------------------------------------------------------------------------------------------
// (a) Moving ellipsoids

/// n ellipsoids in the cube [0, side]^3, side = spacing * cbrt(n) (the same density for every n).
/// Object i at frame k: R = AngleAxis(omega_i k, axis_i) R0_i, p = p0_i + k v_i folded back into
/// the cube (reflection at the walls). Radii log-uniform with aspect ratio up to 3, scale
/// U(0.4, 1); drift up to 0.02 and spin up to 0.03 rad per frame.
class MovingEllipsoids {
 public:
  static constexpr double kSpacing = 3.2;

  MovingEllipsoids(std::size_t n, int frames, std::uint64_t seed) : frames_(frames) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    side_ = kSpacing * std::cbrt(static_cast<double>(n));
    for (std::size_t i = 0; i < n; ++i) {
      Motion m;
      m.R0 = randomRotation(rng);
      for (int c = 0; c < 3; ++c) m.p0[c] = side_ * u(rng);
      m.velocity = 0.02 * u(rng) * randomUnitVector(rng);
      m.axis = randomUnitVector(rng);
      m.omega = 0.03 * u(rng);
      motions_.push_back(m);
      shapes_.push_back(std::make_shared<fcl::Ellipsoidd>(randomRadii(rng, 0.4 + 0.6 * u(rng), 3.0)));
      objects_.push_back(std::make_unique<fcl::CollisionObjectd>(shapes_.back(), poseAt(i, 0)));
      index_[shapes_.back().get()] = i;
    }
    std::vector<fcl::CollisionObjectd*> all;
    for (const auto& o : objects_) all.push_back(o.get());
    manager_.registerObjects(all);
    manager_.setup();
  }

  std::size_t size() const { return objects_.size(); }
  int frames() const { return frames_; }
  double side() const { return side_; }
  fcl::DynamicAABBTreeCollisionManagerd& manager() { return manager_; }
  std::size_t indexOf(const fcl::CollisionGeometryd* g) const { return index_.at(g); }

  fcl::Transform3d poseAt(std::size_t i, int k) const {
    const Motion& m = motions_[i];
    Eigen::Vector3d p = m.p0 + static_cast<double>(k) * m.velocity;
    for (int c = 0; c < 3; ++c) {  // reflect into [0, side]
      double t = std::fmod(p[c], 2.0 * side_);
      if (t < 0.0) t += 2.0 * side_;
      p[c] = t <= side_ ? t : 2.0 * side_ - t;
    }
    return makePose(Eigen::AngleAxisd(m.omega * k, m.axis).toRotationMatrix() * m.R0, p);
  }

  /// Poses and AABBs of frame k, then manager.update(): the per-frame work every peer shares.
  void setFrame(int k) {
    for (std::size_t i = 0; i < objects_.size(); ++i) {
      objects_[i]->setTransform(poseAt(i, k));
      objects_[i]->computeAABB();
    }
    manager_.update();
  }

  /// Ellipsoid i as posed now (after setFrame).
  Ellipsoid ellipsoid(std::size_t i) const { return ellipsoidOf(*shapes_[i], objects_[i]->getTransform()); }

 private:
  struct Motion {
    Eigen::Matrix3d R0;
    Eigen::Vector3d p0, velocity, axis;
    double omega = 0.0;
  };
  int frames_;
  double side_ = 0.0;
  std::vector<Motion> motions_;
  std::vector<std::shared_ptr<fcl::Ellipsoidd>> shapes_;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects_;
  std::unordered_map<const fcl::CollisionGeometryd*, std::size_t> index_;
  fcl::DynamicAABBTreeCollisionManagerd manager_;
};


// ------------------------------------------------------------------------------------------------
// (a) Moving ellipsoids: one frame per peer, and the untimed count of each peer's wrong pairs

enum class Peer { kOurs, kPairCache, kStock, kBroadphaseOnly };
inline constexpr Peer kPeers[] = {Peer::kBroadphaseOnly, Peer::kOurs, Peer::kPairCache, Peer::kStock};

inline const char* peerName(Peer p) {
  switch (p) {
    case Peer::kOurs: return "fcl_quadric";
    case Peer::kPairCache: return "pair_cache";
    case Peer::kStock: return "fcl_libccd";
    case Peer::kBroadphaseOnly: return "broadphase_only";
  }
  return "?";
}

inline bool countCandidate(fcl::CollisionObjectd*, fcl::CollisionObjectd*, void* data) {
  ++*static_cast<std::size_t*>(data);
  return false;
}

using ObjectPairs = std::vector<std::pair<fcl::CollisionObjectd*, fcl::CollisionObjectd*>>;

inline bool recordCandidate(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
  static_cast<ObjectPairs*>(data)->emplace_back(a, b);
  return false;
}

/// One frame with one peer's callback; returns the number of contacts (candidate pairs for
/// broadphase_only). `result`, if given, receives the collision result.
inline std::size_t runFrame(MovingEllipsoids& s, int k, Peer peer, PairCache* cache, fcl::CollisionResultd* result = nullptr) {
  s.setFrame(k);
  switch (peer) {
    case Peer::kOurs:
    case Peer::kStock: {
      fcl::DefaultCollisionData<double> data;
      data.request.num_max_contacts = kAllContacts;
      s.manager().collide(&data, peer == Peer::kOurs ? fcl_quadric::defaultCollisionFunction<double>
                                                     : fcl::DefaultCollisionFunction<double>);
      if (result) *result = data.result;
      return data.result.numContacts();
    }
    case Peer::kPairCache: {
      CoherentCollisionData data(cache);
      data.request.num_max_contacts = kAllContacts;
      s.manager().collide(&data, coherentCollisionFunction);
      if (result) *result = data.result;
      return data.result.numContacts();
    }
    case Peer::kBroadphaseOnly: {
      std::size_t candidates = 0;
      s.manager().collide(&candidates, countCandidate);
      return candidates;
    }
  }
  return 0;
}

struct MovingReport {
  std::size_t n = 0;
  int frames = 0;
  double side = 0.0;
  std::size_t candidates = 0, colliding = 0;  ///< sums over frames (colliding: exact)
  /// Per peer (ours, pair_cache, stock): pairs the peer missed / reported wrongly, summed over frames.
  std::size_t misses[3] = {0, 0, 0}, false_hits[3] = {0, 0, 0};
  std::uint64_t cache_queries = 0, cache_hits = 0;
};

using IndexPairs = std::vector<std::pair<std::size_t, std::size_t>>;

inline IndexPairs sortedPairs(const MovingEllipsoids& s, const fcl::CollisionResultd& r) {
  IndexPairs out;
  for (std::size_t k = 0; k < r.numContacts(); ++k) {
    std::size_t a = s.indexOf(r.getContact(k).o1), b = s.indexOf(r.getContact(k).o2);
    out.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

inline std::size_t countMissing(const IndexPairs& from, const IndexPairs& in) {
  IndexPairs d;
  std::set_difference(from.begin(), from.end(), in.begin(), in.end(), std::back_inserter(d));
  return d.size();
}

/// Frame k (set here) and its exactly colliding pairs (i < j, sorted): classifyEllipsoids on the
/// manager's candidate pairs; touching counts as collision. Also returns the candidate count.
inline IndexPairs exactCollidingPairs(MovingEllipsoids& s, int k, std::size_t* candidate_count = nullptr) {
  s.setFrame(k);
  ObjectPairs candidates;
  s.manager().collide(&candidates, recordCandidate);
  if (candidate_count) *candidate_count = candidates.size();
  IndexPairs exact;
  for (const auto& [a, b] : candidates) {
    const std::size_t i = s.indexOf(a->collisionGeometry().get()), j = s.indexOf(b->collisionGeometry().get());
    if (classifyEllipsoids(s.ellipsoid(i), s.ellipsoid(j)).status != Separation::Separated)
      exact.emplace_back(std::min(i, j), std::max(i, j));
  }
  std::sort(exact.begin(), exact.end());
  return exact;
}

/// Untimed: every frame, each peer's manager result against classifyEllipsoids on the candidates.
inline MovingReport countMoving(MovingEllipsoids& s) {
  MovingReport rep;
  rep.n = s.size();
  rep.frames = s.frames();
  rep.side = s.side();
  PairCache cache;
  for (int k = 0; k < s.frames(); ++k) {
    std::size_t candidates = 0;
    const IndexPairs exact = exactCollidingPairs(s, k, &candidates);
    rep.candidates += candidates;
    rep.colliding += exact.size();
    const Peer peers[3] = {Peer::kOurs, Peer::kPairCache, Peer::kStock};
    for (int p = 0; p < 3; ++p) {
      fcl::CollisionResultd result;
      runFrame(s, k, peers[p], &cache, &result);
      const IndexPairs found = sortedPairs(s, result);
      rep.misses[p] += countMissing(exact, found);
      rep.false_hits[p] += countMissing(found, exact);
    }
  }
  rep.cache_queries = cache.queries();
  rep.cache_hits = cache.planeHits();
  return rep;
}

// ------------------------------------------------------------------------------------------------
// (b) OcTree terrain

/// Height of the terrain at (x, y): smooth hills plus a fixed pseudo-random roughness of up to
/// +-0.06 per 0.05 cell (hashed from the cell, so it is the same for every query).
inline double terrainHeight(double x, double y) {
  const long ix = std::lround(std::floor(x / 0.05)), iy = std::lround(std::floor(y / 0.05));
  std::uint64_t h = static_cast<std::uint64_t>(ix) * 0x9E3779B97F4A7C15ull ^ (static_cast<std::uint64_t>(iy) + 0x632BE59BD9B4E019ull);
  h ^= h >> 29;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 32;
  const double noise = (static_cast<double>(h % 10007) / 10006.0 - 0.5) * 0.12;
  return 0.6 * std::sin(0.45 * x) * std::cos(0.35 * y) + 0.25 * std::sin(1.3 * x + 0.9 * y) + noise;
}

/// Terrain over [-half, half]^2 at `resolution`: in every column the voxels from the lowest of
/// the four neighbouring surface heights up to the column's own height are occupied, so the
/// surface has no holes. Built with lazy evaluation, then the inner nodes are updated and the
/// tree pruned (as a mapping pipeline would leave it).
inline std::shared_ptr<octomap::OcTree> terrainOcTree(double half, double resolution) {
  auto tree = std::make_shared<octomap::OcTree>(resolution);
  const int n = static_cast<int>(std::lround(2.0 * half / resolution));
  auto centre = [&](int i) { return -half + (i + 0.5) * resolution; };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = centre(i), y = centre(j), h = terrainHeight(x, y);
      double low = h;
      for (const auto& d : std::array<std::pair<int, int>, 4>{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}})
        low = std::min(low, terrainHeight(x + d.first * resolution, y + d.second * resolution));
      for (double z = low; z <= h + 0.5 * resolution; z += resolution)
        tree->updateNode(octomap::point3d(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)), true, true);
    }
  }
  tree->updateInnerOccupancy();
  tree->prune();
  return tree;
}

/// The occupied leaves of an fcl::OcTree (as FCL's traversal sees them) in a uniform grid of
/// buckets, for the brute-force oracle.
class LeafBoxes {
 public:
  explicit LeafBoxes(const fcl::OcTreed& tree, double bucket = 0.5) : bucket_(bucket) {
    for (const std::array<double, 6>& b : tree.toBoxes()) {
      boxes_.push_back({Eigen::Vector3d(b[0], b[1], b[2]), 0.5 * b[3]});
      lo_ = lo_.cwiseMin(boxes_.back().centre - Eigen::Vector3d::Constant(boxes_.back().half));
      hi_ = hi_.cwiseMax(boxes_.back().centre + Eigen::Vector3d::Constant(boxes_.back().half));
    }
    for (std::size_t k = 0; k < boxes_.size(); ++k) {
      const Eigen::Vector3d h = Eigen::Vector3d::Constant(boxes_[k].half);
      forCells(boxes_[k].centre - h, boxes_[k].centre + h, [&](long key) { grid_[key].push_back(k); });
    }
  }
  std::size_t size() const { return boxes_.size(); }

  /// Exact: does the ellipsoid touch or overlap an occupied leaf box?
  bool collides(const Ellipsoid& e) const {
    const Eigen::Vector3d h = ellipsoidHalfExtents(e);
    const Eigen::Vector3d lo = e.center() - h, hi = e.center() + h;
    bool hit = false;
    forCells(lo, hi, [&](long key) {
      if (hit) return;
      const auto it = grid_.find(key);
      if (it == grid_.end()) return;
      for (std::size_t k : it->second) {
        const Box& b = boxes_[k];
        if ((b.centre.array() + b.half < lo.array()).any() || (b.centre.array() - b.half > hi.array()).any()) continue;
        if (classifyEllipsoidBox(e, Eigen::Vector3d::Constant(b.half), Eigen::Matrix3d::Identity(), b.centre).status !=
            Separation::Separated) {
          hit = true;
          return;
        }
      }
    });
    return hit;
  }

 private:
  struct Box {
    Eigen::Vector3d centre;
    double half;
  };
  template <typename F>
  void forCells(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, F f) const {
    const Eigen::Vector3d a = ((lo - lo_) / bucket_).array().floor(), b = ((hi - lo_) / bucket_).array().floor();
    for (long i = std::max(0L, std::lround(a[0])); i <= std::min(kCells - 1, std::lround(b[0])); ++i)
      for (long j = std::max(0L, std::lround(a[1])); j <= std::min(kCells - 1, std::lround(b[1])); ++j)
        for (long k = std::max(0L, std::lround(a[2])); k <= std::min(kCells - 1, std::lround(b[2])); ++k)
          f((i * kCells + j) * kCells + k);
  }
  static constexpr long kCells = 4096;
  double bucket_;
  Eigen::Vector3d lo_ = Eigen::Vector3d::Constant(1e300), hi_ = Eigen::Vector3d::Constant(-1e300);
  std::vector<Box> boxes_;
  std::unordered_map<long, std::vector<std::size_t>> grid_;
};

/// Query ellipsoids near the terrain of terrainOcTree(half, ...): (x, y) uniform inside the map,
/// radii scale U(0.1, 0.5) with aspect up to 3, random rotation, centre at the terrain height plus
/// t times the ellipsoid's vertical half extent, t ~ U(-0.5, 2). Seed kQuerySeed.
inline std::vector<Ellipsoid> terrainQueries(double terrain_half, std::size_t n) {
  std::vector<Ellipsoid> out;
  std::mt19937_64 rng(kQuerySeed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double inner = std::max(0.5, terrain_half - 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = inner * (2 * u(rng) - 1), y = inner * (2 * u(rng) - 1);
    const Eigen::Vector3d r = randomRadii(rng, 0.1 + 0.4 * u(rng), 3.0);
    const Eigen::Matrix3d R = randomRotation(rng);
    const double hz = ellipsoidHalfExtents(Ellipsoid(r, R, Eigen::Vector3d::Zero()))[2];
    out.emplace_back(r, R, Eigen::Vector3d(x, y, terrainHeight(x, y) + (2.5 * u(rng) - 0.5) * hz));
  }
  return out;
}

// ------------------------------------------------------------------------------------------------
// (c) Triangle mesh

struct MeshTarget {
  std::vector<fcl::Vector3d> vertices;
  std::vector<fcl::Triangle> triangles;
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> model;
  /// The same triangles with AABB nodes: FCL copies such a model on every query (and rebuilds its
  /// tree unless the pose is the identity); fcl_quadric::collide traverses it in place.
  std::shared_ptr<fcl::BVHModel<fcl::AABBd>> aabb_model;

  /// Exact: does the ellipsoid touch or overlap a triangle (mesh posed at the identity)?
  bool collides(const Ellipsoid& e) const {
    const double reach = e.radii().maxCoeff();
    for (const fcl::Triangle& t : triangles) {
      const Eigen::Vector3d &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
      const double size = std::max({(a - b).norm(), (b - c).norm(), (c - a).norm()});
      if ((a - e.center()).norm() > reach + size) continue;  // cannot touch
      if (classifyEllipsoidTriangle(e, a, b, c).status != Separation::Separated) return true;
    }
    return false;
  }
};

/// Torus around the z axis (major radius R, tube radius r), nu x nv quads split in two.
inline MeshTarget torusMesh(double R, double r, int nu, int nv) {
  MeshTarget m;
  for (int i = 0; i < nu; ++i) {
    const double u = 2.0 * M_PI * i / nu;
    for (int j = 0; j < nv; ++j) {
      const double v = 2.0 * M_PI * j / nv;
      m.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return static_cast<std::size_t>(((i + nu) % nu) * nv + (j + nv) % nv); };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      m.triangles.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      m.triangles.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
  m.model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  m.model->beginModel(static_cast<int>(m.triangles.size()), static_cast<int>(m.vertices.size()));
  m.model->addSubModel(m.vertices, m.triangles);
  m.model->endModel();
  m.model->computeLocalAABB();
  m.aabb_model = std::make_shared<fcl::BVHModel<fcl::AABBd>>();
  m.aabb_model->beginModel(static_cast<int>(m.triangles.size()), static_cast<int>(m.vertices.size()));
  m.aabb_model->addSubModel(m.vertices, m.triangles);
  m.aabb_model->endModel();
  m.aabb_model->computeLocalAABB();
  return m;
}

}  // namespace bench
}  // namespace fcl_quadric
