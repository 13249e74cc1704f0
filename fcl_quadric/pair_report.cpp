#include "fcl_quadric/pair_report.h"

namespace fcl_quadric {
namespace cli {

const char* toString(PairMethod method) {
  switch (method) {
    case PairMethod::Exact: return "exact";
    case PairMethod::Fcl: return "fcl";
    case PairMethod::QuadricRegion: return "quadric_region";
  }
  return "unknown";
}

}  // namespace cli
}  // namespace fcl_quadric
