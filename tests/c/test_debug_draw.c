/* pp_world_debug_draw: outlines on the pixel edges (a box's 4 sides, an L's 6, turned with the body, rebuilt
 * after an edit), AABBs, centres and velocities, contact crosses at the points pp_world_get_contacts reports,
 * joints at the anchors pp_joint_get_anchors reports, the count against a short capacity, the view box, misuse. */
#include "helpers.h"

#include <float.h>

PP_TEST_SUITE(debug_draw);

#define DRAW_ALL_BOX(w, flags, out, cap, n)                                                                          \
    PP_OK_OR_FAIL(pp_world_debug_draw((w), (flags), v2(-FLT_MAX, -FLT_MAX), v2(FLT_MAX, FLT_MAX), (out), (cap), (n)))

/* A body from a mask, every other def field as given. */
static pp_body add_mask(pp_world w, pp_body_def d, const uint8_t *mask, int width, int height)
{
    d.width = width, d.height = height, d.mask = mask;
    return create_body_ok(w, &d);
}

/* Is there a segment from a to b (within tol px) among n? Each may be matched once: used[] marks them. */
static int find_segment(const pp_debug_segment *s, int n, bool *used, double ax, double ay, double bx, double by,
                        double tol)
{
    for (int k = 0; k < n; k++)
        if (!used[k] && fabs(s[k].a.x - ax) <= tol && fabs(s[k].a.y - ay) <= tol && fabs(s[k].b.x - bx) <= tol &&
            fabs(s[k].b.y - by) <= tol) {
            used[k] = true;
            return k;
        }
    return -1;
}

/* The outline of n segments is exactly the closed polygon through the world points p[0..m), clockwise on screen
 * (each segment from p[k] to p[k + 1]), within tol px. */
static void expect_polygon(const pp_debug_segment *s, int n, const double (*p)[2], int m, double tol)
{
    cr_assert_eq(n, m, "%d outline segments, expected %d", n, m);
    bool used[64] = {false};
    for (int k = 0; k < m; k++) {
        const double *a = p[k], *b = p[(k + 1) % m];
        cr_assert_geq(find_segment(s, n, used, a[0], a[1], b[0], b[1], tol), 0,
                      "no segment (%g, %g) -> (%g, %g)", a[0], a[1], b[0], b[1]);
    }
}

/* Bitmap point (x, y) of a body at pos, angle, pivot, in the world. */
static void world_of(double pos_x, double pos_y, double angle, double px, double py, double x, double y, double *out)
{
    const double c = cos(angle), s = sin(angle), lx = x - px, ly = y - py;
    out[0] = pos_x + c * lx - s * ly, out[1] = pos_y + s * lx + c * ly;
}

Test(debug_draw, a_16x16_box_is_exactly_its_four_edges)
{
    pp_world w = make_world(0, 0);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 50, 0), 16, 16);
    pp_debug_segment s[16];
    int32_t n = -1;
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_OUTLINES, s, 16, &n);
    /* The pivot is the bitmap centre: the box covers [92, 108] × [42, 58], clockwise from its top-left corner. */
    const double p[4][2] = {{92, 42}, {108, 42}, {108, 58}, {92, 58}};
    expect_polygon(s, n, p, 4, 0);
    for (int k = 0; k < n; k++) {
        cr_assert_eq(s[k].kind, PP_DEBUG_OUTLINE);
        cr_assert_eq(s[k].body.id, box.id);
        cr_assert_eq(s[k].rgba, PP_DEBUG_COLOR_AWAKE);
    }
    pp_world_destroy(w);
}

