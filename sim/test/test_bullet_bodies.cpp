// The rigid-body scenes' Bullet peer: that it runs the scene we declare (its bodies' start, its
// substeps, only the declared effects) and keeps the small bowl's bodies inside. Ground truth
// is the integrator's closed form and the scene's construction.

#include <gtest/gtest.h>

#include <cmath>

#include "peer/bullet_bodies.h"
#include "scene_fixtures.h"

namespace fse_sim {
namespace {

using test::rigidScene;
using test::smallBowlScene;

TEST(BulletBodiesTest, FreeFallFollowsSemiImplicitEulerOverTheScenesSubsteps) {
  // Gravity alone, 20 substeps of h = 1/1200 s per step: after n substeps Bullet's integrator
  // (v += g·h, then x += v·h) has the body at z0 + v0·n·h − g·h²·n(n+1)/2, and it keeps its
  // spin. Bullet computes in float: within 1 mm over the second's fall of 5 m.
  const Scene scene = rigidScene(R"(["gravity", "rigid_bodies"])",
                                 R"([{"radii": [0.3, 0.4, 0.5], "exponents": [0.5, 0.8],
                                      "position": [1, 2, 10], "velocity": [0.5, 0, 1],
                                      "angular_velocity": [0, 0, 2]}])",
                                 R"("gravity": {"acceleration": [0, 0, -9.81]})", 1.0);
  BulletBodies peer(scene, 1);
  for (int s = 0; s < 60; ++s) peer.step();
  const double h = 1.0 / 1200, n = 1200;
  const RigidBody& b = peer.bodies()[0];
  EXPECT_NEAR(b.x[0], 1 + 0.5 * n * h, 1e-3);
  EXPECT_NEAR(b.x[1], 2, 1e-3);
  EXPECT_NEAR(b.x[2], 10 + n * h - 9.81 * h * h * n * (n + 1) / 2, 1e-3);
  EXPECT_NEAR(b.omega[2], 2, 1e-3);
  EXPECT_NEAR(peer.time(), 1.0, 1e-12);
}

TEST(BulletBodiesTest, WithoutRigidContactBodiesPassThroughEachOther) {
  // A ball dropped onto a fixed slab: with rigid_contact it rests on the slab; without the
  // effect Bullet must not collide them either.
  const std::string bodies =
      R"([{"radii": [5, 5, 0.5], "exponents": [0.2, 0.2], "fixed": true, "position": [0, 0, -0.5]},
          {"radii": [0.2, 0.2, 0.2], "exponents": [1, 1], "position": [0, 0, 0.5]}])";
  const std::string gravity = R"("gravity": {"acceleration": [0, 0, -9.81]})";
  BulletBodies with(rigidScene(R"(["gravity", "rigid_bodies", "rigid_contact"])", bodies,
                               gravity + R"(, "rigid_contact": {"tolerance": 0.01})"),
                    1);
  BulletBodies without(rigidScene(R"(["gravity", "rigid_bodies"])", bodies, gravity), 1);
  for (int s = 0; s < 60; ++s) {
    with.step();
    without.step();
  }
  EXPECT_NEAR(with.bodies()[1].x[2], 0.2, 0.02);  // on the slab's top face
  EXPECT_LT(without.bodies()[1].x[2], -1.0);      // fell through it
}

TEST(BulletBodiesTest, SmallBowlBodiesStayInside) {
  BulletBodies peer(smallBowlScene(4.0), 1);
  for (int s = 0; s < 240; ++s) peer.step();
  for (const RigidBody& b : peer.bodies()) {
    // Inside the bowl (its sphere's centre is the origin, radius 1.5; the rim at z = 0).
    EXPECT_LT(b.x.norm(), 1.5);
    EXPECT_LT(b.x[2], 0.0);
  }
  EXPECT_TRUE(std::isfinite(peer.energy()));
}

}  // namespace
}  // namespace fse_sim
