// FCL's broad-phase managers, unchanged, with the exact narrow phase (issue 3, "Broad phase,
// unchanged"): a scene of more than 1,000 ellipsoids plus spheres, boxes and a triangle-mesh
// BVHModel<OBBRSS> (a tessellated torus), registered in every broad-phase manager type of FCL 0.7,
// gives exactly the brute-force answers.
//  - Collision: with fcl_quadric::defaultCollisionFunction, the set of colliding object pairs equals
//    the brute-force set (every pair through fcl_quadric::collide, in both argument orders) for
//    the self query, for unregistered query objects (manager.collide(obj, ...)) and between two
//    managers (manager.collide(other, ...)). The oracle itself is checked against the geometry
//    layer: every ellipsoid/sphere pair against classifyEllipsoids; ellipsoid/sphere-box and
//    ellipsoid/sphere-mesh pairs against classifyEllipsoidBox / classifyEllipsoidTriangle when
//    QuadricSolver answers them exactly (detail::QuadricPair / QuadricTriangle), and otherwise the
//    disagreements of the delegated (libccd) answers are only printed.
//  - Distance: with fcl_quadric::defaultDistanceFunction, the minimum distance of a scene of
//    pairwise separate objects equals the brute-force minimum (1e-9 relative), for the self query
//    and for unregistered query objects.
//  - Coherence: coherentCollisionFunction with one PairCache in a DynamicAABBTree over frames of
//    small rigid motions (near-tangent pairs move rigidly, so they stay within 1e-8 of tangency),
//    with a radius edited in place, an object unregistered and registered again, equals brute
//    force every frame.
// The scenes hold near-tangent pairs (relative gap 1e-8, both sides) so that a narrow phase that
// is not exact would be caught. Pairs that reach stock libccd run with the test main's
// floating-point traps off (test::ScopedNoFpTraps); the exact pairs keep them on.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/broadphase/broadphase_SSaP.h>
#include <fcl/broadphase/broadphase_SaP.h>
#include <fcl/broadphase/broadphase_bruteforce.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree_array.h>
#include <fcl/broadphase/broadphase_interval_tree.h>
#include <fcl/broadphase/broadphase_spatialhash.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/math/bv/OBBRSS.h>

#include "fcl/fcl_test_support.h"
#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/pair_cache.h"
#include "fcl_quadric/fcl/quadric_solver.h"
#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/signed_distance.h"
#include "support/fcl_fixtures.h"

namespace fcl_quadric {
namespace {

using Index = int;
using IndexPair = std::pair<Index, Index>;  ///< always first < second
using PairSet = std::set<IndexPair>;
using Manager = fcl::BroadPhaseCollisionManagerd;

constexpr double kTangentGap = 1e-8;        ///< relative gap of the near-tangent pairs
constexpr double kDistanceRelTol = 1e-9;    ///< manager minimum vs brute-force minimum

IndexPair ordered(Index a, Index b) { return a < b ? IndexPair{a, b} : IndexPair{b, a}; }

/// Three draws, in this order (the evaluation order of function arguments is unspecified).
template <typename Draw>
Eigen::Vector3d draw3(Draw draw) {
  const double x = draw();
  const double y = draw();
  const double z = draw();
  return Eigen::Vector3d(x, y, z);
}

// ------------------------------------------------------------------------------------------------
// Which pairs QuadricSolver answers exactly (read from its dispatch tables, so the checks below
// tighten by themselves when a pair becomes exact), and the floating-point traps around the rest.

template <typename S1, typename S2>
constexpr bool exactShapePair() {
  return detail::QuadricPair<S1, S2>::kind != detail::QuadricPairKind::kLibccd;
}
template <typename Shape>
constexpr bool exactTriangle() {
  return detail::QuadricTriangle<Shape>::kind != detail::QuadricPairKind::kLibccd;
}

template <typename S1>
bool exactWith(fcl::NODE_TYPE t2) {
  switch (t2) {
    case fcl::GEOM_ELLIPSOID: return exactShapePair<S1, fcl::Ellipsoidd>();
    case fcl::GEOM_SPHERE: return exactShapePair<S1, fcl::Sphered>();
    case fcl::GEOM_BOX: return exactShapePair<S1, fcl::Boxd>();
    default: return false;
  }
}

bool exactTriangleFor(fcl::NODE_TYPE shape) {
  switch (shape) {
    case fcl::GEOM_ELLIPSOID: return exactTriangle<fcl::Ellipsoidd>();
    case fcl::GEOM_SPHERE: return exactTriangle<fcl::Sphered>();
    case fcl::GEOM_BOX: return exactTriangle<fcl::Boxd>();
    default: return false;
  }
}

/// True iff QuadricSolver answers the pair of node types without libccd.
bool runsExact(fcl::NODE_TYPE t1, fcl::NODE_TYPE t2) {
  switch (t1) {
    case fcl::GEOM_ELLIPSOID: return exactWith<fcl::Ellipsoidd>(t2);
    case fcl::GEOM_SPHERE: return exactWith<fcl::Sphered>(t2);
    case fcl::GEOM_BOX: return exactWith<fcl::Boxd>(t2);
    case fcl::BV_OBBRSS: return exactTriangleFor(t2);
    default: return t2 == fcl::BV_OBBRSS && exactTriangleFor(t1);
  }
}

bool runsExact(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b) {
  return runsExact(a.collisionGeometry()->getNodeType(), b.collisionGeometry()->getNodeType());
}

/// The broad-phase callbacks under test, unchanged; only the FP traps are switched off for pairs
/// that reach libccd (stock libccd raises FE_INVALID / FE_DIVBYZERO internally and recovers).
bool collisionCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  std::optional<test::ScopedNoFpTraps> no_traps;
  if (!runsExact(*o1, *o2)) no_traps.emplace();
  return fcl_quadric::defaultCollisionFunction<double>(o1, o2, data);
}
bool coherentCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  std::optional<test::ScopedNoFpTraps> no_traps;
  if (!runsExact(*o1, *o2)) no_traps.emplace();
  return fcl_quadric::coherentCollisionFunction(o1, o2, data);
}
bool distanceCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data, double& dist) {
  std::optional<test::ScopedNoFpTraps> no_traps;
  if (!runsExact(*o1, *o2)) no_traps.emplace();
  return fcl_quadric::defaultDistanceFunction<double>(o1, o2, data, dist);
}

