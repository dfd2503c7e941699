/* The three curves that step whole scenes: body count, terrain bitmap size and body bitmap
 * size. Each scene is a list of boxes run by both engines (engine_physpix.c, engine_ode.c),
 * so the raster scene and ODE's analytic one are built from the same numbers. */
#include "scale.h"

#include <stdio.h>
#include <stdlib.h>

enum { ENGINE_RASTER, ENGINE_ANALYTIC, ENGINE_COUNT };
static const char *const engine_names[ENGINE_COUNT] = {"raster", "analytic"};

/// Untimed steps before timing a scene with sleep off: crates that start touching stop moving within it.
#define SETTLE_AWAKE 30
/// Most untimed steps to wait for every crate to fall asleep.
#define SETTLE_SLEEP_MAX 600
/// Timed steps and runs of the curves whose scenes step in well under a millisecond.
#define CHEAP_STEPS 300
#define RUNS 3

/// A scene's points of both engines over its runs.
typedef struct engine_pair {
    bench_run run[ENGINE_COUNT];   ///< the first run (contacts, pairs, awake, settling)
    double ms[ENGINE_COUNT];       ///< median ms per timed step, the smallest over the runs
    double narrow[ENGINE_COUNT];   ///< median narrowphase ms per timed step, the smallest over the runs
} engine_pair;

static int scene_new(bench_scene *s, const char *name, int capacity, int steps, int settle)
{
    *s = (bench_scene){.name = name, .steps = steps, .tracked = -1, .settle_steps = settle};
    s->boxes = calloc((size_t)capacity, sizeof *s->boxes);
    if (!s->boxes)
        fprintf(stderr, "bench_scale: out of memory for scene %s\n", name);
    return s->boxes ? 0 : -1;
}

static void scene_add(bench_scene *s, bench_box box)
{
    s->boxes[s->count++] = box;
    s->dynamic_count += !box.is_static;
}

/* count crates of `side` px in stacks of `rows` (the last one may be shorter), `pitch` px
 * apart, centred on x = cx, the lowest row touching y = top without overlap: at rest from the
 * first step. */
static void add_stacks(bench_scene *s, int count, int rows, int side, double pitch, double cx, double top)
{
    int cols = (count + rows - 1) / rows;
    for (int i = 0; i < count; i++)
        scene_add(s, (bench_box){.x = cx + (i / rows - (cols - 1) * 0.5) * pitch,
                                 .y = top - side * 0.5 - (i % rows) * side, .w = side, .h = side});
}

/* `runs` times the raster run, then the analytic one, with the same settings; the smallest
 * median over the runs is kept, so that a slow patch of the machine does not count. */
static int run_engines(const bench_scene *s, const bench_settings *set, int runs, engine_pair *out)
{
    double *step_ms = malloc(2 * (size_t)s->steps * sizeof *step_ms);
    if (!step_ms) {
        fprintf(stderr, "bench_scale: out of memory\n");
        return -1;
    }
    double *narrow_ms = step_ms + s->steps;
    int rc = 0;
    for (int r = 0; r < runs && rc == 0; r++) {
        for (int e = 0; e < ENGINE_COUNT && rc == 0; e++) {
            bench_run run = {.step_ms = step_ms, .narrow_ms = narrow_ms};
            rc = e == ENGINE_RASTER ? bench_run_physpix(s, set, &run) : bench_run_ode(s, set, &run);
            double ms = bench_median(step_ms, s->steps), narrow = bench_median(narrow_ms, s->steps);
            if (r == 0) {
                out->run[e] = run;
                out->run[e].step_ms = out->run[e].narrow_ms = NULL;
            }
            out->ms[e] = r == 0 || ms < out->ms[e] ? ms : out->ms[e];
            out->narrow[e] = r == 0 || narrow < out->narrow[e] ? narrow : out->narrow[e];
        }
    }
    free(step_ms);
    return rc;
}

static double per(double ms, double count) { return count > 0 ? ms * 1e3 / count : 0.0; }

/* The CSV row of one engine's run on one point, the per-contact and per-pair costs filled in. */
static scale_row row_of(const scale_ctx *ctx, const char *curve, const char *variant, double x, const char *label,
                        const bench_scene *s, const engine_pair *p, int e)
{
    const bench_run *r = &p->run[e];
    int sub = ctx->set.substeps;
    scale_row row = {.curve = curve, .variant = variant, .x = x, .engine = engine_names[e], .timed = s->steps,
                     .ms = p->ms[e], .narrow_ms = p->narrow[e], .contacts = r->contacts_mean,
                     .pairs = r->pairs_mean, .us_contact = per(p->narrow[e], r->contacts_mean * sub),
                     .us_pair = per(p->narrow[e], r->pairs_mean * sub), .awake = r->awake_end,
                     .ratio = e == ENGINE_RASTER ? p->ms[ENGINE_RASTER] / p->ms[ENGINE_ANALYTIC] : 1.0};
    snprintf(row.label, sizeof row.label, "%s", label);
    return row;
}

