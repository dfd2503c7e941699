/* Out of memory anywhere: an allocator (pp_set_allocator) that fails its N-th call, for every N that a
 * scene's set-up and first steps reach. The failing call must return PP_ERR_OUT_OF_MEMORY and leave
 * the worlds as they were; retried, it succeeds, and the script ends in the same state as a run with
 * no failure. */
#include "helpers.h"

#include "handle.h" /* handle_saved: a body's handle without its world */

#include <pthread.h>
#include <stdbool.h>

PP_TEST_SUITE(out_of_memory);

/* ---- an allocator that fails once, on a chosen call ---------------------------------------------- */

/* Only the calling thread may allocate (worker threads get their scratch from it), so the N-th
 * allocation is the same call in every run. */
static struct {
    int64_t calls;   /* allocations so far (alloc and realloc) */
    int64_t fail_at; /* the call that fails; 0 never */
    bool failed;
    bool other_thread; /* an allocation came from a thread other than the test's */
    pthread_t owner;
} alloc_count;

static bool fail_now(void)
{
    if (!pthread_equal(pthread_self(), alloc_count.owner)) {
        __atomic_store_n(&alloc_count.other_thread, true, __ATOMIC_RELAXED);
        return false;
    }
    if (++alloc_count.calls != alloc_count.fail_at)
        return false;
    alloc_count.failed = true;
    return true;
}

static void *failing_alloc(uint64_t size, void *user) { return fail_now() ? NULL : malloc(size); }
static void *failing_realloc(void *ptr, uint64_t size, void *user) { return fail_now() ? NULL : realloc(ptr, size); }
static void failing_free(void *ptr, void *user) { free(ptr); }

/* ---- the script: a scene's set-up and first steps, one API call an op -------------------------- */

enum { MAX_BODIES = 32, CROWD = 20 };

typedef struct script {
    pp_world w, loaded;            /* the scene, and its snapshot loaded back */
    pp_body terrain, block, giant, disc, shelf, bar, crates[4], extra, crowd[CROWD];
    int crowd_count;
    uint8_t *terrain_mask, *terrain_weights, *crate_rgba, *block_mask, *giant_mask, *disc_mask, *shelf_mask, *bar_mask;
    char dir[64], snapshot[96], scene[96], png[96];
    uint8_t *state;                /* pp_world_save_state's bytes (the host's memory, not the library's) */
    int64_t state_size;
} script;

static int32_t body_count(pp_world w)
{
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, NULL, 0, &n));
    return n;
}

static pp_body_def crate_def(const script *s, int k)
{
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 60.0f + 3.0f * k, 20.0f - 17.0f * k, 0.05f * k);
    d.width = d.height = 16;
    d.rgba = s->crate_rgba;
    return d;
}

static pp_status op_create_world(script *s)
{
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_CPU;
    d.worker_threads = 2; /* the giant pair's batch is big enough to start the pool */
    return pp_world_create(&d, &s->w);
}

static pp_status op_terrain(script *s)
{
    pp_body_def d = body_def(PP_BODY_STATIC, 128, 64, 0);
    d.width = 256, d.height = 64;
    d.mask = s->terrain_mask;
    d.weights = s->terrain_weights;
    return pp_body_create(s->w, &d, &s->terrain);
}

static pp_status op_crate(script *s, int k) { pp_body_def d = crate_def(s, k); return pp_body_create(s->w, &d, &s->crates[k]); }
static pp_status op_crate0(script *s) { return op_crate(s, 0); }
static pp_status op_crate1(script *s) { return op_crate(s, 1); }
static pp_status op_crate2(script *s) { return op_crate(s, 2); }
static pp_status op_crate3(script *s) { return op_crate(s, 3); }

/* A crate already touching the terrain: a second pair, so the batch is shared out. */
/* A crate sunk into the block's edge, beside the giant: a second pair in the pool's batch for a few steps. */
static pp_status op_low_crate(script *s)
{
    pp_body_def d = crate_def(s, 0);
    d.position = v2(1880, 200);
    return pp_body_create(s->w, &d, &s->extra);
}

/* One more 8 px box at the crowd's one spot: together they are crowded (the contact budget, crowd.c). */
static pp_status op_crowd(script *s)
{
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 128, 10, 0);
    d.width = d.height = 8;
    d.mask = s->block_mask; /* all solid: its first 64 bytes make the 8 × 8 box */
    const pp_status st = pp_body_create(s->w, &d, &s->crowd[s->crowd_count]);
    s->crowd_count += st == PP_OK;
    return st;
}

static pp_status op_disc(script *s)
{
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 160, 10, 0);
    d.width = d.height = 20;
    d.mask = s->disc_mask;
    d.restitution = 0.5f;
    return pp_body_create(s->w, &d, &s->disc);
}

