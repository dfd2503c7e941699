/* The GPU backend of the narrowphase core (glsl/narrow_*.comp): the world's masks live in one
 * buffer, each body's bit-packed rows at its own offset followed by its 8×8 occupancy counts, written
 * once and then only where rows were edited. A step's pairs go up as one table and run as five passes
 * over all of them, read back once: tiles (each 16×16 tile of each pair's grid sorted as the CPU's tiled
 * core sorts its leaves: those that add nothing left out, those all in the intersection summed in closed
 * form), sums per mixed tile, normal per pair, strips per tile, summary per pair. Only a pair's rim is
 * sampled, and the host's share of a pair is one row of the table. */
#include "alloc.h"
#include "narrow_gpu.h"
#include "gpu_context.h"
#include "status.h"

#include <stdlib.h>
#include <string.h>

enum { RESULT_WORDS = 24, TILE = 16, PAIRS_PER_GROUP = 64 };
/* One pair as glsl/common.glsl's Pair reads it. */
typedef struct gpu_pair {
    int32_t ra[4], rb[4], grid[4], size[4], q[4], q2[4];
} gpu_pair;

typedef struct span {
    int64_t at, len;
} span;

enum { BUF_MASKS, BUF_PAIRS, BUF_TILES, BUF_RESULTS, BUF_STRIPS, BUF_LISTS, BUF_COUNT };
/* BUF_LISTS (glsl/common.glsl's L_*): the batch's grid tiles and pairs, then two indirect dispatches of three
 * words, written by glsl/narrow_args.comp. */
enum { L_GRID_TILES, L_PAIRS, L_SUMS_ARGS, L_STRIPS_ARGS = L_SUMS_ARGS + 3, L_WORDS = L_STRIPS_ARGS + 3 };

struct gpu_narrow {
    GLuint buf[BUF_COUNT];
    int64_t bytes[BUF_COUNT];   /* allocated size of each buffer */
    int64_t mask_top;           /* 32-bit words of the mask buffer in use, holes included */
    span *holes;                /* freed mask ranges below mask_top, by address */
    int32_t hole_count, hole_cap;
    int64_t row_groups;         /* the most workgroups a dispatch's row holds: the context's, or fewer (the tests) */
    int64_t mixed, full;        /* tiles of each kind sampled since the world was made (the tests' view of the tiles pass) */
    /* Host staging, grown as needed. */
    gpu_pair *pairs;
    int32_t *index;             /* the caller's pair behind each GPU pair */
    uint32_t *results;          /* RESULT_WORDS a pair, then the mixed and full tiles' counts */
    int64_t pair_cap;
};

pp_status gpu_narrow_create(const char *fn, gpu_narrow **out)
{
    const gpu_gl *gl;
    const gpu_info *info;
    pp_status st = gpu_acquire(fn, &gl, &info);
    if (st)
        return st;
    gpu_narrow *g = pp_calloc(1, sizeof *g);
    if (g) {
        gl->GenBuffers(BUF_COUNT, g->buf);
        g->row_groups = info->max_groups_x;
    }
    gpu_release();
    if (!g)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for the GPU backend", fn);
    *out = g;
    return PP_OK;
}

void gpu_narrow_destroy(gpu_narrow *g)
{
    if (!g)
        return;
    const gpu_gl *gl;
    const gpu_info *info;
    if (gpu_acquire("pp_world_destroy", &gl, &info) == PP_OK) {
        gl->DeleteBuffers(BUF_COUNT, g->buf);
        gpu_release();
    }
    pp_free(g->holes);
    pp_free(g->pairs);
    pp_free(g->index);
    pp_free(g->results);
    pp_free(g);
}

pp_status gpu_narrow_probe_software(const char *fn, bool *software) { return gpu_probe_software(fn, software); }

void gpu_narrow_limit_rows(gpu_narrow *g, int32_t groups) { g->row_groups = groups; }

