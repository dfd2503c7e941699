/* One step-cost scene for callgrind (issue 40): builds and settles it uninstrumented, then counts only the
 * measured steps (CALLGRIND_START/STOP_INSTRUMENTATION around them, collection toggled on inside), and prints
 * what report.py divides the instructions by. Outside valgrind the macros do nothing and it just runs.
 *
 *   bench_instr --scene pyramid20|rain500|destruction|sleep1000 [--steps N] [--motion K] [--sleep]
 *
 * stdout, one line: `instr scene=NAME steps=N awake_sum=A contacts_sum=C`, the sums over the measured steps of
 * pp_step_stats.awake_bodies and .contacts (contact points of the last substep). With --motion, before it, every
 * K measured steps of a stack scene: `motion steps=A-B over_10=N rms=V deepest=D awake=W`, over those K steps the
 * mean count of bodies faster than 10 px/s, the rms speed of all (px/s), the deepest contact (px) and the count of
 * awake bodies: how calm a pile stays at what a change saves. --sleep lets the rain's crates fall asleep (its
 * measured steps then count only what stays awake).
 */
#include "../cost/cost.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <valgrind/callgrind.h>

typedef struct measure {
    long long awake, contacts;
    int motion_every; /* --motion: 0, none */
    double over, v2, deepest, awake_bodies; /* --motion: sums over the window's steps, its deepest contact */
} measure;

static void check(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "bench_instr: %s: %s (%s)\n", what, pp_status_name(st), pp_last_error());
        exit(1);
    }
}

static void die(const char *what)
{
    fprintf(stderr, "bench_instr: %s\n", what);
    exit(1);
}

/* As bench_cost: BALANCED, the CPU backend on one thread, so the counts are those of one core's work. */
static pp_world make_world(int sleep)
{
    const pp_world_def def = cost_world_def(sleep);
    pp_world w;
    check(pp_world_create(&def, &w), "pp_world_create");
    return w;
}

static pp_step_stats stats(pp_world w)
{
    pp_step_stats st;
    check(pp_world_get_stats(w, &st), "pp_world_get_stats");
    return st;
}

/* The measured region's bounds: instrumentation is off before it (fast settling) and collection on only
 * inside, so callgrind's totals are the measured steps' alone. */
static void region_begin(void)
{
    CALLGRIND_START_INSTRUMENTATION;
    CALLGRIND_ZERO_STATS;
    CALLGRIND_TOGGLE_COLLECT;
}

static void region_end(void)
{
    CALLGRIND_TOGGLE_COLLECT;
    CALLGRIND_STOP_INSTRUMENTATION;
}

static void step(pp_world w, measure *m)
{
    check(pp_world_step(w, (float)STAB_DT), "pp_world_step");
    if (m) { /* reading the stats is the benchmark's work, not the step's: collection off around it */
        CALLGRIND_TOGGLE_COLLECT;
        const pp_step_stats st = stats(w);
        m->awake += st.awake_bodies, m->contacts += st.contacts;
        CALLGRIND_TOGGLE_COLLECT;
    }
}

/* Add measured step k's motion to the window, and print the window every motion_every steps (read with
 * collection off: not the step's work). */
static void add_motion(pp_world w, const pp_body *bodies, int count, int k, measure *m)
{
    CALLGRIND_TOGGLE_COLLECT;
    int over = 0, n = 0;
    double v2 = 0, deepest = 0;
    for (int i = 0; i < count; i++) {
        pp_vec2 v;
        float av;
        /* Every body of the scene: a static one (the rain's pit, 3 of its 503 bodies) reads 0 and counts in
         * the rms as at rest. */
        check(pp_body_get_velocity(w, bodies[i], &v, &av), "pp_body_get_velocity");
        const double s2 = (double)v.x * v.x + (double)v.y * v.y;
        v2 += s2, n++, over += s2 > 100.0;
    }
    int32_t total = 0;
    check(pp_world_get_contacts(w, NULL, 0, &total), "pp_world_get_contacts");
    pp_contact *c = malloc((size_t)(total > 0 ? total : 1) * sizeof *c);
    if (!c)
        die("out of memory");
    check(pp_world_get_contacts(w, c, total, &total), "pp_world_get_contacts");
    for (int32_t i = 0; i < total; i++)
        deepest = c[i].depth > deepest ? c[i].depth : deepest;
    free(c);
    m->over += over, m->v2 += n ? v2 / n : 0, m->deepest = deepest > m->deepest ? deepest : m->deepest;
    m->awake_bodies += stats(w).awake_bodies;
    if (k % m->motion_every == 0) {
        const int e = m->motion_every;
        printf("motion steps=%d-%d over_10=%.1f rms=%.2f deepest=%.3f awake=%.1f\n", k - e + 1, k, m->over / e,
               sqrt(m->v2 / e), m->deepest, m->awake_bodies / e);
        m->over = m->v2 = m->deepest = m->awake_bodies = 0;
    }
    CALLGRIND_TOGGLE_COLLECT;
}

/* A stability-style scene (pyramid, rain, sleeping crates): settle steps uncounted, then `steps` counted. */
static void run_stab(const stab_scene *s, int sleep, int settle, int steps, measure *m)
{
    pp_world w = make_world(sleep);
    pp_body *bodies = malloc((size_t)s->count * sizeof *bodies);
    if (!bodies || stab_physpix_add_bodies(w, s, bodies) != 0)
        die("could not build the scene");
    /* With sleep on, settling ends when everything sleeps (settle is then a ceiling). */
    for (int k = 0; k < settle && !(sleep && k > 0 && stats(w).awake_bodies == 0); k++)
        step(w, NULL);
    if (sleep && settle > 0 && stats(w).awake_bodies != 0)
        die("the crates did not all fall asleep while settling");
    region_begin();
    for (int k = 0; k < steps; k++) {
        step(w, m);
        if (m->motion_every)
            add_motion(w, bodies, s->count, k + 1, m);
    }
    region_end();
    check(pp_world_destroy(w), "pp_world_destroy");
    free(bodies);
}

