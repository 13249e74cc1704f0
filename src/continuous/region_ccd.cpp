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
#include "algebra/bernstein_matrix.h"
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

/// A moving atom X^T S(u) X in the search frame: Bernstein coefficient matrices in the piece's
/// local time u in [0, 1] (algebra/bernstein_matrix.h; every moving atom has the common degree,
/// twice the relative motion's), and its rounding bounds: `abs` >= |S_i| entrywise for every i,
/// the magnitudes of the products that formed S included (the sign pads are relative to it), and
/// `err` >= the entrywise error of every S_i that the conversion of the motions from the power
/// basis left (an absolute bound, added to the pads; paddingRelative).
struct MovingAtom {
  detail::BernsteinMatrix S;
  Eigen::Matrix4d abs = Eigen::Matrix4d::Zero();
  Eigen::Matrix4d err = Eigen::Matrix4d::Zero();
  double scale = 1.0;  // normalises atoms for pencils and split scores (weightScale)
  bool constant = false;  // a single coefficient (the search frame's own atoms)
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
      : f_(f), atoms_(std::move(atoms)), n_(degree), on_box_(atoms_.size()), slab_(atoms_.size()),
        mid_(atoms_.size()), pad_(atoms_.size()), work_(work) {
    // The sign pad of X^T S X, |X|^T pad |X| (paddingRelative): rounding relative to the
    // magnitudes, plus the conversion's absolute error (its own rounding is far below 2^-30 of it).
    for (std::size_t k = 0; k < atoms_.size(); ++k)
      pad_[k] = sign_relative * atoms_[k].abs + (1.0 + std::ldexp(1.0, -30)) * atoms_[k].err;
  }

  int size() const { return static_cast<int>(atoms_.size()); }