// ------------------------------------------------------------------------------------------------
// Scenes

enum class Kind { kEllipsoid, kSphere, kBox, kMesh };

const char* kindName(Kind k) {
  switch (k) {
    case Kind::kEllipsoid: return "ellipsoid";
    case Kind::kSphere: return "sphere";
    case Kind::kBox: return "box";
    case Kind::kMesh: return "mesh";
  }
  return "?";
}

struct TriangleMesh {
  std::vector<fcl::Vector3d> vertices;  ///< in the mesh frame
  std::vector<fcl::Triangle> triangles;
};

/// A torus around the z axis (major radius R, tube radius r), nu x nv quads split in two.
std::shared_ptr<const TriangleMesh> torus(double R, double r, int nu, int nv) {
  auto m = std::make_shared<TriangleMesh>();
  for (int i = 0; i < nu; ++i) {
    const double u = 2.0 * M_PI * i / nu;
    for (int j = 0; j < nv; ++j) {
      const double v = 2.0 * M_PI * j / nv;
      m->vertices.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return static_cast<std::size_t>(((i + nu) % nu) * nv + (j + nv) % nv); };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      m->triangles.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      m->triangles.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
  return m;
}

struct Body {
  Kind kind = Kind::kEllipsoid;
  std::shared_ptr<const TriangleMesh> mesh;  ///< kMesh only
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  std::unique_ptr<fcl::CollisionObjectd> object;
  fcl::Transform3d X0 = fcl::Transform3d::Identity();  ///< pose at frame 0
  int group = 0;  ///< bodies of a group move rigidly together

  bool quadric() const { return kind == Kind::kEllipsoid || kind == Kind::kSphere; }
  const fcl::Transform3d& pose() const { return object->getTransform(); }
  /// The ellipsoid or sphere, read from the geometry (radii edited in place are seen) and pose.
  Ellipsoid asEllipsoid() const {
    const fcl::Transform3d& X = pose();
    if (kind == Kind::kSphere) return Ellipsoid::sphere(static_cast<const fcl::Sphered&>(*geometry).radius, X.translation());
    return Ellipsoid(static_cast<const fcl::Ellipsoidd&>(*geometry).radii, X.linear(), X.translation());
  }
  Eigen::Vector3d boxHalfExtents() const { return 0.5 * static_cast<const fcl::Boxd&>(*geometry).side; }
  void setPose(const fcl::Transform3d& X) {
    object->setTransform(X);
    object->computeAABB();
  }
};

Body makeBody(Kind kind, std::shared_ptr<fcl::CollisionGeometryd> geometry, const fcl::Transform3d& X,
              std::shared_ptr<const TriangleMesh> mesh = nullptr) {
  Body b;
  b.kind = kind;
  b.mesh = std::move(mesh);
  b.geometry = std::move(geometry);
  b.object = std::make_unique<fcl::CollisionObjectd>(b.geometry, X);
  b.X0 = X;
  return b;
}

Body meshBody(std::shared_ptr<const TriangleMesh> mesh, const fcl::Transform3d& X) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  model->beginModel(static_cast<int>(mesh->triangles.size()), static_cast<int>(mesh->vertices.size()));
  model->addSubModel(mesh->vertices, mesh->triangles);
  model->endModel();
  return makeBody(Kind::kMesh, model, X, std::move(mesh));
}

using test::pose;

/// Rigid motion of a group per frame k: rotation by omega k about `axis` through `pivot`, then a
/// drift by velocity k.
struct Motion {
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero(), velocity = Eigen::Vector3d::Zero(), axis = Eigen::Vector3d::UnitZ();
  double omega = 0.0;
  fcl::Transform3d at(int k) const {
    fcl::Transform3d M = fcl::Transform3d::Identity();
    M.translate(pivot + static_cast<double>(k) * velocity);
    M.rotate(Eigen::AngleAxisd(omega * k, axis));
    M.translate(-pivot);
    return M;
  }
};

struct SceneSpec {
  int ellipsoids = 1000;   ///< random ellipsoids (the near-tangent pairs add more)
  int spheres = 200;
  int boxes = 100;
  int tangent_pairs = 60;  ///< near-tangent ellipsoid-ellipsoid / -sphere / -box pairs, in turn
  int queries = 12;        ///< unregistered query objects (ellipsoids, spheres, boxes, a mesh)
  double side = 21.0;      ///< the region [0, side]^3
  bool pairwise_separate = false;  ///< rejection sampling: no two objects collide
  std::uint64_t seed = 2024;
};

struct Scene {
  std::vector<Body> bodies;   ///< registered in the managers; index i
  std::vector<Body> queries;  ///< not registered; index bodies.size() + q
  std::vector<Motion> motions;
  std::unordered_map<const fcl::CollisionGeometryd*, Index> index;
  struct TangentPair {
    IndexPair bodies;
    bool inward;  ///< just overlapping (else just separate)
  };
  std::vector<TangentPair> tangent_pairs;

  Index size() const { return static_cast<Index>(bodies.size()); }
  const Body& at(Index i) const { return i < size() ? bodies[i] : queries[i - size()]; }
  IndexPair pairOf(const fcl::CollisionGeometryd* a, const fcl::CollisionGeometryd* b) const {
    return ordered(index.at(a), index.at(b));
  }
  std::vector<fcl::CollisionObjectd*> objects(const std::function<bool(Index)>& keep) const {
    std::vector<fcl::CollisionObjectd*> out;
    for (Index i = 0; i < size(); ++i)
      if (keep(i)) out.push_back(bodies[i].object.get());
    return out;
  }
  std::string describe(Index i) const {
    std::ostringstream s;
    s << (i < size() ? "#" : "query #") << (i < size() ? i : i - size()) << " (" << kindName(at(i).kind) << ")";
    return s.str();
  }
  std::map<Kind, int> counts() const {
    std::map<Kind, int> c;
    for (const Body& b : bodies) ++c[b.kind];
    return c;
  }
  /// Poses of frame k (every body), then AABBs.
  void setFrame(int k) {
    for (Body& b : bodies) b.setPose(motions[b.group].at(k) * b.X0);
  }
};

