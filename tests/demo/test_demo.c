/* The demo's output after the short headless run `make test-demo` makes: every expected frame exists,
 * has the camera's size and shows the scene (not just sky), and the contact sheet and the collision
 * debug view have their sizes. The run's folder, seconds and frame interval come from the environment. */
#include "debug_view.h"
#include "render.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { CAMERA_W = 960, CAMERA_H = 540, SHEET_COLS = 4, SHEET_ROWS = 3 };

static const char *env(const char *name)
{
    const char *v = getenv(name);
    cr_assert(v && *v, "%s is not set: run this test through `make test-demo`", name);
    return v;
}

static int expected_frames(void)
{
    const int steps = (int)lround(atof(env("PP_DEMO_SECONDS")) * 60.0), every = atoi(env("PP_DEMO_EVERY"));
    cr_assert(every >= 1 && steps >= 1);
    return steps / every + 1;
}

/* Load a PNG of the demo's folder, asserting its size. */
static uint8_t *load(const char *name, int32_t want_w, int32_t want_h)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", env("PP_DEMO_OUT"), name);
    int32_t w = 0, h = 0;
    cr_assert_eq(pp_image_info(path, &w, &h), PP_OK, "%s: %s", path, pp_last_error());
    cr_assert(w == want_w && h == want_h, "%s is %d x %d, expected %d x %d", path, w, h, want_w, want_h);
    uint8_t *rgba = malloc((size_t)w * h * 4);
    cr_assert_not_null(rgba);
    cr_assert_eq(pp_image_load(path, rgba, (int64_t)w * h * 4, &w, &h), PP_OK, "%s: %s", path, pp_last_error());
    return rgba;
}

