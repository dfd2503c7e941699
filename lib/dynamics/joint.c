/* Joints: lookups (slots from the world's id pool, as the bodies'), creation from a def and
 * its checks, destruction, and the public pp_joint_* calls: values and reactions in pixels, motors, limits,
 * targets. What steps, edits, splits and snapshots do to joints is joint_step.c's. */
#include "joint.h"
#include "alloc.h"
#include "awake.h"
#include "cover.h"
#include "handle.h"
#include "status.h"

#include <float.h>
#include <stddef.h>
#include <math.h>
#include <string.h>

PP_API pp_joint_def pp_joint_def_default(pp_joint_type type)
{
    pp_joint_def d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.type = type >= PP_JOINT_REVOLUTE && type <= PP_JOINT_MOTOR ? type : PP_JOINT_REVOLUTE;
    d.axis = (pp_vec2){1, 0};
    d.correction_factor = 0.3f; /* Box2D's motor joint's */
    if (d.type == PP_JOINT_MOUSE) { /* Box2D's mouse joint: a soft pull */
        d.spring_hertz = 5.0f;
        d.spring_damping_ratio = 0.7f;
    }
    return d;
}

/* ---- the handle table ---- */

joint *joint_find(const world *wd, pp_joint j)
{
    const joint_table *t = &wd->joints;
    const uint32_t slot = handle_slot(j.id);
    if (handle_kind_of(j.id) != HANDLE_JOINT || handle_tag(j.id) != wd->tag ||
        !id_pool_current(&t->ids, slot, handle_gen(j.id)))
        return NULL;
    return t->items[slot];
}

static joint *joint_lookup(pp_world w, pp_joint j, const char *fn, world **wd)
{
    if (!(*wd = world_lookup(w, fn)))
        return NULL;
    joint *jt = joint_find(*wd, j);
    if (jt)
        return jt;
    const uint64_t owner = j.id && handle_tag(j.id) != (*wd)->tag ? world_id_of_tag(handle_tag(j.id)) : 0;
    if (handle_is_other_kind(j.id, HANDLE_JOINT))
        pp_fail(PP_ERR_INVALID_HANDLE, "%s: %#llx is %s handle, not a joint", fn, (unsigned long long)j.id,
                handle_kind_name(j.id));
    else if (owner)
        pp_fail(PP_ERR_INVALID_HANDLE, "%s: joint %#llx belongs to world %#llx, not %#llx", fn,
                (unsigned long long)j.id, (unsigned long long)owner, (unsigned long long)(*wd)->handle.id);
    else
        pp_fail(PP_ERR_INVALID_HANDLE, "%s: joint handle %#llx is null, destroyed, stale or of another world", fn,
                (unsigned long long)j.id);
    return NULL;
}

static body *side_body(const world *wd, pp_body b) { return b.id ? body_of(wd, b) : NULL; }
body *joint_body_a(const world *wd, const joint *jt) { return side_body(wd, jt->def.body_a); }
body *joint_body_b(const world *wd, const joint *jt) { return side_body(wd, jt->def.body_b); }

/* A slot for a new joint, growing the table; PP_ERR_OUT_OF_MEMORY or PP_ERR_LIMIT. */
static pp_status alloc_slot(world *wd, const char *fn, uint32_t *slot)
{
    switch (ID_POOL_TAKE(&wd->joints.ids, PP_MAX_BODIES, wd->joints.items, pp_realloc, slot)) {
    case ID_POOL_TAKEN:
        return PP_OK;
    case ID_POOL_FULL:
        return pp_fail(PP_ERR_LIMIT, "%s: a world holds at most %d joints", fn, PP_MAX_BODIES);
    default:
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d joints", fn, (int)wd->joints.ids.live + 1);
    }
}

void joint_free(world *wd, joint *jt)
{
    joint_table *t = &wd->joints;
    body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
    if (a)
        a->joint_count--;
    if (b)
        b->joint_count--;
    solver_joint_destroy(&jt->sj);
    t->items[jt->index] = NULL;
    id_pool_release(&t->ids, jt->index);
    pp_free(jt);
}

/* ---- creation ---- */

static dvec2 world_to_local(const body *bd, dvec2 p) { return bd ? body_world_to_local(bd, p) : p; }

