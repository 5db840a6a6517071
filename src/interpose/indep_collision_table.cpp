// FCL's collision table for GJKSolver_indep<double>, instantiated here once
// (fcl_glue/indep_tables.h).
#include "fcl_glue/indep_tables.h"

FSE_FCL_TABLE(, CollisionFunctionMatrix, getCollisionFunctionLookTable,
              ::fcl::detail::GJKSolver_indep<double>)
