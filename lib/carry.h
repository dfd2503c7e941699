/* Contacts carried through a step's substeps. The raster narrowphase runs at a step's first substep;
 * each later substep moves a touching pair's points with its two bodies and its depths along the
 * (fixed) normals by their relative motion, as Box2D's substeps do, instead of colliding the rasters
 * again. Pairs that move fast against each other, round bodies and islands the exact solver takes are
 * collided at every substep, and so is a pair that did not touch at the step's start, until it does: a
 * body that lands mid-step is caught at the substep it lands in. */
#ifndef PP_CARRY_H
#define PP_CARRY_H

#include "math2d.h"
#include "physpix.h"

#include <stdbool.h>
#include <stdint.h>

struct world;

/* A contact as found at the step's first substep, with its bodies' poses then. */
typedef struct carried_contact {
    pp_contact c;
    dvec2 com_a, com_b;          /* centres of mass, px */
    double cos_a, sin_a, cos_b, sin_b;
} carried_contact;

/* A pair's run of carried contacts. */
typedef struct carried_pair {
    uint32_t a, b;               /* body slots, a < b (the broadphase's pair) */
    int32_t first, count;        /* in carry.contacts */
    bool claimed;                /* the substep's broadphase still pairs them */
} carried_pair;

typedef struct carried_key {
    uint64_t slots;              /* a << 32 | b */
    int32_t pair;                /* in carry.pairs */
} carried_key;

typedef struct carry {
    carried_contact *contacts;
    int32_t contact_count, contact_capacity;
    carried_pair *pairs;         /* in the order the first substep found them */
    int32_t pair_count, pair_capacity;
    carried_key *by_slots;       /* the pairs sorted by their slots, for carry_claim */
    int32_t by_slots_capacity;
    uint32_t *struck;            /* by slot: the last step in which a collided pair touched the body */
    int32_t struck_capacity;
    uint32_t step;               /* counts carry_record's calls, from 1 */
    bool active;                 /* a later substep: carried pairs are not collided */
} carry;

/* At the step's first substep of a step of dt s, after its contacts and islands: record the pairs to carry. */
pp_status carry_record(struct world *wd, double dt);
/* At a later substep, for each broadphase pair: true if it is carried (it is then not collided). A body
 * that a collided pair touched (something landed on it, or it is round or in an exact island) has its
 * pairs collided from the next substep on: what struck it may push it onto features it was not touching. */
bool carry_claim(struct world *wd, uint32_t a, uint32_t b);
/* At a later substep, after the collided pairs' contacts are pushed: mark their bodies struck. */
void carry_strike(struct world *wd);
/* At a later substep, after carry_strike: the claimed pairs' moved contacts, through touch_pair. */
pp_status carry_push(struct world *wd);
/* At a later substep's start: no pair is claimed yet. */
void carry_unclaim(struct world *wd);
void carry_free(carry *c);

#endif
