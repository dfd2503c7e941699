/* The tree broadphase against a brute force: every pair of boxes that overlap (at least one dynamic and
 * awake, categories agreeing) is a candidate, no more, through creations, destructions and moved static
 * bodies. The dynamic bodies are sensors in zero gravity, so that nothing moves them between the count
 * and the check; a static body's box moves only by pp_body_set_transform. */
#include <criterion/criterion.h>
#include <stdlib.h>

#include "helpers.h"
#include "physpix.h"

PP_TEST_SUITE(broadphase);

#define MAX_BODIES 400

typedef struct probe {
    pp_body b;
    int live, dynamic, w, h;
    float x, y;
    uint32_t category, mask;
} probe;

static uint32_t rng = 12345u;
static uint32_t next_random(void) { return rng = rng * 1664525u + 1013904223u; }
static float uniform(float lo, float hi) { return lo + (hi - lo) * (float)(next_random() >> 8) / 16777216.0f; }

static void make_probe(pp_world w, probe *p, int dynamic)
{
    *p = (probe){.live = 1, .dynamic = dynamic, .w = 4 + (int)(next_random() % 37), .h = 4 + (int)(next_random() % 37),
                 .x = uniform(0, 1000), .y = uniform(0, 1000), .category = 1u << (next_random() % 2),
                 .mask = next_random() % 4 == 0 ? 1u : 3u};
    pp_body_def d = body_def(dynamic ? PP_BODY_DYNAMIC : PP_BODY_STATIC, p->x, p->y, 0);
    d.is_sensor = (uint32_t)dynamic;
    d.category_bits = p->category;
    d.mask_bits = p->mask;
    p->b = add_rect(w, d, p->w, p->h);
}

/* Closed overlap of two axis-aligned boxes centred on their positions (default pivots), as the library's. */
static int overlap(const probe *p, const probe *q)
{
    return p->x - p->w * 0.5f <= q->x + q->w * 0.5f && q->x - q->w * 0.5f <= p->x + p->w * 0.5f &&
           p->y - p->h * 0.5f <= q->y + q->h * 0.5f && q->y - q->h * 0.5f <= p->y + p->h * 0.5f;
}

static int brute_pairs(const probe *p, int n)
{
    int pairs = 0;
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            pairs += p[i].live && p[j].live && (p[i].dynamic || p[j].dynamic) && (p[i].category & p[j].mask) &&
                     (p[j].category & p[i].mask) && overlap(&p[i], &p[j]);
    return pairs;
}

static int32_t stepped_pairs(pp_world w)
{
    PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
    pp_step_stats s;
    PP_OK_OR_FAIL(pp_world_get_stats(w, &s));
    return s.pairs;
}

Test(broadphase, the_tree_finds_exactly_the_overlapping_pairs_through_churn)
{
    pp_world_def d = pp_world_def_default();
    d.gravity = v2(0, 0);
    d.allow_sleep = 0;
    d.backend = PP_BACKEND_CPU;
    pp_world w = make_world_def(&d);
    static probe p[MAX_BODIES];
    int n = 0;
    for (; n < 300; n++)
        make_probe(w, &p[n], n >= 40); /* 40 static, 260 dynamic sensors */
    int checked = 0;
    for (int round = 0; round < 8; round++) {
        const int want = brute_pairs(p, n), got = stepped_pairs(w);
        cr_assert_eq(got, want, "round %d: %d pairs, the brute force finds %d", round, (int)got, want);
        checked += want;
        /* Churn: 30 bodies go, 30 come (some into freed slots), 10 static bodies move. */
        for (int k = 0; k < 30; k++) {
            probe *q = &p[next_random() % (unsigned)n];
            if (q->live) {
                PP_OK_OR_FAIL(pp_body_destroy(w, q->b));
                q->live = 0;
            }
        }
        for (int k = 0; k < 30 && n < MAX_BODIES; k++)
            make_probe(w, &p[n++], next_random() % 4 != 0);
        for (int k = 0; k < 10; k++) {
            probe *q = &p[next_random() % 40u];
            if (!q->live)
                continue;
            q->x = uniform(0, 1000), q->y = uniform(0, 1000);
            PP_OK_OR_FAIL(pp_body_set_transform(w, q->b, v2(q->x, q->y), 0));
        }
    }
    cr_assert_gt(checked, 500, "the scene should make many pairs (%d)", checked);
    pp_world_destroy(w);
}

