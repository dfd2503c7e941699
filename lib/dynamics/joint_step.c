/* What steps, edits, splits and snapshots do to joints: values, attachment to ODE, each substep's springs,
 * ropes and mouse targets, breaking, anchors after edits and splits (kept as bitmap points of their bodies, so
 * the ODE joint re-attaches at the same material points after a split or a moved centre of mass), restore. */
#include "joint.h"
#include "alloc.h"
#include "status.h"

#include <math.h>

/* ---- geometry ---- */

static dvec2 local_to_world(const body *bd, dvec2 p)
{
    return bd ? dv_add(bd->pos, dv_rot(dv_sub(p, bd->pivot), bd->cos_a, bd->sin_a)) : p;
}
static double angle_of(const body *bd) { return bd ? bd->angle : 0.0; }

static dvec2 velocity_at(const world *wd, const body *bd, dvec2 p)
{
    return bd ? body_point_velocity(wd, bd, p) : dv(0, 0);
}

static double spin_of(const world *wd, const body *bd)
{
    if (!bd || !bd->sb.body)
        return 0;
    solver_body_state s;
    solver_body_get_state(wd->solver, &bd->sb, &s);
    return s.angular_velocity;
}

static double wrap_angle(double a) { return remainder(a, 2 * PP_PI); }

/* The joint's value and its rate, as pp_joint_get_value reports them. */
void joint_value(const world *wd, const joint *jt, double *value, double *speed)
{
    const body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
    const dvec2 pa = local_to_world(a, jt->local_a), pb = local_to_world(b, jt->local_b);
    const dvec2 dvel = dv_sub(velocity_at(wd, b, pb), velocity_at(wd, a, pa)), d = dv_sub(pb, pa);
    *value = *speed = 0;
    if (jt->def.type == PP_JOINT_REVOLUTE) {
        *value = wrap_angle(angle_of(b) - angle_of(a) - jt->ref);
        *speed = spin_of(wd, b) - spin_of(wd, a);
    } else if (jt->def.type == PP_JOINT_PRISMATIC || jt->def.type == PP_JOINT_WHEEL) {
        const dvec2 axis = a ? dv_rot(jt->axis_local, a->cos_a, a->sin_a) : jt->axis_local;
        *value = dv_dot(d, axis) - jt->ref;
        *speed = dv_dot(dvel, axis);
    } else if (jt->def.type == PP_JOINT_DISTANCE) {
        *value = dv_norm(d);
        *speed = *value > 0 ? dv_dot(dvel, d) / *value : 0;
    }
}

/* The bodies' mass as the joint's spring sees it: the reduced mass, a body that is not pushed counting as infinite. */
static double joint_mass(const world *wd, const joint *jt)
{
    const body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
    const double ia = a && a->type == PP_BODY_DYNAMIC ? 1.0 / a->mass.mass : 0;
    const double ib = b && b->type == PP_BODY_DYNAMIC ? 1.0 / b->mass.mass : 0;
    return ia + ib > 0 ? 1.0 / (ia + ib) : 0;
}

/* The pair's inertia about a world point as an angular spring there sees it, mass·px²: each pushed body's
 * inertia about the point (exact when the other side does not move, or both turn about their centres). */
static double joint_inertia(const world *wd, const joint *jt, dvec2 p)
{
    const body *side[2] = {joint_body_a(wd, jt), joint_body_b(wd, jt)};
    double inv = 0;
    for (int k = 0; k < 2; k++)
        if (side[k] && side[k]->type == PP_BODY_DYNAMIC) {
            const double r = dv_norm(dv_sub(body_com_world(side[k]), p));
            inv += 1.0 / (side[k]->mass.inertia + side[k]->mass.mass * r * r);
        }
    return inv > 0 ? 1.0 / inv : 0;
}

