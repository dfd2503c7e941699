/* The CPU collision backend, the reference. Both masks are sampled on the reference body's
 * pixel grid (coarsened by the stride); the intersection raster gives the count and centroid,
 * the normal (critical-pixel kernel or overlap-area gradient), and the depth as the longest
 * one-cell strip along the normal. Everything is decided in integers and 16.16 fixed-point
 * steps, so the GPU twin can reproduce it bit for bit. */
#include "narrowphase.h"
#include "status.h"

#include <limits.h>
#include <stdlib.h>

/* Sampled ring around the inner grid: the 5×5 taper window reaches two cells out. */
#define RING 2

static const int8_t NB[8][2] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};

static inline int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

static inline int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }

static inline uint8_t sample_fixed(const pp_raster *r, int64_t qx, int64_t qy)
{
    const int64_t x = qx >> NP_FIX_BITS, y = qy >> NP_FIX_BITS; /* arithmetic shift = floor */
    return x >= 0 && y >= 0 && x < r->width && y < r->height && raster_solid(r, (int32_t)x, (int32_t)y);
}

/* Coverage 0..256 of the mask at a 16.16 point, bilinear between pixel centres, in integers. */
static inline uint32_t coverage_fixed(const pp_raster *r, int64_t qx, int64_t qy)
{
    const int64_t hx = qx - (1 << (NP_FIX_BITS - 1)), hy = qy - (1 << (NP_FIX_BITS - 1));
    const int64_t x = hx >> NP_FIX_BITS, y = hy >> NP_FIX_BITS;
    const uint32_t fx = (uint32_t)((hx >> (NP_FIX_BITS - 8)) & 255), fy = (uint32_t)((hy >> (NP_FIX_BITS - 8)) & 255);
    if (x < -1 || y < -1 || x >= r->width || y >= r->height)
        return 0;
    const int32_t x0 = (int32_t)x, y0 = (int32_t)y;
    const uint32_t m00 = raster_solid_clamped(r, x0, y0), m10 = raster_solid_clamped(r, x0 + 1, y0);
    const uint32_t m01 = raster_solid_clamped(r, x0, y0 + 1), m11 = raster_solid_clamped(r, x0 + 1, y0 + 1);
    return (m00 * (256 - fx) * (256 - fy) + m10 * fx * (256 - fy) + m01 * (256 - fx) * fy + m11 * fx * fy) >> 8;
}

static pp_status grow_scratch(np_scratch *s, int64_t cells, int64_t strips)
{
    if (cells > s->cells_cap) {
        uint8_t *p = realloc(s->cells, (size_t)cells);
        if (!p)
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "narrowphase: no memory for %lld samples", (long long)cells);
        s->cells = p;
        s->cells_cap = cells;
    }
    if (strips > s->strips_cap) {
        int32_t *p = realloc(s->strips, (size_t)strips * sizeof(int32_t));
        if (!p)
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "narrowphase: no memory for %lld strips", (long long)strips);
        s->strips = p;
        s->strips_cap = strips;
    }
    return PP_OK;
}

void np_scratch_free(np_scratch *s)
{
    free(s->cells);
    free(s->strips);
    *s = (np_scratch){0};
}

static int64_t bounds_area(const pp_raster *r) { return (int64_t)(r->x1 - r->x0) * (r->y1 - r->y0); }

/* The sampling grid: cell (i, j) reads the reference pixel (i·s + off, j·s + off). */
typedef struct grid {
    int32_t s, off;
    int32_t i0, j0;     /* grid index of the first inner cell */
    int32_t nx, ny;     /* inner cells; the sampled planes have a RING-cell ring around them */
    int32_t ex, ey;     /* nx + 2·RING, ny + 2·RING */
} grid;

/* Reference-local pixel coordinates of a (fractional) inner-cell position. */
static dvec2 grid_to_local(const grid *g, double ci, double cj)
{
    return dv((g->i0 + ci) * g->s + g->off + 0.5, (g->j0 + cj) * g->s + g->off + 0.5);
}

