/* What one step costs on PhysPix against Box2D 2.4 and Chipmunk 7 on the same scenes in the same run (issue
 * 23): the awake 20-row pyramid, 500 crates raining into a pit, the rain at 100..1000 crates, and crates on a
 * terrain that craters eat (Box2D remeshing it into chain loops). One table line per scene and engine, and CSV.
 *
 *   bench_cost [--quick] [--only TEXT] [--engine TEXT] [--csv PATH]
 */
#include "../bench.h"
#include "../machine.h"
#include "../stability/peers.h"
#include "cost.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_RUNS 3

typedef enum engine_id {
    E_FAST,
    E_BALANCED,
    E_ACCURATE,
    E_BOX2D,    /* the stability peer: any stab_scene, sleep off */
    E_CHIPMUNK, /* the stability peer, 10 iterations, sleep off */
    E_REMESH,   /* Box2D on the destruction terrain, sleep on */
    E_COUNT
} engine_id;

static const char *const engine_names[E_COUNT] = {"PhysPix FAST", "PhysPix BALANCED", "PhysPix ACCURATE",
                                                  "Box2D 2.4", "Chipmunk 7 it10", "Box2D 2.4 remesh"};
static const pp_preset presets[3] = {PP_PRESET_FAST, PP_PRESET_BALANCED, PP_PRESET_ACCURATE};

typedef enum scene_kind { S_PYRAMID, S_RAIN, S_DESTRUCTION } scene_kind;

/* One table scene: what to build, how long to run it, and on which engines. */
typedef struct scene_plan {
    char name[32];
    const char *group; /* CSV: pyramid, rain, sweep, destruction */
    scene_kind kind;
    int crates;        /* rain: crates */
    int settle, steps; /* untimed, timed steps */
    unsigned engines;  /* 1 << engine_id */
} scene_plan;

/* What one run of one engine measured. */
typedef struct run_result {
    double ms;                    /* mean ms per timed step, edits included */
    double edit_ms;               /* summed over the timed edits */
    int edits;
    double narrow, solver, total; /* PhysPix: pp_step_stats summed over the timed steps, ms */
    int threads;                  /* PhysPix: most narrowphase threads in a timed step */
    int awake;                    /* dynamic bodies awake after the last step (-1: not known) */
} run_result;

/* A table line: the runs of one engine on one scene. */
typedef struct row {
    double ms[MAX_RUNS];
    int runs;
    run_result sum; /* edits, stats and threads over all runs */
} row;

typedef struct options {
    int quick;
    const char *only, *engine, *csv_path;
} options;

static stab_engine peers[E_COUNT]; /* the Box2D and Chipmunk rows' engines */

static void check(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "bench_cost: %s: %s (%s)\n", what, pp_status_name(st), pp_last_error());
        exit(1);
    }
}

static void die(const char *what)
{
    fprintf(stderr, "bench_cost: %s\n", what);
    exit(1);
}

static pp_world physpix_world(engine_id e, int sleep)
{
    pp_world_def def = pp_world_def_preset(presets[e]);
    def.allow_sleep = (uint32_t)sleep;
    def.backend = PP_BACKEND_CPU; /* the peers run on the CPU, on one thread */
    def.worker_threads = 1;
    def.gravity = (pp_vec2){0.0f, (float)STAB_GRAVITY};
    pp_world w;
    check(pp_world_create(&def, &w), "pp_world_create");
    return w;
}

static void physpix_stats(pp_world w, run_result *out)
{
    pp_step_stats st;
    check(pp_world_get_stats(w, &st), "pp_world_get_stats");
    out->narrow += st.narrowphase_ms, out->solver += st.solver_ms, out->total += st.total_ms;
    out->threads = st.threads > out->threads ? st.threads : out->threads;
    out->awake = st.awake_bodies;
}

