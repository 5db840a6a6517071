#include "point_cloud_file.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace fse_fit {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what, long line = 0) {
  throw CloudFileError(path + (line > 0 ? ":" + std::to_string(line) : "") + ": " + what);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string extensionOf(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return lower(path.substr(dot + 1));
}

void checkPoint(const std::string& path, const Eigen::Vector3d& p, long index, long line) {
  if (!p.allFinite()) {
    std::ostringstream what;
    what << "point " << index << " is not finite: (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
    fail(path, what.str(), line);
  }
}

std::vector<Eigen::Vector3d> readXyz(const std::string& path, std::istream& in) {
  std::vector<Eigen::Vector3d> points;
  std::string text;
  long line = 0;
  while (std::getline(in, text)) {
    ++line;
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    std::istringstream fields(text);
    Eigen::Vector3d p;
    std::string token;
    for (int i = 0; i < 3; ++i) {
      if (!(fields >> token)) fail(path, "expected three numbers x y z, got '" + text + "'", line);
      char* end = nullptr;
      p[i] = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') {
        fail(path, "expected a number, got '" + token + "'", line);
      }
    }
    checkPoint(path, p, static_cast<long>(points.size()), line);
    points.push_back(p);
  }
  return points;
}

// One PLY scalar type: its size in bytes.
int plyTypeSize(const std::string& type) {
  static const std::map<std::string, int> sizes = {
      {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

// A binary PLY scalar of `type` at `bytes`, converted to double.
double plyValue(const std::string& type, const unsigned char* bytes, bool swap) {
  std::array<unsigned char, 8> b{};
  const int size = plyTypeSize(type);
  std::memcpy(b.data(), bytes, size);
  if (swap) std::reverse(b.begin(), b.begin() + size);
  auto as = [&](auto value) {
    std::memcpy(&value, b.data(), sizeof(value));
    return static_cast<double>(value);
  };
  if (type == "char" || type == "int8") return as(std::int8_t{});
  if (type == "uchar" || type == "uint8") return as(std::uint8_t{});
  if (type == "short" || type == "int16") return as(std::int16_t{});
  if (type == "ushort" || type == "uint16") return as(std::uint16_t{});
  if (type == "int" || type == "int32") return as(std::int32_t{});
  if (type == "uint" || type == "uint32") return as(std::uint32_t{});
  if (type == "float" || type == "float32") return as(float{});
  return as(double{});
}

struct PlyElement {
  std::string name;
  long count = 0;
  std::vector<std::pair<std::string, std::string>> properties;  // (type, name)
  bool has_list = false;
};

std::vector<Eigen::Vector3d> readPly(const std::string& path, std::istream& in) {
  std::string text;
  long line = 0;
  auto next = [&]() -> bool {
    if (!std::getline(in, text)) return false;
    ++line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    return true;
  };
  if (!next() || text != "ply") fail(path, "not a PLY file: the first line is not 'ply'", 1);
  std::string format;
  std::vector<PlyElement> elements;
  for (;;) {
    if (!next()) fail(path, "the header has no 'end_header'", line);
    std::istringstream fields(text);
    std::string keyword;
    fields >> keyword;
    if (keyword == "end_header") break;
    if (keyword == "comment" || keyword == "obj_info" || keyword.empty()) continue;
    if (keyword == "format") {
      std::string version;
      fields >> format >> version;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian") {
        fail(path, "unknown PLY format '" + format + "'", line);
      }
    } else if (keyword == "element") {
      PlyElement e;
      if (!(fields >> e.name >> e.count) || e.count < 0) {
        fail(path, "expected 'element NAME COUNT', got '" + text + "'", line);
      }
      elements.push_back(e);
    } else if (keyword == "property") {
      if (elements.empty()) fail(path, "a property before any element", line);
      std::string type, name;
      fields >> type;
      if (type == "list") {
        elements.back().has_list = true;
        std::string count_type, item_type;
        fields >> count_type >> item_type >> name;
        if (plyTypeSize(count_type) == 0 || plyTypeSize(item_type) == 0) {
          fail(path, "unknown PLY type in '" + text + "'", line);
        }
        type = "list " + count_type + " " + item_type;
      } else {
        fields >> name;
        if (plyTypeSize(type) == 0) fail(path, "unknown PLY type '" + type + "'", line);
      }
      elements.back().properties.emplace_back(type, name);
    } else {
      fail(path, "unknown header line '" + text + "'", line);
    }
  }
  if (format.empty()) fail(path, "the header has no 'format' line", line);
  const auto vertex = std::find_if(elements.begin(), elements.end(),
                                   [](const PlyElement& e) { return e.name == "vertex"; });
  if (vertex == elements.end()) fail(path, "no 'vertex' element");
  std::array<int, 3> xyz = {-1, -1, -1};
  for (int i = 0; i < static_cast<int>(vertex->properties.size()); ++i) {
    const std::string& name = vertex->properties[i].second;
    if (name.size() == 1 && name[0] >= 'x' && name[0] <= 'z') xyz[name[0] - 'x'] = i;
  }
  if (*std::min_element(xyz.begin(), xyz.end()) < 0) {
    fail(path, "the vertex element lacks one of the properties x, y, z");
  }
  if (vertex->has_list) fail(path, "a list property in the vertex element is not supported");
  for (auto e = elements.begin(); e != vertex; ++e) {
    if (e->count > 0 && (e->has_list && format != "ascii")) {
      fail(path, "element '" + e->name + "' before the vertices has a list property");
    }
  }
  std::vector<Eigen::Vector3d> points;
  const long count = vertex->count;
  if (format == "ascii") {
    for (auto e = elements.begin(); e != vertex; ++e) {
      for (long i = 0; i < e->count; ++i) {
        if (!next()) fail(path, "the file ends inside element '" + e->name + "'", line);
      }
    }
    for (long i = 0; i < count; ++i) {
      if (!next())
        fail(path,
             "the file ends after " + std::to_string(i) + " of " + std::to_string(count) +
                 " vertices",
             line);
      std::istringstream fields(text);
      std::vector<double> values;
      std::string token;
      while (fields >> token) {
        char* end = nullptr;
        const double v = std::strtod(token.c_str(), &end);
        if (end == token.c_str() || *end != '\0') {
          fail(path, "expected a number, got '" + token + "'", line);
        }
        values.push_back(v);
      }
      if (values.size() != vertex->properties.size()) {
        fail(path,
             "expected " + std::to_string(vertex->properties.size()) + " values, got " +
                 std::to_string(values.size()),
             line);
      }
      const Eigen::Vector3d p(values[xyz[0]], values[xyz[1]], values[xyz[2]]);
      checkPoint(path, p, i, line);
      points.push_back(p);
    }
    return points;
  }
  const bool swap = format == "binary_big_endian";
  for (auto e = elements.begin(); e != vertex; ++e) {
    long bytes = 0;
    for (const auto& property : e->properties) bytes += plyTypeSize(property.first);
    in.ignore(bytes * e->count);
  }
  std::vector<int> offsets;
  int stride = 0;
  for (const auto& property : vertex->properties) {
    offsets.push_back(stride);
    stride += plyTypeSize(property.first);
  }
  std::vector<unsigned char> record(stride);
  for (long i = 0; i < count; ++i) {
    if (!in.read(reinterpret_cast<char*>(record.data()), stride)) {
      fail(path, "the file ends after " + std::to_string(i) + " of " + std::to_string(count) +
                     " vertices");
    }
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) {
      p[k] = plyValue(vertex->properties[xyz[k]].first, record.data() + offsets[xyz[k]], swap);
    }
    checkPoint(path, p, i, 0);
    points.push_back(p);
  }
  return points;
}

}  // namespace

std::vector<Eigen::Vector3d> readPointCloud(const std::string& path) {
  const std::string extension = extensionOf(path);
  if (extension != "xyz" && extension != "txt" && extension != "ply") {
    fail(path, "unknown point cloud format '" + extension + "' (expected .xyz, .txt or .ply)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open: ") + std::strerror(errno));
  std::vector<Eigen::Vector3d> points = extension == "ply" ? readPly(path, in) : readXyz(path, in);
  if (points.empty()) fail(path, "no point");
  return points;
}

}  // namespace fse_fit
