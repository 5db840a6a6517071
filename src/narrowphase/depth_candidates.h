#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_DEPTH_CANDIDATES_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_DEPTH_CANDIDATES_H

// Internal: the penetration depth of the superellipsoid and a shape with flat faces, edges or
// rims (polytope_pair, round_pair, the capsule's deep overlaps), as the least value of
//   F(v) = h_A(v) + h_B(−v)
// over candidate directions v (docs/math.md → "Shape pairs"). Every F(v) is a translation along
// v that separates the shapes, so the least one found is never shallower than the true depth; it
// is the depth when the candidates include the minimiser. They come from the other shape's
// features, where F is smooth: a face's normal; a vertex's (or a rim point's) escape direction,
// the outward normal at its nearest point on the superellipsoid (the point solver), and the
// Newton descents of a vertex, a rim or an apex inside its own region (offerDescent); an edge's
// arc or a side's one-parameter family of directions, sampled and refined where the restricted F
// is stationary (segment_search.h); and MPR's normal. A polytope's, a cylinder's and a cone's
// candidates include every feature's own minimum, and their best is the answer (best()); a
// capsule's (and every shape's in float) are polished by a pattern search on the sphere
// (refinedBest()), where F's kinks (the other shape's supporting feature changes) leave the
// minimiser between the families.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "fcl_superellipsoid/batch_distance.h"
#include "narrowphase/feature_pair.h"
#include "narrowphase/rolling_certificate.h"
#include "narrowphase/segment_search.h"
#include "narrowphase/sphere_newton.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S, typename OtherSupport>
class DepthCandidates {
 public:
  /// A point of the other shape seen from the superellipsoid (offerPoints).
  struct Escape {
    S distance;            // signed, to the superellipsoid (negative: inside)
    Vector3<S> direction;  // the escape direction: the outward normal at the nearest point
    S f;                   // F there (infinite if it is not finite)
  };

  DepthCandidates(const ShapePair<S>& pair, OtherSupport other_support)
      : pair_(pair), other_support_(other_support) {}

  /// F at the direction v (from the shape towards the other; any length).
  S offerDirection(const Vector3<S>& direction) {
    if (!direction.allFinite() || !(direction.norm() > S(0))) return kNone;
    const Vector3<S> v = direction.normalized();
    return offerWithSupport(v, shapeSupport(pair_, v));
  }

  /// Points of the other shape (vertices, the apex, rim points, a capsule's ends): each one's
  /// escape direction, the outward normal at its nearest point on the superellipsoid, through
  /// the batched queries (SIMD lanes, the calling thread only). Returns, in order, each point's
  /// signed distance to the superellipsoid (negative: inside), its escape direction and F there.
  std::vector<Escape> offerPoints(const std::vector<Vector3<S>>& points) {
    Matrix3X<S> p_W(3, Eigen::Index(points.size()));
    for (std::size_t i = 0; i < points.size(); ++i) p_W.col(Eigen::Index(i)) = points[i];
    BatchOptions<S> options;
    options.distance = pair_.shape->queryOptions();
    options.threads = 1;
    BatchDistanceResult<S> r;
    batchDistance(*pair_.shape, *pair_.X_WS, p_W, r, options);
    std::vector<Escape> escapes(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Vector3<S> v = r.normal.col(Eigen::Index(i));
      escapes[i] = {r.distance[Eigen::Index(i)], v, offerDirection(v)};
    }
    return escapes;
  }

  /// A smooth piece P of the other shape (a vertex or the apex as a point, a rim as a circle:
  /// support_map.h), from a start direction: Newton's method on the sphere for
  /// f_P(v) = h_A(v) + h_P(−v) (sphere_newton.h), then its end offered. Where P supports the
  /// other shape along −v, F is f_P. offerPoints gives a point's f_P minimum over the whole
  /// sphere; where P supports the other shape only in a region elsewhere, f_P may have a second
  /// local minimum inside that region, which is F's there. Returns the end (f NaN for a start
  /// that is not a direction).
  template <typename Stop = bool (*)(const Probe<S>&)>
  Probe<S> offerDescent(
      const SupportMap<S>& piece, const Vector3<S>& start,
      int max_iterations = kSphereNewtonIterations,
      Stop stop = [](const Probe<S>&) { return false; }) {
    if (!start.allFinite() || !(start.norm() > S(0))) {
      return {std::numeric_limits<S>::quiet_NaN(), start, start, start,
              Eigen::Matrix<S, 3, 3>::Zero()};
    }
    const Probe<S> end =
        localMinimum(SupportMap<S>(*pair_.shape, *pair_.X_WS), piece, start, max_iterations, stop);
    offerDirection(end.v);
    return end;
  }

