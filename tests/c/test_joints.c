/* Joints (issue 24): physics against analytic figures (a physical pendulum's period, a motor's speed,
 * limits, lengths, a hanging box's reaction), breaking by force and by an erase, and the exact status of
 * every misuse. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "helpers.h"
#include "physpix.h"

PP_TEST_SUITE(joints);

#define DT (1.0f / 60.0f)
#define G 980.0f

/* A 10 × 60 px rod hung from the world by a revolute joint `d` px above its centre of mass. */
static pp_body hung_rod(pp_world w, double d, pp_joint *j)
{
    pp_body rod = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200, 0), 10, 60);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    jd.body_b = rod;
    jd.anchor_a = v2(200, (float)(200 - d));
    *j = make_joint(w, &jd);
    return rod;
}

/* The mean time between the upward zero crossings of the joint's angle over `steps` steps, s. */
static double swing_period(pp_world w, pp_joint j, int steps)
{
    double prev = joint_value(w, j, NULL), first = -1, last = -1;
    int crossings = 0;
    for (int k = 1; k <= steps; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        const double v = joint_value(w, j, NULL);
        if (prev < 0 && v >= 0) {
            const double t = (k - 1 + prev / (prev - v)) * DT;
            if (first < 0)
                first = t;
            last = t;
            crossings++;
        }
        prev = v;
    }
    cr_assert_geq(crossings, 3, "the pendulum swung through zero %d times", crossings);
    return (last - first) / (crossings - 1);
}

Test(joints, pendulum_period_matches_the_physical_pendulum)
{
    pp_world w = make_world(0, G);
    const double d = 25;
    pp_joint j;
    pp_body rod = hung_rod(w, d, &j);
    float m, I;
    pp_vec2 c;
    PP_OK_OR_FAIL(pp_body_get_mass(w, rod, &m, &c, &I));
    const double w0 = 0.2; /* rad/s: a swing of about 0.03 rad, where the period is the small-angle one */
    PP_OK_OR_FAIL(pp_body_set_velocity(w, rod, v2((float)(-w0 * d), 0), (float)w0));
    const double T = swing_period(w, j, 600);
    const double analytic = 2 * M_PI * sqrt((I + m * d * d) / (m * G * d));
    cr_log_info("pendulum: period %.4f s, analytic 2π√(I/(m·g·d)) %.4f s (%+.2f %%)", T, analytic,
                100 * (T / analytic - 1));
    cr_assert(fabs(T / analytic - 1) < 0.02, "period %g s, analytic %g s", T, analytic);
    pp_world_destroy(w);
}

Test(joints, revolute_motor_reaches_its_speed)
{
    pp_world w = make_world(0, 0);
    pp_body wheel = add_disc(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    jd.body_b = wheel;
    jd.anchor_a = v2(100, 100);
    jd.enable_motor = 1;
    jd.motor_speed = 3;
    jd.max_motor_force = 1e9f;
    pp_joint j = make_joint(w, &jd);
    step_n(w, DT, 30);
    float speed;
    joint_value(w, j, &speed);
    pp_vec2 lin;
    float ang;
    PP_OK_OR_FAIL(pp_body_get_velocity(w, wheel, &lin, &ang));
    cr_log_info("revolute motor: joint speed %.4f rad/s, body %.4f rad/s, asked 3", speed, ang);
    cr_assert_float_eq(speed, 3.0f, 0.01f);
    cr_assert_float_eq(ang, 3.0f, 0.01f);
    cr_assert_lt(hypot(lin.x, lin.y), 1.0, "the wheel's centre stays on the hinge");
    /* Against the world as body_b (a on the wheel), the joint reads the world's turn from the wheel. */
    PP_OK_OR_FAIL(pp_joint_destroy(w, j));
    jd.body_b = (pp_body){0};
    jd.body_a = wheel;
    j = make_joint(w, &jd);
    step_n(w, DT, 30);
    joint_value(w, j, &speed);
    PP_OK_OR_FAIL(pp_body_get_velocity(w, wheel, &lin, &ang));
    cr_assert_float_eq(speed, 3.0f, 0.01f);
    cr_assert_float_eq(ang, -3.0f, 0.01f);
    pp_world_destroy(w);
}

Test(joints, revolute_limits_hold)
{
    pp_world w = make_world(0, G);
    pp_joint j;
    pp_body rod = hung_rod(w, 25, &j);
    PP_OK_OR_FAIL(pp_joint_set_limits(w, j, 1, -0.2f, 0.3f));
    PP_OK_OR_FAIL(pp_body_set_velocity(w, rod, v2(-25 * 4.0f, 0), 4.0f)); /* would swing past 1 rad */
    float lo = 0, hi = 0;
    for (int k = 0; k < 120; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        const float v = joint_value(w, j, NULL);
        lo = fminf(lo, v), hi = fmaxf(hi, v);
    }
    cr_log_info("revolute limits -0.2..0.3 rad: swung over %.4f..%.4f rad", lo, hi);
    cr_assert(lo > -0.22f && hi < 0.32f && hi > 0.25f, "swung over %g..%g rad", lo, hi);
    pp_world_destroy(w);
}

/* A 20 px box on a horizontal prismatic joint to the world, at rest with no gravity. */
static pp_body slider_box(pp_world w, pp_joint *j, pp_vec2 axis)
{
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 20);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_PRISMATIC);
    jd.body_b = box;
    jd.anchor_a = jd.anchor_b = v2(100, 100);
    jd.axis = axis;
    *j = make_joint(w, &jd);
    return box;
}