/* Pixels that are not the sky of their row, and how many colours they have (counted up to 64). */
static void scene_pixels(const uint8_t *rgba, int64_t *drawn, int *colours)
{
    uint32_t seen[64];
    *drawn = 0, *colours = 0;
    for (int32_t y = 0; y < CAMERA_H; y++) {
        const render_color sky = render_sky_color(y, CAMERA_H);
        for (int32_t x = 0; x < CAMERA_W; x++) {
            const uint8_t *p = rgba + ((size_t)y * CAMERA_W + x) * 4;
            if (p[0] == sky.r && p[1] == sky.g && p[2] == sky.b)
                continue;
            ++*drawn;
            const uint32_t c = (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
            int known = 0;
            for (int k = 0; k < *colours; k++)
                known |= seen[k] == c;
            if (!known && *colours < 64)
                seen[(*colours)++] = c;
        }
    }
}

Test(demo, every_frame_exists_has_the_camera_size_and_shows_the_scene)
{
    const int frames = expected_frames();
    for (int f = 0; f < frames; f++) {
        char name[64];
        snprintf(name, sizeof name, "frame_%04d.png", f);
        uint8_t *rgba = load(name, CAMERA_W, CAMERA_H);
        int64_t drawn;
        int colours;
        scene_pixels(rgba, &drawn, &colours);
        free(rgba);
        cr_assert(drawn >= (int64_t)CAMERA_W * CAMERA_H / 20, "%s: only %lld pixels differ from the sky", name,
                  (long long)drawn);
        cr_assert(colours >= 2, "%s: the scene has %d colours", name, colours);
    }
    char past[64];
    snprintf(past, sizeof past, "%s/frame_%04d.png", env("PP_DEMO_OUT"), frames);
    cr_assert_neq(pp_image_info(past, NULL, NULL), PP_OK, "%s: more frames than the run asked for", past);
}

Test(demo, frames_change_as_the_scene_moves)
{
    const int frames = expected_frames();
    char last[64];
    snprintf(last, sizeof last, "frame_%04d.png", frames - 1);
    uint8_t *a = load("frame_0000.png", CAMERA_W, CAMERA_H), *b = load(last, CAMERA_W, CAMERA_H);
    int64_t changed = 0;
    for (int64_t i = 0; i < (int64_t)CAMERA_W * CAMERA_H; i++)
        changed += memcmp(a + 4 * i, b + 4 * i, 3) != 0;
    free(a);
    free(b);
    cr_assert(frames == 1 || changed > 500, "the first and last frames differ in only %lld pixels", (long long)changed);
}

Test(demo, the_contact_sheet_and_the_debug_view_have_their_sizes)
{
    uint8_t *sheet = load("contact_sheet.png", CAMERA_W / SHEET_COLS * SHEET_COLS, CAMERA_H / SHEET_COLS * SHEET_ROWS);
    free(sheet);
    uint8_t *debug = load("collision_debug.png", CAMERA_W, CAMERA_H);
    /* The view shows a pair: cells of the first body (blue), of the second (green) and critical cells (red),
     * beyond the 16 × 16 squares of the legend. */
    const render_color colour[3] = {debug_cell_color(PP_CELL_A), debug_cell_color(PP_CELL_B),
                                    debug_cell_color(PP_CELL_A | PP_CELL_B | PP_CELL_CRITICAL)};
    int64_t count[3] = {0};
    for (int64_t i = 0; i < (int64_t)CAMERA_W * CAMERA_H; i++)
        for (int k = 0; k < 3; k++)
            count[k] += memcmp(debug + 4 * i, &colour[k], 4) == 0;
    free(debug);
    cr_assert(count[0] > 256 && count[1] > 256 && count[2] > 256,
              "debug view: %lld, %lld and %lld pixels of the first body, the second and critical cells",
              (long long)count[0], (long long)count[1], (long long)count[2]);
}

/* The lit cells of one glyph drawn at scale 1, rows top to bottom, '#' lit (as render.c's font writes them). */
static void glyph_cells(char ch, char out[16])
{
    render_image im;
    cr_assert(render_image_init(&im, 3, 5));
    render_fill(&im, (render_color){0, 0, 0, 255});
    render_text(&im, 0, 0, 1, (char[]){ch, '\0'}, (render_color){255, 255, 255, 255});
    for (int k = 0; k < 15; k++)
        out[k] = im.rgba[4 * k] ? '#' : ' ';
    out[15] = '\0';
    render_image_free(&im);
}

Test(render, captions_draw_an_s_with_three_strokes_unlike_a_5)
{
    char s[16], five[16], lower[16];
    glyph_cells('S', s);
    glyph_cells('5', five);
    glyph_cells('s', lower);
    for (int row = 0; row < 5; row += 2)
        cr_assert((s[3 * row] == '#') + (s[3 * row + 1] == '#') + (s[3 * row + 2] == '#') >= 2,
                  "S \"%s\": row %d is not a stroke", s, row);
    cr_assert(s[3] == '#' && s[11] == '#', "S \"%s\": its upper left and lower right sides", s);
    cr_assert(strcmp(s, five) != 0, "S and 5 are the same glyph \"%s\"", s);
    cr_assert_str_eq(lower, s, "a lower-case s draws as S");
}

/* A pair's grid of 100 × 100 cells whose 20 × 2 intersection is all critical: the view shows a 56 × 38 window. */
Test(demo, the_debug_view_s_legend_and_title_match_its_picture)
{
    enum { N = 100 };
    debug_capture c = {.width = N, .height = N, .step_x = {1, 0}, .step_y = {0, 1}, .normal = {0, -1}, .time = 1.5};
    snprintf(c.what, sizeof c.what, "TERRAIN / CRATE 3");
    c.cells = calloc(N * N, 1);
    c.normals = calloc(N * N, sizeof(pp_vec2));
    cr_assert(c.cells && c.normals);
    for (int j = 0; j < N; j++)
        for (int i = 40; i < 60; i++) {
            uint8_t f = (uint8_t)((j >= 50 ? PP_CELL_A : 0) | (j < 52 ? PP_CELL_B : 0));
            c.cells[j * N + i] = f == (PP_CELL_A | PP_CELL_B) ? f | PP_CELL_CRITICAL : f;
        }
    char title[200];
    debug_view_title(&c, title, sizeof title);
    cr_assert_str_eq(title, "COLLISION AT T = 1.50 S: TERRAIN / CRATE 3, 56 X 38 OF 100 X 100 CELLS");
    render_image im;
    cr_assert(render_image_init(&im, CAMERA_W, CAMERA_H));
    debug_view_draw(&im, &c);
    const render_color plain = debug_cell_color(PP_CELL_A | PP_CELL_B), critical = debug_cell_color(PP_CELL_CRITICAL);
    int64_t plain_px = 0, critical_px = 0;
    for (int64_t i = 0; i < (int64_t)CAMERA_W * CAMERA_H; i++) {
        plain_px += memcmp(im.rgba + 4 * i, &plain, 4) == 0;
        critical_px += memcmp(im.rgba + 4 * i, &critical, 4) == 0;
    }
    cr_assert_eq(plain_px, 0, "the legend shows the plain intersection colour, which no cell has");
    cr_assert(critical_px > 256, "the critical cells and their legend square");
    render_image_free(&im);
    free(c.cells);
    free(c.normals);
}
