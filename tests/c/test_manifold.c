/* MANIFOLD contact points from pp_world_collide at set poses (no stepping): the two points are
 * the ends of the contact patch along the tangent, on the outer edges of its extreme pixels, so
 * a box on flat ground gets its two bottom corners, symmetric about its centre, whichever way
 * round the pair is given and however the box's bitmap is turned. */
#include "helpers.h"

PP_TEST_SUITE(manifold);

#define SINK 2.0 /* overlap of box and ground, px */

static pp_world manifold_world(pp_normal_method nm) {
    pp_world_def d = pp_world_def_default();
    d.gravity = v2(0, 0);
    d.normal_method = nm;
    d.contact_mode = PP_CONTACT_MANIFOLD;
    return make_world_def(&d);
}

/* The two contacts of a pair, ordered along x; asserts there are two. */
static void collide_two(pp_world w, pp_body a, pp_body b, pp_contact c[2], const char *what) {
    pp_contact all[4];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_collide(w, a, b, all, 4, &n));
    cr_assert_eq(n, 2, "%s: %d contacts, want 2", what, n);
    const int lo = all[0].point.x <= all[1].point.x ? 0 : 1;
    c[0] = all[lo], c[1] = all[1 - lo];
}

/* Box of width `wide` (even and odd, down to 2 px) on flat ground, pixel-aligned, sunk SINK px:
 * the patch is x in [left, left + wide), y in [top, top + SINK), so the points are (left, top + 1)
 * and (left + wide, top + 1). Checked as (box, ground), (ground, box) and with the box's bitmap
 * stored on its side and turned 90°, for both normal methods. */
Test(manifold, box_on_flat_ground_gets_its_two_bottom_corners) {
    const int widths[] = {32, 31, 8, 7, 2};
    const double top = 500.0, tall = 20.0;
    for (int m = 0; m < 2; m++) {
        pp_normal_method nm = m ? PP_NORMAL_KERNEL : PP_NORMAL_AREA_GRADIENT;
        pp_world w = manifold_world(nm);
        pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 400, (float)(top + 50), 0), 1000, 100);
        for (size_t k = 0; k < sizeof widths / sizeof widths[0]; k++) {
            const int wide = widths[k];
            const double cx = 400.0 + 0.5 * (wide & 1), cy = top + SINK - 0.5 * tall; /* pixel-aligned */
            const double want_x[2] = {cx - 0.5 * wide, cx + 0.5 * wide}, want_y = top + 0.5 * SINK;
            for (int pose = 0; pose < 3; pose++) {
                /* Pose 2 stores the box on its side (tall × wide) and turns it back by 90°. */
                const float turn = pose == 2 ? (float)(M_PI / 2) : 0.0f;
                pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, (float)cx, (float)cy, turn),
                                       pose == 2 ? (int)tall : wide, pose == 2 ? wide : (int)tall);
                char what[96];
                snprintf(what, sizeof what, "%s, %d px box%s", m ? "KERNEL" : "AREA_GRADIENT", wide,
                         pose == 1 ? ", (ground, box)" : pose == 2 ? ", bitmap turned 90 deg" : "");
                pp_contact c[2];
                if (pose == 1)
                    collide_two(w, ground, box, c, what);
                else
                    collide_two(w, box, ground, c, what);
                cr_assert_float_eq(c[0].point.x + c[1].point.x, 2.0 * cx, 1e-3,
                                   "%s: points x %g and %g are not symmetric about the centre %g", what, c[0].point.x,
                                   c[1].point.x, cx);
                for (int i = 0; i < 2; i++) {
                    cr_assert_float_eq(c[i].point.x, want_x[i], 1e-3, "%s: point %d x %.4f, want the corner %g", what,
                                       i, c[i].point.x, want_x[i]);
                    cr_assert_float_eq(c[i].point.y, want_y, 1e-3, "%s: point %d y %.4f, want mid-overlap %g", what, i,
                                       c[i].point.y, want_y);
                    cr_assert_float_eq(c[i].depth, SINK, 1e-3, "%s: point %d depth %g, want %g", what, i, c[i].depth,
                                       SINK);
                }
                PP_OK_OR_FAIL(pp_body_destroy(w, box));
            }
        }
        pp_world_destroy(w);
    }
}

/* Box and ground both turned by the same angle, the box at sub-pixel offsets along the ground's
 * face, sunk SINK px: the analytic patch is the band under the box's bottom face, and each point
 * lies within half a pixel, along the face, of that face's end (on its mid-depth line). On the
 * ground's grid the face is axis-aligned; the next test turns the face against the grid. */
