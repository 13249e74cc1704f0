#pragma once
/// \file scene.h
/// The scene model of the fcl_quadric command-line program and its JSON reader.
///
/// Scene JSON (every field is checked; unknown fields are rejected so that typos are caught):
/// \code
/// {"objects": [{"name": "A",
///               "shape": {"type": "ellipsoid", "radii": [a, b, c]}   // semi-axes
///                      | {"type": "sphere", "radius": r}
///                      | {"type": "box", "size": [x, y, z]}          // full side lengths (fcl::Box)
///                      | {"type": "elliptic_cylinder", "radii": [a, b], "length": h}  // capped, axis z
///                      | {"type": "cylinder", "radius": r, "length": h}              // as fcl::Cylinder
///                      | {"type": "halfspace", "normal": [nx, ny, nz], "offset": d}  // n.x <= d
///                      | {"type": "quadric", "matrix": [[4 numbers] x 4],  // X^T Q X <= 0, X = (x, 1)
///                         "clip": [{"type": "halfspace", ...}, ...]}    // optional; must be bounded
///                      | {"type": "csg", "op": "union" | "intersection" | "difference",
///                         "children": [SHAPE (+ optional "pose"), ...]},  // difference: first - rest
///               "pose": {"translation": [x, y, z], "quaternion": [w, x, y, z]}},  // optional
///              ...],
///  "pairs": [["A", "B"], ...],                                       // optional
///  "ccd": {"interpolation": "rigid" | "affine", "all_intervals": true | false}}  // optional
/// \endcode
/// For `fcl_quadric ccd`, an object may carry a "motion" (body -> world over t in [0, 1]) instead of
/// a "pose":
/// \code
///   {"type": "linear", "from": POSE, "to": POSE}            // thesis §5.4.1 rigid interpolation
///   {"type": "keyframes", "times": [0, ..., 1], "poses": [POSE, ...]}
///   {"type": "polynomial", "matrix": [[e00, e01, e02, e03], ..., [0, 0, 0, w]]}
/// \endcode
/// where each matrix entry is a number (a constant) or an array of power-basis coefficients in t,
/// lowest degree first. A polynomial motion must have last row [0, 0, 0, w(t)] with w(t) and the
/// determinant of the linear part free of roots in [0, 1] (certified; otherwise the error names
/// "/objects/i/motion/matrix").
///
/// A planar scene has "dimension": 2; its objects are {"type": "ellipse", "radii": [a, b]} with
/// an optional pose {"translation": [x, y], "angle": theta} or a motion: {"type": "linear",
/// "from": POSE2, "to": POSE2} (translation linear, rotation by linear interpolation of the
/// half-angle unit vector (cos theta/2, sin theta/2): rational of degree 2) or {"type":
/// "polynomial", "matrix": 3x3 entries, last row [0, 0, w]} (thesis ch.2).
/// `pose` and both of its fields are optional (identity). `pairs` defaults to every unordered
/// pair in object order. A quaternion must have unit norm within tolerance::kQuaternionNorm
/// (relative) and is then normalised. Radii must lie in [tolerance::kMinRadius,
/// tolerance::kMaxLength] and translations within +-kMaxLength (the range Ellipsoid accepts), else
/// a SceneError names the value.

#include <cstddef>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json_fwd.hpp>

#include "fcl_quadric/algebra/polynomial_matrix3.h"
#include "fcl_quadric/continuous/motion_matrix.h"
#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {
namespace cli {

/// A scene-input problem: the JSON pointer (RFC 6901) of the offending value and a message.
/// The pointer is empty when the problem concerns the whole file (unreadable, not JSON).
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string pointer, std::string message);
  /// JSON pointer of the bad value, e.g. "/objects/2/shape/radii/1"; "" for the whole document.
  const std::string& pointer() const { return pointer_; }
  /// Description of the problem without the pointer.
  const std::string& message() const { return message_; }

 private:
  std::string pointer_;
  std::string message_;
};

enum class ShapeType { Ellipsoid, Sphere, Box, Ellipse, EllipticCylinder, Cylinder, Halfspace, Quadric, Csg };

