/* PhysPix — 2D rigid bodies whose shapes are bitmaps used as they are.
 * The public C ABI: value handles, status codes, def structs with a struct_size.
 * Units everywhere: pixels, seconds, radians; world y points down.
 *
 * Conventions. Mass is in mass units (a solid pixel of weight 255 weighs `density`); gravity defaults
 * to (0, 980) px/s². A body's pose maps bitmap coordinates (origin at the bitmap's top-left corner,
 * pixel (i, j) covering [i, i+1) × [j, j+1)) to the world: world = position + R(angle)·(local − pivot),
 * the pivot defaulting to the bitmap centre; the pose does not jump when an edit moves the centre of
 * mass. Velocities are those of the centre of mass. Handles (pp_world, pp_body, pp_joint) are values carrying
 * their kind, a slot and a generation, and a body's or joint's names its world too: a destroyed or stale one,
 * one of another world, or one of another kind (a joint handle passed as a body) is answered with
 * PP_ERR_INVALID_HANDLE, never a crash.
 * Every call that can fail returns a pp_status and writes results through out-pointers; on failure
 * pp_last_error() says why, naming the argument, and the outputs are untouched. Def structs come from
 * their default function, which sets struct_size (a binding with a wrong layout gets PP_ERR_ABI). The
 * caller owns every output buffer: a call writes up to `capacity` items and reports the total in `count`.
 * Results (contacts, events, stats) are read after pp_world_step; there are no callbacks during a step.
 *
 * Threads. A world is used from one thread at a time; different worlds may run on different threads.
 * Inside a step the narrowphase may share its pairs over pp_world_def.worker_threads threads (on the CPU
 * backend each pair's set-up, core and contacts; on the GPU backend the host's share of each pair): they
 * start with the first batch of 32,768 cells or 128 pairs or more and live until the world is destroyed,
 * so a small scene never has any, and each pair writes only its own result, so contacts are the same bit
 * for bit on any number of threads. The ODE step is serialised across worlds by one lock (the price of a
 * deterministic QuickStep with ODE's process-wide random generator). GPU batches from different worlds
 * take turns on the process's one GLES context. Measured figures: tests/bench/README.md. */
#ifndef PHYSPIX_H
#define PHYSPIX_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(PHYSPIX_BUILD)
#define PP_API __attribute__((visibility("default")))
#else
#define PP_API
#endif

/* ---- Base: version, limits, statuses, vectors, handles, errors, log hook, allocator ---- */

/// Library major version (the soname carries it).
#define PHYSPIX_VERSION_MAJOR 0
/// Library minor version.
#define PHYSPIX_VERSION_MINOR 3
/// Library patch version.
#define PHYSPIX_VERSION_PATCH 0

/* Limits. A request over one gets PP_ERR_LIMIT before anything is allocated; PNG and file sizes are read
 * from the header or the file's size, so a 40,000 × 40,000 PNG is refused before its pixels are. */

/// Largest bitmap side accepted by pp_body_create, in pixels.
#define PP_MAX_BITMAP_SIDE 16384
/// Largest bitmap area (width × height) accepted by pp_body_create, in pixels.
#define PP_MAX_BITMAP_AREA (8192 * 8192)
/// Largest number of live bodies in one world.
#define PP_MAX_BODIES (1 << 20)
/// Largest number of live worlds in one process.
#define PP_MAX_WORLDS 4096
/// Most contact points the narrowphase reports for one pair of bodies in a substep.
#define PP_MAX_CONTACTS_PER_PAIR 2
/// Largest scene file (pp_world_load_scene) or snapshot world.json accepted, in bytes.
#define PP_MAX_SCENE_BYTES (64 * 1024 * 1024)
/// Contact pairs a crowded dynamic body keeps in a substep. A body touching more than this many bodies whose
/// overlaps with it add up to over twice its solid pixels (bodies spawned into one spot, never a resting pile)
/// gives the solver only its this-many deepest pairs with other crowded bodies (ties: the partner nearer in
/// slot, then the lower), and collides only its twice-this-many largest box overlaps with them, so a step
/// costs a bounded multiple of a settled pile's. Until the pile spreads, pairs past the first bound get no
/// contact, and pairs past the second are not collided (no contact events).
#define PP_CROWDED_CONTACT_PAIRS 8

/* Motion limits, as Box2D's maximum speed: far above any game's needs (at the default 100 px/m, 10 km/s and
 * 100,000 g), low enough that no float overflows in a step. A value over one is refused where it comes in:
 * gravity (pp_world_def), max_correction_speed, a body def's velocities, pp_body_set_velocity and the velocity
 * pp_body_apply_impulse would give, each with PP_ERR_INVALID_ARGUMENT naming the field. What the solver makes
 * beyond them (contacts, a split piece's share of a spin) is clamped by the step, after each substep, keeping
 * the direction. A step that would still leave a pose or velocity non-finite or past ±FLT_MAX returns
 * PP_ERR_LIMIT and leaves the world as it was before the step. */

/// Largest speed of a body's centre of mass, px/s (refused on input, clamped by the step).
#define PP_MAX_SPEED 1.0e6f
/// Largest angular speed of a body, rad/s (refused on input, clamped by the step).
#define PP_MAX_ANGULAR_SPEED 1.0e5f
/// Largest magnitude of a world's gravity, px/s².
#define PP_MAX_ACCELERATION 1.0e8f
/// Largest magnitude of a body's gravity scale (pp_body_set_gravity_scale): 1000 g is still a fall a step can take.
#define PP_MAX_GRAVITY_SCALE 1000.0f

/// Result of every call that can fail; PP_OK is 0.
typedef enum pp_status {
    PP_OK = 0,                   ///< success
    PP_ERR_INVALID_ARGUMENT = 1, ///< NULL, NaN, out-of-range or inconsistent argument
    PP_ERR_INVALID_HANDLE = 2,   ///< a null, destroyed, stale or wrong-kind world, body or joint handle
    PP_ERR_OUT_OF_MEMORY = 3,    ///< an allocation failed; nothing was changed
    PP_ERR_IO = 4,               ///< a file could not be read or written
    PP_ERR_FORMAT = 5,           ///< a file's contents are malformed
    PP_ERR_UNSUPPORTED = 6,      ///< the feature is not available here (e.g. no GPU)
    PP_ERR_LIMIT = 7,            ///< a size over the documented PP_MAX_* limits, or a step past what a float holds
    PP_ERR_ABI = 8,              ///< a def struct whose struct_size does not match this library
    PP_STATUS_FORCE_U32 = 0x7fffffff
} pp_status;

/// A 2D vector in pixels (or pixels per second, per the call).
typedef struct pp_vec2 {
    float x; ///< x component, pixels
    float y; ///< y component, pixels (down is positive)
} pp_vec2;

/// A world handle; id 0 is never valid.
typedef struct pp_world {
    uint64_t id; ///< kind, slot index and generation; opaque
} pp_world;

/// A body handle; id 0 is never valid. It names its world and its kind: used with another world, or where a
/// joint is expected, it is PP_ERR_INVALID_HANDLE.
typedef struct pp_body {
    uint64_t id; ///< kind, slot index, generation and its world's slot and generation; opaque
} pp_body;

/// A joint handle; id 0 is never valid. It names its world and its kind, as a body's does.
typedef struct pp_joint {
    uint64_t id; ///< kind, slot index, generation and its world's slot and generation; opaque
} pp_joint;

/// Log hook: level 0 debug, 1 info, 2 warning, 3 error; msg is valid during the call only.
typedef void (*pp_log_fn)(int level, const char *msg, void *user);

/* Running out. pp_set_allocator routes every allocation PhysPix makes, libpng's included, through the
 * host's functions (worker threads call them too). ODE and cJSON keep their own: ODE cannot report a failed
 * allocation except in its step (PP_ERR_OUT_OF_MEMORY), and cJSON's hooks are process-wide, so setting them
 * would change the host's own cJSON. Out of memory changes nothing: every call returns PP_ERR_OUT_OF_MEMORY
 * and leaves the world as it was, and succeeds when retried. A step saves what it changes before changing
 * it (144 bytes a body slot) and puts it back if any substep runs short; an edit makes a split's pieces
 * before it commits anything. Timed edits due at a step apply first, each whole or not at all; one applied
 * stays applied if the rest of the step fails, and one that failed stays queued. Worker threads never
 * allocate: the calling thread grows their scratch first, so a failure is reported where it happened.
 * Files are never half-written: a snapshot or image is written beside its target, flushed and renamed over
 * it only when whole; a save that fails part way (disk full, a file-size limit) returns PP_ERR_IO and leaves
 * the previous file as it was. A load that fails creates no world and leaves *out untouched. */

/// The memory functions behind every allocation the library makes; sizes in bytes, never 0.
typedef struct pp_allocator {
    void *(*alloc)(uint64_t size, void *user);              ///< like malloc: NULL when out of memory
    void *(*realloc)(void *ptr, uint64_t size, void *user); ///< like realloc: ptr from alloc or realloc
    void (*free)(void *ptr, void *user);                    ///< like free; ptr is never NULL
    void *user;                                             ///< passed back to every call
} pp_allocator;

/// Library version as MAJOR·10000 + MINOR·100 + PATCH.
PP_API uint32_t pp_version(void);
/// Static name of a status, e.g. "PP_ERR_LIMIT"; never NULL.
PP_API const char *pp_status_name(pp_status status);
/// Message of the last failure on the calling thread ("" if none); never NULL.
PP_API const char *pp_last_error(void);
/// Install a process-wide log hook (NULL removes it); called outside steps only.
PP_API void pp_set_log_hook(pp_log_fn fn, void *user);
/// Route every allocation the library makes (not ODE's or cJSON's) through a (NULL: back to malloc);
/// only while no world exists, else PP_ERR_INVALID_ARGUMENT. The functions may be called from worker threads.
PP_API pp_status pp_set_allocator(const pp_allocator *a);

/* ---- World: settings, presets, create/destroy/step, stats, contacts, events, camera ---- */

/// Which collision backend runs the narrowphase.
typedef enum pp_backend {
    PP_BACKEND_AUTO = 0, ///< the GPU where it pays off, else the CPU
    PP_BACKEND_CPU = 1,  ///< the CPU reference backend
    PP_BACKEND_GPU = 2,  ///< GLES 3.1 compute; PP_ERR_UNSUPPORTED where unavailable
    PP_BACKEND_FORCE_U32 = 0x7fffffff
} pp_backend;