bool frontDoorCollide(const Body& a, const Body& b) {
  std::optional<test::ScopedNoFpTraps> no_traps;
  if (!runsExact(*a.object, *b.object)) no_traps.emplace();
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  return fcl_quadric::collide(a.object.get(), b.object.get(), request, result) > 0;
}

double frontDoorDistance(const Body& a, const Body& b) {
  std::optional<test::ScopedNoFpTraps> no_traps;
  if (!runsExact(*a.object, *b.object)) no_traps.emplace();
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  return fcl_quadric::distance(a.object.get(), b.object.get(), request, result);
}

bool aabbsOverlap(const Body& a, const Body& b, double margin) {
  const fcl::AABBd &x = a.object->getAABB(), &y = b.object->getAABB();
  for (int k = 0; k < 3; ++k)
    if (x.min_[k] > y.max_[k] + margin || y.min_[k] > x.max_[k] + margin) return false;
  return true;
}

class SceneBuilder {
 public:
  explicit SceneBuilder(const SceneSpec& spec) : spec_(spec), rng_(spec.seed) {}

  Scene build() {
    Scene s;
    // The mesh first (large, in the middle), then near-tangent pairs, then the random bodies.
    {
      std::uniform_real_distribution<double> jitter(-1.0, 1.0);
      const Eigen::Vector3d centre = Eigen::Vector3d::Constant(0.5 * spec_.side) + draw3([&] { return jitter(rng_); });
      add(&s.bodies, meshBody(torus(2.4, 0.45, 48, 24), pose(test::randomRotation(rng_), centre)));
    }
    for (int t = 0; t < spec_.tangent_pairs; ++t) addTangentPair(&s, t % 3, t % 2 == 0);
    for (int i = 0; i < spec_.ellipsoids; ++i) addRandom(&s, Kind::kEllipsoid, &s.bodies);
    for (int i = 0; i < spec_.spheres; ++i) addRandom(&s, Kind::kSphere, &s.bodies);
    for (int i = 0; i < spec_.boxes; ++i) addRandom(&s, Kind::kBox, &s.bodies);
    // Unregistered query objects: every kind, and a second (smaller) mesh.
    for (int q = 0; q < spec_.queries; ++q) {
      const int k = q % 4;
      if (k == 3) {
        std::uniform_real_distribution<double> uc(2.0, spec_.side - 2.0);
        for (int attempt = 0;; ++attempt) {
          Body b = meshBody(torus(0.9, 0.3, 24, 12), pose(test::randomRotation(rng_), draw3([&] { return uc(rng_); })));
          if (acceptable(b, s)) {
            add(&s.queries, std::move(b));
            break;
          }
        }
      } else {
        addRandom(&s, k == 0 ? Kind::kEllipsoid : k == 1 ? Kind::kSphere : Kind::kBox, &s.queries);
      }
    }
    for (Index i = 0; i < s.size(); ++i) s.index[s.bodies[i].geometry.get()] = i;
    for (std::size_t q = 0; q < s.queries.size(); ++q) s.index[s.queries[q].geometry.get()] = s.size() + static_cast<Index>(q);
    // One rigid motion per group: slow drift and spin (the mesh too).
    std::uniform_real_distribution<double> u(0.5, 1.0);
    for (Body& b : s.bodies) {
      if (b.group < static_cast<int>(s.motions.size())) continue;
      Motion m;
      m.pivot = b.X0.translation();
      m.velocity = 0.03 * u(rng_) * test::randomUnitVector(rng_);
      m.axis = test::randomUnitVector(rng_);
      m.omega = (b.kind == Kind::kMesh ? 0.005 : 0.03) * u(rng_);
      s.motions.push_back(m);
    }
    return s;
  }

 private:
  /// With pairwise_separate, a body is acceptable only if it collides with nothing placed so far.
  bool acceptable(const Body& b, const Scene& s) const {
    if (!spec_.pairwise_separate) return true;
    for (const std::vector<Body>* list : {&s.bodies, &s.queries})
      for (const Body& o : *list)
        if (aabbsOverlap(b, o, 0.0) && frontDoorCollide(b, o)) return false;
    return true;
  }

  void add(std::vector<Body>* list, Body b) {
    b.group = next_group_++;
    list->push_back(std::move(b));
  }

