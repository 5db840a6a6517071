#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_GJK_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_GJK_H

// Internal: the start of the exact pairs with flat or round features (feature_pair.h) where the
// shapes are apart — GJK (Gilbert, Johnson, Keerthi) on the difference C = A − B of two convex
// sets given by their support points, without libccd's callbacks and object set-up.
//
// The iterate v is the point of a simplex (up to 4 points of C) nearest the origin. Each step
// adds C's support point w along −v and keeps the smallest face of the new simplex that holds
// the new nearest point. ‖v‖ bounds the distance from above, v·w/‖v‖ from below; the search
// stops once the two are within `relative_gap` of each other, or once rounding stops its
// progress (w already in the simplex, or v no nearer: the bounds are then as close as the
// floating-point points allow, which can be farther apart). It gives up (no answer) where the
// origin is inside the simplex or within rounding of C (touching or overlapping: the caller's
// overlap path decides) or after `max_iterations`.
//
// The answer only has to pick out the features near the contact: the caller certifies its own
// exact answer by the duality gap (feature_pair.h says what it does where that fails).

#include <cmath>
#include <initializer_list>
#include <limits>
#include <optional>

#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
struct GjkSeparation {
  S distance;             // ‖v‖ = ‖on_a − on_b‖, an upper bound of the distance
  S lower;                // a lower bound: v·w/‖v‖ for the last support point w (≥ 0)
  Vector3<S> on_a, on_b;  // the witnesses, points of A and B
};

namespace gjk {

/// The simplex: points w_i = a_i − b_i of C with their witnesses.
template <typename S>
struct Simplex {
  Vector3<S> w[4], a[4], b[4];
  int size = 0;

  /// Σ weights_i·points_i over the kept points (w, a or b).
  Vector3<S> combination(const Vector3<S> (&points)[4], const S weights[4]) const {
    Vector3<S> out = Vector3<S>::Zero();
    for (int i = 0; i < size; ++i) out += weights[i] * points[i];
    return out;
  }
};

/// The nearest point to the origin of a sub-simplex's hull: the points it keeps (indices into
/// the simplex, ascending) and their barycentric weights. The sub-algorithms below read only
/// the points w and return one of these; the simplex is reduced once, at the end.
template <typename S>
struct Reduced {
  int index[4];
  S lambda[4];
  int size;

  Vector3<S> point(const Vector3<S>* w) const {
    Vector3<S> out = Vector3<S>::Zero();
    for (int k = 0; k < size; ++k) out += lambda[k] * w[index[k]];
    return out;
  }
};

template <typename S>
Reduced<S> vertexOf(int i) {
  return {{i}, {S(1)}, 1};
}

/// Segment [i, j] (Ericson, Real-Time Collision Detection, 5.1.2, with the point at the origin).
template <typename S>
Reduced<S> nearestOnSegment(const Vector3<S>* w, int i, int j) {
  const Vector3<S> p = w[i], e = w[j] - w[i];
  const S t = -p.dot(e), ee = e.squaredNorm();
  if (!(t > S(0)) || !(ee > S(0))) return vertexOf<S>(i);
  if (t >= ee) return vertexOf<S>(j);
  return {{i, j}, {S(1) - t / ee, t / ee}, 2};
}

/// Of several sub-simplices, the one whose nearest point is nearest the origin.
template <typename S>
class NearestOfSeveral {
 public:
  void offer(const Vector3<S>* w, const Reduced<S>& r) {
    const S d = r.point(w).squaredNorm();
    if (!(d < best_distance_)) return;
    best_distance_ = d;
    best_ = r;
  }
  bool any() const { return best_distance_ < std::numeric_limits<S>::infinity(); }
  const Reduced<S>& best() const { return best_; }

