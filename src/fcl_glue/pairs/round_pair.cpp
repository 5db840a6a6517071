#include "fcl_glue/pairs/round_pair.h"

#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fcl_glue/pairs/candidates.h"
#include "fcl_glue/pairs/segment_search.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

/// A cylinder or a cone in world coordinates: centre t, axis z, radius r, half height h; a cone
/// has its apex at t + h·z and its base at t − h·z.
template <typename S>
struct Round {
  bool cone;
  Vector3<S> t, e1, e2, z;
  S r, h;

  /// The support function h_B(u) (world).
  S support(const Vector3<S>& u) const {
    const S uz = u.dot(z);
    const S radial = r * (u - uz * z).norm();
    if (!cone) return u.dot(t) + radial + h * std::abs(uz);
    return u.dot(t) + std::max(h * uz, radial - h * uz);
  }
  Vector3<S> circle(S theta) const { return std::cos(theta) * e1 + std::sin(theta) * e2; }
  Vector3<S> circleTangent(S theta) const { return -std::sin(theta) * e1 + std::cos(theta) * e2; }
};

template <typename S>
std::optional<Round<S>> roundOf(const fcl::CollisionGeometry<S>* other,
                                const fcl::Transform3<S>& X) {
  Round<S> b;
  if (const auto* c = dynamic_cast<const fcl::Cylinder<S>*>(other)) {
    b = {false,     X.translation(), X.linear().col(0), X.linear().col(1), X.linear().col(2),
         c->radius, c->lz / 2};
  } else if (const auto* c = dynamic_cast<const fcl::Cone<S>*>(other)) {
    b = {true,      X.translation(), X.linear().col(0), X.linear().col(1), X.linear().col(2),
         c->radius, c->lz / 2};
  } else {
    return std::nullopt;
  }
  return b;
}

/// Widens a bracket around x0 until the derivative goes from negative to positive (up to a
/// half turn either side), then finds the stationary point in it.
template <typename S, typename Payload, typename At>
std::optional<Payload> minimumAround(At at, S x0) {
  for (S w = S(0.02); w <= S(3.2); w *= S(2)) {
    const auto lo = at(x0 - w), hi = at(x0 + w);
    if (lo.derivative < S(0) && hi.derivative > S(0)) {
      return stationaryPoint<S>(at, lo, hi).payload;
    }
  }
  return std::nullopt;
}

