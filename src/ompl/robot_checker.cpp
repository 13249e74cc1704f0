// RobotCollisionChecker: static checks and certified continuous checks (robot_checker.h).
#include "fcl_quadric/ompl/robot_checker.h"
#include "finite.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>

#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fcl_quadric/continuous/motion_matrix.h"
#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {
namespace planning {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Rounding allowance of the speed bounds (relative, and absolute in world units per unit t).
constexpr double kSpeedRelativeMargin = 1e-9;
constexpr double kSpeedAbsoluteMargin = 1e-12;

fcl::Transform3<double> toFcl(const Eigen::Isometry3d& X) {
  fcl::Transform3<double> tf = fcl::Transform3<double>::Identity();
  tf.linear() = X.linear();
  tf.translation() = X.translation();
  return tf;
}

bool isEllipsoidal(const fcl::CollisionGeometry<double>* g) {
  const fcl::NODE_TYPE t = g->getNodeType();
  return t == fcl::GEOM_ELLIPSOID || t == fcl::GEOM_SPHERE;
}

/// The body (in its own frame, centred at the origin) as an fcl_quadric::Ellipsoid posed at X.
Ellipsoid ellipsoidOf(const fcl::CollisionGeometry<double>* g, const Eigen::Isometry3d& X) {
  if (const auto* e = dynamic_cast<const fcl::Ellipsoid<double>*>(g)) return Ellipsoid(e->radii, X);
  const auto* s = static_cast<const fcl::Sphere<double>*>(g);
  return Ellipsoid(Eigen::Vector3d::Constant(s->radius), X);
}

/// An ellipsoid-box pair whose exact distance is deferred: best-first evaluation by `bound`.
struct DeferredPair {
  double bound;
  fcl::CollisionObject<double>* o1;
  fcl::CollisionObject<double>* o2;
};

struct DistanceData {
  fcl::DefaultDistanceData<double> base;
  /// Skip ellipsoid / sphere obstacles (they are decided by the exact CCD).
  bool skip_ellipsoidal = false;
  /// Unsigned queries: ellipsoid-box pairs are collected with their cheap lower bound and
  /// evaluated exactly afterwards, nearest bound first (see environmentDistance).
  std::vector<DeferredPair> deferred;
  /// Smallest cheap upper bound of a deferred pair's distance (clamped at 0): the broad phase
  /// prunes against it.
  double upper = std::numeric_limits<double>::max();
};

/// A cheap lower bound of the distance between an ellipsoid and a box (both posed): the largest
/// support gap min_{x in box} n.x - h_E(n) over the unit directions n = centre to centre and the
/// box axes facing the ellipsoid (a separating-axis gap never exceeds the distance).
double ellipsoidBoxGapBound(const fcl::Ellipsoid<double>& e, const fcl::Transform3<double>& Xe, const fcl::Box<double>& b,
                            const fcl::Transform3<double>& Xb) {
  const Eigen::Vector3d c = Xe.translation(), cb = Xb.translation();
  const Eigen::Matrix3d Re = Xe.linear(), Rb = Xb.linear();
  const Eigen::Vector3d half = 0.5 * b.side;
  auto gap = [&](const Eigen::Vector3d& n) {
    const double box_min = n.dot(cb) - (half.array() * (Rb.transpose() * n).array().abs()).sum();
    const double support = n.dot(c) + (e.radii.array() * (Re.transpose() * n).array()).matrix().norm();
    return box_min - support;
  };
  const Eigen::Vector3d dc = cb - c;
  double best = -kInf;
  const double len = dc.norm();
  if (len > 0.0) best = gap(dc / len);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d axis = Rb.col(i);
    best = std::max(best, gap(axis.dot(dc) >= 0.0 ? Eigen::Vector3d(axis) : Eigen::Vector3d(-axis)));
  }
  return best;
}

