/* Edit latency: a 32 px crater in a 4096×2048 terrain with 200 boxes resting on it. Times the
 * erase call itself and the step after it against a step without an edit; median and 99th
 * percentile over the craters, printed and written as CSV. Then one pp_world_erase_circle over n one-pixel
 * bodies (debris), before any step: its time a body should not grow with n. Then a small erase in a terrain
 * while n bodies are awake elsewhere: its time should not grow with n either (an edit costs what is near it).
 *
 *   bench_edit [--csv PATH] [--craters N]
 */
#include "../machine.h"
#include "physpix.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define TW 4096
#define TH 2048
#define TOP 1000.0f /* world y of the terrain's top edge */

static void check(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "bench_edit: %s: %s (%s)\n", what, pp_status_name(st), pp_last_error());
        exit(1);
    }
}

/* One pp_world_erase_circle that empties side² one-pixel bodies 2 px apart, ms. */
static double erase_debris(int side)
{
    pp_world_def wd = pp_world_def_default();
    wd.backend = PP_BACKEND_CPU;
    pp_world w;
    check(pp_world_create(&wd, &w), "pp_world_create");
    uint8_t one = 1;
    for (int j = 0; j < side; j++)
        for (int i = 0; i < side; i++) {
            pp_body_def d = pp_body_def_default();
            d.position = (pp_vec2){2.0f * i, 2.0f * j};
            d.width = d.height = 1, d.mask = &one;
            pp_body b;
            check(pp_body_create(w, &d, &b), "debris");
        }
    int32_t changed = 0;
    const double t0 = bench_clock_ms();
    check(pp_world_erase_circle(w, (pp_vec2){(float)side, (float)side}, 2.0f * side, &changed), "erase the debris");
    const double ms = bench_clock_ms() - t0;
    if (changed != side * side)
        check(PP_ERR_INVALID_ARGUMENT, "the erase missed debris");
    check(pp_world_destroy(w), "pp_world_destroy");
    return ms;
}

/* Median ms of ERASES radius-3 erases in a 1024×256 terrain while n boxes drift, awake, far above it. */
static double erase_with_awake(int n)
{
    enum { ERASES = 400 };
    pp_world_def wd = pp_world_def_default();
    wd.backend = PP_BACKEND_CPU;
    wd.gravity = (pp_vec2){0, 0};
    wd.allow_sleep = 0;
    pp_world w;
    check(pp_world_create(&wd, &w), "pp_world_create");
    uint8_t *ground = malloc(1024 * 256);
    memset(ground, 1, 1024 * 256);
    pp_body_def d = pp_body_def_default();
    d.type = PP_BODY_STATIC, d.width = 1024, d.height = 256, d.mask = ground;
    d.position = (pp_vec2){512, 128};
    pp_body terrain;
    check(pp_body_create(w, &d, &terrain), "terrain");
    uint8_t box[4 * 4];
    memset(box, 1, sizeof box);
    for (int i = 0; i < n; i++) {
        pp_body_def bd = pp_body_def_default();
        bd.width = bd.height = 4, bd.mask = box;
        bd.position = (pp_vec2){8.0f * (i % 500), -1000.0f - 8.0f * (i / 500)};
        bd.linear_velocity = (pp_vec2){1, 0};
        pp_body b;
        check(pp_body_create(w, &bd, &b), "drifting box");
    }
    check(pp_world_step(w, 1.0f / 60), "step"); /* every box awake and in the awake set's index */
    double ms[ERASES];
    for (int k = 0; k < ERASES; k++) {
        const pp_vec2 c = {20.0f + (float)((k * 397) % 980), 20.0f + (float)((k * 131) % 200)};
        const double t0 = bench_clock_ms();
        check(pp_world_erase_circle(w, c, 3.0f, NULL), "small erase");
        ms[k] = bench_clock_ms() - t0;
    }
    check(pp_world_destroy(w), "pp_world_destroy");
    free(ground);
    qsort(ms, ERASES, sizeof *ms, bench_cmp_double);
    return ms[ERASES / 2];
}

static double pct(double *v, int n, double p)
{
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    return v[(int)(p * (n - 1) + 0.5)];
}