/* ---- body count ---------------------------------------------------------------------- */

/* 10,000 crates must fit on one terrain of at most 16384 px: 1,250 stacks of 8, 13 px apart.
 * Stacks of 8 fall asleep within 40 steps; stacks of 10 of these crates took 200. */
enum { CRATE = 12, STACK = 8, CRATE_PITCH = 13, FLOOR_W = 16384, FLOOR_H = 64 };
static const double floor_top = 1000.0;

/* count crates of 12 px in stacks of 8, 13 px apart, on a 16384×64 static terrain (a box). */
static int crates_scene(bench_scene *s, int count, int steps, int settle)
{
    if (scene_new(s, "bodies", 1 + count, steps, settle) != 0)
        return -1;
    s->ground_top = floor_top;
    scene_add(s, (bench_box){.x = FLOOR_W * 0.5, .y = floor_top + FLOOR_H * 0.5, .w = FLOOR_W, .h = FLOOR_H,
                             .is_static = 1});
    add_stacks(s, count, STACK, CRATE, CRATE_PITCH, FLOOR_W * 0.5, floor_top);
    return 0;
}

int scale_curve_bodies(const scale_ctx *ctx)
{
    static const int counts[] = {100, 1000, 5000, 10000};
    /* Timed steps and runs: fewer where one awake step of either engine costs a tenth of a second
     * or more (the whole curve stays near two minutes on a 2-core machine). */
    static const int awake_steps[] = {120, 40, 16, 12}, asleep_steps[] = {120, 120, 60, 60}, runs[] = {3, 3, 2, 1};
    const int n = ctx->quick ? 2 : 4;

    printf("\n== bodies: crates of %d px in stacks of %d (the last may be shorter), %d px apart, on a %dx%d static "
           "terrain (a box) ==\n"
           "   awake: sleep off, timed after %d settling steps; asleep: sleep on, timed once every crate sleeps\n",
           CRATE, STACK, CRATE_PITCH, FLOOR_W, FLOOR_H, ctx->quick ? 5 : SETTLE_AWAKE);
    if (ctx->quick)
        printf("   one run per count (--quick)\n");
    else
        printf("   smallest median of %d, %d, %d and %d runs for the four counts\n", runs[0], runs[1], runs[2],
               runs[3]);
    printf("%7s %-9s %9s %6s %9s %9s %6s %7s %8s %8s %7s %7s\n", "bodies", "engine", "awake", "timed", "contacts",
           "asleep", "timed", "settle", "awake", "asleep/", "r/a", "r/a");
    printf("%7s %-9s %9s %6s %9s %9s %6s %7s %8s %8s %7s %7s\n", "", "", "ms/step", "steps", "per step", "ms/step",
           "steps", "steps", "bodies", "awake", "awake", "asleep");

    double ratio_10k = -1.0;
    for (int k = 0; k < n; k++) {
        bench_settings awake_set = ctx->set, asleep_set = ctx->set;
        awake_set.allow_sleep = 0;
        asleep_set.allow_sleep = 1;
        bench_scene awake_scene, asleep_scene;
        int steps_awake = ctx->quick ? 5 : awake_steps[k], steps_asleep = ctx->quick ? 10 : asleep_steps[k];
        if (crates_scene(&awake_scene, counts[k], steps_awake, ctx->quick ? 5 : SETTLE_AWAKE) != 0)
            return -1;
        if (crates_scene(&asleep_scene, counts[k], steps_asleep, SETTLE_SLEEP_MAX) != 0) {
            bench_scene_free(&awake_scene);
            return -1;
        }
        asleep_scene.settle_to_sleep = 1;

        engine_pair awake, asleep;
        int rc = run_engines(&awake_scene, &awake_set, ctx->quick ? 1 : runs[k], &awake);
        if (rc == 0)
            rc = run_engines(&asleep_scene, &asleep_set, ctx->quick ? 1 : runs[k], &asleep);
        for (int e = 0; e < ENGINE_COUNT && rc == 0; e++) {
            const bench_run *ra = &awake.run[e], *rs = &asleep.run[e];
            double frac = asleep.ms[e] / awake.ms[e];
            printf("%7d %-9s %9.3f %6d %9.0f %9.3f %6d %7d %8d %7.1f%% %7.3f %7.3f\n", counts[k], engine_names[e],
                   awake.ms[e], steps_awake, ra->contacts_mean, asleep.ms[e], steps_asleep, rs->settled,
                   rs->awake_max, 100.0 * frac, awake.ms[e] / awake.ms[ENGINE_ANALYTIC],
                   asleep.ms[e] / asleep.ms[ENGINE_ANALYTIC]);
            if (ra->lost)
                printf("        note: %d %s crates ended below the terrain's top\n", ra->lost, engine_names[e]);
            if (rs->awake_max > 0)
                printf("        note: %s: %d crates still awake after %d settling steps\n", engine_names[e],
                       rs->awake_max, rs->settled);
            if (e == ENGINE_RASTER && counts[k] == 10000)
                ratio_10k = frac;
            char label[24];
            snprintf(label, sizeof label, "%d", counts[k]);
            scale_row row = row_of(ctx, "bodies", "awake", counts[k], label, &awake_scene, &awake, e);
            scale_emit(ctx, &row);
            row = row_of(ctx, "bodies", "asleep", counts[k], label, &asleep_scene, &asleep, e);
            scale_emit(ctx, &row);
        }
        bench_scene_free(&awake_scene);
        bench_scene_free(&asleep_scene);
        if (rc != 0)
            return -1;
    }
    printf("   awake bodies: the most awake after any timed step of the asleep run (raster: pp_world_get_stats; "
           "analytic: enabled ODE bodies)\n");
    if (ratio_10k >= 0)
        printf("   10000 crates, raster: asleep costs %.1f%% of awake (target < 10%%): %s\n", 100.0 * ratio_10k,
               ratio_10k < 0.10 ? "met" : "NOT met");
    return 0;
}

