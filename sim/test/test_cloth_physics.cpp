// The cloth case, CI-sized: edges keep their length within a bound, energy never grows
// without input, the cloth comes to rest on the shape, and threads do not change results.

#include <gtest/gtest.h>

#include "physics/cloth_simulation.h"
#include "report/measurements.h"
#include "scene_fixtures.h"

namespace fse_sim {
namespace {

// The cloth scenes' effects (sim/scenes/cloth_*.json): air damping included, without which
// the hanging hem swings on for minutes.
const char* kClothEffects =
    R"(["gravity", "stretch", "bending", "collision", "friction", "damping"])";
const char* kClothBlocks = R"("bending": {"compliance": 0.01}, "collision": {"tolerance": 0.01},
                              "friction": {"dynamic": 0.3, "static": 0.4},
                              "damping": {"linear": 0.5})";

double kineticEnergy(const ClothSimulation& sim) {
  return 0.5 * sim.vertexMass() * sim.velocities().squaredNorm();
}

TEST(ClothPhysicsTest, EdgeStrainStaysBounded) {
  // Inextensible edges, one iteration per substep: Gauss–Seidel leaves some strain where
  // the cloth folds over the shape's rim; 5 % bounds it on this cloth (3 × 3 m, 16 × 16).
  ClothSimulation sim(test::smallClothScene(kClothEffects, kClothBlocks, 3.0));
  double worst = 0;
  for (int s = 0; s < 180; ++s) {
    sim.step();
    worst = std::max(worst, sim.maxEdgeStrain());
  }
  EXPECT_LT(worst, 0.05);
}

TEST(ClothPhysicsTest, EnergyNeverGrowsWithoutInput) {
  // Gravity is conservative, constraints and contacts only take energy away (XPBD's velocity
  // update after a projection removes the velocity along the correction).
  ClothSimulation sim(test::smallClothScene(kClothEffects, kClothBlocks, 3.0));
  double previous = sim.energy();
  const double start = previous;
  for (int s = 0; s < 180; ++s) {
    sim.step();
    const double e = sim.energy();
    EXPECT_LE(e, start + 1e-9 * std::abs(start)) << "step " << s;
    previous = e;
  }
  EXPECT_LT(previous, start);
}

TEST(ClothPhysicsTest, ClothComesToRestOnTheShape) {
  const Scene scene = test::smallClothScene(kClothEffects, kClothBlocks, 6.0);
  ClothSimulation sim(scene);
  const Measurer measurer(scene);
  const double start = sim.energy();
  for (int s = 0; s < 360; ++s) sim.step();
  const StepRecord r = measurer.measure(sim);
  // At rest: what is still moving carries less than 0.1 % of the energy the fall released.
  EXPECT_LT(kineticEnergy(sim), 1e-3 * (start - sim.energy()));
  EXPECT_GT(r.contacts, 20);  // lying on the shape, not beside it
  EXPECT_LE(r.max_penetration, 0.01);
  EXPECT_GT(sim.positions().row(2).minCoeff(), -0.7);  // nothing fell past the shape's base
}

TEST(ClothPhysicsTest, SameResultsForOneAndTwoThreads) {
  // 40 × 40 = 1,600 vertices: above the batched queries' threshold for a second thread.
  const Scene scene = test::smallClothScene(kClothEffects, kClothBlocks, 1.0, 40);
  SimulationOptions one, two;
  one.threads = 1;
  two.threads = 2;
  ClothSimulation a(scene, one), b(scene, two);
  for (int s = 0; s < 60; ++s) {
    a.step();
    b.step();
  }
  EXPECT_EQ(a.positions(), b.positions());  // bitwise
  EXPECT_EQ(a.velocities(), b.velocities());
}

}  // namespace
}  // namespace fse_sim
