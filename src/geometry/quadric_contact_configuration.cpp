/// \file quadric_contact_configuration.cpp
/// Contact configuration of two tangent quadrics (Choi 2008 §6.3.1 Lemma 6.2, §6.3.2 Procedure,
/// Tables 7-10); see the header for the conventions, the departures from the thesis and the
/// tolerances.
#include "fcl_quadric/geometry/quadric_contact_configuration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "fcl_quadric/algebra/symmetric_eigen.h"

namespace fcl_quadric {

using namespace tolerance_contact;

namespace {

// --- input ----------------------------------------------------------------------------------

void checkMatrix(const Eigen::Matrix4d& Q, const char* name) {
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      if (!std::isfinite(Q(i, j))) {
        std::ostringstream os;
        os << "contact configuration: quadric matrix " << name << " must be finite, got entry (" << i << ", " << j
           << ") = " << Q(i, j) << " in\n"
           << Q;
        throw std::invalid_argument(os.str());
      }
    }
  }
  const double scale = Q.cwiseAbs().maxCoeff();
  const double asym = (Q - Q.transpose()).cwiseAbs().maxCoeff();
  if (asym > kSymmetryRelative * scale) {
    std::ostringstream os;
    os << "contact configuration: quadric matrix " << name << " must be symmetric (max |" << name << " - " << name
       << "^T| = " << asym << ", relative tolerance " << kSymmetryRelative << "), got\n"
       << Q;
    throw std::invalid_argument(os.str());
  }
}

void checkNonZero(const Eigen::Matrix4d& Q, const char* name) {
  if (!(Q.cwiseAbs().maxCoeff() > 0.0)) {
    std::ostringstream os;
    os << "contact configuration: quadric matrix " << name << " must not be zero";
    throw std::invalid_argument(os.str());
  }
}

Eigen::Matrix4d symmetrised(const Eigen::Matrix4d& Q) { return 0.5 * (Q + Q.transpose()); }

// --- the characteristic polynomial ------------------------------------------------------------

using QuarticCoeffs = std::array<double, 5>;

/// det(x X - Y) = sum_k c[k] x^k and the same Leibniz sum over |products| (abs), the scale that
/// bounds the rounding of c and its sensitivity to relative perturbations of the entries.
struct Expansion {
  QuarticCoeffs c{};
  QuarticCoeffs abs{};
};

Expansion expand(const Eigen::Matrix4d& X, const Eigen::Matrix4d& Y) {
  Expansion e;
  std::array<int, 4> perm{0, 1, 2, 3};
  do {
    int inversions = 0;
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) inversions += perm[i] > perm[j] ? 1 : 0;
    }
    // prod_i (a_i x - b_i) and prod_i (|a_i| x + |b_i|), built up one linear factor at a time.
    QuarticCoeffs p{1.0, 0.0, 0.0, 0.0, 0.0};
    QuarticCoeffs q{1.0, 0.0, 0.0, 0.0, 0.0};
    for (int i = 0; i < 4; ++i) {
      const double a = X(i, perm[i]);
      const double b = Y(i, perm[i]);
      for (int k = i + 1; k >= 0; --k) {
        const double p_lower = k > 0 ? p[k - 1] : 0.0;
        const double q_lower = k > 0 ? q[k - 1] : 0.0;
        p[k] = a * p_lower - b * p[k];
        q[k] = std::fabs(a) * q_lower + std::fabs(b) * q[k];
      }
    }
    const double sign = (inversions % 2 == 0) ? 1.0 : -1.0;
    for (int k = 0; k < 5; ++k) {
      e.c[k] += sign * p[k];
      e.abs[k] += q[k];
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return e;
}

