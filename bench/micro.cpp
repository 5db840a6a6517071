// Google Benchmark micro-benchmarks: one query per iteration, cycling through 1,024 points
// near the surface, for each method and shape class. The full comparison is fse_bench; this
// target is for profiling one method and for tracking regressions with Google Benchmark's
// tooling (--benchmark_filter, --benchmark_format=json, compare.py).

#include <benchmark/benchmark.h>

#include <functional>
#include <map>

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
