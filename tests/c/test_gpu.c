/* The GPU backend against the CPU reference: the same contacts bit for bit on random pairs, the
 * same determinism hash over a 600-step scene, and a clear status where no GPU context exists.
 * Where EGL gives no GLES 3.1 compute context the comparisons are skipped with the reason. */
#include "helpers.h"

PP_TEST_SUITE(gpu);

/* Can this machine make a GPU world? If not, *why gets pp_last_error(). */
static int gpu_available(char *why, size_t n) {
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_GPU;
    pp_world w = {0};
    pp_status st = pp_world_create(&d, &w);
    if (st != PP_OK) {
        cr_assert_eq(st, PP_ERR_UNSUPPORTED, "a failed GPU world must say UNSUPPORTED, got %s", pp_status_name(st));
        snprintf(why, n, "%s", pp_last_error());
        return 0;
    }
    pp_world_destroy(w);
    return 1;
}

#define SKIP_WITHOUT_GPU()                                                   \
    do {                                                                     \
        char why_[512];                                                      \
        if (!gpu_available(why_, sizeof why_))                               \
            skip_without_gpu(why_);                                          \
    } while (0)

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static uint32_t rnd(void) {
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (uint32_t)(rng_state >> 32);
}
static double rnd01(void) { return rnd() / 4294967296.0; }

/* A random w×h mask: a box, an ellipse, noise, or an ellipse with holes. Caller frees. */
static uint8_t *random_mask(int w, int h) {
    uint8_t *m = calloc((size_t)w * h, 1);
    cr_assert_not_null(m);
    const int kind = (int)(rnd() % 4);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const double u = (x + 0.5) / w * 2 - 1, v = (y + 0.5) / h * 2 - 1;
            m[(size_t)y * w + x] = kind == 0 ? 1 : kind == 2 ? (rnd() & 1) : u * u + v * v <= 1.0;
        }
    if (kind == 3)
        for (int k = 0; k < 6; k++) {
            const double cx = rnd01() * w, cy = rnd01() * h, r = (0.05 + 0.15 * rnd01()) * (w < h ? w : h);
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++)
                    if ((x - cx) * (x - cx) + (y - cy) * (y - cy) < r * r)
                        m[(size_t)y * w + x] = 0;
        }
    m[(size_t)(h / 2) * w + w / 2] = 1; /* never empty: a massless dynamic body is refused */
    return m;
}

/* Sizes 1..512, log-uniform, so tiny and huge bodies are both common. */
static int random_side(void) { return (int)exp(rnd01() * log(512.0)) + (rnd() % 2); }

static int same_contacts(const pp_contact *a, const pp_contact *b, int n) {
    for (int k = 0; k < n; k++)
        if (memcmp(&a[k].point, &b[k].point, sizeof a[k].point) || memcmp(&a[k].normal, &b[k].normal, sizeof a[k].normal) ||
            memcmp(&a[k].depth, &b[k].depth, sizeof a[k].depth) || a[k].pixel_count != b[k].pixel_count)
            return 0;
    return 1;
}

/* A default world on the CPU backend (gpu 0) or the GPU backend (gpu 1). */
static pp_world backend_world(int gpu) {
    pp_world_def d = pp_world_def_default();
    d.backend = gpu ? PP_BACKEND_GPU : PP_BACKEND_CPU;
    return make_world_def(&d);
}

#define PARITY_PAIRS 1000
#define COMBOS 4 /* normal method × contact mode */

