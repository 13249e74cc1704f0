#include "fcl_quadric/fcl/pair_cache.h"

#include <stdexcept>

#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>

#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/quadric_solver.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"

namespace fcl_quadric {

namespace {

/// The ellipsoid of an object whose geometry is an fcl::Ellipsoid or fcl::Sphere, or false.
bool asQuadric(const fcl::CollisionObject<double>* o, const char* which, Ellipsoid* out) {
  const fcl::CollisionGeometry<double>* g = o->collisionGeometry().get();
  if (g == nullptr) return false;
  switch (g->getNodeType()) {
    case fcl::GEOM_ELLIPSOID:
      *out = detail::asEllipsoid(*static_cast<const fcl::Ellipsoid<double>*>(g), o->getTransform(), which);
      return true;
    case fcl::GEOM_SPHERE:
      *out = detail::asEllipsoid(*static_cast<const fcl::Sphere<double>*>(g), o->getTransform(), which);
      return true;
    default:
      return false;
  }
}

}  // namespace

std::size_t PairCache::collide(const fcl::CollisionObject<double>* o1, const fcl::CollisionObject<double>* o2,
                               const fcl::CollisionRequest<double>& request,
                               fcl::CollisionResult<double>& result) {
  Ellipsoid e1 = Ellipsoid::sphere(1.0, Eigen::Vector3d::Zero()), e2 = e1;
  if (o1 == nullptr || o2 == nullptr || !asQuadric(o1, "o1", &e1) || !asQuadric(o2, "o2", &e2)) {
    return fcl_quadric::collide(o1, o2, request, result);  // validates and handles every other pair
  }
  ++queries_;
  // Canonical key order so that (o1, o2) and (o2, o1) share an entry.
  const bool swap = std::less<const void*>()(o2, o1);
  const Key key{swap ? static_cast<const void*>(o2) : o1, swap ? static_cast<const void*>(o1) : o2};
  const Ellipsoid& ea = swap ? e2 : e1;
  const Ellipsoid& eb = swap ? e1 : e2;
  const void* ga = (swap ? o2 : o1)->collisionGeometry().get();
  const void* gb = (swap ? o1 : o2)->collisionGeometry().get();
  auto it = entries_.find(key);
  if (it != entries_.end() && it->second.geometry_a == ga && it->second.geometry_b == gb &&
      it->second.plane.separates(ea, eb)) {
    ++plane_hits_;
    return 0;  // certified separate: no contact
  }
  const SeparationCertificate cert = classifyEllipsoids(ea, eb);
  if (cert.status == Separation::Separated) {
    const std::optional<CachedPlane> plane = CachedPlane::fromPlane(certificatePlane(cert, ea, eb));
    if (plane) {
      entries_[key] = Entry{*plane, ga, gb};
    } else if (it != entries_.end()) {
      entries_.erase(it);
    }
    return 0;
  }
  if (it != entries_.end()) entries_.erase(it);
  // Colliding: the front door fills contacts with FCL's semantics.
  return fcl_quadric::collide(o1, o2, request, result);
}

void PairCache::invalidate(const fcl::CollisionObject<double>* o) {
  for (auto it = entries_.begin(); it != entries_.end();) {
    if (it->first.a == o || it->first.b == o) it = entries_.erase(it); else ++it;
  }
}

bool coherentCollisionFunction(fcl::CollisionObject<double>* o1, fcl::CollisionObject<double>* o2, void* data) {
  if (data == nullptr) throw std::invalid_argument("coherentCollisionFunction: data is null");
  auto* d = static_cast<CoherentCollisionData*>(data);
  if (d->cache == nullptr) throw std::invalid_argument("coherentCollisionFunction: data->cache is null");
  if (d->done) return true;
  d->cache->collide(o1, o2, d->request, d->result);
  if (!d->request.enable_cost && d->result.isCollision() && d->result.numContacts() >= d->request.num_max_contacts)
    d->done = true;
  return d->done;
}

}  // namespace fcl_quadric
