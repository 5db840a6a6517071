// The dispatcher: a superellipsoid pair goes to the row of pair_kinds.h that the other
// geometry's node type names: a mesh or point cloud (many contacts, mesh_pair.h), or a shape
// (one hit, written here into FCL's results); a pair that none recognises gets FCL's "not
// supported" warning.

#include "fcl_glue/pairs.h"

#include <algorithm>
#include <iostream>
#include <limits>

#include "common/coordinate_range.h"
#include "fcl_glue/contact_manifold.h"
#include "fcl_glue/mesh_manifold.h"
#include "fcl_glue/mesh_pair.h"
#include "fcl_glue/pair.h"
#include "fcl_glue/pair_kinds.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

void warnUnsupported(const char* what, int node_type1, int node_type2) {
  std::cerr << "Warning: " << what << " function between node type " << node_type1
            << " and node type " << node_type2 << " is not supported\n";
}

/// The pair's row of pair_kinds.h, or nullptr.
template <typename S>
const PairKind<S>* kindOf(const Pair<S>& pair) {
  return pair.shape != nullptr ? findPairKind<S>(pair.other_type) : nullptr;
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
  if (const PairKind<S>* kind = kindOf(pair)) {
    if (kind->form == PairForm::kMesh) {
      if (const std::optional<S> answer = meshDistance(pair, request, result)) return *answer;
    } else if (const std::optional<PairHit<S>> hit =
                   kind->answer(pair, "superellipsoid distance")) {
      updateDistance(pair, *hit, request, result);
      return result.min_distance;
    }
  }
  warnUnsupported("distance", o1->getNodeType(), o2->getNodeType());
  return std::numeric_limits<S>::max();
}

namespace {

/// The overlapping regions of the shape and a triangle mesh as FCL's contacts, deepest region
/// first: each region's places (at most four, and at most the room left), the deepest first,
/// with the region's normal and their own depths (0 on a region's rim) and its first triangle.
template <typename S>
void regionsCollide(const Pair<S>& pair, const fcl::CollisionRequest<S>& request, std::size_t room,
                    fcl::CollisionResult<S>& result) {
  ManifoldOptions<S> options;
  options.outline_area_tolerance = S(1);  // the places only: no refined outline
  options.max_points = static_cast<int>(std::min<std::size_t>(room, 4));
  std::vector<int> facets;
  const std::optional<std::vector<ContactManifold<S>>> regions =
      meshManifolds(pair, options, S(1e-3) * pair.shape->size(), "superellipsoid collide", &facets);
  for (std::size_t r = 0; r < regions->size() && result.numContacts() < request.num_max_contacts;
       ++r) {
    const ContactManifold<S>& region = (*regions)[r];
    if (!(region.distance < S(0))) continue;  // touching within the tolerance only
    for (const ManifoldPoint<S>& p : region.points) {
      if (result.numContacts() >= request.num_max_contacts) break;
      const PairHit<S> at{std::min(-p.depth, S(0)), p.on_other, p.on_shape, region.normal,
                          facets[r]};
      addContact(pair, at, p.position, request.enable_contact, result);
    }
  }
}

}  // namespace

template <typename S>
std::size_t pairCollide(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                        const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
                        const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result) {
  checkPose("superellipsoid collide", "of o1", tf1);
  checkPose("superellipsoid collide", "of o2", tf2);
  const Pair<S> pair = makePair(o1, tf1, o2, tf2);
  if (pair.shape != nullptr && request.num_max_contacts <= result.numContacts()) {
    return result.numContacts();  // no room left
  }
  if (const PairKind<S>* kind = kindOf(pair)) {
    const std::size_t room = request.num_max_contacts - result.numContacts();
    if (kind->form == PairForm::kMesh) {
      if (pair.shape->meshContacts() == MeshContacts::kRegions && isTriangleMesh(pair)) {
        regionsCollide(pair, request, room, result);
        return result.numContacts();
      }
      if (meshCollide(pair, request, room, result)) return result.numContacts();
    } else if (const std::optional<PairHit<S>> hit = kind->answer(pair, "superellipsoid collide")) {
      if (hit->distance >= S(0)) return result.numContacts();
      if (room == 1 || kind->region == nullptr) {
        // One contact, halfway between the two surfaces.
        addContact(pair, *hit, Vector3<S>(S(0.5) * (hit->on_shape + hit->on_other)),
                   request.enable_contact, result);
        return result.numContacts();
      }
      // The manifold's places, at most four (contact_manifold.h), each with its own depth and
      // the pair's normal; those on the region's rim touch (depth 0, within the tolerance).
      // Only the places are written: the outline through its first eight directions will do
      // (not refined).
      ManifoldOptions<S> options;
      options.outline_area_tolerance = S(1);
      options.max_points = static_cast<int>(std::min<std::size_t>(room, 4));
      for (const ManifoldPoint<S>& p : pairManifold(pair, *kind, *hit, options).points) {
        const PairHit<S> at{std::min(-p.depth, S(0)), p.on_other, p.on_shape, hit->normal,
                            hit->other_primitive};
        addContact(pair, at, p.position, request.enable_contact, result);
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
