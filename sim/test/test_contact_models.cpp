// The contact models against the exact surface: each finds the vertices within the margin
// with the right sign; the mesh model's pseudonormal sign is right inside and outside, and
// its distances are off by no more than the tessellation's chords.

#include <fcl_superellipsoid/point_distance.h>
#include <gtest/gtest.h>

#include <random>

#include "contact/cloth_contact.h"

namespace fse_sim {
namespace {

namespace fse = fcl_superellipsoid;

/// A small version of the paper's cloth shape (1.2, 1.0, 0.7; 0.4, 0.3), posed off the axes.
ShapeSpec posedShape() {
  ShapeSpec s;
  s.radii = Eigen::Vector3d(1.2, 1.0, 0.7);
  s.eps1 = 0.4;
  s.eps2 = 0.3;
  s.position = Eigen::Vector3d(0.3, -0.2, 0.5);
  s.rotation_deg = Eigen::Vector3d(20, -35, 60);
  return s;
}

/// Points around the posed shape at signed distances in [−0.3, 0.3] × size, by construction:
/// a surface point stepped along its normal.
Eigen::Matrix3Xd pointsAround(const ShapeSpec& spec, std::vector<double>& distance, int n) {
  const fse::Superellipsoidd shape = makeShape(spec);
  const Eigen::Isometry3d X = shapePose(spec);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), depth(-0.3, 0.3);
  Eigen::Matrix3Xd p(3, n);
  distance.clear();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d s = shape.surfacePoint(angle(rng) / 2, angle(rng));
    const Eigen::Vector3d normal = shape.normal(s);
    // Inside, only as deep as the surface point's own nearest-point region reaches safely.
    const double d = depth(rng) * (depth(rng) < 0 ? 0.2 : 1.0);
    const Eigen::Vector3d q = s + d * normal;
    // The true distance from the exact solver's independent construction: for d ≥ 0 it is d;
    // inside we take the Exact solver's answer only as the sign reference.
    p.col(i) = X * q;
    distance.push_back(d >= 0 ? d : fse::pointDistance(shape, q).distance);
  }
  return p;
}

void checkModel(ContactModel model, double distance_tolerance) {
  const ShapeSpec spec = posedShape();
  std::vector<double> truth;
  const Eigen::Matrix3Xd p = pointsAround(spec, truth, 400);
  SimulationOptions options;
  options.model = model;
  auto detector = makeContactDetector(spec, 0, int(p.cols()), options);
  std::vector<ContactCandidate> found;
  const double margin = 0.1;
  detector->detect(p, margin, found);
  std::vector<bool> seen(p.cols(), false);
  for (const ContactCandidate& c : found) {
    SCOPED_TRACE(c.vertex);
    seen[c.vertex] = true;
    EXPECT_NEAR(c.distance, truth[c.vertex], distance_tolerance);
    EXPECT_NEAR(c.normal.norm(), 1, 1e-9);
    // The plane through the contact point holds the vertex on the right side of it.
    EXPECT_NEAR(c.normal.dot(p.col(c.vertex) - c.point), c.distance, distance_tolerance);
  }
  for (Eigen::Index i = 0; i < p.cols(); ++i) {
    if (truth[i] < margin - distance_tolerance) EXPECT_TRUE(seen[i]) << "missed vertex " << i;
  }
}

TEST(ContactModelsTest, ExactFindsEveryVertexWithinTheMargin) {
  checkModel(ContactModel::kExact, 1e-9);
}

TEST(ContactModelsTest, PaperIsThePapersMethodAtItsCaseStudySettings) {
  // The paper's method at 10 iterations is not accurate deep inside a creased shape (off by
  // up to 0.1 m here, and differently with another compiler's rounding: it stops wherever its
  // iterations end), so what is asserted is what the model is: each candidate is the
  // library's single query with the paper's settings (absolute tolerance 1e-3, 10
  // iterations), and its sign is right away from the surface. Its accuracy in the scene is
  // measured and reported (docs/scenes.md), not assumed.
  const ShapeSpec spec = posedShape();
  std::vector<double> truth;
  const Eigen::Matrix3Xd p = pointsAround(spec, truth, 400);
  SimulationOptions options;
  options.model = ContactModel::kPaper;
  auto detector = makeContactDetector(spec, 0, int(p.cols()), options);
  std::vector<ContactCandidate> found;
  detector->detect(p, 0.1, found);
  const fse::Superellipsoidd shape = makeShape(spec);
  const fcl::Transform3d X_WS = shapeTransform(spec);
  fse::DistanceOptions<double> paper{fse::DistanceMethod::kPaper, 1e-3 / shape.size(), 10};
  ASSERT_GT(found.size(), 100u);
  for (const ContactCandidate& c : found) {
    SCOPED_TRACE(c.vertex);
    const auto single = fse::pointDistance(shape, X_WS, Eigen::Vector3d(p.col(c.vertex)), paper);
    EXPECT_NEAR(c.distance, single.distance, 1e-12);
    EXPECT_LE((c.point - single.nearest_point).norm(), 1e-12);
    if (std::abs(truth[c.vertex]) > 0.01) EXPECT_EQ(c.distance < 0, truth[c.vertex] < 0);
  }
}

TEST(ContactModelsTest, MeshSignIsRightAndDistanceWithinTheChords) {
  // 702 vertices on a 1.2 × 1.0 × 0.7 shape with rounded-box creases: facets lie up to a few
  // centimetres inside the surface at the creases (the sagitta of the chords).
  checkModel(ContactModel::kMesh, 0.06);
}

}  // namespace
}  // namespace fse_sim
