#ifndef FCL_SUPERELLIPSOID_BENCH_ACCURACY_TIME_H
#define FCL_SUPERELLIPSOID_BENCH_ACCURACY_TIME_H

// The benchmark's core: every method on the same points, errors against ground truth,
// time per query as the median of interleaved repetitions.

#include <string>
#include <vector>

#include "methods.h"
#include "workload.h"

namespace fcl_superellipsoid {
namespace bench {

/// Accuracy of one method on one point set, over the points with ground truth.
struct Stats {
  int truth_points = 0;
  int failed = 0;      // answers that were not finite (excluded from the errors)
  double avg_err = 0;  // |d − d_true| (unsigned methods: ||d| − |d_true||)
  double sigma_err = 0;
  double max_err = 0;
  double avg_point_err = 0;  // |p − p_true|, nearest points
  double max_point_err = 0;
  double converged_pct = NAN;  // NaN for methods without a convergence test
  double nonconv_err = 0;      // average error of the non-converged (0 if none)
  double avg_estimate = NAN;   // average of the method's own error estimate (paper Eq. 7)
};

/// Scores answers[i] against set's truth, i < set.truthCount().
Stats scoreAnswers(const std::vector<Answer>& answers, const PointSet& set, bool is_signed);

struct Row {
  std::string shape;
  Vector3<double> radii;
  double eps1, eps2;
  bool paper_shape;
  std::string side;
  std::string family, setting;
  double setting_value;
  bool is_signed;
  int points;
  Stats stats;
  double us_per_query;        // median over repetitions
  double evaluations;         // the superellipsoid's support or gauge evaluations per query
                              // (diagnostics.h → shapeEvaluations); NaN where a method makes
                              // none (FCL's mesh, its polytope, its ellipsoid)
  double speedup_vs_mesh272;  // FCL mesh 272 v time / this time, same shape and side (or NaN)
  std::size_t memory_bytes;
  double setup_ms;  // building the representation (tessellation + BVH, ...)
  std::string label() const { return setting.empty() ? family : family + " " + setting; }
};

struct RunConfig {
  int points = 10000;           // per (shape, side); the paper: 10,000
  int reference_points = 1000;  // inside points checked against the long-double reference
  int repetitions = 5;          // timed passes; the median is reported
  unsigned seed = 2026;
  std::vector<std::string> shapes;  // names from benchShapes(); empty: all
  std::vector<Side> sides = allSides();
  MethodSelection methods;
  bool progress = true;  // a progress bar on stderr when it is a terminal
};

/// Runs every selected method on every (shape, side) and returns one row per
/// (shape, side, method), in that order.
/// @throws std::invalid_argument for an unknown shape name or a count < 1.
std::vector<Row> runAccuracyTime(const RunConfig& config);

}  // namespace bench
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_BENCH_ACCURACY_TIME_H
