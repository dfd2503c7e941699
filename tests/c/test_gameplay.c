/* Gameplay features of the step: contact events with approach speeds, contact impulses, sensors and
 * one-way platforms, each checked against the motion it should (or should not) cause. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "helpers.h"
#include "physpix.h"

PP_TEST_SUITE(gameplay);

#define DT (1.0f / 60.0f)
#define G 980.0f

/* Read every pending event; returns how many. */
static int read_events(pp_world w, pp_event *out, int cap)
{
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_events(w, out, cap, &n));
    cr_assert_leq(n, cap);
    return n;
}

static pp_world events_world(void)
{
    pp_world_def d = pp_world_def_default();
    d.contact_events = 1;
    d.allow_sleep = 0;
    return make_world_def(&d);
}

/* A ball bounces on the ground until it rests: every BEGIN is followed by one END before the next BEGIN,
 * the last BEGIN stays open (the ball rests), and each impact's approach speed is the speed the ball
 * fell at just before it, within 5 %. */
Test(gameplay, contact_events_pair_up_over_a_bouncing_ball)
{
    pp_world w = events_world();
    pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 300, 520, 0), 600, 40);
    pp_body_def bd = body_def(PP_BODY_DYNAMIC, 300, 150, 0);
    bd.restitution = 0.7f;
    pp_body ball = add_disc(w, bd, 12);
    bool touching = false;
    int begins = 0, ends = 0, checked = 0;
    float vy_before = 0;
    for (int s = 0; s < 360; s++) {
        vy_before = body_vel(w, ball).y;
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        pp_event ev[16];
        const int n = read_events(w, ev, 16);
        for (int i = 0; i < n; i++) {
            cr_assert_eq(ev[i].body.id, ground.id, "the ground is in the lower slot, so it is the event's body");
            cr_assert_eq(ev[i].other.id, ball.id);
            if (ev[i].type == PP_EVENT_CONTACT_BEGIN) {
                cr_assert(!touching, "step %d: a BEGIN while the pair already touches", s);
                touching = true, begins++;
                cr_assert_float_eq(ev[i].normal.y, -1.0f, 0.02f, "normal from the ground up to the ball");
                /* The impact happened within this step: the ball fell at vy_before plus up to g·dt. */
                const float expect = vy_before + 0.5f * G * DT;
                if (expect > 150) { /* slower impacts are no longer bounces (bounce_threshold) */
                    cr_assert_float_eq(ev[i].approach_speed, expect, 0.05f * expect,
                                       "impact %d: approach %.1f px/s, fell at %.1f px/s", begins, ev[i].approach_speed,
                                       expect);
                    checked++;
                }
                cr_assert_float_eq(ev[i].point.y, 500.0f, 1.5f, "the contact is on the ground's top");
            } else {
                cr_assert_eq(ev[i].type, PP_EVENT_CONTACT_END, "only contact events here");
                cr_assert(touching, "step %d: an END with no BEGIN", s);
                touching = false, ends++;
            }
        }
    }
    cr_assert(touching, "the ball ends at rest on the ground");
    cr_assert_eq(begins, ends + 1);
    cr_assert_geq(checked, 3, "at least three real bounces, got %d", checked);
    cr_assert_float_eq(body_pos(w, ball).y, 500.0f - 12.0f, 1.5f);
    pp_world_destroy(w);
}

/* Events are opt-in: a world without contact_events queues none. */
Test(gameplay, contact_events_are_off_by_default)
{
    pp_world w = make_world(0, G);
    add_rect(w, body_def(PP_BODY_STATIC, 300, 520, 0), 600, 40);
    add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 460, 0), 40, 40);
    step_n(w, DT, 120);
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_get_events(w, NULL, 0, &n));
    cr_assert_eq(n, 0);
    pp_world_destroy(w);
}