/* ---- sleepers: a resting stack that a falling crate wakes mid-step ---- */

static pp_status op_create_sleepy_world(script *s)
{
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_CPU;
    d.sleep_time = 0.04f; /* a crate at rest sleeps after three steps */
    return pp_world_create(&d, &s->w);
}

static pp_status op_stack(script *s, int k)
{
    pp_body_def d = crate_def(s, 0);
    d.position = v2(60, 24.0f - 16 * k); /* resting on the terrain's top (y = 32), then on each other */
    d.angle = 0;
    return pp_body_create(s->w, &d, &s->crates[k]);
}
static pp_status op_stack0(script *s) { return op_stack(s, 0); }
static pp_status op_stack1(script *s) { return op_stack(s, 1); }

static int32_t is_awake(const script *s, pp_body b)
{
    int32_t awake = 0;
    PP_OK_OR_FAIL(pp_body_is_awake(s->w, b, &awake));
    return awake;
}

/* A crate thrown down onto the sleeping stack: the top crate wakes in the first substep, and the
 * bottom one, which the broadphase then pairs with it, in a later one. */
static pp_status op_faller(script *s)
{
    cr_assert(!is_awake(s, s->crates[0]) && !is_awake(s, s->crates[1]), "the stack is not asleep");
    pp_body_def d = crate_def(s, 0);
    d.position = v2(60, -9), d.angle = 0, d.linear_velocity = v2(0, 600);
    return pp_body_create(s->w, &d, &s->crates[2]);
}

static pp_status op_step_hit(script *s)
{
    const pp_status st = pp_world_step(s->w, 1.0f / 60);
    if (st == PP_OK)
        cr_assert(is_awake(s, s->crates[0]) && is_awake(s, s->crates[1]), "the falling crate woke %d of 2",
                  is_awake(s, s->crates[0]) + is_awake(s, s->crates[1]));
    else
        cr_assert(!is_awake(s, s->crates[0]) && !is_awake(s, s->crates[1]), "a failed step left the stack awake");
    return st;
}

/* ---- gameplay: contact events, a sensor and a one-way platform that a crate jumps through ---- */

static pp_status op_create_events_world(script *s)
{
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_CPU;
    d.contact_events = 1;
    return pp_world_create(&d, &s->w);
}

/* A thin one-way platform above the terrain, and a sensor zone the crates fall through. */
static pp_status op_platform(script *s)
{
    pp_body_def d = body_def(PP_BODY_STATIC, 60, -40, 0);
    d.width = 64, d.height = 6;
    d.mask = s->block_mask;
    d.one_way = 1;
    return pp_body_create(s->w, &d, &s->block);
}

static pp_status op_sensor(script *s)
{
    pp_body_def d = body_def(PP_BODY_STATIC, 100, 0, 0);
    d.width = 80, d.height = 40;
    d.mask = s->block_mask;
    d.is_sensor = 1;
    return pp_body_create(s->w, &d, &s->giant);
}

/* A crate thrown up through the platform, which it lands on later. */
static pp_status op_jumper(script *s)
{
    pp_body_def d = crate_def(s, 0);
    d.position = v2(30, 20), d.angle = 0, d.linear_velocity = v2(0, -500);
    return pp_body_create(s->w, &d, &s->crates[2]);
}

/* The script did what it is for: the jumper went up into the platform, and events were queued. */
static pp_status op_check_gameplay(script *s)
{
    int32_t events = 0;
    PP_OK_OR_FAIL(pp_world_get_events(s->w, NULL, 0, &events));
    cr_assert_geq(events, 3, "sensor and contact events: %d", events);
    pp_vec2 p;
    PP_OK_OR_FAIL(pp_body_get_position(s->w, s->crates[2], &p));
    cr_assert_lt(p.y, -40.0f, "the jumper is past the platform's middle (y %g)", p.y);
    return PP_OK;
}

/* A static block and a dynamic giant sunk into it, far from the rest: a batch over the pool's threshold. */
static pp_status op_block(script *s)
{
    pp_body_def d = body_def(PP_BODY_STATIC, 2000, 200, 0);
    d.width = d.height = 256;
    d.mask = s->block_mask;
    return pp_body_create(s->w, &d, &s->block);
}

static pp_status op_giant(script *s)
{
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 2000, 190, 0);
    d.width = d.height = 200;
    d.mask = s->giant_mask;
    return pp_body_create(s->w, &d, &s->giant);
}

/* A static shelf whose pieces fall as dynamic bodies when cut (fracture). */
static pp_status op_shelf(script *s)
{
    pp_body_def d = body_def(PP_BODY_STATIC, 400, 60, 0);
    d.width = 64, d.height = 12;
    d.mask = s->shelf_mask;
    d.detach_islands = 1;
    return pp_body_create(s->w, &d, &s->shelf);
}

