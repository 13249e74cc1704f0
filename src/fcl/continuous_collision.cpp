// Continuous collision in the FCL layer (issue 4): RationalMotion (an fcl::MotionBase carrying
// fcl_quadric's rational motions), fcl_quadric::continuousCollide (exact for ellipsoid pairs under
// rational and translational motions, certified conservative advancement under FCL's InterpMotion
// and ScrewMotion, FCL for the rest) and the continuous broad phase (thesis §5.4.1).
//
// The one translation unit of this layer that includes FCL's continuous-collision headers. It
// instantiates no FCL traversal: fcl::continuousCollide<double> and FCL's motions are extern
// templates compiled into libfcl.so.
#include "fcl_quadric/fcl/continuous_collision.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/motion/interp_motion.h>
#include <fcl/math/motion/screw_motion.h>
#include <fcl/math/motion/spline_motion.h>
#include <fcl/math/motion/tbv_motion_bound_visitor.h>
#include <fcl/math/motion/translation_motion.h>
#include <fcl/math/motion/triangle_motion_bound_visitor.h>
#include <fcl/narrowphase/continuous_collision.h>

#include "fcl_quadric/algebra/bernstein_polynomial.h"
#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fcl_quadric/fcl/continuous_broadphase.h"
#include "fcl_quadric/fcl/rational_motion.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/signed_distance.h"
#include "algebra/input_checks.h"
#include "fcl/input_checks.h"
#include "fcl/quadric_shape_dispatch.h"

// --- Reading the bounding volume / triangle and direction of FCL's motion-bound visitors -------
// TBVMotionBoundVisitor<BV> and TriangleMotionBoundVisitor<S> keep bv / (a, b, c) and n protected
// and befriend every specialization of TBVMotionBoundVisitorVisitImpl / TriangleMotionBoundVisitorVisitImpl
// (FCL's hook for per-motion bounds). A RationalMotion is not one of the motion types the visitors
// dispatch on, so these specializations, keyed by a private tag, only read the fields.
namespace fcl_quadric {
namespace detail {
struct MotionBoundAccess {};
}  // namespace detail
}  // namespace fcl_quadric

namespace fcl {
template <typename S, typename BV>
struct TBVMotionBoundVisitorVisitImpl<S, BV, fcl_quadric::detail::MotionBoundAccess> {
  static const BV& bv(const TBVMotionBoundVisitor<BV>& v) { return v.bv; }
  static const Vector3<S>& n(const TBVMotionBoundVisitor<BV>& v) { return v.n; }
};
template <typename S>
struct TriangleMotionBoundVisitorVisitImpl<S, fcl_quadric::detail::MotionBoundAccess> {
  static std::array<Vector3<S>, 3> vertices(const TriangleMotionBoundVisitor<S>& v) { return {v.a, v.b, v.c}; }
  static const Vector3<S>& n(const TriangleMotionBoundVisitor<S>& v) { return v.n; }
};
}  // namespace fcl

namespace fcl_quadric {

namespace {

// ---------------------------------------------------------------------------------------------
// Certified ranges of polynomials and rational functions on an interval (Bernstein convex hull)
// ---------------------------------------------------------------------------------------------

struct Range {
  double lo = 0.0;
  double hi = 0.0;
};

// Relative widening of every Bernstein-derived bound, for the rounding of the basis conversion.
constexpr double kBoundWidening = 1e-12;

int effectiveDegree(const Polynomial& p) { return std::max(0, p.trimmed().degree()); }

// Range of N(t) / w(t) on [a, b] by the rational Bezier hull: with N = sum n_k B_k and
// w = sum w_k B_k of one common degree and all w_k of one strict sign, N / w is a convex
// combination of the n_k / w_k. The interval is halved until w's coefficients have one sign.
void rationalRangeInto(const Polynomial& N, const Polynomial& w, double a, double b, int depth, Range* out,
                       bool* first) {
  const int deg = std::max(effectiveDegree(N), effectiveDegree(w));
  const BernsteinPolynomial bn = BernsteinPolynomial::fromPower(N.trimmed(), a, b, deg);
  const BernsteinPolynomial bw = BernsteinPolynomial::fromPower(w.trimmed(), a, b, deg);
  const bool positive = bw.minCoefficient() > 0.0, negative = bw.maxCoefficient() < 0.0;
  if (!positive && !negative) {
    if (depth >= 16) {
      std::ostringstream os;
      os << "fcl_quadric: the motion's homogeneous weight w(t) cannot be certified non-zero on [" << a << ", " << b
         << "]";
      throw std::invalid_argument(os.str());
    }
    const double m = 0.5 * (a + b);
    rationalRangeInto(N, w, a, m, depth + 1, out, first);
    rationalRangeInto(N, w, m, b, depth + 1, out, first);
    return;
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, mag = 0.0;
  for (int k = 0; k <= deg; ++k) {
    const double r = bn.coefficients()[k] / bw.coefficients()[k];
    lo = std::min(lo, r);
    hi = std::max(hi, r);
    mag = std::max(mag, std::abs(r));
  }
  const double pad = kBoundWidening * mag + std::numeric_limits<double>::min();
  lo -= pad;
  hi += pad;
  if (*first) {
    *out = {lo, hi};
    *first = false;
  } else {
    out->lo = std::min(out->lo, lo);
    out->hi = std::max(out->hi, hi);
  }
}

// Range of N / w over [a, b], from the hulls of `parts` equal subintervals (Bernstein hulls
// tighten quadratically with the width).
Range rationalRangeSplit(const Polynomial& N, const Polynomial& w, double a, double b, int parts) {
  Range r;
  bool first = true;
  for (int k = 0; k < parts; ++k) {
    const double lo = a + (b - a) * k / parts, hi = k + 1 == parts ? b : a + (b - a) * (k + 1) / parts;
    rationalRangeInto(N, w, lo, hi, 0, &r, &first);
  }
  return r;
}

// Subintervals of the motion-bound windows: 4 brings the RSS bound within a few times the sampled
// supremum on random keyframed motions (test/fcl/continuous_collision_test.cpp).
constexpr int kBoundParts = 4;

double maxAbs(const Range& r) { return std::max(std::abs(r.lo), std::abs(r.hi)); }

// The part of piece k of `motion` inside [t0, 1], as a local parameter interval [a, 1] (widened to
// a non-empty interval when t0 is the piece's end), and the chain-rule factor 1 / (piece width).
struct PieceWindow {
  bool active = false;
  double a = 0.0;
  double b = 1.0;
  double inv_width = 1.0;
};

PieceWindow pieceWindow(const PiecewiseMotion& motion, std::size_t k, double t0) {
  const double lo = motion.breaks()[k], hi = motion.breaks()[k + 1];
  PieceWindow w;
  if (hi < t0) return w;
  w.active = true;
  w.inv_width = 1.0 / (hi - lo);
  w.a = std::clamp((t0 - lo) * w.inv_width, 0.0, 1.0);
  if (w.a > 1.0 - 1.0 / 1048576.0) w.a = 1.0 - 1.0 / 1048576.0;  // widening is conservative
  return w;
}

// Velocity numerators of piece M: dx/ds = G(s) X / w(s)^2 with G = M' w - M w' (rows 0..2).
struct VelocityForm {
  std::array<std::array<Polynomial, 4>, 3> G;
  Polynomial w2;
};

VelocityForm velocityForm(const MotionMatrix& m) {
  const PolynomialMatrix4& M = m.matrix();
  const Polynomial& w = M(3, 3);
  const Polynomial dw = w.derivative();
  VelocityForm f;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) f.G[i][j] = M(i, j).derivative() * w - M(i, j) * dw;
  f.w2 = w * w;
  return f;
}

// sup over s in [a, b] of n . G(s) X / w^2 for each X, max over the X, plus radius times
// sup |(n^T G_{3x3})| / w^2 (componentwise bounds), scaled by the chain-rule factor.
double directionalBoundOnPiece(const VelocityForm& f, const PieceWindow& win, const Eigen::Vector3d& n,
                               const std::vector<Eigen::Vector3d>& points, double radius) {
  std::array<Polynomial, 4> nG;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i)
      if (n[i] != 0.0) nG[j] += f.G[i][j] * n[i];
  double best = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& x : points) {
    Polynomial v = nG[3];
    for (int j = 0; j < 3; ++j)
      if (x[j] != 0.0) v += nG[j] * x[j];
    best = std::max(best, rationalRangeSplit(v, f.w2, win.a, win.b, kBoundParts).hi);
  }
  double ball = 0.0;
  if (radius > 0.0) {
    double s2 = 0.0;
    for (int j = 0; j < 3; ++j) {
      const double m = maxAbs(rationalRangeSplit(nG[j], f.w2, win.a, win.b, kBoundParts));
      s2 += m * m;
    }
    ball = radius * std::sqrt(s2) * (1.0 + kBoundWidening);
  }
  const double r = (best + ball) * win.inv_width;
  return r + kBoundWidening * std::abs(r);
}

