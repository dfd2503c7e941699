/* What a scene pays for the features it does not use. One scene (crates piling on a terrain,
 * sleep off so every step does the same work) runs as the base and with one feature available
 * but idle, or its reading switched on: weight planes of uniform weight, an armed fracture
 * (detach_islands) with no edits, reading events or contacts every step, an idle kinematic body,
 * an idle sensor or one-way platform (either makes the step track touching pairs), contact events,
 * continuous collision off, one thread, the AUTO backend. Variants alternate within each run, and
 * the minimum over runs of each median ms/step is kept. It also says whether the CPU-backend worlds
 * loaded EGL into the process (they must not) and fails if they did.
 *
 *   bench_features [--csv PATH] [--runs N] [--steps N]
 */
#include "../machine.h"
#include "physpix.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

enum { TW = 1400, TH = 200, CRATE = 24, COLS = 14, ROWS = 10 };

typedef enum variant {
    V_BASE, V_WEIGHTS, V_FRACTURE, V_EVENTS, V_CONTACTS, V_KINEMATIC, V_SENSOR, V_ONE_WAY, V_CONTACT_EVENTS,
    V_NO_CONTINUOUS, V_ONE_THREAD,
    V_AUTO, /* last: AUTO may open EGL to look for a GPU, which the CPU variants must not */
    V_COUNT
} variant;

static const char *const variant_names[V_COUNT] = {
    "base (CPU backend)", "uniform weight planes", "fracture armed, no edits", "events read each step",
    "contacts read each step", "idle kinematic body", "idle sensor", "idle one-way platform",
    "contact events, read", "continuous off", "worker_threads 1",
    "AUTO backend",
};

static void check(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "bench_features: %s: %s (%s)\n", what, pp_status_name(st), pp_last_error());
        exit(1);
    }
}

/// The scene with one variant applied; returns the world and fills the timing per step.
static pp_world build(variant v, const uint8_t *solid, const uint8_t *heavy)
{
    pp_world_def wd = pp_world_def_default();
    wd.backend = v == V_AUTO ? PP_BACKEND_AUTO : PP_BACKEND_CPU;
    wd.allow_sleep = 0;
    wd.continuous = v != V_NO_CONTINUOUS;
    wd.worker_threads = v == V_ONE_THREAD ? 1 : 0;
    wd.contact_events = v == V_CONTACT_EVENTS;
    pp_world w;
    check(pp_world_create(&wd, &w), "pp_world_create");

    pp_body_def t = pp_body_def_default();
    t.type = PP_BODY_STATIC;
    t.width = TW, t.height = TH, t.mask = solid;
    t.position = (pp_vec2){TW / 2.0f, 1000.0f + TH / 2.0f};
    t.detach_islands = v == V_FRACTURE;
    pp_body b;
    check(pp_body_create(w, &t, &b), "terrain");
    for (int r = 0; r < ROWS; r++)
        for (int c = 0; c < COLS; c++) {
            pp_body_def d = pp_body_def_default();
            d.width = d.height = CRATE;
            d.mask = solid;
            d.weights = v == V_WEIGHTS ? heavy : NULL;
            d.position = (pp_vec2){200.0f + 70.0f * c + 9.0f * (r % 3), 960.0f - 40.0f * r};
            d.angle = 0.07f * (float)((c + 2 * r) % 5 - 2);
            check(pp_body_create(w, &d, &b), "crate");
        }
    if (v == V_KINEMATIC) {
        pp_body_def k = pp_body_def_default();
        k.type = PP_BODY_KINEMATIC;
        k.width = k.height = CRATE;
        k.mask = solid;
        k.position = (pp_vec2){-5000.0f, 0.0f};
        k.linear_velocity = (pp_vec2){10.0f, 0.0f};
        check(pp_body_create(w, &k, &b), "kinematic");
    }
    if (v == V_SENSOR || v == V_ONE_WAY) { /* far from the crates: it only makes the step track touching pairs */
        pp_body_def k = pp_body_def_default();
        k.type = PP_BODY_STATIC;
        k.width = k.height = CRATE;
        k.mask = solid;
        k.position = (pp_vec2){-5000.0f, 0.0f};
        k.is_sensor = v == V_SENSOR, k.one_way = v == V_ONE_WAY;
        check(pp_body_create(w, &k, &b), "sensor or platform");
    }
    return w;
}

