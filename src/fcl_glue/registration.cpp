// Registration of the superellipsoid entries in FCL's function tables (registration.h).
#include "fcl_glue/registration.h"

#include <mutex>

#include "fcl_glue/fcl_tables.h"
#include "fcl_superellipsoid/fcl_integration.h"

namespace fcl_superellipsoid {

namespace detail {
namespace {

/// Writes the entries into the distance and collision tables for GJKSolver_libccd<S> (instantiated
/// in fcl_{distance,collision}_table_S.cpp).
template <typename S>
void registerTables() {
  using Solver = fcl::detail::GJKSolver_libccd<S>;
  writeEntries(fcl::getDistanceFunctionLookTable<Solver>().distance_matrix, &distanceEntry<S>);
  writeEntries(fcl::getCollisionFunctionLookTable<Solver>().collision_matrix, &collisionEntry<S>);
}

}  // namespace

void registerWithFclOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    registerTables<double>();
    registerTables<float>();
  });
}
}  // namespace detail

void registerWithFcl() { detail::registerWithFclOnce(); }

}  // namespace fcl_superellipsoid
