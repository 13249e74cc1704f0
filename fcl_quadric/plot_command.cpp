#include "fcl_quadric/plot_command.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include <cairo.h>

#include "fcl_quadric/algebra/root_isolation.h"
#include "fcl_quadric/ccd_command.h"
#include "fcl_quadric/example_scenes.h"
#include "fcl_quadric/picture.h"

namespace fcl_quadric {
namespace cli {

namespace {

// --- Sampling ------------------------------------------------------------------------------------

const CcdFunctionSegment& segmentAt(const std::vector<CcdFunctionSegment>& segments, double t) {
  if (segments.empty()) throw std::invalid_argument("ccdFunctionValue: no segments");
  for (const CcdFunctionSegment& s : segments) {
    if (t < s.t_end) return s;
  }
  return segments.back();
}

double localTime(const CcdFunctionSegment& s, double t) { return (t - s.t_begin) / (s.t_end - s.t_begin); }

/// The u in [0, 1] maximising u -> F(u, s) (a quartic): a scan, then golden-section refinement.
double maximisingU(const BivariateBernstein& F, double s) {
  const BernsteinPolynomial row = F.atT(s);
  constexpr int kScan = 400;
  int best = 0;
  double best_value = row.evaluate(0.0);
  for (int i = 1; i <= kScan; ++i) {
    const double v = row.evaluate(static_cast<double>(i) / kScan);
    if (v > best_value) {
      best_value = v;
      best = i;
    }
  }
  double lo = std::max(0.0, (best - 1.0) / kScan), hi = std::min(1.0, (best + 1.0) / kScan);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int k = 0; k < 60; ++k) {
    const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    if (row.evaluate(x1) < row.evaluate(x2)) {
      lo = x1;
    } else {
      hi = x2;
    }
  }
  return 0.5 * (lo + hi);
}

/// Marching squares on one segment's grid, padded by a frame of negative nodes one cell outside
/// [0, 1]^2 so that every outline of {F > 0} closes.
class MarchingSquares {
 public:
  MarchingSquares(const CcdFunctionSegment& segment, const CcdFunctionGrid& grid, std::size_t index)
      : seg_(segment), grid_(grid), index_(index) {}

  void run(CcdFunctionPlot* plot) {
    const int nu = grid_.nu, nt = grid_.nt;
    for (int cj = -1; cj <= nt; ++cj) {
      for (int ci = -1; ci <= nu; ++ci) cell(ci, cj);
    }
    // Link the segments into closed loops through their shared edges.
    std::unordered_map<long long, std::array<int, 2>> incident;
    for (int k = 0; k < static_cast<int>(segments_.size()); ++k) {
      for (long long e : {segments_[k].e0, segments_[k].e1}) {
        auto it = incident.find(e);
        if (it == incident.end()) {
          incident.emplace(e, std::array<int, 2>{k, -1});
        } else {
          it->second[1] = k;
        }
      }
    }
    std::vector<char> used(segments_.size(), 0);
    for (std::size_t start = 0; start < segments_.size(); ++start) {
      if (used[start]) continue;
      // Walk: a list of (edge, segment leaving it).
      std::vector<long long> edges;
      std::vector<int> segs;
      int k = static_cast<int>(start);
      long long e = segments_[start].e0;
      while (k >= 0 && !used[static_cast<std::size_t>(k)]) {
        used[static_cast<std::size_t>(k)] = 1;
        edges.push_back(e);
        segs.push_back(k);
        const Seg& s = segments_[static_cast<std::size_t>(k)];
        e = s.e0 == e ? s.e1 : s.e0;
        const std::array<int, 2>& next = incident.at(e);
        k = next[0] == k ? next[1] : next[0];
      }
      std::vector<Eigen::Vector2d> outline;
      for (long long edge : edges) outline.push_back(point(edge));
      plot->positive_region.push_back({index_, outline});
      // The zero set: runs of segments from real cells, starting after a padding segment if any.
      const std::size_t n = segs.size();
      std::size_t first = 0;
      for (std::size_t m = 0; m < n; ++m) {
        if (!segments_[static_cast<std::size_t>(segs[m])].real) {
          first = (m + 1) % n;
          break;
        }
      }
      std::vector<Eigen::Vector2d> run;
      for (std::size_t m = 0; m < n; ++m) {
        const std::size_t idx = (first + m) % n;
        if (segments_[static_cast<std::size_t>(segs[idx])].real) {
          if (run.empty()) run.push_back(outline[idx]);
          run.push_back(outline[(idx + 1) % n]);
        } else if (!run.empty()) {
          plot->zero_set.push_back(run);
          run.clear();
        }
      }
      if (!run.empty()) plot->zero_set.push_back(run);
    }
  }

 private:
  struct Seg {
    long long e0, e1;
    bool real;
  };

  bool isReal(int i, int j) const { return i >= 0 && i <= grid_.nu && j >= 0 && j <= grid_.nt; }
  double node(int i, int j) const { return isReal(i, j) ? grid_.value(i, j) : -1.0; }
  // Edge keys: horizontal edge from node (i, j) to (i + 1, j), vertical from (i, j) to (i, j + 1).
  long long key(int vertical, int i, int j) const {
    return 2LL * ((i + 1) + static_cast<long long>(grid_.nu + 3) * (j + 1)) + vertical;
  }

  Eigen::Vector2d nodePoint(int i, int j) const {
    return Eigen::Vector2d(static_cast<double>(i) / grid_.nu, static_cast<double>(j) / grid_.nt);
  }

  /// The crossing on an edge, in (u, global t): refined by bisection on F for edges between real
  /// nodes, linear interpolation to the padding otherwise.
  Eigen::Vector2d point(long long edge) {
    const auto cached = points_.find(edge);
    if (cached != points_.end()) return cached->second;
    const int vertical = static_cast<int>(edge % 2);
    const long long cell = edge / 2;
    const int i = static_cast<int>(cell % (grid_.nu + 3)) - 1, j = static_cast<int>(cell / (grid_.nu + 3)) - 1;
    const int i1 = i + (vertical ? 0 : 1), j1 = j + (vertical ? 1 : 0);
    Eigen::Vector2d p0 = nodePoint(i, j), p1 = nodePoint(i1, j1);
    double v0 = node(i, j);
    const double v1 = node(i1, j1);
    Eigen::Vector2d p;
    if (isReal(i, j) && isReal(i1, j1)) {
      for (int k = 0; k < 60; ++k) {
        const Eigen::Vector2d mid = 0.5 * (p0 + p1);
        const double vm = seg_.F.evaluate(mid[0], mid[1]);
        if ((vm > 0.0) == (v0 > 0.0)) {
          p0 = mid;
          v0 = vm;
        } else {
          p1 = mid;
        }
      }
      p = 0.5 * (p0 + p1);
    } else {
      p = p0 + (p1 - p0) * (v0 / (v0 - v1));  // v0, v1 of opposite signs: v0 - v1 != 0
    }
    p[1] = seg_.t_begin + (seg_.t_end - seg_.t_begin) * p[1];
    points_.emplace(edge, p);
    return p;
  }

