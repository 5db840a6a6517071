#include "report.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>

#include "fcl_superellipsoid/batch_distance.h"

namespace fcl_superellipsoid {
namespace bench {
namespace {

using nlohmann::json;

/// The paper's values (Tables 1–4): its Implicit rows and its mesh time; error in mm, time in
/// µs per query.
struct PaperValues {
  double avg_err, sigma, converged_pct, diverged_err, time_us, mesh_time_us;
};
struct PaperShape {
  double e1, e2;
  PaperValues outside, inside;
};

const std::vector<PaperShape>& paperValues() {
  static const std::vector<PaperShape> values = {
      {0.3, 0.3, {0.41, 0.27, 100, 0, 2.63, 35.02}, {0.21, 0.11, 100, 0, 1.80, 32.36}},
      {0.65, 0.65, {0.59, 0.21, 100, 0, 1.76, 29.05}, {0.06, 0.02, 100, 0, 1.70, 23.65}},
      {1.0,
       1.0,
       {2.11e-14, 2.54e-14, 100, 0, 1.23, 32.57},
       {2.10e-14, 2.46e-14, 100, 0, 1.13, 24.35}},
      {1.35, 1.35, {0.46, 0.19, 100, 0, 1.98, 30.37}, {0.06, 0.03, 100, 0, 1.63, 25.45}},
      {1.7, 1.7, {0.73, 0.55, 86, 2.50, 5.86, 33.66}, {0.19, 0.21, 96.08, 1.37, 2.52, 26.42}},
      {1.0, 0.3, {0.40, 0.28, 100, 0, 2.33, 26.51}, {0.15, 0.09, 100, 0, 2.27, 28.10}},
      {1.0, 1.6, {0.34, 0.24, 100, 0, 2.12, 39.27}, {0.09, 0.09, 100, 0, 2.17, 33.47}},
  };
  return values;
}

const PaperValues* paperValuesFor(const Row& row) {
  if (!row.paper_shape) return nullptr;
  for (const PaperShape& p : paperValues()) {
    if (p.e1 == row.eps1 && p.e2 == row.eps2) {
      if (row.side == sideKey(Side::kPaperOutside)) return &p.outside;
      if (row.side == sideKey(Side::kPaperInside)) return &p.inside;
    }
  }
  return nullptr;
}

double size(const Row& r) { return r.radii.maxCoeff(); }

/// Every column of the CSV and JSON, once.
struct Field {
  const char* name;
  std::function<json(const Row&)> value;
};

const std::vector<Field>& fields() {
  auto paper = [](const Row& r, double PaperValues::*member) -> json {
    const PaperValues* p = paperValuesFor(r);
    const bool implicit_row = r.family == kPaper && r.setting_value == 1e-3;
    const bool mesh_row = r.family == kFclMesh && r.setting_value == 272;
    if (p == nullptr || !(implicit_row || mesh_row)) return NAN;
    if (mesh_row) return member == &PaperValues::time_us ? p->mesh_time_us : NAN;
    return p->*member;
  };
  static const std::vector<Field> all = {
      {"side", [](const Row& r) { return json(r.side); }},
      {"shape", [](const Row& r) { return json(r.shape); }},
      {"a1", [](const Row& r) { return json(r.radii[0]); }},
      {"a2", [](const Row& r) { return json(r.radii[1]); }},
      {"a3", [](const Row& r) { return json(r.radii[2]); }},
      {"eps1", [](const Row& r) { return json(r.eps1); }},
      {"eps2", [](const Row& r) { return json(r.eps2); }},
      {"method", [](const Row& r) { return json(r.family); }},
      {"setting", [](const Row& r) { return json(r.setting); }},
      {"setting_value", [](const Row& r) { return json(r.setting_value); }},
      {"signed", [](const Row& r) { return json(r.is_signed); }},
      {"points", [](const Row& r) { return json(r.points); }},
      {"truth_points", [](const Row& r) { return json(r.stats.truth_points); }},
      {"failed", [](const Row& r) { return json(r.stats.failed); }},
      {"avg_err", [](const Row& r) { return json(r.stats.avg_err); }},
      {"sigma_err", [](const Row& r) { return json(r.stats.sigma_err); }},
      {"max_err", [](const Row& r) { return json(r.stats.max_err); }},
      {"avg_point_err", [](const Row& r) { return json(r.stats.avg_point_err); }},
      {"max_point_err", [](const Row& r) { return json(r.stats.max_point_err); }},
      {"converged_pct", [](const Row& r) { return json(r.stats.converged_pct); }},
      {"nonconv_err", [](const Row& r) { return json(r.stats.nonconv_err); }},
      {"avg_error_estimate", [](const Row& r) { return json(r.stats.avg_estimate); }},
      {"us_per_query", [](const Row& r) { return json(r.us_per_query); }},
      {"evaluations_per_query", [](const Row& r) { return json(r.evaluations); }},
      {"speedup_vs_mesh272", [](const Row& r) { return json(r.speedup_vs_mesh272); }},
      {"memory_bytes", [](const Row& r) { return json(r.memory_bytes); }},
      {"setup_ms", [](const Row& r) { return json(r.setup_ms); }},
      {"paper_avg_err_mm", [paper](const Row& r) { return paper(r, &PaperValues::avg_err); }},
      {"paper_converged_pct",
       [paper](const Row& r) { return paper(r, &PaperValues::converged_pct); }},
      {"paper_us", [paper](const Row& r) { return paper(r, &PaperValues::time_us); }},
  };
  return all;
}

std::string csvCell(const json& v) {
  if (v.is_string()) {
    std::string s = "\"";
    for (char c : v.get<std::string>()) s += c == '"' ? std::string("\"\"") : std::string(1, c);
    return s + "\"";
  }
  if (v.is_number_float() && !std::isfinite(v.get<double>())) return "";
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  return v.dump();
}

double geometricMean(const std::vector<double>& v) {
  double log_sum = 0;
  int n = 0;
  for (double x : v) {
    if (std::isfinite(x) && x > 0) {
      log_sum += std::log(x);
      ++n;
    }
  }
  return n ? std::exp(log_sum / n) : NAN;
}

/// Labels in first-appearance order (the method order of the run).
std::vector<std::string> labelsInOrder(const std::vector<Row>& rows) {
  std::vector<std::string> labels;
  for (const Row& r : rows) {
    if (std::find(labels.begin(), labels.end(), r.label()) == labels.end())
      labels.push_back(r.label());
  }
  return labels;
}

std::vector<std::string> sidesInOrder(const std::vector<Row>& rows) {
  std::vector<std::string> sides;
  for (const Row& r : rows) {
    if (std::find(sides.begin(), sides.end(), r.side) == sides.end()) sides.push_back(r.side);
  }
  return sides;
}

const Row* find(const std::vector<Row>& rows, const std::string& shape, const std::string& side,
                const char* family, double setting_value) {
  for (const Row& r : rows) {
    if (r.shape == shape && r.side == side && r.family == family &&
        (r.setting_value == setting_value ||
         (std::isnan(setting_value) && std::isnan(r.setting_value)))) {
      return &r;
    }
  }
  return nullptr;
}

}  // namespace

void printPaperTables(const std::vector<Row>& rows, std::FILE* out) {
  struct Pick {
    const char* family;
    double value;
  };
  const Pick picks[] = {
      {kRadial, NAN}, {kPaper, 1e-3}, {kExact, 1e-9}, {kExact, 1e-12}, {kFclMesh, 272}};
  for (const Side side : {Side::kPaperOutside, Side::kPaperInside}) {
    const std::string key = sideKey(side);
    bool header = false;
    for (const BenchShape& shape : benchShapes()) {
      if (!shape.paper) continue;
      bool first = true;
      for (const Pick& pick : picks) {
        const Row* r = find(rows, shape.name, key, pick.family, pick.value);
        if (r == nullptr) continue;
        if (!header) {
          std::fprintf(
              out, "\n%s: %d points per shape, %s; errors in mm\n",
              side == Side::kPaperOutside ? "Tables 1 and 3, outside" : "Tables 2 and 4, inside",
              r->points, sideDescription(side));
          std::fprintf(out, "%-13s %-15s %9s %9s %9s %7s %9s %9s %8s | %-25s\n", "shape", "method",
                       "avg err", "sigma", "max err", "conv %", "err !conv", "us/query", "xMesh272",
                       "paper: avg err, conv %, us");
          header = true;
        }
        const Stats& s = r->stats;
        std::fprintf(out, "%-13s %-15s %9.3g %9.3g %9.3g %7s %9.3g %9.3f %8.1f",
                     first ? shape.name.c_str() : "", r->label().c_str(), 1e3 * s.avg_err,
                     1e3 * s.sigma_err, 1e3 * s.max_err,
                     std::isnan(s.converged_pct)
                         ? "-"
                         : std::to_string(s.converged_pct).substr(0, 6).c_str(),
                     1e3 * s.nonconv_err, r->us_per_query, r->speedup_vs_mesh272);
        const PaperValues* p = paperValuesFor(*r);
        if (p != nullptr && r->family == kPaper) {
          std::fprintf(out, " | %-8.3g %-7.2f %-6.2f", p->avg_err, p->converged_pct, p->time_us);
        } else if (p != nullptr && r->family == kFclMesh) {
          std::fprintf(out, " | mesh: %.2f us", p->mesh_time_us);
        }
        std::fprintf(out, "\n");
        first = false;
      }
    }
  }
  std::fprintf(out,
               "\nErrors |d - d_true|: truth by construction outside, by the long-double reference "
               "inside. FCL's mesh\ndistance is unsigned: scored on |d|. xMesh272: FCL mesh 272 v "
               "time / this time, this run. The\npaper's columns: its Implicit rows and its mesh "
               "time (an i5-6600, Windows).\n");
}

void printSummary(const std::vector<Row>& rows, std::FILE* out) {
  for (const std::string& side : sidesInOrder(rows)) {
    std::fprintf(
        out, "\nAccuracy against time, %s (all shapes; errors relative to the largest radius)\n",
        side.c_str());
    std::fprintf(out, "%-32s %6s %10s %10s %10s %7s %6s %9s %9s %10s\n", "method", "shapes",
                 "avg err", "max err", "point err", "conv %", "failed", "us/query", "xMesh272",
                 "bytes");
    for (const std::string& label : labelsInOrder(rows)) {
      std::vector<double> times, speedups;
      double avg = 0, worst = 0, point = 0, conv = 0;
      int n = 0, n_conv = 0, failed = 0;
      std::size_t bytes = 0;
      for (const Row& r : rows) {
        if (r.side != side || r.label() != label) continue;
        ++n;
        failed += r.stats.failed;
        avg += r.stats.avg_err / size(r);
        worst = std::max(worst, r.stats.max_err / size(r));
        point += r.stats.avg_point_err / size(r);
        if (!std::isnan(r.stats.converged_pct)) {
          conv += r.stats.converged_pct;
          ++n_conv;
        }
        times.push_back(r.us_per_query);
        speedups.push_back(r.speedup_vs_mesh272);
        bytes = std::max(bytes, r.memory_bytes);
      }
      if (n == 0) continue;
      std::fprintf(out, "%-32s %6d %10.2e %10.2e %10.2e %7s %6d %9.3f %9.2f %10zu\n", label.c_str(),
                   n, avg / n, worst, point / n,
                   n_conv ? std::to_string(conv / n_conv).substr(0, 6).c_str() : "-", failed,
                   geometricMean(times), geometricMean(speedups), bytes);
    }
  }
  std::fprintf(
      out,
      "\navg err: mean over shapes of the average |d - d_true| / size; max err: worst over "
      "all points;\npoint err: mean |p - p_true| / size; failed: answers that were not a "
      "number (excluded);\nus/query and xMesh272: geometric means over shapes.\n");
}

void printSpeedRatios(const std::vector<Row>& rows, std::FILE* out) {
  const std::vector<std::string> sides = sidesInOrder(rows);
  std::vector<std::string> shapes;
  for (const Row& r : rows) {
    if (std::find(shapes.begin(), shapes.end(), r.shape) == shapes.end()) shapes.push_back(r.shape);
  }
  struct Ratio {
    const char* title;
    std::function<double(const std::string&, const std::string&)> value;
  };
  const Ratio ratios[] = {
      {"Speedup of Exact (1e-12) over FCL mesh 272 v (mesh time / Exact time)",
       [&](const std::string& shape, const std::string& side) {
         const Row* e = find(rows, shape, side, kExact, 1e-12);
         return e ? e->speedup_vs_mesh272 : NAN;
       }},
      {"Time of Exact 1e-9 / Paper 1e-3 (the solver's speed target: <= 1)",
       [&](const std::string& shape, const std::string& side) {
         const Row* e = find(rows, shape, side, kExact, 1e-9);
         const Row* p = find(rows, shape, side, kPaper, 1e-3);
         return e && p ? e->us_per_query / p->us_per_query : NAN;
       }},
      {"Evaluations of the shape per query, Exact 1e-9 (support or gauge; Newton steps, starts "
       "and certificates)",
       [&](const std::string& shape, const std::string& side) {
         const Row* e = find(rows, shape, side, kExact, 1e-9);
         return e ? e->evaluations : NAN;
       }},
  };
  for (const Ratio& ratio : ratios) {
    std::fprintf(out, "\n%s\n%-26s", ratio.title, "shape");
    for (const std::string& side : sides) std::fprintf(out, " %12s", side.c_str());
    std::fprintf(out, "\n");
    for (const std::string& shape : shapes) {
      std::fprintf(out, "%-26s", shape.c_str());
      for (const std::string& side : sides) std::fprintf(out, " %12.2f", ratio.value(shape, side));
      std::fprintf(out, "\n");
    }
  }
}

std::string csvHeader() {
  std::string header;
  for (const Field& f : fields()) header += (header.empty() ? "" : ",") + std::string(f.name);
  return header;
}

void writeCsv(const std::vector<Row>& rows, const std::string& path) {
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error("cannot write " + path);
  csv << csvHeader() << '\n';
  for (const Row& r : rows) {
    bool first = true;
    for (const Field& f : fields()) {
      csv << (first ? "" : ",") << csvCell(f.value(r));
      first = false;
    }
    csv << '\n';
  }
}

void writeJson(const std::vector<Row>& rows, const RunConfig& config, const std::string& path) {
  json doc;
  doc["meta"] = {{"machine", machineDescription()},   {"compiler", __VERSION__},
                 {"points", config.points},           {"reference_points", config.reference_points},
                 {"repetitions", config.repetitions}, {"seed", config.seed}};
  json& out = doc["rows"] = json::array();
  for (const Row& r : rows) {
    json row;
    for (const Field& f : fields()) row[f.name] = f.value(r);
    out.push_back(row);
  }
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write " + path);
  file << doc.dump(1) << '\n';
}

std::string machineDescription() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) +
         " hardware threads, SIMD " + simdInstructionSet();
}

}  // namespace bench
}  // namespace fcl_superellipsoid
