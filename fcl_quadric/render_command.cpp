#include "fcl_quadric/render_command.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include <cairo.h>
#include <Eigen/Eigenvalues>

#include "fcl_quadric/check_command.h"
#include "fcl_quadric/picture.h"
#include "fcl_quadric/geometry/separating_plane.h"

namespace fcl_quadric {
namespace cli {

namespace {

// --- Layout (pixels) ---------------------------------------------------------------------------
constexpr int kPanel3 = 400;   // side of a view panel, 3D scenes
constexpr int kPanel2 = 560;   // side of the one panel of a planar scene
constexpr int kMarginX = 64;   // left/right margin (room for the tick labels of the v axis)
constexpr int kGap = 64;       // between panels
constexpr int kHeaderHeight = 96;  // title, subtitle and panel titles
constexpr int kFooterHeight = 96;  // tick labels of the u axis and the legend

constexpr Rgb kCollideFill{0.90, 0.16, 0.14};
constexpr Rgb kCollideLine{0.62, 0.05, 0.04};
constexpr std::array<Rgb, 5> kPalette{{{0.20, 0.45, 0.78}, {0.10, 0.58, 0.55}, {0.46, 0.36, 0.72},
                                       {0.30, 0.56, 0.22}, {0.40, 0.45, 0.55}}};
constexpr Rgb kPlaneColour{0.05, 0.50, 0.25};

/// An orthographic view: world axes u (right) and v (up).
struct View {
  int u, v;
  const char* title;
};
constexpr std::array<View, 3> kViews3{{{0, 1, "Top view (XY)"}, {0, 2, "Front view (XZ)"}, {1, 2, "Side view (YZ)"}}};
constexpr std::array<View, 1> kViews2{{{0, 1, "Plane (XY)"}}};
constexpr const char* kAxisNames[3] = {"x", "y", "z"};

/// A view panel on the surface: world (u, v) -> pixels.
struct Panel {
  View view;
  double x0, y0, size;  // pixel rectangle
  double cu, cv;        // world point at the panel centre
  double scale;         // pixels per unit
  double px(double u) const { return x0 + 0.5 * size + scale * (u - cu); }
  double py(double v) const { return y0 + 0.5 * size - scale * (v - cv); }
  double px(const Eigen::Vector3d& p) const { return px(p[view.u]); }
  double py(const Eigen::Vector3d& p) const { return py(p[view.v]); }
  void clip(cairo_t* cr) const {
    cairo_rectangle(cr, x0, y0, size, size);
    cairo_clip(cr);
  }
};

// --- Per-object geometry in a view ---------------------------------------------------------------

bool isHalfspace(const SceneObject& o) { return o.shape.type == ShapeType::Halfspace || (o.shape.region && !o.shape.box); }

/// World-space corners of the object's box (a box shape, or a quadric shape's local AABB).
std::vector<Eigen::Vector3d> boxCorners(const SceneObject& o) {
  Eigen::Vector3d lo, hi;
  if (o.shape.type == ShapeType::Box) {
    hi = 0.5 * o.shape.dimensions;
    lo = -hi;
  } else {
    lo = o.shape.box->lo;
    hi = o.shape.box->hi;
  }
  std::vector<Eigen::Vector3d> corners;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d c((k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2]);
    corners.push_back(o.pose * c);
  }
  return corners;
}

/// Convex hull (Andrew's monotone chain) of 2D points, counter-clockwise.
std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]);
  });
  if (p.size() < 3) return p;
  std::vector<Eigen::Vector2d> h(2 * p.size());
  std::size_t k = 0;
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o)[0] * (b - o)[1] - (a - o)[1] * (b - o)[0];
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

/// The half-space n.x <= d of a half-space object, in world coordinates.
std::optional<std::pair<Eigen::Vector3d, double>> worldHalfspace(const SceneObject& o) {
  if (!o.shape.region) return std::nullopt;
  const QuadricRegion w = o.shape.region->transformed(o.pose.linear(), o.pose.translation());
  const std::vector<Eigen::Matrix4d> atoms = w.signedAtoms();
  if (atoms.size() != 1 || atoms[0].topLeftCorner<3, 3>().norm() > 1e-12) return std::nullopt;
  // X^T Q X = 2 q.x + Q33 <= 0 with q = Q(0:3, 3).
  const Eigen::Vector3d q = atoms[0].topRightCorner<3, 1>();
  const double nq = q.norm();
  if (!(nq > 0.0)) return std::nullopt;
  return std::make_pair(Eigen::Vector3d(q / nq), -atoms[0](3, 3) / (2.0 * nq));
}

