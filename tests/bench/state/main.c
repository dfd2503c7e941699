/* World state in memory against a step (issue 44): pp_world_save_state and pp_world_restore_state of bench_cost's
 * 500-crate rain and of its destruction scene (the 2048×1024 terrain after 60 craters), each set against one
 * step of the same world. A restore is timed after one step past the save (poses, contacts and sleep changed:
 * what rollback restores every frame) and, on the terrain, after a crater too (the terrain's planes copied back).
 * Medians of the runs; one table and CSV.
 *
 *   bench_state [--csv PATH] [--runs N]
 */
#include "../cost/cost.h"
#include "../machine.h"
#include "physpix.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void check(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "bench_state: %s: %s (%s)\n", what, pp_status_name(st), pp_last_error());
        exit(1);
    }
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

typedef struct row {
    const char *scene, *restore_after;
    int bodies;
    int64_t bytes;
    double step_ms, save_ms, restore_ms, hash_ms;
} row;

static pp_world make_world(int sleep)
{
    const pp_world_def def = cost_world_def(sleep);
    pp_world w;
    check(pp_world_create(&def, &w), "pp_world_create");
    return w;
}

/* Time step, save, restore (after `between`, run after the save and timed apart) and hash, `runs` times each. */
static void measure(pp_world w, int runs, void (*between)(pp_world w, int k, void *user), void *user, row *out)
{
    int64_t size = 0;
    if (pp_world_save_state(w, NULL, 0, &size) != PP_ERR_LIMIT)
        check(PP_ERR_INVALID_ARGUMENT, "the size of the state");
    uint8_t *buf = malloc((size_t)size * 2);
    double *step = malloc(sizeof(double) * (size_t)runs * 4), *save = step + runs, *restore = save + runs,
           *hash = restore + runs;
    if (!buf || !step) {
        fprintf(stderr, "bench_state: out of memory\n");
        exit(1);
    }
    for (int k = 0; k < runs; k++) {
        double t0 = bench_clock_ms();
        check(pp_world_save_state(w, buf, size * 2, &size), "pp_world_save_state");
        save[k] = bench_clock_ms() - t0;
        if (between)
            between(w, k, user);
        t0 = bench_clock_ms();
        check(pp_world_step(w, (float)STAB_DT), "pp_world_step");
        step[k] = bench_clock_ms() - t0;
        t0 = bench_clock_ms();
        check(pp_world_restore_state(w, buf, size), "pp_world_restore_state");
        restore[k] = bench_clock_ms() - t0;
        uint64_t h;
        t0 = bench_clock_ms();
        check(pp_world_get_hash(w, &h), "pp_world_get_hash");
        hash[k] = bench_clock_ms() - t0;
        check(pp_world_step(w, (float)STAB_DT), "pp_world_step"); /* the world moves on between runs */
    }
    int32_t bodies = 0;
    check(pp_world_get_bodies(w, NULL, 0, &bodies), "pp_world_get_bodies");
    out->bodies = bodies;
    out->bytes = size;
    out->step_ms = median(step, runs), out->save_ms = median(save, runs);
    out->restore_ms = median(restore, runs), out->hash_ms = median(hash, runs);
    free(step);
    free(buf);
}

typedef struct crater_plan {
    const cost_destruction *d;
    pp_body terrain;
    int next;
} crater_plan;

static void crater(pp_world w, int k, void *user)
{
    crater_plan *c = user;
    double x, y;
    cost_crater(c->d, c->next++, &x, &y);
    check(pp_body_erase_circle(w, c->terrain, (pp_vec2){(float)x, (float)y}, (float)COST_CRATER_R, NULL), "a crater");
    (void)k;
}

