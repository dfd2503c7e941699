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
 * pairs against the first's 820–890 at 0.25 px; at 1 px, 216 against 800 on average: pairs not yet touching.
 * At 1.5 px the pile's narrowphase costs 0.84 M instructions a step against 2.01 M at 1 px (bench_instr), with
 * every bench_stability verdict kept; at 2 px 0.77 M. */
#define CARRY_STACK_PX 1.5

/* A QuickStep stack is at rest, and solves at half its iterations (island.c), while no collided pair struck it and
 * none of its pairs moves faster than CARRY_REST_PX a step against itself (carry_restless), held or not. At rest
 * by the first alone, the raining crates' pile never settled at half: 47–86 of its 500 moved over 10 px/s with
 * pairs held to 1.5 px, 15–20 with pairs held to 1 px; 8 with this rule, 1 at full iterations always
 * (bench_instr --motion, steps 151–900). */
#define CARRY_REST_PX 1.0

/* A pair touching at a step's first substep that moves faster than a resting one, but under CARRY_MOVING_PX a
 * step against itself (120 px/s at 60 Hz), is collided once in the step too: its contacts are carried through the
 * later substeps (not held into the next step), and a feature they did not see comes at most that far through
 * before the next step's raster finds it; a turn is bounded as a resting pair's. Settling debris and sliding
 * crates are most of a destructible scene's pairs: in bench_instr's destruction scene three quarters of the
 * pairs touching at a first substep moved too fast to rest, and were collided at all four. Every bench_stability
 * verdict stayed the same at 2, 4 and 8 px; at 8 the wall shots moved. */
#define CARRY_MOVING_PX 2.0

/* CARRY_MOVING_PX for a pair of a small island the exact solver takes, whose corners decide whether it stands: at
 * 2 px bench_stability's cardhouse_v3_3 fell, at 1 px cardhouse4w (BALANCED); at 0.5 px every verdict stands at 7
 * grid offsets (--offset 0 … 3.3) and 200 crates of 128 px on a terrain (bench_backends --no-gpu) collide 0.78 ms
 * a step against 1.30–1.37 ms with the exact pairs collided at every substep. */
#define CARRY_EXACT_MOVING_PX 0.5

/* Forget every body's motion: velocities may have changed since (a solve, damping). Called before each pass over
 * the pairs, within which none changes. */
static void motion_stale(carry *c)
{
    if (++c->serial == 0) { /* wrapped: no body's motion may look current */
        if (c->motion)
            memset(c->motion, 0, (size_t)c->motion_capacity * sizeof *c->motion);
        c->serial = 1;
    }
}

/* A body's motion now into *m (the step's dt s: the same for every call of a step). */
static void find_motion(const world *wd, const body *bd, double dt, carry_motion *m)
{
    double w;
    dvec2 vel;
    solver_body_get_velocity(wd->solver, &bd->sb, &vel, &w);
    const double dx = bd->aabb.x1 - bd->aabb.x0, dy = bd->aabb.y1 - bd->aabb.y0; /* floats: no overflow squared */
    const double diagonal = sqrt(dx * dx + dy * dy);
    const carry_motion now = {vel, fabs(w) * diagonal, wd->carry.serial, fabs(w) * dt <= CARRY_TURN_RAD};
    /* PP_CHECKS: a motion found earlier in the pass is the body's motion now */
    PP_ASSERT(m->serial != wd->carry.serial || (m->v.x == now.v.x && m->v.y == now.v.y &&
                                                m->turn_speed == now.turn_speed && m->slow == now.slow));
    *m = now;
}

/* A body's motion: its velocity, how fast its turning may move its points, and whether it turns under
 * CARRY_TURN_RAD in dt s. Found once a pass (still_held and carry_record ask for each of a body's pairs). */