  void cell(int ci, int cj) {
    const double c[4] = {node(ci, cj), node(ci + 1, cj), node(ci + 1, cj + 1), node(ci, cj + 1)};
    const bool in[4] = {c[0] > 0.0, c[1] > 0.0, c[2] > 0.0, c[3] > 0.0};
    // Edges: 0 bottom, 1 right, 2 top, 3 left; edge k joins corners k and k + 1.
    const long long e[4] = {key(0, ci, cj), key(1, ci + 1, cj), key(0, ci, cj + 1), key(1, ci, cj)};
    std::vector<int> cross;
    for (int k = 0; k < 4; ++k) {
      if (in[k] != in[(k + 1) % 4]) cross.push_back(k);
    }
    const bool real = ci >= 0 && ci < grid_.nu && cj >= 0 && cj < grid_.nt;
    if (cross.size() == 2) {
      segments_.push_back({e[cross[0]], e[cross[1]], real});
    } else if (cross.size() == 4) {
      // Saddle: decided by the value at the centre.
      const double centre = real ? seg_.F.evaluate((ci + 0.5) / grid_.nu, (cj + 0.5) / grid_.nt)
                                 : 0.25 * (c[0] + c[1] + c[2] + c[3]);
      if ((centre > 0.0) == in[0]) {  // corners 0 and 2 connected: cut off corners 1 and 3
        segments_.push_back({e[0], e[1], real});
        segments_.push_back({e[2], e[3], real});
      } else {  // cut off corners 0 and 2
        segments_.push_back({e[3], e[0], real});
        segments_.push_back({e[1], e[2], real});
      }
    }
  }

