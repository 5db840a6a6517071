#include "contact/rigid_contact.h"

#include <fcl_superellipsoid/batch_distance.h>
#include <fcl_superellipsoid/contact_manifold.h>
#include <fcl_superellipsoid/point_distance.h>
#include <fcl_superellipsoid/tessellation.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <thread>
#include <unordered_map>

#include "contact/persistent_places.h"
#include "contact/rigid_mesh_contact.h"
#include "contact/support_bound.h"

namespace fse_sim {

namespace fse = fcl_superellipsoid;

namespace {

/// Whether the bodies' bounding boxes (their frames, half-sizes the radii) come within `margin`
/// of each other: the separating-axis test on the 15 axes of two boxes.
bool boxesOverlap(const RigidBody& a, const RigidBody& b, double margin) {
  const Eigen::Matrix3d A = a.q.toRotationMatrix(), B = b.q.toRotationMatrix();
  const Eigen::Vector3d ea = a.shape->radii(), eb = b.shape->radii();
  const Eigen::Vector3d t = b.x - a.x;
  auto separated = [&](const Eigen::Vector3d& axis) {
    const double length = axis.norm();
    if (length < 1e-9) return false;  // parallel edges: a face axis decides
    const Eigen::Vector3d u = axis / length;
    const double ra = ea.dot((A.transpose() * u).cwiseAbs());
    const double rb = eb.dot((B.transpose() * u).cwiseAbs());
    return std::abs(t.dot(u)) > ra + rb + margin;
  };
  for (int k = 0; k < 3; ++k) {
    if (separated(A.col(k)) || separated(B.col(k))) return false;
  }
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < 3; ++l) {
      if (separated(A.col(k).cross(B.col(l)))) return false;
    }
  }
  return true;
}

/// How far body a's nearest point along unit u lies beyond body b's farthest: a's support in −u
/// against b's in +u.
double gapAlong(const RigidBody& a, const RigidBody& b, const Eigen::Vector3d& u) {
  const Eigen::Vector3d on_a = a.toWorld(a.shape->supportPoint(a.q.inverse() * -u));
  const Eigen::Vector3d on_b = b.toWorld(b.shape->supportPoint(b.q.inverse() * u));
  return u.dot(on_a - on_b);
}

/// The contacts of points of body `from` (local(k): the point of query column k, from's frame)
/// that a batched query found within the margin of body `other`: `from` separates along other's
/// outward normal at the point's nearest point.
template <typename Local>
void appendPointContacts(const std::vector<fse::VertexContact<double>>& found, int i_from,
                         const RigidBody& other, int i_other, Local&& local,
                         std::vector<RigidContact>& out) {
  for (const fse::VertexContact<double>& v : found) {
    RigidContact c;
    c.a = i_from;
    c.b = i_other;
    c.distance = v.distance;
    c.n = v.normal;
    c.r_a = local(v.index);
    c.r_b = other.q.inverse() * (v.nearest_point - other.x);
    out.push_back(c);
  }
}

/// How far point p of the triangle's plane (unit normal m) lies outside the triangle, measured
/// from the edges' lines: the largest of its distances beyond them (0 inside, edges included).
double outsideTriangle(const Eigen::Vector3d& p, const fcl::TriangleP<double>& tri,
                       const Eigen::Vector3d& m) {
  double outside = 0;
  const Eigen::Vector3d* corners[3] = {&tri.a, &tri.b, &tri.c};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& from = *corners[k];
    const Eigen::Vector3d edge = *corners[(k + 1) % 3] - from;
    outside = std::max(outside, -m.dot(edge.cross(p - from)) / edge.norm());
  }
  return outside;
}

}  // namespace

struct RigidContactFinder::Impl {
  ContactModel model;
  const StaticMesh* bowl;
  MeshGrid grid;
  std::vector<fcl::TriangleP<double>> triangles;  ///< the bowl's, world frame
  std::vector<Eigen::Matrix3Xd> mesh_vertices;    ///< per body, body frame (vertex models)
  std::vector<Eigen::Matrix3Xd> world_vertices;   ///< per body, this step
  std::vector<SupportBound> support_bounds;       ///< per body (the bowl's faces' cull)
  std::unique_ptr<tbb::task_arena> arena;
  fse::BatchOptions<double> exact_options, model_options;
  std::unique_ptr<RigidMeshContact> meshes;  ///< the mesh model's BVHs

