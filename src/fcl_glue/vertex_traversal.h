#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_VERTEX_TRAVERSAL_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_VERTEX_TRAVERSAL_H

// Internal: the vertices of an fcl::BVHModel as query points against a superellipsoid,
// culled with the model's own BVH (no copy of the model, no vertex moved to the world: the
// shape is posed in the model's frame M instead).
//
// Culling bound. Every BV type is seen as a box swept by a sphere in M (centre c, axes R,
// half extents e, radius r): AABB and OBB as themselves, RSS as its rectangle and radius,
// kIOS and OBBRSS as their OBB, a k-DOP as its axis-aligned slabs (a superset). Along any
// unit axis u the box covers u·c ± (Σ eᵢ|u·Rᵢ| + r) and the superellipsoid covers u·c_S ± h(u),
// h its support function (closed form, docs/math.md); the gap between the two intervals is a
// lower bound on the signed distance from any vertex in the BV to the shape (a negative gap
// bounds its depth). The bound is the largest gap over the box's 3 axes, the shape's 3 axes
// and the line of the centres, and at least −(smallest radius): no point is deeper than that.
// The two children of a node are bounded together, h along their 8 axes on SIMD lanes. Subtrees
// of a few primitives are not bounded at all: testing their vertices costs less.
//
// Solving. The traversal only bounds vertices (one gauge evaluation each, docs/math.md →
// "Culling a BVH's vertices"; on SIMD lanes for collision, docs/design.md → "The BVH
// traversal"); the vertices that survive are then solved together by the batched queries
// (batch_distance.h: the SIMD kernel and threads), with the shape's query options. Distance
// keeps the least upper bound seen and the vertices whose lower bound does not exceed it;
// collision keeps every vertex strictly inside, and with depths hands them to the batched
// queries in blocks on a task while the traversal goes on.

#include <fcl/geometry/bvh/BVH_model.h>

#include <vector>

#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {
namespace detail {

/// One vertex answered by the point solver; world frame.
template <typename S>
struct VertexHit {
  int vertex = -1;                            // index into the model's vertices; −1: none
  S distance{};                               // signed
  Vector3<S> point_W = Vector3<S>::Zero();    // the vertex
  Vector3<S> nearest_W = Vector3<S>::Zero();  // its nearest surface point
  Vector3<S> normal_W = Vector3<S>::Zero();   // outward normal there
};

/// The vertex of least signed distance (vertex = −1 for an empty model). With
/// stop_at_penetration, the first penetrating vertex found ends the search.
template <typename BV>
VertexHit<typename BV::S> nearestVertex(const fcl::BVHModel<BV>& model,
                                        const fcl::Transform3<typename BV::S>& X_WM,
                                        const Superellipsoid<typename BV::S>& shape,
                                        const fcl::Transform3<typename BV::S>& X_WS,
                                        bool stop_at_penetration);

/// The penetrating vertices (strictly inside), the deepest max_count of them, deepest first.
/// Without with_depth, the first max_count found, without solving (distance 0, no points).
template <typename BV>
std::vector<VertexHit<typename BV::S>> penetratingVertices(
    const fcl::BVHModel<BV>& model, const fcl::Transform3<typename BV::S>& X_WM,
    const Superellipsoid<typename BV::S>& shape, const fcl::Transform3<typename BV::S>& X_WS,
    std::size_t max_count, bool with_depth);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_VERTEX_TRAVERSAL_H
