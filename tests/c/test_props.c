/* Runtime properties (issue 24's setters): a property set between steps acts as if the body had been
 * created with it, the physics follows the new value, what it touches wakes, and bad values are refused
 * with the world unchanged. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "helpers.h"
#include "physpix.h"

PP_TEST_SUITE(props);

#define DT (1.0f / 60.0f)
#define GROUND_TOP 500.0f

/* How far a body falls from rest in n substeps of h s under g, px: ODE's semi-implicit Euler gives
 * g·h²·n(n+1)/2 (the default 4 substeps a step: 123.5 px in 30 steps at 980 px/s², not ½gt² = 122.5). */
static double fall(double g, int steps)
{
    const int n = 4 * steps;
    const double h = DT / 4.0;
    return g * h * h * n * (n + 1) / 2;
}

static pp_body add_ground(pp_world w) { return add_rect(w, body_def(PP_BODY_STATIC, 400, GROUND_TOP + 20, 0), 800, 40); }

static int32_t awake(pp_world w, pp_body b)
{
    int32_t a = -1;
    PP_OK_OR_FAIL(pp_body_is_awake(w, b, &a));
    return a;
}

/* A ground and a 16 px box thrown sideways from 100 px above it, with the box def given. */
static pp_world thrown_box(const pp_body_def *box, pp_body *out)
{
    pp_world w = make_world(0, 980);
    add_ground(w);
    *out = add_rect(w, *box, 16, 16);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, *out, v2(200, 0), 3));
    return w;
}

/* Save w to a snapshot, load it, and step both `steps` times: every body of the loaded world (slot order) must
 * stay exactly where its original is. */
static void expect_snapshot_continues(pp_world w, int steps)
{
    pp_world back = snapshot_round_trip(w);
    pp_body orig[8], loaded[8];
    int32_t n = 0, m = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, orig, 8, &n));
    PP_OK_OR_FAIL(pp_world_get_bodies(back, loaded, 8, &m));
    cr_assert(n == m && n <= 8, "%d bodies saved, %d loaded", n, m);
    for (int k = 0; k < steps; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        PP_OK_OR_FAIL(pp_world_step(back, DT));
        for (int i = 0; i < n; i++) {
            const pp_vec2 p = body_pos(w, orig[i]), q = body_pos(back, loaded[i]);
            cr_assert(p.x == q.x && p.y == q.y, "step %d after the snapshot, body %d: (%g, %g) against (%g, %g)", k, i,
                      p.x, p.y, q.x, q.y);
        }
    }
    pp_world_destroy(back);
}

Test(props, friction_restitution_and_damping_set_after_creation_run_bit_for_bit_as_if_created_with_them)
{
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 300, GROUND_TOP - 108, 0);
    pp_body set_box, made_box;
    pp_world set = thrown_box(&d, &set_box);
    d.friction = 0.2f, d.restitution = 0.5f, d.linear_damping = 0.01f, d.angular_damping = 0.02f;
    pp_world made = thrown_box(&d, &made_box);
    PP_OK_OR_FAIL(pp_body_set_friction(set, set_box, 0.2f));
    PP_OK_OR_FAIL(pp_body_set_restitution(set, set_box, 0.5f));
    PP_OK_OR_FAIL(pp_body_set_damping(set, set_box, 0.01f, 0.02f));
    /* Two seconds: it falls, bounces, tumbles and slides, so each of the three shapes the path. */
    for (int k = 0; k < 120; k++) {
        PP_OK_OR_FAIL(pp_world_step(set, DT));
        PP_OK_OR_FAIL(pp_world_step(made, DT));
        const pp_vec2 p = body_pos(set, set_box), q = body_pos(made, made_box);
        cr_assert(p.x == q.x && p.y == q.y && body_angle(set, set_box) == body_angle(made, made_box),
                  "step %d: (%g, %g) set against (%g, %g) created so", k, p.x, p.y, q.x, q.y);
    }
    pp_world_destroy(set);
    pp_world_destroy(made);
}

Test(props, damping_takes_velocity_down_as_exp_minus_c_t_whatever_the_substeps)
{
    /* Damping is a rate, 1/s: a second takes a box thrown in empty space to e^-c of its speed and spin at
     * every preset (ODE's own damping is a fraction taken off each of its steps, so 1/s zeroed it). */
    const pp_preset presets[3] = {PP_PRESET_FAST, PP_PRESET_BALANCED, PP_PRESET_ACCURATE};
    for (int p = 0; p < 3; p++) {
        pp_world_def wd = pp_world_def_preset(presets[p]);
        wd.gravity = (pp_vec2){0, 0};
        pp_world w = make_world_def(&wd);
        pp_body_def d = body_def(PP_BODY_DYNAMIC, 300, 300, 0);
        d.linear_velocity = (pp_vec2){100, -50};
        d.angular_velocity = 2;
        d.linear_damping = 1.0f;
        pp_body box = add_rect(w, d, 16, 16);
        PP_OK_OR_FAIL(pp_body_set_damping(w, box, 1.0f, 0.5f)); /* the angular part from now */
        step_n(w, 1.0f / 60.0f, 60);
        pp_vec2 v;
        float av;
        PP_OK_OR_FAIL(pp_body_get_velocity(w, box, &v, &av));
        cr_assert_float_eq(v.x, 100 * exp(-1.0), 1e-3 * 100, "preset %d: vx %g", (int)presets[p], v.x);
        cr_assert_float_eq(v.y, -50 * exp(-1.0), 1e-3 * 50, "preset %d: vy %g", (int)presets[p], v.y);
        cr_assert_float_eq(av, 2 * exp(-0.5), 1e-3 * 2, "preset %d: w %g", (int)presets[p], av);
        pp_world_destroy(w);
    }
}

