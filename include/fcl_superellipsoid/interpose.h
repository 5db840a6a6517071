#ifndef FCL_SUPERELLIPSOID_INTERPOSE_H
#define FCL_SUPERELLIPSOID_INTERPOSE_H

/// @file
/// The opt-in interposer: FCL's plain calls with the superellipsoid inside.
///
/// Debian's libfcl runs the plain calls, fcl::distance(o1, o2, request, result) and
/// fcl::collide(o1, o2, request, result) for double (object and geometry + pose forms), inside
/// libfcl with its private function tables, which never see the superellipsoid. The separate
/// library fcl_superellipsoid_interpose (CMake: fcl_superellipsoid::interpose) defines those
/// four functions itself, so the dynamic linker hands it every plain call of the process (the
/// application's, its other libraries', FCL's fcl::DefaultCollisionFunction /
/// DefaultDistanceFunction compiled into them). It answers each call as FCL's
/// plain call does, with one difference: a pair with a superellipsoid reads the tables that hold
/// its entries. In detail:
///
/// - A pair with a Superellipsoid: the solver-taking FCL call with GJKSolver_libccd<double>
///   (the tables this library registers its entries in), whatever request.gjk_solver_type says
///   (the pair's answer does not use FCL's solver). FCL's conventions hold: a shape–mesh pair
///   is answered as (mesh, shape), as in fcl_integration.h.
/// - Every other pair: FCL's own code for the plain call, unchanged (the same header code,
///   instantiated in the interposer): GST_LIBCCD runs GJKSolver_libccd<double>, GST_INDEP runs
///   GJKSolver_indep<double>, with the request's tolerances set on the solver as FCL sets them.
/// - A null object or geometry is refused with std::invalid_argument (FCL would crash).
///
/// What a user must do (docs/usage.md → "Plain FCL calls"): link fcl_superellipsoid_interpose
/// before libfcl, i.e. list it before fcl (CMake: link fcl_superellipsoid::interpose; it
/// brings fcl after itself), link it statically into the executable, or preload it
/// (LD_PRELOAD=libfcl_superellipsoid_interpose.so). Loaded after libfcl, it cannot win: then
/// plainCallsInterposed() is false and it says so on stderr once, at load time.
///
/// float: libfcl has no float plain calls; a float plain call is instantiated in the caller's
/// translation unit and reads the caller-side tables (fcl_integration.h), so it needs no
/// interposer for GST_LIBCCD (and does not see the superellipsoid with GST_INDEP).

#include "fcl_superellipsoid/export.h"

namespace fcl_superellipsoid {

/// True when this process's plain fcl::distance<double> and fcl::collide<double> (all four
/// forms) resolve to the interposer, false when libfcl's own copies won the symbol lookup.
FSE_EXPORT bool plainCallsInterposed();

}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_INTERPOSE_H
