/* Tunnelling: the largest speed at which a fast body never passes through an 8 px thick wall at
 * dt = 1/60 s, for substepping alone, continuous collision and bullets, over a ladder of speeds,
 * start phases and approach angles; with the cost of a step of the fast body. Table and CSV.
 *
 *   bench_tunnel [--csv PATH] [--detail PATH] [--quick]
 */
#include "../machine.h"
#include "physpix.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define DT (1.0f / 60.0f)
#define WALL_T 8        /* wall thickness along its normal (x), px */
#define WALL_H 4096     /* wall length (y), px: the slide after an angled hit stays on it */
#define WALL_X 4096.0   /* wall centre, px */
#define WALL_Y 4096.0
#define MAX_STEPS 40
#define SETTLE_STEPS 30 /* extra steps for a body left inside the wall to be pushed out */
#define MAX_SPEEDS 64
#define TIME_SLOW 2000.0   /* px/s: timed hits */
#define TIME_FAST 50000.0  /* px/s: timed hits and grazes */
#define TIMING_RUNS 3
#define TIMING_TRIALS 11
#define GRAZE_GAP 0.25  /* px */
#define PI 3.14159265358979323846

/* One world setting under test. */
typedef struct config {
    const char *name;
    uint32_t continuous; ///< pp_world_def.continuous
    int32_t substeps;
    uint32_t bullet;     ///< pp_body_def.bullet on the fast body
    int dynamic_wall;    ///< nonzero: a heavy dynamic wall instead of a static one
    float restitution;   ///< of the fast body (the wall keeps 0; pairs use the larger)
} config;

static const config configs[] = {
    {"off 1 substep", 0, 1, 0, 0, 0.0f},
    {"off 2 substeps", 0, 2, 0, 0, 0.0f},
    {"off 4 substeps", 0, 4, 0, 0, 0.0f},
    {"off 8 substeps", 0, 8, 0, 0, 0.0f},
    {"continuous 1 substep", 1, 1, 0, 0, 0.0f},
    {"continuous 2 substeps", 1, 2, 0, 0, 0.0f},
    {"off 2 substeps e=0.5", 0, 2, 0, 0, 0.5f},
    {"continuous 2 sub e=0.5", 1, 2, 0, 0, 0.5f},
    {"dyn wall continuous", 1, 2, 0, 1, 0.0f},
    {"dyn wall bullet", 1, 2, 1, 1, 0.0f},
};
#define NCONFIG (int)(sizeof configs / sizeof configs[0])

/* The fast body: a solid w×h box; `along` turns its long side into the direction of motion. */
typedef struct shape {
    const char *name;
    int w, h;
    int along;
    float angle, spin; ///< initial angle, rad, and angular velocity, rad/s
} shape;

static const shape shapes[] = {
    {"box4", 4, 4, 0, 0, 0},
    {"box8", 8, 8, 0, 0, 0},
    {"box16", 16, 16, 0, 0, 0},
    {"stick16x2", 16, 2, 1, 0, 0},
    {"box8 spin", 8, 8, 0, 0.3f, 30.0f},
};
#define NSHAPE (int)(sizeof shapes / sizeof shapes[0])
#define NSHAPE_QUICK 3

typedef struct options {
    const char *csv_path, *detail_path;
    int quick;
} options;

/* A (config, shape) cell of the table. */
typedef struct cell {
    double safe;        ///< largest speed at and below which no trial tunnels, px/s (the top speed: none did)
    double first_fail;  ///< lowest speed at which a trial tunnels, px/s; 0: none
    double clean;       ///< largest speed at and below which no trial tunnels or sticks, px/s
    long trials, tunnelled, stuck;
    long swept;         ///< pp_step_stats.swept_stops, summed over all trials
    double us_hit_slow, us_hit_fast; ///< µs per pp_world_step of a head-on hit at TIME_SLOW, TIME_FAST px/s
    double us_graze;                 ///< µs per pp_world_step sliding past the wall at TIME_FAST px/s
} cell;

enum outcome { OUT_CLEAR, OUT_STUCK, OUT_TUNNEL };

static void usage(FILE *f)
{
    fprintf(f, "usage: bench_tunnel [--csv PATH] [--detail PATH] [--quick]\n"
               "  --csv PATH     write the table as CSV (one line per setting and shape)\n"
               "  --detail PATH  write the outcome at every speed as CSV\n"
               "  --quick        smoke run: 3 shapes, 4 phases, 2 angles, speeds a factor 2 apart\n");
}

