#include "fcl_glue/vertex_traversal.h"

#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>

#include <algorithm>
#include <limits>
#include <unordered_set>

#include "batch/batch_kernel.h"
#include "fcl_superellipsoid/batch_distance.h"
#include "fcl_superellipsoid/diagnostics.h"
#include "fcl_superellipsoid/point_distance.h"
#include "shape/nested_norm.h"
#include "solvers/exact_rules.h"

namespace fcl_superellipsoid {

VertexTraversalStats& vertexTraversalStats() {
  thread_local VertexTraversalStats stats;
  return stats;
}

namespace detail {
namespace {

/// A box swept by a sphere, in the model's frame M: what every BV type is bounded as.
template <typename S>
struct SweptBox {
  Vector3<S> centre;
  fcl::Matrix3<S> axes;  // columns
  Vector3<S> half_extents;
  S radius = 0;
};

template <typename S>
SweptBox<S> sweptBox(const fcl::AABB<S>& bv) {
  return {bv.center(), fcl::Matrix3<S>::Identity(), S(0.5) * (bv.max_ - bv.min_), S(0)};
}
template <typename S>
SweptBox<S> sweptBox(const fcl::OBB<S>& bv) {
  return {bv.To, bv.axis, bv.extent, S(0)};
}
template <typename S>
SweptBox<S> sweptBox(const fcl::RSS<S>& bv) {
  return {bv.center(), bv.axis, Vector3<S>(S(0.5) * bv.l[0], S(0.5) * bv.l[1], S(0)), bv.r};
}
template <typename S>
SweptBox<S> sweptBox(const fcl::kIOS<S>& bv) {
  return sweptBox(bv.obb);
}
template <typename S>
SweptBox<S> sweptBox(const fcl::OBBRSS<S>& bv) {
  return sweptBox(bv.obb);
}
/// A k-DOP's first three slab pairs are the x, y, z ones: its bounding box.
template <typename S, std::size_t N>
SweptBox<S> sweptBox(const fcl::KDOP<S, N>& bv) {
  const Vector3<S> lo(bv.dist(0), bv.dist(1), bv.dist(2));
  const Vector3<S> hi(bv.dist(N / 2), bv.dist(N / 2 + 1), bv.dist(N / 2 + 2));
  return {S(0.5) * (lo + hi), fcl::Matrix3<S>::Identity(), S(0.5) * (hi - lo), S(0)};
}

/// Subtrees with at most this many primitives are descended without bounding their BVs.
constexpr int kUnboundedPrimitives = 16;

/// A distance query solves its first this many survivors together, then twice as many, ….
constexpr std::size_t kFirstSolveBatch = 8;

template <typename BV>
class VertexTraversal {
 public:
  using S = typename BV::S;

  VertexTraversal(const fcl::BVHModel<BV>& model, const fcl::Transform3<S>& X_WM,
                  const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS)
      : model_(model),
        shape_(shape),
        X_WM_(X_WM),
        X_WS_(X_WS),
        X_SM_(X_WS.inverse(Eigen::Isometry) * X_WM),
        support_(NestedNorm<S>::support(shape)),
        gauge_(NestedNorm<S>::gauge(shape)),
        options_(shape.queryOptions()),
        stats_(vertexTraversalStats()) {
    const fcl::Transform3<S> X_MS = X_SM_.inverse(Eigen::Isometry);
    centre_M_ = X_MS.translation();
    R_MS_ = X_MS.linear();
  }