static bool finite_f(double x) { return fabs(x) <= FLT_MAX; }

/* PP_ERR_INVALID_ARGUMENT naming `name` unless a motor's speed is within what a body may reach: PP_MAX_ANGULAR_SPEED
 * for a revolute joint's rad/s, PP_MAX_SPEED for a prismatic's px/s (FLT_MAX drove a pair 4.6e14 px in a step). */
static pp_status check_motor_speed(const char *fn, const char *name, pp_joint_type type, double speed)
{
    const bool turns = type == PP_JOINT_REVOLUTE || type == PP_JOINT_WHEEL;
    const double most = turns ? PP_MAX_ANGULAR_SPEED : PP_MAX_SPEED;
    if (!(fabs(speed) <= most))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s must be within ±%g %s (%s), got %g", fn, name, most,
                       turns ? "rad/s" : "px/s", turns ? "PP_MAX_ANGULAR_SPEED" : "PP_MAX_SPEED", speed);
    return PP_OK;
}

/* PP_ERR_INVALID_ARGUMENT naming the first field of a def out of its range. */
static pp_status check_def_values(const char *fn, const pp_joint_def *d)
{
    const struct { const char *name; double v; } nonneg[] = {
        {"max_motor_force", d->max_motor_force}, {"min_length", d->min_length}, {"max_length", d->max_length},
        {"spring_hertz", d->spring_hertz},       {"spring_damping_ratio", d->spring_damping_ratio},
        {"max_force", d->max_force},             {"break_force", d->break_force},
        {"angular_hertz", d->angular_hertz},     {"angular_damping_ratio", d->angular_damping_ratio},
        {"break_torque", d->break_torque},       {"max_torque", d->max_torque},
    };
    const double pts[] = {d->anchor_a.x, d->anchor_a.y, d->anchor_b.x, d->anchor_b.y};
    for (int i = 0; i < 4; i++)
        if (!finite_f(pts[i]))
            return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: anchor_a and anchor_b must be finite, got (%g, %g) and (%g, %g)",
                           fn, pts[0], pts[1], pts[2], pts[3]);
    for (size_t i = 0; i < sizeof nonneg / sizeof *nonneg; i++)
        if (!(nonneg[i].v >= 0) || !finite_f(nonneg[i].v))
            return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s must be finite and ≥ 0, got %g", fn, nonneg[i].name,
                           nonneg[i].v);
    pp_status st = check_motor_speed(fn, "motor_speed", d->type, d->motor_speed);
    if (st)
        return st;
    /* Every type keeps its def (snapshots and scenes write it whole), so a field it ignores is finite too. */
    const bool slides = d->type == PP_JOINT_PRISMATIC || d->type == PP_JOINT_WHEEL;
    if (!finite_f(d->axis.x) || !finite_f(d->axis.y) || (slides && !(hypot(d->axis.x, d->axis.y) > 0)))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: axis must be finite%s, got (%g, %g)", fn,
                       slides ? " and not zero" : "", d->axis.x, d->axis.y);
    if (!finite_f(d->target) || (d->type == PP_JOINT_REVOLUTE && !(fabs(d->target) <= PP_PI)))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: target must be finite%s, got %g", fn,
                       d->type == PP_JOINT_REVOLUTE ? " and within −π..π" : "", d->target);
    if (!finite_f(d->linear_offset.x) || !finite_f(d->linear_offset.y) || !finite_f(d->angular_offset))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: linear_offset and angular_offset must be finite, got (%g, %g) and %g",
                       fn, d->linear_offset.x, d->linear_offset.y, d->angular_offset);
    if (!(d->correction_factor >= 0 && d->correction_factor <= 1))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: correction_factor must lie within 0..1, got %g", fn,
                       d->correction_factor);
    if (!finite_f(d->lower) || !finite_f(d->upper))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: lower and upper must be finite, got %g and %g", fn, d->lower,
                       d->upper);
    if (d->max_length < d->min_length)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: min_length %g is more than max_length %g", fn, d->min_length,
                       d->max_length);
    return PP_OK;
}

