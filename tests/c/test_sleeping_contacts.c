/* Sleep keeps contacts: an island that falls asleep keeps its pairs in the contact table with the manifold of
 * their last solve, pp_world_get_contacts lists them, sleeping ends nothing and waking while touching begins
 * nothing; an edit that takes the ground away ends the pair once. */
#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "helpers.h"
#include "physpix.h"

PP_TEST_SUITE(sleeping_contacts);

#define DT (1.0f / 60.0f)
#define G 980.0f
#define GROUND_TOP 500.0f
#define MAX_CONTACTS 256

/* Steps until no body is awake; fails after `most` steps. */
static void settle(pp_world w, int most)
{
    for (int k = 0; k < most; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        pp_step_stats s;
        PP_OK_OR_FAIL(pp_world_get_stats(w, &s));
        if (s.awake_bodies == 0)
            return;
    }
    cr_assert_fail("bodies still awake after %d steps", most);
}

static int32_t contacts_of(pp_world w, pp_contact *out)
{
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_contacts(w, out, MAX_CONTACTS, &n));
    cr_assert_leq(n, MAX_CONTACTS);
    return n;
}

/* Distinct body pairs among n contacts (a pair's points come together). */
static int distinct_pairs(const pp_contact *c, int32_t n)
{
    int pairs = 0;
    for (int32_t i = 0; i < n; i++) {
        int seen = 0;
        for (int32_t j = 0; j < i && !seen; j++)
            seen = c[j].a.id == c[i].a.id && c[j].b.id == c[i].b.id;
        pairs += !seen;
    }
    return pairs;
}

static int read_events(pp_world w, pp_event *ev, int32_t cap)
{
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, cap, &n));
    return n;
}

static int count_events(const pp_event *ev, int n, pp_event_type type)
{
    int k = 0;
    for (int i = 0; i < n; i++)
        k += ev[i].type == type;
    return k;
}

/* A box asleep on the ground still lists its contact, carrying its weight: impulses summing to m·g·h. */
Test(sleeping_contacts, a_box_asleep_lists_its_contact_carrying_its_weight)
{
    pp_world_def d = pp_world_def_default();
    pp_world w = make_world_def(&d);
    pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 300, GROUND_TOP + 20, 0), 600, 40);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, GROUND_TOP - 20, 0), 40, 40);
    settle(w, 600);
    step_n(w, DT, 5); /* asleep for several steps: no substep has visited the pair since */
    int32_t awake = 1;
    PP_OK_OR_FAIL(pp_body_is_awake(w, box, &awake));
    cr_assert_eq(awake, 0, "the box sleeps");
    pp_contact c[MAX_CONTACTS];
    const int32_t n = contacts_of(w, c);
    cr_assert(n >= 1 && n <= PP_MAX_CONTACTS_PER_PAIR, "the sleeping pair lists its points: %d contacts", (int)n);
    float mass = 0;
    PP_OK_OR_FAIL(pp_body_get_mass(w, box, &mass, NULL, NULL));
    double sum = 0;
    for (int32_t i = 0; i < n; i++) {
        cr_assert(c[i].a.id == ground.id && c[i].b.id == box.id, "the contact is the ground's and the box's");
        cr_assert_float_eq(c[i].normal.y, -1.0f, 0.02f, "normal from the ground up into the box (y down)? (%g, %g)",
                           c[i].normal.x, c[i].normal.y);
        cr_assert_float_eq(c[i].point.y, GROUND_TOP, 1.5f, "point at the ground's top, y %g", c[i].point.y);
        sum += c[i].normal_impulse;
    }
    const double weight_h = mass * G * DT / d.substeps;
    cr_log_info("asleep: impulses %.3f against m·g·h %.3f (%+.2f %%)", sum, weight_h, 100 * (sum / weight_h - 1));
    cr_assert_float_eq(sum, weight_h, 0.2 * weight_h, "impulses %g against m·g·h %g", sum, weight_h);
    pp_world_destroy(w);
}

/* A ground and four stacks of five 16 px crates: twenty touching pairs (four between crates and one on the
 * ground in each stack). */
