#include "fcl_quadric/scene.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <map>
#include <sstream>

#include <Eigen/SVD>
#include <nlohmann/json.hpp>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/continuous/ellipse_ccd.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace cli {

using nlohmann::json;

SceneError::SceneError(std::string pointer, std::string message)
    : std::runtime_error(pointer.empty() ? message : pointer + ": " + message),
      pointer_(std::move(pointer)),
      message_(std::move(message)) {}

const char* toString(ShapeType type) {
  switch (type) {
    case ShapeType::Ellipsoid: return "ellipsoid";
    case ShapeType::Sphere: return "sphere";
    case ShapeType::Box: return "box";
    case ShapeType::Ellipse: return "ellipse";
    case ShapeType::EllipticCylinder: return "elliptic_cylinder";
    case ShapeType::Cylinder: return "cylinder";
    case ShapeType::Halfspace: return "halfspace";
    case ShapeType::Quadric: return "quadric";
    case ShapeType::Csg: return "csg";
  }
  return "unknown";
}

bool isQuadricShape(const Shape& shape) { return static_cast<bool>(shape.region); }

bool isEllipsoidal(const Shape& shape) {
  return shape.type == ShapeType::Ellipsoid || shape.type == ShapeType::Sphere;
}

Ellipsoid toEllipsoid(const SceneObject& object) {
  if (!isEllipsoidal(object.shape)) {
    throw std::invalid_argument("object " + object.name + " is a " + toString(object.shape.type) +
                                ", not an ellipsoid");
  }
  return Ellipsoid(object.shape.dimensions, object.pose.linear(), object.pose.translation());
}