Test(gpu, random_pairs_match_the_cpu_bit_for_bit, .timeout = 300) {
    SKIP_WITHOUT_GPU();
    pp_world cpu[COMBOS], gpu[COMBOS];
    for (int c = 0; c < COMBOS; c++) {
        pp_world_def d = pp_world_def_default();
        d.normal_method = (c & 1) ? PP_NORMAL_KERNEL : PP_NORMAL_AREA_GRADIENT;
        d.contact_mode = (c & 2) ? PP_CONTACT_CENTROID : PP_CONTACT_MANIFOLD;
        d.backend = PP_BACKEND_CPU;
        cpu[c] = make_world_def(&d);
        d.backend = PP_BACKEND_GPU;
        gpu[c] = make_world_def(&d);
    }
    int touching = 0, two_point = 0, mismatches = 0, big = 0;
    for (int i = 0; i < PARITY_PAIRS; i++) {
        int side[4];
        for (int k = 0; k < 4; k++) side[k] = random_side();
        uint8_t *ma = random_mask(side[0], side[1]), *mb = random_mask(side[2], side[3]);
        big += side[0] * side[1] >= 256 * 256 || side[2] * side[3] >= 256 * 256;
        /* B's centre somewhere over A's box, both at random angles. */
        pp_body_def da = body_def(PP_BODY_STATIC, 1000, 1000, (float)(rnd01() * 2 * M_PI));
        da.width = side[0], da.height = side[1], da.mask = ma;
        pp_body_def db = body_def(PP_BODY_DYNAMIC, 1000 + (float)((rnd01() - 0.5) * (side[0] + side[2] * 0.5)),
                                  1000 + (float)((rnd01() - 0.5) * (side[1] + side[3] * 0.5)), (float)(rnd01() * 2 * M_PI));
        db.width = side[2], db.height = side[3], db.mask = mb;
        for (int c = 0; c < COMBOS; c++) {
            const pp_body ac = create_body_ok(cpu[c], &da), bc = create_body_ok(cpu[c], &db);
            const pp_body ag = create_body_ok(gpu[c], &da);
            const pp_body bg = create_body_ok(gpu[c], &db);
            pp_contact kc[2], kg[2];
            int32_t nc = -1, ng = -1;
            PP_OK_OR_FAIL(pp_world_collide(cpu[c], ac, bc, kc, 2, &nc));
            PP_OK_OR_FAIL(pp_world_collide(gpu[c], ag, bg, kg, 2, &ng));
            if (nc != ng || !same_contacts(kc, kg, nc)) {
                if (mismatches++ < 5)
                    cr_log_error("pair %d (%dx%d vs %dx%d) combo %d: cpu %d contacts, gpu %d; first cpu (%.9g,%.9g) "
                                 "n (%.9g,%.9g) d %.9g px %d, gpu (%.9g,%.9g) n (%.9g,%.9g) d %.9g px %d",
                                 i, side[0], side[1], side[2], side[3], c, nc, ng, kc[0].point.x, kc[0].point.y,
                                 kc[0].normal.x, kc[0].normal.y, kc[0].depth, kc[0].pixel_count, kg[0].point.x,
                                 kg[0].point.y, kg[0].normal.x, kg[0].normal.y, kg[0].depth, kg[0].pixel_count);
            }
            touching += nc > 0;
            two_point += nc == 2;
            pp_body_destroy(cpu[c], ac), pp_body_destroy(cpu[c], bc);
            pp_body_destroy(gpu[c], ag), pp_body_destroy(gpu[c], bg);
        }
        free(ma);
        free(mb);
    }
    cr_log_info("gpu parity: %d pairs x %d settings, %d touching, %d with two points, %d with a side >= 256 px, "
                "%d mismatches", PARITY_PAIRS, COMBOS, touching, two_point, big, mismatches);
    cr_assert_eq(mismatches, 0, "%d of %d comparisons differ", mismatches, PARITY_PAIRS * COMBOS);
    cr_assert_gt(touching, PARITY_PAIRS * COMBOS / 2, "only %d comparisons had contacts", touching);
    cr_assert_gt(two_point, PARITY_PAIRS / 2, "only %d comparisons had two-point manifolds", two_point);
    for (int c = 0; c < COMBOS; c++) {
        pp_world_destroy(cpu[c]);
        pp_world_destroy(gpu[c]);
    }
}

