/* PhysPix scaling benchmark: how the cost of a step or of one collision grows with the number
 * of bodies, the terrain's bitmap, the bodies' bitmaps, the overlap and the edits per step,
 * each curve beside the same scene with ODE's analytic boxes in the same run where one exists.
 *
 *   bench_scale [--csv PATH] [--quick] [--curve bodies|terrain|body_size|overlap|edits]
 */
#include "scale.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct curve {
    const char *name;                 ///< --curve NAME and the CSV's `curve` column
    int (*run)(const scale_ctx *ctx); ///< prints its table and emits its rows
} curve;

static const curve curves[] = {
    {"bodies", scale_curve_bodies},   {"terrain", scale_curve_terrain}, {"body_size", scale_curve_body_size},
    {"overlap", scale_curve_overlap}, {"edits", scale_curve_edits},
};
enum { CURVE_COUNT = sizeof curves / sizeof curves[0] };

static void usage(FILE *f)
{
    fprintf(f, "usage: bench_scale [--csv PATH] [--quick] [--curve NAME]\n"
               "  --csv PATH    also write every row as CSV (one file, a `curve` column)\n"
               "  --quick       smoke run: few points, few steps\n"
               "  --curve NAME  run one curve: bodies, terrain, body_size, overlap or edits\n");
}

void scale_emit(const scale_ctx *ctx, const scale_row *r)
{
    if (!ctx->csv)
        return;
    fprintf(ctx->csv, "%s,%s,%.0f,%s,%s,%d,%.6f,%.6f,%.2f,%.2f,%.5f,%.5f,%d,%.6f,%.4f\n", r->curve, r->variant, r->x,
            r->label, r->engine, r->timed, r->ms, r->narrow_ms, r->contacts, r->pairs, r->us_contact, r->us_pair,
            r->awake, r->edit_ms, r->ratio);
}

/* The 1-minute load average: the machine is shared, and a busy one slows every curve. */
static void print_load(void)
{
    double load = -1.0;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f && fscanf(f, "%lf", &load) != 1)
        load = -1.0;
    if (f)
        fclose(f);
    if (load >= 0)
        printf("load average at start: %.2f (1 min)\n", load);
}

int main(int argc, char **argv)
{
    const char *csv_path = NULL, *only = NULL;
    scale_ctx ctx = {.set = bench_settings_from_defaults()};
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
            csv_path = argv[++i];
        } else if (strcmp(argv[i], "--quick") == 0) {
            ctx.quick = 1;
        } else if (strcmp(argv[i], "--curve") == 0 && i + 1 < argc) {
            only = argv[++i];
        } else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            return 0;
        } else {
            usage(stderr);
            return 2;
        }
    }
    int selected = 0;
    for (int c = 0; c < CURVE_COUNT; c++)
        selected += !only || strcmp(only, curves[c].name) == 0;
    if (!selected) {
        fprintf(stderr, "bench_scale: no curve named %s\n", only);
        usage(stderr);
        return 2;
    }

    bench_print_machine("scaling benchmark");
    print_load();
    bench_print_settings(&ctx.set);
    printf("each curve's title names its sleep setting, its timed steps and its runs (the smallest median is kept)%s\n",
           ctx.quick ? "; --quick" : "");

    if (csv_path) {
        ctx.csv = fopen(csv_path, "w");
        if (!ctx.csv) {
            perror(csv_path);
            return 1;
        }
        fprintf(ctx.csv, "curve,variant,x,label,engine,timed,ms_median,narrow_ms,contacts,pairs,"
                         "narrow_us_per_contact,narrow_us_per_pair,awake_bodies,edit_ms,ratio_raster_analytic\n");
    }

    int failed = 0;
    double t_start = bench_now_ms();
    for (int c = 0; c < CURVE_COUNT && !failed; c++) {
        if (only && strcmp(only, curves[c].name) != 0)
            continue;
        double t0 = bench_now_ms();
        failed = curves[c].run(&ctx) != 0;
        printf("(%s: %.1f s)\n", curves[c].name, (bench_now_ms() - t0) * 1e-3);
    }
    printf("\nwall time %.1f s\n", (bench_now_ms() - t_start) * 1e-3);
    bench_ode_shutdown();

    if (ctx.csv && fclose(ctx.csv) != 0) {
        perror(csv_path);
        failed = 1;
    }
    if (ctx.csv && !failed)
        printf("wrote %s\n", csv_path);
    return failed ? 1 : 0;
}
