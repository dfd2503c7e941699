/* Rays and region queries: hit points and normals against analytic shapes (a turned box, a box drawn
 * turned, a disc), the march against a brute force, rays through a hole erased a step before, rays
 * starting inside, filtering, the nearest of several bodies, a ray over many boxes without memory, the
 * point/box/circle queries against a brute force over every solid pixel, and misuse. */
#include "helpers.h"

PP_TEST_SUITE(raycast);

#define ALL_BITS 0xffffffffu
#define WINDOW_R 8.0 /* the normal window's radius, px (lib/query/raycast.c RAY_WINDOW) */

/* A small deterministic generator (PCG-style LCG), uniform in [0, 1). */
static double rnd(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) / 9007199254740992.0;
}

static pp_raycast_hit cast(pp_world w, pp_vec2 from, pp_vec2 to, uint32_t mask, int32_t *hit)
{
    pp_raycast_hit h;
    memset(&h, 0x5a, sizeof h);
    PP_OK_OR_FAIL(pp_world_raycast(w, from, to, mask, &h, hit));
    return h;
}

/* Errors of a batch of rays: the distance of the point from the analytic ray–shape intersection, its
 * distance from the shape's outline (across the surface), and the angle of the normal. */
typedef struct ray_errors {
    double point[1000], across[1000], normal[1000], incidence[1000]; /* px, px, degrees, degrees off the surface */
    int n;
} ray_errors;

static void record(ray_errors *e, double point_err, double across_err, double normal_err, double incidence)
{
    e->point[e->n] = point_err, e->across[e->n] = across_err, e->normal[e->n] = normal_err;
    e->incidence[e->n] = incidence;
    e->n++;
}

static int worst(const double *v, int n, double min_incidence, const double *incidence)
{
    int w = -1;
    for (int k = 0; k < n; k++)
        if (incidence[k] >= min_incidence && (w < 0 || v[k] > v[w]))
            w = k;
    return w;
}

/* Print the errors and hold them to 0.5 px and 2°; the point's distance from the analytic intersection
 * only on rays at least min_incidence degrees off the surface (0: all of them). */
static void report(const char *what, ray_errors *e, double min_incidence)
{
    const int wp = worst(e->point, e->n, 0, e->incidence), wq = worst(e->point, e->n, min_incidence, e->incidence);
    const int wa = worst(e->across, e->n, 0, e->incidence), wn = worst(e->normal, e->n, 0, e->incidence);
    double p[1000], q[1000];
    memcpy(p, e->point, sizeof p), memcpy(q, e->normal, sizeof q);
    const double p50 = quantile(p, e->n, 0.5), p95 = quantile(p, e->n, 0.95);
    const double n50 = quantile(q, e->n, 0.5), n95 = quantile(q, e->n, 0.95);
    fprintf(stderr,
            "raycast accuracy, %s, %d rays: point error median %.3f p95 %.3f worst %.3f px (ray %.1f deg off the "
            "surface); worst on rays >= %.0f deg off: %.3f px; worst across the surface %.3f px; normal error median "
            "%.3f p95 %.3f worst %.3f deg (ray %.1f deg off)\n",
            what, e->n, p50, p95, e->point[wp], e->incidence[wp], min_incidence, e->point[wq], e->across[wa], n50,
            n95, e->normal[wn], e->incidence[wn]);
    cr_assert_leq(e->point[wq], 0.5, "%s: worst point error %.3f px", what, e->point[wq]);
    cr_assert_leq(e->across[wa], 0.5, "%s: worst point error across the surface %.3f px", what, e->across[wa]);
    cr_assert_leq(e->normal[wn], 2.0, "%s: worst normal error %.3f deg", what, e->normal[wn]);
}

/* Rays against a 120×60 box at 0.37 rad: either a full 120×60 mask turned by the body's angle (the pixel
 * grid turns with it, so the mask's edges are straight), or the box drawn turned into a larger mask by
 * pixel centres (a staircase along every edge) on a body at angle 0. The point error is the distance
 * between the reported point and the analytic ray–box intersection (not its distance across the
 * surface): the library moves the point onto the surface it estimates, so grazing rays are held to
 * the same 0.5 px as square ones. */
