// Batched gradients (batchDistanceDerivatives, batch_distance.h): each row is the single
// query's gradient (pointDistanceDerivatives, itself tested against the long-double reference in
// test/solvers/test_point_derivatives.cpp), bitwise on the scalar path and for vertices inside,
// to the solver's tolerance on the SIMD lanes; a sample of rows against central differences of
// the reference directly; the flag on ties; independence of the thread count; bad input.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fcl_superellipsoid/batch_distance.h"
#include "fcl_superellipsoid/point_derivatives.h"
#include "polished_reference.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

template <typename S>
class BatchDerivativesTest : public ::testing::Test {};
TYPED_TEST_SUITE(BatchDerivativesTest, test::Scalars);

/// A random shape of the derivatives' range: exponents 0.1–1.9, aspect ratios to 100:1,
/// the largest radius `size`.
template <typename S>
Superellipsoid<S> randomShape(std::mt19937& rng, S size) {
  std::uniform_real_distribution<double> unit(0, 1);
  Vector3<S> radii;
  for (int i = 0; i < 3; ++i) radii[i] = size * S(std::pow(10.0, -2 * unit(rng)));
  radii[int(rng() % 3)] = size;
  return Superellipsoid<S>(radii, S(0.1 + 1.8 * unit(rng)), S(0.1 + 1.8 * unit(rng)));
}

/// World points around the posed shape: inside, near the surface on both sides, outside, on
/// the coordinate planes (ties inside), and the centre.
template <typename S>
Matrix3X<S> cloudAround(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
                        std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> unit(0, 1);
  test::AngleSampler angles(rng());
  Matrix3X<S> p(3, count);
  for (int k = 0; k < count; ++k) {
    const auto [eta, omega] = angles();
    const Vector3<S> surface = shape.surfacePoint(S(eta), S(omega));
    const S scales[] = {S(0.3 + 0.65 * unit(rng)), S(1 + 0.02 * (unit(rng) - 0.5)),
                        S(1.05 + 2 * unit(rng))};
    Vector3<S> p_S = scales[k % 3] * surface;
    if (k % 11 == 5) p_S[k % 3] = S(0);  // a coordinate plane
    if (k == 7) p_S.setZero();           // the centre
    p.col(k) = X_WS * p_S;
  }
  return p;
}

/// `call` throws std::invalid_argument whose message contains each of `parts`.
template <typename Call>
void expectInvalidArgument(const Call& call, const std::vector<std::string>& parts) {
  try {
    call();
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    for (const std::string& part : parts) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  }
}

template <typename S>
BatchOptions<S> optionsWith(bool vectorize, int threads = 1) {
  BatchOptions<S> options;
  options.vectorize = vectorize;
  options.threads = threads;
  return options;
}

/// Row i of the batch against the single world-frame query: bitwise where `bitwise`, else
/// within `bound` (relative to the size for lengths, to 1 for unit vectors and d_shape's radii
/// columns, to the size for its exponent columns and d_pose's rotation part).
template <typename S>
void expectRowMatches(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
                      const Matrix3X<S>& p_WV, const BatchDerivativesResult<S>& batch,
                      Eigen::Index i, bool bitwise, S bound) {
  const PointDistanceDerivatives<S> single =
      pointDistanceDerivatives(shape, X_WS, Vector3<S>(p_WV.col(i)));
  SCOPED_TRACE("vertex " + std::to_string(i) + (bitwise ? " (bitwise)" : " (to the tolerance)"));
  if (bitwise) {
    EXPECT_EQ(batch.distance[i], single.value.distance);
    EXPECT_EQ(batch.nearest_point.col(i), single.value.nearest_point);
    EXPECT_EQ(batch.normal.col(i), single.d_query);
    EXPECT_EQ(batch.d_pose.col(i), single.d_pose);
    EXPECT_EQ(batch.d_shape.col(i), single.d_shape);
    EXPECT_EQ(batch.differentiable[i], single.differentiable);
    return;
  }
  const S size = shape.size();
  EXPECT_NEAR(batch.distance[i], single.value.distance, bound * size);
  EXPECT_LE((batch.normal.col(i) - single.d_query).norm(), bound);
  EXPECT_LE((batch.d_pose.col(i).template head<3>() - single.d_pose.template head<3>()).norm(),
            bound * size);
  EXPECT_LE((batch.d_pose.col(i).template tail<3>() - single.d_pose.template tail<3>()).norm(),
            bound);
  EXPECT_LE((batch.d_shape.col(i).template head<3>() - single.d_shape.template head<3>()).norm(),
            bound);
  EXPECT_LE((batch.d_shape.col(i).template tail<2>() - single.d_shape.template tail<2>()).norm(),
            bound * size);
  EXPECT_EQ(batch.differentiable[i], single.differentiable);
}

