/* Joints: the handle table, creation and the pp_joint_* calls (joint.c); the joints' bitmap anchors, and
 * what a step, an edit, a body's removal and a snapshot do to them (joint_step.c). The ODE side is
 * solver_ode.c's (solver_joint_*). */
#ifndef PP_JOINT_H
#define PP_JOINT_H

#include "edit.h"
#include "world.h"

typedef struct joint {
    uint32_t index;           /* slot in the world's joint table */
    pp_joint handle;
    pp_joint_def def;         /* as created, with the limits, motor and bodies as they are now */
    dvec2 local_a, local_b;   /* anchors: bitmap px of their body, world px for the world (MOUSE: a's is the target) */
    bool pinned_a, pinned_b;  /* the anchor had a solid pixel within 1 px at creation: an edit that takes them breaks it */
    dvec2 axis_local;         /* PRISMATIC, WHEEL: unit axis in a's bitmap axes (world axes for the world) */
    double ref;               /* REVOLUTE, a WELD with angular_hertz: b's angle from a at creation, rad; PRISMATIC,
                               * WHEEL: translation then, px */
    double length;            /* DISTANCE: the length it holds rigid or springs about, px */
    double slider_offset;     /* PRISMATIC: the translation when ODE's slider was last attached, px */
    bool dirty;               /* a body's ODE frame changed: attach again before the next solver step */
    uint64_t attach_order;    /* when it was last attached (joint_table.next_attach) */
    dvec2 frame_a, frame_b, frame_axis; /* the world anchors and axis it was last attached with, px */
    double frame_angle;       /* and its angle then, rad */
    solver_exact_state at_a, at_b; /* its ODE bodies' states then: a snapshot attaches it again from them */
    solver_joint sj;
} joint;

/* How far past its body's bitmap an anchor may lie, px (or the body's own size where that is more). */
#define JOINT_REACH 4096.0

/* Whether a def is a weld with a spring on its angle (a ball joint and an angular row in ODE). */
static inline bool joint_soft_angle(const pp_joint_def *d) { return d->type == PP_JOINT_WELD && d->angular_hertz > 0; }

/* A live joint of this world, or NULL (no failure recorded). */
joint *joint_find(const world *wd, pp_joint j);
/* The joint's bodies; NULL for the world. */
body *joint_body_a(const world *wd, const joint *jt);
body *joint_body_b(const world *wd, const joint *jt);
/* The joint's anchors in the world at its bodies' current poses, px (pp_joint_get_anchors). */
void joint_anchors(const world *wd, const joint *jt, dvec2 *a, dvec2 *b);
/* Wake the joint's bodies that have an ODE body. */
void joint_wake(world *wd, const joint *jt);
/* Take the joint out of its bodies' counts and the table, and free it with its ODE joint (no event). */
void joint_free(world *wd, joint *jt);
/* Whether a bitmap point (px) has a solid pixel within 1 px, the nearest one's column and row in *hx, *hy. */
bool joint_anchor_held(const body *bd, dvec2 p, int32_t *hx, int32_t *hy);
/* The joint's value and its rate, as pp_joint_get_value reports them: rad and rad/s revolute, px and px/s else. */
void joint_value(const world *wd, const joint *jt, double *value, double *speed);
/* Attach the ODE joint to its bodies as they are now, recording the frame for snapshots (joint_restore). */
void joint_attach(world *wd, joint *jt);

/* PP_ERR_INVALID_ARGUMENT (or INVALID_HANDLE for a body) unless a def's type, bodies and values make a joint. */
pp_status joint_check_def(world *wd, const char *fn, const pp_joint_def *d);

/* PP_ERR_INVALID_ARGUMENT unless each anchor (bitmap px; a NULL body's is a world point) lies within its body's
 * bitmap grown by 4096 px or its size on each side. */
pp_status joint_check_anchors(const char *fn, const body *a, dvec2 local_a, const body *b, dvec2 local_b);

/* Make a joint from a def (not NULL): checked, attached, its bodies woken; failures name `fn`. */
pp_status joint_make(world *wd, const pp_joint_def *def, const char *fn, joint **out);
/* A body being removed takes its joints with it, without events (pp_body_destroy: the host asked). */
void joint_body_removed(world *wd, body *bd);
/* A body's ODE body was moved to a new centre of mass, remade or given a new mass: its joints attach
 * again before the next solver step. */
void joint_body_changed(world *wd, const body *bd);
/* Whether one of bd's joints would hold nothing that moves were bd static: its other side is the world or a
 * static body, or it is a mouse joint pulling bd. */
bool joint_needs_mover(const world *wd, const body *bd);
/* Whether a joint without collide_connected joins the two bodies. */
bool joint_keeps_apart(const world *wd, const body *a, const body *b);
/* After an edit of bd's pixels, before its split `p` (NULL: none) is committed: a joint whose pinned anchor
 * has no solid pixel within 1 px breaks (room for bd->joint_count events is reserved), one whose anchor
 * lies on a piece moves to that piece. */
void joint_edit_done(world *wd, body *bd, const fracture_plan *p);
/* Before each solver step of h s: attach joints again where needed, springs for h, ropes taut or slack,
 * mouse targets. */
void joint_prepare(world *wd, double h);
/* After a whole step: joints whose reaction passed break_force break, with events. */
pp_status joint_step_done(world *wd);
/* A snapshot's joint into its slot (free, of its generation): its ODE joint attached again as the saved one
 * last was, from at_a, at_b and the frame, so that the world continues bit for bit. jt is the caller's until
 * this succeeds; feedback is the last substep's force and torque on ODE's first body (solver_joint_feedback). */
pp_status joint_restore(world *wd, joint *jt, const double feedback[6], const char *fn);
/* The joint table as a snapshot saved it: capacity slots with their generations, no joint yet, and the free
 * list (checked by the caller); failures name fn. */
pp_status joint_table_restore(world *wd, const uint32_t *generations, int32_t capacity, const uint32_t *free_slots,
                              int32_t free_count, const char *fn);

/* Free the joints of a world being destroyed. */
void joint_free_all(world *wd);

#endif
