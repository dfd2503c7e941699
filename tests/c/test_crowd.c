/* Bodies spawned into one spot and the contact budget (PP_CROWDED_CONTACT_PAIRS): the step stays bounded,
 * the pile separates with every body kept and finite, the same way every run and on any thread count; and a
 * body carrying more bodies than the budget, which is not crowded, keeps every contact. */
#include "helpers.h"

PP_TEST_SUITE(crowd);

#define FLOOR_TOP 1000.0f

/* A static floor 8,000 px wide with its top at FLOOR_TOP, wide enough that nothing flung sideways by a
 * spawn leaves it within the tests' steps. */
static pp_world floor_world(const pp_world_def *d)
{
    pp_world w = make_world_def(d);
    add_rect(w, body_def(PP_BODY_STATIC, 1000, FLOOR_TOP + 10, 0), 8000, 20);
    return w;
}

/* n solid 8 px boxes created at one point (or, jittered, within ±2 px of it, turned a little). */
static pp_body *spawn(pp_world w, int n, int jittered)
{
    pp_body *b = malloc((size_t)n * sizeof *b);
    cr_assert_not_null(b);
    for (int i = 0; i < n; i++) {
        const float dx = jittered ? (float)((i * 7919) % 401) / 100.0f - 2.0f : 0.0f;
        const float dy = jittered ? (float)((i * 104729) % 401) / 100.0f - 2.0f : 0.0f;
        b[i] = add_rect(w, body_def(PP_BODY_DYNAMIC, 1000 + dx, 900 + dy, jittered ? 0.1f * (i % 13) : 0.0f), 8, 8);
    }
    return b;
}

/* Root-mean-square distance of the bodies from their mean, px; false if a pose is not finite or the largest
 * y is at or below the floor's top (a body went through). */
static bool spread(pp_world w, const pp_body *b, int n, double *rms, float *max_y)
{
    double mx = 0, my = 0, r = 0;
    bool ok = true;
    *max_y = -INFINITY;
    pp_vec2 *p = malloc((size_t)n * sizeof *p);
    cr_assert_not_null(p);
    for (int i = 0; i < n; i++) {
        float a = 0;
        p[i] = body_pos(w, b[i]);
        PP_OK_OR_FAIL(pp_body_get_angle(w, b[i], &a));
        ok &= isfinite(p[i].x) && isfinite(p[i].y) && isfinite(a);
        mx += p[i].x, my += p[i].y;
        *max_y = p[i].y > *max_y ? p[i].y : *max_y;
    }
    mx /= n, my /= n;
    for (int i = 0; i < n; i++)
        r += (p[i].x - mx) * (p[i].x - mx) + (p[i].y - my) * (p[i].y - my);
    free(p);
    *rms = sqrt(r / n);
    return ok && *max_y < FLOOR_TOP;
}

static int32_t contact_count(pp_world w)
{
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_contacts(w, NULL, 0, &n));
    return n;
}

/* Before the budget the first step alone took 39-100 s at -O2 (every one of the 499,500 pairs a contact pair,
 * 73,000 contacts in its last substep). With it all 30 steps take 2.3-4.3 s at -O2, 4.8 s under ASan. */
Test(crowd, a_1000_body_spawn_at_one_point_steps_in_bounded_time_and_separates, .timeout = 30)
{
    enum { N = 1000, STEPS = 30 };
    pp_world_def d = pp_world_def_default();
    pp_world w = floor_world(&d);
    pp_body *b = spawn(w, N, 0);
    PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
    /* The budget's bound: at most PP_CROWDED_CONTACT_PAIRS pairs a crowded body, and the floor. */
    const int32_t first = contact_count(w);
    cr_assert_leq(first, PP_MAX_CONTACTS_PER_PAIR * (PP_CROWDED_CONTACT_PAIRS + 1) * N,
                  "%d contacts for %d crowded bodies: the budget did not hold", (int)first, N);
    double rms1, rms;
    float max_y;
    cr_assert(spread(w, b, N, &rms1, &max_y), "after one step a pose is not finite or below the floor (y %g)", max_y);
    for (int k = 1; k < STEPS; k++)
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
    cr_assert(spread(w, b, N, &rms, &max_y), "after %d steps a pose is not finite or below the floor (y %g)", STEPS,
              max_y);
    int32_t bodies = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, NULL, 0, &bodies));
    cr_assert_eq(bodies, N + 1, "%d bodies left of %d", (int)bodies, N + 1);
    cr_assert_gt(rms, 4 * rms1 + 100, "the pile did not spread: rms %g px after one step, %g px after %d", rms1, rms,
                 STEPS);
    const int32_t last = contact_count(w);
    cr_assert_lt(last, N / 2, "%d contacts after %d steps: the pile still overlaps", (int)last, STEPS);
    cr_log_info("1000-body spawn: %d contacts after one step, %d after %d; rms spread %.1f then %.1f px", (int)first,
                (int)last, STEPS, rms1, rms);
    free(b);
    pp_world_destroy(w);
}

