// Batched queries: a bounding-box cull, then the scalar solver per vertex, on TBB's threads.
//
// Determinism: the vertices are cut into fixed chunks independent of the thread count; each
// chunk's contacts are kept apart and concatenated in chunk order, so every thread count
// returns the same vector.

#include "fcl_superellipsoid/batch_distance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "fcl_superellipsoid/point_distance.h"

namespace fcl_superellipsoid {
namespace {

constexpr Eigen::Index kChunk = 1024;

template <typename S>
void checkVertices(const char* function, const Eigen::Ref<const Matrix3X<S>>& p_WV) {
  for (Eigen::Index i = 0; i < p_WV.cols(); ++i) {
    if (!p_WV.col(i).allFinite()) {
      std::ostringstream msg;
      msg << std::setprecision(17) << function << ": vertex " << i << " is not finite, got ("
          << p_WV(0, i) << ", " << p_WV(1, i) << ", " << p_WV(2, i) << ")";
      throw std::invalid_argument(msg.str());
    }
  }
}

/// Runs body(first, last) over [0, n) in kChunk pieces, threaded when it pays.
template <typename S, typename Body>
void forEachChunk(Eigen::Index n, const BatchOptions<S>& options, const Body& body) {
  const Eigen::Index chunks = (n + kChunk - 1) / kChunk;
  auto run = [&](Eigen::Index c) { body(c * kChunk, std::min(n, (c + 1) * kChunk)); };
  if (options.threads == 1 || n < options.min_parallel_vertices) {
    for (Eigen::Index c = 0; c < chunks; ++c) run(c);
    return;
  }
  auto parallel = [&] {
    tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, chunks, 1),
                      [&](const tbb::blocked_range<Eigen::Index>& r) {
                        for (Eigen::Index c = r.begin(); c != r.end(); ++c) run(c);
                      });
  };
  if (options.threads > 1) {
    tbb::task_arena arena(options.threads);
    arena.execute(parallel);
  } else {
    parallel();
  }
}

}  // namespace

template <typename S>
void batchDistance(const Superellipsoid<S>& shape,
                   const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
                   const detail::NonDeduced<Eigen::Ref<const Matrix3X<S>>>& p_WV,
                   BatchDistanceResult<S>& result,
                   const detail::NonDeduced<BatchOptions<S>>& options) {
  validateOptions(options.distance);
  checkVertices<S>("batchDistance", p_WV);
  const Eigen::Index n = p_WV.cols();
  result.distance.resize(n);
  result.nearest_point.resize(3, n);
  result.normal.resize(3, n);
  forEachChunk(n, options, [&](Eigen::Index first, Eigen::Index last) {
    for (Eigen::Index i = first; i < last; ++i) {
      const PointDistanceResult<S> r =
          pointDistance(shape, X_WS, Vector3<S>(p_WV.col(i)), options.distance);
      result.distance[i] = r.distance;
      result.nearest_point.col(i) = r.nearest_point;
      result.normal.col(i) = r.normal;
    }
  });
}

template <typename S>
std::vector<VertexContact<S>> verticesWithinMargin(
    const Superellipsoid<S>& shape, const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
    const detail::NonDeduced<Eigen::Ref<const Matrix3X<S>>>& p_WV, detail::NonDeduced<S> margin,
    const detail::NonDeduced<BatchOptions<S>>& options) {
  if (!std::isfinite(margin)) {
    std::ostringstream msg;
    msg << "verticesWithinMargin: the margin must be finite, got " << margin;
    throw std::invalid_argument(msg.str());
  }
  validateOptions(options.distance);
  checkVertices<S>("verticesWithinMargin", p_WV);
  const Eigen::Index n = p_WV.cols();
  const fcl::Transform3<S> X_SW = X_WS.inverse();
  const Vector3<S>& a = shape.radii();
  std::vector<std::vector<VertexContact<S>>> per_chunk((n + kChunk - 1) / kChunk);
  forEachChunk(n, options, [&](Eigen::Index first, Eigen::Index last) {
    std::vector<VertexContact<S>>& out = per_chunk[first / kChunk];
    for (Eigen::Index i = first; i < last; ++i) {
      // The shape lies in its box [−a, a]: the distance to the box is a lower bound.
      const Vector3<S> p_SV = X_SW * Vector3<S>(p_WV.col(i));
      const Vector3<S> outside_box = (p_SV.cwiseAbs() - a).cwiseMax(S(0));
      const S box_distance = outside_box.norm();
      if (box_distance > std::max(margin, S(0))) continue;  // (margin < 0: inside the box only)
      const PointDistanceResult<S> r = pointDistance(shape, p_SV, options.distance);
      if (r.distance > margin) continue;
      out.push_back({i, r.distance, X_WS * r.nearest_point, X_WS.linear() * r.normal});
    }
  });
  std::vector<VertexContact<S>> contacts;
  for (auto& chunk : per_chunk) contacts.insert(contacts.end(), chunk.begin(), chunk.end());
  return contacts;
}

#define FSE_INSTANTIATE_BATCH(S)                                                                 \
  template void batchDistance(const Superellipsoid<S>&, const fcl::Transform3<S>&,               \
                              const Eigen::Ref<const Matrix3X<S>>&, BatchDistanceResult<S>&,     \
                              const BatchOptions<S>&);                                           \
  template std::vector<VertexContact<S>> verticesWithinMargin(                                   \
      const Superellipsoid<S>&, const fcl::Transform3<S>&, const Eigen::Ref<const Matrix3X<S>>&, \
      S, const BatchOptions<S>&);
FSE_INSTANTIATE_BATCH(float)
FSE_INSTANTIATE_BATCH(double)

}  // namespace fcl_superellipsoid
