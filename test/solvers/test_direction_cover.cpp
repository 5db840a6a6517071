// The direction cover's certificate of inside answers (src/solvers/direction_cover.h and
// directionCoverCertified in src/solvers/ball_certificate.h, docs/math.md → "The direction
// cover"): its cap against the support function evaluated directly in long double over a dense
// lattice of directions, the whole certificate against the long-double reference on stationary
// points built by construction (many of them deep and not the global nearest point), and the
// solver's answers on uniform inside points, where the cover does most of its work.

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <type_traits>

#include "ball_checks.h"
#include "enumerated_depth.h"
#include "fcl_superellipsoid/point_distance.h"
#include "reference_distance.h"
#include "shape/nested_norm.h"
#include "solvers/ball_certificate.h"
#include "solvers/direction_cover.h"
#include "solvers/exact_rules.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

const std::array<double, 5> kShapes[] = {
    {1, 1, 1, 0.3, 0.3},    {1, 1, 1, 0.65, 0.65}, {1, 1, 1, 1.35, 1.35}, {1, 1, 1, 1.9, 1.9},
    {1, 1, 1, 1, 1.6},      {1, 1, 1, 0.1, 1.9},   {3, 2, 1, 1, 1},       {3.5, 3, 2, 0.4, 0.3},
    {1, 2, 0.5, 0.65, 1.2}, {4, 1, 1, 1.5, 0.8}};

/// The first-octant directions of a Fibonacci lattice of n over the sphere.
std::vector<test::V3> firstOctantDirections(int n) {
  std::vector<test::V3> out;
  for (const test::V3& d : test::fibonacciLattice(n)) {
    if (d.minCoeff() >= 0) out.push_back(d);
  }
  return out;
}

/// h in long double (test_support's superellipsoidSupport) at each of `directions`, for the
/// shape of a kShapes row.
std::vector<long double> supportAt(const std::array<double, 5>& p,
                                   const std::vector<test::V3>& directions) {
  const test::V3 radii(p[0], p[1], p[2]);
  std::vector<long double> out(directions.size());
  for (std::size_t i = 0; i < directions.size(); ++i) {
    out[i] = test::superellipsoidSupport(radii, p[3], p[4], directions[i]);
  }
  return out;
}

/// A uniform draw in the shape's box; if inside, its first-octant image y with the solver's
/// depth and nearest normal (the cap claims hold for any n_star; this one is the solver's).
struct InsideDraw {
  bool inside;
  Vector3<double> y, n_star;
  double depth;
};
InsideDraw drawInside(const Superellipsoid<double>& shape, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  const Vector3<double> x = shape.radii().cwiseProduct(Vector3<double>(u(rng), u(rng), u(rng)));
  if (!shape.contains(x)) return {false, {}, {}, 0};
  const Vector3<double> y = x.cwiseAbs();
  const PointDistanceResult<double> r = pointDistance(shape, y);
  return {true, y, r.normal.cwiseAbs(), -r.distance};
}

/// The largest chord ‖n − n_star‖ over the lattice directions with F(n) = h(n) − n·y < need
/// (0 if none), and how many there are.
struct LowDirections {
  double farthest = 0;
  int count = 0;
};
LowDirections lowDirections(const std::vector<test::V3>& directions,
                            const std::vector<long double>& h_of, const Vector3<double>& y,
                            const Vector3<double>& n_star, double need) {
  LowDirections out;
  for (std::size_t i = 0; i < directions.size(); ++i) {
    const test::V3& n = directions[i];
    if (h_of[i] - n.dot(y.cast<long double>()) >= need) continue;
    ++out.count;
    out.farthest = std::max(out.farthest, double((n - n_star.cast<long double>()).norm()));
  }
  return out;
}

/// The solver's direction-cover certificate, with its cap limit and a query's budget of split
/// cells' support points.
bool certifies(const Superellipsoid<double>& shape, const detail::NestedNorm<double>& gauge,
               const Vector3<double>& y, const Vector3<double>& n_point,
               const Vector3<double>& normal, const Vector3<double>& gradient, double d) {
  int split_budget = detail::DirectionCover<double>::kSplitSupportPoints;
  return detail::directionCoverCertified(detail::directionCover(shape), gauge, y, n_point, normal,
                                         gradient, d, detail::exact_rules::kCoverCapLimit,
                                         &split_budget);
}

