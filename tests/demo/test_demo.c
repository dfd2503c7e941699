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
