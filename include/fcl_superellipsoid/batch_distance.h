#ifndef FCL_SUPERELLIPSOID_BATCH_DISTANCE_H
#define FCL_SUPERELLIPSOID_BATCH_DISTANCE_H

/// @file
/// Many vertices against one superellipsoid: what a cloth or a rigid mesh asks every step.
///
/// Vertices come as a 3×N matrix, one vertex per column, in the world frame W. Eigen stores
/// it column-major, so an N×3 row-major array (x0 y0 z0 x1 y1 z1 ...) maps without a copy:
///
///     Eigen::Map<const Eigen::Matrix3Xd> p_WV(data, 3, n);
///
/// Every answer agrees with the scalar pointDistance() of that vertex with the same options,
/// vertex for vertex: to the solver's tolerance with the Exact method's SIMD solver (the
/// default), bitwise with BatchOptions::vectorize = false. Work is spread over TBB's threads
/// above a size where threads pay; results do not depend on the thread count.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "fcl_superellipsoid/distance_options.h"
#include "fcl_superellipsoid/export.h"
#include "fcl_superellipsoid/point_derivatives.h"
#include "fcl_superellipsoid/point_distance.h"
#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {

template <typename S>
using Matrix3X = Eigen::Matrix<S, 3, Eigen::Dynamic>;

/// The instruction set the SIMD solver runs on this CPU ("AVX3" = AVX-512, "AVX2", "SSE4",
/// "SCALAR" or "EMU128" = portable code, as the compiler allows), chosen once at run time.
FSE_EXPORT const char* simdInstructionSet();

/// Where the vertices of one batched call went (BatchOptions::statistics).
struct BatchStatistics {
  std::size_t culled = 0;  ///< dropped by verticesWithinMargin's bounding-box test
  std::size_t simd = 0;    ///< answered by the SIMD solver
  std::size_t scalar = 0;  ///< answered by the scalar solver (handed back, or not vectorised)
};

template <typename S>
struct BatchOptions {
  DistanceOptions<S> distance;  ///< method, tolerance, iteration cap (default: Exact)
  /// 0: as many threads as TBB offers; 1: the calling thread only; n: at most n.
  int threads = 0;
  /// No threads below this many vertices (work is cut into chunks of 256 vertices). The default
  /// was chosen by measurement with the SIMD solver: below it a second thread saves less than it
  /// costs on vertices the within-margin cull drops in nanoseconds.
  int min_parallel_vertices = 1024;
  /// The Exact method on SIMD lanes (the default): several vertices per instruction, with the
  /// instruction set chosen at run time for the CPU (AVX-512, AVX2, SSE4, or portable code).
  /// Answers agree with single queries to the solver's tolerance; a vertex the SIMD solver
  /// cannot settle the way the scalar solver would (docs/usage.md → "Batched queries") goes to
  /// the scalar solver.
  /// false: every vertex through the scalar pointDistance(), bitwise equal to single queries.
  /// The other methods always run the scalar solver.
  bool vectorize = true;
  /// If set, overwritten with where this call's vertices went.
  BatchStatistics* statistics = nullptr;
  /// Optional warm starts, world frame, one column per vertex (3 × N, like p_WV): a point
  /// near each vertex's expected nearest point, typically the previous step's nearest_point.
  /// A column with a NaN means "none". Used by the Exact method for vertices outside the
  /// shape (a convex problem: the answer is the same to the tolerance, found in fewer
  /// iterations); ignored inside. Not owned; must outlive the call.
  const Matrix3X<S>* warm_start_W = nullptr;
};

/// Per-vertex answers, world frame.
template <typename S>
struct BatchDistanceResult {
  Eigen::Matrix<S, Eigen::Dynamic, 1> distance;  ///< signed, < 0 inside
  Matrix3X<S> nearest_point;                     ///< on the surface
  Matrix3X<S> normal;                            ///< unit outward normal there
};

/// Per-vertex signed distances with their gradients (batchDistanceDerivatives), world frame;
/// one column (or entry) per vertex. The derivatives are those of point_derivatives.h.
template <typename S>
struct BatchDerivativesResult {
  Eigen::Matrix<S, Eigen::Dynamic, 1> distance;  ///< signed, < 0 inside
  Matrix3X<S> nearest_point;                     ///< on the surface
  Matrix3X<S> normal;                            ///< unit outward normal there; also ∂d/∂Q
  Eigen::Matrix<S, 6, Eigen::Dynamic> d_pose;    ///< ∂d/∂ξ, the twist ξ = (ω, v) in W
  Eigen::Matrix<S, 5, Eigen::Dynamic> d_shape;   ///< ∂d/∂(a1, a2, a3, ε1, ε2)
  /// False where the vertex has several nearest points (point_derivatives.h); the gradients are
  /// then those of the returned nearest point's branch.
  Eigen::Matrix<bool, Eigen::Dynamic, 1> differentiable;
};