static void box_accuracy(bool staircase)
{
    enum { W = 120, H = 60, MW = 160, MH = 120 };
    const double angle = 0.37, cx = 400, cy = 300, c = cos(angle), s = sin(angle);
    pp_world w = make_world(0, 0);
    if (staircase) {
        uint8_t *m = calloc(MW * MH, 1);
        for (int y = 0; y < MH; y++)
            for (int x = 0; x < MW; x++) {
                const double u = x + 0.5 - MW / 2.0, v = y + 0.5 - MH / 2.0;
                m[y * MW + x] = fabs(c * u + s * v) <= W / 2.0 && fabs(-s * u + c * v) <= H / 2.0;
            }
        pp_body_def d = body_def(PP_BODY_STATIC, (float)cx, (float)cy, 0);
        d.width = MW, d.height = MH, d.mask = m;
        create_body_ok(w, &d);
        free(m);
    } else {
        add_rect(w, body_def(PP_BODY_STATIC, (float)cx, (float)cy, (float)angle), W, H);
    }
    const double bound = hypot(W, H) / 2;
    static ray_errors e;
    memset(&e, 0, sizeof e);
    uint64_t seed = 42;
    int excluded = 0;
    while (e.n < 1000) {
        /* From outside the bounding circle toward a random point of the box; in the box's frame
         * (centred, axis-aligned) the analytic hit is a slab test. */
        const double phi = 2 * M_PI * rnd(&seed), dist = bound + 5 + 150 * rnd(&seed);
        const double tx = (rnd(&seed) - 0.5) * W, ty = (rnd(&seed) - 0.5) * H;
        const pp_vec2 from = v2((float)(cx + dist * cos(phi)), (float)(cy + dist * sin(phi)));
        /* The segment runs on past its target point by its own length, well into the body. */
        const double gx = cx + c * tx - s * ty, gy = cy + s * tx + c * ty;
        const pp_vec2 to = v2((float)(2 * gx - from.x), (float)(2 * gy - from.y));
        /* The float endpoints in the box frame. */
        const double fx = from.x - cx, fy = from.y - cy, ex = to.x - cx, ey = to.y - cy;
        const double ax = c * fx + s * fy, ay = -s * fx + c * fy, bx = c * ex + s * ey, by = -s * ex + c * ey;
        const double dx = bx - ax, dy = by - ay;
        double t0 = 0, nlx = 0, nly = 0;
        const double lo[2] = {-W / 2.0, -H / 2.0}, hi[2] = {W / 2.0, H / 2.0}, o[2] = {ax, ay}, v[2] = {dx, dy};
        for (int k = 0; k < 2; k++) {
            if (v[k] == 0)
                continue;
            const double tin = fmin((lo[k] - o[k]) / v[k], (hi[k] - o[k]) / v[k]);
            if (tin > t0) {
                t0 = tin;
                nlx = k == 0 ? (v[k] > 0 ? -1 : 1) : 0;
                nly = k == 1 ? (v[k] > 0 ? -1 : 1) : 0;
            }
        }
        const double hx = ax + t0 * dx, hy = ay + t0 * dy;
        int32_t hit = 0;
        const pp_raycast_hit h = cast(w, from, to, ALL_BITS, &hit);
        cr_assert_eq(hit, 1, "ray %d missed the box", e.n);
        /* The reported point in the box frame, and its distance from the outline. */
        const double qx = c * (h.point.x - cx) + s * (h.point.y - cy);
        const double qy = -s * (h.point.x - cx) + c * (h.point.y - cy);
        const double ox = fabs(qx) - W / 2.0, oy = fabs(qy) - H / 2.0;
        const double across = ox < 0 && oy < 0 ? fmin(-ox, -oy) : hypot(fmax(ox, 0), fmax(oy, 0));
        /* The analytic normal is undefined at a corner, and the window straddles two faces within its
         * radius of one: rays meeting the box (analytically or as reported) within R + 1 px of a corner
         * are left out. */
        if (hypot(fabs(hx) - W / 2.0, fabs(hy) - H / 2.0) < WINDOW_R + 1 || hypot(ox, oy) < WINDOW_R + 1) {
            excluded++;
            continue;
        }
        const double wx = cx + c * hx - s * hy, wy = cy + s * hx + c * hy;
        const double nx = c * nlx - s * nly, ny = s * nlx + c * nly;
        const double incidence = RAD2DEG(asin(fabs(nlx * dx + nly * dy) / hypot(dx, dy)));
        record(&e, hypot(h.point.x - wx, h.point.y - wy), across, angle_between_deg(h.normal.x, h.normal.y, nx, ny),
               incidence);
        cr_assert_float_eq(hypot(h.normal.x, h.normal.y), 1.0, 1e-5);
        /* The point is where the fraction says along the ray. */
        cr_assert_float_eq(h.point.x, from.x + h.fraction * (to.x - from.x), 1e-3);
        cr_assert_float_eq(h.point.y, from.y + h.fraction * (to.y - from.y), 1e-3);
    }
    fprintf(stderr, "raycast accuracy, %s box: %d rays within %.0f px of a corner left out\n",
            staircase ? "staircase" : "turned", excluded, WINDOW_R + 1);
    /* Drawn turned, the mask's pixel squares stand up to 0.7 px proud of the edge, and a ray a few degrees off
     * the surface meets one up to 0.7 / sin(angle) px before the analytic edge: there the point is held to
     * 0.5 px across the surface, and to 0.5 px from the analytic intersection on rays 15° or more off it. */
    report(staircase ? "box 120x60 drawn at 0.37 rad in the mask" : "box 120x60 mask turned 0.37 rad", &e,
           staircase ? 15 : 0);
    pp_world_destroy(w);
}

Test(raycast, rotated_box_1000_rays_point_within_half_a_pixel_normal_within_2_degrees) { box_accuracy(false); }

Test(raycast, box_drawn_rotated_in_the_mask_1000_rays_point_within_half_a_pixel_normal_within_2_degrees)
{
    box_accuracy(true);
}

