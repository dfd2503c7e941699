/* The scaling benchmark's vocabulary: one row of any curve (printed, written as CSV, plotted),
 * what every curve is handed, and the five curves. */
#ifndef PP_BENCH_SCALE_H
#define PP_BENCH_SCALE_H

#include "bench.h"

#include <stdio.h>

/// One measured point of one engine on one curve; a CSV row.
typedef struct scale_row {
    const char *curve;   ///< "bodies", "terrain", "body_size", "overlap" or "edits"
    const char *variant; ///< "awake"/"asleep" (bodies), "aligned"/"rotated" (overlap), else "-"
    double x;            ///< the curve's x: bodies, terrain pixels, body side px, overlap px, edits per step
    char label[24];      ///< x as printed, e.g. "8192x4096"
    const char *engine;  ///< "raster" or "analytic"
    int timed;           ///< timed steps (overlap: timed batches of calls)
    double ms;           ///< median ms per step (overlap: per collide call), edits included
    double narrow_ms;    ///< mean narrowphase ms per step (analytic: dSpaceCollide, pair search included)
    double contacts;     ///< mean contact points of the last substep (overlap: of one call)
    double pairs;        ///< mean pairs tested in the last substep
    double us_contact;   ///< narrowphase µs per contact point and substep
    double us_pair;      ///< narrowphase µs per pair and substep
    int awake;           ///< bodies awake after the last timed step
    double edit_ms;      ///< median ms of one step's edits (edits curve; else 0)
    double ratio;        ///< ms raster / ms analytic on this point (analytic rows: 1; no analytic: 0)
} scale_row;

/// What every curve is handed.
typedef struct scale_ctx {
    bench_settings set; ///< the library's defaults; curves copy it to change sleep
    int quick;          ///< nonzero: smoke run, few points and steps
    FILE *csv;          ///< NULL: no CSV
} scale_ctx;

/// Write one row to the context's CSV, if any.
void scale_emit(const scale_ctx *ctx, const scale_row *row);

/// Crates resting on a terrain, 100 to 10,000: ms/step awake and asleep; 0 or -1.
int scale_curve_bodies(const scale_ctx *ctx);
/// A fixed set of crates on terrains of 256² to 8192×4096 px: narrowphase per contact and pair; 0 or -1.
int scale_curve_terrain(const scale_ctx *ctx);
/// A few crates of side 8 to 512 px on the ground: ms/step and narrowphase per contact; 0 or -1.
int scale_curve_body_size(const scale_ctx *ctx);
/// Two 256 px boxes overlapping by 1 to 128 px: one pp_world_collide against one dCollide; 0 or -1.
int scale_curve_overlap(const scale_ctx *ctx);
/// 0 to 100 circle erases per step in a 4096×2048 terrain under resting crates: ms/step; 0 or -1.
int scale_curve_edits(const scale_ctx *ctx);

#endif
