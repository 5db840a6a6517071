#include "narrowphase/contact_region.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "narrowphase/region_reduction.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

/// The contact plane: through `origin`, normal n, with n = e1 × e2.
template <typename S>
struct ContactPlane {
  Vector3<S> origin, n, e1, e2;
  /// e1 along `reference` (not parallel to n) projected on the plane.
  ContactPlane(const Vector3<S>& o, const Vector3<S>& normal, const Vector3<S>& reference)
      : origin(o), n(normal) {
    e1 = (reference - reference.dot(n) * n).normalized();
    e2 = n.cross(e1);
  }
  Vector2<S> coordinates(const Vector3<S>& x) const {
    const Vector3<S> r = x - origin;
    return Vector2<S>(r.dot(e1), r.dot(e2));
  }
  Vector3<S> at(const Vector2<S>& y) const { return origin + y.x() * e1 + y.y() * e2; }
};

/// A vertex of an outline: its plane coordinates and, where known exactly, the body's surface
/// point above it (the farthest along the cap's direction on that line).
template <typename S>
struct OutlinePoint {
  Vector2<S> y;
  Vector3<S> on;
  bool exact;
};

/// The extreme point along the lateral unit u of the cap {x in body : x·m ≥ c}, where the
/// body's support along m is beyond c. By duality it is the support point along
/// d(θ) = cos θ·u + sin θ·m for the least θ in [0, π/2] whose support point is at or beyond
/// the cap's base, found by regula falsi (Illinois) on θ to the last bit (the region must not
/// depend on the iterates' path: it turns with the pair); where the support point jumps there
/// (a polytope's edge or face), the answer is on the segment between the bracket's two support
/// points, at the base's height. `exact` tells whether the point is the body's farthest along m
/// on its line along m: so where it is on the base (θ > 0: the tilted support plane touches the
/// cap there alone), not where the support along u is already beyond the base (the line may
/// run along a side face).
///
/// A smooth body (RegionBody::gauge) is solved by Newton's method on the optimality conditions
/// instead: on the base x = x0 + a·u + b·w (w = m × u), G(x) = 1 and ∇G(x)·w = 0 (the gradient
/// in the plane of u and m), with ∇G·u > 0. It starts from `warm` if given (a neighbouring
/// direction's answer, or the last call's), whose answer stands where its normal also leans
/// towards m (∇G·m > 0: then it is the extreme whatever the support along u). Else (or where
/// that fails) the support along u decides whether the cap holds it, and Newton starts from
/// where the ray from `deepest` (the body's point farthest along m), taken to the base, along u
/// leaves the body. Where neither converges (near a crease of an exponent > 1 the extreme point
/// is a corner of the outline, and the gradient turns at once), the search on θ decides.
template <typename S>
Vector3<S> capExtreme(const RegionBody<S>& body, const Vector3<S>& u, const Vector3<S>& m, S c,
                      bool& exact, const Vector3<S>* warm, const Vector3<S>& deepest) {
  const S size = body.size();
  const S eps = std::numeric_limits<S>::epsilon();
  S value;
  Vector3<S> gradient;
  Matrix3<S> hessian;
  const Vector3<S> w = m.cross(u);
  // Newton from x; `certify`: the answer must also have ∇G·m > 0, which makes it the cap's
  // extreme along u whatever the support along u (with the normal ν = cos θ·u + sin θ·m,
  // θ in (0, π/2), every y of the cap has u·y = (ν·y − sin θ·m·y)/cos θ ≤ u·x). A step whose
  // convergence is clearly quadratic (at most 1e-3 of the one before) and whose successor would
  // be below the threshold (C·step² with C = step/previous²) ends the iteration at once, if it
  // is below 1e-6 × the size (in float the threshold itself is larger): the evaluation that would
  // only confirm it is saved.
  const auto newton = [&](Vector3<S> x, bool certify) -> std::optional<Vector3<S>> {
    x -= (x.dot(m) - c) * m;
    const S threshold = S(256) * eps * size;
    S previous = S(0);
    for (int it = 0; it < 24 && body.gauge(x, value, gradient, hessian); ++it) {
      const Vector3<S> hw = hessian * w;
      const S j11 = gradient.dot(u), j12 = gradient.dot(w), j21 = hw.dot(u), j22 = hw.dot(w);
      const S f1 = value - S(1), f2 = gradient.dot(w);
      const S det = j11 * j22 - j12 * j21;
      if (!(std::abs(det) > S(0)) || !(j11 > S(0))) break;
      const S da = -(j22 * f1 - j12 * f2) / det, db = -(j11 * f2 - j21 * f1) / det;
      const S length = std::abs(da) + std::abs(db);
      if (!std::isfinite(length)) break;
      // Along a flat side the outline's curvature is small and a step long: it is taken at
      // most half the size at a time.
      const S shortened = std::min(S(1), S(0.5) * size / length);
      x += shortened * (da * u + db * w);
      const bool upward = !certify || gradient.dot(m) > S(0);
      if (length <= threshold) {
        // Converged; where the gradient still leaves the plane of u and m, x is near a crease
        // and the steps only shrank.
        if (std::abs(f2) <= S(1e4) * eps * gradient.norm() && upward) return x;
        break;
      }
      const S ratio = length / previous;
      if (previous > S(0) && length <= S(1e-6) * size && ratio <= S(1e-3) &&
          length * ratio * ratio <= threshold && upward) {
        return x;
      }
      previous = shortened == S(1) ? length : S(0);
    }
    return std::nullopt;
  };
  if (warm != nullptr) {
    if (const std::optional<Vector3<S>> x = newton(*warm, true)) {
      exact = true;
      return *x;
    }
  }
  Vector3<S> p_lo = body.support(u);
  S g_lo = p_lo.dot(m) - c;
  exact = g_lo < S(0);
  if (!exact) return p_lo;
  if (body.gauge(deepest, value, gradient, hessian)) {
    // The ray's exit: Newton on G(o + r·u) = 1 from beyond the body, where G is convex along
    // the ray and the iterates fall to its exit. o, the deepest point taken back along m to
    // the base, is inside (m is the body's normal there).
    const Vector3<S> o = deepest - (deepest.dot(m) - c) * m;
    S r = S(2) * size;
    for (int it = 0; it < 60 && body.gauge(Vector3<S>(o + r * u), value, gradient, hessian); ++it) {
      const S slope = gradient.dot(u);
      if (!(slope > S(0))) break;
      const S step = (value - S(1)) / slope;
      r -= step;
      if (std::abs(step) <= S(64) * eps * size) {
        if (r > S(0)) {
          if (const std::optional<Vector3<S>> x = newton(Vector3<S>(o + r * u), false)) return *x;
        }
        break;
      }
    }
  }
  S lo = S(0), hi = S(M_PI / 2);
  Vector3<S> p_hi = body.support(m);
  S g_hi = p_hi.dot(m) - c;
  S f_lo = g_lo, f_hi = g_hi;  // the values regula falsi interpolates (halved when stuck)
  int side = 0;
  for (int it = 0; it < 100; ++it) {
    S t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(t > lo && t < hi)) t = S(0.5) * (lo + hi);
    if (!(t > lo && t < hi)) break;  // the bracket is down to adjacent numbers
    const Vector3<S> p = body.support(Vector3<S>(std::cos(t) * u + std::sin(t) * m));
    const S g = p.dot(m) - c;
    if (g == S(0)) return p;
    if (g < S(0)) {
      lo = t, p_lo = p, g_lo = g, f_lo = g;
      if (side == -1) f_hi *= S(0.5);
      side = -1;
    } else {
      hi = t, p_hi = p, g_hi = g, f_hi = g;
      if (side == 1) f_lo *= S(0.5);
      side = 1;
    }
    if ((p_hi - p_lo).squaredNorm() == S(0)) return p_hi;
  }
  const S rise = g_hi - g_lo;
  return rise > S(0) ? Vector3<S>(p_lo + (-g_lo / rise) * (p_hi - p_lo)) : p_hi;
}

