#include "scene/json_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

namespace fse_sim {
namespace {

std::string typeName(const nlohmann::json& value) {
  if (value.is_number_integer() || value.is_number_unsigned()) return "an integer";
  if (value.is_number()) return "a number";
  return std::string("a") + (value.is_array() || value.is_object() ? "n " : " ") +
         value.type_name();
}

[[noreturn]] void wrongType(const nlohmann::json& value, const std::string& path,
                            const std::string& expected) {
  throw SceneError(path + ": must be " + expected + ", got " + typeName(value));
}

std::string formatNumber(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

}  // namespace

namespace {

/// One open object or array while scanning, and what its members were.
struct Frame {
  bool object = false;
  std::string path;
  std::map<std::string, long> key_lines;  // objects: each key's line
  std::size_t index = 0;                  // arrays: the element being read
  std::string key;                        // objects: the member being read
};

/// The JSON string literal at text[at] (at its opening quote), decoded, and the index past it.
/// The text has parsed, so the literal is complete and valid; were it not, the raw characters
/// stand for it (no key of the parsed document can then be confused with it).
std::pair<std::string, std::size_t> stringAt(const std::string& text, std::size_t at) {
  std::size_t end = at + 1;
  while (end < text.size() && text[end] != '"') end += text[end] == '\\' ? 2 : 1;
  if (end >= text.size()) return {text.substr(at), text.size()};
  const std::string literal = text.substr(at, end + 1 - at);
  const auto decoded = nlohmann::json::parse(literal, nullptr, false);
  if (!decoded.is_string()) return {literal, end + 1};
  return {decoded.get<std::string>(), end + 1};
}

}  // namespace

void refuseDuplicateKeys(const std::string& text) {
  std::vector<Frame> open;
  long line = 1;
  // The path of the value that starts next: in an object, its key's; in an array, its index's.
  auto valuePath = [&]() -> std::string {
    if (open.empty()) return "";
    const Frame& f = open.back();
    return f.object ? childPath(f.path, f.key) : childPath(f.path, f.index);
  };
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '\n') ++line;
    if (c == '{' || c == '[') {
      Frame frame;
      frame.object = c == '{';
      frame.path = valuePath();
      open.push_back(std::move(frame));
      ++i;
    } else if (c == '}' || c == ']') {
      open.pop_back();
      ++i;
    } else if (c == ',') {
      if (!open.empty() && !open.back().object) ++open.back().index;
      ++i;
    } else if (c == '"') {
      auto [value, next] = stringAt(text, i);
      line += std::count(text.begin() + long(i), text.begin() + long(next), '\n');
      const long key_line = line;
      std::size_t after = next;
      while (after < text.size() && std::isspace(static_cast<unsigned char>(text[after]))) {
        if (text[after] == '\n') ++line;
        ++after;
      }
      if (!open.empty() && open.back().object && after < text.size() && text[after] == ':') {
        Frame& f = open.back();
        const auto [seen, inserted] = f.key_lines.emplace(value, key_line);
        if (!inserted) {
          throw SceneError(
              childPath(f.path, value) + ": the key is given twice in one object, on line " +
              std::to_string(seen->second) + " and on line " + std::to_string(key_line));
        }
        f.key = value;
        i = after + 1;
      } else {
        i = after;
      }
    } else {
      ++i;
    }
  }
}

std::string childPath(const std::string& path, const std::string& key) {
  std::string escaped;
  for (char c : key) {
    if (c == '~') {
      escaped += "~0";
    } else if (c == '/') {
      escaped += "~1";
    } else {
      escaped += c;
    }
  }
  return path + "/" + escaped;
}

std::string childPath(const std::string& path, std::size_t index) {
  return path + "/" + std::to_string(index);
}

ObjectReader::ObjectReader(const nlohmann::json& value, std::string path)
    : value_(value), path_(std::move(path)) {
  if (!value_.is_object()) wrongType(value_, path_.empty() ? "/" : path_, "an object");
}

