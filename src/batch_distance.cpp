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
#include "solvers.h"

namespace fcl_superellipsoid {
namespace {

constexpr Eigen::Index kChunk = 256;

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

/// The checks and the per-vertex solve shared by both forms.
template <typename S>
class VertexSolver {
 public:
  VertexSolver(const char* function, const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
               const Eigen::Ref<const Matrix3X<S>>& p_WV, const BatchOptions<S>& options)
      : shape_(shape),
        X_WS_(X_WS),
        X_SW_(X_WS.inverse(Eigen::Isometry)),
        p_WV_(p_WV),
        options_(options) {
    validateOptions(options.distance);
    checkVertices<S>(function, p_WV);
    if (options.warm_start_W != nullptr && options.warm_start_W->cols() != p_WV.cols()) {
      std::ostringstream msg;
      msg << function << ": the warm start has " << options.warm_start_W->cols()
          << " columns, the vertices " << p_WV.cols();
      throw std::invalid_argument(msg.str());
    }
  }

  /// Vertex i in the shape's frame, exactly as pointDistance(shape, X_WS, p_WV.col(i)) has it.
  Vector3<S> inShapeFrame(Eigen::Index i) const { return X_SW_ * Vector3<S>(p_WV_.col(i)); }

  /// The answer for vertex i (given in the shape's frame), nearest point and normal in the world.
  PointDistanceResult<S> solve(Eigen::Index i, const Vector3<S>& p_SV) const {
    PointDistanceResult<S> r =
        options_.warm_start_W == nullptr
            ? pointDistance(shape_, p_SV, options_.distance)
            : detail::pointDistanceWithHint(shape_, p_SV,
                                            Vector3<S>(X_SW_ * options_.warm_start_W->col(i)),
                                            options_.distance);
    r.nearest_point = X_WS_ * r.nearest_point;
    r.normal = X_WS_.linear() * r.normal;
    return r;
  }

 private:
  const Superellipsoid<S>& shape_;
  const fcl::Transform3<S> X_WS_, X_SW_;
  const Eigen::Ref<const Matrix3X<S>>& p_WV_;
  const BatchOptions<S>& options_;
};

}  // namespace

template <typename S>
void batchDistance(const Superellipsoid<S>& shape,
                   const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
                   const detail::NonDeduced<Eigen::Ref<const Matrix3X<S>>>& p_WV,
                   BatchDistanceResult<S>& result,
                   const detail::NonDeduced<BatchOptions<S>>& options) {
  const VertexSolver<S> solver("batchDistance", shape, X_WS, p_WV, options);
  const Eigen::Index n = p_WV.cols();
  result.distance.resize(n);
  result.nearest_point.resize(3, n);
  result.normal.resize(3, n);
  forEachChunk(n, options, [&](Eigen::Index first, Eigen::Index last) {
    for (Eigen::Index i = first; i < last; ++i) {
      const PointDistanceResult<S> r = solver.solve(i, solver.inShapeFrame(i));
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
  const VertexSolver<S> solver("verticesWithinMargin", shape, X_WS, p_WV, options);
  const Eigen::Index n = p_WV.cols();
  const Vector3<S>& a = shape.radii();
  std::vector<std::vector<VertexContact<S>>> per_chunk((n + kChunk - 1) / kChunk);
  forEachChunk(n, options, [&](Eigen::Index first, Eigen::Index last) {
    std::vector<VertexContact<S>>& out = per_chunk[first / kChunk];
    for (Eigen::Index i = first; i < last; ++i) {
      // The shape lies in its box [−a, a]: the distance to the box is a lower bound.
      const Vector3<S> p_SV = solver.inShapeFrame(i);
      const S box_distance = (p_SV.cwiseAbs() - a).cwiseMax(S(0)).norm();
      if (box_distance > std::max(margin, S(0))) continue;  // (margin < 0: inside the box only)
      const PointDistanceResult<S> r = solver.solve(i, p_SV);
      if (r.distance <= margin) out.push_back({i, r.distance, r.nearest_point, r.normal});
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
