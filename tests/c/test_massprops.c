/* Mass, centre of mass and inertia computed from the pixels, against counts and sums
 * done here pixel by pixel (each pixel a unit square: its own inertia is w·(1+1)/12 = w/6). */
#include "helpers.h"

PP_TEST_SUITE(massprops);

/* Relative difference |a - b| / |b|. */
static double rel_err(double a, double b) { return fabs(a - b) / fabs(b); }

/* Exact mass properties of a bitmap: solid[k] != 0 marks a solid pixel, weight[k] its 0..255 weight. */
static void pixel_sums(int width, int height, const uint8_t *solid, const uint8_t *weight, double density,
                       double *mass, double *cx, double *cy, double *inertia) {
    double m = 0, sx = 0, sy = 0;
    for (int j = 0; j < height; j++)
        for (int i = 0; i < width; i++) {
            int k = j * width + i;
            if (!solid[k]) continue;
            double wt = weight ? weight[k] / 255.0 : 1.0;
            m += wt;
            sx += wt * (i + 0.5);
            sy += wt * (j + 0.5);
        }
    double x = sx / m, y = sy / m, in = 0;
    for (int j = 0; j < height; j++)
        for (int i = 0; i < width; i++) {
            int k = j * width + i;
            if (!solid[k]) continue;
            double wt = weight ? weight[k] / 255.0 : 1.0;
            double dx = i + 0.5 - x, dy = j + 0.5 - y;
            in += wt * (dx * dx + dy * dy + 1.0 / 6.0);
        }
    *mass = density * m;
    *cx = x;
    *cy = y;
    *inertia = density * in;
}

Test(massprops, filled_rectangle_is_exact) {
    pp_world w = make_world(0, 980);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 100, 100, 0);
    d.density = 2.0f;
    pp_body b = add_rect(w, d, 30, 20);

    float m = 0, in = 0;
    pp_vec2 c = {0, 0};
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, &c, &in));
    double want_m = 2.0 * 600, want_i = want_m * (30.0 * 30 + 20.0 * 20) / 12.0;
    cr_assert_float_eq(m, want_m, 1e-3, "mass %g, want %g", m, want_m);
    cr_assert_float_eq(c.x, 15.0, 1e-4, "centre x %g, want 15", c.x);
    cr_assert_float_eq(c.y, 10.0, 1e-4, "centre y %g, want 10", c.y);
    cr_assert_lt(rel_err(in, want_i), 1e-5, "inertia %g, want %g", in, want_i);

    /* Any out pointer may be NULL. */
    float m2 = 0;
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m2, NULL, NULL));
    cr_assert_float_eq(m2, m, 0.0);
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, NULL, NULL, NULL));
    pp_world_destroy(w);
}

Test(massprops, disc_against_pixel_sum_and_analytic) {
    const int r = 40;
    int count = 0;
    uint8_t *mask = disc_mask(r, &count);
    double pm, pcx, pcy, pin;
    pixel_sums(2 * r, 2 * r, mask, NULL, 1.0, &pm, &pcx, &pcy, &pin);
    cr_assert_float_eq(pm, count, 1e-9);

    pp_world w = make_world(0, 980);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 300, 200, 0.3f);
    d.width = d.height = 2 * r;
    d.mask = mask;
    pp_body b = create_body_ok(w, &d);
    free(mask);

    float m = 0, in = 0;
    pp_vec2 c = {0, 0};
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, &c, &in));
    cr_assert_float_eq(m, (float)count, 1e-3, "mass %g, pixel count %d", m, count);
    cr_assert_float_eq(c.x, r, 0.01, "centre x %g, want %d", c.x, r);
    cr_assert_float_eq(c.y, r, 0.01, "centre y %g, want %d", c.y, r);
    cr_assert_lt(rel_err(in, pin), 0.01, "inertia %g, pixel sum %g", in, pin);
    double analytic = count * (double)r * r / 2.0;
    cr_assert_lt(rel_err(in, analytic), 0.02, "inertia %g, m r^2/2 = %g", in, analytic);
    pp_world_destroy(w);
}

