/* The measurement, the same for every engine: step a scene frame by frame, read the poses, and decide
 * whether a stack stands (no body moves over a quarter of its size from its settled pose), how fast a disc
 * rolls or a box slides (a parabola fitted to the distance along the slope), how high a ball rebounds and
 * where a shot box ends. */
#include "stability.h"

#include "../machine.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

#define FALL_FRACTION 0.25  /* of a body's size: moved farther, it fell */
#define COLLAPSE_TURN 0.25  /* rad: a body turned this far while settling came apart */
#define AFTER_FALL_S 1.0    /* a fallen stack runs this much longer, then stops */
#define FIT_T0 0.5          /* s: the acceleration fit's window, after the start-up contacts settle */
#define FIT_T1 1.5
#define STICK_PX 1.0        /* ramp: slid less than this, it sticks */

const char *stab_verdict_name(stab_verdict v)
{
    static const char *const names[] = {"stands", "FALLS",  "NaN",      "error",   "rolls", "bounces",
                                        "no bounce", "sticks", "slides", "stopped", "STUCK", "TUNNELLED",
                                        "COLLAPSES"};
    return (unsigned)v < sizeof names / sizeof names[0] ? names[v] : "?";
}

double stab_max_displacement(const stab_scene *s, const stab_pose *ref, const stab_pose *now, double *worst)
{
    double largest = 0;
    *worst = 0;
    for (int i = 0; i < s->count; i++) {
        if (s->bodies[i].is_static)
            continue;
        const double d = hypot(now[i].x - ref[i].x, now[i].y - ref[i].y);
        largest = fmax(largest, d);
        *worst = fmax(*worst, d / stab_body_size(&s->bodies[i]));
    }
    return largest;
}

/* The engine's world of a scene, its poses now, and the frame times. */
typedef struct run {
    const stab_engine *e;
    const stab_scene *s;
    void *world;
    stab_pose *pose;
    double *ms;
    int frames, capacity;
} run;

/* One frame: step (timed), read every pose. 0, 1 when a pose is not finite, -1 when the engine failed. */
static int frame(run *r, int timed)
{
    const double t0 = bench_clock_ms();
    if (r->e->step(r->world) != 0)
        return -1;
    const double ms = bench_clock_ms() - t0;
    if (timed && r->frames < r->capacity)
        r->ms[r->frames++] = ms;
    for (int i = 0; i < r->s->count; i++) {
        r->e->pose(r->world, i, &r->pose[i]);
        if (!isfinite(r->pose[i].x) || !isfinite(r->pose[i].y) || !isfinite(r->pose[i].angle))
            return 1;
    }
    return 0;
}

static stab_verdict failed(int rc)
{
    return rc < 0 ? STAB_ERROR : STAB_NAN;
}

/* Whether a stack came apart while settling: a body moved over a quarter of its size sideways from where it
 * was placed, or turned COLLAPSE_TURN. Its sink is not counted: every contact of a column settles to the
 * engine's resting depth (a 20-box PhysPix tower's top sinks 15 px), and crush is measured on its own. A scene
 * with max_move: a body moved that far from where it was placed. */
static bool came_apart(const stab_scene *s, const stab_pose *placed, const stab_pose *now)
{
    if (s->max_move > 0) {
        double worst;
        return stab_max_displacement(s, placed, now, &worst) > s->max_move;
    }
    for (int i = 0; i < s->count; i++)
        if (!s->bodies[i].is_static && (fabs(now[i].x - placed[i].x) > FALL_FRACTION * stab_body_size(&s->bodies[i]) ||
                                        fabs(now[i].angle - placed[i].angle) > COLLAPSE_TURN))
            return true;
    return false;
}

/* Settle, take the reference pose, then watch: drift, the fall, the tracked box's crush. A stack that came
 * apart while settling did not stand, whatever its heap does later: its drift is how far it came apart, and
 * it runs 1 s more for ms/step only. A scene with max_move is measured from where it was built, settle
 * included, and watched at most its `seconds`. */
