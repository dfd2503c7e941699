/* Private to the CPU backend of the narrowphase core: what the dense core (narrow_cpu.c) and the
 * tiled core (narrow_tiled.c) share. The per-cell steps (sums, strip splat) are inline, as they run
 * for every cell; the per-pair steps around them (normal, strips cleared and summed) are narrow_cpu.c's. */
#ifndef PP_NARROW_CPU_H
#define PP_NARROW_CPU_H

#include "narrowphase.h"

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#define RING NP_RING
#define HALF_PIXEL (1 << (NP_FIX_BITS - 1)) /* in 16.16 */

/* The tiled core's leaves are LEAF × LEAF inner cells (narrow_tiled.c); np_scratch_reserve sizes its map by them. */
#define LEAF 8

static const int8_t NB[8][2] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};

/* The sums of np_core, kept in a local while cells are added (the planes are bytes, which may alias
 * anything, so sums kept in np_core would be stored and reloaded for every cell). */
typedef struct cell_sums_acc {
    int64_t count, sx, sy, gx, gy;
} cell_sums_acc;

static inline void add_sums(np_core *r, const cell_sums_acc *a)
{
    r->count += a->count, r->sx += a->sx, r->sy += a->sy, r->gx += a->gx, r->gy += a->gy;
}

/* The reference's 5×5 cells around cell k, each 0 or 1. Each row's five bytes come from one 8-byte load, masked
 * (the three bytes past them lie in the scratch, as sb follows sa, and are dropped); the rows add bytewise (5 at
 * most a byte) and one multiply sums the five bytes into the fifth: a third of the loop's instructions, the same
 * integer. */
static inline int64_t cover_5x5(const uint8_t *sa, int64_t k, int64_t ex)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    uint64_t rows = 0;
    for (int64_t dy = -2; dy <= 2; dy++) {
        uint64_t w;
        memcpy(&w, sa + k + dy * ex - 2, sizeof w);
        rows += w & 0xffffffffffull;
    }
    return (int64_t)((rows * 0x0101010101ull) >> 32 & 0xff);
#else
    int64_t cover = 0;
    for (int64_t dy = -2; dy <= 2; dy++) {
        const uint8_t *row = sa + k + dy * ex;
        cover += row[-2] + row[-1] + row[0] + row[1] + row[2];
    }
    return cover;
#endif
}

/* Cell k of the plane (inner coordinates x, y) added to the sums of the intersection and of the
 * chosen normal estimator (glsl/narrow_sums.comp). Always inlined: a call per cell cost 10%. */
static inline __attribute__((always_inline)) void cell_sums(const uint8_t *sa, const uint8_t *sb, const uint16_t *cb,
                                                            int64_t k, int64_t ex, int64_t x, int64_t y,
                                                            pp_normal_method method, cell_sums_acc *r)
{
    if (!sa[k])
        return;
    if (method == PP_NORMAL_AREA_GRADIENT) {
        /* −∇ overlap(shift of the other body) = Σ over reference cells of the directions to the
         * other body's neighbours (bilinear coverage), axis neighbours weighted 2, diagonals 1
         * (isotropic). Each cell is weighted by the reference's 5×5 coverage, which tapers the
         * ends of the contact arc where the quantisation noise is. */
        const uint16_t *up = cb + k - ex, *mid = cb + k, *down = cb + k + ex;
        const int64_t gx = 2 * (mid[1] - mid[-1]) + (up[1] - up[-1]) + (down[1] - down[-1]);
        const int64_t gy = 2 * (down[0] - up[0]) + (down[-1] - up[-1]) + (down[1] - up[1]);
        if (gx | gy) {
            const int64_t cover = cover_5x5(sa, k, ex);
            r->gx += cover * gx;
            r->gy += cover * gy;
        }
    }
    if (!sb[k])
        return;
    r->count++;
    r->sx += x;
    r->sy += y;
    if (method == PP_NORMAL_KERNEL) {
        /* A critical cell borders the outside of the intersection; its 3×3 kernel counts the
         * other body's cells toward the normal and the reference's against it: the sum of
         * (sb − sa)·offset over the eight neighbours. */
        uint8_t inside = 1;
        for (int d = 0; d < 8; d++)
            inside &= sa[k + NB[d][0] + NB[d][1] * ex] & sb[k + NB[d][0] + NB[d][1] * ex];
        if (!inside) {
            const uint8_t *au = sa + k - ex, *am = sa + k, *ad = sa + k + ex;
            const uint8_t *bu = sb + k - ex, *bm = sb + k, *bd = sb + k + ex;
            r->gx += (bu[1] - au[1]) + (bm[1] - am[1]) + (bd[1] - ad[1]) - (bu[-1] - au[-1]) - (bm[-1] - am[-1]) -
                     (bd[-1] - ad[-1]);
            r->gy += (bd[-1] - ad[-1]) + (bd[0] - ad[0]) + (bd[1] - ad[1]) - (bu[-1] - au[-1]) - (bu[0] - au[0]) -
                     (bu[1] - au[1]);
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

/* Strips 0 .. nstrips − 1 set for the pair's normal (r->tmin, r->nstrips) and emptied; once per pair. */
void strips_clear(const np_pair *p, np_core *r, int32_t *strips);

/* A reference cell (inner coordinates x, y) with the other body's coverage cov > 0 added to the
 * strips; `inside`: it is an intersection cell. */
static inline void strip_cell(const np_core *r, int32_t *strips, int64_t x, int64_t y, uint32_t cov, bool inside)
{
    const int64_t lo = r->tmin, n = r->nstrips;
    /* Tent-splat the coverage between the two strips whose centres are nearest (8-bit weights):
     * b0 is the strip whose centre is at or before the cell, w1 the share of the next one.
     * b0 may be −1 and b0 + 1 may be n, past the corners' strips: those shares are dropped. */
    const int64_t ts = -x * r->nqy + y * r->nqx, b0 = floor_div(ts, NP_NORMAL_ONE) - lo;
    const uint32_t w1 = (uint32_t)((ts - (b0 + lo) * NP_NORMAL_ONE) >> 6); /* 0..255 */
    if (b0 >= 0)
        strips[NP_STRIP_FIELDS * b0 + NP_STRIP_COVER] += (int32_t)((cov * (256 - w1)) >> 8);
    if (b0 + 1 < n)
        strips[NP_STRIP_FIELDS * (b0 + 1) + NP_STRIP_COVER] += (int32_t)((cov * w1) >> 8);
    if (!inside)
        return;
    /* The cell's own strip, round(t): the later of the two from half-way between them on. */
    int32_t *st = strips + NP_STRIP_FIELDS * (b0 + (w1 >= 128));
    const int32_t pr = (int32_t)(x * r->nqx + y * r->nqy);
    if (pr < st[NP_STRIP_MIN]) st[NP_STRIP_MIN] = pr;
    if (pr > st[NP_STRIP_MAX]) st[NP_STRIP_MAX] = pr;
}

/* r->first, r->last, their projections (Q14) and the deepest covers (1/256 cell) from the filled strips. */
void strips_summary(const int32_t *strips, np_core *r);

/* r->nqx, r->nqy: the Q14 normal from the sums r->gx, r->gy, or the pair's fallback when both are zero. */
void quantized_normal(const np_pair *p, np_core *r);

#endif
