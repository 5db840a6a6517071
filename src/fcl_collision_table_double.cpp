// FCL's collision table for GJKSolver_libccd<double>, instantiated here once (see fcl_tables.h).
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_tables.h"

namespace fcl {
namespace detail {
template struct CollisionFunctionMatrix<GJKSolver_libccd<double>>;
}  // namespace detail
template detail::CollisionFunctionMatrix<detail::GJKSolver_libccd<double>>&
getCollisionFunctionLookTable<detail::GJKSolver_libccd<double>>();
}  // namespace fcl

namespace fcl_superellipsoid {
namespace detail {
void registerCollisionTableDouble() {
  writeEntries(
      fcl::getCollisionFunctionLookTable<fcl::detail::GJKSolver_libccd<double>>().collision_matrix,
      &collisionEntry<double>);
}
}  // namespace detail
}  // namespace fcl_superellipsoid