/// World AABB of a bounded object (none for a half-space).
std::optional<Box3> worldBounds(const SceneObject& o) {
  if (isEllipsoidal(o.shape)) {
    const Eigen::Matrix3d M = o.pose.linear() * o.shape.dimensions.asDiagonal();
    const Eigen::Vector3d half = (M * M.transpose()).diagonal().cwiseSqrt();
    return Box3{o.pose.translation() - half, o.pose.translation() + half};
  }
  if (o.shape.type == ShapeType::Box || o.shape.box) {
    Box3 b{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
           Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
    for (const Eigen::Vector3d& c : boxCorners(o)) {
      b.lo = b.lo.cwiseMin(c);
      b.hi = b.hi.cwiseMax(c);
    }
    return b;
  }
  return std::nullopt;
}

bool isCylinder(const Shape& shape) {
  return shape.type == ShapeType::EllipticCylinder || shape.type == ShapeType::Cylinder;
}

/// General quadrics and CSG solids (not cylinders, not half-spaces): drawn by their exact shadow,
/// computed per pixel (silhouetteMask).
bool drawnBySilhouette(const SceneObject& o) {
  return isQuadricShape(o.shape) && !isCylinder(o.shape) && !isHalfspace(o);
}

// --- Exact shadows of CSG solids of quadrics -------------------------------------------------------
//
// A pixel of a view is in the shadow of a solid iff the line through the pixel centre along the
// view axis meets the solid in a segment of positive length. Along the line X(s) = (P + s e, 1),
// each atom X^T Q X <= 0 is the quadratic a s^2 + 2 b s + c <= 0 with a = Q_ww, b = (Q X_P)_w,
// c = X_P^T Q X_P, whose solution set is found in closed form; the CSG tree then combines the
// interval sets exactly (union, intersection, difference). The only approximation is the pixel
// grid of the picture.

using Intervals = std::vector<std::pair<double, double>>;  // sorted, disjoint, closed

Intervals intersectIntervals(const Intervals& x, const Intervals& y) {
  Intervals out;
  std::size_t i = 0, j = 0;
  while (i < x.size() && j < y.size()) {
    const double lo = std::max(x[i].first, y[j].first), hi = std::min(x[i].second, y[j].second);
    if (lo <= hi) out.emplace_back(lo, hi);
    (x[i].second < y[j].second) ? ++i : ++j;
  }
  return out;
}

Intervals uniteIntervals(Intervals x, const Intervals& y) {
  x.insert(x.end(), y.begin(), y.end());
  std::sort(x.begin(), x.end());
  Intervals out;
  for (const auto& iv : x) {
    if (!out.empty() && iv.first <= out.back().second) {
      out.back().second = std::max(out.back().second, iv.second);
    } else {
      out.push_back(iv);
    }
  }
  return out;
}

/// [s0, s1] minus the open interior of y (the closure of the complement, as the regularised CSG
/// difference takes it).
Intervals complementIntervals(const Intervals& y, double s0, double s1) {
  Intervals out;
  double from = s0;
  for (const auto& iv : y) {
    if (iv.first > from) out.emplace_back(from, std::min(iv.first, s1));
    from = std::max(from, iv.second);
  }
  if (from < s1) out.emplace_back(from, s1);
  return out;
}

/// {s in [s0, s1] : a s^2 + 2 b s + c <= 0}.
Intervals quadraticIntervals(double a, double b, double c, double s0, double s1) {
  const double scale = std::fabs(a) * std::max(s0 * s0, s1 * s1) + 2.0 * std::fabs(b) * std::max(std::fabs(s0), std::fabs(s1)) +
                       std::fabs(c);
  Intervals all{{s0, s1}};
  if (!(scale > 0.0)) return all;  // the zero polynomial: 0 <= 0 everywhere
  if (std::fabs(a) * std::max(s0 * s0, s1 * s1) <= 1e-14 * scale) {  // linear: 2 b s + c <= 0
    if (std::fabs(b) * std::max(std::fabs(s0), std::fabs(s1)) <= 1e-14 * scale) return c <= 0.0 ? all : Intervals{};
    const double r = -c / (2.0 * b);
    return intersectIntervals(all, b > 0.0 ? Intervals{{-HUGE_VAL, r}} : Intervals{{r, HUGE_VAL}});
  }
  const double disc = b * b - a * c;
  if (disc < 0.0) return a > 0.0 ? Intervals{} : all;
  const double q = -(b + std::copysign(std::sqrt(disc), b));  // stable roots q / a and c / q
  double r1 = q / a, r2 = q != 0.0 ? c / q : r1;
  if (r1 > r2) std::swap(r1, r2);
  if (a > 0.0) return intersectIntervals(all, Intervals{{r1, r2}});
  return intersectIntervals(all, Intervals{{-HUGE_VAL, r1}, {r2, HUGE_VAL}});
}

/// The parameters s in [s0, s1] where X(s) = (P + s e_axis, 1) is in the region (world frame).
Intervals regionIntervals(const QuadricRegion& r, const Eigen::Vector3d& P, int axis, double s0, double s1) {
  switch (r.op()) {
    case QuadricRegion::Op::Atom: {
      const Eigen::Matrix4d& Q = r.matrix();
      const Eigen::Vector4d X(P[0], P[1], P[2], 1.0);
      const Eigen::Vector4d QX = Q * X;
      return quadraticIntervals(Q(axis, axis), QX[axis], X.dot(QX), s0, s1);
    }
    case QuadricRegion::Op::Union: {
      Intervals out;
      for (const QuadricRegion& c : r.children()) out = uniteIntervals(std::move(out), regionIntervals(c, P, axis, s0, s1));
      return out;
    }
    case QuadricRegion::Op::Intersection: {
      Intervals out{{s0, s1}};
      for (const QuadricRegion& c : r.children()) {
        out = intersectIntervals(out, regionIntervals(c, P, axis, s0, s1));
        if (out.empty()) break;
      }
      return out;
    }
    case QuadricRegion::Op::Difference: {
      Intervals out = regionIntervals(r.children().front(), P, axis, s0, s1);
      for (std::size_t k = 1; k < r.children().size() && !out.empty(); ++k) {
        out = intersectIntervals(out, complementIntervals(regionIntervals(r.children()[k], P, axis, s0, s1), s0, s1));
      }
      return out;
    }
  }
  return {};
}

/// The pixels of a panel in the shadow of a quadric / CSG object: mask[row][col] over the pixel
/// rectangle [x, x + cols) x [y, y + rows) (device coordinates) covering the object's world box.
struct SilhouetteMask {
  int x = 0, y = 0, cols = 0, rows = 0;
  std::vector<char> in;
  bool at(int c, int r) const { return c >= 0 && r >= 0 && c < cols && r < rows && in[static_cast<std::size_t>(r * cols + c)]; }
};

SilhouetteMask silhouetteMask(const Panel& panel, const SceneObject& o) {
  SilhouetteMask m;
  const std::vector<Eigen::Vector3d> corners = boxCorners(o);
  Eigen::Vector3d lo = corners.front(), hi = corners.front();
  for (const Eigen::Vector3d& c : corners) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const int u = panel.view.u, v = panel.view.v, w = 3 - u - v;
  // Pixel range of the box, clipped to the panel.
  const double left = std::max(panel.x0, std::floor(panel.px(lo[u]))), right = std::min(panel.x0 + panel.size, std::ceil(panel.px(hi[u])));
  const double top = std::max(panel.y0, std::floor(panel.py(hi[v]))), bottom = std::min(panel.y0 + panel.size, std::ceil(panel.py(lo[v])));
  if (!(right > left) || !(bottom > top)) return m;
  m.x = static_cast<int>(left);
  m.y = static_cast<int>(top);
  m.cols = static_cast<int>(right - left);
  m.rows = static_cast<int>(bottom - top);
  m.in.assign(static_cast<std::size_t>(m.cols) * static_cast<std::size_t>(m.rows), 0);
  const QuadricRegion world = o.shape.region->transformed(o.pose.linear(), o.pose.translation());
  const double min_length = 1e-9 * (hi - lo).maxCoeff();
  for (int r = 0; r < m.rows; ++r) {
    for (int c = 0; c < m.cols; ++c) {
      Eigen::Vector3d P = Eigen::Vector3d::Zero();
      P[u] = panel.cu + (m.x + c + 0.5 - panel.x0 - 0.5 * panel.size) / panel.scale;
      P[v] = panel.cv - (m.y + r + 0.5 - panel.y0 - 0.5 * panel.size) / panel.scale;
      bool hit = false;
      for (const auto& iv : regionIntervals(world, P, w, lo[w], hi[w])) hit = hit || iv.second - iv.first > min_length;
      m.in[static_cast<std::size_t>(r * m.cols + c)] = hit;
    }
  }
  return m;
}

/// Appends the mask to the path: its pixels as row runs (fill) or the edges between inside and
/// outside pixels, merged into maximal segments (outline).
void maskPath(cairo_t* cr, const SilhouetteMask& m, bool outline) {
  if (!outline) {
    for (int r = 0; r < m.rows; ++r) {
      for (int c = 0; c < m.cols;) {
        if (!m.at(c, r)) {
          ++c;
          continue;
        }
        int e = c;
        while (m.at(e, r)) ++e;
        cairo_rectangle(cr, m.x + c, m.y + r, e - c, 1.0);
        c = e;
      }
    }
    return;
  }
  // Horizontal edges: between rows r - 1 and r; vertical edges: between columns c - 1 and c.
  for (int r = 0; r <= m.rows; ++r) {
    for (int c = 0; c < m.cols;) {
      if (m.at(c, r - 1) == m.at(c, r)) {
        ++c;
        continue;
      }
      int e = c;
      while (e < m.cols && m.at(e, r - 1) != m.at(e, r)) ++e;
      cairo_move_to(cr, m.x + c, m.y + r);
      cairo_line_to(cr, m.x + e, m.y + r);
      c = e;
    }
  }
  for (int c = 0; c <= m.cols; ++c) {
    for (int r = 0; r < m.rows;) {
      if (m.at(c - 1, r) == m.at(c, r)) {
        ++r;
        continue;
      }
      int e = r;
      while (e < m.rows && m.at(c - 1, e) != m.at(c, e)) ++e;
      cairo_move_to(cr, m.x + c, m.y + r);
      cairo_line_to(cr, m.x + c, m.y + e);
      r = e;
    }
  }
}

/// Appends the object's outline in the panel to the current path (device coordinates).
/// Returns false when the object has no outline in this view (half-spaces).
bool outlinePath(cairo_t* cr, const Panel& panel, const SceneObject& o) {
  const int u = panel.view.u, v = panel.view.v;
  if (isEllipsoidal(o.shape)) {
    // The shadow of {p + M w : |w| <= 1} on the (u, v) plane is the ellipse with shape matrix
    // K = [M M^T]_(u,v) (2x2 block): boundary c + V diag(sqrt(lambda)) (cos s, sin s).
    const Eigen::Matrix3d M = o.pose.linear() * o.shape.dimensions.asDiagonal();
    const Eigen::Matrix3d MMt = M * M.transpose();
    Eigen::Matrix2d K;
    K << MMt(u, u), MMt(u, v), MMt(v, u), MMt(v, v);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(K);
    const Eigen::Vector2d l = eig.eigenvalues().cwiseMax(1e-18).cwiseSqrt();
    const Eigen::Matrix2d A = eig.eigenvectors() * l.asDiagonal();
    cairo_matrix_t m;
    cairo_matrix_init(&m, panel.scale * A(0, 0), -panel.scale * A(1, 0), panel.scale * A(0, 1),
                      -panel.scale * A(1, 1), panel.px(o.pose.translation()), panel.py(o.pose.translation()));
    cairo_save(cr);
    cairo_transform(cr, &m);
    cairo_new_sub_path(cr);
    cairo_arc(cr, 0.0, 0.0, 1.0, 0.0, 2.0 * M_PI);
    cairo_close_path(cr);
    cairo_restore(cr);
    return true;
  }
  if (isCylinder(o.shape)) {
    // A capped (elliptic) cylinder is the convex hull of its two end ellipses, so its shadow is the
    // hull of theirs: both cap boundaries, finely sampled (256 points each), then the hull.
    const double a = o.shape.dimensions[0], b = o.shape.dimensions[1], h = 0.5 * o.shape.dimensions[2];
    std::vector<Eigen::Vector2d> pts;
    constexpr int kSamples = 256;
    for (int k = 0; k < kSamples; ++k) {
      const double s = 2.0 * M_PI * k / kSamples;
      for (const double z : {-h, h}) {
        const Eigen::Vector3d c = o.pose * Eigen::Vector3d(a * std::cos(s), b * std::sin(s), z);
        pts.emplace_back(panel.px(c), panel.py(c));
      }
    }
    const std::vector<Eigen::Vector2d> hull = convexHull(pts);
    cairo_new_sub_path(cr);
    for (const Eigen::Vector2d& q : hull) cairo_line_to(cr, q[0], q[1]);
    cairo_close_path(cr);
    return true;
  }
  if (o.shape.type == ShapeType::Box) {  // quadric / CSG solids: silhouetteMask
    std::vector<Eigen::Vector2d> pts;
    for (const Eigen::Vector3d& c : boxCorners(o)) pts.emplace_back(panel.px(c), panel.py(c));
    const std::vector<Eigen::Vector2d> hull = convexHull(pts);
    cairo_new_sub_path(cr);
    for (const Eigen::Vector2d& q : hull) cairo_line_to(cr, q[0], q[1]);
    cairo_close_path(cr);
    return true;
  }
  return false;
}

/// The line {(a, b) : n_u a + n_v b = d'} clipped to the panel as a long segment, if the plane
/// n.x = d is not parallel to the view plane; `depth` is the world coordinate along the view axis
/// at which the trace is taken.
std::optional<std::array<Eigen::Vector2d, 2>> traceLine(const Panel& panel, const Eigen::Vector3d& n, double d,
                                                        double depth) {
  const int u = panel.view.u, v = panel.view.v, w = 3 - u - v;
  const Eigen::Vector2d n2(n[u], n[v]);
  const double len = n2.norm();
  if (len < 1e-6) return std::nullopt;
  const double d2 = d - n[w] * depth;
  const Eigen::Vector2d dir(-n2[1] / len, n2[0] / len);
  const Eigen::Vector2d foot = n2 * (d2 / (len * len));  // closest point of the line to the origin
  const Eigen::Vector2d centre(panel.cu, panel.cv);
  const Eigen::Vector2d mid = foot + dir * dir.dot(centre - foot);
  const double reach = 2.0 * panel.size / panel.scale;
  const Eigen::Vector2d a = mid - reach * dir, b = mid + reach * dir;
  return std::array<Eigen::Vector2d, 2>{Eigen::Vector2d(panel.px(a[0]), panel.py(a[1])),
                                        Eigen::Vector2d(panel.px(b[0]), panel.py(b[1]))};
}

struct PairDrawing {
  std::size_t a, b;
  PairReport report;
  std::optional<SeparatingPlane> plane;
};

struct Evaluated {
  std::vector<PairDrawing> pairs;
  std::vector<char> colliding;  // per object
  int colliding_pairs = 0;
  int separated_pairs = 0;
  int skipped_pairs = 0;
};

Evaluated evaluate(const Scene& scene, const RenderOptions& options) {
  Evaluated ev;
  ev.colliding.assign(scene.objects.size(), 0);
  for (const auto& [i, j] : scene.pairs) {
    const SceneObject& a = scene.objects.at(i);
    const SceneObject& b = scene.objects.at(j);
    PairDrawing d{i, j, PairReport{}, std::nullopt};
    try {
      d.report = evaluatePair(a, b);
    } catch (const std::invalid_argument&) {
      ++ev.skipped_pairs;  // two half-spaces: no bounded region to classify in
      continue;
    }
    if (d.report.collide) {
      ++ev.colliding_pairs;
      ev.colliding[i] = ev.colliding[j] = 1;
    } else {
      ++ev.separated_pairs;
      if (options.separation_details && isEllipsoidal(a.shape) && isEllipsoidal(b.shape)) {
        d.plane = separatingPlane(toEllipsoid(a), toEllipsoid(b));
      }
    }
    ev.pairs.push_back(std::move(d));
  }
  return ev;
}

void drawPanel(cairo_t* cr, const Panel& panel, const Scene& scene, const Evaluated& ev, const RenderOptions& options,
               const Eigen::Vector3d& scene_centre) {
  const int u = panel.view.u, v = panel.view.v, w = 3 - u - v;
  const double half_world = 0.5 * panel.size / panel.scale;
  // Background and grid.
  cairo_rectangle(cr, panel.x0, panel.y0, panel.size, panel.size);
  cairo_set_source_rgb(cr, 0.985, 0.985, 0.98);
  cairo_fill(cr);
  const double step = niceStep(2.0 * half_world / 8.0);
  setFont(cr, 10.5);
  cairo_set_line_width(cr, 1.0);
  for (int axis = 0; axis < 2; ++axis) {
    const double c = axis == 0 ? panel.cu : panel.cv;
    for (double g = std::ceil((c - half_world) / step) * step; g <= c + half_world + 1e-9 * step; g += step) {
      const bool zero = std::fabs(g) < 1e-9 * step;
      cairo_set_source_rgb(cr, zero ? 0.55 : 0.86, zero ? 0.55 : 0.86, zero ? 0.58 : 0.88);
      cairo_set_line_width(cr, zero ? 1.3 : 0.8);
      if (axis == 0) {
        const double x = std::round(panel.px(g)) + 0.5;
        cairo_move_to(cr, x, panel.y0);
        cairo_line_to(cr, x, panel.y0 + panel.size);
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0.35, 0.35, 0.38);
        text(cr, formatNumber(g), x, panel.y0 + panel.size + 14, 0.5);
      } else {
        const double y = std::round(panel.py(g)) + 0.5;
        cairo_move_to(cr, panel.x0, y);
        cairo_line_to(cr, panel.x0 + panel.size, y);
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0.35, 0.35, 0.38);
        text(cr, formatNumber(g), panel.x0 - 5, y + 3.5, 1.0);
      }
    }
  }
  // Axis names and panel title.
  setFont(cr, 12, true);
  setColour(cr, kText);
  text(cr, std::string(kAxisNames[u]) + " \u2192", panel.x0 + panel.size, panel.y0 + panel.size + 30, 1.0);
  text(cr, std::string(kAxisNames[v]) + " \u2191", panel.x0 - 5, panel.y0 - 6, 1.0);
  setFont(cr, 14, true);
  text(cr, panel.view.title, panel.x0 + 0.5 * panel.size, panel.y0 - 8, 0.5);

  cairo_save(cr);
  panel.clip(cr);
  // Half-spaces: shaded side and boundary trace.
  for (std::size_t k = 0; k < scene.objects.size(); ++k) {
    const SceneObject& o = scene.objects[k];
    if (!isHalfspace(o)) continue;
    const auto hs = worldHalfspace(o);
    if (!hs) continue;
    const auto line = traceLine(panel, hs->first, hs->second, scene_centre[w]);
    if (!line) continue;
    const Eigen::Vector2d n_px(hs->first[u], -hs->first[v]);  // outward normal in pixels
    const Eigen::Vector2d back = -3.0 * panel.size * n_px.normalized();
    cairo_move_to(cr, (*line)[0][0], (*line)[0][1]);
    cairo_line_to(cr, (*line)[1][0], (*line)[1][1]);
    cairo_line_to(cr, (*line)[1][0] + back[0], (*line)[1][1] + back[1]);
    cairo_line_to(cr, (*line)[0][0] + back[0], (*line)[0][1] + back[1]);
    cairo_close_path(cr);
    const Rgb c = ev.colliding[k] ? kCollideFill : Rgb{0.55, 0.45, 0.30};
    setColour(cr, c, 0.13);
    cairo_fill(cr);
    cairo_move_to(cr, (*line)[0][0], (*line)[0][1]);
    cairo_line_to(cr, (*line)[1][0], (*line)[1][1]);
    setColour(cr, ev.colliding[k] ? kCollideLine : Rgb{0.45, 0.35, 0.22});
    cairo_set_line_width(cr, 2.0);
    cairo_stroke(cr);
    // Its name just inside, near the point of the boundary closest to the panel centre.
    const Eigen::Vector2d a = (*line)[0], b = (*line)[1];
    const Eigen::Vector2d mid_px(panel.x0 + 0.5 * panel.size, panel.y0 + 0.5 * panel.size);
    const Eigen::Vector2d foot = a + (b - a) * std::clamp((mid_px - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    const Eigen::Vector2d at = foot - 16.0 * n_px.normalized() + Eigen::Vector2d(-0.3 * panel.size, 4.0);
    if (at[0] > panel.x0 && at[0] < panel.x0 + panel.size && at[1] > panel.y0 && at[1] < panel.y0 + panel.size) {
      setFont(cr, 12, true);
      haloText(cr, o.name + " (half-space)", std::max(at[0], panel.x0 + 6.0), at[1],
               ev.colliding[k] ? kCollideLine : Rgb{0.45, 0.35, 0.22});
    }
  }
  // Fills, then outlines (so every outline stays visible through the translucent fills). The
  // shadows of quadric / CSG solids are computed once per panel.
  std::vector<std::optional<SilhouetteMask>> masks(scene.objects.size());
  for (std::size_t k = 0; k < scene.objects.size(); ++k) {
    if (drawnBySilhouette(scene.objects[k])) masks[k] = silhouetteMask(panel, scene.objects[k]);
  }
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t k = 0; k < scene.objects.size(); ++k) {
      const SceneObject& o = scene.objects[k];
      const bool hot = ev.colliding[k] != 0;
      const Rgb fill = hot ? kCollideFill : kPalette[k % kPalette.size()];
      const Rgb line = hot ? kCollideLine : Rgb{0.6 * fill.r, 0.6 * fill.g, 0.6 * fill.b};
      cairo_new_path(cr);
      if (masks[k]) {
        maskPath(cr, *masks[k], pass == 1);
      } else if (!outlinePath(cr, panel, o)) {
        continue;
      }
      if (pass == 0) {
        setColour(cr, fill, hot ? 0.38 : 0.28);
        cairo_fill(cr);
      } else {
        setColour(cr, line);
        cairo_set_line_width(cr, hot ? 2.2 : 1.6);
        cairo_stroke(cr);
      }
    }
  }
  // Separating planes (trace through the midpoint of the two tangent points) and witness segments.
  for (const PairDrawing& d : ev.pairs) {
    if (!d.plane) continue;
    const Eigen::Vector3d mid = 0.5 * (d.plane->tangent_a + d.plane->tangent_b);
    const auto line = traceLine(panel, d.plane->plane.normal, d.plane->plane.offset, mid[w]);
    if (!line) continue;
    const double dash[] = {8.0, 5.0};
    cairo_set_dash(cr, dash, 2, 0.0);
    setColour(cr, kPlaneColour, 0.8);
    cairo_set_line_width(cr, 1.4);
    cairo_move_to(cr, (*line)[0][0], (*line)[0][1]);
    cairo_line_to(cr, (*line)[1][0], (*line)[1][1]);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0.0);
  }
  for (const PairDrawing& d : ev.pairs) {
    const PairReport& r = d.report;
    if (!r.point_a.allFinite() || !r.point_b.allFinite()) continue;
    if (!r.collide) {
      if (!options.separation_details || r.method == PairMethod::QuadricRegion) continue;
      // Witness points of the distance, joined by a dotted segment.
      const double dots[] = {2.0, 3.0};
      cairo_set_dash(cr, dots, 2, 0.0);
      cairo_set_source_rgba(cr, 0.25, 0.25, 0.3, 0.8);
      cairo_set_line_width(cr, 1.2);
      cairo_move_to(cr, panel.px(r.point_a), panel.py(r.point_a));
      cairo_line_to(cr, panel.px(r.point_b), panel.py(r.point_b));
      cairo_stroke(cr);
      cairo_set_dash(cr, nullptr, 0, 0.0);
      for (const Eigen::Vector3d& p : {r.point_a, r.point_b}) {
        cairo_arc(cr, panel.px(p), panel.py(p), 3.0, 0.0, 2.0 * M_PI);
        cairo_set_source_rgb(cr, 1, 1, 1);
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, 0.25, 0.25, 0.3);
        cairo_set_line_width(cr, 1.3);
        cairo_stroke(cr);
      }
    } else {
      // Contact: the witness points (deepest points for an overlap), yellow with a dark rim.
      for (const Eigen::Vector3d& p : {r.point_a, r.point_b}) {
        cairo_arc(cr, panel.px(p), panel.py(p), 4.0, 0.0, 2.0 * M_PI);
        cairo_set_source_rgb(cr, 1.0, 0.85, 0.1);
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, 0.2, 0.1, 0.0);
        cairo_set_line_width(cr, 1.3);
        cairo_stroke(cr);
      }
    }
  }
  // Labels: just above the object's centre (half-spaces: not labelled here), nudged down when
  // they would overlap a label already placed.
  setFont(cr, 12, true);
  std::vector<std::array<double, 4>> placed;
  for (std::size_t k = 0; k < scene.objects.size(); ++k) {
    const SceneObject& o = scene.objects[k];
    if (isHalfspace(o)) continue;
    const std::string& label = o.name;
    cairo_text_extents_t e;
    cairo_text_extents(cr, label.c_str(), &e);
    double x = panel.px(o.pose.translation()) - 0.5 * e.x_advance;
    double y = panel.py(o.pose.translation()) - 7.0;
    for (int tries = 0; tries < 8; ++tries) {
      bool clash = false;
      for (const auto& r : placed) {
        clash = clash || (x < r[0] + r[2] && r[0] < x + e.x_advance && y - 12 < r[1] && r[1] - 12 < y);
      }
      if (!clash) break;
      y += 15.0;
    }
    placed.push_back({x, y, e.x_advance, 12});
    haloText(cr, label, x, y, ev.colliding[k] ? kCollideLine : kText);
  }
  cairo_restore(cr);
  cairo_rectangle(cr, panel.x0 + 0.5, panel.y0 + 0.5, panel.size - 1, panel.size - 1);
  cairo_set_source_rgb(cr, 0.55, 0.55, 0.58);
  cairo_set_line_width(cr, 1.0);
  cairo_stroke(cr);
}