/* Choose the rectangle of the reference grid where the two bodies can overlap.
 * Returns false when it is empty. M, t map reference-local to other-local: q = M·l + t. */
static bool overlap_grid(const pp_raster *ra, const pp_raster *rb, double mc, double ms, dvec2 t, int32_t stride,
                         grid *g)
{
    double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
    const double cx[2] = {rb->x0, rb->x1}, cy[2] = {rb->y0, rb->y1};
    for (int k = 0; k < 4; k++) {
        const dvec2 l = dv_unrot(dv_sub(dv(cx[k & 1], cy[k >> 1]), t), mc, ms);
        lo_x = fmin(lo_x, l.x), hi_x = fmax(hi_x, l.x);
        lo_y = fmin(lo_y, l.y), hi_y = fmax(hi_y, l.y);
    }
    /* A margin of one cell plus one pixel so unit shifts of the other body stay inside. */
    const double margin = stride + 1;
    const int64_t X0 = (int64_t)fmax(ra->x0, floor(lo_x - margin)), X1 = (int64_t)fmin(ra->x1, ceil(hi_x + margin));
    const int64_t Y0 = (int64_t)fmax(ra->y0, floor(lo_y - margin)), Y1 = (int64_t)fmin(ra->y1, ceil(hi_y + margin));
    if (X0 >= X1 || Y0 >= Y1)
        return false;
    g->s = stride;
    g->off = stride / 2;
    const int64_t i0 = ceil_div(X0 - g->off, stride), i1 = floor_div(X1 - 1 - g->off, stride);
    const int64_t j0 = ceil_div(Y0 - g->off, stride), j1 = floor_div(Y1 - 1 - g->off, stride);
    if (i1 < i0 || j1 < j0)
        return false;
    g->i0 = (int32_t)i0, g->j0 = (int32_t)j0;
    g->nx = (int32_t)(i1 - i0 + 1), g->ny = (int32_t)(j1 - j0 + 1);
    g->ex = g->nx + 2 * RING, g->ey = g->ny + 2 * RING;
    return true;
}

/* Sample both masks on the grid plus its ring: sa from the reference directly, sb through
 * 16.16 fixed-point affine steps from one rounded origin, so every backend reads the same cells.
 * cb is the other body's bilinear coverage (0..256), for sub-pixel edges in the gradient and depth. */
static void sample_planes(const grid *g, const pp_raster *ra, const pp_raster *rb, double mc, double ms, dvec2 t,
                          uint8_t *sa, uint8_t *sb, uint16_t *cb)
{
    const double one = (double)(1 << NP_FIX_BITS);
    const dvec2 l0 = grid_to_local(g, -RING, -RING);
    const dvec2 q0 = dv_add(dv_rot(l0, mc, ms), t);
    const int64_t qx0 = llround(q0.x * one), qy0 = llround(q0.y * one);
    const int64_t dix = llround(mc * g->s * one), diy = llround(ms * g->s * one);
    const int64_t djx = llround(-ms * g->s * one), djy = llround(mc * g->s * one);
    for (int32_t cj = 0; cj < g->ey; cj++) {
        const int32_t py = (g->j0 - RING + cj) * g->s + g->off;
        const int64_t rx = qx0 + cj * djx, ry = qy0 + cj * djy;
        uint8_t *ra_row = sa + (int64_t)cj * g->ex, *rb_row = sb + (int64_t)cj * g->ex;
        uint16_t *cb_row = cb + (int64_t)cj * g->ex;
        for (int32_t ci = 0; ci < g->ex; ci++) {
            const int32_t px = (g->i0 - RING + ci) * g->s + g->off;
            ra_row[ci] = raster_solid_clamped(ra, px, py);
            rb_row[ci] = sample_fixed(rb, rx + ci * dix, ry + ci * diy);
            cb_row[ci] = (uint16_t)coverage_fixed(rb, rx + ci * dix, ry + ci * diy);
        }
    }
}

