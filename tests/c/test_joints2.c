/* Joints, second part (issue 41): a rope that goes slack, wheels, motor joints, springs toward a target, the
 * distance motor, soft welds and break_torque, each against its analytic figure; misuse, snapshots, scenes. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "helpers.h"
#include "physpix.h"

PP_TEST_SUITE(joints2);

#define DT (1.0f / 60.0f)
#define G 980.0f

static float spin(pp_world w, pp_body b)
{
    pp_vec2 v;
    float s = 0;
    PP_OK_OR_FAIL(pp_body_get_velocity(w, b, &v, &s));
    return s;
}

/* A free oscillation of x(t) − centre, sampled every step: its mean period from upward zero crossings and the
 * damping ratio from the logarithmic decrement of its successive maxima (each refined by a parabola). */
typedef struct oscillation {
    double period, ratio;
    int crossings, peaks;
} oscillation;

typedef float (*sampler)(pp_world w, const void *ctx);

static oscillation measure(pp_world w, sampler f, const void *ctx, double centre, int steps)
{
    oscillation o = {0};
    double x[3] = {0, 0, f(w, ctx) - centre}, first = -1, last = -1, peak0 = 0, peak1 = 0;
    for (int k = 1; k <= steps; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        x[0] = x[1], x[1] = x[2], x[2] = f(w, ctx) - centre;
        if (x[1] < 0 && x[2] >= 0) {
            const double t = (k - 1 + x[1] / (x[1] - x[2])) * DT;
            first = first < 0 ? t : first;
            last = t;
            o.crossings++;
        }
        if (k >= 2 && x[1] > 0 && x[1] >= x[0] && x[1] > x[2]) {
            const double den = x[0] - 2 * x[1] + x[2];
            const double top = den < 0 ? x[1] - (x[0] - x[2]) * (x[0] - x[2]) / (8 * den) : x[1];
            if (o.peaks == 0)
                peak0 = top;
            peak1 = top;
            o.peaks++;
        }
    }
    cr_assert_geq(o.crossings, 3, "it oscillated through its centre %d times", o.crossings);
    cr_assert_geq(o.peaks, 2);
    o.period = (last - first) / (o.crossings - 1);
    const double delta = log(peak0 / peak1) / (o.peaks - 1);
    o.ratio = delta / sqrt(4 * M_PI * M_PI + delta * delta);
    return o;
}

static float value_of(pp_world w, const void *ctx) { return joint_value(w, *(const pp_joint *)ctx, NULL); }

/* ---- rope ---- */

Test(joints2, a_rope_thrown_inward_moves_freely_and_still_holds_at_max_length)
{
    pp_world w = make_world(0, G);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200, 0), 16, 16);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_DISTANCE);
    jd.body_b = box, jd.anchor_a = v2(200, 100), jd.anchor_b = v2(200, 200), jd.max_length = 100;
    pp_joint j = make_joint(w, &jd);
    step_n(w, DT, 30); /* hanging taut */
    cr_assert(fabsf(joint_value(w, j, NULL) - 100) < 0.5f, "it hangs at max_length: %g", joint_value(w, j, NULL));
    const float v0 = 120; /* thrown toward the anchor: it rises v0²/2g before falling back */
    PP_OK_OR_FAIL(pp_body_set_velocity(w, box, v2(0, -v0), 0));
    const double d0 = joint_value(w, j, NULL), analytic = d0 - v0 * v0 / (2 * G);
    double nearest = 1e9, longest = 0;
    for (int k = 0; k < 180; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        nearest = fmin(nearest, joint_value(w, j, NULL));
        if (k > 30)
            longest = fmax(longest, joint_value(w, j, NULL));
    }
    cr_log_info("rope thrown inward at %g px/s: nearest %.3f px (free flight %.3f), then longest %.3f px", v0, nearest,
                analytic, longest);
    cr_assert_lt(nearest, 95.0, "the rope did not push: nearest %g px", nearest);
    cr_assert(fabs(nearest - analytic) < 0.5, "it flew freely: nearest %g px, free flight %g px", nearest, analytic);
    cr_assert(longest > 99.5 && longest < 101.0, "the rope caught it at max_length: %g px", longest);
    cr_assert(fabsf(joint_value(w, j, NULL) - 100) < 0.5f);
    pp_world_destroy(w);
}