Test(joints, prismatic_motor_and_limits)
{
    pp_world w = make_world(0, G); /* gravity across the axis: the slider holds it */
    pp_joint j;
    pp_body box = slider_box(w, &j, v2(2, 0));
    PP_OK_OR_FAIL(pp_joint_set_motor(w, j, 1, 50, 1e9f));
    PP_OK_OR_FAIL(pp_joint_set_limits(w, j, 1, -10, 40));
    step_n(w, DT, 30);
    float speed, value = joint_value(w, j, &speed);
    const pp_vec2 p = body_pos(w, box);
    cr_log_info("prismatic motor 50 px/s: %.3f px/s after 0.5 s at %.3f px", speed, value);
    cr_assert_float_eq(speed, 50.0f, 0.5f);
    cr_assert_float_eq(value, 25.0f, 1.0f);
    cr_assert_float_eq(p.y, 100.0f, 0.5f, "the box stays on the axis, y = %g", p.y);
    cr_assert_float_eq(body_angle(w, box), 0.0f, 1e-3f);
    step_n(w, DT, 60);
    value = joint_value(w, j, &speed);
    cr_log_info("prismatic limit 40 px: held at %.3f px", value);
    cr_assert_float_eq(value, 40.0f, 0.5f);
    PP_OK_OR_FAIL(pp_joint_set_motor(w, j, 1, -200, 1e9f));
    step_n(w, DT, 60);
    cr_assert_float_eq(joint_value(w, j, NULL), -10.0f, 0.5f);
    pp_world_destroy(w);
}

/* A 16 px box hung `len` px below (200, 100) by a distance joint def `jd` (anchors and bodies filled in). */
static pp_body hung_box(pp_world w, pp_joint_def jd, float len, pp_joint *j)
{
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 200 + len, 100, 0), 16, 16);
    jd.body_b = box;
    jd.anchor_a = v2(200, 100);
    jd.anchor_b = v2(200 + len, 100);
    *j = make_joint(w, &jd);
    return box;
}

Test(joints, distance_rigid_length_holds_through_a_swing)
{
    pp_world w = make_world(0, G);
    pp_joint j;
    hung_box(w, pp_joint_def_default(PP_JOINT_DISTANCE), 100, &j); /* starts level: swings down and back */
    float worst = 0;
    for (int k = 0; k < 120; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        worst = fmaxf(worst, fabsf(joint_value(w, j, NULL) - 100));
    }
    cr_log_info("distance 100 px rigid: worst error %.4f px over 2 s of swing", worst);
    cr_assert_lt(worst, 1.0f);
    pp_world_destroy(w);
}

Test(joints, rope_max_length_holds)
{
    pp_world w = make_world(0, G);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_DISTANCE);
    jd.max_length = 100;
    pp_joint j;
    pp_body box = hung_box(w, jd, 50, &j); /* slack at first: falls free, then the rope catches it */
    float longest = 0;
    bool slack_fall = false;
    for (int k = 0; k < 180; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        const float len = joint_value(w, j, NULL);
        longest = fmaxf(longest, len);
        if (k == 10)
            slack_fall = fabsf(body_vel(w, box).y - G * 11 * DT) < 0.05f * G * 11 * DT;
    }
    cr_log_info("rope max 100 px: longest %.4f px over 3 s", longest);
    cr_assert(slack_fall, "the box falls freely while the rope is slack");
    cr_assert_lt(longest, 101.0f);
    cr_assert_gt(longest, 99.0f);
    pp_world_destroy(w);
}

Test(joints, distance_spring_period)
{
    pp_world w = make_world(0, 0);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_DISTANCE);
    jd.spring_hertz = 2;
    pp_joint j;
    pp_body box = hung_box(w, jd, 100, &j);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, box, v2(60, 0), 0)); /* stretch it along the spring */
    double prev = joint_value(w, j, NULL) - 100, first = -1, last = -1;
    int crossings = 0;
    for (int k = 1; k <= 240; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        const double v = joint_value(w, j, NULL) - 100;
        if (prev < 0 && v >= 0) {
            const double t = (k - 1 + prev / (prev - v)) * DT;
            first = first < 0 ? t : first;
            last = t;
            crossings++;
        }
        prev = v;
    }
    cr_assert_geq(crossings, 3);
    const double T = (last - first) / (crossings - 1);
    cr_log_info("distance spring 2 Hz: period %.4f s (analytic 0.5 s, %+.2f %%)", T, 100 * (T / 0.5 - 1));
    cr_assert(fabs(T / 0.5 - 1) < 0.03, "period %g s", T);
    pp_world_destroy(w);
}

Test(joints, weld_sags_little)
{
    pp_world w = make_world(0, G);
    pp_body plank = add_rect(w, body_def(PP_BODY_DYNAMIC, 150, 100, 0), 100, 10); /* from x 100 to 200 */
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_WELD);
    jd.body_b = plank;
    jd.anchor_a = v2(105, 100);
    make_joint(w, &jd);
    step_n(w, DT, 120);
    const pp_vec2 p = body_pos(w, plank);
    const float a = body_angle(w, plank);
    cr_log_info("weld: a 100 px cantilever sags %.4f px at its centre, %.5f rad", p.y - 100, a);
    cr_assert_lt(fabsf(p.y - 100), 0.5f);
    cr_assert_lt(fabsf(a), 0.01f);
    /* A second plank welded to the first's free end: a weld between two moving bodies. */
    pp_body tip = add_rect(w, body_def(PP_BODY_DYNAMIC, 250, 100, 0), 100, 10);
    jd.body_a = plank, jd.body_b = tip, jd.anchor_a = v2(200, 100);
    make_joint(w, &jd);
    step_n(w, DT, 120);
    const float sag = body_pos(w, tip).y - 100;
    cr_log_info("weld: the second plank of a 200 px two-weld cantilever sags %.4f px at its centre, %.5f rad", sag,
                body_angle(w, tip));
    cr_assert_lt(fabsf(sag), 1.0f);
    cr_assert_lt(fabsf(body_angle(w, tip)), 0.01f);
    pp_world_destroy(w);
}

