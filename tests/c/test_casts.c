/* pp_world_cast_body and pp_world_raycast_all: a box cast onto the ground stops within 1/16 px of the analytic gap
 * with the ground's normal, turned too; casting away hits nothing; a body overlapping at the start hits at 0; the
 * cast body, sensors, filtered and jointed bodies are passed by; the world's future is unchanged; a ray through
 * three bodies names the three, nearest first, also into a short array; random shapes and turns against a brute
 * force over every pair of pixel squares; misuse. */
#include "helpers.h"

PP_TEST_SUITE(casts);

#define ALL_BITS 0xffffffffu
#define TRAVEL_TOL (1.0 / 16) /* px of travel */

/* Ground: a static 400 × 40 slab whose top is y = 280. */
static pp_body ground_of(pp_world w) { return add_rect(w, body_def(PP_BODY_STATIC, 200, 300, 0), 400, 40); }

static pp_raycast_hit cast(pp_world w, pp_body b, pp_vec2 t, uint32_t mask, int32_t *hit)
{
    pp_raycast_hit h;
    memset(&h, 0x5a, sizeof h);
    PP_OK_OR_FAIL(pp_world_cast_body(w, b, t, mask, &h, hit));
    return h;
}

/* The hit of a box dropped by 100 px onto the ground: at the analytic gap, the ground's normal. */
static void expect_landing(pp_world w, pp_body box, pp_body ground, double gap, double touch_x)
{
    int32_t hit = 0;
    const pp_raycast_hit h = cast(w, box, v2(0, 100), ALL_BITS, &hit);
    cr_assert_eq(hit, 1);
    cr_expect_eq(h.body.id, ground.id);
    cr_expect(fabs(h.fraction * 100.0 - gap) <= TRAVEL_TOL, "travel %.5f px, gap %.5f px", h.fraction * 100.0, gap);
    cr_expect(fabs(h.normal.x) < 1e-6 && fabs(h.normal.y + 1) < 1e-6, "normal (%g, %g)", h.normal.x, h.normal.y);
    cr_expect(fabs(h.point.y - 280) < 1e-3 && fabs(h.point.x - touch_x) < 0.5, "point (%g, %g), expected (%g, 280)",
              h.point.x, h.point.y, touch_x);
}

Test(casts, a_box_cast_onto_the_ground_stops_at_the_gap)
{
    pp_world w = make_world(0, 980);
    pp_body ground = ground_of(w);
    /* 20 × 20 centred at (200, 200.3): its underside at 210.3, 69.7 px above the ground. */
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200.3f, 0), 20, 20);
    expect_landing(w, box, ground, 280 - (200.3f + 10.0), 200);
    pp_world_destroy(w);
}

Test(casts, a_turned_box_lands_on_its_corner)
{
    pp_world w = make_world(0, 980);
    pp_body ground = ground_of(w);
    const float a = 0.3f;
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200, a), 20, 20);
    /* Its lowest corner, bitmap (20, 20): (200 + 10(cos − sin), 200 + 10(sin + cos)). */
    const double c = cos(a), s = sin(a);
    expect_landing(w, box, ground, 280 - (200 + 10 * (s + c)), 200 + 10 * (c - s));
    pp_world_destroy(w);
}

Test(casts, sideways_along_the_ground_and_away_from_it_nothing_is_hit)
{
    pp_world w = make_world(0, 980);
    ground_of(w);
    /* Resting exactly on the ground (underside at 280): it slides along it and leaves it freely. */
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 270, 0), 20, 20);
    int32_t hit = 1;
    pp_raycast_hit h = cast(w, box, v2(0, -100), ALL_BITS, &hit);
    cr_expect_eq(hit, 0);
    cr_expect(h.body.id == 0 && h.fraction == 0, "out is zeroed");
    cast(w, box, v2(150, 0), ALL_BITS, &hit);
    cr_expect_eq(hit, 0, "sliding along the ground");
    h = cast(w, box, v2(0, 1), ALL_BITS, &hit);
    cr_expect(hit == 1 && h.fraction < 1e-6, "into the ground it touches: hit %d at %g", hit, h.fraction);
    pp_world_destroy(w);
}

