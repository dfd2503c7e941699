/* The edges of the envelope: mass ratios of 1:1000, one-pixel bodies, 1×512 sticks, a 4096×2048
 * terrain, dt from 1e-4 to 1/15 s, 5,000 px/s against an 8 px wall, spawns overlapping by half,
 * a tower standing for 100,000 steps and a randomized run. Every test asserts where bodies end
 * and how fast they move, not only that nothing crashed. Where the library fails today, the test
 * asserts the range where it holds, and a disabled twin (`.disabled = true`) states the target. */
#include "helpers.h"

#include <float.h>

PP_TEST_SUITE(extremes);

#define DT (1.0f / 60.0f)
#define GROUND_TOP 480.0f /* top face of add_ground's slab, px */

/* A static slab 4000 px wide and 40 px thick whose top face is at y = GROUND_TOP. */
static pp_body add_ground(pp_world w) {
    return add_rect(w, body_def(PP_BODY_STATIC, 400, GROUND_TOP + 20, 0), 4000, 40);
}

static int body_finite(pp_world w, pp_body b) {
    pp_vec2 p, v;
    float a, av;
    PP_OK_OR_FAIL(pp_body_get_position(w, b, &p));
    PP_OK_OR_FAIL(pp_body_get_angle(w, b, &a));
    PP_OK_OR_FAIL(pp_body_get_velocity(w, b, &v, &av));
    return isfinite(p.x) && isfinite(p.y) && isfinite(a) && isfinite(v.x) && isfinite(v.y) && isfinite(av);
}

static double body_speed(pp_world w, pp_body b) {
    pp_vec2 v = body_vel(w, b);
    return hypot(v.x, v.y);
}

/* Largest world y of a width×height bitmap's corners (its lowest point), pivot at the centre. */
static double rect_lowest(pp_world w, pp_body b, int width, int height) {
    const pp_vec2 p = body_pos(w, b);
    const double a = body_angle(w, b), c = cos(a), s = sin(a);
    double lo = -INFINITY;
    for (int k = 0; k < 4; k++) {
        const double lx = (k & 1 ? width : 0) - 0.5 * width, ly = (k & 2 ? height : 0) - 0.5 * height;
        lo = fmax(lo, p.y + s * lx + c * ly);
    }
    return lo;
}

/* The fastest two bodies overlapping by `depth` px may be pushed apart (section 7): 10% over
 * contact_erp · (depth − contact_slop) · substeps / dt, plus what gravity adds in a solver step. */
static double separation_bound(const pp_world_def *d, double depth, float dt) {
    const double v = fmin(d->contact_erp * (depth - d->contact_slop) * d->substeps / dt, d->max_correction_speed);
    return 1.1 * v + hypot(d->gravity.x, d->gravity.y) * dt / d->substeps;
}

/* Number of live bodies in the world. */
static int32_t body_count(pp_world w) {
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, NULL, 0, &n));
    return n;
}

/* ---------------------------------------------------------------------------------------------
 * 1. Mass ratio 1:1000 stacks. Two s×s boxes on the ground; every contact keeps about contact_slop
 * (0.75 px) of overlap, so the centres rest at GROUND_TOP − s/2 + slop and GROUND_TOP − 3s/2 + 2·slop.
 *
 * Measured: light (1) on heavy (1000) stands with the defaults, sleep on or off. Heavy on light
 * does not everywhere: two 16 px boxes, sleep off, 5 s, with the defaults of then (4 substeps × 40
 * iterations) slide 0.33 px at 1:30 and 2.6 px at 1:100, and from 1:300 the top box falls off;
 * the accurate preset holds 1:100 (0.6 px) and slides 4.2 px at 1:300; the exact solver
 * (dWorldStep) holds 1:1000.
 * --------------------------------------------------------------------------------------------- */

typedef struct stack_outcome {
    double worst_dy[2]; /* |centre y − resting height|, bottom and top box, px */
    double worst_dx;    /* sideways drift of either box, px */
    double worst_angle; /* degrees */
    double final_speed; /* faster of the two at the end, px/s */
    int finite;
} stack_outcome;

static stack_outcome two_box_stack(const pp_world_def *def, int s, float density_low, float density_high) {
    pp_world w = make_world_def(def);
    add_ground(w);
    const double slop = def->contact_slop;
    const double rest[2] = {GROUND_TOP - 0.5 * s + slop, GROUND_TOP - 1.5 * s + 2 * slop};
    pp_body_def dl = body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 0.5f * s, 0);
    dl.density = density_low;
    pp_body_def dh = body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 1.5f * s, 0);
    dh.density = density_high;
    pp_body box[2] = {add_rect(w, dl, s, s), add_rect(w, dh, s, s)};
    stack_outcome o = {{0, 0}, 0, 0, 0, 1};
    for (int i = 0; i < 600; i++) { /* 10 s; the first 2 s are settling */
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        for (int k = 0; k < 2; k++) {
            o.finite &= body_finite(w, box[k]);
            const pp_vec2 p = body_pos(w, box[k]);
            o.worst_dx = fmax(o.worst_dx, fabs(p.x - 400.0));
            if (i >= 120) {
                o.worst_dy[k] = fmax(o.worst_dy[k], fabs(p.y - rest[k]));
                o.worst_angle = fmax(o.worst_angle, fabs(RAD2DEG(wrap_angle(body_angle(w, box[k])))));
            }
        }
    }
    o.final_speed = fmax(body_speed(w, box[0]), body_speed(w, box[1]));
    cr_assert_eq(body_count(w), 3);
    pp_world_destroy(w);
    return o;
}

static void assert_stack_stands(const pp_world_def *def, const char *what, float density_low, float density_high) {
    const int sizes[] = {16, 32};
    for (int i = 0; i < 2; i++) {
        const stack_outcome o = two_box_stack(def, sizes[i], density_low, density_high);
        cr_log_info("%s, %d px, densities %g under %g: height error %.3f / %.3f px, drift %.3f px, angle %.3f deg, "
                    "final speed %.3f px/s",
                    what, sizes[i], density_low, density_high, o.worst_dy[0], o.worst_dy[1], o.worst_dx,
                    o.worst_angle, o.final_speed);
        cr_assert(o.finite, "%s, %d px: a pose or velocity became NaN or Inf", what, sizes[i]);
        cr_assert_leq(o.worst_dy[0], 1.0, "%s, %d px, %g under %g: bottom box %.3f px from its resting height", what,
                      sizes[i], density_low, density_high, o.worst_dy[0]);
        cr_assert_leq(o.worst_dy[1], 1.0, "%s, %d px, %g under %g: top box %.3f px from its resting height", what,
                      sizes[i], density_low, density_high, o.worst_dy[1]);
        cr_assert_leq(o.worst_dx, 1.0, "%s, %d px, %g under %g: slid %.3f px sideways", what, sizes[i], density_low,
                      density_high, o.worst_dx);
        cr_assert_leq(o.worst_angle, 1.0, "%s, %d px: tilted %.3f deg", what, sizes[i], o.worst_angle);
        cr_assert_lt(o.final_speed, 2.0, "%s, %d px: still moving at %.3f px/s", what, sizes[i], o.final_speed);
    }
}

Test(extremes, light_on_heavy_1_to_1000_stands) {
    pp_world_def d = pp_world_def_default();
    assert_stack_stands(&d, "defaults", 1000, 1);
    d.allow_sleep = 0;
    assert_stack_stands(&d, "defaults without sleep", 1000, 1);
}

