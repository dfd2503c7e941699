/* Rays and region queries against the bodies' pixels. pp_world_raycast walks each candidate body's
 * pixel grid in the body's own frame (an exact DDA that jumps empty 8×8 tiles) and estimates the
 * surface from the mask around the pixel it meets; the point, box and circle queries read only the
 * bitmap rows their shape covers. Bodies are filtered by category bits; sensors are passed by. */
#include "alloc.h"
#include "awake.h"
#include "cover.h"
#include "status.h"
#include "world.h"

#include <stdlib.h>

/* Rays and queries pass sensors by. */
static bool ray_skips(const body *bd)
{
    return bd->is_sensor;
}

static bool queried(const body *bd, uint32_t mask_bits)
{
    return bd && (bd->category_bits & mask_bits) != 0 && !ray_skips(bd) && !raster_empty(&bd->raster);
}

/* World bounds are compared with this slack: they are a prefilter, and a pixel exactly on a box's
 * edge must not be lost to the rounding of the box. px. */
#define QUERY_SLACK 1e-3

/* ---- rays ---------------------------------------------------------------------------------------- */

/* The windows that read the surface from the mask, under the taper w = 1 − ρ²/R² (ρ from the window's
 * centre). Picked by measurement on 1,000 rays against a disc of radius 50 and a box drawn turned in its
 * mask (tests/c/test_raycast.c, figures in the README): the lattice's first moment converges slowly, so
 * the normal needs R = 8 for 2° (R = 5 leaves 5°, and the taper (1 − ρ²/R²)² does worse than this one);
 * the edge's offset comes from a 4 px window, which a curved edge bends less. */
#define RAY_WINDOW 8      /* px: the normal's window */
#define RAY_EDGE_WINDOW 4 /* px: the window that places the edge along the normal */
#define RAY_MISFIT 0.08   /* the most of the edge window's weight that may disagree with the edge line */

/* Which faces of its pixel a ray entered through: bit 0 a vertical edge (x), bit 1 a horizontal one. */
enum { FACE_X = 1, FACE_Y = 2 };

typedef struct pixel_hit {
    double t;        /* along the segment, where it enters the pixel's square */
    int32_t x, y;    /* the pixel, bitmap px */
    int face;        /* FACE_* bits; 0 when the segment starts inside the pixel */
} pixel_hit;

/* Clip p + t·d, t ∈ [*t0, *t1], to the box [x0, x1] × [y0, y1] (a slab test); *face receives the
 * FACE_* bits of the slabs that set the entry. False when the segment misses the box. */
static bool clip_segment(dvec2 p, dvec2 d, double x0, double y0, double x1, double y1, double *t0, double *t1,
                         int *face)
{
    const double lo[2] = {x0, y0}, hi[2] = {x1, y1}, o[2] = {p.x, p.y}, v[2] = {d.x, d.y};
    *face = 0;
    for (int k = 0; k < 2; k++) {
        if (v[k] == 0) {
            if (o[k] < lo[k] || o[k] > hi[k])
                return false;
            continue;
        }
        double a = (lo[k] - o[k]) / v[k], b = (hi[k] - o[k]) / v[k];
        if (a > b) {
            const double s = a;
            a = b, b = s;
        }
        if (a > *t0)
            *t0 = a, *face = 1 << k;
        else if (a == *t0 && a > 0)
            *face |= 1 << k;
        if (b < *t1)
            *t1 = b;
        if (*t0 > *t1)
            return false;
    }
    return true;
}

/* The cell of coordinate v on one axis of [lo, hi): floor(v), or the box's edge cell when v lies
 * outside it but the ray moves inward (the entry point rounded); INT32_MIN when the ray does not
 * enter along this axis. */
static int32_t entry_cell(double v, int32_t lo, int32_t hi, int step)
{
    const double f = floor(v);
    if (f >= lo && f < hi)
        return (int32_t)f;
    if (f < lo && step > 0)
        return lo;
    if (f >= hi && step < 0)
        return hi - 1;
    return INT32_MIN;
}

