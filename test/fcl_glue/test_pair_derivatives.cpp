// The gradient of a pair's signed distance (pair_derivatives.h) against central finite
// differences of an independent truth: the signed distance as the optimum over directions of
// the two support functions (test_support/pair_construction.h, referenceDepth: long double,
// FCL's shapes in closed form, the superellipsoid's nested norm written there), recomputed for
// each moved pose or changed parameter. The flag against configurations built to have two
// shortest separating moves, and one-sided differences there.

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "benchmark_pairs.h"
#include "fcl_superellipsoid/pair_derivatives.h"
#include "pair_construction.h"
#include "polytope_depth.h"
#include "round_depth.h"

namespace fcl_superellipsoid {
namespace {

using namespace test;  // pair_construction.h
using Geometry = std::shared_ptr<fcl::CollisionGeometryd>;

Superellipsoidd superellipsoid(const RandomShape& s) {
  return Superellipsoidd(Vector3<double>(s.radii.cast<double>()), double(s.e1), double(s.e2));
}

/// A move of a pair's configuration: a world twist (ω, v) of each pose and a change of each
/// superellipsoid's (a1, a2, a3, ε1, ε2).
struct Move {
  Vector6<double> xi_s, xi_o;
  Vector5<double> theta_s, theta_o;
};

/// X moved by t times the world twist ξ = (ω, v): exp(t·ξ)·X (the rotation about the origin).
fcl::Transform3d movedPose(const fcl::Transform3d& X, const Vector6<double>& xi, double t) {
  const Eigen::Vector3d omega = xi.head<3>();
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(t * omega.norm(), omega.normalized()).toRotationMatrix();
  fcl::Transform3d out = X;
  out.linear() = R * X.linear();
  out.translation() = R * X.translation() + t * xi.tail<3>();
  return out;
}

/// The shape's parameters moved by t·θ.
RandomShape movedShape(const RandomShape& s, const Vector5<double>& theta, double t) {
  RandomShape out = s;
  for (int k = 0; k < 3; ++k) out.radii[k] += LD(t * theta[k]);
  out.e1 += LD(t * theta[3]);
  out.e2 += LD(t * theta[4]);
  return out;
}

/// The gradient's terms ∂d/∂x_k·δ_k along a move.
Eigen::VectorXd termsAlong(const PairDistanceDerivatives<double>& g, const Move& move) {
  Eigen::VectorXd terms(22);
  terms << g.d_pose.cwiseProduct(move.xi_s), g.d_other_pose.cwiseProduct(move.xi_o),
      g.d_shape.cwiseProduct(move.theta_s), g.d_other_shape.cwiseProduct(move.theta_o);
  return terms;
}

/// The truth's signed distance of (shape at X_WS, other at X_WO): minus the least of
/// F(v) = h_S(v) + h_O(−v) over unit v. Where both support functions are smooth (a
/// superellipsoid, an ellipsoid, a sphere) F is too, and a pattern search from the minimiser v of
/// a nearby configuration converges (referenceDepthNear); F's kinks, where a polytope's, a
/// segment's or a rim's support changes piece, stall it, so those partners take the
/// enumerations of their pieces (polytope_depth.h, round_depth.h; a capsule is its segment
/// with the ball's radius added to the superellipsoid's support). A halfspace and a plane in
/// closed form: the shape's extreme points along the normal.
LD truthNear(const Superellipsoidd& shape, const fcl::Transform3d& X_WS,
             const fcl::CollisionGeometryd& other, const fcl::Transform3d& X_WO, const V3& v,
             int max_moves = 64) {
  const std::function<LD(const V3&)> h_s = supportFunction(shape, X_WS);
  if (auto* x = dynamic_cast<const fcl::Halfspaced*>(&other)) {
    const V3 u = X_WO.linear().cast<LD>() * x->n.cast<LD>();
    const LD c = LD(x->d) + u.dot(X_WO.translation().cast<LD>());
    return -h_s(V3(-u)) - c;  // the lowest point along u, above the boundary u·x = c
  }
  if (auto* x = dynamic_cast<const fcl::Planed*>(&other)) {
    const V3 u = X_WO.linear().cast<LD>() * x->n.cast<LD>();
    const LD c = LD(x->d) + u.dot(X_WO.translation().cast<LD>());
    return std::max(-h_s(V3(-u)) - c, c - h_s(u));  // above it, or below it
  }
  if (auto* x = dynamic_cast<const fcl::Capsuled*>(&other)) {
    const LD r = x->radius;
    const V3 axis = X_WO.linear().cast<LD>().col(2) * (LD(x->lz) / 2);
    const V3 centre = X_WO.translation().cast<LD>();
    return -polytopeDepth([&](const V3& w) { return h_s(w) + r * w.norm(); },
                          {V3(centre + axis), V3(centre - axis)});
  }
  if (dynamic_cast<const fcl::Cylinderd*>(&other) || dynamic_cast<const fcl::Coned*>(&other)) {
    return -roundDepth(h_s, other, X_WO);
  }
  const std::vector<V3> vertices = polytopeVertices(other, X_WO);
  if (!vertices.empty()) return -polytopeDepth(h_s, vertices);
  return -referenceDepthNear(h_s, supportFunction(other, X_WO), v, LD(1e-3), max_moves);
}

struct Partner {
  std::string name;
  Geometry geometry;
  const RandomShape* shape = nullptr;  // where the partner is a superellipsoid
};

/// A random partner of about `size`, of kind `kind` (0–10: the smooth ones first).
Partner randomPartner(int kind, std::mt19937& rng, LD size, RandomShape& storage) {
  std::uniform_real_distribution<double> r(0.3, 1.0);
  const double s = double(size);
  switch (kind) {
    case 0:
      storage = randomShape(rng, size, 0.2, 1.8);
      return {"superellipsoid", std::make_shared<Superellipsoidd>(superellipsoid(storage)),
              &storage};
    case 1:
      return {"ellipsoid", std::make_shared<fcl::Ellipsoidd>(s * r(rng), s * r(rng), s * r(rng))};
    case 2:
      return {"sphere", std::make_shared<fcl::Sphered>(s * r(rng))};
    case 3:
      return {"box", std::make_shared<fcl::Boxd>(s * r(rng), s * r(rng), s * r(rng))};
    case 4:
      return {"capsule", std::make_shared<fcl::Capsuled>(0.5 * s * r(rng), s * r(rng))};
    case 5:
      return {"cylinder", std::make_shared<fcl::Cylinderd>(0.5 * s * r(rng), s * r(rng))};
    case 6:
      return {"cone", std::make_shared<fcl::Coned>(0.5 * s * r(rng), s * r(rng))};
    case 7: {
      // A tetrahedron.
      auto vertices = std::make_shared<std::vector<Vector3<double>>>();
      for (int i = 0; i < 4; ++i) {
        vertices->push_back(s * Vector3<double>(r(rng) - 0.65, r(rng) - 0.65, r(rng) - 0.65));
      }
      (*vertices)[3] += s * Vector3<double>(0.3, 0.3, 0.9);
      auto faces = std::make_shared<std::vector<int>>(
          std::vector<int>{3, 0, 2, 1, 3, 0, 1, 3, 3, 1, 2, 3, 3, 2, 0, 3});
      return {"convex", std::make_shared<fcl::Convexd>(vertices, 4, faces)};
    }
    case 8:
      return {"triangle", std::make_shared<fcl::TrianglePd>(s * Vector3<double>(r(rng), 0, 0),
                                                            s * Vector3<double>(0, r(rng), 0),
                                                            s * Vector3<double>(0.1, 0.2, r(rng)))};
    case 9:  // {x : z ≤ 0} in its frame
      return {"halfspace", std::make_shared<fcl::Halfspaced>(Vector3<double>(0, 0, 1), 0.0)};
    default:
      return {"plane", std::make_shared<fcl::Planed>(Vector3<double>(0, 0, 1), 0.0)};
  }
}

/// A random pair with a partner of kind `kind` (randomPartner's), of size 10^u (u uniform in
/// [−2, 2]): the partner's centre along a random direction from the shape's, at a distance that
/// makes the pair separated or overlapping. `partner.shape` points into `storage`.
struct RandomPair {
  LD size;
  RandomShape s, storage;
  Partner partner;
  fcl::Transform3d X_WS, X_WO;
};
void drawPair(int kind, std::mt19937& rng, RandomPair& out) {
  std::uniform_real_distribution<double> gap(-0.65, 0.3), unit(-1, 1), log_size(-2, 2);
  out.size = std::pow(LD(10), LD(log_size(rng)));
  out.s = randomShape(rng, out.size, 0.2, 1.8);
  out.partner = randomPartner(kind, rng, out.size, out.storage);
  out.X_WS = pose<double>(randomRotation(rng), out.size * V3(unit(rng), unit(rng), unit(rng)));
  const V3 direction = V3(unit(rng), unit(rng), unit(rng)).normalized();
  const LD reach = (1.0 + gap(rng)) * (out.s.radii.maxCoeff() + out.size * 0.6);
  out.X_WO =
      pose<double>(randomRotation(rng), out.X_WS.translation().cast<LD>() + reach * direction);
}

/// The float twin of one of randomPartner's geometries (nullptr for a convex).
std::shared_ptr<fcl::CollisionGeometry<float>> asFloat(const fcl::CollisionGeometryd& g) {
  if (auto* x = dynamic_cast<const Superellipsoidd*>(&g)) {
    return std::make_shared<Superellipsoidf>(x->radii().cast<float>(), float(x->eps1()),
                                             float(x->eps2()));
  }
  if (auto* x = dynamic_cast<const fcl::Ellipsoidd*>(&g)) {
    return std::make_shared<fcl::Ellipsoidf>(x->radii.cast<float>());
  }
  if (auto* x = dynamic_cast<const fcl::Sphered*>(&g)) {
    return std::make_shared<fcl::Spheref>(float(x->radius));
  }
  if (auto* x = dynamic_cast<const fcl::Boxd*>(&g)) {
    return std::make_shared<fcl::Boxf>(x->side.cast<float>());
  }
  if (auto* x = dynamic_cast<const fcl::Capsuled*>(&g)) {
    return std::make_shared<fcl::Capsulef>(float(x->radius), float(x->lz));
  }
  if (auto* x = dynamic_cast<const fcl::Cylinderd*>(&g)) {
    return std::make_shared<fcl::Cylinderf>(float(x->radius), float(x->lz));
  }
  if (auto* x = dynamic_cast<const fcl::Coned*>(&g)) {
    return std::make_shared<fcl::Conef>(float(x->radius), float(x->lz));
  }
  if (auto* x = dynamic_cast<const fcl::TrianglePd*>(&g)) {
    return std::make_shared<fcl::TrianglePf>(x->a.cast<float>(), x->b.cast<float>(),
                                             x->c.cast<float>());
  }
  if (auto* x = dynamic_cast<const fcl::Halfspaced*>(&g)) {
    return std::make_shared<fcl::Halfspacef>(x->n.cast<float>(), float(x->d));
  }
  if (auto* x = dynamic_cast<const fcl::Planed*>(&g)) {
    return std::make_shared<fcl::Planef>(x->n.cast<float>(), float(x->d));
  }
  return nullptr;
}

/// The minimiser v of a smooth pair's F (the partner a superellipsoid, an ellipsoid or a
/// sphere), from which the moved configurations' searches start; (0, 0, 1) for the others, whose
/// truths enumerate their pieces.
V3 truthStart(const Superellipsoidd& shape, const fcl::Transform3d& X_WS,
              const fcl::CollisionGeometryd& other, const fcl::Transform3d& X_WO, bool smooth) {
  V3 v(0, 0, 1);
  if (smooth) {
    referenceDepth(supportFunction(shape, X_WS), supportFunction(other, X_WO), 20000, &v);
  }
  return v;
}

/// The gradient of (s at X_WS, partner at X_WO) against central differences of the truth along
/// `moves` random moves of the whole configuration (step 1e-5 of a move whose rotations are
/// about 1 rad, translations and radii about `size`, exponents about 0.3): each move's
/// |∇d·δ − difference| / Σ|∂d/∂x_k·δ_k| within 1e-6. Also the distance against the truth, the
/// flag clear, and a rigid motion of both moving nothing. Returns the worst relative error;
/// `overlapping` tells which side the pair was on.
double checkGradient(const RandomShape& s, const Partner& partner, const fcl::Transform3d& X_WS,
                     const fcl::Transform3d& X_WO, LD size, bool smooth, int moves,
                     std::mt19937& rng, bool& overlapping) {
  std::normal_distribution<double> normal;
  const Superellipsoidd shape = superellipsoid(s);
  const PairDistanceDerivatives<double> got =
      pairDistanceDerivatives(shape, X_WS, *partner.geometry, X_WO);
  const V3 v = truthStart(shape, X_WS, *partner.geometry, X_WO, smooth);
  const LD truth = truthNear(shape, X_WS, *partner.geometry, X_WO, v);
  EXPECT_NEAR(got.distance, double(truth), 1e-8 * double(size));
  overlapping = truth < 0;
  EXPECT_TRUE(got.differentiable);
  EXPECT_EQ(got.other_is_superellipsoid, partner.shape != nullptr);
  if (partner.shape == nullptr) EXPECT_EQ(got.d_other_shape, Vector5<double>::Zero());
  // A rigid motion of both moves nothing.
  const double lever = 3 * double(size);  // the rotations' lever arm, about the world origin
  EXPECT_LE((got.d_pose + got.d_other_pose).norm(), 1e-8 * lever);

  double worst = 0;
  for (int m = 0; m < moves; ++m) {
    Move move;
    for (int k = 0; k < 3; ++k) {
      move.xi_s[k] = normal(rng);
      move.xi_o[k] = normal(rng);
      move.xi_s[k + 3] = double(size) * normal(rng);
      move.xi_o[k + 3] = double(size) * normal(rng);
      move.theta_s[k] = 0.3 * double(size) * normal(rng);
      move.theta_o[k] = 0.3 * double(size) * normal(rng);
    }
    for (int k = 3; k < 5; ++k) {
      move.theta_s[k] = 0.3 * normal(rng);
      move.theta_o[k] = 0.3 * normal(rng);
    }
    const double t = 1e-5;
    auto at = [&](double step) {
      const Superellipsoidd moved_shape = superellipsoid(movedShape(s, move.theta_s, step));
      const fcl::Transform3d X_S = movedPose(X_WS, move.xi_s, step);
      const fcl::Transform3d X_O = movedPose(X_WO, move.xi_o, step);
      if (partner.shape != nullptr) {
        const Superellipsoidd moved_other =
            superellipsoid(movedShape(*partner.shape, move.theta_o, step));
        return truthNear(moved_shape, X_S, moved_other, X_O, v);
      }
      return truthNear(moved_shape, X_S, *partner.geometry, X_O, v);
    };
    const double difference = double((at(t) - at(-t)) / (2 * t));
    const Eigen::VectorXd terms = termsAlong(got, move);
    const double error = std::abs(terms.sum() - difference) / terms.cwiseAbs().sum();
    EXPECT_LE(error, 1e-6) << "move " << m << ": gradient " << terms.sum() << ", difference "
                           << difference << "; terms " << terms.transpose();
    worst = std::max(worst, error);
  }
  return worst;
}

// The gradient against central differences of the truth along random moves of the whole
// configuration (both poses' twists, both superellipsoids' parameters at once; two per pair:
// checkGradient), on random pairs of every kind, separated and overlapping, with sizes from
// 0.01 to 100. (A move of every component at once reaches every component of the gradient; the
// truth of the flat-faced partners, an enumeration of their pieces, costs too much for a
// difference per component.)
TEST(PairDerivatives, GradientsMatchFiniteDifferencesOfTheTruth) {
  std::mt19937 rng(53);
  double worst = 0;
  int separated = 0, overlapping = 0;
  // Six pairs of each kind, three of a box and of a tetrahedron (whose truth, an enumeration of
  // every vertex triple and pair, costs the most).
  std::vector<int> kinds;
  for (int round = 0; round < 6; ++round) {
    for (int kind = 0; kind < 11; ++kind) {
      if (round < 3 || (kind != 3 && kind != 7)) kinds.push_back(kind);
    }
  }
  for (std::size_t trial = 0; trial < kinds.size(); ++trial) {
    const int kind = kinds[trial];
    RandomPair pair;
    drawPair(kind, rng, pair);
    SCOPED_TRACE(testing::Message() << "trial " << trial << ", " << pair.partner.name << ", size "
                                    << double(pair.size));
    bool overlap = false;
    worst = std::max(worst, checkGradient(pair.s, pair.partner, pair.X_WS, pair.X_WO, pair.size,
                                          kind <= 2, 2, rng, overlap));
    (overlap ? overlapping : separated)++;
  }
  EXPECT_GT(separated, 15);
  EXPECT_GT(overlapping, 15);
  RecordProperty("worst_relative_error", testing::PrintToString(worst));
  std::printf("pair gradients: worst relative error %g (%d separated, %d overlapping)\n", worst,
              separated, overlapping);
}

/// The benchmark's configurations (test_support/benchmark_pairs.h) as the checks take them: its
/// body and superellipsoid partner as RandomShapes, and each of its five partners with the 64
/// poses of the body about it (the superellipsoid partner's `shape` points into `other`).
struct BenchmarkConfigurations {
  struct Partnered {
    Partner partner;
    bool smooth;  // the truth searches from a minimiser (truthStart)
    std::vector<fcl::Transform3d> poses;
  };
  RandomShape body, other;
  std::vector<Partnered> partners;

