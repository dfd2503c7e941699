/* The tiled core of the CPU narrowphase backend (narrow_cpu_core): the dense core's integers, from the
 * cells near the contact only. It sorts the leaves (sort_tiles), samples the dense ones (sample_dense),
 * and sums the rectangles all in the intersection in closed form (floor_sum, strips_line, strips_full). */
#include "narrow_cpu.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

/* The tiled core. The inner grid is cut into leaves of LEAF × LEAF cells. A rectangle of leaves is
 * halved until it is known to add nothing (no reference cell in it, or no coverage of the other
 * body within a cell of it), known to be all intersection (both bodies solid over it and a cell
 * around it: the normal estimators add nothing, count and centroid sums have closed forms, every
 * cell has coverage 256), or is one leaf. Those leaves alone are sampled, with the two cells
 * around them that their neighbourhoods read, and summed cell by cell as the dense core does.
 * What is known comes from the rasters' tile occupancy (raster_rect_state). */
typedef struct tiling {
    const np_pair *p;
    int32_t leaves_x, leaves_y, words; /* leaves per row and per column; map words per row of leaves */
    uint64_t *dense;                   /* a bit per leaf to sample and sum cell by cell */
    int32_t *full;                     /* rectangles all in the intersection: x0, y0, x1, y1 (inner cells) */
    int64_t nfull;
} tiling;

/* The reference's pixels under inner cells [x0, x1) × [y0, y1) grown by g cells. */
static raster_state ref_state(const np_pair *p, int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t g)
{
    const int64_t s = p->s;
    return raster_rect_state(p->ra, (p->i0 + x0 - g) * s + p->off, (p->j0 + y0 - g) * s + p->off,
                             (p->i0 + x1 - 1 + g) * s + p->off + 1, (p->j0 + y1 - 1 + g) * s + p->off + 1);
}

/* The other body's pixels that the samples of inner cells [x0, x1) × [y0, y1) grown by g cells can
 * read: the box of the points (an affine map, so its corners bound it) and their bilinear
 * footprints, which hold the pixel sb reads. */
static raster_state other_state(const np_pair *p, int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t g)
{
    int64_t lx = INT64_MAX, ly = INT64_MAX, hx = INT64_MIN, hy = INT64_MIN;
    for (int k = 0; k < 4; k++) {
        const int64_t ci = ((k & 1) ? x1 - 1 + g : x0 - g) + RING, cj = ((k >> 1) ? y1 - 1 + g : y0 - g) + RING;
        const int64_t qx = p->qx0 + ci * p->dix + cj * p->djx, qy = p->qy0 + ci * p->diy + cj * p->djy;
        lx = qx < lx ? qx : lx, hx = qx > hx ? qx : hx;
        ly = qy < ly ? qy : ly, hy = qy > hy ? qy : hy;
    }
    return raster_rect_state(p->rb, (lx - HALF_PIXEL) >> NP_FIX_BITS, (ly - HALF_PIXEL) >> NP_FIX_BITS,
                             ((hx - HALF_PIXEL) >> NP_FIX_BITS) + 2, ((hy - HALF_PIXEL) >> NP_FIX_BITS) + 2);
}

/* Inner cells [c[0], c[2]) × [c[1], c[3]) of tiles [tx0, tx1) × [ty0, ty1) of size × size cells (the last are cut
 * by the grid). */
static inline void tile_cells(const np_pair *p, int64_t size, int64_t tx0, int64_t ty0, int64_t tx1, int64_t ty1,
                              int64_t c[4])
{
    c[0] = tx0 * size, c[1] = ty0 * size;
    c[2] = tx1 * size < p->nx ? tx1 * size : p->nx;
    c[3] = ty1 * size < p->ny ? ty1 * size : p->ny;
}

/* The same, of leaves (LEAF × LEAF cells). */
static void leaf_cells(const np_pair *p, int64_t lx0, int64_t ly0, int64_t lx1, int64_t ly1, int64_t c[4])
{
    tile_cells(p, LEAF, lx0, ly0, lx1, ly1, c);
}

/* What a rectangle's parent already knows holds for it too (its cells are a subset). */
enum { REF_FULL = 1, REF_RING_FULL = 2, OTHER_FULL = 4 };

