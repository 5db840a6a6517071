#include "superellipsoid_pairs.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>

#include <iostream>
#include <limits>

#include "fcl_superellipsoid/point_distance.h"
#include "vertex_traversal.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

/// The pair as (superellipsoid, other), remembering which argument the shape was.
template <typename S>
struct Pair {
  const Superellipsoid<S>* shape = nullptr;
  const fcl::Transform3<S>* X_WS = nullptr;
  const fcl::CollisionGeometry<S>* other = nullptr;
  const fcl::Transform3<S>* X_WO = nullptr;
  bool shape_first = true;  // the shape is o1
};

template <typename S>
Pair<S> makePair(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                 const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2) {
  const auto* s1 = dynamic_cast<const Superellipsoid<S>*>(o1);
  const auto* s2 = dynamic_cast<const Superellipsoid<S>*>(o2);
  if (s1 != nullptr && s2 == nullptr) return {s1, &tf1, o2, &tf2, true};
  if (s2 != nullptr && s1 == nullptr) return {s2, &tf2, o1, &tf1, false};
  return {};  // both or neither: not a pair handled here
}

void warnUnsupported(const char* what, int node_type1, int node_type2) {
  std::cerr << "Warning: " << what << " function between node type " << node_type1
            << " and node type " << node_type2 << " is not supported\n";
}

/// Calls f(model) with the BVHModel<BV> behind g for FCL's eight BV types; false if g is
/// not one of them.
template <typename S, typename F>
bool visitBvh(const fcl::CollisionGeometry<S>* g, F&& f) {
  if (g->getObjectType() != fcl::OT_BVH) return false;
  auto as = [&](auto* tag) {
    using BV = std::remove_pointer_t<decltype(tag)>;
    const auto* model = dynamic_cast<const fcl::BVHModel<BV>*>(g);
    if (model == nullptr) return false;
    f(*model);
    return true;
  };
  switch (g->getNodeType()) {
    case fcl::BV_AABB:
      return as(static_cast<fcl::AABB<S>*>(nullptr));
    case fcl::BV_OBB:
      return as(static_cast<fcl::OBB<S>*>(nullptr));
    case fcl::BV_RSS:
      return as(static_cast<fcl::RSS<S>*>(nullptr));
    case fcl::BV_kIOS:
      return as(static_cast<fcl::kIOS<S>*>(nullptr));
    case fcl::BV_OBBRSS:
      return as(static_cast<fcl::OBBRSS<S>*>(nullptr));
    case fcl::BV_KDOP16:
      return as(static_cast<fcl::KDOP<S, 16>*>(nullptr));
    case fcl::BV_KDOP18:
      return as(static_cast<fcl::KDOP<S, 18>*>(nullptr));
    case fcl::BV_KDOP24:
      return as(static_cast<fcl::KDOP<S, 24>*>(nullptr));
    default:
      return false;
  }
}

/// A hit between the shape and the other geometry, in world coordinates: the point on the
/// other geometry, the point on the shape, the shape's outward normal, the other's primitive.
template <typename S>
struct PairHit {
  S distance;
  Vector3<S> on_other, on_shape, normal;
  int other_primitive;
};

template <typename S>
PairHit<S> fromVertex(const VertexHit<S>& h) {
  return {h.distance, h.point_W, h.nearest_W, h.normal_W, h.vertex};
}

/// The sphere as a vertex with a radius: its centre's distance minus the radius.
template <typename S>
PairHit<S> sphereHit(const Pair<S>& pair, const fcl::Sphere<S>& sphere) {
  const Vector3<S> centre_W = pair.X_WO->translation();
  const PointDistanceResult<S> r =
      pointDistance(*pair.shape, *pair.X_WS, centre_W, pair.shape->queryOptions());
  return {r.distance - sphere.radius, centre_W - sphere.radius * r.normal, r.nearest_point,
          r.normal, -1};
}