constexpr double kBinomial[5][5] = {
    {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};

/// f^(k)(x) / k! for f = sum_j c[j] x^j.
double derivative(const QuarticCoeffs& c, int k, double x) {
  double v = 0.0;
  for (int j = 4; j >= k; --j) v = v * x + kBinomial[j][k] * c[j];
  return v;
}

/// Real roots of sum_i q[i] x^i in [lo, hi], ascending: the critical points (recursively) split
/// the interval into monotone pieces, each bisected where it changes sign. 0 is always a split
/// point too, so that the frequent exact root 0 (a singular B, or A at infinity, with structural
/// zeros) is found exactly rather than as a bisection limit ~1e-60. A root where the polynomial
/// only touches zero is found only if it evaluates to exactly 0 (a double root of the derivative
/// searched here is never the target: see findMultipleRoots).
std::vector<double> realRootsIn(std::vector<double> q, double lo, double hi) {
  while (!q.empty() && q.back() == 0.0) q.pop_back();
  std::vector<double> roots;
  const int d = static_cast<int>(q.size()) - 1;
  if (d <= 0) return roots;
  if (d == 1) {
    const double bound = std::max(std::fabs(lo), std::fabs(hi));
    if (std::fabs(q[0]) <= bound * std::fabs(q[1])) {  // |root| <= bound: no overflow, q[1] != 0
      const double r = -q[0] / q[1];
      if (r >= lo && r <= hi) roots.push_back(r);
    }
    return roots;
  }
  const auto eval = [&q](double x) {
    double v = 0.0;
    for (int i = static_cast<int>(q.size()) - 1; i >= 0; --i) v = v * x + q[i];
    return v;
  };
  std::vector<double> dq(q.size() - 1);
  for (std::size_t i = 0; i + 1 < q.size(); ++i) dq[i] = static_cast<double>(i + 1) * q[i + 1];
  std::vector<double> splits = realRootsIn(dq, lo, hi);
  if (lo < 0.0 && hi > 0.0) splits.push_back(0.0);
  std::sort(splits.begin(), splits.end());
  std::vector<double> points{lo};
  for (double c : splits) {
    if (c > points.back() && c < hi) points.push_back(c);
  }
  points.push_back(hi);
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    double a = points[i], b = points[i + 1];
    double fa = eval(a);
    const double fb = eval(b);
    if (fa == 0.0) {
      roots.push_back(a);
      continue;
    }
    if (fb == 0.0 || std::signbit(fa) == std::signbit(fb)) continue;
    for (int it = 0; it < 200; ++it) {
      const double m = 0.5 * (a + b);
      if (!(m > a && m < b)) break;
      const double fm = eval(m);
      if (fm == 0.0) {
        a = b = m;
        break;
      }
      if (std::signbit(fm) == std::signbit(fa)) {
        a = m;
        fa = fm;
      } else {
        b = m;
      }
    }
    roots.push_back(0.5 * (a + b));
  }
  if (eval(hi) == 0.0) roots.push_back(hi);
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  return roots;
}

// --- the normalised pencil on two charts of the projective line ------------------------------

/// One chart: det(x X - Y) = sum_k c[k] x^k. Chart 0: x = mu, (X, Y) = (A', B'); chart 1:
/// x = nu = 1/mu, (X, Y) = (B', A'), coefficients reversed (det(nu B' - A') = nu^4 f(1/nu)).
struct Chart {
  Eigen::Matrix4d X;
  Eigen::Matrix4d Y;
  QuarticCoeffs c{};
  QuarticCoeffs abs{};
  bool reciprocal = false;
};

struct Pencil {
  Chart chart[2];
  int ea = 0;  // A = 2^ea A', B = 2^eb B'; mu = 2^(ea - eb) lambda
  int eb = 0;
  bool singular = false;
};

Pencil makePencil(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B) {
  Pencil p;
  std::frexp(A.norm(), &p.ea);
  std::frexp(B.norm(), &p.eb);
  const Eigen::Matrix4d An = A * std::ldexp(1.0, -p.ea);  // exact: a power of two
  const Eigen::Matrix4d Bn = B * std::ldexp(1.0, -p.eb);
  const Expansion e = expand(An, Bn);
  p.chart[0].X = An;
  p.chart[0].Y = Bn;
  p.chart[0].c = e.c;
  p.chart[0].abs = e.abs;
  p.chart[1].X = Bn;
  p.chart[1].Y = An;
  for (int k = 0; k < 5; ++k) {
    p.chart[1].c[k] = e.c[4 - k];
    p.chart[1].abs[k] = e.abs[4 - k];
  }
  p.chart[1].reciprocal = true;
  p.singular = true;
  for (int k = 0; k < 5; ++k) {
    if (std::fabs(e.c[k]) > kDerivativeZeroRelative * e.abs[k]) p.singular = false;
  }
  return p;
}

/// |f^(k)(x)/k!| <= kDerivativeZeroRelative times its absolute-value scale at |x|, plus 2^-52 of
/// that scale at |x| = 1 (the chart's extent) so that a scale vanishing at x itself (structural
/// zeros: e.g. f = c x^2 with no absolute term) does not make a rounded root fail the test.
bool derivativeIsZero(const Chart& ch, int k, double x) {
  const double scale = derivative(ch.abs, k, std::fabs(x)) + 0x1p-52 * derivative(ch.abs, k, 1.0);
  return std::fabs(derivative(ch.c, k, x)) <= kDerivativeZeroRelative * scale;
}

