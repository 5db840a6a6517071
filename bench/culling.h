#ifndef FCL_SUPERELLIPSOID_BENCH_CULLING_H
#define FCL_SUPERELLIPSOID_BENCH_CULLING_H

namespace fcl_superellipsoid {
namespace bench {

/// The BVH vertex traversal against brute force on a large point cloud (about 1 % of its
/// vertices near the shape): fraction of vertices reached and solved, time ratio.
int runCulling(int vertices);

}  // namespace bench
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_BENCH_CULLING_H