/* A 20 px box at (100, 100) and a def of `type` holding it as body_b at (100, anchor_y). */
static pp_joint_def def_on_box(pp_world w, pp_joint_type type, float anchor_y, pp_body *box)
{
    *box = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 20);
    pp_joint_def jd = pp_joint_def_default(type);
    jd.body_b = *box;
    jd.anchor_a = v2(100, anchor_y);
    return jd;
}

static float mass_of(pp_world w, pp_body b)
{
    float m, I;
    pp_vec2 c;
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, &c, &I));
    return m;
}

Test(joints, mouse_pulls_to_its_target)
{
    pp_world w = make_world(0, G);
    pp_body box;
    pp_joint_def jd = def_on_box(w, PP_JOINT_MOUSE, 100, &box);
    pp_joint j = make_joint(w, &jd);
    PP_OK_OR_FAIL(pp_joint_set_target(w, j, v2(200, 50)));
    step_n(w, DT, 120);
    const pp_vec2 p = body_pos(w, box);
    /* 5 Hz under gravity: the spring sags g/ω² = 1.0 px. */
    const double sag = G / pow(2 * M_PI * 5, 2);
    cr_log_info("mouse: reached (%.3f, %.3f) for target (200, 50), sag %.3f px", p.x, p.y, sag);
    cr_assert_lt(dist(p, v2(200, (float)(50 + sag))), 0.5);
    pp_world_destroy(w);
}

Test(joints, mouse_force_is_capped)
{
    pp_world w = make_world(0, 0);
    pp_body box;
    pp_joint_def jd = def_on_box(w, PP_JOINT_MOUSE, 100, &box);
    const float m = mass_of(w, box);
    jd.spring_damping_ratio = 0;
    jd.max_force = 100 * m; /* at most 100 px/s² */
    pp_joint j = make_joint(w, &jd);
    PP_OK_OR_FAIL(pp_joint_set_target(w, j, v2(1100, 100)));
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    pp_vec2 f;
    PP_OK_OR_FAIL(pp_joint_get_reaction(w, j, &f, NULL));
    const pp_vec2 v = body_vel(w, box);
    /* The implicit spring gives up h·k·v of its pull as the body starts to move: 93 % here. */
    cr_log_info("mouse capped at 100 px/s²: pull %.3f px/s², speed %.4f px/s after a step (%.4f at the cap)", f.x / m,
                v.x, 100 * DT);
    cr_assert(f.x / m > 90 && f.x / m <= 100, "pull %g px/s²", f.x / m);
    cr_assert(v.x > 0.9f * 100 * DT && v.x <= 100 * DT, "speed %g px/s", v.x);
    pp_world_destroy(w);
}

Test(joints, reaction_of_a_hanging_box_is_its_weight)
{
    pp_world w = make_world(0, G);
    pp_body box;
    pp_joint_def jd = def_on_box(w, PP_JOINT_REVOLUTE, 92, &box);
    pp_joint j = make_joint(w, &jd);
    step_n(w, DT, 60);
    const float m = mass_of(w, box);
    float t;
    pp_vec2 f;
    PP_OK_OR_FAIL(pp_joint_get_reaction(w, j, &f, &t));
    cr_log_info("reaction of a hanging box: (%.3f, %.3f), weight m·g = %.3f (%+.3f %%)", f.x, f.y, m * G,
                100 * (-f.y / (m * G) - 1));
    cr_assert(fabs(-f.y / (m * G) - 1) < 0.02, "reaction %g, weight %g", f.y, m * G);
    cr_assert_lt(fabsf(f.x), 0.01f * m * G);
    pp_world_destroy(w);
}

/* The events queued since the last read, at most 16. */
static int32_t read_events(pp_world w, pp_event *ev)
{
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 16, &n));
    cr_assert_leq(n, 16);
    return n;
}

static const pp_event *find_event(const pp_event *ev, int32_t n, pp_event_type type)
{
    for (int32_t i = 0; i < n; i++)
        if (ev[i].type == type)
            return &ev[i];
    return NULL;
}

static int32_t joint_count(pp_world w)
{
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_get_joints(w, NULL, 0, &n));
    return n;
}

Test(joints, a_joint_breaks_under_its_break_force)
{
    pp_world w = make_world(0, G);
    pp_body box;
    pp_joint_def jd = def_on_box(w, PP_JOINT_REVOLUTE, 92, &box);
    const float m = mass_of(w, box);
    jd.break_force = 2 * m * G; /* holds the box's weight */
    pp_joint j = make_joint(w, &jd);
    step_n(w, DT, 30);
    pp_event ev[16];
    cr_assert_eq(read_events(w, ev), 0);
    cr_assert_eq(joint_count(w), 1);
    PP_OK_OR_FAIL(pp_body_apply_force(w, box, v2(0, 3 * m * G), body_pos(w, box))); /* pulls it past 2 m·g */
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    const int32_t n = read_events(w, ev);
    const pp_event *e = find_event(ev, n, PP_EVENT_JOINT_BROKEN);
    cr_assert_not_null(e, "no JOINT_BROKEN among %d events", n);
    cr_assert(e->joint.id == j.id && e->body.id == 0 && e->other.id == box.id);
    cr_assert_eq(joint_count(w), 0);
    float v;
    cr_assert_eq(pp_joint_get_value(w, j, &v, NULL), PP_ERR_INVALID_HANDLE);
    const float y0 = body_pos(w, box).y;
    step_n(w, DT, 10);
    cr_assert_gt(body_pos(w, box).y, y0 + 10, "the box falls once the joint is gone");
    pp_world_destroy(w);
}

