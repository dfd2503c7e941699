/* Loading and scheduling at scale: a scene of N named bodies with N timed edits naming them, a snapshot of
 * N bodies among 2N slots (N free slots), and N edits scheduled in decreasing time order, then the step that
 * applies them all. Each is generated into a temporary folder, timed as the calls that do the work, and
 * reported as the median of the runs, in seconds; printed and written as CSV. Once quadratic (a 40,000-body
 * scene took 97 s), each should now grow linearly, or as n log n.
 *
 *   bench_load [--csv PATH] [--n N] [--runs R]
 */
#include "../machine.h"
#include "physpix.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAX_RUNS 15

static void check(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "bench_load: %s: %s (%s)\n", what, pp_status_name(st), pp_last_error());
        exit(1);
    }
}

static FILE *open_or_die(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        exit(1);
    }
    return f;
}

static void close_or_die(FILE *f, const char *path)
{
    if (ferror(f) | fclose(f)) {
        fprintf(stderr, "bench_load: cannot write %s\n", path);
        exit(1);
    }
}

/* Body i: a 2 × 2 static box on a 1000-wide grid, 4 px apart. */
static float grid_x(int i) { return 4.0f * (float)(i % 1000); }
static float grid_y(int i) { return 4.0f * (float)(i / 1000); }

/* n bodies named "body<i>", then n erase edits in time order, edit k naming body (k · 7919) mod n. */
static void write_scene(const char *path, int n)
{
    FILE *f = open_or_die(path);
    fprintf(f, "{\"world\": {\"backend\": \"cpu\"},\n \"bodies\": [\n");
    for (int i = 0; i < n; i++)
        fprintf(f, "  {\"name\": \"body%d\", \"type\": \"static\", \"box\": [2, 2], \"position\": [%g, %g]}%s\n", i,
                grid_x(i), grid_y(i), i + 1 < n ? "," : "");
    fprintf(f, " ],\n \"edits\": [\n");
    for (int k = 0; k < n; k++) {
        const int i = (int)((long long)k * 7919 % n);
        fprintf(f, "  {\"time\": %d.%03d, \"body\": \"body%d\", \"center\": [%g, %g], \"radius\": 1}%s\n", k / 1000,
                k % 1000, i, grid_x(i), grid_y(i), k + 1 < n ? "," : "");
    }
    fprintf(f, " ]}\n");
    close_or_die(f, path);
}

/* world.json of n static boxes in the even slots of 2n; the odd slots are the free list, last first (as a
 * world that destroyed them saves it). Every body shares one 2 × 2 mask. */
static void write_snapshot(const char *dir, int n)
{
    char path[4096];
    static const uint8_t white[2 * 2 * 4] = {255, 255, 255, 255, 255, 255, 255, 255,
                                             255, 255, 255, 255, 255, 255, 255, 255};
    snprintf(path, sizeof path, "%s/mask.png", dir);
    check(pp_image_save(path, white, 2, 2), "pp_image_save");
    snprintf(path, sizeof path, "%s/world.json", dir);
    FILE *f = open_or_die(path);
    fprintf(f, "{\"format\": \"physpix-snapshot\", \"version\": 1, \"world\": {\"backend\": \"cpu\"},\n"
               " \"time\": 0, \"solver_steps\": 0, \"next_serial\": %d,\n \"generations\": [", n);
    for (int s = 0; s < 2 * n; s++)
        fprintf(f, "%s1", s ? ", " : "");
    fprintf(f, "],\n \"free_slots\": [");
    for (int s = 2 * n - 1; s > 0; s -= 2)
        fprintf(f, "%s%d", s < 2 * n - 1 ? ", " : "", s);
    fprintf(f, "],\n \"edits\": [], \"events\": [], \"touching\": [],\n \"bodies\": [\n");
    for (int i = 0; i < n; i++) {
        const float x = grid_x(i), y = grid_y(i);
        fprintf(f,
                "  {\"type\": \"static\", \"position\": [%g, %g], \"handle\": \"0x00000001%08x\", \"serial\": %d, "
                "\"state\": {\"pose\": [%g, %g, 0, 1, 1], \"user_data\": \"0x0\", \"slow_time\": 0}, "
                "\"mask\": \"mask.png\"}%s\n",
                x, y, (unsigned)(2 * i + 1), i, x, y, i + 1 < n ? "," : "");
    }
    fprintf(f, " ]}\n");
    close_or_die(f, path);
}

