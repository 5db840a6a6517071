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
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "batch/batch_kernel.h"
#include "common/coordinate_range.h"
#include "common/invalid_argument.h"
#include "common/tasks.h"
#include "fcl_superellipsoid/point_distance.h"
#include "solvers/point_gradient.h"
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
  // The TSan build runs the same chunks on TaskGroup's std::threads (common/tasks.h).
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int threads = options.threads > 1 ? options.threads : int(cores);
  std::atomic<Eigen::Index> next{0};
  detail::TaskGroup pool;
  for (int t = 0; t < threads; ++t) {
    pool.run([&] {
      for (Eigen::Index c = next++; c < chunks; c = next++) run(c);
    });
  }
  pool.wait();
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
  std::array<std::size_t, kCapacity> source;  // the lane's index before swaps
  std::array<S, kCapacity> radial[detail::LaneArrays<S>::kRadialArrays];  // the radial starts
  std::array<S, kCapacity> runner_up;  // the inside pass's, where asked for

  /// The lanes from `from` on.
  detail::LaneArrays<S> arrays(bool with_hints, std::size_t from = 0, bool with_runner_up = false) {
    detail::LaneArrays<S> out{{&query[0][from], &query[1][from], &query[2][from]},
                              {nullptr, nullptr, nullptr},
                              {&point[0][from], &point[1][from], &point[2][from]},
                              {&normal[0][from], &normal[1][from], &normal[2][from]},
                              &error[from],
                              &status[from],
                              {}};
    for (int k = 0; k < detail::LaneArrays<S>::kRadialArrays; ++k) out.radial[k] = &radial[k][from];
    if (with_hints) {
      for (int c = 0; c < 3; ++c) out.hint[c] = &hint[c][from];
    }
    if (with_runner_up) out.runner_up = &runner_up[from];
    return out;
  }
  /// Exchanges the inputs of lanes a and b.
  void swap(std::size_t a, std::size_t b, bool with_hints) {
    for (int c = 0; c < 3; ++c) {
      std::swap(query[c][a], query[c][b]);
      if (with_hints) std::swap(hint[c][a], hint[c][b]);
    }
    std::swap(source[a], source[b]);
    for (auto& r : radial) std::swap(r[a], r[b]);
  }
  /// Fills the lanes up to a whole vector with copies of the last one (results ignored); the
  /// hints and the radial starts too where they were filled.
  void pad(bool with_hints, bool with_radial) {
    for (std::size_t k = count; k < count + detail::kMaxLanes && count > 0; ++k) {
      for (int c = 0; c < 3; ++c) {
        query[c][k] = query[c][count - 1];
        if (with_hints) hint[c][k] = hint[c][count - 1];
      }
      if (!with_radial) continue;
      for (auto& r : radial) r[k] = r[count - 1];
    }
  }
};

/// One vertex's answer, as VertexSolver::solveChunk emits it.
template <typename S>
struct VertexAnswer {
  PointDistanceResult<S> result;  // nearest point and normal in the world frame
  Vector3<S> p_SV;                // the vertex in the shape's frame
  Vector3<S> nearest_S;           // the nearest point in the shape's frame
  Vector3<S> normal_S;            // the normal there, in the shape's frame
  // With runner-ups (VertexSolver's `runner_ups`): the distance of the solver's runner-up
  // (solvers.h, Query::runner_up), ∞ for none; else NaN.
  S runner_up;
};