/* A plank from x 100 to 300 at y 100, hung from the world by revolute joints 5 px in from each end. */
static pp_body hung_plank(pp_world w, pp_joint *left, pp_joint *right)
{
    pp_body plank = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 100, 0), 200, 10);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    jd.body_b = plank;
    jd.anchor_a = v2(105, 100);
    *left = make_joint(w, &jd);
    jd.anchor_a = v2(295, 100);
    *right = make_joint(w, &jd);
    return plank;
}

Test(joints, erasing_an_anchor_breaks_its_joint)
{
    pp_world w = make_world(0, G);
    pp_joint left, right;
    pp_body plank = hung_plank(w, &left, &right);
    step_n(w, DT, 10);
    int32_t changed = 0;
    PP_OK_OR_FAIL(pp_body_erase_circle(w, plank, v2(295, 100), 8, &changed)); /* the right end, anchor and all */
    cr_assert_gt(changed, 0);
    pp_event ev[16];
    const int32_t n = read_events(w, ev);
    const pp_event *e = find_event(ev, n, PP_EVENT_JOINT_BROKEN);
    cr_assert_not_null(e, "no JOINT_BROKEN among %d events", n);
    cr_assert(e->joint.id == right.id && e->other.id == plank.id);
    cr_assert_eq(joint_count(w), 1);
    float v;
    PP_OK_OR_FAIL(pp_joint_get_value(w, left, &v, NULL));
    /* Erasing near, but not under, the left anchor keeps it: a solid pixel is left within 1 px. */
    PP_OK_OR_FAIL(pp_body_erase_circle(w, plank, v2(108, 100), 2.5f, &changed));
    cr_assert_gt(changed, 0);
    cr_assert_eq(read_events(w, ev), 0);
    step_n(w, DT, 60);
    cr_assert_gt(joint_value(w, left, NULL), 0.5f, "the plank swings down about its left end");
    pp_world_destroy(w);
}

Test(joints, a_split_keeps_each_joint_on_the_piece_holding_its_anchor)
{
    pp_world w = make_world(0, G);
    pp_joint left, right;
    pp_body plank = hung_plank(w, &left, &right);
    int32_t changed = 0;
    PP_OK_OR_FAIL(pp_body_erase_circle(w, plank, v2(200, 100), 12, &changed)); /* cut in two */
    pp_event ev[16];
    const int32_t n = read_events(w, ev);
    const pp_event *split = find_event(ev, n, PP_EVENT_BODY_SPLIT);
    cr_assert_not_null(split);
    cr_assert_null(find_event(ev, n, PP_EVENT_JOINT_BROKEN));
    pp_body a, b_left, b_right;
    const pp_vec2 anchor_l = v2(105, 100), anchor_r = v2(295, 100);
    PP_OK_OR_FAIL(pp_joint_get_bodies(w, left, &a, &b_left));
    PP_OK_OR_FAIL(pp_joint_get_bodies(w, right, &a, &b_right));
    cr_assert_neq(b_left.id, b_right.id, "each half holds one joint");
    cr_assert(b_left.id == split->other.id || b_right.id == split->other.id);
    const double rl = dist(body_pos(w, b_left), anchor_l), rr = dist(body_pos(w, b_right), anchor_r);
    step_n(w, DT, 90);
    /* Each half hangs from its own end: the left one turns down (+), the right one up (−, y down). */
    const float vl = joint_value(w, left, NULL), vr = joint_value(w, right, NULL);
    cr_log_info("split: the halves hang at %.3f and %.3f rad", vl, vr);
    cr_assert_gt(vl, 0.5f);
    cr_assert_lt(vr, -0.5f);
    /* Each piece turns about its own anchor: the anchor stays put and the piece's distance from it holds. */
    cr_assert_float_eq(dist(body_pos(w, b_left), anchor_l), rl, 0.5);
    cr_assert_float_eq(dist(body_pos(w, b_right), anchor_r), rr, 0.5);
    pp_world_destroy(w);
}

Test(joints, destroying_a_body_destroys_its_joints_without_events)
{
    pp_world w = make_world(0, G);
    pp_joint left, right;
    pp_body plank = hung_plank(w, &left, &right);
    pp_body other = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 100, 0), 10, 10);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_DISTANCE);
    jd.body_a = plank, jd.body_b = other;
    jd.anchor_a = v2(290, 100), jd.anchor_b = v2(400, 100);
    pp_joint d = make_joint(w, &jd);
    cr_assert_eq(joint_count(w), 3);
    PP_OK_OR_FAIL(pp_body_destroy(w, plank));
    cr_assert_eq(joint_count(w), 0);
    pp_event ev[16];
    cr_assert_eq(read_events(w, ev), 0);
    cr_assert_eq(pp_joint_destroy(w, left), PP_ERR_INVALID_HANDLE);
    cr_assert_eq(pp_joint_destroy(w, d), PP_ERR_INVALID_HANDLE);
    step_n(w, DT, 10);
    cr_assert_gt(body_pos(w, other).y, 110.0f, "its partner falls free");
    pp_world_destroy(w);
}

Test(joints, connected_bodies_collide_only_when_asked)
{
    for (uint32_t collide = 0; collide <= 1; collide++) {
        pp_world w = make_world(0, 0);
        pp_body a = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 20);
        pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 115, 100, 0), 20, 20); /* overlapping by 5 px */
        pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
        jd.body_a = a, jd.body_b = b;
        jd.anchor_a = v2(108, 100);
        jd.collide_connected = collide;
        make_joint(w, &jd);
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        int32_t n = -1;
        PP_OK_OR_FAIL(pp_world_get_contacts(w, NULL, 0, &n));
        cr_assert_eq(n > 0, collide == 1, "collide_connected %u: %d contacts", collide, n);
        pp_world_destroy(w);
    }
}

