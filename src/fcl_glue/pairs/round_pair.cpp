#include "fcl_glue/pairs/round_pair.h"

#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "fcl_glue/pairs/candidates.h"
#include "fcl_glue/pairs/depth_candidates.h"
#include "fcl_glue/pairs/feature_newton.h"
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
  /// Whether the cone's apex supports it along u (its base rim otherwise; false for a cylinder).
  bool apexSupports(const Vector3<S>& u) const {
    const S uz = u.dot(z);
    return cone && h * uz >= r * (u - uz * z).norm() - h * uz;
  }
  /// A point where h_B(u) is reached: on the rim (or the apex) toward u's radial part; the
  /// centre of the disc where u is along the axis.
  Vector3<S> supportPoint(const Vector3<S>& u) const {
    const S uz = u.dot(z);
    const Vector3<S> radial = u - uz * z;
    const S length = radial.norm();
    const Vector3<S> out = length > S(0) ? Vector3<S>(r * radial / length) : Vector3<S>::Zero();
    if (!cone) return t + (uz >= S(0) ? h : -h) * z + out;
    if (apexSupports(u)) return t + h * z;
    return t - h * z + out;
  }
  Vector3<S> circle(S theta) const { return std::cos(theta) * e1 + std::sin(theta) * e2; }
  Vector3<S> circleTangent(S theta) const { return -std::sin(theta) * e1 + std::cos(theta) * e2; }
  /// The side's outward unit normal m(θ) (the cone's ∝ 2h·c(θ) + r·z) and its derivative.
  Vector3<S> sideNormal(S theta) const {
    const S slant = std::hypot(2 * h, r);  // 0 for a cone of no size: its side is a point
    return cone && slant > S(0) ? Vector3<S>((2 * h * circle(theta) + r * z) / slant)
                                : circle(theta);
  }
  Vector3<S> sideNormalDerivative(S theta) const {
    const S slant = std::hypot(2 * h, r);
    return cone && slant > S(0) ? Vector3<S>(2 * h * circleTangent(theta) / slant)
                                : circleTangent(theta);
  }
  /// Along a side normal m the support is m·anchor (+ r for the cylinder): the apex, the centre.
  Vector3<S> sideAnchor() const { return cone ? Vector3<S>(t + h * z) : t; }
  /// How far x lies beyond the discs' planes and the side (≤ 0 inside): the cone's side is the
  /// surface where the radius is r·(h − height)/(2h), its distance taken along the side's normal.
  S outside(const Vector3<S>& x) const {
    const S height = (x - t).dot(z);
    const S radial = (x - t - height * z).norm();
    if (!cone) return std::max(std::abs(height) - h, radial - r);
    const S slant = std::hypot(2 * h, r);
    const S side = slant > S(0) ? (2 * h * radial - r * (h - height)) / slant : radial;
    return std::max(-h - height, side);
  }
};

template <typename S>
std::optional<Round<S>> roundOf(const Pair<S>& pair) {
  const fcl::Transform3<S>& X = *pair.X_WO;
  Round<S> b;
  if (const auto* c = otherAs<fcl::Cylinder<S>>(pair, fcl::GEOM_CYLINDER)) {
    b = {false,     X.translation(), X.linear().col(0), X.linear().col(1), X.linear().col(2),
         c->radius, c->lz / 2};
  } else if (const auto* c = otherAs<fcl::Cone<S>>(pair, fcl::GEOM_CONE)) {
    b = {true,      X.translation(), X.linear().col(0), X.linear().col(1), X.linear().col(2),
         c->radius, c->lz / 2};
  } else {
    return std::nullopt;
  }
  return b;
}

