/* Touching pairs across substeps. Each substep builds a new list from the narrowphase's pairs, then
 * compares it with the last one: a pair only in the new list began, one only in the old list ended.
 * A pair whose bodies all sleep (or are static) is not tested; it rests in a list of its own that no substep
 * visits until a body enters the awake set or is removed. The lists are sorted by handle ids so that a
 * pair is found by binary search. */
#include "alloc.h"
#include "status.h"
#include "world.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A one-way platform keeps a contact whose normal (platform to other body) is within 60° of its
 * direction: a body landing on it from above, not one entering from below or the side. */
#define ONE_WAY_COS 0.5

static int touch_cmp(const void *x, const void *y)
{
    const touch *p = x, *q = y;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    return p->b < q->b ? -1 : p->b > q->b;
}

int touch_order(const touch *p, const touch *q) { return touch_cmp(p, q); }

/* The pair in a sorted list, or NULL. A loop, not bsearch: it runs for every pair of every substep. An empty
 * list may have no buffer, and is never read. */
static const touch *search(const touch *key, const touch *list, int32_t n)
{
    int32_t lo = 0, hi = n;
    while (lo < hi) {
        const int32_t mid = lo + (hi - lo) / 2;
        const touch *t = &list[mid];
        if (t->a < key->a || (t->a == key->a && t->b < key->b))
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < n && list[lo].a == key->a && list[lo].b == key->b ? &list[lo] : NULL;
}

static bool listed(const touch *t, const touch *list, int32_t n) { return search(t, list, n) != NULL; }

void touch_sort(touch *list, int32_t n)
{
    if (n > 1)
        qsort(list, (size_t)n, sizeof *list, touch_cmp);
}

const touch *touch_find(const world *wd, uint64_t x, uint64_t y)
{
    const touch key = handle_slot(x) < handle_slot(y) ? (touch){x, y, 0, 0, {0}} : (touch){y, x, 0, 0, {0}};
    const touch *t = search(&key, wd->touch.pairs, wd->touch.count);
    return t ? t : search(&key, wd->touch.resting, wd->touch.resting_count);
}

/* A pair re-anchors (its static friction gave way) when a contact point has slipped this far, or the
 * bodies have turned this far against each other (a rolling body's contact moves round it). At 0.5 px,
 * FAST's 10 iterations let a 10-row pyramid creep past it, re-anchor and creep on (it fell at 49 s). */
#define ANCHOR_SLIP_PX 2.0
#define ANCHOR_TURN_RAD 0.05

static void relative_pose(const body *a, const body *b, double out[3])
{
    const dvec2 q = dv_unrot(dv_sub(b->pos, a->pos), a->cos_a, a->sin_a);
    out[0] = q.x, out[1] = q.y, out[2] = b->angle - a->angle;
}

dvec2 touch_anchor_slip(const touch *t, const body *a, const body *b, dvec2 p)
{
    const dvec2 x = dv_unrot(dv_sub(p, b->pos), b->cos_a, b->sin_a); /* the point in b's bitmap frame */
    const dvec2 then = dv_add(dv(t->anchor[0], t->anchor[1]), dv_rot(x, cos(t->anchor[2]), sin(t->anchor[2])));
    return dv_sub(p, dv_add(a->pos, dv_rot(then, a->cos_a, a->sin_a)));
}

/* Keep the old anchor while every contact point is within ANCHOR_SLIP_PX of it and the pair has not turned. */
static void set_anchor(const touch *old, const body *a, const body *b, const np_result *r, touch *t)
{
    double now[3];
    relative_pose(a, b, now);
    bool keep = old && !(old->flags & TOUCH_UNANCHORED) && fabs(now[2] - old->anchor[2]) <= ANCHOR_TURN_RAD;
    for (int32_t c = 0; keep && c < r->count; c++) {
        const dvec2 slip = touch_anchor_slip(old, a, b, dv(r->contacts[c].point.x, r->contacts[c].point.y));
        keep = dv_dot(slip, slip) <= ANCHOR_SLIP_PX * ANCHOR_SLIP_PX;
    }
    memcpy(t->anchor, keep ? old->anchor : now, sizeof now);
}

void touch_begin(world *wd) { wd->touch.next_count = 0; }

/* A BEGIN event from `from` to `to` at the pair's first contact (its normal points from a to b). */
static pp_event begin_event(const world *wd, pp_event_type type, const body *from, const body *to, const body *a,
                            const np_result *r)
{
    const pp_contact *c = &r->contacts[0];
    const double sign = from == a ? 1.0 : -1.0;
    const dvec2 p = dv(c->point.x, c->point.y), n = dv_scale(dv(c->normal.x, c->normal.y), sign);
    /* `to` closes on `from` when its velocity relative to `from` points against the normal. */
    const dvec2 rel = dv_sub(body_point_velocity(wd, to, p), body_point_velocity(wd, from, p));
    const double closing = -dv_dot(rel, n);
    return (pp_event){type, 0, from->handle, to->handle, c->point, {(float)n.x, (float)n.y},
                      (float)(closing > 0 ? closing : 0), 0, {0}};
}

/* A new pair with a one-way platform: let the other body through unless it comes from the allowed side. */
static bool one_way_passes(const body *a, const body *b, const np_result *r)
{
    const body *plat = a->one_way ? a : b;
    const dvec2 n = dv_scale(dv(r->contacts[0].normal.x, r->contacts[0].normal.y), plat == a ? 1.0 : -1.0);
    const dvec2 d = dv_rot(plat->one_way_dir, plat->cos_a, plat->sin_a);
    return dv_dot(n, d) < ONE_WAY_COS;
}

pp_status touch_pair(world *wd, const body *a, const body *b, const np_result *r, bool *keep)
{
    *keep = true;
    if (a->is_sensor && b->is_sensor) {
        *keep = false; /* sensors sense bodies, not each other */
        return PP_OK;
    }
    const bool sensor = a->is_sensor || b->is_sensor, one_way = a->one_way || b->one_way;
    const touch *old = touch_find(wd, a->handle.id, b->handle.id);
    touch t = {a->handle.id, b->handle.id, sensor ? TOUCH_SENSOR | (a->is_sensor ? 0 : TOUCH_SENSOR_B) : 0, 0, {0}};
    set_anchor(old, a, b, r, &t);
    if (old)
        t.flags = old->flags & ~(uint32_t)TOUCH_UNANCHORED;
    else if (!sensor && one_way && one_way_passes(a, b, r))
        t.flags |= TOUCH_PASSING;
    *keep = !(t.flags & (TOUCH_SENSOR | TOUCH_PASSING));
    /* Room for the record and its event first: a failure changes nothing. */
    pp_status st = world_reserve_events(wd, 1, "pp_world_step");
    if (st || !ARRAY_RESERVE(wd->touch.next, wd->touch.next_capacity, wd->touch.next_count + 1))
        return st ? st : pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for %d touching pairs",
                                 (int)wd->touch.next_count + 1);
    touch *rec = &wd->touch.next[wd->touch.next_count++];
    *rec = t;
    if (t.flags & TOUCH_PASSING)
        return PP_OK;
    if (sensor) { /* the sensor is the event's body */
        if (!old)
            world_queue_event(wd, a->is_sensor ? begin_event(wd, PP_EVENT_SENSOR_BEGIN, a, b, a, r)
                                               : begin_event(wd, PP_EVENT_SENSOR_BEGIN, b, a, a, r));
    } else if (!wd->def.contact_events) {
        rec->flags &= ~(uint32_t)TOUCH_BEGUN; /* switched off: ends silently, begins again if switched on */
    } else if (!(t.flags & TOUCH_BEGUN)) { /* new, or touching since events were switched on */
        world_queue_event(wd, begin_event(wd, PP_EVENT_CONTACT_BEGIN, a, b, a, r));
        rec->flags |= TOUCH_BEGUN;
    }
    return PP_OK;
}

