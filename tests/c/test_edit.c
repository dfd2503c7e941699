/* Editing pixels: exact mass changes, incremental mass properties against a full recomputation,
 * momentum through a split, the ground erased under a box, emptied bodies destroyed with an event,
 * misuse, and an edited body on the GPU backend matching the CPU (only dirty rows re-uploaded). */
#include "helpers.h"

PP_TEST_SUITE(edit);

static void body_mass(pp_world w, pp_body b, float *m, pp_vec2 *c, float *inertia) {
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, m, c, inertia));
}

Test(edit, erasing_k_pixels_lowers_the_mass_by_k_times_density) {
    pp_world w = make_world(0, 0);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 200, 200, 0.3f);
    d.density = 2.5f;
    pp_body b = add_rect(w, d, 64, 40);
    float m0, m1;
    body_mass(w, b, &m0, NULL, NULL);
    int32_t k = -1;
    PP_OK_OR_FAIL(pp_body_erase_circle(w, b, v2(205, 195), 9.5f, &k));
    body_mass(w, b, &m1, NULL, NULL);
    cr_assert_gt(k, 200, "the circle erased only %d pixels", k);
    cr_assert_float_eq(m0 - m1, k * 2.5f, 1e-3f, "mass fell by %g for %d pixels of density 2.5", m0 - m1, k);
    /* Erasing the same circle again changes nothing. */
    PP_OK_OR_FAIL(pp_body_erase_circle(w, b, v2(205, 195), 9.5f, &k));
    cr_assert_eq(k, 0);
    pp_world_destroy(w);
}

/* Mass, centre and inertia of a fresh body made from the edited body's mask and weights. */
static void recomputed(const uint8_t *mask, const uint8_t *weights, int wd, int ht, float *m, pp_vec2 *c, float *inertia) {
    pp_world w = make_world(0, 0);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 0, 0, 0);
    d.width = wd, d.height = ht, d.mask = mask, d.weights = weights;
    pp_body b = create_body_ok(w, &d);
    body_mass(w, b, m, c, inertia);
    pp_world_destroy(w);
}

Test(edit, incremental_mass_properties_match_a_recomputation_after_1000_edits, .timeout = 60) {
    enum { W = 96, H = 64 };
    pp_world w = make_world(0, 0);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 300, 0.7f), W, H);
    uint8_t weights[W * H];
    memset(weights, 255, sizeof weights);
    uint64_t seed = 12345;
    for (int i = 0; i < 1000; i++) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        const uint32_t r = (uint32_t)(seed >> 33);
        const int x = (int)(r % W), y = (int)((r >> 8) % H), op = (int)((r >> 16) % 3);
        int32_t changed;
        if (op == 0) {
            pp_vec2 p;
            PP_OK_OR_FAIL(pp_body_get_position(w, b, &p));
            /* A small erase near the middle (world point of pixel (x, y) at angle 0.7). */
            const float lx = x + 0.5f - W / 2.0f, ly = y + 0.5f - H / 2.0f;
            const pp_vec2 c = v2(p.x + lx * cosf(0.7f) - ly * sinf(0.7f), p.y + lx * sinf(0.7f) + ly * cosf(0.7f));
            PP_OK_OR_FAIL(pp_body_erase_circle(w, b, c, 1.5f, &changed));
        } else {
            /* A 3×2 patch of random mask and weights. */
            uint8_t m6[6], w6[6];
            for (int k = 0; k < 6; k++) m6[k] = (uint8_t)((r >> (20 + k)) & 1 || op == 1), w6[k] = (uint8_t)(1 + (r >> k) % 255);
            PP_OK_OR_FAIL(pp_body_write_pixels(w, b, x, y, 3, 2, m6, w6));
            for (int k = 0; k < 6; k++)
                if (x + k % 3 < W && y + k / 3 < H) weights[(y + k / 3) * W + x + k % 3] = w6[k];
        }
    }
    uint8_t mask[W * H];
    PP_OK_OR_FAIL(pp_body_read_mask(w, b, mask, sizeof mask));
    int solid = 0;
    for (int k = 0; k < W * H; k++) solid += mask[k];
    cr_assert(solid > 100 && solid < W * H - 100, "the edits left %d solid pixels: too few to test", solid);
    float m, mr, inertia, ir;
    pp_vec2 c, cr_;
    body_mass(w, b, &m, &c, &inertia);
    recomputed(mask, weights, W, H, &mr, &cr_, &ir);
    cr_log_info("after 1000 edits: mass %.6g vs %.6g, centre (%.6g, %.6g) vs (%.6g, %.6g), inertia %.8g vs %.8g", m, mr,
                c.x, c.y, cr_.x, cr_.y, inertia, ir);
    cr_assert(fabsf(m - mr) <= 1e-4f * mr);
    cr_assert(fabsf(c.x - cr_.x) <= 1e-4f * W && fabsf(c.y - cr_.y) <= 1e-4f * H);
    cr_assert(fabsf(inertia - ir) <= 1e-4f * ir, "inertia %g vs %g", inertia, ir);
    pp_world_destroy(w);
}