#ifdef PP_TEST_PRIVATE
#include "broadphase.h"

/* A step's candidates against a fresh search: awake boxes found with grown boxes, then moved by up to their
 * reach (most) or past it (some), for three later substeps; broadphase_find_later_pairs must give exactly the
 * pairs, in the order, that broadphase_find_pairs gives on a second broadphase holding the same bodies. */
Test(broadphase, a_steps_candidates_give_the_pairs_a_search_finds)
{
    enum { N = 300, AWAKE = 120 };
    int reused = 0, searched = 0;
    for (int round = 0; round < 20; round++) {
        bp_proxy px[N];
        pp_aabb grown[N];
        int32_t awake[AWAKE];
        double vx[N], vy[N];
        for (int i = 0; i < N; i++) {
            const double x = uniform(0, 400), y = uniform(0, 400), w = uniform(2, 40), h = uniform(2, 40);
            const bool moving = i < AWAKE, dynamic = moving || i % 3 == 0; /* the rest: sleepers and static */
            px[i] = (bp_proxy){{x, y, x + w, y + h}, 1u << (next_random() % 2), next_random() % 4 ? 3u : 1u,
                               dynamic, dynamic, moving, true};
            vx[i] = uniform(-6, 6), vy[i] = uniform(-6, 6);
            if (moving)
                awake[i] = i;
            /* The box over the step: its motion and 1 px either way. */
            grown[i] = (pp_aabb){x + fminf(vx[i], 0) - 1, y + fminf(vy[i], 0) - 1, x + w + fmaxf(vx[i], 0) + 1,
                                 y + h + fmaxf(vy[i], 0) + 1};
        }
        pp_broadphase step = {0}, fresh = {0};
        for (int i = 0; i < N; i++) {
            PP_OK_OR_FAIL(broadphase_update(&step, &px[i], (uint32_t)i, N));
            PP_OK_OR_FAIL(broadphase_update(&fresh, &px[i], (uint32_t)i, N));
        }
        PP_OK_OR_FAIL(broadphase_find_step_pairs(&step, px, N, awake, AWAKE, grown));
        for (int k = 0; k < 4; k++) {
            if (k > 0) { /* a quarter of the step's motion; at the last substep one body in ten shoots past */
                for (int i = 0; i < AWAKE; i++) {
                    const double f = k == 3 && i % 10 == 0 ? 3 : 0.25;
                    px[i].box.x0 += f * vx[i], px[i].box.x1 += f * vx[i];
                    px[i].box.y0 += f * vy[i], px[i].box.y1 += f * vy[i];
                }
                const bool held = !(k == 3);
                PP_OK_OR_FAIL(broadphase_find_later_pairs(&step, px, N, awake, AWAKE));
                reused += held && step.cand_valid, searched += !step.cand_valid;
            }
            PP_OK_OR_FAIL(broadphase_find_pairs(&fresh, px, N, awake, AWAKE));
            cr_assert_eq(step.pair_count, fresh.pair_count, "round %d substep %d: %d pairs, a search finds %d", round, k,
                         (int)step.pair_count, (int)fresh.pair_count);
            for (int p = 0; p < fresh.pair_count; p++)
                cr_assert(step.pairs[p].a == fresh.pairs[p].a && step.pairs[p].b == fresh.pairs[p].b,
                          "round %d substep %d: pair %d is (%u, %u), a search's (%u, %u)", round, k, p,
                          step.pairs[p].a, step.pairs[p].b, fresh.pairs[p].a, fresh.pairs[p].b);
        }
        cr_assert_gt(fresh.pair_count, 50, "round %d: only %d pairs", round, (int)fresh.pair_count);
        broadphase_free(&step), broadphase_free(&fresh);
    }
    cr_assert_eq(reused, 40, "the candidates served %d of 40 substeps within reach", reused);
    cr_assert_eq(searched, 20, "%d of 20 substeps past reach searched again", searched);
}
#endif
