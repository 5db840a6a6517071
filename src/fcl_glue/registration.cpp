// Registration of the superellipsoid entries in FCL's function tables (registration.h).
#include "fcl_glue/registration.h"

#include <mutex>

#include "fcl_glue/fcl_tables.h"
#include "fcl_superellipsoid/fcl_integration.h"

namespace fcl_superellipsoid {

namespace detail {
void registerWithFclOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    registerDistanceTableDouble();
    registerDistanceTableFloat();
    registerCollisionTableDouble();
    registerCollisionTableFloat();
  });
}
}  // namespace detail

void registerWithFcl() { detail::registerWithFclOnce(); }

}  // namespace fcl_superellipsoid
