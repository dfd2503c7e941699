/* The resting bodies' tree (as Box2D's b2DynamicTree: leaves hold fattened boxes, an insert descends to the
 * sibling that grows the tree's perimeter least, AVL rotations keep it balanced) and the awake bodies'
 * sweep. Pairs are sorted into one order that depends on neither the tree's shape nor the sweep's, so a
 * step is the same whatever history built them. */
#include "alloc.h"
#include "broadphase.h"
#include "check.h"
#include "status.h"

#include <stdlib.h>
#include <string.h>

/* A leaf's box is its body's grown by this, px: a body that moves less keeps its leaf. */
#define BP_MARGIN 4.0
/* A step's grown boxes are searched grown by this more, px: a body at rest stays inside them the next steps, whose
 * pairs then come from these candidates without a search. A settling pile creeps a pixel in a few steps: at 1 px
 * the raining crates searched again at 133 of their 300 steps (broadphase 522 k instructions a step, bench_instr),
 * at 8 px 320 k; the packed pyramid filters more candidates (72 k → 87 k). At 16 px the rain rose to 401 k. */
#define BP_STEP_MARGIN 8.0

static pp_aabb combine(pp_aabb a, pp_aabb b)
{
    return (pp_aabb){a.x0 < b.x0 ? a.x0 : b.x0, a.y0 < b.y0 ? a.y0 : b.y0, a.x1 > b.x1 ? a.x1 : b.x1,
                     a.y1 > b.y1 ? a.y1 : b.y1};
}

static double perimeter(pp_aabb b) { return 2.0 * ((b.x1 - b.x0) + (b.y1 - b.y0)); }

static bool contains(pp_aabb outer, pp_aabb in)
{
    return outer.x0 <= in.x0 && outer.y0 <= in.y0 && in.x1 <= outer.x1 && in.y1 <= outer.y1;
}

static int32_t max_i(int32_t a, int32_t b) { return a > b ? a : b; }

/* ---- nodes ---- */