/// A cheap upper bound of max(0, distance) between an ellipsoid and a box: the ball of the
/// smallest radius around the ellipsoid's centre c lies inside it, so the box point closest to c
/// is within |x_b - c| - r_min of the ellipsoid.
double ellipsoidBoxGapUpperBound(const fcl::Ellipsoid<double>& e, const fcl::Transform3<double>& Xe,
                                 const fcl::Box<double>& b, const fcl::Transform3<double>& Xb) {
  const Eigen::Vector3d c_local = Xb.linear().transpose() * (Xe.translation() - Xb.translation());
  const Eigen::Vector3d half = 0.5 * b.side;
  const Eigen::Vector3d closest = c_local.cwiseMax(-half).cwiseMin(half);
  return std::max(0.0, (closest - c_local).norm() - e.radii.minCoeff());
}

bool distanceCallback(fcl::CollisionObject<double>* o1, fcl::CollisionObject<double>* o2, void* data, double& dist) {
  auto* d = static_cast<DistanceData*>(data);
  const fcl::CollisionGeometry<double>* g1 = o1->collisionGeometry().get();
  const fcl::CollisionGeometry<double>* g2 = o2->collisionGeometry().get();
  if (d->skip_ellipsoidal && isEllipsoidal(g1) && isEllipsoidal(g2)) {
    dist = d->base.result.min_distance;
    return d->base.done;
  }
  // Quadric shapes (quadric_shapes.h) and FCL's box / cylinder / cone / capsule: a certified lower bound
  // (fcl_quadric::distanceLowerBound), capped at the running minimum; 0 when the two may touch or
  // overlap (no penetration depth). Both the advancement and clearance() only need a lower bound.
  // (The cap is negative once a signed query has met an overlap: a bound, >= 0, cannot lower it.)
  const double cap = std::max(0.0, std::min(d->base.result.min_distance, d->upper));
  if (const std::optional<double> bound = fcl_quadric::distanceLowerBound(g1, o1->getTransform(), g2, o2->getTransform(), cap)) {
    if (*bound < d->base.result.min_distance) {
      d->base.result.min_distance = *bound;
      d->base.result.o1 = g1;
      d->base.result.o2 = g2;
    }
    dist = d->base.result.min_distance;
    return d->base.done;
  }
  // Skip the exact (costly) ellipsoid-box distance when a cheap lower bound already exceeds the
  // running minimum (OcTree leaves next to a body: most of them); 1e-12 covers rounding.
  if (!d->base.request.enable_signed_distance) {
    const auto* e1 = dynamic_cast<const fcl::Ellipsoid<double>*>(g1);
    const auto* e2 = dynamic_cast<const fcl::Ellipsoid<double>*>(g2);
    const auto* b1 = dynamic_cast<const fcl::Box<double>*>(g1);
    const auto* b2 = dynamic_cast<const fcl::Box<double>*>(g2);
    if ((e1 && b2) || (e2 && b1)) {
      const fcl::Ellipsoid<double>& e = e1 ? *e1 : *e2;
      const fcl::Box<double>& b = b2 ? *b2 : *b1;
      const fcl::Transform3<double>& Xe = e1 ? o1->getTransform() : o2->getTransform();
      const fcl::Transform3<double>& Xb = b2 ? o2->getTransform() : o1->getTransform();
      const double bound = ellipsoidBoxGapBound(e, Xe, b, Xb);
      const double prune = std::min(d->base.result.min_distance, d->upper);
      if (bound - 1e-12 < prune) {
        d->deferred.push_back({bound, o1, o2});
        d->upper = std::min(d->upper, ellipsoidBoxGapUpperBound(e, Xe, b, Xb));
      }
      dist = std::min(d->base.result.min_distance, d->upper);
      return d->base.done;
    }
  }
  return fcl_quadric::defaultDistanceFunction<double>(o1, o2, &d->base, dist);
}