  /// The vertex of least signed distance. The traversal keeps the least cheap upper bound seen
  /// so far and prunes every BV and vertex whose lower bound cannot beat it; the survivors are
  /// solved by the batched queries, and the least answer wins (ties: lower index). With the
  /// Exact method the survivors are solved in order of their lower bounds, in batches that
  /// double (kFirstSolveBatch first), and a survivor whose lower bound exceeds the best answer
  /// so far by more than the solver's accuracy (twice exact_rules::absoluteTolerance) is not
  /// solved: a solved distance is a far tighter bound than the cheap upper ones, and the
  /// survivors of a penetrating cloud lie deep inside, where each solve costs most. Other
  /// methods are approximate, so every survivor is solved, as the brute force would.
  VertexHit<S> nearest(bool stop_at_penetration) {
    stop_at_penetration_ = stop_at_penetration;
    if (model_.getNumBVs() > 0) descendForDistance(0);
    if (penetrator_ >= 0) return solveOne(penetrator_);
    std::vector<Candidate> open;
    for (const Candidate& c : candidates_) {
      if (c.lower <= best_upper_) open.push_back(c);
    }
    VertexHit<S> best;
    auto keep = [&best](const VertexHit<S>& h) {
      if (best.vertex < 0 || h.distance < best.distance ||
          (h.distance == best.distance && h.vertex < best.vertex)) {
        best = h;
      }
    };
    if (options_.method != DistanceMethod::kExact) {
      std::vector<int> survivors;
      for (const Candidate& c : open) survivors.push_back(c.vertex);
      for (const VertexHit<S>& h : solveAll(survivors)) keep(h);
      return best;
    }
    std::sort(open.begin(), open.end(), [](const Candidate& a, const Candidate& b) {
      return a.lower < b.lower || (a.lower == b.lower && a.vertex < b.vertex);
    });
    std::size_t next = 0, batch = kFirstSolveBatch;
    std::vector<int> group;
    while (next < open.size()) {
      group.clear();
      for (; next < open.size() && group.size() < batch; ++next) {
        const Candidate& c = open[next];
        const S accuracy =
            S(2) * exact_rules::absoluteTolerance(options_.tolerance, shape_.size(), c.norm);
        if (best.vertex >= 0 && c.lower > best.distance + accuracy) continue;
        group.push_back(c.vertex);
      }
      for (const VertexHit<S>& h : solveAll(group)) keep(h);
      batch *= 2;
    }
    return best;
  }

  /// The penetrating vertices, the deepest max_count first. With depths, every vertex strictly
  /// inside is found by the traversal and then solved together by the batched queries.
  std::vector<VertexHit<S>> penetrating(std::size_t max_count, bool with_depth) {
    max_count_ = max_count;
    with_depth_ = with_depth;
    if (model_.getNumBVs() > 0 && max_count > 0) descendForCollision(0);
    if (!with_depth_) return hits_;
    std::vector<VertexHit<S>> hits;
    for (const VertexHit<S>& h : solveAll(inside_)) {
      if (h.distance < S(0)) hits.push_back(h);
    }
    // Sorted by (depth, vertex) keys, then gathered: a hit is several times a key's size.
    std::vector<std::pair<S, int>> keys(hits.size());
    for (std::size_t k = 0; k < hits.size(); ++k) keys[k] = {hits[k].distance, int(k)};
    const std::size_t keep = std::min(max_count_, hits.size());
    const auto deeper = [&hits](const std::pair<S, int>& a, const std::pair<S, int>& b) {
      return a.first < b.first ||
             (a.first == b.first && hits[a.second].vertex < hits[b.second].vertex);
    };
    if (keep == hits.size()) {
      std::sort(keys.begin(), keys.end(), deeper);  // partial_sort would heap-sort them all
    } else {
      std::partial_sort(keys.begin(), keys.begin() + keep, keys.end(), deeper);
    }
    std::vector<VertexHit<S>> deepest(keep);
    for (std::size_t k = 0; k < keep; ++k) deepest[k] = hits[keys[k].second];
    return deepest;
  }

