/* The ODE world: one ODE body per dynamic or kinematic body with its centre of mass at the body
 * origin (a plane-2D joint only for fixed rotation), contact joints from the raster contacts, each
 * island stepped by Step or QuickStep (island.c).
 * Lengths are divided by pixels_per_meter so ODE's tolerances see metre-sized numbers. */
#include "alloc.h"
#include "check.h"
#include "solver_ode.h"
#include "status.h"

#include <ode/ode.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct pending_contact {
    solver_contact c;
    int32_t k;                    /* its feedback slot */
} pending_contact;

struct pp_solver {
    dWorldID world;
    dJointGroupID contacts;
    double ppm, inv_ppm;
    double erp, cfm, bounce_vel;  /* bounce_vel in m/s */
    uint64_t steps;               /* seeds QuickStep's constraint shuffle */
    dJointFeedback *feedback;     /* by contact: the forces ODE's step applied */
    int32_t feedback_capacity;
    pending_contact *pending;     /* the next step's contacts, in the world's order */
    int32_t pending_count, pending_capacity;
    dContact ct;                  /* each contact's row, written here for ODE to copy; what it leaves stays 0 */
    int32_t attached;             /* contact joints in the group, emptied after each step */
    int iterations, rest_iterations; /* QuickStep's, and those of the stacks at rest it solves over 2·h */
    solver_exact_state *exact_from; /* the exact islands' bodies before dWorldStep, should it give up */
    int32_t exact_from_capacity;
};

static pthread_once_t ode_once = PTHREAD_ONCE_INIT;
static bool ode_ok;
/* ODE's random generator is process-wide: seeding and stepping happen under one lock. */
static pthread_mutex_t ode_step_lock = PTHREAD_MUTEX_INITIALIZER;
static _Thread_local bool ode_thread_ready;
static _Thread_local bool lcp_gave_up; /* ODE's exact LCP gave up during this thread's dWorldStep */

/* ODE's messages (its errors and debug checks abort, and are never reached from valid input) go to the log
 * hook, never to stderr. The one seen is d_ERR_LCP, "LCP internal error, s <= 0": dWorldStep's Dantzig LCP
 * meeting degenerate rows; step_exact takes that island to QuickStep. */
static void ode_message(int num, const char *msg, va_list ap)
{
    char text[256];
    vsnprintf(text, sizeof text, msg, ap);
    if (num == d_ERR_LCP)
        lcp_gave_up = true;
    pp_log(num == d_ERR_LCP ? 1 : 2, "physpix: ODE message %d: %s", num, text);
}

static void ode_init_once(void)
{
    ode_ok = dInitODE2(0) && dCheckConfiguration("ODE_double_precision");
    if (ode_ok)
        dSetMessageHandler(ode_message);
}

/* A host that unloads the library (as a plugin) gets ODE's process-wide data back. */
__attribute__((destructor)) static void ode_close(void)
{
    if (ode_ok) {
        dCleanupODEAllDataForThread();
        dCloseODE();
    }
}

static pp_status ode_ready(void)
{
    pthread_once(&ode_once, ode_init_once);
    if (!ode_ok)
        return pp_fail(PP_ERR_UNSUPPORTED, "ODE failed to initialise or is not the double-precision build");
    if (!ode_thread_ready) {
        if (!dAllocateODEDataForThread(dAllocateMaskAll))
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "ODE could not allocate its per-thread data");
        ode_thread_ready = true;
    }
    return PP_OK;
}

/* A QuickStep stack at rest (solver_islands.quick_rest) takes half of solver_iterations, at least 5: its pairs
 * are carried with friction anchors and closed at contact_slop, and the other half bought nothing measurable
 * there; QuickStep's sweeps were three quarters of the awake 20-row pyramid's step. A stack with a pair the
 * narrowphase collided this step (something landed, slid or tipped) keeps them all: in 500 raining crates,
 * half for every stack jostled the pile loose and the narrowphase cost 3.6 times as much. */
enum { REST_ITERATION_SHARE = 2, REST_ITERATIONS_MIN = 5 };

pp_status solver_create(const pp_world_def *def, const char *fn, pp_solver **out)
{
    pp_status st = ode_ready();
    if (st)
        return pp_fail_in(fn, st);
    pp_solver *s = pp_calloc(1, sizeof *s);
    if (!s)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for the solver", fn);
    s->ppm = def->pixels_per_meter;
    s->inv_ppm = 1.0 / def->pixels_per_meter;
    s->erp = def->contact_erp;
    s->cfm = def->contact_cfm;
    s->bounce_vel = def->bounce_threshold * s->inv_ppm;
    s->world = dWorldCreate();
    s->contacts = dJointGroupCreate(0);
    solver_set_gravity(s, dv(def->gravity.x, def->gravity.y));
    s->iterations = def->solver_iterations;
    s->rest_iterations = s->iterations / REST_ITERATION_SHARE;
    if (s->rest_iterations < REST_ITERATIONS_MIN)
        s->rest_iterations = s->iterations < REST_ITERATIONS_MIN ? s->iterations : REST_ITERATIONS_MIN;
    dWorldSetQuickStepNumIterations(s->world, s->iterations);
    dWorldSetContactSurfaceLayer(s->world, def->contact_slop * s->inv_ppm);
    /* Deep overlaps (spawned bodies, a fast body stopped inside a wall) separate at a bounded speed;
     * ODE applies the cap to the correction only, never to a bounce. */
    dWorldSetContactMaxCorrectingVel(s->world, def->max_correction_speed * s->inv_ppm);
    /* Sleep is the world's (world.c): ODE's auto-disable timers cannot be read back for snapshots. */
    dWorldSetAutoDisableFlag(s->world, 0);
    *out = s;
    return PP_OK;
}