/* A 600-step pile of boxes and discs: the hash of every pose on both backends. */
static uint64_t pile_hash(pp_backend backend, int *pair_steps, int *gpu_steps) {
    pp_world_def d = pp_world_def_default();
    d.backend = backend;
    d.allow_sleep = 0; /* every step has pairs: since issue 22 the pile slept by step 127 */
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 400, 560, 0), 800, 40);
    add_rect(w, body_def(PP_BODY_STATIC, 250, 470, 0.4f), 200, 30);
    pp_body bodies[14];
    for (int i = 0; i < 14; i++) {
        pp_body_def bd = body_def(PP_BODY_DYNAMIC, 200.0f + 37.0f * (i % 7), 300.0f - 50.0f * (i / 7), 0.2f * i);
        bodies[i] = (i % 4 == 3) ? add_disc(w, bd, 12 + i) : add_rect(w, bd, 16 + 3 * i, 20 + (i % 3) * 9);
    }
    uint64_t h = FNV_START;
    *pair_steps = *gpu_steps = 0;
    for (int s = 0; s < 600; s++) {
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
        pp_step_stats st;
        PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
        *pair_steps += st.pairs > 0;
        *gpu_steps += st.pairs > 0 && st.backend == PP_BACKEND_GPU;
        for (int i = 0; i < 14; i++) {
            pp_vec2 p = body_pos(w, bodies[i]);
            float a = body_angle(w, bodies[i]);
            h = fnv1a(fnv1a(h, &p, sizeof p), &a, sizeof a);
        }
    }
    /* Non-vacuous: the pile fell onto the ground. */
    cr_assert_gt(body_pos(w, bodies[13]).y, 400.0f, "the top of the pile did not fall");
    pp_world_destroy(w);
    return h;
}

Test(gpu, a_600_step_scene_hashes_the_same_on_both_backends, .timeout = 120) {
    SKIP_WITHOUT_GPU();
    int cpu_pair_steps, cpu_gpu_steps, gpu_pair_steps, gpu_gpu_steps;
    const uint64_t hc = pile_hash(PP_BACKEND_CPU, &cpu_pair_steps, &cpu_gpu_steps);
    const uint64_t hg = pile_hash(PP_BACKEND_GPU, &gpu_pair_steps, &gpu_gpu_steps);
    cr_log_info("determinism hash over 600 steps: CPU %016llx, GPU %016llx (%d steps with pairs, all on the GPU: %d)",
                (unsigned long long)hc, (unsigned long long)hg, gpu_pair_steps, gpu_gpu_steps);
    cr_assert_eq(cpu_gpu_steps, 0, "a CPU world reported the GPU backend");
    cr_assert_gt(gpu_pair_steps, 200, "only %d steps had pairs: the scene tests little", gpu_pair_steps);
    cr_assert_eq(gpu_gpu_steps, gpu_pair_steps, "%d of %d steps with pairs ran on the GPU", gpu_gpu_steps,
                 gpu_pair_steps);
    cr_assert_eq(hc, hg, "the backends diverge: CPU %016llx, GPU %016llx", (unsigned long long)hc,
                 (unsigned long long)hg);
}

/* 150 boxes spawned into one spot: the contact budget's choices (crowd.c) come from contacts and slots, so
 * both backends keep the same pairs; poses over 15 steps, hashed. Thousands of pairs a step: on the GPU
 * backend their set-up and contacts are shared over the world's threads. */
static pp_world crowd_world(pp_backend backend, int32_t worker_threads) {
    pp_world_def d = pp_world_def_default();
    d.backend = backend;
    d.worker_threads = worker_threads;
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 1000, 1010, 0), 8000, 20);
    for (int i = 0; i < 150; i++)
        add_rect(w, body_def(PP_BODY_DYNAMIC, 1000.0f + (i % 5) * 0.5f, 900.0f, 0.1f * (i % 7)), 8, 8);
    return w;
}