static void run_stack(run *r, const stab_options *o, stab_result *out)
{
    const stab_scene *s = r->s;
    const bool from_built = s->max_move > 0;
    const double run_s = o->run_s > 0 ? o->run_s : 60.0;
    const int settle = (int)lround((o->settle_s > 0 ? o->settle_s : 1.0) / STAB_DT);
    const int watch = (int)lround((from_built && s->seconds > 0 ? fmin(run_s, s->seconds) : run_s) / STAB_DT);
    stab_pose *ref = malloc((size_t)s->count * sizeof *ref), *placed = malloc((size_t)s->count * sizeof *placed);
    int rc = ref && placed ? 0 : -1, stop = watch;
    for (int i = 0; rc == 0 && i < s->count; i++)
        r->e->pose(r->world, i, &placed[i]);
    out->verdict = STAB_STANDS;
    out->drift = 0;
    for (int f = 0; f < settle && rc == 0; f++) {
        rc = frame(r, 0);
        double worst;
        if (rc == 0 && from_built && out->verdict == STAB_STANDS)
            out->drift = fmax(out->drift, stab_max_displacement(s, placed, r->pose, &worst));
        if (rc == 0 && out->verdict == STAB_STANDS && came_apart(s, placed, r->pose)) {
            out->verdict = STAB_COLLAPSES;
            out->fall_s = (f + 1) * STAB_DT;
            stop = (int)lround(AFTER_FALL_S / STAB_DT); /* for ms/step */
        }
    }
    if (rc == 0) {
        for (int i = 0; i < s->count; i++)
            ref[i] = from_built ? placed[i] : r->pose[i];
        double worst;
        if (out->verdict == STAB_COLLAPSES)
            out->drift = stab_max_displacement(s, placed, r->pose, &worst);
        if (s->tracked >= 0)
            out->settle_sink = r->pose[s->tracked].y - s->bodies[s->tracked].y;
    }
    for (int f = 0; f < stop && rc == 0; f++) {
        rc = frame(r, 1);
        if (rc != 0)
            break;
        if (out->verdict == STAB_COLLAPSES)
            continue;
        double worst;
        out->drift = fmax(out->drift, stab_max_displacement(s, ref, r->pose, &worst));
        const bool fell = from_built ? out->drift > s->max_move : worst > FALL_FRACTION;
        if (fell && out->verdict == STAB_STANDS) {
            out->verdict = STAB_FALLS;
            out->fall_s = (f + 1) * STAB_DT;
            stop = f + 1 + (int)lround(AFTER_FALL_S / STAB_DT);
            stop = stop < watch ? stop : watch;
        }
    }
    if (rc != 0)
        out->verdict = failed(rc);
    else if (s->tracked >= 0)
        out->crush = r->pose[s->tracked].y - ref[s->tracked].y;
    free(ref);
    free(placed);
}

/* Distance of the tracked body's origin down the slope from where it started, px. */
static double along_slope(const run *r, const stab_pose *start)
{
    const stab_pose *p = &r->pose[r->s->tracked];
    return (p->x - start->x) * cos(r->s->slope) + (p->y - start->y) * sin(r->s->slope);
}

/* Least-squares parabola through (t, d) over [FIT_T0, FIT_T1]: twice its t² coefficient, px/s². Times are
 * centred on the window's mean so the normal equations stay well conditioned. */
static double fit_acceleration(const double *t, const double *d, int n)
{
    double tm = 0;
    int m = 0;
    for (int i = 0; i < n; i++)
        if (t[i] >= FIT_T0 - 1e-9 && t[i] <= FIT_T1 + 1e-9)
            tm += t[i], m++;
    if (m < 3)
        return NAN;
    tm /= m;
    double s[5] = {0}, y[3] = {0}; /* sums of τ^k and of d·τ^k */
    for (int i = 0; i < n; i++) {
        if (t[i] < FIT_T0 - 1e-9 || t[i] > FIT_T1 + 1e-9)
            continue;
        const double tau = t[i] - tm;
        double p = 1;
        for (int k = 0; k < 5; k++, p *= tau) {
            s[k] += p;
            if (k < 3)
                y[k] += d[i] * p;
        }
    }
    /* Cramer's rule on [[s0 s1 s2] [s1 s2 s3] [s2 s3 s4]] · c = y, for c2. */
    const double det = s[0] * (s[2] * s[4] - s[3] * s[3]) - s[1] * (s[1] * s[4] - s[3] * s[2]) +
                       s[2] * (s[1] * s[3] - s[2] * s[2]);
    const double det2 = s[0] * (s[2] * y[2] - y[1] * s[3]) - s[1] * (s[1] * y[2] - y[1] * s[2]) +
                        y[0] * (s[1] * s[3] - s[2] * s[2]);
    return 2 * det2 / det;
}

/* Roll and slide: the distance down the slope at every frame; a parabola's acceleration, or the slide. */
static void run_slope(run *r, stab_result *out)
{
    const stab_scene *s = r->s;
    const stab_body *b = &s->bodies[s->tracked];
    const int n = (int)lround(s->seconds / STAB_DT);
    double *t = malloc((size_t)n * sizeof *t), *d = malloc((size_t)n * sizeof *d);
    const stab_pose start = {b->x, b->y, b->angle};
    int rc = t && d ? 0 : -1, f = 0;
    for (; f < n && rc == 0; f++) {
        rc = frame(r, 1);
        t[f] = (f + 1) * STAB_DT;
        d[f] = rc == 0 ? along_slope(r, &start) : NAN;
    }
    const double g_sin = STAB_GRAVITY * sin(s->slope);
    if (rc != 0) {
        out->verdict = failed(rc);
    } else if (s->kind == STAB_ROLL) {
        double m, inertia;
        r->e->mass(r->world, s->tracked, &m, &inertia);
        out->verdict = STAB_ROLLS;
        out->value = fit_acceleration(t, d, n);
        out->ref = 2.0 / 3.0 * g_sin;
        out->ref2 = g_sin / (1 + inertia / (m * b->radius * b->radius));
    } else if (tan(s->slope) < s->mu) {
        out->value = fabs(d[n - 1]);
        out->ref = 0;
        out->verdict = out->value < STICK_PX ? STAB_STICKS : STAB_SLIDES;
    } else {
        out->value = fit_acceleration(t, d, n);
        out->ref = g_sin - s->mu * STAB_GRAVITY * cos(s->slope);
        out->verdict = fabs(d[n - 1]) < STICK_PX ? STAB_STICKS : STAB_SLIDES;
    }
    free(t);
    free(d);
}

