#pragma once
/// \file double_double.h
/// Double-double arithmetic (unevaluated sum hi + lo of two doubles, ~106-bit significand) for the
/// second stage of certified sign decisions. Algorithms: Dekker (1971), Knuth TwoSum, and the QD
/// library of Hida, Li & Bailey (2001); TwoProd uses a fused multiply-add (exact product).
/// Relative error of +,-,* is below 2^-104 (we use that bound in tolerances.h).

#include <cmath>

namespace fcl_quadric {

struct DoubleDouble {
  double hi = 0.0;
  double lo = 0.0;

  constexpr DoubleDouble() = default;
  constexpr DoubleDouble(double x) : hi(x), lo(0.0) {}  // NOLINT: implicit by design
  constexpr DoubleDouble(double h, double l) : hi(h), lo(l) {}

  explicit operator double() const { return hi + lo; }
};

namespace detail {
inline DoubleDouble twoSum(double a, double b) {
  double s = a + b;
  double bb = s - a;
  double e = (a - (s - bb)) + (b - bb);
  return {s, e};
}
inline DoubleDouble quickTwoSum(double a, double b) {  // requires |a| >= |b|
  double s = a + b;
  return {s, b - (s - a)};
}
inline DoubleDouble twoProd(double a, double b) {
  double p = a * b;
  return {p, std::fma(a, b, -p)};
}
}  // namespace detail

inline DoubleDouble operator+(const DoubleDouble& a, const DoubleDouble& b) {
  DoubleDouble s = detail::twoSum(a.hi, b.hi);
  DoubleDouble t = detail::twoSum(a.lo, b.lo);
  s.lo += t.hi;
  s = detail::quickTwoSum(s.hi, s.lo);
  s.lo += t.lo;
  return detail::quickTwoSum(s.hi, s.lo);
}
inline DoubleDouble operator-(const DoubleDouble& a) { return {-a.hi, -a.lo}; }
inline DoubleDouble operator-(const DoubleDouble& a, const DoubleDouble& b) { return a + (-b); }
inline DoubleDouble operator*(const DoubleDouble& a, const DoubleDouble& b) {
  DoubleDouble p = detail::twoProd(a.hi, b.hi);
  p.lo += a.hi * b.lo + a.lo * b.hi;
  return detail::quickTwoSum(p.hi, p.lo);
}
inline DoubleDouble operator/(const DoubleDouble& a, const DoubleDouble& b) {
  // Long division: q1 = a/b, r = a - q1 b, q2 = r/b, ... (QD's accurate division).
  double q1 = a.hi / b.hi;
  DoubleDouble r = a - b * DoubleDouble(q1);
  double q2 = r.hi / b.hi;
  r = r - b * DoubleDouble(q2);
  double q3 = r.hi / b.hi;
  DoubleDouble q = detail::quickTwoSum(q1, q2);
  return q + DoubleDouble(q3);
}
inline DoubleDouble& operator+=(DoubleDouble& a, const DoubleDouble& b) { return a = a + b; }
inline DoubleDouble& operator-=(DoubleDouble& a, const DoubleDouble& b) { return a = a - b; }
inline DoubleDouble& operator*=(DoubleDouble& a, const DoubleDouble& b) { return a = a * b; }
inline bool operator<(const DoubleDouble& a, const DoubleDouble& b) {
  return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo);
}
inline bool operator>(const DoubleDouble& a, const DoubleDouble& b) { return b < a; }
inline bool operator<=(const DoubleDouble& a, const DoubleDouble& b) { return !(b < a); }
inline bool operator>=(const DoubleDouble& a, const DoubleDouble& b) { return !(a < b); }
inline DoubleDouble abs(const DoubleDouble& a) { return a.hi < 0 || (a.hi == 0 && a.lo < 0) ? -a : a; }
inline double toDouble(const DoubleDouble& a) { return a.hi + a.lo; }
inline double toDouble(double a) { return a; }
inline double abs(double a) { return std::fabs(a); }

}  // namespace fcl_quadric
