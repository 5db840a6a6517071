#ifndef FCL_SUPERELLIPSOID_SRC_INTERPOSE_INDEP_TABLES_H
#define FCL_SUPERELLIPSOID_SRC_INTERPOSE_INDEP_TABLES_H

// Internal: FCL's function tables for GJKSolver_indep<double>, which the interposed plain calls
// read for a request with gjk_solver_type = GST_INDEP. libfcl keeps its own copies private, so
// the interposer instantiates them once, each in its own translation unit
// (indep_{distance,collision}_table.cpp: the heavy compiles run in parallel), and these
// declarations keep plain_calls.cpp from instantiating them again. They hold FCL's entries
// only: the superellipsoid's pairs never reach them (plain_calls.cpp).

#include "fcl_glue/fcl_table_templates.h"

FSE_FCL_TABLE(extern, DistanceFunctionMatrix, getDistanceFunctionLookTable,
              ::fcl::detail::GJKSolver_indep<double>)
FSE_FCL_TABLE(extern, CollisionFunctionMatrix, getCollisionFunctionLookTable,
              ::fcl::detail::GJKSolver_indep<double>)

#endif  // FCL_SUPERELLIPSOID_SRC_INTERPOSE_INDEP_TABLES_H