/* What inner cells [x0, x1) × [y0, y1) hold, given what their parent rectangle's `*known` (REF_FULL, ...) says,
 * which it extends: RASTER_EMPTY (they add nothing), RASTER_FULL (every cell and neighbour in both bodies) or
 * RASTER_MIXED. */
static inline raster_state cells_state(const np_pair *p, int64_t x0, int64_t y0, int64_t x1, int64_t y1, int *known)
{
    if (!(*known & REF_FULL)) {
        const raster_state ref = ref_state(p, x0, y0, x1, y1, 0);
        if (ref == RASTER_EMPTY)
            return RASTER_EMPTY; /* every term needs a reference cell */
        *known |= ref == RASTER_FULL ? REF_FULL : 0;
    }
    if (!(*known & OTHER_FULL)) {
        const raster_state other = other_state(p, x0, y0, x1, y1, 1);
        if (other == RASTER_EMPTY)
            return RASTER_EMPTY; /* no coverage on the cells or their neighbours: no intersection, no gradient */
        *known |= other == RASTER_FULL ? OTHER_FULL : 0;
    }
    if ((*known & (REF_FULL | OTHER_FULL)) == (REF_FULL | OTHER_FULL) && !(*known & REF_RING_FULL))
        *known |= ref_state(p, x0, y0, x1, y1, 1) == RASTER_FULL ? REF_RING_FULL : 0;
    return *known == (REF_FULL | REF_RING_FULL | OTHER_FULL) ? RASTER_FULL : RASTER_MIXED;
}

/* Every cell and neighbour in both: count and coordinate sums of the rectangle; the kernel finds no critical cell
 * and the gradient's coverage differences are all zero. */
static inline void add_full_sums(np_core *r, int64_t x0, int64_t y0, int64_t x1, int64_t y1)
{
    const int64_t w = x1 - x0, h = y1 - y0;
    r->count += w * h;
    r->sx += h * (w * (x0 + x1 - 1) / 2);
    r->sy += w * (h * (y0 + y1 - 1) / 2);
}

/* What sort_tiles finds: a rectangle of tiles all in the intersection (full), or one mixed tile. */
typedef void (*rect_visit)(void *user, const int64_t c[4], int32_t tx0, int32_t ty0, int32_t tx1, int32_t ty1,
                           bool full);

/* Sort tiles [tx0, tx1) × [ty0, ty1) of size × size cells: those that add nothing are skipped; a rectangle of them all
 * in the intersection has its count and coordinate sums added to *sums in closed form and is visited whole; the
 * rest are halved down to single tiles, visited as mixed. c: the visited rectangle's inner cells. */
static void sort_tiles(const np_pair *p, int32_t size, int32_t tx0, int32_t ty0, int32_t tx1, int32_t ty1, int known,
                       rect_visit visit, void *user, np_core *sums)
{
    int64_t c[4];
    tile_cells(p, size, tx0, ty0, tx1, ty1, c);
    const raster_state st = cells_state(p, c[0], c[1], c[2], c[3], &known);
    if (st == RASTER_EMPTY)
        return;
    if (st == RASTER_FULL)
        add_full_sums(sums, c[0], c[1], c[2], c[3]);
    if (st == RASTER_FULL || (tx1 - tx0 == 1 && ty1 - ty0 == 1)) {
        visit(user, c, tx0, ty0, tx1, ty1, st == RASTER_FULL);
        return;
    }
    if (tx1 - tx0 >= ty1 - ty0) {
        const int32_t m = tx0 + (tx1 - tx0) / 2;
        sort_tiles(p, size, tx0, ty0, m, ty1, known, visit, user, sums);
        sort_tiles(p, size, m, ty0, tx1, ty1, known, visit, user, sums);
    } else {
        const int32_t m = ty0 + (ty1 - ty0) / 2;
        sort_tiles(p, size, tx0, ty0, tx1, m, known, visit, user, sums);
        sort_tiles(p, size, tx0, m, tx1, ty1, known, visit, user, sums);
    }
}