/* PP_ERR_INVALID_ARGUMENT unless lower..upper is a range a joint of this type can hold. */
static pp_status check_limits(const char *fn, pp_joint_type type, double lower, double upper)
{
    if (!finite_f(lower) || !finite_f(upper) || !(lower <= upper))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: lower %g and upper %g must be finite, lower ≤ upper", fn, lower,
                       upper);
    if (type == PP_JOINT_REVOLUTE && !(lower >= -PP_PI && upper <= PP_PI))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: a revolute joint's lower and upper must lie within −π..π, got %g..%g", fn,
                       lower, upper);
    if (type == PP_JOINT_DISTANCE && !(lower >= 0))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: a distance joint's lengths must be ≥ 0, got %g..%g", fn, lower,
                       upper);
    return PP_OK;
}

/* A def's bodies: live in this world, not the same, at least one with an ODE body. */
static pp_status check_bodies(world *wd, const char *fn, const pp_joint_def *d, body **a, body **b)
{
    *a = *b = NULL;
    if (d->body_a.id && !(*a = body_lookup(wd, d->body_a, fn)))
        return PP_ERR_INVALID_HANDLE;
    if (d->body_b.id && !(*b = body_lookup(wd, d->body_b, fn)))
        return PP_ERR_INVALID_HANDLE;
    if (d->body_a.id == d->body_b.id)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: body_a and body_b are the same %s", fn,
                       d->body_a.id ? "body" : "static world (both zero)");
    if (d->type == PP_JOINT_MOUSE && (*a || !*b || !(*b)->sb.body))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: a mouse joint pulls a dynamic or kinematic body_b; body_a must be zero", fn);
    if (!(*a && (*a)->sb.body) && !(*b && (*b)->sb.body))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: neither body moves (both static or the world)", fn);
    return PP_OK;
}

/* An anchor a body can hold: within its bitmap grown by JOINT_REACH px or its own size on each side, so that
 * the solver's lever arms stay near the body's (ODE's exact solver aborts on astronomical ones). */
static bool anchor_in_reach(const body *bd, dvec2 p)
{
    const double w = bd->raster.width, h = bd->raster.height, m = fmax(JOINT_REACH, w + h);
    return p.x >= -m && p.x <= w + m && p.y >= -m && p.y <= h + m;
}

pp_status joint_check_anchors(const char *fn, const body *a, dvec2 local_a, const body *b, dvec2 local_b)
{
    if (a && !anchor_in_reach(a, local_a))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: anchor_a lies farther than %g px or the body's size from body_a's "
                       "bitmap (bitmap point (%g, %g))", fn, JOINT_REACH, local_a.x, local_a.y);
    if (b && !anchor_in_reach(b, local_b))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: the anchor on body_b (anchor_b; anchor_a of a revolute, weld or "
                       "mouse joint) lies farther than %g px or the body's size from its bitmap (bitmap point (%g, %g))",
                       fn, JOINT_REACH, local_b.x, local_b.y);
    return PP_OK;
}

/* Whether a bitmap point has a solid pixel within 1 px (the pixel's square, not its centre). */
bool joint_anchor_held(const body *bd, dvec2 p, int32_t *hx, int32_t *hy)
{
    const pp_raster *r = &bd->raster;
    double best = 2;
    if (!anchor_in_reach(bd, p))
        return false;
    for (int32_t y = (int32_t)floor(p.y) - 1; y <= (int32_t)floor(p.y) + 1; y++)
        for (int32_t x = (int32_t)floor(p.x) - 1; x <= (int32_t)floor(p.x) + 1; x++) {
            if (x < 0 || y < 0 || x >= r->width || y >= r->height || !raster_solid(r, x, y))
                continue;
            const double dx = fmax(0, fmax(x - p.x, p.x - (x + 1))), dy = fmax(0, fmax(y - p.y, p.y - (y + 1)));
            const double dist = hypot(dx, dy);
            if (dist <= 1 && dist < best)
                best = dist, *hx = x, *hy = y;
        }
    return best <= 1;
}

static bool anchor_pinned(const body *bd, dvec2 p)
{
    int32_t x, y;
    return bd && joint_anchor_held(bd, p, &x, &y);
}

pp_status joint_check_def(world *wd, const char *fn, const pp_joint_def *d)
{
    if (!(d->type >= PP_JOINT_REVOLUTE && d->type <= PP_JOINT_MOTOR))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: type %d is not a pp_joint_type", fn, (int)d->type);
    body *a, *b;
    pp_status st = check_bodies(wd, fn, d, &a, &b);
    if (st || (st = check_def_values(fn, d)))
        return st;
    return check_limits(fn, d->type, d->lower, d->upper);
}

