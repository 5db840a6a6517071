#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_MESH_FEATURES_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_MESH_FEATURES_H

// Internal: the regions a triangle mesh makes where one of its vertices or ridges pokes into
// the superellipsoid with no face holding the shape there (docs/math.md → "A mesh's regions",
// vertices and ridges). The faces' regions (fcl_glue/mesh_manifold.cpp) press the shape against
// a triangle's plane; a vertex or a ridge edge inside the shape, with the shape's deepest point
// over no triangle's face, makes none of them. These are met by their deepest points instead,
// as the mesh's vertices are (the point solver's normal at the nearest point).

#include <vector>

#include "fcl_superellipsoid/contact_manifold.h"
#include "narrowphase/contact_region.h"
#include "narrowphase/mesh_facets.h"

namespace fcl_superellipsoid {
namespace detail {

/// A feature's region and its first triangle (the mesh's index).
template <typename S>
struct FeatureRegion {
  ContactManifold<S> region;
  int triangle;
};

/// What the faces' regions say of one facet: whether it is in a region, and that region's
/// distance and normal.
template <typename S>
struct FaceCover {
  bool covered = false;
  S distance{};
  Vector3<S> normal = Vector3<S>::Zero();
};

/// The regions of the facets' vertices and ridge edges that come within `tolerance` of the shape
/// (`body`: the shape at X_WS as a region body) and that the faces' regions do not hold. A
/// region holds a feature on one of its facets (`cover`, one per facet) where it is at least as
/// deep as the feature less the tolerance and overlaps if the feature does: so a vertex inside
/// the shape always makes an overlapping region, its own or a face's.
/// - A vertex where the signed distance falls along none of its edges: one place, at the
///   vertex, with the shape's normal at its nearest point.
/// - A ridge edge (its triangles bend away from the shape; or the mesh's boundary) whose least
///   signed distance is inside the edge: the region along the edge at that normal, its deepest
///   place and the ends of the part of the edge within the tolerance of the shape's surface.
template <typename S>
std::vector<FeatureRegion<S>> featureRegions(
    const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS, const RegionBody<S>& body,
    const std::vector<Facet<S>>& facets, const std::vector<EdgeOfFacet>& edges,
    const std::vector<FaceCover<S>>& cover, S tolerance, const ManifoldOptions<S>& options);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_MESH_FEATURES_H
