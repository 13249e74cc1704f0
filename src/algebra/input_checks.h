#pragma once
// Private: argument checks shared by the algebra layer. Each throws std::invalid_argument with a
// message naming the function and the bad value.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace fcl_quadric {
namespace detail {

inline void checkFiniteValue(const char* where, const char* what, double v) {
  if (!std::isfinite(v)) {
    std::ostringstream os;
    os << where << ": non-finite " << what << " (" << v << ")";
    throw std::invalid_argument(os.str());
  }
}

/// Every coefficient finite; if `non_empty`, at least one coefficient.
inline void checkCoefficients(const char* where, const std::vector<double>& c, bool non_empty) {
  if (non_empty && c.empty()) throw std::invalid_argument(std::string(where) + ": empty coefficient vector");
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (!std::isfinite(c[i])) {
      std::ostringstream os;
      os << where << ": non-finite coefficient c[" << i << "] = " << c[i];
      throw std::invalid_argument(os.str());
    }
  }
}

}  // namespace detail
}  // namespace fcl_quadric