static pp_world pile(pp_body *ground, pp_body *crates, uint32_t events)
{
    pp_world_def d = pp_world_def_default();
    d.contact_events = events;
    pp_world w = make_world_def(&d);
    *ground = add_rect(w, body_def(PP_BODY_STATIC, 500, GROUND_TOP + 20, 0), 1000, 40);
    for (int s = 0; s < 4; s++)
        for (int k = 0; k < 5; k++)
            crates[5 * s + k] =
                add_rect(w, body_def(PP_BODY_DYNAMIC, 100.0f + 60.0f * s, GROUND_TOP - 8 - 16 * k, 0), 16, 16);
    return w;
}

Test(sleeping_contacts, a_sleeping_pile_lists_every_touching_pair)
{
    pp_body ground, crates[20];
    pp_world w = pile(&ground, crates, 0);
    settle(w, 900);
    step_n(w, DT, 3);
    pp_contact c[MAX_CONTACTS];
    const int32_t n = contacts_of(w, c);
    cr_assert_eq(distinct_pairs(c, n), 20, "20 touching pairs asleep, got %d in %d contacts", distinct_pairs(c, n),
                 (int)n);
    /* Every stack's weight reaches the ground: the ground pairs carry five crates each. */
    float mass = 0;
    PP_OK_OR_FAIL(pp_body_get_mass(w, crates[0], &mass, NULL, NULL));
    pp_world_def d;
    PP_OK_OR_FAIL(pp_world_get_def(w, &d));
    double on_ground = 0;
    for (int32_t i = 0; i < n; i++)
        if (c[i].a.id == ground.id)
            on_ground += c[i].normal_impulse;
    const double weight_h = 20 * mass * G * DT / d.substeps;
    cr_assert_float_eq(on_ground, weight_h, 0.2 * weight_h, "the ground carries %g against 20·m·g·h %g", on_ground,
                       weight_h);
    /* A snapshot keeps them: loaded, the sleeping pile lists the same pairs before any step. */
    pp_world back = snapshot_round_trip(w);
    pp_contact c2[MAX_CONTACTS];
    const int32_t n2 = contacts_of(back, c2);
    cr_assert_eq(n2, n, "the loaded world lists %d contacts, the saved one %d", (int)n2, (int)n);
    for (int32_t i = 0; i < n2; i++)
        cr_assert_float_eq(c2[i].normal_impulse, c[i].normal_impulse, 1e-3f * (1 + c[i].normal_impulse));
    pp_world_destroy(back);
    pp_world_destroy(w);
}

/* Falling asleep ends nothing; waking while touching begins nothing; erasing the ground under a crate ends its
 * pair with the ground exactly once. */
Test(sleeping_contacts, sleep_and_waking_keep_their_pairs_and_an_erased_ground_ends_once)
{
    pp_body ground, crates[20];
    pp_world w = pile(&ground, crates, 1);
    pp_event ev[64];
    int begins = 0;
    for (int k = 0; k < 900; k++) { /* settle, counting every event on the way */
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        const int n = read_events(w, ev, 64);
        cr_assert_eq(count_events(ev, n, PP_EVENT_CONTACT_END), 0, "no pair ends as the pile settles and sleeps");
        begins += count_events(ev, n, PP_EVENT_CONTACT_BEGIN);
        pp_step_stats s;
        PP_OK_OR_FAIL(pp_world_get_stats(w, &s));
        if (s.awake_bodies == 0 && k > 60)
            break;
    }
    cr_assert_eq(begins, 20, "each of the 20 pairs began once: %d BEGINs", begins);
    step_n(w, DT, 30); /* asleep */
    cr_assert_eq(read_events(w, ev, 64), 0, "sleeping queues nothing");
    /* Woken while touching (each stack's top crate; ODE wakes the rest of its island): nothing begins, nothing
     * ends. */
    for (int s = 0; s < 4; s++)
        PP_OK_OR_FAIL(pp_body_set_awake(w, crates[5 * s + 4], 1));
    step_n(w, DT, 1);
    pp_step_stats st;
    PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
    cr_assert_eq(st.awake_bodies, 20, "every crate woke: %d awake", (int)st.awake_bodies);
    step_n(w, DT, 10);
    cr_assert_eq(read_events(w, ev, 64), 0, "woken while touching: no event");
    settle(w, 900);
    cr_assert_eq(read_events(w, ev, 64), 0, "asleep again: no event");
    /* Erase the ground under the first stack, through its whole depth: the stack falls through, and its bottom
     * crate's pair with the ground ends, once. */
    pp_vec2 p = body_pos(w, crates[0]);
    int32_t changed = 0;
    PP_OK_OR_FAIL(pp_body_erase_circle(w, ground, v2(p.x, GROUND_TOP + 20), 40, &changed));
    cr_assert_gt(changed, 0);
    int ends = 0;
    for (int k = 0; k < 20; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        const int n = read_events(w, ev, 64);
        for (int i = 0; i < n; i++)
            if (ev[i].type == PP_EVENT_CONTACT_END && (ev[i].body.id == ground.id || ev[i].other.id == ground.id)) {
                cr_assert(ev[i].body.id == crates[0].id || ev[i].other.id == crates[0].id,
                          "the END is the erased crate's");
                ends++;
            }
    }
    cr_assert_eq(ends, 1, "exactly one CONTACT_END with the ground, got %d", ends);
    pp_world_destroy(w);
}