/// How a contact normal is estimated from the intersection raster.
typedef enum pp_normal_method {
    PP_NORMAL_AREA_GRADIENT = 0, ///< direction in which a unit shift of the second body shrinks the overlap fastest
    PP_NORMAL_KERNEL = 1,        ///< the poster's 3×3 critical-pixel kernel, summed
    PP_NORMAL_FORCE_U32 = 0x7fffffff
} pp_normal_method;

/// How many contact points a colliding pair produces.
typedef enum pp_contact_mode {
    PP_CONTACT_MANIFOLD = 0, ///< two points: the extremes of the intersection along the tangent
    PP_CONTACT_CENTROID = 1, ///< one point: the intersection's centroid (the poster's)
    PP_CONTACT_FORCE_U32 = 0x7fffffff
} pp_contact_mode;

/* Presets are named points on the measured speed/accuracy trade (figures: tests/bench/README.md, "Presets").
 * They differ only in solver work, the knob that decides whether stacks stand; all keep AREA_GRADIENT
 * normals, MANIFOLD contacts (two points a pair) and raster stride 1. BALANCED meets the accuracy targets
 * (normal error median ≤ 0.5°, 95th percentile ≤ 2°; depth error median ≤ 0.5 px) and holds 20-box
 * towers, 20-row pyramids, mass ratios of 1:1000 and an arch for 60 s; FAST holds a 10-row
 * pyramid and a 10-box tower, lets taller stacks fall and is for debris and loose piles. A
 * scene's "preset" key and Python's World.from_preset start from them; the other settings override. */

/// A named point on the measured speed/accuracy trade; see pp_world_def_preset.
typedef enum pp_preset {
    PP_PRESET_FAST = 1,     ///< 1 substep × 10 iterations: cheapest, same contact errors; 10-high stacks stand, taller fall
    PP_PRESET_BALANCED = 2, ///< the default, 4 substeps × 20 iterations: stacks stand, contact errors on target
    PP_PRESET_ACCURATE = 3, ///< 4 substeps × 80 iterations: the stiffest stacks measured, for more solver time
    PP_PRESET_FORCE_U32 = 0x7fffffff
} pp_preset;

/* How a world steps. Each pp_world_step(dt) runs `substeps` passes of collision and solver. Collision:
 * a dynamic AABB tree of the solid pixels' world boxes, queried by the awake bodies only (static–static,
 * filtered and sleeping–sleeping pairs are skipped; a sleeping body costs a step nothing), then the
 * narrowphase samples both masks on one grid and finds each pair's normal, depth and contact points from the
 * intersection raster, in integers, so the CPU and GPU backends agree bit for bit and runs are
 * deterministic; a pair meeting through at most 3 pixels (a corner on a face) takes the face's normal where
 * either body's bitmap axis separates their pixels near the contact better. The narrowphase runs at a step's
 * first substep; a resting pair (moving under 0.25 px against each other in a step) keeps its contacts
 * through the later substeps, each point moved with its bodies and its depth with their separation, and
 * every other pair is collided again at each substep. Solver: ODE 0.16 (double precision) in the plane, ODE seeing metres
 * (pixels_per_meter); contact joints with Coulomb friction μ = √(μa·μb) and restitution max(ea, eb) above
 * bounce_threshold; contact_cfm is relative to the pair's reduced mass, so it does not depend on body size.
 * Each contact is two rows (the normal and one in-plane friction direction). An island of two or more
 * dynamic bodies with at most exact_island_rows rows is solved by ODE's exact dWorldStep (towers, heavy on
 * light), larger ones by QuickStep, and so is one whose bodies' masses differ over 1e6 times (the exact
 * factorisation loses its pivots there). ODE's messages reach the log hook, never stderr. "ODE message 3: LCP
 * internal error" (level 1) means the exact solver gave up on an island's rows, as a stack woken all at once
 * can make it; that substep solves the island by QuickStep instead and the step returns PP_OK: nothing to do,
 * unless it repeats every step, when a smaller exact_island_rows avoids it. A pile would creep on either (QuickStep's solve stops short, and the
 * exact solve gives at contact_cfm under a steady sideways load), so in every island of two or more dynamic
 * bodies each touching pair keeps a friction anchor, and friction takes back what a contact slipped since
 * (within Coulomb's bound; a slip over 2 px or a turn over 0.05 rad re-anchors).
 * QuickStep's random order is seeded from the world's step count before each step: the same scene gives
 * the same result in any run. Sleeping: bodies slower than sleep_linear_speed and sleep_angular_speed for
 * sleep_time sleep, and bodies in contact sleep together or not at all.
 * Continuous collision: contacts are found at the start of each substep, so a body moving farther than
 * about half of (its length + a wall's thickness) in one substep could pass through unseen. With
 * `continuous`, a dynamic body that moved over half its thinnest side is swept along its motion against
 * static and kinematic bodies (`bullet` bodies against dynamic ones too) and stopped, velocity kept, at
 * the first pose where it overlaps (to half a pixel of travel); the rest of that substep is lost.
 * pp_step_stats.swept_stops counts the stops. Only fast bodies pay. How it all works, and what it
 * costs: tests/bench/README.md. */

/// Largest pp_world_def.exact_island_rows: the exact solver's cost grows with the cube of an island's rows.
#define PP_MAX_EXACT_ISLAND_ROWS 1024

/// Settings of a world; fill from pp_world_def_default(). Zero in substeps, solver_iterations or raster_stride means its default.
typedef struct pp_world_def {
    uint32_t struct_size;           ///< sizeof(pp_world_def), set by pp_world_def_default
    pp_vec2 gravity;                ///< acceleration, px/s² (default 0, 980)
    int32_t substeps;               ///< solver steps per pp_world_step, 1..64 (default 4)
    int32_t solver_iterations;      ///< QuickStep iterations a substep, 1..1000 (default 20)
    uint32_t exact_solver;          ///< nonzero: ODE's exact dWorldStep instead of QuickStep
    pp_backend backend;             ///< collision backend (default AUTO)
    pp_normal_method normal_method; ///< contact normal estimator (default AREA_GRADIENT)
    pp_contact_mode contact_mode;   ///< contact points per pair (default MANIFOLD)
    int32_t raster_stride;          ///< collision grid coarsening: 1, 2 or 4 pixels per sample (default 1)
    float pixels_per_meter;         ///< internal length scale handed to ODE, px/m, > 0 (default 100)
    float contact_slop;             ///< depth contacts rest at, px, ≥ 0: deeper is pushed out (default 0.75)
    float contact_erp;              ///< fraction of penetration corrected per solver step, 0..1 (default 0.2)
    float contact_cfm;              ///< contact softness, ODE constraint force mixing, non-dimensional, ≥ 0 (default 1e-5)
    float bounce_threshold;         ///< approach speed below which restitution is ignored, px/s, ≥ 0 (default 20)
    uint32_t allow_sleep;           ///< nonzero: resting bodies are put to sleep (default 1)
    float sleep_linear_speed;       ///< speed under which a body may sleep, px/s, ≥ 0 (default 5)
    float sleep_angular_speed;      ///< angular speed under which a body may sleep, rad/s, ≥ 0 (default 0.1)
    float sleep_time;               ///< time a body must stay slow before it sleeps, s, ≥ 0 (default 0.5)
    uint32_t continuous;            ///< nonzero: a dynamic body moving over half its thickness in a substep is swept
                                    ///< against static and kinematic bodies and stopped where it first hits (default 1)
    float max_correction_speed;     ///< fastest that contacts push overlapping bodies apart, px/s, > 0 (default 300)
    int32_t worker_threads;         ///< threads the narrowphase may use, 1..16, or 0: one per CPU, at most 16 (default 0);
                                    ///< started only when a step's pairs are big enough to need them
    uint32_t contact_events;        ///< nonzero: PP_EVENT_CONTACT_BEGIN/END are queued for pp_world_get_events (default 0)
    int32_t exact_island_rows;      ///< islands of at most this many constraint rows (2 a contact point) are solved
                                    ///< by ODE's exact dWorldStep, larger ones by QuickStep; 0: none (default 128)
} pp_world_def;

/// Default world settings (the balanced preset).
PP_API pp_world_def pp_world_def_default(void);
/// The settings of a preset; an unknown preset gives struct_size 0, which pp_world_create refuses (PP_ERR_ABI).
PP_API pp_world_def pp_world_def_preset(pp_preset preset);
/// Create a world from a def.
PP_API pp_status pp_world_create(const pp_world_def *def, pp_world *out);
/// The settings the world runs with: its def, with zero counts replaced by their defaults.
PP_API pp_status pp_world_get_def(pp_world w, pp_world_def *out);
/// Set the world's gravity, px/s² (finite, at most PP_MAX_ACCELERATION long); wakes every sleeping body.
PP_API pp_status pp_world_set_gravity(pp_world w, pp_vec2 gravity);
/// Destroy a world and all its bodies; the handle becomes stale.
PP_API pp_status pp_world_destroy(pp_world w);
/// Advance the world by dt seconds (0 < dt ≤ 1), in `substeps` solver steps.
PP_API pp_status pp_world_step(pp_world w, float dt);
/// Simulated time since the world was created, s (the sum of the dt of every step).
PP_API pp_status pp_world_get_time(pp_world w, double *seconds);

/// What the last pp_world_step did and what it cost.
typedef struct pp_step_stats {
    float broadphase_ms;   ///< candidate-pair search, milliseconds (all substeps)
    float narrowphase_ms;  ///< raster collision, milliseconds (all substeps)
    float solver_ms;       ///< ODE, milliseconds (all substeps)
    float total_ms;        ///< the whole step, milliseconds
    int32_t bodies;        ///< live bodies
    int32_t awake_bodies;  ///< dynamic or kinematic bodies not asleep
    int32_t pairs;         ///< candidate pairs in the last substep (carried ones included)
    int32_t contacts;      ///< contact points made in the last substep
    int64_t pixels_tested; ///< raster samples tested (all substeps; a pair touching at the step's start once)
    pp_backend backend;    ///< the backend that ran the narrowphase (CPU or GPU)
    uint32_t swept_stops;  ///< times continuous collision stopped a fast body at a wall (all substeps)
    int32_t threads;       ///< most threads any narrowphase work of the step ran on (the pairs' set-up, CPU cores,
                           ///< contacts), the calling one included (1: it alone; 0: no pairs)
} pp_step_stats;

/// Statistics of the last step.
PP_API pp_status pp_world_get_stats(pp_world w, pp_step_stats *out);