  const CcdFunctionSegment& seg_;
  const CcdFunctionGrid& grid_;
  std::size_t index_;
  std::vector<Seg> segments_;
  std::unordered_map<long long, Eigen::Vector2d> points_;
};

}  // namespace

double ccdFunctionValue(const std::vector<CcdFunctionSegment>& segments, double u, double t) {
  const CcdFunctionSegment& s = segmentAt(segments, t);
  return s.F.evaluate(u, localTime(s, t));
}

CcdFunctionPlot sampleCcdFunction(const MovingEllipsoid& a, const MovingEllipsoid& b, CcdInterpolation interpolation,
                                  int nu, int nt) {
  if (nu < 2 || nt < 2) throw std::invalid_argument("sampleCcdFunction: the grid needs at least 2 x 2 cells");
  CcdFunctionPlot plot;
  plot.segments = ccdFunctionSegments(a, b, interpolation);
  CcdOptions options;
  options.all_intervals = true;
  options.interpolation = interpolation;
  plot.result = continuousCollideEllipsoids(a, b, options);
  for (const CcdFunctionSegment& s : plot.segments) {
    CcdFunctionGrid grid;
    grid.t_begin = s.t_begin;
    grid.t_end = s.t_end;
    grid.nu = nu;
    grid.nt = std::max(8, static_cast<int>(std::lround(nt * (s.t_end - s.t_begin))));
    grid.values.resize(static_cast<std::size_t>((grid.nu + 1) * (grid.nt + 1)));
    for (int j = 0; j <= grid.nt; ++j) {
      const BernsteinPolynomial row = s.F.atT(static_cast<double>(j) / grid.nt);
      for (int i = 0; i <= grid.nu; ++i) {
        grid.values[static_cast<std::size_t>(i + (grid.nu + 1) * j)] = row.evaluate(static_cast<double>(i) / grid.nu);
      }
    }
    plot.grids.push_back(std::move(grid));
  }
  for (std::size_t k = 0; k < plot.segments.size(); ++k) MarchingSquares(plot.segments[k], plot.grids[k], k).run(&plot);
  for (const CcdInterval& c : plot.result.collision_intervals) {
    for (const double t : {c.begin, c.end}) {
      if (!(t > 0.0 && t < 1.0)) continue;
      if (!plot.contacts.empty() && plot.contacts.back()[1] == t) continue;
      const CcdFunctionSegment& s = segmentAt(plot.segments, t);
      plot.contacts.emplace_back(maximisingU(s.F, localTime(s, t)), t);
    }
  }
  return plot;
}

DiscriminantPlot sampleDiscriminant(const MovingEllipse2& a, const MovingEllipse2& b) {
  DiscriminantPlot plot;
  plot.delta = ellipseDiscriminant(a, b);
  plot.result = collideMovingEllipses(a, b, EllipseCcdQuery::AllContacts);
  for (const RootInterval& r : isolateRoots(plot.delta, kEllipseIsolationWidth)) {
    const bool bracket = r.kind == RootKind::Single && r.lo < r.hi;
    plot.roots.push_back(bracket ? refineRoot(plot.delta, r.lo, r.hi, kEllipseRootTolerance) : 0.5 * (r.lo + r.hi));
  }
  return plot;
}

std::pair<std::size_t, std::size_t> parsePair(const Scene& scene, const std::string& text) {
  const std::size_t comma = text.find(',');
  if (text.empty() || comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) {
    throw SceneError("", "--pair must be I,J (two object indices or names), got \"" + text + "\"");
  }
  auto object = [&](const std::string& token) -> std::size_t {
    if (!token.empty() && token.size() <= 9 && token.find_first_not_of("0123456789") == std::string::npos) {
      const std::size_t index = std::stoul(token);
      if (index >= scene.objects.size()) {
        throw SceneError("", "--pair: object index " + token + " is out of range (the scene has " +
                                 std::to_string(scene.objects.size()) + " objects, indices 0.." +
                                 std::to_string(scene.objects.size() - 1) + ")");
      }
      return index;
    }
    for (std::size_t k = 0; k < scene.objects.size(); ++k) {
      if (scene.objects[k].name == token) return k;
    }
    throw SceneError("", "--pair: no object named \"" + token + "\"");
  };
  const std::size_t i = object(text.substr(0, comma)), j = object(text.substr(comma + 1));
  if (i == j) throw SceneError("", "--pair: the two objects must differ, got \"" + text + "\"");
  return {i, j};
}

bool isMoving(const Scene& scene, std::size_t object) {
  const SceneObject& o = scene.objects.at(object);
  if (scene.dimension == 2) return o.motion2.maxDegree() > 0;
  return o.motion.has_value();
}

namespace {

// --- Drawing -------------------------------------------------------------------------------------

constexpr Rgb kPositive{0.80, 0.88, 0.97};   // F > 0: separate
constexpr Rgb kNegative{1.00, 0.95, 0.78};   // F < 0
constexpr Rgb kZeroSet{0.05, 0.20, 0.55};
constexpr Rgb kContact{0.84, 0.10, 0.08};
constexpr Rgb kCollision{0.88, 0.22, 0.16};
constexpr Rgb kMuted{0.38, 0.38, 0.42};
constexpr Rgb kFrame{0.55, 0.55, 0.58};

std::string fixed(double v, int digits = 4) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

std::string interval(double t0, double t1) {
  return t0 == t1 ? "t = " + fixed(t0) : "[" + fixed(t0) + ", " + fixed(t1) + "]";
}

void line(cairo_t* cr, double x0, double y0, double x1, double y1) {
  cairo_move_to(cr, x0, y0);
  cairo_line_to(cr, x1, y1);
  cairo_stroke(cr);
}

void dot(cairo_t* cr, double x, double y, double r, const Rgb& fill) {
  cairo_arc(cr, x, y, r, 0.0, 2.0 * M_PI);
  setColour(cr, fill);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_set_line_width(cr, 1.5);
  cairo_stroke(cr);
}

void heading(cairo_t* cr, const std::string& title, const std::string& subtitle, double x) {
  setFont(cr, 19, true);
  setColour(cr, kText);
  text(cr, title, x, 34);
  setFont(cr, 13);
  setColour(cr, kMuted);
  text(cr, subtitle, x, 56);
}

/// Words of `s` wrapped to `width` pixels, drawn from (x, y) downwards; returns the next baseline.
double paragraph(cairo_t* cr, const std::string& s, double x, double y, double width, double leading) {
  std::string current;
  std::size_t pos = 0;
  while (pos < s.size()) {
    std::size_t end = s.find(' ', pos);
    if (end == std::string::npos) end = s.size();
    const std::string word = s.substr(pos, end - pos);
    const std::string candidate = current.empty() ? word : current + " " + word;
    if (!current.empty() && textWidth(cr, candidate) > width) {
      text(cr, current, x, y);
      y += leading;
      current = word;
    } else {
      current = candidate;
    }
    pos = end + 1;
  }
  if (!current.empty()) {
    text(cr, current, x, y);
    y += leading;
  }
  return y;
}

/// The heading "Legend" at baseline y; sets the font of the items and returns their first baseline.
double legendHeading(cairo_t* cr, double x, double y) {
  setFont(cr, 13, true);
  setColour(cr, kText);
  text(cr, "Legend", x, y);
  setFont(cr, 12);
  return y + 22;
}

/// Legend entry: a symbol drawn by `symbol(x, y_mid)` and a label; returns the next baseline.
template <class Symbol>
double legendItem(cairo_t* cr, double x, double y, const std::string& label, Symbol symbol) {
  cairo_new_path(cr);
  symbol(x, y - 4.5);
  cairo_new_path(cr);
  setColour(cr, kText);
  text(cr, label, x + 30, y);
  return y + 21;
}

auto swatch(cairo_t* cr, const Rgb& c) {
  return [cr, c](double x, double y) {
    cairo_rectangle(cr, x, y - 7, 22, 14);
    setColour(cr, c);
    cairo_fill_preserve(cr);
    setColour(cr, kFrame);
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);
  };
}

auto stroke(cairo_t* cr, const Rgb& c, double width, bool dashed) {
  return [cr, c, width, dashed](double x, double y) {
    const double dash[] = {5.0, 3.0};
    cairo_set_dash(cr, dash, dashed ? 2 : 0, 0.0);
    setColour(cr, c);
    cairo_set_line_width(cr, width);
    line(cr, x, y, x + 22, y);
    cairo_set_dash(cr, nullptr, 0, 0.0);
  };
}

/// The right-hand column under the legend: explanatory notes, then the solver's result (first
/// contact, collision intervals) and a footer line.
void notesAndResult(cairo_t* cr, double x, double y, double width, const std::vector<std::string>& notes,
                    const std::optional<double>& first_contact, const std::vector<std::pair<double, double>>& intervals,
                    const std::string& footer) {
  setFont(cr, 11.5);
  setColour(cr, kMuted);
  for (const std::string& note : notes) y = paragraph(cr, note, x, y, width, 16) + 4;
  y += 10;
  setFont(cr, 13, true);
  setColour(cr, kText);
  text(cr, "Result", x, y);
  y += 20;
  setFont(cr, 12);
  text(cr, first_contact ? "first contact t = " + fixed(*first_contact) : "no contact in [0, 1]", x, y);
  y += 18;
  if (!intervals.empty()) {
    text(cr, "collision intervals:", x, y);
    y += 18;
    for (std::size_t k = 0; k < intervals.size() && k < 8; ++k) {
      text(cr, "  " + interval(intervals[k].first, intervals[k].second), x, y);
      y += 17;
    }
  }
  setColour(cr, kMuted);
  text(cr, footer, x, y + 4);
}

/// Labels at the wanted y positions, moved apart to at least `gap` pixels (order kept).
std::vector<double> spread(std::vector<double> y, double gap, double lo, double hi) {
  for (std::size_t k = 1; k < y.size(); ++k) y[k] = std::max(y[k], y[k - 1] + gap);
  if (!y.empty() && y.back() > hi) {
    y.back() = hi;
    for (std::size_t k = y.size() - 1; k > 0; --k) y[k - 1] = std::min(y[k - 1], y[k] - gap);
  }
  for (double& v : y) v = std::max(v, lo);
  return y;
}

std::string pairName(const Scene& scene, std::size_t i, std::size_t j) {
  return scene.objects[i].name + " \u2013 " + scene.objects[j].name;
}

// --- ccd-function ----------------------------------------------------------------------------------

constexpr int kFnWidth = 1040, kFnHeight = 740;
constexpr double kFnX = 96, kFnY = 118, kFnSize = 540;

void drawCcdFunction(cairo_t* cr, const CcdFunctionPlot& plot, const std::string& title, const std::string& subtitle) {
  const double x0 = kFnX, y0 = kFnY, S = kFnSize;
  auto px = [&](double u) { return x0 + S * u; };
  auto py = [&](double t) { return y0 + S * (1.0 - t); };
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  heading(cr, title, subtitle, x0);

  // Regions: F < 0 everywhere, then the outlines of F > 0 (even-odd), clipped to the square.
  cairo_save(cr);
  cairo_rectangle(cr, x0, y0, S, S);
  cairo_clip(cr);
  setColour(cr, kNegative);
  cairo_paint(cr);
  cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
  for (std::size_t k = 0; k < plot.segments.size(); ++k) {
    cairo_save(cr);
    cairo_rectangle(cr, x0, py(plot.segments[k].t_end), S, py(plot.segments[k].t_begin) - py(plot.segments[k].t_end));
    cairo_clip(cr);
    for (const auto& outline : plot.positive_region) {
      if (outline.segment != k) continue;
      cairo_new_sub_path(cr);
      for (const Eigen::Vector2d& p : outline.points) cairo_line_to(cr, px(p[0]), py(p[1]));
      cairo_close_path(cr);
    }
    setColour(cr, kPositive);
    cairo_fill(cr);
    cairo_restore(cr);
  }
  // Light grid.
  cairo_set_source_rgba(cr, 0.3, 0.3, 0.35, 0.12);
  cairo_set_line_width(cr, 1.0);
  for (int k = 1; k < 10; ++k) {
    line(cr, std::round(px(0.1 * k)) + 0.5, y0, std::round(px(0.1 * k)) + 0.5, y0 + S);
    line(cr, x0, std::round(py(0.1 * k)) + 0.5, x0 + S, std::round(py(0.1 * k)) + 0.5);
  }
  // Segment breaks (the u scale changes there).
  const double dots[] = {2.0, 3.0};
  for (std::size_t k = 1; k < plot.segments.size(); ++k) {
    cairo_set_dash(cr, dots, 2, 0.0);
    setColour(cr, kMuted);
    cairo_set_line_width(cr, 1.2);
    line(cr, x0, py(plot.segments[k].t_begin), x0 + S, py(plot.segments[k].t_begin));
    cairo_set_dash(cr, nullptr, 0, 0.0);
  }
  // Contact instants: dashed lines across.
  const double dash[] = {6.0, 4.0};
  for (const Eigen::Vector2d& c : plot.contacts) {
    cairo_set_dash(cr, dash, 2, 0.0);
    setColour(cr, kContact, 0.75);
    cairo_set_line_width(cr, 1.2);
    line(cr, x0, py(c[1]), x0 + S, py(c[1]));
    cairo_set_dash(cr, nullptr, 0, 0.0);
  }
  // The zero set.
  setColour(cr, kZeroSet);
  cairo_set_line_width(cr, 2.2);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (const auto& run : plot.zero_set) {
    cairo_new_sub_path(cr);
    for (const Eigen::Vector2d& p : run) cairo_line_to(cr, px(p[0]), py(p[1]));
    cairo_stroke(cr);
  }
  for (const Eigen::Vector2d& c : plot.contacts) dot(cr, px(c[0]), py(c[1]), 5.0, kContact);
  cairo_restore(cr);

  // Frame and axes.
  setColour(cr, kFrame);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, x0 + 0.5, y0 + 0.5, S - 1, S - 1);
  cairo_stroke(cr);
  setFont(cr, 12);
  for (int k = 0; k <= 10; k += 2) {
    const double v = 0.1 * k;
    setColour(cr, kFrame);
    line(cr, px(v), y0 + S, px(v), y0 + S + 5);
    line(cr, x0 - 5, py(v), x0, py(v));
    setColour(cr, kMuted);
    text(cr, formatNumber(v), px(v), y0 + S + 19, 0.5);
    text(cr, formatNumber(v), x0 - 8, py(v) + 4, 1.0);
  }
  // The top axis: lambda = (u - 1) / u.
  for (const double lambda : {-4.0, -2.0, -1.0, -0.5, -0.25}) {
    const double u = 1.0 / (1.0 - lambda);
    setColour(cr, kFrame);
    line(cr, px(u), y0 - 5, px(u), y0);
    setColour(cr, kMuted);
    text(cr, formatNumber(lambda), px(u), y0 - 9, 0.5);
  }
  setColour(cr, kMuted);
  text(cr, "\u2212\u221e", px(0.0), y0 - 9, 0.5);
  text(cr, "0", px(1.0), y0 - 9, 0.5);
  setFont(cr, 13, true);
  setColour(cr, kText);
  text(cr, "u", x0 + S / 2, y0 + S + 42, 0.5);
  setFont(cr, 12);
  setColour(cr, kMuted);
  text(cr, "\u03bb = (u \u2212 1) / u   (pencil parameter, balanced A and B)", x0 + S / 2, y0 - 28, 0.5);
  cairo_save(cr);
  cairo_translate(cr, x0 - 44, y0 + S / 2);
  cairo_rotate(cr, -M_PI / 2);
  setFont(cr, 13, true);
  setColour(cr, kText);
  text(cr, "time t", 0, 0, 0.5);
  cairo_restore(cr);