/// The legend: items left to right, wrapping onto a second row at `right`.
void drawLegend(cairo_t* cr, double x0, double y, double right, bool details) {
  setFont(cr, 12);
  double x = x0;
  // Each item: a symbol of width `symbol` drawn at (x, y) and its label.
  auto item = [&](double symbol, const char* label, auto&& draw_symbol) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, label, &e);
    if (x > x0 && x + symbol + 6 + e.x_advance > right) {
      x = x0;
      y += 20;
    }
    cairo_new_path(cr);
    draw_symbol(x, y);
    cairo_new_path(cr);
    setColour(cr, kText);
    text(cr, label, x + symbol + 6, y);
    x += symbol + 6 + e.x_advance + 24;
  };
  auto swatch = [&](const Rgb& c) {
    return [&cr, c](double sx, double sy) {
      cairo_rectangle(cr, sx, sy - 10, 18, 12);
      setColour(cr, c, 0.35);
      cairo_fill_preserve(cr);
      setColour(cr, {0.6 * c.r, 0.6 * c.g, 0.6 * c.b});
      cairo_set_line_width(cr, 1.5);
      cairo_stroke(cr);
    };
  };
  auto segment = [&cr](const Rgb& c, const double* dash, double width) {
    return [&cr, c, dash, width](double sx, double sy) {
      cairo_set_dash(cr, dash, 2, 0.0);
      setColour(cr, c);
      cairo_set_line_width(cr, width);
      cairo_move_to(cr, sx, sy - 4);
      cairo_line_to(cr, sx + 28, sy - 4);
      cairo_stroke(cr);
      cairo_set_dash(cr, nullptr, 0, 0.0);
    };
  };
  item(18, "colliding (touching or overlapping)", swatch(kCollideFill));
  item(18, "free (a colour per object)", swatch(kPalette[0]));
  item(10, "contact witness points", [&cr](double sx, double sy) {
    cairo_arc(cr, sx + 5, sy - 4, 4.0, 0.0, 2.0 * M_PI);
    cairo_set_source_rgb(cr, 1.0, 0.85, 0.1);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.2, 0.1, 0.0);
    cairo_set_line_width(cr, 1.3);
    cairo_stroke(cr);
  });
  static const double kPlaneDash[] = {8.0, 5.0};
  static const double kDots[] = {2.0, 3.0};
  if (details) {
    item(28, "separating plane (trace)", segment(kPlaneColour, kPlaneDash, 1.4));
    item(28, "closest points", segment({0.25, 0.25, 0.3}, kDots, 1.2));
  }
}

