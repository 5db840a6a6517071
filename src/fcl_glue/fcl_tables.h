#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_FCL_TABLES_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_FCL_TABLES_H

// Internal: the superellipsoid entries of FCL's function tables for GJKSolver_libccd<S>.
//
// FCL indexes its tables [node type of o1][node type of o2] and, for a shape–mesh pair, calls
// them as (mesh, shape), so the mesh rows get a BV_UNKNOWN column (BV_UNKNOWN is the
// superellipsoid's node type). A shape pair is called in the caller's order: both slots. The
// node types are the rows of pair_kinds.h.
// Every entry checks the dynamic type (another user shape, or a BVHModel of an unknown BV
// type, also reports BV_UNKNOWN) and answers with pairDistance / pairCollide.
//
// The tables themselves are instantiated in fcl_{distance,collision}_table_{double,float}.cpp
// (fcl_table_templates.h); the entries are written by registration.cpp.

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "fcl_glue/pair_kinds.h"
#include "fcl_glue/pairs.h"

namespace fcl_superellipsoid {
namespace detail {

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
  for (const PairKind<double>& kind : kPairKinds<double>) {
    if (kind.form == PairForm::kMesh) {
      matrix[kind.node_type][fcl::BV_UNKNOWN] = entry;
    } else {
      matrix[fcl::BV_UNKNOWN][kind.node_type] = entry;
      matrix[kind.node_type][fcl::BV_UNKNOWN] = entry;
    }
  }
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_FCL_TABLES_H