/* Switched on in a running world, events begin the pairs already touching; off, pairs end silently. */
Test(gameplay, contact_events_switch_on_and_off)
{
    pp_world_def d = pp_world_def_default();
    d.allow_sleep = 0;
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 300, 520, 0), 600, 40);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 480, 0), 40, 40);
    step_n(w, DT, 30);
    pp_event ev[8];
    cr_assert_eq(read_events(w, ev, 8), 0);
    PP_OK_OR_FAIL(pp_world_set_contact_events(w, 1));
    pp_world_def got;
    PP_OK_OR_FAIL(pp_world_get_def(w, &got));
    cr_assert_eq(got.contact_events, 1);
    step_n(w, DT, 1);
    cr_assert_eq(read_events(w, ev, 8), 1);
    cr_assert(ev[0].type == PP_EVENT_CONTACT_BEGIN && ev[0].other.id == box.id);
    PP_OK_OR_FAIL(pp_world_set_contact_events(w, 0));
    PP_OK_OR_FAIL(pp_body_destroy(w, box));
    step_n(w, DT, 2);
    cr_assert_eq(read_events(w, ev, 8), 0, "no END once events are off");
    PP_OK_OR_FAIL(pp_world_destroy(w));
    EXPECT_ERR(pp_world_set_contact_events(w, 1), PP_ERR_INVALID_HANDLE, "world");
}

/* Destroying a body ends its contacts. */
Test(gameplay, destroying_a_body_ends_its_contact)
{
    pp_world w = events_world();
    add_rect(w, body_def(PP_BODY_STATIC, 300, 520, 0), 600, 40);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 480, 0), 40, 40);
    step_n(w, DT, 30);
    pp_event ev[8];
    cr_assert_eq(read_events(w, ev, 8), 1);
    cr_assert_eq(ev[0].type, PP_EVENT_CONTACT_BEGIN);
    PP_OK_OR_FAIL(pp_body_destroy(w, box));
    step_n(w, DT, 1);
    cr_assert_eq(read_events(w, ev, 8), 1);
    cr_assert_eq(ev[0].type, PP_EVENT_CONTACT_END);
    cr_assert_eq(ev[0].other.id, box.id, "the END names the destroyed body");
    pp_world_destroy(w);
}

/* A resting box's contacts carry its weight: their impulses sum to m·g·h per substep, within 2 %. */
Test(gameplay, impulses_on_a_resting_box_sum_to_its_weight)
{
    for (int sub = 1; sub <= 4; sub *= 4) {
        pp_world_def d = pp_world_def_default();
        d.allow_sleep = 0;
        d.substeps = sub;
        pp_world w = make_world_def(&d);
        add_rect(w, body_def(PP_BODY_STATIC, 300, 520, 0), 600, 40);
        pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 479, 0), 40, 40);
        step_n(w, DT, 120);
        float mass = 0;
        PP_OK_OR_FAIL(pp_body_get_mass(w, box, &mass, NULL, NULL));
        pp_contact c[8];
        int32_t n = 0;
        PP_OK_OR_FAIL(pp_world_get_contacts(w, c, 8, &n));
        cr_assert_geq(n, 1);
        double sum = 0;
        for (int i = 0; i < n; i++) {
            cr_assert_geq(c[i].normal_impulse, 0.0f);
            sum += c[i].normal_impulse;
        }
        const double weight_h = mass * G * DT / sub;
        cr_log_info("substeps %d: impulses %.3f against m·g·h %.3f (%+.3f %%)", sub, sum, weight_h,
                    100 * (sum / weight_h - 1));
        cr_assert_float_eq(sum, weight_h, 0.02 * weight_h, "substeps %d: %g against %g", sub, sum, weight_h);
        /* A query runs no solver: its impulse is zero. */
        pp_body bodies[2];
        int32_t nb = 0;
        PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 2, &nb));
        PP_OK_OR_FAIL(pp_world_collide(w, bodies[0], bodies[1], c, 8, &n));
        for (int i = 0; i < n; i++)
            cr_assert_eq(c[i].normal_impulse, 0.0f);
        pp_world_destroy(w);
    }
}

/* A stack's lower contacts carry more: the bottom box's impulses are twice the top box's. Summed over a
 * second of frames: a resting contact sits at contact_slop, and a substep that pushes its creep back out
 * carries that push too. */
Test(gameplay, impulses_grow_down_a_stack)
{
    pp_world_def d = pp_world_def_default();
    d.allow_sleep = 0;
    pp_world w = make_world_def(&d);
    pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 300, 520, 0), 600, 40);
    pp_body low = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 479, 0), 40, 40);
    pp_body high = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 438, 0), 40, 40);
    step_n(w, DT, 120);
    double on_ground = 0, between = 0;
    for (int f = 0; f < 60; f++) {
        step_n(w, DT, 1);
        pp_contact c[16];
        int32_t n = 0;
        PP_OK_OR_FAIL(pp_world_get_contacts(w, c, 16, &n));
        for (int i = 0; i < n; i++) {
            if (c[i].a.id == ground.id && c[i].b.id == low.id)
                on_ground += c[i].normal_impulse;
            if (c[i].a.id == low.id && c[i].b.id == high.id)
                between += c[i].normal_impulse;
        }
    }
    cr_assert_gt(between, 0);
    cr_assert_float_eq(on_ground / between, 2.0, 0.02, "ground %g, between %g", on_ground, between);
    pp_world_destroy(w);
}

