/* The CPU narrowphase core alone, dense against tiled, on named pairs: ns per pair (the fastest of the
 * repeats) and sampled cells per second (the plane a dense core samples, over its time), with a
 * check that both give the same np_core. Links the static library for its private headers; part of
 * `make bench`, or alone:
 *
 *   make build/bench/bench_core && build/bench/bench_core [--reps N] [--only NAME] [--tiled-only] [--dense-only]
 */
#include "../machine.h"
#include "narrowphase.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define TW 4096
#define TH 2048
#define TOP 1024 /* the flat terrain's top row */

static pp_raster make_raster(int w, int h, const uint8_t *mask)
{
    pp_body_def d = pp_body_def_default();
    d.width = w, d.height = h, d.mask = mask;
    pp_raster r;
    if (raster_init("bench_core", &r, &d) != PP_OK) {
        fprintf(stderr, "bench_core: raster_init: %s\n", pp_last_error());
        exit(1);
    }
    return r;
}

static pp_raster box_raster(int w, int h)
{
    uint8_t *m = malloc((size_t)w * h);
    memset(m, 1, (size_t)w * h);
    pp_raster r = make_raster(w, h, m);
    free(m);
    return r;
}

/* Terrain: solid below y = top(x); hilly adds two sines; a crater of radius cr at (cx, cy) when cr > 0. */
static pp_raster terrain_raster(int hilly, double cx, double cy, double cr)
{
    uint8_t *m = calloc((size_t)TW * TH, 1);
    for (int x = 0; x < TW; x++) {
        const double top = hilly ? TOP + 60 * sin(x / 200.0) + 15 * sin(x / 37.0) : TOP;
        for (int y = 0; y < TH; y++) {
            const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
            m[(size_t)y * TW + x] = y + 0.5 >= top && !(cr > 0 && dx * dx + dy * dy <= cr * cr);
        }
    }
    pp_raster r = make_raster(TW, TH, m);
    free(m);
    return r;
}

static np_body body_at(const pp_raster *r, double x, double y, double angle)
{
    return (np_body){.raster = r, .pos = dv(x, y), .pivot = dv(r->width / 2.0, r->height / 2.0), .c = cos(angle),
                     .s = sin(angle)};
}

typedef struct scenario {
    const char *name;
    np_body a, b;
} scenario;

/* The fastest of reps calls, ns (the least disturbed by other processes). */
static double time_core(pp_status (*core)(const np_settings *, const np_pair *, np_scratch *, np_core *),
                        const np_settings *set, const np_pair *p, np_scratch *s, int reps, np_core *out)
{
    double *t = malloc(sizeof(double) * reps);
    core(set, p, s, out); /* warm the scratch */
    for (int i = 0; i < reps; i++) {
        const double t0 = (1e6 * bench_clock_ms());
        core(set, p, s, out);
        t[i] = (1e6 * bench_clock_ms()) - t0;
    }
    qsort(t, (size_t)reps, sizeof *t, bench_cmp_double);
    const double best = t[0];
    free(t);
    return best;
}