/// The view panels of a scene: one scale for all views (so sizes compare across them), each view
/// centred on the bounds of the bounded objects, 10% padding.
std::vector<Panel> layoutPanels(const Scene& scene) {
  const bool planar = scene.dimension == 2;
  const int panel_size = planar ? kPanel2 : kPanel3;
  const std::vector<View> views = planar ? std::vector<View>(kViews2.begin(), kViews2.end())
                                         : std::vector<View>(kViews3.begin(), kViews3.end());
  Box3 bounds{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
              Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
  for (const SceneObject& o : scene.objects) {
    if (const auto b = worldBounds(o)) {
      bounds.lo = bounds.lo.cwiseMin(b->lo);
      bounds.hi = bounds.hi.cwiseMax(b->hi);
    }
  }
  if (bounds.empty()) bounds = Box3{Eigen::Vector3d::Constant(-1.0), Eigen::Vector3d::Constant(1.0)};
  const Eigen::Vector3d centre = bounds.center();
  const Eigen::Vector3d half = (0.5 * (bounds.hi - bounds.lo)).cwiseMax(1e-3 * (bounds.hi - bounds.lo).maxCoeff() + 1e-9);
  double scale = std::numeric_limits<double>::infinity();
  for (const View& view : views) {
    scale = std::min(scale, 0.5 * panel_size / (1.1 * std::max(half[view.u], half[view.v])));
  }
  std::vector<Panel> panels;
  for (std::size_t k = 0; k < views.size(); ++k) {
    panels.push_back(Panel{views[k], static_cast<double>(kMarginX + static_cast<int>(k) * (panel_size + kGap)),
                           static_cast<double>(kHeaderHeight), static_cast<double>(panel_size), centre[views[k].u],
                           centre[views[k].v], scale});
  }
  return panels;
}

void draw(cairo_t* cr, const Scene& scene, const RenderOptions& options) {
  const ImageSize size = renderImageSize(scene.dimension);
  const bool planar = scene.dimension == 2;
  const Evaluated ev = evaluate(scene, options);
  const std::vector<Panel> panels = layoutPanels(scene);
  // Depth at which half-space traces are taken: the middle of the drawn region.
  const Eigen::Vector3d centre(panels[0].cu, panels[0].cv, planar ? 0.0 : panels[1].cv);

  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  setFont(cr, 19, true);
  setColour(cr, kText);
  char time_text[64];
  std::snprintf(time_text, sizeof time_text, "t = %g", options.time);
  text(cr, options.title + "   \u00b7   " + (options.time_text.empty() ? std::string(time_text) : options.time_text),
       kMarginX, 32);
  setFont(cr, 13);
  cairo_set_source_rgb(cr, 0.35, 0.35, 0.38);
  std::string subtitle = std::to_string(scene.objects.size()) + " objects, " + std::to_string(ev.pairs.size()) +
                         " pairs classified exactly: " + std::to_string(ev.colliding_pairs) + " colliding, " +
                         std::to_string(ev.separated_pairs) + " separated";
  if (ev.skipped_pairs > 0) subtitle += ", " + std::to_string(ev.skipped_pairs) + " not classified (two half-spaces)";
  if (planar) subtitle += "  (planar scene)";
  if (!options.pairs_note.empty()) subtitle += "  " + options.pairs_note;
  text(cr, subtitle, kMarginX, 54);

  for (const Panel& panel : panels) drawPanel(cr, panel, scene, ev, options, centre);
  drawLegend(cr, kMarginX, size.height - 42, size.width - kMarginX, options.separation_details);
}

}  // namespace

