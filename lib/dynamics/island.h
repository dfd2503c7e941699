/* Islands: the bodies this substep's contacts join, as ODE will step them, each sent to the exact
 * solver or to QuickStep by its size; and the groups that fall asleep together. */
#ifndef PP_ISLAND_H
#define PP_ISLAND_H

#include "solver_ode.h"
#include "world.h"

/* Where a substep falls in its pair: QuickStep stacks sit the first of a pair out and solve the second with
 * twice its time step, which halves their cost; exact islands, lone bodies, jointed islands and piles with a
 * body over 4 times heavier than one it touches solve every substep. A substep without a pair (FAST's one,
 * an odd count's last) solves everything. */
typedef enum substep_pairing { PAIR_NONE, PAIR_FIRST, PAIR_SECOND, PAIR_MID, PAIR_LAST } substep_pairing;
/* Substep k's place of `substeps`: the first or second of a pair; in four whole substeps the second pair's
 * second is PAIR_LAST and the first's PAIR_MID, where a stack at rest keeps sitting out to solve 4·h at the last. */
static inline substep_pairing island_pairing(int32_t k, int32_t substeps)
{
    if (k % 2 == 0)
        return k + 1 < substeps ? PAIR_FIRST : PAIR_NONE;
    if (k % 4 == 1)
        return (k | 3) < substeps ? PAIR_MID : PAIR_SECOND;
    return PAIR_LAST;
}

/* Collect substep k's nodes (k counts a step's substeps from 0) and sort the awake islands into `out` (arrays owned
 * by the world) for solver_step, each body's span (SPAN_*) in wd->island_span. `still`: nothing moved, woke or slept
 * since the last call (the contacts are the same), so its islands stand and only the spans are made anew. */
pp_status island_plan(world *wd, int32_t k, substep_pairing pairing, bool still, solver_islands *out);

/* After solver_step: list in the awake set every node ODE woke through a contact. */
void island_list_woken(world *wd);

/* Whether the pair of contacts [k, end) of wd->contacts is two points more than 64 px apart on a face off both
 * bodies' bitmap axes (over 2°): its load moves between the ends (an arch's joints), so its stack is not solved
 * exactly and, moving, it is collided at every substep (carry.c). */
bool island_slanted_face(const world *wd, int32_t k, int32_t end);

/* Advance the awake dynamic bodies' sleep timers by h s and put to sleep each group of bodies in contact
 * whose every body is ready. Uses island_plan's nodes and arrays; cannot fail. True if a body fell asleep. */
bool island_sleep(world *wd, double h);
/* In a world without sleep, after a step's last substep: the awake bodies' timers (a woken sleeper's mark too) at 0.
 * Only island_sleep reads them, and within a step the awake set only grows: once a step does what each substep
 * would. */
void island_sleep_off(world *wd);

void island_free(island_set *is);

#endif