/// A stationary point Q = N − d·n (N on the surface, n its normal) judged twice: whether N is
/// the reference's nearest point (its depth at Q is d), and whether the certificate says so.
struct Verdict {
  bool global, certified;
  double reference_depth;
};
Verdict judge(const Superellipsoid<double>& shape, const test::ReferenceDistance& reference,
              const detail::NestedNorm<double>& gauge, const Vector3<double>& y,
              const Vector3<double>& n_point, const Vector3<double>& normal, double d) {
  const auto truth = reference.query({y[0], y[1], y[2]});
  const Vector3<double> gradient = gauge.evaluate(n_point, false).gradient;
  return {double(-truth.distance) >= d - 1e-9 * shape.size(),
          certifies(shape, gauge, y, n_point, normal, gradient, d), double(-truth.distance)};
}

// The claim of cap: every first-octant direction n where F(n) = h(n) − n·y is below `need` lies
// within the returned chord of n_star. Checked with h evaluated directly in long double
// (test_support's superellipsoidSupport, itself checked against surface points here) over 8,000
// lattice directions, for points at every depth, n_star the solver's nearest normal (the claim
// holds for any) and `need` from the depth itself up to 0.3 × size beyond it (wider caps).
TEST(DirectionCover, CapHoldsEveryLowDirection) {
  std::mt19937 rng(5);
  const std::vector<test::V3> directions = firstOctantDirections(64000);
  int queries = 0, low_directions = 0, finite_caps = 0;
  for (const auto& p : kShapes) {
    const Superellipsoid<double> shape{p[0], p[1], p[2], p[3], p[4]};
    SCOPED_TRACE(test::describe(shape));
    const std::vector<long double> h_of = supportAt(p, directions);
    // The test's own support function: at least n·x for surface points, equal at the support
    // point of n.
    test::AngleSampler angles(3);
    for (int k = 0; k < 50; ++k) {
      const auto [eta, omega] = angles();
      const Vector3<double> x = shape.surfacePoint(eta, omega);
      const test::V3 n = shape.normal(x).cast<long double>();
      ASSERT_NEAR(double(test::superellipsoidSupport({p[0], p[1], p[2]}, p[3], p[4], n)),
                  double(n.dot(x.cast<long double>())), 1e-12 * shape.size());
    }
    const detail::DirectionCover<double>& cover = detail::directionCover(shape);
    for (int k = 0; k < 12; ++k) {
      const InsideDraw draw = drawInside(shape, rng);
      if (!draw.inside) continue;
      for (double extra : {0.0, 1e-3, 0.03, 0.3}) {
        const double need = draw.depth + extra * shape.size();
        const double theta = cover.cap(draw.y, draw.n_star, need, 2.0).radius;
        ++queries;
        if (!std::isfinite(theta)) continue;
        ++finite_caps;
        const LowDirections low = lowDirections(directions, h_of, draw.y, draw.n_star, need);
        low_directions += low.count;
        ASSERT_LE(low.farthest, theta) << "y = " << draw.y.transpose() << ", need = " << need;
      }
    }
  }
  EXPECT_GT(finite_caps, queries / 2);
  EXPECT_GT(low_directions, 1000) << "the sample should hold directions inside the caps";
}

