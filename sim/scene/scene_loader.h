#ifndef FSE_SIM_SCENE_SCENE_LOADER_H
#define FSE_SIM_SCENE_SCENE_LOADER_H

// Scene files: JSON, read strictly (the format, key by key: docs/scenes.md → "Scene files").
// Every mistake is refused with a SceneError that names where it is: line and column for
// JSON that does not parse, the JSON Pointer of the value otherwise.

#include <string>

#include "model/scene.h"
#include "scene/json_reader.h"

namespace fse_sim {

/// Largest cloth the runner accepts (vertices); beyond it a scene is refused, not attempted.
constexpr long kMaxClothVertices = 10000000;
/// Most rigid bodies a scene may have.
constexpr int kMaxRigidBodies = 2000;
/// Most steps a run may take (duration / step): the run keeps a record of every step (about a
/// tenth of a kilobyte) for its files.
constexpr double kMaxSteps = 1e7;
/// Most vertices of the bodies' tessellations together (bodies × rigid_bodies.mesh_vertices):
/// each body keeps its tessellation, and the vertex and mesh models a world copy of it.
constexpr long kMaxBodyMeshVertices = 10000000;
/// Most vertices of a generated bowl (2·(1 + rings·segments)).
constexpr long kMaxBowlVertices = 4000000;

/// Parses scene text. `source` names it in messages (a file name).
/// @throws SceneError for invalid JSON or an invalid scene.
Scene parseScene(const std::string& text, const std::string& source);

/// Refuses a run of more than kMaxSteps steps: the scene's duration over its step. `where`
/// names the duration in the message ("/time/duration", or a command-line option that set it).
/// @throws SceneError naming the steps and the limit.
void checkSteps(const TimeSpec& time, const std::string& where);

/// Reads and parses a scene file (files it names, such as a bowl's OBJ, are relative to it).
/// @throws SceneError also if the file cannot be read.
Scene loadScene(const std::string& path);

}  // namespace fse_sim

#endif  // FSE_SIM_SCENE_SCENE_LOADER_H