/// The checks and the per-vertex solve shared by the batched queries.
template <typename S>
class VertexSolver {
 public:
  /// With `runner_ups` (the derivatives' flag needs them), every answer comes with the
  /// runner-up of its solver: the scalar solver's, or the kernel's inside pass's over its starts
  /// (outside, the problem is convex: none).
  VertexSolver(const char* function, const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
               const Eigen::Ref<const Matrix3X<S>>& p_WV, const BatchOptions<S>& options,
               bool runner_ups = false)
      : shape_(shape),
        X_WS_(X_WS),
        X_SW_(X_WS.inverse(Eigen::Isometry)),
        p_WV_(p_WV),
        options_(options),
        simd_(options.vectorize && options.distance.method == DistanceMethod::kExact),
        runner_ups_(runner_ups),
        problem_{detail::NestedNorm<S>::gauge(shape), detail::NestedNorm<S>::support(shape),
                 shape.radii(), detail::primalIsSmoother(shape),
                 options.distance.tolerance * shape.size(), shape.size(),
                 options.distance.max_iterations,
                 // Only the SIMD kernel reads it; its first computation per shape costs
                 // milliseconds, which a Paper or Radial batch should not pay.
                 simd_ ? shape.minRadiusOfCurvature() : S(0), &shape} {
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

  /// Solves the vertices [first, last) that `keep(p_SV)` accepts and calls emit(i, answer) for
  /// each (a VertexAnswer), in index order. With the SIMD kernel for the Exact method, else one
  /// scalar query per vertex.
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
    // The kept vertices in index order; those the kernel solves have a lane, the others (far
    // away, where squares may overflow in the kernel; near the centre, where subnormal
    // coordinates lose their direction) have their own answer in the scalar path.
    ChunkLanes<S> lanes;
    std::size_t kept = 0, own_answer = 0;
    std::array<Eigen::Index, kChunk> vertex;
    std::array<Vector3<S>, kChunk> p_SV;
    std::array<std::size_t, kChunk> lane_of;
    constexpr std::size_t kOwnAnswer = ~std::size_t(0);
    for (Eigen::Index i = first; i < last; ++i) {
      const Vector3<S> p = inShapeFrame(i);
      if (!keep(p)) continue;
      vertex[kept] = i;
      p_SV[kept] = p;
      if (detail::isFarQuery(shape_, p) || detail::isNearCentreQuery(shape_, p)) {
        lane_of[kept++] = kOwnAnswer;
        ++own_answer;
        continue;
      }
      const std::size_t k = lanes.count++;
      lane_of[kept++] = k;
      lanes.source[k] = k;
      for (int c = 0; c < 3; ++c) lanes.query[c][k] = std::abs(p[c]);
      if (options_.warm_start_W != nullptr) {
        const Vector3<S> hint = X_SW_ * options_.warm_start_W->col(i);
        for (int c = 0; c < 3; ++c) lanes.hint[c][k] = std::abs(hint[c]);
      }
    }
    const std::size_t culled = std::size_t(last - first) - kept;
    std::size_t outside = 0;
    if (lanes.count > 0) {
      const bool with_hints = options_.warm_start_W != nullptr;
      lanes.pad(with_hints, false);
      // Outside vertices first, inside ones after them, so that each pass runs on whole vectors
      // of its own lanes (a vector iterates as long as its slowest lane).
      detail::solveLanes(problem_, lanes.arrays(false), lanes.count, detail::LanePass::kClassify);
      for (std::size_t k = 0; k < lanes.count; ++k) {
        if (lanes.status[k] == detail::kLaneInside) continue;
        if (k != outside) lanes.swap(k, outside, with_hints);
        ++outside;
      }
      std::array<std::size_t, kChunk> slot;  // lane → where the partition put it
      for (std::size_t k = 0; k < lanes.count; ++k) slot[lanes.source[k]] = k;
      for (std::size_t j = 0; j < kept; ++j) {
        if (lane_of[j] != kOwnAnswer) lane_of[j] = slot[lane_of[j]];
      }
      lanes.pad(with_hints, true);
      if (outside > 0) {
        detail::solveLanes(problem_, lanes.arrays(with_hints), outside, detail::LanePass::kOutside);
      }
      if (outside < lanes.count) {
        detail::solveLanes(problem_, lanes.arrays(false, outside, runner_ups_),
                           lanes.count - outside, detail::LanePass::kInside);
      }
    }

    // In index order: the kernel's answers, and the scalar solver's for the rest.
    std::size_t handed_back = 0;
    for (std::size_t j = 0; j < kept; ++j) {
      const std::size_t k = lane_of[j];
      if (k == kOwnAnswer || lanes.status[k] != detail::kLaneSolved) {
        emit(vertex[j], solve(vertex[j], p_SV[j]));
        if (k != kOwnAnswer) ++handed_back;
        continue;
      }
      // Back from the first octant to the vertex's own, then to W. (Outside, the problem is
      // convex: no runner-up.)
      const bool inside = k >= outside;
      const PointDistanceResult<S> r = detail::fromFirstOctant(
          p_SV[j], Vector3<S>(lanes.point[0][k], lanes.point[1][k], lanes.point[2][k]),
          Vector3<S>(lanes.normal[0][k], lanes.normal[1][k], lanes.normal[2][k]), inside);
      const S runner_up = !runner_ups_ ? std::numeric_limits<S>::quiet_NaN()
                          : inside     ? lanes.runner_up[k]
                                       : std::numeric_limits<S>::infinity();
      emit(vertex[j], inWorld(r, p_SV[j], runner_up));
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

  /// The scalar answer for vertex i (given in the shape's frame), as pointDistance() (or with
  /// the warm start, pointDistanceWithHint()) gives it.
  VertexAnswer<S> solve(Eigen::Index i, const Vector3<S>& p_SV) const {
    S runner_up = std::numeric_limits<S>::quiet_NaN();
    Vector3<S> hint;
    if (options_.warm_start_W != nullptr) hint = X_SW_ * options_.warm_start_W->col(i);
    const bool with_hint = options_.warm_start_W != nullptr && hint.allFinite();
    detail::validateQuery("pointDistance", p_SV, options_.distance);  // as pointDistance() does
    const PointDistanceResult<S> r =
        detail::solve(shape_, p_SV, with_hint ? &hint : nullptr, options_.distance,
                      runner_ups_ ? &runner_up : nullptr);
    return inWorld(r, p_SV, runner_up);
  }

  /// The answer r, in the shape's frame, with its nearest point and normal taken to W.
  VertexAnswer<S> inWorld(const PointDistanceResult<S>& r, const Vector3<S>& p_SV,
                          S runner_up) const {
    VertexAnswer<S> a{r, p_SV, r.nearest_point, r.normal, runner_up};
    a.result.nearest_point = X_WS_ * r.nearest_point;
    a.result.normal = X_WS_.linear() * r.normal;
    return a;
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
  const bool runner_ups_;
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
        [&](Eigen::Index i, const VertexAnswer<S>& a) {
          result.distance[i] = a.result.distance;
          result.nearest_point.col(i) = a.result.nearest_point;
          result.normal.col(i) = a.result.normal;
        });
  });
  solver.reportStatistics();
}

