#include "scaling.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <thread>
#include <tuple>

#include "fcl_superellipsoid/batch_distance.h"
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

void printRow(const ScalingRow& r) {
  std::printf("%-6s %-7s %9d  %-28s %7d %9.1f %12.3f %11.1f %14.6g", r.cloud.c_str(),
              r.scalar.c_str(), r.vertices, r.path.c_str(), r.threads, r.setup_ms, r.total_ms,
              r.ns_per_vertex, r.result);
  if (r.vs_single > 0) std::printf(" %9.2f", r.vs_single);
  if (r.simd_share >= 0) std::printf(" %9.1f %%", 100 * r.simd_share);
  std::printf("\n");
}

/// Share of the vertices the batched call solved that the SIMD solver answered; −1 (not shown)
/// where the cull left none to solve.
double simdShare(const BatchStatistics& s) {
  const std::size_t solved = s.simd + s.scalar;
  return solved == 0 ? -1.0 : double(s.simd) / double(solved);
}

/// The threads a batched call with BatchOptions::threads = `threads` really uses for n vertices.
int threadsUsed(int threads, int n) {
  const bool parallel = threads != 1 && n >= BatchOptions<double>().min_parallel_vertices;
  return parallel ? int(std::thread::hardware_concurrency()) : 1;
}

/// Median time of verticesWithinMargin (shape at the origin) into one reused vector; value = the
/// count found.
template <typename S>
double withinMarginMs(const Superellipsoid<S>& shape, const Eigen::Ref<const Matrix3X<S>>& p_WV,
                      S margin, int threads, int repetitions, double& value,
                      BatchStatistics& statistics) {
  BatchOptions<S> options;
  options.threads = threads;
  options.statistics = &statistics;
  std::vector<VertexContact<S>> contacts;  // reused, as a simulation reuses it every step
  return medianMs(
      repetitions,
      [&] {
        verticesWithinMargin(shape, fcl::Transform3<S>::Identity(), p_WV, margin, contacts,
                             options);
        return double(contacts.size());
      },
      value);
}

/// The scene: single queries, the FCL front end, and the batched within-margin query.
void sceneRows(const std::shared_ptr<Superellipsoidd>& shape, int n, int repetitions,
               std::vector<ScalingRow>& rows) {
  TriangleMesh<double> cloud;
  cloud.vertices = makeSceneCloud(*shape, n, 0.01, 99);
  double single_ms = 0;
  auto add = [&](const char* path, int threads, double setup_ms, double ms, double value,
                 double simd_share = -1) {
    rows.push_back({"scene", "double", n, path, threads, setup_ms, ms, 1e6 * ms / n, value,
                    single_ms > 0 ? single_ms / ms : 0, simd_share});
    printRow(rows.back());
  };
  double value = 0;
  double ms = medianMs(
      repetitions,
      [&] {
        double best = std::numeric_limits<double>::infinity();
        for (const Vector3<double>& v : cloud.vertices)
          best = std::min(best, pointDistance(*shape, v).distance);
        return best;
      },
      value);
  add("single queries (min)", 1, 0, ms, value);
  single_ms = ms;

  const Clock::time_point start = Clock::now();
  const auto model = makeBVHModel<fcl::OBBRSSd>(cloud);
  const double build_ms = msSince(start);
  const fcl::CollisionObjectd a(shape), b(model);
  ms = medianMs(
      repetitions,
      [&] {
        fcl::DistanceResultd result;
        return fcl_superellipsoid::distance(&a, &b, fcl::DistanceRequestd(true, true), result);
      },
      value);
  add("front end distance", 1, build_ms, ms, value);
  ms = medianMs(
      repetitions,
      [&] {
        fcl::CollisionResultd result;
        return double(fcl_superellipsoid::collide(&a, &b, fcl::CollisionRequestd(n, true), result));
      },
      value);
  add("front end collide", 1, build_ms, ms, value);

  const Eigen::Map<const Matrix3X<double>> p_WV(cloud.vertices[0].data(), 3, n);
  for (int threads : {1, 0}) {
    BatchStatistics statistics;
    ms = withinMarginMs<double>(*shape, p_WV, 0.0, threads, repetitions, value, statistics);
    add("batch within margin 0", threadsUsed(threads, n), 0, ms, value, simdShare(statistics));
  }
}

