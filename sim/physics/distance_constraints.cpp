#include "physics/distance_constraints.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace fse_sim {

namespace {

/// The pairs reordered by a greedy colouring: pairs of one colour share no vertex, and each
/// colour is contiguous (colour c is [colour_begin[c], colour_begin[c + 1])). Consecutive
/// projections then touch different vertices, so the CPU overlaps them instead of waiting for
/// each to store what the next one loads, and a colour can be split across threads with the
/// same result, bit for bit.
std::vector<std::array<int, 2>> colourOrdered(const std::vector<std::array<int, 2>>& pairs,
                                              std::vector<std::size_t>& colour_begin) {
  int vertices = 0;
  for (const auto& p : pairs) vertices = std::max({vertices, p[0] + 1, p[1] + 1});
  std::vector<std::uint64_t> used(std::size_t(vertices), 0);  // colours (< 64) at each vertex
  std::vector<std::vector<std::array<int, 2>>> by_colour;
  std::vector<std::array<int, 2>> overflow;  // a vertex with 64 colours: kept in order
  for (const auto& p : pairs) {
    const std::uint64_t taken = used[std::size_t(p[0])] | used[std::size_t(p[1])];
    if (taken == ~std::uint64_t(0)) {
      overflow.push_back(p);
      continue;
    }
    int colour = 0;
    while (taken & (std::uint64_t(1) << colour)) ++colour;
    used[std::size_t(p[0])] |= std::uint64_t(1) << colour;
    used[std::size_t(p[1])] |= std::uint64_t(1) << colour;
    if (by_colour.size() <= std::size_t(colour)) by_colour.resize(std::size_t(colour) + 1);
    by_colour[std::size_t(colour)].push_back(p);
  }
  std::vector<std::array<int, 2>> ordered;
  ordered.reserve(pairs.size());
  colour_begin.clear();
  for (const auto& group : by_colour) {
    colour_begin.push_back(ordered.size());
    ordered.insert(ordered.end(), group.begin(), group.end());
  }
  // Pairs of a vertex with 64 colours already (none on a cloth grid): one at a time, in order.
  for (const auto& p : overflow) {
    colour_begin.push_back(ordered.size());
    ordered.push_back(p);
  }
  colour_begin.push_back(ordered.size());
  return ordered;
}

}  // namespace

DistanceConstraints::DistanceConstraints(const std::vector<std::array<int, 2>>& pairs,
                                         const Eigen::Matrix3Xd& rest, double compliance)
    : pairs_(colourOrdered(pairs, colour_begin_)), compliance_(compliance) {
  rest_length_.reserve(pairs.size());
  for (const auto& p : pairs_) rest_length_.push_back((rest.col(p[0]) - rest.col(p[1])).norm());
}

void DistanceConstraints::projectRange(std::size_t first, std::size_t last, Eigen::Matrix3Xd& x,
                                       const Eigen::VectorXd& inverse_mass,
                                       double alpha_tilde) const {
  double* data = x.data();
  const double* w = inverse_mass.data();
  for (std::size_t k = first; k < last; ++k) {
    const int i = pairs_[k][0], j = pairs_[k][1];
    const double wsum = w[i] + w[j] + alpha_tilde;
    if (wsum <= 0) continue;  // both pinned
    double* xi = data + 3 * i;
    double* xj = data + 3 * j;
    const double dx = xi[0] - xj[0], dy = xi[1] - xj[1], dz = xi[2] - xj[2];
    const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (length <= 1e-12 * rest_length_[k]) continue;  // coincident: no direction to push along
    const double s = -(length - rest_length_[k]) / (wsum * length);  // Δλ / |x_i − x_j|
    xi[0] += w[i] * s * dx, xi[1] += w[i] * s * dy, xi[2] += w[i] * s * dz;
    xj[0] -= w[j] * s * dx, xj[1] -= w[j] * s * dy, xj[2] -= w[j] * s * dz;
  }
}

void DistanceConstraints::project(Eigen::Matrix3Xd& x, const Eigen::VectorXd& inverse_mass,
                                  double h, bool parallel) const {
  const double alpha_tilde = compliance_ / (h * h);
  for (std::size_t c = 0; c + 1 < colour_begin_.size(); ++c) {
    const std::size_t first = colour_begin_[c], last = colour_begin_[c + 1];
#if !defined(__SANITIZE_THREAD__)  // TSan cannot see Debian's uninstrumented TBB: serial there
    if (parallel && last - first >= 2 * kParallelGrain) {
      // One colour's pairs share no vertex: any split, any order, the same bits.
      tbb::parallel_for(tbb::blocked_range<std::size_t>(first, last, kParallelGrain),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                          projectRange(r.begin(), r.end(), x, inverse_mass, alpha_tilde);
                        });
      continue;
    }
#endif
    projectRange(first, last, x, inverse_mass, alpha_tilde);
  }
}

double DistanceConstraints::maxStrain(const Eigen::Matrix3Xd& x) const {
  double worst = 0;
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const double length = (x.col(pairs_[k][0]) - x.col(pairs_[k][1])).norm();
    worst = std::max(worst, std::abs(length / rest_length_[k] - 1));
  }
  return worst;
}

double DistanceConstraints::energy(const Eigen::Matrix3Xd& x) const {
  if (compliance_ <= 0) return 0;
  double sum = 0;
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const double c = (x.col(pairs_[k][0]) - x.col(pairs_[k][1])).norm() - rest_length_[k];
    sum += c * c;
  }
  return sum / (2 * compliance_);
}

}  // namespace fse_sim
