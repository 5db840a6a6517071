#include "synthetic_cloud.h"

#include <fcl_superellipsoid/tessellation.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace fse_fit {

namespace fse = fcl_superellipsoid;

namespace {
constexpr int kTessellationVertices = 20000;
}  // namespace

std::vector<Eigen::Vector3d> surfaceSamples(const Superquadric& sq, int count, std::uint64_t seed) {
  const fse::Superellipsoidd shape = sq.shape();
  const fse::TriangleMesh<double> mesh = fse::tessellate(shape, kTessellationVertices);
  std::vector<double> areas;
  areas.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    areas.push_back((mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm());
  }
  std::mt19937_64 random(seed);
  std::discrete_distribution<std::size_t> triangle(areas.begin(), areas.end());
  std::uniform_real_distribution<double> unit(0, 1);
  const fcl::Transform3d X_WS = sq.pose();
  std::vector<Eigen::Vector3d> out;
  out.reserve(count);
  for (int i = 0; i < count; ++i) {
    const auto& t = mesh.triangles[triangle(random)];
    double u = unit(random), v = unit(random);
    if (u + v > 1) {
      u = 1 - u;
      v = 1 - v;
    }
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d p = a + u * (mesh.vertices[t[1]] - a) + v * (mesh.vertices[t[2]] - a);
    out.push_back(X_WS * (p / shape.gauge(p)));
  }
  return out;
}

SyntheticCloud makeCloud(const CloudSpec& spec) {
  const int outliers = static_cast<int>(std::lround(spec.outliers * spec.points));
  const int inliers = spec.points - outliers;
  const fse::Superellipsoidd shape = spec.truth.shape();
  const fcl::Transform3d X_WS = spec.truth.pose();
  SyntheticCloud cloud;
  std::uint64_t seed = spec.seed;
  while (static_cast<int>(cloud.inliers.size()) < inliers) {
    for (const Eigen::Vector3d& p : surfaceSamples(spec.truth, inliers, seed++)) {
      if (static_cast<int>(cloud.inliers.size()) == inliers) break;
      if (spec.partial) {
        const Eigen::Vector3d n_W = X_WS.linear() * shape.normal(X_WS.inverse() * p);
        if (n_W.dot(spec.view) <= 0) continue;
      }
      cloud.inliers.push_back(p);
    }
  }
  std::mt19937_64 random(spec.seed ^ 0x9e3779b97f4a7c15ULL);
  std::normal_distribution<double> gauss(0, spec.noise * spec.truth.size());
  if (spec.noise > 0) {
    for (Eigen::Vector3d& p : cloud.inliers)
      p += Eigen::Vector3d(gauss(random), gauss(random), gauss(random));
  }
  cloud.points = cloud.inliers;
  // The world bounding box of the posed shape, from its corners, scaled 1.5 about its centre.
  Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY), high = -low;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner((c & 1 ? 1 : -1) * spec.truth.radii[0],
                                 (c & 2 ? 1 : -1) * spec.truth.radii[1],
                                 (c & 4 ? 1 : -1) * spec.truth.radii[2]);
    low = low.cwiseMin(X_WS * corner);
    high = high.cwiseMax(X_WS * corner);
  }
  const Eigen::Vector3d mid = (low + high) / 2, half = 0.75 * (high - low);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int i = 0; i < outliers; ++i) {
    cloud.points.push_back(
        mid + half.cwiseProduct(Eigen::Vector3d(unit(random), unit(random), unit(random))));
  }
  return cloud;
}

double surfaceRms(const Superquadric& sq, const std::vector<Eigen::Vector3d>& points) {
  double sum = 0;
  for (const double d : signedDistances(sq, points)) sum += d * d;
  return std::sqrt(sum / static_cast<double>(points.size()));
}

double surfaceError(const Superquadric& fitted, const Superquadric& reference, int count) {
  const double a = surfaceRms(fitted, surfaceSamples(reference, count, 7));
  const double b = surfaceRms(reference, surfaceSamples(fitted, count, 8));
  return std::sqrt((a * a + b * b) / 2) / reference.size();
}

}  // namespace fse_fit
