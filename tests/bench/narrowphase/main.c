/* PhysPix narrowphase benchmark: N static-dynamic pairs of S×S full overlap, stepped on the CPU
 * backend, the GPU backend and AUTO; the minimum over runs of the median narrowphase ms per step,
 * printed as a table with the GPU/CPU crossover and written as CSV.
 *
 *   bench_narrow [--csv PATH] [--quick] [--runs N] [--max-cells N]
 */
#include "../machine.h"
#include "physpix.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

enum { ENG_CPU, ENG_GPU, ENG_AUTO, ENG_COUNT };
static const pp_backend engine_backend[ENG_COUNT] = {PP_BACKEND_CPU, PP_BACKEND_GPU, PP_BACKEND_AUTO};
static const int all_pairs[] = {1, 10, 100, 1000, 10000}, quick_pairs[] = {1, 100, 1000};
static const int all_sides[] = {16, 32, 64, 128, 256, 512, 1024}, quick_sides[] = {16, 64, 256};
#define NP_MAX 5
#define NS_MAX 7

typedef struct options {
    const char *csv_path;
    int quick, runs;
    long long max_cells;
} options;

/* One configuration's outcome; ms < 0 means not measured. */
typedef struct result {
    int skipped;
    long long cells;
    double ms[ENG_COUNT];
    pp_backend auto_ran;
} result;

/* The three worlds of one configuration, with the start poses of the B's. */
typedef struct scene {
    pp_world w[ENG_COUNT]; ///< id 0: engine not run
    pp_body *b[ENG_COUNT];
    pp_vec2 *start;
    int n;
} scene;

static void usage(FILE *f)
{
    fprintf(f, "usage: bench_narrow [--csv PATH] [--quick] [--runs N] [--max-cells N]\n"
               "  --csv PATH      also write the table as CSV\n"
               "  --quick         smoke run: N 1,100,1000 x S 16,64,256, 3 steps, one run\n"
               "  --runs N        repeats of each measurement (default 3; the minimum median is kept)\n"
               "  --max-cells N   skip configurations with N*S^2 above this (default 2^28)\n");
}

static int parse_options(int argc, char **argv, options *o)
{
    *o = (options){.runs = 3, .max_cells = 1LL << 28};
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
            o->csv_path = argv[++i];
        } else if (strcmp(argv[i], "--quick") == 0) {
            o->quick = 1;
        } else if (strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
            if ((o->runs = atoi(argv[++i])) < 1)
                return fprintf(stderr, "bench_narrow: --runs needs a positive count\n"), -1;
        } else if (strcmp(argv[i], "--max-cells") == 0 && i + 1 < argc) {
            if ((o->max_cells = atoll(argv[++i])) < 1)
                return fprintf(stderr, "bench_narrow: --max-cells needs a positive count\n"), -1;
        } else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            exit(0);
        } else {
            usage(stderr);
            return -1;
        }
    }
    if (o->quick)
        o->runs = 1;
    return 0;
}

static void *xmalloc(size_t bytes)
{
    void *p = malloc(bytes);
    if (!p) {
        fprintf(stderr, "bench_narrow: out of memory (%zu bytes)\n", bytes);
        exit(1);
    }
    return p;
}

static void check(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "bench_narrow: %s: %s: %s\n", what, pp_status_name(st), pp_last_error());
        exit(1);
    }
}

/* Each AUTO world logs the same "stays on the CPU" line; print a message only when it changes. */
static void log_hook(int level, const char *msg, void *user)
{
    (void)user;
    static char last[512];
    if (level >= 1 && strcmp(msg, last) != 0) {
        snprintf(last, sizeof last, "%s", msg);
        printf("log: %s\n", msg);
        fflush(stdout);
    }
}