/// Lower bound of the distance of a posed body to the environment (<= 0 on contact; +inf if the
/// environment is empty or every obstacle is skipped), or `cap` if nothing is closer than cap:
/// the broad phase and FCL's OcTree traversal prune every subtree farther than the running
/// minimum, which starts at cap (the advancement needs no distance beyond the one that finishes
/// the motion). Unsigned queries evaluate ellipsoid-box pairs (OcTree leaves) best-first: the
/// traversal only collects them with a certified lower bound (separating-axis gap) and prunes
/// with their cheap upper bounds; then the exact distances are computed in increasing order of
/// the lower bound until that bound reaches the smallest exact distance found (no pair left
/// unevaluated can be closer). The result is the same minimum as evaluating every pair.
double environmentDistance(const Environment& env, const Body& body, const Eigen::Isometry3d& X, bool signed_distance,
                           bool skip_ellipsoidal, double cap = std::numeric_limits<double>::max()) {
  if (env.size() == 0) return kInf;
  fcl::CollisionObject<double> obj(body.geometry, toFcl(X));
  obj.computeAABB();
  DistanceData data;
  data.base.request.enable_signed_distance = signed_distance;
  data.base.result.min_distance = cap;
  data.skip_ellipsoidal = skip_ellipsoidal;
  env.manager().distance(&obj, &data, distanceCallback);
  std::sort(data.deferred.begin(), data.deferred.end(),
            [](const DeferredPair& a, const DeferredPair& b) { return a.bound < b.bound; });
  for (const DeferredPair& p : data.deferred) {
    if (data.base.result.min_distance <= 0.0 || p.bound - 1e-12 >= data.base.result.min_distance) break;
    fcl_quadric::distance(p.o1, p.o2, data.base.request, data.base.result);
  }
  if (signed_distance && data.base.result.min_distance <= 0.0) {
    // The broad phase stops at the first pair at distance <= 0 (FCL's DefaultDistanceFunction), so
    // with several overlaps the value was that of whichever the traversal met first
    // (reliability.md finding 33). Every obstacle overlapping the body has a box that meets the
    // body's: each of those gets its signed distance, each in a fresh result (FCL leaves a result
    // at <= 0 unchanged, DistanceRequest::isSatisfied), and the smallest is kept.
    double smallest = data.base.result.min_distance;
    env.manager().collide(&obj, &smallest, [](fcl::CollisionObject<double>* o1, fcl::CollisionObject<double>* o2, void* p) {
      DistanceData pair;
      pair.base.request.enable_signed_distance = true;
      double dist = 0.0;
      distanceCallback(o1, o2, &pair, dist);
      double& m = *static_cast<double*>(p);
      m = std::min(m, pair.base.result.min_distance);
      return false;  // visit every candidate
    });
    return smallest;
  }
  const double d = data.base.result.min_distance;
  return d >= std::numeric_limits<double>::max() ? kInf : d;
}

/// A body or obstacle whose contacts FCL's libccd decides in fcl_quadric::collide (no closed form
/// or exact kernel: box, cylinder, cone, capsule against each other, meshes, octrees and
/// half-spaces). libccd's MPR stops at a tolerance and misses overlaps of 1e-12 to 3e-7 of such
/// shapes (reliability.md finding 33); their static checks use the certified lower bound of
/// distanceLowerBound instead (GJK's, 0 when they may touch).
bool isGjkPrimitive(const fcl::CollisionGeometry<double>* g) {
  switch (g->getNodeType()) {
    case fcl::GEOM_BOX:
    case fcl::GEOM_CYLINDER:
    case fcl::GEOM_CONE:
    case fcl::GEOM_CAPSULE: return true;
    default: return false;
  }
}

/// The smallest positive cap: a lower-bound query with it returns 0 exactly when some pair may
/// touch or overlap, and prunes every obstacle whose box does not meet the body's.
constexpr double kContactCap = std::numeric_limits<double>::min();