/// The n of the n-th derivative test: smallest n with f^(n)(x) != 0 (-1 if none: f == 0).
int firstNonZeroDerivative(const Chart& ch, double x) {
  for (int k = 0; k <= 4; ++k) {
    if (!derivativeIsZero(ch, k, x)) return k;
  }
  return -1;
}

struct Root {
  int chart = 0;
  double x = 0.0;
  int multiplicity = 0;
};

/// Sine of the angle between the projective points (on the normalised scale).
double chordal(int chart_a, double xa, int chart_b, double xb) {
  const double sa = chart_a == 0 ? xa : 1.0, ta = chart_a == 0 ? 1.0 : xa;
  const double sb = chart_b == 0 ? xb : 1.0, tb = chart_b == 0 ? 1.0 : xb;
  return std::fabs(sa * tb - sb * ta) / (std::hypot(sa, ta) * std::hypot(sb, tb));
}

/// Multiple roots: an m-fold root is a simple root of f^(m-1) (well conditioned even when noise
/// has split the root of f) where f, ..., f^(m-2) vanish to tolerance. Candidates of both charts,
/// highest multiplicity first, merged within kRootCluster.
std::vector<Root> findMultipleRoots(const Pencil& p) {
  std::vector<Root> candidates;
  for (int m = 4; m >= 2; --m) {
    for (int ci = 0; ci < 2; ++ci) {
      const Chart& ch = p.chart[ci];
      std::vector<double> q(6 - m);
      for (int i = 0; i <= 5 - m; ++i) q[i] = kBinomial[i + m - 1][m - 1] * ch.c[i + m - 1];
      for (double r : realRootsIn(q, -kChartRadius, kChartRadius)) {
        bool ok = true;
        for (int k = 0; k + 2 <= m && ok; ++k) ok = derivativeIsZero(ch, k, r);
        if (ok) candidates.push_back(Root{ci, r, m});
      }
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(), [](const Root& a, const Root& b) {
    if (a.multiplicity != b.multiplicity) return a.multiplicity > b.multiplicity;
    return std::fabs(a.x) < std::fabs(b.x);  // the better-conditioned chart first
  });
  std::vector<Root> accepted;
  for (const Root& c : candidates) {
    bool duplicate = false;
    for (const Root& a : accepted) {
      if (chordal(a.chart, a.x, c.chart, c.x) <= kRootCluster) duplicate = true;
    }
    if (!duplicate) accepted.push_back(c);
  }
  return accepted;
}

double toLambda(const Pencil& p, int chart, double x) {
  if (chart == 0) return std::ldexp(x, p.eb - p.ea);
  if (std::fabs(x) <= kInfinitySnap) return std::numeric_limits<double>::infinity();
  return std::ldexp(1.0 / x, p.eb - p.ea);
}

void fromLambda(const Pencil& p, double lambda, int* chart, double* x) {
  if (std::isinf(lambda)) {
    *chart = 1;
    *x = 0.0;
    return;
  }
  const double mu = std::ldexp(lambda, p.ea - p.eb);
  if (std::fabs(mu) <= 1.0) {
    *chart = 0;
    *x = mu;
  } else {
    *chart = 1;
    *x = 1.0 / mu;  // |mu| > 1 (possibly inf: x = 0, the root at infinity)
  }
}

// --- contact points ---------------------------------------------------------------------------

Eigen::Vector4d canonicalPoint(const Eigen::Vector4d& v) {
  Eigen::Vector4d X = v / v.norm();
  if (std::fabs(X(3)) > 1e-12) {
    if (X(3) < 0.0) X = -X;
  } else {
    Eigen::Index i = 0;
    X.cwiseAbs().maxCoeff(&i);
    if (X(i) < 0.0) X = -X;
  }
  return X;
}

/// Real points of the null space N (columns orthonormal) on the quadric X (the pencil member
/// other than Y; on N, x X = Y). plane_section: lambda0 A - B is the double plane Y itself.
void contactPoints(const Eigen::Matrix4d& X, const Eigen::MatrixXd& N, bool plane_section, ContactConfiguration& cfg) {
  const int dim = static_cast<int>(N.cols());
  auto push = [&cfg](const Eigen::Vector4d& v) { cfg.contact_points.push_back(canonicalPoint(v)); };
  if (dim == 1) {
    push(N.col(0));  // Lemma 6.2 case 1: the null vector lies on both quadrics
  } else if (dim == 2 || dim == 3) {
    const Eigen::MatrixXd C = N.transpose() * X * N;
    const SymmetricEigenDecomposition es = symmetricEigen(C);  // of (C + C^T) / 2
    const Eigen::VectorXd& c = es.values;  // ascending
    const Eigen::MatrixXd& V = es.vectors;
    // Relative to C's own scale (far from the origin the restricted form shrinks as a whole),
    // but never below kRankRelative * 1e-4 (rounding of C and of the null space N).
    const double threshold = kRankRelative * std::max(c.cwiseAbs().maxCoeff(), 1e-4);
    int pos = 0, neg = 0, zero_index = -1, zeros = 0;
    for (int i = 0; i < dim; ++i) {
      if (c(i) > threshold) {
        ++pos;
      } else if (c(i) < -threshold) {
        ++neg;
      } else {
        ++zeros;
        if (zero_index < 0) zero_index = i;
      }
    }
    if (dim == 2) {
      if (zeros == 2) {  // the null-space line lies on both quadrics
        push(N * V.col(0));
        push(N * V.col(1));
        cfg.contact_curve = true;
      } else if (zeros == 1) {  // the line is tangent to A: one (double) point
        push(N * V.col(zero_index));
      } else if (pos == 1 && neg == 1) {  // two real points: c0 < 0 < c1
        const Eigen::VectorXd a = std::sqrt(c(1)) * V.col(0);
        const Eigen::VectorXd b = std::sqrt(-c(0)) * V.col(1);
        push(N * (a + b));
        push(N * (a - b));
      }
    } else if (plane_section) {
      // One quadric is a double plane: the section conic C; contact only at its singular point.
      if (zeros == 1) {
        push(N * V.col(zero_index));
      } else if (zeros >= 2) {
        for (int i = 0; i < dim; ++i) {
          if (std::fabs(c(i)) <= threshold) push(N * V.col(i));
        }
        cfg.contact_curve = true;
      }
    } else {
      if (zeros == 3) {  // the null plane lies on both quadrics
        push(N.col(0));
        cfg.contact_curve = true;
      } else if (zeros >= 1) {  // vertex of a line pair / the double line / an isolated real point
        push(N * V.col(zero_index));
        cfg.contact_curve = (pos > 0 && neg > 0) || zeros == 2;
      } else if (pos > 0 && neg > 0) {  // a real non-degenerate conic: one representative point
        const Eigen::VectorXd a = std::sqrt(c(dim - 1)) * V.col(0);
        const Eigen::VectorXd b = std::sqrt(-c(0)) * V.col(dim - 1);
        push(N * (a + b));
        cfg.contact_curve = true;
      }
    }
  }
  cfg.real_contact = !cfg.contact_points.empty();
}

}  // namespace

