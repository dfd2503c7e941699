/* Collision rasters: building the bit-packed mask from a sprite, a mask or both, editing
 * single pixels, and keeping the bounds of the solid pixels exact through per-row and
 * per-column counts and the tile occupancy exact through per-tile counts (an edit never
 * rescans the bitmap). */
#include "alloc.h"
#include "outline.h"
#include "raster.h"
#include "status.h"

#include <stdlib.h>
#include <string.h>

pp_status raster_check_def(const char *fn, const pp_body_def *def)
{
    if (def->width <= 0 || def->height <= 0)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: width and height must be > 0, got %d × %d", fn,
                       (int)def->width, (int)def->height);
    if (def->width > PP_MAX_BITMAP_SIDE || def->height > PP_MAX_BITMAP_SIDE)
        return pp_fail(PP_ERR_LIMIT, "%s: width and height must be ≤ %d (PP_MAX_BITMAP_SIDE), got %d × %d", fn,
                       PP_MAX_BITMAP_SIDE, (int)def->width, (int)def->height);
    if ((int64_t)def->width * def->height > (int64_t)PP_MAX_BITMAP_AREA)
        return pp_fail(PP_ERR_LIMIT, "%s: width × height = %lld is over PP_MAX_BITMAP_AREA (%lld)", fn,
                       (long long)def->width * def->height, (long long)PP_MAX_BITMAP_AREA);
    if (!def->rgba && !def->mask)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: the def has no bitmap (rgba and mask are both NULL)", fn);
    if (!def->mask && (def->alpha_threshold < 1 || def->alpha_threshold > 255))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: alpha_threshold must be 1..255, got %u", fn,
                       (unsigned)def->alpha_threshold);
    return PP_OK;
}

pp_status raster_init(const char *fn, pp_raster *r, const pp_body_def *def)
{
    memset(r, 0, sizeof *r);
    const int32_t w = def->width, h = def->height;
    r->width = w;
    r->height = h;
    r->words_per_row = (w + 63) / 64;
    r->gpu_word = -1;
    r->version = 1;
    r->bits = pp_calloc((size_t)r->words_per_row * (size_t)h, sizeof(uint64_t));
    r->row_count = pp_calloc((size_t)h, sizeof(int32_t));
    r->col_count = pp_calloc((size_t)w, sizeof(int32_t));
    r->tiles_x = (w + RASTER_TILE - 1) >> RASTER_TILE_SHIFT;
    r->tiles_y = (h + RASTER_TILE - 1) >> RASTER_TILE_SHIFT;
    r->tile_count = pp_calloc((size_t)r->tiles_x * (size_t)r->tiles_y, sizeof *r->tile_count);
    if (!r->bits || !r->row_count || !r->col_count || !r->tile_count) {
        raster_free(r);
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for a %d × %d mask", fn, (int)w, (int)h);
    }
    if (def->weights) {
        r->weights = pp_malloc((size_t)w * (size_t)h);
        if (!r->weights) {
            raster_free(r);
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for a %d × %d weight plane", fn, (int)w, (int)h);
        }
        memcpy(r->weights, def->weights, (size_t)w * (size_t)h);
    }

    int32_t x0 = w, y0 = h, x1 = 0, y1 = 0;
    const uint8_t thr = (uint8_t)def->alpha_threshold;
    for (int32_t y = 0; y < h; y++) {
        uint64_t *row = r->bits + (int64_t)y * r->words_per_row;
        const int64_t base = (int64_t)y * w;
        for (int32_t x = 0; x < w; x++) {
            const bool solid = def->mask ? def->mask[base + x] != 0 : def->rgba[4 * (base + x) + 3] >= thr;
            if (!solid)
                continue;
            row[x >> 6] |= (uint64_t)1 << (x & 63);
            r->solid_count++;
            r->row_count[y]++;
            r->col_count[x]++;
            r->tile_count[(int64_t)(y >> RASTER_TILE_SHIFT) * r->tiles_x + (x >> RASTER_TILE_SHIFT)]++;
            if (x < x0) x0 = x;
            if (x >= x1) x1 = x + 1;
            if (y < y0) y0 = y;
            y1 = y + 1;
        }
    }
    r->x0 = x0, r->y0 = y0, r->x1 = x1, r->y1 = y1;
    return PP_OK;
}

