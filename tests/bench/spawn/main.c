/* Crowded spawns: n solid 8 px boxes created at one point, against a settled pile of the same n (a grid
 * resting on a floor, kept awake so that the solver works every step). What the contact budget
 * (PP_CROWDED_CONTACT_PAIRS) bounds: the spawn's first step, its next nine, and how far it has spread.
 * Minimum of the runs; default world settings (4 substeps, QuickStep 40, worker threads one per CPU).
 *
 *   bench_spawn [--csv PATH] [--runs N] [--sizes 250,500,1000]
 */
#include "../machine.h"
#include "physpix.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DT (1.0f / 60.0f)
#define SETTLE_STEPS 120
#define TIMED_STEPS 10
#define MAX_SIZES 8

static void check(pp_status st, const char *what)
{
    if (st == PP_OK)
        return;
    fprintf(stderr, "bench_spawn: %s: %s: %s\n", what, pp_status_name(st), pp_last_error());
    exit(1);
}

/* A world with a static floor 8,000 px wide whose top is at y = 1000. */
static pp_world floor_world(int allow_sleep)
{
    pp_world_def d = pp_world_def_default();
    d.allow_sleep = (uint32_t)allow_sleep;
    pp_world w;
    check(pp_world_create(&d, &w), "pp_world_create");
    uint8_t *mask = malloc(8000 * 20);
    memset(mask, 1, 8000 * 20);
    pp_body_def b = pp_body_def_default();
    b.type = PP_BODY_STATIC, b.position = (pp_vec2){1000, 1010}, b.width = 8000, b.height = 20, b.mask = mask;
    pp_body floor;
    check(pp_body_create(w, &b, &floor), "the floor");
    free(mask);
    return w;
}

static void add_box(pp_world w, float x, float y)
{
    static uint8_t mask[64];
    memset(mask, 1, sizeof mask);
    pp_body_def b = pp_body_def_default();
    b.position = (pp_vec2){x, y}, b.width = b.height = 8, b.mask = mask;
    pp_body out;
    check(pp_body_create(w, &b, &out), "a box");
}

static double step_ms(pp_world w)
{
    const double t0 = bench_clock_ms();
    check(pp_world_step(w, DT), "pp_world_step");
    return bench_clock_ms() - t0;
}

/* Root-mean-square distance of the dynamic bodies from their mean, px (slot 0 is the floor). */
static double spread(pp_world w)
{
    int32_t n = 0;
    check(pp_world_get_bodies(w, NULL, 0, &n), "pp_world_get_bodies");
    pp_body *b = malloc((size_t)n * sizeof *b);
    pp_vec2 *p = malloc((size_t)n * sizeof *p);
    check(pp_world_get_bodies(w, b, n, &n), "pp_world_get_bodies");
    double mx = 0, my = 0, r = 0;
    for (int i = 1; i < n; i++) {
        check(pp_body_get_position(w, b[i], &p[i]), "pp_body_get_position");
        mx += p[i].x, my += p[i].y;
    }
    mx /= n - 1, my /= n - 1;
    for (int i = 1; i < n; i++)
        r += (p[i].x - mx) * (p[i].x - mx) + (p[i].y - my) * (p[i].y - my);
    free(b), free(p);
    return sqrt(r / (n - 1));
}

typedef struct result {
    double settled_ms;     /* median step of the awake settled pile */
    double first_ms;       /* the spawn's first step */
    double next_ms;        /* the mean of its next TIMED_STEPS − 1 */
    int32_t first_contacts, settled_contacts;
    double spread_px;      /* after TIMED_STEPS steps */
} result;

