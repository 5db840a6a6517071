// The dispatcher: a superellipsoid pair goes to the pair kind that recognises the other
// geometry: a mesh or point cloud (many contacts), or a shape (one hit, written here into FCL's
// results); a pair that none recognises gets FCL's "not supported" warning. A new shape pair
// kind is a file beside this one (docs/design.md → "Adding a pair") and a case in shapeHit.

#include "fcl_glue/pairs/pairs.h"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <string>

#include "common/coordinate_range.h"
#include "common/invalid_argument.h"
#include "fcl_glue/pairs/capsule_pair.h"
#include "fcl_glue/pairs/halfspace_pair.h"
#include "fcl_glue/pairs/mesh_pair.h"
#include "fcl_glue/pairs/pair.h"
#include "fcl_glue/pairs/polytope_pair.h"
#include "fcl_glue/pairs/round_pair.h"
#include "fcl_glue/pairs/smooth_pair.h"
#include "fcl_glue/pairs/sphere_pair.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

void warnUnsupported(const char* what, int node_type1, int node_type2) {
  std::cerr << "Warning: " << what << " function between node type " << node_type1
            << " and node type " << node_type2 << " is not supported\n";
}

/// The shape pair kind's hit, chosen by the other geometry's node type (each kind checks the
/// dynamic type too: a user's geometry may report any node type).
template <typename S>
std::optional<PairHit<S>> shapeHit(const Pair<S>& pair) {
  switch (pair.other_type) {
    case fcl::GEOM_SPHERE:
      return sphereHit(pair);
    case fcl::GEOM_HALFSPACE:
    case fcl::GEOM_PLANE:
      return halfspaceHit(pair);
    case fcl::GEOM_ELLIPSOID:
    case fcl::BV_UNKNOWN:  // another superellipsoid
      return smoothHit(pair);
    case fcl::GEOM_CAPSULE:
      return capsuleHit(pair);
    case fcl::GEOM_BOX:
    case fcl::GEOM_CONVEX:
    case fcl::GEOM_TRIANGLE:
      return polytopeHit(pair);
    case fcl::GEOM_CYLINDER:
    case fcl::GEOM_CONE:
      return roundHit(pair);
    default:
      return std::nullopt;
  }
}

/// Refuses another shape whose parameters are not finite, a negative length, or a length or
/// coordinate beyond a sixteenth of the largest finite value (its features' coordinates, sums
/// of a few of them, must stay finite; docs/hardening.md → "Bad input").
template <typename S>
void checkOther(const char* where, const Pair<S>& pair) {
  const S limit = std::numeric_limits<S>::max() / 16;
  auto length = [&](const char* name, S v) {
    if (!(v >= S(0) && v <= limit)) {
      throwInvalidArgument(
          where, std::string("the other shape's ") + name + " must be finite, >= 0 and <= max/16",
          v);
    }
  };
  auto point = [&](const char* name, const Vector3<S>& p) {
    if (!p.allFinite() || !(p.cwiseAbs().maxCoeff() <= limit)) {
      throwInvalidArgument(
          where,
          std::string("the other shape's ") + name + " must be finite, each |coordinate| <= max/16",
          p);
    }
  };
  auto round = [&](const auto& x) {  // capsule, cylinder, cone
    length("radius", x.radius);
    length("lz", x.lz);
  };
  auto plane = [&](const auto& x) {  // halfspace, plane
    point("normal n", x.n);
    length("|d|", std::abs(x.d));
  };
  switch (pair.other_type) {
    case fcl::GEOM_SPHERE:
      if (const auto* x = otherAs<fcl::Sphere<S>>(pair, fcl::GEOM_SPHERE)) {
        length("radius", x->radius);
      }
      break;
    case fcl::GEOM_ELLIPSOID:
      if (const auto* x = otherAs<fcl::Ellipsoid<S>>(pair, fcl::GEOM_ELLIPSOID)) {
        for (int i = 0; i < 3; ++i) length("radii", x->radii[i]);
      }
      break;
    case fcl::GEOM_BOX:
      if (const auto* x = otherAs<fcl::Box<S>>(pair, fcl::GEOM_BOX)) {
        for (int i = 0; i < 3; ++i) length("side", x->side[i]);
      }
      break;
    case fcl::GEOM_CAPSULE:
      if (const auto* x = otherAs<fcl::Capsule<S>>(pair, fcl::GEOM_CAPSULE)) round(*x);
      break;
    case fcl::GEOM_CYLINDER:
      if (const auto* x = otherAs<fcl::Cylinder<S>>(pair, fcl::GEOM_CYLINDER)) round(*x);
      break;
    case fcl::GEOM_CONE:
      if (const auto* x = otherAs<fcl::Cone<S>>(pair, fcl::GEOM_CONE)) round(*x);
      break;
    case fcl::GEOM_HALFSPACE:
      if (const auto* x = otherAs<fcl::Halfspace<S>>(pair, fcl::GEOM_HALFSPACE)) plane(*x);
      break;
    case fcl::GEOM_PLANE:
      if (const auto* x = otherAs<fcl::Plane<S>>(pair, fcl::GEOM_PLANE)) plane(*x);
      break;
    case fcl::GEOM_CONVEX:
      if (const auto* x = otherAs<fcl::Convex<S>>(pair, fcl::GEOM_CONVEX)) {
        for (const Vector3<S>& v : x->getVertices()) point("vertex", v);
      }
      break;
    case fcl::GEOM_TRIANGLE:
      if (const auto* x = otherAs<fcl::TriangleP<S>>(pair, fcl::GEOM_TRIANGLE)) {
        point("vertex a", x->a);
        point("vertex b", x->b);
        point("vertex c", x->c);
      }
      break;
    default:
      break;
  }
}

