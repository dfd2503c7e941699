/* Contacts carried through a step's substeps, and resting pairs' from step to step. The raster narrowphase
 * runs at a step's first substep;
 * each later substep moves a touching pair's points with its two bodies and its depths along the
 * (fixed) normals by their relative motion, as Box2D's substeps do, instead of colliding the rasters
 * again, for pairs moving under 2 px a step against themselves (0.5 px in a small island the exact solver
 * takes). Pairs that move faster and round bodies are collided at every substep, and so is a pair that did not touch at the step's start, until it does: a
 * body that lands mid-step is caught at the substep it lands in.
 * A pair whose bodies sat a substep out (island.h: QuickStep stacks solve every other substep) is where it
 * was, so its contacts are carried into the next substep too, however fast it moves: the raster would
 * find the same ones.
 * A resting pair carried through a whole step is held into the next ones (it is not collided at their first
 * substeps either) for as long as its points move under a bound against each other since the raster found
 * them, counting the step ahead, and neither body is edited, retyped or removed: a settled pile is collided
 * once, not once a step. Held pairs are world state: snapshots save them and a failed step puts them back. */
#ifndef PP_CARRY_H
#define PP_CARRY_H

#include "broadphase.h"
#include "math2d.h"
#include "physpix.h"

#include <stdbool.h>
#include <stdint.h>

struct world;

/* The carried pairs themselves are contact records (contact_table.h: carry_* fields, and the table's carry
 * order); what is left here is the step's own state. */
/* A body's motion for the carry decisions (carry.c: motion_of), found once a pass over the pairs. */
typedef struct carry_motion {
    dvec2 v;                     /* px/s */
    double turn_speed;           /* px/s its turning may move its points */
    uint32_t serial;             /* carry.serial when found */
    bool slow;                   /* it turns under CARRY_TURN_RAD in the step */
} carry_motion;

typedef struct carry {
    uint32_t *struck;            /* by slot: the last step in which a collided pair touched the body */
    int32_t struck_capacity;
    uint32_t *collided;          /* by slot: the last step in which the narrowphase found one of its pairs touching */
    int32_t collided_capacity;
    uint32_t *restless;          /* by slot: the last step a QuickStep stack's pair of it moved past CARRY_REST_PX */
    int32_t restless_capacity;
    carry_motion *motion;        /* by slot, current where serial matches */
    int32_t motion_capacity;
    struct carry_moved *moved;   /* by record: a held pair's contacts moved to the first substep's poses */
    int32_t moved_capacity;
    uint32_t serial;             /* counts the passes over carried pairs: no velocity changes within one */
    uint32_t step;               /* counts the steps carry_begin started, from 1 */
    int32_t substep;             /* the substep now, 0 = the step's first */
    bool active;                 /* a later substep: carried pairs are not collided */
} carry;

/* Whether a pair the narrowphase collided touched the body in this slot in this step (so far): something
 * landed on it, or it moved too fast against another body for its pair to be carried. */
static inline bool carry_struck(const carry *c, uint32_t slot)
{
    return (int32_t)slot < c->struck_capacity && c->struck[slot] == c->step;
}
/* Whether a QuickStep stack's pair of the body in this slot moved faster than a pile at rest in this step (so far):
 * its island needs its full iterations, carried or not. */
static inline bool carry_restless(const carry *c, uint32_t slot)
{
    return (int32_t)slot < c->restless_capacity && c->restless[slot] == c->step;
}
/* Whether the narrowphase found a pair of the body in this slot touching in this step (so far): none of its
 * contacts is carried or held, at rest. */
static inline bool carry_was_collided(const carry *c, uint32_t slot)
{
    return (int32_t)slot < c->collided_capacity && c->collided[slot] == c->step;
}

/* At substep k of a step of dt s, after its contacts and islands: at the first (k = 0), record the pairs to
 * carry; at any, the pairs whose bodies sit it out. */
pp_status carry_record(struct world *wd, double dt, int32_t k);
/* At a later substep, for each broadphase pair: true if it is carried (it is then not collided). A body
 * that a collided pair touched (something landed on it, or it is round or in an exact island) has its
 * pairs collided from the next substep on: what struck it may push it onto features it was not touching.
 * A pair whose bodies both sat the last substep out is not collided either, touching or not. */
bool carry_claim(struct world *wd, uint32_t a, uint32_t b);
/* At a later substep, after the collided pairs' contacts are pushed: mark their bodies struck. */
void carry_strike(struct world *wd);
/* The narrowphase found a pair of these two bodies touching (at any substep). */
void carry_collided(struct world *wd, uint32_t a, uint32_t b);
/* At a later substep, after carry_strike: the claimed pairs' moved contacts, through contact_table_found. */
pp_status carry_push(struct world *wd);
/* At substep k's start, of a step of dt s: no pair is claimed yet; at the step's first, the held pairs that
 * stay within their bound through this step are carried into it, the rest dropped. */
pp_status carry_begin(struct world *wd, int32_t k, double dt);
/* After a step's last substep: keep the pairs to hold (carried through it, never collided) and drop the rest. */
void carry_end_step(struct world *wd);
/* Drop the held pairs of the body in this slot: its pixels, type or existence changed outside a step. */
void carry_forget(struct world *wd, uint32_t slot);
/* The pixels of the static body in this slot changed within `region` (a world box) and nowhere else: drop its
 * held pairs with a body whose box comes within CARRY_EDIT_REACH_PX of the region. The others touch it as they
 * did (the raster reads no pixel farther from their overlap), and stay held: an erase at one end of a terrain
 * does not make every crate resting on it collide again. */
void carry_forget_near(struct world *wd, uint32_t slot, pp_aabb region);
void carry_free(carry *c);

#endif
