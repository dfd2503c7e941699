/* Contact normals, depths and points from pp_world_collide at set poses (no stepping),
 * against the analytic answer: circle–circle at 36 directions, box–ground at 0..90°, rotated
 * box–box. The poses live in tests/bench/accuracy/analytic.h, shared with the accuracy benchmark. */
#include "helpers.h"
#include "../bench/accuracy/analytic.h"

PP_TEST_SUITE(normals);

#define DISC_R ANALYTIC_DISC_R
#define BOX_HALF ANALYTIC_BOX_HALF
#define PEN ANALYTIC_PEN /* penetration of the analytic shapes, px */
#define MAXC ANALYTIC_MAX_CONTACTS

#define MAX_PAIRS (2 * ANALYTIC_BOXBOX_POSES + ANALYTIC_BOX_ANGLES + ANALYTIC_CIRCLE_DIRS)

typedef struct sample_set {
    double normal_err[2 * MAX_PAIRS]; /* degrees, per contact */
    int n_normal;
    double depth_err[MAX_PAIRS]; /* px, per pair (max depth) */
    int n_depth;
} sample_set;

static pp_world_def collide_def(pp_normal_method nm, pp_contact_mode cm) {
    pp_world_def d = pp_world_def_default();
    d.gravity = v2(0, 0);
    d.normal_method = nm;
    d.contact_mode = cm;
    return d;
}

static pp_world collide_world(pp_normal_method nm, pp_contact_mode cm) {
    pp_world_def d = collide_def(nm, cm);
    return make_world_def(&d);
}

/* Checks what every contact of a collided pair must satisfy, and returns the count. */
static int check_pair(const analytic_pair *p, pp_contact_mode cm) {
    const char *what = p->what;
    const pp_contact *c = p->c;
    int32_t n = p->count;
    cr_assert_eq(p->status, PP_OK, "%s: pp_world_collide -> %s (%s)", what, pp_status_name(p->status),
                 pp_last_error());
    cr_assert_geq(n, 1, "%s: no contact for an overlapping pair", what);
    if (cm == PP_CONTACT_CENTROID)
        cr_assert_eq(n, 1, "%s: CENTROID mode gave %d contacts", what, n);
    else
        cr_assert_leq(n, 2, "%s: MANIFOLD mode gave %d contacts", what, n);
    for (int k = 0; k < n; k++) {
        double len = hypot(c[k].normal.x, c[k].normal.y);
        cr_assert_float_eq(len, 1.0, 1e-3, "%s: contact %d normal (%g, %g) is not unit", what, k, c[k].normal.x,
                           c[k].normal.y);
        cr_assert_eq(c[k].a.id, p->a.id, "%s: contact %d: a is not the first body", what, k);
        cr_assert_eq(c[k].b.id, p->b.id, "%s: contact %d: b is not the second body", what, k);
        cr_assert_gt(c[k].pixel_count, 0, "%s: contact %d: pixel_count %d", what, k, c[k].pixel_count);
        cr_assert(isfinite(c[k].depth) && c[k].depth >= 0, "%s: contact %d depth %g", what, k, c[k].depth);
    }
    return n;
}

/* Collides every pose of a family; checks each pair and gathers its errors into s. */
static const analytic_set *run_family(analytic_family f, pp_normal_method nm, pp_contact_mode cm, sample_set *s) {
    static analytic_set set;
    pp_world_def d = collide_def(nm, cm);
    PP_OK_OR_FAIL(analytic_run(f, &d, &set));
    s->n_normal = s->n_depth = 0;
    for (int i = 0; i < set.n; i++) {
        check_pair(&set.pair[i], cm);
        s->depth_err[s->n_depth++] = analytic_errors(&set.pair[i], s->normal_err, &s->n_normal);
    }
    return &set;
}

