/* Eight worlds on eight threads under ThreadSanitizer (make check-deep). Each thread runs the same
 * scene: crates fall onto a terrain and rest, the terrain is erased and painted, edits are scheduled,
 * bodies, contacts, events and stats are read, the world is saved as a snapshot and loaded back. Some
 * threads share their narrowphase over a worker pool; all of them churn the world handle table, use
 * stale handles of worlds other threads destroyed, fail calls for pp_last_error and swap the log hook.
 * Each thread also pours a bin of small crates: hundreds of pairs a step, whose set-up and contacts are shared
 * over its narrowphase threads. It passes only if every thread's hash equals that of the same scene run alone
 * before the threads start, the crates rested where they should, and TSan (halt_on_error) found no race.
 * A plain program, not Criterion: Criterion does not start under TSan. */
#define _GNU_SOURCE /* mkdtemp */
#include <dirent.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "handle.h" /* handle_saved: ids compared across worlds */
#include "physpix.h"
#include "workers.h" /* WORKERS_MIN_CELLS: below it only the pairs' set-up and contacts are shared */

enum {
    THREADS = 8,
    ROUNDS = 3,              /* the threads run the scene this many times, each time together */
    TW = 900, TH = 300,     /* terrain bitmap, px: a 40 px ground and an 8 px wall at the left */
    CRATES = 10, CRATE = 60, /* crates, px: eight on the ground, two on top of crates 2 and 5 */
    REST_STEPS = 150,        /* 2.5 s to land and rest */
    EDIT_STEPS = 120,        /* 2 s of craters, paint and scheduled edits */
    AFTER_STEPS = 40,        /* the original and its snapshot, stepped side by side */
    CHURN = 24,              /* throwaway worlds each thread creates and destroys */
    SKIPPED_EDITS = 12,      /* edits scheduled on a body destroyed before they apply: one log line each */
    BIN_CRATES = 300, BIN_CRATE = 5, BIN_STEPS = 90, /* the bin: crates of 5 px, 24 a row */
};
#define DT (1.0f / 60.0f)
#define TERRAIN_X 450.0f
#define TERRAIN_Y 450.0f
#define GROUND_TOP (TERRAIN_Y - TH / 2.0f + (TH - 40)) /* world y of the ground's surface: 560 */
#define SLOP 0.75f     /* px: pp_world_def's default contact_slop, the overlap a resting contact keeps */
#define REST_TOL 0.5f  /* px */

static int failures;
static pthread_mutex_t fail_lock = PTHREAD_MUTEX_INITIALIZER;

/* Record a failure with its thread and line; the run goes on so that every failure is printed. */
#define CHECK(cond, ...)                                                         \
    do {                                                                         \
        if (!(cond)) {                                                           \
            pthread_mutex_lock(&fail_lock);                                      \
            failures++;                                                          \
            fprintf(stderr, "tsan_worlds: thread %d, line %d: ", t->index, __LINE__); \
            fprintf(stderr, __VA_ARGS__);                                        \
            fputc('\n', stderr);                                                 \
            pthread_mutex_unlock(&fail_lock);                                    \
        }                                                                        \
    } while (0)
#define OK(call) CHECK((call) == PP_OK, "%s failed: %s", #call, pp_last_error())

/* Every world a thread destroyed, for the others to try as stale handles. */
static _Atomic uint64_t stale_worlds[ROUNDS * THREADS * CHURN];
static atomic_int stale_count;

/* Log lines delivered to the hook, by the user pointer it was installed with. */
static atomic_int log_lines[THREADS + 1];

static void count_log(int level, const char *msg, void *user)
{
    (void)level;
    (void)msg;
    atomic_fetch_add((atomic_int *)user, 1);
}

typedef struct run {
    int index;        /* thread number; THREADS for the main thread's lone run */
    int workers;      /* pp_world_def.worker_threads */
    uint64_t hash;    /* poses after every phase */
    int max_threads;  /* most threads a step's narrowphase ran on */
    int events, splits;
    int stale_tried;
    int contacts_seen;
    float rest_y[CRATES];
    float crater_fall; /* how far crate 0 fell into its crater, px */
    uint64_t bin_hash; /* the bin's poses after every step */
    int bin_shared;    /* the bin's steps that shared their set-up and contacts, not their cores */
} run;