void solver_destroy(pp_solver *s)
{
    if (!s)
        return;
    dJointGroupDestroy(s->contacts);
    dWorldDestroy(s->world);
    pp_free(s->feedback);
    pp_free(s->pending);
    pp_free(s->exact_from);
    pp_free(s);
}

/* A rotation about z by its quaternion: ODE keeps the quaternion and makes the matrix from it, so this is
 * what dBodySetRotation would end in, without its trip through a matrix and back. */
static void set_rotation_half(solver_body *sb, double angle, double half_c, double half_s)
{
    sb->rotation_angle = angle;
    const dQuaternion q = {half_c, 0, 0, half_s};
    dBodySetQuaternion(sb->body, q);
}

static void set_rotation_z(solver_body *sb, double angle)
{
    set_rotation_half(sb, angle, cos(0.5 * angle), sin(0.5 * angle));
}

static void set_mass(const pp_solver *s, dBodyID b, double mass, double inertia)
{
    dMass m;
    dMassSetZero(&m);
    const double I = inertia * s->inv_ppm * s->inv_ppm;
    /* Only I33 acts in the plane; the other two keep the tensor well-conditioned. */
    dMassSetParameters(&m, mass, 0, 0, 0, I, I, I, 0, 0, 0);
    dBodySetMass(b, &m);
}

void solver_body_set_mass(pp_solver *s, const solver_body *sb, double mass, double inertia)
{
    if (!dBodyIsKinematic((dBodyID)sb->body))
        set_mass(s, (dBodyID)sb->body, mass, inertia);
}

void solver_body_add_force(pp_solver *s, const solver_body *sb, dvec2 f, double torque)
{
    dBodyAddForce((dBodyID)sb->body, f.x * s->inv_ppm, f.y * s->inv_ppm, 0);
    dBodyAddTorque((dBodyID)sb->body, 0, 0, torque * s->inv_ppm * s->inv_ppm);
}

void solver_body_clear_force(const solver_body *sb)
{
    dBodySetForce((dBodyID)sb->body, 0, 0, 0);
    dBodySetTorque((dBodyID)sb->body, 0, 0, 0);
}

void solver_set_gravity(pp_solver *s, dvec2 g) { dWorldSetGravity(s->world, g.x * s->inv_ppm, g.y * s->inv_ppm, 0); }

pp_status solver_body_create(pp_solver *s, const solver_body_desc *d, solver_body *out)
{
    dBodyID b = dBodyCreate(s->world);
    if (d->type == PP_BODY_KINEMATIC) {
        dBodySetKinematic(b);
        dBodySetAutoDisableFlag(b, 0);
    } else {
        set_mass(s, b, d->mass, d->inertia);
    }
    dBodySetData(b, d->user);
    /* Every force and row is in the plane (contacts' normals and friction directions, gravity), so a body
     * never leaves it: no plane-2D joint, whose three rows a body would cost every step. A body that must
     * not turn keeps one for its angle motor, holding ω = 0 with unbounded torque. */
    dJointID plane = NULL;
    if (d->fixed_rotation) {
        plane = dJointCreatePlane2D(s->world, 0);
        dJointAttach(plane, b, 0);
        dJointSetPlane2DAngleParam(plane, dParamVel, 0);
        dJointSetPlane2DAngleParam(plane, dParamFMax, dInfinity);
    }
    out->body = b;
    out->plane = plane;
    solver_body_set_pose(s, out, d->com_world, d->angle);
    solver_body_set_velocity(s, out, d->velocity, d->angular_velocity);
    return PP_OK;
}

void solver_body_destroy(pp_solver *s, solver_body *sb)
{
    if (sb->plane)
        dJointDestroy((dJointID)sb->plane);
    if (sb->body)
        dBodyDestroy((dBodyID)sb->body);
    sb->body = sb->plane = NULL;
}

void solver_body_set_pose(pp_solver *s, solver_body *sb, dvec2 com, double angle)
{
    dBodySetPosition(sb->body, com.x * s->inv_ppm, com.y * s->inv_ppm, 0);
    set_rotation_z(sb, angle);
}

void solver_body_set_velocity(pp_solver *s, const solver_body *sb, dvec2 v, double w)
{
    dBodySetLinearVel(sb->body, v.x * s->inv_ppm, v.y * s->inv_ppm, 0);
    dBodySetAngularVel(sb->body, 0, 0, w);
}

void solver_body_wake(const solver_body *sb)
{
    if (sb->body)
        dBodyEnable(sb->body);
}

