// FCL's distance table for GJKSolver_libccd<double>, instantiated here once (see fcl_tables.h).
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_tables.h"

namespace fcl {
namespace detail {
template struct DistanceFunctionMatrix<GJKSolver_libccd<double>>;
}  // namespace detail
template detail::DistanceFunctionMatrix<detail::GJKSolver_libccd<double>>&
getDistanceFunctionLookTable<detail::GJKSolver_libccd<double>>();
}  // namespace fcl

namespace fcl_superellipsoid {
namespace detail {
void registerDistanceTableDouble() {
  writeEntries(
      fcl::getDistanceFunctionLookTable<fcl::detail::GJKSolver_libccd<double>>().distance_matrix,
      &distanceEntry<double>);
}
}  // namespace detail
}  // namespace fcl_superellipsoid
