#ifndef FSE_SIM_TEST_SCENE_FIXTURES_H
#define FSE_SIM_TEST_SCENE_FIXTURES_H

// CI-sized scenes for the tests: a small cloth over a small version of the paper's shape; rigid
// bodies from a list; a few bodies dropped into a small bowl.

#include <string>

#include "scene/scene_loader.h"

namespace fse_sim {
namespace test {

/// A 16 × 16 cloth (3 m square, 1 kg) 0.5 m above a (1.2, 1.0, 0.7; 0.4, 0.3)
/// superellipsoid, with the given effects list (JSON array text) and extra blocks.
inline Scene smallClothScene(const std::string& effects, const std::string& blocks = "",
                             double duration = 1.0, int grid = 16) {
  const std::string text = R"({
    "effects": )" + effects +
                           R"(,
    "time": {"step": 0.016666666666666666, "substeps": 10, "duration": )" +
                           std::to_string(duration) + R"(},
    "cloth": {"grid": [)" + std::to_string(grid) +
                           ", " + std::to_string(grid) +
                           R"(], "size": [3, 3], "centre": [0, 0, 1.2], "mass": 1},
    "shapes": [{"radii": [1.2, 1.0, 0.7], "exponents": [0.4, 0.3]}])" +
                           (blocks.empty() ? "" : ", " + blocks) + "}";
  return parseScene(text, "fixture");
}

/// A rigid-body scene from its effects, bodies (JSON array text) and extra blocks.
inline Scene rigidScene(const std::string& effects, const std::string& bodies,
                        const std::string& blocks = "", double duration = 1.0) {
  const std::string text = R"({"effects": )" + effects + R"(,
    "time": {"step": 0.016666666666666666, "substeps": 20, "duration": )" +
                           std::to_string(duration) + R"(},
    "rigid_bodies": {"density": 1000, "bodies": )" +
                           bodies + "}" + (blocks.empty() ? "" : ", " + blocks) + "}";
  return parseScene(text, "test");
}

/// Five bodies dropped into a small bowl, every effect on.
inline Scene smallBowlScene(double duration) {
  return parseScene(R"({"effects": ["gravity", "rigid_bodies", "rigid_contact", "friction",
                                    "restitution", "damping"],
    "time": {"step": 0.016666666666666666, "substeps": 10, "duration": )" +
                        std::to_string(duration) + R"(},
    "rigid_bodies": {"density": 1000, "mesh_vertices": 200,
      "generate": {"count": 5, "seed": 3, "radii": [0.25, 0.3], "exponents": [0.3, 1.7],
                   "start": [0, 0, 0.2], "helix_radius": 0.5, "turn_deg": 120, "rise": 0.7}},
    "bowl": {"radius": 1.5, "thickness": 0.1, "rings": 12, "segments": 48},
    "rigid_contact": {"tolerance": 0.01},
    "friction": {"dynamic": 0.4, "static": 0.5},
    "restitution": {"coefficient": 0.2},
    "damping": {"linear": 1.0}})",
                    "small bowl");
}

}  // namespace test
}  // namespace fse_sim

#endif  // FSE_SIM_TEST_SCENE_FIXTURES_H
