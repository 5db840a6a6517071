// A scene simulates only the effects it declares: without effects nothing moves (bitwise),
// gravity alone is the integrator's closed-form free fall, an effect not declared has no
// phase and no time, and without collision the cloth passes through the shape.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/cloth_simulation.h"
#include "report/measurements.h"
#include "scene_fixtures.h"

namespace fse_sim {
namespace {

bool hasPhase(const ClothSimulation& sim, Phase phase) {
  return std::count(sim.phases().begin(), sim.phases().end(), phase) > 0;
}

TEST(ClothEffectsTest, NoEffectsLeaveTheStateBitwiseUnchanged) {
  ClothSimulation sim(test::smallClothScene("[]"));
  const Eigen::Matrix3Xd start = sim.positions();
  for (int s = 0; s < 30; ++s) sim.step();
  EXPECT_EQ(sim.positions(), start);  // bitwise
  EXPECT_TRUE(sim.velocities().isZero(0));
  EXPECT_EQ(sim.phases(),
            (std::vector<Phase>{Phase::kIntegration, Phase::kVelocityUpdate, Phase::kTotal}));
  for (Phase p : {Phase::kPositionConstraints, Phase::kContactConstraints,
                  Phase::kVelocityConstraints, Phase::kCollisionDetection}) {
    EXPECT_EQ(sim.lastStepTimes()[int(p)], 0) << toString(p);
  }
  EXPECT_EQ(sim.contacts(), nullptr);
}

TEST(ClothEffectsTest, GravityAloneIsTheIntegratorsClosedFormFreeFall) {
  const Scene scene =
      test::smallClothScene(R"(["gravity"])", R"("gravity": {"acceleration": [0.5, 0, -9.81]})");
  ClothSimulation sim(scene);
  const Eigen::Matrix3Xd start = sim.positions();
  const int steps = 20, substeps = scene.time.substeps;
  for (int s = 0; s < steps; ++s) sim.step();
  // Semi-implicit Euler over k substeps of h: v_k = k h g, x_k = x_0 + h² g k(k + 1)/2.
  const double h = scene.time.step / substeps;
  const double k = double(steps * substeps);
  const Eigen::Vector3d g = scene.gravity->acceleration;
  const Eigen::Vector3d dx = h * h * g * k * (k + 1) / 2;
  // Rounding: XPBD takes each substep's velocity from positions, v = (x − x_start)/h, so a
  // substep's velocity carries up to 2ε·|x|/h of cancellation error (ε = 2⁻⁵³), and k
  // substeps add up; positions carry h times that, plus their own rounding, per substep.
  const double x_max = std::max(start.cwiseAbs().maxCoeff(), sim.positions().cwiseAbs().maxCoeff());
  const double eps = std::numeric_limits<double>::epsilon() / 2;
  const double velocity_bound = k * 2 * eps * x_max / h * std::sqrt(3.0);
  const double position_bound = k * (h * velocity_bound + 2 * eps * x_max * std::sqrt(3.0));
  for (Eigen::Index i = 0; i < start.cols(); ++i) {
    EXPECT_LE((sim.positions().col(i) - (start.col(i) + dx)).norm(), position_bound) << i;
    EXPECT_LE((sim.velocities().col(i) - k * h * g).norm(), velocity_bound) << i;
  }
  EXPECT_EQ(sim.phases(),
            (std::vector<Phase>{Phase::kIntegration, Phase::kVelocityUpdate, Phase::kTotal}));
}

TEST(ClothEffectsTest, UndeclaredEffectsHaveNoPhase) {
  ClothSimulation stretch_only(test::smallClothScene(R"(["gravity", "stretch"])"));
  EXPECT_TRUE(hasPhase(stretch_only, Phase::kPositionConstraints));
  EXPECT_FALSE(hasPhase(stretch_only, Phase::kCollisionDetection));
  EXPECT_FALSE(hasPhase(stretch_only, Phase::kContactConstraints));
  EXPECT_FALSE(hasPhase(stretch_only, Phase::kVelocityConstraints));
  ClothSimulation with_collision(test::smallClothScene(R"(["gravity", "collision"])"));
  EXPECT_TRUE(hasPhase(with_collision, Phase::kCollisionDetection));
  EXPECT_TRUE(hasPhase(with_collision, Phase::kContactConstraints));
  EXPECT_FALSE(hasPhase(with_collision, Phase::kPositionConstraints));
  EXPECT_FALSE(hasPhase(with_collision, Phase::kVelocityConstraints));
  ClothSimulation damped(test::smallClothScene(R"(["damping"])"));
  EXPECT_TRUE(hasPhase(damped, Phase::kVelocityConstraints));
  damped.step();
  EXPECT_EQ(damped.lastStepTimes()[int(Phase::kCollisionDetection)], 0);
}

TEST(ClothEffectsTest, WithoutCollisionTheClothPassesThroughTheShape) {
  const Scene scene = test::smallClothScene(R"(["gravity", "stretch"])", "", 1.5);
  ClothSimulation sim(scene);
  const Measurer measurer(scene);
  double deepest = 0;
  for (int s = 0; s < 90; ++s) {
    sim.step();
    deepest = std::max(deepest, measurer.maxPenetration(sim.positions()));
  }
  EXPECT_GT(deepest, 0.5);  // went through the middle of the 0.7-high shape
  EXPECT_LT(sim.positions().row(2).maxCoeff(), -0.7);  // and out below it
}

TEST(ClothEffectsTest, WithCollisionNoVertexEndsAStepDeeperThanTheTolerance) {
  const Scene scene = test::smallClothScene(R"(["gravity", "stretch", "bending", "collision"])",
                                            R"("collision": {"tolerance": 0.01})", 2.0);
  ClothSimulation sim(scene);
  const Measurer measurer(scene);
  int steps_with_contact = 0;
  for (int s = 0; s < 120; ++s) {
    sim.step();
    ASSERT_LE(measurer.maxPenetration(sim.positions()), scene.collision->tolerance) << "step " << s;
    if (!sim.contacts()->active().empty()) ++steps_with_contact;
  }
  EXPECT_GT(steps_with_contact, 60);  // it did land
}

TEST(ClothEffectsTest, PinningFixesAndAttachesVertices) {
  const Scene scene = test::smallClothScene(
      R"(["gravity", "stretch", "pinning"])",
      R"("pinning": {"fixed": [0], "attached": [{"vertex": 15, "target": [2, -1.5, 1.2]}]})", 0.5);
  ClothSimulation sim(scene);
  const Eigen::Vector3d fixed = sim.positions().col(0);
  for (int s = 0; s < 30; ++s) sim.step();
  EXPECT_EQ(sim.positions().col(0), fixed);
  // A hard attachment (compliance 0) is the last position constraint: exactly on target.
  EXPECT_LE((sim.positions().col(15) - Eigen::Vector3d(2, -1.5, 1.2)).norm(), 1e-12);
}

}  // namespace
}  // namespace fse_sim
