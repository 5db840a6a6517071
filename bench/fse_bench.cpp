// fse_bench: what accuracy costs in time. See --help, and docs/benchmark.md for a full run.
//
// The default run answers the same points with every method (our Exact solver at several
// tolerances, the paper's method, Radial, FCL's BVH mesh at several resolutions, FCL's GJK on
// a convex polytope and on its Ellipsoid, Bullet's GJK on the exact support function, and
// our FCL front end), prints the paper's Tables 1–4, a summary per point distribution and the
// speed ratios per shape, then the scaling section; it writes every row as CSV and JSON.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "accuracy_time.h"
#include "aspect_sweep.h"
#include "culling.h"
#include "pairs.h"
#include "report.h"
#include "scaling.h"

namespace {

using namespace fcl_superellipsoid::bench;

/// Keeps only the method families named in `families` (all if empty).
void filterFamilies(const std::vector<std::string>& families, MethodSelection& s) {
  if (families.empty()) return;
  auto keep = [&](const char* family) {
    return std::find(families.begin(), families.end(), family) != families.end();
  };
  if (!keep(kExact)) s.exact_tolerances.clear();
  if (!keep(kPaper)) s.paper_tolerances.clear();
  if (!keep(kFclMesh)) s.mesh_vertices.clear();
  if (!keep(kFclConvex)) s.convex_vertices.clear();
  s.radial = keep(kRadial);
  s.fcl_ellipsoid = keep(kFclEllipsoid);
  s.bullet = keep(kBullet);
  s.front_end = keep(kFrontEnd);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "fse_bench: point-to-superellipsoid distance, accuracy against time.\n"
      "Every method answers the same points in one process: Exact (tolerances 1e-3 .. 1e-12),\n"
      "Paper (1e-1 .. 1e-6, 30 iterations), Radial, FCL mesh (OBBRSS BVH, 72 .. 64k vertices),\n"
      "FCL GJK on the tessellation's convex polytope and on fcl::Ellipsoid, Bullet GJK on the\n"
      "exact support function, and the library's FCL front end. Shapes: the paper's 7 and 5\n"
      "hard ones. Points: the paper's protocol (+0.05, -0.015 along the normal) and near, far\n"
      "and inside distributions. Output: the paper's Tables 1-4, a summary per distribution,\n"
      "speed ratios per shape, scaling to 1e6 vertices; CSV and JSON of every row in --out\n"
      "(plot them with bench/plot.py)."};
  RunConfig config;
  bool quick = false;
  app.add_flag("--quick", quick,
               "A run of seconds: 500 points, 40 inside reference points, 2 repetitions, meshes "
               "up to 4k vertices, convex up to 272, scaling to 1e4");
  app.add_option("--points", config.points, "Points per shape and distribution (default 10,000)")
      ->check(CLI::Range(1, 10000000));
  app.add_option("--reference-points", config.reference_points,
                 "Inside points per shape scored against the long-double reference (~5 ms each; "
                 "default 1,000)")
      ->check(CLI::Range(1, 10000000));
  app.add_option("--repetitions", config.repetitions,
                 "Timed passes per method; the median is reported (default 5)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--seed", config.seed, "Seed of the point sets");
  std::vector<std::string> shape_names, side_keys, families;
  std::vector<std::string> all_shapes, all_sides;
  for (const BenchShape& s : benchShapes()) all_shapes.push_back(s.name);
  for (Side s : allSides()) all_sides.push_back(sideKey(s));
  app.add_option("--shapes", shape_names, "Only these shapes (default: all)")
      ->check(CLI::IsMember(all_shapes));
  app.add_option("--sides", side_keys, "Only these point distributions (default: all)")
      ->check(CLI::IsMember(all_sides));
  app.add_option("--methods", families, "Only these method families (default: all)")
      ->check(CLI::IsMember(
          {kExact, kPaper, kRadial, kFclMesh, kFclConvex, kFclEllipsoid, kBullet, kFrontEnd}));
  bool no_scaling = false, scaling_only = false, no_progress = false;
  app.add_flag("--no-scaling", no_scaling, "Skip the scaling section");
  app.add_flag("--scaling", scaling_only, "Only the scaling section");
  app.add_flag("--no-progress", no_progress, "No progress bar (it is drawn only on a terminal)");
  std::string out_dir = "out";
  app.add_option("--out", out_dir,
                 "Directory for results.csv, results.json and scaling.csv ('' for none)");
  bool aspect_sweep = false;
  app.add_flag("--aspect-sweep", aspect_sweep,
               "Instead: the Exact solver's accuracy against elongation (radii up to 1000:1)");
  int culling = 0;
  app.add_option("--culling", culling,
                 "Instead: the FCL front end's BVH culling on a point cloud of this many vertices "
                 "(1 % near the shape) against brute force")
      ->check(CLI::Range(100, 100000000));
  int pairs = 0;
  app.add_option("--pairs", pairs,
                 "Instead: the superellipsoid against every FCL shape, this many random pairs per "
                 "kind, against FCL's libccd and Bullet's GJK/EPA (pairs.csv in --out)")
      ->check(CLI::Range(6, 1000000));
  std::vector<std::string> pair_kinds;
  app.add_option("--pair-kinds", pair_kinds,
                 "With --pairs: only these partner kinds (superellipsoid, ellipsoid, sphere, box, "
                 "capsule, cylinder, cone, convex, triangle, halfspace, plane)")
      ->check(CLI::IsMember({"superellipsoid", "ellipsoid", "sphere", "box", "capsule", "cylinder",
                             "cone", "convex", "triangle", "halfspace", "plane"}));
  std::string pair_answers;
  app.add_option("--pair-answers", pair_answers,
                 "With --pairs N: instead of timing, write our answer to each of the pairs to this "
                 "file (hexadecimal floats; compare two builds with diff)");
  CLI11_PARSE(app, argc, argv);

