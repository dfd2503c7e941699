/* The step loop: timed edits, then `substeps` passes of broadphase → narrowphase per pair → contact
 * joints → ODE step, the poses read back; all of it undone if any part fails (step_undo.c). */
#include "alloc.h"
#include "awake.h"
#include "contact_solve.h"
#include "corner.h"
#include "continuous.h"
#include "forces.h"
#include "island.h"
#include "joint.h"
#include "status.h"
#include "step_undo.h"
#include "timed_edits.h"
#include "world.h"

#include <float.h>
#include <math.h>
#include <time.h>

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static pp_status push_contact(world *wd, const pp_contact *c)
{
    if (!ARRAY_RESERVE(wd->contacts, wd->contact_capacity, wd->contact_count + 1))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for %d contacts", (int)wd->contact_count + 1);
    wd->contacts[wd->contact_count++] = *c;
    return PP_OK;
}

pp_status world_reserve_pairs(world *wd, const char *fn, int32_t n)
{
    if (n <= wd->batch.capacity)
        return PP_OK;
    int32_t pairs = wd->batch.capacity, cores = pairs, results = pairs, candidates = pairs, bodies = pairs; /* alike */
    if (!ARRAY_RESERVE(wd->batch.pairs, pairs, n) || !ARRAY_RESERVE(wd->batch.cores, cores, n) ||
        !ARRAY_RESERVE(wd->batch.results, results, n) || !ARRAY_RESERVE(wd->batch.candidates, candidates, n) ||
        !array_reserve((void **)&wd->batch.bodies, &bodies, n, 2 * sizeof *wd->batch.bodies))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d pairs", fn, (int)n);
    wd->batch.capacity = pairs;
    return PP_OK;
}

/* The threads a batch's per-pair host work is shared over: the world's workers for a batch of many pairs. */
static int32_t host_threads(const world *wd, int32_t pairs)
{
    return pairs >= WORKERS_MIN_PAIRS ? workers_wanted(wd->def.worker_threads) : 1;
}

/* The step's stats keep the most threads any of its narrowphase work ran on. */
static void note_threads(world *wd, int32_t used)
{
    wd->stats.threads = used > wd->stats.threads ? used : wd->stats.threads;
}

/* Whether AUTO may send a batch of `cells` either way: large enough, and a hardware GPU up. A software rasteriser
 * (llvmpipe) never gets AUTO's work (make bench finds it 3–6× slower than the CPU), so AUTO makes no GPU state there. */
static bool auto_has_choice(const world *wd, int64_t cells)
{
    return wd->def.backend == PP_BACKEND_AUTO && cells >= AUTO_MIN_CELLS && wd->gpu;
}

/* AUTO's backend for a batch: the CPU but where it has a choice and backend_auto.h's models of the batches run so
 * far find the GPU cheaper. */
static pp_backend choose_backend(world *wd, int32_t pairs, int64_t cells)
{
    if (wd->def.backend != PP_BACKEND_AUTO)
        return wd->def.backend;
    if (cells < AUTO_MIN_CELLS)
        return PP_BACKEND_CPU;
    if (!wd->gpu_tried) {
        wd->gpu_tried = true;
        bool software = false;
        pp_status st = gpu_narrow_probe_software("pp_world_step", &software);
        if (!st && !software)
            st = gpu_narrow_create("pp_world_step", &wd->gpu);
        if (st)
            pp_log(1, "physpix: AUTO keeps the narrowphase on the CPU: %s", pp_last_error());
        else if (software)
            pp_log(1, "physpix: AUTO keeps the narrowphase on the CPU: the GPU context is a software rasteriser");
    }
    return auto_has_choice(wd, cells) && backend_auto_wants_gpu(&wd->auto_costs, pairs, cells) ? PP_BACKEND_GPU
                                                                                                : PP_BACKEND_CPU;
}