/* As ODE's auto-disable does: a sleeping body keeps no velocity. */
void solver_body_sleep(const solver_body *sb)
{
    dBodySetLinearVel(sb->body, 0, 0, 0);
    dBodySetAngularVel(sb->body, 0, 0, 0);
    dBodyDisable(sb->body);
}


void solver_body_get_velocity(const pp_solver *s, const solver_body *sb, dvec2 *v, double *w)
{
    const dReal *lv = dBodyGetLinearVel((dBodyID)sb->body), *av = dBodyGetAngularVel((dBodyID)sb->body);
    *v = dv(lv[0] * s->ppm, lv[1] * s->ppm);
    *w = av[2];
}

dvec2 solver_body_get_com(const pp_solver *s, const solver_body *sb)
{
    const dReal *p = dBodyGetPosition((dBodyID)sb->body);
    return dv(p[0] * s->ppm, p[1] * s->ppm);
}

void solver_body_get_state(const pp_solver *s, const solver_body *sb, solver_body_state *out)
{
    dBodyID b = sb->body;
    const dReal *p = dBodyGetPosition(b), *R = dBodyGetRotation(b);
    const dReal *v = dBodyGetLinearVel(b), *w = dBodyGetAngularVel(b);
    out->com_world = dv(p[0] * s->ppm, p[1] * s->ppm);
    out->angle = atan2(R[4], R[0]);
    out->velocity = dv(v[0] * s->ppm, v[1] * s->ppm);
    out->angular_velocity = w[2];
    out->awake = dBodyIsEnabled(b) != 0;
}

