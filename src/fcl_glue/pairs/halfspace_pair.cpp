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

/// The hit of the plane's side `side` (+1: the side n points to, a halfspace's outside; −1: the
/// other side of a plane), given the shape's extreme point p along −side·n: its signed distance
/// to that side, the foot on the plane, and the direction from the shape to the plane.
template <typename S>
PairHit<S> sideHit(const WorldPlane<S>& plane, S side, const Vector3<S>& p) {
  const Vector3<S> toward = -side * plane.n;  // from the shape to the plane, when separated
  const S distance = side * (plane.n.dot(p) - plane.d);
  return {distance, Vector3<S>(p + distance * toward), p, toward, -1};
}

}  // namespace

template <typename S>
std::optional<PairHit<S>> halfspaceHit(const Pair<S>& pair) {
  const auto* halfspace = otherAs<fcl::Halfspace<S>>(pair, fcl::GEOM_HALFSPACE);
  const auto* plane = otherAs<fcl::Plane<S>>(pair, fcl::GEOM_PLANE);
  if (halfspace == nullptr && plane == nullptr) return std::nullopt;
  const WorldPlane<S> w = halfspace != nullptr ? toWorld(halfspace->n, halfspace->d, *pair.X_WO)
                                               : toWorld(plane->n, plane->d, *pair.X_WO);
  // The shape's lowest point along n, in its frame; the shape is symmetric about its centre,
  // so its highest point is the mirror image, and one support point serves both sides.
  const Vector3<S> low_S =
      pair.shape->supportPoint(Vector3<S>(-(pair.X_WS->linear().transpose() * w.n)));
  const Vector3<S> low = *pair.X_WS * low_S;
  if (halfspace != nullptr) return sideHit(w, S(1), low);
  const Vector3<S> high = *pair.X_WS * Vector3<S>(-low_S);
  const PairHit<S> above = sideHit(w, S(1), low), below = sideHit(w, S(-1), high);
  // Above: lowest − d; below: d − highest. Separated on one side, that one is positive and
  // the other is negative; straddling, both are ≤ 0 and the larger is the shorter way out.
  return above.distance >= below.distance ? above : below;
}

#define FSE_INSTANTIATE_HALFSPACE_HIT(S) \
  template std::optional<PairHit<S>> halfspaceHit(const Pair<S>&);
FSE_INSTANTIATE_HALFSPACE_HIT(float)
FSE_INSTANTIATE_HALFSPACE_HIT(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