/* Integer sums of the intersection and of the chosen normal estimator. */
typedef struct isect_sums {
    int64_t count, sx, sy;  /* intersection cells and the sums of their inner-cell coordinates */
    int64_t nx, ny;         /* unnormalised normal, reference grid axes, pointing from reference to other */
} isect_sums;

static void intersection_sums(const grid *g, const uint8_t *sa, const uint8_t *sb, const uint16_t *cb,
                              pp_normal_method method, isect_sums *r)
{
    *r = (isect_sums){0};
    const int32_t ex = g->ex;
    for (int32_t cj = RING; cj < g->ny + RING; cj++) {
        for (int32_t ci = RING; ci < g->nx + RING; ci++) {
            const int64_t k = (int64_t)cj * ex + ci;
            if (!sa[k])
                continue;
            if (method == PP_NORMAL_AREA_GRADIENT) {
                /* −∇ overlap(shift of the other body) = Σ over reference cells of the directions to the
                 * other body's neighbours (bilinear coverage), axis neighbours weighted 2, diagonals 1
                 * (isotropic). Each cell is weighted by the reference's 5×5 coverage, which tapers the
                 * ends of the contact arc where the quantisation noise is. */
                int64_t gx = 0, gy = 0;
                for (int d = 0; d < 8; d++) {
                    const int w = (NB[d][0] && NB[d][1]) ? 1 : 2;
                    const int64_t c = cb[k + NB[d][0] + (int64_t)NB[d][1] * ex];
                    gx += w * NB[d][0] * c;
                    gy += w * NB[d][1] * c;
                }
                if (gx | gy) {
                    int64_t cover = 0;
                    for (int dy = -2; dy <= 2; dy++)
                        for (int dx = -2; dx <= 2; dx++)
                            cover += sa[k + dx + (int64_t)dy * ex];
                    r->nx += cover * gx;
                    r->ny += cover * gy;
                }
            }
            if (!sb[k])
                continue;
            r->count++;
            r->sx += ci - RING;
            r->sy += cj - RING;
            if (method == PP_NORMAL_KERNEL) {
                /* A critical cell borders the outside of the intersection; its 3×3 kernel counts the
                 * other body's cells toward the normal and the reference's against it. */
                int64_t kx = 0, ky = 0;
                bool critical = false;
                for (int d = 0; d < 8; d++) {
                    const int64_t n = k + NB[d][0] + (int64_t)NB[d][1] * ex;
                    critical |= !(sa[n] && sb[n]);
                    const int v = (int)sb[n] - (int)sa[n];
                    kx += v * NB[d][0];
                    ky += v * NB[d][1];
                }
                if (critical) {
                    r->nx += kx;
                    r->ny += ky;
                }
            }
        }
    }
}

/* Strips across the normal, one cell wide. Per strip: the min and max projection of its
 * intersection cells on the normal (Q14), and the other body's coverage summed over the strip's
 * reference cells, which is the overlap length along the strip to sub-pixel precision (for a
 * flat edge, exactly). Each cell's coverage is shared between the two strips whose centres are
 * nearest, by distance, since a tilted strip holds a varying number of cell centres.
 * Returns the number of strips; *tmin is the index of the first. */
enum { STRIP_MIN, STRIP_MAX, STRIP_COVER, STRIP_FIELDS };

