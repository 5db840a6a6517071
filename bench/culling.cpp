#include "culling.h"

#include <chrono>
#include <cstdio>
#include <random>

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

  std::printf("%-28s %12s %12s %12s %12s %10s\n", "query", "result", "reached", "solved",
              "time [ms]", "speedup");
  std::printf("%-28s %12.6f %11.2f%% %11.2f%% %12.1f %10s\n", "brute force (distance)", brute,
              100.0, 100.0, 1e3 * t_brute, "1");
  for (int pass = 0; pass < 2; ++pass) {
    const bool collision = pass == 1;
    vertexTraversalStats() = {};
    t0 = Clock::now();
    double value;
    if (collision) {
      fcl::CollisionResultd result;
      fcl_superellipsoid::collide(&a, &b, fcl::CollisionRequestd(vertices, true), result);
      value = double(result.numContacts());
    } else {
      fcl::DistanceResultd result;
      fcl_superellipsoid::distance(&a, &b, fcl::DistanceRequestd(true, true), result);
      value = result.min_distance;
    }
    const double t = seconds(t0);
    const VertexTraversalStats s = vertexTraversalStats();
    std::printf("%-28s %12.6g %11.3f%% %11.3f%% %12.2f %10.0f\n",
                collision ? "front end collide (all)" : "front end distance (signed)", value,
                100.0 * s.vertices_bounded / vertices, 100.0 * s.vertices_solved / vertices,
                1e3 * t, t_brute / t);
  }
  std::printf(
      "\nbrute force: %zu penetrating vertices. 'reached': vertices the traversal "
      "bounded; 'solved': those\nthat needed the point solver. Speedup: brute-force "
      "time / traversal time, same process.\n",
      brute_inside);
  return 0;
}

}  // namespace bench
}  // namespace fcl_superellipsoid
