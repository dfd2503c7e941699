/* pp_world_explode: Box2D v3's rule on pixels. Impulses measured as mass × Δv against impulse_per_length × the
 * solid extent across the blast × the falloff: two boxes of extent 16 and 48 px, half at radius + falloff / 2,
 * none beyond; static bodies stay; the pieces an erase splits off are pushed; the masks filter; misuse. */
#include "helpers.h"

PP_TEST_SUITE(explode);

#define IPL 10.0f /* impulse_per_length of these tests, mass·px/s per px */

/* A world without gravity, so that a velocity read after the call is the impulse's alone. */
static pp_world still_world(void) { return make_world(0, 0); }

/* The blast at (200, 200), radius 50, falloff 40, no erase. */
static pp_explosion_def blast(void)
{
    pp_explosion_def d = pp_explosion_def_default();
    d.position = v2(200, 200);
    d.radius = 50;
    d.falloff = 40;
    d.impulse_per_length = IPL;
    return d;
}

/* The impulse a body took: mass × its centre of mass's velocity, mass·px/s. */
static pp_vec2 momentum(pp_world w, pp_body b)
{
    float m;
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, NULL, NULL));
    const pp_vec2 v = body_vel(w, b);
    return v2(m * v.x, m * v.y);
}

static void expect_near(double got, double want, double rel, const char *what)
{
    cr_expect(fabs(got - want) <= rel * fabs(want) + 1e-4, "%s: %g, expected %g", what, got, want);
}

Test(explode, extents_16_and_48_across_take_impulses_in_ratio_3_of_the_documented_size)
{
    pp_world w = still_world();
    /* A: 16 px tall, its left face 20 px right of the centre; B: 48 px tall, its right face 20 px left of it. */
    pp_body a = add_rect(w, body_def(PP_BODY_DYNAMIC, 228, 200, 0), 16, 16);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 172, 200, 0), 16, 48);
    pp_explosion_def d = blast();
    int32_t changed = -1;
    PP_OK_OR_FAIL(pp_world_explode(w, &d, &changed));
    cr_expect_eq(changed, 0);
    const pp_vec2 ja = momentum(w, a), jb = momentum(w, b);
    expect_near(ja.x, IPL * 16, 1e-4, "A's impulse");
    expect_near(jb.x, -IPL * 48, 1e-4, "B's impulse");
    cr_expect(fabs(ja.y) < 1e-3 && fabs(jb.y) < 1e-3, "sideways: %g, %g", ja.y, jb.y);
    expect_near(-jb.x / ja.x, 3.0, 0.05, "ratio");
    /* Pushed at the face's middle: no turn. */
    pp_vec2 v;
    float av;
    PP_OK_OR_FAIL(pp_body_get_velocity(w, a, &v, &av));
    cr_expect(fabs(av) < 1e-5, "A turns at %g rad/s", av);
    pp_world_destroy(w);
}

Test(explode, a_turned_body_takes_its_extent_across_the_blast)
{
    pp_world w = still_world();
    /* A 16 × 48 box turned a quarter: 48 px across a blast from above its middle. */
    pp_body a = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 228, (float)(M_PI / 2)), 16, 48);
    pp_explosion_def d = blast();
    PP_OK_OR_FAIL(pp_world_explode(w, &d, NULL));
    const pp_vec2 j = momentum(w, a);
    expect_near(j.y, IPL * 48, 1e-3, "impulse down");
    cr_expect(fabs(j.x) < 1e-2, "sideways %g", j.x);
    pp_world_destroy(w);
}

Test(explode, half_at_radius_plus_half_the_falloff_and_none_beyond)
{
    pp_world w = still_world();
    /* Left faces at 70 px (radius + falloff / 2) and 91 px (past radius + falloff), below at 89.5 px. */
    pp_body half = add_rect(w, body_def(PP_BODY_DYNAMIC, 200 + 70 + 8, 200, 0), 16, 16);
    pp_body past = add_rect(w, body_def(PP_BODY_DYNAMIC, 200 - 91 - 8, 200, 0), 16, 16);
    pp_body edge = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200 + 89.5f + 8, 0), 16, 16);
    pp_explosion_def d = blast();
    PP_OK_OR_FAIL(pp_world_explode(w, &d, NULL));
    expect_near(momentum(w, half).x, IPL * 16 * 0.5, 1e-4, "at radius + falloff / 2");
    const pp_vec2 jp = momentum(w, past);
    cr_expect(jp.x == 0 && jp.y == 0, "beyond: (%g, %g)", jp.x, jp.y);
    expect_near(momentum(w, edge).y, IPL * 16 * (0.5 / 40), 1e-3, "0.5 px inside the reach");
    pp_world_destroy(w);
}

Test(explode, static_bodies_never_move)
{
    pp_world w = make_world(0, 980);
    pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 200, 230, 0), 200, 40);
    pp_explosion_def d = blast();
    d.position = v2(200, 205);
    d.impulse_per_length = 1e6f;
    d.erase_radius = 12;
    int32_t changed = 0;
    PP_OK_OR_FAIL(pp_world_explode(w, &d, &changed));
    cr_expect_gt(changed, 0, "the crater");
    step_n(w, 1.0f / 60, 30);
    const pp_vec2 p = body_pos(w, ground), v = body_vel(w, ground);
    cr_expect(p.x == 200 && p.y == 230 && body_angle(w, ground) == 0, "moved to (%g, %g)", p.x, p.y);
    cr_expect(v.x == 0 && v.y == 0);
    pp_world_destroy(w);
}

