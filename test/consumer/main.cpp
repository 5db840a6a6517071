// An out-of-tree user of the installed package: build, link, and check a few answers.
#include <fcl_superellipsoid/superellipsoid.h>

#include <cmath>
#include <cstdio>

int main() {
  const fcl_superellipsoid::Superellipsoidd sphere(1, 1, 1, 1, 1);
  const double volume_error = std::abs(sphere.computeVolume() - 4.0 * M_PI / 3.0);
  const double gauge = sphere.gauge(fcl::Vector3d(0, 2, 0));
  std::printf("volume error %.3g, gauge %.17g\n", volume_error, gauge);
  return (volume_error < 1e-12 && std::abs(gauge - 2.0) < 1e-15) ? 0 : 1;
}