pp_status raster_ensure_weights(const char *fn, pp_raster *r)
{
    if (r->weights)
        return PP_OK;
    r->weights = pp_malloc((size_t)r->width * (size_t)r->height);
    if (!r->weights)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for a %d × %d weight plane", fn, (int)r->width, (int)r->height);
    memset(r->weights, 255, (size_t)r->width * (size_t)r->height);
    return PP_OK;
}

void raster_write(pp_raster *r, int32_t x, int32_t y, bool solid, uint32_t weight)
{
    uint64_t *word = &r->bits[(int64_t)y * r->words_per_row + (x >> 6)];
    const uint64_t bit = (uint64_t)1 << (x & 63);
    if (r->weights)
        r->weights[(int64_t)y * r->width + x] = (uint8_t)weight;
    if (((*word & bit) != 0) == solid)
        return;
    const int32_t d = solid ? 1 : -1;
    *word ^= bit;
    r->version++;
    r->solid_count += d;
    r->row_count[y] += d;
    r->col_count[x] += d;
    uint8_t *tile = &r->tile_count[(int64_t)(y >> RASTER_TILE_SHIFT) * r->tiles_x + (x >> RASTER_TILE_SHIFT)];
    *tile = (uint8_t)(*tile + d);
    if (solid) { /* growing is immediate; shrinking waits for raster_edit_done */
        if (raster_empty(r))
            r->x0 = x, r->x1 = x + 1, r->y0 = y, r->y1 = y + 1;
        r->x0 = x < r->x0 ? x : r->x0, r->x1 = x >= r->x1 ? x + 1 : r->x1;
        r->y0 = y < r->y0 ? y : r->y0, r->y1 = y >= r->y1 ? y + 1 : r->y1;
    }
}

void raster_edit_done(pp_raster *r, int32_t y0, int32_t y1)
{
    if (r->solid_count == 0) {
        r->x0 = r->width, r->y0 = r->height, r->x1 = r->y1 = 0;
    } else {
        while (r->col_count[r->x0] == 0) r->x0++;
        while (r->col_count[r->x1 - 1] == 0) r->x1--;
        while (r->row_count[r->y0] == 0) r->y0++;
        while (r->row_count[r->y1 - 1] == 0) r->y1--;
    }
    if (y0 < y1) {
        r->version++; /* a weight alone may have changed, which raster_write does not count */
        raster_mark_dirty(r, y0, y1);
    }
}

void raster_free(pp_raster *r)
{
    raster_outline_free(r);
    pp_free(r->bits);
    pp_free(r->weights);
    pp_free(r->row_count);
    pp_free(r->col_count);
    pp_free(r->tile_count);
    pp_free(r->changed_bands);
    memset(r, 0, sizeof *r);
}

int64_t raster_memory_bytes(const pp_raster *r)
{
    const int64_t pixels = (int64_t)r->width * r->height;
    return (int64_t)r->words_per_row * r->height * (int64_t)sizeof(uint64_t) + (r->weights ? pixels : 0) +
           ((int64_t)r->width + r->height) * (int64_t)sizeof(int32_t) +
           (int64_t)r->tiles_x * r->tiles_y * (int64_t)sizeof *r->tile_count;
}

