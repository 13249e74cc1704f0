// Newton's method on the KKT system of the distance of two quadric models: nearest_points.h,
// docs/algorithms.md section 12c.
#include "fcl_quadric/geometry/nearest_points.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "algebra/dense_decompositions.h"

namespace fcl_quadric {

using namespace tolerance_nearest_points;

namespace {

// Fixed-capacity matrices (at most three active surfaces per model, so at most 12 unknowns): no
// heap allocation in the iteration, whose cost it otherwise dominated.
using Multipliers = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
using KktVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 12, 1>;
using KktMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 12, 12>;

/// An atom g(x) = x^T A x + 2 b.x + c (<= 0 on the model's side), scaled so that its gradient at
/// the start point has unit length: g is then the signed distance to its surface to first order,
/// and the multipliers are O(1).
struct Atom {
  Eigen::Matrix3d A;
  Eigen::Vector3d b;
  double c = 0.0;
  double value(const Eigen::Vector3d& x) const { return x.dot(A * x) + 2.0 * b.dot(x) + c; }
  Eigen::Vector3d gradient(const Eigen::Vector3d& x) const { return 2.0 * (A * x + b); }
};

/// Atom k of `atoms` scaled to a unit gradient at x; nullopt where the gradient vanishes (a cone's
/// apex, a degenerate atom) or is not finite.
std::optional<Atom> scaledAtom(const std::vector<Eigen::Matrix4d>& atoms, int k, const Eigen::Vector3d& x) {
  const Eigen::Matrix4d& Q = atoms[k];
  Atom t;
  t.A = Q.topLeftCorner<3, 3>();
  t.b = Q.topRightCorner<3, 1>();
  t.c = Q(3, 3);
  const double gn = t.gradient(x).norm();
  if (!std::isfinite(gn) || !(gn > 0.0)) return std::nullopt;
  const double s = 1.0 / gn;
  t.A *= s;
  t.b *= s;
  t.c *= s;
  return t;
}

/// g(x) / |grad g(x)| for the atom Q: to first order the signed distance from x to its surface
/// (> 0 on the side the model excludes); nullopt where the gradient vanishes.
std::optional<double> surfaceOffset(const Eigen::Matrix4d& Q, const Eigen::Vector3d& x) {
  const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
  const double gn = 2.0 * (Q.topLeftCorner<3, 3>() * x + Q.topRightCorner<3, 1>()).norm();
  if (!(gn > 0.0)) return std::nullopt;
  return X.dot(Q * X) / gn;
}

/// True when x is within `band` of an apex of one of `atoms`: a point of the surface where the
/// gradient vanishes (the centre -A^-1 b of a curved atom with g(centre) = 0 to rounding: a
/// cone's). Near it g / |grad g| is no distance (g is second-order there), and neither Newton's
/// steps on the atom nor the membership test of the answer can be trusted: the caller keeps its
/// own pair, which GJK gets exact at an apex (a vertex of the support mapping).
bool nearApex(const std::vector<Eigen::Matrix4d>& atoms, const Eigen::Vector3d& x, double band) {
  for (const Eigen::Matrix4d& Q : atoms) {
    const Eigen::Matrix3d A = Q.topLeftCorner<3, 3>();
    const Eigen::Vector3d b = Q.topRightCorner<3, 1>();
    const double a_max = A.cwiseAbs().maxCoeff();
    if (!(a_max > 0.0)) continue;  // a plane
    Eigen::Vector3d centre;
    if (!detail::fullPivLuSolve(Eigen::Matrix3d(A / a_max), Eigen::Vector3d(-b / a_max), &centre))
      continue;  // rank < 3: cylinders, paraboloids, no isolated singular point
    if (!centre.allFinite() || (x - centre).norm() > band) continue;
    const Eigen::Vector3d c_abs = centre.cwiseAbs();
    const double mag = c_abs.dot(A.cwiseAbs() * c_abs) + 2.0 * b.cwiseAbs().dot(c_abs) + std::abs(Q(3, 3));
    const double g = centre.dot(A * centre) + 2.0 * b.dot(centre) + Q(3, 3);
    if (std::abs(g) <= 1e-12 * mag) return true;
  }
  return false;
}

/// For each atom, the index of its twin: another atom that is its exact negation (to 1e-14 of its
/// largest entry), -1 if none. A model holding both g <= 0 and -g <= 0 lies on the surface g = 0:
/// a mesh triangle is its plane as two opposite half-spaces (triangleSolid in the FCL layer).
/// Taken as two inequality constraints the pair has opposite gradients, the KKT system is singular,
/// and at a triangle's vertex the plane pair and one edge fill the three active places, so the
/// vertex could not be reached (audit finding 34 (2): an elliptic cylinder's distance to a mesh
/// vertex 1e-3 relative too large at a gap of 3e-9). The pair is one equality constraint instead:
/// one atom of it in the active set, with a multiplier of either sign.
std::vector<int> twinAtoms(const std::vector<Eigen::Matrix4d>& atoms) {
  std::vector<int> twin(atoms.size(), -1);
  for (std::size_t k = 0; k < atoms.size(); ++k)
    for (std::size_t j = k + 1; j < atoms.size() && twin[k] < 0; ++j) {
      if (twin[j] >= 0) continue;
      const double m = atoms[k].cwiseAbs().maxCoeff();
      if (m > 0.0 && (atoms[k] + atoms[j]).cwiseAbs().maxCoeff() <= 1e-14 * m) {
        twin[k] = static_cast<int>(j);
        twin[j] = static_cast<int>(k);
      }
    }
  return twin;
}

bool contains(const std::vector<int>& v, int k) { return std::find(v.begin(), v.end(), k) != v.end(); }

/// The atoms whose surfaces pass within `band` of x, nearest first, at most three; of twins
/// (twinAtoms) only the nearer.
std::vector<int> activeAtoms(const std::vector<Eigen::Matrix4d>& atoms, const std::vector<int>& twin,
                             const Eigen::Vector3d& x, double band) {
  std::vector<std::pair<double, int>> near;
  for (std::size_t k = 0; k < atoms.size(); ++k)
    if (const std::optional<double> o = surfaceOffset(atoms[k], x); o && std::fabs(*o) <= band)
      near.emplace_back(std::fabs(*o), static_cast<int>(k));
  std::sort(near.begin(), near.end());
  std::vector<int> out;
  for (std::size_t i = 0; i < near.size() && out.size() < 3; ++i) {
    const int k = near[i].second;
    if (twin[k] < 0 || !contains(out, twin[k])) out.push_back(k);
  }
  return out;
}

/// The atom of `atoms` (not in `active`, nor the twin of an active one: that surface is held as
/// an equality, and its twin's excess is rounding) that x violates most, by g / |grad g| > 0; -1
/// if none.
int mostViolated(const std::vector<Eigen::Matrix4d>& atoms, const std::vector<int>& twin, const std::vector<int>& active,
                 const Eigen::Vector3d& x) {
  int worst = -1;
  double excess = 0.0;
  for (std::size_t k = 0; k < atoms.size(); ++k) {
    if (contains(active, static_cast<int>(k)) || (twin[k] >= 0 && contains(active, twin[k]))) continue;
    if (const std::optional<double> o = surfaceOffset(atoms[k], x); o && *o > excess) {
      excess = *o;
      worst = static_cast<int>(k);
    }
  }
  return worst;
}

/// p moved onto the surfaces of `atoms` (Gauss-Newton, minimal-norm steps, quadratically
/// convergent: two or three take a point within a Newton step's O(step^2) of them to rounding;
/// at most kProjectionSteps). Newton's steps move along the
/// surfaces' tangent planes; without this retraction a long step along a curved surface leaves
/// both points off their surfaces by more than their gap, and they seem to cross.
Eigen::Vector3d ontoSurfaces(const std::vector<Atom>& atoms, Eigen::Vector3d p) {
  const int m = static_cast<int>(atoms.size());
  for (int step = 0; step < kProjectionSteps; ++step) {
    Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 3, 3> J(m, 3);
    Multipliers g(m);
    for (int i = 0; i < m; ++i) {
      J.row(i) = atoms[i].gradient(p).transpose();
      g[i] = atoms[i].value(p);
    }
    // The minimal-norm step -J^T (J J^T)^-1 g: through the m x m Gram matrix (Cholesky) when
    // it is well conditioned, the usual case of independent surface normals; otherwise (normals
    // nearly dependent) by the complete orthogonal decomposition.
    Eigen::Vector3d dp;
    const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3> gram = J * J.transpose();
    const Eigen::LLT<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>> llt(gram);
    const double diag_min = gram.diagonal().minCoeff(), diag_max = gram.diagonal().maxCoeff();
    bool gram_ok = llt.info() == Eigen::Success && diag_min > 0.0;
    if (gram_ok) {
      // Cholesky's pivots bound the conditioning: a small one means nearly dependent normals.
      for (int i = 0; i < m; ++i) {
        const double pivot = llt.matrixLLT()(i, i);
        gram_ok = gram_ok && pivot * pivot > 1e-8 * diag_max;
      }
    }
    if (gram_ok) {
      dp = -J.transpose() * llt.solve(g);
    } else {
      dp = -J.completeOrthogonalDecomposition().solve(g);
    }
    if (!dp.allFinite()) break;
    p += dp;
    if (dp.norm() <= kStepRelative * p.norm()) break;
  }
  return p;
}

/// How a run of Newton's method on one active set ended.
struct KktRun {
  enum class Outcome { Converged, LeftA, LeftB, Failed };
  Outcome outcome = Outcome::Failed;
  Eigen::Vector3d x, y;  ///< Converged: the solution; LeftA / LeftB: the last pair inside both models
  Eigen::Vector3d exit;  ///< LeftA / LeftB: the point that left its model
  Multipliers lambda, mu;
  int steps = 0;
};

/// Newton's method on the KKT system of min |x - y| with the given active surfaces, from (x, y)
/// (nearest_points.h; the distance itself, not its square, is the objective: its multipliers stay
/// O(1) as the gap closes, where those of |x - y|^2 / 2 vanish with it and the joint sliding of
/// both points along the surfaces, the system's weakest direction, would be determined only to
/// rounding / gap).
KktRun solveKkt(const std::vector<Atom>& ga, const std::vector<Atom>& hb, const QuadricRegion& a, const QuadricRegion& b,
                Eigen::Vector3d x, Eigen::Vector3d y, double scale) {
  using Outcome = KktRun::Outcome;
  const int na = static_cast<int>(ga.size()), nb = static_cast<int>(hb.size());
  const int n = 6 + na + nb;
  KktRun run;
  run.x = x;
  run.y = y;
  // A point that left its model ends the run: the caller adds the surface it crossed.
  auto left = [&](const Eigen::Vector3d& xn, const Eigen::Vector3d& yn) {
    if (a.classifyPoint(xn) < 0) {
      run.outcome = Outcome::LeftA;
      run.exit = xn;
      return true;
    }
    if (b.classifyPoint(yn) < 0) {
      run.outcome = Outcome::LeftB;
      run.exit = yn;
      return true;
    }
    return false;
  };
  // Align the start: x becomes the foot point of y on a's surfaces and y that of x on b's, so
  // that x - y starts along a surface normal. Starts displaced along the surfaces (GJK's and the
  // branch and bound's near contact) are otherwise joined by a nearly tangent x - y, far from
  // where Newton's method converges quadratically.
  {
    // A foot point outside its model ends the run as a Newton step would (the surface it
    // crossed joins the active set: near an edge the foot point on one face is often beyond it).
    // Three alternations: on an edge the foot point can lie far along it from y, and x must
    // follow it to face it.
    for (int round = 0; round < 3; ++round) {
      const Eigen::Vector3d xa = ontoSurfaces(ga, y);
      const Eigen::Vector3d yb = ontoSurfaces(hb, xa);
      if (!xa.allFinite() || !yb.allFinite() || left(xa, yb)) return run;
      x = xa;
      y = yb;
    }
  }
  // Multipliers from the start's stationarity, in the least-squares sense.
  auto multipliers = [](const std::vector<Atom>& atoms, const Eigen::Vector3d& p, const Eigen::Vector3d& target) {
    Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 3> G(3, atoms.size());
    for (std::size_t i = 0; i < atoms.size(); ++i) G.col(static_cast<Eigen::Index>(i)) = atoms[i].gradient(p);
    return Multipliers(G.colPivHouseholderQr().solve(target));
  };
  double d = (x - y).norm();
  if (!std::isfinite(d) || !(d > 0.0)) return run;
  run.lambda = multipliers(ga, x, (y - x) / d);
  run.mu = multipliers(hb, y, (x - y) / d);
  const double tiny = kStepRelative * scale;
  bool converged = false;
  double last_len = std::numeric_limits<double>::infinity();
  for (int step = 0; step < kMaxNewtonSteps && !converged; ++step) {
    run.steps = step + 1;
    run.x = x;
    run.y = y;
    d = (x - y).norm();
    if (!std::isfinite(d) || !(d > 0.0)) return run;
    const Eigen::Vector3d u = (x - y) / d;
    const Eigen::Matrix3d P = (Eigen::Matrix3d::Identity() - u * u.transpose()) / d;
    KktVector F = KktVector::Zero(n);
    KktMatrix J = KktMatrix::Zero(n, n);
    Eigen::Vector3d fx = u, fy = -u;
    Eigen::Matrix3d Jxx = P, Jyy = P;
    for (int i = 0; i < na; ++i) {
      const Eigen::Vector3d g = ga[i].gradient(x);
      fx += run.lambda[i] * g;
      Jxx += 2.0 * run.lambda[i] * ga[i].A;
      J.block<3, 1>(0, 6 + i) = g;
      J.block<1, 3>(6 + i, 0) = g.transpose();
      F[6 + i] = ga[i].value(x);
    }
    for (int j = 0; j < nb; ++j) {
      const Eigen::Vector3d h = hb[j].gradient(y);
      fy += run.mu[j] * h;
      Jyy += 2.0 * run.mu[j] * hb[j].A;
      J.block<3, 1>(3, 6 + na + j) = h;
      J.block<1, 3>(6 + na + j, 3) = h.transpose();
      F[6 + na + j] = hb[j].value(y);
    }
    F.segment<3>(0) = fx;
    F.segment<3>(3) = fy;
    J.block<3, 3>(0, 0) = Jxx;
    J.block<3, 3>(0, 3) = -P;
    J.block<3, 3>(3, 0) = -P;
    J.block<3, 3>(3, 3) = Jyy;
    if (!F.allFinite() || !J.allFinite()) return run;
    const KktVector delta = J.fullPivLu().solve(-F);
    if (!delta.allFinite()) return run;
    const Eigen::Vector3d dx = delta.segment<3>(0), dy = delta.segment<3>(3);
    // Damping: no step longer than kMaxStepRelative of the scale; each step is retracted onto the
    // surfaces (ontoSurfaces()) and halved until the retracted points neither cross (x - y keeps
    // its side of the plane normal to u) nor move apart (beyond rounding): the iteration descends
    // the distance between the surfaces and cannot wander to a distant stationary pair.
    double k = 1.0;
    const double len = std::max(dx.norm(), dy.norm());
    if (len > kMaxStepRelative * scale) k = kMaxStepRelative * scale / len;
    Eigen::Vector3d xn = ontoSurfaces(ga, x + k * dx), yn = ontoSurfaces(hb, y + k * dy);
    const double rounding = kDistanceRoundingRelative * scale;
    auto acceptable = [&] { return (xn - yn).dot(u) > 0.0 && (xn - yn).norm() <= d + rounding; };
    bool stalled = false;
    for (int halvings = 0; !acceptable(); ++halvings) {
      if (halvings == 60) {
        stalled = true;
        break;
      }
      k *= 0.5;
      xn = ontoSurfaces(ga, x + k * dx);
      yn = ontoSurfaces(hb, y + k * dy);
    }
    if (stalled) {
      // No step along this direction keeps the distance: at a settled pair that is rounding (the
      // pair stands), elsewhere a direction that does not descend (the run fails).
      converged = len <= kSettledRelative * scale;
      break;
    }
    if (left(xn, yn)) return run;
    x = xn;
    y = yn;
    run.lambda += k * delta.segment(6, na);
    run.mu += k * delta.segment(6 + na, nb);
    converged = k == 1.0 && len <= tiny;
    last_len = len;  // Newton's own step, undamped: a damped one says nothing about convergence
  }
  // At the step cap, a pair whose last step was below kSettledRelative of the scale counts: the
  // residual's rounding (that of u = (x - y) / |x - y|, eps |x| / |x - y|) can keep the joint
  // sliding from settling below kStepRelative at tiny gaps, but the distance is second-order in it.
  converged = converged || last_len <= kSettledRelative * scale;
  if (!converged || !x.allFinite() || !y.allFinite()) return run;
  run.outcome = Outcome::Converged;
  run.x = x;
  run.y = y;
  return run;
}

}  // namespace

std::optional<NearestPoints> refineNearestPoints(const QuadricRegion& a, const QuadricRegion& b,
                                                 const Eigen::Vector3d& start_a, const Eigen::Vector3d& start_b,
                                                 double scale) {
  using Outcome = KktRun::Outcome;
  const double start = (start_b - start_a).norm();
  // (isfinite before the ordered comparisons, which would raise FE_INVALID on a NaN.)
  if (!std::isfinite(start) || !std::isfinite(scale) || !(start > 0.0) || !(scale > 0.0)) return std::nullopt;
  const std::vector<Eigen::Matrix4d> atoms_a = a.signedAtoms(), atoms_b = b.signedAtoms();
  const double band = kActiveRelative * scale;
  if (nearApex(atoms_a, start_a, band) || nearApex(atoms_b, start_b, band)) return std::nullopt;
  const std::vector<int> twin_a = twinAtoms(atoms_a), twin_b = twinAtoms(atoms_b);
  std::vector<int> act_a = activeAtoms(atoms_a, twin_a, start_a, band), act_b = activeAtoms(atoms_b, twin_b, start_b, band);
  Eigen::Vector3d x = start_a, y = start_b;
  NearestPoints out;
  for (int round = 0; round < kMaxActiveSetRounds; ++round) {
    if (act_a.empty() || act_b.empty()) return std::nullopt;
    std::vector<Atom> ga, hb;
    for (int k : act_a) {
      const std::optional<Atom> t = scaledAtom(atoms_a, k, x);
      if (!t) return std::nullopt;
      ga.push_back(*t);
    }
    for (int k : act_b) {
      const std::optional<Atom> t = scaledAtom(atoms_b, k, y);
      if (!t) return std::nullopt;
      hb.push_back(*t);
    }
    const KktRun run = solveKkt(ga, hb, a, b, x, y, scale);
    out.iterations += run.steps;
    x = run.x;
    y = run.y;
    switch (run.outcome) {
      case Outcome::Failed: return std::nullopt;
      case Outcome::LeftA:
      case Outcome::LeftB: {
        // The surface the point crossed most joins the active set (a face becomes the edge it ran
        // into, an edge the vertex); the next run starts from the last pair inside both models.
        const bool on_a = run.outcome == Outcome::LeftA;
        std::vector<int>& act = on_a ? act_a : act_b;
        if (act.size() >= 3) return std::nullopt;
        const int k = mostViolated(on_a ? atoms_a : atoms_b, on_a ? twin_a : twin_b, act, run.exit);
        if (k < 0) return std::nullopt;
        act.push_back(k);
        continue;
      }
      case Outcome::Converged: break;
    }
    // A negative multiplier: the minimum lies off that surface, on the model's side of it; the
    // surface leaves the active set and the next run starts from this solution. (Not an equality,
    // an atom with a twin: its multiplier has either sign.)
    auto mostNegative = [](const Multipliers& m, const std::vector<int>& act, const std::vector<int>& twin) {
      int worst = -1;
      double v = -kNegativeMultiplier;
      for (int i = 0; i < static_cast<int>(act.size()); ++i)
        if (twin[act[i]] < 0 && m[i] < v) {
          v = m[i];
          worst = i;
        }
      return worst;
    };
    const int neg_a = mostNegative(run.lambda, act_a, twin_a), neg_b = mostNegative(run.mu, act_b, twin_b);
    if (neg_a >= 0 && act_a.size() > 1) {
      act_a.erase(act_a.begin() + neg_a);
      continue;
    }
    if (neg_b >= 0 && act_b.size() > 1) {
      act_b.erase(act_b.begin() + neg_b);
      continue;
    }
    if (neg_a >= 0 || neg_b >= 0) return std::nullopt;  // a face's own multiplier: not a minimum
    const double dist = (y - x).norm();
    if (a.classifyPoint(x) < 0 || b.classifyPoint(y) < 0 || !(dist > 0.0) || dist > start) return std::nullopt;
    out.point_a = x;
    out.point_b = y;
    out.distance = dist;
    return out;
  }
  return std::nullopt;
}

}  // namespace fcl_quadric