/* Attach the ODE joint with its recorded frame, then its limits, motor and length. */
static void attach_recorded(world *wd, joint *jt)
{
    const body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
    const pp_joint_def *d = &jt->def;
    const solver_joint_frame f = {a && a->sb.body ? &a->sb : NULL, b && b->sb.body ? &b->sb : NULL, jt->frame_a,
                                  jt->frame_b, jt->frame_axis, jt->frame_angle};
    solver_joint_attach(wd->solver, d->type, &jt->sj, &f);
    if (d->type == PP_JOINT_REVOLUTE || d->type == PP_JOINT_PRISMATIC) {
        solver_joint_set_limits(wd->solver, d->type, &jt->sj, d->enable_limit, d->lower - jt->slider_offset,
                                d->upper - jt->slider_offset);
        solver_joint_set_motor(wd->solver, d->type, &jt->sj, d->enable_motor, d->motor_speed, d->max_motor_force);
    }
    if (d->type == PP_JOINT_DISTANCE)
        solver_joint_set_length(wd->solver, &jt->sj, true, jt->length);
}

static dvec2 unit_or_x(dvec2 v)
{
    const double n = dv_norm(v);
    return n > 1e-9 ? dv_scale(v, 1.0 / n) : dv(1, 0);
}

/* Attach the ODE joint to its bodies as they are now, recording how for snapshots. */
void joint_attach(world *wd, joint *jt)
{
    const body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
    double value, speed;
    joint_value(wd, jt, &value, &speed);
    jt->frame_a = local_to_world(a, jt->local_a), jt->frame_b = local_to_world(b, jt->local_b);
    jt->frame_axis = a ? dv_rot(jt->axis_local, a->cos_a, a->sin_a) : jt->axis_local;
    jt->frame_angle = value;
    jt->at_a = jt->at_b = (solver_exact_state){0};
    if (a && a->sb.body)
        solver_body_save(&a->sb, &jt->at_a);
    if (b && b->sb.body)
        solver_body_save(&b->sb, &jt->at_b);
    jt->attach_order = wd->joints.next_attach++;
    jt->dirty = false;
    if (jt->def.type == PP_JOINT_PRISMATIC)
        jt->slider_offset = value;
    attach_recorded(wd, jt);
}

/* ---- the step, edits, removal ---- */

static bool joint_has(const joint *jt, const body *bd)
{
    return jt->def.body_a.id == bd->handle.id || jt->def.body_b.id == bd->handle.id;
}

void joint_body_removed(world *wd, body *bd)
{
    for (int32_t i = 0; bd->joint_count > 0 && i < wd->joints.ids.capacity; i++) {
        joint *jt = wd->joints.items[i];
        if (jt && joint_has(jt, bd)) {
            joint_wake(wd, jt);
            joint_free(wd, jt);
        }
    }
}

void joint_body_changed(world *wd, const body *bd)
{
    for (int32_t i = 0; bd->joint_count > 0 && i < wd->joints.ids.capacity; i++) {
        joint *jt = wd->joints.items[i];
        if (jt && joint_has(jt, bd))
            jt->dirty = true;
    }
}

bool joint_needs_mover(const world *wd, const body *bd)
{
    for (int32_t i = 0; bd->joint_count > 0 && i < wd->joints.ids.capacity; i++) {
        const joint *jt = wd->joints.items[i];
        if (!jt || !joint_has(jt, bd))
            continue;
        const body *other = jt->def.body_a.id == bd->handle.id ? joint_body_b(wd, jt) : joint_body_a(wd, jt);
        if (jt->def.type == PP_JOINT_MOUSE || !other || !other->sb.body)
            return true;
    }
    return false;
}

bool joint_keeps_apart(const world *wd, const body *a, const body *b)
{
    if (a->joint_count == 0 || b->joint_count == 0)
        return false;
    for (int32_t i = 0; i < wd->joints.ids.capacity; i++) {
        const joint *jt = wd->joints.items[i];
        if (jt && !jt->def.collide_connected && joint_has(jt, a) && joint_has(jt, b))
            return true;
    }
    return false;
}

static void joint_break(world *wd, joint *jt)
{
    world_queue_event(wd, (pp_event){.type = PP_EVENT_JOINT_BROKEN, .body = jt->def.body_a, .other = jt->def.body_b,
                                     .joint = jt->handle}); /* room reserved */
    joint_wake(wd, jt);
    joint_free(wd, jt);
}