static void print_machine(const options *o)
{
    char model[256];
    bench_cpu_model(model, sizeof model);
    uint32_t v = pp_version();
    printf("PhysPix %u.%u.%u narrowphase benchmark\n", v / 10000, v / 100 % 100, v % 100);
    printf("machine: %ld cpus online, %s\nGPU: see PHYSPIX log\n", sysconf(_SC_NPROCESSORS_ONLN), model);
    printf("runs: %d per measurement (minimum of the per-run medians of narrowphase_ms), budget %lld cells%s\n",
           o->runs, o->max_cells, o->quick ? ", --quick" : "");
}

/* Bring the GPU up once before the table so its log line comes first and a failure is told once. */
static int probe_gpu(void)
{
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_GPU;
    pp_world w;
    pp_status st = pp_world_create(&d, &w);
    if (st == PP_ERR_UNSUPPORTED) {
        printf("GPU backend unavailable: %s\n", pp_last_error());
        return 0;
    }
    check(st, "pp_world_create (GPU probe)");
    check(pp_world_destroy(w), "pp_world_destroy");
    return 1;
}

static void scene_free(scene *sc)
{
    for (int e = 0; e < ENG_COUNT; e++) {
        if (sc->w[e].id)
            check(pp_world_destroy(sc->w[e]), "pp_world_destroy");
        free(sc->b[e]);
    }
    free(sc->start);
}

/* A solid static L×L body A covering world [0, L)², and n solid S×S B's on a grid inside it;
 * categories keep the B's apart, so the broadphase yields exactly n pairs. */
static void scene_build(scene *sc, int n, int side, int gpu_ok)
{
    *sc = (scene){.n = n};
    const int g = (int)ceil(sqrt((double)n));
    long long l = (long long)g * side / 2 + side;
    l = l < 2 * side ? 2 * side : l > 8192 ? 8192 : l;
    /* Spacing S/2, shrunk when the cap on L leaves less room, so every B stays inside A. */
    const int spacing = g > 1 && (l - side) / (g - 1) < side / 2 ? (int)((l - side) / (g - 1)) : side / 2;
    const long long first = (l - (long long)(g - 1) * spacing) / 2;
    uint8_t *mask_a = xmalloc((size_t)(l * l)), *mask_b = xmalloc((size_t)side * side);
    sc->start = xmalloc((size_t)n * sizeof *sc->start);
    memset(mask_a, 1, (size_t)(l * l));
    memset(mask_b, 1, (size_t)side * side);
    for (int i = 0; i < n; i++)
        sc->start[i] = (pp_vec2){(float)(first + (i % g) * spacing), (float)(first + (i / g) * spacing)};

    for (int e = 0; e < ENG_COUNT; e++) {
        if (e == ENG_GPU && !gpu_ok)
            continue;
        pp_world_def wd = pp_world_def_default();
        wd.gravity = (pp_vec2){0, 0};
        wd.substeps = 1;
        wd.backend = engine_backend[e];
        check(pp_world_create(&wd, &sc->w[e]), "pp_world_create");
        pp_body_def a = pp_body_def_default();
        a.type = PP_BODY_STATIC;
        a.position = (pp_vec2){(float)l / 2, (float)l / 2};
        a.width = a.height = (int32_t)l;
        a.mask = mask_a;
        a.category_bits = 1, a.mask_bits = 2;
        pp_body body_a;
        check(pp_body_create(sc->w[e], &a, &body_a), "pp_body_create (A)");
        sc->b[e] = xmalloc((size_t)n * sizeof *sc->b[e]);
        for (int i = 0; i < n; i++) {
            pp_body_def b = pp_body_def_default();
            b.position = sc->start[i];
            b.width = b.height = side;
            b.mask = mask_b;
            b.category_bits = 2, b.mask_bits = 1;
            check(pp_body_create(sc->w[e], &b, &sc->b[e][i]), "pp_body_create (B)");
        }
    }
    free(mask_a);
    free(mask_b);
}