double speedBoundOnPiece(const VelocityForm& f, const PieceWindow& win, const Eigen::Vector3d& c, double radius) {
  double v2 = 0.0, l2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    Polynomial v = f.G[i][3];
    for (int j = 0; j < 3; ++j)
      if (c[j] != 0.0) v += f.G[i][j] * c[j];
    const double m = maxAbs(rationalRangeSplit(v, f.w2, win.a, win.b, kBoundParts));
    v2 += m * m;
    if (radius > 0.0) {
      for (int j = 0; j < 3; ++j) {
        const double g = maxAbs(rationalRangeSplit(f.G[i][j], f.w2, win.a, win.b, kBoundParts));
        l2 += g * g;
      }
    }
  }
  return (std::sqrt(v2) + radius * std::sqrt(l2)) * win.inv_width * (1.0 + 4.0 * kBoundWidening);
}

fcl::Transform3d toTransform(const Eigen::Matrix4d& X) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = X.topLeftCorner<3, 3>();
  tf.translation() = X.block<3, 1>(0, 3);
  return tf;
}

Eigen::Matrix4d toMatrix(const fcl::Transform3d& tf) {
  Eigen::Matrix4d X = Eigen::Matrix4d::Identity();
  X.topLeftCorner<3, 3>() = tf.linear();
  X.block<3, 1>(0, 3) = tf.translation();
  return X;
}


}  // namespace

// =============================================================================================
// RationalMotion
// =============================================================================================

template <typename S>
RationalMotion<S>::RationalMotion(const fcl::Transform3<S>& tf_beg, const fcl::Transform3<S>& tf_end)
    : motion_([&] {
        detail::checkPose(tf_beg, "fcl_quadric::RationalMotion", "tf_beg");
        detail::checkPose(tf_end, "fcl_quadric::RationalMotion", "tf_end");
        const Eigen::Isometry3d a = tf_beg.template cast<double>(), b = tf_end.template cast<double>();
        return PiecewiseMotion(MotionMatrix::fromPoses(a, b));
      }()) {
  integrate(0);
}

template <typename S>
RationalMotion<S>::RationalMotion(const std::vector<S>& times, const std::vector<fcl::Transform3<S>>& poses)
    : motion_([&] {
        std::vector<double> t(times.begin(), times.end());
        std::vector<Eigen::Isometry3d> x;
        for (std::size_t k = 0; k < poses.size(); ++k) {
          const std::string which = "poses[" + std::to_string(k) + "]";
          detail::checkPose(poses[k], "fcl_quadric::RationalMotion", which.c_str());
          x.push_back(poses[k].template cast<double>());
        }
        return PiecewiseMotion::fromKeyframes(t, x);
      }()) {
  integrate(0);
}

template <typename S>
RationalMotion<S>::RationalMotion(const PolynomialMatrix4& M)
    : motion_(PiecewiseMotion(MotionMatrix::fromPolynomialMatrix(M))) {
  integrate(0);
}

template <typename S>
RationalMotion<S>::RationalMotion(PiecewiseMotion motion) : motion_(std::move(motion)) {
  integrate(0);
}

template <typename S>
bool RationalMotion<S>::integrate(S dt) const {
  if (std::isnan(dt)) return false;
  const double t = std::clamp(static_cast<double>(dt), 0.0, 1.0);
  current_ = motion_.evaluate(t);
  time_ = t;
  tf_.linear() = current_.topLeftCorner<3, 3>().template cast<S>();
  tf_.translation() = current_.block<3, 1>(0, 3).template cast<S>();
  return true;
}

template <typename S>
void RationalMotion<S>::getCurrentTransform(fcl::Transform3<S>& tf) const {
  tf = tf_;
}

template <typename S>
void RationalMotion<S>::getTaylorModel(fcl::TMatrix3<S>&, fcl::TVector3<S>&) const {
  throw std::logic_error(
      "fcl_quadric::RationalMotion::getTaylorModel: rational motions have no Taylor model. FCL uses Taylor "
      "models only in CCDC_POLYNOMIAL_SOLVER (BVH-BVH pairs under TranslationMotion) and in "
      "ContinuousCollisionObject::computeAABB; use CCDC_CONSERVATIVE_ADVANCEMENT or CCDC_NAIVE with this "
      "motion, fcl_quadric::continuousCollide, or fcl_quadric::sweptAABB / SweptCollisionObject for AABBs");
}

template <typename S>
double RationalMotion<S>::directionalSpeedBound(const Eigen::Vector3d& n, const std::vector<Eigen::Vector3d>& points,
                                                double radius, double t0) const {
  if (!(t0 >= 0.0 && t0 <= 1.0)) {
    std::ostringstream os;
    os << "fcl_quadric::RationalMotion::directionalSpeedBound: t0 must be in [0, 1], got " << t0;
    throw std::invalid_argument(os.str());
  }
  double best = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < motion_.pieces().size(); ++k) {
    const PieceWindow win = pieceWindow(motion_, k, t0);
    if (!win.active) continue;
    best = std::max(best, directionalBoundOnPiece(velocityForm(motion_.pieces()[k]), win, n, points, radius));
  }
  return best;
}