  // The state strip right of the square: collision intervals in red.
  const double sx = x0 + S + 12, sw = 14;
  cairo_rectangle(cr, sx, y0, sw, S);
  cairo_set_source_rgb(cr, 0.92, 0.94, 0.92);
  cairo_fill(cr);
  for (const CcdInterval& c : plot.result.collision_intervals) {
    const double ya = py(c.end), yb = py(c.begin);
    const double h = std::max(2.5, yb - ya);
    cairo_rectangle(cr, sx, 0.5 * (ya + yb) - 0.5 * h, sw, h);
    setColour(cr, kCollision);
    cairo_fill(cr);
  }
  setColour(cr, kFrame);
  cairo_rectangle(cr, sx + 0.5, y0 + 0.5, sw - 1, S - 1);
  cairo_stroke(cr);
  // Contact labels beside the strip, spread apart.
  std::vector<double> wanted;
  for (const Eigen::Vector2d& c : plot.contacts) wanted.push_back(py(c[1]) + 4);
  std::reverse(wanted.begin(), wanted.end());  // top to bottom
  const std::vector<double> placed = spread(wanted, 16, y0 + 10, y0 + S);
  setFont(cr, 12);
  for (std::size_t k = 0; k < placed.size(); ++k) {
    const Eigen::Vector2d& c = plot.contacts[plot.contacts.size() - 1 - k];
    setColour(cr, kContact, 0.6);
    cairo_set_line_width(cr, 1.0);
    line(cr, sx + sw, py(c[1]), sx + sw + 6, placed[k] - 4);
    const bool first = plot.result.first_contact_time && *plot.result.first_contact_time == c[1];
    setFont(cr, 12, first);
    setColour(cr, kContact);
    text(cr, "t = " + fixed(c[1]), sx + sw + 8, placed[k]);
  }

