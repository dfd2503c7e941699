/* PhysPix accuracy benchmark: the speed/accuracy trade of the world's knobs. Each setting (one knob
 * at a time around the default, the poster's method, the presets, candidates for FAST and ACCURATE)
 * is measured for time per step, contact normal and depth errors, resting penetration, stack
 * stability, bounce energy and momentum; a combined score (worst ratio to its target, ≤ 1 meets
 * all) against ms/step marks the Pareto front. A table, and CSV for tests/bench/accuracy/plot.py.
 *
 *   bench_accuracy [--csv PATH] [--quick] [--only TEXT]
 */
#include "accuracy.h"
#include "machine.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* What a setting is in the sweep; a def reached twice keeps one row with both roles. */
enum {
    ROLE_DEFAULT = 1 << 0,
    ROLE_FAST = 1 << 1,
    ROLE_BALANCED = 1 << 2,
    ROLE_ACCURATE = 1 << 3,
    ROLE_POSTER = 1 << 4,
    ROLE_SWEEP = 1 << 5,
    ROLE_FAST_CAND = 1 << 6,
    ROLE_ACC_CAND = 1 << 7,
};
static const char *const role_names[] = {"default", "FAST", "BALANCED", "ACCURATE", "poster", "sweep", "fast?",
                                         "accurate?"};
#define ROLE_COUNT (int)(sizeof role_names / sizeof role_names[0])

#define MAX_SETTINGS 48

typedef struct setting {
    pp_world_def def;
    unsigned roles;
    char name[96];   ///< the knobs that differ from the default, e.g. "sub1 it10 stride2"
    acc_metrics m;
    int measured;    ///< nonzero: every run finished
    double ms;       ///< ms/step of the pyramid plus the tower (the Pareto axis)
    double score;    ///< worst ratio of a metric to its target
    int limit;       ///< index of that metric in `targets`
    int pareto;      ///< nonzero: on the Pareto front of (ms, score)
} setting;

/* The targets of the combined score: the bars' (tests/bench/README.md) where they name one, else ours, each with why. */
enum { T_NMED, T_NP95, T_DEPTH, T_PYR, T_TOWER, T_DRIFT, T_PENMEAN, T_PENMAX, T_ENERGY, T_MOMENTUM, T_COUNT };
static const struct target {
    const char *name, *unit;
    double limit;
    const char *why;
} targets[T_COUNT] = {
    [T_NMED] = {"normal median", "deg", 0.5, "accuracy bar (worst of the three analytic families)"},
    [T_NP95] = {"normal p95", "deg", 2.0, "accuracy bar (worst of the three analytic families)"},
    [T_DEPTH] = {"depth median", "px", 0.5, "accuracy bar (worst of the three analytic families)"},
    [T_PYR] = {"pyramid stands", "px", ACC_STAND_PX, "stability bar: a 10-row pyramid stands 60 s (see 'standing')"},
    [T_TOWER] = {"tower stands", "px", ACC_STAND_PX, "stability bar: a 10-box tower stands 60 s (see 'standing')"},
    [T_DRIFT] = {"tower drift", "px", 1.0, "ours: a standing tower moves less than a pixel in a minute"},
    [T_PENMEAN] = {"rest pen. mean", "px", 1.0, "ours: the slop (0.75 px) plus a quarter pixel"},
    [T_PENMAX] = {"rest pen. max", "px", 2.0, "ours: the slop plus the raster's one-pixel step, rounded up"},
    [T_ENERGY] = {"bounce energy", "%", 5.0, "ours: 10 elastic bounces keep their energy within 0.5% a bounce"},
    [T_MOMENTUM] = {"momentum", "%", 1.0, "tests/c/test_dynamics.c's bar for free collisions"},
};

typedef struct options {
    const char *csv_path; ///< NULL: no CSV
    int quick;            ///< nonzero: a 10 s horizon and short timing runs
    const char *only;     ///< NULL: every setting; else those whose name or role contains it
} options;

