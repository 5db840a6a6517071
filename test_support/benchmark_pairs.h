#ifndef FCL_SUPERELLIPSOID_TEST_SUPPORT_BENCHMARK_PAIRS_H
#define FCL_SUPERELLIPSOID_TEST_SUPPORT_BENCHMARK_PAIRS_H

// The configurations the benchmark times a pair's distance and derivatives on (fse_microbench
// PairDistance/, PairGradient/, PairJacobians/), shared with the test that checks the
// derivatives on them (test/fcl_glue/test_pair_derivatives.cpp): a superellipsoid body
// (ε = (0.6, 1.2), a rounded box-like body) posed around a partner at the origin, 64 poses, half
// of them overlapping (a quarter of the size deep at most), half apart (up to half the size).

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>

#include <Eigen/Geometry>
#include <memory>
#include <random>
#include <vector>

#include "fcl_superellipsoid/pair_derivatives.h"
#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {
namespace test {

enum class BenchmarkPartner { kSuperellipsoid, kEllipsoid, kBox, kCapsule, kCylinder };

constexpr BenchmarkPartner kBenchmarkPartners[] = {
    BenchmarkPartner::kSuperellipsoid, BenchmarkPartner::kEllipsoid, BenchmarkPartner::kBox,
    BenchmarkPartner::kCapsule, BenchmarkPartner::kCylinder};

inline const char* partnerName(BenchmarkPartner partner) {
  switch (partner) {
    case BenchmarkPartner::kSuperellipsoid:
      return "superellipsoid";
    case BenchmarkPartner::kEllipsoid:
      return "ellipsoid";
    case BenchmarkPartner::kBox:
      return "box";
    case BenchmarkPartner::kCapsule:
      return "capsule";
    case BenchmarkPartner::kCylinder:
      return "cylinder";
  }
  return "";
}

/// The body's parameters: radii (0.5, 0.4, 0.3), exponents (0.6, 1.2); and the superellipsoid
/// partner's: (0.6, 0.5, 0.4), (0.3, 0.8).
constexpr double kBenchmarkBody[5] = {0.5, 0.4, 0.3, 0.6, 1.2};
constexpr double kBenchmarkSuperellipsoidPartner[5] = {0.6, 0.5, 0.4, 0.3, 0.8};

inline std::shared_ptr<Superellipsoid<double>> benchmarkBody() {
  const double* p = kBenchmarkBody;
  return std::make_shared<Superellipsoid<double>>(p[0], p[1], p[2], p[3], p[4]);
}

inline std::shared_ptr<fcl::CollisionGeometry<double>> benchmarkPartner(BenchmarkPartner partner) {
  switch (partner) {
    case BenchmarkPartner::kSuperellipsoid: {
      const double* p = kBenchmarkSuperellipsoidPartner;
      return std::make_shared<Superellipsoid<double>>(p[0], p[1], p[2], p[3], p[4]);
    }
    case BenchmarkPartner::kEllipsoid:
      return std::make_shared<fcl::Ellipsoid<double>>(0.6, 0.5, 0.4);
    case BenchmarkPartner::kBox:
      return std::make_shared<fcl::Box<double>>(1.2, 1.0, 0.8);
    case BenchmarkPartner::kCapsule:
      return std::make_shared<fcl::Capsule<double>>(0.3, 0.8);
    case BenchmarkPartner::kCylinder:
      return std::make_shared<fcl::Cylinder<double>>(0.4, 0.8);
  }
  return nullptr;
}

/// The body's 64 poses about `partner` at the identity: a random rotation, and a random
/// direction along which the body slides until the pair's signed distance is the drawn gap
/// (uniform in [−0.25, 0.5] × the body's size, met within 1e-3 of it).
inline std::vector<fcl::Transform3d> benchmarkPoses(const Superellipsoid<double>& body,
                                                    const fcl::CollisionGeometry<double>& partner) {
  std::mt19937 rng(53);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> gap(-0.25, 0.5);
  const fcl::Transform3d X_WO = fcl::Transform3d::Identity();
  std::vector<fcl::Transform3d> poses;
  while (poses.size() < 64) {
    fcl::Transform3d X = fcl::Transform3d::Identity();
    X.linear() = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    const Vector3<double> direction = Vector3<double>(g(rng), g(rng), g(rng)).normalized();
    const double target = gap(rng) * body.size();
    double t = 2.0;
    for (int k = 0; k < 30; ++k) {
      X.translation() = t * direction;
      t += target - pairDistanceDerivatives(body, X, partner, X_WO).distance;
    }
    poses.push_back(X);
  }
  return poses;
}

}  // namespace test
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TEST_SUPPORT_BENCHMARK_PAIRS_H
