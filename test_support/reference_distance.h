#ifndef FCL_SUPERELLIPSOID_TEST_REFERENCE_DISTANCE_H
#define FCL_SUPERELLIPSOID_TEST_REFERENCE_DISTANCE_H

// An independent reference for the point–surface distance, for tests and the benchmark's
// ground truth: a global search in long double that shares no code with src/.
//
// The nearest point of a first-octant query is in the first octant (reflecting a nearest
// point's coordinate into the query's sign never moves it away), so the search covers the
// first-octant surface, parametrised by directions d(α, β) of the unit sphere, scaled by the
// radii and projected radially onto the surface (and, for exponents below 0.1, also by the
// paper's Eq. 4 angles, which crowd at razor edges). A 33 × 33 grid over the octant and a
// 8× finer one around the query's own direction find the basins (each grid's local minima,
// the best 4); each is refined by a pattern search (8 directions, step halving
// down to 1e-9 rad). The distance is stationary at the minimum, so a parameter error δ costs
// only O(δ²) in distance: far below 1e-15 relative. The nearest point is good to ~1e-9.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace fcl_superellipsoid {
namespace test {

struct ReferenceResult {
  long double distance;                // signed
  std::array<long double, 3> nearest;  // in the query's octant
};

class ReferenceDistance {
 public:
  ReferenceDistance(std::array<long double, 3> radii, long double eps1, long double eps2)
      : a_(radii), e1_(eps1), e2_(eps2) {}

  /// G = F^(ε2/2), straight from F's formula, coordinates divided by their largest |x_i/a_i|.
  long double gauge(const std::array<long double, 3>& x) const {
    long double u[3], m = 0;
    for (int i = 0; i < 3; ++i) {
      u[i] = std::fabs(x[i] / a_[i]);
      m = std::max(m, u[i]);
    }
    if (m == 0) return 0;
    for (long double& ui : u) ui /= m;
    const long double xy = std::pow(u[0], 2 / e1_) + std::pow(u[1], 2 / e1_);
    return m * std::pow(std::pow(xy, e1_ / e2_) + std::pow(u[2], 2 / e2_), e2_ / 2);
  }

  ReferenceResult query(const std::array<long double, 3>& x) const {
    std::array<long double, 3> y{std::fabs(x[0]), std::fabs(x[1]), std::fabs(x[2])};
    const long double half_pi = std::acos(-1.0L) / 2;
    Sample best = search(y, false, {0, half_pi, 0, half_pi});
    // A second, 8× finer grid around the query's own direction: a nearby feature smaller
    // than the coarse spacing (a pinched tip, the small faces of a box-like cross-section near
    // a pole) has a basin there that the coarse grid can step over. Around the pole, where α
    // is degenerate, the window spans every α.
    const long double rho = std::hypot(y[0] / a_[0], y[1] / a_[1]);
    const long double alpha0 = std::atan2(y[1] / a_[1], y[0] / a_[0]);
    const long double beta0 = std::atan2(rho, y[2] / a_[2]);
    const long double w = 2 * half_pi / 32;
    const Window zoom = beta0 < w
                            ? Window{0, half_pi, 0, 2 * w}
                            : Window{std::max(0.0L, alpha0 - w), std::min(half_pi, alpha0 + w),
                                     std::max(0.0L, beta0 - w), std::min(half_pi, beta0 + w)};
    const Sample local = search(y, false, zoom);
    if (local.d2 < best.d2) best = local;
    // The parametric pass is only needed where the radial grid is coarse: razor edges.
    const Sample parametric = std::min(e1_, e2_) < 0.1L ? search(y, true, {0, half_pi, 0, half_pi})
                                                        : Sample{INFINITY, 0, 0};
    parametric_ = false;
    const std::array<long double, 3> p = parametric.d2 < best.d2
                                             ? parametricPoint(parametric.alpha, parametric.beta)
                                             : point(best.alpha, best.beta);
    if (parametric.d2 < best.d2) best = parametric;
    ReferenceResult r;
    const bool inside = gauge(y) < 1;
    r.distance = (inside ? -1 : 1) * std::sqrt(best.d2);
    for (int i = 0; i < 3; ++i) r.nearest[i] = x[i] < 0 ? -p[i] : p[i];
    return r;
  }

 private:
  struct Sample {
    long double d2, alpha, beta;
  };