/* Disc b around disc a at 36 directions, overlapping by PEN px. */
static void run_circles(pp_normal_method nm, pp_contact_mode cm, sample_set *s) {
    const analytic_set *set = run_family(ANALYTIC_CIRCLES, nm, cm, s);
    for (int k = 0; k < set->n; k++) {
        const analytic_pair *p = &set->pair[k];
        const char *what = p->what;
        const pp_contact *c = p->c;
        for (int i = 0; i < p->count; i++) {
            /* The point lies in the lens: within both discs (1 px of slack for the raster). */
            double da = hypot(c[i].point.x - p->a_x, c[i].point.y - p->a_y);
            double db = hypot(c[i].point.x - p->b_x, c[i].point.y - p->b_y);
            cr_assert_leq(da, DISC_R + 1.0, "%s: point (%g, %g) is %g px from a's centre", what, c[i].point.x,
                          c[i].point.y, da);
            cr_assert_leq(db, DISC_R + 1.0, "%s: point (%g, %g) is %g px from b's centre", what, c[i].point.x,
                          c[i].point.y, db);
        }
    }
}

/* A 40×40 box at 0..90° sunk PEN px into a wide static ground; a = box, b = ground. */
static void run_box_ground(pp_normal_method nm, pp_contact_mode cm, sample_set *s) {
    const analytic_set *set = run_family(ANALYTIC_BOX_GROUND, nm, cm, s);
    const double top = ANALYTIC_GROUND_TOP;
    for (int k = 0; k < set->n; k++) {
        const analytic_pair *p = &set->pair[k];
        const char *what = p->what;
        const pp_contact *c = p->c;
        const double x = p->a_x, y = p->a_y, a = p->a_angle;
        for (int i = 0; i < p->count; i++) {
            /* The point lies in the overlap: below the ground top, above the box's lowest point, inside the box. */
            cr_assert(c[i].point.y >= top - 1.0 && c[i].point.y <= top + PEN + 1.0,
                      "%s: point y %g outside the overlap [%g, %g]", what, c[i].point.y, top, top + PEN);
            double dx = c[i].point.x - x, dy = c[i].point.y - y;
            double lx = cos(a) * dx + sin(a) * dy, ly = -sin(a) * dx + cos(a) * dy; /* R(-a)·d */
            cr_assert(fabs(lx) <= BOX_HALF + 1.0 && fabs(ly) <= BOX_HALF + 1.0,
                      "%s: point (%g, %g) outside the box (local %g, %g)", what, c[i].point.x, c[i].point.y, lx, ly);
        }
    }
}

/* A 30×30 box's corner PEN px into a 60×60 box's face, turned 5..85° against it, at 90 poses,
 * collided both ways: (A, B) must give A's face normal n, (B, A) must give -n. */
static void run_box_box(pp_normal_method nm, pp_contact_mode cm, sample_set *s) {
    (void)run_family(ANALYTIC_BOX_BOX, nm, cm, s);
}

static void report(const char *name, sample_set *s, double *med, double *p95, double *dmed, double *dp95) {
    *med = quantile(s->normal_err, s->n_normal, 0.5);
    *p95 = quantile(s->normal_err, s->n_normal, 0.95);
    *dmed = quantile(s->depth_err, s->n_depth, 0.5);
    *dp95 = quantile(s->depth_err, s->n_depth, 0.95);
    cr_log_info("%s: normal error median %.3f deg, p95 %.3f deg, max %.3f deg (%d contacts); "
                "depth error median %.3f px, p95 %.3f px",
                name, *med, *p95, s->normal_err[s->n_normal - 1], s->n_normal, *dmed, *dp95);
}

/* The accuracy bar on normals (tests/bench/README.md): median ≤ 0.5°, 95th percentile ≤ 2°. */
static void assert_normal_bar(double med, double p95) {
    cr_assert_leq(med, 0.5, "normal error median %.3f deg > 0.5", med);
    cr_assert_leq(p95, 2.0, "normal error p95 %.3f deg > 2", p95);
}

Test(normals, area_gradient_circle_circle) {
    static sample_set s;
    double med, p95, dmed, dp95;
    run_circles(PP_NORMAL_AREA_GRADIENT, PP_CONTACT_MANIFOLD, &s);
    report("AREA_GRADIENT circle-circle (manifold)", &s, &med, &p95, &dmed, &dp95);
    assert_normal_bar(med, p95);
}

Test(normals, area_gradient_box_ground) {
    static sample_set s;
    double med, p95, dmed, dp95;
    run_box_ground(PP_NORMAL_AREA_GRADIENT, PP_CONTACT_MANIFOLD, &s);
    report("AREA_GRADIENT box-ground (manifold)", &s, &med, &p95, &dmed, &dp95);
    assert_normal_bar(med, p95);
}