static inline const carry_motion *motion_of(const world *wd, const body *bd, double dt)
{
    static const carry_motion still = {{0, 0}, 0, 0, true}; /* a static body */
    if (!bd->sb.body)
        return &still;
    PP_ASSERT((int32_t)bd->index < wd->carry.motion_capacity);
    carry_motion *m = &wd->carry.motion[bd->index];
    if (m->serial != wd->carry.serial || PP_CHECKS_ON)
        find_motion(wd, bd, dt, m);
    return m;
}

/* How far a point of one body may move against the other in a step of dt s, px; INFINITY if either turns more
 * than CARRY_TURN_RAD. Bodies falling together move nothing against each other: it is their relative motion. */
static double pair_motion(const world *wd, const body *a, const body *b, double dt)
{
    const carry_motion *ma = motion_of(wd, a, dt), *mb = motion_of(wd, b, dt);
    if (!ma->slow || !mb->slow)
        return INFINITY;
    const dvec2 d = dv_sub(mb->v, ma->v); /* under PP_MAX_SPEED: no overflow squared */
    return (sqrt(dv_dot(d, d)) + ma->turn_speed + mb->turn_speed) * dt;
}

/* Whether a point of one body may move more than `bound` px against the other in a step of dt s (pair_motion's
 * measure, without its square root): a turn past CARRY_TURN_RAD does. */
static bool moves_past(const world *wd, const body *a, const body *b, double dt, double bound)
{
    const carry_motion *ma = motion_of(wd, a, dt), *mb = motion_of(wd, b, dt);
    if (!ma->slow || !mb->slow)
        return true;
    const double room = bound / dt - ma->turn_speed - mb->turn_speed; /* px/s the linear motion may take */
    const dvec2 d = dv_sub(mb->v, ma->v);
    return room < 0 || dv_dot(d, d) > room * room;
}

static void strike(carry *c, const body *bd)
{
    if (bd->sb.body) /* a static body never moves onto anything */
        c->struck[bd->index] = c->step;
}

static void mark_restless(carry *c, const body *bd)
{
    if (bd->sb.body)
        c->restless[bd->index] = c->step;
}

/* Marked restless in this step already, or static (a body that never moves needs no mark). */
static bool marked_restless(const carry *c, const body *bd)
{
    return !bd->sb.body || c->restless[bd->index] == c->step;
}

void carry_collided(world *wd, uint32_t a, uint32_t b)
{
    carry *c = &wd->carry;
    if ((int32_t)b < c->collided_capacity) /* a < b; one substep makes no room: nothing pairs then */
        c->collided[a] = c->collided[b] = c->step;
}

/* The body sits the substep out (after island_plan; before the next one's, it sat the last one out), or never
 * moves. A sensor's or a one-way platform's pairs are always collided: their touch state lives on pairs that
 * make no contacts. */
static bool sits_out(const world *wd, const body *bd)
{
    return !bd->is_sensor && !bd->one_way && (!bd->sb.body || bd->sat_out == wd->islands.substep_serial);
}

/* The record carried for these slots, its index in *at, or NULL. */
static const contact_record *carried_pair(const world *wd, uint32_t a, uint32_t b, int32_t *at)
{
    *at = contact_table_lookup(wd, a, b);
    const contact_record *r = *at >= 0 ? &wd->table.records[*at] : NULL;
    return r && r->carried ? r : NULL;
}

/* Carried into substep k or later. */
static bool carried_into(const world *wd, const contact_record *r, const void *k)
{
    (void)wd;
    return r->carry_last >= *(const int32_t *)k;
}