Test(raycast, disc_1000_rays_point_within_half_a_pixel_normal_within_2_degrees)
{
    enum { R = 50 };
    const double cx = 300, cy = 250;
    pp_world w = make_world(0, 0);
    add_disc(w, body_def(PP_BODY_STATIC, (float)cx, (float)cy, 0.2f), R);
    static ray_errors e;
    memset(&e, 0, sizeof e);
    uint64_t seed = 7;
    while (e.n < 1000) {
        const double phi = 2 * M_PI * rnd(&seed), dist = R + 5 + 150 * rnd(&seed);
        const double psi = 2 * M_PI * rnd(&seed), rr = R * sqrt(rnd(&seed));
        const pp_vec2 from = v2((float)(cx + dist * cos(phi)), (float)(cy + dist * sin(phi)));
        const pp_vec2 to = v2((float)(2 * (cx + rr * cos(psi)) - from.x), (float)(2 * (cy + rr * sin(psi)) - from.y));
        /* Ray–circle: |f + t·d|² = R², the smaller root. */
        const double fx = from.x - cx, fy = from.y - cy, dx = to.x - from.x, dy = to.y - from.y;
        const double qa = dx * dx + dy * dy, qb = 2 * (fx * dx + fy * dy), qc = fx * fx + fy * fy - R * R;
        const double t = (-qb - sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
        const double hx = fx + t * dx, hy = fy + t * dy;
        int32_t hit = 0;
        const pp_raycast_hit h = cast(w, from, to, ALL_BITS, &hit);
        cr_assert_eq(hit, 1, "ray %d missed the disc", e.n);
        const double incidence = RAD2DEG(asin(fabs(hx * dx + hy * dy) / (R * sqrt(qa))));
        record(&e, hypot(h.point.x - (cx + hx), h.point.y - (cy + hy)), fabs(hypot(h.point.x - cx, h.point.y - cy) - R),
               angle_between_deg(h.normal.x, h.normal.y, hx, hy), incidence);
    }
    report("disc r = 50", &e, 0);
    pp_world_destroy(w);
}

/* The march against a brute force: a 600×300 mask of scattered single pixels and 1 px lines (most tiles
 * empty, the rest mixed), 2,000 random segments; the first pixel square each segment enters, by testing
 * every solid pixel. Features this thin hold no straight edge across the 4 px window, so the point stays
 * where the ray enters the pixel and the fraction must match to 1e-3 px. Rays that only graze the square
 * they hit (inside it for under 1e-4 of their length) are drawn again. */
Test(raycast, the_march_finds_the_first_pixel_a_brute_force_finds)
{
    enum { MW = 600, MH = 300 };
    uint8_t *m = calloc(MW * MH, 1);
    uint64_t seed = 5;
    for (int k = 0; k < MW * MH / 500; k++)
        m[(int)(rnd(&seed) * MH) * MW + (int)(rnd(&seed) * MW)] = 1;
    for (int k = 0; k < 6; k++) {
        const int y = (int)(rnd(&seed) * MH), x = (int)(rnd(&seed) * MW);
        for (int i = 0; i < MW / 3; i++)
            m[y * MW + (x + i) % MW] = 1, m[((y + i) % MH) * MW + x] = 1;
    }
    int n = 0;
    int *px = malloc(sizeof *px * MW * MH), *py = malloc(sizeof *py * MW * MH);
    for (int y = 0; y < MH; y++)
        for (int x = 0; x < MW; x++)
            if (m[y * MW + x])
                px[n] = x, py[n] = y, n++;
    pp_world w = make_world(0, 0);
    /* Bitmap (x, y) is world (x + 100, y + 100). */
    pp_body_def d = body_def(PP_BODY_STATIC, 100 + MW / 2, 100 + MH / 2, 0);
    d.width = MW, d.height = MH, d.mask = m;
    create_body_ok(w, &d);
    int tested = 0, hits = 0;
    while (tested < 2000) {
        const pp_vec2 from = v2((float)(50 + 700 * rnd(&seed)), (float)(50 + 400 * rnd(&seed)));
        const double len = 5 + 400 * rnd(&seed), a = 2 * M_PI * rnd(&seed);
        const pp_vec2 to = v2((float)(from.x + len * cos(a)), (float)(from.y + len * sin(a)));
        const double ax = from.x - 100.0, ay = from.y - 100.0, dx = to.x - (double)from.x, dy = to.y - (double)from.y;
        double best = INFINITY, inside = 0;
        for (int k = 0; k < n; k++) {
            double t0 = 0, t1 = 1;
            const double o[2] = {ax, ay}, v[2] = {dx, dy}, lo[2] = {px[k], py[k]};
            for (int j = 0; j < 2 && t0 <= t1; j++) {
                if (v[j] == 0) {
                    if (o[j] < lo[j] || o[j] >= lo[j] + 1)
                        t0 = 2;
                    continue;
                }
                const double u = (lo[j] - o[j]) / v[j], e = (lo[j] + 1 - o[j]) / v[j];
                t0 = fmax(t0, fmin(u, e)), t1 = fmin(t1, fmax(u, e));
            }
            if (t0 <= t1 && t0 < best)
                best = t0, inside = t1 - t0;
        }
        if (best < INFINITY && inside < 1e-4)
            continue;
        int32_t hit = 0;
        const pp_raycast_hit h = cast(w, from, to, ALL_BITS, &hit);
        cr_assert_eq(hit, best < INFINITY, "ray %d: hit %d, the brute force %s", tested, hit,
                     best < INFINITY ? "hits" : "misses");
        if (hit) {
            cr_assert_leq(fabs(h.fraction - best) * hypot(dx, dy), 1e-3,
                          "ray %d (%g, %g)-(%g, %g): fraction %.7f, brute force %.7f", tested, from.x, from.y, to.x,
                          to.y, h.fraction, best);
            hits++;
        }
        tested++;
    }
    cr_assert_gt(hits, 400, "only %d of the rays hit: too few to test", hits);
    cr_assert_lt(hits, 1900, "%d of the rays hit: too few misses to test", hits);
    free(px), free(py), free(m);
    pp_world_destroy(w);
}

/* ---- holes, starts inside, misses, filters, the nearest body --------------------------------------- */

Test(raycast, rays_pass_through_a_hole_erased_a_step_before)
{
    pp_world w = make_world(0, 980);
    /* A 20 px thick wall (x 290..310), a second one behind it (x 490..510). */
    const pp_body wall = add_rect(w, body_def(PP_BODY_STATIC, 300, 300, 0), 20, 240);
    const pp_body back = add_rect(w, body_def(PP_BODY_STATIC, 500, 300, 0), 20, 240);
    int32_t changed = 0;
    /* Radius 30 at the wall's centre line: the hole goes right through for |y − 300| < √(30² − 10²) ≈ 28.3. */
    PP_OK_OR_FAIL(pp_body_erase_circle(w, wall, v2(300, 300), 30, &changed));
    cr_assert_gt(changed, 0);
    PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
    for (int k = -25; k <= 25; k += 5) {
        const float y = 300.5f + (float)k;
        int32_t hit = 0;
        pp_raycast_hit h = cast(w, v2(100, y), v2(700, y), ALL_BITS, &hit);
        cr_assert_eq(hit, 1, "the ray at y %g hit nothing; the back wall is behind the hole", y);
        cr_assert_eq(h.body.id, back.id, "the ray at y %g stopped in the hole", y);
        cr_assert_float_eq(h.point.x, 490, 0.5f);
        /* Without the back wall it misses everything. */
        h = cast(w, v2(100, y), v2(450, y), ALL_BITS, &hit);
        cr_assert_eq(hit, 0, "the ray at y %g hit body %llu at x %g", y, (unsigned long long)h.body.id, h.point.x);
    }
    for (int k = 36; k <= 100; k += 8) {
        for (int side = -1; side <= 1; side += 2) {
            const float y = 300.5f + (float)(side * k);
            int32_t hit = 0;
            const pp_raycast_hit h = cast(w, v2(100, y), v2(700, y), ALL_BITS, &hit);
            cr_assert_eq(hit, 1);
            cr_assert_eq(h.body.id, wall.id, "the ray at y %g passed the wall beside the hole", y);
            cr_assert_float_eq(h.point.x, 290, 0.5f, "the ray at y %g hit the wall at x %g", y, h.point.x);
            cr_assert_float_eq(h.point.y, y, 1e-4f);
            cr_assert_float_eq(h.fraction, (290 - 100) / 600.0f, 0.5f / 600);
            cr_assert_leq(angle_between_deg(h.normal.x, h.normal.y, -1, 0), 2.0, "normal (%g, %g)", h.normal.x,
                          h.normal.y);
        }
    }
    pp_world_destroy(w);
}

Test(raycast, a_ray_starting_inside_hits_at_fraction_0_reversed)
{
    pp_world w = make_world(0, 0);
    const pp_body b = add_rect(w, body_def(PP_BODY_DYNAMIC, 200, 200, 0.3f), 40, 40);
    int32_t hit = 0;
    const pp_vec2 from = v2(203, 198), to = v2(260, 230);
    const pp_raycast_hit h = cast(w, from, to, ALL_BITS, &hit);
    cr_assert_eq(hit, 1);
    cr_assert_eq(h.body.id, b.id);
    cr_assert_eq(h.fraction, 0.0f);
    cr_assert(h.point.x == from.x && h.point.y == from.y, "point (%g, %g)", h.point.x, h.point.y);
    const double len = hypot(to.x - from.x, to.y - from.y);
    cr_assert_float_eq(h.normal.x, -(to.x - from.x) / len, 1e-6);
    cr_assert_float_eq(h.normal.y, -(to.y - from.y) / len, 1e-6);
    cr_assert_eq(h.reserved, 0u);
    /* A zero-length ray is a point test: inside it hits with a zero normal, outside it misses. */
    pp_raycast_hit z = cast(w, from, from, ALL_BITS, &hit);
    cr_assert_eq(hit, 1);
    cr_assert(z.fraction == 0 && z.point.x == from.x && z.point.y == from.y && z.normal.x == 0 && z.normal.y == 0);
    z = cast(w, v2(100, 100), v2(100, 100), ALL_BITS, &hit);
    cr_assert_eq(hit, 0);
    pp_world_destroy(w);
}

Test(raycast, a_miss_reports_0_and_zeroes_out)
{
    pp_world w = make_world(0, 0);
    add_rect(w, body_def(PP_BODY_STATIC, 200, 200, 0), 40, 40);
    int32_t hit = 7;
    /* Passing beside the box, stopping short of it, and pointing away from it. */
    const pp_vec2 rays[][2] = {{{100, 230}, {300, 230}}, {{100, 200}, {170, 200}}, {{150, 200}, {50, 200}}};
    for (int k = 0; k < 3; k++) {
        const pp_raycast_hit h = cast(w, rays[k][0], rays[k][1], ALL_BITS, &hit);
        cr_assert_eq(hit, 0, "ray %d hit", k);
        const pp_raycast_hit zero = {0};
        cr_assert(!memcmp(&h, &zero, sizeof h), "ray %d: out is not zeroed on a miss", k);
    }
    /* The ray ending exactly on the face reaches it. */
    const pp_raycast_hit h = cast(w, v2(100, 200), v2(180, 200), ALL_BITS, &hit);
    cr_assert_eq(hit, 1);
    cr_assert_float_eq(h.point.x, 180, 0.02);
    pp_world_destroy(w);
}

Test(raycast, mask_bits_filter_the_bodies_a_ray_sees)
{
    pp_world w = make_world(0, 0);
    pp_body_def d = body_def(PP_BODY_STATIC, 200, 200, 0);
    d.category_bits = 2;
    const pp_body front = add_rect(w, d, 20, 100);
    d = body_def(PP_BODY_KINEMATIC, 300, 200, 0);
    d.category_bits = 4;
    const pp_body back = add_rect(w, d, 20, 100);
    int32_t hit;
    pp_raycast_hit h = cast(w, v2(100, 200), v2(400, 200), 2 | 4, &hit);
    cr_assert(hit && h.body.id == front.id);
    h = cast(w, v2(100, 200), v2(400, 200), 4, &hit);
    cr_assert(hit && h.body.id == back.id);
    cr_assert_float_eq(h.point.x, 290, 0.5f);
    h = cast(w, v2(100, 200), v2(400, 200), 1 | 8, &hit);
    cr_assert_eq(hit, 0);
    /* The queries filter alike. */
    pp_body out[4];
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_query_aabb(w, v2(150, 150), v2(350, 250), 4, out, 4, &n));
    cr_assert(n == 1 && out[0].id == back.id);
    PP_OK_OR_FAIL(pp_world_query_point(w, v2(200, 200), 4, out, 4, &n));
    cr_assert_eq(n, 0);
    PP_OK_OR_FAIL(pp_world_query_circle(w, v2(250, 200), 60, 2, out, 4, &n));
    cr_assert(n == 1 && out[0].id == front.id);
    pp_world_destroy(w);
}

