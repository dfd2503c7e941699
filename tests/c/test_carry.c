/* Contacts carried through a step's substeps (lib/dynamics/carry.h): the raster narrowphase runs once a step for
 * pairs that touch at its start, and the later substeps move their contacts with the bodies. */
#include <cjson/cJSON.h>
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

/* A frictionless 16 px box sunk 1 px into the ground, sliding at `speed` px/s; the steps' raster samples summed
 * over 30 steps, and where it ends. */
static int64_t slide(int32_t substeps, float speed, pp_vec2 *end)
{
    pp_world w = quickstep_world(substeps, GROUND_TOP);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 100, GROUND_TOP - 7, 0);
    d.friction = 0;
    const pp_body box = add_rect(w, d, 16, 16);
    PP_OK_OR_FAIL(pp_body_set_velocity(w, box, v2(speed, 0), 0));
    int64_t samples = 0;
    for (int k = 0; k < 30; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        samples += pixels_tested(w);
    }
    *end = body_pos(w, box);
    pp_world_destroy(w);
    return samples;
}

Test(carry, a_pair_moving_under_two_pixels_a_step_is_collided_once_a_step)
{
    /* 90 px/s is 1.5 px a step: too fast to rest, carried through each step all the same, so four substeps test
     * about what one does, and the box slides on at its speed, on the ground. At 300 px/s (5 px a step) each
     * substep collides the pair again. */
    pp_vec2 end_one, end_four;
    const int64_t one = slide(1, 90, &end_one), four = slide(4, 90, &end_four);
    cr_assert_gt(one, 0);
    cr_assert_lt(four, 3 * one / 2, "4 substeps tested %lld samples in 30 steps, one %lld", (long long)four,
                 (long long)one);
    cr_assert_float_eq(end_four.x, 100 + 90 * 30 * DT, 0.5, "the box slid to x = %g", end_four.x);
    cr_assert(end_four.y >= GROUND_TOP - 8.5f && end_four.y <= GROUND_TOP - 7, "the box is at y = %g", end_four.y);
    const int64_t fast_one = slide(1, 300, &end_one), fast_four = slide(4, 300, &end_four);
    cr_assert_gt(fast_four, 3 * fast_one, "at 300 px/s 4 substeps tested %lld samples, one %lld", (long long)fast_four,
                 (long long)fast_one);
    cr_assert_float_eq(end_four.x, 100 + 300 * 30 * DT, 0.5, "the fast box slid to x = %g", end_four.x);
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

/* Steps w until a step tests no raster sample (its pairs are held), at most 240 steps; how many it took. */
static int step_until_held(pp_world w)
{
    for (int k = 1; k <= 240; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        pp_step_stats st;
        PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
        if (st.pixels_tested == 0 && st.contacts > 0) /* tested nothing, yet touches: held */
            return k;
    }
    cr_assert_fail("the pile was still collided after 240 steps");
    return 0;
}

/* Of 60 steps of a settled scene whose `pairs` pairs keep their two points each, those that tested no raster
 * sample (every pair held). */
static int idle_steps(pp_world w, int pairs)
{
    int idle = 0;
    for (int k = 0; k < 60; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        idle += pixels_tested(w) == 0;
        pp_step_stats s;
        PP_OK_OR_FAIL(pp_world_get_stats(w, &s));
        cr_assert_eq(s.contacts, 2 * pairs, "step %d: %d contacts (%d pairs of two points)", k, (int)s.contacts, pairs);
    }
    return idle;
}

Test(carry, a_settled_pile_is_collided_once_not_once_a_step)
{
    /* Resting pairs are held from step to step: after the towers settle, whole steps test nothing, and the
     * towers stand as when collided every step (the resting-height test above). */
    pp_world w = towers(4);
    step_n(w, DT, 120);
    const int idle = idle_steps(w, 10);
    cr_assert_geq(idle, 50, "only %d of 60 settled steps tested no raster sample", idle);
    pp_body bodies[11];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 11, &n));
    for (int t = 0; t < 2; t++) {
        const float sink = body_pos(w, bodies[5 + 5 * t]).y - (GROUND_TOP - 4 * 16 - 8);
        cr_assert(sink >= 0 && sink <= 5, "tower %d's top box sank %g px", t, sink);
    }
    pp_world_destroy(w);
}

