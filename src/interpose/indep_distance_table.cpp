// FCL's distance table for GJKSolver_indep<double>, instantiated here once (indep_tables.h).
#include "interpose/indep_tables.h"

namespace fcl {
namespace detail {
template struct DistanceFunctionMatrix<GJKSolver_indep<double>>;
}  // namespace detail
template detail::DistanceFunctionMatrix<detail::GJKSolver_indep<double>>&
getDistanceFunctionLookTable<detail::GJKSolver_indep<double>>();
}  // namespace fcl
