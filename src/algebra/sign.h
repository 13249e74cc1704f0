#pragma once
/// \file sign.h
/// The sign of a double as -1, 0 or +1, shared by the root-counting sources (Sturm sequences,
/// root isolation). One definition: the core library's unity batches (scripts/ci-sanitizers.sh)
/// compile several sources as one translation unit, where two file-local copies would clash.
/// Internal (src/).

namespace fcl_quadric::detail {

/// -1, 0 or +1; NaN gives 0 (callers reject non-finite input before counting signs).
inline int sign(double v) { return (v > 0.0) - (v < 0.0); }

}  // namespace fcl_quadric::detail
