/* A body's collision raster: a bit-packed solid mask, an optional weight plane, the bounds of
 * its solid pixels, and its tile occupancy (solid pixels per tile, so that a region can be known
 * all empty or all solid without reading its bits). */
#ifndef PP_RASTER_H
#define PP_RASTER_H

#include "physpix.h"

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

/* Occupancy tiles are RASTER_TILE × RASTER_TILE pixels; those on the right and bottom edges are
 * cut by the bitmap. 8 px measured best against 16 and 32 on terrain contacts (tests/bench/
 * narrowphase/core.c: a crate in a crater 5-10% faster, a deep 256 px overlap 2-4% slower), and
 * its byte counts cost 1/8 bit per pixel. */
#define RASTER_TILE_SHIFT 3
#define RASTER_TILE (1 << RASTER_TILE_SHIFT)
_Static_assert(RASTER_TILE * RASTER_TILE <= UINT8_MAX, "a tile's count must fit its byte");

/* What a tile or a region holds: no solid pixel, only solid pixels, or both. */
typedef enum raster_state { RASTER_EMPTY, RASTER_FULL, RASTER_MIXED } raster_state;

typedef struct pp_raster {
    int32_t width, height;
    int32_t words_per_row;   /* 64-bit words per row; bit k of word w is pixel 64·w + k */
    uint64_t *bits;          /* solid mask, height × words_per_row */
    uint8_t *weights;        /* width × height relative masses; NULL: every solid pixel weighs 255 */
    int64_t solid_count;     /* number of solid pixels */
    int32_t x0, y0, x1, y1;  /* solid bounds [x0, x1) × [y0, y1); empty when x0 ≥ x1 */
    int32_t *row_count, *col_count; /* solid pixels per row and per column: exact bounds after edits */
    int32_t tiles_x, tiles_y; /* occupancy tiles per row and per column */
    uint8_t *tile_count;     /* solid pixels per tile, tiles_y × tiles_x, exact after every write */
    int64_t gpu_word;        /* first 32-bit word of the mask in the world's GPU mirror; −1: not mirrored */
    int32_t dirty_y0, dirty_y1; /* rows edited since the mirror was written; clean when y0 ≥ y1 */
    uint64_t version;        /* counts the mask's changes (1 when made): what is derived from the bits keys on it */
    struct raster_outline *outline; /* the boundary's runs (outline.c), as of its own version; NULL until asked */
    uint8_t *changed_bands;  /* per band of RASTER_TILE rows: changed since the world kept its planes for saved
                              * states (lib/io/state.c); NULL while it keeps none */
} pp_raster;

/* Validate a def's bitmap (sizes, limits, planes) without allocating. */
pp_status raster_check_def(const char *fn, const pp_body_def *def);

/* Build the raster from a def's planes (rgba alpha, mask override, weights). */
pp_status raster_init(const char *fn, pp_raster *r, const pp_body_def *def);

void raster_free(pp_raster *r);

/* Bytes the raster allocates (mask, weight plane, row, column and tile counts). */
int64_t raster_memory_bytes(const pp_raster *r);

/* The state of the pixels [x0, x1) × [y0, y1), exactly; pixels outside the bitmap are empty. Whole
 * tiles answer from their counts, the bits are read only where a mixed tile is cut by the region. */
raster_state raster_rect_state(const pp_raster *r, int64_t x0, int64_t y0, int64_t x1, int64_t y1);

/* Give the raster a weight plane (every pixel 255) before a write of another weight. */
pp_status raster_ensure_weights(const char *fn, pp_raster *r);

/* Set one pixel (the weight is stored only where there is a plane); bounds grow at once. */
void raster_write(pp_raster *r, int32_t x, int32_t y, bool solid, uint32_t weight);

/* After a batch of writes touching rows [y0, y1): shrink the bounds, mark the rows dirty. */
void raster_edit_done(pp_raster *r, int32_t y0, int32_t y1);

/* The first solid pixel of row y at or after column x (x may lie outside the bitmap), or width if none. */
int32_t raster_row_next(const pp_raster *r, int32_t y, int32_t x);
/* The last solid pixel of row y at or before column x (x may lie outside the bitmap), or -1 if none. */
int32_t raster_row_prev(const pp_raster *r, int32_t y, int32_t x);

static inline bool raster_solid(const pp_raster *r, int32_t x, int32_t y)
{
    return (r->bits[(int64_t)y * r->words_per_row + (x >> 6)] >> (x & 63)) & 1u;
}

