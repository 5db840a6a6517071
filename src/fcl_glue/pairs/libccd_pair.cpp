#include "fcl_glue/pairs/libccd_pair.h"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl/narrowphase/detail/convexity_based_algorithm/gjk_libccd.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include <cmath>
#include <exception>

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

/// The signed distance through libccd, as a hit (points in world coordinates), with the
/// iteration limits and tolerances of a default GJKSolver_libccd.
template <typename S, typename Other>
PairHit<S> ccdHit(const Pair<S>& pair, const Other& other) {
  const fcl::detail::GJKSolver_libccd<S> solver;
  const CcdObject<S> a = ccdObject(*pair.shape, *pair.X_WS);
  const CcdObject<S> b = ccdObject(other, *pair.X_WO);
  S d = S(0);
  Vector3<S> on_shape = pair.X_WS->translation(), on_other = pair.X_WO->translation();
  bool answered = false;
  try {
    fcl::detail::GJKSignedDistance<S>(a.object, a.support, b.object, b.support,
                                      solver.max_distance_iterations, solver.distance_tolerance, &d,
                                      &on_shape, &on_other);
    answered = std::isfinite(d) && on_shape.allFinite() && on_other.allFinite();
  } catch (const std::exception&) {
    // libccd's penetration algorithm gave up ("origin outside the polytope"): MPR below.
  }
  Vector3<S> normal = on_other - on_shape;  // separated: from the shape to the other
  if (!answered || d < S(0)) {
    Vector3<S> pos, n;
    S depth = S(0);
    if (fcl::detail::GJKCollide<S>(a.object, a.support, a.centre, b.object, b.support, b.centre,
                                   solver.max_collision_iterations, solver.collision_tolerance,
                                   &pos, &depth, &n) &&
        n.allFinite() && std::isfinite(depth)) {
      // MPR's normal points from the shape (the first object) to the other.
      if (!answered) {
        d = -depth;
        on_shape = pos + S(0.5) * depth * n;
        on_other = pos - S(0.5) * depth * n;
      }
      normal = n;
    } else if (!answered) {
      d = S(0);
    }
  }
  if (!(normal.norm() > S(0)) || !normal.allFinite()) {
    normal = pair.X_WO->translation() - pair.X_WS->translation();
    if (!(normal.norm() > S(0))) normal = Vector3<S>::UnitZ();
  }
  return {d, on_other, on_shape, normal.normalized(), -1};
}

}  // namespace

template <typename S>
std::optional<PairHit<S>> libccdHit(const Pair<S>& pair) {
  if (const auto* o = dynamic_cast<const fcl::Box<S>*>(pair.other)) return ccdHit(pair, *o);
  if (const auto* o = dynamic_cast<const fcl::Capsule<S>*>(pair.other)) return ccdHit(pair, *o);
  if (const auto* o = dynamic_cast<const fcl::Cylinder<S>*>(pair.other)) return ccdHit(pair, *o);
  if (const auto* o = dynamic_cast<const fcl::Cone<S>*>(pair.other)) return ccdHit(pair, *o);
  if (const auto* o = dynamic_cast<const fcl::Convex<S>*>(pair.other)) return ccdHit(pair, *o);
  if (const auto* o = dynamic_cast<const fcl::TriangleP<S>*>(pair.other)) {
    return ccdHit(pair, *o);
  }
  return std::nullopt;
}

#define FSE_INSTANTIATE_LIBCCD_PAIR(S) template std::optional<PairHit<S>> libccdHit(const Pair<S>&);
FSE_INSTANTIATE_LIBCCD_PAIR(float)
FSE_INSTANTIATE_LIBCCD_PAIR(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
