/* What sleeping bodies cost: N crates of 12 px asleep in stacks of 8 on a 16384 × 64 terrain, alone and
 * beside 8 awake boxes that bounce on a platform of their own above the crates; and those 8 boxes alone.
 * A sleeping body should cost nothing, so the mixed world should step as fast as the 8 boxes alone.
 * Timed: one step only (the kicks that keep the 8 awake are outside the clock), PhysPix's CPU backend,
 * the median of each block's mean step, the smallest median over the runs; Box2D 2.4 and Chipmunk 7 from
 * Debian on the same scene in the same run (peer_box2d.cpp, peer_chipmunk.c).
 *
 *   bench_sleep [--csv PATH] [--quick]
 */
#include "../machine.h"
#include "peer.h"
#include "physpix.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { CRATE = 12, STACK = 8, PITCH = 13, FLOOR_W = 16384, FLOOR_H = 64, MOVERS = 8, BLOCK = 50 };
static const float floor_top = 1000.0f, platform_top = 200.0f;

static void check(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "bench_sleep: %s: %s (%s)\n", what, pp_status_name(st), pp_last_error());
        exit(1);
    }
}

static pp_body add_box(pp_world w, pp_body_type type, int width, int height, float x, float y)
{
    uint8_t *mask = malloc((size_t)width * (size_t)height);
    if (!mask)
        check(PP_ERR_OUT_OF_MEMORY, "a mask");
    memset(mask, 1, (size_t)width * (size_t)height);
    pp_body_def d = pp_body_def_default();
    d.type = type, d.width = width, d.height = height, d.mask = mask, d.position = (pp_vec2){x, y};
    pp_body b;
    check(pp_body_create(w, &d, &b), "pp_body_create");
    free(mask);
    return b;
}

/* crates sleeping crates (settled until none is awake) and, with movers, 8 boxes over a platform. */
static pp_world make_world(int crates, int movers, pp_body *mover)
{
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_CPU;
    pp_world w;
    check(pp_world_create(&d, &w), "pp_world_create");
    if (crates > 0) {
        add_box(w, PP_BODY_STATIC, FLOOR_W, FLOOR_H, FLOOR_W * 0.5f, floor_top + FLOOR_H * 0.5f);
        const int cols = (crates + STACK - 1) / STACK;
        for (int i = 0; i < crates; i++)
            add_box(w, PP_BODY_DYNAMIC, CRATE, CRATE, FLOOR_W * 0.5f + (float)((i / STACK - (cols - 1) * 0.5) * PITCH),
                    floor_top - CRATE * 0.5f - (float)(i % STACK) * CRATE);
        pp_step_stats s = {0};
        for (int k = 0; k < 600 && (k == 0 || s.awake_bodies > 0); k++) {
            check(pp_world_step(w, 1.0f / 60.0f), "settling");
            check(pp_world_get_stats(w, &s), "pp_world_get_stats");
        }
        if (s.awake_bodies > 0)
            fprintf(stderr, "bench_sleep: %d crates still awake after 600 steps\n", (int)s.awake_bodies);
    }
    if (movers > 0) {
        add_box(w, PP_BODY_STATIC, 400, 16, 300.0f, platform_top + 8.0f);
        for (int i = 0; i < movers; i++)
            mover[i] = add_box(w, PP_BODY_DYNAMIC, 16, 16, 150.0f + 40.0f * (float)i, platform_top - 60.0f);
    }
    return w;
}

/* ms per step: the median of the blocks' means over `blocks` blocks; the 8 boxes are thrown up every 30 steps. */
static double time_steps(pp_world w, const pp_body *mover, int movers, int blocks, int *awake)
{
    double *ms = malloc((size_t)blocks * sizeof *ms);
    if (!ms)
        check(PP_ERR_OUT_OF_MEMORY, "the timings");
    int step = 0;
    for (int b = 0; b < blocks; b++) {
        double spent = 0;
        for (int k = 0; k < BLOCK; k++, step++) {
            if (step % 30 == 0)
                for (int i = 0; i < movers; i++)
                    check(pp_body_set_velocity(w, mover[i], (pp_vec2){0.0f, -300.0f}, 0.0f), "a kick");
            const double t0 = bench_clock_ms();
            check(pp_world_step(w, 1.0f / 60.0f), "pp_world_step");
            spent += bench_clock_ms() - t0;
        }
        ms[b] = spent / BLOCK;
    }
    qsort(ms, (size_t)blocks, sizeof *ms, bench_cmp_double);
    const double median = ms[blocks / 2];
    free(ms);
    pp_step_stats s;
    check(pp_world_get_stats(w, &s), "pp_world_get_stats");
    *awake = s.awake_bodies;
    return median;
}