template <typename S>
double RationalMotion<S>::speedBound(const Eigen::Vector3d& centre, double radius, double t0) const {
  if (!(t0 >= 0.0 && t0 <= 1.0)) {
    std::ostringstream os;
    os << "fcl_quadric::RationalMotion::speedBound: t0 must be in [0, 1], got " << t0;
    throw std::invalid_argument(os.str());
  }
  double best = 0.0;
  for (std::size_t k = 0; k < motion_.pieces().size(); ++k) {
    const PieceWindow win = pieceWindow(motion_, k, t0);
    if (!win.active) continue;
    best = std::max(best, speedBoundOnPiece(velocityForm(motion_.pieces()[k]), win, centre, radius));
  }
  return best;
}

template <typename S>
S RationalMotion<S>::computeMotionBound(const fcl::BVMotionBoundVisitor<S>& mb_visitor) const {
  using Access = detail::MotionBoundAccess;
  const fcl::RSS<S>* rss = nullptr;
  Eigen::Vector3d n;
  if (const auto* v = dynamic_cast<const fcl::TBVMotionBoundVisitor<fcl::RSS<S>>*>(&mb_visitor)) {
    rss = &fcl::TBVMotionBoundVisitorVisitImpl<S, fcl::RSS<S>, Access>::bv(*v);
    n = fcl::TBVMotionBoundVisitorVisitImpl<S, fcl::RSS<S>, Access>::n(*v).template cast<double>();
  } else if (const auto* w = dynamic_cast<const fcl::TBVMotionBoundVisitor<fcl::OBBRSS<S>>*>(&mb_visitor)) {
    rss = &fcl::TBVMotionBoundVisitorVisitImpl<S, fcl::OBBRSS<S>, Access>::bv(*w).rss;
    n = fcl::TBVMotionBoundVisitorVisitImpl<S, fcl::OBBRSS<S>, Access>::n(*w).template cast<double>();
  } else {
    throw std::logic_error(
        "fcl_quadric::RationalMotion::computeMotionBound: unsupported BVMotionBoundVisitor (only "
        "TBVMotionBoundVisitor<RSS> and TBVMotionBoundVisitor<OBBRSS>, the ones FCL's conservative advancement "
        "builds, expose their bounding volume)");
  }
  // The RSS: the rectangle To + [0, l0] axis0 + [0, l1] axis1 (body frame) swept by a ball of
  // radius r. n . dx/dt is affine in x, so its sup over the rectangle is at a corner.
  const Eigen::Vector3d To = rss->To.template cast<double>();
  const Eigen::Vector3d e0 = (rss->axis.col(0) * rss->l[0]).template cast<double>();
  const Eigen::Vector3d e1 = (rss->axis.col(1) * rss->l[1]).template cast<double>();
  const std::vector<Eigen::Vector3d> corners{To, To + e0, To + e1, To + e0 + e1};
  return static_cast<S>(directionalSpeedBound(n, corners, static_cast<double>(rss->r), time_));
}

template <typename S>
S RationalMotion<S>::computeMotionBound(const fcl::TriangleMotionBoundVisitor<S>& mb_visitor) const {
  using Impl = fcl::TriangleMotionBoundVisitorVisitImpl<S, detail::MotionBoundAccess>;
  const auto v = Impl::vertices(mb_visitor);
  const std::vector<Eigen::Vector3d> pts{v[0].template cast<double>(), v[1].template cast<double>(),
                                         v[2].template cast<double>()};
  return static_cast<S>(directionalSpeedBound(Impl::n(mb_visitor).template cast<double>(), pts, 0.0, time_));
}

template class RationalMotion<double>;

// =============================================================================================
// continuousCollide
// =============================================================================================

namespace {

thread_local ContinuousCollideStats g_stats;

constexpr const char* kWhere = "fcl_quadric::continuousCollide";

// FCL's InterpMotion with its reference point at the body origin. InterpMotion(tf1, tf2) leaves
// reference_p uninitialised (interp_motion-inl.h), while its comments say "Default reference
// point is local zero point"; the default constructor touches nothing uninitialised.
class OriginInterpMotion : public fcl::InterpMotion<double> {
 public:
  OriginInterpMotion(const fcl::Transform3d& tf_beg, const fcl::Transform3d& tf_end) {
    tf1 = tf_beg;
    tf2 = tf_end;
    tf = tf1;
    reference_p.setZero();
    computeVelocity();
  }
};

enum class MotionKind { Rational, Translation, Interp, Screw, Spline, Other };

MotionKind kindOf(const fcl::MotionBase<double>* m) {
  if (dynamic_cast<const RationalMotion<double>*>(m)) return MotionKind::Rational;
  if (dynamic_cast<const fcl::TranslationMotion<double>*>(m)) return MotionKind::Translation;
  if (dynamic_cast<const fcl::InterpMotion<double>*>(m)) return MotionKind::Interp;
  if (dynamic_cast<const fcl::ScrewMotion<double>*>(m)) return MotionKind::Screw;
  if (dynamic_cast<const fcl::SplineMotion<double>*>(m)) return MotionKind::Spline;
  return MotionKind::Other;
}

const char* kindName(MotionKind k) {
  switch (k) {
    case MotionKind::Rational: return "fcl_quadric::RationalMotion";
    case MotionKind::Translation: return "fcl::TranslationMotion";
    case MotionKind::Interp: return "fcl::InterpMotion";
    case MotionKind::Screw: return "fcl::ScrewMotion";
    case MotionKind::Spline: return "fcl::SplineMotion";
    default: return "fcl::MotionBase";
  }
}

// Radii of an fcl::Ellipsoid or fcl::Sphere (body frame centred at the origin, axes aligned).
std::optional<Eigen::Vector3d> quadricRadii(const fcl::CollisionGeometry<double>* g) {
  if (g->getNodeType() == fcl::GEOM_ELLIPSOID) return static_cast<const fcl::Ellipsoidd*>(g)->radii;
  if (g->getNodeType() == fcl::GEOM_SPHERE)
    return Eigen::Vector3d::Constant(static_cast<const fcl::Sphered*>(g)->radius);
  return std::nullopt;
}

Ellipsoid bodyEllipsoid(const Eigen::Vector3d& radii, const char* which) {
  try {
    return Ellipsoid(radii, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(kWhere) + ": " + which + ": " + e.what());
  }
}

Eigen::Matrix4d currentPose(const fcl::MotionBase<double>* m, double t, const char* which) {
  m->integrate(t);
  fcl::Transform3d tf;
  m->getCurrentTransform(tf);
  const Eigen::Matrix4d X = toMatrix(tf);
  if (!detail::allFinite(X)) {
    std::ostringstream os;
    os << kWhere << ": " << which << " gives a non-finite pose at t = " << t;
    throw std::invalid_argument(os.str());
  }
  return X;
}

// The rational motion of an exact-capable motion (RationalMotion or TranslationMotion).
PiecewiseMotion rationalOf(const fcl::MotionBase<double>* m, MotionKind kind, const char* which) {
  if (kind == MotionKind::Rational) return static_cast<const RationalMotion<double>*>(m)->piecewiseMotion();
  const auto* tm = static_cast<const fcl::TranslationMotion<double>*>(m);
  const Eigen::Matrix4d X0 = currentPose(m, 0.0, which);
  const Eigen::Vector3d v = tm->getVelocity();
  const Eigen::Matrix3d R = X0.topLeftCorner<3, 3>();
  const Eigen::Vector3d p0 = X0.block<3, 1>(0, 3);
  try {
    return PiecewiseMotion(MotionMatrix::fromPoses(R, p0, R, p0 + v));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(kWhere) + ": " + which + " (fcl::TranslationMotion): " + e.what());
  }
}

