#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_INDEP_TABLES_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_INDEP_TABLES_H

// Internal: FCL's function tables for GJKSolver_indep, which plain FCL calls read for a request
// with gjk_solver_type = GST_INDEP. They hold FCL's entries only: the superellipsoid's pairs never
// reach them. Each is instantiated once, in its own translation unit; these declarations keep
// every other unit from instantiating it again.
//  - <float>: the float front end's other pairs (front_end_float.cpp; libfcl has no float code),
//    instantiated in fcl_glue/indep_float_{distance,collision}_table.cpp (this library);
//  - <double>: the interposer's other pairs (interpose/plain_calls.cpp; libfcl keeps its own
//    copies private), instantiated in interpose/indep_{distance,collision}_table.cpp (the
//    interposer's library).

#include "fcl_glue/fcl_table_templates.h"

FSE_FCL_TABLE(extern, DistanceFunctionMatrix, getDistanceFunctionLookTable,
              ::fcl::detail::GJKSolver_indep<float>)
FSE_FCL_TABLE(extern, CollisionFunctionMatrix, getCollisionFunctionLookTable,
              ::fcl::detail::GJKSolver_indep<float>)
FSE_FCL_TABLE(extern, DistanceFunctionMatrix, getDistanceFunctionLookTable,
              ::fcl::detail::GJKSolver_indep<double>)
FSE_FCL_TABLE(extern, CollisionFunctionMatrix, getCollisionFunctionLookTable,
              ::fcl::detail::GJKSolver_indep<double>)

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_INDEP_TABLES_H
