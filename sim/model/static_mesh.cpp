#include "model/static_mesh.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "model/scene.h"

namespace fse_sim {
namespace {

StaticMesh generatedBowl(const BowlSpec& spec) {
  const int rings = spec.rings, segments = spec.segments;
  const int per_face = 1 + rings * segments;
  StaticMesh mesh;
  mesh.vertices.resize(3, 2 * per_face);
  // Face 0 the inner surface (radius R), face 1 the outer (R + thickness). Vertex 0 of a face
  // is its pole (the bottom), then ring k = 1..rings (polar angle k/rings · 90°), the last ring
  // on the rim (z = 0).
  for (int face = 0; face < 2; ++face) {
    const double r = spec.radius + face * spec.thickness;
    const int base = face * per_face;
    mesh.vertices.col(base) = spec.position + Eigen::Vector3d(0, 0, -r);
    for (int k = 1; k <= rings; ++k) {
      const double theta = 0.5 * M_PI * k / rings;
      for (int j = 0; j < segments; ++j) {
        const double phi = 2 * M_PI * (j + 0.5 * (k % 2)) / segments;
        mesh.vertices.col(base + 1 + (k - 1) * segments + j) =
            spec.position + r * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                std::sin(theta) * std::sin(phi), -std::cos(theta));
      }
    }
  }
  auto ring = [&](int face, int k, int j) {
    return face * per_face + 1 + (k - 1) * segments + (j % segments);
  };
  for (int face = 0; face < 2; ++face) {
    // Inner faces wound to face the cavity, outer ones away from it.
    auto add = [&](int a, int b, int c) {
      if (face == 0) {
        mesh.triangles.push_back({a, c, b});
      } else {
        mesh.triangles.push_back({a, b, c});
      }
    };
    for (int j = 0; j < segments; ++j) add(face * per_face, ring(face, 1, j + 1), ring(face, 1, j));
    for (int k = 1; k < rings; ++k) {
      for (int j = 0; j < segments; ++j) {
        // Odd rings are offset by half a segment: the quad's diagonal follows the offset.
        const int a = ring(face, k, j), b = ring(face, k, j + 1);
        const int c = ring(face, k + 1, j), d = ring(face, k + 1, j + 1);
        if (k % 2 == 1) {
          add(a, b, d);
          add(a, d, c);
        } else {
          add(a, b, c);
          add(b, d, c);
        }
      }
    }
  }
  for (int j = 0; j < segments; ++j) {  // the rim: inner ring to outer ring
    const int a = ring(0, rings, j), b = ring(0, rings, j + 1);
    const int c = ring(1, rings, j), d = ring(1, rings, j + 1);
    mesh.triangles.push_back({a, c, b});
    mesh.triangles.push_back({b, c, d});
  }
  return mesh;
}

StaticMesh objBowl(const BowlSpec& spec) {
  std::ifstream in(spec.obj);
  if (!in) throw SceneError(spec.obj + ": cannot read the bowl's OBJ file");
  std::vector<Eigen::Vector3d> vertices;
  StaticMesh mesh;
  std::string line;
  long number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    const std::string where = spec.obj + ":" + std::to_string(number);
    if (kind == "v") {
      Eigen::Vector3d p;
      if (!(words >> p[0] >> p[1] >> p[2]) || !p.allFinite() || p.norm() > 1e6) {
        throw SceneError(where + ": a vertex must be 3 finite numbers within 1e6 m, got \"" + line +
                         "\"");
      }
      vertices.push_back(p + spec.position);
    } else if (kind == "f") {
      std::vector<int> face;
      std::string item;
      while (words >> item) {
        // "i", "i/t", "i/t/n", "i//n"; negative indices count back from the last vertex.
        long index = 0;
        try {
          index = std::stol(item.substr(0, item.find('/')));
        } catch (const std::exception&) {
          throw SceneError(where + ": a face index must be an integer, got \"" + item + "\"");
        }
        if (index < 0) index += long(vertices.size()) + 1;
        if (index < 1 || index > long(vertices.size())) {
          throw SceneError(where + ": face index " + item + " names no vertex defined before it");
        }
        face.push_back(int(index - 1));
      }
      if (face.size() < 3) throw SceneError(where + ": a face needs at least 3 vertices");
      for (std::size_t k = 1; k + 1 < face.size(); ++k) {
        mesh.triangles.push_back({face[0], face[k], face[k + 1]});
      }
    }
  }
  if (mesh.triangles.empty()) throw SceneError(spec.obj + ": the bowl's OBJ file has no faces");
  mesh.vertices.resize(3, long(vertices.size()));
  for (std::size_t i = 0; i < vertices.size(); ++i) mesh.vertices.col(long(i)) = vertices[i];
  return mesh;
}

}  // namespace