bool environmentCollides(const Environment& env, const Body& body, const Eigen::Isometry3d& X) {
  if (env.size() == 0) return false;
  fcl::CollisionObject<double> obj(body.geometry, toFcl(X));
  obj.computeAABB();
  fcl::DefaultCollisionData<double> data;
  env.manager().collide(&obj, &data, fcl_quadric::defaultCollisionFunction<double>);
  if (data.result.isCollision()) return true;
  // Touching counts as collision: a GJK-primitive body is in contact when no obstacle is
  // certified separate from it (errs toward contact within GJK's certified error, ~1e-10 of the
  // size; pairs with an exact kernel, such as its contacts with ellipsoids and spheres, stay exact).
  return isGjkPrimitive(body.geometry.get()) && environmentDistance(env, body, X, false, false, kContactCap) <= 0.0;
}

double pairDistance(const Body& a, const Eigen::Isometry3d& Xa, const Body& b, const Eigen::Isometry3d& Xb,
                    bool signed_distance) {
  if (const std::optional<double> bound = fcl_quadric::distanceLowerBound(a.geometry.get(), toFcl(Xa), b.geometry.get(),
                                                                           toFcl(Xb), std::numeric_limits<double>::max())) {
    return *bound;  // a composite quadric model: a certified lower bound, 0 on contact
  }
  fcl::DistanceRequest<double> request;
  request.enable_signed_distance = signed_distance;
  fcl::DistanceResult<double> result;
  return fcl_quadric::distance(a.geometry.get(), toFcl(Xa), b.geometry.get(), toFcl(Xb), request, result);
}

bool pairCollides(const Body& a, const Eigen::Isometry3d& Xa, const Body& b, const Eigen::Isometry3d& Xb) {
  if (isGjkPrimitive(a.geometry.get()) && isGjkPrimitive(b.geometry.get())) {
    // As in environmentCollides: GJK's certified bound, not libccd's collide (touching counts).
    if (const std::optional<double> bound =
            fcl_quadric::distanceLowerBound(a.geometry.get(), toFcl(Xa), b.geometry.get(), toFcl(Xb), kContactCap))
      return *bound <= 0.0;
  }
  fcl::CollisionRequest<double> request;
  fcl::CollisionResult<double> result;
  return fcl_quadric::collide(a.geometry.get(), toFcl(Xa), b.geometry.get(), toFcl(Xb), request, result) > 0;
}

/// The end configurations of a motion: finite, and for a Fixed-base robot one value per joint
/// within the joint's limits (the speed bound of a prismatic joint's chain assumes its limits,
/// RobotModel::chainLength).
void checkConfiguration(const RobotModel& r, const Configuration& q, const char* which) {
  const std::string where = std::string("RobotCollisionChecker::checkMotion: ");
  if (!detail::allFinite(q.base.matrix())) throw std::invalid_argument(where + "base pose of " + which + " is not finite");
  if (r.base() == RobotModel::Base::Fixed && q.joints.size() != r.jointCount())
    throw std::invalid_argument(where + which + " has " + std::to_string(q.joints.size()) + " joint values, the robot has " +
                                std::to_string(r.jointCount()) + " joints");
  for (std::size_t i = 0; i < q.joints.size(); ++i) {
    if (!std::isfinite(q.joints[i]))
      throw std::invalid_argument(where + "joint " + std::to_string(i) + " of " + which + " is not finite");
    if (r.base() != RobotModel::Base::Fixed) continue;
    const Joint& j = r.joint(i);
    if (q.joints[i] < j.lower || q.joints[i] > j.upper) {
      std::ostringstream os;
      os.precision(17);
      os << where << "joint " << i << " (\"" << j.name << "\") of " << which << " is " << q.joints[i]
         << ", outside its limits [" << j.lower << ", " << j.upper << "]";
      throw std::invalid_argument(os.str());
    }
  }
}