/* Solid test that answers false outside the bitmap. */
static inline bool raster_solid_clamped(const pp_raster *r, int32_t x, int32_t y)
{
    return (uint32_t)x < (uint32_t)r->width && (uint32_t)y < (uint32_t)r->height && raster_solid(r, x, y);
}

/* Has pixel (x, y) an empty neighbour (corners count, outside the bitmap is empty)? Only such a pixel's square can
 * be touched first by a shape moving in from outside (the casts). */
static inline bool raster_edge_pixel(const pp_raster *r, int32_t x, int32_t y)
{
    for (int32_t dy = -1; dy <= 1; dy++)
        for (int32_t dx = -1; dx <= 1; dx++)
            if (!raster_solid_clamped(r, x + dx, y + dy))
                return true;
    return false;
}

/* Pixels x .. x + 63 of row y as bits (bit k is pixel x + k), 0 outside the bitmap: a row's neighbourhood read a
 * word at a time. */
static inline uint64_t raster_row_bits(const pp_raster *r, int32_t y, int32_t x)
{
    if ((uint32_t)y >= (uint32_t)r->height)
        return 0;
    const uint64_t *row = r->bits + (int64_t)y * r->words_per_row;
    const int32_t w = x >= 0 ? x >> 6 : -((63 - x) >> 6), o = x - 64 * w; /* w = floor(x / 64) */
    const uint64_t lo = w >= 0 && w < r->words_per_row ? row[w] : 0;
    const uint64_t hi = w + 1 >= 0 && w + 1 < r->words_per_row ? row[w + 1] : 0;
    return o ? lo >> o | hi << (64 - o) : lo;
}

/* From the bits of rows y − 1, y, y + 1 at x − 1 (raster_row_bits): row y's pixels x .. x + n − 1 (n ≤ 62) that are
 * solid with an empty neighbour (raster_edge_pixel), as bits. */
static inline uint64_t raster_edge_bits_of(uint64_t a, uint64_t s, uint64_t b, int32_t n)
{
    /* Bit k of a run of three: pixels k − 1, k, k + 1 all solid. */
    const uint64_t inner = (a & a >> 1 & a << 1) & (s & s >> 1 & s << 1) & (b & b >> 1 & b << 1);
    return (s & ~inner) >> 1 & (n >= 64 ? ~(uint64_t)0 : ((uint64_t)1 << n) - 1);
}

/* Row y's pixels x .. x + n − 1 (n ≤ 62) that are solid with an empty neighbour, as bits. */
static inline uint64_t raster_edge_bits(const pp_raster *r, int32_t y, int32_t x, int32_t n)
{
    return raster_edge_bits_of(raster_row_bits(r, y - 1, x - 1), raster_row_bits(r, y, x - 1),
                               raster_row_bits(r, y + 1, x - 1), n);
}

/* The state of tile (tx, ty) from its count (an edge tile holds fewer pixels). */
static inline raster_state raster_tile_state(const pp_raster *r, int32_t tx, int32_t ty)
{
    const int32_t n = r->tile_count[(int64_t)ty * r->tiles_x + tx];
    if (n == 0)
        return RASTER_EMPTY;
    const int32_t w = r->width - (tx << RASTER_TILE_SHIFT), h = r->height - (ty << RASTER_TILE_SHIFT);
    return n == (w < RASTER_TILE ? w : RASTER_TILE) * (h < RASTER_TILE ? h : RASTER_TILE) ? RASTER_FULL : RASTER_MIXED;
}

static inline uint32_t raster_weight(const pp_raster *r, int32_t x, int32_t y)
{
    return r->weights ? r->weights[(int64_t)y * r->width + x] : 255u;
}

/* Rows [y0, y1) changed: the GPU mirror rewrites them before its next use. */
static inline void raster_mark_dirty(pp_raster *r, int32_t y0, int32_t y1)
{
    if (r->changed_bands && y0 < y1)
        memset(r->changed_bands + (y0 >> RASTER_TILE_SHIFT), 1,
               (size_t)(((y1 - 1) >> RASTER_TILE_SHIFT) - (y0 >> RASTER_TILE_SHIFT) + 1));
    if (r->dirty_y0 >= r->dirty_y1)
        r->dirty_y0 = y0, r->dirty_y1 = y1;
    r->dirty_y0 = y0 < r->dirty_y0 ? y0 : r->dirty_y0;
    r->dirty_y1 = y1 > r->dirty_y1 ? y1 : r->dirty_y1;
}

static inline bool raster_empty(const pp_raster *r) { return r->x0 >= r->x1; }

#endif