/* The cut splits the shelf into several pieces (so one piece is made before the next fails), or,
 * when memory runs out, into none. */
static pp_status op_cut_shelf(script *s)
{
    const int32_t before = body_count(s->w);
    const pp_status st = pp_body_erase_circle(s->w, s->shelf, v2(400, 54), 14, NULL);
    if (st == PP_OK)
        cr_assert_geq(body_count(s->w), before + 3, "the cut made %d bodies", body_count(s->w) - before);
    else
        cr_assert_eq(body_count(s->w), before, "a failed cut made %d bodies", body_count(s->w) - before);
    return st;
}

/* A dynamic bar cut in two: a split whose mass sums must come back if it fails. */
static pp_status op_bar(script *s)
{
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 40, -60, 0);
    d.width = 40, d.height = 6;
    d.mask = s->bar_mask;
    return pp_body_create(s->w, &d, &s->bar);
}

static pp_status op_cut_bar(script *s)
{
    const int32_t before = body_count(s->w);
    pp_vec2 p;
    PP_OK_OR_FAIL(pp_body_get_position(s->w, s->bar, &p));
    const pp_status st = pp_body_erase_circle(s->w, s->bar, p, 4, NULL);
    cr_assert_eq(body_count(s->w), before + (st == PP_OK), "the cut made %d bodies", body_count(s->w) - before);
    return st;
}

static pp_status op_schedule(script *s)
{
    const pp_timed_edit e = {.time = 3.0 / 60, .type = PP_EDIT_ERASE_CIRCLE, .center = {100, 40}, .radius = 6};
    return pp_world_schedule_edit(s->w, &e);
}

static pp_status op_step(script *s) { return pp_world_step(s->w, 1.0f / 60); }
static pp_status op_step_loaded(script *s) { return pp_world_step(s->loaded, 1.0f / 60); }
static pp_status op_erase(script *s) { return pp_body_erase_circle(s->w, s->terrain, v2(150, 40), 5, NULL); }
static pp_status op_erase_world(script *s) { return pp_world_erase_circle(s->w, v2(70, 40), 4, NULL); }
/* A blast that cuts the terrain beside a crate and pushes the crates near it. */
static pp_status op_explode(script *s)
{
    pp_explosion_def d = pp_explosion_def_default();
    d.position = v2(110, 40), d.radius = 20, d.falloff = 20, d.impulse_per_length = 2000, d.erase_radius = 5;
    return pp_world_explode(s->w, &d, NULL);
}

/* A crate cast down and a ray across the scene: a failure writes nothing, a success changes nothing. */
static pp_status op_casts(script *s)
{
    pp_raycast_hit h[8];
    int32_t hit = 0, n = 0;
    const pp_status st = pp_world_cast_body(s->w, s->crates[0], v2(0, 60), 0xffffffffu, h, &hit);
    return st ? st : pp_world_raycast_all(s->w, v2(0, 30), v2(300, 30), 0xffffffffu, h, 8, &n);
}

static pp_status op_paint(script *s) { return pp_body_paint_circle(s->w, s->crates[0], v2(60, 20), 4, 128, NULL); }

static pp_status op_collide(script *s)
{
    pp_contact c[4];
    int32_t n = 0;
    return pp_world_collide(s->w, s->crates[0], s->terrain, c, 4, &n);
}

static pp_status op_debug_collision(script *s)
{
    static uint8_t cells[1 << 16];
    pp_collision_view view;
    return pp_world_debug_collision(s->w, s->crates[0], s->terrain, cells, NULL, (int64_t)sizeof cells, &view);
}

/* Builds every body's outline (the edits above changed some): a failure writes nothing. */
static pp_status op_debug_draw(script *s)
{
    static pp_debug_segment segs[4096];
    int32_t n = -1;
    const pp_status st = pp_world_debug_draw(s->w, PP_DEBUG_DRAW_ALL, v2(-1e6f, -1e6f), v2(1e6f, 1e6f), segs, 4096, &n);
    cr_assert(st != PP_OK || (n > 0 && n <= 4096), "%d segments", n);
    cr_assert(st == PP_OK || n == -1, "a failed pp_world_debug_draw wrote count");
    return st;
}

static pp_status op_destroy_crate(script *s) { return pp_body_destroy(s->w, s->crates[3]); }

static pp_status op_extra(script *s)
{
    pp_body_def d = crate_def(s, 3);
    d.position = v2(200, 10);
    return pp_body_create(s->w, &d, &s->extra);
}

/* The whole of a small file, NUL-terminated, or NULL if there is none. */
static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *text = calloc(1, 1 << 20);
    cr_assert(fread(text, 1, (1 << 20) - 1, f) < (1 << 20) - 1);
    fclose(f);
    return text;
}