static void usage(FILE *f)
{
    fprintf(f, "usage: bench_accuracy [--csv PATH] [--quick] [--only TEXT]\n"
               "  --csv PATH   also write the table as CSV (for tests/bench/accuracy/plot.py)\n"
               "  --quick      stacks watched 10 s instead of 60 s, short timing runs (under a minute)\n"
               "  --only TEXT  measure only settings whose name or role contains TEXT\n");
}

static int parse_options(int argc, char **argv, options *o)
{
    *o = (options){0};
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
            o->csv_path = argv[++i];
        } else if (strcmp(argv[i], "--quick") == 0) {
            o->quick = 1;
        } else if (strcmp(argv[i], "--only") == 0 && i + 1 < argc) {
            o->only = argv[++i];
        } else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            exit(0);
        } else {
            usage(stderr);
            return -1;
        }
    }
    return 0;
}

/* The knobs in which d differs from the default, as a short name. */
static void describe(const pp_world_def *d, char *buf, size_t size)
{
    const pp_world_def z = pp_world_def_default();
    size_t k = 0;
    buf[0] = '\0';
#define ADD(...) (k += k < size ? (size_t)snprintf(buf + k, size - k, __VA_ARGS__) : 0)
#define SEP (k ? " " : "")
    if (d->backend != z.backend)
        ADD("%s%s", SEP, d->backend == PP_BACKEND_GPU ? "gpu" : d->backend == PP_BACKEND_CPU ? "cpu" : "auto");
    if (d->normal_method != z.normal_method)
        ADD("%s%s", SEP, d->normal_method == PP_NORMAL_KERNEL ? "kernel" : "area-gradient");
    if (d->contact_mode != z.contact_mode)
        ADD("%s%s", SEP, d->contact_mode == PP_CONTACT_CENTROID ? "centroid" : "manifold");
    if (d->raster_stride != z.raster_stride)
        ADD("%sstride%d", SEP, (int)d->raster_stride);
    if (d->substeps != z.substeps)
        ADD("%ssub%d", SEP, (int)d->substeps);
    if (d->solver_iterations != z.solver_iterations)
        ADD("%sit%d", SEP, (int)d->solver_iterations);
    if (d->exact_solver != z.exact_solver)
        ADD("%s%s", SEP, d->exact_solver ? "exact" : "quick");
    if (d->contact_slop != z.contact_slop)
        ADD("%sslop%g", SEP, (double)d->contact_slop);
    if (d->contact_erp != z.contact_erp)
        ADD("%serp%g", SEP, (double)d->contact_erp);
    if (d->contact_cfm != z.contact_cfm)
        ADD("%scfm%g", SEP, (double)d->contact_cfm);
    if (d->pixels_per_meter != z.pixels_per_meter)
        ADD("%sppm%g", SEP, (double)d->pixels_per_meter);
    if (d->continuous != z.continuous)
        ADD("%sccd%u", SEP, (unsigned)d->continuous);
    if (d->bounce_threshold != z.bounce_threshold)
        ADD("%sbounce%g", SEP, (double)d->bounce_threshold);
    pp_world_def rest = *d; /* any other field that differs, named only as "+other" */
    rest.backend = z.backend, rest.normal_method = z.normal_method, rest.contact_mode = z.contact_mode;
    rest.raster_stride = z.raster_stride, rest.substeps = z.substeps, rest.solver_iterations = z.solver_iterations;
    rest.exact_solver = z.exact_solver, rest.contact_slop = z.contact_slop, rest.contact_erp = z.contact_erp;
    rest.contact_cfm = z.contact_cfm, rest.pixels_per_meter = z.pixels_per_meter, rest.continuous = z.continuous;
    rest.bounce_threshold = z.bounce_threshold;
    if (memcmp(&rest, &z, sizeof z) != 0)
        ADD("%s+other", SEP);
    if (k == 0)
        ADD("default");
#undef SEP
#undef ADD
}

static void role_string(unsigned roles, char *buf, size_t size)
{
    size_t k = 0;
    buf[0] = '\0';
    for (int r = 0; r < ROLE_COUNT; r++)
        if (roles & (1u << r))
            k += k < size ? (size_t)snprintf(buf + k, size - k, "%s%s", k ? "+" : "", role_names[r]) : 0;
}