// The support points stored for the first split grid (rounded through float, relative to the
// size): each is a point of the shape by the long-double reference gauge, the bounds' premise,
// and within 1e-5 × size (1e-4 in float) of the support of its cell's centre direction (computed
// here from the grid: the direction through the cell's centre on its cube face), in float and
// double, at the ends of the radius range and at the aspect-ratio limit.
template <typename S>
void checkSplitSupport(const Superellipsoid<S>& shape, int* checked) {
  SCOPED_TRACE(test::describe(shape));
  const auto& radii = shape.radii();
  const std::array<long double, 3> a{radii[0], radii[1], radii[2]};
  const test::ReferenceDistance reference(a, shape.eps1(), shape.eps2());
  const detail::DirectionCover<S>& cover = detail::directionCover(shape);
  constexpr int kSide = 2 * detail::DirectionCover<S>::kFinestSide;
  // In float every support point of the cover is pulled inward by 64 ulps (7.6e-6).
  const long double closeness = std::is_same<S, float>::value ? 1e-4L : 1e-5L;
  for (int face = 0; face < 3; ++face) {
    for (int i = 0; i < kSide; i += 3) {
      for (int j = 0; j < kSide; j += 5) {
        test::V3 n;
        n[face] = 1;
        n[(face + 1) % 3] = (i + 0.5L) / kSide;
        n[(face + 2) % 3] = (j + 0.5L) / kSide;
        n.normalize();
        const Vector3<S> s = cover.splitSupport(face, i, j);
        const test::V3 x = s.template cast<long double>();
        ASSERT_LE(reference.gauge({x[0], x[1], x[2]}), 1.0L) << face << " " << i << " " << j;
        const long double h =
            test::superellipsoidSupport(test::V3(a[0], a[1], a[2]), shape.eps1(), shape.eps2(), n);
        ASSERT_GE(n.dot(x), h - closeness * shape.size()) << face << " " << i << " " << j;
        ++*checked;
      }
    }
  }
}

TEST(DirectionCover, StoredSplitSupportPointsAreOnTheShape) {
  int checked = 0;
  for (const auto& p : kShapes) {
    checkSplitSupport(Superellipsoid<double>{p[0], p[1], p[2], p[3], p[4]}, &checked);
    checkSplitSupport(
        Superellipsoid<float>{float(p[0]), float(p[1]), float(p[2]), float(p[3]), float(p[4])},
        &checked);
  }
  using Range = NumericRange<double>;
  for (double scale : {Range::kMinRadius, Range::kMaxRadius / 4}) {
    checkSplitSupport(Superellipsoid<double>{4 * scale, 2 * scale, scale, 0.1, 1.9}, &checked);
  }
  checkSplitSupport(Superellipsoid<double>{Range::kMaxAspectRatio, 1, 1, 1.35, 0.3}, &checked);
  EXPECT_GT(checked, 5000);
}

// The claim of capWithin: where it says a target radius holds (a half, a quarter and an eighth
// of the cap's, the certificate's tries), every first-octant direction n where F(n) < need lies
// within the target of n_star. Checked as cap's claim above, with h in long double over 8,000
// lattice directions; and where the lattice itself holds a low direction beyond the target,
// capWithin must have said no.
TEST(DirectionCover, RefinedCapHoldsEveryLowDirection) {
  std::mt19937 rng(23);
  const std::vector<test::V3> directions = firstOctantDirections(64000);
  int tries = 0, held = 0, refused_by_lattice = 0;
  for (const auto& p : kShapes) {
    const Superellipsoid<double> shape{p[0], p[1], p[2], p[3], p[4]};
    SCOPED_TRACE(test::describe(shape));
    const std::vector<long double> h_of = supportAt(p, directions);
    const detail::DirectionCover<double>& cover = detail::directionCover(shape);
    for (int k = 0; k < 16; ++k) {
      const InsideDraw draw = drawInside(shape, rng);
      if (!draw.inside) continue;
      for (double extra : {0.0, 1e-3, 0.03}) {
        const double need = draw.depth + extra * shape.size();
        const detail::DirectionCover<double>::Cap cap = cover.cap(draw.y, draw.n_star, need, 2.0);
        if (!std::isfinite(cap.radius)) continue;
        const double farthest = lowDirections(directions, h_of, draw.y, draw.n_star, need).farthest;
        for (double fraction : {0.5, 0.25, 0.125}) {
          const double target = fraction * cap.radius;
          int budget = 1 << 20;  // no budget: the claim itself
          const bool within = cover.capWithin(cap, draw.y, draw.n_star, need, target, &budget);
          ++tries;
          if (within) {
            ++held;
            ASSERT_LE(farthest, target) << "y = " << draw.y.transpose() << ", need = " << need;
          } else if (farthest > target) {
            ++refused_by_lattice;
          }
        }
      }
    }
  }
  std::printf("[ capWithin ] %d tries: %d held, %d refused with a low lattice direction beyond\n",
              tries, held, refused_by_lattice);
  EXPECT_GT(held, tries / 4) << "the refinement should hold often enough to be tested";
  EXPECT_GT(refused_by_lattice, 0) << "some targets should be too small for the lattice itself";
}

