// Batched queries: a bounding-box cull, then the Exact method's SIMD kernel (batch_kernel.h) on
// whole vectors of vertices, with the scalar solver for the vertices it hands back (and for the
// other methods), on TBB's threads.
//
// Determinism: the vertices are cut into fixed chunks independent of the thread count; each
// chunk's contacts are kept apart and concatenated in chunk order, so every thread count
// returns the same vector.

#include "fcl_superellipsoid/batch_distance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "batch/batch_kernel.h"
#include "common/coordinate_range.h"
#include "common/invalid_argument.h"
#include "fcl_superellipsoid/point_distance.h"
#include "solvers/solvers.h"

namespace fcl_superellipsoid {
namespace {

constexpr Eigen::Index kChunk = 256;

template <typename S>
void checkVertices(const char* function, const Eigen::Ref<const Matrix3X<S>>& p_WV) {
  for (Eigen::Index i = 0; i < p_WV.cols(); ++i) {
    if (!p_WV.col(i).allFinite()) {
      detail::throwInvalidArgument(function, "vertex " + std::to_string(i) + " must be finite",
                                   p_WV.col(i));
    }
    if (!detail::withinCoordinateRange(p_WV.col(i))) {
      detail::throwInvalidArgument(
          function,
          "vertex " + std::to_string(i) + "'s coordinates must be at most " +
              detail::formatValue(detail::maxCoordinate<S>()) + " in magnitude",
          p_WV.col(i));
    }
  }
}

/// True where forEachChunk runs the chunks in order on the calling thread.
template <typename S>
bool runsSerially(Eigen::Index n, const BatchOptions<S>& options) {
  return options.threads == 1 || n < options.min_parallel_vertices;
}

/// Runs body(first, last) over [0, n) in kChunk pieces, threaded when it pays.
template <typename S, typename Body>
void forEachChunk(Eigen::Index n, const BatchOptions<S>& options, const Body& body) {
  const Eigen::Index chunks = (n + kChunk - 1) / kChunk;
  auto run = [&](Eigen::Index c) { body(c * kChunk, std::min(n, (c + 1) * kChunk)); };
  if (runsSerially(n, options)) {
    for (Eigen::Index c = 0; c < chunks; ++c) run(c);
    return;
  }
#if defined(__SANITIZE_THREAD__)
  // ThreadSanitizer cannot see TBB's synchronisation (Debian's libtbb is not instrumented), so in
  // the TSan build (scripts/test.sh --tsan) the same chunks run on std::threads, joined visibly:
  // its reports are then about this library's shared state, not TBB's scheduler.
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int threads = options.threads > 1 ? options.threads : int(cores);
  std::atomic<Eigen::Index> next{0};
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&] {
      for (Eigen::Index c = next++; c < chunks; c = next++) run(c);
    });
  }
  for (std::thread& t : pool) t.join();
  return;
#endif
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

/// One chunk's vertices as SIMD lanes (batch_kernel.h), structure of arrays.
template <typename S>
struct ChunkLanes {
  static constexpr std::size_t kCapacity = std::size_t(kChunk) + detail::kMaxLanes;
  std::size_t count = 0;
  std::array<S, kCapacity> query[3], hint[3], point[3], normal[3], error;
  std::array<std::int32_t, kCapacity> status;
  std::array<std::size_t, kCapacity> source;  // the lane of the outside pass (inside pass only)

