#include "narrowphase/mesh_features.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <utility>

#include "fcl_superellipsoid/point_distance.h"
#include "narrowphase/segment_search.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

/// Whether every point of the segment [p0, p1] (a point: p0 = p1) lies at least `tolerance`
/// beyond the shape: along u, the unit direction from the shape's centre c to the segment's
/// point nearest c, the segment starts at u·x0 (x0 that point) and the shape ends at its
/// support's u·s(u), a gap no point of the segment closes.
template <typename S>
bool apartBy(const RegionBody<S>& body, const Vector3<S>& c, const Vector3<S>& p0,
             const Vector3<S>& p1, S tolerance) {
  const Vector3<S> e = p1 - p0;
  const S ee = e.squaredNorm();
  const S t = ee > S(0) ? std::clamp(S((c - p0).dot(e) / ee), S(0), S(1)) : S(0);
  const Vector3<S> w = p0 + t * e - c;
  const S r = w.norm();
  if (!(r > S(0))) return false;
  const Vector3<S> u = w / r;
  return r - (body.support(u) - c).dot(u) >= tolerance;
}

/// A place of a feature: the shape's surface at `on_shape` over the mesh's at `on_other`, along
/// the feature's normal n, on the contact plane through `origin` with normal n.
template <typename S>
ManifoldPoint<S> place(const Vector3<S>& on_shape, const Vector3<S>& on_other,
                       const Vector3<S>& origin, const Vector3<S>& n) {
  ManifoldPoint<S> p;
  p.on_shape = on_shape;
  p.on_other = on_other;
  p.depth = (on_shape - on_other).dot(n);
  p.position = on_other + (origin - on_other).dot(n) * n;
  return p;
}

/// The region of one place.
template <typename S>
ContactManifold<S> pointRegion(const PointDistanceResult<S>& at, const Vector3<S>& point,
                               S tolerance) {
  ContactManifold<S> m;
  m.normal = at.normal;
  m.distance = at.distance;
  m.on_shape = at.nearest_point;
  m.on_other = point;
  m.patch_tolerance = tolerance;
  m.polygon.push_back(
      place(at.nearest_point, point, Vector3<S>(S(0.5) * (at.nearest_point + point)), at.normal));
  m.points = m.polygon;
  return m;
}

/// The region along an edge [p0, p1] whose deepest place `deepest` is inside it: the part of
/// the edge where the shape reaches within `tolerance` of it along the normal n (the depth along
/// a line across n is concave on the shape's shadow, so that part is one interval about the
/// deepest place), its ends found by bisection to within the tolerance; its places are the
/// deepest and the two ends.
template <typename S>
ContactManifold<S> edgeRegion(const RegionBody<S>& body, const SegmentMinimum<S>& deepest,
                              const Vector3<S>& p0, const Vector3<S>& p1, S tolerance,
                              const ManifoldOptions<S>& options) {
  ContactManifold<S> m = pointRegion(deepest.at, deepest.point, tolerance);
  const Vector3<S> n = m.normal;
  const Vector3<S> origin = m.points.front().position;
  const Vector3<S> e = p1 - p0;
  const S length = e.norm();
  // The shape's surface over p(t) along n, where it reaches within the tolerance of p(t).
  const auto reaches = [&](S t) -> std::optional<ManifoldPoint<S>> {
    const Vector3<S> p = p0 + t * e;
    const std::optional<S> up = body.extent(p, n);
    if (!up || !(*up >= -tolerance)) return std::nullopt;
    const ManifoldPoint<S> q = place(Vector3<S>(p + *up * n), p, origin, n);
    if (!(q.on_shape.allFinite() && q.position.allFinite())) return std::nullopt;
    return q;
  };
  std::vector<ManifoldPoint<S>> ends;
  for (const S end : {S(0), S(1)}) {
    S in = deepest.t, out = end;  // reaches at `in`; the end of the interval lies in between
    std::optional<ManifoldPoint<S>> last = reaches(end);
    if (!last) {
      for (int it = 0; it < 64 && std::abs(out - in) * length > tolerance; ++it) {
        const S mid = S(0.5) * (in + out);
        if (const std::optional<ManifoldPoint<S>> q = reaches(mid)) {
          in = mid;
          last = q;
        } else {
          out = mid;
        }
      }
    }
    if (last && (last->on_other - deepest.point).norm() > tolerance) ends.push_back(*last);
  }
  // The outline: the two ends on either side of the deepest place; the points: the deepest
  // place, then the farther end, then the nearer.
  const ManifoldPoint<S> middle = m.points.front();
  m.polygon.clear();
  if (!ends.empty()) m.polygon.push_back(ends.front());
  m.polygon.push_back(middle);
  if (ends.size() > 1) m.polygon.push_back(ends.back());
  std::sort(ends.begin(), ends.end(), [&](const ManifoldPoint<S>& a, const ManifoldPoint<S>& b) {
    return (a.on_other - deepest.point).squaredNorm() > (b.on_other - deepest.point).squaredNorm();
  });
  for (const ManifoldPoint<S>& q : ends) {
    if (int(m.points.size()) < options.max_points) m.points.push_back(q);
  }
  return m;
}

}  // namespace