// The whole certificate on stationary points by construction: Q = N − d·n for a surface point
// N of the first octant and its normal n, d from shallow to beyond the smallest radius (N then
// mostly a local minimum or a saddle, not the global answer). Where the cap is found and the
// Hessian bound over its slab holds, the sampled sphere of B(Q, d) stays inside the reference
// gauge and the reference's distance is d; none of the stationary points that are not global
// may be certified.
TEST(DirectionCover, CertifiesOnlyGlobalNearestPoints) {
  std::mt19937 rng(17);
  test::AngleSampler angles(19);
  int total = 0, certified = 0, not_global = 0, beyond_ball = 0;
  for (const auto& p : kShapes) {
    const Superellipsoid<double> shape{p[0], p[1], p[2], p[3], p[4]};
    SCOPED_TRACE(test::describe(shape));
    const test::ReferenceDistance reference({p[0], p[1], p[2]}, p[3], p[4]);
    const auto gauge = detail::NestedNorm<double>::gauge(shape);
    for (int k = 0; k < 60; ++k) {
      // d from 1e-2 to 1.6 × the smallest radius.
      const std::optional<test::StationaryPoint> point =
          test::stationaryPoint(shape, angles, rng, -2, 2.2);
      if (!point || !shape.contains(point->y)) continue;
      const auto& [y, n_point, normal, d] = *point;
      ++total;
      const Verdict verdict = judge(shape, reference, gauge, y, n_point, normal, d);
      if (!verdict.global) ++not_global;
      if (!verdict.certified) continue;
      ++certified;
      const Vector3<double> gradient = gauge.evaluate(n_point, false).gradient;
      if (!detail::hessianBallCertified(gauge, y, n_point, gradient, d, 0.0)) ++beyond_ball;
      const long double worst = test::worstGaugeOnSphere(reference, y, d, 300, rng);
      EXPECT_LE(double(worst), 1 + 1e-12) << "Q = " << y.transpose() << ", d = " << d;
      EXPECT_TRUE(verdict.global) << "certified a point that is not the nearest: Q = "
                                  << y.transpose() << ", N = " << n_point.transpose()
                                  << ", reference " << verdict.reference_depth << " < d = " << d;
    }
  }
  std::printf("stationary points %d, not global %d, certified %d (%d not by the Hessian ball)\n",
              total, not_global, certified, beyond_ball);
  EXPECT_GT(not_global, 20) << "the sample should hold stationary points that are not global";
  EXPECT_GT(certified, total / 3) << "the certificate should hold on many points";
  EXPECT_GT(beyond_ball, 30) << "... among them points the Hessian ball does not certify";
}