Test(raycast, the_nearest_body_wins_even_behind_an_earlier_box)
{
    pp_world w = make_world(0, 0);
    /* A long bar at 45° (made first, so it takes the lower slot) whose box contains a small crate in front
     * of it: the ray enters the bar's box first but meets the crate's pixels first. */
    const pp_body bar = add_rect(w, body_def(PP_BODY_STATIC, 300, 300, (float)(M_PI / 4)), 200, 20);
    const pp_body crate = add_rect(w, body_def(PP_BODY_DYNAMIC, 250, 300, 0), 10, 10);
    int32_t hit;
    pp_raycast_hit h = cast(w, v2(200, 300.5f), v2(400, 300.5f), ALL_BITS, &hit);
    cr_assert_eq(hit, 1);
    cr_assert_eq(h.body.id, crate.id, "hit body %llu, not the crate in front", (unsigned long long)h.body.id);
    cr_assert_float_eq(h.point.x, 245, 0.5f);
    /* From the other side the bar is first. */
    h = cast(w, v2(400, 300.5f), v2(200, 300.5f), ALL_BITS, &hit);
    cr_assert(hit && h.body.id == bar.id);
    cr_assert_float_eq(h.point.x, 300.5 + 10 * sqrt(2.0), 0.5f);
    /* Many bodies along one ray: the nearest is the first crate along it whatever the slot order. */
    for (int k = 0; k < 300; k++)
        add_rect(w, body_def(PP_BODY_DYNAMIC, 1000 - 2.5f * k, 600, 0), 2, 2);
    h = cast(w, v2(100, 600), v2(1100, 600), ALL_BITS, &hit);
    cr_assert(hit);
    cr_assert_float_eq(h.point.x, 1000 - 2.5f * 299 - 1, 1e-3);
    pp_world_destroy(w);
}

