/* The collision-stage contract shared by the CPU and GPU backends. A pair is set up once on the
 * CPU (np_pair_setup: the reference body, the sampling grid, 16.16 fixed-point steps), its
 * integer core runs on either backend (np_core: sums, quantised normal, strips), and the CPU
 * turns the core into contacts (np_pair_finish). Only the core runs on the GPU, and it is all
 * integers, so both backends return the same contacts bit for bit. */
#ifndef PP_NARROWPHASE_H
#define PP_NARROWPHASE_H

#include "math2d.h"
#include "raster.h"

#include <stdbool.h>
#include <stdint.h>

typedef struct np_body {
    const pp_raster *raster;
    dvec2 pos;          /* world position of the pivot, px */
    dvec2 pivot;        /* bitmap coordinates, px */
    double c, s;        /* cos and sin of the angle */
} np_body;

typedef struct np_settings {
    pp_normal_method normal_method;
    pp_contact_mode contact_mode;
    int32_t stride;     /* 1, 2 or 4 pixels per sample */
} np_settings;

/* Sampled ring around the inner grid: the 5×5 taper window reaches two cells out. */
#define NP_RING 2

/* Fixed-point precisions: sampling positions in 16.16, the normal in Q14. */
#define NP_FIX_BITS 16
#define NP_NORMAL_ONE 16384

/* One pair, ready for either backend. Grid cell (i, j) of the sampled plane (inner grid plus
 * the ring) reads reference pixel ((i0 − RING + i)·s + off, (j0 − RING + j)·s + off) and the
 * other body at the 16.16 point q0 + i·di + j·dj. */
typedef struct np_pair {
    const pp_raster *ra, *rb;   /* reference (the larger body) and other */
    bool swap;                  /* the reference is the caller's b */
    bool fits_int32;            /* every sample point fits the GPU's 32-bit arithmetic */
    int32_t s, off, i0, j0;
    int32_t nx, ny;             /* inner cells */
    int64_t qx0, qy0, dix, diy, djx, djy;
    dvec2 fallback_n;           /* unit normal, reference axes, when the overlap is symmetric */
    int32_t fallback_nqx, fallback_nqy;
} np_pair;

/* The integer outcome of one pair; identical from both backends. */
typedef struct np_core {
    int64_t count, sx, sy;      /* intersection cells and the sums of their inner-cell coordinates */
    int64_t gx, gy;             /* unnormalised normal estimate, reference axes */
    int32_t nqx, nqy;           /* the normal in Q14 */
    int32_t tmin, nstrips;      /* strip index of strip 0, and the strip count; strip b is centred on t = b */
    int32_t first, last;        /* first and last strips holding intersection cells */
    int32_t first_min, first_max, last_min, last_max; /* their projections on the normal, Q14 */
    int32_t cover_all, cover_lo, cover_hi; /* deepest cover (1/256 cell): all strips, [first, mid], (mid, last] */
} np_core;

/* Up to two contact points; normal points from a to b (handles are the caller's to fill). */
typedef struct np_result {
    int32_t count;
    pp_contact contacts[PP_MAX_CONTACTS_PER_PAIR];
    int64_t samples;    /* raster samples examined */
} np_result;

/* Reusable CPU buffers, grown as needed, owned by the world (one per thread). */
typedef struct np_scratch {
    uint8_t *cells;     /* sampled planes of A and B and B's coverage */
    int64_t cells_cap;
    int32_t *strips;    /* min/max projection and cover per strip */
    int64_t strips_cap;
    uint64_t *leaves;   /* tiled core: a bit per leaf summed cell by cell */
    int64_t leaves_cap;
    int32_t *rects;     /* tiled core: rectangles of cells all in the intersection, 4 ints each */
    int64_t rects_cap;
} np_scratch;

enum { NP_STRIP_MIN, NP_STRIP_MAX, NP_STRIP_COVER, NP_STRIP_FIELDS };