  Body randomBody(Kind kind, const Eigen::Vector3d& centre) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Eigen::Matrix3d R = test::randomRotation(rng_);
    switch (kind) {
      case Kind::kEllipsoid: {
        const Eigen::Vector3d r = test::randomRadii(rng_, 0.35 + 0.55 * u(rng_), 4.0);
        return makeBody(kind, std::make_shared<fcl::Ellipsoidd>(r), pose(R, centre));
      }
      case Kind::kSphere:
        return makeBody(kind, std::make_shared<fcl::Sphered>(0.2 + 0.5 * u(rng_)), pose(R, centre));
      case Kind::kBox: {
        const Eigen::Vector3d side = draw3([&] { return 0.3 + 0.9 * u(rng_); });
        return makeBody(kind, std::make_shared<fcl::Boxd>(side), pose(R, centre));
      }
      case Kind::kMesh: break;
    }
    return Body();
  }

  void addRandom(Scene* s, Kind kind, std::vector<Body>* list) {
    std::uniform_real_distribution<double> uc(1.0, spec_.side - 1.0);
    for (;;) {
      Body b = randomBody(kind, draw3([&] { return uc(rng_); }));
      if (acceptable(b, *s)) {
        add(list, std::move(b));
        return;
      }
    }
  }

  /// An ellipsoid and an ellipsoid (which 0), a sphere (1) or a box (2) at relative gap
  /// kTangentGap from tangency along a random direction, just overlapping (`inward`) or just
  /// separate; bisection with the exact tests of the geometry layer. Both move as one group.
  void addTangentPair(Scene* s, int which, bool inward) {
    std::uniform_real_distribution<double> u(0.0, 1.0), uc(2.0, spec_.side - 2.0);
    const Eigen::Vector3d ra = test::randomRadii(rng_, 0.4 + 0.5 * u(rng_), 4.0);
    const Eigen::Matrix3d Ra = test::randomRotation(rng_), Rb = test::randomRotation(rng_);
    const Eigen::Vector3d c = draw3([&] { return uc(rng_); });
    const Eigen::Vector3d d = test::randomUnitVector(rng_);
    const Ellipsoid a(ra, Ra, c);
    const Eigen::Vector3d rb = which == 0 ? test::randomRadii(rng_, 0.3 + 0.5 * u(rng_), 4.0)
                                          : which == 1 ? Eigen::Vector3d::Constant(0.2 + 0.4 * u(rng_))
                                                       : draw3([&] { return 0.15 + 0.45 * u(rng_); });
    auto separated = [&](double t) {
      const Eigen::Vector3d cb = c + t * d;
      if (which == 0) return classifyEllipsoids(a, Ellipsoid(rb, Rb, cb)).status == Separation::Separated;
      if (which == 1) return classifyEllipsoids(a, Ellipsoid::sphere(rb[0], cb)).status == Separation::Separated;
      return classifyEllipsoidBox(a, rb, Rb, cb).status == Separation::Separated;
    };
    double lo = 0.0, hi = 2.0 * (ra.maxCoeff() + std::sqrt(3.0) * rb.maxCoeff());
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (separated(mid) ? hi : lo) = mid;
    }
    const double t = inward ? lo * (1.0 - kTangentGap) : hi * (1.0 + kTangentGap);
    const fcl::Transform3d Xb = pose(Rb, c + t * d);
    Body ba = makeBody(Kind::kEllipsoid, std::make_shared<fcl::Ellipsoidd>(ra), pose(Ra, c));
    Body bb = which == 0   ? makeBody(Kind::kEllipsoid, std::make_shared<fcl::Ellipsoidd>(rb), Xb)
              : which == 1 ? makeBody(Kind::kSphere, std::make_shared<fcl::Sphered>(rb[0]), Xb)
                           : makeBody(Kind::kBox, std::make_shared<fcl::Boxd>(2.0 * rb), Xb);
    const int group = next_group_++;
    ba.group = bb.group = group;
    const Index ia = static_cast<Index>(s->bodies.size());
    s->tangent_pairs.push_back({IndexPair{ia, ia + 1}, inward});
    s->bodies.push_back(std::move(ba));
    s->bodies.push_back(std::move(bb));
  }

  SceneSpec spec_;
  std::mt19937_64 rng_;
  int next_group_ = 0;
};

// ------------------------------------------------------------------------------------------------
// Brute-force oracles

/// Exact answer of the geometry layer for a quadric against a box or a mesh (any triangle).
bool exactQuadricPolytope(const Body& quadric, const Body& other) {
  const Ellipsoid e = quadric.asEllipsoid();
  if (other.kind == Kind::kBox) {
    return classifyEllipsoidBox(e, other.boxHalfExtents(), other.pose().linear(), other.pose().translation()).status !=
           Separation::Separated;
  }
  const double reach = e.radii().maxCoeff();
  for (const fcl::Triangle& t : other.mesh->triangles) {
    const Eigen::Vector3d a = other.pose() * other.mesh->vertices[t[0]];
    const Eigen::Vector3d b = other.pose() * other.mesh->vertices[t[1]];
    const Eigen::Vector3d c = other.pose() * other.mesh->vertices[t[2]];
    const double size = std::max({(a - b).norm(), (b - c).norm(), (c - a).norm()});
    if ((a - e.center()).norm() > reach + size) continue;  // cannot touch
    if (classifyEllipsoidTriangle(e, a, b, c).status != Separation::Separated) return true;
  }
  return false;
}

struct CollisionOracle {
  PairSet colliding;        ///< fcl_quadric::collide reports a collision in both argument orders
  PairSet order_dependent;  ///< the two argument orders disagree (allowed only where libccd runs)
  std::size_t pairs = 0;
  std::size_t quadric_checked = 0, quadric_mismatch = 0;  ///< vs classifyEllipsoids (must be 0)
  std::size_t exact_order_dependent = 0;                  ///< exact pairs whose orders disagree (must be 0)
  /// Quadric-box and quadric-mesh pairs with overlapping AABBs against classifyEllipsoidBox /
  /// classifyEllipsoidTriangle: [box, mesh][exact, delegated to libccd]. Only the exact
  /// mismatches are failures; the delegated ones are printed.
  std::size_t polytope_checked[2][2] = {{0, 0}, {0, 0}}, polytope_mismatch[2][2] = {{0, 0}, {0, 0}};
  std::vector<std::string> failures;  ///< the first few

  void note(const std::string& s) {
    if (failures.size() < 8) failures.push_back(s);
  }
};

void evaluateCollision(const Scene& s, Index i, Index j, CollisionOracle* o) {
  const Body &a = s.at(i), &b = s.at(j);
  const bool ab = frontDoorCollide(a, b), ba = frontDoorCollide(b, a);
  const bool exact = runsExact(*a.object, *b.object);
  ++o->pairs;
  if (ab != ba) {
    o->order_dependent.insert(ordered(i, j));
    if (exact) {
      ++o->exact_order_dependent;
      o->note("argument order changes the exact answer: " + s.describe(i) + " / " + s.describe(j));
    }
  } else if (ab) {
    o->colliding.insert(ordered(i, j));
  }
  if (a.quadric() && b.quadric()) {
    ++o->quadric_checked;
    const bool truth = classifyEllipsoids(a.asEllipsoid(), b.asEllipsoid()).status != Separation::Separated;
    if (ab != truth || ba != truth) {
      ++o->quadric_mismatch;
      o->note("fcl_quadric::collide differs from classifyEllipsoids: " + s.describe(i) + " / " + s.describe(j));
    }
  } else if (a.quadric() != b.quadric() && (a.kind == Kind::kBox || b.kind == Kind::kBox || a.kind == Kind::kMesh ||
                                            b.kind == Kind::kMesh)) {
    const Body& q = a.quadric() ? a : b;
    const Body& p = a.quadric() ? b : a;
    if (!aabbsOverlap(q, p, 1e-6)) {
      if (ab || ba) o->note("collision reported for disjoint AABBs: " + s.describe(i) + " / " + s.describe(j));
      return;
    }
    const bool truth = exactQuadricPolytope(q, p);
    const bool mismatch = ab != truth || ba != truth;
    const int kind = p.kind == Kind::kBox ? 0 : 1, path = exact ? 0 : 1;
    ++o->polytope_checked[kind][path];
    o->polytope_mismatch[kind][path] += mismatch;
    if (exact && mismatch) o->note("exact pair differs from the geometry layer: " + s.describe(i) + " / " + s.describe(j));
  }
}

