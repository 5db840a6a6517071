// Which copy of the plain FCL calls a process runs, by behaviour: `probe interposed` checks
// that plain fcl::distance / fcl::collide answer a superellipsoid pair (the interposer won),
// `probe libfcl` that they print FCL's warning and return libfcl's "not supported" answer.
// Built and run several ways by test/CMakeLists.txt (link orders, preloading, a static build).
// Prints "FAILED: ..." and exits 1 when the process does not behave as expected.

#include <dlfcn.h>
#include <fcl/geometry/shape/box.h>
#include <fcl_superellipsoid/fcl_integration.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <memory>

int main(int argc, char** argv) {
  if (argc != 2 ||
      (std::strcmp(argv[1], "interposed") != 0 && std::strcmp(argv[1], "libfcl") != 0)) {
    std::cerr << "usage: probe interposed|libfcl\n";
    return 2;
  }
  const bool expect_interposed = std::strcmp(argv[1], "interposed") == 0;

  // The shape's flat top at z = 0.5, the box's bottom face at z = 0.9: 0.4 apart; moved down
  // to 0.4, they overlap by 0.1.
  const auto shape = std::make_shared<fcl_superellipsoid::Superellipsoidd>(1, 1, 0.5, 0.3, 0.3);
  const auto box = std::make_shared<fcl::Boxd>(0.4, 0.4, 0.4);
  const fcl::CollisionObjectd s(shape), above(box, fcl::Transform3d(fcl::Translation3d(0, 0, 1.1))),
      overlapping(box, fcl::Transform3d(fcl::Translation3d(0, 0, 0.6)));
  fcl::DistanceResultd distance;
  const double d = fcl::distance(&s, &above, fcl::DistanceRequestd(), distance);
  fcl::CollisionResultd contacts;
  const std::size_t n = fcl::collide(&s, &overlapping, fcl::CollisionRequestd(), contacts);

  // The interposer's own report, when the process exports it (a preloaded or linked shared
  // interposer does; a static executable exports only what shared libraries need).
  using Query = bool (*)();
  const auto query = reinterpret_cast<Query>(
      dlsym(RTLD_DEFAULT, "_ZN18fcl_superellipsoid20plainCallsInterposedEv"));
  const char* reported = query == nullptr ? "not found" : (query() ? "true" : "false");
  std::cout << "probe: distance " << d << ", contacts " << n
            << ", plainCallsInterposed(): " << reported << "\n";

  const bool interposed = std::abs(d - 0.4) < 1e-12 && n == 1;
  const bool libfcl = d == std::numeric_limits<double>::max() && n == 0;
  const bool report_agrees = query == nullptr || query() == expect_interposed;
  if (!(expect_interposed ? interposed : libfcl) || !report_agrees) {
    std::cout << "FAILED: expected " << argv[1] << "\n";
    return 1;
  }
  std::cout << "probe: as expected (" << argv[1] << ")\n";
  return 0;
}