/// With the scalar solver every row is the single query's, bit for bit; on the SIMD lanes the
/// rows agree to the solver's tolerance (the gradients are Lipschitz in the nearest point: a
/// shift of δ moves them by δ × curvature), and the flags are the same (the lanes' runner-up).
TYPED_TEST(BatchDerivativesTest, RowsAreTheSingleQuerysGradients) {
  using S = TypeParam;
  std::mt19937 rng(7101);
  // Float's tolerance is 1e-6 × size; its nearest points near a sharp shape's edges move the
  // normal by up to about 1e-3 (test_point_derivatives.cpp, float). Double's is 1e-12.
  const S bound = sizeof(S) == 4 ? S(2e-2) : S(1e-6);
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const S size = S(std::pow(10.0, -3 + 6 * (trial % 7) / 6.0));
    const Superellipsoid<S> shape = randomShape<S>(rng, size);
    SCOPED_TRACE(testing::PrintToString(shape.radii().transpose()) + " eps " +
                 std::to_string(shape.eps1()) + ", " + std::to_string(shape.eps2()));
    const fcl::Transform3<S> X_WS = test::randomPose<S>(rng, S(2) * size);
    const Matrix3X<S> p_WV = cloudAround(shape, X_WS, rng, 60);
    BatchDerivativesResult<S> scalar, simd;
    batchDistanceDerivatives(shape, X_WS, p_WV, scalar, optionsWith<S>(false));
    batchDistanceDerivatives(shape, X_WS, p_WV, simd, optionsWith<S>(true));
    for (Eigen::Index i = 0; i < p_WV.cols(); ++i) {
      expectRowMatches(shape, X_WS, p_WV, scalar, i, true, bound);
      (simd.distance[i] < S(0) ? inside : outside) += 1;
      expectRowMatches(shape, X_WS, p_WV, simd, i, false, bound);
    }
  }
  EXPECT_GT(inside, 300);
  EXPECT_GT(outside, 600);
}

/// Central difference with one Richardson step, error O(h⁴).
template <typename F>
long double centralDifference(F&& at, long double h) {
  const long double d1 = (at(h) - at(-h)) / (2 * h);
  const long double d2 = (at(h / 2) - at(-h / 2)) / h;
  return (4 * d2 - d1) / 3;
}