Test(props, a_box_that_sticks_on_a_30_degree_ramp_slides_as_coulomb_says_once_its_friction_drops)
{
    const double a = DEG2RAD(30.0);
    pp_world w = make_world(0, 980);
    pp_body ramp = add_rect(w, body_def(PP_BODY_STATIC, 400, 400, (float)a), 600, 40);
    /* Resting on the ramp's top face: 20 px (half the ramp) + 8 px (half the box) along its normal. */
    const double nx = sin(a), ny = -cos(a);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, (float)(400 + 28.5 * nx), (float)(400 + 28.5 * ny), (float)a), 16, 16);
    PP_OK_OR_FAIL(pp_body_set_friction(w, ramp, 1.0f));
    PP_OK_OR_FAIL(pp_body_set_friction(w, box, 1.0f));
    step_n(w, DT, 30);
    const pp_vec2 p0 = body_pos(w, box);
    step_n(w, DT, 30);
    const pp_vec2 p1 = body_pos(w, box);
    cr_assert_lt(hypot(p1.x - p0.x, p1.y - p0.y), 0.5, "at μ = 1 (over tan 30°) the box crept %g px",
                 hypot(p1.x - p0.x, p1.y - p0.y));
    /* μ = 0.1 for both (the pair's √(0.1·0.1)): from rest, s = ½·g(sin 30° − 0.1·cos 30°)·t² = 51.2 px in 0.5 s. */
    PP_OK_OR_FAIL(pp_body_set_friction(w, ramp, 0.1f));
    PP_OK_OR_FAIL(pp_body_set_friction(w, box, 0.1f));
    step_n(w, DT, 30);
    const pp_vec2 p2 = body_pos(w, box);
    const double s = hypot(p2.x - p1.x, p2.y - p1.y), want = 0.5 * 980 * (0.5 - 0.1 * cos(a)) * 0.25;
    cr_assert_float_eq(s, want, 0.05 * want, "slid %.2f px in 0.5 s, Coulomb says %.2f", s, want);
    pp_world_destroy(w);
}

Test(props, restitution_set_on_a_box_in_flight_gives_its_bounce)
{
    for (int elastic = 0; elastic < 2; elastic++) {
        pp_world w = make_world(0, 980);
        pp_body ground = add_ground(w);
        pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 8 - 200, 0), 16, 16);
        step_n(w, DT, 10); /* falling */
        PP_OK_OR_FAIL(pp_body_set_restitution(w, box, elastic ? 1.0f : 0.0f));
        PP_OK_OR_FAIL(pp_body_set_restitution(w, ground, elastic ? 1.0f : 0.0f));
        float apex = INFINITY, landed = 0;
        for (int k = 0; k < 90; k++) { /* the fall takes 0.64 s; then the rebound's apex */
            PP_OK_OR_FAIL(pp_world_step(w, DT));
            const float y = body_pos(w, box).y;
            if (!landed && body_vel(w, box).y <= 0 && y > GROUND_TOP - 30)
                landed = 1;
            if (landed)
                apex = fminf(apex, y);
        }
        const float rise = GROUND_TOP - 8 - apex;
        if (elastic) /* e = 1 keeps all but the substeps' few per cent (README, Presets) */
            cr_assert_gt(rise, 180.0f, "e = 1: rebound apex %g px above the ground, dropped from 200", rise);
        else
            cr_assert_lt(rise, 5.0f, "e = 0: rebound apex %g px above the ground (only the overlap's push-out)", rise);
        pp_world_destroy(w);
    }
}

Test(props, a_sleeping_box_whose_filter_drops_the_ground_wakes_and_falls_through_it)
{
    pp_world w = make_world(0, 980);
    add_ground(w);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 8, 0), 16, 16);
    step_n(w, DT, 120);
    cr_assert_eq(awake(w, box), 0, "the resting box should be asleep");
    const float y0 = body_pos(w, box).y;
    PP_OK_OR_FAIL(pp_body_set_filter(w, box, 1, 0)); /* collides with nothing */
    cr_assert_eq(awake(w, box), 1);
    step_n(w, DT, 30);
    cr_assert_float_eq(body_pos(w, box).y - y0, fall(980, 30), 0.05, "fell %g px through the ground in 0.5 s",
                       body_pos(w, box).y - y0);
    pp_world_destroy(w);
}

