// FCL's collision table for GJKSolver_libccd<float>, instantiated here once (see fcl_tables.h).
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_tables.h"

namespace fcl {
namespace detail {
template struct CollisionFunctionMatrix<GJKSolver_libccd<float>>;
}  // namespace detail
template detail::CollisionFunctionMatrix<detail::GJKSolver_libccd<float>>&
getCollisionFunctionLookTable<detail::GJKSolver_libccd<float>>();
}  // namespace fcl

namespace fcl_superellipsoid {
namespace detail {
void registerCollisionTableFloat() {
  writeEntries(
      fcl::getCollisionFunctionLookTable<fcl::detail::GJKSolver_libccd<float>>().collision_matrix,
      &collisionEntry<float>);
}
}  // namespace detail
}  // namespace fcl_superellipsoid