/* A 16 px box resting on a 64 px static block on the ground; the pair held. */
static pp_world box_on_block(pp_body *block, pp_body *box)
{
    pp_world w = quickstep_world(4, GROUND_TOP);
    *block = add_rect(w, body_def(PP_BODY_STATIC, 400, GROUND_TOP - 100, 0), 64, 16);
    *box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 116, 0), 16, 16);
    step_until_held(w);
    return w;
}

Test(carry, a_held_pair_is_dropped_when_its_pixels_or_pose_change)
{
    /* Held contacts would hold the box in the air: an edit or a move of the block must drop them. */
    for (int how = 0; how < 3; how++) {
        pp_body block, box;
        pp_world w = box_on_block(&block, &box);
        const float rest = body_pos(w, box).y;
        if (how == 0) /* erase the block's middle, under the box */
            PP_OK_OR_FAIL(pp_body_erase_circle(w, block, v2(400, GROUND_TOP - 100), 20, NULL));
        else if (how == 1) /* move the block 40 px down */
            PP_OK_OR_FAIL(pp_body_set_transform(w, block, v2(400, GROUND_TOP - 60), 0));
        else /* destroy it */
            PP_OK_OR_FAIL(pp_body_destroy(w, block));
        step_n(w, DT, 10);
        const float fell = body_pos(w, box).y - rest;
        cr_assert_gt(fell, 5.0f, "case %d: the box fell %g px in 10 steps", how, fell);
        pp_world_destroy(w);
    }
}

Test(carry, an_erase_far_from_a_held_pair_keeps_it_held)
{
    /* The static block is edited 30 px from the box: the pair's overlap is as it was, so it stays held (a step
     * tests no raster sample) and the box stays put; an erase under the box drops it, and it falls. */
    pp_body block, box;
    pp_world w = box_on_block(&block, &box);
    const pp_vec2 rest = body_pos(w, box);
    int32_t erased = 0;
    PP_OK_OR_FAIL(pp_body_erase_circle(w, block, v2(370, GROUND_TOP - 100), 3, &erased));
    cr_assert_gt(erased, 0);
    for (int k = 0; k < 5; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        cr_assert_eq(pixels_tested(w), 0, "step %d after the far erase tested %lld samples", k,
                     (long long)pixels_tested(w));
    }
    cr_assert_float_eq(body_pos(w, box).y, rest.y, 0.01f, "the box moved from %g to %g", rest.y, body_pos(w, box).y);
    PP_OK_OR_FAIL(pp_body_erase_circle(w, block, v2(400, GROUND_TOP - 108), 10, NULL));
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    pp_step_stats st;
    PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
    cr_assert_eq(st.contacts, 0, "the erase under the box left %d held contacts", (int)st.contacts);
    step_n(w, DT, 10);
    cr_assert_gt(body_pos(w, box).y - rest.y, 2.0f, "the box sank into the hole: %g px", body_pos(w, box).y - rest.y);
    pp_world_destroy(w);
}

