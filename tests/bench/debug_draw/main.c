/* What pp_world_debug_draw costs beside a step: a 2048×1024 hilly terrain cut by 200 craters, with 300 crates
 * settled on it. The whole world with every flag, the outlines alone, a 960×540 view, and the first call after
 * a crater (the terrain's outline rebuilt); the median and the minimum of the runs of each (the very first
 * call, which builds every outline, once), printed as a table and written as CSV.
 *
 *   bench_debug_draw [--csv PATH] [--runs N]
 */
#include "../machine.h"
#include "physpix.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TW 2048
#define TH 1024
#define TOP 600.0f /* world y of the terrain bitmap's top edge */
#define CRATERS 200
#define CRATES 300
#define PI 3.14159265358979323846

static void check(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "bench_debug_draw: %s: %s (%s)\n", what, pp_status_name(st), pp_last_error());
        exit(1);
    }
}

static uint64_t seed = 4242;

static double rnd(void)
{
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(seed >> 11) / 9007199254740992.0;
}

/* Bitmap row of the terrain's surface at column x: rolling hills a third of the way down. */
static double surface(int x)
{
    const double u = x / (double)TW;
    return TH * 0.3 + 120 * sin(2 * PI * 1.3 * u) + 50 * sin(2 * PI * 4.7 * u + 1.0) + 15 * sin(2 * PI * 17 * u);
}

/* The segments buffer, grown to the largest count seen. */
static pp_debug_segment *segs;
static int32_t seg_capacity;

/* One call, ms; *n receives its count. */
static double draw_ms(pp_world w, uint32_t flags, pp_vec2 lo, pp_vec2 hi, int32_t *n)
{
    for (;;) {
        const double t0 = bench_clock_ms();
        check(pp_world_debug_draw(w, flags, lo, hi, segs, seg_capacity, n), "pp_world_debug_draw");
        const double ms = bench_clock_ms() - t0;
        if (*n <= seg_capacity)
            return ms;
        seg_capacity = *n;
        segs = realloc(segs, sizeof *segs * (size_t)seg_capacity);
        if (!segs)
            check(PP_ERR_OUT_OF_MEMORY, "the segments buffer");
    }
}

static int cmp(const void *a, const void *b) { return bench_cmp_double(a, b); }

typedef struct row {
    const char *name;
    double median, min;
    int32_t segments;
} row;

static row summarise(const char *name, double *ms, int n, int32_t segments)
{
    qsort(ms, (size_t)n, sizeof *ms, cmp);
    return (row){name, ms[n / 2], ms[0], segments};
}