Test(massprops, weighted_bitmap_shifts_centre) {
    /* 20×10: left half weight 255, right half weight 51 (= 0.2). */
    const int W = 20, H = 10;
    uint8_t mask[20 * 10], wt[20 * 10];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            mask[j * W + i] = 1;
            wt[j * W + i] = i < W / 2 ? 255 : 51;
        }
    double pm, pcx, pcy, pin;
    pixel_sums(W, H, mask, wt, 3.0, &pm, &pcx, &pcy, &pin);
    /* Analytic: mass 3·(100 + 20) = 360, centre x = (100·5 + 20·15) / 120 = 20/3. */
    cr_assert_float_eq(pm, 360.0, 1e-9);
    cr_assert_float_eq(pcx, 20.0 / 3.0, 1e-9);

    pp_world w = make_world(0, 980);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 100, 100, 0);
    d.density = 3.0f;
    d.width = W;
    d.height = H;
    d.mask = mask;
    d.weights = wt;
    pp_body b = create_body_ok(w, &d);

    float m = 0, in = 0;
    pp_vec2 c = {0, 0};
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, &c, &in));
    cr_assert_float_eq(m, 360.0, 1e-2, "mass %g, want 360", m);
    cr_assert_float_eq(c.x, 20.0 / 3.0, 1e-3, "centre x %g, want %g", c.x, 20.0 / 3.0);
    cr_assert_float_eq(c.y, 5.0, 1e-3, "centre y %g, want 5", c.y);
    cr_assert_lt(rel_err(in, pin), 1e-4, "inertia %g, weighted pixel sum %g", in, pin);
    pp_world_destroy(w);
}

Test(massprops, weights_without_mask_weigh_only_solid_pixels) {
    /* rgba sprite, alpha 255 on the top 4 rows only; weights 255 everywhere: the
     * transparent rows carry weight but are not solid, so they add no mass. */
    const int W = 8, H = 8;
    uint8_t rgba[8 * 8 * 4], wt[8 * 8];
    for (int k = 0; k < W * H; k++) {
        rgba[4 * k + 0] = rgba[4 * k + 1] = rgba[4 * k + 2] = 200;
        rgba[4 * k + 3] = (k / W) < 4 ? 255 : 0;
        wt[k] = 255;
    }
    pp_world w = make_world(0, 980);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 50, 50, 0);
    d.width = W;
    d.height = H;
    d.rgba = rgba;
    d.weights = wt;
    pp_body b = create_body_ok(w, &d);
    float m = 0;
    pp_vec2 c = {0, 0};
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, &c, NULL));
    cr_assert_float_eq(m, 32.0, 1e-3, "mass %g, want 32", m);
    cr_assert_float_eq(c.x, 4.0, 1e-3, "centre x %g", c.x);
    cr_assert_float_eq(c.y, 2.0, 1e-3, "centre y %g", c.y);
    pp_world_destroy(w);
}

/* A 16×16 sprite whose pixel k (row-major) has alpha k: rows j ≥ 8 have alpha ≥ 128. */
static void alpha_ramp(uint8_t *rgba) {
    for (int k = 0; k < 256; k++) {
        rgba[4 * k + 0] = 255;
        rgba[4 * k + 1] = 0;
        rgba[4 * k + 2] = 0;
        rgba[4 * k + 3] = (uint8_t)k;
    }
}

