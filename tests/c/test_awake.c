/* The awake set: a step visits only awake bodies and bodies changed since the last one. These scenes
 * check what it must not lose: a sleeping world stands still bit for bit, a touch wakes a sleeping stack,
 * a static body moved between steps is met where it now is, and a body destroyed while everything
 * sleeps ends its contacts. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "helpers.h"
#include "physpix.h"

PP_TEST_SUITE(awake);

#define DT (1.0f / 60.0f)
#define GROUND_TOP 500.0f

static int32_t awake_bodies(pp_world w)
{
    pp_step_stats s;
    PP_OK_OR_FAIL(pp_world_get_stats(w, &s));
    return s.awake_bodies;
}

/* Steps until no body is awake; fails after `most` steps. */
static void settle(pp_world w, int most)
{
    for (int k = 0; k < most; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        if (awake_bodies(w) == 0)
            return;
    }
    cr_assert_fail("still %d bodies awake after %d steps", (int)awake_bodies(w), most);
}

/* A ground and `stacks` stacks of four 16 px crates, 40 px apart from x = 100; crates[] gets them. */
static void crate_stacks(pp_world w, int stacks, pp_body *crates)
{
    add_rect(w, body_def(PP_BODY_STATIC, 500, GROUND_TOP + 20, 0), 1000, 40);
    for (int s = 0; s < stacks; s++)
        for (int k = 0; k < 4; k++)
            crates[4 * s + k] = add_rect(w, body_def(PP_BODY_DYNAMIC, 100.0f + 40.0f * s, GROUND_TOP - 8 - 16 * k, 0), 16, 16);
}

Test(awake, a_sleeping_world_stands_still_and_a_thrown_box_wakes_the_stack_it_lands_on)
{
    pp_world w = make_world(0, 980);
    pp_body crates[20];
    crate_stacks(w, 5, crates);
    settle(w, 600);
    pp_vec2 before[20];
    for (int i = 0; i < 20; i++)
        before[i] = body_pos(w, crates[i]);
    step_n(w, DT, 120);
    cr_assert_eq(awake_bodies(w), 0);
    for (int i = 0; i < 20; i++) {
        const pp_vec2 p = body_pos(w, crates[i]);
        cr_assert(p.x == before[i].x && p.y == before[i].y, "crate %d moved while asleep", i);
    }
    /* A box dropped onto the third stack (x = 180) wakes its four crates through their contacts, and only them. */
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 180, GROUND_TOP - 64 - 40, 0), 16, 16);
    int woke = 0;
    for (int k = 0; k < 60; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        woke = awake_bodies(w) > woke ? awake_bodies(w) : woke;
    }
    cr_assert_eq(woke, 5, "the box and the 4 crates under it wake, no more (got %d)", woke);
    settle(w, 600);
    /* It rests on the stack's top crate: its centre 16 px above that crate's, within the contact slop. */
    const pp_vec2 top = body_pos(w, crates[11]), p = body_pos(w, box);
    cr_assert(fabsf(p.y - (top.y - 16)) < 1.5f, "box at y %.2f, top crate at %.2f", p.y, top.y);
    for (int i = 0; i < 20; i++)
        if (i < 8 || i >= 12)
            cr_assert(body_pos(w, crates[i]).x == before[i].x, "crate %d of another stack moved", i);
    pp_world_destroy(w);
}

Test(awake, a_static_platform_moved_between_steps_catches_a_falling_box)
{
    pp_world w = make_world(0, 980);
    pp_body crates[8];
    crate_stacks(w, 2, crates);
    settle(w, 600); /* the static bodies' boxes are left as they were: only the moved one is refreshed */
    pp_body platform = add_rect(w, body_def(PP_BODY_STATIC, 900, 100, 0), 100, 20);
    step_n(w, DT, 2);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 600, 100, 0), 16, 16);
    step_n(w, DT, 10); /* falling: 49 px by now */
    PP_OK_OR_FAIL(pp_body_set_transform(w, platform, v2(600, 300), 0));
    step_n(w, DT, 120);
    const pp_vec2 p = body_pos(w, box);
    /* The platform's top is at y = 290; the box rests on it, not on the ground at 500. */
    cr_assert(fabsf(p.y - (290 - 8)) < 1.5f, "box at y %.2f: the platform was not where it was moved to", p.y);
    pp_world_destroy(w);
}

/* A world with contact events and one stack of four crates (crates[0] at the bottom). */
static pp_world events_stack(pp_body *crates)
{
    pp_world_def d = pp_world_def_default();
    d.contact_events = 1;
    pp_world w = make_world_def(&d);
    crate_stacks(w, 1, crates);
    return w;
}

Test(awake, destroying_a_body_in_a_sleeping_world_ends_its_contact)
{
    pp_body crates[4];
    pp_world w = events_stack(crates);
    settle(w, 600);
    pp_event ev[16];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 16, &n)); /* the four BEGINs */
    cr_assert_eq(n, 4);
    /* The top crate touches only the one under it: destroying it wakes nothing, yet the pair must end. */
    PP_OK_OR_FAIL(pp_body_destroy(w, crates[3]));
    step_n(w, DT, 1);
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 16, &n));
    cr_assert_eq(n, 1, "one END, got %d events", (int)n);
    cr_assert_eq(ev[0].type, PP_EVENT_CONTACT_END);
    cr_assert(ev[0].body.id == crates[3].id || ev[0].other.id == crates[3].id, "the END names the destroyed crate");
    cr_assert_eq(awake_bodies(w), 0);
    pp_world_destroy(w);
}

