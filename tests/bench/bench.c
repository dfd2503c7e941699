/* PhysPix benchmark: named scenes, each run with raster bodies and with ODE's analytic boxes
 * under the same solver settings in the same process; the minimum over runs of the median
 * ms per pp_world_step, printed as a table and written as CSV.
 *
 *   bench [--csv PATH] [--quick] [--runs N] [--scene NAME]
 */
#include "bench.h"
#include "physpix.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { ENGINE_RASTER, ENGINE_ANALYTIC, ENGINE_COUNT };
static const char *const engine_names[ENGINE_COUNT] = {"raster", "analytic"};

typedef struct options {
    const char *csv_path; ///< NULL: no CSV
    int quick;            ///< nonzero: few steps, one run
    int runs;             ///< repeats of each measurement
    const char *only;     ///< NULL: every scene
} options;

/// One engine's result on one scene, over all runs.
typedef struct engine_result {
    double ms_median;     ///< minimum over runs of the median ms/step
    bench_run first;      ///< the first run (contacts, phases, drop, awake, lost)
    double drop_spread;   ///< largest difference of the tracked drop between runs, px
    double contacts_spread;
} engine_result;

static void usage(FILE *f)
{
    fprintf(f, "usage: bench [--csv PATH] [--quick] [--runs N] [--scene pyramid|rain]\n"
               "  --csv PATH   also write the table as CSV\n"
               "  --quick      smoke run: 60 steps, one run\n"
               "  --runs N     repeats of each measurement (default 3; the minimum median is kept)\n"
               "  --scene S    run one scene only\n");
}