Test(props, set_awake_puts_a_falling_box_to_sleep_in_the_air_and_wakes_it_again)
{
    pp_world w = make_world(0, 980);
    add_ground(w);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 200, 0), 16, 16);
    step_n(w, DT, 10);
    PP_OK_OR_FAIL(pp_body_set_awake(w, box, 0));
    cr_assert_eq(awake(w, box), 0);
    const pp_vec2 hung = body_pos(w, box);
    step_n(w, DT, 30);
    const pp_vec2 still = body_pos(w, box);
    cr_assert(still.x == hung.x && still.y == hung.y, "asleep, it moved from (%g, %g) to (%g, %g)", hung.x, hung.y,
              still.x, still.y);
    cr_assert(body_vel(w, box).y == 0, "asleep with velocity %g", body_vel(w, box).y);
    PP_OK_OR_FAIL(pp_body_set_awake(w, box, 1));
    step_n(w, DT, 30); /* from rest again */
    cr_assert_float_eq(body_pos(w, box).y - still.y, fall(980, 30), 0.05, "woken, it fell %g px in 0.5 s",
                       body_pos(w, box).y - still.y);
    pp_world_destroy(w);
}

Test(props, world_gravity_set_mid_fall_changes_the_acceleration_and_wakes_sleepers)
{
    pp_world w = make_world(0, 980);
    add_ground(w);
    pp_body sleeper = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, GROUND_TOP - 8, 0), 16, 16);
    step_n(w, DT, 120);
    cr_assert_eq(awake(w, sleeper), 0);
    pp_body faller = add_rect(w, body_def(PP_BODY_DYNAMIC, 600, -2000, 0), 16, 16);
    step_n(w, DT, 6);
    const float v0 = body_vel(w, faller).y;
    PP_OK_OR_FAIL(pp_world_set_gravity(w, v2(0, 490)));
    cr_assert_eq(awake(w, sleeper), 1, "the sleeper did not wake to the new gravity");
    step_n(w, DT, 60);
    const float dv = body_vel(w, faller).y - v0;
    cr_assert_float_eq(dv, 490.0f, 0.01f, "1 s at g = 490 px/s² added %g px/s", dv);
    pp_world_def got;
    PP_OK_OR_FAIL(pp_world_get_def(w, &got));
    cr_assert(got.gravity.x == 0 && got.gravity.y == 490);
    pp_world_destroy(w);
}

Test(props, body_states_match_the_getters_for_every_body_in_slot_order)
{
    pp_world w = make_world(0, 980);
    pp_body bodies[4];
    bodies[0] = add_ground(w);
    bodies[1] = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 300, 0.3f), 16, 16);
    bodies[2] = add_rect(w, body_def(PP_BODY_KINEMATIC, 500, 300, 0), 32, 8);
    bodies[3] = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 8, 0), 16, 16);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, bodies[2], v2(50, 0), 1));
    step_n(w, DT, 20);
    pp_body_state s[5];
    memset(s, 0xab, sizeof s);
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_body_states(w, s, 5, &n));
    cr_assert_eq(n, 4);
    for (int i = 0; i < 4; i++) {
        pp_vec2 v;
        float wz;
        int32_t a;
        PP_OK_OR_FAIL(pp_body_get_velocity(w, bodies[i], &v, &wz));
        PP_OK_OR_FAIL(pp_body_is_awake(w, bodies[i], &a));
        const pp_vec2 p = body_pos(w, bodies[i]);
        cr_assert_eq(s[i].body.id, bodies[i].id, "state %d is of another body", i);
        cr_assert(s[i].position.x == p.x && s[i].position.y == p.y && s[i].angle == body_angle(w, bodies[i]),
                  "body %d's pose", i);
        cr_assert(s[i].linear_velocity.x == v.x && s[i].linear_velocity.y == v.y && s[i].angular_velocity == wz,
                  "body %d's velocity", i);
        cr_assert_eq((int32_t)s[i].awake, a, "body %d's sleep", i);
    }
    cr_assert_eq(s[2].linear_velocity.x, 50.0f, "the kinematic body keeps its set speed");
    /* A short buffer: the count of all, only capacity written. */
    pp_body_state two[3];
    memset(two, 0xab, sizeof two);
    PP_OK_OR_FAIL(pp_world_get_body_states(w, two, 2, &n));
    cr_assert_eq(n, 4);
    cr_assert_eq(two[1].body.id, bodies[1].id);
    const unsigned char *tail = (const unsigned char *)&two[2];
    for (size_t k = 0; k < sizeof two[2]; k++)
        cr_assert_eq(tail[k], 0xab, "wrote past capacity");
    pp_world_destroy(w);
}

Test(props, body_states_carry_each_body_s_user_data_after_the_older_fields)
{
    /* user_data was appended, so a binding built against the older layout still finds every other field. */
    cr_assert_eq(offsetof(pp_body_state, awake), 32);
    cr_assert_eq(offsetof(pp_body_state, user_data), 40);
    cr_assert_eq(sizeof(pp_body_state), 48);
    pp_world w = make_world(0, 980);
    pp_body_def d = body_def(PP_BODY_STATIC, 400, 500, 0);
    d.user_data = 0xfeedface12345678u;
    pp_body ground = add_rect(w, d, 800, 40);
    pp_body plain = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 300, 0), 16, 16);
    pp_body_state s[2];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_body_states(w, s, 2, &n));
    cr_assert_eq(n, 2);
    cr_assert(s[0].body.id == ground.id && s[0].user_data == 0xfeedface12345678u, "the ground's user_data");
    cr_assert(s[1].body.id == plain.id && s[1].user_data == 0, "a body made without user_data reads 0");
    pp_world_destroy(w);
}

