// Continuous collision of composite quadric models by certified space-time subdivision
// (region_ccd.h; docs/algorithms.md section 10).
#include "fcl_quadric/continuous/region_ccd.h"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "../geometry/region_formula.h"
#include "algebra/dense_decompositions.h"

namespace fcl_quadric {

using namespace tolerance_region;
using detail::Formula;
using detail::FormulaBox;
using detail::goldenArgmax;
using detail::Tri;

namespace {

constexpr int kMaxCoef = kRegionCcdMaxDegree + 1;
/// Boxes one time slab may visit before it is halved, at least (three times the cost of the last
/// certified slab when that is more); a slab of width kRegionCcdTimeTolerance gets the piece's
/// whole box limit (RegionCcdLimits::max_boxes).
constexpr int kRegionCcdSlabBudget = 500;
/// Triple pencils: rounds of coordinate ascent over the weight simplex, and golden-section steps
/// per direction (0.618^20 ~ 7e-5 of the edge).
constexpr int kTripleRounds = 2;
constexpr int kTripleSteps = 14;
/// Golden-section steps of a pair pencil's weight (0.618^30 ~ 5e-7 of [0, 1]).
constexpr int kPairSteps = 30;

/// In a slab of the final width, boxes searched for a witness after the first undecided one.
constexpr int kRegionCcdExtraBoxesAfterUndecided = 256;
/// Bisection steps that move a witness (c, t1) to the earliest certified-inside instant of c.
constexpr int kWitnessBisections = 40;

/// A moving atom X^T S(t) X in the search frame: power-basis coefficient matrices in the piece's
/// local time u in [0, 1] (all atoms padded to the common degree), and `abs` >= sum_m |S_m|
/// entrywise including the magnitudes of the products that formed S (rounding pads).
struct MovingAtom {
  std::vector<Eigen::Matrix4d> S;
  Eigen::Matrix4d abs = Eigen::Matrix4d::Zero();
  double scale = 1.0;  // 1 / max |abs|: normalises atoms for pencils and split scores
  bool constant = false;  // S_m = 0 for m >= 1 (the search frame's own atoms)
};

// The ten polynomials of an atom's centred form on a box (v, g_0..2, A_00, A_11, A_22, A_01,
// A_02, A_12), in Bernstein form on the box's time interval, and their ranges.
struct AtomOnBox {
  std::array<std::array<double, kMaxCoef>, 10> b;
  double vmin = 0, vmax = 0;
  std::array<double, 3> gmax{}, amin{}, amax{}, aoff{};  // aoff: |A_01|, |A_02|, |A_12| maxima
  Eigen::Vector3d gmid = Eigen::Vector3d::Zero();        // gradient at (c, time midpoint)
  double pad = 0.0;                                      // rounding pad on the box
  Tri state = Tri::Unknown;
};

/// The work of one query so far (all pieces), and its limits, which hold for each piece: a
/// keyframed motion is answered as its pieces would be one by one (docs/reliability.md finding
/// 41), and its time is at most the number of pieces times a capped piece's.
struct QueryWork {
  RegionCcdLimits limits;
  long long boxes = 0;  // long: a piece may use max_boxes, and a motion may have many pieces
  long long evaluations = 0;
  long long piece_boxes0 = 0;  // the counts when the current piece started
  long long piece_evaluations0 = 0;
  void startPiece() {
    piece_boxes0 = boxes;
    piece_evaluations0 = evaluations;
  }
  bool spent() const {
    return boxes - piece_boxes0 >= limits.max_boxes ||
           evaluations - piece_evaluations0 >= limits.max_pencil_evaluations;
  }
};

class SpaceTimeEngine {
 public:
  /// `work`: the query's counts, shared by its pieces; the engine counts its pencil bound
  /// evaluations (pencilLower) there, the search its boxes.
  SpaceTimeEngine(const Formula& f, std::vector<MovingAtom> atoms, int degree, double sign_relative, QueryWork* work)
      : f_(f), atoms_(std::move(atoms)), n_(degree), sign_relative_(sign_relative), on_box_(atoms_.size()),
        work_(work) {
    // ratio[i][j] = C(i, j) / C(n, j): power -> Bernstein on [0, 1].
    ratio_.assign((n_ + 1) * (n_ + 1), 0.0);
    for (int i = 0; i <= n_; ++i)
      for (int j = 0; j <= i; ++j) ratio_[i * (n_ + 1) + j] = binom(i, j) / binom(n_, j);
  }

  int size() const { return static_cast<int>(atoms_.size()); }