/* Adds a setting, or a role to the setting with the same def. */
static void add_setting(setting *list, int *n, pp_world_def d, unsigned roles)
{
    for (int i = 0; i < *n; i++)
        if (memcmp(&list[i].def, &d, sizeof d) == 0) {
            list[i].roles |= roles;
            return;
        }
    if (*n == MAX_SETTINGS)
        return;
    setting *s = &list[(*n)++];
    *s = (setting){.def = d, .roles = roles};
    describe(&d, s->name, sizeof s->name);
}

/* A def from the default with the given knobs; 0 leaves a count at the default. */
static pp_world_def knobs(int substeps, int iterations, int stride, int exact)
{
    pp_world_def d = pp_world_def_default();
    if (substeps)
        d.substeps = substeps;
    if (iterations)
        d.solver_iterations = iterations;
    if (stride)
        d.raster_stride = stride;
    d.exact_solver = (uint32_t)exact;
    return d;
}

static int build_settings(setting *list, int gpu_ok)
{
    int n = 0;
    pp_world_def d = pp_world_def_default();
    add_setting(list, &n, d, ROLE_DEFAULT);
    add_setting(list, &n, pp_world_def_preset(PP_PRESET_BALANCED), ROLE_BALANCED);
    add_setting(list, &n, pp_world_def_preset(PP_PRESET_FAST), ROLE_FAST);
    add_setting(list, &n, pp_world_def_preset(PP_PRESET_ACCURATE), ROLE_ACCURATE);
    d.normal_method = PP_NORMAL_KERNEL;
    d.contact_mode = PP_CONTACT_CENTROID;
    add_setting(list, &n, d, ROLE_POSTER);

    /* One knob at a time around the default. */
    d = pp_world_def_default();
    d.normal_method = PP_NORMAL_KERNEL;
    add_setting(list, &n, d, ROLE_SWEEP);
    d = pp_world_def_default();
    d.contact_mode = PP_CONTACT_CENTROID;
    add_setting(list, &n, d, ROLE_SWEEP);
    static const int strides[] = {1, 2, 4}, substeps[] = {1, 2, 4, 8}, iterations[] = {5, 10, 20, 30, 40};
    for (int i = 0; i < 3; i++)
        add_setting(list, &n, knobs(0, 0, strides[i], 0), ROLE_SWEEP);
    for (int i = 0; i < 4; i++)
        add_setting(list, &n, knobs(substeps[i], 0, 0, 0), ROLE_SWEEP);
    for (int i = 0; i < 5; i++)
        add_setting(list, &n, knobs(0, iterations[i], 0, 0), ROLE_SWEEP);
    add_setting(list, &n, knobs(0, 0, 0, 1), ROLE_SWEEP);
    if (gpu_ok) {
        d = pp_world_def_default();
        d.backend = PP_BACKEND_GPU;
        add_setting(list, &n, d, ROLE_SWEEP);
    }

    /* Candidates: cheaper solving for FAST, more of it (or the exact solver) for ACCURATE; and the
     * same with one contact point a pair (CENTROID), the one knob that keeps the tower standing.
     * With CENTROID, iterations hold the pyramid better than substeps do, and substeps cost bounce
     * energy, so the ACCURATE candidates raise iterations. */
    static const struct {
        int substeps, iterations, stride, exact, centroid, kernel;
        unsigned role;
    } cand[] = {
        {1, 10, 2, 0, 0, 0, ROLE_FAST_CAND}, {2, 10, 2, 0, 0, 0, ROLE_FAST_CAND},
        {1, 10, 1, 0, 0, 0, ROLE_FAST_CAND}, {1, 20, 1, 0, 1, 0, ROLE_FAST_CAND},
        {2, 10, 1, 0, 1, 0, ROLE_FAST_CAND}, {2, 30, 1, 0, 1, 0, ROLE_FAST_CAND},
        {2, 30, 1, 0, 1, 1, ROLE_FAST_CAND}, {2, 40, 1, 0, 1, 1, ROLE_FAST_CAND},
        {4, 40, 1, 0, 0, 0, ROLE_ACC_CAND},  {8, 40, 1, 0, 0, 0, ROLE_ACC_CAND},
        {2, 60, 1, 0, 0, 0, ROLE_ACC_CAND},  {2, 80, 1, 0, 0, 0, ROLE_ACC_CAND},
        {4, 80, 1, 0, 0, 0, ROLE_ACC_CAND},
        {2, 40, 1, 0, 1, 0, ROLE_ACC_CAND},  {2, 80, 1, 0, 1, 0, ROLE_ACC_CAND},
        {4, 40, 1, 0, 1, 0, ROLE_ACC_CAND},  {2, 20, 1, 1, 1, 0, ROLE_ACC_CAND},
    };
    for (size_t i = 0; i < sizeof cand / sizeof cand[0]; i++) {
        d = knobs(cand[i].substeps, cand[i].iterations, cand[i].stride, cand[i].exact);
        if (cand[i].centroid)
            d.contact_mode = PP_CONTACT_CENTROID;
        if (cand[i].kernel)
            d.normal_method = PP_NORMAL_KERNEL;
        add_setting(list, &n, d, cand[i].role);
    }
    return n;
}

