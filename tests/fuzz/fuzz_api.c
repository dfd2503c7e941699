/* libFuzzer target: the API as a sequence of calls. Each input byte stream is read as operations on a few
 * worlds and bodies: creating and destroying them, edits, pixels, poses, impulses, timed edits, steps, every
 * read-out, pair queries, snapshots, joints and the runtime setters — with stale, zero and random handles, NULL out-pointers, NaN and
 * infinite floats, sizes past the limits and capacities that do not match. Every status is checked, and the
 * invariants that hold whatever the arguments (a refused create adds no body, a destroyed handle is refused
 * with PP_ERR_INVALID_HANDLE). An op can make a later allocation fail (pp_set_allocator): the call must then
 * return PP_ERR_OUT_OF_MEMORY and change nothing the harness can see. Everything is destroyed at the end of each
 * input. */
#include "fuzz_common.h"

#include <math.h>
#include <stddef.h>

/* Harness caps that keep one input cheap; out-of-range values still go through on the rare paths. */
#define MAX_WORLDS 3
#define MAX_BODIES 12   /* tracked per world, live or stale */
#define MAX_SIDE 32     /* bitmap side on the common path */
#define MAX_STEPS 12    /* steps per input */
#define MAX_SNAPSHOTS 2 /* snapshot save+load per input */
#define MAX_JOINTS 8    /* tracked per world, live or stale */

typedef struct reader {
    const uint8_t *p;
    size_t n;
} reader;

static uint8_t u8(reader *r)
{
    if (!r->n)
        return 0;
    r->n--;
    return *r->p++;
}

static uint32_t u32(reader *r)
{
    uint32_t v = 0;
    for (int i = 0; i < 4; i++)
        v = v << 8 | u8(r);
    return v;
}

/* A float: mostly small and ordinary, sometimes NaN, ±inf, huge, -0 or any bit pattern. */
static float f32(reader *r, float scale)
{
    const uint8_t k = u8(r);
    switch (k) {
    case 0: return NAN;
    case 1: return INFINITY;
    case 2: return -INFINITY;
    case 3: return 1e30f;
    case 4: return -0.0f;
    case 5: {
        const uint32_t bits = u32(r);
        float f;
        memcpy(&f, &bits, sizeof f);
        return f;
    }
    default: return (float)(int8_t)u8(r) * scale / 128.0f + (float)(k & 7) * scale / 16.0f;
    }
}

typedef struct tracked_world {
    pp_world w;
    int live;
    int32_t body_count; /* as the harness counts: creates minus destroys (edits may destroy more) */
    pp_body bodies[MAX_BODIES];
    int body_live[MAX_BODIES]; /* 1: created and not destroyed by the harness; 0: destroyed, a stale handle */
    int nbodies;
    pp_joint joints[MAX_JOINTS]; /* every joint the harness made (a body's destroy or an edit may end it) */
    int njoints;
} tracked_world;

static tracked_world worlds[MAX_WORLDS];
static pp_world stale_worlds[8];
static int nstale_worlds;
static int steps, snapshots;
static char snap_dir[300];
static uint8_t *plane; /* MAX_SIDE² × 4 bytes of pixels for creates and writes */

/* Allocation failures on demand: op_fail_soon makes the k-th allocation from now fail, once. */
static int64_t fail_countdown;
static int injected; /* an allocation failed during the current op */

static void *fail_soon_alloc(uint64_t size, void *user)
{
    if (fail_countdown > 0 && --fail_countdown == 0) {
        injected = 1;
        return NULL;
    }
    return malloc(size);
}

static void *fail_soon_realloc(void *ptr, uint64_t size, void *user)
{
    if (fail_countdown > 0 && --fail_countdown == 0) {
        injected = 1;
        return NULL;
    }
    return realloc(ptr, size);
}

static void fail_soon_free(void *ptr, void *user) { free(ptr); }

static void op_fail_soon(reader *r) { fail_countdown = 1 + u8(r) % 64; }

/* The call ran out of memory because op_fail_soon made it. */
#define INJECTED_OOM(st) (injected && (st) == PP_ERR_OUT_OF_MEMORY)

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    fuzz_no_gpu();
    static const pp_allocator failing = {fail_soon_alloc, fail_soon_realloc, fail_soon_free, NULL};
    if (pp_set_allocator(&failing) != PP_OK)
        abort();
    snprintf(snap_dir, sizeof snap_dir, "%s/snap", fuzz_scratch());
    return 0;
}

static int32_t count_bodies(pp_world w)
{
    int32_t n = -1;
    FUZZ_CHECK(ST(pp_world_get_bodies(w, NULL, 0, &n)) == PP_OK && n >= 0, "count");
    return n;
}

/* A world handle: mostly a tracked one (live or not), sometimes stale, zero or random. */
static pp_world pick_world(reader *r, tracked_world **t)
{
    const uint8_t k = u8(r);
    *t = NULL;
    if (k < 200) {
        tracked_world *tw = &worlds[k % MAX_WORLDS];
        if (tw->live)
            *t = tw;
        return tw->w;
    }
    if (k < 230 && nstale_worlds)
        return stale_worlds[k % nstale_worlds];
    if (k < 245)
        return (pp_world){0};
    return (pp_world){(uint64_t)u32(r) << 32 | u32(r)};
}

/* A body handle of world t: mostly one it made (maybe destroyed), sometimes another world's (which t must
 * refuse), zero or random. *stale tells whether t must refuse it. */
static pp_body pick_body(reader *r, tracked_world *t, int *stale)
{
    const uint8_t k = u8(r);
    *stale = 0;
    if (t && t->nbodies && k < 210) {
        const int i = k % t->nbodies;
        *stale = !t->body_live[i];
        return t->bodies[i];
    }
    const tracked_world *o = &worlds[k % MAX_WORLDS]; /* live: its slot is not t's */
    if (k < 220 && o != t && o->live && o->nbodies) {
        *stale = 1;
        return o->bodies[k % o->nbodies];
    }
    if (k < 240)
        return (pp_body){0};
    return (pp_body){(uint64_t)u32(r) << 32 | u32(r)};
}

