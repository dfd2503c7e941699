/* The collision-stage contract shared by the CPU and GPU backends: a pair of rasters at their
 * poses in, up to two contacts out, decided in integers so both backends agree bit for bit. */
#ifndef PP_NARROWPHASE_H
#define PP_NARROWPHASE_H

#include "math2d.h"
#include "raster.h"

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

/* Up to two contact points; normal points from a to b (handles are the caller's to fill). */
typedef struct np_result {
    int32_t count;
    pp_contact contacts[2];
    int64_t samples;    /* raster samples examined */
} np_result;

/* Reusable buffers, grown as needed, owned by the world. */
typedef struct np_scratch {
    uint8_t *cells;     /* two planes of sampled A and B */
    int64_t cells_cap;
    int32_t *strips;    /* min/max projection per strip */
    int64_t strips_cap;
} np_scratch;

/* Fixed-point precisions: sampling positions in 16.16, the normal in Q14. */
#define NP_FIX_BITS 16
#define NP_NORMAL_ONE 16384

pp_status narrow_cpu_collide(const np_settings *set, const np_body *a, const np_body *b, np_scratch *scratch,
                             np_result *out);
void np_scratch_free(np_scratch *s);

#endif
