/* The contact table: one record for every pair of bodies that touches, awake or asleep, and the one owner of
 * what the world remembers of a pair between substeps: what it is (sensor, passing a one-way platform, its
 * BEGIN queued), its friction anchor, and its manifold with the impulses of its last solve. A record is made
 * when the narrowphase first finds the pair touching and goes when it no longer does, or a body goes; an
 * island falling asleep keeps its records (and pp_world_get_contacts lists their manifolds), so it ends
 * nothing, and waking while still touching begins nothing. Contact and sensor events come from the records'
 * changes in one pass a substep (contact_table_end_substep).
 * Records live in one array, the pairs with an awake body first, the resting ones after; a hash by the two
 * bodies' slots finds a pair. A step's changes are logged record by record, so that a failed step puts the
 * table back as it was at the cost of what changed. */
#ifndef PP_CONTACT_TABLE_H
#define PP_CONTACT_TABLE_H

#include "math2d.h"
#include "narrowphase.h"
#include "pair_map.h"

#include <stdbool.h>
#include <stdint.h>

struct world;
struct body;

/* What a pair is to the world while it touches (the values snapshots keep). */
enum {
    CT_SENSOR = 1,      /* one body is a sensor: events, no contacts */
    CT_SENSOR_B = 2,    /* with CT_SENSOR: the sensor is b */
    CT_PASSING = 4,     /* a one-way platform let the other body in from the wrong side: no contacts until they part */
    CT_BEGUN = 8,       /* its PP_EVENT_CONTACT_BEGIN was queued: its END will be */
    CT_UNANCHORED = 16, /* loaded from a snapshot without anchors: anchors at its next substep */
    CT_SAVED_FLAGS = 31,
    CT_GONE = 32,       /* a body was removed: the pair ends at the next substep (out of the hash meanwhile) */
};

/* A carried pair's flags (carry.c): what its substeps have done with it. */
enum {
    CARRY_MISSED = 2,  /* collided at a substep it was carried into */
    CARRY_HELD = 4,    /* resting at the substep that found it: may be held into later steps */
    CARRY_STACK = 8,   /* its bodies sat that substep out: bound CARRY_STACK_PX, else CARRY_MOTION_PX */
};

/* Both bodies' centres of mass (px) and rotations when a carried pair's contacts were found. */
typedef struct carried_pose {
    dvec2 com_a, com_b;
    double cos_a, sin_a, cos_b, sin_b;
} carried_pose;

/* One touching pair: a is the body in the lower slot (the broadphase's order). */
typedef struct contact_record {
    uint64_t a, b;         /* body handle ids */
    uint32_t flags;        /* CT_* */
    uint32_t found;        /* the substep (contact_table.substep) the narrowphase last found the pair in */
    uint32_t claimed;      /* the substep whose broadphase last paired it carried: its contacts moved, not collided */
    int32_t run;           /* its place in the table's runs, while found is the substep now and it has contacts */
    double anchor[3];      /* b's pivot and angle in a's frame when the pair last held still: px, px, rad */
    double anchor_cos, anchor_sin; /* of anchor[2], for every slip measured against it: derived (anchor_turn),
                                    * never read from bytes */
    int32_t point_count;   /* the manifold: the points of the pair's last solve, their impulses with them */
    int32_t carried;       /* 1 + its place in the table's carry order, or 0: not carried (carry.h) */
    pp_contact points[PP_MAX_CONTACTS_PER_PAIR];
    /* Carried: the contacts the raster found, moved with the bodies through later substeps. */
    int8_t carry_count;    /* carry_points in use */
    int8_t carry_last;     /* the last substep (0 = the step's first) it is carried into */
    uint8_t carry_flags;   /* CARRY_* */
    carried_pose carry_pose;
    pp_contact carry_points[PP_MAX_CONTACTS_PER_PAIR];
    dvec2 carry_local[PP_MAX_CONTACTS_PER_PAIR][2]; /* each carried point in a's and b's frame at carry_pose, px:
                                                     * derived (contact_table_locate_carried), never read from bytes */
} contact_record;

/* One touching pair of the substep's contacts (wd->contacts): its points [first, end), its bodies' slots and its
 * record. Added as a pair's contacts are (contact_table_add_run), its record kept where the record moves to; the
 * passes after the substep's search (islands, carrying, solver rows, impulses, the step's saves) walk pairs
 * through it, with no search. */
typedef struct contact_run {
    int32_t first, end;
    uint32_t a, b;           /* body slots, a < b */
    int32_t record;          /* its index in records */
    uint32_t node;           /* a, or b where a has no solver body (is static): the slot its island is found by */
} contact_run;

typedef struct contact_table {
    contact_record *records; /* [0, awake): a body awake at the last substep; [awake, count): resting */
    int32_t count, awake, capacity;
    pair_map index;          /* the pair's slots → its record (not the gone ones) */
    int32_t *carry_order;    /* the carried records' indices in the order carry.c found them; −1: ended since */
    int32_t carry_count, carry_capacity;
    uint32_t substep;        /* counts the substeps that looked for pairs */
    int32_t found_count;     /* pairs found in this one */
    bool resting_stale;      /* a body entered the awake set: resting pairs with an awake body are tested again */
    int32_t gone;            /* records marked CT_GONE, ended at the next substep */
    contact_run *runs;       /* the substep's contacts pair by pair: valid from find_contacts to the step's end */
    int32_t run_count, run_capacity;
    /* The step's log: the records as the step found them, each saved on its first change. */
    contact_record *log;
    int32_t *log_at;         /* the index each logged record was at */
    int32_t log_count, log_capacity, log_at_capacity;
    uint32_t *logged;        /* by index: the step that logged it */
    int32_t logged_capacity;
    uint32_t step;           /* counts the steps saved, from 1 */
    int32_t saved_count, saved_awake, saved_gone; /* the counts the step found; saved_count 0 outside a step */
    uint32_t saved_substep;
    int32_t *saved_order;    /* carry_order as the step found it */
    int32_t saved_order_count, saved_order_capacity;
} contact_table;

