#include "fcl_glue/mesh_pair.h"

#include <limits>

#include "fcl_glue/bv_types.h"
#include "fcl_glue/vertex_traversal.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

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