Test(joints2, a_rope_with_min_length_pushes_only_there)
{
    pp_world w = make_world(0, 0);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 260, 100, 0), 16, 16);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_DISTANCE);
    jd.body_b = box, jd.anchor_a = v2(200, 100), jd.anchor_b = v2(260, 100), jd.min_length = 40, jd.max_length = 80;
    pp_joint j = make_joint(w, &jd);
    /* Pushed in at 60 px/s it stops at min_length (a stop does not bounce); sent out at 60 px/s it travels
     * freely until max_length stops it. */
    PP_OK_OR_FAIL(pp_body_set_velocity(w, box, v2(-60, 0), 0));
    double lo = 1e9, hi = 0, slowest = 1e9;
    for (int k = 0; k < 60; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        lo = fmin(lo, joint_value(w, j, NULL));
    }
    PP_OK_OR_FAIL(pp_body_set_velocity(w, box, v2(60, 0), 0));
    for (int k = 0; k < 60; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        float speed;
        const double d = joint_value(w, j, &speed);
        hi = fmax(hi, d);
        if (d < 78)
            slowest = fmin(slowest, speed);
    }
    cr_log_info("rope 40..80 px: stopped at %.3f px inward, %.3f px outward, %.3f px/s between", lo, hi, slowest);
    cr_assert(lo > 39.5 && lo < 40.5 && hi > 79.5 && hi < 80.5, "it stopped at its lengths: %g..%g", lo, hi);
    cr_assert_gt(slowest, 59.9, "it moved freely between them: %g px/s", slowest);
    pp_world_destroy(w);
}

/* ---- wheel ---- */

/* A disc of radius 12 on a wheel joint to the world, its axis vertical (down is +): spring hz, damping ratio. */
static pp_body wheel_on_world(pp_world w, float hz, float ratio, pp_joint *j)
{
    pp_body disc = add_disc(w, body_def(PP_BODY_DYNAMIC, 200, 200, 0), 12);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_WHEEL);
    jd.body_b = disc, jd.anchor_a = v2(200, 200), jd.anchor_b = v2(200, 200), jd.axis = v2(0, 1);
    jd.spring_hertz = hz, jd.spring_damping_ratio = ratio;
    *j = make_joint(w, &jd);
    return disc;
}

Test(joints2, a_wheel_sags_by_weight_over_stiffness_and_bounces_at_its_frequency)
{
    const double hz = 2, omega = 2 * M_PI * hz, sag = G / (omega * omega); /* m·g/k with k = m·ω² */
    pp_world w = make_world(0, G);
    pp_joint j;
    pp_body disc = wheel_on_world(w, (float)hz, 0.7f, &j);
    step_n(w, DT, 240);
    const double rest = joint_value(w, j, NULL);
    cr_log_info("wheel 2 Hz: sag %.4f px, m·g/k %.4f px (%+.2f %%)", rest, sag, 100 * (rest / sag - 1));
    cr_assert(fabs(rest / sag - 1) < 0.03, "sag %g px, m·g/k %g px", rest, sag);
    cr_assert(fabsf(body_pos(w, disc).x - 200) < 0.05f, "it stays on its axis: x %g", body_pos(w, disc).x);
    pp_world_destroy(w);

    w = make_world(0, G); /* released undamped at its unsprung height: bounces about the sag */
    wheel_on_world(w, (float)hz, 0, &j);
    const oscillation o = measure(w, value_of, &j, sag, 300);
    cr_log_info("wheel 2 Hz: bounce period %.4f s, analytic %.4f s (%+.2f %%)", o.period, 1 / hz,
                100 * (o.period * hz - 1));
    cr_assert(fabs(o.period * hz - 1) < 0.03, "bounce period %g s", o.period);
    pp_world_destroy(w);
}

