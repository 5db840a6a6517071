#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_INDEP_FLOAT_TABLES_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_INDEP_FLOAT_TABLES_H

// Internal: FCL's function tables for GJKSolver_indep<float>, which the float front end's plain
// FCL calls read for a request with gjk_solver_type = GST_INDEP (front_end_float.cpp; libfcl has
// no float code). Instantiated once, in indep_float_{distance,collision}_table.cpp; these
// declarations keep front_end_float.cpp from instantiating them again.

#include "fcl_glue/fcl_table_templates.h"

FSE_FCL_TABLE(extern, DistanceFunctionMatrix, getDistanceFunctionLookTable,
              ::fcl::detail::GJKSolver_indep<float>)
FSE_FCL_TABLE(extern, CollisionFunctionMatrix, getCollisionFunctionLookTable,
              ::fcl::detail::GJKSolver_indep<float>)

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_INDEP_FLOAT_TABLES_H