/* List wd->contacts pair by pair into runs again, after they were compacted (PP_ERR_OUT_OF_MEMORY). */
pp_status contact_table_list_runs(struct world *wd);

/* The contacts [first, end) of wd->contacts just added are the pair of the record at index `record`, the bodies in
 * slots a < b (PP_ERR_OUT_OF_MEMORY). */
pp_status contact_table_add_run(struct world *wd, int32_t first, int32_t end, uint32_t a, uint32_t b, int32_t record);

/* Start a substep's search. */
void contact_table_begin_substep(struct world *wd);

/* A pair the narrowphase found touching (r->count > 0): find or make its record (*at: its index when the caller
 * holds it, as a carried pair's does, else -1; then where the record is now), queue its BEGIN event if it is new,
 * and say whether its contacts go to the solver (not for sensors or a passing one-way pair). */
pp_status contact_table_found(struct world *wd, const struct body *a, const struct body *b, const np_result *r,
                              int32_t *at, bool *keep);

/* After every pair: end each awake pair not found (its END event queued), put to rest those neither of whose
 * bodies was awake to be tested (a sleeping stack still touches), and take back the resting pairs a woken body
 * is in. */
pp_status contact_table_end_substep(struct world *wd);

/* After a substep's solve of h s: each contact's impulse over it from the solver (0 where its island sat the substep
 * out), and each solved contact's pair keeps its points and impulses as its manifold. */
void contact_table_store(struct world *wd, double h);

/* The index of the record of the bodies in these slots (a < b), or −1. */
int32_t contact_table_lookup(const struct world *wd, uint32_t a, uint32_t b);

/* The record at index i, to be changed: logged first for a failed step. */
contact_record *contact_table_edit(struct world *wd, int32_t i);

/* Carry the record at index i (not carried yet): it joins the end of the carry order. Room reserved with
 * contact_table_reserve_carried. */
void contact_table_carry(struct world *wd, int32_t i);

/* Room for n carried records; fn names the call in the message. */
pp_status contact_table_reserve_carried(struct world *wd, int32_t n, const char *fn);

/* Keep the carried records for which keep(…, arg) holds, in their order; the rest are carried no more. */
void contact_table_keep_carried(struct world *wd,
                                bool (*keep)(const struct world *, const contact_record *, const void *),
                                const void *arg);

/* The record of two bodies (handle ids, either order), or NULL. */
const contact_record *contact_table_find(const struct world *wd, uint64_t x, uint64_t y);

/* How far b's material point at world point p has moved relative to a since the pair's anchor, px:
 * the slip that static friction has let through and the solver should undo. */
dvec2 contact_anchor_slip(const contact_record *t, const struct body *a, const struct body *b, dvec2 p);

/* Set carry_local from carry_pose and carry_points, whenever either is written. */
void contact_table_locate_carried(contact_record *r);

/* A body is being removed: its pairs end at the next substep. Cannot fail. */
void contact_table_body_removed(struct world *wd, uint64_t id);

/* Add a record read from a snapshot (a in the lower slot), before any step; PP_ERR_FORMAT names `where` when
 * the pair is listed twice. A pair naming a body the world does not hold is gone: it ends at the next substep. */
pp_status contact_table_add(struct world *wd, const contact_record *rec, const char *fn, const char *where);

/* The contacts a sleeping pair keeps: its manifold, when neither of its bodies is awake; else 0. */
int32_t contact_table_resting_points(const struct world *wd, const contact_record *rec);

/* What a saved state keeps of the table besides its records and carry order. */
typedef struct contact_table_counts {
    int32_t count, awake, gone, carry_count;
    uint32_t substep;
    int32_t found_count;
    bool resting_stale;
} contact_table_counts;
void contact_table_get_counts(const struct world *wd, contact_table_counts *n);
/* A saved state's table (state.c): room first, which is all that can fail, then the copy, the index made
 * again from the records (validated by the caller once the awake set is listed again). */
pp_status contact_table_reserve_state(struct world *wd, int32_t count, int32_t carry_count, const char *fn);
void contact_table_set_state(struct world *wd, const contact_table_counts *n, const contact_record *records,
                             const int32_t *carry_order);
/* The step transaction (step_undo.c): start logging (it allocates; nothing changes on failure), put the table
 * back as the step found it (cannot fail), and stop logging after a step that ran whole. */
pp_status contact_table_save(struct world *wd);
void contact_table_restore(struct world *wd);
void contact_table_commit(struct world *wd);

/* PP_CHECKS: the runs list the substep's contacts, each with its record (asserts); a no-op otherwise. */
void contact_table_validate_runs(const struct world *wd);
/* PP_CHECKS: the table's invariants hold (asserts); a no-op otherwise. */
void contact_table_validate(const struct world *wd);

void contact_table_free(contact_table *t);

#endif
