// What threads share: the same shapes, the same FCL objects and broadphase manager, queried
// from several threads at once; FCL's tables filled by the first construction while other
// threads construct too. Each threaded answer must equal the one computed on one thread.
// Built and run under ThreadSanitizer by `scripts/test.sh --tsan` (docs/hardening.md), where a
// data race is a failure even when the answers happen to agree.

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include "common/tasks.h"
#include "fcl_superellipsoid/batch_distance.h"
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_superellipsoid/point_distance.h"
#include "fcl_superellipsoid/tessellation.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

constexpr int kThreads = 4;

/// Runs body(t) on kThreads threads released together, so their first calls overlap.
void onThreadsAtOnce(const std::function<void(int)>& body) {
  std::atomic<int> ready{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      ++ready;
      while (ready.load() < kThreads) std::this_thread::yield();
      body(t);
    });
  }
  for (std::thread& t : threads) t.join();
}

/// Runs answers() on kThreads threads at once; each must return exactly `expected`.
template <typename Value, typename Answers>
void expectEveryThreadGets(const Value& expected, const Answers& answers) {
  std::vector<int> mismatches(kThreads, 0);
  onThreadsAtOnce([&](int t) {
    if (answers() != expected) ++mismatches[t];
  });
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(mismatches[t], 0) << "thread " << t;
}

template <typename S>
Matrix3X<S> randomPoints(int n, S extent, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Matrix3X<S> p(3, n);
  for (int i = 0; i < n; ++i) p.col(i) = extent * Vector3<S>(S(u(rng)), S(u(rng)), S(u(rng)));
  return p;
}

template <typename S>
class ThreadSafetyTest : public ::testing::Test {};
TYPED_TEST_SUITE(ThreadSafetyTest, test::Scalars);

// The first construction registers with FCL's tables (once per process). Under ctest each test
// runs in its own process, so here the registration itself races: every thread constructs a
// shape and at once asks FCL, through its own table, for a distance that needs the entry.
TYPED_TEST(ThreadSafetyTest, FirstConstructionRacesOnSeveralThreads) {
  using S = TypeParam;
  std::vector<S> distance(kThreads, S(-2));
  onThreadsAtOnce([&](int t) {
    // A sphere per thread: fcl::CollisionObject's constructor recomputes its geometry's AABB,
    // so objects built at once on one shared geometry race inside FCL (TSan saw it).
    const auto sphere = std::make_shared<fcl::Sphere<S>>(S(0.5));
    const auto shape = std::make_shared<Superellipsoid<S>>(S(1), S(1), S(1), S(1), S(1));
    const fcl::CollisionObject<S> a(shape),
        b(sphere, fcl::Transform3<S>(fcl::Translation3<S>(S(3 + t), S(0), S(0))));
    fcl::detail::GJKSolver_libccd<S> solver;
    fcl::DistanceResult<S> result;
    fcl::distance(&a, &b, &solver, fcl::DistanceRequest<S>(), result);
    distance[t] = result.min_distance;
  });
  for (int t = 0; t < kThreads; ++t) {
    // Unit sphere to a sphere of radius 0.5 centred at 3 + t: 1.5 + t by construction.
    EXPECT_NEAR(distance[t], S(1.5 + t), S(1e-5)) << "thread " << t;
  }
}

// One shape, every method, many threads: each answer bitwise equal to the single-thread one.
// The expected answers come from a copy, so the threads race on the shape's first computation
// of its rolling radius and of its direction cover (the inside points deeper than G = 0.9).
TYPED_TEST(ThreadSafetyTest, ManyThreadsQueryTheSameShape) {
  using S = TypeParam;
  const Superellipsoid<S> shape(S(1.2), S(0.8), S(0.5), S(0.4), S(1.3));
  const Matrix3X<S> points = randomPoints<S>(200, S(1.5), 21);
  auto answersOf = [&](const Superellipsoid<S>& queried) {
    std::vector<S> out;
    for (DistanceMethod m :
         {DistanceMethod::kRadial, DistanceMethod::kPaper, DistanceMethod::kExact}) {
      for (Eigen::Index i = 0; i < points.cols(); ++i) {
        const auto r = pointDistance(queried, Vector3<S>(points.col(i)), DistanceOptions<S>::of(m));
        out.insert(out.end(),
                   {r.distance, r.nearest_point[0], r.nearest_point[1], r.nearest_point[2]});
      }
    }
    return out;
  };
  expectEveryThreadGets(answersOf(Superellipsoid<S>(shape)), [&] { return answersOf(shape); });
}