/* An allocator that fails on demand: a ray over more boxes than the call's stack holds sorts them on the
 * heap, and without memory walks them in slot order instead, with the same answer. */
static bool alloc_fails;
static void *flaky_alloc(uint64_t size, void *user) { return alloc_fails ? NULL : malloc(size); }
static void *flaky_realloc(void *p, uint64_t size, void *user) { return alloc_fails ? NULL : realloc(p, size); }
static void flaky_free(void *p, void *user) { free(p); }

Test(raycast, a_ray_over_many_boxes_needs_no_memory)
{
    const pp_allocator a = {flaky_alloc, flaky_realloc, flaky_free, NULL};
    PP_OK_OR_FAIL(pp_set_allocator(&a));
    pp_world w = make_world(0, 0);
    for (int k = 0; k < 400; k++) /* crates along y 600, the nearest to x = 0 made last */
        add_rect(w, body_def(PP_BODY_DYNAMIC, 1100 - 2.5f * k, 600, 0), 2, 2);
    pp_raycast_hit with, without;
    int32_t hit_with = 0, hit_without = 0;
    PP_OK_OR_FAIL(pp_world_raycast(w, v2(0, 600), v2(1200, 600), ALL_BITS, &with, &hit_with));
    alloc_fails = true;
    const pp_status st = pp_world_raycast(w, v2(0, 600), v2(1200, 600), ALL_BITS, &without, &hit_without);
    alloc_fails = false;
    cr_assert_eq(st, PP_OK, "%s (%s)", pp_status_name(st), pp_last_error());
    cr_assert(hit_with && hit_without);
    cr_assert(!memcmp(&with, &without, sizeof with), "the answers differ");
    cr_assert_float_eq(with.point.x, 1100 - 2.5f * 399 - 1, 1e-3);
    pp_world_destroy(w);
    PP_OK_OR_FAIL(pp_set_allocator(NULL));
}

/* ---- queries against a brute force --------------------------------------------------------------- */

