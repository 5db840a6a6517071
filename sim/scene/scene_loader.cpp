#include "scene/scene_loader.h"

#include <fcl_superellipsoid/superellipsoid.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

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
    // The library's own checks (radii, exponents in (0, 2), aspect ratio), with its message.
    try {
      fcl_superellipsoid::Superellipsoidd(s.radii[0], s.radii[1], s.radii[2], s.eps1, s.eps2);
    } catch (const std::invalid_argument& e) {
      throw SceneError(r.path() + ": " + e.what());
    }
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
    if (!scene.has(Effect::kCollision)) {
      throw SceneError("/effects: \"friction\" acts at contacts and needs \"collision\" declared");
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
  if (scene.has(Effect::kCollision) && scene.shapes.empty()) {
    throw SceneError("/shapes: \"collision\" is declared but the scene has no shapes");
  }
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& source) {
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
    Scene scene;
    ObjectReader root(document, "");
    scene.name = root.string("name", "");
    scene.description = root.string("description", "");
    readEffects(root, scene);
    readTime(root, scene);
    readCloth(root, scene);
    readShapes(root, scene);
    readEffectBlocks(root, scene);
    root.finish();
    return scene;
  } catch (const SceneError& e) {
    throw SceneError(source + ": " + e.what());
  }
}

Scene loadScene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot read the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path + ": cannot read the scene file");
  return parseScene(text.str(), path);
}

}  // namespace fse_sim