Test(extremes, heavy_on_light_1_to_1000_stands_with_the_exact_solver) {
    pp_world_def d = pp_world_def_default();
    d.exact_solver = 1;
    assert_stack_stands(&d, "exact solver", 1, 1000);
    d.allow_sleep = 0;
    assert_stack_stands(&d, "exact solver without sleep", 1, 1000);
}

Test(extremes, heavy_on_light_1_to_5_stands_with_the_defaults) {
    pp_world_def d = pp_world_def_default();
    assert_stack_stands(&d, "defaults", 1, 5);
}

Test(extremes, heavy_on_light_1_to_1000_stands_with_the_defaults, .disabled = true) {
    /* The target (the stability bar, tests/bench/README.md: 1000:1 mass ratios stack); fails today, see the block comment above. */
    pp_world_def d = pp_world_def_default();
    assert_stack_stands(&d, "defaults", 1, 1000);
}

/* ---------------------------------------------------------------------------------------------
 * 2. One-pixel bodies. A 1×1 body's contact depth saturates at about 0.5 px (below contact_slop,
 * 0.75 px), so it is held by the contact's velocity constraint alone and never pushed back out:
 * it keeps whatever penetration its impact left (0.7 px placed on the ground, 2.3 px after a
 * 20 px drop, 4.6 px after 200 px) and, awake, creeps in at 0.01 px/s. These tests hold its
 * rotation fixed and drop it at most 1 px. With free rotation it used to spin and fall through the
 * ground, from contact points half a pixel off along the tangent (since centred), a joint order
 * that leaned every two-point contact one way (since alternated) and sleepers woken one at a time
 * (since grouped); one_pixel_body_dropped_anywhere_rests now holds it for every placement tried.
 * --------------------------------------------------------------------------------------------- */

/* Steps a 1×1 body for 10 s; *worst_err receives its worst |penetration − slop| after the first
 * second (a resting body keeps contact_slop, 0.75 px, of overlap), *final_pen its last penetration. */
static void one_pixel_drop(pp_world w, pp_body b, double *worst_err, double *final_pen) {
    *worst_err = 0;
    for (int i = 0; i < 600; i++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        cr_assert(body_finite(w, b), "1×1 body: NaN or Inf at step %d", i);
        const double pen = body_pos(w, b).y + 0.5 - GROUND_TOP;
        if (i >= 60) *worst_err = fmax(*worst_err, fabs(pen - 0.75));
    }
    *final_pen = body_pos(w, b).y + 0.5 - GROUND_TOP;
}

Test(extremes, one_pixel_body_rests_on_the_ground) {
    const float offsets[] = {0.0f, 0.25f, 0.5f, 0.75f};
    const float drops[] = {0.0f, 1.0f};
    for (int sleep = 0; sleep <= 1; sleep++)
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 2; k++) {
                pp_world_def wd = pp_world_def_default();
                wd.allow_sleep = (uint32_t)sleep;
                pp_world w = make_world_def(&wd);
                add_ground(w);
                pp_body_def d = body_def(PP_BODY_DYNAMIC, 400 + offsets[i], GROUND_TOP - 0.5f - drops[k], 0);
                d.fixed_rotation = 1;
                pp_body b = add_rect(w, d, 1, 1);
                float m = 0;
                PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, NULL, NULL));
                cr_assert_float_eq(m, 1.0, 1e-6, "a 1×1 body of density 1 weighs %g", m);
                double err, pen;
                one_pixel_drop(w, b, &err, &pen);
                const pp_vec2 p = body_pos(w, b);
                cr_log_info("1×1 at x+%.2f dropped %.0f px, sleep %d: rests %.3f px into the ground (worst |pen − slop| "
                            "%.3f)",
                            offsets[i], drops[k], sleep, pen, err);
                cr_assert_leq(err, 0.5, "1×1 at x+%.2f dropped %.0f px (sleep %d): %.3f px from its resting depth",
                              offsets[i], drops[k], sleep, err);
                cr_assert_float_eq(p.x, 400 + offsets[i], 0.01, "1×1 slid to x %.3f", p.x);
                cr_assert_lt(body_speed(w, b), 1.0, "1×1 still moving at %.3f px/s", body_speed(w, b));
                pp_world_destroy(w);
            }
}

Test(extremes, many_one_pixel_bodies_rest_side_by_side) {
    /* 200 grains 2 px apart, each at its own sub-pixel offset, placed on the ground or 1 px above it. */
    pp_world w = make_world(0, 980);
    add_ground(w);
    enum { N = 200 };
    pp_body b[N];
    for (int i = 0; i < N; i++) {
        const float x = 200 + 2.0f * i + 0.01f * (float)(i % 97);
        pp_body_def d = body_def(PP_BODY_DYNAMIC, x, GROUND_TOP - 0.5f - (float)(i % 2), 0);
        d.fixed_rotation = 1;
        d.density = 0.5f + (float)(i % 5);
        b[i] = add_rect(w, d, 1, 1);
    }
    step_n(w, DT, 600);
    cr_assert_eq(body_count(w), N + 1);
    double worst = 0;
    for (int i = 0; i < N; i++) {
        cr_assert(body_finite(w, b[i]), "grain %d: NaN or Inf", i);
        const double pen = body_pos(w, b[i]).y + 0.5 - GROUND_TOP;
        worst = fmax(worst, fabs(pen - 0.75));
        cr_assert_lt(body_speed(w, b[i]), 1.0, "grain %d still moving at %.3f px/s", i, body_speed(w, b[i]));
    }
    cr_log_info("200 grains: worst |penetration − slop| %.3f px", worst);
    cr_assert_leq(worst, 0.5, "a grain rests %.3f px from the resting depth", worst);
    pp_world_destroy(w);
}

Test(extremes, one_pixel_body_dropped_anywhere_rests) {
    /* Free rotation, any sub-pixel x, dropped from up to 200 px. Failed before the manifold points were
     * centred, the contacts' solve order alternated and piles slept together; holds since. */
    const float offsets[] = {0.0f, 0.3f, 0.5f, 0.7f};
    const float drops[] = {0.0f, 5.0f, 20.0f, 100.0f, 200.0f};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 5; k++) {
            pp_world w = make_world(0, 980);
            add_ground(w);
            pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 400 + offsets[i], GROUND_TOP - 0.5f - drops[k], 0), 1, 1);
            double err, pen;
            one_pixel_drop(w, b, &err, &pen);
            cr_assert_leq(err, 1.0, "1×1 at x+%.2f dropped %.0f px: rests %.3f px into the ground", offsets[i],
                          drops[k], pen);
            pp_world_destroy(w);
        }
}

/* ---------------------------------------------------------------------------------------------
 * 3. 1×512 sticks, falling flat and on end. Measured: flat, the stick rests with its underside
 * 0.65–0.75 px into the ground; dropped on end it either stays standing (its 1 px foot 1.5 px in)
 * or falls over and lies flat, the far end arriving fast but reaching at most 1.8 px into the
 * ground (10 px before continuous collision was added).
 * --------------------------------------------------------------------------------------------- */

/* Drops a width×height stick at a pose and steps 10 s; returns the deepest any corner reached
 * below the ground top after the first contact, and leaves the world for the caller to inspect. */
static double drop_stick(pp_world w, pp_body b, int width, int height) {
    double deepest = -INFINITY;
    for (int i = 0; i < 600; i++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        cr_assert(body_finite(w, b), "%d×%d stick: NaN or Inf at step %d", width, height, i);
        deepest = fmax(deepest, rect_lowest(w, b, width, height) - GROUND_TOP);
    }
    return deepest;
}