/* A call that got a stale or zero handle of a live world, or a world that is not live, must say so. */
static void expect_handle_refused(pp_status st, int refused, const char *call)
{
    if (refused)
        FUZZ_CHECK(st == PP_ERR_INVALID_HANDLE || st == PP_ERR_INVALID_ARGUMENT, "%s on a stale handle: %d", call,
                   (int)st);
}

static void fill_plane(reader *r, int32_t w, int32_t h)
{
    const uint8_t pattern = u8(r) % 4;
    const uint8_t seed = u8(r);
    for (int32_t i = 0; i < w * h * 4; i++)
        plane[i] = pattern == 0 ? 255 : pattern == 1 ? (uint8_t)((i / 4 + seed) % 3 ? 255 : 0)
                 : pattern == 2 ? 0 : (uint8_t)(i * 31 + seed);
}

static void op_world_create(reader *r)
{
    tracked_world *t = &worlds[u8(r) % MAX_WORLDS];
    if (t->live)
        return;
    pp_world_def d = pp_world_def_default();
    const uint8_t k = u8(r);
    if (k < 20)
        d = pp_world_def_preset((pp_preset)(k % 5));
    d.contact_events = k & 1;
    if (u8(r) < 40) { /* one field set to a fuzzed value */
        switch (u8(r) % 13) {
        case 0: d.substeps = (int32_t)(int8_t)u8(r); break;
        case 1: d.solver_iterations = (int32_t)(int16_t)(u8(r) << 4); break;
        case 2: d.raster_stride = (int32_t)(int8_t)u8(r); break;
        case 3: d.pixels_per_meter = f32(r, 200); break;
        case 4: d.contact_erp = f32(r, 1); break;
        case 5: d.gravity = (pp_vec2){f32(r, 1000), f32(r, 1000)}; break;
        case 6: d.worker_threads = (int32_t)(int8_t)u8(r); break;
        case 7: d.normal_method = (pp_normal_method)(u8(r) % 3); break;
        case 8: d.contact_mode = (pp_contact_mode)(u8(r) % 3); break;
        case 9: d.max_correction_speed = f32(r, 500); break;
        case 10: d.struct_size = u32(r); break;
        case 11: d.exact_island_rows = (int32_t)u8(r) * 8 - 8; break; /* -8..2032: the ends refused */
        default: d.exact_solver = 1, d.allow_sleep = u8(r) & 1, d.continuous = u8(r) & 1; break;
        }
    }
    if (d.substeps > 8)
        d.substeps = 8; /* harness cap: step cost */
    if (d.solver_iterations > 100)
        d.solver_iterations = 100;
    if (d.backend != PP_BACKEND_CPU)
        d.backend = PP_BACKEND_CPU; /* never the GPU while fuzzing */
    if (d.worker_threads == 0 || d.worker_threads > 2)
        d.worker_threads = 1 + (u8(r) & 1);
    const int null_out = u8(r) < 8;
    pp_world w = {0};
    const pp_status st = ST(pp_world_create(&d, null_out ? NULL : &w));
    if (null_out) {
        FUZZ_CHECK(st == PP_ERR_INVALID_ARGUMENT, "create with NULL out: %d", (int)st);
        return;
    }
    FUZZ_CHECK(st != PP_ERR_INVALID_HANDLE, "create: %d", (int)st);
    if (st != PP_OK)
        return;
    FUZZ_CHECK(w.id != 0, "a created world has id 0");
    memset(t, 0, sizeof *t);
    t->w = w, t->live = 1;
    FUZZ_CHECK(count_bodies(w) == 0, "a new world has bodies");
}

static void op_world_destroy(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    const pp_status st = ST(pp_world_destroy(w));
    if (t) {
        FUZZ_CHECK(st == PP_OK, "destroy a live world: %d", (int)st);
        t->live = 0;
        if (nstale_worlds < 8)
            stale_worlds[nstale_worlds++] = w;
        pp_step_stats s;
        FUZZ_CHECK(ST(pp_world_get_stats(w, &s)) == PP_ERR_INVALID_HANDLE, "a destroyed world answers");
        FUZZ_CHECK(ST(pp_world_destroy(w)) == PP_ERR_INVALID_HANDLE, "destroyed twice");
    } else if (w.id == 0) {
        FUZZ_CHECK(st == PP_ERR_INVALID_HANDLE, "destroy of the zero world: %d", (int)st);
    }
}