/* A body as the brute force sees it: its pose, through the public calls, and its solid pixels. */
typedef struct probe_body {
    pp_body b;
    uint32_t category;
    double px, py, c, s, pivx, pivy;
    int n, w, h;         /* solid pixels, bitmap size */
    int32_t *x, *y;      /* solid pixels */
    double *wx, *wy;     /* their centres in the world */
} probe_body;

static probe_body *probe_world(pp_world w, int *count)
{
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, NULL, 0, &n));
    pp_body *ids = malloc(sizeof *ids * (size_t)n);
    PP_OK_OR_FAIL(pp_world_get_bodies(w, ids, n, &n));
    probe_body *pb = calloc((size_t)n, sizeof *pb);
    for (int i = 0; i < n; i++) {
        probe_body *p = &pb[i];
        p->b = ids[i];
        pp_vec2 pos, piv;
        float a;
        int32_t wd, ht;
        PP_OK_OR_FAIL(pp_body_get_position(w, ids[i], &pos));
        PP_OK_OR_FAIL(pp_body_get_angle(w, ids[i], &a));
        PP_OK_OR_FAIL(pp_body_get_pivot(w, ids[i], &piv));
        PP_OK_OR_FAIL(pp_body_get_size(w, ids[i], &wd, &ht));
        p->w = wd, p->h = ht;
        p->px = pos.x, p->py = pos.y, p->c = cos((double)a), p->s = sin((double)a), p->pivx = piv.x, p->pivy = piv.y;
        uint8_t *m = malloc((size_t)wd * ht);
        PP_OK_OR_FAIL(pp_body_read_mask(w, ids[i], m, (int64_t)wd * ht));
        for (int k = 0; k < wd * ht; k++)
            p->n += m[k] != 0;
        p->x = malloc(sizeof *p->x * (size_t)p->n), p->y = malloc(sizeof *p->y * (size_t)p->n);
        p->wx = malloc(sizeof *p->wx * (size_t)p->n), p->wy = malloc(sizeof *p->wy * (size_t)p->n);
        int j = 0;
        for (int y = 0; y < ht; y++)
            for (int x = 0; x < wd; x++)
                if (m[y * wd + x]) {
                    const double lx = x + 0.5 - p->pivx, ly = y + 0.5 - p->pivy;
                    p->x[j] = x, p->y[j] = y;
                    p->wx[j] = p->px + p->c * lx - p->s * ly, p->wy[j] = p->py + p->s * lx + p->c * ly;
                    j++;
                }
        free(m);
    }
    free(ids);
    *count = n;
    return pb;
}

static void free_probe(probe_body *pb, int n)
{
    for (int i = 0; i < n; i++)
        free(pb[i].x), free(pb[i].y), free(pb[i].wx), free(pb[i].wy);
    free(pb);
}

/* The expected answer of a query in slot order (the order of pp_world_get_bodies); *margin receives how
 * close any pixel came to the rule's boundary, px, so that samples closer than 1e-3 px are drawn again:
 * the brute force computes in double from the pose the public calls give, as the library does, and
 * agrees exactly in practice; the margin keeps it from depending on the last bit of a rounding. */
enum { Q_POINT, Q_BOX, Q_CIRCLE };

static int brute(const probe_body *pb, int n, int kind, const double *q, uint32_t mask, pp_body *out, double *margin)
{
    int count = 0;
    *margin = INFINITY;
    for (int i = 0; i < n; i++) {
        const probe_body *p = &pb[i];
        bool in = false;
        if (kind == Q_POINT) {
            const double dx = q[0] - p->px, dy = q[1] - p->py;
            const double lx = p->pivx + p->c * dx + p->s * dy, ly = p->pivy - p->s * dx + p->c * dy;
            if (lx > -1 && ly > -1 && lx < p->w + 1 && ly < p->h + 1)
                *margin = fmin(*margin, fmin(fabs(lx - round(lx)), fabs(ly - round(ly))));
            for (int k = 0; k < p->n && !in; k++)
                in = p->x[k] <= lx && lx < p->x[k] + 1 && p->y[k] <= ly && ly < p->y[k] + 1;
        } else {
            for (int k = 0; k < p->n; k++) {
                const double x = p->wx[k], y = p->wy[k];
                double m;
                if (kind == Q_BOX) {
                    const bool inside = x >= q[0] && x <= q[2] && y >= q[1] && y <= q[3];
                    in |= inside;
                    m = inside ? fmin(fmin(x - q[0], q[2] - x), fmin(y - q[1], q[3] - y))
                               : hypot(fmax(fmax(q[0] - x, x - q[2]), 0), fmax(fmax(q[1] - y, y - q[3]), 0));
                } else {
                    const double dd = hypot(x - q[0], y - q[1]);
                    in |= dd <= q[2];
                    m = fabs(dd - q[2]);
                }
                *margin = fmin(*margin, m);
            }
        }
        if (in && (p->category & mask))
            out[count++] = p->b;
    }
    return count;
}

