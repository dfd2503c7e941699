/* Stability against Box2D 2.4 and Chipmunk 7 (issue 22): every scene of stability.h on PhysPix's three
 * presets and on the peers, one table line per scene and engine, and CSV. Exit status 0 even when a stack
 * falls: the table says what fell.
 *
 *   bench_stability [--quick] [--only TEXT] [--engine TEXT] [--offset PX] [--csv PATH]
 */
#include "../bench.h"
#include "../machine.h"
#include "peers.h"
#include "stability.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_ENGINES 6

typedef struct options {
    int quick;
    double offset;
    const char *only, *engine, *csv_path;
} options;

static void usage(FILE *f)
{
    fprintf(f, "usage: bench_stability [--quick] [--only TEXT] [--engine TEXT] [--offset PX] [--csv PATH]\n"
               "  --quick        watch stacks 10 s instead of 60 s\n"
               "  --offset PX    move every body of the stacking scenes PX along x (0..1: where the pixel grid\n"
               "                 falls on them; a card house's outcome depends on it)\n"
               "  --only TEXT    scenes whose name contains TEXT (e.g. tower20, heavy1000, shot)\n"
               "  --engine TEXT  engines whose name contains TEXT (e.g. BALANCED, PhysPix, Box2D, it30)\n"
               "  --csv PATH     also write the table as CSV\n"
               "matching ignores case\n");
}

static int parse_options(int argc, char **argv, options *o)
{
    *o = (options){0};
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--quick") == 0)
            o->quick = 1;
        else if (strcmp(argv[i], "--only") == 0 && i + 1 < argc)
            o->only = argv[++i];
        else if (strcmp(argv[i], "--engine") == 0 && i + 1 < argc)
            o->engine = argv[++i];
        else if (strcmp(argv[i], "--offset") == 0 && i + 1 < argc)
            o->offset = atof(argv[++i]);
        else if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc)
            o->csv_path = argv[++i];
        else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            exit(0);
        } else {
            usage(stderr);
            return -1;
        }
    }
    return 0;
}

static int make_engines(stab_engine *out)
{
    int n = 0;
    out[n++] = stab_engine_physpix(PP_PRESET_FAST);
    out[n++] = stab_engine_physpix(PP_PRESET_BALANCED);
    out[n++] = stab_engine_physpix(PP_PRESET_ACCURATE);
    out[n++] = stab_engine_box2d();
    out[n++] = stab_engine_chipmunk(10); /* Chipmunk's default */
    out[n++] = stab_engine_chipmunk(30);
    return n;
}

static void print_header(const options *o, const stab_engine *engines, int n, double run_s)
{
    bench_print_machine(o->quick ? "stability benchmark (--quick)" : "stability benchmark");
    printf("peers: Box2D (b2_version %s; 8 velocity, 3 position iterations; polygon cores inside its 1 px skin),\n"
           "       Chipmunk %s (10 or 30 iterations, as named; no CCD)\n",
           stab_box2d_version(), stab_chipmunk_version());
    printf("PhysPix rows (substeps x iterations, sleep off):");
    for (int i = 0; i < n; i++)
        if (strncmp(engines[i].name, "PhysPix", 7) == 0)
            printf(" %s %dx%d%s%s", engines[i].name + 8, engines[i].world_def.substeps,
                   engines[i].world_def.solver_iterations, engines[i].world_def.exact_solver ? " exact" : "",
                   engines[i].world_def.contact_mode == PP_CONTACT_CENTROID ? " centroid" : "");
    printf("\n100 px = 1 m, gravity (0, %.0f) px/s^2, dt 1/60 s, one step a frame, sleep off in every engine;\n"
           "stacks settle 1 s, then are watched %.0f s: 'stands' = no body moved over 1/4 of its size (its longest\n"
           "side) from the settled pose; drift = the largest such move, px; fall = when one first did, s (a fallen\n"
           "stack runs 1 s more); crush = the tracked heavy box's sink below its settled pose at the end, px.\n"
           "cardhouse_v3, arch_v3 (Box2D v3's samples): watched at most 30 s, and from where they were built:\n"
           "'stands' = no body moved 20 px (card house) or 50 px (arch) from there, settle included.\n"
           "value / ref / err%%: roll, ramp35 = acceleration down the slope (parabola fitted over 0.5-1.5 s), px/s^2,\n"
           "against 2/3 g sin(a) and g(sin a - mu cos a); ref2 / err2%% (roll) = the body's own g sin(a)/(1 + I/(m r^2));\n"
           "ramp20 = slide over 2 s, px; bounce = first rebound apex (bottom above ground), px, against e^2 * 200\n"
           "(bounce10: of the first 10 rebounds' apexes, the one farthest from 200);\n"
           "shot = the box's leading face past the wall's near face after 1 s, px (0: stopped at it; 8: through).\n"
           "ms/step: median over the frames run after the settle.\n",
           STAB_GRAVITY, run_s);
    if (o->offset != 0)
        printf("stacking scenes moved %.3f px along x (--offset)\n", o->offset);
    printf("\n");
    printf("%-14s %-17s %-9s %8s %6s %8s %9s %9s %8s %9s %8s %8s\n", "scene", "engine", "result", "drift", "fall",
           "crush", "value", "ref", "err%", "ref2", "err2%", "ms/step");
}