static void op_body_create(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    pp_body_def d = pp_body_def_default();
    const uint8_t size_kind = u8(r);
    int32_t bw = 1 + u8(r) % MAX_SIDE, bh = 1 + u8(r) % MAX_SIDE;
    int in_range = 1;
    if (size_kind >= 240) { /* out of range: zero, negative, over the side or area limit */
        static const int32_t odd[] = {0, -1, -16384, PP_MAX_BITMAP_SIDE + 1, INT32_MAX, INT32_MIN, 100000, 8193};
        bw = odd[u8(r) % 8];
        if (size_kind & 1)
            bh = odd[u8(r) % 8];
        if (bw == 8193 && bh <= MAX_SIDE)
            bh = 8192; /* both sides in range, area over PP_MAX_BITMAP_AREA */
        in_range = 0;
    }
    d.width = bw, d.height = bh;
    d.type = (pp_body_type)(u8(r) % 4); /* 3 is no type */
    d.position = (pp_vec2){f32(r, 300), f32(r, 300)};
    const uint8_t extra = u8(r);
    if (extra & 1)
        d.angle = f32(r, 4);
    if (extra & 2)
        d.linear_velocity = (pp_vec2){f32(r, 500), f32(r, 500)};
    if (extra & 4)
        d.density = f32(r, 4), d.friction = f32(r, 2), d.restitution = f32(r, 1);
    if (extra & 8)
        d.custom_pivot = 1, d.pivot = (pp_vec2){f32(r, 40), f32(r, 40)};
    if (extra & 16)
        d.category_bits = u32(r), d.mask_bits = u32(r);
    d.fixed_rotation = (extra >> 5) & 1;
    d.bullet = (extra >> 6) & 1;
    d.detach_islands = extra >> 7;
    d.alpha_threshold = u8(r);
    const uint8_t play = u8(r); /* sensors and one-way platforms */
    d.is_sensor = play & 1, d.one_way = (play >> 1) & 1;
    if (play & 4)
        d.one_way_direction = (pp_vec2){f32(r, 2), f32(r, 2)};
    const uint8_t planes = u8(r);
    uint8_t *buf = NULL;
    if (in_range) {
        fill_plane(r, bw, bh);
        const size_t n = (size_t)bw * bh;
        /* Exactly sized buffers, so that a read past a plane is a heap overflow ASan reports. */
        buf = malloc(n * 6);
        memcpy(buf, plane, n * 4);
        memcpy(buf + n * 4, plane, n);
        memcpy(buf + n * 5, plane + n, n);
        if (planes & 1)
            d.rgba = buf;
        if (planes & 2)
            d.mask = buf + n * 4;
        if (planes & 4)
            d.weights = buf + n * 5;
    } else if (planes & 1) {
        d.mask = plane; /* a plane far smaller than the size claims: the library must refuse before reading */
    }
    if (planes & 8)
        d.struct_size = planes & 16 ? 0 : sizeof d + 4;
    const int null_out = (planes >> 5) == 7;
    const int32_t before = t ? count_bodies(w) : 0;
    pp_body b = {0};
    const pp_status st = ST(pp_body_create(w, (planes >> 5) == 6 ? NULL : &d, null_out ? NULL : &b));
    free(buf);
    if (!t) {
        if (w.id == 0)
            FUZZ_CHECK(st == PP_ERR_INVALID_HANDLE, "create on the zero world: %d", (int)st);
        FUZZ_CHECK(st != PP_OK || w.id != 0, "create on a dead world");
        if (st == PP_OK) { /* a random id that happened to name a live world: undo */
            for (int i = 0; i < MAX_WORLDS; i++)
                if (worlds[i].live && worlds[i].w.id == w.id)
                    FUZZ_CHECK(0, "untracked handle names a tracked world");
            ST(pp_body_destroy(w, b));
        }
        return;
    }
    if (!in_range)
        FUZZ_CHECK(st == PP_ERR_INVALID_ARGUMENT || st == PP_ERR_LIMIT || st == PP_ERR_ABI || st == PP_ERR_INVALID_ARGUMENT,
                   "create %dx%d: %d", (int)bw, (int)bh, (int)st);
    if (!in_range && st != PP_ERR_ABI && st != PP_ERR_INVALID_ARGUMENT)
        FUZZ_CHECK(st == PP_ERR_LIMIT && (bw > PP_MAX_BITMAP_SIDE || bh > PP_MAX_BITMAP_SIDE ||
                                          (int64_t)bw * bh > PP_MAX_BITMAP_AREA),
                   "create %dx%d: %d", (int)bw, (int)bh, (int)st);
    if (null_out || (planes >> 5) == 6)
        FUZZ_CHECK(st == PP_ERR_INVALID_ARGUMENT, "create with NULL def or out: %d", (int)st);
    const int32_t after = count_bodies(w);
    if (st != PP_OK) {
        FUZZ_CHECK(after == before, "a refused create (%d) changed the body count %d -> %d", (int)st, (int)before,
                   (int)after);
        return;
    }
    FUZZ_CHECK(after == before + 1, "a create changed the body count %d -> %d", (int)before, (int)after);
    int32_t gw = 0, gh = 0;
    FUZZ_CHECK(ST(pp_body_get_size(w, b, &gw, &gh)) == PP_OK && gw == bw && gh == bh, "size");
    if (t->nbodies < MAX_BODIES) {
        t->bodies[t->nbodies] = b;
        t->body_live[t->nbodies++] = 1;
    } else {
        FUZZ_CHECK(ST(pp_body_destroy(w, b)) == PP_OK, "destroy an untracked body");
    }
}

static void op_body_destroy(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    int stale;
    const pp_body b = pick_body(r, t, &stale);
    const pp_status st = ST(pp_body_destroy(w, b));
    if (!t || b.id == 0 || stale)
        FUZZ_CHECK(st == PP_ERR_INVALID_HANDLE, "destroy of a stale body or in a dead world: %d", (int)st);
    if (st == PP_OK && t) {
        for (int i = 0; i < t->nbodies; i++)
            if (t->bodies[i].id == b.id)
                t->body_live[i] = 0;
        pp_vec2 p;
        FUZZ_CHECK(ST(pp_body_get_position(w, b, &p)) == PP_ERR_INVALID_HANDLE, "a destroyed body answers");
    }
}

static void op_edit(reader *r, int kind)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    int stale;
    const pp_body b = pick_body(r, t, &stale);
    const pp_vec2 c = {f32(r, 300), f32(r, 300)};
    const float radius = f32(r, 24);
    int32_t changed = -1;
    int32_t *changed_p = u8(r) < 32 ? NULL : &changed;
    pp_status st;
    if (kind == 0)
        st = ST(pp_world_erase_circle(w, c, radius, changed_p));
    else if (kind == 1)
        st = ST(pp_body_erase_circle(w, b, c, radius, changed_p));
    else
        st = ST(pp_body_paint_circle(w, b, c, radius, u8(r), changed_p));
    expect_handle_refused(st, !t || (kind && (b.id == 0 || stale)), "edit");
    if (st == PP_OK && changed_p)
        FUZZ_CHECK(changed >= 0, "changed %d", (int)changed);
    if (st != PP_OK && (!isfinite(c.x) || !isfinite(c.y) || !isfinite(radius)))
        FUZZ_CHECK(st == PP_ERR_INVALID_ARGUMENT || st == PP_ERR_INVALID_HANDLE, "edit with NaN: %d", (int)st);
    if (st == PP_OK)
        FUZZ_CHECK(isfinite(c.x) && isfinite(c.y) && isfinite(radius) && radius >= 0, "edit accepted a bad circle");
}

