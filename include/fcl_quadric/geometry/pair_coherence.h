#pragma once
/// \file pair_coherence.h
/// Inter-frame coherence for one ellipsoid pair (EECD: Wang et al. 2004 §4, Choi 2008 §4.3):
/// keep the last separating plane and test it first on the next frame.

#include <cstdint>
#include <optional>

#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/separating_plane.h"

namespace fcl_quadric {

/// Per-pair state. Not thread-safe: one object per pair per thread (the FCL-level pair cache of
/// a later layer owns these). Cheap to copy.
class PairCoherence {
 public:
  /// Classify (a, b), using and refreshing the candidate plane:
  ///  1. if a candidate plane exists and CachedPlane::separates() certifies it (the margins of
  ///     planeSeparates()), report Separated;
  ///  2. else run classifyEllipsoids(); if Separated, compute a new plane for the next frame.
  /// The answer is always identical to classifyEllipsoids(a, b).status except that a certified
  /// plane short-cuts the work (a plane is only trusted when it provably separates).
  /// Never throws for valid Ellipsoid objects.
  Separation query(const Ellipsoid& a, const Ellipsoid& b) {
    ++queries_;  // the plane hits are counted as queries less full tests: one store on this path
    if (candidate_.separates(a, b)) return Separation::Separated;  // false for the empty record
    ++full_tests_;
    return classifyAndRemember(a, b);
  }

  /// The plane the next query tries first (the certificate's unit normal, placed midway by
  /// planeWithNormal()), or std::nullopt.
  std::optional<Plane> candidate() const {
    return candidate_.empty() ? std::nullopt : std::optional<Plane>(candidate_.plane());
  }
  void reset() { candidate_ = CachedPlane(); }

  std::uint64_t queries() const { return queries_; }
  std::uint64_t planeHits() const { return queries_ - full_tests_; }

 private:
  /// Step 2 of query(): the full classification, keeping a new (finite) plane if Separated.
  Separation classifyAndRemember(const Ellipsoid& a, const Ellipsoid& b);

  CachedPlane candidate_;  ///< empty when there is none
  std::uint64_t queries_ = 0;
  std::uint64_t full_tests_ = 0;  ///< queries the plane did not answer
};

}  // namespace fcl_quadric