Test(props, bad_values_and_handles_are_refused_and_change_nothing)
{
    pp_world w = make_world(0, 980);
    pp_body ground = add_ground(w);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 300, 0), 16, 16);
    EXPECT_ERR(pp_body_set_friction(w, box, NAN), PP_ERR_INVALID_ARGUMENT, "friction");
    EXPECT_ERR(pp_body_set_friction(w, box, -0.5f), PP_ERR_INVALID_ARGUMENT, "friction");
    EXPECT_ERR(pp_body_set_restitution(w, box, 1.5f), PP_ERR_INVALID_ARGUMENT, "restitution");
    EXPECT_ERR(pp_body_set_damping(w, box, -1, 0), PP_ERR_INVALID_ARGUMENT, "damping");
    EXPECT_ERR(pp_body_set_damping(w, box, 0, INFINITY), PP_ERR_INVALID_ARGUMENT, "damping");
    EXPECT_ERR(pp_body_set_awake(w, ground, 1), PP_ERR_INVALID_ARGUMENT, "static");
    EXPECT_ERR(pp_world_set_gravity(w, v2(NAN, 0)), PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_world_set_gravity(w, v2(0, 2e8f)), PP_ERR_INVALID_ARGUMENT, "PP_MAX_ACCELERATION");
    EXPECT_ERR(pp_world_get_body_states(w, NULL, 4, NULL), PP_ERR_INVALID_ARGUMENT, "count|NULL|null");
    pp_world_def got;
    PP_OK_OR_FAIL(pp_world_get_def(w, &got));
    cr_assert(got.gravity.x == 0 && got.gravity.y == 980, "a refused gravity changed it");
    /* The refused values changed nothing: the box falls as a fresh one does. */
    pp_world fresh = make_world(0, 980);
    add_ground(fresh);
    pp_body twin = add_rect(fresh, body_def(PP_BODY_DYNAMIC, 400, 300, 0), 16, 16);
    step_n(w, DT, 60);
    step_n(fresh, DT, 60);
    cr_assert(body_pos(w, box).y == body_pos(fresh, twin).y, "the refused calls changed the fall");
    PP_OK_OR_FAIL(pp_body_destroy(w, box));
    EXPECT_ERR(pp_body_set_friction(w, box, 0.5f), PP_ERR_INVALID_HANDLE, "pp_body_set_friction");
    EXPECT_ERR(pp_body_set_filter(w, box, 1, 1), PP_ERR_INVALID_HANDLE, "pp_body_set_filter");
    pp_world_destroy(fresh);
    pp_world_destroy(w);
    EXPECT_ERR(pp_world_set_gravity(w, v2(0, 1)), PP_ERR_INVALID_HANDLE, "pp_world_set_gravity");
}

Test(props, set_properties_survive_a_snapshot_and_the_run_continues_bit_for_bit)
{
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 300, GROUND_TOP - 108, 0);
    pp_body box;
    pp_world w = thrown_box(&d, &box);
    PP_OK_OR_FAIL(pp_body_set_friction(w, box, 0.1f));
    PP_OK_OR_FAIL(pp_body_set_restitution(w, box, 0.7f));
    PP_OK_OR_FAIL(pp_body_set_damping(w, box, 0.01f, 0.02f));
    PP_OK_OR_FAIL(pp_world_set_gravity(w, v2(100, 600)));
    step_n(w, DT, 20);
    expect_snapshot_continues(w, 100);
    pp_world_destroy(w);
}

/* ---- forces, torques, angular impulses and gravity scales ---- */

static void mass_of(pp_world w, pp_body b, float *m, float *inertia)
{
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, m, NULL, inertia));
}

static pp_vec2 com_of(pp_world w, pp_body b)
{
    /* A 16 px box made at its centre keeps its centre of mass on its pivot while it does not turn. */
    return body_pos(w, b);
}

Test(props, a_force_equal_to_the_weight_holds_a_box_in_the_air_while_it_is_applied_each_step)
{
    /* Sleep off: held still for 0.5 s, a box would sleep in the air (as in Box2D) and stay there. */
    pp_world_def d = pp_world_def_default();
    d.allow_sleep = 0;
    pp_world w = make_world_def(&d);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 200, 0), 16, 16);
    float m, inertia;
    mass_of(w, box, &m, &inertia);
    for (int k = 0; k < 60; k++) {
        PP_OK_OR_FAIL(pp_body_apply_force(w, box, v2(0, -m * 980), com_of(w, box)));
        PP_OK_OR_FAIL(pp_world_step(w, DT));
    }
    cr_assert_float_eq(body_pos(w, box).y, 200.0f, 1e-3, "held by its weight's force, it moved to y = %g",
                       body_pos(w, box).y);
    /* Spent by the step: without it the box falls again from rest. */
    step_n(w, DT, 30);
    cr_assert_float_eq(body_pos(w, box).y - 200.0f, fall(980, 30), 0.01, "it fell %g px once the force stopped",
                       body_pos(w, box).y - 200.0f);
    pp_world_destroy(w);
}