Eigen::Vector2d pixelOf(const Scene& scene, int view, const Eigen::Vector3d& world) {
  const std::vector<Panel> panels = layoutPanels(scene);
  const Panel& panel = panels.at(static_cast<std::size_t>(view));
  return Eigen::Vector2d(panel.px(world), panel.py(world));
}

ImageSize renderImageSize(int dimension) {
  if (dimension == 2) return {2 * kMarginX + kPanel2 + 160, kHeaderHeight + kPanel2 + kFooterHeight};
  return {2 * kMarginX + 3 * kPanel3 + 2 * kGap, kHeaderHeight + kPanel3 + kFooterHeight};
}

void renderScene(const Scene& scene, const RenderOptions& options, const std::string& path) {
  const ImageSize size = renderImageSize(scene.dimension);
  writePicture(path, size.width, size.height, [&](cairo_t* cr) { draw(cr, scene, options); });
}

void runRender(const std::string& scene_path, const std::string& output, double time) {
  requirePictureFile(output);
  if (!std::isfinite(time) || time < 0.0 || time > 1.0) {
    throw SceneError("", "--time must be a number in [0, 1], got " + formatNumber(time));
  }
  const Scene scene = sceneAtTime(readSceneFile(scene_path), time);
  RenderOptions options;
  const std::size_t slash = scene_path.find_last_of('/');
  options.title = slash == std::string::npos ? scene_path : scene_path.substr(slash + 1);
  options.time = time;
  renderScene(scene, options, output);
}

