/* QuickStep stacks solve every other substep with twice its time step (lib/dynamics/island.h): what the bodies of
 * such a pile feel per step (weight, forces, contact impulses) is what they would feel solved every substep,
 * its pairs are collided once a step, and a snapshot continues it exactly. */
#include <criterion/criterion.h>
#include <math.h>

#include "helpers.h"
#include "physpix.h"

PP_TEST_SUITE(spans);

#define DT (1.0f / 60.0f)
#define G 980.0
#define GROUND_TOP 500.0f

static pp_world quick_world(int32_t substeps) { return quickstep_world(substeps, GROUND_TOP); }

/* A column of n 16 px boxes on the ground, each sunk 1 px into the one below; their handles into b. */
static void add_column(pp_world w, pp_body *b, int n)
{
    for (int k = 0; k < n; k++)
        b[k] = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 7 - 15 * k, 0), 16, 16);
}

Test(spans, a_quickstep_pile_reports_its_weight_per_substep)
{
    /* Solved over 2·h, the ground still reports the pile's weight × h a substep (force × the substep). */
    pp_world w = quick_world(4);
    pp_body b[3];
    add_column(w, b, 3);
    step_n(w, DT, 120);
    double mass = 0;
    for (int k = 0; k < 3; k++) {
        float m = 0;
        PP_OK_OR_FAIL(pp_body_get_mass(w, b[k], &m, NULL, NULL));
        mass += m;
    }
    pp_contact c[16];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_contacts(w, c, 16, &n));
    double ground = 0;
    for (int i = 0; i < n; i++)
        if (c[i].a.id != b[0].id && c[i].b.id == b[0].id)
            ground += c[i].normal_impulse;
    const double weight_h = mass * G * DT / 4;
    cr_log_info("ground impulses %.3f against the pile's m·g·h %.3f", ground, weight_h);
    cr_assert_float_eq(ground, weight_h, 0.02 * weight_h, "%g against %g", ground, weight_h);
    pp_world_destroy(w);
}

Test(spans, a_force_on_a_box_of_a_quickstep_pile_acts_once_a_step)
{
    /* Held up by a force equal to its weight, the top box stays put: a force counted again in the substep
     * its pile sits out would lift it at g (490 px in the second). */
    pp_world w = quick_world(4);
    pp_body b[2];
    add_column(w, b, 2);
    step_n(w, DT, 60);
    float m = 0;
    PP_OK_OR_FAIL(pp_body_get_mass(w, b[1], &m, NULL, NULL));
    const pp_vec2 start = body_pos(w, b[1]);
    for (int k = 0; k < 60; k++) {
        /* A 16 px box made at its centre keeps its centre of mass on its pivot. */
        PP_OK_OR_FAIL(pp_body_apply_force(w, b[1], v2(0, (float)(-m * G)), body_pos(w, b[1])));
        PP_OK_OR_FAIL(pp_world_step(w, DT));
    }
    const float moved = body_pos(w, b[1]).y - start.y;
    cr_assert_lt(fabsf(moved), 0.5f, "the held box moved %g px", moved);
    pp_world_destroy(w);
}

Test(spans, a_pair_sliding_in_a_quickstep_pile_is_collided_once_a_step)
{
    /* A frictionless box sliding at 30 px/s (0.5 px a step) along a plank: over a resting pair's bound, under a
     * stack's, so four substeps test the rasters as much as one (exactly at the first step, from the same
     * poses; then within the drift of two runs apart, where colliding the sliding pair again would add half). */
    pp_world w[2] = {quick_world(1), quick_world(4)};
    pp_body box[2];
    for (int i = 0; i < 2; i++) {
        /* 4 times the box's mass: a stack, not a heavy-on-light pile (those solve every substep). */
        const pp_body plank = add_rect(w[i], body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 7, 0), 64, 16);
        box[i] = add_rect(w[i], body_def(PP_BODY_DYNAMIC, 380, GROUND_TOP - 22, 0), 16, 16);
        PP_OK_OR_FAIL(pp_body_set_friction(w[i], plank, 0));
        PP_OK_OR_FAIL(pp_body_set_friction(w[i], box[i], 0));
        PP_OK_OR_FAIL(pp_body_set_velocity(w[i], box[i], v2(30, 0), 0));
    }
    for (int s = 0; s < 30; s++) {
        PP_OK_OR_FAIL(pp_world_step(w[0], DT));
        PP_OK_OR_FAIL(pp_world_step(w[1], DT));
        const int64_t four = pixels_tested(w[1]), one = pixels_tested(w[0]);
        cr_assert(s == 0 ? four == one : 4 * four < 5 * one, "step %d: 4 substeps tested %lld samples, 1 tested %lld",
                  s, (long long)four, (long long)one);
    }
    const pp_vec2 v = body_vel(w[1], box[1]);
    cr_assert_float_eq(v.x, 30.0f, 0.5f, "it slides at %g px/s", v.x);
    pp_world_destroy(w[0]);
    pp_world_destroy(w[1]);
}