/// Every pair of registered bodies (active ones only, if `active` is given).
CollisionOracle bruteForceCollisions(const Scene& s, const std::vector<bool>* active = nullptr) {
  CollisionOracle o;
  for (Index i = 0; i < s.size(); ++i) {
    if (active && !(*active)[i]) continue;
    for (Index j = i + 1; j < s.size(); ++j) {
      if (active && !(*active)[j]) continue;
      evaluateCollision(s, i, j, &o);
    }
  }
  return o;
}

/// Every (query, body) pair.
CollisionOracle bruteForceQueryCollisions(const Scene& s) {
  CollisionOracle o;
  for (std::size_t q = 0; q < s.queries.size(); ++q)
    for (Index i = 0; i < s.size(); ++i) evaluateCollision(s, s.size() + static_cast<Index>(q), i, &o);
  return o;
}

void expectCleanOracle(const CollisionOracle& o, const char* what) {
  EXPECT_EQ(o.quadric_mismatch, 0u) << what;
  EXPECT_EQ(o.exact_order_dependent, 0u) << what;
  EXPECT_EQ(o.polytope_mismatch[0][0], 0u) << what << ": exact quadric-box pairs vs classifyEllipsoidBox";
  EXPECT_EQ(o.polytope_mismatch[1][0], 0u) << what << ": exact quadric-mesh pairs vs classifyEllipsoidTriangle";
  for (const std::string& f : o.failures) ADD_FAILURE() << what << ": " << f;
}

void printOracle(const CollisionOracle& o, const char* what) {
  std::printf("[ info ] %s: %zu pairs, %zu colliding, %zu whose answer depends on the argument order (libccd); "
              "%zu of %zu ellipsoid/sphere pairs agree with classifyEllipsoids\n",
              what, o.pairs, o.colliding.size(), o.order_dependent.size(), o.quadric_checked - o.quadric_mismatch,
              o.quadric_checked);
  const char* names[2] = {"quadric-box pairs vs classifyEllipsoidBox", "quadric-mesh pairs vs classifyEllipsoidTriangle"};
  for (int k = 0; k < 2; ++k) {
    std::printf("[ info ]   %s (overlapping AABBs): exact path %zu checked, %zu differ; libccd path %zu checked, "
                "%zu differ\n",
                names[k], o.polytope_checked[k][0], o.polytope_mismatch[k][0], o.polytope_checked[k][1],
                o.polytope_mismatch[k][1]);
  }
}

/// Keeps the pairs of an oracle that satisfy `keep`.
CollisionOracle restrictTo(const CollisionOracle& o, const std::function<bool(const IndexPair&)>& keep) {
  CollisionOracle r;
  for (const IndexPair& p : o.colliding)
    if (keep(p)) r.colliding.insert(p);
  for (const IndexPair& p : o.order_dependent)
    if (keep(p)) r.order_dependent.insert(p);
  return r;
}

/// The colliding pairs a manager reported, from the contacts of the result. Pairs reported with
/// more than one contact although neither object is a mesh are counted in `duplicates` (a mesh
/// pair may report one contact per triangle).
PairSet contactPairs(const Scene& s, const fcl::CollisionResultd& r, std::size_t* duplicates) {
  std::map<IndexPair, int> count;
  for (std::size_t k = 0; k < r.numContacts(); ++k) ++count[s.pairOf(r.getContact(k).o1, r.getContact(k).o2)];
  PairSet out;
  *duplicates = 0;
  for (const auto& [p, n] : count) {
    out.insert(p);
    if (n > 1 && s.at(p.first).kind != Kind::kMesh && s.at(p.second).kind != Kind::kMesh) ++*duplicates;
  }
  return out;
}

/// found must contain every oracle collision and nothing but oracle collisions and
/// order-dependent pairs.
::testing::AssertionResult sameCollisions(const Scene& s, const PairSet& found, const CollisionOracle& o) {
  std::vector<IndexPair> missing, extra;
  std::set_difference(o.colliding.begin(), o.colliding.end(), found.begin(), found.end(), std::back_inserter(missing));
  for (const IndexPair& p : found)
    if (!o.colliding.count(p) && !o.order_dependent.count(p)) extra.push_back(p);
  if (missing.empty() && extra.empty()) return ::testing::AssertionSuccess();
  auto failure = ::testing::AssertionFailure();
  failure << missing.size() << " colliding pairs missing, " << extra.size() << " extra (of " << o.colliding.size()
          << " colliding)";
  for (std::size_t k = 0; k < std::min<std::size_t>(missing.size(), 5); ++k)
    failure << "\n  missing " << s.describe(missing[k].first) << " / " << s.describe(missing[k].second);
  for (std::size_t k = 0; k < std::min<std::size_t>(extra.size(), 5); ++k)
    failure << "\n  extra   " << s.describe(extra[k].first) << " / " << s.describe(extra[k].second);
  return failure;
}