Test(massprops, sprite_alpha_threshold) {
    uint8_t rgba[256 * 4];
    alpha_ramp(rgba);
    pp_world w = make_world(0, 980);

    pp_body_def d = body_def(PP_BODY_DYNAMIC, 50, 50, 0);
    d.width = d.height = 16;
    d.rgba = rgba;
    cr_assert_eq(d.alpha_threshold, 128u, "default alpha_threshold %u", d.alpha_threshold);
    pp_body b = create_body_ok(w, &d);
    float m = 0;
    pp_vec2 c = {0, 0};
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, &c, NULL));
    cr_assert_float_eq(m, 128.0, 1e-3, "mass %g with threshold 128 (alpha >= 128 is solid)", m);
    cr_assert_float_eq(c.x, 8.0, 1e-3, "centre x %g", c.x);
    cr_assert_float_eq(c.y, 12.0, 1e-3, "centre y %g", c.y);

    /* Threshold 200: alpha 200..255 solid = 56 pixels, inclusive at 200. */
    d.alpha_threshold = 200;
    b = create_body_ok(w, &d);
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, NULL, NULL));
    cr_assert_float_eq(m, 56.0, 1e-3, "mass %g with threshold 200", m);

    /* Threshold 255: only the last pixel. */
    d.alpha_threshold = 255;
    b = create_body_ok(w, &d);
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, &c, NULL));
    cr_assert_float_eq(m, 1.0, 1e-4, "mass %g with threshold 255", m);
    cr_assert_float_eq(c.x, 15.5, 1e-3);
    cr_assert_float_eq(c.y, 15.5, 1e-3);
    pp_world_destroy(w);
}

Test(massprops, mask_overrides_rgba) {
    uint8_t rgba[256 * 4], mask[256];
    pp_world w = make_world(0, 980);

    /* Fully opaque sprite, mask solid on the left half only: the mask wins. */
    for (int k = 0; k < 256; k++) {
        rgba[4 * k + 0] = rgba[4 * k + 1] = rgba[4 * k + 2] = rgba[4 * k + 3] = 255;
        mask[k] = (k % 16) < 8 ? 7 : 0; /* any non-zero value is solid */
    }
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 50, 50, 0);
    d.width = d.height = 16;
    d.rgba = rgba;
    d.mask = mask;
    pp_body b = create_body_ok(w, &d);
    float m = 0;
    pp_vec2 c = {0, 0};
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, &c, NULL));
    cr_assert_float_eq(m, 128.0, 1e-3, "mass %g: mask has 128 solid pixels, rgba 256", m);
    cr_assert_float_eq(c.x, 4.0, 1e-3, "centre x %g", c.x);
    cr_assert_float_eq(c.y, 8.0, 1e-3, "centre y %g", c.y);

    /* Fully transparent sprite, fully solid mask: solid everywhere. */
    for (int k = 0; k < 256; k++) {
        rgba[4 * k + 3] = 0;
        mask[k] = 255;
    }
    b = create_body_ok(w, &d);
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, &c, NULL));
    cr_assert_float_eq(m, 256.0, 1e-3, "mass %g: transparent sprite under a solid mask", m);
    cr_assert_float_eq(c.x, 8.0, 1e-3);
    cr_assert_float_eq(c.y, 8.0, 1e-3);
    pp_world_destroy(w);
}

Test(massprops, local_centre_is_independent_of_pose_and_pivot) {
    /* An L shape: a 20×10 bar over a 10×10 block at the left, 300 pixels. */
    const int W = 20, H = 20;
    uint8_t mask[20 * 20];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) mask[j * W + i] = (j < 10 || i < 10) ? 1 : 0;
    double pm, pcx, pcy, pin;
    pixel_sums(W, H, mask, NULL, 1.0, &pm, &pcx, &pcy, &pin);

    pp_world w = make_world(0, 980);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 10, 20, 1.0f);
    d.width = W;
    d.height = H;
    d.mask = mask;
    d.custom_pivot = 1;
    d.pivot = v2(0, 0);
    pp_body b = create_body_ok(w, &d);
    float m = 0, in = 0;
    pp_vec2 c = {0, 0};
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, &c, &in));
    cr_assert_float_eq(m, 300.0, 1e-3, "mass %g", m);
    cr_assert_float_eq(c.x, pcx, 1e-3, "centre x %g, want %g", c.x, pcx);
    cr_assert_float_eq(c.y, pcy, 1e-3, "centre y %g, want %g", c.y, pcy);
    cr_assert_lt(rel_err(in, pin), 1e-4, "inertia %g, pixel sum %g (about the centre of mass)", in, pin);
    pp_world_destroy(w);
}
