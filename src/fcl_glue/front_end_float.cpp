// The front end for float (see front_end.h). Its plain FCL calls for other pairs read FCL's
// tables for both solvers: GJKSolver_libccd<float>'s (fcl_integration.h) and
// GJKSolver_indep<float>'s (indep_tables.h), each instantiated in its own unit.
#include "fcl_glue/front_end.h"
#include "fcl_glue/indep_tables.h"

FSE_INSTANTIATE_FRONT_END(float)