static int32_t pending_edits(pp_world w)
{
    int32_t n = 0;
    check(pp_world_get_scheduled_edits(w, NULL, 0, &n), "pp_world_get_scheduled_edits");
    return n;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

enum { SCENE, SNAPSHOT, SCHEDULE, APPLY, ROWS };

int main(int argc, char **argv)
{
    const char *csv_path = NULL;
    int n = 100000, runs = 3;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--csv") && i + 1 < argc)
            csv_path = argv[++i];
        else if (!strcmp(argv[i], "--n") && i + 1 < argc)
            n = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_load [--csv PATH] [--n N] [--runs R]\n");
            return 2;
        }
    }
    if (n < 1 || n > PP_MAX_BODIES / 2 || runs < 1 || runs > MAX_RUNS) {
        fprintf(stderr, "bench_load: --n must be 1..%d and --runs 1..%d\n", PP_MAX_BODIES / 2, MAX_RUNS);
        return 2;
    }
    char dir[] = "/tmp/physpix_bench_load_XXXXXX";
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    char scene[sizeof dir + 16], snap[sizeof dir + 16], file[sizeof dir + 32];
    snprintf(scene, sizeof scene, "%s/scene.json", dir);
    snprintf(snap, sizeof snap, "%s/snap", dir);
    if (mkdir(snap, 0700) != 0) {
        perror(snap);
        return 1;
    }
    write_scene(scene, n);
    write_snapshot(snap, n);

    static const char *const names[ROWS] = {"scene_load", "snapshot_load", "schedule_decreasing", "apply_due"};
    char what[ROWS][96];
    snprintf(what[SCENE], sizeof what[SCENE], "load a scene: %d named bodies, %d edits naming them", n, n);
    snprintf(what[SNAPSHOT], sizeof what[SNAPSHOT], "load a snapshot: %d bodies, %d free slots", n, n);
    snprintf(what[SCHEDULE], sizeof what[SCHEDULE], "schedule %d edits, decreasing time", n);
    snprintf(what[APPLY], sizeof what[APPLY], "the step applying those %d edits", n);
    double t[ROWS][MAX_RUNS];
    for (int r = 0; r < runs; r++) {
        pp_world w;
        double t0 = bench_clock_ms();
        check(pp_world_load_scene(scene, &w), "pp_world_load_scene");
        t[SCENE][r] = (bench_clock_ms() - t0) * 1e-3;
        if (pending_edits(w) != n) {
            fprintf(stderr, "bench_load: the scene has %d edits, not %d\n", (int)pending_edits(w), n);
            return 1;
        }
        check(pp_world_destroy(w), "pp_world_destroy");

        t0 = bench_clock_ms();
        check(pp_world_load_snapshot(snap, &w), "pp_world_load_snapshot");
        t[SNAPSHOT][r] = (bench_clock_ms() - t0) * 1e-3;
        int32_t bodies = 0;
        check(pp_world_get_bodies(w, NULL, 0, &bodies), "pp_world_get_bodies");
        if (bodies != n) {
            fprintf(stderr, "bench_load: the snapshot has %d bodies, not %d\n", (int)bodies, n);
            return 1;
        }
        check(pp_world_destroy(w), "pp_world_destroy");

        /* Every edit is due at the first step (before dt/2) and erases far from the one body. */
        pp_world_def d = pp_world_def_default();
        d.backend = PP_BACKEND_CPU;
        check(pp_world_create(&d, &w), "pp_world_create");
        t0 = bench_clock_ms();
        for (int i = 0; i < n; i++) {
            const pp_timed_edit e = {.time = (n - i) * (1e-3 / n), .type = PP_EDIT_ERASE_CIRCLE,
                                     .center = {-1000.0f - (float)(i % 1000), -1000.0f}, .radius = 1};
            check(pp_world_schedule_edit(w, &e), "pp_world_schedule_edit");
        }
        t[SCHEDULE][r] = (bench_clock_ms() - t0) * 1e-3;
        t0 = bench_clock_ms();
        check(pp_world_step(w, 1.0f / 60), "pp_world_step");
        t[APPLY][r] = (bench_clock_ms() - t0) * 1e-3;
        if (pending_edits(w) != 0) {
            fprintf(stderr, "bench_load: %d edits still pending after the step\n", (int)pending_edits(w));
            return 1;
        }
        check(pp_world_destroy(w), "pp_world_destroy");
    }
    snprintf(file, sizeof file, "%s/mask.png", snap);
    unlink(file);
    snprintf(file, sizeof file, "%s/world.json", snap);
    unlink(file);
    rmdir(snap);
    unlink(scene);
    rmdir(dir);

    char cpu[256];
    bench_cpu_model(cpu, sizeof cpu);
    printf("loading and scheduling at scale, median of %d runs; %s\n", runs, cpu);
    printf("%-60s %10s %10s %10s\n", "", "median s", "min s", "max s");
    double med[ROWS], lo[ROWS], hi[ROWS];
    for (int k = 0; k < ROWS; k++) {
        med[k] = median(t[k], runs); /* sorts: min and max are the ends */
        lo[k] = t[k][0], hi[k] = t[k][runs - 1];
        printf("%-60s %10.4f %10.4f %10.4f\n", what[k], med[k], lo[k], hi[k]);
    }
    if (csv_path) {
        FILE *f = open_or_die(csv_path);
        fprintf(f, "what,n,runs,median_s,min_s,max_s\n");
        for (int k = 0; k < ROWS; k++)
            fprintf(f, "%s,%d,%d,%.6f,%.6f,%.6f\n", names[k], n, runs, med[k], lo[k], hi[k]);
        close_or_die(f, csv_path);
        printf("wrote %s\n", csv_path);
    }
    return 0;
}
