// Strict loading: every mistake a scene file can hold is refused with a message that says
// where it is (JSON Pointer, or line and column), and the runner writes nothing.

#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <vector>

#include "model/cloth_mesh.h"
#include "model/static_mesh.h"
#include "scene/scene_loader.h"

namespace fse_sim {
namespace {

// A valid scene; each test breaks one thing in it.
const char* kValid = R"({
  "effects": ["gravity", "stretch", "collision"],
  "time": {"step": 0.01, "substeps": 4, "duration": 0.1},
  "cloth": {"grid": [4, 5], "size": [1, 1], "centre": [0, 0, 2], "mass": 1},
  "shapes": [{"radii": [1, 1, 1], "exponents": [0.5, 0.5]}],
  "stretch": {"compliance": 0},
  "collision": {"tolerance": 0.01}
})";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

/// The message parseScene gives `text`; fails the test if it parses.
std::string errorOf(const std::string& text) {
  try {
    parseScene(text, "test.json");
  } catch (const SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return "";
}

#define EXPECT_REFUSED(text, ...)                           \
  do {                                                      \
    const std::string message = errorOf(text);              \
    for (const char* part : {__VA_ARGS__}) {                \
      EXPECT_NE(message.find(part), std::string::npos)      \
          << "message: " << message << "\nlacks: " << part; \
    }                                                       \
  } while (0)

TEST(SceneLoaderTest, ValidSceneLoads) {
  const Scene scene = parseScene(kValid, "test.json");
  EXPECT_EQ(scene.effects.size(), 3u);
  EXPECT_TRUE(scene.has(Effect::kCollision));
  EXPECT_FALSE(scene.has(Effect::kFriction));
  EXPECT_FALSE(scene.friction.has_value());
  EXPECT_EQ(scene.cloth.nx, 4);
  EXPECT_EQ(scene.time.substeps, 4);
  EXPECT_DOUBLE_EQ(scene.collision->tolerance, 0.01);
}

TEST(SceneLoaderTest, ShippedScenesLoadWithThePapersMeshCounts) {
  const Scene small = loadScene(std::string(FSE_SIM_SCENES) + "/cloth_3240.json");
  const ClothMesh mesh = makeClothMesh(small.cloth);
  EXPECT_EQ(mesh.vertexCount(), 3240);
  EXPECT_EQ(mesh.triangles.size(), 6254u);
  const Scene large = loadScene(std::string(FSE_SIM_SCENES) + "/cloth_6460.json");
  EXPECT_EQ(makeClothMesh(large.cloth).vertexCount(), 6460);
  for (const Scene* s : {&small, &large}) {
    EXPECT_EQ(s->shapes.size(), 1u);
    EXPECT_EQ(s->shapes[0].radii, Eigen::Vector3d(3.5, 3.0, 2.0));
    EXPECT_EQ(s->shapes[0].eps1, 0.4);
    EXPECT_EQ(s->shapes[0].eps2, 0.3);
    EXPECT_EQ(s->collision->tolerance, 0.025);
  }
}

TEST(SceneLoaderTest, UnknownKeyNamedByItsPath) {
  EXPECT_REFUSED(replaced(kValid, "\"mass\": 1", "\"mass\": 1, \"colour\": 3"), "/cloth/colour",
                 "unknown key");
  EXPECT_REFUSED(replaced(kValid, "\"exponents\"", "\"colour\": 1, \"exponents\""),
                 "/shapes/0/colour", "unknown key");
  EXPECT_REFUSED(replaced(kValid, "\"effects\"", "\"wind\": {}, \"effects\""), "/wind",
                 "unknown key");
}

TEST(SceneLoaderTest, UnknownEffectListsTheValidOnes) {
  EXPECT_REFUSED(replaced(kValid, "\"gravity\",", "\"wind\","), "/effects/0", "\"wind\"",
                 "gravity, stretch, bending, pinning, collision, friction, damping");
}

TEST(SceneLoaderTest, EffectDeclaredTwice) {
  EXPECT_REFUSED(replaced(kValid, "\"gravity\",", "\"gravity\", \"gravity\","), "/effects/1",
                 "twice");
}

TEST(SceneLoaderTest, BlockForAnEffectNotDeclared) {
  EXPECT_REFUSED(replaced(kValid, "\"stretch\": {", "\"damping\": {\"linear\": 1}, \"stretch\": {"),
                 "/damping", "not declared", "gravity, stretch, collision");
}

TEST(SceneLoaderTest, WrongType) {
  EXPECT_REFUSED(replaced(kValid, "\"step\": 0.01", "\"step\": \"fast\""), "/time/step",
                 "must be a number", "a string");
  EXPECT_REFUSED(replaced(kValid, "\"substeps\": 4", "\"substeps\": 4.5"), "/time/substeps",
                 "an integer");
  EXPECT_REFUSED(replaced(kValid, "\"grid\": [4, 5]", "\"grid\": 20"), "/cloth/grid", "an array");
  EXPECT_REFUSED(replaced(kValid, "\"centre\": [0, 0, 2]", "\"centre\": [0, 2]"), "/cloth/centre",
                 "3 numbers");
  EXPECT_REFUSED(replaced(kValid, "\"effects\": [\"gravity\"", "\"effects\": [7"), "/effects/0",
                 "a string");
  EXPECT_REFUSED(R"([1, 2])", "must be an object");
}

TEST(SceneLoaderTest, MissingRequiredKey) {
  EXPECT_REFUSED(replaced(kValid, "\"step\": 0.01, ", ""), "/time/step", "missing");
  EXPECT_REFUSED(replaced(kValid, "\"effects\": [\"gravity\", \"stretch\", \"collision\"],", ""),
                 "/effects", "missing");
}

TEST(SceneLoaderTest, NonFiniteOrOutOfRangeValues) {
  // JSON has no infinity; a literal beyond double's range is refused while parsing.
  EXPECT_REFUSED(replaced(kValid, "\"step\": 0.01", "\"step\": 1e999"), "1e999", "line 3",
                 "not a finite number");
  EXPECT_REFUSED(replaced(kValid, "\"step\": 0.01", "\"step\": 0"), "/time/step", "(0, 1]",
                 "got 0");
  EXPECT_REFUSED(replaced(kValid, "\"step\": 0.01", "\"step\": -0.01"), "/time/step", "got -0.01");
  EXPECT_REFUSED(replaced(kValid, "\"compliance\": 0", "\"compliance\": -1"), "/stretch/compliance",
                 "≥ 0", "got -1");
  EXPECT_REFUSED(replaced(kValid, "\"grid\": [4, 5]", "\"grid\": [0, 5]"), "/cloth/grid/0",
                 "at least 2", "got 0");
  EXPECT_REFUSED(replaced(kValid, "\"grid\": [4, 5]", "\"grid\": [100000, 100000]"), "/cloth/grid",
                 "at most");
  EXPECT_REFUSED(replaced(kValid, "\"tolerance\": 0.01", "\"tolerance\": 0"),
                 "/collision/tolerance", "got 0");
  EXPECT_REFUSED(replaced(kValid, "\"mass\": 1", "\"mass\": -2"), "/cloth/mass", "got -2");
  EXPECT_REFUSED(replaced(kValid, "\"duration\": 0.1", "\"duration\": 0.001"), "/time/duration",
                 "at least one step");
}

TEST(SceneLoaderTest, ExponentsOutsideTheShapesRangeGetTheLibrarysError) {
  // The library names the exponent and its value; the loader adds where the shape is.
  const std::string message = errorOf(replaced(kValid, "[0.5, 0.5]", "[2.5, 0.5]"));
  EXPECT_NE(message.find("/shapes/0"), std::string::npos) << message;
  EXPECT_NE(message.find("eps1"), std::string::npos) << message;
  EXPECT_NE(message.find("2.5"), std::string::npos) << message;
  EXPECT_REFUSED(replaced(kValid, "[0.5, 0.5]", "[0.5, 0]"), "/shapes/0", "eps2");
  EXPECT_REFUSED(replaced(kValid, "\"radii\": [1, 1, 1]", "\"radii\": [1, -1, 1]"), "/shapes/0");
}

TEST(SceneLoaderTest, PinnedVertexOutOfRange) {
  const std::string scene =
      replaced(replaced(kValid, "\"collision\"]", "\"collision\", \"pinning\"]"), "\"stretch\": {",
               "\"pinning\": {\"fixed\": [0, 20]}, \"stretch\": {");
  EXPECT_REFUSED(scene, "/pinning/fixed/1", "[0, 19]", "got 20");
}

TEST(SceneLoaderTest, FrictionWithoutCollisionAndCollisionWithoutShapes) {
  EXPECT_REFUSED(replaced(kValid, "\"collision\"]", "\"friction\"]"), "friction", "collision");
  EXPECT_REFUSED(
      replaced(kValid, "\"shapes\": [{\"radii\": [1, 1, 1], \"exponents\": [0.5, 0.5]}],", ""),
      "/shapes", "no shapes");
}

// A valid rigid-body scene; each test below breaks one thing in it.
const char* kRigid = R"({
  "effects": ["gravity", "rigid_bodies", "rigid_contact", "friction", "restitution"],
  "time": {"step": 0.01, "substeps": 4, "duration": 0.1},
  "rigid_bodies": {"density": 1000, "mesh_vertices": 100,
    "bodies": [{"radii": [0.3, 0.3, 0.3], "exponents": [1, 1], "position": [0, 0, 2],
                "velocity": [0, 0, 0], "angular_velocity": [0, 0, 0], "fixed": false}],
    "generate": {"count": 3, "seed": 1, "radii": [0.2, 0.25], "exponents": [0.5, 1.5],
                 "start": [0, 0, 4], "helix_radius": 0, "turn_deg": 0, "rise": 1}},
  "bowl": {"radius": 2, "thickness": 0.2, "rings": 5, "segments": 12},
  "rigid_contact": {"tolerance": 0.01},
  "restitution": {"coefficient": 0.3}
})";