Test(props, a_force_and_a_torque_for_one_step_give_momentum_f_dt_and_angular_momentum_tau_dt)
{
    pp_world w = make_world(0, 0);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 300, 0), 16, 16);
    float m, inertia;
    mass_of(w, box, &m, &inertia);
    /* F at the centre and τ separately, then the same F 8 px below the centre: τ = r × F. */
    PP_OK_OR_FAIL(pp_body_apply_force(w, box, v2(600 * m, 0), com_of(w, box)));
    PP_OK_OR_FAIL(pp_body_apply_torque(w, box, 3 * inertia));
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    pp_vec2 v;
    float wz;
    PP_OK_OR_FAIL(pp_body_get_velocity(w, box, &v, &wz));
    cr_assert_float_eq(v.x, 600 * DT, 1e-4, "F·dt/m: %g px/s", v.x);
    cr_assert_float_eq(wz, 3 * DT, 1e-5, "τ·dt/I: %g rad/s", wz);
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    PP_OK_OR_FAIL(pp_body_get_velocity(w, box, &v, &wz));
    cr_assert_float_eq(v.x, 600 * DT, 1e-4, "spent after one step, yet the speed changed to %g", v.x);
    const pp_vec2 c = com_of(w, box);
    PP_OK_OR_FAIL(pp_body_apply_force(w, box, v2(600 * m, 0), v2(c.x, c.y + 8)));
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    float wz2;
    PP_OK_OR_FAIL(pp_body_get_velocity(w, box, &v, &wz2));
    /* r = (0, 8), F = (600m, 0): r × F = 0·0 − 8·600m, clockwise in y-down terms. */
    cr_assert_float_eq(wz2 - wz, -8 * 600 * m / inertia * DT, 1e-4, "off-centre force turned it by %g rad/s", wz2 - wz);
    cr_assert_float_eq(v.x, 2 * 600 * DT, 1e-3, "and pushed it to %g px/s", v.x);
    /* An angular impulse changes ω by J/I at once. */
    PP_OK_OR_FAIL(pp_body_apply_angular_impulse(w, box, 2 * inertia));
    float wz3;
    PP_OK_OR_FAIL(pp_body_get_velocity(w, box, NULL, &wz3));
    cr_assert_float_eq(wz3 - wz2, 2.0f, 1e-5, "J/I: %g rad/s", wz3 - wz2);
    pp_world_destroy(w);
}

Test(props, gravity_scale_0_floats_2_doubles_the_fall_and_minus_1_rises)
{
    const float scales[] = {0, 2, -1, 1};
    pp_world w = make_world(0, 980);
    pp_body b[4];
    for (int i = 0; i < 4; i++) {
        b[i] = add_rect(w, body_def(PP_BODY_DYNAMIC, 100.0f + 100 * i, 1000, 0), 16, 16);
        PP_OK_OR_FAIL(pp_body_set_gravity_scale(w, b[i], scales[i]));
    }
    step_n(w, DT, 30); /* the scale stays: every step */
    for (int i = 0; i < 4; i++)
        cr_assert_float_eq(body_pos(w, b[i]).y - 1000, fall(980 * scales[i], 30), 0.01,
                           "scale %g: moved %g px in 0.5 s", scales[i], body_pos(w, b[i]).y - 1000);
    /* Back to 1: it falls as any body. */
    PP_OK_OR_FAIL(pp_body_set_gravity_scale(w, b[0], 1));
    step_n(w, DT, 30);
    cr_assert_float_eq(body_pos(w, b[0]).y - 1000, fall(980, 30), 0.01);
    pp_world_destroy(w);
}

/* Issue 39: at a scale of 1e10 a body crossed 6.8e8 px in one step, and at FLT_MAX most steps failed with
 * PP_ERR_LIMIT. The scale's range is ±PP_MAX_GRAVITY_SCALE; past it, or not finite, is refused and changes nothing,
 * and the largest accepted scale still steps. */
Test(props, gravity_scale_has_a_range_and_the_largest_still_steps)
{
    pp_world w = make_world(0, 980);
    const pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 16, 16);
    const float bad[] = {1e10f, -1e10f, FLT_MAX, -FLT_MAX, INFINITY, NAN, nextafterf(PP_MAX_GRAVITY_SCALE, INFINITY),
                         -nextafterf(PP_MAX_GRAVITY_SCALE, INFINITY)};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        EXPECT_ERR(pp_body_set_gravity_scale(w, box, bad[i]), PP_ERR_INVALID_ARGUMENT, "scale");
    EXPECT_ERR(pp_body_set_gravity_scale(w, box, 1e10f), PP_ERR_INVALID_ARGUMENT, "-1000..1000");
    float scale = 0;
    PP_OK_OR_FAIL(pp_body_get_gravity_scale(w, box, &scale));
    cr_assert_eq(scale, 1.0f, "a refused scale was kept: %g", scale);
    PP_OK_OR_FAIL(pp_body_set_gravity_scale(w, box, -PP_MAX_GRAVITY_SCALE));
    PP_OK_OR_FAIL(pp_body_set_gravity_scale(w, box, PP_MAX_GRAVITY_SCALE));
    for (int i = 0; i < 60; i++)
        PP_OK_OR_FAIL(pp_world_step(w, DT));
    cr_assert(body_pos(w, box).y > 100 && isfinite(body_pos(w, box).y), "the box fell: y %g", body_pos(w, box).y);
    pp_world_destroy(w);
}