  /// Encloses every atom on c ± r times [t0, t1] and returns the formula's state there.
  FormulaBox evaluate(const Eigen::Vector3d& c, const Eigen::Vector3d& r, double t0, double t1) {
    c_ = c;
    r_ = r;
    if (t0 != t0_ || t1 != t1_) setSlab(t0, t1);
    const Eigen::Vector4d C(c[0], c[1], c[2], 1.0);
    const Eigen::Vector4d Xa((c.cwiseAbs() + r)[0], (c.cwiseAbs() + r)[1], (c.cwiseAbs() + r)[2], 1.0);
    std::vector<Tri> states(atoms_.size());
    for (std::size_t k = 0; k < atoms_.size(); ++k) {
      const MovingAtom& m = atoms_[k];
      AtomOnBox& e = on_box_[k];
      // v and g depend on the centre: their Bernstein coefficients on [t0, t1] are the forms of
      // the slab's coefficient matrices (setSlab); the A entries were set for the slab too.
      const detail::BernsteinMatrix& Sk = m.constant ? m.S : slab_[k];
      for (std::size_t d = 0; d < Sk.size(); ++d) {
        const Eigen::Vector4d SC = Sk[d] * C;
        e.b[0][d] = C.dot(SC);
        e.b[1][d] = 2.0 * SC[0];
        e.b[2][d] = 2.0 * SC[1];
        e.b[3][d] = 2.0 * SC[2];
      }
      if (m.constant)
        for (int q = 0; q < 4; ++q) std::fill(e.b[q].begin() + 1, e.b[q].begin() + n_ + 1, e.b[q][0]);
      e.gmid = 2.0 * (mid_[k] * C).head<3>();
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
      const double pad = Xa.dot(pad_[k] * Xa);
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

  /// Every atom's coefficient matrices restricted to [t0, t1] (de Casteljau subdivision), its
  /// matrix at the slab's midpoint, and the A entries (second-order part) over the slab: none of
  /// them depends on the box centre, so a slab computes them once.
  void setSlab(double t0, double t1) {
    t0_ = t0;
    t1_ = t1;
    tm_ = 0.5 * (t0 + t1);
    static constexpr int kIndex[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
    for (std::size_t k = 0; k < atoms_.size(); ++k) {
      const MovingAtom& m = atoms_[k];
      AtomOnBox& e = on_box_[k];
      if (m.constant) {
        mid_[k] = m.S[0];
      } else {
        detail::bernsteinRestrict(m.S, t0, t1, &slab_[k]);
        mid_[k] = detail::bernsteinAt(slab_[k], 0.5);
      }
      for (int q = 0; q < 6; ++q) {
        const int i = kIndex[q][0], j = kIndex[q][1];
        if (m.constant) {
          std::fill(e.b[4 + q].begin(), e.b[4 + q].begin() + n_ + 1, m.S[0](i, j));
        } else {
          for (int d = 0; d <= n_; ++d) e.b[4 + q][d] = slab_[k][d](i, j);
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

  /// S(t) of atom k: at the current slab's ends and midpoint from the slab (setSlab), elsewhere
  /// by de Casteljau on the piece's coefficients.
  Eigen::Matrix4d matrixAt(int k, double t) const {
    const MovingAtom& m = atoms_[k];
    if (m.constant) return m.S[0];
    if (t == t1_) return slab_[k][n_];
    if (t == t0_) return slab_[k][0];
    if (t == tm_) return mid_[k];
    return detail::bernsteinAt(m.S, t);
  }

  /// Certified sign of atom k at (x, t): -1 inside, +1 outside, 0 within the rounding band.
  int pointSign(int k, const Eigen::Vector3d& x, double t) const {
    const Eigen::Matrix4d S = matrixAt(k, t);
    const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
    const double v = X.dot(S * X);
    const Eigen::Vector4d Xa = X.cwiseAbs();
    const double pad = Xa.dot(pad_[k] * Xa);
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
  std::vector<AtomOnBox> on_box_;
  // The current slab's coefficient matrices of each moving atom and its matrix at the midpoint.
  std::vector<detail::BernsteinMatrix> slab_;
  std::vector<Eigen::Matrix4d> mid_;
  // The sign pad of every enclosure and point sign: |X|^T pad_[k] |X| (paddingRelative).
  std::vector<Eigen::Matrix4d> pad_;
  Eigen::Vector3d c_ = Eigen::Vector3d::Zero(), r_ = Eigen::Vector3d::Zero();
  double t0_ = -1.0, t1_ = -1.0, tm_ = -1.0;  // the current slab (none yet)
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

// The rounding pad of the space-time engine, relative to |X|^T abs |X| with abs >= the
// magnitudes of every product that formed the moving atom (MovingAtom). An error bound
// gamma_k ~ k 2^-53 (k roundings on a path, each relative to the magnitudes; every weight of the
// Bernstein products and of de Casteljau is positive and below 1, so no intermediate exceeds the
// magnitude) for: P = N_O M_F (4-term products, the weight, at most dN + dM + 1 sums: dN + dM + 9
// roundings, counted twice because S holds P twice), S = P^T (Q P) (dN + dM + 17), the slab's
// coefficients by two subdivisions and a point value by a third de Casteljau (4 roundings per
// level: 12 n), and on each box the ten forms X^T S_i X (20). The pad is 4 times the sum. The
// conversion of the motions' power coefficients to the Bernstein basis is not counted here: its
// error is bounded separately (RelativeMotion::err, MovingAtom::err) and added to the pad.
double paddingRelative(std::size_t dN, std::size_t dM, int n) {
  const double d = static_cast<double>(dN + dM);
  const double k = 2.0 * (d + 9.0) + (d + 17.0) + 12.0 * n + 20.0;
  return 4.0 * k * std::ldexp(1.0, -53);
}

using detail::BernsteinMatrix;

// The normalisation of an atom in the pencils' weights and the split scores (no rounding role;
// any positive value keeps every exclusion certified): one over its largest second-order
// magnitude (the curvature block of abs), or its largest first-order one for a plane. Neither
// depends on where the atom is, unlike the largest entry, whose constant term grows with the
// square of the distance from the frame's origin. Measured against the largest magnitude of the
// Bernstein coefficients (docs/reliability.md finding 49): a ring's line contact that reached the
// box cap at two of four ball radii is decided at all four, turning and thin pairs alike.
double weightScale(const Eigen::Matrix4d& abs) {
  const double second = abs.topLeftCorner<3, 3>().maxCoeff(), first = abs.block<3, 1>(0, 3).maxCoeff();
  const double e = second > 0.0 ? second : first > 0.0 ? first : abs.maxCoeff();
  return e > 0.0 ? 1.0 / e : 1.0;
}

BernsteinMatrix sum(BernsteinMatrix a, const BernsteinMatrix& b) {
  for (std::size_t i = 0; i < a.size(); ++i) a[i] += b[i];
  return a;
}
BernsteinMatrix scaled(BernsteinMatrix a, double s) {
  for (Eigen::Matrix4d& m : a) m *= s;
  return a;
}

// The relative motion P = N_O M_F of one piece (F's local coordinates -> O's, up to a scalar
// factor without roots on the piece) in the Bernstein basis of the piece's [0, 1], with the bounds
// the sign pads need: mag >= |P_i| entrywise, the magnitudes of the products that formed it
// included, and err >= the entrywise error of P_i that converting the motions' power coefficients
// left (the conversion's weights are positive: its rounding is a few ulps of the conversion of the
// coefficients' magnitudes). The power coefficients of a turning motion cancel, so converting the
// factors first keeps every later rounding relative to the values (docs/reliability.md finding 49).
struct RelativeMotion {
  BernsteinMatrix P, mag, err;
};

RelativeMotion relativeMotion(const MotionMatrix& mO, const MotionMatrix& mF) {
  const std::vector<Eigen::Matrix4d>& N = mO.inverseCoefficients();
  const std::vector<Eigen::Matrix4d>& M = mF.matrixCoefficients();
  const std::size_t dN = N.size() - 1, dM = M.size() - 1;
  const double u = std::ldexp(1.0, -53);
  // The degree of the power-basis product, exact zeros removed: two translations' top terms
  // cancel exactly (a translation of degree 1 relative to another is of degree 1, not 2), and the
  // moving atoms' degree sets the work on every box.
  std::vector<Eigen::Matrix4d> Ppow = multiplyCoefficients(N, M);
  std::size_t dP = Ppow.size() - 1;
  while (dP > 0 && (Ppow[dP].array() == 0.0).all()) --dP;
  RelativeMotion r;
  if (dP == dN + dM) {
    const BernsteinMatrix NB = detail::bernsteinFromPower(N), MB = detail::bernsteinFromPower(M);
    const BernsteinMatrix NA = detail::cwiseAbs(NB), MA = detail::cwiseAbs(MB);
    const BernsteinMatrix EN = scaled(detail::bernsteinFromPower(detail::cwiseAbs(N)), 2.0 * (dN + 3) * u);
    const BernsteinMatrix EM = scaled(detail::bernsteinFromPower(detail::cwiseAbs(M)), 2.0 * (dM + 3) * u);
    r.P = detail::bernsteinProduct(NB, MB);
    r.mag = detail::bernsteinProduct(NA, MA);
    // (NB + dN)(MB + dM) - NB MB = dN MB + (NB + dN) dM, |dN| <= EN, |dM| <= EM.
    r.err = sum(detail::bernsteinProduct(EN, MA), detail::bernsteinProduct(sum(NA, EN), EM));
    return r;
  }
  // The product's degree is lower than the factors' together: convert the product itself (the
  // Bernstein product would carry the higher degree). Its rounding and the conversion's go into
  // err, relative to the product of the magnitudes; the terms above dP (computed as exact zeros,
  // each within its rounding of the magnitudes' product) are bounded on [0, 1] by the sum of
  // those magnitudes, a constant added to every coefficient.
  const std::vector<Eigen::Matrix4d> Pmag = multiplyCoefficients(detail::cwiseAbs(N), detail::cwiseAbs(M));
  const double k = 2.0 * (4.0 * (dN + dM + 2) + dP + 3);
  Eigen::Matrix4d tail = Eigen::Matrix4d::Zero();
  for (std::size_t i = dP + 1; i < Pmag.size(); ++i) tail += Pmag[i];
  Ppow.resize(dP + 1);
  r.P = detail::bernsteinFromPower(Ppow);
  r.mag = detail::cwiseAbs(r.P);
  r.err = scaled(detail::bernsteinFromPower(std::vector<Eigen::Matrix4d>(Pmag.begin(), Pmag.begin() + dP + 1)), k * u);
  for (Eigen::Matrix4d& e : r.err) e += k * u * tail;
  return r;
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
    // X_O ~ P(t) X_F; O's atom Q becomes P^T Q P in F's frame.
    const RelativeMotion rel = relativeMotion(mO, mF);
    const int degree = 2 * static_cast<int>(rel.P.size() - 1);
    if (degree > kRegionCcdMaxDegree) {
      std::ostringstream os;
      os << "continuousCollideRegions: the relative motion gives moving atoms of degree " << degree
         << " in t, above kRegionCcdMaxDegree = " << kRegionCcdMaxDegree;
      throw CcdDegreeError(os.str(), degree, kRegionCcdMaxDegree);
    }
    std::vector<MovingAtom> atoms(f.atoms.size());
    for (std::size_t k = 0; k < f.atoms.size(); ++k) {
      const Eigen::Matrix4d& Q = f.atoms[k];
      const Eigen::Matrix4d Qabs = Q.cwiseAbs();
      MovingAtom& m = atoms[k];
      if (k < nF) {
        m.S = {Q};
        m.abs = Qabs;
      } else {
        // S and its bounds: |S_i| <= mag^T |Q| mag (Bernstein products of magnitudes), and the
        // conversion's error (P + E)^T Q (P + E) - P^T Q P <= E^T |Q| (mag + E) + mag^T |Q| E.
        m.S = detail::bernsteinCongruence(Q, rel.P);
        m.abs = detail::entrywiseMax(detail::bernsteinCongruence(Qabs, rel.mag));
        const BernsteinMatrix QE = detail::bernsteinProduct({Qabs}, rel.err);
        const BernsteinMatrix QmagE = sum(detail::bernsteinProduct({Qabs}, rel.mag), QE);
        m.err = detail::entrywiseMax(sum(detail::bernsteinProduct(detail::transposed(rel.err), QmagE),
                                         detail::bernsteinProduct(detail::transposed(rel.mag), QE)));
      }
      m.constant = m.S.size() == 1;
      m.scale = weightScale(m.abs);
    }
    std::vector<int> active;
    const PieceAnswer ans = searchPiece(
        f, std::move(atoms), degree,
        paddingRelative(mO.inverseCoefficients().size() - 1, mF.matrixCoefficients().size() - 1, degree), box,
        kRegionCcdTimeTolerance / (s1 - s0), min_width, &active, &work);
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