/* Steps until none of the crates is awake (other bodies may be), then a few more; fails after `most` steps. */
static void settle_crates(pp_world w, const pp_body *crates, int n, int most)
{
    for (int k = 0; k < most; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        int32_t awake = 0, any = 0;
        for (int i = 0; i < n; i++) {
            PP_OK_OR_FAIL(pp_body_is_awake(w, crates[i], &awake));
            any |= awake;
        }
        if (!any) {
            step_n(w, DT, 3);
            return;
        }
    }
    cr_assert_fail("crates still awake after %d steps", most);
}

/* A pair whose bodies sleep rests outside the substeps' walk (a kinematic body far off keeps the walk
 * going); woken, it is the same pair again: a nudge that keeps the crate on the stack begins nothing new, a
 * throw that lifts it off ends the pair once, and so does a move between steps that leaves the pair apart
 * before any substep could find it. */
Test(awake, a_resting_pair_woken_is_the_same_pair_and_ends_when_parted)
{
    pp_body crates[4];
    pp_world w = events_stack(crates);
    pp_body_def k = body_def(PP_BODY_KINEMATIC, 900, 100, 0);
    k.angular_velocity = 1.0f;
    add_rect(w, k, 16, 16);
    settle_crates(w, crates, 4, 600);
    pp_event ev[16];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 16, &n));
    cr_assert_eq(n, 4, "the four BEGINs, got %d events", (int)n);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, crates[3], v2(3, 0), 0)); /* the top crate slides a little */
    step_n(w, DT, 10);
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 16, &n));
    cr_assert_eq(n, 0, "a nudged crate still touches the one under it: %d events", (int)n);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, crates[3], v2(0, -400), 0)); /* thrown up, off the stack */
    step_n(w, DT, 10);
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 16, &n));
    cr_assert_eq(n, 1, "one END as the thrown crate leaves, got %d events", (int)n);
    cr_assert_eq(ev[0].type, PP_EVENT_CONTACT_END);
    cr_assert(ev[0].body.id == crates[3].id || ev[0].other.id == crates[3].id, "the END names the thrown crate");
    settle_crates(w, crates, 4, 600); /* it lands back on the stack (and may bounce); the pairs rest again */
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 16, &n));
    cr_assert(n >= 1 && n % 2 == 1 && ev[n - 1].type == PP_EVENT_CONTACT_BEGIN, "it lands: %d events", (int)n);
    PP_OK_OR_FAIL(pp_body_set_transform(w, crates[3], v2(700, GROUND_TOP - 7), 0)); /* moved away, 1 px into the ground */
    step_n(w, DT, 1);
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 16, &n));
    int ends = 0, begins = 0;
    for (int i = 0; i < n; i++)
        ends += ev[i].type == PP_EVENT_CONTACT_END, begins += ev[i].type == PP_EVENT_CONTACT_BEGIN;
    cr_assert_eq(ends, 1, "the moved crate's pair with the stack ends: %d ENDs", ends);
    cr_assert_eq(begins, 1, "and it begins one with the ground: %d BEGINs", begins);
    pp_world_destroy(w);
}

/* Box queries find awake bodies through an index of them by x, built once a substep: a body moved, painted
 * or put to sleep between steps must still be met where it now is, by an erase and by the wake an edit
 * spreads. 16×16 boxes, 256 px each. */
Test(awake, the_box_queries_meet_awake_bodies_where_they_are_now)
{
    pp_world_def d = pp_world_def_default();
    d.gravity = (pp_vec2){0, 0};
    pp_world w = make_world_def(&d);
    pp_body mover = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 16, 16);
    pp_body others[20];
    for (int i = 0; i < 20; i++) /* awake neighbours along x, so the index has more than one entry */
        others[i] = add_rect(w, body_def(PP_BODY_DYNAMIC, 300 + 40.0f * i, 100, 0), 16, 16);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, mover, (pp_vec2){30, 0}, 0));
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    int32_t changed = -1;
    /* A query now builds the index with the mover near x 100. */
    PP_OK_OR_FAIL(pp_world_erase_circle(w, (pp_vec2){2000, 2000}, 4, &changed));
    cr_assert_eq(changed, 0);
    /* Teleported between steps: erased where it now is, not where the index saw it. */
    PP_OK_OR_FAIL(pp_body_set_transform(w, mover, (pp_vec2){1200, 600}, 0));
    PP_OK_OR_FAIL(pp_world_erase_circle(w, (pp_vec2){100.5f, 100}, 3, &changed));
    cr_assert_eq(changed, 0, "the erase at the mover's old place took %d of its pixels", changed);
    PP_OK_OR_FAIL(pp_world_erase_circle(w, (pp_vec2){1200, 600}, 3, &changed));
    cr_assert_gt(changed, 0, "the erase at the mover's new place missed it");
    /* Put to sleep between steps (listed still, in no tree leaf): an erase finds it and its edit wakes it. */
    PP_OK_OR_FAIL(pp_body_set_awake(w, others[3], 0));
    int32_t awake = 1;
    PP_OK_OR_FAIL(pp_body_is_awake(w, others[3], &awake));
    cr_assert_eq(awake, 0);
    PP_OK_OR_FAIL(pp_world_erase_circle(w, (pp_vec2){420 + 7, 100}, 2, &changed));
    cr_assert_gt(changed, 0, "the erase missed the sleeper's edge");
    PP_OK_OR_FAIL(pp_body_is_awake(w, others[3], &awake));
    cr_assert_eq(awake, 1, "an edit of a sleeper's edge did not wake it");
    pp_world_destroy(w);
}
