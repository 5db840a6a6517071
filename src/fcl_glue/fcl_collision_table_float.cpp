// FCL's collision table for GJKSolver_libccd<float>, instantiated here once (see fcl_tables.h).
#include "fcl_glue/fcl_tables.h"
#include "fcl_superellipsoid/fcl_integration.h"

FSE_DEFINE_TABLE(CollisionFunctionMatrix, getCollisionFunctionLookTable, collision_matrix,
                 collisionEntry, float, registerCollisionTableFloat)