Test(extremes, stick_1x512_falling_flat_rests) {
    /* The same stick two ways: a 512×1 bitmap level, and a 1×512 bitmap turned a quarter turn. */
    const struct { int w, h; float angle; } shapes[] = {{512, 1, 0.0f}, {1, 512, (float)(M_PI / 2)}};
    const float offsets[] = {0.0f, 0.3f};
    for (int s = 0; s < 2; s++)
        for (int i = 0; i < 2; i++) {
            pp_world w = make_world(0, 980);
            add_ground(w);
            pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 400 + offsets[i], GROUND_TOP - 100, shapes[s].angle),
                                 shapes[s].w, shapes[s].h);
            const double deepest = drop_stick(w, b, shapes[s].w, shapes[s].h);
            const double low = rect_lowest(w, b, shapes[s].w, shapes[s].h) - GROUND_TOP;
            const double tilt = RAD2DEG(wrap_angle(body_angle(w, b) - shapes[s].angle));
            cr_log_info("%d×%d stick flat at x+%.1f: underside %.3f px into the ground (deepest %.3f), tilt %.4f deg",
                        shapes[s].w, shapes[s].h, offsets[i], low, deepest, tilt);
            cr_assert_float_eq(low, 0.75, 0.5, "%d×%d flat stick rests %.3f px into the ground", shapes[s].w,
                               shapes[s].h, low);
            cr_assert_leq(deepest, 4.0, "%d×%d flat stick reached %.3f px into the 40 px ground", shapes[s].w,
                          shapes[s].h, deepest);
            cr_assert_leq(fabs(tilt), 0.5, "flat stick tilted %.4f deg", tilt);
            cr_assert_lt(body_speed(w, b), 1.0, "flat stick still moving at %.3f px/s", body_speed(w, b));
            pp_world_destroy(w);
        }
}

Test(extremes, stick_1x512_falling_on_end_rests) {
    /* Upright, 50 px above the ground, at two sub-pixel offsets and two small tilts. */
    const float offsets[] = {0.0f, 0.3f};
    const float tilts[] = {0.0f, 0.02f};
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++) {
            pp_world w = make_world(0, 980);
            add_ground(w);
            const pp_body_def d = body_def(PP_BODY_DYNAMIC, 400 + offsets[i], GROUND_TOP - 256 - 50, tilts[k]);
            pp_body b = add_rect(w, d, 1, 512);
            const double deepest = drop_stick(w, b, 1, 512);
            const double low = rect_lowest(w, b, 1, 512) - GROUND_TOP;
            const double a = RAD2DEG(wrap_angle(body_angle(w, b)));
            const int standing = fabs(a) < 2.0, lying = fabs(fabs(a) - 90.0) < 2.0;
            cr_log_info("1×512 on end at x+%.1f, tilt %.2f: ends %s at %.2f deg, lowest point %.3f px into the ground "
                        "(deepest %.3f)",
                        offsets[i], tilts[k], standing ? "standing" : lying ? "lying" : "neither", a, low, deepest);
            cr_assert(standing || lying, "stick on end ended at %.2f deg, neither standing nor lying", a);
            cr_assert(low >= 0.25 && low <= 2.0, "stick %s with its lowest point %.3f px into the ground",
                      standing ? "standing" : "lying", low);
            cr_assert_leq(deepest, 4.0, "stick reached %.3f px into the 40 px ground", deepest);
            cr_assert_lt(body_speed(w, b), 1.0, "stick still moving at %.3f px/s", body_speed(w, b));
            pp_world_destroy(w);
        }
}

/* ---------------------------------------------------------------------------------------------
 * 4. A 4096×2048 static terrain with rolling hills and small bumps, steepest slope about 24°,
 * below the friction angle (atan 0.6 = 31°) so boxes stay where they land; discs roll to hollows.
 * --------------------------------------------------------------------------------------------- */

#define TERRAIN_W 4096
#define TERRAIN_H 2048

static double terrain_surface(double x) {
    return 1300.0 + 100.0 * sin(x / 400.0) + 6.0 * sin(x / 31.0);
}

/* How far the body's lowest solid pixel centre lies below the terrain's top face (top[i]: first
 * solid row of column i), px. Resting with contact_slop of overlap it is about slop − 0.5 = 0.25;
 * negative is above the surface. */
static double terrain_depth(pp_world w, pp_body b, const int32_t *top) {
    int32_t bw = 0, bh = 0;
    PP_OK_OR_FAIL(pp_body_get_size(w, b, &bw, &bh));
    uint8_t *m = malloc((size_t)bw * (size_t)bh);
    cr_assert_not_null(m);
    PP_OK_OR_FAIL(pp_body_read_mask(w, b, m, (int64_t)bw * bh));
    pp_vec2 pivot;
    PP_OK_OR_FAIL(pp_body_get_pivot(w, b, &pivot));
    const pp_vec2 p = body_pos(w, b);
    const double a = body_angle(w, b), c = cos(a), s = sin(a);
    double deepest = -INFINITY;
    for (int j = 0; j < bh; j++)
        for (int i = 0; i < bw; i++) {
            if (!m[j * bw + i]) continue;
            const double lx = i + 0.5 - pivot.x, ly = j + 0.5 - pivot.y;
            const double x = p.x + c * lx - s * ly, y = p.y + s * lx + c * ly;
            const int col = (int)floor(x);
            if (col >= 0 && col < TERRAIN_W) deepest = fmax(deepest, y - top[col]);
        }
    free(m);
    return deepest;
}