StaticMesh makeBowl(const BowlSpec& spec) {
  StaticMesh mesh = spec.obj.empty() ? generatedBowl(spec) : objBowl(spec);
  computeFaceData(mesh);
  return mesh;
}

void computeFaceData(StaticMesh& mesh) {
  const std::size_t n = mesh.triangles.size();
  mesh.normals.setZero(3, long(n));
  mesh.centroids.setZero(3, long(n));
  mesh.radii.assign(n, 0.0);
  mesh.corner_factors.assign(n, std::numeric_limits<double>::infinity());
  mesh.centroid_slack =
      1e-12 * (mesh.vertices.cols() > 0 ? mesh.vertices.colwise().norm().maxCoeff() : 0.0);
  for (std::size_t t = 0; t < n; ++t) {
    const auto& v = mesh.triangles[t];
    const Eigen::Vector3d corners[3] = {mesh.vertices.col(v[0]), mesh.vertices.col(v[1]),
                                        mesh.vertices.col(v[2])};
    const Eigen::Vector3d m = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
    const double length = m.norm();
    if (length > 0) mesh.normals.col(long(t)) = m / length;
    const Eigen::Vector3d centroid = (corners[0] + corners[1] + corners[2]) / 3;
    mesh.centroids.col(long(t)) = centroid;
    double factor = 1;
    for (int k = 0; k < 3; ++k) {
      mesh.radii[t] = std::max(mesh.radii[t], (corners[k] - centroid).norm());
      const Eigen::Vector3d e1 = (corners[(k + 1) % 3] - corners[k]).normalized();
      const Eigen::Vector3d e2 = (corners[(k + 2) % 3] - corners[k]).normalized();
      // sin(α/2) = ‖e1 − e2‖/2 for unit edges e1, e2 at angle α.
      factor = std::max(factor, 2 / (e1 - e2).norm());
    }
    // A degenerate triangle (a zero angle, or no normal) is never culled.
    if (length > 0 && std::isfinite(factor)) mesh.corner_factors[t] = factor;
  }
  // Each edge (low, high vertex) with the triangles on it and their third vertices.
  struct Side {
    int triangle, opposite;
  };
  std::map<std::pair<int, int>, std::vector<Side>> edges;
  for (std::size_t t = 0; t < n; ++t) {
    const auto& v = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int a = v[k], b = v[(k + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back({int(t), v[(k + 2) % 3]});
    }
  }
  mesh.convex_edge.assign(n, 0);
  for (const auto& [edge, sides] : edges) {
    bool convex = sides.size() != 2;
    if (!convex) {
      // Convex where each face's far vertex lies below the other face's plane.
      const Eigen::Vector3d p = mesh.vertices.col(edge.first);
      const Eigen::Vector3d m0 = mesh.normals.col(sides[0].triangle);
      convex = m0.dot(mesh.vertices.col(sides[1].opposite) - p) < 0;
    }
    if (convex) {
      for (const Side& s : sides) mesh.convex_edge[std::size_t(s.triangle)] = 1;
    }
  }
  mesh.convex_vertex.assign(std::size_t(mesh.vertices.cols()), 0);
  for (std::size_t t = 0; t < n; ++t) {
    if (!mesh.convex_edge[t]) continue;
    for (int v : mesh.triangles[t]) mesh.convex_vertex[std::size_t(v)] = 1;
  }
}

MeshGrid::MeshGrid(const StaticMesh& mesh) {
  const Eigen::Vector3d lo = mesh.vertices.rowwise().minCoeff();
  const Eigen::Vector3d hi = mesh.vertices.rowwise().maxCoeff();
  // Each triangle goes in the cell of its centroid, and a query grows its box by the largest
  // distance from a centroid to its corners: every triangle and vertex is in one cell, so a
  // query visits each once, in the order of the cells (no sorting, no duplicates).
  std::vector<Eigen::Vector3d> centroids;
  double edges = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices.col(t[0]), b = mesh.vertices.col(t[1]),
                          c = mesh.vertices.col(t[2]);
    centroids.push_back((a + b + c) / 3);
    for (const Eigen::Vector3d& p : {a, b, c}) {
      triangle_reach_ = std::max(triangle_reach_, (p - centroids.back()).norm());
    }
    edges += (b - a).norm();
  }
  // Cells of about twice the mean edge length, at most 64 per axis.
  const double mean_edge = edges / double(std::max<std::size_t>(1, mesh.triangles.size()));
  cell_ = std::max({2 * mean_edge, (hi - lo).maxCoeff() / 64, 1e-9});
  origin_ = lo;
  for (int k = 0; k < 3; ++k) dims_[k] = 1 + int((hi[k] - lo[k]) / cell_);
  vertex_cells_.resize(std::size_t(dims_.prod()));
  triangle_cells_.resize(std::size_t(dims_.prod()));
  for (Eigen::Index i = 0; i < mesh.vertices.cols(); ++i) {
    vertex_cells_[std::size_t(bucket(cellOf(mesh.vertices.col(i))))].push_back(int(i));
  }
  for (std::size_t t = 0; t < centroids.size(); ++t) {
    triangle_cells_[std::size_t(bucket(cellOf(centroids[t])))].push_back(int(t));
  }
}