/* An old pair not found this substep: still touching if neither body was awake to be tested. */
static bool untested(const world *wd, const touch *t)
{
    const body *a = body_find(wd, (pp_body){t->a}), *b = body_find(wd, (pp_body){t->b});
    PP_ASSERT(wd->awake.proxy_capacity >= wd->body_ids.capacity);
    return a && b && !wd->awake.proxies[a->index].awake && !wd->awake.proxies[b->index].awake;
}

/* Merge two sorted runs of pairs into out. */
static void merge(const touch *x, int32_t nx, const touch *y, int32_t ny, touch *out)
{
    int32_t i = 0, j = 0, k = 0;
    while (i < nx && j < ny)
        out[k++] = touch_cmp(&x[i], &y[j]) <= 0 ? x[i++] : y[j++];
    while (i < nx)
        out[k++] = x[i++];
    while (j < ny)
        out[k++] = y[j++];
}

/* Take the resting pairs back into the touching ones, to be tested again. */
static pp_status wake_resting(world *wd)
{
    const int32_t n = wd->touch.count + wd->touch.resting_count;
    pp_status st = step_save_touching(wd, true);
    if (st || !ARRAY_RESERVE(wd->touch.resting_next, wd->touch.resting_next_capacity, n))
        return st ? st : pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for %d touching pairs", (int)n);
    merge(wd->touch.pairs, wd->touch.count, wd->touch.resting, wd->touch.resting_count, wd->touch.resting_next);
    touch *list = wd->touch.pairs;
    const int32_t cap = wd->touch.capacity;
    wd->touch.pairs = wd->touch.resting_next, wd->touch.count = n, wd->touch.capacity = wd->touch.resting_next_capacity;
    wd->touch.resting_next = list, wd->touch.resting_next_capacity = cap;
    wd->touch.resting_count = 0;
    return PP_OK;
}

