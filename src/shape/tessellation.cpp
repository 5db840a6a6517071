#include "fcl_superellipsoid/tessellation.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numeric>
#include <ostream>
#include <stdexcept>
#include <string>

#include "common/invalid_argument.h"

namespace fcl_superellipsoid {
namespace {

/// How many vertices each latitude ring gets (see tessellate()'s doc).
std::vector<int> ringSizes(int ring_vertices) {
  int rings = static_cast<int>(std::lround(std::sqrt(ring_vertices / 2.0)));
  rings = std::clamp(rings, 1, ring_vertices / 3);
  std::vector<int> sizes(rings, ring_vertices / rings);
  // Hand the remainder to the rings nearest the equator.
  std::vector<int> order(rings);
  std::iota(order.begin(), order.end(), 0);
  const double middle = (rings - 1) / 2.0;
  std::stable_sort(order.begin(), order.end(),
                   [middle](int a, int b) { return std::abs(a - middle) < std::abs(b - middle); });
  for (int i = 0; i < ring_vertices % rings; ++i) ++sizes[order[i]];
  return sizes;
}

}  // namespace

template <typename S>
TriangleMesh<S> tessellate(const Superellipsoid<S>& shape, int num_vertices) {
  if (num_vertices < 5 || num_vertices > kMaxTessellationVertices) {
    detail::throwInvalidArgument(
        "tessellate",
        "num_vertices must be in [5, " + std::to_string(kMaxTessellationVertices) + "]",
        num_vertices);
  }
  const double pi = 3.14159265358979323846;
  const std::vector<int> sizes = ringSizes(num_vertices - 2);
  const int rings = static_cast<int>(sizes.size());

  TriangleMesh<S> mesh;
  mesh.vertices.reserve(num_vertices);
  mesh.vertices.emplace_back(S(0), S(0), shape.radii()[2]);  // north pole, index 0
  std::vector<int> first(rings);                             // index of each ring's vertex 0
  std::vector<double> offset(rings);                         // longitude offset, in steps
  for (int j = 0; j < rings; ++j) offset[j] = (j % 2) ? 0.5 : 0.0;
  auto longitude = [&](int j, int k) { return -pi + 2 * pi * (k + offset[j]) / sizes[j]; };
  for (int j = 0; j < rings; ++j) {
    first[j] = static_cast<int>(mesh.vertices.size());
    const double latitude = pi / 2 - pi * (j + 1) / (rings + 1);
    for (int k = 0; k < sizes[j]; ++k) {
      // A direction of the unit sphere, stretched by the radii, projected radially onto the
      // surface: G is 1-homogeneous, so v/G(v) is exactly on it (to rounding).
      const double omega = longitude(j, k);
      const Vector3<S> direction(S(shape.radii()[0] * std::cos(latitude) * std::cos(omega)),
                                 S(shape.radii()[1] * std::cos(latitude) * std::sin(omega)),
                                 S(shape.radii()[2] * std::sin(latitude)));
      mesh.vertices.push_back(direction / shape.gauge(direction));
    }
  }
  const int south = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(S(0), S(0), -shape.radii()[2]);

  auto ringIndex = [&](int j, int k) { return first[j] + k % sizes[j]; };
  for (int k = 0; k < sizes[0]; ++k) {
    mesh.triangles.emplace_back(0, ringIndex(0, k), ringIndex(0, k + 1));
  }
  // Zipper between ring j (above) and j + 1 (below): advance along the ring whose next
  // vertex comes first in longitude. Both windings below put the outward normal on the
  // right-hand side (checked at ω = 0: (down) × (east) = outward).
  auto fraction = [&](int j, int k) { return (k + offset[j]) / sizes[j]; };
  for (int j = 0; j + 1 < rings; ++j) {
    const int na = sizes[j], nb = sizes[j + 1];
    int i = 0, k = 0;
    while (i < na || k < nb) {
      const double next_a = fraction(j, i + 1);
      const double next_b = fraction(j + 1, k + 1);
      if (k == nb || (i < na && next_a <= next_b)) {
        mesh.triangles.emplace_back(ringIndex(j, i), ringIndex(j + 1, k), ringIndex(j, i + 1));
        ++i;
      } else {
        mesh.triangles.emplace_back(ringIndex(j, i), ringIndex(j + 1, k), ringIndex(j + 1, k + 1));
        ++k;
      }
    }
  }
  const int last = rings - 1;
  for (int k = 0; k < sizes[last]; ++k) {
    mesh.triangles.emplace_back(south, ringIndex(last, k + 1), ringIndex(last, k));
  }
  return mesh;
}

template <typename S>
void checkMesh(const TriangleMesh<S>& mesh) {
  if (mesh.vertices.empty()) {
    detail::throwInvalidArgument("makeBVHModel", "the mesh must have a vertex, vertex count", 0);
  }
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!mesh.vertices[i].allFinite()) {
      detail::throwInvalidArgument(
          "makeBVHModel", "vertex " + std::to_string(i) + " must be finite", mesh.vertices[i]);
    }
  }
  const std::size_t n = mesh.vertices.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const fcl::Triangle& tri = mesh.triangles[t];
    if (tri[0] >= n || tri[1] >= n || tri[2] >= n) {
      detail::throwInvalidArgument(
          "makeBVHModel",
          "triangle " + std::to_string(t) + " must index the " + std::to_string(n) + " vertices",
          Eigen::Matrix<std::size_t, 3, 1>(tri[0], tri[1], tri[2]));
    }
  }
}

template <typename S>
void writeObj(const TriangleMesh<S>& mesh, std::ostream& out) {
  out.precision(std::numeric_limits<S>::max_digits10);
  for (const auto& v : mesh.vertices) out << "v " << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
  for (const auto& t : mesh.triangles) {
    out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  }
}

template <typename S>
void writeObj(const TriangleMesh<S>& mesh, const std::string& path) {
  std::ofstream file(path);
  if (!file) throw std::runtime_error("writeObj: cannot open '" + path + "' for writing");
  writeObj(mesh, file);
  if (!file) throw std::runtime_error("writeObj: writing '" + path + "' failed");
}

template TriangleMesh<float> tessellate(const Superellipsoid<float>&, int);
template TriangleMesh<double> tessellate(const Superellipsoid<double>&, int);
template void checkMesh(const TriangleMesh<float>&);
template void checkMesh(const TriangleMesh<double>&);
template void writeObj(const TriangleMesh<float>&, std::ostream&);
template void writeObj(const TriangleMesh<double>&, std::ostream&);
template void writeObj(const TriangleMesh<float>&, const std::string&);
template void writeObj(const TriangleMesh<double>&, const std::string&);

}  // namespace fcl_superellipsoid