/* At the step's first substep: a fresh stamp for struck bodies, room for one by slot. */
static pp_status start_step(world *wd)
{
    carry *c = &wd->carry;
    static const char *what = "the carried pairs";
    pp_status st = world_slot_array_zeroed(wd, (void **)&c->struck, &c->struck_capacity, sizeof *c->struck, what);
    if (st ||
        (st = world_slot_array_zeroed(wd, (void **)&c->collided, &c->collided_capacity, sizeof *c->collided, what)) ||
        (st = world_slot_array_zeroed(wd, (void **)&c->motion, &c->motion_capacity, sizeof *c->motion, what)) ||
        (st = world_slot_array_zeroed(wd, (void **)&c->restless, &c->restless_capacity, sizeof *c->restless, what)))
        return st;
#ifdef PP_CHECKS
    for (int32_t i = 0; i < c->struck_capacity; i++) /* stamps are steps that began: none from the future */
        PP_ASSERT(c->struck[i] <= c->step);
    for (int32_t i = 0; i < c->collided_capacity; i++)
        PP_ASSERT(c->collided[i] <= c->step);
    for (int32_t i = 0; i < c->restless_capacity; i++)
        PP_ASSERT(c->restless[i] <= c->step);
#endif
    if (++c->step == 0) { /* wrapped: no stale stamp may match */
        memset(c->struck, 0, (size_t)c->struck_capacity * sizeof *c->struck);
        memset(c->collided, 0, (size_t)c->collided_capacity * sizeof *c->collided);
        memset(c->restless, 0, (size_t)c->restless_capacity * sizeof *c->restless);
        c->step = 1;
    }
    return PP_OK;
}

pp_status carry_record(world *wd, double dt, int32_t k)
{
    if (k > 0) /* at the step's first substep nothing has changed a velocity since carry_begin read them */
        motion_stale(&wd->carry);
    contact_table_keep_carried(wd, carried_into, &k);
    const int32_t n = wd->contact_count, before = wd->table.carry_count;
    if (n == 0)
        return PP_OK;
    pp_status st = contact_table_reserve_carried(wd, before + n, "pp_world_step");
    if (st)
        return st;
    for (int32_t u = 0; u < wd->table.run_count; u++) {
        const contact_run run = wd->table.runs[u];
        const int32_t i = run.first, end = run.end, at = run.record;
        const pp_contact *ct = &wd->contacts[i];
        const body *a = wd->bodies[run.a], *b = wd->bodies[run.b];
        PP_ASSERT(end - i <= PP_MAX_CONTACTS_PER_PAIR);
        const contact_record *rec = &wd->table.records[at];
        const bool carried_before = rec->carried && rec->carried <= before;
        /* A QuickStep stack's pair that sat this substep out: bound CARRY_STACK_PX. A lone body at rest sits out
         * too, but keeps a resting pair's bound. */
        const bool both_out = sits_out(wd, a) && sits_out(wd, b);
        const bool stack = both_out && wd->islands.kind[(a->sb.body ? a : b)->index] == ISLAND_QUICK_STACK;
        if (stack && !(marked_restless(&wd->carry, a) && marked_restless(&wd->carry, b)) &&
            moves_past(wd, a, b, dt, CARRY_REST_PX))
            mark_restless(&wd->carry, a), mark_restless(&wd->carry, b);
        if (k == 0 && carried_before) { /* held from the steps before: no longer a stack's, it is collided from
                                           the next substep */
            if ((rec->carry_flags & CARRY_STACK) && !stack)
                contact_table_edit(wd, at)->carry_last = 0;
            continue;
        }
        const double bound = stack ? CARRY_STACK_PX : CARRY_MOTION_PX;
        /* Collided at every substep instead: a round body, whose contact stays under its centre as it rolls
         * (carried, it turned with the disc and a rolling disc lost 0.5 % of its acceleration); and, moving, a
         * pair of a small island solved exactly past CARRY_EXACT_MOVING_PX, and a pair on a long slanted face,
         * whose load moves between its ends (carried at 2 px, Box2D v3's arch fell). An exact island's resting
         * pair is carried and held as any other: every verdict stands, its towers stop jittering (drift
         * 0.002–0.04 px to under 1e-5), and most pairs of bench_backends' terrain scenes are no longer collided
         * at every substep. */
        const bool exact = wd->islands.kind[(a->sb.body ? a : b)->index] == ISLAND_EXACT;
        const bool carriable = k == 0 && body_round_radius(a) == 0 && body_round_radius(b) == 0;
        const double motion = carriable ? pair_motion(wd, a, b, dt) : INFINITY;
        const bool slow = motion <= bound;
        const bool moving =
            !slow && motion <= (exact ? CARRY_EXACT_MOVING_PX : CARRY_MOVING_PX) && !island_slanted_face(wd, i, end);
        const bool still = !slow && !moving && both_out && (k == 0 || !carried_before);
        if (k == 0 && !slow && !moving)
            strike(&wd->carry, a), strike(&wd->carry, b);
        if (!slow && !moving && !still)
            continue;
        contact_table_carry(wd, at);
        contact_record *r = contact_table_edit(wd, at);
        r->carry_count = (int8_t)(end - i);
        r->carry_last = (int8_t)(slow || moving ? wd->def.substeps - 1 : k + 1);
        r->carry_flags = (slow ? CARRY_HELD : 0) | (stack ? CARRY_STACK : 0);
        r->carry_pose = (carried_pose){body_com_world(a), body_com_world(b), a->cos_a, a->sin_a, b->cos_a, b->sin_a};
        memcpy(r->carry_points, ct, (size_t)(end - i) * sizeof *ct);
        contact_table_locate_carried(r);
    }
    wd->carry.active = wd->table.carry_count > 0;
    return PP_OK;
}