/* Bring the GPU up once, so a failure is told once and its rows are skipped. */
static int probe_gpu(void)
{
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_GPU;
    pp_world w;
    pp_status st = pp_world_create(&d, &w);
    if (st != PP_OK) {
        printf("GPU backend unavailable (%s): %s; GPU rows skipped\n", pp_status_name(st), pp_last_error());
        return 0;
    }
    pp_world_destroy(w);
    return 1;
}

static int matches(const setting *s, const char *only)
{
    char roles[128];
    role_string(s->roles, roles, sizeof roles);
    return !only || strstr(s->name, only) || strstr(roles, only);
}

static double worst(const double *v)
{
    double w = v[0];
    for (int f = 1; f < ANALYTIC_FAMILY_COUNT; f++)
        w = fmax(w, v[f]);
    return w;
}

static double pen_mean(const acc_metrics *m)
{
    long n = m->pyramid.pen_count + m->tower.pen_count;
    return n ? (m->pyramid.pen_sum + m->tower.pen_sum) / n : 0.0;
}

/* A stack's standing measure: how far a box went, px; standing is ≤ ACC_STAND_PX (NaN: never settled). */
static double stand_px(const acc_stack *s)
{
    if (s->nan)
        return INFINITY;
    return isnan(s->settle_shift) || isnan(s->drift) ? NAN : fmax(s->settle_shift, s->drift);
}

/* Each metric's value in its target's unit. */
static void metric_values(const acc_metrics *m, double v[T_COUNT])
{
    v[T_NMED] = worst(m->normal_med);
    v[T_NP95] = worst(m->normal_p95);
    v[T_DEPTH] = worst(m->depth_med);
    v[T_PYR] = stand_px(&m->pyramid);
    v[T_TOWER] = stand_px(&m->tower);
    v[T_DRIFT] = m->tower.nan ? INFINITY : m->tower.drift;
    if (!(v[T_TOWER] <= ACC_STAND_PX))
        v[T_DRIFT] = NAN; /* a fallen tower's drift is its fall, which 'tower stands' already counts */
    v[T_PENMEAN] = pen_mean(m);
    v[T_PENMAX] = fmax(m->pyramid.pen_max, m->tower.pen_max);
    v[T_ENERGY] = m->energy_pct;
    v[T_MOMENTUM] = m->momentum_collided ? m->momentum_pct : INFINITY; /* no collision: nothing was tested */
}

/* Unmeasured metrics (NaN) are left out; the row is then incomplete, or the tower fell. */
static void score_setting(setting *s)
{
    double v[T_COUNT];
    metric_values(&s->m, v);
    s->score = 0;
    s->limit = 0;
    for (int t = 0; t < T_COUNT; t++) {
        double r = v[t] / targets[t].limit;
        if (r > s->score) {
            s->score = r;
            s->limit = t;
        }
    }
    s->ms = s->m.pyramid.ms_median + s->m.tower.ms_median;
}