  /// A point w of the other shape inside the superellipsoid, seen from it as `escape`
  /// (offerPoints). Where w does not support the other shape along its own escape direction (F
  /// there is above h_A(v) − v·w), f_w(v) = h_A(v) − v·w has other local minima, and one in w's
  /// region (where w supports the other shape along −v: `supports(v)`) can be F's:
  ///  - near a mirror plane of the superellipsoid they mirror the escape direction across it
  ///    (without them a rounded shape's overlap with a triangle came out too deep);
  ///  - where the superellipsoid is box-like, f_w has a local minimum near each of its axis
  ///    directions (the depth below each flat face), and one in w's region can be F's minimum
  ///    while the escape direction lies below another face, outside it (a rounded shape's
  ///    overlap with a triangle, and a box-like one's with a capsule about its centre, came
  ///    out too deep).
  /// So f_w descends from the three mirror images and from each axis direction in w's region.
  /// `stop()` is asked after each descent (a certificate): true ends them. Returns whether it
  /// did.
  template <typename Supports, typename Stop>
  bool offerInsidePointDescents(const Vector3<S>& w, const Escape& escape, S tolerance,
                                Supports supports, Stop stop) {
    if (!(escape.distance < S(0)) || !(escape.f > -escape.distance + tolerance)) return false;
    const SupportMap<S> point = SupportMap<S>::ofPoint(w);
    const Eigen::Matrix<S, 3, 3> R = pair_.X_WS->linear();
    for (int k = 0; k < 3; ++k) {
      Vector3<S> local = R.transpose() * escape.direction;
      local[k] = -local[k];
      offerDescent(point, Vector3<S>(R * local));
      if (stop()) return true;
    }
    for (int k = 0; k < 6; ++k) {
      const Vector3<S> axis = R.col(k % 3) * (k < 3 ? S(1) : S(-1));
      if (!supports(axis)) continue;
      offerDescent(point, axis);
      if (stop()) return true;
    }
    return false;
  }

  /// A one-parameter family of directions v(θ) (unit), θ over [from, to], with derivative(θ, v, a)
  /// the derivative of the function to minimise over it, given the superellipsoid's support
  /// point a at v: samples at most `spacing` apart, each offered, then the stationary point in
  /// every interval where the derivative goes from negative to positive (its iterates offered
  /// too). Every local minimum, not only the lowest sample's: on an edge's circle the function is
  /// F only where the edge supports the other shape, and its local minimum there can be F's
  /// minimum while the circle's lowest point lies outside (the tests found one 35° away, with a
  /// maximum between them). A closed family (the whole circle: to = from + 2π) wraps around.
  template <typename Direction, typename Derivative>
  void offerFamily(Direction direction, Derivative derivative, S from, S to, bool closed,
                   S spacing = S(kCircleSpacing)) {
    if (!(to > from)) return;
    const int intervals = std::max(closed ? 3 : 1, int(std::ceil((to - from) / spacing)));
    const S step = (to - from) / S(intervals);
    auto at = [&](S theta) {
      const Vector3<S> v = direction(theta);
      const Vector3<S> a = shapeSupport(pair_, v);
      // Unit up to rounding; a degenerate edge's basis (not finite, or zero) is not offered.
      if (std::abs(v.norm() - S(1)) <= S(1e-3)) offerWithSupport(v, a);
      return Sample<S, S>{theta, derivative(theta, v, a), theta};
    };
    const Sample<S, S> first = at(from);
    Sample<S, S> previous = first;
    for (int k = 1; k <= intervals; ++k) {
      const Sample<S, S> next = closed && k == intervals
                                    ? Sample<S, S>{to, first.derivative, to}
                                    : at(k == intervals ? to : from + S(k) * step);
      if (previous.derivative < S(0) && next.derivative > S(0)) {
        stationaryPoint<S>(at, previous, next);  // its iterates are offered by `at`
      }
      previous = next;
    }
  }

  /// An edge w0–w1 of the other shape whose outward normal cone, perpendicular to the edge, is
  /// the arc u(θ) = cos θ·c1 + sin θ·c2, θ ∈ [0, angle] (c1, c2 orthonormal, ⊥ the edge): there
  /// the edge supports the other shape along u = −v, so F(v) = h_A(v) − v·w0, with derivative
  /// v'·(a − w0). Outside the arc F exceeds that function, so F's minima along the edge lie on
  /// the arc or at its ends (the faces' normals, offered with them).
  void offerEdgeArc(const Vector3<S>& w0, const Vector3<S>& c1, const Vector3<S>& c2, S angle) {
    auto direction = [&](S t) { return Vector3<S>(-std::cos(t) * c1 - std::sin(t) * c2); };
    auto derivative = [&](S t, const Vector3<S>&, const Vector3<S>& a) {
      return Vector3<S>(std::sin(t) * c1 - std::cos(t) * c2).dot(a - w0);
    };
    offerFamily(direction, derivative, S(0), angle, false, S(kArcSpacing));
  }