Test(debug_draw, a_turned_box_has_its_turned_corners)
{
    pp_world w = make_world(0, 0);
    const double angle = 0.3, x = 200.5, y = -40.25;
    add_rect(w, body_def(PP_BODY_STATIC, (float)x, (float)y, (float)angle), 16, 16);
    pp_debug_segment s[16];
    int32_t n = -1;
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_OUTLINES, s, 16, &n);
    double p[4][2];
    const double corner[4][2] = {{0, 0}, {16, 0}, {16, 16}, {0, 16}};
    /* The angle as the body holds it: a float. */
    for (int k = 0; k < 4; k++)
        world_of(x, y, (float)angle, 8, 8, corner[k][0], corner[k][1], p[k]);
    expect_polygon(s, n, p, 4, 1e-4);
    for (int k = 0; k < n; k++)
        cr_assert_eq(s[k].rgba, PP_DEBUG_COLOR_STATIC);
    pp_world_destroy(w);
}

Test(debug_draw, an_l_shaped_mask_is_six_segments)
{
    pp_world w = make_world(0, 0);
    uint8_t m[16 * 16];
    for (int j = 0; j < 16; j++)
        for (int i = 0; i < 16; i++)
            m[j * 16 + i] = !(i >= 8 && j < 8); /* the top-right quarter cut away */
    add_mask(w, body_def(PP_BODY_STATIC, 8, 8, 0), m, 16, 16); /* bitmap px = world px */
    pp_debug_segment s[16];
    int32_t n = -1;
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_OUTLINES, s, 16, &n);
    const double p[6][2] = {{0, 0}, {8, 0}, {8, 8}, {16, 8}, {16, 16}, {0, 16}};
    expect_polygon(s, n, p, 6, 0);
    pp_world_destroy(w);
}

Test(debug_draw, holes_and_pieces_are_outlined_each)
{
    pp_world w = make_world(0, 0);
    /* A 12×12 ring (a 4×4 hole in the middle) and, apart from it, a lone pixel: 4 + 4 + 4 runs. The two
     * pixels touching at a corner are 8 runs: runs end where the solid side changes. */
    uint8_t m[20 * 12] = {0};
    for (int j = 0; j < 12; j++)
        for (int i = 0; i < 12; i++)
            m[j * 20 + i] = !(i >= 4 && i < 8 && j >= 4 && j < 8);
    m[0 * 20 + 15] = 1;
    m[5 * 20 + 15] = 1, m[6 * 20 + 16] = 1;
    add_mask(w, body_def(PP_BODY_STATIC, 10, 6, 0), m, 20, 12);
    pp_debug_segment s[32];
    int32_t n = -1;
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_OUTLINES, s, 32, &n);
    cr_assert_eq(n, 4 + 4 + 4 + 8);
    bool used[32] = {false};
    /* The hole goes the other way round: solid on the right of each run as drawn. */
    cr_assert_geq(find_segment(s, n, used, 4, 4, 4, 8, 0), 0);
    cr_assert_geq(find_segment(s, n, used, 4, 8, 8, 8, 0), 0);
    cr_assert_geq(find_segment(s, n, used, 8, 8, 8, 4, 0), 0);
    cr_assert_geq(find_segment(s, n, used, 8, 4, 4, 4, 0), 0);
    /* The corner-touching pair: the row between them is two runs, one per pixel. */
    cr_assert_geq(find_segment(s, n, used, 16, 6, 15, 6, 0), 0);
    cr_assert_geq(find_segment(s, n, used, 16, 6, 17, 6, 0), 0);
    double perimeter = 0;
    for (int k = 0; k < n; k++)
        perimeter += hypot(s[k].b.x - s[k].a.x, s[k].b.y - s[k].a.y);
    cr_assert_float_eq(perimeter, 48 + 16 + 4 + 8, 0);
    pp_world_destroy(w);
}

