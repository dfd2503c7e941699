/* The edits curve: 0 to 100 circle erases per step in a 4096×2048 terrain with crates resting
 * on it, each step timed with its edits. ODE's analytic boxes cannot be edited, so this curve
 * has no analytic line. */
#include "physpix.h"
#include "scale.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum {
    TW = 4096, TH = 2048, SKY = 256,       ///< terrain size and its empty top rows, px
    CRATE = 32, COLS = 4, ROWS = 2,        ///< the crates: 4 stacks of 2 on the surface's middle
    RADIUS = 16, SPOT_PITCH = 40,          ///< erases: radius, and the grid of their centres, px
    SPOT_MARGIN = 24, SPOT_BELOW = 64,     ///< spots stay this far from the sides and under the surface, px
    STEPS = 40,                            ///< timed steps: 100 erases a step use fresh spots for 40 steps
};

static int check(pp_status st, const char *what)
{
    if (st == PP_OK)
        return 0;
    fprintf(stderr, "bench_scale: %s failed: %s: %s\n", what, pp_status_name(st), pp_last_error());
    return -1;
}

static int gcd(int a, int b) { return b ? gcd(b, a % b) : a; }

/* The spots' count, and all spot centres in the order they are used: a grid walked with a
 * stride near 0.618 of its size, so that one step's erases land far apart. */
static int spot_count(void)
{
    int cols = (TW - 2 * SPOT_MARGIN) / SPOT_PITCH + 1;
    int rows = (TH - SKY - SPOT_BELOW - SPOT_MARGIN) / SPOT_PITCH + 1;
    return cols * rows;
}

static void spots_in_order(pp_vec2 *out, int n)
{
    int stride = (int)(n * 0.618), cols = (TW - 2 * SPOT_MARGIN) / SPOT_PITCH + 1;
    while (gcd(stride, n) != 1) /* coprime: the walk visits every spot once */
        stride++;
    for (int k = 0; k < n; k++) {
        int i = (int)((long)k * stride % n);
        out[k] = (pp_vec2){(float)(SPOT_MARGIN + (i % cols) * SPOT_PITCH),
                           (float)(SKY + SPOT_BELOW + (i / cols) * SPOT_PITCH)};
    }
}

/* The world: terrain with its top-left corner at the origin (surface at y = SKY), crates on it, sleep off. */
static int build(pp_world *w, pp_body *terrain)
{
    pp_world_def def = pp_world_def_default();
    def.allow_sleep = 0;
    if (check(pp_world_create(&def, w), "pp_world_create") != 0)
        return -1;
    uint8_t *mask = malloc((size_t)TW * TH);
    if (!mask) {
        fprintf(stderr, "bench_scale: out of memory for the terrain\n");
        return -1;
    }
    memset(mask, 0, (size_t)TW * SKY);
    memset(mask + (size_t)TW * SKY, 1, (size_t)TW * (TH - SKY));
    pp_body_def td = pp_body_def_default();
    td.type = PP_BODY_STATIC;
    td.width = TW, td.height = TH, td.mask = mask;
    td.position = (pp_vec2){TW * 0.5f, TH * 0.5f};
    int rc = check(pp_body_create(*w, &td, terrain), "pp_body_create (terrain)");
    memset(mask, 1, (size_t)CRATE * CRATE);
    for (int c = 0; c < COLS && rc == 0; c++) {
        for (int r = 0; r < ROWS && rc == 0; r++) {
            pp_body_def bd = pp_body_def_default();
            bd.width = bd.height = CRATE, bd.mask = mask;
            bd.position = (pp_vec2){(float)(TW * 0.5 + (c - (COLS - 1) * 0.5) * 2 * CRATE),
                                    (float)(SKY - CRATE * 0.5 - r * CRATE)};
            pp_body b;
            rc = check(pp_body_create(*w, &bd, &b), "pp_body_create (crate)");
        }
    }
    free(mask);
    return rc;
}

/* One point: a fresh world, settled, then `edits` erases and a step, timed together, per step;
 * the medians of the whole, the edits, the step and its narrowphase. */
