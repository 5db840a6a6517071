#ifndef FCL_SUPERELLIPSOID_BENCH_SCALING_H
#define FCL_SUPERELLIPSOID_BENCH_SCALING_H

#include <string>
#include <vector>

namespace fcl_superellipsoid {
namespace bench {

struct ScalingRow {
  std::string cloud;   // "scene" (1 % near the surface), "near" (all), "far" (all)
  std::string scalar;  // "double" or "float"
  int vertices;
  std::string path;  // "single queries", "front end distance", "batch distance", ...
  int threads;
  double setup_ms;  // building the point cloud's BVH (front end only)
  double total_ms;  // the query itself (median of repetitions)
  double ns_per_vertex;
  double result;      // min distance or vertex count: paths on one cloud must agree
  double vs_single;   // speed-up over single queries on the same cloud in the same run (0: none)
  double simd_share;  // batched rows: share of the solved vertices the SIMD solver answered
                      // (−1: not a batched row, or none left to solve)
};

/// Time per vertex and in total for point clouds of each size, around the cloth-scene shape:
///  - a scene cloud (1 % within ±0.05 × size of the surface; makeSceneCloud), double: every
///    vertex through the Exact solver one at a time, the FCL front end (BVH culling) for
///    distance and collision, and the batched within-margin query;
///  - all-near and all-far clouds, float and double: single queries against the batched
///    per-vertex query on the scalar path and on SIMD lanes (BatchOptions::vectorize), on one
///    thread and on all, the within-margin query, and warm starts.
/// Prints tables; writes CSV to csv_path unless empty.
std::vector<ScalingRow> runScaling(const std::vector<int>& sizes, int repetitions,
                                   const std::string& csv_path);

}  // namespace bench
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_BENCH_SCALING_H