Test(props, forces_and_gravity_scales_survive_a_snapshot_bit_for_bit)
{
    pp_world w = make_world(0, 980);
    add_ground(w);
    pp_body a = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 300, 0.2f), 16, 16);
    pp_body floater = add_rect(w, body_def(PP_BODY_DYNAMIC, 500, 300, 0), 16, 16);
    PP_OK_OR_FAIL(pp_body_set_gravity_scale(w, floater, 0.25f));
    step_n(w, DT, 5);
    PP_OK_OR_FAIL(pp_body_apply_force(w, a, v2(3000, -2000), v2(305, 300)));
    PP_OK_OR_FAIL(pp_body_apply_torque(w, floater, 50000));
    expect_snapshot_continues(w, 60);
    pp_world_destroy(w);
}

Test(props, forces_refuse_static_and_kinematic_bodies_and_non_finite_values)
{
    pp_world w = make_world(0, 980);
    pp_body ground = add_ground(w);
    pp_body kin = add_rect(w, body_def(PP_BODY_KINEMATIC, 100, 100, 0), 8, 8);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 300, 0), 16, 16);
    EXPECT_ERR(pp_body_apply_force(w, ground, v2(1, 0), v2(0, 0)), PP_ERR_INVALID_ARGUMENT, "dynamic");
    EXPECT_ERR(pp_body_apply_torque(w, kin, 1), PP_ERR_INVALID_ARGUMENT, "dynamic");
    EXPECT_ERR(pp_body_set_gravity_scale(w, ground, 0), PP_ERR_INVALID_ARGUMENT, "dynamic");
    EXPECT_ERR(pp_body_apply_angular_impulse(w, kin, 1), PP_ERR_INVALID_ARGUMENT, "dynamic");
    EXPECT_ERR(pp_body_apply_force(w, box, v2(NAN, 0), v2(0, 0)), PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_body_apply_force(w, box, v2(1, 0), v2(INFINITY, 0)), PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_body_apply_torque(w, box, NAN), PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_body_set_gravity_scale(w, box, INFINITY), PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_body_apply_angular_impulse(w, box, 1e30f), PP_ERR_INVALID_ARGUMENT, "angular");
    /* Nothing was applied: it falls as a fresh box. */
    step_n(w, DT, 30);
    cr_assert_float_eq(body_pos(w, box).y - 300, fall(980, 30), 0.01);
    PP_OK_OR_FAIL(pp_body_destroy(w, box));
    EXPECT_ERR(pp_body_apply_force(w, box, v2(1, 0), v2(0, 0)), PP_ERR_INVALID_HANDLE, "pp_body_apply_force");
    pp_world_destroy(w);
}

Test(props, density_set_scales_mass_and_inertia_keeps_the_velocity_and_the_solver_feels_it)
{
    pp_world w = make_world(0, 0);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 300, 0), 16, 16);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, box, v2(50, -20), 0.5f));
    float m0, i0, m1, i1;
    mass_of(w, box, &m0, &i0);
    PP_OK_OR_FAIL(pp_body_set_density(w, box, 4.0f));
    mass_of(w, box, &m1, &i1);
    cr_assert_float_eq(m1, 4 * m0, 1e-3 * m0, "mass %g after density 4, %g before", m1, m0);
    cr_assert_float_eq(i1, 4 * i0, 1e-3 * i0, "inertia %g after density 4, %g before", i1, i0);
    pp_vec2 v;
    float wz;
    PP_OK_OR_FAIL(pp_body_get_velocity(w, box, &v, &wz));
    cr_assert(v.x == 50 && v.y == -20 && wz == 0.5f, "velocity (%g, %g), %g rad/s after the change", v.x, v.y, wz);
    /* ODE has the new mass: the force that gave the old mass 600 px/s² gives the new one a quarter of it. */
    PP_OK_OR_FAIL(pp_body_apply_force(w, box, v2(600 * m0, 0), body_pos(w, box)));
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    PP_OK_OR_FAIL(pp_body_get_velocity(w, box, &v, NULL));
    cr_assert_float_eq(v.x - 50, 150 * DT, 1e-3, "Δv %g px/s, want F·dt/(4m)", v.x - 50);
    EXPECT_ERR(pp_body_set_density(w, box, 0), PP_ERR_INVALID_ARGUMENT, "density");
    EXPECT_ERR(pp_body_set_density(w, box, NAN), PP_ERR_INVALID_ARGUMENT, "density");
    pp_world_destroy(w);
}

Test(props, getters_read_back_the_defaults_and_what_was_set)
{
    pp_world w = make_world(0, 980);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 300, 0), 16, 16);
    float f, e, d, g;
    PP_OK_OR_FAIL(pp_body_get_friction(w, box, &f));
    PP_OK_OR_FAIL(pp_body_get_restitution(w, box, &e));
    PP_OK_OR_FAIL(pp_body_get_density(w, box, &d));
    PP_OK_OR_FAIL(pp_body_get_gravity_scale(w, box, &g));
    const pp_body_def def = pp_body_def_default();
    cr_assert(f == def.friction && e == def.restitution && d == def.density && g == 1, "defaults %g %g %g %g", f, e,
              d, g);
    PP_OK_OR_FAIL(pp_body_set_friction(w, box, 0.25f));
    PP_OK_OR_FAIL(pp_body_set_restitution(w, box, 0.5f));
    PP_OK_OR_FAIL(pp_body_set_density(w, box, 3));
    PP_OK_OR_FAIL(pp_body_set_gravity_scale(w, box, -0.5f));
    PP_OK_OR_FAIL(pp_body_get_friction(w, box, &f));
    PP_OK_OR_FAIL(pp_body_get_restitution(w, box, &e));
    PP_OK_OR_FAIL(pp_body_get_density(w, box, &d));
    PP_OK_OR_FAIL(pp_body_get_gravity_scale(w, box, &g));
    cr_assert(f == 0.25f && e == 0.5f && d == 3 && g == -0.5f, "read back %g %g %g %g", f, e, d, g);
    EXPECT_ERR(pp_body_get_friction(w, box, NULL), PP_ERR_INVALID_ARGUMENT, "NULL");
    pp_world_destroy(w);
}

