/* The step-cost benchmark's own scenes (issue 23): crates raining into a walled pit, as a stab_scene that every
 * stability engine runs, and the destruction scene (crates on a bitmap terrain that craters eat) with its
 * Box2D 2.4 peer, which remeshes the terrain into chain loops (peer_remesh.cpp). Units as stability.h: px,
 * y down, rad. */
#ifndef PP_BENCH_COST_H
#define PP_BENCH_COST_H

#include "../stability/stability.h"

#ifdef __cplusplus
extern "C" {
#endif

#define COST_TERRAIN_W 2048 ///< destruction terrain bitmap, px; its pixel (i, j) is the world's
#define COST_TERRAIN_H 1024
#define COST_CRATES 50      ///< destruction crates, 16..32 px
#define COST_CRATER_R 32.0  ///< crater radius, px
#define COST_EDIT_EVERY 10  ///< steps between craters

/// `crates` boxes of 32 px in a 20-column grid above a walled pit (ground, then two walls, then the crates),
/// friction 0.6, sleep left to the engine; 0, or -1 (no memory).
int cost_rain_build(int crates, stab_scene *out);

/// The destruction scene: a terrain bitmap whose lower half is solid under a gently wavy surface, and the
/// crates resting on it.
typedef struct cost_destruction {
    uint8_t *terrain;   ///< COST_TERRAIN_W × COST_TERRAIN_H bytes, 1 solid, rows top to bottom
    int *top;           ///< per column, the first solid row at the start, px
    stab_scene crates;  ///< the crates only, dynamic boxes
} cost_destruction;

/// The settings PhysPix runs the rain and the destruction scene with outside bench_cost (bench_instr, bench_state):
/// BALANCED, the CPU backend on one thread, STAB_GRAVITY, sleep on or off.
pp_world_def cost_world_def(int sleep);

/// Build the destruction scene; 0, or -1 (no memory).
int cost_destruction_build(cost_destruction *out);
/// Release its memory.
void cost_destruction_free(cost_destruction *d);
/// Centre of the k-th crater, world px: under the start position of a crate (cycling through them), each pass
/// deeper; the same for every engine, so all erase the same pixels.
void cost_crater(const cost_destruction *d, int k, double *x, double *y);

/// The Box2D 2.4 world of the destruction scene: sleep on, 8 velocity and 3 position iterations.
typedef struct cost_remesh cost_remesh;
/// Build it (the terrain copied and meshed); NULL when out of memory.
cost_remesh *cost_remesh_create(const cost_destruction *d);
/// Erase the terrain pixels whose centres lie within radius (px) of (x, y) (world px), remesh the chunks they
/// lie in and wake the crates whose box overlaps the crater's.
void cost_remesh_erase(cost_remesh *r, double x, double y, double radius);
/// One step of STAB_DT.
void cost_remesh_step(cost_remesh *r);
/// Crates awake now.
int cost_remesh_awake(const cost_remesh *r);
/// The terrain's chain loops and their vertices now.
void cost_remesh_counts(const cost_remesh *r, int *loops, int *vertices);
void cost_remesh_destroy(cost_remesh *r);

#ifdef __cplusplus
}
#endif

#endif
