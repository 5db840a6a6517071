#ifndef FCL_SUPERELLIPSOID_FCL_INTEGRATION_H
#define FCL_SUPERELLIPSOID_FCL_INTEGRATION_H

/// @file
/// The superellipsoid inside FCL's own query calls.
///
/// 1. FCL's function tables. The library registers entries for the narrow-phase solver type
///    fcl::detail::GJKSolver_libccd<S> (float and double) in the slots of FCL's free node
///    type BV_UNKNOWN, guarded by a dynamic type check. So these calls work with a
///    Superellipsoid on either side:
///
///        fcl::detail::GJKSolver_libccd<double> solver;
///        fcl::distance(&o1, &o2, &solver, request, result);   // and the geometry + pose form
///        fcl::collide(&o1, &o2, &solver, request, result);
///
///    Registration happens once, thread-safely, when the first Superellipsoid is constructed
///    (or by registerWithFcl()). The plain fcl::distance(&o1, &o2, request, result) of a
///    Debian FCL runs inside libfcl with libfcl's private tables: it prints FCL's "not
///    supported" warning for a Superellipsoid and returns (no crash), unless the opt-in
///    interposer is linked (interpose.h). Results of the
///    solver-taking calls follow FCL's conventions: for shape–mesh pairs FCL calls the table
///    as (mesh, shape) and does not swap back, so o1/b1/nearest_points[0] refer to the mesh.
///
/// 2. A drop-in front end with the signatures of fcl::distance and fcl::collide (no solver).
///    Pairs with a Superellipsoid are answered by the same functions as the table entries,
///    in the caller's argument order; every other pair goes to plain FCL unchanged. The
///    broadphase callbacks below are FCL's DefaultCollisionFunction / DefaultDistanceFunction
///    with the front end inside.
///
/// Bad input (the front end and the table entries): a null object or geometry, or a pose that
/// is not finite, is refused with std::invalid_argument naming it (docs/hardening.md).
///
/// Counters of the traversal behind these calls (how many vertices a query reached) are in
/// diagnostics.h.
///
/// Pairs: Superellipsoid vs fcl::BVHModel<BV> for every BV type (triangle meshes and point
/// clouds: the model's vertices are the query points, paper §3), and vs every FCL shape and
/// another Superellipsoid (Sphere, Ellipsoid, Halfspace, Plane, Capsule, Box, Convex, TriangleP,
/// Cylinder, Cone): one hit per pair, exact where the library has its own solver, libccd with
/// the exact support function (gjk_support.h) where shapes with flat faces overlap. Their
/// conventions are below and in docs/pairs.md. A geometry the library does not know is refused
/// with FCL's warning.
///
/// Conventions of the mesh pairs, for the front end and the table entries alike:
/// - distance: the minimum signed distance over the vertices, computed with the shape's
///   queryOptions(). b1/b2 name the vertex index on the
///   mesh side and fcl::DistanceResult::NONE on the shape side; nearest_points (if
///   request.enable_nearest_points) are in world coordinates: the vertex and its nearest
///   surface point. If a vertex penetrates and request.enable_signed_distance is false, the
///   result is −1 (FCL's convention for "in collision, depth not asked for").
/// - collide: one fcl::Contact per penetrating vertex, the deepest num_max_contacts of them:
///   pos = the vertex (world), normal = the superellipsoid's outward normal at the vertex's
///   nearest point, signed to point from o1 to o2, penetration_depth = the vertex's depth.
///   With request.enable_contact = false the contacts carry zero pos, normal and depth, and
///   the search stops at num_max_contacts penetrating vertices. Where the shape's
///   meshContacts() is MeshContacts::kRegions, a triangle mesh (not a point cloud) is met as a
///   surface instead: the places of its overlapping regions (contact_manifold.h,
///   contactManifolds), deepest region first, at most four per region, each with the region's
///   normal and its own depth, b of the mesh side the region's deepest triangle.
/// - Through the solver-taking calls, FCL's signed-distance fallback turns a negative mesh
///   distance into a collide() with num_max_contacts = 1; that returns the deepest vertex, so
///   the depth is the same exact value, but FCL then sets both nearest points to the
///   contact's pos (the vertex). The front end reports the vertex and its surface point.
///
/// Conventions of the shape pairs:
/// - distance: the signed distance (overlapping: −(the shortest separating translation)), or −1
///   when they overlap and request.enable_signed_distance is false; nearest_points (world, the
///   caller's order) the two witnesses; b1 = b2 = fcl::DistanceResult::NONE.
/// - collide: when they overlap, with num_max_contacts = 1 (or against a cone) one fcl::Contact:
///   pos halfway between the witnesses, normal the separating direction from o1 to o2,
///   penetration_depth = −(signed distance). With num_max_contacts > 1
///   against the geometries contact_manifold.h builds regions for, the manifold's places (at
///   most four, and at most the room left): the deepest first, then those spanning the region;
///   each with the pair's normal, pos halfway between the two surfaces there and its own depth
///   (0 on the region's rim, where the surfaces come within the patch tolerance).