namespace {

[[noreturn]] void fail(const std::string& pointer, const std::string& message) {
  throw SceneError(pointer, message);
}

/// RFC 6901 reference token escaping: '~' -> "~0", '/' -> "~1".
std::string escapeToken(const std::string& token) {
  std::string out;
  for (char c : token) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

std::string child(const std::string& pointer, const std::string& key) {
  return pointer + "/" + escapeToken(key);
}

std::string child(const std::string& pointer, std::size_t index) {
  return pointer + "/" + std::to_string(index);
}

/// A JSON string as a quoted, escaped literal (safe to embed in a one-line message).
std::string jsonQuoted(const std::string& s) {
  return json(s).dump(-1, ' ', false, json::error_handler_t::replace);  // paths need not be UTF-8
}

/// The number as written in the document where possible ("-1", "0.5"); inf/nan spelled out.
std::string describeNumber(const json& node) {
  if (node.is_number_float()) {
    const double v = node.get<double>();
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0.0 ? "inf" : "-inf";
  }
  return node.dump();
}

void requireType(const json& node, const std::string& pointer, json::value_t type, const char* expected) {
  if (node.type() != type) fail(pointer, std::string("must be ") + expected + ", got " + node.type_name());
}

/// Any JSON number (integer or floating point; booleans are not numbers).
void requireNumber(const json& node, const std::string& pointer) {
  if (!node.is_number()) fail(pointer, std::string("must be a number, got ") + node.type_name());
}

/// The member `key` of `object`; fails with the member's pointer if it is missing.
const json& requireField(const json& object, const std::string& pointer, const char* key) {
  const auto it = object.find(key);
  if (it == object.end()) fail(child(pointer, key), "required field is missing");
  return *it;
}

void rejectUnknownFields(const json& object, const std::string& pointer,
                         std::initializer_list<const char*> allowed) {
  for (const auto& item : object.items()) {
    bool known = false;
    for (const char* a : allowed) known = known || item.key() == a;
    if (!known) {
      std::string list;
      for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      fail(child(pointer, item.key()), "unknown field (allowed here: " + list + ")");
    }
  }
}

/// A finite number.
double readNumber(const json& node, const std::string& pointer, const char* what) {
  requireNumber(node, pointer);
  const double v = node.get<double>();
  if (!std::isfinite(v)) fail(pointer, std::string(what) + " must be finite, got " + describeNumber(node));
  // A translation beyond the library's range would pass here and fail later as an internal error
  // (found by fuzz_scene).
  if (std::strcmp(what, "translation") == 0 && !(std::fabs(v) <= tolerance::kMaxLength)) {
    fail(pointer, "translation must be within +-1e+100, got " + describeNumber(node));
  }
  return v;
}

/// A finite number > 0; a radius also within the library's range [kMinRadius, kMaxLength] (an
/// Ellipsoid rejects others: found by fuzz_scene, a radius of 1e-300 was an internal error).
double readPositive(const json& node, const std::string& pointer, const char* what) {
  requireNumber(node, pointer);
  const double v = node.get<double>();
  if (!std::isfinite(v) || !(v > 0.0)) {
    fail(pointer, std::string(what) + " must be finite and > 0, got " + describeNumber(node));
  }
  if (std::strcmp(what, "radius") == 0 && !(v >= tolerance::kMinRadius && v <= tolerance::kMaxLength)) {
    fail(pointer, "radius must be in [1e-100, 1e+100], got " + describeNumber(node));
  }
  return v;
}

/// An array of exactly n elements.
void requireArray(const json& node, const std::string& pointer, std::size_t n, const char* expected) {
  requireType(node, pointer, json::value_t::array, expected);
  if (node.size() != n) {
    fail(pointer, "must have exactly " + std::to_string(n) + " elements, got " + std::to_string(node.size()));
  }
}

Eigen::Vector3d readPositive3(const json& node, const std::string& pointer, const char* what) {
  requireArray(node, pointer, 3, "an array of 3 numbers");
  Eigen::Vector3d v;
  for (std::size_t i = 0; i < 3; ++i) v[static_cast<Eigen::Index>(i)] = readPositive(node[i], child(pointer, i), what);
  return v;
}

Eigen::Isometry3d readPose(const json& node, const std::string& pointer);
Shape readShape(const json& node, const std::string& pointer, bool allow_pose = false);

Eigen::Vector3d readVector3(const json& node, const std::string& pointer, const char* what) {
  requireArray(node, pointer, 3, "an array of 3 numbers");
  Eigen::Vector3d v;
  for (std::size_t i = 0; i < 3; ++i) v[static_cast<Eigen::Index>(i)] = readNumber(node[i], child(pointer, i), what);
  return v;
}

/// {"type": "halfspace" (optional inside "clip"), "normal": [3], "offset": d}: n.x <= d.
QuadricRegion readHalfspace(const json& node, const std::string& pointer, bool type_optional) {
  requireType(node, pointer, json::value_t::object, "an object");
  rejectUnknownFields(node, pointer, {"type", "normal", "offset"});
  if (!type_optional || node.find("type") != node.end()) {
    const json& type = requireField(node, pointer, "type");
    if (!type.is_string() || type.get<std::string>() != "halfspace")
      fail(child(pointer, "type"), "a clip must be {\"type\": \"halfspace\", ...}");
  }
  const std::string np = child(pointer, "normal");
  const Eigen::Vector3d n = readVector3(requireField(node, pointer, "normal"), np, "normal component");
  if (!(n.norm() > 0.0)) fail(np, "normal must be non-zero");
  const double d = readNumber(requireField(node, pointer, "offset"), child(pointer, "offset"), "offset");
  return QuadricRegion::halfspace(n, d);
}

/// Local AABB of a region read from the scene; unbounded / empty regions are scene errors.
Box3 boundedBox(const QuadricRegion& region, const std::string& pointer, const Box3* hint) {
  try {
    return regionAabb(region, hint);
  } catch (const std::invalid_argument& e) {
    fail(pointer, e.what());
  }
}

Shape readQuadricShape(const json& node, const std::string& pointer, const std::string& name, bool allow_pose) {
  auto allowed = [&](std::initializer_list<const char*> fields) {
    std::vector<const char*> v(fields);
    if (allow_pose) v.push_back("pose");
    for (const auto& item : node.items()) {
      bool known = false;
      for (const char* a : v) known = known || item.key() == a;
      if (!known) {
        std::string list;
        for (const char* a : v) list += std::string(list.empty() ? "" : ", ") + a;
        fail(child(pointer, item.key()), "unknown field (allowed here: " + list + ")");
      }
    }
  };
  using Op = QuadricRegion::Op;
  Shape shape;
  if (name == "elliptic_cylinder" || name == "cylinder") {
    double a, b;
    if (name == "elliptic_cylinder") {
      allowed({"type", "radii", "length"});
      shape.type = ShapeType::EllipticCylinder;
      const std::string rp = child(pointer, "radii");
      const json& radii = requireField(node, pointer, "radii");
      requireArray(radii, rp, 2, "an array of 2 numbers");
      a = readPositive(radii[0], child(rp, 0), "radius");
      b = readPositive(radii[1], child(rp, 1), "radius");
    } else {
      allowed({"type", "radius", "length"});
      shape.type = ShapeType::Cylinder;
      a = b = readPositive(requireField(node, pointer, "radius"), child(pointer, "radius"), "radius");
    }
    const double h = readPositive(requireField(node, pointer, "length"), child(pointer, "length"), "length");
    shape.dimensions = Eigen::Vector3d(a, b, h);
    shape.region = std::make_shared<const QuadricRegion>(QuadricRegion::combine(
        Op::Intersection, {QuadricRegion::atom(quadric::ellipticCylinder(a, b)),
                           QuadricRegion::halfspace({0, 0, 1}, 0.5 * h), QuadricRegion::halfspace({0, 0, -1}, 0.5 * h)}));
    shape.box = Box3{Eigen::Vector3d(-a, -b, -0.5 * h), Eigen::Vector3d(a, b, 0.5 * h)};
  } else if (name == "halfspace") {
    allowed({"type", "normal", "offset"});
    shape.type = ShapeType::Halfspace;
    json copy = node;
    copy.erase("pose");
    shape.region = std::make_shared<const QuadricRegion>(readHalfspace(copy, pointer, false));
  } else if (name == "quadric") {
    allowed({"type", "matrix", "clip"});
    shape.type = ShapeType::Quadric;
    const std::string mp = child(pointer, "matrix");
    const json& m = requireField(node, pointer, "matrix");
    requireArray(m, mp, 4, "a 4x4 array of numbers");
    Eigen::Matrix4d Q;
    for (std::size_t i = 0; i < 4; ++i) {
      requireArray(m[i], child(mp, i), 4, "an array of 4 numbers");
      for (std::size_t j = 0; j < 4; ++j)
        Q(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = readNumber(m[i][j], child(child(mp, i), j), "matrix entry");
    }
    std::vector<QuadricRegion> parts;
    try {
      parts.push_back(QuadricRegion::atom(Q));
    } catch (const std::invalid_argument& e) {
      fail(mp, e.what());
    }
    if (const auto it = node.find("clip"); it != node.end()) {
      const std::string cp = child(pointer, "clip");
      requireType(*it, cp, json::value_t::array, "an array of half-spaces");
      for (std::size_t i = 0; i < it->size(); ++i) parts.push_back(readHalfspace((*it)[i], child(cp, i), true));
    }
    const QuadricRegion region = parts.size() == 1 ? parts[0] : QuadricRegion::combine(Op::Intersection, parts);
    shape.box = boundedBox(region, pointer, nullptr);
    shape.region = std::make_shared<const QuadricRegion>(region);
  } else {  // csg
    allowed({"type", "op", "children"});
    shape.type = ShapeType::Csg;
    const std::string op_pointer = child(pointer, "op");
    const json& op_node = requireField(node, pointer, "op");
    requireType(op_node, op_pointer, json::value_t::string, "a string");
    const std::string op_name = op_node.get<std::string>();
    Op op;
    if (op_name == "union") {
      op = Op::Union;
    } else if (op_name == "intersection") {
      op = Op::Intersection;
    } else if (op_name == "difference") {
      op = Op::Difference;
    } else {
      fail(op_pointer, "unknown CSG op " + jsonQuoted(op_name) + " (expected \"union\", \"intersection\" or \"difference\")");
    }
    const std::string cp = child(pointer, "children");
    const json& children = requireField(node, pointer, "children");
    requireType(children, cp, json::value_t::array, "an array of shapes");
    if (children.empty()) fail(cp, "a CSG operation needs at least one child");
    std::vector<QuadricRegion> parts;
    std::optional<Box3> hint;
    bool all_bounded = true;
    for (std::size_t i = 0; i < children.size(); ++i) {
      const std::string ip = child(cp, i);
      const Shape c = readShape(children[i], ip, /*allow_pose=*/true);
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      if (const auto it = children[i].find("pose"); it != children[i].end()) X = readPose(*it, child(ip, "pose"));
      std::optional<QuadricRegion> r;
      std::optional<Box3> box;
      if (c.region) {
        r = *c.region;
        box = c.box;
      } else {  // ellipsoid, sphere, box as regions
        if (c.type == ShapeType::Box) {
          const Eigen::Vector3d hh = 0.5 * c.dimensions;
          std::vector<QuadricRegion> planes;
          for (int k = 0; k < 3; ++k) {
            Eigen::Vector3d n = Eigen::Vector3d::Zero();
            n[k] = 1.0;
            planes.push_back(QuadricRegion::halfspace(n, hh[k]));
            planes.push_back(QuadricRegion::halfspace(-n, hh[k]));
          }
          r = QuadricRegion::combine(Op::Intersection, planes);
          box = Box3{-hh, hh};
        } else {
          r = QuadricRegion::atom(quadric::ellipsoid(c.dimensions));
          box = Box3{-c.dimensions, c.dimensions};
        }
      }
      parts.push_back(r->transformed(X.linear(), X.translation()));
      const std::optional<Box3> wb = box ? std::optional<Box3>(transformBox(*box, X.linear(), X.translation())) : std::nullopt;
      // Hint for the AABB search: as QuadricCSG (union: all bounded; intersection: any; difference: first).
      if (op == Op::Union) {
        all_bounded = all_bounded && wb.has_value();
        if (wb) hint = hint ? Box3{hint->lo.cwiseMin(wb->lo), hint->hi.cwiseMax(wb->hi)} : *wb;
      } else if (op == Op::Intersection) {
        if (wb) hint = hint ? Box3{hint->lo.cwiseMax(wb->lo), hint->hi.cwiseMin(wb->hi)} : *wb;
      } else if (i == 0) {
        hint = wb;
      }
    }
    if (op == Op::Union && !all_bounded) hint.reset();
    if (hint && hint->empty()) fail(pointer, "quadric region is empty (its bounding pieces do not meet)");
    const QuadricRegion region = QuadricRegion::combine(op, parts);
    shape.box = boundedBox(region, pointer, hint ? &*hint : nullptr);
    shape.region = std::make_shared<const QuadricRegion>(region);
  }
  return shape;
}

Shape readShape(const json& node, const std::string& pointer, bool allow_pose) {
  requireType(node, pointer, json::value_t::object, "an object");
  const json& type = requireField(node, pointer, "type");
  const std::string type_pointer = child(pointer, "type");
  requireType(type, type_pointer, json::value_t::string, "a string");
  const std::string name = type.get<std::string>();
  if (name == "elliptic_cylinder" || name == "cylinder" || name == "halfspace" || name == "quadric" || name == "csg")
    return readQuadricShape(node, pointer, name, allow_pose);
  Shape shape;
  auto rejectUnknownFields = [&](const json& n, const std::string& p, std::initializer_list<const char*> fields) {
    std::vector<const char*> v(fields);
    if (allow_pose) v.push_back("pose");
    for (const auto& item : n.items()) {
      bool known = false;
      for (const char* a : v) known = known || item.key() == a;
      if (!known) {
        std::string list;
        for (const char* a : v) list += std::string(list.empty() ? "" : ", ") + a;
        fail(child(p, item.key()), "unknown field (allowed here: " + list + ")");
      }
    }
  };
  if (name == "ellipsoid") {
    rejectUnknownFields(node, pointer, {"type", "radii"});
    shape.type = ShapeType::Ellipsoid;
    shape.dimensions = readPositive3(requireField(node, pointer, "radii"), child(pointer, "radii"), "radius");
  } else if (name == "sphere") {
    rejectUnknownFields(node, pointer, {"type", "radius"});
    shape.type = ShapeType::Sphere;
    const double r = readPositive(requireField(node, pointer, "radius"), child(pointer, "radius"), "radius");
    shape.dimensions = Eigen::Vector3d::Constant(r);
  } else if (name == "box") {
    rejectUnknownFields(node, pointer, {"type", "size"});
    shape.type = ShapeType::Box;
    shape.dimensions = readPositive3(requireField(node, pointer, "size"), child(pointer, "size"), "box size");
  } else {
    fail(type_pointer, "unknown shape type " + jsonQuoted(name) +
                           " (expected \"ellipsoid\", \"sphere\", \"box\", \"elliptic_cylinder\", \"cylinder\", "
                           "\"halfspace\", \"quadric\" or \"csg\")");
  }
  return shape;
}

Eigen::Isometry3d readPose(const json& node, const std::string& pointer) {
  requireType(node, pointer, json::value_t::object, "an object");
  rejectUnknownFields(node, pointer, {"translation", "quaternion"});
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (const auto it = node.find("translation"); it != node.end()) {
    const std::string p = child(pointer, "translation");
    requireArray(*it, p, 3, "an array of 3 numbers");
    for (std::size_t i = 0; i < 3; ++i) {
      pose.translation()[static_cast<Eigen::Index>(i)] = readNumber((*it)[i], child(p, i), "translation");
    }
  }
  if (const auto it = node.find("quaternion"); it != node.end()) {
    const std::string p = child(pointer, "quaternion");
    requireArray(*it, p, 4, "an array of 4 numbers [w, x, y, z]");
    double q[4];
    for (std::size_t i = 0; i < 4; ++i) q[i] = readNumber((*it)[i], child(p, i), "quaternion component");
    Eigen::Quaterniond quaternion(q[0], q[1], q[2], q[3]);
    const double norm = quaternion.norm();
    if (!(std::abs(norm - 1.0) <= tolerance::kQuaternionNorm)) {
      std::ostringstream os;
      os << "quaternion must have unit norm (relative tolerance " << tolerance::kQuaternionNorm << "), got norm "
         << json(norm).dump();
      fail(p, os.str());
    }
    quaternion.normalize();
    pose.linear() = quaternion.toRotationMatrix();
  }
  return pose;
}

/// A power-basis polynomial: a number (constant) or a non-empty array of coefficients.
Polynomial readPolynomial(const json& node, const std::string& pointer) {
  if (node.is_number()) return Polynomial{readNumber(node, pointer, "matrix entry")};
  requireType(node, pointer, json::value_t::array, "a number or an array of coefficients");
  if (node.empty()) fail(pointer, "coefficient array must not be empty");
  std::vector<double> c;
  for (std::size_t i = 0; i < node.size(); ++i) c.push_back(readNumber(node[i], child(pointer, i), "coefficient"));
  return Polynomial(std::move(c));
}

PiecewiseMotion readMotion(const json& node, const std::string& pointer) {
  requireType(node, pointer, json::value_t::object, "an object");
  const json& type = requireField(node, pointer, "type");
  const std::string type_pointer = child(pointer, "type");
  requireType(type, type_pointer, json::value_t::string, "a string");
  const std::string name = type.get<std::string>();
  if (name == "linear") {
    rejectUnknownFields(node, pointer, {"type", "from", "to"});
    const Eigen::Isometry3d from = readPose(requireField(node, pointer, "from"), child(pointer, "from"));
    const Eigen::Isometry3d to = readPose(requireField(node, pointer, "to"), child(pointer, "to"));
    return PiecewiseMotion(MotionMatrix::fromPoses(from, to));
  }
  if (name == "keyframes") {
    rejectUnknownFields(node, pointer, {"type", "times", "poses"});
    const json& times = requireField(node, pointer, "times");
    const std::string tp = child(pointer, "times");
    requireType(times, tp, json::value_t::array, "an array of times");
    if (times.size() < 2) fail(tp, "needs at least two times, got " + std::to_string(times.size()));
    std::vector<double> t;
    for (std::size_t i = 0; i < times.size(); ++i) {
      const double v = readNumber(times[i], child(tp, i), "time");
      if (i == 0 && v != 0.0) fail(child(tp, i), "the first time must be 0, got " + describeNumber(times[i]));
      if (i + 1 == times.size() && v != 1.0) fail(child(tp, i), "the last time must be 1, got " + describeNumber(times[i]));
      if (i > 0 && !(v > t.back())) fail(child(tp, i), "times must increase strictly, got " + describeNumber(times[i]));
      t.push_back(v);
    }
    const json& poses = requireField(node, pointer, "poses");
    const std::string pp = child(pointer, "poses");
    requireArray(poses, pp, t.size(), "an array of poses, one per time");
    std::vector<Eigen::Isometry3d> x;
    for (std::size_t i = 0; i < poses.size(); ++i) x.push_back(readPose(poses[i], child(pp, i)));
    return PiecewiseMotion::fromKeyframes(t, x);
  }
  if (name == "polynomial") {
    rejectUnknownFields(node, pointer, {"type", "matrix"});
    const json& matrix = requireField(node, pointer, "matrix");
    const std::string mp = child(pointer, "matrix");
    requireArray(matrix, mp, 4, "a 4x4 array of entries");
    PolynomialMatrix4 M;
    for (std::size_t i = 0; i < 4; ++i) {
      requireArray(matrix[i], child(mp, i), 4, "a row of 4 entries");
      for (std::size_t j = 0; j < 4; ++j) {
        M(static_cast<int>(i), static_cast<int>(j)) = readPolynomial(matrix[i][j], child(child(mp, i), j));
      }
    }
    try {
      return PiecewiseMotion(MotionMatrix::fromPolynomialMatrix(M));
    } catch (const std::invalid_argument& e) {
      fail(mp, e.what());
    }
  }
  fail(type_pointer, "unknown motion type " + jsonQuoted(name) + " (expected \"linear\", \"keyframes\" or \"polynomial\")");
}

CcdSettings readCcdSettings(const json& node, const std::string& pointer) {
  requireType(node, pointer, json::value_t::object, "an object");
  rejectUnknownFields(node, pointer, {"interpolation", "all_intervals"});
  CcdSettings settings;
  if (const auto it = node.find("interpolation"); it != node.end()) {
    const std::string p = child(pointer, "interpolation");
    requireType(*it, p, json::value_t::string, "a string");
    const std::string v = it->get<std::string>();
    if (v != "rigid" && v != "affine") fail(p, "must be \"rigid\" or \"affine\", got " + jsonQuoted(v));
    settings.affine = v == "affine";
  }
  if (const auto it = node.find("all_intervals"); it != node.end()) {
    requireType(*it, child(pointer, "all_intervals"), json::value_t::boolean, "true or false");
    settings.all_intervals = it->get<bool>();
  }
  return settings;
}

/// The object's non-empty "name".
std::string readName(const json& node, const std::string& pointer) {
  const json& name = requireField(node, pointer, "name");
  requireType(name, child(pointer, "name"), json::value_t::string, "a string");
  std::string text = name.get<std::string>();
  if (text.empty()) fail(child(pointer, "name"), "object name must not be empty");
  return text;
}

// --- Planar scenes (dimension 2) -------------------------------------------------------------

Eigen::Matrix3d readPose2(const json& node, const std::string& pointer) {
  requireType(node, pointer, json::value_t::object, "an object");
  rejectUnknownFields(node, pointer, {"translation", "angle"});
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  if (const auto it = node.find("translation"); it != node.end()) {
    const std::string p = child(pointer, "translation");
    requireArray(*it, p, 2, "an array of 2 numbers");
    for (std::size_t i = 0; i < 2; ++i) T(static_cast<Eigen::Index>(i), 2) = readNumber((*it)[i], child(p, i), "translation");
  }
  if (const auto it = node.find("angle"); it != node.end()) {
    const double a = readNumber(*it, child(pointer, "angle"), "angle");
    T.topLeftCorner<2, 2>() << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  }
  return T;
}

// Planar rigid motion between two poses: translation linear, rotation by the linear interpolation
// e(t) = (1-t) e0 + t e1 of the half-angle unit vectors (shorter arc), R = [[e0^2 - e1^2, -2 e0 e1],
// [2 e0 e1, e0^2 - e1^2]] / |e|^2: M = [[R~, |e|^2 p(t)], [0, |e|^2]].
PolynomialMatrix3 linearMotion2(const Eigen::Matrix3d& from, const Eigen::Matrix3d& to) {
  auto half = [](const Eigen::Matrix3d& T) {
    const double a = std::atan2(T(1, 0), T(0, 0));
    return Eigen::Vector2d(std::cos(0.5 * a), std::sin(0.5 * a));
  };
  const Eigen::Vector2d h0 = half(from);
  Eigen::Vector2d h1 = half(to);
  if (h0.dot(h1) < 0.0) h1 = -h1;
  const Polynomial e0{h0[0], h1[0] - h0[0]}, e1{h0[1], h1[1] - h0[1]};
  const Polynomial E = e0 * e0 + e1 * e1, c = e0 * e0 - e1 * e1, s = 2.0 * (e0 * e1);
  PolynomialMatrix3 M;
  M(0, 0) = c;
  M(0, 1) = -s;
  M(1, 0) = s;
  M(1, 1) = c;
  M(0, 2) = E * Polynomial{from(0, 2), to(0, 2) - from(0, 2)};
  M(1, 2) = E * Polynomial{from(1, 2), to(1, 2) - from(1, 2)};
  M(2, 2) = E;
  return M;
}

PolynomialMatrix3 readMotion2(const json& node, const std::string& pointer, double a, double b) {
  requireType(node, pointer, json::value_t::object, "an object");
  const json& type = requireField(node, pointer, "type");
  const std::string type_pointer = child(pointer, "type");
  requireType(type, type_pointer, json::value_t::string, "a string");
  const std::string name = type.get<std::string>();
  PolynomialMatrix3 M;
  std::string where = pointer;
  if (name == "linear") {
    rejectUnknownFields(node, pointer, {"type", "from", "to"});
    M = linearMotion2(readPose2(requireField(node, pointer, "from"), child(pointer, "from")),
                      readPose2(requireField(node, pointer, "to"), child(pointer, "to")));
  } else if (name == "polynomial") {
    rejectUnknownFields(node, pointer, {"type", "matrix"});
    const json& matrix = requireField(node, pointer, "matrix");
    where = child(pointer, "matrix");
    requireArray(matrix, where, 3, "a 3x3 array of entries");
    for (std::size_t i = 0; i < 3; ++i) {
      requireArray(matrix[i], child(where, i), 3, "a row of 3 entries");
      for (std::size_t j = 0; j < 3; ++j) {
        M(static_cast<int>(i), static_cast<int>(j)) = readPolynomial(matrix[i][j], child(child(where, i), j));
      }
    }
  } else {
    fail(type_pointer, "unknown planar motion type " + jsonQuoted(name) + " (expected \"linear\" or \"polynomial\")");
  }
  try {
    (void)MovingEllipse2(a, b, M);  // validates the motion (last row, w(t), det L(t) on [0, 1])
  } catch (const std::invalid_argument& e) {
    fail(where, e.what());
  }
  return M;
}

SceneObject readObject2(const json& node, const std::string& pointer) {
  requireType(node, pointer, json::value_t::object, "an object");
  rejectUnknownFields(node, pointer, {"name", "shape", "pose", "motion"});
  SceneObject object;
  object.name = readName(node, pointer);
  const json& shape = requireField(node, pointer, "shape");
  const std::string sp = child(pointer, "shape");
  requireType(shape, sp, json::value_t::object, "an object");
  const json& type = requireField(shape, sp, "type");
  requireType(type, child(sp, "type"), json::value_t::string, "a string");
  if (type.get<std::string>() != "ellipse") {
    fail(child(sp, "type"), "a 2D scene holds ellipses, got " + jsonQuoted(type.get<std::string>()) + " (expected \"ellipse\")");
  }
  rejectUnknownFields(shape, sp, {"type", "radii"});
  const json& radii = requireField(shape, sp, "radii");
  const std::string rp = child(sp, "radii");
  requireArray(radii, rp, 2, "an array of 2 numbers");
  object.shape.type = ShapeType::Ellipse;
  object.shape.dimensions = Eigen::Vector3d(readPositive(radii[0], child(rp, 0), "radius"),
                                            readPositive(radii[1], child(rp, 1), "radius"), 0.0);
  const auto pose = node.find("pose");
  if (pose != node.end()) object.motion2 = PolynomialMatrix3(readPose2(*pose, child(pointer, "pose")));
  if (const auto it = node.find("motion"); it != node.end()) {
    if (pose != node.end()) fail(child(pointer, "motion"), "an object has a \"pose\" or a \"motion\", not both");
    object.motion2 = readMotion2(*it, child(pointer, "motion"), object.shape.dimensions[0], object.shape.dimensions[1]);
  }
  return object;
}

/// M(t) / w(t): the homogeneous matrix of a motion at t, normalised to last entry 1.
Eigen::Matrix4d normalisedMotionAt(const PiecewiseMotion& motion, double t) {
  Eigen::Matrix4d H = motion.evaluate(t);
  return H / H(3, 3);  // w(t) != 0 on [0, 1] (MotionMatrix validates it)
}

/// The nearest rotation to A (polar factor): a rigid motion's L / w evaluated in floating point
/// is a rotation only to rounding (rigidity is detected to 1e-13 relative, motion_matrix.cpp).
Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& A) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  if ((U * svd.matrixV().transpose()).determinant() < 0.0) U.col(2) = -U.col(2);
  return U * svd.matrixV().transpose();
}

/// The pose at t of a rigid motion (PiecewiseMotion::isRigid()).
Eigen::Isometry3d rigidPoseAt(const PiecewiseMotion& motion, double t) {
  const Eigen::Matrix4d H = normalisedMotionAt(motion, t);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = nearestRotation(H.topLeftCorner<3, 3>());
  pose.translation() = H.topRightCorner<3, 1>();
  return pose;
}

/// Sets an ellipsoid object to the affine image { M u + p : |u| <= 1 } (principal axes).
void setEllipsoid(SceneObject* object, const Eigen::Matrix3d& M, const Eigen::Vector3d& p) {
  const Ellipsoid e = Ellipsoid::fromAffine(M, p);
  Eigen::Matrix3d R = e.rotation();
  if (R.determinant() < 0.0) R.col(2) = -R.col(2);  // the solid is symmetric: keep a proper rotation
  object->shape.type = ShapeType::Ellipsoid;
  object->shape.dimensions = e.radii();
  object->pose = Eigen::Isometry3d::Identity();
  object->pose.linear() = R;
  object->pose.translation() = p;
}

SceneObject readObject(const json& node, const std::string& pointer) {
  requireType(node, pointer, json::value_t::object, "an object");
  rejectUnknownFields(node, pointer, {"name", "shape", "pose", "motion"});
  SceneObject object;
  object.name = readName(node, pointer);
  object.shape = readShape(requireField(node, pointer, "shape"), child(pointer, "shape"));
  if (const auto it = node.find("pose"); it != node.end()) object.pose = readPose(*it, child(pointer, "pose"));
  if (const auto it = node.find("motion"); it != node.end()) {
    if (node.find("pose") != node.end()) fail(child(pointer, "motion"), "an object has a \"pose\" or a \"motion\", not both");
    object.motion = readMotion(*it, child(pointer, "motion"));
    if (object.motion->isRigid()) {
      object.pose = rigidPoseAt(*object.motion, 0.0);
    } else if (!isEllipsoidal(object.shape)) {
      // An affine map of a box or a quadric solid is not a posed copy of it; only an ellipsoid's
      // affine image is again an ellipsoid (sceneAtTime draws and checks it as one).
      fail(child(pointer, "motion"), std::string("the motion is not rigid (L(t) is not w(t) times a rotation), and a ") +
                                         toString(object.shape.type) + " may only move rigidly; affine motions are for ellipsoids and spheres");
    }
  }
  return object;
}

/// Records where a parse stopped, so that a number overflow (JSON cannot spell inf or nan; a
/// literal such as 1e999 is the only way to write a non-finite number) is reported at its
/// pointer. Used only after json::parse() has failed.
class PointerTracker : public nlohmann::json_sax<json> {
 public:
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    frames_.push_back({false, 0, ""});
    return true;
  }
  bool key(string_t& k) override {
    frames_.back().key = k;
    return true;
  }
  bool end_object() override {
    frames_.pop_back();
    return value();
  }
  bool start_array(std::size_t) override {
    frames_.push_back({true, 0, ""});
    return true;
  }
  bool end_array() override {
    frames_.pop_back();
    return value();
  }
  bool parse_error(std::size_t, const std::string& last_token, const nlohmann::detail::exception&) override {
    for (const Frame& f : frames_) pointer_ = f.array ? child(pointer_, f.index) : child(pointer_, f.key);
    token_ = last_token;
    return false;
  }
  const std::string& pointer() const { return pointer_; }
  const std::string& token() const { return token_; }

