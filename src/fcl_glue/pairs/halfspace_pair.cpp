#include "fcl_glue/pairs/halfspace_pair.h"

#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>

namespace fcl_superellipsoid {
namespace detail {
namespace {

/// The plane n·x = d of a halfspace or plane given in the other geometry's frame, in world
/// coordinates.
template <typename S>
struct WorldPlane {
  Vector3<S> n;
  S d;
};

template <typename S>
WorldPlane<S> toWorld(const Vector3<S>& n_O, S d_O, const fcl::Transform3<S>& X_WO) {
  const Vector3<S> n = X_WO.linear() * n_O;
  return {n, d_O + n.dot(X_WO.translation())};
}

/// The shape's extreme point along −n (side = −1) or +n (side = +1), its signed distance to the
/// plane's side facing it, and the hit.
template <typename S>
PairHit<S> sideHit(const Pair<S>& pair, const WorldPlane<S>& plane, S side) {
  const Vector3<S> toward = -side * plane.n;  // from the shape to the plane, when separated
  const Vector3<S> p =
      *pair.X_WS * pair.shape->supportPoint(Vector3<S>(pair.X_WS->linear().transpose() * toward));
  const S distance = side * (plane.n.dot(p) - plane.d);
  const Vector3<S> on_plane = p + distance * toward;
  return {distance, on_plane, p, toward, -1};
}

}  // namespace

template <typename S>
std::optional<PairHit<S>> halfspaceHit(const Pair<S>& pair) {
  if (const auto* h = dynamic_cast<const fcl::Halfspace<S>*>(pair.other)) {
    return sideHit(pair, toWorld(h->n, h->d, *pair.X_WO), S(1));
  }
  if (const auto* plane = dynamic_cast<const fcl::Plane<S>*>(pair.other)) {
    const WorldPlane<S> w = toWorld(plane->n, plane->d, *pair.X_WO);
    const PairHit<S> above = sideHit(pair, w, S(1)), below = sideHit(pair, w, S(-1));
    // Above: lowest − d; below: d − highest. Separated on one side, that one is positive and
    // the other is negative; straddling, both are ≤ 0 and the larger is the shorter way out.
    return above.distance >= below.distance ? above : below;
  }
  return std::nullopt;
}

#define FSE_INSTANTIATE_HALFSPACE_HIT(S) \
  template std::optional<PairHit<S>> halfspaceHit(const Pair<S>&);
FSE_INSTANTIATE_HALFSPACE_HIT(float)
FSE_INSTANTIATE_HALFSPACE_HIT(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
