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

}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_DIAGNOSTICS_H