/* Integer division rounding toward −∞ and +∞. */
static inline int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

static inline int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }

/* Reference-body bitmap coordinates (px) of inner cell (ci, cj)'s sample point. */
static inline dvec2 np_grid_to_local(const np_pair *p, double ci, double cj)
{
    return dv((p->i0 + ci) * p->s + p->off + 0.5, (p->j0 + cj) * p->s + p->off + 0.5);
}

/* Set a pair up; false when no cell of the grid can be in both bodies (no contact, nothing to run). */
bool np_pair_setup(const np_settings *set, const np_body *a, const np_body *b, np_pair *p);

/* np_pair_setup's grid alone (false only when the boxes cannot overlap); the tests check against it that a pair
 * np_pair_setup drops has no intersection cell. */
bool np_pair_grid(const np_settings *set, const np_body *a, const np_body *b, np_pair *p);

/* Cells of the sampled plane (inner grid plus ring), and the most strips the pair can have: the
 * inner cells' tangent coordinates span at most (nx − 1) + (ny − 1) cells, so their rounded values
 * at most nx + ny strips. */
static inline int64_t np_pair_cells(const np_pair *p)
{
    return (int64_t)(p->nx + 2 * NP_RING) * (p->ny + 2 * NP_RING);
}
static inline int64_t np_pair_max_strips(const np_pair *p) { return (int64_t)p->nx + p->ny + 4; }

/* The normal in Q14 from the integer estimate: magnitudes cut to 15 bits toward zero, then
 * each component rounded exactly (half away from zero) without floating point. */
void np_quantize_normal(int64_t gx, int64_t gy, int32_t *nqx, int32_t *nqy);

/* The CPU backend's integer core of one pair: works only near the contact (tiles known empty or
 * all intersection are skipped or summed in closed form); the same integers as the dense core. */
pp_status narrow_cpu_core(const np_settings *set, const np_pair *p, np_scratch *scratch, np_core *out);

/* The C twin of the GPU's tiles pass (glsl/narrow_tiles.comp), which the tests hold it to: a pair's inner grid cut
 * into tiles of size × size cells (row-major index), sorted as narrow_cpu_core sorts its leaves. A tile that adds nothing is skipped; every other is visited,
 * `full` when each of its cells and their neighbours lie in both bodies (then coverage 256, no normal term), and a
 * full tile's count and coordinate sums are added to *sums in closed form. */
typedef void (*np_tile_visit)(void *user, int32_t tile, bool full);
void np_classify_tiles(const np_pair *p, int32_t size, np_tile_visit visit, void *user, np_core *sums);

/* The plain per-cell core, the reference the tiled core is tested against: every cell of the plane
 * sampled and summed, as the GPU does. */
pp_status narrow_cpu_core_dense(const np_settings *set, const np_pair *p, np_scratch *scratch, np_core *out);

/* Contacts from a pair's core (both backends). */
void np_pair_finish(const np_settings *set, const np_body *a, const np_body *b, const np_pair *p,
                    const np_core *core, np_result *out);

/* Set up, run on the CPU, finish: one pair, as queries need it. */
pp_status narrow_cpu_collide(const np_settings *set, const np_body *a, const np_body *b, np_scratch *scratch,
                             np_result *out);
void np_scratch_free(np_scratch *s);

/* Grow the scratch to what narrow_cpu_core needs for any pair of at most nx × ny cells. */
pp_status np_scratch_reserve(np_scratch *s, int32_t nx, int32_t ny);

/* A pair's inner grid for debug views: per cell the reference's (bit 0) and the other's (bit 1)
 * solidity, bit 2 on critical intersection cells, and there the 3×3-kernel vector (x, y) in reference
 * axes, pointing from the reference into the other body. */
pp_status narrow_cpu_debug(const np_pair *p, np_scratch *scratch, uint8_t *flags, int32_t *kernel_xy);

#endif
