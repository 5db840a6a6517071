#include "narrowphase/capsule_pair.h"

#include <array>

#include "narrowphase/depth_candidates.h"
#include "narrowphase/feature_newton.h"
#include "narrowphase/feature_pair.h"
#include "narrowphase/libccd_pair.h"
#include "narrowphase/segment_search.h"

namespace fcl_superellipsoid {
namespace detail {
template <typename S>
std::optional<PairHit<S>> capsuleHit(const ShapePair<S>& pair, const fcl::Capsule<S>& capsule) {
  const Vector3<S> half_axis = pair.X_WO->linear().col(2) * (capsule.lz / 2);
  const Vector3<S> centre = pair.X_WO->translation();
  const Vector3<S> p0 = centre - half_axis, p1 = centre + half_axis;
  const S radius = capsule.radius;
  // The axis apart from the shape: against the shape's support function (feature_newton.h),
  // certified by the duality gap of the axis (feature_pair.h); the capsule's answer is the axis's
  // moved by the radius, an overlap too where the axis stays outside. Else the point queries.
  if (const std::optional<PairHit<S>> axis = segmentApart(
          *pair.shape, *pair.X_WS, p0, p1, Vector3<S>(centre - pair.X_WS->translation()))) {
    auto support = [&](const Vector3<S>& u) { return std::max(u.dot(p0), u.dot(p1)); };
    Candidates<S, decltype(support)> candidates(pair, support, capsule.lz / 2 + radius);
    if (candidates.offer(*axis)) {
      return PairHit<S>{axis->distance - radius, Vector3<S>(axis->on_other - radius * axis->normal),
                        axis->on_shape, axis->normal, -1};
    }
  }
  const SegmentMinimum<S> m = nearestOnSegment(*pair.shape, *pair.X_WS, p0, p1);
  if (!(m.at.distance > S(0))) {
    // The axis penetrates the shape: the least F over the ends' escape directions, the axis's
    // family of directions and MPR's normal (depth_candidates.h).
    auto support = [&](const Vector3<S>& u) {
      return std::max(u.dot(p0), u.dot(p1)) + radius * u.norm();
    };
    DepthCandidates<S, decltype(support)> depth(pair, support);
    if (const std::optional<PairHit<S>> start = libccdHit(pair, capsule)) {
      depth.offerDirection(start->normal);
    }
    const auto escapes = depth.offerPoints({p0, p1});
    depth.offerEdge(p0, p1);
    // An end inside the shape: the other local minima of its piece in its own region (where it
    // supports the capsule along −v: the far end lies behind it). Without them a box-like
    // shape's overlap with a capsule about its centre came out 2.6e-4 × size too deep.
    const S tolerance = overlapTolerance(*pair.shape, capsule.lz / 2 + radius);
    const std::array<Vector3<S>, 2> ends = {p0, p1};
    for (int i = 0; i < 2; ++i) {
      const Vector3<S> along = ends[1 - i] - ends[i];
      depth.offerInsidePointDescents(
          ends[i], escapes[std::size_t(i)], tolerance,
          [&](const Vector3<S>& v) { return !(v.dot(along) < S(0)); }, [] { return false; });
    }
    return depth.refinedBest();
  }
  return PairHit<S>{m.at.distance - capsule.radius,
                    Vector3<S>(m.point - capsule.radius * m.at.normal), m.at.nearest_point,
                    m.at.normal, -1};
}

#define FSE_INSTANTIATE_CAPSULE_HIT(S) \
  template std::optional<PairHit<S>> capsuleHit(const ShapePair<S>&, const fcl::Capsule<S>&);
FSE_INSTANTIATE_CAPSULE_HIT(float)
FSE_INSTANTIATE_CAPSULE_HIT(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