/// The near-tangent pairs (relative gap 1e-8): where QuadricSolver is exact, the oracle reports
/// the inward ones colliding and the outward ones not; the delegated ones are only counted.
/// Returns a summary "inward found a/b exact, c/d delegated; outward found ...".
std::string checkTangentPairs(const Scene& s, const CollisionOracle& o) {
  std::size_t found[2][2] = {{0, 0}, {0, 0}}, total[2][2] = {{0, 0}, {0, 0}};  // [inward, outward][exact, libccd]
  for (const Scene::TangentPair& t : s.tangent_pairs) {
    const bool exact = runsExact(*s.at(t.bodies.first).object, *s.at(t.bodies.second).object);
    const bool hit = o.colliding.count(t.bodies) > 0;
    ++total[t.inward ? 0 : 1][exact ? 0 : 1];
    found[t.inward ? 0 : 1][exact ? 0 : 1] += hit;
    if (exact) {
      EXPECT_EQ(hit, t.inward) << "near-tangent pair " << s.describe(t.bodies.first) << " / "
                               << s.describe(t.bodies.second) << (t.inward ? " (overlapping)" : " (separate)");
    }
  }
  std::ostringstream out;
  out << "overlapping ones reported colliding " << found[0][0] << "/" << total[0][0] << " exact, " << found[0][1] << "/"
      << total[0][1] << " via libccd; separate ones reported colliding " << found[1][0] << "/" << total[1][0]
      << " exact, " << found[1][1] << "/" << total[1][1] << " via libccd";
  return out.str();
}

// ------------------------------------------------------------------------------------------------
// Managers

struct ManagerType {
  std::string name;
  std::function<std::unique_ptr<Manager>()> make;
};

/// Every broad-phase manager type of FCL 0.7. SpatialHashing gets the scene's AABB and a cell of
/// about two object diameters, with both of its hash tables; a third instance covers only the
/// middle of the scene, so objects also lie partly or wholly outside its scene limit.
std::vector<ManagerType> managerTypes(const Scene& s) {
  std::vector<fcl::CollisionObjectd*> all = s.objects([](Index) { return true; });
  for (const Body& q : s.queries) all.push_back(q.object.get());
  fcl::Vector3d lo, hi;
  fcl::SpatialHashingCollisionManagerd<>::computeBound(all, lo, hi);
  const double cell = 2.5;
  const fcl::Vector3d mid_lo = lo + 0.3 * (hi - lo), mid_hi = hi - 0.3 * (hi - lo);
  using SparseTable = fcl::detail::SparseHashTable<fcl::AABBd, fcl::CollisionObjectd*, fcl::detail::SpatialHash<double>>;
  std::vector<ManagerType> m;
  m.push_back({"DynamicAABBTree", [] { return std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>(); }});
  m.push_back({"DynamicAABBTree_Array", [] { return std::make_unique<fcl::DynamicAABBTreeCollisionManager_Arrayd>(); }});
  m.push_back({"SaP", [] { return std::make_unique<fcl::SaPCollisionManagerd>(); }});
  m.push_back({"SSaP", [] { return std::make_unique<fcl::SSaPCollisionManagerd>(); }});
  m.push_back({"IntervalTree", [] { return std::make_unique<fcl::IntervalTreeCollisionManagerd>(); }});
  m.push_back({"SpatialHashing", [=] { return std::make_unique<fcl::SpatialHashingCollisionManagerd<>>(cell, lo, hi); }});
  m.push_back({"SpatialHashing_SparseHashTable",
               [=] { return std::make_unique<fcl::SpatialHashingCollisionManager<double, SparseTable>>(cell, lo, hi); }});
  m.push_back({"SpatialHashing_PartialSceneLimit",
               [=] { return std::make_unique<fcl::SpatialHashingCollisionManagerd<>>(cell, mid_lo, mid_hi); }});
  m.push_back({"Naive", [] { return std::make_unique<fcl::NaiveCollisionManagerd>(); }});
  return m;
}

std::unique_ptr<Manager> registered(const ManagerType& type, const std::vector<fcl::CollisionObjectd*>& objects) {
  std::unique_ptr<Manager> m = type.make();
  m->registerObjects(objects);
  m->setup();
  return m;
}

fcl::DefaultCollisionData<double> collectAll() {
  fcl::DefaultCollisionData<double> data;
  data.request.num_max_contacts = 1000000;  // every colliding pair (and every mesh triangle)
  return data;
}

// ------------------------------------------------------------------------------------------------
// Collision

