// The front end for double, and the one-time registration of the table entries.
#include "front_end.h"

#include <mutex>

#include "fcl_tables.h"

FSE_INSTANTIATE_FRONT_END(double)

namespace fcl_superellipsoid {

void registerWithFcl() {
  static std::once_flag once;
  std::call_once(once, [] {
    detail::registerDistanceTableDouble();
    detail::registerDistanceTableFloat();
    detail::registerCollisionTableDouble();
    detail::registerCollisionTableFloat();
  });
}

}  // namespace fcl_superellipsoid