Test(carry, a_snapshot_keeps_the_held_pairs)
{
    /* The loaded world carries the same held pairs uncollided, and goes on bit for bit. */
    pp_world w = towers(4);
    step_until_held(w);
    pp_world back = snapshot_round_trip(w);
    for (int k = 0; k < 30; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        PP_OK_OR_FAIL(pp_world_step(back, DT));
        cr_assert_eq(pixels_tested(back), pixels_tested(w), "step %d", k);
    }
    pp_body_state s[2][11];
    int32_t n[2] = {0, 0};
    PP_OK_OR_FAIL(pp_world_get_body_states(w, s[0], 11, &n[0]));
    PP_OK_OR_FAIL(pp_world_get_body_states(back, s[1], 11, &n[1]));
    cr_assert_eq(n[0], n[1]);
    for (int i = 0; i < n[0]; i++)
        cr_assert(memcmp(&s[0][i].position, &s[1][i].position, sizeof s[0][i].position) == 0 &&
                      s[0][i].angle == s[1][i].angle,
                  "body %d moved otherwise after the load", i);
    pp_world_destroy(w);
    pp_world_destroy(back);
}

Test(carry, broken_held_pairs_in_a_snapshot_are_refused)
{
    pp_world w = towers(4);
    step_until_held(w);
    const struct { const char *from, *to, *words; } cases[] = {
        {"\"stack\":\ttrue", "\"stack\":\t1", "held[0].stack: expected true or false"},
        {"\"contacts\":\t[[", "\"contacts\":\t[[0, ", "held[0].contacts[0]: expected 15 finite numbers"},
        {"\"held\":\t[{", "\"held\":\t[{\n\"x\": 1,", "held[0].x: unknown key"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char dir[] = "/tmp/pp_held_XXXXXX";
        cr_assert_not_null(mkdtemp(dir));
        PP_OK_OR_FAIL(pp_world_save_snapshot(w, dir));
        patch_json(dir, cases[i].from, cases[i].to);
        pp_world out = {0};
        EXPECT_ERR(pp_world_load_snapshot(dir, &out), PP_ERR_FORMAT, cases[i].words);
        remove_tree(dir);
    }
    pp_world_destroy(w);
}

/* The snapshot in dir without the "touching" record of its first held pair. */
static void drop_first_held_record(const char *dir)
{
    char path[160];
    snprintf(path, sizeof path, "%s/world.json", dir);
    static char text[1 << 20];
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f);
    text[fread(text, 1, sizeof text - 1, f)] = 0;
    fclose(f);
    cJSON *root = cJSON_Parse(text);
    cr_assert_not_null(root);
    const cJSON *held = cJSON_GetArrayItem(cJSON_GetObjectItem(root, "held"), 0);
    cr_assert_not_null(held, "no held pair in the snapshot");
    const char *a = cJSON_GetObjectItem(held, "a")->valuestring, *b = cJSON_GetObjectItem(held, "b")->valuestring;
    cJSON *touching = cJSON_GetObjectItem(root, "touching");
    int dropped = 0;
    for (int i = cJSON_GetArraySize(touching) - 1; i >= 0; i--) {
        const cJSON *t = cJSON_GetArrayItem(touching, i);
        if (!strcmp(cJSON_GetObjectItem(t, "a")->valuestring, a) && !strcmp(cJSON_GetObjectItem(t, "b")->valuestring, b))
            cJSON_DeleteItemFromArray(touching, i), dropped++;
    }
    cr_assert_eq(dropped, 1, "the held pair's record was listed %d times", dropped);
    char *out = cJSON_Print(root);
    f = fopen(path, "wb");
    cr_assert_not_null(f);
    fputs(out, f);
    fclose(f);
    cJSON_free(out);
    cJSON_Delete(root);
}

Test(carry, a_held_pair_without_its_touching_record_is_refused)
{
    /* A held pair's carried contacts live in its contact record: a snapshot that lists none is broken. */
    pp_world w = towers(4);
    step_until_held(w);
    char dir[] = "/tmp/pp_held_XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, dir));
    drop_first_held_record(dir);
    pp_world out = {0};
    EXPECT_ERR(pp_world_load_snapshot(dir, &out), PP_ERR_FORMAT,
               "held[0]: expected a pair in \"touching\" that makes contacts");
    remove_tree(dir);
    pp_world_destroy(w);
}

