// The library's own point solvers as benchmark methods, and the factory of all methods.

#include "methods.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "fcl_superellipsoid/point_distance.h"

namespace fcl_superellipsoid {
namespace bench {
namespace {

class SolverMethod final : public Method {
 public:
  SolverMethod(const BenchShape& shape, const char* family, DistanceOptions<double> options,
               std::string setting, double setting_value)
      // The representation: 3 radii and 2 exponents.
      : Method(family, std::move(setting), setting_value, true, 5 * sizeof(double)),
        shape_(shape.make()),
        options_(options) {}

  Answer query(const Vector3<double>& x) const override {
    const PointDistanceResult<double> r = pointDistance(shape_, x, options_);
    return {r.distance, r.nearest_point, r.converged ? 1 : 0, r.error};
  }

 private:
  Superellipsoid<double> shape_;
  DistanceOptions<double> options_;
};

}  // namespace

std::string toleranceText(double tolerance) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0e", tolerance);
  return text;
}

std::unique_ptr<Method> makeSolverMethod(const BenchShape& shape, const char* family,
                                         double tolerance) {
  const std::string name(family);
  if (name == kRadial) {
    return std::make_unique<SolverMethod>(
        shape, kRadial, DistanceOptions<double>::of(DistanceMethod::kRadial), "", NAN);
  }
  DistanceOptions<double> options =
      DistanceOptions<double>::of(name == kPaper ? DistanceMethod::kPaper : DistanceMethod::kExact);
  options.tolerance = tolerance;
  return std::make_unique<SolverMethod>(shape, family, options, toleranceText(tolerance),
                                        tolerance);
}

std::vector<std::unique_ptr<Method>> makeMethods(const BenchShape& shape,
                                                 const MethodSelection& selection) {
  using Clock = std::chrono::steady_clock;
  std::vector<std::unique_ptr<Method>> methods;
  auto add = [&methods](auto&& build) {
    const Clock::time_point start = Clock::now();
    std::unique_ptr<Method> method = build();
    method->setSetupSeconds(std::chrono::duration<double>(Clock::now() - start).count());
    methods.push_back(std::move(method));
  };
  for (double t : selection.exact_tolerances)
    add([&] { return makeSolverMethod(shape, kExact, t); });
  for (double t : selection.paper_tolerances)
    add([&] { return makeSolverMethod(shape, kPaper, t); });
  if (selection.radial) add([&] { return makeSolverMethod(shape, kRadial, 0); });
  if (selection.front_end) add([&] { return makeFrontEndMethod(shape); });
  for (int n : selection.mesh_vertices) add([&] { return makeFclMeshMethod(shape, n); });
  for (int n : selection.convex_vertices) add([&] { return makeFclConvexMethod(shape, n); });
  if (selection.fcl_ellipsoid && shape.eps1 == 1 && shape.eps2 == 1) {
    add([&] { return makeFclEllipsoidMethod(shape); });
  }
  if (selection.bullet) add([&] { return makeBulletMethod(shape); });
  return methods;
}

}  // namespace bench
}  // namespace fcl_superellipsoid