Test(debug_draw, a_wide_body_is_outlined_across_word_boundaries)
{
    pp_world w = make_world(0, 0);
    /* 200 px wide (four 64-bit words a row), a notch at columns 60..70 of its top rows. */
    static uint8_t m[200 * 10];
    for (int j = 0; j < 10; j++)
        for (int i = 0; i < 200; i++)
            m[j * 200 + i] = !(i >= 60 && i < 70 && j < 3);
    add_mask(w, body_def(PP_BODY_STATIC, 100, 5, 0), m, 200, 10);
    pp_debug_segment s[16];
    int32_t n = -1;
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_OUTLINES, s, 16, &n);
    const double p[8][2] = {{0, 0}, {60, 0}, {60, 3}, {70, 3}, {70, 0}, {200, 0}, {200, 10}, {0, 10}};
    expect_polygon(s, n, p, 8, 0);
    pp_world_destroy(w);
}

Test(debug_draw, an_erase_changes_the_outline_at_the_next_call)
{
    pp_world w = make_world(0, 0);
    pp_body box = add_rect(w, body_def(PP_BODY_STATIC, 8, 8, 0), 16, 16);
    pp_debug_segment s[16];
    int32_t n = -1;
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_OUTLINES, s, 16, &n);
    cr_assert_eq(n, 4);
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_OUTLINES, s, 16, &n); /* from the cache: the same */
    const double square[4][2] = {{0, 0}, {16, 0}, {16, 16}, {0, 16}};
    expect_polygon(s, n, square, 4, 0);
    /* The top-left 4×4 corner erased: two more runs round the notch. */
    uint8_t none[16] = {0};
    PP_OK_OR_FAIL(pp_body_write_pixels(w, box, 0, 0, 4, 4, none, NULL));
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_OUTLINES, s, 16, &n);
    const double notched[6][2] = {{4, 0}, {16, 0}, {16, 16}, {0, 16}, {0, 4}, {4, 4}};
    expect_polygon(s, n, notched, 6, 0);
    /* Painted back, it is the square again; an erase by circle at the opposite corner notches it there. */
    uint8_t all[16];
    memset(all, 1, sizeof all);
    PP_OK_OR_FAIL(pp_body_write_pixels(w, box, 0, 0, 4, 4, all, NULL));
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_OUTLINES, s, 16, &n);
    expect_polygon(s, n, square, 4, 0);
    int32_t changed = 0;
    PP_OK_OR_FAIL(pp_body_erase_circle(w, box, v2(16, 16), 1.5f, &changed));
    cr_assert_eq(changed, 1, "the circle takes the corner pixel (15, 15) alone, took %d", changed);
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_OUTLINES, s, 16, &n);
    const double cut[6][2] = {{0, 0}, {16, 0}, {16, 15}, {15, 15}, {15, 16}, {0, 16}};
    expect_polygon(s, n, cut, 6, 0);
    pp_world_destroy(w);
}