/* One side of a joint on an edited body: false if its anchor lost its pixels; else moved onto the piece of the
 * split holding it (a massless piece, which is not made, breaks it). */
static bool anchor_follows(world *wd, const body *bd, const fracture_plan *p, pp_body *side, dvec2 *local, bool pinned)
{
    int32_t x, y, k;
    dvec2 origin;
    if (!pinned)
        return true;
    if (!joint_anchor_held(bd, *local, &x, &y))
        return false;
    if (!p || !fracture_island_at(p, x, y, &k, &origin) || k == p->keep)
        return true;
    if (!p->children[k].id)
        return false;
    body *piece = body_of(wd, p->children[k]);
    *side = piece->handle;
    *local = dv_sub(*local, origin);
    return true;
}

void joint_edit_done(world *wd, body *bd, const fracture_plan *p)
{
    for (int32_t i = 0; bd->joint_count > 0 && i < wd->joints.ids.capacity; i++) {
        joint *jt = wd->joints.items[i];
        if (!jt || !joint_has(jt, bd))
            continue;
        pp_joint_def *d = &jt->def;
        const pp_body a0 = d->body_a, b0 = d->body_b;
        const bool on_a = a0.id == bd->handle.id;
        const bool held = on_a ? anchor_follows(wd, bd, p, &d->body_a, &jt->local_a, jt->pinned_a)
                               : anchor_follows(wd, bd, p, &d->body_b, &jt->local_b, jt->pinned_b);
        if (!held) {
            joint_break(wd, jt);
            continue;
        }
        if (d->body_a.id != a0.id || d->body_b.id != b0.id) { /* onto a new piece (never the other side's body) */
            bd->joint_count--;
            body_of(wd, on_a ? d->body_a : d->body_b)->joint_count++;
        }
        jt->dirty = true;
    }
}

/* A rope only pulls at max_length and only pushes at min_length: one-sided stops along the anchors' line (their
 * lever arms are those of the anchors, which lie on it), slack between. A rod (max = min) is held by both. */
static void rope_prepare(world *wd, joint *jt, dvec2 pa, dvec2 pb, double h)
{
    const pp_joint_def *def = &jt->def;
    const double d = dv_norm(dv_sub(pb, pa));
    const dvec2 u = unit_or_x(dv_sub(pb, pa));
    solver_joint_set_length(wd->solver, &jt->sj, false, 0);
    solver_joint_add_stop(wd->solver, &jt->sj, pb, dv_scale(u, -1), def->max_length - d, h);
    if (def->min_length > 0)
        solver_joint_add_stop(wd->solver, &jt->sj, pb, u, d - def->min_length, h);
}

/* DISTANCE: a rope's stops, a winch's drive of the length (a rigid one's length is then the motor's). */
static void distance_prepare(world *wd, joint *jt, double h)
{
    const pp_joint_def *d = &jt->def;
    const body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
    const dvec2 pa = local_to_world(a, jt->local_a), pb = local_to_world(b, jt->local_b);
    const bool rope = d->spring_hertz == 0 && d->max_length > 0;
    if (rope)
        rope_prepare(wd, jt, pa, pb, h);
    if (!d->enable_motor)
        return;
    if (!rope && d->spring_hertz == 0)
        solver_joint_set_length(wd->solver, &jt->sj, false, 0);
    const solver_drive dr = {pb, unit_or_x(dv_sub(pb, pa)), {d->motor_speed, 0}, {0, 0}, {d->max_motor_force, 0}};
    solver_joint_add_drive(wd->solver, &jt->sj, &dr, h);
}

