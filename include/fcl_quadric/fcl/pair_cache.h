#pragma once
/// \file pair_cache.h
/// Inter-frame coherence across broad-phase calls (Wang et al. 2004 §4, Choi 2008 §4.3): for each
/// pair of CollisionObjects whose geometries are ellipsoids or spheres, keep the last separating
/// plane and test it first in the next frame.
///
/// Usage with any fcl::BroadPhaseCollisionManager, once per frame:
///   fcl_quadric::PairCache cache;                       // lives across frames
///   fcl_quadric::CoherentCollisionData data(&cache);     // request/result as DefaultCollisionData
///   manager.update();
///   manager.collide(&data, fcl_quadric::coherentCollisionFunction);
///
/// Correctness never depends on the cache: a cached plane is used only when planeSeparates()
/// certifies it for the current poses and the current shape parameters (read from the geometry at
/// every query, so a radius edited in place is seen), so a stale entry (moved, resized or deleted
/// object, a recycled address) can only cost a miss. Entries are keyed by the two object
/// pointers; invalidate(o) drops the entries of an object you unregister or destroy, to bound
/// memory, and entries whose geometry pointer changed are replaced on their next use.
///
/// Threads: a PairCache is not thread-safe; use one per thread (e.g. one per manager that a single
/// thread queries). The solver and the front doors themselves are stateless and thread-safe.

#include <cstddef>
#include <cstdint>
#include <unordered_map>

#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/narrowphase/collision_object.h>

#include "fcl_quadric/geometry/separating_plane.h"

namespace fcl_quadric {

class PairCache {
 public:
  /// FCL-semantics collision query of o1 and o2 (as fcl_quadric::collide) that first tries the
  /// pair's cached separating plane. Pairs that are not both ellipsoid/sphere go straight to
  /// fcl_quadric::collide. \return the number of contacts added to `result`.
  /// \throws std::invalid_argument as fcl_quadric::collide.
  std::size_t collide(const fcl::CollisionObject<double>* o1, const fcl::CollisionObject<double>* o2,
                      const fcl::CollisionRequest<double>& request, fcl::CollisionResult<double>& result);

  /// Drop every entry involving o (call when o is unregistered or destroyed).
  void invalidate(const fcl::CollisionObject<double>* o);
  void clear() { entries_.clear(); }
  std::size_t size() const { return entries_.size(); }

  std::uint64_t queries() const { return queries_; }      ///< ellipsoid/sphere pair queries
  std::uint64_t planeHits() const { return plane_hits_; }  ///< answered by a cached plane

 private:
  struct Key {
    const void* a;
    const void* b;
    bool operator==(const Key& o) const { return a == o.a && b == o.b; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      const auto x = reinterpret_cast<std::uintptr_t>(k.a), y = reinterpret_cast<std::uintptr_t>(k.b);
      return std::hash<std::uintptr_t>()(x * 0x9E3779B97F4A7C15ull ^ (y + 0x7F4A7C15ull + (x << 6) + (x >> 2)));
    }
  };
  struct Entry {
    CachedPlane plane;  ///< first object (key.a) on the negative side
    const void* geometry_a;
    const void* geometry_b;
  };
  std::unordered_map<Key, Entry, KeyHash> entries_;
  std::uint64_t queries_ = 0;
  std::uint64_t plane_hits_ = 0;
};

/// fcl::DefaultCollisionData plus the cache to use.
struct CoherentCollisionData {
  explicit CoherentCollisionData(PairCache* c) : cache(c) {}
  fcl::CollisionRequest<double> request;
  fcl::CollisionResult<double> result;
  bool done = false;
  PairCache* cache;
};

/// Broad-phase callback: FCL's DefaultCollisionFunction with PairCache::collide. `data` must
/// point to a CoherentCollisionData with a non-null cache. \throws std::invalid_argument otherwise.
bool coherentCollisionFunction(fcl::CollisionObject<double>* o1, fcl::CollisionObject<double>* o2, void* data);

}  // namespace fcl_quadric