static int entries(const char *dir)
{
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *e; d && (e = readdir(d));)
        n += e->d_name[0] != '.';
    if (d)
        closedir(d);
    return n;
}

/* A save that fails leaves the previous snapshot as it was, and nothing beside it. */
static pp_status op_save_snapshot(script *s)
{
    char json[160];
    snprintf(json, sizeof json, "%s/world.json", s->snapshot);
    char *before = slurp(json);
    const int files = entries(s->dir);
    const pp_status st = pp_world_save_snapshot(s->w, s->snapshot);
    if (st) {
        char *after = slurp(json);
        cr_assert((!before && !after) || (before && after && strcmp(before, after) == 0),
                  "a failed save changed the snapshot before it");
        cr_assert_eq(entries(s->dir), files, "a failed save left files behind");
        free(after);
    }
    free(before);
    return st;
}
static pp_status op_load_snapshot(script *s) { return pp_world_load_snapshot(s->snapshot, &s->loaded); }

static pp_status op_save_state(script *s)
{
    free(s->state);
    s->state = NULL;
    pp_status st = pp_world_save_state(s->w, NULL, 0, &s->state_size);
    if (st != PP_ERR_LIMIT)
        return st;
    s->state = malloc((size_t)s->state_size);
    return pp_world_save_state(s->w, s->state, s->state_size, &s->state_size);
}
static pp_status op_restore_state(script *s) { return pp_world_restore_state(s->w, s->state, s->state_size); }
static pp_status op_load_state(script *s) { return pp_world_load_state(s->state, s->state_size, &s->loaded); }
static pp_status op_save_png(script *s) { return pp_image_save(s->png, s->crate_rgba, 16, 16); }

static pp_status op_load_png(script *s)
{
    uint8_t px[16 * 16 * 4];
    int32_t w = 0, h = 0;
    return pp_image_load(s->png, px, (int64_t)sizeof px, &w, &h);
}

typedef struct op {
    const char *name;
    pp_status (*run)(script *s);
} op;

#define OP(f) {#f, f}
/* The scene: set-up, steps, every kind of edit, queries, files. */
static const op scene_ops[] = {
    OP(op_create_world), OP(op_terrain), OP(op_crate0), OP(op_crate1), OP(op_crate2), OP(op_crate3),
    OP(op_disc), OP(op_shelf), OP(op_bar), OP(op_schedule), OP(op_step), OP(op_step), OP(op_step), OP(op_step),
    OP(op_step), OP(op_cut_bar),
    OP(op_erase), OP(op_erase_world), OP(op_explode), OP(op_casts), OP(op_paint), OP(op_cut_shelf), OP(op_collide), OP(op_debug_collision),
    OP(op_debug_draw),
    OP(op_destroy_crate), OP(op_extra), OP(op_step), OP(op_step), OP(op_save_png), OP(op_load_png),
    OP(op_save_snapshot), OP(op_load_snapshot), OP(op_step_loaded), OP(op_step_loaded), OP(op_step), OP(op_step),
    OP(op_save_snapshot),
};

/* State in memory: restored in place, and over a crate destroyed and one made since (built apart), then loaded; the
 * 256×256 block is big enough for the world to keep its pixels once and save its changed bands. */
static const op state_ops[] = {
    OP(op_create_world), OP(op_terrain), OP(op_block), OP(op_crate0), OP(op_crate1), OP(op_crate2), OP(op_crate3),
    OP(op_step), OP(op_step), OP(op_step), OP(op_save_state), OP(op_step), OP(op_erase),
    OP(op_step), OP(op_restore_state), OP(op_step), OP(op_destroy_crate), OP(op_extra), OP(op_step),
    OP(op_restore_state), OP(op_step), OP(op_load_state), OP(op_step_loaded), OP(op_step), OP(op_save_snapshot),
};

/* A pair big enough for the narrowphase's worker threads, beside a crate. */
static const op pool_ops[] = {
    OP(op_create_world), OP(op_terrain), OP(op_low_crate), OP(op_block), OP(op_giant), OP(op_step), OP(op_step),
    OP(op_step), OP(op_save_snapshot),
};

/* A stack falls asleep; a thrown crate wakes it in the middle of a step. */
static const op sleeper_ops[] = {
    OP(op_create_sleepy_world), OP(op_terrain), OP(op_stack0), OP(op_stack1), OP(op_step), OP(op_step), OP(op_step),
    OP(op_step), OP(op_step), OP(op_step), OP(op_step), OP(op_step), OP(op_step), OP(op_step), OP(op_step),
    OP(op_step), OP(op_faller), OP(op_step_hit), OP(op_step), OP(op_save_snapshot),
};

