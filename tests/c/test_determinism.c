/* The same scene stepped twice in one process gives bit-identical poses, also when other
 * worlds are stepped in between (ODE's random generator is process-wide), and the same pinned hash
 * per preset in every build, on the CPU and on the GPU. */
#include "helpers.h"
#include "workers.h" /* WORKERS_MIN_CELLS: when the cores share */

PP_TEST_SUITE(determinism);

#define DET_BOXES 6
#define DET_STEPS 300

typedef struct det_scene {
    pp_world w;
    pp_body boxes[DET_BOXES];
    uint64_t hash;
    int max_contacts;
} det_scene;

static void det_begin_def(det_scene *s, const pp_world_def *def) {
    s->w = make_world_def(def);
    add_rect(s->w, body_def(PP_BODY_STATIC, 400, 520, 0), 800, 40);
    for (int i = 0; i < DET_BOXES; i++) {
        /* Boxes of three sizes, staggered so that they land on one another. */
        int size = 20 + 6 * (i % 3);
        pp_body_def d = body_def(PP_BODY_DYNAMIC, 380.0f + 13.0f * (i % 3), 440.0f - 45.0f * i, 0.15f * (i - 2));
        d.angular_velocity = 0.3f * ((i % 2) ? 1 : -1);
        s->boxes[i] = add_rect(s->w, d, size, size);
    }
    s->hash = FNV_START;
    s->max_contacts = 0;
}

static void det_begin(det_scene *s) {
    const pp_world_def d = pp_world_def_default();
    det_begin_def(s, &d);
}

static void det_step(det_scene *s) {
    PP_OK_OR_FAIL(pp_world_step(s->w, 1.0f / 60.0f));
    for (int i = 0; i < DET_BOXES; i++) {
        pp_vec2 p, v;
        float a, av;
        PP_OK_OR_FAIL(pp_body_get_position(s->w, s->boxes[i], &p));
        PP_OK_OR_FAIL(pp_body_get_angle(s->w, s->boxes[i], &a));
        PP_OK_OR_FAIL(pp_body_get_velocity(s->w, s->boxes[i], &v, &av));
        s->hash = fnv1a(s->hash, &p, sizeof p);
        s->hash = fnv1a(s->hash, &a, sizeof a);
        s->hash = fnv1a(s->hash, &v, sizeof v);
        s->hash = fnv1a(s->hash, &av, sizeof av);
    }
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_contacts(s->w, NULL, 0, &n));
    if (n > s->max_contacts) s->max_contacts = n;
}

static uint64_t det_run_alone(int *max_contacts) {
    det_scene s;
    det_begin(&s);
    for (int k = 0; k < DET_STEPS; k++) det_step(&s);
    /* Non-vacuous: the boxes fell and touched. */
    pp_vec2 top = body_pos(s.w, s.boxes[DET_BOXES - 1]);
    cr_assert_gt(top.y, 440.0f - 45.0f * (DET_BOXES - 1) + 100.0f, "the top box did not fall (y = %g)", top.y);
    if (max_contacts) *max_contacts = s.max_contacts;
    pp_world_destroy(s.w);
    return s.hash;
}

Test(determinism, same_scene_twice_is_bit_identical, .timeout = 60) {
    int mc = 0;
    uint64_t h1 = det_run_alone(&mc);
    uint64_t h2 = det_run_alone(NULL);
    cr_log_info("determinism hash %016llx (max %d contacts in a step)", (unsigned long long)h1, mc);
    cr_assert_geq(mc, 4, "the boxes made only %d contacts: the scene tests nothing", mc);
    cr_assert_eq(h1, h2, "two runs of one scene differ: %016llx vs %016llx", (unsigned long long)h1,
                 (unsigned long long)h2);
}

Test(determinism, interleaved_worlds_match_a_lone_run, .timeout = 60) {
    uint64_t alone = det_run_alone(NULL);
    det_scene a, b;
    det_begin(&a);
    det_begin(&b);
    /* A third world with a different scene, stepped in between, draws on the same generator. */
    pp_world other = make_world(0, 500);
    add_rect(other, body_def(PP_BODY_STATIC, 200, 300, 0.1f), 400, 20);
    for (int i = 0; i < 4; i++) add_rect(other, body_def(PP_BODY_DYNAMIC, 150.0f + 25 * i, 250.0f - 30 * i, 0.2f * i), 16, 24);
    for (int k = 0; k < DET_STEPS; k++) {
        det_step(&a);
        PP_OK_OR_FAIL(pp_world_step(other, 1.0f / 45.0f));
        det_step(&b);
    }
    cr_assert_eq(a.hash, alone, "world A interleaved: %016llx, alone: %016llx", (unsigned long long)a.hash,
                 (unsigned long long)alone);
    cr_assert_eq(b.hash, alone, "world B interleaved: %016llx, alone: %016llx", (unsigned long long)b.hash,
                 (unsigned long long)alone);
    uint64_t ha = 0, hb = 0, ho = 0;
    PP_OK_OR_FAIL(pp_world_get_hash(a.w, &ha));
    PP_OK_OR_FAIL(pp_world_get_hash(b.w, &hb));
    PP_OK_OR_FAIL(pp_world_get_hash(other, &ho));
    cr_assert_eq(ha, hb, "the library hashes A to %016llx, B to %016llx", (unsigned long long)ha, (unsigned long long)hb);
    cr_assert_neq(ha, ho);
    pp_world_destroy(a.w);
    pp_world_destroy(b.w);
    pp_world_destroy(other);
}

