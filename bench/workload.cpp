#include "workload.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <thread>

#include "reference_distance.h"  // test_support/

namespace fcl_superellipsoid {
namespace bench {

const std::vector<BenchShape>& benchShapes() {
  const Vector3<double> unit(1, 1, 1);
  static const std::vector<BenchShape> shapes = {
      {"(0.3; 0.3)", unit, 0.3, 0.3, true},
      {"(0.65; 0.65)", unit, 0.65, 0.65, true},
      {"(1; 1)", unit, 1.0, 1.0, true},
      {"(1.35; 1.35)", unit, 1.35, 1.35, true},
      {"(1.7; 1.7)", unit, 1.7, 1.7, true},
      {"(1; 0.3)", unit, 1.0, 0.3, true},
      {"(1; 1.6)", unit, 1.0, 1.6, true},
      {"(0.1; 0.1)", unit, 0.1, 0.1, false},
      {"(1.9; 1.9)", unit, 1.9, 1.9, false},
      {"(0.1; 1.9)", unit, 0.1, 1.9, false},
      {"cloth 3.5x3x2 (0.4; 0.3)", Vector3<double>(3.5, 3.0, 2.0), 0.4, 0.3, false},
      {"ellipsoid 3x2x1 (1; 1)", Vector3<double>(3.0, 2.0, 1.0), 1.0, 1.0, false},
  };
  return shapes;
}

namespace {

/// One row per point set, in Side's order: its key and what it is.
struct SideInfo {
  Side side;
  const char* key;
  const char* description;
};

constexpr SideInfo kSides[] = {
    {Side::kPaperOutside, "paper+0.05", "surface points +0.05 x size along the normal (paper)"},
    {Side::kPaperInside, "paper-0.015", "surface points -0.015 x size along the normal (paper)"},
    {Side::kNear, "near", "surface points +U(0, 0.5) x size along the normal"},
    {Side::kFar, "far", "surface points +10^U(0, 3) x size along the normal"},
    {Side::kInside, "inside", "uniform in the volume"},
};

const SideInfo& info(Side side) {
  for (const SideInfo& s : kSides) {
    if (s.side == side) return s;
  }
  throw std::invalid_argument("unknown Side " + std::to_string(static_cast<int>(side)));
}

}  // namespace

const std::vector<Side>& allSides() {
  static const std::vector<Side> sides = [] {
    std::vector<Side> out;
    for (const SideInfo& s : kSides) out.push_back(s.side);
    return out;
  }();
  return sides;
}

const char* sideKey(Side side) { return info(side).key; }

const char* sideDescription(Side side) { return info(side).description; }

bool truthByConstruction(Side side) { return side != Side::kPaperInside && side != Side::kInside; }

namespace {

/// The long-double reference for points[0, n), spread over all cores.
void referenceTruth(const BenchShape& s, PointSet& set, int n) {
  const test::ReferenceDistance reference({s.radii[0], s.radii[1], s.radii[2]}, s.eps1, s.eps2);
  set.true_distance.assign(n, 0.0);
  set.true_nearest.assign(n, Vector3<double>::Zero());
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      for (int i = static_cast<int>(t); i < n; i += static_cast<int>(threads)) {
        const Vector3<double>& x = set.points[i];
        const test::ReferenceResult r = reference.query({x[0], x[1], x[2]});
        set.true_distance[i] = static_cast<double>(r.distance);
        for (int k = 0; k < 3; ++k) set.true_nearest[i][k] = static_cast<double>(r.nearest[k]);
      }
    });
  }
  for (std::thread& th : pool) th.join();
}

}  // namespace

PointSet makePointSet(const BenchShape& s, Side side, int n, int reference_n, unsigned seed) {
  if (n < 1) throw std::invalid_argument("makePointSet: n = " + std::to_string(n) + " < 1");
  const Superellipsoid<double> shape = s.make();
  const double size = shape.size();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> eta(-M_PI / 2, M_PI / 2), omega(-M_PI, M_PI), unit(0, 1),
      box(-1, 1);
  PointSet set{side, {}, {}, {}};
  set.points.reserve(n);
  if (side == Side::kInside) {
    while (static_cast<int>(set.points.size()) < n) {
      const Vector3<double> x =
          shape.radii().cwiseProduct(Vector3<double>(box(rng), box(rng), box(rng)));
      if (shape.gauge(x) < 1) set.points.push_back(x);
    }
    referenceTruth(s, set, std::min(n, reference_n));
    return set;
  }
  std::vector<Vector3<double>> surface(n);
  for (int i = 0; i < n; ++i) {
    surface[i] = shape.surfacePoint(eta(rng), omega(rng));
    double t = 0;
    switch (side) {
      case Side::kPaperOutside:
        t = 0.05 * size;
        break;
      case Side::kPaperInside:
        t = -0.015 * size;
        break;
      case Side::kNear:
        t = 0.5 * size * unit(rng);
        break;
      case Side::kFar:
        t = size * std::pow(10.0, 3 * unit(rng));
        break;
      case Side::kInside:
        break;
    }
    set.points.push_back(surface[i] + t * shape.normal(surface[i]));
    if (t >= 0) {
      set.true_distance.push_back(t);
      set.true_nearest.push_back(surface[i]);
    }
  }
  if (side == Side::kPaperInside) referenceTruth(s, set, std::min(n, reference_n));
  return set;
}

namespace {

/// A surface point of uniform parametric angles stepped along its normal by U(−1, 1) × half_width.
Vector3<double> bandPoint(const Superellipsoid<double>& shape, double half_width,
                          std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1), eta(-M_PI / 2, M_PI / 2), omega(-M_PI, M_PI);
  const Vector3<double> p = shape.surfacePoint(eta(rng), omega(rng));
  return p + half_width * u(rng) * shape.normal(p);
}

}  // namespace

std::vector<Vector3<double>> makeContactBand(const Superellipsoid<double>& shape, int n,
                                             double half_width, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Vector3<double>> band;
  band.reserve(n);
  for (int i = 0; i < n; ++i) band.push_back(bandPoint(shape, half_width, rng));
  return band;
}

std::vector<Vector3<double>> makeSceneCloud(const Superellipsoid<double>& shape, int n,
                                            double near_fraction, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const double size = shape.size();
  const int near = static_cast<int>(std::lround(near_fraction * n));
  std::vector<Vector3<double>> cloud;
  cloud.reserve(n);
  for (int i = 0; i < n; ++i) {
    if (i < near) {
      cloud.push_back(bandPoint(shape, 0.05 * size, rng));
    } else {
      cloud.push_back(10 * size * Vector3<double>(u(rng), u(rng), u(rng)));
    }
  }
  return cloud;
}

}  // namespace bench
}  // namespace fcl_superellipsoid