/// The obstacles whose boxes meet the ball of radius r about (c0 + c1) / 2: with c0, c1 the
/// positions of a body's ball centre at t = 0 and 1 and r = ball radius + V / 2 (V the body's
/// speed bound), the ball holds the body for every t in [0, 1] (the centre c(t) is within V t of
/// c0 and V (1 - t) of c1, so |c(t) - (c0 + c1) / 2| <= V / 2). The broad phase of the exact
/// ellipsoid pairs, which otherwise solved the CCD against every ellipsoid obstacle.
std::vector<fcl::CollisionObject<double>*> sweptCandidates(const Environment& env, const Eigen::Vector3d& c0,
                                                           const Eigen::Vector3d& c1, double r) {
  std::vector<fcl::CollisionObject<double>*> out;
  if (env.size() == 0) return out;
  fcl::Transform3<double> tf = fcl::Transform3<double>::Identity();
  tf.translation() = 0.5 * (c0 + c1);
  fcl::CollisionObject<double> probe(std::make_shared<fcl::Sphere<double>>(r), tf);
  probe.computeAABB();
  struct Data {
    const fcl::CollisionObject<double>* probe;
    std::vector<fcl::CollisionObject<double>*>* out;
  } data{&probe, &out};
  env.manager().collide(&probe, &data, [](fcl::CollisionObject<double>* o1, fcl::CollisionObject<double>* o2, void* p) {
    auto* d = static_cast<Data*>(p);
    d->out->push_back(o1 == d->probe ? o2 : o1);
    return false;
  });
  return out;
}

double yawOf(const Eigen::Isometry3d& X) { return std::atan2(X.linear()(1, 0), X.linear()(0, 0)); }

}  // namespace

RobotCollisionChecker::RobotCollisionChecker(std::shared_ptr<const RobotModel> robot,
                                             std::shared_ptr<const Environment> environment)
    : robot_(std::move(robot)), env_(std::move(environment)) {
  if (!robot_) throw std::invalid_argument("RobotCollisionChecker: null robot");
  if (!env_) throw std::invalid_argument("RobotCollisionChecker: null environment");
  robot_->validate();
}

bool RobotCollisionChecker::isValid(const Configuration& q) const {
  std::vector<Eigen::Isometry3d> links;
  robot_->linkPoses(q, links);
  for (std::size_t l = 0; l < links.size(); ++l)
    for (const Body& b : robot_->bodies(l))
      if (environmentCollides(*env_, b, links[l] * b.offset)) return false;
  for (const auto& [la, lb] : robot_->selfCollisionPairs())
    for (const Body& a : robot_->bodies(la))
      for (const Body& b : robot_->bodies(lb))
        if (pairCollides(a, links[la] * a.offset, b, links[lb] * b.offset)) return false;
  return true;
}

double RobotCollisionChecker::clearance(const Configuration& q) const {
  std::vector<Eigen::Isometry3d> links;
  robot_->linkPoses(q, links);
  double d = kInf;
  for (std::size_t l = 0; l < links.size(); ++l)
    for (const Body& b : robot_->bodies(l)) d = std::min(d, environmentDistance(*env_, b, links[l] * b.offset, true, false));
  for (const auto& [la, lb] : robot_->selfCollisionPairs())
    for (const Body& a : robot_->bodies(la))
      for (const Body& b : robot_->bodies(lb))
        d = std::min(d, pairDistance(a, links[la] * a.offset, b, links[lb] * b.offset, true));
  return d;
}

