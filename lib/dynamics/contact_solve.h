/* Contacts into solver rows (contact_solve.c): what a step hands ODE for each contact of a substep. */
#ifndef PP_CONTACT_SOLVE_H
#define PP_CONTACT_SOLVE_H

#include "contact_table.h"
#include "solver_ode.h"

typedef struct world world;

/* Hand the solver the substep's contacts, h seconds a substep, in the world's contact order: each whose island
 * advances this substep (island.c), with its bounce and target speeds for its island's time step. */
void contact_joints_add(world *wd, double h);

#endif