void gpu_narrow_tiles_sampled(const gpu_narrow *g, int64_t *mixed, int64_t *full) { *mixed = g->mixed, *full = g->full; }

/* A mask's 32-bit words in the mirror: its rows, then its tiles' counts, a byte each (glsl/narrow_tiles.comp). */
static int64_t row_words(const pp_raster *r) { return (int64_t)r->height * r->words_per_row * 2; }
static int64_t mask_words(const pp_raster *r) { return row_words(r) + ((int64_t)r->tiles_x * r->tiles_y + 3) / 4; }

void gpu_narrow_forget(gpu_narrow *g, pp_raster *r)
{
    if (r->gpu_word < 0)
        return;
    span s = {r->gpu_word, mask_words(r)};
    r->gpu_word = -1;
    /* Keep the holes sorted and merged; a hole at the top lowers the top instead. */
    int32_t i = 0;
    while (i < g->hole_count && g->holes[i].at < s.at)
        i++;
    if (i > 0 && g->holes[i - 1].at + g->holes[i - 1].len == s.at) {
        s.at = g->holes[i - 1].at, s.len += g->holes[i - 1].len;
        memmove(g->holes + i - 1, g->holes + i, (size_t)(g->hole_count - i) * sizeof(span));
        g->hole_count--, i--;
    }
    if (i < g->hole_count && s.at + s.len == g->holes[i].at) {
        s.len += g->holes[i].len;
        memmove(g->holes + i, g->holes + i + 1, (size_t)(g->hole_count - i - 1) * sizeof(span));
        g->hole_count--;
    }
    if (s.at + s.len == g->mask_top) {
        g->mask_top = s.at;
        return;
    }
    if (!ARRAY_RESERVE(g->holes, g->hole_cap, g->hole_count + 1))
        return; /* the words stay unused until the world goes; nothing is lost but space */
    memmove(g->holes + i + 1, g->holes + i, (size_t)(g->hole_count - i) * sizeof(span));
    g->holes[i] = s;
    g->hole_count++;
}

/* Room for `words` in the mask buffer: the first hole that fits, else the top, growing the
 * buffer (copied on the GPU) up to the largest storage block the context allows. −1: no room. */
static int64_t mask_alloc(gpu_narrow *g, const gpu_gl *gl, const gpu_info *info, int64_t words)
{
    for (int32_t i = 0; i < g->hole_count; i++) {
        if (g->holes[i].len < words)
            continue;
        const int64_t at = g->holes[i].at;
        g->holes[i].at += words, g->holes[i].len -= words;
        if (g->holes[i].len == 0)
            memmove(g->holes + i, g->holes + i + 1, (size_t)(--g->hole_count - i) * sizeof(span));
        return at;
    }
    const int64_t need = (g->mask_top + words) * 4, limit = info->max_ssbo_bytes;
    if (need > limit)
        return -1;
    if (need > g->bytes[BUF_MASKS]) {
        int64_t cap = 2 * g->bytes[BUF_MASKS];
        cap = cap < need ? need : cap;
        cap = cap < (1 << 20) ? (1 << 20) : cap > limit ? limit : cap;
        GLuint grown;
        gl->GenBuffers(1, &grown);
        gl->BindBuffer(GL_COPY_WRITE_BUFFER, grown);
        gl->BufferData(GL_COPY_WRITE_BUFFER, cap, NULL, GL_DYNAMIC_DRAW);
        if (gl->GetError() != GL_NO_ERROR) {
            gl->DeleteBuffers(1, &grown);
            return -1;
        }
        if (g->mask_top > 0) {
            gl->BindBuffer(GL_COPY_READ_BUFFER, g->buf[BUF_MASKS]);
            gl->CopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, g->mask_top * 4);
        }
        gl->DeleteBuffers(1, &g->buf[BUF_MASKS]);
        g->buf[BUF_MASKS] = grown;
        g->bytes[BUF_MASKS] = cap;
    }
    const int64_t at = g->mask_top;
    g->mask_top += words;
    return at;
}