Test(debug_draw, aabbs_centres_and_velocities)
{
    pp_world w = make_world(0, 0);
    const double angle = 0.3, x = 300, y = 200;
    pp_body_def d = body_def(PP_BODY_DYNAMIC, (float)x, (float)y, (float)angle);
    d.linear_velocity = v2(50, -20);
    pp_body box = add_rect(w, d, 32, 16);
    pp_debug_segment s[16];
    int32_t n = -1;
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_AABBS | PP_DEBUG_DRAW_CENTERS | PP_DEBUG_DRAW_VELOCITIES, s, 16, &n);
    cr_assert_eq(n, 4 + 2 + 1);
    /* AABB: the bounds of the turned corners. */
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    const double corner[4][2] = {{0, 0}, {32, 0}, {32, 16}, {0, 16}};
    for (int k = 0; k < 4; k++) {
        double p[2];
        world_of(x, y, (float)angle, 16, 8, corner[k][0], corner[k][1], p);
        x0 = fmin(x0, p[0]), y0 = fmin(y0, p[1]), x1 = fmax(x1, p[0]), y1 = fmax(y1, p[1]);
    }
    const double box_[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    for (int k = 0; k < 4; k++) {
        cr_assert_eq(s[k].kind, PP_DEBUG_AABB);
        cr_assert_eq(s[k].rgba, PP_DEBUG_COLOR_AWAKE);
        cr_assert_float_eq(s[k].a.x, box_[k][0], 1e-3);
        cr_assert_float_eq(s[k].a.y, box_[k][1], 1e-3);
        cr_assert_float_eq(s[k].b.x, box_[(k + 1) % 4][0], 1e-3);
        cr_assert_float_eq(s[k].b.y, box_[(k + 1) % 4][1], 1e-3);
    }
    /* The centre of mass of a full box is its pivot: axes along the turned bitmap x and y. */
    const double c = cos((float)angle), sn = sin((float)angle), L = PP_DEBUG_AXIS_LENGTH;
    cr_assert(s[4].kind == PP_DEBUG_CENTER && s[5].kind == PP_DEBUG_CENTER);
    cr_assert(s[4].rgba == PP_DEBUG_COLOR_AXIS_X && s[5].rgba == PP_DEBUG_COLOR_AXIS_Y);
    for (int k = 4; k < 7; k++) {
        cr_assert_float_eq(s[k].a.x, x, 1e-3);
        cr_assert_float_eq(s[k].a.y, y, 1e-3);
        cr_assert_eq(s[k].body.id, box.id);
    }
    cr_assert_float_eq(s[4].b.x, x + L * c, 1e-3);
    cr_assert_float_eq(s[4].b.y, y + L * sn, 1e-3);
    cr_assert_float_eq(s[5].b.x, x - L * sn, 1e-3);
    cr_assert_float_eq(s[5].b.y, y + L * c, 1e-3);
    cr_assert_eq(s[6].kind, PP_DEBUG_VELOCITY);
    cr_assert_float_eq(s[6].b.x, x + 50 * PP_DEBUG_VELOCITY_TIME, 1e-3);
    cr_assert_float_eq(s[6].b.y, y - 20 * PP_DEBUG_VELOCITY_TIME, 1e-3);
    /* A static body has no velocity to draw. */
    pp_world_destroy(w);
}

Test(debug_draw, colours_say_the_state)
{
    pp_world w = make_world(0, 0);
    pp_body stat = add_rect(w, body_def(PP_BODY_STATIC, 0, 0, 0), 8, 8);
    pp_body kin = add_rect(w, body_def(PP_BODY_KINEMATIC, 100, 0, 0), 8, 8);
    pp_body awake = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 0, 0), 8, 8);
    pp_body asleep = add_rect(w, body_def(PP_BODY_DYNAMIC, 300, 0, 0), 8, 8);
    pp_body_def sd = body_def(PP_BODY_STATIC, 400, 0, 0);
    sd.is_sensor = 1;
    pp_body sensor = add_rect(w, sd, 8, 8);
    PP_OK_OR_FAIL(pp_body_set_awake(w, asleep, 0));
    pp_debug_segment s[64];
    int32_t n = -1;
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_OUTLINES | PP_DEBUG_DRAW_VELOCITIES, s, 64, &n);
    /* In slot order: 4 outline runs each, and a velocity for the kinematic and dynamic ones. */
    cr_assert_eq(n, 5 * 4 + 3);
    const pp_body order[5] = {stat, kin, awake, asleep, sensor};
    const uint32_t colour[5] = {PP_DEBUG_COLOR_STATIC, PP_DEBUG_COLOR_KINEMATIC, PP_DEBUG_COLOR_AWAKE,
                                PP_DEBUG_COLOR_ASLEEP, PP_DEBUG_COLOR_SENSOR};
    int k = 0;
    for (int b = 0; b < 5; b++) {
        for (int r = 0; r < 4; r++, k++) {
            cr_assert_eq(s[k].body.id, order[b].id, "segment %d", k);
            cr_assert_eq(s[k].kind, PP_DEBUG_OUTLINE);
            cr_assert_eq(s[k].rgba, colour[b], "body %d: colour %08x, expected %08x", b, s[k].rgba, colour[b]);
        }
        if (b >= 1 && b <= 3) {
            cr_assert_eq(s[k].kind, PP_DEBUG_VELOCITY);
            cr_assert_eq(s[k++].body.id, order[b].id);
        }
    }
    pp_world_destroy(w);
}

