// What the fuzz targets share: turning libFuzzer's bytes into numbers that reach every corner
// (any bit pattern, the special values, every magnitude), and reporting a broken contract.
#ifndef FCL_SUPERELLIPSOID_FUZZ_FUZZ_INPUT_H
#define FCL_SUPERELLIPSOID_FUZZ_FUZZ_INPUT_H

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "fcl_superellipsoid/superellipsoid.h"

/// The fuzz target's entry point: the input's first byte chooses run<double> or run<float>.
#define FSE_FUZZ_FLOAT_AND_DOUBLE(run)                                      \
  extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { \
    FuzzedDataProvider in(data, size);                                      \
    if (in.ConsumeBool()) {                                                 \
      run<double>(in);                                                      \
    } else {                                                                \
      run<float>(in);                                                       \
    }                                                                       \
    return 0;                                                               \
  }

namespace fuzz {

using fcl_superellipsoid::Vector3;

/// A scalar of type S: a raw bit pattern (1 in 8), a special value (1 in 8: ±0, ±inf, NaN,
/// the smallest subnormal, the largest finite, epsilon), or sign × [1, 2) × 2^e with e anywhere
/// in [min_exp, max_exp] (the rest), so that every magnitude is about as likely.
template <typename S>
S anyScalar(FuzzedDataProvider& in, int min_exp, int max_exp) {
  using L = std::numeric_limits<S>;
  const int mode = in.ConsumeIntegralInRange<int>(0, 7);
  if (mode == 0) {
    S value;
    const auto bytes = in.ConsumeBytes<unsigned char>(sizeof(S));
    unsigned char raw[sizeof(S)] = {};
    if (!bytes.empty()) std::memcpy(raw, bytes.data(), bytes.size());
    std::memcpy(&value, raw, sizeof(S));
    return value;
  }
  if (mode == 1) {
    const S specials[] = {S(0),           -S(0),           L::infinity(), -L::infinity(),
                          L::quiet_NaN(), L::denorm_min(), L::max(),      L::lowest(),
                          L::epsilon(),   L::min()};
    return specials[in.ConsumeIntegralInRange<int>(0, 9)];
  }
  const S mantissa = S(1) + in.ConsumeProbability<S>();
  const int exponent = in.ConsumeIntegralInRange<int>(min_exp, max_exp);
  return (in.ConsumeBool() ? S(-1) : S(1)) * std::ldexp(mantissa, exponent);
}

/// A positive scalar around 1 (|log2| ≤ spread), sometimes any scalar at all.
template <typename S>
S aroundOne(FuzzedDataProvider& in, int spread) {
  if (in.ConsumeIntegralInRange<int>(0, 15) == 0) {
    return anyScalar<S>(in, std::numeric_limits<S>::min_exponent,
                        std::numeric_limits<S>::max_exponent);
  }
  return std::ldexp(S(1) + in.ConsumeProbability<S>(),
                    in.ConsumeIntegralInRange<int>(-spread, spread));
}

/// An exponent: mostly in (0, 2) (the whole interval, its ends included as the closest values),
/// sometimes any scalar.
template <typename S>
S anyExponent(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 9)) {
    case 0:
      return anyScalar<S>(in, -40, 4);
    case 1:
      return std::nextafter(S(0), S(1)) * S(1 + in.ConsumeIntegralInRange<int>(0, 3));
    case 2:
      return std::nextafter(S(2), S(0));
    default:
      return S(2) * in.ConsumeProbability<S>();
  }
}

/// A pose: any rotation (a quaternion from the bytes; identity if it is nearly zero), a
/// translation within ±reach on each axis.
template <typename S>
fcl::Transform3<S> makePose(FuzzedDataProvider& in, S reach) {
  fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  const auto unit = [&in] { return S(1) - S(2) * in.ConsumeProbability<S>(); };
  const S w = unit(), x = unit(), y = unit(), z = unit();
  const Eigen::Quaternion<S> q(w, x, y, z);
  if (q.norm() > S(1e-3)) X.linear() = q.normalized().toRotationMatrix();
  for (int c = 0; c < 3; ++c) X.translation()[c] = reach * unit();
  return X;
}

/// Reports a broken contract with the values involved and aborts: libFuzzer keeps the input.
[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "contract failure: %s\n", what.c_str());
  std::abort();
}

/// Checks a contract. `what` names what broke: a string, or a callable that returns one, so that
/// a check that holds formats nothing (formatting the values for every check was most of an
/// input's time under the sanitizers).
template <typename What>
void require(bool ok, const What& what) {
  if (ok) return;
  if constexpr (std::is_invocable_v<const What&>) {
    fail(what());
  } else {
    fail(what);
  }
}

/// An std::invalid_argument from the library must name the value it refused ("..., got <v>").
inline void requireNamedValue(const std::invalid_argument& e) {
  require(std::string(e.what()).find(", got ") != std::string::npos,
          std::string("error without the value: ") + e.what());
}

}  // namespace fuzz

#endif  // FCL_SUPERELLIPSOID_FUZZ_FUZZ_INPUT_H