  /// Encloses every atom on c ± r times [t0, t1] and returns the formula's state there.
  FormulaBox evaluate(const Eigen::Vector3d& c, const Eigen::Vector3d& r, double t0, double t1) {
    c_ = c;
    r_ = r;
    if (t0 != t0_ || t1 != t1_) setSlab(t0, t1);
    const Eigen::Vector4d C(c[0], c[1], c[2], 1.0);
    const Eigen::Vector4d Xa((c.cwiseAbs() + r)[0], (c.cwiseAbs() + r)[1], (c.cwiseAbs() + r)[2], 1.0);
    const double tm = 0.5 * (t0 + t1), tau = t1 - t0;
    std::vector<Tri> states(atoms_.size());
    std::array<std::array<double, kMaxCoef>, 4> p;
    for (std::size_t k = 0; k < atoms_.size(); ++k) {
      const MovingAtom& m = atoms_[k];
      AtomOnBox& e = on_box_[k];
      // v and g depend on the centre; the A entries were set for the slab (setSlab).
      const int top = m.constant ? 0 : n_;
      for (int d = 0; d <= top; ++d) {
        const Eigen::Matrix4d& S = m.S[d];
        const Eigen::Vector4d SC = S * C;
        p[0][d] = C.dot(SC);
        p[1][d] = 2.0 * SC[0];
        p[2][d] = 2.0 * SC[1];
        p[3][d] = 2.0 * SC[2];
      }
      if (m.constant) {
        for (int q = 0; q < 4; ++q) std::fill(e.b[q].begin(), e.b[q].begin() + n_ + 1, p[q][0]);
        for (int i = 0; i < 3; ++i) e.gmid[i] = p[1 + i][0];
      } else {
        for (int i = 0; i < 3; ++i) e.gmid[i] = horner(p[1 + i].data(), tm);
        for (int q = 0; q < 4; ++q) bernstein(p[q].data(), t0, tau, e.b[q].data());
      }
      e.vmin = minOf(e.b[0]);
      e.vmax = maxOf(e.b[0]);
      for (int i = 0; i < 3; ++i) e.gmax[i] = maxAbsOf(e.b[1 + i]);
      const double lin = e.gmax[0] * r[0] + e.gmax[1] * r[1] + e.gmax[2] * r[2];
      const double off = 2.0 * (e.aoff[0] * r[0] * r[1] + e.aoff[1] * r[0] * r[2] + e.aoff[2] * r[1] * r[2]);
      double qlo = -off, qhi = off;
      for (int i = 0; i < 3; ++i) {
        qlo += std::min(0.0, e.amin[i]) * r[i] * r[i];
        qhi += std::max(0.0, e.amax[i]) * r[i] * r[i];
      }
      const double pad = sign_relative_ * Xa.dot(m.abs * Xa);
      e.pad = pad;
      if (e.vmin - lin + qlo - pad > 0.0) {
        e.state = Tri::Out;
      } else if (e.vmax + lin + qhi + pad < 0.0) {
        e.state = Tri::In;
      } else {
        e.state = Tri::Unknown;
      }
      states[k] = e.state;
    }
    return FormulaBox(f_, std::move(states));
  }