Test(joints, joined_bodies_sleep_and_wake_together)
{
    pp_world w = make_world(0, G);
    pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 200, 220, 0), 400, 40);
    (void)ground;
    pp_body a = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 190, 0), 20, 20);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 190, 0), 20, 20);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_DISTANCE);
    jd.body_a = a, jd.body_b = b;
    jd.anchor_a = v2(100, 190), jd.anchor_b = v2(200, 190);
    make_joint(w, &jd);
    step_n(w, DT, 240);
    int32_t awake_a = -1, awake_b = -1;
    PP_OK_OR_FAIL(pp_body_is_awake(w, a, &awake_a));
    PP_OK_OR_FAIL(pp_body_is_awake(w, b, &awake_b));
    cr_assert(!awake_a && !awake_b, "both asleep: %d %d", awake_a, awake_b);
    PP_OK_OR_FAIL(pp_body_apply_impulse(w, a, v2(-40000, 0), body_pos(w, a))); /* wakes a alone */
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    PP_OK_OR_FAIL(pp_body_is_awake(w, b, &awake_b));
    cr_assert(awake_b, "b wakes with a");
    cr_assert_float_eq(body_vel(w, b).x, body_vel(w, a).x, 0.01f, "and moves with it: %g and %g px/s",
                       body_vel(w, b).x, body_vel(w, a).x);
    cr_assert_lt(body_vel(w, b).x, -0.5f);
    pp_world_destroy(w);
}

/* Every body's state, slot order, for comparing two worlds bit for bit. */
static int32_t states(pp_world w, pp_body_state *out, int32_t cap)
{
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_body_states(w, out, cap, &n));
    cr_assert_leq(n, cap);
    return n;
}

Test(joints, a_snapshot_saved_mid_swing_continues_exactly)
{
    pp_world w = make_world(0, G);
    add_rect(w, body_def(PP_BODY_STATIC, 300, 420, 0), 600, 40);
    pp_joint left, right, j;
    pp_body plank = hung_plank(w, &left, &right);
    PP_OK_OR_FAIL(pp_joint_set_limits(w, left, 1, -1, 1));
    pp_body bob = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 180, 0), 12, 12);
    pp_body slider = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 100, 0), 16, 16);
    pp_body held = add_rect(w, body_def(PP_BODY_DYNAMIC, 500, 100, 0), 16, 16);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_DISTANCE);
    jd.body_a = plank, jd.body_b = bob, jd.anchor_a = v2(200, 104), jd.anchor_b = v2(200, 180), jd.max_length = 90;
    make_joint(w, &jd);
    jd = pp_joint_def_default(PP_JOINT_PRISMATIC);
    jd.body_b = slider, jd.anchor_a = jd.anchor_b = v2(400, 100), jd.axis = v2(1, 1);
    jd.enable_limit = 1, jd.lower = -20, jd.upper = 60, jd.enable_motor = 1, jd.motor_speed = 30;
    jd.max_motor_force = 1e5f;
    make_joint(w, &jd);
    jd = pp_joint_def_default(PP_JOINT_WELD);
    jd.body_a = slider, jd.body_b = held, jd.anchor_a = v2(450, 100), jd.spring_hertz = 3, jd.spring_damping_ratio = 0.2f;
    make_joint(w, &jd);
    jd = pp_joint_def_default(PP_JOINT_MOUSE);
    jd.body_b = bob, jd.anchor_a = v2(200, 180), jd.max_force = 5e5f;
    j = make_joint(w, &jd);
    PP_OK_OR_FAIL(pp_joint_set_target(w, j, v2(260, 150)));
    PP_OK_OR_FAIL(pp_body_set_velocity(w, plank, v2(0, -50), 0.3f));
    step_n(w, DT, 20);
    int32_t changed = 0; /* a split mid-run: joints on a piece re-attached */
    PP_OK_OR_FAIL(pp_body_erase_circle(w, plank, v2(250, 100), 10, &changed));
    step_n(w, DT, 5);

    pp_world back = snapshot_round_trip(w);
    pp_joint ja[8], jb[8];
    int32_t na = 0, nb = 0;
    PP_OK_OR_FAIL(pp_world_get_joints(w, ja, 8, &na));
    PP_OK_OR_FAIL(pp_world_get_joints(back, jb, 8, &nb));
    cr_assert(na == nb && na == 6, "%d joints saved, %d loaded", na, nb);
    for (int k = 0; k < 90; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        PP_OK_OR_FAIL(pp_world_step(back, DT));
        pp_body_state sa[16], sb[16];
        const int32_t n = states(w, sa, 16), m = states(back, sb, 16);
        cr_assert_eq(n, m);
        for (int32_t i = 0; i < n; i++) {
            sa[i].body.id = sb[i].body.id = 0; /* the handles name their worlds */
            cr_assert(memcmp(&sa[i], &sb[i], sizeof sa[i]) == 0, "step %d, body %d: (%.9g, %.9g) vs (%.9g, %.9g)", k,
                      (int)i, sa[i].position.x, sa[i].position.y, sb[i].position.x, sb[i].position.y);
        }
        for (int32_t i = 0; i < na; i++) {
            float va, vb, ta, tb;
            pp_vec2 fa, fb;
            PP_OK_OR_FAIL(pp_joint_get_value(w, ja[i], &va, NULL));
            PP_OK_OR_FAIL(pp_joint_get_value(back, jb[i], &vb, NULL));
            PP_OK_OR_FAIL(pp_joint_get_reaction(w, ja[i], &fa, &ta));
            PP_OK_OR_FAIL(pp_joint_get_reaction(back, jb[i], &fb, &tb));
            cr_assert(va == vb && fa.x == fb.x && fa.y == fb.y && ta == tb, "step %d, joint %d", k, (int)i);
        }
    }
    pp_world_destroy(w);
    pp_world_destroy(back);
}