Test(spans, a_snapshot_of_a_settling_quickstep_pile_continues_it_exactly)
{
    /* Sitting out is decided inside a step: the loaded world steps the pile as the saved one does. */
    pp_world w = quick_world(4);
    pp_body b[6];
    add_column(w, b, 6);
    add_rect(w, body_def(PP_BODY_DYNAMIC, 420, GROUND_TOP - 140, 0.3f), 24, 12);
    step_n(w, DT, 20);
    pp_world back = snapshot_round_trip(w);
    step_n(w, DT, 60);
    step_n(back, DT, 60);
    pp_body_state s[2][8];
    int32_t n[2] = {0, 0};
    PP_OK_OR_FAIL(pp_world_get_body_states(w, s[0], 8, &n[0]));
    PP_OK_OR_FAIL(pp_world_get_body_states(back, s[1], 8, &n[1]));
    cr_assert_eq(n[0], n[1]);
    for (int i = 0; i < n[0]; i++) {
        cr_assert(s[0][i].position.x == s[1][i].position.x && s[0][i].position.y == s[1][i].position.y &&
                      s[0][i].angle == s[1][i].angle,
                  "body %d: (%.9g, %.9g) against (%.9g, %.9g) after the load", i, s[0][i].position.x,
                  s[0][i].position.y, s[1][i].position.x, s[1][i].position.y);
    }
    pp_world_destroy(w);
    pp_world_destroy(back);
}

/* A default world (lone bodies solved exactly), sleep off, with the ground of quick_world. */
static pp_world exact_world(void)
{
    pp_world_def d = pp_world_def_default();
    d.allow_sleep = 0;
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 400, GROUND_TOP + 20, 0), 800, 40);
    return w;
}

Test(spans, a_lone_crate_at_rest_reports_its_weight_per_substep_and_stays_put)
{
    /* A lone body whose contacts are all held solves every other substep over 2·h (island.c): the ground still
     * reports its weight × h a substep, and it rests where it would. */
    pp_world w = exact_world();
    const pp_body crate = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 15, 0), 32, 32);
    step_n(w, DT, 120);
    const pp_vec2 rest = body_pos(w, crate);
    step_n(w, DT, 120);
    float m = 0;
    PP_OK_OR_FAIL(pp_body_get_mass(w, crate, &m, NULL, NULL));
    pp_contact c[8];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_contacts(w, c, 8, &n));
    double ground = 0;
    for (int i = 0; i < n; i++)
        ground += c[i].normal_impulse;
    const double weight_h = m * G * DT / 4;
    cr_assert_float_eq(ground, weight_h, 0.02 * weight_h, "ground impulses %g against m·g·h %g", ground, weight_h);
    const pp_vec2 now = body_pos(w, crate);
    cr_assert(fabsf(now.x - rest.x) < 0.01f && fabsf(now.y - rest.y) < 0.01f, "it moved from (%g, %g) to (%g, %g)",
              rest.x, rest.y, now.x, now.y);
    cr_assert_float_eq(rest.y, GROUND_TOP - 16, 1.0f, "it rests on the ground: y %g", rest.y);
    pp_world_destroy(w);
}