/* The step of a direction component, 0 when it is too small to cross a pixel (1/v overflows). */
static int axis_step(double v) { return isfinite(1.0 / v) ? (v > 0) - (v < 0) : 0; }

/* Where the ray a + t·d crosses the grid line `edge` on an axis, in t; infinite without a step. */
static double cross_at(double edge, double a, double inv, int step) { return step ? (edge - a) * inv : INFINITY; }

/* March the bitmap-frame segment a + t·d, t ∈ [0, 1], through the pixel squares of the solid bounds
 * in order (Amanatides–Woo, stepping both axes at an exact corner), jumping to the exit of every
 * empty 8×8 tile; the first solid pixel it enters, or false. The start pixel is the caller's. */
static bool ray_march(const pp_raster *r, dvec2 a, dvec2 d, pixel_hit *h)
{
    double t = 0, t1 = 1;
    int face;
    if (!clip_segment(a, d, r->x0, r->y0, r->x1, r->y1, &t, &t1, &face))
        return false;
    const int sx = axis_step(d.x), sy = axis_step(d.y);
    if (!sx && !sy)
        return false;
    const double ix = sx ? 1.0 / d.x : 0, iy = sy ? 1.0 / d.y : 0;
    int32_t cx = entry_cell(a.x + t * d.x, r->x0, r->x1, sx), cy = entry_cell(a.y + t * d.y, r->y0, r->y1, sy);
    if (face == 0) /* starting in the box, on its edge when an axis was kept inside it */
        face = (floor(a.x) != cx ? FACE_X : 0) | (floor(a.y) != cy ? FACE_Y : 0);
    while (cx >= r->x0 && cx < r->x1 && cy >= r->y0 && cy < r->y1 && t <= t1) {
        const int32_t tx = cx >> RASTER_TILE_SHIFT, ty = cy >> RASTER_TILE_SHIFT;
        const raster_state st = raster_tile_state(r, tx, ty);
        if (st != RASTER_EMPTY && (st == RASTER_FULL || raster_solid(r, cx, cy))) {
            *h = (pixel_hit){t, cx, cy, face};
            return true;
        }
        /* The box to leave: the empty tile, or the pixel. */
        const int32_t side = st == RASTER_EMPTY ? RASTER_TILE : 1;
        const int32_t bx0 = st == RASTER_EMPTY ? tx << RASTER_TILE_SHIFT : cx, bx1 = bx0 + side;
        const int32_t by0 = st == RASTER_EMPTY ? ty << RASTER_TILE_SHIFT : cy, by1 = by0 + side;
        const double tX = cross_at(sx > 0 ? bx1 : bx0, a.x, ix, sx), tY = cross_at(sy > 0 ? by1 : by0, a.y, iy, sy);
        face = (tX <= tY ? FACE_X : 0) | (tY <= tX ? FACE_Y : 0);
        t = fmin(tX, tY);
        /* Crossing one face, the other coordinate is where the ray is then, kept inside the box. */
        if (face & FACE_X)
            cx = sx > 0 ? bx1 : bx0 - 1;
        else if (st == RASTER_EMPTY)
            cx = (int32_t)fmin(fmax(floor(a.x + t * d.x), bx0), bx1 - 1);
        if (face & FACE_Y)
            cy = sy > 0 ? by1 : by0 - 1;
        else if (st == RASTER_EMPTY)
            cy = (int32_t)fmin(fmax(floor(a.y + t * d.y), by0), by1 - 1);
    }
    return false;
}

/* The first solid pixel of one body on the bitmap-frame segment a + t·d: the start pixel at t = 0
 * (face 0) when it is solid, else the march's. */