Test(debug_draw, contact_crosses_sit_at_the_reported_points_along_the_reported_normals)
{
    pp_world w = make_world(0, 980);
    add_rect(w, body_def(PP_BODY_STATIC, 200, 300, 0), 400, 40);
    add_rect(w, body_def(PP_BODY_DYNAMIC, 150, 270, 0.2f), 24, 24);
    add_rect(w, body_def(PP_BODY_DYNAMIC, 260, 262, 0), 32, 32);
    step_n(w, 1.0f / 60, 30);
    pp_contact c[32];
    int32_t nc = 0;
    PP_OK_OR_FAIL(pp_world_get_contacts(w, c, 32, &nc));
    cr_assert_geq(nc, 2, "the boxes rest on the ground: %d contacts", nc);
    pp_debug_segment s[128];
    int32_t n = -1;
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_CONTACTS, s, 128, &n);
    cr_assert_eq(n, 3 * nc);
    const float h = PP_DEBUG_CROSS_SIZE;
    for (int i = 0; i < nc; i++) {
        const pp_vec2 p = c[i].point, nn = c[i].normal;
        const pp_debug_segment *x = &s[3 * i], *y = &s[3 * i + 1], *nrm = &s[3 * i + 2];
        cr_assert(x->kind == PP_DEBUG_CONTACT && y->kind == PP_DEBUG_CONTACT && nrm->kind == PP_DEBUG_NORMAL);
        cr_assert(x->rgba == PP_DEBUG_COLOR_CONTACT && nrm->rgba == PP_DEBUG_COLOR_NORMAL);
        cr_assert(x->body.id == c[i].a.id && nrm->body.id == c[i].a.id);
        /* The cross: exactly the point ± h along x and along y. */
        cr_assert(x->a.x == p.x - h && x->b.x == p.x + h && x->a.y == p.y && x->b.y == p.y);
        cr_assert(y->a.y == p.y - h && y->b.y == p.y + h && y->a.x == p.x && y->b.x == p.x);
        /* The normal: from the point, along the reported normal, PP_DEBUG_NORMAL_LENGTH long. */
        cr_assert(nrm->a.x == p.x && nrm->a.y == p.y);
        const double dx = nrm->b.x - p.x, dy = nrm->b.y - p.y, len = hypot(dx, dy);
        cr_assert_float_eq(len, PP_DEBUG_NORMAL_LENGTH, 1e-4);
        cr_assert_float_eq(dx / len, nn.x, 1e-5);
        cr_assert_float_eq(dy / len, nn.y, 1e-5);
    }
    /* Asleep, the pile still lists its contacts, and draws them. */
    step_n(w, 1.0f / 60, 240);
    PP_OK_OR_FAIL(pp_world_get_contacts(w, c, 32, &nc));
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_CONTACTS, s, 128, &n);
    cr_assert_eq(n, 3 * nc);
    for (int i = 0; i < nc; i++)
        cr_assert(s[3 * i].a.x == c[i].point.x - h && s[3 * i].a.y == c[i].point.y);
    pp_world_destroy(w);
}

/* The world point of a full box's centre of mass: its pivot. */
static pp_vec2 com_of(pp_world w, pp_body b) { return body_pos(w, b); }

