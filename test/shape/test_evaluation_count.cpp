// shapeEvaluations() (diagnostics.h): the benchmark's iteration count per query. It counts each
// evaluation of a superellipsoid's support function or gauge exactly once, on the thread that
// made it, and the FCL libccd path the benchmark compares with is counted through the same
// support function.

#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include <cstdint>
#include <thread>

#include "fcl_superellipsoid/diagnostics.h"
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_superellipsoid/gjk_support.h"
#include "fcl_superellipsoid/superellipsoid.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

TEST(ShapeEvaluations, OnePerSupportPointAndGaugeCall) {
  const Superellipsoidd shape(1.0, 2.0, 0.5, 0.3, 1.4);
  shapeEvaluations() = 0;
  for (int i = 0; i < 7; ++i) shape.supportPoint(Vector3<double>(1.0, -0.5 * i, 0.25));
  EXPECT_EQ(shapeEvaluations(), 7u);
  shape.gauge(Vector3<double>(0.3, 0.1, -0.2));
  shape.gaugeGradient(Vector3<double>(0.3, 0.1, -0.2));
  EXPECT_EQ(shapeEvaluations(), 9u);
  shapeEvaluations() = 0;
  EXPECT_EQ(shapeEvaluations(), 0u);
}

TEST(ShapeEvaluations, EveryPairMethodIsCounted) {
  const Superellipsoidd shape(1.0, 2.0, 0.5, 0.3, 1.4);
  const fcl::Boxd box(1.0, 0.5, 2.0);
  fcl::Transform3d X_WA = fcl::Transform3d::Identity(), X_WB = fcl::Transform3d::Identity();
  X_WB.translation() << 3.0, 0.2, -0.1;

  // Ours: a separated query evaluates the shape, and the same query evaluates it as often again.
  fcl::DistanceRequestd request(true, true);
  fcl::DistanceResultd result;
  shapeEvaluations() = 0;
  fcl_superellipsoid::distance(static_cast<const fcl::CollisionGeometryd*>(&shape), X_WA,
                               static_cast<const fcl::CollisionGeometryd*>(&box), X_WB, request,
                               result);
  const std::uint64_t ours = shapeEvaluations();
  EXPECT_GT(ours, 0u);
  fcl_superellipsoid::distance(static_cast<const fcl::CollisionGeometryd*>(&shape), X_WA,
                               static_cast<const fcl::CollisionGeometryd*>(&box), X_WB, request,
                               result);
  EXPECT_EQ(shapeEvaluations(), 2 * ours);

  // FCL's libccd GJK through the exact support function (gjk_support.h): one evaluation per
  // support call, at least one per iteration.
  const fcl::detail::GJKSolver_libccd<double> solver;
  double d = 0;
  shapeEvaluations() = 0;
  ASSERT_TRUE(solver.shapeDistance(shape, X_WA, box, X_WB, &d, nullptr, nullptr));
  EXPECT_GT(shapeEvaluations(), 0u);
}

// The count is per thread: another thread's evaluations do not reach this thread's count, and
// its own starts at zero. (Run under ThreadSanitizer by scripts/test.sh --tsan.)
TEST(ShapeEvaluations, EvaluationsArePerThread) {
  const Superellipsoidd shape(1.0, 2.0, 0.5, 0.3, 1.4);
  shapeEvaluations() = 0;
  shape.supportPoint(Vector3<double>(1.0, 0.0, 0.0));
  std::uint64_t other_start = 1, other_end = 0;
  std::thread other([&] {
    other_start = shapeEvaluations();
    for (int i = 0; i < 100; ++i) shape.supportPoint(Vector3<double>(0.0, 1.0, 0.01 * i));
    other_end = shapeEvaluations();
  });
  other.join();
  EXPECT_EQ(other_start, 0u);
  EXPECT_EQ(other_end, 100u);
  EXPECT_EQ(shapeEvaluations(), 1u);
}

}  // namespace
}  // namespace fcl_superellipsoid
