#pragma once
/// \file cli.h
/// Entry point of the fcl_quadric command-line program (commands `check`, `ccd`, `render`, `demo`
/// and `bench`).

#include <ostream>
#include <string>

namespace fcl_quadric {
namespace cli {

/// Exit statuses of the program.
enum ExitStatus : int {
  kExitOk = 0,
  kExitInternalError = 1,  ///< a bug: library failure or coherence mismatch
  kExitBadInput = 2,       ///< bad scene file or command-line usage error
};

/// Runs the program with the given arguments, writing results to `out` and diagnostics to `err`.
/// An error is reported as exactly one line "fcl_quadric: error: ..." on `err` (prefixed by the
/// JSON pointer of the bad value for scene errors) with nothing written to `out`.
/// \return an ExitStatus.
int run(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

/// The one-line diagnostic for `message`: "fcl_quadric: error: " + message with control
/// characters (newlines included) replaced by spaces, ending in '\n'.
std::string errorLine(const std::string& message);

}  // namespace cli
}  // namespace fcl_quadric