int main(int argc, char **argv)
{
    int reps = 201, which = 3; /* bit 0 dense, bit 1 tiled */
    const char *only = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--reps") && i + 1 < argc) reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
        else if (!strcmp(argv[i], "--tiled-only")) which = 2;
        else if (!strcmp(argv[i], "--dense-only")) which = 1;
        else {
            fprintf(stderr, "usage: bench_core [--reps N] [--only NAME] [--tiled-only] [--dense-only]\n");
            return 2;
        }
    }
    char model[256];
    bench_cpu_model(model, sizeof model);
    printf("narrow_cpu_core, dense against tiled: fastest of %d calls per row; %s\n", reps, model);

    pp_raster flat = terrain_raster(0, 0, 0, 0);
    /* A crater of radius 40 whose centre is 10 px under the hilly surface at x = 2000. */
    const double crater_x = 2000, crater_r = 40;
    const double crater_y = TOP + 60 * sin(crater_x / 200.0) + 15 * sin(crater_x / 37.0) + 10;
    pp_raster hilly = terrain_raster(1, crater_x, crater_y, crater_r);
    pp_raster crate = box_raster(32, 32), big = box_raster(256, 256), box128 = box_raster(128, 128);
    /* Two 128 px boxes at 0.3 and 1.1 rad, side by side, moved together until they are 4 px deep. */
    const np_settings probe = {PP_NORMAL_AREA_GRADIENT, PP_CONTACT_MANIFOLD, 1};
    const np_body box_a = body_at(&box128, 500, 500, 0.3);
    double bx = 500 + 64 * (fabs(cos(0.3)) + fabs(sin(0.3)) + fabs(cos(1.1)) + fabs(sin(1.1)));
    for (;; bx -= 0.25) {
        const np_body box_b = body_at(&box128, bx, 500, 1.1);
        np_scratch s = {0};
        np_result res;
        narrow_cpu_collide(&probe, &box_a, &box_b, &s, &res);
        np_scratch_free(&s);
        if (res.count > 0 && res.contacts[0].depth >= 4)
            break;
    }
    const scenario sc[] = {
        {"crate_on_flat", body_at(&flat, TW / 2.0, TH / 2.0, 0), body_at(&crate, 1000.5, TOP - 16 + 1, 0)},
        {"crate_in_crater", body_at(&hilly, TW / 2.0, TH / 2.0, 0),
         body_at(&crate, crater_x, crater_y + crater_r - 16 + 1, 0.05)},
        {"box256_half_sunk", body_at(&flat, TW / 2.0, TH / 2.0, 0), body_at(&big, 1000.5, TOP, 0)},
        {"box256_half_sunk_tilted", body_at(&flat, TW / 2.0, TH / 2.0, 0), body_at(&big, 1000.5, TOP, 0.2)},
        {"box128_pair_rotated", box_a, body_at(&box128, bx, 500, 1.1)},
    };
    const pp_normal_method methods[2] = {PP_NORMAL_AREA_GRADIENT, PP_NORMAL_KERNEL};
    printf("%-24s %-8s %6s %9s %12s %12s %8s %12s %12s %s\n", "scenario", "normal", "stride", "cells", "dense_ns",
           "tiled_ns", "speedup", "dense_Mc/s", "tiled_Mc/s", "same");
    np_scratch scratch = {0};
    int differ = 0;
    for (size_t i = 0; i < sizeof sc / sizeof sc[0]; i++) {
        if (only && !strstr(sc[i].name, only))
            continue;
        for (int m = 0; m < 2; m++)
            for (int stride = 1; stride <= 4; stride *= 2) {
                const np_settings set = {methods[m], PP_CONTACT_MANIFOLD, stride};
                np_pair p;
                if (!np_pair_setup(&set, &sc[i].a, &sc[i].b, &p)) {
                    printf("%-24s no overlap\n", sc[i].name);
                    continue;
                }
                const double cells = (double)np_pair_cells(&p);
                np_core cd = {0}, ct = {0};
                const double td = which & 1 ? time_core(narrow_cpu_core_dense, &set, &p, &scratch, reps, &cd) : 0;
                const double tt = which & 2 ? time_core(narrow_cpu_core, &set, &p, &scratch, reps, &ct) : 0;
                const int same = which != 3 || !memcmp(&cd, &ct, sizeof cd);
                differ += !same;
                printf("%-24s %-8s %6d %9.0f %12.0f %12.0f %8.1f %12.1f %12.1f %s (count %lld)\n", sc[i].name,
                       m ? "kernel" : "gradient", stride, cells, td, tt, td > 0 && tt > 0 ? td / tt : 0,
                       td > 0 ? cells / td * 1e3 : 0, tt > 0 ? cells / tt * 1e3 : 0, same ? "yes" : "NO",
                       (long long)(which & 1 ? cd.count : ct.count));
            }
    }
    np_scratch_free(&scratch);
    printf("cells: the sampled plane (inner grid plus ring); Mc/s: millions of those per second\n");
    /* Memory per pixel from raster_memory_bytes, the mask alone and then with a weight plane. */
    pp_raster *mem[2] = {&flat, &crate};
    const char *mem_name[2] = {"4096x2048 terrain", "32x32 crate"};
    for (int k = 0; k < 2; k++) {
        const double px = (double)mem[k]->width * mem[k]->height, mask_only = 8.0 * raster_memory_bytes(mem[k]) / px;
        if (raster_ensure_weights("bench_core", mem[k]) != PP_OK)
            return 1;
        printf("raster memory, %s: %.3f bits/px mask only, %.3f with weights\n", mem_name[k], mask_only,
               8.0 * raster_memory_bytes(mem[k]) / px);
    }
    raster_free(&flat), raster_free(&hilly), raster_free(&crate), raster_free(&big), raster_free(&box128);
    return differ ? 1 : 0;
}
