/* The contact budget of crowded bodies (PP_CROWDED_CONTACT_PAIRS). Bodies spawned into one spot all
 * overlap one another: colliding every pair and giving the solver a contact for each would make a step's
 * work quadratic in the bodies. A scene without a crowded body goes through untouched. */
#ifndef PP_CROWD_H
#define PP_CROWD_H

#include "physpix.h"

#include <stdbool.h>
#include <stdint.h>

struct world;

/* Candidate pairs a dynamic body may have with other dynamic bodies before its pairs are collided in two
 * passes: first its CROWD_CANDIDATES best boxes, which may prove it crowded, then the rest. */
#define CROWD_CANDIDATES (2 * PP_CROWDED_CONTACT_PAIRS)

/* What the budget counts of a body slot in one substep. */
typedef struct crowd_slot {
    int64_t overlap;  /* intersecting pixels of its pairs with contacts */
    int32_t pairs;    /* candidates with dynamic bodies, then pairs with contacts */
    int32_t list;     /* its entry in crowd.lists, or −1 */
    uint32_t stamp;   /* crowd.serial of the count that last reset it */
    bool proven;      /* crowded by its first-pass pairs alone */
} crowd_slot;

/* A body's best candidates, then the first contacts of its deepest pairs; best first. */
typedef struct crowd_list {
    int32_t kept;
    int32_t best[CROWD_CANDIDATES];
} crowd_list;

/* The world's budget state, rebuilt every substep; lists only for the bodies that need them. */
typedef struct crowd {
    crowd_slot *slots;   /* by body slot */
    int32_t slot_capacity;
    crowd_list *lists;
    int32_t list_count, list_capacity;
    uint8_t *pass;       /* by candidate pair: CROWD_* flags, when split */
    float *box;          /* by candidate pair: its boxes' overlap, px², when split */
    int32_t pass_capacity, box_capacity;
    int32_t *order;      /* set-up pairs in candidate order, when split */
    int32_t order_capacity;
    uint32_t serial;     /* counts the counts over the slots (crowd_plan, crowd_limit_contacts) */
    bool split;          /* this substep collides its pairs in two passes */
} crowd;

/* Decide after the broadphase whether this substep's pairs are collided in two passes. */
pp_status crowd_plan(struct world *wd);

/* Whether candidate pair k is set up in `pass`: 0 everything (no split), 1 the first pass, 2 the second
 * (the rest, less the pairs of two bodies the first pass proved crowded). */
bool crowd_wants(const struct world *wd, int32_t k, int pass);

/* Record that candidate pair k was set up (after the pairs set up before it). */
void crowd_set_up(struct world *wd, int32_t k);

/* After the first pass's cores, wd->batch.cores[0, n): mark the bodies they prove crowded. */
void crowd_prove(struct world *wd, int32_t n);

/* The set-up pairs in candidate order, the first pass's being wd->batch.pairs[0, first) and the second's
 * [first, n), as indices into wd->pairs. */
pp_status crowd_order(struct world *wd, int32_t first, int32_t n, const int32_t **order);

/* Drop from wd->contacts (and its runs, listed again) the pairs of two crowded bodies that are among neither body's
 * PP_CROWDED_CONTACT_PAIRS deepest; the order of the rest is kept. */
pp_status crowd_limit_contacts(struct world *wd);

void crowd_free(crowd *c);

#endif
