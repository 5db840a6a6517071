#ifndef FCL_SUPERELLIPSOID_SRC_BATCH_SIMD_TARGETS_FOR_TEST_H
#define FCL_SUPERELLIPSOID_SRC_BATCH_SIMD_TARGETS_FOR_TEST_H

// Test hooks of the SIMD kernel, for test/batch/ only: run the kernel on each instruction set
// this CPU has, not just the best one. Nothing in the library calls these. The bodies live in
// batch/batch_kernel.cpp, beside Highway's dispatch table that they steer.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace fcl_superellipsoid {
namespace detail {

/// The instruction sets compiled into the kernel that this CPU runs, best first, as Highway's
/// target bits and names (e.g. "AVX3", "AVX2", "SSE4", "SCALAR").
std::vector<std::pair<std::int64_t, std::string>> simdTargetsOfThisCpu();

/// Makes the dispatch choose among `targets` only (Highway target bits); 0 restores the CPU's
/// own choice. Not thread-safe: call it while no batched query runs.
void restrictSimdTargets(std::int64_t targets);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_BATCH_SIMD_TARGETS_FOR_TEST_H