pp_status world_run_cores(world *wd, const char *fn, int32_t first, int32_t n, int64_t cells, pp_backend *ran,
                          int32_t *threads)
{
    const np_settings set = world_np_settings(wd);
    *ran = choose_backend(wd, n, cells);
    *threads = 0;
    /* AUTO times the batches it could send either way, to learn what each backend costs. */
    const bool timed = auto_has_choice(wd, cells);
    const double t0 = timed ? now_ms() : 0;
    /* A world with no pair yet has no arrays: NULL + 0 is undefined, so offset only a real array. */
    np_pair *pairs = first ? wd->batch.pairs + first : wd->batch.pairs;
    np_core *cores = first ? wd->batch.cores + first : wd->batch.cores;
    pp_status st;
    if (*ran == PP_BACKEND_GPU) {
        st = gpu_narrow_run(wd->gpu, fn, &set, pairs, n, &wd->scratch, cores);
        *threads = 1;
    } else {
        const int32_t wanted = n > 1 && cells >= WORKERS_MIN_CELLS ? workers_wanted(wd->def.worker_threads) : 1;
        st = workers_run(&wd->workers, wanted, &set, pairs, n, &wd->scratch, cores, threads);
    }
    if (timed && !st)
        backend_auto_learn(&wd->auto_costs, *ran == PP_BACKEND_GPU, n, cells, now_ms() - t0);
    return st ? pp_fail_in(fn, st) : PP_OK;
}

typedef struct pair_work {
    world *wd;
    np_settings set;
    int32_t from;
} pair_work;

/* Set up candidate from + k; one whose bodies have no cell in common gets −1 for its first body. */
static pp_status set_up_one(void *user, int32_t k, np_scratch *scratch)
{
    (void)scratch;
    const pair_work *w = user;
    int32_t *slots = &w->wd->batch.bodies[2 * (w->from + k)];
    const np_body va = body_np_view(w->wd->bodies[slots[0]]), vb = body_np_view(w->wd->bodies[slots[1]]);
    if (!np_pair_setup(&w->set, &va, &vb, &w->wd->batch.pairs[w->from + k]))
        slots[0] = -1;
    return PP_OK;
}

/* Set up the candidate pairs of one pass (crowd_wants) after the *n set up before, adding their cells: the
 * candidates are listed, set up (shared over the workers when there are many) and the kept ones closed up. */
static pp_status set_up_pairs(world *wd, int pass, int32_t *n, int64_t *cells)
{
    pair_batch *b = &wd->batch;
    int32_t listed = *n;
    for (int32_t p = 0; p < wd->broad.pair_count; p++) {
        if (!crowd_wants(wd, p, pass))
            continue;
        pp_status st = pass ? world_reserve_pairs(wd, "pp_world_step", listed + 1) : PP_OK;
        if (st)
            return st;
        const int32_t ia = wd->broad.pairs[p].a, ib = wd->broad.pairs[p].b;
        if (joint_keeps_apart(wd, wd->bodies[ia], wd->bodies[ib]) || carry_claim(wd, (uint32_t)ia, (uint32_t)ib))
            continue;
        PP_ASSERT(listed < b->capacity);
        b->bodies[2 * listed] = ia, b->bodies[2 * listed + 1] = ib, b->candidates[listed] = p;
        listed++;
    }
    pair_work w = {wd, world_np_settings(wd), *n};
    int32_t used;
    pp_status st = workers_for(&wd->workers, host_threads(wd, listed - *n), listed - *n, WORKERS_GRAIN, set_up_one,
                               &w, &wd->scratch, &used);
    if (st)
        return st;
    note_threads(wd, used);
    for (int32_t k = w.from; k < listed; k++) {
        if (b->bodies[2 * k] < 0)
            continue; /* most candidates of a pile: boxes side by side */
        if (k != *n) {
            b->pairs[*n] = b->pairs[k], b->candidates[*n] = b->candidates[k];
            b->bodies[2 * *n] = b->bodies[2 * k], b->bodies[2 * *n + 1] = b->bodies[2 * k + 1];
        }
        *cells += np_pair_cells(&b->pairs[*n]);
        if (pass)
            crowd_set_up(wd, b->candidates[*n]);
        ++*n;
    }
    return PP_OK;
}