/* Linear momentum and angular momentum about the world origin of all dynamic bodies. */
static void momentum(pp_world w, double *px, double *py, double *l) {
    pp_body bs[16];
    int32_t n;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bs, 16, &n));
    *px = *py = *l = 0;
    for (int i = 0; i < n; i++) {
        float m, inertia, om, ang;
        pp_vec2 c, v, p;
        body_mass(w, bs[i], &m, &c, &inertia);
        PP_OK_OR_FAIL(pp_body_get_velocity(w, bs[i], &v, &om));
        PP_OK_OR_FAIL(pp_body_get_position(w, bs[i], &p));
        PP_OK_OR_FAIL(pp_body_get_angle(w, bs[i], &ang));
        int32_t bw, bh;
        PP_OK_OR_FAIL(pp_body_get_size(w, bs[i], &bw, &bh));
        /* Centre of mass in the world: pivot (the bitmap centre) + R(angle)(c − pivot). */
        const double dx = c.x - bw / 2.0, dy = c.y - bh / 2.0;
        const double cx = p.x + dx * cos(ang) - dy * sin(ang), cy = p.y + dx * sin(ang) + dy * cos(ang);
        *px += m * v.x, *py += m * v.y;
        *l += inertia * om + m * (cx * v.y - cy * v.x);
    }
}

Test(edit, cutting_a_spinning_bar_conserves_momentum) {
    enum { W = 200, H = 8 };
    pp_world w = make_world(0, 0);
    /* The halves hang together by one weightless pixel, so the cut removes no mass. */
    uint8_t mask[W * H], weights[W * H];
    memset(mask, 1, sizeof mask);
    memset(weights, 255, sizeof weights);
    for (int y = 0; y < H - 1; y++) mask[y * W + 100] = 0;
    weights[(H - 1) * W + 100] = 0;
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 300, 300, 0.4f);
    d.width = W, d.height = H, d.mask = mask, d.weights = weights;
    d.linear_velocity = v2(30, -12), d.angular_velocity = 1.7f;
    pp_body bar = create_body_ok(w, &d);
    double px0, py0, l0, px1, py1, l1;
    momentum(w, &px0, &py0, &l0);
    /* The bridge pixel's centre in the world. */
    const double lx = 100.5 - W / 2.0, ly = H - 0.5 - H / 2.0;
    const pp_vec2 bridge = v2((float)(300 + lx * cos(0.4) - ly * sin(0.4)), (float)(300 + lx * sin(0.4) + ly * cos(0.4)));
    int32_t changed;
    PP_OK_OR_FAIL(pp_body_erase_circle(w, bar, bridge, 0.4f, &changed));
    cr_assert_eq(changed, 1, "the cut erased %d pixels, not the one bridge", changed);
    pp_event ev[4];
    int32_t n;
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 4, &n));
    cr_assert_eq(n, 1);
    cr_assert_eq(ev[0].type, PP_EVENT_BODY_SPLIT);
    cr_assert_eq(ev[0].body.id, bar.id, "the parent keeps its handle");
    momentum(w, &px1, &py1, &l1);
    cr_log_info("split bar: p (%.6g, %.6g) -> (%.6g, %.6g), L %.8g -> %.8g", px0, py0, px1, py1, l0, l1);
    const double pmag = hypot(px0, py0);
    cr_assert(hypot(px1 - px0, py1 - py0) <= 1e-4 * pmag, "linear momentum changed");
    cr_assert(fabs(l1 - l0) <= 1e-4 * fabs(l0), "angular momentum %g -> %g", l0, l1);
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 4, &n));
    cr_assert_eq(n, 0, "events are forgotten once read");
    pp_world_destroy(w);
}

