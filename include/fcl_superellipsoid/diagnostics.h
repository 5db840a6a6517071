#ifndef FCL_SUPERELLIPSOID_DIAGNOSTICS_H
#define FCL_SUPERELLIPSOID_DIAGNOSTICS_H

/// @file
/// Diagnostics: counters that show what a query did, for benchmarks and for tuning a scene.
/// Not needed to use the library; nothing here changes a result. (The batched queries report
/// their own counts through BatchOptions::statistics, batch_distance.h.)

#include <cstdint>

#include "fcl_superellipsoid/export.h"

namespace fcl_superellipsoid {

/// Counters of the BVH vertex traversal behind the FCL pairs with a mesh or point cloud
/// (fcl_integration.h), per thread, accumulated until the caller resets them
/// (`vertexTraversalStats() = {};`): the fraction of a model's vertices a query touched.
struct VertexTraversalStats {
  std::uint64_t bv_tests = 0;          ///< bounding volumes bounded against the shape
  std::uint64_t vertices_bounded = 0;  ///< vertices reached by the traversal
  std::uint64_t vertices_solved = 0;   ///< vertices that needed the point solver
};

/// This thread's counters.
FSE_EXPORT VertexTraversalStats& vertexTraversalStats();

/// Evaluations of a superellipsoid's gauge or support function made by this thread, accumulated
/// until the caller resets them (`shapeEvaluations() = 0;`): the unit of work every query here
/// is made of. One evaluation is one call of Superellipsoid's gauge, gaugeGradient, normal,
/// radialProjection or supportPoint (the Radial and Paper solvers are made of these), one
/// step of the Exact solver's Newton iterations or of the pairs' searches, one support call of
/// a GJK iteration or an EPA expansion (FCL's libccd path and Bullet's, through gjk_support.h
/// and Superellipsoid::supportPoint). Each costs a few exp2 and log2 (or pow) calls, so the
/// count per query says where a query's time goes and compares methods by their iterations.
/// Not counted: the batched SIMD kernel's lanes (batch_distance.h) and a partner shape's own
/// support calls (a box's, a mesh's).
FSE_EXPORT std::uint64_t& shapeEvaluations();

}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_DIAGNOSTICS_H
