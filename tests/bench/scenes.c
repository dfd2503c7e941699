/* The benchmark's scenes as plain lists of boxes, so that the raster run and the analytic
 * run are built from the same numbers. */
#include "bench.h"
#include "machine.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

double bench_now_ms(void) { return bench_clock_ms(); }

static int scene_alloc(bench_scene *out, const char *name, int count, int steps)
{
    *out = (bench_scene){.name = name, .steps = steps, .tracked = -1};
    out->boxes = calloc((size_t)count, sizeof *out->boxes);
    if (!out->boxes) {
        fprintf(stderr, "bench: out of memory for scene %s\n", name);
        return -1;
    }
    return 0;
}

static void scene_add(bench_scene *s, bench_box box)
{
    s->boxes[s->count++] = box;
    if (!box.is_static)
        s->dynamic_count++;
}

int bench_scene_pyramid(bench_scene *out, int steps)
{
    enum { ROWS = 10, SIDE = 16, GAP = 1 };
    const double ground_top = 400.0, centre_x = 320.0;
    if (scene_alloc(out, "pyramid", 1 + ROWS * (ROWS + 1) / 2, steps) != 0)
        return -1;
    out->ground_top = ground_top;

    scene_add(out, (bench_box){.x = centre_x, .y = ground_top + 16.0, .w = 640, .h = 32, .is_static = 1});

    /* Row r has ROWS − r boxes, each resting exactly on the row below (no overlap at t = 0),
     * one pixel apart sideways so that no side contact exists before the stack settles. */
    const double pitch = SIDE + GAP;
    for (int r = 0; r < ROWS; r++) {
        int n = ROWS - r;
        double y = ground_top - SIDE * 0.5 - (double)(r * SIDE);
        for (int i = 0; i < n; i++) {
            double x = centre_x + ((double)i - (double)(n - 1) * 0.5) * pitch;
            scene_add(out, (bench_box){.x = x, .y = y, .w = SIDE, .h = SIDE});
        }
    }
    out->tracked = out->count - 1; /* the top box */
    return 0;
}

int bench_scene_rain(bench_scene *out, int steps)
{
    enum { COLS = 25, ROWS = 20, SIDE = 32, PITCH = 48 };
    const double ground_top = 1200.0, centre_x = 1000.0;
    if (scene_alloc(out, "rain", 1 + COLS * ROWS, steps) != 0)
        return -1;
    out->ground_top = ground_top;

    scene_add(out, (bench_box){.x = centre_x, .y = ground_top + 20.0, .w = 2000, .h = 40, .is_static = 1});

    /* A 25 × 20 grid, 16 px apart, odd rows shifted half a gap, each crate turned by one of
     * nine angles in ±0.2 rad so that the pile does not land as a perfect lattice. */
    for (int r = 0; r < ROWS; r++) {
        double y = ground_top - 100.0 - (double)(r * PITCH);
        double shift = (r % 2) ? PITCH / 6.0 : 0.0;
        for (int c = 0; c < COLS; c++) {
            double x = centre_x + ((double)c - (COLS - 1) * 0.5) * PITCH + shift;
            double angle = (double)((c * 7 + r * 3) % 9 - 4) * 0.05;
            scene_add(out, (bench_box){.x = x, .y = y, .w = SIDE, .h = SIDE, .angle = angle});
        }
    }
    return 0;
}

void bench_scene_free(bench_scene *scene)
{
    free(scene->boxes);
    *scene = (bench_scene){0};
}