/* The spring of a slide (PRISMATIC toward target, WHEEL toward where it was made) on b's anchor along a's axis. */
static void slide_spring(world *wd, joint *jt, double target, double h)
{
    const pp_joint_def *d = &jt->def;
    const body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
    const dvec2 axis = a ? dv_rot(jt->axis_local, a->cos_a, a->sin_a) : jt->axis_local;
    double value, speed;
    joint_value(wd, jt, &value, &speed);
    const double m = joint_mass(wd, jt), omega = 2 * PP_PI * d->spring_hertz;
    solver_joint_linear_spring(wd->solver, &jt->sj, local_to_world(b, jt->local_b), axis, value - target,
                               m * omega * omega, 2 * m * d->spring_damping_ratio * omega, h);
}

/* An angular spring on b's angle from a: error rad, at the anchor's inertia. */
static void angle_spring(world *wd, joint *jt, double error, double hertz, double ratio, double h)
{
    const double I = joint_inertia(wd, jt, local_to_world(joint_body_b(wd, jt), jt->local_b));
    const double omega = 2 * PP_PI * hertz;
    solver_joint_angle_spring(wd->solver, &jt->sj, error, I * omega * omega, 2 * I * ratio * omega, h);
}

/* WHEEL: b's anchor held on a's axis line (its slide rigid without a spring), the slide's spring and limits,
 * the spin's motor. */
static void wheel_prepare(world *wd, joint *jt, double h)
{
    const pp_joint_def *d = &jt->def;
    const body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
    const dvec2 u = a ? dv_rot(jt->axis_local, a->cos_a, a->sin_a) : jt->axis_local, n = dv(-u.y, u.x);
    const dvec2 pa = local_to_world(a, jt->local_a), pb = local_to_world(b, jt->local_b);
    const double s = dv_dot(dv_sub(pb, pa), u) - jt->ref, off = dv_dot(dv_sub(pb, pa), n);
    const bool sprung = d->spring_hertz > 0;
    const solver_drive dr = {pb, u, {0, 0}, {s, off}, {sprung ? 0 : -1, -1}};
    solver_joint_add_drive(wd->solver, &jt->sj, &dr, h);
    if (sprung)
        slide_spring(wd, jt, 0, h);
    if (d->enable_limit) {
        solver_joint_add_stop(wd->solver, &jt->sj, pb, u, s - d->lower, h);
        solver_joint_add_stop(wd->solver, &jt->sj, pb, dv_scale(u, -1), d->upper - s, h);
    }
    if (d->enable_motor)
        solver_joint_angle_motor(wd->solver, &jt->sj, d->motor_speed, d->max_motor_force);
}

/* MOTOR: b's centre of mass driven toward linear_offset in a's frame and its angle toward angular_offset, each
 * at correction_factor of the error a substep, under max_force (shared between the error's direction and across
 * it as the last substep used it) and max_torque. */
static void motor_prepare(world *wd, joint *jt, double h)
{
    const pp_joint_def *d = &jt->def;
    const body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
    const dvec2 ca = a ? body_com_world(a) : dv(0, 0), cb = b ? body_com_world(b) : dv(0, 0);
    const dvec2 off = dv(d->linear_offset.x, d->linear_offset.y);
    const dvec2 goal = dv_add(ca, a ? dv_rot(off, a->cos_a, a->sin_a) : off), e = dv_sub(cb, goal);
    const dvec2 u = unit_or_x(e);
    const double beta = d->correction_factor / h;
    double f_perp = -1, f_along = -1;
    if (d->max_force > 0) {
        dvec2 f;
        double t;
        solver_joint_reaction(wd->solver, &jt->sj, &f, &t);
        const double along = fmin(fabs(dv_dot(f, u)), d->max_force);
        f_along = d->max_force;
        f_perp = fmax(sqrt(d->max_force * d->max_force - along * along), 1e-3 * d->max_force);
    }
    const solver_drive dr = {cb, u, {-beta * dv_norm(e), 0}, {0, 0}, {f_along, f_perp}};
    solver_joint_add_drive(wd->solver, &jt->sj, &dr, h);
    const double turn = wrap_angle(angle_of(b) - angle_of(a) - d->angular_offset);
    solver_joint_angle_motor(wd->solver, &jt->sj, -beta * turn, d->max_torque);
}