Eigen::Array3i MeshGrid::cellOf(const Eigen::Vector3d& p) const {
  Eigen::Array3i c;
  for (int k = 0; k < 3; ++k) {
    c[k] = std::clamp(int(std::floor((p[k] - origin_[k]) / cell_)), 0, dims_[k] - 1);
  }
  return c;
}

void MeshGrid::query(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                     std::vector<int>& vertices, std::vector<int>& triangles) const {
  vertices.clear();
  triangles.clear();
  if (vertex_cells_.empty()) return;
  const Eigen::Array3d grown_lo = lo.array() - triangle_reach_;
  const Eigen::Array3d grown_hi = hi.array() + triangle_reach_;
  // Boxes wholly outside the grid meet no cell (clamping would map them onto the border).
  const Eigen::Array3d grid_hi = origin_.array() + cell_ * dims_.cast<double>();
  if ((grown_hi < origin_.array()).any() || (grown_lo > grid_hi).any()) return;
  const Eigen::Array3i a = cellOf(grown_lo.matrix()), b = cellOf(grown_hi.matrix());
  const Eigen::Array3i va = cellOf(lo), vb = cellOf(hi);
  for (int z = a[2]; z <= b[2]; ++z)
    for (int y = a[1]; y <= b[1]; ++y)
      for (int x = a[0]; x <= b[0]; ++x) {
        const Eigen::Array3i cell(x, y, z);
        const std::size_t k = std::size_t(bucket(cell));
        triangles.insert(triangles.end(), triangle_cells_[k].begin(), triangle_cells_[k].end());
        if ((cell >= va).all() && (cell <= vb).all()) {
          vertices.insert(vertices.end(), vertex_cells_[k].begin(), vertex_cells_[k].end());
        }
      }
}

}  // namespace fse_sim