Test(raycast, queries_agree_with_a_brute_force_over_every_pixel, .timeout = 120)
{
    pp_world w = make_world(0, 0);
    uint64_t seed = 2024;
    const pp_body_type types[3] = {PP_BODY_STATIC, PP_BODY_DYNAMIC, PP_BODY_KINEMATIC};
    pp_body made[60];
    for (int i = 0; i < 60; i++) {
        const int wd = 4 + (int)(60 * rnd(&seed)), ht = 4 + (int)(60 * rnd(&seed));
        pp_body_def d = body_def(types[i % 3], (float)(40 + 520 * rnd(&seed)), (float)(40 + 520 * rnd(&seed)),
                                 (float)(2 * M_PI * rnd(&seed)));
        d.category_bits = 1u << (i % 3);
        uint8_t *m = calloc((size_t)wd * ht, 1);
        const int shape = i % 4;
        for (int y = 0; y < ht; y++)
            for (int x = 0; x < wd; x++) {
                const double u = (x + 0.5) / wd - 0.5, v = (y + 0.5) / ht - 0.5;
                m[y * wd + x] = shape == 0 || (shape == 1 && u * u + v * v <= 0.25) ||
                                (shape == 2 && (fabs(u) > 0.3 || fabs(v) > 0.3)) || (shape == 3 && rnd(&seed) < 0.6);
            }
        d.width = wd, d.height = ht, d.mask = m;
        if (i % 5 == 0)
            d.custom_pivot = 1, d.pivot = v2((float)(wd * rnd(&seed)), (float)(ht * rnd(&seed)));
        const pp_body b = made[i] = create_body_ok(w, &d);
        free(m);
        if (i % 4 == 0) { /* a hole in a full rectangle, off centre: at most a notch, never a split */
            pp_vec2 p = body_pos(w, b);
            PP_OK_OR_FAIL(pp_body_erase_circle(w, b, v2(p.x + 3, p.y - 2), (float)(0.25 * fmin(wd, ht)), NULL));
        }
    }
    int n;
    probe_body *pb = probe_world(w, &n);
    cr_assert_eq(n, 60, "an erase split a body: %d bodies", n);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < 60; j++)
            if (made[j].id == pb[i].b.id)
                pb[i].category = 1u << (j % 3);
    int per_kind[3] = {0}, hits[3] = {0}, redrawn = 0;
    for (int kind = 0; kind < 3; kind++)
        while (per_kind[kind] < 500) {
            double q[4] = {0, 0, 0, 0};
            q[0] = 600 * rnd(&seed), q[1] = 600 * rnd(&seed);
            if (kind == Q_BOX)
                q[2] = q[0] + 80 * rnd(&seed), q[3] = q[1] + 80 * rnd(&seed);
            if (kind == Q_CIRCLE)
                q[2] = 50 * rnd(&seed);
            /* The float values the call receives. */
            for (int k = 0; k < 4; k++)
                q[k] = (float)q[k];
            const uint32_t mask = rnd(&seed) < 0.25 ? 1u << (int)(3 * rnd(&seed)) : ALL_BITS;
            pp_body want[512], got[512];
            double margin;
            const int nw = brute(pb, n, kind, q, mask, want, &margin);
            if (margin < 1e-3) {
                redrawn++;
                continue;
            }
            int32_t ng = -1;
            if (kind == Q_POINT)
                PP_OK_OR_FAIL(pp_world_query_point(w, v2((float)q[0], (float)q[1]), mask, got, 512, &ng));
            else if (kind == Q_BOX)
                PP_OK_OR_FAIL(pp_world_query_aabb(w, v2((float)q[0], (float)q[1]), v2((float)q[2], (float)q[3]), mask,
                                                  got, 512, &ng));
            else
                PP_OK_OR_FAIL(pp_world_query_circle(w, v2((float)q[0], (float)q[1]), (float)q[2], mask, got, 512, &ng));
            cr_assert_eq(ng, nw, "query kind %d #%d (%g, %g, %g, %g) mask %x: %d bodies, brute force %d", kind,
                         per_kind[kind], q[0], q[1], q[2], q[3], mask, ng, nw);
            for (int k = 0; k < nw; k++)
                cr_assert_eq(got[k].id, want[k].id, "query kind %d #%d: body %d differs", kind, per_kind[kind], k);
            hits[kind] += nw > 0;
            per_kind[kind]++;
        }
    fprintf(stderr, "queries vs brute force: %d bodies; samples with a body: point %d, box %d, circle %d of 500 each; "
                    "%d samples within 1e-3 px of a pixel boundary drawn again\n",
            n, hits[0], hits[1], hits[2], redrawn);
    cr_assert_gt(hits[0], 30);
    cr_assert_gt(hits[1], 150);
    cr_assert_gt(hits[2], 100);
    free_probe(pb, n);
    pp_world_destroy(w);
}

Test(raycast, query_circle_names_the_bodies_erase_circle_changes)
{
    pp_world w = make_world(0, 0);
    uint64_t seed = 99;
    for (int i = 0; i < 20; i++)
        add_disc(w, body_def(PP_BODY_STATIC, (float)(50 + 400 * rnd(&seed)), (float)(50 + 400 * rnd(&seed)),
                             (float)rnd(&seed)),
                 5 + (int)(20 * rnd(&seed)));
    for (int k = 0; k < 200; k++) {
        const pp_vec2 c = v2((float)(500 * rnd(&seed)), (float)(500 * rnd(&seed)));
        const float r = (float)(30 * rnd(&seed));
        pp_body named[32];
        int32_t n = 0, erased = 0;
        PP_OK_OR_FAIL(pp_world_query_circle(w, c, r, ALL_BITS, named, 32, &n));
        /* Each named body loses pixels to the erase, and the total erased is zero iff none is named. */
        for (int i = 0; i < n; i++) {
            int32_t changed = 0;
            PP_OK_OR_FAIL(pp_body_erase_circle(w, named[i], c, r, &changed));
            cr_assert_gt(changed, 0, "circle %d: a named body lost no pixel", k);
        }
        PP_OK_OR_FAIL(pp_world_erase_circle(w, c, r, &erased));
        cr_assert_eq(erased, 0, "circle %d: the erase changed %d pixels of bodies not named", k, erased);
    }
    pp_world_destroy(w);
}