/// The cap's outline on the plane, counter-clockwise: its extreme points in `samples`
/// directions, then, edge by edge, the extreme point along the edge's outward normal inserted
/// wherever it lies farther than η beyond the edge. The area an edge misses is about 2/3 of
/// its length times its gap, so η = 1.5·area_tolerance·A/P (A, P: the first polygon's area and
/// perimeter) keeps the missed area within area_tolerance of the whole. Points closer than
/// `merge` to their predecessor are merged. `warm` (if not null): read as the samples' starts
/// where it holds one per direction (else each starts from its neighbour's answer), then
/// replaced by the samples' answers.
template <typename S>
std::vector<OutlinePoint<S>> capOutline(const RegionBody<S>& body, const ContactPlane<S>& plane,
                                        const Vector3<S>& m, S c, const Vector3<S>& deepest,
                                        const ManifoldOptions<S>& options, S merge,
                                        std::vector<Vector3<S>>* warm) {
  std::vector<OutlinePoint<S>> outline;
  // Every point found is in the cap, so none may lie farther along a direction than that
  // direction's extreme: a warm-started answer that does is a wrong root, and the direction is
  // solved again from its start (and if that fails too, the farthest point known stands in).
  const auto farthestKnown = [&](const Vector2<S>& dir, const OutlinePoint<S>& o) {
    const OutlinePoint<S>* best = &o;
    for (const OutlinePoint<S>& q : outline) {
      if (dir.dot(q.y - best->y) > merge) best = &q;
    }
    return best;
  };
  const auto extreme = [&](const Vector2<S>& dir, const Vector3<S>* warm) {
    const Vector3<S> u = dir.x() * plane.e1 + dir.y() * plane.e2;
    OutlinePoint<S> o;
    o.on = capExtreme(body, u, m, c, o.exact, warm, deepest);
    o.y = plane.coordinates(o.on);
    if (warm != nullptr && farthestKnown(dir, o) != &o) {
      o.on = capExtreme<S>(body, u, m, c, o.exact, nullptr, deepest);
      o.y = plane.coordinates(o.on);
    }
    const OutlinePoint<S>* best = farthestKnown(dir, o);
    return best == &o ? o : *best;
  };
  const int samples = options.outline_samples;
  const bool warm_started = warm != nullptr && warm->size() == std::size_t(samples);
  std::vector<Vector3<S>> answers;
  for (int k = 0; k < samples; ++k) {
    const S phi = S(2 * M_PI) * S(k) / S(samples);
    const Vector3<S>* start = warm_started                               ? &(*warm)[std::size_t(k)]
                              : outline.empty() || !outline.back().exact ? nullptr
                                                                         : &outline.back().on;
    const OutlinePoint<S> o = extreme(Vector2<S>(std::cos(phi), std::sin(phi)), start);
    if (warm != nullptr) answers.push_back(o.on);
    if (outline.empty() || (o.y - outline.back().y).norm() > merge) outline.push_back(o);
  }
  if (warm != nullptr) *warm = std::move(answers);
  while (outline.size() > 1 && (outline.front().y - outline.back().y).norm() <= merge) {
    outline.pop_back();
  }
  if (outline.size() < 3 || options.outline_area_tolerance >= S(1)) return outline;
  S area = S(0), perimeter = S(0);
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Vector2<S>& a = outline[i].y;
    const Vector2<S>& b = outline[(i + 1) % outline.size()].y;
    area += S(0.5) * cross2(a, b);
    perimeter += (b - a).norm();
  }
  const S gap_allowed = std::max(
      {S(1.5) * options.outline_area_tolerance * area / perimeter, merge, S(1e-6) * perimeter});
  const std::size_t most = std::size_t(16) * std::size_t(samples);
  // Edges shorter than √ε × the size are rounding's (their direction is noise) and miss no
  // area worth a sample.
  const S shortest = std::max(merge, std::sqrt(std::numeric_limits<S>::epsilon()) * perimeter);
  for (std::size_t k = 0; k < outline.size() && outline.size() < most;) {
    const Vector2<S> edge = outline[(k + 1) % outline.size()].y - outline[k].y;
    const S length = edge.norm();
    if (length <= shortest) {
      ++k;
      continue;
    }
    const Vector2<S> outward(edge.y() / length, -edge.x() / length);
    const OutlinePoint<S>& next = outline[(k + 1) % outline.size()];
    const Vector3<S> middle = S(0.5) * (outline[k].on + next.on);
    const OutlinePoint<S> o = extreme(outward, outline[k].exact && next.exact ? &middle : nullptr);
    // The extreme along an edge's outward normal lies beyond the edge and between its ends
    // (the outline is convex); a point elsewhere is rounding's, and the edge is kept.
    const S along = edge.dot(o.y - outline[k].y) / length;
    if (outward.dot(o.y - outline[k].y) > gap_allowed && along > -merge && along < length + merge) {
      outline.insert(outline.begin() + std::ptrdiff_t(k + 1), o);
    } else {
      ++k;
    }
  }
  return outline;
}

