#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_FRONT_END_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_FRONT_END_H

// Internal: the bodies of the front end (fcl_integration.h), instantiated in front_end.cpp
// (double) and front_end_float.cpp (float: plain FCL for float is not in libfcl, so that TU
// instantiates it, at the cost of FCL's other solver's tables).

#include "common/invalid_argument.h"
#include "fcl_glue/pairs.h"
#include "fcl_superellipsoid/fcl_integration.h"

namespace fcl_superellipsoid {
namespace detail {

/// Refuses a null object or geometry (FCL would dereference it).
template <typename Object>
void checkNotNull(const char* where, const Object* o1, const Object* o2) {
  if (o1 == nullptr || o2 == nullptr) {
    throwInvalidArgument(where, "o1 and o2 must not be null",
                         o1 == nullptr ? "o1 = null" : "o2 = null");
  }
}

template <typename S>
void checkGeometries(const char* where, const fcl::CollisionObject<S>* o1,
                     const fcl::CollisionObject<S>* o2) {
  checkNotNull(where, o1, o2);
  checkNotNull(where, o1->collisionGeometry().get(), o2->collisionGeometry().get());
}

}  // namespace detail

template <typename S>
S distance(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
           const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
           const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
  detail::checkNotNull("fcl_superellipsoid::distance", o1, o2);
  if (!detail::involvesSuperellipsoid(o1, o2)) {
    return fcl::distance(o1, tf1, o2, tf2, request, result);
  }
  // The table entries' own function, called in the caller's order: nothing to swap back,
  // and no signed-distance fallback to overwrite the nearest points.
  return detail::pairDistance(o1, tf1, o2, tf2, request, result);
}

template <typename S>
S distance(const fcl::CollisionObject<S>* o1, const fcl::CollisionObject<S>* o2,
           const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
  detail::checkGeometries("fcl_superellipsoid::distance", o1, o2);
  return fcl_superellipsoid::distance(o1->collisionGeometry().get(), o1->getTransform(),
                                      o2->collisionGeometry().get(), o2->getTransform(), request,
                                      result);
}

template <typename S>
std::size_t collide(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                    const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
                    const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result) {
  detail::checkNotNull("fcl_superellipsoid::collide", o1, o2);
  if (!detail::involvesSuperellipsoid(o1, o2)) {
    return fcl::collide(o1, tf1, o2, tf2, request, result);
  }
  if (request.num_max_contacts == 0) {  // as FCL
    std::cerr << "Warning: should stop early as num_max_contact is 0 !\n";
    return 0;
  }
  return detail::pairCollide(o1, tf1, o2, tf2, request, result);
}

template <typename S>
std::size_t collide(const fcl::CollisionObject<S>* o1, const fcl::CollisionObject<S>* o2,
                    const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result) {
  detail::checkGeometries("fcl_superellipsoid::collide", o1, o2);
  return fcl_superellipsoid::collide(o1->collisionGeometry().get(), o1->getTransform(),
                                     o2->collisionGeometry().get(), o2->getTransform(), request,
                                     result);
}

template <typename S>
bool defaultCollisionFunction(fcl::CollisionObject<S>* o1, fcl::CollisionObject<S>* o2,
                              void* data) {
  detail::checkNotNull("fcl_superellipsoid::defaultCollisionFunction", o1, o2);
  if (data == nullptr) {
    detail::throwInvalidArgument("fcl_superellipsoid::defaultCollisionFunction",
                                 "data must point to an fcl::DefaultCollisionData", "null");
  }
  auto* collision_data = static_cast<fcl::DefaultCollisionData<S>*>(data);
  const fcl::CollisionRequest<S>& request = collision_data->request;
  fcl::CollisionResult<S>& result = collision_data->result;
  if (collision_data->done) return true;
  fcl_superellipsoid::collide(o1, o2, request, result);
  if (!request.enable_cost && result.isCollision() &&
      result.numContacts() >= request.num_max_contacts) {
    collision_data->done = true;
  }
  return collision_data->done;
}

template <typename S>
bool defaultDistanceFunction(fcl::CollisionObject<S>* o1, fcl::CollisionObject<S>* o2, void* data,
                             S& dist) {
  detail::checkNotNull("fcl_superellipsoid::defaultDistanceFunction", o1, o2);
  if (data == nullptr) {
    detail::throwInvalidArgument("fcl_superellipsoid::defaultDistanceFunction",
                                 "data must point to an fcl::DefaultDistanceData", "null");
  }
  auto* distance_data = static_cast<fcl::DefaultDistanceData<S>*>(data);
  fcl::DistanceResult<S>& result = distance_data->result;
  if (distance_data->done) {
    dist = result.min_distance;
    return true;
  }
  fcl_superellipsoid::distance(o1, o2, distance_data->request, result);
  dist = result.min_distance;
  if (dist <= 0) return true;  // in collision or in touch, as FCL's callback
  return distance_data->done;
}

}  // namespace fcl_superellipsoid

#define FSE_INSTANTIATE_FRONT_END(S)                                                               \
  namespace fcl_superellipsoid {                                                                   \
  template S distance(const fcl::CollisionObject<S>*, const fcl::CollisionObject<S>*,              \
                      const fcl::DistanceRequest<S>&, fcl::DistanceResult<S>&);                    \
  template S distance(const fcl::CollisionGeometry<S>*, const fcl::Transform3<S>&,                 \
                      const fcl::CollisionGeometry<S>*, const fcl::Transform3<S>&,                 \
                      const fcl::DistanceRequest<S>&, fcl::DistanceResult<S>&);                    \
  template std::size_t collide(const fcl::CollisionObject<S>*, const fcl::CollisionObject<S>*,     \
                               const fcl::CollisionRequest<S>&, fcl::CollisionResult<S>&);         \
  template std::size_t collide(const fcl::CollisionGeometry<S>*, const fcl::Transform3<S>&,        \
                               const fcl::CollisionGeometry<S>*, const fcl::Transform3<S>&,        \
                               const fcl::CollisionRequest<S>&, fcl::CollisionResult<S>&);         \
  template bool defaultCollisionFunction(fcl::CollisionObject<S>*, fcl::CollisionObject<S>*,       \
                                         void*);                                                   \
  template bool defaultDistanceFunction(fcl::CollisionObject<S>*, fcl::CollisionObject<S>*, void*, \
                                        S&);                                                       \
  }

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_FRONT_END_H