Test(joints2, a_wheel_spins_freely_its_motor_reaches_its_speed_and_its_limit_holds)
{
    pp_world w = make_world(0, G);
    pp_joint j;
    pp_body disc = wheel_on_world(w, 3, 1, &j);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, disc, v2(0, 0), 5));
    step_n(w, DT, 60);
    const float free_spin = spin(w, disc);
    cr_log_info("wheel spun at 5 rad/s: %.5f rad/s after 1 s", free_spin);
    cr_assert(fabsf(free_spin - 5) < 0.01f, "it spins freely: %g rad/s", free_spin);
    PP_OK_OR_FAIL(pp_joint_set_motor(w, j, 1, -8, 1e8f));
    step_n(w, DT, 60);
    cr_log_info("wheel motor -8 rad/s: %.5f rad/s", spin(w, disc));
    cr_assert(fabsf(spin(w, disc) + 8) < 0.05f, "the motor's speed: %g rad/s", spin(w, disc));
    /* A soft spring sags 980/π² ≈ 99 px; the limit stops it at 5. */
    PP_OK_OR_FAIL(pp_joint_set_spring(w, j, 0.5f, 0.2f, 0));
    PP_OK_OR_FAIL(pp_joint_set_limits(w, j, 1, -5, 5));
    float most = 0;
    for (int k = 0; k < 180; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        most = fmaxf(most, joint_value(w, j, NULL));
    }
    cr_log_info("wheel limit 5 px under a 99 px sag: most %.4f px, rests at %.4f px", most, joint_value(w, j, NULL));
    cr_assert(most < 5.5f && joint_value(w, j, NULL) > 4.5f, "the limit holds: most %g px", most);
    pp_world_destroy(w);
}

/* ---- motor joint ---- */

/* b's centre of mass in a's frame from a's centre of mass (uniform boxes: their positions), px. */
static pp_vec2 offset_in(pp_world w, pp_body a, pp_body b)
{
    const pp_vec2 pa = body_pos(w, a), pb = body_pos(w, b);
    const double c = cos(body_angle(w, a)), s = sin(body_angle(w, a)), dx = pb.x - pa.x, dy = pb.y - pa.y;
    return v2((float)(c * dx + s * dy), (float)(-s * dx + c * dy));
}

Test(joints2, a_motor_joint_brings_its_body_to_the_offsets)
{
    pp_world w = make_world(0, G);
    pp_body ground = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 300, 0), 60, 20);
    PP_OK_OR_FAIL(pp_body_set_gravity_scale(w, ground, 0));
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 20);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_MOTOR);
    cr_assert_float_eq(jd.correction_factor, 0.3f, 1e-7);
    jd.body_a = ground, jd.body_b = box, jd.linear_offset = v2(50, -120), jd.angular_offset = 0.5f;
    pp_joint j = make_joint(w, &jd);
    step_n(w, DT, 240);
    const pp_vec2 off = offset_in(w, ground, box); /* a turned too: read both */
    const double aa = body_angle(w, ground), ab = body_angle(w, box), lx = off.x, ly = off.y;
    cr_log_info("motor joint to (50, -120), 0.5 rad: (%.4f, %.4f), %.5f rad", lx, ly, ab - aa);
    cr_assert(hypot(lx - 50, ly + 120) < 0.5, "offset (%g, %g)", lx, ly);
    cr_assert(fabs(ab - aa - 0.5) < 0.01, "angle %g", ab - aa);
    PP_OK_OR_FAIL(pp_joint_set_offsets(w, j, v2(-40, -100), 0));
    step_n(w, DT, 240);
    cr_assert(dist(offset_in(w, ground, box), v2(-40, -100)) < 0.5, "offset (%g, %g)", offset_in(w, ground, box).x,
              offset_in(w, ground, box).y);
    cr_assert(fabsf(body_angle(w, box) - body_angle(w, ground)) < 0.01f);
    pp_world_destroy(w);
}

