/* What renderers read: a body's look (its sprite where solid, carried into split pieces), its pivot
 * and type, and a colliding pair's sampled grid (the poster's Figure 1c) against the contacts. */
#include "helpers.h"

PP_TEST_SUITE(view);

/* A 200×40 static ground centred at (100, 100) (top at y = 80) and a 32×32 box sunk 3 px into it. */
static void box_on_ground(pp_world w, pp_body *ground, pp_body *box)
{
    uint8_t *g = rect_mask(200, 40), *b = rect_mask(32, 32);
    pp_body_def d = body_def(PP_BODY_STATIC, 100, 100, 0);
    d.width = 200, d.height = 40, d.mask = g;
    *ground = create_body_ok(w, &d);
    d = body_def(PP_BODY_DYNAMIC, 100, 80 - 16 + 3, 0);
    d.width = 32, d.height = 32, d.mask = b;
    *box = create_body_ok(w, &d);
    free(g);
    free(b);
}

Test(view, the_grid_matches_the_contacts_of_a_box_on_the_ground)
{
    pp_world_def wd = pp_world_def_default();
    wd.normal_method = PP_NORMAL_KERNEL;
    pp_world w = make_world_def(&wd);
    pp_body ground, box;
    box_on_ground(w, &ground, &box);
    pp_contact c[4];
    int32_t nc = 0;
    PP_OK_OR_FAIL(pp_world_collide(w, box, ground, c, 4, &nc));
    cr_assert_gt(nc, 0);

    pp_collision_view v;
    static uint8_t cells[64 * 64];
    static pp_vec2 normals[64 * 64];
    PP_OK_OR_FAIL(pp_world_debug_collision(w, box, ground, cells, normals, 64 * 64, &v));
    cr_assert(v.width > 0 && v.height > 0 && (int64_t)v.width * v.height <= 64 * 64);
    /* The intersection is 32 × 3 pixels, as the contacts count it; the normal is theirs. */
    cr_assert_eq(v.intersection, c[0].pixel_count, "grid %d vs contacts %d", v.intersection, c[0].pixel_count);
    cr_assert_eq(v.intersection, 32 * 3);
    cr_assert(v.normal.x == c[0].normal.x && v.normal.y == c[0].normal.y);
    cr_assert(fabsf(v.normal.y - 1) < 1e-6f, "normal (%g, %g) should point down into the ground", v.normal.x, v.normal.y);
    int a_only = 0, crit = 0, inter = 0;
    double sx = 0, sy = 0;
    for (int k = 0; k < v.width * v.height; k++) {
        const uint8_t f = cells[k];
        a_only += (f & 3) == PP_CELL_A;
        inter += (f & 3) == 3;
        if (f & PP_CELL_CRITICAL) {
            crit++;
            cr_assert_eq(f & 3, 3, "a critical cell must be in the intersection");
            cr_assert(fabsf(hypotf(normals[k].x, normals[k].y) - 1) < 1e-5f || (normals[k].x == 0 && normals[k].y == 0));
            sx += normals[k].x, sy += normals[k].y;
            /* Each intersection cell's centre lies in the 3 px band under the ground's top. */
            const int i = k % v.width, j = k / v.width;
            const float cy = v.origin.y + i * v.step_x.y + j * v.step_y.y;
            cr_assert(cy > 80 && cy < 83, "critical cell centre y %g outside the overlap", cy);
        } else {
            cr_assert(normals[k].x == 0 && normals[k].y == 0, "only critical cells have local normals");
        }
    }
    cr_assert_eq(inter, v.intersection);
    cr_assert_eq(crit, v.critical);
    cr_assert(crit > 0 && crit <= inter);
    cr_assert_eq(a_only, 0, "the grid is bounded by the box, which the ground covers below its top");
    /* The local normals sum along the global normal (the kernel method is their sum). */
    const double ang = RAD2DEG(fabs(atan2(sx * v.normal.y - sy * v.normal.x, sx * v.normal.x + sy * v.normal.y)));
    cr_assert_lt(ang, 1.0, "summed local normals %.2f° off the global normal", ang);

    /* Swapping the pair swaps the flags and turns the normal. */
    static uint8_t swapped[64 * 64];
    pp_collision_view v2_;
    PP_OK_OR_FAIL(pp_world_debug_collision(w, ground, box, swapped, NULL, 64 * 64, &v2_));
    cr_assert(v2_.width == v.width && v2_.height == v.height && v2_.normal.y == -v.normal.y);
    for (int k = 0; k < v.width * v.height; k++)
        cr_assert_eq(swapped[k], (cells[k] & 4) | (cells[k] & 1) << 1 | (cells[k] & 2) >> 1);
    pp_world_destroy(w);
}

Test(view, apart_bodies_give_an_empty_grid_and_misuse_is_refused)
{
    pp_world w = make_world(0, 980);
    pp_body ground, box;
    box_on_ground(w, &ground, &box);
    pp_collision_view v;
    uint8_t cell;
    EXPECT_ERR(pp_world_debug_collision(w, box, ground, &cell, NULL, 1, &v), PP_ERR_INVALID_ARGUMENT, "capacity");
    cr_assert(v.width > 0 && v.height > 0, "a short capacity still reports the grid's size");
    EXPECT_ERR(pp_world_debug_collision(w, box, box, &cell, NULL, 1, &v), PP_ERR_INVALID_ARGUMENT, "same body");
    EXPECT_ERR(pp_world_debug_collision(w, box, ground, &cell, NULL, 1, NULL), PP_ERR_INVALID_ARGUMENT, "NULL");
    PP_OK_OR_FAIL(pp_body_set_transform(w, box, v2(100, 0), 0));
    PP_OK_OR_FAIL(pp_world_debug_collision(w, box, ground, NULL, NULL, 0, &v));
    cr_assert(v.width == 0 && v.height == 0 && v.intersection == 0 && v.normal.x == 0 && v.normal.y == 0);
    pp_body gone = box;
    PP_OK_OR_FAIL(pp_body_destroy(w, box));
    EXPECT_ERR(pp_world_debug_collision(w, gone, ground, NULL, NULL, 0, &v), PP_ERR_INVALID_HANDLE, "stale");
    pp_world_destroy(w);
}