// Batched queries from several threads at once, each itself threaded: the same answers.
TYPED_TEST(ThreadSafetyTest, BatchedQueriesFromSeveralThreads) {
  using S = TypeParam;
  const Superellipsoid<S> shape(S(1), S(0.9), S(0.7), S(0.3), S(0.6));
  const fcl::Transform3<S> X_WS(fcl::Translation3<S>(S(0.1), S(-0.2), S(0.05)));
  const Matrix3X<S> points = randomPoints<S>(3000, S(1.2), 22);
  BatchOptions<S> options;
  options.threads = 2;
  options.min_parallel_vertices = 1;
  auto answers = [&] {
    std::vector<VertexContact<S>> contacts;
    verticesWithinMargin<S>(shape, X_WS, points, S(0.05), contacts, options);
    std::vector<S> out;
    for (const auto& c : contacts) out.insert(out.end(), {S(c.index), c.distance});
    return out;
  };
  const std::vector<S> expected = answers();
  ASSERT_GT(expected.size(), 1000u);  // over 500 contacts
  expectEveryThreadGets(expected, answers);
}

// Batched gradients from several threads at once, each itself threaded: the same rows.
TYPED_TEST(ThreadSafetyTest, BatchedGradientsFromSeveralThreads) {
  using S = TypeParam;
  const Superellipsoid<S> shape(S(1), S(0.9), S(0.7), S(0.3), S(0.6));
  const fcl::Transform3<S> X_WS(fcl::Translation3<S>(S(0.1), S(-0.2), S(0.05)));
  const Matrix3X<S> points = randomPoints<S>(3000, S(1.2), 23);
  BatchOptions<S> options;
  options.threads = 2;
  options.min_parallel_vertices = 1;
  auto answers = [&] {
    BatchDerivativesResult<S> g;
    batchDistanceDerivatives<S>(shape, X_WS, points, g, options);
    std::vector<S> out(g.d_shape.data(), g.d_shape.data() + g.d_shape.size());
    out.insert(out.end(), g.distance.data(), g.distance.data() + g.distance.size());
    for (Eigen::Index i = 0; i < g.differentiable.size(); ++i)
      out.push_back(S(g.differentiable[i]));
    return out;
  };
  expectEveryThreadGets(answers(), answers);
}

// The same FCL objects (a shape, a mesh, a sphere) queried from several threads, through the
// front end and through FCL's own calls with the solver.
TYPED_TEST(ThreadSafetyTest, ManyThreadsQueryTheSameFclObjects) {
  using S = TypeParam;
  const auto shape = std::make_shared<Superellipsoid<S>>(S(1), S(0.8), S(0.6), S(0.5), S(1.2));
  const auto mesh = makeBVHModel<fcl::OBBRSS<S>>(
      tessellate(Superellipsoid<S>(S(0.9), S(1.1), S(0.7), S(1), S(1)), 400));
  const auto sphere = std::make_shared<fcl::Sphere<S>>(S(0.3));
  const fcl::CollisionObject<S> o_shape(shape),
      o_sphere(sphere, fcl::Transform3<S>(fcl::Translation3<S>(S(1.1), 0, 0)));
  std::vector<fcl::CollisionObject<S>> meshes;
  for (int k = 0; k < 3; ++k) {
    meshes.emplace_back(mesh, fcl::Transform3<S>(fcl::Translation3<S>(S(0.5 + k), S(0.2), 0)));
  }
  // One answer per (partner, call): distance and the number of contacts.
  auto answers = [&] {
    std::vector<S> out;
    fcl::detail::GJKSolver_libccd<S> solver;
    std::vector<const fcl::CollisionObject<S>*> partners{&o_sphere};
    for (const auto& m : meshes) partners.push_back(&m);
    for (const auto* other : partners) {
      fcl::DistanceResult<S> d1, d2;
      const fcl::DistanceRequest<S> request(true, true);
      fcl_superellipsoid::distance(&o_shape, other, request, d1);
      fcl::distance(other, &o_shape, &solver, request, d2);
      fcl::CollisionResult<S> c1, c2;
      const fcl::CollisionRequest<S> crequest(100, true);
      fcl_superellipsoid::collide(&o_shape, other, crequest, c1);
      fcl::collide(other, &o_shape, &solver, crequest, c2);
      out.insert(out.end(),
                 {d1.min_distance, d2.min_distance, S(c1.numContacts()), S(c2.numContacts())});
    }
    return out;
  };
  expectEveryThreadGets(answers(), answers);
}

