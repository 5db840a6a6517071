#include "fcl_glue/mesh_pair.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>

#include <limits>
#include <type_traits>

#include "fcl_glue/vertex_traversal.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

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

template <typename S>
PairHit<S> fromVertex(const VertexHit<S>& h) {
  return {h.distance, h.point_W, h.nearest_W, h.normal_W, h.vertex};
}

}  // namespace

template <typename S>
std::optional<S> meshDistance(const Pair<S>& pair, const fcl::DistanceRequest<S>& request,
                              fcl::DistanceResult<S>& result) {
  bool any_vertex = false;
  const bool handled = visitBvh(pair.other, [&](const auto& model) {
    const VertexHit<S> hit =
        nearestVertex(model, *pair.X_WO, *pair.shape, *pair.X_WS, !request.enable_signed_distance);
    if (hit.vertex < 0) return;  // an empty model: nothing to report
    any_vertex = true;
    updateDistance(pair, fromVertex(hit), request, result);
  });
  if (!handled) return std::nullopt;
  return any_vertex ? result.min_distance : std::numeric_limits<S>::max();
}

template <typename S>
bool meshCollide(const Pair<S>& pair, const fcl::CollisionRequest<S>& request, std::size_t room,
                 fcl::CollisionResult<S>& result) {
  return visitBvh(pair.other, [&](const auto& model) {
    for (const VertexHit<S>& h : penetratingVertices(model, *pair.X_WO, *pair.shape, *pair.X_WS,
                                                     room, request.enable_contact)) {
      addContact(pair, fromVertex(h), h.point_W, request.enable_contact, result);
    }
  });
}

#define FSE_INSTANTIATE_MESH_PAIR(S)                                                      \
  template std::optional<S> meshDistance(const Pair<S>&, const fcl::DistanceRequest<S>&,  \
                                         fcl::DistanceResult<S>&);                        \
  template bool meshCollide(const Pair<S>&, const fcl::CollisionRequest<S>&, std::size_t, \
                            fcl::CollisionResult<S>&);
FSE_INSTANTIATE_MESH_PAIR(float)
FSE_INSTANTIATE_MESH_PAIR(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