Test(casts, a_body_overlapping_at_the_start_hits_at_0)
{
    pp_world w = make_world(0, 980);
    pp_body ground = ground_of(w);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 275, 0), 20, 20);
    int32_t hit = 0;
    pp_raycast_hit h = cast(w, box, v2(5, -50), ALL_BITS, &hit);
    cr_assert_eq(hit, 1);
    cr_expect(h.body.id == ground.id && h.fraction == 0, "fraction %g", h.fraction);
    /* Wholly inside the ground, no edge pixel of the box over an edge of the ground. */
    pp_body inner = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 300, 0), 4, 4);
    h = cast(w, inner, v2(0, 0), ALL_BITS, &hit);
    cr_expect(hit == 1 && h.body.id == ground.id && h.fraction == 0, "inside: hit %d", hit);
    pp_world_destroy(w);
}

Test(casts, the_body_itself_sensors_filtered_and_jointed_bodies_are_passed_by)
{
    pp_world w = make_world(0, 980);
    pp_body ground = ground_of(w);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200, 0), 20, 20);
    /* Four slabs in its path, each of which the cast must pass by. */
    pp_body_def sd = body_def(PP_BODY_STATIC, 200, 230, 0);
    sd.is_sensor = 1;
    add_rect(w, sd, 60, 4);
    pp_body_def cd = body_def(PP_BODY_STATIC, 200, 240, 0);
    cd.category_bits = 4; /* outside the call's mask */
    add_rect(w, cd, 60, 4);
    pp_body_def md = body_def(PP_BODY_STATIC, 200, 250, 0);
    md.mask_bits = ~1u; /* its filter keeps out the box's category */
    add_rect(w, md, 60, 4);
    pp_body jointed = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 260, 0), 60, 4);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    jd.body_a = box;
    jd.body_b = jointed;
    jd.anchor_a = v2(200, 200);
    make_joint(w, &jd);
    int32_t hit = 0;
    const pp_raycast_hit h = cast(w, box, v2(0, 100), ~4u, &hit);
    cr_assert_eq(hit, 1);
    cr_expect(h.body.id == ground.id && fabs(h.fraction * 100 - 70) <= TRAVEL_TOL, "hit %llu at %g",
              (unsigned long long)h.body.id, h.fraction);
    /* The jointed slab is hit once the joint lets the two collide. */
    pp_body_def d2 = body_def(PP_BODY_DYNAMIC, 100, 200, 0);
    pp_body other = add_rect(w, d2, 20, 20);
    jd.body_a = other;
    jd.anchor_a = v2(100, 200);
    jd.collide_connected = 1;
    make_joint(w, &jd);
    PP_OK_OR_FAIL(pp_body_set_transform(w, jointed, v2(100, 260), 0));
    const pp_raycast_hit h2 = cast(w, other, v2(0, 100), ALL_BITS, &hit);
    cr_expect(hit == 1 && h2.body.id == jointed.id, "collide_connected: hit %llu", (unsigned long long)h2.body.id);
    pp_world_destroy(w);
}

/* The world's hash: everything its next steps depend on (pp_world_get_hash). */
static uint64_t world_hash(pp_world w)
{
    uint64_t h = 0;
    PP_OK_OR_FAIL(pp_world_get_hash(w, &h));
    return h;
}

static pp_world cast_scene(pp_body *boxes)
{
    pp_world w = make_world(0, 980);
    ground_of(w);
    for (int k = 0; k < 3; k++)
        boxes[k] = add_rect(w, body_def(PP_BODY_DYNAMIC, 150.0f + 50 * k, 240.0f - 30 * k, 0.2f * k), 20, 20);
    step_n(w, 1.0f / 60, 10);
    return w;
}