Test(spans, a_force_on_a_lone_crate_at_rest_acts_once_a_step)
{
    /* Held up by a force equal to its weight, a resting crate stays put: counted again in a substep it sits out,
     * the force would lift it at g. */
    pp_world w = exact_world();
    const pp_body crate = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 15, 0), 32, 32);
    step_n(w, DT, 60);
    float m = 0;
    PP_OK_OR_FAIL(pp_body_get_mass(w, crate, &m, NULL, NULL));
    const pp_vec2 start = body_pos(w, crate);
    for (int k = 0; k < 60; k++) {
        PP_OK_OR_FAIL(pp_body_apply_force(w, crate, v2(0, (float)(-m * G)), body_pos(w, crate)));
        PP_OK_OR_FAIL(pp_world_step(w, DT));
    }
    const float moved = body_pos(w, crate).y - start.y;
    cr_assert_lt(fabsf(moved), 0.5f, "the held crate moved %g px", moved);
    pp_world_destroy(w);
}

Test(spans, a_lone_crate_landing_and_coming_to_rest_continues_exactly_from_a_snapshot)
{
    /* Whether a lone body rests is decided inside a step, from what its pairs did in it: a world loaded while the
     * crate lands and settles steps it as the saved one does. */
    pp_world w = exact_world();
    const pp_body crate = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 60, 0.2f), 32, 24);
    step_n(w, DT, 25);
    pp_world back = snapshot_round_trip(w);
    for (int k = 0; k < 90; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        PP_OK_OR_FAIL(pp_world_step(back, DT));
    }
    pp_body_state s[2][2];
    int32_t n[2] = {0, 0};
    PP_OK_OR_FAIL(pp_world_get_body_states(w, s[0], 2, &n[0]));
    PP_OK_OR_FAIL(pp_world_get_body_states(back, s[1], 2, &n[1]));
    cr_assert(n[0] == 2 && n[1] == 2);
    for (int i = 0; i < 2; i++)
        cr_assert(s[0][i].position.x == s[1][i].position.x && s[0][i].position.y == s[1][i].position.y &&
                      s[0][i].angle == s[1][i].angle,
                  "body %d: (%.9g, %.9g) against (%.9g, %.9g) after the load", i, s[0][i].position.x,
                  s[0][i].position.y, s[1][i].position.x, s[1][i].position.y);
    const pp_vec2 at = body_pos(w, crate);
    cr_assert(fabsf(body_angle(w, crate)) < 0.01f || fabsf(fabsf(body_angle(w, crate)) - 1.5707963f) < 0.01f,
              "it settles flat: %g rad, at (%g, %g)", body_angle(w, crate), at.x, at.y);
    pp_world_destroy(w);
    pp_world_destroy(back);
}

#ifdef PP_TEST_PRIVATE
#include "island.h"
#include "world.h" /* the islands' plan, and the carry's strikes */

/* The stepped lists of a plan of substep k, as a still substep (its contacts stand) plans them. */
static solver_islands plan_still(world *wd, int32_t k)
{
    solver_islands out;
    cr_assert_eq(island_plan(wd, k, island_pairing(k, wd->def.substeps), true, &out), PP_OK);
    return out;
}

/* The bodies a plan steps, over every list. */
static int32_t stepped(const solver_islands *is)
{
    int32_t n = 0;
    for (int i = 0; i < SOLVE_IDLE; i++)
        n += is->count[i];
    return n;
}

/* A QuickStep pile at rest sits the first three of four substeps out and solves the fourth over 4·h with every
 * iteration. One that a collided pair touched in this step solves each pair of substeps with every iteration, not
 * with the half that a pile at rest gets over 2·h, also where the second substep looks for no pairs (its contacts
 * stand from the first, where a landing crate struck the pile): island_plan is told which substep it plans, rather
 * than reading it from the last substep that looked for pairs. */