 private:
  struct Frame {
    bool array;
    std::size_t index;  ///< arrays: index of the element being parsed
    std::string key;    ///< objects: key of the member being parsed
  };
  bool value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return true;
  }
  std::vector<Frame> frames_;
  std::string pointer_;
  std::string token_;
};

/// nlohmann's message without its "[json.exception.xxx.nnn] " prefix.
std::string stripExceptionPrefix(const char* what) {
  std::string s(what);
  const auto close = s.find("] ");
  return close == std::string::npos ? s : s.substr(close + 2);
}

}  // namespace

Scene parseScene(const json& document) {
  const std::string root;
  requireType(document, root, json::value_t::object, "a JSON object with an \"objects\" array");
  rejectUnknownFields(document, root, {"objects", "pairs", "ccd", "dimension"});
  const json& objects = requireField(document, root, "objects");
  const std::string objects_pointer = child(root, "objects");
  requireType(objects, objects_pointer, json::value_t::array, "an array");

  Scene scene;
  if (const auto it = document.find("dimension"); it != document.end()) {
    const std::string p = child(root, "dimension");
    if (!it->is_number_integer() && !it->is_number_unsigned()) fail(p, std::string("must be 2 or 3, got ") + it->dump());
    const auto d = it->get<long long>();
    if (d != 2 && d != 3) fail(p, "must be 2 or 3, got " + it->dump());
    scene.dimension = static_cast<int>(d);
  }
  if (const auto it = document.find("ccd"); it != document.end()) {
    scene.ccd = readCcdSettings(*it, child(root, "ccd"));
    if (scene.dimension == 2 && scene.ccd.affine) fail(child(child(root, "ccd"), "interpolation"), "the affine interpolant applies to 3D scenes only");
  }
  std::map<std::string, std::size_t> index_of;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const std::string p = child(objects_pointer, i);
    SceneObject object = scene.dimension == 2 ? readObject2(objects[i], p) : readObject(objects[i], p);
    const auto [it, inserted] = index_of.emplace(object.name, i);
    if (!inserted) {
      fail(child(p, "name"), "duplicate object name " + jsonQuoted(object.name) + " (first used by " +
                                 child(objects_pointer, it->second) + ")");
    }
    scene.objects.push_back(std::move(object));
  }

  const auto pairs = document.find("pairs");
  if (pairs == document.end()) {
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      for (std::size_t j = i + 1; j < scene.objects.size(); ++j) scene.pairs.emplace_back(i, j);
    }
    return scene;
  }
  const std::string pairs_pointer = child(root, "pairs");
  requireType(*pairs, pairs_pointer, json::value_t::array, "an array of [name, name] pairs");
  for (std::size_t k = 0; k < pairs->size(); ++k) {
    const std::string p = child(pairs_pointer, k);
    const json& pair = (*pairs)[k];
    requireArray(pair, p, 2, "an array of two object names");
    std::size_t idx[2];
    for (std::size_t e = 0; e < 2; ++e) {
      const std::string pe = child(p, e);
      requireType(pair[e], pe, json::value_t::string, "an object name (string)");
      const std::string name = pair[e].get<std::string>();
      const auto it = index_of.find(name);
      if (it == index_of.end()) fail(pe, "unknown object " + jsonQuoted(name));
      idx[e] = it->second;
    }
    if (idx[0] == idx[1]) fail(p, "pair names object " + jsonQuoted(scene.objects[idx[0]].name) + " twice");
    scene.pairs.emplace_back(idx[0], idx[1]);
  }
  return scene;
}