Test(explode, the_pieces_an_erase_splits_off_are_pushed_apart)
{
    pp_world w = still_world();
    add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200, 0), 120, 10);
    pp_explosion_def d = blast();
    d.erase_radius = 10;
    int32_t changed = 0;
    PP_OK_OR_FAIL(pp_world_explode(w, &d, &changed));
    cr_expect_gt(changed, 0);
    pp_body bodies[4];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 4, &n));
    cr_assert_eq(n, 2, "the bar in two: %d bodies", n);
    int left = 0, right = 0;
    for (int k = 0; k < n; k++) {
        /* Each piece is pushed away from the centre, at full strength (its inner end lies within radius). */
        const pp_vec2 j = momentum(w, bodies[k]);
        cr_expect(hypot(j.x, j.y) >= IPL * 10, "a piece took (%g, %g)", j.x, j.y);
        left += j.x < 0, right += j.x > 0;
    }
    cr_expect(left == 1 && right == 1, "left %d, right %d", left, right);
    pp_world_destroy(w);
}

Test(explode, the_masks_filter_the_push_and_the_erase)
{
    pp_world w = still_world();
    pp_body_def cd = body_def(PP_BODY_DYNAMIC, 228, 200, 0);
    cd.category_bits = 2;
    pp_body two = add_rect(w, cd, 16, 16);
    pp_body one = add_rect(w, body_def(PP_BODY_DYNAMIC, 172, 200, 0), 16, 16); /* category 1 */
    pp_explosion_def d = blast();
    d.mask_bits = 1;
    PP_OK_OR_FAIL(pp_world_explode(w, &d, NULL));
    cr_expect(momentum(w, two).x == 0, "category 2 pushed");
    expect_near(momentum(w, one).x, -IPL * 16, 1e-4, "category 1");
    /* The erase: a circle over both boxes' near faces takes only category 1's pixels. */
    d = blast();
    d.impulse_per_length = 0;
    d.erase_radius = 25;
    d.erase_mask_bits = 1;
    int32_t changed = 0;
    PP_OK_OR_FAIL(pp_world_explode(w, &d, &changed));
    cr_expect_gt(changed, 0);
    float m2;
    PP_OK_OR_FAIL(pp_body_get_mass(w, two, &m2, NULL, NULL));
    float m1;
    PP_OK_OR_FAIL(pp_body_get_mass(w, one, &m1, NULL, NULL));
    cr_expect(m2 > m1, "category 2 erased too: masses %g and %g", m2, m1);
    pp_world_destroy(w);
}

Test(explode, a_push_wakes_a_sleeping_body_and_speeds_stay_within_the_limits)
{
    pp_world w = make_world(0, 980);
    add_rect(w, body_def(PP_BODY_STATIC, 200, 260, 0), 300, 40);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 232, 0), 16, 16);
    step_n(w, 1.0f / 60, 240);
    pp_body_state s[2];
    int32_t n;
    PP_OK_OR_FAIL(pp_world_get_body_states(w, s, 2, &n));
    cr_assert(!s[1].awake, "the box should sleep before the blast");
    pp_explosion_def d = blast();
    d.position = v2(180, 232);
    d.impulse_per_length = 3e38f; /* far past PP_MAX_SPEED: scaled down to it */
    PP_OK_OR_FAIL(pp_world_explode(w, &d, NULL));
    PP_OK_OR_FAIL(pp_world_get_body_states(w, s, 2, &n));
    cr_expect(s[1].awake, "pushed bodies wake");
    const pp_vec2 v = body_vel(w, box);
    cr_expect(hypot(v.x, v.y) <= PP_MAX_SPEED * 1.0001 && v.x > 0.99 * PP_MAX_SPEED, "speed (%g, %g)", v.x, v.y);
    pp_world_destroy(w);
}

/* Misuse: each a status and a message naming the call and what was wrong; nothing changes. */
Test(explode, misuse)
{
    pp_world w = still_world();
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 228, 200, 0), 16, 16);
    pp_explosion_def d = blast();
    EXPECT_ERR(pp_world_explode(w, NULL, NULL), PP_ERR_INVALID_ARGUMENT, "def is NULL");
    cr_expect(strncmp(pp_last_error(), "pp_world_explode", 16) == 0, "%s", pp_last_error());
    pp_explosion_def bad = d;
    bad.struct_size = 8;
    EXPECT_ERR(pp_world_explode(w, &bad, NULL), PP_ERR_ABI, "struct_size");
    bad = d, bad.position.x = NAN;
    EXPECT_ERR(pp_world_explode(w, &bad, NULL), PP_ERR_INVALID_ARGUMENT, "position");
    bad = d, bad.radius = -1;
    EXPECT_ERR(pp_world_explode(w, &bad, NULL), PP_ERR_INVALID_ARGUMENT, "radius");
    bad = d, bad.falloff = INFINITY;
    EXPECT_ERR(pp_world_explode(w, &bad, NULL), PP_ERR_INVALID_ARGUMENT, "falloff");
    bad = d, bad.impulse_per_length = NAN;
    EXPECT_ERR(pp_world_explode(w, &bad, NULL), PP_ERR_INVALID_ARGUMENT, "impulse_per_length");
    bad = d, bad.erase_radius = -0.5f;
    EXPECT_ERR(pp_world_explode(w, &bad, NULL), PP_ERR_INVALID_ARGUMENT, "erase_radius");
    EXPECT_ERR(pp_world_explode((pp_world){12345}, &d, NULL), PP_ERR_INVALID_HANDLE, "pp_world_explode");
    const pp_vec2 v = body_vel(w, box);
    cr_expect(v.x == 0 && v.y == 0, "a refused call pushed");
    pp_world_destroy(w);
    EXPECT_ERR(pp_world_explode(w, &d, NULL), PP_ERR_INVALID_HANDLE, "pp_world_explode");
}