/* Set up and run the cores of the substep's pairs: one batch, or crowd.c's two passes, the second after
 * the first has proved which bodies are crowded. *n pairs set up, the first pass's *first of them. */
static pp_status collide_pairs(world *wd, int32_t *n, int32_t *first, int64_t *cells)
{
    const int first_pass = wd->crowd.split ? 1 : 0, last_pass = wd->crowd.split ? 2 : 0;
    for (int pass = first_pass; pass <= last_pass; pass++) {
        const int32_t from = *n;
        const int64_t cells_from = *cells;
        pp_status st = set_up_pairs(wd, pass, n, cells);
        /* An empty second pass, or a later substep's when every pair is carried, leaves the stats of the one before. */
        int32_t threads = 0;
        if (!st && (*n > from || (pass == 0 && !wd->carry.active))) {
            st = world_run_cores(wd, "pp_world_step", from, *n - from, *cells - cells_from, &wd->stats.backend,
                                 &threads);
            note_threads(wd, threads);
        }
        if (st)
            return st;
        if (pass == 1)
            crowd_prove(wd, *first = *n);
    }
    return PP_OK;
}

/* Relative angular speed above which a round body rolls (see touch_round), rad/s: a disc of radius 16 px
 * rolls it at 8 px/s; a resting one sways at hundredths of it. */
#define ROLLING_RATE 0.5

static double angular_speed(const world *wd, const body *bd)
{
    if (!bd->sb.body)
        return 0;
    dvec2 v;
    double w;
    solver_body_get_velocity(wd->solver, &bd->sb, &v, &w);
    return w;
}

/* A round body that rolls touches where a circle would: at one point on the line from its centre of mass
 * along the normal. The ends of its patch would be a flat foot on the pixel polygon's flat runs, and a
 * point off that line would kick it over each corner of the polygon (it lost a fifth to a half of its
 * acceleration on a slope). The point keeps the patch's deepest depth. Slower than ROLLING_RATE it keeps
 * the patch's ends and comes to rest, as a pixel polygon does, rather than rock in a hollow for ever. */
static void touch_round(const world *wd, const body *a, const body *b, np_result *r)
{
    const double ra = body_round_radius(a), rb = body_round_radius(b);
    if ((ra == 0 && rb == 0) || fabs(angular_speed(wd, a) - angular_speed(wd, b)) <= ROLLING_RATE)
        return;
    const body *disc = rb > 0 ? b : a;
    pp_contact *c = &r->contacts[0];
    float depth = c->depth;
    for (int32_t k = 1; k < r->count; k++)
        depth = fmaxf(depth, r->contacts[k].depth);
    const dvec2 n = dv(c->normal.x, c->normal.y); /* from a to b */
    const dvec2 toward_other = disc == b ? dv_scale(n, -1.0) : n;
    const dvec2 p = dv_add(body_com_world(disc), dv_scale(toward_other, (disc == b ? rb : ra) - 0.5 * depth));
    c->point = (pp_vec2){(float)p.x, (float)p.y};
    c->depth = depth;
    r->count = 1;
}

/* Pair k's contacts from its core, on whichever thread takes it: reads the bodies, writes its own result. */
static pp_status finish_one(void *user, int32_t k, np_scratch *scratch)
{
    (void)scratch;
    const pair_work *w = user;
    const body *a = w->wd->bodies[w->wd->batch.bodies[2 * k]], *b = w->wd->bodies[w->wd->batch.bodies[2 * k + 1]];
    const np_body va = body_np_view(a), vb = body_np_view(b);
    np_result *r = &w->wd->batch.results[k];
    np_pair_finish(&w->set, &va, &vb, &w->wd->batch.pairs[k], &w->wd->batch.cores[k], r);
    corner_normal(a, b, r);
    if (w->set.contact_mode == PP_CONTACT_MANIFOLD && r->count > 0)
        touch_round(w->wd, a, b, r);
    return PP_OK;
}

