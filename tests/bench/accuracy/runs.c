/* The accuracy benchmark's measurements, through the public API only: analytic collisions,
 * stacks stepped with sleep off, a timing scene, an elastic bounce and free collisions. */
#include "accuracy.h"
#include "machine.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int check(pp_status st, const char *what)
{
    if (st == PP_OK)
        return 0;
    fprintf(stderr, "bench_accuracy: %s failed: %s: %s\n", what, pp_status_name(st), pp_last_error());
    return -1;
}

double acc_quantile(double *v, int n, double q)
{
    if (n <= 0)
        return NAN;
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    int k = (int)ceil(q * n) - 1;
    k = k < 0 ? 0 : k >= n ? n - 1 : k;
    return v[k];
}

static double median_of(double *v, int n)
{
    if (n <= 0)
        return NAN;
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int acc_measure_collide(const pp_world_def *def, acc_metrics *m)
{
    static analytic_set set;
    static double normal_err[2 * ANALYTIC_MAX_PAIRS * ANALYTIC_MAX_CONTACTS], depth_err[ANALYTIC_MAX_PAIRS];
    pp_world_def d = *def;
    d.gravity = (pp_vec2){0, 0};
    m->collide_ok = 1;
    for (int f = 0; f < ANALYTIC_FAMILY_COUNT; f++) {
        if (check(analytic_run((analytic_family)f, &d, &set), analytic_family_name((analytic_family)f)) != 0)
            return -1;
        int nn = 0;
        for (int i = 0; i < set.n; i++) {
            const analytic_pair *p = &set.pair[i];
            if (p->status != PP_OK || p->count < 1) {
                /* A missed contact counts as the worst answer: a reversed normal and no depth. */
                m->collide_ok = 0;
                normal_err[nn++] = 180.0;
                depth_err[i] = p->depth;
                continue;
            }
            depth_err[i] = analytic_errors(p, normal_err, &nn);
        }
        m->normal_med[f] = acc_quantile(normal_err, nn, 0.5);
        m->normal_p95[f] = acc_quantile(normal_err, nn, 0.95);
        m->depth_med[f] = acc_quantile(depth_err, set.n, 0.5);
    }
    return 0;
}

/* A world from def with the scene's boxes as solid masks; bodies[i] is box i. */
static int build_scene(const bench_scene *scene, const pp_world_def *def, pp_world *w, pp_body *bodies)
{
    if (check(pp_world_create(def, w), "pp_world_create") != 0)
        return -1;
    size_t largest = 1;
    for (int i = 0; i < scene->count; i++) {
        size_t area = (size_t)scene->boxes[i].w * (size_t)scene->boxes[i].h;
        largest = area > largest ? area : largest;
    }
    uint8_t *mask = malloc(largest);
    if (!mask) {
        fprintf(stderr, "bench_accuracy: out of memory for the masks\n");
        return -1;
    }
    memset(mask, 1, largest);
    int rc = 0;
    for (int i = 0; i < scene->count && rc == 0; i++) {
        const bench_box *box = &scene->boxes[i];
        pp_body_def bd = pp_body_def_default();
        bd.type = box->is_static ? PP_BODY_STATIC : PP_BODY_DYNAMIC;
        bd.position = (pp_vec2){(float)box->x, (float)box->y};
        bd.angle = (float)box->angle;
        bd.width = box->w;
        bd.height = box->h;
        bd.mask = mask;
        rc = check(pp_body_create(*w, &bd, &bodies[i]), "pp_body_create");
    }
    free(mask);
    return rc;
}

/* Reads every dynamic box's pose; 0, or 1 when one is not finite. */
static int read_poses(pp_world w, const bench_scene *scene, const pp_body *bodies, double *x, double *y, double *a)
{
    for (int i = 0; i < scene->count; i++) {
        if (scene->boxes[i].is_static)
            continue;
        pp_vec2 p;
        float ang;
        if (pp_body_get_position(w, bodies[i], &p) != PP_OK || pp_body_get_angle(w, bodies[i], &ang) != PP_OK)
            return 1;
        x[i] = p.x, y[i] = p.y, a[i] = ang;
        if (!isfinite(p.x) || !isfinite(p.y) || !isfinite(ang))
            return 1;
    }
    return 0;
}

int acc_measure_stack(const bench_scene *scene, const pp_world_def *def, const acc_plan *plan, acc_stack *out,
                      int *backend_ran)
{
    const int settle = (int)lround(plan->settle_s / ACC_DT), total = settle + (int)lround(plan->horizon_s / ACC_DT);
    const int contact_from = total - (int)lround(plan->contact_s / ACC_DT);
    const int n = scene->count, cap = 8 * n;
    pp_world_def d = *def;
    d.allow_sleep = 0; /* sleeping would hide the solver's drift */
    *out = (acc_stack){0};

    pp_world w = {0};
    pp_body *bodies = calloc((size_t)n, sizeof *bodies);
    double *x = calloc((size_t)n * 5, sizeof *x), *step_ms = malloc((size_t)total * sizeof *step_ms);
    pp_contact *contacts = malloc((size_t)cap * sizeof *contacts);
    int rc = bodies && x && step_ms && contacts ? 0 : -1;
    if (rc)
        fprintf(stderr, "bench_accuracy: out of memory for %s\n", scene->name);
    double *y = x + n, *a = x + 2 * n, *sx = x + 3 * n, *sy = x + 4 * n;
    if (rc == 0)
        rc = build_scene(scene, &d, &w, bodies);

    const double t_start = bench_now_ms();
    double contacts_sum = 0;
    int s = 0;
    pp_step_stats stats = {0};
    for (; s < total && rc == 0; s++) {
        if (bench_now_ms() - t_start > plan->budget_s * 1e3 && s > 0)
            break; /* the exact solver on a big island: too slow for the whole horizon */
        const double t0 = bench_now_ms();
        pp_status st = pp_world_step(w, (float)ACC_DT);
        step_ms[s] = bench_now_ms() - t0;
        if ((rc = check(st, "pp_world_step")) || (rc = check(pp_world_get_stats(w, &stats), "pp_world_get_stats")))
            break;
        contacts_sum += stats.contacts;
        if ((out->nan = read_poses(w, scene, bodies, x, y, a)))
            break;
        if (s + 1 == settle) {
            memcpy(sx, x, (size_t)n * sizeof *x);
            memcpy(sy, y, (size_t)n * sizeof *x);
            for (int i = 0; i < n; i++) {
                if (scene->boxes[i].is_static)
                    continue;
                out->settle_shift = fmax(out->settle_shift, fabs(x[i] - scene->boxes[i].x));
                out->sag = fmax(out->sag, y[i] - scene->boxes[i].y);
            }
        } else if (s + 1 > settle) {
            for (int i = 0; i < n; i++)
                if (!scene->boxes[i].is_static)
                    out->drift = fmax(out->drift, hypot(x[i] - sx[i], y[i] - sy[i]));
        }
        if (s >= contact_from) {
            int32_t count = 0;
            if ((rc = check(pp_world_get_contacts(w, contacts, cap, &count), "pp_world_get_contacts")))
                break;
            for (int k = 0; k < count && k < cap; k++) {
                out->pen_sum += contacts[k].depth;
                out->pen_max = fmax(out->pen_max, contacts[k].depth);
                out->pen_count++;
            }
        }
    }
    if (s < settle)
        out->settle_shift = out->sag = out->drift = NAN; /* never settled: nothing measured */
    out->complete = rc == 0 && (out->nan || s == total); /* a diverged run is a full answer: it failed */
    out->sim_s = s * ACC_DT;
    /* The fastest of six blocks' medians: other processes slowing a stretch of the run do not count
     * (as tests/bench/bench.c keeps the minimum over runs of the median). */
    const int block = total / 6;
    out->ms_median = median_of(step_ms, s < block ? s : block);
    for (int b = 1; (b + 1) * block <= s; b++)
        out->ms_median = fmin(out->ms_median, median_of(step_ms + b * block, block));
    out->contacts_mean = s > 0 ? contacts_sum / s : 0;
    if (backend_ran)
        *backend_ran = (int)stats.backend;
    if (w.id && check(pp_world_destroy(w), "pp_world_destroy") != 0)
        rc = -1;
    free(bodies);
    free(x);
    free(step_ms);
    free(contacts);
    return rc;
}

int acc_measure_timing(const bench_scene *scene, const pp_world_def *def, double budget_s, double *ms_median,
                       int *steps_done)
{
    pp_world_def d = *def;
    d.allow_sleep = 0;
    pp_world w = {0};
    pp_body *bodies = calloc((size_t)scene->count, sizeof *bodies);
    double *step_ms = malloc((size_t)scene->steps * sizeof *step_ms);
    int rc = bodies && step_ms ? build_scene(scene, &d, &w, bodies) : -1;
    int s = 0;
    const double t_start = bench_now_ms();
    for (; s < scene->steps && rc == 0; s++) {
        if (bench_now_ms() - t_start > budget_s * 1e3 && s > 0)
            break;
        const double t0 = bench_now_ms();
        pp_status st = pp_world_step(w, (float)ACC_DT);
        step_ms[s] = bench_now_ms() - t0;
        rc = check(st, "pp_world_step");
    }
    *ms_median = median_of(step_ms, s);
    *steps_done = s;
    if (w.id && check(pp_world_destroy(w), "pp_world_destroy") != 0)
        rc = -1;
    free(bodies);
    free(step_ms);
    return rc;
}

int acc_scene_tower(bench_scene *out, int steps)
{
    enum { BOXES = 10 };
    const double ground_top = 400.0, centre_x = 320.0;
    *out = (bench_scene){.name = "tower", .steps = steps, .ground_top = ground_top};
    if (!(out->boxes = calloc(1 + BOXES, sizeof *out->boxes)))
        return -1;
    out->boxes[out->count++] = (bench_box){.x = centre_x, .y = ground_top + 16.0, .w = 640, .h = 32, .is_static = 1};
    /* An aligned column, each box resting exactly on the one below (no overlap at t = 0). */
    for (int i = 0; i < BOXES; i++) {
        double y = ground_top - ACC_SIDE * 0.5 - (double)(i * ACC_SIDE);
        out->boxes[out->count++] = (bench_box){.x = centre_x, .y = y, .w = ACC_SIDE, .h = ACC_SIDE};
        out->dynamic_count++;
    }
    out->tracked = out->count - 1;
    return 0;
}

/* A body from a def and a solid rectangle or (r > 0) a disc of radius r, pixels in by their centres. */
static int add_body(pp_world w, pp_body_def bd, int width, int height, int r, pp_body *out)
{
    if (r > 0)
        width = height = 2 * r;
    uint8_t *m = calloc((size_t)width * (size_t)height, 1);
    if (!m)
        return -1;
    for (int j = 0; j < height; j++)
        for (int i = 0; i < width; i++) {
            double dx = i + 0.5 - r, dy = j + 0.5 - r;
            m[j * width + i] = r <= 0 || dx * dx + dy * dy <= (double)r * r;
        }
    bd.width = width;
    bd.height = height;
    bd.mask = m;
    int rc = check(pp_body_create(w, &bd, out), "pp_body_create");
    free(m);
    return rc;
}

static pp_body_def body_at(pp_body_type type, double x, double y, double angle)
{
    pp_body_def bd = pp_body_def_default();
    bd.type = type;
    bd.position = (pp_vec2){(float)x, (float)y};
    bd.angle = (float)angle;
    return bd;
}

/* Kinetic plus potential energy of a body, with potential zero at y_rest (gravity points to +y). */
static int body_energy(pp_world w, pp_body b, double g, double y_rest, double *e)
{
    float mass, inertia, omega;
    pp_vec2 p, v;
    if (check(pp_body_get_mass(w, b, &mass, NULL, &inertia), "pp_body_get_mass") ||
        check(pp_body_get_position(w, b, &p), "pp_body_get_position") ||
        check(pp_body_get_velocity(w, b, &v, &omega), "pp_body_get_velocity"))
        return -1;
    *e = 0.5 * mass * ((double)v.x * v.x + (double)v.y * v.y) + 0.5 * inertia * (double)omega * omega +
         mass * g * (y_rest - p.y);
    return 0;
}

int acc_measure_bounce(const pp_world_def *def, acc_metrics *m)
{
    enum { R = 16 };
    const double top = 500.0, drop = 200.0, y_rest = top - R, max_s = 40.0;
    pp_world_def d = *def;
    d.allow_sleep = 0;
    d.bounce_threshold = 0; /* every approach bounces */
    pp_world w;
    if (check(pp_world_create(&d, &w), "pp_world_create"))
        return -1;
    /* The ground is wide: a bounce that kicks the ball sideways must not roll it off the edge. */
    pp_body_def gd = body_at(PP_BODY_STATIC, 2000, top + 20, 0), bd = body_at(PP_BODY_DYNAMIC, 2000, y_rest - drop, 0);
    gd.restitution = bd.restitution = 1.0f;
    pp_body ground, ball;
    int rc = add_body(w, gd, 4000, 40, 0, &ground) || add_body(w, bd, 0, 0, R, &ball) ? -1 : 0;
    double e0 = 0, e = 0;
    if (rc == 0)
        rc = body_energy(w, ball, d.gravity.y, y_rest, &e0);

    /* A bounce is the fall turning into a rise; the apex after it is the rise turning into a fall,
     * where the energy is read: the integrator's error in flight cancels there. */
    m->bounces = 0;
    m->energy_pct = m->energy_final_pct = m->bounce_side_speed = 0;
    int rising = 0, apexes = 0;
    for (int s = 0; rc == 0 && apexes < ACC_BOUNCES && s * ACC_DT < max_s; s++) {
        pp_vec2 v;
        if ((rc = check(pp_world_step(w, (float)ACC_DT), "pp_world_step")) ||
            (rc = check(pp_body_get_velocity(w, ball, &v, NULL), "pp_body_get_velocity")))
            break;
        if (!rising && v.y < 0) {
            rising = 1;
            m->bounces++;
        } else if (rising && v.y >= 0) {
            rising = 0;
            if ((rc = body_energy(w, ball, d.gravity.y, y_rest, &e)))
                break;
            apexes++;
            m->bounce_side_speed = fmax(m->bounce_side_speed, fabs(v.x));
            m->energy_final_pct = 100.0 * (e - e0) / e0;
            m->energy_pct = fmax(m->energy_pct, fabs(m->energy_final_pct));
        }
    }
    /* A ball that came to rest (or left) before its last bounce is measured where it ended. */
    if (rc == 0 && apexes < ACC_BOUNCES && (rc = body_energy(w, ball, d.gravity.y, y_rest, &e)) == 0) {
        m->energy_final_pct = 100.0 * (e - e0) / e0;
        m->energy_pct = fmax(m->energy_pct, fabs(m->energy_final_pct));
    }
    if (!isfinite(m->energy_pct))
        m->energy_pct = INFINITY;
    if (check(pp_world_destroy(w), "pp_world_destroy"))
        rc = -1;
    return rc;
}

/* One free-collision case: bodies with their start velocities, in a world without gravity. */
typedef struct momentum_body {
    double x, y, angle, vx, vy, w; ///< pose (px, rad) and velocity (px/s, rad/s)
    int width, height, r;          ///< a box, or a disc when r > 0
    double density, restitution;
} momentum_body;

/* Total linear momentum of n bodies, and each one's velocity. */
static int momentum_of(pp_world w, const pp_body *b, int n, double p[2], pp_vec2 *v)
{
    p[0] = p[1] = 0;
    for (int i = 0; i < n; i++) {
        float mass;
        if (check(pp_body_get_mass(w, b[i], &mass, NULL, NULL), "pp_body_get_mass") ||
            check(pp_body_get_velocity(w, b[i], &v[i], NULL), "pp_body_get_velocity"))
            return -1;
        p[0] += mass * (double)v[i].x;
        p[1] += mass * (double)v[i].y;
    }
    return 0;
}

/* |p_after − p_before| / |p_before| (%) after one second; *collided: some body's velocity changed
 * by at least a tenth of the fastest start speed, so the case tested a collision at all. */
static int momentum_case(const pp_world_def *def, const momentum_body *mb, int n, double *err_pct, int *collided)
{
    enum { MAX_BODIES = 4, STEPS = 60 };
    pp_world w;
    pp_body b[MAX_BODIES];
    pp_vec2 v0[MAX_BODIES], v1[MAX_BODIES];
    double p0[2], p1[2];
    if (check(pp_world_create(def, &w), "pp_world_create"))
        return -1;
    int rc = 0;
    for (int i = 0; i < n && rc == 0; i++) {
        pp_body_def bd = body_at(PP_BODY_DYNAMIC, mb[i].x, mb[i].y, mb[i].angle);
        bd.linear_velocity = (pp_vec2){(float)mb[i].vx, (float)mb[i].vy};
        bd.angular_velocity = (float)mb[i].w;
        bd.density = (float)mb[i].density;
        bd.restitution = (float)mb[i].restitution;
        rc = add_body(w, bd, mb[i].width, mb[i].height, mb[i].r, &b[i]);
    }
    if (rc == 0)
        rc = momentum_of(w, b, n, p0, v0);
    for (int s = 0; s < STEPS && rc == 0; s++)
        rc = check(pp_world_step(w, (float)ACC_DT), "pp_world_step");
    if (rc == 0)
        rc = momentum_of(w, b, n, p1, v1);
    if (rc == 0) {
        double fastest = 0, changed = 0;
        for (int i = 0; i < n; i++) {
            fastest = fmax(fastest, hypot(v0[i].x, v0[i].y));
            changed = fmax(changed, hypot(v1[i].x - v0[i].x, v1[i].y - v0[i].y));
        }
        *collided = changed >= 0.1 * fastest;
        *err_pct = 100.0 * hypot(p1[0] - p0[0], p1[1] - p0[1]) / hypot(p0[0], p0[1]);
        if (!isfinite(*err_pct))
            *err_pct = INFINITY;
    }
    if (check(pp_world_destroy(w), "pp_world_destroy"))
        rc = -1;
    return rc;
}

int acc_measure_momentum(const pp_world_def *def, acc_metrics *m)
{
    /* Head-on boxes, an oblique hit of two discs (tests/c/test_dynamics.c), and a spinning bar
     * batting two boxes. */
    static const momentum_body head_on[] = {
        {.x = 300, .y = 300, .vx = 300, .width = 20, .height = 20, .density = 1},
        {.x = 400, .y = 300, .width = 30, .height = 30, .density = 1},
    };
    static const momentum_body oblique[] = {
        {.x = 200, .y = 310, .vx = 250, .vy = -20, .r = 16, .density = 1, .restitution = 0.5},
        {.x = 300, .y = 300, .vx = -40, .vy = 10, .r = 20, .density = 2},
    };
    static const momentum_body bar[] = {
        {.x = 200, .y = 300, .angle = 0.2, .vx = 250, .w = 3, .width = 60, .height = 10, .density = 1},
        {.x = 275, .y = 290, .width = 20, .height = 20, .density = 1},
        {.x = 300, .y = 325, .angle = 0.4, .width = 24, .height = 24, .density = 0.5},
    };
    const struct {
        const momentum_body *bodies;
        int n;
    } cases[] = {{head_on, 2}, {oblique, 2}, {bar, 3}};
    pp_world_def d = *def;
    d.gravity = (pp_vec2){0, 0};
    d.allow_sleep = 0;
    m->momentum_pct = 0;
    m->momentum_collided = 1;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double err = 0;
        int collided = 0;
        if (momentum_case(&d, cases[k].bodies, cases[k].n, &err, &collided))
            return -1;
        m->momentum_pct = fmax(m->momentum_pct, err);
        m->momentum_collided &= collided;
    }
    return 0;
}