Test(normals, circle_circle_depth_centroid) {
    static sample_set s;
    double med, p95, dmed, dp95;
    run_circles(PP_NORMAL_AREA_GRADIENT, PP_CONTACT_CENTROID, &s);
    report("AREA_GRADIENT circle-circle (centroid)", &s, &med, &p95, &dmed, &dp95);
    assert_normal_bar(med, p95);
    cr_assert_leq(dmed, 0.5, "depth error median %.3f px > 0.5 (analytic overlap %.1f px)", dmed, PEN);
    cr_assert_leq(dp95, 1.5, "depth error p95 %.3f px > 1.5 (analytic overlap %.1f px)", dp95, PEN);
}

Test(normals, box_ground_depth_centroid) {
    static sample_set s;
    double med, p95, dmed, dp95;
    run_box_ground(PP_NORMAL_AREA_GRADIENT, PP_CONTACT_CENTROID, &s);
    report("AREA_GRADIENT box-ground (centroid)", &s, &med, &p95, &dmed, &dp95);
    assert_normal_bar(med, p95);
    cr_assert_leq(dmed, 0.5, "depth error median %.3f px > 0.5 (analytic %.1f px)", dmed, PEN);
    cr_assert_leq(dp95, 1.0, "depth error p95 %.3f px > 1 (analytic %.1f px)", dp95, PEN);
}

Test(normals, area_gradient_rotated_box_box) {
    static sample_set s;
    double med, p95, dmed, dp95;
    run_box_box(PP_NORMAL_AREA_GRADIENT, PP_CONTACT_CENTROID, &s);
    report("AREA_GRADIENT rotated box-box (centroid)", &s, &med, &p95, &dmed, &dp95);
    assert_normal_bar(med, p95);
    cr_assert_leq(dmed, 1.0, "depth error median %.3f px > 1 (analytic %.1f px)", dmed, PEN);
}

Test(normals, kernel_method_sanity) {
    static sample_set s;
    double med, p95, dmed, dp95;
    run_circles(PP_NORMAL_KERNEL, PP_CONTACT_MANIFOLD, &s);
    report("KERNEL circle-circle (manifold)", &s, &med, &p95, &dmed, &dp95);
    cr_assert_lt(p95, 30.0, "KERNEL circle-circle normal error p95 %.3f deg", p95);
    run_box_ground(PP_NORMAL_KERNEL, PP_CONTACT_MANIFOLD, &s);
    report("KERNEL box-ground (manifold)", &s, &med, &p95, &dmed, &dp95);
    cr_assert_lt(p95, 30.0, "KERNEL box-ground normal error p95 %.3f deg", p95);
    run_box_box(PP_NORMAL_KERNEL, PP_CONTACT_MANIFOLD, &s);
    report("KERNEL rotated box-box (manifold)", &s, &med, &p95, &dmed, &dp95);
    cr_assert_lt(p95, 30.0, "KERNEL rotated box-box normal error p95 %.3f deg", p95);
}

Test(normals, swapping_the_pair_flips_the_normal) {
    pp_world w = collide_world(PP_NORMAL_AREA_GRADIENT, PP_CONTACT_CENTROID);
    pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 1000, 550, 0), 2000, 100);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 1000.5f, 483, 0), 40, 40);
    pp_contact ab, ba;
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_collide(w, box, ground, &ab, 1, &n));
    cr_assert_eq(n, 1);
    PP_OK_OR_FAIL(pp_world_collide(w, ground, box, &ba, 1, &n));
    cr_assert_eq(n, 1);
    cr_assert_lt(angle_between_deg(ab.normal.x, ab.normal.y, 0, 1), 0.5, "box->ground normal (%g, %g), want (0, 1)",
                 ab.normal.x, ab.normal.y);
    cr_assert_lt(angle_between_deg(ba.normal.x, ba.normal.y, 0, -1), 0.5,
                 "ground->box normal (%g, %g), want (0, -1)", ba.normal.x, ba.normal.y);
    cr_assert_eq(ba.a.id, ground.id);
    cr_assert_eq(ba.b.id, box.id);
    pp_world_destroy(w);
}