PP_API pp_status pp_joint_create(pp_world w, const pp_joint_def *def, pp_joint *out)
{
    static const char *fn = "pp_joint_create";
    world *wd = world_lookup(w, fn);
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!def || !out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s is NULL", fn, def ? "out" : "def");
    joint *jt = NULL;
    pp_status st = joint_make(wd, def, fn, &jt);
    if (!st)
        *out = jt->handle;
    return st;
}

/* The def as this library's: one whose struct_size ends at user_data (before WHEEL and MOTOR) gets the later
 * fields' defaults. PP_ERR_ABI for any other size. */
static pp_status def_of_size(const char *fn, const pp_joint_def *def, pp_joint_def *out)
{
    const size_t v1 = offsetof(pp_joint_def, target);
    if (def->struct_size == sizeof *def) {
        *out = *def;
        return PP_OK;
    }
    if (def->struct_size != v1)
        return pp_fail(PP_ERR_ABI, "%s: def.struct_size is %u, this library's pp_joint_def is %u bytes (or %u before "
                       "WHEEL and MOTOR; use pp_joint_def_default)", fn, (unsigned)def->struct_size,
                       (unsigned)sizeof *def, (unsigned)v1);
    *out = pp_joint_def_default(def->type);
    memcpy(out, def, v1);
    out->struct_size = sizeof *out;
    return PP_OK;
}

pp_status joint_make(world *wd, const pp_joint_def *given, const char *fn, joint **out)
{
    pp_joint_def full;
    pp_status st = def_of_size(fn, given, &full);
    if (st)
        return st;
    const pp_joint_def *def = &full;
    st = joint_check_def(wd, fn, def);
    if (st)
        return st;
    body *a = side_body(wd, def->body_a), *b = side_body(wd, def->body_b);
    const bool one_anchor = def->type == PP_JOINT_REVOLUTE || def->type == PP_JOINT_WELD || def->type == PP_JOINT_MOUSE;
    dvec2 wa = dv(def->anchor_a.x, def->anchor_a.y), wb = one_anchor ? wa : dv(def->anchor_b.x, def->anchor_b.y);
    if (def->type == PP_JOINT_MOTOR) /* it holds each body by its centre of mass (the world by its origin) */
        wa = a ? body_com_world(a) : dv(0, 0), wb = b ? body_com_world(b) : dv(0, 0);
    if (def->type == PP_JOINT_DISTANCE && def->max_length == 0 && !(dv_norm(dv_sub(wb, wa)) >= 1e-3))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: a rigid distance joint's anchors coincide (use a revolute joint)", fn);
    const dvec2 local_a = def->type == PP_JOINT_MOUSE ? wa : world_to_local(a, wa), local_b = world_to_local(b, wb);
    if ((st = joint_check_anchors(fn, a, local_a, b, local_b)))
        return st;
    joint *jt = pp_calloc(1, sizeof *jt);
    if (!jt)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for the joint", fn);
    uint32_t slot = 0;
    if ((st = alloc_slot(wd, fn, &slot))) {
        pp_free(jt);
        return st;
    }
    if ((st = solver_joint_create(wd->solver, def->type, joint_soft_angle(def), fn, &jt->sj))) {
        id_pool_untake(&wd->joints.ids, slot);
        pp_free(jt);
        return st;
    }
    joint_table *t = &wd->joints;
    jt->index = slot;
    jt->handle = (pp_joint){handle_make(HANDLE_JOINT, wd->tag, slot, t->ids.generations[slot])};
    jt->def = *def;
    jt->local_a = local_a, jt->local_b = local_b;
    jt->pinned_a = anchor_pinned(a, jt->local_a), jt->pinned_b = anchor_pinned(b, jt->local_b);
    /* Only a prismatic joint has an axis (checked non-zero); another keeps the default's, so that a zero one it
     * ignores leaves no NaN in its state (fuzz_api: a revolute joint of axis (0, 0) could not be saved). */
    const dvec2 axis = def->type == PP_JOINT_PRISMATIC || def->type == PP_JOINT_WHEEL
                           ? dv_scale(dv(def->axis.x, def->axis.y), 1.0 / hypot(def->axis.x, def->axis.y))
                           : dv(1, 0);
    jt->axis_local = a ? dv_unrot(axis, a->cos_a, a->sin_a) : axis;
    t->items[slot] = jt;
    if (a)
        a->joint_count++;
    if (b)
        b->joint_count++;
    double value, speed;
    jt->ref = 0;
    joint_value(wd, jt, &value, &speed);
    jt->ref = def->type == PP_JOINT_REVOLUTE || def->type == PP_JOINT_PRISMATIC || def->type == PP_JOINT_WHEEL ? value
              : joint_soft_angle(def) ? (b ? b->angle : 0) - (a ? a->angle : 0) /* where its angular spring pulls */
                                      : 0;
    jt->length = def->type == PP_JOINT_DISTANCE ? value : 0;
    joint_attach(wd, jt);
    if (def->type == PP_JOINT_MOUSE)
        solver_joint_set_target(wd->solver, &jt->sj, wa);
    if (a && a->sb.body)
        awake_wake(wd, a);
    if (b && b->sb.body)
        awake_wake(wd, b);
    *out = jt;
    return PP_OK;
}

