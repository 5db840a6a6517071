#include "scene/rigid_bodies.h"

#include <fcl_superellipsoid/fcl_integration.h>

#include <cmath>
#include <random>
#include <sstream>

#include "contact/contact_model.h"
#include "scene/json_reader.h"

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

void checkBodiesApart(const RigidBodiesSpec& spec, const std::string& path) {
  const std::vector<BodySpec> bodies = sceneBodies(spec);
  const std::size_t listed = spec.bodies.size();
  auto name = [&](std::size_t i) {
    return i < listed ? childPath(childPath(path, "bodies"), i)
                      : childPath(path, "generate") + " (body " + std::to_string(i - listed) + ")";
  };
  std::vector<fcl_superellipsoid::Superellipsoidd> shapes;
  for (const BodySpec& b : bodies) shapes.push_back(makeShape(b.shape));
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < bodies.size(); ++j) {
      const double reach = shapes[i].radii().norm() + shapes[j].radii().norm();
      if ((bodies[i].shape.position - bodies[j].shape.position).norm() > reach) continue;
      fcl::DistanceRequestd request;
      request.enable_signed_distance = true;
      fcl::DistanceResultd result;
      const double d =
          fcl_superellipsoid::distance(&shapes[i], shapeTransform(bodies[i].shape), &shapes[j],
                                       shapeTransform(bodies[j].shape), request, result);
      if (d < 0) {
        std::ostringstream message;
        message << name(i) << " and " << name(j)
                << ": the bodies overlap at the start (signed distance " << d
                << " m); place them further apart";
        throw SceneError(message.str());
      }
    }
  }
}

}  // namespace fse_sim