/// FCL's BVH models (BV_AABB … BV_KDOP24 are contiguous in FCL's NODE_TYPE).
template <typename S>
bool isMesh(const Pair<S>& pair) {
  return pair.other_type >= fcl::BV_AABB && pair.other_type <= fcl::BV_KDOP24;
}

}  // namespace

template <typename S>
bool involvesSuperellipsoid(const fcl::CollisionGeometry<S>* o1,
                            const fcl::CollisionGeometry<S>* o2) {
  return asSuperellipsoid(o1) != nullptr || asSuperellipsoid(o2) != nullptr;
}

template <typename S>
S pairDistance(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
               const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
               const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
  checkPose("superellipsoid distance", "of o1", tf1);
  checkPose("superellipsoid distance", "of o2", tf2);
  const Pair<S> pair = makePair(o1, tf1, o2, tf2);
  if (pair.shape != nullptr) {
    if (isMesh(pair)) {
      if (const std::optional<S> answer = meshDistance(pair, request, result)) return *answer;
    }
    if (!isMesh(pair)) checkOther("superellipsoid distance", pair);
    if (const std::optional<PairHit<S>> hit = shapeHit(pair)) {
      updateDistance(pair, *hit, request, result);
      return result.min_distance;
    }
  }
  warnUnsupported("distance", o1->getNodeType(), o2->getNodeType());
  return std::numeric_limits<S>::max();
}

template <typename S>
std::size_t pairCollide(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                        const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
                        const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result) {
  checkPose("superellipsoid collide", "of o1", tf1);
  checkPose("superellipsoid collide", "of o2", tf2);
  const Pair<S> pair = makePair(o1, tf1, o2, tf2);
  if (pair.shape != nullptr) {
    if (request.num_max_contacts <= result.numContacts()) return result.numContacts();
    const std::size_t room = request.num_max_contacts - result.numContacts();
    if (isMesh(pair) && meshCollide(pair, request, room, result)) return result.numContacts();
    if (!isMesh(pair)) checkOther("superellipsoid collide", pair);
    if (const std::optional<PairHit<S>> hit = shapeHit(pair)) {
      // One contact where they overlap, halfway between the two surfaces.
      if (hit->distance < S(0)) {
        addContact(pair, *hit, Vector3<S>(S(0.5) * (hit->on_shape + hit->on_other)),
                   request.enable_contact, result);
      }
      return result.numContacts();
    }
  }
  warnUnsupported("collision", o1->getNodeType(), o2->getNodeType());
  return 0;
}

#define FSE_INSTANTIATE_PAIRS(S)                                                                \
  template bool involvesSuperellipsoid(const fcl::CollisionGeometry<S>*,                        \
                                       const fcl::CollisionGeometry<S>*);                       \
  template S pairDistance(const fcl::CollisionGeometry<S>*, const fcl::Transform3<S>&,          \
                          const fcl::CollisionGeometry<S>*, const fcl::Transform3<S>&,          \
                          const fcl::DistanceRequest<S>&, fcl::DistanceResult<S>&);             \
  template std::size_t pairCollide(const fcl::CollisionGeometry<S>*, const fcl::Transform3<S>&, \
                                   const fcl::CollisionGeometry<S>*, const fcl::Transform3<S>&, \
                                   const fcl::CollisionRequest<S>&, fcl::CollisionResult<S>&);
FSE_INSTANTIATE_PAIRS(float)
FSE_INSTANTIATE_PAIRS(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
