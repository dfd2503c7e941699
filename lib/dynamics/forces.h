/* Forces, torques and gravity scales: what acts on a body besides its contacts and the world's gravity.
 * The bodies that carry any are listed, so a scene without them walks nothing for them. */
#ifndef PP_FORCES_H
#define PP_FORCES_H

#include "physpix.h"

struct world;
struct body;
struct forced_list;

/* Before each solver step of a substep: hand every listed awake body its force, torque and the part of
 * gravity its scale adds or takes away. */
void forces_apply(struct world *wd);
/* Before each solver step of a substep of h s: every awake dynamic body's velocities decay by their damping
 * (1/s) as exp(−damping·h), so a second of substeps takes off the same whatever their count (kinematic
 * bodies keep their set velocity). */
void forces_damp(struct world *wd, double h);
/* After a whole step: forces and torques are spent; a body whose gravity scale is 1 leaves the list. */
void forces_step_done(struct world *wd);
/* After a step is undone: what ODE was handed and did not use is dropped (the list keeps every force). */
void forces_step_undone(struct world *wd);
/* A body being removed leaves the list. */
void forces_forget(struct world *wd, struct body *bd);
/* List a body (a snapshot's, with its force, torque or scale already set); PP_ERR_OUT_OF_MEMORY. */
pp_status forces_list(struct world *wd, struct body *bd, const char *fn);
void forces_free(struct forced_list *f);

#endif