void setContactPoses(const fcl::MotionBase<double>* m1, const fcl::MotionBase<double>* m2, double t,
                     fcl::ContinuousCollisionResult<double>& result) {
  m1->integrate(t);
  m2->integrate(t);
  m1->getCurrentTransform(result.contact_tf1);
  m2->getCurrentTransform(result.contact_tf2);
}

double exactPair(const Ellipsoid& a_body, const fcl::MotionBase<double>* m1, MotionKind k1, const Ellipsoid& b_body,
                 const fcl::MotionBase<double>* m2, MotionKind k2, fcl::ContinuousCollisionResult<double>& result) {
  const MovingEllipsoid a{a_body, rationalOf(m1, k1, "motion1")};
  const MovingEllipsoid b{b_body, rationalOf(m2, k2, "motion2")};
  CcdOptions opt;
  opt.all_intervals = false;
  const EllipsoidCcdResult r = continuousCollideEllipsoids(a, b, opt);
  g_stats.path = ContinuousCollideStats::Path::Exact;
  g_stats.steps = r.work;
  g_stats.near_tangent = r.near_tangent || r.unresolved;
  result.is_collide = r.collide;
  result.time_of_contact = r.collide ? *r.first_contact_time : 1.0;
  if (r.collide) setContactPoses(m1, m2, result.time_of_contact, result);
  return result.time_of_contact;
}

// One solid of a conservative-advancement pair: its pose at t (solidSpeedBound() bounds the
// velocity of its points over [0, 1]).
struct AdvancingSolid {
  const fcl::MotionBase<double>* motion = nullptr;
  MotionKind kind = MotionKind::Other;
  const char* which = "";
  Eigen::Vector3d radii;
  bool rigid = true;

  Eigen::Matrix4d pose(double t) const {
    if (kind == MotionKind::Rational) {
      const Eigen::Matrix4d X = static_cast<const RationalMotion<double>*>(motion)->piecewiseMotion().evaluate(t);
      if (!detail::allFinite(X)) {
        std::ostringstream os;
        os << kWhere << ": " << which << " gives a non-finite pose at t = " << t;
        throw std::invalid_argument(os.str());
      }
      return X;
    }
    return currentPose(motion, t, which);
  }

  Ellipsoid at(double t) const {
    const Eigen::Matrix4d X = pose(t);
    if (rigid) return Ellipsoid(radii, X.topLeftCorner<3, 3>(), X.block<3, 1>(0, 3));
    return Ellipsoid::fromAffine(X.topLeftCorner<3, 3>() * radii.asDiagonal(), X.block<3, 1>(0, 3));
  }
};

void requireFinite(double v, const char* which, const char* what) {
  if (!std::isfinite(v)) {
    std::ostringstream os;
    os << kWhere << ": " << which << " has a non-finite " << what;
    throw std::invalid_argument(os.str());
  }
}

// The control points of an fcl::SplineMotion (protected members, read through a derived type's
// member pointers: no copy of FCL's code).
struct SplineControlPoints {
  Eigen::Vector3d T[4], R[4];
};
struct SplineAccess : fcl::SplineMotion<double> {
  static SplineControlPoints get(const fcl::SplineMotion<double>& m) {
    SplineControlPoints c;
    const auto& Td = m.*(&SplineAccess::Td);
    const auto& Rd = m.*(&SplineAccess::Rd);
    for (int i = 0; i < 4; ++i) {
      c.T[i] = Td[i];
      c.R[i] = Rd[i];
    }
    return c;
  }
};
SplineControlPoints splineControlPoints(const fcl::SplineMotion<double>& m) { return SplineAccess::get(m); }

// Certified bound of the velocity of every point of the solid (body ball of radius max radius
// around the origin) over [0, 1], from the motion's parameters: a constant velocity `linear`
// shared by all its points (the motion's translation at a constant rate, zero where it has none)
// plus a vector of length at most `rest`. The relative velocity of two solids' points is then at
// most |linear_a - linear_b| + rest_a + rest_b: two bodies translated alike do not approach each
// other (session 35, an audit: two balls moved side by side 1000 apart at a gap of 1e-2 hit the
// step cap, and were reported colliding, with the plain sum of their speeds).
struct SpeedBound {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  double rest = 0.0;
};