static void op_write_pixels(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    int stale;
    const pp_body b = pick_body(r, t, &stale);
    int32_t x = (int8_t)u8(r), y = (int8_t)u8(r);
    int32_t ww = u8(r) % (MAX_SIDE + 1), hh = u8(r) % (MAX_SIDE + 1);
    const uint8_t k = u8(r);
    if (k >= 250) { /* far out: any origin, a negative width (a larger one would promise more bytes than the plane) */
        x = (int32_t)u32(r), y = (int32_t)u32(r);
        if (k & 1)
            ww = -ww;
    }
    fill_plane(r, MAX_SIDE, MAX_SIDE);
    const int in_buf = ww >= 0 && hh >= 0 && ww <= MAX_SIDE && hh <= MAX_SIDE;
    const pp_status st = ST(pp_body_write_pixels(w, b, x, y, ww, hh, k < 8 ? NULL : plane,
                                                 (k & 16) ? plane + MAX_SIDE * MAX_SIDE : NULL));
    expect_handle_refused(st, !t || b.id == 0 || stale, "write_pixels");
    if (!in_buf)
        FUZZ_CHECK(st != PP_OK || (int64_t)ww * hh == 0, "write of %dx%d accepted", (int)ww, (int)hh);
}

static void op_motion(reader *r, int kind)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    int stale;
    const pp_body b = pick_body(r, t, &stale);
    const pp_vec2 v = {f32(r, 400), f32(r, 400)};
    const float a = f32(r, 6);
    pp_status st;
    int finite = isfinite(v.x) && isfinite(v.y) && isfinite(a);
    if (kind == 0) {
        st = ST(pp_body_set_transform(w, b, v, a));
    } else if (kind == 1) {
        st = ST(pp_body_set_velocity(w, b, v, a));
    } else {
        const pp_vec2 at = {f32(r, 300), f32(r, 300)};
        finite = isfinite(v.x) && isfinite(v.y) && isfinite(at.x) && isfinite(at.y);
        st = ST(pp_body_apply_impulse(w, b, v, at));
    }
    expect_handle_refused(st, !t || b.id == 0 || stale, "motion");
    if (!finite)
        FUZZ_CHECK(st != PP_OK, "non-finite motion (%d) accepted", kind);
}

static void op_schedule(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    int stale;
    pp_timed_edit e = {0};
    e.body = pick_body(r, t, &stale);
    const uint8_t k = u8(r);
    e.time = k < 8 ? NAN : k < 16 ? -1.0 : (double)(k % 64) / 32.0;
    e.type = (pp_edit_type)(u8(r) % 4);
    e.weight = u8(r);
    e.center = (pp_vec2){f32(r, 300), f32(r, 300)};
    e.radius = f32(r, 24);
    e.reserved = u8(r) < 8;
    const pp_status st = ST(pp_world_schedule_edit(w, u8(r) < 8 ? NULL : &e));
    if (!t)
        FUZZ_CHECK(st == PP_ERR_INVALID_HANDLE, "schedule on a dead world: %d", (int)st);
    if (!isfinite(e.time) || !isfinite(e.radius) || !isfinite(e.center.x) || !isfinite(e.center.y))
        FUZZ_CHECK(st != PP_OK, "schedule of a non-finite edit accepted");
    int32_t n = -1;
    pp_timed_edit out[2];
    const pp_status g = ST(pp_world_get_scheduled_edits(w, out, (int32_t)(u8(r) % 4) - 1, &n));
    if (g == PP_OK)
        FUZZ_CHECK(n >= 0, "scheduled count %d", (int)n);
}

static void op_step(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    const uint8_t k = u8(r);
    static const float odd[] = {NAN, INFINITY, -INFINITY, 0.0f, -0.0f, -1.0f / 60, 1.0001f, 1e30f, 1e-30f, 1.0f};
    const float dt = k < 200 ? 1.0f / 60 * (1 + k % 4) : odd[k % 10];
    if ((steps >= MAX_STEPS || (t && fuzz_too_fast(w))) && dt > 0 && dt <= 1)
        return;
    steps++;
    const int32_t before = t ? count_bodies(w) : 0;
    double time_before = 0, time_after = 0;
    if (t)
        pp_world_get_time(w, &time_before);
    const pp_status st = ST(pp_world_step(w, dt));
    if (!t)
        FUZZ_CHECK(st == PP_ERR_INVALID_HANDLE, "step of a dead world: %d", (int)st);
    else if (!(dt > 0 && dt <= 1 && isfinite(dt)))
        FUZZ_CHECK(st == PP_ERR_INVALID_ARGUMENT, "step with dt %g: %d", dt, (int)st);
    else if (injected && st == PP_ERR_OUT_OF_MEMORY) { /* the step was not taken */
        pp_world_get_time(w, &time_after);
        FUZZ_CHECK(time_after == time_before, "a step that ran out of memory moved the clock");
    } else if (st == PP_ERR_LIMIT) { /* a body past a float: the step was not taken */
        pp_world_get_time(w, &time_after);
        FUZZ_CHECK(time_after == time_before, "a step refused at the limits moved the clock");
    } else
        FUZZ_CHECK(st == PP_OK, "step: %d", (int)st);
    if (t && st == PP_OK) {
        pp_step_stats s;
        FUZZ_CHECK(ST(pp_world_get_stats(w, &s)) == PP_OK, "stats");
        FUZZ_CHECK(s.bodies == count_bodies(w), "stats says %d bodies, get_bodies %d", (int)s.bodies,
                   (int)count_bodies(w));
        FUZZ_CHECK(s.awake_bodies >= 0 && s.awake_bodies <= s.bodies, "awake %d of %d", (int)s.awake_bodies,
                   (int)s.bodies);
        (void)before;
    }
}