/* 15 steps of crowd_world's w, which it destroys: the boxes' poses hashed. */
static uint64_t crowd_run(pp_world w, int *gpu_steps, int32_t *max_threads) {
    pp_body all[151], *b = all + 1; /* the ground, then the boxes, in slot order */
    int32_t count;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, all, 151, &count));
    cr_assert_eq(count, 151);
    uint64_t h = FNV_START;
    *gpu_steps = *max_threads = 0;
    for (int s = 0; s < 15; s++) {
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
        pp_step_stats st;
        PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
        *gpu_steps += st.backend == PP_BACKEND_GPU;
        *max_threads = st.threads > *max_threads ? st.threads : *max_threads;
        for (int i = 0; i < 150; i++) {
            const pp_vec2 p = body_pos(w, b[i]);
            h = fnv1a(h, &p, sizeof p);
        }
    }
    pp_world_destroy(w);
    return h;
}

Test(gpu, a_crowded_spawn_keeps_the_same_contacts_on_both_backends, .timeout = 120) {
    SKIP_WITHOUT_GPU();
    int cpu_gpu_steps, gpu_steps;
    int32_t cpu_threads, gpu_threads;
    const uint64_t hc = crowd_run(crowd_world(PP_BACKEND_CPU, 1), &cpu_gpu_steps, &cpu_threads);
    const uint64_t hg = crowd_run(crowd_world(PP_BACKEND_GPU, 3), &gpu_steps, &gpu_threads);
    cr_assert_eq(cpu_gpu_steps, 0, "a CPU world reported the GPU backend");
    cr_assert_eq(gpu_steps, 15, "%d of 15 steps ran on the GPU", gpu_steps);
    cr_assert_eq(cpu_threads, 1, "the CPU world on one thread ran on %d", cpu_threads);
    cr_assert_eq(gpu_threads, 3, "the GPU world's host work ran on at most %d of its 3 threads", gpu_threads);
    cr_assert_eq(hc, hg, "the backends diverge on a crowded spawn: CPU %016llx, GPU %016llx", (unsigned long long)hc,
                 (unsigned long long)hg);
}

/* Without a usable EGL the GPU world is refused with the reason; CPU and AUTO worlds still work. */
Test(gpu, without_egl_gpu_is_unsupported_and_auto_runs_on_the_cpu) {
    setenv("PHYSPIX_LIBEGL", "/nonexistent/libEGL.so.1", 1);
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_GPU;
    pp_world w = {0};
    EXPECT_ERR(pp_world_create(&d, &w), PP_ERR_UNSUPPORTED, "libEGL");
    cr_assert_eq(w.id, 0, "a failed create wrote a handle");
    EXPECT_ERR(pp_world_create(&d, &w), PP_ERR_UNSUPPORTED, "libEGL"); /* the same answer, not a crash */

    /* AUTO with a batch large enough to want the GPU: it falls back and steps on the CPU. */
    d.backend = PP_BACKEND_AUTO;
    w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 600, 600, 0), 1200, 1200);
    add_rect(w, body_def(PP_BODY_DYNAMIC, 600, 600, 0.3f), 700, 700);
    PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
    pp_step_stats st;
    PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
    cr_assert_eq(st.pairs, 1);
    cr_assert_gt(st.pixels_tested, 400000, "the batch (%lld samples) is too small to ask for the GPU",
                 (long long)st.pixels_tested);
    cr_assert_eq(st.backend, PP_BACKEND_CPU, "AUTO reported backend %d with no EGL", (int)st.backend);
    cr_assert_gt(st.contacts, 0);
    pp_world_destroy(w);
}

/* A 16384 px strip on a 16384 px ground: sample points past 2^30 in 16.16, near the edge of the
 * GPU's 32-bit arithmetic. The contacts must still be the same. */