/* Neither body of the pair moved since the substep before: both sat it out (or never move). At a step's first
 * substep none did: nothing sat the substep before out. */
static bool still_pair(const world *wd, uint32_t a, uint32_t b)
{
    return wd->carry.substep > 0 && sits_out(wd, wd->bodies[a]) && sits_out(wd, wd->bodies[b]);
}

bool carry_claim(world *wd, uint32_t a, uint32_t b)
{
    carry *c = &wd->carry;
    int32_t at = -1;
    const contact_record *p = c->active ? carried_pair(wd, a, b, &at) : NULL;
    if (p && p->carry_last >= c->substep) {
        /* A struck body may have been pushed onto features its carried pairs did not touch; a still pair's
         * bodies were pushed nowhere. */
        if (!(carry_struck(c, a) || carry_struck(c, b)) || still_pair(wd, a, b)) {
            contact_table_edit(wd, at)->claimed = wd->table.substep;
            return true;
        }
        contact_table_edit(wd, at)->carry_flags |= CARRY_MISSED;
        return false;
    }
    return still_pair(wd, a, b); /* then it made no contact last substep, and nothing has moved since */
}

/* How far carried point k has moved with each body since the raster found it at p0: *ua with a, *ub with b, px;
 * com_a and com_b are the bodies' centres of mass now (body_com_world, found once for all of a pair's points). */
static void moved_pair(const contact_record *r, int32_t k, const body *a, const body *b, dvec2 com_a, dvec2 com_b,
                       dvec2 p0, dvec2 *ua, dvec2 *ub)
{
    *ua = dv_sub(dv_add(com_a, dv_rot(r->carry_local[k][0], a->cos_a, a->sin_a)), p0);
    *ub = dv_sub(dv_add(com_b, dv_rot(r->carry_local[k][1], b->cos_a, b->sin_a)), p0);
}

/* A carried pair's contacts at the bodies' poses now: each point at the midpoint of where its two material
 * points went, its depth less their separation along the normal. Points pulled apart are dropped. *drift: the
 * farthest any point's two material points moved apart, squared, px². */