Test(casts, casts_and_rays_leave_the_world_as_it_was)
{
    pp_body a[3], b[3];
    pp_world w = cast_scene(a), twin = cast_scene(b);
    const uint64_t before = world_hash(w);
    cr_assert_eq(before, world_hash(twin), "two worlds built alike hash alike");
    for (int k = 0; k < 3; k++) {
        int32_t hit, count;
        cast(w, a[k], v2(30, 120), ALL_BITS, &hit);
        cast(w, a[k], v2(-200, 0), ALL_BITS, &hit);
        pp_raycast_hit hits[4];
        PP_OK_OR_FAIL(pp_world_raycast_all(w, v2(0, 230), v2(400, 290), ALL_BITS, hits, 4, &count));
    }
    cr_assert_eq(world_hash(w), before, "a cast or a ray changed the world");
    for (int s = 0; s < 60; s++) { /* equal hashes, equal futures: the twin that was never cast in */
        step_n(w, 1.0f / 60, 1);
        step_n(twin, 1.0f / 60, 1);
        cr_assert_eq(world_hash(w), world_hash(twin), "the futures part at step %d", s);
    }
    pp_world_destroy(w);
    pp_world_destroy(twin);
}

Test(casts, raycast_all_names_three_bodies_nearest_first)
{
    pp_world w = make_world(0, 0);
    /* Added far to near, so that slot order is not the answer. */
    pp_body far = add_rect(w, body_def(PP_BODY_STATIC, 300, 100, 0), 20, 40);
    pp_body mid = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 100, 0.4f), 20, 40);
    pp_body near = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 20, 40);
    pp_raycast_hit hits[4];
    int32_t count = 0;
    PP_OK_OR_FAIL(pp_world_raycast_all(w, v2(0, 100), v2(400, 100), ALL_BITS, hits, 4, &count));
    cr_assert_eq(count, 3);
    cr_expect(hits[0].body.id == near.id && hits[1].body.id == mid.id && hits[2].body.id == far.id);
    cr_expect(fabs(hits[0].point.x - 90) < 0.05 && fabs(hits[2].point.x - 290) < 0.05, "entries at %g and %g",
              hits[0].point.x, hits[2].point.x);
    cr_expect(hits[0].fraction < hits[1].fraction && hits[1].fraction < hits[2].fraction);
    /* Each the nearest hit pp_world_raycast finds from just before it. */
    int32_t one = 0;
    pp_raycast_hit single;
    PP_OK_OR_FAIL(pp_world_raycast(w, v2(0, 100), v2(400, 100), ALL_BITS, &single, &one));
    cr_expect(one && memcmp(&single, &hits[0], sizeof single) == 0);
    /* A short array: the nearest two, and the total. */
    pp_raycast_hit two[2];
    PP_OK_OR_FAIL(pp_world_raycast_all(w, v2(0, 100), v2(400, 100), ALL_BITS, two, 2, &count));
    cr_expect(count == 3 && two[0].body.id == near.id && two[1].body.id == mid.id);
    PP_OK_OR_FAIL(pp_world_raycast_all(w, v2(0, 100), v2(400, 100), ALL_BITS, NULL, 0, &count));
    cr_expect_eq(count, 3);
    /* Filtered, and a segment that stops short. */
    PP_OK_OR_FAIL(pp_world_raycast_all(w, v2(0, 100), v2(250, 100), ALL_BITS, hits, 4, &count));
    cr_expect_eq(count, 2);
    PP_OK_OR_FAIL(pp_world_raycast_all(w, v2(0, 100), v2(400, 100), 0, hits, 4, &count));
    cr_expect_eq(count, 0);
    pp_world_destroy(w);
}

/* ---- against a brute force: every pair of pixel squares, separated on the four axes of their bitmaps ---- */

typedef struct square_body {
    int w, h;
    uint8_t mask[49];
    double x, y, angle; /* the pivot (the bitmap centre) in the world, px, and the turn */
} square_body;