template <typename S>
std::vector<FeatureRegion<S>> featureRegions(
    const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS, const RegionBody<S>& body,
    const std::vector<Facet<S>>& facets, const std::vector<EdgeOfFacet>& edges,
    const std::vector<FaceCover<S>>& cover, S tolerance, const ManifoldOptions<S>& options) {
  std::vector<FeatureRegion<S>> out;
  const Vector3<S> c = X_WS.translation();
  const S slack = S(64) * std::numeric_limits<S>::epsilon();
  // Each covering region's normal n and the shape's support height h(n) along it: a point x is
  // no deeper than h(n) − n·x (moving along n leaves the shape by then).
  std::vector<S> height(cover.size());
  for (std::size_t i = 0; i < cover.size(); ++i) {
    if (cover[i].covered) height[i] = body.support(cover[i].normal).dot(cover[i].normal);
  }
  // Whether facet i's region holds a feature whose points x lie on the facet: the region is at
  // least as deep as the feature less the tolerance, and it overlaps where the feature does (so
  // that a vertex inside the shape always makes an overlapping region). Decided by a lower bound
  // on the feature's signed distance where it can be (`bound(n, h(n))`: at least the least n·x
  // over the feature less h(n)), else by the signed distance (`distance`, computed only then).
  const auto held = [&](std::size_t i, const auto& bound_of, const auto& distance) {
    const FaceCover<S>& f = cover[i];
    if (!f.covered) return false;
    const S bound = bound_of(f.normal, height[i]);
    if (bound >= f.distance - tolerance && (f.distance < S(0) || bound >= S(0))) return true;
    const S d = distance();
    return f.distance <= d + tolerance && (f.distance < S(0) || d >= S(0));
  };
  // The facets' vertices, each with its facets (vertex, facet), in vertex order.
  std::vector<std::pair<int, int>> corners;
  for (std::size_t i = 0; i < facets.size(); ++i) {
    for (const int v : facets[i].corner) corners.emplace_back(v, int(i));
  }
  std::sort(corners.begin(), corners.end());
  const auto cornerPoint = [](const Facet<S>& f, int v) {
    for (int k = 0; k < 3; ++k) {
      if (f.corner[k] == v) return f.p[k];
    }
    return f.p[0];
  };
  // Each vertex once: its facets corners[begin, end), its point, its point query once asked
  // (shared by its edges), and whether it is a feature (within the tolerance, held by no region,
  // the signed distance falling along none of its edges).
  struct Vertex {
    int id;
    std::size_t begin, end;
    Vector3<S> point;
    std::optional<PointDistanceResult<S>> at;
    bool feature = false;
  };
  std::vector<Vertex> vertices;
  for (std::size_t k = 0; k < corners.size();) {
    std::size_t end = k + 1;
    while (end < corners.size() && corners[end].first == corners[k].first) ++end;
    vertices.push_back({corners[k].first, k, end,
                        cornerPoint(facets[std::size_t(corners[k].second)], corners[k].first),
                        std::nullopt, false});
    k = end;
  }
  const auto queried = [&](Vertex& v) -> const PointDistanceResult<S>& {
    if (!v.at) v.at = pointDistance(shape, X_WS, v.point, shape.queryOptions());
    return *v.at;
  };
  const auto vertexOf = [&](int id) -> Vertex& {
    return *std::lower_bound(vertices.begin(), vertices.end(), id,
                             [](const Vertex& x, int value) { return x.id < value; });
  };
  for (Vertex& v : vertices) {
    if (apartBy(body, c, v.point, v.point, tolerance)) continue;
    const auto distance = [&] { return queried(v).distance; };
    const auto bound = [&](const Vector3<S>& n, S h) { return n.dot(v.point) - h; };
    bool is_held = false;
    for (std::size_t j = v.begin; j < v.end && !is_held; ++j) {
      is_held = held(std::size_t(corners[j].second), bound, distance);
    }
    v.feature = !is_held && distance() < tolerance;
  }
  for (std::size_t first = 0; first < edges.size();) {
    std::size_t last = first + 1;
    while (last < edges.size() && edges[last][0] == edges[first][0] &&
           edges[last][1] == edges[first][1]) {
      ++last;
    }
    const std::size_t begin = first;
    first = last;
    Vertex& va = vertexOf(edges[begin][0]);
    Vertex& vb = vertexOf(edges[begin][1]);
    const Vector3<S> pa = va.point, pb = vb.point;
    // The signed distance is convex along the edge: it falls from an end where its derivative
    // n·e (n the normal at the end's nearest point) is negative, and its least is inside the
    // edge only where it falls from both ends.
    const bool falls_from_a = va.at && va.at->normal.dot(pb - pa) < S(0);
    const bool falls_from_b = vb.at && vb.at->normal.dot(pa - pb) < S(0);
    if (falls_from_a) va.feature = false;
    if (falls_from_b) vb.feature = false;
    // A ridge: the mesh's boundary, or one of its triangles bends away from another's side
    // towards the shape (a flat continuation or a valley is no ridge).
    const int a = va.id, b = vb.id;
    bool ridge = last - begin == 1;
    for (std::size_t i = begin; i < last && !ridge; ++i) {
      for (std::size_t j = begin; j < last && !ridge; ++j) {
        if (i == j) continue;
        const Facet<S>& f = facets[std::size_t(edges[i][2])];
        const Facet<S>& g = facets[std::size_t(edges[j][2])];
        for (int k = 0; k < 3; ++k) {
          if (g.corner[k] == a || g.corner[k] == b) continue;
          const Vector3<S> r = g.p[k] - pa;
          ridge = ridge || r.dot(f.normal) < -slack * r.norm();
        }
      }
    }
    if (!ridge || apartBy(body, c, pa, pb, tolerance)) continue;
    // The ends' derivatives along the edge, f'(0) = n_a·e < 0 < f'(1) = n_b·e (the queries
    // shared with the other edges of each end); the tangents at the ends bound f from below,
    // and where they cross is a bound on its least.
    const Vector3<S> e = pb - pa;
    const S slope_a = queried(va).normal.dot(e), slope_b = queried(vb).normal.dot(e);
    if (!(slope_a < S(0)) || !(slope_b > S(0))) continue;
    const S fa = va.at->distance, fb = vb.at->distance;
    const S floor =
        fa + slope_a * std::clamp((fb - slope_b - fa) / (slope_a - slope_b), S(0), S(1));
    if (floor >= tolerance) continue;
    std::optional<SegmentMinimum<S>> m;
    const auto distance = [&] {
      if (!m) m = nearestOnSegment(shape, X_WS, pa, pb);
      return m->at.distance;
    };
    const auto bound = [&](const Vector3<S>& n, S h) {
      return std::max(floor, std::min(n.dot(pa), n.dot(pb)) - h);
    };
    bool is_held = false;
    for (std::size_t i = begin; i < last && !is_held; ++i) {
      is_held = held(std::size_t(edges[i][2]), bound, distance);
    }
    if (is_held || !(distance() < tolerance) || !(m->t > slack && m->t < S(1) - slack)) continue;
    out.push_back({edgeRegion(body, *m, pa, pb, tolerance, options),
                   facets[std::size_t(edges[begin][2])].index});
  }
  for (const Vertex& v : vertices) {
    if (v.feature) {
      out.push_back({pointRegion(*v.at, v.point, tolerance),
                     facets[std::size_t(corners[v.begin].second)].index});
    }
  }
  return out;
}

#define FSE_INSTANTIATE_MESH_FEATURES(S)                                         \
  template std::vector<FeatureRegion<S>> featureRegions(                         \
      const Superellipsoid<S>&, const fcl::Transform3<S>&, const RegionBody<S>&, \
      const std::vector<Facet<S>>&, const std::vector<EdgeOfFacet>&,             \
      const std::vector<FaceCover<S>>&, S, const ManifoldOptions<S>&);
FSE_INSTANTIATE_MESH_FEATURES(float)
FSE_INSTANTIATE_MESH_FEATURES(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
