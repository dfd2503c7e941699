/* World lifetime, the handle tables, and the step loop:
 * broadphase → narrowphase per pair → ODE contact joints → ODE step, `substeps` times. */
#include "alloc.h"
#include "awake.h"
#include "continuous.h"
#include "edit.h"
#include "forces.h"
#include "handle.h"
#include "island.h"
#include "joint.h"
#include "world.h"
#include "status.h"

#include <float.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Worlds live in a process-wide table of fixed size, its slots from an id pool; a world id is
 * (generation << 32) | (slot + 1) (handle.h). Everything here is read and written under the lock. */
static world *worlds[PP_MAX_WORLDS];
static uint32_t world_generations[PP_MAX_WORLDS], world_free_slots[PP_MAX_WORLDS];
static id_pool world_ids;
static pthread_mutex_t worlds_lock = PTHREAD_MUTEX_INITIALIZER;

/* Lock the table, setting its pool up on first use. */
static void worlds_enter(void)
{
    pthread_mutex_lock(&worlds_lock);
    if (!world_ids.generations)
        id_pool_init_fixed(&world_ids, world_generations, world_free_slots, PP_MAX_WORLDS);
}

int32_t world_live_count(void)
{
    worlds_enter();
    const int32_t n = world_ids.live;
    pthread_mutex_unlock(&worlds_lock);
    return n;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

world *world_lookup(pp_world w, const char *fn)
{
    const uint32_t slot = world_id_slot(w.id), gen = world_id_gen(w.id);
    world *wd = NULL;
    worlds_enter();
    if (w.id != 0 && id_pool_current(&world_ids, slot, gen))
        wd = worlds[slot];
    pthread_mutex_unlock(&worlds_lock);
    if (!wd)
        pp_fail(PP_ERR_INVALID_HANDLE, "%s: world handle %#llx is null, destroyed or stale", fn,
                (unsigned long long)w.id);
    return wd;
}

uint64_t world_id_of_tag(uint32_t tag)
{
    const uint32_t slot = tag_world_slot(tag);
    uint64_t id = 0;
    worlds_enter();
    if (worlds[slot] && worlds[slot]->tag == tag)
        id = worlds[slot]->handle.id;
    pthread_mutex_unlock(&worlds_lock);
    return id;
}

PP_API pp_world_def pp_world_def_default(void)
{
    pp_world_def d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.gravity = (pp_vec2){0.0f, 980.0f};
    d.substeps = 4;
    d.solver_iterations = 20;
    d.backend = PP_BACKEND_AUTO;
    d.normal_method = PP_NORMAL_AREA_GRADIENT;
    d.contact_mode = PP_CONTACT_MANIFOLD;
    d.raster_stride = 1;
    d.pixels_per_meter = 100.0f;
    d.contact_slop = 0.75f;
    d.contact_erp = 0.2f;
    d.contact_cfm = 1e-5f;
    d.bounce_threshold = 20.0f;
    d.allow_sleep = 1;
    d.sleep_linear_speed = 5.0f;
    d.sleep_angular_speed = 0.1f;
    d.sleep_time = 0.5f;
    d.continuous = 1;
    d.max_correction_speed = 300.0f;
    d.worker_threads = 0; /* one per CPU */
    d.exact_island_rows = 128;
    return d;
}

/* The presets differ only in the solver's work, the knob that decides whether stacks stand; the
 * figures behind each are in the README ("Presets") and come from build/bench/bench_accuracy.
 * FAST is the front's cheapest point without a coarse stride (stride 2 took the depth error from 0.26 to 1 px):
 * it holds 10-high stacks, not 20. BALANCED's 20 iterations stand bench_stability's card house for 60 s with
 * carried contacts, as 15 do with the arch and the 20-row pyramid drifting more; 10 let the card house fall at
 * 35 s, and 40 cost 1.5 times as much and stand nothing more. One contact point a pair (CENTROID) lets a box tip on a gentle slope,
 * so every preset keeps two. */
PP_API pp_world_def pp_world_def_preset(pp_preset preset)
{
    pp_world_def d = pp_world_def_default();
    switch (preset) {
    case PP_PRESET_FAST:
        d.substeps = 1;
        d.solver_iterations = 10;
        return d;
    case PP_PRESET_BALANCED:
        return d;
    case PP_PRESET_ACCURATE:
        d.solver_iterations = 80;
        return d;
    default:
        d.struct_size = 0;
        return d;
    }
}

/* Zero in a count field means its default (as the header says). */
static void apply_count_defaults(pp_world_def *d)
{
    const pp_world_def def = pp_world_def_default();
    if (d->substeps == 0) d->substeps = def.substeps;
    if (d->solver_iterations == 0) d->solver_iterations = def.solver_iterations;
    if (d->raster_stride == 0) d->raster_stride = def.raster_stride;
}

static pp_status check_world_def(const pp_world_def *d)
{
    if (!finite2(d->gravity.x, d->gravity.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: gravity must be finite");
    if (!(hypot(d->gravity.x, d->gravity.y) <= PP_MAX_ACCELERATION))
        return pp_fail(PP_ERR_INVALID_ARGUMENT,
                       "pp_world_create: gravity (%g, %g) px/s² is over PP_MAX_ACCELERATION (%g px/s²)", d->gravity.x,
                       d->gravity.y, PP_MAX_ACCELERATION);
    if (d->substeps < 1 || d->substeps > 64)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: substeps must be 1..64, got %d", (int)d->substeps);
    if (d->solver_iterations < 1 || d->solver_iterations > 1000)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: solver_iterations must be 1..1000, got %d",
                       (int)d->solver_iterations);
    if (d->raster_stride != 1 && d->raster_stride != 2 && d->raster_stride != 4)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: raster_stride must be 1, 2 or 4, got %d",
                       (int)d->raster_stride);
    if ((uint32_t)d->normal_method > PP_NORMAL_KERNEL)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: normal_method %d is unknown", (int)d->normal_method);
    if ((uint32_t)d->contact_mode > PP_CONTACT_CENTROID)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: contact_mode %d is unknown", (int)d->contact_mode);
    if ((uint32_t)d->backend > PP_BACKEND_GPU)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: backend %d is unknown", (int)d->backend);
    if (!(d->pixels_per_meter > 0) || !isfinite(d->pixels_per_meter))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: pixels_per_meter must be finite and > 0");
    if (!(d->contact_slop >= 0) || !isfinite(d->contact_slop))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: contact_slop must be finite and ≥ 0");
    if (!(d->contact_erp >= 0 && d->contact_erp <= 1))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: contact_erp must be in 0..1");
    if (!(d->contact_cfm >= 0) || !isfinite(d->contact_cfm))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: contact_cfm must be finite and ≥ 0");
    if (!(d->bounce_threshold >= 0) || !isfinite(d->bounce_threshold))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: bounce_threshold must be finite and ≥ 0");
    if (d->worker_threads < 0 || d->worker_threads > 16)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: worker_threads must be 0 (one per CPU) or 1..16, got %d",
                       (int)d->worker_threads);
    if (d->exact_island_rows < 0 || d->exact_island_rows > PP_MAX_EXACT_ISLAND_ROWS)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: exact_island_rows must be 0..%d, got %d",
                       PP_MAX_EXACT_ISLAND_ROWS, (int)d->exact_island_rows);
    if (!(d->max_correction_speed > 0 && d->max_correction_speed <= PP_MAX_SPEED))
        return pp_fail(PP_ERR_INVALID_ARGUMENT,
                       "pp_world_create: max_correction_speed must be > 0 and at most PP_MAX_SPEED (%g px/s), got %g",
                       PP_MAX_SPEED, d->max_correction_speed);
    if (!(d->sleep_linear_speed >= 0 && d->sleep_angular_speed >= 0 && d->sleep_time >= 0) ||
        !isfinite(d->sleep_linear_speed) || !isfinite(d->sleep_angular_speed) || !isfinite(d->sleep_time))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: sleep thresholds must be finite and ≥ 0");
    return PP_OK;
}

