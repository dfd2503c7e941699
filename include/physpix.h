/* PhysPix — 2D rigid bodies whose shapes are bitmaps used as they are.
 * The public C ABI: value handles, status codes, def structs with a struct_size.
 * Units everywhere: pixels, seconds, radians; world y points down. */
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

/// Library major version (the soname carries it).
#define PHYSPIX_VERSION_MAJOR 0
/// Library minor version.
#define PHYSPIX_VERSION_MINOR 2
/// Library patch version.
#define PHYSPIX_VERSION_PATCH 0

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

/// Result of every call that can fail; PP_OK is 0.
typedef enum pp_status {
    PP_OK = 0,                   ///< success
    PP_ERR_INVALID_ARGUMENT = 1, ///< NULL, NaN, out-of-range or inconsistent argument
    PP_ERR_INVALID_HANDLE = 2,   ///< a null, destroyed or stale world or body handle
    PP_ERR_OUT_OF_MEMORY = 3,    ///< an allocation failed; nothing was changed
    PP_ERR_IO = 4,               ///< a file could not be read or written
    PP_ERR_FORMAT = 5,           ///< a file's contents are malformed
    PP_ERR_UNSUPPORTED = 6,      ///< the feature is not available here (e.g. no GPU)
    PP_ERR_LIMIT = 7,            ///< a size over the documented PP_MAX_* limits
    PP_ERR_ABI = 8,              ///< a def struct whose struct_size does not match this library
    PP_STATUS_FORCE_U32 = 0x7fffffff
} pp_status;

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

/// A named point on the measured speed/accuracy trade (README, "Presets").
typedef enum pp_preset {
    PP_PRESET_FAST = 1,     ///< 1 substep × 10 iterations: 7.5 times cheaper, same contact errors; tall stacks fall
    PP_PRESET_BALANCED = 2, ///< the default, 4 substeps × 40 iterations: meets DESIGN.md's accuracy targets
    PP_PRESET_ACCURATE = 3, ///< 4 substeps × 80 iterations: the stiffest stacks measured, at 1.7 times the cost
    PP_PRESET_FORCE_U32 = 0x7fffffff
} pp_preset;

/// How a body moves.
typedef enum pp_body_type {
    PP_BODY_DYNAMIC = 0,   ///< moved by forces and contacts
    PP_BODY_STATIC = 1,    ///< never moves; no mass, no ODE body
    PP_BODY_KINEMATIC = 2, ///< moved only by its velocity; pushes dynamic bodies, is never pushed
    PP_BODY_FORCE_U32 = 0x7fffffff
} pp_body_type;

/// A 2D vector in pixels (or pixels per second, per the call).
typedef struct pp_vec2 {
    float x; ///< x component, pixels
    float y; ///< y component, pixels (down is positive)
} pp_vec2;

/// A world handle; id 0 is never valid.
typedef struct pp_world {
    uint64_t id; ///< slot index and generation; opaque
} pp_world;

/// A body handle; id 0 is never valid.
typedef struct pp_body {
    uint64_t id; ///< slot index and generation; opaque
} pp_body;