/// The outline as a convex polygon, counter-clockwise: as it is where it turns left at every
/// vertex (up to `merge`), else the convex hull of its points (monotone chain), which a
/// sampling that rounding has reordered or folded would otherwise make a wrong clip of.
template <typename S>
std::vector<OutlinePoint<S>> convexOutline(std::vector<OutlinePoint<S>> outline, S merge) {
  const std::size_t n = outline.size();
  if (n < 3) return outline;
  bool convex = true;
  S turning = S(0);
  for (std::size_t i = 0; i < n && convex; ++i) {
    const Vector2<S> e0 = outline[(i + 1) % n].y - outline[i].y;
    const Vector2<S> e1 = outline[(i + 2) % n].y - outline[(i + 1) % n].y;
    convex = cross2(e0, e1) >= -merge * (e0.norm() + e1.norm());
    turning += std::atan2(cross2(e0, e1), e0.dot(e1));
  }
  if (convex && std::abs(turning - S(2 * M_PI)) < S(0.5)) return outline;
  std::vector<Vector2<S>> points;
  for (const OutlinePoint<S>& o : outline) points.push_back(o.y);
  std::vector<OutlinePoint<S>> hull;
  for (const std::size_t i : hullOrder(points)) hull.push_back(outline[i]);
  return hull;
}

