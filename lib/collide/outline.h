/* A raster's outline: the boundary between its solid and empty pixels, on the pixel squares' edges, merged into
 * maximal straight runs. Built from the bits a word at a time and kept with the raster until its mask changes
 * (pp_raster.version), so that drawing a world every frame rebuilds only what an edit touched. */
#ifndef PP_OUTLINE_H
#define PP_OUTLINE_H

#include "raster.h"

/* One run from (ax, ay) to (bx, by), bitmap px on the pixel grid; the solid side lies to its right as drawn with
 * y down (a box's runs go round it clockwise on screen). */
typedef struct outline_run {
    int32_t ax, ay, bx, by;
} outline_run;

typedef struct raster_outline {
    outline_run *runs;
    int32_t count, capacity;
    uint64_t version; /* the raster's version it was built at */
} raster_outline;

/* The raster's outline as its mask is now: the cached one, or one built here. PP_ERR_OUT_OF_MEMORY names `fn`
 * (the cache is then left as it was). */
pp_status raster_outline_get(const char *fn, pp_raster *r, const raster_outline **out);

/* Free the cached outline (raster_free does). */
void raster_outline_free(pp_raster *r);

#endif