static void op_reads(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    const uint8_t k = u8(r);
    int32_t cap = (int32_t)(int8_t)u8(r) % 8, n = -1;
    const int null_buf = k & 1, null_count = (k & 6) == 6;
    static pp_body bodies[8];
    static pp_contact contacts[8];
    static pp_event events[8];
    pp_status st;
    switch ((k >> 3) % 6) {
    case 0: st = ST(pp_world_get_bodies(w, null_buf ? NULL : bodies, cap, null_count ? NULL : &n)); break;
    case 1: st = ST(pp_world_get_contacts(w, null_buf ? NULL : contacts, cap, null_count ? NULL : &n)); break;
    case 2: st = ST(pp_world_get_events(w, null_buf ? NULL : events, cap, null_count ? NULL : &n)); break;
    case 3: {
        pp_step_stats s;
        st = ST(pp_world_get_stats(w, null_count ? NULL : &s));
        break;
    }
    case 4: {
        double time;
        pp_world_def d;
        st = ST(pp_world_get_time(w, null_count ? NULL : &time));
        ST(pp_world_get_def(w, null_buf ? NULL : &d));
        break;
    }
    default: {
        pp_camera c;
        st = ST(pp_world_get_camera(w, &c));
        if (st == PP_OK) {
            c.zoom = f32(r, 4), c.width = (int32_t)(int16_t)u32(r), c.height = 1 + u8(r);
            ST(pp_world_set_camera(w, null_buf ? NULL : &c));
        }
        break;
    }
    }
    if (!t)
        FUZZ_CHECK(st == PP_ERR_INVALID_HANDLE || st == PP_ERR_INVALID_ARGUMENT, "read of a dead world: %d", (int)st);
    if (t && st == PP_OK && (k >> 3) % 6 < 3) {
        FUZZ_CHECK(n >= 0, "count %d", (int)n);
        FUZZ_CHECK(cap >= 0, "negative capacity %d accepted", (int)cap);
        FUZZ_CHECK(!null_count, "NULL count accepted");
    }
}

static void op_body_reads(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    int stale;
    const pp_body b = pick_body(r, t, &stale);
    const uint8_t k = u8(r);
    const int null_out = (k & 7) == 0;
    pp_status st;
    switch ((k >> 3) % 12) {
    case 0: { pp_vec2 p; st = ST(pp_body_get_position(w, b, null_out ? NULL : &p)); break; }
    case 1: { float a; st = ST(pp_body_get_angle(w, b, null_out ? NULL : &a)); break; }
    case 2: { pp_vec2 v; float a; st = ST(pp_body_get_velocity(w, b, null_out ? NULL : &v, &a)); break; }
    case 3: { float m, i; pp_vec2 c; st = ST(pp_body_get_mass(w, b, &m, null_out ? NULL : &c, &i)); break; }
    case 4: { int64_t cb, sb; st = ST(pp_body_get_memory(w, b, &cb, null_out ? NULL : &sb)); break; }
    case 5: { int32_t a; st = ST(pp_body_is_awake(w, b, null_out ? NULL : &a)); break; }
    case 6: { uint64_t u; st = ST(pp_body_get_user_data(w, b, null_out ? NULL : &u)); break; }
    case 7: { pp_vec2 p; st = ST(pp_body_get_pivot(w, b, null_out ? NULL : &p)); break; }
    case 8: { pp_body_type ty; st = ST(pp_body_get_type(w, b, null_out ? NULL : &ty)); break; }
    default: {
        int32_t bw = 0, bh = 0;
        st = ST(pp_body_get_size(w, b, &bw, &bh));
        int64_t need = st == PP_OK ? (int64_t)bw * bh : 16;
        const int rgba = (k >> 3) % 12 >= 10, weights = (k >> 3) == 21; /* 21 % 12 = 9: half the mask reads */
        if (rgba)
            need *= 4;
        const int64_t cap = need - (int64_t)(u8(r) % 3) + 1; /* short by one, exact, one over */
        uint8_t *out = malloc((size_t)(cap > 0 ? cap : 1));
        st = rgba      ? ST(pp_body_read_rgba(w, b, null_out ? NULL : out, cap))
             : weights ? ST(pp_body_read_weights(w, b, null_out ? NULL : out, cap))
                       : ST(pp_body_read_mask(w, b, null_out ? NULL : out, cap));
        if (t && !stale && b.id && cap < need)
            FUZZ_CHECK(st != PP_OK, "read with capacity %lld < %lld accepted", (long long)cap, (long long)need);
        free(out);
        break;
    }
    }
    expect_handle_refused(st, !t || b.id == 0 || stale, "body read");
    if (null_out && (k >> 3) % 12 != 2 && (k >> 3) % 12 != 3 && (k >> 3) % 12 != 4)
        FUZZ_CHECK(st != PP_OK, "NULL out accepted (%d)", (k >> 3) % 12);
}

static void op_collide(reader *r, int debug)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    int s1, s2;
    const pp_body a = pick_body(r, t, &s1), b = pick_body(r, t, &s2);
    const int32_t cap = (int32_t)(int8_t)u8(r) % 6;
    pp_status st;
    if (!debug) {
        pp_contact c[6];
        int32_t n = -1;
        st = ST(pp_world_collide(w, a, b, u8(r) < 16 ? NULL : c, cap, &n));
        if (st == PP_OK)
            FUZZ_CHECK(n >= 0, "count %d", (int)n);
    } else {
        pp_collision_view v;
        st = ST(pp_world_debug_collision(w, a, b, NULL, NULL, 0, &v));
        if ((st == PP_OK || st == PP_ERR_INVALID_ARGUMENT) && v.width >= 0 && v.height >= 0 &&
            (int64_t)v.width * v.height <= 256 * 256 && u8(r) & 1) {
            const int64_t cells = (int64_t)v.width * v.height;
            uint8_t *cell = malloc((size_t)cells + 1);
            pp_vec2 *normals = malloc(((size_t)cells + 1) * sizeof *normals);
            const int64_t capc = cells - (u8(r) % 2);
            st = ST(pp_world_debug_collision(w, a, b, cell, u8(r) & 1 ? normals : NULL, capc, &v));
            free(cell);
            free(normals);
        }
    }
    expect_handle_refused(st, !t || a.id == 0 || b.id == 0 || s1 || s2, "collide");
}