#ifdef PP_TEST_PRIVATE
#include "world.h" /* wd->islands.span: how much time a body's island advanced at the last substep */

/* The span (SPAN_*) of b's island at w's last substep. */
static int last_span(pp_world w, pp_body b)
{
    world *wd = world_lookup(w, "test");
    cr_assert_not_null(wd);
    return wd->islands.span[handle_slot(b.id)];
}
#endif

Test(carry, a_lone_crate_at_rest_is_solved_once_a_step_and_still_rests)
{
    /* A 32 px crate on the ground, sleep off: once settled, every pair held, its exact lone solve sits three
     * substeps out and solves the fourth over 4·h. It rests where 1 px of ground overlap plus the slop put it,
     * and the last substep's impulse is its weight × h, as the header has it, whatever span it was solved over. */
    pp_world_def d = pp_world_def_default();
    d.allow_sleep = 0;
    d.gravity = v2(0, 980);
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 400, GROUND_TOP + 20, 0), 800, 40);
    const pp_body crate = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, GROUND_TOP - 16, 0), 32, 32);
    step_n(w, DT, 120);
    const double h = DT / d.substeps;
    float mass = 0;
    PP_OK_OR_FAIL(pp_body_get_mass(w, crate, &mass, NULL, NULL));
    for (int k = 0; k < 60; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        const pp_vec2 p = body_pos(w, crate);
        cr_assert(p.y > GROUND_TOP - 16 && p.y < GROUND_TOP - 15, "step %d: the crate's centre at y = %g", k, p.y);
        cr_assert_float_eq(p.x, 400.0f, 0.01f, "step %d: the crate slid to x = %g", k, p.x);
        pp_contact c[4];
        int32_t n = 0;
        PP_OK_OR_FAIL(pp_world_get_contacts(w, c, 4, &n));
        cr_assert_eq(n, 2, "step %d: %d contacts", k, (int)n);
        const double weight_h = mass * 980.0 * h, sum = c[0].normal_impulse + c[1].normal_impulse;
        cr_assert(fabs(sum - weight_h) < 0.01 * weight_h, "step %d: impulses %g, weight × h %g", k, sum, weight_h);
#ifdef PP_TEST_PRIVATE
        cr_assert_eq(last_span(w, crate), SPAN_FOUR, "step %d: span %d", k, last_span(w, crate));
#endif
    }
    /* Pushed, it moves: its pair is collided and it is solved at every substep again. */
    PP_OK_OR_FAIL(pp_body_set_velocity(w, crate, v2(300, 0), 0));
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    cr_assert_gt(body_pos(w, crate).x, 402.0f);
#ifdef PP_TEST_PRIVATE
    cr_assert_eq(last_span(w, crate), SPAN_ONE);
#endif
    pp_world_destroy(w);
}

/* Two towers of three 16 px boxes on the ground, in the default world (sleep off): each tower is an island of a few
 * rows, which the exact solver takes. */
static pp_world exact_towers(void)
{
    pp_world_def d = pp_world_def_default();
    d.allow_sleep = 0;
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 400, GROUND_TOP + 20, 0), 800, 40);
    for (int t = 0; t < 2; t++)
        for (int k = 0; k < 3; k++)
            add_rect(w, body_def(PP_BODY_DYNAMIC, 300.0f + 200.0f * t, GROUND_TOP - 7 - 15 * k, 0), 16, 16);
    return w;
}

Test(carry, an_exact_tower_at_rest_is_held_and_stands)
{
    /* A small stack's resting pairs are held as a QuickStep pile's are: settled, whole steps test no raster
     * sample, every pair keeps its two points, and the towers stand where they rest when collided (their top box
     * sinks 0–5 px below three bare boxes, in line with the bottom one). */
    pp_world w = exact_towers();
    step_n(w, DT, 120);
#ifdef PP_TEST_PRIVATE
    {
        world *wd = world_lookup(w, "test");
        int32_t n = 0;
        pp_body bodies[7];
        PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 7, &n));
        cr_assert_eq(wd->islands.kind[handle_slot(bodies[1].id)], ISLAND_EXACT, "the tower is not an exact island");
    }