/* ---- terrain bitmap size ------------------------------------------------------------- */

enum { TCRATE = 32, TCOLS = 4, TROWS = 2, TPITCH = 64 };

/* A w×h static terrain, solid below its middle row (ODE: a box of the solid half), with
 * 4 stacks of 2 crates of 32 px resting on the surface at its centre. */
static int terrain_scene(bench_scene *s, int w, int h, int steps, int settle)
{
    if (scene_new(s, "terrain", 1 + TCOLS * TROWS, steps, settle) != 0)
        return -1;
    s->ground_top = h * 0.5;
    scene_add(s, (bench_box){.x = w * 0.5, .y = h * 0.5, .w = w, .h = h, .is_static = 1, .empty_top = h / 2});
    add_stacks(s, TCOLS * TROWS, TROWS, TCRATE, TPITCH, w * 0.5, h * 0.5);
    return 0;
}

int scale_curve_terrain(const scale_ctx *ctx)
{
    static const int sizes[][2] = {{256, 256}, {1024, 1024}, {2048, 2048}, {4096, 2048}, {8192, 4096}};
    const int n = sizeof sizes / sizeof sizes[0];
    const int steps = ctx->quick ? 10 : CHEAP_STEPS, runs = ctx->quick ? 1 : RUNS;
    bench_settings set = ctx->set;
    set.allow_sleep = 0;

    printf("\n== terrain: %d crates of %d px (%d stacks of %d) on a static terrain solid below its middle row; "
           "sleep off ==\n   timed %d steps after %d settling steps, smallest median of %d runs; analytic: a ground "
           "box of the solid half\n   narrow: median narrowphase ms per step (analytic: dSpaceCollide, pair search "
           "included), per contact or pair and substep in us\n",
           TCOLS * TROWS, TCRATE, TCOLS, TROWS, steps, ctx->quick ? 5 : SETTLE_AWAKE, runs);
    printf("%-10s %-9s %9s %9s %8s %6s %10s %9s %7s %9s\n", "terrain", "engine", "ms/step", "narrow", "contacts",
           "pairs", "narrow", "narrow", "r/a", "r/a");
    printf("%-10s %-9s %9s %9s %8s %6s %10s %9s %7s %9s\n", "px", "", "median", "ms/step", "/substep", "", "us/contact",
           "us/pair", "ms/step", "us/contact");

    double lo[ENGINE_COUNT] = {1e300, 1e300}, hi[ENGINE_COUNT] = {0, 0};
    for (int k = 0; k < n; k++) {
        const int w = sizes[k][0], h = sizes[k][1];
        bench_scene s;
        if (terrain_scene(&s, w, h, steps, ctx->quick ? 5 : SETTLE_AWAKE) != 0)
            return -1;
        engine_pair p;
        int rc = run_engines(&s, &set, runs, &p);
        char label[24];
        snprintf(label, sizeof label, "%dx%d", w, h);
        scale_row rows[ENGINE_COUNT];
        for (int e = 0; e < ENGINE_COUNT && rc == 0; e++)
            rows[e] = row_of(ctx, "terrain", "-", (double)w * h, label, &s, &p, e);
        for (int e = 0; e < ENGINE_COUNT && rc == 0; e++) {
            const scale_row *r = &rows[e];
            printf("%-10s %-9s %9.4f %9.4f %8.1f %6.1f %10.3f %9.3f %7.3f %9.3f\n", label, r->engine, r->ms,
                   r->narrow_ms, r->contacts, r->pairs, r->us_contact, r->us_pair, r->ratio,
                   r->us_contact / rows[ENGINE_ANALYTIC].us_contact);
            lo[e] = r->us_contact < lo[e] ? r->us_contact : lo[e];
            hi[e] = r->us_contact > hi[e] ? r->us_contact : hi[e];
            scale_emit(ctx, r);
        }
        bench_scene_free(&s);
        if (rc != 0)
            return -1;
    }
    printf("   narrowphase us/contact, largest / smallest over the terrains: raster %.2f (target <= 1.20: %s), "
           "analytic %.2f\n",
           hi[ENGINE_RASTER] / lo[ENGINE_RASTER], hi[ENGINE_RASTER] <= 1.2 * lo[ENGINE_RASTER] ? "met" : "NOT met",
           hi[ENGINE_ANALYTIC] / lo[ENGINE_ANALYTIC]);
    return 0;
}