/// Rows of the SIMD batch in double against central differences of the long-double reference
/// distance (polished_reference.h): the shape's five parameters and the pose's twist.
TEST(BatchDerivatives, RowsMatchFiniteDifferencesOfTheReference) {
  using test::ReferenceShape;
  using test::Vec3L;
  std::mt19937 rng(7102);
  long double worst = 0;
  int checked = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const double size = std::pow(10.0, -3 + 6 * trial / 7.0);
    const Superellipsoid<double> shape = randomShape<double>(rng, size);
    const fcl::Transform3<double> X_WS = test::randomPose<double>(rng, 2 * size);
    const Matrix3X<double> p_WV = cloudAround(shape, X_WS, rng, 9);
    BatchDerivativesResult<double> got;
    batchDistanceDerivatives(shape, X_WS, p_WV, got, optionsWith<double>(true));
    const ReferenceShape ref{
        {shape.radii()[0], shape.radii()[1], shape.radii()[2]}, shape.eps1(), shape.eps2()};
    const Eigen::Transform<long double, 3, Eigen::Isometry> xl = X_WS.cast<long double>();
    for (Eigen::Index i = 0; i < p_WV.cols(); ++i) {
      if (!got.differentiable[i]) continue;
      SCOPED_TRACE("trial " + std::to_string(trial) + ", vertex " + std::to_string(i));
      const Vec3L q_w = p_WV.col(i).cast<long double>();
      // Inside, a stencil that crosses a symmetry plane crosses the medial surface, where the
      // distance has a kink (the pose's steps move Q by up to about 1e-5 × size).
      const Vec3L q_s = xl.inverse() * q_w;
      if (got.distance[i] < 0 && q_s.cwiseAbs().minCoeff() < 1e-4L * size) continue;
      const test::PolishedResult base = test::polishedReference(ref, q_s);
      ASSERT_TRUE(base.ok);
      Eigen::Matrix<long double, 5, 1> d_shape;
      for (int j = 0; j < 5; ++j) {
        d_shape[j] = centralDifference(
            [&](long double h) {
              ReferenceShape s = ref;
              if (j < 3) s.a[j] += h;
              if (j == 3) s.e1 += h;
              if (j == 4) s.e2 += h;
              return test::polish(s, q_s, base.nearest).distance;
            },
            j < 3 ? 1e-6L * ref.a[j] : 1e-6L);
      }
      Eigen::Matrix<long double, 6, 1> d_pose;
      for (int k = 0; k < 6; ++k) {
        d_pose[k] = centralDifference(
            [&](long double h) {
              return test::polish(ref, test::twisted(xl, k, h).inverse() * q_w, base.nearest)
                  .distance;
            },
            k < 3 ? 1e-6L : 1e-6L * size);
      }
      // Relative to the derivative's scale (1 for lengths per length, the size per radian or
      // per unit of exponent).
      const long double e_radii =
          (got.d_shape.col(i).head<3>().cast<long double>() - d_shape.head<3>()).norm() /
          std::max(d_shape.head<3>().norm(), 1e-3L);
      const long double e_exponents =
          (got.d_shape.col(i).tail<2>().cast<long double>() - d_shape.tail<2>()).norm() /
          std::max(d_shape.tail<2>().norm(), 1e-3L * size);
      const long double e_pose =
          (got.d_pose.col(i).head<3>().cast<long double>() - d_pose.head<3>()).norm() / size +
          (got.d_pose.col(i).tail<3>().cast<long double>() - d_pose.tail<3>()).norm();
      EXPECT_LE(e_radii, 1e-6L) << got.d_shape.col(i).transpose();
      EXPECT_LE(e_exponents, 1e-6L) << got.d_shape.col(i).transpose();
      EXPECT_LE(e_pose, 1e-6L) << got.d_pose.col(i).transpose() << "\nreference "
                               << d_pose.transpose();
      worst = std::max({worst, e_radii, e_exponents, e_pose});
      ++checked;
    }
  }
  EXPECT_GE(checked, 40);
  std::ostringstream text;
  text << std::scientific << double(worst);
  RecordProperty("worst_relative_error", text.str());
  RecordProperty("rows_checked", checked);
}

/// Vertices built to have several nearest points are flagged, as the single query flags them;
/// every number stays finite.
TYPED_TEST(BatchDerivativesTest, FlagsTiesAsTheSingleQueryDoes) {
  using S = TypeParam;
  const Superellipsoid<S> ellipsoid(S(3), S(2), S(1), S(1), S(1));
  const Superellipsoid<S> box_like(S(1), S(1), S(1.5), S(0.1), S(0.1));
  std::mt19937 rng(7103);
  const fcl::Transform3<S> X_WS = test::randomPose<S>(rng, S(1));
  struct Case {
    const Superellipsoid<S>* shape;
    Vector3<S> p_S;
  };
  const Case cases[] = {{&ellipsoid, Vector3<S>(S(0.5), S(0.3), S(0))},    // a symmetry plane
                        {&ellipsoid, Vector3<S>::Zero()},                  // the centre
                        {&box_like, Vector3<S>(S(0.3), S(0.3), S(0.2))}};  // the diagonal plane
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::PrintToString(c.p_S.transpose()));
    Matrix3X<S> p_WV(3, 2);
    p_WV.col(0) = X_WS * c.p_S;
    p_WV.col(1) = X_WS * Vector3<S>(c.p_S + S(1e-2) * Vector3<S>(S(0.31), S(0.17), S(0.23)));
    for (bool vectorize : {false, true}) {
      BatchDerivativesResult<S> r;
      batchDistanceDerivatives(*c.shape, X_WS, p_WV, r, optionsWith<S>(vectorize));
      EXPECT_FALSE(r.differentiable[0]);
      EXPECT_TRUE(r.differentiable[1]);
      EXPECT_TRUE(r.d_pose.allFinite() && r.d_shape.allFinite() && r.normal.allFinite());
      // Off the centre the solver's answer is one of the tied points (an exact tie is not
      // flagged where the rounded query is not exactly on the plane; the single query agrees).
      EXPECT_EQ(r.differentiable[0],
                pointDistanceDerivatives(*c.shape, X_WS, Vector3<S>(p_WV.col(0))).differentiable);
    }
  }
}

