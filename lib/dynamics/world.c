/* Worlds: the process-wide table, settings (defaults, presets, checks), creation and destruction, and the
 * world's simple getters. The step is step.c's. */
#include "alloc.h"
#include "awake.h"
#include "continuous.h"
#include "forces.h"
#include "island.h"
#include "handle.h"
#include "joint.h"
#include "status.h"
#include "world.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

/* Worlds live in a process-wide table of fixed size, its slots from an id pool; a world id is
 * (kind << 61) | (generation << 32) | (slot + 1) (handle.h). Everything here is read and written under the lock. */
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

world *world_find(uint64_t id)
{
    const uint32_t slot = world_id_slot(id), gen = world_id_gen(id);
    world *wd = NULL;
    worlds_enter();
    if (handle_kind_of(id) == HANDLE_WORLD && id_pool_current(&world_ids, slot, gen))
        wd = worlds[slot];
    pthread_mutex_unlock(&worlds_lock);
    return wd;
}

world *world_lookup(pp_world w, const char *fn)
{
    world *wd = world_find(w.id);
    if (!wd && handle_is_other_kind(w.id, HANDLE_WORLD))
        pp_fail(PP_ERR_INVALID_HANDLE, "%s: %#llx is %s handle, not a world", fn, (unsigned long long)w.id,
                handle_kind_name(w.id));
    else if (!wd)
        pp_fail(PP_ERR_INVALID_HANDLE, "%s: world handle %#llx is null, destroyed or stale", fn,
                (unsigned long long)w.id);
    return wd;
}

world *world_lookup_list(pp_world w, const char *fn, const void *out, int32_t capacity, const int32_t *count,
                         pp_status *st)
{
    world *wd = world_lookup(w, fn);
    *st = wd ? pp_check_out_buffer(fn, out, capacity, count) : PP_ERR_INVALID_HANDLE;
    return *st ? NULL : wd;
}

world *world_lookup_out(pp_world w, const char *fn, const void *out, const char *out_name, pp_status *st)
{
    world *wd = world_lookup(w, fn);
    *st = !wd ? PP_ERR_INVALID_HANDLE : !out ? pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s is NULL", fn, out_name) : PP_OK;
    return *st ? NULL : wd;
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
 * it holds 10-high stacks, not 20. BALANCED's 20 iterations stand bench_stability's arch and 20-row pyramid for
 * 60 s with carried contacts (15 drift more), and 40 cost 1.5 times as much and stand nothing more; its card
 * house, for which 20 were picked, collapses while settling at every preset. One contact point a pair
 * (CENTROID) lets a box tip on a gentle slope, so every preset keeps two. */
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

pp_status world_check_def(const pp_world_def *d, const char *fn)
{
    if (!finite2(d->gravity.x, d->gravity.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: gravity must be finite", fn);
    if (!(hypot(d->gravity.x, d->gravity.y) <= PP_MAX_ACCELERATION))
        return pp_fail(PP_ERR_INVALID_ARGUMENT,
                       "%s: gravity (%g, %g) px/s² is over PP_MAX_ACCELERATION (%g px/s²)", fn, d->gravity.x,
                       d->gravity.y, PP_MAX_ACCELERATION);
    if (d->substeps < 1 || d->substeps > 64)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: substeps must be 1..64, got %d", fn, (int)d->substeps);
    if (d->solver_iterations < 1 || d->solver_iterations > 1000)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: solver_iterations must be 1..1000, got %d", fn,
                       (int)d->solver_iterations);
    if (d->raster_stride != 1 && d->raster_stride != 2 && d->raster_stride != 4)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: raster_stride must be 1, 2 or 4, got %d", fn,
                       (int)d->raster_stride);
    if ((uint32_t)d->normal_method > PP_NORMAL_KERNEL)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: normal_method %d is unknown", fn, (int)d->normal_method);
    if ((uint32_t)d->contact_mode > PP_CONTACT_CENTROID)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: contact_mode %d is unknown", fn, (int)d->contact_mode);
    if ((uint32_t)d->backend > PP_BACKEND_GPU)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: backend %d is unknown", fn, (int)d->backend);
    if (!(d->pixels_per_meter > 0) || !isfinite(d->pixels_per_meter))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: pixels_per_meter must be finite and > 0", fn);
    if (!(d->contact_slop >= 0) || !isfinite(d->contact_slop))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: contact_slop must be finite and ≥ 0", fn);
    if (!(d->contact_erp >= 0 && d->contact_erp <= 1))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: contact_erp must be in 0..1", fn);
    if (!(d->contact_cfm >= 0) || !isfinite(d->contact_cfm))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: contact_cfm must be finite and ≥ 0", fn);
    if (!(d->bounce_threshold >= 0) || !isfinite(d->bounce_threshold))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: bounce_threshold must be finite and ≥ 0", fn);
    if (d->worker_threads < 0 || d->worker_threads > 16)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: worker_threads must be 0 (one per CPU) or 1..16, got %d", fn,
                       (int)d->worker_threads);
    if (d->exact_island_rows < 0 || d->exact_island_rows > PP_MAX_EXACT_ISLAND_ROWS)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: exact_island_rows must be 0..%d, got %d", fn,
                       PP_MAX_EXACT_ISLAND_ROWS, (int)d->exact_island_rows);
    if (!(d->max_correction_speed > 0 && d->max_correction_speed <= PP_MAX_SPEED))
        return pp_fail(PP_ERR_INVALID_ARGUMENT,
                       "%s: max_correction_speed must be > 0 and at most PP_MAX_SPEED (%g px/s), got %g", fn,
                       PP_MAX_SPEED, d->max_correction_speed);
    const struct { const char *name; float v; } sleep[] = {
        {"sleep_linear_speed", d->sleep_linear_speed}, {"sleep_angular_speed", d->sleep_angular_speed},
        {"sleep_time", d->sleep_time},
    };
    for (size_t i = 0; i < sizeof sleep / sizeof *sleep; i++)
        if (!(sleep[i].v >= 0) || !isfinite(sleep[i].v))
            return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s must be finite and ≥ 0, got %g", fn, sleep[i].name,
                           sleep[i].v);
    return PP_OK;
}