 private:
  /// Lower bound on the signed distance of any vertex inside bv (comment in the header). It may
  /// stop as soon as the bound exceeds `cutoff` (the caller prunes the BV then): the shape's
  /// own axes first, which need no support-function evaluation.
  S lowerBound(const BV& bv, S cutoff) {
    ++stats_.bv_tests;
    const SweptBox<S> box = sweptBox(bv);
    const Vector3<S> d = centre_M_ - box.centre;
    auto gap = [&](const Vector3<S>& u, S shape_half_width, S box_half_width) {
      return std::abs(u.dot(d)) - shape_half_width - box_half_width - box.radius;
    };
    auto boxHalfWidth = [&](const Vector3<S>& u) {
      return (box.axes.transpose() * u).cwiseAbs().dot(box.half_extents);
    };
    auto shapeHalfWidth = [&](const Vector3<S>& u) {
      return support_.value((R_MS_.transpose() * u).cwiseAbs());
    };
    S best = -std::numeric_limits<S>::infinity();
    for (int i = 0; i < 3; ++i) {
      const Vector3<S> v = R_MS_.col(i);
      best = std::max(best, gap(v, shape_.radii()[i], boxHalfWidth(v)));
    }
    if (best > cutoff) return best;
    for (int i = 0; i < 3; ++i) {
      const Vector3<S> u = box.axes.col(i);
      best = std::max(best, gap(u, shapeHalfWidth(u), box.half_extents[i]));
      if (best > cutoff) return best;
    }
    const S n = d.norm();
    if (n > S(0)) {
      const Vector3<S> u = d / n;
      best = std::max(best, gap(u, shapeHalfWidth(u), boxHalfWidth(u)));
    }
    return best > S(0) ? best : -shape_.radii().minCoeff();
  }

  /// lowerBound of a node's BV; −infinity, without a test, for a node with at most
  /// kUnboundedPrimitives primitives: bounding its few vertices one by one (one gauge
  /// evaluation each) costs less than bounding its BVs (support-function evaluations).
  S boundOf(int node, S cutoff) {
    const fcl::BVNode<BV>& n = model_.getBV(node);
    if (n.num_primitives <= kUnboundedPrimitives) return -std::numeric_limits<S>::infinity();
    return lowerBound(n.bv, cutoff);
  }

  /// The vertices of the subtree at `root`, breadth first: each level's nodes, and then the
  /// vertices, are prefetched together. A small subtree's nodes are scattered over a large
  /// model, and its vertices over the vertex array (a point cloud's are in no spatial order), so
  /// visiting them one at a time waited on a cache miss for each: that was most of the
  /// traversal's time on a 1e6-vertex cloud (docs/design.md → "The BVH traversal"). The
  /// returned buffer is reused by the next call.
  const std::vector<int>& gatherSubtree(int root) {
    subtree_.clear();
    level_.assign(1, root);
    while (!level_.empty()) {
      next_level_.clear();
      for (const int node : level_) {
        const fcl::BVNode<BV>& n = model_.getBV(node);
        if (n.isLeaf()) {
          forEachVertex(n, [this](int v) {
            __builtin_prefetch(&model_.vertices[v]);
            subtree_.push_back(v);
          });
          continue;
        }
        for (const int child : {n.leftChild(), n.rightChild()}) {
          __builtin_prefetch(&model_.getBV(child));
          next_level_.push_back(child);
        }
      }
      level_.swap(next_level_);
    }
    return subtree_;
  }

  /// Calls f(vertex index) for the vertices of a leaf's primitive.
  template <typename F>
  void forEachVertex(const fcl::BVNode<BV>& leaf, F&& f) {
    const int id = leaf.primitiveId();
    if (model_.getModelType() == fcl::BVH_MODEL_POINTCLOUD || model_.num_tris == 0) {
      f(id);
      return;
    }
    const fcl::Triangle& t = model_.tri_indices[id];
    for (int k = 0; k < 3; ++k) {
      const int v = static_cast<int>(t[k]);
      if (seen_.insert(v).second) f(v);  // a vertex shared by several triangles: once
    }
  }

  Vector3<S> inShapeFrame(int v) const { return X_SM_ * model_.vertices[v]; }