/* Contact and sensor events begin and end, a crate passes through a one-way platform mid-script. */
static const op gameplay_ops[] = {
    OP(op_create_events_world), OP(op_terrain), OP(op_platform), OP(op_sensor), OP(op_crate0), OP(op_crate1),
    OP(op_jumper), OP(op_step), OP(op_step), OP(op_step), OP(op_step), OP(op_step), OP(op_step), OP(op_step),
    OP(op_step), OP(op_save_snapshot), OP(op_load_snapshot), OP(op_step_loaded), OP(op_step), OP(op_step),
    OP(op_step), OP(op_step), OP(op_check_gameplay), OP(op_save_snapshot),
};

/* Twenty boxes created at one spot: the two-pass narrowphase and the contact budget of crowded bodies. */
#define OP_CROWD4 OP(op_crowd), OP(op_crowd), OP(op_crowd), OP(op_crowd)
static const op crowd_ops[] = {
    OP(op_create_world), OP(op_terrain), OP_CROWD4, OP_CROWD4, OP_CROWD4, OP_CROWD4, OP_CROWD4,
    OP(op_step), OP(op_step), OP(op_step), OP(op_step), OP(op_save_snapshot),
};

typedef struct script_ops {
    const op *ops;
    int count;
    bool pool; /* the reference run checks that the steps ran on the worker threads */
} script_ops;

enum { MAX_OPS = 64 };

/* ---- the observable state of the script's worlds ---------------------------------------------- */

/* FNV-1a, eight bytes at a time: the masks are most of what is hashed. */
static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const uint8_t *p = data;
    size_t i = 0;
    for (uint64_t word; i + 8 <= n; i += 8) {
        memcpy(&word, p + i, 8);
        h = (h ^ word) * 1099511628211ull;
    }
    for (; i < n; i++)
        h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

/* Every body's handle (slot and generation: its world differs from run to run), pose, velocity, sleep, mass and
 * mask; the contacts, time and pending edits. */
static uint64_t world_hash(uint64_t h, pp_world w)
{
    if (w.id == 0)
        return fnv(h, "none", 4);
    pp_body bodies[MAX_BODIES];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, MAX_BODIES, &n));
    cr_assert(n <= MAX_BODIES);
    h = fnv(h, &n, sizeof n);
    for (int32_t i = 0; i < n; i++) {
        pp_vec2 p, v;
        float a, omega, mass[2];
        pp_vec2 com;
        int32_t awake = 0, bw = 0, bh = 0;
        PP_OK_OR_FAIL(pp_body_get_position(w, bodies[i], &p));
        PP_OK_OR_FAIL(pp_body_get_angle(w, bodies[i], &a));
        PP_OK_OR_FAIL(pp_body_get_velocity(w, bodies[i], &v, &omega));
        PP_OK_OR_FAIL(pp_body_get_mass(w, bodies[i], &mass[0], &com, &mass[1]));
        PP_OK_OR_FAIL(pp_body_is_awake(w, bodies[i], &awake));
        PP_OK_OR_FAIL(pp_body_get_size(w, bodies[i], &bw, &bh));
        uint8_t *mask = malloc((size_t)bw * bh);
        PP_OK_OR_FAIL(pp_body_read_mask(w, bodies[i], mask, (int64_t)bw * bh));
        const uint64_t saved = handle_saved(bodies[i].id);
        h = fnv(h, &saved, sizeof saved);
        h = fnv(h, &p, sizeof p), h = fnv(h, &a, sizeof a), h = fnv(h, &v, sizeof v), h = fnv(h, &omega, sizeof omega);
        h = fnv(h, mass, sizeof mass), h = fnv(h, &com, sizeof com), h = fnv(h, &awake, sizeof awake), h = fnv(h, mask, (size_t)bw * bh);
        free(mask);
    }
    pp_contact contacts[64];
    int32_t nc = 0, ne = 0;
    PP_OK_OR_FAIL(pp_world_get_contacts(w, contacts, 64, &nc));
    for (int32_t i = 0; i < nc && i < 64; i++)
        contacts[i].a.id = handle_saved(contacts[i].a.id), contacts[i].b.id = handle_saved(contacts[i].b.id);
    h = fnv(h, &nc, sizeof nc);
    h = fnv(h, contacts, (size_t)(nc < 64 ? nc : 64) * sizeof *contacts);
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, NULL, 0, &ne));
    int32_t events = 0; /* counted, not read: reading would forget them */
    PP_OK_OR_FAIL(pp_world_get_events(w, NULL, 0, &events));
    h = fnv(h, &events, sizeof events);
    double t = 0;
    PP_OK_OR_FAIL(pp_world_get_time(w, &t));
    return fnv(fnv(h, &ne, sizeof ne), &t, sizeof t);
}