Test(joints2, a_motor_joint_never_pushes_past_max_force_or_max_torque)
{
    pp_world w = make_world(0, 0);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 20);
    float m, I;
    pp_vec2 c;
    PP_OK_OR_FAIL(pp_body_get_mass(w, box, &m, &c, &I));
    const double F = 50 * m, T = 2 * I; /* 50 px/s², 2 rad/s² at most */
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_MOTOR);
    jd.body_b = box, jd.linear_offset = v2(400, 400), jd.angular_offset = 3;
    jd.max_force = (float)F, jd.max_torque = (float)T;
    pp_joint j = make_joint(w, &jd);
    double fmax_seen = 0, tmax_seen = 0;
    for (int k = 0; k < 60; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        pp_vec2 f;
        float t;
        PP_OK_OR_FAIL(pp_joint_get_reaction(w, j, &f, &t));
        fmax_seen = fmax(fmax_seen, hypot(f.x, f.y)), tmax_seen = fmax(tmax_seen, fabs(t));
    }
    /* After 1 s at the cap from rest: v = a·t along the diagonal, ω = α·t. */
    const pp_vec2 v = body_vel(w, box);
    cr_log_info("motor joint capped at %g, %g: largest reaction %.2f (%+.2f %%), torque %.2f (%+.2f %%); speed %.3f px/s "
                "(a·t %.3f), spin %.4f rad/s (α·t 2)", F, T, fmax_seen, 100 * (fmax_seen / F - 1), tmax_seen,
                100 * (tmax_seen / T - 1), hypot(v.x, v.y), 50.0, spin(w, box));
    cr_assert(fmax_seen < 1.05 * F && fmax_seen > 0.95 * F, "force %g against max_force %g", fmax_seen, F);
    cr_assert(tmax_seen < 1.05 * T && tmax_seen > 0.95 * T, "torque %g against max_torque %g", tmax_seen, T);
    cr_assert(fabs(hypot(v.x, v.y) / 50 - 1) < 0.05, "pushed at max_force/m: %g px/s", hypot(v.x, v.y));
    cr_assert(fabs(spin(w, box) / 2 - 1) < 0.05, "turned at max_torque/I: %g rad/s", spin(w, box));
    pp_world_destroy(w);
}

/* ---- springs toward a target ---- */

Test(joints2, a_revolute_spring_oscillates_about_its_target)
{
    const double hz = 2, zeta = 0.1, target = 0.3, Td = 1 / (hz * sqrt(1 - zeta * zeta));
    pp_world w = make_world(0, 0);
    pp_body disc = add_disc(w, body_def(PP_BODY_DYNAMIC, 200, 200, 0), 20);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    jd.body_b = disc, jd.anchor_a = v2(200, 200);
    jd.spring_hertz = (float)hz, jd.spring_damping_ratio = (float)zeta, jd.target = (float)target;
    pp_joint j = make_joint(w, &jd);
    const oscillation o = measure(w, value_of, &j, target, 150);
    cr_log_info("revolute spring 2 Hz, ζ 0.1 about 0.3 rad: period %.4f s (analytic %.4f, %+.2f %%), ζ %.4f", o.period,
                Td, 100 * (o.period / Td - 1), o.ratio);
    cr_assert(fabs(o.period / Td - 1) < 0.03, "period %g s", o.period);
    cr_assert(fabs(o.ratio - zeta) < 0.1 * zeta, "damping ratio %g", o.ratio);
    step_n(w, DT, 240);
    cr_assert(fabsf(joint_value(w, j, NULL) - (float)target) < 0.005f, "it rests at its target");
    pp_world_destroy(w);
}

Test(joints2, a_prismatic_spring_oscillates_about_its_target)
{
    const double hz = 1.5, zeta = 0.05, target = 30, Td = 1 / (hz * sqrt(1 - zeta * zeta));
    pp_world w = make_world(0, 0);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200, 0), 20, 20);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_PRISMATIC);
    jd.body_b = box, jd.anchor_a = v2(200, 200), jd.anchor_b = v2(200, 200), jd.axis = v2(1, 1);
    jd.spring_hertz = (float)hz, jd.spring_damping_ratio = (float)zeta, jd.target = (float)target;
    pp_joint j = make_joint(w, &jd);
    const oscillation o = measure(w, value_of, &j, target, 200);
    cr_log_info("prismatic spring 1.5 Hz, ζ 0.05 about 30 px: period %.4f s (analytic %.4f, %+.2f %%), ζ %.4f",
                o.period, Td, 100 * (o.period / Td - 1), o.ratio);
    cr_assert(fabs(o.period / Td - 1) < 0.03, "period %g s", o.period);
    cr_assert(fabs(o.ratio - zeta) < 0.15 * zeta, "damping ratio %g", o.ratio);
    cr_assert(fabsf(body_pos(w, box).x - 200 - (body_pos(w, box).y - 200)) < 0.05f, "it stays on its axis");
    pp_world_destroy(w);
}