/* How deep the squares of pixel (i, j) of a, moved by d, and pixel (k, l) of b overlap: the least of their overlaps
 * on the four axes, px (≤ 0: apart or touching). */
static double square_depth(const square_body *a, int i, int j, double dx, double dy, const square_body *b, int k,
                           int l)
{
    const square_body *s[2] = {a, b};
    double cx[2], cy[2];
    const int px[2] = {i, k}, py[2] = {j, l};
    for (int q = 0; q < 2; q++) {
        const double c = cos(s[q]->angle), n = sin(s[q]->angle);
        const double lx = px[q] + 0.5 - s[q]->w / 2.0, ly = py[q] + 0.5 - s[q]->h / 2.0;
        cx[q] = s[q]->x + c * lx - n * ly + (q == 0 ? dx : 0), cy[q] = s[q]->y + n * lx + c * ly + (q == 0 ? dy : 0);
    }
    double depth = INFINITY;
    for (int q = 0; q < 4; q++) {
        const double t = s[q / 2]->angle + (q % 2) * M_PI / 2, ux = cos(t), uy = sin(t);
        double reach = 0;
        for (int r = 0; r < 2; r++)
            reach += 0.5 * (fabs(ux * cos(s[r]->angle) + uy * sin(s[r]->angle)) +
                            fabs(-ux * sin(s[r]->angle) + uy * cos(s[r]->angle)));
        depth = fmin(depth, reach - fabs(ux * (cx[0] - cx[1]) + uy * (cy[0] - cy[1])));
    }
    return depth;
}

/* The deepest overlap of a moved by d with b, px. */
static double bodies_depth(const square_body *a, double dx, double dy, const square_body *b)
{
    double deepest = -INFINITY;
    for (int j = 0; j < a->h; j++)
        for (int i = 0; i < a->w; i++)
            for (int l = 0; a->mask[j * a->w + i] && l < b->h; l++)
                for (int k = 0; k < b->w; k++)
                    if (b->mask[l * b->w + k])
                        deepest = fmax(deepest, square_depth(a, i, j, dx, dy, b, k, l));
    return deepest;
}

static void random_body(square_body *s, int side, uint64_t *seed, double x, double y)
{
    s->w = s->h = side;
    int solid = 0;
    while (!solid)
        for (int k = 0; k < side * side; k++)
            solid += s->mask[k] = (*seed = *seed * 6364136223846793005ull + 1442695040888963407ull) >> 62 != 0;
    *seed = *seed * 6364136223846793005ull + 1442695040888963407ull;
    s->angle = (double)(*seed >> 11) / 9007199254740992.0 * 2 * M_PI;
    s->x = x, s->y = y;
}

static pp_body add_square_body(pp_world w, const square_body *s, pp_body_type type)
{
    pp_body_def d = body_def(type, (float)s->x, (float)s->y, (float)s->angle);
    d.width = s->w, d.height = s->h, d.mask = s->mask;
    return create_body_ok(w, &d);
}

#define TRIALS 120

