/* The GPU backend of the narrowphase core: a world's masks mirrored in one GPU buffer, and all
 * of a step's pairs run in one batch of five compute passes with one readback. */
#ifndef PP_NARROW_GPU_H
#define PP_NARROW_GPU_H

#include "narrowphase.h"

typedef struct gpu_narrow gpu_narrow;

/* A world's GPU state; brings the process's context up on first use. PP_ERR_UNSUPPORTED (with
 * the EGL/GL reason in pp_last_error()) where no GLES 3.1 compute context can be made. */
pp_status gpu_narrow_create(const char *fn, gpu_narrow **out);
void gpu_narrow_destroy(gpu_narrow *g);

/* Whether the process's context is, or would be, a CPU rasteriser, told without making it where EGL lists only
 * Mesa's software device (gpu_probe_software): AUTO asks before it pays for a context it would never use. */
pp_status gpu_narrow_probe_software(const char *fn, bool *software);

/* A raster is going away: give its words in the mirror back (no GL call). */
void gpu_narrow_forget(gpu_narrow *g, pp_raster *r);

/* The integer cores of n pairs: on the GPU where the pair fits its 32-bit arithmetic and its
 * masks fit the mirror, on the CPU otherwise; the outcome is the same either way. */
pp_status gpu_narrow_run(gpu_narrow *g, const char *fn, const np_settings *set, const np_pair *pairs, int32_t n,
                         np_scratch *scratch, np_core *out);

/* Dispatch rows of at most `groups` workgroups (the context's limit until then), so that the tests run small batches
 * as 2D grids. */
void gpu_narrow_limit_rows(gpu_narrow *g, int32_t groups);

/* The mixed and the full 16×16 tiles the GPU has sampled since the world was made (the tiles pass's sort). */
void gpu_narrow_tiles_sampled(const gpu_narrow *g, int64_t *mixed, int64_t *full);

#endif
