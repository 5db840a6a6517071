// Rigid bodies, CI-sized: friction on an incline, a bounce, torque-free rotation, energy, a few
// bodies coming to rest in a small bowl, the mesh model's contacts, threads, and the bowl's
// mesh. Ground truth is
// mechanics in closed form (or the scene's own construction), never the code under test.

#include <fcl_superellipsoid/tessellation.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>

#include "physics/rigid_simulation.h"
#include "scene_fixtures.h"

namespace fse_sim {
namespace {

using test::rigidScene;
using test::smallBowlScene;

constexpr double kG = 9.81;
constexpr double kStep = 1.0 / 60;

/// A fixed slab (box-like, 40 × 40 × 1 m, top face at height 0 before turning) tilted by theta
/// about the y axis, and a box-like slider (0.6 × 0.6 × 0.4 m) resting on it, 0.1 mm above its
/// face, its faces parallel to the slab's.
std::string inclineBodies(double theta_deg) {
  const double t = theta_deg * M_PI / 180;
  // The slab's centre 0.5 m below the origin along its normal n = (sin θ, 0, cos θ) turned.
  const Eigen::Vector3d n(std::sin(t), 0, std::cos(t));
  const Eigen::Vector3d slab = -0.5 * n, slider = 0.2001 * n;
  auto vec = [](const Eigen::Vector3d& v) {
    return "[" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) +
           "]";
  };
  return R"([{"radii": [20, 20, 0.5], "exponents": [0.1, 0.1], "fixed": true, "position": )" +
         vec(slab) + R"(, "rotation_deg": [0, )" + std::to_string(theta_deg) + R"(, 0]},
             {"radii": [0.3, 0.3, 0.2], "exponents": [0.1, 0.1], "position": )" +
         vec(slider) + R"(, "rotation_deg": [0, )" + std::to_string(theta_deg) + R"(, 0]}])";
}

/// Distance the slider moved down the slope (along +x turned by θ) after `seconds`.
double slideAfter(double theta_deg, double mu, ContactModel model, double seconds) {
  const std::string mu_text = std::to_string(mu);
  const Scene scene = rigidScene(
      R"(["gravity", "rigid_bodies", "rigid_contact", "friction"])", inclineBodies(theta_deg),
      R"("rigid_contact": {"tolerance": 0.01}, "friction": {"dynamic": )" + mu_text +
          R"(, "static": )" + mu_text + "}",
      seconds);
  SimulationOptions options;
  options.model = model;
  options.threads = 1;
  RigidSimulation sim(scene, options);
  const Eigen::Vector3d start = sim.bodies()[1].x;
  const long steps = std::lround(seconds / kStep);
  for (long s = 0; s < steps; ++s) sim.step();
  const double t = theta_deg * M_PI / 180;
  const Eigen::Vector3d down(std::cos(t), 0, -std::sin(t));  // down the slope
  return (sim.bodies()[1].x - start).dot(down);
}

TEST(RigidBodiesTest, StaticFrictionHoldsWhenMuExceedsTanTheta) {
  // θ = 20°: tan θ = 0.364; μ = 0.5 holds the slider (the vertex model; the exact model's
  // inclines: test_resting_contact.cpp).
  EXPECT_LT(std::abs(slideAfter(20, 0.5, ContactModel::kVertices, 1.0)), 0.005);
}

TEST(RigidBodiesTest, SlidingAcceleratesAtGTimesSinMinusMuCos) {
  // θ = 30°, μ = 0.2: a = g(sin θ − μ cos θ) = 3.206 m/s², s(1 s) = a/2 = 1.603 m. The vertex
  // model holds the slider's face at many points (the exact model's inclines:
  // test_resting_contact.cpp). Within 5 %: the Gauss–Seidel sweeps per substep leave the face's
  // normal impulse a little short of the weight (each contact alone also turns the body, so it
  // pushes less than the whole sink), and the friction it bounds with it.
  const double t = 30 * M_PI / 180, mu = 0.2;
  const double expected = 0.5 * kG * (std::sin(t) - mu * std::cos(t));
  EXPECT_NEAR(slideAfter(30, mu, ContactModel::kVertices, 1.0), expected, 0.05 * expected);
}

TEST(RigidBodiesTest, BounceReachesESquaredTimesTheDropHeight) {
  // A ball (ε = 1) dropped from 1 m (its lowest point above the slab's face) with e = 0.5
  // rises again to e²·h0 = 0.25 m.
  const double h0 = 1.0, e = 0.5, r = 0.2;
  const Scene scene = rigidScene(
      R"(["gravity", "rigid_bodies", "rigid_contact", "restitution"])",
      R"([{"radii": [20, 20, 0.5], "exponents": [0.1, 0.1], "fixed": true, "position": [0, 0, -0.5]},
          {"radii": [0.2, 0.2, 0.2], "exponents": [1, 1], "position": [0, 0, )" +
          std::to_string(h0 + r) + "]}]",
      R"("rigid_contact": {"tolerance": 0.01}, "restitution": {"coefficient": )" +
          std::to_string(e) + "}",
      2.0);
  for (ContactModel model : {ContactModel::kExact, ContactModel::kVertices}) {
    SimulationOptions options;
    options.model = model;
    options.threads = 1;
    RigidSimulation sim(scene, options);
    double apex = 0;
    bool bounced = false;
    for (int s = 0; s < 120; ++s) {
      sim.step();
      const RigidBody& ball = sim.bodies()[1];
      if (ball.v[2] > 0) bounced = true;
      if (bounced) apex = std::max(apex, ball.x[2] - r);
    }
    EXPECT_TRUE(bounced) << toString(model);
    EXPECT_NEAR(apex, e * e * h0, 0.05 * e * e * h0) << toString(model);
  }
}

TEST(RigidBodiesTest, TorqueFreeRotationKeepsItsAngularMomentum) {
  // No gravity, no contact: a body with three different moments spinning about a skew axis
  // (the intermediate axis is unstable: the motion tumbles) keeps L = I·ω in the world frame.
  // Its kinetic energy must never grow; the integrator may dissipate a little of it (it keeps
  // L, not the energy ellipsoid): at most 1 % over 5 s of tumbling.
  const Scene scene = rigidScene(R"(["rigid_bodies"])",
                                 R"([{"radii": [0.3, 0.5, 0.8], "exponents": [0.6, 0.9],
                                      "angular_velocity": [1.0, 4.0, 0.5]}])",
                                 "", 5.0);
  RigidSimulation sim(scene);
  const Eigen::Vector3d L0 = sim.bodies()[0].angularMomentum();
  const double E0 = sim.bodies()[0].kineticEnergy();
  double worst_L = 0, lowest_E = E0;
  for (int s = 0; s < 300; ++s) {
    sim.step();
    worst_L = std::max(worst_L, (sim.bodies()[0].angularMomentum() - L0).norm() / L0.norm());
    const double E = sim.bodies()[0].kineticEnergy();
    EXPECT_LE(E, E0 * (1 + 1e-12)) << "step " << s;
    lowest_E = std::min(lowest_E, E);
  }
  EXPECT_LT(worst_L, 1e-6);
  EXPECT_GT(lowest_E, 0.99 * E0);
}