Test(joints2, a_distance_motor_changes_the_length_at_its_speed)
{
    pp_world w = make_world(0, G);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 250, 0), 16, 16);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_DISTANCE);
    jd.body_b = box, jd.anchor_a = v2(200, 100), jd.anchor_b = v2(200, 250);
    jd.enable_motor = 1, jd.motor_speed = -40, jd.max_motor_force = 1e8f; /* a winch reeling in */
    pp_joint j = make_joint(w, &jd);
    step_n(w, DT, 6);
    const float l0 = joint_value(w, j, NULL);
    step_n(w, DT, 60);
    float rate = 0;
    const float l1 = joint_value(w, j, &rate);
    cr_log_info("winch at -40 px/s: %.3f px in 1 s, rate %.4f px/s", l1 - l0, rate);
    cr_assert(fabsf((l1 - l0) + 40) < 0.8f, "length changed %g px in 1 s", l1 - l0);
    cr_assert(fabsf(rate + 40) < 0.4f, "rate %g", rate);
    PP_OK_OR_FAIL(pp_joint_set_motor(w, j, 0, 0, 0)); /* stopped: it holds there */
    step_n(w, DT, 60);
    cr_assert(fabsf(joint_value(w, j, NULL) - l1) < 0.5f, "held at %g, now %g", l1, joint_value(w, j, NULL));
    PP_OK_OR_FAIL(pp_joint_set_motor(w, j, 1, 30, 0.5f * G * 256)); /* too weak to hold the box: it pays out */
    step_n(w, DT, 30);
    cr_assert_gt(joint_value(w, j, NULL), l1 + 15 + 5);
    pp_world_destroy(w);
}

/* ---- soft welds ---- */

static float angle_of_body(pp_world w, const void *ctx) { return body_angle(w, *(const pp_body *)ctx); }

Test(joints2, a_soft_weld_bends_and_springs_back_at_its_angular_frequency)
{
    const double hz = 3;
    pp_world w = make_world(0, 0);
    pp_body plank = add_rect(w, body_def(PP_BODY_DYNAMIC, 150, 100, 0), 100, 10); /* from x 100 to 200 */
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_WELD);
    jd.body_b = plank, jd.anchor_a = v2(105, 100), jd.angular_hertz = (float)hz;
    make_joint(w, &jd);
    PP_OK_OR_FAIL(pp_body_apply_angular_impulse(w, plank, 5e5f));
    const oscillation o = measure(w, angle_of_body, &plank, 0, 120);
    cr_log_info("soft weld 3 Hz: period %.4f s (analytic %.4f, %+.2f %%)", o.period, 1 / hz, 100 * (o.period * hz - 1));
    cr_assert(fabs(o.period * hz - 1) < 0.03, "period %g s", o.period);
    pp_world_destroy(w);

    w = make_world(0, G); /* under its weight it bends by m·g·d / (I·ω²), I about the weld, and no farther */
    plank = add_rect(w, body_def(PP_BODY_DYNAMIC, 150, 100, 0), 100, 10);
    jd.body_b = plank, jd.angular_damping_ratio = 1;
    make_joint(w, &jd);
    float m, I;
    pp_vec2 c;
    PP_OK_OR_FAIL(pp_body_get_mass(w, plank, &m, &c, &I));
    const double d = 45, Ia = I + m * d * d, omega = 2 * M_PI * hz;
    const double bend = atan(m * G * d / (Ia * omega * omega)); /* small: sin θ ≈ θ within 0.1 % */
    step_n(w, DT, 120);
    cr_log_info("soft weld 3 Hz under its weight: bent %.5f rad, m·g·d/(I·ω²) %.5f rad", body_angle(w, plank), bend);
    cr_assert(fabs(body_angle(w, plank) / bend - 1) < 0.03, "bent %g rad", body_angle(w, plank));
    PP_OK_OR_FAIL(pp_world_set_gravity(w, v2(0, 0)));
    step_n(w, DT, 120);
    cr_assert(fabsf(body_angle(w, plank)) < 0.02f * (float)bend, "it springs back: %g rad", body_angle(w, plank));
    pp_world_destroy(w);
}

