/* Which pairs collide: category/mask bits, static–static pairs; and fixed rotation. */
#include "helpers.h"

PP_TEST_SUITE(filtering);

/* Two 30×30 dynamic boxes overlapping by 10 px in x, gravity off; steps 30 times.
 * Returns the most contacts seen in a step and how far apart they ended. */
static void overlap_pair(uint32_t cat_a, uint32_t mask_a, uint32_t cat_b, uint32_t mask_b, int *max_contacts,
                         double *final_dx) {
    pp_world w = make_world(0, 0);
    pp_body_def da = body_def(PP_BODY_DYNAMIC, 100, 100, 0);
    da.category_bits = cat_a;
    da.mask_bits = mask_a;
    pp_body a = add_rect(w, da, 30, 30);
    pp_body_def db = body_def(PP_BODY_DYNAMIC, 120, 100, 0);
    db.category_bits = cat_b;
    db.mask_bits = mask_b;
    pp_body b = add_rect(w, db, 30, 30);
    *max_contacts = 0;
    for (int i = 0; i < 30; i++) {
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
        int32_t n = -1;
        PP_OK_OR_FAIL(pp_world_get_contacts(w, NULL, 0, &n));
        if (n > *max_contacts) *max_contacts = n;
    }
    *final_dx = body_pos(w, b).x - body_pos(w, a).x;
    pp_world_destroy(w);
}

Test(filtering, default_bits_collide) {
    int mc;
    double dx;
    overlap_pair(1, 0xffffffffu, 1, 0xffffffffu, &mc, &dx);
    cr_assert_gt(mc, 0, "overlapping boxes with default bits made no contact");
    cr_assert_gt(dx, 21.0, "overlapping boxes were not pushed apart: centres %g px apart (start 20)", dx);
}

Test(filtering, mutually_excluded_categories_do_not_collide) {
    int mc;
    double dx;
    overlap_pair(0x1, ~0x2u, 0x2, ~0x1u, &mc, &dx);
    cr_assert_eq(mc, 0, "mutually excluded boxes made %d contacts", mc);
    cr_assert_float_eq(dx, 20.0, 1e-3, "mutually excluded boxes moved: centres %g px apart (start 20)", dx);
}

Test(filtering, one_sided_exclusion_is_enough) {
    /* a's mask excludes b's category; b's mask accepts a: no collision (both must agree). */
    int mc;
    double dx;
    overlap_pair(0x1, ~0x2u, 0x2, 0xffffffffu, &mc, &dx);
    cr_assert_eq(mc, 0, "one-sided exclusion: %d contacts", mc);
    overlap_pair(0x1, 0xffffffffu, 0x2, ~0x1u, &mc, &dx);
    cr_assert_eq(mc, 0, "one-sided exclusion (other side): %d contacts", mc);
}

Test(filtering, zero_mask_collides_with_nothing) {
    pp_world w = make_world(0, 980);
    add_rect(w, body_def(PP_BODY_STATIC, 200, 300, 0), 400, 40); /* top at 280 */
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 200, 250, 0);
    d.mask_bits = 0;
    pp_body ghost = add_rect(w, d, 20, 20);
    step_n(w, 1.0f / 60, 60);
    pp_vec2 p = body_pos(w, ghost);
    cr_assert_gt(p.y, 350.0, "a body with mask 0 was stopped by the ground (y = %g)", p.y);
    pp_world_destroy(w);
}