void joint_wake(world *wd, const joint *jt)
{
    body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
    if (a && a->sb.body)
        awake_wake(wd, a);
    if (b && b->sb.body)
        awake_wake(wd, b);
}

PP_API pp_status pp_joint_destroy(pp_world w, pp_joint j)
{
    world *wd;
    joint *jt = joint_lookup(w, j, "pp_joint_destroy", &wd);
    if (!jt)
        return PP_ERR_INVALID_HANDLE;
    joint_wake(wd, jt);
    joint_free(wd, jt);
    return PP_OK;
}

PP_API pp_status pp_world_get_joints(pp_world w, pp_joint *out, int32_t capacity, int32_t *count)
{
    pp_status st;
    world *wd = world_lookup_list(w, "pp_world_get_joints", out, capacity, count, &st);
    if (!wd)
        return st;
    int32_t n = 0;
    for (int32_t i = 0; i < wd->joints.ids.capacity; i++)
        if (wd->joints.items[i]) {
            if (n < capacity)
                out[n] = wd->joints.items[i]->handle;
            n++;
        }
    *count = n;
    return PP_OK;
}

/* A getter's joint with its out-pointer checked (`what` says which, e.g. "out is"); NULL and the status in *st
 * on failure. */
static joint *joint_for_out(pp_world w, pp_joint j, const char *fn, const void *out, const char *what, world **wd,
                            pp_status *st)
{
    joint *jt = joint_lookup(w, j, fn, wd);
    *st = jt ? PP_OK : PP_ERR_INVALID_HANDLE;
    if (jt && !out) {
        *st = pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s NULL", fn, what);
        return NULL;
    }
    return jt;
}

PP_API pp_status pp_joint_get_reaction(pp_world w, pp_joint j, pp_vec2 *force, float *torque)
{
    world *wd;
    pp_status st;
    joint *jt = joint_for_out(w, j, "pp_joint_get_reaction", force ? (void *)force : (void *)torque,
                              "force and torque are both", &wd, &st);
    if (!jt)
        return st;
    dvec2 f;
    double t;
    solver_joint_reaction(wd->solver, &jt->sj, &f, &t);
    if (force)
        *force = (pp_vec2){(float)f.x, (float)f.y};
    if (torque)
        *torque = (float)t;
    return PP_OK;
}

PP_API pp_status pp_joint_get_value(pp_world w, pp_joint j, float *value, float *speed)
{
    world *wd;
    pp_status st;
    joint *jt = joint_for_out(w, j, "pp_joint_get_value", value ? value : speed, "value and speed are both", &wd, &st);
    if (!jt)
        return st;
    double v, s;
    joint_value(wd, jt, &v, &s);
    if (value)
        *value = (float)v;
    if (speed)
        *speed = (float)s;
    return PP_OK;
}

