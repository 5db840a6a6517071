#ifndef FSE_SIM_MODEL_STATIC_MESH_H
#define FSE_SIM_MODEL_STATIC_MESH_H

// The fixed bowl of a rigid-body scene: a closed triangle mesh in the world frame, generated
// from the scene's sizes or read from an OBJ file, and a uniform grid over it that finds the
// vertices and triangles near a body without looking at the others.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "model/scene.h"

namespace fse_sim {

struct StaticMesh {
  Eigen::Matrix3Xd vertices;                  ///< world frame
  std::vector<std::array<int, 3>> triangles;  ///< indices into vertices, counter-clockwise
                                              ///< seen from outside the solid
  Eigen::Matrix3Xd normals;                   ///< per triangle: unit, outward (0 if degenerate)
  /// Per triangle: one of its edges is convex (the faces bend away from each other across it,
  /// as on a rim) or has no neighbour. Only there can a body touch the mesh on an edge away
  /// from every vertex and every face's interior (contact/rigid_contact.h).
  std::vector<char> convex_edge;
  /// Per vertex: on a triangle with a convex edge. Elsewhere (a valley of the surface) the
  /// faces round a vertex reach at least as far as the vertex does.
  std::vector<char> convex_vertex;
  /// Per triangle, for culling: its centroid, the largest distance from it to a corner, and the
  /// largest 1/sin(α/2) over its corners' angles α. The triangle grown by δ in its plane (each
  /// edge's line moved out by δ) has its corners δ/sin(α/2) farther out, so every point of it
  /// lies within radius + δ·corner_factor of the centroid.
  Eigen::Matrix3Xd centroids;
  std::vector<double> radii, corner_factors;
  /// How far a centroid may lie off its triangle's plane by rounding (1e-12 × the largest
  /// vertex norm, a thousand times more than it does).
  double centroid_slack = 0;
};

/// Fills a mesh's normals, convex_edge and convex_vertex from its vertices and triangles.
void computeFaceData(StaticMesh& mesh);

/// The bowl of `spec`: a hemispherical shell opening up (+z), inner radius `radius`, closed by
/// a flat rim; each face has a pole and `rings` rings of `segments` vertices (5,002 vertices for
/// 25 × 100). Or, with `obj` set, the OBJ file's vertices and faces (polygons fanned into
/// triangles), moved by `position`; its faces must be wound counter-clockwise seen from outside.
/// @throws SceneError for an OBJ file that cannot be read or holds a bad face or number.
StaticMesh makeBowl(const BowlSpec& spec);

/// Uniform grid buckets of a mesh's vertices and triangles (a triangle in every cell its
/// bounding box meets).
class MeshGrid {
 public:
  MeshGrid() = default;
  explicit MeshGrid(const StaticMesh& mesh);

  /// The vertices in the cells the box [lo, hi] meets and the triangles that can reach into it,
  /// each once, in an order fixed by the grid (a superset of those inside the box).
  void query(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::vector<int>& vertices,
             std::vector<int>& triangles) const;

 private:
  Eigen::Array3i cellOf(const Eigen::Vector3d& p) const;
  int bucket(const Eigen::Array3i& cell) const {
    return cell[0] + dims_[0] * (cell[1] + dims_[1] * cell[2]);
  }
  Eigen::Vector3d origin_{0, 0, 0};
  double cell_ = 1;
  double triangle_reach_ = 0;  ///< largest distance from a triangle's centroid to its corners
  Eigen::Array3i dims_{1, 1, 1};
  std::vector<std::vector<int>> vertex_cells_, triangle_cells_;
};

}  // namespace fse_sim

#endif  // FSE_SIM_MODEL_STATIC_MESH_H
