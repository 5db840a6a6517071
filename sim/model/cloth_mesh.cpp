#include "model/cloth_mesh.h"

#include <algorithm>
#include <map>

namespace fse_sim {

ClothMesh makeClothMesh(const ClothSpec& spec) {
  ClothMesh mesh;
  mesh.nx = spec.nx;
  mesh.ny = spec.ny;
  mesh.rest_positions.resize(3, mesh.vertexCount());
  for (int j = 0; j < spec.ny; ++j) {
    for (int i = 0; i < spec.nx; ++i) {
      const double x = spec.size_x * (double(i) / (spec.nx - 1) - 0.5);
      const double y = spec.size_y * (double(j) / (spec.ny - 1) - 0.5);
      mesh.rest_positions.col(mesh.index(i, j)) = spec.centre + Eigen::Vector3d(x, y, 0);
    }
  }
  for (int j = 0; j + 1 < spec.ny; ++j) {
    for (int i = 0; i + 1 < spec.nx; ++i) {
      const int a = mesh.index(i, j), b = mesh.index(i + 1, j), c = mesh.index(i + 1, j + 1),
                d = mesh.index(i, j + 1);
      if ((i + j) % 2 == 0) {  // diagonal a–c
        mesh.triangles.push_back({a, b, c});
        mesh.triangles.push_back({a, c, d});
      } else {  // diagonal b–d
        mesh.triangles.push_back({a, b, d});
        mesh.triangles.push_back({b, c, d});
      }
    }
  }
  // Edge → the vertices opposite it in its one or two triangles.
  std::map<std::pair<int, int>, std::vector<int>> opposite;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int u = t[k], v = t[(k + 1) % 3], w = t[(k + 2) % 3];
      opposite[{std::min(u, v), std::max(u, v)}].push_back(w);
    }
  }
  for (const auto& [edge, others] : opposite) {
    mesh.edges.push_back({edge.first, edge.second});
    if (others.size() == 2) mesh.bending_pairs.push_back({others[0], others[1]});
  }
  return mesh;
}

}  // namespace fse_sim