  /// The A entries (second-order part) of every atom over [t0, t1]: they do not depend on the
  /// box centre, so a slab computes them once.
  void setSlab(double t0, double t1) {
    t0_ = t0;
    t1_ = t1;
    std::array<double, kMaxCoef> p;
    static constexpr int kIndex[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
    for (std::size_t k = 0; k < atoms_.size(); ++k) {
      const MovingAtom& m = atoms_[k];
      AtomOnBox& e = on_box_[k];
      for (int q = 0; q < 6; ++q) {
        if (m.constant) {
          std::fill(e.b[4 + q].begin(), e.b[4 + q].begin() + n_ + 1, m.S[0](kIndex[q][0], kIndex[q][1]));
        } else {
          for (int d = 0; d <= n_; ++d) p[d] = m.S[d](kIndex[q][0], kIndex[q][1]);
          bernstein(p.data(), t0, t1 - t0, e.b[4 + q].data());
        }
      }
      for (int i = 0; i < 3; ++i) {
        e.amin[i] = minOf(e.b[4 + i]);
        e.amax[i] = maxOf(e.b[4 + i]);
        e.aoff[i] = maxAbsOf(e.b[7 + i]);
      }
    }
  }

  /// Pencil exclusion of the last evaluated box: some pair (golden section on the weight) or
  /// triple (weights from the first-order condition at the box centre) of the conjoined atoms
  /// with a certified-positive combination.
  bool pencilExcluded(const std::vector<int>& atoms) const {
    // Warm start: the weights that certified a neighbouring box (the search is depth-first, so
    // the last certificate of a pair or triple is usually valid for its sibling too).
    for (std::size_t i = 0; i < atoms.size(); ++i)
      for (std::size_t j = i + 1; j < atoms.size(); ++j) {
        const auto it = pair_mu_.find(key(atoms[i], atoms[j]));
        if (it != pair_mu_.end() && pairLower(atoms[i], atoms[j], it->second) > 0.0) return true;
      }
    for (std::size_t i = 0; i < atoms.size(); ++i)
      for (std::size_t j = i + 1; j < atoms.size(); ++j)
        for (std::size_t k = j + 1; k < atoms.size(); ++k) {
          const int ids[3] = {atoms[i], atoms[j], atoms[k]};
          const auto it = triple_mu_.find(key(ids[0], ids[1], ids[2]));
          if (it != triple_mu_.end() && tripleLower(ids, it->second) > 0.0) return true;
        }
    for (std::size_t i = 0; i < atoms.size(); ++i)
      for (std::size_t j = i + 1; j < atoms.size(); ++j) {
        const int a = atoms[i], b = atoms[j];
        double mu = 0.5;
        if (goldenArgmax([&](double x) { return pairLower(a, b, x); }, kPairSteps, &mu)) {
          pair_mu_[key(a, b)] = mu;
          return true;
        }
      }
    for (std::size_t i = 0; i < atoms.size(); ++i)
      for (std::size_t j = i + 1; j < atoms.size(); ++j)
        for (std::size_t k = j + 1; k < atoms.size(); ++k) {
          const int ids[3] = {atoms[i], atoms[j], atoms[k]};
          Eigen::Matrix3d G;
          for (int m = 0; m < 3; ++m) G.col(m) = atoms_[ids[m]].scale * on_box_[ids[m]].gmid;
          Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
          K.topLeftCorner<3, 3>() = G.transpose() * G;
          K.block<3, 1>(0, 3) = Eigen::Vector3d::Ones();
          K.block<1, 3>(3, 0) = Eigen::RowVector3d::Ones();
          Eigen::Vector4d sol;
          detail::fullPivLuSolve(K, Eigen::Vector4d(0, 0, 0, 1), &sol);
          // Start from the first-order weights projected onto the simplex (the centroid when they
          // are not finite), then coordinate ascent by golden section along the two edges through
          // the third vertex: the lower bound is concave in the weights, and any positive value
          // certifies the box (an edge of one solid against a face of the other, or a rim).
          Eigen::Vector3d mu = Eigen::Vector3d::Constant(1.0 / 3.0);
          if (sol.allFinite()) {
            mu = sol.head<3>().cwiseMax(0.0);
            if (mu.sum() > 0.0) mu /= mu.sum();
            else mu.setConstant(1.0 / 3.0);
          }
          if (tripleLower(ids, mu) > 0.0) {
            triple_mu_[key(ids[0], ids[1], ids[2])] = mu;
            return true;
          }
          for (int round = 0; round < kTripleRounds; ++round) {
            for (int axis = 0; axis < 2; ++axis) {
              // mu(s) = mu + s (e_axis - e_2), s in [-mu_axis, mu_2], mapped to [0, 1].
              const double s_lo = -mu[axis], s_hi = mu[2];
              if (!(s_hi - s_lo > 1e-12)) continue;
              auto at = [&](double x) {
                Eigen::Vector3d m = mu;
                const double s = s_lo + x * (s_hi - s_lo);
                m[axis] += s;
                m[2] -= s;
                return Eigen::Vector3d(m.cwiseMax(0.0));
              };
              double best_x = -s_lo / (s_hi - s_lo);
              const bool found = goldenArgmax([&](double x) { return tripleLower(ids, at(x)); }, kTripleSteps, &best_x);
              mu = at(best_x);
              if (found) {
                triple_mu_[key(ids[0], ids[1], ids[2])] = mu;
                return true;
              }
            }
          }
        }
    return false;
  }

  /// The spatial axis to split for the last evaluated box (slabs are searched in space only), -1
  /// when every edge is at the resolution limit.
  int splitAxis(double min_width) const {
    Eigen::Vector3d score = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < atoms_.size(); ++k) {
      const AtomOnBox& e = on_box_[k];
      if (e.state != Tri::Unknown) continue;
      const double s = atoms_[k].scale;
      const double a[3][3] = {{std::max(std::fabs(e.amin[0]), std::fabs(e.amax[0])), e.aoff[0], e.aoff[1]},
                              {e.aoff[0], std::max(std::fabs(e.amin[1]), std::fabs(e.amax[1])), e.aoff[2]},
                              {e.aoff[1], e.aoff[2], std::max(std::fabs(e.amin[2]), std::fabs(e.amax[2]))}};
      for (int i = 0; i < 3; ++i) {
        double t = e.gmax[i] * r_[i];
        for (int j = 0; j < 3; ++j) t += a[i][j] * r_[i] * r_[j];
        score[i] += s * t;
      }
    }
    return detail::chooseSplitAxis(score, r_, min_width, kRegionMaxAspect);
  }