/* This substep's parts beside the ODE joint (none for a joint of the first part's kinds without the new
 * settings, which steps as before them). */
static void parts_prepare(world *wd, joint *jt, double h)
{
    const pp_joint_def *d = &jt->def;
    switch (d->type) {
    case PP_JOINT_REVOLUTE:
        if (d->spring_hertz > 0) {
            double value, speed;
            joint_value(wd, jt, &value, &speed);
            angle_spring(wd, jt, wrap_angle(value - d->target), d->spring_hertz, d->spring_damping_ratio, h);
        }
        break;
    case PP_JOINT_PRISMATIC:
        if (d->spring_hertz > 0)
            slide_spring(wd, jt, d->target, h);
        break;
    case PP_JOINT_DISTANCE: distance_prepare(wd, jt, h); break;
    case PP_JOINT_WELD:
        if (joint_soft_angle(d))
            angle_spring(wd, jt, wrap_angle(angle_of(joint_body_b(wd, jt)) - angle_of(joint_body_a(wd, jt)) - jt->ref),
                         d->angular_hertz, d->angular_damping_ratio, h);
        break;
    case PP_JOINT_WHEEL: wheel_prepare(wd, jt, h); break;
    case PP_JOINT_MOTOR: motor_prepare(wd, jt, h); break;
    default: break;
    }
}

/* The mouse's target, brought within max_force / k of the anchor so that the spring pulls no harder. */
static void mouse_prepare(world *wd, joint *jt, double k)
{
    const body *b = joint_body_b(wd, jt);
    const dvec2 pb = local_to_world(b, jt->local_b), e = dv_sub(jt->local_a, pb);
    const double len = dv_norm(e), cap = jt->def.max_force;
    dvec2 t = jt->local_a;
    if (cap > 0 && k > 0 && len * k > cap)
        t = dv_add(pb, dv_scale(e, cap / (k * len)));
    solver_joint_set_target(wd->solver, &jt->sj, t);
}

void joint_prepare(world *wd, double h)
{
    for (int32_t i = 0; wd->joints.ids.live > 0 && i < wd->joints.ids.capacity; i++) {
        joint *jt = wd->joints.items[i];
        if (!jt)
            continue;
        const pp_joint_def *d = &jt->def;
        if (jt->dirty)
            joint_attach(wd, jt);
        const double m = joint_mass(wd, jt), omega = 2 * PP_PI * d->spring_hertz;
        const double k = m * omega * omega, c = 2 * m * d->spring_damping_ratio * omega;
        if (d->type == PP_JOINT_DISTANCE || d->type == PP_JOINT_WELD || d->type == PP_JOINT_MOUSE)
            solver_joint_set_spring(wd->solver, d->type, &jt->sj, k, c, h);
        if (d->type == PP_JOINT_MOUSE)
            mouse_prepare(wd, jt, k);
        solver_joint_parts_begin(wd->solver, &jt->sj);
        parts_prepare(wd, jt, h);
    }
}

/* Whether the last substep's reaction passed break_force, or its torque about body_b's anchor break_torque. */
static bool over_break_force(const world *wd, const joint *jt)
{
    if (!(jt->def.break_force > 0) && !(jt->def.break_torque > 0))
        return false;
    dvec2 f;
    double t;
    solver_joint_reaction(wd->solver, &jt->sj, &f, &t);
    if (jt->def.break_force > 0 && dv_norm(f) > jt->def.break_force)
        return true;
    if (!(jt->def.break_torque > 0))
        return false;
    /* The reaction's torque is about b's centre of mass (a's against the world); about the anchor the force's
     * moment comes off, leaving what the joint's angle holds. */
    const body *b = joint_body_b(wd, jt), *a = joint_body_a(wd, jt);
    const body *on = b && b->sb.body ? b : a;
    const dvec2 anchor = local_to_world(on, on == b ? jt->local_b : jt->local_a), com = body_com_world(on);
    const dvec2 r = dv_sub(com, anchor);
    const double about = t + r.x * f.y - r.y * f.x; /* the reverse for a: the size is the same */
    return fabs(about) > jt->def.break_torque;
}