static int lcp_messages;

static void count_lcp(int level, const char *msg, void *user)
{
    (void)user;
    if (strstr(msg, "LCP") && level == 1)
        lcp_messages++;
}

/* A pile woken all at once stands. Waking every crate of a sleeping stack hands the exact solver its rows in an
 * order its LCP gives up on ("LCP internal error"), which applied no contact force: the crates fell through one
 * another (the top ones 14 px in 30 steps). Such an island is solved by QuickStep instead, and the message
 * reaches the log hook, not stderr (ODE printed it there). */
Test(sleeping_contacts, a_pile_woken_all_at_once_stands, .init = cr_redirect_stderr)
{
    pp_body ground, crates[20];
    pp_world w = pile(&ground, crates, 0);
    settle(w, 900);
    pp_vec2 rest[20];
    for (int i = 0; i < 20; i++)
        rest[i] = body_pos(w, crates[i]);
    lcp_messages = 0;
    pp_set_log_hook(count_lcp, NULL);
    for (int i = 0; i < 20; i++)
        PP_OK_OR_FAIL(pp_body_set_awake(w, crates[i], 1));
    step_n(w, DT, 30);
    pp_set_log_hook(NULL, NULL);
    cr_log_info("woken pile: %d LCP messages through the hook", lcp_messages);
    cr_assert_gt(lcp_messages, 0, "ODE's LCP message reaches the log hook at level 1");
    for (int i = 0; i < 20; i++) {
        const pp_vec2 p = body_pos(w, crates[i]);
        cr_assert(fabsf(p.y - rest[i].y) < 1.0f && fabsf(p.x - rest[i].x) < 1.0f,
                  "crate %d moved from (%.2f, %.2f) to (%.2f, %.2f)", i, rest[i].x, rest[i].y, p.x, p.y);
    }
    pp_world_destroy(w);
    fflush(stderr);
    cr_assert_stderr_eq_str("", "ODE wrote to stderr");
}

#ifdef PP_TEST_PRIVATE
#include "world.h" /* the bodies' sleep timers */

/* Without sleep, a body put to sleep by hand carries the sleeper's mark (sleep_time + 1 s) until it is woken; the
 * step it wakes in leaves its timer at 0, as every substep of that step once set it (island_sleep_off does it once,
 * after the last). Its crate above it, awake throughout, keeps 0 too. */
Test(sleeping_contacts, without_sleep_a_woken_sleepers_mark_is_cleared_by_the_step)
{
    pp_world w = quickstep_world(4, GROUND_TOP);
    const pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 8, 0), 16, 16);
    const pp_body top = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 23, 0), 16, 16);
    step_n(w, DT, 30);
    PP_OK_OR_FAIL(pp_body_set_awake(w, box, 0));
    world *wd = world_lookup(w, "test");
    cr_assert_not_null(wd);
    const body *bd = body_find(wd, box), *above = body_find(wd, top);
    cr_assert(bd && above);
    cr_assert_float_eq(bd->slow_time, wd->def.sleep_time + 1, 1e-12, "put to sleep: the mark, got %g", bd->slow_time);
    PP_OK_OR_FAIL(pp_body_set_awake(w, box, 1));
    cr_assert_gt(bd->slow_time, wd->def.sleep_time, "woken: the mark stays until a step");
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    cr_assert_eq(bd->slow_time, 0.0, "after the step it woke in: %g s", bd->slow_time);
    cr_assert_eq(above->slow_time, 0.0, "the crate above: %g s", above->slow_time);
    pp_world_destroy(w);
}
#endif
