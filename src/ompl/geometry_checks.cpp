// The geometries the planning layer accepts, with their parameters checked (geometry_checks.h).
#include "geometry_checks.h"
#include "finite.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>

#include "fcl_quadric/fcl/quadric_shapes.h"

namespace fcl_quadric {
namespace planning {
namespace detail {

namespace {

[[noreturn]] void reject(const std::string& where, const std::string& what) {
  throw std::invalid_argument(where + ": " + what);
}

std::string valueText(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

/// `value` must be finite and > 0 (or >= 0 when zero_ok).
void requirePositive(double value, const char* name, const std::string& where, bool zero_ok = false) {
  if (!std::isfinite(value) || value < 0.0 || (value == 0.0 && !zero_ok))
    reject(where, std::string(name) + " must be finite and " + (zero_ok ? ">= 0" : "> 0") + ", got " + valueText(value));
}

template <typename BV>
void checkMesh(const fcl::CollisionGeometry<double>& g, const std::string& where) {
  const auto& m = static_cast<const fcl::BVHModel<BV>&>(g);
  if (m.build_state != fcl::BVH_BUILD_STATE_PROCESSED)
    reject(where, "the BVH mesh is not finished (call endModel() before adding it)");
  if (m.getModelType() != fcl::BVH_MODEL_TRIANGLES) reject(where, "the BVH model is not a triangle mesh");
  for (int i = 0; i < m.num_vertices; ++i)
    if (!allFinite(m.vertices[i])) reject(where, "mesh vertex " + std::to_string(i) + " is not finite");
}

}  // namespace

void checkSupportedGeometry(const fcl::CollisionGeometry<double>& g, const std::string& where) {
  if (dynamic_cast<const QuadricShape<double>*>(&g) != nullptr) return;  // checked when it was made
  switch (g.getNodeType()) {
    case fcl::GEOM_SPHERE: requirePositive(static_cast<const fcl::Sphere<double>&>(g).radius, "sphere radius", where); return;
    case fcl::GEOM_ELLIPSOID: {
      const Eigen::Vector3d& r = static_cast<const fcl::Ellipsoid<double>&>(g).radii;
      for (int i = 0; i < 3; ++i) requirePositive(r[i], ("ellipsoid radius " + std::to_string(i)).c_str(), where);
      return;
    }
    case fcl::GEOM_BOX: {
      const Eigen::Vector3d& s = static_cast<const fcl::Box<double>&>(g).side;
      for (int i = 0; i < 3; ++i) requirePositive(s[i], ("box side " + std::to_string(i)).c_str(), where);
      return;
    }
    case fcl::GEOM_CAPSULE: {
      const auto& c = static_cast<const fcl::Capsule<double>&>(g);
      requirePositive(c.radius, "capsule radius", where);
      requirePositive(c.lz, "capsule length", where, true);
      return;
    }
    case fcl::GEOM_CYLINDER: {
      const auto& c = static_cast<const fcl::Cylinder<double>&>(g);
      requirePositive(c.radius, "cylinder radius", where);
      requirePositive(c.lz, "cylinder length", where);
      return;
    }
    case fcl::GEOM_CONE: {
      const auto& c = static_cast<const fcl::Cone<double>&>(g);
      requirePositive(c.radius, "cone radius", where);
      requirePositive(c.lz, "cone length", where);
      return;
    }
    case fcl::GEOM_PLANE:
    case fcl::GEOM_HALFSPACE: {
      const bool plane = g.getNodeType() == fcl::GEOM_PLANE;
      const Eigen::Vector3d n = plane ? static_cast<const fcl::Plane<double>&>(g).n
                                      : static_cast<const fcl::Halfspace<double>&>(g).n;
      const double d = plane ? static_cast<const fcl::Plane<double>&>(g).d : static_cast<const fcl::Halfspace<double>&>(g).d;
      if (!allFinite(n) || n.squaredNorm() == 0.0 || !std::isfinite(d))
        reject(where, std::string(plane ? "plane" : "half-space") + " needs a finite non-zero normal and a finite offset");
      return;
    }
    case fcl::GEOM_CONVEX: {
      const auto& c = static_cast<const fcl::Convex<double>&>(g);
      const auto& v = c.getVertices();
      if (v.empty()) reject(where, "the convex shape has no vertices");
      for (std::size_t i = 0; i < v.size(); ++i)
        if (!allFinite(v[i])) reject(where, "convex vertex " + std::to_string(i) + " is not finite");
      return;
    }
    case fcl::GEOM_OCTREE: return;
    case fcl::BV_AABB: checkMesh<fcl::AABB<double>>(g, where); return;
    case fcl::BV_OBB: checkMesh<fcl::OBB<double>>(g, where); return;
    case fcl::BV_RSS: checkMesh<fcl::RSS<double>>(g, where); return;
    case fcl::BV_kIOS: checkMesh<fcl::kIOS<double>>(g, where); return;
    case fcl::BV_OBBRSS: checkMesh<fcl::OBBRSS<double>>(g, where); return;
    case fcl::BV_KDOP16: checkMesh<fcl::KDOP<double, 16>>(g, where); return;
    case fcl::BV_KDOP18: checkMesh<fcl::KDOP<double, 18>>(g, where); return;
    case fcl::BV_KDOP24: checkMesh<fcl::KDOP<double, 24>>(g, where); return;
    case fcl::GEOM_TRIANGLE:
      reject(where,
             "fcl::TriangleP is not supported (FCL 0.7 has no collision or distance function for it against most "
             "shapes, so it would never be in contact): use an fcl::BVHModel of one triangle");
    default: reject(where, "unsupported geometry (FCL node type " + std::to_string(int(g.getNodeType())) + ")");
  }
}

}  // namespace detail
}  // namespace planning
}  // namespace fcl_quadric
