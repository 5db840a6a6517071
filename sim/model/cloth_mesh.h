#ifndef FSE_SIM_MODEL_CLOTH_MESH_H
#define FSE_SIM_MODEL_CLOTH_MESH_H

// The cloth's topology and rest shape: a rectangular grid of nx × ny vertices, each quad cut
// into two triangles (2·(nx−1)·(ny−1) triangles: 6,254 for the paper's 54 × 60 grid).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "model/scene.h"

namespace fse_sim {

struct ClothMesh {
  int nx = 0, ny = 0;
  Eigen::Matrix3Xd rest_positions;            ///< world frame, flat, at the scene's centre
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from +z
  std::vector<std::array<int, 2>> edges;      ///< every triangle edge once (stretch)
  /// For every edge shared by two triangles, the two vertices opposite it (bending).
  std::vector<std::array<int, 2>> bending_pairs;

  int vertexCount() const { return nx * ny; }
  int index(int i, int j) const { return i + nx * j; }
};

/// The grid of `spec`. Quads are cut along alternating diagonals (a "union jack" pattern) so
/// that the cloth has no preferred folding direction.
ClothMesh makeClothMesh(const ClothSpec& spec);

}  // namespace fse_sim

#endif  // FSE_SIM_MODEL_CLOTH_MESH_H