Test(extremes, bodies_land_and_rest_on_a_4096x2048_terrain, .timeout = 120) {
    uint8_t *mask = malloc((size_t)TERRAIN_W * TERRAIN_H);
    int32_t *top = malloc(sizeof(int32_t) * TERRAIN_W);
    cr_assert(mask && top);
    for (int i = 0; i < TERRAIN_W; i++) {
        top[i] = TERRAIN_H;
        for (int j = 0; j < TERRAIN_H; j++) {
            const int solid = j + 0.5 >= terrain_surface(i + 0.5);
            mask[(size_t)j * TERRAIN_W + i] = (uint8_t)solid;
            if (solid && top[i] == TERRAIN_H) top[i] = j;
        }
    }
    pp_world w = make_world(0, 980);
    /* Placed so that bitmap coordinates are world coordinates: its centre, the pivot, at (2048, 1024). */
    pp_body_def td = body_def(PP_BODY_STATIC, TERRAIN_W / 2.0f, TERRAIN_H / 2.0f, 0);
    td.width = TERRAIN_W;
    td.height = TERRAIN_H;
    td.mask = mask;
    pp_body terrain = create_body_ok(w, &td);
    free(mask);

    enum { N = 24 };
    pp_body b[N];
    for (int k = 0; k < N; k++) {
        const double x = 100 + k * (3900.0 / N);
        const int size = 8 + (k % 4) * 8;
        pp_body_def d = body_def(PP_BODY_DYNAMIC, (float)x, (float)(terrain_surface(x) - 100 - size), 0.1f * (k % 5));
        b[k] = k % 3 == 2 ? add_disc(w, d, size / 2) : add_rect(w, d, size, size);
    }
    /* 20 s: a disc rocking in a hollow against a box loses little per swing (at 4 × 20 iterations one
     * came to rest at 15 s, at 4 × 40 at 6 s). */
    step_n(w, DT, 1200);
    cr_assert_eq(body_count(w), N + 1);
    for (int k = 0; k < N; k++) {
        cr_assert(body_finite(w, b[k]), "body %d: NaN or Inf", k);
        const double depth = terrain_depth(w, b[k], top);
        /* Supported by the terrain (a pixel within reach of the surface) or resting on another body. */
        pp_contact c[2];
        int32_t n = 0, on_body = 0;
        PP_OK_OR_FAIL(pp_world_collide(w, terrain, b[k], c, 2, &n));
        for (int o = 0; o < N && !on_body; o++) {
            int32_t m = 0;
            if (o != k) PP_OK_OR_FAIL(pp_world_collide(w, b[o], b[k], c, 2, &m));
            on_body = m > 0;
        }
        const pp_vec2 p = body_pos(w, b[k]);
        cr_log_info("terrain body %d (%s) at (%.1f, %.1f): lowest pixel centre %.3f px below the surface; %d terrain "
                    "contacts%s; %.3f px/s",
                    k, k % 3 == 2 ? "disc" : "box", p.x, p.y, depth, n, on_body ? ", on a body" : "",
                    body_speed(w, b[k]));
        cr_assert_leq(depth, 1.0, "body %d sank: a pixel centre %.3f px below the terrain surface", k, depth);
        cr_assert(n > 0 || on_body, "body %d at (%.1f, %.1f) touches neither the terrain nor a body", k, p.x, p.y);
        if (!on_body) cr_assert_geq(depth, -1.0, "body %d hovers %.3f px above the terrain", k, -depth);
        /* A disc may still rock in a hollow, under the sleep speed. */
        cr_assert_lt(body_speed(w, b[k]), 5.0, "body %d still moving at %.3f px/s", k, body_speed(w, b[k]));
    }
    free(top);
    pp_world_destroy(w);
}

/* ---------------------------------------------------------------------------------------------
 * 5. dt from 1e-4 to 1/15 s. Measured: the resting penetration is 0.50–0.78 px at every dt (0.5
 * at 1e-4 s, where ERP per solver step is tiny and the slop layer is never quite reached, 0.75 from
 * 1/240 s up). The impact reaches up to 7.8 px into the ground for the 32 px box at 1/20 s, which
 * moves less than half its thickness a substep and so is not swept, and 1.6 px for the 8 px box.
 * --------------------------------------------------------------------------------------------- */

Test(extremes, a_dropped_box_rests_at_the_same_height_at_every_dt, .timeout = 120) {
    const float dts[] = {1e-4f, 1e-3f, 1.0f / 240, 1.0f / 60, 1.0f / 30, 1.0f / 15};
    const int sizes[] = {32, 8};
    for (int si = 0; si < 2; si++)
        for (int sleep = 1; sleep >= 0; sleep--) {
            if (sizes[si] == 8 && !sleep) continue; /* one awake run is enough; 1e-4 s awake is the slow one */
            double lo = INFINITY, hi = -INFINITY;
            for (int k = 0; k < 6; k++) {
                pp_world_def wd = pp_world_def_default();
                wd.allow_sleep = (uint32_t)sleep;
                pp_world w = make_world_def(&wd);
                add_ground(w);
                const int s = sizes[si];
                pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 64 - s / 2.0f, 0), s, s);
                const int n = (int)lround(3.0 / dts[k]);
                double deepest = 0;
                for (int i = 0; i < n; i++) {
                    PP_OK_OR_FAIL(pp_world_step(w, dts[k]));
                    if (!body_finite(w, b)) cr_assert_fail("dt %g: NaN or Inf at step %d", dts[k], i);
                    deepest = fmax(deepest, body_pos(w, b).y + s / 2.0 - GROUND_TOP);
                }
                /* Deeper than half the box plus a pixel, contacts would push it out the wrong side. */
                cr_assert_leq(deepest, s / 2.0 + 1, "dt %g s: %d px box landed %.3f px into the ground", dts[k], s,
                              deepest);
                const pp_vec2 p = body_pos(w, b);
                const double pen = p.y + s / 2.0 - GROUND_TOP, tilt = RAD2DEG(wrap_angle(body_angle(w, b)));
                cr_log_info("%d px box, dt %.5f s, sleep %d: rests %.3f px into the ground (landed %.3f), x %+.4f, "
                            "tilt %.4f deg",
                            s, dts[k], sleep, pen, deepest, p.x - 400, tilt);
                cr_assert(pen >= 0.25 && pen <= 1.25, "dt %g s: %d px box rests %.3f px into the ground", dts[k], s,
                          pen);
                cr_assert_leq(fabs(p.x - 400), 0.5, "dt %g s: box slid %.3f px", dts[k], p.x - 400);
                cr_assert_leq(fabs(tilt), 0.5, "dt %g s: box tilted %.3f deg", dts[k], tilt);
                cr_assert_lt(body_speed(w, b), 1.0, "dt %g s: box still moving at %.3f px/s", dts[k], body_speed(w, b));
                lo = fmin(lo, pen), hi = fmax(hi, pen);
                pp_world_destroy(w);
            }
            cr_assert_leq(hi - lo, 0.5, "%d px box (sleep %d): resting depth varies by %.3f px across dt (%.3f..%.3f)",
                          sizes[si], sleep, hi - lo, lo, hi);
        }
}

/* ---------------------------------------------------------------------------------------------
 * 6. 5,000 px/s against an 8 px static wall. A substep (1/120 s) moves a body 41.7 px, farther than
 * the wall and the body together, so without continuous collision the wall is missed. The wall's
 * near face is at x 496, its far face at 504; "its own side" means the body ends with its centre
 * before the wall's middle (x 500) and no part of it ever got past the far face.
 * --------------------------------------------------------------------------------------------- */

#define WALL_NEAR 496.0f
#define WALL_FAR 504.0f

typedef struct shot {
    float final_x;   /* centre at the end, px */
    float far_front; /* farthest the body's front edge (centre + half its extent along x) got, px */
    float speed;     /* at the end, px/s */
    int finite;
} shot;

/* In a world without gravity, fires a body (a width×height box, or a disc of diameter width) from
 * x 100 + phase at `speed` along `dir_deg` and steps one second. */
static shot fire_at_wall(uint32_t continuous, int width, int height, int disc, float speed, float phase,
                         float dir_deg) {
    pp_world_def wd = pp_world_def_default();
    wd.gravity = v2(0, 0);
    wd.continuous = continuous;
    pp_world w = make_world_def(&wd);
    add_rect(w, body_def(PP_BODY_STATIC, 0.5f * (WALL_NEAR + WALL_FAR), 300, 0), (int)(WALL_FAR - WALL_NEAR), 2400);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 100 + phase, 300, 0);
    d.linear_velocity = v2(speed * (float)cos(DEG2RAD(dir_deg)), speed * (float)sin(DEG2RAD(dir_deg)));
    pp_body b = disc ? add_disc(w, d, width / 2) : add_rect(w, d, width, height);
    shot r = {0, -INFINITY, 0, 1};
    for (int i = 0; i < 60; i++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        r.finite &= body_finite(w, b);
        r.far_front = fmaxf(r.far_front, body_pos(w, b).x + 0.5f * width);
    }
    r.final_x = body_pos(w, b).x;
    r.speed = (float)body_speed(w, b);
    cr_assert_eq(body_count(w), 2);
    pp_world_destroy(w);
    return r;
}