const nlohmann::json& ObjectReader::required(const std::string& key) {
  const nlohmann::json* member = optional(key);
  if (member == nullptr) throw SceneError(pathOf(key) + ": missing (required)");
  return *member;
}

const nlohmann::json* ObjectReader::optional(const std::string& key) {
  auto it = value_.find(key);
  if (it == value_.end()) return nullptr;
  read_.insert(key);
  return &*it;
}

double ObjectReader::number(const std::string& key) { return asNumber(required(key), pathOf(key)); }
double ObjectReader::number(const std::string& key, double fallback) {
  const nlohmann::json* member = optional(key);
  return member ? asNumber(*member, pathOf(key)) : fallback;
}
int ObjectReader::integer(const std::string& key) { return asInteger(required(key), pathOf(key)); }
int ObjectReader::integer(const std::string& key, int fallback) {
  const nlohmann::json* member = optional(key);
  return member ? asInteger(*member, pathOf(key)) : fallback;
}
std::string ObjectReader::string(const std::string& key, const std::string& fallback) {
  const nlohmann::json* member = optional(key);
  return member ? asString(*member, pathOf(key)) : fallback;
}
Eigen::Vector3d ObjectReader::vector3(const std::string& key) {
  return asVector3(required(key), pathOf(key));
}
Eigen::Vector3d ObjectReader::vector3(const std::string& key, const Eigen::Vector3d& fallback) {
  const nlohmann::json* member = optional(key);
  return member ? asVector3(*member, pathOf(key)) : fallback;
}

void ObjectReader::finish() const {
  for (auto it = value_.begin(); it != value_.end(); ++it) {
    if (read_.count(it.key())) continue;
    std::string valid;
    for (const std::string& key : read_) valid += (valid.empty() ? "" : ", ") + key;
    throw SceneError(pathOf(it.key()) + ": unknown key" +
                     (valid.empty() ? std::string() : " (keys read here: " + valid + ")"));
  }
}

double asNumber(const nlohmann::json& value, const std::string& path) {
  if (!value.is_number()) wrongType(value, path, "a number");
  const double x = value.get<double>();
  // JSON has no NaN or infinity, but a literal like 1e999 parses to infinity.
  requireRange(std::isfinite(x), path, "finite", x);
  return x;
}

int asInteger(const nlohmann::json& value, const std::string& path) {
  if (value.is_number_unsigned()) {
    const auto x = value.get<std::uint64_t>();
    if (x > std::uint64_t(std::numeric_limits<int>::max())) {
      throw SceneError(path + ": must be an integer of at most " +
                       std::to_string(std::numeric_limits<int>::max()) + ", got " +
                       std::to_string(x));
    }
    return int(x);
  }
  if (!value.is_number_integer()) wrongType(value, path, "an integer");
  const auto x = value.get<std::int64_t>();
  if (x < std::numeric_limits<int>::min() || x > std::numeric_limits<int>::max()) {
    throw SceneError(path + ": must be an integer that fits in 32 bits, got " + std::to_string(x));
  }
  return int(x);
}

std::string asString(const nlohmann::json& value, const std::string& path) {
  if (!value.is_string()) wrongType(value, path, "a string");
  return value.get<std::string>();
}

const nlohmann::json::array_t& asArray(const nlohmann::json& value, const std::string& path) {
  if (!value.is_array()) wrongType(value, path, "an array");
  return value.get_ref<const nlohmann::json::array_t&>();
}

Eigen::Vector3d asVector3(const nlohmann::json& value, const std::string& path) {
  const auto& array = asArray(value, path);
  if (array.size() != 3) {
    throw SceneError(path + ": must be an array of 3 numbers, got " + std::to_string(array.size()) +
                     " elements");
  }
  Eigen::Vector3d v;
  for (std::size_t i = 0; i < 3; ++i) v[Eigen::Index(i)] = asNumber(array[i], childPath(path, i));
  return v;
}

void requireRange(bool ok, const std::string& path, const std::string& requirement, double value) {
  if (!ok) throw SceneError(path + ": must be " + requirement + ", got " + formatNumber(value));
}

}  // namespace fse_sim