static void print_row(FILE *csv, const stab_scene *s, const stab_engine *e, const stab_result *r)
{
    char b[8][32];
    printf("%-14s %-17s %-9s %8s %6s %8s %9s %9s %8s %9s %8s %8.3f\n", s->name, e->name, stab_verdict_name(r->verdict),
           bench_fmt(b[0], 32, "%.2f", r->drift), bench_fmt(b[1], 32, "%.2f", r->fall_s),
           bench_fmt(b[2], 32, "%.2f", r->crush), bench_fmt(b[3], 32, "%.2f", r->value),
           bench_fmt(b[4], 32, "%.2f", r->ref), bench_fmt(b[5], 32, "%+.2f", r->err_pct), bench_fmt(b[6], 32, "%.2f", r->ref2), bench_fmt(b[7], 32, "%+.2f", r->err2_pct), r->ms_median);
    fflush(stdout);
    if (!csv)
        return;
    fprintf(csv, "%s,%s,%s", s->name, e->name, stab_verdict_name(r->verdict));
    const double figures[] = {r->drift, r->fall_s, r->crush, r->settle_sink, r->value, r->ref,
                              r->err_pct, r->ref2, r->err2_pct, r->ms_median};
    for (size_t i = 0; i < sizeof figures / sizeof figures[0]; i++)
        bench_csv_field(csv, figures[i]);
    fprintf(csv, ",%d\n", r->frames);
}

int main(int argc, char **argv)
{
    options opt;
    if (parse_options(argc, argv, &opt) != 0)
        return 2;
    stab_engine engines[MAX_ENGINES];
    const int nengines = make_engines(engines);
    const stab_options run = {.settle_s = 1.0, .run_s = opt.quick ? 10.0 : 60.0};
    print_header(&opt, engines, nengines, run.run_s);

    FILE *csv = NULL;
    if (opt.csv_path && !(csv = fopen(opt.csv_path, "w")))
        return perror(opt.csv_path), 1;
    if (csv)
        fprintf(csv, "scene,engine,result,drift_px,fall_s,crush_px,settle_sink_px,value,reference,error_pct,"
                     "reference2,error2_pct,ms_per_step,frames\n");

    const double t0 = bench_clock_ms();
    int rows = 0;
    for (int i = 0; i < stab_scene_count(); i++) {
        if (!bench_matches(stab_scene_name(i), opt.only))
            continue;
        stab_scene scene;
        if (stab_scene_build(i, &scene) != 0) {
            fprintf(stderr, "bench_stability: out of memory building %s\n", stab_scene_name(i));
            return 1;
        }
        for (int b = 0; scene.kind == STAB_STACK && b < scene.count; b++)
            scene.bodies[b].x += opt.offset;
        for (int k = 0; k < nengines; k++) {
            if (!bench_matches(engines[k].name, opt.engine))
                continue;
            stab_result r;
            (void)stab_run(&engines[k], &scene, &run, &r); /* a failed build is an "error" row */
            print_row(csv, &scene, &engines[k], &r);
            rows++;
        }
        stab_scene_free(&scene);
    }
    printf("\n%d rows, wall time %.1f s\n", rows, (bench_clock_ms() - t0) * 1e-3);
    if (csv && fclose(csv) != 0)
        return perror(opt.csv_path), 1;
    if (csv)
        printf("wrote %s\n", opt.csv_path);
    return 0;
}