PP_API pp_status pp_joint_set_motor(pp_world w, pp_joint j, uint32_t enabled, float speed, float max_force)
{
    static const char *fn = "pp_joint_set_motor";
    world *wd;
    joint *jt = joint_lookup(w, j, fn, &wd);
    if (!jt)
        return PP_ERR_INVALID_HANDLE;
    const pp_joint_type type = jt->def.type;
    if (type != PP_JOINT_REVOLUTE && type != PP_JOINT_PRISMATIC && type != PP_JOINT_WHEEL && type != PP_JOINT_DISTANCE)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: only revolute, prismatic, wheel and distance joints have motors", fn);
    if (!finite_f(max_force) || !(max_force >= 0))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: max_force must be finite and ≥ 0, got %g", fn, max_force);
    pp_status st = check_motor_speed(fn, "speed", type, speed);
    if (st)
        return st;
    if (type == PP_JOINT_DISTANCE && jt->def.enable_motor && !enabled) { /* a rigid one holds where the motor left it */
        double value, rate;
        joint_value(wd, jt, &value, &rate);
        jt->length = value;
        solver_joint_set_length(wd->solver, &jt->sj, true, jt->length);
    }
    jt->def.enable_motor = enabled != 0;
    jt->def.motor_speed = speed, jt->def.max_motor_force = max_force;
    if (type == PP_JOINT_REVOLUTE || type == PP_JOINT_PRISMATIC)
        solver_joint_set_motor(wd->solver, type, &jt->sj, enabled, speed, max_force);
    joint_wake(wd, jt);
    return PP_OK;
}

PP_API pp_status pp_joint_set_limits(pp_world w, pp_joint j, uint32_t enabled, float lower, float upper)
{
    static const char *fn = "pp_joint_set_limits";
    world *wd;
    joint *jt = joint_lookup(w, j, fn, &wd);
    if (!jt)
        return PP_ERR_INVALID_HANDLE;
    pp_joint_def *d = &jt->def;
    if (d->type != PP_JOINT_REVOLUTE && d->type != PP_JOINT_PRISMATIC && d->type != PP_JOINT_DISTANCE &&
        d->type != PP_JOINT_WHEEL)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: only revolute, prismatic, wheel and distance joints have limits", fn);
    pp_status st = check_limits(fn, d->type, lower, upper);
    if (st)
        return st;
    if (d->type == PP_JOINT_DISTANCE) { /* off: rigid at the creation length again */
        d->min_length = enabled ? lower : 0, d->max_length = enabled ? upper : 0;
    } else if (d->type == PP_JOINT_WHEEL) { /* rows set each substep */
        d->enable_limit = enabled != 0, d->lower = lower, d->upper = upper;
    } else {
        d->enable_limit = enabled != 0, d->lower = lower, d->upper = upper;
        solver_joint_set_limits(wd->solver, d->type, &jt->sj, enabled, lower - jt->slider_offset,
                                upper - jt->slider_offset);
    }
    joint_wake(wd, jt);
    return PP_OK;
}

PP_API pp_status pp_joint_set_target(pp_world w, pp_joint j, pp_vec2 target)
{
    static const char *fn = "pp_joint_set_target";
    world *wd;
    joint *jt = joint_lookup(w, j, fn, &wd);
    if (!jt)
        return PP_ERR_INVALID_HANDLE;
    if (jt->def.type != PP_JOINT_MOUSE)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: only mouse joints have a target", fn);
    if (!finite_f(target.x) || !finite_f(target.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: target must be finite, got (%g, %g)", fn, target.x, target.y);
    jt->local_a = dv(target.x, target.y);
    joint_wake(wd, jt);
    return PP_OK;
}

PP_API pp_status pp_joint_set_spring(pp_world w, pp_joint j, float hertz, float damping_ratio, float target)
{
    static const char *fn = "pp_joint_set_spring";
    world *wd;
    joint *jt = joint_lookup(w, j, fn, &wd);
    if (!jt)
        return PP_ERR_INVALID_HANDLE;
    pp_joint_def *d = &jt->def;
    if (d->type == PP_JOINT_MOUSE || d->type == PP_JOINT_MOTOR)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: only revolute, prismatic, wheel, distance and weld joints have a "
                       "spring", fn);
    if (!(hertz >= 0) || !finite_f(hertz) || !(damping_ratio >= 0) || !finite_f(damping_ratio))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: hertz and damping_ratio must be finite and ≥ 0, got %g and %g", fn,
                       hertz, damping_ratio);
    if (!finite_f(target) || (d->type == PP_JOINT_REVOLUTE && !(fabs(target) <= PP_PI)))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: target must be finite%s, got %g", fn,
                       d->type == PP_JOINT_REVOLUTE ? " and within −π..π" : "", target);
    if (d->type == PP_JOINT_DISTANCE && d->spring_hertz > 0 && !(hertz > 0)) /* rigid again where it is */
        solver_joint_set_length(wd->solver, &jt->sj, true, jt->length);
    d->spring_hertz = hertz, d->spring_damping_ratio = damping_ratio;
    if (d->type == PP_JOINT_REVOLUTE || d->type == PP_JOINT_PRISMATIC)
        d->target = target;
    joint_wake(wd, jt);
    return PP_OK;
}

