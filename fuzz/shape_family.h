// The shapes the query targets draw from: a fixed family, each built once per process (with
// the caches its first queries build), chosen by the input's bytes. A query target's inputs
// then spend their time on the queries, not on a new shape's caches; fuzz_new_shape covers
// arbitrary new shapes. docs/hardening.md → "Fuzzing".
#ifndef FCL_SUPERELLIPSOID_FUZZ_SHAPE_FAMILY_H
#define FCL_SUPERELLIPSOID_FUZZ_SHAPE_FAMILY_H

#include <array>
#include <cmath>
#include <memory>

#include "fcl_superellipsoid/superellipsoid.h"
#include "fuzz_input.h"

namespace fuzz {

using fcl_superellipsoid::NumericRange;
using fcl_superellipsoid::Superellipsoid;

/// The exponent grid: both ends of the supported range, the sharp, the round and the pinched.
constexpr double kFamilyExponents[] = {0.02, 0.1, 0.3, 0.65, 1.0, 1.35, 1.7, 1.98};
constexpr int kFamilyExponentCount = 8;
/// Radii profiles: a sphere-like shape, a 4:2:1 box-like one, a needle and a disc at the aspect
/// limit (NumericRange<S>::kMaxAspectRatio, less a thousandth for rounding).
constexpr int kFamilyProfiles = 4;
/// Scales: the radius range's low end, 1, its high end (the profile's largest radius).
constexpr int kFamilyScales = 3;
constexpr int kFamilySize =
    kFamilyExponentCount * kFamilyExponentCount * kFamilyProfiles * kFamilyScales;

template <typename S>
Vector3<S> familyRadii(int profile, int scale) {
  using Range = NumericRange<S>;
  const S aspect = Range::kMaxAspectRatio * S(0.999);
  const Vector3<S> radii = profile == 0   ? Vector3<S>(S(1), S(0.9), S(0.8))
                           : profile == 1 ? Vector3<S>(S(1), S(0.5), S(0.25))
                           : profile == 2 ? Vector3<S>(S(1) / aspect, S(1) / aspect, S(1))
                                          : Vector3<S>(S(1), S(1), S(1) / aspect);
  // The smallest radius stays in range at the low end (a thousandth above it, for rounding),
  // the largest (1 in every profile) at the high end.
  const S factor = scale == 0   ? Range::kMinRadius / radii.minCoeff() * S(1.001)
                   : scale == 1 ? S(1)
                                : Range::kMaxRadius;
  return radii * factor;
}

/// A shape of the family, chosen by the input's next bytes; built on its first use, then kept.
template <typename S>
const std::shared_ptr<Superellipsoid<S>>& familyShape(FuzzedDataProvider& in) {
  static std::array<std::shared_ptr<Superellipsoid<S>>, kFamilySize> family;
  const int e1 = in.ConsumeIntegralInRange<int>(0, kFamilyExponentCount - 1);
  const int e2 = in.ConsumeIntegralInRange<int>(0, kFamilyExponentCount - 1);
  // Mostly at scale 1 (1 in 8 at an end of the radius range), mostly the first two profiles.
  const int profile = in.ConsumeIntegralInRange<int>(0, 7) == 0
                          ? in.ConsumeIntegralInRange<int>(2, kFamilyProfiles - 1)
                          : in.ConsumeIntegralInRange<int>(0, 1);
  const int scale =
      in.ConsumeIntegralInRange<int>(0, 7) == 0 ? 2 * in.ConsumeIntegralInRange<int>(0, 1) : 1;
  const int index =
      ((e1 * kFamilyExponentCount + e2) * kFamilyProfiles + profile) * kFamilyScales + scale;
  std::shared_ptr<Superellipsoid<S>>& shape = family[std::size_t(index)];
  if (!shape) {
    shape = std::make_shared<Superellipsoid<S>>(familyRadii<S>(profile, scale),
                                                S(kFamilyExponents[e1]), S(kFamilyExponents[e2]));
  }
  return shape;
}

}  // namespace fuzz

#endif  // FCL_SUPERELLIPSOID_FUZZ_SHAPE_FAMILY_H