/// Median ms per step of one variant over `steps` steps after the same settle; *narrow gets the
/// median narrowphase ms of those steps.
static double run(variant v, int steps, const uint8_t *solid, const uint8_t *heavy, double *contacts, double *narrow)
{
    pp_world w = build(v, solid, heavy);
    double *ms = malloc((size_t)steps * sizeof *ms), *nms = malloc((size_t)steps * sizeof *nms);
    static pp_contact buf[4096];
    static pp_event events[4096];
    if (!ms || !nms)
        exit(1);
    double sum_contacts = 0;
    for (int s = 0; s < 60 + steps; s++) {
        const double t0 = bench_clock_ms();
        check(pp_world_step(w, 1.0f / 60.0f), "pp_world_step");
        int32_t n;
        if (v == V_EVENTS || v == V_CONTACT_EVENTS)
            check(pp_world_get_events(w, events, 4096, &n), "pp_world_get_events");
        if (v == V_CONTACTS)
            check(pp_world_get_contacts(w, buf, 4096, &n), "pp_world_get_contacts");
        if (s >= 60) {
            ms[s - 60] = bench_clock_ms() - t0;
            pp_step_stats st;
            check(pp_world_get_stats(w, &st), "pp_world_get_stats");
            sum_contacts += st.contacts;
            nms[s - 60] = st.narrowphase_ms;
        }
    }
    check(pp_world_destroy(w), "pp_world_destroy");
    qsort(ms, (size_t)steps, sizeof *ms, bench_cmp_double);
    qsort(nms, (size_t)steps, sizeof *nms, bench_cmp_double);
    const double med = ms[steps / 2];
    *narrow = nms[steps / 2];
    free(ms);
    free(nms);
    *contacts = sum_contacts / steps;
    return med;
}

/// Whether a library whose name holds `name` is mapped into this process.
static int mapped(const char *name)
{
    char line[1024];
    int found = 0;
    FILE *f = fopen("/proc/self/maps", "r");
    while (f && fgets(line, sizeof line, f))
        found |= strstr(line, name) != NULL;
    if (f)
        fclose(f);
    return found;
}

int main(int argc, char **argv)
{
    const char *csv_path = NULL;
    int runs = 3, steps = 300;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--csv") && i + 1 < argc)
            csv_path = argv[++i];
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--steps") && i + 1 < argc)
            steps = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_features [--csv PATH] [--runs N] [--steps N]\n");
            return 2;
        }
    }
    if (runs < 1 || steps < 2) {
        fprintf(stderr, "bench_features: --runs ≥ 1 and --steps ≥ 2\n");
        return 2;
    }
    uint8_t *solid = malloc((size_t)TW * TH), *heavy = malloc((size_t)CRATE * CRATE);
    if (!solid || !heavy)
        return 1;
    memset(solid, 1, (size_t)TW * TH);
    memset(heavy, 255, (size_t)CRATE * CRATE);

    char model[256];
    bench_cpu_model(model, sizeof model);
    printf("PhysPix feature cost: %d crates of %d px piling on a %d×%d terrain, sleep off, %d steps after 60, "
           "%d runs (minimum of medians)\nmachine: %ld cpus online, %s\n\n",
           ROWS * COLS, CRATE, TW, TH, steps, runs, sysconf(_SC_NPROCESSORS_ONLN), model);

    double best[V_COUNT], contacts[V_COUNT], narrow[V_COUNT], nbest[V_COUNT];
    int egl = 0;
    for (int r = 0; r < runs; r++)
        for (int v = 0; v < V_COUNT; v++) {
            if (r == 0 && v == V_AUTO)
                egl = mapped("libEGL"); /* after every CPU-backend world has run */
            const double med = run((variant)v, steps, solid, heavy, &contacts[v], &narrow[v]);
            best[v] = r == 0 || med < best[v] ? med : best[v];
            nbest[v] = r == 0 || narrow[v] < nbest[v] ? narrow[v] : nbest[v];
        }

    FILE *csv = csv_path ? fopen(csv_path, "w") : NULL;
    if (csv_path && !csv) {
        perror(csv_path);
        return 1;
    }
    if (csv)
        fprintf(csv, "variant,ms_step_median,delta_percent,narrowphase_ms_median,contacts_mean\n");
    printf("%-28s %10s %8s %10s %9s\n", "variant", "ms/step", "vs base", "narrow ms", "contacts");
    for (int v = 0; v < V_COUNT; v++) {
        const double delta = 100.0 * (best[v] / best[V_BASE] - 1.0);
        printf("%-28s %10.4f %+7.1f%% %10.4f %9.1f\n", variant_names[v], best[v], delta, nbest[v], contacts[v]);
        if (csv)
            fprintf(csv, "\"%s\",%.6f,%.2f,%.6f,%.2f\n", variant_names[v], best[v], delta, nbest[v], contacts[v]);
    }
    printf("\nlibEGL loaded by the CPU-backend worlds: %s\n", egl ? "yes (something touched the GPU)" : "no");
    free(solid);
    free(heavy);
    if (csv) {
        fclose(csv);
        printf("wrote %s\n", csv_path);
    }
    return egl ? 1 : 0;
}
