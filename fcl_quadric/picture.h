#pragma once
/// \file picture.h
/// Small Cairo helpers shared by the commands that draw pictures (`render`, `plot`, the demo):
/// the output file (SVG or PNG by its extension), text placement, colours and axis steps.

#include <functional>
#include <string>

#include <cairo.h>

namespace fcl_quadric {
namespace cli {

struct Rgb {
  double r, g, b;
};
constexpr Rgb kText{0.12, 0.12, 0.14};

/// True when `path` ends in ".svg" or ".png" (case-insensitive).
bool isPictureFile(const std::string& path);

/// \throws SceneError ("output file must end in .svg or .png: PATH") unless isPictureFile(path).
void requirePictureFile(const std::string& path);

/// Creates a width x height picture, calls draw(cr) and writes it to `path` as SVG or PNG by the
/// extension. \throws SceneError for an unknown extension or an unwritable file (exceptions of
/// `draw` propagate; nothing usable is written then).
void writePicture(const std::string& path, int width, int height, const std::function<void(cairo_t*)>& draw);

/// "%g" of v, with |v| < 1e-12 printed as 0.
std::string formatNumber(double v);

/// A "nice" grid step (1, 2 or 5 times a power of ten) near raw > 0.
double niceStep(double raw);

void setColour(cairo_t* cr, const Rgb& c, double alpha = 1.0);
void setFont(cairo_t* cr, double size, bool bold = false);

/// Draws text with its reference point at (x, y): align 0 left, 0.5 centre, 1 right; baseline y.
void text(cairo_t* cr, const std::string& s, double x, double y, double align = 0.0);

/// Width of the text in the current font.
double textWidth(cairo_t* cr, const std::string& s);

/// Text with a white halo, for labels over the drawing.
void haloText(cairo_t* cr, const std::string& s, double x, double y, const Rgb& colour);

}  // namespace cli
}  // namespace fcl_quadric
