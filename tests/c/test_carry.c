/* Contacts carried through a step's substeps (lib/carry.h): the raster narrowphase runs once a step for
 * pairs that touch at its start, and the later substeps move their contacts with the bodies. */
#include <criterion/criterion.h>
#include <math.h>

#include "helpers.h"
#include "physpix.h"

PP_TEST_SUITE(carry);

#define DT (1.0f / 60.0f)
#define GROUND_TOP 500.0f

/* A ground and two towers of five 16 px boxes, each box sunk 1 px into the one below, QuickStep for every
 * island (no exact solver), so every pair touches at the first step's start and is carried. */
static pp_world towers(int32_t substeps)
{
    pp_world w = quickstep_world(substeps, GROUND_TOP);
    for (int t = 0; t < 2; t++)
        for (int k = 0; k < 5; k++)
            add_rect(w, body_def(PP_BODY_DYNAMIC, 300.0f + 200.0f * t, GROUND_TOP - 7 - 15 * k, 0), 16, 16);
    return w;
}

Test(carry, the_narrowphase_runs_once_a_step_whatever_the_substeps)
{
    /* Same scene, one substep and four: the first substep of both tests the same pixels at the same poses,
     * and the four-substep world tests nothing more. */
    pp_world one = towers(1), four = towers(4);
    PP_OK_OR_FAIL(pp_world_step(one, DT));
    PP_OK_OR_FAIL(pp_world_step(four, DT));
    const int64_t once = pixels_tested(one);
    cr_assert_gt(once, 0);
    cr_assert_eq(pixels_tested(four), once, "4 substeps tested %lld raster samples, one substep %lld",
                 (long long)pixels_tested(four), (long long)once);
    /* Settled, it stays once a step: every pair keeps its two points and no pair is collided twice. */
    step_n(four, DT, 60);
    for (int k = 0; k < 60; k++) {
        PP_OK_OR_FAIL(pp_world_step(four, DT));
        pp_step_stats s;
        PP_OK_OR_FAIL(pp_world_get_stats(four, &s));
        cr_assert_eq(s.contacts, 20, "step %d: %d contacts (10 pairs of two points)", k, (int)s.contacts);
        cr_assert_lt(s.pixels_tested, 3 * once / 2, "step %d: %lld samples", k, (long long)s.pixels_tested);
    }
    pp_world_destroy(one);
    pp_world_destroy(four);
}

Test(carry, carried_contacts_hold_a_quickstep_tower_at_its_resting_height)
{
    /* A carried contact's depth follows the bodies, so each of the five contacts under the top box sinks
     * into the slop (0.75 px) and no further: the top box is 0–5 px below where five bare 16 px boxes put it. */
    pp_world w = towers(4);
    step_n(w, DT, 120);
    pp_body bodies[11];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 11, &n));
    cr_assert_eq(n, 11);
    for (int t = 0; t < 2; t++) {
        const pp_vec2 top = body_pos(w, bodies[5 + 5 * t]);
        const float sink = top.y - (GROUND_TOP - 4 * 16 - 8);
        cr_assert(sink >= 0 && sink <= 5, "tower %d's top box sank %g px", t, sink);
        cr_assert_float_eq(top.x, 300.0f + 200.0f * t, 0.5, "tower %d's top box at x = %g", t, top.x);
    }
    pp_world_destroy(w);
}