  /// An edge w0–w1 whose normal cone is not known (a capsule's axis: every direction ⊥ it): the
  /// whole circle of directions v ⊥ the edge, over which the edge's support is v·w0, so the
  /// function is h_A(v) − v·w0 with derivative v'·(a − w0).
  void offerEdge(const Vector3<S>& w0, const Vector3<S>& w1) {
    const Vector3<S> e = w1 - w0;
    if (!(e.norm() > S(0))) return;
    const Vector3<S> c1 = e.unitOrthogonal(), c2 = e.stableNormalized().cross(c1);
    auto direction = [&](S t) { return Vector3<S>(std::cos(t) * c1 + std::sin(t) * c2); };
    auto derivative = [&](S t, const Vector3<S>&, const Vector3<S>& a) {
      return Vector3<S>(-std::sin(t) * c1 + std::cos(t) * c2).dot(a - w0);
    };
    offerFamily(direction, derivative, S(0), S(2 * M_PI), true);
  }

  /// F's minimum near the best direction so far: a pattern search on the sphere (16 directions,
  /// the step quartered from 0.1 rad to 1e-9 rad), which needs no derivative, since F has kinks
  /// where the other shape's supporting feature changes. Then the best: distance −F, the shape's
  /// support point, the other's witness moved back by the depth along v (so that
  /// on_shape − on_other = depth·v).
  PairHit<S> refinedBest() {
    // The best candidate is usually a minimiser already, and every level ends with all 16 polls
    // failing: so the step is quartered, not halved, which finds the same depths with fewer
    // polls (docs/math.md).
    constexpr int kPolls = 16, kMovesPerStep = 64;
    for (S step = S(0.1); has_best_ && step > S(1e-9); step *= S(0.25)) {
      for (int moves = 0; moves < kMovesPerStep; ++moves) {
        const Vector3<S> v = v_, t1 = v.unitOrthogonal(), t2 = v.cross(t1);
        const S f = f_;
        for (int k = 0; k < kPolls && !(f_ < f); ++k) {
          const S angle = S(2 * M_PI) * S(k) / S(kPolls);
          offerDirection(Vector3<S>(v + step * (std::cos(angle) * t1 + std::sin(angle) * t2)));
        }
        if (!(f_ < f)) break;
      }
    }
    return best();
  }
  /// The best candidate as it is, without the pattern search: where the candidates include
  /// every feature's own minimum (a polytope's faces, edge arcs and vertices; docs/math.md).
  PairHit<S> best() const { return {-f_, Vector3<S>(a_ - f_ * v_), a_, v_, -1}; }
  bool found() const { return has_best_; }
  /// Whether the best candidate is the depth (rolling_certificate.h: twoBallsCertified): by a
  /// ball inside the other shape tangent at its witness b = a − F·v and one inside the
  /// superellipsoid tangent at a, of radii summing to F. `outside(x)` says how far a point x lies
  /// beyond the other shape's bounding planes or surfaces, and, inside it, minus its distance to
  /// the boundary; the two balls' shortfalls are to be within `tolerance` together. Tried once
  /// per best candidate.
  template <typename Outside>
  bool certified(const Outside& outside, S tolerance) {
    if (!has_best_ || ball_tried_) return false;
    ball_tried_ = true;
    return twoBallsCertified(*pair_.shape, *pair_.X_WS, v_, a_, f_, outside,
                             rollingRadius(*pair_.shape), tolerance);
  }

 private:
  /// F at the unit direction v, given the superellipsoid's support point a there.
  S offerWithSupport(const Vector3<S>& v, const Vector3<S>& a) {
    const S f = v.dot(a) + other_support_(Vector3<S>(-v));
    if (!std::isfinite(f)) return kNone;
    if (!has_best_ || f < f_) {
      ball_tried_ = false;
      f_ = f;
      v_ = v;
      a_ = a;
      has_best_ = true;
    }
    return f;
  }

  static constexpr S kNone = std::numeric_limits<S>::infinity();
  // The families' sample spacing: 30° around a whole circle (12 samples); 0.15 rad on an edge's
  // arc (a box's 90° arc: 11 intervals), where samples 0.4 rad apart missed one of the two
  // minima EdgeCirclesWithSeveralLocalMinima replays and 0.3 rad found both.
  static constexpr double kCircleSpacing = 2 * M_PI / 12;
  static constexpr double kArcSpacing = 0.15;
  const ShapePair<S>& pair_;
  OtherSupport other_support_;
  S f_ = S(0);
  Vector3<S> v_ = Vector3<S>::UnitZ(), a_ = Vector3<S>::Zero();
  bool has_best_ = false;
  bool ball_tried_ = false;  // the balls were tried on the best so far (certified)
};

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_DEPTH_CANDIDATES_H
