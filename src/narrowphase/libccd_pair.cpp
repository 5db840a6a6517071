#include "narrowphase/libccd_pair.h"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl/narrowphase/detail/convexity_based_algorithm/gjk_libccd.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include <cmath>
#include <csetjmp>

#include "fcl_superellipsoid/gjk_support.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

/// A geometry as libccd sees it: an opaque object and its support and centre functions.
template <typename S>
struct CcdObject {
  void* object;
  fcl::detail::GJKSupportFunction support;
  fcl::detail::GJKCenterFunction centre;
  void (*destroy)(void*);
  ~CcdObject() { destroy(object); }
};

template <typename S, typename Shape>
CcdObject<S> ccdObject(const Shape& shape, const fcl::Transform3<S>& X) {
  using Init = fcl::detail::GJKInitializer<S, Shape>;
  return {Init::createGJKObject(shape, X), Init::getSupportFunction(), Init::getCenterFunction(),
          &Init::deleteGJKObject};
}

/// FCL has no GJKInitializer for its triangle; its own triangle functions instead.
template <typename S>
CcdObject<S> ccdObject(const fcl::TriangleP<S>& t, const fcl::Transform3<S>& X) {
  return {fcl::detail::triCreateGJKObject(t.a, t.b, t.c, X), fcl::detail::triGetSupportFunction(),
          fcl::detail::triGetCenterFunction(), &fcl::detail::triDeleteGJKObject};
}

/// A libccd object whose support calls are counted: libccd's MPR refines its portal in a loop
/// with no iteration limit, and on some inputs (a float cylinder pair, docs/hardening.md →
/// "Findings", 15) the portal never reaches the tolerance. Past `limit` calls (four times the
/// iteration limit of MPR's last phase; its first two phases take a few calls each) the call
/// leaves libccd with longjmp (boundedCollide), and ccdHit answers as if MPR had found no
/// overlap. It leaves the same way when MPR asks for the support of a direction that is not
/// finite (its portal's normals, cross products of cross products of the shapes' coordinates,
/// overflow on a triangle of 1e50 × size around the shape in double, 1e19 in float: finding 23):
/// the support functions would refuse it with an exception, which must not cross libccd's C
/// frames. What the jump skips: libccd's MPR, which keeps its simplices on the stack and
/// allocates nothing, and FCL's GJKCollide, whose locals are plain C structures; no destructor.
struct BoundedObject {
  void* object;
  fcl::detail::GJKSupportFunction support;
  fcl::detail::GJKCenterFunction centre;
  int* calls;
  int limit;
  std::jmp_buf* bail;
};

void boundedSupport(const void* o, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const auto* b = static_cast<const BoundedObject*>(o);
  if (++*b->calls > b->limit ||
      !(std::isfinite(direction->v[0]) && std::isfinite(direction->v[1]) &&
        std::isfinite(direction->v[2]))) {
    std::longjmp(*b->bail, 1);
  }
  b->support(b->object, direction, out);
}
void boundedCentre(const void* o, ccd_vec3_t* out) {
  const auto* b = static_cast<const BoundedObject*>(o);
  b->centre(b->object, out);
}

/// FCL's GJKCollide (libccd's MPR) on bounded objects; false where the bound was reached. (Its
/// own function, so that no local of the caller lives across setjmp.)
template <typename S>
bool boundedCollide(BoundedObject* a, BoundedObject* b, unsigned int max_iterations, S tolerance,
                    Vector3<S>* pos, S* depth, Vector3<S>* normal) {
  std::jmp_buf bail;
  a->bail = b->bail = &bail;
  if (setjmp(bail) != 0) return false;
  return fcl::detail::GJKCollide<S>(a, &boundedSupport, &boundedCentre, b, &boundedSupport,
                                    &boundedCentre, max_iterations, tolerance, pos, depth, normal);
}

/// libccd's overlap (MPR) as a hit (points in world coordinates), with the iteration limits and
/// tolerances of a default GJKSolver_libccd, and a bound on its support calls (BoundedObject).
/// (Neither libccd's GJK distance, which aborts on some inputs — libccd_pair.h —, nor its polytope
/// expansion, FCL's signed distance, which throws "origin outside the polytope" on some overlaps
/// and leaks its polytope when it does.)
template <typename S, typename Other>
PairHit<S> ccdHit(const ShapePair<S>& pair, const Other& other) {
  const fcl::detail::GJKSolver_libccd<S> solver;
  const CcdObject<S> a = ccdObject(*pair.shape, *pair.X_WS);
  const CcdObject<S> b = ccdObject(other, *pair.X_WO);
  Vector3<S> pos, n;
  S depth = S(0);
  int calls = 0;
  const int limit = 4 * int(solver.max_collision_iterations);
  BoundedObject bounded_a{a.object, a.support, a.centre, &calls, limit, nullptr};
  BoundedObject bounded_b{b.object, b.support, b.centre, &calls, limit, nullptr};
  const bool overlap = boundedCollide<S>(&bounded_a, &bounded_b, solver.max_collision_iterations,
                                         solver.collision_tolerance, &pos, &depth, &n) &&
                       pos.allFinite() && n.allFinite() && n.norm() > S(0) && std::isfinite(depth);
  if (overlap) {
    // MPR's normal points from the shape (the first object) to the other; the witnesses are
    // its contact point moved half the depth each way.
    n.normalize();
    return {-depth, Vector3<S>(pos - S(0.5) * depth * n), Vector3<S>(pos + S(0.5) * depth * n), n,
            -1};
  }
  // No overlap: distance 0 on the line of the centres.
  Vector3<S> towards = pair.X_WO->translation() - pair.X_WS->translation();
  if (!(towards.norm() > S(0))) towards = Vector3<S>::UnitZ();
  towards.normalize();
  const Vector3<S> p =
      *pair.X_WS * pair.shape->supportPoint(Vector3<S>(pair.X_WS->linear().transpose() * towards));
  return {S(0), p, p, towards, -1};
}

}  // namespace

template <typename S, typename Other>
std::optional<PairHit<S>> libccdHit(const ShapePair<S>& pair, const Other& other) {
  return ccdHit(pair, other);
}

#define FSE_INSTANTIATE_LIBCCD_PAIR(S)                                                        \
  template std::optional<PairHit<S>> libccdHit(const ShapePair<S>&, const fcl::Box<S>&);      \
  template std::optional<PairHit<S>> libccdHit(const ShapePair<S>&, const fcl::Capsule<S>&);  \
  template std::optional<PairHit<S>> libccdHit(const ShapePair<S>&, const fcl::Cylinder<S>&); \
  template std::optional<PairHit<S>> libccdHit(const ShapePair<S>&, const fcl::Cone<S>&);     \
  template std::optional<PairHit<S>> libccdHit(const ShapePair<S>&, const fcl::Convex<S>&);   \
  template std::optional<PairHit<S>> libccdHit(const ShapePair<S>&, const fcl::TriangleP<S>&);
FSE_INSTANTIATE_LIBCCD_PAIR(float)
FSE_INSTANTIATE_LIBCCD_PAIR(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
