#include "pairs.h"

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConeShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/CollisionShapes/btTriangleShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "bt_superellipsoid_shape.h"
#include "fcl_superellipsoid/diagnostics.h"
#include "fcl_superellipsoid/fcl_integration.h"
#include "pair_construction.h"

namespace fcl_superellipsoid {
namespace bench {
namespace {

using namespace test;  // pair_construction.h
using Clock = std::chrono::steady_clock;

/// The partner kinds, in the order their pairs are drawn.
const std::vector<std::string> kPairKinds = {"superellipsoid", "ellipsoid", "sphere", "box",
                                             "capsule",        "cylinder",  "cone",   "convex",
                                             "triangle",       "halfspace", "plane"};

/// The separations of the buckets, × the superellipsoid's size (Coal's protocol: −0.1 … 1).
constexpr double kBuckets[] = {-0.1, -0.01, 0.001, 0.01, 0.1, 1.0};
/// Timed passes over each bucket's pairs; the time is the mean of the fastest kKept of them
/// (Coal's protocol: the mean of the fastest 90 % of repeats).
constexpr int kRepetitions = 10;
constexpr int kKept = 9;

/// One configuration: the superellipsoid, the partner, their poses, the constructed distance
/// (for d ≥ 0 the true distance; for d < 0 an overlap along the construction's normal).
struct Case {
  std::shared_ptr<Superellipsoidd> shape;
  fcl::Transform3d X_WA;
  std::shared_ptr<fcl::CollisionGeometryd> other;
  fcl::Transform3d X_WB;
  double d;
  double size;
  int bucket;
  std::shared_ptr<btConvexShape> bt_shape, bt_other;  // null: no Bullet peer for the partner
};

std::shared_ptr<Superellipsoidd> makeShape(const RandomShape& s) {
  return std::make_shared<Superellipsoidd>(Vector3<double>(s.radii.cast<double>()), double(s.e1),
                                           double(s.e2));
}

template <typename T>
std::shared_ptr<btConvexShape> noMargin(std::shared_ptr<T> s) {
  s->setMargin(0);
  return s;
}

/// The Bullet twin of an FCL geometry with the same surface, or null.
std::shared_ptr<btConvexShape> bulletTwin(const fcl::CollisionGeometryd* g) {
  if (auto* x = dynamic_cast<const Superellipsoidd*>(g)) {
    return std::make_shared<support::BtSuperellipsoidShape>(*x);
  }
  if (auto* x = dynamic_cast<const fcl::Ellipsoidd*>(g)) {
    static std::vector<std::unique_ptr<Superellipsoidd>> keep;  // the twins' shapes live on
    keep.push_back(std::make_unique<Superellipsoidd>(x->radii, 1.0, 1.0));
    return std::make_shared<support::BtSuperellipsoidShape>(*keep.back());
  }
  if (auto* x = dynamic_cast<const fcl::Sphered*>(g)) {
    return std::make_shared<btSphereShape>(btScalar(x->radius));
  }
  if (auto* x = dynamic_cast<const fcl::Boxd*>(g)) {
    return noMargin(std::make_shared<btBoxShape>(support::toBt(x->side / 2)));
  }
  if (auto* x = dynamic_cast<const fcl::Capsuled*>(g)) {
    return std::make_shared<btCapsuleShapeZ>(btScalar(x->radius), btScalar(x->lz));
  }
  if (auto* x = dynamic_cast<const fcl::Cylinderd*>(g)) {
    return noMargin(std::make_shared<btCylinderShapeZ>(
        btVector3(btScalar(x->radius), btScalar(x->radius), btScalar(x->lz / 2))));
  }
  if (auto* x = dynamic_cast<const fcl::Coned*>(g)) {
    return noMargin(std::make_shared<btConeShapeZ>(btScalar(x->radius), btScalar(x->lz)));
  }
  if (auto* x = dynamic_cast<const fcl::Convexd*>(g)) {
    auto hull = std::make_shared<btConvexHullShape>();
    for (const auto& v : x->getVertices()) hull->addPoint(support::toBt(v));
    return noMargin(hull);
  }
  if (auto* x = dynamic_cast<const fcl::TrianglePd*>(g)) {
    return noMargin(std::make_shared<btTriangleShape>(support::toBt(x->a), support::toBt(x->b),
                                                      support::toBt(x->c)));
  }
  return nullptr;
}

/// `count` cases of one partner kind, the buckets in turn.
std::vector<Case> makeCases(const std::string& kind, int count, std::mt19937& rng) {
  std::vector<Case> cases;
  std::uniform_real_distribution<double> size(0.5, 5.0);
  for (int i = 0; i < count; ++i) {
    const int bucket = i % int(std::size(kBuckets));
    const LD scale = LD(size(rng));
    const Construction c = constructShape(rng, scale);
    const double shape_size = double(c.shape.radii.maxCoeff());
    const LD d = LD(kBuckets[bucket]) * shape_size;
    Case k{makeShape(c.shape),
           c.X_WA,
           nullptr,
           fcl::Transform3d::Identity(),
           double(d),
           shape_size,
           bucket,
           nullptr,
           nullptr};
    if (kind == "superellipsoid" || kind == "ellipsoid") {
      RandomShape partner = randomShape(rng, scale);
      if (kind == "ellipsoid") partner.e1 = partner.e2 = 1;
      const SurfacePoint b = randomSurfacePoint(partner, rng);
      k.X_WB = placePartner(c, d, b.x, b.n, rng);
      k.other = kind == "ellipsoid"
                    ? std::shared_ptr<fcl::CollisionGeometryd>(std::make_shared<fcl::Ellipsoidd>(
                          Vector3<double>(partner.radii.cast<double>())))
                    : makeShape(partner);
    } else if (kind == "sphere") {
      std::normal_distribution<double> g;
      const V3 m = V3(LD(g(rng)), LD(g(rng)), LD(g(rng))).normalized();
      const LD radius = scale * LD(0.5);
      k.X_WB = placePartner(c, d, radius * m, m, rng);
      k.other = std::make_shared<fcl::Sphered>(double(radius));
    } else if (kind == "halfspace" || kind == "plane") {
      const Vector3<double> n = -c.u.cast<double>();
      const double offset = double(-(c.u.dot(c.a) + d));
      if (kind == "halfspace") {
        k.other = std::make_shared<fcl::Halfspaced>(n, offset);
      } else {
        k.other = std::make_shared<fcl::Planed>(n, offset);
      }
    } else {
      // box, capsule, cylinder, cone, convex, triangle: any of pair_construction.h's features
      std::vector<FlatPartner> options;
      for (FlatPartner& p : flatPartners(rng, scale)) {
        if (std::string(p.name).rfind(kind, 0) == 0) options.push_back(std::move(p));
      }
      const FlatPartner& p = options[std::size_t(i / int(std::size(kBuckets))) % options.size()];
      k.X_WB = placePartner(c, d, p.b_L, p.m_L, rng);
      k.other = p.geometry;
    }
    k.bt_other = bulletTwin(k.other.get());
    if (k.bt_other) k.bt_shape = bulletTwin(k.shape.get());
    cases.push_back(std::move(k));
  }
  return cases;
}

/// A method's answer: the signed distance, or NaN where it has none.
using Query = std::function<double(const Case&)>;

double ours(const Case& k) {
  fcl::DistanceRequestd request(true, true);
  fcl::DistanceResultd result;
  return fcl_superellipsoid::distance(k.shape.get(), k.X_WA, k.other.get(), k.X_WB, request,
                                      result);
}

/// FCL's GJKSolver_libccd on the concrete types, with the exact support (gjk_support.h).
double libccd(const Case& k) {
  static const fcl::detail::GJKSolver_libccd<double> solver;
  double d = NAN;
  Vector3<double> p1, p2;
  auto run = [&](const auto& other) {
    try {
      solver.shapeSignedDistance(*k.shape, k.X_WA, other, k.X_WB, &d, &p1, &p2);
    } catch (const std::exception&) {
      d = NAN;  // counted as a failure
    }
  };
  const fcl::CollisionGeometryd* g = k.other.get();
  if (auto* x = dynamic_cast<const Superellipsoidd*>(g))
    run(*x);
  else if (auto* x = dynamic_cast<const fcl::Ellipsoidd*>(g))
    run(*x);
  else if (auto* x = dynamic_cast<const fcl::Sphered*>(g))
    run(*x);
  else if (auto* x = dynamic_cast<const fcl::Boxd*>(g))
    run(*x);
  else if (auto* x = dynamic_cast<const fcl::Capsuled*>(g))
    run(*x);
  else if (auto* x = dynamic_cast<const fcl::Cylinderd*>(g))
    run(*x);
  else if (auto* x = dynamic_cast<const fcl::Coned*>(g))
    run(*x);
  else if (auto* x = dynamic_cast<const fcl::Convexd*>(g))
    run(*x);
  return d;
}

btTransform toBt(const fcl::Transform3d& X) {
  btMatrix3x3 R;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R[i][j] = btScalar(X.linear()(i, j));
  }
  return btTransform(R, support::toBt(X.translation()));
}

double bullet(const Case& k) {
  btGjkEpaSolver2::sResults result;
  const btVector3 guess = support::toBt(k.X_WB.translation() - k.X_WA.translation());
  if (!btGjkEpaSolver2::SignedDistance(k.bt_shape.get(), toBt(k.X_WA), k.bt_other.get(),
                                       toBt(k.X_WB), guess, result)) {
    return NAN;
  }
  // btGjkEpaSolver2 measures the shapes without their collision margins (Bullet's own pipeline
  // adds them); the sphere's and the capsule's radius is their margin.
  return double(result.distance) - double(k.bt_shape->getMargin()) -
         double(k.bt_other->getMargin());
}

struct Row {
  std::string kind, method;
  int bucket;
  double us;         // the mean of the fastest kKept passes, per query
  double max_error;  // × size, against the construction (separated) or ours (overlapping)
  double median_error;
  int failures;  // NaN, non-finite, exceptions
  int cases;
  double evaluations;  // the superellipsoid's support or gauge evaluations per query
};

}  // namespace

int runPairs(int per_kind, const std::string& csv, const std::vector<std::string>& only) {
  const std::vector<std::string>& kinds = kPairKinds;
  std::printf(
      "Shape pairs: the superellipsoid (ε1, ε2 in [0.1, 1.9], radii 10:1) against each kind, "
      "%d random pairs × poses per kind, built with a known separation d (test_support/"
      "pair_construction.h) in buckets d/size = -0.1, -0.01, 0.001, 0.01, 0.1, 1. Time: the "
      "mean of the fastest %d of %d passes, per query. Error × size: against the construction "
      "where separated; overlapping, against ours where ours is exact (the smooth shapes, sphere, "
      "halfspace, plane: checked against an independent reference in "
      "test/fcl_glue/test_shape_pairs.cpp); for the "
      "others ours is a search over candidate directions without an independent reference here "
      "(the tests check it is never deeper than the construction's overlap or a long-double "
      "search's), and no error is given (nan). libccd and Bullet see the exact support "
      "function.\n\n",
      per_kind, kKept, kRepetitions);
  std::mt19937 rng(2026);
  std::vector<Row> rows;
  for (const std::string& kind : kinds) {
    const std::vector<Case> cases = makeCases(kind, per_kind, rng);  // also for skipped kinds:
    // every kind draws the same pairs whichever others run
    if (!only.empty() && std::find(only.begin(), only.end(), kind) == only.end()) continue;
    // Overlapping, the reference is ours where ours is exact (the smooth shapes, the sphere and
    // the planes); for the others ours is libccd's answer, and there is no reference.
    const bool overlap_reference = kind == "superellipsoid" || kind == "ellipsoid" ||
                                   kind == "sphere" || kind == "halfspace" || kind == "plane";
    std::vector<double> reference(cases.size());
    for (std::size_t i = 0; i < cases.size(); ++i) {
      reference[i] = cases[i].d >= 0 ? cases[i].d : overlap_reference ? ours(cases[i]) : NAN;
    }
    const bool has_libccd = kind != "triangle" && kind != "halfspace" && kind != "plane";
    const bool has_bullet = cases.front().bt_other != nullptr;
    std::vector<std::pair<std::string, Query>> methods = {{"ours", ours}};
    if (has_libccd) methods.push_back({"fcl-libccd", libccd});
    if (has_bullet) methods.push_back({"bullet", bullet});
    for (const auto& [name, query] : methods) {
      for (int bucket = 0; bucket < int(std::size(kBuckets)); ++bucket) {
        std::vector<const Case*> group;
        std::vector<double> truth;
        for (std::size_t i = 0; i < cases.size(); ++i) {
          if (cases[i].bucket == bucket) {
            group.push_back(&cases[i]);
            truth.push_back(reference[i]);
          }
        }
        std::vector<double> answers(group.size()), passes;
        shapeEvaluations() = 0;  // every pass makes the same evaluations
        for (int r = 0; r < kRepetitions; ++r) {
          const Clock::time_point t0 = Clock::now();
          for (std::size_t i = 0; i < group.size(); ++i) answers[i] = query(*group[i]);
          passes.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
        }
        std::sort(passes.begin(), passes.end());
        const double kept = std::accumulate(passes.begin(), passes.begin() + kKept, 0.0) / kKept;
        const double evaluations =
            double(shapeEvaluations()) / (double(kRepetitions) * double(group.size()));
        Row row{kind,       name, bucket, 1e6 * kept / double(group.size()),
                0,          0,    0,      int(group.size()),
                evaluations};
        std::vector<double> errors;
        for (std::size_t i = 0; i < group.size(); ++i) {
          if (!std::isfinite(answers[i]) || std::abs(answers[i]) > 1e30) {
            ++row.failures;
            continue;
          }
          errors.push_back(std::abs(answers[i] - truth[i]) / group[i]->size);
        }
        // Overlapping, ours is the reference (where there is one): no error of its own.
        if (std::isnan(truth.front()) || (name == "ours" && kBuckets[bucket] < 0)) {
          row.max_error = row.median_error = NAN;
        } else if (!errors.empty()) {
          std::sort(errors.begin(), errors.end());
          row.max_error = errors.back();
          row.median_error = errors[errors.size() / 2];
        }
        rows.push_back(row);
      }
    }
  }
  // The table: per kind and method, separated (d ≥ 0.001) and overlapping buckets; time ratios
  // ours ÷ method (< 1: ours is faster).
  std::printf(
      "| pair | method | separated µs | max error | ours ÷ method | overlapping µs | max error | "
      "ours ÷ method | failures |\n|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
  std::map<std::pair<std::string, std::string>, std::array<double, 5>> summary;
  for (const Row& r : rows) {
    auto& s = summary[{r.kind, r.method}];
    const bool separated = kBuckets[r.bucket] > 0;
    s[separated ? 0 : 2] += r.us / (separated ? 4 : 2);
    double& e = s[separated ? 1 : 3];
    e = std::isnan(r.max_error) || std::isnan(e) ? NAN : std::max(e, r.max_error);
    s[4] += r.failures;
  }
  for (const std::string& kind : kinds) {
    if (summary.find({kind, "ours"}) == summary.end()) continue;  // not run
    const auto ours_row = summary[{kind, "ours"}];
    for (const char* method : {"ours", "fcl-libccd", "bullet"}) {
      const auto it = summary.find({kind, method});
      if (it == summary.end()) continue;
      const auto& s = it->second;
      std::printf("| %s | %s | %.2f | %.1e | %.2f | %.2f | %.1e | %.2f | %d |\n", kind.c_str(),
                  method, s[0], s[1], ours_row[0] / s[0], s[2], s[3], ours_row[2] / s[2],
                  int(s[4]));
    }
  }
  // Coal's protocol also counts iterations per bucket. libccd and Bullet report none, so the
  // common count is the superellipsoid's support (or gauge) evaluations, which every method is
  // made of (diagnostics.h → shapeEvaluations): one per GJK iteration and EPA expansion (two
  // where the partner is a superellipsoid too), one per Newton step or point query of ours.
  std::printf(
      "\nThe superellipsoid's support or gauge evaluations per query, by bucket d/size:\n\n"
      "| pair | method |");
  for (double b : kBuckets) std::printf(" %g |", b);
  std::printf("\n|---|---|");
  for (std::size_t b = 0; b < std::size(kBuckets); ++b) std::printf("---:|");
  std::printf("\n");
  for (std::size_t i = 0; i < rows.size(); i += std::size(kBuckets)) {
    std::printf("| %s | %s |", rows[i].kind.c_str(), rows[i].method.c_str());
    for (std::size_t b = 0; b < std::size(kBuckets); ++b) {
      std::printf(" %.1f |", rows[i + b].evaluations);
    }
    std::printf("\n");
  }
  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "kind,method,bucket,us_per_query,max_error,median_error,failures,cases,"
           "evaluations_per_query\n";
    for (const Row& r : rows) {
      out << r.kind << ',' << r.method << ',' << kBuckets[r.bucket] << ',' << r.us << ','
          << r.max_error << ',' << r.median_error << ',' << r.failures << ',' << r.cases << ','
          << r.evaluations << '\n';
    }
    std::printf("\n(every bucket: %s)\n", csv.c_str());
  }
  return 0;
}

namespace {

template <typename S>
void writeVector(std::FILE* out, const Vector3<S>& v) {
  std::fprintf(out, " %a %a %a", double(v[0]), double(v[1]), double(v[2]));
}

/// One query in both argument orders: distance with nearest points, then collide's contacts.
template <typename S>
void writeAnswer(std::FILE* out, const fcl::CollisionGeometry<S>* a, const fcl::Transform3<S>& X_A,
                 const fcl::CollisionGeometry<S>* b, const fcl::Transform3<S>& X_B) {
  for (int order = 0; order < 2; ++order) {
    const fcl::CollisionGeometry<S>* o1 = order == 0 ? a : b;
    const fcl::CollisionGeometry<S>* o2 = order == 0 ? b : a;
    const fcl::Transform3<S>& X1 = order == 0 ? X_A : X_B;
    const fcl::Transform3<S>& X2 = order == 0 ? X_B : X_A;
    fcl::DistanceRequest<S> request(true, true);
    fcl::DistanceResult<S> result;
    const S d = fcl_superellipsoid::distance(o1, X1, o2, X2, request, result);
    std::fprintf(out, "  d %a", double(d));
    writeVector(out, result.nearest_points[0]);
    writeVector(out, result.nearest_points[1]);
    fcl::CollisionRequest<S> collide_request(4, true);
    fcl::CollisionResult<S> collide_result;
    fcl_superellipsoid::collide(o1, X1, o2, X2, collide_request, collide_result);
    std::fprintf(out, "\n  contacts %zu", collide_result.numContacts());
    for (std::size_t i = 0; i < collide_result.numContacts(); ++i) {
      const fcl::Contact<S>& c = collide_result.getContact(i);
      std::fprintf(out, "\n   %a", double(c.penetration_depth));
      writeVector(out, c.pos);
      writeVector(out, c.normal);
    }
    std::fprintf(out, "\n");
  }
}

/// The case's geometry in float (the same parameters, rounded), or nullptr.
std::shared_ptr<fcl::CollisionGeometryf> toFloat(const fcl::CollisionGeometryd* g) {
  if (auto* x = dynamic_cast<const Superellipsoidd*>(g)) {
    return std::make_shared<Superellipsoidf>(Vector3<float>(x->radii().cast<float>()),
                                             float(x->eps1()), float(x->eps2()));
  }
  if (auto* x = dynamic_cast<const fcl::Ellipsoidd*>(g)) {
    return std::make_shared<fcl::Ellipsoidf>(Vector3<float>(x->radii.cast<float>()));
  }
  if (auto* x = dynamic_cast<const fcl::Sphered*>(g)) {
    return std::make_shared<fcl::Spheref>(float(x->radius));
  }
  if (auto* x = dynamic_cast<const fcl::Boxd*>(g)) {
    return std::make_shared<fcl::Boxf>(Vector3<float>(x->side.cast<float>()));
  }
  if (auto* x = dynamic_cast<const fcl::Capsuled*>(g)) {
    return std::make_shared<fcl::Capsulef>(float(x->radius), float(x->lz));
  }
  if (auto* x = dynamic_cast<const fcl::Cylinderd*>(g)) {
    return std::make_shared<fcl::Cylinderf>(float(x->radius), float(x->lz));
  }
  if (auto* x = dynamic_cast<const fcl::Coned*>(g)) {
    return std::make_shared<fcl::Conef>(float(x->radius), float(x->lz));
  }
  if (auto* x = dynamic_cast<const fcl::Halfspaced*>(g)) {
    return std::make_shared<fcl::Halfspacef>(Vector3<float>(x->n.cast<float>()), float(x->d));
  }
  if (auto* x = dynamic_cast<const fcl::Planed*>(g)) {
    return std::make_shared<fcl::Planef>(Vector3<float>(x->n.cast<float>()), float(x->d));
  }
  if (auto* x = dynamic_cast<const fcl::TrianglePd*>(g)) {
    return std::make_shared<fcl::TrianglePf>(Vector3<float>(x->a.cast<float>()),
                                             Vector3<float>(x->b.cast<float>()),
                                             Vector3<float>(x->c.cast<float>()));
  }
  return nullptr;  // Convex: its double answers only
}

}  // namespace

int writePairAnswers(int per_kind, const std::string& path) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (out == nullptr) {
    std::fprintf(stderr, "error: cannot write %s\n", path.c_str());
    return 2;
  }
  std::mt19937 rng(2026);  // the same draws as runPairs
  for (const std::string& kind : kPairKinds) {
    const std::vector<Case> cases = makeCases(kind, per_kind, rng);
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const Case& k = cases[i];
      std::fprintf(out, "%s %zu bucket %d\n", kind.c_str(), i, k.bucket);
      writeAnswer<double>(out, k.shape.get(), k.X_WA, k.other.get(), k.X_WB);
      const std::shared_ptr<fcl::CollisionGeometryf> a = toFloat(k.shape.get());
      const std::shared_ptr<fcl::CollisionGeometryf> b = toFloat(k.other.get());
      if (a && b) {
        std::fprintf(out, " float\n");
        writeAnswer<float>(out, a.get(), fcl::Transform3f(k.X_WA.cast<float>()), b.get(),
                           fcl::Transform3f(k.X_WB.cast<float>()));
      }
    }
  }
  std::fclose(out);
  std::printf("pair answers: %s\n", path.c_str());
  return 0;
}

}  // namespace bench
}  // namespace fcl_superellipsoid