static uint64_t fnv1a(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

/* Positions and angles of every live body, in the world's handle order. */
static uint64_t hash_world(run *t, pp_world w, uint64_t h)
{
    pp_body bodies[64];
    int32_t n = 0;
    OK(pp_world_get_bodies(w, bodies, 64, &n));
    CHECK(n <= 64, "%d bodies", (int)n);
    h = fnv1a(h, &n, sizeof n);
    for (int32_t i = 0; i < n && i < 64; i++) {
        pp_vec2 p = {0, 0};
        float a = 0;
        OK(pp_body_get_position(w, bodies[i], &p));
        OK(pp_body_get_angle(w, bodies[i], &a));
        const uint64_t id = handle_saved(bodies[i].id); /* the same in every world: slot and generation */
        h = fnv1a(h, &id, sizeof id);
        h = fnv1a(h, &p, sizeof p);
        h = fnv1a(h, &a, sizeof a);
    }
    return h;
}

static uint8_t crate_mask[CRATE * CRATE]; /* all solid; filled before any thread starts */

static pp_body add_box(run *t, pp_world w, float x, float y, float angle)
{
    pp_body_def d = pp_body_def_default();
    d.position = (pp_vec2){x, y};
    d.angle = angle;
    d.width = d.height = CRATE;
    d.mask = crate_mask;
    pp_body b = {0};
    OK(pp_body_create(w, &d, &b));
    return b;
}

static pp_body crate_body[THREADS + 1][CRATES];

static pp_world make_scene(run *t, pp_body *terrain)
{
    pp_world_def wd = pp_world_def_default();
    wd.backend = PP_BACKEND_CPU;
    wd.worker_threads = t->workers;
    pp_world w = {0};
    OK(pp_world_create(&wd, &w));
    uint8_t *ground = malloc((size_t)TW * TH);
    CHECK(ground != NULL, "no memory");
    if (!ground)
        return w;
    for (int y = 0; y < TH; y++)
        for (int x = 0; x < TW; x++)
            ground[y * TW + x] = y >= TH - 40 || x < 8;
    pp_body_def d = pp_body_def_default();
    d.type = PP_BODY_STATIC;
    d.position = (pp_vec2){TERRAIN_X, TERRAIN_Y};
    d.width = TW, d.height = TH, d.mask = ground;
    d.friction = 0.8f;
    OK(pp_body_create(w, &d, terrain));
    free(ground);
    pp_body *c = crate_body[t->index];
    /* The eight on the ground start 1 px into it, so the first step collides them together: a batch over the
     * worker pool's threshold (a pair touching at a step's start and moving slowly is collided once a step, so
     * crates landing one by one never make one). */
    for (int i = 0; i < 8; i++)
        c[i] = add_box(t, w, 80.0f + 100.0f * i, GROUND_TOP - CRATE / 2.0f + 1.0f, 0);
    c[8] = add_box(t, w, 80.0f + 100.0f * 2, GROUND_TOP - 1.5f * CRATE - 12.0f, 0);
    c[9] = add_box(t, w, 80.0f + 100.0f * 5, GROUND_TOP - 1.5f * CRATE - 12.0f, 0);
    return w;
}

/* Read what a step left: events (counted into the hash), contacts, stats; try other threads' stale worlds. */
static uint64_t after_step(run *t, pp_world w, uint64_t h, int k)
{
    pp_event ev[16];
    int32_t n = 0;
    OK(pp_world_get_events(w, ev, 16, &n));
    for (int32_t i = 0; i < n && i < 16; i++) {
        t->events++;
        t->splits += ev[i].type == PP_EVENT_BODY_SPLIT;
        pp_event e = ev[i]; /* its handles without the bits that name this world */
        e.body.id = handle_saved(e.body.id), e.other.id = handle_saved(e.other.id);
        h = fnv1a(h, &e, sizeof e);
    }
    pp_contact contacts[256];
    OK(pp_world_get_contacts(w, contacts, 256, &n));
    t->contacts_seen += n;
    for (int32_t i = 0; i < n && i < 256; i++)
        CHECK(fabsf(contacts[i].normal.x * contacts[i].normal.x + contacts[i].normal.y * contacts[i].normal.y - 1) <
                  1e-3f, "contact normal (%g, %g) is not a unit vector", contacts[i].normal.x, contacts[i].normal.y);
    pp_step_stats st;
    OK(pp_world_get_stats(w, &st));
    CHECK(st.backend == PP_BACKEND_CPU, "backend %d", (int)st.backend);
    if (st.threads > t->max_threads)
        t->max_threads = st.threads;
    /* Every few steps: a world another thread destroyed is a stale handle here, even if its slot is reused. */
    const int have = atomic_load(&stale_count);
    if (k % 7 == 0 && have > 0) {
        const pp_world stale = {atomic_load(&stale_worlds[(k * 31 + t->index) % have])};
        CHECK(stale.id != w.id, "a destroyed world's handle %#llx equals a live one", (unsigned long long)w.id);
        CHECK(pp_world_step(stale, DT) == PP_ERR_INVALID_HANDLE, "stepping a stale world: %s", pp_last_error());
        CHECK(pp_world_get_stats(stale, &st) == PP_ERR_INVALID_HANDLE, "stats of a stale world");
        CHECK(pp_world_destroy(stale) == PP_ERR_INVALID_HANDLE, "destroying a stale world twice");
        t->stale_tried++;
    }
    return h;
}

/* A failing call's message stays on its thread, whatever the other threads fail meanwhile. */
static void own_last_error(run *t, pp_world w)
{
    const float dt = 2.0f + (float)t->index; /* out of range: the message names it */
    CHECK(pp_world_step(w, dt) == PP_ERR_INVALID_ARGUMENT, "dt %g accepted", dt);
    char want[128];
    snprintf(want, sizeof want, "got %g", dt);
    for (int i = 0; i < 50; i++) {
        pp_step_stats st;
        OK(pp_world_get_stats(w, &st)); /* succeeds: leaves the message alone */
        sched_yield();
    }
    CHECK(strstr(pp_last_error(), want) != NULL, "pp_last_error() is \"%s\", expected one naming \"%s\"",
          pp_last_error(), want);
}

/* Throwaway worlds: the handle table's slots are taken and freed under the other threads' feet. */
static void churn(run *t, int count)
{
    pp_world_def wd = pp_world_def_default();
    wd.backend = PP_BACKEND_CPU;
    for (int i = 0; i < count; i++) {
        pp_world w = {0};
        OK(pp_world_create(&wd, &w));
        pp_body b = add_box(t, w, 0, 0, 0);
        OK(pp_world_step(w, DT));
        OK(pp_world_destroy(w));
        CHECK(pp_body_get_position(w, b, &(pp_vec2){0, 0}) == PP_ERR_INVALID_HANDLE, "world outlived its destroy");
        const int k = atomic_fetch_add(&stale_count, 1);
        if (k < (int)(sizeof stale_worlds / sizeof stale_worlds[0]))
            atomic_store(&stale_worlds[k], w.id);
        else
            atomic_fetch_sub(&stale_count, 1);
    }
}

static int remove_snapshot(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    struct dirent *e;
    char path[512];
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
            unlink(path);
        }
    closedir(d);
    return rmdir(dir);
}