  /// S(t) of atom k (Horner on the coefficient matrices).
  Eigen::Matrix4d matrixAt(int k, double t) const {
    const MovingAtom& m = atoms_[k];
    Eigen::Matrix4d S = m.S[n_];
    for (int d = n_ - 1; d >= 0; --d) S = S * t + m.S[d];
    return S;
  }

  /// Certified sign of atom k at (x, t): -1 inside, +1 outside, 0 within the rounding band.
  int pointSign(int k, const Eigen::Vector3d& x, double t) const {
    const MovingAtom& m = atoms_[k];
    const Eigen::Matrix4d S = matrixAt(k, t);
    const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
    const double v = X.dot(S * X);
    const Eigen::Vector4d Xa = X.cwiseAbs();
    const double pad = sign_relative_ * Xa.dot(m.abs * Xa);
    if (v > pad) return 1;
    if (v < -pad) return -1;
    return 0;
  }

  /// Approximate distance of x to atom k's surface at t (|f| / |grad f|), to name the elements.
  double surfaceDistance(int k, const Eigen::Vector3d& x, double t) const {
    const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
    const Eigen::Vector4d SX = matrixAt(k, t) * X;
    const double g = 2.0 * SX.head<3>().norm();
    if (!(g > 0.0)) return std::numeric_limits<double>::infinity();
    return std::fabs(X.dot(SX)) / g;
  }

  /// Heuristic depth at (x, t): the largest f / |grad f| of the atoms undecided on the last box.
  double depth(const Eigen::Vector3d& x, double t) const {
    double worst = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < size(); ++k) {
      if (on_box_[k].state != Tri::Unknown) continue;
      const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
      const Eigen::Vector4d SX = matrixAt(k, t) * X;
      worst = std::max(worst, X.dot(SX) / std::max(2.0 * SX.head<3>().norm(), 1e-300));
    }
    return worst;
  }

  Tri pointState(const Eigen::Vector3d& x, double t) const {
    return detail::pointEval(f_, f_.root, [&](int a) { return pointSign(a, x, t); });
  }

 private:
  static double binom(int n, int k) {
    double r = 1.0;
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return r;
  }
  double horner(const double* p, double t) const {
    double v = p[n_];
    for (int d = n_ - 1; d >= 0; --d) v = v * t + p[d];
    return v;
  }
  // Bernstein coefficients on [t0, t0 + tau] of the power-basis polynomial p (degree n_): Taylor
  // shift by t0, scaling by tau, then the power -> Bernstein matrix. Rounding: the intermediate
  // magnitudes stay below sum |p_d| (t0 + tau <= 1), so the error is a few hundred ulps of the
  // atom's magnitude for n_ <= 60, far inside the 2^-40 pad.
  void bernstein(const double* p, double t0, double tau, double* out) const {
    double q[kMaxCoef];
    for (int d = 0; d <= n_; ++d) q[d] = p[d];
    if (t0 != 0.0)
      for (int k = 0; k < n_; ++k)
        for (int i = n_ - 1; i >= k; --i) q[i] += t0 * q[i + 1];
    double s = 1.0;
    for (int d = 0; d <= n_; ++d) {
      q[d] *= s;
      s *= tau;
    }
    for (int i = 0; i <= n_; ++i) {
      double v = 0.0;
      const double* row = &ratio_[i * (n_ + 1)];
      for (int j = 0; j <= i; ++j) v += row[j] * q[j];
      out[i] = v;
    }
  }
  double minOf(const std::array<double, kMaxCoef>& b) const { return *std::min_element(b.begin(), b.begin() + n_ + 1); }
  double maxOf(const std::array<double, kMaxCoef>& b) const { return *std::max_element(b.begin(), b.begin() + n_ + 1); }
  double maxAbsOf(const std::array<double, kMaxCoef>& b) const {
    double m = 0.0;
    for (int i = 0; i <= n_; ++i) m = std::max(m, std::fabs(b[i]));
    return m;
  }

  static long long key(int a, int b, int c = -1) {
    return (static_cast<long long>(a) << 40) ^ (static_cast<long long>(b) << 20) ^ static_cast<long long>(c + 1);
  }
  double pairLower(int a, int b, double mu) const {
    const int ids[2] = {a, b};
    const double w[2] = {mu * atoms_[a].scale, (1.0 - mu) * atoms_[b].scale};
    return pencilLower(ids, w, 2);
  }
  double tripleLower(const int* ids, const Eigen::Vector3d& mu) const {
    double w[3];
    for (int q = 0; q < 3; ++q) w[q] = mu[q] * atoms_[ids[q]].scale;
    return pencilLower(ids, w, 3);
  }

