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

/* The worst contact normal, deg off the slope's, of a 12 px box dropped upright onto a static terrain whose
 * bitmap holds a slope of `deg` rising to the right (axis-aligned pixel steps), at eight places a pixel and an
 * eighth apart. The box lands on a corner and tumbles or slides down: every contact is the box on the slope. */
static double box_on_terrain_slope(double deg)
{
    const double th = deg * M_PI / 180, tn = tan(th);
    uint8_t *m = calloc(SLOPE_W * SLOPE_H, 1);
    cr_assert_not_null(m);
    for (int j = 0; j < SLOPE_H; j++)
        for (int i = 0; i < SLOPE_W; i++)
            m[j * SLOPE_W + i] = j + 0.5 > SLOPE_H - 10 - (i + 0.5) * tn;
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
