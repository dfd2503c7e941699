/* The rigid-body solver: an ODE world constrained to the plane, in metres inside and pixels
 * outside. ODE types stay in solver_ode.c; the rest of the library sees opaque pointers. */
#ifndef PP_SOLVER_ODE_H
#define PP_SOLVER_ODE_H

#include "math2d.h"
#include "physpix.h"

#include <stdbool.h>

typedef struct pp_solver pp_solver;

/* A body's ODE objects; both NULL for static bodies. */
typedef struct solver_body {
    void *body;
    void *plane;
    double rotation_angle;     /* rad, the angle ODE's rotation was last built from (snapshots rebuild it bit for bit) */
} solver_body;

/* What the solver needs to create or update a body. */
typedef struct solver_body_desc {
    pp_body_type type;
    double mass, inertia;      /* mass units, mass·px² */
    dvec2 com_world;           /* px */
    double angle;              /* rad */
    dvec2 velocity;            /* of the centre of mass, px/s */
    double angular_velocity;   /* rad/s */
    bool fixed_rotation;
    void *user;                /* the library's body record */
} solver_body_desc;

/* The state read back after a step. */
typedef struct solver_body_state {
    dvec2 com_world;
    double angle;
    dvec2 velocity;
    double angular_velocity;
    bool awake;
    double cos_a, sin_a;       /* of angle (angle_cos_sin's): solver_body_sync's only */
} solver_body_state;

/* One contact handed to the solver; normal points from a to b. */
typedef struct solver_contact {
    const solver_body *a, *b;  /* b may be a static body (no ODE body) */
    double inv_mass_a, inv_mass_b;
    dvec2 point, normal;       /* px, unit */
    double depth;              /* px */
    double friction, restitution;
    double tangent_speed;      /* px/s the friction row drives a's point past b's along (−normal.y, normal.x) */
    double closing_speed;      /* px/s the pair may approach along the normal this substep (≥ 0) */
    uint8_t span;              /* substeps of time its island advances in this one: 1, 2 or 4 (SPAN_*) */
    bool bounce;               /* it bounces this substep: no softness, which would keep part of the speed */
} solver_contact;

pp_status solver_create(const pp_world_def *def, const char *fn, pp_solver **out);
void solver_destroy(pp_solver *s);

pp_status solver_body_create(pp_solver *s, const solver_body_desc *desc, solver_body *out);
void solver_body_destroy(pp_solver *s, solver_body *sb);
void solver_body_set_pose(pp_solver *s, solver_body *sb, dvec2 com_world, double angle);
void solver_body_set_velocity(pp_solver *s, const solver_body *sb, dvec2 v, double w);
/* New mass (mass units) and inertia about the centre of mass (mass·px²) after an edit. */
void solver_body_set_mass(pp_solver *s, const solver_body *sb, double mass, double inertia);
/* Add a force (mass·px/s², at the centre of mass) and a torque (mass·px²/s²) for the next solver step only. */
void solver_body_add_force(pp_solver *s, const solver_body *sb, dvec2 force, double torque);
/* Drop what solver_body_add_force gave a body that a failed step did not consume. */
void solver_body_clear_force(const solver_body *sb);
/* The world's gravity, px/s². */
void solver_set_gravity(pp_solver *s, dvec2 gravity);
void solver_body_wake(const solver_body *sb);
void solver_body_sleep(const solver_body *sb);
/* ODE's own test, declared here so that the step's many awake tests (awake_mover) are not a call deeper. */
struct dxBody;
int dBodyIsEnabled(struct dxBody *body);
static inline bool solver_body_is_awake(const solver_body *sb) { return dBodyIsEnabled(sb->body) != 0; }
/* After each step, once per body: read its state and, if awake, undo ODE's drift out of the plane. */
void solver_body_sync(const pp_solver *s, solver_body *sb, solver_body_state *out);
void solver_body_get_state(const pp_solver *s, const solver_body *sb, solver_body_state *out);
/* The state's velocities alone (px/s, rad/s), and its centre of mass alone (px): no angle to work out. */
void solver_body_get_velocity(const pp_solver *s, const solver_body *sb, dvec2 *v, double *w);
dvec2 solver_body_get_com(const pp_solver *s, const solver_body *sb);