/* Contacts are those of the last substep, then those of the sleeping pairs: an island that falls asleep keeps
 * its pairs and each pair its points with the impulses of its last solve, so a pile at rest still lists what
 * it stands on. `a` is the pair's body in the lower slot. normal_impulse is read back from ODE's joint
 * feedback: a box resting on the ground (awake or asleep) has impulses summing to its weight × the substep;
 * divide by the substep (s) for a force. pp_world_collide runs no solver and reports 0. */

/// One contact point between two bodies.
typedef struct pp_contact {
    pp_body a;           ///< first body
    pp_body b;           ///< second body
    pp_vec2 point;       ///< world contact point, px
    pp_vec2 normal;      ///< unit normal pointing from a to b
    float depth;         ///< penetration along the normal, px
    int32_t pixel_count; ///< intersecting pixels of the pair (shared by a pair's points)
    float normal_impulse; ///< impulse the solver applied at this point along the normal in the last substep,
                          ///< mass·px/s, ≥ 0 (force = impulse ÷ substep); 0 from pp_world_collide
    uint32_t reserved;   ///< zero
} pp_contact;

/// Write up to capacity contacts: the last substep's, then the sleeping pairs'; count receives the total.
PP_API pp_status pp_world_get_contacts(pp_world w, pp_contact *out, int32_t capacity, int32_t *count);

/* Events queue inside a step and inside an edit between steps (an erase, paint, pixel write or explosion
 * that splits or empties a body or breaks a joint), and wait, across any number of steps, until
 * pp_world_get_events reads them, oldest first; reading forgets those written, and nothing else does but the
 * queue's cap (past PP_MAX_QUEUED_EVENTS unread, the oldest are dropped, with a log line). Read them when it
 * suits, usually after each pp_world_step; a handle in an event may be stale by then (a piece destroyed
 * since). Contacts, unlike events, are the last substep's and each step replaces them.
 * Splits and destruction: an edit that cuts a dynamic body (or a static one with detach_islands) into
 *   several 8-connected islands keeps the largest under the old handle and makes each other island a new
 *   body moving as its material did (v + ω × r): BODY_SPLIT. A body left without pixels is destroyed:
 *   BODY_DESTROYED.
 * What a split piece inherits from its parent: its island's pixels (mask,
 *   weights and sprite); the type (a static parent's piece, cut loose by detach_islands, is dynamic); the
 *   angle; density, friction, restitution, linear and angular damping, category and mask bits,
 *   fixed_rotation, detach_islands, bullet, is_sensor, one_way and one_way_direction, user_data, and a
 *   dynamic piece's gravity scale. Not inherited: the pivot (the centre of the piece's own bitmap, whatever
 *   the parent's), the velocity (the parent's material's at the piece's centre of mass: v + ω × r, and ω
 *   itself unless fixed_rotation), forces and torques applied for the next step (they stay on the parent),
 *   and joints (each stays on the piece that holds its anchor).
 * Contact events (opt-in: pp_world_def.contact_events or pp_world_set_contact_events, since they queue
 *   until read): each substep compares the touching pairs with those of the substep before; a new pair
 *   queues CONTACT_BEGIN, a pair gone CONTACT_END. `body` is the pair's body in the lower slot, as in
 *   pp_contact. Pairs of sleeping bodies are not tested and not ended, so a pile that falls asleep keeps
 *   its pairs (and lists their contacts), and a pair woken while still touching begins nothing; an edit
 *   that parts a sleeping pair wakes it and ends the pair at the next substep, and destroying a body (or
 *   emptying it) ends its pairs there too. Switched on, pairs
 *   already touching begin at the next substep; switched off, recorded pairs end without an event. Among
 *   crowded bodies (PP_CROWDED_CONTACT_PAIRS) only the pairs the budget collides are seen.
 * Sensors (pp_body_def.is_sensor): a pair with a sensor runs the narrowphase but makes no contact:
 *   SENSOR_BEGIN/END with the sensor as `body`, with or without contact_events. Continuous collision,
 *   rays and queries ignore sensors; two sensors do not sense each other; a body moves through a sensor
 *   exactly as if it were not there.
 * One-way platforms (pp_body_def.one_way): when a pair with a platform begins, its contacts are kept only
 *   if the normal from the platform to the other body lies within 60° of one_way_direction (bitmap axes,
 *   turning with the body); otherwise the pair passes until the two part. The choice lasts while they
 *   touch, so a body standing on a platform stays on it, and one that jumps up through it lands on it on
 *   the way down. Continuous collision stops a fast body only when it moves against
 *   one_way_direction (falling onto the platform), and not while it is inside.
 * The step records touching pairs only when something needs them (contact events, a sensor or a platform
 * in the world, or pairs still to be ended); an unused feature costs nothing. */

/// What an event reports.
typedef enum pp_event_type {
    PP_EVENT_BODY_SPLIT = 1,     ///< an edit cut `body` apart; `other` is a new body made of one of its islands
    PP_EVENT_BODY_DESTROYED = 2, ///< an edit left `body` without solid pixels; the handle is now stale
    PP_EVENT_CONTACT_BEGIN = 3,  ///< `body` and `other` started touching (worlds with contact_events only)
    PP_EVENT_CONTACT_END = 4,    ///< `body` and `other` stopped touching, or one of them was destroyed
    PP_EVENT_SENSOR_BEGIN = 5,   ///< `other` started overlapping the sensor `body`
    PP_EVENT_SENSOR_END = 6,     ///< `other` stopped overlapping the sensor `body`, or one of them was destroyed
    PP_EVENT_JOINT_BROKEN = 7,   ///< `joint` (between `body` = body_a and `other` = body_b) broke: its reaction passed
                                 ///< break_force, or an edit left no solid pixel within 1 px of an anchor; now stale
    PP_EVENT_TYPE_FORCE_U32 = 0x7fffffff
} pp_event_type;

/// Something that happened to a body, read with pp_world_get_events.
typedef struct pp_event {
    pp_event_type type;   ///< what happened
    uint32_t reserved;    ///< zero
    pp_body body;         ///< the body it happened to (SPLIT: the parent, which keeps the largest island; SENSOR: the sensor)
    pp_body other;        ///< SPLIT: the new body; DESTROYED: zero; CONTACT, SENSOR: the other body of the pair
    pp_vec2 point;        ///< CONTACT_BEGIN, SENSOR_BEGIN: world point of the first contact, px; else zero
    pp_vec2 normal;       ///< CONTACT_BEGIN, SENSOR_BEGIN: unit normal from `body` to `other`; else zero
    float approach_speed; ///< CONTACT_BEGIN, SENSOR_BEGIN: speed at which the bodies closed along the normal
                          ///< at the point before the solver acted, px/s, ≥ 0; else zero
    uint32_t reserved2;   ///< zero
    pp_joint joint;       ///< JOINT_BROKEN: the joint, now stale; else zero
} pp_event;

/// Events a world keeps unread: a step drops the oldest beyond this many before it runs (a log line says how
/// many), so a host that never reads events does not grow without bound. Read them every frame and none go.
#define PP_MAX_QUEUED_EVENTS (1 << 16)
/// Write up to capacity events that happened since they were last read, oldest first, and forget those
/// written; count receives how many were pending (capacity 0 only counts them).
PP_API pp_status pp_world_get_events(pp_world w, pp_event *out, int32_t capacity, int32_t *count);
/// Switch CONTACT_BEGIN/END events on (nonzero) or off, as pp_world_def.contact_events; pairs already touching
/// when they go on begin at the next substep.
PP_API pp_status pp_world_set_contact_events(pp_world w, uint32_t enabled);

/// A renderer's view of a world: the world point at the image centre, the scale and the image size.
typedef struct pp_camera {
    pp_vec2 center; ///< world point shown at the image centre, px, finite (default 480, 270)
    float zoom;     ///< image pixels per world pixel, > 0 (default 1)
    int32_t width;  ///< image width, image px, 1..PP_MAX_BITMAP_SIDE (default 960)
    int32_t height; ///< image height, image px, 1..PP_MAX_BITMAP_SIDE (default 540)
} pp_camera;

/// The world's camera (a scene file's, or the default).
PP_API pp_status pp_world_get_camera(pp_world w, pp_camera *out);
/// Replace the world's camera.
PP_API pp_status pp_world_set_camera(pp_world w, const pp_camera *camera);

/* ---- Bodies: settings, creation, pose, velocity, mass, runtime properties, forces ---- */

/// How a body moves.
typedef enum pp_body_type {
    PP_BODY_DYNAMIC = 0,   ///< moved by forces and contacts
    PP_BODY_STATIC = 1,    ///< never moves; no mass, no ODE body
    PP_BODY_KINEMATIC = 2, ///< moved only by its velocity; pushes dynamic bodies, is never pushed
    PP_BODY_FORCE_U32 = 0x7fffffff
} pp_body_type;

/// Settings of a body; fill from pp_body_def_default(). The library copies the bitmap planes.
typedef struct pp_body_def {
    uint32_t struct_size;     ///< sizeof(pp_body_def), set by pp_body_def_default
    pp_body_type type;        ///< dynamic, static or kinematic (default DYNAMIC)
    pp_vec2 position;         ///< world position of the pivot, px, finite
    float angle;              ///< rotation, radians, finite (positive turns +x toward +y)
    uint32_t custom_pivot;    ///< nonzero: use `pivot`; zero: the pivot is the bitmap centre
    pp_vec2 pivot;            ///< pivot in bitmap coordinates (origin at the top-left corner), px
    pp_vec2 linear_velocity;  ///< initial velocity of the centre of mass, px/s, at most PP_MAX_SPEED long
    float angular_velocity;   ///< initial angular velocity, rad/s, within ±PP_MAX_ANGULAR_SPEED
    float density;            ///< mass of one solid pixel of weight 255, mass units, > 0 (default 1)
    float friction;           ///< Coulomb coefficient, ≥ 0 (default 0.6); pairs use sqrt(fa·fb)
    float restitution;        ///< bounciness 0..1 (default 0); pairs use max(ra, rb)
    float linear_damping;     ///< velocity decay, 1/s, ≥ 0 (default 0)
    float angular_damping;    ///< angular velocity decay, 1/s, ≥ 0 (default 0)
    uint32_t category_bits;   ///< the categories this body is in (default 1)
    uint32_t mask_bits;       ///< the categories it collides with (default all)
    uint32_t fixed_rotation;  ///< nonzero: the body never rotates
    int32_t width;            ///< bitmap width, px, 1..PP_MAX_BITMAP_SIDE
    int32_t height;           ///< bitmap height, px, 1..PP_MAX_BITMAP_SIDE
    const uint8_t *rgba;      ///< optional sprite, width·height·4 bytes, rows top to bottom
    const uint8_t *mask;      ///< optional collision mask, width·height bytes, non-zero is solid; overrides rgba
    const uint8_t *weights;   ///< optional relative mass per pixel 0..255, width·height bytes
    uint32_t alpha_threshold; ///< sprite alpha at or above which a pixel is solid, 1..255 (default 128)
    uint32_t detach_islands;  ///< static bodies: nonzero makes islands cut loose by an edit fall as dynamic bodies (default 0)
    uint64_t user_data;       ///< the host's value, returned by pp_body_get_user_data
    uint32_t bullet;          ///< nonzero: when fast, swept against every body it collides with, dynamic ones too,
                              ///< even in a world without `continuous` (default 0)
    uint32_t is_sensor;       ///< nonzero: overlaps are reported as PP_EVENT_SENSOR_BEGIN/END, nothing collides with it
                              ///< and rays and queries skip it; static and kinematic sensors need no mass (default 0)
    uint32_t one_way;         ///< nonzero: a one-way platform; a contact is kept only when the other body arrives from
                              ///< the `one_way_direction` side, and then for as long as they touch (default 0)
    pp_vec2 one_way_direction; ///< the side bodies may land from, in bitmap axes, any length > 0 (default (0, −1): up)
} pp_body_def;