static int32_t strips_along(const grid *g, const uint8_t *sa, const uint8_t *sb, const uint16_t *cb, int32_t nqx,
                            int32_t nqy, int32_t *strips, int64_t *tmin)
{
    /* Tangent coordinate t = −x·ny + y·nx over the rectangle's corners bounds the strip indices. */
    int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (int k = 0; k < 4; k++) {
        const int64_t x = (k & 1) ? g->nx - 1 : 0, y = (k >> 1) ? g->ny - 1 : 0;
        const int64_t b = floor_div(-x * nqy + y * nqx, NP_NORMAL_ONE);
        lo = b < lo ? b : lo;
        hi = b > hi ? b : hi;
    }
    const int32_t n = (int32_t)(hi - lo + 1);
    for (int32_t i = 0; i < n; i++) {
        strips[STRIP_FIELDS * i + STRIP_MIN] = INT32_MAX;
        strips[STRIP_FIELDS * i + STRIP_MAX] = INT32_MIN;
        strips[STRIP_FIELDS * i + STRIP_COVER] = 0;
    }
    for (int32_t cj = RING; cj < g->ny + RING; cj++) {
        for (int32_t ci = RING; ci < g->nx + RING; ci++) {
            const int64_t k = (int64_t)cj * g->ex + ci;
            if (!sa[k] || !cb[k])
                continue;
            const int64_t x = ci - RING, y = cj - RING;
            /* Tent-splat the coverage between the two strips whose centres are nearest (8-bit weights):
             * b0 is the strip whose centre is at or before the cell, w1 the share of the next one. */
            const int64_t ts = -x * nqy + y * nqx - NP_NORMAL_ONE / 2, b0 = floor_div(ts, NP_NORMAL_ONE) - lo;
            const int32_t w1 = (int32_t)((ts - (b0 + lo) * NP_NORMAL_ONE) >> 6); /* 0..255 */
            if (b0 >= 0)
                strips[STRIP_FIELDS * b0 + STRIP_COVER] += (cb[k] * (256 - w1)) >> 8;
            if (b0 + 1 < n)
                strips[STRIP_FIELDS * (b0 + 1) + STRIP_COVER] += (cb[k] * w1) >> 8;
            if (!sb[k])
                continue;
            /* The cell's own strip: the later of the two once the cell is past b0's right edge. */
            int32_t *st = strips + STRIP_FIELDS * (b0 + (w1 >= 128));
            const int32_t p = (int32_t)(x * nqx + y * nqy);
            if (p < st[STRIP_MIN]) st[STRIP_MIN] = p;
            if (p > st[STRIP_MAX]) st[STRIP_MAX] = p;
        }
    }
    *tmin = lo;
    return n;
}

static bool strip_hit(const int32_t *strips, int32_t b)
{
    return strips[STRIP_FIELDS * b + STRIP_MIN] <= strips[STRIP_FIELDS * b + STRIP_MAX];
}

/* Depth in pixels of the deepest strip in [from, to]: its covered length along the normal. */
static double deepest_in(const int32_t *strips, int32_t from, int32_t to, int32_t stride)
{
    int32_t best = 0;
    for (int32_t b = from; b <= to; b++)
        if (strips[STRIP_FIELDS * b + STRIP_COVER] > best)
            best = strips[STRIP_FIELDS * b + STRIP_COVER];
    return (double)best / 256.0 * stride;
}

/* Inner-cell coordinates of the middle of strip b's intersection. */
static dvec2 strip_point(const int32_t *strips, int32_t b, int64_t tmin, int32_t nqx, int32_t nqy)
{
    const int32_t *st = strips + STRIP_FIELDS * b;
    const double v = 0.5 * ((double)st[STRIP_MIN] + st[STRIP_MAX]) / NP_NORMAL_ONE; /* along n */
    const double u = (double)(b + tmin) + 0.5;                                       /* along t */
    const double q = (double)NP_NORMAL_ONE;
    return dv((nqx * v - nqy * u) / q, (nqy * v + nqx * u) / q);
}