/* ---- break_torque ---- */

/* Whether a plank welded by one end, whose weight bends the weld by m·g·d, breaks at `share` of that. */
static bool plank_breaks(double share, double *moment)
{
    pp_world w = make_world(0, G);
    pp_body plank = add_rect(w, body_def(PP_BODY_DYNAMIC, 150, 100, 0), 100, 10);
    float m, I;
    pp_vec2 c;
    PP_OK_OR_FAIL(pp_body_get_mass(w, plank, &m, &c, &I));
    *moment = m * G * 45;
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_WELD);
    jd.body_b = plank, jd.anchor_a = v2(105, 100), jd.break_torque = (float)(share * *moment);
    pp_joint j = make_joint(w, &jd);
    bool broke = false;
    for (int k = 0; k < 60 && !broke; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        pp_event ev[8];
        int32_t n = 0;
        PP_OK_OR_FAIL(pp_world_get_events(w, ev, 8, &n));
        for (int32_t i = 0; i < n; i++)
            if (ev[i].type == PP_EVENT_JOINT_BROKEN && ev[i].joint.id == j.id && ev[i].other.id == plank.id)
                broke = true;
    }
    pp_joint_type t;
    if (broke)
        EXPECT_ERR(pp_joint_get_type(w, j, &t), PP_ERR_INVALID_HANDLE, "joint");
    pp_world_destroy(w);
    return broke;
}

Test(joints2, break_torque_breaks_above_and_not_below)
{
    double moment;
    cr_assert(!plank_breaks(1.1, &moment), "a weld that holds 1.1 × m·g·d holds");
    cr_assert(plank_breaks(0.9, &moment), "a weld that holds 0.9 × m·g·d (%g) breaks with PP_EVENT_JOINT_BROKEN", moment);
}

/* ---- misuse, versions, snapshots, scenes ---- */

Test(joints2, misuse_is_refused_with_its_status)
{
    pp_world w = make_world(0, G);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 20);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    jd.body_b = box, jd.anchor_a = v2(100, 100);
    pp_joint rev = make_joint(w, &jd);
    EXPECT_ERR(pp_joint_set_offsets(w, rev, v2(1, 2), 0), PP_ERR_INVALID_ARGUMENT, "only motor joints");
    EXPECT_ERR(pp_joint_set_spring(w, rev, -1, 0, 0), PP_ERR_INVALID_ARGUMENT, "hertz");
    EXPECT_ERR(pp_joint_set_spring(w, rev, NAN, 0, 0), PP_ERR_INVALID_ARGUMENT, "hertz");
    EXPECT_ERR(pp_joint_set_spring(w, rev, 1, NAN, 0), PP_ERR_INVALID_ARGUMENT, "damping_ratio");
    EXPECT_ERR(pp_joint_set_spring(w, rev, 1, 0, 4), PP_ERR_INVALID_ARGUMENT, "target");
    pp_joint_def md = pp_joint_def_default(PP_JOINT_MOTOR);
    md.body_b = box;
    pp_joint mot = make_joint(w, &md);
    EXPECT_ERR(pp_joint_set_spring(w, mot, 1, 0, 0), PP_ERR_INVALID_ARGUMENT, "spring");
    EXPECT_ERR(pp_joint_set_offsets(w, mot, v2(NAN, 0), 0), PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_joint_set_motor(w, mot, 1, 1, 1), PP_ERR_INVALID_ARGUMENT, "motors");
    PP_OK_OR_FAIL(pp_joint_destroy(w, mot));
    EXPECT_ERR(pp_joint_set_offsets(w, mot, v2(0, 0), 0), PP_ERR_INVALID_HANDLE, "stale");
    EXPECT_ERR(pp_joint_set_spring(w, mot, 1, 0, 0), PP_ERR_INVALID_HANDLE, "stale");
    pp_joint_def bad = md;
    bad.correction_factor = 1.5f;
    pp_joint j;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "correction_factor");
    bad = md, bad.max_torque = -1;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "max_torque");
    bad = md, bad.break_torque = NAN;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "break_torque");
    bad = md, bad.angular_offset = INFINITY;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "angular_offset");
    bad = pp_joint_def_default(PP_JOINT_WHEEL), bad.body_b = box, bad.axis = v2(0, 0);
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "axis");
    bad = pp_joint_def_default(PP_JOINT_WELD), bad.body_b = box, bad.angular_hertz = -2;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "angular_hertz");
    bad = jd, bad.type = (pp_joint_type)8;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_INVALID_ARGUMENT, "type");
    bad = jd, bad.struct_size -= 4;
    EXPECT_ERR(pp_joint_create(w, &bad, &j), PP_ERR_ABI, "struct_size");
    /* A caller built before these fields passes the old size: taken, the new fields at their defaults. */
    bad = jd, bad.struct_size = (uint32_t)offsetof(pp_joint_def, target), bad.target = NAN;
    PP_OK_OR_FAIL(pp_joint_create(w, &bad, &j));
    pp_world_destroy(w);
}