Test(joints, misuse_is_refused_with_its_status)
{
    pp_world w = make_world(0, G), other = make_world(0, G);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 20);
    pp_body wall = add_rect(w, body_def(PP_BODY_STATIC, 300, 100, 0), 20, 20);
    pp_body foreign = add_rect(other, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 20);
    pp_joint_def d = pp_joint_def_default(PP_JOINT_REVOLUTE);
    d.body_b = box;
    d.anchor_a = v2(100, 100);
    pp_joint j = {0};
    EXPECT_ERR(pp_joint_create(w, NULL, &j), PP_ERR_INVALID_ARGUMENT, "def");
    EXPECT_ERR(pp_joint_create(w, &d, NULL), PP_ERR_INVALID_ARGUMENT, "out");
    EXPECT_ERR(pp_joint_create((pp_world){0}, &d, &j), PP_ERR_INVALID_HANDLE, "world");
    pp_joint_def bad = d;
    bad.struct_size = 0;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_ABI, "struct_size");
    bad = d, bad.type = (pp_joint_type)9;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "type");
    bad = d, bad.body_a = box;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "same");
    bad = d, bad.body_b = (pp_body){0};
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "same");
    bad = d, bad.body_b = wall;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "neither body moves");
    bad = d, bad.body_a = foreign;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_HANDLE, "belongs to world");
    bad = d, bad.anchor_a.x = NAN;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "anchor_a");
    bad = d, bad.anchor_a = v2(100, 1e30f);
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "farther");
    bad = d, bad.lower = 0.5f, bad.upper = 0.1f;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "lower");
    bad = d, bad.lower = -4, bad.upper = 0;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "within");
    bad = d, bad.max_motor_force = -1;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "max_motor_force");
    bad = d, bad.type = PP_JOINT_MOUSE, bad.max_force = -1;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "max_force");
    bad = d, bad.type = PP_JOINT_MOUSE, bad.body_a = wall;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "mouse");
    bad = d, bad.break_force = INFINITY;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "break_force");
    bad = d, bad.type = PP_JOINT_PRISMATIC, bad.axis = v2(0, 0);
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "axis");
    bad = d, bad.type = PP_JOINT_DISTANCE, bad.anchor_b = bad.anchor_a;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "coincide");
    bad = d, bad.type = PP_JOINT_DISTANCE, bad.anchor_b = v2(120, 100), bad.min_length = 50, bad.max_length = 10;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "min_length");
    cr_assert_eq(j.id, 0, "no failed call wrote its out");
    cr_assert_eq(joint_count(w), 0);

    j = make_joint(w, &d);
    pp_vec2 f;
    float x;
    int32_t n;
    pp_joint stale = j, alien = {0};
    EXPECT_ERR(pp_joint_get_reaction(w, j, NULL, NULL), PP_ERR_INVALID_ARGUMENT, "NULL");
    EXPECT_ERR(pp_joint_get_value(w, j, NULL, NULL), PP_ERR_INVALID_ARGUMENT, "NULL");
    EXPECT_ERR(pp_world_get_joints(w, NULL, 1, &n), PP_ERR_INVALID_ARGUMENT, "out");
    EXPECT_ERR(pp_world_get_joints(w, NULL, 0, NULL), PP_ERR_INVALID_ARGUMENT, "count");
    EXPECT_ERR(pp_joint_set_motor(w, j, 1, NAN, 1), PP_ERR_INVALID_ARGUMENT, "speed");
    EXPECT_ERR(pp_joint_set_motor(w, j, 1, 1, -1), PP_ERR_INVALID_ARGUMENT, "max_force");
    EXPECT_ERR(pp_joint_set_limits(w, j, 1, 1, -1), PP_ERR_INVALID_ARGUMENT, "lower");
    EXPECT_ERR(pp_joint_set_target(w, j, v2(0, 0)), PP_ERR_INVALID_ARGUMENT, "mouse");
    EXPECT_ERR(pp_joint_get_type(w, j, NULL), PP_ERR_INVALID_ARGUMENT, "out");
    EXPECT_ERR(pp_joint_get_user_data(w, j, NULL), PP_ERR_INVALID_ARGUMENT, "out");
    EXPECT_ERR(pp_joint_get_bodies(w, j, NULL, NULL), PP_ERR_INVALID_ARGUMENT, "body_a");
    pp_joint_def md = pp_joint_def_default(PP_JOINT_MOUSE);
    md.body_b = foreign;
    pp_joint mouse = make_joint(other, &md);
    EXPECT_ERR(pp_joint_set_target(other, mouse, v2(INFINITY, 0)), PP_ERR_INVALID_ARGUMENT, "target");
    EXPECT_ERR(pp_joint_set_motor(other, mouse, 1, 1, 1), PP_ERR_INVALID_ARGUMENT, "motor");
    EXPECT_ERR(pp_joint_set_limits(other, mouse, 1, 0, 1), PP_ERR_INVALID_ARGUMENT, "limits");
    EXPECT_ERR(pp_joint_destroy(w, mouse), PP_ERR_INVALID_HANDLE, "belongs to world");
    PP_OK_OR_FAIL(pp_joint_destroy(w, j));
    EXPECT_ERR(pp_joint_destroy(w, stale), PP_ERR_INVALID_HANDLE, "stale");
    EXPECT_ERR(pp_joint_get_reaction(w, stale, &f, &x), PP_ERR_INVALID_HANDLE, "stale");
    EXPECT_ERR(pp_joint_get_value(w, alien, &x, &x), PP_ERR_INVALID_HANDLE, "null");
    EXPECT_ERR(pp_joint_set_motor(w, stale, 0, 0, 0), PP_ERR_INVALID_HANDLE, "stale");
    EXPECT_ERR(pp_joint_set_limits(w, stale, 0, 0, 0), PP_ERR_INVALID_HANDLE, "stale");
    EXPECT_ERR(pp_joint_set_target(w, stale, v2(0, 0)), PP_ERR_INVALID_HANDLE, "stale");
    cr_assert_eq(pp_joint_def_default((pp_joint_type)42).type, PP_JOINT_REVOLUTE);
    pp_world_destroy(w);
    pp_world_destroy(other);
}