  // Legend and reading notes on the right.
  const double lx = sx + sw + 100, width = kFnWidth - lx - 20;
  double y = legendHeading(cr, lx, y0 + 4);
  y = legendItem(cr, lx, y, "F(u, t) > 0", swatch(cr, kPositive));
  y = legendItem(cr, lx, y, "F(u, t) < 0", swatch(cr, kNegative));
  y = legendItem(cr, lx, y, "zero set F = 0", stroke(cr, kZeroSet, 2.2, false));
  y = legendItem(cr, lx, y, "contact (double root)", [&](double x, double ym) { dot(cr, x + 11, ym, 5.0, kContact); });
  y = legendItem(cr, lx, y, "collision interval", [&](double x, double ym) {
    cairo_rectangle(cr, x + 4, ym - 8, 14, 16);
    setColour(cr, kCollision);
    cairo_fill(cr);
  });
  if (plot.segments.size() > 1) y = legendItem(cr, lx, y, "motion piece break", stroke(cr, kMuted, 1.2, true));
  y += 10;
  std::vector<std::string> notes{
      "A line t = const meets the zero set twice while the ellipsoids are separate, touches it at a contact and "
      "misses it while they overlap (thesis Theorem 5.1)."};
  if (plot.segments.size() > 1) {
    notes.push_back("Each motion piece has its own pencil scaling, so the u position jumps at a break.");
  }
  const EllipsoidCcdResult& r = plot.result;
  std::vector<std::pair<double, double>> intervals;
  for (const CcdInterval& c : r.collision_intervals) intervals.emplace_back(c.begin, c.end);
  notesAndResult(cr, lx, y + 10, width, notes, r.first_contact_time, intervals,
                 "degree of F in t: " + std::to_string(r.degree_t > 0 ? r.degree_t : plot.segments.front().F.degreeT()));
}

// --- discriminant ----------------------------------------------------------------------------------

constexpr int kDiscWidth = 1040, kDiscHeight = 620;
constexpr double kDiscX = 104, kDiscY = 84, kDiscW = 620, kDiscH = 440;

/// "10" with a superscript exponent for v = +-10^k ("−" for the sign).
std::string powerOfTen(double v) {
  static const char* const kSuperscript[] = {"⁰", "¹", "²", "³", "⁴",
                                             "⁵", "⁶", "⁷", "⁸", "⁹"};
  const long k = std::lround(std::log10(std::fabs(v)));
  std::string exponent;
  for (const char c : std::to_string(std::labs(k))) exponent += kSuperscript[c - '0'];
  return std::string(v < 0.0 ? "−" : "") + "10" + (k < 0 ? "⁻" : "") + exponent;
}

/// The y scale of the discriminant plot: linear, or symmetric-log when |Delta| spans many orders.
struct YScale {
  bool symlog = false;
  double threshold = 1.0;  // symlog: linear inside +-threshold
  double lo = -1.0, hi = 1.0;  // in transformed units
  double transform(double v) const {
    if (!symlog) return v;
    const double m = std::log10(1.0 + std::fabs(v) / threshold);
    return v < 0.0 ? -m : m;
  }
};