/* ---- misuse ---------------------------------------------------------------------------------------- */

Test(raycast, misuse_gives_exact_status_codes)
{
    pp_world w = make_world(0, 0);
    add_rect(w, body_def(PP_BODY_STATIC, 100, 100, 0), 20, 20);
    add_rect(w, body_def(PP_BODY_STATIC, 110, 100, 0), 20, 20);
    add_rect(w, body_def(PP_BODY_STATIC, 120, 100, 0), 20, 20);
    pp_raycast_hit h;
    int32_t hit, n;
    pp_body out[2];
    const float nan = NAN, inf = INFINITY;
    EXPECT_ERR(pp_world_raycast(w, v2(0, 0), v2(1, 1), ALL_BITS, NULL, &hit), PP_ERR_INVALID_ARGUMENT, "out");
    EXPECT_ERR(pp_world_raycast(w, v2(0, 0), v2(1, 1), ALL_BITS, &h, NULL), PP_ERR_INVALID_ARGUMENT, "hit");
    EXPECT_ERR(pp_world_raycast(w, v2(nan, 0), v2(1, 1), ALL_BITS, &h, &hit), PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_world_raycast(w, v2(0, 0), v2(1, inf), ALL_BITS, &h, &hit), PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_world_query_point(w, v2(nan, 0), ALL_BITS, out, 2, &n), PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_world_query_point(w, v2(0, 0), ALL_BITS, out, 2, NULL), PP_ERR_INVALID_ARGUMENT, "count");
    EXPECT_ERR(pp_world_query_point(w, v2(0, 0), ALL_BITS, NULL, 2, &n), PP_ERR_INVALID_ARGUMENT, "out");
    EXPECT_ERR(pp_world_query_point(w, v2(0, 0), ALL_BITS, out, -1, &n), PP_ERR_INVALID_ARGUMENT, "capacity");
    EXPECT_ERR(pp_world_query_aabb(w, v2(10, 0), v2(0, 10), ALL_BITS, out, 2, &n), PP_ERR_INVALID_ARGUMENT, "lower");
    EXPECT_ERR(pp_world_query_aabb(w, v2(0, 0), v2(inf, 10), ALL_BITS, out, 2, &n), PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_world_query_aabb(w, v2(0, 0), v2(1, 1), ALL_BITS, out, 2, NULL), PP_ERR_INVALID_ARGUMENT, "count");
    EXPECT_ERR(pp_world_query_circle(w, v2(0, 0), -1, ALL_BITS, out, 2, &n), PP_ERR_INVALID_ARGUMENT, "radius");
    EXPECT_ERR(pp_world_query_circle(w, v2(0, 0), nan, ALL_BITS, out, 2, &n), PP_ERR_INVALID_ARGUMENT, "radius");
    EXPECT_ERR(pp_world_query_circle(w, v2(0, nan), 1, ALL_BITS, out, 2, &n), PP_ERR_INVALID_ARGUMENT, "finite");
    EXPECT_ERR(pp_world_query_circle(w, v2(0, 0), 1, ALL_BITS, NULL, 2, &n), PP_ERR_INVALID_ARGUMENT, "out");
    /* Short capacity: count is the total, the first capacity bodies written (in slot order). */
    n = -1;
    PP_OK_OR_FAIL(pp_world_query_aabb(w, v2(0, 0), v2(200, 200), ALL_BITS, out, 2, &n));
    cr_assert_eq(n, 3);
    PP_OK_OR_FAIL(pp_world_query_circle(w, v2(110, 100), 5, ALL_BITS, NULL, 0, &n));
    cr_assert_eq(n, 3);
    PP_OK_OR_FAIL(pp_world_query_point(w, v2(105, 100), ALL_BITS, out, 1, &n));
    cr_assert_eq(n, 2);
    /* Radius 0 is a point of the rule: the pixel centre must lie on it. */
    PP_OK_OR_FAIL(pp_world_query_circle(w, v2(100.5f, 100.5f), 0, ALL_BITS, out, 2, &n));
    cr_assert_eq(n, 2);
    PP_OK_OR_FAIL(pp_world_query_circle(w, v2(100.6f, 100.5f), 0, ALL_BITS, out, 2, &n));
    cr_assert_eq(n, 0);
    PP_OK_OR_FAIL(pp_world_destroy(w));
    EXPECT_ERR(pp_world_raycast(w, v2(0, 0), v2(1, 1), ALL_BITS, &h, &hit), PP_ERR_INVALID_HANDLE, "world|handle");
    EXPECT_ERR(pp_world_query_point(w, v2(0, 0), ALL_BITS, out, 2, &n), PP_ERR_INVALID_HANDLE, "world|handle");
    EXPECT_ERR(pp_world_query_aabb(w, v2(0, 0), v2(1, 1), ALL_BITS, out, 2, &n), PP_ERR_INVALID_HANDLE, "world|handle");
    EXPECT_ERR(pp_world_query_circle(w, v2(0, 0), 1, ALL_BITS, out, 2, &n), PP_ERR_INVALID_HANDLE, "world|handle");
}