template <typename S>
void updateDistance(const Pair<S>& pair, const fcl::CollisionGeometry<S>* o1,
                    const fcl::CollisionGeometry<S>* o2, const PairHit<S>& hit,
                    const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
  constexpr int kNone = fcl::DistanceResult<S>::NONE;
  const S d = (hit.distance < S(0) && !request.enable_signed_distance) ? S(-1) : hit.distance;
  const int b1 = pair.shape_first ? kNone : hit.other_primitive;
  const int b2 = pair.shape_first ? hit.other_primitive : kNone;
  if (request.enable_nearest_points) {
    const Vector3<S>& p1 = pair.shape_first ? hit.on_shape : hit.on_other;
    const Vector3<S>& p2 = pair.shape_first ? hit.on_other : hit.on_shape;
    result.update(d, o1, o2, b1, b2, p1, p2);
  } else {
    result.update(d, o1, o2, b1, b2);
  }
}

/// FCL's normal points from o1 to o2. The other geometry leaves the shape along the shape's
/// outward normal, so that is the normal when the shape is o1, and its opposite otherwise.
template <typename S>
void addContact(const Pair<S>& pair, const fcl::CollisionGeometry<S>* o1,
                const fcl::CollisionGeometry<S>* o2, const PairHit<S>& hit, const Vector3<S>& pos,
                bool with_details, fcl::CollisionResult<S>& result) {
  constexpr int kNone = fcl::Contact<S>::NONE;
  fcl::Contact<S> c(o1, o2, pair.shape_first ? kNone : hit.other_primitive,
                    pair.shape_first ? hit.other_primitive : kNone);
  c.pos.setZero();
  c.normal.setZero();
  c.penetration_depth = S(0);
  if (with_details) {
    c.pos = pos;
    c.normal = pair.shape_first ? hit.normal : Vector3<S>(-hit.normal);
    c.penetration_depth = -hit.distance;
  }
  result.addContact(c);
}

}  // namespace

template <typename S>
bool involvesSuperellipsoid(const fcl::CollisionGeometry<S>* o1,
                            const fcl::CollisionGeometry<S>* o2) {
  return dynamic_cast<const Superellipsoid<S>*>(o1) != nullptr ||
         dynamic_cast<const Superellipsoid<S>*>(o2) != nullptr;
}

template <typename S>
S pairDistance(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
               const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
               const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
  const Pair<S> pair = makePair(o1, tf1, o2, tf2);
  if (pair.shape != nullptr) {
    if (const auto* sphere = dynamic_cast<const fcl::Sphere<S>*>(pair.other)) {
      updateDistance(pair, o1, o2, sphereHit(pair, *sphere), request, result);
      return result.min_distance;
    }
    bool any_vertex = false;
    const bool handled = visitBvh(pair.other, [&](const auto& model) {
      const VertexHit<S> hit = nearestVertex(model, *pair.X_WO, *pair.shape, *pair.X_WS,
                                             !request.enable_signed_distance);
      if (hit.vertex < 0) return;  // an empty model: nothing to report
      any_vertex = true;
      updateDistance(pair, o1, o2, fromVertex(hit), request, result);
    });
    if (handled) return any_vertex ? result.min_distance : std::numeric_limits<S>::max();
  }
  warnUnsupported("distance", o1->getNodeType(), o2->getNodeType());
  return std::numeric_limits<S>::max();
}

template <typename S>
std::size_t pairCollide(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                        const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
                        const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result) {
  const Pair<S> pair = makePair(o1, tf1, o2, tf2);
  if (pair.shape != nullptr) {
    if (request.num_max_contacts <= result.numContacts()) return result.numContacts();
    const std::size_t room = request.num_max_contacts - result.numContacts();
    if (const auto* sphere = dynamic_cast<const fcl::Sphere<S>*>(pair.other)) {
      const PairHit<S> hit = sphereHit(pair, *sphere);
      if (hit.distance < S(0)) {
        addContact(pair, o1, o2, hit, Vector3<S>(S(0.5) * (hit.on_shape + hit.on_other)),
                   request.enable_contact, result);
      }
      return result.numContacts();
    }
    const bool handled = visitBvh(pair.other, [&](const auto& model) {
      for (const VertexHit<S>& h : penetratingVertices(model, *pair.X_WO, *pair.shape, *pair.X_WS,
                                                       room, request.enable_contact)) {
        addContact(pair, o1, o2, fromVertex(h), h.point_W, request.enable_contact, result);
      }
    });
    if (handled) return result.numContacts();
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