Test(edit, a_box_falls_within_5_steps_when_the_ground_under_it_is_erased) {
    pp_world w = make_world(0, 980);
    pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 400, 500, 0), 800, 40);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 464, 0), 32, 32);
    step_n(w, 1.0f / 60.0f, 240);
    int32_t awake = 1;
    PP_OK_OR_FAIL(pp_body_is_awake(w, box, &awake));
    const float rest = body_pos(w, box).y;
    cr_assert_float_eq(rest, 464.0f, 2.0f, "the box should rest on the ground first (y %g)", rest);
    int32_t changed;
    PP_OK_OR_FAIL(pp_body_erase_circle(w, ground, v2(400, 500), 60, &changed));
    cr_assert_gt(changed, 3000);
    PP_OK_OR_FAIL(pp_body_is_awake(w, box, &awake));
    cr_assert_eq(awake, 1, "the box resting on the edited ground must wake");
    step_n(w, 1.0f / 60.0f, 5);
    const float y5 = body_pos(w, box).y;
    cr_log_info("box at %.3f, 5 steps after the crater: %.3f", rest, y5);
    cr_assert_gt(y5, rest + 0.5f, "the box did not fall (y %g -> %g)", rest, y5);
    pp_world_destroy(w);
}

/* An edit wakes only the bodies near the pixels it changed: a crater deep in the terrain, or at its
 * far end, leaves a box sleeping on the surface asleep; cutting to within a pixel under it wakes it. */
Test(edit, an_edit_wakes_only_the_bodies_near_its_pixels) {
    pp_world w = make_world(0, 980);
    pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 1000, 700, 0), 2000, 400); /* top at y 500 */
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 484, 0), 32, 32);
    step_n(w, 1.0f / 60.0f, 120);
    int32_t awake = 1, changed;
    PP_OK_OR_FAIL(pp_body_is_awake(w, box, &awake));
    cr_assert_eq(awake, 0, "the box should sleep on the ground first");
    PP_OK_OR_FAIL(pp_body_erase_circle(w, ground, v2(400, 600), 40, &changed)); /* 60 px under it */
    PP_OK_OR_FAIL(pp_body_erase_circle(w, ground, v2(1800, 500), 40, &changed)); /* at the surface, far away */
    cr_assert_gt(changed, 1000);
    PP_OK_OR_FAIL(pp_body_is_awake(w, box, &awake));
    cr_assert_eq(awake, 0, "craters far from the box woke it");
    /* A cut reaching one pixel under the box's bottom edge wakes it. */
    PP_OK_OR_FAIL(pp_body_erase_circle(w, ground, v2(400, 560), 58.6f, &changed));
    PP_OK_OR_FAIL(pp_body_is_awake(w, box, &awake));
    cr_assert_eq(awake, 1, "a cut 1 px under the box left it asleep");
    pp_world_destroy(w);
}

Test(edit, erasing_every_pixel_destroys_the_body_with_an_event) {
    pp_world w = make_world(0, 0);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 10);
    int32_t changed, n;
    PP_OK_OR_FAIL(pp_body_erase_circle(w, b, v2(100, 100), 50, &changed));
    cr_assert_eq(changed, 200);
    pp_event ev[2];
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 2, &n));
    cr_assert_eq(n, 1);
    cr_assert_eq(ev[0].type, PP_EVENT_BODY_DESTROYED);
    cr_assert_eq(ev[0].body.id, b.id);
    EXPECT_ERR(pp_body_get_position(w, b, &(pp_vec2){0}), PP_ERR_INVALID_HANDLE, "stale");
    PP_OK_OR_FAIL(pp_world_get_bodies(w, NULL, 0, &n));
    cr_assert_eq(n, 0);
    pp_world_destroy(w);
}

static int dropped_logs;
static void count_dropped(int level, const char *msg, void *user) { dropped_logs += strstr(msg, "PP_MAX_QUEUED_EVENTS") != 0; }

