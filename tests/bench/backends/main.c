/* Whole scenes on each narrowphase backend (issue 46): crates falling onto a 4096 × 2048 terrain and coming to rest
 * on it while a blast (pp_world_explode) digs into the surface every 30 steps, stepped on the CPU backend (every
 * core), the GPU backend and AUTO. The three worlds of a scene step in turn, so a slow patch of the machine hits all
 * of them; the backends give the same contacts bit for bit, so the three must end with the same hash. Per scene:
 * the narrowphase's and the whole step's mean ms over the measured steps (the first 10 are warm-up: the GPU uploads
 * the terrain and compiles on first use), the pairs a step, and how many of AUTO's steps ran the GPU. One table and
 * CSV.
 *
 *   bench_backends [--csv PATH] [--steps N] [--quick] [--only NAME] [--no-gpu]
 *
 * --no-gpu leaves the GPU world out, as on a machine without EGL: the CPU backend's figures alone, in a fraction
 * of the time where the GPU is llvmpipe.
 */
#include "../machine.h"
#include "physpix.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define TERRAIN_W 4096
#define TERRAIN_H 2048
#define SURFACE 1024   /* the terrain's mean top row, px */
#define BLAST_EVERY 30 /* steps between blasts */
#define WARM_UP 10     /* steps not measured */

enum { ENG_CPU, ENG_GPU, ENG_AUTO, ENG_COUNT };
static const pp_backend engine_backend[ENG_COUNT] = {PP_BACKEND_CPU, PP_BACKEND_GPU, PP_BACKEND_AUTO};
static const char *const engine_name[ENG_COUNT] = {"CPU", "GPU", "AUTO"};

typedef struct scene_spec {
    const char *name;
    int crates, side; /* crates of side × side px */
} scene_spec;

static const scene_spec specs[] = {
    {"200x32", 200, 32}, {"200x128", 200, 128}, {"50x256", 50, 256}, {"1000x32", 1000, 32},
};
#define SCENE_COUNT ((int)(sizeof specs / sizeof specs[0]))

typedef struct totals {
    double narrow_ms, step_ms, pairs;
    int steps, gpu_steps;
    uint64_t hash;
} totals;

static void check(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "bench_backends: %s: %s (%s)\n", what, pp_status_name(st), pp_last_error());
        exit(1);
    }
}

static void *xmalloc(size_t n)
{
    void *p = malloc(n);
    if (!p) {
        fprintf(stderr, "bench_backends: out of memory (%zu bytes)\n", n);
        exit(1);
    }
    return p;
}

/* The terrain's top row at column x: gentle hills, the same for every scene. */
static int surface_at(int x)
{
    return SURFACE + (int)lround(40 * sin(x / 310.0) + 12 * sin(x / 67.0));
}

/* A world of the scene on backend e: the terrain, then the crates in rows above it, 1.5 sides apart. */
static pp_world build(const scene_spec *s, pp_backend backend, const uint8_t *terrain, const uint8_t *crate)
{
    pp_world_def d = pp_world_def_default();
    d.backend = backend;
    pp_world w;
    check(pp_world_create(&d, &w), "pp_world_create");
    pp_body_def t = pp_body_def_default();
    t.type = PP_BODY_STATIC;
    t.width = TERRAIN_W, t.height = TERRAIN_H;
    t.position = (pp_vec2){TERRAIN_W / 2.0f, TERRAIN_H / 2.0f};
    t.mask = terrain;
    pp_body body;
    check(pp_body_create(w, &t, &body), "pp_body_create (terrain)");
    const int pitch = s->side * 3 / 2, columns = (TERRAIN_W - 2 * s->side) / pitch;
    for (int i = 0; i < s->crates; i++) {
        const int col = i % columns, row = i / columns;
        const float x = (float)(s->side + col * pitch + pitch / 2);
        pp_body_def c = pp_body_def_default();
        c.width = c.height = s->side;
        c.mask = crate;
        /* Rows from 8 px above the highest ground, up; a small turn so that they do not land as a lattice. */
        c.position = (pp_vec2){x, (float)(SURFACE - 60 - s->side / 2 - row * pitch)};
        c.angle = 0.02f * (float)((i * 7) % 5 - 2);
        check(pp_body_create(w, &c, &body), "pp_body_create (crate)");
    }
    return w;
}