static void op_snapshot(reader *r)
{
    if (snapshots >= MAX_SNAPSHOTS)
        return;
    snapshots++;
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    fuzz_rm_tree(snap_dir);
    const pp_status st = ST(pp_world_save_snapshot(w, u8(r) < 8 ? NULL : snap_dir));
    if (!t)
        FUZZ_CHECK(st == PP_ERR_INVALID_HANDLE || st == PP_ERR_INVALID_ARGUMENT, "save of a dead world: %d", (int)st);
    else
        FUZZ_CHECK(st == PP_OK || st == PP_ERR_INVALID_ARGUMENT || INJECTED_OOM(st), "save: %d", (int)st);
    if (st != PP_OK)
        return;
    pp_world w2 = {0};
    const pp_status ls = ST(pp_world_load_snapshot(snap_dir, &w2));
    FUZZ_CHECK(ls == PP_OK || INJECTED_OOM(ls), "loading a snapshot just saved: %d (%s)", (int)ls, pp_last_error());
    if (ls != PP_OK) {
        FUZZ_CHECK(w2.id == 0, "a failed load wrote its out handle");
        return;
    }
    FUZZ_CHECK(count_bodies(w2) == count_bodies(w), "body counts differ after save and load");
    if (u8(r) & 1) {
        ST(pp_world_step(w, 1.0f / 60));
        ST(pp_world_step(w2, 1.0f / 60));
    }
    FUZZ_CHECK(ST(pp_world_destroy(w2)) == PP_OK, "destroy loaded");
    FUZZ_CHECK(ST(pp_world_load_snapshot(snap_dir, NULL)) == PP_ERR_INVALID_ARGUMENT, "NULL out");
    fuzz_rm_tree(snap_dir);
    FUZZ_CHECK(ST(pp_world_load_snapshot(snap_dir, &w2)) == PP_ERR_IO, "load of a missing folder");
}

/* A ray or a point, box or circle query: a hit lies on the segment and names a live body. */
/* A joint handle of world t: mostly one it made (maybe since ended), sometimes zero or random. */
static pp_joint pick_joint(reader *r, tracked_world *t)
{
    const uint8_t k = u8(r);
    if (t && t->njoints && k < 220)
        return t->joints[k % t->njoints];
    return k < 240 ? (pp_joint){0} : (pp_joint){(uint64_t)u32(r) << 32 | u32(r)};
}

static void op_joint_create(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    int stale_a, stale_b;
    pp_joint_def d = pp_joint_def_default((pp_joint_type)(u8(r) % 9)); /* 0 and 8 are no type */
    d.type = (pp_joint_type)(u8(r) % 9);
    d.body_a = u8(r) < 64 ? (pp_body){0} : pick_body(r, t, &stale_a);
    d.body_b = pick_body(r, t, &stale_b);
    d.anchor_a = (pp_vec2){f32(r, 300), f32(r, 300)};
    d.anchor_b = (pp_vec2){f32(r, 300), f32(r, 300)};
    d.axis = (pp_vec2){f32(r, 2), f32(r, 2)};
    const uint8_t flags = u8(r);
    d.collide_connected = flags & 1, d.enable_limit = flags & 2, d.enable_motor = flags & 4;
    d.lower = f32(r, 4), d.upper = f32(r, 4);
    d.motor_speed = f32(r, 10), d.max_motor_force = f32(r, 1e6f);
    d.min_length = f32(r, 100), d.max_length = f32(r, 100);
    d.spring_hertz = f32(r, 10), d.spring_damping_ratio = f32(r, 2);
    d.max_force = f32(r, 1e6f), d.break_force = f32(r, 1e7f);
    if (flags & 64) { /* the second part's fields */
        d.target = f32(r, 4), d.angular_hertz = f32(r, 10), d.angular_damping_ratio = f32(r, 2);
        d.break_torque = f32(r, 1e9f), d.linear_offset = (pp_vec2){f32(r, 300), f32(r, 300)};
        d.angular_offset = f32(r, 4), d.max_torque = f32(r, 1e9f), d.correction_factor = f32(r, 1.2f);
    }
    if (flags & 8)
        d.struct_size = u8(r) & 1 ? (uint32_t)offsetof(pp_joint_def, target) : u8(r);
    pp_joint j = {0};
    const pp_status st = ST(pp_joint_create(w, (flags & 16) ? NULL : &d, (flags & 32) ? NULL : &j));
    if (!t)
        FUZZ_CHECK(st == PP_ERR_INVALID_HANDLE || st == PP_ERR_INVALID_ARGUMENT, "joint in a dead world: %d", (int)st);
    if (st == PP_OK) {
        FUZZ_CHECK(t && j.id != 0, "a joint made without a handle");
        pp_joint_type type;
        FUZZ_CHECK(ST(pp_joint_get_type(w, j, &type)) == PP_OK && type == d.type, "the joint's type");
        if (t->njoints < MAX_JOINTS)
            t->joints[t->njoints++] = j;
        else
            ST(pp_joint_destroy(w, j));
    }
}