Scene ellipsoidScene(const std::vector<Ellipsoid>& ellipsoids) {
  Scene scene;
  const int n = static_cast<int>(ellipsoids.size());
  for (int k = 0; k < n; ++k) {
    const Ellipsoid& e = ellipsoids[static_cast<std::size_t>(k)];
    SceneObject o;
    int digits = 1;
    for (int m = n - 1; m >= 10; m /= 10) ++digits;
    std::string number = std::to_string(k);
    number.insert(0, static_cast<std::size_t>(std::max(0, digits - static_cast<int>(number.size()))), '0');
    o.name = "E" + number;
    o.shape.type = ShapeType::Ellipsoid;
    o.shape.dimensions = e.radii();
    o.pose.linear() = e.rotation();
    o.pose.translation() = e.center();
    scene.objects.push_back(std::move(o));
  }
  for (std::size_t a = 0; a < ellipsoids.size(); ++a) {
    for (std::size_t b = a + 1; b < ellipsoids.size(); ++b) {
      const double reach = ellipsoids[a].maxRadius() + ellipsoids[b].maxRadius();
      if ((ellipsoids[b].center() - ellipsoids[a].center()).squaredNorm() <= reach * reach) scene.pairs.emplace_back(a, b);
    }
  }
  return scene;
}