std::vector<double> RobotCollisionChecker::speedBounds(const Configuration& from, const Configuration& to,
                                                       Interpolation kind) const {
  const RobotModel& r = *robot_;
  std::vector<double> V;
  const bool joints = kind == Interpolation::Joints;
  if (joints != (r.base() == RobotModel::Base::Fixed))
    throw std::invalid_argument(
        "RobotCollisionChecker: Joints interpolation needs a Fixed-base robot and a rigid-body interpolation a "
        "Planar / Free one");
  if (kind == Interpolation::Planar && r.base() != RobotModel::Base::Planar)
    throw std::invalid_argument("RobotCollisionChecker: Planar interpolation needs a Planar robot");
  double translation = 0.0, omega = 0.0;
  if (!joints) {
    translation = (to.base.translation() - from.base.translation()).norm();
    if (kind == Interpolation::Planar) {
      const double d = std::abs(yawOf(to.base) - yawOf(from.base));
      omega = d > M_PI ? 2.0 * M_PI - d : d;
    } else {
      const Eigen::Quaterniond q0(from.base.linear()), q1raw(to.base.linear());
      Eigen::Vector4d a = q0.coeffs().normalized(), b = q1raw.coeffs().normalized();
      if (a.dot(b) < 0.0) b = -b;
      if (kind == Interpolation::Slerp)
        omega = 4.0 * std::atan2((a - b).norm(), (a + b).norm());  // 2 theta, theta = 2 atan2(...)
      else
        omega = 4.0 * (b - a).norm() / (a + b).norm();
    }
  }
  for (std::size_t l = 0; l < r.linkCount(); ++l)
    for (const Body& b : r.bodies(l)) {
      const double reach = b.ball_centre.norm() + b.ball_radius;
      double v = 0.0;
      if (!joints) {
        v = translation + omega * reach;
      } else {
        for (std::size_t j = 0; j < l; ++j) {
          const double dq = std::abs(to.joints.at(j) - from.joints.at(j));
          v += r.joint(j).type == JointType::Revolute ? dq * (r.chainLength(j, l) + reach) : dq;
        }
      }
      V.push_back(v > 0.0 ? v * (1.0 + kSpeedRelativeMargin) + kSpeedAbsoluteMargin : 0.0);
    }
  return V;
}