/* Read the bits of [x0, x1) × [y0, y1) (inside the bitmap): is any solid, is any empty? */
static void scan_bits(const pp_raster *r, int64_t x0, int64_t y0, int64_t x1, int64_t y1, bool *solid, bool *hole)
{
    for (int64_t y = y0; y < y1 && !(*solid && *hole); y++) {
        const uint64_t *row = r->bits + y * r->words_per_row;
        for (int64_t w = x0 >> 6; w <= (x1 - 1) >> 6; w++) {
            const int64_t a = x0 > 64 * w ? x0 - 64 * w : 0, b = x1 < 64 * w + 64 ? x1 - 64 * w : 64;
            const uint64_t mask = (b - a == 64 ? ~(uint64_t)0 : (((uint64_t)1 << (b - a)) - 1)) << a;
            *solid |= (row[w] & mask) != 0;
            *hole |= (row[w] & mask) != mask;
        }
    }
}

raster_state raster_rect_state(const pp_raster *r, int64_t x0, int64_t y0, int64_t x1, int64_t y1)
{
    bool solid = false, hole = x0 < 0 || y0 < 0 || x1 > r->width || y1 > r->height;
    x0 = x0 < 0 ? 0 : x0, y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > r->width ? r->width : x1, y1 = y1 > r->height ? r->height : y1;
    if (x0 >= x1 || y0 >= y1)
        return RASTER_EMPTY;
    const int64_t tx0 = x0 >> RASTER_TILE_SHIFT, tx1 = (x1 - 1) >> RASTER_TILE_SHIFT;
    const int64_t ty0 = y0 >> RASTER_TILE_SHIFT, ty1 = (y1 - 1) >> RASTER_TILE_SHIFT;
    for (int64_t ty = ty0; ty <= ty1 && !(solid && hole); ty++)
        for (int64_t tx = tx0; tx <= tx1 && !(solid && hole); tx++) {
            const raster_state st = raster_tile_state(r, (int32_t)tx, (int32_t)ty);
            /* The tile [ax, ex) × [ay, ey), and its part inside the region. */
            const int64_t ax = tx << RASTER_TILE_SHIFT, ay = ty << RASTER_TILE_SHIFT;
            const int64_t ex = ax + RASTER_TILE < r->width ? ax + RASTER_TILE : r->width;
            const int64_t ey = ay + RASTER_TILE < r->height ? ay + RASTER_TILE : r->height;
            const int64_t cx0 = ax > x0 ? ax : x0, cy0 = ay > y0 ? ay : y0;
            const int64_t cx1 = ex < x1 ? ex : x1, cy1 = ey < y1 ? ey : y1;
            if (st == RASTER_MIXED && (cx0 > ax || cy0 > ay || cx1 < ex || cy1 < ey)) {
                scan_bits(r, cx0, cy0, cx1, cy1, &solid, &hole);
            } else {
                solid |= st != RASTER_EMPTY;
                hole |= st != RASTER_FULL;
            }
        }
    return !solid ? RASTER_EMPTY : hole ? RASTER_MIXED : RASTER_FULL;
}

int32_t raster_row_next(const pp_raster *r, int32_t y, int32_t x)
{
    if (x < 0)
        x = 0;
    const uint64_t *row = r->bits + (int64_t)y * r->words_per_row;
    for (int32_t w = x >> 6; w < r->words_per_row; w++) {
        const uint64_t m = row[w] & (w == x >> 6 ? ~(uint64_t)0 << (x & 63) : ~(uint64_t)0);
        if (m)
            return 64 * w + __builtin_ctzll(m); /* bits past the width are never set */
    }
    return r->width;
}

int32_t raster_row_prev(const pp_raster *r, int32_t y, int32_t x)
{
    if (x >= r->width)
        x = r->width - 1;
    const uint64_t *row = r->bits + (int64_t)y * r->words_per_row;
    for (int32_t w = x >> 6; x >= 0 && w >= 0; w--) {
        const uint64_t m = row[w] & (w == x >> 6 ? ~(uint64_t)0 >> (63 - (x & 63)) : ~(uint64_t)0);
        if (m)
            return 64 * w + 63 - __builtin_clzll(m);
    }
    return -1;
}