/* Make the GPU copy of a mask current: written whole the first time, edited rows and their tiles' counts after
 * that. The bit-packed rows go up as they are: little-endian 64-bit words read as pairs of 32-bit ones. */
static bool mask_sync(gpu_narrow *g, const gpu_gl *gl, const gpu_info *info, const pp_raster *cr)
{
    pp_raster *r = (pp_raster *)cr; /* the mirror fields are this backend's cache */
    const int64_t row_bytes = (int64_t)r->words_per_row * 8;
    if (r->gpu_word < 0) {
        r->gpu_word = mask_alloc(g, gl, info, mask_words(r));
        if (r->gpu_word < 0)
            return false;
        r->dirty_y0 = 0, r->dirty_y1 = r->height;
    }
    if (r->dirty_y0 < r->dirty_y1) {
        gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, g->buf[BUF_MASKS]);
        gl->BufferSubData(GL_SHADER_STORAGE_BUFFER, r->gpu_word * 4 + r->dirty_y0 * row_bytes,
                          (r->dirty_y1 - r->dirty_y0) * row_bytes, r->bits + (int64_t)r->dirty_y0 * r->words_per_row);
        const int64_t ty0 = r->dirty_y0 >> RASTER_TILE_SHIFT, ty1 = ((r->dirty_y1 - 1) >> RASTER_TILE_SHIFT) + 1;
        gl->BufferSubData(GL_SHADER_STORAGE_BUFFER, (r->gpu_word + row_words(r)) * 4 + ty0 * r->tiles_x,
                          (ty1 - ty0) * r->tiles_x, r->tile_count + ty0 * r->tiles_x);
        r->dirty_y0 = r->dirty_y1 = 0;
    }
    return true;
}

static pp_status grow_host(gpu_narrow *g, const char *fn, int64_t pairs)
{
    if (pairs <= g->pair_cap)
        return PP_OK;
    gpu_pair *p = pp_realloc(g->pairs, (size_t)pairs * sizeof *p);
    if (p)
        g->pairs = p;
    int32_t *ix = pp_realloc(g->index, (size_t)pairs * sizeof *ix);
    if (ix)
        g->index = ix;
    uint32_t *res = pp_realloc(g->results, ((size_t)pairs * RESULT_WORDS + 2) * sizeof *res);
    if (res)
        g->results = res;
    if (!p || !ix || !res)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %lld GPU pairs", fn, (long long)pairs);
    g->pair_cap = pairs;
    return PP_OK;
}

/* Size a buffer for `bytes` (contents are rewritten before use, so growing discards them). */
static void buffer_reserve(gpu_narrow *g, const gpu_gl *gl, int which, int64_t bytes)
{
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, g->buf[which]);
    if (bytes > g->bytes[which]) {
        int64_t cap = 2 * g->bytes[which];
        cap = cap < bytes ? bytes : cap;
        gl->BufferData(GL_SHADER_STORAGE_BUFFER, cap, NULL, GL_DYNAMIC_DRAW);
        g->bytes[which] = cap;
    }
}

static void buffer_write(gpu_narrow *g, const gpu_gl *gl, int which, const void *data, int64_t bytes)
{
    buffer_reserve(g, gl, which, bytes);
    gl->BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, bytes, data);
}

/* A pass over `groups` workgroups, as a 2D grid of rows of at most `row` when one row is not enough; or, with
 * groups < 0, the workgroups that BUF_LISTS holds at word `count`. */
