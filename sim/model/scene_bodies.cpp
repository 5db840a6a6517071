#include "model/scene_bodies.h"

#include <cmath>
#include <random>

namespace fse_sim {

std::vector<BodySpec> sceneBodies(const RigidBodiesSpec& spec) {
  std::vector<BodySpec> bodies = spec.bodies;
  if (!spec.generate) return bodies;
  const BodyGenerator& g = *spec.generate;
  // std::mt19937's sequence is fixed by the standard; the distributions are drawn from its
  // raw output here (not std::uniform_real_distribution, whose algorithm is the library's).
  std::mt19937 random(g.seed);
  auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * (double(random()) / 4294967296.0);
  };
  for (int i = 0; i < g.count; ++i) {
    BodySpec b;
    ShapeSpec& s = b.shape;
    for (int k = 0; k < 3; ++k) s.radii[k] = uniform(g.radii.first, g.radii.second);
    s.eps1 = uniform(g.exponents.first, g.exponents.second);
    s.eps2 = uniform(g.exponents.first, g.exponents.second);
    const double angle = double(i) * g.turn_deg * (M_PI / 180);
    s.position = g.start + Eigen::Vector3d(g.helix_radius * std::cos(angle),
                                           g.helix_radius * std::sin(angle), double(i) * g.rise);
    for (int k = 0; k < 3; ++k) s.rotation_deg[k] = uniform(0, 360);
    bodies.push_back(b);
  }
  return bodies;
}

}  // namespace fse_sim