SpeedBound solidSpeedBound(const AdvancingSolid& s) {
  const double r = s.radii.maxCoeff();
  switch (s.kind) {
    case MotionKind::Rational:
      return {Eigen::Vector3d::Zero(),
              static_cast<const RationalMotion<double>*>(s.motion)->speedBound(Eigen::Vector3d::Zero(), r, 0.0)};
    case MotionKind::Translation: {
      const Eigen::Vector3d v = static_cast<const fcl::TranslationMotion<double>*>(s.motion)->getVelocity();
      for (int i = 0; i < 3; ++i) requireFinite(v[i], s.which, "velocity");
      return {v, 0.0};
    }
    case MotionKind::Interp: {
      // x(t) = R(t) (x_b - ref) + tf1 * ref + v t, R(t) = AngleAxis(omega t, axis) R1 (interp_motion-inl.h):
      // |dx/dt| <= |v| + omega |axis x R(t) (x_b - ref)|, and the distance of R(t) y to the axis
      // does not depend on t; over the ball |x_b| <= r it is at most that of -R1 ref plus r.
      const auto* m = static_cast<const fcl::InterpMotion<double>*>(s.motion);
      const Eigen::Vector3d v = m->getLinearVelocity(), axis = m->getAngularAxis(), ref = m->getReferencePoint();
      const double omega = m->getAngularVelocity();
      for (int i = 0; i < 3; ++i) {
        requireFinite(v[i], s.which, "linear velocity");
        requireFinite(axis[i], s.which, "angular axis");
        requireFinite(ref[i], s.which, "reference point");
      }
      requireFinite(omega, s.which, "angular velocity");
      const Eigen::Matrix3d R0 = s.pose(0.0).topLeftCorner<3, 3>();
      const Eigen::Vector3d y = R0 * (-ref);
      const double an = axis.norm();
      const double perp = an > 0.0 ? (axis.cross(y)).norm() / an : y.norm();
      return {v, std::abs(omega) * (perp + r) * (1.0 + 1e-12) + 1e-12 * v.norm()};
    }
    case MotionKind::Screw: {
      // x(t) = dR(t) (R1 x_b + T1 - p) + p + axis lv t (screw_motion-inl.h): |dx/dt| <=
      // |axis| |lv| + omega * (distance of R1 x_b + T1 to the screw axis through p), constant in t.
      // (When the rotation is below 1e-10, FCL sets axis = T2 - T1 unnormalised and lv = |axis|.)
      const auto* m = static_cast<const fcl::ScrewMotion<double>*>(s.motion);
      const Eigen::Vector3d axis = m->getAxis(), p = m->getAxisOrigin();
      const double lv = m->getLinearVelocity(), omega = m->getAngularVelocity();
      for (int i = 0; i < 3; ++i) {
        requireFinite(axis[i], s.which, "axis");
        requireFinite(p[i], s.which, "axis origin");
      }
      requireFinite(lv, s.which, "linear velocity");
      requireFinite(omega, s.which, "angular velocity");
      const Eigen::Vector3d T0 = s.pose(0.0).block<3, 1>(0, 3);
      const Eigen::Vector3d y = T0 - p;
      const double an = axis.norm();
      const double perp = an > 0.0 ? (axis.cross(y)).norm() / an : y.norm();
      const Eigen::Vector3d v = lv * axis;
      return {v, std::abs(omega) * (perp + r) * (1.0 + 1e-12) + 1e-12 * v.norm()};
    }
    case MotionKind::Spline: {
      // spline_motion-inl.h: T(t) = sum_i Td_i w_i(t), rotation = exp of w(t) = sum_i Rd_i w_i(t)
      // with the uniform cubic B-spline weights w_i. |dx/dt| <= |T'(t)| + |omega(t)| |x_b| and
      // |omega| = |J(w) w'| <= |w'| (the SO(3) Jacobian has norm <= 1: eigenvalues 1 along w
      // and |sin(theta/2)| / (theta/2) across). Each component of T' and w' is a quadratic in t:
      // its maximum modulus on [0, 1] is at the ends or the vertex.
      const auto* m = static_cast<const fcl::SplineMotion<double>*>(s.motion);
      const SplineControlPoints cp = splineControlPoints(*m);
      auto maxDerivative = [&](const Eigen::Vector3d* d) {
        // w_i'(t) = (a_i + b_i t + c_i t^2) / 6 (derivatives of the weights above).
        static constexpr double a[4] = {-3, 0, 3, 0}, b[4] = {6, -12, 6, 0}, c[4] = {-3, 9, -9, 3};
        double sum = 0.0;
        for (int k = 0; k < 3; ++k) {
          double q0 = 0, q1 = 0, q2 = 0;
          for (int i = 0; i < 4; ++i) {
            requireFinite(d[i][k], s.which, "spline control point");
            q0 += a[i] * d[i][k] / 6;
            q1 += b[i] * d[i][k] / 6;
            q2 += c[i] * d[i][k] / 6;
          }
          auto q = [&](double t) { return std::abs(q0 + t * (q1 + t * q2)); };
          double mx = std::max(q(0.0), q(1.0));
          if (q2 != 0.0) {
            const double tv = -q1 / (2 * q2);
            if (tv > 0.0 && tv < 1.0) mx = std::max(mx, q(tv));
          }
          sum += mx * mx;
        }
        return std::sqrt(sum);
      };
      return {Eigen::Vector3d::Zero(), (maxDerivative(cp.T) + maxDerivative(cp.R) * r) * (1.0 + 1e-12)};
    }
    default: return {Eigen::Vector3d::Zero(), std::numeric_limits<double>::infinity()};
  }
}

double advancementPair(AdvancingSolid a, AdvancingSolid b, fcl::ContinuousCollisionResult<double>& result) {
  const SpeedBound va = solidSpeedBound(a), vb = solidSpeedBound(b);  // (relative velocity: see SpeedBound)
  const double speed = ((va.linear - vb.linear).norm() + va.rest + vb.rest) * (1.0 + 1e-12);
  const double scale = a.radii.maxCoeff() + b.radii.maxCoeff();
  const double tol = kAdvancementDistanceRelative * scale;
  g_stats.path = ContinuousCollideStats::Path::ConservativeAdvancement;
  double t = 0.0;
  std::optional<double> contact;
  Eigen::Vector3d warm = Eigen::Vector3d::Zero();
  int step = 0;
  for (;; ++step) {
    if (step >= kAdvancementMaxSteps) {
      g_stats.step_cap = true;
      contact = t;  // conservative: not certified separate beyond t
      break;
    }
    const Ellipsoid ea = a.at(t), eb = b.at(t);
    const SignedDistanceResult sd = signedDistance(ea, eb, warm.squaredNorm() > 0.0 ? &warm : nullptr);
    if (sd.status != Separation::Separated) {
      contact = t;
      break;
    }
    warm = sd.normal;
    // sd.distance is the support gap along a unit normal, a lower bound of the distance; minus
    // a margin for the rounding of the poses and of the gap itself.
    const double margin = 1e-12 * (scale + ea.center().norm() + eb.center().norm());
    const double d = sd.distance - margin;
    if (d <= tol) {
      contact = t;
      break;
    }
    if (!(speed > 0.0)) break;  // neither solid moves relative to the other
    const double next = t + d / speed;
    if (next > 1.0) break;
    t = next;
  }
  g_stats.steps = step;
  result.is_collide = contact.has_value();
  result.time_of_contact = contact ? *contact : 1.0;
  if (contact) setContactPoses(a.motion, b.motion, *contact, result);
  return result.time_of_contact;
}

// Quadric shapes (EllipticCylinder, Quadric, QuadricCSG) against each other or FCL primitives:
// the certified space-time search of region_ccd.h under the exact rational motions.
double quadricShapePair(const fcl::CollisionGeometry<double>* o1, const fcl::MotionBase<double>* m1, MotionKind k1,
                        const fcl::CollisionGeometry<double>* o2, const fcl::MotionBase<double>* m2, MotionKind k2,
                        const fcl::ContinuousCollisionRequest<double>& request,
                        fcl::ContinuousCollisionResult<double>& result) {
  for (const auto& [k, which] : {std::pair(k1, "motion1"), std::pair(k2, "motion2")}) {
    if (k != MotionKind::Rational && k != MotionKind::Translation)
      throw std::invalid_argument(std::string(kWhere) + ": " + which + " is an " + kindName(k) +
                                  "; quadric shapes (EllipticCylinder, Quadric, QuadricCSG) need "
                                  "fcl_quadric::RationalMotion or fcl::TranslationMotion (exact rational motions)");
  }
  bool by_reduction = false;
  const RegionCcdResult r = detail::continuousCollideQuadricShapes(o1, rationalOf(m1, k1, "motion1"), o2,
                                                                   rationalOf(m2, k2, "motion2"), kWhere, nullptr, nullptr,
                                                                   request.ccd_solver_type == fcl::CCDC_POLYNOMIAL_SOLVER,
                                                                   &by_reduction);
  g_stats.path = ContinuousCollideStats::Path::Exact;
  g_stats.dimension_reduction = by_reduction;
  g_stats.steps = r.boxes;
  g_stats.near_tangent = r.near_tangent || r.capped;
  g_stats.step_cap = r.capped;
  g_stats.contact_point = r.point;
  result.is_collide = r.collide;
  result.time_of_contact = r.collide ? r.time : 1.0;
  if (r.collide) setContactPoses(m1, m2, result.time_of_contact, result);
  return result.time_of_contact;
}