static void dispatch(const gpu_gl *gl, int64_t row, gpu_program_id prog, int64_t count, int64_t groups, int32_t method)
{
    const GLuint p = gpu_program(prog);
    gl->UseProgram(p);
    gl->Uniform1ui(gl->GetUniformLocation(p, "u_count"), (GLuint)count);
    if (prog == GPU_PROG_NARROW_SUMS)
        gl->Uniform1i(gl->GetUniformLocation(p, "u_method"), method);
    if (groups < 0) {
        gl->DispatchComputeIndirect((GLintptr)(count * 4));
    } else {
        const int64_t gx = groups < row ? groups : row;
        gl->DispatchCompute((GLuint)gx, (GLuint)((groups + gx - 1) / gx), 1);
    }
    gl->MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

static inline int64_t word64(const uint32_t *w) { return (int64_t)((uint64_t)w[0] | (uint64_t)w[1] << 32); }

/* The tiles of a pair's grid. */
static int64_t grid_tiles(const np_pair *p) { return (int64_t)((p->nx + TILE - 1) / TILE) * ((p->ny + TILE - 1) / TILE); }

/* One batch: GPU pairs [from, to) of g->index, all five passes, one readback into out. */
static pp_status run_batch(gpu_narrow *g, const char *fn, const gpu_gl *gl, const np_settings *set,
                           const np_pair *pairs, int32_t from, int32_t to, np_core *out)
{
    const int32_t n = to - from;
    int64_t strip_words = 0, tiles = 0;
    for (int32_t k = 0; k < n; k++) {
        const np_pair *p = &pairs[g->index[from + k]];
        const int32_t ra[4] = {(int32_t)p->ra->gpu_word, p->ra->width, p->ra->height, 2 * p->ra->words_per_row};
        const int32_t rb[4] = {(int32_t)p->rb->gpu_word, p->rb->width, p->rb->height, 2 * p->rb->words_per_row};
        gpu_pair *gp = &g->pairs[k];
        memcpy(gp->ra, ra, sizeof ra);
        memcpy(gp->rb, rb, sizeof rb);
        gp->grid[0] = p->s, gp->grid[1] = p->off, gp->grid[2] = p->i0, gp->grid[3] = p->j0;
        gp->size[0] = p->nx, gp->size[1] = p->ny, gp->size[2] = p->fallback_nqx, gp->size[3] = p->fallback_nqy;
        gp->q[0] = (int32_t)p->qx0, gp->q[1] = (int32_t)p->qy0, gp->q[2] = (int32_t)p->dix, gp->q[3] = (int32_t)p->diy;
        gp->q2[0] = (int32_t)p->djx, gp->q2[1] = (int32_t)p->djy;
        gp->q2[2] = (int32_t)strip_words, gp->q2[3] = (int32_t)tiles;
        strip_words += NP_STRIP_FIELDS * np_pair_max_strips(p);
        tiles += grid_tiles(p);
    }
    const int64_t result_words = (int64_t)n * RESULT_WORDS + 2;
    memset(g->results, 0, (size_t)result_words * sizeof *g->results);
    const uint32_t lists[L_WORDS] = {[L_GRID_TILES] = (uint32_t)tiles, [L_PAIRS] = (uint32_t)n};
    buffer_write(g, gl, BUF_PAIRS, g->pairs, (int64_t)n * sizeof(gpu_pair));
    buffer_write(g, gl, BUF_RESULTS, g->results, result_words * 4);
    buffer_write(g, gl, BUF_LISTS, lists, sizeof lists);
    buffer_reserve(g, gl, BUF_TILES, tiles > 0 ? tiles * 2 * 4 : 8);
    buffer_reserve(g, gl, BUF_STRIPS, strip_words * 4);
    for (int b = 0; b < BUF_COUNT; b++)
        gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)b, g->buf[b]);
    gl->BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, g->buf[BUF_LISTS]);

    const int32_t method = set->normal_method == PP_NORMAL_KERNEL;
    const int64_t pair_groups = (n + PAIRS_PER_GROUP - 1) / PAIRS_PER_GROUP;
    if (tiles > 0) {
        dispatch(gl, g->row_groups, GPU_PROG_NARROW_TILES, tiles, (tiles + 63) / 64, method);
        dispatch(gl, g->row_groups, GPU_PROG_NARROW_ARGS, g->row_groups, 1, method);
        dispatch(gl, g->row_groups, GPU_PROG_NARROW_SUMS, L_SUMS_ARGS, -1, method);
    }
    dispatch(gl, g->row_groups, GPU_PROG_NARROW_NORMAL, n, pair_groups, method);
    if (tiles > 0)
        dispatch(gl, g->row_groups, GPU_PROG_NARROW_STRIPS, L_STRIPS_ARGS, -1, method);
    dispatch(gl, g->row_groups, GPU_PROG_NARROW_FINISH, n, pair_groups, method);

    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, g->buf[BUF_RESULTS]);
    const uint32_t *res = gl->MapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, result_words * 4, GL_MAP_READ_BIT);
    if (!res)
        return pp_fail(PP_ERR_UNSUPPORTED, "%s: reading the GPU results failed (GL error 0x%x)", fn,
                       (unsigned)gl->GetError());
    for (int32_t k = 0; k < n; k++) {
        const uint32_t *w = res + (int64_t)k * RESULT_WORDS;
        np_core *c = &out[g->index[from + k]];
        const int32_t *v = (const int32_t *)w; /* the R_* layout of glsl/common.glsl */
        *c = (np_core){
            .count = word64(w), .sx = word64(w + 2), .sy = word64(w + 4), .gx = word64(w + 6), .gy = word64(w + 8),
            .nqx = v[10], .nqy = v[11], .tmin = v[12], .nstrips = v[13], .first = v[14], .last = v[15],
            .first_min = v[16], .first_max = v[17], .last_min = v[18], .last_max = v[19],
            .cover_all = v[20], .cover_lo = v[21], .cover_hi = v[22],
        };
    }
    g->mixed += res[(int64_t)n * RESULT_WORDS], g->full += res[(int64_t)n * RESULT_WORDS + 1];
    gl->UnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    const GLenum err = gl->GetError();
    if (err != GL_NO_ERROR)
        return pp_fail(PP_ERR_UNSUPPORTED, "%s: the GPU narrowphase failed (GL error 0x%x)", fn, (unsigned)err);
    return PP_OK;
}