  // Lower bound of the centred form of sum_i w_i f_ids[i] (w_i >= 0) on the last box: the
  // Bernstein coefficients of the combination are the combinations of the coefficients, and the
  // rounding pad is the same combination of the atoms' pads (set by evaluate).
  double pencilLower(const int* ids, const double* w, int count) const {
    ++work_->evaluations;
    const int N = n_ + 1;
    double ext[10];
    double tmp[kMaxCoef];
    for (int q = 0; q < 10; ++q) {
      const double* b0 = on_box_[ids[0]].b[q].data();
      for (int i = 0; i < N; ++i) tmp[i] = w[0] * b0[i];
      for (int m = 1; m < count; ++m) {
        const double* bm = on_box_[ids[m]].b[q].data();
        const double wm = w[m];
        for (int i = 0; i < N; ++i) tmp[i] += wm * bm[i];
      }
      double e;
      if (q == 0 || (q >= 4 && q <= 6)) {  // minima: v and the diagonal of A
        e = tmp[0];
        for (int i = 1; i < N; ++i) e = std::min(e, tmp[i]);
      } else {  // maxima of |.|: g and the off-diagonal of A
        e = 0.0;
        for (int i = 0; i < N; ++i) e = std::max(e, std::fabs(tmp[i]));
      }
      ext[q] = e;
    }
    const Eigen::Vector3d& r = r_;
    double lo = ext[0] - (ext[1] * r[0] + ext[2] * r[1] + ext[3] * r[2]);
    for (int i = 0; i < 3; ++i) lo += std::min(0.0, ext[4 + i]) * r[i] * r[i];
    lo -= 2.0 * (ext[7] * r[0] * r[1] + ext[8] * r[0] * r[2] + ext[9] * r[1] * r[2]);
    double pad = 0.0;
    for (int m = 0; m < count; ++m) pad += w[m] * on_box_[ids[m]].pad;
    return lo - pad;
  }

