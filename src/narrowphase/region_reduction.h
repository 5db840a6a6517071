#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_REGION_REDUCTION_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_REGION_REDUCTION_H

// Internal: the plane geometry a contact region is made of, shared by the region of one pair
// (contact_region.h) and the merging of a mesh's regions (region_merge.h): places with their
// coordinates on the contact plane, the convex hull of points on the plane, and the reduction
// of a region's places to the few contact points a simulator keeps (docs/math.md → "Contact
// regions").

#include <algorithm>
#include <limits>
#include <vector>

#include "fcl_superellipsoid/contact_manifold.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
using Vector2 = Eigen::Matrix<S, 2, 1>;

template <typename S>
S cross2(const Vector2<S>& a, const Vector2<S>& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// A place of a region with its coordinates on the contact plane.
template <typename S>
struct Place {
  ManifoldPoint<S> point;
  Vector2<S> y;
};

/// The indices of the points' convex hull, counter-clockwise, without collinear points
/// (Andrew's monotone chain); every index for fewer than three points.
template <typename S>
std::vector<std::size_t> hullOrder(const std::vector<Vector2<S>>& points) {
  const std::size_t n = points.size();
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  if (n < 3) return order;
  std::sort(order.begin(), order.end(), [&points](std::size_t a, std::size_t b) {
    const Vector2<S>& p = points[a];
    const Vector2<S>& q = points[b];
    return p.x() < q.x() || (p.x() == q.x() && (p.y() < q.y() || (p.y() == q.y() && a < b)));
  });
  std::vector<std::size_t> hull(2 * n);
  std::size_t k = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t start = k;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = pass == 0 ? order[i] : order[n - 1 - i];
      while (k >= start + 2 && cross2(Vector2<S>(points[hull[k - 1]] - points[hull[k - 2]]),
                                      Vector2<S>(points[j] - points[hull[k - 2]])) <= S(0)) {
        --k;
      }
      hull[k++] = j;
    }
    --k;  // the last point starts the other chain
  }
  hull.resize(k);
  return hull;
}

/// The area of the points' convex hull.
template <typename S>
S hullArea(const std::vector<Vector2<S>>& points) {
  if (points.size() < 3) return S(0);
  const std::vector<std::size_t> hull = hullOrder(points);
  S area = S(0);
  for (std::size_t i = 0; i < hull.size(); ++i) {
    area += cross2(points[hull[i]], points[hull[(i + 1) % hull.size()]]);
  }
  return S(0.5) * area;
}

/// At most `max_points` of the candidates: the deepest (of those within `tie` of the deepest
/// depth, the first: the outline's vertices come before the hit's place, so that a flat
/// contact is held at its corners), then the farthest from it, then each time the one that adds
/// the most area to their hull; fewer where the rest add no more than `merge` (length) or
/// merge² (area).
template <typename S>
std::vector<ManifoldPoint<S>> reduce(const std::vector<Place<S>>& candidates, int max_points, S tie,
                                     S merge) {
  std::vector<ManifoldPoint<S>> out;
  if (candidates.empty()) return out;
  S deepest = -std::numeric_limits<S>::infinity();
  for (const Place<S>& c : candidates) deepest = std::max(deepest, c.point.depth);
  std::size_t first = 0;
  while (candidates[first].point.depth < deepest - tie) ++first;
  std::vector<std::size_t> chosen{first};
  std::vector<Vector2<S>> hull{candidates[first].y};
  while (static_cast<int>(chosen.size()) < max_points) {
    std::size_t best = candidates.size();
    S best_gain = chosen.size() == 1 ? merge : merge * merge;
    const S base = hullArea(hull);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (std::find(chosen.begin(), chosen.end(), i) != chosen.end()) continue;
      S gain;
      if (chosen.size() == 1) {
        gain = (candidates[i].y - hull[0]).norm();
      } else {
        hull.push_back(candidates[i].y);
        gain = hullArea(hull) - base;
        hull.pop_back();
      }
      // A later candidate must gain clearly more: ties go to the earlier one, whatever the
      // rounding (the order of the candidates turns with the pair).
      if (gain > best_gain * (S(1) + S(1e-6))) best = i, best_gain = gain;
    }
    if (best == candidates.size()) break;
    chosen.push_back(best);
    hull.push_back(candidates[best].y);
  }
  for (std::size_t i : chosen) out.push_back(candidates[i].point);
  return out;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_REGION_REDUCTION_H