/// Default body settings: a dynamic body with no bitmap yet.
PP_API pp_body_def pp_body_def_default(void);
/// Create a body from a def; the bitmap planes are copied.
PP_API pp_status pp_body_create(pp_world w, const pp_body_def *def, pp_body *out);
/// Destroy a body; its handle becomes stale.
PP_API pp_status pp_body_destroy(pp_world w, pp_body b);
/// Write up to capacity live body handles; count receives the total.
PP_API pp_status pp_world_get_bodies(pp_world w, pp_body *out, int32_t capacity, int32_t *count);
/// Bitmap size of the body, px; either pointer may be NULL.
PP_API pp_status pp_body_get_size(pp_world w, pp_body b, int32_t *width, int32_t *height);
/// The host's value given in the body def.
PP_API pp_status pp_body_get_user_data(pp_world w, pp_body b, uint64_t *out);
/// World position of the body's pivot, px.
PP_API pp_status pp_body_get_position(pp_world w, pp_body b, pp_vec2 *out);
/// Rotation of the body, radians.
PP_API pp_status pp_body_get_angle(pp_world w, pp_body b, float *out);
/// Pivot of the body in bitmap coordinates, px.
PP_API pp_status pp_body_get_pivot(pp_world w, pp_body b, pp_vec2 *out);
/// Teleport the body: pivot to position (px), rotation to angle (radians), both finite; wakes it.
PP_API pp_status pp_body_set_transform(pp_world w, pp_body b, pp_vec2 position, float angle);
/// Velocity of the centre of mass (px/s) and angular velocity (rad/s); either pointer may be NULL.
PP_API pp_status pp_body_get_velocity(pp_world w, pp_body b, pp_vec2 *linear, float *angular);
/// Set the velocity of the centre of mass (px/s, at most PP_MAX_SPEED long) and angular velocity (rad/s, within
/// ±PP_MAX_ANGULAR_SPEED); wakes it.
PP_API pp_status pp_body_set_velocity(pp_world w, pp_body b, pp_vec2 linear, float angular);
/// Mass (mass units), centre of mass in bitmap coordinates (px) and inertia about it (mass·px²); any pointer may be NULL.
PP_API pp_status pp_body_get_mass(pp_world w, pp_body b, float *mass, pp_vec2 *local_center, float *inertia);
/// Memory the body holds, bytes: its collision raster (1-bit mask, tile, row and column counts, and an 8-bit
/// weight plane only if it has weights) and its sprite copy (4 bytes a pixel; 0 without a sprite); either may be NULL.
PP_API pp_status pp_body_get_memory(pp_world w, pp_body b, int64_t *collision_bytes, int64_t *sprite_bytes);
/// Whether the body is awake (1) or asleep (0); static bodies are never awake.
PP_API pp_status pp_body_is_awake(pp_world w, pp_body b, int32_t *awake);

/// One body's state as pp_world_get_body_states reads it.
typedef struct pp_body_state {
    pp_body body;
    pp_vec2 position;          ///< the pivot in the world, px
    float angle;               ///< rotation, rad
    pp_vec2 linear_velocity;   ///< of the centre of mass, px/s (0 for a static body)
    float angular_velocity;    ///< rad/s
    uint32_t awake;            ///< 1 awake, 0 asleep (a static body is never awake)
    uint64_t user_data;        ///< the host's value (pp_body_get_user_data); last, so older fields keep their offsets
} pp_body_state;

/// Every live body's state in one call, in slot order (pp_world_get_bodies' order); count receives how many
/// live bodies there are, even when capacity is short (then only capacity are written).
PP_API pp_status pp_world_get_body_states(pp_world w, pp_body_state *out, int32_t capacity, int32_t *count);

/* Runtime properties. A setter takes effect at the next step, keeps the pose, and wakes the body and the
 * bodies whose boxes meet its own (a sleeping crate on a ground whose friction changed notices it). What a
 * body def refuses, the setter refuses the same way, with PP_ERR_INVALID_ARGUMENT naming the value. */

/// Set the body's Coulomb friction coefficient (≥ 0); pairs use sqrt(fa·fb).
PP_API pp_status pp_body_set_friction(pp_world w, pp_body b, float friction);
/// Set the body's restitution (0..1); pairs use max(ea, eb).
PP_API pp_status pp_body_set_restitution(pp_world w, pp_body b, float restitution);
/// Set the body's velocity decay, 1/s (≥ 0), linear and angular, as pp_body_def's damping fields.
PP_API pp_status pp_body_set_damping(pp_world w, pp_body b, float linear, float angular);
/// Make the body static, dynamic or kinematic: the pose stays, a moving body keeps its velocity (a static one
/// starts at rest), mass and inertia come from its pixels; one that stops being dynamic drops its forces and
/// gravity scale. Refused for massless pixels made dynamic, or a static body left on a joint holding nothing
/// that moves. Wakes it and what it touches.
PP_API pp_status pp_body_set_type(pp_world w, pp_body b, pp_body_type type);
/// Hold the body's rotation (nonzero: angular velocity 0 from now, as pp_body_def's fixed_rotation) or free it.
PP_API pp_status pp_body_set_fixed_rotation(pp_world w, pp_body b, uint32_t fixed);
/// Set the mass per solid pixel (> 0, pp_body_def's density): mass and inertia follow, the velocity stays.
PP_API pp_status pp_body_set_density(pp_world w, pp_body b, float density);
/// Set the categories the body is in and those it collides with (pp_body_def's category_bits, mask_bits).
PP_API pp_status pp_body_set_filter(pp_world w, pp_body b, uint32_t category_bits, uint32_t mask_bits);
/// Wake a dynamic or kinematic body (awake 1) or put it to sleep now, its velocity zeroed (awake 0); an awake
/// body touching it wakes it again at the next step. PP_ERR_INVALID_ARGUMENT for a static body.
PP_API pp_status pp_body_set_awake(pp_world w, pp_body b, uint32_t awake);
/// Scale the world's gravity on this body (default 1; 0 floats, −1 rises); kept until set again. Dynamic only.
/// Range: finite, −PP_MAX_GRAVITY_SCALE..PP_MAX_GRAVITY_SCALE (±1000); outside it PP_ERR_INVALID_ARGUMENT.
PP_API pp_status pp_body_set_gravity_scale(pp_world w, pp_body b, float scale);
/// The body's friction coefficient.
PP_API pp_status pp_body_get_friction(pp_world w, pp_body b, float *out);
/// The body's restitution, 0..1.
PP_API pp_status pp_body_get_restitution(pp_world w, pp_body b, float *out);
/// The body's mass per solid pixel (density).
PP_API pp_status pp_body_get_density(pp_world w, pp_body b, float *out);
/// The body's gravity scale (1 unless set).
PP_API pp_status pp_body_get_gravity_scale(pp_world w, pp_body b, float *out);
/// Whether the body's rotation is held (1) or free (0).
PP_API pp_status pp_body_get_fixed_rotation(pp_world w, pp_body b, uint32_t *out);
/// Type of the body (dynamic, static or kinematic).
PP_API pp_status pp_body_get_type(pp_world w, pp_body b, pp_body_type *out);

/// Apply an impulse (mass·px/s) at a world point (px), both finite, giving a velocity within PP_MAX_SPEED and
/// PP_MAX_ANGULAR_SPEED; wakes the body. Dynamic bodies only.
PP_API pp_status pp_body_apply_impulse(pp_world w, pp_body b, pp_vec2 impulse, pp_vec2 world_point);
/// Change the angular velocity by impulse / inertia at once (mass·px²/s); wakes the body. Dynamic bodies only.
PP_API pp_status pp_body_apply_angular_impulse(pp_world w, pp_body b, float impulse);
/// Apply a force (mass·px/s²) at a world point (px), both finite, through every substep of the next step; forces
/// add up and are spent by the step. Wakes the body. Dynamic bodies only.
PP_API pp_status pp_body_apply_force(pp_world w, pp_body b, pp_vec2 force, pp_vec2 world_point);
/// Apply a torque (mass·px²/s², finite, +x turning toward +y) through the next step, as pp_body_apply_force.
/// Dynamic only.
PP_API pp_status pp_body_apply_torque(pp_world w, pp_body b, float torque);

/* ---- Joints: types, settings, creation, reactions, motors, limits ---- */