Test(debug_draw, joints_are_drawn_at_the_anchors_the_joint_reports)
{
    pp_world w = make_world(0, 980);
    pp_body a = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 20);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 130, 100, 0), 20, 20);
    pp_joint_def rd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    rd.body_b = a, rd.anchor_a = v2(90, 80); /* a hung from the world */
    pp_joint hinge, rope, mouse;
    PP_OK_OR_FAIL(pp_joint_create(w, &rd, &hinge));
    pp_joint_def dd = pp_joint_def_default(PP_JOINT_DISTANCE);
    dd.body_a = a, dd.body_b = b, dd.anchor_a = v2(105, 95), dd.anchor_b = v2(125, 102);
    PP_OK_OR_FAIL(pp_joint_create(w, &dd, &rope));
    pp_joint_def md = pp_joint_def_default(PP_JOINT_MOUSE);
    md.body_b = b, md.anchor_a = v2(160, 60);
    PP_OK_OR_FAIL(pp_joint_create(w, &md, &mouse));
    /* Before a step the anchors are the def's. */
    pp_vec2 pa, pb;
    PP_OK_OR_FAIL(pp_joint_get_anchors(w, rope, &pa, &pb));
    cr_assert_float_eq(pa.x, 105, 1e-4);
    cr_assert_float_eq(pa.y, 95, 1e-4);
    cr_assert_float_eq(pb.x, 125, 1e-4);
    cr_assert_float_eq(pb.y, 102, 1e-4);
    PP_OK_OR_FAIL(pp_joint_get_anchors(w, mouse, &pa, NULL));
    cr_assert(pa.x == 160 && pa.y == 60, "a mouse joint's anchor_a is its target");
    step_n(w, 1.0f / 60, 20);

    pp_debug_segment s[16];
    int32_t n = -1;
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_JOINTS, s, 16, &n);
    /* The hinge and the mouse hold one body and the world: 2 segments; the rope 3. */
    cr_assert_eq(n, 2 + 3 + 2);
    const pp_joint joints[3] = {hinge, rope, mouse};
    int k = 0;
    for (int j = 0; j < 3; j++) {
        pp_body ja, jb;
        PP_OK_OR_FAIL(pp_joint_get_bodies(w, joints[j], &ja, &jb));
        PP_OK_OR_FAIL(pp_joint_get_anchors(w, joints[j], &pa, &pb));
        cr_assert(s[k].kind == PP_DEBUG_JOINT && s[k].rgba == PP_DEBUG_COLOR_JOINT);
        cr_assert(s[k].a.x == pa.x && s[k].a.y == pa.y && s[k].b.x == pb.x && s[k].b.y == pb.y,
                  "joint %d: (%g, %g) -> (%g, %g), anchors (%g, %g), (%g, %g)", j, s[k].a.x, s[k].a.y, s[k].b.x,
                  s[k].b.y, pa.x, pa.y, pb.x, pb.y);
        cr_assert_eq(s[k].body.id, jb.id);
        k++;
        const pp_body side[2] = {ja, jb};
        const pp_vec2 anchor[2] = {pa, pb};
        for (int e = 0; e < 2; e++) {
            if (!side[e].id)
                continue;
            const pp_vec2 com = com_of(w, side[e]);
            cr_assert_eq(s[k].body.id, side[e].id);
            cr_assert_float_eq(s[k].a.x, com.x, 1e-3);
            cr_assert_float_eq(s[k].a.y, com.y, 1e-3);
            cr_assert(s[k].b.x == anchor[e].x && s[k].b.y == anchor[e].y);
            k++;
        }
    }
    /* The bodies moved: the anchors moved with them. */
    PP_OK_OR_FAIL(pp_joint_get_anchors(w, rope, &pa, &pb));
    cr_assert(fabsf(pa.y - 95) > 0.5f, "the rope's anchor on a stayed at (%g, %g)", pa.x, pa.y);
    pp_world_destroy(w);
}

