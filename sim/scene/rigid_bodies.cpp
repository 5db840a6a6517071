#include "scene/rigid_bodies.h"

#include <fcl_superellipsoid/fcl_integration.h>

#include <cmath>
#include <sstream>

#include "model/scene_bodies.h"
#include "model/shapes.h"
#include "scene/json_reader.h"

namespace fse_sim {

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