/// Settings of a world; fill from pp_world_def_default(). Zero in substeps, solver_iterations or raster_stride means its default.
typedef struct pp_world_def {
    uint32_t struct_size;           ///< sizeof(pp_world_def), set by pp_world_def_default
    pp_vec2 gravity;                ///< acceleration, px/s² (default 0, 980)
    int32_t substeps;               ///< solver steps per pp_world_step, 1..64 (default 4)
    int32_t solver_iterations;      ///< QuickStep iterations, 1..1000 (default 40)
    uint32_t exact_solver;          ///< nonzero: ODE's exact dWorldStep instead of QuickStep
    pp_backend backend;             ///< collision backend (default AUTO)
    pp_normal_method normal_method; ///< contact normal estimator (default AREA_GRADIENT)
    pp_contact_mode contact_mode;   ///< contact points per pair (default MANIFOLD)
    int32_t raster_stride;          ///< collision grid coarsening: 1, 2 or 4 pixels per sample (default 1)
    float pixels_per_meter;         ///< internal length scale handed to ODE, px/m (default 100)
    float contact_slop;             ///< penetration left uncorrected, px (default 0.75)
    float contact_erp;              ///< fraction of penetration corrected per solver step, 0..1 (default 0.2)
    float contact_cfm;              ///< contact softness, ODE constraint force mixing, non-dimensional (default 1e-5)
    float bounce_threshold;         ///< approach speed below which restitution is ignored, px/s (default 20)
    uint32_t allow_sleep;           ///< nonzero: resting bodies are put to sleep (default 1)
    float sleep_linear_speed;       ///< speed under which a body may sleep, px/s (default 5)
    float sleep_angular_speed;      ///< angular speed under which a body may sleep, rad/s (default 0.1)
    float sleep_time;               ///< time a body must stay slow before it sleeps, s (default 0.5)
    uint32_t continuous;            ///< nonzero: a dynamic body moving over half its thickness in a substep is swept
                                    ///< against static and kinematic bodies and stopped where it first hits (default 1)
    float max_correction_speed;     ///< fastest that contacts push overlapping bodies apart, px/s, > 0 (default 300)
    int32_t worker_threads;         ///< threads the CPU narrowphase may use, 1..16, or 0 for one per CPU (default 0);
                                    ///< started only when a step's pairs are big enough to need them
    uint32_t contact_events;        ///< nonzero: PP_EVENT_CONTACT_BEGIN/END are queued for pp_world_get_events (default 0)
} pp_world_def;