/// FCL's naive solver samples t = i / (num_max_iterations - 1): with fewer than two iterations
/// that is 0 / 0, and it returned NaN as the contact time with is_collide set, even for a clear
/// miss (session 35, an audit). A request FCL cannot answer is an error here.
void checkDelegatedRequest(const fcl::ContinuousCollisionRequest<double>& request) {
  if (request.ccd_solver_type == fcl::CCDC_NAIVE && request.num_max_iterations < 2)
    throw std::invalid_argument(std::string(kWhere) +
                                ": request.num_max_iterations must be >= 2 for CCDC_NAIVE (FCL samples t = i / (n - 1)), "
                                "got " + std::to_string(request.num_max_iterations));
}

double delegate(const fcl::CollisionGeometry<double>* o1, const fcl::MotionBase<double>* motion1,
                const fcl::CollisionGeometry<double>* o2, const fcl::MotionBase<double>* motion2,
                const fcl::ContinuousCollisionRequest<double>& request,
                fcl::ContinuousCollisionResult<double>& result) {
  checkDelegatedRequest(request);
  g_stats.path = ContinuousCollideStats::Path::Delegated;
  return fcl::continuousCollide(o1, motion1, o2, motion2, request, result);
}

void checkMotion(const fcl::MotionBase<double>* m, const char* which) {
  if (m == nullptr) throw std::invalid_argument(std::string(kWhere) + ": " + which + " is a null motion");
}

}  // namespace

const ContinuousCollideStats& lastContinuousCollideStats() { return g_stats; }

template <typename S>
S continuousCollide(const fcl::CollisionGeometry<S>* o1, const fcl::MotionBase<S>* motion1,
                    const fcl::CollisionGeometry<S>* o2, const fcl::MotionBase<S>* motion2,
                    const fcl::ContinuousCollisionRequest<S>& request, fcl::ContinuousCollisionResult<S>& result) {
  static_assert(std::is_same<S, double>::value, "only double is instantiated");
  detail::checkGeometry(o1, kWhere, "o1");
  detail::checkGeometry(o2, kWhere, "o2");
  checkMotion(motion1, "motion1");
  checkMotion(motion2, "motion2");
  g_stats = ContinuousCollideStats();
  const MotionKind k1 = kindOf(motion1), k2 = kindOf(motion2);
  if (detail::isQuadricShape(o1) || detail::isQuadricShape(o2))
    return quadricShapePair(o1, motion1, k1, o2, motion2, k2, request, result);
  const std::optional<Eigen::Vector3d> r1 = quadricRadii(o1), r2 = quadricRadii(o2);

  if (r1 && r2) {
    const Ellipsoid a = bodyEllipsoid(*r1, "o1"), b = bodyEllipsoid(*r2, "o2");
    auto rational = [](MotionKind k) { return k == MotionKind::Rational || k == MotionKind::Translation; };
    auto certified = [&](MotionKind k) {
      return rational(k) || k == MotionKind::Interp || k == MotionKind::Screw || k == MotionKind::Spline;
    };
    if (rational(k1) && rational(k2)) return exactPair(a, motion1, k1, b, motion2, k2, result);
    if (certified(k1) && certified(k2)) {
      auto solid = [](const fcl::MotionBase<double>* m, MotionKind k, const char* which, const Eigen::Vector3d& radii) {
        AdvancingSolid s;
        s.motion = m;
        s.kind = k;
        s.which = which;
        s.radii = radii;
        s.rigid = k != MotionKind::Rational || static_cast<const RationalMotion<double>*>(m)->piecewiseMotion().isRigid();
        return s;
      };
      return advancementPair(solid(motion1, k1, "motion1", *r1), solid(motion2, k2, "motion2", *r2), result);
    }
    // An unknown motion type: no certified bound; FCL's answer (not certified).
  }

  // Delegated pairs: FCL's narrow phase needs rigid poses.
  for (const auto& [m, k, which] : {std::make_tuple(motion1, k1, "motion1"), std::make_tuple(motion2, k2, "motion2")}) {
    if (k == MotionKind::Rational && !static_cast<const RationalMotion<double>*>(m)->piecewiseMotion().isRigid())
      throw std::invalid_argument(std::string(kWhere) + ": " + which +
                                  " is a non-rigid RationalMotion; only ellipsoid and sphere pairs accept affine motions");
  }
  // fcl::continuousCollide C-casts both motions to TranslationMotion for this setting.
  if (request.ccd_solver_type == fcl::CCDC_POLYNOMIAL_SOLVER && o1->getObjectType() == fcl::OT_BVH &&
      o2->getObjectType() == fcl::OT_BVH && request.ccd_motion_type == fcl::CCDM_TRANS) {
    if (k1 != MotionKind::Translation || k2 != MotionKind::Translation)
      throw std::invalid_argument(std::string(kWhere) + ": CCDC_POLYNOMIAL_SOLVER needs fcl::TranslationMotion, got " +
                                  kindName(k1) + " and " + kindName(k2));
  }
  return delegate(o1, motion1, o2, motion2, request, result);
}

