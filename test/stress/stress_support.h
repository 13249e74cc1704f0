#pragma once
// Bookkeeping of the numerical stress suite (docs/reliability.md): counts cases, cases the oracle
// judges (clear outside the tolerance band), disagreements, and the slowest single query (the
// time guard: every loop of the library is capped, so no query may take long).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <string>

namespace fcl_quadric {
namespace test {

/// Wall-clock limit of one query (a classification, a signed distance or a CCD solve), generous
/// enough for sanitizer builds on a loaded 2-core machine (a CCD solve of flat bodies far from the
/// origin took 24 s under ASan at load 8): an uncapped loop would exceed it by far.
constexpr double kQuerySecondsLimit = 120.0;

struct StressCounts {
  std::string name;
  long cases = 0;
  long judged = 0;  ///< the oracle's answer is clear outside the tolerance band
  long disagreements = 0;  ///< a certified answer (separate / overlapping) the oracle contradicts
  long conservative = 0;   ///< Touching (contact) where the oracle is clearly separate: errs safe
  double slowest = 0.0;  ///< seconds

  explicit StressCounts(std::string n) : name(std::move(n)) {}
  ~StressCounts() {
    // One line per test, collected by docs/reliability.md ("stress: NAME cases judged disagreements").
    std::cout << "stress: " << name << " cases=" << cases << " judged=" << judged << " disagreements=" << disagreements << " conservative=" << conservative
              << " slowest=" << slowest << "s" << std::endl;
  }

  /// Times f(), records the slowest, and fails the test if one query exceeds the limit.
  template <typename F>
  auto timed(F f) -> decltype(f()) {
    const auto t0 = std::chrono::steady_clock::now();
    auto r = f();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    slowest = std::max(slowest, s);
    EXPECT_LT(s, kQuerySecondsLimit) << name << ": one query took " << s << " s";
    return r;
  }
};

}  // namespace test
}  // namespace fcl_quadric
