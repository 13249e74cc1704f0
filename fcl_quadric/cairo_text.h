#pragma once
/// \file cairo_text.h
/// Drawing helpers shared by the pictures of the program (`render`, the charts of `bench`): the
/// font, text placed by its reference point, and "nice" axis steps.

#include <cmath>
#include <string>

#include <cairo.h>

namespace fcl_quadric {
namespace cli {

inline void setFont(cairo_t* cr, double size, bool bold = false) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

/// Draws text with its reference point at (x, y): align 0 left, 0.5 centre, 1 right; baseline y.
inline void text(cairo_t* cr, const std::string& s, double x, double y, double align = 0.0) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_move_to(cr, x - align * e.x_advance, y);
  cairo_show_text(cr, s.c_str());
}

/// A "nice" grid step (1, 2 or 5 times a power of ten) near `raw`.
inline double niceStep(double raw) {
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / p;
  return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * p;
}

}  // namespace cli
}  // namespace fcl_quadric