  detail::LaneArrays<S> arrays(bool with_hints) {
    detail::LaneArrays<S> out{{query[0].data(), query[1].data(), query[2].data()},
                              {nullptr, nullptr, nullptr},
                              {point[0].data(), point[1].data(), point[2].data()},
                              {normal[0].data(), normal[1].data(), normal[2].data()},
                              error.data(),
                              status.data()};
    if (with_hints) {
      for (int c = 0; c < 3; ++c) out.hint[c] = hint[c].data();
    }
    return out;
  }
  /// Fills the lanes up to a whole vector with copies of the last one (results ignored); the
  /// hints too where they were filled.
  void pad(bool with_hints) {
    for (std::size_t k = count; k < count + detail::kMaxLanes && count > 0; ++k) {
      for (int c = 0; c < 3; ++c) {
        query[c][k] = query[c][count - 1];
        if (with_hints) hint[c][k] = hint[c][count - 1];
      }
    }
  }
};

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
        options_(options),
        simd_(options.vectorize && options.distance.method == DistanceMethod::kExact),
        problem_{detail::NestedNorm<S>::gauge(shape), detail::NestedNorm<S>::support(shape),
                 shape.radii(), detail::primalIsSmoother(shape),
                 options.distance.tolerance * shape.size(), shape.size(),
                 options.distance.max_iterations,
                 // Only the SIMD kernel reads it; its first computation per shape costs
                 // milliseconds, which a Paper or Radial batch should not pay.
                 simd_ ? shape.minRadiusOfCurvature() : S(0)} {
    validateOptions(options.distance);
    if (options.threads < 0) {
      detail::throwInvalidArgument(function, "options.threads must be >= 0", options.threads);
    }
    detail::checkPose(function, "X_WS", X_WS);
    checkVertices<S>(function, p_WV);
    if (options.warm_start_W != nullptr && options.warm_start_W->cols() != p_WV.cols()) {
      detail::throwInvalidArgument(function,
                                   "the warm start must have one column per vertex (" +
                                       std::to_string(p_WV.cols()) + " columns)",
                                   options.warm_start_W->cols());
    }
  }

  /// Solves the vertices [first, last) that `keep(p_SV)` accepts and calls emit(i, result) for
  /// each, in index order (nearest point and normal in the world frame). With the SIMD kernel
  /// for the Exact method, else one scalar query per vertex.
  template <typename Keep, typename Emit>
  void solveChunk(Eigen::Index first, Eigen::Index last, const Keep& keep, const Emit& emit) {
    if (!simd_) {
      std::size_t solved = 0;
      for (Eigen::Index i = first; i < last; ++i) {
        const Vector3<S> p_SV = inShapeFrame(i);
        if (!keep(p_SV)) continue;
        emit(i, solve(i, p_SV));
        ++solved;
      }
      count(std::size_t(last - first) - solved, 0, solved);
      return;
    }
    ChunkLanes<S> lanes;
    std::size_t own_answer = 0;  // far or near-centre vertices: the scalar path
    std::array<Eigen::Index, kChunk> vertex;
    std::array<Vector3<S>, kChunk> p_SV;
    for (Eigen::Index i = first; i < last; ++i) {
      const std::size_t k = lanes.count;
      p_SV[k] = inShapeFrame(i);
      if (!keep(p_SV[k])) continue;
      // Far away, squares may overflow in the kernel; near the centre, subnormal coordinates
      // lose their direction: both have their own answer in the scalar path.
      if (detail::isFarQuery(shape_, p_SV[k]) || detail::isNearCentreQuery(shape_, p_SV[k])) {
        emit(i, solve(i, p_SV[k]));
        ++own_answer;
        continue;
      }
      vertex[k] = i;
      for (int c = 0; c < 3; ++c) lanes.query[c][k] = std::abs(p_SV[k][c]);
      if (options_.warm_start_W != nullptr) {
        const Vector3<S> hint = X_SW_ * options_.warm_start_W->col(i);
        for (int c = 0; c < 3; ++c) lanes.hint[c][k] = std::abs(hint[c]);
      }
      ++lanes.count;
    }
    const std::size_t culled = std::size_t(last - first) - lanes.count - own_answer;
    if (lanes.count == 0) return count(culled, 0, own_answer);
    const bool with_hints = options_.warm_start_W != nullptr;
    lanes.pad(with_hints);
    detail::solveLanes(problem_, lanes.arrays(with_hints), lanes.count, false);

    // The vertices found inside, gathered into whole vectors for the inside pass.
    ChunkLanes<S> inside;
    for (std::size_t k = 0; k < lanes.count; ++k) {
      if (lanes.status[k] != detail::kLaneInside) continue;
      for (int c = 0; c < 3; ++c) inside.query[c][inside.count] = lanes.query[c][k];
      inside.source[inside.count++] = k;
    }
    std::array<bool, kChunk> is_inside{};
    if (inside.count > 0) {
      inside.pad(false);
      detail::solveLanes(problem_, inside.arrays(false), inside.count, true);
      for (std::size_t j = 0; j < inside.count; ++j) {
        const std::size_t k = inside.source[j];
        is_inside[k] = true;
        lanes.status[k] = inside.status[j];
        for (int c = 0; c < 3; ++c) {
          lanes.point[c][k] = inside.point[c][j];
          lanes.normal[c][k] = inside.normal[c][j];
        }
      }
    }

    std::size_t handed_back = 0;
    for (std::size_t k = 0; k < lanes.count; ++k) {
      if (lanes.status[k] != detail::kLaneSolved) {
        emit(vertex[k], solve(vertex[k], p_SV[k]));
        ++handed_back;
        continue;
      }
      // Back from the first octant to the vertex's own, then to W.
      PointDistanceResult<S> r = detail::fromFirstOctant(
          p_SV[k], Vector3<S>(lanes.point[0][k], lanes.point[1][k], lanes.point[2][k]),
          Vector3<S>(lanes.normal[0][k], lanes.normal[1][k], lanes.normal[2][k]), is_inside[k]);
      r.nearest_point = X_WS_ * r.nearest_point;
      r.normal = X_WS_.linear() * r.normal;
      emit(vertex[k], r);
    }
    count(culled, lanes.count - handed_back, handed_back + own_answer);
  }

  /// Writes the counts of all chunks to BatchOptions::statistics, if set.
  void reportStatistics() const {
    if (options_.statistics == nullptr) return;
    *options_.statistics = {culled_.load(), simd_solved_.load(), scalar_solved_.load()};
  }

 private:
  /// Vertex i in the shape's frame, exactly as pointDistance(shape, X_WS, p_WV.col(i)) has it.
  Vector3<S> inShapeFrame(Eigen::Index i) const { return X_SW_ * Vector3<S>(p_WV_.col(i)); }

  /// The scalar answer for vertex i (given in the shape's frame), world frame.
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

  void count(std::size_t culled, std::size_t simd, std::size_t scalar) {
    culled_ += culled;
    simd_solved_ += simd;
    scalar_solved_ += scalar;
  }

  const Superellipsoid<S>& shape_;
  const fcl::Transform3<S> X_WS_, X_SW_;
  const Eigen::Ref<const Matrix3X<S>>& p_WV_;
  const BatchOptions<S>& options_;
  const bool simd_;
  const detail::LaneProblem<S> problem_;
  std::atomic<std::size_t> culled_{0}, simd_solved_{0}, scalar_solved_{0};  // chunks add up
};

}  // namespace