/// All-near or all-far clouds: single queries against the batched paths.
template <typename S>
void batchRows(const Superellipsoid<S>& shape, const char* kind, int n, int repetitions,
               std::vector<ScalingRow>& rows) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1), eta(-M_PI / 2, M_PI / 2), omega(-M_PI, M_PI);
  const bool near = std::string(kind) == "near";
  Matrix3X<S> p_WV(3, n);
  for (int i = 0; i < n; ++i) {
    const Vector3<S> p = shape.surfacePoint(S(eta(rng)), S(omega(rng)));
    const S t = near ? S(0.05 * u(rng)) * shape.size() : S(10 + 5 * u(rng)) * shape.size();
    p_WV.col(i) = p + t * shape.normal(p);
  }
  const char* scalar = std::is_same<S, float>::value ? "float" : "double";
  double single_ms = 0;
  auto add = [&](const char* path, int threads, double ms, double value, double simd_share = -1) {
    rows.push_back({kind, scalar, n, path, threads, 0, ms, 1e6 * ms / n, value,
                    single_ms > 0 ? single_ms / ms : 0, simd_share});
    printRow(rows.back());
  };
  const fcl::Transform3<S> X_WS = fcl::Transform3<S>::Identity();
  double value = 0;
  double ms = medianMs(
      repetitions,
      [&] {
        double sum = 0;
        for (int i = 0; i < n; ++i)
          sum += double(pointDistance(shape, Vector3<S>(p_WV.col(i))).distance);
        return sum;
      },
      value);
  add("single queries (sum)", 1, ms, value);
  single_ms = ms;
  BatchDistanceResult<S> batch;
  BatchStatistics statistics;
  // The batched per-vertex query on the scalar path (one thread), then on SIMD lanes.
  for (const auto& [vectorize, threads, path] :
       {std::tuple{false, 1, "batch distance scalar (sum)"},
        std::tuple{true, 1, "batch distance (sum)"}, std::tuple{true, 0, "batch distance (sum)"}}) {
    BatchOptions<S> options;
    options.threads = threads;
    options.vectorize = vectorize;
    options.statistics = &statistics;
    ms = medianMs(
        repetitions,
        [&] {
          batchDistance(shape, X_WS, p_WV, batch, options);
          return double(batch.distance.template cast<double>().sum());
        },
        value);
    add(path, threadsUsed(threads, n), ms, value, simdShare(statistics));
  }
  for (int threads : {1, 0}) {
    ms = withinMarginMs<S>(shape, p_WV, S(0.05) * shape.size(), threads, repetitions, value,
                           statistics);
    add("batch within 0.05 (count)", threadsUsed(threads, n), ms, value, simdShare(statistics));
  }
  // A simulation step: the previous step's nearest points (vertices 0.001 × size away) as
  // warm starts.
  Matrix3X<S> previous_step = p_WV;
  for (int i = 0; i < n; ++i) {
    previous_step.col(i) += S(0.001) * shape.size() * Vector3<S>(S(u(rng)), S(u(rng)), S(u(rng)));
  }
  BatchDistanceResult<S> previous;
  batchDistance(shape, X_WS, previous_step, previous);
  BatchOptions<S> warm;
  warm.threads = 1;
  warm.warm_start_W = &previous.nearest_point;
  warm.statistics = &statistics;
  ms = medianMs(
      repetitions,
      [&] {
        batchDistance(shape, X_WS, p_WV, batch, warm);
        return double(batch.distance.template cast<double>().sum());
      },
      value);
  add("batch distance warm (sum)", 1, ms, value, simdShare(statistics));
}

}  // namespace

std::vector<ScalingRow> runScaling(const std::vector<int>& sizes, int repetitions,
                                   const std::string& csv_path) {
  const auto shape = std::make_shared<Superellipsoidd>(3.5, 3.0, 2.0, 0.4, 0.3);  // cloth scene
  const Superellipsoidf shape_f(3.5f, 3.0f, 2.0f, 0.4f, 0.3f);
  std::vector<ScalingRow> rows;
  std::printf(
      "\nScaling: point clouds around the cloth-scene shape (3.5, 3, 2; 0.4, 0.3), Exact "
      "solver, median of %d.\nscene: 1 %% of the vertices within +-0.05 x size of the "
      "surface, the rest in a cube of side 20 x size;\nnear: all within +-0.05 x size; "
      "far: all 5 to 15 x size away. threads: those a call really used (of %u). Batched paths "
      "run on SIMD lanes\n(%s) unless named scalar. x single: speed-up over single queries on "
      "the same cloud, this run.\nSIMD: share of the solved vertices the SIMD solver answered "
      "(the rest it handed to the scalar solver).\n",
      repetitions, std::thread::hardware_concurrency(), simdInstructionSet());
  std::printf("%-6s %-7s %9s  %-28s %7s %9s %12s %11s %14s %9s %11s\n", "cloud", "scalar",
              "vertices", "path", "threads", "BVH [ms]", "query [ms]", "ns/vertex", "result",
              "x single", "SIMD");
  for (const int n : sizes) sceneRows(shape, n, repetitions, rows);
  for (const char* kind : {"near", "far"}) {
    for (const int n : sizes) {
      batchRows(*shape, kind, n, repetitions, rows);
      batchRows(shape_f, kind, n, repetitions, rows);
    }
  }
  std::printf(
      "result: the minimum or the sum of the signed distances, or the number of vertices "
      "found; paths on\nthe same cloud agree. The BVH is built once per cloud, as a scene "
      "would.\n");
  if (!csv_path.empty()) {
    std::ofstream csv(csv_path);
    csv << "cloud,scalar,vertices,path,threads,setup_ms,total_ms,ns_per_vertex,result,"
           "vs_single,simd_share\n";
    for (const ScalingRow& r : rows) {
      csv << r.cloud << ',' << r.scalar << ',' << r.vertices << ",\"" << r.path << "\","
          << r.threads << ',' << r.setup_ms << ',' << r.total_ms << ',' << r.ns_per_vertex << ','
          << r.result << ',' << r.vs_single << ',' << r.simd_share << '\n';
    }
  }
  return rows;
}

}  // namespace bench
}  // namespace fcl_superellipsoid
