#include "fcl_quadric/picture.h"

#include <cctype>
#include <cmath>
#include <cstdio>

#include <cairo-svg.h>

#include "fcl_quadric/scene.h"

namespace fcl_quadric {
namespace cli {

namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

bool isPictureFile(const std::string& path) {
  const std::string ext = lower(path);
  return endsWith(ext, ".svg") || endsWith(ext, ".png");
}

void requirePictureFile(const std::string& path) {
  if (!isPictureFile(path)) throw SceneError("", "output file must end in .svg or .png: " + path);
}

void writePicture(const std::string& path, int width, int height, const std::function<void(cairo_t*)>& draw) {
  requirePictureFile(path);
  const bool svg = endsWith(lower(path), ".svg");
  cairo_surface_t* surface = svg ? cairo_svg_surface_create(path.c_str(), width, height)
                                 : cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
  cairo_t* cr = cairo_create(surface);
  cairo_status_t status = cairo_status(cr);
  if (status == CAIRO_STATUS_SUCCESS) {
    try {
      draw(cr);
    } catch (...) {
      cairo_destroy(cr);
      cairo_surface_destroy(surface);
      throw;
    }
    status = cairo_status(cr);
  }
  cairo_destroy(cr);
  if (status == CAIRO_STATUS_SUCCESS && !svg) status = cairo_surface_write_to_png(surface, path.c_str());
  cairo_surface_finish(surface);
  if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS) {
    throw SceneError("", "cannot write " + path + ": " + cairo_status_to_string(status));
  }
}

std::string formatNumber(double v) {
  if (std::isfinite(v) && std::fabs(v) < 1e-12) v = 0.0;
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

double niceStep(double raw) {
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / p;
  return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * p;
}

void setColour(cairo_t* cr, const Rgb& c, double alpha) { cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha); }

void setFont(cairo_t* cr, double size, bool bold) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

double textWidth(cairo_t* cr, const std::string& s) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  return e.x_advance;
}

void text(cairo_t* cr, const std::string& s, double x, double y, double align) {
  cairo_move_to(cr, x - align * textWidth(cr, s), y);
  cairo_show_text(cr, s.c_str());
}

void haloText(cairo_t* cr, const std::string& s, double x, double y, const Rgb& colour) {
  cairo_move_to(cr, x, y);
  cairo_text_path(cr, s.c_str());
  cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
  cairo_set_line_width(cr, 3.0);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_stroke(cr);
  setColour(cr, colour);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
}

}  // namespace cli
}  // namespace fcl_quadric
