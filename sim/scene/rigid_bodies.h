#ifndef FSE_SIM_SCENE_RIGID_BODIES_H
#define FSE_SIM_SCENE_RIGID_BODIES_H

// The bodies of a `rigid_bodies` scene: the listed ones and those its generator draws, and the
// loader's check that none of them overlap at the start.

#include <vector>

#include "scene/scene.h"

namespace fse_sim {

/// The listed bodies, then the generated ones. The generator draws from std::mt19937 with the
/// scene's seed, its raw output only (the standard fixes its sequence; the distributions of
/// <random> are each library's own), so a scene gives the same bodies everywhere.
std::vector<BodySpec> sceneBodies(const RigidBodiesSpec& spec);

/// @throws SceneError naming the two bodies (JSON paths) and their signed distance if two of
/// them overlap at the start: a simulation would begin by throwing them apart.
void checkBodiesApart(const RigidBodiesSpec& spec, const std::string& path);

}  // namespace fse_sim

#endif  // FSE_SIM_SCENE_RIGID_BODIES_H