  /// A unit of work whose contacts land in their own slot: a body pair, or a body and the bowl.
  struct Job {
    int a, b;                      // b = −1: the bowl
    double margin;                 // tolerance + the travel of both
    PairPlaces* places = nullptr;  // the exact model's, for body pairs
  };
  /// The exact model's persistent places of each body pair in reach, by pair (i·n + j).
  std::unordered_map<long, PairPlaces> places;
  double skin = 0;  ///< m: how far apart the solver holds resting contacts this step
  std::vector<Job> jobs;
  std::vector<std::vector<RigidContact>> slots;

  void collectJobs(const std::vector<RigidBody>& bodies, double tolerance,
                   const std::vector<double>& travel) {
    jobs.clear();
    const int n = int(bodies.size());
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        if (bodies[i].fixed() && bodies[j].fixed()) continue;
        const double margin = tolerance + travel[std::size_t(i)] + travel[std::size_t(j)];
        const double reach = bodies[i].bounding_radius + bodies[j].bounding_radius + margin;
        if ((bodies[i].x - bodies[j].x).squaredNorm() <= reach * reach &&
            boxesOverlap(bodies[i], bodies[j], margin)) {
          jobs.push_back({i, j, margin, nullptr});
        }
      }
      if (bowl != nullptr && !bodies[i].fixed()) {
        jobs.push_back({i, -1, tolerance + travel[std::size_t(i)], nullptr});
      }
    }
  }

  template <typename F>
  void forEachJob(F&& f) {
    slots.resize(jobs.size());
#if defined(__SANITIZE_THREAD__)
    // ThreadSanitizer cannot see TBB's synchronisation (Debian's libtbb is not instrumented): in
    // the TSan build the jobs run on two std::threads, joined visibly, so that its reports are
    // about the jobs' shared state.
    if (arena) {
      std::atomic<std::size_t> next{0};
      auto worker = [&] {
        for (std::size_t k = next++; k < jobs.size(); k = next++) {
          slots[k].clear();
          f(jobs[k], slots[k]);
        }
      };
      std::thread other(worker);
      worker();
      other.join();
      return;
    }
#endif
    auto run = [&] {
      tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t k) {
        slots[k].clear();
        f(jobs[k], slots[k]);
      });
    };
    if (arena) {
      arena->execute(run);
    } else {
      for (std::size_t k = 0; k < jobs.size(); ++k) {
        slots[k].clear();
        f(jobs[k], slots[k]);
      }
    }
  }

  /// Gives each body-pair job its pair's persistent places, and forgets the places of pairs out
  /// of reach.
  void attachPlaces(std::size_t bodies) {
    std::unordered_map<long, PairPlaces> kept;
    for (Job& job : jobs) {
      if (job.b < 0) continue;
      const long key = long(job.a) * long(bodies) + job.b;
      auto found = places.find(key);
      auto& entry = kept[key];
      if (found != places.end()) entry = std::move(found->second);
    }
    places = std::move(kept);
    for (Job& job : jobs) {
      if (job.b >= 0) job.places = &places.at(long(job.a) * long(bodies) + job.b);
    }
  }

  void exactPair(const std::vector<RigidBody>& bodies, int i, int j, double margin,
                 PairPlaces* kept, std::vector<RigidContact>& out) const {
    const RigidBody& a = bodies[std::size_t(i)];
    const RigidBody& b = bodies[std::size_t(j)];
    // The pair's signed distance and witnesses: where the pair keeps places, from its contact
    // region, which reports them as the distance query would (one pair query, not two).
    double d;
    Eigen::Vector3d w_a, w_b;
    std::optional<fse::ContactManifold<double>> region;
    const fse::ManifoldOptions<double> options = regionOptions(a, b, skin);
    if (kept != nullptr) {
      region = fse::contactManifold(*a.shape, a.transform(), *b.shape, b.transform(), options,
                                    kept->warm);
      d = region->distance;
      w_a = region->on_shape;
      w_b = region->on_other;
    } else {
      fcl::DistanceRequestd request;
      request.enable_nearest_points = true;
      request.enable_signed_distance = true;
      fcl::DistanceResultd result;
      d = fse::distance(a.shape.get(), a.transform(), b.shape.get(), b.transform(), request,
                        result);
      w_a = result.nearest_points[0];
      w_b = result.nearest_points[1];
    }
    if (!(d <= margin)) return;
    // The contact normal: of the candidate directions u, the one whose gap (how far a's
    // nearest point along u lies beyond b's farthest) is largest; the true normal's gap is the
    // signed distance itself (separating-axis duality). The candidates: the witnesses'
    // difference (the normal itself wherever the witnesses are unique), both shapes' normals at
    // the witnesses, and both frames' axes (the faces of box-like shapes, where the witnesses
    // are one of many pairs: a support point on a face as flat as ε = 0.1's moves far along it,
    // into the rounded edge, for a tiny turn of the direction).
    Eigen::Vector3d n = b.q * b.shape->normal(b.q.inverse() * (w_b - b.x));
    double best = gapAlong(a, b, n);
    auto consider = [&](const Eigen::Vector3d& u) {
      if (!u.allFinite()) return;
      const double g = gapAlong(a, b, u);
      if (g > best) {
        best = g;
        n = u;
      }
    };
    const Eigen::Vector3d gap = d >= 0 ? Eigen::Vector3d(w_a - w_b) : Eigen::Vector3d(w_b - w_a);
    if (gap.norm() > 0) consider(gap.normalized());
    consider(-(a.q * a.shape->normal(a.q.inverse() * (w_a - a.x))));
    for (const RigidBody* body : {&a, &b}) {
      const Eigen::Matrix3d axes = body->q.toRotationMatrix();
      for (int k = 0; k < 3; ++k) {
        consider(axes.col(k));
        consider(-axes.col(k));
      }
    }
    // The witnesses along the chosen normal: a's support toward b, b's toward a. Where no
    // candidate reaches the distance itself (best < d: a direction a little off the normal),
    // b's point moves along n so that the contact starts at the true distance rather than
    // demanding a larger push than the bodies' overlap.
    const Eigen::Vector3d on_a = a.toWorld(a.shape->supportPoint(a.q.inverse() * -n));
    const Eigen::Vector3d on_b =
        b.toWorld(b.shape->supportPoint(b.q.inverse() * n)) + (best - d) * n;
    const std::size_t before = out.size();
    if (region) {
      updatePlaces(a, i, b, j, *region, n, options.patch_tolerance, options.max_points, *kept, out);
    }
    const bool has_places = out.size() > before;
    out.push_back(contactAt(a, i, &b, j, d, on_a, on_b, n));
    out.back().follows_support = true;
    out.back().support_offset = best - d;
    out.back().turning_only = has_places;
  }

  /// The options of a pair's contact region from the library (fse::contactManifold, a as the
  /// shape, warm-started from the pair's last one), whose places update the pair's persistent
  /// places (contact/persistent_places.h), a contact each: the outline unrefined (only its
  /// reduced places are used); the patch tolerance 1e-3 × the smaller body's size plus the skin
  /// (a resting pair is held the skin apart, and its region must reach across that).
  static fse::ManifoldOptions<double> regionOptions(const RigidBody& a, const RigidBody& b,
                                                    double skin) {
    fse::ManifoldOptions<double> options;
    options.patch_tolerance = 1e-3 * std::min(a.shape->size(), b.shape->size()) + skin;
    options.outline_area_tolerance = 1;
    return options;
  }

  /// Vertices of body i against body j's implicit surface.
  void verticesAgainst(const std::vector<RigidBody>& bodies, int i, int j, double margin,
                       std::vector<RigidContact>& out) const {
    const RigidBody& b = bodies[std::size_t(j)];
    fse::BatchOptions<double> options = model_options;
    if (model == ContactModel::kPaper) {
      // The paper's case-study settings: tolerance 1e-3 (absolute, as in the paper; the
      // library's tolerances are relative to the shape's size) and 10 iterations.
      options.distance.tolerance = 1e-3 / b.shape->size();
    }
    thread_local std::vector<fse::VertexContact<double>> found;
    fse::verticesWithinMargin(*b.shape, b.transform(), world_vertices[std::size_t(i)], margin,
                              found, options);
    const Eigen::Matrix3Xd& local = mesh_vertices[std::size_t(i)];
    appendPointContacts(
        found, i, b, j, [&](Eigen::Index k) { return local.col(k); }, out);
  }

  /// Whether any of the bowl's triangles is in the grid's cells within body a's reach.
  bool bowlNear(const RigidBody& a, double margin) const {
    const double reach = a.bounding_radius + margin;
    thread_local std::vector<int> near_vertices, near_triangles;
    grid.query(a.x.array() - reach, a.x.array() + reach, near_vertices, near_triangles);
    return !near_triangles.empty();
  }

  /// Body a's contacts with the bowl: its vertices where the bowl is convex, and its faces
  /// (with their convex edges) within the margin.
  void bowlContacts(const RigidBody& a, int i, double margin,
                    std::vector<RigidContact>& out) const {
    const double reach = a.bounding_radius + margin;
    thread_local std::vector<int> near_vertices, near_triangles;
    grid.query(a.x.array() - reach, a.x.array() + reach, near_vertices, near_triangles);
    const fcl::Transform3d X = a.transform();
    if (!near_vertices.empty()) bowlVertexContacts(a, i, X, near_vertices, margin, out);
    const SupportBound& support_bound = support_bounds[std::size_t(i)];
    for (int t : near_triangles) bowlFaceContact(a, i, X, support_bound, t, margin, out);
  }

  /// The bowl's vertices where its surface is convex (the rim) against the body's surface: a
  /// separates from a vertex V along −(its outward normal at V's nearest point). In a valley of
  /// the surface the faces round a vertex reach as far as it does (bowlFaceContact).
  void bowlVertexContacts(const RigidBody& a, int i, const fcl::Transform3d& X,
                          const std::vector<int>& near_vertices, double margin,
                          std::vector<RigidContact>& out) const {
    thread_local Eigen::Matrix3Xd points;
    points.resize(3, long(near_vertices.size()));
    long count = 0;
    for (int v : near_vertices) {
      if (bowl->convex_vertex[std::size_t(v)]) points.col(count++) = bowl->vertices.col(v);
    }
    points.conservativeResize(3, count);
    thread_local std::vector<fse::VertexContact<double>> found;
    fse::verticesWithinMargin(*a.shape, X, points, margin, found, exact_options);
    for (const fse::VertexContact<double>& v : found) {
      RigidContact c;
      c.a = i;
      c.b = -1;
      c.distance = v.distance;
      c.n = -v.normal;
      c.r_a = a.q.inverse() * (v.nearest_point - a.x);
      c.r_b = points.col(v.index);
      out.push_back(c);
    }
  }

  /// The body against bowl triangle t, if it comes within the margin of its plane (it reaches
  /// down to s − h(−m) along the face's outward normal m, h its support function). On a face,
  /// the body's nearest point to the plane is its support point along −m: where that point lies
  /// over the triangle it is the nearest point to the triangle too (the Halfspace pair's answer;
  /// faces whose foot is near the triangle count too, below). Elsewhere the triangle's nearest
  /// point is on its boundary: at a vertex (bowlVertexContacts), or at a convex edge (a rim),
  /// where the library's superellipsoid–triangle pair answers (bowlRimContact). Across a flat or
  /// concave edge, a face beside it or a vertex is at least as near.
  void bowlFaceContact(const RigidBody& a, int i, const fcl::Transform3d& X,
                       const SupportBound& support_bound, int t, double margin,
                       std::vector<RigidContact>& out) const {
    const Eigen::Vector3d m = bowl->normals.col(t);
    // Culled first, from the triangle's centroid (in its plane to rounding, so with a slack for
    // the tests below that measure from a corner): a body whose centre is behind the plane or
    // farther in front than its bounding radius and the margin; a face whose contact would have
    // its foot (below) within the margin of the triangle, or a rim that comes within the margin
    // of the body, has the projection of the body's centre on its plane within the bounding
    // radius of the triangle grown by the margin.
    const Eigen::Vector3d r = a.x - bowl->centroids.col(t);
    const double along = m.dot(r);
    const double slack = bowl->centroid_slack;
    if (along < -slack || along - a.bounding_radius > margin + slack) return;
    const double reach = a.bounding_radius + bowl->radii[std::size_t(t)] +
                         bowl->corner_factors[std::size_t(t)] * margin;
    if (r.squaredNorm() - along * along > reach * reach) return;
    if (m.squaredNorm() == 0) return;
    const fcl::TriangleP<double>& tri = triangles[std::size_t(t)];
    // A body's centre behind a face is on the solid's side of it: that face is the far side
    // of a wall (the bowl's outside, seen from its cavity); the near side answers.
    const double s = m.dot(a.x - tri.a);
    if (s < 0 || s - a.bounding_radius > margin) return;
    const Eigen::Vector3d m_body = a.q.inverse() * m;
    if (s - support_bound(-m_body) > margin) return;
    const Eigen::Vector3d support = a.shape->supportPoint(-m_body);  // body frame
    const double h = -m_body.dot(support);
    if (s - h > margin) return;
    if (bowl->convex_edge[std::size_t(t)]) {
      bowlRimContact(a, i, X, tri, m, margin, out);
      return;
    }
    const Eigen::Vector3d p = a.toWorld(support);
    const double d = m.dot(p - tri.a);
    if (d > margin) return;
    // The exact model: the foot may leave the triangle during the step, so a face whose foot
    // is within the margin of it constrains too. Beyond a concave or flat edge the face's plane
    // lies behind the bowl's surface, so it never holds a body off the surface there; without
    // it, a body that slides or falls fast across the faces meets faces it had no contact with
    // until the next detection. (The vertex models keep the paper-like rule: the foot on the
    // triangle.)
    const Eigen::Vector3d foot = p - d * m;
    const bool exact = model == ContactModel::kExact;
    if (outsideTriangle(foot, tri, m) > (exact ? margin : 0.0)) return;
    RigidContact c;
    c.a = i;
    c.b = -1;
    c.distance = d;
    c.n = m;
    c.r_a = support;
    c.r_b = foot;
    c.follows_support = exact;
    out.push_back(c);
  }

  /// The body against a triangle with a convex edge (face normal m), through the library's
  /// superellipsoid–triangle pair. At a rim the triangle's nearest point may be on an edge,
  /// where it has no normal: a separates along the witnesses' difference (apart: w_a − w_b;
  /// overlapping, the witnesses are the support points along the separating direction:
  /// w_b − w_a), or along the face's normal where they coincide.
  void bowlRimContact(const RigidBody& a, int i, const fcl::Transform3d& X,
                      const fcl::TriangleP<double>& tri, const Eigen::Vector3d& m, double margin,
                      std::vector<RigidContact>& out) const {
    fcl::DistanceRequestd request;
    request.enable_nearest_points = true;
    request.enable_signed_distance = true;
    fcl::DistanceResultd result;
    const double d =
        fse::distance(a.shape.get(), X, &tri, fcl::Transform3d::Identity(), request, result);
    if (!(d <= margin)) return;
    const Eigen::Vector3d& w_a = result.nearest_points[0];
    const Eigen::Vector3d& w_b = result.nearest_points[1];
    const Eigen::Vector3d gap = d >= 0 ? Eigen::Vector3d(w_a - w_b) : Eigen::Vector3d(w_b - w_a);
    const double length = gap.norm();
    const Eigen::Vector3d n = length > 1e-9 * a.bounding_radius ? Eigen::Vector3d(gap / length) : m;
    out.push_back(contactAt(a, i, nullptr, -1, d, w_a, w_b, n));
  }

  /// The contacts of one step for `pair_model`; `measuring`: the exact pair's contact only,
  /// for leastDistance (its manifold points add no distance the pair has not found).
  void collect(const std::vector<RigidBody>& bodies, double tolerance,
               const std::vector<double>& travel, ContactModel pair_model, bool measuring,
               std::vector<RigidContact>& out) {
    collectJobs(bodies, tolerance, travel);
    skin = kRigidSkinPerTolerance * tolerance;
    if (!measuring && pair_model == ContactModel::kExact) attachPlaces(bodies.size());
    const bool vertex_model =
        pair_model == ContactModel::kVertices || pair_model == ContactModel::kPaper;
    if (vertex_model) {
      world_vertices.resize(bodies.size());
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        world_vertices[i] =
            (bodies[i].q.toRotationMatrix() * mesh_vertices[i]).colwise() + bodies[i].x;
      }
    }
    forEachJob([&](const Job& job, std::vector<RigidContact>& slot) {
      if (pair_model == ContactModel::kMesh) {
        // FCL's mesh distance looks for the nearest of all the bowl's triangles: a body the
        // bowl's grid finds nothing near is culled first, as the other models cull.
        if (job.b >= 0 || bowlNear(bodies[std::size_t(job.a)], job.margin)) {
          meshes->contacts(bodies, job.a, job.b, job.margin, slot);
        }
      } else if (job.b < 0) {
        bowlContacts(bodies[std::size_t(job.a)], job.a, job.margin, slot);
      } else if (vertex_model) {
        verticesAgainst(bodies, job.a, job.b, job.margin, slot);
        verticesAgainst(bodies, job.b, job.a, job.margin, slot);
      } else {
        exactPair(bodies, job.a, job.b, job.margin, measuring ? nullptr : job.places, slot);
      }
    });
    out.clear();
    for (const auto& slot : slots) out.insert(out.end(), slot.begin(), slot.end());
  }
};