template <typename S>
void batchDistance(const Superellipsoid<S>& shape,
                   const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
                   const detail::NonDeduced<Eigen::Ref<const Matrix3X<S>>>& p_WV,
                   BatchDistanceResult<S>& result,
                   const detail::NonDeduced<BatchOptions<S>>& options) {
  VertexSolver<S> solver("batchDistance", shape, X_WS, p_WV, options);
  const Eigen::Index n = p_WV.cols();
  result.distance.resize(n);
  result.nearest_point.resize(3, n);
  result.normal.resize(3, n);
  forEachChunk(n, options, [&](Eigen::Index first, Eigen::Index last) {
    solver.solveChunk(
        first, last, [](const Vector3<S>&) { return true; },
        [&](Eigen::Index i, const PointDistanceResult<S>& r) {
          result.distance[i] = r.distance;
          result.nearest_point.col(i) = r.nearest_point;
          result.normal.col(i) = r.normal;
        });
  });
  solver.reportStatistics();
}

template <typename S>
std::vector<VertexContact<S>> verticesWithinMargin(
    const Superellipsoid<S>& shape, const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
    const detail::NonDeduced<Eigen::Ref<const Matrix3X<S>>>& p_WV, detail::NonDeduced<S> margin,
    const detail::NonDeduced<BatchOptions<S>>& options) {
  std::vector<VertexContact<S>> contacts;
  verticesWithinMargin<S>(shape, X_WS, p_WV, margin, contacts, options);
  return contacts;
}