/* ---- body bitmap size ---------------------------------------------------------------- */

enum { BCOUNT = 4, GROUND_W = 4096, GROUND_H = 64 };

/* 4 crates of `side` px in one row, side/2 apart, on a 4096×64 static ground (a box). */
static int body_size_scene(bench_scene *s, int side, int steps, int settle)
{
    if (scene_new(s, "body_size", 1 + BCOUNT, steps, settle) != 0)
        return -1;
    s->ground_top = floor_top;
    scene_add(s, (bench_box){.x = GROUND_W * 0.5, .y = floor_top + GROUND_H * 0.5, .w = GROUND_W, .h = GROUND_H,
                             .is_static = 1});
    add_stacks(s, BCOUNT, 1, side, side * 1.5, GROUND_W * 0.5, floor_top);
    return 0;
}

int scale_curve_body_size(const scale_ctx *ctx)
{
    static const int all_sides[] = {8, 16, 32, 64, 128, 256, 512}, quick_sides[] = {8, 64, 512};
    const int *sides = ctx->quick ? quick_sides : all_sides;
    const int n = ctx->quick ? 3 : 7, steps = ctx->quick ? 10 : CHEAP_STEPS, runs = ctx->quick ? 1 : RUNS;
    bench_settings set = ctx->set;
    set.allow_sleep = 0;

    printf("\n== body_size: %d crates of side S in a row, S/2 apart, on a %dx%d static ground (a box); sleep off ==\n"
           "   timed %d steps after %d settling steps, smallest median of %d runs\n   narrow: median narrowphase ms "
           "per step (analytic: dSpaceCollide, pair search included), per contact and substep in us\n",
           BCOUNT, GROUND_W, GROUND_H, steps, ctx->quick ? 5 : SETTLE_AWAKE, runs);
    printf("%-6s %-9s %9s %9s %8s %10s %7s %9s\n", "side", "engine", "ms/step", "narrow", "contacts", "narrow", "r/a",
           "r/a");
    printf("%-6s %-9s %9s %9s %8s %10s %7s %9s\n", "px", "", "median", "ms/step", "/substep", "us/contact", "ms/step",
           "us/contact");
    for (int k = 0; k < n; k++) {
        bench_scene s;
        if (body_size_scene(&s, sides[k], steps, ctx->quick ? 5 : SETTLE_AWAKE) != 0)
            return -1;
        engine_pair p;
        int rc = run_engines(&s, &set, runs, &p);
        char label[24];
        snprintf(label, sizeof label, "%d", sides[k]);
        scale_row rows[ENGINE_COUNT];
        for (int e = 0; e < ENGINE_COUNT && rc == 0; e++)
            rows[e] = row_of(ctx, "body_size", "-", sides[k], label, &s, &p, e);
        for (int e = 0; e < ENGINE_COUNT && rc == 0; e++) {
            const scale_row *r = &rows[e];
            printf("%-6s %-9s %9.4f %9.4f %8.1f %10.3f %7.3f %9.3f\n", label, r->engine, r->ms, r->narrow_ms,
                   r->contacts, r->us_contact, r->ratio, r->us_contact / rows[ENGINE_ANALYTIC].us_contact);
            if (p.run[e].lost)
                printf("       note: %d %s crates ended below the ground's top\n", p.run[e].lost, r->engine);
            scale_emit(ctx, r);
        }
        bench_scene_free(&s);
        if (rc != 0)
            return -1;
    }
    return 0;
}