/* A host that never reads events keeps the newest PP_MAX_QUEUED_EVENTS of them, not every one. */
Test(edit, unread_events_are_bounded_oldest_dropped_first, .timeout = 60) {
    enum { N = PP_MAX_QUEUED_EVENTS + 100 };
    pp_world w = make_world(0, 0);
    static pp_body made[N];
    const uint8_t one = 1;
    for (int i = 0; i < N; i++) { /* one pixel each, on a 512-wide grid of 2 px cells */
        pp_body_def d = body_def(PP_BODY_STATIC, 2.0f * (i % 512) + 0.5f, 2.0f * (i / 512) + 0.5f, 0);
        d.width = d.height = 1, d.mask = &one;
        PP_OK_OR_FAIL(pp_body_create(w, &d, &made[i]));
    }
    PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60)); /* a static body leaves the awake set at its first step */
    int32_t changed = 0, n = 0;
    PP_OK_OR_FAIL(pp_world_erase_circle(w, v2(512, 256), 1000, &changed));
    cr_assert_eq(changed, N);
    PP_OK_OR_FAIL(pp_world_get_events(w, NULL, 0, &n));
    cr_assert_eq(n, N, "an edit queues every event it makes");
    dropped_logs = 0;
    pp_set_log_hook(count_dropped, NULL);
    PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
    pp_set_log_hook(NULL, NULL);
    cr_assert_eq(dropped_logs, 1, "the drop is logged once");
    static pp_event ev[N];
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, N, &n));
    cr_assert_eq(n, PP_MAX_QUEUED_EVENTS);
    /* Bodies are destroyed in slot order, which is creation order: the first 100 events went. */
    cr_assert_eq(ev[0].type, PP_EVENT_BODY_DESTROYED);
    cr_assert_eq(ev[0].body.id, made[100].id);
    cr_assert_eq(ev[n - 1].body.id, made[N - 1].id);
    pp_world_destroy(w);
}

Test(edit, bad_edits_are_refused_and_change_nothing) {
    pp_world w = make_world(0, 0);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 10);
    int32_t changed = -1;
    EXPECT_ERR(pp_body_erase_circle(w, b, v2(NAN, 100), 5, &changed), PP_ERR_INVALID_ARGUMENT, "world_center");
    EXPECT_ERR(pp_body_erase_circle(w, b, v2(100, 100), -1, &changed), PP_ERR_INVALID_ARGUMENT, "radius");
    EXPECT_ERR(pp_world_erase_circle(w, v2(100, INFINITY), 5, &changed), PP_ERR_INVALID_ARGUMENT, "world_center");
    EXPECT_ERR(pp_body_paint_circle(w, b, v2(100, 100), NAN, 255, &changed), PP_ERR_INVALID_ARGUMENT, "radius");
    EXPECT_ERR(pp_body_paint_circle(w, b, v2(100, 100), 3, 0, &changed), PP_ERR_INVALID_ARGUMENT, "weight");
    uint8_t ones[4] = {1, 1, 1, 1};
    EXPECT_ERR(pp_body_write_pixels(w, b, 20, 0, 2, 2, ones, NULL), PP_ERR_INVALID_ARGUMENT, "outside");
    EXPECT_ERR(pp_body_write_pixels(w, b, -2, -2, 2, 2, ones, NULL), PP_ERR_INVALID_ARGUMENT, "outside");
    EXPECT_ERR(pp_body_write_pixels(w, b, 0, 0, -2, 2, ones, NULL), PP_ERR_INVALID_ARGUMENT, "width");
    EXPECT_ERR(pp_body_write_pixels(w, b, 0, 0, 2, 2, NULL, NULL), PP_ERR_INVALID_ARGUMENT, "mask");
    uint8_t small[10];
    EXPECT_ERR(pp_body_read_mask(w, b, small, sizeof small), PP_ERR_INVALID_ARGUMENT, "200");
    EXPECT_ERR(pp_body_erase_circle(w, (pp_body){12345}, v2(1, 1), 1, &changed), PP_ERR_INVALID_HANDLE, "body");
    float m;
    body_mass(w, b, &m, NULL, NULL);
    cr_assert_float_eq(m, 200.0f, 1e-4f, "a refused edit changed the mass to %g", m);
    /* Partly outside: clipped. A 4×4 hole over the corner (−2..2)² clears the 2×2 inside. */
    uint8_t zeros[16] = {0};
    PP_OK_OR_FAIL(pp_body_write_pixels(w, b, -2, -2, 4, 4, zeros, NULL));
    body_mass(w, b, &m, NULL, NULL);
    cr_assert_float_eq(m, 196.0f, 1e-4f);
    pp_world_destroy(w);
}