void checkEveryManagerFindsTheBruteForcePairs(const SceneSpec& spec) {
  Scene s = SceneBuilder(spec).build();
  const std::map<Kind, int> counts = s.counts();
  ASSERT_GE(counts.at(Kind::kEllipsoid), 1000);
  const CollisionOracle truth = bruteForceCollisions(s);
  const CollisionOracle query_truth = bruteForceQueryCollisions(s);
  printOracle(truth, "scene");
  printOracle(query_truth, "query objects");
  expectCleanOracle(truth, "scene oracle");
  expectCleanOracle(query_truth, "query oracle");
  std::printf("[ info ] %d ellipsoids, %d spheres, %d boxes, %d mesh (%zu triangles); %zu queries\n",
              counts.at(Kind::kEllipsoid), counts.at(Kind::kSphere), counts.at(Kind::kBox), counts.at(Kind::kMesh),
              s.bodies[0].mesh->triangles.size(), s.queries.size());
  EXPECT_GE(truth.colliding.size(), 200u) << "the scene is meant to be dense";
  const std::string tangent = checkTangentPairs(s, truth);

  const std::vector<fcl::CollisionObjectd*> all = s.objects([](Index) { return true; });
  const std::vector<fcl::CollisionObjectd*> even = s.objects([](Index i) { return i % 2 == 0; });
  const std::vector<fcl::CollisionObjectd*> odd = s.objects([](Index i) { return i % 2 == 1; });
  const CollisionOracle cross = restrictTo(truth, [](const IndexPair& p) { return (p.first + p.second) % 2 == 1; });
  for (const ManagerType& type : managerTypes(s)) {
    SCOPED_TRACE(type.name);
    std::size_t duplicates = 0;
    // Self query.
    std::unique_ptr<Manager> m = registered(type, all);
    fcl::DefaultCollisionData<double> data = collectAll();
    m->collide(&data, collisionCallback);
    EXPECT_TRUE(sameCollisions(s, contactPairs(s, data.result, &duplicates), truth)) << "self query";
    EXPECT_EQ(duplicates, 0u) << "self query: a pair was reported twice";
    // One object against the manager.
    for (std::size_t q = 0; q < s.queries.size(); ++q) {
      const Index qi = s.size() + static_cast<Index>(q);
      fcl::DefaultCollisionData<double> qdata = collectAll();
      m->collide(s.queries[q].object.get(), &qdata, collisionCallback);
      const CollisionOracle expected = restrictTo(query_truth, [&](const IndexPair& p) { return p.second == qi; });
      EXPECT_TRUE(sameCollisions(s, contactPairs(s, qdata.result, &duplicates), expected)) << s.describe(qi);
      EXPECT_EQ(duplicates, 0u) << s.describe(qi);
    }
    // Two managers of the same type (even and odd bodies).
    std::unique_ptr<Manager> a = registered(type, even), b = registered(type, odd);
    fcl::DefaultCollisionData<double> xdata = collectAll();
    a->collide(b.get(), &xdata, collisionCallback);
    EXPECT_TRUE(sameCollisions(s, contactPairs(s, xdata.result, &duplicates), cross)) << "manager against manager";
    if (type.name == "IntervalTree") {
      // FCL 0.7's IntervalTreeCollisionManager::collide(other_manager) walks endpoints[0], which
      // holds two endpoints per object, so it offers every pair to the callback twice (FCL's own
      // DefaultCollisionFunction too). The set of pairs is still right; note the duplicates.
      std::printf("[ info ] IntervalTree, manager against manager: %zu pairs reported twice (FCL 0.7)\n", duplicates);
    } else {
      EXPECT_EQ(duplicates, 0u) << "manager against manager";
    }
  }

  // For the record: the same manager with FCL's own callback (stock libccd narrow phase).
  std::unique_ptr<Manager> stock_manager = registered(managerTypes(s).front(), all);
  fcl::DefaultCollisionData<double> stock = collectAll();
  {
    const test::ScopedNoFpTraps no_traps;  // stock libccd code
    stock_manager->collide(&stock, fcl::DefaultCollisionFunction<double>);
  }
  std::size_t duplicates = 0;
  const PairSet stock_pairs = contactPairs(s, stock.result, &duplicates);
  std::vector<IndexPair> missed, extra;
  std::set_difference(truth.colliding.begin(), truth.colliding.end(), stock_pairs.begin(), stock_pairs.end(),
                      std::back_inserter(missed));
  std::set_difference(stock_pairs.begin(), stock_pairs.end(), truth.colliding.begin(), truth.colliding.end(),
                      std::back_inserter(extra));
  std::printf("[ info ] %zu colliding pairs; near-tangent pairs: %s; stock FCL's callback in the same manager "
              "(DynamicAABBTree) missed %zu and added %zu\n",
              truth.colliding.size(), tangent.c_str(), missed.size(), extra.size());
}

TEST(BroadPhaseManagers, EveryManagerTypeFindsExactlyTheBruteForceCollidingPairs) {
  checkEveryManagerFindsTheBruteForcePairs(SceneSpec{});
}

TEST(BroadPhaseManagersLong, FiveThousandEllipsoidsInEveryManagerTypeGiveTheBruteForcePairs) {
  SceneSpec spec;
  spec.ellipsoids = 5000;
  spec.spheres = 600;
  spec.boxes = 300;
  spec.tangent_pairs = 150;
  spec.queries = 24;
  spec.side = 36.0;
  spec.seed = 5005;
  checkEveryManagerFindsTheBruteForcePairs(spec);
}

// ------------------------------------------------------------------------------------------------
// Distance

/// Minimum over pairs of the front door's distance, as a bracket over the argument orders: the
/// delegated (libccd) pairs are evaluated in both orders, since a manager may call either.
struct DistanceOracle {
  double lo = std::numeric_limits<double>::max();  ///< min over pairs of min over orders
  double hi = std::numeric_limits<double>::max();  ///< min over pairs of max over orders
  IndexPair argmin{-1, -1};
  std::size_t pairs = 0, quadric_checked = 0, quadric_mismatch = 0, colliding = 0;

  void add(const Scene& s, Index i, Index j) {
    const Body &a = s.at(i), &b = s.at(j);
    const double ab = frontDoorDistance(a, b);
    const double ba = runsExact(*a.object, *b.object) ? ab : frontDoorDistance(b, a);
    ++pairs;
    colliding += std::min(ab, ba) <= 0.0;
    if (std::min(ab, ba) < lo) argmin = ordered(i, j);
    lo = std::min(lo, std::min(ab, ba));
    hi = std::min(hi, std::max(ab, ba));
    if (a.quadric() && b.quadric() && ab < 1.0) {  // the near pairs against the geometry layer
      ++quadric_checked;
      const double truth = signedDistance(a.asEllipsoid(), b.asEllipsoid()).distance;
      quadric_mismatch += !(std::abs(ab - truth) <= 1e-12 * std::max(1.0, std::abs(truth)));
    }
  }
  /// The manager's minimum lies within the bracket (1e-9 relative).
  ::testing::AssertionResult contains(double d) const {
    if (d >= lo * (1.0 - kDistanceRelTol) && d <= hi * (1.0 + kDistanceRelTol)) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "minimum " << d << " outside the brute-force bracket [" << lo << ", " << hi
                                         << "] (relative tolerance " << kDistanceRelTol << ")";
  }
};

