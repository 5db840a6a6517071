// Google Benchmark micro-benchmarks: one query per iteration, cycling through 1,024 points
// near the surface, for each method and shape class, and the Exact value against its
// derivatives; a new shape's first inside query, and new
// shapes' first queries near the surface against the same on warm shapes; and the
// batched Exact query over the same 1,024 points per iteration, on SIMD lanes and on the scalar
// path, and over a contact band of the cloth shape (±0.05 of its surface, half inside), also
// with the gradients (batchDistanceDerivatives); the
// contact manifold of a body resting on a face against one contact of the same pair; a pair's
// signed distance against the same with its gradient. The full
// comparison is fse_bench; this target is for profiling one method and for tracking regressions
// with Google Benchmark's tooling (--benchmark_filter, --benchmark_format=json, compare.py).

#include <benchmark/benchmark.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>

#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "benchmark_pairs.h"
#include "fcl_superellipsoid/batch_distance.h"
#include "fcl_superellipsoid/contact_manifold.h"
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_superellipsoid/pair_derivatives.h"
#include "fcl_superellipsoid/point_derivatives.h"
#include "fcl_superellipsoid/point_distance.h"
#include "methods.h"

namespace fcl_superellipsoid {
namespace bench {
namespace {

/// Shape classes by name: round, sharp-edged, pinched, and the paper's cloth-scene shape.
const BenchShape& shapeClass(const std::string& name) {
  static const std::map<std::string, std::string> classes = {{"round", "(1; 1)"},
                                                             {"sharp", "(0.1; 0.1)"},
                                                             {"pinched", "(1.9; 1.9)"},
                                                             {"cloth", "cloth 3.5x3x2 (0.4; 0.3)"}};
  for (const BenchShape& s : benchShapes()) {
    if (s.name == classes.at(name)) return s;
  }
  throw std::logic_error("no shape " + name);
}

void runQueries(benchmark::State& state, const std::string& shape_class,
                const std::function<std::unique_ptr<Method>(const BenchShape&)>& make) {
  const BenchShape& shape = shapeClass(shape_class);
  const std::unique_ptr<Method> method = make(shape);
  const PointSet points = makePointSet(shape, Side::kNear, 1024, 1, 7);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(method->query(points.points[i]));
    i = (i + 1) & 1023;
  }
  state.SetItemsProcessed(state.iterations());
}

/// The cost of the derivatives (point_derivatives.h) over the same 1,024 points near the
/// surface: the Exact value alone (pointDistance), with its gradient, and with the Jacobians.
enum class Derivatives { kValue, kGradient, kJacobians };

void runDerivatives(benchmark::State& state, const std::string& shape_class, Derivatives what) {
  const Superellipsoid<double> shape = shapeClass(shape_class).make();
  const std::vector<Vector3<double>> points =
      makePointSet(shapeClass(shape_class), Side::kNear, 1024, 1, 7).points;
  std::size_t i = 0;
  for (auto _ : state) {
    if (what == Derivatives::kValue) {
      benchmark::DoNotOptimize(pointDistance(shape, points[i]));
    } else {
      benchmark::DoNotOptimize(pointDistanceDerivatives(shape, points[i],
                                                        what == Derivatives::kGradient
                                                            ? DerivativeOrder::kGradient
                                                            : DerivativeOrder::kJacobians));
    }
    i = (i + 1) & 1023;
  }
  state.SetItemsProcessed(state.iterations());
}

/// The batched Exact query (1e-12, one thread) over the same 1,024 points per iteration, on
/// SIMD lanes or on the scalar path: its items per second are vertices per second, so the time
/// per vertex compares directly with the single-query rows above.
/// With `band`, the points are a contact band instead: within ±0.05 of the surface along the
/// normal, about half of them inside (makeContactBand; the cloth scene's contacts).
/// `gradients`: batchDistanceDerivatives instead (the distances with their gradients, SIMD).
void runBatch(benchmark::State& state, const std::string& shape_class, bool vectorize,
              bool band = false, bool gradients = false) {
  const Superellipsoid<double> shape = shapeClass(shape_class).make();
  const std::vector<Vector3<double>> points =
      band ? makeContactBand(shape, 1024, 0.05, 7)
           : makePointSet(shapeClass(shape_class), Side::kNear, 1024, 1, 7).points;
  const Eigen::Map<const Matrix3X<double>> p_WV(points[0].data(), 3, 1024);
  BatchOptions<double> options;
  options.threads = 1;
  options.vectorize = vectorize;
  BatchDistanceResult<double> result;
  BatchDerivativesResult<double> derivatives;
  for (auto _ : state) {
    if (gradients) {
      batchDistanceDerivatives(shape, fcl::Transform3d::Identity(), p_WV, derivatives, options);
      benchmark::DoNotOptimize(derivatives.d_shape.data());
    } else {
      batchDistance(shape, fcl::Transform3d::Identity(), p_WV, result, options);
      benchmark::DoNotOptimize(result.distance.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * 1024);
}

/// A new shape and one inside Exact query per iteration: the first inside query on a shape
/// computes its rolling radius (Superellipsoid::minRadiusOfCurvature(), docs/math.md), a cost a
/// scene pays once per shape it creates. Compare with the Exact rows above (one query, same
/// shape).
void runFirstInsideQuery(benchmark::State& state, const std::string& shape_class) {
  const BenchShape& bench_shape = shapeClass(shape_class);
  const PointSet points = makePointSet(bench_shape, Side::kInside, 1024, 1, 7);
  std::size_t i = 0;
  for (auto _ : state) {
    const Superellipsoid<double> shape = bench_shape.make();
    benchmark::DoNotOptimize(pointDistance(shape, points.points[i]));
    i = (i + 1) & 1023;
  }
  state.SetItemsProcessed(state.iterations());
}

/// New shapes queried near their surface (docs/benchmark.md → "Micro-benchmarks"): 256 shapes
/// with exponents in [0.1, 1.9], aspect ratios up to 100:1 and sizes from 1e-3 to 1e3, each with a
/// point within 5 % of its size of the surface along the normal, half inside. `fresh`: the shape
/// is built anew for each query (what a fit that changes the shape every step pays); otherwise
/// the same queries on shapes already queried everywhere (their caches built).
struct NearSurfaceCase {
  Vector3<double> radii;
  double e1, e2;
  Vector3<double> q;
};

const std::vector<NearSurfaceCase>& nearSurfaceCases() {
  static const std::vector<NearSurfaceCase> cases = [] {
    std::mt19937 rng(53);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<NearSurfaceCase> out;
    for (int k = 0; k < 256; ++k) {
      NearSurfaceCase c;
      c.e1 = 0.1 + 1.8 * u(rng);
      c.e2 = 0.1 + 1.8 * u(rng);
      c.radii = Vector3<double>(std::pow(100.0, u(rng)), std::pow(100.0, u(rng)),
                                std::pow(100.0, u(rng)));
      c.radii *= std::pow(10.0, -3 + 6 * u(rng)) / c.radii.maxCoeff();
      const Superellipsoid<double> shape(c.radii, c.e1, c.e2);
      const Vector3<double> p = shape.surfacePoint(M_PI * (u(rng) - 0.5), M_PI * (2 * u(rng) - 1));
      const double offset = 0.05 * shape.size() * u(rng) * (k % 2 ? 1 : -1);
      c.q = p + offset * shape.normal(p);
      out.push_back(c);
    }
    return out;
  }();
  return cases;
}

void runNearSurface(benchmark::State& state, bool fresh) {
  const std::vector<NearSurfaceCase>& cases = nearSurfaceCases();
  std::vector<Superellipsoid<double>> warm;
  for (const NearSurfaceCase& c : cases) {
    warm.emplace_back(c.radii, c.e1, c.e2);
    for (double depth : {0.99, 0.9, 0.5, 0.1}) {  // inside at every depth: every cache built
      pointDistance(warm.back(),
                    Vector3<double>(depth * c.radii.cwiseProduct(Vector3<double>(0.3, 0.5, 0.6))));
    }
    (void)warm.back().minRadiusOfCurvature();
    pointDistance(warm.back(), c.q);
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const NearSurfaceCase& c = cases[i];
    if (fresh) {
      const Superellipsoid<double> shape(c.radii, c.e1, c.e2);
      benchmark::DoNotOptimize(pointDistance(shape, c.q));
    } else {
      benchmark::DoNotOptimize(pointDistance(warm[i], c.q));
    }
    i = (i + 1) % cases.size();
  }
  state.SetItemsProcessed(state.iterations());
}

/// The contact manifold (contact_manifold.h) of a box-like body (ε = 0.2) resting on a face,
/// pressed 1e-3 of its size into it and tilted up to 0.02 rad, over 64 such poses: against a
/// halfspace, another box-like superellipsoid, a box, and a floor of 8 × 8 cells of two
/// triangles (a BVHModel, its regions from contactManifolds, FCL's collide with
/// MeshContacts::kRegions; no warm start). The whole manifold (contactManifold),
/// FCL's collide() with four contacts (the manifold's places), and the one-contact collide() of
/// the same pair as the baseline, measured in the same run. The warm start: the body moving
/// along a closed path of 64 steps (turning by about 1e-3 rad and moving 5e-3 of its size a
/// step), the reduced places only (outline_area_tolerance 1), fresh and warm-started from the
/// step before.
enum class ManifoldPartner { kHalfspace, kSuperellipsoid, kBox, kMesh };
enum class ManifoldCall { kOneContact, kFourContacts, kManifold, kStepFresh, kStepWarm };

void runManifold(benchmark::State& state, ManifoldPartner partner, ManifoldCall call) {
  const auto body = std::make_shared<Superellipsoid<double>>(0.5, 0.4, 0.3, 0.2, 0.2);
  std::shared_ptr<fcl::CollisionGeometry<double>> other;
  double half_height = 0;  // of the other, below the contact
  if (partner == ManifoldPartner::kHalfspace) {
    other = std::make_shared<fcl::Halfspace<double>>(Vector3<double>(0, 0, 1), 0.0);
  } else if (partner == ManifoldPartner::kSuperellipsoid) {
    other = std::make_shared<Superellipsoid<double>>(0.6, 0.5, 0.3, 0.2, 0.2);
    half_height = 0.3;
  } else if (partner == ManifoldPartner::kBox) {
    other = std::make_shared<fcl::Box<double>>(1.2, 1.0, 0.6);
    half_height = 0.3;
  } else {
    std::vector<Vector3<double>> vertices;
    std::vector<fcl::Triangle> triangles;
    for (int i = 0; i <= 8; ++i) {
      for (int j = 0; j <= 8; ++j) vertices.emplace_back(-2 + 0.5 * i, -2 + 0.5 * j, 0);
    }
    for (int i = 0; i < 8; ++i) {
      for (int j = 0; j < 8; ++j) {
        const int c = i * 9 + j;
        triangles.emplace_back(c, c + 9, c + 10);
        triangles.emplace_back(c, c + 10, c + 1);
      }
    }
    auto floor = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
    floor->beginModel();
    floor->addSubModel(vertices, triangles);
    floor->endModel();
    other = floor;
    body->setMeshContacts(MeshContacts::kRegions);
  }
  const bool path = call == ManifoldCall::kStepFresh || call == ManifoldCall::kStepWarm;
  std::mt19937 rng(52);
  std::uniform_real_distribution<double> tilt(-0.02, 0.02), shift(-0.1, 0.1);
  std::vector<fcl::Transform3d> poses;
  for (int k = 0; k < 64; ++k) {
    const double phase = 2 * M_PI * k / 64;
    fcl::Transform3d X = fcl::Transform3d::Identity();
    X.linear() =
        (Eigen::AngleAxisd(path ? 0.01 * std::sin(phase) : tilt(rng), Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(path ? 0.01 * std::cos(phase) : tilt(rng), Eigen::Vector3d::UnitY()))
            .toRotationMatrix();
    const double lowest =
        (X * body->supportPoint(-(X.linear().transpose() * Vector3<double>::UnitZ()))).z();
    X.translation() =
        path ? Eigen::Vector3d(0.05 * std::cos(phase), 0.05 * std::sin(phase), -lowest - 5e-4)
             : Eigen::Vector3d(shift(rng), shift(rng), -lowest - 5e-4);
    poses.push_back(X);
  }
  fcl::Transform3d X_other = fcl::Transform3d::Identity();
  X_other.translation().z() = -half_height;
  fcl::CollisionObjectd a(body), b(other, X_other);
  const fcl::CollisionRequestd request(call == ManifoldCall::kOneContact ? 1 : 4, true);
  ManifoldOptions<double> points_only;
  points_only.outline_area_tolerance = 1;
  ManifoldWarmStart<double> warm;
  std::size_t i = 0;
  for (auto _ : state) {
    if (partner == ManifoldPartner::kMesh && call == ManifoldCall::kManifold) {
      benchmark::DoNotOptimize(contactManifolds(*body, poses[i], *other, X_other));
    } else if (partner == ManifoldPartner::kMesh && call == ManifoldCall::kStepFresh) {
      benchmark::DoNotOptimize(contactManifolds(*body, poses[i], *other, X_other, points_only));
    } else if (call == ManifoldCall::kManifold) {
      benchmark::DoNotOptimize(contactManifold(*body, poses[i], *other, X_other));
    } else if (call == ManifoldCall::kStepFresh) {
      benchmark::DoNotOptimize(contactManifold(*body, poses[i], *other, X_other, points_only));
    } else if (call == ManifoldCall::kStepWarm) {
      benchmark::DoNotOptimize(
          contactManifold(*body, poses[i], *other, X_other, points_only, warm));
    } else {
      a.setTransform(poses[i]);
      fcl::CollisionResultd result;
      benchmark::DoNotOptimize(fcl_superellipsoid::collide(&a, &b, request, result));
    }
    i = (i + 1) & 63;
  }
  state.SetItemsProcessed(state.iterations());
}

/// A pair's signed distance alone (the front end, signed, with the witnesses) against the same
/// with its gradient (pairDistanceDerivatives), and with the Jacobians of its witnesses and
/// normal too (DerivativeOrder::kJacobians), over the 64 poses of test_support/benchmark_pairs.h
/// (on which the tests check these derivatives).
enum class PairCall { kDistance, kGradient, kJacobians };

void runPairGradient(benchmark::State& state, test::BenchmarkPartner partner, PairCall call) {
  const std::shared_ptr<Superellipsoid<double>> body = test::benchmarkBody();
  const std::shared_ptr<fcl::CollisionGeometry<double>> other = test::benchmarkPartner(partner);
  const fcl::Transform3d X_WO = fcl::Transform3d::Identity();
  const std::vector<fcl::Transform3d> poses = test::benchmarkPoses(*body, *other);
  fcl::CollisionObjectd a(body), b(other, X_WO);
  fcl::DistanceRequestd request(true, true);
  std::size_t i = 0;
  for (auto _ : state) {
    if (call == PairCall::kGradient) {
      benchmark::DoNotOptimize(pairDistanceDerivatives(*body, poses[i], *other, X_WO));
    } else if (call == PairCall::kJacobians) {
      benchmark::DoNotOptimize(
          pairDistanceDerivatives(*body, poses[i], *other, X_WO, DerivativeOrder::kJacobians));
    } else {
      a.setTransform(poses[i]);
      fcl::DistanceResultd result;
      benchmark::DoNotOptimize(fcl_superellipsoid::distance(&a, &b, request, result));
    }
    i = (i + 1) & 63;
  }
  state.SetItemsProcessed(state.iterations());
}

void registerAll() {
  const std::vector<
      std::pair<std::string, std::function<std::unique_ptr<Method>(const BenchShape&)>>>
      methods = {
          {"Exact/1e-12", [](const BenchShape& s) { return makeSolverMethod(s, kExact, 1e-12); }},
          {"Exact/1e-9", [](const BenchShape& s) { return makeSolverMethod(s, kExact, 1e-9); }},
          {"Paper/1e-3", [](const BenchShape& s) { return makeSolverMethod(s, kPaper, 1e-3); }},
          {"Radial", [](const BenchShape& s) { return makeSolverMethod(s, kRadial, 0); }},
          {"FrontEnd", [](const BenchShape& s) { return makeFrontEndMethod(s); }},
          {"FclMesh/272", [](const BenchShape& s) { return makeFclMeshMethod(s, 272); }},
          {"FclMesh/4k", [](const BenchShape& s) { return makeFclMeshMethod(s, 4000); }},
          {"FclConvex/272", [](const BenchShape& s) { return makeFclConvexMethod(s, 272); }},
          {"FclEllipsoid", [](const BenchShape& s) { return makeFclEllipsoidMethod(s); }},
          {"Bullet", [](const BenchShape& s) { return makeBulletMethod(s); }},
      };
  for (const auto& [name, make] : methods) {
    for (const char* shape_class : {"round", "sharp", "pinched", "cloth"}) {
      // FCL's Ellipsoid exists only for ε1 = ε2 = 1: the round class.
      if (name == "FclEllipsoid" && std::string(shape_class) != "round") continue;
      benchmark::RegisterBenchmark((name + "/" + shape_class).c_str(),
                                   [make = make, shape_class](benchmark::State& state) {
                                     runQueries(state, shape_class, make);
                                   });
    }
  }
  for (const char* shape_class : {"round", "sharp", "pinched", "cloth"}) {
    benchmark::RegisterBenchmark(
        (std::string("FirstInsideQuery/") + shape_class).c_str(),
        [shape_class](benchmark::State& state) { runFirstInsideQuery(state, shape_class); });
  }
  for (const char* shape_class : {"round", "sharp", "pinched", "cloth"}) {
    for (const auto& [name, what] :
         {std::pair{"Value", Derivatives::kValue}, std::pair{"Gradient", Derivatives::kGradient},
          std::pair{"Jacobians", Derivatives::kJacobians}}) {
      benchmark::RegisterBenchmark((std::string("Derivatives/") + name + "/" + shape_class).c_str(),
                                   [shape_class, what = what](benchmark::State& state) {
                                     runDerivatives(state, shape_class, what);
                                   });
    }
  }
  for (const auto& [name, partner] :
       {std::pair{"halfspace", ManifoldPartner::kHalfspace},
        std::pair{"superellipsoid", ManifoldPartner::kSuperellipsoid},
        std::pair{"box", ManifoldPartner::kBox}, std::pair{"mesh", ManifoldPartner::kMesh}}) {
    for (const auto& [prefix, call] : {std::pair{"OneContact/", ManifoldCall::kOneContact},
                                       std::pair{"FourContacts/", ManifoldCall::kFourContacts},
                                       std::pair{"Manifold/", ManifoldCall::kManifold},
                                       std::pair{"ManifoldStepFresh/", ManifoldCall::kStepFresh},
                                       std::pair{"ManifoldStepWarm/", ManifoldCall::kStepWarm}}) {
      if (partner == ManifoldPartner::kMesh && call == ManifoldCall::kStepWarm) continue;
      benchmark::RegisterBenchmark((std::string(prefix) + name).c_str(),
                                   [partner = partner, call = call](benchmark::State& state) {
                                     runManifold(state, partner, call);
                                   });
    }
  }
  for (const test::BenchmarkPartner partner : test::kBenchmarkPartners) {
    for (const auto& [label, call] : {std::pair{"PairDistance/", PairCall::kDistance},
                                      std::pair{"PairGradient/", PairCall::kGradient},
                                      std::pair{"PairJacobians/", PairCall::kJacobians}}) {
      benchmark::RegisterBenchmark((std::string(label) + test::partnerName(partner)).c_str(),
                                   [partner = partner, call = call](benchmark::State& state) {
                                     runPairGradient(state, partner, call);
                                   });
    }
  }
  for (const bool fresh : {true, false}) {
    benchmark::RegisterBenchmark(
        fresh ? "NearSurfaceNewShape" : "NearSurfaceWarmShape",
        [fresh](benchmark::State& state) { runNearSurface(state, fresh); });
  }
  for (const bool vectorize : {true, false}) {
    for (const char* shape_class : {"round", "sharp", "pinched", "cloth"}) {
      const std::string name = std::string(vectorize ? "BatchSimd" : "BatchScalar") + "/" +
                               simdInstructionSet() + "/" + shape_class;
      benchmark::RegisterBenchmark(name.c_str(), [vectorize, shape_class](benchmark::State& state) {
        runBatch(state, shape_class, vectorize);
      });
    }
    const std::string band = std::string(vectorize ? "BatchSimd" : "BatchScalar") + "/" +
                             simdInstructionSet() + "/cloth-band";
    benchmark::RegisterBenchmark(band.c_str(), [vectorize](benchmark::State& state) {
      runBatch(state, "cloth", vectorize, true);
    });
  }
  // The batched gradients beside BatchSimd: the same vertices with ∂d/∂Q, ∂d/∂ξ and ∂d/∂θ.
  for (const char* shape_class : {"round", "sharp", "pinched", "cloth", "cloth-band"}) {
    const bool band = std::string(shape_class) == "cloth-band";
    const std::string name =
        std::string("BatchGradient/") + simdInstructionSet() + "/" + shape_class;
    benchmark::RegisterBenchmark(name.c_str(), [band, shape_class](benchmark::State& state) {
      runBatch(state, band ? "cloth" : shape_class, true, band, true);
    });
  }
}

}  // namespace
}  // namespace bench
}  // namespace fcl_superellipsoid

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  fcl_superellipsoid::bench::registerAll();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