  /// The hit of vertex v from a point-distance answer in the shape's frame.
  VertexHit<S> hitOf(int v, const Vector3<S>& nearest_S, const Vector3<S>& normal_S,
                     S distance) const {
    VertexHit<S> hit;
    hit.vertex = v;
    hit.distance = distance;
    hit.point_W = X_WM_ * model_.vertices[v];
    hit.nearest_W = X_WS_ * nearest_S;
    hit.normal_W = X_WS_.linear() * normal_S;
    return hit;
  }

  VertexHit<S> solveOne(int v) {
    ++stats_.vertices_solved;
    const PointDistanceResult<S> r = pointDistance(shape_, inShapeFrame(v), options_);
    return hitOf(v, r.nearest_point, r.normal, r.distance);
  }

  /// The vertices, solved together by the batched queries (the SIMD kernel for the Exact
  /// method, threads for many vertices), with the shape's query options, in the shape's frame.
  std::vector<VertexHit<S>> solveAll(const std::vector<int>& vertices) {
    stats_.vertices_solved += vertices.size();
    Matrix3X<S> p_S(3, Eigen::Index(vertices.size()));
    for (std::size_t k = 0; k < vertices.size(); ++k) p_S.col(k) = inShapeFrame(vertices[k]);
    BatchOptions<S> options;
    options.distance = options_;
    BatchDistanceResult<S> r;
    batchDistance(shape_, fcl::Transform3<S>::Identity(), p_S, r, options);
    std::vector<VertexHit<S>> hits;
    hits.reserve(vertices.size());
    for (std::size_t k = 0; k < vertices.size(); ++k) {
      hits.push_back(hitOf(vertices[k], r.nearest_point.col(k), r.normal.col(k), r.distance[k]));
    }
    return hits;
  }

  bool done() const { return stop_at_penetration_ && penetrator_ >= 0; }

  /// Bounds of a vertex's signed distance from one evaluation of the gauge G, with
  /// a = the smallest radius and G(v) ≤ √3·‖v‖/a (each nested p-norm, p ≥ 1, is at most the
  /// 1-norm): G's triangle inequality gives depth ≥ a·(1 − G)/√3 inside and distance ≥
  /// a·(G − 1)/√3 outside; the radial projection is a surface point, so its distance bounds
  /// the depth and the distance from above; outside, the box bounds the distance from below.
  void testForDistance(int v) {
    ++stats_.vertices_bounded;
    const Vector3<S> p_S = inShapeFrame(v);
    const S g = gauge_.value(p_S.cwiseAbs());
    const S a = shape_.radii().minCoeff() / std::sqrt(S(3));
    S lower, upper;
    if (g < S(1)) {
      if (stop_at_penetration_) {
        penetrator_ = v;
        return;
      }
      // The shape lies in its bounding box, so the ray from v along an axis leaves the shape
      // before the box: the depth is at most the distance to the box's nearest face too.
      const S box_depth = (shape_.radii() - p_S.cwiseAbs()).minCoeff();
      lower = g > S(0) ? -std::min(p_S.norm() * (S(1) / g - S(1)), box_depth) : -box_depth;
      upper = -a * (S(1) - g);
    } else {
      const S box_distance = (p_S.cwiseAbs() - shape_.radii()).cwiseMax(S(0)).norm();
      lower = std::max(box_distance, a * (g - S(1)));
      upper = p_S.norm() * (S(1) - S(1) / g);
    }
    best_upper_ = std::min(best_upper_, upper);
    if (lower <= best_upper_) candidates_.push_back({v, lower, p_S.norm()});
  }

  void descendForDistance(int node) {
    if (done()) return;
    const fcl::BVNode<BV>& n = model_.getBV(node);
    if (n.num_primitives <= kUnboundedPrimitives) {  // no BV of it is bounded (boundOf)
      for (const int v : gatherSubtree(node)) {
        if (done()) return;
        testForDistance(v);
      }
      return;
    }
    int first = n.leftChild(), second = n.rightChild();
    prefetchNodes(first, second);
    S bound_first = boundOf(first, best_upper_);
    S bound_second = boundOf(second, best_upper_);
    if (bound_second < bound_first) {
      std::swap(first, second);
      std::swap(bound_first, bound_second);
    }
    // Nearer child first: its bounds let the other be culled.
    if (bound_first <= best_upper_) descendForDistance(first);
    if (bound_second <= best_upper_) descendForDistance(second);
  }