/* A ball falls through a static sensor: SENSOR_BEGIN then SENSOR_END name the sensor as `body`, and
 * the ball moves exactly as in a world without the sensor. */
Test(gameplay, a_sensor_reports_an_overlap_and_never_pushes)
{
    pp_world w = make_world(0, G), plain = make_world(0, G);
    pp_body_def bd = body_def(PP_BODY_DYNAMIC, 300, 100, 0);
    pp_body ball = add_disc(w, bd, 12), ball2 = add_disc(plain, bd, 12); /* the ball takes the lower slot */
    pp_body_def sd = body_def(PP_BODY_STATIC, 300, 300, 0);
    sd.is_sensor = 1;
    pp_body sensor = add_rect(w, sd, 200, 60);
    int begin_step = -1, end_step = -1;
    float vy_before = 0;
    for (int s = 0; s < 60; s++) {
        vy_before = body_vel(w, ball).y;
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        PP_OK_OR_FAIL(pp_world_step(plain, DT));
        const pp_vec2 p = body_pos(w, ball), q = body_pos(plain, ball2);
        cr_assert(p.x == q.x && p.y == q.y, "step %d: the sensor moved the ball (%g vs %g)", s, p.y, q.y);
        pp_event ev[4];
        const int n = read_events(w, ev, 4);
        for (int i = 0; i < n; i++) {
            cr_assert_eq(ev[i].body.id, sensor.id, "the sensor is the event's body");
            cr_assert_eq(ev[i].other.id, ball.id);
            if (ev[i].type == PP_EVENT_SENSOR_BEGIN) {
                cr_assert_eq(begin_step, -1);
                begin_step = s;
                const float expect = vy_before + 0.5f * G * DT;
                cr_assert_float_eq(ev[i].approach_speed, expect, 0.05f * expect);
                cr_assert_float_eq(ev[i].normal.y, -1.0f, 0.05f, "from the sensor up to the ball above it");
            } else {
                cr_assert_eq(ev[i].type, PP_EVENT_SENSOR_END);
                cr_assert_eq(end_step, -1);
                end_step = s;
            }
        }
        int32_t nc = 0;
        PP_OK_OR_FAIL(pp_world_get_contacts(w, NULL, 0, &nc));
        cr_assert_eq(nc, 0, "a sensor makes no contacts");
    }
    cr_assert_geq(begin_step, 0, "the ball entered the sensor");
    cr_assert_gt(end_step, begin_step, "and left it");
    pp_world_destroy(w);
    pp_world_destroy(plain);
}

/* A kinematic sensor swept over resting bodies reports each; sleeping inside it is no END. */
Test(gameplay, a_kinematic_sensor_finds_sleeping_bodies_and_keeps_them)
{
    pp_world w = make_world(0, G);
    add_rect(w, body_def(PP_BODY_STATIC, 300, 520, 0), 800, 40);
    pp_body boxes[3];
    for (int i = 0; i < 3; i++)
        boxes[i] = add_rect(w, body_def(PP_BODY_DYNAMIC, 150 + 150 * i, 480, 0), 30, 30);
    step_n(w, DT, 90); /* all asleep */
    int32_t awake = 1;
    PP_OK_OR_FAIL(pp_body_is_awake(w, boxes[0], &awake));
    cr_assert_eq(awake, 0);
    pp_body_def sd = body_def(PP_BODY_KINEMATIC, 0, 480, 0);
    sd.is_sensor = 1;
    sd.linear_velocity = v2(300, 0);
    pp_body sensor = add_rect(w, sd, 60, 60);
    int begins[3] = {0}, ends[3] = {0};
    for (int s = 0; s < 120; s++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        pp_event ev[8];
        const int n = read_events(w, ev, 8);
        for (int i = 0; i < n; i++)
            for (int k = 0; k < 3; k++)
                if (ev[i].other.id == boxes[k].id) {
                    cr_assert_eq(ev[i].body.id, sensor.id);
                    begins[k] += ev[i].type == PP_EVENT_SENSOR_BEGIN;
                    ends[k] += ev[i].type == PP_EVENT_SENSOR_END;
                }
    }
    for (int k = 0; k < 3; k++) {
        cr_assert_eq(begins[k], 1, "box %d: %d begins", k, begins[k]);
        cr_assert_eq(ends[k], 1, "box %d: %d ends", k, ends[k]);
        cr_assert_float_eq(body_pos(w, boxes[k]).y, 485.0f, 1.0f, "the sensor did not push box %d", k);
    }
    pp_world_destroy(w);
}