/* Broadphase and narrowphase at the current poses of `substep`; fills wd->contacts. At a step's first
 * substep every pair is collided but the held ones, and resting pairs' contacts are carried through the later
 * ones, as are a pair's whose bodies sat a substep out into the next (carry.h). */
static pp_status find_contacts(world *wd, int32_t substep, double dt, double *t_broad, double *t_narrow)
{
    static const char *fn = "pp_world_step";
    const double t0 = now_ms();
    pp_status st = carry_begin(wd, substep, dt);
    if (!st) /* before the claims, which carry.c stamps with the substep */
        contact_table_begin_substep(wd);
    if (st || (st = awake_refresh(wd)))
        return st ? pp_fail_in(fn, st) : st;
    /* Every pair needs an awake body: with none, the sweep over every box would find nothing. */
    const awake_set *aw = &wd->awake;
    if (aw->movers > 0 && (st = awake_find_pairs(wd, substep, dt)))
        return pp_fail_in(fn, st);
    if (wd->awake.movers == 0)
        wd->broad.pair_count = 0, wd->broad.cand_valid = false;
    if (st || (st = crowd_plan(wd)) || (!wd->crowd.split && (st = world_reserve_pairs(wd, fn, wd->broad.pair_count))))
        return st;
    const double t1 = now_ms();

    /* Set every pair up and run the cores as one batch (or, with crowded bodies, in crowd.c's two
     * passes), turn them into contacts, then take those in the broadphase's order. */
    int32_t n = 0, first = 0, used;
    int64_t cells = 0;
    const int32_t *order = NULL;
    pair_work w = {wd, world_np_settings(wd), 0};
    if ((st = collide_pairs(wd, &n, &first, &cells)) || (wd->crowd.split && (st = crowd_order(wd, first, n, &order))) ||
        (st = workers_for(&wd->workers, host_threads(wd, n), n, WORKERS_GRAIN, finish_one, &w, &wd->scratch, &used)))
        return st;
    note_threads(wd, used);
    step_take_contacts(wd);
    wd->contact_count = 0;
    for (int32_t i = 0; i < n; i++) {
        const int32_t k = order ? order[i] : i;
        const body *a = wd->bodies[wd->batch.bodies[2 * k]], *b = wd->bodies[wd->batch.bodies[2 * k + 1]];
        np_result r = wd->batch.results[k];
        bool keep = true;
        int32_t at = -1;
        if (r.count > 0 && (st = contact_table_found(wd, a, b, &r, &at, &keep)))
            return st;
        if (r.count > 0)
            carry_collided(wd, a->index, b->index);
        const int32_t from = wd->contact_count;
        for (int32_t c = 0; keep && c < r.count; c++) {
            r.contacts[c].a = a->handle;
            r.contacts[c].b = b->handle;
            if ((st = push_contact(wd, &r.contacts[c])))
                return st;
        }
        if (keep && r.count > 0 && (st = contact_table_add_run(wd, from, wd->contact_count, a->index, b->index, at)))
            return st;
    }
    carry_strike(wd);
    if ((st = carry_push(wd)) || (st = contact_table_end_substep(wd)) || (st = crowd_limit_contacts(wd)))
        return st;
    wd->stats.pixels_tested += cells;
    wd->stats.pairs = wd->broad.pair_count;
    wd->stats.contacts = wd->contact_count;
    *t_broad += t1 - t0;
    *t_narrow += now_ms() - t1;
    return PP_OK;
}

static bool within_float(double x) { return fabs(x) <= FLT_MAX; } /* false for NaN too */