/// The convex polygon `subject` clipped by the convex polygon `clip` (both counter-clockwise;
/// Sutherland–Hodgman).
/// (The subject's vertices keep their surface points; the new ones have none.)
template <typename S>
std::vector<OutlinePoint<S>> clipConvex(std::vector<OutlinePoint<S>> subject,
                                        const std::vector<OutlinePoint<S>>& clip) {
  if (clip.size() < 3) return subject;  // a point or a segment clips nothing (the cap is thin)
  for (std::size_t i = 0; i < clip.size() && !subject.empty(); ++i) {
    const Vector2<S>& a = clip[i].y;
    const Vector2<S> edge = clip[(i + 1) % clip.size()].y - a;
    std::vector<OutlinePoint<S>> kept;
    kept.reserve(subject.size() + 1);
    for (std::size_t j = 0; j < subject.size(); ++j) {
      const OutlinePoint<S>& p = subject[j];
      const OutlinePoint<S>& q = subject[(j + 1) % subject.size()];
      const S sp = cross2(edge, Vector2<S>(p.y - a)), sq = cross2(edge, Vector2<S>(q.y - a));
      if (sp >= S(0)) kept.push_back(p);
      if ((sp >= S(0)) != (sq >= S(0))) {
        kept.push_back(
            {Vector2<S>(p.y + (sp / (sp - sq)) * (q.y - p.y)), Vector3<S>::Zero(), false});
      }
    }
    subject = std::move(kept);
  }
  return subject;
}

