/* The stability scenes of issue 22 as engine-neutral data (PhysPix world units: px, y down, rad), the
 * measurement that says whether a stack stands, and the PhysPix side of the benchmark. Tests build the same
 * scenes through this header; it needs only physpix.h (the peers live behind peers.h): link scenes.c,
 * scenes_physpix.c and measure.c.
 *
 *   stab_scene s;  stab_scene_build(stab_scene_find("tower20_16"), &s);
 *   stab_engine e = stab_engine_physpix(PP_PRESET_BALANCED);
 *   stab_result r; stab_run(&e, &s, &(stab_options){.run_s = 10}, &r);   // r.verdict == STAB_STANDS
 *   stab_scene_free(&s);
 */
#ifndef PP_BENCH_STABILITY_H
#define PP_BENCH_STABILITY_H

#include "physpix.h"

#ifdef __cplusplus
extern "C" {
#endif

#define STAB_PX_PER_M 100.0   ///< px per metre for the peers
#define STAB_GRAVITY 980.0    ///< px/s², down (+y)
#define STAB_DT (1.0 / 60.0)  ///< s, one pp_world_step per frame
#define STAB_MAX_VERTS 8      ///< vertices of a polygon body

/// What a scene measures.
typedef enum stab_kind {
    STAB_STACK = 0,  ///< stands for the run after a settle; drift, fall time (crush when `tracked` >= 0)
    STAB_ROLL = 1,   ///< a disc rolls down a slope: acceleration along it
    STAB_BOUNCE = 2, ///< a ball dropped from 200 px: first rebound apex
    STAB_RAMP = 3,   ///< a box on a ramp: slide distance (sticks) or acceleration (slides)
    STAB_SHOT = 4    ///< a fast box shot at a wall: tunnelled or where it stopped
} stab_kind;

/// The shape of a body, about its origin.
typedef enum stab_shape {
    STAB_BOX = 0,  ///< w × h, centred on the origin
    STAB_DISC = 1, ///< radius, centred on the origin
    STAB_POLY = 2  ///< convex polygon, vertices about the origin (its centroid)
} stab_shape;

/// One body: its shape, pose, material and start velocity, in px, px/s and rad (y down).
typedef struct stab_body {
    stab_shape shape;
    double x, y, angle;                   ///< origin, px, and rotation, rad (+x turns toward +y)
    double w, h;                          ///< STAB_BOX size, px
    double radius;                        ///< STAB_DISC radius, px
    int nverts;                           ///< STAB_POLY vertex count, 3..STAB_MAX_VERTS
    double vx[STAB_MAX_VERTS], vy[STAB_MAX_VERTS]; ///< STAB_POLY vertices about the origin, px
    double density;                       ///< mass per px² (PhysPix: per solid pixel)
    double friction;                      ///< Coulomb coefficient; a pair's is sqrt(fa·fb)
    double restitution;                   ///< a pair's is max(ea, eb)
    double vel_x, vel_y;                  ///< start velocity, px/s
    int is_static;                        ///< nonzero: never moves
    int bullet;                           ///< nonzero: Box2D's bullet flag (PhysPix's `continuous` already sweeps it)
} stab_body;

/// A named scene and what to measure on it.
typedef struct stab_scene {
    char name[32];
    stab_kind kind;
    stab_body *bodies;  ///< owned; stab_scene_free releases it
    int count;
    int tracked;        ///< the body measured (heavy box, disc, ball, box), or -1
    double slope;       ///< ROLL, RAMP: slope angle, rad (down the slope is (cos, sin))
    double mu;          ///< RAMP: the pair's friction
    double drop;        ///< BOUNCE: drop height of the ball's bottom above the ground, px
    int bounces;        ///< BOUNCE: rebounds measured (0: the first); value is the apex farthest from e²·drop
    double wall_x0;     ///< SHOT: x of the wall's near face, px
    double wall_x1;     ///< SHOT: x of the wall's far face, px
    double ground_top;  ///< y of the ground's top, px
    double seconds;     ///< run time of a non-stack scene, s; a stack with max_move: its longest watch
    double max_move;    ///< stack: > 0, it stands while no body moves this far from where it was built, px
                        ///< (settle and watch alike); 0: a quarter of its size from the settled pose
} stab_scene;

/// Number of scenes in the list.
int stab_scene_count(void);
/// The i-th scene's name, or NULL.
const char *stab_scene_name(int i);
/// Index of the scene named exactly `name`, or -1.
int stab_scene_find(const char *name);
/// Build the i-th scene into out; 0, or -1 for a bad index or no memory.
int stab_scene_build(int i, stab_scene *out);
/// Release a scene's bodies.
void stab_scene_free(stab_scene *s);
/// The size a body may move a quarter of and still stand: its longest side (disc: diameter), px.
double stab_body_size(const stab_body *b);

/// A body's pose: its origin, px, and angle, rad, in PhysPix's frame.
typedef struct stab_pose {
    double x, y, angle;
} stab_pose;

/// One engine as the measurement drives it; `world` is the engine's own state.
typedef struct stab_engine stab_engine;
struct stab_engine {
    char name[32];                                          ///< table name, e.g. "PhysPix BALANCED"
    void *(*create)(const stab_engine *e, const stab_scene *s); ///< a world of the scene, or NULL (says why)
    int (*step)(void *world);                               ///< one frame of STAB_DT; 0, or -1 (says why)
    void (*pose)(void *world, int body, stab_pose *out);    ///< a body's pose now
    void (*mass)(void *world, int body, double *m, double *inertia); ///< mass and inertia about the centre
    void (*destroy)(void *world);
    pp_world_def world_def;                                 ///< PhysPix rows: the world's settings
    int iterations;                                         ///< peers: solver iterations
};

/// A PhysPix engine row: the preset's settings with sleep off.
stab_engine stab_engine_physpix(pp_preset preset);
/// A PhysPix engine row with these world settings, named `name`.
stab_engine stab_engine_physpix_def(const char *name, const pp_world_def *def);
/// Create the scene's bodies in w; bodies receives count handles. 0, or -1 (prints why).
int stab_physpix_add_bodies(pp_world w, const stab_scene *s, pp_body *bodies);
/// The mask of a body as PhysPix gets it: 1 where a pixel centre lies inside the shape. Returns a malloc'd
/// w × h plane and writes its size and the bitmap point of the body's origin (the pivot); NULL: no memory.
uint8_t *stab_body_mask(const stab_body *b, int32_t *w, int32_t *h, pp_vec2 *pivot);

/// How long to watch a stack.
typedef struct stab_options {
    double settle_s;  ///< untimed settle before the reference pose, s (0: 1 s)
    double run_s;     ///< stack watch time after the settle, s (0: 60 s)
} stab_options;

/// How a scene ended.
typedef enum stab_verdict {
    STAB_STANDS = 0,    ///< stack: no body moved over a quarter of its size
    STAB_FALLS = 1,     ///< stack: one did (fall_s says when)
    STAB_NAN = 2,       ///< a pose became NaN or infinite
    STAB_ERROR = 3,     ///< the engine failed (it said why)
    STAB_ROLLS = 4,     ///< roll: measured
    STAB_BOUNCES = 5,   ///< bounce: rebounded
    STAB_NO_BOUNCE = 6, ///< bounce: rebounded less than 1 px
    STAB_STICKS = 7,    ///< ramp: slid under 1 px
    STAB_SLIDES = 8,    ///< ramp: slid
    STAB_STOPPED = 9,   ///< shot: stopped in front of the wall
    STAB_STUCK = 10,    ///< shot: ended inside the wall
    STAB_TUNNELLED = 11, ///< shot: ended beyond the wall
    STAB_COLLAPSES = 12  ///< stack: came apart while settling (fall_s says when, from the start)
} stab_verdict;

/// What one scene on one engine measured. Unused figures are NaN.
typedef struct stab_result {
    stab_verdict verdict;
    double drift;        ///< stack: largest move of any body from the settled pose, px
    double fall_s;       ///< stack: time after the settle when a body first moved over a quarter of its size, s;
                         ///< COLLAPSES: time from the start when one first moved so far sideways or turned, s
    double crush;        ///< stack with a tracked box: its sink below the settled pose at the end, px
    double settle_sink;  ///< stack with a tracked box: its sink during the settle, px
    double value;        ///< roll, ramp 35°: acceleration, px/s²; ramp 20°: slide, px; bounce: apex, px (of
                         ///< several bounces, the one farthest from ref);
                         ///< shot: the box's leading face past the wall's near face, px
    double ref;          ///< what value should be: 2/3·g·sinθ, g(sinθ − μcosθ), e²·drop, 0
    double err_pct;      ///< 100·(value − ref)/ref
    double ref2;         ///< roll: the body's own prediction g·sinθ/(1 + I/(m r²)), px/s²
    double err2_pct;     ///< 100·(value − ref2)/ref2
    double ms_median;    ///< median ms per frame after the settle
    int frames;          ///< frames run after the settle
} stab_result;

/// Run a scene on an engine and measure it; 0, or -1 when the engine could not build it.
int stab_run(const stab_engine *e, const stab_scene *s, const stab_options *o, stab_result *out);
/// The verdict's table word.
const char *stab_verdict_name(stab_verdict v);
/// Largest distance of any dynamic body's origin from its reference pose, px; *worst gets the largest
/// distance as a fraction of that body's size (over 0.25: it fell).
double stab_max_displacement(const stab_scene *s, const stab_pose *ref, const stab_pose *now, double *worst);

#ifdef __cplusplus
}
#endif

#endif
