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

#include "fcl_superellipsoid/diagnostics.h"
#include "fcl_superellipsoid/point_distance.h"
#include "shape/nested_norm.h"

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
        options_(shape.queryOptions()),
        stats_(vertexTraversalStats()) {
    const fcl::Transform3<S> X_MS = X_SM_.inverse(Eigen::Isometry);
    centre_M_ = X_MS.translation();
    R_MS_ = X_MS.linear();
  }

  VertexHit<S> nearest(bool stop_at_penetration) {
    stop_at_penetration_ = stop_at_penetration;
    if (model_.getNumBVs() > 0) descendForDistance(0);
    return best_;
  }

  std::vector<VertexHit<S>> penetrating(std::size_t max_count, bool with_depth) {
    max_count_ = max_count;
    with_depth_ = with_depth;
    if (model_.getNumBVs() > 0 && max_count > 0) descendForCollision(0);
    if (with_depth_) {
      const auto deeper = [](const VertexHit<S>& a, const VertexHit<S>& b) {
        return a.distance < b.distance || (a.distance == b.distance && a.vertex < b.vertex);
      };
      const std::size_t keep = std::min(max_count_, hits_.size());
      std::partial_sort(hits_.begin(), hits_.begin() + keep, hits_.end(), deeper);
      hits_.resize(keep);
    }
    return hits_;
  }

 private:
  /// Lower bound on the signed distance of any vertex inside bv (comment in the header).
  S lowerBound(const BV& bv) {
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
      const Vector3<S> u = box.axes.col(i);
      best = std::max(best, gap(u, shapeHalfWidth(u), box.half_extents[i]));
      const Vector3<S> v = R_MS_.col(i);
      best = std::max(best, gap(v, shape_.radii()[i], boxHalfWidth(v)));
    }
    const S n = d.norm();
    if (n > S(0)) {
      const Vector3<S> u = d / n;
      best = std::max(best, gap(u, shapeHalfWidth(u), boxHalfWidth(u)));
    }
    return best > S(0) ? best : -shape_.radii().minCoeff();
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

  VertexHit<S> solve(int v, const Vector3<S>& p_S) {
    ++stats_.vertices_solved;
    const PointDistanceResult<S> r = pointDistance(shape_, p_S, options_);
    VertexHit<S> hit;
    hit.vertex = v;
    hit.distance = r.distance;
    hit.point_W = X_WM_ * model_.vertices[v];
    hit.nearest_W = X_WS_ * r.nearest_point;
    hit.normal_W = X_WS_.linear() * r.normal;
    return hit;
  }

  bool done() const { return stop_at_penetration_ && best_.vertex >= 0 && best_.distance < 0; }

  void testForDistance(int v) {
    ++stats_.vertices_bounded;
    const Vector3<S> p_S = inShapeFrame(v);
    // The distance to the shape's box bounds the distance to the shape from below; inside
    // the box, no point is deeper than the smallest radius.
    const S box_distance = (p_S.cwiseAbs() - shape_.radii()).cwiseMax(S(0)).norm();
    const S bound = box_distance > S(0) ? box_distance : -shape_.radii().minCoeff();
    if (best_.vertex >= 0 && bound >= best_.distance) return;
    const VertexHit<S> hit = solve(v, p_S);
    if (best_.vertex < 0 || hit.distance < best_.distance) best_ = hit;
  }

  void descendForDistance(int node) {
    if (done()) return;
    const fcl::BVNode<BV>& n = model_.getBV(node);
    if (n.isLeaf()) {
      forEachVertex(n, [this](int v) {
        if (!done()) testForDistance(v);
      });
      return;
    }
    int first = n.leftChild(), second = n.rightChild();
    S bound_first = lowerBound(model_.getBV(first).bv);
    S bound_second = lowerBound(model_.getBV(second).bv);
    if (bound_second < bound_first) {
      std::swap(first, second);
      std::swap(bound_first, bound_second);
    }
    // Nearer child first: its answer lets the other be culled.
    if (best_.vertex < 0 || bound_first < best_.distance) descendForDistance(first);
    if (best_.vertex < 0 || bound_second < best_.distance) descendForDistance(second);
  }

  bool full() const { return !with_depth_ && hits_.size() >= max_count_; }

  void testForCollision(int v) {
    ++stats_.vertices_bounded;
    const Vector3<S> p_S = inShapeFrame(v);
    if (!(shape_.gauge(p_S) < S(1))) return;  // on or outside the surface
    if (!with_depth_) {
      VertexHit<S> hit;
      hit.vertex = v;
      hits_.push_back(hit);
      return;
    }
    const VertexHit<S> hit = solve(v, p_S);
    if (hit.distance < S(0)) hits_.push_back(hit);
  }

  void descendForCollision(int node) {
    if (full()) return;
    const fcl::BVNode<BV>& n = model_.getBV(node);
    if (n.isLeaf()) {
      forEachVertex(n, [this](int v) {
        if (!full()) testForCollision(v);
      });
      return;
    }
    for (int child : {n.leftChild(), n.rightChild()}) {
      if (lowerBound(model_.getBV(child).bv) < S(0)) descendForCollision(child);
    }
  }

  const fcl::BVHModel<BV>& model_;
  const Superellipsoid<S>& shape_;
  fcl::Transform3<S> X_WM_, X_WS_, X_SM_;
  Vector3<S> centre_M_;    // the shape's centre in M
  fcl::Matrix3<S> R_MS_;   // the shape's axes in M
  NestedNorm<S> support_;  // h, in the shape's frame
  DistanceOptions<S> options_;
  VertexTraversalStats& stats_;
  std::unordered_set<int> seen_;  // triangle meshes: vertices already tested
  bool stop_at_penetration_ = false;
  VertexHit<S> best_;
  std::size_t max_count_ = 0;
  bool with_depth_ = true;
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
