#pragma once
/// \file plot_command.h
/// `fcl_quadric plot KIND SCENE.json [--pair I,J] -o out.png|out.svg`: plots that explain the
/// continuous-collision algorithms, drawn with Cairo.
///  - ccd-function: the zero set of the CCD function F(u, t) = det((u - 1) A(t) - u B(t)) over
///    [0, 1]^2 of a moving ellipsoid pair (thesis ch.5, Fig. 18), F > 0 and F < 0 shaded, the
///    contact instants (ends of the collision intervals of continuousCollideEllipsoids) marked;
///  - discriminant: Delta(t) of a moving ellipse pair of a planar scene (thesis ch.2) with its real
///    roots and the collision intervals of collideMovingEllipses;
///  - timeline: one row per moving pair of a scene, the overlap intervals as bars.
/// Uses the algebra and continuous-collision layers only (no FCL).

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "fcl_quadric/continuous/ellipse_ccd.h"
#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fcl_quadric/scene.h"

namespace fcl_quadric {
namespace cli {

/// F on a grid of one segment: value(i, j) = F(i / nu, j / nt) in the segment's local time.
struct CcdFunctionGrid {
  double t_begin = 0.0;
  double t_end = 1.0;
  int nu = 0;
  int nt = 0;
  std::vector<double> values;  ///< (nu + 1) x (nt + 1), index i + (nu + 1) j
  double value(int i, int j) const { return values[static_cast<std::size_t>(i + (nu + 1) * j)]; }
  /// Global time of grid row j.
  double t(int j) const { return t_begin + (t_end - t_begin) * j / nt; }
};

/// Everything the ccd-function plot draws, in plot coordinates (u, global t).
struct CcdFunctionPlot {
  std::vector<CcdFunctionSegment> segments;  ///< ccdFunctionSegments()
  EllipsoidCcdResult result;                 ///< continuousCollideEllipsoids(), all intervals
  std::vector<CcdFunctionGrid> grids;        ///< one per segment
  /// The zero set F = 0 inside [0, 1]^2 as polylines (marching squares on the grids, every vertex
  /// refined by bisection on F along its grid edge, so |F| there is at rounding level).
  std::vector<std::vector<Eigen::Vector2d>> zero_set;
  /// Closed outlines of the region F > 0 of each segment (they may reach a cell beyond the
  /// segment's strip [0, 1] x [t_begin, t_end]: clip to it).
  struct Outline {
    std::size_t segment = 0;
    std::vector<Eigen::Vector2d> points;
  };
  std::vector<Outline> positive_region;
  /// Critical points (u*, t*) of the zero set at the contact instants t* in (0, 1): u* maximises
  /// u -> F(u, t*) (Theorem 5.1: a double root there).
  std::vector<Eigen::Vector2d> contacts;
};

/// F(u, t) at global time t from the segment containing t (at a break: the later segment).
/// \throws std::invalid_argument if segments is empty or u, t are not finite.
double ccdFunctionValue(const std::vector<CcdFunctionSegment>& segments, double u, double t);

/// Samples the CCD function of the pair: grids of about nu x nt cells over [0, 1]^2 (each segment
/// gets its share of the nt rows, at least 8), the zero set, the F > 0 region and the contacts.
/// \throws std::invalid_argument for nu < 2 or nt < 2, else as continuousCollideEllipsoids().
CcdFunctionPlot sampleCcdFunction(const MovingEllipsoid& a, const MovingEllipsoid& b, CcdInterpolation interpolation,
                                  int nu = 200, int nt = 300);

/// What the discriminant plot draws for a planar pair.
struct DiscriminantPlot {
  BernsteinPolynomial delta;  ///< ellipseDiscriminant()
  EllipseCcdResult result;    ///< collideMovingEllipses(AllContacts)
  std::vector<double> roots;  ///< real roots of Delta in [0, 1] (isolated and refined; midpoints of unresolved intervals)
};

/// \throws nothing for valid moving ellipses.
DiscriminantPlot sampleDiscriminant(const MovingEllipse2& a, const MovingEllipse2& b);

/// The pair "I,J" of a scene: I and J are object indices (0-based, in file order) or names.
/// \throws SceneError naming the bad value (malformed, unknown name, index out of range, I == J).
std::pair<std::size_t, std::size_t> parsePair(const Scene& scene, const std::string& text);

/// True when the scene object moves (a motion in 3D; a non-constant motion2 in 2D).
bool isMoving(const Scene& scene, std::size_t object);

/// Options of one plot.
struct PlotRequest {
  std::string kind;   ///< "ccd-function", "discriminant" or "timeline"
  std::string pair;   ///< "I,J" (ccd-function, discriminant); "" for timeline
  std::string title;  ///< scene name shown in the heading
};

/// Draws one plot of `scene` to `output` (SVG or PNG by the extension).
/// \throws SceneError for a bad kind, pair, scene or output path.
void plotScene(const Scene& scene, const PlotRequest& request, const std::string& output);

/// Runs `plot`: checks the output name, reads the scene and draws the plot.
/// \throws SceneError for bad input; nothing is written then.
void runPlot(const std::string& kind, const std::string& scene_path, const std::string& pair, const std::string& output);

/// Writes the CCD plots of the embedded example scenes (examples/scene_ccd.json and
/// scene_ccd_2d.json, built in) into `directory` (created if needed): ccd_function.png,
/// discriminant.png, timeline.png. \return the paths written, comma separated.
/// \throws SceneError if the directory or a picture cannot be written.
std::string writeDemoPlots(const std::string& directory);

}  // namespace cli
}  // namespace fcl_quadric