static void run_scene(run *t)
{
    uint64_t h = 1469598103934665603ull;
    pp_body terrain = {0};
    pp_world w = make_scene(t, &terrain);
    const pp_body *c = crate_body[t->index];
    for (int k = 0; k < REST_STEPS; k++) {
        OK(pp_world_step(w, DT));
        h = after_step(t, w, h, k);
    }
    h = hash_world(t, w, h);
    for (int i = 0; i < CRATES; i++) {
        pp_vec2 p = {0, 0};
        OK(pp_body_get_position(w, c[i], &p));
        t->rest_y[i] = p.y;
    }
    own_last_error(t, w);

    /* A crater under crate 0, a bump of paint beside crate 7, a small bite out of every body near crate 3. */
    pp_vec2 p0 = {0, 0};
    OK(pp_body_get_position(w, c[0], &p0));
    int32_t changed = 0;
    OK(pp_body_erase_circle(w, terrain, (pp_vec2){p0.x, GROUND_TOP + 15.0f}, 45.0f, &changed));
    CHECK(changed > 2000, "the crater erased only %d px", (int)changed);
    OK(pp_body_paint_circle(w, terrain, (pp_vec2){80.0f + 100.0f * 7 + 45.0f, GROUND_TOP}, 8.0f, 255, &changed));
    CHECK(changed > 50, "the bump painted only %d px", (int)changed);
    OK(pp_world_erase_circle(w, (pp_vec2){80.0f + 100.0f * 3 + 30.0f, GROUND_TOP - CRATE}, 12.0f, &changed));
    /* Scheduled: a crater under crate 6 in 0.5 s, and paint on crate 9, which is destroyed first (a skipped
     * edit, which logs a line through the hook). */
    double now = 0;
    OK(pp_world_get_time(w, &now));
    pp_vec2 p6 = {0, 0};
    OK(pp_body_get_position(w, c[6], &p6));
    pp_timed_edit e = {.time = now + 0.5, .type = PP_EDIT_ERASE_CIRCLE, .body = terrain,
                       .center = {p6.x, GROUND_TOP + 15.0f}, .radius = 45.0f};
    OK(pp_world_schedule_edit(w, &e));
    for (int i = 0; i < SKIPPED_EDITS; i++) {
        e = (pp_timed_edit){.time = now + 0.1 * (i + 1), .type = PP_EDIT_PAINT_CIRCLE, .weight = 200, .body = c[9],
                            .center = {80.0f + 100.0f * 5, GROUND_TOP - 1.5f * CRATE}, .radius = 5.0f};
        OK(pp_world_schedule_edit(w, &e));
    }
    int32_t pending = 0;
    OK(pp_world_get_scheduled_edits(w, NULL, 0, &pending));
    CHECK(pending == 1 + SKIPPED_EDITS, "%d edits pending, expected %d", (int)pending, 1 + SKIPPED_EDITS);
    OK(pp_body_destroy(w, c[9]));
    /* Crate 3 erased whole (a DESTROYED event), crate 4 cut in two by a column of small circles (a SPLIT). */
    pp_vec2 p3 = {0, 0}, p4 = {0, 0};
    OK(pp_body_get_position(w, c[3], &p3));
    OK(pp_body_get_position(w, c[4], &p4));
    OK(pp_body_erase_circle(w, c[3], p3, 45.0f, &changed));
    CHECK(changed > 3000, "erasing crate 3 whole took only %d px", (int)changed);
    for (float y = p4.y - CRATE / 2.0f - 2.0f; y < p4.y + CRATE / 2.0f + 3.0f; y += 2.0f)
        OK(pp_body_erase_circle(w, c[4], (pp_vec2){p4.x, y}, 3.0f, NULL));
    CHECK(pp_body_get_position(w, c[9], &p0) == PP_ERR_INVALID_HANDLE, "a destroyed body still answers");
    pp_set_log_hook(count_log, &log_lines[t->index]);
    for (int k = 0; k < EDIT_STEPS; k++) {
        OK(pp_world_step(w, DT));
        h = after_step(t, w, h, REST_STEPS + k);
        if (k % 3 == 0) /* swapped while the others step and log */
            pp_set_log_hook(count_log, &log_lines[(t->index + k / 3) % (THREADS + 1)]);
    }
    OK(pp_world_get_scheduled_edits(w, NULL, 0, &pending));
    CHECK(pending == 0, "%d edits still pending", (int)pending);
    pp_vec2 p = {0, 0};
    OK(pp_body_get_position(w, c[0], &p));
    t->crater_fall = p.y - t->rest_y[0];
    h = hash_world(t, w, h);

    /* Save, load, and step the two side by side: the copy continues exactly as the original. */
    char dir[] = "/tmp/physpix_tsan_XXXXXX", folder[64];
    CHECK(mkdtemp(dir) != NULL, "mkdtemp failed");
    snprintf(folder, sizeof folder, "%s/snap", dir);
    OK(pp_world_save_snapshot(w, folder));
    pp_world copy = {0};
    OK(pp_world_load_snapshot(folder, &copy));
    CHECK(remove_snapshot(folder) == 0 && rmdir(dir) == 0, "cannot remove %s", folder);
    uint64_t ho = hash_world(t, w, 1), hc = hash_world(t, copy, 1);
    CHECK(ho == hc, "the loaded snapshot's poses differ from the original's");
    for (int k = 0; k < AFTER_STEPS; k++) {
        OK(pp_world_step(w, DT));
        OK(pp_world_step(copy, DT));
        ho = hash_world(t, w, ho);
        hc = hash_world(t, copy, hc);
    }
    CHECK(ho == hc, "the snapshot continued differently: %016llx, original %016llx", (unsigned long long)hc,
          (unsigned long long)ho);
    t->hash = fnv1a(h, &ho, sizeof ho);
    OK(pp_world_destroy(copy));
    OK(pp_world_destroy(w));
    CHECK(pp_world_step(w, DT) == PP_ERR_INVALID_HANDLE, "a destroyed world still steps");
}