/* A world with every new kind: a car (two wheels under a chassis), a motor-held crate, a rope, a sprung door. */
static pp_world contraptions(pp_body *bodies)
{
    pp_world w = make_world(0, G);
    pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 400, 420, 0), 800, 40);
    pp_body chassis = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 340, 0), 80, 16);
    pp_body w1 = add_disc(w, body_def(PP_BODY_DYNAMIC, 175, 375, 0), 12);
    pp_body w2 = add_disc(w, body_def(PP_BODY_DYNAMIC, 225, 375, 0), 12);
    pp_joint_def wd = pp_joint_def_default(PP_JOINT_WHEEL);
    wd.body_a = chassis, wd.axis = v2(0, 1), wd.spring_hertz = 4, wd.spring_damping_ratio = 0.7f;
    wd.enable_motor = 1, wd.motor_speed = 6, wd.max_motor_force = 5e7f, wd.enable_limit = 1, wd.lower = -10, wd.upper = 10;
    wd.body_b = w1, wd.anchor_a = wd.anchor_b = v2(175, 375);
    make_joint(w, &wd);
    wd.body_b = w2, wd.anchor_a = wd.anchor_b = v2(225, 375);
    make_joint(w, &wd);
    pp_body crate = add_rect(w, body_def(PP_BODY_DYNAMIC, 500, 300, 0), 20, 20);
    pp_joint_def md = pp_joint_def_default(PP_JOINT_MOTOR);
    md.body_b = crate, md.linear_offset = v2(520, 250), md.angular_offset = 0.4f, md.max_force = 3e6f;
    make_joint(w, &md);
    pp_body bob = add_rect(w, body_def(PP_BODY_DYNAMIC, 650, 200, 0), 16, 16);
    pp_joint_def rd = pp_joint_def_default(PP_JOINT_DISTANCE);
    rd.body_b = bob, rd.anchor_a = v2(600, 150), rd.anchor_b = v2(650, 200), rd.max_length = 90;
    make_joint(w, &rd);
    pp_body door = add_rect(w, body_def(PP_BODY_DYNAMIC, 340, 200, 0), 60, 8);
    pp_joint_def dd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    dd.body_b = door, dd.anchor_a = v2(312, 200), dd.spring_hertz = 1, dd.spring_damping_ratio = 0.1f, dd.target = 0.5f;
    make_joint(w, &dd);
    pp_body beam = add_rect(w, body_def(PP_BODY_DYNAMIC, 150, 100, 0), 100, 10);
    pp_joint_def bd = pp_joint_def_default(PP_JOINT_WELD);
    bd.body_b = beam, bd.anchor_a = v2(105, 100), bd.angular_hertz = 2, bd.angular_damping_ratio = 0.2f;
    make_joint(w, &bd);
    pp_body sled = add_rect(w, body_def(PP_BODY_DYNAMIC, 700, 350, 0), 20, 10);
    pp_joint_def pd = pp_joint_def_default(PP_JOINT_PRISMATIC);
    pd.body_b = sled, pd.anchor_a = pd.anchor_b = v2(700, 350), pd.spring_hertz = 2, pd.target = -20;
    make_joint(w, &pd);
    (void)ground;
    bodies[0] = chassis, bodies[1] = w1, bodies[2] = crate, bodies[3] = bob, bodies[4] = door, bodies[5] = beam,
    bodies[6] = sled;
    return w;
}

