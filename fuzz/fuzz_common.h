#pragma once
// Shared helpers of the libFuzzer targets (docs/reliability.md).
//
// Input encoding: a stream of bytes read front to back; a missing byte reads as 0. A double is one
// selector byte followed by its payload:
//   selector <  128: a "nice" value, int16 / 2^(selector % 16)        (2 bytes)
//   selector <  208: the raw IEEE bits                                 (8 bytes): any magnitude,
//                    subnormals, NaN and inf included
//   otherwise      : one of kSpecials[selector % size]                 (0 bytes)
// so that the fuzzer reaches both ordinary configurations (where the oracle can judge) and hostile
// ones (where the documented std::invalid_argument or a NaN-free answer is the property).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/tolerances.h"
#include "support/exact_oracle.h"
#include "support/oracle_margin.h"

// A violated property: print it and abort, which libFuzzer reports as a crash with the input.
#define FUZZ_CHECK(cond, ...)                                                     \
  do {                                                                            \
    if (!(cond)) {                                                                \
      std::fprintf(stderr, "FUZZ_CHECK failed at %s:%d: %s\n  ", __FILE__, __LINE__, #cond); \
      std::fprintf(stderr, __VA_ARGS__);                                          \
      std::fprintf(stderr, "\n");                                                 \
      std::abort();                                                               \
    }                                                                             \
  } while (0)

namespace fcl_quadric {
namespace fuzz {

using test::clearExactCollision;
using test::rigidMargin;

class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  bool empty() const { return pos_ >= size_; }

  double value() {
    static const double kSpecials[] = {0.0,
                                       -0.0,
                                       1.0,
                                       -1.0,
                                       1e-300,
                                       1e300,
                                       -1e300,
                                       std::numeric_limits<double>::denorm_min(),
                                       std::numeric_limits<double>::min() / 4,  // subnormal
                                       std::numeric_limits<double>::max(),
                                       std::numeric_limits<double>::infinity(),
                                       -std::numeric_limits<double>::infinity(),
                                       std::numeric_limits<double>::quiet_NaN(),
                                       1e-100,
                                       1e100,
                                       1e-4,
                                       1e6,
                                       1.0 + std::numeric_limits<double>::epsilon()};
    const std::uint8_t s = byte();
    if (s < 128) {
      const auto hi = byte(), lo = byte();
      const auto v = static_cast<std::int16_t>(static_cast<std::uint16_t>((hi << 8) | lo));
      return std::ldexp(static_cast<double>(v), -(s % 16));
    }
    if (s < 208) {
      std::uint64_t bits = 0;
      for (int i = 0; i < 8; ++i) bits = (bits << 8) | byte();
      double d;
      std::memcpy(&d, &bits, sizeof d);
      return d;
    }
    return kSpecials[s % (sizeof kSpecials / sizeof kSpecials[0])];
  }

  Eigen::Vector3d vector3() {
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) v[i] = value();
    return v;
  }

  /// A 3x3 matrix from a quaternion (w, x, y, z): with the flag byte even, the quaternion is
  /// normalised when it can be (a rotation to ~1e-16), otherwise used as given (Eigen's formula
  /// on a non-unit quaternion: not orthogonal unless |q| = 1).
  Eigen::Matrix3d rotation() {
    const bool normalise = (byte() % 2) == 0;
    const double w = value(), x = value(), y = value(), z = value();
    Eigen::Quaterniond q(w, x, y, z);
    if (normalise) {
      const double n = q.norm();
      if (std::isfinite(n) && n > 1e-150) q.coeffs() /= n;
    }
    return q.toRotationMatrix();
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

/// Rotation defect as the library measures it (max over R^T R - I), or +inf if not finite.
inline double rotationDefect(const Eigen::Matrix3d& R) {
  if (!R.allFinite()) return std::numeric_limits<double>::infinity();
  const double d = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  return std::isnan(d) ? std::numeric_limits<double>::infinity() : d;
}

enum class Expect { Valid, Invalid, Either };

/// What the documented precondition of Ellipsoid (ellipsoid.h) says about these inputs. Near the
/// orthogonality threshold (rounding of the defect itself) either answer is accepted.
inline Expect expectedEllipsoid(const Eigen::Vector3d& r, const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  for (int i = 0; i < 3; ++i)
    if (!(r[i] >= tolerance::kMinRadius && r[i] <= tolerance::kMaxLength)) return Expect::Invalid;  // NaN too
  if (!p.allFinite() || !(p.cwiseAbs().maxCoeff() <= tolerance::kMaxLength)) return Expect::Invalid;
  if (R == Eigen::Matrix3d::Identity()) return Expect::Valid;
  const double defect = rotationDefect(R);
  if (defect > 2 * tolerance::kRotationOrthogonality) return Expect::Invalid;
  if (defect > 0.5 * tolerance::kRotationOrthogonality) return Expect::Either;
  return R.determinant() > 0 ? Expect::Valid : Expect::Invalid;
}

/// Builds the ellipsoid and checks the constructor against expectedEllipsoid(): a valid input must
/// be accepted, an invalid one must throw std::invalid_argument (any other exception escapes and
/// crashes the fuzzer). Returns the ellipsoid when constructed.
inline std::optional<Ellipsoid> makeEllipsoid(const Eigen::Vector3d& r, const Eigen::Matrix3d& R,
                                              const Eigen::Vector3d& p) {
  const Expect e = expectedEllipsoid(r, R, p);
  try {
    Ellipsoid el(r, R, p);
    FUZZ_CHECK(e != Expect::Invalid, "invalid ellipsoid accepted: radii %g %g %g, defect %g, centre %g %g %g", r[0],
               r[1], r[2], rotationDefect(R), p[0], p[1], p[2]);
    return el;
  } catch (const std::invalid_argument&) {
    FUZZ_CHECK(e != Expect::Valid, "valid ellipsoid rejected: radii %g %g %g, defect %g, centre %g %g %g", r[0], r[1],
               r[2], rotationDefect(R), p[0], p[1], p[2]);
    return std::nullopt;
  }
}

inline bool hasNaN(const Eigen::Vector3d& v) { return v.hasNaN(); }

/// A rigid motion from the reader: normalised rotation and translation (both finite, else the
/// identity rotation / zero translation).
inline Eigen::Isometry3d rigidMotion(Reader& in) {
  // Named draws: the order in which function arguments are evaluated is unspecified.
  const double w = in.value(), x = in.value(), y = in.value(), z = in.value();
  Eigen::Quaterniond q(w, x, y, z);
  const double n = q.norm();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (std::isfinite(n) && n > 1e-150) {
    q.coeffs() /= n;
    T.linear() = q.toRotationMatrix();
  }
  const Eigen::Vector3d t = in.vector3();
  if (t.allFinite()) T.translation() = t;
  return T;
}

}  // namespace fuzz
}  // namespace fcl_quadric
