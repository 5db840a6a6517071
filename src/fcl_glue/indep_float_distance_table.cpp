// FCL's distance table for GJKSolver_indep<float>, instantiated here once (indep_tables.h).
#include "fcl_glue/indep_tables.h"

FSE_FCL_TABLE(, DistanceFunctionMatrix, getDistanceFunctionLookTable,
              ::fcl::detail::GJKSolver_indep<float>)