static uint64_t script_hash(const script *s) { return world_hash(world_hash(14695981039346656037ull, s->w), s->loaded); }

static int32_t pending_edits(const script *s)
{
    int32_t n = 0;
    if (s->w.id)
        PP_OK_OR_FAIL(pp_world_get_scheduled_edits(s->w, NULL, 0, &n));
    return n;
}

/* ---- running it ---------------------------------------------------------------------------------- */

static void script_open(script *s)
{
    *s = (script){0};
    /* tmpfs where there is one: the snapshot's fsyncs would otherwise dominate the run. */
    struct stat st;
    snprintf(s->dir, sizeof s->dir, "%s/pp_oom_XXXXXX", stat("/dev/shm", &st) == 0 && S_ISDIR(st.st_mode) ? "/dev/shm" : "/tmp");
    cr_assert_not_null(mkdtemp(s->dir));
    snprintf(s->snapshot, sizeof s->snapshot, "%s/snap", s->dir);
    snprintf(s->png, sizeof s->png, "%s/crate.png", s->dir);
    s->terrain_mask = rect_mask(256, 64);
    s->terrain_weights = malloc(256 * 64);
    for (int i = 0; i < 256 * 64; i++)
        s->terrain_weights[i] = (uint8_t)(100 + i % 100);
    for (int x = 90; x < 110; x++) /* a dip for the timed edit to deepen */
        for (int y = 0; y < 8; y++)
            s->terrain_mask[y * 256 + x] = 0;
    s->crate_rgba = malloc(16 * 16 * 4);
    for (int i = 0; i < 16 * 16; i++)
        memcpy(s->crate_rgba + 4 * i, (uint8_t[4]){(uint8_t)i, 80, 40, 255}, 4);
    s->block_mask = rect_mask(256, 256);
    s->giant_mask = rect_mask(200, 200);
    s->shelf_mask = rect_mask(64, 12); /* three blocks held together by their top two rows */
    for (int y = 2; y < 12; y++)
        for (int x = 20; x < 44; x += 22)
            s->shelf_mask[y * 64 + x] = s->shelf_mask[y * 64 + x + 1] = 0;
    s->bar_mask = rect_mask(40, 6);
    int count = 0;
    s->disc_mask = disc_mask(10, &count);
}

static void script_close(script *s)
{
    if (s->loaded.id)
        PP_OK_OR_FAIL(pp_world_destroy(s->loaded));
    if (s->w.id)
        PP_OK_OR_FAIL(pp_world_destroy(s->w));
    free(s->terrain_mask), free(s->terrain_weights), free(s->crate_rgba);
    free(s->block_mask), free(s->giant_mask), free(s->disc_mask), free(s->shelf_mask), free(s->bar_mask);
    remove_tree(s->dir);
    free(s->state);
}

/* Run every op with the N-th allocation failing (0: none). Returns the allocations made, and, when
 * hashes is given, fills hashes[i] with the state after op i. The world's last snapshot holds what no
 * call shows (creation serials, slot generations, the solver's step count, ODE's exact state): the
 * reference run keeps its world.json in *saved, and every other run must end with the same text. */