static int stayed_on_its_side(const shot *r) {
    return r->finite && r->final_x < 0.5f * (WALL_NEAR + WALL_FAR) && r->far_front < WALL_FAR;
}

/* 16 start phases spread over one substep's travel at 5,000 px/s, so the wall falls at every
 * point between two substep positions. */
#define PHASES 16
static float phase_of(int k) { return k * (5000.0f / 120.0f) / PHASES; }

Test(extremes, fast_boxes_and_discs_stop_at_an_8px_wall) {
    const int sizes[] = {4, 8, 16};
    const float speeds[] = {1000, 2500, 5000};
    for (int disc = 0; disc <= 1; disc++)
        for (int i = 0; i < 3; i++)
            for (int v = 0; v < 3; v++) {
                float deepest = 0, rebound = 0;
                /* Restitution is 0, yet the body comes back: the sweep stops it up to about half its
                 * thickness into the wall (measured: 2.5 px for 4 px bodies, 7.8 px for 16 px), and the
                 * contact turns that overlap into a separating speed, at most the section 7 bound. */
                pp_world_def wd = pp_world_def_default();
                wd.gravity = v2(0, 0);
                const double rebound_bound = separation_bound(&wd, sizes[i] / 2.0 + 1.0, DT);
                for (int k = 0; k < PHASES; k++) {
                    const shot r = fire_at_wall(1, sizes[i], sizes[i], disc, speeds[v], phase_of(k), 0);
                    cr_assert(stayed_on_its_side(&r),
                              "%s %d px at %.0f px/s, phase %.1f: ended at x %.2f, front reached %.2f (wall %.0f..%.0f)",
                              disc ? "disc" : "box", sizes[i], speeds[v], phase_of(k), r.final_x, r.far_front,
                              WALL_NEAR, WALL_FAR);
                    cr_assert_leq(r.speed, rebound_bound, "%s %d px at %.0f px/s: rebounds at %.1f px/s (bound %.1f)",
                                  disc ? "disc" : "box", sizes[i], speeds[v], r.speed, rebound_bound);
                    deepest = fmaxf(deepest, r.far_front - WALL_NEAR);
                    rebound = fmaxf(rebound, r.speed);
                }
                cr_log_info("%s %d px at %.0f px/s: front reached at most %.2f px into the 8 px wall, rebounds at up "
                            "to %.1f px/s",
                            disc ? "disc" : "box", sizes[i], speeds[v], deepest, rebound);
            }
}

Test(extremes, fast_thin_bodies_stop_at_an_8px_wall) {
    /* Bodies thin along or across the shot, the 1×512 stick broadside and the 512×1 one end on. */
    const struct { int w, h; } shapes[] = {{2, 2}, {3, 3}, {2, 8}, {8, 2}, {1, 512}, {512, 1}};
    for (int s = 0; s < 6; s++) {
        float deepest = 0;
        for (int k = 0; k < PHASES; k++) {
            const shot r = fire_at_wall(1, shapes[s].w, shapes[s].h, 0, 5000, phase_of(k), 0);
            cr_assert(stayed_on_its_side(&r), "%d×%d at 5000 px/s, phase %.1f: ended at x %.2f, front reached %.2f",
                      shapes[s].w, shapes[s].h, phase_of(k), r.final_x, r.far_front);
            deepest = fmaxf(deepest, r.far_front - WALL_NEAR);
        }
        cr_log_info("%d×%d at 5000 px/s: front reached at most %.2f px into the wall", shapes[s].w, shapes[s].h,
                    deepest);
    }
}

Test(extremes, fast_bodies_stop_at_an_8px_wall_when_shot_obliquely) {
    const float dirs[] = {-60, -30, 30, 60};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < PHASES; k++) {
            const shot r = fire_at_wall(1, 8, 8, 0, 5000, phase_of(k), dirs[i]);
            cr_assert(stayed_on_its_side(&r),
                      "8 px box at 5000 px/s, %.0f deg, phase %.1f: ended at x %.2f, front %.2f", dirs[i],
                      phase_of(k), r.final_x, r.far_front);
        }
}

Test(extremes, fast_bodies_land_on_an_8px_floor) {
    /* Fired straight down at 5,000 px/s with gravity onto an 8 px floor: they end lying on it. */
    const int sizes[] = {4, 8, 16};
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < PHASES; k++) {
            pp_world w = make_world(0, 980);
            add_rect(w, body_def(PP_BODY_STATIC, 400, 804, 0), 800, 8); /* top face at 800 */
            pp_body_def d = body_def(PP_BODY_DYNAMIC, 400, 100 + phase_of(k), 0);
            d.linear_velocity = v2(0, 5000);
            pp_body b = add_rect(w, d, sizes[i], sizes[i]);
            step_n(w, DT, 120);
            cr_assert(body_finite(w, b));
            const double pen = body_pos(w, b).y + sizes[i] / 2.0 - 800;
            cr_assert(pen > -0.5 && pen < 2.0,
                      "%d px box shot down at 5000 px/s, phase %.1f: rests %.2f px into the floor", sizes[i],
                      phase_of(k), pen);
            cr_assert_lt(body_speed(w, b), 1.0, "%d px box on the floor moves at %.2f px/s", sizes[i],
                         body_speed(w, b));
            pp_world_destroy(w);
        }
}

Test(extremes, without_continuous_collision_fast_bodies_tunnel) {
    /* The baseline the tests above stand on. Some phases put a substep position inside the wall,
     * where contacts catch the body; measured, 12 to 14 of the 16 phases pass through. */
    const int sizes[] = {4, 8, 16};
    for (int disc = 0; disc <= 1; disc++)
        for (int i = 0; i < 3; i++) {
            int tunnelled = 0;
            for (int k = 0; k < PHASES; k++) {
                const shot r = fire_at_wall(0, sizes[i], sizes[i], disc, 5000, phase_of(k), 0);
                tunnelled += r.final_x > WALL_FAR + 1000;
            }
            cr_log_info("continuous off: %s %d px at 5000 px/s passed the wall in %d of %d phases",
                        disc ? "disc" : "box", sizes[i], tunnelled, PHASES);
            cr_assert_geq(tunnelled, PHASES / 2, "continuous off: %s %d px at 5000 px/s passed in only %d of %d phases",
                          disc ? "disc" : "box", sizes[i], tunnelled, PHASES);
        }
}

Test(extremes, one_pixel_body_stops_at_an_8px_wall, .disabled = true) {
    /* The target. Fails today at every phase: the sweep now stops a 1×1 body at the wall, but the
     * contact of a single free-rotating pixel then spins it through (with fixed_rotation it holds,
     * see continuous tests). */
    for (int k = 0; k < PHASES; k++) {
        const shot r = fire_at_wall(1, 1, 1, 0, 5000, phase_of(k), 0);
        cr_assert(stayed_on_its_side(&r), "1×1 at 5000 px/s, phase %.1f: ended at x %.2f", phase_of(k), r.final_x);
    }
}

/* ---------------------------------------------------------------------------------------------
 * 7. Bodies spawned overlapping by half. ODE corrects a contact's depth d beyond the slop through
 * the constraint's velocity: per solver step of h = dt / substeps it asks for a separating speed
 * of contact_erp · (d − contact_slop) / h, capped at max_correction_speed. So the pair's relative
 * speed is bounded by
 *     v_max = min(contact_erp · (d0 − contact_slop) · substeps / dt, max_correction_speed)   (+ g·h under gravity),
 * d0 being the spawn overlap. Measured before the cap, the first step reached the uncapped term
 * exactly (32 px boxes, d0 16 px: 366 px/s at 1/60 s, 1460 px/s at 1/240 s) and 64 px boxes at
 * 1/240 s flew apart at 3,000 px/s; with the default cap of 300 px/s no pair separates faster.
 * The bound asserted is 1.1 · v_max + g·h.
 * --------------------------------------------------------------------------------------------- */

