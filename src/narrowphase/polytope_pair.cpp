#include "narrowphase/polytope_pair.h"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/triangle_p.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "narrowphase/depth_candidates.h"
#include "narrowphase/feature_newton.h"
#include "narrowphase/feature_pair.h"
#include "narrowphase/libccd_pair.h"
#include "narrowphase/segment_search.h"
#include "shape/nested_norm.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

/// An edge of a polytope, vertices i < j, and the faces it borders (the first two; front and
/// back of a flat polytope's face count as two).
struct Edge {
  int i, j;
  int faces[2] = {-1, -1};
  int face_count = 0;
};

/// An edge's normal cone ⊥ the edge: the outward directions cos θ·c1 + sin θ·c2, θ ∈ [0, angle],
/// between its two faces' normals (c1 the first's; c2 the unit direction ⊥ c1 towards the
/// second's, or, on a flat polytope, whose faces' two sides are opposite, along the face away
/// from the edge's polygon).
template <typename S>
struct EdgeArc {
  Vector3<S> c1, c2;
  S angle;
};

/// A polytope's combinatorics: faces as vertex loops (on a flat polytope the second half are the
/// first half's other sides), the edges of those loops with the faces they border, and whether
/// it is flat. A box's and a triangle's depend on nothing but which faces are degenerate or flat,
/// so the common case is built once and shared (sharedTopology) instead of per query.
struct Topology {
  std::vector<std::vector<int>> faces;
  std::vector<Edge> edges;
  bool flat = false;  // a polygon (a triangle): its faces are the two sides of one loop
};

/// A polytope in world coordinates: vertices, the faces' outward normals, and its topology.
template <typename S>
struct Polytope {
  std::vector<Vector3<S>> vertices;
  std::vector<Vector3<S>> normals;   // outward, unit, one per face
  const Topology* shared = nullptr;  // the shared topology it has, or null for
  Topology own;                      // its own
  S extent = S(0);                   // largest distance between the centroid and a vertex

  const Topology& topology() const { return shared != nullptr ? *shared : own; }
  const std::vector<std::vector<int>>& faces() const { return topology().faces; }
  const std::vector<Edge>& edges() const { return topology().edges; }
  bool flat() const { return topology().flat; }

  /// The support function h(u) = max over the vertices of u·w.
  S support(const Vector3<S>& u) const {
    S h = -std::numeric_limits<S>::infinity();
    for (const Vector3<S>& w : vertices) h = std::max(h, u.dot(w));
    return h;
  }
  /// How far x lies beyond the face planes (≤ 0 inside); for a flat polytope, beyond its plane
  /// or, in the plane, beyond its loop's edges. A polytope without a face (a segment or a point:
  /// every face degenerate) bounds nothing: infinity, so that no point counts as inside it.
  S outside(const Vector3<S>& x) const {
    const std::vector<std::vector<int>>& loops = faces();
    if (loops.empty()) return std::numeric_limits<S>::infinity();
    S beyond = -std::numeric_limits<S>::infinity();
    for (std::size_t f = 0; f < loops.size(); ++f) {
      beyond = std::max(beyond, normals[f].dot(x - vertices[loops[f][0]]));
    }
    if (flat() && !loops.empty()) {
      const std::vector<int>& loop = loops[0];
      const Vector3<S>& n = normals[0];
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const Vector3<S>& a = vertices[loop[k]];
        const Vector3<S> e = vertices[loop[(k + 1) % loop.size()]] - a;
        // The in-plane normal of the edge, pointing away from the loop's centroid side.
        Vector3<S> m = e.cross(n).normalized();
        if (m.dot(vertices[loop[(k + 2) % loop.size()]] - a) > S(0)) m = -m;
        if (m.allFinite()) beyond = std::max(beyond, m.dot(x - a));
      }
    }
    return beyond;
  }
  /// A vertex where that maximum is reached (the first).
  Vector3<S> supportPoint(const Vector3<S>& u) const {
    std::size_t best = 0;
    for (std::size_t i = 1; i < vertices.size(); ++i) {
      if (u.dot(vertices[i]) > u.dot(vertices[best])) best = i;
    }
    return vertices[best];
  }
};

