/* Runtime properties: body and world settings changed between steps. Each takes effect at the next step,
 * keeps the pose, and wakes what it touches, so that a sleeping pile notices the change. */
#include "awake.h"
#include "check.h"
#include "edit.h"
#include "forces.h"
#include "joint.h"
#include "massprops.h"
#include "status.h"
#include "world.h"

#include <math.h>

/* Wake the body and every movable body whose box meets its own grown by a pixel (those it may touch). */
static void wake_touching(world *wd, body *bd)
{
    const pp_aabb b = bd->aabb;
    awake_wake_in_box(wd, (pp_aabb){b.x0 - 1, b.y0 - 1, b.x1 + 1, b.y1 + 1});
    if (bd->sb.body)
        awake_wake(wd, bd);
}

PP_API pp_status pp_body_set_friction(pp_world w, pp_body b, float friction)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_set_friction", &wd, &bd);
    if (st)
        return st;
    if ((st = body_check_surface("pp_body_set_friction", friction, bd->restitution, bd->linear_damping,
                                 bd->angular_damping)))
        return st;
    bd->friction = friction;
    wake_touching(wd, bd);
    return PP_OK;
}

PP_API pp_status pp_body_set_restitution(pp_world w, pp_body b, float restitution)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_set_restitution", &wd, &bd);
    if (st)
        return st;
    if ((st = body_check_surface("pp_body_set_restitution", bd->friction, restitution, bd->linear_damping,
                                 bd->angular_damping)))
        return st;
    bd->restitution = restitution;
    wake_touching(wd, bd);
    return PP_OK;
}

PP_API pp_status pp_body_set_damping(pp_world w, pp_body b, float linear, float angular)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_set_damping", &wd, &bd);
    if (st)
        return st;
    if ((st = body_check_surface("pp_body_set_damping", bd->friction, bd->restitution, linear, angular)))
        return st;
    bd->linear_damping = linear, bd->angular_damping = angular;
    wake_touching(wd, bd);
    return PP_OK;
}

PP_API pp_status pp_body_set_type(pp_world w, pp_body b, pp_body_type type)
{
    static const char *fn = "pp_body_set_type";
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, fn, &wd, &bd);
    if (st)
        return st;
    if (type != PP_BODY_STATIC && type != PP_BODY_DYNAMIC && type != PP_BODY_KINEMATIC)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: type %d is none of static, dynamic, kinematic", fn, (int)type);
    if (type == bd->type)
        return PP_OK;
    if (type == PP_BODY_DYNAMIC && !(mass_from_sums(&bd->sums, bd->raster.width, bd->raster.height, bd->density).mass > 0))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: the body's pixels weigh nothing, so it cannot be dynamic", fn);
    if (type == PP_BODY_STATIC && joint_needs_mover(wd, bd))
        return pp_fail(PP_ERR_INVALID_ARGUMENT,
                       "%s: a joint of the body would hold nothing that moves; destroy it first", fn);
    wake_touching(wd, bd); /* before: a static body is no mover to wake */
    body_remake_solver(wd, bd, type, bd->fixed_rotation);
    return PP_OK;
}

PP_API pp_status pp_body_set_fixed_rotation(pp_world w, pp_body b, uint32_t fixed)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_set_fixed_rotation", &wd, &bd);
    if (st)
        return st;
    if ((fixed != 0) == bd->fixed_rotation)
        return PP_OK;
    if (bd->sb.body)
        body_remake_solver(wd, bd, bd->type, fixed != 0);
    else
        bd->fixed_rotation = fixed != 0; /* a static body turns only when set_transform says so */
    wake_touching(wd, bd);
    return PP_OK;
}

PP_API pp_status pp_body_set_density(pp_world w, pp_body b, float density)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_set_density", &wd, &bd);
    if (st)
        return st;
    if (!(density > 0) || !isfinite(density))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_body_set_density: density must be finite and > 0, got %g", density);
    bd->density = density;
    if (bd->type == PP_BODY_DYNAMIC) /* mass and inertia scale; the velocity stays, as an edit keeps the material's */
        edit_update_solver_body(wd, bd);
    wake_touching(wd, bd);
    return PP_OK;
}