Test(extremes, half_overlapping_bodies_separate_at_a_bounded_speed) {
    const int sizes[] = {8, 16, 32, 64};
    const float dts[] = {1.0f / 60, 1.0f / 240};
    for (int disc = 0; disc <= 1; disc++)
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 2; k++) {
                pp_world_def wd = pp_world_def_default();
                wd.gravity = v2(0, 0);
                pp_world w = make_world_def(&wd);
                const int s = sizes[i];
                /* Centres s/2 apart: half of each body overlaps the other, the overlap s/2 deep. */
                const pp_body_def da = body_def(PP_BODY_DYNAMIC, 400 - s / 4.0f, 300, 0);
                const pp_body_def db = body_def(PP_BODY_DYNAMIC, 400 + s / 4.0f, 300, 0);
                pp_body a = disc ? add_disc(w, da, s / 2) : add_rect(w, da, s, s);
                pp_body b = disc ? add_disc(w, db, s / 2) : add_rect(w, db, s, s);
                const double bound = separation_bound(&wd, s / 2.0, dts[k]);
                double worst = 0;
                const int n = (int)lround(1.0 / dts[k]);
                for (int j = 0; j < n; j++) {
                    PP_OK_OR_FAIL(pp_world_step(w, dts[k]));
                    cr_assert(body_finite(w, a) && body_finite(w, b));
                    const pp_vec2 va = body_vel(w, a), vb = body_vel(w, b);
                    worst = fmax(worst, hypot(vb.x - va.x, vb.y - va.y));
                }
                const pp_vec2 pa = body_pos(w, a), pb = body_pos(w, b);
                cr_log_info("%s %d px overlapping by half, dt %.5f: separated at up to %.1f px/s (bound %.1f), now %.1f px "
                            "apart",
                            disc ? "discs" : "boxes", s, dts[k], worst, bound, pb.x - pa.x);
                cr_assert_leq(worst, bound, "%s %d px, dt %g: separated at %.1f px/s, over the bound %.1f px/s",
                              disc ? "discs" : "boxes", s, dts[k], worst, bound);
                cr_assert_gt(worst, 0.5 * bound / 1.1, "%s %d px, dt %g: separated at only %.1f px/s (v_max %.1f)",
                             disc ? "discs" : "boxes", s, dts[k], worst, bound / 1.1);
                /* Apart: their centres at least a body width less the slop apart, no longer in contact. */
                cr_assert_geq(pb.x - pa.x, s - 1.0, "%s %d px, dt %g: centres only %.2f px apart after 1 s",
                              disc ? "discs" : "boxes", s, dts[k], pb.x - pa.x);
                pp_contact c[2];
                int32_t nc = 0;
                PP_OK_OR_FAIL(pp_world_collide(w, a, b, c, 2, &nc));
                cr_assert_eq(nc, 0, "%s %d px, dt %g: still touching after 1 s", disc ? "discs" : "boxes", s, dts[k]);
                pp_world_destroy(w);
            }
}

Test(extremes, half_overlapping_stack_separates_and_rests) {
    /* On the ground at 1/60 s: the top box spawned half inside the bottom one pops up by less
     * than v_max²/2g and both come to rest stacked. */
    const int sizes[] = {8, 16, 32};
    for (int i = 0; i < 3; i++) {
        pp_world_def wd = pp_world_def_default();
        pp_world w = make_world_def(&wd);
        add_ground(w);
        const int s = sizes[i];
        pp_body low = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - s / 2.0f, 0), s, s);
        pp_body up = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - s, 0), s, s);
        const double bound = separation_bound(&wd, s / 2.0, DT);
        double worst = 0, highest = INFINITY;
        for (int j = 0; j < 300; j++) {
            PP_OK_OR_FAIL(pp_world_step(w, DT));
            cr_assert(body_finite(w, low) && body_finite(w, up));
            const pp_vec2 va = body_vel(w, low), vb = body_vel(w, up);
            worst = fmax(worst, hypot(vb.x - va.x, vb.y - va.y));
            highest = fmin(highest, body_pos(w, up).y);
        }
        const double rise = (GROUND_TOP - s) - highest, rise_bound = bound * bound / (2 * 980.0);
        const pp_vec2 pl = body_pos(w, low), pu = body_pos(w, up);
        cr_log_info("%d px stack spawned half overlapping: %.1f px/s (bound %.1f), top rose %.1f px (bound %.1f), rests at "
                    "%.3f / %.3f",
                    s, worst, bound, rise, rise_bound, pl.y, pu.y);
        cr_assert_leq(worst, bound, "%d px: separated at %.1f px/s, bound %.1f", s, worst, bound);
        cr_assert_leq(rise, rise_bound, "%d px: top box rose %.1f px, more than v_max²/2g = %.1f", s, rise, rise_bound);
        cr_assert_float_eq(pl.y, GROUND_TOP - 0.5 * s + 0.75, 1.0, "%d px: bottom box rests at y %.3f", s, pl.y);
        cr_assert_float_eq(pu.y, GROUND_TOP - 1.5 * s + 1.5, 1.0, "%d px: top box rests at y %.3f", s, pu.y);
        cr_assert_leq(fabs(pu.x - 400) + fabs(pl.x - 400), 1.0, "%d px: the stack slid", s);
        cr_assert_lt(body_speed(w, up), 1.0, "%d px: top box still moving", s);
        pp_world_destroy(w);
    }
}

/* ---------------------------------------------------------------------------------------------
 * 8. A 10-box tower for 100,000 steps at 1/60 s (27.8 simulated minutes).
 *
 * Measured: with the defaults (QuickStep, 20 iterations, 2 substeps, MANIFOLD contacts) a 10-box
 * tower does not stand at all: 16 px boxes fall within the first 2 s, 32 px boxes after about
 * 3 s, sleep on or off. With sleep on the defaults hold towers of 4 boxes of 16 px and 5 of 32 px
 * (5 and 7 fall); without sleep even a 2-box stack creeps sideways 1.5 px within 40 s. 100 iterations,
 * CENTROID contacts or the exact solver hold the 10-box tower (sleep on). The exact solver holds it
 * without sleep too: over the full 100,000 steps the worst drift is 0.025 px (32 px boxes) and
 * 0.032 px (16 px), at about 0.35 ms a step; the no-sleep test runs 10,000 steps to stay quick.
 * --------------------------------------------------------------------------------------------- */

/* Stacks n s×s boxes exactly, settles 2 s, then steps `steps` times checking every 10th step (and
 * the last) that no box moved more than 1 px from its settled position and nothing is NaN. */
