// fse_bench: what accuracy costs in time.
//
// Modes (see --help):
//   --quick          a few seconds: the paper's table protocol on 2,000 points per shape
//   (default)        the full protocol: 10,000 points per shape, 1,000 inside reference points
//   --aspect-sweep   the Exact solver's accuracy against elongation
//   --culling N      the FCL front end's BVH culling on an N-vertex point cloud
//
// The same points go to every method in one process; times are medians of interleaved
// repetitions. Results print as the paper's Tables 1–4 and, with --csv, as one CSV row per
// (side, shape, method).

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "aspect_sweep.h"
#include "culling.h"
#include "paper_tables.h"

int main(int argc, char** argv) {
  using fcl_superellipsoid::bench::PaperTablesConfig;
  CLI::App app{
      "fse_bench: point-to-superellipsoid distance, accuracy against time.\n"
      "Reproduces the reference paper's Tables 1-4 (7 shapes, surface points offset +0.05 and\n"
      "-0.015 along the normal) for the Radial, Paper (tolerance 1e-3, 30 iterations) and Exact\n"
      "methods, with the paper's values beside ours."};
  PaperTablesConfig config;
  bool quick = false;
  app.add_flag("--quick", quick,
               "Short run (2,000 points, 200 inside reference points, 3 repetitions)");
  app.add_option("--points", config.points,
                 "Surface points per shape (default 10,000, as the paper)")
      ->check(CLI::Range(1, 10000000));
  app.add_option(
         "--reference-points", config.reference_points,
         "Inside points per shape checked against the long-double reference (slow: ~5 ms each)")
      ->check(CLI::Range(1, 10000000));
  app.add_option("--repetitions", config.repetitions, "Timing repetitions (median reported)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--seed", config.seed, "Seed of the surface samples");
  bool aspect_sweep = false;
  app.add_flag("--aspect-sweep", aspect_sweep,
               "Instead: the Exact solver's accuracy against elongation (radii up to 1000:1)");
  int culling = 0;
  app.add_option("--culling", culling,
                 "Instead: the FCL front end's BVH culling on a point cloud of this many vertices "
                 "(1 % near the shape) against brute force")
      ->check(CLI::Range(100, 100000000));
  std::string out_dir = "out";
  app.add_option("--out", out_dir, "Directory for the CSV of every row ('' for none)");
  CLI11_PARSE(app, argc, argv);
  if (quick) {
    if (app.count("--points") == 0) config.points = 2000;
    if (app.count("--reference-points") == 0) config.reference_points = 200;
    if (app.count("--repetitions") == 0) config.repetitions = 3;
  }
  if (culling > 0) return fcl_superellipsoid::bench::runCulling(culling);
  if (aspect_sweep) return fcl_superellipsoid::bench::runAspectSweep(quick ? 50 : 200);
  if (!out_dir.empty()) {
    std::filesystem::create_directories(out_dir);
    config.csv_path = out_dir + "/paper_tables.csv";
  }
  const int rc = fcl_superellipsoid::bench::runPaperTables(config);
  if (!config.csv_path.empty()) std::printf("Rows written to %s\n", config.csv_path.c_str());
  return rc;
}
