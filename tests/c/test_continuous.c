/* Continuous collision: a fast body stops at a thin wall instead of passing through it, and a
 * body that is not about to hit anything is never stopped. */
#include "helpers.h"

PP_TEST_SUITE(continuous);

#define WALL_X 500.0f  /* centre of the 8 px wall, px */
#define WALL_W 8

/* A gravity-free world with an 8 × 200 px wall of the given type at x = WALL_X. */
static pp_world wall_world(uint32_t continuous, pp_body_type wall_type, pp_body *wall) {
    pp_world_def d = pp_world_def_default();
    d.gravity = v2(0, 0);
    d.continuous = continuous;
    d.substeps = 2; /* the figures below are per 1/120 s substep */
    d.allow_sleep = 0; /* a heavy wall pushed to 0.5 px/s would otherwise fall asleep and drop its momentum */
    pp_world w = make_world_def(&d);
    pp_body_def wd = body_def(wall_type, WALL_X, 100, 0);
    wd.density = 100; /* a dynamic wall is 100 times heavier per pixel than what hits it */
    *wall = add_rect(w, wd, WALL_W, 200);
    return w;
}

/* Step n times at 1/60 s; the times continuous collision stopped a body. */
static int step_counting_stops(pp_world w, int n) {
    int stops = 0;
    for (int i = 0; i < n; i++) {
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
        pp_step_stats st;
        PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
        stops += (int)st.swept_stops;
    }
    return stops;
}

/* Fire a size × size box at the wall from x = 100 and step one second; returns its final x. */
static float fire(pp_world w, int size, float speed, uint32_t bullet, float restitution, int *stops) {
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 100, 100, 0);
    d.linear_velocity = v2(speed, 0);
    d.bullet = bullet;
    d.restitution = restitution;
    pp_body b = add_rect(w, d, size, size);
    *stops = step_counting_stops(w, 60);
    return body_pos(w, b).x;
}

Test(continuous, fast_boxes_stop_at_a_thin_static_wall) {
    const int sizes[] = {2, 4, 8, 16};
    const float speeds[] = {1000, 5000, 20000, 100000};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++) {
            pp_body wall;
            pp_world w = wall_world(1, PP_BODY_STATIC, &wall);
            int stops;
            const float x = fire(w, sizes[i], speeds[k], 0, 0, &stops);
            /* Resting against the wall's near face (WALL_X − 4) with its centre half a box before it. */
            cr_assert_lt(x, WALL_X - WALL_W / 2 - sizes[i] / 2 + 2, "%d px box at %.0f px/s ended at x %.2f", sizes[i],
                         speeds[k], x);
            /* Slower than this, a substep cannot carry the box past the wall, and contacts alone hold it. */
            if (speeds[k] / 120 > sizes[i] + WALL_W)
                cr_assert_geq(stops, 1, "%d px box at %.0f px/s: no sweep stopped it", sizes[i], speeds[k]);
            pp_world_destroy(w);
        }
}

Test(continuous, without_it_the_same_boxes_pass_through) {
    /* The baseline the sweep is measured against: at 5,000 px/s a substep moves a box 42 px, more
     * than the wall and the box together, so the wall is never seen. */
    const int sizes[] = {2, 4, 8, 16};
    for (int i = 0; i < 4; i++) {
        pp_body wall;
        pp_world w = wall_world(0, PP_BODY_STATIC, &wall);
        int stops;
        const float x = fire(w, sizes[i], 5000, 0, 0, &stops);
        cr_assert_gt(x, WALL_X + 1000, "%d px box without continuous collision ended at x %.2f", sizes[i], x);
        cr_assert_eq(stops, 0);
        pp_world_destroy(w);
    }
}

Test(continuous, a_stopped_body_bounces_with_its_restitution) {
    pp_body wall;
    pp_world w = wall_world(1, PP_BODY_STATIC, &wall);
    int stops;
    fire(w, 8, 3000, 0, 1.0f, &stops);
    pp_body bodies[2];
    int32_t n;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 2, &n));
    const pp_vec2 v = body_vel(w, bodies[1]);
    /* An elastic box comes back at the speed it arrived with, less what the stop costs. */
    cr_assert_lt(v.x, -0.9f * 3000, "elastic rebound at %.1f px/s after arriving at 3000 px/s", v.x);
    cr_assert_gt(v.x, -1.1f * 3000, "rebound %.1f px/s is faster than the impact", v.x);
    pp_world_destroy(w);
}