/// Newell's normal of a loop (not normalised): its orientation follows the loop's.
template <typename S>
Vector3<S> loopNormal(const std::vector<Vector3<S>>& v, const std::vector<int>& loop) {
  Vector3<S> n = Vector3<S>::Zero();
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Vector3<S>& p = v[loop[k]];
    const Vector3<S>& q = v[loop[(k + 1) % loop.size()]];
    n += Vector3<S>((p[1] - q[1]) * (p[2] + q[2]), (p[2] - q[2]) * (p[0] + q[0]),
                    (p[0] - q[0]) * (p[1] + q[1]));
  }
  return n;
}

/// The centroid of p's vertices; sets p.extent.
template <typename S>
Vector3<S> centroidAndExtent(Polytope<S>& p) {
  Vector3<S> centroid = Vector3<S>::Zero();
  for (const Vector3<S>& v : p.vertices) centroid += v;
  centroid /= S(p.vertices.size());
  p.extent = S(0);
  for (const Vector3<S>& v : p.vertices) p.extent = std::max(p.extent, (v - centroid).norm());
  return centroid;
}

/// A face's unit normal: none for a degenerate loop; outward (away from the centroid), or, for
/// a flat face (the loop passes through the centroid), as the loop's orientation gives it.
template <typename S>
struct FaceNormal {
  bool degenerate = true;
  bool flat = false;
  Vector3<S> n = Vector3<S>::Zero();
};

template <typename S>
FaceNormal<S> faceNormal(const Polytope<S>& p, const std::vector<int>& loop,
                         const Vector3<S>& centroid) {
  const Vector3<S> newell = loopNormal(p.vertices, loop);
  if (!(newell.norm() > S(0)) || !newell.allFinite()) return {};
  const Vector3<S> n = newell.normalized();
  const S side = n.dot(p.vertices[loop[0]] - centroid);
  // Flat (a triangle): the face is both sides. The rounding of `side` is a few ulps of the
  // extent: in float, 1e-9 × extent alone took a triangle for a solid with one side.
  const S flat = std::max(S(1e-9), S(64) * std::numeric_limits<S>::epsilon()) * p.extent;
  if (std::abs(side) <= flat) return {false, true, n};
  return {false, false, side > 0 ? n : Vector3<S>(-n)};
}

/// Builds p's own topology from its faces' loops (a degenerate face leaves its edges only; a
/// flat face gets its other side too), with the normals and extent.
template <typename S>
void finish(Polytope<S>& p, const std::vector<std::vector<int>>& loops) {
  const Vector3<S> centroid = centroidAndExtent(p);
  Topology& t = p.own;
  p.shared = nullptr;
  p.normals.clear();
  std::vector<std::pair<int, int>> edges;    // each face's, then sorted and made unique
  std::vector<std::vector<int>> back_faces;  // the other side of a flat polytope's faces
  std::vector<Vector3<S>> back_normals;
  for (const std::vector<int>& loop : loops) {
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int i = loop[k], j = loop[(k + 1) % loop.size()];
      edges.push_back({std::min(i, j), std::max(i, j)});
    }
    const FaceNormal<S> face = faceNormal(p, loop, centroid);
    if (face.degenerate) continue;  // edges only
    t.faces.push_back(loop);
    p.normals.push_back(face.n);
    if (face.flat) {
      t.flat = true;
      back_faces.push_back(loop);
      back_normals.push_back(-face.n);
    }
  }
  t.faces.insert(t.faces.end(), back_faces.begin(), back_faces.end());
  p.normals.insert(p.normals.end(), back_normals.begin(), back_normals.end());
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (const auto& [i, j] : edges) t.edges.push_back(Edge{i, j});
  for (std::size_t f = 0; f < t.faces.size(); ++f) {
    const std::vector<int>& loop = t.faces[f];
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const std::pair<int, int> e{std::min(loop[k], loop[(k + 1) % loop.size()]),
                                  std::max(loop[k], loop[(k + 1) % loop.size()])};
      Edge& edge = t.edges[std::lower_bound(edges.begin(), edges.end(), e) - edges.begin()];
      if (edge.face_count < 2) edge.faces[edge.face_count] = int(f);
      ++edge.face_count;
    }
  }
}