void checkEveryManagerFindsTheBruteForceMinimumDistance(const SceneSpec& spec) {
  Scene s = SceneBuilder(spec).build();
  const std::map<Kind, int> counts = s.counts();
  ASSERT_GE(counts.at(Kind::kEllipsoid), 1000);
  DistanceOracle truth;
  for (Index i = 0; i < s.size(); ++i)
    for (Index j = i + 1; j < s.size(); ++j) truth.add(s, i, j);
  std::vector<DistanceOracle> query_truth(s.queries.size());
  for (std::size_t q = 0; q < s.queries.size(); ++q)
    for (Index i = 0; i < s.size(); ++i) query_truth[q].add(s, s.size() + static_cast<Index>(q), i);
  std::printf("[ info ] %d ellipsoids, %d spheres, %d boxes, %d mesh, pairwise separate; %zu pairs, minimum distance "
              "%.17g (%s / %s; bracket over argument orders [%.17g, %.17g]); %zu near ellipsoid/sphere pairs checked "
              "against signedDistance\n",
              counts.at(Kind::kEllipsoid), counts.at(Kind::kSphere), counts.at(Kind::kBox), counts.at(Kind::kMesh),
              truth.pairs, truth.lo, s.describe(truth.argmin.first).c_str(), s.describe(truth.argmin.second).c_str(),
              truth.lo, truth.hi, truth.quadric_checked);
  EXPECT_EQ(truth.colliding, 0u) << "the scene is pairwise separate";
  EXPECT_EQ(truth.quadric_mismatch, 0u) << "fcl_quadric::distance differs from signedDistance";
  ASSERT_GT(truth.lo, 0.0);

  const std::vector<fcl::CollisionObjectd*> all = s.objects([](Index) { return true; });
  for (const ManagerType& type : managerTypes(s)) {
    SCOPED_TRACE(type.name);
    std::unique_ptr<Manager> m = registered(type, all);
    fcl::DefaultDistanceData<double> data;
    m->distance(&data, distanceCallback);
    EXPECT_TRUE(truth.contains(data.result.min_distance)) << "self query";
    if (data.result.o1 && data.result.o2) {  // the reported pair has that distance
      const IndexPair p = s.pairOf(data.result.o1, data.result.o2);
      DistanceOracle pair;
      pair.add(s, p.first, p.second);
      EXPECT_TRUE(pair.contains(data.result.min_distance)) << s.describe(p.first) << " / " << s.describe(p.second);
    } else {
      ADD_FAILURE() << "no pair reported";
    }
    for (std::size_t q = 0; q < s.queries.size(); ++q) {
      fcl::DefaultDistanceData<double> qdata;
      m->distance(s.queries[q].object.get(), &qdata, distanceCallback);
      EXPECT_TRUE(query_truth[q].contains(qdata.result.min_distance)) << s.describe(s.size() + static_cast<Index>(q));
    }
  }
}

TEST(BroadPhaseManagers, EveryManagerTypeFindsTheBruteForceMinimumDistance) {
  SceneSpec spec;
  spec.pairwise_separate = true;
  spec.tangent_pairs = 0;
  spec.side = 30.0;
  spec.seed = 77;
  checkEveryManagerFindsTheBruteForceMinimumDistance(spec);
}

// ------------------------------------------------------------------------------------------------
// Inter-frame coherence

void checkCoherentFrames(const SceneSpec& spec, int frames) {
  Scene s = SceneBuilder(spec).build();
  fcl::DynamicAABBTreeCollisionManagerd manager;
  std::vector<bool> active(s.bodies.size(), true);
  manager.registerObjects(s.objects([](Index) { return true; }));
  manager.setup();
  PairCache cache;
  const int grow_frame = 2, remove_frame = 3, restore_frame = 4;
  const Index first_random = 1 + 2 * spec.tangent_pairs;  // after the mesh and the near-tangent pairs
  Index grown = -1, removed = -1;
  std::size_t collisions = 0;
  std::string tangent;
  for (int k = 0; k < frames; ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    s.setFrame(k);
    if (k == grow_frame) {
      // Grow, in place, the random ellipsoid whose box overlaps the most others (its cached
      // planes with them were certified for the old radii).
      int best = -1;
      for (Index i = first_random; i < s.size(); ++i) {
        if (s.bodies[i].kind != Kind::kEllipsoid) continue;
        int n = 0;
        for (Index j = 0; j < s.size(); ++j) n += j != i && aabbsOverlap(s.bodies[i], s.bodies[j], 0.0);
        if (n > best) {
          best = n;
          grown = i;
        }
      }
      ASSERT_GE(grown, 0);
      auto& e = static_cast<fcl::Ellipsoidd&>(*s.bodies[grown].geometry);
      e.radii *= 1.3;
      e.computeLocalAABB();
      s.bodies[grown].object->computeAABB();
    }
    if (k == remove_frame) {
      // Unregister a colliding random ellipsoid (and drop its cache entries).
      for (const IndexPair& p : bruteForceCollisions(s, &active).colliding) {
        if (p.second >= first_random && p.second != grown && s.at(p.second).kind == Kind::kEllipsoid) removed = p.second;
      }
      ASSERT_GE(removed, 0);
      manager.unregisterObject(s.bodies[removed].object.get());
      cache.invalidate(s.bodies[removed].object.get());
      active[removed] = false;
    }
    if (k == restore_frame) {
      manager.registerObject(s.bodies[removed].object.get());
      active[removed] = true;
    }
    manager.update();
    CoherentCollisionData data(&cache);
    data.request.num_max_contacts = 1000000;
    manager.collide(&data, coherentCallback);
    const CollisionOracle truth = bruteForceCollisions(s, &active);
    expectCleanOracle(truth, "frame oracle");
    std::size_t duplicates = 0;
    const PairSet found = contactPairs(s, data.result, &duplicates);
    ASSERT_TRUE(sameCollisions(s, found, truth));
    EXPECT_EQ(duplicates, 0u);
    collisions += truth.colliding.size();
    tangent = checkTangentPairs(s, truth);  // they move rigidly: still within 1e-8 of tangency
  }
  std::printf("[ info ] %d frames: %zu colliding pairs in all; near-tangent pairs in the last frame: %s\n", frames,
              collisions, tangent.c_str());
  std::printf("[ info ] PairCache: %llu ellipsoid/sphere queries, %llu answered by a cached plane, %zu entries\n",
              static_cast<unsigned long long>(cache.queries()), static_cast<unsigned long long>(cache.planeHits()),
              cache.size());
  EXPECT_GT(cache.planeHits(), cache.queries() / 4) << "slow motion: many cached planes stay valid";
}

TEST(BroadPhaseManagers, CoherentCollisionFunctionMatchesBruteForceEveryFrame) {
  SceneSpec spec;
  spec.queries = 0;
  spec.side = 21.0;
  spec.seed = 99;
  checkCoherentFrames(spec, 6);
}

TEST(BroadPhaseManagersLong, CoherentCollisionFunctionMatchesBruteForceOverThirtyFrames) {
  SceneSpec spec;
  spec.ellipsoids = 2000;
  spec.spheres = 300;
  spec.boxes = 150;
  spec.queries = 0;
  spec.side = 26.5;
  spec.seed = 3030;
  checkCoherentFrames(spec, 30);
}

}  // namespace
}  // namespace fcl_quadric
