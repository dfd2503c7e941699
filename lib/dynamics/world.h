/* The private world and body records shared by world.c, body.c, query.c and the solver glue. */
#ifndef PP_WORLD_H
#define PP_WORLD_H

#include "backend_auto.h"
#include "broadphase.h"
#include "carry.h"
#include "check.h"
#include "contact_table.h"
#include "crowd.h"
#include "events.h"
#include "handle.h"
#include "id_pool.h"
#include "massprops.h"
#include "math2d.h"
#include "narrow_gpu.h"
#include "narrowphase.h"
#include "raster.h"
#include "solver_ode.h"
#include "step_undo.h"
#include "timed_edits.h"
#include "workers.h"

#include <stdbool.h>
#include <stddef.h>

typedef struct body {
    uint32_t index;          /* slot in the world's body table */
    pp_body handle;
    pp_body_type type;
    pp_raster raster;
    uint8_t *sprite;         /* the def's rgba plane, width × height × 4; NULL without one */
    pp_mass_sums sums;
    pp_mass mass;            /* zero for static bodies */
    double density, friction, restitution, linear_damping, angular_damping;
    uint32_t category_bits, mask_bits;
    bool fixed_rotation;
    bool detach_islands;     /* static: islands cut loose by an edit become dynamic bodies */
    dvec2 pivot;             /* bitmap coordinates, px */
    dvec2 pos;               /* world position of the pivot, px */
    double angle, cos_a, sin_a;
    dvec2 com;               /* world centre of mass, px: body_com_world's, kept with the pose (body_update_com) */
    solver_body sb;          /* the ODE body; empty for static bodies */
    pp_aabb aabb;            /* world bounds of the solid pixels */
    uint64_t user_data;
    uint64_t serial;         /* creation order; a snapshot recreates ODE bodies in it */
    int32_t awake_at;        /* its place in the world's awake set (awake.h), or -1 */
    int32_t changed_at;      /* its place in the awake set's changed list (awake.h), or -1 */
    double slow_time;        /* s the body has stayed under the sleep speeds, at most sleep_time while awake;
                              * sleep_time + 1 while asleep */
    bool bullet;             /* swept against dynamic bodies too */
    bool is_sensor;          /* overlaps make events, never contacts */
    bool one_way;            /* a one-way platform: contacts only from the one_way_dir side */
    dvec2 one_way_dir;       /* unit, bitmap axes */
    dvec2 force;             /* applied since the last step, mass·px/s² (forces.c) … */
    double torque;           /* … and its torque about the centre of mass, mass·px²/s² */
    double gravity_scale;    /* of the world's gravity; 1 by default */
    bool forced;             /* listed in wd->forced.slots: a force, torque or gravity scale acts on it */
    int32_t joint_count;     /* joints attached to it (joint.c) */
    uint64_t sat_out;        /* the substep (wd->islands.substep_serial) its QuickStep island last sat out (island.c) */
    uint8_t behind;          /* substeps in a row it sat out, up to sat_out (island.c) */
    uint64_t pixel_stamp;    /* names its pixels' content in the world (state.c): equal stamps, equal pixels */
    uint64_t stamp_version;  /* the raster version the stamp was given at; a newer one needs a new stamp */
} body;

/* A body's pose at the start of a substep, for continuous collision. */
typedef struct continuous_pose {
    dvec2 com;               /* px */
    double angle;            /* rad */
} continuous_pose;

/* The joints of a world (joint.c): their records by slot of their id pool, as the bodies'. */
typedef struct joint_table {
    struct joint **items;    /* by slot of ids; NULL where free */
    id_pool ids;             /* the joints' slots and generations */
    uint64_t next_attach;    /* the next attach's order: ODE lists a body's joints newest attached first */
} joint_table;

/* How a body's island is solved this substep (island.c): a stack (two or more dynamic bodies) or a lone body,
 * by the exact solver or by QuickStep. */
enum { ISLAND_NONE, ISLAND_EXACT, ISLAND_EXACT_ALONE, ISLAND_QUICK_ALONE, ISLAND_QUICK_STACK };
static inline bool island_exact(int kind) { return kind == ISLAND_EXACT || kind == ISLAND_EXACT_ALONE; }
/* How many substeps of time a body's island advances this substep (island.c): QuickStep islands sit the
 * first substep of a pair out and solve the second with twice its time step; a stack at rest sits three of
 * four out and solves the fourth with four times it. */