Test(gpu, the_widest_bitmaps_match_at_the_edge_of_32_bit_sampling, .timeout = 60) {
    SKIP_WITHOUT_GPU();
    pp_contact kc[2], kg[2];
    int32_t n[2] = {-1, -1};
    for (int g = 0; g < 2; g++) {
        pp_world w = backend_world(g);
        pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 8192, 1032, 0), 16384, 64);
        pp_body strip = add_rect(w, body_def(PP_BODY_DYNAMIC, 8192, 1000, 0.0002f), 16384, 8);
        PP_OK_OR_FAIL(pp_world_collide(w, strip, ground, g ? kg : kc, 2, &n[g]));
        pp_world_destroy(w);
    }
    cr_assert_eq(n[0], 2, "the strip resting 4 px deep should touch at both ends, got %d contacts", n[0]);
    cr_assert_eq(n[1], n[0]);
    cr_assert(same_contacts(kc, kg, n[0]), "CPU (%.9g, %.9g) d %.9g vs GPU (%.9g, %.9g) d %.9g", kc[0].point.x,
              kc[0].point.y, kc[0].depth, kg[0].point.x, kg[0].point.y, kg[0].depth);
    cr_assert_float_eq(kc[0].normal.y, 1.0f, 1e-3f, "normal (%g, %g)", kc[0].normal.x, kc[0].normal.y);
}

/* After an edit the GPU sees the new shape: only the dirty rows are rewritten, and the contacts
 * still equal the CPU's, edit after edit (a stale mirror would keep the old contacts). */
Test(gpu, edited_bodies_match_the_cpu_after_every_edit, .timeout = 60) {
    SKIP_WITHOUT_GPU();
    pp_world w[2];
    pp_body ground[2], box[2];
    for (int g = 0; g < 2; g++) {
        w[g] = backend_world(g);
        ground[g] = add_rect(w[g], body_def(PP_BODY_STATIC, 400, 500, 0), 800, 40);
        box[g] = add_rect(w[g], body_def(PP_BODY_DYNAMIC, 400, 466, 0.1f), 48, 48);
    }
    int differ = 0, changes = 0;
    for (int k = 0; k < 12; k++) {
        pp_contact c[2][2];
        int32_t n[2];
        for (int g = 0; g < 2; g++) {
            PP_OK_OR_FAIL(pp_world_collide(w[g], box[g], ground[g], c[g], 2, &n[g]));
            int32_t changed;
            /* Bite the ground's top edge under the box, a little further each time. */
            PP_OK_OR_FAIL(pp_body_erase_circle(w[g], ground[g], v2(370.0f + 6.0f * k, 482), 5, &changed));
            if (g) changes += changed;
        }
        differ += n[0] != n[1] || !same_contacts(c[0], c[1], n[0]);
    }
    cr_assert_gt(changes, 300, "the edits changed only %d pixels", changes);
    cr_assert_eq(differ, 0, "%d of 12 collisions differ after edits", differ);
    for (int g = 0; g < 2; g++) pp_world_destroy(w[g]);
}

/* Two large boxes overlapping deeply: most of the GPU's tiles are all intersection, summed on the host in closed
 * form and splatted into the strips without a sample, and the contacts are still the CPU's. */
static void deep_overlap(pp_world w, pp_body *ground, pp_body *box) {
    *ground = add_rect(w, body_def(PP_BODY_STATIC, 1000, 1000, 0.2f), 400, 400);
    *box = add_rect(w, body_def(PP_BODY_DYNAMIC, 1040, 980, 0.7f), 300, 300);
}

Test(gpu, a_deep_overlap_sums_its_inside_in_closed_form_and_matches_the_cpu, .timeout = 60) {
    SKIP_WITHOUT_GPU();
    pp_contact c[2][2];
    int32_t n[2] = {-1, -1};
    for (int g = 0; g < 2; g++) {
        pp_world w = backend_world(g);
        pp_body ground, box;
        deep_overlap(w, &ground, &box);
        PP_OK_OR_FAIL(pp_world_collide(w, box, ground, c[g], 2, &n[g]));
        pp_world_destroy(w);
    }
    cr_assert_gt(n[0], 0, "the boxes overlap");
    cr_assert_gt(c[0][0].pixel_count, 50000, "deeply: %d pixels", c[0][0].pixel_count);
    cr_assert_eq(n[1], n[0]);
    cr_assert(same_contacts(c[0], c[1], n[0]), "CPU (%.9g, %.9g) d %.9g vs GPU (%.9g, %.9g) d %.9g", c[0][0].point.x,
              c[0][0].point.y, c[0][0].depth, c[1][0].point.x, c[1][0].point.y, c[1][0].depth);
}

