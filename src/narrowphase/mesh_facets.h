#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_MESH_FACETS_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_MESH_FACETS_H

// Internal: a triangle mesh's triangles near the superellipsoid, in the world, as the mesh's
// regions see them (fcl_glue/mesh_manifold.cpp, narrowphase/mesh_features.h): each triangle's
// corners and unit normal on the shape's side, and the triangles' edges sorted so that each
// edge's triangles are adjacent.

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {
namespace detail {

/// A triangle near the shape, in the world: its index in the mesh, its corners' vertex indices
/// and points, and its unit normal on the shape's side (towards the shape's centre).
template <typename S>
struct Facet {
  int index;
  std::array<int, 3> corner;
  std::array<Vector3<S>, 3> p;
  Vector3<S> normal;
};

/// Barycentric coordinates of x (on or off the facet's plane) in the facet.
template <typename S>
Vector3<S> barycentric(const Facet<S>& f, const Vector3<S>& x) {
  const Vector3<S> area = (f.p[1] - f.p[0]).cross(f.p[2] - f.p[0]);
  const S twice = area.dot(f.normal);
  Vector3<S> l;
  for (int k = 0; k < 3; ++k) {
    const Vector3<S>& b = f.p[(k + 1) % 3];
    const Vector3<S>& c = f.p[(k + 2) % 3];
    l[k] = (c - b).cross(x - b).dot(f.normal) / twice;
  }
  return l;
}

/// One side of an edge: (smaller vertex, larger vertex, facet's position in the facets).
using EdgeOfFacet = std::array<int, 3>;

/// The facets' edges, sorted: each edge's facets are adjacent.
template <typename S>
std::vector<EdgeOfFacet> edgesOf(const std::vector<Facet<S>>& facets) {
  std::vector<EdgeOfFacet> edges;
  edges.reserve(3 * facets.size());
  for (std::size_t i = 0; i < facets.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const int a = facets[i].corner[k], b = facets[i].corner[(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), int(i)});
    }
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_MESH_FACETS_H