/* Complete: no scored run was cut short by the budget, so its score is a claim. */
static int complete(const setting *s) { return s->measured && s->m.pyramid.complete && s->m.tower.complete; }

/* On the front: no other complete setting is at least as fast and as good, and better in one. */
static void mark_pareto(setting *list, int n, const acc_plan *plan)
{
    for (int i = 0; i < n; i++) {
        list[i].pareto = complete(&list[i]);
        for (int j = 0; j < n && list[i].pareto; j++) {
            if (j == i || !complete(&list[j]))
                continue;
            const setting *a = &list[i], *b = &list[j];
            if (b->ms <= a->ms && b->score <= a->score && (b->ms < a->ms || b->score < a->score))
                list[i].pareto = 0;
        }
    }
}

static int measure(setting *s, const acc_plan *plan, bench_scene *pyramid, bench_scene *tower, bench_scene *rain)
{
    acc_metrics *m = &s->m;
    *m = (acc_metrics){0};
    if (acc_measure_collide(&s->def, m) || acc_measure_stack(pyramid, &s->def, plan, &m->pyramid, &m->backend_ran) ||
        acc_measure_stack(tower, &s->def, plan, &m->tower, NULL) ||
        acc_measure_timing(rain, &s->def, plan->budget_s / 4, &m->rain_ms, &m->rain_steps) ||
        acc_measure_bounce(&s->def, m) || acc_measure_momentum(&s->def, m))
        return -1;
    s->measured = 1;
    score_setting(s);
    return 0;
}

static void print_machine(const acc_plan *plan, const options *o)
{
    char model[256];
    bench_cpu_model(model, sizeof model);
    uint32_t v = pp_version();
    printf("PhysPix %u.%u.%u accuracy benchmark%s\n", v / 10000, v / 100 % 100, v % 100, o->quick ? " (--quick)" : "");
    printf("machine: %ld cpus online, %s; one thread\n", sysconf(_SC_NPROCESSORS_ONLN), model);
    printf("every run: dt 1/60 s, sleep OFF (allow_sleep = 0) so that the solver's drift is what is measured;\n"
           "  other world settings from pp_world_def_default() except the knobs named in 'setting'\n");
    printf("ms/step: wall time of one pp_world_step with sleep off (the least median of six equal blocks of a run,\n"
           "  so that other processes do not count), on the pyramid (10 rows of %d px boxes, %.0f s) and the tower\n"
           "  (10 boxes, %.0f s); 'p+t' sums the two and is the Pareto axis; 'rain' (500 crates falling into a pile,\n"
           "  %d steps, plain median) is the many-body cost, not scored: its pile differs by setting\n",
           ACC_SIDE, plan->settle_s + plan->horizon_s, plan->settle_s + plan->horizon_s, plan->rain_steps);
    printf("normal/depth: pp_world_collide at %.0f px overlap on circle-circle (%d directions), box-ground (0..90 deg)\n"
           "  and rotated box-box (%d poses, both ways); the worst family's median and 95th percentile\n",
           ANALYTIC_PEN, ANALYTIC_CIRCLE_DIRS, ANALYTIC_BOXBOX_POSES);
    printf("standing: a stack settles %.0f s; it stands if no box is then more than %.0f px (a quarter box) off its\n"
           "  built x, and no box moves more than %.0f px from that settled pose over the next %.0f s%s;\n"
           "  'stand' columns give that largest offset, px (the vertical sag while settling is the resting\n"
           "  penetration's: pen = contact depths of both stacks over their last %.0f s, mean and max, px)\n",
           plan->settle_s, ACC_STAND_PX, ACC_STAND_PX, plan->horizon_s, o->quick ? " (--quick: the bar is 60)" : "",
           plan->contact_s);
    printf("drift: the tower's largest displacement of a box from its settled pose over the %.0f s, px; scored\n"
           "  only while the tower stands (a fall is scored as 'tower stands')\n",
           plan->horizon_s);
    printf("energy: a r=16 disc dropped 200 px on a static ground, restitution 1, bounce_threshold 0: largest\n"
           "  |E - E0|/E0 (kinetic + potential) at the apexes after each of %d bounces, %%\n",
           ACC_BOUNCES);
    printf("momentum: gravity 0, head-on boxes, oblique discs, a spinning bar and two boxes; largest\n"
           "  |p_after - p_before| / |p_before| after 1 s, %%\n");
    printf("score: the worst ratio of a metric to its target (<= 1 meets all); 'limit' names that metric:\n");
    for (int t = 0; t < T_COUNT; t++)
        printf("  %-15s <= %-4g %-3s  %s\n", targets[t].name, targets[t].limit, targets[t].unit, targets[t].why);
    printf("Pareto: no other complete setting is both at least as fast (p+t ms) and scores at least as well;\n"
           "  a setting whose stack runs took over %.0f s (rain: %.0f s) was cut short: marked '*', its score counts\n"
           "  what ran ('meets' is '?' unless that already fails), and it is left off the front\n\n",
           plan->budget_s, plan->budget_s / 4);
}

