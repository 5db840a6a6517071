#include "narrowphase/round_pair.h"

#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "narrowphase/depth_candidates.h"
#include "narrowphase/feature_newton.h"
#include "narrowphase/feature_pair.h"
#include "narrowphase/libccd_pair.h"
#include "narrowphase/segment_search.h"

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
  /// The point at angle θ of the rim on the end side·z (side ±1; the cone's base: −1).
  Vector3<S> rimPoint(S side, S theta) const { return t + side * h * z + r * circle(theta); }
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
  /// Whether the rim at `side` (±1: t ± h·z; the cone's base is −1) supports B along u.
  bool rimSupports(S side, const Vector3<S>& u) const {
    return cone ? !apexSupports(u) : side * u.dot(z) >= S(0);
  }
  /// The rim at `side` as a support map (a circle).
  SupportMap<S> rim(S side) const { return SupportMap<S>::ofCircle(t + side * h * z, z, r); }
  /// The direction v mirrored across the border of the rims' regions (the directions −v along
  /// which a side normal supports B): its elevation φ over the plane ⊥ z reflected about the
  /// border's, 0 for a cylinder, −atan(r/(2h)) for a cone; the azimuth kept.
  Vector3<S> mirroredAcrossTheSide(const Vector3<S>& v) const {
    const S vz = v.dot(z);
    const Vector3<S> perp = v - vz * z;
    const S rho = perp.norm();
    const Vector3<S> radial = rho > S(0) ? Vector3<S>(perp / rho) : e1;
    const S border = cone ? -std::atan2(r, 2 * h) : S(0);
    const S phi = S(2) * border - std::atan2(vz, rho);
    return std::cos(phi) * radial + std::sin(phi) * z;
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

/// A cylinder or a cone (`cone`) of radius r and height lz posed by X.
template <typename S>
Round<S> roundOf(bool cone, S radius, S lz, const fcl::Transform3<S>& X) {
  return {cone,   X.translation(), X.linear().col(0), X.linear().col(1), X.linear().col(2),
          radius, lz / 2};
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

/// The side's candidate, over its outward normals m(θ) from θ0 (the direction to the other
/// shape is v = −m): F(θ) = h_A(−m) + h_B(m), with h_B(m) = m·t + r for the cylinder (m ⊥ z) and
/// m·apex for the cone (m ∝ 2h·c(θ) + r·z), so F' = m'·(t − a) or m'·(apex − a), a = the support
/// point; nothing where F has no minimum near θ0 or its point is off the side.
template <typename S>
std::optional<PairHit<S>> sideHit(const ShapePair<S>& pair, const Round<S>& b, S theta0) {
  struct Side {
    Vector3<S> v, a;
  };
  auto at = [&](S theta) {
    const Vector3<S> m = b.sideNormal(theta);
    const Vector3<S> a = shapeSupport(pair, Vector3<S>(-m));
    const S derivative = b.sideNormalDerivative(theta).dot(b.sideAnchor() - a);
    return Sample<S, Side>{theta, derivative, {Vector3<S>(-m), a}};
  };
  const std::optional<Side> s = minimumAround<S, Side>(at, theta0);
  if (!s) return std::nullopt;
  const S gap = -b.support(Vector3<S>(-s->v)) - s->v.dot(s->a);  // −h_B(−v) − h_A(v)
  const Vector3<S> on = s->a + gap * s->v;
  if (!(std::abs((on - b.t).dot(b.z)) <= b.h)) return std::nullopt;
  return PairHit<S>{gap, on, s->a, s->v, -1};
}

/// sideHit by Newton's method in θ from θ0 (few support evaluations with their Hessians where
/// sideHit's bracketing takes dozens of support points): F' = m'·(anchor − a) as there, and
/// F'' = m''·(anchor − a) + m'·∇²h_A(−m)·m' (a = ∇h_A(−m)), with a backtracking line search;
/// F is convex in θ near a minimum with F < 0 (the side apart from the shape). Nothing unless
/// it settles at a minimum with F < 0 whose point is on the side; `past_base` says whether the
/// point where it settled, moved onto the side's plane, lies beyond the base's plane (the base's
/// rim is then the likely contact).
template <typename S>
std::optional<PairHit<S>> sideNewton(const ShapePair<S>& pair, const Round<S>& b, S theta0,
                                     bool& past_base) {
  const SupportMap<S> A(*pair.shape, *pair.X_WS);
  const S slant = std::hypot(2 * b.h, b.r);
  const S curl = b.cone && slant > S(0) ? 2 * b.h / slant : S(1);  // m'' = −curl·c(θ)
  const Vector3<S> anchor = b.sideAnchor();
  const S offset = b.cone ? S(0) : b.r;  // h_B(m) = m·anchor + offset
  struct At {
    S theta, f, f1, f2;
    Vector3<S> m, a;
  };
  auto at = [&](S theta) {
    const Vector3<S> m = b.sideNormal(theta), m1 = b.sideNormalDerivative(theta);
    const SupportEval<S> e = A.evaluate(Vector3<S>(-m));
    const Vector3<S> to_anchor = anchor - e.point;
    return At{theta,
              e.value + m.dot(anchor) + offset,
              m1.dot(to_anchor),
              -curl * b.circle(theta).dot(to_anchor) + m1.dot(e.hessian * m1),
              m,
              e.point};
  };
  const S eps = std::numeric_limits<S>::epsilon();
  At p = at(theta0);
  for (int it = 0; it < kCircleNewtonIterations; ++it) {
    const S scale = std::abs(p.f2) + std::abs(p.f) + std::numeric_limits<S>::min();
    S step = -p.f1 / std::max(p.f2, S(1e-8) * scale);
    if (!std::isfinite(step)) return std::nullopt;
    step = std::max(S(-0.5), std::min(S(0.5), step));
    const S noise = S(16) * eps * (p.a.norm() + anchor.norm() + std::abs(p.f));
    bool moved = false;
    for (S alpha = S(1); alpha > S(1e-6); alpha *= S(0.5)) {
      const At q = at(p.theta + alpha * step);
      if (q.f <= p.f + S(1e-4) * alpha * step * p.f1 || (q.f <= p.f + noise && alpha == S(1))) {
        moved = q.theta != p.theta;
        p = q;
        break;
      }
    }
    if (!moved || std::abs(step) < S(64) * eps) break;
  }
  const Vector3<S> v = -p.m;
  const Vector3<S> on = p.a - p.f * v;  // the gap −F along v (F < 0), on the side's plane
  past_base = (on - b.t).dot(b.z) < -b.h;
  if (!(p.f < S(0)) || !p.a.allFinite()) return std::nullopt;
  if (!(std::abs((on - b.t).dot(b.z)) <= b.h)) return std::nullopt;
  return PairHit<S>{-p.f, on, p.a, v, -1};
}

/// A flat end's candidate (the cylinder's disc on `side`, ±1, or the cone's base, −1): the
/// shape's support point along the end's inward normal and its projection into the end's plane
/// (a candidate where it lands on the disc: onEnd).
template <typename S>
PairHit<S> endCandidate(const ShapePair<S>& pair, const Round<S>& b, S side) {
  const Vector3<S> n = side * b.z;
  const Vector3<S> a = shapeSupport(pair, Vector3<S>(-n));
  const S d = n.dot(a) - n.dot(b.t) - b.h;
  return PairHit<S>{d, Vector3<S>(a - d * n), a, Vector3<S>(-n), -1};
}

template <typename S>
bool onEnd(const Round<S>& b, const PairHit<S>& end) {
  const Vector3<S> off_axis = (end.on_other - b.t) - (end.on_other - b.t).dot(b.z) * b.z;
  return off_axis.norm() <= b.r;
}

/// Whether the cone's apex lies nearer the shape than the base rim's point at θ0, by the shape's
/// gauge (as the polytope's nearest vertex is picked): which of the two to try first once the
/// side has failed.
template <typename S>
bool apexNearer(const ShapePair<S>& pair, const Round<S>& b, S theta0) {
  const fcl::Transform3<S> X_SW = pair.X_WS->inverse(Eigen::Isometry);
  auto gauge = [&](const Vector3<S>& p) { return pair.shape->gauge(Vector3<S>(X_SW * p)); };
  return gauge(Vector3<S>(b.t + b.h * b.z)) < gauge(b.rimPoint(S(-1), theta0));
}

/// Newton steps on the facing rim at most before a separating direction is found: apart, it
/// converges in a few; where the shapes overlap there is none to find.
constexpr int kGuessSteps = 10;

/// The exact answer for separated shapes from the features that face the shape, picked by the
/// direction w from B's centre towards the shape's, tried before any GJK: the flat end facing
/// it (the cone's base, wherever w points), the side (the cylinder's: its axis against the shape
/// by Newton, feature_newton.h, moved out by r; the cone's: the search over its normals from w's
/// angle), that end's rim (Newton on its disc), the cone's apex (the point solver, cold), in the
/// order w suggests, and once the cone's side has failed, the apex before the base if it is
/// nearer by the shape's gauge. Nothing
/// unless one is certified; a miss costs the features tried, then GJK starts as before
/// (docs/math.md → "Shape pairs"). A point of the shape found inside B, or of B's rim inside
/// the shape, proves an overlap: then nothing more is tried (the rim's Newton, finding no
/// separating direction, would run long).
template <typename S>
class FacingFeatures {
 public:
  /// `w`: the unit direction from B's centre towards the shape's.
  FacingFeatures(const ShapePair<S>& pair, const Round<S>& b, const Vector3<S>& w)
      : pair_(pair),
        b_(b),
        w_(w),
        candidates_(pair, Support{&b}, std::hypot(b.r, b.h)),
        // The end whose outward normal side·z points towards the shape; the cone's base, its
        // only end, wherever the shape is (a shape above the base's plane can still touch its
        // rim).
        side_(b.cone || w.dot(b.z) < S(0) ? S(-1) : S(1)),
        theta0_(std::atan2(w.dot(b.e2), w.dot(b.e1))) {}

  std::optional<PairHit<S>> run() {
    std::array<Feature, 4> order = firstOrder();
    for (std::size_t k = 0; k < order.size(); ++k) {
      const Feature feature = order[k];
      const Tried t = feature == kEnd    ? end()
                      : feature == kSide ? lateral()
                      : feature == kRim  ? rim()
                                         : apex();
      if (t == Tried::kCertified) return candidates_.certified();
      if (t == Tried::kOverlap) return std::nullopt;
      // The cone's side failed first: the apex next if it lies nearer the shape than the base
      // rim.
      if (k == 0 && feature == kSide && b_.cone && apexNearer(pair_, b_, theta0_)) {
        order = {kSide, kApex, kEnd, kRim};
      }
    }
    return std::nullopt;
  }

 private:
  struct Support {
    const Round<S>* b;
    S operator()(const Vector3<S>& x) const { return b->support(x); }
  };
  enum class Tried { kCertified, kOverlap, kNot };
  enum Feature { kEnd, kSide, kRim, kApex };

  /// The order w suggests: the apex first where it supports B along w; the side first where
  /// w's axial part is nearer the side normal's (at w's angle) than the ends'; else the end and
  /// its rim.
  std::array<Feature, 4> firstOrder() const {
    const S side_z = b_.sideNormal(theta0_).dot(b_.z);  // 0 for the cylinder
    const S wz = w_.dot(b_.z);
    const bool side_first =
        wz > S(0.5) * (side_z - S(1)) && (b_.cone || wz < S(0.5) * (side_z + S(1)));
    if (b_.apexSupports(w_)) return {kApex, kSide, kEnd, kRim};
    if (side_first) return {kSide, kEnd, kRim, kApex};
    return {kEnd, kRim, kSide, kApex};
  }

  bool inside(const PairHit<S>& hit) const { return b_.outside(hit.on_shape) <= S(0); }
  /// A cone's base faces away from a shape above its plane: there it is tried only where the
  /// side's search settled past the base (an overlap would otherwise spend the rim's guesses).
  bool baseFaces() const { return !(b_.cone && w_.dot(b_.z) > S(0)) || past_base_; }

  /// The flat end facing the shape.
  Tried end() {
    if (!baseFaces()) return Tried::kNot;
    const PairHit<S> hit = endCandidate(pair_, b_, side_);
    if (inside(hit)) return Tried::kOverlap;
    return onEnd(b_, hit) && candidates_.offer(hit) ? Tried::kCertified : Tried::kNot;
  }

  /// The side: the cone's by the search over its normals from w's angle, the cylinder's as its
  /// axis against the shape (feature_newton.h), moved out by r.
  Tried lateral() {
    std::optional<PairHit<S>> hit;
    if (b_.cone) {
      hit = sideNewton(pair_, b_, theta0_, past_base_);
    } else if (const std::optional<PairHit<S>> axis =
                   segmentInteriorApart(*pair_.shape, *pair_.X_WS, Vector3<S>(b_.t - b_.h * b_.z),
                                        Vector3<S>(b_.t + b_.h * b_.z), Vector3<S>(-w_))) {
      hit = PairHit<S>{axis->distance - b_.r, Vector3<S>(axis->on_other - b_.r * axis->normal),
                       axis->on_shape, axis->normal, -1};
    }
    if (!hit) return Tried::kNot;
    if (inside(*hit)) return Tried::kOverlap;
    return candidates_.offer(*hit) ? Tried::kCertified : Tried::kNot;
  }

  /// The facing end's rim: Newton on its disc from the middle of the rim's normals at θ0
  /// (between the end's and the side's); given up after kGuessSteps steps without a separating
  /// direction (F < 0), or at one along which the cone's apex, not the disc, supports B (the
  /// disc's answer there is not the cone's), else run to its end, so the answer is as exact as
  /// the other features'.
  Tried rim() {
    if (!baseFaces()) return Tried::kNot;
    const Vector3<S> centre = b_.t + side_ * b_.h * b_.z;
    const fcl::Transform3<S> X_SW = pair_.X_WS->inverse(Eigen::Isometry);
    if (pair_.shape->contains(Vector3<S>(X_SW * b_.rimPoint(side_, theta0_)))) {
      return Tried::kOverlap;
    }
    const Vector3<S> normal = side_ * b_.z + b_.sideNormal(theta0_);
    int steps = 0;
    auto hopeless = [&](const Probe<S>& p) {
      return ++steps >= kGuessSteps && (!(p.f < S(0)) || b_.apexSupports(Vector3<S>(-p.v)));
    };
    const std::optional<PairHit<S>> hit =
        discApart(*pair_.shape, *pair_.X_WS, centre, b_.z, b_.r, Vector3<S>(-normal), hopeless);
    return hit && candidates_.offer(*hit) ? Tried::kCertified : Tried::kNot;
  }

  /// The cone's apex, by the point solver (cold).
  Tried apex() {
    if (!b_.cone) return Tried::kNot;
    const std::optional<PairHit<S>> hit =
        pointApart(*pair_.shape, *pair_.X_WS, Vector3<S>(b_.t + b_.h * b_.z), noHint<S>());
    if (hit && !(hit->distance > S(0))) return Tried::kOverlap;
    return hit && candidates_.offer(*hit) ? Tried::kCertified : Tried::kNot;
  }

  const ShapePair<S>& pair_;
  const Round<S>& b_;
  const Vector3<S> w_;
  Candidates<S, Support> candidates_;
  const S side_;
  const S theta0_;
  bool past_base_ = false;  // the cone's side search settled past the base's plane
};

template <typename S>
std::optional<PairHit<S>> facingFeatures(const ShapePair<S>& pair, const Round<S>& b) {
  const Vector3<S> w = (pair.X_WS->translation() - b.t).normalized();
  if (!w.allFinite()) return std::nullopt;
  return FacingFeatures<S>(pair, b, w).run();
}

/// The exact answer for separated shapes, if a candidate among the features within `margin` of
/// the start's witness (GJK's or libccd's: feature_pair.h) is certified.
template <typename S>
std::optional<PairHit<S>> exactSeparated(const ShapePair<S>& pair, const Round<S>& b,
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
    const PairHit<S> end = endCandidate(pair, b, side);
    if (onEnd(b, end) && candidates.offer(end)) return candidates.certified();
  }
  // The side, near the start's witness.
  const S lateral_gap =
      b.cone ? std::abs(rho0 - b.r * (b.h - z0) / (2 * b.h)) : std::abs(rho0 - b.r);
  if (lateral_gap <= 2 * margin && std::abs(z0) <= b.h + margin) {
    const std::optional<PairHit<S>> side = sideHit(pair, b, theta0);
    if (side && candidates.offer(*side)) return candidates.certified();
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
      const Vector3<S> p = b.rimPoint(side, theta);
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

/// The overlap's candidates that need no start: the flat ends' normals and the side's family.
/// The best if the balls certify it (rolling_certificate.h).
template <typename S, typename Depth>
std::optional<PairHit<S>> endsAndSide(const ShapePair<S>& pair, const Round<S>& b, Depth& depth) {
  depth.offerDirection(Vector3<S>(b.z));  // the base (cone, cylinder): v = −n = z
  if (!b.cone) depth.offerDirection(Vector3<S>(-b.z));
  auto direction = [&](S theta) { return Vector3<S>(-b.sideNormal(theta)); };
  auto derivative = [&](S theta, const Vector3<S>&, const Vector3<S>& a) {
    return b.sideNormalDerivative(theta).dot(b.sideAnchor() - a);
  };
  depth.offerFamily(direction, derivative, S(0), S(2 * M_PI), true);
  auto outside = [&b](const Vector3<S>& x) { return b.outside(x); };
  if (depth.certified(outside, overlapTolerance(*pair.shape, std::hypot(b.r, b.h))))
    return depth.best();
  return std::nullopt;
}

/// The overlap's depth: the least F over the flat ends' normals, the side's family of normals,
/// the rims' and the apex's regions and MPR's normal (depth_candidates.h). B is the hull of its
/// rims (the cone's: the base rim and the apex), and F is smooth inside each one's region (the
/// directions along which it supports B), equal to that piece's f_P there; so the minimiser is
/// a disc's normal, a local minimum along the side's family (the regions' border), or a local
/// minimum of a rim's or the apex's f_P inside its region. A rim's f_P can have several local
/// minima (the tests found two about 0.2 rad apart, within 5e-6 × size of each other); Newton's
/// method on f_P (sphere_newton.h) starts from the escape directions of the rim's deepest
/// sampled point and its two neighbours, of the sample with the least F, from the best
/// candidate where the rim supports B there (the last first, before the rims' points: where the
/// balls certify its minimum, the rest is skipped), and from halfway between the best so far and
/// the rim's axis, where the rim supports B there; the apex gets a polytope vertex's descents
/// (docs/math.md → "Flat faces, edges and rims overlapping").
/// Newton on a rim's f_P takes at most kRimSteps steps and stops within kNearAxis (rad) of the
/// rim's axis: there f_P has a kink (the disc's normal, a candidate of its own), which Newton
/// approaches by ever smaller steps and does not reach (uncapped, the overlaps took ten times
/// as long). Away from the axis it converges in under 10 steps; one overlap of the larger
/// sample needed more than 30 to reach 1e-10 × size. Where MPR found a deep overlap, a rim's and
/// the apex's descents also stop once f_P < 0: they have left the piece's region for good.
constexpr int kRimSteps = 100;
constexpr double kNearAxis = 1e-3;

/// A rim's meridians: the great-circle arcs v(ψ) = cos ψ·d + sin ψ·c(φ) from the disc's
/// direction d = −side·z (ψ = 0) to the border of the rim's region (ψ = π/2, the cone's base
/// π/2 + atan(r/(2h))), at kMeridians azimuths φ. Along one, the rim point q = t + side·h·z −
/// r·c(φ) supports B along −v, so F(ψ) = h_A(v) − v·q, smooth, with derivative v'·(a − q); each
/// meridian's local minima are offered (offerFamily). f_P has a kink at the rim's axis that
/// breaks Newton's basins around it into fragments; in these polar coordinates (ψ > 0) F is
/// smooth (docs/math.md → "The rims' meridians"). Searched where the best ends uncertified within
/// kMeridianTrigger (rad) of a rim's axis.
constexpr int kMeridians = 24;
constexpr double kMeridianSpacing = 0.15;
constexpr double kMeridianTrigger = 0.1;

template <typename S, typename Depth>
void offerMeridians(const Round<S>& b, S side, S from, Depth& depth) {
  const Vector3<S> d = -side * b.z;
  const S reach = S(M_PI / 2) + (b.cone ? std::atan2(b.r, 2 * b.h) : S(0));
  for (int k = 0; k < kMeridians; ++k) {
    const Vector3<S> c = b.circle(S(2 * M_PI * k / kMeridians));
    const Vector3<S> q = b.t + side * b.h * b.z - b.r * c;
    auto direction = [&](S psi) { return Vector3<S>(std::cos(psi) * d + std::sin(psi) * c); };
    auto derivative = [&](S psi, const Vector3<S>&, const Vector3<S>& a) {
      return Vector3<S>(-std::sin(psi) * d + std::cos(psi) * c).dot(a - q);
    };
    depth.offerFamily(direction, derivative, from, reach, false, S(kMeridianSpacing));
  }
}

/// The rest of an overlap's candidates (endsAndSide's are in `depth`), from libccd's start, in
/// stages (run()); each stops the search where the superellipsoid's balls certify the best so
/// far (rolling_certificate.h).
template <typename S, typename Depth>
class RoundOverlap {
 public:
  RoundOverlap(const ShapePair<S>& pair, const Round<S>& b, const PairHit<S>& start, Depth& depth)
      : pair_(pair),
        b_(b),
        start_(start),
        depth_(depth),
        tolerance_(overlapTolerance(*pair.shape, std::hypot(b.r, b.h))),
        // Where MPR found the shapes overlapping by more than kNearTouching × size, F ≥ the
        // depth > 0 everywhere; a piece's f_P equals F inside its region and only falls along a
        // descent, so once f_P < 0 the descent has left the region for good, and its end cannot
        // be F's minimum there.
        depth_floor_(start.distance < -nearTouching(pair, std::hypot(b.r, b.h))
                         ? S(0)
                         : -std::numeric_limits<S>::infinity()),
        apex_(b.t + b.h * b.z),
        apex_map_(SupportMap<S>::ofPoint(apex_)) {
    for (S side : {S(1), S(-1)}) {  // the rims: the cylinder's two, the cone's base
      if (!(b.cone && side > S(0))) sides_.push_back(side);
    }
  }

  PairHit<S> run() {
    depth_.offerDirection(start_.normal);
    if (certified()) return depth_.best();
    const Vector3<S> early = depth_.best().normal;
    if (!std::is_same_v<S, float> && descendFromBest(early)) return depth_.best();
    const std::vector<typename Depth::Escape> escapes = offerRimPoints();
    if (certified()) return depth_.best();
    // In float the pattern search stays, as for the polytopes (docs/math.md).
    if constexpr (std::is_same_v<S, float>) return depth_.refinedBest();
    // The descent from the best is not repeated while the best is the one it started from.
    const Vector3<S> best = depth_.best().normal;
    const bool repeated = best == early;
    if (descendRims(escapes, best, repeated) || descendApex(escapes, best, repeated)) {
      return depth_.best();
    }
    if (certified()) return depth_.best();
    meridiansNearTheAxis();
    return depth_.best();
  }

 private:
  /// The number of points on each rim whose escapes are offered.
  static constexpr int kRimPoints = 12;

  bool certified() const {
    return depth_.certified([this](const Vector3<S>& x) { return b_.outside(x); }, tolerance_);
  }
  /// A descent's stop once it has left its piece's region for good (depth_floor_).
  bool leftRegion(const Probe<S>& p) const { return p.f < depth_floor_; }
  /// A rim's descent's stop: that, or within kNearAxis of the rim's axis (its kink).
  bool nearAxis(const Probe<S>& p) const {
    return leftRegion(p) || (p.v - p.v.dot(b_.z) * b_.z).norm() < S(kNearAxis);
  }

  /// A descent of `piece` (a rim of side `side`, or the apex: side 0) from `from`; true where
  /// the balls certify the best so far. A rim's descent that ends outside the rim's region,
  /// below the best F so far, may hide F's minimum in a second local minimum of f_P inside the
  /// region, the first's mirror image across the side's normals, where the depth would come out
  /// too deep (docs/math.md). Each such end is mirrored once.
  template <typename Stop>
  bool descend(const SupportMap<S>& piece, const Vector3<S>& from, int steps, Stop stop, S side) {
    const Probe<S> end = depth_.offerDescent(piece, from, steps, stop);
    if (certified()) return true;
    if (side == S(0) || !std::isfinite(end.f) || b_.rimSupports(side, Vector3<S>(-end.v)) ||
        !(end.f < -depth_.best().distance)) {
      return false;
    }
    for (const Vector3<S>& v : mirrored_) {
      if ((v - end.v).norm() < S(kNearAxis)) return false;
    }
    mirrored_.push_back(end.v);
    depth_.offerDescent(piece, b_.mirroredAcrossTheSide(end.v), steps, stop);
    return certified();
  }
  bool descendRim(S side, const Vector3<S>& from) {
    return descend(
        b_.rim(side), from, kRimSteps, [this](const Probe<S>& p) { return nearAxis(p); }, side);
  }
  bool descendApexFrom(const Vector3<S>& from) {
    return descend(
        apex_map_, from, kSphereNewtonIterations,
        [this](const Probe<S>& p) { return leftRegion(p); }, S(0));
  }

  /// The descent from the best so far of the piece that supports B there: first, since where it
  /// is certified the rims' point queries (a good part of an overlap's time) are not needed.
  bool descendFromBest(const Vector3<S>& best) {
    const Vector3<S> u = -best;  // B's supporting direction there
    if (b_.cone && b_.apexSupports(u)) return descendApexFrom(best);
    for (S side : sides_) {  // the rims that support B along u (both where u ⊥ z)
      if (b_.rimSupports(side, u) && descendRim(side, best)) return true;
    }
    return false;
  }

  /// The escapes of kRimPoints points on each rim, and of the cone's apex (last).
  std::vector<typename Depth::Escape> offerRimPoints() {
    std::vector<Vector3<S>> points;
    for (S side : sides_) {
      for (int k = 0; k < kRimPoints; ++k) {
        points.push_back(b_.rimPoint(side, S(2 * M_PI * k / kRimPoints)));
      }
    }
    if (b_.cone) points.push_back(apex_);
    return depth_.offerPoints(points);
  }

  /// Each rim's descents: from its deepest point and its two neighbours, from its lowest F if
  /// that is elsewhere, from the best so far (`best`, unless `repeated`) where the rim supports
  /// B there, and from halfway between the best and the rim's axis (the disc's direction
  /// −side·z: the basin of a minimum nearer the axis than the best's). True once certified.
  bool descendRims(const std::vector<typename Depth::Escape>& escapes, const Vector3<S>& best,
                   bool repeated) {
    const Vector3<S> u = -best;  // B's supporting direction there
    for (std::size_t k = 0; k < sides_.size(); ++k) {
      const S side = sides_[k];
      const auto first = escapes.begin() + std::ptrdiff_t(k * kRimPoints),
                 last = first + kRimPoints;
      const int deepest = int(
          std::min_element(first, last,
                           [](const auto& x, const auto& y) { return x.distance < y.distance; }) -
          first);
      const int lowest = int(
          std::min_element(first, last, [](const auto& x, const auto& y) { return x.f < y.f; }) -
          first);
      for (int i : {deepest, (deepest + 1) % kRimPoints, (deepest + kRimPoints - 1) % kRimPoints}) {
        if (descendRim(side, first[i].direction)) return true;
      }
      if (std::abs(lowest - deepest) > 1 && std::abs(lowest - deepest) != kRimPoints - 1) {
        if (descendRim(side, first[lowest].direction)) return true;
      }
      if (b_.rimSupports(side, u) && !repeated && descendRim(side, best)) return true;
      const Vector3<S> now = depth_.best().normal;
      if (b_.rimSupports(side, Vector3<S>(-now)) &&
          descendRim(side, Vector3<S>(now - side * b_.z))) {
        return true;
      }
    }
    return false;
  }

  /// The cone's apex: from its axis direction where the apex is inside the superellipsoid, and
  /// from the best so far where the apex supports B there. True once certified.
  bool descendApex(const std::vector<typename Depth::Escape>& escapes, const Vector3<S>& best,
                   bool repeated) {
    if (!b_.cone) return false;
    if (escapes.back().distance < S(0) && descendApexFrom(Vector3<S>(-b_.z))) return true;
    if (b_.apexSupports(Vector3<S>(-best)) && !repeated) {
      depth_.offerDescent(apex_map_, best, kSphereNewtonIterations,
                          [this](const Probe<S>& p) { return leftRegion(p); });
    }
    return false;
  }

  /// A best near a rim's axis (the disc's normal, or a descent's end near it) that the balls do
  /// not certify: the rim's meridians (offerMeridians), then Newton from the best (without them a
  /// rim's minimum beside the axis kink is missed: RimMinimaAroundTheAxisKink).
  void meridiansNearTheAxis() {
    for (S side : sides_) {
      const Vector3<S> d = -side * b_.z;
      if ((depth_.best().normal - d).norm() > S(kMeridianTrigger)) continue;
      offerMeridians(b_, side, S(kNearAxis), depth_);
      if (descendRim(side, depth_.best().normal)) break;
    }
  }

  const ShapePair<S>& pair_;
  const Round<S>& b_;
  const PairHit<S>& start_;
  Depth& depth_;
  const S tolerance_;
  const S depth_floor_;
  const Vector3<S> apex_;
  const SupportMap<S> apex_map_;
  std::vector<S> sides_;
  std::vector<Vector3<S>> mirrored_;  // the descents' ends mirrored so far
};

template <typename S, typename Depth>
PairHit<S> overlap(const ShapePair<S>& pair, const Round<S>& b, const PairHit<S>& start,
                   Depth& depth) {
  return RoundOverlap<S, Depth>(pair, b, start, depth).run();
}

/// The cylinder's or cone's stages for featurePair (feature_pair.h); `Geometry` is FCL's class
/// of it, for libccd's start.
template <typename S, typename Geometry, typename Depth>
struct RoundFeatures {
  const ShapePair<S>& pair;
  const Geometry& geometry;
  const Round<S>& b;
  Depth& depth;

  S size() const { return std::hypot(b.r, b.h); }
  Vector3<S> supportPoint(const Vector3<S>& u) const { return b.supportPoint(u); }
  /// The features near the start's witness; failing that (its witness can be off by more than
  /// the margin, far away), every feature.
  std::optional<PairHit<S>> separated(const PairHit<S>& start) const {
    if (auto hit = exactSeparated(pair, b, start, S(1e-3) * size())) return hit;
    return exactSeparated(pair, b, start, std::numeric_limits<S>::infinity());
  }
  std::optional<PairHit<S>> startFree() const { return endsAndSide(pair, b, depth); }
  PairHit<S> overlap(const PairHit<S>& start) const {
    return detail::overlap(pair, b, start, depth);
  }
  std::optional<PairHit<S>> libccdStart() const { return libccdHit(pair, geometry); }
};

template <typename S, typename Geometry>
std::optional<PairHit<S>> roundPair(const ShapePair<S>& pair, const Geometry& geometry,
                                    const Round<S>& b) {
  if (const std::optional<PairHit<S>> hit = facingFeatures(pair, b)) return hit;
  auto support = [&b](const Vector3<S>& u) { return b.support(u); };
  DepthCandidates<S, decltype(support)> depth(pair, support);
  return featurePair(pair, RoundFeatures<S, Geometry, decltype(depth)>{pair, geometry, b, depth});
}

}  // namespace

template <typename S>
std::optional<PairHit<S>> cylinderHit(const ShapePair<S>& pair, const fcl::Cylinder<S>& c) {
  return roundPair(pair, c, roundOf(false, c.radius, c.lz, *pair.X_WO));
}
template <typename S>
std::optional<PairHit<S>> coneHit(const ShapePair<S>& pair, const fcl::Cone<S>& c) {
  return roundPair(pair, c, roundOf(true, c.radius, c.lz, *pair.X_WO));
}

#define FSE_INSTANTIATE_ROUND_HIT(S)                                                            \
  template std::optional<PairHit<S>> cylinderHit(const ShapePair<S>&, const fcl::Cylinder<S>&); \
  template std::optional<PairHit<S>> coneHit(const ShapePair<S>&, const fcl::Cone<S>&);
FSE_INSTANTIATE_ROUND_HIT(float)
FSE_INSTANTIATE_ROUND_HIT(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