#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "fcl_superellipsoid/export.h"
#include "fcl_superellipsoid/gjk_support.h"
#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {

/// Registers the superellipsoid entries in FCL's tables for GJKSolver_libccd<float> and
/// <double>. Idempotent and thread-safe; every Superellipsoid constructor calls it.
FSE_EXPORT void registerWithFcl();

/// fcl::distance without a solver argument; results in the caller's order.
template <typename S>
FSE_EXPORT S distance(const fcl::CollisionObject<S>* o1, const fcl::CollisionObject<S>* o2,
                      const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result);
template <typename S>
FSE_EXPORT S distance(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                      const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
                      const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result);

/// fcl::collide without a solver argument; contacts in the caller's order.
template <typename S>
FSE_EXPORT std::size_t collide(const fcl::CollisionObject<S>* o1, const fcl::CollisionObject<S>* o2,
                               const fcl::CollisionRequest<S>& request,
                               fcl::CollisionResult<S>& result);
template <typename S>
FSE_EXPORT std::size_t collide(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                               const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
                               const fcl::CollisionRequest<S>& request,
                               fcl::CollisionResult<S>& result);

/// fcl::DefaultCollisionFunction with the front end: pass it to a broadphase manager's
/// collide() with an fcl::DefaultCollisionData<S>.
template <typename S>
FSE_EXPORT bool defaultCollisionFunction(fcl::CollisionObject<S>* o1, fcl::CollisionObject<S>* o2,
                                         void* data);
/// fcl::DefaultDistanceFunction with the front end (fcl::DefaultDistanceData<S>).
template <typename S>
FSE_EXPORT bool defaultDistanceFunction(fcl::CollisionObject<S>* o1, fcl::CollisionObject<S>* o2,
                                        void* data, S& dist);

#define FSE_DECLARE_FRONT_END(S)                                                                   \
  extern template FSE_EXPORT S distance(const fcl::CollisionObject<S>*,                            \
                                        const fcl::CollisionObject<S>*,                            \
                                        const fcl::DistanceRequest<S>&, fcl::DistanceResult<S>&);  \
  extern template FSE_EXPORT S distance(                                                           \
      const fcl::CollisionGeometry<S>*, const fcl::Transform3<S>&,                                 \
      const fcl::CollisionGeometry<S>*, const fcl::Transform3<S>&, const fcl::DistanceRequest<S>&, \
      fcl::DistanceResult<S>&);                                                                    \
  extern template FSE_EXPORT std::size_t collide(                                                  \
      const fcl::CollisionObject<S>*, const fcl::CollisionObject<S>*,                              \
      const fcl::CollisionRequest<S>&, fcl::CollisionResult<S>&);                                  \
  extern template FSE_EXPORT std::size_t collide(                                                  \
      const fcl::CollisionGeometry<S>*, const fcl::Transform3<S>&,                                 \
      const fcl::CollisionGeometry<S>*, const fcl::Transform3<S>&,                                 \
      const fcl::CollisionRequest<S>&, fcl::CollisionResult<S>&);                                  \
  extern template FSE_EXPORT bool defaultCollisionFunction(fcl::CollisionObject<S>*,               \
                                                           fcl::CollisionObject<S>*, void*);       \
  extern template FSE_EXPORT bool defaultDistanceFunction(fcl::CollisionObject<S>*,                \
                                                          fcl::CollisionObject<S>*, void*, S&);
FSE_DECLARE_FRONT_END(float)
FSE_DECLARE_FRONT_END(double)
#undef FSE_DECLARE_FRONT_END

}  // namespace fcl_superellipsoid

// FCL's function tables for GJKSolver_libccd are instantiated once, in this library
// (src/fcl_glue/fcl_*_table_*.cpp, 30–60 s of compile time each). These declarations keep every
// translation unit that includes this header, and calls fcl::distance / fcl::collide with
// that solver, from instantiating them again, and make its calls read the tables that hold
// the superellipsoid entries.
namespace fcl {
namespace detail {
extern template struct DistanceFunctionMatrix<GJKSolver_libccd<float>>;
extern template struct DistanceFunctionMatrix<GJKSolver_libccd<double>>;
extern template struct CollisionFunctionMatrix<GJKSolver_libccd<float>>;
extern template struct CollisionFunctionMatrix<GJKSolver_libccd<double>>;
}  // namespace detail
extern template detail::DistanceFunctionMatrix<detail::GJKSolver_libccd<float>>&
getDistanceFunctionLookTable<detail::GJKSolver_libccd<float>>();
extern template detail::DistanceFunctionMatrix<detail::GJKSolver_libccd<double>>&
getDistanceFunctionLookTable<detail::GJKSolver_libccd<double>>();
extern template detail::CollisionFunctionMatrix<detail::GJKSolver_libccd<float>>&
getCollisionFunctionLookTable<detail::GJKSolver_libccd<float>>();
extern template detail::CollisionFunctionMatrix<detail::GJKSolver_libccd<double>>&
getCollisionFunctionLookTable<detail::GJKSolver_libccd<double>>();
}  // namespace fcl

#endif  // FCL_SUPERELLIPSOID_FCL_INTEGRATION_H
