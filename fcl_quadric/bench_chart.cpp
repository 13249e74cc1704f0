#include "fcl_quadric/bench_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include <cairo.h>

#include "fcl_quadric/picture.h"
#include "fcl_quadric/scene.h"

namespace fcl_quadric {
namespace cli {

namespace {

constexpr int kWidth = 1000;
constexpr double kLabelWidth = 250;  // case and peer names
constexpr double kRight = 200;       // value labels
constexpr double kTop = 78, kBottom = 92;
constexpr double kBar = 20, kBarGap = 5, kGroupGap = 18;

/// The colour of a peer, the same in every chart: fcl_quadric (and its coherent variants) warm,
/// FCL blue/green, Bullet purple, the shared broad phase grey.
Rgb peerColour(const std::string& peer) {
  if (peer == "fcl_quadric") return {0.86, 0.30, 0.10};
  if (peer == "pair_coherence" || peer == "pair_cache") return {0.95, 0.62, 0.18};
  if (peer == "fcl_libccd" || peer == "fcl_naive") return {0.20, 0.45, 0.78};
  if (peer == "fcl_indep") return {0.10, 0.58, 0.55};
  if (peer == "bullet") return {0.46, 0.36, 0.72};
  if (peer.rfind("fcl_convex", 0) == 0) return {0.45, 0.62, 0.85};
  return {0.60, 0.60, 0.63};
}

std::string timeText(double ns) {
  char buf[32];
  if (ns >= 1e6) {
    std::snprintf(buf, sizeof buf, "%.3g ms", ns / 1e6);
  } else if (ns >= 1e3) {
    std::snprintf(buf, sizeof buf, "%.3g \xc2\xb5s", ns / 1e3);
  } else {
    std::snprintf(buf, sizeof buf, "%.3g ns", ns);
  }
  return buf;
}

/// The value a bar shows.
double barValue(const BenchExperiment& e, const BenchRow& r) {
  if (e.chart_wrong) return r.wrong > 0 && r.n > 0 ? 100.0 * static_cast<double>(r.wrong) / static_cast<double>(r.n) : 0.0;
  return r.ns_per_query;
}

void draw(cairo_t* cr, const BenchExperiment& e, double height) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  setColour(cr, kText);
  setFont(cr, 17, true);
  text(cr, e.title, 24, 32);
  setFont(cr, 12.5);
  cairo_set_source_rgb(cr, 0.35, 0.35, 0.38);
  text(cr, e.chart_wrong ? "Wrong answers against the exact answer, % of the pairs of each case (shorter is better)"
                         : "CPU time per " + e.unit + ", same inputs for every peer (shorter is faster); label: time and ratio to fcl_quadric",
       24, 54);

  // Axis range.
  double lo = 1e300, hi = 0.0;
  for (const BenchRow& r : e.rows) {
    const double v = barValue(e, r);
    if (v > 0.0) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  if (!(hi > 0.0)) {
    lo = 1.0;
    hi = e.chart_wrong ? 100.0 : 10.0;
  }
  const bool log_scale = !e.chart_wrong && hi / lo > 10.0;
  double a0 = 0.0, a1 = hi * 1.05;
  if (log_scale) {
    a0 = std::floor(std::log10(lo));
    a1 = std::ceil(std::log10(hi));
    if (a1 <= a0) a1 = a0 + 1;
  } else if (e.chart_wrong) {
    a1 = std::max(1.0, std::min(100.0, hi * 1.1));
  }
  const double x0 = kLabelWidth, x1 = kWidth - kRight;
  auto xOf = [&](double v) {
    if (log_scale) {
      const double lv = v > 0.0 ? std::log10(v) : a0;
      return x0 + (x1 - x0) * (std::max(lv, a0) - a0) / (a1 - a0);
    }
    return x0 + (x1 - x0) * std::min(v, a1) / a1;
  };
  const double plot_top = kTop, plot_bottom = height - kBottom;

  // Grid and tick labels.
  setFont(cr, 11);
  std::vector<std::pair<double, std::string>> ticks;
  if (log_scale) {
    for (int k = static_cast<int>(a0); k <= static_cast<int>(a1); ++k) ticks.emplace_back(std::pow(10.0, k), timeText(std::pow(10.0, k)));
  } else {
    const double step = niceStep(a1 / 6);
    for (double v = 0.0; v <= a1 * (1 + 1e-9); v += step) {
      char buf[32];
      if (e.chart_wrong) {
        std::snprintf(buf, sizeof buf, "%g %%", v);
        ticks.emplace_back(v, buf);
      } else {
        ticks.emplace_back(v, timeText(v));
      }
    }
  }
  for (const auto& [v, label] : ticks) {
    const double x = xOf(v);
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.90);
    cairo_set_line_width(cr, 1.0);
    cairo_move_to(cr, std::round(x) + 0.5, plot_top - 6);
    cairo_line_to(cr, std::round(x) + 0.5, plot_bottom + 4);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.35, 0.35, 0.38);
    text(cr, label, x, plot_bottom + 20, 0.5);
  }
  setFont(cr, 12.5);
  setColour(cr, kText);
  std::string axis = e.chart_wrong ? "wrong answers (% of the pairs)" : "CPU time per " + e.unit;
  if (log_scale) axis += " (log scale)";
  text(cr, axis, 0.5 * (x0 + x1), plot_bottom + 42, 0.5);
  setFont(cr, 10.5);
  cairo_set_source_rgb(cr, 0.45, 0.45, 0.48);
  text(cr, "Wrong answers counted against: " + e.truth, 24, height - 18);