  bool full() const { return !with_depth_ && hits_.size() >= max_count_; }

  /// The vertices strictly inside, in order, until full(): their gauge G < 1, evaluated on SIMD
  /// lanes (gaugeLanes, within a few ulps of the scalar gauge). With depths, a vertex that close
  /// to the surface is solved and kept only if its solved distance is negative (penetrating());
  /// without, the lanes' gauge decides alone, as the scalar gauge did before, to a few ulps.
  void testForCollision(const std::vector<int>& vertices) {
    const std::size_t n = vertices.size();
    if (n == 0) return;
    const std::size_t padded = (n + kMaxLanes - 1) / kMaxLanes * kMaxLanes;
    for (std::vector<S>& coordinate : lane_query_) coordinate.resize(padded);
    lane_gauge_.resize(padded);
    for (std::size_t k = 0; k < n; ++k) {
      const Vector3<S> p_S = inShapeFrame(vertices[k]).cwiseAbs();
      for (int i = 0; i < 3; ++i) lane_query_[i][k] = p_S[i];
    }
    for (std::vector<S>& coordinate : lane_query_) {  // the padding repeats the last vertex
      std::fill(coordinate.begin() + std::ptrdiff_t(n), coordinate.end(), coordinate[n - 1]);
    }
    const S* const query[3] = {lane_query_[0].data(), lane_query_[1].data(), lane_query_[2].data()};
    gaugeLanes(gauge_, query, lane_gauge_.data(), padded);
    for (std::size_t k = 0; k < n; ++k) {
      if (full()) return;
      ++stats_.vertices_bounded;
      if (!(lane_gauge_[k] < S(1))) continue;  // on or outside the surface
      if (!with_depth_) {
        VertexHit<S> hit;
        hit.vertex = vertices[k];
        hits_.push_back(hit);
        continue;
      }
      inside_.push_back(vertices[k]);  // solved together after the traversal
    }
  }

  void descendForCollision(int node) {
    if (full()) return;
    const fcl::BVNode<BV>& n = model_.getBV(node);
    if (n.num_primitives <= kUnboundedPrimitives) {  // no BV of it is bounded (boundOf)
      testForCollision(gatherSubtree(node));
      return;
    }
    prefetchNodes(n.leftChild(), n.rightChild());
    for (int child : {n.leftChild(), n.rightChild()}) {
      if (boundOf(child, S(0)) < S(0)) descendForCollision(child);
    }
  }

  /// Prefetches two nodes whole (a node with its BV spans several cache lines), so that their
  /// cache misses overlap instead of following each other.
  void prefetchNodes(int a, int b) const {
    for (const int node : {a, b}) {
      const char* first = reinterpret_cast<const char*>(&model_.getBV(node));
      for (std::size_t offset = 0; offset < sizeof(fcl::BVNode<BV>); offset += 64) {
        __builtin_prefetch(first + offset);
      }
    }
  }