/* The pyramid or the rain on PhysPix, sleep off as on the stability peers. */
static void run_physpix_stab(engine_id e, const stab_scene *s, const scene_plan *p, run_result *out)
{
    pp_world w = physpix_world(e, 0);
    pp_body *bodies = malloc((size_t)s->count * sizeof *bodies);
    if (!bodies || stab_physpix_add_bodies(w, s, bodies) != 0)
        die("could not build the scene");
    for (int k = 0; k < p->settle; k++)
        check(pp_world_step(w, (float)STAB_DT), "settling");
    double spent = 0;
    for (int k = 0; k < p->steps; k++) {
        const double t0 = bench_clock_ms();
        check(pp_world_step(w, (float)STAB_DT), "pp_world_step");
        spent += bench_clock_ms() - t0;
        physpix_stats(w, out);
    }
    out->ms = spent / p->steps;
    check(pp_world_destroy(w), "pp_world_destroy");
    free(bodies);
}

static void run_peer_stab(engine_id e, const stab_scene *s, const scene_plan *p, run_result *out)
{
    const stab_engine *pe = &peers[e];
    void *world = pe->create(pe, s);
    if (!world)
        die("a peer could not build the scene");
    for (int k = 0; k < p->settle; k++)
        (void)pe->step(world);
    double spent = 0;
    for (int k = 0; k < p->steps; k++) {
        const double t0 = bench_clock_ms();
        (void)pe->step(world);
        spent += bench_clock_ms() - t0;
    }
    out->ms = spent / p->steps;
    out->awake = -1; /* stab engines say nothing of sleep: it is off */
    pe->destroy(world);
}

/* Destruction on PhysPix: the terrain one static bitmap body, sleep on; a crater every COST_EDIT_EVERY steps. */
static void run_physpix_destruction(engine_id e, const cost_destruction *d, const scene_plan *p, run_result *out)
{
    pp_world w = physpix_world(e, 1);
    pp_body_def td = pp_body_def_default();
    td.type = PP_BODY_STATIC;
    td.width = COST_TERRAIN_W, td.height = COST_TERRAIN_H, td.mask = d->terrain;
    td.custom_pivot = 1; /* pivot (0, 0) at the origin: bitmap pixels are world pixels */
    pp_body terrain, *crates = malloc((size_t)d->crates.count * sizeof *crates);
    check(pp_body_create(w, &td, &terrain), "the terrain");
    if (!crates || stab_physpix_add_bodies(w, &d->crates, crates) != 0)
        die("could not build the crates");
    for (int k = 0; k < p->settle; k++)
        check(pp_world_step(w, (float)STAB_DT), "settling");
    double spent = 0;
    for (int k = 0; k < p->steps; k++) {
        const double t0 = bench_clock_ms();
        if (k % COST_EDIT_EVERY == 0) {
            double x, y;
            cost_crater(d, k / COST_EDIT_EVERY, &x, &y);
            check(pp_body_erase_circle(w, terrain, (pp_vec2){(float)x, (float)y}, (float)COST_CRATER_R, NULL),
                  "pp_body_erase_circle");
            out->edit_ms += bench_clock_ms() - t0;
            out->edits++;
        }
        check(pp_world_step(w, (float)STAB_DT), "pp_world_step");
        spent += bench_clock_ms() - t0;
        physpix_stats(w, out);
    }
    out->ms = spent / p->steps;
    check(pp_world_destroy(w), "pp_world_destroy");
    free(crates);
}

static void run_remesh(const cost_destruction *d, const scene_plan *p, run_result *out)
{
    cost_remesh *r = cost_remesh_create(d);
    if (!r)
        die("out of memory for the Box2D terrain");
    for (int k = 0; k < p->settle; k++)
        cost_remesh_step(r);
    double spent = 0;
    for (int k = 0; k < p->steps; k++) {
        const double t0 = bench_clock_ms();
        if (k % COST_EDIT_EVERY == 0) {
            double x, y;
            cost_crater(d, k / COST_EDIT_EVERY, &x, &y);
            cost_remesh_erase(r, x, y, COST_CRATER_R);
            out->edit_ms += bench_clock_ms() - t0;
            out->edits++;
        }
        cost_remesh_step(r);
        spent += bench_clock_ms() - t0;
    }
    out->ms = spent / p->steps;
    out->awake = cost_remesh_awake(r);
    cost_remesh_destroy(r);
}