template <typename S>
S continuousCollide(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1_beg,
                    const fcl::Transform3<S>& tf1_end, const fcl::CollisionGeometry<S>* o2,
                    const fcl::Transform3<S>& tf2_beg, const fcl::Transform3<S>& tf2_end,
                    const fcl::ContinuousCollisionRequest<S>& request, fcl::ContinuousCollisionResult<S>& result) {
  detail::checkGeometry(o1, kWhere, "o1");
  detail::checkGeometry(o2, kWhere, "o2");
  detail::checkPose(tf1_beg, kWhere, "tf1_beg");
  detail::checkPose(tf1_end, kWhere, "tf1_end");
  detail::checkPose(tf2_beg, kWhere, "tf2_beg");
  detail::checkPose(tf2_end, kWhere, "tf2_end");
  // FCL builds its motions from rigid poses (a quaternion of the rotation, or the rotation kept as
  // given): a scaled or sheared linear part was read as a rotation and answered silently (session
  // 35, an audit), for every pair.
  for (const auto& [tf, which] : {std::pair(&tf1_beg, "tf1_beg"), std::pair(&tf1_end, "tf1_end"),
                                  std::pair(&tf2_beg, "tf2_beg"), std::pair(&tf2_end, "tf2_end")}) {
    const Eigen::Matrix3d R = tf->linear().template cast<double>();
    const Eigen::Vector3d p = tf->translation().template cast<double>();
    if (detail::isRigidPose(R, p)) continue;  // the messages only when a check fails
    const std::string what = std::string(kWhere) + ": " + which;
    detail::checkRotation(R, (what + " rotation").c_str());
    detail::checkPosition(p, (what + " translation").c_str());
  }
  if (detail::isQuadricShape(o1) || detail::isQuadricShape(o2)) {
    // Only translations are rational among FCL's motion types (FCL's CCDM_LINEAR / CCDM_SCREW
    // rotate at a constant angular velocity, which no rational motion reproduces).
    if (request.ccd_motion_type != fcl::CCDM_TRANS)
      throw std::invalid_argument(std::string(kWhere) +
                                  ": quadric shapes (EllipticCylinder, Quadric, QuadricCSG) need request.ccd_motion_type "
                                  "CCDM_TRANS with two poses, or fcl_quadric::RationalMotion objects "
                                  "(RationalMotion(tf_beg, tf_end) interpolates the rotation rationally)");
    const fcl::TranslationMotion<S> m1(tf1_beg, tf1_end), m2(tf2_beg, tf2_end);
    return fcl_quadric::continuousCollide(o1, &m1, o2, &m2, request, result);
  }
  if (!(quadricRadii(o1) && quadricRadii(o2))) {
    checkDelegatedRequest(request);
    g_stats = ContinuousCollideStats();
    g_stats.path = ContinuousCollideStats::Path::Delegated;
    return fcl::continuousCollide(o1, tf1_beg, tf1_end, o2, tf2_beg, tf2_end, request, result);
  }
  // The motions live on the stack: FCL's motion classes declare EIGEN_MAKE_ALIGNED_OPERATOR_NEW,
  // which is empty in this C++17 code but a real class operator delete in libfcl (built as C++14),
  // so a heap object allocated here would be freed there with a mismatched deallocation
  // (AddressSanitizer: alloc-dealloc-mismatch).
  switch (request.ccd_motion_type) {
    case fcl::CCDM_TRANS: {
      const fcl::TranslationMotion<S> m1(tf1_beg, tf1_end), m2(tf2_beg, tf2_end);
      return fcl_quadric::continuousCollide(o1, &m1, o2, &m2, request, result);
    }
    case fcl::CCDM_LINEAR: {
      const OriginInterpMotion m1(tf1_beg, tf1_end), m2(tf2_beg, tf2_end);
      return fcl_quadric::continuousCollide(o1, &m1, o2, &m2, request, result);
    }
    case fcl::CCDM_SCREW: {
      const fcl::ScrewMotion<S> m1(tf1_beg, tf1_end), m2(tf2_beg, tf2_end);
      return fcl_quadric::continuousCollide(o1, &m1, o2, &m2, request, result);
    }
    case fcl::CCDM_SPLINE:
      // FCL 0.7's SplineMotion(tf1, tf2) is an empty TODO: its control points stay
      // uninitialised, so no answer could be trusted. Build a SplineMotion from control points.
      throw std::invalid_argument(std::string(kWhere) +
                                  ": request.ccd_motion_type CCDM_SPLINE is not implemented by FCL 0.7 for two poses "
                                  "(SplineMotion(tf1, tf2) leaves its control points uninitialised); pass "
                                  "fcl::SplineMotion objects built from control points");
  }
  std::ostringstream os;
  os << kWhere << ": request.ccd_motion_type " << static_cast<int>(request.ccd_motion_type) << " is not a CCDMotionType";
  throw std::invalid_argument(os.str());
}

template <typename S>
S continuousCollide(const fcl::CollisionObject<S>* o1, const fcl::Transform3<S>& tf1_end,
                    const fcl::CollisionObject<S>* o2, const fcl::Transform3<S>& tf2_end,
                    const fcl::ContinuousCollisionRequest<S>& request, fcl::ContinuousCollisionResult<S>& result) {
  detail::checkObject(o1, kWhere, "o1");
  detail::checkObject(o2, kWhere, "o2");
  return fcl_quadric::continuousCollide(o1->collisionGeometry().get(), o1->getTransform(), tf1_end,
                                        o2->collisionGeometry().get(), o2->getTransform(), tf2_end, request, result);
}

template double continuousCollide(const fcl::CollisionGeometry<double>*, const fcl::MotionBase<double>*,
                                  const fcl::CollisionGeometry<double>*, const fcl::MotionBase<double>*,
                                  const fcl::ContinuousCollisionRequest<double>&, fcl::ContinuousCollisionResult<double>&);
template double continuousCollide(const fcl::CollisionGeometry<double>*, const fcl::Transform3<double>&,
                                  const fcl::Transform3<double>&, const fcl::CollisionGeometry<double>*,
                                  const fcl::Transform3<double>&, const fcl::Transform3<double>&,
                                  const fcl::ContinuousCollisionRequest<double>&, fcl::ContinuousCollisionResult<double>&);
template double continuousCollide(const fcl::CollisionObject<double>*, const fcl::Transform3<double>&,
                                  const fcl::CollisionObject<double>*, const fcl::Transform3<double>&,
                                  const fcl::ContinuousCollisionRequest<double>&, fcl::ContinuousCollisionResult<double>&);

// =============================================================================================
// Swept AABBs and the continuous broad phase
// =============================================================================================

namespace {

// Bounds of the body ball/ellipsoid's world image over the motion: centre coordinate ranges and
// half-extent bounds, per piece, united. `shape` maps the unit ball to the body solid's offsets.
fcl::AABB<double> sweptBox(const Eigen::Vector3d& centre, const Eigen::Matrix3d& shape, double max_radius,
                           const PiecewiseMotion& motion) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const MotionMatrix& piece : motion.pieces()) {
    const PolynomialMatrix4& M = piece.matrix();
    const Polynomial& w = M(3, 3);
    for (int i = 0; i < 3; ++i) {
      Polynomial c = M(i, 3);
      for (int k = 0; k < 3; ++k)
        if (centre[k] != 0.0) c += M(i, k) * centre[k];
      const Range rc = rationalRangeSplit(c, w, 0.0, 1.0, kBoundParts);
      double h2 = 0.0;
      for (int j = 0; j < 3; ++j) {
        Polynomial a;
        for (int k = 0; k < 3; ++k)
          if (shape(k, j) != 0.0) a += M(i, k) * shape(k, j);
        const double m = maxAbs(rationalRangeSplit(a, w, 0.0, 1.0, kBoundParts));
        h2 += m * m;
      }
      double h = std::sqrt(h2);
      if (piece.isRigid()) h = std::min(h, max_radius);
      h *= 1.0 + kBoundWidening;
      lo[i] = std::min(lo[i], rc.lo - h);
      hi[i] = std::max(hi[i], rc.hi + h);
    }
  }
  return fcl::AABB<double>(lo, hi);
}

}  // namespace

fcl::AABB<double> sweptAABB(const Ellipsoid& body, const PiecewiseMotion& motion) {
  return sweptBox(body.center(), body.rotation() * body.radii().asDiagonal(), body.radii().maxCoeff(), motion);
}

