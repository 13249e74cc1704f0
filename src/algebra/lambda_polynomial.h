#pragma once
// Private: polynomials in lambda whose coefficients are polynomials in t, the entries of the
// pencils lambda A(t) - B(t) whose determinants PolynomialMatrix4 and PolynomialMatrix3 expand.
#include <algorithm>
#include <vector>

#include "fcl_quadric/algebra/polynomial.h"

namespace fcl_quadric {
namespace detail {

/// Polynomial in lambda whose coefficients are polynomials in t (index = power of lambda).
using Bivariate = std::vector<Polynomial>;

inline Bivariate operator*(const Bivariate& a, const Bivariate& b) {
  Bivariate c(a.size() + b.size() - 1);
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  }
  return c;
}

inline Bivariate operator+(const Bivariate& a, const Bivariate& b) {
  Bivariate c(std::max(a.size(), b.size()));
  for (std::size_t i = 0; i < a.size(); ++i) c[i] += a[i];
  for (std::size_t i = 0; i < b.size(); ++i) c[i] += b[i];
  return c;
}

inline Bivariate operator-(const Bivariate& a, const Bivariate& b) {
  Bivariate c(std::max(a.size(), b.size()));
  for (std::size_t i = 0; i < a.size(); ++i) c[i] += a[i];
  for (std::size_t i = 0; i < b.size(); ++i) c[i] -= b[i];
  return c;
}

}  // namespace detail
}  // namespace fcl_quadric
