// The dispatcher: a superellipsoid pair goes to the pair kind that recognises the other
// geometry: a mesh or point cloud (many contacts), or a shape (one hit, written here into FCL's
// results); a pair that none recognises gets FCL's "not supported" warning. A new shape pair
// kind is a file beside this one (docs/design.md → "Adding a pair") and one entry in shapeHit.

#include "fcl_glue/pairs/pairs.h"

#include <iostream>
#include <limits>

#include "common/coordinate_range.h"
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

/// The first shape pair kind's hit (each is std::nullopt for a geometry not its own).
template <typename S>
std::optional<PairHit<S>> shapeHit(const Pair<S>& pair) {
  for (auto kind : {&sphereHit<S>, &halfspaceHit<S>, &smoothHit<S>, &capsuleHit<S>, &polytopeHit<S>,
                    &roundHit<S>}) {
    if (std::optional<PairHit<S>> hit = kind(pair)) return hit;
  }
  return std::nullopt;
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
  checkPose("superellipsoid distance", "of o1", tf1);
  checkPose("superellipsoid distance", "of o2", tf2);
  const Pair<S> pair = makePair(o1, tf1, o2, tf2);
  if (pair.shape != nullptr) {
    if (const std::optional<S> answer = meshDistance(pair, request, result)) return *answer;
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
    if (meshCollide(pair, request, room, result)) return result.numContacts();
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