void drawDiscriminant(cairo_t* cr, const DiscriminantPlot& plot, const std::string& title, const std::string& subtitle) {
  const double x0 = kDiscX, y0 = kDiscY, W = kDiscW, H = kDiscH;
  constexpr int kSamples = 1600;
  std::vector<double> values(kSamples + 1);
  double vmax = 0.0;
  for (int k = 0; k <= kSamples; ++k) {
    values[static_cast<std::size_t>(k)] = plot.delta.evaluate(static_cast<double>(k) / kSamples);
    vmax = std::max(vmax, std::fabs(values[static_cast<std::size_t>(k)]));
  }
  YScale scale;
  if (vmax > 0.0) {
    std::vector<double> mags;
    for (double v : values) {
      if (v != 0.0) mags.push_back(std::fabs(v));
    }
    std::sort(mags.begin(), mags.end());
    // The smallest sampled magnitude sets the linear zone, so that sign changes stay visible.
    // Floor: 32 decades below the maximum (below that Delta is rounding noise of its coefficients).
    const double low = mags.empty() ? vmax : std::max(mags.front(), vmax * 1e-32);
    if (vmax > 1e3 * low) {
      scale.symlog = true;
      scale.threshold = std::pow(10.0, std::floor(std::log10(low)));
    }
    const double m = scale.transform(vmax);
    scale.lo = -1.08 * m;
    scale.hi = 1.08 * m;
    double vmin_signed = 0.0, vmax_signed = 0.0;
    for (double v : values) {
      vmin_signed = std::min(vmin_signed, v);
      vmax_signed = std::max(vmax_signed, v);
    }
    // Asymmetric range when Delta keeps one sign over most of its span.
    scale.lo = std::min(-0.08 * m, 1.08 * scale.transform(vmin_signed));
    scale.hi = std::max(0.08 * m, 1.08 * scale.transform(vmax_signed));
  }
  auto px = [&](double t) { return x0 + W * t; };
  auto py = [&](double v) { return y0 + H * (scale.hi - scale.transform(v)) / (scale.hi - scale.lo); };

  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  heading(cr, title, subtitle, x0);
  cairo_rectangle(cr, x0, y0, W, H);
  cairo_set_source_rgb(cr, 0.985, 0.985, 0.98);
  cairo_fill(cr);

  // Collision intervals as bands.
  for (const auto& [t0, t1] : plot.result.collision_intervals) {
    const double w = std::max(3.0, px(t1) - px(t0));
    cairo_rectangle(cr, 0.5 * (px(t0) + px(t1)) - 0.5 * w, y0, w, H);
    setColour(cr, kCollision, 0.16);
    cairo_fill(cr);
  }
  // Grid and y ticks.
  setFont(cr, 12);
  std::vector<double> ticks;
  if (scale.symlog) {
    ticks.push_back(0.0);
    for (double v = scale.threshold; v <= vmax * 1.0001; v *= 10.0) {
      if (scale.transform(v) <= scale.hi) ticks.push_back(v);
      if (scale.transform(-v) >= scale.lo) ticks.push_back(-v);
    }
  } else if (scale.hi > scale.lo) {
    const double step = niceStep((scale.hi - scale.lo) / 8.0);
    for (double v = std::ceil(scale.lo / step) * step; v <= scale.hi; v += step) ticks.push_back(v);
  }
  // The zero line always; others (smallest magnitude first) only where they do not crowd it.
  std::sort(ticks.begin(), ticks.end(), [](double a, double b) { return std::fabs(a) < std::fabs(b); });
  std::vector<double> shown{0.0};
  for (double v : ticks) {
    const bool room = std::all_of(shown.begin(), shown.end(), [&](double w) { return std::fabs(py(v) - py(w)) >= 18.0; });
    if (room) shown.push_back(v);
  }
  for (double v : shown) {
    const double y = std::round(py(v)) + 0.5;
    const bool zero = v == 0.0;
    cairo_set_source_rgba(cr, 0.3, 0.3, 0.35, zero ? 0.6 : 0.13);
    cairo_set_line_width(cr, zero ? 1.3 : 1.0);
    line(cr, x0, y, x0 + W, y);
    setColour(cr, kMuted);
    text(cr, zero ? std::string("0") : scale.symlog ? powerOfTen(v) : formatNumber(v), x0 - 8, y + 4, 1.0);
  }
  for (int k = 0; k <= 10; ++k) {
    const double x = std::round(px(0.1 * k)) + 0.5;
    cairo_set_source_rgba(cr, 0.3, 0.3, 0.35, 0.13);
    line(cr, x, y0, x, y0 + H);
    setColour(cr, kMuted);
    if (k % 2 == 0) text(cr, formatNumber(0.1 * k), x, y0 + H + 19, 0.5);
  }
  // The curve.
  cairo_save(cr);
  cairo_rectangle(cr, x0, y0, W, H);
  cairo_clip(cr);
  setColour(cr, kZeroSet);
  cairo_set_line_width(cr, 2.0);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (int k = 0; k <= kSamples; ++k) {
    cairo_line_to(cr, px(static_cast<double>(k) / kSamples), py(values[static_cast<std::size_t>(k)]));
  }
  cairo_stroke(cr);
  // Contacts in red with a dashed vertical; the roots of Delta as rings on the zero line.
  const double dash[] = {6.0, 4.0};
  for (const EllipseContact& c : plot.result.contacts) {
    cairo_set_dash(cr, dash, 2, 0.0);
    setColour(cr, kContact, 0.7);
    cairo_set_line_width(cr, 1.2);
    line(cr, px(c.t), y0, px(c.t), y0 + H);
    cairo_set_dash(cr, nullptr, 0, 0.0);
    dot(cr, px(c.t), py(plot.delta.evaluate(c.t)), 5.0, kContact);
  }
  for (double t : plot.roots) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, px(t), py(0.0), 8.0, 0.0, 2.0 * M_PI);
    setColour(cr, kZeroSet);
    cairo_set_line_width(cr, 1.6);
    cairo_stroke(cr);
  }
  cairo_restore(cr);
  setColour(cr, kFrame);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, x0 + 0.5, y0 + 0.5, W - 1, H - 1);
  cairo_stroke(cr);
  // Contact labels along the top edge, spread apart.
  std::vector<double> wanted;
  for (const EllipseContact& c : plot.result.contacts) wanted.push_back(px(c.t));
  const std::vector<double> placed = spread(wanted, 66, x0 + 30, x0 + W - 30);
  setFont(cr, 11.5);
  setColour(cr, kContact);
  for (std::size_t k = 0; k < placed.size(); ++k) text(cr, fixed(plot.result.contacts[k].t, 3), placed[k], y0 - 6, 0.5);

  setFont(cr, 13, true);
  setColour(cr, kText);
  text(cr, "time t", x0 + W / 2, y0 + H + 42, 0.5);
  cairo_save(cr);
  cairo_translate(cr, x0 - 70, y0 + H / 2);
  cairo_rotate(cr, -M_PI / 2);
  text(cr, scale.symlog ? "\u0394(t), symlog scale" : "\u0394(t)", 0, 0, 0.5);
  if (scale.symlog) {
    setFont(cr, 11);
    setColour(cr, kMuted);
    text(cr, "log\u2081\u2080 beyond \u00b1" + powerOfTen(scale.threshold) + ", linear inside", 0, 15, 0.5);
  }
  cairo_restore(cr);

  // Legend.
  const double lx = x0 + W + 30, width = kDiscWidth - lx - 20;
  double y = legendHeading(cr, lx, y0 + 4);
  y = legendItem(cr, lx, y, "\u0394(t), discriminant of f(\u03bb; t)", stroke(cr, kZeroSet, 2.0, false));
  y = legendItem(cr, lx, y, "real root of \u0394", [&](double x, double ym) {
    cairo_arc(cr, x + 11, ym, 7.0, 0.0, 2.0 * M_PI);
    setColour(cr, kZeroSet);
    cairo_set_line_width(cr, 1.6);
    cairo_stroke(cr);
  });
  y = legendItem(cr, lx, y, "external contact", [&](double x, double ym) { dot(cr, x + 11, ym, 5.0, kContact); });
  y = legendItem(cr, lx, y, "collision interval", [&](double x, double ym) {
    cairo_rectangle(cr, x, ym - 7, 22, 14);
    setColour(cr, kCollision, 0.25);
    cairo_fill(cr);
  });
  const EllipseCcdResult& r = plot.result;
  notesAndResult(cr, lx, y + 8, width,
                 {"The contact state can change only at a root of \u0394 (thesis Theorem 2.9); CD-DISC checks each root "
                  "and each extremum with the static test."},
                 r.first_contact, r.collision_intervals,
                 "degree of \u0394: " + std::to_string(r.discriminant_degree) +
                     ", real roots in [0, 1]: " + std::to_string(plot.roots.size()));
}