/* A world whose pairs are big enough for the narrowphase to share them over threads: crates on a
 * terrain with a pillar, so that each crate's whole box lies inside the terrain's solid bounds. */
static uint64_t threaded_run(int32_t worker_threads, int32_t *max_threads) {
    pp_world_def d = pp_world_def_default();
    d.worker_threads = worker_threads;
    pp_world w = make_world_def(&d);
    enum { TW = 900, TH = 300, CRATES = 10 };
    uint8_t *terrain = calloc((size_t)TW * TH, 1);
    cr_assert_not_null(terrain);
    for (int y = 0; y < TH; y++)
        for (int x = 0; x < TW; x++)
            terrain[y * TW + x] = y >= TH - 40 || x < 8;
    pp_body_def t = body_def(PP_BODY_STATIC, 450, 450, 0);
    t.width = TW, t.height = TH, t.mask = terrain;
    create_body_ok(w, &t);
    free(terrain);
    pp_body crates[CRATES];
    for (int i = 0; i < CRATES; i++)
        crates[i] = add_rect(w, body_def(PP_BODY_DYNAMIC, 60.0f + 80.0f * i, 520.0f - 20.0f * (i % 3), 0.1f * (i % 4)), 60, 60);
    uint64_t h = FNV_START;
    *max_threads = 0;
    for (int k = 0; k < 120; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
        pp_step_stats st;
        PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
        if (st.threads > *max_threads) *max_threads = st.threads;
        uint64_t state = 0; /* the library's hash of everything the next steps depend on */
        PP_OK_OR_FAIL(pp_world_get_hash(w, &state));
        h = fnv1a(h, &state, sizeof state);
    }
    pp_vec2 p = body_pos(w, crates[0]);
    cr_assert(p.y > 500 && p.y < 580, "crate 0 did not land on the terrain (y = %g)", p.y);
    pp_world_destroy(w);
    return h;
}

Test(determinism, worker_threads_give_the_result_of_one, .timeout = 60) {
    int32_t used1, used4, used_auto;
    const uint64_t h1 = threaded_run(1, &used1), h4 = threaded_run(4, &used4), h_auto = threaded_run(0, &used_auto);
    cr_assert_eq(used1, 1, "worker_threads 1 ran on %d threads", used1);
    cr_assert_eq(used4, 4, "worker_threads 4 never ran on 4 threads (at most %d): the test shares nothing", used4);
    cr_assert_geq(used_auto, 1);
    cr_assert_eq(h1, h4, "1 thread: %016llx, 4 threads: %016llx", (unsigned long long)h1, (unsigned long long)h4);
    cr_assert_eq(h1, h_auto, "1 thread: %016llx, one per CPU: %016llx", (unsigned long long)h1,
                 (unsigned long long)h_auto);
}

/* The hash of the scene above per preset, pinned: a change that moves any body of it by one bit in any step
 * changes them. Pinned on x86-64 with Debian's ODE 0.16 (double precision) and glibc's libm. */
static const struct {
    pp_preset preset;
    const char *name;
    uint64_t hash;
} golden[] = {
    {PP_PRESET_FAST, "FAST", 0x04dc08de2c68889dull},
    {PP_PRESET_BALANCED, "BALANCED", 0xf82416a238d400adull},
    {PP_PRESET_ACCURATE, "ACCURATE", 0xf82416a238d400adull},
};

static uint64_t golden_run(pp_preset preset, pp_backend backend) {
    pp_world_def d = pp_world_def_preset(preset);
    d.backend = backend;
    det_scene s;
    det_begin_def(&s, &d);
    for (int k = 0; k < DET_STEPS; k++) det_step(&s);
    pp_step_stats st;
    PP_OK_OR_FAIL(pp_world_get_stats(s.w, &st));
    cr_assert_eq(st.backend, backend, "the scene ran on backend %d, not %d", (int)st.backend, (int)backend);
    cr_assert_geq(s.max_contacts, 4, "the boxes made only %d contacts: the scene tests nothing", s.max_contacts);
    pp_world_destroy(s.w);
    return s.hash;
}

