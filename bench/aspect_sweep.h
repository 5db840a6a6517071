#ifndef FCL_SUPERELLIPSOID_BENCH_ASPECT_SWEEP_H
#define FCL_SUPERELLIPSOID_BENCH_ASPECT_SWEEP_H

namespace fcl_superellipsoid {
namespace bench {

/// Exact-solver accuracy against elongation: for cigar-like radii (a, 1, 1) and rotations of
/// them, the whole exponent grid 0.02 … 1.98, outside points by construction (offsets 1e-3,
/// 0.05 and 1 × size): how many queries miss the accuracy target (1e-9 × size for
/// ε ∈ [0.1, 1.9], 1e-6 × size beyond), and the worst error. Returns 0.
int runAspectSweep(int points_per_shape);

}  // namespace bench
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_BENCH_ASPECT_SWEEP_H
