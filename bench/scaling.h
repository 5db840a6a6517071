#ifndef FCL_SUPERELLIPSOID_BENCH_SCALING_H
#define FCL_SUPERELLIPSOID_BENCH_SCALING_H

#include <string>
#include <vector>

namespace fcl_superellipsoid {
namespace bench {

struct ScalingRow {
  int vertices;
  std::string path;  // "single queries", "front end distance", "front end collide"
  double setup_ms;   // building the point cloud's BVH (0 for single queries)
  double total_ms;   // the query itself (median of repetitions)
  double ns_per_vertex;
  double result;  // min distance or contact count: the paths must agree
};

/// Time per vertex and in total for point clouds of each size (1 % within ±0.05 × size of
/// the surface, as in a scene; makeSceneCloud): every vertex through the Exact solver one at
/// a time, and the FCL front end (BVH culling) for distance and collision. Prints a table;
/// writes CSV to csv_path unless empty.
std::vector<ScalingRow> runScaling(const std::vector<int>& sizes, int repetitions,
                                   const std::string& csv_path);

}  // namespace bench
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_BENCH_SCALING_H