#ifdef PP_TEST_PRIVATE
#include "world.h" /* a pair's grid, and the narrowphase's cores */

enum { GPU_TILE = 16 };

typedef struct tile_count {
    uint8_t *kind; /* by tile: 0 skipped, 1 mixed, 2 full */
    int mixed, full;
} tile_count;

static void count_tile(void *user, int32_t tile, bool full) {
    tile_count *t = user;
    cr_assert_eq(t->kind[tile], 0, "tile %d visited twice", tile);
    t->kind[tile] = full ? 2 : 1;
    full ? t->full++ : t->mixed++;
}

/* The narrowphase's pair of box (the reference) and ground in world w, and the world's settings in *set. */
static np_pair pair_set_up(pp_world w, pp_body box, pp_body ground, np_settings *set) {
    world *wd = world_lookup(w, "test");
    cr_assert_not_null(wd);
    *set = world_np_settings(wd);
    const np_body va = body_np_view(body_find(wd, box)), vb = body_np_view(body_find(wd, ground));
    np_pair p;
    cr_assert(np_pair_setup(set, &va, &vb, &p));
    return p;
}

/* np_classify_tiles against the plain per-cell core on the deep overlap: a full tile's cells all lie in both bodies
 * and its closed-form sums are theirs, a skipped tile holds no intersection cell, and the full tiles' count plus the
 * mixed tiles' intersection cells is the dense core's count. */
Test(gpu, tiles_sorted_for_the_gpu_add_up_to_the_dense_core) {
    pp_world w = make_world(0, 0);
    pp_body ground, box;
    deep_overlap(w, &ground, &box);
    np_settings set;
    const np_pair p = pair_set_up(w, box, ground, &set);
    const int32_t tx = (p.nx + GPU_TILE - 1) / GPU_TILE, ty = (p.ny + GPU_TILE - 1) / GPU_TILE;
    tile_count t = {calloc((size_t)tx * ty, 1), 0, 0};
    uint8_t *flags = malloc((size_t)p.nx * p.ny);
    int32_t *kernel = malloc((size_t)p.nx * p.ny * 2 * sizeof *kernel);
    cr_assert(t.kind && flags && kernel);
    np_core sums = {0}, dense;
    np_classify_tiles(&p, GPU_TILE, count_tile, &t, &sums);
    np_scratch scratch = {0};
    PP_OK_OR_FAIL(narrow_cpu_core_dense(&set, &p, &scratch, &dense));
    PP_OK_OR_FAIL(narrow_cpu_debug(&p, &scratch, flags, kernel));
    int64_t in_full = 0, in_mixed = 0, in_skipped = 0, sx = 0, sy = 0;
    for (int32_t y = 0; y < p.ny; y++)
        for (int32_t x = 0; x < p.nx; x++) {
            const int kind = t.kind[(y / GPU_TILE) * tx + x / GPU_TILE];
            const bool both = (flags[(int64_t)y * p.nx + x] & 3) == 3;
            cr_assert(kind != 2 || both, "cell (%d, %d) of a full tile is not in both bodies", x, y);
            in_full += kind == 2, in_mixed += kind == 1 && both, in_skipped += kind == 0 && both;
            sx += kind == 2 ? x : 0, sy += kind == 2 ? y : 0;
        }
    cr_log_info("%d x %d tiles: %d full, %d mixed, %d skipped; intersection cells %lld = %lld full + %lld mixed",
                tx, ty, t.full, t.mixed, tx * ty - t.full - t.mixed, (long long)dense.count, (long long)in_full,
                (long long)in_mixed);
    cr_assert_gt(t.full, 2 * t.mixed, "the inside is most of the overlap: %d full, %d mixed tiles", t.full, t.mixed);
    cr_assert_gt(tx * ty - t.full - t.mixed, 0, "some tiles lie outside the overlap");
    cr_assert_eq(in_skipped, 0, "a skipped tile holds %lld intersection cells", (long long)in_skipped);
    cr_assert_eq(sums.count, in_full, "closed-form count %lld, cells %lld", (long long)sums.count, (long long)in_full);
    cr_assert_eq(sums.sx, sx);
    cr_assert_eq(sums.sy, sy);
    cr_assert_eq(sums.count + in_mixed, dense.count, "%lld + %lld against the dense core's %lld", (long long)sums.count,
                 (long long)in_mixed, (long long)dense.count);
    np_scratch_free(&scratch);
    free(t.kind), free(flags), free(kernel);
    pp_world_destroy(w);
}