static double tower_drift(const pp_world_def *d, int n, int s, int steps, int *worst_step) {
    pp_world w = make_world_def(d);
    add_ground(w);
    pp_body b[16];
    pp_vec2 settled[16];
    for (int k = 0; k < n; k++)
        b[k] = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - s / 2.0f - k * s, 0), s, s);
    step_n(w, DT, 120);
    for (int k = 0; k < n; k++) settled[k] = body_pos(w, b[k]);
    double worst = 0;
    *worst_step = -1;
    for (int i = 0; i < steps; i++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        if (i % 10 != 9 && i != steps - 1) continue;
        for (int k = 0; k < n; k++) {
            cr_assert(body_finite(w, b[k]), "tower box %d: NaN or Inf at step %d", k, i);
            const pp_vec2 p = body_pos(w, b[k]);
            const double dd = hypot(p.x - settled[k].x, p.y - settled[k].y);
            if (dd > worst) worst = dd, *worst_step = i;
        }
    }
    /* Settled between touching and a stack of slop-deep contacts: box k between GROUND_TOP − (k + ½)s
     * and that plus (k + 1)·slop (a pile may fall asleep before its contacts reach the slop). */
    for (int k = 0; k < n; k++) {
        const double top = GROUND_TOP - (k + 0.5) * s;
        cr_assert(settled[k].y >= top - 0.05 && settled[k].y <= top + (k + 1) * d->contact_slop + 0.5 + 0.05 * k,
                  "tower box %d settled at y %.3f, not in %.2f..%.2f", k, settled[k].y, top,
                  top + (k + 1) * d->contact_slop);
    }
    cr_assert_eq(body_count(w), n + 1);
    pp_world_destroy(w);
    return worst;
}

Test(extremes, ten_box_tower_stands_100000_steps, .timeout = 120) {
    pp_world_def d = pp_world_def_default();
    d.exact_solver = 1;
    const int sizes[] = {16, 32};
    for (int i = 0; i < 2; i++) {
        int at;
        const double drift = tower_drift(&d, 10, sizes[i], 100000, &at);
        cr_log_info("10 × %d px tower, exact solver, sleep on: worst drift %.4f px over 100,000 steps (step %d)",
                    sizes[i], drift, at);
        cr_assert_leq(drift, 1.0, "10 × %d px tower drifted %.3f px (step %d)", sizes[i], drift, at);
    }
}

Test(extremes, ten_box_tower_stands_without_sleep, .timeout = 120) {
    pp_world_def d = pp_world_def_default();
    d.exact_solver = 1;
    d.allow_sleep = 0;
    int at;
    const double drift = tower_drift(&d, 10, 16, 10000, &at);
    cr_log_info("10 × 16 px tower, exact solver, no sleep: worst drift %.4f px over 10,000 steps (step %d)", drift,
                at);
    cr_assert_leq(drift, 1.0, "10 × 16 px tower without sleep drifted %.3f px (step %d)", drift, at);
}

Test(extremes, short_towers_stand_100000_steps_with_the_defaults, .timeout = 120) {
    /* What the default QuickStep settings hold (with sleep): 4 boxes of 16 px, 5 of 32 px. */
    pp_world_def d = pp_world_def_default();
    const int sizes[] = {16, 32}, counts[] = {4, 5};
    for (int i = 0; i < 2; i++) {
        int at;
        const double drift = tower_drift(&d, counts[i], sizes[i], 100000, &at);
        cr_log_info("%d × %d px tower, defaults: worst drift %.4f px over 100,000 steps", counts[i], sizes[i], drift);
        cr_assert_leq(drift, 1.0, "%d × %d px tower drifted %.3f px (step %d)", counts[i], sizes[i], drift, at);
    }
}

Test(extremes, ten_box_tower_stands_with_the_defaults, .timeout = 120) {
    /* The stability bar (tests/bench/README.md): a 10-box tower stands for 60 simulated seconds. With the defaults (sleep on)
     * for 100,000 steps, and awake for 60 s, where only the solver holds it. */
    pp_world_def d = pp_world_def_default();
    const int sizes[] = {16, 32};
    for (int i = 0; i < 2; i++) {
        int at;
        double drift = tower_drift(&d, 10, sizes[i], 100000, &at);
        cr_log_info("10 × %d px tower, defaults: worst drift %.4f px over 100,000 steps", sizes[i], drift);
        cr_assert_leq(drift, 1.0, "10 × %d px tower drifted %.3f px (step %d)", sizes[i], drift, at);
        pp_world_def awake = d;
        awake.allow_sleep = 0;
        drift = tower_drift(&awake, 10, sizes[i], 3600, &at);
        cr_log_info("10 × %d px tower, defaults without sleep: worst drift %.4f px over 60 s", sizes[i], drift);
        cr_assert_leq(drift, 2.0, "10 × %d px tower without sleep drifted %.3f px in 60 s (step %d)", sizes[i], drift, at);
    }
}

/* ---------------------------------------------------------------------------------------------
 * 9. Randomized scenes: a closed 256×256 box of 40 px static walls (floor, ceiling, sides) and
 * 2–5 random boxes and discs, 3–32 px, 0.1–10 density, up to 1,000 px/s and 10 rad/s, restitution
 * 0–0.8, friction 0–1, stepped 600 times at 1/60 s. No value may become NaN or Inf and no body may
 * leave the box (through the floor or anywhere else). Each scene has its own seed, derived from
 * RANDOM_SEED and its index, so a failure names a scene that can be replayed alone.
 *
 * Measured when this suite was written: bodies 1–2 px thin were lost through the 40 px walls in
 * about 1 scene in 200 (1×1, 1×2, 2×1, 1×3 boxes, 2×2 discs at 250–750 px/s), and so was a thin
 * body asleep on the floor when something fast landed on it; the latter is fixed (a sleeper paired
 * with an awake body keeps its static pairs, tests/c/test_resting.c). Sizes stay at 3–32 px and
 * speeds at 1,000 px/s here.
 * --------------------------------------------------------------------------------------------- */

#define RANDOM_SEED 0x5eed2024u
#define ARENA 256.0f
#define WALL 40.0f

static uint64_t rng_next(uint64_t *s) { /* xorshift64* */
    *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
    return *s * 2685821657736338717ull;
}
static double rng_uniform(uint64_t *s, double lo, double hi) {
    return lo + (hi - lo) * (double)(rng_next(s) >> 11) * (1.0 / 9007199254740992.0);
}
static int rng_int(uint64_t *s, int lo, int hi) { return lo + (int)(rng_next(s) % (uint64_t)(hi - lo + 1)); }