static void run_once(engine_id e, const scene_plan *p, const stab_scene *s, const cost_destruction *d,
                     run_result *out)
{
    memset(out, 0, sizeof *out);
    if (p->kind == S_DESTRUCTION && e == E_REMESH)
        run_remesh(d, p, out);
    else if (p->kind == S_DESTRUCTION)
        run_physpix_destruction(e, d, p, out);
    else if (e == E_BOX2D || e == E_CHIPMUNK)
        run_peer_stab(e, s, p, out);
    else
        run_physpix_stab(e, s, p, out);
}

static int make_plans(const options *o, scene_plan *out)
{
    const unsigned all = 1u << E_FAST | 1u << E_BALANCED | 1u << E_ACCURATE | 1u << E_BOX2D | 1u << E_CHIPMUNK;
    const unsigned sweep = 1u << E_BALANCED | 1u << E_BOX2D | 1u << E_CHIPMUNK;
    const int rain_steps = o->quick ? 100 : 300;
    int n = 0;
    out[n++] = (scene_plan){"pyramid20", "pyramid", S_PYRAMID, 0, 60, o->quick ? 60 : 600, all};
    out[n++] = (scene_plan){"rain500", "rain", S_RAIN, 500, 0, rain_steps, all};
    const int counts[] = {100, 200, 500, 1000};
    for (int i = 0; i < (o->quick ? 3 : 4); i++) { /* --quick: no 1000 */
        out[n] = (scene_plan){"", "sweep", S_RAIN, counts[i], 0, rain_steps, sweep};
        snprintf(out[n].name, sizeof out[n].name, "sweep_rain%d", counts[i]);
        n++;
    }
    out[n++] = (scene_plan){"destruction", "destruction", S_DESTRUCTION, 0, 120, o->quick ? 120 : 600,
                            1u << E_FAST | 1u << E_BALANCED | 1u << E_REMESH};
    return n;
}

static void print_header(const options *o, const scene_plan *plans, int nplans, int runs)
{
    bench_print_machine(o->quick ? "step-cost benchmark (--quick)" : "step-cost benchmark");
    printf("peers: Box2D %s (8 velocity, 3 position iterations; polygon cores inside its 1 px skin),\n"
           "       Chipmunk %s (10 iterations)\n",
           stab_box2d_version(), stab_chipmunk_version());
    int steps[3] = {0}; /* timed steps by scene_kind */
    for (int i = 0; i < nplans; i++)
        steps[plans[i].kind] = plans[i].steps;
    pp_world_def pd[3];
    for (int i = 0; i < 3; i++)
        pd[i] = pp_world_def_preset(presets[i]);
    printf("PhysPix: CPU backend, one thread as the peers, each preset's substeps x iterations (FAST %dx%d, BALANCED\n"
           "%dx%d, ACCURATE %dx%d); 100 px = 1 m, gravity (0, %.0f) px/s^2, dt 1/60 s, friction 0.6.\n"
           "pyramid20: the stability scene's 20-row pyramid of 16 px boxes, sleep off, settled 1 s, %d steps timed.\n"
           "rain500, sweep_rainN: 500 (N) crates of 32 px dropped from a 20-column grid into a walled pit, sleep off:\n"
           "  the first %d steps from the drop timed.\n"
           "destruction: %d crates of 16-32 px on a %dx%d terrain, sleep on, settled 2 s; then a %.0f px crater under\n"
           "  a crate every %d steps, the erase and the step timed together over %d steps. Box2D keeps the terrain\n"
           "  as a bitmap: each 64x64 px chunk with erased pixels is remeshed (marching squares, Douglas-Peucker 1 px,\n"
           "  chain loops) and the crates near it woken.\n"
           "ms/step: mean over the timed steps of a run, median of %d run(s), engines taking turns run by run;\n"
           "/Box2D, /Chipmunk: the row's ms/step over that peer's on the scene; bodies: dynamic bodies;\n"
           "narrow%%, solver%%: PhysPix's narrowphase and solver time over its step time (pp_world_get_stats).\n\n",
           (int)pd[0].substeps, (int)pd[0].solver_iterations, (int)pd[1].substeps, (int)pd[1].solver_iterations,
           (int)pd[2].substeps, (int)pd[2].solver_iterations, STAB_GRAVITY, steps[S_PYRAMID], steps[S_RAIN], COST_CRATES,
           COST_TERRAIN_W, COST_TERRAIN_H, COST_CRATER_R,
           COST_EDIT_EVERY, steps[S_DESTRUCTION], runs);
    printf("%-16s %-18s %6s %9s %7s %9s %8s %8s\n", "scene", "engine", "bodies", "ms/step", "/Box2D", "/Chipmunk",
           "narrow%", "solver%");
}

