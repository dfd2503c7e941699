/* Candidate pairs: world AABBs of the solid pixels, sweep-and-prune along x. */
#ifndef PP_BROADPHASE_H
#define PP_BROADPHASE_H

#include "physpix.h"

#include <stdbool.h>
#include <stdint.h>

typedef struct pp_aabb {
    double x0, y0, x1, y1;
} pp_aabb;

/* What the sweep needs of each body slot. */
typedef struct bp_proxy {
    pp_aabb box;
    uint32_t category_bits, mask_bits;
    bool movable;   /* dynamic or kinematic */
    bool dynamic;
    bool awake;
    bool live;
} bp_proxy;

typedef struct bp_pair {
    uint32_t a, b;  /* body slots, a < b */
} bp_pair;

typedef struct pp_broadphase {
    uint32_t *order;        /* live slots sorted by box.x0 */
    int32_t order_count, order_cap;
    bp_pair *pairs;
    int32_t pair_count, pair_cap;
} pp_broadphase;

/* Find the pairs among `proxies[0..n)` that can touch: overlapping boxes, passing the category
 * filter, at least one dynamic, at least one awake; and the static pairs of a sleeping body that
 * is paired with an awake one. Fills bp->pairs in a deterministic order. */
pp_status broadphase_find_pairs(pp_broadphase *bp, const bp_proxy *proxies, int32_t n);
void broadphase_free(pp_broadphase *bp);

#endif
