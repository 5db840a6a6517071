#ifndef FCL_SUPERELLIPSOID_BENCH_WORKLOAD_H
#define FCL_SUPERELLIPSOID_BENCH_WORKLOAD_H

// What the benchmark asks: the shapes, and the query points with their ground truth.

#include <string>
#include <vector>

#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {
namespace bench {

struct BenchShape {
  std::string name;  // "(0.3; 0.3)" for the paper's unit shapes, a label otherwise
  Vector3<double> radii;
  double eps1, eps2;
  bool paper;  // one of the paper's 7 (Tables 1–4)
  Superellipsoid<double> make() const { return {radii, eps1, eps2}; }
};

/// The paper's 7 unit shapes, then the hard ones: sharp (0.1; 0.1), pinched (1.9; 1.9),
/// mixed (0.1; 1.9), the paper's cloth-scene shape (3.5, 3, 2; 0.4, 0.3), and an ellipsoid
/// (3, 2, 1; 1, 1) on which FCL's own Ellipsoid answers too.
const std::vector<BenchShape>& benchShapes();

/// The point distributions. Offsets and depths scale with the shape's size (largest radius),
/// so for the paper's unit shapes they are the paper's.
enum class Side {
  kPaperOutside,  // the paper's Tables 1, 3: surface points stepped +0.05 along the normal
  kPaperInside,   // the paper's Tables 2, 4: stepped −0.015 along the normal
  kNear,          // stepped out by a uniform 0 … 0.5 × size
  kFar,           // stepped out by 1 … 1000 × size, log-uniform
  kInside,        // uniform in the shape's volume
};
const std::vector<Side>& allSides();
/// Short key ("paper+0.05", "paper-0.015", "near", "far", "inside") and a description.
const char* sideKey(Side side);
const char* sideDescription(Side side);
/// True where every point's truth comes from construction (no reference needed).
bool truthByConstruction(Side side);

/// Query points in the shape's frame with their ground truth. Outside points are a surface
/// point P stepped along its normal by t > 0: the shape is convex, so P is the nearest point
/// and t the distance, exactly. Inside points (stepping inwards is not exact: another part of
/// the surface can be nearer) get the independent long-double reference
/// (test_support/reference_distance.h) for their first `truth_count` points.
struct PointSet {
  Side side;
  std::vector<Vector3<double>> points;
  std::vector<double> true_distance;          // signed; size truth_count
  std::vector<Vector3<double>> true_nearest;  // size truth_count
  int truthCount() const { return static_cast<int>(true_distance.size()); }
};

/// `n` points (reference truth for min(n, reference_n) inside points, on all cores).
/// Surface points are the paper's: uniform parametric angles η ∈ (−π/2, π/2), ω ∈ (−π, π).
PointSet makePointSet(const BenchShape& shape, Side side, int n, int reference_n, unsigned seed);

/// A contact band: n vertices within ±half_width (length units) of the surface, stepped along
/// the normal by a uniform offset from surface points of uniform parametric angles, so about
/// half of them are inside. What a cloth resting on the shape asks every step.
std::vector<Vector3<double>> makeContactBand(const Superellipsoid<double>& shape, int n,
                                             double half_width, unsigned seed);

/// A scene's point cloud around `shape` (at the origin): `near_fraction` of the n vertices
/// within ±0.05 × size of the surface (stepped along the normal), the rest uniform in a
/// cube of side 20 × size. The culling and scaling sections use it.
std::vector<Vector3<double>> makeSceneCloud(const Superellipsoid<double>& shape, int n,
                                            double near_fraction, unsigned seed);

}  // namespace bench
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_BENCH_WORKLOAD_H
