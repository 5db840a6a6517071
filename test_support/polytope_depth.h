#ifndef FCL_SUPERELLIPSOID_TEST_POLYTOPE_DEPTH_H
#define FCL_SUPERELLIPSOID_TEST_POLYTOPE_DEPTH_H

// The penetration depth of a smooth convex body A and a convex polytope B, by enumeration of
// B's faces, edges and vertices, in long double; shares no code with src/.
//
// The depth is min over unit v of F(v) = h_A(v) + max_j(−v·b_j) (pair_construction.h's
// referenceDepth minimises the same F by a pattern search, which stalls on F's kinks). F is
// smooth inside each vertex b's region R_b = {v : b maximises −v·b_j}, where it equals
// f_b(v) = h_A(v) − v·b, and kinked on the regions' borders. So the minimiser v* is
//  - inside some R_b: a local minimum of the smooth f_b (found from lattice starts);
//  - on a border of two regions, away from corners: a local minimum of F along the great circle
//    of directions perpendicular to b1 − b2 (on it f_b1 = f_b2; found by sampling the circle and
//    a golden-section search);
//  - at a corner: the normal of a face of B (three or more vertices maximal).
// Every vertex pair's circle and every vertex triple's normal (both signs) are tried, a superset
// of B's edges and faces, so no topology is needed; each candidate is scored by the full F, so
// every one is a valid upper bound and their least is the depth. The superellipsoid's support
// function is smooth for exponents in (0, 2).

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "enumerated_depth.h"
#include "pair_construction.h"

namespace fcl_superellipsoid {
namespace test {

/// The world vertices of a box, a convex or a triangle posed by X (empty for other shapes).
inline std::vector<V3> polytopeVertices(const fcl::CollisionGeometryd& g,
                                        const fcl::Transform3d& X) {
  const M3 R = X.linear().cast<LD>();
  const V3 t = X.translation().cast<LD>();
  std::vector<V3> local;
  if (auto* box = dynamic_cast<const fcl::Boxd*>(&g)) {
    const V3 h = box->side.cast<LD>() / 2;
    for (int i = 0; i < 8; ++i) {
      local.push_back(V3((i & 1) ? h[0] : -h[0], (i & 2) ? h[1] : -h[1], (i & 4) ? h[2] : -h[2]));
    }
  } else if (auto* convex = dynamic_cast<const fcl::Convexd*>(&g)) {
    for (const auto& p : convex->getVertices()) local.push_back(p.cast<LD>());
  } else if (auto* triangle = dynamic_cast<const fcl::TrianglePd*>(&g)) {
    local = {triangle->a.cast<LD>(), triangle->b.cast<LD>(), triangle->c.cast<LD>()};
  }
  std::vector<V3> world;
  for (const V3& p : local) world.push_back(R * p + t);
  return world;
}

/// min over unit v of h_a(v) + max_j(−v·b_j) (negative: the distance), by enumeration.
inline LD polytopeDepth(const std::function<LD(const V3&)>& h_a, const std::vector<V3>& b) {
  auto F = [&](const V3& v) {
    LD hb = -std::numeric_limits<LD>::infinity();
    for (const V3& p : b) hb = std::max(hb, -v.dot(p));
    return h_a(v) + hb;
  };
  LD best = std::numeric_limits<LD>::infinity();
  const std::size_t n = b.size();

  // Corners: the normals of every vertex triple's plane.
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        const V3 normal = (b[j] - b[i]).cross(b[k] - b[i]);
        if (!(normal.norm() > 0)) continue;
        best = std::min({best, F(normal.normalized()), F(V3(-normal.normalized()))});
      }
    }
  }

  // Borders: F along the great circle perpendicular to each vertex pair's difference
  // (enumerated_depth.h).
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const V3 e = (b[j] - b[i]).normalized();
      const V3 p = e.unitOrthogonal(), q = e.cross(p);
      best = std::min(
          best,
          borderMinimum([&](LD angle) { return F(V3(std::cos(angle) * p + std::sin(angle) * q)); },
                        360));
    }
  }

  // Interiors: local minima of each smooth f_b, by a pattern search on f_b (smooth: it
  // converges), scored by F. Its starts: the best lattice directions inside R_b (v* is near
  // them when it is inside R_b, where f_b may also have a lower minimum outside R_b, e.g. for a
  // vertex near A's medial axis), and the best overall.
  const std::vector<V3> directions = fibonacciLattice(1000);
  for (const V3& vertex : b) {
    best = std::min(
        best, pieceMinimum([&](const V3& v) { return h_a(v) - v.dot(vertex); }, F, directions, 3));
  }
  return best;
}

}  // namespace test
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TEST_POLYTOPE_DEPTH_H
