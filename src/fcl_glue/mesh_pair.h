#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_MESH_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_MESH_PAIR_H

// Internal: the superellipsoid against fcl::BVHModel<BV> for FCL's eight BV types (triangle
// meshes and point clouds). The model's vertices are the query points (the reference paper's
// contact model), culled by the model's own BVH (fcl_glue/vertex_traversal.h) and answered by
// the point solver with the shape's queryOptions().

#include <cstddef>
#include <optional>

#include "fcl_glue/pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// Answers the pair if the other geometry is a BVHModel of a known BV type: the vertex of
/// least signed distance. Returns result.min_distance, std::numeric_limits<S>::max() for an
/// empty model; std::nullopt if the other geometry is not such a model.
template <typename S>
std::optional<S> meshDistance(const Pair<S>& pair, const fcl::DistanceRequest<S>& request,
                              fcl::DistanceResult<S>& result);

/// Adds one contact per penetrating vertex, the deepest `room` of them, deepest first; false if
/// the other geometry is not such a model.
template <typename S>
bool meshCollide(const Pair<S>& pair, const fcl::CollisionRequest<S>& request, std::size_t room,
                 fcl::CollisionResult<S>& result);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_MESH_PAIR_H
