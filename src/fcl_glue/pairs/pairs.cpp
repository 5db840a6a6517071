// The dispatcher: a superellipsoid pair goes to the first pair kind that recognises the other
// geometry; a pair that none recognises gets FCL's "not supported" warning. A new pair kind is
// a file beside this one (docs/design.md → "Adding a pair") and one line in each list below.

#include "fcl_glue/pairs/pairs.h"

#include <iostream>
#include <limits>

#include "common/coordinate_range.h"
#include "fcl_glue/pairs/mesh_pair.h"
#include "fcl_glue/pairs/pair.h"
#include "fcl_glue/pairs/sphere_pair.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

void warnUnsupported(const char* what, int node_type1, int node_type2) {
  std::cerr << "Warning: " << what << " function between node type " << node_type1
            << " and node type " << node_type2 << " is not supported\n";
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
    for (auto kind : {&sphereDistance<S>, &meshDistance<S>}) {
      if (const std::optional<S> answer = kind(pair, request, result)) return *answer;
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
    for (auto kind : {&sphereCollide<S>, &meshCollide<S>}) {
      if (kind(pair, request, room, result)) return result.numContacts();
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