/// A vertex within the margin.
template <typename S>
struct VertexContact {
  Eigen::Index index;        ///< column of the vertex in p_WV
  S distance;                ///< signed, ≤ margin
  Vector3<S> nearest_point;  ///< world frame
  Vector3<S> normal;         ///< world frame, outward
};

/// Signed distance, nearest point and normal of every vertex.
/// @throws std::invalid_argument naming the first non-finite vertex (index and value),
///         invalid options (see validateOptions), or a warm start of the wrong size; result
///         is then unchanged.
template <typename S>
FSE_EXPORT void batchDistance(const Superellipsoid<S>& shape,
                              const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
                              const detail::NonDeduced<Eigen::Ref<const Matrix3X<S>>>& p_WV,
                              BatchDistanceResult<S>& result,
                              const detail::NonDeduced<BatchOptions<S>>& options = {});

/// Signed distance, nearest point, normal and the gradients of the distance of every vertex:
/// the rows pointDistanceDerivatives() gives with DerivativeOrder::kGradient (the world-frame
/// call), solved as batchDistance() solves them (on the SIMD lanes with options.vectorize, where
/// the rows agree with the single query's to the solver's tolerance; bitwise without SIMD and
/// warm starts). The flag's test for other nearest points reads the answers the solver's starts
/// converged to, on the lanes as in the scalar solver. options.distance.method must be
/// DistanceMethod::kExact.
/// @throws std::invalid_argument as batchDistance(), or for another method, naming it.
template <typename S>
FSE_EXPORT void batchDistanceDerivatives(
    const Superellipsoid<S>& shape, const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
    const detail::NonDeduced<Eigen::Ref<const Matrix3X<S>>>& p_WV,
    BatchDerivativesResult<S>& result, const detail::NonDeduced<BatchOptions<S>>& options = {});

/// Only the vertices whose signed distance is ≤ margin, in increasing index order. Vertices
/// whose distance to the shape's bounding box already exceeds the margin are dropped after a
/// few arithmetic operations, without a solver call.
/// @throws std::invalid_argument for a non-finite margin or vertex (naming it) or bad options.
template <typename S>
FSE_EXPORT std::vector<VertexContact<S>> verticesWithinMargin(
    const Superellipsoid<S>& shape, const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
    const detail::NonDeduced<Eigen::Ref<const Matrix3X<S>>>& p_WV, detail::NonDeduced<S> margin,
    const detail::NonDeduced<BatchOptions<S>>& options = {});

/// The same into a caller's vector: `contacts` is cleared and refilled, and keeps its capacity,
/// so a simulation that passes the same vector every step allocates nothing once it has grown
/// (1e6 contacts are 64 MB in double: fresh pages for them cost more than the query on some
/// machines).
template <typename S>
FSE_EXPORT void verticesWithinMargin(const Superellipsoid<S>& shape,
                                     const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
                                     const detail::NonDeduced<Eigen::Ref<const Matrix3X<S>>>& p_WV,
                                     detail::NonDeduced<S> margin,
                                     std::vector<VertexContact<S>>& contacts,
                                     const detail::NonDeduced<BatchOptions<S>>& options = {});

#define FSE_DECLARE_BATCH(S)                                                                     \
  extern template FSE_EXPORT void batchDistance(                                                 \
      const Superellipsoid<S>&, const fcl::Transform3<S>&, const Eigen::Ref<const Matrix3X<S>>&, \
      BatchDistanceResult<S>&, const BatchOptions<S>&);                                          \
  extern template FSE_EXPORT void batchDistanceDerivatives(                                      \
      const Superellipsoid<S>&, const fcl::Transform3<S>&, const Eigen::Ref<const Matrix3X<S>>&, \
      BatchDerivativesResult<S>&, const BatchOptions<S>&);                                       \
  extern template FSE_EXPORT std::vector<VertexContact<S>> verticesWithinMargin(                 \
      const Superellipsoid<S>&, const fcl::Transform3<S>&, const Eigen::Ref<const Matrix3X<S>>&, \
      S, const BatchOptions<S>&);                                                                \
  extern template FSE_EXPORT void verticesWithinMargin(                                          \
      const Superellipsoid<S>&, const fcl::Transform3<S>&, const Eigen::Ref<const Matrix3X<S>>&, \
      S, std::vector<VertexContact<S>>&, const BatchOptions<S>&);
FSE_DECLARE_BATCH(float)
FSE_DECLARE_BATCH(double)
#undef FSE_DECLARE_BATCH

}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_BATCH_DISTANCE_H