Test(joints, a_scene_names_its_joints_bodies)
{
    char dir[] = "/tmp/pp_joints_XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    write_file(dir, "ok.json",
               "{ \"world\": { \"backend\": \"cpu\" },\n"
               "  \"bodies\": [ { \"name\": \"rod\", \"box\": [10, 60], \"position\": [200, 200] },\n"
               "              { \"name\": \"bob\", \"box\": [10, 10], \"position\": [300, 200] } ],\n"
               "  \"joints\": [ { \"type\": \"revolute\", \"body_b\": \"rod\", \"anchor_a\": [200, 175],\n"
               "                \"enable_limit\": true, \"lower\": -0.5, \"upper\": 0.5, \"user_data\": 7 },\n"
               "              { \"type\": \"distance\", \"body_a\": \"rod\", \"body_b\": \"bob\",\n"
               "                \"anchor_a\": [200, 220], \"anchor_b\": [300, 200], \"max_length\": 120 } ] }\n");
    write_file(dir, "unknown.json", "{ \"bodies\": [ { \"name\": \"rod\", \"box\": [10, 60] } ],\n"
                                    "  \"joints\": [ { \"type\": \"revolute\", \"body_b\": \"nobody\" } ] }\n");
    write_file(dir, "bad.json", "{ \"bodies\": [ { \"name\": \"rod\", \"box\": [10, 60] } ],\n"
                                "  \"joints\": [ { \"type\": \"weld\", \"body_a\": \"rod\", \"body_b\": \"rod\" } ] }\n");
    write_file(dir, "typeless.json", "{ \"joints\": [ { \"anchor_a\": [0, 0] } ] }\n");
    char path[256];
    snprintf(path, sizeof path, "%s/ok.json", dir);
    pp_world w = {0};
    PP_OK_OR_FAIL(pp_world_load_scene(path, &w));
    pp_joint js[4];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_joints(w, js, 4, &n));
    cr_assert_eq(n, 2);
    pp_joint_type t;
    uint64_t user = 0;
    PP_OK_OR_FAIL(pp_joint_get_type(w, js[0], &t));
    PP_OK_OR_FAIL(pp_joint_get_user_data(w, js[0], &user));
    cr_assert(t == PP_JOINT_REVOLUTE && user == 7);
    PP_OK_OR_FAIL(pp_joint_get_type(w, js[1], &t));
    cr_assert_eq(t, PP_JOINT_DISTANCE);
    float lo = 0, hi = 0;
    for (int k = 0; k < 120; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        const float v = joint_value(w, js[0], NULL);
        lo = fminf(lo, v), hi = fmaxf(hi, v);
        cr_assert_lt(joint_value(w, js[1], NULL), 121.0f);
    }
    cr_assert(lo > -0.52f && hi < 0.52f, "the scene's limits hold: %g..%g", lo, hi);
    pp_world_destroy(w);
    snprintf(path, sizeof path, "%s/unknown.json", dir);
    EXPECT_ERR(pp_world_load_scene(path, &w), PP_ERR_FORMAT, "joints[0].body_b: no body is named 'nobody'");
    snprintf(path, sizeof path, "%s/bad.json", dir);
    EXPECT_ERR(pp_world_load_scene(path, &w), PP_ERR_FORMAT, "joints[0]");
    snprintf(path, sizeof path, "%s/typeless.json", dir);
    EXPECT_ERR(pp_world_load_scene(path, &w), PP_ERR_FORMAT, "joints[0].type: missing");
    remove_tree(dir);
}

Test(joints, a_soft_weld_deflects_by_weight_over_stiffness)
{
    pp_world w = make_world(0, G);
    pp_body plank = add_rect(w, body_def(PP_BODY_DYNAMIC, 150, 100, 0), 100, 10);
    pp_body tip = add_rect(w, body_def(PP_BODY_DYNAMIC, 250, 100, 0), 100, 10);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_WELD);
    jd.body_b = plank, jd.anchor_a = v2(105, 100);
    make_joint(w, &jd);
    jd.body_a = plank, jd.body_b = tip, jd.anchor_a = v2(200, 100);
    jd.spring_hertz = 2, jd.spring_damping_ratio = 1;
    make_joint(w, &jd);
    step_n(w, DT, 120);
    /* k = m_reduced·(2π·2 Hz)²; the weld carries the tip's weight (its rotation stays rigid in ODE's fixed joint). */
    const double ma = mass_of(w, plank), mb = mass_of(w, tip), k = ma * mb / (ma + mb) * pow(4 * M_PI, 2);
    const double sag = body_pos(w, tip).y - 100, analytic = mb * G / k;
    cr_log_info("soft weld 2 Hz: the tip sags %.4f px, m·g/k = %.4f px", sag, analytic);
    cr_assert(fabs(sag / analytic - 1) < 0.02, "sag %g px, m·g/k %g px", sag, analytic);
    pp_world_destroy(w);
}