/* The CPU's leaves: a full rectangle kept for strips_full, a mixed leaf marked dense. */
static void leaf_sorted(void *user, const int64_t c[4], int32_t lx0, int32_t ly0, int32_t lx1, int32_t ly1, bool full)
{
    tiling *t = user;
    (void)lx1, (void)ly1;
    if (full) {
        int32_t *f = t->full + 4 * t->nfull++;
        f[0] = (int32_t)c[0], f[1] = (int32_t)c[1], f[2] = (int32_t)c[2], f[3] = (int32_t)c[3];
    } else {
        t->dense[(int64_t)ly0 * t->words + (lx0 >> 6)] |= (uint64_t)1 << (lx0 & 63);
    }
}

/* The next dense leaf at or after map bit *it, its cells in c; false when none is left. */
static bool next_leaf(const tiling *t, int64_t *it, int64_t c[4])
{
    const int64_t words = (int64_t)t->words * t->leaves_y, row = 64 * (int64_t)t->words;
    for (int64_t w = *it >> 6; w < words; w++, *it = 64 * w) {
        const uint64_t m = t->dense[w] >> (*it & 63);
        if (m) {
            const int64_t bit = *it + __builtin_ctzll(m);
            *it = bit + 1;
            leaf_cells(t->p, bit % row, bit / row, bit % row + 1, bit / row + 1, c);
            return true;
        }
    }
    return false;
}

/* The other body at a 16.16 point, as sample_fixed and coverage_fixed give it. A footprint inside
 * one tile that is empty or full answers from the tile's count; otherwise both pixels of a
 * footprint row come from one word where they share it. */
static inline void sample_other(const pp_raster *r, int64_t qx, int64_t qy, uint8_t *sb, uint16_t *cb)
{
    const int64_t hx = qx - HALF_PIXEL, hy = qy - HALF_PIXEL;
    const int64_t x = hx >> NP_FIX_BITS, y = hy >> NP_FIX_BITS;
    uint32_t m0, m1; /* the footprint's rows y and y + 1: bit 0 pixel x, bit 1 pixel x + 1 */
    if ((uint64_t)x < (uint64_t)r->width - 1 && (uint64_t)y < (uint64_t)r->height - 1) { /* x, y ≥ 0 and a pixel to spare */
        if (((x + 1) & (RASTER_TILE - 1)) && ((y + 1) & (RASTER_TILE - 1))) {
            const int32_t tx = (int32_t)(x >> RASTER_TILE_SHIFT), ty = (int32_t)(y >> RASTER_TILE_SHIFT);
            const raster_state st = raster_tile_state(r, tx, ty);
            if (st != RASTER_MIXED) {
                *sb = st == RASTER_FULL, *cb = st == RASTER_FULL ? 256 : 0;
                return;
            }
        }
        const uint64_t *w = r->bits + y * r->words_per_row + (x >> 6);
        if ((x & 63) != 63) {
            m0 = (uint32_t)(w[0] >> (x & 63)) & 3u;
            m1 = (uint32_t)(w[r->words_per_row] >> (x & 63)) & 3u;
        } else {
            m0 = (uint32_t)(w[0] >> 63) | (uint32_t)(w[1] & 1u) << 1;
            m1 = (uint32_t)(w[r->words_per_row] >> 63) | (uint32_t)(w[r->words_per_row + 1] & 1u) << 1;
        }
    } else if (x < -1 || y < -1 || x >= r->width || y >= r->height) {
        *sb = 0, *cb = 0;
        return;
    } else {
        const int32_t x0 = (int32_t)x, y0 = (int32_t)y;
        m0 = raster_solid_clamped(r, x0, y0) | (uint32_t)raster_solid_clamped(r, x0 + 1, y0) << 1;
        m1 = raster_solid_clamped(r, x0, y0 + 1) | (uint32_t)raster_solid_clamped(r, x0 + 1, y0 + 1) << 1;
    }
    const uint32_t fx = (uint32_t)((hx >> (NP_FIX_BITS - 8)) & 255), fy = (uint32_t)((hy >> (NP_FIX_BITS - 8)) & 255);
    const uint32_t m00 = m0 & 1u, m10 = m0 >> 1, m01 = m1 & 1u, m11 = m1 >> 1;
    const uint32_t sum = m00 * (256 - fx) * (256 - fy) + m10 * fx * (256 - fy) + m01 * (256 - fx) * fy + m11 * fx * fy;
    *cb = (uint16_t)(sum >> 8);
    /* sb's pixel (floor of the point) is one of the footprint's. */
    const int64_t sx = (qx >> NP_FIX_BITS) - x, sy = (qy >> NP_FIX_BITS) - y;
    *sb = (uint8_t)(((sy ? m1 : m0) >> sx) & 1u);
}