static double row_median(row *r)
{
    return bench_median(r->ms, r->runs);
}

/* The scene's lines, once all its runs are in. */
static void print_rows(FILE *csv, const scene_plan *p, int bodies, row *rows)
{
    const int b2 = p->kind == S_DESTRUCTION ? E_REMESH : E_BOX2D;
    const double b2_ms = rows[b2].runs ? row_median(&rows[b2]) : NAN; /* NaN: left out by --engine */
    const double cp_ms = rows[E_CHIPMUNK].runs ? row_median(&rows[E_CHIPMUNK]) : NAN;
    for (int e = 0; e < E_COUNT; e++) {
        if (rows[e].runs == 0)
            continue;
        row *r = &rows[e];
        const double ms = row_median(r);
        const int physpix = e <= E_ACCURATE;
        const double narrow = physpix ? 100 * r->sum.narrow / r->sum.total : NAN;
        const double solver = physpix ? 100 * r->sum.solver / r->sum.total : NAN;
        const double edit = r->sum.edits ? r->sum.edit_ms / r->sum.edits : NAN;
        char b[4][32];
        printf("%-16s %-18s %6d %9.4f %7s %9s %8s %8s\n", p->name, engine_names[e], bodies, ms,
               bench_fmt(b[0], 32, "%.2f", ms / b2_ms), bench_fmt(b[1], 32, "%.2f", ms / cp_ms),
               bench_fmt(b[2], 32, "%.1f", narrow), bench_fmt(b[3], 32, "%.1f", solver));
        if (!csv)
            continue;
        fprintf(csv, "%s,%s,%s,%d", p->group, p->name, engine_names[e], bodies);
        const double figures[] = {ms, ms / b2_ms, ms / cp_ms, narrow, solver, edit};
        for (size_t i = 0; i < sizeof figures / sizeof figures[0]; i++)
            bench_csv_field(csv, figures[i]);
        fprintf(csv, ",%d,%d,%d,%d\n", r->runs, p->steps, physpix ? r->sum.threads : 0, r->sum.awake);
    }
    fflush(stdout);
}