/* A joint's ODE objects. ODE's first body is body_b, or body_a when body_b is the world: ODE never swaps
 * them itself, so its hinge and slider read b relative to a, or the reverse (sign −1) against the world. */
enum { SOLVER_JOINT_ROWS = 3 };
typedef struct solver_joint {
    void *joint;               /* the ODE joint (WHEEL and MOTOR: an angular motor, which is `angle` too) */
    void *feedback;            /* dJointFeedback of the joint, angle, spring and rows: the last substep's force on
                                * ODE's first body */
    void *angle;               /* an angular motor about z in user mode, or NULL: axis 0 a spring, axis 1 a motor */
    void *spring;              /* a distance ball anchored far along a slide's axis (a linear spring), or NULL */
    void *rows[SOLVER_JOINT_ROWS]; /* this substep's contact joints: drives and one-sided stops */
    int32_t row_count;
    void *body1, *body2;       /* the ODE bodies the joint was last attached to */
    bool first_is_b;
} solver_joint;

/* Where a joint attaches, at the bodies' current poses. */
typedef struct solver_joint_frame {
    const solver_body *a, *b;  /* NULL: the world (or a static body) */
    dvec2 anchor_a, anchor_b;  /* world px */
    dvec2 axis;                /* PRISMATIC: unit, world */
    double angle;              /* REVOLUTE: the angle b has turned from a since creation, rad */
} solver_joint_frame;

/* An ODE joint of the type (hinge, slider, distance ball, fixed, ball; WHEEL and MOTOR an angular motor; a WELD
 * with `soft_angle` a ball), attached to nothing yet. */
pp_status solver_joint_create(pp_solver *s, pp_joint_type type, bool soft_angle, const char *fn, solver_joint *out);
void solver_joint_destroy(solver_joint *sj);
/* Attach to the frame's bodies with its anchors and axis, as they are now; a joint between two bodies
 * without ODE bodies is disabled. */
void solver_joint_attach(pp_solver *s, pp_joint_type type, solver_joint *sj, const solver_joint_frame *f);
/* REVOLUTE (rad), PRISMATIC (px, measured from where solver_joint_attach left the slider): the stops. */
void solver_joint_set_limits(const pp_solver *s, pp_joint_type type, const solver_joint *sj, bool enabled,
                             double lower, double upper);
/* REVOLUTE (rad/s, mass·px²/s²), PRISMATIC (px/s, mass·px/s²): the motor. */
void solver_joint_set_motor(const pp_solver *s, pp_joint_type type, const solver_joint *sj, bool enabled,
                            double speed, double max_force);
/* A spring of stiffness k (mass/s²) and damping c (mass/s) for a substep of h s; k = 0 is rigid. */
void solver_joint_set_spring(const pp_solver *s, pp_joint_type type, const solver_joint *sj, double k, double c, double h);
/* DISTANCE: the held length, px, or none (the rope is slack). */
void solver_joint_set_length(const pp_solver *s, const solver_joint *sj, bool held, double length);
/* MOUSE: the world point, px, the body's anchor is pulled to. */
void solver_joint_set_target(const pp_solver *s, const solver_joint *sj, dvec2 target);
/* Before a substep: drop the last one's rows and switch the angle and spring parts off; what follows sets
 * this substep's (each part acts on the bodies the joint was last attached to). */
void solver_joint_parts_begin(pp_solver *s, solver_joint *sj);
/* A spring on b's angle relative to a: `error` rad from where it pulls, k (mass·px²/s² per rad), c (mass·px²/s per
 * rad) for a substep of h s. */
void solver_joint_angle_spring(pp_solver *s, solver_joint *sj, double error, double k, double c, double h);
/* A motor on b's spin relative to a: speed rad/s under max_torque (mass·px²/s²; 0: no cap). */
void solver_joint_angle_motor(pp_solver *s, solver_joint *sj, double speed, double max_torque);
/* A spring on b's point pb (world px) along the unit `dir` fixed in a: `error` px past where it pulls, k (mass/s²),
 * c (mass/s) for a substep of h s. */
void solver_joint_linear_spring(pp_solver *s, solver_joint *sj, dvec2 pb, dvec2 dir, double error, double k, double c,
                                double h);
