#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_CANDIDATES_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_CANDIDATES_H

// Internal: how the exact pairs with flat or round features (polytope_pair, round_pair, and the
// capsule's hand-over) start (our GJK, else libccd), certify their separated answers, and fall
// back to libccd.
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

#include "fcl_glue/pairs/gjk.h"
#include "fcl_glue/pairs/libccd_pair.h"
#include "fcl_glue/pairs/pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// The superellipsoid's support point along the world direction v.
template <typename S>
Vector3<S> shapeSupport(const Pair<S>& pair, const Vector3<S>& v) {
  return *pair.X_WS * pair.shape->supportPoint(Vector3<S>(pair.X_WS->linear().transpose() * v));
}

/// Keeps the best candidate; `other_support(u)` is the other geometry's support function h_B.
template <typename S, typename OtherSupport>
class Candidates {
 public:
  Candidates(const Pair<S>& pair, OtherSupport other_support, S other_size)
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
  const Pair<S>& pair_;
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

/// The pair's answer. Where our GJK (gjk.h, with the superellipsoid's exact support points and
/// `other_support_point(u)`, the other geometry's point farthest along u) finds the shapes apart,
/// `separated(start)` (an std::optional<PairHit<S>>, certified or nothing) from its witnesses;
/// if nothing is certified, again from a GJK run to a tight gap. Otherwise the overlap's
/// candidates: `first()` offers those that need no start (a polytope's face normals, a cylinder's
/// and a cone's flat ends and side) and gives the best if it is certified (depth_candidates.h);
/// a certified depth above kNearTouching × size is the answer, with no libccd run (MPR took a
/// quarter of a cylinder's overlap). Else libccd's overlap start (MPR, libccd_pair.h):
/// `separated(start)` where the shapes are within kNearTouching × size of touching (the exact
/// answer then decides the sign), else, or if nothing is certified, `overlap(start)` (a PairHit:
/// depth_candidates.h), after `first()` if it has not run.
constexpr double kNearTouching = 1e-3;
/// kNearTouching × size: how deep an overlap has to be for the pairs to trust its sign.
template <typename S>
S nearTouching(const Pair<S>& pair, S other_size) {
  return S(kNearTouching) * std::max(pair.shape->size(), other_size);
}
template <typename S, typename OtherSupportPoint, typename Separated, typename First,
          typename Overlap>
std::optional<PairHit<S>> exactPair(const Pair<S>& pair, S other_size,
                                    const OtherSupportPoint& other_support_point,
                                    Separated separated, First first, Overlap overlap) {
  auto shape_support_point = [&pair](const Vector3<S>& u) { return shapeSupport(pair, u); };
  const S near = nearTouching(pair, other_size);
  bool first_ran = false;
  for (const auto& [gap, iterations] : {std::pair<S, int>{S(kGjkRelativeGap), kGjkIterations},
                                        std::pair<S, int>{S(kGjkTightGap), kGjkTightIterations}}) {
    const std::optional<GjkSeparation<S>> apart = gjkSeparation<S>(
        shape_support_point, other_support_point,
        Vector3<S>(pair.X_WO->translation() - pair.X_WS->translation()), gap, iterations);
    if (!apart) {  // touching or overlapping (or not settled): a tighter gap will not help
      first_ran = true;
      const std::optional<PairHit<S>> hit = first();
      if (hit && hit->distance < -near) return hit;
      break;
    }
    const Vector3<S> normal = (apart->on_b - apart->on_a).normalized();
    if (!normal.allFinite()) break;
    if (const std::optional<PairHit<S>> answer =
            separated(PairHit<S>{apart->distance, apart->on_b, apart->on_a, normal, -1})) {
      return answer;
    }
  }
  const std::optional<PairHit<S>> start = libccdHit(pair);
  if (!start) return std::nullopt;
  if (start->distance > -near) {
    if (const std::optional<PairHit<S>> answer = separated(*start)) return answer;
  }
  if (!first_ran) {
    if (const std::optional<PairHit<S>> hit = first()) return hit;
  }
  return overlap(*start);
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_CANDIDATES_H