// --- timeline --------------------------------------------------------------------------------------

struct TimelineRow {
  std::string label;
  std::vector<std::pair<double, double>> intervals;
  std::optional<double> first_contact;
  bool near_tangent = false;
};

constexpr int kTlWidth = 1040;
constexpr double kTlX = 230, kTlW = 640, kTlTop = 96, kTlRow = 40;

int timelineHeight(std::size_t rows) { return static_cast<int>(kTlTop + kTlRow * static_cast<double>(rows) + 96); }

void drawTimeline(cairo_t* cr, const std::vector<TimelineRow>& rows, const std::string& title, const std::string& subtitle) {
  const double x0 = kTlX, W = kTlW, y0 = kTlTop;
  const double H = kTlRow * static_cast<double>(rows.size());
  auto px = [&](double t) { return x0 + W * t; };
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  heading(cr, title, subtitle, 24);
  // Grid.
  setFont(cr, 12);
  for (int k = 0; k <= 10; ++k) {
    const double x = std::round(px(0.1 * k)) + 0.5;
    cairo_set_source_rgba(cr, 0.3, 0.3, 0.35, k % 5 == 0 ? 0.3 : 0.12);
    cairo_set_line_width(cr, 1.0);
    line(cr, x, y0, x, y0 + H);
    setColour(cr, kMuted);
    text(cr, formatNumber(0.1 * k), x, y0 + H + 19, 0.5);
  }
  setFont(cr, 13, true);
  setColour(cr, kText);
  text(cr, "time t", x0 + W / 2, y0 + H + 42, 0.5);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const TimelineRow& row = rows[k];
    const double yc = y0 + kTlRow * (static_cast<double>(k) + 0.5);
    if (k % 2 == 0) {
      cairo_rectangle(cr, 12, yc - kTlRow / 2, kTlWidth - 24, kTlRow);
      cairo_set_source_rgba(cr, 0.2, 0.2, 0.3, 0.04);
      cairo_fill(cr);
    }
    setFont(cr, 13, true);
    setColour(cr, kText);
    text(cr, row.label, x0 - 14, yc + 5, 1.0);
    // Track.
    cairo_rectangle(cr, x0, yc - 3, W, 6);
    cairo_set_source_rgb(cr, 0.84, 0.88, 0.84);
    cairo_fill(cr);
    for (const auto& [t0, t1] : row.intervals) {
      const double w = std::max(3.0, px(t1) - px(t0));
      cairo_rectangle(cr, std::min(0.5 * (px(t0) + px(t1)) - 0.5 * w, x0 + W - w), yc - 9, w, 18);
      setColour(cr, kCollision);
      cairo_fill_preserve(cr);
      setColour(cr, {0.55, 0.08, 0.05});
      cairo_set_line_width(cr, 1.0);
      cairo_stroke(cr);
    }
    setFont(cr, 12);
    if (row.first_contact) {
      const double x = px(*row.first_contact);
      cairo_move_to(cr, x, yc - 15);
      cairo_line_to(cr, x + 6, yc - 21);
      cairo_line_to(cr, x - 6, yc - 21);
      cairo_close_path(cr);
      setColour(cr, kText);
      cairo_fill(cr);
      const bool touch_only = std::all_of(row.intervals.begin(), row.intervals.end(),
                                          [](const std::pair<double, double>& iv) { return iv.first == iv.second; });
      const std::string label = "t = " + fixed(*row.first_contact, 3) + (touch_only ? " (touch)" : "") +
                                (row.near_tangent ? " (near-tangent)" : "");
      setColour(cr, kMuted);
      text(cr, label, x0 + W + 12, yc + 4);
    } else {
      setColour(cr, kMuted);
      text(cr, "no contact", x0 + W + 12, yc + 4);
    }
  }
  setColour(cr, kFrame);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, x0 + 0.5, y0 + 0.5, W - 1, H - 1);
  cairo_stroke(cr);
  setFont(cr, 12, true);
  setColour(cr, kMuted);
  text(cr, "pair", x0 - 14, y0 - 10, 1.0);
  text(cr, "first contact", x0 + W + 12, y0 - 10);
  // Legend under the axis.
  const double ly = y0 + H + 74;
  setFont(cr, 12);
  double x = x0;
  cairo_rectangle(cr, x, ly - 11, 22, 14);
  setColour(cr, kCollision);
  cairo_fill(cr);
  setColour(cr, kText);
  text(cr, "touching or overlapping", x + 30, ly);
  x += 30 + textWidth(cr, "touching or overlapping") + 28;
  cairo_rectangle(cr, x, ly - 7, 22, 6);
  cairo_set_source_rgb(cr, 0.84, 0.88, 0.84);
  cairo_fill(cr);
  setColour(cr, kText);
  text(cr, "separate", x + 30, ly);
  x += 30 + textWidth(cr, "separate") + 28;
  cairo_move_to(cr, x + 11, ly - 1);
  cairo_line_to(cr, x + 17, ly - 9);
  cairo_line_to(cr, x + 5, ly - 9);
  cairo_close_path(cr);
  cairo_fill(cr);
  text(cr, "first contact", x + 30, ly);
}

std::string sceneTitle(const std::string& title) { return title.empty() ? std::string("scene") : title; }

