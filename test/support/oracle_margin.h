#pragma once
// When the exact oracle's answer is "clear": the tolerance band of the property checks of the
// stress suite and the fuzz targets (docs/reliability.md, "Tolerance band").
#include <algorithm>
#include <cmath>
#include <optional>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/tolerances.h"
#include "support/exact_oracle.h"

namespace fcl_quadric {
namespace test {

/// The same ellipsoid with every radius multiplied by `factor`, if still a valid Ellipsoid.
inline std::optional<Ellipsoid> scaledRadii(const Ellipsoid& e, double factor) {
  const Eigen::Vector3d r = e.radii() * factor;
  if (!(r.minCoeff() >= tolerance::kMinRadius && r.maxCoeff() <= tolerance::kMaxLength)) return std::nullopt;
  return Ellipsoid(r, e.rotation(), e.center());
}

/// The exact answer (true: the solids collide) when it is clear by a relative margin `delta`:
/// both ellipsoids grown by (1 + delta) are still exactly separate (-> false), or both shrunk by
/// (1 - delta) still exactly collide (-> true). Growing both only adds contact, so either outcome
/// fixes the exact answer of the original pair and of every configuration within the margin.
/// Within the margin, or for magnitudes outside [1e-30, 1e30] (kept out so that one GMP
/// evaluation stays fast), nullopt.
inline std::optional<bool> clearExactCollision(const Ellipsoid& a, const Ellipsoid& b, double delta) {
  auto moderate = [](const Ellipsoid& e) {
    return e.radii().minCoeff() >= 1e-30 && e.radii().maxCoeff() <= 1e30 && e.center().cwiseAbs().maxCoeff() <= 1e30;
  };
  if (!moderate(a) || !moderate(b) || !(delta < 0.5)) return std::nullopt;
  const auto ga = scaledRadii(a, 1 + delta), gb = scaledRadii(b, 1 + delta);
  if (ga && gb && exactClassify(*ga, *gb) == Separation::Separated) return false;
  const auto sa = scaledRadii(a, 1 - delta), sb = scaledRadii(b, 1 - delta);
  if (sa && sb && exactClassify(*sa, *sb) != Separation::Separated) return true;
  return std::nullopt;
}

/// The relative margin within which a configuration computed in double (a rigid transform of
/// both ellipsoids, a world ellipsoid evaluated from a motion) may legitimately flip: rounding
/// moves points by a few ulps of the coordinates, ~1e-15 (|p_a| + |p_b| + r_max + extra), which
/// must stay small against delta * r_min. Never below 1e-9, the relative gap down to which
/// docs/tolerances.md reports zero misclassifications against the oracle.
inline double rigidMargin(const Ellipsoid& a, const Ellipsoid& b, double extra_length = 0.0) {
  const double len = a.center().norm() + b.center().norm() + a.maxRadius() + b.maxRadius() + extra_length;
  const double rmin = std::min(a.radii().minCoeff(), b.radii().minCoeff());
  return std::max(1e-9, 1e-13 * len / rmin);
}

}  // namespace test
}  // namespace fcl_quadric
