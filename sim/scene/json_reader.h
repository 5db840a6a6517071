#ifndef FSE_SIM_SCENE_JSON_READER_H
#define FSE_SIM_SCENE_JSON_READER_H

// Strict reading of one JSON object: every key is either read or refused. Errors name the
// value by its JSON Pointer (RFC 6901, "/cloth/grid/1") so that a user finds it in the file.

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/scene.h"

namespace fse_sim {

/// Refuses a key given twice in one object of `text` (JSON that parses: nlohmann keeps the last
/// one silently, and JSON leaves duplicate names undefined).
/// @throws SceneError naming the key by its JSON Pointer and the lines of both.
void refuseDuplicateKeys(const std::string& text);

/// The path of member `key` of the object at `path`, JSON Pointer escaping applied.
std::string childPath(const std::string& path, const std::string& key);
std::string childPath(const std::string& path, std::size_t index);

/// Reads the members of one JSON object. Call finish() after the last read: it refuses the
/// members nobody asked for.
class ObjectReader {
 public:
  /// @throws SceneError if `value` is not an object.
  ObjectReader(const nlohmann::json& value, std::string path);

  /// The member `key`, which must exist.
  const nlohmann::json& required(const std::string& key);
  /// The member `key`, or nullptr.
  const nlohmann::json* optional(const std::string& key);

  double number(const std::string& key);                   ///< required, finite
  double number(const std::string& key, double fallback);  ///< optional, finite
  int integer(const std::string& key);                     ///< required
  int integer(const std::string& key, int fallback);       ///< optional
  std::string string(const std::string& key, const std::string& fallback);
  Eigen::Vector3d vector3(const std::string& key);  ///< required
  Eigen::Vector3d vector3(const std::string& key, const Eigen::Vector3d& fallback);

  /// Refuses the first member that was not read, naming its path and the valid keys.
  void finish() const;

  const std::string& path() const { return path_; }
  std::string pathOf(const std::string& key) const { return childPath(path_, key); }

 private:
  const nlohmann::json& value_;
  std::string path_;
  std::set<std::string> read_;
};

/// Typed conversions of a single value at `path`; each refuses a wrong type or a non-finite
/// number with a SceneError naming the path and what was expected.
double asNumber(const nlohmann::json& value, const std::string& path);
int asInteger(const nlohmann::json& value, const std::string& path);
std::string asString(const nlohmann::json& value, const std::string& path);
Eigen::Vector3d asVector3(const nlohmann::json& value, const std::string& path);
/// An array's elements, refusing a non-array.
const nlohmann::json::array_t& asArray(const nlohmann::json& value, const std::string& path);

/// Range checks: a SceneError "PATH: must be REQUIREMENT, got VALUE".
void requireRange(bool ok, const std::string& path, const std::string& requirement, double value);

}  // namespace fse_sim

#endif  // FSE_SIM_SCENE_JSON_READER_H