static int64_t run_script(const script_ops *so, int64_t fail_at, uint64_t *hashes, const uint64_t *expected,
                          int *failed_op, char **saved)
{
    const op *ops = so->ops;
    script s;
    script_open(&s);
    alloc_count.calls = 0, alloc_count.fail_at = fail_at, alloc_count.failed = false;
    *failed_op = -1;
    for (int i = 0; i < so->count; i++) {
        /* Only the ops are counted and may fail, never the reads that hash the state. */
        const bool armed = !alloc_count.failed;
        const int64_t calls = alloc_count.calls;
        alloc_count.fail_at = 0;
        const uint64_t before = armed ? script_hash(&s) : 0;
        const int32_t edits_before = armed ? pending_edits(&s) : 0;
        alloc_count.calls = calls;
        alloc_count.fail_at = armed ? fail_at : 0;
        pp_status st = ops[i].run(&s);
        const int64_t after = alloc_count.calls;
        alloc_count.fail_at = 0;
        if (armed && alloc_count.failed) {
            *failed_op = i;
            cr_assert_eq(st, PP_ERR_OUT_OF_MEMORY, "allocation %lld fails in %s, which returned %s (%s)",
                         (long long)fail_at, ops[i].name, pp_status_name(st), pp_last_error());
            /* The message names the call the user made, wherever inside it the memory ran out. */
            cr_assert(strncmp(pp_last_error(), "pp_", 3) == 0, "allocation %lld failing in %s: \"%s\" names no call",
                      (long long)fail_at, ops[i].name, pp_last_error());
            /* A step applies its due timed edits first and keeps them: then the edit is the only change. */
            if (pending_edits(&s) == edits_before)
                cr_assert_eq(script_hash(&s), before, "allocation %lld failing in %s changed the world",
                             (long long)fail_at, ops[i].name);
            st = ops[i].run(&s);
        }
        cr_assert_eq(st, PP_OK, "%s with allocation %lld failing -> %s (%s)", ops[i].name, (long long)fail_at,
                     pp_status_name(st), pp_last_error());
        alloc_count.calls = after;
        if (hashes && so->pool && ops[i].run == op_step) {
            pp_step_stats stats;
            PP_OK_OR_FAIL(pp_world_get_stats(s.w, &stats));
            cr_assert_eq(stats.threads, 2, "the narrowphase ran on %d threads", (int)stats.threads);
        }
        if (hashes)
            hashes[i] = script_hash(&s);
        /* Right after the failed call is retried, and at the end. */
        if (expected && (i == *failed_op || i == so->count - 1))
            cr_assert_eq(script_hash(&s), expected[i], "after %s (allocation %lld failed in %s) the state differs",
                         ops[i].name, (long long)fail_at, *failed_op >= 0 ? ops[*failed_op].name : "none");
    }
    char json[160];
    snprintf(json, sizeof json, "%s/world.json", s.snapshot);
    char *text = slurp(json);
    if (!expected)
        *saved = text;
    else {
        cr_assert((!text && !*saved) || (text && *saved && strcmp(text, *saved) == 0),
                  "allocation %lld failing in %s: the last snapshot differs from the reference run's",
                  (long long)fail_at, *failed_op >= 0 ? ops[*failed_op].name : "none");
        free(text);
    }
    const int64_t made = alloc_count.calls;
    script_close(&s);
    return made;
}

/* Fail each allocation of the script in turn; every name in must_fail has an allocation that failed. */
static void fail_each_allocation(const script_ops *so, const char *const *must_fail, int must_count)
{
    const pp_allocator failing = {failing_alloc, failing_realloc, failing_free, NULL};
    PP_OK_OR_FAIL(pp_set_allocator(&failing));
    alloc_count.owner = pthread_self();
    uint64_t reference[MAX_OPS];
    cr_assert_leq(so->count, MAX_OPS);
    int failed_op = -1;
    char *saved = NULL;
    const int64_t total = run_script(so, 0, reference, NULL, &failed_op, &saved);
    cr_assert(!alloc_count.other_thread, "a worker thread allocated");
    int per_op[MAX_OPS] = {0};
    for (int64_t n = 1; n <= total; n++) {
        run_script(so, n, NULL, reference, &failed_op, &saved);
        cr_assert_geq(failed_op, 0, "allocation %lld of %lld was never made", (long long)n, (long long)total);
        per_op[failed_op]++;
    }
    for (int k = 0; k < must_count; k++) {
        int n = 0;
        for (int i = 0; i < so->count; i++)
            n += strcmp(so->ops[i].name, must_fail[k]) == 0 ? per_op[i] : 0;
        cr_assert_gt(n, 0, "no allocation failed inside %s", must_fail[k]);
    }
    cr_log_info("out_of_memory: %lld allocations, each failed in turn", (long long)total);
    free(saved);
    PP_OK_OR_FAIL(pp_set_allocator(NULL));
}

Test(out_of_memory, every_allocation_of_a_scene_can_fail_and_changes_nothing, .timeout = 300)
{
    static const char *const must_fail[] = {"op_create_world", "op_terrain", "op_crate0", "op_step",
                                            "op_paint", "op_cut_shelf", "op_cut_bar", "op_save_snapshot",
                                            "op_load_snapshot",
                                            "op_save_png", "op_load_png"};
    const script_ops so = {scene_ops, (int)(sizeof scene_ops / sizeof *scene_ops), false};
    fail_each_allocation(&so, must_fail, (int)(sizeof must_fail / sizeof *must_fail));
}

Test(out_of_memory, every_allocation_of_the_worker_pool_can_fail_and_changes_nothing, .timeout = 300)
{
    static const char *const must_fail[] = {"op_giant", "op_step"};
    const script_ops so = {pool_ops, (int)(sizeof pool_ops / sizeof *pool_ops), true};
    fail_each_allocation(&so, must_fail, (int)(sizeof must_fail / sizeof *must_fail));
}

Test(out_of_memory, a_step_that_fails_after_waking_sleepers_puts_them_back_to_sleep, .timeout = 300)
{
    static const char *const must_fail[] = {"op_step_hit"};
    const script_ops so = {sleeper_ops, (int)(sizeof sleeper_ops / sizeof *sleeper_ops), false};
    fail_each_allocation(&so, must_fail, (int)(sizeof must_fail / sizeof *must_fail));
}