/// The JSON spelling ("ellipsoid", "sphere", "box", "ellipse", "elliptic_cylinder", "cylinder",
/// "halfspace", "quadric", "csg").
const char* toString(ShapeType type);

/// A primitive shape in its body frame, centred at the body origin.
struct Shape {
  ShapeType type = ShapeType::Ellipsoid;
  /// Ellipsoid: semi-axes (a, b, c). Sphere: (r, r, r). Box: full side lengths, as fcl::Box.
  /// Ellipse (2D scenes): semi-axes (a, b, 0).
  Eigen::Vector3d dimensions = Eigen::Vector3d::Ones();
  /// Quadric shapes (elliptic_cylinder, cylinder, halfspace, quadric, csg): the solid in the body
  /// frame (quadric_region.h) and its certified local AABB (none for a half-space).
  std::shared_ptr<const QuadricRegion> region;
  std::optional<Box3> box;
};

/// True for the shapes answered by the composite-quadric engine (quadric_region.h).
bool isQuadricShape(const Shape& shape);

/// A named, posed shape. `pose` is X_WB: body frame to world frame, a proper rigid transform.
struct SceneObject {
  std::string name;
  Shape shape;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// The object's motion over [0, 1] when the scene gives one. `pose` is then the pose at t = 0
  /// for a rigid motion and the identity for an affine one (only ellipsoids and spheres may move
  /// affinely; their shape at t = 0 has other radii): use sceneAtTime() for a static snapshot.
  std::optional<PiecewiseMotion> motion;
  /// 2D scenes: the 3x3 homogeneous motion (body -> world in the plane), or the pose as a
  /// constant matrix when the object has no motion.
  PolynomialMatrix3 motion2 = PolynomialMatrix3(Eigen::Matrix3d::Identity());
};

/// Options of `fcl_quadric ccd` (the scene's "ccd" object).
struct CcdSettings {
  bool affine = false;        ///< "interpolation": "affine" (thesis §5.2) instead of "rigid"
  bool all_intervals = true;  ///< report every overlap interval (else only the first contact)
};

/// Objects and the pairs to test (indices into `objects`, first < second not required).
struct Scene {
  std::vector<SceneObject> objects;
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  CcdSettings ccd;
  /// 3, or 2 for a planar scene of ellipses ("dimension": 2; `fcl_quadric ccd` only).
  int dimension = 3;
};

/// Builds a Scene from a parsed JSON document.
/// \throws SceneError with the pointer of the first problem found.
Scene parseScene(const nlohmann::json& document);

/// Parses JSON text and builds the Scene. Malformed JSON gives a SceneError with an empty pointer
/// and the parse position (line, column) in the message; a number too large for a finite double
/// gives a SceneError with the pointer of that number.
Scene parseSceneText(const std::string& text);

/// Reads and parses a scene file.
/// \throws SceneError (empty pointer) if the file cannot be read, else as parseSceneText().
Scene readSceneFile(const std::string& path);

/// True for the shapes that are ellipsoids for the exact library (ellipsoid, sphere).
bool isEllipsoidal(const Shape& shape);

/// The scene with every moving object placed at time t (the motion code of `ccd`:
/// PiecewiseMotion::evaluate / PolynomialMatrix3::evaluate) and its motion removed: a rigid
/// motion gives the object its pose at t; an affine motion of an ellipsoid gives the image
/// ellipsoid (new radii and principal axes; an ellipsoid's affine image is an ellipsoid). A
/// planar scene's ellipses become ellipsoids in the plane z = 0 with a common third semi-axis
/// (their pairs classify as the ellipses do). Objects without a motion keep their pose. The
/// static commands (`check`, `render --time`) work on this snapshot.
/// \throws SceneError if t is not finite or not in [0, 1].
Scene sceneAtTime(const Scene& scene, double t);

/// The library's Ellipsoid for an ellipsoid or sphere object.
/// \pre isEllipsoidal(object.shape) (else std::invalid_argument).
Ellipsoid toEllipsoid(const SceneObject& object);

}  // namespace cli
}  // namespace fcl_quadric