Test(normals, flat_overlap_centroid_and_manifold_points) {
    /* A 40×40 box at angle 0 whose pixels line up with the ground's, sunk exactly 3 rows:
     * the overlap is x in [480, 520), y in [500, 503), 120 pixels. */
    for (int mode = 0; mode < 2; mode++) {
        pp_contact_mode cm = mode ? PP_CONTACT_CENTROID : PP_CONTACT_MANIFOLD;
        pp_world w = collide_world(PP_NORMAL_AREA_GRADIENT, cm);
        pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 500, 550, 0), 1000, 100);
        pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 500, 483, 0), 40, 40);
        pp_contact c[MAXC];
        int32_t n = 0;
        PP_OK_OR_FAIL(pp_world_collide(w, box, ground, c, MAXC, &n));
        for (int k = 0; k < n; k++) {
            cr_assert_eq(c[k].pixel_count, 120, "mode %d contact %d: pixel_count %d, want 120", mode, k,
                         c[k].pixel_count);
            cr_assert_lt(angle_between_deg(c[k].normal.x, c[k].normal.y, 0, 1), 0.5,
                         "mode %d contact %d: normal (%g, %g)", mode, k, c[k].normal.x, c[k].normal.y);
            cr_assert(c[k].point.x >= 479.5 && c[k].point.x <= 520.5 && c[k].point.y >= 499.5 && c[k].point.y <= 503.5,
                      "mode %d contact %d: point (%g, %g) outside the overlap [480,520]x[500,503]", mode, k,
                      c[k].point.x, c[k].point.y);
        }
        if (cm == PP_CONTACT_CENTROID) {
            cr_assert_eq(n, 1, "CENTROID gave %d contacts", n);
            cr_assert_float_eq(c[0].point.x, 500.0, 0.5, "centroid x %g, want 500", c[0].point.x);
            cr_assert_float_eq(c[0].point.y, 501.5, 0.5, "centroid y %g, want 501.5", c[0].point.y);
            cr_assert_float_eq(c[0].depth, 3.0, 0.5, "centroid depth %g, want 3", c[0].depth);
        } else {
            /* The two extremes of the overlap along the tangent: near x = 480 and x = 520. */
            cr_assert_eq(n, 2, "MANIFOLD gave %d contacts for a 40 px wide flat overlap", n);
            double lo = fmin(c[0].point.x, c[1].point.x), hi = fmax(c[0].point.x, c[1].point.x);
            cr_assert_leq(lo, 482.0, "manifold points at x = %g and %g: not at the left extreme", lo, hi);
            cr_assert_geq(hi, 518.0, "manifold points at x = %g and %g: not at the right extreme", lo, hi);
            for (int k = 0; k < 2; k++)
                cr_assert_float_eq(c[k].depth, 3.0, 0.5, "manifold point %d depth %g, want 3", k, c[k].depth);
        }
        /* capacity 0 with out NULL reports the count only. */
        int32_t n0 = -1;
        PP_OK_OR_FAIL(pp_world_collide(w, box, ground, NULL, 0, &n0));
        cr_assert_eq(n0, n, "count with capacity 0 is %d, with capacity %d it was %d", n0, MAXC, n);
        pp_world_destroy(w);
    }
}

Test(normals, separated_pair_has_no_contact) {
    pp_world w = collide_world(PP_NORMAL_AREA_GRADIENT, PP_CONTACT_MANIFOLD);
    pp_body a = add_disc(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), DISC_R);
    pp_body b = add_disc(w, body_def(PP_BODY_DYNAMIC, 100 + 2 * DISC_R + 2, 100, 0), DISC_R);
    pp_contact c[MAXC];
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_collide(w, a, b, c, MAXC, &n));
    cr_assert_eq(n, 0, "discs 2 px apart: %d contacts", n);
    /* Bounding boxes overlap but pixels do not: a disc in the corner of a box's bitmap area. */
    PP_OK_OR_FAIL(pp_body_set_transform(w, b, v2(100 + 2 * DISC_R * 0.75f, 100 + 2 * DISC_R * 0.75f), 0));
    PP_OK_OR_FAIL(pp_world_collide(w, a, b, c, MAXC, &n));
    cr_assert_eq(n, 0, "discs at 1.06 diameters diagonally (bitmaps overlap, pixels do not): %d contacts", n);
    pp_world_destroy(w);
}
