#ifndef FCL_SUPERELLIPSOID_TEST_ROUND_DEPTH_H
#define FCL_SUPERELLIPSOID_TEST_ROUND_DEPTH_H

// The penetration depth of a smooth convex body A and a cylinder or a cone B, by enumeration of
// B's smooth pieces, in long double; shares no code with src/.
//
// B is the convex hull of its pieces: a cylinder's two rims (circles), a cone's base rim and
// apex. So h_B(u) = max over the pieces P of h_P(u), and the depth is min over unit v of
// F(v) = h_A(v) + h_B(−v) = max_P f_P(v), f_P(v) = h_A(v) + h_P(−v). Each f_P is smooth off its
// rim's axis, and F equals f_P inside P's region (the directions −v along which P supports B).
// So the minimiser v* is
//  - inside some region: a local minimum of f_P there (found from lattice starts by a pattern
//    search on f_P);
//  - on the border of two regions (the side's normals: the cylinder's directions ⊥ its axis,
//    the cone's slanted normals): a local minimum of F along that circle (sampled, then a
//    golden-section search);
//  - on a rim's axis (a disc's normal), where f_P has its own kink.
// Every candidate is scored by the full F (pair_construction.h's supportFunction), so each is an
// upper bound and their least is the depth. This is the polytope enumeration
// (polytope_depth.h) with circles among the pieces.

#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "enumerated_depth.h"
#include "pair_construction.h"

namespace fcl_superellipsoid {
namespace test {

/// min over unit v of h_a(v) + h_B(−v) for the cylinder or cone `g` posed by X (negative: the
/// distance), by enumeration; NaN for other shapes.
inline LD roundDepth(const std::function<LD(const V3&)>& h_a, const fcl::CollisionGeometryd& g,
                     const fcl::Transform3d& X) {
  const M3 R = X.linear().cast<LD>();
  const V3 t = X.translation().cast<LD>(), z = R.col(2), e1 = R.col(0), e2 = R.col(1);
  LD r = 0, h = 0;
  bool cone = false;
  if (auto* c = dynamic_cast<const fcl::Cylinderd*>(&g)) {
    r = c->radius, h = LD(c->lz) / 2;
  } else if (auto* c = dynamic_cast<const fcl::Coned*>(&g)) {
    r = c->radius, h = LD(c->lz) / 2, cone = true;
  } else {
    return std::numeric_limits<LD>::quiet_NaN();
  }
  const std::function<LD(const V3&)> h_b = supportFunction(g, X);
  auto F = [&](const V3& v) { return h_a(v) + h_b(V3(-v)); };

  // The pieces' support functions h_P.
  std::vector<std::function<LD(const V3&)>> pieces;
  for (LD side : {LD(1), LD(-1)}) {
    if (cone && side > 0) continue;
    const V3 centre = t + side * h * z;
    pieces.push_back([=](const V3& u) { return u.dot(centre) + r * (u - u.dot(z) * z).norm(); });
  }
  if (cone) {
    const V3 apex = t + h * z;
    pieces.push_back([=](const V3& u) { return u.dot(apex); });
  }

  // The rims' axes: the discs' normals.
  LD best = std::min(F(z), cone ? std::numeric_limits<LD>::infinity() : F(V3(-z)));

  // The border: v(θ) = −m(θ), m the side's outward normal (enumerated_depth.h).
  const LD slant = std::hypot(2 * h, r);
  best = std::min(best, borderMinimum(
                            [&](LD theta) {
                              const V3 c = std::cos(theta) * e1 + std::sin(theta) * e2;
                              return F(V3(cone ? V3(-(2 * h * c + r * z) / slant) : V3(-c)));
                            },
                            720));

  // The regions: local minima of each f_P by a pattern search from the best lattice directions
  // inside P's region and overall, scored by F (enumerated_depth.h).
  const std::vector<V3> directions = fibonacciLattice(2000);
  for (const auto& h_p : pieces) {
    best = std::min(
        best, pieceMinimum([&](const V3& v) { return h_a(v) + h_p(V3(-v)); }, F, directions, 4));
  }
  return best;
}

}  // namespace test
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TEST_ROUND_DEPTH_H
