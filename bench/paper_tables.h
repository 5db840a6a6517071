#ifndef FCL_SUPERELLIPSOID_BENCH_PAPER_TABLES_H
#define FCL_SUPERELLIPSOID_BENCH_PAPER_TABLES_H

#include <string>

namespace fcl_superellipsoid {
namespace bench {

struct PaperTablesConfig {
  int points = 10000;           // surface samples per shape (the paper: 10,000)
  int reference_points = 1000;  // inside points checked against the long-double reference
  int repetitions = 5;          // timing repetitions; the median is reported
  std::string csv_path;         // where to write every row (empty: nowhere)
  unsigned seed = 2026;
};

/// The paper's Tables 1–4 protocol: for each of its 7 shapes, surface points offset by +0.05
/// and −0.015 along the normal, answered by Radial, Paper (1e-3, 30 iterations) and Exact
/// (at 1e-9, the speed target's tolerance, and at its default 1e-12);
/// prints the tables with the paper's values beside ours and returns 0.
int runPaperTables(const PaperTablesConfig& config);

}  // namespace bench
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_BENCH_PAPER_TABLES_H