static void op_joint_use(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    const pp_joint j = pick_joint(r, t);
    const uint8_t k = u8(r);
    const float x = f32(r, 100), y = f32(r, 100);
    pp_vec2 f;
    float a, b;
    pp_body ba, bb;
    pp_status st;
    switch (k % 10) {
    case 8: st = ST(pp_joint_set_spring(w, j, x * 0.1f, y * 0.02f, f32(r, 4))); break;
    case 9: st = ST(pp_joint_set_offsets(w, j, (pp_vec2){x, y}, f32(r, 4))); break;
    case 0: st = ST(pp_joint_destroy(w, j)); break;
    case 1: st = ST(pp_joint_get_reaction(w, j, k & 8 ? NULL : &f, &a)); break;
    case 2: st = ST(pp_joint_get_value(w, j, &a, k & 8 ? NULL : &b)); break;
    case 3: st = ST(pp_joint_set_motor(w, j, k & 8, x, y)); break;
    case 4: st = ST(pp_joint_set_limits(w, j, k & 8, x, y)); break;
    case 5: st = ST(pp_joint_set_target(w, j, (pp_vec2){x, y})); break;
    case 6: st = ST(pp_joint_get_bodies(w, j, &ba, k & 8 ? NULL : &bb)); break;
    default: {
        pp_joint out[4];
        int32_t n = -1;
        st = ST(pp_world_get_joints(w, k & 8 ? NULL : out, (int32_t)(u8(r) % 6) - 1, &n));
        if (st == PP_OK)
            FUZZ_CHECK(n >= 0, "joint count %d", (int)n);
    }
    }
    if (!t || (j.id == 0 && k % 10 != 7))
        FUZZ_CHECK(st != PP_OK, "a joint call (%d) on a dead world or a zero joint succeeded", k % 10);
    if ((k % 10) == 0 && st == PP_OK)
        FUZZ_CHECK(ST(pp_joint_destroy(w, j)) == PP_ERR_INVALID_HANDLE, "a joint destroyed twice");
}

/* The runtime setters, forces and the bulk state read. */
static void op_props(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    int stale;
    const pp_body b = pick_body(r, t, &stale);
    const uint8_t k = u8(r);
    const float x = f32(r, 10), y = f32(r, 10);
    pp_status st;
    switch (k % 12) {
    case 0: st = ST(pp_body_set_type(w, b, (pp_body_type)(u8(r) % 4))); break;
    case 1: st = ST(pp_body_set_fixed_rotation(w, b, k & 16)); break;
    case 2: st = ST(pp_body_set_damping(w, b, x, y)); break;
    case 3: st = ST(pp_body_set_density(w, b, x)); break;
    case 4: st = ST(pp_body_set_friction(w, b, x)); break;
    case 5: st = ST(pp_body_set_restitution(w, b, x)); break;
    case 6: st = ST(pp_body_set_gravity_scale(w, b, x)); break;
    case 7: st = ST(pp_body_set_awake(w, b, k & 16)); break;
    case 8: st = ST(pp_body_apply_force(w, b, (pp_vec2){x * 1e4f, y * 1e4f}, (pp_vec2){f32(r, 300), f32(r, 300)})); break;
    case 9: st = ST(pp_body_apply_torque(w, b, x * 1e6f)); break;
    case 10: st = ST(pp_world_set_gravity(w, (pp_vec2){x * 100, y * 100})); break;
    default: {
        pp_body_state s[4];
        int32_t n = -1;
        st = ST(pp_world_get_body_states(w, k & 16 ? NULL : s, (int32_t)(u8(r) % 6) - 1, &n));
        if (st == PP_OK)
            FUZZ_CHECK(n >= 0, "state count %d", (int)n);
    }
    }
    if ((k % 12) < 10)
        expect_handle_refused(st, !t || b.id == 0 || stale, "a body setter");
    if ((k % 12) >= 2 && (k % 12) <= 6 && (!isfinite(x) || ((k % 12) == 2 && !isfinite(y))))
        FUZZ_CHECK(st != PP_OK, "a non-finite setting (%d) accepted", k % 12);
}

/* Issue 44's calls, on a query's kind of inputs: every body a ray enters, a body cast along q, a blast at p. */
static void op_casts(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    const uint8_t k = u8(r);
    const uint32_t mask = k & 8 ? u32(r) : 0xffffffffu;
    const pp_vec2 p = {f32(r, 400), f32(r, 400)}, q = {f32(r, 400), f32(r, 400)};
    const int32_t cap = (int32_t)(int8_t)u8(r) % 8;
    static pp_raycast_hit hits[8];
    pp_raycast_hit h;
    int32_t n = -1, hit = -1, stale = 0;
    pp_status st;
    if (k % 4 == 0) {
        st = ST(pp_world_raycast_all(w, p, q, mask, k & 16 ? NULL : hits, cap, k & 32 ? NULL : &n));
    } else if (k % 4 == 1) {
        const pp_body b = pick_body(r, t, &stale);
        st = ST(pp_world_cast_body(w, b, q, mask, k & 16 ? NULL : &h, k & 32 ? NULL : &hit));
    } else {
        pp_explosion_def d = pp_explosion_def_default();
        d.position = p, d.radius = q.x, d.falloff = q.y, d.erase_radius = f32(r, 24);
        d.impulse_per_length = f32(r, 1e5f), d.mask_bits = mask, d.erase_mask_bits = u32(r);
        d.struct_size += k & 64 ? 4 : 0;
        st = ST(pp_world_explode(w, k & 16 ? NULL : &d, k & 32 ? NULL : &n));
    }
    if (!t) {
        FUZZ_CHECK(st == PP_ERR_INVALID_HANDLE || st == PP_ERR_INVALID_ARGUMENT, "a cast in a dead world: %d", (int)st);
        return;
    }
    if (st != PP_OK)
        return;
    FUZZ_CHECK(k % 4 != 1 || !stale, "a cast of a stale body accepted");
    pp_vec2 pos;
    for (int32_t i = 0; k % 4 == 0 && i < n && i < cap; i++) {
        FUZZ_CHECK(hits[i].fraction >= 0 && hits[i].fraction <= 1 && (i == 0 || hits[i].fraction >= hits[i - 1].fraction),
                   "hit %d at %g, out of order", (int)i, hits[i].fraction);
        FUZZ_CHECK(pp_body_get_position(w, hits[i].body, &pos) == PP_OK, "raycast_all hit no live body");
    }
    if (k % 4 == 1 && hit == 1) {
        FUZZ_CHECK(h.fraction >= 0 && h.fraction <= 1, "cast fraction %g", h.fraction);
        FUZZ_CHECK(pp_body_get_position(w, h.body, &pos) == PP_OK, "a cast hit no live body");
    }
}

