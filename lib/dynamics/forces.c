/* Forces, torques, gravity scales and damping (forces.h). A force or torque applies through every substep of the
 * next step and is then spent, as Box2D's are; a gravity scale stays until set back to 1. */
#include "alloc.h"
#include "forces.h"
#include "awake.h"
#include "check.h"
#include "status.h"
#include "world.h"

#include <float.h>
#include <math.h>

pp_status forces_list(world *wd, body *bd, const char *fn)
{
    if (bd->forced)
        return PP_OK;
    if (!ARRAY_RESERVE(wd->forced.slots, wd->forced.capacity, wd->forced.count + 1))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory to list %d bodies under forces", fn,
                       (int)wd->forced.count + 1);
    wd->forced.slots[wd->forced.count++] = (int32_t)bd->index;
    bd->forced = true;
    return PP_OK;
}

void forces_forget(world *wd, body *bd)
{
    if (!bd->forced)
        return;
    int32_t n = 0;
    for (int32_t i = 0; i < wd->forced.count; i++)
        if (wd->forced.slots[i] != (int32_t)bd->index)
            wd->forced.slots[n++] = wd->forced.slots[i];
    wd->forced.count = n;
    bd->forced = false;
}

void forces_apply(world *wd)
{
    const dvec2 g = dv(wd->def.gravity.x, wd->def.gravity.y);
    for (int32_t i = 0; i < wd->forced.count; i++) {
        const body *bd = wd->bodies[wd->forced.slots[i]];
        if (!solver_body_is_awake(&bd->sb) || wd->islands.span[bd->index] == SPAN_SKIP)
            continue; /* ODE keeps the sum of a body it does not step: it would get every substep's at once */
        const dvec2 f = dv_add(bd->force, dv_scale(g, (bd->gravity_scale - 1) * bd->mass.mass));
        solver_body_add_force(wd->solver, &bd->sb, f, bd->fixed_rotation ? 0.0 : bd->torque);
    }
}

void forces_damp(world *wd, double h)
{
    for (int32_t k = 0; k < wd->awake.count; k++) {
        const body *bd = wd->bodies[wd->awake.slots[k]];
        if (bd->type != PP_BODY_DYNAMIC || (bd->linear_damping == 0 && bd->angular_damping == 0) ||
            !solver_body_is_awake(&bd->sb))
            continue;
        solver_body_state s;
        solver_body_get_state(wd->solver, &bd->sb, &s);
        solver_body_set_velocity(wd->solver, &bd->sb, dv_scale(s.velocity, exp(-bd->linear_damping * h)),
                                 s.angular_velocity * exp(-bd->angular_damping * h));
    }
}

void forces_step_done(world *wd)
{
    int32_t n = 0;
    for (int32_t i = 0; i < wd->forced.count; i++) {
        body *bd = wd->bodies[wd->forced.slots[i]];
        bd->force = dv(0, 0), bd->torque = 0;
        if (bd->gravity_scale != 1)
            wd->forced.slots[n++] = wd->forced.slots[i];
        else
            bd->forced = false;
    }
    wd->forced.count = n;
}

void forces_step_undone(world *wd)
{
    for (int32_t i = 0; i < wd->forced.count; i++)
        solver_body_clear_force(&wd->bodies[wd->forced.slots[i]]->sb);
}

/* The body a force call acts on: dynamic, listed, awake. */
static pp_status forced_body(pp_world w, pp_body b, const char *fn, world **wd, body **bd)
{
    pp_status st = world_body_lookup(w, b, fn, wd, bd);
    if (st)
        return st;
    if ((*bd)->type != PP_BODY_DYNAMIC)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: only dynamic bodies take forces", fn);
    return forces_list(*wd, *bd, fn);
}

/* PP_ERR_INVALID_ARGUMENT unless every value is finite and under what a float holds. */
static pp_status check_finite(const char *fn, const char *what, const double *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!(fabs(v[i]) <= FLT_MAX))
            return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s must be finite, got %g", fn, what, v[i]);
    return PP_OK;
}

PP_API pp_status pp_body_apply_force(pp_world w, pp_body b, pp_vec2 force, pp_vec2 world_point)
{
    static const char *fn = "pp_body_apply_force";
    const double v[4] = {force.x, force.y, world_point.x, world_point.y};
    world *wd;
    body *bd;
    pp_status st = check_finite(fn, "force and world_point", v, 4);
    if (st || (st = forced_body(w, b, fn, &wd, &bd)))
        return st;
    const dvec2 f = dv(force.x, force.y), r = dv_sub(dv(world_point.x, world_point.y), body_com_world(bd));
    bd->force = dv_add(bd->force, f);
    bd->torque += r.x * f.y - r.y * f.x;
    awake_wake(wd, bd);
    return PP_OK;
}

PP_API pp_status pp_body_apply_torque(pp_world w, pp_body b, float torque)
{
    static const char *fn = "pp_body_apply_torque";
    const double v = torque;
    world *wd;
    body *bd;
    pp_status st = check_finite(fn, "torque", &v, 1);
    if (st || (st = forced_body(w, b, fn, &wd, &bd)))
        return st;
    bd->torque += torque;
    awake_wake(wd, bd);
    return PP_OK;
}

PP_API pp_status pp_body_set_gravity_scale(pp_world w, pp_body b, float scale)
{
    static const char *fn = "pp_body_set_gravity_scale";
    const double v = scale;
    world *wd;
    body *bd;
    pp_status st = check_finite(fn, "scale", &v, 1);
    if (!st && !(fabsf(scale) <= PP_MAX_GRAVITY_SCALE)) /* at 1e10 a body crossed 6.8e8 px in one step */
        st = pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: scale must be in -%g..%g (PP_MAX_GRAVITY_SCALE), got %g", fn,
                     PP_MAX_GRAVITY_SCALE, PP_MAX_GRAVITY_SCALE, scale);
    if (st || (st = forced_body(w, b, fn, &wd, &bd)))
        return st;
    bd->gravity_scale = scale;
    awake_wake(wd, bd);
    return PP_OK;
}

PP_API pp_status pp_body_apply_angular_impulse(pp_world w, pp_body b, float impulse)
{
    static const char *fn = "pp_body_apply_angular_impulse";
    const double v = impulse;
    world *wd;
    body *bd;
    pp_status st = check_finite(fn, "impulse", &v, 1);
    if (st || (st = world_body_lookup(w, b, fn, &wd, &bd)))
        return st;
    if (bd->type != PP_BODY_DYNAMIC)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: only dynamic bodies take impulses", fn);
    if (bd->fixed_rotation)
        return PP_OK; /* its rotation is held: the impulse is taken up, as a contact's would be */
    solver_body_state s;
    solver_body_get_state(wd->solver, &bd->sb, &s);
    const double wz = s.angular_velocity + impulse / bd->mass.inertia;
    if ((st = body_check_speed(fn, "the velocity", s.velocity, "the angular velocity the impulse gives,", wz)))
        return st;
    solver_body_set_velocity(wd->solver, &bd->sb, s.velocity, wz);
    awake_wake(wd, bd);
    return PP_OK;
}

void forces_free(forced_list *f)
{
    pp_free(f->slots);
    *f = (forced_list){0};
}