int main(int argc, char **argv)
{
    const char *csv_path = NULL;
    int craters = 200;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--csv") && i + 1 < argc)
            csv_path = argv[++i];
        else if (!strcmp(argv[i], "--craters") && i + 1 < argc)
            craters = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_edit [--csv PATH] [--craters N]\n");
            return 2;
        }
    }
    if (craters < 2)
        craters = 2;
    pp_world_def wd = pp_world_def_default();
    wd.backend = PP_BACKEND_CPU;
    pp_world w;
    check(pp_world_create(&wd, &w), "pp_world_create");
    uint8_t *mask = malloc((size_t)TW * TH);
    memset(mask, 1, (size_t)TW * TH);
    pp_body_def d = pp_body_def_default();
    d.type = PP_BODY_STATIC, d.width = TW, d.height = TH, d.mask = mask;
    d.position = (pp_vec2){TW / 2.0f, TOP + TH / 2.0f};
    pp_body terrain;
    check(pp_body_create(w, &d, &terrain), "terrain");
    uint8_t box[16 * 16];
    memset(box, 1, sizeof box);
    for (int i = 0; i < 200; i++) {
        pp_body_def bd = pp_body_def_default();
        bd.width = bd.height = 16, bd.mask = box;
        bd.position = (pp_vec2){48.0f + 20.0f * i, TOP - 8.0f};
        pp_body b;
        check(pp_body_create(w, &bd, &b), "box");
    }
    for (int s = 0; s < 120; s++)
        check(pp_world_step(w, 1.0f / 60), "settle");

    double *edit = malloc(sizeof(double) * craters), *after = malloc(sizeof(double) * craters);
    double *plain = malloc(sizeof(double) * craters);
    long long erased = 0;
    for (int k = 0; k < craters; k++) {
        double t0 = bench_clock_ms();
        check(pp_world_step(w, 1.0f / 60), "step");
        plain[k] = bench_clock_ms() - t0;
        /* Craters across the surface, below the boxes' row so no box is cut. */
        const pp_vec2 c = {40.0f + (float)((k * 997) % (TW - 80)), TOP + 100.0f + (float)((k * 131) % 1800)};
        int32_t changed;
        t0 = bench_clock_ms();
        check(pp_world_erase_circle(w, c, 32.0f, &changed), "erase");
        edit[k] = bench_clock_ms() - t0;
        erased += changed;
        t0 = bench_clock_ms();
        check(pp_world_step(w, 1.0f / 60), "step after the edit");
        after[k] = bench_clock_ms() - t0;
    }
    const double e50 = pct(edit, craters, 0.5), e99 = pct(edit, craters, 0.99);
    const double a50 = pct(after, craters, 0.5), a99 = pct(after, craters, 0.99);
    const double p50 = pct(plain, craters, 0.5), p99 = pct(plain, craters, 0.99);
    printf("edit latency: %d craters of radius 32 px in a %d x %d terrain, 200 boxes resting, CPU backend\n", craters,
           TW, TH);
    printf("%-26s %10s %10s\n", "", "median ms", "p99 ms");
    printf("%-26s %10.4f %10.4f\n", "erase call", e50, e99);
    printf("%-26s %10.4f %10.4f\n", "step after an edit", a50, a99);
    printf("%-26s %10.4f %10.4f\n", "step without an edit", p50, p99);
    printf("pixels erased per crater: %.0f\n", (double)erased / craters);
    enum { DEBRIS_SIZES = 3 };
    const int sides[DEBRIS_SIZES] = {64, 128, 256};
    double debris_ms[DEBRIS_SIZES];
    printf("\none erase emptying n one-pixel bodies (before any step)\n%-26s %10s %14s\n", "bodies", "ms",
           "us per body");
    for (int i = 0; i < DEBRIS_SIZES; i++) {
        debris_ms[i] = erase_debris(sides[i]);
        printf("%-26d %10.3f %14.3f\n", sides[i] * sides[i], debris_ms[i],
               1e3 * debris_ms[i] / (sides[i] * sides[i]));
    }
    enum { AWAKE_SIZES = 3 };
    const int awake_n[AWAKE_SIZES] = {100, 1000, 10000};
    double awake_ms[AWAKE_SIZES];
    printf("\na radius-3 erase in a terrain while n bodies are awake elsewhere (median of 400)\n%-26s %10s\n",
           "awake bodies", "us");
    for (int i = 0; i < AWAKE_SIZES; i++) {
        awake_ms[i] = erase_with_awake(awake_n[i]);
        printf("%-26d %10.2f\n", awake_n[i], 1e3 * awake_ms[i]);
    }
    if (csv_path) {
        FILE *f = fopen(csv_path, "w");
        if (!f) {
            perror(csv_path);
            return 1;
        }
        fprintf(f, "what,median_ms,p99_ms\nerase,%.6f,%.6f\nstep_after_edit,%.6f,%.6f\nstep_plain,%.6f,%.6f\n", e50,
                e99, a50, a99, p50, p99);
        for (int i = 0; i < DEBRIS_SIZES; i++) /* one run each: median and p99 are that run */
            fprintf(f, "erase_debris_%d,%.6f,%.6f\n", sides[i] * sides[i], debris_ms[i], debris_ms[i]);
        for (int i = 0; i < AWAKE_SIZES; i++) /* a median of 400 erases; p99 not kept */
            fprintf(f, "erase_with_%d_awake,%.6f,%.6f\n", awake_n[i], awake_ms[i], awake_ms[i]);
        fclose(f);
        printf("wrote %s\n", csv_path);
    }
    free(edit), free(after), free(plain), free(mask);
    check(pp_world_destroy(w), "pp_world_destroy");
    return 0;
}
