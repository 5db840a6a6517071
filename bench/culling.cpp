#include "culling.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

#include "fcl_superellipsoid/batch_distance.h"
#include "fcl_superellipsoid/diagnostics.h"
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_superellipsoid/point_distance.h"
#include "fcl_superellipsoid/tessellation.h"
#include "workload.h"

namespace fcl_superellipsoid {
namespace bench {

int runCulling(int vertices) {
  using Clock = std::chrono::steady_clock;
  const auto shape = std::make_shared<Superellipsoidd>(1.0, 0.8, 0.6, 0.5, 1.2);
  TriangleMesh<double> cloud;
  cloud.vertices = makeSceneCloud(*shape, vertices, 0.01, 17);
  const int near = vertices / 100;
  const auto model = makeBVHModel<fcl::OBBRSSd>(cloud);
  fcl::CollisionObjectd a(shape), b(model);

  auto seconds = [](Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  std::printf(
      "BVH vertex traversal vs brute force: %d-vertex point cloud (OBBRSS), %d within "
      "0.05 of the surface, shape (1, 0.8, 0.6; 0.5, 1.2), Exact solver\n\n",
      vertices, near);
  // Brute force: every vertex through the point solver.
  Clock::time_point t0 = Clock::now();
  double brute = std::numeric_limits<double>::infinity();
  std::size_t brute_inside = 0;
  for (const Vector3<double>& v : cloud.vertices) {
    const double d = pointDistance(*shape, v).distance;
    brute = std::min(brute, d);
    brute_inside += d < 0;
  }
  const double t_brute = seconds(t0);

  // The penetrating vertices alone, for the batched reference row.
  Matrix3X<double> inside(3, Eigen::Index(brute_inside));
  for (std::size_t i = 0, k = 0; i < cloud.vertices.size(); ++i) {
    if (shape->gauge(cloud.vertices[i]) < 1 && k < brute_inside)
      inside.col(k++) = cloud.vertices[i];
  }

  std::printf("%-34s %12s %9s %9s %10s %8s %12s\n", "query (median of 5)", "result", "reached",
              "solved", "time [ms]", "speedup", "µs / solved");
  std::printf("%-34s %12.6f %8.2f%% %8.2f%% %10.1f %8s %12.3f\n", "brute force (distance)", brute,
              100.0, 100.0, 1e3 * t_brute, "1", 1e6 * t_brute / vertices);
  constexpr int kRepetitions = 5;
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  double collide_per_solved = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const bool collision = pass == 1;
    std::vector<double> times;
    double value = 0;
    VertexTraversalStats s;
    for (int rep = 0; rep < kRepetitions; ++rep) {
      vertexTraversalStats() = {};
      t0 = Clock::now();
      if (collision) {
        fcl::CollisionResultd result;
        fcl_superellipsoid::collide(&a, &b, fcl::CollisionRequestd(vertices, true), result);
        value = double(result.numContacts());
      } else {
        fcl::DistanceResultd result;
        fcl_superellipsoid::distance(&a, &b, fcl::DistanceRequestd(true, true), result);
        value = result.min_distance;
      }
      times.push_back(seconds(t0));
      s = vertexTraversalStats();
    }
    const double t = median(times);
    const double per_solved = s.vertices_solved > 0 ? 1e6 * t / double(s.vertices_solved) : 0;
    if (collision) collide_per_solved = per_solved;
    std::printf("%-34s %12.6g %8.3f%% %8.3f%% %10.2f %8.0f %12.3f\n",
                collision ? "front end collide (all)" : "front end distance (signed)", value,
                100.0 * s.vertices_bounded / vertices, 100.0 * s.vertices_solved / vertices,
                1e3 * t, t_brute / t, per_solved);
  }
  // The batched queries on exactly the penetrating vertices: what the traversal's solving costs
  // at best, per vertex (same threads: all of this machine's).
  std::vector<double> times;
  double batch_min = 0;
  for (int rep = 0; rep < kRepetitions; ++rep) {
    BatchDistanceResult<double> r;
    t0 = Clock::now();
    batchDistance(*shape, fcl::Transform3d::Identity(), inside, r);
    times.push_back(seconds(t0));
    batch_min = r.distance.size() > 0 ? r.distance.minCoeff() : 0;
  }
  const double t_batch = median(times);
  const double batch_per_vertex = 1e6 * t_batch / double(std::max<std::size_t>(brute_inside, 1));
  std::printf("%-34s %12.6g %8s %8.3f%% %10.2f %8s %12.3f\n", "batched, penetrating vertices only",
              batch_min, "-", 100.0 * double(brute_inside) / vertices, 1e3 * t_batch, "-",
              batch_per_vertex);
  std::printf(
      "\nbrute force: %zu penetrating vertices. 'reached': vertices the traversal bounded; "
      "'solved': those it\nhanded to the point solver (batched). Speedup: brute-force time / "
      "traversal time, same process.\nFront end collide per solved vertex / batched per vertex: "
      "%.2f.\n",
      brute_inside, collide_per_solved / batch_per_vertex);
  return 0;
}

}  // namespace bench
}  // namespace fcl_superellipsoid