static bool body_ray(const body *bd, dvec2 a, dvec2 d, pixel_hit *h)
{
    const pp_raster *r = &bd->raster;
    const double fx = floor(a.x), fy = floor(a.y);
    if (fx >= r->x0 && fx < r->x1 && fy >= r->y0 && fy < r->y1 && raster_solid(r, (int32_t)fx, (int32_t)fy)) {
        *h = (pixel_hit){0, (int32_t)fx, (int32_t)fy, 0};
        return true;
    }
    return ray_march(r, a, d, h);
}

/* What the mask shows within R of a bitmap point c: the unit outward normal n (the area gradient
 * −Σ w·(p − c) over solid pixel centres p) and the signed distance s along n from c to the straight edge
 * that would leave the window's weighted solid fraction. False without a gradient. */
static bool window_surface(const pp_raster *r, dvec2 c, double R, dvec2 *n, double *s)
{
    double gx = 0, gy = 0, solid = 0, total = 0;
    const int32_t x0 = (int32_t)ceil(c.x - R - 0.5), x1 = (int32_t)floor(c.x + R - 0.5);
    const int32_t y0 = (int32_t)ceil(c.y - R - 0.5), y1 = (int32_t)floor(c.y + R - 0.5);
    for (int32_t y = y0; y <= y1; y++)
        for (int32_t x = x0; x <= x1; x++) {
            const double dx = x + 0.5 - c.x, dy = y + 0.5 - c.y, q = 1 - (dx * dx + dy * dy) / (R * R);
            if (q <= 0)
                continue;
            total += q;
            if (raster_solid_clamped(r, x, y))
                solid += q, gx -= q * dx, gy -= q * dy;
        }
    const double g = hypot(gx, gy);
    if (!(g > 1e-9 * total))
        return false;
    *n = dv(gx / g, gy / g);
    /* The taper integrated along a chord at v·R from the centre is ∝ (1 − v²)^(3/2); the weight on the
     * solid side of the edge, as a fraction, rises with v: bisect for the edge. */
    const double f = solid / total;
    double lo = -1, hi = 1;
    for (int k = 0; k < 40; k++) {
        const double v = 0.5 * (lo + hi), u = sqrt(fmax(0.0, 1 - v * v));
        const double below = 0.5 + (v * (5 - 2 * v * v) * u + 3 * asin(v)) / (3 * PP_PI);
        if (below < f)
            lo = v;
        else
            hi = v;
    }
    *s = R * 0.5 * (lo + hi);
    return true;
}

/* How far the mask around c departs from the half-plane n·(p − c) < s: the weight of the pixels on the
 * wrong side, as a fraction of the window's (radius R, the same taper). A straight edge, even a staircase
 * one, leaves only pixels within a pixel of the line wrong. */
static double edge_misfit(const pp_raster *r, dvec2 c, dvec2 n, double s, double R)
{
    double wrong = 0, total = 0;
    const int32_t x0 = (int32_t)ceil(c.x - R - 0.5), x1 = (int32_t)floor(c.x + R - 0.5);
    const int32_t y0 = (int32_t)ceil(c.y - R - 0.5), y1 = (int32_t)floor(c.y + R - 0.5);
    for (int32_t y = y0; y <= y1; y++)
        for (int32_t x = x0; x <= x1; x++) {
            const double dx = x + 0.5 - c.x, dy = y + 0.5 - c.y, q = 1 - (dx * dx + dy * dy) / (R * R);
            if (q <= 0)
                continue;
            total += q;
            if (raster_solid_clamped(r, x, y) != (n.x * dx + n.y * dy < s))
                wrong += q;
        }
    return wrong / total;
}

