/* A raster's outline (outline.h): horizontal runs from each grid line's pair of rows (the bits where one row
 * is solid and the other not), vertical runs from each row's bits against themselves shifted by one column,
 * carried down the rows while they continue. A word at a time; only the rows of the solid bounds are read. */
#include "alloc.h"
#include "outline.h"
#include "status.h"

#include <string.h>

/* The runs being built, and whether growing them failed. */
typedef struct run_list {
    outline_run *runs;
    int32_t count, capacity;
    bool failed;
} run_list;

static void add_run(run_list *l, int32_t ax, int32_t ay, int32_t bx, int32_t by)
{
    if (l->failed || !ARRAY_RESERVE(l->runs, l->capacity, l->count + 1)) {
        l->failed = true;
        return;
    }
    l->runs[l->count++] = (outline_run){ax, ay, bx, by};
}

/* Each run of set bits [x0, x1) of a bit row of `words` words on grid line y, as a horizontal run: left to right
 * when the solid side is below (ltr), else right to left. */
static void add_bit_runs(run_list *l, const uint64_t *m, int32_t words, int32_t y, bool ltr)
{
    int64_t start = -1;
    for (int32_t w = 0; w < words; w++) {
        const uint64_t v = m[w];
        int b = 0;
        while (b < 64) {
            if (start < 0) {
                const uint64_t s = v >> b;
                if (!s)
                    break;
                b += __builtin_ctzll(s);
                start = 64 * (int64_t)w + b;
            }
            const uint64_t z = ~v >> b;
            if (!z)
                break; /* the run goes on into the next word */
            b += __builtin_ctzll(z);
            const int32_t end = 64 * w + b;
            if (ltr)
                add_run(l, (int32_t)start, y, end, y);
            else
                add_run(l, end, y, (int32_t)start, y);
            start = -1;
        }
    }
    if (start >= 0)
        add_run(l, (int32_t)start, y, 64 * words, y);
}

/* The vertical runs on one side: for each grid column x whose bit changed between the previous row's mask and
 * this row's (cur), a run starts at row y or ends there (down when the solid side is left of it, else up). */
static void carry_columns(run_list *l, const uint64_t *prev, const uint64_t *cur, int32_t words, int32_t y,
                          int32_t *start, bool down)
{
    for (int32_t w = 0; w < words; w++) {
        uint64_t d = prev[w] ^ cur[w];
        while (d) {
            const int b = __builtin_ctzll(d);
            d &= d - 1;
            const int32_t x = 64 * w + b;
            if (cur[w] >> b & 1)
                start[x] = y;
            else if (down)
                add_run(l, x, start[x], x, y);
            else
                add_run(l, x, y, x, start[x]);
        }
    }
}

/* Build the outline of r's mask as it is now. */
static pp_status outline_build(const char *fn, const pp_raster *r, run_list *l)
{
    if (raster_empty(r))
        return PP_OK;
    const int32_t wpr = r->words_per_row, lw = r->width / 64 + 1; /* grid columns 0..width */
    /* Scratch: a zero row, the shifted row, and per side the previous mask, this row's and the runs' starts. */
    uint64_t *buf = pp_calloc((size_t)lw * 6, sizeof *buf);
    int32_t *start = pp_malloc(2 * ((size_t)r->width + 1) * sizeof *start);
    if (!buf || !start) {
        pp_free(buf);
        pp_free(start);
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory to outline a %d × %d bitmap", fn, (int)r->width,
                       (int)r->height);
    }
    uint64_t *zero = buf, *mask = buf + lw, *left_prev = buf + 2 * lw, *left = buf + 3 * lw;
    uint64_t *right_prev = buf + 4 * lw, *right = buf + 5 * lw;
    int32_t *start_left = start, *start_right = start + r->width + 1;
    for (int32_t y = r->y0; y <= r->y1; y++) {
        const uint64_t *above = y > r->y0 ? r->bits + (int64_t)(y - 1) * wpr : zero;
        const uint64_t *row = y < r->y1 ? r->bits + (int64_t)y * wpr : zero;
        /* Grid line y: the tops of this row's solid pixels (solid below), then the bottoms of the row above's. */
        for (int32_t w = 0; w < wpr; w++)
            mask[w] = row[w] & ~above[w];
        add_bit_runs(l, mask, wpr, y, true);
        for (int32_t w = 0; w < wpr; w++)
            mask[w] = above[w] & ~row[w];
        add_bit_runs(l, mask, wpr, y, false);
        /* Grid columns of row y: bit x of the shifted row is pixel x − 1. */
        for (int32_t w = 0; w < lw; w++) {
            const uint64_t here = w < wpr ? row[w] : 0, before = w > 0 ? row[w - 1] >> 63 : 0;
            const uint64_t shifted = here << 1 | before;
            left[w] = shifted & ~here, right[w] = here & ~shifted;
        }
        carry_columns(l, left_prev, left, lw, y, start_left, true);
        carry_columns(l, right_prev, right, lw, y, start_right, false);
        memcpy(left_prev, left, (size_t)lw * sizeof *left);
        memcpy(right_prev, right, (size_t)lw * sizeof *right);
    }
    pp_free(buf);
    pp_free(start);
    return l->failed ? pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for the outline of a %d × %d bitmap", fn,
                               (int)r->width, (int)r->height)
                     : PP_OK;
}

pp_status raster_outline_get(const char *fn, pp_raster *r, const raster_outline **out)
{
    if (r->outline && r->outline->version == r->version) {
        *out = r->outline;
        return PP_OK;
    }
    raster_outline *o = r->outline ? r->outline : pp_calloc(1, sizeof *o);
    if (!o)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for an outline", fn);
    r->outline = o;
    /* Built into the old array's room; on failure the outline is left empty and stale, built again next time. */
    run_list l = {o->runs, 0, o->capacity, false};
    o->count = 0, o->version = 0;
    pp_status st = outline_build(fn, r, &l);
    o->runs = l.runs, o->capacity = l.capacity;
    if (st)
        return st;
    o->count = l.count, o->version = r->version;
    *out = o;
    return PP_OK;
}

void raster_outline_free(pp_raster *r)
{
    if (r->outline)
        pp_free(r->outline->runs);
    pp_free(r->outline);
    r->outline = NULL;
}