TEST(SceneLoaderTest, RigidSceneLoads) {
  const Scene scene = parseScene(kRigid, "test.json");
  EXPECT_TRUE(scene.isRigid());
  EXPECT_EQ(scene.rigid_bodies->bodies.size(), 1u);
  EXPECT_EQ(scene.rigid_bodies->generate->count, 3);
  EXPECT_EQ(scene.bowl->rings, 5);
  EXPECT_DOUBLE_EQ(scene.rigid_contact->tolerance, 0.01);
  EXPECT_DOUBLE_EQ(scene.restitution->coefficient, 0.3);
  EXPECT_TRUE(scene.friction.has_value());
}

TEST(SceneLoaderTest, ShippedBowlSceneHasThePapersCounts) {
  const Scene scene = loadScene(std::string(FSE_SIM_SCENES) + "/bowl_50.json");
  EXPECT_EQ(scene.rigid_bodies->generate->count, 50);
  EXPECT_EQ(scene.rigid_bodies->mesh_vertices, 506);
  EXPECT_EQ(2 * (1 + scene.bowl->rings * scene.bowl->segments), 5002);
  EXPECT_DOUBLE_EQ(scene.rigid_contact->tolerance, 0.015);
}

TEST(SceneLoaderTest, EveryRigidKeyIsChecked) {
  const std::vector<std::array<std::string, 3>> cases = {
      // {from, to, part of the message}
      {"\"density\": 1000", "\"density\": 0", "/rigid_bodies/density"},
      {"\"mesh_vertices\": 100", "\"mesh_vertices\": 3", "/rigid_bodies/mesh_vertices"},
      {"\"radii\": [0.3, 0.3, 0.3]", "\"radii\": [0.3, -1, 0.3]", "/rigid_bodies/bodies/0"},
      {"\"exponents\": [1, 1]", "\"exponents\": [1, 2.5]", "/rigid_bodies/bodies/0"},
      {"\"position\": [0, 0, 2]", "\"position\": [0, 0, 1e7]", "/rigid_bodies/bodies/0/position"},
      {"\"velocity\": [0, 0, 0]", "\"velocity\": [1e5, 0, 0]", "/rigid_bodies/bodies/0/velocity"},
      {"\"angular_velocity\": [0, 0, 0]", "\"angular_velocity\": [0, 1e5, 0]",
       "/rigid_bodies/bodies/0/angular_velocity"},
      {"\"fixed\": false", "\"fixed\": 0", "/rigid_bodies/bodies/0/fixed"},
      {"\"count\": 3", "\"count\": -1", "/rigid_bodies/generate/count"},
      {"\"seed\": 1", "\"seed\": -4", "/rigid_bodies/generate/seed"},
      {"\"radii\": [0.2, 0.25]", "\"radii\": [0.25, 0.2]", "/rigid_bodies/generate/radii"},
      {"\"exponents\": [0.5, 1.5]", "\"exponents\": [0.5, 2.5]", "/rigid_bodies/generate"},
      {"\"helix_radius\": 0", "\"helix_radius\": -1", "/rigid_bodies/generate/helix_radius"},
      {"\"turn_deg\": 0", "\"turn_deg\": 400", "/rigid_bodies/generate/turn_deg"},
      {"\"rise\": 1", "\"rise\": 1e6", "/rigid_bodies/generate/rise"},
      {"\"rise\": 1", "\"rise\": 0.1", "overlap at the start"},
      {"\"radius\": 2", "\"radius\": 0", "/bowl/radius"},
      {"\"thickness\": 0.2", "\"thickness\": 3", "/bowl/thickness"},
      {"\"rings\": 5", "\"rings\": 1", "/bowl/rings"},
      {"\"segments\": 12", "\"segments\": 2", "/bowl/segments"},
      {"\"rings\": 5", "\"obj\": \"x.obj\", \"rings\": 5", "takes no generated size"},
      {"\"tolerance\": 0.01", "\"tolerance\": 0", "/rigid_contact/tolerance"},
      {"\"coefficient\": 0.3", "\"coefficient\": 1.5", "/restitution/coefficient"},
      {"\"seed\": 1,", "\"seed\": 1, \"colour\": 2,", "/rigid_bodies/generate/colour"},
      {"\"rigid_contact\", ", "", "needs \"collision\" or \"rigid_contact\""},
      {"\"effects\": [\"gravity\", ", "\"effects\": [\"gravity\", \"stretch\", ",
       "acts on a cloth"},
      {"\"bowl\": {", "\"cloth\": {}, \"bowl\": {", "/cloth"},
  };
  for (const auto& [from, to, part] : cases) {
    EXPECT_REFUSED(replaced(kRigid, from, to), part.c_str());
  }
  // A bowl in a cloth scene, and rigid bodies declared without their block.
  EXPECT_REFUSED(replaced(kValid, "\"stretch\": {", "\"bowl\": {}, \"stretch\": {"), "/bowl",
                 "rigid_bodies");
  EXPECT_REFUSED(R"({"effects": ["rigid_bodies"], "time": {"step": 0.01, "duration": 1}})",
                 "/rigid_bodies", "no block");
}

