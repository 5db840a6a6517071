#ifndef FCL_SUPERELLIPSOID_TEST_ENUMERATED_DEPTH_H
#define FCL_SUPERELLIPSOID_TEST_ENUMERATED_DEPTH_H

// The two searches the enumerated depths share (polytope_depth.h, round_depth.h), in long double;
// shares no code with src/. The depth is min over unit v of F(v) = h_A(v) + h_B(−v), where B is
// the hull of pieces P whose f_P(v) = h_A(v) + h_P(−v) are smooth, F = max over P of f_P:
//  - borderMinimum: the least local minimum of F along a closed curve of directions (the border
//    of two pieces' regions), sampled and each sampled local minimum refined by a golden-section
//    search on its bracket;
//  - pieceMinimum: the least F at the ends of pattern searches on f_P, started from the best
//    lattice directions inside P's region (where f_P = F) and overall.

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "pair_construction.h"

namespace fcl_superellipsoid {
namespace test {

/// `n` directions spread over the unit sphere (a Fibonacci lattice).
inline std::vector<V3> fibonacciLattice(int n) {
  std::vector<V3> directions;
  for (int i = 0; i < n; ++i) {
    const LD z = 1 - (2 * LD(i) + 1) / n, r = std::sqrt(std::max(LD(0), 1 - z * z));
    const LD phi = LD(2.39996322972865332) * i;
    directions.push_back(V3(r * std::cos(phi), r * std::sin(phi), z));
  }
  return directions;
}

/// The least local minimum of g over the closed curve θ ∈ [0, 2π): `samples` samples, each local
/// minimum among them refined by a golden-section search on its two neighbours' bracket.
inline LD borderMinimum(const std::function<LD(LD)>& g, int samples) {
  const LD step = LD(2 * M_PI) / samples;
  std::vector<LD> g_s(samples);
  for (int s = 0; s < samples; ++s) g_s[s] = g(s * step);
  LD best = std::numeric_limits<LD>::infinity();
  for (int s = 0; s < samples; ++s) {
    if (g_s[s] > g_s[(s + samples - 1) % samples] || g_s[s] > g_s[(s + 1) % samples]) continue;
    LD lo = (s - 1) * step, hi = (s + 1) * step;
    const LD ratio = (std::sqrt(LD(5)) - 1) / 2;
    LD x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
    LD f1 = g(x1), f2 = g(x2);
    for (int it = 0; it < 120 && hi - lo > LD(1e-17); ++it) {
      if (f1 <= f2) {
        hi = x2, x2 = x1, f2 = f1;
        x1 = hi - ratio * (hi - lo), f1 = g(x1);
      } else {
        lo = x1, x1 = x2, f1 = f2;
        x2 = lo + ratio * (hi - lo), f2 = g(x2);
      }
    }
    best = std::min({best, f1, f2, g_s[s]});
  }
  return best;
}

/// The least F at the ends of pattern searches on the smooth piece function f, from the best
/// `starts` of `directions` inside the piece's region (f ≥ F there, up to rounding: f = F) and
/// the best `starts` overall (the piece's minimum inside its region is near the former when it
/// is there, and f may have a lower minimum outside the region).
inline LD pieceMinimum(const std::function<LD(const V3&)>& f, const std::function<LD(const V3&)>& F,
                       const std::vector<V3>& directions, int starts) {
  std::vector<std::pair<LD, V3>> inside, all;
  for (const V3& v : directions) {
    const LD fv = f(v);
    all.push_back({fv, v});
    if (fv >= F(v) - LD(1e-12) * (1 + std::abs(fv))) inside.push_back({fv, v});
  }
  auto by_value = [](const auto& x, const auto& y) { return x.first < y.first; };
  std::vector<std::pair<LD, V3>> chosen;
  for (auto* points : {&inside, &all}) {
    const std::size_t k = std::min<std::size_t>(std::size_t(starts), points->size());
    std::partial_sort(points->begin(), points->begin() + k, points->end(), by_value);
    chosen.insert(chosen.end(), points->begin(), points->begin() + k);
  }
  LD best = std::numeric_limits<LD>::infinity();
  for (const auto& [f0, v0] : chosen) {
    V3 v = v0;
    LD fv = f0;
    patternSearch(f, v, fv, 8, LD(1e-15));
    best = std::min(best, F(v));
  }
  return best;
}

}  // namespace test
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TEST_ENUMERATED_DEPTH_H