/* Two rows at a world point (px), on the unit `dir` and on its perpendicular (−dir.y, dir.x): each drives b's
 * speed there relative to a's material point to speed (px/s) less the world's ERP of error (px) over h, under
 * max_force (mass·px/s²; < 0 no cap, 0 no row). */
typedef struct solver_drive {
    dvec2 point, dir;
    double speed[2], error[2], max_force[2];
} solver_drive;
void solver_joint_add_drive(pp_solver *s, solver_joint *sj, const solver_drive *d, double h);
/* A one-sided stop at a world point (px): it only pushes b along the unit `dir` relative to a, once b has moved
 * `gap` px against dir (negative: past it already). */
void solver_joint_add_stop(pp_solver *s, solver_joint *sj, dvec2 point, dvec2 dir, double gap, double h);
/* ODE's own record of the last substep's force and torque on its first body, all parts summed (N, N·m: x, y, z
 * each), for snapshots. */
void solver_joint_feedback(const solver_joint *sj, double out[6]);
void solver_joint_set_feedback(const solver_joint *sj, const double in[6]);
/* The force (mass·px/s²) and torque (mass·px²/s²) the last substep applied to body_b. */
void solver_joint_reaction(const pp_solver *s, const solver_joint *sj, dvec2 *force, double *torque);

/* Room for n contacts in the next step and their impulses, zeroed; call before adding them. */
pp_status solver_reserve_contacts(pp_solver *s, int32_t n);
/* Room for a contact of the next step, to be filled in place, its impulse read back as contact k. The solver
 * orders its rows itself. */
solver_contact *solver_add_contact(pp_solver *s, int32_t k);
/* Into each of contacts[first, end) (k = its index): the impulse the last step of h s applied at contact k along its
 * unit normal, mass·px/s (≥ 0). One call a pair, not a point: contact_table_store's loop runs every substep. */
void solver_store_impulses(const pp_solver *s, pp_contact *contacts, int32_t first, int32_t end, double h);

/* The exact ODE state of a body, in ODE's units, for snapshots. */
typedef struct solver_exact_state {
    double px, py;             /* centre of mass, m */
    double rotation_angle;     /* rad */
    double vx, vy, wz;         /* m/s, rad/s */
    bool enabled;
} solver_exact_state;

void solver_body_save(const solver_body *sb, solver_exact_state *out);
void solver_body_restore(solver_body *sb, const solver_exact_state *in);
/* Solver steps taken so far (they seed QuickStep's shuffle). */
uint64_t solver_get_steps(const pp_solver *s);
void solver_set_steps(pp_solver *s, uint64_t steps);

/* How a substep's awake islands are solved, in the order solver_step runs them: ODE's exact dWorldStep (every
 * body of its islands, sleepers included) over h, over 2·h and over 4·h (a lone body at rest that sat the one or
 * three substeps before out: island.c), QuickStep over h, over 2·h (the stacks that sat the substep before
 * out), over 2·h at rest (no pair of the stack collided this step: island.c), with fewer iterations, over 4·h
 * (a stack at rest that sat the three substeps before out), with every iteration, and not at all (islands
 * sitting this substep out). */
enum { SOLVE_EXACT, SOLVE_EXACT_TWO, SOLVE_EXACT_FOUR, SOLVE_QUICK, SOLVE_QUICK_TWO, SOLVE_QUICK_TWO_REST,
       SOLVE_QUICK_FOUR, SOLVE_IDLE, SOLVE_LISTS };
/* The substeps of time each list (SOLVE_*) advances. */
static const uint8_t SOLVE_SPAN[SOLVE_LISTS] = {1, 2, 4, 1, 2, 2, 4, 0};

/* The bodies of one substep's awake islands, by how they are solved (SOLVE_*). */
typedef struct solver_islands {
    solver_body **list[SOLVE_LISTS];
    int32_t count[SOLVE_LISTS];
} solver_islands;

/* No island to step. */
static inline bool solver_islands_empty(const solver_islands *is)
{
    for (int i = 0; i < SOLVE_IDLE; i++)
        if (is->count[i] > 0)
            return false;
    return true;
}

/* Advance by h seconds (one substep) and drop the contact joints. Nothing awake skips ODE, which
 * would change nothing but still walk every body. False when ODE could not get memory for its step. */
bool solver_step(pp_solver *s, double h, const solver_islands *islands);

#endif
