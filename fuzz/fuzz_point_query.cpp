// Fuzz target 1: a shape of the fixed family (shape_family.h, built once per process) and a
// query point, every method, float and double. Invalid input may only throw
// std::invalid_argument naming the value; valid input must give an answer that meets the
// point-query contract (point_contract.h). New shapes from raw bytes: fuzz_new_shape.
// docs/hardening.md → "Fuzzing".
#include <memory>

#include "fcl_superellipsoid/point_distance.h"
#include "fuzz_input.h"
#include "point_contract.h"
#include "shape_family.h"

namespace {

using fcl_superellipsoid::DistanceMethod;
using fcl_superellipsoid::DistanceOptions;
using fcl_superellipsoid::Superellipsoid;
using fuzz::Vector3;

template <typename S>
void run(FuzzedDataProvider& in) {
  const std::shared_ptr<Superellipsoid<S>>& shape = fuzz::familyShape<S>(in);
  // The query: relative to the shape's size (near the surface, deep inside, far away), or any
  // scalar at all.
  Vector3<S> p;
  const bool relative = in.ConsumeBool();
  for (int c = 0; c < 3; ++c) {
    p[c] = relative ? shape->size() * fuzz::anyScalar<S>(in, -30, 30)
                    : fuzz::anyScalar<S>(in, std::numeric_limits<S>::min_exponent,
                                         std::numeric_limits<S>::max_exponent);
    if (in.ConsumeIntegralInRange<int>(0, 3) == 0) p[c] = S(0);
  }
  for (DistanceMethod method :
       {DistanceMethod::kRadial, DistanceMethod::kPaper, DistanceMethod::kExact}) {
    DistanceOptions<S> options = DistanceOptions<S>::of(method);
    if (in.ConsumeIntegralInRange<int>(0, 7) == 0)
      options.tolerance = fuzz::anyScalar<S>(in, -60, 2);
    if (in.ConsumeIntegralInRange<int>(0, 7) == 0)
      options.max_iterations = in.ConsumeIntegralInRange<int>(-2, 1000);
    // Valid: finite coordinates up to a quarter of the largest finite value (docs/hardening.md →
    // "Numeric range"), a finite positive tolerance, at least one iteration.
    const bool valid =
        p.allFinite() && (p.array().abs() <= std::numeric_limits<S>::max() / 4).all() &&
        std::isfinite(options.tolerance) && options.tolerance > S(0) && options.max_iterations >= 1;
    try {
      const auto r = fcl_superellipsoid::pointDistance(*shape, p, options);
      fuzz::require(valid, [&] {
        return "accepted invalid input: " + fuzz::describe(*shape, p, options, r);
      });
      fuzz::checkPointContract(*shape, p, options, r);
    } catch (const std::invalid_argument& e) {
      fuzz::require(!valid, std::string("refused valid input: ") + e.what());
      fuzz::requireNamedValue(e);
    }
  }
}

}  // namespace

FSE_FUZZ_FLOAT_AND_DOUBLE(run)