/* One step from the start poses, so the solver's push-out never changes the work. */
static pp_step_stats step_once(scene *sc, int e)
{
    for (int i = 0; i < sc->n; i++) {
        check(pp_body_set_transform(sc->w[e], sc->b[e][i], sc->start[i], 0), "pp_body_set_transform");
        check(pp_body_set_velocity(sc->w[e], sc->b[e][i], (pp_vec2){0, 0}, 0), "pp_body_set_velocity");
    }
    check(pp_world_step(sc->w[e], 1.0f / 60.0f), "pp_world_step");
    pp_step_stats s;
    check(pp_world_get_stats(sc->w[e], &s), "pp_world_get_stats");
    if (s.pairs != sc->n || s.contacts < sc->n) {
        fprintf(stderr, "bench_narrow: N=%d: %d pairs and %d contacts per step, expected %d and >= %d\n", sc->n,
                (int)s.pairs, (int)s.contacts, sc->n, sc->n);
        exit(1);
    }
    return s;
}

/* Runs alternate between the engines so that a slow patch of the machine hits all of them. */
static void measure(int n, int side, const options *o, int gpu_ok, result *r)
{
    const long long work = (long long)n * side * side;
    /* About 2^24 cells of timed work per run; down to one step per run for the largest, where
     * llvmpipe takes up to 20 s a step (a floor of three: an estimated 18-minute full run). */
    const long long kw = (1LL << 24) / work;
    const int k = o->quick ? 3 : kw < 1 ? 1 : kw > 30 ? 30 : (int)kw;
    double ms[30];
    scene sc;
    scene_build(&sc, n, side, gpu_ok);
    for (int e = 0; e < ENG_COUNT; e++) {
        r->ms[e] = -1;
        if (sc.w[e].id)
            (void)step_once(&sc, e); /* warm-up: the GPU uploads masks and compiles on first use */
    }
    for (int run = 0; run < o->runs; run++) {
        for (int e = 0; e < ENG_COUNT; e++) {
            if (!sc.w[e].id)
                continue;
            for (int s = 0; s < k; s++) {
                const pp_step_stats st = step_once(&sc, e);
                ms[s] = st.narrowphase_ms;
                if (e == ENG_CPU)
                    r->cells = st.pixels_tested;
                if (e == ENG_AUTO)
                    r->auto_ran = st.backend;
            }
            qsort(ms, (size_t)k, sizeof *ms, bench_cmp_double);
            const double med = k % 2 ? ms[k / 2] : 0.5 * (ms[k / 2 - 1] + ms[k / 2]);
            if (r->ms[e] < 0 || med < r->ms[e])
                r->ms[e] = med;
        }
    }
    scene_free(&sc);
}

/* A GPU figure, or "n/a" (negative) where the GPU backend could not run. */
static void fmt_gpu(char *buf, size_t size, double v, const char *spec)
{
    snprintf(buf, size, v < 0 ? "n/a" : spec, v);
}

static void print_row(int n, int side, const result *r, FILE *csv)
{
    char ov[32];
    snprintf(ov, sizeof ov, "%dx%d", side, side);
    if (r->skipped) {
        printf("%6d %10s   skipped (over budget)\n", n, ov);
        return;
    }
    const double cpu = r->ms[ENG_CPU], gpu = r->ms[ENG_GPU], c = (double)r->cells;
    char g_ms[32], ratio[32], g_rate[32];
    fmt_gpu(g_ms, sizeof g_ms, gpu, "%.3f");
    fmt_gpu(ratio, sizeof ratio, gpu < 0 || cpu <= 0 ? -1 : gpu / cpu, "%.2f");
    fmt_gpu(g_rate, sizeof g_rate, gpu <= 0 ? -1 : c / gpu * 1e-3, "%.1f");
    const char *auto_name = r->auto_ran == PP_BACKEND_GPU ? "GPU" : "CPU";
    printf("%6d %10s %12lld %10.3f %10s %7s %9.1f %9s %5s %10.3f\n", n, ov, r->cells, cpu, g_ms, ratio,
           cpu > 0 ? c / cpu * 1e-3 : 0.0, g_rate, auto_name, r->ms[ENG_AUTO]);
    fflush(stdout);
    if (csv) {
        fprintf(csv, "%d,%d,%lld,%.6f,", n, side, r->cells, cpu);
        if (gpu >= 0)
            fprintf(csv, "%.6f,%.4f,%.3f,%.3f,", gpu, gpu / cpu, c / cpu * 1e-3, c / gpu * 1e-3);
        else
            fprintf(csv, ",,%.3f,,", c / cpu * 1e-3);
        fprintf(csv, "%s,%.6f\n", auto_name, r->ms[ENG_AUTO]);
    }
}

