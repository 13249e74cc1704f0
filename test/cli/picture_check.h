#pragma once
// Helpers of the CLI tests that produce pictures (render_test.cpp, plot_test.cpp): the readers of
// support/picture_files.h plus Google Test expectations.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/picture_files.h"

namespace fcl_quadric {
namespace cli {
namespace test {

/// Runs the CLI with bad arguments and expects exit status 2, nothing on stdout and exactly one
/// error line on stderr (containing `named` when given).
inline void expectBadInput(const std::vector<std::string>& args, const std::string& named = "") {
  const RunResult r = runCli(args);
  std::string joined;
  for (const auto& a : args) joined += a + " ";
  EXPECT_EQ(r.status, kExitBadInput) << joined;
  EXPECT_EQ(r.out, "") << joined;
  ASSERT_FALSE(r.err.empty()) << joined;
  EXPECT_EQ(r.err.rfind("fcl_quadric: error: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  EXPECT_NE(r.err.find(named), std::string::npos) << "should name " << named << ": " << r.err;
}

}  // namespace test
}  // namespace cli
}  // namespace fcl_quadric