static int parse_options(int argc, char **argv, options *o)
{
    *o = (options){0};
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc)
            o->csv_path = argv[++i];
        else if (strcmp(argv[i], "--detail") == 0 && i + 1 < argc)
            o->detail_path = argv[++i];
        else if (strcmp(argv[i], "--quick") == 0)
            o->quick = 1;
        else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            exit(0);
        } else {
            usage(stderr);
            return -1;
        }
    }
    return 0;
}

static void check(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "bench_tunnel: %s: %s: %s\n", what, pp_status_name(st), pp_last_error());
        exit(1);
    }
}

/* Half the extent along the wall normal (x) of a w×h box at angle a, px; a spinning box takes
 * its half diagonal, so no angle it reaches starts inside the wall. */
static double half_extent_x(const shape *sh, double a)
{
    if (sh->spin != 0)
        return 0.5 * hypot(sh->w, sh->h);
    return 0.5 * sh->w * fabs(cos(a)) + 0.5 * sh->h * fabs(sin(a));
}

/* Where the body's centre is relative to the wall's faces. A body on the near side still heading
 * for the wall at over half its speed never reached it: the trial was too short, a bug here. */
static enum outcome classify(pp_world w, pp_body b, pp_body wall, double vx)
{
    pp_vec2 p, pw, v;
    check(pp_body_get_position(w, b, &p), "pp_body_get_position");
    check(pp_body_get_position(w, wall, &pw), "pp_body_get_position (wall)");
    check(pp_body_get_velocity(w, b, &v, NULL), "pp_body_get_velocity");
    const double rel = (double)p.x - pw.x;
    if (rel > 0.5 * WALL_T)
        return OUT_TUNNEL;
    if (rel >= -0.5 * WALL_T)
        return OUT_STUCK;
    if (v.x > 0.5 * vx) {
        fprintf(stderr, "bench_tunnel: a body %.1f px before the wall still moves at %.0f of %.0f px/s\n", -rel,
                (double)v.x, vx);
        exit(1);
    }
    return OUT_CLEAR;
}

static uint8_t wall_mask[WALL_T * WALL_H], body_mask[16 * 16];

/* A world of the setting with only the wall in it. */
static pp_world make_world(const config *c, pp_body *wall_b)
{
    if (!wall_mask[0]) {
        memset(wall_mask, 1, sizeof wall_mask);
        memset(body_mask, 1, sizeof body_mask);
    }
    pp_world_def wd = pp_world_def_default();
    wd.gravity = (pp_vec2){0, 0};
    wd.substeps = c->substeps;
    wd.continuous = c->continuous;
    wd.backend = PP_BACKEND_CPU;
    pp_world w;
    check(pp_world_create(&wd, &w), "pp_world_create");
    pp_body_def wall = pp_body_def_default();
    wall.type = c->dynamic_wall ? PP_BODY_DYNAMIC : PP_BODY_STATIC;
    wall.position = (pp_vec2){(float)WALL_X, (float)WALL_Y};
    wall.width = WALL_T, wall.height = WALL_H, wall.mask = wall_mask;
    wall.density = 1000.0f; /* dynamic wall: ~10^5 times the heaviest fast body */
    wall.fixed_rotation = 1;
    check(pp_body_create(w, &wall, wall_b), "pp_body_create (wall)");
    return w;
}

static pp_body make_body(pp_world w, const config *c, const shape *sh, double x, double y, double angle, double vx,
                         double vy)
{
    pp_body_def bd = pp_body_def_default();
    bd.width = sh->w, bd.height = sh->h, bd.mask = body_mask;
    bd.position = (pp_vec2){(float)x, (float)y};
    bd.angle = (float)angle;
    bd.linear_velocity = (pp_vec2){(float)vx, (float)vy};
    bd.angular_velocity = sh->spin;
    bd.restitution = c->restitution;
    bd.bullet = c->bullet;
    pp_body b;
    check(pp_body_create(w, &bd, &b), "pp_body_create (fast body)");
    return b;
}

/* One fast body thrown at the wall: speed px/s, approach `theta` rad from the wall normal, and a
 * start such that its leading side would touch the wall (1 + phase) steps in. Steps until it has
 * passed or stopped; the outcome is where its centre ends relative to the wall. `us` (if not
 * NULL) receives the mean µs per step. */