static void print_crossover(const int *pairs, int np, const int *sides, int ns, result res[NP_MAX][NS_MAX])
{
    long long best = -1;
    printf("\ncrossover (smallest N at which GPU ms < CPU ms):\n");
    for (int j = 0; j < ns; j++) {
        int found = -1;
        for (int i = 0; i < np; i++) {
            const result *r = &res[i][j];
            if (r->skipped || r->ms[ENG_GPU] < 0 || r->ms[ENG_GPU] >= r->ms[ENG_CPU])
                continue;
            if (found < 0)
                found = pairs[i];
            if (best < 0 || r->cells < best)
                best = r->cells;
        }
        char at[32] = "none";
        if (found >= 0)
            snprintf(at, sizeof at, "N=%d", found);
        printf("  S=%-5d %s\n", sides[j], at);
    }
    char cells[32] = "none measured";
    if (best >= 0)
        snprintf(cells, sizeof cells, "%lld", best);
    printf("smallest cells/step at which the GPU wins: %s\n", cells);
}

int main(int argc, char **argv)
{
    options opt;
    if (parse_options(argc, argv, &opt) != 0)
        return 2;
    pp_set_log_hook(log_hook, NULL);
    print_machine(&opt);
    const int gpu_ok = probe_gpu();

    FILE *csv = NULL;
    if (opt.csv_path) {
        if (!(csv = fopen(opt.csv_path, "w"))) {
            perror(opt.csv_path);
            return 1;
        }
        fprintf(csv, "pairs,side,cells,cpu_ms,gpu_ms,ratio,cpu_mcells_s,gpu_mcells_s,auto_backend,auto_ms\n");
    }

    const int *pairs = opt.quick ? quick_pairs : all_pairs, *sides = opt.quick ? quick_sides : all_sides;
    const int np = opt.quick ? 3 : NP_MAX, ns = opt.quick ? 3 : NS_MAX;
    static result res[NP_MAX][NS_MAX];
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    printf("\n%6s %10s %12s %10s %10s %7s %9s %9s %5s %10s\n", "pairs", "overlap", "cells/step", "CPU ms", "GPU ms",
           "GPU/CPU", "CPU Mc/s", "GPU Mc/s", "AUTO", "AUTO ms");
    for (int i = 0; i < np; i++) {
        for (int j = 0; j < ns; j++) {
            result *r = &res[i][j];
            r->skipped = (long long)pairs[i] * sides[j] * sides[j] > opt.max_cells;
            if (!r->skipped)
                measure(pairs[i], sides[j], &opt, gpu_ok, r);
            print_row(pairs[i], sides[j], r, csv);
        }
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    print_crossover(pairs, np, sides, ns, res);
    printf("\nwall time %.1f s\n", (double)(t1.tv_sec - t0.tv_sec) + (t1.tv_nsec - t0.tv_nsec) * 1e-9);

    if (csv) {
        if (fclose(csv) != 0) {
            perror(opt.csv_path);
            return 1;
        }
        printf("wrote %s\n", opt.csv_path);
    }
    return 0;
}