 private:
  Reduced<S> best_{};
  S best_distance_ = std::numeric_limits<S>::infinity();
};

/// Triangle [i, j, k] (Ericson 5.1.5, with the point at the origin).
template <typename S>
Reduced<S> nearestOnTriangle(const Vector3<S>* w, int i, int j, int k) {
  auto edge = [&](int x, int y, S t) {  // (1 − t)·w_x + t·w_y
    return Reduced<S>{{x, y}, {S(1) - t, t}, 2};
  };
  const Vector3<S> a = w[i], b = w[j], c = w[k];
  const Vector3<S> ab = b - a, ac = c - a;
  const S d1 = -ab.dot(a), d2 = -ac.dot(a);
  if (d1 <= S(0) && d2 <= S(0)) return vertexOf<S>(i);
  const S d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= S(0) && d4 <= d3) return vertexOf<S>(j);
  const S vc = d1 * d4 - d3 * d2;
  if (vc <= S(0) && d1 >= S(0) && d3 <= S(0)) return edge(i, j, d1 / (d1 - d3));
  const S d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= S(0) && d5 <= d6) return vertexOf<S>(k);
  const S vb = d5 * d2 - d1 * d6;
  if (vb <= S(0) && d2 >= S(0) && d6 <= S(0)) return edge(i, k, d2 / (d2 - d6));
  const S va = d3 * d6 - d5 * d4;
  if (va <= S(0) && (d4 - d3) >= S(0) && (d5 - d6) >= S(0)) {
    return edge(j, k, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const S denominator = va + vb + vc;
  if (!(std::abs(denominator) > S(0))) {  // degenerate: the best of its edges
    NearestOfSeveral<S> best;
    best.offer(w, nearestOnSegment(w, i, j));
    best.offer(w, nearestOnSegment(w, i, k));
    best.offer(w, nearestOnSegment(w, j, k));
    if (!best.any()) return vertexOf<S>(i);  // not a number anywhere: the search gives up later
    return best.best();
  }
  const S l1 = vb / denominator, l2 = vc / denominator;
  return {{i, j, k}, {S(1) - l1 - l2, l1, l2}, 3};
}

/// The nearest point to the origin of the hull of the first n points w; nothing if the origin
/// is inside a tetrahedron (C's hull reaches it).
template <typename S>
std::optional<Reduced<S>> nearest(const Vector3<S>* w, int n) {
  switch (n) {
    case 1:
      return vertexOf<S>(0);
    case 2:
      return nearestOnSegment(w, 0, 1);
    case 3:
      return nearestOnTriangle(w, 0, 1, 2);
    default:
      break;
  }
  // Tetrahedron (Ericson 5.1.6): the nearest point of each face the origin lies outside of.
  static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
  NearestOfSeveral<S> best;
  for (const auto& f : kFaces) {
    const Vector3<S> normal = (w[f[1]] - w[f[0]]).cross(w[f[2]] - w[f[0]]);
    const S origin_side = -w[f[0]].dot(normal), opposite_side = (w[f[3]] - w[f[0]]).dot(normal);
    // Outside this face: the origin and the fourth point on opposite sides of its plane (a flat
    // tetrahedron counts every face).
    if (!(origin_side * opposite_side < S(0)) && opposite_side != S(0)) continue;
    best.offer(w, nearestOnTriangle(w, f[0], f[1], f[2]));
  }
  if (!best.any()) return std::nullopt;
  return best.best();
}

/// The simplex reduced to r's points, in r's (ascending) order, with r's weights in `lambda`.
template <typename S>
void reduce(Simplex<S>* s, const Reduced<S>& r, S lambda[4]) {
  for (int k = 0; k < r.size; ++k) {  // index[k] ≥ k: nothing is overwritten before it is read
    s->w[k] = s->w[r.index[k]];
    s->a[k] = s->a[r.index[k]];
    s->b[k] = s->b[r.index[k]];
    lambda[k] = r.lambda[k];
  }
  for (int k = r.size; k < 4; ++k) lambda[k] = S(0);
  s->size = r.size;
}

}  // namespace gjk

/// The separation of convex A and B from their support points `support_a(u)`, `support_b(u)`
/// (the point of each set farthest along u, world), starting along `first` (any direction from
/// A towards B); nothing where they touch, overlap, or the search does not settle.
template <typename S, typename SupportA, typename SupportB>
std::optional<GjkSeparation<S>> gjkSeparation(const SupportA& support_a, const SupportB& support_b,
                                              Vector3<S> first, S relative_gap,
                                              int max_iterations) {
  if (!(first.norm() > S(0)) || !first.allFinite()) first = Vector3<S>::UnitX();
  gjk::Simplex<S> s;
  // The first point of C along −first (v points from B to A in C = A − B).
  s.a[0] = support_a(first);
  s.b[0] = support_b(Vector3<S>(-first));
  s.w[0] = s.a[0] - s.b[0];
  s.size = 1;
  S lambda[4] = {S(1), S(0), S(0), S(0)};
  Vector3<S> v = s.w[0];
  const S rounding = S(64) * std::numeric_limits<S>::epsilon();
  S lower = S(0);
  auto answer = [&] {
    return std::optional<GjkSeparation<S>>(
        GjkSeparation<S>{v.norm(), lower, s.combination(s.a, lambda), s.combination(s.b, lambda)});
  };
  for (int it = 0; it < max_iterations; ++it) {
    const S vv = v.squaredNorm();
    if (!std::isfinite(vv)) return std::nullopt;
    const Vector3<S> a = support_a(Vector3<S>(-v)), b = support_b(v);
    const Vector3<S> w = a - b;
    // The support plane along −v bounds the distance from below by v·w/‖v‖ (by 0 while that is
    // negative: then the search goes on, as it does until the bounds meet).
    const S vw = v.dot(w);
    const S scale = std::max(a.norm(), b.norm());
    if (vv <= rounding * rounding * scale * scale) return std::nullopt;  // touching
    lower = std::max(lower, vw / std::sqrt(vv));
    // Done when the bounds meet, or when w is already in the simplex: v cannot get nearer
    // (rounding has the last word; the gap is then a few ulps).
    bool done = vv - vw <= relative_gap * vv;
    for (int i = 0; i < s.size && !done; ++i) done = s.w[i] == w;
    if (done) return answer();
    // The grown simplex: w in the slot after the kept points (the answer above still reads
    // only the kept ones).
    s.w[s.size] = w;
    s.a[s.size] = a;
    s.b[s.size] = b;
    const std::optional<gjk::Reduced<S>> r = gjk::nearest(s.w, s.size + 1);
    if (!r) return std::nullopt;  // the origin is inside
    const Vector3<S> next = r->point(s.w);
    if (!(next.squaredNorm() < vv)) return answer();  // no progress: as above
    gjk::reduce(&s, *r, lambda);
    v = next;
  }
  return std::nullopt;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_GJK_H