static void print_header(void)
{
    printf("%-28s %-20s %7s %7s %7s %7s | %6s %6s %6s | %5s %5s | %6s %6s %6s | %6s %7s | %7s %5s %-14s %1s %s\n",
           "setting", "role", "pyr", "tower", "p+t", "rain", "n.med", "n.p95", "d.med", "pen", "pen", "pyr",
           "tower", "tower", "energy", "moment.", "score", "meets", "limit", "P", "");
    printf("%-28s %-20s %7s %7s %7s %7s | %6s %6s %6s | %5s %5s | %6s %6s %6s | %6s %7s | %7s %5s %-14s %1s %s\n", "",
           "", "ms", "ms", "ms", "ms", "deg", "deg", "px", "mean", "max", "stand", "stand", "drift", "%", "%", "", "",
           "", "", "");
}

/* A number, "inf" (diverged) or "n/a" (not measured, or drift of a fallen tower). */
static void fmt(char *buf, size_t size, double v, int prec)
{
    if (isfinite(v))
        snprintf(buf, size, "%.*f", prec, v);
    else
        snprintf(buf, size, "%s", isnan(v) ? "n/a" : "inf");
}

static void print_row(const setting *s, const acc_plan *plan)
{
    double v[T_COUNT];
    metric_values(&s->m, v);
    char roles[128], c[T_COUNT][32], score[32];
    role_string(s->roles, roles, sizeof roles);
    const int prec[T_COUNT] = {2, 2, 2, 2, 2, 2, 2, 2, 2, 3};
    for (int t = 0; t < T_COUNT; t++)
        fmt(c[t], sizeof c[t], v[t], prec[t]);
    fmt(score, sizeof score, s->score, 2);
    char cut[96] = "";
    if (!complete(s) || s->m.rain_steps < plan->rain_steps)
        snprintf(cut, sizeof cut, "* ran: pyramid %.1f s, tower %.1f s, rain %d steps", s->m.pyramid.sim_s,
                 s->m.tower.sim_s, s->m.rain_steps);
    const char *meets = s->score > 1.0 ? "no" : complete(s) ? "yes" : "?";
    printf("%-28s %-20s %7.3f %7.3f %7.3f %7.3f | %6s %6s %6s | %5s %5s | %6s %6s %6s | %6s %7s | %7s %5s %-14s %1s %s\n",
           s->name, roles, s->m.pyramid.ms_median, s->m.tower.ms_median, s->ms, s->m.rain_ms, c[T_NMED], c[T_NP95],
           c[T_DEPTH], c[T_PENMEAN], c[T_PENMAX], c[T_PYR], c[T_TOWER], c[T_DRIFT], c[T_ENERGY], c[T_MOMENTUM], score,
           meets, targets[s->limit].name, s->pareto ? "P" : "", cut);
}

