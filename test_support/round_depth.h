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
#include <utility>
#include <vector>

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

  // The border: v(θ) = −m(θ), m the side's outward normal, sampled and refined.
  const LD slant = std::hypot(2 * h, r);
  auto border = [&](LD theta) {
    const V3 c = std::cos(theta) * e1 + std::sin(theta) * e2;
    const V3 m = cone ? V3((2 * h * c + r * z) / slant) : c;
    return F(V3(-m));
  };
  const int samples = 720;
  const LD step = LD(2 * M_PI) / samples;
  std::vector<LD> g_s(samples);
  for (int s = 0; s < samples; ++s) g_s[s] = border(s * step);
  for (int s = 0; s < samples; ++s) {
    if (g_s[s] > g_s[(s + samples - 1) % samples] || g_s[s] > g_s[(s + 1) % samples]) continue;
    LD lo = (s - 1) * step, hi = (s + 1) * step;
    const LD ratio = (std::sqrt(LD(5)) - 1) / 2;
    LD x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
    LD f1 = border(x1), f2 = border(x2);
    for (int it = 0; it < 120 && hi - lo > LD(1e-17); ++it) {
      if (f1 <= f2) {
        hi = x2, x2 = x1, f2 = f1;
        x1 = hi - ratio * (hi - lo), f1 = border(x1);
      } else {
        lo = x1, x1 = x2, f1 = f2;
        x2 = lo + ratio * (hi - lo), f2 = border(x2);
      }
    }
    best = std::min({best, f1, f2, g_s[s]});
  }

  // The regions: local minima of each f_P by a pattern search from the best lattice directions
  // inside P's region and overall, scored by F.
  const int lattice = 2000, starts = 4;
  std::vector<V3> directions;
  for (int i = 0; i < lattice; ++i) {
    const LD zz = 1 - (2 * LD(i) + 1) / lattice, rr = std::sqrt(std::max(LD(0), 1 - zz * zz));
    const LD phi = LD(2.39996322972865332) * i;
    directions.push_back(V3(rr * std::cos(phi), rr * std::sin(phi), zz));
  }
  for (const auto& h_p : pieces) {
    auto f = [&](const V3& v) { return h_a(v) + h_p(V3(-v)); };
    std::vector<std::pair<LD, V3>> inside, all;
    for (const V3& v : directions) {
      const LD fv = f(v);
      all.push_back({fv, v});
      if (fv >= F(v) - LD(1e-12) * (1 + std::abs(fv))) inside.push_back({fv, v});
    }
    auto by_value = [](const auto& x, const auto& y) { return x.first < y.first; };
    std::vector<std::pair<LD, V3>> chosen;
    for (auto* points : {&inside, &all}) {
      const std::size_t k = std::min<std::size_t>(starts, points->size());
      std::partial_sort(points->begin(), points->begin() + k, points->end(), by_value);
      chosen.insert(chosen.end(), points->begin(), points->begin() + k);
    }
    for (const auto& [f0, v0] : chosen) {
      V3 v = v0;
      LD fv = f0;
      patternSearch(f, v, fv, 8, LD(1e-15));
      best = std::min(best, F(v));
    }
  }
  return best;
}

}  // namespace test
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TEST_ROUND_DEPTH_H
