/* Contacts carried through a step's substeps, and held from step to step (carry.h). */
#include "carry.h"
#include "alloc.h"
#include "island.h"
#include "status.h"
#include "world.h"

#include <math.h>
#include <string.h>

/* A carried point whose bodies have pulled it this far apart no longer touches, px. Nearer, it stays: ODE
 * corrects only depth past contact_slop, so it holds the bodies as the raster's thin overlap would. */
#define CARRY_GAP_PX 1.0

static uint32_t slot_of(pp_body b) { return handle_slot(b.id); }


/* A pair is carried only while no point of one body moves more than CARRY_MOTION_PX against the other in a
 * step, px, and neither turns more than CARRY_TURN_RAD: a resting pair. Its contacts then stay within that of
 * the truth, and a feature the first substep did not see touching (a falling stick's far end) cannot come
 * through more than that before the next step finds it. At 1 px, QuickStep's 1:10:100:1000 chain, which
 * jitters at tens of px/s, fell carried; at 0.25 px (15 px/s at 60 Hz) it stands as when collided. A tiny
 * body may spin fast and still move under a pixel; turned, its raster contact is another one (a 1 px body
 * carried while it tumbled came to rest 2 px deep). */
#define CARRY_MOTION_PX 0.25
#define CARRY_TURN_RAD 0.05

/* The bound for a pair of a QuickStep stack that solves every other substep (island.h), px a step: it is
 * collided once a step while it moves under it against itself. Not the heavy chain above (it solves every
 * substep). In the first 300 steps of 500 raining crates (one pile), the third substep collided 700–820
 * pairs against the first's 820–890 at 0.25 px; at 1 px, 216 against 800 on average: pairs not yet touching. */
#define CARRY_STACK_PX 1.0

/* A body's velocity, px/s, and how fast its turning may move its points, px/s; false if it turns more than
 * CARRY_TURN_RAD in dt s. */
static bool slow_turn(const world *wd, const body *bd, double dt, dvec2 *v, double *turn_speed)
{
    *v = dv(0, 0), *turn_speed = 0;
    if (!bd->sb.body)
        return true;
    double w;
    solver_body_get_velocity(wd->solver, &bd->sb, v, &w);
    const double diagonal = hypot(bd->aabb.x1 - bd->aabb.x0, bd->aabb.y1 - bd->aabb.y0);
    *turn_speed = fabs(w) * diagonal;
    return fabs(w) * dt <= CARRY_TURN_RAD;
}

/* Bodies falling together move nothing against each other: the bound is on their relative motion. */
static bool slow_pair(const world *wd, const body *a, const body *b, double dt, double bound)
{
    dvec2 va, vb;
    double ta, tb;
    return slow_turn(wd, a, dt, &va, &ta) && slow_turn(wd, b, dt, &vb, &tb) &&
           (dv_norm(dv_sub(vb, va)) + ta + tb) * dt <= bound;
}

static void strike(carry *c, const body *bd)
{
    if (bd->sb.body) /* a static body never moves onto anything */
        c->struck[bd->index] = c->step;
}

static bool struck(const carry *c, uint32_t slot) { return c->struck[slot] == c->step; }

bool carry_struck(const world *wd, uint32_t slot)
{
    const carry *c = &wd->carry;
    return (int32_t)slot < c->struck_capacity && struck(c, slot);
}

/* The body sits the substep out (after island_plan; before the next one's, it sat the last one out), or never
 * moves. A sensor's or a one-way platform's pairs are always collided: their touch state lives on pairs that
 * make no contacts. */
static bool sits_out(const world *wd, const body *bd)
{
    return !bd->is_sensor && !bd->one_way && (!bd->sb.body || bd->sat_out == wd->islands.substep_serial);
}

/* The pair carried for these slots among the first n indexed, or NULL. */
static carried_pair *find_pair(carry *c, int32_t n, uint32_t a, uint32_t b)
{
    const int32_t i = pair_map_get(&c->by_slots, pair_key(a, b));
    return i >= 0 && i < n ? &c->pairs[i] : NULL;
}

/* Drop the pairs carried no further than before substep k and index the rest (unless the pairs and their index
 * are as they were). */
static void keep_from(carry *c, int32_t k, bool added)
{
    int32_t n = 0;
    for (int32_t i = 0; i < c->pair_count; i++)
        if (c->pairs[i].last >= k)
            c->pairs[n++] = c->pairs[i];
    if (n == c->pair_count && !added)
        return;
    c->pair_count = n;
    (void)carry_index(c); /* the pairs were unique before */
}

