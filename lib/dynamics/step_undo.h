/* The step transaction: everything pp_world_step changes after its timed edits is saved before it changes
 * any of it, and put back if the step fails, so that a step runs whole or not at all (step_undo.c). This
 * file is the one place that knows what a failed step puts back; a sanitizer build (PP_CHECKS) checks that
 * the world's fingerprint after step_restore is the one step_save saw. */
#ifndef PP_STEP_UNDO_H
#define PP_STEP_UNDO_H

#include "math2d.h"
#include "physpix.h"
#include "solver_ode.h"

#include <stdbool.h>
#include <stdint.h>

typedef struct world world;
typedef struct body body;

/* A movable body's part of what a step changes. */
typedef struct step_saved_body {
    uint64_t step;            /* the step that saved it: a body is saved at most once a step */
    solver_exact_state ode;
    dvec2 pos;
    double angle, cos_a, sin_a, slow_time;
    pp_aabb aabb;
} step_saved_body;

typedef struct step_undo {
    step_saved_body *bodies;  /* by slot: awake movable bodies, and sleepers once a contact may wake them */
    int32_t body_capacity;
    uint64_t step;            /* counts steps, so a saved entry is known as this step's */
    pp_contact *contacts;     /* the contacts as the step found them, once step_take_contacts took them */
    int32_t contact_count, contact_capacity;
    bool contacts_taken;      /* this step's first search took the world's array (step_take_contacts) */
    pp_step_stats stats;
    uint64_t solver_steps;
    int32_t event_count;      /* events queued before the step */
    uint64_t fingerprint;     /* PP_CHECKS: the world's state at step_save */
} step_undo;

/* Save what the step may change. It allocates first and changes nothing, so a failure here is harmless. */
pp_status step_save(world *wd);
/* Before the step's first search writes the contacts: the world's array becomes the saved one, and the saved one
 * (whatever it holds) the world's, emptied by the caller. A swap, not a copy; cannot fail. */
void step_take_contacts(world *wd);
/* Before the solver runs: every body a contact joint or a joint may wake is saved (a sleeper changes only
 * then). */
void step_save_contact_bodies(world *wd);
/* Put back what the step saved; cannot fail. */
void step_restore(world *wd);
/* After a step that ran whole: what it saved is no longer needed. */
void step_commit(world *wd);
void step_undo_free(step_undo *u);

#endif