/* The ball falls, touches down (its lowest point), and rises to the apex before it falls again; so `bounces`
 * times, and the apex farthest from e²·drop is the value. */
static void run_bounce(run *r, stab_result *out)
{
    const stab_scene *s = r->s;
    const stab_body *b = &s->bodies[s->tracked];
    const int n = (int)lround(s->seconds / STAB_DT), want = s->bounces > 1 ? s->bounces : 1;
    const double bottom_of = s->ground_top - b->radius; /* centre height for a bottom on the ground */
    const double ref = b->restitution * b->restitution * s->drop;
    double prev = b->y, lowest = -INFINITY, apex = INFINITY, worst = NAN;
    int rc = 0, rising = 0, seen = 0, bounced = 1;
    for (int f = 0; f < n && rc == 0 && seen < want; f++) {
        rc = frame(r, 1);
        const double y = r->pose[s->tracked].y;
        if (rc != 0)
            break;
        if (rising && y > apex + 0.5) { /* falling again: the apex is behind */
            const double h = bottom_of - apex;
            worst = seen == 0 || fabs(h - ref) > fabs(worst - ref) ? h : worst;
            bounced &= lowest - apex > 1.0;
            seen++, rising = 0, lowest = -INFINITY;
        }
        if (!rising && y < prev && lowest > -INFINITY)
            rising = 1;
        lowest = rising ? lowest : fmax(lowest, y);
        apex = rising ? fmin(apex, y) : y;
        prev = y;
    }
    if (rc != 0) {
        out->verdict = failed(rc);
        return;
    }
    /* Still rising at the end: that apex so far (one bounce), or too few bounces (several). */
    out->value = seen > 0 ? worst : rising ? bottom_of - apex : 0;
    out->ref = ref;
    const bool all = seen > 0 ? bounced && seen == want : want == 1 && rising && lowest - apex > 1.0;
    out->verdict = all ? STAB_BOUNCES : STAB_NO_BOUNCE;
}

/* The box flies, hits the wall or not, and comes to rest; its centre says on which side. */
static void run_shot(run *r, stab_result *out)
{
    const stab_scene *s = r->s;
    const int n = (int)lround(s->seconds / STAB_DT);
    int rc = 0;
    for (int f = 0; f < n && rc == 0; f++)
        rc = frame(r, 1);
    if (rc != 0) {
        out->verdict = failed(rc);
        return;
    }
    const double x = r->pose[s->tracked].x;
    out->value = x + 0.5 * s->bodies[s->tracked].w - s->wall_x0;
    out->ref = 0;
    out->verdict = x > s->wall_x1 ? STAB_TUNNELLED : x >= s->wall_x0 ? STAB_STUCK : STAB_STOPPED;
}

int stab_run(const stab_engine *e, const stab_scene *s, const stab_options *o, stab_result *out)
{
    const stab_options defaults = {0};
    o = o ? o : &defaults;
    *out = (stab_result){.verdict = STAB_ERROR, .drift = NAN, .fall_s = NAN, .crush = NAN, .settle_sink = NAN,
                         .value = NAN, .ref = NAN, .err_pct = NAN, .ref2 = NAN, .err2_pct = NAN, .ms_median = NAN};
    const double watch = s->kind == STAB_STACK ? (o->run_s > 0 ? o->run_s : 60.0) : s->seconds;
    run r = {.e = e, .s = s, .capacity = (int)lround(watch / STAB_DT) + 1};
    r.pose = calloc((size_t)s->count, sizeof *r.pose);
    r.ms = malloc((size_t)r.capacity * sizeof *r.ms);
    r.world = r.pose && r.ms ? e->create(e, s) : NULL;
    if (!r.world) {
        free(r.pose);
        free(r.ms);
        return -1;
    }
    if (s->kind == STAB_STACK)
        run_stack(&r, o, out);
    else if (s->kind == STAB_ROLL || s->kind == STAB_RAMP)
        run_slope(&r, out);
    else if (s->kind == STAB_BOUNCE)
        run_bounce(&r, out);
    else
        run_shot(&r, out);
    e->destroy(r.world);
    if (out->ref != 0 && isfinite(out->ref))
        out->err_pct = 100 * (out->value - out->ref) / out->ref;
    if (isfinite(out->ref2))
        out->err2_pct = 100 * (out->value - out->ref2) / out->ref2;
    out->frames = r.frames;
    if (r.frames > 0) {
        qsort(r.ms, (size_t)r.frames, sizeof *r.ms, bench_cmp_double);
        out->ms_median = r.frames % 2 ? r.ms[r.frames / 2] : 0.5 * (r.ms[r.frames / 2 - 1] + r.ms[r.frames / 2]);
    }
    free(r.pose);
    free(r.ms);
    return 0;
}
