/* The world's clock, its camera and timed edits: an edit applies at the step nearest its time, in
 * time order, and bad edits or cameras are refused with their reason. */
#include "helpers.h"

PP_TEST_SUITE(timed);

#define DT (1.0f / 60.0f)

/* A static 200×40 slab centred at (100, 100): its top-left pixel is at world (0, 80). */
static pp_body add_slab(pp_world w)
{
    uint8_t *m = rect_mask(200, 40);
    pp_body_def d = body_def(PP_BODY_STATIC, 100, 100, 0);
    d.width = 200, d.height = 40, d.mask = m;
    pp_body b = create_body_ok(w, &d);
    free(m);
    return b;
}

static int64_t solid_pixels(pp_world w, pp_body b)
{
    static uint8_t mask[200 * 40];
    PP_OK_OR_FAIL(pp_body_read_mask(w, b, mask, sizeof mask));
    int64_t n = 0;
    for (size_t i = 0; i < sizeof mask; i++)
        n += mask[i];
    return n;
}

Test(timed, the_clock_sums_the_steps)
{
    pp_world w = make_world(0, 980);
    double t = -1;
    PP_OK_OR_FAIL(pp_world_get_time(w, &t));
    cr_assert_eq(t, 0.0);
    for (int i = 0; i < 90; i++)
        PP_OK_OR_FAIL(pp_world_step(w, DT));
    PP_OK_OR_FAIL(pp_world_get_time(w, &t));
    cr_assert(fabs(t - 1.5) < 1e-5, "time %.9f after 90 steps of 1/60 s", t);
    EXPECT_ERR(pp_world_get_time(w, NULL), PP_ERR_INVALID_ARGUMENT, "NULL");
    pp_world_destroy(w);
    EXPECT_ERR(pp_world_get_time(w, &t), PP_ERR_INVALID_HANDLE, "stale");
}

Test(timed, an_erase_applies_at_the_step_nearest_its_time)
{
    pp_world w = make_world(0, 980);
    pp_body slab = add_slab(w);
    const pp_timed_edit e = {.time = 0.5, .type = PP_EDIT_ERASE_CIRCLE, .center = {100, 100}, .radius = 10};
    PP_OK_OR_FAIL(pp_world_schedule_edit(w, &e));
    const int64_t full = solid_pixels(w, slab);
    cr_assert_eq(full, 200 * 40);
    /* Step 30 starts at t = 29/60 < 0.5 − dt/2: untouched; step 31 starts at 30/60 = 0.5: applied. */
    for (int i = 0; i < 30; i++)
        PP_OK_OR_FAIL(pp_world_step(w, DT));
    cr_assert_eq(solid_pixels(w, slab), full, "the edit applied early");
    int32_t pending = 0;
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, NULL, 0, &pending));
    cr_assert_eq(pending, 1);
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    const int64_t erased = full - solid_pixels(w, slab);
    /* A disc of radius 10 by pixel centres: 316 pixels (π·10² ≈ 314). */
    cr_assert(erased >= 300 && erased <= 330, "erased %lld pixels", (long long)erased);
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, NULL, 0, &pending));
    cr_assert_eq(pending, 0);
    pp_world_destroy(w);
}

Test(timed, edits_apply_in_time_order_and_paint_refills)
{
    pp_world w = make_world(0, 0);
    pp_body slab = add_slab(w);
    /* Scheduled out of order: the erase at 0.1 must come before the paint at 0.2 refills it. */
    const pp_timed_edit paint = {.time = 0.2, .type = PP_EDIT_PAINT_CIRCLE, .weight = 255, .body = slab,
                                 .center = {50, 100}, .radius = 6};
    const pp_timed_edit erase = {.time = 0.1, .type = PP_EDIT_ERASE_CIRCLE, .body = slab, .center = {50, 100},
                                 .radius = 6};
    PP_OK_OR_FAIL(pp_world_schedule_edit(w, &paint));
    PP_OK_OR_FAIL(pp_world_schedule_edit(w, &erase));
    pp_timed_edit list[2];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, list, 2, &n));
    cr_assert(n == 2 && list[0].time == 0.1 && list[1].time == 0.2, "order %g %g", list[0].time, list[1].time);
    for (int i = 0; i < 9; i++)
        PP_OK_OR_FAIL(pp_world_step(w, DT));
    cr_assert_lt(solid_pixels(w, slab), 200 * 40, "the erase at 0.1 s has applied by 0.15 s");
    for (int i = 0; i < 6; i++)
        PP_OK_OR_FAIL(pp_world_step(w, DT));
    cr_assert_eq(solid_pixels(w, slab), 200 * 40, "the paint at 0.2 s refilled the hole");
    pp_world_destroy(w);
}