int main(int argc, char **argv)
{
    const char *csv = NULL;
    int runs = 15;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc)
            csv = argv[++i];
        else if (strcmp(argv[i], "--runs") == 0 && i + 1 < argc)
            runs = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_state [--csv PATH] [--runs N]\n");
            return 2;
        }
    }
    if (runs < 1)
        runs = 1;
    row rows[3];

    /* The rain: 500 crates of 32 px falling into a walled pit, sleep off (as bench_cost), 2 s in. */
    stab_scene rain;
    if (cost_rain_build(500, &rain) != 0)
        return 1;
    pp_world w = make_world(0);
    pp_body *bodies = malloc((size_t)rain.count * sizeof *bodies);
    if (!bodies || stab_physpix_add_bodies(w, &rain, bodies) != 0)
        return 1;
    for (int k = 0; k < 120; k++)
        check(pp_world_step(w, (float)STAB_DT), "settling");
    rows[0] = (row){.scene = "rain 500 crates", .restore_after = "a step"};
    measure(w, runs, NULL, NULL, &rows[0]);
    check(pp_world_destroy(w), "pp_world_destroy");
    free(bodies);
    stab_scene_free(&rain);

    /* The destruction scene: the terrain after 60 craters (one each 10 steps), its crates on it, sleep on. */
    cost_destruction d;
    if (cost_destruction_build(&d) != 0)
        return 1;
    w = make_world(1);
    pp_body_def td = pp_body_def_default();
    td.type = PP_BODY_STATIC;
    td.width = COST_TERRAIN_W, td.height = COST_TERRAIN_H, td.mask = d.terrain;
    td.custom_pivot = 1;
    crater_plan plan = {&d, {0}, 0};
    check(pp_body_create(w, &td, &plan.terrain), "the terrain");
    bodies = malloc((size_t)d.crates.count * sizeof *bodies);
    if (!bodies || stab_physpix_add_bodies(w, &d.crates, bodies) != 0)
        return 1;
    for (int k = 0; k < 120; k++)
        check(pp_world_step(w, (float)STAB_DT), "settling");
    for (int k = 0; k < 60 * COST_EDIT_EVERY; k++) {
        if (k % COST_EDIT_EVERY == 0)
            crater(w, k, &plan);
        check(pp_world_step(w, (float)STAB_DT), "pp_world_step");
    }
    rows[1] = (row){.scene = "destruction 2048x1024", .restore_after = "a step"};
    measure(w, runs, NULL, NULL, &rows[1]);
    rows[2] = (row){.scene = "destruction 2048x1024", .restore_after = "a crater and a step"};
    measure(w, runs, crater, &plan, &rows[2]);
    check(pp_world_destroy(w), "pp_world_destroy");
    free(bodies);
    cost_destruction_free(&d);

    char cpu[128];
    bench_cpu_model(cpu, sizeof cpu);
    printf("state in memory: save and restore against one step (median of %d runs; CPU backend, 1 thread, BALANCED)\n"
           "machine: %s\n\n", runs, cpu);
    printf("%-22s %-20s %6s %10s %9s %9s %10s %9s %11s\n", "scene", "restore after", "bodies", "bytes", "step ms",
           "save ms", "restore ms", "hash ms", "(s+r)/step");
    for (int i = 0; i < 3; i++) {
        const row *r = &rows[i];
        printf("%-22s %-20s %6d %10lld %9.3f %9.4f %10.4f %9.4f %11.3f\n", r->scene, r->restore_after, r->bodies,
               (long long)r->bytes, r->step_ms, r->save_ms, r->restore_ms, r->hash_ms,
               (r->save_ms + r->restore_ms) / r->step_ms);
    }
    if (csv) {
        FILE *f = fopen(csv, "w");
        if (!f) {
            fprintf(stderr, "bench_state: cannot write %s\n", csv);
            return 1;
        }
        fprintf(f, "scene,restore_after,bodies,bytes,step_ms,save_ms,restore_ms,hash_ms,ratio\n");
        for (int i = 0; i < 3; i++) {
            const row *r = &rows[i];
            fprintf(f, "%s,%s,%d,%lld,%.5f,%.5f,%.5f,%.5f,%.5f\n", r->scene, r->restore_after, r->bodies,
                    (long long)r->bytes, r->step_ms, r->save_ms, r->restore_ms, r->hash_ms,
                    (r->save_ms + r->restore_ms) / r->step_ms);
        }
        fclose(f);
    }
    return 0;
}
