// Fuzz target 4: a new shape from raw bytes (radii, exponents: any bit pattern) on every input,
// and a few query points on it, every method, float and double: the constructor refuses what is
// out of range naming the value, and a new shape's first queries (which build its caches: the
// rolling radius, the direction cover) meet the point-query contract (point_contract.h). The
// query targets draw their shapes from a fixed family instead (shape_family.h).
// docs/hardening.md → "Fuzzing".
#include <cmath>
#include <limits>
#include <optional>

#include "fcl_superellipsoid/point_distance.h"
#include "fuzz_input.h"
#include "point_contract.h"

namespace {

using fcl_superellipsoid::DistanceMethod;
using fcl_superellipsoid::DistanceOptions;
using fcl_superellipsoid::Superellipsoid;
using fuzz::Vector3;

template <typename S>
std::optional<Superellipsoid<S>> makeShape(FuzzedDataProvider& in) {
  const int spread = sizeof(S) == 4 ? 24 : 180;  // radii around 1, up to 2^±spread
  const S a1 = fuzz::aroundOne<S>(in, spread);
  const S a2 = in.ConsumeBool() ? a1 : fuzz::aroundOne<S>(in, spread);
  const S a3 = in.ConsumeBool() ? a1 : fuzz::aroundOne<S>(in, spread);
  const S e1 = fuzz::anyExponent<S>(in);
  const S e2 = in.ConsumeBool() ? e1 : fuzz::anyExponent<S>(in);
  try {
    return Superellipsoid<S>(a1, a2, a3, e1, e2);
  } catch (const std::invalid_argument& e) {
    fuzz::requireNamedValue(e);
    return std::nullopt;
  }
}

template <typename S>
void run(FuzzedDataProvider& in) {
  const std::optional<Superellipsoid<S>> shape = makeShape<S>(in);
  if (!shape) return;
  // One to three query points relative to the shape's size (near the surface, deep inside, far
  // away), with the default options of every method: the queries that build the caches.
  const int queries = in.ConsumeIntegralInRange<int>(1, 3);
  for (int k = 0; k < queries; ++k) {
    Vector3<S> p;
    for (int c = 0; c < 3; ++c) {
      p[c] = shape->size() * fuzz::anyScalar<S>(in, -30, 8);
      // Valid queries only (finite, up to a quarter of the largest finite value): the query
      // targets check the refusals.
      if (!(std::abs(p[c]) <= std::numeric_limits<S>::max() / 4) ||
          in.ConsumeIntegralInRange<int>(0, 3) == 0) {
        p[c] = S(0);
      }
    }
    for (DistanceMethod method :
         {DistanceMethod::kRadial, DistanceMethod::kPaper, DistanceMethod::kExact}) {
      const DistanceOptions<S> options = DistanceOptions<S>::of(method);
      const auto r = fcl_superellipsoid::pointDistance(*shape, p, options);
      fuzz::checkPointContract(*shape, p, options, r);
    }
  }
}

}  // namespace

FSE_FUZZ_FLOAT_AND_DOUBLE(run)