static enum outcome throw_body(const config *c, const shape *sh, double speed, double theta, double phase,
                               long *swept, double *us)
{
    pp_body wall_b;
    const pp_world w = make_world(c, &wall_b);
    const double angle = sh->along ? theta : sh->angle;
    const double hx = half_extent_x(sh, angle), vx = speed * cos(theta), vy = speed * sin(theta);
    const double t_touch = (1.0 + phase) * DT;
    const double t_centre = t_touch + (0.5 * WALL_T + hx) / vx; /* centre on the wall's mid-plane */
    const pp_body b = make_body(w, c, sh, WALL_X - 0.5 * WALL_T - hx - vx * t_touch, WALL_Y - vy * t_centre, angle,
                                vx, vy);

    /* Two steps to reach the wall, enough to cross it and clear it, and three to settle; a body
     * still inside the wall then gets up to SETTLE_STEPS more to be pushed out. */
    const double cross = WALL_T + 2 * hx + 2;
    int steps = 2 + (int)ceil(cross / (vx * DT)) + 3;
    steps = steps > MAX_STEPS ? MAX_STEPS : steps;
    double t_us = 0;
    enum outcome out = OUT_STUCK;
    for (int s = 0; s < steps + SETTLE_STEPS && out == OUT_STUCK; s++) {
        const double t0 = (1e3 * bench_clock_ms());
        check(pp_world_step(w, DT), "pp_world_step");
        if (s < steps)
            t_us += (1e3 * bench_clock_ms()) - t0;
        pp_step_stats st;
        check(pp_world_get_stats(w, &st), "pp_world_get_stats");
        *swept += st.swept_stops;
        if (s >= steps - 1)
            out = classify(w, b, wall_b, vx);
    }
    if (us)
        *us = t_us / steps;
    check(pp_world_destroy(w), "pp_world_destroy");
    return out;
}

/* A fast body sliding past the wall, GRAZE_GAP px from its face, parallel to it: every substep's
 * swept bounds meet the wall's, so the sweep tests the whole path and finds no hit (except for the
 * spinning box, kept a half diagonal away). Mean µs per step. */
static double graze(const config *c, const shape *sh, double speed)
{
    pp_body wall_b;
    const pp_world w = make_world(c, &wall_b);
    const double angle = sh->along ? PI / 2 : sh->angle, hx = half_extent_x(sh, angle);
    (void)make_body(w, c, sh, WALL_X - 0.5 * WALL_T - GRAZE_GAP - hx, WALL_Y - 0.45 * WALL_H, angle, 0, speed);
    const int steps = 3; /* up to 0.9 WALL_H at TIME_FAST: still beside the wall */
    double t_us = 0;
    for (int s = 0; s < steps; s++) {
        const double t0 = (1e3 * bench_clock_ms());
        check(pp_world_step(w, DT), "pp_world_step");
        t_us += (1e3 * bench_clock_ms()) - t0;
    }
    check(pp_world_destroy(w), "pp_world_destroy");
    return t_us / steps;
}

/* µs per step of a head-on hit (graze: a slide past the wall) at `speed`: the minimum over
 * TIMING_RUNS runs of the median of TIMING_TRIALS fresh worlds, after a warm-up. */
static double time_step(const config *c, const shape *sh, double speed, int grazing)
{
    double us[TIMING_TRIALS], best = -1;
    long swept = 0;
    for (int r = -1; r < TIMING_RUNS; r++) {
        for (int k = 0; k < TIMING_TRIALS; k++) {
            if (grazing)
                us[k] = graze(c, sh, speed);
            else
                (void)throw_body(c, sh, speed, 0.0, 0.37, &swept, &us[k]);
        }
        qsort(us, TIMING_TRIALS, sizeof *us, bench_cmp_double);
        if (r >= 0 && (best < 0 || us[TIMING_TRIALS / 2] < best))
            best = us[TIMING_TRIALS / 2];
    }
    return best;
}