PP_API pp_status pp_world_create(const pp_world_def *def, pp_world *out)
{
    if (!def || !out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_create: %s is NULL", def ? "out" : "def");
    world *wd = NULL;
    pp_status st = world_make(def, "pp_world_create", &wd);
    if (!st)
        *out = wd->handle;
    return st;
}

pp_status world_make(const pp_world_def *def, const char *fn, world **out)
{
    if (def->struct_size != sizeof(pp_world_def))
        return pp_fail(PP_ERR_ABI, "%s: def->struct_size is %u, this library expects %u%s", fn,
                       (unsigned)def->struct_size, (unsigned)sizeof(pp_world_def),
                       def->struct_size == 0 ? " (fill the def from pp_world_def_default or a known preset)" : "");
    pp_world_def d = *def;
    apply_count_defaults(&d);
    pp_status st = world_check_def(&d, fn);
    if (st)
        return st;
    /* Refused before anything is allocated; the pool's take below stays the check that counts. */
    if (world_live_count() >= PP_MAX_WORLDS)
        return pp_fail(PP_ERR_LIMIT, "%s: already %d live worlds (PP_MAX_WORLDS)", fn, PP_MAX_WORLDS);
    world *wd = pp_calloc(1, sizeof *wd);
    if (!wd)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory", fn);
    wd->def = d;
    if (d.backend == PP_BACKEND_GPU && (st = gpu_narrow_create(fn, &wd->gpu))) {
        pp_free(wd);
        return st;
    }
    if ((st = solver_create(&d, fn, &wd->solver))) {
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
        return pp_fail(PP_ERR_LIMIT, "%s: already %d live worlds (PP_MAX_WORLDS)", fn, PP_MAX_WORLDS);
    }
    worlds[slot] = wd;
    wd->slot = slot;
    wd->tag = world_tag(slot, world_generations[slot]);
    wd->handle.id = world_id_make(slot, world_generations[slot]);
    pthread_mutex_unlock(&worlds_lock);
    wd->stats.backend = d.backend == PP_BACKEND_GPU ? PP_BACKEND_GPU : PP_BACKEND_CPU;
    *out = wd;
    return PP_OK;
}

PP_API pp_status pp_world_destroy(pp_world w)
{
    world *wd = world_lookup(w, "pp_world_destroy");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    world_free(wd);
    return PP_OK;
}

void body_free(world *wd, body *bd); /* body.c */

/* Every owner frees its own part. */
void world_free(world *wd)
{
    worlds_enter();
    worlds[wd->slot] = NULL;
    id_pool_release(&world_ids, wd->slot);
    pthread_mutex_unlock(&worlds_lock);
    joint_free_all(wd); /* before the bodies: ODE's joints go before what they attach */
    for (int32_t i = 0; i < wd->body_ids.capacity; i++)
        if (wd->bodies[i])
            body_free(wd, wd->bodies[i]);
    pp_free(wd->bodies);
    id_pool_free(&wd->body_ids, pp_free);
    solver_destroy(wd->solver);
    broadphase_free(&wd->broad);
    np_scratch_free(&wd->scratch);
    workers_free(wd->workers);
    gpu_narrow_destroy(wd->gpu);
    events_free(&wd->events);
    timed_edits_free(&wd->edits);
    step_undo_free(&wd->undo);
    carry_free(&wd->carry);
    crowd_free(&wd->crowd);
    awake_free(&wd->awake);
    island_free(&wd->islands);
    continuous_free(&wd->sweeps);
    forces_free(&wd->forced);
    pp_free(wd->batch.pairs);
    pp_free(wd->batch.cores);
    pp_free(wd->batch.results);
    pp_free(wd->batch.candidates);
    pp_free(wd->batch.bodies);
    contact_table_free(&wd->table);
    pp_free(wd->contacts);
    for (int32_t i = 0; i < wd->base_count; i++) {
        const state_base *b = &wd->bases[i];
        pp_free(b->bits), pp_free(b->weights), pp_free(b->rows), pp_free(b->tiles), pp_free(b->sprite);
    }
    pp_free(wd->bases);
    pp_free(wd);
}

pp_status world_slot_array_grow(world *wd, void **items, int32_t *capacity, size_t per_slot, const char *what)
{
    if (!array_reserve(items, capacity, wd->body_ids.capacity, per_slot))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for %s", what);
    return PP_OK;
}

pp_status world_slot_array_grow_zeroed(world *wd, void **items, int32_t *capacity, size_t per_slot, const char *what)
{
    const int32_t had = *capacity;
    const pp_status st = world_slot_array_grow(wd, items, capacity, per_slot, what);
    if (!st)
        memset((char *)*items + (size_t)had * per_slot, 0, (size_t)(*capacity - had) * per_slot);
    return st;
}

WORLD_GETTER(pp_world_get_def, pp_world_def, wd->def)

PP_API pp_status pp_world_get_bodies(pp_world w, pp_body *out, int32_t capacity, int32_t *count)
{
    pp_status st;
    world *wd = world_lookup_list(w, "pp_world_get_bodies", out, capacity, count, &st);
    if (!wd)
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

void world_each_contact(const world *wd, void (*visit)(const pp_contact *c, void *user), void *user)
{
    for (int32_t i = 0; i < wd->contact_count; i++)
        visit(&wd->contacts[i], user);
    for (int32_t i = 0; i < wd->table.count; i++) {
        const contact_record *r = &wd->table.records[i];
        const int32_t points = contact_table_resting_points(wd, r);
        for (int32_t k = 0; k < points; k++)
            visit(&r->points[k], user);
    }
}

typedef struct contact_list {
    pp_contact *out;
    int32_t capacity, total;
} contact_list;

static void list_contact(const pp_contact *c, void *user)
{
    contact_list *l = user;
    if (l->total < l->capacity)
        l->out[l->total] = *c;
    l->total++;
}

PP_API pp_status pp_world_get_contacts(pp_world w, pp_contact *out, int32_t capacity, int32_t *count)
{
    pp_status st;
    world *wd = world_lookup_list(w, "pp_world_get_contacts", out, capacity, count, &st);
    if (!wd)
        return st;
    contact_list l = {out, capacity, 0};
    world_each_contact(wd, list_contact, &l);
    *count = l.total;
    return PP_OK;
}

WORLD_GETTER(pp_world_get_stats, pp_step_stats, wd->stats)

PP_API pp_status pp_world_get_time(pp_world w, double *seconds)
{
    pp_status st;
    world *wd = world_lookup_out(w, "pp_world_get_time", seconds, "seconds", &st);
    if (!wd)
        return st;
    *seconds = wd->time;
    return PP_OK;
}