static result run(int n)
{
    result r = {0};
    pp_world w = floor_world(0);
    const int cols = (int)ceil(sqrt(n));
    for (int i = 0; i < n; i++)
        add_box(w, 1000 - cols * 4 + 8.0f * (i % cols) + 4, 1000 - 4 - 8.0f * (i / cols) - 0.5f);
    for (int k = 0; k < SETTLE_STEPS; k++)
        step_ms(w);
    double t[TIMED_STEPS];
    for (int k = 0; k < TIMED_STEPS; k++)
        t[k] = step_ms(w);
    qsort(t, TIMED_STEPS, sizeof *t, bench_cmp_double);
    r.settled_ms = t[TIMED_STEPS / 2];
    check(pp_world_get_contacts(w, NULL, 0, &r.settled_contacts), "pp_world_get_contacts");
    check(pp_world_destroy(w), "pp_world_destroy");

    w = floor_world(1);
    for (int i = 0; i < n; i++)
        add_box(w, 1000, 900);
    r.first_ms = step_ms(w);
    check(pp_world_get_contacts(w, NULL, 0, &r.first_contacts), "pp_world_get_contacts");
    for (int k = 1; k < TIMED_STEPS; k++)
        r.next_ms += step_ms(w) / (TIMED_STEPS - 1);
    r.spread_px = spread(w);
    check(pp_world_destroy(w), "pp_world_destroy");
    return r;
}

int main(int argc, char **argv)
{
    const char *csv_path = NULL;
    int runs = 3, sizes[MAX_SIZES] = {250, 500, 1000}, nsizes = 3;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--csv") && i + 1 < argc)
            csv_path = argv[++i];
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--sizes") && i + 1 < argc) {
            nsizes = 0;
            for (char *p = argv[++i]; *p && nsizes < MAX_SIZES; p += *p == ',')
                sizes[nsizes++] = (int)strtol(p, &p, 10);
        } else {
            fprintf(stderr, "usage: bench_spawn [--csv PATH] [--runs N] [--sizes 250,500,1000]\n");
            return 2;
        }
    }
    runs = runs < 1 ? 1 : runs;
    char cpu[256];
    bench_cpu_model(cpu, sizeof cpu);
    printf("crowded spawns: n 8 px boxes created at one point against a settled, awake grid of n on a floor\n"
           "machine: %s; default settings (4 substeps, QuickStep 40); minimum of %d runs; budget %d pairs a crowded body\n",
           cpu, runs, PP_CROWDED_CONTACT_PAIRS);
    printf("%6s %12s %14s %16s %12s %12s %18s %10s\n", "n", "settled ms", "spawn step 1", "spawn steps 2-10",
           "step 1 /", "steps 2-10 /", "contacts settled", "spread");
    printf("%6s %12s %14s %16s %12s %12s %18s %10s\n", "", "per step", "ms", "ms per step", "settled", "settled",
           "· spawn step 1", "px");
    FILE *csv = NULL;
    if (csv_path && !(csv = fopen(csv_path, "w"))) {
        perror(csv_path);
        return 1;
    }
    if (csv)
        fprintf(csv, "n,settled_ms,spawn_first_ms,spawn_next_ms,settled_contacts,spawn_first_contacts,spread_px\n");
    for (int s = 0; s < nsizes; s++) {
        result best = run(sizes[s]);
        for (int k = 1; k < runs; k++) {
            const result r = run(sizes[s]);
            best.settled_ms = fmin(best.settled_ms, r.settled_ms);
            best.first_ms = fmin(best.first_ms, r.first_ms);
            best.next_ms = fmin(best.next_ms, r.next_ms);
        }
        printf("%6d %12.2f %14.1f %16.1f %12.1f %12.1f %8d · %7d %10.0f\n", sizes[s], best.settled_ms, best.first_ms,
               best.next_ms, best.first_ms / best.settled_ms, best.next_ms / best.settled_ms,
               (int)best.settled_contacts, (int)best.first_contacts, best.spread_px);
        if (csv)
            fprintf(csv, "%d,%.4f,%.4f,%.4f,%d,%d,%.2f\n", sizes[s], best.settled_ms, best.first_ms, best.next_ms,
                    (int)best.settled_contacts, (int)best.first_contacts, best.spread_px);
        fflush(stdout);
    }
    if (csv) {
        fclose(csv);
        printf("wrote %s\n", csv_path);
    }
    return 0;
}
