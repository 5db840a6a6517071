#ifndef FCL_SUPERELLIPSOID_TESSELLATION_H
#define FCL_SUPERELLIPSOID_TESSELLATION_H

/// @file
/// Triangle meshes of a superellipsoid: for FCL's BVH queries (the paper's baseline), for
/// display, and as vertex sets for the point-distance solvers.

#include <fcl/geometry/bvh/BVH_model.h>

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {

/// An indexed triangle mesh in the shape's frame, triangles wound counter-clockwise seen
/// from outside (right-hand normal points outward).
template <typename S>
struct TriangleMesh {
  std::vector<Vector3<S>> vertices;
  std::vector<fcl::Triangle> triangles;
};

/// The most vertices tessellate() makes (a mesh of a few GB); more is refused, not attempted.
constexpr int kMaxTessellationVertices = 100000000;

/// Tessellates the surface into a closed mesh with exactly num_vertices vertices, every one
/// on the surface to rounding (G = 1).
///
/// Layout: a latitude–longitude grid of the unit sphere, stretched by the radii and projected
/// radially onto the surface (v/G(v)). The two poles (0, 0, ±a3) plus R latitude rings evenly
/// spaced in (−π/2, π/2), R = round(√((num_vertices − 2)/2)) (≥ 1, each ring ≥ 3 vertices);
/// the num_vertices − 2 ring vertices are shared out evenly, extra ones going to the rings
/// nearest the equator; longitudes evenly spaced per ring, odd rings offset by half a step;
/// rings are stitched by a "zipper" that always advances along the ring whose next vertex has
/// the smaller longitude. Deterministic, so a count reproduces its mesh: 272 vertices (the
/// paper's mesh resolution) gives 12 rings of 22 or 23 vertices and 540 triangles.
///
/// Why not the paper's parametric angles (Eq. 4): for small ε they crowd the samples onto the
/// edges (with ε2 = 0.02 every ring lies within a few percent of the rim), and rings that
/// nearly coincide fold triangles inwards. Radial projection keeps rings apart for every ε.
///
/// @throws std::invalid_argument if num_vertices is not in [5, kMaxTessellationVertices].
template <typename S>
FSE_EXPORT TriangleMesh<S> tessellate(const Superellipsoid<S>& shape, int num_vertices);

/// Writes the mesh as Wavefront OBJ ("v x y z" lines, then 1-based "f i j k" lines).
template <typename S>
FSE_EXPORT void writeObj(const TriangleMesh<S>& mesh, std::ostream& out);

/// Writes the mesh as an OBJ file. @throws std::runtime_error if the file cannot be written.
template <typename S>
FSE_EXPORT void writeObj(const TriangleMesh<S>& mesh, const std::string& path);

/// Checks a mesh for makeBVHModel: at least one vertex, every vertex finite, every triangle's
/// indices in range. @throws std::invalid_argument naming the first bad vertex or triangle.
template <typename S>
FSE_EXPORT void checkMesh(const TriangleMesh<S>& mesh);

/// Builds an FCL BVH model (any BV type: AABB, OBB, RSS, kIOS, OBBRSS, KDOP<S, 16|18|24>)
/// of the mesh, in the mesh's frame. With no triangles, it builds a point cloud.
/// @throws std::invalid_argument as checkMesh().
template <typename BV>
std::shared_ptr<fcl::BVHModel<BV>> makeBVHModel(const TriangleMesh<typename BV::S>& mesh) {
  checkMesh(mesh);
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  model->beginModel(static_cast<int>(mesh.triangles.size()),
                    static_cast<int>(mesh.vertices.size()));
  if (mesh.triangles.empty()) {
    model->addSubModel(mesh.vertices);
  } else {
    model->addSubModel(mesh.vertices, mesh.triangles);
  }
  model->endModel();
  return model;
}

extern template FSE_EXPORT TriangleMesh<float> tessellate(const Superellipsoid<float>&, int);
extern template FSE_EXPORT TriangleMesh<double> tessellate(const Superellipsoid<double>&, int);
extern template FSE_EXPORT void checkMesh(const TriangleMesh<float>&);
extern template FSE_EXPORT void checkMesh(const TriangleMesh<double>&);
extern template FSE_EXPORT void writeObj(const TriangleMesh<float>&, std::ostream&);
extern template FSE_EXPORT void writeObj(const TriangleMesh<double>&, std::ostream&);
extern template FSE_EXPORT void writeObj(const TriangleMesh<float>&, const std::string&);
extern template FSE_EXPORT void writeObj(const TriangleMesh<double>&, const std::string&);

}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TESSELLATION_H