/* Sum of a weight plane's bytes over 255: the body's mass at density 1. */
static float plane_mass(const uint8_t *weights, int n) {
    long sum = 0;
    for (int k = 0; k < n; k++) sum += weights[k];
    return (float)sum / 255.0f;
}

Test(edit, read_weights_gives_each_pixels_weight_after_painting_and_erasing) {
    enum { W = 20, H = 10 };
    pp_world w = make_world(0, 0);
    /* Pivot at the centre, angle 0: pixel (i, j)'s centre is at world (90 + i + 0.5, 95 + j + 0.5). */
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), W, H);
    uint8_t got[W * H], want[W * H];
    PP_OK_OR_FAIL(pp_body_read_weights(w, b, got, sizeof got));
    memset(want, 255, sizeof want);
    cr_assert_eq(memcmp(got, want, sizeof got), 0, "without a weight plane every solid pixel reads 255");
    /* A plus of five pixels around (5, 2) painted 60; pixel (15, 7) erased. */
    int32_t changed = 0;
    PP_OK_OR_FAIL(pp_body_paint_circle(w, b, v2(95.5f, 97.5f), 1.2f, 60, &changed));
    cr_assert_eq(changed, 5);
    PP_OK_OR_FAIL(pp_body_erase_circle(w, b, v2(105.5f, 102.5f), 0.4f, &changed));
    cr_assert_eq(changed, 1);
    const int plus[5][2] = {{5, 2}, {4, 2}, {6, 2}, {5, 1}, {5, 3}};
    for (int k = 0; k < 5; k++) want[plus[k][1] * W + plus[k][0]] = 60;
    want[7 * W + 15] = 0;
    PP_OK_OR_FAIL(pp_body_read_weights(w, b, got, sizeof got));
    for (int k = 0; k < W * H; k++)
        cr_assert_eq(got[k], want[k], "pixel (%d, %d) reads %d, painted %d", k % W, k / W, got[k], want[k]);
    /* The bytes are the mass: density 1 gives Σ weight / 255. */
    float m;
    body_mass(w, b, &m, NULL, NULL);
    cr_assert_float_eq(m, plane_mass(got, W * H), 1e-3f, "mass %g against the plane's %g", m, plane_mass(got, W * H));
    /* Written weights, a solid pixel of weight 0 among them, read back as written. */
    const uint8_t mask[3] = {1, 1, 0}, weights[3] = {7, 0, 200};
    PP_OK_OR_FAIL(pp_body_write_pixels(w, b, 0, 9, 3, 1, mask, weights));
    PP_OK_OR_FAIL(pp_body_read_weights(w, b, got, sizeof got));
    cr_assert(got[9 * W] == 7 && got[9 * W + 1] == 0 && got[9 * W + 2] == 0 && got[9 * W + 3] == 255,
              "row 9 starts %d %d %d %d, written 7 0 (empty) 255", got[9 * W], got[9 * W + 1], got[9 * W + 2],
              got[9 * W + 3]);
    pp_world_destroy(w);
}

Test(edit, read_weights_refuses_stale_handles_short_and_null_buffers) {
    pp_world w = make_world(0, 0);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 10);
    pp_body gone = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 100, 0), 4, 4);
    PP_OK_OR_FAIL(pp_body_destroy(w, gone));
    uint8_t out[200], small[199];
    memset(out, 0xab, sizeof out);
    EXPECT_ERR(pp_body_read_weights(w, gone, out, sizeof out), PP_ERR_INVALID_HANDLE, "body");
    EXPECT_ERR(pp_body_read_weights(w, (pp_body){0}, out, sizeof out), PP_ERR_INVALID_HANDLE, "body");
    EXPECT_ERR(pp_body_read_weights((pp_world){12345}, b, out, sizeof out), PP_ERR_INVALID_HANDLE, "world");
    EXPECT_ERR(pp_body_read_weights(w, b, small, sizeof small), PP_ERR_INVALID_ARGUMENT, "200");
    EXPECT_ERR(pp_body_read_weights(w, b, out, -1), PP_ERR_INVALID_ARGUMENT, "200");
    EXPECT_ERR(pp_body_read_weights(w, b, NULL, sizeof out), PP_ERR_INVALID_ARGUMENT, "NULL");
    cr_assert_eq(out[0], 0xab, "a refused read wrote into out");
    PP_OK_OR_FAIL(pp_body_read_weights(w, b, out, INT64_MAX));
    cr_assert_eq(out[0], 255);
    pp_world_destroy(w);
}