template <typename S>
void verticesWithinMargin(const Superellipsoid<S>& shape,
                          const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
                          const detail::NonDeduced<Eigen::Ref<const Matrix3X<S>>>& p_WV,
                          detail::NonDeduced<S> margin, std::vector<VertexContact<S>>& contacts,
                          const detail::NonDeduced<BatchOptions<S>>& options) {
  if (!std::isfinite(margin)) {
    detail::throwInvalidArgument("verticesWithinMargin", "the margin must be finite", margin);
  }
  VertexSolver<S> solver("verticesWithinMargin", shape, X_WS, p_WV, options);
  const Eigen::Index n = p_WV.cols();
  const Vector3<S>& a = shape.radii();
  const S cull = std::max(margin, S(0));  // (margin < 0: inside the box only)
  // In order on this thread, contacts go straight into the caller's vector (its capacity is
  // reused); on threads, into one vector per chunk, concatenated in chunk order.
  const bool serial = runsSerially(n, options);
  std::vector<std::vector<VertexContact<S>>> per_chunk(serial ? 0 : (n + kChunk - 1) / kChunk);
  contacts.clear();
  forEachChunk(n, options, [&](Eigen::Index first, Eigen::Index last) {
    std::vector<VertexContact<S>>& out = serial ? contacts : per_chunk[first / kChunk];
    solver.solveChunk(
        first, last,
        // The shape lies in its box [−a, a]: the distance to the box is a lower bound.
        // (Its norm can overflow far away; then the largest coordinate decides.)
        [&](const Vector3<S>& p_SV) {
          const Vector3<S> gap = (p_SV.cwiseAbs() - a).cwiseMax(S(0));
          const S largest = gap.maxCoeff();
          return largest <= cull &&
                 (gap.norm() <= cull || (gap / largest).norm() * largest <= cull);
        },
        [&](Eigen::Index i, const PointDistanceResult<S>& r) {
          if (r.distance <= margin) out.push_back({i, r.distance, r.nearest_point, r.normal});
        });
  });
  solver.reportStatistics();
  if (serial) return;
  std::size_t total = 0;
  for (const auto& chunk : per_chunk) total += chunk.size();
  contacts.reserve(total);
  for (const auto& chunk : per_chunk) contacts.insert(contacts.end(), chunk.begin(), chunk.end());
}

#define FSE_INSTANTIATE_BATCH(S)                                                                 \
  template void batchDistance(const Superellipsoid<S>&, const fcl::Transform3<S>&,               \
                              const Eigen::Ref<const Matrix3X<S>>&, BatchDistanceResult<S>&,     \
                              const BatchOptions<S>&);                                           \
  template std::vector<VertexContact<S>> verticesWithinMargin(                                   \
      const Superellipsoid<S>&, const fcl::Transform3<S>&, const Eigen::Ref<const Matrix3X<S>>&, \
      S, const BatchOptions<S>&);                                                                \
  template void verticesWithinMargin(const Superellipsoid<S>&, const fcl::Transform3<S>&,        \
                                     const Eigen::Ref<const Matrix3X<S>>&, S,                    \
                                     std::vector<VertexContact<S>>&, const BatchOptions<S>&);
FSE_INSTANTIATE_BATCH(float)
FSE_INSTANTIATE_BATCH(double)

}  // namespace fcl_superellipsoid
