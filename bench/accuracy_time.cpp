// Ground truth: workload.h (construction outside, the long-double reference inside).
// Timing: after one untimed pass per method (which also gives the answers that are
// scored), `repetitions` timed passes over all points, the methods in rotating order so that
// drift on this shared machine hits every method alike; the median pass is reported.

#include "accuracy_time.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "fcl_superellipsoid/diagnostics.h"
#include "progress_bar.h"

namespace fcl_superellipsoid {
namespace bench {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// Seconds for one pass of `method` over all points (the sum keeps the calls alive).
double timePass(const Method& method, const std::vector<Vector3<double>>& points, double& sink) {
  const auto start = std::chrono::steady_clock::now();
  double sum = 0;
  for (const Vector3<double>& x : points) sum += method.query(x).distance;
  const auto stop = std::chrono::steady_clock::now();
  sink += sum;
  return std::chrono::duration<double>(stop - start).count();
}

std::vector<const BenchShape*> selectShapes(const std::vector<std::string>& names) {
  std::vector<const BenchShape*> out;
  for (const BenchShape& s : benchShapes()) {
    if (names.empty() || std::find(names.begin(), names.end(), s.name) != names.end()) {
      out.push_back(&s);
    }
  }
  for (const std::string& name : names) {
    const auto& all = benchShapes();
    if (std::none_of(all.begin(), all.end(), [&](const BenchShape& s) { return s.name == name; })) {
      throw std::invalid_argument("unknown shape '" + name + "'");
    }
  }
  return out;
}

/// The seed of a (shape, side) point set: the same whichever shapes a run selects.
unsigned pointSeed(unsigned seed, const BenchShape& shape, Side side) {
  const auto index = static_cast<unsigned>(&shape - benchShapes().data());
  return seed + 7 * index + static_cast<unsigned>(side);
}

}  // namespace

Stats scoreAnswers(const std::vector<Answer>& answers, const PointSet& set, bool is_signed) {
  Stats s;
  s.truth_points = set.truthCount();
  double sum2 = 0;
  int scored = 0, with_test = 0, converged = 0, nonconv = 0, estimates = 0;
  double estimate_sum = 0;
  for (int i = 0; i < set.truthCount(); ++i) {
    const Answer& a = answers[i];
    if (!std::isfinite(a.distance) || !a.nearest.allFinite()) {
      ++s.failed;
      continue;
    }
    const double truth = set.true_distance[i];
    const double err =
        is_signed ? std::abs(a.distance - truth) : std::abs(std::abs(a.distance) - std::abs(truth));
    const double point_err = (a.nearest - set.true_nearest[i]).norm();
    ++scored;
    s.avg_err += err;
    sum2 += err * err;
    s.max_err = std::max(s.max_err, err);
    s.avg_point_err += point_err;
    s.max_point_err = std::max(s.max_point_err, point_err);
    if (std::isfinite(a.estimate)) {
      estimate_sum += a.estimate;
      ++estimates;
    }
    if (a.converged >= 0) {
      ++with_test;
      if (a.converged == 1) {
        ++converged;
      } else {
        ++nonconv;
        s.nonconv_err += err;
      }
    }
  }
  if (scored > 0) {
    s.avg_err /= scored;
    s.avg_point_err /= scored;
    s.sigma_err = std::sqrt(std::max(0.0, sum2 / scored - s.avg_err * s.avg_err));
  }
  if (with_test > 0) s.converged_pct = 100.0 * converged / with_test;
  if (nonconv > 0) s.nonconv_err /= nonconv;
  if (estimates > 0) s.avg_estimate = estimate_sum / estimates;
  return s;
}

std::vector<Row> runAccuracyTime(const RunConfig& config) {
  if (config.points < 1 || config.repetitions < 1 || config.reference_points < 1) {
    throw std::invalid_argument(
        "runAccuracyTime: points, repetitions and reference_points must "
        "be >= 1 (got " +
        std::to_string(config.points) + ", " + std::to_string(config.repetitions) + ", " +
        std::to_string(config.reference_points) + ")");
  }
  const std::vector<const BenchShape*> shapes = selectShapes(config.shapes);
  support::ProgressBar progress(
      long(shapes.size() * config.sides.size()) * (config.repetitions + 1), config.progress);
  std::vector<Row> rows;
  double sink = 0;
  for (std::size_t si = 0; si < shapes.size(); ++si) {
    const BenchShape& shape = *shapes[si];
    progress.advance(0, shape.name + ": building methods");
    const std::vector<std::unique_ptr<Method>> methods = makeMethods(shape, config.methods);
    for (const Side side : config.sides) {
      const std::string task = shape.name + ", " + sideKey(side);
      progress.advance(0, task + ": points and truth");
      const PointSet set = makePointSet(shape, side, config.points, config.reference_points,
                                        pointSeed(config.seed, shape, side));
      // Untimed pass: warms caches, gives the answers to score and counts the evaluations.
      std::vector<Stats> stats;
      std::vector<double> evaluations;
      for (const auto& method : methods) {
        std::vector<Answer> answers;
        answers.reserve(set.points.size());
        shapeEvaluations() = 0;
        for (const Vector3<double>& x : set.points) answers.push_back(method->query(x));
        const std::uint64_t count = shapeEvaluations();
        evaluations.push_back(count > 0 ? double(count) / double(set.points.size()) : NAN);
        stats.push_back(scoreAnswers(answers, set, method->isSigned()));
      }
      progress.advance(1, task);
      std::vector<std::vector<double>> seconds(methods.size());
      for (int rep = 0; rep < config.repetitions; ++rep) {
        for (std::size_t k = 0; k < methods.size(); ++k) {
          const std::size_t m = (k + std::size_t(rep)) % methods.size();
          seconds[m].push_back(timePass(*methods[m], set.points, sink));
        }
        progress.advance(1, task);
      }
      const std::size_t first = rows.size();
      double mesh272_us = NAN;
      for (std::size_t m = 0; m < methods.size(); ++m) {
        const Method& method = *methods[m];
        Row row{shape.name,
                shape.radii,
                shape.eps1,
                shape.eps2,
                shape.paper,
                sideKey(side),
                method.family(),
                method.setting(),
                method.settingValue(),
                method.isSigned(),
                int(set.points.size()),
                stats[m],
                1e6 * median(seconds[m]) / set.points.size(),
                evaluations[m],
                NAN,
                method.memoryBytes(),
                1e3 * method.setupSeconds()};
        if (method.family() == kFclMesh && method.settingValue() == 272)
          mesh272_us = row.us_per_query;
        rows.push_back(row);
      }
      for (std::size_t r = first; r < rows.size(); ++r) {
        rows[r].speedup_vs_mesh272 = mesh272_us / rows[r].us_per_query;
      }
    }
  }
  progress.finish();
  if (sink == 42.4242) std::fprintf(stderr, " ");  // keeps the timed sums observable
  return rows;
}

}  // namespace bench
}  // namespace fcl_superellipsoid