/* Joints hold two bodies together through ODE's joints in the plane: REVOLUTE a hinge about z, PRISMATIC a
 * slider along an in-plane axis, DISTANCE ODE's distance ball (rigid, a rope between min_length and
 * max_length, or a spring), WELD a fixed joint (rigid or soft; with angular_hertz a ball joint and a spring on
 * its angle), MOUSE a soft pull of a body's point toward a target. WHEEL and MOTOR, the springs toward `target`,
 * a rope's one-sided pulls and pushes and DISTANCE's motor are rows of ODE's angular motor, distance ball and
 * contact joints set each substep. A zero body is the static world. Anchors are given in world px at creation and kept as bitmap
 * points of their bodies (each within 4096 px, or the bitmap's size, of its bitmap): an edit that leaves no solid pixel within 1 px of an anchor breaks the joint, and a
 * split keeps each joint on the piece holding its anchor. A joint whose reaction passes break_force, or whose
 * torque about body_b's anchor passes break_torque, after a step breaks. A broken joint queues PP_EVENT_JOINT_BROKEN; a joint of a body destroyed by pp_body_destroy
 * goes with it silently (the host asked). Joined bodies solve and sleep together; collide_connected 0 (the
 * default) keeps the two from colliding. Springs are given by frequency (Hz) and damping ratio, made into
 * ODE's ERP and CFM from the pair's reduced mass (angular ones from the inertias about the anchor); 0 Hz is rigid. */

/// What a joint holds.
typedef enum pp_joint_type {
    PP_JOINT_REVOLUTE = 1,  ///< a shared point; the bodies turn about it (angle limits, motor)
    PP_JOINT_PRISMATIC = 2, ///< b slides along an axis fixed in a, without turning (translation limits, motor)
    PP_JOINT_DISTANCE = 3,  ///< the anchors' distance held rigid, between min and max (rope), or by a spring
    PP_JOINT_WELD = 4,      ///< the bodies held together, rigid or by a spring
    PP_JOINT_MOUSE = 5,     ///< body_b's anchor pulled toward a target by a spring under max_force
    PP_JOINT_WHEEL = 6,     ///< b's anchor slides along an axis fixed in a on a spring and turns freely (motor: b's spin)
    PP_JOINT_MOTOR = 7,     ///< drives b's pose relative to a toward linear_offset, angular_offset under max_force, max_torque
    PP_JOINT_TYPE_FORCE_U32 = 0x7fffffff
} pp_joint_type;

/// A joint's description, filled by pp_joint_def_default(type).
typedef struct pp_joint_def {
    uint32_t struct_size;        ///< sizeof(pp_joint_def), set by pp_joint_def_default
    pp_joint_type type;          ///< the kind of joint
    pp_body body_a;              ///< first body; zero is the static world
    pp_body body_b;              ///< second body; zero is the static world (not both zero, not the same body)
    pp_vec2 anchor_a;            ///< world px at creation; REVOLUTE, WELD and MOUSE use anchor_a alone
    pp_vec2 anchor_b;            ///< world px at creation (PRISMATIC, DISTANCE)
    pp_vec2 axis;                ///< PRISMATIC: the slide direction in the world, any length > 0 (default (1, 0))
    uint32_t collide_connected;  ///< nonzero: the two bodies still collide with each other (default 0)
    uint32_t enable_limit;       ///< nonzero: lower..upper hold (REVOLUTE, PRISMATIC, WHEEL's slide)
    float lower;                 ///< lowest angle (rad, within −π..π) or translation (px), ≤ upper
    float upper;                 ///< highest angle (rad) or translation (px)
    uint32_t enable_motor;       ///< nonzero: drive toward motor_speed under max_motor_force (REVOLUTE, PRISMATIC,
                                 ///< WHEEL's spin, DISTANCE's length)
    float motor_speed;           ///< rad/s (REVOLUTE, WHEEL, within ±PP_MAX_ANGULAR_SPEED) or px/s (PRISMATIC, DISTANCE
                                 ///< (positive lengthens), ±PP_MAX_SPEED)
    float max_motor_force;       ///< ≥ 0: mass·px/s² (PRISMATIC, DISTANCE) or a torque in mass·px²/s² (REVOLUTE, WHEEL)
    float min_length;            ///< DISTANCE: shortest anchor distance, px, ≥ 0; min 0 and max 0 keep it rigid
    float max_length;            ///< DISTANCE: longest anchor distance, px, ≥ min_length; a rope (max > min) only pulls at
                                 ///< max_length and only pushes at min_length
    float spring_hertz;          ///< DISTANCE, WELD (its translation), MOUSE, WHEEL (its slide), REVOLUTE and PRISMATIC
                                 ///< (toward target): spring frequency, Hz, ≥ 0; 0 is rigid or none (MOUSE default 5)
    float spring_damping_ratio;  ///< the same joints' damping ratio, ≥ 0, 1 critical (MOUSE default 0.7)
    float max_force;             ///< MOUSE: largest pull of the spring (its damping acts on top); MOTOR: largest push;
                                 ///< mass·px/s², ≥ 0; 0: no cap
    float break_force;           ///< the reaction force that breaks the joint after a step, mass·px/s², ≥ 0; 0 never
    uint32_t reserved;           ///< zero
    uint64_t user_data;          ///< the host's value, returned by pp_joint_get_user_data
    /* Added with WHEEL and MOTOR: a def whose struct_size ends at user_data is still taken, these at their defaults. */
    float target;                ///< REVOLUTE (rad, −π..π), PRISMATIC (px): where spring_hertz > 0 pulls, from creation
    float angular_hertz;         ///< WELD: spring frequency of its rotation, Hz, ≥ 0; 0 rigid
    float angular_damping_ratio; ///< WELD: damping ratio of its rotation, ≥ 0, 1 critical
    float break_torque;          ///< the torque about body_b's anchor that breaks the joint after a step, mass·px²/s², ≥ 0; 0 never
    pp_vec2 linear_offset;       ///< MOTOR: b's centre of mass in a's frame, a's centre of mass as origin, px
    float angular_offset;        ///< MOTOR: b's angle minus a's, rad
    float max_torque;            ///< MOTOR: largest torque, mass·px²/s², ≥ 0; 0: no cap
    float correction_factor;     ///< MOTOR: share of the pose error corrected each substep, 0..1 (default 0.3)
    uint32_t reserved2;          ///< zero
} pp_joint_def;

/// A joint def with the defaults of its type (struct_size set; type PP_JOINT_REVOLUTE for an unknown type).
PP_API pp_joint_def pp_joint_def_default(pp_joint_type type);
/// Create a joint from a def; anchors in world px at the bodies' current poses. Wakes both bodies.
PP_API pp_status pp_joint_create(pp_world w, const pp_joint_def *def, pp_joint *out);
/// Destroy a joint; its handle goes stale. Wakes its bodies.
PP_API pp_status pp_joint_destroy(pp_world w, pp_joint j);
/// Every live joint, in slot order; count receives the total even when capacity is short.
PP_API pp_status pp_world_get_joints(pp_world w, pp_joint *out, int32_t capacity, int32_t *count);
/// The force (mass·px/s²) and torque (mass·px²/s², about body_b's centre of mass) the joint applied to
/// body_b in the last substep; zeros before the first step and while asleep.
PP_API pp_status pp_joint_get_reaction(pp_world w, pp_joint j, pp_vec2 *force, float *torque);
/// REVOLUTE: angle of b relative to a since creation, rad (−π..π), and its rate, rad/s; PRISMATIC, WHEEL:
/// translation of b along the axis since creation, px, px/s; DISTANCE: anchor distance, px, px/s; others 0.
PP_API pp_status pp_joint_get_value(pp_world w, pp_joint j, float *value, float *speed);
/// REVOLUTE, PRISMATIC, WHEEL (spin), DISTANCE (length): switch the motor; speed in rad/s (±PP_MAX_ANGULAR_SPEED) or
/// px/s (±PP_MAX_SPEED), max_force finite and ≥ 0 (a torque for REVOLUTE and WHEEL).
PP_API pp_status pp_joint_set_motor(pp_world w, pp_joint j, uint32_t enabled, float speed, float max_force);
/// REVOLUTE (rad, −π..π), PRISMATIC, WHEEL (px), DISTANCE (min and max length, px): switch and set the limits.
PP_API pp_status pp_joint_set_limits(pp_world w, pp_joint j, uint32_t enabled, float lower, float upper);
/// MOUSE: move the target, world px, finite. Wakes the body.
PP_API pp_status pp_joint_set_target(pp_world w, pp_joint j, pp_vec2 target);
/// REVOLUTE, PRISMATIC (toward target: rad within −π..π, px), WHEEL, DISTANCE, WELD (translation): the spring, Hz ≥ 0
/// (0 rigid or none) and damping ratio ≥ 0. Wakes the bodies.
PP_API pp_status pp_joint_set_spring(pp_world w, pp_joint j, float hertz, float damping_ratio, float target);
/// MOTOR: the pose it drives body_b to: b's centre of mass in a's frame from a's (px) and b's angle minus a's (rad).
PP_API pp_status pp_joint_set_offsets(pp_world w, pp_joint j, pp_vec2 linear, float angular);
/// The joint's type.
PP_API pp_status pp_joint_get_type(pp_world w, pp_joint j, pp_joint_type *out);
/// The joint's two bodies (zero for the static world).
PP_API pp_status pp_joint_get_bodies(pp_world w, pp_joint j, pp_body *body_a, pp_body *body_b);
/// The host's value given in the joint's def.
PP_API pp_status pp_joint_get_user_data(pp_world w, pp_joint j, uint64_t *out);
/// The joint's anchors in world px at the bodies' current poses (a static world side's is the world point it was
/// given; MOUSE: anchor_a is the target); either pointer may be NULL.
PP_API pp_status pp_joint_get_anchors(pp_world w, pp_joint j, pp_vec2 *anchor_a, pp_vec2 *anchor_b);

/* ---- Queries: rays, point/box/circle queries, pair collision, debug view ---- */

/* Rays (pp_world_raycast) walk each body's pixel grid in the body's frame, an exact DDA over the pixel
 * squares [i, i+1) × [j, j+1) that jumps whole empty 8×8 tiles, and stop at the first solid pixel of the
 * nearest body. The normal is the mask's area gradient (the contact normal's estimator) over the solid
 * pixel centres within 8 px of where the ray enters the pixel; the point then moves along the ray (≤ 8 px)
 * onto the edge line that a 4 px window places across it. Where no straight edge fits the window (a body
 * or feature thinner than it, a crossing of lines) the point stays where the ray enters the pixel, and
 * with no usable gradient the normal is the axis of the face entered. A ray a few degrees off a staircase
 * edge meets a pixel that stands proud of the edge up to 0.7 / sin(angle) px early: that pixel is the hit.
 * Queries (pp_world_query_point, _aabb, _circle) name bodies in slot order and stop at a body's first
 * pixel; the circle query uses the rule of pp_world_erase_circle, so it names exactly the bodies that
 * erase would change. Rays and queries filter by category_bits & mask_bits, skip sensors, and see static,
 * kinematic and dynamic bodies alike. Accuracy and speed: tests/bench/README.md. */

