// FCL's collision table for GJKSolver_indep<double>, instantiated here once (indep_tables.h).
#include "interpose/indep_tables.h"

namespace fcl {
namespace detail {
template struct CollisionFunctionMatrix<GJKSolver_indep<double>>;
}  // namespace detail
template detail::CollisionFunctionMatrix<detail::GJKSolver_indep<double>>&
getCollisionFunctionLookTable<detail::GJKSolver_indep<double>>();
}  // namespace fcl
