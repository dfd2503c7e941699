/* The awake set (awake.h): a list of body slots with each listed body's place in it, so that adding and
 * forgetting a body cost O(1); it is sorted by slot at each substep's start, when it changed. */
#include "awake.h"
#include "alloc.h"
#include "status.h"

#include <math.h>
#include <stdlib.h>

pp_status awake_reserve(world *wd, int32_t n, const char *fn)
{
    if (!ARRAY_RESERVE(wd->awake.slots, wd->awake.capacity, n) ||
        !ARRAY_RESERVE(wd->awake.changed, wd->awake.changed_capacity, n) ||
        !ARRAY_RESERVE(wd->awake.by_x, wd->awake.by_x_capacity, n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d awake bodies", fn, (int)n);
    return PP_OK;
}

/* Into the changed list, once (room reserved with the set's). */
static void note_changed(world *wd, body *bd)
{
    if (bd->changed_at >= 0)
        return;
    PP_ASSERT(wd->awake.changed_count < wd->awake.changed_capacity);
    bd->changed_at = wd->awake.changed_count;
    wd->awake.changed[wd->awake.changed_count++] = (int32_t)bd->index;
}

static void clear_changed(world *wd)
{
    for (int32_t k = 0; k < wd->awake.changed_count; k++)
        wd->bodies[wd->awake.changed[k]]->changed_at = -1;
    wd->awake.changed_count = 0;
}

void awake_slept(world *wd, body *bd)
{
    if (bd->awake_at >= 0)
        note_changed(wd, bd);
}

void awake_moved(world *wd, body *bd)
{
    awake_add(wd, bd);
    note_changed(wd, bd);
}

void awake_add(world *wd, body *bd)
{
    if (bd->awake_at >= 0)
        return;
    note_changed(wd, bd);
    PP_ASSERT(wd->awake.count < wd->awake.capacity); /* awake_reserve at creation */
    wd->table.resting_stale = true; /* it may be in a resting pair (contact_table.c) */
    const int32_t n = wd->awake.count++;
    wd->awake.slots[n] = (int32_t)bd->index;
    bd->awake_at = n;
    wd->awake.sorted = wd->awake.sorted && (n == 0 || wd->awake.slots[n - 1] < (int32_t)bd->index);
}

void awake_wake(world *wd, body *bd)
{
    solver_body_wake(&bd->sb);
    awake_add(wd, bd);
}

void awake_forget(world *wd, body *bd)
{
    if (bd->index < (uint32_t)wd->awake.proxy_capacity)
        wd->awake.proxies[bd->index].live = false;
    broadphase_remove(&wd->broad, bd->index);
    const int32_t c = bd->changed_at;
    if (c >= 0) {
        const int32_t last_changed = wd->awake.changed[--wd->awake.changed_count];
        wd->awake.changed[c] = last_changed;
        wd->bodies[last_changed]->changed_at = c;
        bd->changed_at = -1;
    }
    const int32_t at = bd->awake_at;
    if (at < 0)
        return;
    const int32_t last = wd->awake.slots[--wd->awake.count];
    if (at < wd->awake.count) {
        wd->awake.slots[at] = last;
        wd->bodies[last]->awake_at = at;
        wd->awake.sorted = false;
    }
    bd->awake_at = -1;
}

void awake_rebuild(world *wd)
{
    clear_changed(wd);
    awake_index_stale(wd);
    wd->awake.count = 0;
    wd->awake.sorted = true;
    for (int32_t i = 0; i < wd->body_ids.capacity; i++)
        if (wd->bodies[i])
            wd->bodies[i]->awake_at = -1;
    for (int32_t i = 0; i < wd->body_ids.capacity; i++)
        if (wd->bodies[i])
            awake_add(wd, wd->bodies[i]);
}

static int slot_order(const void *x, const void *y)
{
    const int32_t a = *(const int32_t *)x, b = *(const int32_t *)y;
    return (a > b) - (a < b);
}

/* The broadphase's view of a body now. */
static bp_proxy proxy_of(const body *bd)
{
    return (bp_proxy){bd->aabb, bd->category_bits, bd->mask_bits, bd->type != PP_BODY_STATIC,
                      bd->type == PP_BODY_DYNAMIC, bd->type != PP_BODY_STATIC && (!bd->sb.body || awake_mover(bd)),
                      true};
}

pp_status awake_refresh(world *wd)
{
    const int32_t had = wd->awake.proxy_capacity;
    if (!ARRAY_RESERVE(wd->awake.proxies, wd->awake.proxy_capacity, wd->body_ids.capacity))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for the broadphase");
    for (int32_t i = had; i < wd->awake.proxy_capacity; i++) /* new slots hold no body until one is listed */
        wd->awake.proxies[i] = (bp_proxy){.live = false};
    for (int32_t k = 0; k < wd->awake.count; k++) {
        const int32_t i = wd->awake.slots[k];
        wd->awake.proxies[i] = proxy_of(wd->bodies[i]);
        if (broadphase_update_is_idle(&wd->broad, &wd->awake.proxies[i], (uint32_t)i, wd->body_ids.capacity))
            continue;
        pp_status st = broadphase_update(&wd->broad, &wd->awake.proxies[i], (uint32_t)i, wd->body_ids.capacity);
        if (st)
            return st;
    }
    clear_changed(wd); /* every listed body left is an awake mover, the rest are in the tree */
    awake_index_stale(wd);
    int32_t kept = 0, movers = 0;
    for (int32_t k = 0; k < wd->awake.count; k++) {
        const int32_t i = wd->awake.slots[k];
        body *bd = wd->bodies[i];
        movers += wd->awake.proxies[i].awake;
        if (awake_mover(bd))
            wd->awake.slots[kept++] = i;
        else
            bd->awake_at = -1;
    }
    wd->awake.count = kept;
    wd->awake.movers = movers;
    if (!wd->awake.sorted && kept > 1)
        qsort(wd->awake.slots, (size_t)kept, sizeof *wd->awake.slots, slot_order);
    for (int32_t k = 0; k < kept; k++)
        wd->bodies[wd->awake.slots[k]]->awake_at = k;
    wd->awake.sorted = true;
    return PP_OK;
}

/* Slack on a step box, px: what the velocity read at the step's start leaves out but rounding. */
#define STEP_BOX_SLACK 0.5

/* Where a body's box can reach in dt s from its velocity now: its box and the box moved by v·dt, grown by what
 * a turn at w moves its corners and by `fall`, gravity's ½·g·dt². A push harder than that (a collision) leaves
 * it, and the later substeps search again. */
static pp_aabb step_box(const world *wd, const body *bd, double dt, double fall)
{
    dvec2 v = dv(0, 0);
    double w = 0;
    if (bd->sb.body)
        solver_body_get_velocity(wd->solver, &bd->sb, &v, &w);
    const pp_aabb b = bd->aabb;
    const double half_diagonal = 0.5 * ((b.x1 - b.x0) + (b.y1 - b.y0)); /* at least it */
    const double m = fabs(w) * dt * half_diagonal + fall + STEP_BOX_SLACK;
    const double dx = v.x * dt, dy = v.y * dt;
    return (pp_aabb){b.x0 + dmin(dx, 0) - m, b.y0 + dmin(dy, 0) - m, b.x1 + dmax(dx, 0) + m, b.y1 + dmax(dy, 0) + m};
}

pp_status awake_find_pairs(world *wd, int32_t k, double dt)
{
    awake_set *a = &wd->awake;
    const int32_t slots = wd->body_ids.capacity;
    if (k > 0)
        return broadphase_find_later_pairs(&wd->broad, a->proxies, slots, a->slots, a->count);
    if (wd->def.substeps == 1) /* no later substep to find pairs for */
        return broadphase_find_pairs(&wd->broad, a->proxies, slots, a->slots, a->count);
    if (!ARRAY_RESERVE(a->step_boxes, a->step_box_capacity, slots))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for the broadphase");
    const double fall = 0.5 * hypot(wd->def.gravity.x, wd->def.gravity.y) * dt * dt;
    for (int32_t i = 0; i < a->count; i++) {
        const int32_t s = a->slots[i];
        if (a->proxies[s].awake)
            a->step_boxes[s] = step_box(wd, wd->bodies[s], dt, fall);
    }
    return broadphase_find_step_pairs(&wd->broad, a->proxies, slots, a->slots, a->count, a->step_boxes);
}

typedef struct box_visit {
    world *wd;
    pp_aabb box;
    bool (*visit)(world *wd, body *bd, void *user);
    void *user;
    bool stopped;  /* a visit returned false */
} box_visit;

/* A leaf whose fat box meets the query: its body, unless it is listed (the set's loop takes those). */
static bool visit_leaf(uint32_t slot, void *user)
{
    box_visit *v = user;
    body *bd = v->wd->bodies[slot];
    if (bd->awake_at >= 0 || !aabb_overlap(&bd->aabb, &v->box) || v->visit(v->wd, bd, v->user))
        return true;
    v->stopped = true;
    return false;
}

static int by_x0(const void *x, const void *y)
{
    const awake_entry *a = x, *b = y;
    return a->x0 != b->x0 ? (a->x0 > b->x0) - (a->x0 < b->x0) : (a->slot > b->slot) - (a->slot < b->slot);
}

/* The awake movers by their boxes' x0 (then slot), as they are now. Room was reserved with the set's. */
static void build_index(world *wd)
{
    awake_set *a = &wd->awake;
    a->by_x_count = 0;
    a->by_x_width = 0;
    for (int32_t k = 0; k < a->count; k++) {
        const body *bd = wd->bodies[a->slots[k]];
        if (!awake_mover(bd))
            continue;
        a->by_x[a->by_x_count++] = (awake_entry){bd->aabb.x0, a->slots[k]};
        a->by_x_width = dmax(a->by_x_width, bd->aabb.x1 - bd->aabb.x0);
    }
    if (a->by_x_count > 1)
        qsort(a->by_x, (size_t)a->by_x_count, sizeof *a->by_x, by_x0);
    a->by_x_valid = true;
}

void awake_each_in_box(world *wd, pp_aabb box, bool (*visit)(world *wd, body *bd, void *user), void *user)
{
    box_visit v = {wd, box, visit, user, false};
    broadphase_query(&wd->broad, box, visit_leaf, &v);
    /* Bodies a visit lists or moves join the changed list: walk the count and the index as they were. */
    const int32_t changed = wd->awake.changed_count;
    for (int32_t k = 0; k < changed && !v.stopped; k++) {
        body *bd = wd->bodies[wd->awake.changed[k]];
        if (bd->awake_at >= 0 && aabb_overlap(&bd->aabb, &box) && !visit(wd, bd, user))
            return;
    }
    if (v.stopped)
        return;
    if (!wd->awake.by_x_valid)
        build_index(wd);
    const awake_set *a = &wd->awake;
    /* The first entry past box.x1, then back while an entry as wide as the widest could still reach box.x0. */
    int32_t lo = 0, hi = a->by_x_count;
    while (lo < hi) {
        const int32_t mid = lo + (hi - lo) / 2;
        if (a->by_x[mid].x0 <= box.x1)
            lo = mid + 1;
        else
            hi = mid;
    }
    for (int32_t k = lo - 1; k >= 0 && a->by_x[k].x0 >= box.x0 - a->by_x_width; k--) {
        body *bd = wd->bodies[a->by_x[k].slot];
        /* Gone, asleep or moved since (then the changed list had it): not this entry's to visit. */
        if (!bd || bd->awake_at < 0 || bd->changed_at >= 0 || !awake_mover(bd))
            continue;
        if (aabb_overlap(&bd->aabb, &box) && !visit(wd, bd, user))
            return;
    }
}

/* A growing list of slots. */
typedef struct slot_list {
    int32_t *slots;
    int32_t count, capacity;
    bool failed;
} slot_list;

static bool list_slot(world *wd, body *bd, void *user)
{
    slot_list *l = user;
    if (!ARRAY_RESERVE(l->slots, l->capacity, l->count + 1))
        return l->failed = true, false;
    l->slots[l->count++] = (int32_t)bd->index;
    return true;
}

/* The bodies whose box meets `box` appended to l, then sorted into slot order. */
static void collect_in_box(world *wd, pp_aabb box, slot_list *l)
{
    awake_each_in_box(wd, box, list_slot, l);
    if (l->failed)
        return;
    if (l->count > 1)
        qsort(l->slots, (size_t)l->count, sizeof *l->slots, slot_order);
#ifdef PP_CHECKS
    /* The same bodies as a walk of every live body finds. */
    int32_t expected = 0;
    for (int32_t i = 0; i < wd->body_ids.capacity; i++) {
        const body *bd = wd->bodies[i];
        if (bd && aabb_overlap(&bd->aabb, &box)) {
            PP_ASSERT(expected < l->count && l->slots[expected] == i);
            expected++;
        }
    }
    PP_ASSERT(expected == l->count);
#endif
}

pp_status awake_bodies_in_box(world *wd, const char *fn, pp_aabb box, int32_t **slots, int32_t *n)
{
    slot_list l = {NULL, 0, 0, false};
    collect_in_box(wd, box, &l);
    if (l.failed) {
        pp_free(l.slots);
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for the bodies near (%g, %g)", fn,
                       0.5 * (box.x0 + box.x1), 0.5 * (box.y0 + box.y1));
    }
    *slots = l.slots, *n = l.count;
    return PP_OK;
}

int32_t awake_slots_in_box(world *wd, pp_aabb box, int32_t *slots)
{
    slot_list l = {slots, 0, wd->body_ids.capacity, false}; /* room for every slot: it never grows */
    collect_in_box(wd, box, &l);
    PP_ASSERT(!l.failed && l.slots == slots);
    return l.count;
}

static bool wake_movable(world *wd, body *bd, void *user)
{
    (void)user;
    if (bd->sb.body)
        awake_wake(wd, bd);
    return true;
}

/* A leaf whose fat box meets the query: wake its body (a listed one is an awake mover or in the changed list). */
static bool wake_leaf(uint32_t slot, void *user)
{
    box_visit *v = user;
    body *bd = v->wd->bodies[slot];
    if (bd->awake_at < 0 && aabb_overlap(&bd->aabb, &v->box))
        wake_movable(v->wd, bd, NULL);
    return true;
}

void awake_wake_in_box(world *wd, pp_aabb box)
{
#ifdef PP_CHECKS
    /* Every listed body that needs waking is in the changed list. */
    for (int32_t k = 0; k < wd->awake.count; k++) {
        const body *bd = wd->bodies[wd->awake.slots[k]];
        PP_ASSERT(!bd->sb.body || awake_mover(bd) || bd->changed_at >= 0);
    }
#endif
    box_visit v = {wd, box, wake_movable, NULL, false};
    broadphase_query(&wd->broad, box, wake_leaf, &v);
    /* Waking lists a body and may add to the list: walk the count the query left. */
    for (int32_t k = 0; k < wd->awake.changed_count; k++) {
        body *bd = wd->bodies[wd->awake.changed[k]];
        if (bd->awake_at >= 0 && aabb_overlap(&bd->aabb, &box))
            wake_movable(wd, bd, NULL);
    }
}

void awake_free(awake_set *a)
{
    pp_free(a->slots);
    pp_free(a->changed);
    pp_free(a->by_x);
    pp_free(a->proxies);
    pp_free(a->step_boxes);
    *a = (awake_set){0};
}