enum { SPAN_SKIP = 0, SPAN_ONE = 1, SPAN_TWO = 2, SPAN_FOUR = 4 };

/* The parts of a world each file owns: only its owner writes them; the others read, or call its functions. */

/* An awake mover in the awake set's index: its box's x0 (px) when the index was built, and its slot. */
typedef struct awake_entry {
    double x0;
    int32_t slot;
} awake_entry;

/* The awake set (awake.c). */
typedef struct awake_set {
    int32_t *slots;          /* slots, sorted from each substep's start */
    int32_t count, capacity;
    bool sorted;
    int32_t *changed;        /* listed bodies the index may not show as they are: listed, put to sleep or moved
                              * outside a step since the last refresh */
    int32_t changed_count, changed_capacity;
    struct awake_entry *by_x; /* the index: the awake movers when it was built, by their boxes' x0 */
    int32_t by_x_count, by_x_capacity;
    double by_x_width;       /* the widest of their boxes, px */
    bool by_x_valid;         /* no body moved in a step since it was built */
    int32_t movers;          /* dynamic or kinematic bodies awake at the last broadphase */
    bp_proxy *proxies;       /* the broadphase's view of every slot, refreshed for the set's bodies */
    int32_t proxy_capacity;
    pp_aabb *step_boxes;     /* by slot: an awake mover's box grown over the step (awake_find_pairs) */
    int32_t step_box_capacity;
} awake_set;

/* The substep's narrowphase batch (step.c; crowd.c orders it). */
typedef struct pair_batch {
    np_pair *pairs;          /* the pairs that passed set-up … */
    np_core *cores;          /* … their integer cores … */
    np_result *results;      /* … their contacts … */
    int32_t *bodies;         /* … their bodies' slots, two per pair … */
    int32_t *candidates;     /* … and their broadphase pairs (wd->broad.pairs) */
    int32_t capacity;
} pair_batch;

/* Continuous collision's bodies (continuous.c). */
typedef struct sweep_set {
    continuous_pose *from;   /* by slot: where each swept body started the substep */
    int32_t from_capacity;
    int32_t *slots;          /* the slots continuous_begin recorded, in order */
    int32_t count, capacity;
} sweep_set;

/* Islands and sleep groups (island.c). */
typedef struct island_set {
    int32_t *group;          /* three per slot: union-find parents, each root's rows or restless flag, and its
                              * ROOT_* flags */
    int32_t group_capacity;
    int32_t *root;           /* by slot: a node's island root, found once the plan's islands are whole */
    int32_t root_capacity;
    uint32_t *node_mark;     /* by slot: the island pass that last made it a node */
    int32_t node_mark_capacity;
    uint32_t node_pass;
    int32_t *nodes;          /* the substep's island nodes: awake bodies and contacts' movable bodies */
    int32_t node_count, node_capacity;
    int32_t awake_nodes;     /* nodes [0, awake_nodes) are the awake set's, listed first */
    solver_body **bodies;    /* this substep's islands for solver_step … */
    int32_t bodies_capacity;
    uint8_t *kind;           /* … and by slot, how each body's island is solved (ISLAND_*) */
    int32_t kind_capacity;
    uint8_t *span;           /* … and by slot, the substeps of time it advances (SPAN_*) */
    int32_t span_capacity;
    int8_t *list;            /* by node: the solver list it goes in this substep, or −1 (list_islands' scratch) */
    int32_t list_capacity;
    double *heaviest;        /* by root: its heaviest dynamic body's mass (island_plan's scratch) */
    int32_t heaviest_capacity;
    uint8_t *every;          /* by root, found once a plan: a joint or a hard mass ratio has it solve every substep
                              * (EVERY_SUBSTEP); a slanted face keeps it off a span of four (EVERY_SLANT) */
    int32_t every_capacity;
    int32_t *sleep_group;    /* two per slot: island_sleep's union-find parents and restless flags, apart from
                              * `group` so that a still substep's islands stand */
    int32_t sleep_group_capacity;
    uint64_t substep_serial; /* counts island_plan's calls: which substep a body's sat_out names */
    uint64_t planned;        /* PP_CHECKS: a digest of the contacts and awake set the islands were made from */
} island_set;

