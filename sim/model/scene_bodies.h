#ifndef FSE_SIM_MODEL_SCENE_BODIES_H
#define FSE_SIM_MODEL_SCENE_BODIES_H

// The bodies of a `rigid_bodies` scene: the listed ones and those its generator draws.

#include <vector>

#include "model/scene.h"

namespace fse_sim {

/// The listed bodies, then the generated ones. The generator draws from std::mt19937 with the
/// scene's seed, its raw output only (the standard fixes its sequence; the distributions of
/// <random> are each library's own), so a scene gives the same bodies everywhere.
std::vector<BodySpec> sceneBodies(const RigidBodiesSpec& spec);

}  // namespace fse_sim

#endif  // FSE_SIM_MODEL_SCENE_BODIES_H