/* A box thrown up from under a one-way platform passes through it, then lands and stays on it, whichever
 * of the two is the pair's first body; the same platform without one_way stops it underneath. */
Test(gameplay, a_body_jumps_up_through_a_one_way_platform_and_lands_on_it)
{
    for (int run = 0; run < 3; run++) {
        const int one_way = run > 0, box_first = run == 2;
        pp_world_def wd = pp_world_def_default();
        wd.contact_events = 1;
        pp_world w = make_world_def(&wd);
        pp_body_def pd = body_def(PP_BODY_STATIC, 300, 300, 0);
        pd.one_way = (uint32_t)one_way;
        pp_body_def bd = body_def(PP_BODY_DYNAMIC, 300, 420, 0);
        bd.linear_velocity = v2(0, -800); /* rises v²/2g = 327 px: its bottom clears the platform */
        pp_body box = {0};
        if (box_first)
            box = add_rect(w, bd, 24, 24);
        add_rect(w, pd, 240, 12);
        if (!box_first)
            box = add_rect(w, bd, 24, 24);
        float highest = 1e9f;
        for (int s = 0; s < 240; s++) {
            PP_OK_OR_FAIL(pp_world_step(w, DT));
            highest = fminf(highest, body_pos(w, box).y);
        }
        const pp_vec2 p = body_pos(w, box);
        if (one_way) {
            cr_assert_lt(highest, 294.0f - 12.0f, "it rose above the platform (highest %g)", highest);
            cr_assert_float_eq(p.y, 294.0f - 12.0f, 1.5f, "it rests on the platform's top, y %g", p.y);
            cr_assert_float_eq(body_vel(w, box).y, 0.0f, 5.0f);
            pp_event ev[16];
            const int n = read_events(w, ev, 16);
            int begins = 0;
            for (int i = 0; i < n; i++)
                begins += ev[i].type == PP_EVENT_CONTACT_BEGIN;
            cr_assert_eq(begins, 1, "one contact: the landing (passing through is no contact)");
        } else {
            cr_assert_gt(highest, 306.0f, "a plain platform stops it underneath (highest %g)", highest);
        }
        pp_world_destroy(w);
    }
}

/* The direction is the platform's own: turned upside down (direction +y in a platform rotated by π),
 * it is a floor seen from above; pointing down, a falling body goes through. */
Test(gameplay, a_one_way_platform_follows_its_direction_and_rotation)
{
    for (int variant = 0; variant < 2; variant++) {
        pp_world w = make_world(0, G);
        pp_body_def pd = body_def(PP_BODY_STATIC, 300, 300, variant == 0 ? 0.0f : (float)M_PI);
        pd.one_way = 1;
        pd.one_way_direction = v2(0, 1); /* down in bitmap axes */
        add_rect(w, pd, 240, 12);
        pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 200, 0), 24, 24);
        step_n(w, DT, 120);
        const float y = body_pos(w, box).y;
        if (variant == 0)
            cr_assert_gt(y, 330.0f, "direction down: the box falls through (y %g)", y);
        else
            cr_assert_float_eq(y, 294.0f - 12.0f, 1.5f, "rotated by π the direction is up: it lands (y %g)", y);
        pp_world_destroy(w);
    }
}

/* A body standing on a rising kinematic one-way platform (a lift) stays on it, carried up. */
Test(gameplay, a_one_way_lift_carries_a_body_standing_on_it)
{
    pp_world w = make_world(0, G);
    pp_body_def pd = body_def(PP_BODY_KINEMATIC, 300, 300, 0);
    pd.one_way = 1;
    pd.linear_velocity = v2(0, -60);
    pp_body lift = add_rect(w, pd, 120, 12);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 250, 0), 24, 24);
    step_n(w, DT, 180);
    const float top = body_pos(w, lift).y - 6.0f;
    cr_assert_float_eq(body_pos(w, lift).y, 300.0f - 180.0f, 0.5f, "the lift rose 3 s × 60 px/s");
    cr_assert_float_eq(body_pos(w, box).y, top - 12.0f, 1.5f, "the box rides on the lift's top (y %g, top %g)",
                       body_pos(w, box).y, top);
    cr_assert_float_eq(body_vel(w, box).y, -60.0f, 3.0f, "at the lift's speed");
    pp_world_destroy(w);
}

