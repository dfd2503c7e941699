/* Candidate pairs, with static and moving bodies apart: the bodies at rest (static and sleeping) in a dynamic
 * AABB tree whose leaves are fattened by a margin, so that an edit or a move of a few pixels keeps a leaf;
 * the awake dynamic and kinematic bodies in a sweep-and-prune list along x. Awake bodies pair among
 * themselves in the sweep and query the tree for the rest, so a step's broadphase costs in proportion to
 * what is awake, not to the world; the tree also answers region queries. */
#ifndef PP_BROADPHASE_H
#define PP_BROADPHASE_H

#include "physpix.h"

#include <stdbool.h>
#include <stdint.h>

typedef struct pp_aabb {
    double x0, y0, x1, y1;
} pp_aabb;

/* Whether two boxes meet, edges included. */
static inline bool aabb_overlap(const pp_aabb *a, const pp_aabb *b)
{
    return a->x0 <= b->x1 && b->x0 <= a->x1 && a->y0 <= b->y1 && b->y0 <= a->y1;
}

/* What the broadphase needs of each body slot. */
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

/* A tree node: a leaf holds a body slot; an inner node two children. */
typedef struct bp_node {
    pp_aabb box;            /* a leaf's: the body's box grown by BP_MARGIN; an inner node's: its children's union */
    int32_t parent;         /* -1 at the root; the next free node while free */
    int32_t child1, child2; /* -1 in a leaf */
    int32_t height;         /* 0 for a leaf, -1 while free */
    uint32_t slot;
} bp_node;

typedef struct pp_broadphase {
    bp_node *nodes;
    int32_t node_count, node_cap, free_node, root;
    uint32_t *order;        /* the awake bodies' slots by box.x0, then slot: kept between calls, so that the
                             * insertion sort runs in near-linear time while they move a little */
    int32_t order_count, order_cap;
    int32_t *leaf;          /* by slot: its leaf, or -1 */
    int32_t leaf_cap;
    int32_t *stack;         /* the walk of a query */
    int32_t stack_cap;
    uint8_t *roused;        /* by slot, scratch of find_pairs; all zero between calls */
    bp_pair *pairs;
    int32_t pair_count, pair_cap;
    /* A step's candidates (broadphase_find_step_pairs): the pairs of the awake bodies' boxes grown over the
     * step, [0, cand_first) with an awake body and [cand_first, cand_count) a roused sleeper's static ones. */
    bp_pair *cand;
    int32_t cand_count, cand_first, cand_cap;
    pp_aabb *grown;         /* by slot: an awake body's box grown over the step */
    int32_t grown_cap;
    int32_t *cand_awake;    /* the awake list they were found for, a slot's awake flag in its sign (~slot: not) */
    int32_t cand_awake_count, cand_awake_cap;
    uint64_t tree_serial;   /* counts the tree's changes */
    uint64_t cand_serial;   /* tree_serial when they were found */
    bool cand_valid;
} pp_broadphase;

/* Bring slot's leaf in line with its proxy: a body at rest with solid pixels has one (inserted, kept while its
 * box stays inside the fat one, or moved); an awake, dead or empty one has none. `slots` is the world's slot count. */
pp_status broadphase_update(pp_broadphase *bp, const bp_proxy *proxy, uint32_t slot, int32_t slots);

/* Whether broadphase_update would change nothing for slot: its proxy is awake or dead and has no leaf, the
 * tree is started and room is made for `slots`. An awake body is listed at every search: most have no leaf. */
static inline bool broadphase_update_is_idle(const pp_broadphase *bp, const bp_proxy *proxy, uint32_t slot,
                                             int32_t slots)
{
    return (proxy->awake || !proxy->live) && bp->node_cap > 0 && slots <= bp->leaf_cap && bp->leaf[slot] < 0;
}

/* Take slot's leaf out (its body is being removed); cannot fail. */
void broadphase_remove(pp_broadphase *bp, uint32_t slot);

/* Find the pairs that can touch: overlapping boxes, passing the category filter, at least one dynamic, at
 * least one awake; and the static pairs of a sleeping body paired with an awake one. Every proxy's leaf must
 * be up to date. `awake` lists every awake body's slot (the awake set; it may hold others). Fills bp->pairs
 * in the order one sweep of every box along x would: by the pair's first body in (box.x0, slot) order, then
 * its second. */
pp_status broadphase_find_pairs(pp_broadphase *bp, const bp_proxy *proxies, int32_t slots, const int32_t *awake,
                                int32_t awake_count);

/* broadphase_find_pairs for a step's first substep, which also keeps the candidates of the whole step: the pairs
 * found with each awake body's box grown to grown[slot] (its box over the step, which the caller makes from its
 * velocity) and a pixel more. The pairs themselves are those of the boxes now. When the last step's candidates
 * still hold (as for a later substep, with every grown box inside its last one) they are kept: no search. */
pp_status broadphase_find_step_pairs(pp_broadphase *bp, bp_proxy *proxies, int32_t slots, const int32_t *awake,
                                     int32_t awake_count, const pp_aabb *grown);

/* A later substep's pairs: exactly what broadphase_find_pairs would give, taken from the step's candidates
 * (no tree walk, no sweep) while the awake list, every awake flag and the tree are as they were and every awake
 * box is still inside its grown one; otherwise broadphase_find_pairs, and no candidates for the rest of the
 * step. */
pp_status broadphase_find_later_pairs(pp_broadphase *bp, const bp_proxy *proxies, int32_t slots, const int32_t *awake,
                                      int32_t awake_count);

/* Call visit(slot, user) for each slot whose fat box overlaps `box` (closed), in no particular order; stops
 * early when visit returns false. Sees the leaves as the last update left them; never allocates. */
void broadphase_query(pp_broadphase *bp, pp_aabb box, bool (*visit)(uint32_t slot, void *user), void *user);

void broadphase_free(pp_broadphase *bp);

#endif