bool carry_index(carry *c)
{
    PP_ASSERT(2 * c->pair_count <= c->by_slots.capacity || c->pair_count == 0);
    pair_map_clear(&c->by_slots);
    for (int32_t i = 0; i < c->pair_count; i++) {
        const uint64_t key = pair_key(c->pairs[i].a, c->pairs[i].b);
        if (pair_map_get(&c->by_slots, key) >= 0)
            return false;
        pair_map_set(&c->by_slots, key, i);
    }
    return true;
}

/* At the step's first substep: a fresh stamp for struck bodies, room for one by slot. */
static pp_status start_step(world *wd)
{
    carry *c = &wd->carry;
    const int32_t had = c->struck_capacity;
    pp_status st =
        world_slot_array(wd, (void **)&c->struck, &c->struck_capacity, sizeof *c->struck, "the carried pairs");
    if (st)
        return st;
    if (c->struck_capacity > had)
        memset(c->struck + had, 0, (size_t)(c->struck_capacity - had) * sizeof *c->struck);
    if (++c->step == 0) { /* wrapped: no stale stamp may match */
        memset(c->struck, 0, (size_t)c->struck_capacity * sizeof *c->struck);
        c->step = 1;
    }
    return PP_OK;
}

pp_status carry_record(world *wd, double dt, int32_t k)
{
    carry *c = &wd->carry;
    keep_from(c, k, false);
    const int32_t n = wd->contact_count, pairs_before = c->pair_count;
    if (n == 0)
        return PP_OK;
    if (!ARRAY_RESERVE(c->contacts, c->contact_capacity, c->contact_count + n) ||
        !ARRAY_RESERVE(c->pairs, c->pair_capacity, c->pair_count + n) ||
        !pair_map_reserve(&c->by_slots, c->pair_count + n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to carry %d contacts", (int)n);
    for (int32_t i = 0, end; i < n; i = end) {
        const pp_contact *ct = &wd->contacts[i];
        end = contact_pair_end(wd, i);
        const body *a = body_of(wd, ct->a), *b = body_of(wd, ct->b);
        const uint32_t sa = slot_of(ct->a), sb = slot_of(ct->b);
        PP_ASSERT(sa < sb); /* contacts keep the broadphase pair's order */
        /* Collided at every substep instead: a small island solved exactly, whose corners decide whether it
         * stands (a card house fell carried), and a round body, whose contact stays under its centre as it
         * rolls (carried, it turned with the disc and a rolling disc lost 0.5 % of its acceleration). */
        const bool stack = sits_out(wd, a) && sits_out(wd, b);
        carried_pair *held = k == 0 ? find_pair(c, pairs_before, sa, sb) : NULL;
        if (held) { /* held from the steps before: no longer a stack's, it is collided from the next substep */
            if (held->stack && !stack)
                held->last = 0;
            continue;
        }
        const double bound = stack ? CARRY_STACK_PX : CARRY_MOTION_PX;
        const bool slow = k == 0 && wd->islands.kind[(a->sb.body ? a : b)->index] != ISLAND_EXACT &&
                          body_round_radius(a) == 0 && body_round_radius(b) == 0 && slow_pair(wd, a, b, dt, bound);
        const bool still =
            !slow && sits_out(wd, a) && sits_out(wd, b) && (k == 0 || !find_pair(c, pairs_before, sa, sb));
        if (k == 0 && !slow)
            strike(c, a), strike(c, b);
        if (!slow && !still)
            continue;
        c->pairs[c->pair_count++] = (carried_pair){
            sa, sb, c->contact_count, end - i, slow ? wd->def.substeps - 1 : k + 1, false, false, slow, stack};
        const dvec2 com_a = body_com_world(a), com_b = body_com_world(b);
        for (int32_t j = i; j < end; j++)
            c->contacts[c->contact_count++] =
                (carried_contact){wd->contacts[j], com_a, com_b, a->cos_a, a->sin_a, b->cos_a, b->sin_a};
    }
    if (c->pair_count > pairs_before)
        keep_from(c, k, true);
    c->active = c->pair_count > 0;
    return PP_OK;
}

bool carry_claim(world *wd, uint32_t a, uint32_t b)
{
    carry *c = &wd->carry;
    /* At a step's first substep only held pairs are carried: nothing sat the substep before out. */
    const bool still = c->substep > 0 && sits_out(wd, wd->bodies[a]) && sits_out(wd, wd->bodies[b]);
    carried_pair *p = c->active ? find_pair(c, c->pair_count, a, b) : NULL;
    /* A struck body may have been pushed onto features its carried pairs did not touch; a still pair's
     * bodies were pushed nowhere. */
    if (p && p->last >= c->substep && (still || !(struck(c, a) || struck(c, b)))) {
        p->claimed = true;
        return true;
    }
    if (p && p->last >= c->substep)
        p->missed = true;
    return still; /* then it made no contact last substep, and nothing has moved since */
}

/* How far the material point of a body that was at p when the contact was found has moved, px; com is the
 * body's centre of mass now (body_com_world, found once for all of a pair's points). */
static dvec2 moved(const body *bd, dvec2 com, dvec2 com0, double c0, double s0, dvec2 p)
{
    const dvec2 local = dv_unrot(dv_sub(p, com0), c0, s0);
    return dv_sub(dv_add(com, dv_rot(local, bd->cos_a, bd->sin_a)), p);
}

/* A carried pair's contacts at the bodies' poses now: each point at the midpoint of where its two material
 * points went, its depth less their separation along the normal. Points pulled apart are dropped. */
static void move_pair(const world *wd, const carried_pair *p, np_result *r)
{
    r->count = 0;
    r->samples = 0;
    const body *a = wd->bodies[p->a], *b = wd->bodies[p->b];
    const dvec2 com_a = body_com_world(a), com_b = body_com_world(b);
    for (int32_t k = 0; k < p->count; k++) {
        const carried_contact *cc = &wd->carry.contacts[p->first + k];
        PP_ASSERT(cc->c.a.id == a->handle.id && cc->c.b.id == b->handle.id);
        const dvec2 p0 = dv(cc->c.point.x, cc->c.point.y), n = dv(cc->c.normal.x, cc->c.normal.y);
        const dvec2 ua = moved(a, com_a, cc->com_a, cc->cos_a, cc->sin_a, p0);
        const dvec2 ub = moved(b, com_b, cc->com_b, cc->cos_b, cc->sin_b, p0);
        const double depth = cc->c.depth - dv_dot(dv_sub(ub, ua), n);
        if (!(depth >= -CARRY_GAP_PX))
            continue;
        pp_contact *out = &r->contacts[r->count++];
        *out = cc->c;
        const dvec2 at = dv_add(p0, dv_scale(dv_add(ua, ub), 0.5));
        out->point = (pp_vec2){(float)at.x, (float)at.y};
        out->depth = (float)dmax(depth, 0.0); /* a contact reports overlap, never a gap */
    }
}

void carry_strike(world *wd)
{
    carry *c = &wd->carry;
    if (c->substep == 0) /* at the first substep carry_record strikes */
        return;
    for (int32_t i = 0; i < wd->contact_count; i++)
        strike(c, body_of(wd, wd->contacts[i].a)), strike(c, body_of(wd, wd->contacts[i].b));
}

pp_status carry_push(world *wd)
{
    carry *c = &wd->carry;
    if (!c->active)
        return PP_OK;
    for (int32_t i = 0; i < c->pair_count; i++) {
        const carried_pair *p = &c->pairs[i];
        if (!p->claimed)
            continue; /* the broadphase no longer pairs them: apart */
        np_result r;
        move_pair(wd, p, &r);
        if (r.count == 0)
            continue;
        const body *a = wd->bodies[p->a], *b = wd->bodies[p->b];
        bool keep = true;
        pp_status st = contact_table_found(wd, a, b, &r, &keep);
        if (st)
            return st;
        if (!keep)
            continue;
        if (!ARRAY_RESERVE(wd->contacts, wd->contact_capacity, wd->contact_count + r.count))
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for %d contacts",
                           (int)(wd->contact_count + r.count));
        for (int32_t k = 0; k < r.count; k++)
            wd->contacts[wd->contact_count++] = r.contacts[k];
    }
    return PP_OK;
}

/* Whether a body turned less than CARRY_TURN_RAD from the rotation (cos, sin) it had. */
static bool turned_little(const body *bd, double c0, double s0)
{
    const double sin_turn = bd->sin_a * c0 - bd->cos_a * s0, cos_turn = bd->cos_a * c0 + bd->sin_a * s0;
    return cos_turn > 0 && fabs(sin_turn) <= sin(CARRY_TURN_RAD);
}

/* Whether a held pair stays within its bound through a step of dt s: its points' motion against each other
 * since the raster found them, plus what the bodies' velocities add this step; neither body turned past
 * CARRY_TURN_RAD since. */
static bool still_held(const world *wd, const carried_pair *p, const void *step_dt)
{
    const double dt = *(const double *)step_dt;
    const double bound = p->stack ? CARRY_STACK_PX : CARRY_MOTION_PX;
    const carried_contact *cc = &wd->carry.contacts[p->first];
    const body *a = body_find(wd, cc->c.a), *b = body_find(wd, cc->c.b);
    if (!a || !b)
        return false;
    if (!turned_little(a, cc->cos_a, cc->sin_a) || !turned_little(b, cc->cos_b, cc->sin_b))
        return false;
    double drift = 0;
    const dvec2 com_a = body_com_world(a), com_b = body_com_world(b);
    for (int32_t k = 0; k < p->count; k++, cc++) {
        const dvec2 p0 = dv(cc->c.point.x, cc->c.point.y);
        const dvec2 ua = moved(a, com_a, cc->com_a, cc->cos_a, cc->sin_a, p0);
        const dvec2 ub = moved(b, com_b, cc->com_b, cc->cos_b, cc->sin_b, p0);
        drift = dmax(drift, dv_dot(dv_sub(ub, ua), dv_sub(ub, ua)));
    }
    drift = sqrt(drift);
    return drift <= bound && slow_pair(wd, a, b, dt, bound - drift);
}

/* Keep the pairs for which keep(…, arg) holds, in order, their contacts packed; then index them. */
static void keep_pairs(world *wd, bool (*keep)(const world *, const carried_pair *, const void *), const void *arg)
{
    carry *c = &wd->carry;
    int32_t n = 0, m = 0;
    for (int32_t i = 0; i < c->pair_count; i++) {
        carried_pair p = c->pairs[i];
        if (!keep(wd, &p, arg))
            continue;
        if (p.first != m)
            memmove(&c->contacts[m], &c->contacts[p.first], (size_t)p.count * sizeof *c->contacts);
        p.first = m, m += p.count;
        c->pairs[n++] = p;
    }
    const bool dropped = n < c->pair_count; /* else every pair is where the index has it */
    c->pair_count = n, c->contact_count = m;
    if (dropped)
        (void)carry_index(c); /* the pairs were unique before */
}

pp_status carry_begin(world *wd, int32_t k, double dt)
{
    carry *c = &wd->carry;
    c->substep = k;
    if (k == 0 && wd->def.substeps > 1) { /* one substep carries nothing and holds nothing */
        pp_status st = start_step(wd);
        if (st)
            return st;
        keep_pairs(wd, still_held, &dt);
        c->active = c->pair_count > 0;
    }
    for (int32_t i = 0; i < c->pair_count; i++)
        c->pairs[i].claimed = false;
    return PP_OK;
}

/* Carried through the whole step and never collided: the raster's contacts, moved. */
static bool to_hold(const world *wd, const carried_pair *p, const void *unused)
{
    return p->held && p->last == wd->def.substeps - 1 && p->claimed && !p->missed;
}

void carry_end_step(world *wd)
{
    keep_pairs(wd, to_hold, NULL);
    wd->carry.active = false;
}

pp_status carry_save(world *wd)
{
    carry *c = &wd->carry;
    if (!ARRAY_RESERVE(c->saved_pairs, c->saved_pair_capacity, c->pair_count) ||
        !ARRAY_RESERVE(c->saved_contacts, c->saved_contact_capacity, c->contact_count))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to save %d held pairs", (int)c->pair_count);
    if (c->pair_count > 0) {
        memcpy(c->saved_pairs, c->pairs, (size_t)c->pair_count * sizeof *c->pairs);
        memcpy(c->saved_contacts, c->contacts, (size_t)c->contact_count * sizeof *c->contacts);
    }
    c->saved_pair_count = c->pair_count, c->saved_contact_count = c->contact_count;
    return PP_OK;
}

void carry_restore(world *wd)
{
    carry *c = &wd->carry;
    /* The arrays only grow, and they held these counts when they were saved. */
    PP_ASSERT(c->saved_pair_count <= c->pair_capacity && c->saved_contact_count <= c->contact_capacity);
    if (c->saved_pair_count > 0) {
        memcpy(c->pairs, c->saved_pairs, (size_t)c->saved_pair_count * sizeof *c->pairs);
        memcpy(c->contacts, c->saved_contacts, (size_t)c->saved_contact_count * sizeof *c->contacts);
    }
    c->pair_count = c->saved_pair_count, c->contact_count = c->saved_contact_count;
    c->active = false;
}

static bool not_of(const world *wd, const carried_pair *p, const void *slot)
{
    return p->a != *(const uint32_t *)slot && p->b != *(const uint32_t *)slot;
}

void carry_forget(world *wd, uint32_t slot) { keep_pairs(wd, not_of, &slot); }

void carry_free(carry *c)
{
    pp_free(c->struck);
    pp_free(c->contacts);
    pp_free(c->pairs);
    pair_map_free(&c->by_slots);
    pp_free(c->saved_pairs);
    pp_free(c->saved_contacts);
}