/* Put n pairs (sorted) to rest beside those resting already. */
static pp_status put_to_rest(world *wd, const touch *pairs, int32_t n)
{
    const int32_t total = wd->touch.resting_count + n;
    pp_status st = step_save_touching(wd, true);
    if (st || !ARRAY_RESERVE(wd->touch.resting_next, wd->touch.resting_next_capacity, total))
        return st ? st : pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for %d resting pairs", (int)total);
    merge(wd->touch.resting, wd->touch.resting_count, pairs, n, wd->touch.resting_next);
    touch *list = wd->touch.resting;
    const int32_t cap = wd->touch.resting_capacity;
    wd->touch.resting = wd->touch.resting_next, wd->touch.resting_count = total;
    wd->touch.resting_capacity = wd->touch.resting_next_capacity;
    wd->touch.resting_next = list, wd->touch.resting_next_capacity = cap;
    return PP_OK;
}

pp_status touch_end(world *wd)
{
    const int32_t found = wd->touch.next_count;
    /* Nothing awake, found, removed or woken: every pair still touches, untested. No pair at all: nothing to
     * do, and maybe no buffers yet (NULL + 0 below would be undefined, fuzz_scene). */
    if (found + wd->touch.count + wd->touch.resting_count == 0 ||
        (found == 0 && wd->awake.movers == 0 && !wd->touch.body_gone && !wd->touch.resting_stale))
        return PP_OK;
    touch_sort(wd->touch.next, found);
    pp_status st = step_save_touching(wd, false);
    /* Resting pairs are tested again when a body woke or went, or one was found (a sleeper an awake body roused). */
    bool review = wd->touch.resting_stale || wd->touch.body_gone;
    for (int32_t i = 0; !review && i < found; i++)
        review = listed(&wd->touch.next[i], wd->touch.resting, wd->touch.resting_count);
    if (!st && review && wd->touch.resting_count > 0)
        st = wake_resting(wd);
    /* Room for the worst case first (every old pair resting, or ended with an event). */
    const int32_t n = found + wd->touch.count;
    if (!st)
        st = world_reserve_events(wd, wd->touch.count, "pp_world_step");
    if (st || !ARRAY_RESERVE(wd->touch.next, wd->touch.next_capacity, n) ||
        !ARRAY_RESERVE(wd->touch.pairs, wd->touch.capacity, found))
        return st ? st : pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for %d touching pairs", (int)n);
    wd->touch.body_gone = wd->touch.resting_stale = false;
    for (int32_t i = 0; i < wd->touch.count; i++) {
        const touch *t = &wd->touch.pairs[i];
        if (listed(t, wd->touch.next, found))
            continue;
        if (untested(wd, t)) { /* to rest, after the found pairs */
            PP_ASSERT(wd->touch.next_count < wd->touch.next_capacity);
            wd->touch.next[wd->touch.next_count++] = *t;
            continue;
        }
        if (t->flags & TOUCH_PASSING)
            continue; /* a body that went through a one-way platform never touched it */
        const bool b_first = (t->flags & TOUCH_SENSOR_B) != 0; /* the sensor is the event's body */
        const pp_body first = {b_first ? t->b : t->a}, second = {b_first ? t->a : t->b};
        if (t->flags & TOUCH_SENSOR)
            world_queue_event(wd, (pp_event){PP_EVENT_SENSOR_END, 0, first, second, {0, 0}, {0, 0}, 0, 0, {0}});
        else if (wd->def.contact_events && (t->flags & TOUCH_BEGUN))
            world_queue_event(wd, (pp_event){PP_EVENT_CONTACT_END, 0, first, second, {0, 0}, {0, 0}, 0, 0, {0}});
    }
    /* The found pairs are the touching ones now; the untested ones (in the old list's order) go to rest. */
    if (found > 0)
        memcpy(wd->touch.pairs, wd->touch.next, (size_t)found * sizeof *wd->touch.pairs);
    wd->touch.count = found;
    const int32_t resting = wd->touch.next_count - found;
    wd->touch.next_count = 0;
    return resting > 0 ? put_to_rest(wd, wd->touch.next + found, resting) : PP_OK;
}

void touch_free(touch_set *t)
{
    pp_free(t->pairs);
    pp_free(t->resting);
    pp_free(t->next);
    pp_free(t->resting_next);
    *t = (touch_set){0};
}