  const Formula& f_;
  std::vector<MovingAtom> atoms_;
  int n_;
  // Rounding pad of every enclosure and point sign, relative to |X|^T abs |X| (see
  // paddingRelative).
  double sign_relative_ = 0.0;
  std::vector<double> ratio_;
  std::vector<AtomOnBox> on_box_;
  Eigen::Vector3d c_ = Eigen::Vector3d::Zero(), r_ = Eigen::Vector3d::Zero();
  double t0_ = -1.0, t1_ = -1.0;  // the slab of the A entries (none yet)
  // The last certifying weights of each pair / triple of atoms (warm starts; any weights are a
  // valid certificate, so a stale entry costs one evaluation and never a wrong exclusion).
  mutable std::unordered_map<long long, double> pair_mu_;
  mutable std::unordered_map<long long, Eigen::Vector3d> triple_mu_;
  QueryWork* work_;
};

struct PieceAnswer {
  bool collide = false;
  double time = 1.0;  // local time of the piece
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double band = 0.0;  // size of the box the answer came from
  bool near_tangent = false, capped = false;
};

// The rounding pad of the space-time engine, relative to |X|^T abs |X| with abs >= the sum of
// the magnitudes of every product that formed the moving atom. An error bound gamma_k ~ k 2^-53
// (k roundings on a path, each relative to the magnitudes) for: P = N_O M_F (sums of at most
// 4 (dN + 1) products per entry), S = P^T Q P (at most 16 (dP + 1) products per entry), and on
// each box the ten polynomials (16 products), the Taylor shift by t0, the scaling by tau and the
// Bernstein conversion (at most 3 n + 20 roundings; every intermediate stays below the magnitude
// because t0 + tau <= 1 and the conversion weights are <= 1). The pad is 4 times the sum.
double paddingRelative(std::size_t dP, std::size_t dN, int n) {
  const double k = 4.0 * (dN + 1) + 16.0 * (dP + 1) + 3.0 * n + 20.0;
  return 4.0 * k * std::ldexp(1.0, -53);
}

std::vector<Eigen::Matrix4d> magnitudes(const std::vector<Eigen::Matrix4d>& M) {
  std::vector<Eigen::Matrix4d> out;
  for (const Eigen::Matrix4d& m : M) out.push_back(m.cwiseAbs());
  return out;
}

enum class SlabOutcome { Empty, Found, Undecided, Inconclusive, Capped };

struct SlabAnswer {
  SlabOutcome outcome = SlabOutcome::Empty;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // witness or undecided box centre
  double time = 0.0;                                // witness time
  double band = 0.0;                                // diagonal of the box the point came from
};

// Depth-first search of the slab box x [t0, t1] (spatial splits only) for a certified interior
// point at some instant, or a certificate that the slab holds none. `budget` boxes at most
// (Inconclusive beyond, or Capped when a cap of the query is reached: RegionCcdLimits, both
// checked before each box).
SlabAnswer searchSlab(SpaceTimeEngine& engine, const Box3& box, double t0, double t1, double min_width, double t_tol,
                      int budget, int extra_after_undecided, QueryWork* work) {
  SlabAnswer ans;
  int undecided_at = -1, used = 0;
  std::vector<Box3> stack{box};
  while (!stack.empty()) {
    const Box3 b = stack.back();
    stack.pop_back();
    ++used;
    ++work->boxes;
    if (work->spent()) {
      ans.outcome = SlabOutcome::Capped;
      if (undecided_at < 0) ans.point = b.center();
      return ans;
    }
    const Eigen::Vector3d c = b.center(), r = b.halfWidth();
    FormulaBox fb = engine.evaluate(c, r, t0, t1);
    if (fb.root() == Tri::Out) continue;
    const bool inside_all = fb.root() == Tri::In;
    const double tm = 0.5 * (t0 + t1);
    double in = inside_all ? t0 : t1;
    if (inside_all || engine.pointState(c, t1) == Tri::In || engine.pointState(c, in = tm) == Tri::In) {
      // A witness at (c, t1) or (c, tm) (at (c, t0) when the whole box is inside); the earliest
      // instant at which c is still certified inside (bisection on the certified point test) is
      // one too.
      double out = t0;
      for (int k = 0; k < kWitnessBisections && in - out > t_tol; ++k) {
        const double mid = 0.5 * (in + out);
        (engine.pointState(c, mid) == Tri::In ? in : out) = mid;
      }
      if (engine.pointState(c, out) == Tri::In) in = out;  // out = t0 can be inside too
      ans.outcome = SlabOutcome::Found;
      ans.point = c;
      ans.time = in;
      ans.band = 2.0 * r.norm();
      return ans;
    }
    if (fb.excluded([&](const std::vector<int>& ids) { return engine.pencilExcluded(ids); })) continue;
    if (used >= budget) {
      ans.outcome = SlabOutcome::Inconclusive;
      return ans;
    }
    const int axis = engine.splitAxis(min_width);
    if (axis < 0) {
      // Within the band: keep looking for a witness for a while (as findPoint does).
      if (undecided_at < 0) {
        undecided_at = used;
        ans.point = c;
        ans.band = 2.0 * r.norm();
      }
      if (used - undecided_at >= extra_after_undecided) break;
      continue;
    }
    Box3 lo = b, hi = b;
    const double mid = 0.5 * (b.lo[axis] + b.hi[axis]);
    lo.hi[axis] = mid;
    hi.lo[axis] = mid;
    // The child whose centre looks deeper inside at t1 is searched first.
    if (engine.depth(lo.center(), t1) <= engine.depth(hi.center(), t1)) {
      stack.push_back(hi);
      stack.push_back(lo);
    } else {
      stack.push_back(lo);
      stack.push_back(hi);
    }
  }
  ans.outcome = undecided_at < 0 ? SlabOutcome::Empty : SlabOutcome::Undecided;
  return ans;
}

// First contact on one piece (local time [0, 1]) by an advancing front of time slabs: [0, L) is
// certified free; a witness at U bounds the first contact from above. The slab [L, L + dt] is
// searched with a small box budget: Empty advances L and doubles dt; a witness lowers U and
// halves dt; an inconclusive or undecided slab halves dt. A slab of width t_tol gets the full
// budget: Undecided there is a contact within the band (near_tangent). `work` holds the query's
// counts and the limits of one piece (kRegionCcdMaxBoxes and kRegionCcdMaxPencilEvaluations by
// default).
PieceAnswer searchPiece(const Formula& f, std::vector<MovingAtom> atoms, int degree, double sign_relative,
                        const Box3& box, double t_tol, double min_width, std::vector<int>* active, QueryWork* work) {
  SpaceTimeEngine engine(f, std::move(atoms), degree, sign_relative, work);
  work->startPiece();
  PieceAnswer ans;
  double lower = 0.0, upper = std::numeric_limits<double>::infinity(), dt = 1.0;
  int budget = kRegionCcdSlabBudget;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double band = 0.0;
  while (true) {
    if (upper - lower <= t_tol) {  // a witness within t_tol of the certified front
      ans.collide = true;
      ans.time = lower;
      ans.point = point;
      ans.band = band;
      break;
    }
    if (lower >= 1.0) break;  // certified free on the whole piece
    const double end = std::min({lower + dt, upper, 1.0});
    const bool finest = end - lower <= t_tol;
    const long long before = work->boxes;
    const SlabAnswer s = searchSlab(engine, box, lower, end, min_width, t_tol, finest ? work->limits.max_boxes : budget,
                                    finest ? kRegionCcdExtraBoxesAfterUndecided : 0, work);
    switch (s.outcome) {
      case SlabOutcome::Empty: {
        lower = end;
        dt *= 2.0;
        // A slab twice as wide costs more where the hardness is spatial (a small gap that closes
        // slowly): the budget follows the cost of the last certified slab.
        const long long next = std::max<long long>(kRegionCcdSlabBudget, 3 * (work->boxes - before));
        budget = static_cast<int>(std::min<long long>(next, work->limits.max_boxes));
        continue;
      }
      case SlabOutcome::Found:
        upper = s.time;
        point = s.point;
        band = s.band;
        dt = 0.5 * (upper - lower);
        continue;
      case SlabOutcome::Inconclusive:
      case SlabOutcome::Undecided:
        if (!finest) {
          dt = 0.5 * (end - lower);
          continue;
        }
        ans.near_tangent = true;
        break;
      case SlabOutcome::Capped: ans.capped = true; break;
    }
    ans.collide = true;  // conservative contact at the certified front
    ans.time = lower;
    ans.point = s.point;
    ans.band = s.band;
    break;
  }
  if (ans.collide) {
    // A witness within t_tol of the front lies in a thin lens at the contact: its distance to the
    // touching surfaces is tiny whatever the size of the box it came from. An undecided box holds
    // the contact somewhere inside: its own size is the band.
    const double floor = 1e-6 * (box.hi - box.lo).maxCoeff();
    const double b = (ans.near_tangent || ans.capped) ? std::max(ans.band, floor) : floor;
    for (int k = 0; k < engine.size(); ++k)
      if (engine.surfaceDistance(k, ans.point, ans.time) <= b) active->push_back(k);
  }
  return ans;
}

}  // namespace