Test(debug_draw, a_short_capacity_writes_only_capacity_and_counts_all)
{
    pp_world w = make_world(0, 0);
    add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 16, 16);
    add_rect(w, body_def(PP_BODY_STATIC, 200, 100, 0), 16, 16);
    pp_debug_segment full[64];
    int32_t total = -1;
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_ALL, full, 64, &total);
    cr_assert_eq(total, (4 + 4 + 2 + 1) + (4 + 4 + 2));
    int32_t n = -1;
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_ALL, NULL, 0, &n);
    cr_assert_eq(n, total);
    pp_debug_segment s[64];
    memset(s, 0xab, sizeof s);
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_ALL, s, 5, &n);
    cr_assert_eq(n, total);
    cr_assert(memcmp(s, full, 5 * sizeof *s) == 0);
    const uint8_t *rest = (const uint8_t *)&s[5];
    for (size_t k = 0; k < (64 - 5) * sizeof *s; k++)
        cr_assert_eq(rest[k], 0xab, "byte %zu past capacity written", k);
    /* No flag, nothing. */
    DRAW_ALL_BOX(w, 0, s, 64, &n);
    cr_assert_eq(n, 0);
    pp_world_destroy(w);
}

Test(debug_draw, the_view_box_keeps_what_meets_it)
{
    pp_world w = make_world(0, 0);
    pp_body in = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 16, 16);
    add_rect(w, body_def(PP_BODY_DYNAMIC, 1000, 100, 0), 16, 16);
    pp_debug_segment s[64];
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_debug_draw(w, PP_DEBUG_DRAW_ALL, v2(0, 0), v2(200, 200), s, 64, &n));
    cr_assert_eq(n, 4 + 4 + 2 + 1);
    for (int k = 0; k < n; k++)
        cr_assert_eq(s[k].body.id, in.id);
    /* A box touching nothing, and a box touching the body's corner (closed). */
    PP_OK_OR_FAIL(pp_world_debug_draw(w, PP_DEBUG_DRAW_ALL, v2(300, 300), v2(400, 400), s, 64, &n));
    cr_assert_eq(n, 0);
    PP_OK_OR_FAIL(pp_world_debug_draw(w, PP_DEBUG_DRAW_OUTLINES, v2(108, 108), v2(120, 120), s, 64, &n));
    cr_assert_eq(n, 2, "the corner (108, 108) meets the right and bottom runs: %d", n);
    /* A long bar seen at its left end: its top, bottom and left runs, not its far right one. */
    add_rect(w, body_def(PP_BODY_STATIC, 2200, 500, 0), 400, 16);
    PP_OK_OR_FAIL(pp_world_debug_draw(w, PP_DEBUG_DRAW_OUTLINES, v2(1990, 480), v2(2050, 520), s, 64, &n));
    cr_assert_eq(n, 3);
    for (int k = 0; k < n; k++)
        cr_assert(s[k].a.x < 2050 || s[k].b.x < 2050);
    /* A world box as large as floats go sees everything. */
    DRAW_ALL_BOX(w, PP_DEBUG_DRAW_OUTLINES, s, 64, &n);
    cr_assert_eq(n, 12);
    pp_world_destroy(w);
}

Test(debug_draw, contacts_and_joints_are_culled_by_their_points)
{
    pp_world w = make_world(0, 0);
    pp_body a = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 16, 16);
    pp_joint_def md = pp_joint_def_default(PP_JOINT_MOUSE);
    md.body_b = a, md.anchor_a = v2(500, 100);
    pp_joint j;
    PP_OK_OR_FAIL(pp_joint_create(w, &md, &j));
    pp_debug_segment s[8];
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_debug_draw(w, PP_DEBUG_DRAW_JOINTS, v2(490, 90), v2(510, 110), s, 8, &n));
    cr_assert_eq(n, 2, "the target is in the box");
    PP_OK_OR_FAIL(pp_world_debug_draw(w, PP_DEBUG_DRAW_JOINTS, v2(200, 90), v2(300, 110), s, 8, &n));
    cr_assert_eq(n, 0, "neither anchor is in the box, though the segment crosses it");
    pp_world_destroy(w);
}