static void expect_golden(pp_backend backend, const char *backend_name) {
    for (size_t i = 0; i < sizeof golden / sizeof golden[0]; i++) {
        const uint64_t h = golden_run(golden[i].preset, backend);
        cr_log_info("golden %s %s: %#018llx", backend_name, golden[i].name, (unsigned long long)h);
        cr_expect_eq(h, golden[i].hash,
                     "%s on the %s backend hashes to %#018llx, pinned %#018llx: the scene moves differently. "
                     "If this change is meant to alter the physics, re-pin the value in tests/c/test_determinism.c "
                     "(and say so in the commit); if not, it is a regression.",
                     golden[i].name, backend_name, (unsigned long long)h, (unsigned long long)golden[i].hash);
    }
}

Test(determinism, the_cpu_backend_gives_the_pinned_hash_per_preset, .timeout = 120) {
    expect_golden(PP_BACKEND_CPU, "CPU");
}

/* The GPU makes the CPU's decisions pixel for pixel, so the pinned values hold there too. */
Test(determinism, the_gpu_backend_gives_the_pinned_hash_per_preset, .timeout = 300) {
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_GPU;
    pp_world w = {0};
    const pp_status st = pp_world_create(&d, &w);
    if (st != PP_OK) {
        cr_assert_eq(st, PP_ERR_UNSUPPORTED, "a failed GPU world must say UNSUPPORTED, got %s", pp_status_name(st));
        skip_without_gpu(pp_last_error());
    }
    pp_world_destroy(w);
    expect_golden(PP_BACKEND_GPU, "GPU");
}

/* A bin of 300 crates of 5 px: several hundred pairs a step, each of a few dozen cells. The pairs' set-up and
 * contacts are shared over the threads from WORKERS_MIN_PAIRS pairs; the cores, from WORKERS_MIN_CELLS cells.
 * *shared_alone counts the steps whose threads came from the host work alone (under WORKERS_MIN_CELLS cells). */
static uint64_t small_crates_run(int32_t worker_threads, int32_t *max_threads, int *shared_alone) {
    enum { CRATES = 300, SIDE = 5, STEPS = 90 };
    pp_world_def d = pp_world_def_default();
    d.worker_threads = worker_threads;
    d.allow_sleep = 0;
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 200, 410, 0), 400, 20);
    add_rect(w, body_def(PP_BODY_STATIC, 115, 300, 0), 10, 200);
    add_rect(w, body_def(PP_BODY_STATIC, 285, 300, 0), 10, 200);
    pp_body crates[CRATES];
    for (int i = 0; i < CRATES; i++)
        crates[i] = add_rect(w, body_def(PP_BODY_DYNAMIC, 125.0f + 6.5f * (i % 24), 395.0f - 6.5f * (i / 24),
                                         0.05f * (i % 5)), SIDE, SIDE);
    uint64_t h = FNV_START;
    *max_threads = 0, *shared_alone = 0;
    for (int k = 0; k < STEPS; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
        pp_step_stats st;
        PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
        *max_threads = st.threads > *max_threads ? st.threads : *max_threads;
        *shared_alone += st.threads > 1 && st.pixels_tested < WORKERS_MIN_CELLS;
        uint64_t state = 0;
        PP_OK_OR_FAIL(pp_world_get_hash(w, &state));
        h = fnv1a(h, &state, sizeof state);
    }
    const pp_vec2 p = body_pos(w, crates[0]);
    cr_assert(p.y > 390 && p.y < 400, "the bottom crate is not on the floor (y = %g)", p.y);
    pp_world_destroy(w);
    return h;
}

Test(determinism, pairs_set_up_and_finished_on_threads_give_the_result_of_one, .timeout = 60) {
    int32_t used1, used3;
    int alone1, alone3;
    const uint64_t h1 = small_crates_run(1, &used1, &alone1), h3 = small_crates_run(3, &used3, &alone3);
    cr_log_info("300 crates of 5 px, 90 steps: %d steps shared only their set-up and contacts", alone3);
    cr_assert_eq(used1, 1, "worker_threads 1 ran on %d threads", used1);
    cr_assert_eq(used3, 3, "worker_threads 3 never ran on 3 threads (at most %d)", used3);
    cr_assert_gt(alone3, 10, "only %d steps shared their set-up and contacts without their cores: the test shares "
                             "little of them", alone3);
    cr_assert_eq(h1, h3, "1 thread: %016llx, 3 threads: %016llx", (unsigned long long)h1, (unsigned long long)h3);
}
