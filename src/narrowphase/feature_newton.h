#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_FEATURE_NEWTON_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_FEATURE_NEWTON_H

// Internal: the superellipsoid A against a segment or a disc that lies apart from it, by Newton
// on A's support function instead of point queries, and against a point, by the point solver
// warm-started near the answer (docs/math.md → "Points, segments and discs apart: Newton on the
// support function"). A support evaluation costs a fraction of a point query, and these
// searches need a handful of them.
//
// The argument behind both searches: for a convex set B apart from A, F(v) = h_A(v) + h_B(−v)
// is negative exactly on the directions of the planes that separate them, F's Riemannian Hessian
// on the sphere (P·∇²F·P − F·P) is positive definite there, and F has one minimum there, −dist.
//
// segmentApart: for a segment with midpoint c and unit axis â, G(v) = h_A(v) − v·c on the circle
// v ⊥ â is F of the whole line (v·x is the same for every point x of the line); where the line
// misses A, G's one minimum with G < 0 is −dist(line, A), and the line's nearest point is
// b = c + ((a − c)·â)·â, a the support point. If b lies on the segment it is the segment's
// nearest point; if beyond an end, that end is (the distance along the line is convex). If the
// line meets A, the segment is apart only where its nearest point is the end nearer A, and only
// where the distance grows from that end into the segment (the derivative test of
// segment_search.h).
//
// discApart: for a disc (a cylinder's or a cone's rim with the face it bounds), F on the sphere
// with h_D the disc's support function (SupportMap::ofCircle), smooth wherever v is not along
// the disc's axis (sphere_newton.h); the disc's witness is its support point: on the rim, or its
// centre along the axis.
//
// Every answer is a pair of real points (one on A's surface, one on the feature), so its
// distance is an upper bound: the callers certify it against the support functions
// (feature_pair.h) and keep their point-query searches for what is not certified.

#include <cmath>
#include <limits>
#include <optional>

#include "narrowphase/shape_pair.h"
#include "narrowphase/sphere_newton.h"
#include "narrowphase/support_map.h"
#include "solvers/solvers.h"