  const fcl::BVHModel<BV>& model_;
  const Superellipsoid<S>& shape_;
  fcl::Transform3<S> X_WM_, X_WS_, X_SM_;
  Vector3<S> centre_M_;    // the shape's centre in M
  fcl::Matrix3<S> R_MS_;   // the shape's axes in M
  NestedNorm<S> support_;  // h, in the shape's frame
  NestedNorm<S> gauge_;    // G, in the shape's frame
  DistanceOptions<S> options_;
  VertexTraversalStats& stats_;
  std::unordered_set<int> seen_;                   // triangle meshes: vertices already tested
  std::vector<int> subtree_, level_, next_level_;  // gatherSubtree's buffers
  std::vector<S> lane_query_[3], lane_gauge_;      // testForCollision's lanes
  // Distance: the least upper bound so far, the vertices that may still beat it, and with
  // stop_at_penetration the first vertex found inside.
  struct Candidate {
    int vertex;
    S lower;
    S norm;  // ‖vertex‖ in the shape's frame (the solver's rounding floor grows with it)
  };
  bool stop_at_penetration_ = false;
  S best_upper_ = std::numeric_limits<S>::infinity();
  std::vector<Candidate> candidates_;
  int penetrator_ = -1;
  // Collision: the vertices found inside (with depths), or the hits without depths.
  std::size_t max_count_ = 0;
  bool with_depth_ = true;
  std::vector<int> inside_;
  std::vector<VertexHit<S>> hits_;
};

}  // namespace

template <typename BV>
VertexHit<typename BV::S> nearestVertex(const fcl::BVHModel<BV>& model,
                                        const fcl::Transform3<typename BV::S>& X_WM,
                                        const Superellipsoid<typename BV::S>& shape,
                                        const fcl::Transform3<typename BV::S>& X_WS,
                                        bool stop_at_penetration) {
  return VertexTraversal<BV>(model, X_WM, shape, X_WS).nearest(stop_at_penetration);
}

template <typename BV>
std::vector<VertexHit<typename BV::S>> penetratingVertices(
    const fcl::BVHModel<BV>& model, const fcl::Transform3<typename BV::S>& X_WM,
    const Superellipsoid<typename BV::S>& shape, const fcl::Transform3<typename BV::S>& X_WS,
    std::size_t max_count, bool with_depth) {
  return VertexTraversal<BV>(model, X_WM, shape, X_WS).penetrating(max_count, with_depth);
}

#define FSE_INSTANTIATE_TRAVERSAL(BV)                                                              \
  template VertexHit<BV::S> nearestVertex(const fcl::BVHModel<BV>&, const fcl::Transform3<BV::S>&, \
                                          const Superellipsoid<BV::S>&,                            \
                                          const fcl::Transform3<BV::S>&, bool);                    \
  template std::vector<VertexHit<BV::S>> penetratingVertices(                                      \
      const fcl::BVHModel<BV>&, const fcl::Transform3<BV::S>&, const Superellipsoid<BV::S>&,       \
      const fcl::Transform3<BV::S>&, std::size_t, bool);
using Kdop16f = fcl::KDOP<float, 16>;
using Kdop18f = fcl::KDOP<float, 18>;
using Kdop24f = fcl::KDOP<float, 24>;
using Kdop16d = fcl::KDOP<double, 16>;
using Kdop18d = fcl::KDOP<double, 18>;
using Kdop24d = fcl::KDOP<double, 24>;
#define FSE_INSTANTIATE_TRAVERSAL_ALL(S, K16, K18, K24) \
  FSE_INSTANTIATE_TRAVERSAL(fcl::AABB<S>)               \
  FSE_INSTANTIATE_TRAVERSAL(fcl::OBB<S>)                \
  FSE_INSTANTIATE_TRAVERSAL(fcl::RSS<S>)                \
  FSE_INSTANTIATE_TRAVERSAL(fcl::kIOS<S>)               \
  FSE_INSTANTIATE_TRAVERSAL(fcl::OBBRSS<S>)             \
  FSE_INSTANTIATE_TRAVERSAL(K16)                        \
  FSE_INSTANTIATE_TRAVERSAL(K18)                        \
  FSE_INSTANTIATE_TRAVERSAL(K24)
FSE_INSTANTIATE_TRAVERSAL_ALL(float, Kdop16f, Kdop18f, Kdop24f)
FSE_INSTANTIATE_TRAVERSAL_ALL(double, Kdop16d, Kdop18d, Kdop24d)

}  // namespace detail
}  // namespace fcl_superellipsoid