Test(props, a_static_box_made_dynamic_falls_from_where_it_was_and_made_static_again_stops_dead)
{
    pp_world w = make_world(0, 980);
    add_ground(w);
    pp_body box = add_rect(w, body_def(PP_BODY_STATIC, 400, 200, 0.3f), 16, 16);
    step_n(w, DT, 10);
    PP_OK_OR_FAIL(pp_body_set_type(w, box, PP_BODY_DYNAMIC));
    pp_body_type t = PP_BODY_STATIC;
    PP_OK_OR_FAIL(pp_body_get_type(w, box, &t));
    cr_assert_eq(t, PP_BODY_DYNAMIC);
    cr_assert_eq(awake(w, box), 1);
    float mass = 0;
    PP_OK_OR_FAIL(pp_body_get_mass(w, box, &mass, NULL, NULL));
    cr_assert_float_eq(mass, 256.0f, 1e-3f, "mass %g from 256 solid pixels of density 1", mass);
    const pp_vec2 p0 = body_pos(w, box);
    cr_assert(p0.x == 400.0f && p0.y == 200.0f && body_angle(w, box) == 0.3f, "the pose stays");
    step_n(w, DT, 20);
    cr_assert_float_eq(body_pos(w, box).y - p0.y, fall(980, 20), 1e-2, "fell %g px", body_pos(w, box).y - p0.y);
    PP_OK_OR_FAIL(pp_body_set_type(w, box, PP_BODY_STATIC));
    const pp_vec2 p1 = body_pos(w, box);
    step_n(w, DT, 20);
    const pp_vec2 p2 = body_pos(w, box);
    cr_assert(p1.x == p2.x && p1.y == p2.y, "a static body stays: (%g, %g) then (%g, %g)", p1.x, p1.y, p2.x, p2.y);
    cr_assert_eq(awake(w, box), 0);
    pp_world_destroy(w);
}

Test(props, a_kinematic_body_keeps_the_velocity_it_had_as_dynamic_and_ignores_gravity)
{
    pp_world w = make_world(0, 980);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 200, 0), 16, 16);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, box, v2(60, -30), 1.5f));
    PP_OK_OR_FAIL(pp_body_set_type(w, box, PP_BODY_KINEMATIC));
    const pp_vec2 p0 = body_pos(w, box);
    step_n(w, DT, 60);
    const pp_vec2 v = body_vel(w, box), p = body_pos(w, box);
    cr_assert(v.x == 60.0f && v.y == -30.0f, "velocity (%g, %g)", v.x, v.y);
    cr_assert_float_eq(p.x - p0.x, 60.0, 1e-3);
    cr_assert_float_eq(p.y - p0.y, -30.0, 1e-3);
    cr_assert_float_eq(body_angle(w, box), 1.5, 1e-4);
    PP_OK_OR_FAIL(pp_body_set_type(w, box, PP_BODY_DYNAMIC)); /* and back: gravity takes it again */
    step_n(w, DT, 30);
    cr_assert_float_eq(body_vel(w, box).y, -30.0 + 980.0 * 30 * DT, 1e-2, "vy %g", body_vel(w, box).y);
    pp_world_destroy(w);
}

Test(props, a_platform_made_dynamic_drops_the_sleeping_box_on_it)
{
    pp_world w = make_world(0, 980);
    add_ground(w);
    pp_body shelf = add_rect(w, body_def(PP_BODY_STATIC, 400, 300, 0), 64, 8);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 300 - 4 - 8, 0), 16, 16);
    step_n(w, DT, 120);
    cr_assert_eq(awake(w, box), 0, "the box sleeps on the shelf");
    const float y0 = body_pos(w, box).y;
    PP_OK_OR_FAIL(pp_body_set_type(w, shelf, PP_BODY_DYNAMIC));
    cr_assert_eq(awake(w, box), 1, "what the shelf touches wakes");
    step_n(w, DT, 120);
    /* On the shelf (8 px) on the ground: its centre 8 + 8 px above the ground's top, give or take the slop. */
    cr_assert_float_eq(body_pos(w, box).y, GROUND_TOP - 16, 2.0f, "the box fell with the shelf to the ground: y %g (from %g)",
                       body_pos(w, box).y, y0);
    pp_world_destroy(w);
}

