#ifndef FCL_SUPERELLIPSOID_SRC_SHAPE_EVALUATION_COUNT_H
#define FCL_SUPERELLIPSOID_SRC_SHAPE_EVALUATION_COUNT_H

// Internal: the per-thread count behind shapeEvaluations() (diagnostics.h). NestedNorm counts
// each evaluation of a superellipsoid's gauge or support function here; a Newton step, a GJK
// iteration's support call and an EPA expansion each cost one (two where both shapes are
// superellipsoids).
//
// The count is always on, so it must cost next to nothing beside an evaluation (a few exp2 and
// log2 calls): a GNU `__thread` integer, which has no C++ initialisation to guard, in the
// initial-exec TLS model, so the increment is one add at a fixed offset from the thread pointer
// (no call to __tls_get_addr). The library is linked into programs or preloaded, not opened
// with dlopen() late, so the static TLS block holds these eight bytes.

#include <cstdint>

namespace fcl_superellipsoid {
namespace detail {

extern __thread std::uint64_t shape_evaluations __attribute__((tls_model("initial-exec")));

inline void countShapeEvaluation() { ++shape_evaluations; }

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SHAPE_EVALUATION_COUNT_H
