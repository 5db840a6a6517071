// FCL's collision table for GJKSolver_libccd<float>, instantiated here once (fcl_table_templates.h;
// fcl_integration.h declares it extern).
#include "fcl_glue/fcl_table_templates.h"

FSE_FCL_TABLE(, CollisionFunctionMatrix, getCollisionFunctionLookTable,
              ::fcl::detail::GJKSolver_libccd<float>)