/// The nearest solid pixel a ray meets, from pp_world_raycast.
typedef struct pp_raycast_hit {
    pp_body body;     ///< the body hit
    pp_vec2 point;    ///< world point on the surface, px: where the ray enters the first solid pixel's square, moved
                      ///< along the ray (≤ 8 px) onto the edge line the mask around it shows; `from` at fraction 0
    pp_vec2 normal;   ///< unit surface normal there, out of the body, world axes: the mask's area gradient in an 8 px
                      ///< window; the ray's reverse when the ray starts inside a solid pixel, (0, 0) if from == to
    float fraction;   ///< where along from → to the point lies, 0..1; 0 when from is in a solid pixel
    uint32_t reserved; ///< zero
} pp_raycast_hit;

/// Cast the segment from → to (world px) through the pixel grid of every body whose category_bits meet mask_bits
/// (sensors are skipped); hit receives 1 and out the nearest solid pixel, or 0 and out zeroed. A ray starting inside
/// a solid pixel hits that body at fraction 0; a zero-length ray (from == to) is such a point test.
PP_API pp_status pp_world_raycast(pp_world w, pp_vec2 from, pp_vec2 to, uint32_t mask_bits, pp_raycast_hit *out,
                                  int32_t *hit);
/// Write up to capacity bodies (category_bits meeting mask_bits, sensors skipped) with a solid pixel whose square
/// contains the world point (px), in slot order; count receives the total.
PP_API pp_status pp_world_query_point(pp_world w, pp_vec2 point, uint32_t mask_bits, pp_body *out, int32_t capacity,
                                      int32_t *count);
/// As pp_world_query_point, for bodies with a solid pixel whose centre lies in the world box [lower, upper] (px).
PP_API pp_status pp_world_query_aabb(pp_world w, pp_vec2 lower, pp_vec2 upper, uint32_t mask_bits, pp_body *out,
                                     int32_t capacity, int32_t *count);
/// As pp_world_query_point, for bodies with a solid pixel whose centre lies within radius (px, ≥ 0) of a world
/// point (px): the bodies pp_world_erase_circle would change.
PP_API pp_status pp_world_query_circle(pp_world w, pp_vec2 center, float radius, uint32_t mask_bits, pp_body *out,
                                       int32_t capacity, int32_t *count);

/// Sweep b's solid pixels, as their squares, from its pose along translation (px, finite; rotation held) against
/// the bodies whose category_bits meet mask_bits (b, sensors and the bodies b's filter or joints keep apart are
/// skipped); hit receives 1 and out the first touch (fraction: the part of translation b moves free, to 1/16 px of
/// travel; point, px; normal out of the body hit; 0 when b overlaps one at its start), or 0 and out zeroed.
/// Nothing in the world changes.
PP_API pp_status pp_world_cast_body(pp_world w, pp_body b, pp_vec2 translation, uint32_t mask_bits,
                                    pp_raycast_hit *out, int32_t *hit);
/// As pp_world_raycast for every body the segment from → to (world px) enters: up to capacity hits, each body's
/// first entry, nearest first (ties in slot order); count receives the total even when capacity is smaller.
PP_API pp_status pp_world_raycast_all(pp_world w, pp_vec2 from, pp_vec2 to, uint32_t mask_bits, pp_raycast_hit *out,
                                      int32_t capacity, int32_t *count);

/// A character for pp_world_move_character: a capsule the host owns, not a body.
typedef struct pp_character_def {
    uint32_t struct_size;   ///< set by pp_character_def_default
    float radius;           ///< px, > 0: a capsule of two discs of this radius
    float half_height;      ///< px, ≥ 0: the discs' centres at position ± (0, half_height); 0: one disc
    float step_height;      ///< px, ≥ 0: a ledge up to this high is climbed while moving along the ground (default 4)
    float snap_distance;    ///< px, ≥ 0: a grounded character moving on keeps to ground within this below it (default 4)
    float max_slope;        ///< rad, 0..π/2: ground steeper than this is a wall to slide down (default 0.8)
    uint32_t mask_bits;     ///< solid pixels of bodies whose category_bits meet it block (default all; sensors never)
} pp_character_def;

/// Where a move took a character (pp_world_move_character).
typedef struct pp_character_move {
    pp_vec2 position;        ///< where the character ends, px
    pp_vec2 velocity;        ///< the velocity asked for, less the parts the surfaces met took away, px/s
    uint32_t grounded;       ///< nonzero: standing on ground no steeper than max_slope
    pp_vec2 ground_normal;   ///< unit, out of the ground; (0, 0) when not grounded
    pp_body ground_body;     ///< the body stood on; zero when not grounded
    pp_vec2 ground_velocity; ///< that body's velocity under the character, px/s (moving platforms)
    int32_t surfaces;        ///< surfaces met during the move
} pp_character_move;

/// A character def with the defaults: radius 8 px, half_height 8 px, step_height 4 px, snap_distance 4 px,
/// max_slope 0.8 rad, every mask bit.
PP_API pp_character_def pp_character_def_default(void);
/// Move a character's capsule from position (px) along velocity (px/s) × dt (s, ≥ 0) against the solid pixels of
/// the bodies def->mask_bits meets, sliding along them, climbing steps, keeping to the ground; "up" is against the
/// world's gravity ((0, -1) without one). The capsule's round bottom also climbs, as a slope, a ledge whose corner is
/// no steeper than max_slope (up to radius·(1 − cos max_slope) high). A walker (velocity not against gravity) on the
/// ground rides its pixels smoothed: its height moves toward the exact contact by at most 18 px/s (0.3 px a frame at
/// 60 Hz; more on ground sloping over 0.25, to follow it), so ±1 px pixel noise does not shake it, sinking at most
/// 0.4 px into the solid pixels' centres or floating at most 1.5 px above them (still grounded); pass the position
/// back and the next move starts from the exact contact under it. out receives where it ends. Nothing in the world
/// changes.
PP_API pp_status pp_world_move_character(pp_world w, const pp_character_def *def, pp_vec2 position, pp_vec2 velocity,
                                         float dt, pp_character_move *out);

/// Cell flags written by pp_world_debug_collision.
#define PP_CELL_A 1u        ///< the first body is solid in this cell
#define PP_CELL_B 2u        ///< the second body is solid in this cell
#define PP_CELL_CRITICAL 4u ///< an intersection cell with a neighbour outside the intersection

/// A pair's intersection raster on the narrowphase's sampling grid, for debug views (the poster's Figure 1c).
typedef struct pp_collision_view {
    int32_t width;          ///< grid width, cells
    int32_t height;         ///< grid height, cells
    pp_vec2 origin;         ///< world position of the centre of cell (0, 0), px
    pp_vec2 step_x;         ///< world offset from a cell to its neighbour along the grid's x, px
    pp_vec2 step_y;         ///< world offset from a cell to its neighbour along the grid's y, px
    pp_vec2 normal;         ///< the pair's global normal from a to b, unit; zero when they do not touch
    int32_t intersection;   ///< intersection cells
    int32_t critical;       ///< critical cells
} pp_collision_view;

/// Run the narrowphase on one pair at the current poses, without stepping; count receives the total.
PP_API pp_status pp_world_collide(pp_world w, pp_body a, pp_body b, pp_contact *out, int32_t capacity,
                                  int32_t *count);
/// Run the narrowphase on a pair and write its sampled grid: cells (PP_CELL_* flags) and, when local_normals is
/// not NULL, each critical cell's 3×3-kernel normal in world axes (zero elsewhere); capacity in cells.
/// The view is filled even when capacity is short (then PP_ERR_INVALID_ARGUMENT and nothing written).
PP_API pp_status pp_world_debug_collision(pp_world w, pp_body a, pp_body b, uint8_t *cells, pp_vec2 *local_normals,
                                          int64_t capacity, pp_collision_view *view);

/* Debug drawing: the world's physics as line segments a host draws after a step, as it reads contacts.
 * What is drawn, in this order:
 *   bodies, in slot order, those whose world bounds (the box of their solid pixels) meet the view box, each:
 *     OUTLINE   its solid pixels' boundary on the pixel squares' edges, merged into maximal straight runs and
 *               turned with the body (a w×h box is 4 segments, an L 6); only the runs whose bounds meet the box;
 *               each run has the solid on its right as drawn with y down (clockwise round a box on screen);
 *     AABB      the 4 sides of its world bounds;
 *     CENTER    two segments from its centre of mass along its bitmap x and y axes, PP_DEBUG_AXIS_LENGTH px;
 *     VELOCITY  dynamic and kinematic bodies: from the centre of mass to where it goes in PP_DEBUG_VELOCITY_TIME s;
 *   contacts, in pp_world_get_contacts' order, those whose point lies in the box, each:
 *     CONTACT   a cross of two segments, PP_DEBUG_CROSS_SIZE px to either side of the point along x and along y;
 *     NORMAL    from the point along the normal (a to b), PP_DEBUG_NORMAL_LENGTH px;
 *   joints, in slot order, those with an anchor in the box (the anchors pp_joint_get_anchors reports):
 *     JOINT     anchor a to anchor b, then each body's centre of mass to its anchor (none for the static world).
 * `body` is the body a segment belongs to: a contact's a; for a joint, the body whose centre of mass it starts
 * from, and body_b for anchor to anchor; zero for the static world. The box [lower, upper] is closed, world px, finite; (−FLT_MAX, −FLT_MAX) to
 * (FLT_MAX, FLT_MAX) draws everything. Bodies are found through the broadphase, so a small box costs what it
 * shows. Each body's outline is kept in bitmap px and built again only after an edit changed its mask; the
 * first call after an edit pays for that body's outline, every other call for the transform of its runs.
 * Colours are 0xRRGGBBAA: outlines and AABBs by the body's state, in this order of precedence:
 * sensor PP_DEBUG_COLOR_SENSOR, static PP_DEBUG_COLOR_STATIC, asleep PP_DEBUG_COLOR_ASLEEP, kinematic
 * PP_DEBUG_COLOR_KINEMATIC, awake dynamic PP_DEBUG_COLOR_AWAKE; the rest by kind. */