Scene parseSceneText(const std::string& text) {
  json document;
  try {
    document = json::parse(text);
  } catch (const json::parse_error& e) {
    fail("", "malformed JSON: " + stripExceptionPrefix(e.what()));
  } catch (const json::out_of_range&) {
    // The only out_of_range the parser raises: a number literal overflowing double (error 406).
    PointerTracker tracker;
    json::sax_parse(text, &tracker);
    fail(tracker.pointer(), "number " + tracker.token() + " is out of the range of double (values must be finite)");
  }
  return parseScene(document);
}

Scene readSceneFile(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) fail("", "cannot open scene file " + jsonQuoted(path) + ": " + std::strerror(errno));
  std::string text;
  char buffer[65536];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, file)) > 0) text.append(buffer, n);
  const bool read_error = std::ferror(file) != 0;
  const int read_errno = errno;
  std::fclose(file);
  if (read_error) fail("", "cannot read scene file " + jsonQuoted(path) + ": " + std::strerror(read_errno));
  try {
    return parseSceneText(text);
  } catch (const SceneError& e) {
    if (!e.pointer().empty()) throw;
    fail("", path + ": " + e.message());  // name the file in whole-document errors
  }
}

Scene sceneAtTime(const Scene& scene, double t) {
  if (!std::isfinite(t) || t < 0.0 || t > 1.0) {
    std::ostringstream v;
    v.precision(17);
    v << t;
    fail("", "the time must be a number in [0, 1], got " + v.str());
  }
  Scene out = scene;
  if (scene.dimension == 2) {
    // Ellipses in z = 0 as ellipsoids with a common third semi-axis: two such ellipsoids meet
    // exactly when the ellipses do (the best height is z = 0 for both).
    for (SceneObject& o : out.objects) {
      Eigen::Matrix3d H = o.motion2.evaluate(t);
      H /= H(2, 2);
      Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
      M.topLeftCorner<2, 2>() = H.topLeftCorner<2, 2>() * o.shape.dimensions.head<2>().asDiagonal();
      M(2, 2) = 1.0;
      setEllipsoid(&o, M, Eigen::Vector3d(H(0, 2), H(1, 2), 0.0));
      o.motion.reset();
    }
    return out;
  }
  for (SceneObject& o : out.objects) {
    if (!o.motion) continue;
    if (o.motion->isRigid()) {
      o.pose = rigidPoseAt(*o.motion, t);
    } else {  // an ellipsoid (readObject rejects affine motions of other shapes)
      const Eigen::Matrix4d H = normalisedMotionAt(*o.motion, t);
      setEllipsoid(&o, H.topLeftCorner<3, 3>() * o.shape.dimensions.asDiagonal(), H.topRightCorner<3, 1>());
    }
    o.motion.reset();
  }
  return out;
}

}  // namespace cli
}  // namespace fcl_quadric
