#include "scaling.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>

#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_superellipsoid/point_distance.h"
#include "fcl_superellipsoid/tessellation.h"
#include "workload.h"

namespace fcl_superellipsoid {
namespace bench {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// Median of `repetitions` timings of f (ms); f's last value is kept in `value`.
double medianMs(int repetitions, const std::function<double()>& f, double& value) {
  std::vector<double> ms;
  for (int i = 0; i < repetitions; ++i) {
    const Clock::time_point start = Clock::now();
    value = f();
    ms.push_back(msSince(start));
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

}  // namespace

std::vector<ScalingRow> runScaling(const std::vector<int>& sizes, int repetitions,
                                   const std::string& csv_path) {
  const auto shape = std::make_shared<Superellipsoidd>(3.5, 3.0, 2.0, 0.4, 0.3);  // cloth scene
  std::vector<ScalingRow> rows;
  std::printf(
      "\nScaling: point clouds around the cloth-scene shape (3.5, 3, 2; 0.4, 0.3), 1 %% of "
      "the vertices within\n+-0.05 x size of the surface; Exact solver; median of %d; one "
      "thread (the batched, threaded path is issue #6)\n",
      repetitions);
  std::printf("%10s  %-22s %10s %12s %12s %14s\n", "vertices", "path", "BVH [ms]", "query [ms]",
              "ns/vertex", "result");
  for (const int n : sizes) {
    TriangleMesh<double> cloud;
    cloud.vertices = makeSceneCloud(*shape, n, 0.01, 99);
    double value = 0;
    const double single_ms = medianMs(
        repetitions,
        [&] {
          double best = std::numeric_limits<double>::infinity();
          for (const Vector3<double>& v : cloud.vertices)
            best = std::min(best, pointDistance(*shape, v).distance);
          return best;
        },
        value);
    rows.push_back({n, "single queries", 0, single_ms, 1e6 * single_ms / n, value});

    const Clock::time_point start = Clock::now();
    const auto model = makeBVHModel<fcl::OBBRSSd>(cloud);
    const double build_ms = msSince(start);
    const fcl::CollisionObjectd a(shape), b(model);
    const double distance_ms = medianMs(
        repetitions,
        [&] {
          fcl::DistanceResultd result;
          return fcl_superellipsoid::distance(&a, &b, fcl::DistanceRequestd(true, true), result);
        },
        value);
    rows.push_back({n, "front end distance", build_ms, distance_ms, 1e6 * distance_ms / n, value});
    const double collide_ms = medianMs(
        repetitions,
        [&] {
          fcl::CollisionResultd result;
          return double(
              fcl_superellipsoid::collide(&a, &b, fcl::CollisionRequestd(n, true), result));
        },
        value);
    rows.push_back({n, "front end collide", build_ms, collide_ms, 1e6 * collide_ms / n, value});
    for (std::size_t r = rows.size() - 3; r < rows.size(); ++r) {
      std::printf("%10d  %-22s %10.1f %12.3f %12.1f %14.6g\n", rows[r].vertices,
                  rows[r].path.c_str(), rows[r].setup_ms, rows[r].total_ms, rows[r].ns_per_vertex,
                  rows[r].result);
    }
  }
  std::printf(
      "result: the minimum signed distance (single queries, front end distance) or the "
      "number of\npenetrating vertices (collide). The BVH is built once per cloud, as a "
      "scene would.\n");
  if (!csv_path.empty()) {
    std::ofstream csv(csv_path);
    csv << "vertices,path,setup_ms,total_ms,ns_per_vertex,result\n";
    for (const ScalingRow& r : rows) {
      csv << r.vertices << ",\"" << r.path << "\"," << r.setup_ms << ',' << r.total_ms << ','
          << r.ns_per_vertex << ',' << r.result << '\n';
    }
  }
  return rows;
}

}  // namespace bench
}  // namespace fcl_superellipsoid
