// FCL's distance table for GJKSolver_libccd<double>, instantiated here once (fcl_table_templates.h;
// fcl_integration.h declares it extern).
#include "fcl_glue/fcl_table_templates.h"

FSE_FCL_TABLE(, DistanceFunctionMatrix, getDistanceFunctionLookTable,
              ::fcl::detail::GJKSolver_libccd<double>)