/* The leaves whose cells grown by g cells hold plane row cj, as a mask of leaf columns (false: none). */
static bool leaves_near_row(const tiling *t, int64_t cj, int64_t g, uint64_t *mask)
{
    const int64_t y = cj - RING;
    if (y < -g || y >= t->p->ny + g)
        return false;
    const int64_t lo = y - g < 0 ? 0 : (y - g) / LEAF;
    const int64_t hi = (y + g) / LEAF < t->leaves_y ? (y + g) / LEAF : t->leaves_y - 1;
    memcpy(mask, t->dense + lo * t->words, (size_t)t->words * sizeof *mask);
    for (int64_t ly = lo + 1; ly <= hi; ly++)
        for (int32_t w = 0; w < t->words; w++)
            mask[w] |= t->dense[ly * t->words + w];
    return true;
}

/* Plane cells [c0, c1) of plane row cj of the reference. */
static void sample_ref_run(const np_pair *p, int64_t cj, int64_t c0, int64_t c1, uint8_t *sa)
{
    const pp_raster *ra = p->ra;
    const int64_t py = (p->j0 - RING + cj) * p->s + p->off, k0 = cj * (p->nx + 2 * RING);
    if (py < 0 || py >= ra->height) {
        memset(sa + k0 + c0, 0, (size_t)(c1 - c0));
        return;
    }
    const uint64_t *row = ra->bits + py * ra->words_per_row;
    int64_t ci = c0, px = (p->i0 - RING + c0) * p->s + p->off;
    for (; ci < c1 && px < 0; ci++, px += p->s) /* left of the bitmap, inside it, right of it */
        sa[k0 + ci] = 0;
    for (; ci < c1 && px < ra->width; ci++, px += p->s)
        sa[k0 + ci] = (row[px >> 6] >> (px & 63)) & 1u;
    for (; ci < c1; ci++)
        sa[k0 + ci] = 0;
}

/* Whether any of the reference's 3×3 cells around cell k is solid: three rows' 8-byte loads OR-ed and their first
 * three bytes kept (the bytes past them lie in the scratch, as sb follows sa). */
static inline bool any_3x3(const uint8_t *sa, int64_t k, int64_t ex)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    uint64_t up, mid, down;
    memcpy(&up, sa + k - ex - 1, sizeof up);
    memcpy(&mid, sa + k - 1, sizeof mid);
    memcpy(&down, sa + k + ex - 1, sizeof down);
    return ((up | mid | down) & 0xffffffu) != 0;
#else
    return sa[k - ex - 1] | sa[k - ex] | sa[k - ex + 1] | sa[k - 1] | sa[k] | sa[k + 1] | sa[k + ex - 1] | sa[k + ex] |
           sa[k + ex + 1];
#endif
}

/* Plane cells [c0, c1) of plane row cj of the other body, where a reference cell is next to them
 * (nothing reads the others). */
static void sample_other_run(const np_pair *p, int64_t cj, int64_t c0, int64_t c1, const uint8_t *sa, uint8_t *sb,
                             uint16_t *cb)
{
    const int64_t ex = p->nx + 2 * RING;
    int64_t qx = p->qx0 + cj * p->djx + c0 * p->dix, qy = p->qy0 + cj * p->djy + c0 * p->diy;
    for (int64_t k = cj * ex + c0; k < cj * ex + c1; k++, qx += p->dix, qy += p->diy)
        if (any_3x3(sa, k, ex))
            sample_other(p->rb, qx, qy, &sb[k], &cb[k]);
}

/* Sample what the dense leaves read, each cell once: the reference two cells around them (the 5×5
 * cover), the other body one cell around them (the 3×3 neighbourhoods). */