pp_status gpu_narrow_run(gpu_narrow *g, const char *fn, const np_settings *set, const np_pair *pairs, int32_t n,
                         np_scratch *scratch, np_core *out)
{
    const gpu_gl *gl;
    const gpu_info *info;
    pp_status st = grow_host(g, fn, n);
    if (st || (st = gpu_acquire(fn, &gl, &info)))
        return st;
    int32_t m = 0;
    for (int32_t i = 0; i < n; i++)
        if (pairs[i].fits_int32 && mask_sync(g, gl, info, pairs[i].ra) && mask_sync(g, gl, info, pairs[i].rb))
            g->index[m++] = i;
    /* Batches as large as the storage-block limit allows; one batch in any ordinary step. */
    const int64_t limit = info->max_ssbo_bytes;
    for (int32_t from = 0, to; !st && from < m; from = to) {
        int64_t tiles = 0, strips = 0;
        for (to = from; to < m; to++) {
            const np_pair *p = &pairs[g->index[to]];
            tiles += grid_tiles(p);
            strips += NP_STRIP_FIELDS * np_pair_max_strips(p);
            const int64_t results = ((int64_t)(to - from + 1) * RESULT_WORDS + 2) * 4;
            if (to > from && (tiles * 8 > limit || strips * 4 > limit || results > limit))
                break;
        }
        st = run_batch(g, fn, gl, set, pairs, from, to, out);
    }
    gpu_release();
    /* The rest on the CPU: pairs beyond 32-bit sample points, or masks the mirror has no room for. */
    for (int32_t i = 0, j = 0; !st && i < n; i++) {
        if (j < m && g->index[j] == i)
            j++;
        else
            st = narrow_cpu_core(set, &pairs[i], scratch, &out[i]);
    }
    return st;
}