PP_API pp_status pp_body_set_filter(pp_world w, pp_body b, uint32_t category_bits, uint32_t mask_bits)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_set_filter", &wd, &bd);
    if (st)
        return st;
    bd->category_bits = category_bits, bd->mask_bits = mask_bits;
    wd->broad.cand_valid = false; /* the step candidates were filtered by the old bits */
    wake_touching(wd, bd); /* its resting pairs are tested again, now filtered */
    return PP_OK;
}

PP_API pp_status pp_body_set_awake(pp_world w, pp_body b, uint32_t awake)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_set_awake", &wd, &bd);
    if (st)
        return st;
    if (!bd->sb.body)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_body_set_awake: a static body never moves, awake or asleep");
    if (awake) {
        awake_wake(wd, bd);
        return PP_OK;
    }
    solver_body_sleep(&bd->sb); /* the awake set drops it at the next substep's start */
    awake_slept(wd, bd);
    bd->slow_time = wd->def.sleep_time + 1; /* asleep, as island_sleep marks a sleeper */
    return PP_OK;
}

PP_API pp_status pp_world_set_gravity(pp_world w, pp_vec2 gravity)
{
    world *wd = world_lookup(w, "pp_world_set_gravity");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!finite2(gravity.x, gravity.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_set_gravity: gravity must be finite, got (%g, %g)",
                       gravity.x, gravity.y);
    if (!(hypot(gravity.x, gravity.y) <= PP_MAX_ACCELERATION))
        return pp_fail(PP_ERR_INVALID_ARGUMENT,
                       "pp_world_set_gravity: gravity (%g, %g) px/s² is over PP_MAX_ACCELERATION (%g px/s²)",
                       gravity.x, gravity.y, PP_MAX_ACCELERATION);
    wd->def.gravity = gravity;
    solver_set_gravity(wd->solver, dv(gravity.x, gravity.y));
    for (int32_t i = 0; i < wd->body_ids.capacity; i++) /* gravity touches every body */
        if (wd->bodies[i] && wd->bodies[i]->sb.body)
            awake_wake(wd, wd->bodies[i]);
    return PP_OK;
}

PP_API pp_status pp_world_get_body_states(pp_world w, pp_body_state *out, int32_t capacity, int32_t *count)
{
    pp_status st;
    world *wd = world_lookup_list(w, "pp_world_get_body_states", out, capacity, count, &st);
    if (!wd)
        return st;
    int32_t n = 0;
    for (int32_t i = 0; i < wd->body_ids.capacity; i++) {
        const body *bd = wd->bodies[i];
        if (!bd)
            continue;
        if (n < capacity) {
            pp_body_state *s = &out[n];
            *s = (pp_body_state){.body = bd->handle, .position = {(float)bd->pos.x, (float)bd->pos.y},
                                 .angle = (float)bd->angle, .user_data = bd->user_data};
            if (bd->sb.body) {
                solver_body_state v;
                solver_body_get_state(wd->solver, &bd->sb, &v);
                s->linear_velocity = (pp_vec2){(float)v.velocity.x, (float)v.velocity.y};
                s->angular_velocity = (float)v.angular_velocity;
                s->awake = v.awake;
            }
        }
        n++;
    }
    *count = n;
    return PP_OK;
}

BODY_GETTER(pp_body_get_friction, float, (float)bd->friction)
BODY_GETTER(pp_body_get_restitution, float, (float)bd->restitution)
BODY_GETTER(pp_body_get_density, float, (float)bd->density)
BODY_GETTER(pp_body_get_gravity_scale, float, (float)bd->gravity_scale)
BODY_GETTER(pp_body_get_fixed_rotation, uint32_t, bd->fixed_rotation)