/* Hold a body under the motion limits (physpix.h), as Box2D clamps speed: the direction is kept. A speed
 * under them is left bit for bit as it is. */
static void clamp_speed(world *wd, body *bd, solver_body_state *s)
{
    const double max_v = PP_MAX_SPEED, max_w = PP_MAX_ANGULAR_SPEED;
    if (!(dv_dot(s->velocity, s->velocity) > max_v * max_v || fabs(s->angular_velocity) > max_w))
        return;
    const double speed = hypot(s->velocity.x, s->velocity.y);
    if (speed > max_v)
        s->velocity = dv_scale(s->velocity, max_v / speed);
    s->angular_velocity = dmax(-max_w, dmin(max_w, s->angular_velocity));
    solver_body_set_velocity(wd->solver, &bd->sb, s->velocity, s->angular_velocity);
}

/* Read every awake body back from ODE into the cached pose (a sleeper's pose has not moved, nor has one
 * that sat the substep out), its speed clamped. PP_ERR_LIMIT for a pose or velocity past a float even so;
 * the caller undoes the step. */
static pp_status sync_bodies(world *wd)
{
    awake_index_stale(wd);
    for (int32_t k = 0; k < wd->awake.count; k++) {
        body *bd = wd->bodies[wd->awake.slots[k]];
        if (!awake_mover(bd) || wd->islands.span[bd->index] == SPAN_SKIP)
            continue;
        solver_body_state s;
        solver_body_sync(wd->solver, &bd->sb, &s);
        clamp_speed(wd, bd, &s);
        const double c = s.cos_a, sn = s.sin_a;
        /* pivot = com − R(angle)·(com_local − pivot) */
        const dvec2 pos = dv_sub(s.com_world, dv_rot(dv_sub(dv(bd->mass.cx, bd->mass.cy), bd->pivot), c, sn));
        if (!within_float(pos.x) || !within_float(pos.y) || !isfinite(s.angle) || !within_float(s.velocity.x) ||
            !within_float(s.velocity.y) || !isfinite(s.angular_velocity))
            return pp_fail(PP_ERR_LIMIT,
                           "pp_world_step: body %#llx would reach (%g, %g) px, %g rad, moving (%g, %g) px/s, %g rad/s: "
                           "past what a float holds; the step is undone", (unsigned long long)bd->handle.id, pos.x,
                           pos.y, s.angle, s.velocity.x, s.velocity.y, s.angular_velocity);
        bd->angle = s.angle, bd->cos_a = c, bd->sin_a = sn;
        bd->pos = pos;
        body_update_pose_cache(bd);
    }
    return PP_OK;
}

/* The substeps of one step; on failure the caller undoes them. */
static pp_status run_substeps(world *wd, float dt, double *t_broad, double *t_narrow, double *t_solver)
{
    const double h = (double)dt / wd->def.substeps;
    bool still = false; /* nothing moved, woke or slept in the substep before: its contacts stand */
    for (int32_t k = 0; k < wd->def.substeps; k++) {
        pp_status st = still ? PP_OK : find_contacts(wd, k, dt, t_broad, t_narrow);
        if (st)
            return st;
        const double t0 = now_ms();
        if ((st = solver_reserve_contacts(wd->solver, wd->contact_count)))
            return st;
        solver_islands islands; /* before the joints: a failure must leave ODE none */
        const substep_pairing pairing = island_pairing(k, wd->def.substeps);
        if ((st = island_plan(wd, k, pairing, still, &islands)) ||
            ((k == 0 || pairing == PAIR_FIRST) && wd->def.substeps > 1 && (st = carry_record(wd, dt, k))) ||
            (st = continuous_begin(wd)))
            return st;
        if (!still) /* else its contacts' bodies were saved at the substep before */
            step_save_contact_bodies(wd);
        contact_joints_add(wd, h);
        joint_prepare(wd, h);
        forces_apply(wd);
        forces_damp(wd, h);
        if (!solver_step(wd->solver, h, &islands))
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: ODE has no memory for its step");
        still = solver_islands_empty(&islands);
        island_list_woken(wd);
        contact_table_store(wd, h);
        if ((st = sync_bodies(wd)))
            return st;
        if ((st = continuous_end(wd)))
            return st;
        still &= !island_sleep(wd, h);
        *t_solver += now_ms() - t0;
    }
    if (!wd->def.allow_sleep)
        island_sleep_off(wd);
    carry_end_step(wd);
    return PP_OK;
}