RigidContact contactAt(const RigidBody& a, int ia, const RigidBody* b, int ib, double d,
                       const Eigen::Vector3d& w_a, const Eigen::Vector3d& w_b,
                       const Eigen::Vector3d& n) {
  RigidContact c;
  c.a = ia;
  c.b = ib;
  c.distance = d;
  c.n = n;
  c.r_a = a.q.inverse() * (w_a - a.x);
  c.r_b = b != nullptr ? Eigen::Vector3d(b->q.inverse() * (w_b - b->x)) : w_b;
  return c;
}

void followSupport(const std::vector<RigidBody>& bodies, RigidContact& c) {
  const RigidBody& a = bodies[std::size_t(c.a)];
  c.r_a = a.shape->supportPoint(a.q.inverse() * -c.n);
  if (c.b >= 0) {
    const RigidBody& b = bodies[std::size_t(c.b)];
    c.r_b = b.shape->supportPoint(b.q.inverse() * c.n) + c.support_offset * (b.q.inverse() * c.n);
  } else {
    const Eigen::Vector3d p_a = a.toWorld(c.r_a);
    c.r_b = p_a - (p_a - c.r_b).dot(c.n) * c.n;  // the foot on the same plane
  }
}

RigidContactFinder::RigidContactFinder(const std::vector<RigidBody>& bodies, const StaticMesh* bowl,
                                       ContactModel model, int mesh_vertices, int threads)
    : impl_(std::make_unique<Impl>()) {
  impl_->model = model;
  impl_->bowl = bowl;
  if (bowl != nullptr) {
    impl_->grid = MeshGrid(*bowl);
    for (const RigidBody& body : bodies) impl_->support_bounds.emplace_back(*body.shape);
    for (const auto& t : bowl->triangles) {
      impl_->triangles.emplace_back(bowl->vertices.col(t[0]), bowl->vertices.col(t[1]),
                                    bowl->vertices.col(t[2]));
    }
  }
  if (model == ContactModel::kMesh) {
    impl_->meshes = std::make_unique<RigidMeshContact>(bodies, bowl, mesh_vertices);
  } else if (model != ContactModel::kExact) {
    for (const RigidBody& body : bodies) {
      const fse::TriangleMesh<double> mesh = fse::tessellate(*body.shape, mesh_vertices);
      Eigen::Matrix3Xd v(3, long(mesh.vertices.size()));
      for (std::size_t k = 0; k < mesh.vertices.size(); ++k) v.col(long(k)) = mesh.vertices[k];
      impl_->mesh_vertices.push_back(v);
    }
  }
  // Threads come from the jobs; each batched call runs on its job's thread.
  impl_->exact_options.threads = 1;
  impl_->model_options.threads = 1;
  if (model == ContactModel::kPaper) {
    impl_->model_options.distance.method = fse::DistanceMethod::kPaper;
    impl_->model_options.distance.max_iterations = 10;  // the tolerance per body (above)
  }
  if (threads != 1) {
    impl_->arena = threads > 1 ? std::make_unique<tbb::task_arena>(threads)
                               : std::make_unique<tbb::task_arena>();
  }
}

RigidContactFinder::~RigidContactFinder() = default;

void RigidContactFinder::find(const std::vector<RigidBody>& bodies, double tolerance,
                              const std::vector<double>& travel, std::vector<RigidContact>& out) {
  impl_->collect(bodies, tolerance, travel, impl_->model, false, out);
}

double RigidContactFinder::leastDistance(const std::vector<RigidBody>& bodies, double reach) {
  thread_local std::vector<RigidContact> contacts;
  impl_->collect(bodies, reach, std::vector<double>(bodies.size(), 0.0), ContactModel::kExact, true,
                 contacts);
  double least = std::numeric_limits<double>::infinity();
  for (const RigidContact& c : contacts) least = std::min(least, c.distance);
  return least;
}

}  // namespace fse_sim