/* The bodies with a force, torque or gravity scale (forces.c). */
typedef struct forced_list {
    int32_t *slots;
    int32_t count, capacity;
} forced_list;

/* A big body's planes as the world kept them at its first saved state (lib/io/state.c): its states hold only the
 * bands of rows changed since. Kept until the world goes, so that a state restores the body after it is destroyed. */
typedef struct state_base {
    uint64_t serial;         /* the body's */
    uint64_t *bits;
    uint8_t *weights;        /* NULL: every weight 255 */
    int32_t *rows;           /* solid pixels per row */
    uint8_t *tiles;          /* per tile */
    uint8_t *sprite;         /* NULL without one; it never changes, so states leave it out */
} state_base;

typedef struct world {
    uint32_t slot;
    uint32_t tag;            /* what its bodies' ids carry of it (handle.h) */
    pp_world handle;
    pp_world_def def;
    body **bodies;           /* by slot of body_ids; NULL where free */
    id_pool body_ids;        /* the bodies' slots and generations */
    pp_solver *solver;
    pp_broadphase broad;
    pp_contact *contacts;    /* the last substep's contacts */
    int32_t contact_count, contact_capacity;
    awake_set awake;         /* the bodies a substep visits (awake.c) */
    pair_batch batch;        /* the substep's pairs for the narrowphase (step.c, crowd.c) */
    np_scratch scratch;
    np_workers *workers;     /* NULL until a batch needs more than one thread */
    gpu_narrow *gpu;         /* NULL until the GPU is used (at creation for PP_BACKEND_GPU) */
    bool gpu_tried;          /* AUTO tried to bring the GPU up */
    backend_auto auto_costs; /* AUTO's models of what a batch costs on each backend (backend_auto.h) */
    event_queue events;      /* since the host last read them (events.c) */
    pp_step_stats stats;
    double time;             /* simulated s, the sum of every step's dt */
    timed_edits edits;       /* pending timed edits (timed_edits.c) */
    uint64_t next_serial;    /* the next body's creation serial */
    sweep_set sweeps;          /* continuous collision's swept bodies (continuous.c) */
    island_set islands;        /* the substep's islands and sleep groups (island.c) */
    contact_table table;     /* every touching pair, awake or resting (contact_table.c) */
    step_undo undo;          /* the step transaction (step_undo.c) */
    crowd crowd;             /* the contact budget of crowded bodies (crowd.c) */
    carry carry;             /* the step's first contacts, moved through its later substeps (carry.c) */
    forced_list forced;      /* the bodies a force, torque or gravity scale acts on (forces.c) */
    joint_table joints;
    uint64_t pixel_clock;    /* the last pixel stamp handed out (state.c); never goes back, not even by a restore */
    state_base *bases;       /* big bodies' planes kept for saved states (state.c) */
    uint64_t state_key;      /* the seal's key of the states it saves (state.c): never in the bytes, 0 until a save */
    int32_t base_count, base_capacity;
} world;