Test(timed, an_edit_whose_body_is_gone_is_skipped)
{
    pp_world w = make_world(0, 0);
    pp_body a = add_slab(w), b = add_slab(w);
    const pp_timed_edit e = {.time = 0, .type = PP_EDIT_ERASE_CIRCLE, .body = a, .center = {100, 100}, .radius = 5};
    PP_OK_OR_FAIL(pp_world_schedule_edit(w, &e));
    PP_OK_OR_FAIL(pp_body_destroy(w, a));
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    cr_assert_eq(solid_pixels(w, b), 200 * 40, "only the destroyed body was named");
    pp_world_destroy(w);
}

Test(timed, bad_edits_are_refused_with_their_reason)
{
    pp_world w = make_world(0, 0);
    pp_body slab = add_slab(w);
    pp_timed_edit e = {.time = 1, .type = PP_EDIT_ERASE_CIRCLE, .center = {0, 0}, .radius = 4};
    EXPECT_ERR(pp_world_schedule_edit(w, NULL), PP_ERR_INVALID_ARGUMENT, "NULL");
    e.time = NAN;
    EXPECT_ERR(pp_world_schedule_edit(w, &e), PP_ERR_INVALID_ARGUMENT, "finite");
    e.time = 1, e.radius = -1;
    EXPECT_ERR(pp_world_schedule_edit(w, &e), PP_ERR_INVALID_ARGUMENT, "radius");
    e.radius = 4, e.type = (pp_edit_type)9;
    EXPECT_ERR(pp_world_schedule_edit(w, &e), PP_ERR_INVALID_ARGUMENT, "unknown");
    e.type = PP_EDIT_PAINT_CIRCLE, e.weight = 255;
    EXPECT_ERR(pp_world_schedule_edit(w, &e), PP_ERR_INVALID_ARGUMENT, "needs a body");
    e.body = slab, e.weight = 0;
    EXPECT_ERR(pp_world_schedule_edit(w, &e), PP_ERR_INVALID_ARGUMENT, "1..255");
    e.weight = 255, e.body.id = slab.id + 7;
    EXPECT_ERR(pp_world_schedule_edit(w, &e), PP_ERR_INVALID_HANDLE, "stale");
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, NULL, 0, &n));
    cr_assert_eq(n, 0, "a refused edit left something behind");
    pp_world_destroy(w);
}

Test(timed, the_camera_defaults_and_is_checked)
{
    pp_world w = make_world(0, 0);
    pp_camera c;
    PP_OK_OR_FAIL(pp_world_get_camera(w, &c));
    cr_assert(c.center.x == 480 && c.center.y == 270 && c.zoom == 1 && c.width == 960 && c.height == 540);
    const pp_camera set = {{10, 20}, 2.5f, 320, 200};
    PP_OK_OR_FAIL(pp_world_set_camera(w, &set));
    PP_OK_OR_FAIL(pp_world_get_camera(w, &c));
    cr_assert(memcmp(&c, &set, sizeof c) == 0);
    pp_camera bad = set;
    bad.zoom = 0;
    EXPECT_ERR(pp_world_set_camera(w, &bad), PP_ERR_INVALID_ARGUMENT, "zoom");
    bad = set, bad.width = 0;
    EXPECT_ERR(pp_world_set_camera(w, &bad), PP_ERR_INVALID_ARGUMENT, "size");
    bad = set, bad.center.x = INFINITY;
    EXPECT_ERR(pp_world_set_camera(w, &bad), PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_world_set_camera(w, NULL), PP_ERR_INVALID_ARGUMENT, "NULL");
    PP_OK_OR_FAIL(pp_world_get_camera(w, &c));
    cr_assert(memcmp(&c, &set, sizeof c) == 0, "a refused camera changed the world's");
    pp_world_destroy(w);
}
