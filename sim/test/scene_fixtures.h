#ifndef FSE_SIM_TEST_SCENE_FIXTURES_H
#define FSE_SIM_TEST_SCENE_FIXTURES_H

// CI-sized scenes for the tests: a small cloth over a small version of the paper's shape.

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

}  // namespace test
}  // namespace fse_sim

#endif  // FSE_SIM_TEST_SCENE_FIXTURES_H