fcl::AABB<double> sweptAABB(const Eigen::Vector3d& centre, double radius, const PiecewiseMotion& motion) {
  if (!(radius >= 0.0) || !std::isfinite(radius)) {
    std::ostringstream os;
    os << "fcl_quadric::sweptAABB: radius must be finite and >= 0, got " << radius;
    throw std::invalid_argument(os.str());
  }
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(centre[i])) throw std::invalid_argument("fcl_quadric::sweptAABB: centre is not finite");
  return sweptBox(centre, radius * Eigen::Matrix3d::Identity(), radius, motion);
}

namespace {
std::shared_ptr<fcl::CollisionGeometry<double>> checkedGeometry(
    const std::shared_ptr<fcl::CollisionGeometry<double>>& g) {
  if (!g) throw std::invalid_argument("fcl_quadric::SweptCollisionObject: geometry is null");
  return g;
}
}  // namespace

SweptCollisionObject::SweptCollisionObject(const std::shared_ptr<fcl::CollisionGeometry<double>>& geometry,
                                           PiecewiseMotion motion)
    : fcl::CollisionObject<double>(checkedGeometry(geometry), toTransform(motion.evaluate(0.0))),
      motion_(std::move(motion)) {
  refreshSweptAABB();
}

void SweptCollisionObject::setMotion(PiecewiseMotion motion) {
  motion_ = std::move(motion);
  setTransform(toTransform(motion_.evaluate(0.0)));
  refreshSweptAABB();
}

void SweptCollisionObject::refreshSweptAABB() {
  const std::optional<Eigen::Vector3d> r = quadricRadii(cgeom.get());
  if (r) {
    aabb = sweptAABB(Ellipsoid(*r, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), motion_);
  } else {
    if (!motion_.isRigid())
      throw std::invalid_argument(
          "fcl_quadric::SweptCollisionObject: a non-rigid motion is only supported for ellipsoids and spheres");
    aabb = sweptAABB(cgeom->aabb_center, cgeom->aabb_radius, motion_);
  }
}

MotionMap motionMap(const std::vector<SweptCollisionObject*>& objects) {
  MotionMap map;
  for (SweptCollisionObject* o : objects) {
    if (o == nullptr) throw std::invalid_argument("fcl_quadric::motionMap: null object");
    map.emplace(o, o->motion());
  }
  return map;
}

namespace {

struct BroadPhaseData {
  const MotionMap* motions = nullptr;
  const ContinuousBroadPhaseRequest* request = nullptr;
  ContinuousBroadPhaseResult* result = nullptr;
  double t_bar = 1.0;
  bool found = false;
  std::unordered_map<const fcl::CollisionObject<double>*, std::shared_ptr<const MovingEllipsoid>> cache;
};

PiecewiseMotion motionOf(const BroadPhaseData& d, const fcl::CollisionObject<double>* o) {
  const auto it = d.motions->find(o);
  if (it != d.motions->end()) return it->second;
  const fcl::Transform3d& tf = o->getTransform();
  return PiecewiseMotion(MotionMatrix::constant(tf.linear(), tf.translation()));
}

std::shared_ptr<const MovingEllipsoid> movingEllipsoid(BroadPhaseData& d, const fcl::CollisionObject<double>* o,
                                                       const Eigen::Vector3d& radii) {
  auto& slot = d.cache[o];
  if (!slot)
    slot = std::make_shared<const MovingEllipsoid>(
        MovingEllipsoid{Ellipsoid(radii, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), motionOf(d, o)});
  return slot;
}

void report(BroadPhaseData& d, const ContinuousContactPair& c) {
  if (!d.request->earliest_only) {
    d.result->contacts.push_back(c);
    return;
  }
  if (!d.found || c.time_of_contact < d.t_bar) {
    d.result->contacts.assign(1, c);
    d.t_bar = c.time_of_contact;
    d.found = true;
  }
}

bool broadPhaseCallback(fcl::CollisionObject<double>* o1, fcl::CollisionObject<double>* o2, void* data) {
  BroadPhaseData& d = *static_cast<BroadPhaseData*>(data);
  ++d.result->candidate_pairs;
  if (d.request->earliest_only && d.found && d.t_bar <= 0.0) return true;  // nothing can be earlier
  const std::optional<Eigen::Vector3d> r1 = quadricRadii(o1->collisionGeometry().get());
  const std::optional<Eigen::Vector3d> r2 = quadricRadii(o2->collisionGeometry().get());
  if (r1 && r2) {
    const auto a = movingEllipsoid(d, o1, *r1), b = movingEllipsoid(d, o2, *r2);
    CcdOptions opt;
    opt.all_intervals = false;
    if (d.request->earliest_only && d.found) opt.t_max = d.t_bar;  // thesis §5.4.1: prune by t-bar
    const EllipsoidCcdResult r = continuousCollideEllipsoids(*a, *b, opt);
    ++d.result->exact_solves;
    if (r.culled_by != 0) ++d.result->culled;
    if (r.collide) {
      ContinuousContactPair c;
      c.o1 = o1;
      c.o2 = o2;
      c.time_of_contact = *r.first_contact_time;
      c.contact_point = r.contact_point;
      c.exact = true;
      c.near_tangent = r.near_tangent || r.unresolved;
      report(d, c);
    }
  } else {
    const RationalMotion<double> m1(motionOf(d, o1)), m2(motionOf(d, o2));
    fcl::ContinuousCollisionResult<double> r;
    fcl_quadric::continuousCollide(o1->collisionGeometry().get(), &m1, o2->collisionGeometry().get(), &m2,
                                   d.request->delegated_request, r);
    const ContinuousCollideStats& stats = lastContinuousCollideStats();
    const bool exact = stats.path == ContinuousCollideStats::Path::Exact;  // quadric shapes
    if (exact) {
      ++d.result->exact_solves;
    } else {
      ++d.result->delegated;
    }
    if (r.is_collide && r.time_of_contact >= 0.0 && r.time_of_contact <= 1.0) {
      ContinuousContactPair c;
      c.o1 = o1;
      c.o2 = o2;
      c.time_of_contact = r.time_of_contact;
      c.contact_point = exact ? stats.contact_point : 0.5 * (r.contact_tf1.translation() + r.contact_tf2.translation());
      c.exact = exact;
      c.near_tangent = exact && stats.near_tangent;
      report(d, c);
    }
  }
  return d.request->earliest_only && d.found && d.t_bar <= 0.0;
}

}  // namespace

void continuousCollideBroadPhase(const fcl::BroadPhaseCollisionManager<double>* manager, const MotionMap& motions,
                                 const ContinuousBroadPhaseRequest& request, ContinuousBroadPhaseResult& result) {
  if (manager == nullptr) throw std::invalid_argument("fcl_quadric::continuousCollideBroadPhase: manager is null");
  result = ContinuousBroadPhaseResult();
  BroadPhaseData d;
  d.motions = &motions;
  d.request = &request;
  d.result = &result;
  manager->collide(&d, broadPhaseCallback);
  std::stable_sort(result.contacts.begin(), result.contacts.end(),
                   [](const ContinuousContactPair& x, const ContinuousContactPair& y) {
                     return x.time_of_contact < y.time_of_contact;
                   });
}

}  // namespace fcl_quadric