/// The exact answer for separated shapes, if a candidate among the features within `margin` of
/// libccd's witness is certified.
template <typename S>
std::optional<PairHit<S>> exactSeparated(const Pair<S>& pair, const Round<S>& b,
                                         const PairHit<S>& start, S margin) {
  const S extent = std::hypot(b.r, b.h);
  const Vector3<S> q = start.on_other - b.t;
  const S z0 = q.dot(b.z);
  const Vector3<S> radial0 = q - z0 * b.z;
  const S rho0 = radial0.norm();
  const Vector3<S> toward = rho0 > S(1e-3) * extent ? radial0 : Vector3<S>(-start.normal);
  const S theta0 = std::atan2(toward.dot(b.e2), toward.dot(b.e1));
  auto support = [&b](const Vector3<S>& u) { return b.support(u); };
  Candidates<S, decltype(support)> candidates(pair, support, extent);
  auto pointHit = [&](const Vector3<S>& p) {
    const PointDistanceResult<S> r =
        pointDistance(*pair.shape, *pair.X_WS, p, pair.shape->queryOptions());
    return PairHit<S>{r.distance, p, r.nearest_point, r.normal, -1};
  };
  // The flat ends: the cylinder's two discs, the cone's base.
  for (S side : {S(1), S(-1)}) {
    if (b.cone && side > S(0)) continue;
    if (std::abs(z0 - side * b.h) > margin) continue;
    const Vector3<S> n = side * b.z;
    const Vector3<S> a = shapeSupport(pair, Vector3<S>(-n));
    const S d = n.dot(a) - n.dot(b.t) - b.h;
    const Vector3<S> on = a - d * n;
    const Vector3<S> off_axis = (on - b.t) - (on - b.t).dot(b.z) * b.z;
    if (off_axis.norm() <= b.r && candidates.offer({d, on, a, Vector3<S>(-n), -1}))
      return candidates.certified();
  }
  // The side, over its outward normals m(θ) (the direction to the other shape is v = −m):
  // F(θ) = h_A(−m) + h_B(m), with h_B(m) = m·t + r for the cylinder (m ⊥ z) and m·apex for the
  // cone (m ∝ 2h·c(θ) + r·z), so F' = m'·(t − a) or m'·(apex − a), a = the support point.
  const S lateral_gap =
      b.cone ? std::abs(rho0 - b.r * (b.h - z0) / (2 * b.h)) : std::abs(rho0 - b.r);
  if (lateral_gap <= 2 * margin && std::abs(z0) <= b.h + margin) {
    struct Side {
      Vector3<S> v, a;
    };
    const S length = std::hypot(2 * b.h, b.r);  // the cone's slant, for its normal
    auto normalAt = [&](S theta) {              // the side's outward normal at angle θ
      return b.cone ? Vector3<S>((2 * b.h * b.circle(theta) + b.r * b.z) / length)
                    : b.circle(theta);
    };
    const Vector3<S> apex = b.t + b.h * b.z;
    auto at = [&](S theta) {
      const Vector3<S> m = normalAt(theta);
      const Vector3<S> a = shapeSupport(pair, Vector3<S>(-m));
      const Vector3<S> dm =
          b.cone ? Vector3<S>(2 * b.h * b.circleTangent(theta) / length) : b.circleTangent(theta);
      const S derivative = b.cone ? dm.dot(apex - a) : dm.dot(b.t - a);
      return Sample<S, Side>{theta, derivative, {Vector3<S>(-m), a}};
    };
    if (const std::optional<Side> s = minimumAround<S, Side>(at, theta0)) {
      const S gap = -b.support(Vector3<S>(-s->v)) - s->v.dot(s->a);  // −h_B(−v) − h_A(v)
      const Vector3<S> on = s->a + gap * s->v;
      if (std::abs((on - b.t).dot(b.z)) <= b.h && candidates.offer({gap, on, s->a, s->v, -1}))
        return candidates.certified();
    }
  }
  // The rims: the cylinder's two, the cone's base; the apex.
  for (S side : {S(1), S(-1)}) {
    if (b.cone && side > S(0)) continue;
    if (std::abs(z0 - side * b.h) > margin || std::abs(rho0 - b.r) > margin) continue;
    const Vector3<S> centre = b.t + side * b.h * b.z;
    auto at = [&](S theta) {
      const Vector3<S> p = centre + b.r * b.circle(theta);
      const PairHit<S> hit = pointHit(p);
      return Sample<S, PairHit<S>>{theta, hit.normal.dot(b.r * b.circleTangent(theta)), hit};
    };
    if (const std::optional<PairHit<S>> hit = minimumAround<S, PairHit<S>>(at, theta0)) {
      if (candidates.offer(*hit)) return candidates.certified();
    }
  }
  if (b.cone && (start.on_other - (b.t + b.h * b.z)).norm() <= margin) {
    if (candidates.offer(pointHit(Vector3<S>(b.t + b.h * b.z)))) return candidates.certified();
  }
  return candidates.certified();
}

}  // namespace

template <typename S>
std::optional<PairHit<S>> roundHit(const Pair<S>& pair) {
  const std::optional<Round<S>> b = roundOf(pair.other, *pair.X_WO);
  if (!b) return std::nullopt;
  return exactWhereSeparated(pair, std::hypot(b->r, b->h), [&](const PairHit<S>& start) {
    // The features near libccd's witness; failing that (its witness can be off by more than the
    // margin, far away), every feature.
    const S extent = std::hypot(b->r, b->h);
    if (auto hit = exactSeparated(pair, *b, start, S(1e-3) * extent)) return hit;
    return exactSeparated(pair, *b, start, std::numeric_limits<S>::infinity());
  });
}

#define FSE_INSTANTIATE_ROUND_HIT(S) template std::optional<PairHit<S>> roundHit(const Pair<S>&);
FSE_INSTANTIATE_ROUND_HIT(float)
FSE_INSTANTIATE_ROUND_HIT(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