  // Bars.
  double y = plot_top;
  std::string group;
  for (const BenchRow& r : e.rows) {
    if (r.case_name != group) {
      if (!group.empty()) y += kGroupGap;
      group = r.case_name;
      setFont(cr, 12.5, true);
      setColour(cr, kText);
      text(cr, group, 24, y + kBar - 5);
    }
    const double v = barValue(e, r);
    const double xe = std::max(xOf(v), x0 + (v > 0.0 ? 1.5 : 0.0));
    setColour(cr, peerColour(r.peer));
    cairo_rectangle(cr, x0, y, xe - x0, kBar);
    cairo_fill(cr);
    setFont(cr, 12, r.peer == "fcl_quadric");
    setColour(cr, kText);
    text(cr, r.peer, x0 - 8, y + kBar - 5, 1.0);
    std::string label;
    char buf[96];
    if (e.chart_wrong) {
      if (r.wrong > 0) {
        std::snprintf(buf, sizeof buf, "%.3g %% (%ld of %zu)", v, r.wrong, r.n);
      } else {
        std::snprintf(buf, sizeof buf, "0 of %zu", r.n);
      }
      label = buf;
    } else {
      label = timeText(r.ns_per_query);
      if (r.peer != "fcl_quadric" && r.ratio > 0.0) {
        std::snprintf(buf, sizeof buf, "  \xc3\x97%.3g", r.ratio);
        label += buf;
      }
    }
    setFont(cr, 11.5);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.22);
    text(cr, label, xe + 6, y + kBar - 5);
    if (!e.chart_wrong && r.wrong > 0) {  // wrong answers in red after the time
      cairo_text_extents_t ext;
      cairo_text_extents(cr, label.c_str(), &ext);
      std::snprintf(buf, sizeof buf, "  %ld wrong", r.wrong);
      cairo_set_source_rgb(cr, 0.80, 0.10, 0.08);
      text(cr, buf, xe + 6 + ext.x_advance, y + kBar - 5);
    }
    y += kBar + kBarGap;
  }
  // Axis line.
  cairo_set_source_rgb(cr, 0.35, 0.35, 0.38);
  cairo_set_line_width(cr, 1.0);
  cairo_move_to(cr, x0 + 0.5, plot_top - 6);
  cairo_line_to(cr, x0 + 0.5, plot_bottom + 4);
  cairo_stroke(cr);
}

}  // namespace

void writeBenchChart(const BenchExperiment& e, const std::string& path) {
  std::size_t groups = 0;
  std::string group;
  for (const BenchRow& r : e.rows) {
    if (r.case_name != group || groups == 0) ++groups;
    group = r.case_name;
  }
  const double bars = static_cast<double>(e.rows.size());
  const double height = kTop + bars * (kBar + kBarGap) + static_cast<double>(groups > 0 ? groups - 1 : 0) * kGroupGap + kBottom;
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, kWidth, static_cast<int>(std::ceil(height)));
  cairo_t* cr = cairo_create(surface);
  cairo_status_t status = cairo_status(cr);
  if (status == CAIRO_STATUS_SUCCESS) {
    draw(cr, e, std::ceil(height));
    status = cairo_status(cr);
  }
  cairo_destroy(cr);
  if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_write_to_png(surface, path.c_str());
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS) throw SceneError("", "cannot write " + path + ": " + cairo_status_to_string(status));
}

}  // namespace cli
}  // namespace fcl_quadric