/// What a debug segment shows.
typedef enum pp_debug_kind {
    PP_DEBUG_OUTLINE = 1,  ///< a straight run of a body's solid-pixel boundary
    PP_DEBUG_AABB = 2,     ///< a side of a body's world bounds
    PP_DEBUG_CONTACT = 3,  ///< half of the cross at a contact point
    PP_DEBUG_NORMAL = 4,   ///< a contact's normal, from its point
    PP_DEBUG_JOINT = 5,    ///< anchor to anchor, or a body's centre of mass to its anchor
    PP_DEBUG_CENTER = 6,   ///< a body's bitmap x or y axis from its centre of mass
    PP_DEBUG_VELOCITY = 7, ///< a body's velocity from its centre of mass
    PP_DEBUG_KIND_FORCE_U32 = 0x7fffffff
} pp_debug_kind;

/// One line segment to draw.
typedef struct pp_debug_segment {
    pp_vec2 a;          ///< start, world px
    pp_vec2 b;          ///< end, world px
    uint32_t rgba;      ///< colour, 0xRRGGBBAA
    pp_debug_kind kind; ///< what it shows
    pp_body body;       ///< the body it belongs to; zero for the static world
} pp_debug_segment;

/// pp_world_debug_draw flag: each body's solid-pixel boundary, on the pixel squares' edges.
#define PP_DEBUG_DRAW_OUTLINES (1u << 0)
/// pp_world_debug_draw flag: each body's world bounds.
#define PP_DEBUG_DRAW_AABBS (1u << 1)
/// pp_world_debug_draw flag: a cross at each contact point and its normal.
#define PP_DEBUG_DRAW_CONTACTS (1u << 2)
/// pp_world_debug_draw flag: anchor to anchor, and each anchor to its body's centre of mass.
#define PP_DEBUG_DRAW_JOINTS (1u << 3)
/// pp_world_debug_draw flag: the centre of mass with the body's axes.
#define PP_DEBUG_DRAW_CENTERS (1u << 4)
/// pp_world_debug_draw flag: each moving body's velocity.
#define PP_DEBUG_DRAW_VELOCITIES (1u << 5)
/// Every pp_world_debug_draw flag; other bits are PP_ERR_INVALID_ARGUMENT.
#define PP_DEBUG_DRAW_ALL 0x3fu

/// Half the width of a contact's cross, px.
#define PP_DEBUG_CROSS_SIZE 3.0f
/// Length of a drawn contact normal, px.
#define PP_DEBUG_NORMAL_LENGTH 12.0f
/// Length of a drawn body axis, px.
#define PP_DEBUG_AXIS_LENGTH 10.0f
/// A velocity is drawn as the distance it covers in this time, s.
#define PP_DEBUG_VELOCITY_TIME 0.1f

/// Outline and AABB colour of a sensor body (pale yellow), 0xRRGGBBAA.
#define PP_DEBUG_COLOR_SENSOR 0xE6E64CFFu
/// Outline and AABB colour of a static body (pale green).
#define PP_DEBUG_COLOR_STATIC 0x7FE57FFFu
/// Outline and AABB colour of a dynamic or kinematic body asleep (grey).
#define PP_DEBUG_COLOR_ASLEEP 0x999999FFu
/// Outline and AABB colour of an awake kinematic body (blue).
#define PP_DEBUG_COLOR_KINEMATIC 0x7F7FE5FFu
/// Outline and AABB colour of an awake dynamic body (pink).
#define PP_DEBUG_COLOR_AWAKE 0xE5B2B2FFu
/// Colour of a contact's cross (red).
#define PP_DEBUG_COLOR_CONTACT 0xFF3333FFu
/// Colour of a contact's normal (orange).
#define PP_DEBUG_COLOR_NORMAL 0xFFA500FFu
/// Colour of a joint's segments (cyan).
#define PP_DEBUG_COLOR_JOINT 0x4CE5E5FFu
/// Colour of a body's bitmap x axis (red).
#define PP_DEBUG_COLOR_AXIS_X 0xE53333FFu
/// Colour of a body's bitmap y axis (green).
#define PP_DEBUG_COLOR_AXIS_Y 0x33E533FFu
/// Colour of a velocity (yellow).
#define PP_DEBUG_COLOR_VELOCITY 0xFFFF33FFu

/// Write up to capacity segments (flags: PP_DEBUG_DRAW_* bits) of what meets the world box [lower, upper] (px),
/// in the order above; count receives the total even when capacity is short.
PP_API pp_status pp_world_debug_draw(pp_world w, uint32_t flags, pp_vec2 lower, pp_vec2 upper, pp_debug_segment *out,
                                     int32_t capacity, int32_t *count);

/* ---- Edits: erase, paint, write and read pixels, timed edits ---- */

/* Edits change pixels between steps, and the next step sees them. The mass sums and the solid bounds follow
 * from the changed pixels alone; the pivot stays put and the body moves to its new centre of mass with the
 * velocity its material had; bodies around the edit wake. A dynamic body cut into several 8-connected
 * islands (pixels touching at a corner hold together) splits, and a static one only with detach_islands;
 * a body left without pixels is destroyed (PP_EVENT_BODY_SPLIT, PP_EVENT_BODY_DESTROYED). A circle changes
 * the pixels whose centres lie within its radius. */

/// Erase the body's pixels whose centres lie within radius (px, finite, ≥ 0) of a world point (px, finite);
/// changed receives how many (may be NULL).
PP_API pp_status pp_body_erase_circle(pp_world w, pp_body b, pp_vec2 world_center, float radius, int32_t *changed);
/// Erase every body's pixels within radius (px, finite, ≥ 0) of a world point (px, finite);
/// changed receives the pixels erased (may be NULL).
PP_API pp_status pp_world_erase_circle(pp_world w, pp_vec2 world_center, float radius, int32_t *changed);

/// pp_explosion_def_default's impulse_per_length, mass·px/s per px: a full-strength blast sends a 20 px square crate
/// of density 1 off at 250 px/s (a square's speed is impulse_per_length / its side).
#define PP_EXPLOSION_IMPULSE_PER_LENGTH 5000.0f

/// An explosion (pp_world_explode): an erase, then one impulse on each dynamic body near it, Box2D v3's rule on
/// pixels.
typedef struct pp_explosion_def {
    uint32_t struct_size;      ///< set by pp_explosion_def_default
    pp_vec2 position;          ///< centre, world px
    float radius;              ///< px, finite, ≥ 0: full strength within this distance
    float falloff;             ///< px, finite, ≥ 0: strength falls linearly to 0 from radius to radius + falloff
    float impulse_per_length;  ///< mass·px/s for each px of a body's solid extent across the blast, finite, ≥ 0
    float erase_radius;        ///< px, finite, ≥ 0: first erase the pixels within it as pp_world_erase_circle (0: none)
    uint32_t mask_bits;        ///< bodies whose category_bits meet it are pushed (default all)
    uint32_t erase_mask_bits;  ///< bodies whose category_bits meet it are erased (default all)
} pp_explosion_def;

/// Defaults: at the origin, radius, falloff and erase 0, PP_EXPLOSION_IMPULSE_PER_LENGTH, every category pushed and
/// erased.
PP_API pp_explosion_def pp_explosion_def_default(void);
/// Erase (pieces split off included), then give every dynamic body whose category meets mask_bits with a solid
/// pixel within radius + falloff of position one impulse (mass·px/s) at its pixel nearest to position, from
/// position toward it: impulse_per_length × L × s, L the body's solid extent across that direction (px), s 1 up
/// to radius and linear to 0 at radius + falloff by the distance to that pixel's square; pushed bodies wake, and a
/// push that would pass PP_MAX_SPEED or PP_MAX_ANGULAR_SPEED is scaled down to it. changed receives the pixels
/// erased (may be NULL).
PP_API pp_status pp_world_explode(pp_world w, const pp_explosion_def *def, int32_t *changed);

/// Make solid, with weight 1..255, the pixels whose centres lie within radius (px, finite, ≥ 0) of a world point
/// (px, finite); changed receives how many changed.
PP_API pp_status pp_body_paint_circle(pp_world w, pp_body b, pp_vec2 world_center, float radius, uint8_t weight,
                                      int32_t *changed);
/// Overwrite a width×height rectangle at bitmap pixel (x, y): mask bytes non-zero are solid, weights (may be NULL: 255)
/// 0..255; the part outside the bitmap is clipped. Rows are `width` bytes apart.
PP_API pp_status pp_body_write_pixels(pp_world w, pp_body b, int32_t x, int32_t y, int32_t width, int32_t height,
                                      const uint8_t *mask, const uint8_t *weights);
/// Copy the collision mask, one byte per pixel (1 solid, 0 empty), rows top to bottom; capacity in bytes ≥ width·height.
PP_API pp_status pp_body_read_mask(pp_world w, pp_body b, uint8_t *out, int64_t capacity);
/// Copy the weight plane, one byte per pixel (0..255 relative mass; 255 where solid without a plane, 0 where empty),
/// rows top to bottom; capacity in bytes ≥ width·height.
PP_API pp_status pp_body_read_weights(pp_world w, pp_body b, uint8_t *out, int64_t capacity);
/// Copy the body's look as RGBA8 rows: the sprite where solid, transparent where not; without a sprite, solid
/// pixels are opaque gray of their weight. Capacity in bytes ≥ width·height·4.
PP_API pp_status pp_body_read_rgba(pp_world w, pp_body b, uint8_t *out, int64_t capacity);

/// What a timed edit does.
typedef enum pp_edit_type {
    PP_EDIT_ERASE_CIRCLE = 1, ///< erase pixels within the circle (one body, or every body when `body` is zero)
    PP_EDIT_PAINT_CIRCLE = 2, ///< make pixels within the circle solid with `weight` (one body)
    PP_EDIT_TYPE_FORCE_U32 = 0x7fffffff
} pp_edit_type;

/// An edit the world applies by itself at the start of the step nearest `time` (the first starting after time − dt/2).
typedef struct pp_timed_edit {
    double time;       ///< world time at which it applies, s, finite
    pp_edit_type type; ///< erase or paint
    uint32_t weight;   ///< PAINT: weight of the painted pixels, 1..255; ERASE: ignored
    pp_body body;      ///< the body edited; zero for ERASE means every body
    pp_vec2 center;    ///< world point, px
    float radius;      ///< circle radius, px, ≥ 0
    uint32_t reserved; ///< zero
} pp_timed_edit;

/// Schedule an edit at a world time, s; edits due at once apply at the start of the next step, in time order.
PP_API pp_status pp_world_schedule_edit(pp_world w, const pp_timed_edit *edit);
/// Write up to capacity edits still pending, in the order they will apply; count receives the total.
PP_API pp_status pp_world_get_scheduled_edits(pp_world w, pp_timed_edit *out, int32_t capacity, int32_t *count);