// Competing faces: on box-like shapes, Q below a point N near the middle of the largest face,
// at depths d on both sides of the distance to a nearer face. N is a local minimum with a flat
// neighbourhood (the local Hessian bound holds), so only the cap can refuse the points where
// the other face is nearer; every certified point must be the reference's nearest.
TEST(DirectionCover, CompetingFacesAreNotCertified) {
  const std::array<double, 5> shapes[] = {{1, 0.6, 0.8, 0.2, 0.2},
                                          {1, 0.6, 0.8, 0.1, 0.3},
                                          {2, 1, 1.5, 0.3, 0.1},
                                          {1, 0.7, 0.9, 0.4, 0.4}};
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(0, 1);
  int total = 0, certified = 0, certified_global = 0, not_global = 0;
  for (const auto& p : shapes) {
    const Superellipsoid<double> shape{p[0], p[1], p[2], p[3], p[4]};
    SCOPED_TRACE(test::describe(shape));
    const test::ReferenceDistance reference({p[0], p[1], p[2]}, p[3], p[4]);
    const auto gauge = detail::NestedNorm<double>::gauge(shape);
    const double nearer = std::min(p[1], p[2]);  // the distance to the nearer faces' middles
    for (int k = 0; k < 80; ++k) {
      const Vector3<double> n_point = shape.radialProjection(
          Vector3<double>(p[0], p[1] * (0.02 + 0.4 * u(rng)), p[2] * (0.02 + 0.4 * u(rng))));
      const Vector3<double> normal = shape.normal(n_point);
      const double d = nearer * (0.3 + 0.9 * u(rng));
      const Vector3<double> y = n_point - d * normal;
      if ((y.array() < 0).any() || !shape.contains(y)) continue;
      ++total;
      const Verdict verdict = judge(shape, reference, gauge, y, n_point, normal, d);
      const bool global = verdict.global;
      if (!global) ++not_global;
      if (!verdict.certified) continue;
      ++certified;
      if (global) ++certified_global;
      EXPECT_TRUE(global) << "certified a point that is not the nearest: Q = " << y.transpose()
                          << ", d = " << d << ", reference " << verdict.reference_depth;
    }
  }
  std::printf("competing faces: %d points, %d not global, %d certified\n", total, not_global,
              certified);
  EXPECT_GT(not_global, 40);
  EXPECT_GT(certified_global, 40);
}

// The cover's start is a surface point of the first octant (its support points are pulled a
// few ulps inside, no more).
TEST(DirectionCover, StartIsASurfacePoint) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const auto& p : kShapes) {
    const Superellipsoid<double> shape{p[0], p[1], p[2], p[3], p[4]};
    SCOPED_TRACE(test::describe(shape));
    const test::ReferenceDistance reference({p[0], p[1], p[2]}, p[3], p[4]);
    for (int k = 0; k < 20; ++k) {
      const Vector3<double> y =
          shape.radii().cwiseProduct(Vector3<double>(u(rng), u(rng), u(rng))).cwiseAbs();
      const Vector3<double> s = detail::directionCover(shape).startNear(y);
      ASSERT_TRUE((s.array() >= 0).all()) << s.transpose();
      EXPECT_NEAR(double(reference.gauge({s[0], s[1], s[2]})), 1.0, 1e-13);
    }
  }
}

// The solver on uniform inside points (the benchmark's "uniform inside" set, where the cover
// supplies the first start and most certificates) against the long-double reference.
template <typename S>
class CoverSolverTest : public ::testing::Test {};
TYPED_TEST_SUITE_P(CoverSolverTest);
TYPED_TEST_P(CoverSolverTest, UniformInsideAnswersAreTheGlobalMinimum) {
  using S = TypeParam;
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto options = DistanceOptions<S>::of(DistanceMethod::kExact);
  for (const auto& p : kShapes) {
    const Superellipsoid<S> shape{S(p[0]), S(p[1]), S(p[2]), S(p[3]), S(p[4])};
    SCOPED_TRACE(test::describe(shape));
    const test::ReferenceDistance reference({p[0], p[1], p[2]}, p[3], p[4]);
    const double size = shape.size(), target = test::exactTarget<S>(p[3], p[4]);
    int checked = 0;
    while (checked < 40) {
      const Vector3<S> x = Vector3<S>(S(p[0] * u(rng)), S(p[1] * u(rng)), S(p[2] * u(rng)));
      if (!shape.contains(x)) continue;
      ++checked;
      const auto r = pointDistance(shape, x, options);
      const auto truth = reference.query({x[0], x[1], x[2]});
      EXPECT_TRUE(r.converged) << "at " << x.transpose();
      EXPECT_NEAR(double(r.distance), double(truth.distance), target * size)
          << "at " << x.transpose();
    }
  }
}
REGISTER_TYPED_TEST_SUITE_P(CoverSolverTest, UniformInsideAnswersAreTheGlobalMinimum);
using Scalars = ::testing::Types<float, double>;
INSTANTIATE_TYPED_TEST_SUITE_P(FloatAndDouble, CoverSolverTest, Scalars);

}  // namespace
}  // namespace fcl_superellipsoid