static void op_query(reader *r)
{
    tracked_world *t;
    const pp_world w = pick_world(r, &t);
    const uint8_t k = u8(r);
    const uint32_t mask = k & 8 ? u32(r) : 0xffffffffu;
    const pp_vec2 p = {f32(r, 400), f32(r, 400)}, q = {f32(r, 400), f32(r, 400)};
    static pp_body bodies[8];
    static pp_debug_segment segs[8];
    int32_t cap = (int32_t)(int8_t)u8(r) % 8, n = -1, hit = -1;
    pp_raycast_hit h;
    pp_status st;
    switch (k % 4) {
    case 0: st = ST(pp_world_raycast(w, p, q, mask, k & 16 ? NULL : &h, k & 32 ? NULL : &hit)); break;
    case 1: st = ST(pp_world_query_point(w, p, mask, k & 16 ? NULL : bodies, cap, k & 32 ? NULL : &n)); break;
    case 2:
        if (k & 64) /* the debug segments of the same box instead: flags from the mask, a bit past them at times */
            st = ST(pp_world_debug_draw(w, mask & 0x7f, p, q, k & 16 ? NULL : segs, cap, k & 32 ? NULL : &n));
        else
            st = ST(pp_world_query_aabb(w, p, q, mask, k & 16 ? NULL : bodies, cap, k & 32 ? NULL : &n));
        break;
    default: st = ST(pp_world_query_circle(w, p, q.x, mask, k & 16 ? NULL : bodies, cap, k & 32 ? NULL : &n)); break;
    }
    if (!t) {
        FUZZ_CHECK(st == PP_ERR_INVALID_HANDLE || st == PP_ERR_INVALID_ARGUMENT, "query of a dead world: %d", (int)st);
        return;
    }
    if (st != PP_OK)
        return;
    pp_vec2 pos;
    if (k % 4 == 0) {
        FUZZ_CHECK(hit == 0 || hit == 1, "hit %d", (int)hit);
        if (hit) {
            FUZZ_CHECK(h.fraction >= 0 && h.fraction <= 1, "fraction %g", h.fraction);
            FUZZ_CHECK(isfinite(h.point.x) && isfinite(h.point.y) && isfinite(h.normal.x) && isfinite(h.normal.y),
                       "a hit that is not finite");
            FUZZ_CHECK(pp_body_get_position(w, h.body, &pos) == PP_OK, "a ray hit no live body");
        }
        return;
    }
    FUZZ_CHECK(n >= 0, "count %d", (int)n);
    if (k % 4 == 2 && (k & 64)) {
        FUZZ_CHECK((mask & 0x7f) < 64, "flags 0x%x past PP_DEBUG_DRAW_ALL accepted", (unsigned)(mask & 0x7f));
        for (int32_t i = 0; i < n && i < cap; i++)
            FUZZ_CHECK(segs[i].kind >= PP_DEBUG_OUTLINE && segs[i].kind <= PP_DEBUG_VELOCITY &&
                           (segs[i].body.id == 0 || pp_body_get_position(w, segs[i].body, &pos) == PP_OK),
                       "segment %d: kind %d of no live body", (int)i, (int)segs[i].kind);
        return;
    }
    for (int32_t i = 0; i < n && i < cap; i++)
        FUZZ_CHECK(pp_body_get_position(w, bodies[i], &pos) == PP_OK, "a query returned no live body");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!plane)
        plane = malloc(MAX_SIDE * MAX_SIDE * 4);
    reader rd = {data, size}, *r = &rd;
    memset(worlds, 0, sizeof worlds);
    nstale_worlds = 0, steps = 0, snapshots = 0;
    fail_countdown = 0;
    for (int ops = 0; r->n && ops < 200; ops++) {
        injected = 0;
        const uint8_t op = u8(r);
        switch (op % 24) {
        case 0: case 1: op_world_create(r); break;
        case 2: op_world_destroy(r); break;
        case 3: case 4: case 5: op_body_create(r); break;
        case 6: op_body_destroy(r); break;
        case 7: op_edit(r, 0); break;
        case 8: op_edit(r, 1); break;
        case 9: op_edit(r, 2); break;
        case 10: op_write_pixels(r); break;
        case 11: op_motion(r, 0); break;
        case 12: op_motion(r, 1); break;
        case 13: op_motion(r, 2); break;
        case 14: op_schedule(r); break;
        case 15: case 16: op_step(r); break;
        case 17: op_reads(r); break;
        case 18: op_body_reads(r); break;
        case 19: op_collide(r, 0); break;
        case 20: op_collide(r, 1); break;
        case 21: op_snapshot(r); break;
        case 22: op_query(r); break;
        default: /* bytes 215, 239 and 191, once fail-soon, drive the later ops: older seeds keep their meaning */
            if (op == 191) {
                op_casts(r);
            } else if (op == 215 || op == 239) {
                const uint8_t sub = u8(r) % 3;
                if (sub == 0)
                    op_joint_create(r);
                else if (sub == 1)
                    op_joint_use(r);
                else
                    op_props(r);
            } else
                op_fail_soon(r);
        }
        FUZZ_CHECK(pp_status_name((pp_status)u8(r)) != NULL, "status name");
    }
    fail_countdown = 0;
    for (int i = 0; i < MAX_WORLDS; i++)
        if (worlds[i].live)
            FUZZ_CHECK(ST(pp_world_destroy(worlds[i].w)) == PP_OK, "final destroy");
    return 0;
}