/* A motor's speed is within what a body may reach (issue 39): FLT_MAX was accepted and drove the pair 4.6e14 px
 * in a step, each step taking seconds. Past the limit is refused, naming the argument and the range; at the
 * limit, with the largest force, the pair turns at no more than PP_MAX_ANGULAR_SPEED and stays finite. */
Test(joints, a_motor_speed_past_what_a_body_may_reach_is_refused, .timeout = 60)
{
    pp_world w = make_world(0, 0);
    pp_body a = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200, 0), 20, 20);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 240, 200, 0), 20, 20);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    jd.body_a = a, jd.body_b = b, jd.anchor_a = v2(220, 200);
    pp_joint j = make_joint(w, &jd);
    EXPECT_ERR(pp_joint_set_motor(w, j, 1, FLT_MAX, FLT_MAX), PP_ERR_INVALID_ARGUMENT, "speed|PP_MAX_ANGULAR_SPEED");
    EXPECT_ERR(pp_joint_set_motor(w, j, 1, -1.01f * PP_MAX_ANGULAR_SPEED, 1), PP_ERR_INVALID_ARGUMENT, "speed");
    EXPECT_ERR(pp_joint_set_motor(w, j, 1, 1, FLT_MAX * 2.0f), PP_ERR_INVALID_ARGUMENT, "max_force");
    jd.enable_motor = 1, jd.motor_speed = 2 * PP_MAX_ANGULAR_SPEED;
    pp_joint k;
    EXPECT_ERR(pp_joint_create(w, &jd, &k), PP_ERR_INVALID_ARGUMENT, "motor_speed|PP_MAX_ANGULAR_SPEED");
    pp_joint_def pd = pp_joint_def_default(PP_JOINT_PRISMATIC);
    pd.body_a = a, pd.body_b = b, pd.anchor_a = v2(220, 200), pd.axis = v2(1, 0);
    pd.enable_motor = 1, pd.motor_speed = -2 * PP_MAX_SPEED;
    EXPECT_ERR(pp_joint_create(w, &pd, &k), PP_ERR_INVALID_ARGUMENT, "motor_speed|PP_MAX_SPEED");
    PP_OK_OR_FAIL(pp_joint_set_motor(w, j, 1, PP_MAX_ANGULAR_SPEED, FLT_MAX));
    for (int i = 0; i < 120; i++) {
        const pp_status st = pp_world_step(w, DT);
        cr_assert(st == PP_OK, "step %d: %s (%s)", i, pp_status_name(st), pp_last_error());
    }
    /* At 1e5 rad/s the hinge cannot hold a 20 px arm (2e11 px/s² outward), but no body passes the motion limits:
     * each stays within PP_MAX_SPEED × the 2 s run of where it was, turning at most PP_MAX_ANGULAR_SPEED. */
    const pp_body bodies[2] = {a, b};
    const pp_vec2 from[2] = {v2(200, 200), v2(240, 200)};
    for (int i = 0; i < 2; i++) {
        pp_vec2 p = body_pos(w, bodies[i]), v;
        float spin = 0;
        PP_OK_OR_FAIL(pp_body_get_velocity(w, bodies[i], &v, &spin));
        cr_assert(isfinite(p.x) && isfinite(p.y) && dist(p, from[i]) <= PP_MAX_SPEED * 120 * DT,
                  "body %d at (%g, %g)", i, p.x, p.y);
        cr_assert(fabsf(spin) <= PP_MAX_ANGULAR_SPEED && hypot(v.x, v.y) <= PP_MAX_SPEED, "body %d moves at "
                  "(%g, %g) px/s, %g rad/s", i, v.x, v.y, spin);
    }
    pp_world_destroy(w);
}

/* Only a prismatic joint has an axis: another's ignored axis of (0, 0) was normalised into NaN in its state, and
 * the world could no longer be saved (fuzz_api: PP_ERR_LIMIT, "joint … holds nan"). */
Test(joints, a_revolute_joint_with_a_zero_axis_saves_and_loads)
{
    pp_world w = make_world(0, 980);
    pp_body rod = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200, 0), 10, 60);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    jd.body_b = rod, jd.anchor_a = v2(200, 175), jd.axis = v2(0, 0);
    make_joint(w, &jd);
    step_n(w, DT, 10);
    pp_world back = snapshot_round_trip(w);
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_joints(back, NULL, 0, &n));
    cr_assert_eq(n, 1, "the loaded world holds the joint");
    pp_world_destroy(back);
    pp_world_destroy(w);
}

/* Every type keeps its def whole (snapshots and scenes write it), so a field a type ignores is finite too: a
 * revolute joint of axis (NaN, NaN) was accepted and its world's snapshot was invalid JSON (fuzz_api). */
Test(joints, a_field_a_type_ignores_is_still_finite)
{
    pp_world w = make_world(0, 980);
    pp_body rod = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200, 0), 10, 60);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    jd.body_b = rod, jd.anchor_a = v2(200, 175), jd.axis = v2(NAN, NAN);
    pp_joint j;
    EXPECT_ERR(pp_joint_create(w, &jd, &j), PP_ERR_INVALID_ARGUMENT, "axis");
    jd.axis = v2(1, 0), jd.upper = INFINITY;
    EXPECT_ERR(pp_joint_create(w, &jd, &j), PP_ERR_INVALID_ARGUMENT, "upper");
    pp_world_destroy(w);
}