  if (culling > 0) return runCulling(culling);
  if (pairs > 0 && !pair_answers.empty()) return writePairAnswers(pairs, pair_answers);
  if (pairs > 0) {
    if (!out_dir.empty()) std::filesystem::create_directories(out_dir);
    return runPairs(pairs, out_dir.empty() ? std::string() : out_dir + "/pairs.csv", pair_kinds);
  }
  if (aspect_sweep) return runAspectSweep(quick ? 50 : 200);

  std::vector<int> scaling_sizes = {1000, 10000, 100000, 1000000};
  if (quick) {
    if (app.count("--points") == 0) config.points = 500;
    if (app.count("--reference-points") == 0) config.reference_points = 40;
    if (app.count("--repetitions") == 0) config.repetitions = 2;
    config.methods.mesh_vertices = {72, 272, 1000, 4000};
    config.methods.convex_vertices = {72, 272};
    scaling_sizes = {1000, 10000};
  }
  filterFamilies(families, config.methods);
  config.shapes = shape_names;
  if (!side_keys.empty()) {
    config.sides.clear();
    for (Side s : allSides()) {
      if (std::find(side_keys.begin(), side_keys.end(), sideKey(s)) != side_keys.end()) {
        config.sides.push_back(s);
      }
    }
  }
  config.progress = !no_progress;
  if (!out_dir.empty()) std::filesystem::create_directories(out_dir);
  auto outPath = [&](const char* file) {
    return out_dir.empty() ? std::string() : out_dir + "/" + file;
  };

  std::printf("fse_bench on %s\n", machineDescription().c_str());
  if (!scaling_only) {
    const std::vector<Row> rows = runAccuracyTime(config);
    printPaperTables(rows, stdout);
    printSummary(rows, stdout);
    printSpeedRatios(rows, stdout);
    if (!out_dir.empty()) {
      writeCsv(rows, outPath("results.csv"));
      writeJson(rows, config, outPath("results.json"));
    }
  }
  if (!no_scaling || scaling_only) runScaling(scaling_sizes, quick ? 3 : 5, outPath("scaling.csv"));
  if (!out_dir.empty()) {
    std::printf(
        "\nRows written to %s/ (results.csv, results.json, scaling.csv); plots: "
        "/usr/bin/python3 bench/plot.py %s\n",
        out_dir.c_str(), out_dir.c_str());
  }
  return 0;
}