// A box's and a triangle's faces and edges are built once per process and shared by every
// query (src/narrowphase/polytope_pair.cpp, sharedTopology). Under ctest each test runs in
// its own process, so the threads here race on building them: every thread's answers (distance,
// nearest points, contacts; separated and overlapping) equal those of the same queries made
// after, on one thread.
TYPED_TEST(ThreadSafetyTest, PolytopePairsRaceOnTheirSharedTopology) {
  using S = TypeParam;
  const auto shape = std::make_shared<Superellipsoid<S>>(S(1), S(0.8), S(0.6), S(0.5), S(1.2));
  const auto box = std::make_shared<fcl::Box<S>>(S(0.4), S(0.6), S(0.3));
  const auto triangle = std::make_shared<fcl::TriangleP<S>>(Vector3<S>(S(0), S(0), S(0)),
                                                            Vector3<S>(S(0.5), S(0), S(0)),
                                                            Vector3<S>(S(0), S(0.4), S(0.1)));
  auto answers = [&] {
    std::vector<S> out;
    for (const std::shared_ptr<fcl::CollisionGeometry<S>>& other :
         {std::static_pointer_cast<fcl::CollisionGeometry<S>>(box),
          std::static_pointer_cast<fcl::CollisionGeometry<S>>(triangle)}) {
      for (S x : {S(1.5), S(1.25), S(0.9)}) {  // apart, near, overlapping
        const fcl::Transform3<S> X_WO(fcl::Translation3<S>(x, S(0.1), S(-0.05)));
        fcl::DistanceResult<S> d;
        fcl_superellipsoid::distance(shape.get(), fcl::Transform3<S>::Identity(), other.get(), X_WO,
                                     fcl::DistanceRequest<S>(true, true), d);
        fcl::CollisionResult<S> c;
        fcl_superellipsoid::collide(shape.get(), fcl::Transform3<S>::Identity(), other.get(), X_WO,
                                    fcl::CollisionRequest<S>(1, true), c);
        out.insert(out.end(), {d.min_distance, d.nearest_points[0][0], d.nearest_points[1][0],
                               S(c.numContacts())});
      }
    }
    return out;
  };
  std::vector<std::vector<S>> got(kThreads);
  onThreadsAtOnce([&](int t) { got[t] = answers(); });
  const std::vector<S> after = answers();
  ASSERT_EQ(after.size(), 24u);
  EXPECT_GT(after[0], S(0));   // the box apart
  EXPECT_LT(after[8], S(0));   // and overlapping
  EXPECT_EQ(after[11], S(1));  // with one contact
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(got[t], after) << "thread " << t;
}

// A broadphase manager set up once and queried (self-collision, distance to an object) from
// several threads with the front end's callbacks.
TYPED_TEST(ThreadSafetyTest, BroadphaseQueriesFromSeveralThreads) {
  using S = TypeParam;
  const auto shape = std::make_shared<Superellipsoid<S>>(S(1), S(0.8), S(0.6), S(0.5), S(1.2));
  const auto cloth = makeBVHModel<fcl::OBBRSS<S>>(
      tessellate(Superellipsoid<S>(S(2), S(2), S(0.05), S(1), S(0.2)), 300));
  fcl::CollisionObject<S> o_shape(shape),
      o_cloth(cloth, fcl::Transform3<S>(fcl::Translation3<S>(0, 0, S(0.58))));
  fcl::CollisionObject<S> o_probe(shape, fcl::Transform3<S>(fcl::Translation3<S>(0, 0, S(-3))));
  fcl::DynamicAABBTreeCollisionManager<S> manager;
  manager.registerObjects({&o_shape, &o_cloth});
  manager.setup();
  auto answers = [&] {
    fcl::DefaultCollisionData<S> cdata;
    cdata.request.num_max_contacts = 100000;
    cdata.request.enable_contact = true;
    manager.collide(&cdata, defaultCollisionFunction<S>);
    fcl::DefaultDistanceData<S> ddata;
    ddata.request.enable_signed_distance = true;
    manager.distance(&o_probe, &ddata, defaultDistanceFunction<S>);
    return std::vector<S>{S(cdata.result.numContacts()), ddata.result.min_distance};
  };
  const std::vector<S> expected = answers();
  ASSERT_GT(expected[0], S(0));  // contacts
  expectEveryThreadGets(expected, answers);
}

// The library's own tasks (common/tasks.h: TBB's, std::threads under TSan): every task runs and
// its writes are seen after wait(); a task's exception comes back from wait(), and the group is
// usable again; a group destroyed with a failed task waits for it and does not throw.
TEST(ThreadSafety, TaskGroupRunsEveryTaskAndRethrows) {
  std::vector<int> slots(64, 0);
  {
    detail::TaskGroup group;
    for (int i = 0; i < 64; ++i) group.run([&slots, i] { slots[std::size_t(i)] = i + 1; });
    group.wait();
    for (int i = 0; i < 64; ++i) EXPECT_EQ(slots[std::size_t(i)], i + 1);
    group.run([] { throw std::runtime_error("task 7 failed"); });
    try {
      group.wait();
      ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "task 7 failed");
    }
    std::atomic<int> ran{0};
    for (int i = 0; i < 8; ++i) group.run([&ran] { ++ran; });
    group.wait();
    EXPECT_EQ(ran.load(), 8);
  }
  EXPECT_NO_THROW({
    detail::TaskGroup group;
    group.run([] { throw std::runtime_error("dropped"); });
  });
}

}  // namespace
}  // namespace fcl_superellipsoid
