// The benchmark's plumbing (bench/): scoring, ground truth, every column, CSV and JSON.
// Never its timings.

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "accuracy_time.h"
#include "report.h"

namespace fcl_superellipsoid {
namespace bench {
namespace {

TEST(BenchScoring, AveragesSigmaMaximumAndConvergenceOnAKnownCase) {
  PointSet set{Side::kNear, {}, {1.0, 2.0, -1.0, 0.5}, {}};
  set.points.assign(4, Vector3<double>::Zero());
  for (int i = 0; i < 4; ++i) set.true_nearest.push_back(Vector3<double>(i, 0, 0));
  const Vector3<double> nan = Vector3<double>::Constant(NAN);
  const std::vector<Answer> answers = {
      {1.1, Vector3<double>(0, 0.3, 0), 1, 0.01},   // error 0.1, point error 0.3
      {2.3, Vector3<double>(1, 0, 0), 0, 0.02},     // error 0.3, not converged
      {-1.0, Vector3<double>(2, 0, 0.1), 1, 0.03},  // exact, point error 0.1
      {NAN, nan, 1, 5.0},                           // a failure: counted, not scored
  };
  const Stats s = scoreAnswers(answers, set, true);
  EXPECT_EQ(s.truth_points, 4);
  EXPECT_EQ(s.failed, 1);
  EXPECT_NEAR(s.avg_err, 0.4 / 3, 1e-15);
  EXPECT_NEAR(s.max_err, 0.3, 1e-15);
  const double mean = 0.4 / 3;
  EXPECT_NEAR(s.sigma_err, std::sqrt((0.01 + 0.09 + 0.0) / 3 - mean * mean), 1e-15);
  EXPECT_NEAR(s.avg_point_err, 0.4 / 3, 1e-15);
  EXPECT_NEAR(s.max_point_err, 0.3, 1e-15);
  EXPECT_NEAR(s.converged_pct, 100.0 * 2 / 3, 1e-12);
  EXPECT_NEAR(s.nonconv_err, 0.3, 1e-15);
  EXPECT_NEAR(s.avg_estimate, 0.02, 1e-15);

  // An unsigned method is scored on |d|: reporting +1 for the inside point is no error.
  const std::vector<Answer> unsigned_answers = {{1.0, set.true_nearest[0], -1},
                                                {2.0, set.true_nearest[1], -1},
                                                {1.0, set.true_nearest[2], -1},
                                                {0.5, set.true_nearest[3], -1}};
  const Stats u = scoreAnswers(unsigned_answers, set, false);
  EXPECT_EQ(u.max_err, 0.0);
  EXPECT_TRUE(std::isnan(u.converged_pct));
  EXPECT_TRUE(std::isnan(u.avg_estimate));
  EXPECT_GT(scoreAnswers(unsigned_answers, set, true).max_err, 1.9);  // signed: −1 vs +1
}

TEST(BenchWorkload, OutsideTruthIsByConstructionAndInsideByTheReference) {
  const BenchShape& shape = benchShapes().at(10);  // the cloth-scene shape, not unit size
  const Superellipsoid<double> s = shape.make();
  for (Side side : allSides()) {
    SCOPED_TRACE(sideKey(side));
    const PointSet set = makePointSet(shape, side, 50, 5, 3);
    ASSERT_EQ(set.points.size(), 50u);
    ASSERT_EQ(set.truthCount(), truthByConstruction(side) ? 50 : 5);
    for (int i = 0; i < set.truthCount(); ++i) {
      const Vector3<double> step = set.points[i] - set.true_nearest[i];
      EXPECT_NEAR(s.gauge(set.true_nearest[i]), 1.0, 1e-9);
      if (truthByConstruction(side)) {
        EXPECT_GE(set.true_distance[i], 0.0);
        EXPECT_NEAR(step.norm(), set.true_distance[i], 1e-9 * (1 + set.true_distance[i]));
        if (step.norm() > 0)
          EXPECT_NEAR(step.normalized().dot(s.normal(set.true_nearest[i])), 1, 1e-9);
      } else {
        EXPECT_LT(s.gauge(set.points[i]), 1.0);
        EXPECT_LT(set.true_distance[i], 0.0);
        EXPECT_NEAR(step.norm(), -set.true_distance[i], 1e-6);
      }
    }
  }
  EXPECT_THROW(makePointSet(shape, Side::kFar, 0, 1, 1), std::invalid_argument);
}

/// A run of a fraction of a second with one setting of every method family.
std::vector<Row> tinyRun(RunConfig& config) {
  config.points = 30;
  config.reference_points = 4;
  config.repetitions = 1;
  config.shapes = {"(1; 1)", "(0.3; 0.3)"};
  config.methods.exact_tolerances = {1e-12};
  config.methods.paper_tolerances = {1e-3};
  config.methods.mesh_vertices = {272};
  config.methods.convex_vertices = {72};
  config.progress = false;
  return runAccuracyTime(config);
}

TEST(BenchRun, ATinyRunFillsEveryColumnOfEveryRow) {
  RunConfig config;
  const std::vector<Row> rows = tinyRun(config);
  // Methods per shape: Exact, Paper, Radial, Front end, mesh, convex, Bullet (+ Ellipsoid on (1;
  // 1)).
  ASSERT_EQ(rows.size(), (8u + 7u) * allSides().size());
  for (const Row& r : rows) {
    SCOPED_TRACE(r.shape + " " + r.side + " " + r.label());
    EXPECT_EQ(r.points, 30);
    EXPECT_GT(r.stats.truth_points, 0);
    if (r.family != kBullet) EXPECT_EQ(r.stats.failed, 0);  // Bullet's EPA may give up
    EXPECT_TRUE(std::isfinite(r.stats.avg_err) && std::isfinite(r.stats.max_err));
    EXPECT_GE(r.stats.max_err, r.stats.avg_err);
    EXPECT_GT(r.us_per_query, 0.0);
    // The solvers of ours evaluate the shape; FCL's mesh and polytope never do.
    if (r.family == kExact || r.family == kFrontEnd) EXPECT_GE(r.evaluations, 1.0);
    if (r.family == kFclMesh || r.family == kFclConvex) EXPECT_TRUE(std::isnan(r.evaluations));
    EXPECT_TRUE(std::isfinite(r.speedup_vs_mesh272));
    EXPECT_GT(r.memory_bytes, 0u);
    EXPECT_EQ(std::isnan(r.stats.converged_pct),
              r.family != kExact && r.family != kPaper && r.family != kRadial);
    // Accuracy ceilings that a plumbing mistake (wrong frame, wrong point, wrong sign) breaks.
    if (r.family == kExact || r.family == kFrontEnd) EXPECT_LT(r.stats.max_err, 1e-9);
    if (r.family == kExact || r.family == kFrontEnd) EXPECT_LT(r.stats.max_point_err, 1e-6);
    if (r.family == kFclMesh) EXPECT_LT(r.stats.max_err, 0.1);
    if (r.family == kFclMesh && r.side != "inside") EXPECT_LT(r.stats.max_point_err, 0.3);
    // Bullet is single precision with GJK/EPA tolerances of 1e-4 (relative to the distance,
    // up to 1000 × size far away): a sign or frame mistake costs ~ the size, or the distance.
    if (r.family == kBullet) EXPECT_LT(r.stats.max_err, r.side == "far" ? 1.0 : 0.1);
  }
  // The mesh row is its own baseline.
  for (const Row& r : rows) {
    if (r.family == kFclMesh) EXPECT_DOUBLE_EQ(r.speedup_vs_mesh272, 1.0);
  }
  config.shapes = {"no such shape"};
  EXPECT_THROW(runAccuracyTime(config), std::invalid_argument);
}

/// Splits one RFC 4180 line.
std::vector<std::string> csvFields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      out.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

TEST(BenchOutput, CsvAndJsonHoldEveryRowWithEveryColumn) {
  RunConfig config;
  const std::vector<Row> rows = tinyRun(config);
  const std::string dir = ::testing::TempDir();
  writeCsv(rows, dir + "/rows.csv");
  writeJson(rows, config, dir + "/rows.json");

  std::ifstream csv(dir + "/rows.csv");
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  const std::vector<std::string> header = csvFields(line);
  EXPECT_EQ(line, csvHeader());
  for (const char* column :
       {"side", "shape", "method", "setting", "avg_err", "sigma_err", "max_err", "avg_point_err",
        "converged_pct", "nonconv_err", "us_per_query", "speedup_vs_mesh272", "memory_bytes",
        "paper_avg_err_mm"}) {
    EXPECT_NE(std::find(header.begin(), header.end(), column), header.end()) << column;
  }
  std::size_t lines = 0;
  while (std::getline(csv, line)) {
    const std::vector<std::string> f = csvFields(line);
    ASSERT_EQ(f.size(), header.size()) << line;
    for (std::size_t k = 0; k < f.size(); ++k) {
      if (header[k] == "us_per_query" || header[k] == "avg_err" || header[k] == "points") {
        EXPECT_GE(std::stod(f[k]), 0.0) << header[k];
      }
    }
    ++lines;
  }
  EXPECT_EQ(lines, rows.size());

  std::ifstream json_file(dir + "/rows.json");
  const nlohmann::json doc = nlohmann::json::parse(json_file);
  ASSERT_EQ(doc.at("rows").size(), rows.size());
  EXPECT_EQ(doc.at("meta").at("points"), 30);
  for (const auto& row : doc.at("rows")) {
    EXPECT_EQ(row.size(), header.size());
    for (const std::string& column : header) EXPECT_TRUE(row.contains(column)) << column;
  }
  // The paper's value sits beside the Paper 1e-3 row of its shape.
  bool found = false;
  for (const auto& row : doc.at("rows")) {
    if (row.at("shape") == "(0.3; 0.3)" && row.at("side") == "paper+0.05" &&
        row.at("method") == "Paper" && row.at("setting_value") == 1e-3) {
      EXPECT_EQ(row.at("paper_avg_err_mm"), 0.41);
      EXPECT_EQ(row.at("paper_us"), 2.63);
      found = true;
    }
  }
  EXPECT_TRUE(found);
}

TEST(BenchOutput, TablesNameEveryMethodAndThePapersValues) {
  RunConfig config;
  const std::vector<Row> rows = tinyRun(config);
  std::FILE* out = std::tmpfile();
  printPaperTables(rows, out);
  printSummary(rows, out);
  printSpeedRatios(rows, out);
  std::rewind(out);
  std::string text;
  for (int c; (c = std::fgetc(out)) != EOF;) text += char(c);
  std::fclose(out);
  for (const char* expected :
       {"Tables 1 and 3", "Tables 2 and 4", "35.02", "Exact 1e-12", "Paper 1e-03", "FCL mesh 272 v",
        "FCL GJK convex 72 v", "FCL GJK ellipsoid", "Bullet GJK", "Front end", "Radial",
        "inside"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << expected;
  }
}

}  // namespace
}  // namespace bench
}  // namespace fcl_superellipsoid