int main(int argc, char **argv)
{
    const char *csv_path = NULL;
    int runs = 60;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--csv") && i + 1 < argc)
            csv_path = argv[++i];
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_debug_draw [--csv PATH] [--runs N]\n");
            return 2;
        }
    }
    if (runs < 3)
        runs = 3;
    pp_world_def wd = pp_world_def_default();
    wd.backend = PP_BACKEND_CPU;
    pp_world w;
    check(pp_world_create(&wd, &w), "pp_world_create");
    uint8_t *mask = malloc((size_t)TW * TH);
    for (int y = 0; y < TH; y++)
        for (int x = 0; x < TW; x++)
            mask[(size_t)y * TW + x] = y >= surface(x);
    pp_body_def d = pp_body_def_default();
    d.type = PP_BODY_STATIC, d.width = TW, d.height = TH, d.mask = mask;
    d.position = (pp_vec2){TW / 2.0f, TOP + TH / 2.0f};
    pp_body terrain;
    check(pp_body_create(w, &d, &terrain), "terrain");
    /* Craters of radius 12..40 px, their centres on or under the surface. */
    for (int k = 0; k < CRATERS; k++) {
        const int x = 20 + (int)((TW - 40) * rnd());
        const float y = TOP + (float)(surface(x) + (TH - surface(x) - 40) * rnd() * rnd());
        check(pp_world_erase_circle(w, (pp_vec2){(float)x, y}, (float)(12 + 28 * rnd()), NULL), "crater");
    }
    /* Crates of 12..16 px in three rows over the surface, settled. */
    uint8_t box[16 * 16];
    memset(box, 1, sizeof box);
    for (int i = 0; i < CRATES; i++) {
        const int col = i % 100, layer = i / 100, side = 12 + (int)(5 * rnd());
        pp_body_def bd = pp_body_def_default();
        bd.width = bd.height = side, bd.mask = box;
        const int x = 12 + 20 * col;
        bd.position = (pp_vec2){(float)x, TOP + (float)surface(x) - 40.0f - 30.0f * layer};
        pp_body b;
        check(pp_body_create(w, &bd, &b), "crate");
    }
    for (int s = 0; s < 180; s++)
        check(pp_world_step(w, 1.0f / 60), "settle");

    const pp_vec2 all_lo = {-FLT_MAX, -FLT_MAX}, all_hi = {FLT_MAX, FLT_MAX};
    const pp_vec2 view_lo = {544, 500}, view_hi = {544 + 960, 500 + 540}; /* a 960×540 camera mid-map */
    double *step = malloc(sizeof(double) * runs), *all = malloc(sizeof(double) * runs);
    double *outl = malloc(sizeof(double) * runs), *view = malloc(sizeof(double) * runs);
    double *cold = malloc(sizeof(double) * runs);
    int32_t n_all = 0, n_outl = 0, n_view = 0, n_cold = 0;
    double first = draw_ms(w, PP_DEBUG_DRAW_ALL, all_lo, all_hi, &n_all); /* it builds every outline */
    for (int k = 0; k < runs; k++) {
        const double t0 = bench_clock_ms();
        check(pp_world_step(w, 1.0f / 60), "step");
        step[k] = bench_clock_ms() - t0;
        all[k] = draw_ms(w, PP_DEBUG_DRAW_ALL, all_lo, all_hi, &n_all);
        outl[k] = draw_ms(w, PP_DEBUG_DRAW_OUTLINES, all_lo, all_hi, &n_outl);
        view[k] = draw_ms(w, PP_DEBUG_DRAW_ALL, view_lo, view_hi, &n_view);
        /* A crater deep in the terrain (no crate is cut), then the call that rebuilds its outline. */
        const pp_vec2 c = {40.0f + (float)((k * 997) % (TW - 80)), TOP + TH - 60.0f - (float)((k * 131) % 200)};
        check(pp_world_erase_circle(w, c, 16.0f, NULL), "erase");
        cold[k] = draw_ms(w, PP_DEBUG_DRAW_ALL, all_lo, all_hi, &n_cold);
    }
    int32_t bodies = 0;
    check(pp_world_get_bodies(w, NULL, 0, &bodies), "pp_world_get_bodies");
    pp_step_stats stats;
    check(pp_world_get_stats(w, &stats), "pp_world_get_stats");
    enum { ROWS = 6 };
    const row rows[ROWS] = {
        summarise("step (1/60 s, 4 substeps)", step, runs, 0),
        summarise("debug_draw ALL, whole world", all, runs, n_all),
        summarise("debug_draw OUTLINES, whole", outl, runs, n_outl),
        summarise("debug_draw ALL, 960x540 view", view, runs, n_view),
        summarise("debug_draw ALL after a crater", cold, runs, n_cold),
        summarise("first call (builds 301 outlines)", &first, 1, n_all),
    };
    char cpu[256];
    bench_cpu_model(cpu, sizeof cpu);
    printf("debug draw: a %d x %d terrain with %d craters, %d crates (%d bodies, %d awake at the end), CPU backend, "
           "%d runs\nmachine: %s\n",
           TW, TH, CRATERS, CRATES, (int)bodies, (int)stats.awake_bodies, runs, cpu);
    printf("%-32s %10s %10s %10s %12s\n", "", "median ms", "min ms", "segments", "x step");
    for (int i = 0; i < ROWS; i++)
        printf("%-32s %10.4f %10.4f %10d %12.3f\n", rows[i].name, rows[i].median, rows[i].min, (int)rows[i].segments,
               rows[i].median / rows[0].median);
    if (csv_path) {
        FILE *f = fopen(csv_path, "w");
        if (!f) {
            perror(csv_path);
            return 1;
        }
        fprintf(f, "what,median_ms,min_ms,segments\n");
        const char *keys[ROWS] = {"step",           "draw_all",          "draw_outlines", "draw_view_960x540",
                                  "draw_after_crater", "draw_first_call"};
        for (int i = 0; i < ROWS; i++)
            fprintf(f, "%s,%.6f,%.6f,%d\n", keys[i], rows[i].median, rows[i].min, (int)rows[i].segments);
        fclose(f);
        printf("wrote %s\n", csv_path);
    }
    free(step), free(all), free(outl), free(view), free(cold), free(mask), free(segs);
    check(pp_world_destroy(w), "pp_world_destroy");
    return 0;
}
