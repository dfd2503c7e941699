/* Poses and motion: the pivot and rotation conventions, free motion, kinematic bodies,
 * sleeping, user data and stats. */
#include "helpers.h"

PP_TEST_SUITE(pose);

Test(pose, bitmap_to_world_mapping) {
    /* A 10×10 bitmap whose only solid pixel is (9, 0): centre (9.5, 0.5), pivot (5, 5).
     * At angle +90° (turning +x toward +y), local − pivot = (4.5, −4.5) maps to (4.5, 4.5). */
    pp_world_def wd = pp_world_def_default();
    wd.gravity = v2(0, 0);
    wd.contact_mode = PP_CONTACT_CENTROID;
    pp_world w = make_world_def(&wd);
    uint8_t m[100] = {0};
    m[0 * 10 + 9] = 1;
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 100, 100, (float)(M_PI / 2));
    d.width = d.height = 10;
    d.mask = m;
    pp_body dot = create_body_ok(w, &d);
    pp_vec2 c;
    PP_OK_OR_FAIL(pp_body_get_mass(w, dot, NULL, &c, NULL));
    cr_assert_float_eq(c.x, 9.5, 1e-4);
    cr_assert_float_eq(c.y, 0.5, 1e-4);

    /* A 3×3 static probe centred on where the pixel should be. */
    pp_body probe = add_rect(w, body_def(PP_BODY_STATIC, 104.5f, 104.5f, 0), 3, 3);
    pp_contact ct;
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_collide(w, dot, probe, &ct, 1, &n));
    cr_assert_eq(n, 1, "no contact where R(+90deg) puts the pixel (104.5, 104.5)");
    cr_assert_eq(ct.pixel_count, 1, "pixel_count %d, want 1", ct.pixel_count);
    cr_assert_float_eq(ct.point.x, 104.5, 0.5, "contact point (%g, %g), want (104.5, 104.5)", ct.point.x, ct.point.y);
    cr_assert_float_eq(ct.point.y, 104.5, 0.5, "contact point (%g, %g), want (104.5, 104.5)", ct.point.x, ct.point.y);

    /* Where the opposite rotation sense would put it: nothing. */
    PP_OK_OR_FAIL(pp_body_set_transform(w, probe, v2(95.5f, 95.5f), 0));
    PP_OK_OR_FAIL(pp_world_collide(w, dot, probe, &ct, 1, &n));
    cr_assert_eq(n, 0, "contact where R(-90deg) would put the pixel: rotation sense is wrong");

    /* A custom pivot at the bitmap's top-left corner: position is that corner. At angle 0,
     * the pixel is at (100 + 9.5, 100 + 0.5). */
    d.custom_pivot = 1;
    d.pivot = v2(0, 0);
    d.angle = 0;
    pp_body dot2 = create_body_ok(w, &d);
    pp_vec2 p = body_pos(w, dot2);
    cr_assert(p.x == 100 && p.y == 100, "position (%g, %g) after create at (100, 100)", p.x, p.y);
    PP_OK_OR_FAIL(pp_body_set_transform(w, probe, v2(109.5f, 100.5f), 0));
    PP_OK_OR_FAIL(pp_world_collide(w, dot2, probe, &ct, 1, &n));
    cr_assert_eq(n, 1, "custom pivot (0, 0): no contact at (109.5, 100.5)");
    pp_world_destroy(w);
}

Test(pose, set_transform_reads_back) {
    pp_world w = make_world(0, 980);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 0, 0, 0), 10, 10);
    PP_OK_OR_FAIL(pp_body_set_transform(w, b, v2(123.25f, -45.5f), 0.75f));
    pp_vec2 p = body_pos(w, b);
    float a = body_angle(w, b);
    cr_assert_float_eq(p.x, 123.25, 1e-3, "x %g", p.x);
    cr_assert_float_eq(p.y, -45.5, 1e-3, "y %g", p.y);
    cr_assert_float_eq(a, 0.75, 1e-5, "angle %g", a);
    pp_world_destroy(w);
}

Test(pose, free_body_moves_at_constant_velocity) {
    pp_world w = make_world(0, 0);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 100, 200, 0);
    d.linear_velocity = v2(120, -60);
    d.angular_velocity = 0.5f;
    pp_body b = add_rect(w, d, 16, 16);
    step_n(w, 1.0f / 60, 60);
    pp_vec2 p = body_pos(w, b);
    float a = body_angle(w, b);
    cr_assert_float_eq(p.x, 220.0, 0.05, "after 1 s at (120, -60) px/s: (%g, %g), want (220, 140)", p.x, p.y);
    cr_assert_float_eq(p.y, 140.0, 0.05, "after 1 s at (120, -60) px/s: (%g, %g), want (220, 140)", p.x, p.y);
    cr_assert_float_eq(a, 0.5, 1e-3, "after 1 s at +0.5 rad/s: angle %g", a);
    pp_world_destroy(w);
}