/// Widens a bracket around x0 until the derivative goes from negative to positive (each end
/// doubling its distance from x0, up to a half turn), then finds the stationary point in it. An
/// end that is on the wrong side becomes the other end (the minimum lies beyond it).
template <typename S, typename Payload, typename At>
std::optional<Payload> minimumAround(At at, S x0) {
  constexpr S kFirst = S(0.02), kLast = S(3.2);
  S w_lo = kFirst, w_hi = kFirst;
  auto lo = at(x0 - w_lo), hi = at(x0 + w_hi);
  while (!(lo.derivative < S(0) && hi.derivative > S(0))) {
    if (!(lo.derivative < S(0))) {
      if (lo.derivative > S(0)) hi = lo;
      if ((w_lo *= S(2)) > kLast) return std::nullopt;
      lo = at(x0 - w_lo);
    } else {
      if (hi.derivative < S(0)) lo = hi;
      if ((w_hi *= S(2)) > kLast) return std::nullopt;
      hi = at(x0 + w_hi);
    }
  }
  return stationaryPoint<S>(at, lo, hi).payload;
}

/// The exact answer for separated shapes, if a candidate among the features within `margin` of
/// the start's witness (GJK's or libccd's: candidates.h) is certified.
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
  WarmPointQueries<S> query(*pair.shape, *pair.X_WS);  // the rims' samples are close together
  auto pointHit = [&](const Vector3<S>& p) {
    const PointDistanceResult<S> r = query(p);
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
    auto at = [&](S theta) {
      const Vector3<S> m = b.sideNormal(theta);
      const Vector3<S> a = shapeSupport(pair, Vector3<S>(-m));
      const S derivative = b.sideNormalDerivative(theta).dot(b.sideAnchor() - a);
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
    // Newton on the rim's disc (feature_newton.h), else point queries along the rim.
    const std::optional<PairHit<S>> disc =
        discApart(*pair.shape, *pair.X_WS, centre, b.z, b.r, start.normal);
    if (disc && candidates.offer(*disc)) return candidates.certified();
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
    const std::optional<PairHit<S>> hit =
        pointApart(*pair.shape, *pair.X_WS, Vector3<S>(b.t + b.h * b.z), start.on_shape);
    if (hit && candidates.offer(*hit)) return candidates.certified();
  }
  return candidates.certified();
}

/// The overlap's depth: the least F over the flat ends' normals, the side's family of normals,
/// the rims' and the apex's regions and MPR's normal (depth_candidates.h). B is the hull of its
/// rims (the cone's: the base rim and the apex), and F is smooth inside each one's region (the
/// directions along which it supports B), equal to that piece's f_P there; so the minimiser is
/// a disc's normal, a local minimum along the side's family (the regions' border), or a local
/// minimum of a rim's or the apex's f_P inside its region. A rim's f_P can have several local
/// minima (the tests found two about 0.2 rad apart, within 5e-6 × size of each other); Newton's
/// method on f_P (sphere_newton.h) starts from the escape directions of the rim's deepest
/// sampled point and its two neighbours, of the sample with the least F, and from the best
/// candidate where the rim supports B there; the apex gets a polytope vertex's descents
/// (docs/math.md → "Flat faces, edges and rims overlapping").
/// Newton on a rim's f_P takes at most kRimSteps steps and stops within kNearAxis (rad) of the
/// rim's axis: there f_P has a kink (the disc's normal, a candidate of its own), which Newton
/// approaches by ever smaller steps and does not reach (uncapped, the overlaps took ten times
/// as long). Away from the axis it converges in under 10 steps; one overlap of the larger
/// sample needed more than 30 to reach 1e-10 × size.
constexpr int kRimSteps = 100;
constexpr double kNearAxis = 1e-3;

