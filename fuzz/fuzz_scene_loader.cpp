// Fuzz target 4: the scene loader (sim/scene/). Any byte string is either refused with a
// SceneError that says where (a JSON Pointer, or "line"/"column", or the file name) or gives a
// valid scene; a valid scene small enough to step here (a cloth, or a few rigid bodies) is built
// and stepped, and its state must stay finite. Nothing else may escape: no other exception, crash
// or sanitizer report. docs/hardening.md → "Fuzzing".
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "physics/cloth_simulation.h"
#include "physics/rigid_simulation.h"
#include "scene/scene_loader.h"

namespace {

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "contract failure: %s\n", what.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  fse_sim::Scene scene;
  try {
    scene = fse_sim::parseScene(text, "fuzz.json");
  } catch (const fse_sim::SceneError& e) {
    const std::string message = e.what();
    if (message.rfind("fuzz.json: ", 0) != 0 || message.size() <= 11) {
      fail("refusal without a place: " + message);
    }
    return 0;
  }
  // Valid: a scene small enough to step a few times here must stay finite.
  if (scene.isRigid()) {
    const auto& bodies = *scene.rigid_bodies;
    const long count = long(bodies.bodies.size()) + (bodies.generate ? bodies.generate->count : 0);
    if (count > 8 || bodies.mesh_vertices > 600) return 0;
    if (scene.bowl && scene.bowl->obj.empty() &&
        long(scene.bowl->rings) * scene.bowl->segments > 2000) {
      return 0;
    }
    fse_sim::RigidSimulation sim(scene);
    for (int s = 0; s < 3; ++s) sim.step();
    for (const fse_sim::RigidBody& b : sim.bodies()) {
      if (!b.x.allFinite() || !b.v.allFinite() || !b.omega.allFinite() ||
          !b.q.coeffs().allFinite()) {
        fail("non-finite body state after 3 steps of a valid scene");
      }
    }
    return 0;
  }
  if (long(scene.cloth.nx) * scene.cloth.ny > 400 || scene.shapes.size() > 4) return 0;
  fse_sim::ClothSimulation sim(scene);
  for (int s = 0; s < 3; ++s) sim.step();
  if (!sim.positions().allFinite() || !sim.velocities().allFinite()) {
    fail("non-finite cloth state after 3 steps of a valid scene");
  }
  return 0;
}
