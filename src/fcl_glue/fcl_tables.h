#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_FCL_TABLES_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_FCL_TABLES_H

// Internal: the superellipsoid entries of FCL's function tables for GJKSolver_libccd<S>.
//
// FCL indexes its tables [node type of o1][node type of o2] and, for a shape–mesh pair, calls
// them as (mesh, shape), so the mesh rows get a BV_UNKNOWN column (BV_UNKNOWN is the
// superellipsoid's node type). A shape pair is called in the caller's order: both slots.
// Every entry checks the dynamic type (another user shape, or a BVHModel of an unknown BV
// type, also reports BV_UNKNOWN) and answers with pairDistance / pairCollide.
//
// The tables themselves are instantiated in fcl_{distance,collision}_table_{double,float}.cpp
// (fcl_table_templates.h); the entries are written by registration.cpp.

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "fcl_glue/pairs/pairs.h"

namespace fcl_superellipsoid {
namespace detail {

constexpr fcl::NODE_TYPE kMeshNodeTypes[] = {fcl::BV_AABB,   fcl::BV_OBB,    fcl::BV_RSS,
                                             fcl::BV_kIOS,   fcl::BV_OBBRSS, fcl::BV_KDOP16,
                                             fcl::BV_KDOP18, fcl::BV_KDOP24};

/// FCL's shapes, and BV_UNKNOWN itself (superellipsoid–superellipsoid).
constexpr fcl::NODE_TYPE kShapeNodeTypes[] = {
    fcl::GEOM_BOX,       fcl::GEOM_SPHERE,   fcl::GEOM_ELLIPSOID, fcl::GEOM_CAPSULE,
    fcl::GEOM_CONE,      fcl::GEOM_CYLINDER, fcl::GEOM_CONVEX,    fcl::GEOM_PLANE,
    fcl::GEOM_HALFSPACE, fcl::GEOM_TRIANGLE, fcl::BV_UNKNOWN};

template <typename S>
S distanceEntry(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
                const fcl::detail::GJKSolver_libccd<S>* /*solver: not needed*/,
                const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
  return pairDistance(o1, tf1, o2, tf2, request, result);
}

template <typename S>
std::size_t collisionEntry(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                           const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
                           const fcl::detail::GJKSolver_libccd<S>* /*solver: not needed*/,
                           const fcl::CollisionRequest<S>& request,
                           fcl::CollisionResult<S>& result) {
  return pairCollide(o1, tf1, o2, tf2, request, result);
}

/// Writes the entries into a table (a DistanceFunctionMatrix's distance_matrix or a
/// CollisionFunctionMatrix's collision_matrix).
template <typename Matrix, typename Entry>
void writeEntries(Matrix& matrix, Entry entry) {
  for (fcl::NODE_TYPE mesh : kMeshNodeTypes) matrix[mesh][fcl::BV_UNKNOWN] = entry;
  for (fcl::NODE_TYPE shape : kShapeNodeTypes) {
    matrix[fcl::BV_UNKNOWN][shape] = entry;
    matrix[shape][fcl::BV_UNKNOWN] = entry;
  }
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_FCL_TABLES_H
