#include "shape/evaluation_count.h"

#include "fcl_superellipsoid/diagnostics.h"

namespace fcl_superellipsoid {
namespace detail {

__thread std::uint64_t shape_evaluations __attribute__((tls_model("initial-exec"))) = 0;

}  // namespace detail

std::uint64_t& shapeEvaluations() { return detail::shape_evaluations; }

}  // namespace fcl_superellipsoid