/// The small bowl run for `duration`: the deepest interpenetration over the run (exact
/// surfaces) and the simulation at its end.
struct BowlRun {
  double deepest = 0;
  std::unique_ptr<RigidSimulation> sim;
};
BowlRun runSmallBowl(ContactModel model, double duration) {
  const Scene scene = smallBowlScene(duration);
  SimulationOptions options;
  options.model = model;
  BowlRun run;
  run.sim = std::make_unique<RigidSimulation>(scene, options);
  const long steps = std::lround(duration / kStep);
  for (long s = 0; s < steps; ++s) {
    run.sim->step();
    run.deepest = std::max(run.deepest, -run.sim->leastDistance(scene.rigid_contact->tolerance));
  }
  return run;
}

class SmallBowlTest : public ::testing::TestWithParam<ContactModel> {};

TEST_P(SmallBowlTest, BodiesStayInside) {
  const BowlRun run = runSmallBowl(GetParam(), 6.0);
  for (const RigidBody& b : run.sim->bodies()) {
    // Inside the bowl (its sphere's centre is the origin, radius 1.5; the rim at z = 0).
    EXPECT_LT(b.x.norm(), 1.5);
    EXPECT_LT(b.x[2], 0.0);
  }
}

TEST_P(SmallBowlTest, EnergyNeverGrowsWithoutInput) {
  // Contacts, friction, restitution (e < 1) and damping only take energy away. The position
  // pass may lift a body out of an overlap: at most the tolerance's worth of potential energy.
  const Scene scene = smallBowlScene(3.0);
  SimulationOptions options;
  options.model = GetParam();
  RigidSimulation sim(scene, options);
  double lift = 0;
  for (const RigidBody& b : sim.bodies()) lift += b.mass * kG * scene.rigid_contact->tolerance;
  double previous = sim.energy();
  for (int s = 0; s < 180; ++s) {
    sim.step();
    const double e = sim.energy();
    EXPECT_LE(e, previous + lift) << "step " << s;
    previous = std::min(previous, e);
  }
}

