#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_GJK_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_GJK_H

// Internal: the start of the exact pairs with flat or round features (candidates.h) where the
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
// exact answer by the duality gap (candidates.h says what it does where that fails).

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

  /// Keeps the points at `indices` (ascending), in that order.
  void keep(std::initializer_list<int> indices) {
    int k = 0;
    for (int i : indices) {  // i ≥ k: nothing is overwritten before it is read
      w[k] = w[i];
      a[k] = a[i];
      b[k] = b[i];
      ++k;
    }
    size = k;
  }

  /// Σ weights_i·points_i over the kept points (w, a or b).
  Vector3<S> combination(const Vector3<S> (&points)[4], const S weights[4]) const {
    Vector3<S> out = Vector3<S>::Zero();
    for (int i = 0; i < size; ++i) out += weights[i] * points[i];
    return out;
  }
};

/// Of several sub-simplices with their nearest points (weights over each), the one nearest the
/// origin.
template <typename S>
class NearestOfSeveral {
 public:
  void offer(const Simplex<S>& sub, const S weights[4]) {
    const Vector3<S> v = sub.combination(sub.w, weights);
    if (!(v.squaredNorm() < best_distance_)) return;
    best_distance_ = v.squaredNorm();
    best_ = sub;
    for (int i = 0; i < 4; ++i) best_weights_[i] = weights[i];
  }
  bool any() const { return best_distance_ < std::numeric_limits<S>::infinity(); }
  void into(Simplex<S>* s, S lambda[4]) const {
    *s = best_;
    for (int i = 0; i < 4; ++i) lambda[i] = best_weights_[i];
  }

 private:
  Simplex<S> best_;
  S best_weights_[4] = {};
  S best_distance_ = std::numeric_limits<S>::infinity();
};

/// The nearest point to the origin of the simplex's hull, as barycentric weights `lambda` over
/// the kept points; the simplex is reduced to the points with positive weight. False if the
/// origin is inside a tetrahedron (C's hull reaches it).
template <typename S>
bool nearest(Simplex<S>* s, S lambda[4]);

/// Segment [0, 1] (Ericson, Real-Time Collision Detection, 5.1.2, with the point at the origin).
template <typename S>
void nearestOnSegment(Simplex<S>* s, S lambda[4]) {
  const Vector3<S> p = s->w[0], e = s->w[1] - s->w[0];
  const S t = -p.dot(e), ee = e.squaredNorm();
  if (!(t > S(0)) || !(ee > S(0))) {
    s->keep({0});
    lambda[0] = S(1);
  } else if (t >= ee) {
    s->keep({1});
    lambda[0] = S(1);
  } else {
    lambda[0] = S(1) - t / ee;
    lambda[1] = t / ee;
  }
}

/// Triangle [0, 1, 2] (Ericson 5.1.5, with the point at the origin).
template <typename S>
void nearestOnTriangle(Simplex<S>* s, S lambda[4]) {
  auto vertex = [&](int i) {
    s->keep({i});
    lambda[0] = S(1);
  };
  auto edge = [&](int i, int j, S t) {  // (1 − t)·w_i + t·w_j
    s->keep({i, j});
    lambda[0] = S(1) - t;
    lambda[1] = t;
  };
  const Vector3<S> a = s->w[0], b = s->w[1], c = s->w[2];
  const Vector3<S> ab = b - a, ac = c - a;
  const S d1 = -ab.dot(a), d2 = -ac.dot(a);
  if (d1 <= S(0) && d2 <= S(0)) return vertex(0);
  const S d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= S(0) && d4 <= d3) return vertex(1);
  const S vc = d1 * d4 - d3 * d2;
  if (vc <= S(0) && d1 >= S(0) && d3 <= S(0)) return edge(0, 1, d1 / (d1 - d3));
  const S d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= S(0) && d5 <= d6) return vertex(2);
  const S vb = d5 * d2 - d1 * d6;
  if (vb <= S(0) && d2 >= S(0) && d6 <= S(0)) return edge(0, 2, d2 / (d2 - d6));
  const S va = d3 * d6 - d5 * d4;
  if (va <= S(0) && (d4 - d3) >= S(0) && (d5 - d6) >= S(0)) {
    return edge(1, 2, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const S denominator = va + vb + vc;
  if (!(std::abs(denominator) > S(0))) {  // degenerate: the best of its edges
    NearestOfSeveral<S> best;
    for (auto edge : {std::initializer_list<int>{0, 1}, {0, 2}, {1, 2}}) {
      Simplex<S> e = *s;
      e.keep(edge);
      S l[4] = {};
      nearestOnSegment(&e, l);
      best.offer(e, l);
    }
    if (!best.any()) return vertex(0);  // not a number anywhere: the search gives up later
    return best.into(s, lambda);
  }
  lambda[1] = vb / denominator;
  lambda[2] = vc / denominator;
  lambda[0] = S(1) - lambda[1] - lambda[2];
}

template <typename S>
bool nearest(Simplex<S>* s, S lambda[4]) {
  switch (s->size) {
    case 1:
      lambda[0] = S(1);
      return true;
    case 2:
      nearestOnSegment(s, lambda);
      return true;
    case 3:
      nearestOnTriangle(s, lambda);
      return true;
    default:
      break;
  }
  // Tetrahedron (Ericson 5.1.6): the nearest point of each face the origin lies outside of.
  static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
  NearestOfSeveral<S> best;
  for (const auto& f : kFaces) {
    const Vector3<S> n = (s->w[f[1]] - s->w[f[0]]).cross(s->w[f[2]] - s->w[f[0]]);
    const S origin_side = -s->w[f[0]].dot(n), opposite_side = (s->w[f[3]] - s->w[f[0]]).dot(n);
    // Outside this face: the origin and the fourth point on opposite sides of its plane (a flat
    // tetrahedron counts every face).
    if (!(origin_side * opposite_side < S(0)) && opposite_side != S(0)) continue;
    Simplex<S> face = *s;
    face.keep({f[0], f[1], f[2]});
    S l[4] = {};
    nearestOnTriangle(&face, l);
    best.offer(face, l);
  }
  if (!best.any()) return false;
  best.into(s, lambda);
  return true;
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
    gjk::Simplex<S> grown = s;
    grown.w[grown.size] = w;
    grown.a[grown.size] = a;
    grown.b[grown.size] = b;
    ++grown.size;
    S grown_lambda[4] = {};
    if (!gjk::nearest(&grown, grown_lambda)) return std::nullopt;  // the origin is inside
    const Vector3<S> next = grown.combination(grown.w, grown_lambda);
    if (!(next.squaredNorm() < vv)) return answer();  // no progress: as above
    s = grown;
    for (int i = 0; i < 4; ++i) lambda[i] = grown_lambda[i];
    v = next;
  }
  return std::nullopt;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_GJK_H
