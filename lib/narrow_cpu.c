/* The CPU backend of the narrowphase core, the reference for glsl/narrow_*.comp. Both masks are
 * sampled on the reference body's grid; the intersection gives the count and centroid, the
 * normal (overlap-area gradient or critical-pixel kernel), and the strips across the normal
 * give the contact points and depths. Integers only, so the GPU twin matches bit for bit. */
#include "narrowphase.h"
#include "status.h"

#include <limits.h>
#include <stdlib.h>

#define RING NP_RING

static const int8_t NB[8][2] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};

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

/* Sample both masks on the plane (inner grid plus ring): sa from the reference directly, sb and
 * cb (the other body's bilinear coverage, 0..256, for sub-pixel edges) at the fixed-point points. */
static void sample_planes(const np_pair *p, uint8_t *sa, uint8_t *sb, uint16_t *cb)
{
    const int32_t ex = p->nx + 2 * RING, ey = p->ny + 2 * RING;
    for (int32_t cj = 0; cj < ey; cj++) {
        const int32_t py = (p->j0 - RING + cj) * p->s + p->off;
        const int64_t rx = p->qx0 + cj * p->djx, ry = p->qy0 + cj * p->djy;
        uint8_t *ra_row = sa + (int64_t)cj * ex, *rb_row = sb + (int64_t)cj * ex;
        uint16_t *cb_row = cb + (int64_t)cj * ex;
        for (int32_t ci = 0; ci < ex; ci++) {
            const int32_t px = (p->i0 - RING + ci) * p->s + p->off;
            ra_row[ci] = raster_solid_clamped(p->ra, px, py);
            rb_row[ci] = sample_fixed(p->rb, rx + ci * p->dix, ry + ci * p->diy);
            cb_row[ci] = (uint16_t)coverage_fixed(p->rb, rx + ci * p->dix, ry + ci * p->diy);
        }
    }
}

/* Integer sums of the intersection and of the chosen normal estimator (glsl/narrow_sums.comp). */
static void intersection_sums(const np_pair *p, const uint8_t *sa, const uint8_t *sb, const uint16_t *cb,
                              pp_normal_method method, np_core *r)
{
    const int32_t ex = p->nx + 2 * RING;
    for (int32_t cj = RING; cj < p->ny + RING; cj++) {
        for (int32_t ci = RING; ci < p->nx + RING; ci++) {
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
                    r->gx += cover * gx;
                    r->gy += cover * gy;
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
                    r->gx += kx;
                    r->gy += ky;
                }
            }
        }
    }
}

/* Strips across the normal, one cell wide (glsl/narrow_strips.comp). Strip b is centred on the
 * tangent coordinate t = b, so a cell belongs to strip round(t) and an axis-aligned strip is one
 * column of cells, centred on it. Per strip: the min and max projection of its intersection cells
 * on the normal (Q14), and the other body's coverage summed over the strip's reference cells,
 * which is the overlap length along the strip to sub-pixel precision (for a flat edge, exactly).
 * Each cell's coverage is shared between the two strips whose centres are nearest, by distance,
 * since a tilted strip holds a varying number of cells. */
static void strips_along(const np_pair *p, const uint8_t *sa, const uint8_t *sb, const uint16_t *cb, np_core *r,
                         int32_t *strips)
{
    const int32_t nqx = r->nqx, nqy = r->nqy, ex = p->nx + 2 * RING;
    /* The tangent coordinate t = −x·ny + y·nx is linear, so the cells' own strips round(t) (ties
     * up) lie between those of the rectangle's corners. */
    int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (int k = 0; k < 4; k++) {
        const int64_t x = (k & 1) ? p->nx - 1 : 0, y = (k >> 1) ? p->ny - 1 : 0;
        const int64_t b = floor_div(-x * nqy + y * nqx + NP_NORMAL_ONE / 2, NP_NORMAL_ONE);
        lo = b < lo ? b : lo;
        hi = b > hi ? b : hi;
    }
    const int32_t n = (int32_t)(hi - lo + 1);
    r->tmin = (int32_t)lo, r->nstrips = n;
    for (int32_t i = 0; i < n; i++) {
        strips[NP_STRIP_FIELDS * i + NP_STRIP_MIN] = INT32_MAX;
        strips[NP_STRIP_FIELDS * i + NP_STRIP_MAX] = INT32_MIN;
        strips[NP_STRIP_FIELDS * i + NP_STRIP_COVER] = 0;
    }
    for (int32_t cj = RING; cj < p->ny + RING; cj++) {
        for (int32_t ci = RING; ci < p->nx + RING; ci++) {
            const int64_t k = (int64_t)cj * ex + ci;
            if (!sa[k] || !cb[k])
                continue;
            const int64_t x = ci - RING, y = cj - RING;
            /* Tent-splat the coverage between the two strips whose centres are nearest (8-bit weights):
             * b0 is the strip whose centre is at or before the cell, w1 the share of the next one.
             * b0 may be −1 and b0 + 1 may be n, past the corners' strips: those shares are dropped. */
            const int64_t ts = -x * nqy + y * nqx, b0 = floor_div(ts, NP_NORMAL_ONE) - lo;
            const int32_t w1 = (int32_t)((ts - (b0 + lo) * NP_NORMAL_ONE) >> 6); /* 0..255 */
            if (b0 >= 0)
                strips[NP_STRIP_FIELDS * b0 + NP_STRIP_COVER] += (cb[k] * (256 - w1)) >> 8;
            if (b0 + 1 < n)
                strips[NP_STRIP_FIELDS * (b0 + 1) + NP_STRIP_COVER] += (cb[k] * w1) >> 8;
            if (!sb[k])
                continue;
            /* The cell's own strip, round(t): the later of the two from half-way between them on. */
            int32_t *st = strips + NP_STRIP_FIELDS * (b0 + (w1 >= 128));
            const int32_t pr = (int32_t)(x * nqx + y * nqy);
            if (pr < st[NP_STRIP_MIN]) st[NP_STRIP_MIN] = pr;
            if (pr > st[NP_STRIP_MAX]) st[NP_STRIP_MAX] = pr;
        }
    }
}