/* np_classify_tiles' mixed and full tiles of the box on the ground, and the collision's contacts. */
static void cpu_tile_sort(pp_world w, pp_body box, pp_body ground, tile_count *t, pp_contact *c, int32_t *n) {
    np_settings set;
    const np_pair p = pair_set_up(w, box, ground, &set);
    const int32_t tiles = ((p.nx + GPU_TILE - 1) / GPU_TILE) * ((p.ny + GPU_TILE - 1) / GPU_TILE);
    *t = (tile_count){calloc((size_t)tiles, 1), 0, 0};
    cr_assert_not_null(t->kind);
    np_core sums = {0};
    np_classify_tiles(&p, GPU_TILE, count_tile, t, &sums);
    free(t->kind);
    PP_OK_OR_FAIL(pp_world_collide(w, box, ground, c, 2, n));
}

/* The GPU's tiles pass sorts a pair's tiles as np_classify_tiles does, from the occupancy counts it mirrors: on the
 * deep overlap, then after holes bitten out of the box turn full tiles mixed (the mirror follows the edit). */
Test(gpu, the_tiles_pass_sorts_a_pairs_tiles_as_the_cpu_does, .timeout = 60) {
    SKIP_WITHOUT_GPU();
    pp_world w[2];
    pp_body ground[2], box[2];
    for (int g = 0; g < 2; g++) {
        w[g] = backend_world(g);
        deep_overlap(w[g], &ground[g], &box[g]);
    }
    const gpu_narrow *gpu = world_lookup(w[1], "test")->gpu;
    cr_assert_not_null(gpu);
    int64_t mixed0 = 0, full0 = 0, mixed_before = -1;
    for (int round = 0; round < 2; round++) {
        tile_count t[2];
        pp_contact c[2][2];
        int32_t n[2];
        for (int g = 0; g < 2; g++)
            cpu_tile_sort(w[g], box[g], ground[g], &t[g], c[g], &n[g]);
        int64_t mixed, full;
        gpu_narrow_tiles_sampled(gpu, &mixed, &full);
        cr_log_info("round %d: CPU %d mixed, %d full; GPU %lld mixed, %lld full", round, t[0].mixed, t[0].full,
                    (long long)(mixed - mixed0), (long long)(full - full0));
        cr_assert_eq(mixed - mixed0, t[0].mixed, "round %d: the GPU sampled %lld mixed tiles, the CPU sorts %d", round,
                     (long long)(mixed - mixed0), t[0].mixed);
        cr_assert_eq(full - full0, t[0].full, "round %d: the GPU summed %lld full tiles, the CPU sorts %d", round,
                     (long long)(full - full0), t[0].full);
        cr_assert_eq(n[1], n[0]);
        cr_assert(same_contacts(c[0], c[1], n[0]), "round %d: the contacts differ", round);
        if (round == 1)
            cr_assert_gt(t[0].mixed, mixed_before + 20, "the holes made %d mixed tiles of %lld", t[0].mixed,
                         (long long)mixed_before);
        mixed_before = t[0].mixed, mixed0 = mixed, full0 = full;
        for (int g = 0; g < 2 && round == 0; g++)
            for (int k = 0; k < 6; k++) {
                int32_t changed;
                PP_OK_OR_FAIL(pp_body_erase_circle(w[g], box[g], v2(980.0f + 25.0f * k, 1000.0f - 12.0f * k), 6,
                                                   &changed));
                cr_assert_gt(changed, 50, "hole %d bit %d pixels", k, changed);
            }
    }
    for (int g = 0; g < 2; g++)
        pp_world_destroy(w[g]);
}

