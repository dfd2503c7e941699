/* Islands: the bodies this substep's contacts join, as ODE will step them, each sent to the exact
 * solver or to QuickStep by its size. */
#ifndef PP_ISLAND_H
#define PP_ISLAND_H

#include "solver_ode.h"
#include "world.h"

/* Sort the awake islands into `out` (arrays owned by the world) for solver_step. */
pp_status island_plan(world *wd, solver_islands *out);

#endif
