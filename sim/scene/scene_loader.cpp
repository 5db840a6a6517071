#include "scene/scene_loader.h"

#include <fcl_superellipsoid/superellipsoid.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "model/static_mesh.h"
#include "scene/rigid_bodies.h"

namespace fse_sim {
namespace {

using nlohmann::json;

std::string effectList() {
  std::string names;
  for (Effect e : kAllEffects) names += (names.empty() ? "" : ", ") + std::string(toString(e));
  return names;
}

void readTime(ObjectReader& root, Scene& scene) {
  ObjectReader r(root.required("time"), root.pathOf("time"));
  TimeSpec& t = scene.time;
  t.step = r.number("step");
  requireRange(t.step > 0 && t.step <= 1, r.pathOf("step"), "in (0, 1] s", t.step);
  t.substeps = r.integer("substeps", t.substeps);
  requireRange(t.substeps >= 1 && t.substeps <= 1000, r.pathOf("substeps"), "in [1, 1000]",
               t.substeps);
  t.duration = r.number("duration");
  requireRange(t.duration >= t.step && t.duration <= 1e6, r.pathOf("duration"),
               "at least one step and at most 1e6 s", t.duration);
  r.finish();
}

std::pair<double, double> readPair(const json& value, const std::string& path) {
  const auto& array = asArray(value, path);
  if (array.size() != 2) {
    throw SceneError(path + ": must be an array of 2 numbers, got " + std::to_string(array.size()) +
                     " elements");
  }
  return {asNumber(array[0], childPath(path, 0)), asNumber(array[1], childPath(path, 1))};
}

void readCloth(ObjectReader& root, Scene& scene) {
  ObjectReader r(root.required("cloth"), root.pathOf("cloth"));
  ClothSpec& c = scene.cloth;
  const std::string grid_path = r.pathOf("grid");
  const auto& grid = asArray(r.required("grid"), grid_path);
  if (grid.size() != 2) {
    throw SceneError(grid_path + ": must be an array of 2 integers, got " +
                     std::to_string(grid.size()) + " elements");
  }
  c.nx = asInteger(grid[0], childPath(grid_path, 0));
  c.ny = asInteger(grid[1], childPath(grid_path, 1));
  requireRange(c.nx >= 2, childPath(grid_path, 0), "at least 2 vertices", c.nx);
  requireRange(c.ny >= 2, childPath(grid_path, 1), "at least 2 vertices", c.ny);
  requireRange(long(c.nx) * long(c.ny) <= kMaxClothVertices, grid_path,
               "at most " + std::to_string(kMaxClothVertices) + " vertices in all",
               double(c.nx) * double(c.ny));
  std::tie(c.size_x, c.size_y) = readPair(r.required("size"), r.pathOf("size"));
  requireRange(c.size_x > 0 && c.size_x <= 1e6, childPath(r.pathOf("size"), 0), "in (0, 1e6] m",
               c.size_x);
  requireRange(c.size_y > 0 && c.size_y <= 1e6, childPath(r.pathOf("size"), 1), "in (0, 1e6] m",
               c.size_y);
  c.centre = r.vector3("centre");
  requireRange(c.centre.norm() <= 1e6, r.pathOf("centre"), "within 1e6 m of the origin",
               c.centre.norm());
  c.mass = r.number("mass");
  requireRange(c.mass > 0 && c.mass <= 1e9, r.pathOf("mass"), "in (0, 1e9] kg", c.mass);
  c.velocity = r.vector3("velocity", c.velocity);
  requireRange(c.velocity.norm() <= 1e4, r.pathOf("velocity"), "at most 1e4 m/s",
               c.velocity.norm());
  r.finish();
}

/// The library's own checks of a superellipsoid (radii, exponents in (0, 2), aspect ratio),
/// with its message under `path`.
void checkShape(const ShapeSpec& s, const std::string& path) {
  try {
    fcl_superellipsoid::Superellipsoidd(s.radii[0], s.radii[1], s.radii[2], s.eps1, s.eps2);
  } catch (const std::invalid_argument& e) {
    throw SceneError(path + ": " + e.what());
  }
}

void readShapes(ObjectReader& root, Scene& scene) {
  const json* shapes = root.optional("shapes");
  if (shapes == nullptr) return;
  const std::string path = root.pathOf("shapes");
  const auto& array = asArray(*shapes, path);
  for (std::size_t i = 0; i < array.size(); ++i) {
    ObjectReader r(array[i], childPath(path, i));
    ShapeSpec s;
    s.radii = r.vector3("radii");
    std::tie(s.eps1, s.eps2) = readPair(r.required("exponents"), r.pathOf("exponents"));
    s.position = r.vector3("position", s.position);
    requireRange(s.position.norm() <= 1e6, r.pathOf("position"), "within 1e6 m of the origin",
                 s.position.norm());
    s.rotation_deg = r.vector3("rotation_deg", s.rotation_deg);
    r.finish();
    checkShape(s, r.path());
    scene.shapes.push_back(s);
  }
}

void readEffects(ObjectReader& root, Scene& scene) {
  const std::string path = root.pathOf("effects");
  const auto& array = asArray(root.required("effects"), path);
  for (std::size_t i = 0; i < array.size(); ++i) {
    const std::string name = asString(array[i], childPath(path, i));
    const std::optional<Effect> effect = effectNamed(name);
    if (!effect) {
      throw SceneError(childPath(path, i) + ": unknown effect \"" + name +
                       "\" (valid: " + effectList() + ")");
    }
    if (scene.has(*effect)) {
      throw SceneError(childPath(path, i) + ": effect \"" + name + "\" declared twice");
    }
    scene.effects.push_back(*effect);
  }
}

/// The parameter block of `effect`: refused if the effect is not declared; nullptr if the
/// effect is declared without a block (its defaults apply).
const json* effectBlock(ObjectReader& root, const Scene& scene, Effect effect) {
  const json* block = root.optional(toString(effect));
  if (block != nullptr && !scene.has(effect)) {
    std::string declared;
    for (Effect e : scene.effects)
      declared += (declared.empty() ? "" : ", ") + std::string(toString(e));
    throw SceneError(root.pathOf(toString(effect)) +
                     ": parameters for an effect that is not declared in /effects (declared: " +
                     (declared.empty() ? "none" : declared) + ")");
  }
  return block;
}

void readCompliance(ObjectReader& root, Scene& scene, Effect effect,
                    std::optional<ComplianceSpec>& out) {
  const json* block = effectBlock(root, scene, effect);
  if (!scene.has(effect)) return;
  out.emplace();
  if (block == nullptr) return;
  ObjectReader r(*block, root.pathOf(toString(effect)));
  out->compliance = r.number("compliance", out->compliance);
  requireRange(out->compliance >= 0, r.pathOf("compliance"), "≥ 0 m/N", out->compliance);
  r.finish();
}

void checkVertex(int vertex, const Scene& scene, const std::string& path) {
  const long n = long(scene.cloth.nx) * scene.cloth.ny;
  requireRange(vertex >= 0 && vertex < n, path,
               "a cloth vertex index in [0, " + std::to_string(n - 1) + "]", vertex);
}

void readPinning(ObjectReader& root, Scene& scene) {
  const json* block = effectBlock(root, scene, Effect::kPinning);
  if (!scene.has(Effect::kPinning)) return;
  scene.pinning.emplace();
  if (block == nullptr) return;
  ObjectReader r(*block, root.pathOf("pinning"));
  if (const json* fixed = r.optional("fixed")) {
    const auto& array = asArray(*fixed, r.pathOf("fixed"));
    for (std::size_t i = 0; i < array.size(); ++i) {
      const std::string p = childPath(r.pathOf("fixed"), i);
      const int v = asInteger(array[i], p);
      checkVertex(v, scene, p);
      scene.pinning->fixed.push_back(v);
    }
  }
  if (const json* attached = r.optional("attached")) {
    const auto& array = asArray(*attached, r.pathOf("attached"));
    for (std::size_t i = 0; i < array.size(); ++i) {
      ObjectReader a(array[i], childPath(r.pathOf("attached"), i));
      AttachmentSpec spec;
      spec.vertex = a.integer("vertex");
      checkVertex(spec.vertex, scene, a.pathOf("vertex"));
      spec.target = a.vector3("target");
      requireRange(spec.target.norm() <= 1e6, a.pathOf("target"), "within 1e6 m of the origin",
                   spec.target.norm());
      spec.compliance = a.number("compliance", 0);
      requireRange(spec.compliance >= 0, a.pathOf("compliance"), "≥ 0 m/N", spec.compliance);
      a.finish();
      scene.pinning->attached.push_back(spec);
    }
  }
  r.finish();
}

std::pair<double, double> readRange(ObjectReader& r, const std::string& key,
                                    std::pair<double, double> fallback) {
  const json* value = r.optional(key);
  if (value == nullptr) return fallback;
  const auto range = readPair(*value, r.pathOf(key));
  requireRange(range.first <= range.second, r.pathOf(key), "an interval [low, high], low ≤ high",
               range.first - range.second);
  return range;
}

void readBodyGenerator(ObjectReader& parent, RigidBodiesSpec& spec) {
  const json* block = parent.optional("generate");
  if (block == nullptr) return;
  ObjectReader r(*block, parent.pathOf("generate"));
  BodyGenerator g;
  g.count = r.integer("count");
  requireRange(g.count >= 0 && g.count <= kMaxRigidBodies, r.pathOf("count"),
               "in [0, " + std::to_string(kMaxRigidBodies) + "]", g.count);
  const int seed = r.integer("seed", 1);
  requireRange(seed >= 0, r.pathOf("seed"), "≥ 0", seed);
  g.seed = unsigned(seed);
  g.radii = readRange(r, "radii", g.radii);
  g.exponents = readRange(r, "exponents", g.exponents);
  g.start = r.vector3("start", g.start);
  requireRange(g.start.norm() <= 1e6, r.pathOf("start"), "within 1e6 m of the origin",
               g.start.norm());
  g.helix_radius = r.number("helix_radius", g.helix_radius);
  requireRange(g.helix_radius >= 0 && g.helix_radius <= 1e6, r.pathOf("helix_radius"),
               "in [0, 1e6] m", g.helix_radius);
  g.turn_deg = r.number("turn_deg", g.turn_deg);
  requireRange(std::abs(g.turn_deg) <= 360, r.pathOf("turn_deg"), "in [-360, 360] degrees",
               g.turn_deg);
  g.rise = r.number("rise", g.rise);
  requireRange(std::abs(g.rise) * g.count <= 1e6, r.pathOf("rise"),
               "at most 1e6 m for the whole chain", std::abs(g.rise) * g.count);
  r.finish();
  // The extremes of the ranges are shapes the generator can draw: the library checks them.
  for (double radius : {g.radii.first, g.radii.second}) {
    for (double eps : {g.exponents.first, g.exponents.second}) {
      ShapeSpec s;
      s.radii.setConstant(radius);
      s.eps1 = s.eps2 = eps;
      checkShape(s, r.path());
    }
  }
  spec.generate = g;
}

void readRigidBodies(ObjectReader& root, Scene& scene) {
  const json* block = effectBlock(root, scene, Effect::kRigidBodies);
  if (!scene.has(Effect::kRigidBodies)) return;
  if (block == nullptr) {
    throw SceneError(root.pathOf("rigid_bodies") +
                     ": \"rigid_bodies\" is declared but has no block (its bodies are listed "
                     "there, under \"bodies\" or \"generate\")");
  }
  RigidBodiesSpec& spec = scene.rigid_bodies.emplace();
  ObjectReader r(*block, root.pathOf("rigid_bodies"));
  spec.density = r.number("density", spec.density);
  requireRange(spec.density > 0 && spec.density <= 1e6, r.pathOf("density"), "in (0, 1e6] kg/m³",
               spec.density);
  spec.mesh_vertices = r.integer("mesh_vertices", spec.mesh_vertices);
  requireRange(spec.mesh_vertices >= 6 && spec.mesh_vertices <= 100000, r.pathOf("mesh_vertices"),
               "in [6, 100000]", spec.mesh_vertices);
  if (const json* bodies = r.optional("bodies")) {
    const std::string path = r.pathOf("bodies");
    const auto& array = asArray(*bodies, path);
    requireRange(array.size() <= std::size_t(kMaxRigidBodies), path,
                 "at most " + std::to_string(kMaxRigidBodies) + " bodies", double(array.size()));
    for (std::size_t i = 0; i < array.size(); ++i) {
      ObjectReader b(array[i], childPath(path, i));
      BodySpec body;
      ShapeSpec& s = body.shape;
      s.radii = b.vector3("radii");
      std::tie(s.eps1, s.eps2) = readPair(b.required("exponents"), b.pathOf("exponents"));
      s.position = b.vector3("position", s.position);
      requireRange(s.position.norm() <= 1e6, b.pathOf("position"), "within 1e6 m of the origin",
                   s.position.norm());
      s.rotation_deg = b.vector3("rotation_deg", s.rotation_deg);
      body.velocity = b.vector3("velocity", body.velocity);
      requireRange(body.velocity.norm() <= 1e4, b.pathOf("velocity"), "at most 1e4 m/s",
                   body.velocity.norm());
      body.angular_velocity = b.vector3("angular_velocity", body.angular_velocity);
      requireRange(body.angular_velocity.norm() <= 1e4, b.pathOf("angular_velocity"),
                   "at most 1e4 rad/s", body.angular_velocity.norm());
      if (const json* fixed = b.optional("fixed")) {
        if (!fixed->is_boolean()) {
          throw SceneError(b.pathOf("fixed") + ": must be true or false, got " + fixed->dump());
        }
        body.fixed = fixed->get<bool>();
      }
      b.finish();
      checkShape(s, b.path());
      spec.bodies.push_back(body);
    }
  }
  readBodyGenerator(r, spec);
  r.finish();
  const long total = long(spec.bodies.size()) + (spec.generate ? spec.generate->count : 0);
  requireRange(total >= 1 && total <= kMaxRigidBodies, r.path(),
               "between 1 and " + std::to_string(kMaxRigidBodies) +
                   " bodies (listed under \"bodies\" and generated)",
               double(total));
  // Every body keeps its tessellation: the loader refuses what the run could not hold.
  requireRange(double(total) * spec.mesh_vertices <= double(kMaxBodyMeshVertices),
               r.pathOf("mesh_vertices"),
               "at most " + std::to_string(kMaxBodyMeshVertices) + " vertices for all " +
                   std::to_string(total) + " bodies' tessellations together",
               spec.mesh_vertices);
  checkBodiesApart(spec, r.path());
}

void readBowl(ObjectReader& root, Scene& scene, const std::string& directory) {
  const json* block = root.optional("bowl");
  if (block == nullptr) return;
  if (!scene.isRigid()) {
    throw SceneError(root.pathOf("bowl") + ": a bowl needs \"rigid_bodies\" declared in /effects");
  }
  ObjectReader r(*block, root.pathOf("bowl"));
  BowlSpec& bowl = scene.bowl.emplace();
  bowl.position = r.vector3("position", bowl.position);
  requireRange(bowl.position.norm() <= 1e6, r.pathOf("position"), "within 1e6 m of the origin",
               bowl.position.norm());
  if (const json* obj = r.optional("obj")) {
    bowl.obj = asString(*obj, r.pathOf("obj"));
    if (bowl.obj.empty()) throw SceneError(r.pathOf("obj") + ": must be a file name, got \"\"");
    // Relative to the scene file, as a user who writes "bowl.obj" beside it means.
    if (bowl.obj.front() != '/' && !directory.empty()) bowl.obj = directory + "/" + bowl.obj;
    for (const char* key : {"radius", "thickness", "rings", "segments"}) {
      if (r.optional(key) != nullptr) {
        throw SceneError(r.pathOf(key) + ": a bowl read from \"obj\" takes no generated size");
      }
    }
    // Read now, so that a bad file is refused before anything runs or is written.
    try {
      makeBowl(bowl);
    } catch (const SceneError& e) {
      throw SceneError(r.pathOf("obj") + ": " + e.what());
    }
  } else {
    bowl.radius = r.number("radius", bowl.radius);
    requireRange(bowl.radius > 0 && bowl.radius <= 1e6, r.pathOf("radius"), "in (0, 1e6] m",
                 bowl.radius);
    bowl.thickness = r.number("thickness", bowl.thickness);
    requireRange(bowl.thickness > 0 && bowl.thickness <= bowl.radius, r.pathOf("thickness"),
                 "in (0, radius] m", bowl.thickness);
    bowl.rings = r.integer("rings", bowl.rings);
    requireRange(bowl.rings >= 2 && bowl.rings <= 1000, r.pathOf("rings"), "in [2, 1000]",
                 bowl.rings);
    bowl.segments = r.integer("segments", bowl.segments);
    requireRange(bowl.segments >= 3 && bowl.segments <= 10000, r.pathOf("segments"),
                 "in [3, 10000]", bowl.segments);
    const long vertices = 2 * (1 + long(bowl.rings) * long(bowl.segments));
    requireRange(vertices <= kMaxBowlVertices, r.pathOf("segments"),
                 "rings × segments of at most " + std::to_string(kMaxBowlVertices) +
                     " vertices in all (2·(1 + rings·segments))",
                 bowl.segments);
  }
  r.finish();
}

void readEffectBlocks(ObjectReader& root, Scene& scene) {
  if (const json* block = effectBlock(root, scene, Effect::kGravity); scene.has(Effect::kGravity)) {
    scene.gravity.emplace();
    if (block != nullptr) {
      ObjectReader r(*block, root.pathOf("gravity"));
      scene.gravity->acceleration = r.vector3("acceleration", scene.gravity->acceleration);
      requireRange(scene.gravity->acceleration.norm() <= 1e4, r.pathOf("acceleration"),
                   "at most 1e4 m/s²", scene.gravity->acceleration.norm());
      r.finish();
    }
  }
  readCompliance(root, scene, Effect::kStretch, scene.stretch);
  readCompliance(root, scene, Effect::kBending, scene.bending);
  readPinning(root, scene);
  if (const json* block = effectBlock(root, scene, Effect::kCollision);
      scene.has(Effect::kCollision)) {
    scene.collision.emplace();
    if (block != nullptr) {
      ObjectReader r(*block, root.pathOf("collision"));
      scene.collision->tolerance = r.number("tolerance", scene.collision->tolerance);
      requireRange(scene.collision->tolerance > 0 && scene.collision->tolerance <= 1e3,
                   r.pathOf("tolerance"), "in (0, 1e3] m", scene.collision->tolerance);
      r.finish();
    }
  }
  if (const json* block = effectBlock(root, scene, Effect::kFriction);
      scene.has(Effect::kFriction)) {
    if (!scene.has(Effect::kCollision) && !scene.has(Effect::kRigidContact)) {
      throw SceneError(
          "/effects: \"friction\" acts at contacts and needs \"collision\" or \"rigid_contact\" "
          "declared");
    }
    scene.friction.emplace();
    if (block != nullptr) {
      ObjectReader r(*block, root.pathOf("friction"));
      scene.friction->dynamic = r.number("dynamic", scene.friction->dynamic);
      requireRange(scene.friction->dynamic >= 0 && scene.friction->dynamic <= 100,
                   r.pathOf("dynamic"), "in [0, 100]", scene.friction->dynamic);
      scene.friction->static_ = r.number("static", scene.friction->static_);
      requireRange(scene.friction->static_ >= 0 && scene.friction->static_ <= 100,
                   r.pathOf("static"), "in [0, 100]", scene.friction->static_);
      r.finish();
    }
  }
  if (const json* block = effectBlock(root, scene, Effect::kDamping); scene.has(Effect::kDamping)) {
    scene.damping.emplace();
    if (block != nullptr) {
      ObjectReader r(*block, root.pathOf("damping"));
      scene.damping->linear = r.number("linear", scene.damping->linear);
      requireRange(scene.damping->linear >= 0 && scene.damping->linear <= 1e6, r.pathOf("linear"),
                   "in [0, 1e6] 1/s", scene.damping->linear);
      r.finish();
    }
  }
  if (const json* block = effectBlock(root, scene, Effect::kRigidContact);
      scene.has(Effect::kRigidContact)) {
    if (!scene.has(Effect::kRigidBodies)) {
      throw SceneError(
          "/effects: \"rigid_contact\" acts between rigid bodies and needs "
          "\"rigid_bodies\" declared");
    }
    scene.rigid_contact.emplace();
    if (block != nullptr) {
      ObjectReader r(*block, root.pathOf("rigid_contact"));
      scene.rigid_contact->tolerance = r.number("tolerance", scene.rigid_contact->tolerance);
      requireRange(scene.rigid_contact->tolerance > 0 && scene.rigid_contact->tolerance <= 1e3,
                   r.pathOf("tolerance"), "in (0, 1e3] m", scene.rigid_contact->tolerance);
      r.finish();
    }
  }
  if (const json* block = effectBlock(root, scene, Effect::kRestitution);
      scene.has(Effect::kRestitution)) {
    if (!scene.has(Effect::kRigidContact)) {
      throw SceneError(
          "/effects: \"restitution\" acts at contacts and needs \"rigid_contact\" "
          "declared");
    }
    scene.restitution.emplace();
    if (block != nullptr) {
      ObjectReader r(*block, root.pathOf("restitution"));
      scene.restitution->coefficient = r.number("coefficient", scene.restitution->coefficient);
      requireRange(scene.restitution->coefficient >= 0 && scene.restitution->coefficient <= 1,
                   r.pathOf("coefficient"), "in [0, 1]", scene.restitution->coefficient);
      r.finish();
    }
  }
  if (scene.has(Effect::kCollision) && scene.shapes.empty()) {
    throw SceneError("/shapes: \"collision\" is declared but the scene has no shapes");
  }
}

/// A rigid-body scene has no cloth: the cloth's blocks and effects are refused there.
void refuseClothInRigidScene(ObjectReader& root, const Scene& scene) {
  for (const char* key : {"cloth", "shapes"}) {
    if (root.optional(key) != nullptr) {
      throw SceneError(root.pathOf(key) +
                       ": a \"rigid_bodies\" scene has no cloth and no fixed shapes (a fixed "
                       "body is a body with \"fixed\": true)");
    }
  }
  for (Effect e : {Effect::kStretch, Effect::kBending, Effect::kPinning, Effect::kCollision}) {
    if (scene.has(e)) {
      throw SceneError(std::string("/effects: \"") + toString(e) +
                       "\" acts on a cloth, and a \"rigid_bodies\" scene has none");
    }
  }
}

/// The folder of a file's path ("" for a bare name): where the files a scene names are.
std::string directoryOf(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? "" : path.substr(0, slash);
}

Scene parseSceneIn(const std::string& text, const std::string& source,
                   const std::string& directory) {
  // A NUL byte ends nlohmann's input: what follows would be ignored, not read. JSON text has
  // none, so a file with one is refused where it is.
  if (const auto nul = text.find('\0'); nul != std::string::npos) {
    const long line = 1 + std::count(text.begin(), text.begin() + long(nul), '\n');
    const auto line_start = text.rfind('\n', nul);
    const long column = long(nul - (line_start == std::string::npos ? 0 : line_start + 1)) + 1;
    throw SceneError(source + ": invalid JSON at line " + std::to_string(line) + ", column " +
                     std::to_string(column) + ": a NUL byte");
  }
  json document;
  try {
    document = json::parse(text);
  } catch (const json::parse_error& e) {
    // nlohmann's message says "parse error at line L, column C: ...".
    std::string what = e.what();
    const auto at = what.find("parse error");
    throw SceneError(source +
                     ": invalid JSON: " + (at == std::string::npos ? what : what.substr(at)));
  } catch (const json::out_of_range& e) {
    // A number literal beyond double's range ("1e999"): nlohmann names the literal, not where
    // it is; find it in the text.
    const std::string what = e.what();
    const auto quote = what.find('\'');
    const std::string literal =
        quote == std::string::npos ? "" : what.substr(quote + 1, what.rfind('\'') - quote - 1);
    const auto at = literal.empty() ? std::string::npos : text.find(literal);
    std::string where;
    if (at != std::string::npos) {
      const long line = 1 + std::count(text.begin(), text.begin() + long(at), '\n');
      const auto line_start = text.rfind('\n', at);
      const long column = long(at - (line_start == std::string::npos ? 0 : line_start + 1)) + 1;
      where = " at line " + std::to_string(line) + ", column " + std::to_string(column);
    }
    throw SceneError(source + ": invalid JSON" + where + ": " + literal +
                     " is not a finite number");
  }
  try {
    refuseDuplicateKeys(text);
    Scene scene;
    ObjectReader root(document, "");
    scene.name = root.string("name", "");
    scene.description = root.string("description", "");
    readEffects(root, scene);
    readTime(root, scene);
    if (scene.has(Effect::kRigidBodies)) {
      refuseClothInRigidScene(root, scene);
      readRigidBodies(root, scene);
      readBowl(root, scene, directory);
    } else {
      readCloth(root, scene);
      readShapes(root, scene);
      readBowl(root, scene, directory);  // refused: no rigid bodies
    }
    readEffectBlocks(root, scene);
    root.finish();
    checkSteps(scene.time, "/time/duration");
    return scene;
  } catch (const SceneError& e) {
    throw SceneError(source + ": " + e.what());
  }
}

}  // namespace

void checkSteps(const TimeSpec& time, const std::string& where) {
  const double steps = time.duration / time.step;
  if (!(steps <= kMaxSteps)) {
    std::ostringstream message;
    message << where << ": " << time.duration << " s at a step of " << time.step << " s is "
            << steps << " steps; a run takes at most " << kMaxSteps
            << " (it keeps a record of every step): shorten the duration or lengthen the step";
    throw SceneError(message.str());
  }
}

Scene parseScene(const std::string& text, const std::string& source) {
  return parseSceneIn(text, source, "");
}

Scene loadScene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot read the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path + ": cannot read the scene file");
  return parseSceneIn(text.str(), path, directoryOf(path));
}

}  // namespace fse_sim