/* The k-th blast: on the surface under the crates' columns, cycling across the terrain. */
static void blast(pp_world w, const scene_spec *s, int k)
{
    pp_explosion_def e = pp_explosion_def_default();
    const int x = (int)((k * 977L) % (TERRAIN_W - 200)) + 100;
    e.position = (pp_vec2){(float)x, (float)surface_at(x)};
    e.radius = 1.5f * (float)s->side;
    e.falloff = (float)s->side;
    int32_t changed = 0;
    check(pp_world_explode(w, &e, &changed), "pp_world_explode");
}

static void run_scene(const scene_spec *s, int steps, int gpu_ok, totals out[ENG_COUNT])
{
    uint8_t *terrain = xmalloc((size_t)TERRAIN_W * TERRAIN_H), *crate = xmalloc((size_t)s->side * s->side);
    for (int y = 0; y < TERRAIN_H; y++)
        for (int x = 0; x < TERRAIN_W; x++)
            terrain[(size_t)y * TERRAIN_W + x] = y >= surface_at(x);
    memset(crate, 1, (size_t)s->side * s->side);
    pp_world w[ENG_COUNT] = {{0}};
    for (int e = 0; e < ENG_COUNT; e++) {
        out[e] = (totals){0};
        if (e != ENG_GPU || gpu_ok)
            w[e] = build(s, engine_backend[e], terrain, crate);
    }
    free(terrain);
    free(crate);
    for (int k = 0; k < steps; k++)
        for (int e = 0; e < ENG_COUNT; e++) {
            if (!w[e].id)
                continue;
            if (k > 0 && k % BLAST_EVERY == 0)
                blast(w[e], s, k / BLAST_EVERY);
            check(pp_world_step(w[e], 1.0f / 60), "pp_world_step");
            pp_step_stats st;
            check(pp_world_get_stats(w[e], &st), "pp_world_get_stats");
            if (k < WARM_UP)
                continue;
            out[e].narrow_ms += st.narrowphase_ms, out[e].step_ms += st.total_ms, out[e].pairs += st.pairs;
            out[e].gpu_steps += st.backend == PP_BACKEND_GPU;
            out[e].steps++;
        }
    for (int e = 0; e < ENG_COUNT; e++)
        if (w[e].id) {
            check(pp_world_get_hash(w[e], &out[e].hash), "pp_world_get_hash");
            check(pp_world_destroy(w[e]), "pp_world_destroy");
        }
}

/* Bring the GPU up once before the table, so that its log line comes first and a failure is told once. */
static int probe_gpu(void)
{
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_GPU;
    pp_world w;
    const pp_status st = pp_world_create(&d, &w);
    if (st != PP_OK) {
        printf("GPU backend unavailable (%s): %s\n", pp_status_name(st), pp_last_error());
        return 0;
    }
    check(pp_world_destroy(w), "pp_world_destroy");
    return 1;
}

static void log_once(int level, const char *msg, void *user)
{
    (void)user;
    static char last[512];
    if (level >= 1 && strcmp(msg, last) != 0) {
        snprintf(last, sizeof last, "%s", msg);
        printf("log: %s\n", msg);
    }
}

static double mean(double v, int n) { return n ? v / n : -1; }