/// A tie the SIMD lanes solve (off the coordinate planes, near the surface): two faces of a
/// box-like shape equally near, on its diagonal plane x = y. The lanes' runner-up flags it.
TYPED_TEST(BatchDerivativesTest, FlagsATieSolvedOnTheLanes) {
  using S = TypeParam;
  const Superellipsoid<S> box_like(S(1), S(1), S(1.5), S(0.2), S(0.2));
  Matrix3X<S> p(3, 1);
  p.col(0) = Vector3<S>(S(0.8), S(0.8), S(0.3));
  BatchStatistics statistics;
  BatchOptions<S> options = optionsWith<S>(true);
  options.statistics = &statistics;
  BatchDerivativesResult<S> r;
  batchDistanceDerivatives(box_like, fcl::Transform3<S>::Identity(), p, r, options);
  EXPECT_EQ(statistics.simd, 1u);
  EXPECT_FALSE(r.differentiable[0]);
  // Off the plane the faces are no longer tied.
  p.col(0) = Vector3<S>(S(0.8), S(0.78), S(0.3));
  batchDistanceDerivatives(box_like, fcl::Transform3<S>::Identity(), p, r, options);
  EXPECT_EQ(statistics.simd, 1u);
  EXPECT_TRUE(r.differentiable[0]);
}

/// Threads split the vertices into fixed chunks: every thread count gives the same rows.
TYPED_TEST(BatchDerivativesTest, SameRowsOnAnyNumberOfThreads) {
  using S = TypeParam;
  std::mt19937 rng(7104);
  const Superellipsoid<S> shape(S(1), S(0.6), S(0.3), S(0.4), S(1.3));
  const fcl::Transform3<S> X_WS = test::randomPose<S>(rng, S(1));
  const Matrix3X<S> p_WV = cloudAround(shape, X_WS, rng, 2000);
  BatchDerivativesResult<S> one, many;
  batchDistanceDerivatives(shape, X_WS, p_WV, one, optionsWith<S>(true, 1));
  BatchOptions<S> threaded = optionsWith<S>(true, 4);
  threaded.min_parallel_vertices = 1;
  batchDistanceDerivatives(shape, X_WS, p_WV, many, threaded);
  EXPECT_EQ(one.distance, many.distance);
  EXPECT_EQ(one.d_pose, many.d_pose);
  EXPECT_EQ(one.d_shape, many.d_shape);
  EXPECT_EQ(one.differentiable, many.differentiable);
}

TYPED_TEST(BatchDerivativesTest, RefusesAnotherMethodAndBadVerticesNamingThem) {
  using S = TypeParam;
  const Superellipsoid<S> shape(S(1), S(1), S(1), S(0.5), S(0.5));
  Matrix3X<S> p_WV = Matrix3X<S>::Ones(3, 3);
  BatchDerivativesResult<S> r;
  BatchOptions<S> paper;
  paper.distance = DistanceOptions<S>::of(DistanceMethod::kPaper);
  expectInvalidArgument(
      [&] { batchDistanceDerivatives(shape, fcl::Transform3<S>::Identity(), p_WV, r, paper); },
      {"batchDistanceDerivatives", "Paper"});
  p_WV(1, 2) = std::numeric_limits<S>::quiet_NaN();
  expectInvalidArgument(
      [&] { batchDistanceDerivatives(shape, fcl::Transform3<S>::Identity(), p_WV, r); },
      {"batchDistanceDerivatives", "vertex 2", "nan"});
  EXPECT_EQ(r.distance.size(), 0);  // unchanged
}

}  // namespace
}  // namespace fcl_superellipsoid