Test(manifold, tilted_box_on_tilted_ground_ends_within_half_a_pixel) {
    const double degs[] = {30.0, 17.0, -40.0};
    const double gx = 1000.0, gy = 1000.0, half_w = 16.0, half_h = 10.0, ground_half_h = 50.0;
    for (size_t a = 0; a < sizeof degs / sizeof degs[0]; a++) {
        const double th = DEG2RAD(degs[a]), ca = cos(th), sa = sin(th);
        pp_world w = manifold_world(PP_NORMAL_AREA_GRADIENT);
        pp_body ground =
            add_rect(w, body_def(PP_BODY_STATIC, (float)gx, (float)gy, (float)th), 1000, 2 * (int)ground_half_h);
        pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 0, 0, (float)th), 2 * (int)half_w, 2 * (int)half_h);
        /* The ground's frame: tangent (ca, sa), normal (−sa, ca) into the ground; its top at −50. */
        double worst = 0;
        for (int k = 0; k < 16; k++) {
            const double s = -3.0 + 0.37 * k, v = -ground_half_h + SINK - half_h; /* box centre along, across */
            const double bx = gx + s * ca - v * sa, by = gy + s * sa + v * ca;
            PP_OK_OR_FAIL(pp_body_set_transform(w, box, v2((float)bx, (float)by), (float)th));
            char what[96];
            snprintf(what, sizeof what, "%.0f deg, box %.2f px along the face", degs[a], s);
            pp_contact c[2];
            collide_two(w, box, ground, c, what);
            double t[2], u[2];
            for (int i = 0; i < 2; i++) {
                const double dx = c[i].point.x - gx, dy = c[i].point.y - gy;
                t[i] = dx * ca + dy * sa, u[i] = -dx * sa + dy * ca;
            }
            const int lo = t[0] <= t[1] ? 0 : 1;
            const double end[2] = {s - half_w, s + half_w}, mid = -ground_half_h + 0.5 * SINK;
            for (int i = 0; i < 2; i++) {
                const int q = i ? 1 - lo : lo;
                const double err = fabs(t[q] - end[i]);
                worst = fmax(worst, err);
                cr_assert_leq(err, 0.5 + 1e-3, "%s: end %d at %.4f along the face, want %.4f (error %.4f px)", what,
                              i, t[q], end[i], err);
                cr_assert_leq(fabs(u[q] - mid), 0.5 + 1e-3, "%s: end %d at %.4f across the face, want %.4f", what, i,
                              u[q], mid);
            }
        }
        cr_log_info("tilted %.0f deg, face-to-face: worst end error %.3f px along the face", degs[a], worst);
        PP_OK_OR_FAIL(pp_body_destroy(w, box));
        PP_OK_OR_FAIL(pp_body_destroy(w, ground));
        pp_world_destroy(w);
    }
}

/* A box lying on a rasterised slope, so the strips run across the reference grid: each end is
 * within about one strip (1 px) of the analytic end, and over 40 sub-pixel offsets the ends are
 * neither pulled in nor pushed out, nor shifted along the slope, by more than 0.35 px
 * on average. */
Test(manifold, box_on_a_rasterised_slope_ends_are_unbiased) {
    const double degs[] = {10.0, 22.5, 30.0, 37.0, 60.0};
    const int W = 400, H = 400, offsets = 40;
    const double gx = 1000.0, gy = 1000.0, half_w = 16.0, half_h = 10.0;
    uint8_t *m = malloc((size_t)W * H);
    cr_assert_not_null(m);
    for (size_t a = 0; a < sizeof degs / sizeof degs[0]; a++) {
        const double th = DEG2RAD(degs[a]), ca = cos(th), sa = sin(th);
        /* Solid where the pixel centre is past the line through the bitmap's centre along
         * (ca, sa); the normal into the slope is (−sa, ca). */
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++)
                m[j * W + i] = -sa * (i + 0.5 - 0.5 * W) + ca * (j + 0.5 - 0.5 * H) >= 0;
        pp_world w = manifold_world(PP_NORMAL_AREA_GRADIENT);
        pp_body_def gd = body_def(PP_BODY_STATIC, (float)gx, (float)gy, 0);
        gd.width = W, gd.height = H, gd.mask = m;
        pp_body slope = create_body_ok(w, &gd);
        pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 0, 0, (float)th), 2 * (int)half_w, 2 * (int)half_h);
        double outward = 0, shift = 0, worst = 0;
        for (int k = 0; k < offsets; k++) {
            const double s = -20.0 + 1.037 * k, v = SINK - half_h; /* box centre along and across the line */
            const double bx = gx + s * ca - v * sa, by = gy + s * sa + v * ca;
            PP_OK_OR_FAIL(pp_body_set_transform(w, box, v2((float)bx, (float)by), (float)th));
            char what[96];
            snprintf(what, sizeof what, "slope %.1f deg, box %.2f px along it", degs[a], s);
            pp_contact c[2];
            collide_two(w, box, slope, c, what);
            double t[2];
            for (int i = 0; i < 2; i++)
                t[i] = (c[i].point.x - gx) * ca + (c[i].point.y - gy) * sa;
            const double e0 = fmin(t[0], t[1]) - (s - half_w), e1 = fmax(t[0], t[1]) - (s + half_w);
            worst = fmax(worst, fmax(fabs(e0), fabs(e1)));
            outward += 0.5 * (e1 - e0) / offsets;
            shift += 0.5 * (e0 + e1) / offsets;
            cr_assert_leq(fmax(fabs(e0), fabs(e1)), 1.0 + 1e-3, "%s: ends %.3f and %.3f px off", what, e0, e1);
        }
        cr_log_info("slope %4.1f deg: ends mean outward %+.3f px, mean shift along %+.3f px, worst %.3f px", degs[a],
                    outward, shift, worst);
        cr_assert_leq(fabs(outward), 0.35, "slope %.1f deg: ends %+.3f px outward on average", degs[a], outward);
        cr_assert_leq(fabs(shift), 0.35, "slope %.1f deg: ends shifted %+.3f px along on average", degs[a], shift);
        pp_world_destroy(w);
    }
    free(m);
}