RegionCcdResult continuousCollideRegions(const MovingRegion& a, const MovingRegion& b, const RegionCcdLimits& limits) {
  if (!a.box && !b.box)
    throw std::invalid_argument("continuousCollideRegions: both regions are unbounded (no local AABB)");
  if (limits.max_boxes < 1 || limits.max_pencil_evaluations < 1) {
    std::ostringstream os;
    os << "continuousCollideRegions: limits.max_boxes = " << limits.max_boxes
       << " and limits.max_pencil_evaluations = " << limits.max_pencil_evaluations << " must both be at least 1";
    throw std::invalid_argument(os.str());
  }
  QueryWork work{limits};
  // The search frame: the body with the smaller box (the bounded one if only one is).
  auto volume = [](const Box3& x) { return (x.hi - x.lo).prod(); };
  const bool frame_is_a = a.box && (!b.box || volume(*a.box) <= volume(*b.box));
  const MovingRegion& F = frame_is_a ? a : b;
  const MovingRegion& O = frame_is_a ? b : a;
  {
    // Far from the origin: the same query on both motions shifted by -o, o the frame body's
    // start (kRegionCcdShiftRelative). The shifted frame body starts within rounding of the
    // origin, so this recurses once at most.
    const Eigen::Vector3d o = F.motion.evaluate(0.0).block<3, 1>(0, 3);
    const double extent = (F.box->hi - F.box->lo).maxCoeff();
    if (o.allFinite() && o.norm() > kRegionCcdShiftRelative * extent) {
      auto shifted = [&](const MovingRegion& m) {
        const MotionMatrix T = MotionMatrix::constant(Eigen::Matrix3d::Identity(), -o);
        std::vector<MotionMatrix> pieces;
        for (const MotionMatrix& piece : m.motion.pieces()) pieces.push_back(MotionMatrix::compose(T, piece));
        return MovingRegion(m.region, m.box, PiecewiseMotion(m.motion.breaks(), std::move(pieces)), m.elements);
      };
      RegionCcdResult r = continuousCollideRegions(shifted(a), shifted(b), limits);
      r.point += o;
      return r;
    }
  }
  const Formula f(QuadricRegion::combine(QuadricRegion::Op::Intersection, {F.region, O.region}));
  const std::size_t nF = F.region.signedAtoms().size();
  const Box3& box = *F.box;
  const double min_width = kRegionCcdMinBoxRelative * (box.hi - box.lo).maxCoeff();

  // Pieces: the union of both motions' breaks.
  std::vector<double> breaks = a.motion.breaks();
  breaks.insert(breaks.end(), b.motion.breaks().begin(), b.motion.breaks().end());
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());

  RegionCcdResult res;
  for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
    const double s0 = breaks[p], s1 = breaks[p + 1];
    const MotionMatrix mF = F.motion.restricted(s0, s1), mO = O.motion.restricted(s0, s1);
    // F's local coordinates -> O's local coordinates, X_O ~ N_O(t) M_F(t) X_F up to a scalar factor
    // without roots on the piece; O's atom Q becomes P^T Q P in F's frame.
    const std::vector<Eigen::Matrix4d> P = multiplyCoefficients(mO.inverseCoefficients(), mF.matrixCoefficients());
    const std::vector<Eigen::Matrix4d> Pabs = multiplyCoefficients(magnitudes(mO.inverseCoefficients()), magnitudes(mF.matrixCoefficients()));
    std::vector<MovingAtom> atoms(f.atoms.size());
    int degree = 0;
    for (std::size_t k = 0; k < f.atoms.size(); ++k) {
      const Eigen::Matrix4d& Q = f.atoms[k];
      MovingAtom& m = atoms[k];
      if (k < nF) {
        m.S = {Q};
        m.abs = Q.cwiseAbs();
      } else {
        m.S = coefficientMatrices(congruence(Q, P));
        for (const Eigen::Matrix4d& A : coefficientMatrices(congruence(Eigen::Matrix4d(Q.cwiseAbs()), Pabs))) m.abs += A;
      }
      degree = std::max(degree, static_cast<int>(m.S.size()) - 1);
    }
    if (degree > kRegionCcdMaxDegree) {
      std::ostringstream os;
      os << "continuousCollideRegions: the relative motion gives moving atoms of degree " << degree
         << " in t, above kRegionCcdMaxDegree = " << kRegionCcdMaxDegree;
      throw CcdDegreeError(os.str(), degree, kRegionCcdMaxDegree);
    }
    for (MovingAtom& m : atoms) {
      m.constant = m.S.size() == 1;
      m.S.resize(degree + 1, Eigen::Matrix4d::Zero());
      const double mx = m.abs.maxCoeff();
      m.scale = mx > 0.0 ? 1.0 / mx : 1.0;
    }
    std::vector<int> active;
    const PieceAnswer ans =
        searchPiece(f, std::move(atoms), degree, paddingRelative(P.size() - 1, mO.inverseCoefficients().size() - 1, degree),
                    box, kRegionCcdTimeTolerance / (s1 - s0), min_width, &active, &work);
    res.boxes = static_cast<int>(std::min<long long>(work.boxes, std::numeric_limits<int>::max()));
    res.pencil_evaluations = work.evaluations;
    if (!ans.collide) continue;
    res.collide = true;
    res.time = std::min(1.0, s0 + (s1 - s0) * ans.time);
    res.near_tangent = ans.near_tangent;
    res.capped = ans.capped;
    const Eigen::Matrix4d X = F.motion.evaluate(res.time);
    res.point = X.topLeftCorner<3, 3>() * ans.point + X.block<3, 1>(0, 3);
    for (int k : active) {
      const bool in_f = static_cast<std::size_t>(k) < nF;
      const int local = in_f ? k : k - static_cast<int>(nF);
      ((in_f == frame_is_a) ? res.active_a : res.active_b).push_back(local);
    }
    break;
  }
  return res;
}

std::string boundaryElementLabel(const BoundaryElements& elements, const std::vector<int>& atoms) {
  std::vector<int> faces;
  for (int atom : atoms)
    for (std::size_t i = 0; i < elements.faces.size(); ++i)
      if (elements.faces[i].atom == atom) faces.push_back(static_cast<int>(i));
  std::sort(faces.begin(), faces.end());
  if (faces.empty()) return "";
  if (faces.size() == 1) return "F" + std::to_string(faces[0]);
  auto same = [&](std::vector<int> x) {
    std::sort(x.begin(), x.end());
    return x == faces;
  };
  if (faces.size() == 2)
    for (std::size_t i = 0; i < elements.edges.size(); ++i)
      if (same({elements.edges[i].face0, elements.edges[i].face1})) return "E" + std::to_string(i);
  if (faces.size() == 3)
    for (std::size_t i = 0; i < elements.vertices.size(); ++i) {
      const BoundaryVertex& v = elements.vertices[i];
      if (same({v.face0, v.face1, v.face2})) return "V" + std::to_string(i);
    }
  std::string out;
  for (int fi : faces) out += (out.empty() ? "F" : "+F") + std::to_string(fi);
  return out;
}

}  // namespace fcl_quadric