/* At least n free nodes, or PP_ERR_OUT_OF_MEMORY with nothing changed. */
static pp_status reserve_nodes(pp_broadphase *bp, int32_t n)
{
    if (bp->node_cap - bp->node_count >= n)
        return PP_OK;
    int32_t cap = bp->node_cap;
    if (!ARRAY_RESERVE(bp->nodes, cap, bp->node_count + n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory for %d tree nodes", (int)(bp->node_count + n));
    bp_node *p = bp->nodes;
    for (int32_t i = cap - 1; i >= bp->node_cap; i--) /* the new nodes, lowest first, on the free list */
        p[i] = (bp_node){.parent = bp->free_node, .child1 = -1, .child2 = -1, .height = -1};
    for (int32_t i = bp->node_cap; i < cap; i++)
        p[i].parent = i + 1 < cap ? i + 1 : bp->free_node;
    bp->free_node = bp->node_cap;
    bp->node_cap = cap;
    return PP_OK;
}

static int32_t take_node(pp_broadphase *bp)
{
    const int32_t i = bp->free_node;
    PP_ASSERT(i >= 0); /* reserve_nodes first */
    bp->free_node = bp->nodes[i].parent;
    bp->nodes[i] = (bp_node){.parent = -1, .child1 = -1, .child2 = -1, .height = 0};
    bp->node_count++;
    return i;
}

static void give_node(pp_broadphase *bp, int32_t i)
{
    bp->nodes[i] = (bp_node){.parent = bp->free_node, .child1 = -1, .child2 = -1, .height = -1};
    bp->free_node = i;
    bp->node_count--;
}

/* ---- the tree ---- */

static void replace_child(pp_broadphase *bp, int32_t parent, int32_t old, int32_t now)
{
    if (parent < 0)
        bp->root = now;
    else if (bp->nodes[parent].child1 == old)
        bp->nodes[parent].child1 = now;
    else
        bp->nodes[parent].child2 = now;
}

/* If a's subtrees differ in height by more than one, lift the taller child over a; returns the subtree's root. */
static int32_t balance(pp_broadphase *bp, int32_t ia)
{
    bp_node *n = bp->nodes, *a = &n[ia];
    if (a->child1 < 0 || a->height < 2)
        return ia;
    const int32_t ib = a->child1, ic = a->child2;
    const int32_t diff = n[ic].height - n[ib].height;
    if (diff > 1 || diff < -1) {
        /* up: the taller child; keep: the other child of a; its own taller child stays under it */
        const int32_t up = diff > 1 ? ic : ib, keep = diff > 1 ? ib : ic;
        const int32_t f = n[up].child1, g = n[up].child2;
        const int32_t stay = n[f].height > n[g].height ? f : g, move = stay == f ? g : f;
        n[up].parent = a->parent;
        replace_child(bp, a->parent, ia, up);
        a->parent = up;
        n[up].child1 = ia, n[up].child2 = stay;
        if (diff > 1)
            a->child2 = move;
        else
            a->child1 = move;
        n[move].parent = ia;
        a->box = combine(n[keep].box, n[move].box);
        a->height = 1 + max_i(n[keep].height, n[move].height);
        n[up].box = combine(a->box, n[stay].box);
        n[up].height = 1 + max_i(a->height, n[stay].height);
        return up;
    }
    return ia;
}

/* Refit boxes and heights from i up to the root, balancing as it goes. */
static void refit(pp_broadphase *bp, int32_t i)
{
    while (i >= 0) {
        i = balance(bp, i);
        bp_node *n = &bp->nodes[i];
        n->box = combine(bp->nodes[n->child1].box, bp->nodes[n->child2].box);
        n->height = 1 + max_i(bp->nodes[n->child1].height, bp->nodes[n->child2].height);
        i = n->parent;
    }
}

/* Hang a detached leaf beside the sibling that makes the tree's total perimeter grow least. */
static void insert_leaf(pp_broadphase *bp, int32_t leaf)
{
    bp_node *n = bp->nodes;
    if (bp->root < 0) {
        bp->root = leaf, n[leaf].parent = -1;
        return;
    }
    const pp_aabb box = n[leaf].box;
    int32_t i = bp->root;
    while (n[i].child1 >= 0) {
        const double here = perimeter(n[i].box), joined = perimeter(combine(n[i].box, box));
        const double cost = 2.0 * joined, inherited = 2.0 * (joined - here);
        double child_cost[2];
        for (int k = 0; k < 2; k++) {
            const int32_t c = k ? n[i].child2 : n[i].child1;
            const double grown = perimeter(combine(box, n[c].box));
            child_cost[k] = (n[c].child1 < 0 ? grown : grown - perimeter(n[c].box)) + inherited;
        }
        if (cost < child_cost[0] && cost < child_cost[1])
            break;
        i = child_cost[0] <= child_cost[1] ? n[i].child1 : n[i].child2;
    }
    const int32_t parent = take_node(bp), old = n[i].parent;
    n[parent] = (bp_node){combine(box, n[i].box), old, i, leaf, n[i].height + 1, 0};
    replace_child(bp, old, i, parent);
    n[i].parent = parent, n[leaf].parent = parent;
    refit(bp, old);
}

/* Detach a leaf (kept allocated); its parent node goes back to the free list. */
static void detach_leaf(pp_broadphase *bp, int32_t leaf)
{
    bp_node *n = bp->nodes;
    if (leaf == bp->root) {
        bp->root = -1;
        return;
    }
    const int32_t parent = n[leaf].parent, grand = n[parent].parent;
    const int32_t sibling = n[parent].child1 == leaf ? n[parent].child2 : n[parent].child1;
    replace_child(bp, grand, parent, sibling);
    n[sibling].parent = grand;
    give_node(bp, parent);
    refit(bp, grand);
}

static pp_status reserve_slots(pp_broadphase *bp, int32_t slots)
{
    if (slots <= bp->leaf_cap)
        return PP_OK;
    int32_t leaf_cap = bp->leaf_cap, roused_cap = bp->leaf_cap; /* both grow alike */
    if (!ARRAY_RESERVE(bp->leaf, leaf_cap, slots) || !ARRAY_RESERVE(bp->roused, roused_cap, slots))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory for %d bodies", (int)slots);
    for (int32_t i = bp->leaf_cap; i < leaf_cap; i++)
        bp->leaf[i] = -1, bp->roused[i] = 0;
    bp->leaf_cap = leaf_cap;
    return PP_OK;
}

pp_status broadphase_update(pp_broadphase *bp, const bp_proxy *proxy, uint32_t slot, int32_t slots)
{
    if (bp->node_cap == 0)
        bp->root = bp->free_node = -1;
    pp_status st = reserve_slots(bp, slots);
    if (st)
        return st;
    const pp_aabb b = proxy->box;
    int32_t leaf = bp->leaf[slot];
    if (!proxy->live || proxy->awake || !(b.x0 <= b.x1 && b.y0 <= b.y1)) { /* dead, awake, or no solid pixel */
        broadphase_remove(bp, slot);
        return PP_OK;
    }
    /* A body at rest is updated when it changed (an edit, a move, a new type): the step candidates were filtered by
     * its old box, which its leaf's margin may still hold (fuzz_scene: a terrain's timed erase and paint under a
     * falling crate, whose pair the reused candidates then missed while the crate stayed within its searched box). */
    bp->cand_valid = false;
    if (leaf >= 0 && contains(bp->nodes[leaf].box, b))
        return PP_OK;
    /* A query's walk holds at most the root's height + 1 nodes, and an insert adds at most one level: room
     * for both first, so that a query never allocates (and an edit's commit, which queries, cannot fail). */
    const int32_t height = bp->root >= 0 ? bp->nodes[bp->root].height : 0;
    if ((st = reserve_nodes(bp, 2)))
        return st;
    if (!ARRAY_RESERVE(bp->stack, bp->stack_cap, height + 3))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory for a query's walk");
    bp->tree_serial++;
    if (leaf >= 0)
        detach_leaf(bp, leaf);
    else
        leaf = bp->leaf[slot] = take_node(bp);
    bp->nodes[leaf] = (bp_node){{b.x0 - BP_MARGIN, b.y0 - BP_MARGIN, b.x1 + BP_MARGIN, b.y1 + BP_MARGIN}, -1, -1, -1, 0,
                                slot};
    insert_leaf(bp, leaf);
    return PP_OK;
}

void broadphase_remove(pp_broadphase *bp, uint32_t slot)
{
    if (slot >= (uint32_t)bp->leaf_cap || bp->leaf[slot] < 0)
        return;
    bp->tree_serial++;
    detach_leaf(bp, bp->leaf[slot]);
    give_node(bp, bp->leaf[slot]);
    bp->leaf[slot] = -1;
}

void broadphase_query(pp_broadphase *bp, pp_aabb box, bool (*visit)(uint32_t slot, void *user), void *user)
{
    if (bp->node_cap == 0 || bp->root < 0)
        return;
    PP_ASSERT(bp->stack_cap >= bp->nodes[bp->root].height + 2); /* broadphase_update keeps it so */
    int32_t top = 0;
    bp->stack[top++] = bp->root;
    while (top > 0) {
        const bp_node *n = &bp->nodes[bp->stack[--top]];
        if (!aabb_overlap(&n->box, &box))
            continue;
        if (n->child1 < 0) {
            if (!visit(n->slot, user))
                return;
        } else {
            PP_ASSERT(top + 2 <= bp->stack_cap);
            bp->stack[top++] = n->child1;
            bp->stack[top++] = n->child2;
        }
    }
}

/* ---- pairs ---- */

/* The order of a sweep along x: by the box's left edge, then by slot. */
static bool before(const bp_proxy *p, uint32_t a, uint32_t b)
{
    return p[a].box.x0 < p[b].box.x0 || (p[a].box.x0 == p[b].box.x0 && a < b);
}

/* A pair's place in that sweep: its earlier body first. */
typedef struct pair_key {
    double x_first, x_second;
    uint32_t first, second;
} pair_key;

static inline int key_compare(const pair_key *p, const pair_key *q)
{
    if (p->x_first != q->x_first)
        return p->x_first < q->x_first ? -1 : 1;
    if (p->first != q->first)
        return p->first < q->first ? -1 : 1;
    if (p->x_second != q->x_second)
        return p->x_second < q->x_second ? -1 : 1;
    return (p->second > q->second) - (p->second < q->second);
}

static int key_order(const void *x, const void *y) { return key_compare(x, y); } /* qsort's */

static inline pair_key key_of(const bp_proxy *px, bp_pair p)
{
    const uint32_t first = before(px, p.a, p.b) ? p.a : p.b, second = first == p.a ? p.b : p.a;
    return (pair_key){px[first].box.x0, px[second].box.x0, first, second};
}

static bp_pair pair_of(const pair_key *k)
{
    return k->first < k->second ? (bp_pair){k->first, k->second} : (bp_pair){k->second, k->first};
}

/* Sort pairs [mid, to) into the sweep's order and merge them with [from, mid), already in it. */
static pp_status sort_pairs(pp_broadphase *bp, const bp_proxy *px, int32_t from, int32_t mid, int32_t to)
{
    const int32_t n = to - from;
    if (to - mid == 0 || n < 2)
        return PP_OK;
    pair_key *keys = pp_malloc((size_t)n * sizeof *keys);
    if (!keys)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory to sort %d pairs", (int)n);
    pair_key *sorted = keys + (mid - from); /* after the check: an offset on NULL is undefined (found by fuzz_api) */
    for (int32_t k = mid; k < to; k++)
        sorted[k - mid] = key_of(px, bp->pairs[k]);
    qsort(sorted, (size_t)(to - mid), sizeof *keys, key_order);
    for (int32_t k = from; k < mid; k++) /* room for the merge: the sorted part moves to the keys' front */
        keys[k - from] = key_of(px, bp->pairs[k]);
    int32_t i = 0, j = mid - from, out = from;
    while (i < mid - from && j < n)
        bp->pairs[out++] = key_compare(&keys[i], &keys[j]) <= 0 ? pair_of(&keys[i++]) : pair_of(&keys[j++]);
    while (i < mid - from)
        bp->pairs[out++] = pair_of(&keys[i++]);
    while (j < n)
        bp->pairs[out++] = pair_of(&keys[j++]);
    pp_free(keys);
    return PP_OK;
}

typedef struct pair_search {
    pp_broadphase *bp;
    const bp_proxy *proxies;
    uint32_t self;
    bool roused;   /* the second pass: a roused sleeper's pairs with static bodies */
    pp_status status;
} pair_search;

static bool may_touch(const bp_proxy *p, const bp_proxy *q)
{
    if (!p->dynamic && !q->dynamic)
        return false; /* static and kinematic never respond to each other */
    if (!(p->category_bits & q->mask_bits) || !(q->category_bits & p->mask_bits))
        return false;
    return aabb_overlap(&p->box, &q->box);
}

static bool add_candidate(uint32_t other, void *user)
{
    pair_search *s = user;
    const bp_proxy *p = &s->proxies[s->self], *q = &s->proxies[other];
    if (other == s->self)
        return true;
    PP_ASSERT(!q->awake); /* the tree holds bodies at rest only */
    if (s->roused && q->movable)
        return true;
    if (!may_touch(p, q))
        return true;
    pp_broadphase *bp = s->bp;
    if (!ARRAY_RESERVE(bp->pairs, bp->pair_cap, bp->pair_count + 1)) {
        s->status = pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory for %d pairs", (int)bp->pair_count + 1);
        return false;
    }
    bp->pairs[bp->pair_count++] = s->self < other ? (bp_pair){s->self, other} : (bp_pair){other, s->self};
    return true;
}

static pp_status search(pp_broadphase *bp, const bp_proxy *proxies, uint32_t self, bool roused)
{
    pair_search s = {bp, proxies, self, roused, PP_OK};
    broadphase_query(bp, proxies[self].box, add_candidate, &s);
    return s.status;
}

/* A sleeping body paired with an awake one may be woken by ODE through their contact joint in this
 * very step, and would then move with nothing under it: pairs skip two bodies that both sleep, and a
 * static body sleeps. Such a sleeper gets its pairs with static bodies too (its sleeping neighbours stay out). */
static uint32_t sleeper_of(const bp_proxy *px, bp_pair p)
{
    const uint32_t sleeper = px[p.a].awake ? p.b : p.a, other = sleeper == p.a ? p.b : p.a;
    return px[other].awake && !px[sleeper].awake && px[sleeper].dynamic ? sleeper : UINT32_MAX;
}

/* The awake bodies in the sweep's order: last call's order kept where still awake, the newly awake after it,
 * then an insertion sort. `roused` marks the kept ones meanwhile. */
static pp_status order_awake(pp_broadphase *bp, const bp_proxy *px, const int32_t *awake, int32_t awake_count)
{
    if (!ARRAY_RESERVE(bp->order, bp->order_cap, bp->order_count + awake_count))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory for %d awake bodies", (int)awake_count);
    int32_t m = 0;
    for (int32_t i = 0; i < bp->order_count; i++) {
        const uint32_t s = bp->order[i];
        if (s < (uint32_t)bp->leaf_cap && px[s].live && px[s].awake && !bp->roused[s])
            bp->order[m++] = s, bp->roused[s] = 1;
    }
    for (int32_t k = 0; k < awake_count; k++) {
        const uint32_t s = (uint32_t)awake[k];
        if (px[s].live && px[s].awake && !bp->roused[s])
            bp->order[m++] = s, bp->roused[s] = 1;
    }
    bp->order_count = m;
    for (int32_t i = 0; i < m; i++)
        bp->roused[bp->order[i]] = 0;
    for (int32_t i = 1; i < m; i++) {
        const uint32_t key = bp->order[i];
        int32_t j = i - 1;
        for (; j >= 0 && before(px, key, bp->order[j]); j--)
            bp->order[j + 1] = bp->order[j];
        bp->order[j + 1] = key;
    }
    return PP_OK;
}

/* The pairs of two awake bodies: a sweep along the order. */
static pp_status sweep_awake(pp_broadphase *bp, const bp_proxy *px)
{
    for (int32_t i = 0; i < bp->order_count; i++) {
        const uint32_t ip = bp->order[i];
        for (int32_t j = i + 1; j < bp->order_count; j++) {
            const uint32_t iq = bp->order[j];
            if (px[iq].box.x0 > px[ip].box.x1)
                break;
            if (!may_touch(&px[ip], &px[iq]))
                continue;
            if (!ARRAY_RESERVE(bp->pairs, bp->pair_cap, bp->pair_count + 1))
                return pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory for %d pairs", (int)bp->pair_count + 1);
            bp->pairs[bp->pair_count++] = ip < iq ? (bp_pair){ip, iq} : (bp_pair){iq, ip};
        }
    }
    return PP_OK;
}

/* broadphase_find_pairs; *first: where the roused sleepers' static pairs start. */
static pp_status find_pairs(pp_broadphase *bp, const bp_proxy *proxies, int32_t slots, const int32_t *awake,
                            int32_t awake_count, int32_t *first_out)
{
    bp->pair_count = 0;
    pp_status st = reserve_slots(bp, slots);
    if (!st && !(st = order_awake(bp, proxies, awake, awake_count)))
        st = sweep_awake(bp, proxies); /* in the sweep's order already */
    const int32_t swept = bp->pair_count;
    for (int32_t k = 0; !st && k < bp->order_count; k++) /* each awake body against the bodies at rest */
        st = search(bp, proxies, bp->order[k], false);
    const int32_t first = bp->pair_count;
    if (!st)
        st = sort_pairs(bp, proxies, 0, swept, first);
    for (int32_t k = 0; k < first; k++) {
        const uint32_t s = sleeper_of(proxies, bp->pairs[k]);
        if (s == UINT32_MAX || bp->roused[s])
            continue;
        bp->roused[s] = 1;
        if (!st)
            st = search(bp, proxies, s, true);
    }
    for (int32_t k = 0; k < first; k++) { /* all zero again, whatever failed */
        const uint32_t s = sleeper_of(proxies, bp->pairs[k]);
        if (s != UINT32_MAX)
            bp->roused[s] = 0;
    }
    *first_out = first;
    return st ? st : sort_pairs(bp, proxies, first, first, bp->pair_count);
}

pp_status broadphase_find_pairs(pp_broadphase *bp, const bp_proxy *proxies, int32_t slots, const int32_t *awake,
                                int32_t awake_count)
{
    int32_t first;
    bp->cand_valid = false;
    return find_pairs(bp, proxies, slots, awake, awake_count, &first);
}

/* Pairs [from, to) into the sweep's order: the candidates keep the order of the grown boxes they were found
 * with, near the order of the boxes now, so an insertion sort mostly runs in linear time; past a few moves a
 * pair (bodies spawned into one spot overlap in every order) the rest goes to sort_pairs. */
static pp_status settle_pairs(pp_broadphase *bp, const bp_proxy *px, int32_t from, int32_t to)
{
    if (to - from < 2)
        return PP_OK;
    int64_t budget = 8 * (int64_t)(to - from);
    pair_key last = key_of(px, bp->pairs[from]); /* the key of pairs[i − 1]: the largest so far */
    for (int32_t i = from + 1; i < to; i++) {
        const bp_pair p = bp->pairs[i];
        const pair_key k = key_of(px, p);
        if (key_compare(&last, &k) <= 0) { /* in order: most pairs, the boxes having moved little */
            last = k;
            continue;
        }
        /* pairs[i − 1] moves up to i and stays the largest: `last` holds */
        int32_t j = i - 1;
        for (; j >= from; j--) {
            const pair_key q = key_of(px, bp->pairs[j]);
            if (key_compare(&q, &k) <= 0)
                break;
            bp->pairs[j + 1] = bp->pairs[j];
            budget--;
        }
        bp->pairs[j + 1] = p;
        if (budget < 0)
            return sort_pairs(bp, px, from, from, to);
    }
    return PP_OK;
}

/* The pairs of the boxes now among the step's candidates, in find_pairs' order: those with an awake body whose
 * boxes overlap, then the static pairs of the sleepers they rouse (neither moves in a step). */
static pp_status pairs_from_candidates(pp_broadphase *bp, const bp_proxy *px)
{
    if (!ARRAY_RESERVE(bp->pairs, bp->pair_cap, bp->cand_count))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory for %d pairs", (int)bp->cand_count);
    int32_t n = 0;
    for (int32_t k = 0; k < bp->cand_first; k++)
        if (aabb_overlap(&px[bp->cand[k].a].box, &px[bp->cand[k].b].box))
            bp->pairs[n++] = bp->cand[k];
    const int32_t first = n;
    const bool sleepers = bp->cand_first < bp->cand_count; /* static pairs of sleepers a pair may rouse */
    for (int32_t k = 0; sleepers && k < first; k++) {
        const uint32_t s = sleeper_of(px, bp->pairs[k]);
        if (s != UINT32_MAX)
            bp->roused[s] = 1;
    }
    for (int32_t k = bp->cand_first; k < bp->cand_count; k++) {
        const bp_pair p = bp->cand[k];
        if (bp->roused[px[p.a].movable ? p.a : p.b]) /* the other is static */
            bp->pairs[n++] = p;
    }
    for (int32_t k = 0; sleepers && k < first; k++) {
        const uint32_t s = sleeper_of(px, bp->pairs[k]);
        if (s != UINT32_MAX)
            bp->roused[s] = 0;
    }
    bp->pair_count = n;
    pp_status st = settle_pairs(bp, px, 0, first);
    return st ? st : settle_pairs(bp, px, first, n);
}

/* Whether the candidates hold every pair find_pairs would find with each awake body's box at boxes[slot] (its box
 * now, or its box grown over a new step), or at its box now when boxes is NULL. */
static bool candidates_hold(const pp_broadphase *bp, const bp_proxy *px, const int32_t *awake, int32_t awake_count,
                            const pp_aabb *boxes)
{
    if (!bp->cand_valid || bp->cand_serial != bp->tree_serial || bp->cand_awake_count != awake_count)
        return false;
    for (int32_t k = 0; k < awake_count; k++) {
        const int32_t s = awake[k];
        if (bp->cand_awake[k] != (px[s].awake ? s : ~s) ||
            (px[s].awake && !contains(bp->grown[s], boxes ? boxes[s] : px[s].box)))
            return false;
    }
    return true;
}

/* The pairs now from the candidates: the same pairs, in the same order, as the tree and the sweep find (checked
 * against them in PP_CHECKS builds, where a failed allocation fails the step). */
static pp_status pairs_reused(pp_broadphase *bp, const bp_proxy *proxies, int32_t slots, const int32_t *awake,
                              int32_t awake_count)
{
    pp_status st = pairs_from_candidates(bp, proxies);
#ifdef PP_CHECKS
    const int32_t n = bp->pair_count;
    bp_pair *got = st ? NULL : pp_malloc((size_t)n * sizeof *got + 1);
    int32_t first;
    if (!st && (!got || (st = find_pairs(bp, proxies, slots, awake, awake_count, &first))))
        st = st ? st : pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory to check %d pairs", (int)n);
    if (got && !st) {
        if (n > 0)
            memcpy(got, bp->pairs, (size_t)n * sizeof *got); /* find_pairs' */
        PP_ASSERT(bp->pair_count == n);
        if ((st = pairs_from_candidates(bp, proxies)) == PP_OK)
            for (int32_t k = 0; k < n; k++)
                PP_ASSERT(bp->pairs[k].a == got[k].a && bp->pairs[k].b == got[k].b);
    }
    pp_free(got);
#else
    (void)slots, (void)awake, (void)awake_count;
#endif
    return st;
}

pp_status broadphase_find_step_pairs(pp_broadphase *bp, bp_proxy *proxies, int32_t slots, const int32_t *awake,
                                     int32_t awake_count, const pp_aabb *grown)
{
    if (candidates_hold(bp, proxies, awake, awake_count, grown)) /* the last step's hold this one's */
        return pairs_reused(bp, proxies, slots, awake, awake_count);
    bp->cand_valid = false;
    if (!ARRAY_RESERVE(bp->grown, bp->grown_cap, slots) ||
        !ARRAY_RESERVE(bp->cand_awake, bp->cand_awake_cap, awake_count))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory for a step's %d awake bodies", (int)awake_count);
    /* The awake boxes grown for the search, then put back. */
    for (int32_t k = 0; k < awake_count; k++) {
        const int32_t s = awake[k];
        bp->cand_awake[k] = proxies[s].awake ? s : ~s;
        if (proxies[s].awake) {
            const pp_aabb g = grown[s];
            bp->grown[s] = proxies[s].box;
            proxies[s].box = (pp_aabb){g.x0 - BP_STEP_MARGIN, g.y0 - BP_STEP_MARGIN, g.x1 + BP_STEP_MARGIN,
                                       g.y1 + BP_STEP_MARGIN};
        }
    }
    int32_t first = 0;
    pp_status st = find_pairs(bp, proxies, slots, awake, awake_count, &first);
    for (int32_t k = 0; k < awake_count; k++) {
        const int32_t s = awake[k];
        if (proxies[s].awake) {
            const pp_aabb box = bp->grown[s];
            bp->grown[s] = proxies[s].box;
            proxies[s].box = box;
        }
    }
    if (st || !ARRAY_RESERVE(bp->cand, bp->cand_cap, bp->pair_count))
        return st ? st : pp_fail(PP_ERR_OUT_OF_MEMORY, "broadphase: no memory for %d pairs", (int)bp->pair_count);
    if (bp->pair_count > 0)
        memcpy(bp->cand, bp->pairs, (size_t)bp->pair_count * sizeof *bp->cand);
    bp->cand_count = bp->pair_count, bp->cand_first = first;
    bp->cand_awake_count = awake_count;
    bp->cand_serial = bp->tree_serial;
    if ((st = pairs_from_candidates(bp, proxies)))
        return st;
    bp->cand_valid = true;
    return PP_OK;
}

pp_status broadphase_find_later_pairs(pp_broadphase *bp, const bp_proxy *proxies, int32_t slots, const int32_t *awake,
                                      int32_t awake_count)
{
    if (!candidates_hold(bp, proxies, awake, awake_count, NULL))
        return broadphase_find_pairs(bp, proxies, slots, awake, awake_count);
    return pairs_reused(bp, proxies, slots, awake, awake_count);
}

void broadphase_free(pp_broadphase *bp)
{
    pp_free(bp->nodes);
    pp_free(bp->order);
    pp_free(bp->leaf);
    pp_free(bp->stack);
    pp_free(bp->roused);
    pp_free(bp->pairs);
    pp_free(bp->cand);
    pp_free(bp->grown);
    pp_free(bp->cand_awake);
    *bp = (pp_broadphase){0};
}