/* Runs one random scene; returns 0 or a failure described in `why`; *bodies receives its body count. */
static int random_scene(uint32_t index, char *why, size_t why_size, int *bodies) {
    uint64_t s = ((uint64_t)RANDOM_SEED << 32 | index) * 0x9E3779B97F4A7C15ull + 1;
    pp_world w = make_world(0, 980);
    const int span = (int)(ARENA + 2 * WALL), side = (int)ARENA, thick = (int)WALL;
    add_rect(w, body_def(PP_BODY_STATIC, ARENA / 2, ARENA + WALL / 2, 0), span, thick); /* floor */
    add_rect(w, body_def(PP_BODY_STATIC, ARENA / 2, -WALL / 2, 0), span, thick);        /* ceiling */
    add_rect(w, body_def(PP_BODY_STATIC, -WALL / 2, ARENA / 2, 0), thick, side);
    add_rect(w, body_def(PP_BODY_STATIC, ARENA + WALL / 2, ARENA / 2, 0), thick, side);
    enum { MAX_BODIES = 5 };
    pp_body b[MAX_BODIES];
    char desc[MAX_BODIES][48];
    const int n = rng_int(&s, 2, MAX_BODIES);
    *bodies = n;
    for (int k = 0; k < n; k++) {
        const int disc = rng_int(&s, 0, 1), bw = rng_int(&s, 3, 32), bh = rng_int(&s, 3, 32);
        pp_body_def d = body_def(PP_BODY_DYNAMIC, (float)rng_uniform(&s, 20, ARENA - 20),
                                 (float)rng_uniform(&s, 20, ARENA - 40), (float)rng_uniform(&s, -M_PI, M_PI));
        d.linear_velocity = v2((float)rng_uniform(&s, -1000, 1000), (float)rng_uniform(&s, -1000, 1000));
        d.angular_velocity = (float)rng_uniform(&s, -10, 10);
        d.density = (float)exp(rng_uniform(&s, log(0.1), log(10.0)));
        d.restitution = (float)rng_uniform(&s, 0, 0.8);
        d.friction = (float)rng_uniform(&s, 0, 1);
        if (disc) {
            b[k] = add_disc(w, d, (bw + 1) / 2);
            snprintf(desc[k], sizeof desc[k], "disc r %d, density %.2f", (bw + 1) / 2, d.density);
        } else {
            b[k] = add_rect(w, d, bw, bh);
            snprintf(desc[k], sizeof desc[k], "box %d×%d, density %.2f", bw, bh, d.density);
        }
    }
    int failed = 0;
    for (int i = 0; i < 600 && !failed; i++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        for (int k = 0; k < n && !failed; k++) {
            const pp_vec2 p = body_pos(w, b[k]);
            if (!body_finite(w, b[k])) {
                snprintf(why, why_size, "scene %u, step %d: %s became NaN or Inf", index, i, desc[k]);
                failed = 1;
            } else if (p.y > ARENA + WALL || p.y < -WALL || p.x < -WALL || p.x > ARENA + WALL) {
                snprintf(why, why_size, "scene %u, step %d: %s left the box, at (%.1f, %.1f)", index, i, desc[k],
                         p.x, p.y);
                failed = 1;
            }
        }
    }
    if (!failed && body_count(w) != n + 4) {
        snprintf(why, why_size, "scene %u: %d bodies, expected %d", index, (int)body_count(w), n + 4);
        failed = 1;
    }
    pp_world_destroy(w);
    return failed;
}

/* 1,000 scenes in four tests of 250, so that `--jobs 2` runs them side by side. */
static void random_scenes(uint32_t first, uint32_t count) {
    char why[256] = "";
    int failures = 0, bodies = 0;
    for (uint32_t i = first; i < first + count; i++) {
        int n = 0;
        if (random_scene(i, why, sizeof why, &n) && failures++ < 5) cr_log_error("%s", why);
        bodies += n;
    }
    cr_log_info("random scenes %u..%u (seed %#x): %d bodies, %u × 600 steps, %d scenes failed", first,
                first + count - 1, RANDOM_SEED, bodies, count, failures);
    cr_assert_eq(failures, 0, "%d of %u random scenes failed (seed %#x); last: %s", failures, count, RANDOM_SEED, why);
}

Test(extremes, random_scenes_0_249, .timeout = 300) { random_scenes(0, 250); }
Test(extremes, random_scenes_250_499, .timeout = 300) { random_scenes(250, 250); }
Test(extremes, random_scenes_500_749, .timeout = 300) { random_scenes(500, 250); }
Test(extremes, random_scenes_750_999, .timeout = 300) { random_scenes(750, 250); }

/* Every density the API takes, on either crate of a two-crate stack settled on the ground, and on one box of a
 * revolute pair: no step may reach an ODE assertion (a 16 px crate of density 1e-13 under one of 1 aborted the
 * process in the exact solver's factorisation, dxLDLTRemove; 1e-30 in dxNormalize4), and every body stays
 * finite. Up to 1000:1 the stack still stands (light_on_heavy, heavy_on_light above); past the exact solver's
 * ratio it is QuickStep's, which lets the heavy crate sink through the light one but keeps the numbers whole. */
Test(extremes, tiny_and_huge_densities_never_reach_an_ode_assertion, .timeout = 120) {
    for (int e = -45; e <= 38; e += 1) {
        const float density = powf(10.0f, (float)e);
        if (!(density > 0) || !isfinite(density))
            continue;
        for (int which = 0; which < 3; which++) {
            pp_world w = make_world(0, 980);
            add_ground(w);
            pp_body a = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, GROUND_TOP - 8, 0), 16, 16);
            pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, GROUND_TOP - 24, 0), 16, 16);
            if (which == 2) { /* a revolute pair beside the stack, the light box hanging from the heavy one */
                pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
                jd.body_a = a, jd.body_b = b, jd.anchor_a = v2(300, GROUND_TOP - 16);
                pp_joint j;
                PP_OK_OR_FAIL(pp_joint_create(w, &jd, &j));
            }
            step_n(w, DT, 20);
            PP_OK_OR_FAIL(pp_body_set_density(w, which == 1 ? b : a, density));
            for (int k = 0; k < 30; k++) {
                const pp_status st = pp_world_step(w, DT);
                cr_assert(st == PP_OK || st == PP_ERR_LIMIT, "density %g: step %d: %s (%s)", density, k,
                          pp_status_name(st), pp_last_error());
            }
            cr_assert(body_finite(w, a) && body_finite(w, b), "density %g on %s: a body is not finite", density,
                      which == 1 ? "the top crate" : "the bottom crate");
            pp_world_destroy(w);
        }
    }
}

/* The largest forces, torques and gravity scales the API takes, on a stack solved exactly and on a revolute pair,
 * every step for half a second: no ODE assertion, every status PP_OK or PP_ERR_LIMIT (a step undone past a
 * float), every body finite. */
Test(extremes, huge_forces_torques_and_scales_never_reach_an_ode_assertion, .timeout = 120) {
    const float values[] = {FLT_MAX, -FLT_MAX, 1e30f, -1e30f, 1e10f, 1e-30f};
    for (size_t v = 0; v < sizeof values / sizeof values[0]; v++)
        for (int mode = 0; mode < 3; mode++)
            for (int jointed = 0; jointed < 2; jointed++) {
                pp_world w = make_world(0, 980);
                add_ground(w);
                pp_body a = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, GROUND_TOP - 8, 0), 16, 16);
                pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, GROUND_TOP - 24, 0), 16, 16);
                if (jointed) {
                    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
                    jd.body_a = a, jd.body_b = b, jd.anchor_a = v2(300, GROUND_TOP - 16);
                    pp_joint j;
                    PP_OK_OR_FAIL(pp_joint_create(w, &jd, &j));
                }
                step_n(w, DT, 20);
                const float x = values[v];
                for (int k = 0; k < 30; k++) {
                    if (mode == 0)
                        PP_OK_OR_FAIL(pp_body_apply_force(w, b, v2(x, x), v2(305, GROUND_TOP - 30)));
                    else if (mode == 1)
                        PP_OK_OR_FAIL(pp_body_apply_torque(w, a, x));
                    else
                        PP_OK_OR_FAIL(pp_body_set_gravity_scale(w, b, x > 0 ? PP_MAX_GRAVITY_SCALE : -PP_MAX_GRAVITY_SCALE));
                    const pp_status st = pp_world_step(w, DT);
                    cr_assert(st == PP_OK || st == PP_ERR_LIMIT, "%g, mode %d: %s (%s)", x, mode, pp_status_name(st),
                              pp_last_error());
                }
                cr_assert(body_finite(w, a) && body_finite(w, b), "%g, mode %d: a body is not finite", x, mode);
                pp_world_destroy(w);
            }
}