Test(props, fixed_rotation_set_holds_a_spinning_box_and_released_lets_a_torque_turn_it)
{
    pp_world w = make_world(0, 0);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 300, 0), 16, 16);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, box, v2(10, 0), 2));
    step_n(w, DT, 10);
    PP_OK_OR_FAIL(pp_body_set_fixed_rotation(w, box, 1));
    uint32_t fixed = 0;
    PP_OK_OR_FAIL(pp_body_get_fixed_rotation(w, box, &fixed));
    cr_assert_eq(fixed, 1);
    const float a0 = body_angle(w, box);
    PP_OK_OR_FAIL(pp_body_apply_torque(w, box, 1e6f));
    step_n(w, DT, 30);
    cr_assert_eq(body_angle(w, box), a0, "held: %g then %g", a0, body_angle(w, box));
    cr_assert_float_eq(body_vel(w, box).x, 10, 1e-4, "the linear velocity stays");
    PP_OK_OR_FAIL(pp_body_set_fixed_rotation(w, box, 0));
    float inertia = 0;
    PP_OK_OR_FAIL(pp_body_get_mass(w, box, NULL, NULL, &inertia));
    PP_OK_OR_FAIL(pp_body_apply_torque(w, box, (float)(3 * inertia)));
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    float spin = 0;
    PP_OK_OR_FAIL(pp_body_get_velocity(w, box, NULL, &spin));
    cr_assert_float_eq(spin, 3 * DT, 1e-5, "τ·dt/I: %g", spin);
    pp_world_destroy(w);
}

Test(props, set_type_and_fixed_rotation_refuse_what_cannot_be)
{
    pp_world w = make_world(0, 980);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 300, 0), 16, 16);
    EXPECT_ERR(pp_body_set_type(w, box, (pp_body_type)7), PP_ERR_INVALID_ARGUMENT, "type 7");
    /* Pixels of weight 0 have no mass: static is fine, dynamic is not. */
    static uint8_t mask[64], weights[64];
    memset(mask, 1, sizeof mask);
    pp_body_def d = body_def(PP_BODY_STATIC, 200, 300, 0);
    d.width = d.height = 8, d.mask = mask, d.weights = weights;
    pp_body ghost;
    PP_OK_OR_FAIL(pp_body_create(w, &d, &ghost));
    EXPECT_ERR(pp_body_set_type(w, ghost, PP_BODY_DYNAMIC), PP_ERR_INVALID_ARGUMENT, "weigh nothing");
    pp_body_type t;
    PP_OK_OR_FAIL(pp_body_get_type(w, ghost, &t));
    cr_assert_eq(t, PP_BODY_STATIC);
    /* A box hung on the world by a hinge: static, the joint would hold nothing. */
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    jd.body_b = box, jd.anchor_a = v2(400, 292);
    pp_joint j;
    PP_OK_OR_FAIL(pp_joint_create(w, &jd, &j));
    EXPECT_ERR(pp_body_set_type(w, box, PP_BODY_STATIC), PP_ERR_INVALID_ARGUMENT, "joint");
    PP_OK_OR_FAIL(pp_body_get_type(w, box, &t));
    cr_assert_eq(t, PP_BODY_DYNAMIC);
    PP_OK_OR_FAIL(pp_body_set_type(w, box, PP_BODY_KINEMATIC)); /* still moves: the joint holds on */
    pp_body stale = box;
    PP_OK_OR_FAIL(pp_body_destroy(w, box));
    EXPECT_ERR(pp_body_set_type(w, stale, PP_BODY_DYNAMIC), PP_ERR_INVALID_HANDLE, "pp_body_set_type");
    EXPECT_ERR(pp_body_set_fixed_rotation(w, stale, 1), PP_ERR_INVALID_HANDLE, "pp_body_set_fixed_rotation");
    pp_world_destroy(w);
}

Test(props, a_body_whose_type_and_rotation_changed_continues_bit_for_bit_through_a_snapshot)
{
    pp_world w = make_world(0, 980);
    add_ground(w);
    pp_body a = add_rect(w, body_def(PP_BODY_STATIC, 380, 300, 0.2f), 16, 16);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 420, 300, 0), 16, 16);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, b, v2(-30, 0), 4));
    step_n(w, DT, 5);
    PP_OK_OR_FAIL(pp_body_set_type(w, a, PP_BODY_DYNAMIC));
    PP_OK_OR_FAIL(pp_body_set_fixed_rotation(w, b, 1));
    step_n(w, DT, 5);
    expect_snapshot_continues(w, 90);
    pp_world_destroy(w);
}

Test(props, the_pieces_of_a_floating_body_cut_in_two_float_as_it_did)
{
    pp_world w = make_world(0, 980);
    pp_body plank = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 200, 0), 64, 8);
    PP_OK_OR_FAIL(pp_body_set_gravity_scale(w, plank, 0));
    int32_t changed = 0;
    PP_OK_OR_FAIL(pp_body_erase_circle(w, plank, v2(400, 200), 6, &changed));
    pp_body bodies[4];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 4, &n));
    cr_assert_eq(n, 2, "the cut leaves two pieces, got %d", n);
    float y0[2];
    for (int i = 0; i < 2; i++) {
        float scale = -1;
        PP_OK_OR_FAIL(pp_body_get_gravity_scale(w, bodies[i], &scale));
        cr_assert_eq(scale, 0.0f, "piece %d has gravity scale %g", i, scale);
        y0[i] = body_pos(w, bodies[i]).y;
    }
    step_n(w, DT, 60);
    for (int i = 0; i < 2; i++)
        cr_assert_eq(body_pos(w, bodies[i]).y, y0[i], "piece %d moved from %g to %g", i, y0[i], body_pos(w, bodies[i]).y);
    pp_world_destroy(w);
}