static int parse_options(int argc, char **argv, options *o)
{
    *o = (options){.runs = 3};
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
            o->csv_path = argv[++i];
        } else if (strcmp(argv[i], "--quick") == 0) {
            o->quick = 1;
        } else if (strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
            o->runs = atoi(argv[++i]);
            if (o->runs < 1) {
                fprintf(stderr, "bench: --runs needs a positive count\n");
                return -1;
            }
        } else if (strcmp(argv[i], "--scene") == 0 && i + 1 < argc) {
            o->only = argv[++i];
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

static void print_settings(const bench_settings *s, const options *o)
{
    bench_print_settings(s);
    printf("runs: %d per measurement (minimum of the per-run medians)%s\n\n", o->runs,
           o->quick ? ", --quick" : "");
}

static double absd(double x) { return x < 0 ? -x : x; }

/* Runs alternate between the engines so that a slow patch of the machine hits both. */
static int measure_scene(const bench_scene *scene, const bench_settings *set, int runs,
                         engine_result results[ENGINE_COUNT])
{
    double *step_ms = malloc((size_t)scene->steps * sizeof *step_ms);
    if (!step_ms) {
        fprintf(stderr, "bench: out of memory\n");
        return -1;
    }
    for (int r = 0; r < runs; r++) {
        for (int e = 0; e < ENGINE_COUNT; e++) {
            bench_run run = {.step_ms = step_ms};
            int rc = e == ENGINE_RASTER ? bench_run_physpix(scene, set, &run) : bench_run_ode(scene, set, &run);
            if (rc != 0) {
                free(step_ms);
                return -1;
            }
            double med = bench_median(step_ms, scene->steps);
            engine_result *res = &results[e];
            if (r == 0) {
                *res = (engine_result){.ms_median = med, .first = run};
            } else {
                if (med < res->ms_median)
                    res->ms_median = med;
                double dd = absd(run.tracked_drop - res->first.tracked_drop);
                double dc = absd(run.contacts_mean - res->first.contacts_mean);
                res->drop_spread = dd > res->drop_spread ? dd : res->drop_spread;
                res->contacts_spread = dc > res->contacts_spread ? dc : res->contacts_spread;
            }
            res->first.step_ms = NULL;
        }
    }
    free(step_ms);
    return 0;
}

static void print_header(void)
{
    printf("%-8s %-9s %6s %5s %10s %10s %7s %9s %9s %6s %5s %8s\n", "scene", "engine", "bodies", "steps", "ms/step",
           "contacts", "ratio", "collide", "solver", "awake", "lost", "sag_px");
    printf("%-8s %-9s %6s %5s %10s %10s %7s %9s %9s %6s %5s %8s\n", "", "", "", "", "median", "per step", "r/a",
           "ms/step", "ms/step", "at end", "", "top box");
}

static void print_row(const bench_scene *scene, int engine, const engine_result *res, double ratio)
{
    const bench_run *run = &res->first;
    char sag[32] = "-";
    if (scene->tracked >= 0)
        snprintf(sag, sizeof sag, "%.2f", run->tracked_drop);
    printf("%-8s %-9s %6d %5d %10.4f %10.1f %7.3f %9.4f %9.4f %6d %5d %8s\n", scene->name, engine_names[engine],
           scene->dynamic_count, scene->steps, res->ms_median, run->contacts_mean, ratio,
           run->phase_ms[0] + run->phase_ms[1], run->phase_ms[2], run->awake_end, run->lost, sag);
}

static void print_notes(const bench_scene *scene, const engine_result results[ENGINE_COUNT])
{
    const bench_run *raster = &results[ENGINE_RASTER].first;
    printf("         raster phases per step: broadphase %.4f ms, narrowphase %.4f ms, solver %.4f ms (backend %d)\n",
           raster->phase_ms[0], raster->phase_ms[1], raster->phase_ms[2], raster->backend);
    for (int e = 0; e < ENGINE_COUNT; e++) {
        if (results[e].drop_spread > 0.0 || results[e].contacts_spread > 0.0)
            printf("         note: %s runs of %s differ (drop by %.3g px, contacts by %.3g): not deterministic\n",
                   engine_names[e], scene->name, results[e].drop_spread, results[e].contacts_spread);
    }
}

static void write_csv_rows(FILE *csv, const bench_scene *scene, const engine_result results[ENGINE_COUNT],
                           const double ratio[ENGINE_COUNT])
{
    for (int e = 0; e < ENGINE_COUNT; e++)
        fprintf(csv, "%s,%s,%d,%d,%.6f,%.3f,%.4f\n", scene->name, engine_names[e], scene->dynamic_count,
                scene->steps, results[e].ms_median, results[e].first.contacts_mean, ratio[e]);
}

int main(int argc, char **argv)
{
    options opt;
    if (parse_options(argc, argv, &opt) != 0)
        return 2;

    const int steps = opt.quick ? 60 : 600;
    bench_settings set = bench_settings_from_defaults();
    bench_print_machine("benchmark");
    print_settings(&set, &opt);

    FILE *csv = NULL;
    if (opt.csv_path) {
        csv = fopen(opt.csv_path, "w");
        if (!csv) {
            perror(opt.csv_path);
            return 1;
        }
        fprintf(csv, "scene,engine,bodies,steps,ms_step_median,contacts_mean,ratio\n");
    }

    int (*const builders[])(bench_scene *, int) = {bench_scene_pyramid, bench_scene_rain};
    int failed = 0, ran = 0;
    double t_start = bench_now_ms();
    print_header();
    for (size_t k = 0; k < sizeof builders / sizeof builders[0] && !failed; k++) {
        bench_scene scene;
        if (builders[k](&scene, steps) != 0) {
            failed = 1;
            break;
        }
        if (!opt.only || strcmp(opt.only, scene.name) == 0) {
            engine_result results[ENGINE_COUNT];
            if (measure_scene(&scene, &set, opt.runs, results) == 0) {
                double analytic = results[ENGINE_ANALYTIC].ms_median;
                double ratio[ENGINE_COUNT] = {analytic > 0 ? results[ENGINE_RASTER].ms_median / analytic : 0.0, 1.0};
                for (int e = 0; e < ENGINE_COUNT; e++)
                    print_row(&scene, e, &results[e], ratio[e]);
                print_notes(&scene, results);
                if (csv)
                    write_csv_rows(csv, &scene, results, ratio);
                ran++;
            } else {
                failed = 1;
            }
        }
        bench_scene_free(&scene);
    }
    printf("\nwall time %.1f s\n", (bench_now_ms() - t_start) * 1e-3);
    bench_ode_shutdown();

    if (csv && fclose(csv) != 0) {
        perror(opt.csv_path);
        failed = 1;
    }
    if (!failed && ran == 0) {
        fprintf(stderr, "bench: no scene named %s\n", opt.only);
        failed = 1;
    }
    if (csv && !failed)
        printf("wrote %s\n", opt.csv_path);
    return failed ? 1 : 0;
}