/* A crowded spawn's poses after 20 steps, hashed. */
static uint64_t crowd_hash(int worker_threads, int jittered)
{
    enum { N = 200, STEPS = 20 };
    pp_world_def d = pp_world_def_default();
    d.worker_threads = worker_threads;
    pp_world w = floor_world(&d);
    pp_body *b = spawn(w, N, jittered);
    uint64_t h = FNV_START;
    for (int k = 0; k < STEPS; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
        for (int i = 0; i < N; i++) {
            const pp_vec2 p = body_pos(w, b[i]);
            h = fnv1a(h, &p, sizeof p);
        }
    }
    free(b);
    pp_world_destroy(w);
    return h;
}

Test(crowd, a_crowded_spawn_is_the_same_every_run_and_on_any_thread_count, .timeout = 60)
{
    for (int jittered = 0; jittered < 2; jittered++) {
        const uint64_t one = crowd_hash(1, jittered), again = crowd_hash(1, jittered), two = crowd_hash(2, jittered);
        cr_assert_eq(one, again, "two runs differ (jittered %d): %016llx vs %016llx", jittered, (unsigned long long)one,
                     (unsigned long long)again);
        cr_assert_eq(one, two, "1 and 2 worker threads differ (jittered %d): %016llx vs %016llx", jittered,
                     (unsigned long long)one, (unsigned long long)two);
    }
}

/* A dynamic plank carrying 40 boxes touches far more bodies than the budget, but along thin bands: it is not
 * crowded, and every box keeps its contact with it (none sinks in). */
Test(crowd, a_plank_carrying_more_boxes_than_the_budget_keeps_every_contact, .timeout = 60)
{
    enum { BOXES = 40 };
    pp_world_def d = pp_world_def_default();
    d.allow_sleep = 0; /* sleeping bodies make no contacts to count */
    pp_world w = floor_world(&d);
    const pp_body plank = add_rect(w, body_def(PP_BODY_DYNAMIC, 1000, FLOOR_TOP - 6, 0), 400, 12);
    pp_body box[BOXES];
    for (int i = 0; i < BOXES; i++)
        box[i] = add_rect(w, body_def(PP_BODY_DYNAMIC, 1000 - 195 + 10.0f * i, FLOOR_TOP - 12 - 4 - 1, 0), 8, 8);
    for (int k = 0; k < 120; k++)
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
    const int32_t n = contact_count(w);
    pp_contact *c = malloc((size_t)n * sizeof *c);
    cr_assert_not_null(c);
    int32_t got = 0;
    PP_OK_OR_FAIL(pp_world_get_contacts(w, c, n, &got));
    for (int i = 0; i < BOXES; i++) {
        int with_plank = 0;
        for (int k = 0; k < n; k++)
            with_plank += (c[k].a.id == plank.id && c[k].b.id == box[i].id) ||
                          (c[k].b.id == plank.id && c[k].a.id == box[i].id);
        const pp_vec2 p = body_pos(w, box[i]);
        cr_assert_gt(with_plank, 0, "box %d lost its contact with the plank", i);
        cr_assert_lt(p.y, FLOOR_TOP - 12 - 4 + 1.5f, "box %d sank into the plank (y %g)", i, p.y);
    }
    cr_assert_gt(BOXES, PP_CROWDED_CONTACT_PAIRS, "the plank must touch more bodies than the budget");
    free(c);
    pp_world_destroy(w);
}
