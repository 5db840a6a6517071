#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_FCL_TABLE_TEMPLATES_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_FCL_TABLE_TEMPLATES_H

// Internal: FCL's function tables as templates we instantiate ourselves. Debian's libfcl keeps
// its own tables private (docs/fcl-notes.md), so this project instantiates the ones it reads:
// GJKSolver_libccd<float/double> (fcl_tables.h, with the superellipsoid's entries) and
// GJKSolver_indep<float> and <double> (the float front end's and the interposer's other pairs:
// indep_tables.h). Each table is 30–60 s of compile time, so each has its own translation unit,
// which holds FCL's code and nothing of ours (src/CMakeLists.txt compiles those units
// uninstrumented in the sanitizer builds), and every other unit sees the table declared extern.

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

/// FCL's table fcl::detail::Matrix<Solver> and its getter fcl::getter<Solver>():
/// FSE_FCL_TABLE(extern, ...) declares them instantiated elsewhere, FSE_FCL_TABLE(, ...)
/// instantiates them. Solver is fully qualified, e.g. ::fcl::detail::GJKSolver_indep<float>.
#define FSE_FCL_TABLE(keyword, Matrix, getter, Solver)       \
  namespace fcl {                                            \
  namespace detail {                                         \
  keyword template struct Matrix<Solver>;                    \
  }                                                          \
  keyword template detail::Matrix<Solver>& getter<Solver>(); \
  }

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_FCL_TABLE_TEMPLATES_H