/// Settings of a body; fill from pp_body_def_default(). The library copies the bitmap planes.
typedef struct pp_body_def {
    uint32_t struct_size;     ///< sizeof(pp_body_def), set by pp_body_def_default
    pp_body_type type;        ///< dynamic, static or kinematic (default DYNAMIC)
    pp_vec2 position;         ///< world position of the pivot, px
    float angle;              ///< rotation, radians (positive turns +x toward +y)
    uint32_t custom_pivot;    ///< nonzero: use `pivot`; zero: the pivot is the bitmap centre
    pp_vec2 pivot;            ///< pivot in bitmap coordinates (origin at the top-left corner), px
    pp_vec2 linear_velocity;  ///< initial velocity of the centre of mass, px/s
    float angular_velocity;   ///< initial angular velocity, rad/s
    float density;            ///< mass of one solid pixel of weight 255, mass units (default 1)
    float friction;           ///< Coulomb coefficient, ≥ 0 (default 0.6); pairs use sqrt(fa·fb)
    float restitution;        ///< bounciness 0..1 (default 0); pairs use max(ra, rb)
    float linear_damping;     ///< velocity decay, 1/s (default 0)
    float angular_damping;    ///< angular velocity decay, 1/s (default 0)
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

/// What an event reports.
typedef enum pp_event_type {
    PP_EVENT_BODY_SPLIT = 1,     ///< an edit cut `body` apart; `other` is a new body made of one of its islands
    PP_EVENT_BODY_DESTROYED = 2, ///< an edit left `body` without solid pixels; the handle is now stale
    PP_EVENT_CONTACT_BEGIN = 3,  ///< `body` and `other` started touching (worlds with contact_events only)
    PP_EVENT_CONTACT_END = 4,    ///< `body` and `other` stopped touching, or one of them was destroyed
    PP_EVENT_SENSOR_BEGIN = 5,   ///< `other` started overlapping the sensor `body`
    PP_EVENT_SENSOR_END = 6,     ///< `other` stopped overlapping the sensor `body`, or one of them was destroyed
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
} pp_event;

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

/// What the last pp_world_step did and what it cost.
typedef struct pp_step_stats {
    float broadphase_ms;   ///< candidate-pair search, milliseconds (all substeps)
    float narrowphase_ms;  ///< raster collision, milliseconds (all substeps)
    float solver_ms;       ///< ODE, milliseconds (all substeps)
    float total_ms;        ///< the whole step, milliseconds
    int32_t bodies;        ///< live bodies
    int32_t awake_bodies;  ///< dynamic or kinematic bodies not asleep
    int32_t pairs;         ///< candidate pairs tested in the last substep
    int32_t contacts;      ///< contact points made in the last substep
    int64_t pixels_tested; ///< raster samples tested (all substeps)
    pp_backend backend;    ///< the backend that ran the narrowphase (CPU or GPU)
    uint32_t swept_stops;  ///< times continuous collision stopped a fast body at a wall (all substeps)
    int32_t threads;       ///< threads that ran the last substep's CPU narrowphase, the calling one included
                           ///< (1: it alone; 0: the narrowphase ran on the GPU or had no pairs)
} pp_step_stats;

/// Log hook: level 0 debug, 1 info, 2 warning, 3 error; msg is valid during the call only.
typedef void (*pp_log_fn)(int level, const char *msg, void *user);

/// The memory functions behind every allocation the library makes; sizes in bytes, never 0.
typedef struct pp_allocator {
    void *(*alloc)(uint64_t size, void *user);              ///< like malloc: NULL when out of memory
    void *(*realloc)(void *ptr, uint64_t size, void *user); ///< like realloc: ptr from alloc or realloc
    void (*free)(void *ptr, void *user);                    ///< like free; ptr is never NULL
    void *user;                                             ///< passed back to every call
} pp_allocator;

/// A renderer's view of a world: the world point at the image centre, the scale and the image size.
typedef struct pp_camera {
    pp_vec2 center; ///< world point shown at the image centre, px (default 480, 270)
    float zoom;     ///< image pixels per world pixel, > 0 (default 1)
    int32_t width;  ///< image width, image px, 1..PP_MAX_BITMAP_SIDE (default 960)
    int32_t height; ///< image height, image px, 1..PP_MAX_BITMAP_SIDE (default 540)
} pp_camera;

/// What a timed edit does.
typedef enum pp_edit_type {
    PP_EDIT_ERASE_CIRCLE = 1, ///< erase pixels within the circle (one body, or every body when `body` is zero)
    PP_EDIT_PAINT_CIRCLE = 2, ///< make pixels within the circle solid with `weight` (one body)
    PP_EDIT_TYPE_FORCE_U32 = 0x7fffffff
} pp_edit_type;

/// An edit the world applies by itself at the start of the step nearest `time` (the first starting after time − dt/2).
typedef struct pp_timed_edit {
    double time;       ///< world time at which it applies, s
    pp_edit_type type; ///< erase or paint
    uint32_t weight;   ///< PAINT: weight of the painted pixels, 1..255; ERASE: ignored
    pp_body body;      ///< the body edited; zero for ERASE means every body
    pp_vec2 center;    ///< world point, px
    float radius;      ///< circle radius, px, ≥ 0
    uint32_t reserved; ///< zero
} pp_timed_edit;

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

/// Default world settings (the balanced preset).
PP_API pp_world_def pp_world_def_default(void);
/// The settings of a preset; an unknown preset gives struct_size 0, which pp_world_create refuses (PP_ERR_ABI).
PP_API pp_world_def pp_world_def_preset(pp_preset preset);
/// Create a world from a def.
PP_API pp_status pp_world_create(const pp_world_def *def, pp_world *out);
/// The settings the world runs with: its def, with zero counts replaced by their defaults.
PP_API pp_status pp_world_get_def(pp_world w, pp_world_def *out);
/// Switch CONTACT_BEGIN/END events on (nonzero) or off, as pp_world_def.contact_events; pairs already touching
/// when they go on begin at the next substep.
PP_API pp_status pp_world_set_contact_events(pp_world w, uint32_t enabled);
/// Destroy a world and all its bodies; the handle becomes stale.
PP_API pp_status pp_world_destroy(pp_world w);
/// Advance the world by dt seconds (0 < dt ≤ 1), in `substeps` solver steps.
PP_API pp_status pp_world_step(pp_world w, float dt);
/// Write up to capacity live body handles; count receives the total.
PP_API pp_status pp_world_get_bodies(pp_world w, pp_body *out, int32_t capacity, int32_t *count);
/// Write up to capacity contacts of the last substep; count receives the total.
PP_API pp_status pp_world_get_contacts(pp_world w, pp_contact *out, int32_t capacity, int32_t *count);
/// Statistics of the last step.
PP_API pp_status pp_world_get_stats(pp_world w, pp_step_stats *out);
/// Write up to capacity events that happened since they were last read, oldest first, and forget those
/// written; count receives how many were pending (capacity 0 only counts them).
PP_API pp_status pp_world_get_events(pp_world w, pp_event *out, int32_t capacity, int32_t *count);
/// Erase every body's pixels within radius (px) of a world point (px); changed receives the pixels erased (may be NULL).
PP_API pp_status pp_world_erase_circle(pp_world w, pp_vec2 world_center, float radius, int32_t *changed);
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
/// Run the narrowphase on one pair at the current poses, without stepping; count receives the total.
PP_API pp_status pp_world_collide(pp_world w, pp_body a, pp_body b, pp_contact *out, int32_t capacity,
                                  int32_t *count);

/// Default body settings: a dynamic body with no bitmap yet.
PP_API pp_body_def pp_body_def_default(void);
/// Create a body from a def; the bitmap planes are copied.
PP_API pp_status pp_body_create(pp_world w, const pp_body_def *def, pp_body *out);
/// Destroy a body; its handle becomes stale.
PP_API pp_status pp_body_destroy(pp_world w, pp_body b);
/// World position of the body's pivot, px.
PP_API pp_status pp_body_get_position(pp_world w, pp_body b, pp_vec2 *out);
/// Rotation of the body, radians.
PP_API pp_status pp_body_get_angle(pp_world w, pp_body b, float *out);
/// Teleport the body: pivot to position (px), rotation to angle (radians); wakes it.
PP_API pp_status pp_body_set_transform(pp_world w, pp_body b, pp_vec2 position, float angle);
/// Velocity of the centre of mass (px/s) and angular velocity (rad/s); either pointer may be NULL.
PP_API pp_status pp_body_get_velocity(pp_world w, pp_body b, pp_vec2 *linear, float *angular);
/// Set the velocity of the centre of mass (px/s) and angular velocity (rad/s); wakes it.
PP_API pp_status pp_body_set_velocity(pp_world w, pp_body b, pp_vec2 linear, float angular);
/// Apply an impulse (mass·px/s) at a world point (px); wakes the body. Dynamic bodies only.
PP_API pp_status pp_body_apply_impulse(pp_world w, pp_body b, pp_vec2 impulse, pp_vec2 world_point);
/// Mass (mass units), centre of mass in bitmap coordinates (px) and inertia about it (mass·px²); any pointer may be NULL.
PP_API pp_status pp_body_get_mass(pp_world w, pp_body b, float *mass, pp_vec2 *local_center, float *inertia);
/// Memory the body holds, bytes: its collision raster (1-bit mask, tile, row and column counts, and an 8-bit
/// weight plane only if it has weights) and its sprite copy (4 bytes a pixel; 0 without a sprite); either may be NULL.
PP_API pp_status pp_body_get_memory(pp_world w, pp_body b, int64_t *collision_bytes, int64_t *sprite_bytes);
/// Whether the body is awake (1) or asleep (0); static bodies are never awake.
PP_API pp_status pp_body_is_awake(pp_world w, pp_body b, int32_t *awake);
/// Erase the body's pixels whose centres lie within radius (px) of a world point (px); changed receives how many (may be NULL).
PP_API pp_status pp_body_erase_circle(pp_world w, pp_body b, pp_vec2 world_center, float radius, int32_t *changed);
/// Make solid, with weight 1..255, the pixels whose centres lie within radius (px) of a world point (px); changed receives how many changed.
PP_API pp_status pp_body_paint_circle(pp_world w, pp_body b, pp_vec2 world_center, float radius, uint8_t weight,
                                      int32_t *changed);
/// Overwrite a width×height rectangle at bitmap pixel (x, y): mask bytes non-zero are solid, weights (may be NULL: 255)
/// 0..255; the part outside the bitmap is clipped. Rows are `width` bytes apart.
PP_API pp_status pp_body_write_pixels(pp_world w, pp_body b, int32_t x, int32_t y, int32_t width, int32_t height,
                                      const uint8_t *mask, const uint8_t *weights);
/// Copy the collision mask, one byte per pixel (1 solid, 0 empty), rows top to bottom; capacity in bytes ≥ width·height.
PP_API pp_status pp_body_read_mask(pp_world w, pp_body b, uint8_t *out, int64_t capacity);
/// Bitmap size of the body, px; either pointer may be NULL.
PP_API pp_status pp_body_get_size(pp_world w, pp_body b, int32_t *width, int32_t *height);
/// The host's value given in the body def.
PP_API pp_status pp_body_get_user_data(pp_world w, pp_body b, uint64_t *out);

/// Size of a PNG file's image, px, read from its header without decoding; either pointer may be NULL.
PP_API pp_status pp_image_info(const char *path, int32_t *width, int32_t *height);
/// Decode a PNG file (gray, gray+alpha, RGB, RGBA, palette, 8 or 16 bit) into RGBA8 rows top to bottom;
/// capacity in bytes ≥ width·height·4; width and height receive the size, px, even when capacity is short.
PP_API pp_status pp_image_load(const char *path, uint8_t *out_rgba, int64_t capacity, int32_t *width, int32_t *height);

/// Encode RGBA8 rows (top to bottom, width·4 bytes apart) as a PNG file; sizes up to the bitmap limits.
PP_API pp_status pp_image_save(const char *path, const uint8_t *rgba, int32_t width, int32_t height);

/// Pivot of the body in bitmap coordinates, px.
PP_API pp_status pp_body_get_pivot(pp_world w, pp_body b, pp_vec2 *out);
/// Type of the body (dynamic, static or kinematic).
PP_API pp_status pp_body_get_type(pp_world w, pp_body b, pp_body_type *out);
/// Copy the body's look as RGBA8 rows: the sprite where solid, transparent where not; without a sprite, solid
/// pixels are opaque gray of their weight. Capacity in bytes ≥ width·height·4.
PP_API pp_status pp_body_read_rgba(pp_world w, pp_body b, uint8_t *out, int64_t capacity);

/// Simulated time since the world was created, s (the sum of the dt of every step).
PP_API pp_status pp_world_get_time(pp_world w, double *seconds);
/// The world's camera (a scene file's, or the default).
PP_API pp_status pp_world_get_camera(pp_world w, pp_camera *out);
/// Replace the world's camera.
PP_API pp_status pp_world_set_camera(pp_world w, const pp_camera *camera);
/// Schedule an edit at a world time, s; edits due at once apply at the start of the next step, in time order.
PP_API pp_status pp_world_schedule_edit(pp_world w, const pp_timed_edit *edit);
/// Write up to capacity edits still pending, in the order they will apply; count receives the total.
PP_API pp_status pp_world_get_scheduled_edits(pp_world w, pp_timed_edit *out, int32_t capacity, int32_t *count);
/// Run the narrowphase on a pair and write its sampled grid: cells (PP_CELL_* flags) and, when local_normals is
/// not NULL, each critical cell's 3×3-kernel normal in world axes (zero elsewhere); capacity in cells.
/// The view is filled even when capacity is short (then PP_ERR_INVALID_ARGUMENT and nothing written).
PP_API pp_status pp_world_debug_collision(pp_world w, pp_body a, pp_body b, uint8_t *cells, pp_vec2 *local_normals,
                                          int64_t capacity, pp_collision_view *view);

/// Create a world from a JSON scene file (see README, "Scene files"); PNG paths are relative to the file.
PP_API pp_status pp_world_load_scene(const char *path, pp_world *out);
/// Write the whole state of a world into a new folder (world.json and PNG planes), atomically by rename.
PP_API pp_status pp_world_save_snapshot(pp_world w, const char *folder);
/// Create a world from a snapshot folder; stepping it continues exactly as the saved world would have.
PP_API pp_status pp_world_load_snapshot(const char *folder, pp_world *out);

#ifdef __cplusplus
}
#endif

#endif /* PHYSPIX_H */