PP_API pp_status pp_world_create(const pp_world_def *def, pp_world *out)
{
    if (!def || !out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: %s is NULL", def ? "out" : "def");
    if (def->struct_size != sizeof(pp_world_def))
        return pp_fail(PP_ERR_ABI, "pp_world_create: def->struct_size is %u, this library expects %u%s",
                       (unsigned)def->struct_size, (unsigned)sizeof(pp_world_def),
                       def->struct_size == 0 ? " (fill the def from pp_world_def_default or a known preset)" : "");
    pp_world_def d = *def;
    apply_count_defaults(&d);
    pp_status st = check_world_def(&d);
    if (st)
        return st;
    /* Refused before anything is allocated; the slot search below stays the check that counts. */
    if (world_live_count() >= PP_MAX_WORLDS)
        return pp_fail(PP_ERR_LIMIT, "pp_world_create: already %d live worlds (PP_MAX_WORLDS)", PP_MAX_WORLDS);
    world *wd = pp_calloc(1, sizeof *wd);
    if (!wd)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_create: no memory");
    wd->def = d;
    wd->camera = (pp_camera){{480.0f, 270.0f}, 1.0f, 960, 540};
    if (d.backend == PP_BACKEND_GPU && (st = gpu_narrow_create("pp_world_create", &wd->gpu))) {
        pp_free(wd);
        return st;
    }
    if ((st = solver_create(&d, &wd->solver))) {
        gpu_narrow_destroy(wd->gpu);
        pp_free(wd);
        return st;
    }
    worlds_enter();
    uint32_t slot = 0;
    if (!id_pool_take_free(&world_ids, &slot)) {
        pthread_mutex_unlock(&worlds_lock);
        solver_destroy(wd->solver);
        gpu_narrow_destroy(wd->gpu);
        pp_free(wd);
        return pp_fail(PP_ERR_LIMIT, "pp_world_create: already %d live worlds (PP_MAX_WORLDS)", PP_MAX_WORLDS);
    }
    worlds[slot] = wd;
    wd->slot = slot;
    wd->tag = world_tag(slot, world_generations[slot]);
    wd->handle.id = world_id_make(slot, world_generations[slot]);
    pthread_mutex_unlock(&worlds_lock);
    wd->stats.backend = d.backend == PP_BACKEND_GPU ? PP_BACKEND_GPU : PP_BACKEND_CPU;
    *out = wd->handle;
    return PP_OK;
}

void body_free(world *wd, body *bd); /* body.c */

PP_API pp_status pp_world_destroy(pp_world w)
{
    world *wd = world_lookup(w, "pp_world_destroy");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    worlds_enter();
    worlds[wd->slot] = NULL;
    id_pool_release(&world_ids, wd->slot);
    pthread_mutex_unlock(&worlds_lock);
    joint_free_all(wd); /* before the bodies: ODE's joints go before what they attach */
    for (int32_t i = 0; i < wd->body_ids.capacity; i++)
        if (wd->bodies[i])
            body_free(wd, wd->bodies[i]);
    solver_destroy(wd->solver);
    broadphase_free(&wd->broad);
    np_scratch_free(&wd->scratch);
    workers_free(wd->workers);
    gpu_narrow_destroy(wd->gpu);
    pp_free(wd->pairs);
    pp_free(wd->cores);
    pp_free(wd->pair_bodies);
    pp_free(wd->events);
    pp_free(wd->proxies);
    pp_free(wd->sweep_from);
    pp_free(wd->group);
    pp_free(wd->island_bodies);
    pp_free(wd->island_kind);
    pp_free(wd->island_span);
    pp_free(wd->node_mark);
    pp_free(wd->nodes);
    pp_free(wd->swept);
    pp_free(wd->awake_slots);
    pp_free(wd->bodies);
    pp_free(wd->body_ids.generations);
    pp_free(wd->body_ids.free_slots);
    pp_free(wd->contacts);
    pp_free(wd->edits);
    pp_free(wd->undo.bodies);
    pp_free(wd->undo.contacts);
    pp_free(wd->undo.touching);
    pp_free(wd->undo.resting);
    pp_free(wd->resting);
    pp_free(wd->resting_next);
    pp_free(wd->touching);
    pp_free(wd->touch_next);
    carry_free(&wd->carry);
    pp_free(wd->forced);
    crowd_free(&wd->crowd);
    pp_free(wd);
    return PP_OK;
}

pp_status world_slot_array(world *wd, void **items, int32_t *capacity, size_t per_slot, const char *what)
{
    if (!array_reserve(items, capacity, wd->body_ids.capacity, per_slot))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for %s", what);
    return PP_OK;
}

static pp_status push_contact(world *wd, const pp_contact *c)
{
    if (!ARRAY_RESERVE(wd->contacts, wd->contact_capacity, wd->contact_count + 1))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for %d contacts", (int)wd->contact_count + 1);
    wd->contacts[wd->contact_count++] = *c;
    return PP_OK;
}

static double inv_mass(const body *bd)
{
    return bd->type == PP_BODY_DYNAMIC && bd->mass.mass > 0 ? 1.0 / bd->mass.mass : 0.0;
}

pp_status world_reserve_pairs(world *wd, const char *fn, int32_t n)
{
    if (n <= wd->pair_capacity)
        return PP_OK;
    int32_t pairs = wd->pair_capacity, cores = pairs, bodies = pairs; /* the three grow alike */
    if (!ARRAY_RESERVE(wd->pairs, pairs, n) || !ARRAY_RESERVE(wd->cores, cores, n) ||
        !array_reserve((void **)&wd->pair_bodies, &bodies, n, 2 * sizeof *wd->pair_bodies))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d pairs", fn, (int)n);
    wd->pair_capacity = pairs;
    return PP_OK;
}

/* AUTO sends a batch to a hardware GPU from this many sampled cells on. Not yet a measured
 * hardware crossover: the smallest GPU batch (one 16² pair) takes 0.43 ms on llvmpipe in make bench,
 * the CPU's time for about 20,000 cells at its measured ~22 ns a cell. A software rasteriser
 * (llvmpipe) never gets AUTO's work: make bench finds it 3–6× slower than the CPU. */
#define GPU_AUTO_MIN_CELLS 20000

static pp_backend choose_backend(world *wd, int64_t cells)
{
    if (wd->def.backend != PP_BACKEND_AUTO)
        return wd->def.backend;
    if (cells < GPU_AUTO_MIN_CELLS)
        return PP_BACKEND_CPU;
    if (!wd->gpu_tried) {
        wd->gpu_tried = true;
        if (gpu_narrow_create("pp_world_step", &wd->gpu) == PP_OK && gpu_narrow_is_software(wd->gpu))
            pp_log(1, "physpix: AUTO keeps the narrowphase on the CPU: the GPU context is a software rasteriser");
        else if (!wd->gpu)
            pp_log(1, "physpix: AUTO keeps the narrowphase on the CPU: %s", pp_last_error());
    }
    return wd->gpu && !gpu_narrow_is_software(wd->gpu) ? PP_BACKEND_GPU : PP_BACKEND_CPU;
}

pp_status world_run_cores(world *wd, const char *fn, int32_t first, int32_t n, int64_t cells, pp_backend *ran,
                          int32_t *threads)
{
    const np_settings set = world_np_settings(wd);
    *ran = choose_backend(wd, cells);
    *threads = 0;
    /* A world with no pair yet has no arrays: NULL + 0 is undefined, so offset only a real array. */
    np_pair *pairs = first ? wd->pairs + first : wd->pairs;
    np_core *cores = first ? wd->cores + first : wd->cores;
    pp_status st;
    if (*ran == PP_BACKEND_GPU)
        st = gpu_narrow_run(wd->gpu, fn, &set, pairs, n, &wd->scratch, cores);
    else {
        const int32_t wanted = n > 1 && cells >= WORKERS_MIN_CELLS ? workers_wanted(wd->def.worker_threads) : 1;
        st = workers_run(&wd->workers, wanted, &set, pairs, n, &wd->scratch, cores, threads);
    }
    return st ? pp_fail_in(fn, st) : PP_OK;
}

/* Set up the candidate pairs of one pass (crowd_wants) after the *n set up before, adding their cells. */
static pp_status set_up_pairs(world *wd, int pass, int32_t *n, int64_t *cells)
{
    const np_settings set = world_np_settings(wd);
    for (int32_t p = 0; p < wd->broad.pair_count; p++) {
        if (!crowd_wants(wd, p, pass))
            continue;
        pp_status st = pass ? world_reserve_pairs(wd, "pp_world_step", *n + 1) : PP_OK;
        if (st)
            return st;
        const int32_t ia = wd->broad.pairs[p].a, ib = wd->broad.pairs[p].b;
        if (joint_keeps_apart(wd, wd->bodies[ia], wd->bodies[ib]) || carry_claim(wd, (uint32_t)ia, (uint32_t)ib))
            continue;
        const np_body va = body_np_view(wd->bodies[ia]), vb = body_np_view(wd->bodies[ib]);
        PP_ASSERT(*n < wd->pair_capacity);
        if (!np_pair_setup(&set, &va, &vb, &wd->pairs[*n]))
            continue;
        *cells += np_pair_cells(&wd->pairs[*n]);
        wd->pair_bodies[2 * *n] = ia, wd->pair_bodies[2 * *n + 1] = ib;
        ++*n;
        if (pass)
            crowd_set_up(wd, p);
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
            wd->stats.threads = threads > wd->stats.threads ? threads : wd->stats.threads;
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

/* Broadphase and narrowphase at the current poses of `substep`; fills wd->contacts. At a step's first
 * substep every pair is collided but the held ones, and resting pairs' contacts are carried through the later
 * ones, as are a pair's whose bodies sat a substep out into the next (carry.h). */
static pp_status find_contacts(world *wd, int32_t substep, double dt, double *t_broad, double *t_narrow)
{
    static const char *fn = "pp_world_step";
    const double t0 = now_ms();
    pp_status st = carry_begin(wd, substep, dt);
    if (st || (st = awake_refresh(wd)))
        return st ? pp_fail_in(fn, st) : st;
    /* Every pair needs an awake body: with none, the sweep over every box would find nothing. */
    if (wd->awake_movers > 0 &&
        (st = broadphase_find_pairs(&wd->broad, wd->proxies, wd->body_ids.capacity, wd->awake_slots, wd->awake_count)))
        return pp_fail_in(fn, st);
    if (wd->awake_movers == 0)
        wd->broad.pair_count = 0;
    if (st || (st = crowd_plan(wd)) || (!wd->crowd.split && (st = world_reserve_pairs(wd, fn, wd->broad.pair_count))))
        return st;
    const double t1 = now_ms();

    /* Set every pair up and run the cores as one batch (or, with crowded bodies, in crowd.c's two
     * passes), then turn them into contacts in the broadphase's order. */
    const np_settings set = world_np_settings(wd);
    int32_t n = 0, first = 0;
    int64_t cells = 0;
    const int32_t *order = NULL;
    if ((st = collide_pairs(wd, &n, &first, &cells)) || (wd->crowd.split && (st = crowd_order(wd, first, n, &order))))
        return st;
    wd->contact_count = 0;
    touch_begin(wd);
    for (int32_t i = 0; i < n; i++) {
        const int32_t k = order ? order[i] : i;
        const body *a = wd->bodies[wd->pair_bodies[2 * k]], *b = wd->bodies[wd->pair_bodies[2 * k + 1]];
        const np_body va = body_np_view(a), vb = body_np_view(b);
        np_result r;
        np_pair_finish(&set, &va, &vb, &wd->pairs[k], &wd->cores[k], &r);
        if (set.contact_mode == PP_CONTACT_MANIFOLD && r.count > 0)
            touch_round(wd, a, b, &r);
        bool keep = true;
        if (r.count > 0 && (st = touch_pair(wd, a, b, &r, &keep)))
            return st;
        for (int32_t c = 0; keep && c < r.count; c++) {
            r.contacts[c].a = a->handle;
            r.contacts[c].b = b->handle;
            if ((st = push_contact(wd, &r.contacts[c])))
                return st;
        }
    }
    carry_strike(wd);
    if ((st = carry_push(wd)) || (st = touch_end(wd)) || (st = crowd_limit_contacts(wd)))
        return st;
    wd->stats.pixels_tested += cells;
    wd->stats.pairs = wd->broad.pair_count;
    wd->stats.contacts = wd->contact_count;
    *t_broad += t1 - t0;
    *t_narrow += now_ms() - t1;
    return PP_OK;
}

/* The tangential speed that takes back, at the contact_erp rate, what a contact has slipped since its
 * pair's friction anchor (touch.c); Coulomb's bound still caps the force, so a sliding body slides.
 * Only QuickStep's stacks slip unasked (their solve stops short); an exact or lone-body solve does not. */
static double anchor_speed(const world *wd, const body *a, const body *b, const touch *t, const pp_contact *c,
                           double h)
{
    if (wd->island_kind[(a->sb.body ? a : b)->index] != ISLAND_QUICK_STACK)
        return 0;
    if (!t || handle_slot(t->a) != a->index)
        return 0;
    const dvec2 slip = touch_anchor_slip(t, a, b, dv(c->point.x, c->point.y));
    const double along = dv_dot(slip, dv(-c->normal.y, c->normal.x));
    const double v = wd->def.contact_erp * along / h, cap = wd->def.max_correction_speed;
    return fmax(-cap, fmin(cap, v));
}

/* How fast the pair's points meet along the contact normal, px/s (> 0: approaching). */
static double approach_speed(const world *wd, const body *a, const body *b, const pp_contact *c)
{
    const dvec2 p = dv(c->point.x, c->point.y), n = dv(c->normal.x, c->normal.y);
    return -dv_dot(dv_sub(body_point_velocity(wd, b, p), body_point_velocity(wd, a, p)), n);
}

/* The contact is found a substep late, up to a substep's travel deep, and a bounce of e·v from there
 * would rise e²·depth short. The coefficient handed to ODE instead gives the speed that, against the
 * pair's gravity along the normal, reaches the slop depth at e times the speed the bodies met with:
 * v_out² = e²·v² + 2·g·d·(1 − e²), d the depth past contact_slop. Never more than the approach speed. */
static double bounce_for(const world *wd, const body *a, const body *b, const pp_contact *c, double e)
{
    if (e <= 0)
        return 0;
    const dvec2 n = dv(c->normal.x, c->normal.y);
    const double closing = approach_speed(wd, a, b, c);
    if (!(closing > wd->def.bounce_threshold))
        return e; /* ODE bounces nothing this slow */
    const dvec2 g = dv(wd->def.gravity.x, wd->def.gravity.y);
    const dvec2 ga = a->type == PP_BODY_DYNAMIC ? g : dv(0, 0), gb = b->type == PP_BODY_DYNAMIC ? g : dv(0, 0);
    const double g_closing = -dv_dot(dv_sub(gb, ga), n), d = fmax(0.0, c->depth - wd->def.contact_slop);
    const double v2 = e * e * closing * closing + 2.0 * fmax(0.0, g_closing) * d * (1.0 - e * e);
    return fmin(fmax(e, sqrt(v2) / closing), fmax(e, 1.0));
}

/* ODE's surface layer leaves a contact shallower than contact_slop where it is, and QuickStep's unfinished
 * solve lets a pile creep down through that band for seconds (a 10-row pyramid sank 0.65 px in the minute
 * after its first second at 4 × 80). On a QuickStep stack the pair closes that gap at the contact_erp rate,
 * as the depth past it is pushed out, so the pile settles in a few steps. Not where a light body carries one
 * over 4 times its mass (QuickStep's weak solve let a 1:10:100:1000 chain fall through the gap), not on an
 * exact island (it holds where it is), and not on a bounce (it keeps its own speed). */
enum { CLOSING_MASS_RATIO = 4 };

static double closing_speed(const world *wd, const body *a, const body *b, const pp_contact *c, double h, double e)
{
    const body *mover = a->sb.body ? a : b;
    const double gap = wd->def.contact_slop - c->depth, ia = inv_mass(a), ib = inv_mass(b);
    if (!(gap > 0) || wd->island_kind[mover->index] != ISLAND_QUICK_STACK)
        return 0;
    if ((ia > 0 && ib > 0 && fmax(ia, ib) > CLOSING_MASS_RATIO * fmin(ia, ib)) ||
        (e > 0 && approach_speed(wd, a, b, c) > wd->def.bounce_threshold))
        return 0;
    return wd->def.contact_erp * gap / h;
}

/* The substeps of time a contact's island advances in this one (SPAN_*). */
static int contact_span(const world *wd, const pp_contact *c)
{
    const body *a = body_of(wd, c->a);
    return wd->island_span[(a->sb.body ? a : body_of(wd, c->b))->index];
}

/* The joints of the contacts whose island advances `span` substeps of h / span s, in order or reversed. */
static void add_span_joints(world *wd, int span, double h, bool reversed)
{
    const touch *t = NULL; /* the last pair's, found once for its points (they come together) */
    uint64_t ta = 0, tb = 0;
    for (int32_t k = 0; k < wd->contact_count; k++) {
        const int32_t i = reversed ? wd->contact_count - 1 - k : k;
        const pp_contact *c = &wd->contacts[i];
        if (contact_span(wd, c) != span)
            continue;
        const body *a = body_of(wd, c->a), *b = body_of(wd, c->b);
        if (c->a.id != ta || c->b.id != tb)
            t = touch_find(wd, c->a.id, c->b.id), ta = c->a.id, tb = c->b.id;
        const double e = fmax(a->restitution, b->restitution);
        const solver_contact sc = {
            a->sb.body ? &a->sb : NULL, b->sb.body ? &b->sb : NULL, inv_mass(a), inv_mass(b),
            dv(c->point.x, c->point.y), dv(c->normal.x, c->normal.y), c->depth,
            sqrt(a->friction * b->friction), bounce_for(wd, a, b, c, e),
            anchor_speed(wd, a, b, t, c, h), closing_speed(wd, a, b, c, h, e),
        };
        solver_add_contact(wd->solver, &sc, i);
    }
}

/* QuickStep solves the joints in the order they were added, and that order biases it: a stack whose
 * pairs each have two points leans toward the point solved first. The order flips every time an island
 * is solved (by the step count, so snapshots keep it), and the biases cancel: islands solved every substep
 * by its parity, those solved every other substep (SPAN_TWO, at every second count) by the next bit. No
 * contact joins two islands, so each span's contacts go in their own order. */
static void add_contact_joints(world *wd, const solver_islands *is, double substep)
{
    const uint64_t steps = solver_get_steps(wd->solver);
    if (is->exact_count + is->quick_count > 0)
        add_span_joints(wd, SPAN_ONE, substep, steps & 1);
    if (is->quick_two_count > 0)
        add_span_joints(wd, SPAN_TWO, 2 * substep, steps >> 1 & 1);
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
    s->angular_velocity = fmax(-max_w, fmin(max_w, s->angular_velocity));
    solver_body_set_velocity(wd->solver, &bd->sb, s->velocity, s->angular_velocity);
}

/* Read every awake body back from ODE into the cached pose (a sleeper's pose has not moved, nor has one
 * that sat the substep out), its speed clamped. PP_ERR_LIMIT for a pose or velocity past a float even so;
 * the caller undoes the step. */
static pp_status sync_bodies(world *wd)
{
    for (int32_t k = 0; k < wd->awake_count; k++) {
        body *bd = wd->bodies[wd->awake_slots[k]];
        if (!awake_mover(bd) || wd->island_span[bd->index] == SPAN_SKIP)
            continue;
        solver_body_flatten(&bd->sb);
        solver_body_state s;
        solver_body_get_state(wd->solver, &bd->sb, &s);
        clamp_speed(wd, bd, &s);
        const double c = cos(s.angle), sn = sin(s.angle);
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

/* ---- timed edits: a binary heap, so that scheduling and applying n edits cost n log n, in any order ---- */

static bool edit_before(const timed_edit *a, const timed_edit *b)
{
    return a->edit.time < b->edit.time || (a->edit.time == b->edit.time && a->serial < b->serial);
}

static int edit_order(const void *a, const void *b)
{
    return edit_before(a, b) ? -1 : edit_before(b, a);
}

/* Add an edit into room already made. */
static void edits_push(world *wd, const pp_timed_edit *e)
{
    timed_edit x = {*e, wd->edit_serial++};
    x.edit.reserved = 0;
    int32_t i = wd->edit_count++;
    /* Into an empty heap, or past every edit of a sorted one, it leaves the heap sorted. */
    wd->edits_in_order = i == 0 || (wd->edits_in_order && !edit_before(&x, &wd->edits[i - 1]));
    for (; i > 0 && edit_before(&x, &wd->edits[(i - 1) / 2]); i = (i - 1) / 2)
        wd->edits[i] = wd->edits[(i - 1) / 2];
    wd->edits[i] = x;
}

/* Remove the next edit to apply, edits[0]. */
static void edits_pop(world *wd)
{
    const int32_t n = --wd->edit_count;
    const timed_edit x = wd->edits[n];
    int32_t i = 0;
    for (int32_t c; (c = 2 * i + 1) < n; i = c) {
        if (c + 1 < n && edit_before(&wd->edits[c + 1], &wd->edits[c]))
            c++;
        if (!edit_before(&wd->edits[c], &x))
            break;
        wd->edits[i] = wd->edits[c];
    }
    wd->edits[i] = x;
    wd->edits_in_order = n <= 1;
}

/* Sort the heap in place, which leaves it a heap; keys are unique, so the order is the same every run. */
static void edits_sort(world *wd)
{
    if (!wd->edits_in_order)
        qsort(wd->edits, (size_t)wd->edit_count, sizeof *wd->edits, edit_order);
    wd->edits_in_order = true;
}

timed_edit *world_edits_in_order(const world *wd)
{
    timed_edit *copy = pp_malloc(((size_t)wd->edit_count + 1) * sizeof *copy);
    if (copy && wd->edit_count > 0) {
        memcpy(copy, wd->edits, (size_t)wd->edit_count * sizeof *copy);
        if (!wd->edits_in_order)
            qsort(copy, (size_t)wd->edit_count, sizeof *copy, edit_order);
    }
    return copy;
}

/* Apply, in order, the timed edits due at a step that starts now: those nearest this step or earlier.
 * An edit leaves the queue once applied, so one that fails is tried again by the next step. */
static pp_status apply_due_edits(world *wd, float dt)
{
    while (wd->edit_count > 0 && wd->edits[0].edit.time < wd->time + 0.5 * dt) {
        const pp_timed_edit e = wd->edits[0].edit;
        body *bd = e.body.id ? body_find(wd, e.body) : NULL;
        pp_status st = PP_OK;
        if (e.body.id && !bd)
            pp_log(1, "physpix: a timed edit at t = %g s skipped: its body is gone", e.time);
        else if (e.type == PP_EDIT_PAINT_CIRCLE)
            st = edit_paint_circle(wd, bd, e.center, e.radius, (uint8_t)e.weight, "pp_world_step", NULL);
        else
            st = edit_erase_circle(wd, bd, e.center, e.radius, "pp_world_step", NULL);
        if (st)
            return st;
        edits_pop(wd);
    }
    return PP_OK;
}

/* Save a movable body's part of the step, once a step. */
static void save_body(step_undo *u, const body *bd)
{
    PP_ASSERT(bd->index < (uint32_t)u->body_capacity);
    step_saved_body *sv = &u->bodies[bd->index];
    if (!bd->sb.body || sv->step == u->step)
        return;
    sv->step = u->step;
    solver_body_save(&bd->sb, &sv->ode);
    sv->pos = bd->pos, sv->angle = bd->angle, sv->cos_a = bd->cos_a, sv->sin_a = bd->sin_a;
    sv->slow_time = bd->slow_time, sv->aabb = bd->aabb;
}

/* Save what a step may change. It allocates first and changes nothing, so a failure here is harmless.
 * A sleeper changes only if a contact joint lets ODE wake it: save_contact_bodies saves it then. */
static pp_status step_save(world *wd)
{
    step_undo *u = &wd->undo;
    const int32_t saved = u->body_capacity;
    if (!ARRAY_RESERVE(u->bodies, u->body_capacity, wd->body_ids.capacity))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to start a step of %d bodies",
                       (int)wd->body_ids.live);
    memset(u->bodies + saved, 0, (size_t)(u->body_capacity - saved) * sizeof *u->bodies); /* step 0: never */
    if (!ARRAY_RESERVE(u->contacts, u->contact_capacity, wd->contact_count))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to start a step of %d bodies",
                       (int)wd->body_ids.live);
    u->step++;
    for (int32_t k = 0; k < wd->awake_count; k++) {
        const body *bd = wd->bodies[wd->awake_slots[k]];
        if (awake_mover(bd))
            save_body(u, bd);
    }
    if (wd->contact_count > 0)
        memcpy(u->contacts, wd->contacts, (size_t)wd->contact_count * sizeof *u->contacts);
    u->contact_count = wd->contact_count;
    u->touch_saved = u->resting_saved = false; /* saved by touch_end before it first changes them (world_save_touching) */
    u->event_count = wd->event_count;
    u->stats = wd->stats;
    u->solver_steps = solver_get_steps(wd->solver);
    return carry_save(wd);
}

pp_status world_save_touching(world *wd, bool resting)
{
    step_undo *u = &wd->undo;
    bool *saved = resting ? &u->resting_saved : &u->touch_saved;
    touch **copy = resting ? &u->resting : &u->touching;
    int32_t *copy_count = resting ? &u->resting_count : &u->touch_count;
    int32_t *copy_cap = resting ? &u->resting_capacity : &u->touch_capacity;
    const touch *list = resting ? wd->resting : wd->touching;
    const int32_t n = resting ? wd->resting_count : wd->touch_count;
    if (*saved)
        return PP_OK;
    if (!ARRAY_RESERVE(*copy, *copy_cap, n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to save %d touching pairs", (int)n);
    if (n > 0)
        memcpy(*copy, list, (size_t)n * sizeof **copy);
    *copy_count = n;
    *saved = true;
    return PP_OK;
}

/* Before the solver runs: every body a contact joint or a joint may wake is saved. */
static void save_contact_bodies(world *wd)
{
    for (int32_t k = 0; k < wd->contact_count; k++) {
        save_body(&wd->undo, body_of(wd, wd->contacts[k].a));
        save_body(&wd->undo, body_of(wd, wd->contacts[k].b));
    }
    for (int32_t i = 0; wd->joints.ids.live > 0 && i < wd->joints.ids.capacity; i++) {
        const joint *jt = wd->joints.items[i];
        const body *a = jt ? joint_body_a(wd, jt) : NULL, *b = jt ? joint_body_b(wd, jt) : NULL;
        if (a)
            save_body(&wd->undo, a);
        if (b)
            save_body(&wd->undo, b);
    }
}

/* Put back what the step saved; the buffers it restores into are at least as large as when saved. */
static void step_restore(world *wd)
{
    step_undo *u = &wd->undo;
    PP_ASSERT(u->body_capacity >= wd->body_ids.capacity && u->contact_count <= wd->contact_capacity &&
              u->event_count <= wd->event_count);
    for (int32_t i = 0; i < wd->body_ids.capacity; i++) {
        body *bd = wd->bodies[i];
        const step_saved_body *sv = &u->bodies[i];
        if (!bd || sv->step != u->step)
            continue;
        solver_body_restore(&bd->sb, &sv->ode);
        bd->pos = sv->pos, bd->angle = sv->angle, bd->cos_a = sv->cos_a, bd->sin_a = sv->sin_a;
        bd->slow_time = sv->slow_time, bd->aabb = sv->aabb;
    }
    if (u->contact_count > 0)
        memcpy(wd->contacts, u->contacts, (size_t)u->contact_count * sizeof *wd->contacts);
    wd->contact_count = u->contact_count;
    wd->stats = u->stats;
    solver_set_steps(wd->solver, u->solver_steps);
    /* The saved pairs become the world's, its buffer the next save's: nothing to allocate. */
    if (u->touch_saved) {
        touch *list = wd->touching;
        const int32_t cap = wd->touch_capacity;
        wd->touching = u->touching, wd->touch_count = u->touch_count, wd->touch_capacity = u->touch_capacity;
        u->touching = list, u->touch_capacity = cap;
    }
    if (u->resting_saved) {
        touch *list = wd->resting;
        const int32_t cap = wd->resting_capacity;
        wd->resting = u->resting, wd->resting_count = u->resting_count, wd->resting_capacity = u->resting_capacity;
        u->resting = list, u->resting_capacity = cap;
    }
    wd->event_count = u->event_count;
    carry_restore(wd);
    awake_rebuild(wd); /* poses and sleep came back behind the set's back */
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
        if ((st = continuous_begin(wd)))
            return st;
        if ((st = solver_reserve_feedback(wd->solver, wd->contact_count)))
            return st;
        solver_islands islands; /* before the joints: a failure must leave ODE none */
        const substep_pairing pairing = k % 2 ? PAIR_SECOND : k + 1 < wd->def.substeps ? PAIR_FIRST : PAIR_NONE;
        if ((st = island_plan(wd, pairing, &islands)) ||
            ((k == 0 || pairing == PAIR_FIRST) && wd->def.substeps > 1 && (st = carry_record(wd, dt, k))))
            return st;
        save_contact_bodies(wd);
        add_contact_joints(wd, &islands, h);
        joint_prepare(wd, h);
        forces_apply(wd);
        forces_damp(wd, h);
        if (!solver_step(wd->solver, h, &islands))
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: ODE has no memory for its step");
        still = islands.exact_count + islands.quick_count + islands.quick_two_count == 0;
        island_list_woken(wd);
        for (int32_t c = 0; c < wd->contact_count; c++) {
            pp_contact *ct = &wd->contacts[c];
            /* Over one substep, whatever the span: force × h, as the header has it. */
            ct->normal_impulse = contact_span(wd, ct) > 0
                                     ? (float)solver_contact_impulse(wd->solver, c, dv(ct->normal.x, ct->normal.y), h)
                                     : 0;
        }
        if ((st = sync_bodies(wd)))
            return st;
        if ((st = continuous_end(wd)))
            return st;
        still &= !island_sleep(wd, h);
        *t_solver += now_ms() - t0;
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
    pp_status st = apply_due_edits(wd, dt);
    if (st || (st = step_save(wd)))
        return st;
    wd->stats.pixels_tested = 0;
    wd->stats.swept_stops = 0;
    wd->stats.threads = 0;
    if ((st = run_substeps(wd, dt, &t_broad, &t_narrow, &t_solver))) {
        step_restore(wd);
        forces_step_undone(wd);
        return st;
    }
    forces_step_done(wd);
    if ((st = joint_step_done(wd)))
        pp_log(1, "physpix: joints past their break force stay until a step has room for their events");
    int32_t awake = 0;
    for (int32_t k = 0; k < wd->awake_count; k++)
        awake += awake_mover(wd->bodies[wd->awake_slots[k]]);
    wd->stats.broadphase_ms = (float)t_broad;
    wd->stats.narrowphase_ms = (float)t_narrow;
    wd->stats.solver_ms = (float)t_solver;
    wd->stats.total_ms = (float)(now_ms() - t_start);
    wd->stats.bodies = wd->body_ids.live;
    wd->stats.awake_bodies = awake;
    wd->time += dt;
    return PP_OK;
}

PP_API pp_status pp_world_set_contact_events(pp_world w, uint32_t enabled)
{
    world *wd = world_lookup(w, "pp_world_set_contact_events");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    /* Off, the pairs recorded for events end silently (touch.c queues no END without it). */
    wd->def.contact_events = enabled != 0;
    return PP_OK;
}

PP_API pp_status pp_world_get_def(pp_world w, pp_world_def *out)
{
    world *wd = world_lookup(w, "pp_world_get_def");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_get_def: out is NULL");
    *out = wd->def;
    return PP_OK;
}

PP_API pp_status pp_world_get_bodies(pp_world w, pp_body *out, int32_t capacity, int32_t *count)
{
    world *wd = world_lookup(w, "pp_world_get_bodies");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    pp_status st = pp_check_out_buffer("pp_world_get_bodies", out, capacity, count);
    if (st)
        return st;
    int32_t n = 0;
    for (int32_t i = 0; i < wd->body_ids.capacity; i++)
        if (wd->bodies[i]) {
            if (n < capacity)
                out[n] = wd->bodies[i]->handle;
            n++;
        }
    *count = n;
    return PP_OK;
}

PP_API pp_status pp_world_get_contacts(pp_world w, pp_contact *out, int32_t capacity, int32_t *count)
{
    world *wd = world_lookup(w, "pp_world_get_contacts");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    pp_status st = pp_check_out_buffer("pp_world_get_contacts", out, capacity, count);
    if (st)
        return st;
    const int32_t n = wd->contact_count < capacity ? wd->contact_count : capacity;
    if (n > 0)
        memcpy(out, wd->contacts, (size_t)n * sizeof *out);
    *count = wd->contact_count;
    return PP_OK;
}

pp_status world_reserve_events(world *wd, int32_t n, const char *fn)
{
    if (!ARRAY_RESERVE(wd->events, wd->event_capacity, wd->event_count + n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d events", fn, (int)(wd->event_count + n));
    return PP_OK;
}

void world_queue_event(world *wd, pp_event ev)
{
    PP_ASSERT(wd->event_count < wd->event_capacity);
    wd->events[wd->event_count++] = ev;
}

PP_API pp_status pp_world_get_events(pp_world w, pp_event *out, int32_t capacity, int32_t *count)
{
    world *wd = world_lookup(w, "pp_world_get_events");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    pp_status st = pp_check_out_buffer("pp_world_get_events", out, capacity, count);
    if (st)
        return st;
    const int32_t n = wd->event_count < capacity ? wd->event_count : capacity;
    if (n > 0) {
        memcpy(out, wd->events, (size_t)n * sizeof *out);
        memmove(wd->events, wd->events + n, (size_t)(wd->event_count - n) * sizeof *out);
    }
    *count = wd->event_count;
    wd->event_count -= n;
    return PP_OK;
}

PP_API pp_status pp_world_get_stats(pp_world w, pp_step_stats *out)
{
    world *wd = world_lookup(w, "pp_world_get_stats");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_get_stats: out is NULL");
    *out = wd->stats;
    return PP_OK;
}

PP_API pp_status pp_world_get_time(pp_world w, double *seconds)
{
    world *wd = world_lookup(w, "pp_world_get_time");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!seconds)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_get_time: seconds is NULL");
    *seconds = wd->time;
    return PP_OK;
}

PP_API pp_status pp_world_get_camera(pp_world w, pp_camera *out)
{
    world *wd = world_lookup(w, "pp_world_get_camera");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_get_camera: out is NULL");
    *out = wd->camera;
    return PP_OK;
}

PP_API pp_status pp_world_set_camera(pp_world w, const pp_camera *c)
{
    static const char *fn = "pp_world_set_camera";
    world *wd = world_lookup(w, fn);
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!c)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: camera is NULL", fn);
    if (!isfinite(c->center.x) || !isfinite(c->center.y) || !(c->zoom > 0) || !isfinite(c->zoom))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: center must be finite and zoom finite and > 0", fn);
    if (c->width < 1 || c->height < 1 || c->width > PP_MAX_BITMAP_SIDE || c->height > PP_MAX_BITMAP_SIDE)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: size %dx%d must be within 1..%d px", fn, (int)c->width,
                       (int)c->height, PP_MAX_BITMAP_SIDE);
    wd->camera = *c;
    return PP_OK;
}

static pp_status check_timed_edit(world *wd, const pp_timed_edit *e)
{
    static const char *fn = "pp_world_schedule_edit";
    if (!isfinite(e->time))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: time must be finite, got %g", fn, e->time);
    if (e->type != PP_EDIT_ERASE_CIRCLE && e->type != PP_EDIT_PAINT_CIRCLE)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: type %d is unknown", fn, (int)e->type);
    if (!isfinite(e->center.x) || !isfinite(e->center.y) || !(e->radius >= 0) || !isfinite(e->radius))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: center must be finite and radius finite and ≥ 0", fn);
    if (e->type == PP_EDIT_PAINT_CIRCLE && (e->weight < 1 || e->weight > 255))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: paint weight must be 1..255, got %u", fn, (unsigned)e->weight);
    if (e->type == PP_EDIT_PAINT_CIRCLE && e->body.id == 0)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: a paint edit needs a body", fn);
    if (e->body.id != 0 && !body_lookup(wd, e->body, fn))
        return PP_ERR_INVALID_HANDLE;
    return PP_OK;
}

PP_API pp_status pp_world_schedule_edit(pp_world w, const pp_timed_edit *edit)
{
    world *wd = world_lookup(w, "pp_world_schedule_edit");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!edit)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_schedule_edit: edit is NULL");
    pp_status st = check_timed_edit(wd, edit);
    if (st)
        return st;
    if (!ARRAY_RESERVE(wd->edits, wd->edit_capacity, wd->edit_count + 1))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_schedule_edit: no memory for %d edits", (int)wd->edit_count + 1);
    edits_push(wd, edit);
    return PP_OK;
}

PP_API pp_status pp_world_get_scheduled_edits(pp_world w, pp_timed_edit *out, int32_t capacity, int32_t *count)
{
    world *wd = world_lookup(w, "pp_world_get_scheduled_edits");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    pp_status st = pp_check_out_buffer("pp_world_get_scheduled_edits", out, capacity, count);
    if (st)
        return st;
    const int32_t n = wd->edit_count < capacity ? wd->edit_count : capacity;
    if (n > 0)
        edits_sort(wd);
    for (int32_t i = 0; i < n; i++)
        out[i] = wd->edits[i].edit;
    *count = wd->edit_count;
    return PP_OK;
}
