/* The contact table (contact_table.h): every touching pair's record, found by a hash of its two slots, the
 * awake pairs before the resting ones. Each substep stamps the pairs the narrowphase finds; the pass after it
 * ends the awake pairs it did not find and puts to rest those it could not have found. */
#include "alloc.h"
#include "awake.h"
#include "contact_solve.h"
#include "status.h"
#include "world.h"

#include <math.h>
#include <string.h>

/* A one-way platform keeps a contact whose normal (platform to other body) is within 60° of its
 * direction: a body landing on it from above, not one entering from below or the side. */
#define ONE_WAY_COS 0.5

static uint64_t key_of(const contact_record *r) { return pair_key(handle_slot(r->a), handle_slot(r->b)); }

static int32_t lookup(const contact_table *t, uint64_t key) { return pair_map_get(&t->index, key); }

static void index_rebuild(contact_table *t)
{
    pair_map_clear(&t->index);
    for (int32_t i = 0; i < t->count; i++)
        if (!(t->records[i].flags & CT_GONE))
            pair_map_set(&t->index, key_of(&t->records[i]), i);
}

/* Room for n records and their keys. */
static pp_status reserve(contact_table *t, int32_t n, const char *fn)
{
    if (!ARRAY_RESERVE(t->records, t->capacity, n) || !pair_map_reserve(&t->index, n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d touching pairs", fn, (int)n);
    return PP_OK;
}

/* ---- records, each change logged for a failed step ------------------------------------------------- */

/* Keep the record at i as the step found it, once a step (only a step logs: saved_count is 0 outside one). */
static void log_record(contact_table *t, int32_t i)
{
    if (i >= t->saved_count || t->logged[i] == t->step)
        return;
    PP_ASSERT(t->log_count < t->log_capacity && t->log_count < t->log_at_capacity);
    t->logged[i] = t->step;
    t->log[t->log_count] = t->records[i];
    t->log_at[t->log_count++] = i;
}

static contact_record *edit(contact_table *t, int32_t i)
{
    log_record(t, i);
    return &t->records[i];
}

/* The record now at i: the hash, the carry order and the substep's runs find it there. */
static void placed(contact_table *t, int32_t i)
{
    const contact_record *r = &t->records[i];
    if (!(r->flags & CT_GONE))
        pair_map_set(&t->index, key_of(r), i);
    if (r->carried)
        t->carry_order[r->carried - 1] = i;
    if (r->found == t->substep && r->run >= 0 && r->run < t->run_count && t->runs[r->run].a == handle_slot(r->a) &&
        t->runs[r->run].b == handle_slot(r->b))
        t->runs[r->run].record = i;
}

static void move(contact_table *t, int32_t from, int32_t to)
{
    *edit(t, to) = t->records[from];
    placed(t, to);
}

static void swap(contact_table *t, int32_t i, int32_t j)
{
    if (i == j)
        return;
    const contact_record ri = t->records[i];
    move(t, j, i);
    *edit(t, j) = ri;
    placed(t, j);
}

/* A resting record into the awake part; returns where it is now. */
static int32_t wake_record(contact_table *t, int32_t i)
{
    PP_ASSERT(i >= t->awake && i < t->count);
    swap(t, i, t->awake);
    return t->awake++;
}

static void rest_record(contact_table *t, int32_t i)
{
    PP_ASSERT(i < t->awake);
    swap(t, i, --t->awake);
}

/* An awake record out of the table: the last awake one takes its place, the last resting one that one's. */
static void remove_record(contact_table *t, int32_t i)
{
    PP_ASSERT(i < t->awake);
    if (!(t->records[i].flags & CT_GONE))
        pair_map_remove(&t->index, key_of(&t->records[i]));
    if (t->records[i].carried) /* its place in the carry order stays empty until carry.c keeps the rest */
        t->carry_order[t->records[i].carried - 1] = -1;
    const int32_t last_awake = t->awake - 1, last = t->count - 1;
    if (i != last_awake)
        move(t, last_awake, i);
    if (last_awake != last)
        move(t, last, last_awake);
    t->awake--, t->count--;
}

/* A new record into the awake part (room reserved): the first resting record moves to the end. */
static int32_t insert_record(contact_table *t, const contact_record *rec)
{
    PP_ASSERT(t->count < t->capacity && 2 * (t->count + 1) <= t->index.capacity);
    if (t->awake < t->count)
        move(t, t->awake, t->count);
    const int32_t i = t->awake++;
    t->count++;
    *edit(t, i) = *rec;
    placed(t, i);
    return i;
}

int32_t contact_table_lookup(const world *wd, uint32_t a, uint32_t b) { return lookup(&wd->table, pair_key(a, b)); }

contact_record *contact_table_edit(world *wd, int32_t i)
{
    PP_ASSERT(i >= 0 && i < wd->table.count);
    return edit(&wd->table, i);
}

/* ---- the carry order ------------------------------------------------------------------------------- */

pp_status contact_table_reserve_carried(world *wd, int32_t n, const char *fn)
{
    contact_table *t = &wd->table;
    if (!ARRAY_RESERVE(t->carry_order, t->carry_capacity, n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory to carry %d pairs", fn, (int)n);
    return PP_OK;
}

void contact_table_carry(world *wd, int32_t i)
{
    contact_table *t = &wd->table;
    PP_ASSERT(t->carry_count < t->carry_capacity && !t->records[i].carried && !(t->records[i].flags & CT_GONE));
    t->carry_order[t->carry_count++] = i;
    edit(t, i)->carried = t->carry_count;
}

void contact_table_keep_carried(world *wd, bool (*keep)(const world *, const contact_record *, const void *),
                                const void *arg)
{
    contact_table *t = &wd->table;
    int32_t n = 0;
    for (int32_t k = 0; k < t->carry_count; k++) {
        const int32_t i = t->carry_order[k];
        if (i < 0)
            continue; /* ended */
        if (!keep(wd, &t->records[i], arg)) {
            contact_record *r = edit(t, i);
            r->carried = 0, r->carry_count = 0, r->carry_last = 0, r->carry_flags = 0;
            continue;
        }
        if (t->records[i].carried != n + 1)
            edit(t, i)->carried = n + 1;
        t->carry_order[n++] = i;
    }
    t->carry_count = n;
}

const contact_record *contact_table_find(const world *wd, uint64_t x, uint64_t y)
{
    const uint32_t sx = handle_slot(x), sy = handle_slot(y);
    const int32_t i = lookup(&wd->table, sx < sy ? pair_key(sx, sy) : pair_key(sy, sx));
    if (i < 0)
        return NULL;
    const contact_record *r = &wd->table.records[i];
    return (r->a == x && r->b == y) || (r->a == y && r->b == x) ? r : NULL;
}

/* ---- friction anchors ------------------------------------------------------------------------------ */

/* A pair re-anchors (its static friction gave way) when a contact point has slipped this far, or the
 * bodies have turned this far against each other (a rolling body's contact moves round it). At 0.5 px,
 * FAST's 10 iterations let a 10-row pyramid creep past it, re-anchor and creep on (it fell at 49 s); at 2 px
 * the top tent of Box2D v3's card house, swaying 1.5 px on its one-pixel apex, did the same at ACCURATE. */
#define ANCHOR_SLIP_PX 4.0
#define ANCHOR_TURN_RAD 0.05

static void relative_pose(const body *a, const body *b, double out[3])
{
    const dvec2 q = dv_unrot(dv_sub(b->pos, a->pos), a->cos_a, a->sin_a);
    out[0] = q.x, out[1] = q.y, out[2] = b->angle - a->angle;
}

dvec2 contact_anchor_slip(const contact_record *t, const body *a, const body *b, dvec2 p)
{
    const dvec2 x = dv_unrot(dv_sub(p, b->pos), b->cos_a, b->sin_a); /* the point in b's bitmap frame */
    const dvec2 then = dv_add(dv(t->anchor[0], t->anchor[1]), dv_rot(x, t->anchor_cos, t->anchor_sin));
    return dv_sub(p, dv_add(a->pos, dv_rot(then, a->cos_a, a->sin_a)));
}

void contact_table_locate_carried(contact_record *r)
{
    const carried_pose *q = &r->carry_pose;
    for (int32_t k = 0; k < r->carry_count; k++) {
        const dvec2 p = dv(r->carry_points[k].point.x, r->carry_points[k].point.y);
        r->carry_local[k][0] = dv_unrot(dv_sub(p, q->com_a), q->cos_a, q->sin_a);
        r->carry_local[k][1] = dv_unrot(dv_sub(p, q->com_b), q->cos_b, q->sin_b);
    }
}

static void anchor_turn(contact_record *t)
{
    t->anchor_cos = cos(t->anchor[2]);
    t->anchor_sin = sin(t->anchor[2]);
}

/* px: a slip bound this far under ANCHOR_SLIP_PX is under it however the slips round. */
#define ANCHOR_BOUND_SLACK 1e-6

/* Whether every point of r has surely slipped less than ANCHOR_SLIP_PX from the anchor, pose `now`
 * (relative_pose): a point x px from b's pivot has slipped at most |now's offset − the anchor's| + x·|turn|. */
static bool slips_under_bound(const contact_record *t, const body *b, const np_result *r, const double now[3])
{
    double far2 = 0;
    for (int32_t c = 0; c < r->count; c++) {
        const dvec2 x = dv_sub(dv(r->contacts[c].point.x, r->contacts[c].point.y), b->pos);
        far2 = dmax(far2, dv_dot(x, x));
    }
    const dvec2 d = dv(now[0] - t->anchor[0], now[1] - t->anchor[1]);
    return sqrt(dv_dot(d, d)) + sqrt(far2) * fabs(now[2] - t->anchor[2]) < ANCHOR_SLIP_PX - ANCHOR_BOUND_SLACK;
}

/* Keep the old anchor while every contact point is within ANCHOR_SLIP_PX of it and the pair has not turned
 * (old may be out). */
static void set_anchor(const contact_record *old, const body *a, const body *b, const np_result *r,
                       contact_record *out)
{
    double now[3];
    relative_pose(a, b, now);
    bool keep = old && !(old->flags & CT_UNANCHORED) && fabs(now[2] - old->anchor[2]) <= ANCHOR_TURN_RAD;
    /* Most pairs hold still: the bound answers without each point's slip. */
    const bool measure = keep && !slips_under_bound(old, b, r, now);
    for (int32_t c = 0; measure && keep && c < r->count; c++) {
        const dvec2 slip = contact_anchor_slip(old, a, b, dv(r->contacts[c].point.x, r->contacts[c].point.y));
        keep = dv_dot(slip, slip) <= ANCHOR_SLIP_PX * ANCHOR_SLIP_PX;
    }
#ifdef PP_CHECKS
    for (int32_t c = 0; keep && !measure && c < r->count; c++) { /* the bound never keeps what a slip would not */
        const dvec2 slip = contact_anchor_slip(old, a, b, dv(r->contacts[c].point.x, r->contacts[c].point.y));
        PP_ASSERT(dv_dot(slip, slip) <= ANCHOR_SLIP_PX * ANCHOR_SLIP_PX);
    }
#endif
    if (keep && old != out) {
        memcpy(out->anchor, old->anchor, sizeof now);
        out->anchor_cos = old->anchor_cos, out->anchor_sin = old->anchor_sin;
    } else if (!keep) {
        memcpy(out->anchor, now, sizeof now);
        anchor_turn(out);
    }
}

/* ---- a substep's pass ------------------------------------------------------------------------------ */

void contact_table_begin_substep(world *wd)
{
    contact_table *t = &wd->table;
    if (++t->substep == 0) { /* wrapped: no record's stamp may look current */
        for (int32_t i = 0; i < t->count; i++)
            edit(t, i)->found = 0, t->records[i].claimed = 0;
        t->substep = 1;
    }
    t->found_count = 0;
    t->run_count = 0; /* added again with the substep's contacts (contact_table_add_run) */
}

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

pp_status contact_table_found(world *wd, const body *a, const body *b, const np_result *r, int32_t *at, bool *keep)
{
    static const char *fn = "pp_world_step";
    *keep = true;
    if (a->is_sensor && b->is_sensor) {
        *keep = false; /* sensors sense bodies, not each other */
        return PP_OK;
    }
    contact_table *t = &wd->table;
    int32_t i = *at >= 0 ? *at : lookup(t, pair_key(a->index, b->index));
    PP_ASSERT(i == lookup(t, pair_key(a->index, b->index)));
    PP_ASSERT(i < 0 || (t->records[i].a == a->handle.id && t->records[i].b == b->handle.id));
    /* Room for the record and its event first: a failure changes nothing. */
    pp_status st = world_reserve_events(wd, 1, fn);
    if (st || (i < 0 && (st = reserve(t, t->count + 1, fn))))
        return st;
    const bool sensor = a->is_sensor || b->is_sensor, one_way = a->one_way || b->one_way;
    contact_record fresh, *rec = &fresh;
    if (i >= 0) { /* the pair as it was: its flags, manifold and carried contacts */
        if (i >= t->awake)
            i = wake_record(t, i); /* a sleeper an awake body roused */
        rec = edit(t, i);
        set_anchor(rec, a, b, r, rec);
        rec->flags &= ~(uint32_t)CT_UNANCHORED;
    } else {
        fresh = (contact_record){.a = a->handle.id, .b = b->handle.id,
                                 .flags = sensor ? CT_SENSOR | (a->is_sensor ? 0 : CT_SENSOR_B) : 0};
        set_anchor(NULL, a, b, r, rec);
        if (!sensor && one_way && one_way_passes(a, b, r))
            rec->flags |= CT_PASSING;
    }
    rec->found = t->substep;
    rec->run = -1; /* until its contacts are added (contact_table_add_run) */
    *keep = !(rec->flags & (CT_SENSOR | CT_PASSING));
    if (!*keep)
        rec->point_count = 0;
    t->found_count++;
    if (!(rec->flags & CT_PASSING)) {
        if (sensor) { /* the sensor is the event's body */
            if (i < 0)
                world_queue_event(wd, a->is_sensor ? begin_event(wd, PP_EVENT_SENSOR_BEGIN, a, b, a, r)
                                                   : begin_event(wd, PP_EVENT_SENSOR_BEGIN, b, a, a, r));
        } else if (!wd->def.contact_events) {
            rec->flags &= ~(uint32_t)CT_BEGUN; /* switched off: ends silently, begins again if switched on */
        } else if (!(rec->flags & CT_BEGUN)) { /* new, or touching since events were switched on */
            world_queue_event(wd, begin_event(wd, PP_EVENT_CONTACT_BEGIN, a, b, a, r));
            rec->flags |= CT_BEGUN;
        }
    }
    *at = i >= 0 ? i : insert_record(t, rec);
    return PP_OK;
}

/* A pair not found this substep still touches if neither body was awake to be tested. */
static bool untested(const world *wd, const contact_record *r)
{
    const body *a = body_find(wd, (pp_body){r->a}), *b = body_find(wd, (pp_body){r->b});
    PP_ASSERT(wd->awake.proxy_capacity >= wd->body_ids.capacity);
    return a && b && !wd->awake.proxies[a->index].awake && !wd->awake.proxies[b->index].awake;
}

/* The END of a pair that no longer touches (room reserved); a body that went through a one-way platform
 * never touched it. */
static void queue_end(world *wd, const contact_record *r)
{
    if (r->flags & CT_PASSING)
        return;
    const bool b_first = (r->flags & CT_SENSOR_B) != 0; /* the sensor is the event's body */
    const pp_body first = {b_first ? r->b : r->a}, second = {b_first ? r->a : r->b};
    if (r->flags & CT_SENSOR)
        world_queue_event(wd, (pp_event){PP_EVENT_SENSOR_END, 0, first, second, {0, 0}, {0, 0}, 0, 0, {0}});
    else if (wd->def.contact_events && (r->flags & CT_BEGUN))
        world_queue_event(wd, (pp_event){PP_EVENT_CONTACT_END, 0, first, second, {0, 0}, {0, 0}, 0, 0, {0}});
}

pp_status contact_table_end_substep(world *wd)
{
    contact_table *t = &wd->table;
    /* Nothing awake, found, removed or woken: every pair still touches, untested. */
    if (t->count == 0 || (t->found_count == 0 && wd->awake.movers == 0 && t->gone == 0 && !t->resting_stale))
        return PP_OK;
    pp_status st = world_reserve_events(wd, t->count, "pp_world_step"); /* the worst case: every pair ends */
    if (st)
        return st;
    if (t->resting_stale) /* a body woke: its resting pairs are tested again */
        for (int32_t i = t->awake; i < t->count; i++)
            if (!untested(wd, &t->records[i]))
                wake_record(t, i);
    t->resting_stale = false;
    for (int32_t i = 0; i < t->awake;) {
        const contact_record *r = &t->records[i];
        const bool gone = (r->flags & CT_GONE) != 0;
        if (!gone && r->found == t->substep)
            i++;
        else if (!gone && untested(wd, r))
            rest_record(t, i); /* the last awake record comes to i: look at it next */
        else {
            queue_end(wd, r);
            remove_record(t, i);
        }
    }
    t->gone = 0;
    contact_table_validate(wd);
    return PP_OK;
}

static uint32_t run_node(const world *wd, uint32_t a, uint32_t b) { return wd->bodies[a]->sb.body ? a : b; }

pp_status contact_table_list_runs(world *wd)
{
    contact_table *t = &wd->table;
    t->run_count = 0;
    if (!ARRAY_RESERVE(t->runs, t->run_capacity, wd->contact_count)) /* a pair a contact at most */
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to list %d contacts' pairs",
                       (int)wd->contact_count);
    for (int32_t i = 0, end; i < wd->contact_count; i = end) {
        end = contact_pair_end(wd, i);
        const uint32_t a = handle_slot(wd->contacts[i].a.id), b = handle_slot(wd->contacts[i].b.id);
        const int32_t k = lookup(t, pair_key(a, b));
        PP_ASSERT(a < b && k >= 0 && t->records[k].a == wd->contacts[i].a.id); /* every contact's pair was found */
        t->records[k].run = t->run_count; /* not logged: read only while found is this substep */
        t->runs[t->run_count++] = (contact_run){i, end, a, b, k, run_node(wd, a, b)};
    }
    return PP_OK;
}

pp_status contact_table_add_run(world *wd, int32_t first, int32_t end, uint32_t a, uint32_t b, int32_t record)
{
    contact_table *t = &wd->table;
    if (!ARRAY_RESERVE(t->runs, t->run_capacity, t->run_count + 1))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to list %d contacts' pairs", (int)end);
    PP_ASSERT(a < b && record >= 0 && record < t->count && t->records[record].found == t->substep);
    t->records[record].run = t->run_count; /* not logged: read only while found is this substep */
    t->runs[t->run_count++] = (contact_run){first, end, a, b, record, run_node(wd, a, b)};
    return PP_OK;
}

void contact_table_validate_runs(const world *wd)
{
#ifdef PP_CHECKS
    const contact_table *t = &wd->table;
    int32_t next = 0;
    for (int32_t n = 0; n < t->run_count; n++) {
        const contact_run *u = &t->runs[n];
        PP_ASSERT(u->first == next && u->end == contact_pair_end(wd, u->first));
        PP_ASSERT(u->record >= 0 && u->record < t->count && u->node == run_node(wd, u->a, u->b));
        const contact_record *rec = &t->records[u->record];
        PP_ASSERT(rec->a == wd->contacts[u->first].a.id && rec->b == wd->contacts[u->first].b.id &&
                  handle_slot(rec->a) == u->a && handle_slot(rec->b) == u->b);
        next = u->end;
    }
    PP_ASSERT(next == wd->contact_count);
#else
    (void)wd;
#endif
}

void contact_table_store(world *wd, double h)
{
    contact_table *t = &wd->table;
    for (int32_t n = 0; n < t->run_count; n++) {
        const contact_run *u = &t->runs[n];
        if (contact_run_span(wd, u) == SPAN_SKIP) { /* it sat the substep out: its last solve stands */
            for (int32_t c = u->first; c < u->end; c++)
                wd->contacts[c].normal_impulse = 0;
            continue;
        }
        /* Over one substep, whatever the span: force × h, as the header has it. */
        solver_store_impulses(wd->solver, wd->contacts, u->first, u->end, h);
        contact_record *rec = edit(t, u->record);
        rec->point_count = u->end - u->first;
        PP_ASSERT(rec->point_count <= PP_MAX_CONTACTS_PER_PAIR);
        memcpy(rec->points, &wd->contacts[u->first], (size_t)rec->point_count * sizeof *rec->points);
    }
}

int32_t contact_table_resting_points(const world *wd, const contact_record *rec)
{
    if ((rec->flags & CT_GONE) || rec->found == wd->table.substep) /* found: its points are the world's contacts */
        return 0;
    const body *a = body_find(wd, (pp_body){rec->a}), *b = body_find(wd, (pp_body){rec->b});
    return a && b && !awake_mover(a) && !awake_mover(b) ? rec->point_count : 0;
}

void contact_table_body_removed(world *wd, uint64_t id)
{
    contact_table *t = &wd->table;
    for (int32_t i = 0; i < t->count; i++) {
        contact_record *r = &t->records[i];
        if ((r->a != id && r->b != id) || (r->flags & CT_GONE))
            continue;
        pair_map_remove(&t->index, key_of(r));
        r->flags |= CT_GONE;
        r->point_count = 0;
        t->gone++;
        if (i >= t->awake)
            wake_record(t, i); /* ended by the next substep's pass, which sees only awake records */
    }
}

pp_status contact_table_add(world *wd, const contact_record *rec, const char *fn, const char *where)
{
    contact_table *t = &wd->table;
    /* A snapshot saved between a body's removal and the next step lists its pairs (writers before the table
     * did): they end at the next substep, as they would have. */
    const bool live = body_find(wd, (pp_body){rec->a}) && body_find(wd, (pp_body){rec->b});
    if (live && lookup(t, key_of(rec)) >= 0)
        return pp_fail(PP_ERR_FORMAT, "%s: %s: the pair is listed twice", fn, where);
    pp_status st = reserve(t, t->count + 1, fn);
    if (st)
        return st;
    contact_record r = *rec;
    anchor_turn(&r);
    r.carried = 0, r.carry_count = 0; /* carry.c's pairs join the carry order themselves */
    r.found = t->substep - 1; /* not found at the last substep: a resting pair lists its own points */
    if (!live) {
        r.flags |= CT_GONE, r.point_count = 0;
        t->gone++;
    }
    insert_record(t, &r);
    return PP_OK;
}

/* ---- a saved state (pp_world_restore_state) --------------------------------------------------------- */

pp_status contact_table_reserve_state(world *wd, int32_t count, int32_t carry_count, const char *fn)
{
    contact_table *t = &wd->table;
    pp_status st = reserve(t, count, fn);
    if (!st && !ARRAY_RESERVE(t->carry_order, t->carry_capacity, carry_count))
        st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d carried pairs", fn, (int)carry_count);
    return st;
}

void contact_table_set_state(world *wd, const contact_table_counts *n, const contact_record *records,
                             const int32_t *carry_order)
{
    contact_table *t = &wd->table;
    PP_ASSERT(t->saved_count == 0 && n->count <= t->capacity && n->carry_count <= t->carry_capacity);
    if (n->count > 0 && records != t->records)
        memcpy(t->records, records, (size_t)n->count * sizeof *records);
    if (n->carry_count > 0)
        memcpy(t->carry_order, carry_order, (size_t)n->carry_count * sizeof *carry_order);
    t->count = n->count, t->awake = n->awake, t->gone = n->gone, t->carry_count = n->carry_count;
    t->substep = n->substep, t->found_count = n->found_count, t->resting_stale = n->resting_stale;
    for (int32_t i = 0; i < t->count; i++) { /* what is derived is derived again, never taken from the bytes */
        anchor_turn(&t->records[i]);
        if (t->records[i].carried)
            contact_table_locate_carried(&t->records[i]);
    }
    index_rebuild(t); /* room reserved: the keys are the records' */
}

void contact_table_get_counts(const world *wd, contact_table_counts *n)
{
    const contact_table *t = &wd->table;
    *n = (contact_table_counts){t->count, t->awake, t->gone, t->carry_count, t->substep, t->found_count,
                                t->resting_stale};
}

/* ---- the step transaction -------------------------------------------------------------------------- */

pp_status contact_table_save(world *wd)
{
    contact_table *t = &wd->table;
    const int32_t had = t->logged_capacity;
    if (!ARRAY_RESERVE(t->log, t->log_capacity, t->count) || !ARRAY_RESERVE(t->log_at, t->log_at_capacity, t->count) ||
        !ARRAY_RESERVE(t->logged, t->logged_capacity, t->count))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to save %d touching pairs", (int)t->count);
    if (t->logged_capacity > had)
        memset(t->logged + had, 0, (size_t)(t->logged_capacity - had) * sizeof *t->logged);
    if (!ARRAY_RESERVE(t->saved_order, t->saved_order_capacity, t->carry_count))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to save %d carried pairs", (int)t->carry_count);
    if (++t->step == 0) { /* wrapped: no stale mark may match */
        memset(t->logged, 0, (size_t)t->logged_capacity * sizeof *t->logged);
        t->step = 1;
    }
    if (t->carry_count > 0)
        memcpy(t->saved_order, t->carry_order, (size_t)t->carry_count * sizeof *t->carry_order);
    t->saved_order_count = t->carry_count;
    t->log_count = 0;
    t->saved_count = t->count, t->saved_awake = t->awake, t->saved_gone = t->gone, t->saved_substep = t->substep;
    return PP_OK;
}

void contact_table_restore(world *wd)
{
    contact_table *t = &wd->table;
    for (int32_t k = 0; k < t->log_count; k++)
        t->records[t->log_at[k]] = t->log[k];
    t->count = t->saved_count, t->awake = t->saved_awake, t->gone = t->saved_gone, t->substep = t->saved_substep;
    /* The order only grows within a step (carry_capacity ≥ the saved count), as do the records. */
    if (t->saved_order_count > 0)
        memcpy(t->carry_order, t->saved_order, (size_t)t->saved_order_count * sizeof *t->carry_order);
    t->carry_count = t->saved_order_count;
    index_rebuild(t); /* it held at least this many: no room to find */
    contact_table_commit(wd);
}

void contact_table_commit(world *wd)
{
    wd->table.saved_count = 0;
    wd->table.log_count = 0;
}

/* ---- the validator --------------------------------------------------------------------------------- */

void contact_table_validate(const world *wd)
{
#ifdef PP_CHECKS
    const contact_table *t = &wd->table;
    PP_ASSERT(0 <= t->awake && t->awake <= t->count && t->count <= t->capacity);
    PP_ASSERT(t->count == 0 || 2 * t->count <= t->index.capacity);
    int32_t keyed = 0;
    for (int32_t i = 0; i < t->count; i++) {
        const contact_record *r = &t->records[i];
        PP_ASSERT(r->point_count >= 0 && r->point_count <= PP_MAX_CONTACTS_PER_PAIR);
        if (r->flags & CT_GONE) {
            PP_ASSERT(i < t->awake); /* only the next pass ends it */
            continue;
        }
        keyed++;
        PP_ASSERT(handle_slot(r->a) < handle_slot(r->b));
        PP_ASSERT(lookup(t, key_of(r)) == i); /* the hash finds it where it is */
        const body *a = body_find(wd, (pp_body){r->a}), *b = body_find(wd, (pp_body){r->b});
        PP_ASSERT(a && b); /* a removed body's pairs are marked gone */
        PP_ASSERT(!(r->flags & (CT_SENSOR | CT_PASSING)) || r->point_count == 0);
        contact_record turned = *r; /* the anchor's cos and sin are its angle's (anchor_turn) */
        anchor_turn(&turned);
        PP_ASSERT(turned.anchor_cos == r->anchor_cos && turned.anchor_sin == r->anchor_sin);
        /* A resting pair has no awake body (the pass moved the rest; awake_add marks the table stale). */
        PP_ASSERT(i < t->awake || t->resting_stale ||
                  (!wd->awake.proxies[a->index].awake && !wd->awake.proxies[b->index].awake));
    }
    PP_ASSERT(t->index.count == keyed);
    int32_t carried = 0;
    for (int32_t k = 0; k < t->carry_count; k++) {
        const int32_t i = t->carry_order[k];
        PP_ASSERT(i >= -1 && i < t->count);
        if (i < 0)
            continue;
        const contact_record *r = &t->records[i];
        PP_ASSERT(r->carried == k + 1 && !(r->flags & (CT_GONE | CT_SENSOR | CT_PASSING)));
        PP_ASSERT(r->carry_count >= 1 && r->carry_count <= PP_MAX_CONTACTS_PER_PAIR);
        contact_record located = *r;
        contact_table_locate_carried(&located);
        PP_ASSERT(!memcmp(located.carry_local, r->carry_local, (size_t)r->carry_count * sizeof *r->carry_local));
        carried++;
    }
    for (int32_t i = 0; i < t->count; i++)
        carried -= t->records[i].carried != 0;
    PP_ASSERT(carried == 0); /* every carried record is in the order once */
#else
    (void)wd;
#endif
}

void contact_table_free(contact_table *t)
{
    pp_free(t->runs);
    pp_free(t->records);
    pair_map_free(&t->index);
    pp_free(t->log);
    pp_free(t->log_at);
    pp_free(t->logged);
    pp_free(t->carry_order);
    pp_free(t->saved_order);
    *t = (contact_table){0};
}
