/* A corner resting on a face, stepped: the contact must push along the face's normal. Where the two bodies
 * meet through a pixel or two the intersection raster alone can point far off the face (a card house's flat
 * card slid off the card corners it rested on), so the step re-picks such a normal from the bodies' faces;
 * a terrain drawn in its bitmap has no faces along its bitmap axes, and a slope keeps its own normal. */
#include "helpers.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

PP_TEST_SUITE(corners);

#define DT (1.0f / 60.0f)

/* The worst angle, deg, between any contact's normal and the line of unit vector (nx, ny) over `frames`. */
static double worst_normal_deg(pp_world w, int frames, double nx, double ny)
{
    double worst = 0;
    for (int f = 0; f < frames; f++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        pp_contact c[16];
        int32_t n = 0;
        PP_OK_OR_FAIL(pp_world_get_contacts(w, c, 16, &n));
        for (int i = 0; i < n; i++)
            worst = fmax(worst, acos(fmin(1.0, fabs(c[i].normal.x * nx + c[i].normal.y * ny))) * 180 / M_PI);
    }
    return worst;
}

/* A flat card resting on the top corners of two tilted cards, as in a card house: each corner meets the
 * flat's face through a pixel or two, where the intersection raster alone gave a normal 28° and then 66° off
 * the face, and the flat slid off. Its contacts push along its face's normal, and it stays put. */
Test(corners, a_flat_card_on_two_card_corners_is_held_by_its_face_normal, .timeout = 30)
{
    const float tilt = 15 * (float)M_PI / 180, corner_dx = 3.175f, corner_dy = 15.714f; /* a 2 × 32 card's top corner */
    pp_world_def d = pp_world_def_default();
    d.allow_sleep = 0;
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 385.3f + corner_dx, 300 + corner_dy, -tilt), 2, 32);
    add_rect(w, body_def(PP_BODY_STATIC, 414.7f - corner_dx, 300 + corner_dy, tilt), 2, 32);
    pp_body_def fd = body_def(PP_BODY_DYNAMIC, 400, 299, 0);
    fd.friction = 1.0f;
    const pp_body flat = add_rect(w, fd, 32, 2);
    const double worst = worst_normal_deg(w, 60, 0, 1);
    const pp_vec2 p = body_pos(w, flat);
    cr_log_info("flat on two card corners: normals within %.1f deg of its face's, moved (%.2f, %.2f) px, turned %.3f rad",
                worst, p.x - 400, p.y - 299, body_angle(w, flat));
    cr_assert_lt(worst, 5.0, "a contact's normal lay %.1f deg off the flat's face", worst);
    cr_assert_lt(fabs(p.x - 400), 0.5, "the flat slid %.2f px along its face", p.x - 400);
    pp_world_destroy(w);
}

#define SLOPE_W 200
#define SLOPE_H 160

/* A SLOPE_W × SLOPE_H terrain bitmap holding a slope of `deg` rising to the right (axis-aligned pixel steps);
 * the caller frees it. */
static uint8_t *slope_mask(double deg)
{
    const double tn = tan(deg * M_PI / 180);
    uint8_t *m = calloc(SLOPE_W * SLOPE_H, 1);
    cr_assert_not_null(m);
    for (int j = 0; j < SLOPE_H; j++)
        for (int i = 0; i < SLOPE_W; i++)
            m[j * SLOPE_W + i] = j + 0.5 > SLOPE_H - 10 - (i + 0.5) * tn;
    return m;
}

/* The worst contact normal, deg off the slope's, of a 12 px box dropped upright onto a static terrain whose
 * bitmap holds a slope of `deg` rising to the right (axis-aligned pixel steps), at eight places a pixel and an
 * eighth apart. The box lands on a corner and tumbles or slides down: every contact is the box on the slope. */
static double box_on_terrain_slope(double deg)
{
    const double th = deg * M_PI / 180, tn = tan(th);
    uint8_t *m = slope_mask(deg);
    double worst = 0;
    for (int k = 0; k < 8; k++) {
        pp_world_def d = pp_world_def_default();
        d.allow_sleep = 0;
        pp_world w = make_world_def(&d);
        pp_body_def td = body_def(PP_BODY_STATIC, 0.5f * SLOPE_W, 0.5f * SLOPE_H, 0);
        td.width = SLOPE_W, td.height = SLOPE_H, td.mask = m;
        create_body_ok(w, &td);
        const double x = 90 + 1.125 * k, surface = SLOPE_H - 10 - x * tn; /* under the box's centre */
        add_rect(w, body_def(PP_BODY_DYNAMIC, (float)x, (float)(surface - 8 - 6 * tn), 0), 12, 12); /* 2 px up */
        worst = fmax(worst, worst_normal_deg(w, 40, -sin(th), -cos(th)));
        pp_world_destroy(w);
    }
    free(m);
    return worst;
}

/* A terrain's bitmap axes are no faces of its slope: a corner on it keeps the slope's normal. */
Test(corners, a_box_on_a_slope_drawn_in_a_terrain_bitmap_pushes_along_the_slope, .timeout = 60)
{
    static const double slopes[] = {15, 30, 45};
    for (int i = 0; i < 3; i++) {
        const double worst = box_on_terrain_slope(slopes[i]);
        cr_log_info("box on a %.0f deg terrain slope: normals within %.1f deg of the slope's", slopes[i], worst);
        cr_expect_lt(worst, 12.0, "on the %.0f deg slope a contact's normal lay %.1f deg off the slope's", slopes[i],
                     worst);
    }
}