static void write_csv(FILE *f, const setting *list, int n, const acc_plan *plan)
{
    fprintf(f, "setting,roles,normal_method,contact_mode,raster_stride,substeps,solver_iterations,exact_solver,"
               "backend,backend_ran,ms_pyramid,ms_tower,ms_pyramid_tower,ms_rain,rain_steps");
    for (int fam = 0; fam < ANALYTIC_FAMILY_COUNT; fam++) {
        const char *name = analytic_family_name((analytic_family)fam);
        fprintf(f, ",normal_med_%s,normal_p95_%s,depth_med_%s", name, name, name);
    }
    fprintf(f, ",normal_med,normal_p95,depth_med,pen_mean,pen_max,pyramid_sim_s,pyramid_settle_shift,pyramid_sag,"
               "pyramid_drift,pyramid_stand,pyramid_stands,tower_sim_s,tower_settle_shift,tower_sag,tower_drift,"
               "tower_stand,tower_stands,energy_pct,energy_final_pct,bounces,bounce_side_speed,momentum_pct,"
               "momentum_collided,"
               "score,limit,meets,complete,pareto\n");
    for (int i = 0; i < n; i++) {
        const setting *s = &list[i];
        if (!s->measured)
            continue;
        const acc_metrics *m = &s->m;
        double v[T_COUNT];
        metric_values(m, v);
        char roles[128];
        role_string(s->roles, roles, sizeof roles);
        fprintf(f, "%s,%s,%s,%s,%d,%d,%d,%u,%s,%s,%.6f,%.6f,%.6f,%.6f,%d", s->name, roles,
                s->def.normal_method == PP_NORMAL_KERNEL ? "KERNEL" : "AREA_GRADIENT",
                s->def.contact_mode == PP_CONTACT_CENTROID ? "CENTROID" : "MANIFOLD", (int)s->def.raster_stride,
                (int)s->def.substeps, (int)s->def.solver_iterations, (unsigned)s->def.exact_solver,
                s->def.backend == PP_BACKEND_GPU ? "GPU" : s->def.backend == PP_BACKEND_CPU ? "CPU" : "AUTO",
                m->backend_ran == PP_BACKEND_GPU ? "GPU" : "CPU", m->pyramid.ms_median, m->tower.ms_median, s->ms,
                m->rain_ms, m->rain_steps);
        for (int fam = 0; fam < ANALYTIC_FAMILY_COUNT; fam++)
            fprintf(f, ",%.4f,%.4f,%.4f", m->normal_med[fam], m->normal_p95[fam], m->depth_med[fam]);
        fprintf(f, ",%.4f,%.4f,%.4f,%.4f,%.3f,%.3f,%.3f,%.4f,%.4f,%.4f,%d,%.3f,%.3f,%.3f,%.4f,%.4f,%d", v[T_NMED],
                v[T_NP95], v[T_DEPTH], v[T_PENMEAN], v[T_PENMAX], m->pyramid.sim_s, m->pyramid.settle_shift,
                m->pyramid.sag, m->pyramid.drift, v[T_PYR], v[T_PYR] <= ACC_STAND_PX, m->tower.sim_s,
                m->tower.settle_shift, m->tower.sag, m->tower.drift, v[T_TOWER], v[T_TOWER] <= ACC_STAND_PX);
        fprintf(f, ",%.4f,%.4f,%d,%.3f,%.6f,%d,%.4f,%s,%d,%d,%d\n", m->energy_pct, m->energy_final_pct, m->bounces,
                m->bounce_side_speed, m->momentum_pct, m->momentum_collided, s->score, targets[s->limit].name,
                s->score <= 1.0 && complete(s), complete(s), s->pareto);
    }
}

