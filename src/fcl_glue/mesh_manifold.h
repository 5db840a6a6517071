#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_MESH_MANIFOLD_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_MESH_MANIFOLD_H

// Internal: the contact regions of the superellipsoid and a triangle mesh (fcl::BVHModel<BV>,
// FCL's eight BV types) as a surface: each triangle near the shape meets it along its own normal,
// as a halfspace clipped to the triangle would (narrowphase/contact_region.h), triangles facing
// alike are merged into one region, and the vertices and ridges no face holds make regions of
// their own (narrowphase/mesh_features.h). The triangles are found through the model's own BVH,
// the shape posed in the model's frame and bounded by its box (docs/math.md → "A mesh's
// regions").

#include <optional>
#include <vector>

#include "fcl_glue/pair.h"
#include "fcl_superellipsoid/contact_manifold.h"

namespace fcl_superellipsoid {
namespace detail {

/// The regions of the pair's shape and mesh, deepest first (none where every triangle is apart
/// by more than `tolerance`, > 0); std::nullopt if the other geometry is not a BVHModel of a
/// known BV type. Refuses a point cloud (it has no surface) and a triangle whose vertices are not
/// finite, naming them; `where` names the call. Options are checked by the caller. If
/// `first_facets` is given, it receives each region's first (deepest) triangle's index.
template <typename S>
std::optional<std::vector<ContactManifold<S>>> meshManifolds(
    const Pair<S>& pair, const ManifoldOptions<S>& options, S tolerance, const char* where,
    std::vector<int>* first_facets = nullptr);

/// Whether the pair's other geometry is a BVHModel of a known BV type with triangles.
template <typename S>
bool isTriangleMesh(const Pair<S>& pair);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_MESH_MANIFOLD_H