/* Sprite pixel (x, y) of a 40×8 bar: colour from x, alpha 255 except a transparent first column. */
static void bar_pixel(int x, int y, uint8_t *p)
{
    p[0] = (uint8_t)(6 * x), p[1] = (uint8_t)(30 * y), p[2] = 77, p[3] = x == 0 ? 0 : 255;
}

Test(view, the_look_is_the_sprite_where_solid_and_split_pieces_keep_theirs)
{
    pp_world w = make_world(0, 0);
    enum { BW = 40, BH = 8 };
    static uint8_t sprite[BW * BH * 4], look[BW * BH * 4];
    for (int y = 0; y < BH; y++)
        for (int x = 0; x < BW; x++)
            bar_pixel(x, y, sprite + 4 * (y * BW + x));
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 100, 100, 0);
    d.width = BW, d.height = BH, d.rgba = sprite, d.custom_pivot = 1, d.pivot = v2(3, 4);
    pp_body bar = create_body_ok(w, &d);
    pp_vec2 pivot;
    pp_body_type type;
    PP_OK_OR_FAIL(pp_body_get_pivot(w, bar, &pivot));
    PP_OK_OR_FAIL(pp_body_get_type(w, bar, &type));
    cr_assert(pivot.x == 3 && pivot.y == 4 && type == PP_BODY_DYNAMIC);
    PP_OK_OR_FAIL(pp_body_read_rgba(w, bar, look, sizeof look));
    for (int y = 0; y < BH; y++)
        for (int x = 0; x < BW; x++) {
            const uint8_t *p = sprite + 4 * (y * BW + x), clear[4] = {0, 0, 0, 0};
            cr_assert_arr_eq(look + 4 * (y * BW + x), x == 0 ? clear : p, 4,
                             "pixel (%d,%d): the sprite where solid, clear where its alpha is under the threshold", x, y);
        }

    /* Cut it at x = 20: the left piece stays, the right one becomes a new body with its own colours. */
    for (int y = 0; y < BH; y++)
        PP_OK_OR_FAIL(pp_body_erase_circle(w, bar, v2(100 - 3 + 20.5f, 100 - 4 + y + 0.5f), 0.5f, NULL));
    pp_event ev[4];
    int32_t ne = 0;
    PP_OK_OR_FAIL(pp_world_get_events(w, ev, 4, &ne));
    cr_assert(ne == 1 && ev[0].type == PP_EVENT_BODY_SPLIT, "%d events", ne);
    PP_OK_OR_FAIL(pp_body_read_rgba(w, bar, look, sizeof look));
    for (int x = 20; x < BW; x++)
        cr_assert_eq(look[4 * x + 3], 0, "column %d left the parent, so it is transparent there", x);
    int32_t cw, ch;
    PP_OK_OR_FAIL(pp_body_get_size(w, ev[0].other, &cw, &ch));
    cr_assert(cw == 19 && ch == BH, "piece %dx%d", cw, ch);
    uint8_t piece[19 * BH * 4], want[4];
    PP_OK_OR_FAIL(pp_body_read_rgba(w, ev[0].other, piece, sizeof piece));
    for (int y = 0; y < BH; y++)
        for (int x = 0; x < 19; x++) {
            bar_pixel(21 + x, y, want);
            cr_assert_arr_eq(piece + 4 * (y * 19 + x), want, 4, "piece pixel (%d,%d)", x, y);
        }
    EXPECT_ERR(pp_body_read_rgba(w, bar, look, 16), PP_ERR_INVALID_ARGUMENT, "capacity");
    EXPECT_ERR(pp_body_get_pivot(w, bar, NULL), PP_ERR_INVALID_ARGUMENT, "NULL");
    EXPECT_ERR(pp_body_get_type(w, bar, NULL), PP_ERR_INVALID_ARGUMENT, "NULL");
    pp_world_destroy(w);
}

Test(view, a_body_without_a_sprite_looks_gray_by_weight)
{
    pp_world w = make_world(0, 0);
    uint8_t mask[4] = {1, 1, 0, 1}, weights[4] = {10, 200, 50, 255}, look[16];
    pp_body_def d = body_def(PP_BODY_STATIC, 0, 0, 0);
    d.width = 2, d.height = 2, d.mask = mask, d.weights = weights;
    pp_body b = create_body_ok(w, &d);
    PP_OK_OR_FAIL(pp_body_read_rgba(w, b, look, sizeof look));
    const uint8_t want[16] = {10, 10, 10, 255, 200, 200, 200, 255, 0, 0, 0, 0, 255, 255, 255, 255};
    cr_assert_arr_eq(look, want, 16);
    pp_body_type type;
    PP_OK_OR_FAIL(pp_body_get_type(w, b, &type));
    cr_assert_eq(type, PP_BODY_STATIC);
    pp_world_destroy(w);
}