int main(int argc, char **argv)
{
    const char *csv_path = NULL, *only = NULL;
    int steps = 240, quick = 0, no_gpu = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--csv") && i + 1 < argc)
            csv_path = argv[++i];
        else if (!strcmp(argv[i], "--steps") && i + 1 < argc)
            steps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--only") && i + 1 < argc)
            only = argv[++i];
        else if (!strcmp(argv[i], "--quick"))
            quick = 1;
        else if (!strcmp(argv[i], "--no-gpu"))
            no_gpu = 1;
        else {
            fprintf(stderr, "usage: bench_backends [--csv PATH] [--steps N] [--quick] [--only NAME] [--no-gpu]\n");
            return 2;
        }
    }
    if (quick)
        steps = 40;
    if (steps <= WARM_UP) {
        fprintf(stderr, "bench_backends: --steps must be over %d\n", WARM_UP);
        return 2;
    }
    pp_set_log_hook(log_once, NULL);
    char model[256];
    bench_cpu_model(model, sizeof model);
    printf("whole scenes on each backend: a %d x %d terrain, crates falling on it, a blast every %d steps; %d steps "
           "(%d measured), BALANCED\nmachine: %ld cpus online, %s\n", TERRAIN_W, TERRAIN_H, BLAST_EVERY, steps,
           steps - WARM_UP, sysconf(_SC_NPROCESSORS_ONLN), model);
    const int gpu_ok = !no_gpu && probe_gpu();
    FILE *csv = csv_path ? fopen(csv_path, "w") : NULL;
    if (csv_path && !csv) {
        fprintf(stderr, "bench_backends: cannot write %s\n", csv_path);
        return 1;
    }
    if (csv)
        fprintf(csv, "scene,crates,side,engine,narrowphase_ms,step_ms,pairs,gpu_steps,steps,same_hash\n");
    printf("\n%-9s %7s %9s %9s %9s %9s %9s %9s %11s %5s\n", "scene", "pairs", "CPU np", "GPU np", "AUTO np", "CPU step",
           "GPU step", "AUTO step", "AUTO on GPU", "same");
    int differ = 0;
    for (int i = 0; i < SCENE_COUNT; i++) {
        const scene_spec *s = &specs[i];
        if ((only && strcmp(only, s->name)) || (quick && !only && s->crates > 200))
            continue;
        totals t[ENG_COUNT];
        run_scene(s, steps, gpu_ok, t);
        const int same = (!gpu_ok || t[ENG_GPU].hash == t[ENG_CPU].hash) && t[ENG_AUTO].hash == t[ENG_CPU].hash;
        differ |= !same;
        char gnp[16] = "n/a", gst[16] = "n/a";
        if (gpu_ok) {
            snprintf(gnp, sizeof gnp, "%.3f", mean(t[ENG_GPU].narrow_ms, t[ENG_GPU].steps));
            snprintf(gst, sizeof gst, "%.3f", mean(t[ENG_GPU].step_ms, t[ENG_GPU].steps));
        }
        printf("%-9s %7.0f %9.3f %9s %9.3f %9.3f %9s %9.3f %5d of %3d %5s\n", s->name,
               mean(t[ENG_CPU].pairs, t[ENG_CPU].steps), mean(t[ENG_CPU].narrow_ms, t[ENG_CPU].steps), gnp,
               mean(t[ENG_AUTO].narrow_ms, t[ENG_AUTO].steps), mean(t[ENG_CPU].step_ms, t[ENG_CPU].steps), gst,
               mean(t[ENG_AUTO].step_ms, t[ENG_AUTO].steps), t[ENG_AUTO].gpu_steps, t[ENG_AUTO].steps,
               same ? "yes" : "NO");
        fflush(stdout);
        for (int e = 0; csv && e < ENG_COUNT; e++)
            if (t[e].steps)
                fprintf(csv, "%s,%d,%d,%s,%.4f,%.4f,%.1f,%d,%d,%d\n", s->name, s->crates, s->side, engine_name[e],
                        mean(t[e].narrow_ms, t[e].steps), mean(t[e].step_ms, t[e].steps),
                        mean(t[e].pairs, t[e].steps), t[e].gpu_steps, t[e].steps, same);
    }
    if (csv)
        fclose(csv);
    if (differ)
        fprintf(stderr, "bench_backends: the backends' worlds ended with different hashes\n");
    return differ;
}