PP_API pp_status pp_joint_set_offsets(pp_world w, pp_joint j, pp_vec2 linear, float angular)
{
    static const char *fn = "pp_joint_set_offsets";
    world *wd;
    joint *jt = joint_lookup(w, j, fn, &wd);
    if (!jt)
        return PP_ERR_INVALID_HANDLE;
    if (jt->def.type != PP_JOINT_MOTOR)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: only motor joints have offsets", fn);
    if (!finite_f(linear.x) || !finite_f(linear.y) || !finite_f(angular))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: linear and angular must be finite, got (%g, %g) and %g", fn,
                       linear.x, linear.y, angular);
    jt->def.linear_offset = linear, jt->def.angular_offset = angular;
    joint_wake(wd, jt);
    return PP_OK;
}

PP_API pp_status pp_joint_get_type(pp_world w, pp_joint j, pp_joint_type *out)
{
    world *wd;
    pp_status st;
    joint *jt = joint_for_out(w, j, "pp_joint_get_type", out, "out is", &wd, &st);
    if (jt)
        *out = jt->def.type;
    return st;
}

PP_API pp_status pp_joint_get_bodies(pp_world w, pp_joint j, pp_body *body_a, pp_body *body_b)
{
    world *wd;
    pp_status st;
    joint *jt = joint_for_out(w, j, "pp_joint_get_bodies", body_a && body_b ? body_a : NULL, "body_a or body_b is",
                              &wd, &st);
    if (jt)
        *body_a = jt->def.body_a, *body_b = jt->def.body_b;
    return st;
}

void joint_anchors(const world *wd, const joint *jt, dvec2 *a, dvec2 *b)
{
    const body *ba = joint_body_a(wd, jt), *bb = joint_body_b(wd, jt);
    *a = ba ? dv_add(ba->pos, dv_rot(dv_sub(jt->local_a, ba->pivot), ba->cos_a, ba->sin_a)) : jt->local_a;
    *b = bb ? dv_add(bb->pos, dv_rot(dv_sub(jt->local_b, bb->pivot), bb->cos_a, bb->sin_a)) : jt->local_b;
}

PP_API pp_status pp_joint_get_anchors(pp_world w, pp_joint j, pp_vec2 *anchor_a, pp_vec2 *anchor_b)
{
    world *wd;
    pp_status st;
    joint *jt = joint_for_out(w, j, "pp_joint_get_anchors", anchor_a ? (void *)anchor_a : (void *)anchor_b,
                              "anchor_a and anchor_b are both", &wd, &st);
    if (!jt)
        return st;
    dvec2 a, b;
    joint_anchors(wd, jt, &a, &b);
    if (anchor_a)
        *anchor_a = vec2_of(a);
    if (anchor_b)
        *anchor_b = vec2_of(b);
    return PP_OK;
}

PP_API pp_status pp_joint_get_user_data(pp_world w, pp_joint j, uint64_t *out)
{
    world *wd;
    pp_status st;
    joint *jt = joint_for_out(w, j, "pp_joint_get_user_data", out, "out is", &wd, &st);
    if (jt)
        *out = jt->def.user_data;
    return st;
}

void joint_free_all(world *wd)
{
    joint_table *t = &wd->joints;
    for (int32_t i = 0; i < t->ids.capacity; i++)
        if (t->items[i]) {
            solver_joint_destroy(&t->items[i]->sj);
            pp_free(t->items[i]);
        }
    pp_free(t->items);
    id_pool_free(&t->ids, pp_free);
    *t = (joint_table){0};
}
