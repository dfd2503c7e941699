/* A body's collision raster: a bit-packed solid mask, an optional weight plane,
 * and the bounds of its solid pixels. */
#ifndef PP_RASTER_H
#define PP_RASTER_H

#include "physpix.h"

#include <stdbool.h>
#include <stdint.h>

typedef struct pp_raster {
    int32_t width, height;
    int32_t words_per_row;   /* 64-bit words per row; bit k of word w is pixel 64·w + k */
    uint64_t *bits;          /* solid mask, height × words_per_row */
    uint8_t *weights;        /* width × height relative masses; NULL: every solid pixel weighs 255 */
    int64_t solid_count;     /* number of solid pixels */
    int32_t x0, y0, x1, y1;  /* solid bounds [x0, x1) × [y0, y1); empty when x0 ≥ x1 */
    int32_t *row_count, *col_count; /* solid pixels per row and per column: exact bounds after edits */
    int64_t gpu_word;        /* first 32-bit word of the mask in the world's GPU mirror; −1: not mirrored */
    int32_t dirty_y0, dirty_y1; /* rows edited since the mirror was written; clean when y0 ≥ y1 */
} pp_raster;

/* Validate a def's bitmap (sizes, limits, planes) without allocating. */
pp_status raster_check_def(const pp_body_def *def);

/* Build the raster from a def's planes (rgba alpha, mask override, weights). */
pp_status raster_init(pp_raster *r, const pp_body_def *def);

void raster_free(pp_raster *r);

/* Give the raster a weight plane (every pixel 255) before a write of another weight. */
pp_status raster_ensure_weights(pp_raster *r);

/* Set one pixel (the weight is stored only where there is a plane); bounds grow at once. */
void raster_write(pp_raster *r, int32_t x, int32_t y, bool solid, uint32_t weight);

/* After a batch of writes touching rows [y0, y1): shrink the bounds, mark the rows dirty. */
void raster_edit_done(pp_raster *r, int32_t y0, int32_t y1);

static inline bool raster_solid(const pp_raster *r, int32_t x, int32_t y)
{
    return (r->bits[(int64_t)y * r->words_per_row + (x >> 6)] >> (x & 63)) & 1u;
}

/* Solid test that answers false outside the bitmap. */
static inline bool raster_solid_clamped(const pp_raster *r, int32_t x, int32_t y)
{
    return (uint32_t)x < (uint32_t)r->width && (uint32_t)y < (uint32_t)r->height && raster_solid(r, x, y);
}

static inline uint32_t raster_weight(const pp_raster *r, int32_t x, int32_t y)
{
    return r->weights ? r->weights[(int64_t)y * r->width + x] : 255u;
}

/* Rows [y0, y1) changed: the GPU mirror rewrites them before its next use. */
static inline void raster_mark_dirty(pp_raster *r, int32_t y0, int32_t y1)
{
    if (r->dirty_y0 >= r->dirty_y1)
        r->dirty_y0 = y0, r->dirty_y1 = y1;
    r->dirty_y0 = y0 < r->dirty_y0 ? y0 : r->dirty_y0;
    r->dirty_y1 = y1 > r->dirty_y1 ? y1 : r->dirty_y1;
}

static inline bool raster_empty(const pp_raster *r) { return r->x0 >= r->x1; }

#endif