pp_status joint_step_done(world *wd)
{
    int32_t n = 0;
    for (int32_t i = 0; wd->joints.ids.live > 0 && i < wd->joints.ids.capacity; i++)
        n += wd->joints.items[i] && over_break_force(wd, wd->joints.items[i]);
    if (n == 0)
        return PP_OK;
    pp_status st = world_reserve_events(wd, n, "pp_world_step");
    if (st)
        return st;
    for (int32_t i = 0; i < wd->joints.ids.capacity; i++)
        if (wd->joints.items[i] && over_break_force(wd, wd->joints.items[i]))
            joint_break(wd, wd->joints.items[i]);
    return PP_OK;
}

/* ---- snapshots ---- */

/* Put a body's ODE body where `at` has it (pose only), saving where it was into *now. */
static void pose_body_at(const body *bd, const solver_exact_state *at, solver_exact_state *now)
{
    if (!bd || !bd->sb.body)
        return;
    solver_body_save(&bd->sb, now);
    solver_exact_state s = *now;
    s.px = at->px, s.py = at->py, s.rotation_angle = at->rotation_angle;
    solver_body_restore((solver_body *)&bd->sb, &s);
}

/* Whether a saved attach is one the API could have made: anchors in reach of the poses they were attached at,
 * unit axes. */
static bool attach_plausible(const world *wd, const joint *jt)
{
    const body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
    const double ppm = wd->def.pixels_per_meter;
    const body *side[2] = {a, b};
    const solver_exact_state *at[2] = {&jt->at_a, &jt->at_b};
    const dvec2 anchor[2] = {jt->frame_a, jt->frame_b};
    for (int k = 0; k < 2; k++)
        if (side[k] && side[k]->sb.body &&
            !(dv_norm(dv_sub(anchor[k], dv(at[k]->px * ppm, at[k]->py * ppm))) <=
              2 * (JOINT_REACH + side[k]->raster.width + side[k]->raster.height)))
            return false;
    return jt->def.type != PP_JOINT_PRISMATIC ||
           (fabs(dv_norm(jt->frame_axis) - 1) < 1e-6 && fabs(dv_norm(jt->axis_local) - 1) < 1e-6);
}

pp_status joint_restore(world *wd, joint *jt, const double feedback[6], const char *fn)
{
    joint_table *t = &wd->joints;
    body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
    if (!attach_plausible(wd, jt))
        return pp_fail(PP_ERR_FORMAT, "%s: joint %#llx was attached far from its bodies or along no axis", fn,
                       (unsigned long long)jt->handle.id);
    pp_status st = solver_joint_create(wd->solver, jt->def.type, joint_soft_angle(&jt->def), fn,
                                       &jt->sj);
    if (st)
        return st;
    solver_exact_state now_a, now_b;
    pose_body_at(a, &jt->at_a, &now_a);
    pose_body_at(b, &jt->at_b, &now_b);
    attach_recorded(wd, jt);
    if (a && a->sb.body)
        solver_body_restore(&a->sb, &now_a);
    if (b && b->sb.body)
        solver_body_restore(&b->sb, &now_b);
    solver_joint_set_feedback(&jt->sj, feedback);
    t->items[jt->index] = jt;
    id_pool_claim(&t->ids); /* joint_table_restore left its slot neither free nor live */
    if (a)
        a->joint_count++;
    if (b)
        b->joint_count++;
    return PP_OK;
}

pp_status joint_table_restore(world *wd, const uint32_t *generations, int32_t capacity, const uint32_t *free_slots,
                              int32_t free_count, const char *fn)
{
    joint_table *t = &wd->joints;
    PP_ASSERT(t->ids.capacity == 0 && free_count <= capacity);
    t->items = pp_calloc((size_t)capacity + 1, sizeof *t->items);
    if (!t->items || !id_pool_restore(&t->ids, generations, capacity, free_slots, free_count, pp_realloc))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d joint slots", fn, (int)capacity);
    return PP_OK;
}