static void sample_dense(const tiling *t, uint64_t *mask, uint8_t *sa, uint8_t *sb, uint16_t *cb)
{
    const np_pair *p = t->p;
    const int64_t ey = p->ny + 2 * RING;
    for (int pass = 0; pass < 2; pass++) {
        const int64_t g = pass ? 1 : 2;
        for (int64_t cj = 0; cj < ey; cj++) {
            if (!leaves_near_row(t, cj, g, mask))
                continue;
            for (int32_t w = 0; w < t->words; w++)
                for (uint64_t m = mask[w]; m;) {
                    /* The lowest run of dense leaves [a, a + n) (one that crosses words is two). */
                    const uint64_t rest = m & (m + (m & (0 - m))), run = m ^ rest;
                    const int64_t a = 64 * w + __builtin_ctzll(run), n = 64 * w + 64 - __builtin_clzll(run) - a;
                    m = rest;
                    int64_t c[4];
                    leaf_cells(p, a, 0, a + n, 1, c);
                    if (pass == 0)
                        sample_ref_run(p, cj, c[0] - g + RING, c[2] + g + RING, sa);
                    else
                        sample_other_run(p, cj, c[0] - g + RING, c[2] + g + RING, sa, sb, cb);
                }
        }
    }
}

/* Σ floor((a·i + b)/m) for i in [0, n), with a, b ≥ 0, m ≥ 1, exactly in O(log): the classic
 * Euclid-like reduction (as in AtCoder's floor_sum). */
static int64_t floor_sum(int64_t n, int64_t m, int64_t a, int64_t b)
{
    int64_t sum = 0;
    for (;;) {
        if (a >= m) {
            sum += n * (n - 1) / 2 * (a / m);
            a %= m;
        }
        if (b >= m) {
            sum += n * (b / m);
            b %= m;
        }
        const int64_t top = a * n + b;
        if (top < m)
            return sum;
        n = top / m, b = top % m;
        const int64_t t = m;
        m = a, a = t;
    }
}

/* The own strip b of intersection cells whose projections run from pa to pb. */
static inline void own_strip_range(int32_t *strips, int64_t b, int64_t pa, int64_t pb)
{
    int32_t *st = strips + NP_STRIP_FIELDS * b;
    const int32_t lo = (int32_t)(pa < pb ? pa : pb), hi = (int32_t)(pa < pb ? pb : pa);
    if (lo < st[NP_STRIP_MIN]) st[NP_STRIP_MIN] = lo;
    if (hi > st[NP_STRIP_MAX]) st[NP_STRIP_MAX] = hi;
}

/* strip_cell for m cells in a line, all in the intersection (coverage 256): tangent coordinate
 * u + k·du (Q14, counted from strip 0's centre) and projection pr + k·dp, k in [0, m). Cells in the
 * same pair of strips form runs; a run adds 256 − w1 and w1 summed in closed form (w1 = the Q14
 * fraction >> 6, a floor sum), and its projections are linear, so their ends bound them. */
static void strips_line(const np_core *r, int32_t *strips, int64_t u, int64_t du, int64_t pr, int64_t dp, int64_t m)
{
    if (du < 0) /* walk the other way: u grows */
        u += (m - 1) * du, du = -du, pr += (m - 1) * dp, dp = -dp;
    const int64_t one = NP_NORMAL_ONE, half = NP_NORMAL_ONE / 2;
    while (m > 0) {
        const int64_t b = floor_div(u, one), f = u - b * one;
        int64_t len = du ? (one - f + du - 1) / du : m;             /* cells before u reaches strip b + 1 */
        len = len < m ? len : m;
        int64_t k = f >= half ? 0 : du ? (half - f + du - 1) / du : len; /* cells with own strip b */
        k = k < len ? k : len;
        const int64_t w1 = floor_sum(len, 64, du, f);
        if (b >= 0)
            strips[NP_STRIP_FIELDS * b + NP_STRIP_COVER] += (int32_t)(256 * len - w1);
        if (b + 1 < r->nstrips)
            strips[NP_STRIP_FIELDS * (b + 1) + NP_STRIP_COVER] += (int32_t)w1;
        if (k > 0)
            own_strip_range(strips, b, pr, pr + (k - 1) * dp);
        if (k < len)
            own_strip_range(strips, b + 1, pr + k * dp, pr + (len - 1) * dp);
        u += len * du, pr += len * dp, m -= len;
    }
}