std::vector<TimelineRow> timelineRows(const Scene& scene) {
  Scene moving = scene;
  moving.pairs.clear();
  for (const auto& [i, j] : scene.pairs) {
    if (isMoving(scene, i) || isMoving(scene, j)) moving.pairs.emplace_back(i, j);
  }
  if (moving.pairs.empty()) throw SceneError("/objects", "plot timeline: the scene has no pair with a moving object");
  moving.ccd.all_intervals = true;
  const nlohmann::ordered_json result = ccdScene(moving);
  std::vector<TimelineRow> rows;
  for (std::size_t k = 0; k < moving.pairs.size(); ++k) {
    const nlohmann::ordered_json& p = result["pairs"][k];
    TimelineRow row;
    row.label = pairName(moving, moving.pairs[k].first, moving.pairs[k].second);
    for (const auto& iv : p["overlap_intervals"]) row.intervals.emplace_back(iv[0].get<double>(), iv[1].get<double>());
    if (!p["first_contact_time"].is_null()) row.first_contact = p["first_contact_time"].get<double>();
    row.near_tangent = p["near_tangent"].get<bool>();
    rows.push_back(std::move(row));
  }
  return rows;
}

void plotCcdFunction(const Scene& scene, std::size_t i, std::size_t j, const std::string& title,
                     const std::string& output) {
  if (scene.dimension != 3) {
    throw SceneError("/dimension", "plot ccd-function needs a 3D scene of ellipsoids; for a planar scene use plot discriminant");
  }
  if (!isMoving(scene, i) && !isMoving(scene, j)) {
    throw SceneError("/objects/" + std::to_string(i),
                     "plot ccd-function: neither \"" + scene.objects[i].name + "\" nor \"" + scene.objects[j].name +
                         "\" has a motion (F would not depend on t)");
  }
  const MovingEllipsoid a = movingEllipsoid(scene.objects[i], i), b = movingEllipsoid(scene.objects[j], j);
  const CcdInterpolation interpolation = scene.ccd.affine ? CcdInterpolation::Affine : CcdInterpolation::Rigid;
  CcdFunctionPlot plot;
  try {
    plot = sampleCcdFunction(a, b, interpolation);
  } catch (const CcdDegreeError& e) {
    throw degreeLimitError(scene, i, j, e);
  }
  const std::string heading_text = "CCD function F(u, t) \u00b7 " + pairName(scene, i, j) + "   (" + title + ")";
  const std::string subtitle = std::string("F(u, t) = det((u \u2212 1) A(t) \u2212 u B(t)), zero set by marching squares, ") +
                               (scene.ccd.affine ? "affine interpolant (thesis \u00a75.2)" : "rigid motions") +
                               ", " + std::to_string(plot.segments.size()) +
                               (plot.segments.size() == 1 ? " motion piece" : " motion pieces");
  writePicture(output, kFnWidth, kFnHeight, [&](cairo_t* cr) { drawCcdFunction(cr, plot, heading_text, subtitle); });
}

void plotDiscriminant(const Scene& scene, std::size_t i, std::size_t j, const std::string& title,
                      const std::string& output) {
  if (scene.dimension != 2) {
    throw SceneError("/dimension", "plot discriminant needs a planar scene (\"dimension\": 2); for 3D use plot ccd-function");
  }
  const DiscriminantPlot plot = sampleDiscriminant(movingEllipse2(scene.objects[i]), movingEllipse2(scene.objects[j]));
  const std::string heading_text = "Discriminant \u0394(t) \u00b7 " + pairName(scene, i, j) + "   (" + title + ")";
  const std::string subtitle =
      "\u0394(t) = discriminant in \u03bb of f(\u03bb; t) = det(\u03bb A(t) \u2212 B(t)), Bernstein form on [0, 1] "
      "(thesis ch.2, eq. 2.2), scaled to max |coefficient| ~ 1";
  writePicture(output, kDiscWidth, kDiscHeight, [&](cairo_t* cr) { drawDiscriminant(cr, plot, heading_text, subtitle); });
}

void plotTimeline(const Scene& scene, const std::string& title, const std::string& output) {
  const std::vector<TimelineRow> rows = timelineRows(scene);
  const std::string heading_text = "Overlap intervals over t \u2208 [0, 1] \u00b7 " + title;
  const std::string subtitle = std::to_string(rows.size()) + (rows.size() == 1 ? " moving pair" : " moving pairs") +
                               (scene.dimension == 2 ? ", CD-DISC (thesis ch.2)" : ", continuousCollideEllipsoids (thesis ch.5)");
  writePicture(output, kTlWidth, timelineHeight(rows.size()),
               [&](cairo_t* cr) { drawTimeline(cr, rows, heading_text, subtitle); });
}

}  // namespace

void plotScene(const Scene& scene, const PlotRequest& request, const std::string& output) {
  requirePictureFile(output);
  const std::string title = sceneTitle(request.title);
  if (request.kind == "timeline") {
    plotTimeline(scene, title, output);
    return;
  }
  if (request.kind != "ccd-function" && request.kind != "discriminant") {
    throw SceneError("", "unknown plot \"" + request.kind + "\" (ccd-function, discriminant or timeline)");
  }
  if (request.pair.empty()) throw SceneError("", "plot " + request.kind + " needs --pair I,J");
  const auto [i, j] = parsePair(scene, request.pair);
  if (request.kind == "ccd-function") {
    plotCcdFunction(scene, i, j, title, output);
  } else {
    plotDiscriminant(scene, i, j, title, output);
  }
}

void runPlot(const std::string& kind, const std::string& scene_path, const std::string& pair, const std::string& output) {
  requirePictureFile(output);
  const Scene scene = readSceneFile(scene_path);
  const std::size_t slash = scene_path.find_last_of('/');
  PlotRequest request;
  request.kind = kind;
  request.pair = pair;
  request.title = slash == std::string::npos ? scene_path : scene_path.substr(slash + 1);
  plotScene(scene, request, output);
}

std::string writeDemoPlots(const std::string& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw SceneError("", "cannot create the pictures directory " + directory + ": " + ec.message());
  const std::filesystem::path dir(directory);
  const Scene scene3 = parseSceneText(kExampleSceneCcd);
  const Scene scene2 = parseSceneText(kExampleSceneCcd2d);
  const std::string f = (dir / "ccd_function.png").string(), d = (dir / "discriminant.png").string(),
                    t = (dir / "timeline.png").string();
  plotScene(scene3, {"ccd-function", kExampleSceneCcdPair, "examples/scene_ccd.json"}, f);
  plotScene(scene2, {"discriminant", kExampleSceneCcd2dPair, "examples/scene_ccd_2d.json"}, d);
  plotScene(scene3, {"timeline", "", "examples/scene_ccd.json"}, t);
  return f + ", " + d + ", " + t;
}

}  // namespace cli
}  // namespace fcl_quadric