/* Fill a hit on body bd at pixel h of the bitmap-frame segment a + t·d (world from + t·(to − from)). */
static void ray_result(const body *bd, dvec2 from, dvec2 to, dvec2 a, dvec2 d, const pixel_hit *h,
                       pp_raycast_hit *out)
{
    const dvec2 wd = dv_sub(to, from);
    const double len = dv_norm(wd);
    double t = h->t;
    dvec2 n = {0, 0};
    if (h->face == 0) { /* started inside: the ray's reverse, (0, 0) for a zero-length ray */
        if (len > 0)
            n = dv_scale(wd, -1 / len);
    } else {
        /* Normal: the mask's area gradient in a tapered window at the entry point (the contact normal's
         * estimator). Point: moved along the ray onto the edge line the 4 px window's solid fraction places,
         * where that line fits the mask and lies within 1 px (the squares' staircase misses a turned edge by
         * up to 0.7 px across, far more along a grazing ray); read again there; ≤ R px, within [0, 1]. */
        const double reach = RAY_WINDOW / dv_norm(d), tmin = fmax(0.0, h->t - reach), tmax = fmin(1.0, h->t + reach);
        bool have = false;
        for (int pass = 0; pass < 2; pass++) {
            dvec2 m;
            double s;
            const dvec2 c = dv_add(a, dv_scale(d, t));
            if (!window_surface(&bd->raster, c, RAY_WINDOW, &m, &s) || dv_dot(m, d) >= 0)
                break;
            n = m, have = true;
            /* The offset from a smaller window: a curved edge leaves its tangent by ρ²/2r. */
            dvec2 unused;
            if (!window_surface(&bd->raster, c, RAY_EDGE_WINDOW, &unused, &s) ||
                edge_misfit(&bd->raster, c, m, s, RAY_EDGE_WINDOW) > RAY_MISFIT)
                break;
            if (fabs(s) > 1.0)
                break;
            t = fmin(fmax(t + s / dv_dot(m, d), tmin), tmax);
        }
        if (!have) { /* no gradient, or one facing away from the ray: the face it entered by */
            const int sx = (d.x > 0) - (d.x < 0), sy = (d.y > 0) - (d.y < 0);
            n = h->face == (FACE_X | FACE_Y) ? dv(-sx * sqrt(0.5), -sy * sqrt(0.5))
                : h->face == FACE_X          ? dv(-sx, 0)
                                             : dv(0, -sy);
        }
        n = dv_rot(n, bd->cos_a, bd->sin_a);
    }
    const dvec2 p = h->face == 0 ? from : dv_add(from, dv_scale(wd, t));
    *out = (pp_raycast_hit){bd->handle, {(float)p.x, (float)p.y}, {(float)n.x, (float)n.y}, (float)t, 0};
}

typedef struct ray_candidate {
    double t;     /* where the segment enters the body's world box */
    int32_t slot;
} ray_candidate;

static int candidate_order(const void *pa, const void *pb)
{
    const ray_candidate *a = pa, *b = pb;
    return a->t < b->t ? -1 : a->t > b->t ? 1 : (a->slot > b->slot) - (a->slot < b->slot);
}

/* Of the bodies near the segment from + t·d, t ∈ [0, 1] (`near`, n of them), those passing the filter whose
 * world box the segment meets, into c; returns how many. */
static int32_t ray_candidates(const world *wd, dvec2 from, dvec2 d, uint32_t mask_bits, const int32_t *near, int32_t n,
                              ray_candidate *c)
{
    int32_t m = 0;
    for (int32_t k = 0; k < n; k++) {
        const body *bd = wd->bodies[near[k]];
        double t0 = 0, t1 = 1;
        int face;
        if (queried(bd, mask_bits) &&
            clip_segment(from, d, bd->aabb.x0 - QUERY_SLACK, bd->aabb.y0 - QUERY_SLACK, bd->aabb.x1 + QUERY_SLACK,
                         bd->aabb.y1 + QUERY_SLACK, &t0, &t1, &face))
            c[m++] = (ray_candidate){t0, near[k]};
    }
    return m;
}

/* The nearest hit so far of a ray from + t·d; ties go to the lower slot. */
typedef struct ray_best {
    dvec2 from, d;
    uint32_t mask_bits;
    const body *best;
    pixel_hit hit;
    dvec2 a, dir; /* the segment in the best body's bitmap frame */
} ray_best;