/* The root of i's set in a union-find forest of parents, halving the path as it goes. */
static inline int32_t world_group_root(int32_t *parent, int32_t i)
{
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

/* Whether a def's values are valid (count defaults applied); failures name fn. */
pp_status world_check_def(const pp_world_def *d, const char *fn);
/* Make a world from a def (not NULL), failures naming `fn`; world_free takes it and everything in it. */
pp_status world_make(const pp_world_def *def, const char *fn, world **out);
void world_free(world *wd);

/* Look a handle up; on failure record why and return NULL. `fn` names the API call for the message. */
world *world_lookup(pp_world w, const char *fn);
/* The live world of this id, or NULL, recording nothing. */
world *world_find(uint64_t id);
/* Each contact pp_world_get_contacts lists, in its order: the last substep's, then the manifolds the sleeping
 * pairs keep. */
void world_each_contact(const world *wd, void (*visit)(const pp_contact *c, void *user), void *user);

/* The lookup of a call that lists into (out, capacity, count), checked as every list call takes them, or
 * that writes one result through `out` (named out_name in messages); NULL with *st the failure. */
world *world_lookup_list(pp_world w, const char *fn, const void *out, int32_t capacity, const int32_t *count,
                         pp_status *st);
world *world_lookup_out(pp_world w, const char *fn, const void *out, const char *out_name, pp_status *st);
/* The id of the live world whose bodies carry this tag, or 0 (for a message naming a body's world). */
uint64_t world_id_of_tag(uint32_t tag);
body *body_lookup(world *wd, pp_body b, const char *fn);
/* The same lookup without recording a failure: NULL for a null, destroyed or stale handle. */
body *body_find(const world *wd, pp_body b);

/* The body of a handle the world made and knows is live (a contact's, a new split piece's). */
static inline body *body_of(const world *wd, pp_body b)
{
    body *bd = wd->bodies[handle_slot(b.id)];
    PP_ASSERT(bd && bd->handle.id == b.id);
    return bd;
}

/* Both lookups at once, as most body calls need them. */
pp_status world_body_lookup(pp_world w, pp_body b, const char *fn, world **wd, body **bd);

/* body_make's slot for a new body: the next the world's pool hands out. */
#define BODY_ANY_SLOT (-1)
/* Make a body from a def (not NULL) into want_slot (BODY_ANY_SLOT, or a snapshot's restored slot that holds
 * nothing); failures name `fn`, the call the user made. */
pp_status body_make(world *wd, const pp_body_def *def, int64_t want_slot, const char *fn, body **out);

/* The lookup of a body call that writes one result through `out` (named out_name in messages), both
 * checked; NULL with *st the failure. */
body *body_lookup_out(pp_world w, pp_body b, const char *fn, const void *out, const char *out_name, world **wd,
                      pp_status *st);

/* A getter of one value of a world: the lookup and the check of `out`, then *out = value, an expression of wd. */
#define WORLD_GETTER(name, type, value)                                                                          \
    PP_API pp_status name(pp_world w, type *out)                                                                 \
    {                                                                                                            \
        pp_status st;                                                                                            \
        const world *wd = world_lookup_out(w, #name, out, "out", &st);                                           \
        if (wd)                                                                                                  \
            *out = (value);                                                                                      \
        return st;                                                                                               \
    }

/* One past the last of the substep's contacts of the pair whose first contact is i: a pair's contacts are
 * adjacent in wd->contacts, so passes that need a pair once walk it pair by pair. */
static inline int32_t contact_pair_end(const world *wd, int32_t i)
{
    int32_t j = i + 1;
    while (j < wd->contact_count && wd->contacts[j].a.id == wd->contacts[i].a.id &&
           wd->contacts[j].b.id == wd->contacts[i].b.id)
        j++;
    return j;
}

/* A point or vector as the ABI gives it, px. */
static inline pp_vec2 vec2_of(dvec2 v) { return (pp_vec2){(float)v.x, (float)v.y}; }

/* A getter of one value of a body: the lookup and the check of `out`, then *out = value, an expression of bd. */
#define BODY_GETTER(name, type, value)                                                                           \
    PP_API pp_status name(pp_world w, pp_body b, type *out)                                                      \
    {                                                                                                            \
        world *wd;                                                                                               \
        pp_status st;                                                                                            \
        const body *bd = body_lookup_out(w, b, #name, out, "out", &wd, &st);                                     \
        if (bd)                                                                                                  \
            *out = (value);                                                                                      \
        return st;                                                                                               \
    }

/* Take a body out of the world and free it; its handle goes stale. */
void body_remove(world *wd, body *bd);
/* Give bd the ODE body its new type and fixed rotation ask for (none when static), keeping its pose and, where
 * it still moves, its velocity; forces and gravity scale go with a body that stops being dynamic. The caller
 * checked the change (a dynamic body has mass; no joint is left holding nothing that moves). */
void body_remake_solver(world *wd, body *bd, pp_body_type type, bool fixed_rotation);

/* Undo the latest pp_body_create exactly, for a call that fails after making bodies: the slot, its
 * generation and the creation serial come back as they were. Newest first when undoing several. */
void body_unmake(world *wd, body *bd);

/* The velocity (px/s) and angular velocity (rad/s) a dynamic body would have after an impulse (mass·px/s) at a
 * world point (px); nothing changes. */
void body_velocity_after_impulse(const world *wd, const body *bd, dvec2 impulse, dvec2 world_point, dvec2 *v,
                                 double *w);
/* Velocity of a body's material point at a world point, px/s; static bodies do not move. */
dvec2 body_point_velocity(const world *wd, const body *bd, dvec2 p);

/* Centre of mass (the pivot for massless bodies): in bitmap coordinates, px. */
static inline dvec2 body_com_local(const body *bd)
{
    return bd->mass.mass > 0 ? dv(bd->mass.cx, bd->mass.cy) : bd->pivot;
}
/* The world centre of mass found from the pose and mass, px: for a body's saved bytes, whose cache is unchecked. */
static inline dvec2 body_com_of_pose(const body *bd)
{
    return dv_add(bd->pos, dv_rot(dv_sub(body_com_local(bd), bd->pivot), bd->cos_a, bd->sin_a));
}
/* The world centre of mass, px: kept with the pose (body_update_com), read by every pass over pairs. */
static inline dvec2 body_com_world(const body *bd)
{
    PP_ASSERT(bd->com.x == body_com_of_pose(bd).x && bd->com.y == body_com_of_pose(bd).y);
    return bd->com;
}

/* The substeps of time a touching pair's island advances in this one (SPAN_*). */
static inline int contact_run_span(const world *wd, const contact_run *u)
{
    return wd->islands.span[u->node];
}
/* The radius of the disc a dynamic body's inertia matches, px, or 0 for a body that is not round. */
double body_round_radius(const body *bd);

/* Room for n pairs in the world's pair arrays. */
pp_status world_reserve_pairs(world *wd, const char *fn, int32_t n);

/* The integer cores of wd->batch.pairs[first, first + n) (`cells` samples in all) on the backend the world asked
 * for; says which one ran and on how many threads (0 on the GPU). */
pp_status world_run_cores(world *wd, const char *fn, int32_t first, int32_t n, int64_t cells, pp_backend *ran,
                          int32_t *threads);

/* Grow a per-slot array (*items, per_slot bytes a slot) to the world's body capacity. */
pp_status world_slot_array_grow(world *wd, void **items, int32_t *capacity, size_t per_slot, const char *what);
static inline pp_status world_slot_array(world *wd, void **items, int32_t *capacity, size_t per_slot, const char *what)
{
    return wd->body_ids.capacity <= *capacity ? PP_OK : world_slot_array_grow(wd, items, capacity, per_slot, what);
}
/* The same, its new slots zeroed as it grows: for arrays whose entries are read as stamps or counts, never reset
 * before use, so that a later failure cannot leave entries unset behind a capacity that says they are. */
pp_status world_slot_array_grow_zeroed(world *wd, void **items, int32_t *capacity, size_t per_slot, const char *what);
static inline pp_status world_slot_array_zeroed(world *wd, void **items, int32_t *capacity, size_t per_slot,
                                                const char *what)
{
    return wd->body_ids.capacity <= *capacity ? PP_OK
                                              : world_slot_array_grow_zeroed(wd, items, capacity, per_slot, what);
}

/* Whether a velocity (px/s) and angular velocity (rad/s) are within PP_MAX_SPEED and PP_MAX_ANGULAR_SPEED. */
bool body_speed_ok(dvec2 v, double w);
/* PP_ERR_INVALID_ARGUMENT, naming the field, for a velocity past PP_MAX_SPEED or PP_MAX_ANGULAR_SPEED. */
/* PP_ERR_INVALID_ARGUMENT naming the first of a body's surface and damping values out of its range. */
pp_status body_check_surface(const char *fn, double friction, double restitution, double linear_damping,
                             double angular_damping);
pp_status body_check_speed(const char *fn, const char *linear_name, dvec2 v, const char *angular_name, double w);

/* Refresh the cached world bounds and centre of mass after a pose change (cos_a, sin_a set already). */
void body_update_pose_cache(body *bd);
/* Refresh the cached world centre of mass alone: after a change of mass with the pose kept. */
void body_update_com(body *bd);

/* The narrowphase's view of a body at its current pose. */
static inline np_settings world_np_settings(const world *wd)
{
    return (np_settings){wd->def.normal_method, wd->def.contact_mode, wd->def.raster_stride};
}

static inline np_body body_np_view(const body *bd)
{
    return (np_body){&bd->raster, bd->pos, bd->pivot, bd->cos_a, bd->sin_a};
}

#endif
