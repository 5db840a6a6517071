// FCL's distance table for GJKSolver_libccd<float>, instantiated here once (see fcl_tables.h).
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_tables.h"

namespace fcl {
namespace detail {
template struct DistanceFunctionMatrix<GJKSolver_libccd<float>>;
}  // namespace detail
template detail::DistanceFunctionMatrix<detail::GJKSolver_libccd<float>>&
getDistanceFunctionLookTable<detail::GJKSolver_libccd<float>>();
}  // namespace fcl

namespace fcl_superellipsoid {
namespace detail {
void registerDistanceTableFloat() {
  writeEntries(
      fcl::getDistanceFunctionLookTable<fcl::detail::GJKSolver_libccd<float>>().distance_matrix,
      &distanceEntry<float>);
}
}  // namespace detail
}  // namespace fcl_superellipsoid