std::string writeDemoPictures(const DemoSummary& summary, const std::string& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw SceneError("", "cannot create the pictures directory " + directory + ": " + ec.message());
  const std::filesystem::path dir(directory);
  RenderOptions options;
  options.separation_details = false;  // dozens of pairs: planes would only clutter the picture
  const double frame_time = 1.0 / 60.0;
  const std::pair<const std::vector<Ellipsoid>*, const char*> frames[] = {{&summary.first_frame, "demo_first_frame.png"},
                                                                          {&summary.last_frame, "demo_last_frame.png"}};
  for (std::size_t k = 0; k < 2; ++k) {
    const int frame = k == 0 ? 0 : summary.options.frames - 1;
    options.title = "fcl_quadric demo, frame " + std::to_string(frame);
    options.time = frame * frame_time;
    char seconds[64];
    std::snprintf(seconds, sizeof seconds, "%.2f s simulated", options.time);
    options.time_text = seconds;
    options.pairs_note = "(the pairs whose bounding spheres overlap, as in the demo)";
    renderScene(ellipsoidScene(*frames[k].first), options, (dir / frames[k].second).string());
  }
  return (dir / "demo_first_frame.png").string() + ", " + (dir / "demo_last_frame.png").string();
}

}  // namespace cli
}  // namespace fcl_quadric