Test(continuous, a_bullet_hits_a_dynamic_wall_and_momentum_is_kept) {
    for (uint32_t bullet = 0; bullet <= 1; bullet++) {
        pp_body wall;
        pp_world w = wall_world(1, PP_BODY_DYNAMIC, &wall);
        int stops;
        const float x = fire(w, 4, 5000, bullet, 0, &stops);
        if (!bullet) {
            cr_assert_gt(x, WALL_X + 1000, "a non-bullet passes a dynamic wall (continuous covers static ones): x %.2f",
                         x);
        } else {
            float m_wall, m_box;
            pp_body bodies[2];
            int32_t n;
            PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 2, &n));
            PP_OK_OR_FAIL(pp_body_get_mass(w, wall, &m_wall, NULL, NULL));
            PP_OK_OR_FAIL(pp_body_get_mass(w, bodies[1], &m_box, NULL, NULL));
            const double p = m_wall * body_vel(w, wall).x + m_box * body_vel(w, bodies[1]).x;
            cr_assert_lt(x, body_pos(w, wall).x, "the bullet ended at x %.2f, beyond the wall at %.2f", x,
                         body_pos(w, wall).x);
            cr_assert_float_eq(p, m_box * 5000.0, 0.01 * m_box * 5000.0, "momentum %.1f after, %.1f before", p,
                               m_box * 5000.0);
        }
        pp_world_destroy(w);
    }
}

Test(continuous, sliding_fast_along_the_ground_is_not_stopped) {
    /* Overlap with the ground does not grow as the box slides, so no sweep may stop it. */
    pp_world_def d = pp_world_def_default();
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 4000, 532, 0), 8000, 64);
    pp_body_def bd = body_def(PP_BODY_DYNAMIC, 100, 500, 0);
    bd.friction = 0;
    pp_body b = add_rect(w, bd, 32, 32);
    step_n(w, 1.0f / 60, 60);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, b, v2(3000, 0), 0));
    const float x0 = body_pos(w, b).x;
    cr_assert_eq(step_counting_stops(w, 60), 0);
    const float slid = body_pos(w, b).x - x0;
    cr_assert_float_eq(slid, 3000.0f, 30.0f, "slid %.1f px in 1 s at 3000 px/s", slid);
    pp_world_destroy(w);
}

Test(continuous, a_falling_stick_does_not_pass_a_thin_floor) {
    /* A 2 × 64 px stick dropped from high above a 4 px floor, spinning, arrives at about 3,100 px/s. */
    pp_world_def d = pp_world_def_default();
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 500, 5000, 0), 8000, 4);
    pp_body_def bd = body_def(PP_BODY_DYNAMIC, 500, 0, 0.3f);
    bd.angular_velocity = 7;
    pp_body b = add_rect(w, bd, 2, 64);
    step_n(w, 1.0f / 60, 240);
    const pp_vec2 p = body_pos(w, b);
    cr_assert(isfinite(p.x) && isfinite(p.y));
    /* Lying on the floor (top at y 4998), its centre is a pixel above it. */
    cr_assert_lt(p.y, 4998, "the stick ended at y %.1f, inside or below the floor (4998..5002)", p.y);
    cr_assert_gt(p.y, 4990, "the stick ended at y %.1f, not on the floor", p.y);
    pp_world_destroy(w);
}

Test(continuous, a_filtered_wall_is_not_swept) {
    /* A body whose mask_bits leave out the wall's category passes it, swept or not. */
    pp_body wall;
    pp_world w = wall_world(1, PP_BODY_STATIC, &wall);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 100, 100, 0);
    d.linear_velocity = v2(5000, 0);
    d.mask_bits = ~1u; /* the wall is in category 1 */
    pp_body b = add_rect(w, d, 8, 8);
    cr_assert_eq(step_counting_stops(w, 60), 0);
    cr_assert_gt(body_pos(w, b).x, WALL_X + 1000, "the filtered box ended at x %.1f", body_pos(w, b).x);
    pp_world_destroy(w);
}
