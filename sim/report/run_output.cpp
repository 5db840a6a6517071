#include "report/run_output.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace fse_sim {

RunSummary summarize(const std::string& model, const std::vector<Phase>& phases,
                     const std::vector<StepRecord>& records) {
  RunSummary s;
  s.model = model;
  s.phases = phases;
  s.steps = long(records.size());
  long with_contacts = 0;
  for (const StepRecord& r : records) {
    for (Phase p : phases) s.mean_ms[int(p)] += 1e3 * r.seconds[int(p)];
    s.max_penetration = std::max(s.max_penetration, r.max_penetration);
    s.contact_error_max = std::max(s.contact_error_max, r.contact_error_max);
    if (r.contacts > 0) {
      s.contact_error_mean += r.contact_error_mean;
      ++with_contacts;
      if (s.first_contact_time < 0) s.first_contact_time = r.time;
    }
    s.max_edge_strain = std::max(s.max_edge_strain, r.max_edge_strain);
  }
  if (s.steps > 0) {
    for (double& ms : s.mean_ms) ms /= double(s.steps);
    s.final_max_speed = records.back().max_speed;
    s.energy_start = records.front().energy;
    s.energy_end = records.back().energy;
  }
  if (with_contacts > 0) s.contact_error_mean /= double(with_contacts);
  return s;
}

nlohmann::json toJson(const RunSummary& s) {
  nlohmann::json phases = nlohmann::json::object();
  for (Phase p : s.phases) phases[columnName(p)] = s.mean_ms[int(p)];
  nlohmann::json out = {{"model", s.model},
                        {"steps", s.steps},
                        {"mean_ms", phases},
                        {"max_penetration", s.max_penetration},
                        {"contact_error_max", s.contact_error_max},
                        {"contact_error_mean", s.contact_error_mean},
                        {"first_contact_time", s.first_contact_time},
                        {"max_edge_strain", s.max_edge_strain},
                        {"final_max_speed", s.final_max_speed},
                        {"energy_start", s.energy_start},
                        {"energy_end", s.energy_end}};
  if (s.bodies > 0) {
    out["bodies"] = s.bodies;
    out["bodies_inside"] = s.bodies_inside;
  }
  return out;
}

namespace {
std::ofstream openForWriting(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot be written");
  return out;
}
}  // namespace

void writeStepsCsv(const std::string& path, const std::vector<Phase>& phases,
                   const std::vector<StepRecord>& records) {
  std::ofstream out = openForWriting(path);
  out << "time";
  for (Phase p : phases) out << ',' << columnName(p) << "_ms";
  out << ",max_penetration,contacts,contact_error_max,contact_error_mean,max_edge_strain,energy,"
         "max_speed\n";
  out.precision(9);
  for (const StepRecord& r : records) {
    out << r.time;
    for (Phase p : phases) out << ',' << 1e3 * r.seconds[int(p)];
    out << ',' << r.max_penetration << ',' << r.contacts << ',' << r.contact_error_max << ','
        << r.contact_error_mean << ',' << r.max_edge_strain << ',' << r.energy << ',' << r.max_speed
        << '\n';
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

void writeJson(const std::string& path, const nlohmann::json& value) {
  std::ofstream out = openForWriting(path);
  out << value.dump(2) << '\n';
  if (!out) throw std::runtime_error(path + ": write failed");
}

void writeClothObj(const std::string& path, const ClothMesh& mesh, const Eigen::Matrix3Xd& x) {
  std::ofstream out = openForWriting(path);
  out.precision(9);
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    out << "v " << x(0, i) << ' ' << x(1, i) << ' ' << x(2, i) << '\n';
  }
  for (const auto& t : mesh.triangles) {
    out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace fse_sim