/* bench_cost's destruction scene: sleep on, a crater every COST_EDIT_EVERY steps, the erase counted. */
static void run_destruction(int settle, int steps, measure *m)
{
    cost_destruction d;
    if (cost_destruction_build(&d) != 0)
        die("out of memory building the terrain");
    pp_world w = make_world(1);
    pp_body_def td = pp_body_def_default();
    td.type = PP_BODY_STATIC;
    td.width = COST_TERRAIN_W, td.height = COST_TERRAIN_H, td.mask = d.terrain;
    td.custom_pivot = 1; /* pivot (0, 0) at the origin: bitmap pixels are world pixels */
    pp_body terrain, *crates = malloc((size_t)d.crates.count * sizeof *crates);
    check(pp_body_create(w, &td, &terrain), "the terrain");
    if (!crates || stab_physpix_add_bodies(w, &d.crates, crates) != 0)
        die("could not build the crates");
    for (int k = 0; k < settle; k++)
        step(w, NULL);
    region_begin();
    for (int k = 0; k < steps; k++) {
        if (k % COST_EDIT_EVERY == 0) {
            double x, y;
            cost_crater(&d, k / COST_EDIT_EVERY, &x, &y);
            check(pp_body_erase_circle(w, terrain, (pp_vec2){(float)x, (float)y}, (float)COST_CRATER_R, NULL),
                  "pp_body_erase_circle");
        }
        step(w, m);
    }
    region_end();
    check(pp_world_destroy(w), "pp_world_destroy");
    free(crates);
    cost_destruction_free(&d);
}

/* 1000 crates of 32 px in 250 stacks of 4 on a static ground, each crate 1 px above the one below. */
enum { SLEEP_CRATES = 1000, SLEEP_STACK = 4, SLEEP_PITCH = 36 };

static int sleep_scene_build(stab_scene *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "sleep%d", SLEEP_CRATES);
    out->tracked = -1;
    out->bodies = calloc(SLEEP_CRATES + 1, sizeof *out->bodies);
    if (!out->bodies)
        return -1;
    const int cols = SLEEP_CRATES / SLEEP_STACK;
    const double width = cols * SLEEP_PITCH;
    out->bodies[out->count++] = (stab_body){.shape = STAB_BOX, .x = 0, .y = 20, .w = width + 64, .h = 40,
                                            .density = 1, .friction = 0.6, .is_static = 1};
    for (int i = 0; i < SLEEP_CRATES; i++)
        out->bodies[out->count++] = (stab_body){.shape = STAB_BOX, .x = (i / SLEEP_STACK - 0.5 * (cols - 1)) * SLEEP_PITCH,
                                                .y = -16.5 - (i % SLEEP_STACK) * 33.0, .w = 32, .h = 32,
                                                .density = 1, .friction = 0.6};
    return 0;
}

int main(int argc, char **argv)
{
    const char *scene = NULL;
    int steps = 0, motion = 0, sleep_on = 0; /* 0: the scene's own count; no motion lines; the scene's sleep */
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--scene") == 0 && i + 1 < argc)
            scene = argv[++i];
        else if (strcmp(argv[i], "--steps") == 0 && i + 1 < argc && atoi(argv[i + 1]) > 0)
            steps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--motion") == 0 && i + 1 < argc && atoi(argv[i + 1]) > 0)
            motion = atoi(argv[++i]);
        else if (strcmp(argv[i], "--sleep") == 0)
            sleep_on = 1;
        else
            scene = NULL, i = argc;
    }
    if (!scene) {
        fprintf(stderr, "usage: bench_instr --scene pyramid20|rain500|destruction|sleep1000 [--steps N] [--motion K]\n"
                        "  [--sleep]\n"
                        "  run under valgrind --tool=callgrind --instr-atstart=no --collect-atstart=no\n"
                        "  (tests/bench/instr/report.py does)\n");
        return 2;
    }

    measure m = {.motion_every = motion};
    stab_scene s;
    if (strcmp(scene, "pyramid20") == 0) {
        steps = steps ? steps : 60;
        if (stab_scene_build(stab_scene_find("pyramid20"), &s) != 0)
            die("could not build pyramid20");
        run_stab(&s, 0, 60, steps, &m);
        stab_scene_free(&s);
    } else if (strcmp(scene, "rain500") == 0) {
        steps = steps ? steps : 300; /* from the drop, as bench_cost: falling, landing, piling up */
        if (cost_rain_build(500, &s) != 0)
            die("could not build rain500");
        run_stab(&s, sleep_on, 0, steps, &m);
        stab_scene_free(&s);
    } else if (strcmp(scene, "destruction") == 0) {
        steps = steps ? steps : 120;
        run_destruction(120, steps, &m);
    } else if (strcmp(scene, "sleep1000") == 0) {
        steps = steps ? steps : 60;
        if (sleep_scene_build(&s) != 0)
            die("could not build sleep1000");
        run_stab(&s, 1, 1200, steps, &m);
        stab_scene_free(&s);
    } else {
        fprintf(stderr, "bench_instr: unknown scene %s\n", scene);
        return 2;
    }
    printf("instr scene=%s steps=%d awake_sum=%lld contacts_sum=%lld\n", scene, steps, m.awake, m.contacts);
    return 0;
}
