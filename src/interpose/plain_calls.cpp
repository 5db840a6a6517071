// The interposed plain calls (include/fcl_superellipsoid/interpose.h; how and why:
// docs/fcl-notes.md → "Interposing the plain calls").
//
// C++ forbids an explicit specialisation of fcl::distance<double> after FCL's headers declared
// it `extern template`, so the four functions are ordinary functions given the assembler names
// of libfcl's exported instantiations (GCC and Clang asm labels). The symbol names are those of
// the Itanium C++ ABI for FCL 0.7's signatures; the tests check that plain calls reach them.

#include <dlfcn.h>

#include <cstddef>
#include <iostream>

#include "common/invalid_argument.h"
#include "fcl_glue/indep_tables.h"
#include "fcl_glue/pairs.h"
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_superellipsoid/interpose.h"

namespace fcl_superellipsoid {
namespace interpose {
namespace {

using Geometry = fcl::CollisionGeometry<double>;
using Object = fcl::CollisionObject<double>;
using Pose = fcl::Transform3<double>;

#define FSE_DISTANCE_OBJECTS                                                              \
  "_ZN3fcl8distanceIdEET_PKNS_15CollisionObjectIS1_EES5_RKNS_15DistanceRequestIS1_EERNS_" \
  "14DistanceResultIS1_EE"
#define FSE_DISTANCE_GEOMETRIES                                                                  \
  "_ZN3fcl8distanceIdEET_PKNS_17CollisionGeometryIS1_EERKN5Eigen9TransformIS1_Li3ELi1ELi0EEES5_" \
  "SA_RKNS_15DistanceRequestIS1_EERNS_14DistanceResultIS1_EE"
#define FSE_COLLIDE_OBJECTS                                                             \
  "_ZN3fcl7collideIdEEmPKNS_15CollisionObjectIT_EES5_RKNS_16CollisionRequestIS2_EERNS_" \
  "15CollisionResultIS2_EE"
#define FSE_COLLIDE_GEOMETRIES                                                                   \
  "_ZN3fcl7collideIdEEmPKNS_17CollisionGeometryIT_EERKN5Eigen9TransformIS2_Li3ELi1ELi0EEES5_SA_" \
  "RKNS_16CollisionRequestIS2_EERNS_15CollisionResultIS2_EE"

void checkNotNull(const char* where, const void* o1, const void* o2) {
  if (o1 == nullptr || o2 == nullptr) {
    detail::throwInvalidArgument(where, "o1 and o2 must not be null",
                                 o1 == nullptr ? "o1 = null" : "o2 = null");
  }
}

}  // namespace

// The bodies follow FCL 0.7's plain calls (narrowphase/distance-inl.h, collision-inl.h) line
// for line, except that a pair with a superellipsoid always takes the GST_LIBCCD branch.

double distanceGeometries(const Geometry* o1, const Pose& tf1, const Geometry* o2, const Pose& tf2,
                          const fcl::DistanceRequest<double>& request,
                          fcl::DistanceResult<double>& result) __asm__(FSE_DISTANCE_GEOMETRIES);
double distanceGeometries(const Geometry* o1, const Pose& tf1, const Geometry* o2, const Pose& tf2,
                          const fcl::DistanceRequest<double>& request,
                          fcl::DistanceResult<double>& result) {
  checkNotNull("fcl::distance (fcl_superellipsoid_interpose)", o1, o2);
  if (request.gjk_solver_type == fcl::GST_LIBCCD || detail::involvesSuperellipsoid(o1, o2)) {
    fcl::detail::GJKSolver_libccd<double> solver;
    solver.distance_tolerance = request.distance_tolerance;
    return fcl::distance(o1, tf1, o2, tf2, &solver, request, result);
  }
  if (request.gjk_solver_type == fcl::GST_INDEP) {
    fcl::detail::GJKSolver_indep<double> solver;
    solver.gjk_tolerance = request.distance_tolerance;
    return fcl::distance(o1, tf1, o2, tf2, &solver, request, result);
  }
  return -1;  // FCL's answer to an unknown solver type
}

double distanceObjects(const Object* o1, const Object* o2,
                       const fcl::DistanceRequest<double>& request,
                       fcl::DistanceResult<double>& result) __asm__(FSE_DISTANCE_OBJECTS);
double distanceObjects(const Object* o1, const Object* o2,
                       const fcl::DistanceRequest<double>& request,
                       fcl::DistanceResult<double>& result) {
  checkNotNull("fcl::distance (fcl_superellipsoid_interpose)", o1, o2);
  return distanceGeometries(o1->collisionGeometry().get(), o1->getTransform(),
                            o2->collisionGeometry().get(), o2->getTransform(), request, result);
}

std::size_t collideGeometries(const Geometry* o1, const Pose& tf1, const Geometry* o2,
                              const Pose& tf2, const fcl::CollisionRequest<double>& request,
                              fcl::CollisionResult<double>& result) __asm__(FSE_COLLIDE_GEOMETRIES);
std::size_t collideGeometries(const Geometry* o1, const Pose& tf1, const Geometry* o2,
                              const Pose& tf2, const fcl::CollisionRequest<double>& request,
                              fcl::CollisionResult<double>& result) {
  checkNotNull("fcl::collide (fcl_superellipsoid_interpose)", o1, o2);
  if (request.gjk_solver_type == fcl::GST_LIBCCD || detail::involvesSuperellipsoid(o1, o2)) {
    fcl::detail::GJKSolver_libccd<double> solver;
    solver.collision_tolerance = request.gjk_tolerance;
    return fcl::collide(o1, tf1, o2, tf2, &solver, request, result);
  }
  if (request.gjk_solver_type == fcl::GST_INDEP) {
    fcl::detail::GJKSolver_indep<double> solver;
    solver.gjk_tolerance = request.gjk_tolerance;
    solver.epa_tolerance = request.gjk_tolerance;
    return fcl::collide(o1, tf1, o2, tf2, &solver, request, result);
  }
  std::cerr << "Warning! Invalid GJK solver\n";
  return static_cast<std::size_t>(-1);  // FCL's answer to an unknown solver type
}

std::size_t collideObjects(const Object* o1, const Object* o2,
                           const fcl::CollisionRequest<double>& request,
                           fcl::CollisionResult<double>& result) __asm__(FSE_COLLIDE_OBJECTS);
std::size_t collideObjects(const Object* o1, const Object* o2,
                           const fcl::CollisionRequest<double>& request,
                           fcl::CollisionResult<double>& result) {
  checkNotNull("fcl::collide (fcl_superellipsoid_interpose)", o1, o2);
  return collideGeometries(o1->collisionGeometry().get(), o1->getTransform(),
                           o2->collisionGeometry().get(), o2->getTransform(), request, result);
}

namespace {

/// Whether the process-wide definition of `symbol` is `own` (this library's).
bool resolvesHere(const char* symbol, const void* own) {
  return dlsym(RTLD_DEFAULT, symbol) == own;
}

/// At load time: say once if libfcl won the lookup (the interposer cannot help then).
__attribute__((constructor)) void warnIfNotInterposed() {
  if (!plainCallsInterposed()) {
    std::cerr << "fcl_superellipsoid_interpose: libfcl was loaded before it, so plain "
                 "fcl::distance / fcl::collide still run libfcl's own code and do not see the "
                 "superellipsoid; link fcl_superellipsoid_interpose before fcl, or preload it\n";
  }
}

}  // namespace
}  // namespace interpose

bool plainCallsInterposed() {
  using namespace interpose;
  return resolvesHere(FSE_DISTANCE_OBJECTS, reinterpret_cast<const void*>(&distanceObjects)) &&
         resolvesHere(FSE_DISTANCE_GEOMETRIES,
                      reinterpret_cast<const void*>(&distanceGeometries)) &&
         resolvesHere(FSE_COLLIDE_OBJECTS, reinterpret_cast<const void*>(&collideObjects)) &&
         resolvesHere(FSE_COLLIDE_GEOMETRIES, reinterpret_cast<const void*>(&collideGeometries));
}

}  // namespace fcl_superellipsoid

// What a static build's link option names (src/CMakeLists.txt) so that this object is linked.
extern "C" void fse_interpose_anchor() {}