static void print_machine(const options *o, int nspeeds, const double *speeds, int nphase, int nangle,
                          const double *angles)
{
    char model[256];
    bench_cpu_model(model, sizeof model);
    const uint32_t v = pp_version();
    printf("PhysPix %u.%u.%u tunnelling benchmark%s\n", v / 10000, v / 100 % 100, v % 100, o->quick ? " (--quick)" : "");
    printf("machine: %ld cpus online, %s\n", sysconf(_SC_NPROCESSORS_ONLN), model);
    printf("dt 1/60 s, gravity 0, CPU backend, friction 0.6; wall %d px thick, %d px long, static unless 'dyn wall'\n"
           "(density 1000, fixed rotation: ~1e5 times the fast body's mass)\n",
           WALL_T, WALL_H);
    printf("speeds: %d from %.0f to %.0f px/s; per speed %d start phases x %d angles from the normal (", nspeeds,
           speeds[0], speeds[nspeeds - 1], nphase, nangle);
    for (int i = 0; i < nangle; i++)
        printf("%s%.0f", i ? ", " : "", angles[i] * 180 / PI);
    printf(" deg)\n");
    printf("tunnel: the centre ends beyond the wall's far face; stuck: it ends inside the wall after %d more\n"
           "steps to be pushed out; safe: largest tested speed at and below which no trial tunnels (\"all\":\n"
           "none up to the top speed; \"none\": the lowest tunnels)\n"
           "clean: the same with no trial stuck either\n"
           "hit, graze: us per pp_world_step of that shape thrown head-on at the wall (approach, hit, after), and\n"
           "sliding along it %.2f px from its face; minimum over %d runs of the median of %d\n\n",
           SETTLE_STEPS, GRAZE_GAP, TIMING_RUNS, TIMING_TRIALS);
}

static void fmt_speed(char *buf, size_t size, double v, double top)
{
    if (v >= top)
        snprintf(buf, size, "all");
    else if (v <= 0)
        snprintf(buf, size, "none");
    else
        snprintf(buf, size, "%.0f", v);
}