/* The first solid pixel of bd on the world segment from + t·d, with the segment in bd's bitmap frame (a + t·ad;
 * t stays the world segment's). */
static bool body_segment_hit(const body *bd, dvec2 from, dvec2 d, dvec2 *a, dvec2 *ad, pixel_hit *h)
{
    *a = body_world_to_local(bd, from), *ad = dv_unrot(d, bd->cos_a, bd->sin_a);
    return body_ray(bd, *a, *ad, h);
}

static bool ray_try(world *wd, body *bd, void *user)
{
    ray_best *rb = user;
    if (!queried(bd, rb->mask_bits))
        return true;
    dvec2 a, ad;
    pixel_hit h;
    if (body_segment_hit(bd, rb->from, rb->d, &a, &ad, &h) &&
        (!rb->best || h.t < rb->hit.t || (h.t == rb->hit.t && bd->index < rb->best->index)))
        rb->best = bd, rb->hit = h, rb->a = a, rb->dir = ad;
    return true;
}

/* The world box a segment's candidates are looked for in. */
static pp_aabb segment_box(dvec2 f, dvec2 e)
{
    return (pp_aabb){fmin(f.x, e.x) - QUERY_SLACK, fmin(f.y, e.y) - QUERY_SLACK, fmax(f.x, e.x) + QUERY_SLACK,
                     fmax(f.y, e.y) + QUERY_SLACK};
}

PP_API pp_status pp_world_raycast(pp_world w, pp_vec2 from, pp_vec2 to, uint32_t mask_bits, pp_raycast_hit *out,
                                  int32_t *hit)
{
    static const char *fn = "pp_world_raycast";
    world *wd = world_lookup(w, fn);
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!out || !hit)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s is NULL", fn, out ? "hit" : "out");
    if (!finite2(from.x, from.y) || !finite2(to.x, to.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: from and to must be finite, got (%g, %g) and (%g, %g)", fn,
                       from.x, from.y, to.x, to.y);
    const dvec2 f = dv(from.x, from.y), e = dv(to.x, to.y), d = dv_sub(e, f);
    /* Bodies in the order the ray meets their boxes, so that the search stops at the first box past the
     * nearest hit. Many boxes on one ray go to the heap; without memory, every body near the ray is tried. */
    const pp_aabb box = segment_box(f, e);
    int32_t *near = NULL, n_near = 0;
    ray_candidate local[128], *c = NULL;
    if (awake_bodies_in_box(wd, fn, box, &near, &n_near) == PP_OK)
        c = n_near <= 128 ? local : pp_malloc((size_t)n_near * sizeof *c);
    ray_best rb = {.from = f, .d = d, .mask_bits = mask_bits};
    if (c) {
        const int32_t n = ray_candidates(wd, f, d, mask_bits, near, n_near, c);
        qsort(c, (size_t)n, sizeof *c, candidate_order);
        for (int32_t k = 0; k < n && !(rb.best && c[k].t > rb.hit.t); k++)
            ray_try(wd, wd->bodies[c[k].slot], &rb);
    } else {
        awake_each_in_box(wd, box, ray_try, &rb);
    }
    pp_free(near);
    if (c != local)
        pp_free(c);
    *hit = rb.best != NULL;
    if (rb.best)
        ray_result(rb.best, f, e, rb.a, rb.dir, &rb.hit, out);
    else
        *out = (pp_raycast_hit){0};
    return PP_OK;
}

/* One body's first entry of a segment, for pp_world_raycast_all. */
typedef struct ray_entry {
    pixel_hit hit;
    int32_t slot;
    dvec2 a, dir; /* the segment in the body's bitmap frame */
} ray_entry;

static int entry_order(const void *pa, const void *pb)
{
    const ray_entry *a = pa, *b = pb;
    return a->hit.t < b->hit.t ? -1 : a->hit.t > b->hit.t ? 1 : (a->slot > b->slot) - (a->slot < b->slot);
}