template <typename S>
PairHit<S> overlap(const Pair<S>& pair, const Round<S>& b, const PairHit<S>& start) {
  auto support = [&b](const Vector3<S>& u) { return b.support(u); };
  DepthCandidates<S, decltype(support)> depth(pair, support);
  depth.offerDirection(start.normal);
  depth.offerDirection(Vector3<S>(b.z));  // the base (cone, cylinder): v = −n = z
  if (!b.cone) depth.offerDirection(Vector3<S>(-b.z));
  auto direction = [&](S theta) { return Vector3<S>(-b.sideNormal(theta)); };
  auto derivative = [&](S theta, const Vector3<S>&, const Vector3<S>& a) {
    return b.sideNormalDerivative(theta).dot(b.sideAnchor() - a);
  };
  depth.offerFamily(direction, derivative, S(0), S(2 * M_PI), true);
  // Where the superellipsoid's rolling ball certifies the best so far (rolling_certificate.h),
  // the rest is not needed: after the discs and the side, and again after the rims' points.
  const S tolerance =
      S(kRollingOutsideTolerance) * std::max(pair.shape->size(), std::hypot(b.r, b.h));
  auto outside = [&b](const Vector3<S>& x) { return b.outside(x); };
  if (depth.certified(outside, tolerance)) return depth.best();
  constexpr int kRimPoints = 12;
  std::vector<S> sides;  // the rims: the cylinder's two, the cone's base
  for (S side : {S(1), S(-1)}) {
    if (!(b.cone && side > S(0))) sides.push_back(side);
  }
  std::vector<Vector3<S>> points;
  for (S side : sides) {
    for (int k = 0; k < kRimPoints; ++k) {
      points.push_back(b.t + side * b.h * b.z + b.r * b.circle(S(2 * M_PI * k / kRimPoints)));
    }
  }
  const Vector3<S> apex = b.t + b.h * b.z;
  if (b.cone) points.push_back(apex);
  const auto escapes = depth.offerPoints(points);
  if (depth.certified(outside, tolerance)) return depth.best();
  // In float the pattern search stays, as for the polytopes (docs/math.md).
  if constexpr (std::is_same_v<S, float>) return depth.refinedBest();
  const Vector3<S> best = depth.best().normal, u = -best;  // B's supporting direction there
  const bool apex_supports = b.apexSupports(u);
  auto near_axis = [&](const Vector3<S>& v) {
    return (v - v.dot(b.z) * b.z).norm() < S(kNearAxis);
  };
  for (std::size_t k = 0; k < sides.size(); ++k) {
    const SupportMap<S> rim = SupportMap<S>::ofCircle(b.t + sides[k] * b.h * b.z, b.z, b.r);
    const auto first = escapes.begin() + std::ptrdiff_t(k * kRimPoints), last = first + kRimPoints;
    const int deepest =
        int(std::min_element(first, last,
                             [](const auto& x, const auto& y) { return x.distance < y.distance; }) -
            first);
    const int lowest =
        int(std::min_element(first, last, [](const auto& x, const auto& y) { return x.f < y.f; }) -
            first);
    for (int i : {deepest, (deepest + 1) % kRimPoints, (deepest + kRimPoints - 1) % kRimPoints}) {
      depth.offerDescent(rim, first[i].direction, kRimSteps, near_axis);
    }
    if (std::abs(lowest - deepest) > 1 && std::abs(lowest - deepest) != kRimPoints - 1) {
      depth.offerDescent(rim, first[lowest].direction, kRimSteps, near_axis);
    }
    const bool rim_supports = b.cone ? !apex_supports : sides[k] * u.dot(b.z) >= S(0);
    if (rim_supports) depth.offerDescent(rim, best, kRimSteps, near_axis);
  }
  if (b.cone) {
    const SupportMap<S> point = SupportMap<S>::ofPoint(apex);
    if (escapes.back().distance < S(0)) depth.offerDescent(point, Vector3<S>(-b.z));
    if (apex_supports) depth.offerDescent(point, best);
  }
  return depth.best();
}

}  // namespace

template <typename S>
std::optional<PairHit<S>> roundHit(const Pair<S>& pair) {
  const std::optional<Round<S>> b = roundOf(pair);
  if (!b) return std::nullopt;
  const S extent = std::hypot(b->r, b->h);
  return exactPair(
      pair, extent, [&](const Vector3<S>& u) { return b->supportPoint(u); },
      [&](const PairHit<S>& start) {
        // The features near the start's witness; failing that (its witness can be off by more
        // than the margin, far away), every feature.
        if (auto hit = exactSeparated(pair, *b, start, S(1e-3) * extent)) return hit;
        return exactSeparated(pair, *b, start, std::numeric_limits<S>::infinity());
      },
      [&](const PairHit<S>& start) { return overlap(pair, *b, start); });
}

#define FSE_INSTANTIATE_ROUND_HIT(S) template std::optional<PairHit<S>> roundHit(const Pair<S>&);
FSE_INSTANTIATE_ROUND_HIT(float)
FSE_INSTANTIATE_ROUND_HIT(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