/// The region of `a` against the bodies `pieces` at the hit (contactRegion, facetsRegion): a's
/// cap outlined once, clipped by each piece's cap, the clipped vertices measured along n against
/// that piece; of several pieces the region is the convex hull of their places. The hit's place
/// is a candidate of the reduction where `hit_is_a_place`. For a mesh's `facets` a flat piece's
/// cap that holds all its corners is outlined by them (a pair's is searched, as ever).
template <typename S>
ContactManifold<S> regionOfPieces(const RegionBody<S>& a,
                                  const std::vector<const RegionBody<S>*>& pieces,
                                  const PairHit<S>& hit, bool hit_is_a_place, bool facets,
                                  const Matrix3<S>& R_WS, S tolerance, S size,
                                  const ManifoldOptions<S>& options, RegionWarmStart<S>* warm) {
  ContactManifold<S> out;
  out.normal = hit.normal.normalized();
  out.distance = hit.distance;
  out.on_shape = hit.on_shape;
  out.on_other = hit.on_other;
  out.patch_tolerance = tolerance;
  const S thickness = tolerance - hit.distance;
  if (!(thickness > S(0))) return out;  // apart by more than the tolerance: no region

  const Vector3<S>& n = out.normal;
  // The outline's first direction comes from the shape's frame, so that the region turns with
  // the pair: its x axis, or its y axis where x is within 25° of the normal.
  const Vector3<S> reference = std::abs(R_WS.col(0).dot(n)) < S(0.9) ? R_WS.col(0) : R_WS.col(1);
  const ContactPlane<S> plane(S(0.5) * (hit.on_shape + hit.on_other), n, reference);
  const S merge = S(64) * std::numeric_limits<S>::epsilon() * size;

  // Each cap: the body beyond the other's supporting plane less the tolerance.
  const std::vector<OutlinePoint<S>> a_cap =
      convexOutline(capOutline(a, plane, n, S(hit.on_shape.dot(n) - thickness), hit.on_shape,
                               options, merge, warm != nullptr ? &warm->a : nullptr),
                    merge);
  const auto centroidOf = [](const std::vector<OutlinePoint<S>>& polygon) {
    Vector2<S> centroid = Vector2<S>::Zero();
    for (const OutlinePoint<S>& o : polygon) centroid += o.y;
    return polygon.empty() ? centroid : Vector2<S>(centroid / S(polygon.size()));
  };
  // The place at y on the plane between a's surface `up` above it and b's `down` below, if both
  // lines met their bodies and the place is finite. Rounding on bodies far apart in scale (a
  // float sphere of radius 3.7e30 on a unit shape) can overflow a measurement: such a place is
  // dropped like a missed one.
  const auto placeAt = [&](const Vector2<S>& y, const Vector3<S>& at, const std::optional<S>& up,
                           const std::optional<S>& down) -> std::optional<Place<S>> {
    if (!up || !down) return std::nullopt;
    ManifoldPoint<S> p;
    p.on_shape = at + *up * n;
    p.on_other = at - *down * n;
    p.position = S(0.5) * (p.on_shape + p.on_other);
    p.depth = *up + *down;
    if (!(p.on_shape.allFinite() && p.on_other.allFinite() && p.position.allFinite() &&
          std::isfinite(p.depth))) {
      return std::nullopt;
    }
    return Place<S>{p, y};
  };
  // A line that misses a body by rounding (on a cap's rim) is measured again a little towards
  // `centroid`.
  const S pulls[] = {S(0), S(1e-6), S(1e-3)};
  // The place above y against b (the shape's surface point known if `known` is an exact outline
  // point at y); std::nullopt where every pull misses.
  const auto measured = [&](const Vector2<S>& y0, const Vector2<S>& centroid,
                            const RegionBody<S>& b,
                            const OutlinePoint<S>* known) -> std::optional<Place<S>> {
    for (const S pull : pulls) {
      const Vector2<S> y = y0 + pull * (centroid - y0);
      const Vector3<S> at = plane.at(y);
      const std::optional<S> up = known != nullptr && known->exact && pull == S(0)
                                      ? std::optional<S>((known->on - at).dot(n))
                                      : a.extent(at, n);
      if (std::optional<Place<S>> p = placeAt(y, at, up, b.extent(at, Vector3<S>(-n)))) return p;
    }
    return std::nullopt;
  };
  // The region's vertices, each with its piece and its piece's clipped polygon's centroid; of
  // several pieces only those on the hull of them all are measured.
  struct Vertex {
    OutlinePoint<S> o;
    const RegionBody<S>* piece;
    Vector2<S> centroid;
  };
  std::vector<Vertex> vertices;
  std::vector<Vector3<S>> corners;
  for (const RegionBody<S>* b : pieces) {
    std::vector<OutlinePoint<S>> region = a_cap;
    if (!b->unbounded()) {
      const Vector3<S> m = -n;
      const S base = hit.on_other.dot(m) - thickness;
      std::vector<OutlinePoint<S>> b_cap;
      if (facets && b->corners(corners) &&
          std::all_of(corners.begin(), corners.end(),
                      [&](const Vector3<S>& p) { return p.dot(m) >= base; })) {
        for (const Vector3<S>& p : corners) b_cap.push_back({plane.coordinates(p), p, false});
      } else {
        b_cap = capOutline(*b, plane, m, base, hit.on_other, options, merge,
                           warm != nullptr && pieces.size() == 1 ? &warm->b : nullptr);
      }
      region = clipConvex(region, convexOutline(std::move(b_cap), merge));
    }
    const Vector2<S> centroid = centroidOf(region);
    for (const OutlinePoint<S>& o : region) vertices.push_back({o, b, centroid});
  }
  if (pieces.size() > 1) {
    std::vector<Vector2<S>> ys;
    for (const Vertex& v : vertices) ys.push_back(v.o.y);
    std::vector<Vertex> hull;
    for (const std::size_t i : hullOrder(ys)) hull.push_back(vertices[i]);
    vertices = std::move(hull);
  }

  // The depth at each vertex, along n: the shape's surface point is known where the vertex is
  // one of its outline's, else measured; a vertex whose line misses a body by rounding (it is on
  // a cap's rim) is measured a little towards its piece's centroid.
  std::vector<Place<S>> places;
  for (const Vertex& v : vertices) {
    if (const std::optional<Place<S>> p = measured(v.o.y, v.centroid, *v.piece, &v.o)) {
      if (!places.empty() && (p->y - places.back().y).norm() <= merge) continue;
      places.push_back(*p);
    }
  }
  for (const Place<S>& p : places) out.polygon.push_back(p.point);

  if (hit_is_a_place) {
    // The deepest place, the hit's, is a candidate after the vertices.
    ManifoldPoint<S> deepest;
    deepest.on_shape = hit.on_shape;
    deepest.on_other = hit.on_other;
    deepest.position = plane.origin;
    deepest.depth = -hit.distance;
    if (out.polygon.empty()) out.polygon.push_back(deepest);
    places.push_back({deepest, Vector2<S>::Zero()});
  } else if (!places.empty()) {
    // The shape's deepest point is off the pieces, so the region's deepest place is on its rim
    // (the depth is concave on the plane, greatest at the origin, the point under the shape's
    // deepest point): at a vertex, or inside an edge whose line has the origin on its far side
    // (at the deepest place a line supports the region and the superlevel set of the depth
    // beyond it: the edge's own line, if the place is inside an edge). Each such edge is
    // bisected on the sign of the depth's slope along it, which locates its deepest place to
    // rounding (the depth itself is flat there: its values would locate it only to about √ε ×
    // the size); that place is a candidate after the vertices.
    const auto deeper = [](const Place<S>& x, const Place<S>& y) {
      return x.point.depth < y.point.depth;
    };
    std::vector<OutlinePoint<S>> rim;
    for (const Place<S>& p : places) rim.push_back({p.y, p.point.on_shape, false});
    const Vector2<S> centroid = centroidOf(rim);
    // The place at y over any piece (the shape's line is measured once for all of them), with
    // the slope of the depth there along the plane's direction `along`: the shape's surface
    // rises by −(∇G·along)/(∇G·n) and the piece's falls by (n_P·along)/(n_P·n) (n_P its plane's
    // normal); 0 where either normal is unknown.
    struct RimPlace {
      Place<S> place;
      S slope;
    };
    std::vector<Vector3<S>> piece_corners;
    const auto placeOnRim = [&](const Vector2<S>& y0,
                                const Vector3<S>& along) -> std::optional<RimPlace> {
      for (const S pull : pulls) {
        const Vector2<S> y = y0 + pull * (centroid - y0);
        const Vector3<S> at = plane.at(y);
        const std::optional<S> up = a.extent(at, n);
        if (!up) continue;
        for (const RegionBody<S>* b : pieces) {
          std::optional<Place<S>> p = placeAt(y, at, up, b->extent(at, Vector3<S>(-n)));
          if (!p) continue;
          S slope = S(0);
          S value;
          Vector3<S> gradient;
          Matrix3<S> hessian;
          if (a.gauge(p->point.on_shape, value, gradient, hessian) && b->corners(piece_corners) &&
              piece_corners.size() == 3) {
            const Vector3<S> n_p = (piece_corners[1] - piece_corners[0])
                                       .cross(Vector3<S>(piece_corners[2] - piece_corners[0]));
            const S rise = -gradient.dot(along) / gradient.dot(n);
            const S fall = n_p.dot(along) / n_p.dot(n);
            if (std::isfinite(rise) && std::isfinite(fall)) slope = rise + fall;
          }
          return RimPlace{*p, slope};
        }
      }
      return std::nullopt;
    };
    Place<S> best = *std::max_element(places.begin(), places.end(), deeper);
    for (std::size_t k = 0; k < places.size() && places.size() > 1; ++k) {
      const Vector2<S> y0 = places[k].y, y1 = places[(k + 1) % places.size()].y;
      if (!(cross2(Vector2<S>(y1 - y0), Vector2<S>(-y0)) < S(0))) continue;  // origin inside
      const Vector3<S> along = plane.at(y1) - plane.at(y0);
      // The slope is ≥ 0 left of the deepest place and ≤ 0 right of it.
      // (A place whose lines miss both bodies ends the bisection; the last one found stands.)
      S lo = S(0), hi = S(1);
      std::optional<RimPlace> last;
      for (int it = 0; it < 64 && (hi - lo) * (y1 - y0).norm() > merge; ++it) {
        const S t = S(0.5) * (lo + hi);
        const std::optional<RimPlace> at = placeOnRim(Vector2<S>(y0 + t * (y1 - y0)), along);
        if (!at) break;
        last = at;
        if (last->slope > S(0)) {
          lo = t;
        } else {
          hi = t;
        }
      }
      if (last && last->place.point.depth > best.point.depth) best = last->place;
    }
    out.distance = -best.point.depth;
    out.on_shape = best.point.on_shape;
    out.on_other = best.point.on_other;
    places.push_back(best);
  }
  out.points = reduce(places, options.max_points, tolerance, merge);
  return out;
}

}  // namespace