Test(spans, a_quickstep_pile_at_rest_solves_once_a_step_and_a_struck_one_keeps_its_iterations)
{
    pp_world w = quick_world(4);
    pp_body b[3];
    add_column(w, b, 3);
    step_n(w, DT, 60);
    world *wd = world_lookup(w, "test");
    cr_assert_not_null(wd);
    wd->carry.substep = 0; /* the step's first substep was the last to look for pairs */

    for (int32_t k = 0; k < 3; k++) {
        const solver_islands out = plan_still(wd, k);
        cr_assert_eq(stepped(&out), 0, "at rest, the pile sits substep %d out: %d bodies stepped", k, stepped(&out));
    }
    solver_islands last = plan_still(wd, 3);
    cr_assert_eq(last.count[SOLVE_QUICK_FOUR], 3, "at rest, it solves 4·h at the last substep: %d of 3 bodies",
                 last.count[SOLVE_QUICK_FOUR]);

    /* Now a collided pair touched the top box in this step. */
    const uint32_t top = handle_slot(b[2].id);
    cr_assert_lt((int32_t)top, wd->carry.struck_capacity);
    wd->carry.struck[top] = wd->carry.step;
    solver_islands first = plan_still(wd, 0), second = plan_still(wd, 1);
    cr_assert_eq(stepped(&first), 0, "the pile sits substep 0 out");
    cr_assert_eq(second.count[SOLVE_QUICK_TWO], 3, "struck, it keeps every iteration: %d of 3 bodies (%d at rest)",
                 second.count[SOLVE_QUICK_TWO], second.count[SOLVE_QUICK_TWO_REST]);
    first = plan_still(wd, 2), second = plan_still(wd, 3);
    cr_assert_eq(stepped(&first), 0, "the pile sits substep 2 out");
    cr_assert_eq(second.count[SOLVE_QUICK_TWO], 3, "and solves 2·h at the last with every iteration: %d of 3 bodies",
                 second.count[SOLVE_QUICK_TWO]);
    pp_world_destroy(w);
}

/* A QuickStep pile whose pairs move faster than CARRY_REST_PX (1 px a step) against themselves is not at rest, though
 * its pairs stay held (under CARRY_STACK_PX, 1.5 px) and no collided pair strikes it: it keeps every iteration. Solved
 * at half, such a pile of 500 raining crates boiled (tests/bench/README.md). */
Test(spans, a_quickstep_pile_moving_past_rest_keeps_its_iterations_while_its_pairs_are_held)
{
    pp_world w = quick_world(4);
    pp_body b[3];
    add_column(w, b, 3);
    step_n(w, DT, 60);
    world *wd = world_lookup(w, "test");
    cr_assert_not_null(wd);
    const uint32_t top = handle_slot(b[2].id), middle = handle_slot(b[1].id), bottom = handle_slot(b[0].id);
    /* 66 px/s sideways: 1.1 px a step against the box under it */
    pp_vec2 v;
    float av = 0;
    PP_OK_OR_FAIL(pp_body_get_velocity(w, b[2], &v, &av));
    PP_OK_OR_FAIL(pp_body_set_velocity(w, b[2], (pp_vec2){v.x + 66.0f, v.y}, av));
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    const carry *c = &wd->carry;
    cr_assert(!carry_was_collided(c, top) && !carry_struck(c, top) && !carry_struck(c, middle),
              "its pairs stay held and nothing strikes it: collided %d, struck %d %d", carry_was_collided(c, top),
              carry_struck(c, top), carry_struck(c, middle));
    cr_assert(carry_restless(c, top) && carry_restless(c, middle) && !carry_restless(c, bottom),
              "the sliding pair's bodies are restless (top %d, middle %d), the pair under them not (bottom %d)",
              carry_restless(c, top), carry_restless(c, middle), carry_restless(c, bottom));
    const solver_islands first = plan_still(wd, 2), second = plan_still(wd, 3);
    cr_assert_eq(stepped(&first), 0, "the pile sits substep 2 out");
    cr_assert_eq(second.count[SOLVE_QUICK_TWO], 3, "it keeps every iteration: %d of 3 bodies (%d at rest)",
                 second.count[SOLVE_QUICK_TWO], second.count[SOLVE_QUICK_TWO_REST]);
    pp_world_destroy(w);
}
#endif