MotionCheckResult RobotCollisionChecker::checkMotion(const Configuration& from, const Configuration& to,
                                                     Interpolation kind,
                                                     const std::function<void(double, Configuration&)>& at,
                                                     const MotionCheckOptions& options, bool stop_at_first) const {
  checkConfiguration(*robot_, from, "the start");
  checkConfiguration(*robot_, to, "the goal");
  if (!at) throw std::invalid_argument("RobotCollisionChecker::checkMotion: null interpolation callback");
  if (!(options.contact_distance >= 0.0) || !std::isfinite(options.contact_distance))
    throw std::invalid_argument("RobotCollisionChecker::checkMotion: contact_distance must be finite and >= 0, got " +
                                std::to_string(options.contact_distance));
  if (options.max_steps < 1)
    throw std::invalid_argument("RobotCollisionChecker::checkMotion: max_steps must be >= 1, got " +
                                std::to_string(options.max_steps));
  const RobotModel& r = *robot_;
  const std::vector<double> V = speedBounds(from, to, kind);
  const bool exact = options.exact_ellipsoid_pairs && kind == Interpolation::QuaternionLerp;

  MotionCheckResult res;
  double T = 1.0;  // earliest contact found so far
  bool found = false;
  auto report = [&](double t) {
    if (!found || t < T) T = t;
    found = true;
  };
  Configuration q;
  std::vector<Eigen::Isometry3d> links;
  auto poseAt = [&](double t) {
    at(t, q);
    r.linkPoses(q, links);
  };

  // Flattened bodies.
  struct Ref {
    std::size_t link;
    const Body* body;
  };
  std::vector<Ref> bodies;
  std::vector<std::size_t> first_of_link(r.linkCount() + 1, 0);
  for (std::size_t l = 0; l < r.linkCount(); ++l) {
    first_of_link[l] = bodies.size();
    for (const Body& b : r.bodies(l)) bodies.push_back({l, &b});
  }
  first_of_link[r.linkCount()] = bodies.size();

  // Conservative advancement of one distance function with speed bound `speed`. distanceNow(cap)
  // returns a lower bound of the distance, or a value >= cap when nothing is closer than cap.
  auto advance = [&](double speed, const std::function<double(double)>& distanceNow) {
    double t = 0.0;
    for (int step = 0;; ++step) {
      if (found && t >= T) return;  // cannot improve the earliest contact
      poseAt(t);
      // A distance of 2 speed (1 - t) already carries the advancement past t = 1.
      const double cap = speed > 0.0 ? 2.0 * speed * (1.0 - t) + 2.0 * options.contact_distance + 1e-9 : kInf;
      const double d = distanceNow(std::min(cap, std::numeric_limits<double>::max()));
      ++res.advancement_steps;
      if (d <= options.contact_distance || step >= options.max_steps) {
        report(t);
        return;
      }
      if (!(speed > 0.0)) return;  // the body does not move
      const double next = t + d / speed;
      if (next > 1.0) return;
      t = next;
    }
  };

  // 1. Exact ellipsoid pairs (QuaternionLerp only: the base motion is MotionMatrix::fromPoses).
  if (exact) {
    const MotionMatrix base = MotionMatrix::fromPoses(from.base, to.base);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const Ref& ref = bodies[i];
      if (!isEllipsoidal(ref.body->geometry.get())) continue;
      const Eigen::Isometry3d& off = ref.body->offset;
      MovingEllipsoid a{ellipsoidOf(ref.body->geometry.get(), Eigen::Isometry3d::Identity()),
                        PiecewiseMotion(MotionMatrix::compose(base, MotionMatrix::constant(off.linear(), off.translation())))};
      for (fcl::CollisionObject<double>* obj : sweptCandidates(*env_, from.base * ref.body->ball_centre,
                                                               to.base * ref.body->ball_centre,
                                                               ref.body->ball_radius + 0.5 * V[i])) {
        if (!isEllipsoidal(obj->collisionGeometry().get())) continue;
        if (found && T <= 0.0) break;
        Eigen::Isometry3d Xo = Eigen::Isometry3d::Identity();
        Xo.linear() = obj->getRotation();
        Xo.translation() = obj->getTranslation();
        MovingEllipsoid b{ellipsoidOf(obj->collisionGeometry().get(), Xo), PiecewiseMotion()};
        CcdOptions o;
        o.all_intervals = false;
        o.t_max = found ? T : 1.0;
        const EllipsoidCcdResult c = continuousCollideEllipsoids(a, b, o);
        ++res.exact_solves;
        if (c.collide) report(c.first_contact_time.value_or(0.0));
        if (found && stop_at_first) break;
      }
      if (found && stop_at_first) break;
    }
  }

  // 2. Bodies against the environment (every obstacle, or the non-ellipsoidal ones when exact).
  for (std::size_t i = 0; i < bodies.size() && !(found && stop_at_first); ++i) {
    const Ref& ref = bodies[i];
    const bool skip = exact && isEllipsoidal(ref.body->geometry.get());
    advance(V[i], [&](double cap) {
      return environmentDistance(*env_, *ref.body, links[ref.link] * ref.body->offset, false, skip, cap);
    });
  }

  // 3. Self-collision pairs.
  for (const auto& [la, lb] : r.selfCollisionPairs()) {
    for (std::size_t ia = first_of_link[la]; ia < first_of_link[la + 1]; ++ia)
      for (std::size_t ib = first_of_link[lb]; ib < first_of_link[lb + 1]; ++ib) {
        if (found && stop_at_first) break;
        const Ref& a = bodies[ia];
        const Ref& b = bodies[ib];
        advance(V[ia] + V[ib], [&](double) {
          return pairDistance(*a.body, links[a.link] * a.body->offset, *b.body, links[b.link] * b.body->offset, false);
        });
      }
  }

  if (!found) return res;
  res.valid = false;
  res.contact_time = T;
  // Every instant before T is certified free (robot_checker.h); step back from T by a margin that
  // covers the exact solver's early-reporting tolerance and confirm with the static check.
  res.last_valid_time = 0.0;
  for (double delta : {1e-9, 1e-7, 1e-5, 1e-3}) {
    const double t = T - delta;
    if (t <= 0.0) break;
    at(t, q);
    if (isValid(q)) {
      res.last_valid_time = t;
      break;
    }
  }
  return res;
}

}  // namespace planning
}  // namespace fcl_quadric