/// A box's loops (vertex i is (±h0, ±h1, ±h2), bit k of i the sign of h_k) and a triangle's.
/// (Function-local statics, like the topologies below: ready whenever the first query comes,
/// even from another library's static initialisation.)
const std::vector<std::vector<int>>& loopsOf(bool box) {
  static const std::vector<std::vector<int>> box_loops = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                                          {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
  static const std::vector<std::vector<int>> triangle_loops = {{0, 1, 2}};
  return box ? box_loops : triangle_loops;
}

/// The topology finish() gives a box's or a triangle's loops where no face is degenerate and,
/// for a box, none is flat: built once, on a unit cube and a unit triangle.
const Topology& sharedTopology(bool box) {
  auto build = [](std::vector<Vector3<double>> vertices,
                  const std::vector<std::vector<int>>& loops) {
    Polytope<double> p;
    p.vertices = std::move(vertices);
    finish(p, loops);
    return p.own;
  };
  static const Topology cube = [&] {
    std::vector<Vector3<double>> v;
    for (int i = 0; i < 8; ++i)
      v.emplace_back((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    return build(v, loopsOf(true));
  }();
  static const Topology triangle =
      build({Vector3<double>(0, 0, 0), Vector3<double>(1, 0, 0), Vector3<double>(0, 1, 0)},
            loopsOf(false));
  return box ? cube : triangle;
}

/// A convex's face list, its loops and the topology finish() built from them.
struct ConvexTopology {
  bool reusable = false;
  std::vector<int> list;
  int face_count = -1;
  std::vector<std::vector<int>> loops;
  Topology topology;
};

/// Normals and extent for p with the shared topology t built from the same loops: the same
/// arithmetic as finish(), so the same polytope. False where t does not fit p (a face of p is
/// degenerate, or flat where t's are not or the reverse); then finish() builds p's own.
template <typename S>
bool finishShared(Polytope<S>& p, const Topology& t, const std::vector<std::vector<int>>& loops) {
  const Vector3<S> centroid = centroidAndExtent(p);
  p.normals.clear();
  for (const std::vector<int>& loop : loops) {
    const FaceNormal<S> face = faceNormal(p, loop, centroid);
    if (face.degenerate || face.flat != t.flat) return false;
    p.normals.push_back(face.n);
  }
  if (t.flat) {
    for (std::size_t f = 0; f < loops.size(); ++f) p.normals.push_back(-p.normals[f]);
  }
  p.shared = &t;
  return true;
}

/// The normal cone of an edge of exactly two faces (the overlap's edge search; not needed when
/// the shapes are apart, so not computed with the polytope); nothing if it is not finite.
template <typename S>
std::optional<EdgeArc<S>> arcOf(const Polytope<S>& p, const Edge& edge,
                                const Vector3<S>& centroid) {
  if (edge.face_count != 2) return std::nullopt;
  const Vector3<S>& n1 = p.normals[edge.faces[0]];
  const Vector3<S>& n2 = p.normals[edge.faces[1]];
  Vector3<S> c2 = n2 - n1.dot(n2) * n1;
  if (!(c2.norm() > S(1e-6))) {  // opposite sides of a flat face: through the face's plane
    c2 = (p.vertices[edge.j] - p.vertices[edge.i]).cross(n1);
    if (c2.dot(p.vertices[edge.i] - centroid) < S(0)) c2 = -c2;
  }
  c2.stableNormalize();
  const S angle = std::atan2(std::max(S(0), c2.dot(n2)), n1.dot(n2));
  if (!c2.allFinite() || !std::isfinite(angle)) return std::nullopt;
  return EdgeArc<S>{n1, c2, angle};
}

/// A box's vertices in world coordinates, with the box's topology.
template <typename S>
Polytope<S> polytopeOf(const fcl::Box<S>& box, const fcl::Transform3<S>& X) {
  Polytope<S> p;
  const Vector3<S> h = box.side / 2;
  p.vertices.reserve(8);
  for (int i = 0; i < 8; ++i) {
    p.vertices.push_back(
        X * Vector3<S>((i & 1) ? h[0] : -h[0], (i & 2) ? h[1] : -h[1], (i & 4) ? h[2] : -h[2]));
  }
  if (!finishShared(p, sharedTopology(true), loopsOf(true))) finish(p, loopsOf(true));
  return p;
}

/// A convex's vertices in world coordinates, with its topology.
template <typename S>
Polytope<S> polytopeOf(const fcl::Convex<S>& convex, const fcl::Transform3<S>& X) {
  Polytope<S> p;
  for (const Vector3<S>& v : convex.getVertices()) p.vertices.push_back(X * v);
  // The last convex's topology, per thread: a simulation asks about the same convex shapes
  // again and again, and building the edges costs more than the query's support points. It
  // is reused where the face list is the same, finish() left every face in, and finishShared
  // finds it fits these vertices (no face degenerate, the same flatness).
  thread_local ConvexTopology cache;
  const std::vector<int>& list = convex.getFaces();
  const bool same =
      cache.reusable && cache.face_count == convex.getFaceCount() && cache.list == list;
  if (!same || !finishShared(p, cache.topology, cache.loops)) {
    std::vector<std::vector<int>> loops;
    for (std::size_t k = 0, f = 0;
         f < static_cast<std::size_t>(convex.getFaceCount()) && k < list.size(); ++f) {
      const int n = list[k];
      loops.emplace_back(list.begin() + k + 1, list.begin() + k + 1 + n);
      k += n + 1;
    }
    finish(p, loops);
    cache.reusable = p.own.faces.size() == loops.size() * (p.own.flat ? 2 : 1);
    if (cache.reusable) {
      cache.list = list;
      cache.face_count = convex.getFaceCount();
      cache.loops = std::move(loops);
      cache.topology = p.own;
    }
  }
  return p;
}

/// A triangle's vertices in world coordinates, with a flat polytope's topology.
template <typename S>
Polytope<S> polytopeOf(const fcl::TriangleP<S>& t, const fcl::Transform3<S>& X) {
  Polytope<S> p;
  p.vertices = {X * t.a, X * t.b, X * t.c};
  if (!finishShared(p, sharedTopology(false), loopsOf(false))) finish(p, loopsOf(false));
  return p;
}

/// Whether x (on the face's plane) lies inside the face's loop.
template <typename S>
bool insideFace(const Polytope<S>& p, const std::vector<int>& loop, const Vector3<S>& x) {
  const Vector3<S> n = loopNormal(p.vertices, loop);
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Vector3<S>& a = p.vertices[loop[k]];
    const Vector3<S>& b = p.vertices[loop[(k + 1) % loop.size()]];
    if ((b - a).cross(x - a).dot(n) < S(0)) return false;
  }
  return true;
}

/// The exact answer for separated shapes, if a candidate is certified.
template <typename S>
std::optional<PairHit<S>> exactSeparated(const ShapePair<S>& pair, const Polytope<S>& p,
                                         const PairHit<S>& start) {
  const Vector3<S>& normal = start.normal;
  // The polytope's vertices near its support along −normal span the candidate features.
  const S margin = S(1e-3) * p.extent;
  S best_support = -std::numeric_limits<S>::infinity();
  for (const Vector3<S>& w : p.vertices) best_support = std::max(best_support, -normal.dot(w));
  std::vector<bool> near(p.vertices.size());
  for (std::size_t i = 0; i < p.vertices.size(); ++i) {
    near[i] = -normal.dot(p.vertices[i]) >= best_support - margin;
  }
  auto support = [&p](const Vector3<S>& u) { return p.support(u); };
  Candidates<S, decltype(support)> candidates(pair, support, p.extent);
  // Faces: every vertex of the loop near the support.
  for (std::size_t f = 0; f < p.faces().size(); ++f) {
    const std::vector<int>& loop = p.faces()[f];
    if (!std::all_of(loop.begin(), loop.end(), [&](int i) { return near[i]; })) continue;
    const Vector3<S>& n = p.normals[f];
    const Vector3<S> a = shapeSupport(pair, Vector3<S>(-n));
    const S d = n.dot(a) - n.dot(p.vertices[loop[0]]);
    const Vector3<S> b = a - d * n;
    if (insideFace(p, loop, b) && candidates.offer({d, b, a, Vector3<S>(-n), -1}))
      return candidates.certified();
  }
  // Edges with both ends near: Newton on the shape's support function (feature_newton.h) from
  // the start's normal, and point queries along the edge where that is not certified.
  for (const Edge& edge : p.edges()) {
    if (!near[edge.i] || !near[edge.j]) continue;
    const Vector3<S>& a = p.vertices[edge.i];
    const Vector3<S>& b = p.vertices[edge.j];
    const std::optional<PairHit<S>> hit = segmentApart(*pair.shape, *pair.X_WS, a, b, normal);
    if (hit && candidates.offer(*hit)) return candidates.certified();
    const SegmentMinimum<S> m = nearestOnSegment(*pair.shape, *pair.X_WS, a, b);
    if (candidates.offer({m.at.distance, m.point, m.at.nearest_point, m.at.normal, -1}))
      return candidates.certified();
  }
  // Vertices: the point solver, warm-started at the start's witness.
  for (std::size_t i = 0; i < p.vertices.size(); ++i) {
    if (!near[i]) continue;
    const std::optional<PairHit<S>> hit =
        pointApart(*pair.shape, *pair.X_WS, p.vertices[i], start.on_shape);
    if (hit && candidates.offer(*hit)) return candidates.certified();
  }
  return candidates.certified();
}

/// The exact answer for separated shapes from the features at the polytope's vertex of least
/// gauge (the one the shape's own scaling puts nearest), tried before any GJK: the faces at that
/// vertex (the shape's support point along −n projected into the face), the vertex itself (the
/// point solver, cold), the edges at it (Newton on the support function from the vertex's
/// normal). Nothing unless one is certified; nothing more is tried once the shapes are seen to
/// overlap (that vertex inside the shape, or the shape's support point inside the polytope).
/// Where the contact is a face, that vertex is one of its vertices whenever the gauge orders the
/// vertices as the distance does (the others lie behind the face's plane); a miss costs the
/// features tried, then GJK starts as before (docs/math.md → "Shape pairs").
template <typename S>
std::optional<PairHit<S>> nearestVertexFeatures(const ShapePair<S>& pair, const Polytope<S>& p) {
  const fcl::Transform3<S> X_SW = pair.X_WS->inverse(Eigen::Isometry);
  const NestedNorm<S> gauge = NestedNorm<S>::gauge(*pair.shape);
  std::size_t nearest = 0;
  S least = std::numeric_limits<S>::infinity();
  for (std::size_t i = 0; i < p.vertices.size(); ++i) {
    const Vector3<S> u = Vector3<S>(X_SW * p.vertices[i]).cwiseAbs().cwiseProduct(gauge.scale);
    const S g = u.isZero() ? S(0) : gauge.levels(u).norm;  // the gauge, without pow()
    if (g < least) {
      least = g;
      nearest = i;
    }
  }
  if (!(least > S(1)) || !std::isfinite(least)) return std::nullopt;
  const int k = int(nearest);
  const Vector3<S>& w = p.vertices[nearest];
  auto support = [&p](const Vector3<S>& u) { return p.support(u); };
  Candidates<S, decltype(support)> candidates(pair, support, p.extent);
  for (std::size_t f = 0; f < p.faces().size(); ++f) {
    const std::vector<int>& loop = p.faces()[f];
    if (std::find(loop.begin(), loop.end(), k) == loop.end()) continue;
    const Vector3<S>& n = p.normals[f];
    const Vector3<S> a = shapeSupport(pair, Vector3<S>(-n));
    if (p.outside(a) <= S(0)) return std::nullopt;  // a point of the shape inside: overlapping
    const S d = n.dot(a - w);
    const Vector3<S> b = a - d * n;
    if (insideFace(p, loop, b) && candidates.offer({d, b, a, Vector3<S>(-n), -1}))
      return candidates.certified();
  }
  const std::optional<PairHit<S>> vertex = pointApart(*pair.shape, *pair.X_WS, w, noHint<S>());
  if (!vertex) return std::nullopt;
  if (candidates.offer(*vertex)) return candidates.certified();
  for (const Edge& edge : p.edges()) {
    if (edge.i != k && edge.j != k) continue;
    // The distance is convex along the edge: nearer than the vertex only if it falls from the
    // vertex into the edge, and then its minimum is inside the edge or at the other end (left
    // to GJK's start below).
    const Vector3<S>& other_end = p.vertices[edge.i == k ? edge.j : edge.i];
    if (!(vertex->normal.dot(other_end - w) < S(0))) continue;
    const std::optional<PairHit<S>> hit = segmentInteriorApart(
        *pair.shape, *pair.X_WS, p.vertices[edge.i], p.vertices[edge.j], vertex->normal);
    if (hit && candidates.offer(*hit)) return candidates.certified();
  }
  return candidates.certified();
}

/// The radius of a ball about the superellipsoid's centre that it holds: its exponents are at
/// most 2, so it holds the octahedron of its axes' ends, |x|/a + |y|/b + |z|/c ≤ 1, whose inscribed
/// radius is 1/|(1/a, 1/b, 1/c)|.
template <typename S>
S inscribedRadius(const Superellipsoid<S>& shape) {
  return S(1) / shape.radii().cwiseInverse().norm();
}

/// The least of v·d over an edge's arc of directions v(θ) = −cos θ·c1 − sin θ·c2, θ ∈ [0, angle]:
/// −(p cos θ + q sin θ) with p = c1·d, q = c2·d, least at an end or where θ = atan2(q, p).
template <typename S>
S arcLowerBound(const EdgeArc<S>& arc, const Vector3<S>& d) {
  const S p = arc.c1.dot(d), q = arc.c2.dot(d);
  S low = std::min(-p, -(std::cos(arc.angle) * p + std::sin(arc.angle) * q));
  const S peak = std::atan2(q, p);
  if (peak >= S(0) && peak <= arc.angle) low = std::min(low, -std::hypot(p, q));
  return low;
}

/// `overlap`'s candidates that need no start, the faces' normals (in `depth`): the best if the
/// balls certify it (rolling_certificate.h).
template <typename S, typename Depth>
std::optional<PairHit<S>> faceNormals(const ShapePair<S>& pair, const Polytope<S>& p,
                                      Depth& depth) {
  for (const Vector3<S>& n : p.normals) depth.offerDirection(Vector3<S>(-n));
  auto outside = [&p](const Vector3<S>& x) { return p.outside(x); };
  if (depth.certified(outside, overlapTolerance(*pair.shape, p.extent))) return depth.best();
  return std::nullopt;
}

/// The overlap's depth: the least F over the faces' normals, the vertices' escape directions and
/// descents, the edges' arcs and MPR's normal (depth_candidates.h). These include every feature's
/// own minimum, so no pattern search follows (docs/math.md).
/// Here the rest, from libccd's start (faceNormals' candidates are in `depth`).
template <typename S, typename Depth>
PairHit<S> overlap(const ShapePair<S>& pair, const Polytope<S>& p, const PairHit<S>& start,
                   Depth& depth) {
  depth.offerDirection(start.normal);
  // Where the superellipsoid's balls certify the best so far (rolling_certificate.h), the rest
  // is not needed: after the faces (faceNormals), MPR's normal, the vertices' point queries,
  // each descent and each edge.
  const S tolerance = overlapTolerance(*pair.shape, p.extent);
  auto outside = [&p](const Vector3<S>& x) { return p.outside(x); };
  if (depth.certified(outside, tolerance)) return depth.best();
  Vector3<S> centroid = Vector3<S>::Zero();
  for (const Vector3<S>& w : p.vertices) centroid += w / S(p.vertices.size());
  // A vertex inside the superellipsoid also descends from inside its own region (where F is its
  // h_A(v) − v·w, which can have a second local minimum there: the case the tests found).
  // Vertices outside descend only from the shape's axis directions, after the edges (below; a
  // choice, not a proof: docs/math.md).
  const auto escapes = depth.offerPoints(p.vertices);
  if (depth.certified(outside, tolerance)) return depth.best();
  // Each descent, and each edge's arc, may give a candidate the balls certify; then the rest is
  // not needed.
  const auto certified = [&] { return depth.certified(outside, tolerance); };
  for (std::size_t i = 0; i < p.vertices.size(); ++i) {
    if (!(escapes[i].distance < S(0))) continue;
    const Vector3<S>& w = p.vertices[i];
    depth.offerDescent(SupportMap<S>::ofPoint(w), Vector3<S>(centroid - w));
    if (certified()) return depth.best();
    // The other local minima of h_A(v) − v·w in w's region (RoundedOverlapsAgainstTheEnumerated
    // Depth found them).
    const auto supports = [&](const Vector3<S>& v) {
      return !(p.support(Vector3<S>(-v)) > -v.dot(w) + tolerance);
    };
    if (depth.offerInsidePointDescents(w, escapes[i], tolerance, supports, certified)) {
      return depth.best();
    }
  }
  const S inscribed = inscribedRadius(*pair.shape);
  for (const Edge& e : p.edges()) {
    if (const std::optional<EdgeArc<S>> arc = arcOf(p, e, centroid)) {
      // On the arc F(v) = h_A(v) − v·w0 ≥ v·(c − w0) + ρ (A holds the ball of radius ρ about its
      // centre c): an arc whose bound is not below the best F cannot improve it.
      if (arcLowerBound(*arc, Vector3<S>(pair.X_WS->translation() - p.vertices[e.i])) + inscribed >=
          -depth.best().distance)
        continue;
      depth.offerEdgeArc(p.vertices[e.i], arc->c1, arc->c2, arc->angle);
    } else {
      depth.offerEdge(p.vertices[e.i], p.vertices[e.j]);
    }
    if (depth.certified(outside, tolerance)) return depth.best();
  }
  // A vertex outside the superellipsoid: where the shape is thin or box-like, h_A(v) − v·w has a
  // local minimum near each of the shape's axis directions, and one inside w's region can be F's
  // minimum (a plate 0.1 thick through a box's centre came out 2.3e-2 × size too deep:
  // docs/hardening.md, finding 31). So f_w descends from each axis direction in w's region.
  for (std::size_t i = 0; i < p.vertices.size(); ++i) {
    if (escapes[i].distance < S(0)) continue;
    const Vector3<S>& w = p.vertices[i];
    for (int k = 0; k < 6; ++k) {
      const Vector3<S> axis = pair.X_WS->linear().col(k % 3) * (k < 3 ? S(1) : S(-1));
      if (p.support(Vector3<S>(-axis)) > -axis.dot(w) + tolerance) continue;
      depth.offerDescent(SupportMap<S>::ofPoint(w), axis);
      if (certified()) return depth.best();
    }
  }
  // In float the candidates alone can miss a triangle overlap's depth (FloatAgreesWithDouble,
  // docs/math.md); float keeps the pattern search.
  if constexpr (std::is_same_v<S, float>) return depth.refinedBest();
  return depth.best();
}

/// The polytope's stages for featurePair (feature_pair.h); `Geometry` is FCL's class of it, for
/// libccd's start.
template <typename S, typename Geometry, typename Depth>
struct PolytopeFeatures {
  const ShapePair<S>& pair;
  const Geometry& geometry;
  const Polytope<S>& p;
  Depth& depth;

  S size() const { return p.extent; }
  Vector3<S> supportPoint(const Vector3<S>& u) const { return p.supportPoint(u); }
  std::optional<PairHit<S>> separated(const PairHit<S>& start) const {
    return exactSeparated(pair, p, start);
  }
  std::optional<PairHit<S>> startFree() const { return faceNormals(pair, p, depth); }
  PairHit<S> overlap(const PairHit<S>& start) const {
    return detail::overlap(pair, p, start, depth);
  }
  std::optional<PairHit<S>> libccdStart() const { return libccdHit(pair, geometry); }
};

template <typename S, typename Geometry>
std::optional<PairHit<S>> polytopePair(const ShapePair<S>& pair, const Geometry& geometry) {
  const Polytope<S> p = polytopeOf(geometry, *pair.X_WO);
  if (const std::optional<PairHit<S>> hit = nearestVertexFeatures(pair, p)) return hit;
  auto support = [&p](const Vector3<S>& u) { return p.support(u); };
  DepthCandidates<S, decltype(support)> depth(pair, support);
  return featurePair(pair,
                     PolytopeFeatures<S, Geometry, decltype(depth)>{pair, geometry, p, depth});
}

}  // namespace

template <typename S>
std::optional<PairHit<S>> boxHit(const ShapePair<S>& pair, const fcl::Box<S>& box) {
  return polytopePair(pair, box);
}
template <typename S>
std::optional<PairHit<S>> convexHit(const ShapePair<S>& pair, const fcl::Convex<S>& convex) {
  return polytopePair(pair, convex);
}
template <typename S>
std::optional<PairHit<S>> triangleHit(const ShapePair<S>& pair, const fcl::TriangleP<S>& t) {
  return polytopePair(pair, t);
}

#define FSE_INSTANTIATE_POLYTOPE_HIT(S)                                                     \
  template std::optional<PairHit<S>> boxHit(const ShapePair<S>&, const fcl::Box<S>&);       \
  template std::optional<PairHit<S>> convexHit(const ShapePair<S>&, const fcl::Convex<S>&); \
  template std::optional<PairHit<S>> triangleHit(const ShapePair<S>&, const fcl::TriangleP<S>&);
FSE_INSTANTIATE_POLYTOPE_HIT(float)
FSE_INSTANTIATE_POLYTOPE_HIT(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
