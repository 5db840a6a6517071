#ifndef FCL_SUPERELLIPSOID_TEST_PAIR_CONSTRUCTION_H
#define FCL_SUPERELLIPSOID_TEST_PAIR_CONSTRUCTION_H

// Shape pairs with a known distance, for the pair tests and the benchmark's ground truth; shares
// no code with src/. A surface point a of a superellipsoid and its outward normal u come from the
// parametric form (the paper's Eq. 4) and the implicit function's gradient, in long double; the
// partner is posed so that its own surface point with outward normal −u sits at a + d·u. For
// d ≥ 0 the slab between the two tangent planes separates the shapes, so their distance is d and
// the witnesses are a and a + d·u (unique: the superellipsoid is strictly convex). For d < 0 the
// shapes overlap by at least |d| along u (the depth, the shortest separating move, is at most
// |d|).

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl_superellipsoid/superellipsoid.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <limits>
#include <memory>
#include <random>
#include <vector>

namespace fcl_superellipsoid {
namespace test {

using LD = long double;
using V3 = Eigen::Matrix<LD, 3, 1>;
using M3 = Eigen::Matrix<LD, 3, 3>;

inline LD spow(LD c, LD e) { return c < 0 ? -std::pow(-c, e) : std::pow(c, e); }

/// A superellipsoid's surface point at (η, ω) (paper Eq. 4) and its outward unit normal, the
/// normalised gradient of F = ((x/a1)^(2/ε1) + (y/a2)^(2/ε1))^(ε1/ε2) + (z/a3)^(2/ε2).
struct SurfacePoint {
  V3 x, n;
};

inline SurfacePoint superellipsoidPoint(const V3& a, LD e1, LD e2, LD eta, LD omega) {
  const V3 x(a[0] * spow(std::cos(eta), e2) * spow(std::cos(omega), e1),
             a[1] * spow(std::cos(eta), e2) * spow(std::sin(omega), e1),
             a[2] * spow(std::sin(eta), e2));
  const LD px = std::pow(std::abs(x[0] / a[0]), 2 / e1),
           py = std::pow(std::abs(x[1] / a[1]), 2 / e1);
  const LD inner = std::pow(px + py, e1 / e2 - 1);
  auto sgn = [](LD v) { return v < 0 ? LD(-1) : LD(1); };
  V3 g((2 / e2) * inner * px / std::abs(x[0]) * sgn(x[0]),
       (2 / e2) * inner * py / std::abs(x[1]) * sgn(x[1]),
       (2 / e2) * std::pow(std::abs(x[2] / a[2]), 2 / e2) / std::abs(x[2]) * sgn(x[2]));
  return {x, g.normalized()};
}

/// The support function of a superellipsoid (docs/math.md: the nested norm with the dual
/// exponents q = 2/(2 − ε)), evaluated directly.
inline LD superellipsoidSupport(const V3& a, LD e1, LD e2, const V3& u) {
  const LD q1 = 2 / (2 - e1), q2 = 2 / (2 - e2);
  const LD r =
      std::pow(std::pow(std::abs(a[0] * u[0]), q1) + std::pow(std::abs(a[1] * u[1]), q1), 1 / q1);
  return std::pow(std::pow(r, q2) + std::pow(std::abs(a[2] * u[2]), q2), 1 / q2);
}

/// Random rotation with R·m = target (a random twist about target).
inline M3 rotationTaking(const V3& m, const V3& target, std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  const M3 align = Eigen::Quaternion<LD>::FromTwoVectors(m, target).toRotationMatrix();
  return Eigen::AngleAxis<LD>(LD(angle(rng)), target).toRotationMatrix() * align;
}

template <typename S>
fcl::Transform3<S> pose(const M3& R, const V3& t) {
  fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  X.linear() = R.cast<S>();
  X.translation() = t.cast<S>();
  return X;
}

inline M3 randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaternion<LD>(LD(g(rng)), LD(g(rng)), LD(g(rng)), LD(g(rng)))
      .normalized()
      .toRotationMatrix();
}

/// A random superellipsoid: exponents in [e_low, e_high] (by default [0.1, 1.9]), radii with
/// aspect up to 10:1 around `size`.
struct RandomShape {
  V3 radii;
  LD e1, e2;
};

inline RandomShape randomShape(std::mt19937& rng, LD size, double e_low = 0.1,
                               double e_high = 1.9) {
  std::uniform_real_distribution<double> e(e_low, e_high), r(0.1, 1.0);
  return {V3(size * LD(r(rng)), size * LD(r(rng)), size * LD(r(rng))), LD(e(rng)), LD(e(rng))};
}

/// A random surface point away from the coordinate planes (where the normal of a creased shape
/// is not defined).
inline SurfacePoint randomSurfacePoint(const RandomShape& s, std::mt19937& rng) {
  std::uniform_real_distribution<double> eta(0.05, M_PI / 2 - 0.05), omega(0.05, M_PI / 2 - 0.05);
  std::uniform_int_distribution<int> quadrant(0, 3), hemisphere(0, 1);
  const LD w = LD(omega(rng)) + quadrant(rng) * LD(M_PI / 2);
  const LD h = (hemisphere(rng) ? 1 : -1) * LD(eta(rng));
  return superellipsoidPoint(s.radii, s.e1, s.e2, h, w);
}

/// The superellipsoid side of a constructed pair: the shape posed at X_WA, its witness a and
/// outward normal u (world).
struct Construction {
  RandomShape shape;
  fcl::Transform3<double> X_WA;
  V3 a, u;
};

inline Construction constructShape(std::mt19937& rng, LD size, double e_low = 0.1,
                                   double e_high = 1.9) {
  Construction c;
  c.shape = randomShape(rng, size, e_low, e_high);
  const SurfacePoint p = randomSurfacePoint(c.shape, rng);
  const M3 R = randomRotation(rng);
  std::uniform_real_distribution<double> t(-1, 1);
  const V3 centre = size * V3(LD(t(rng)), LD(t(rng)), LD(t(rng)));
  c.X_WA = pose<double>(R, centre);
  c.a = R * p.x + centre;
  c.u = R * p.n;
  return c;
}

/// Places a partner whose local surface point b_L has outward normal m_L so that it sits at
/// a + d·u with normal −u.
inline fcl::Transform3<double> placePartner(const Construction& c, LD d, const V3& b_L,
                                            const V3& m_L, std::mt19937& rng) {
  const M3 R = rotationTaking(m_L, -c.u, rng);
  return pose<double>(R, c.a + d * c.u - R * b_L);
}

/// A partner with flat faces or edges: its geometry, and a local surface point b_L that is its
/// unique support point along the outward direction m_L.
struct FlatPartner {
  const char* name;
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  V3 b_L, m_L;
};

/// A positive combination of the given directions (a direction strictly inside their cone).
inline V3 insideCone(std::mt19937& rng, std::initializer_list<V3> directions) {
  std::uniform_real_distribution<double> w(0.2, 1.0);
  V3 m = V3::Zero();
  for (const V3& d : directions) m += LD(w(rng)) * d.normalized();
  return m.normalized();
}

inline std::vector<FlatPartner> flatPartners(std::mt19937& rng, LD size) {
  std::uniform_real_distribution<double> r(0.2, 1.0), angle(-M_PI, M_PI);
  std::uniform_int_distribution<int> sign(0, 1);
  auto s = [&] { return sign(rng) ? LD(1) : LD(-1); };
  std::vector<FlatPartner> out;
  {  // box: a vertex
    const V3 h = size * V3(LD(r(rng)), LD(r(rng)), LD(r(rng)));
    const V3 sg(s(), s(), s());
    out.push_back({"box", std::make_shared<fcl::Boxd>(Vector3<double>(2 * h.cast<double>())),
                   h.cwiseProduct(sg),
                   insideCone(rng, {V3(sg[0], 0, 0), V3(0, sg[1], 0), V3(0, 0, sg[2])})});
  }
  {  // capsule: a point of a cap
    const LD radius = size * LD(r(rng)), length = size * LD(r(rng));
    const V3 m =
        insideCone(rng, {V3(0, 0, s()), V3(std::cos(angle(rng)), std::sin(angle(rng)), 0)});
    const LD end = m[2] > 0 ? length / 2 : -length / 2;
    out.push_back({"capsule", std::make_shared<fcl::Capsuled>(double(radius), double(length)),
                   V3(0, 0, end) + radius * m, m});
  }
  {  // cylinder: a point of a rim
    const LD radius = size * LD(r(rng)), length = size * LD(r(rng)), t = LD(angle(rng));
    const LD z = s();
    const V3 radial(std::cos(t), std::sin(t), 0);
    out.push_back({"cylinder", std::make_shared<fcl::Cylinderd>(double(radius), double(length)),
                   radius * radial + V3(0, 0, z * length / 2),
                   insideCone(rng, {radial, V3(0, 0, z)})});
  }
  {  // cone: a point of the base's rim (apex at +length/2)
    const LD radius = size * LD(r(rng)), length = size * LD(r(rng)), t = LD(angle(rng));
    const V3 radial(std::cos(t), std::sin(t), 0);
    out.push_back({"cone", std::make_shared<fcl::Coned>(double(radius), double(length)),
                   radius * radial + V3(0, 0, -length / 2),
                   insideCone(rng, {V3(0, 0, -1), radial + V3(0, 0, radius / length)})});
  }
  {  // convex: a vertex of a tetrahedron
    std::uniform_real_distribution<double> c(-0.2, 0.2);
    std::array<V3, 4> v = {V3(1, 1, 1), V3(1, -1, -1), V3(-1, 1, -1), V3(-1, -1, 1)};
    for (V3& p : v) p = size * (p + V3(LD(c(rng)), LD(c(rng)), LD(c(rng))));
    const V3 centroid = (v[0] + v[1] + v[2] + v[3]) / 4;
    // Faces oriented outward: (i, j, k) with the normal pointing away from the centroid.
    auto vertices = std::make_shared<std::vector<Vector3<double>>>();
    for (const V3& p : v) vertices->push_back(p.cast<double>());
    auto faces = std::make_shared<std::vector<int>>();
    std::vector<V3> normals_at_0;
    for (const std::array<int, 3>& f :
         {std::array<int, 3>{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}) {
      V3 n = (v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]);
      const bool outward = n.dot(v[f[0]] - centroid) > 0;
      faces->insert(faces->end(), {3, f[0], outward ? f[1] : f[2], outward ? f[2] : f[1]});
      if (f[0] == 0) normals_at_0.push_back(outward ? n : V3(-n));
    }
    out.push_back({"convex", std::make_shared<fcl::Convexd>(vertices, 4, faces), v[0],
                   insideCone(rng, {normals_at_0[0], normals_at_0[1], normals_at_0[2]})});
  }
  {  // triangle: a vertex, the normal between the face's and the in-plane outward direction
    const V3 a = size * V3(1, 0, 0), b = size * V3(-0.5, 0.8, 0), c = size * V3(-0.5, -0.8, 0);
    out.push_back(
        {"triangle",
         std::make_shared<fcl::TrianglePd>(a.cast<double>(), b.cast<double>(), c.cast<double>()), a,
         insideCone(rng, {V3(0, 0, s()), a - (a + b + c) / 3})});
  }
  // Contacts on faces, sides and the apex (the other shape's witness still unique: the
  // superellipsoid's, moved by d along u).
  std::uniform_real_distribution<double> inside(-0.9, 0.9), fraction(0.1, 0.9);
  {
    const V3 h = size * V3(LD(r(rng)), LD(r(rng)), LD(r(rng)));
    const LD sg = s();
    out.push_back({"box face", std::make_shared<fcl::Boxd>(Vector3<double>(2 * h.cast<double>())),
                   V3(sg * h[0], LD(inside(rng)) * h[1], LD(inside(rng)) * h[2]), V3(sg, 0, 0)});
  }
  {
    const LD radius = size * LD(r(rng)), length = size * LD(r(rng)), t = LD(angle(rng));
    const V3 radial(std::cos(t), std::sin(t), 0);
    out.push_back({"capsule side", std::make_shared<fcl::Capsuled>(double(radius), double(length)),
                   radius * radial + V3(0, 0, LD(inside(rng)) * length / 2), radial});
    out.push_back({"cylinder side",
                   std::make_shared<fcl::Cylinderd>(double(radius), double(length)),
                   radius * radial + V3(0, 0, LD(inside(rng)) * length / 2), radial});
    const LD z = s();
    out.push_back({"cylinder disc",
                   std::make_shared<fcl::Cylinderd>(double(radius), double(length)),
                   LD(fraction(rng)) * radius * radial + V3(0, 0, z * length / 2), V3(0, 0, z)});
    const V3 apex(0, 0, length / 2), rim = radius * radial - apex;
    const V3 side_normal = (length * radial + V3(0, 0, radius)).normalized();
    out.push_back({"cone side", std::make_shared<fcl::Coned>(double(radius), double(length)),
                   apex + LD(fraction(rng)) * (rim - apex), side_normal});
    out.push_back({"cone apex", std::make_shared<fcl::Coned>(double(radius), double(length)), apex,
                   insideCone(rng, {V3(0, 0, 1), side_normal})});
  }
  {
    const V3 a = size * V3(1, 0, 0), b = size * V3(-0.5, 0.8, 0), c = size * V3(-0.5, -0.8, 0);
    const LD u = LD(fraction(rng)) / 2, v = LD(fraction(rng)) / 2;
    out.push_back(
        {"triangle face",
         std::make_shared<fcl::TrianglePd>(a.cast<double>(), b.cast<double>(), c.cast<double>()),
         a + u * (b - a) + v * (c - a), V3(0, 0, s())});
  }
  return out;
}

/// The support function h(u) = max over the geometry of u·x, posed by X (world, long double):
/// the superellipsoid's nested norm (superellipsoidSupport), FCL's shapes in closed form.
inline std::function<LD(const V3&)> supportFunction(const fcl::CollisionGeometryd& g,
                                                    const fcl::Transform3d& X) {
  const M3 R = X.linear().cast<LD>();
  const V3 t = X.translation().cast<LD>();
  std::function<LD(const V3&)> local;
  if (auto* x = dynamic_cast<const Superellipsoidd*>(&g)) {
    const V3 a = x->radii().cast<LD>();
    const LD e1 = x->eps1(), e2 = x->eps2();
    local = [=](const V3& w) { return superellipsoidSupport(a, e1, e2, w); };
  } else if (auto* x = dynamic_cast<const fcl::Ellipsoidd*>(&g)) {
    const V3 a = x->radii.cast<LD>();
    local = [=](const V3& w) { return a.cwiseProduct(w).norm(); };
  } else if (auto* x = dynamic_cast<const fcl::Sphered*>(&g)) {
    const LD r = x->radius;
    local = [=](const V3& w) { return r * w.norm(); };
  } else if (auto* x = dynamic_cast<const fcl::Boxd*>(&g)) {
    const V3 h = x->side.cast<LD>() / 2;
    local = [=](const V3& w) { return h.dot(w.cwiseAbs()); };
  } else if (auto* x = dynamic_cast<const fcl::Capsuled*>(&g)) {
    const LD r = x->radius, h = LD(x->lz) / 2;
    local = [=](const V3& w) { return r * w.norm() + h * std::abs(w[2]); };
  } else if (auto* x = dynamic_cast<const fcl::Cylinderd*>(&g)) {
    const LD r = x->radius, h = LD(x->lz) / 2;
    local = [=](const V3& w) { return r * std::hypot(w[0], w[1]) + h * std::abs(w[2]); };
  } else if (auto* x = dynamic_cast<const fcl::Coned*>(&g)) {
    const LD r = x->radius, h = LD(x->lz) / 2;
    local = [=](const V3& w) { return std::max(h * w[2], r * std::hypot(w[0], w[1]) - h * w[2]); };
  } else if (auto* x = dynamic_cast<const fcl::Convexd*>(&g)) {
    std::vector<V3> v;
    for (const auto& p : x->getVertices()) v.push_back(p.cast<LD>());
    local = [=](const V3& w) {
      LD best = -std::numeric_limits<LD>::infinity();
      for (const V3& p : v) best = std::max(best, w.dot(p));
      return best;
    };
  } else if (auto* x = dynamic_cast<const fcl::TrianglePd*>(&g)) {
    const V3 a = x->a.cast<LD>(), b = x->b.cast<LD>(), c = x->c.cast<LD>();
    local = [=](const V3& w) { return std::max({w.dot(a), w.dot(b), w.dot(c)}); };
  } else {
    return nullptr;
  }
  return [=](const V3& u) { return local(R.transpose() * u) + u.dot(t); };
}

/// Moves the unit direction v downhill on f by a pattern search on the sphere: `polls` directions
/// around v at an angle step from `first_step` rad, halved down to `floor`, at most `max_moves`
/// moves at each step; f_v is f(v), kept current.
template <typename F>
void patternSearch(const F& f, V3& v, LD& f_v, int polls, LD floor, LD first_step = 0.05,
                   int max_moves = 64) {
  for (LD step = first_step; step > floor; step /= 2) {
    bool moved = true;
    for (int moves = 0; moved && moves < max_moves; ++moves) {
      moved = false;
      const V3 t1 = v.unitOrthogonal(), t2 = v.cross(t1);
      for (int j = 0; j < polls && !moved; ++j) {
        const LD angle = LD(2 * M_PI) * j / polls;
        const V3 w = (v + step * (std::cos(angle) * t1 + std::sin(angle) * t2)).normalized();
        const LD fw = f(w);
        if (fw < f_v) {
          f_v = fw;
          v = w;
          moved = true;
        }
      }
    }
  }
}

/// The penetration depth of two convex shapes, min over unit v of h_A(v) + h_B(−v) (negative:
/// their distance), by a long-double search: a Fibonacci lattice of `lattice` directions, then a
/// pattern search (16 directions, the step halved to 1e-13 rad) from the best 8. `direction`, if
/// given, receives the minimising direction.
inline LD referenceDepth(const std::function<LD(const V3&)>& h_a,
                         const std::function<LD(const V3&)>& h_b, int lattice = 20000,
                         V3* direction = nullptr) {
  auto F = [&](const V3& v) { return h_a(v) + h_b(-v); };
  const int n = lattice;
  std::vector<std::pair<LD, V3>> samples;
  for (int i = 0; i < n; ++i) {
    const LD z = 1 - (2 * LD(i) + 1) / n, r = std::sqrt(std::max(LD(0), 1 - z * z));
    const LD phi = LD(2.39996322972865332) * i;
    const V3 v(r * std::cos(phi), r * std::sin(phi), z);
    samples.push_back({F(v), v});
  }
  const int starts = 8;
  std::partial_sort(samples.begin(), samples.begin() + starts, samples.end(),
                    [](const auto& x, const auto& y) { return x.first < y.first; });
  LD best = samples[0].first;
  if (direction != nullptr) *direction = samples[0].second;
  for (int k = 0; k < starts; ++k) {
    V3 v = samples[k].second;
    LD f = samples[k].first;
    patternSearch(F, v, f, 16, LD(1e-13));
    if (f < best && direction != nullptr) *direction = v;
    best = std::min(best, f);
  }
  return best;
}

/// The same depth near a known minimiser: a pattern search from the unit direction v (64
/// directions, the step from `first_step` halved to 1e-15 rad), for configurations that differ
/// from the one v was found for by a small move (finite differences). Beside a box-like
/// shape's face centre F is nearly kinked (its support function's Hessian grows without bound
/// there), and 16 directions stalled a few 1e-6 of the value short. `max_moves` at each step:
/// a long narrow valley of F (an overlap of elongated shapes) takes many; `direction`, if given,
/// receives the minimiser.
inline LD referenceDepthNear(const std::function<LD(const V3&)>& h_a,
                             const std::function<LD(const V3&)>& h_b, V3 v, LD first_step,
                             int max_moves = 64, V3* direction = nullptr) {
  auto F = [&](const V3& w) { return h_a(w) + h_b(-w); };
  LD f = F(v);
  patternSearch(F, v, f, 64, LD(1e-15), first_step, max_moves);
  if (direction != nullptr) *direction = v;
  return f;
}

}  // namespace test
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TEST_PAIR_CONSTRUCTION_H