PP_API pp_status pp_world_raycast_all(pp_world w, pp_vec2 from, pp_vec2 to, uint32_t mask_bits, pp_raycast_hit *out,
                                      int32_t capacity, int32_t *count)
{
    static const char *fn = "pp_world_raycast_all";
    pp_status st;
    world *wd = world_lookup_list(w, fn, out, capacity, count, &st);
    if (!wd)
        return st;
    if (!finite2(from.x, from.y) || !finite2(to.x, to.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: from and to must be finite, got (%g, %g) and (%g, %g)", fn,
                       from.x, from.y, to.x, to.y);
    const dvec2 f = dv(from.x, from.y), e = dv(to.x, to.y), d = dv_sub(e, f);
    int32_t *near = NULL, n_near = 0, n = 0;
    if ((st = awake_bodies_in_box(wd, fn, segment_box(f, e), &near, &n_near)))
        return st;
    ray_entry *hits = n_near > 0 ? pp_malloc((size_t)n_near * sizeof *hits) : NULL;
    if (n_near > 0 && !hits) {
        pp_free(near);
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d bodies", fn, (int)n_near);
    }
    for (int32_t k = 0; k < n_near; k++) {
        const body *bd = wd->bodies[near[k]];
        ray_entry *h = &hits[n];
        if (queried(bd, mask_bits) && body_segment_hit(bd, f, d, &h->a, &h->dir, &h->hit))
            h->slot = near[k], n++;
    }
    pp_free(near);
    if (n > 1)
        qsort(hits, (size_t)n, sizeof *hits, entry_order);
    for (int32_t k = 0; k < n && k < capacity; k++)
        ray_result(wd->bodies[hits[k].slot], f, e, hits[k].a, hits[k].dir, &hits[k].hit, &out[k]);
    pp_free(hits);
    *count = n;
    return PP_OK;
}

/* ---- point, box and circle queries --------------------------------------------------------------- */

/* A query's shape in the world, px: its bounds, and what the test of each body reads. */
typedef struct query_shape {
    double x0, y0, x1, y1; /* world bounds */
    dvec2 a, b;            /* point: a; box: [a, b]; circle: centre a, radius b.x */
} query_shape;

/* Write, in slot order, the bodies passing the filter whose box meets the shape's and that `meets`
 * accepts: up to capacity of them, all counted. */
static pp_status query_scan(world *wd, const char *fn, uint32_t mask_bits, const query_shape *q,
                            bool (*meets)(const body *, const query_shape *), pp_body *out, int32_t capacity,
                            int32_t *count)
{
    const pp_aabb box = {q->x0 - QUERY_SLACK, q->y0 - QUERY_SLACK, q->x1 + QUERY_SLACK, q->y1 + QUERY_SLACK};
    int32_t *near = NULL, n_near = 0, n = 0;
    pp_status st = awake_bodies_in_box(wd, fn, box, &near, &n_near);
    if (st)
        return st;
    for (int32_t k = 0; k < n_near; k++) {
        const body *bd = wd->bodies[near[k]];
        if (!queried(bd, mask_bits) || !meets(bd, q))
            continue;
        if (n < capacity)
            out[n] = bd->handle;
        n++;
    }
    pp_free(near);
    *count = n;
    return PP_OK;
}

/* Is any pixel of columns [xa, xb] of row y solid (inside the bitmap, xa ≤ xb)? A word at a time. */
static bool row_any(const pp_raster *r, int32_t y, int32_t xa, int32_t xb)
{
    const uint64_t *row = r->bits + (int64_t)y * r->words_per_row;
    for (int32_t k = xa >> 6; k <= xb >> 6; k++) {
        uint64_t m = ~(uint64_t)0;
        if (k == xa >> 6)
            m &= ~(uint64_t)0 << (xa & 63);
        if (k == xb >> 6)
            m &= ~(uint64_t)0 >> (63 - (xb & 63));
        if (row[k] & m)
            return true;
    }
    return false;
}

/* Double bounds of a span clamped into [lo, hi] as integers; false when empty. */
static bool clamp_span(double a, double b, int32_t lo, int32_t hi, int32_t *ia, int32_t *ib)
{
    a = fmax(a, lo), b = fmin(b, hi);
    if (!(a <= b))
        return false;
    *ia = (int32_t)a, *ib = (int32_t)b;
    return true;
}

/* Is the rectangle [x0, x1] × [y0, y1] of bitmap rows and columns (inclusive) all empty? Tile counts. */
static bool rect_empty(const pp_raster *r, int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    return raster_rect_state(r, x0, y0, (int64_t)x1 + 1, (int64_t)y1 + 1) == RASTER_EMPTY;
}

/* Is the pixel whose square holds the world point solid? The rule of pp_world_query_point. */
static bool body_meets_point(const body *bd, const query_shape *s)
{
    const pp_raster *r = &bd->raster;
    const dvec2 q = body_world_to_local(bd, s->a);
    const double fx = floor(q.x), fy = floor(q.y);
    return fx >= r->x0 && fx < r->x1 && fy >= r->y0 && fy < r->y1 && raster_solid(r, (int32_t)fx, (int32_t)fy);
}

PP_API pp_status pp_world_query_point(pp_world w, pp_vec2 point, uint32_t mask_bits, pp_body *out, int32_t capacity,
                                      int32_t *count)
{
    static const char *fn = "pp_world_query_point";
    pp_status st;
    world *wd = world_lookup_list(w, fn, out, capacity, count, &st);
    if (!wd)
        return st;
    if (!finite2(point.x, point.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: point must be finite, got (%g, %g)", fn, point.x, point.y);
    const query_shape q = {point.x, point.y, point.x, point.y, dv(point.x, point.y), dv(0, 0)};
    return query_scan(wd, fn, mask_bits, &q, body_meets_point, out, capacity, count);
}

/* Does the centre of pixel (x, y) lie in the world box [lo, hi]? The rule of pp_world_query_aabb. */
static bool centre_in_box(const body *bd, int32_t x, int32_t y, dvec2 lo, dvec2 hi)
{
    const dvec2 p = dv_add(bd->pos, dv_rot(dv_sub(dv(x + 0.5, y + 0.5), bd->pivot), bd->cos_a, bd->sin_a));
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y;
}

/* Has the body a solid pixel whose centre lies in the world box [lo, hi]? Row by row over the box's
 * rows in the bitmap, each row's span of centres from the pose, its ends settled by the rule itself. */
static bool body_meets_box(const body *bd, const query_shape *shape)
{
    const dvec2 lo = shape->a, hi = shape->b;
    const pp_raster *r = &bd->raster;
    double ly0 = INFINITY, ly1 = -INFINITY, lx0 = INFINITY, lx1 = -INFINITY;
    for (int k = 0; k < 4; k++) {
        const dvec2 q = body_world_to_local(bd, dv(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y));
        lx0 = fmin(lx0, q.x), lx1 = fmax(lx1, q.x), ly0 = fmin(ly0, q.y), ly1 = fmax(ly1, q.y);
    }
    int32_t xa, xb, ya, yb;
    if (!clamp_span(ceil(lx0 - 0.5) - 1, floor(lx1 - 0.5) + 1, r->x0, r->x1 - 1, &xa, &xb) ||
        !clamp_span(ceil(ly0 - 0.5) - 1, floor(ly1 - 0.5) + 1, r->y0, r->y1 - 1, &ya, &yb) ||
        rect_empty(r, xa, ya, xb, yb))
        return false;
    const double c = bd->cos_a, s = bd->sin_a;
    for (int32_t y = ya; y <= yb; y++) {
        if (r->row_count[y] == 0)
            continue;
        /* Centre x of this row lands at base + x·(c, s): the x where both coordinates are in the box. */
        const dvec2 base = dv_add(bd->pos, dv_rot(dv_sub(dv(0.5, y + 0.5), bd->pivot), c, s));
        double a = -INFINITY, b = INFINITY;
        const double coef[2] = {c, s}, o[2] = {base.x, base.y}, l[2] = {lo.x, lo.y}, h[2] = {hi.x, hi.y};
        for (int k = 0; k < 2; k++) {
            if (coef[k] != 0) {
                const double u = (l[k] - o[k]) / coef[k], v = (h[k] - o[k]) / coef[k];
                a = fmax(a, fmin(u, v)), b = fmin(b, fmax(u, v));
            } else if (o[k] < l[k] - 1e-9 || o[k] > h[k] + 1e-9) {
                b = -INFINITY;
            }
        }
        int32_t x0, x1;
        if (!clamp_span(ceil(a) - 1, floor(b) + 1, xa, xb, &x0, &x1))
            continue;
        while (x0 <= x1 && !centre_in_box(bd, x0, y, lo, hi))
            x0++;
        while (x1 >= x0 && !centre_in_box(bd, x1, y, lo, hi))
            x1--;
        if (x0 <= x1 && row_any(r, y, x0, x1))
            return true;
    }
    return false;
}

PP_API pp_status pp_world_query_aabb(pp_world w, pp_vec2 lower, pp_vec2 upper, uint32_t mask_bits, pp_body *out,
                                     int32_t capacity, int32_t *count)
{
    static const char *fn = "pp_world_query_aabb";
    pp_status st;
    world *wd = world_lookup_list(w, fn, out, capacity, count, &st);
    if (!wd)
        return st;
    if ((st = pp_check_box(fn, lower, upper)))
        return st;
    const query_shape q = {lower.x, lower.y, upper.x, upper.y, dv(lower.x, lower.y), dv(upper.x, upper.y)};
    return query_scan(wd, fn, mask_bits, &q, body_meets_box, out, capacity, count);
}

/* Has the body a solid pixel whose centre lies within radius of the world point center? The edits' rule. */
static bool body_meets_circle(const body *bd, const query_shape *shape)
{
    const dvec2 center = shape->a;
    const double radius = shape->b.x;
    const pp_raster *r = &bd->raster;
    const dvec2 c = body_world_to_local(bd, center);
    int32_t xa, xb, ya, yb;
    if (!clamp_span(floor(c.x - radius) - 1, ceil(c.x + radius) + 1, r->x0, r->x1 - 1, &xa, &xb) ||
        !clamp_span(floor(c.y - radius) - 1, ceil(c.y + radius) + 1, r->y0, r->y1 - 1, &ya, &yb) ||
        rect_empty(r, xa, ya, xb, yb))
        return false;
    for (int32_t y = ya; y <= yb; y++) {
        double a, b;
        int32_t x0, x1;
        if (r->row_count[y] > 0 && circle_row_span(c, radius, y, &a, &b) && clamp_span(a, b, xa, xb, &x0, &x1) &&
            row_any(r, y, x0, x1))
            return true;
    }
    return false;
}

PP_API pp_status pp_world_query_circle(pp_world w, pp_vec2 center, float radius, uint32_t mask_bits, pp_body *out,
                                       int32_t capacity, int32_t *count)
{
    static const char *fn = "pp_world_query_circle";
    pp_status st;
    world *wd = world_lookup_list(w, fn, out, capacity, count, &st);
    if (!wd)
        return st;
    if (!finite2(center.x, center.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: center must be finite, got (%g, %g)", fn, center.x, center.y);
    if (!(radius >= 0) || !isfinite(radius))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: radius must be finite and ≥ 0, got %g", fn, radius);
    const double r = radius;
    const query_shape q = {center.x - r, center.y - r, center.x + r, center.y + r, dv(center.x, center.y), dv(r, 0)};
    return query_scan(wd, fn, mask_bits, &q, body_meets_circle, out, capacity, count);
}