/* Nothing awake or changed (the awake set is empty), no contact, carried pair, force, joint or pending END: a
 * step of such a world finds nothing, solves nothing and moves nothing. */
static bool world_is_quiet(const world *wd)
{
    return wd->awake.count == 0 && wd->contact_count == 0 && wd->table.carry_count == 0 && wd->forced.count == 0 &&
           wd->joints.ids.live == 0 && wd->table.gone == 0 && !wd->table.resting_stale;
}

/* A quiet world's step: only the clocks the stages stamp their records with advance, as the full step would
 * advance them (so the next step is the one it would have been), through the stages' own calls. */
static pp_status quiet_substeps(world *wd, float dt)
{
    for (int32_t k = 0; k < wd->def.substeps; k++) {
        pp_status st = carry_begin(wd, k, dt);
        if (st)
            return pp_fail_in("pp_world_step", st);
        if (k == 0) { /* the first substep looks for pairs; the others are still */
            contact_table_begin_substep(wd);
            wd->broad.pair_count = 0;
            wd->stats.backend = choose_backend(wd, 0, 0);
        }
        solver_islands islands;
        if ((st = island_plan(wd, k, PAIR_NONE, false, &islands)) || !solver_step(wd->solver, 0, &islands))
            return st ? st : pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: ODE has no memory for its step");
    }
    carry_end_step(wd);
    return PP_OK;
}

/* Timed edits due now are applied first, each whole or not at all, and stay applied; then the step
 * runs whole or, if memory runs out, not at all. */
PP_API pp_status pp_world_step(pp_world w, float dt)
{
    world *wd = world_lookup(w, "pp_world_step");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!isfinite(dt) || !(dt > 0) || dt > 1)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_step: dt must be finite and in (0, 1] s, got %g", dt);
    const double t_start = now_ms();
    double t_broad = 0, t_narrow = 0, t_solver = 0;
    events_trim(wd);
    pp_status st = timed_edits_apply_due(wd, dt);
    if (st)
        return st;
    const bool quiet = world_is_quiet(wd);
    if (!quiet && (st = step_save(wd)))
        return st;
    wd->stats.pixels_tested = 0;
    wd->stats.swept_stops = 0;
    wd->stats.threads = 0;
    if (quiet) {
        if ((st = quiet_substeps(wd, dt)))
            return st;
        wd->stats.pairs = wd->stats.contacts = 0;
    } else if ((st = run_substeps(wd, dt, &t_broad, &t_narrow, &t_solver))) {
        step_restore(wd);
        forces_step_undone(wd);
        return st;
    }
    step_commit(wd);
    forces_step_done(wd);
    if ((st = joint_step_done(wd)))
        pp_log(1, "physpix: joints past their break force stay until a step has room for their events");
    int32_t awake = 0;
    for (int32_t k = 0; k < wd->awake.count; k++)
        awake += awake_mover(wd->bodies[wd->awake.slots[k]]);
    wd->stats.broadphase_ms = (float)t_broad;
    wd->stats.narrowphase_ms = (float)t_narrow;
    wd->stats.solver_ms = (float)t_solver;
    wd->stats.total_ms = (float)(now_ms() - t_start);
    wd->stats.bodies = wd->body_ids.live;
    wd->stats.awake_bodies = awake;
    wd->time += dt;
    return PP_OK;
}