Test(debug_draw, misuse_is_refused_and_writes_nothing)
{
    pp_world w = make_world(0, 0);
    pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 16, 16);
    pp_debug_segment s[8];
    int32_t n = 77;
    const pp_vec2 lo = v2(-1000, -1000), hi = v2(1000, 1000);
    EXPECT_ERR(pp_world_debug_draw(w, PP_DEBUG_DRAW_ALL, lo, hi, s, 8, NULL), PP_ERR_INVALID_ARGUMENT, "count");
    EXPECT_ERR(pp_world_debug_draw(w, PP_DEBUG_DRAW_ALL, lo, hi, s, -1, &n), PP_ERR_INVALID_ARGUMENT, "capacity");
    EXPECT_ERR(pp_world_debug_draw(w, PP_DEBUG_DRAW_ALL, lo, hi, NULL, 8, &n), PP_ERR_INVALID_ARGUMENT, "out");
    EXPECT_ERR(pp_world_debug_draw(w, PP_DEBUG_DRAW_ALL | (1u << 6), lo, hi, s, 8, &n), PP_ERR_INVALID_ARGUMENT,
               "flags");
    EXPECT_ERR(pp_world_debug_draw(w, 0x80000000u, lo, hi, s, 8, &n), PP_ERR_INVALID_ARGUMENT, "flags");
    EXPECT_ERR(pp_world_debug_draw(w, PP_DEBUG_DRAW_ALL, v2(NAN, 0), hi, s, 8, &n), PP_ERR_INVALID_ARGUMENT,
               "finite");
    EXPECT_ERR(pp_world_debug_draw(w, PP_DEBUG_DRAW_ALL, lo, v2(0, INFINITY), s, 8, &n), PP_ERR_INVALID_ARGUMENT,
               "finite");
    EXPECT_ERR(pp_world_debug_draw(w, PP_DEBUG_DRAW_ALL, v2(-INFINITY, -INFINITY), v2(INFINITY, INFINITY), s, 8, &n),
               PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_world_debug_draw(w, PP_DEBUG_DRAW_ALL, v2(10, 0), v2(5, 100), s, 8, &n), PP_ERR_INVALID_ARGUMENT,
               "lower");
    EXPECT_ERR(pp_world_debug_draw(w, PP_DEBUG_DRAW_ALL, v2(0, 10), v2(100, 5), s, 8, &n), PP_ERR_INVALID_ARGUMENT,
               "lower");
    EXPECT_ERR(pp_world_debug_draw((pp_world){0}, PP_DEBUG_DRAW_ALL, lo, hi, s, 8, &n), PP_ERR_INVALID_HANDLE,
               "world");
    EXPECT_ERR(pp_world_debug_draw((pp_world){b.id}, PP_DEBUG_DRAW_ALL, lo, hi, s, 8, &n), PP_ERR_INVALID_HANDLE,
               "world|handle");
    cr_assert_eq(n, 77, "a refused call wrote count");
    pp_world other = make_world(0, 0);
    pp_world_destroy(other);
    EXPECT_ERR(pp_world_debug_draw(other, PP_DEBUG_DRAW_ALL, lo, hi, s, 8, &n), PP_ERR_INVALID_HANDLE,
               "world|stale|destroyed");
    cr_assert_eq(n, 77);
    /* pp_joint_get_anchors: nowhere to write, a stale joint. */
    pp_joint_def md = pp_joint_def_default(PP_JOINT_MOUSE);
    md.body_b = b, md.anchor_a = v2(100, 100);
    pp_joint j;
    PP_OK_OR_FAIL(pp_joint_create(w, &md, &j));
    EXPECT_ERR(pp_joint_get_anchors(w, j, NULL, NULL), PP_ERR_INVALID_ARGUMENT, "anchor_a");
    PP_OK_OR_FAIL(pp_joint_destroy(w, j));
    pp_vec2 pa = v2(7, 7);
    EXPECT_ERR(pp_joint_get_anchors(w, j, &pa, NULL), PP_ERR_INVALID_HANDLE, "joint");
    cr_assert(pa.x == 7 && pa.y == 7);
    pp_world_destroy(w);
}