  /// Grid + refinement in one parametrisation: radial directions, or the paper's Eq. 4
  /// angles (which crowd at the edges of box-like shapes, where the radial grid is coarse).
  struct Window {
    long double alpha_lo, alpha_hi, beta_lo, beta_hi;
  };

  Sample search(const std::array<long double, 3>& y, bool parametric, const Window& window) const {
    parametric_ = parametric;
    const int n = 32;
    std::vector<Sample> grid((n + 1) * (n + 1));
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n; ++j) {
        const long double alpha = window.alpha_lo + (window.alpha_hi - window.alpha_lo) * i / n;
        const long double beta = window.beta_lo + (window.beta_hi - window.beta_lo) * j / n;
        grid[i * (n + 1) + j] = {dist2(y, alpha, beta), alpha, beta};
      }
    }
    // Every basin: the grid's local minima (no lower neighbour), best first, at most 12.
    std::vector<Sample> starts;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n; ++j) {
        const long double v = grid[i * (n + 1) + j].d2;
        bool lowest = true;
        for (int di = -1; di <= 1 && lowest; ++di) {
          for (int dj = -1; dj <= 1 && lowest; ++dj) {
            const int a = i + di, b = j + dj;
            if ((di || dj) && a >= 0 && a <= n && b >= 0 && b <= n) {
              lowest = grid[a * (n + 1) + b].d2 >= v;
            }
          }
        }
        if (lowest) starts.push_back(grid[i * (n + 1) + j]);
      }
    }
    std::sort(starts.begin(), starts.end(),
              [](const Sample& p, const Sample& q) { return p.d2 < q.d2; });
    if (starts.size() > 4) starts.resize(4);
    Sample best = starts[0];
    for (const Sample& start : starts) {
      const Sample s =
          refine(y, start,
                 std::max(window.alpha_hi - window.alpha_lo, window.beta_hi - window.beta_lo) / n);
      if (s.d2 < best.d2) best = s;
    }
    return best;
  }

  std::array<long double, 3> parametricPoint(long double omega, long double eta) const {
    auto spow = [](long double c, long double e) { return std::pow(std::fabs(c), e); };
    return {a_[0] * spow(std::cos(eta), e2_) * spow(std::cos(omega), e1_),
            a_[1] * spow(std::cos(eta), e2_) * spow(std::sin(omega), e1_),
            a_[2] * spow(std::sin(eta), e2_)};
  }

  std::array<long double, 3> point(long double alpha, long double beta) const {
    std::array<long double, 3> d{a_[0] * std::sin(beta) * std::cos(alpha),
                                 a_[1] * std::sin(beta) * std::sin(alpha), a_[2] * std::cos(beta)};
    const long double g = gauge(d);
    return {d[0] / g, d[1] / g, d[2] / g};
  }

  long double dist2(const std::array<long double, 3>& y, long double alpha,
                    long double beta) const {
    const auto p = parametric_ ? parametricPoint(alpha, beta) : point(alpha, beta);
    return (p[0] - y[0]) * (p[0] - y[0]) + (p[1] - y[1]) * (p[1] - y[1]) +
           (p[2] - y[2]) * (p[2] - y[2]);
  }

  Sample refine(const std::array<long double, 3>& y, Sample s, long double step) const {
    const long double half_pi = std::acos(-1.0L) / 2;
    const long double max_step = step;
    const int dirs[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}};
    // Pattern search: expand after a successful move, contract after a failed sweep, so a
    // long valley is crossed in a few steps instead of crawled at the smallest one.
    for (int sweeps = 0; step > 1e-9L && sweeps < 2000; ++sweeps) {
      bool moved = false;
      for (const auto& d : dirs) {
        const long double alpha = std::clamp(s.alpha + d[0] * step, 0.0L, half_pi);
        const long double beta = std::clamp(s.beta + d[1] * step, 0.0L, half_pi);
        const long double d2 = dist2(y, alpha, beta);
        if (d2 < s.d2) {
          s = {d2, alpha, beta};
          moved = true;
        }
      }
      step = moved ? std::min(2 * step, max_step) : step / 2;
    }
    return s;
  }

  std::array<long double, 3> a_;
  long double e1_, e2_;
  mutable bool parametric_ = false;
};

}  // namespace test
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TEST_REFERENCE_DISTANCE_H