int main(int argc, char **argv)
{
    const char *csv_path = NULL;
    int quick = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc)
            csv_path = argv[++i];
        else if (strcmp(argv[i], "--quick") == 0)
            quick = 1;
        else {
            fprintf(stderr, "usage: bench_sleep [--csv PATH] [--quick]\n");
            return 2;
        }
    }
    const int counts[] = {0, 1000, 10000}, runs = quick ? 1 : 3, blocks = quick ? 4 : 20;
    FILE *csv = csv_path ? fopen(csv_path, "w") : NULL;
    if (csv_path && !csv)
        return perror(csv_path), 1;
    if (csv)
        fprintf(csv, "sleeping,awake_boxes,ms_step_median,ratio_to_boxes_alone,awake_at_end,box2d_ms_step_median,"
                     "box2d_awake_at_end,ratio_to_box2d,chipmunk_ms_step_median,chipmunk_awake_at_end,ratio_to_chipmunk\n");
    char cpu[128];
    bench_cpu_model(cpu, sizeof cpu);
    printf("sleep benchmark on %s; BALANCED defaults, CPU backend, dt 1/60 s\n"
           "crates of %d px asleep in stacks of %d on a %dx%d terrain; %d boxes of 16 px bounce on a platform of "
           "their own,\nthrown up every 30 steps; ms/step: median of %d blocks of %d steps, smallest of %d runs\n\n",
           cpu, CRATE, STACK, FLOOR_W, FLOOR_H, MOVERS, blocks, BLOCK, runs);
    printf("%9s %11s %12s %14s %8s %12s %8s %10s %12s %8s %10s\n", "sleeping", "awake boxes", "ms/step",
           "/ boxes alone", "awake", "Box2D ms", "awake", "/ Box2D", "Chipmunk ms", "awake", "/ Chipmunk");
    double alone = 0;
    for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++) {
        for (int movers = counts[c] == 0 ? MOVERS : 0; movers <= MOVERS; movers += MOVERS) {
            double best = 0, b2_best = 0, cp_best = 0;
            int awake = 0, b2_awake = 0, cp_awake = 0;
            const sleep_scene scene = {counts[c], movers, CRATE, STACK, PITCH, FLOOR_W, FLOOR_H, floor_top, platform_top,
                                       BLOCK};
            for (int r = 0; r < runs; r++) {
                pp_body mover[MOVERS];
                pp_world w = make_world(counts[c], movers, mover);
                const double ms = time_steps(w, mover, movers, blocks, &awake);
                best = r == 0 || ms < best ? ms : best;
                check(pp_world_destroy(w), "pp_world_destroy");
                const double b2 = sleep_box2d_ms(&scene, blocks, &b2_awake);
                b2_best = r == 0 || b2 < b2_best ? b2 : b2_best;
                const double cp = sleep_chipmunk_ms(&scene, blocks, &cp_awake);
                if (cp < 0)
                    check(PP_ERR_OUT_OF_MEMORY, "the Chipmunk scene");
                cp_best = r == 0 || cp < cp_best ? cp : cp_best;
            }
            if (counts[c] == 0)
                alone = best;
            const double ratio = movers > 0 && alone > 0 ? best / alone : 0;
            char r_text[32] = "-";
            if (ratio > 0)
                snprintf(r_text, sizeof r_text, "%.2f", ratio);
            printf("%9d %11d %12.4f %14s %8d %12.4f %8d %10.4f %12.4f %8d %10.4f\n", counts[c], movers, best, r_text,
                   awake, b2_best, b2_awake, best / b2_best, cp_best, cp_awake, best / cp_best);
            if (csv)
                fprintf(csv, "%d,%d,%.6f,%.4f,%d,%.6f,%d,%.4f,%.6f,%d,%.4f\n", counts[c], movers, best, ratio, awake,
                        b2_best, b2_awake, best / b2_best, cp_best, cp_awake, best / cp_best);
        }
    }
    if (csv && fclose(csv) != 0)
        return perror(csv_path), 1;
    return 0;
}