Test(pose, free_fall_follows_gravity) {
    pp_world w = make_world(0, 980);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 0, 0), 16, 16);
    step_n(w, 1.0f / 60, 60);
    pp_vec2 p = body_pos(w, b);
    pp_vec2 v = body_vel(w, b);
    /* Analytic ½ g t² = 490 px, v = 980 px/s; the integrator's discretisation is within 2%. */
    cr_assert_float_eq(p.y, 490.0, 0.02 * 490.0, "fell %g px in 1 s, want ~490", p.y);
    cr_assert_float_eq(v.y, 980.0, 1.0, "speed %g px/s after 1 s, want 980", v.y);
    cr_assert_float_eq(p.x, 100.0, 1e-3);
    pp_world_destroy(w);
}

/* World position of the centre of mass of a 40×20 box whose pivot is its top-left corner. */
static pp_vec2 corner_box_com(pp_world w, pp_body b)
{
    pp_vec2 p = body_pos(w, b);
    double a = body_angle(w, b);
    return v2((float)(p.x + cos(a) * 20 - sin(a) * 10), (float)(p.y + sin(a) * 20 + cos(a) * 10));
}

/* That box, its centre of mass set moving at (10, −20) px/s while it spins at 1 rad/s. */
static pp_body spinning_corner_box(pp_world w)
{
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 200, 200, 0);
    d.custom_pivot = 1;
    d.pivot = v2(0, 0);
    pp_body b = add_rect(w, d, 40, 20);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, b, v2(10, -20), 1.0f));
    return b;
}

Test(pose, velocity_is_that_of_the_centre_of_mass) {
    /* A 40×20 box with its pivot at the top-left corner, centre of mass (20, 10) local, (220, 210)
     * world. Set to (10, −20) px/s while spinning at 1 rad/s, the centre of mass moves in a
     * straight line at exactly that velocity, whatever the pivot does. */
    pp_world w = make_world(0, 0);
    pp_body b = spinning_corner_box(w);
    pp_vec2 v;
    float av;
    PP_OK_OR_FAIL(pp_body_get_velocity(w, b, &v, &av));
    cr_assert_float_eq(v.x, 10, 1e-3, "velocity (%g, %g) read back", v.x, v.y);
    cr_assert_float_eq(v.y, -20, 1e-3, "velocity (%g, %g) read back", v.x, v.y);
    cr_assert_float_eq(av, 1.0, 1e-5);
    double worst = 0;
    for (int i = 1; i <= 60; i++) {
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
        pp_vec2 c = corner_box_com(w, b);
        double t = i / 60.0, e = hypot(c.x - (220.0 + 10 * t), c.y - (210.0 - 20 * t));
        if (e > worst) worst = e;
    }
    cr_assert_leq(worst, 0.05, "the centre of mass strayed %g px from its straight line", worst);
    cr_assert_float_eq(body_angle(w, b), 1.0, 1e-2, "angle %g after 1 s at 1 rad/s", body_angle(w, b));
    pp_world_destroy(w);
}

Test(pose, reported_velocity_matches_centre_of_mass_motion) {
    /* The same box spinning at 1 rad/s: get_velocity must match the motion of the centre of mass
     * (central differences), and the pivot, off the centre, must move differently. */
    pp_world w = make_world(0, 0);
    pp_body b = spinning_corner_box(w);
    const float dt = 1.0f / 240;
    step_n(w, dt, 10);
    pp_vec2 c0 = corner_box_com(w, b), p0 = body_pos(w, b);
    PP_OK_OR_FAIL(pp_world_step(w, dt));
    pp_vec2 v1 = body_vel(w, b);
    PP_OK_OR_FAIL(pp_world_step(w, dt));
    pp_vec2 c2 = corner_box_com(w, b), p2 = body_pos(w, b);
    double fx = (c2.x - c0.x) / (2 * dt), fy = (c2.y - c0.y) / (2 * dt);
    double px = (p2.x - p0.x) / (2 * dt), py = (p2.y - p0.y) / (2 * dt);
    cr_log_info("com: reported (%.3f, %.3f), measured (%.3f, %.3f); pivot (%.3f, %.3f) px/s", v1.x, v1.y, fx, fy, px,
                py);
    cr_assert_leq(hypot(v1.x - fx, v1.y - fy), 1.0,
                  "get_velocity (%.3f, %.3f) px/s, but the centre of mass moves at (%.3f, %.3f) px/s", v1.x, v1.y, fx,
                  fy);
    cr_assert_gt(hypot(px - fx, py - fy), 5.0, "the pivot moves like the centre of mass: the test is vacuous");
    pp_world_destroy(w);
}