/* A fast body falling onto a one-way platform is stopped by continuous collision, not tunnelled. */
Test(gameplay, a_fast_body_lands_on_a_one_way_platform)
{
    pp_world w = make_world(0, G);
    pp_body_def pd = body_def(PP_BODY_STATIC, 300, 300, 0);
    pd.one_way = 1;
    add_rect(w, pd, 240, 8);
    pp_body_def bd = body_def(PP_BODY_DYNAMIC, 300, 100, 0);
    bd.linear_velocity = v2(0, 3000); /* 12 px a substep: more than the platform is thick */
    pp_body box = add_rect(w, bd, 16, 16);
    step_n(w, DT, 120);
    cr_assert_float_eq(body_pos(w, box).y, 296.0f - 8.0f, 1.5f);
    pp_world_destroy(w);
}

/* The touching pairs are in a snapshot: a box midway through a one-way platform keeps passing after a
 * load, and the loaded world's events and motion equal the original's. */
Test(gameplay, snapshots_keep_touching_pairs)
{
    pp_world_def wd = pp_world_def_default();
    wd.contact_events = 1;
    pp_world w = make_world_def(&wd);
    pp_body_def pd = body_def(PP_BODY_STATIC, 300, 300, 0);
    pd.one_way = 1;
    const pp_body platform = add_rect(w, pd, 240, 12);
    pp_body_def bd = body_def(PP_BODY_DYNAMIC, 300, 420, 0);
    bd.linear_velocity = v2(0, -800);
    pp_body box = add_rect(w, bd, 24, 24);
    const pp_body original[2] = {platform, box};
    step_n(w, DT, 10); /* the box is inside the platform now */
    cr_assert_lt(body_pos(w, box).y, 320.0f);
    cr_assert_gt(body_pos(w, box).y, 280.0f);
    char dir[] = "/tmp/pp_gameplay_XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    char snap[256];
    snprintf(snap, sizeof snap, "%s/snap", dir);
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));
    pp_world l = {0};
    PP_OK_OR_FAIL(pp_world_load_snapshot(snap, &l));
    pp_body loaded[2]; /* the platform and the box, in the same slots; their handles name l */
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(l, loaded, 2, &n));
    cr_assert_eq(n, 2);
    for (int s = 0; s < 200; s++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        PP_OK_OR_FAIL(pp_world_step(l, DT));
        const pp_vec2 p = body_pos(w, box), q = body_pos(l, loaded[1]);
        cr_assert(p.x == q.x && p.y == q.y, "step %d: %g,%g vs %g,%g", s, p.x, p.y, q.x, q.y);
        pp_event a[8], b[8];
        const int na = read_events(w, a, 8), nb = read_events(l, b, 8);
        cr_assert_eq(na, nb);
        for (int i = 0; i < nb; i++) /* l's handles as w's */
            for (int k = 0; k < 2; k++) {
                b[i].body = b[i].body.id == loaded[k].id ? original[k] : b[i].body;
                b[i].other = b[i].other.id == loaded[k].id ? original[k] : b[i].other;
            }
        cr_assert(memcmp(a, b, (size_t)na * sizeof *a) == 0, "step %d: the events differ", s);
    }
    cr_assert_float_eq(body_pos(l, loaded[1]).y, 294.0f - 12.0f, 1.5f, "it landed on the platform in both");
    pp_world_destroy(w);
    pp_world_destroy(l);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_assert_eq(system(cmd), 0);
}

/* Misuse of the new def fields. */
Test(gameplay, a_one_way_direction_must_be_finite_and_not_zero)
{
    pp_world w = make_world(0, G);
    uint8_t m[4] = {1, 1, 1, 1};
    pp_body_def d = body_def(PP_BODY_STATIC, 0, 0, 0);
    d.width = d.height = 2, d.mask = m, d.one_way = 1;
    pp_body b = {0};
    d.one_way_direction = v2(0, 0);
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "one_way_direction");
    d.one_way_direction = v2(NAN, 1);
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "one_way_direction");
    cr_assert_eq(b.id, 0);
    d.one_way = 0; /* ignored when not one-way */
    PP_OK_OR_FAIL(pp_body_create(w, &d, &b));
    pp_world_destroy(w);
}