INSTANTIATE_TEST_SUITE_P(Models, SmallBowlTest,
                         ::testing::Values(ContactModel::kExact, ContactModel::kVertices,
                                           ContactModel::kPaper, ContactModel::kMesh),
                         [](const auto& info) { return std::string(toString(info.param)); });

TEST(RigidBodiesTest, ExactModelComesToRestWithoutInterpenetrationAboveTheTolerance) {
  // Rounded bodies roll to and fro in a bowl; air damping (1/s) stills them in a few seconds.
  const BowlRun run = runSmallBowl(ContactModel::kExact, 6.0);
  EXPECT_LE(run.deepest, 0.01);  // the scene's tolerance
  EXPECT_LT(run.sim->maxSpeed(), 0.05);
}

TEST(RigidBodiesTest, VertexModelComesToRest) {
  // Vertices against the implicit surface cannot see a sharp feature of the other body poke
  // between them: the paper's model bounds no interpenetration (docs/scenes.md).
  EXPECT_LT(runSmallBowl(ContactModel::kVertices, 6.0).sim->maxSpeed(), 0.05);
}

TEST(RigidBodiesTest, SpinningPointyBodyLandsWithoutInterpenetrationAboveTheTolerance) {
  // A nearly octahedral body (ε = 1.8) spinning at 15 rad/s lands on a slab: in one step its
  // tips turn by 0.25 rad, so the tip lowest at landing is not the one that was lowest at
  // detection (kept as a fixed point of the body, it let the next tip in by 0.0087 m). The
  // pair's contact must follow the support point (exact model).
  const double tolerance = 0.005;
  const Scene scene = rigidScene(
      R"(["gravity", "rigid_bodies", "rigid_contact"])",
      R"([{"radii": [20, 20, 0.5], "exponents": [0.1, 0.1], "fixed": true, "position": [0, 0, -0.5]},
          {"radii": [0.5, 0.45, 0.4], "exponents": [1.8, 1.8], "position": [0, 0, 1.5],
           "angular_velocity": [3, 15, 1]}])",
      R"("gravity": {"acceleration": [0, 0, -9.81]}, "rigid_contact": {"tolerance": 0.005})", 2.0);
  SimulationOptions options;
  options.threads = 1;
  RigidSimulation sim(scene, options);
  double deepest = 0;
  for (int s = 0; s < 120; ++s) {
    sim.step();
    deepest = std::max(deepest, -sim.leastDistance(tolerance));
  }
  EXPECT_LE(deepest, tolerance);
  EXPECT_LT(sim.bodies()[1].x[2], 0.6);  // it landed
}

/// The mesh model's contacts between two balls of radius r (ε = 1) on the x axis, body 0 at
/// the origin and body 1 at distance `centres`, with `vertices`-vertex tessellations.
std::vector<RigidContact> meshContactsOfTwoBalls(double r, double centres, int vertices,
                                                 double margin) {
  const std::string radius = std::to_string(r);
  const Scene scene = rigidScene(R"(["rigid_bodies", "rigid_contact"])",
                                 R"([{"radii": [)" + radius + ", " + radius + ", " + radius +
                                     R"(], "exponents": [1, 1], "position": [0, 0, 0]},
          {"radii": [)" + radius + ", " +
                                     radius + ", " + radius +
                                     R"(], "exponents": [1, 1], "position": [)" +
                                     std::to_string(3 * r) + R"(, 0, 0]}])");
  std::vector<RigidBody> bodies;
  for (const BodySpec& spec : sceneBodies(*scene.rigid_bodies)) {
    bodies.push_back(makeBody(spec, 1000));
  }
  bodies[1].x[0] = centres;  // the loader refuses bodies that overlap at the start
  RigidContactFinder finder(bodies, nullptr, ContactModel::kMesh, vertices, 1);
  std::vector<RigidContact> contacts;
  finder.find(bodies, margin, {0.0, 0.0}, contacts);
  return contacts;
}

TEST(RigidBodiesTest, MeshModelPushesOverlappingBodiesApart) {
  // Balls of radius 0.3 overlapping by 0.03: every contact FCL's triangle pairs give must move
  // body 0 away from body 1 (along −x) and report an overlap.
  const std::vector<RigidContact> contacts = meshContactsOfTwoBalls(0.3, 0.57, 200, 0.01);
  ASSERT_FALSE(contacts.empty());
  for (const RigidContact& c : contacts) {
    EXPECT_EQ(c.a, 0);
    EXPECT_EQ(c.b, 1);
    EXPECT_LT(c.n.dot(Eigen::Vector3d::UnitX()), -0.5) << c.n.transpose();
    EXPECT_LT(c.distance, 0);
    // Both points are within the bodies' reach of their centres.
    EXPECT_LE(c.r_a.norm(), 0.3 + 0.03);
    EXPECT_LE(c.r_b.norm(), 0.3 + 0.03);
  }
}

TEST(RigidBodiesTest, MeshModelSeesNearBodiesAtTheirMeshDistance) {
  // Balls of radius 0.3, 0.005 apart, margin 0.05. A tessellation's vertices lie on the
  // sphere and its triangles inside it, no nearer the centre than the least distance from the
  // centre to a triangle's plane (the inner radius, from the mesh itself): the meshes are
  // between 0.005 and 0.005 + 2·(r − inner) apart, along x.
  const double r = 0.3, gap = 0.005;
  const fcl_superellipsoid::TriangleMesh<double> mesh =
      fcl_superellipsoid::tessellate(fcl_superellipsoid::Superellipsoidd(r, r, r, 1, 1), 200);
  double inner = r;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).normalized();
    inner = std::min(inner, std::abs(n.dot(a)));
  }
  const std::vector<RigidContact> contacts = meshContactsOfTwoBalls(r, 2 * r + gap, 200, 0.05);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_GE(contacts[0].distance, gap - 1e-12);
  EXPECT_LE(contacts[0].distance, gap + 2 * (r - inner));
  EXPECT_LT(contacts[0].n.dot(Eigen::Vector3d::UnitX()), -0.9);
  // Nothing within a margin smaller than the gap.
  EXPECT_TRUE(meshContactsOfTwoBalls(r, 2 * r + gap, 200, 0.004).empty());
}