Test(pose, kinematic_moves_by_velocity_and_is_not_pushed, .timeout = 30) {
    pp_world w = make_world(0, 980);
    pp_body_def kd = body_def(PP_BODY_KINEMATIC, 300, 400, 0);
    kd.linear_velocity = v2(30, 0);
    pp_body platform = add_rect(w, kd, 200, 20); /* top at 390 */
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 350, 0), 30, 30);
    step_n(w, 1.0f / 60, 120);
    pp_vec2 p = body_pos(w, platform), pb = body_pos(w, box);
    cr_assert_float_eq(p.x, 360.0, 0.05, "kinematic x %g after 2 s at 30 px/s, want 360", p.x);
    cr_assert_float_eq(p.y, 400.0, 1e-3, "kinematic body fell or was pushed: y %g", p.y);
    cr_assert_float_eq(body_angle(w, platform), 0.0, 1e-5);
    /* The box rides on it. */
    cr_assert_leq(fabs(pb.y + 15 - 390.0), 1.5, "box bottom %g, platform top 390", pb.y + 15);
    cr_assert_gt(pb.x, 330.0, "the box did not ride along with the platform (x %g)", pb.x);
    pp_world_destroy(w);
}

Test(pose, resting_body_sleeps_and_wakes, .timeout = 30) {
    pp_world w = make_world(0, 980);
    pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 400, 500, 0), 800, 40);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 463, 0), 32, 32);
    int32_t awake = -1;
    PP_OK_OR_FAIL(pp_body_is_awake(w, box, &awake));
    cr_assert_eq(awake, 1, "a new dynamic body is asleep");
    PP_OK_OR_FAIL(pp_body_is_awake(w, ground, &awake));
    cr_assert_eq(awake, 0, "a static body reports awake");
    step_n(w, 1.0f / 60, 180);
    PP_OK_OR_FAIL(pp_body_is_awake(w, box, &awake));
    cr_assert_eq(awake, 0, "a box resting 3 s on the ground is still awake");
    pp_step_stats st;
    PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
    cr_assert_eq(st.awake_bodies, 0, "stats say %d awake bodies", st.awake_bodies);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, box, v2(0, -100), 0));
    PP_OK_OR_FAIL(pp_body_is_awake(w, box, &awake));
    cr_assert_eq(awake, 1, "set_velocity did not wake the body");
    pp_vec2 p0 = body_pos(w, box);
    PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
    pp_vec2 p1 = body_pos(w, box);
    cr_assert_lt(p1.y, p0.y - 0.5, "the woken body did not move up (%g -> %g)", p0.y, p1.y);
    pp_world_destroy(w);
}

Test(pose, user_data_and_stats) {
    pp_world w = make_world(0, 980);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 400, 466, 0);
    d.user_data = 0xDEADBEEFCAFEF00Dull;
    pp_body box = add_rect(w, d, 32, 32);
    add_rect(w, body_def(PP_BODY_STATIC, 400, 500, 0), 800, 40);
    uint64_t ud = 0;
    PP_OK_OR_FAIL(pp_body_get_user_data(w, box, &ud));
    cr_assert_eq(ud, 0xDEADBEEFCAFEF00Dull);

    PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
    pp_step_stats st;
    memset(&st, 0xFF, sizeof st);
    PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_get_contacts(w, NULL, 0, &n));
    cr_assert_eq(st.bodies, 2);
    cr_assert_eq(st.awake_bodies, 1);
    cr_assert_geq(st.pairs, 1, "the box and the ground overlap: %d pairs", st.pairs);
    cr_assert_eq(st.contacts, n, "stats.contacts %d, get_contacts %d", st.contacts, n);
    cr_assert_gt(st.pixels_tested, 0);
    cr_assert(st.backend == PP_BACKEND_CPU || st.backend == PP_BACKEND_GPU, "stats.backend %d", (int)st.backend);
    cr_assert(st.total_ms >= 0 && isfinite(st.total_ms));
    cr_assert_eq(st.swept_stops, 0u, "a box resting on the ground is never stopped by a sweep");
    pp_world_destroy(w);
}

Test(pose, cpu_backend_is_always_available) {
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_CPU;
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 400, 500, 0), 800, 40);
    add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 466, 0), 32, 32);
    PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
    pp_step_stats st;
    PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
    cr_assert_eq(st.backend, PP_BACKEND_CPU);
    pp_world_destroy(w);
}
