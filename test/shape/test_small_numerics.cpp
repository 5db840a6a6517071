// The small numeric helpers the solvers' inner loops use instead of slower library calls:
// hypot2 (shape/symmetric2.h) against std::hypot, and negatedWhere (shape/octant.h) against
// the unary minus, bit for bit. Ground truth: the standard library, and long double.

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "shape/octant.h"
#include "shape/symmetric2.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

template <typename S>
class SmallNumericsTest : public ::testing::Test {};
TYPED_TEST_SUITE(SmallNumericsTest, test::Scalars);

template <typename S>
bool sameBits(S a, S b) {
  return std::memcmp(&a, &b, sizeof(S)) == 0;
}

// Within an ulp of the long-double √(a² + b²) across the whole range (squares of values beyond
// 2^±(max_exponent/2) over- or underflow: those go to std::hypot), and exactly std::hypot's
// answer for zeros, infinities and NaN.
TYPED_TEST(SmallNumericsTest, Hypot2IsWithinAnUlpOfTheExactValue) {
  using S = TypeParam;
  using Limits = std::numeric_limits<S>;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> mantissa(-2, 2);
  std::uniform_int_distribution<int> exponent(Limits::min_exponent - Limits::digits,
                                              Limits::max_exponent - 2);
  std::uniform_int_distribution<int> offset(-80, 80);
  for (int i = 0; i < 200000; ++i) {
    const int e = exponent(rng);
    const S a = S(std::ldexp(mantissa(rng), e));
    // b: near a's magnitude most of the time, anywhere the rest.
    const int eb = i % 4 == 0 ? exponent(rng) : e + offset(rng) % (i % 3 == 0 ? 80 : 4);
    const S b = S(std::ldexp(mantissa(rng), eb));
    if (!std::isfinite(a) || !std::isfinite(b)) continue;
    const long double exact = std::sqrt((long double)a * a + (long double)b * b);
    const S got = detail::hypot2(a, b);
    if (std::isinf(got)) {  // only where the value is beyond the type, as std::hypot's
      EXPECT_GT(exact, (long double)Limits::max() * (1 - (long double)Limits::epsilon()))
          << a << " " << b;
      continue;
    }
    const long double ulp =
        std::max((long double)Limits::denorm_min(),
                 (long double)Limits::epsilon() * std::max(std::abs((long double)got), exact));
    EXPECT_LE(std::abs((long double)got - exact), ulp) << "a = " << a << ", b = " << b;
  }
  const S inf = Limits::infinity(), nan = Limits::quiet_NaN();
  for (const auto& [a, b] :
       std::initializer_list<std::pair<S, S>>{{S(0), S(0)},
                                              {-S(0), S(0)},
                                              {inf, S(1)},
                                              {S(1), -inf},
                                              {inf, nan},
                                              {nan, S(2)},
                                              {Limits::max(), Limits::max()},
                                              {Limits::denorm_min(), Limits::denorm_min()},
                                              {Limits::min(), S(0)}}) {
    const S expected = std::hypot(a, b), got = detail::hypot2(a, b);
    EXPECT_TRUE(sameBits(got, expected) || (std::isnan(got) && std::isnan(expected)))
        << "a = " << a << ", b = " << b << ": " << got << " instead of " << expected;
  }
}

// The reflection's sign flip is the unary minus, bit for bit, on every kind of value, and a
// query coordinate of −0 counts as positive (no flip), as point_distance.h promises.
TYPED_TEST(SmallNumericsTest, NegatedWhereIsTheUnaryMinus) {
  using S = TypeParam;
  using Limits = std::numeric_limits<S>;
  for (const S x : {S(0), -S(0), S(1.5), S(-2.25), Limits::min(), Limits::denorm_min(),
                    Limits::max(), Limits::infinity(), -Limits::infinity()}) {
    EXPECT_TRUE(sameBits(detail::negatedWhere(true, x), S(-x))) << x;
    EXPECT_TRUE(sameBits(detail::negatedWhere(false, x), x)) << x;
  }
  const S nan = Limits::quiet_NaN();
  EXPECT_TRUE(std::signbit(detail::negatedWhere(true, nan)) != std::signbit(nan));
  const Vector3<S> v(S(1), S(2), S(3));
  const Vector3<S> q(-S(0), S(-1), S(0.5));
  const Vector3<S> r = detail::intoOctantOf(q, v);
  EXPECT_TRUE(sameBits(r[0], S(1)));  // −0 is not negative
  EXPECT_TRUE(sameBits(r[1], S(-2)));
  EXPECT_TRUE(sameBits(r[2], S(3)));
}

}  // namespace
}  // namespace fcl_superellipsoid