static void move_points(const world *wd, const contact_record *p, np_result *r, double *drift)
{
    r->count = 0;
    r->samples = 0;
    *drift = 0;
    const body *a = wd->bodies[handle_slot(p->a)], *b = wd->bodies[handle_slot(p->b)];
    const dvec2 com_a = body_com_world(a), com_b = body_com_world(b);
    for (int32_t k = 0; k < p->carry_count; k++) {
        const pp_contact *cc = &p->carry_points[k];
        PP_ASSERT(cc->a.id == a->handle.id && cc->b.id == b->handle.id);
        const dvec2 p0 = dv(cc->point.x, cc->point.y), n = dv(cc->normal.x, cc->normal.y);
        dvec2 ua, ub;
        moved_pair(p, k, a, b, com_a, com_b, p0, &ua, &ub);
        *drift = dmax(*drift, dv_dot(dv_sub(ub, ua), dv_sub(ub, ua)));
        const double depth = cc->depth - dv_dot(dv_sub(ub, ua), n);
        if (!(depth >= -CARRY_GAP_PX))
            continue;
        pp_contact *out = &r->contacts[r->count++];
        *out = *cc;
        const dvec2 at = dv_add(p0, dv_scale(dv_add(ua, ub), 0.5));
        out->point = (pp_vec2){(float)at.x, (float)at.y};
        out->depth = (float)dmax(depth, 0.0); /* a contact reports overlap, never a gap */
    }
}

/* A held pair's contacts as still_held moved them at the step's first substep, for carry_push there: no body
 * moves in between. */
typedef struct carry_moved {
    uint64_t a, b;  /* the record's pair: records do not move before carry_push, but a stale entry must not match */
    uint32_t step;  /* carry.step when moved */
    np_result r;
} carry_moved;

static void move_pair(const world *wd, int32_t i, np_result *r)
{
    const contact_record *p = &wd->table.records[i];
    const carry *c = &wd->carry;
    const carry_moved *m = c->substep == 0 && i < c->moved_capacity ? &c->moved[i] : NULL;
    double drift;
    if (m && m->step == c->step && m->a == p->a && m->b == p->b) {
        *r = m->r;
#ifdef PP_CHECKS
        np_result again;
        move_points(wd, p, &again, &drift);
        PP_ASSERT(again.count == r->count && !memcmp(again.contacts, r->contacts, (size_t)r->count * sizeof *r->contacts));
#endif
        return;
    }
    move_points(wd, p, r, &drift);
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
    if (!wd->carry.active)
        return PP_OK;
    const contact_table *t = &wd->table;
    /* contact_table_found finds every carried record where it is: none is made or ended meanwhile. */
    for (int32_t k = 0; k < t->carry_count; k++) {
        const int32_t i = t->carry_order[k];
        if (i < 0 || t->records[i].claimed != t->substep)
            continue; /* ended, or the broadphase no longer pairs them: apart */
        np_result r;
        move_pair(wd, i, &r);
        if (r.count == 0)
            continue;
        const body *a = wd->bodies[handle_slot(t->records[i].a)], *b = wd->bodies[handle_slot(t->records[i].b)];
        bool keep = true;
        int32_t at = i;
        pp_status st = contact_table_found(wd, a, b, &r, &at, &keep);
        if (st)
            return st;
        if (!keep)
            continue;
        if (!ARRAY_RESERVE(wd->contacts, wd->contact_capacity, wd->contact_count + r.count))
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for %d contacts",
                           (int)(wd->contact_count + r.count));
        const int32_t from = wd->contact_count;
        for (int32_t m = 0; m < r.count; m++)
            wd->contacts[wd->contact_count++] = r.contacts[m];
        if ((st = contact_table_add_run(wd, from, wd->contact_count, a->index, b->index, at)))
            return st;
    }
    return PP_OK;
}

/* Whether a body turned less than CARRY_TURN_RAD from the rotation (cos, sin) it had. */
static bool turned_little(const body *bd, double c0, double s0)
{
    const double sin_turn = bd->sin_a * c0 - bd->cos_a * s0, cos_turn = bd->cos_a * c0 + bd->sin_a * s0;
    return cos_turn > 0 && fabs(sin_turn) <= sin(CARRY_TURN_RAD);
}

/* What still_held reads and where it leaves each held pair's moved contacts (by record). */
typedef struct held_pass {
    double dt;          /* the step, s */
    carry_moved *moved; /* by record, room for every record */
} held_pass;