static int32_t deepest_in(const int32_t *strips, int32_t from, int32_t to)
{
    int32_t best = 0;
    for (int32_t b = from; b <= to; b++)
        if (strips[NP_STRIP_FIELDS * b + NP_STRIP_COVER] > best)
            best = strips[NP_STRIP_FIELDS * b + NP_STRIP_COVER];
    return best;
}

/* The first and last strips holding intersection cells, and the deepest cover overall and in
 * each half between them (glsl/narrow_finish.comp). */
static void strips_summary(const int32_t *strips, np_core *r)
{
    const int32_t n = r->nstrips;
    int32_t first = 0, last = n - 1;
    while (strips[NP_STRIP_FIELDS * first + NP_STRIP_MIN] > strips[NP_STRIP_FIELDS * first + NP_STRIP_MAX]) first++;
    while (strips[NP_STRIP_FIELDS * last + NP_STRIP_MIN] > strips[NP_STRIP_FIELDS * last + NP_STRIP_MAX]) last--;
    const int32_t mid = first + (last - first) / 2;
    r->first = first, r->last = last;
    r->first_min = strips[NP_STRIP_FIELDS * first + NP_STRIP_MIN];
    r->first_max = strips[NP_STRIP_FIELDS * first + NP_STRIP_MAX];
    r->last_min = strips[NP_STRIP_FIELDS * last + NP_STRIP_MIN];
    r->last_max = strips[NP_STRIP_FIELDS * last + NP_STRIP_MAX];
    r->cover_all = deepest_in(strips, 0, n - 1);
    r->cover_lo = deepest_in(strips, first, mid);
    r->cover_hi = deepest_in(strips, mid + 1, last);
}

pp_status narrow_cpu_core(const np_settings *set, const np_pair *p, np_scratch *scratch, np_core *out)
{
    *out = (np_core){0};
    const int64_t cells = np_pair_cells(p);
    pp_status st = grow_scratch(scratch, 4 * cells, NP_STRIP_FIELDS * np_pair_max_strips(p));
    if (st)
        return st;
    uint8_t *sa = scratch->cells, *sb = scratch->cells + cells;
    uint16_t *cb = (uint16_t *)(scratch->cells + 2 * cells);
    sample_planes(p, sa, sb, cb);
    intersection_sums(p, sa, sb, cb, set->normal_method, out);
    if (out->count == 0)
        return PP_OK;
    if (out->gx != 0 || out->gy != 0)
        np_quantize_normal(out->gx, out->gy, &out->nqx, &out->nqy);
    else
        out->nqx = p->fallback_nqx, out->nqy = p->fallback_nqy;
    strips_along(p, sa, sb, cb, out, scratch->strips);
    strips_summary(scratch->strips, out);
    return PP_OK;
}

pp_status narrow_cpu_debug(const np_pair *p, np_scratch *scratch, uint8_t *flags, int32_t *kernel_xy)
{
    const int64_t cells = np_pair_cells(p);
    pp_status st = grow_scratch(scratch, 4 * cells, 0);
    if (st)
        return st;
    uint8_t *sa = scratch->cells, *sb = scratch->cells + cells;
    sample_planes(p, sa, sb, (uint16_t *)(scratch->cells + 2 * cells));
    const int32_t ex = p->nx + 2 * RING;
    for (int32_t j = 0; j < p->ny; j++)
        for (int32_t i = 0; i < p->nx; i++) {
            const int64_t k = (int64_t)(j + RING) * ex + i + RING, o = (int64_t)j * p->nx + i;
            int32_t kx = 0, ky = 0;
            bool critical = false;
            for (int d = 0; d < 8 && sa[k] && sb[k]; d++) {
                const int64_t n = k + NB[d][0] + (int64_t)NB[d][1] * ex;
                critical |= !(sa[n] && sb[n]);
                kx += ((int)sb[n] - (int)sa[n]) * NB[d][0];
                ky += ((int)sb[n] - (int)sa[n]) * NB[d][1];
            }
            flags[o] = (uint8_t)(sa[k] | sb[k] << 1 | (critical ? 4 : 0));
            kernel_xy[2 * o] = critical ? kx : 0;
            kernel_xy[2 * o + 1] = critical ? ky : 0;
        }
    return PP_OK;
}