/* Strips of a rectangle all in the intersection, by lines along the axis on which the tangent
 * coordinate changes least (the longest runs). */
static void strips_full(const np_core *r, int32_t *strips, const int32_t *f)
{
    const int64_t nqx = r->nqx, nqy = r->nqy, u0 = -(int64_t)r->tmin * NP_NORMAL_ONE;
    if (llabs(nqy) <= llabs(nqx)) {
        for (int64_t y = f[1]; y < f[3]; y++)
            strips_line(r, strips, u0 - f[0] * nqy + y * nqx, -nqy, f[0] * nqx + y * nqy, nqx, f[2] - f[0]);
    } else {
        for (int64_t x = f[0]; x < f[2]; x++)
            strips_line(r, strips, u0 - x * nqy + f[1] * nqx, nqx, x * nqx + f[1] * nqy, nqy, f[3] - f[1]);
    }
}

/* np_classify_tiles' visit, and where it goes. */
typedef struct tile_visit {
    int32_t tiles_x;
    np_tile_visit visit;
    void *user;
} tile_visit;

/* Each tile of a sorted rectangle. */
static void tiles_sorted(void *user, const int64_t c[4], int32_t tx0, int32_t ty0, int32_t tx1, int32_t ty1, bool full)
{
    const tile_visit *v = user;
    (void)c;
    for (int32_t ty = ty0; ty < ty1; ty++)
        for (int32_t tx = tx0; tx < tx1; tx++)
            v->visit(v->user, ty * v->tiles_x + tx, full);
}

void np_classify_tiles(const np_pair *p, int32_t size, np_tile_visit visit, void *user, np_core *sums)
{
    tile_visit v = {(p->nx + size - 1) / size, visit, user};
    sort_tiles(p, size, 0, 0, v.tiles_x, (p->ny + size - 1) / size, 0, tiles_sorted, &v, sums);
}

pp_status narrow_cpu_core(const np_settings *set, const np_pair *p, np_scratch *scratch, np_core *out)
{
    *out = (np_core){0};
    tiling t = {.p = p};
    t.leaves_x = (p->nx + LEAF - 1) / LEAF, t.leaves_y = (p->ny + LEAF - 1) / LEAF;
    t.words = (t.leaves_x + 63) / 64;
    const int64_t map_words = (int64_t)t.words * (t.leaves_y + 1);
    pp_status st = np_scratch_reserve(scratch, p->nx, p->ny);
    if (st)
        return st;
    t.dense = scratch->leaves, t.full = scratch->rects;
    memset(t.dense, 0, (size_t)map_words * sizeof *t.dense);
    sort_tiles(p, LEAF, 0, 0, t.leaves_x, t.leaves_y, 0, leaf_sorted, &t, out);

    const int64_t cells = np_pair_cells(p);
    uint8_t *sa = scratch->cells, *sb = scratch->cells + cells;
    uint16_t *cb = (uint16_t *)(scratch->cells + 2 * cells);
    sample_dense(&t, t.dense + (int64_t)t.words * t.leaves_y, sa, sb, cb);
    const int64_t ex = p->nx + 2 * RING;
    for (int64_t it = 0, c[4]; next_leaf(&t, &it, c);) {
        cell_sums_acc acc = {0};
        for (int64_t y = c[1]; y < c[3]; y++)
            for (int64_t x = c[0]; x < c[2]; x++)
                cell_sums(sa, sb, cb, (y + RING) * ex + x + RING, ex, x, y, set->normal_method, &acc);
        add_sums(out, &acc);
    }
    if (out->count == 0)
        return PP_OK;
    quantized_normal(p, out);
    strips_clear(p, out, scratch->strips);
    for (int64_t it = 0, c[4]; next_leaf(&t, &it, c);)
        for (int64_t y = c[1]; y < c[3]; y++)
            for (int64_t x = c[0]; x < c[2]; x++) {
                const int64_t k = (y + RING) * ex + x + RING;
                if (sa[k] && cb[k])
                    strip_cell(out, scratch->strips, x, y, cb[k], sb[k]);
            }
    for (int64_t i = 0; i < t.nfull; i++)
        strips_full(out, scratch->strips, t.full + 4 * i);
    strips_summary(scratch->strips, out);
    return PP_OK;
}