/* Whether a held pair stays within its bound through a step of dt s: its points' motion against each other
 * since the raster found them, plus what the bodies' velocities add this step; neither body turned past
 * CARRY_TURN_RAD since. Its contacts, moved, are kept for carry_push. */
static bool still_held(const world *wd, const contact_record *p, const void *arg)
{
    const held_pass *pass = arg;
    const double bound = (p->carry_flags & CARRY_STACK) ? CARRY_STACK_PX : CARRY_MOTION_PX;
    const carried_pose *q = &p->carry_pose;
    const body *a = body_find(wd, (pp_body){p->a}), *b = body_find(wd, (pp_body){p->b});
    if (!a || !b)
        return false;
    if (!turned_little(a, q->cos_a, q->sin_a) || !turned_little(b, q->cos_b, q->sin_b))
        return false;
    carry_moved *m = &pass->moved[p - wd->table.records];
    double drift;
    move_points(wd, p, &m->r, &drift);
    drift = sqrt(drift);
    if (!(drift <= bound && pair_motion(wd, a, b, pass->dt) <= bound - drift))
        return false;
    m->a = p->a, m->b = p->b, m->step = wd->carry.step;
    return true;
}

pp_status carry_begin(world *wd, int32_t k, double dt)
{
    carry *c = &wd->carry;
    c->substep = k;
    if (k == 0 && wd->def.substeps > 1) { /* one substep carries nothing and holds nothing */
        pp_status st = start_step(wd);
        if (st)
            return st;
        motion_stale(c);
        if (!ARRAY_RESERVE(c->moved, c->moved_capacity, wd->table.count))
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for %d held pairs", (int)wd->table.count);
        contact_table_keep_carried(wd, still_held, &(held_pass){dt, c->moved});
        c->active = wd->table.carry_count > 0;
    }
    return PP_OK;
}

/* Carried through the whole step and never collided: the raster's contacts, moved. The step's last search for
 * pairs claimed it, or found it (the step's only one, when every island sat the later substeps out). */
static bool to_hold(const world *wd, const contact_record *p, const void *unused)
{
    (void)unused;
    return (p->carry_flags & (CARRY_HELD | CARRY_MISSED)) == CARRY_HELD &&
           (p->claimed == wd->table.substep || p->found == wd->table.substep) && p->carry_last == wd->def.substeps - 1;
}

void carry_end_step(world *wd)
{
    contact_table_keep_carried(wd, to_hold, NULL);
    wd->carry.active = false;
}

static bool not_of(const world *wd, const contact_record *p, const void *slot)
{
    (void)wd;
    const uint32_t s = *(const uint32_t *)slot;
    return handle_slot(p->a) != s && handle_slot(p->b) != s;
}

void carry_forget(world *wd, uint32_t slot) { contact_table_keep_carried(wd, not_of, &slot); }

/* How far from a pair's overlap the raster reads pixels for its contacts, px: the corner normal's 6 px
 * (corner.c) and a pixel of bilinear coverage, with one to spare. */
#define CARRY_EDIT_REACH_PX 8.0

typedef struct edited {
    uint32_t slot;
    pp_aabb region; /* grown by CARRY_EDIT_REACH_PX */
} edited;

static bool clear_of(const world *wd, const contact_record *p, const void *arg)
{
    const edited *e = arg;
    const uint32_t a = handle_slot(p->a), b = handle_slot(p->b);
    if (a != e->slot && b != e->slot)
        return true;
    return !aabb_overlap(&wd->bodies[a == e->slot ? b : a]->aabb, &e->region);
}

void carry_forget_near(world *wd, uint32_t slot, pp_aabb region)
{
    const double m = CARRY_EDIT_REACH_PX;
    const edited e = {slot, {region.x0 - m, region.y0 - m, region.x1 + m, region.y1 + m}};
    contact_table_keep_carried(wd, clear_of, &e);
}

void carry_free(carry *c)
{
    pp_free(c->struck);
    pp_free(c->collided);
    pp_free(c->motion);
    pp_free(c->restless);
    pp_free(c->moved);
}