pp_status solver_reserve_contacts(pp_solver *s, int32_t n)
{
    if (!ARRAY_RESERVE(s->feedback, s->feedback_capacity, n) || !ARRAY_RESERVE(s->pending, s->pending_capacity, n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory for %d contact impulses", (int)n);
    return PP_OK;
}

void solver_store_impulses(const pp_solver *s, pp_contact *contacts, int32_t first, int32_t end, double h)
{
    for (int32_t k = first; k < end; k++) {
        /* f1 is the force on the joint's first body; along the normal it is the contact's push alone. */
        const dReal *f = s->feedback[k].f1;
        const pp_vec2 n = contacts[k].normal;
        contacts[k].normal_impulse = (float)(fabs(f[0] * (double)n.x + f[1] * (double)n.y) * h * s->ppm);
    }
}

solver_contact *solver_add_contact(pp_solver *s, int32_t k)
{
    PP_ASSERT(k >= 0 && k < s->feedback_capacity && s->pending_count < s->pending_capacity); /* reserved first */
    pending_contact *p = &s->pending[s->pending_count++];
    p->k = k;
    return &p->c;
}

static void attach_contact(pp_solver *s, const solver_contact *c, int32_t k)
{
    dContact *ct = &s->ct; /* every field written below, each time: the rest stay as calloc left them */
    /* One friction row, along the in-plane tangent: ODE's second direction would be z, where nothing moves. */
    int mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM | dContactMu2 | dContactFDir1;
    ct->surface.mu = c->friction;
    ct->fdir1[0] = -c->normal.y;
    ct->fdir1[1] = c->normal.x;
    /* Attached as (0, b), ODE swaps the bodies and flips the normal but not fdir1: the row then reads b past a. */
    ct->surface.motion1 = c->tangent_speed != 0 ? (c->a ? c->tangent_speed : -c->tangent_speed) * s->inv_ppm : 0;
    mode |= c->tangent_speed != 0 ? dContactMotion1 : 0;
    /* the row's target: separate at −closing_speed, i.e. approach at most that */
    ct->surface.motionN = c->closing_speed > 0 ? -c->closing_speed * s->inv_ppm : 0;
    mode |= c->closing_speed > 0 ? dContactMotionN : 0;
    ct->surface.bounce = c->restitution > 0 ? c->restitution : 0;
    ct->surface.bounce_vel = c->restitution > 0 ? s->bounce_vel : 0;
    mode |= c->restitution > 0 ? dContactBounce : 0;
    ct->surface.mode = mode;
    /* cfm is relative to the pair's reduced mass, so softness does not depend on body size. A bounce is hard:
     * the softness kept back 0.5 % of an elastic ball's speed at each bounce (5 % of its height in 10). */
    const double inv_m = c->inv_mass_a + c->inv_mass_b;
    ct->surface.soft_erp = s->erp;
    ct->surface.soft_cfm = c->bounce ? 0.0 : s->cfm * (inv_m > 0 ? inv_m : 1.0);
    /* ODE pushes body 1 along the normal to separate: our normal points from a to b, so negate. */
    ct->geom.pos[0] = c->point.x * s->inv_ppm;
    ct->geom.pos[1] = c->point.y * s->inv_ppm;
    ct->geom.normal[0] = -c->normal.x;
    ct->geom.normal[1] = -c->normal.y;
    ct->geom.depth = c->depth * s->inv_ppm;
    dJointID j = dJointCreateContact(s->world, s->contacts, ct);
    s->attached++;
    dJointAttach(j, c->a ? (dBodyID)c->a->body : 0, c->b ? (dBodyID)c->b->body : 0);
    /* A joint ODE leaves out of its step (all its bodies asleep) writes no feedback: it applied nothing. Only f1
     * is read (solver_contact_impulse). */
    memset(s->feedback[k].f1, 0, sizeof s->feedback[k].f1);
    dJointSetFeedback(j, &s->feedback[k]);
}

/* ---- joints ---- */

enum { PART_JOINT, PART_ANGLE, PART_SPRING, PART_ROWS, PART_COUNT = PART_ROWS + SOLVER_JOINT_ROWS };

static dJointFeedback *part_feedback(const solver_joint *sj, int part) { return (dJointFeedback *)sj->feedback + part; }

/* An angular motor about z in user mode: axis 0 a spring (its stops), axis 1 a motor, both off. */
static dJointID angle_motor_create(pp_solver *s)
{
    dJointID j = dJointCreateAMotor(s->world, 0);
    dJointSetAMotorMode(j, dAMotorUser);
    dJointSetAMotorNumAxes(j, 2);
    dJointSetAMotorAxis(j, 0, 0, 0, 0, 1);
    dJointSetAMotorAxis(j, 1, 0, 0, 0, 1);
    return j;
}

pp_status solver_joint_create(pp_solver *s, pp_joint_type type, bool soft_angle, const char *fn, solver_joint *out)
{
    dJointFeedback *fb = pp_calloc(PART_COUNT, sizeof *fb);
    if (!fb)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for the joint", fn);
    dJointID j;
    switch (type) {
    case PP_JOINT_REVOLUTE: j = dJointCreateHinge(s->world, 0); break;
    case PP_JOINT_PRISMATIC: j = dJointCreateSlider(s->world, 0); break;
    case PP_JOINT_DISTANCE: j = dJointCreateDBall(s->world, 0); break;
    case PP_JOINT_WELD: j = soft_angle ? dJointCreateBall(s->world, 0) : dJointCreateFixed(s->world, 0); break;
    case PP_JOINT_WHEEL: /* its slide and limits are rows set each substep; the motor turns b */
    case PP_JOINT_MOTOR: j = angle_motor_create(s); break;
    default: j = dJointCreateBall(s->world, 0); break;
    }
    dJointSetFeedback(j, fb);
    *out = (solver_joint){.joint = j, .feedback = fb, .first_is_b = true};
    if (type == PP_JOINT_WHEEL || type == PP_JOINT_MOTOR)
        out->angle = j;
    return PP_OK;
}

static void rows_destroy(solver_joint *sj)
{
    for (int32_t k = 0; k < sj->row_count; k++)
        dJointDestroy((dJointID)sj->rows[k]);
    sj->row_count = 0;
}

void solver_joint_destroy(solver_joint *sj)
{
    rows_destroy(sj);
    if (sj->angle && sj->angle != sj->joint)
        dJointDestroy((dJointID)sj->angle);
    if (sj->spring)
        dJointDestroy((dJointID)sj->spring);
    if (sj->joint)
        dJointDestroy((dJointID)sj->joint);
    pp_free(sj->feedback);
    *sj = (solver_joint){0};
}

/* +1 when ODE reads b relative to a, −1 when it reads a relative to the world (body_b). */
static double joint_sign(const solver_joint *sj) { return sj->first_is_b ? 1.0 : -1.0; }

void solver_joint_attach(pp_solver *s, pp_joint_type type, solver_joint *sj, const solver_joint_frame *f)
{
    dJointID j = sj->joint;
    dBodyID a = f->a ? (dBodyID)f->a->body : 0, b = f->b ? (dBodyID)f->b->body : 0;
    sj->first_is_b = b != 0;
    sj->body1 = b ? b : a, sj->body2 = b ? a : 0;
    dJointAttach(j, b ? b : a, b ? a : 0);
    if (!a && !b) {
        dJointDisable(j);
        return;
    }
    dJointEnable(j);
    const double k = s->inv_ppm;
    /* ODE's first body's anchor, then the other's. */
    const dvec2 p1 = b ? f->anchor_b : f->anchor_a, p2 = b ? f->anchor_a : f->anchor_b;
    switch (type) {
    case PP_JOINT_REVOLUTE:
        dJointSetHingeAnchor(j, p1.x * k, p1.y * k, 0);
        dJointSetHingeAxisOffset(j, 0, 0, 1, joint_sign(sj) * f->angle);
        break;
    case PP_JOINT_PRISMATIC:
        dJointSetSliderAxis(j, f->axis.x, f->axis.y, 0);
        break;
    case PP_JOINT_DISTANCE: {
        const double d = dJointGetDBallDistance(j);
        dJointSetDBallAnchor1(j, p1.x * k, p1.y * k, 0);
        dJointSetDBallAnchor2(j, p2.x * k, p2.y * k, 0);
        dJointSetDBallDistance(j, d); /* setting anchors measures them; the held length stays */
        break;
    }
    case PP_JOINT_WELD:
        if (dJointGetType(j) == dJointTypeBall)
            dJointSetBallAnchor(j, p1.x * k, p1.y * k, 0);
        else
            dJointSetFixed(j);
        break;
    case PP_JOINT_WHEEL:
    case PP_JOINT_MOTOR:
        break;
    default: /* the body's point; solver_joint_set_target moves the world's */
        dJointSetBallAnchor(j, p1.x * k, p1.y * k, 0);
        break;
    }
}

static void set_stops(dJointID j, pp_joint_type type, double lo, double hi)
{
    void (*set)(dJointID, int, dReal) = type == PP_JOINT_REVOLUTE ? dJointSetHingeParam : dJointSetSliderParam;
    /* ODE may refuse a low stop above the high one: open both first. */
    set(j, dParamLoStop, -dInfinity);
    set(j, dParamHiStop, dInfinity);
    set(j, dParamHiStop, hi);
    set(j, dParamLoStop, lo);
}

void solver_joint_set_limits(const pp_solver *s, pp_joint_type type, const solver_joint *sj, bool enabled,
                             double lower, double upper)
{
    const double k = type == PP_JOINT_PRISMATIC ? s->inv_ppm : 1.0, sg = joint_sign(sj);
    if (!enabled)
        set_stops(sj->joint, type, -dInfinity, dInfinity);
    else if (sg > 0)
        set_stops(sj->joint, type, lower * k, upper * k);
    else
        set_stops(sj->joint, type, -upper * k, -lower * k);
}

void solver_joint_set_motor(const pp_solver *s, pp_joint_type type, const solver_joint *sj, bool enabled,
                            double speed, double max_force)
{
    void (*set)(dJointID, int, dReal) = type == PP_JOINT_REVOLUTE ? dJointSetHingeParam : dJointSetSliderParam;
    const double k = type == PP_JOINT_PRISMATIC ? s->inv_ppm : 1.0;
    const double f = type == PP_JOINT_PRISMATIC ? s->inv_ppm : s->inv_ppm * s->inv_ppm;
    set(sj->joint, dParamVel, enabled ? joint_sign(sj) * speed * k : 0);
    set(sj->joint, dParamFMax, enabled ? max_force * f : 0);
}

void solver_joint_set_spring(const pp_solver *s, pp_joint_type type, const solver_joint *sj, double k, double c, double h)
{
    /* ODE's manual: a spring k and damper c over a step h are ERP = hk/(hk + c), CFM = 1/(hk + c). Both are
     * force per length, the same number in metres as in pixels. */
    const bool fixed = dJointGetType((dJointID)sj->joint) == dJointTypeFixed;
    void (*set)(dJointID, int, dReal) = type == PP_JOINT_DISTANCE ? dJointSetDBallParam
                                        : fixed                   ? dJointSetFixedParam
                                                                  : dJointSetBallParam;
    const bool rigid = !(k > 0) || !(h * k + c > 0);
    set(sj->joint, dParamERP, rigid ? dWorldGetERP(s->world) : h * k / (h * k + c));
    set(sj->joint, dParamCFM, rigid ? dWorldGetCFM(s->world) : 1.0 / (h * k + c));
}

void solver_joint_set_length(const pp_solver *s, const solver_joint *sj, bool held, double length)
{
    if (held) {
        dJointSetDBallDistance(sj->joint, length * s->inv_ppm);
        dJointEnable(sj->joint);
    } else {
        dJointDisable(sj->joint);
    }
}

void solver_joint_set_target(const pp_solver *s, const solver_joint *sj, dvec2 t)
{
    dJointSetBallAnchor2(sj->joint, t.x * s->inv_ppm, t.y * s->inv_ppm, 0);
}

/* ---- a joint's parts: rows set each substep beside its ODE joint ---- */

/* ERP and CFM of a spring k, damper c over a step h whose position term uses the new velocity: ODE's mapping
 * (c + hk) damps hk more than asked (a 2 Hz spring over 1/240 s lost 15 % a period undamped), so the damper
 * asked for is lessened by hk as far as it goes. */
static void spring_erp_cfm(double k, double c, double h, double *erp, double *cfm)
{
    const double d = fmax(c - h * k, 0) + h * k;
    *erp = h * k / d;
    *cfm = 1.0 / d;
}

static void zero_feedback(const solver_joint *sj, int part) { memset(part_feedback(sj, part), 0, sizeof(dJointFeedback)); }

void solver_joint_parts_begin(pp_solver *s, solver_joint *sj)
{
    (void)s;
    rows_destroy(sj);
    for (int k = PART_ROWS; k < PART_COUNT; k++)
        zero_feedback(sj, k);
    if (sj->angle) { /* both axes off: no row */
        dJointID j = sj->angle;
        if (j != sj->joint) /* first in its bodies' lists again, as after a snapshot's load */
            dJointAttach(j, sj->body1, sj->body2);
        dJointSetAMotorParam(j, dParamLoStop, -dInfinity);
        dJointSetAMotorParam(j, dParamHiStop, dInfinity);
        dJointSetAMotorParam(j, dParamFMax2, 0);
    }
    if (sj->spring) {
        dJointAttach(sj->spring, sj->body1, sj->body2);
        dJointDisable(sj->spring);
    }
}

static dJointID angle_part(pp_solver *s, solver_joint *sj)
{
    if (!sj->angle) {
        sj->angle = angle_motor_create(s);
        dJointSetFeedback(sj->angle, part_feedback(sj, PART_ANGLE));
        dJointAttach(sj->angle, sj->body1, sj->body2);
    }
    return sj->angle;
}

void solver_joint_angle_spring(pp_solver *s, solver_joint *sj, double error, double k, double c, double h)
{
    if (!sj->body1)
        return;
    dJointID j = angle_part(s, sj);
    double erp, cfm;
    const double u = s->inv_ppm * s->inv_ppm; /* mass·px² → mass·m² */
    spring_erp_cfm(k * u, c * u, h, &erp, &cfm);
    dJointSetAMotorAngle(j, 0, joint_sign(sj) * error);
    dJointSetAMotorParam(j, dParamStopERP, erp);
    dJointSetAMotorParam(j, dParamStopCFM, cfm);
    dJointSetAMotorParam(j, dParamLoStop, 0); /* low and high at once: one unbounded row toward 0 */
    dJointSetAMotorParam(j, dParamHiStop, 0);
}

void solver_joint_angle_motor(pp_solver *s, solver_joint *sj, double speed, double max_torque)
{
    if (!sj->body1)
        return;
    dJointID j = angle_part(s, sj);
    dJointSetAMotorParam(j, dParamVel2, joint_sign(sj) * speed);
    dJointSetAMotorParam(j, dParamFMax2, max_torque > 0 ? max_torque * s->inv_ppm * s->inv_ppm : dInfinity);
}

/* How far along its axis a linear spring's anchor on a lies: its row then points along the axis to within
 * the slide's error over this, and its lever arms are exact (they differ by a multiple of the axis). */
#define SPRING_REACH 1e4

void solver_joint_linear_spring(pp_solver *s, solver_joint *sj, dvec2 pb, dvec2 dir, double error, double k, double c,
                                double h)
{
    if (!sj->body1)
        return;
    if (!sj->spring) {
        sj->spring = dJointCreateDBall(s->world, 0);
        dJointSetFeedback(sj->spring, part_feedback(sj, PART_SPRING));
        dJointAttach(sj->spring, sj->body1, sj->body2);
    }
    dJointID j = sj->spring;
    const double q = s->inv_ppm;
    const dvec2 pa = dv_sub(pb, dv_scale(dir, SPRING_REACH + error));
    const dvec2 p1 = sj->first_is_b ? pb : pa, p2 = sj->first_is_b ? pa : pb;
    double erp, cfm;
    spring_erp_cfm(k, c, h, &erp, &cfm);
    dJointEnable(j);
    dJointSetDBallAnchor1(j, p1.x * q, p1.y * q, 0);
    dJointSetDBallAnchor2(j, p2.x * q, p2.y * q, 0);
    dJointSetDBallDistance(j, SPRING_REACH * q);
    dJointSetDBallParam(j, dParamERP, erp);
    dJointSetDBallParam(j, dParamCFM, cfm);
}

/* A contact joint between the joint's bodies as one of its rows this substep. */
static void add_row(pp_solver *s, solver_joint *sj, dContact *ct)
{
    PP_ASSERT(sj->row_count < SOLVER_JOINT_ROWS);
    dJointID j = dJointCreateContact(s->world, 0, ct);
    dJointAttach(j, sj->body1, sj->body2);
    dJointSetFeedback(j, part_feedback(sj, PART_ROWS + sj->row_count));
    sj->rows[sj->row_count++] = j;
}

void solver_joint_add_drive(pp_solver *s, solver_joint *sj, const solver_drive *d, double h)
{
    if (!sj->body1 || !(d->max_force[0] != 0 || d->max_force[1] != 0))
        return;
    const double q = s->inv_ppm, sg = joint_sign(sj), erp = dWorldGetERP(s->world);
    dContact ct = {0};
    /* The normal is z, where nothing moves, and may always separate: only the two friction rows act, in the
     * plane, each bounded by its mu as a force (no dContactApprox1) and driven at its motion. */
    ct.surface.mode = dContactMu2 | dContactFDir1 | dContactMotion1 | dContactMotion2 | dContactMotionN;
    ct.surface.mu = d->max_force[0] < 0 ? dInfinity : d->max_force[0] * q;
    ct.surface.mu2 = d->max_force[1] < 0 ? dInfinity : d->max_force[1] * q;
    ct.surface.motion1 = sg * (d->speed[0] - erp * d->error[0] / h) * q;
    ct.surface.motion2 = sg * (d->speed[1] - erp * d->error[1] / h) * q;
    ct.surface.motionN = -1e4; /* m/s: never reached */
    ct.geom.pos[0] = d->point.x * q;
    ct.geom.pos[1] = d->point.y * q;
    ct.geom.normal[2] = 1;
    ct.fdir1[0] = d->dir.x;
    ct.fdir1[1] = d->dir.y;
    add_row(s, sj, &ct);
}

void solver_joint_add_stop(pp_solver *s, solver_joint *sj, dvec2 point, dvec2 dir, double gap, double h)
{
    if (!sj->body1)
        return;
    const double q = s->inv_ppm, sg = joint_sign(sj);
    dContact ct = {0};
    /* ODE pushes its first body along the normal: b along dir, or a against it when b is the world. Past the
     * stop the depth corrects (the surface layer added back: a joint has no slop); short of it the row lets b
     * close the gap in this substep and no more. */
    ct.surface.mode = dContactMotionN;
    ct.surface.motionN = gap > 0 ? -gap / h * q : 0;
    ct.geom.pos[0] = point.x * q;
    ct.geom.pos[1] = point.y * q;
    ct.geom.normal[0] = sg * dir.x;
    ct.geom.normal[1] = sg * dir.y;
    ct.geom.depth = gap < 0 ? -gap * q + dWorldGetContactSurfaceLayer(s->world) : 0;
    add_row(s, sj, &ct);
}

void solver_joint_feedback(const solver_joint *sj, double out[6])
{
    for (int k = 0; k < 6; k++)
        out[k] = 0;
    for (int p = 0; p < PART_COUNT; p++) {
        const dJointFeedback *fb = part_feedback(sj, p);
        for (int k = 0; k < 3; k++)
            out[k] += fb->f1[k], out[3 + k] += fb->t1[k];
    }
}

void solver_joint_set_feedback(const solver_joint *sj, const double in[6])
{
    for (int p = 1; p < PART_COUNT; p++)
        zero_feedback(sj, p);
    dJointFeedback *fb = part_feedback(sj, PART_JOINT);
    for (int k = 0; k < 3; k++)
        fb->f1[k] = in[k], fb->t1[k] = in[3 + k];
}

void solver_joint_reaction(const pp_solver *s, const solver_joint *sj, dvec2 *force, double *torque)
{
    double fb[6];
    solver_joint_feedback(sj, fb);
    const double sg = joint_sign(sj); /* against the world, body_b (the world) takes the reverse */
    *force = dv(sg * fb[0] * s->ppm, sg * fb[1] * s->ppm);
    *torque = sg * fb[5] * s->ppm * s->ppm;
}

/* Plane-2D keeps positions in the plane but lets the orientation drift off the z axis; an awake body is
 * projected back to a pure z rotation, as ODE's own plane-2D demo does, and its state read at once. */
void solver_body_sync(const pp_solver *s, solver_body *sb, solver_body_state *out)
{
    dBodyID b = sb->body;
    const dReal *R = dBodyGetRotation(b), *w = dBodyGetAngularVel(b), *p = dBodyGetPosition(b);
    const dReal *v = dBodyGetLinearVel(b);
    *out = (solver_body_state){dv(p[0] * s->ppm, p[1] * s->ppm), atan2(R[4], R[0]), dv(v[0] * s->ppm, v[1] * s->ppm),
                               w[2], dBodyIsEnabled(b) != 0, 0, 0};
    const double half_c = cos(0.5 * out->angle), half_s = sin(0.5 * out->angle);
    turn_from_half(half_c, half_s, &out->cos_a, &out->sin_a);
    if (!out->awake)
        return;
    const double px = p[0], py = p[1], vx = v[0], vy = v[1], wz = w[2];
    set_rotation_half(sb, out->angle, half_c, half_s);
    dBodySetAngularVel(b, 0, 0, wz);
    dBodySetPosition(b, px, py, 0);
    dBodySetLinearVel(b, vx, vy, 0);
}

void solver_body_save(const solver_body *sb, solver_exact_state *out)
{
    dBodyID b = sb->body;
    const dReal *p = dBodyGetPosition(b), *v = dBodyGetLinearVel(b), *w = dBodyGetAngularVel(b);
    *out = (solver_exact_state){p[0], p[1], sb->rotation_angle, v[0], v[1], w[2], dBodyIsEnabled(b) != 0};
}

/* Rebuild exactly what ODE held: the rotation from the same angle by the same calls. */
void solver_body_restore(solver_body *sb, const solver_exact_state *in)
{
    dBodyID b = sb->body;
    dBodySetPosition(b, in->px, in->py, 0);
    set_rotation_z(sb, in->rotation_angle);
    dBodySetLinearVel(b, in->vx, in->vy, 0);
    dBodySetAngularVel(b, 0, 0, in->wz);
    if (in->enabled)
        dBodyEnable(b);
    else
        dBodyDisable(b);
}

uint64_t solver_get_steps(const pp_solver *s) { return s->steps; }
void solver_set_steps(pp_solver *s, uint64_t steps) { s->steps = steps; }

static void set_enabled(solver_body *const *list, int32_t n, bool enabled)
{
    for (int32_t i = 0; i < n; i++)
        if (enabled)
            dBodyEnable((dBodyID)list[i]->body);
        else
            dBodyDisable((dBodyID)list[i]->body);
}

/* The exact islands by dWorldStep. Its LCP can give up on an island's rows (a woken stack of two crates, whose
 * four contacts come in one order, did every substep) and then applies no contact force at all: the stack fell
 * through itself. Then the islands start again from where they were and QuickStep solves them, as it does
 * islands past exact_island_rows. */
static int step_exact(pp_solver *s, double h, solver_body *const *list, int32_t n)
{
    for (int32_t i = 0; i < n; i++)
        solver_body_save(list[i], &s->exact_from[i]);
    lcp_gave_up = false;
    const int ok = dWorldStep(s->world, h);
    if (!lcp_gave_up)
        return ok;
    for (int32_t i = 0; i < n; i++)
        solver_body_restore(list[i], &s->exact_from[i]);
    pp_log(1, "physpix: the exact solver gave up on an island this substep (ODE's LCP); QuickStep solved it");
    return dWorldQuickStep(s->world, h);
}

/* ODE steps only enabled bodies' islands, and no contact joins two islands: hiding the other lists' bodies
 * while one list's method runs steps each island once, by its own method, time step and iterations. The exact
 * lists go first: dWorldStep wakes every body of its islands, sleepers touched included, so showing them again
 * wakes nothing that it did not. The idle bodies stay hidden throughout. */
static int step_methods(pp_solver *s, double h, const solver_islands *is)
{
    int32_t runs = 0;
    for (int i = 0; i < SOLVE_IDLE; i++)
        runs += is->count[i] > 0;
    set_enabled(is->list[SOLVE_IDLE], is->count[SOLVE_IDLE], false);
    int ok = 1;
    for (int i = 0; i < SOLVE_IDLE; i++) {
        if (is->count[i] == 0)
            continue;
        for (int j = 0; j < SOLVE_IDLE && runs > 1; j++)
            if (j != i)
                set_enabled(is->list[j], is->count[j], false);
        const bool rest = i == SOLVE_QUICK_TWO_REST;
        if (rest)
            dWorldSetQuickStepNumIterations(s->world, s->rest_iterations);
        const double span = SOLVE_SPAN[i] * h;
        ok &= i <= SOLVE_EXACT_FOUR ? step_exact(s, span, is->list[i], is->count[i])
                                                     : dWorldQuickStep(s->world, span);
        if (rest)
            dWorldSetQuickStepNumIterations(s->world, s->iterations);
        for (int j = 0; j < SOLVE_IDLE && runs > 1; j++)
            if (j != i)
                set_enabled(is->list[j], is->count[j], true);
    }
    set_enabled(is->list[SOLVE_IDLE], is->count[SOLVE_IDLE], true);
    return ok;
}

/* QuickStep solves the joints in the order they were added, and that order biases it: a stack whose
 * pairs each have two points leans toward the point solved first. The order flips every time an island
 * is solved (by the step count, so snapshots keep it), and the biases cancel: islands solved every substep
 * by its parity, those solved every other substep (at every second count) by the next bit, those solved
 * every fourth by the bit after. No contact joins two islands, so each span's contacts go in their own order. */
static int span_order(uint8_t span) { return span == 4 ? 2 : span == 2 ? 1 : 0; }

static void attach_contacts(pp_solver *s, const solver_islands *is)
{
    if (s->pending_count == 0)
        return;
    bool stepped[3] = {false, false, false}; /* by span: h, 2·h, 4·h */
    for (int i = 0; i < SOLVE_IDLE; i++)
        stepped[span_order(SOLVE_SPAN[i])] |= is->count[i] > 0;
    const int32_t had = s->attached;
    for (int o = 0; o < 3; o++) {
        const bool reversed = (s->steps >> o & 1) != 0;
        for (int32_t n = 0; stepped[o] && n < s->pending_count; n++) {
            const pending_contact *p = &s->pending[reversed ? s->pending_count - 1 - n : n];
            if (span_order(p->c.span) == o)
                attach_contact(s, &p->c, p->k);
        }
    }
    for (int32_t n = 0; s->attached - had < s->pending_count && n < s->pending_count; n++)
        if (!stepped[span_order(s->pending[n].c.span)]) /* not attached: it applied nothing */
            memset(s->feedback[s->pending[n].k].f1, 0, sizeof s->feedback[s->pending[n].k].f1);
    s->pending_count = 0;
}

static void empty_contacts(pp_solver *s)
{
    if (s->attached > 0) /* ODE walks the group even when it is empty */
        dJointGroupEmpty(s->contacts);
    s->attached = 0;
}

bool solver_step(pp_solver *s, double h, const solver_islands *islands)
{
    int32_t exact = 0; /* the largest exact list, saved before its step */
    for (int i = SOLVE_EXACT; i <= SOLVE_EXACT_FOUR; i++)
        exact = islands->count[i] > exact ? islands->count[i] : exact;
    if (!ARRAY_RESERVE(s->exact_from, s->exact_from_capacity, exact)) {
        s->pending_count = 0; /* nothing attached: the caller undoes the step */
        return false;
    }
    attach_contacts(s, islands);
    if (solver_islands_empty(islands)) {
        s->steps++; /* the count still orders the joints and seeds the shuffle of later steps */
        empty_contacts(s);
        return true;
    }
    pthread_mutex_lock(&ode_step_lock);
    dRandSetSeed((unsigned long)(s->steps * 2654435761u + 12345u));
    const int ok = step_methods(s, h, islands);
    pthread_mutex_unlock(&ode_step_lock);
    s->steps++;
    empty_contacts(s);
    return ok != 0;
}
