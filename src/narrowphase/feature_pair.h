#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_FEATURE_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_FEATURE_PAIR_H

// Internal: the pipeline every pair with flat or round features runs through (polytope_pair,
// round_pair; the capsule certifies with its Candidates): how it starts (our GJK, else
// libccd's MPR), certifies its separated answers, and finds an overlap's depth.
//
// A candidate is a pair of real surface points, on_shape and on_other: its distance is an upper
// bound of the shapes' distance. Along its direction v = (on_other − on_shape)/|…| the support
// functions give a lower bound, −h_A(v) − h_B(−v) (the gap between the two supporting planes).
// When the two bounds meet, to 1e-12 × size plus the rounding of the points' coordinates, the
// candidate is the answer (docs/math.md → "Shape pairs").

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "narrowphase/gjk.h"
#include "narrowphase/shape_pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// Keeps the best candidate; `other_support(u)` is the other geometry's support function h_B.
template <typename S, typename OtherSupport>
class Candidates {
 public:
  Candidates(const ShapePair<S>& pair, OtherSupport other_support, S other_size)
      : pair_(pair),
        other_support_(other_support),
        size_(std::max(pair.shape->size(), other_size)) {}

  /// Offers a candidate; true once the best one is certified. A candidate that overlaps by
  /// more than rounding is not one (its points do not bound a separated distance).
  bool offer(const PairHit<S>& hit) {
    if (!hit.on_shape.allFinite() || !hit.on_other.allFinite()) return false;
    const S tolerance = S(1e-12) * size_ + S(64) * std::numeric_limits<S>::epsilon() *
                                               (hit.on_shape.norm() + hit.on_other.norm() + size_);
    if (!(hit.distance >= -tolerance)) return false;
    if (has_best_ && !(hit.distance < best_.distance)) return false;
    const Vector3<S> gap = hit.on_other - hit.on_shape;
    const Vector3<S> v = gap.norm() > S(0) ? Vector3<S>(gap.normalized()) : hit.normal;
    if (!v.allFinite() || !(v.norm() > S(0.5))) return false;  // no direction to certify along
    best_ = hit;
    has_best_ = true;
    const S lower = -v.dot(shapeSupport(pair_, v)) - other_support_(Vector3<S>(-v));
    certified_ = hit.distance - lower <= tolerance;
    return certified_;
  }

  /// The best candidate if it is certified.
  std::optional<PairHit<S>> certified() const {
    return certified_ ? std::optional<PairHit<S>>(best_) : std::nullopt;
  }

 private:
  const ShapePair<S>& pair_;
  OtherSupport other_support_;
  S size_;
  PairHit<S> best_{};
  bool has_best_ = false;
  bool certified_ = false;
};

/// GJK's start (gjk.h): the relative gap between its bounds at which it stops, and its
/// iteration limit. Its answer only has to pick out the features near the contact, which the
/// separated search then solves exactly and certifies.
constexpr double kGjkRelativeGap = 1e-4;
constexpr int kGjkIterations = 64;
/// Where the features of that start are not certified, GJK once more to this gap.
constexpr double kGjkTightGap = 1e-10;
constexpr int kGjkTightIterations = 256;

/// kNearTouching × size: how deep libccd's MPR start has to find an overlap for the pairs to
/// trust its sign.
constexpr double kNearTouching = 1e-3;
/// A certified depth (the start-free candidates', depth_candidates.h) is the answer where it is
/// deeper than this × size and than the type's rounding: the certificate proves the overlap (a
/// ball about the origin inside A − B), so only a depth within rounding of 0 leaves the sign to
/// the separated search. It is the pairs' accuracy target.
constexpr double kCertifiedDepth = 1e-9;
template <typename S>
S nearTouching(const ShapePair<S>& pair, S other_size) {
  return S(kNearTouching) * std::max(pair.shape->size(), other_size);
}

/// The answer of a pair with features. `Features` is the pair kind's view of the other geometry
/// and provides its stages:
/// - `S size()`: its extent, for the size-relative tolerances;
/// - `Vector3<S> supportPoint(u)`: its point farthest along the world direction u;
/// - `std::optional<PairHit<S>> separated(start)`: the exact separated answer from a start's
///   witnesses, certified, or nothing;
/// - `std::optional<PairHit<S>> startFree()`: the overlap candidates that need no start (a
///   polytope's face normals, a cylinder's and a cone's flat ends and side), the best if it is
///   certified (depth_candidates.h);
/// - `PairHit<S> overlap(start)`: the overlap's depth from a start;
/// - `std::optional<PairHit<S>> libccdStart()`: libccd's MPR on the pair (libccd_pair.h).
///
/// The stages, in order: where our GJK (gjk.h, on the superellipsoid's exact support points
/// and the other's) finds the shapes apart, `separated` from its witnesses; if nothing is
/// certified, again from a GJK run to a tight gap. Where GJK finds them touching or
/// overlapping, `startFree`: a certified depth (kCertifiedDepth) is the answer, with no libccd
/// run. Else libccd's start: `separated` where the shapes are within kNearTouching ×
/// size of touching (the exact answer then decides the sign), else, or if nothing is certified,
/// `startFree` if it has not run, then `overlap`.
template <typename S, typename Features>
std::optional<PairHit<S>> featurePair(const ShapePair<S>& pair, const Features& features) {
  auto shape_support_point = [&pair](const Vector3<S>& u) { return shapeSupport(pair, u); };
  auto other_support_point = [&features](const Vector3<S>& u) { return features.supportPoint(u); };
  const S near = nearTouching(pair, features.size());
  const S certified_depth =
      std::max(S(kCertifiedDepth), S(64) * std::numeric_limits<S>::epsilon()) *
      std::max(pair.shape->size(), features.size());
  bool start_free_ran = false;
  for (const auto& [gap, iterations] : {std::pair<S, int>{S(kGjkRelativeGap), kGjkIterations},
                                        std::pair<S, int>{S(kGjkTightGap), kGjkTightIterations}}) {
    const std::optional<GjkSeparation<S>> apart = gjkSeparation<S>(
        shape_support_point, other_support_point,
        Vector3<S>(pair.X_WO->translation() - pair.X_WS->translation()), gap, iterations);
    if (!apart) {  // touching or overlapping (or not settled): a tighter gap will not help
      start_free_ran = true;
      const std::optional<PairHit<S>> hit = features.startFree();
      if (hit && hit->distance < -certified_depth) return hit;
      break;
    }
    const Vector3<S> normal = (apart->on_b - apart->on_a).normalized();
    if (!normal.allFinite()) break;
    if (const std::optional<PairHit<S>> answer =
            features.separated(PairHit<S>{apart->distance, apart->on_b, apart->on_a, normal, -1})) {
      return answer;
    }
  }
  const std::optional<PairHit<S>> start = features.libccdStart();
  if (!start) return std::nullopt;
  if (start->distance > -near) {
    if (const std::optional<PairHit<S>> answer = features.separated(*start)) return answer;
  }
  if (!start_free_ran) {
    if (const std::optional<PairHit<S>> hit = features.startFree()) return hit;
  }
  return features.overlap(*start);
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_FEATURE_PAIR_H