template <typename S>
void batchDistanceDerivatives(const Superellipsoid<S>& shape,
                              const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
                              const detail::NonDeduced<Eigen::Ref<const Matrix3X<S>>>& p_WV,
                              BatchDerivativesResult<S>& result,
                              const detail::NonDeduced<BatchOptions<S>>& options) {
  constexpr const char* kFunction = "batchDistanceDerivatives";
  VertexSolver<S> solver(kFunction, shape, X_WS, p_WV, options, true);
  if (options.distance.method != DistanceMethod::kExact) {
    detail::throwInvalidArgument(kFunction,
                                 "options.distance.method must be DistanceMethod::kExact",
                                 std::string(toString(options.distance.method)));
  }
  const Eigen::Index n = p_WV.cols();
  result.distance.resize(n);
  result.nearest_point.resize(3, n);
  result.normal.resize(3, n);
  result.d_pose.resize(6, n);
  result.d_shape.resize(5, n);
  result.differentiable.resize(n);
  // With the SIMD kernel the parameter columns come from its lanes too (shapeGradientLanes, at
  // the chunk's nearest points and normals folded into the first octant: the columns do not
  // depend on the octant), else as the single query takes them.
  const detail::NestedNorm<S> gauge = detail::NestedNorm<S>::gauge(shape);
  forEachChunk(n, options, [&](Eigen::Index first, Eigen::Index last) {
    constexpr std::size_t kCapacity = std::size_t(kChunk) + detail::kMaxLanes;
    std::array<S, kCapacity> point[3], normal[3], d_shape[5];
    std::array<Eigen::Index, kCapacity> vertex;
    std::size_t count = 0;
    solver.solveChunk(
        first, last, [](const Vector3<S>&) { return true; },
        [&](Eigen::Index i, const VertexAnswer<S>& a) {
          const PointDistanceResult<S>& r = a.result;
          result.distance[i] = r.distance;
          result.nearest_point.col(i) = r.nearest_point;
          result.normal.col(i) = r.normal;
          result.d_pose.col(i) = detail::poseGradient(r.normal, r.nearest_point);
          if (options.vectorize) {
            vertex[count] = i;
            for (int c = 0; c < 3; ++c) {
              point[c][count] = std::abs(a.nearest_S[c]);
              normal[c][count] = std::abs(a.normal_S[c]);
            }
            ++count;
          } else {
            result.d_shape.col(i) = detail::shapeGradient(shape, a.nearest_S, a.normal_S);
          }
          result.differentiable[i] =
              !detail::hasSeveralNearestPoints(shape.size(), a.p_SV, a.nearest_S, r.distance,
                                               a.runner_up, options.distance.tolerance);
        });
    if (count == 0) return;
    const std::size_t lanes = detail::kVectorLanes<S>;
    const std::size_t padded = (count + lanes - 1) / lanes * lanes;
    for (std::size_t k = count; k < padded; ++k) {
      for (int c = 0; c < 3; ++c) {
        point[c][k] = point[c][count - 1];
        normal[c][k] = normal[c][count - 1];
      }
    }
    const S* const points[3] = {point[0].data(), point[1].data(), point[2].data()};
    const S* const normals[3] = {normal[0].data(), normal[1].data(), normal[2].data()};
    S* const columns[5] = {d_shape[0].data(), d_shape[1].data(), d_shape[2].data(),
                           d_shape[3].data(), d_shape[4].data()};
    detail::shapeGradientLanes(gauge, points, normals, columns, padded);
    for (std::size_t k = 0; k < count; ++k) {
      Vector5<S> column;
      for (int j = 0; j < 5; ++j) column[j] = d_shape[j][k];
      if (!column.allFinite()) {  // not seen; the scalar logarithms handle every range
        column = detail::shapeGradient(shape, Vector3<S>(point[0][k], point[1][k], point[2][k]),
                                       Vector3<S>(normal[0][k], normal[1][k], normal[2][k]));
      }
      result.d_shape.col(vertex[k]) = column;
    }
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
        [&](Eigen::Index i, const VertexAnswer<S>& a) {
          const PointDistanceResult<S>& r = a.result;
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
  template void batchDistanceDerivatives(const Superellipsoid<S>&, const fcl::Transform3<S>&,    \
                                         const Eigen::Ref<const Matrix3X<S>>&,                   \
                                         BatchDerivativesResult<S>&, const BatchOptions<S>&);    \
  template std::vector<VertexContact<S>> verticesWithinMargin(                                   \
      const Superellipsoid<S>&, const fcl::Transform3<S>&, const Eigen::Ref<const Matrix3X<S>>&, \
      S, const BatchOptions<S>&);                                                                \
  template void verticesWithinMargin(const Superellipsoid<S>&, const fcl::Transform3<S>&,        \
                                     const Eigen::Ref<const Matrix3X<S>>&, S,                    \
                                     std::vector<VertexContact<S>>&, const BatchOptions<S>&);
FSE_INSTANTIATE_BATCH(float)
FSE_INSTANTIATE_BATCH(double)

}  // namespace fcl_superellipsoid