template <typename S>
ContactManifold<S> contactRegion(const RegionBody<S>& a, const RegionBody<S>& b,
                                 const PairHit<S>& hit, const Matrix3<S>& R_WS, S tolerance, S size,
                                 const ManifoldOptions<S>& options, RegionWarmStart<S>* warm) {
  return regionOfPieces(a, {&b}, hit, true, false, R_WS, tolerance, size, options, warm);
}

template <typename S>
ContactManifold<S> facetsRegion(const RegionBody<S>& a,
                                const std::vector<const RegionBody<S>*>& facets,
                                const PairHit<S>& hit, bool hit_on_facets, const Matrix3<S>& R_WS,
                                S tolerance, S size, const ManifoldOptions<S>& options) {
  return regionOfPieces(a, facets, hit, hit_on_facets, true, R_WS, tolerance, size, options,
                        static_cast<RegionWarmStart<S>*>(nullptr));
}

#define FSE_INSTANTIATE_CONTACT_REGION(S)                                                      \
  template ContactManifold<S> contactRegion(const RegionBody<S>&, const RegionBody<S>&,        \
                                            const PairHit<S>&, const Matrix3<S>&, S, S,        \
                                            const ManifoldOptions<S>&, RegionWarmStart<S>*);   \
  template ContactManifold<S> facetsRegion(                                                    \
      const RegionBody<S>&, const std::vector<const RegionBody<S>*>&, const PairHit<S>&, bool, \
      const Matrix3<S>&, S, S, const ManifoldOptions<S>&);
FSE_INSTANTIATE_CONTACT_REGION(float)
FSE_INSTANTIATE_CONTACT_REGION(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
