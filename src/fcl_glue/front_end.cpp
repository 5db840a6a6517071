// The front end for double (see front_end.h).
#include "fcl_glue/front_end.h"

FSE_INSTANTIATE_FRONT_END(double)
