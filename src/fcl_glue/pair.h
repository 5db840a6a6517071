#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIR_H

// Internal: a query as FCL hands it over, and the answer as FCL wants it back. A query arrives
// as (o1, tf1, o2, tf2) in the caller's order; the narrowphase sees it as (superellipsoid,
// other) (narrowphase/shape_pair.h) and reports a PairHit; the writers below put that hit into
// FCL's result in the caller's order, with FCL's conventions (fcl_integration.h documents them
// for the user).

#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>
#include <fcl/narrowphase/distance_request.h>
#include <fcl/narrowphase/distance_result.h>

#include <typeinfo>

#include "fcl_superellipsoid/superellipsoid.h"
#include "narrowphase/shape_pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// g as FCL's geometry class T, or nullptr. A dynamic_cast that fails compares type names with
/// strcmp across shared libraries, and a successful one walks the class hierarchy: both cost
/// more than a halfspace pair's own arithmetic, so the exact type is compared first (one
/// comparison of type_info objects); a subclass of T still gets the dynamic_cast. The caller
/// has compared g's node type already (a user's geometry may report any node type).
template <typename T, typename S>
const T* geometryAs(const fcl::CollisionGeometry<S>* g) {
  if (typeid(*g) == typeid(T)) return static_cast<const T*>(g);
  return dynamic_cast<const T*>(g);
}

/// g as a Superellipsoid (node type BV_UNKNOWN), or nullptr, where g's node type (read by the
/// caller: one virtual call per geometry and query) is `node_type`.
template <typename S>
const Superellipsoid<S>* asSuperellipsoid(const fcl::CollisionGeometry<S>* g,
                                          fcl::NODE_TYPE node_type) {
  return node_type == fcl::BV_UNKNOWN ? geometryAs<Superellipsoid<S>>(g) : nullptr;
}

/// g as a Superellipsoid, or nullptr (reads g's node type).
template <typename S>
const Superellipsoid<S>* asSuperellipsoid(const fcl::CollisionGeometry<S>* g) {
  return asSuperellipsoid(g, g->getNodeType());
}

/// The pair as (superellipsoid, other) for the narrowphase, remembering the caller's order.
template <typename S>
struct Pair : ShapePair<S> {
  const fcl::CollisionGeometry<S>* o1 = nullptr;  // the caller's order
  const fcl::CollisionGeometry<S>* o2 = nullptr;
  const fcl::CollisionGeometry<S>* other = nullptr;
  bool shape_first = true;                      // the shape is o1
  fcl::NODE_TYPE other_type = fcl::BV_UNKNOWN;  // other->getNodeType(), read once
};

/// The pair, or one with shape == nullptr if neither geometry is a superellipsoid. Of two
/// superellipsoids, o1 is the shape and o2 the other.
template <typename S>
Pair<S> makePair(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                 const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2) {
  const fcl::NODE_TYPE t1 = o1->getNodeType(), t2 = o2->getNodeType();
  if (const auto* s1 = asSuperellipsoid(o1, t1)) return {{s1, &tf1, &tf2}, o1, o2, o2, true, t2};
  if (const auto* s2 = asSuperellipsoid(o2, t2)) return {{s2, &tf2, &tf1}, o1, o2, o1, false, t1};
  Pair<S> none;
  none.o1 = o1;
  none.o2 = o2;
  return none;
}

/// Offers a hit to FCL's distance result (which keeps the smallest): b1/b2 and the nearest
/// points in the caller's order; −1 for a penetration when the request is unsigned.
template <typename S>
void updateDistance(const Pair<S>& pair, const PairHit<S>& hit,
                    const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
  constexpr int kNone = fcl::DistanceResult<S>::NONE;
  const S d = (hit.distance < S(0) && !request.enable_signed_distance) ? S(-1) : hit.distance;
  const int b1 = pair.shape_first ? kNone : hit.other_primitive;
  const int b2 = pair.shape_first ? hit.other_primitive : kNone;
  if (request.enable_nearest_points) {
    const Vector3<S>& p1 = pair.shape_first ? hit.on_shape : hit.on_other;
    const Vector3<S>& p2 = pair.shape_first ? hit.on_other : hit.on_shape;
    result.update(d, pair.o1, pair.o2, b1, b2, p1, p2);
  } else {
    result.update(d, pair.o1, pair.o2, b1, b2);
  }
}

/// Adds a contact at pos. FCL's normal points from o1 to o2: the other geometry leaves the
/// shape along the shape's outward normal, so that is the normal when the shape is o1, and its
/// opposite otherwise. Without details, pos, normal and depth are zero.
template <typename S>
void addContact(const Pair<S>& pair, const PairHit<S>& hit, const Vector3<S>& pos,
                bool with_details, fcl::CollisionResult<S>& result) {
  constexpr int kNone = fcl::Contact<S>::NONE;
  fcl::Contact<S> c(pair.o1, pair.o2, pair.shape_first ? kNone : hit.other_primitive,
                    pair.shape_first ? hit.other_primitive : kNone);
  c.pos.setZero();
  c.normal.setZero();
  c.penetration_depth = S(0);
  if (with_details) {
    c.pos = pos;
    c.normal = pair.shape_first ? hit.normal : Vector3<S>(-hit.normal);
    c.penetration_depth = -hit.distance;
  }
  result.addContact(c);
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIR_H