/* Two thin cards pushed together end to end, turned by `deg`: the first step's contact normals, worst angle off
 * the cards' thin axis (deg), and where the second card went relative to the first, in the cards' frame. */
static double thin_cards_end_to_end(double deg, double *along, double *across)
{
    const double th = deg * M_PI / 180, c = cos(th), s = sin(th), pitch = 52; /* 64 px cards overlap 12 px */
    pp_world_def d = pp_world_def_default();
    d.gravity = v2(0, 0);
    d.substeps = 1; /* the contacts read after the first step are the deep pair's */
    pp_world w = make_world_def(&d);
    pp_body_def da = body_def(PP_BODY_DYNAMIC, 300, 300, (float)th), db = da;
    db.position = v2((float)(300 + pitch * c), (float)(300 + pitch * s));
    const pp_body a = add_rect(w, da, 64, 2), b = add_rect(w, db, 64, 2);
    const double worst = worst_normal_deg(w, 1, -s, c);
    step_n(w, DT, 29);
    const pp_vec2 pa = body_pos(w, a), pb = body_pos(w, b);
    const double dx = pb.x - pa.x, dy = pb.y - pa.y;
    *along = dx * c + dy * s, *across = -dx * s + dy * c;
    pp_world_destroy(w);
    return worst;
}

/* Two thin bodies at the same height overlap through a strip 12 px long and 2 px thick: the area gradient
 * cancels across the thin axis and points along the cards (normal (1, 0), depth 12: they were pushed 12 px
 * apart along their length, as a card house's flats were). Deeper than a few pixels, the normal is the face
 * axis of least overlap, perpendicular ones included: they part across their thickness and keep their places
 * along it (within the push of the thin overlap left after the first step, whose raster normal leans 7°). */
Test(corners, thin_cards_pushed_end_to_end_part_across_their_thickness, .timeout = 30)
{
    static const double angles[] = {0, 30};
    for (int i = 0; i < 2; i++) {
        double along, across;
        const double worst = thin_cards_end_to_end(angles[i], &along, &across);
        cr_log_info("thin cards end to end at %.0f deg: normals within %.2f deg of the thin axis; after 0.5 s "
                    "%.2f px apart along, %.2f across", angles[i], worst, along, across);
        cr_expect_lt(worst, 1.0, "at %.0f deg a normal lay %.1f deg off the cards' thin axis", angles[i], worst);
        cr_expect_float_eq(along, 52.0, 2.0, "at %.0f deg the cards were pushed %.2f px apart along their length",
                           angles[i], along - 52.0);
        cr_expect_geq(fabs(across), 1.5, "at %.0f deg the cards parted only %.2f px across", angles[i], across);
    }
}

/* The contacts of a `size` px box set `deep` px into a static terrain bitmap holding a slope of `deg`, after one
 * step without gravity: the worst normal off the slope's (deg) and the deepest depth (px). */
static double deep_box_on_terrain_slope(double deg, double deep, double *depth)
{
    const double th = deg * M_PI / 180, tn = tan(th);
    uint8_t *m = slope_mask(deg);
    pp_world_def d = pp_world_def_default();
    d.gravity = v2(0, 0);
    d.substeps = 1; /* the contacts read after the first step are those found `deep` px deep */
    pp_world w = make_world_def(&d);
    pp_body_def td = body_def(PP_BODY_STATIC, 0.5f * SLOPE_W, 0.5f * SLOPE_H, 0);
    td.width = SLOPE_W, td.height = SLOPE_H, td.mask = m;
    create_body_ok(w, &td);
    free(m);
    /* The box turned with the slope, its bottom face `deep` px under the surface. */
    const double x = 100, surface = SLOPE_H - 10 - x * tn, h = 8 - deep;
    add_rect(w, body_def(PP_BODY_DYNAMIC, (float)(x - h * sin(th)), (float)(surface - h * cos(th)), (float)-th), 16, 16);
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    pp_contact c[4];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_contacts(w, c, 4, &n));
    cr_assert_gt(n, 0, "the box sunk into the slope has no contact");
    double worst = 0;
    *depth = 0;
    for (int i = 0; i < n; i++) {
        worst = fmax(worst, acos(fmin(1.0, fabs(-c[i].normal.x * sin(th) - c[i].normal.y * cos(th)))) * 180 / M_PI);
        *depth = fmax(*depth, c[i].depth);
    }
    pp_world_destroy(w);
    return worst;
}

/* A deep pair chooses among the raster's normal and the bodies' axes: a box sunk into a slope drawn in a terrain
 * bitmap (whose axes are no faces of it) keeps the slope's normal and its depth. */
Test(corners, a_box_sunk_deep_into_a_terrain_slope_keeps_the_slope_normal, .timeout = 30)
{
    static const double slopes[] = {0, 15, 30};
    for (int i = 0; i < 3; i++) {
        double depth;
        const double worst = deep_box_on_terrain_slope(slopes[i], 6, &depth);
        cr_log_info("box 6 px into a %.0f deg terrain slope: normals within %.1f deg of the slope's, depth %.2f px",
                    slopes[i], worst, depth);
        cr_expect_lt(worst, 5.0, "on the %.0f deg slope a normal lay %.1f deg off the slope's", slopes[i], worst);
        cr_expect_float_eq(depth, 6.0, 1.5, "on the %.0f deg slope the depth was %.2f px, not 6", slopes[i], depth);
    }
}
