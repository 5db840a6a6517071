#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SEGMENT_SEARCH_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SEGMENT_SEARCH_H

// Internal: one-dimensional searches of the exact pairs.
//
// stationaryPoint: where a derivative changes sign inside a bracket, by regula falsi (Illinois),
// with a bisection whenever three steps have not halved the bracket, until two iterates (or the
// bracket) are a few ulps apart; the sample with the smallest derivative.
//
// nearestOnSegment: the point of a segment nearest to the superellipsoid (least signed
// distance), for the capsule's axis and a polytope's edges. The signed distance to a convex set
// is convex, so along p(t) = p0 + t·(p1 − p0) it has one minimum; its derivative is
// n(t)·(p1 − p0), with n(t) the surface normal at p(t)'s nearest point (exact from the point
// solver), each point query warm-started from the previous one (WarmPointQueries).

#include <limits>

#include "fcl_superellipsoid/point_distance.h"
#include "solvers/solvers.h"

namespace fcl_superellipsoid {
namespace detail {

/// A sample of a search: the parameter, the derivative there, and what was computed with it.
template <typename S, typename Payload>
struct Sample {
  S x;
  S derivative;
  Payload payload;
};

/// The sample where `at(x)` (returning a Sample) has a derivative that changes sign between lo
/// (negative) and hi (positive); the end with the smaller derivative magnitude if the bracket
/// closes first.
template <typename S, typename Payload, typename At>
Sample<S, Payload> stationaryPoint(At at, Sample<S, Payload> lo, Sample<S, Payload> hi) {
  S d_lo = lo.derivative, d_hi = hi.derivative;  // Illinois weights
  int last = 0;                                  // the end moved last (−1 low, +1 high)
  const S width =
      S(4) * std::numeric_limits<S>::epsilon() * (S(1) + std::abs(lo.x) + std::abs(hi.x));
  Sample<S, Payload> best = -lo.derivative <= hi.derivative ? lo : hi;
  S previous = std::numeric_limits<S>::quiet_NaN();
  S block_span = hi.x - lo.x;  // the bracket three steps ago: it must have halved since
  for (int it = 1; it <= 100 && hi.x - lo.x > width; ++it) {
    const bool bisect = it % 3 == 0 && hi.x - lo.x > S(0.5) * block_span;
    if (it % 3 == 0) block_span = hi.x - lo.x;
    S x = bisect ? S(0.5) * (lo.x + hi.x) : lo.x + (hi.x - lo.x) * d_lo / (d_lo - d_hi);
    if (!(x > lo.x && x < hi.x)) x = S(0.5) * (lo.x + hi.x);
    const Sample<S, Payload> mid = at(x);
    if (std::abs(mid.derivative) < std::abs(best.derivative)) best = mid;
    if (mid.derivative == S(0)) break;
    if (mid.derivative < S(0)) {
      lo = mid;
      d_lo = mid.derivative;
      if (last == -1) d_hi *= S(0.5);
      last = -1;
    } else {
      hi = mid;
      d_hi = mid.derivative;
      if (last == 1) d_lo *= S(0.5);
      last = 1;
    }
    // Converged: the secant iterates no longer move.
    if (std::abs(x - previous) <= width) break;
    previous = x;
  }
  return best;
}

template <typename S>
struct SegmentMinimum {
  S t;                        // in [0, 1]
  Vector3<S> point;           // p(t), world
  PointDistanceResult<S> at;  // the point query at p(t), world
};

/// Point queries at a sequence of nearby world points (a search along a segment or a rim), each
/// warm-started from the previous one's nearest point: outside, a converged warm start is the
/// answer (solvers.h), and it converges in a few iterations where the points are close.
template <typename S>
class WarmPointQueries {
 public:
  WarmPointQueries(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS)
      : shape_(shape), X_WS_(X_WS), X_SW_(X_WS.inverse(Eigen::Isometry)) {}

  /// pointDistance(shape, X_WS, p_W, shape.queryOptions()), in world coordinates.
  PointDistanceResult<S> operator()(const Vector3<S>& p_W) {
    PointDistanceResult<S> r =
        pointDistanceWithHint(shape_, Vector3<S>(X_SW_ * p_W), hint_S_, shape_.queryOptions());
    hint_S_ = r.nearest_point;
    r.nearest_point = X_WS_ * r.nearest_point;
    r.normal = X_WS_.linear() * r.normal;
    return r;
  }

 private:
  const Superellipsoid<S>& shape_;
  const fcl::Transform3<S>& X_WS_;
  const fcl::Transform3<S> X_SW_;
  Vector3<S> hint_S_ = Vector3<S>::Constant(std::numeric_limits<S>::quiet_NaN());  // none yet
};

template <typename S>
SegmentMinimum<S> nearestOnSegment(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
                                   const Vector3<S>& p0, const Vector3<S>& p1) {
  const Vector3<S> e = p1 - p0;
  WarmPointQueries<S> query(shape, X_WS);
  auto at = [&](S t) {
    const Vector3<S> p = p0 + t * e;
    const PointDistanceResult<S> r = query(p);
    return Sample<S, SegmentMinimum<S>>{t, r.normal.dot(e), {t, p, r}};
  };
  const auto lo = at(S(0)), hi = at(S(1));
  if (!(lo.derivative < S(0))) return lo.payload;
  if (!(hi.derivative > S(0))) return hi.payload;
  return stationaryPoint<S>(at, lo, hi).payload;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SEGMENT_SEARCH_H