Test(filtering, static_static_never_collide) {
    pp_world w = make_world(0, 980);
    /* Two overlapping statics, and one dynamic box sunk into the first as a control. */
    pp_body s1 = add_rect(w, body_def(PP_BODY_STATIC, 200, 300, 0), 200, 40);
    pp_body s2 = add_rect(w, body_def(PP_BODY_STATIC, 250, 310, 0.3f), 200, 40);
    pp_body dyn = add_rect(w, body_def(PP_BODY_DYNAMIC, 115, 272, 0), 20, 20); /* 2 px into s1 */
    int seen_dyn = 0;
    for (int i = 0; i < 10; i++) {
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
        pp_contact c[32];
        int32_t n = -1;
        PP_OK_OR_FAIL(pp_world_get_contacts(w, c, 32, &n));
        cr_assert_leq(n, 32);
        for (int k = 0; k < n; k++) {
            int static_pair = (c[k].a.id == s1.id || c[k].a.id == s2.id) && (c[k].b.id == s1.id || c[k].b.id == s2.id);
            cr_assert(!static_pair, "step %d: a contact between two static bodies", i);
            if (c[k].a.id == dyn.id || c[k].b.id == dyn.id) seen_dyn = 1;
        }
    }
    cr_assert(seen_dyn, "control failed: the dynamic box sunk into a static made no contact");
    pp_vec2 p1 = body_pos(w, s1), p2 = body_pos(w, s2);
    cr_assert(p1.x == 200 && p1.y == 300 && p2.x == 250 && p2.y == 310, "a static body moved");
    pp_world_destroy(w);
}

Test(filtering, fixed_rotation_ignores_off_centre_impulse) {
    pp_world w = make_world(0, 0);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 100, 100, 0);
    d.fixed_rotation = 1;
    pp_body fixed = add_rect(w, d, 40, 20);
    d.fixed_rotation = 0;
    d.position = v2(300, 100);
    pp_body free_ = add_rect(w, d, 40, 20);
    /* An impulse at the right end, pointing down: a free body spins and translates. */
    PP_OK_OR_FAIL(pp_body_apply_impulse(w, fixed, v2(0, 8000), v2(119, 100)));
    PP_OK_OR_FAIL(pp_body_apply_impulse(w, free_, v2(0, 8000), v2(319, 100)));
    step_n(w, 1.0f / 60, 30);
    float af = body_angle(w, fixed), ar = body_angle(w, free_);
    float avf = 0;
    PP_OK_OR_FAIL(pp_body_get_velocity(w, fixed, NULL, &avf));
    pp_vec2 vf = body_vel(w, fixed);
    cr_assert_gt(fabs(ar), DEG2RAD(5.0), "control: the free body did not turn (%g rad)", ar);
    cr_assert_float_eq(af, 0.0, 1e-6, "fixed-rotation body turned to %g rad", af);
    cr_assert_float_eq(avf, 0.0, 1e-6, "fixed-rotation body has angular velocity %g", avf);
    /* Both got the same linear momentum: 8000 / 800 = 10 px/s downward at the centre of mass. */
    cr_assert_float_eq(vf.y, 10.0, 0.1, "fixed-rotation body velocity (%g, %g), want (0, 10)", vf.x, vf.y);
    pp_world_destroy(w);
}

Test(filtering, fixed_rotation_keeps_angle_when_hit_off_centre, .timeout = 30) {
    double angle[2];
    for (int fixed = 0; fixed < 2; fixed++) {
        pp_world w = make_world(0, 0);
        pp_body_def td = body_def(PP_BODY_DYNAMIC, 300, 300, 0);
        td.fixed_rotation = (uint32_t)fixed;
        pp_body target = add_rect(w, td, 20, 80); /* a tall bar */
        /* A box moving right, hitting the bar 30 px below its centre. */
        pp_body_def pd = body_def(PP_BODY_DYNAMIC, 240, 330, 0);
        pd.linear_velocity = v2(400, 0);
        add_rect(w, pd, 16, 16);
        double worst = 0;
        for (int i = 0; i < 60; i++) {
            PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
            double a = fabs(wrap_angle(body_angle(w, target)));
            if (a > worst) worst = a;
        }
        pp_vec2 v = body_vel(w, target);
        cr_assert_gt(v.x, 20.0, "fixed=%d: the bar was not hit (v = %g, %g)", fixed, v.x, v.y);
        angle[fixed] = worst;
        pp_world_destroy(w);
    }
    cr_assert_gt(angle[0], DEG2RAD(2.0), "control: a free bar hit off-centre turned only %g deg", RAD2DEG(angle[0]));
    cr_assert_leq(angle[1], 1e-6, "fixed-rotation bar turned %g deg when hit off-centre", RAD2DEG(angle[1]));
}
