/* Contacts into solver rows (contact_solve.c): what a step hands ODE for each contact of a substep. */
#ifndef PP_CONTACT_SOLVE_H
#define PP_CONTACT_SOLVE_H

#include "solver_ode.h"

typedef struct world world;

/* Add the substep's contact joints, h seconds a substep, for the islands the plan solves (island.c). */
void contact_joints_add(world *wd, const solver_islands *is, double h);
/* The substeps of time a contact's island advances in this one (SPAN_*, world.h). */
int contact_span(const world *wd, const pp_contact *c);

#endif