/* 300 crates of 5 px poured into a bin, every pose hashed after each step. */
static void run_bin(run *t)
{
    pp_world_def wd = pp_world_def_default();
    wd.backend = PP_BACKEND_CPU;
    wd.worker_threads = t->workers;
    pp_world w = {0};
    OK(pp_world_create(&wd, &w));
    static const float walls[3][4] = {{200, 410, 400, 20}, {115, 300, 10, 200}, {285, 300, 10, 200}}; /* x y w h */
    uint8_t *solid = malloc(400 * 200);
    CHECK(solid != NULL, "no memory");
    if (!solid)
        return;
    memset(solid, 1, 400 * 200);
    pp_body_def d = pp_body_def_default();
    pp_body b = {0};
    for (int i = 0; i < 3; i++) {
        d.type = PP_BODY_STATIC;
        d.position = (pp_vec2){walls[i][0], walls[i][1]};
        d.width = (int32_t)walls[i][2], d.height = (int32_t)walls[i][3], d.mask = solid;
        OK(pp_body_create(w, &d, &b));
    }
    pp_body crates[BIN_CRATES];
    for (int i = 0; i < BIN_CRATES; i++) {
        d = pp_body_def_default();
        d.position = (pp_vec2){125.0f + 6.5f * (i % 24), 395.0f - 6.5f * (i / 24)};
        d.angle = 0.05f * (i % 5);
        d.width = d.height = BIN_CRATE, d.mask = solid;
        OK(pp_body_create(w, &d, &crates[i]));
    }
    free(solid);
    uint64_t h = 1469598103934665603ull;
    for (int k = 0; k < BIN_STEPS; k++) {
        OK(pp_world_step(w, DT));
        pp_step_stats st;
        OK(pp_world_get_stats(w, &st));
        t->bin_shared += st.threads > 1 && st.pixels_tested < WORKERS_MIN_CELLS;
        t->max_threads = st.threads > t->max_threads ? st.threads : t->max_threads;
        for (int i = 0; i < BIN_CRATES; i++) {
            pp_vec2 p = {0, 0};
            OK(pp_body_get_position(w, crates[i], &p));
            h = fnv1a(h, &p, sizeof p);
        }
    }
    t->bin_hash = h;
    OK(pp_world_destroy(w));
}