pp_status narrow_cpu_collide(const np_settings *set, const np_body *a, const np_body *b, np_scratch *scratch,
                             np_result *out)
{
    out->count = 0;
    out->samples = 0;
    if (raster_empty(a->raster) || raster_empty(b->raster))
        return PP_OK;

    /* The larger body is the reference: its own boundary stays exact on its own grid (a flat ground
     * gives an exact normal), and the grid is still bounded by the smaller body's box. */
    const bool swap = bounds_area(b->raster) > bounds_area(a->raster);
    const np_body *A = swap ? b : a, *B = swap ? a : b;
    const pp_raster *ra = A->raster, *rb = B->raster;

    /* q = M·l + t maps A-local to B-local: M = R(θA − θB), t = pivotB + R(−θB)(posA − posB) − M·pivotA. */
    const double mc = A->c * B->c + A->s * B->s, ms = A->s * B->c - A->c * B->s;
    const dvec2 d = dv_unrot(dv_sub(A->pos, B->pos), B->c, B->s);
    const dvec2 t = dv_sub(dv_add(B->pivot, d), dv_rot(A->pivot, mc, ms));

    grid g;
    if (!overlap_grid(ra, rb, mc, ms, t, set->stride, &g))
        return PP_OK;
    const int64_t cells = (int64_t)g.ex * g.ey;
    pp_status st = grow_scratch(scratch, 4 * cells, STRIP_FIELDS * ((int64_t)g.nx + g.ny + 4));
    if (st)
        return st;
    uint8_t *sa = scratch->cells, *sb = scratch->cells + cells;
    uint16_t *cb = (uint16_t *)(scratch->cells + 2 * cells);
    sample_planes(&g, ra, rb, mc, ms, t, sa, sb, cb);
    out->samples = cells;

    isect_sums sum;
    intersection_sums(&g, sa, sb, cb, set->normal_method, &sum);
    if (sum.count == 0)
        return PP_OK;

    dvec2 n = dv((double)sum.nx, (double)sum.ny);
    if (n.x == 0 && n.y == 0) /* symmetric overlap: fall back to the line between the bodies */
        n = dv_unrot(dv_sub(B->pos, A->pos), A->c, A->s);
    if (n.x == 0 && n.y == 0)
        n = dv(0, 1);
    n = dv_scale(n, 1.0 / sqrt(dv_dot(n, n)));
    const int32_t nqx = (int32_t)lround(n.x * NP_NORMAL_ONE), nqy = (int32_t)lround(n.y * NP_NORMAL_ONE);

    int64_t tmin;
    const int32_t nstrips = strips_along(&g, sa, sb, cb, nqx, nqy, scratch->strips, &tmin);
    const int32_t *strips = scratch->strips;

    /* Contact points in inner-cell coordinates, with their depths in pixels. */
    dvec2 pts[2];
    double depth[2];
    int32_t first = 0, last = nstrips - 1;
    while (!strip_hit(strips, first)) first++;
    while (!strip_hit(strips, last)) last--;
    if (set->contact_mode == PP_CONTACT_CENTROID || first == last) {
        pts[0] = set->contact_mode == PP_CONTACT_CENTROID ? dv((double)sum.sx / sum.count, (double)sum.sy / sum.count)
                                                          : strip_point(strips, first, tmin, nqx, nqy);
        depth[0] = deepest_in(strips, 0, nstrips - 1, g.s);
        out->count = 1;
    } else {
        /* The two ends along the tangent, each as deep as the deepest strip of its half. */
        const int32_t mid = first + (last - first) / 2;
        pts[0] = strip_point(strips, first, tmin, nqx, nqy);
        pts[1] = strip_point(strips, last, tmin, nqx, nqy);
        depth[0] = deepest_in(strips, first, mid, g.s);
        depth[1] = deepest_in(strips, mid + 1, last, g.s);
        out->count = 2;
    }

    const dvec2 nw = dv_rot(n, A->c, A->s);
    const double sign = swap ? -1.0 : 1.0;
    for (int32_t k = 0; k < out->count; k++) {
        const dvec2 l = grid_to_local(&g, pts[k].x, pts[k].y);
        const dvec2 w = dv_add(A->pos, dv_rot(dv_sub(l, A->pivot), A->c, A->s));
        pp_contact *c = &out->contacts[k];
        c->point = (pp_vec2){(float)w.x, (float)w.y};
        c->normal = (pp_vec2){(float)(sign * nw.x), (float)(sign * nw.y)};
        c->depth = (float)depth[k];
        c->pixel_count = (int32_t)(sum.count * g.s * g.s);
    }
    return PP_OK;
}