namespace fcl_superellipsoid {
namespace detail {

/// Newton iterations on the circle at most.
constexpr int kCircleNewtonIterations = 100;
/// segmentApart's early look at an end: once Newton's next step on the line is under this (rad).
constexpr double kNearMinimum = 0.1;

/// A direction of the circle v(θ) = cos θ·t1 + sin θ·t2 and G there, with G' and G''.
template <typename S>
struct CircleProbe {
  S theta, g, g1, g2;
  Vector3<S> v, a;  // the direction and A's support point
};

/// The direction v ⊥ axis (unit) minimising G(v) = h_A(v) − v·c from v0's part ⊥ axis: Newton in
/// θ with a backtracking line search; G'' = t·∇²h_A·t − G (t = dv/dθ), so G is strictly convex
/// where G < 0. Stops early at an iterate with stop(probe).
template <typename S, typename Stop = bool (*)(const CircleProbe<S>&)>
CircleProbe<S> lineMinimum(
    const SupportMap<S>& A, const Vector3<S>& c, const Vector3<S>& axis, const Vector3<S>& v0,
    Stop stop = [](const CircleProbe<S>&) { return false; }) {
  Vector3<S> t1 = v0 - v0.dot(axis) * axis;
  if (!(t1.norm() > S(1e-3) * v0.norm())) t1 = axis.unitOrthogonal();
  t1.normalize();
  const Vector3<S> t2 = axis.cross(t1);
  auto at = [&](S theta) {
    const S cs = std::cos(theta), sn = std::sin(theta);
    const Vector3<S> v = cs * t1 + sn * t2, t = cs * t2 - sn * t1;
    const SupportEval<S> e = A.evaluate(v);
    const Vector3<S> d = e.point - c;
    const S g = e.value - v.dot(c);
    return CircleProbe<S>{theta, g, d.dot(t), t.dot(e.hessian * t) - g, v, e.point};
  };
  const S eps = std::numeric_limits<S>::epsilon();
  CircleProbe<S> p = at(S(0));
  for (int it = 0; it < kCircleNewtonIterations && !stop(p); ++it) {
    const S scale = std::abs(p.g2) + std::abs(p.g) + std::numeric_limits<S>::min();
    const S curvature = std::max(p.g2, S(1e-8) * scale);
    S step = -p.g1 / curvature;
    if (!std::isfinite(step)) break;
    step = std::max(S(-0.5), std::min(S(0.5), step));  // a quarter turn at most
    const S noise = S(16) * eps * (p.a.norm() + c.norm() + std::abs(p.g));
    bool moved = false;
    for (S alpha = S(1); alpha > S(1e-12); alpha *= S(0.5)) {
      const CircleProbe<S> q = at(p.theta + alpha * step);
      if (q.g <= p.g + S(1e-4) * alpha * step * p.g1 || (q.g <= p.g + noise && alpha == S(1))) {
        moved = q.theta != p.theta;
        p = q;
        break;
      }
    }
    if (!moved || std::abs(step) < S(64) * eps) break;
  }
  return p;
}

/// pointApart's hint for none: the point solver starts on its own.
template <typename S>
Vector3<S> noHint() {
  return Vector3<S>::Constant(std::numeric_limits<S>::quiet_NaN());
}

/// p and the shape's (posed by X_WS) point nearest to it, a negative distance where p lies
/// inside: the point solver, warm-started at hint_W, a point of the shape's surface near the
/// answer (outside, a converged warm start is the answer: solvers.h); nothing if it is not finite.
template <typename S>
std::optional<PairHit<S>> pointApart(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
                                     const Vector3<S>& p, const Vector3<S>& hint_W) {
  const fcl::Transform3<S> X_SW = X_WS.inverse(Eigen::Isometry);
  const PointDistanceResult<S> r = pointDistanceWithHint(
      shape, Vector3<S>(X_SW * p), Vector3<S>(X_SW * hint_W), shape.queryOptions());
  if (!std::isfinite(r.distance)) return std::nullopt;
  return PairHit<S>{r.distance, p, Vector3<S>(X_WS * r.nearest_point),
                    Vector3<S>(X_WS.linear() * r.normal), -1};
}

/// The disc's point nearest to the shape (posed by X_WS) and the shape's nearest point, if the
/// disc (centre, unit axis, radius r) is found apart from it; v0 is where the search starts (a
/// direction from the shape towards the disc); Newton stops early after an iterate with
/// stop(probe) (sphere_newton.h).
template <typename S, typename Stop = bool (*)(const Probe<S>&)>
std::optional<PairHit<S>> discApart(
    const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS, const Vector3<S>& centre,
    const Vector3<S>& axis, S r, const Vector3<S>& v0,
    Stop stop = [](const Probe<S>&) { return false; }) {
  const Vector3<S> start = v0.squaredNorm() > S(0) ? v0 : Vector3<S>::UnitZ();
  const Probe<S> q =
      localMinimum(SupportMap<S>(shape, X_WS), SupportMap<S>::ofCircle(centre, axis, r), start,
                   kSphereNewtonIterations, stop);
  if (!(q.f < S(0)) || !q.v.allFinite() || !q.b.allFinite()) return std::nullopt;
  return PairHit<S>{(q.b - q.a).norm(), q.b, q.a, q.v, -1};
}

/// The pair of points of lineMinimum's answer, the line's at s along the axis from c.
template <typename S>
PairHit<S> lineHit(const CircleProbe<S>& line, const Vector3<S>& c, const Vector3<S>& axis, S s) {
  const Vector3<S> b = c + s * axis;
  return PairHit<S>{(b - line.a).norm(), b, line.a, line.v, -1};
}

/// segmentApart's first case alone: the segment's interior point nearest to the shape, if the
/// segment's line is apart from the shape and its nearest point lies on the segment; nothing
/// otherwise (no point query for the ends).
template <typename S>
std::optional<PairHit<S>> segmentInteriorApart(const Superellipsoid<S>& shape,
                                               const fcl::Transform3<S>& X_WS, const Vector3<S>& p0,
                                               const Vector3<S>& p1, const Vector3<S>& v0) {
  const Vector3<S> e = p1 - p0, c = S(0.5) * (p0 + p1);
  const S length = e.norm();
  if (!(length > S(0))) return std::nullopt;
  const Vector3<S> axis = e / length;
  const CircleProbe<S> line = lineMinimum(SupportMap<S>(shape, X_WS), c, axis, v0);
  if (!(line.g < S(0)) || !line.v.allFinite()) return std::nullopt;
  const S s = (line.a - c).dot(axis);
  if (!(std::abs(s) <= S(0.5) * length)) return std::nullopt;
  return lineHit(line, c, axis, s);
}

/// The segment's point nearest to the shape (posed by X_WS) and the shape's nearest point, if
/// the segment is found apart from it; v0 is where the search starts (a direction from the
/// shape towards the segment).
template <typename S>
std::optional<PairHit<S>> segmentApart(const Superellipsoid<S>& shape,
                                       const fcl::Transform3<S>& X_WS, const Vector3<S>& p0,
                                       const Vector3<S>& p1, const Vector3<S>& v0) {
  const SupportMap<S> A(shape, X_WS);
  const Vector3<S> e = p1 - p0, c = S(0.5) * (p0 + p1);
  const S length = e.norm();
  if (!(length > S(0))) {  // a point
    const std::optional<PairHit<S>> hit = pointApart(shape, X_WS, p0, A.point(v0));
    return hit && hit->distance >= S(0) ? hit : std::nullopt;
  }
  const Vector3<S> axis = e / length;
  // Once G < 0 the line is apart from the shape; where the support point then lies beyond an
  // end, that end is usually the segment's nearest point, and it is if the distance grows from
  // it into the segment (convex along the segment): then the line's minimum is not needed.
  auto beyond_an_end = [&](const CircleProbe<S>& p) {
    return p.g < S(0) && std::abs(p.g1) <= S(kNearMinimum) * p.g2 &&
           std::abs((p.a - c).dot(axis)) > S(0.5) * length;
  };
  CircleProbe<S> line = lineMinimum(A, c, axis, v0, beyond_an_end);
  if (beyond_an_end(line) && line.v.allFinite()) {
    const bool last = (line.a - c).dot(axis) > S(0);
    const std::optional<PairHit<S>> hit = pointApart(shape, X_WS, last ? p1 : p0, line.a);
    if (hit && hit->distance >= S(0) && hit->normal.dot(last ? Vector3<S>(-e) : e) >= S(0)) {
      return hit;
    }
    line = lineMinimum(A, c, axis, line.v);  // the line's minimum after all
  }
  if (line.g < S(0) && line.v.allFinite()) {
    const S s = (line.a - c).dot(axis);
    if (std::abs(s) <= S(0.5) * length) return lineHit(line, c, axis, s);
    const Vector3<S>& end = s > S(0) ? p1 : p0;
    return pointApart(shape, X_WS, end, line.a);
  }
  // The line meets the shape. If the segment does not, its nearest point is the end nearer the
  // shape along the line: the one with the smaller gauge (the gauge is convex along the line and
  // falls towards the part inside). That end is the answer if the distance grows from it into
  // the segment; otherwise the segment meets the shape.
  auto gauge = [&](const Vector3<S>& x) {
    return shape.gauge(Vector3<S>(X_WS.linear().transpose() * (x - X_WS.translation())));
  };
  const bool first = gauge(p0) <= gauge(p1);
  const Vector3<S>& end = first ? p0 : p1;
  const std::optional<PairHit<S>> hit = pointApart(shape, X_WS, end, line.a);
  if (hit && hit->distance >= S(0) && hit->normal.dot(first ? e : Vector3<S>(-e)) >= S(0)) {
    return hit;
  }
  return std::nullopt;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_FEATURE_NEWTON_H