TEST(SceneLoaderTest, BowlObjIsReadRelativeToTheSceneAndBadFacesAreRefused) {
  const auto dir = std::filesystem::temp_directory_path() / "fse_sim_bowl_obj_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // A tetrahedron, counter-clockwise seen from outside.
  std::ofstream(dir / "bowl.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                     "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
  const std::string scene_text =
      replaced(kRigid, "\"radius\": 2, \"thickness\": 0.2, \"rings\": 5, \"segments\": 12",
               "\"obj\": \"bowl.obj\", \"position\": [0, 0, -5]");
  std::ofstream(dir / "scene.json") << scene_text;
  const Scene scene = loadScene((dir / "scene.json").string());
  const StaticMesh mesh = makeBowl(*scene.bowl);
  EXPECT_EQ(mesh.vertices.cols(), 4);
  EXPECT_EQ(mesh.triangles.size(), 4u);
  EXPECT_EQ(mesh.vertices.col(3), Eigen::Vector3d(0, 0, -4));
  for (char convex : mesh.convex_edge) EXPECT_TRUE(convex);  // every edge of a tetrahedron
  // A bad face is refused when the scene is loaded, before anything runs: the file, its line,
  // and the scene's key.
  std::ofstream(dir / "bowl.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 7\n";
  try {
    loadScene((dir / "scene.json").string());
    ADD_FAILURE() << "accepted a face index beyond the vertices";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/bowl/obj"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bowl.obj:3"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(SceneLoaderTest, InvalidJsonGivesLineAndColumn) {
  EXPECT_REFUSED(replaced(kValid, "\"substeps\": 4,", "\"substeps\": 4,,"), "test.json",
                 "invalid JSON", "line 3", "column");
  EXPECT_REFUSED("", "invalid JSON", "line 1");
}

TEST(SceneLoaderTest, MissingFile) {
  try {
    loadScene("/nonexistent/scene.json");
    FAIL() << "accepted a missing file";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.json"), std::string::npos);
  }
}

// JSON leaves a name given twice in one object undefined (nlohmann keeps the last): refused,
// with the key's path and both lines, in the root and nested, and not across objects.
TEST(SceneLoaderTest, KeyGivenTwiceIsRefusedWithBothLines) {
  EXPECT_REFUSED(replaced(kValid, "\"duration\": 0.1}", "\"duration\": 0.1,\n  \"step\": 0.02}"),
                 "/time/step", "given twice", "line 3", "line 4");
  EXPECT_REFUSED(replaced(kValid, "\"collision\": {", "\"effects\": [],\n  \"collision\": {"),
                 "/effects", "line 2", "line 7");
  EXPECT_REFUSED(replaced(kValid, "[0.5, 0.5]}", "[0.5, 0.5], \"radii\": [2, 2, 2]}"),
                 "/shapes/0/radii", "line 5", "given twice");
  // The same key in two objects, and a key's name as a string value, are not duplicates.
  const std::string two_bodies =
      replaced(kRigid, "\"fixed\": false}]",
               "\"fixed\": false}, {\"radii\": [0.3, 0.3, 0.3], \"exponents\": [1, 1], "
               "\"position\": [5, 0, 2], \"fixed\": false}]");
  EXPECT_EQ(parseScene(two_bodies, "test.json").rigid_bodies->bodies.size(), 2u);
  parseScene(replaced(kValid, "\"effects\": [",
                      "\"name\": \"time\", \"description\": \"\\\"step\\\": 1, \\\"step\\\": 2\", "
                      "\"effects\": ["),
             "test.json");
}

// nlohmann's reader stops at a NUL byte: a scene followed by one and anything at all would be
// read as the scene alone. Refused where the byte is (found by fuzz_scene_loader: the
// duplicate-key scan went on past it into an unterminated string).
TEST(SceneLoaderTest, ANulByteIsRefusedWhereItIs) {
  const std::string nul(1, '\0');
  EXPECT_REFUSED(kValid + nul + "{\"garbage", "line 8, column 2", "NUL byte");
  EXPECT_REFUSED("2222222222" + nul + nul + "\"\\/\\/22222\xb2", "line 1, column 11", "NUL byte");
}

// What a scene makes the run hold is refused at load time, naming the limit: the steps
// (duration / step: each is recorded), the bodies' tessellations, the bowl's vertices.
TEST(SceneLoaderTest, RunsTooLargeToHoldAreRefusedAtLoadTime) {
  EXPECT_REFUSED(replaced(kValid, "\"step\": 0.01, \"substeps\": 4, \"duration\": 0.1",
                          "\"step\": 1e-300, \"substeps\": 4, \"duration\": 1e6"),
                 "/time/duration", "steps", "at most 1e+07");
  EXPECT_REFUSED(replaced(kValid, "\"step\": 0.01, \"substeps\": 4, \"duration\": 0.1",
                          "\"step\": 1e-5, \"substeps\": 4, \"duration\": 1000"),
                 "/time/duration", "1e+08 steps");
  // At the limit: 1e7 steps exactly.
  parseScene(replaced(kValid, "\"step\": 0.01, \"substeps\": 4, \"duration\": 0.1",
                      "\"step\": 0.0625, \"substeps\": 4, \"duration\": 625000"),
             "test.json");
  EXPECT_REFUSED(replaced(replaced(kRigid, "\"mesh_vertices\": 100", "\"mesh_vertices\": 100000"),
                          "\"count\": 3", "\"count\": 200"),
                 "/rigid_bodies/mesh_vertices", "10000000 vertices", "201 bodies");
  EXPECT_REFUSED(
      replaced(kRigid, "\"rings\": 5, \"segments\": 12", "\"rings\": 1000, \"segments\": 10000"),
      "/bowl/segments", "4000000 vertices");
}

// The runner itself: a bad scene exits non-zero and writes nothing.
TEST(SceneLoaderTest, RunnerRefusesABadSceneAndWritesNothing) {
  const auto dir = std::filesystem::temp_directory_path() / "fse_sim_bad_scene_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto scene = dir / "bad.json";
  std::ofstream(scene) << replaced(kValid, "\"step\": 0.01", "\"step\": -1");
  const auto out = dir / "out";
  const std::string command = std::string(FSE_SIM_BINARY) + " " + scene.string() + " --out " +
                              out.string() + " 2>" + (dir / "stderr.txt").string();
  const int status = std::system(command.c_str());
  EXPECT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_FALSE(std::filesystem::exists(out));
  std::ifstream err(dir / "stderr.txt");
  const std::string message((std::istreambuf_iterator<char>(err)), {});
  EXPECT_NE(message.find("/time/step"), std::string::npos) << message;
  std::filesystem::remove_all(dir);
}

// The same for a run too long to record, set by the scene or by --duration: exit 2, the limit
// named, nothing written (the output folder is not even created).
TEST(SceneLoaderTest, RunnerRefusesARunTooLongAndWritesNothing) {
  const auto dir = std::filesystem::temp_directory_path() / "fse_sim_long_run_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto scene = dir / "long.json";
  std::ofstream(scene) << replaced(kValid, "\"step\": 0.01, \"substeps\": 4, \"duration\": 0.1",
                                   "\"step\": 1e-300, \"substeps\": 4, \"duration\": 1e6");
  const auto good = dir / "good.json";
  std::ofstream(good) << kValid;
  for (const auto& [file, extra, part] :
       std::vector<std::array<std::string, 3>>{{scene.string(), "", "/time/duration"},
                                               {good.string(), " --duration 1e6", "--duration"}}) {
    const auto out = dir / "out";
    const std::string command = std::string(FSE_SIM_BINARY) + " " + file + extra + " --out " +
                                out.string() + " 2>" + (dir / "stderr.txt").string();
    const int status = std::system(command.c_str());
    EXPECT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2) << command;
    EXPECT_FALSE(std::filesystem::exists(out)) << command;
    std::ifstream err(dir / "stderr.txt");
    const std::string message((std::istreambuf_iterator<char>(err)), {});
    EXPECT_NE(message.find(part), std::string::npos) << message;
    EXPECT_NE(message.find("at most 1e+07"), std::string::npos) << message;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace fse_sim