#endif
    const int idle = idle_steps(w, 6);
    cr_assert_geq(idle, 50, "only %d of 60 settled steps tested no raster sample", idle);
    pp_body bodies[7];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 7, &n));
    cr_assert_eq(n, 7);
    for (int t = 0; t < 2; t++) {
        const pp_vec2 top = body_pos(w, bodies[3 + 3 * t]), bottom = body_pos(w, bodies[1 + 3 * t]);
        const float sink = top.y - (GROUND_TOP - 2 * 16 - 8);
        cr_assert(sink >= 0 && sink <= 5, "tower %d's top box sank %g px", t, sink);
        cr_assert_float_eq(top.x, bottom.x, 0.05, "tower %d leans: top at x = %g, bottom at %g", t, top.x, bottom.x);
    }
    pp_world_destroy(w);
}

/* A stack of two 16 px boxes (an island the exact solver takes) sliding on a frictionless ground at `speed` px/s,
 * the top box carried along by friction; the raster samples of 30 steps, and where the top box ends against the
 * bottom one. */
static int64_t slide_stack(int32_t substeps, float speed, pp_vec2 *offset)
{
    pp_world_def d = pp_world_def_default();
    d.substeps = substeps;
    d.allow_sleep = 0;
    pp_world w = make_world_def(&d);
    pp_body_def g = body_def(PP_BODY_STATIC, 400, GROUND_TOP + 20, 0);
    g.friction = 0;
    add_rect(w, g, 800, 40);
    const pp_body bottom = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, GROUND_TOP - 7, 0), 16, 16);
    const pp_body top = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, GROUND_TOP - 22, 0), 16, 16);
    step_n(w, DT, 30); /* settled */
    PP_OK_OR_FAIL(pp_body_set_velocity(w, bottom, v2(speed, 0), 0));
    PP_OK_OR_FAIL(pp_body_set_velocity(w, top, v2(speed, 0), 0));
    int64_t samples = 0;
    for (int k = 0; k < 30; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        samples += pixels_tested(w);
    }
    const pp_vec2 pb = body_pos(w, bottom), pt = body_pos(w, top);
    *offset = v2(pt.x - pb.x, pt.y - pb.y);
    pp_world_destroy(w);
    return samples;
}

Test(carry, a_small_exact_stack_under_half_a_pixel_a_step_is_collided_once_a_step)
{
    /* 24 px/s is 0.4 px a step: too fast to rest, slow enough for a stack whose corners the exact solver weighs,
     * so four substeps test about what one does, and the top box rides along on the bottom one. At 90 px/s
     * (1.5 px a step, which a QuickStep pile would carry) the stack's pairs are collided at every substep. */
    pp_vec2 off;
    const int64_t one = slide_stack(1, 24, &off), four = slide_stack(4, 24, &off);
    cr_assert_gt(one, 0);
    cr_assert_lt(four, 3 * one / 2, "4 substeps tested %lld samples in 30 steps, one %lld", (long long)four,
                 (long long)one);
    cr_assert(fabsf(off.x) < 0.5f && off.y > -16.5f && off.y < -14.0f, "the top box ended at (%g, %g) from the bottom",
              off.x, off.y);
    const int64_t fast_one = slide_stack(1, 90, &off), fast_four = slide_stack(4, 90, &off);
    cr_assert_gt(fast_four, 3 * fast_one, "at 90 px/s 4 substeps tested %lld samples, one %lld", (long long)fast_four,
                 (long long)fast_one);
    cr_assert(fabsf(off.x) < 0.5f && off.y > -16.5f && off.y < -14.0f, "the fast stack's top box ended at (%g, %g)",
              off.x, off.y);
}