Test(casts, random_shapes_and_turns_stop_within_a_sixteenth_of_a_pixel_of_the_brute_force)
{
    uint64_t seed = 44;
    int hits = 0, starts = 0;
    for (int trial = 0; trial < TRIALS; trial++) {
        pp_world w = make_world(0, 0);
        square_body a, b;
        random_body(&b, 7, &seed, 100, 100);
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        const double ax = 100 + ((double)(seed >> 11) / 9007199254740992.0 - 0.5) * 40;
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        const double ay = 100 + ((double)(seed >> 11) / 9007199254740992.0 - 0.5) * 40;
        random_body(&a, 5, &seed, ax, ay);
        /* Toward b's centre, give or take, from 5 to 40 px. */
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        const double len = 5 + 35 * (double)(seed >> 11) / 9007199254740992.0, off = (double)(seed & 1023) / 1023 - 0.5;
        const double dir = atan2(100 - ay, 100 - ax) + off;
        const pp_vec2 T = v2((float)(len * cos(dir)), (float)(len * sin(dir)));
        /* Poses as the library holds them (floats). */
        a.x = (float)a.x, a.y = (float)a.y, a.angle = (float)a.angle, b.angle = (float)b.angle;
        pp_body pa = add_square_body(w, &a, PP_BODY_DYNAMIC);
        add_square_body(w, &b, PP_BODY_STATIC);
        int32_t hit = 0;
        pp_raycast_hit h;
        PP_OK_OR_FAIL(pp_world_cast_body(w, pa, T, ALL_BITS, &h, &hit));
        const double step = (1.0 / 16) / len; /* a sixteenth of a pixel of travel, as a fraction */
        const double f = hit ? h.fraction : 1.0;
        /* Free up to the fraction (sampled every 1/16 px of travel), touching at it (a corner may only graze a
         * corner, overlapping a thousandth of a pixel for under a thousandth of a pixel of travel: no sample after
         * it need see that). */
        for (double t = 0; t < f - step; t += step)
            cr_assert(bodies_depth(&a, t * T.x, t * T.y, &b) <= 1e-4, "trial %d: overlap at %g before the hit at %g",
                      trial, t, f);
        if (hit) {
            hits++, starts += h.fraction == 0;
            const double depth = bodies_depth(&a, f * T.x, f * T.y, &b);
            cr_assert(depth > -1e-4 && (f == 0 || depth < 1e-4), "trial %d: %g px deep at the hit at %g", trial, depth,
                      f);
        }
        pp_world_destroy(w);
    }
    cr_log_info("cast vs brute force: %d random pairs, %d hits (%d overlapping at the start)", TRIALS, hits, starts);
    cr_expect(hits > TRIALS / 2 && hits - starts > TRIALS / 3, "%d hits, %d at the start: too few to mean much", hits, starts);
}

Test(casts, misuse)
{
    pp_world w = make_world(0, 980);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200, 0), 20, 20);
    pp_raycast_hit h;
    int32_t hit, count;
    EXPECT_ERR(pp_world_cast_body(w, box, v2(0, 1), ALL_BITS, NULL, &hit), PP_ERR_INVALID_ARGUMENT, "out");
    cr_expect(strncmp(pp_last_error(), "pp_world_cast_body", 18) == 0, "%s", pp_last_error());
    EXPECT_ERR(pp_world_cast_body(w, box, v2(0, 1), ALL_BITS, &h, NULL), PP_ERR_INVALID_ARGUMENT, "hit");
    EXPECT_ERR(pp_world_cast_body(w, box, v2(NAN, 1), ALL_BITS, &h, &hit), PP_ERR_INVALID_ARGUMENT, "translation");
    EXPECT_ERR(pp_world_cast_body(w, box, v2(0, INFINITY), ALL_BITS, &h, &hit), PP_ERR_INVALID_ARGUMENT,
               "translation");
    EXPECT_ERR(pp_world_cast_body(w, (pp_body){0}, v2(0, 1), ALL_BITS, &h, &hit), PP_ERR_INVALID_HANDLE,
               "pp_world_cast_body");
    EXPECT_ERR(pp_world_raycast_all(w, v2(0, 0), v2(NAN, 0), ALL_BITS, &h, 1, &count), PP_ERR_INVALID_ARGUMENT,
               "finite");
    EXPECT_ERR(pp_world_raycast_all(w, v2(0, 0), v2(1, 0), ALL_BITS, &h, -1, &count), PP_ERR_INVALID_ARGUMENT,
               "capacity");
    EXPECT_ERR(pp_world_raycast_all(w, v2(0, 0), v2(1, 0), ALL_BITS, &h, 1, NULL), PP_ERR_INVALID_ARGUMENT, "count");
    PP_OK_OR_FAIL(pp_body_destroy(w, box));
    EXPECT_ERR(pp_world_cast_body(w, box, v2(0, 1), ALL_BITS, &h, &hit), PP_ERR_INVALID_HANDLE, "pp_world_cast_body");
    pp_world_destroy(w);
}