/* The same crowded spawn with the GPU's dispatches cut into rows of two workgroups: every pass, the per-pair ones and
 * the indirect ones, then runs as a 2D grid of many rows, and the contacts are still the CPU's. */
Test(gpu, passes_dispatched_as_2d_grids_match_the_cpu, .timeout = 120) {
    SKIP_WITHOUT_GPU();
    int gpu_steps, cpu_gpu_steps;
    int32_t threads;
    pp_world w = crowd_world(PP_BACKEND_GPU, 1);
    gpu_narrow_limit_rows(world_lookup(w, "test")->gpu, 2);
    const uint64_t hg = crowd_run(w, &gpu_steps, &threads);
    const uint64_t hc = crowd_run(crowd_world(PP_BACKEND_CPU, 1), &cpu_gpu_steps, &threads);
    cr_assert_eq(gpu_steps, 15, "%d of 15 steps ran on the GPU", gpu_steps);
    cr_assert_eq(hc, hg, "rows of two workgroups diverge: CPU %016llx, GPU %016llx", (unsigned long long)hc,
                 (unsigned long long)hg);
}

#include "gpu_context.h" /* whether the context is up, and what it is */

static char auto_said[512]; /* AUTO's line on where it keeps the narrowphase */

static void keep_auto_line(int level, const char *msg, void *user) {
    (void)level, (void)user;
    if (strstr(msg, "AUTO keeps"))
        snprintf(auto_said, sizeof auto_said, "%s", msg);
}

/* AUTO never runs a CPU rasteriser, so where EGL lists only Mesa's software device (CI's llvmpipe) its first large
 * batch brings no context up: that cost 30 ms in the step (70 ms with Mesa's shader cache cold) for nothing. With a
 * hardware GPU AUTO brings it up, to have the choice. Either way the context made afterwards agrees. */
Test(gpu, auto_brings_up_no_context_where_it_could_only_be_a_cpu_rasteriser, .timeout = 60) {
    auto_said[0] = 0;
    pp_set_log_hook(keep_auto_line, NULL);
    int gpu_steps;
    int32_t threads;
    crowd_run(crowd_world(PP_BACKEND_AUTO, 1), &gpu_steps, &threads);
    pp_set_log_hook(NULL, NULL);
    const bool up = gpu_is_up();
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_GPU;
    pp_world g;
    if (pp_world_create(&d, &g) != PP_OK) {
        skip_without_gpu(pp_last_error());
        return;
    }
    const gpu_gl *gl;
    const gpu_info *info;
    PP_OK_OR_FAIL(gpu_acquire("test", &gl, &info));
    const bool software = info->software, llvmpipe = strstr(info->renderer, "llvmpipe") != NULL;
    gpu_release();
    pp_world_destroy(g);
    cr_log_info("context: %s; up after AUTO's steps: %d; AUTO said: %s", info->renderer, up, auto_said);
    if (software) {
        cr_assert_eq(gpu_steps, 0, "AUTO ran %d steps on a CPU rasteriser", gpu_steps);
        cr_assert(strstr(auto_said, "software rasteriser"), "AUTO said: \"%s\"", auto_said);
        cr_assert(!llvmpipe || !up, "AUTO brought llvmpipe's context up, which it never runs");
    } else {
        cr_assert(up, "AUTO had large batches and a hardware GPU but brought no context up");
        cr_assert_eq(auto_said[0], 0, "AUTO said: \"%s\"", auto_said);
    }
}
#endif