const char* toString(TangencyKind k) {
  switch (k) {
    case TangencyKind::SinglePoint:
      return "SinglePoint";
    case TangencyKind::TwoPointsOrLine:
      return "TwoPointsOrLine";
    case TangencyKind::Conic:
      return "Conic";
    case TangencyKind::Coincident:
      return "Coincident";
    case TangencyKind::None:
      return "None";
  }
  return "?";
}

std::array<double, 5> characteristicQuartic(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B) {
  checkMatrix(A, "A");
  checkMatrix(B, "B");
  return expand(symmetrised(A), symmetrised(B)).c;
}

std::vector<double> multipleRoots(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B) {
  checkMatrix(A, "A");
  checkMatrix(B, "B");
  checkNonZero(A, "A");
  checkNonZero(B, "B");
  const Pencil p = makePencil(symmetrised(A), symmetrised(B));
  std::vector<double> out;
  if (p.singular) return out;
  for (const Root& r : findMultipleRoots(p)) out.push_back(toLambda(p, r.chart, r.x));
  std::sort(out.begin(), out.end());  // +infinity last
  return out;
}

ContactConfiguration contactConfiguration(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B, double lambda0) {
  checkMatrix(A, "A");
  checkMatrix(B, "B");
  checkNonZero(A, "A");
  checkNonZero(B, "B");
  if (std::isnan(lambda0)) {
    throw std::invalid_argument("contact configuration: lambda0 must not be NaN (+-infinity is the root at infinity)");
  }
  const Pencil p = makePencil(symmetrised(A), symmetrised(B));
  ContactConfiguration cfg;
  cfg.lambda0 = lambda0;

  int ci = 0;
  double x = 0.0;
  fromLambda(p, lambda0, &ci, &x);

  int multiplicity = 0;
  int n = -1;
  bool multiple = false;
  if (p.singular) {
    cfg.singular_pencil = true;
    multiplicity = -1;
  } else {
    n = firstNonZeroDerivative(p.chart[ci], x);
    multiplicity = n;
    if (n >= 2) {
      // The derivative test says lambda0 is a multiple root: refine it to the well-conditioned
      // root of f^(m-1) nearby (if the search found one).
      double best = kRootCluster;
      for (const Root& r : findMultipleRoots(p)) {
        const double d = chordal(ci, x, r.chart, r.x);
        if (d <= best) {
          best = d;
          ci = r.chart;
          x = r.x;
          multiplicity = r.multiplicity;
          cfg.lambda0 = toLambda(p, r.chart, r.x);
        }
      }
      n = firstNonZeroDerivative(p.chart[ci], x);
      multiple = n >= 2 && multiplicity >= 2;
      if (!multiple) multiplicity = n;
    }
  }
  cfg.multiplicity = multiplicity;
  cfg.first_nonzero_derivative = n;
  const Chart& ch = p.chart[ci];

  // Step 1 (n-th derivative test): f ~ f^(n)(x0)/n! (x - x0)^n; f < 0 is an "ellipsoid" (det of
  // a 4x4 symmetric matrix is < 0 iff it has an odd number of negative eigenvalues). The chart
  // polynomials have the sign of f: positive factors 2^(4 eb) and nu^4.
  if (n >= 0) {
    const double s = derivative(ch.c, n, x);
    const bool after = s < 0.0;
    const bool before = (n % 2 == 0) ? after : !after;
    // The chart nu = 1/mu runs against lambda (and through +inf -> -inf at nu = 0).
    cfg.ellipsoid_before = ch.reciprocal ? after : before;
    cfg.ellipsoid_after = ch.reciprocal ? before : after;
  }

  // Rank and inertia of M = x X - Y (in chart 1, M = -nu (lambda0 A - B) up to a positive factor).
  const Eigen::Matrix4d M = x * ch.X - ch.Y;
  Eigen::Vector4d sigma = Eigen::Vector4d::Zero();
  Eigen::Matrix4d vectors = Eigen::Matrix4d::Identity();
  if (M.cwiseAbs().maxCoeff() > 0.0) {
    const SymmetricEigenDecomposition es = symmetricEigen(M);
    sigma = es.values;
    vectors = es.vectors;
  }
  std::array<int, 4> order{0, 1, 2, 3};
  std::sort(order.begin(), order.end(), [&sigma](int a, int b) { return std::fabs(sigma(a)) < std::fabs(sigma(b)); });
  const double threshold = kRankRelative * (1.0 + std::fabs(x));
  int zeros = 0;
  for (int i = 0; i < 4; ++i) zeros += std::fabs(sigma(i)) <= threshold ? 1 : 0;
  if (multiple) zeros = std::min(std::max(zeros, 1), multiplicity);
  cfg.rank = 4 - zeros;
  int pos = 0, neg = 0;
  for (int i = zeros; i < 4; ++i) (sigma(order[i]) > 0.0 ? pos : neg) += 1;
  if (ch.reciprocal && x >= 0.0) std::swap(pos, neg);
  cfg.positive = pos;
  cfg.negative = neg;

  if (!multiple) {
    cfg.kind = TangencyKind::None;
    return cfg;
  }
  switch (cfg.rank) {
    case 3:
      cfg.kind = TangencyKind::SinglePoint;
      break;
    case 2:
      cfg.kind = TangencyKind::TwoPointsOrLine;
      break;
    case 1:
      cfg.kind = TangencyKind::Conic;
      break;
    default:
      cfg.kind = TangencyKind::Coincident;
      return cfg;  // the same surface: neither a contact nor genuine
  }

  // The Procedure of §6.3.2 (with the corrections of the header, items 1 and 2).
  const bool semidefinite = pos == 0 || neg == 0;
  if (n % 2 == 0) {
    if (!cfg.ellipsoid_after) {
      cfg.genuine = false;  // hyperboloids on both sides
    } else {
      cfg.genuine = !(n == 4 && !semidefinite);  // ellipsoids on both sides; Case 27 is not genuine
    }
  } else {
    cfg.genuine = cfg.rank != 3 && semidefinite;  // Case 11 (rank 3), 21 (indefinite), 22
  }

  Eigen::MatrixXd N(4, zeros);
  for (int i = 0; i < zeros; ++i) N.col(i) = vectors.col(order[i]);
  contactPoints(ch.X, N, zeros == 3 && std::fabs(x) <= kRankRelative, cfg);
  return cfg;
}

}  // namespace fcl_quadric
