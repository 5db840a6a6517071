#include "fcl_glue/vertex_traversal.h"

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <unordered_set>

#include "batch/batch_kernel.h"
#include "common/tasks.h"
#include "fcl_glue/bv_types.h"
#include "fcl_glue/bvh_node.h"
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

/// Subtrees with at most this many primitives are descended without bounding their BVs.
constexpr int kUnboundedPrimitives = 16;

/// The axes along which boundsOf evaluates the support function, per BV.
constexpr int kBoundAxes = 4;

/// boundsOf raises the lanes' support function by this fraction: more than their powers'
/// difference from exact ones along a unit direction (test_batch_distance.cpp checks 4 ulps).
template <typename S>
constexpr S kLaneSupportSlack = 16 * std::numeric_limits<S>::epsilon();

/// A collision query classifies the vertices of this many small subtrees together.
constexpr std::size_t kPendingSubtrees = 8;

/// A collision query with depths hands the vertices it finds inside to a task in blocks of at
/// least this many.
constexpr std::size_t kSolveBlock = 512;

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
  /// inside is found by the traversal and solved by the batched queries, in blocks handed to a
  /// task as the traversal finds them (solveInside).
  std::vector<VertexHit<S>> penetrating(std::size_t max_count, bool with_depth) {
    max_count_ = max_count;
    with_depth_ = with_depth;
    if (model_.getNumBVs() > 0 && max_count > 0) {
      descendForCollision(0);
      testPending();
    }
    if (!with_depth_) return hits_;
    solveInside(true);
    solving_.wait();
    // The penetrating ones sorted by (depth, vertex) keys; hits are made only for those kept.
    std::vector<std::pair<S, int>> keys;  // (distance, index in inside_)
    for (const std::unique_ptr<SolveBlock>& block : blocks_) {
      const auto& distance = block->answer.distance;
      for (Eigen::Index k = 0; k < distance.size(); ++k) {
        if (distance[k] < S(0)) keys.emplace_back(distance[k], int(block->first + std::size_t(k)));
      }
    }
    const std::size_t keep = std::min(max_count_, keys.size());
    const auto deeper = [this](const std::pair<S, int>& a, const std::pair<S, int>& b) {
      return a.first < b.first || (a.first == b.first && inside_[a.second] < inside_[b.second]);
    };
    if (keep == keys.size()) {
      // Sorting on one thread is a noticeable part of a query with many contacts.
      parallelSort(keys.begin(), keys.end(), deeper);
    } else {
      std::partial_sort(keys.begin(), keys.begin() + std::ptrdiff_t(keep), keys.end(), deeper);
    }
    std::vector<VertexHit<S>> deepest;
    deepest.reserve(keep);
    for (std::size_t i = 0; i < keep; ++i) deepest.push_back(insideHit(keys[i].second));
    return deepest;
  }

 private:
  /// Lower bounds on the signed distance of any vertex inside the BVs of two nodes (comment in
  /// the header); −infinity, without a test, for a node with at most kUnboundedPrimitives
  /// primitives: bounding its few vertices one by one (one gauge evaluation each) costs less
  /// than bounding its BV. The support function along both BVs' four axes (their box's three
  /// and the line of the centres) is evaluated on SIMD lanes at once (normOnLanes with h's
  /// nested norm), and raised by kLaneSupportSlack, so that it bounds h from above although
  /// the lanes' powers may differ from exact ones by a few ulps: a bound stays a lower bound.
  std::array<S, 2> boundsOf(int first, int second) {
    const int nodes[2] = {first, second};
    std::array<S, 2> bounds;
    SweptBox<S> boxes[2];
    Vector3<S> offsets[2];  // the shape's centre from the box's, in M
    bool bounded[2];
    resizeLanes(2 * kBoundAxes);
    std::size_t lanes = 0;
    for (int k = 0; k < 2; ++k) {
      const fcl::BVNode<BV>& n = model_.getBV(nodes[k]);
      bounded[k] = n.num_primitives > kUnboundedPrimitives;
      bounds[k] = -std::numeric_limits<S>::infinity();
      if (!bounded[k]) continue;
      ++stats_.bv_tests;
      boxes[k] = sweptBox(n.bv);
      offsets[k] = centre_M_ - boxes[k].centre;
      for (int i = 0; i < kBoundAxes; ++i) {
        const Vector3<S> w = (R_MS_.transpose() * boundAxis(boxes[k], offsets[k], i)).cwiseAbs();
        for (int c = 0; c < 3; ++c) lane_query_[c][lanes] = w[c];
        ++lanes;
      }
    }
    if (lanes == 0) return bounds;
    const std::vector<S>& h = normOnLanes(support_, lanes);
    std::size_t lane = 0;
    for (int k = 0; k < 2; ++k) {
      if (!bounded[k]) continue;
      const SweptBox<S>& box = boxes[k];
      const Vector3<S>& d = offsets[k];
      auto gap = [&](const Vector3<S>& u, S shape_half_width, S box_half_width) {
        return std::abs(u.dot(d)) - shape_half_width - box_half_width - box.radius;
      };
      S best = -std::numeric_limits<S>::infinity();
      for (int i = 0; i < 3; ++i) {  // the shape's axes: its radii are its half widths
        const Vector3<S> u = R_MS_.col(i);
        best = std::max(best, gap(u, shape_.radii()[i], boxHalfWidth(box, u)));
      }
      for (int i = 0; i < kBoundAxes; ++i) {
        const Vector3<S> u = boundAxis(box, d, i);
        const S shape_half_width = h[lane++] * (S(1) + kLaneSupportSlack<S>);
        best = std::max(best, gap(u, shape_half_width, boxHalfWidth(box, u)));
      }
      bounds[k] = std::max(best, -shape_.radii().minCoeff());  // no point is deeper than that
    }
    return bounds;
  }

  /// The box's three axes, then the unit line of the centres (the box's first axis again if
  /// the centres coincide): the axes along which a BV is bounded with the support function.
  static Vector3<S> boundAxis(const SweptBox<S>& box, const Vector3<S>& d, int i) {
    if (i < 3) return box.axes.col(i);
    const S n = d.norm();
    return n > S(0) ? Vector3<S>(d / n) : Vector3<S>(box.axes.col(0));
  }

  /// Appends the vertices of the subtree at `root` to subtree_, breadth first: each level's
  /// nodes, and then the vertices, are prefetched together. A small subtree's nodes are
  /// scattered over a large model, and its vertices over the vertex array (a point cloud's are
  /// in no spatial order), so visiting them one at a time waited on a cache miss for each: that
  /// was most of the traversal's time on a 1e6-vertex cloud (docs/design.md → "The BVH
  /// traversal"). Calling prefetchBelow(root) earlier lets the levels' misses overlap too.
  void gatherSubtree(int root) {
    level_.assign(1, root);
    while (!level_.empty()) {
      next_level_.clear();
      for (const int node : level_) {
        const fcl::BVNode<BV>& n = model_.getBV(node);
        if (isLeaf(n)) {
          forEachVertex(n, [this](int v) {
            __builtin_prefetch(&model_.vertices[v]);
            subtree_.push_back(v);
          });
          continue;
        }
        for (const int child : {leftChild(n), rightChild(n)}) {
          __builtin_prefetch(&model_.getBV(child));
          next_level_.push_back(child);
        }
      }
      level_.swap(next_level_);
    }
  }

  /// Prefetches the nodes below root before they are visited. fcl builds a tree depth first and
  /// gives each node's two children the next free pair of indices, so a subtree of P primitives
  /// (P leaves, 2P − 1 nodes) keeps the 2P − 2 nodes below its root in the indices that follow
  /// its first child: all its levels' cache misses then overlap, where the breadth-first walk
  /// alone waits for them level by level. Only where the memory is fetched depends on that
  /// layout, never what the walk finds; the range stays inside the model.
  void prefetchBelow(int root) const {
    const fcl::BVNode<BV>& n = model_.getBV(root);
    if (isLeaf(n)) return;
    const int first = leftChild(n);
    const int end = std::min(first + 2 * (n.num_primitives - 1), model_.getNumBVs());
    for (int node = first; node < end; ++node) __builtin_prefetch(&model_.getBV(node));
  }

  /// Calls f(vertex index) for the vertices of a leaf's primitive.
  template <typename F>
  void forEachVertex(const fcl::BVNode<BV>& leaf, F&& f) {
    const int id = primitiveId(leaf);
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

  /// The vertices in the shape's frame, as the batched queries take them.
  Matrix3X<S> inShapeFrame(const int* vertices, std::size_t n) const {
    Matrix3X<S> p_S(3, Eigen::Index(n));
    for (std::size_t k = 0; k < n; ++k) p_S.col(Eigen::Index(k)) = inShapeFrame(vertices[k]);
    return p_S;
  }

  /// Points in the shape's frame, solved together by the batched queries (the SIMD kernel for
  /// the Exact method, threads for many points), with the shape's query options. It only reads
  /// the traversal's state, so it may run on a task beside it.
  BatchDistanceResult<S> solveBatch(const Matrix3X<S>& p_S) const {
    BatchOptions<S> options;
    options.distance = options_;
    BatchDistanceResult<S> r;
    batchDistance(shape_, fcl::Transform3<S>::Identity(), p_S, r, options);
    return r;
  }

  /// The vertices, solved together (solveBatch), as hits.
  std::vector<VertexHit<S>> solveAll(const std::vector<int>& vertices) {
    stats_.vertices_solved += vertices.size();
    const BatchDistanceResult<S> r = solveBatch(inShapeFrame(vertices.data(), vertices.size()));
    std::vector<VertexHit<S>> hits;
    hits.reserve(vertices.size());
    for (std::size_t k = 0; k < vertices.size(); ++k) {
      const Eigen::Index i = Eigen::Index(k);
      hits.push_back(hitOf(vertices[k], r.nearest_point.col(i), r.normal.col(i), r.distance[i]));
    }
    return hits;
  }

  /// Hands the vertices found inside since the last call (inside_ from solved_inside_ on) to
  /// the batched queries as one block: once kSolveBlock of them have gathered, on a task, while
  /// the traversal goes on (it is memory-bound and single-threaded, so the solving, the larger
  /// part of a collision query, overlaps it); at the end (last), the rest on this thread.
  void solveInside(bool last) {
    const std::size_t first = solved_inside_, n = inside_.size() - first;
    if (n == 0 || (!last && n < kSolveBlock)) return;
    auto block = std::make_unique<SolveBlock>();
    block->first = first;
    block->p_S = inShapeFrame(inside_.data() + first, n);
    stats_.vertices_solved += n;
    solved_inside_ = inside_.size();
    SolveBlock* const b = block.get();
    blocks_.push_back(std::move(block));
    const auto solve = [this, b] { b->answer = solveBatch(b->p_S); };
    if (last) {
      solve();
    } else {
      solving_.run(solve);
    }
  }

  /// The hit of inside_[i], from its block's answer.
  VertexHit<S> insideHit(int i) const {
    const auto after = std::upper_bound(
        blocks_.begin(), blocks_.end(), std::size_t(i),
        [](std::size_t index, const std::unique_ptr<SolveBlock>& b) { return index < b->first; });
    const SolveBlock& b = **std::prev(after);
    const Eigen::Index k = Eigen::Index(std::size_t(i) - b.first);
    return hitOf(inside_[std::size_t(i)], b.answer.nearest_point.col(k), b.answer.normal.col(k),
                 b.answer.distance[k]);
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
    if (n.num_primitives <= kUnboundedPrimitives) {  // no BV of it is bounded (boundsOf)
      subtree_.clear();
      prefetchBelow(node);
      gatherSubtree(node);
      for (const int v : subtree_) {
        if (done()) return;
        testForDistance(v);
      }
      return;
    }
    int first = leftChild(n), second = rightChild(n);
    prefetchNodes(first, second);
    auto [bound_first, bound_second] = boundsOf(first, second);
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
    resizeLanes(n);
    for (std::size_t k = 0; k < n; ++k) {
      const Vector3<S> p_S = inShapeFrame(vertices[k]).cwiseAbs();
      for (int i = 0; i < 3; ++i) lane_query_[i][k] = p_S[i];
    }
    const std::vector<S>& gauge = normOnLanes(gauge_, n);
    for (std::size_t k = 0; k < n; ++k) {
      if (full()) return;
      ++stats_.vertices_bounded;
      if (!(gauge[k] < S(1))) continue;  // on or outside the surface
      if (!with_depth_) {
        VertexHit<S> hit;
        hit.vertex = vertices[k];
        hits_.push_back(hit);
        continue;
      }
      inside_.push_back(vertices[k]);  // solved in blocks (solveInside)
    }
  }

  void descendForCollision(int node) {
    if (full()) return;
    const fcl::BVNode<BV>& n = model_.getBV(node);
    if (n.num_primitives <= kUnboundedPrimitives) {  // no BV of it is bounded (boundsOf)
      prefetchBelow(node);
      pending_.push_back(node);
      if (pending_.size() == kPendingSubtrees) testPending();
      return;
    }
    const int first = leftChild(n), second = rightChild(n);
    prefetchNodes(first, second);
    const std::array<S, 2> bounds = boundsOf(first, second);
    if (bounds[0] < S(0)) descendForCollision(first);
    if (bounds[1] < S(0)) descendForCollision(second);
  }

  /// The pending subtrees' vertices, gathered and then classified together (testForCollision):
  /// each subtree's nodes were prefetched when it was found, so gathering one overlaps the
  /// misses of the next, and the gauge runs on full vectors of lanes.
  void testPending() {
    subtree_.clear();
    for (const int root : pending_) gatherSubtree(root);
    pending_.clear();
    testForCollision(subtree_);
    if (with_depth_) solveInside(false);
  }

  /// Room for n first-octant points in lane_query_, whole vectors of lanes.
  void resizeLanes(std::size_t n) {
    const std::size_t padded = (n + kVectorLanes<S> - 1) / kVectorLanes<S> * kVectorLanes<S>;
    for (std::vector<S>& coordinate : lane_query_) coordinate.resize(padded);
    lane_value_.resize(padded);
  }

  /// The nested norm at lane_query_'s first n points (n ≥ 1), on SIMD lanes (gaugeLanes); the
  /// padding repeats the last point. The values are in the returned buffer, reused by the next
  /// call.
  const std::vector<S>& normOnLanes(const NestedNorm<S>& norm, std::size_t n) {
    for (std::vector<S>& coordinate : lane_query_) {
      std::fill(coordinate.begin() + std::ptrdiff_t(n), coordinate.end(), coordinate[n - 1]);
    }
    const S* const query[3] = {lane_query_[0].data(), lane_query_[1].data(), lane_query_[2].data()};
    gaugeLanes(norm, query, lane_value_.data(), lane_value_.size());
    return lane_value_;
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
  std::vector<int> pending_;                       // subtrees found, not yet classified
  std::vector<S> lane_query_[3], lane_value_;      // normOnLanes's points and values
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
  // With depths: inside_ in blocks, solved on tasks (solveInside). solving_ is declared last, so
  // that it waits for its tasks before the blocks they write are destroyed.
  struct SolveBlock {
    std::size_t first = 0;  // its first vertex's index in inside_
    Matrix3X<S> p_S;
    BatchDistanceResult<S> answer;
  };
  std::size_t solved_inside_ = 0;
  std::vector<std::unique_ptr<SolveBlock>> blocks_;
  TaskGroup solving_;
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