static run runs[ROUNDS][THREADS];
static pthread_barrier_t round_start;

/* Each round starts on all threads at once, with another share of narrowphase threads. */
static void *thread_main(void *arg)
{
    const int i = (int)(intptr_t)arg;
    for (int r = 0; r < ROUNDS; r++) {
        run *t = &runs[r][i];
        *t = (run){.index = i, .workers = 1 + (i + r) % 3}; /* 1, 2 or 3 narrowphase threads */
        pthread_barrier_wait(&round_start);
        churn(t, CHURN / 2);
        run_scene(t);
        run_bin(t);
        churn(t, CHURN / 2);
    }
    return NULL;
}

static double seconds_since(const struct timespec *a)
{
    struct timespec b;
    clock_gettime(CLOCK_MONOTONIC, &b);
    return (double)(b.tv_sec - a->tv_sec) + 1e-9 * (double)(b.tv_nsec - a->tv_nsec);
}

int main(void)
{
    struct timespec start;
    clock_gettime(CLOCK_MONOTONIC, &start);
    memset(crate_mask, 1, sizeof crate_mask);
    pp_set_log_hook(count_log, &log_lines[THREADS]);
    static run ref;
    ref = (run){.index = THREADS, .workers = 1};
    run *t = &ref; /* CHECK names it */
    run_scene(&ref);
    run_bin(&ref);
    int ref_lines = 0;
    for (int i = 0; i <= THREADS; i++)
        ref_lines += atomic_exchange(&log_lines[i], 0);
    printf("tsan_worlds: the scene alone: hash %016llx, %d events, crate 0 fell %.1f px into its crater, %.2f s\n",
           (unsigned long long)ref.hash, ref.events, ref.crater_fall, seconds_since(&start));

    /* Physics of the lone run: crates rest on the ground or on another crate; crate 0 fell into the crater. */
    for (int i = 0; i < CRATES; i++) {
        const float want = i < 8 ? GROUND_TOP - CRATE / 2.0f + SLOP : GROUND_TOP - 1.5f * CRATE + 2 * SLOP;
        CHECK(fabsf(ref.rest_y[i] - want) < REST_TOL, "crate %d rests at y %.2f, expected %.2f ± %.1f", i,
              ref.rest_y[i], want, REST_TOL);
    }
    CHECK(ref.crater_fall > CRATE, "crate 0 fell only %.1f px into its crater", ref.crater_fall);
    CHECK(ref.contacts_seen > 0, "no contacts: the scene tests nothing");
    CHECK(ref_lines == SKIPPED_EDITS, "%d skipped edits logged %d lines", SKIPPED_EDITS, ref_lines);
    CHECK(ref.events >= 2 && ref.splits >= 1, "%d events, %d splits: expected crate 3 destroyed and crate 4 split",
          ref.events, ref.splits);
    CHECK(ref.max_threads == 1, "worker_threads 1 ran on %d threads", ref.max_threads);

    pthread_t threads[THREADS];
    pthread_barrier_init(&round_start, NULL, THREADS);
    for (int i = 0; i < THREADS; i++) {
        if (pthread_create(&threads[i], NULL, thread_main, (void *)(intptr_t)i) != 0) {
            fprintf(stderr, "tsan_worlds: cannot start thread %d\n", i);
            return 1;
        }
    }
    for (int i = 0; i < THREADS; i++)
        pthread_join(threads[i], NULL);
    int lines = 0, stale = 0;
    for (int i = 0; i <= THREADS; i++)
        lines += atomic_load(&log_lines[i]);
    pthread_barrier_destroy(&round_start);
    for (int i = 0; i < THREADS * ROUNDS; i++) {
        t = &runs[i / THREADS][i % THREADS];
        CHECK(t->hash == ref.hash, "hash %016llx, alone %016llx (%d narrowphase threads)",
              (unsigned long long)t->hash, (unsigned long long)ref.hash, t->workers);
        CHECK(t->events == ref.events, "%d events, alone %d", t->events, ref.events);
        CHECK(t->bin_hash == ref.bin_hash, "the bin's hash %016llx, alone %016llx (%d narrowphase threads)",
              (unsigned long long)t->bin_hash, (unsigned long long)ref.bin_hash, t->workers);
        CHECK(t->workers == 1 || t->bin_shared > 0, "the bin never shared its set-up and contacts alone over %d threads",
              t->workers);
        CHECK(t->max_threads == t->workers, "worker_threads %d ran on at most %d threads", t->workers,
              t->max_threads);
        for (int k = 0; k < CRATES; k++)
            CHECK(t->rest_y[k] == ref.rest_y[k], "crate %d rests at %.3f, alone at %.3f", k, t->rest_y[k],
                  ref.rest_y[k]);
        stale += t->stale_tried;
    }
    t = &ref;
    CHECK(lines == ROUNDS * THREADS * ref_lines, "the hook got %d lines, expected %d", lines, ROUNDS * THREADS * ref_lines);
    CHECK(stale > 0, "no stale handle was tried");
    pp_set_log_hook(NULL, NULL);
    printf("tsan_worlds: %d threads × %d rounds, %d stale handles tried, %d log lines: %s, %.2f s\n", THREADS, ROUNDS, stale, lines,
           failures ? "FAILED" : "ok", seconds_since(&start));
    return failures ? 1 : 0;
}
