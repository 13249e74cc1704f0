#pragma once
/// \file render_command.h
/// `fcl_quadric render SCENE.json -o out.svg|out.png [--time t]`: the scene drawn with Cairo in
/// three orthographic views (top XY, front XZ, side YZ; a planar scene gets its one XY view), with
/// the pairs classified exactly as `check` does (evaluatePair): objects of colliding pairs in red,
/// contact / witness points marked, separating planes of separated ellipsoid pairs drawn as their
/// trace lines.

#include <string>
#include <vector>

#include "fcl_quadric/demo_command.h"
#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/scene.h"

namespace fcl_quadric {
namespace cli {

struct RenderOptions {
  /// Heading of the picture (e.g. the scene file name); the time is appended.
  std::string title = "scene";
  double time = 0.0;
  /// Replaces "t = <time>" in the heading when not empty.
  std::string time_text;
  /// Appended to the subtitle (e.g. which pairs were classified).
  std::string pairs_note;
  /// Draw separating planes and witness segments of separated pairs (off for crowded scenes).
  bool separation_details = true;
};

/// Size in pixels of the picture of a scene of the given dimension (3: three views; 2: one view).
struct ImageSize {
  int width = 0;
  int height = 0;
};
ImageSize renderImageSize(int dimension);

/// Where the world point appears in the picture of `scene` (pixels from the top-left corner) in
/// view `view`: 0 top (XY), 1 front (XZ), 2 side (YZ); a planar scene has view 0 only.
/// \throws std::out_of_range for a view the picture does not have.
Eigen::Vector2d pixelOf(const Scene& scene, int view, const Eigen::Vector3d& world);

/// Draws the scene (already at its time; see sceneAtTime) to `path`, SVG or PNG by the extension
/// (".svg" / ".png", case-insensitive).
/// \throws SceneError for an unknown extension or an unwritable file.
void renderScene(const Scene& scene, const RenderOptions& options, const std::string& path);

/// Runs `render`: reads the scene, places it at `time` and draws it to `output`.
/// \throws SceneError for a bad scene, time or output path; nothing is written then.
void runRender(const std::string& scene_path, const std::string& output, double time);

/// A scene of the given ellipsoids named E00, E01, ... whose pairs are those with overlapping
/// bounding spheres (the demo's broad phase).
Scene ellipsoidScene(const std::vector<Ellipsoid>& ellipsoids);

/// Writes the demo's first and last frame as PNG pictures (demo_first_frame.png,
/// demo_last_frame.png) into `directory`, creating it if needed.
/// \return the text for the demo's "pictures:" line (the directory and file names).
/// \throws SceneError if the directory or a picture cannot be written.
std::string writeDemoPictures(const DemoSummary& summary, const std::string& directory);

}  // namespace cli
}  // namespace fcl_quadric