  static std::unique_ptr<const BenchmarkConfigurations> make() {
    auto out = std::make_unique<BenchmarkConfigurations>();
    const double *b = kBenchmarkBody, *o = kBenchmarkSuperellipsoidPartner;
    out->body = {V3(b[0], b[1], b[2]), b[3], b[4]};
    out->other = {V3(o[0], o[1], o[2]), o[3], o[4]};
    for (const BenchmarkPartner kind : kBenchmarkPartners) {
      const bool is_superellipsoid = kind == BenchmarkPartner::kSuperellipsoid;
      Partner partner{partnerName(kind), benchmarkPartner(kind),
                      is_superellipsoid ? &out->other : nullptr};
      std::vector<fcl::Transform3d> poses =
          benchmarkPoses(superellipsoid(out->body), *partner.geometry);
      out->partners.push_back({std::move(partner),
                               is_superellipsoid || kind == BenchmarkPartner::kEllipsoid,
                               std::move(poses)});
    }
    return out;
  }
};

// The same on the configurations the benchmark times (test_support/benchmark_pairs.h: a
// rounded box-like body about a superellipsoid, an ellipsoid, a box, a capsule and a cylinder),
// an eighth of its 64 poses each, one move each.
TEST(PairDerivatives, GradientsOnTheBenchmarksPairs) {
  std::mt19937 rng(57);
  const auto configurations = BenchmarkConfigurations::make();
  const RandomShape& body = configurations->body;
  double worst = 0;
  int separated = 0, overlapping = 0;
  for (const BenchmarkConfigurations::Partnered& entry : configurations->partners) {
    const Partner& partner = entry.partner;
    const std::vector<fcl::Transform3d>& poses = entry.poses;
    const bool smooth = entry.smooth;
    for (std::size_t i = 0; i < poses.size(); i += 8) {
      SCOPED_TRACE(testing::Message() << partner.name << ", pose " << i);
      bool overlap = false;
      worst = std::max(worst, checkGradient(body, partner, poses[i], fcl::Transform3d::Identity(),
                                            LD(body.radii.maxCoeff()), smooth, 1, rng, overlap));
      (overlap ? overlapping : separated)++;
    }
  }
  EXPECT_GE(separated, 10);
  EXPECT_GE(overlapping, 10);
  RecordProperty("worst_relative_error", testing::PrintToString(worst));
  std::printf(
      "pair gradients on the benchmark's pairs: worst relative error %g (%d separated, "
      "%d overlapping)\n",
      worst, separated, overlapping);
}

/// The truth's normal and witnesses of (shape at X_WS, other at X_WO), from its signed distance
/// alone: n = ∂d/∂v_O and ∂d/∂ω_S = n × N_S (central differences, steps h of length and
/// `angle` of rotation), so
/// N_S = (∂d/∂ω_S) × n + h_S(n)·n with the shape's support function h_S, and N_O = N_S + d·n.
/// The smooth partners' searches may take many moves along a narrow valley of F (kPatient).
constexpr int kPatient = 100000;
struct TruthWitnesses {
  V3 normal, on_shape, on_other;
};
TruthWitnesses truthWitnesses(const Superellipsoidd& shape, const fcl::Transform3d& X_WS,
                              const fcl::CollisionGeometryd& other, const fcl::Transform3d& X_WO,
                              const V3& v, double h, double angle) {
  V3 n, rotation;
  for (int k = 0; k < 3; ++k) {
    Vector6<double> xi = Vector6<double>::Zero();
    xi[k + 3] = 1;  // the other geometry moved along axis k
    n[k] = (truthNear(shape, X_WS, other, movedPose(X_WO, xi, h), v, kPatient) -
            truthNear(shape, X_WS, other, movedPose(X_WO, xi, -h), v, kPatient)) /
           (2 * h);
    xi.setZero();
    xi[k] = 1;  // the superellipsoid turned about axis k
    rotation[k] = (truthNear(shape, movedPose(X_WS, xi, angle), other, X_WO, v, kPatient) -
                   truthNear(shape, movedPose(X_WS, xi, -angle), other, X_WO, v, kPatient)) /
                  (2 * angle);
  }
  n.normalize();
  const V3 on_shape = rotation.cross(n) + supportFunction(shape, X_WS)(n) * n;
  const LD d = truthNear(shape, X_WS, other, X_WO, v, kPatient);
  return {n, on_shape, V3(on_shape + d * n)};
}

/// Whether a superellipsoid's witness along the unit direction n (world) is where its support
/// map is too bent for a difference of step `step` rad to measure its Jacobian: beside a
/// coordinate plane of directions, for an exponent below 1 (a box-like face or edge: the support
/// point moves as a power below 1 of the direction's component, its Jacobian unbounded at 0).
/// A central difference of the power p is off by about (step/m)²·(1 − p)(2 − p)/6 at the
/// component m, so it takes m ≥ 500 steps for 1e-6.
bool tooBentForDifferences(const RandomShape& s, const fcl::Transform3d& X, const V3& n,
                           double step) {
  if (std::min(s.e1, s.e2) >= 1) return false;
  const V3 m = X.linear().cast<LD>().transpose() * n;
  return m.cwiseAbs().minCoeff() < 500 * step;
}

/// What checkJacobians found: whether the pair was checked (not too bent), on which side.
struct JacobianCheck {
  bool checked = false, overlapping = false;
  double worst = 0;
};

/// The Jacobians of the witnesses and of the normal (DerivativeOrder::kJacobians) of (s at
/// X_WS, partner at X_WO) against central differences of the truth's witnesses and normal
/// (truthWitnesses: differences of its signed distance, nested) along a random move of both
/// poses: |J·δ − difference| within 1e-6 of Σ‖J_k‖·|δ_k| for each of the three. Also the same
/// twist of both poses moving the witnesses and the normal rigidly with it. Pairs where a
/// superellipsoid's support map is too bent at the difference's step are left to that rigid
/// motion's check (tooBentForDifferences).
JacobianCheck checkJacobians(const RandomShape& s, const Partner& partner,
                             const fcl::Transform3d& X_WS, const fcl::Transform3d& X_WO, LD size,
                             bool smooth, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  JacobianCheck out;
  const Superellipsoidd shape = superellipsoid(s);
  const PairDistanceDerivatives<double> got =
      pairDistanceDerivatives(shape, X_WS, *partner.geometry, X_WO, DerivativeOrder::kJacobians);
  EXPECT_TRUE(got.has_jacobians);
  EXPECT_TRUE(got.differentiable);
  V3 v(0, 0, 1);
  if (smooth) {
    const auto h_s = supportFunction(shape, X_WS), h_o = supportFunction(*partner.geometry, X_WO);
    referenceDepth(h_s, h_o, 20000, &v);
    referenceDepthNear(h_s, h_o, v, LD(1e-3), kPatient, &v);
  }
  const double h = 1e-5;  // of the size, and in radians
  // The same twist of both poses moves the witnesses and the normal rigidly with it.
  {
    Vector6<double> xi;
    for (int k = 0; k < 6; ++k) xi[k] = (k < 3 ? 1.0 : double(size)) * normal(rng);
    const Eigen::Vector3d w = xi.head<3>(), u = xi.tail<3>();
    const double lever = 3 * double(size);
    EXPECT_LE(((got.normal_d_pose + got.normal_d_other_pose) * xi - w.cross(got.normal)).norm(),
              1e-8 * (got.normal_d_pose.norm() + got.normal_d_other_pose.norm()) * xi.norm());
    for (const auto& [J_s, J_o, p] :
         {std::tie(got.on_shape_d_pose, got.on_shape_d_other_pose, got.on_shape),
          std::tie(got.on_other_d_pose, got.on_other_d_other_pose, got.on_other)}) {
      EXPECT_LE(((J_s + J_o) * xi - (w.cross(p) + u)).norm(),
                1e-8 * (J_s.norm() + J_o.norm()) * xi.norm() + 1e-12 * lever * xi.norm());
    }
  }

  Vector6<double> xi_s, xi_o;
  for (int k = 0; k < 3; ++k) {
    xi_s[k] = normal(rng);
    xi_o[k] = normal(rng);
    xi_s[k + 3] = double(size) * normal(rng);
    xi_o[k + 3] = double(size) * normal(rng);
  }
  const double t = 3e-5;
  const TruthWitnesses plus = truthWitnesses(shape, movedPose(X_WS, xi_s, t), *partner.geometry,
                                             movedPose(X_WO, xi_o, t), v, h * double(size), h);
  const TruthWitnesses minus = truthWitnesses(shape, movedPose(X_WS, xi_s, -t), *partner.geometry,
                                              movedPose(X_WO, xi_o, -t), v, h * double(size), h);
  // Where a superellipsoid's support map is too bent at the difference's step, the truth
  // cannot measure the Jacobian (the rigid motion above still checks it).
  const V3 n_truth = ((plus.normal + minus.normal) / 2).normalized();
  const double step = t * (xi_s.head<3>().norm() + xi_o.head<3>().norm() +
                           (xi_s.tail<3>().norm() + xi_o.tail<3>().norm()) / double(size));
  if (tooBentForDifferences(s, X_WS, n_truth, step) ||
      (partner.shape != nullptr &&
       tooBentForDifferences(*partner.shape, X_WO, V3(-n_truth), step))) {
    return out;
  }
  out.checked = true;
  out.overlapping = got.distance < 0;
  // The truth where the library answered: the mean of the two, to second order in t.
  EXPECT_LE(((plus.normal + minus.normal) / 2 - got.normal.cast<LD>()).norm(), LD(1e-7));
  EXPECT_LE(((plus.on_shape + minus.on_shape) / 2 - got.on_shape.cast<LD>()).norm(),
            LD(1e-6) * size);
  const auto check = [&](const char* what, const Eigen::Matrix<double, 3, 6>& J_s,
                         const Eigen::Matrix<double, 3, 6>& J_o, const V3& p, const V3& m) {
    const Eigen::Vector3d predicted = J_s * xi_s + J_o * xi_o;
    const Eigen::Vector3d difference = ((p - m) / (2 * t)).cast<double>();
    double scale = 1e-12 * double(size);
    for (int k = 0; k < 6; ++k) {
      scale += J_s.col(k).norm() * std::abs(xi_s[k]) + J_o.col(k).norm() * std::abs(xi_o[k]);
    }
    const double error = (predicted - difference).norm() / scale;
    EXPECT_LE(error, 1e-6) << what << ": predicted " << predicted.transpose() << ", difference "
                           << difference.transpose();
    out.worst = std::max(out.worst, error);
  };
  check("normal", got.normal_d_pose, got.normal_d_other_pose, plus.normal, minus.normal);
  check("on_shape", got.on_shape_d_pose, got.on_shape_d_other_pose, plus.on_shape, minus.on_shape);
  check("on_other", got.on_other_d_pose, got.on_other_d_other_pose, plus.on_other, minus.on_other);
  return out;
}

// checkJacobians on random pairs of every kind, separated and overlapping, sizes 0.01–100:
// three pairs of each kind, one of a box and of a tetrahedron (whose truths cost the most):
// each move costs 26 evaluations of the truth.
TEST(PairDerivatives, JacobiansMatchFiniteDifferencesOfTheTruth) {
  std::mt19937 rng(56);
  double worst = 0;
  int separated = 0, overlapping = 0, bent = 0;
  for (int trial = 0; trial < 33; ++trial) {
    const int kind = trial % 11;
    if (trial >= 11 && (kind == 3 || kind == 7)) continue;  // a box's and a tetrahedron's truth
    RandomPair pair;
    drawPair(kind, rng, pair);
    SCOPED_TRACE(testing::Message() << "trial " << trial << ", " << pair.partner.name << ", size "
                                    << double(pair.size));
    const JacobianCheck c =
        checkJacobians(pair.s, pair.partner, pair.X_WS, pair.X_WO, pair.size, kind <= 2, rng);
    if (!c.checked) {
      ++bent;
      continue;
    }
    (c.overlapping ? overlapping : separated)++;
    worst = std::max(worst, c.worst);
  }
  EXPECT_GT(separated, 5);
  EXPECT_GT(overlapping, 5);
  RecordProperty("worst_relative_error", testing::PrintToString(worst));
  std::printf(
      "pair Jacobians: worst relative error %g (%d separated, %d overlapping, %d too bent)\n",
      worst, separated, overlapping, bent);
}

// checkJacobians on the configurations the benchmark times (test_support/benchmark_pairs.h),
// four of its 64 poses about each partner (each costs 26 evaluations of the truth).
TEST(PairDerivatives, JacobiansOnTheBenchmarksPairs) {
  std::mt19937 rng(58);
  const auto configurations = BenchmarkConfigurations::make();
  const RandomShape& body = configurations->body;
  double worst = 0;
  int separated = 0, overlapping = 0, bent = 0;
  for (const BenchmarkConfigurations::Partnered& entry : configurations->partners) {
    const Partner& partner = entry.partner;
    const std::vector<fcl::Transform3d>& poses = entry.poses;
    const bool smooth = entry.smooth;
    for (std::size_t i = 1; i < poses.size(); i += 16) {
      SCOPED_TRACE(testing::Message() << partner.name << ", pose " << i);
      const JacobianCheck c = checkJacobians(body, partner, poses[i], fcl::Transform3d::Identity(),
                                             LD(body.radii.maxCoeff()), smooth, rng);
      if (!c.checked) {
        ++bent;
        continue;
      }
      (c.overlapping ? overlapping : separated)++;
      worst = std::max(worst, c.worst);
    }
  }
  // About half of them have a witness where the body's support map is too bent for the
  // differences (its ε1 = 0.6): at least 8 of the 20 are measured.
  EXPECT_GE(separated + overlapping, 8);
  RecordProperty("worst_relative_error", testing::PrintToString(worst));
  std::printf(
      "pair Jacobians on the benchmark's pairs: worst relative error %g (%d separated, %d "
      "overlapping, %d too bent)\n",
      worst, separated, overlapping, bent);
}

// Two shortest separating moves: coincident centres of the superellipsoid and a centrally
// symmetric partner (another superellipsoid, a sphere, a box, a capsule; rotated at random),
// where −n separates them as well as n, and a plane through the shape's centre (straddled by
// equal depths). The flag is set, the gradient is finite and it is that of the returned
// direction: moving the partner along n raises the distance at rate 1, the truth's one-sided
// difference. Moved off the centre by 1e-2 of the size, the same pairs are differentiable.
TEST(PairDerivatives, TwoShortestSeparatingMovesAreFlagged) {
  std::mt19937 rng(54);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    const int kind = std::array<int, 5>{0, 2, 3, 4, 10}[trial % 5];
    const RandomShape s = randomShape(rng, 1, 0.2, 1.8);
    RandomShape storage;
    const Partner partner = randomPartner(kind, rng, 1, storage);
    const Superellipsoidd shape = superellipsoid(s);
    const V3 centre(unit(rng), unit(rng), unit(rng));
    const fcl::Transform3d X_WS = pose<double>(randomRotation(rng), centre);
    const fcl::Transform3d X_WO = pose<double>(randomRotation(rng), centre);
    SCOPED_TRACE(testing::Message() << "trial " << trial << ", " << partner.name);
    const PairDistanceDerivatives<double> g =
        pairDistanceDerivatives(shape, X_WS, *partner.geometry, X_WO);
    EXPECT_LT(g.distance, 0);
    EXPECT_FALSE(g.differentiable);
    ASSERT_TRUE(g.d_pose.allFinite() && g.d_other_pose.allFinite() && g.d_shape.allFinite());
    EXPECT_LE((g.d_other_pose.tail<3>() - g.normal).norm(), 1e-12);
    // One-sided: the partner moved along n by t.
    const double t = 1e-6;
    fcl::Transform3d moved = X_WO;
    moved.translation() += t * g.normal;
    V3 v = g.normal.cast<LD>();
    const LD before = truthNear(shape, X_WS, *partner.geometry, X_WO, v);
    const LD after = truthNear(shape, X_WS, *partner.geometry, moved, v);
    EXPECT_NEAR(g.distance, double(before), 1e-9);
    EXPECT_NEAR(double((after - before) / t), 1.0, 1e-6);
    // Off the centre (not for the plane: any plane through the shape straddles it).
    if (kind == 10) continue;
    fcl::Transform3d off = X_WO;
    off.translation() += 1e-2 * Vector3<double>(unit(rng), unit(rng), unit(rng)).normalized();
    EXPECT_TRUE(pairDistanceDerivatives(shape, X_WS, *partner.geometry, off).differentiable);
  }
}

// Float against double on random pairs of every kind: the same distance, normal and gradient
// to float's precision (1e-3 of the size or of the gradient's scale: a float pair's witnesses
// carry that; ShapePairs.FloatAgreesWithDouble), and the same flag; float's Jacobians finite.
TEST(PairDerivatives, FloatAgreesWithDouble) {
  std::mt19937 rng(55);
  std::uniform_real_distribution<double> gap(-0.65, 0.3), unit(-1, 1);
  for (int trial = 0; trial < 44; ++trial) {
    const int kind = trial % 11;
    if (kind == 7) continue;  // fcl::Convex's float form takes its own vertex list
    const RandomShape s = randomShape(rng, 1, 0.2, 1.8);
    RandomShape storage;
    const Partner partner = randomPartner(kind, rng, 1, storage);
    const Superellipsoidd shape = superellipsoid(s);
    const fcl::Transform3d X_WS = pose<double>(randomRotation(rng), V3(unit(rng), unit(rng), 0));
    const V3 direction = V3(unit(rng), unit(rng), unit(rng)).normalized();
    const LD reach = (1.0 + gap(rng)) * (s.radii.maxCoeff() + 0.6);
    const fcl::Transform3d X_WO =
        pose<double>(randomRotation(rng), X_WS.translation().cast<LD>() + reach * direction);
    SCOPED_TRACE(testing::Message() << "trial " << trial << ", " << partner.name);
    const PairDistanceDerivatives<double> d =
        pairDistanceDerivatives(shape, X_WS, *partner.geometry, X_WO);
    const std::shared_ptr<fcl::CollisionGeometry<float>> other = asFloat(*partner.geometry);
    ASSERT_NE(other, nullptr);
    const PairDistanceDerivatives<float> f = pairDistanceDerivatives(
        Superellipsoidf(shape.radii().cast<float>(), float(shape.eps1()), float(shape.eps2())),
        fcl::Transform3f(X_WS.cast<float>()), *other, fcl::Transform3f(X_WO.cast<float>()),
        DerivativeOrder::kJacobians);
    EXPECT_TRUE(f.has_jacobians);
    EXPECT_TRUE(f.normal_d_pose.allFinite() && f.normal_d_other_pose.allFinite() &&
                f.on_shape_d_pose.allFinite() && f.on_shape_d_other_pose.allFinite() &&
                f.on_other_d_pose.allFinite() && f.on_other_d_other_pose.allFinite());
    EXPECT_NEAR(f.distance, d.distance, 1e-3);
    EXPECT_LE((f.normal.cast<double>() - d.normal).norm(), 1e-3);
    const double scale = 1 + d.d_pose.norm() + d.d_other_pose.norm();
    EXPECT_LE((f.d_pose.cast<double>() - d.d_pose).norm(), 1e-3 * scale);
    EXPECT_LE((f.d_other_pose.cast<double>() - d.d_other_pose).norm(), 1e-3 * scale);
    EXPECT_LE((f.d_shape.cast<double>() - d.d_shape).norm(), 1e-3 * (1 + d.d_shape.norm()));
    EXPECT_EQ(f.differentiable, d.differentiable);
  }
}

}  // namespace
}  // namespace fcl_superellipsoid