/* What a reader wants first: the default against the bars, the presets, the front. */
static void print_summary(const setting *list, int n)
{
    for (int i = 0; i < n; i++) {
        const setting *s = &list[i];
        if (!s->measured || !(s->roles & ROLE_DEFAULT))
            continue;
        double v[T_COUNT];
        metric_values(&s->m, v);
        printf("\nthe default against the bars (tests/bench/README.md):\n");
        const int bars[] = {T_NMED, T_NP95, T_DEPTH, T_PYR, T_TOWER};
        for (size_t k = 0; k < sizeof bars / sizeof bars[0]; k++) {
            int t = bars[k];
            printf("  %-15s %8.3f %-3s (target <= %g): %s\n", targets[t].name, v[t], targets[t].unit, targets[t].limit,
                   v[t] <= targets[t].limit ? "holds" : "FAILS");
        }
        printf("  and ours:\n");
        for (int t = T_DRIFT; t < T_COUNT; t++) {
            if (isnan(v[t]))
                printf("  %-15s      n/a     (target <= %g %s): %s\n", targets[t].name, targets[t].limit,
                       targets[t].unit, t == T_DRIFT ? "the tower fell" : "not measured");
            else
                printf("  %-15s %8.3g %-3s (target <= %g): %s\n", targets[t].name, v[t], targets[t].unit,
                       targets[t].limit, v[t] <= targets[t].limit ? "holds" : "over");
        }
    }
    printf("\nPareto front (fastest first):");
    double after = -1;
    for (;;) { /* the front's settings in order of ms, without sorting the table */
        const setting *next = NULL;
        for (int i = 0; i < n; i++)
            if (list[i].pareto && list[i].ms > after && (!next || list[i].ms < next->ms))
                next = &list[i];
        if (!next)
            break;
        char roles[128];
        role_string(next->roles, roles, sizeof roles);
        printf("\n  %-28s %8.3f ms  score %7.2f  %s", next->name, next->ms, next->score, roles);
        after = next->ms;
    }
    printf("\n");
}

int main(int argc, char **argv)
{
    options opt;
    if (parse_options(argc, argv, &opt) != 0)
        return 2;
    const acc_plan plan = opt.quick ? (acc_plan){.settle_s = 1, .horizon_s = 10, .contact_s = 1, .rain_steps = 40,
                                                 .budget_s = 3}
                                    : (acc_plan){.settle_s = 1, .horizon_s = 60, .contact_s = 1, .rain_steps = 120,
                                                 .budget_s = 28};
    print_machine(&plan, &opt);
    const int gpu_ok = probe_gpu();

    static setting list[MAX_SETTINGS];
    const int n = build_settings(list, gpu_ok);
    bench_scene pyramid, tower, rain;
    if (bench_scene_pyramid(&pyramid, 0) || acc_scene_tower(&tower, 0) || bench_scene_rain(&rain, plan.rain_steps))
        return 1;

    const double t_start = bench_now_ms();
    int failed = 0, ran = 0;
    for (int i = 0; i < n; i++) {
        if (!matches(&list[i], opt.only))
            continue;
        const double t0 = bench_now_ms();
        if (measure(&list[i], &plan, &pyramid, &tower, &rain) != 0) {
            fprintf(stderr, "bench_accuracy: setting %s failed\n", list[i].name);
            failed = 1;
            continue;
        }
        ran++;
        printf("measured %-24s in %5.1f s (score %.2f, %s)\n", list[i].name, (bench_now_ms() - t0) * 1e-3,
               list[i].score, targets[list[i].limit].name);
        fflush(stdout);
    }
    mark_pareto(list, n, &plan);

    printf("\n");
    print_header();
    for (int i = 0; i < n; i++)
        if (list[i].measured)
            print_row(&list[i], &plan);
    print_summary(list, n);
    printf("\nwall time %.1f s\n", (bench_now_ms() - t_start) * 1e-3);

    if (opt.csv_path) {
        FILE *csv = fopen(opt.csv_path, "w");
        if (!csv) {
            perror(opt.csv_path);
            return 1;
        }
        write_csv(csv, list, n, &plan);
        if (fclose(csv) != 0) {
            perror(opt.csv_path);
            return 1;
        }
        printf("wrote %s\n", opt.csv_path);
    }
    bench_scene_free(&pyramid);
    bench_scene_free(&tower);
    bench_scene_free(&rain);
    if (ran == 0 && !failed)
        fprintf(stderr, "bench_accuracy: no setting matches %s\n", opt.only);
    return failed || ran == 0 ? 1 : 0;
}