TEST(RigidBodiesTest, OneAndTwoThreadsGiveIdenticalResults) {
  const Scene scene = smallBowlScene(1.5);
  for (ContactModel model : {ContactModel::kExact, ContactModel::kVertices, ContactModel::kMesh}) {
    SimulationOptions one, two;
    one.model = two.model = model;
    one.threads = 1;
    two.threads = 2;
    RigidSimulation a(scene, one), b(scene, two);
    for (int s = 0; s < 90; ++s) {
      a.step();
      b.step();
    }
    for (std::size_t i = 0; i < a.bodies().size(); ++i) {
      EXPECT_EQ(a.bodies()[i].x, b.bodies()[i].x) << toString(model) << " body " << i;
      EXPECT_EQ(a.bodies()[i].q.coeffs(), b.bodies()[i].q.coeffs()) << toString(model);
    }
  }
}

TEST(RigidBodiesTest, GeneratedBowlHasThePapersVertexCountAndIsClosed) {
  BowlSpec spec;  // 25 rings × 100 segments per face
  const StaticMesh bowl = makeBowl(spec);
  EXPECT_EQ(bowl.vertices.cols(), 5002);
  // Closed: every edge has exactly two triangles, traversed in opposite directions.
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : bowl.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  // Every vertex lies on the inner or outer sphere; inner faces face the cavity (the centre).
  for (Eigen::Index i = 0; i < bowl.vertices.cols(); ++i) {
    const double r = bowl.vertices.col(i).norm();
    EXPECT_TRUE(std::abs(r - spec.radius) < 1e-12 ||
                std::abs(r - spec.radius - spec.thickness) < 1e-12);
  }
  int facing_in = 0;
  for (std::size_t t = 0; t < bowl.triangles.size(); ++t) {
    const Eigen::Vector3d c = bowl.vertices.col(bowl.triangles[t][0]);
    if (std::abs(c.norm() - spec.radius) < 1e-12 &&
        bowl.vertices.col(bowl.triangles[t][1]).norm() < spec.radius + 1e-12) {
      facing_in += bowl.normals.col(long(t)).dot(-c) > 0;
    }
  }
  EXPECT_GE(facing_in, 2 * spec.rings * spec.segments - spec.segments);
}

TEST(RigidBodiesTest, GeneratorIsReproducibleAndWithinItsRanges) {
  const Scene scene = smallBowlScene(1.0);
  const std::vector<BodySpec> a = sceneBodies(*scene.rigid_bodies);
  const std::vector<BodySpec> b = sceneBodies(*scene.rigid_bodies);
  ASSERT_EQ(a.size(), 5u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].shape.radii, b[i].shape.radii);
    EXPECT_EQ(a[i].shape.rotation_deg, b[i].shape.rotation_deg);
    EXPECT_GE(a[i].shape.radii.minCoeff(), 0.25);
    EXPECT_LE(a[i].shape.radii.maxCoeff(), 0.3);
    for (double eps : {a[i].shape.eps1, a[i].shape.eps2}) {
      EXPECT_GE(eps, 0.3);
      EXPECT_LE(eps, 1.7);
    }
    EXPECT_NEAR(a[i].shape.position[2], 0.2 + 0.7 * double(i), 1e-12);
  }
}

}  // namespace
}  // namespace fse_sim
