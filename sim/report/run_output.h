#ifndef FSE_SIM_REPORT_RUN_OUTPUT_H
#define FSE_SIM_REPORT_RUN_OUTPUT_H

// A run's files (docs/scenes.md → "Output"): steps.csv (one row per step), summary.json (the
// figures the tables are made of), and optional OBJ frames of the cloth.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/cloth_mesh.h"
#include "physics/phases.h"
#include "report/measurements.h"

namespace fse_sim {

/// The averages and extremes of a run's records.
struct RunSummary {
  std::string model;          ///< "exact", "paper", "mesh", or the peer's name
  std::vector<Phase> phases;  ///< those the run timed
  PhaseTimes mean_ms{};       ///< per phase, averaged over every step
  long steps = 0;
  double max_penetration = 0;      ///< m, over every step
  double contact_error_max = 0;    ///< m, over every step
  double contact_error_mean = 0;   ///< m, mean over the steps with contacts
  double first_contact_time = -1;  ///< s, the end of the first step with a contact (−1: none)
  double max_edge_strain = 0;
  double final_max_speed = 0;  ///< m/s, at the end
  double energy_start = 0, energy_end = 0;
  /// Rigid-body scenes: how many bodies, and how many end inside the bowl (−1: no bowl).
  int bodies = 0;
  int bodies_inside = -1;
};

RunSummary summarize(const std::string& model, const std::vector<Phase>& phases,
                     const std::vector<StepRecord>& records);
nlohmann::json toJson(const RunSummary& summary);

/// steps.csv: time, one column per phase (ms; only the phases run), then the measurements.
void writeStepsCsv(const std::string& path, const std::vector<Phase>& phases,
                   const std::vector<StepRecord>& records);
void writeJson(const std::string& path, const nlohmann::json& value);
/// The cloth at one moment as an OBJ file (positions and the grid's triangles).
void writeClothObj(const std::string& path, const ClothMesh& mesh, const Eigen::Matrix3Xd& x);

}  // namespace fse_sim

#endif  // FSE_SIM_REPORT_RUN_OUTPUT_H
