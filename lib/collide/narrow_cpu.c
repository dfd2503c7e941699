/* The CPU backend of the narrowphase core, the reference for glsl/narrow_*.comp. Both masks are
 * sampled on the reference body's grid; the intersection gives the count and centroid, the
 * normal (overlap-area gradient or critical-pixel kernel), and the strips across the normal
 * give the contact points and depths. Integers only, so the GPU twin matches bit for bit.
 * Two cores compute the same integers: the dense one samples every cell (the specification, as
 * the GPU runs it); the tiled one works only near the contact, from the rasters' tile occupancy.
 * This file: the dense core, the debug view, the scratch, and the per-pair steps both cores share;
 * the tiled core is narrow_tiled.c, the per-cell steps are inline in narrow_cpu.h. */
#include "alloc.h"
#include "narrow_cpu.h"
#include "status.h"

#include <limits.h>

static inline uint8_t sample_fixed(const pp_raster *r, int64_t qx, int64_t qy)
{
    const int64_t x = qx >> NP_FIX_BITS, y = qy >> NP_FIX_BITS; /* arithmetic shift = floor */
    return x >= 0 && y >= 0 && x < r->width && y < r->height && raster_solid(r, (int32_t)x, (int32_t)y);
}

/* Coverage 0..256 of the mask at a 16.16 point, bilinear between pixel centres, in integers. */
static inline uint32_t coverage_fixed(const pp_raster *r, int64_t qx, int64_t qy)
{
    const int64_t hx = qx - HALF_PIXEL, hy = qy - HALF_PIXEL;
    const int64_t x = hx >> NP_FIX_BITS, y = hy >> NP_FIX_BITS;
    const uint32_t fx = (uint32_t)((hx >> (NP_FIX_BITS - 8)) & 255), fy = (uint32_t)((hy >> (NP_FIX_BITS - 8)) & 255);
    if (x < -1 || y < -1 || x >= r->width || y >= r->height)
        return 0;
    const int32_t x0 = (int32_t)x, y0 = (int32_t)y;
    const uint32_t m00 = raster_solid_clamped(r, x0, y0), m10 = raster_solid_clamped(r, x0 + 1, y0);
    const uint32_t m01 = raster_solid_clamped(r, x0, y0 + 1), m11 = raster_solid_clamped(r, x0 + 1, y0 + 1);
    return (m00 * (256 - fx) * (256 - fy) + m10 * fx * (256 - fy) + m01 * (256 - fx) * fy + m11 * fx * fy) >> 8;
}

/* A scratch buffer grown to n elements of `size` bytes; on failure *st says so and buf is kept. */
static void *grow(void *buf, int64_t *cap, int64_t n, size_t size, pp_status *st)
{
    if (*st || n <= *cap)
        return buf;
    void *p = pp_realloc(buf, (size_t)n * size);
    if (!p) {
        *st = pp_fail(PP_ERR_OUT_OF_MEMORY, "narrowphase: no memory for %lld scratch elements", (long long)n);
        return buf;
    }
    *cap = n;
    return p;
}

static pp_status grow_scratch(np_scratch *s, int64_t cells, int64_t strips)
{
    pp_status st = PP_OK;
    s->cells = grow(s->cells, &s->cells_cap, cells, 1, &st);
    s->strips = grow(s->strips, &s->strips_cap, strips, sizeof *s->strips, &st);
    return st;
}

void np_scratch_free(np_scratch *s)
{
    pp_free(s->cells);
    pp_free(s->strips);
    pp_free(s->leaves);
    pp_free(s->rects);
    *s = (np_scratch){0};
}

pp_status np_scratch_reserve(np_scratch *s, int32_t nx, int32_t ny)
{
    const np_pair p = {.nx = nx, .ny = ny};
    const int64_t leaves_x = (nx + LEAF - 1) / LEAF, leaves_y = (ny + LEAF - 1) / LEAF;
    const int64_t map_words = (leaves_x + 63) / 64 * (leaves_y + 1); /* the map, and one row of scratch */
    pp_status st = grow_scratch(s, 4 * np_pair_cells(&p), NP_STRIP_FIELDS * np_pair_max_strips(&p));
    s->leaves = grow(s->leaves, &s->leaves_cap, map_words, sizeof *s->leaves, &st);
    s->rects = grow(s->rects, &s->rects_cap, 4 * leaves_x * leaves_y, sizeof *s->rects, &st);
    return st;
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

void strips_clear(const np_pair *p, np_core *r, int32_t *strips)
{
    /* The tangent coordinate t = −x·ny + y·nx is linear, so the cells' own strips round(t) (ties
     * up) lie between those of the rectangle's corners. */
    int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (int k = 0; k < 4; k++) {
        const int64_t x = (k & 1) ? p->nx - 1 : 0, y = (k >> 1) ? p->ny - 1 : 0;
        const int64_t b = floor_div(-x * r->nqy + y * r->nqx + NP_NORMAL_ONE / 2, NP_NORMAL_ONE);
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
void strips_summary(const int32_t *strips, np_core *r)
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

/* The normal in Q14 from the sums, or the pair's fallback when they cancel. */
void quantized_normal(const np_pair *p, np_core *r)
{
    if (r->gx != 0 || r->gy != 0)
        np_quantize_normal(r->gx, r->gy, &r->nqx, &r->nqy);
    else
        r->nqx = p->fallback_nqx, r->nqy = p->fallback_nqy;
}

pp_status narrow_cpu_core_dense(const np_settings *set, const np_pair *p, np_scratch *scratch, np_core *out)
{
    *out = (np_core){0};
    const int64_t cells = np_pair_cells(p);
    pp_status st = grow_scratch(scratch, 4 * cells, NP_STRIP_FIELDS * np_pair_max_strips(p));
    if (st)
        return st;
    uint8_t *sa = scratch->cells, *sb = scratch->cells + cells;
    uint16_t *cb = (uint16_t *)(scratch->cells + 2 * cells);
    sample_planes(p, sa, sb, cb);
    const int64_t ex = p->nx + 2 * RING;
    cell_sums_acc acc = {0};
    for (int64_t y = 0; y < p->ny; y++)
        for (int64_t x = 0; x < p->nx; x++)
            cell_sums(sa, sb, cb, (y + RING) * ex + x + RING, ex, x, y, set->normal_method, &acc);
    add_sums(out, &acc);
    if (out->count == 0)
        return PP_OK;
    quantized_normal(p, out);
    strips_clear(p, out, scratch->strips);
    for (int64_t y = 0; y < p->ny; y++)
        for (int64_t x = 0; x < p->nx; x++) {
            const int64_t k = (y + RING) * ex + x + RING;
            if (sa[k] && cb[k])
                strip_cell(out, scratch->strips, x, y, cb[k], sb[k]);
        }
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