Test(edit, painting_adds_weighted_pixels_and_a_static_body_splits_only_when_asked) {
    pp_world w = make_world(0, 0);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 10);
    int32_t changed, n;
    PP_OK_OR_FAIL(pp_body_erase_circle(w, b, v2(100, 100), 30, &changed));
    PP_OK_OR_FAIL(pp_world_get_events(w, NULL, 0, &n));
    cr_assert_eq(n, 1, "emptied: one DESTROYED event pending");

    b = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 10);
    PP_OK_OR_FAIL(pp_body_paint_circle(w, b, v2(100, 100), 30, 51, &changed)); /* nothing new: all solid, new weight */
    float m;
    body_mass(w, b, &m, NULL, NULL);
    cr_assert_eq(changed, 200);
    cr_assert_float_eq(m, 200 * 51 / 255.0f, 1e-3f, "repainted at weight 51: mass %g", m);

    /* A static bar cut in two stays one static body; with detach_islands the cut-off part falls. */
    for (int detach = 0; detach < 2; detach++) {
        pp_world w2 = make_world(0, 980);
        pp_body_def d = body_def(PP_BODY_STATIC, 300, 300, 0);
        d.detach_islands = (uint32_t)detach;
        pp_body bar = add_rect(w2, d, 200, 10);
        PP_OK_OR_FAIL(pp_body_erase_circle(w2, bar, v2(330, 300), 8, &changed));
        PP_OK_OR_FAIL(pp_world_get_bodies(w2, NULL, 0, &n));
        cr_assert_eq(n, 1 + detach, "detach_islands %d: %d bodies", detach, n);
        pp_event ev;
        PP_OK_OR_FAIL(pp_world_get_events(w2, &ev, 1, &n));
        cr_assert_eq(n, detach);
        if (detach) {
            cr_assert_eq(ev.type, PP_EVENT_BODY_SPLIT);
            step_n(w2, 1.0f / 60.0f, 30);
            cr_assert_gt(body_pos(w2, ev.other).y, 310.0f, "the detached island should fall");
            cr_assert_float_eq(body_pos(w2, bar).y, 300.0f, 1e-4f, "the static part stays");
        }
        pp_world_destroy(w2);
    }
    pp_world_destroy(w);
}

/* A split whose largest island is massless (all weights zero): the parent, which keeps that island,
 * goes as a body left without mass does, and the weighted island falls on as a new body (the fuzzer
 * found ODE aborting the process on the parent's zero mass). */
Test(edit, a_split_leaving_the_parent_massless_destroys_it)
{
    pp_world w = make_world(0, 980);
    uint8_t mask[10 * 3], weights[10 * 3], hole[3] = {0, 0, 0};
    for (int i = 0; i < 30; i++)
        mask[i] = 1, weights[i] = i % 10 >= 6 ? 255 : 0;
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 100, 100, 0);
    d.width = 10, d.height = 3, d.mask = mask, d.weights = weights;
    pp_body b;
    PP_OK_OR_FAIL(pp_body_create(w, &d, &b));
    PP_OK_OR_FAIL(pp_body_write_pixels(w, b, 6, 0, 1, 3, hole, NULL));
    pp_event ev[4];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 4, &n));
    cr_assert_eq(n, 2, "%d events", (int)n);
    cr_assert_eq(ev[0].type, PP_EVENT_BODY_SPLIT);
    cr_assert_eq(ev[1].type, PP_EVENT_BODY_DESTROYED);
    cr_assert_eq(ev[1].body.id, b.id);
    pp_vec2 p;
    cr_assert_eq(pp_body_get_position(w, b, &p), PP_ERR_INVALID_HANDLE);
    int32_t bw = 0, bh = 0;
    PP_OK_OR_FAIL(pp_body_get_size(w, ev[0].other, &bw, &bh));
    cr_assert(bw == 3 && bh == 3, "the weighted island is %d × %d", (int)bw, (int)bh);
    PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
    PP_OK_OR_FAIL(pp_world_destroy(w));
}