int main(int argc, char **argv)
{
    options opt;
    if (parse_options(argc, argv, &opt) != 0)
        return 2;
    const double speed_lo = 250, speed_hi = 100000, factor = opt.quick ? 2.0 : pow(2.0, 1.0 / 6);
    double speeds[MAX_SPEEDS];
    int nspeeds = 0;
    for (double s = speed_lo; s < speed_hi * 1.0001 && nspeeds < MAX_SPEEDS; s *= factor)
        speeds[nspeeds++] = s;
    if (speeds[nspeeds - 1] < speed_hi * 0.999 && nspeeds < MAX_SPEEDS)
        speeds[nspeeds++] = speed_hi;
    const double all_angles[] = {0, 30 * PI / 180, 60 * PI / 180}, quick_angles[] = {0, 60 * PI / 180};
    const double *angles = opt.quick ? quick_angles : all_angles;
    const int nangle = opt.quick ? 2 : 3, nphase = opt.quick ? 4 : 12, nshape = opt.quick ? NSHAPE_QUICK : NSHAPE;
    /* Start phases spread by the golden ratio, so they are spread within a substep too, for any count. */
    double phases[12];
    for (int k = 0; k < nphase; k++)
        phases[k] = fmod(0.5 + k * 0.6180339887498949, 1.0);
    print_machine(&opt, nspeeds, speeds, nphase, nangle, angles);

    FILE *csv = NULL, *detail = NULL;
    if (opt.csv_path && !(csv = fopen(opt.csv_path, "w")))
        return perror(opt.csv_path), 1;
    if (opt.detail_path && !(detail = fopen(opt.detail_path, "w")))
        return perror(opt.detail_path), 1;
    if (csv)
        fprintf(csv, "setting,continuous,substeps,bullet,wall,restitution,shape,safe_px_s,first_tunnel_px_s,clean_px_s,"
                     "trials,tunnelled,stuck,swept_stops,us_per_step_hit_%.0f,us_per_step_hit_%.0f,us_per_step_graze_%.0f\n",
                TIME_SLOW, TIME_FAST, TIME_FAST);
    if (detail)
        fprintf(detail, "setting,shape,speed_px_s,trials,tunnelled,stuck,swept_stops\n");

    const double t_start = (1e3 * bench_clock_ms());
    static cell cells[NCONFIG][NSHAPE];
    printf("%-23s %-10s %6s %6s %7s %6s %6s %5s %6s %7s %7s %9s\n", "setting", "shape", "bound", "safe", "tunnel@",
           "clean", "tunnel", "stuck", "sweeps", "hit@2k", "hit@50k", "graze@50k");
    for (int ci = 0; ci < NCONFIG; ci++) {
        const config *c = &configs[ci];
        for (int si = 0; si < nshape; si++) {
            const shape *sh = &shapes[si];
            cell *ce = &cells[ci][si];
            int tunnel_seen = 0, stuck_seen = 0;
            ce->safe = ce->clean = speeds[nspeeds - 1];
            for (int vi = 0; vi < nspeeds; vi++) {
                long t = 0, st = 0, n = 0, swept = 0;
                for (int ai = 0; ai < nangle; ai++)
                    for (int k = 0; k < nphase; k++, n++) {
                        const enum outcome out = throw_body(c, sh, speeds[vi], angles[ai], phases[k], &swept, NULL);
                        t += out == OUT_TUNNEL, st += out == OUT_STUCK;
                    }
                if (t && !tunnel_seen) {
                    tunnel_seen = 1;
                    ce->first_fail = speeds[vi];
                    ce->safe = vi ? speeds[vi - 1] : 0;
                }
                if ((t || st) && !stuck_seen) {
                    stuck_seen = 1;
                    ce->clean = vi ? speeds[vi - 1] : 0;
                }
                ce->trials += n, ce->tunnelled += t, ce->stuck += st, ce->swept += swept;
                if (detail)
                    fprintf(detail, "%s,%s,%.1f,%ld,%ld,%ld,%ld\n", c->name, sh->name, speeds[vi], n, t, st, swept);
            }
            ce->us_hit_slow = time_step(c, sh, TIME_SLOW, 0);
            ce->us_hit_fast = time_step(c, sh, TIME_FAST, 0);
            ce->us_graze = time_step(c, sh, TIME_FAST, 1);
            /* Substepping alone: above this head-on speed the first overlap can put the centre past the
             * wall's mid-plane, where the contact pushes it on through. */
            char bound[16] = "-", safe[16], fail[16], clean[16];
            if (sh->spin == 0)
                snprintf(bound, sizeof bound, "%.0f", c->substeps * 0.5 * (WALL_T + sh->w) / DT);
            fmt_speed(safe, sizeof safe, ce->safe, speeds[nspeeds - 1]);
            fmt_speed(clean, sizeof clean, ce->clean, speeds[nspeeds - 1]);
            if (ce->first_fail > 0)
                snprintf(fail, sizeof fail, "%.0f", ce->first_fail);
            else
                snprintf(fail, sizeof fail, "-");
            printf("%-23s %-10s %6s %6s %7s %6s %6ld %5ld %6ld %7.1f %7.1f %9.1f\n", si ? "" : c->name, sh->name, bound, safe,
                   fail, clean, ce->tunnelled, ce->stuck, ce->swept, ce->us_hit_slow, ce->us_hit_fast,
                   ce->us_graze);
            fflush(stdout);
            if (csv)
                fprintf(csv, "%s,%u,%d,%u,%s,%.2f,%s,%.1f,%.1f,%.1f,%ld,%ld,%ld,%ld,%.3f,%.3f,%.3f\n", c->name,
                        c->continuous, c->substeps, c->bullet, c->dynamic_wall ? "dynamic" : "static", c->restitution,
                        sh->name, ce->safe, ce->first_fail, ce->clean, ce->trials, ce->tunnelled, ce->stuck,
                        ce->swept, ce->us_hit_slow, ce->us_hit_fast, ce->us_graze);
        }
    }
    const double wall_s = ((1e3 * bench_clock_ms()) - t_start) * 1e-6;

    printf("\nsafe speed, px/s (no trial tunnels at or below it):\n%-23s", "setting");
    for (int si = 0; si < nshape; si++)
        printf(" %10s", shapes[si].name);
    printf("\n");
    for (int ci = 0; ci < NCONFIG; ci++) {
        printf("%-23s", configs[ci].name);
        for (int si = 0; si < nshape; si++) {
            char safe[16];
            fmt_speed(safe, sizeof safe, cells[ci][si].safe, speeds[nspeeds - 1]);
            printf(" %10s", safe);
        }
        printf("\n");
    }
    printf("\nbound: substeps x (wall + body length along the motion) / 2 / dt: above it a head-on body's\n"
           "first overlap with the wall can put its centre past the wall's mid-plane, and the contact then\n"
           "pushes it on through (at twice it, it can skip the wall between two checks). wall time %.1f s\n",
           wall_s);
    if (csv && fclose(csv) != 0)
        return perror(opt.csv_path), 1;
    if (detail && fclose(detail) != 0)
        return perror(opt.detail_path), 1;
    if (csv)
        printf("wrote %s\n", opt.csv_path);
    if (detail)
        printf("wrote %s\n", opt.detail_path);
    return 0;
}
