#include "narrowphase/halfspace_pair.h"

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

/// The shape's lowest point along the plane's normal, in its frame. The shape is symmetric
/// about its centre, so its highest point is the mirror image, and one support point serves
/// both sides.
template <typename S>
Vector3<S> lowestAlong(const ShapePair<S>& pair, const WorldPlane<S>& w) {
  return pair.shape->supportPoint(Vector3<S>(-(pair.X_WS->linear().transpose() * w.n)));
}

}  // namespace

template <typename S>
std::optional<PairHit<S>> halfspaceHit(const ShapePair<S>& pair,
                                       const fcl::Halfspace<S>& halfspace) {
  const WorldPlane<S> w = toWorld(halfspace.n, halfspace.d, *pair.X_WO);
  return sideHit(w, S(1), Vector3<S>(*pair.X_WS * lowestAlong(pair, w)));
}

template <typename S>
std::optional<PairHit<S>> planeHit(const ShapePair<S>& pair, const fcl::Plane<S>& plane) {
  const WorldPlane<S> w = toWorld(plane.n, plane.d, *pair.X_WO);
  const Vector3<S> low_S = lowestAlong(pair, w);
  const Vector3<S> low = *pair.X_WS * low_S;
  const Vector3<S> high = *pair.X_WS * Vector3<S>(-low_S);
  const PairHit<S> above = sideHit(w, S(1), low), below = sideHit(w, S(-1), high);
  // Above: lowest − d; below: d − highest. Separated on one side, that one is positive and
  // the other is negative; straddling, both are ≤ 0 and the larger is the shorter way out.
  return above.distance >= below.distance ? above : below;
}

#define FSE_INSTANTIATE_HALFSPACE_HIT(S)                                                          \
  template std::optional<PairHit<S>> halfspaceHit(const ShapePair<S>&, const fcl::Halfspace<S>&); \
  template std::optional<PairHit<S>> planeHit(const ShapePair<S>&, const fcl::Plane<S>&);
FSE_INSTANTIATE_HALFSPACE_HIT(float)
FSE_INSTANTIATE_HALFSPACE_HIT(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