/* ---- Files: PNG images, scene files, snapshots ---- */

/* PNG in and out, through libpng. Loading accepts gray, gray+alpha, RGB, RGBA and palette images of 1–16 bits,
 * all converted to RGBA8. A header declaring more than the bitmap limits gets PP_ERR_LIMIT before anything is
 * allocated; a truncated file or a bad CRC gets PP_ERR_FORMAT with libpng's reason. Only a regular file is
 * read: a FIFO or a device gets PP_ERR_IO ("not a regular file") at once, never a wait. */

/// Size of a PNG file's image, px, read from its header without decoding; either pointer may be NULL.
PP_API pp_status pp_image_info(const char *path, int32_t *width, int32_t *height);
/// Decode a PNG file (gray, gray+alpha, RGB, RGBA, palette, 1 to 16 bits) into RGBA8 rows top to bottom;
/// capacity in bytes ≥ width·height·4; width and height receive the size, px, even when capacity is short.
PP_API pp_status pp_image_load(const char *path, uint8_t *out_rgba, int64_t capacity, int32_t *width, int32_t *height);

/// Encode RGBA8 rows (top to bottom, width·4 bytes apart) as a PNG file; sizes up to the bitmap limits.
PP_API pp_status pp_image_save(const char *path, const uint8_t *rgba, int32_t width, int32_t height);

/* Scene files. One JSON object; every key is optional and takes the default of pp_world_def_default(),
 * pp_body_def_default() or the default camera, but each body needs a bitmap. Keys are case-sensitive; an
 * unknown key or a key given twice is an error (it catches typos).
 *
 *   { "world":  { "preset": "balanced", "gravity": [0, 980], "substeps": 4, "backend": "cpu" },
 *     "camera": { "center": [480, 270], "zoom": 1, "width": 960, "height": 540 },
 *     "bodies": [ { "name": "terrain", "type": "static", "sprite": "terrain.png", "mask": "terrain_mask.png",
 *                   "position": [480, 400], "detach_islands": true },
 *                 { "name": "crate", "box": [32, 32], "position": [480, 300], "density": 2 } ],
 *     "joints": [ { "type": "revolute", "body_b": "crate", "anchor_a": [480, 290], "break_force": 1e6 } ],
 *     "edits":  [ { "time": 1.0, "type": "erase", "center": [500, 420], "radius": 40 },
 *                 { "time": 2.0, "type": "paint", "body": "terrain", "center": [500, 420], "radius": 10,
 *                   "weight": 255 } ] }
 *
 * "world":  every pp_world_def field but struct_size, by name, with its unit, default and range: vectors
 *           as [x, y], flags as true/false, enums as lower-case strings ("backend" auto|cpu|gpu,
 *           "normal_method" area_gradient|kernel, "contact_mode" manifold|centroid); and "preset"
 *           fast|balanced|accurate (default "balanced"), the starting values that the other keys override.
 * "camera": the pp_camera fields.
 * "bodies": created in file order. Every pp_body_def field by name but struct_size, custom_pivot and the
 *           bitmap's (width, height, rgba, mask, weights): "type" is dynamic|static|kinematic, "pivot" is in
 *           bitmap px (the bitmap centre when absent), "category_bits" and "mask_bits" are integers
 *           0..4294967295, "user_data" an integer 0..2^53. Plus "name" (unique; edits name bodies by it) and
 *           the bitmap: "sprite" (a PNG, solid where alpha ≥ alpha_threshold unless there is a mask), "mask"
 *           (a PNG of the same size, solid where red ≥ 128 and alpha ≥ 128), "weights" (a PNG of the same
 *           size, red is each pixel's weight 0..255; default all 255), or "box": [w, h] (integers, px: a
 *           solid rectangle; not with "sprite" or "mask").
 * "joints": created in file order, after the bodies: "type" (required) revolute|prismatic|distance|weld|mouse|
 *           wheel|motor,
 *           "body_a" and "body_b" (bodies' names; absent is the static world), and every other pp_joint_def
 *           field by name (anchors and axis as [x, y] world px, flags as true/false, "user_data" 0..2^53).
 * "edits":  pp_timed_edit's fields: "time" (s of world time, ≥ 0, default 0), "type" erase|paint (default
 *           erase), "body" (a body's name; default every body; required for paint), "center" (world px),
 *           "radius" (px; pixels whose centres lie within change), "weight" (1..255, default 255; paint only).
 *           They apply at the start of the step nearest their time, in time order (file order among equal
 *           times).
 * PNG paths are relative to the scene file's folder and read only from inside it: an absolute path, a ".."
 * component or a symlink leading outside (a symlink that stays inside is followed) is refused with PP_ERR_IO
 * and the message a missing file gets, "cannot open '<path>': missing, unreadable, not a regular file, or
 * outside '<folder>/'", whatever the reason, so that a scene from a mod or a download cannot probe other
 * paths. Only regular files are read, the scene file too: a FIFO or a device is refused at once. On failure
 * nothing is created, *out is untouched, and pp_last_error() names the file and the JSON path of the fault, e.g.
 *   pp_world_load_scene: 'scenes/a.json': bodies[3].density: expected a number > 0
 *   pp_world_load_scene: 'scenes/a.json': bodies[2].densty: unknown key
 *   pp_world_load_scene: 'scenes/a.json': edits[1].body: no body is named 'nobody'
 *   pp_world_load_scene: 'scenes/a.json': line 4: invalid JSON
 * Statuses: PP_ERR_INVALID_ARGUMENT (NULL path or out), PP_ERR_IO (the file cannot be read), PP_ERR_LIMIT
 * (a file over PP_MAX_SCENE_BYTES, a bitmap over the limits), PP_ERR_FORMAT (bad JSON or a bad field), a
 * PNG's own status under its JSON path, PP_ERR_UNSUPPORTED ("backend": "gpu" without a GPU). */

/// Create a world from a JSON scene file (format above); PNG paths are read only from inside the file's folder.
PP_API pp_status pp_world_load_scene(const char *path, pp_world *out);

/* Snapshots. A snapshot is a folder: world.json (settings, camera, clock, pending timed edits and events, the
 * body slot tables, per body its settings, handle, creation order, pose, ODE state and sleep timer, and the joints
 * with their slot table, settings and the poses their ODE joints were attached at, every
 * double printed so that it reads back bit for bit) and each body's planes as PNG (body<slot>_mask.png,
 * body<slot>_weights.png, body<slot>_sprite.png). It is written into a temporary folder beside the target,
 * flushed and renamed into place (or swapped with an older snapshot, which is then removed whole, subfolders
 * too), so a reader or a crash sees the old snapshot or the new one, never half of one. Every step goes
 * through the parent folder's descriptor and never follows a symlink at the target, the temporary or the old
 * folder: a target that is a symlink, or anything but a folder holding world.json, is refused as not a
 * snapshot, and one swapped for something else during the save is put back and the save fails (PP_ERR_IO),
 * so nothing outside the snapshot is ever written or removed. Loading reads world.json and the planes only
 * from inside the folder and only regular files, as pp_world_load_scene reads PNGs. A loaded world continues
 * with the same determinism hash as the original. Its bodies keep their slots and generations:
 * pp_world_get_bodies lists them in the same order, and each handle differs from the saved world's only in
 * the bits that name the world (a handle of the saved world is PP_ERR_INVALID_HANDLE in the loaded one). The
 * last step's contacts are not saved (the next step makes them); the pairs touching at the last substep are,
 * with the points of their last solve (a sleeping pile lists its contacts as soon as it is loaded),
 * so a loaded world does not report resting contacts as begun again and a body halfway through a one-way
 * platform is not stopped inside it, and so are the resting pairs held from step to step with their contacts
 * ("held"), which the loaded world carries uncollided as the saved one would. A world holding a number that is not finite, or past ±FLT_MAX (which
 * the loader refuses), is refused with PP_ERR_LIMIT before anything is written. */

/// Write the whole state of a world into a new folder (world.json and PNG planes), atomically by rename.
PP_API pp_status pp_world_save_snapshot(pp_world w, const char *folder);
/// Create a world from a snapshot folder; stepping it continues exactly as the saved world would have.
PP_API pp_status pp_world_load_snapshot(const char *folder, pp_world *out);

/* World state in memory, for rollback and undo: the whole world as bytes (bodies and their pixels, joints, the
 * touching and held pairs, sleep, scheduled edits, events not yet read, time, the solver's step count), read only
 * by this build of the library. The bytes carry a format version, the saving world's id and a checksum: bytes
 * that were changed, cut short or come from another build are PP_ERR_FORMAT, and so are bytes with a right
 * checksum whose values no world holds (a peer's bug); bytes of another world are PP_ERR_INVALID_ARGUMENT, settings
 * asking for a GPU where there is none PP_ERR_UNSUPPORTED, and in every case the world is unchanged. Bytes a world
 * saved itself carry its seal (a keyed hash of their checksum, keyed by a value of the world's that no bytes hold):
 * restored into it unchanged, they skip those value checks, so rollback pays a copy and a checksum. A restore
 * copies the saved records back over the live ones (a body's pixels only when they changed since), and builds the
 * saved world apart and swaps it in only when bodies or joints were made, destroyed or retyped since the save, or
 * the bytes hold other world settings than those it was made with. A body of 65536 pixels or more (a terrain) is
 * kept once by the world at its first save, and its states hold only the bands of 8 rows changed since: such bytes
 * load into a new world (pp_world_load_state) only while the world that saved them exists, and not while another
 * thread changes it (else PP_ERR_INVALID_ARGUMENT). The camera is not part of the state. */

/// Save the world into buffer (capacity bytes); *size receives the bytes needed, PP_ERR_LIMIT when they do not fit.
PP_API pp_status pp_world_save_state(pp_world w, void *buffer, int64_t capacity, int64_t *size);
/// Put w back as it was when it saved the bytes (size bytes): handles live then are valid, later ones stale.
PP_API pp_status pp_world_restore_state(pp_world w, const void *buffer, int64_t size);
/// Create a new world from saved state bytes (size bytes); it continues exactly as the saved world would have.
PP_API pp_status pp_world_load_state(const void *buffer, int64_t size, pp_world *out);
/// 64 bits over everything the next steps depend on: equal hashes, equal futures, on either backend, in any run.
PP_API pp_status pp_world_get_hash(pp_world w, uint64_t *out);

#ifdef __cplusplus
}
#endif

#endif /* PHYSPIX_H */