static int measure(int edits, int steps, int settle, float dt, scale_row *row, double *step_ms_median,
                   double *px_per_edit)
{
    pp_world w = {0};
    pp_body terrain;
    const int n = spot_count();
    double *total = malloc(sizeof(double) * 4 * (size_t)steps);
    pp_vec2 *spots = malloc(sizeof *spots * (size_t)n);
    if (!total || !spots) {
        fprintf(stderr, "bench_scale: out of memory\n");
        free(total);
        free(spots);
        return -1;
    }
    spots_in_order(spots, n);
    double *edit = total + steps, *step = edit + steps, *narrow = step + steps;
    int rc = build(&w, &terrain);
    for (int s = 0; s < settle && rc == 0; s++)
        rc = check(pp_world_step(w, dt), "pp_world_step");
    long erased = 0;
    pp_step_stats stats = {0};
    for (int s = 0; s < steps && rc == 0; s++) {
        double t0 = bench_now_ms();
        for (int e = 0; e < edits && rc == 0; e++) {
            int32_t changed = 0;
            rc = check(pp_body_erase_circle(w, terrain, spots[s * edits + e], RADIUS, &changed),
                       "pp_body_erase_circle");
            erased += changed;
        }
        double t1 = bench_now_ms();
        if (rc == 0)
            rc = check(pp_world_step(w, dt), "pp_world_step");
        double t2 = bench_now_ms();
        total[s] = t2 - t0, edit[s] = t1 - t0, step[s] = t2 - t1;
        if (rc == 0)
            rc = check(pp_world_get_stats(w, &stats), "pp_world_get_stats");
        narrow[s] = stats.narrowphase_ms;
    }
    if (rc == 0) {
        row->ms = bench_median(total, steps);
        row->edit_ms = bench_median(edit, steps);
        row->narrow_ms = bench_median(narrow, steps);
        row->contacts = stats.contacts;
        row->pairs = stats.pairs;
        row->awake = stats.awake_bodies;
        *step_ms_median = bench_median(step, steps);
        *px_per_edit = edits ? (double)erased / ((double)edits * steps) : 0.0;
    }
    free(total);
    free(spots);
    if (w.id && check(pp_world_destroy(w), "pp_world_destroy") != 0)
        rc = -1;
    return rc;
}

int scale_curve_edits(const scale_ctx *ctx)
{
    static const int counts[] = {0, 1, 10, 100};
    const int steps = ctx->quick ? 5 : STEPS, settle = ctx->quick ? 5 : 30, runs = ctx->quick ? 1 : 3;
    printf("\n== edits: pp_body_erase_circle of radius %d px, N per step, in a %dx%d static terrain (top %d rows "
           "empty) ==\n   %d crates of %d px resting on it; erases on a %d px grid at least %d px under the surface, "
           "never twice in one place; sleep off\n   timed %d steps after %d settling steps, smallest median of %d "
           "runs (a fresh world each); analytic: none (ODE's boxes cannot be edited)\n",
           RADIUS, TW, TH, SKY, COLS * ROWS, CRATE, SPOT_PITCH, SPOT_BELOW, steps, settle, runs);
    if ((long)steps * counts[3] > spot_count()) {
        fprintf(stderr, "bench_scale: %d spots are too few for %d steps of %d erases\n", spot_count(), steps,
                counts[3]);
        return -1;
    }
    printf("%-6s %9s %9s %9s %9s %9s %8s %9s\n", "edits", "ms/step", "edits", "step", "narrow", "px erased",
           "contacts", "analytic");
    printf("%-6s %9s %9s %9s %9s %9s %8s %9s\n", "/step", "incl.", "ms/step", "ms/step", "ms/step", "per edit",
           "/substep", "");
    for (size_t k = 0; k < sizeof counts / sizeof counts[0]; k++) {
        scale_row row;
        double step_ms = 0.0, px = 0.0;
        for (int r = 0; r < runs; r++) {
            scale_row run = {.curve = "edits", .variant = "-", .x = counts[k], .engine = "raster", .timed = steps};
            snprintf(run.label, sizeof run.label, "%d", counts[k]);
            double run_step_ms;
            if (measure(counts[k], steps, settle, (float)ctx->set.dt, &run, &run_step_ms, &px) != 0)
                return -1;
            if (r == 0)
                row = run, step_ms = run_step_ms;
            row.ms = run.ms < row.ms ? run.ms : row.ms;
            row.edit_ms = run.edit_ms < row.edit_ms ? run.edit_ms : row.edit_ms;
            row.narrow_ms = run.narrow_ms < row.narrow_ms ? run.narrow_ms : row.narrow_ms;
            step_ms = run_step_ms < step_ms ? run_step_ms : step_ms;
        }
        printf("%-6d %9.3f %9.3f %9.3f %9.4f %9.0f %8.0f %9s\n", counts[k], row.ms, row.edit_ms, step_ms,
               row.narrow_ms, px, row.contacts, "n/a");
        scale_emit(ctx, &row);
    }
    return 0;
}