/* Destruction's figures outside the table: what an edit costs, who is awake, how large the mesh is. */
static void print_destruction_note(const cost_destruction *d, row *rows)
{
    cost_remesh *r = cost_remesh_create(d);
    int loops = 0, verts = 0;
    if (r)
        cost_remesh_counts(r, &loops, &verts);
    cost_remesh_destroy(r);
    printf("  destruction: mean ms per edit (inside ms/step):");
    for (int e = 0; e < E_COUNT; e++)
        if (rows[e].sum.edits)
            printf(" %s %.3f;", engine_names[e], rows[e].sum.edit_ms / rows[e].sum.edits);
    printf("\n  crates awake after the last step:");
    for (int e = 0; e < E_COUNT; e++)
        if (rows[e].runs)
            printf(" %s %d;", engine_names[e], rows[e].sum.awake);
    printf("\n  Box2D's terrain before the craters: %d chain loops, %d vertices\n", loops, verts);
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
        else if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc)
            o->csv_path = argv[++i];
        else {
            fprintf(strcmp(argv[i], "--help") == 0 ? stdout : stderr,
                    "usage: bench_cost [--quick] [--only TEXT] [--engine TEXT] [--csv PATH]\n"
                    "  --quick        shorter runs, one each, no 1000-crate rain\n"
                    "  --only TEXT    scenes whose name contains TEXT (any case): pyramid, rain, sweep, destruction\n"
                    "  --engine TEXT  engines whose name contains TEXT (any case), e.g. BALANCED (to time one build\n"
                    "                 against another with farm-bench)\n"
                    "  --csv PATH     also write the table as CSV\n");
            return strcmp(argv[i], "--help") == 0 ? 1 : -1;
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    options opt;
    const int parsed = parse_options(argc, argv, &opt);
    if (parsed != 0)
        return parsed > 0 ? 0 : 2;
    peers[E_BOX2D] = stab_engine_box2d();
    peers[E_CHIPMUNK] = stab_engine_chipmunk(10); /* Chipmunk's default */
    scene_plan plans[8];
    const int nplans = make_plans(&opt, plans), runs = opt.quick ? 1 : MAX_RUNS;
    print_header(&opt, plans, nplans, runs);

    FILE *csv = NULL;
    if (opt.csv_path && !(csv = fopen(opt.csv_path, "w")))
        return perror(opt.csv_path), 1;
    if (csv)
        fprintf(csv, "group,scene,engine,bodies,ms_step_median,ratio_box2d,ratio_chipmunk,narrowphase_pct,solver_pct,"
                     "edit_ms_mean,runs,steps,threads_max,awake_end\n");

    const double t0 = bench_clock_ms();
    for (int i = 0; i < nplans; i++) {
        const scene_plan *p = &plans[i];
        if (!bench_matches(p->name, opt.only))
            continue;
        stab_scene scene = {0};
        cost_destruction destruction = {0};
        int bodies = 0;
        if (p->kind == S_PYRAMID ? stab_scene_build(stab_scene_find("pyramid20"), &scene)
            : p->kind == S_RAIN  ? cost_rain_build(p->crates, &scene)
                                 : cost_destruction_build(&destruction))
            die("out of memory building a scene");
        const stab_scene *counted = p->kind == S_DESTRUCTION ? &destruction.crates : &scene;
        for (int k = 0; k < counted->count; k++)
            bodies += !counted->bodies[k].is_static;

        row rows[E_COUNT];
        memset(rows, 0, sizeof rows);
        for (int r = 0; r < runs; r++) /* A B C A B C: the machine's noise falls on every engine alike */
            for (int e = 0; e < E_COUNT; e++) {
                if (!(p->engines >> e & 1) || !bench_matches(engine_names[e], opt.engine))
                    continue;
                run_result res;
                run_once((engine_id)e, p, &scene, &destruction, &res);
                row *w = &rows[e];
                w->ms[w->runs++] = res.ms;
                w->sum.edit_ms += res.edit_ms, w->sum.edits += res.edits;
                w->sum.narrow += res.narrow, w->sum.solver += res.solver, w->sum.total += res.total;
                w->sum.threads = res.threads > w->sum.threads ? res.threads : w->sum.threads;
                w->sum.awake = res.awake;
            }
        print_rows(csv, p, bodies, rows);
        if (p->kind == S_DESTRUCTION)
            print_destruction_note(&destruction, rows);
        stab_scene_free(&scene);
        cost_destruction_free(&destruction);
    }
    printf("\nwall time %.1f s\n", (bench_clock_ms() - t0) * 1e-3);
    if (csv && fclose(csv) != 0)
        return perror(opt.csv_path), 1;
    if (csv)
        printf("wrote %s\n", opt.csv_path);
    return 0;
}
