#ifndef FSE_SIM_SCENE_RIGID_BODIES_H
#define FSE_SIM_SCENE_RIGID_BODIES_H

// The loader's check that none of the bodies of a `rigid_bodies` scene overlap at the start.

#include <string>

#include "model/scene.h"

namespace fse_sim {

/// @throws SceneError naming the two bodies (JSON paths) and their signed distance if two of
/// them overlap at the start: a simulation would begin by throwing them apart.
void checkBodiesApart(const RigidBodiesSpec& spec, const std::string& path);

}  // namespace fse_sim

#endif  // FSE_SIM_SCENE_RIGID_BODIES_H