Test(out_of_memory, every_allocation_of_contact_events_sensors_and_one_way_platforms_can_fail, .timeout = 300)
{
    static const char *const must_fail[] = {"op_step", "op_load_snapshot"};
    const script_ops so = {gameplay_ops, (int)(sizeof gameplay_ops / sizeof *gameplay_ops), false};
    fail_each_allocation(&so, must_fail, (int)(sizeof must_fail / sizeof *must_fail));
}

Test(out_of_memory, every_allocation_of_a_crowded_spawn_can_fail_and_changes_nothing, .timeout = 300)
{
    static const char *const must_fail[] = {"op_crowd", "op_step"};
    const script_ops so = {crowd_ops, (int)(sizeof crowd_ops / sizeof *crowd_ops), false};
    fail_each_allocation(&so, must_fail, (int)(sizeof must_fail / sizeof *must_fail));
}

Test(out_of_memory, every_allocation_of_a_state_restored_or_loaded_can_fail_and_changes_nothing, .timeout = 300)
{
    static const char *const must_fail[] = {"op_save_state", "op_restore_state", "op_load_state"};
    const script_ops so = {state_ops, (int)(sizeof state_ops / sizeof *state_ops), false};
    fail_each_allocation(&so, must_fail, (int)(sizeof must_fail / sizeof *must_fail));
}

Test(out_of_memory, the_allocator_is_set_only_while_no_world_exists)
{
    const pp_allocator failing = {failing_alloc, failing_realloc, failing_free, NULL};
    const pp_allocator half = {failing_alloc, NULL, failing_free, NULL};
    EXPECT_ERR(pp_set_allocator(&half), PP_ERR_INVALID_ARGUMENT, "realloc");
    pp_world w = make_world(0, 0);
    EXPECT_ERR(pp_set_allocator(&failing), PP_ERR_INVALID_ARGUMENT, "worlds exist");
    PP_OK_OR_FAIL(pp_world_destroy(w));
    PP_OK_OR_FAIL(pp_set_allocator(&failing));
    alloc_count.calls = 0, alloc_count.fail_at = 0, alloc_count.owner = pthread_self();
    w = make_world(0, 0);
    cr_assert_gt(alloc_count.calls, 0, "the world was not allocated through the allocator");
    PP_OK_OR_FAIL(pp_world_destroy(w));
    PP_OK_OR_FAIL(pp_set_allocator(NULL));
}

/* A size over a documented limit is refused with PP_ERR_LIMIT before the library allocates anything. */
Test(out_of_memory, limits_are_refused_before_anything_is_allocated, .timeout = 120)
{
    const pp_allocator counting = {failing_alloc, failing_realloc, failing_free, NULL};
    PP_OK_OR_FAIL(pp_set_allocator(&counting));
    alloc_count.owner = pthread_self();
    alloc_count.fail_at = 0;
    pp_world w = make_world(0, 0);

    uint8_t tiny[4] = {1, 1, 1, 1};
    pp_body_def d = body_def(PP_BODY_STATIC, 0, 0, 0);
    d.mask = tiny;
    d.width = PP_MAX_BITMAP_SIDE + 1, d.height = 1;
    pp_body b = {0};
    alloc_count.calls = 0;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_LIMIT, "PP_MAX_BITMAP_SIDE");
    d.width = PP_MAX_BITMAP_SIDE, d.height = PP_MAX_BITMAP_AREA / PP_MAX_BITMAP_SIDE + 1;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_LIMIT, "PP_MAX_BITMAP_AREA");
    cr_assert_eq(alloc_count.calls, 0, "a refused bitmap allocated %lld times", (long long)alloc_count.calls);

    /* PP_MAX_WORLDS: this process holds one world already. */
    static pp_world worlds[PP_MAX_WORLDS];
    const pp_world_def def = pp_world_def_default();
    int32_t n = 0;
    while (n < PP_MAX_WORLDS - 1 && pp_world_create(&def, &worlds[n]) == PP_OK)
        n++;
    cr_assert_eq(n, PP_MAX_WORLDS - 1, "world %d of %d was refused: %s", n + 2, PP_MAX_WORLDS, pp_last_error());
    pp_world extra = {7};
    alloc_count.calls = 0;
    EXPECT_ERR(pp_world_create(&def, &extra), PP_ERR_LIMIT, "PP_MAX_WORLDS");
    cr_assert_eq(alloc_count.calls, 0, "the refused world allocated %lld times", (long long)alloc_count.calls);
    cr_assert_eq(extra.id, 7, "a refused create wrote its out handle");
    for (int32_t i = 0; i < n; i++)
        PP_OK_OR_FAIL(pp_world_destroy(worlds[i]));

    PP_OK_OR_FAIL(pp_world_destroy(w));
    PP_OK_OR_FAIL(pp_set_allocator(NULL));
}
