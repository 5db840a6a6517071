// FCL's distance table for GJKSolver_libccd<double>, instantiated here once (see fcl_tables.h).
#include "fcl_glue/fcl_tables.h"
#include "fcl_superellipsoid/fcl_integration.h"

FSE_DEFINE_TABLE(DistanceFunctionMatrix, getDistanceFunctionLookTable, distance_matrix,
                 distanceEntry, double, registerDistanceTableDouble)