Test(joints2, a_snapshot_of_every_new_joint_continues_exactly)
{
    pp_body b[7];
    pp_world w = contraptions(b);
    step_n(w, DT, 25);
    pp_world back = snapshot_round_trip(w);
    step_n(w, DT, 40);
    step_n(back, DT, 40);
    pp_body_state s1[16], s2[16];
    int32_t n1 = 0, n2 = 0;
    PP_OK_OR_FAIL(pp_world_get_body_states(w, s1, 16, &n1));
    PP_OK_OR_FAIL(pp_world_get_body_states(back, s2, 16, &n2));
    cr_assert_eq(n1, n2);
    for (int32_t i = 0; i < n1; i++)
        cr_assert(s1[i].position.x == s2[i].position.x && s1[i].position.y == s2[i].position.y &&
                      s1[i].angle == s2[i].angle && s1[i].angular_velocity == s2[i].angular_velocity,
                  "body %d: (%.9g, %.9g) against (%.9g, %.9g)", (int)i, s1[i].position.x, s1[i].position.y,
                  s2[i].position.x, s2[i].position.y);
    cr_assert_gt(body_pos(w, b[0]).x, 215.0f, "the car drove: %g", body_pos(w, b[0]).x);
    pp_world_destroy(w);
    pp_world_destroy(back);
}

Test(joints2, erasing_a_wheels_anchor_breaks_it)
{
    pp_body b[7];
    pp_world w = contraptions(b);
    step_n(w, DT, 5);
    pp_event ev[16];
    int32_t n = 0, changed = 0;
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 16, &n));
    PP_OK_OR_FAIL(pp_body_erase_circle(w, b[1], body_pos(w, b[1]), 4, &changed));
    cr_assert_gt(changed, 0);
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 16, &n));
    bool broke = false;
    for (int32_t i = 0; i < n; i++)
        broke |= ev[i].type == PP_EVENT_JOINT_BROKEN && ev[i].other.id == b[1].id;
    cr_assert(broke, "the wheel's joint broke with its axle");
    pp_world_destroy(w);
}

Test(joints2, a_scene_makes_wheels_and_motors)
{
    char dir[] = "/tmp/pp_joints2_XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    write_file(dir, "car.json",
               "{ \"bodies\": [ { \"name\": \"chassis\", \"box\": [80, 16], \"position\": [200, 200] },\n"
               "              { \"name\": \"wheel\", \"box\": [20, 20], \"position\": [180, 230] },\n"
               "              { \"name\": \"crate\", \"box\": [20, 20], \"position\": [400, 200] } ],\n"
               "  \"joints\": [ { \"type\": \"wheel\", \"body_a\": \"chassis\", \"body_b\": \"wheel\", \"anchor_a\": [180, 230],\n"
               "                \"anchor_b\": [180, 230], \"axis\": [0, 1], \"spring_hertz\": 3, \"break_torque\": 1e12 },\n"
               "              { \"type\": \"motor\", \"body_b\": \"crate\", \"linear_offset\": [420, 150],\n"
               "                \"angular_offset\": 0.25, \"max_torque\": 0, \"correction_factor\": 0.5 } ] }\n");
    char path[600];
    snprintf(path, sizeof path, "%s/car.json", dir);
    pp_world w = {0};
    PP_OK_OR_FAIL(pp_world_load_scene(path, &w));
    pp_joint js[2];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_joints(w, js, 2, &n));
    pp_joint_type t0, t1;
    PP_OK_OR_FAIL(pp_joint_get_type(w, js[0], &t0));
    PP_OK_OR_FAIL(pp_joint_get_type(w, js[1], &t1));
    cr_assert(n == 2 && t0 == PP_JOINT_WHEEL && t1 == PP_JOINT_MOTOR);
    pp_body bodies[3];
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 3, &n));
    step_n(w, DT, 120);
    cr_assert(dist(body_pos(w, bodies[2]), v2(420, 150)) < 0.5, "the scene's motor joint holds the crate");
    cr_assert(fabsf(body_angle(w, bodies[2]) - 0.25f) < 0.01f);
    pp_world_destroy(w);
    remove_tree(dir);
}
