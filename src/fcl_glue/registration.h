#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_REGISTRATION_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_REGISTRATION_H

// Internal: the one place where the shape layer calls up into the FCL layer.
//
// Superellipsoid's constructor (shape/superellipsoid.cpp) calls registerWithFclOnce(), so
// FCL's function tables hold the superellipsoid entries before the first query with any
// superellipsoid (superellipsoid.h says so). This header is deliberately light: it keeps FCL's
// narrow-phase headers (and their 30 s table templates) out of the shape's translation unit.
// The body is fcl_glue/registration.cpp; the public spelling of the same call is
// fcl_superellipsoid::registerWithFcl() in fcl_integration.h.

namespace fcl_superellipsoid {
namespace detail {

/// Writes the superellipsoid entries into FCL's tables for GJKSolver_libccd<float> and
/// <double>, once per process; thread-safe.
void registerWithFclOnce();

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_REGISTRATION_H
