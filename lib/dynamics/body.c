/* Bodies: lookups (slots from the world's id pool, and the world's tag: handle.h), creation from a def, poses
 * and velocities. A pose is the world position of the pivot and an angle; ODE holds the centre of mass. */
#include "alloc.h"
#include "awake.h"
#include "forces.h"
#include "handle.h"
#include "joint.h"
#include "status.h"
#include "world.h"

#include <stdlib.h>
#include <string.h>

PP_API pp_body_def pp_body_def_default(void)
{
    pp_body_def d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.type = PP_BODY_DYNAMIC;
    d.density = 1.0f;
    d.friction = 0.6f;
    d.category_bits = 1;
    d.mask_bits = 0xffffffffu;
    d.alpha_threshold = 128;
    d.one_way_direction = (pp_vec2){0, -1};
    return d;
}

body *body_find(const world *wd, pp_body b)
{
    const uint32_t slot = handle_slot(b.id);
    if (handle_kind_of(b.id) != HANDLE_BODY || handle_tag(b.id) != wd->tag ||
        !id_pool_current(&wd->body_ids, slot, handle_gen(b.id)))
        return NULL;
    return wd->bodies[slot];
}

body *body_lookup(world *wd, pp_body b, const char *fn)
{
    body *bd = body_find(wd, b);
    if (bd)
        return bd;
    const uint64_t owner = b.id && handle_tag(b.id) != wd->tag ? world_id_of_tag(handle_tag(b.id)) : 0;
    if (handle_is_other_kind(b.id, HANDLE_BODY))
        pp_fail(PP_ERR_INVALID_HANDLE, "%s: %#llx is %s handle, not a body", fn, (unsigned long long)b.id,
                handle_kind_name(b.id));
    else if (owner)
        pp_fail(PP_ERR_INVALID_HANDLE, "%s: body %#llx belongs to world %#llx, not %#llx", fn, (unsigned long long)b.id,
                (unsigned long long)owner, (unsigned long long)wd->handle.id);
    else if (b.id && handle_tag(b.id) != wd->tag)
        pp_fail(PP_ERR_INVALID_HANDLE, "%s: body %#llx belongs to a world that no longer exists (slot %u), not %#llx",
                fn, (unsigned long long)b.id, (unsigned)tag_world_slot(handle_tag(b.id)),
                (unsigned long long)wd->handle.id);
    else
        pp_fail(PP_ERR_INVALID_HANDLE, "%s: body handle %#llx is null, destroyed or stale", fn,
                (unsigned long long)b.id);
    return NULL;
}

/* Look up both handles for a body call; returns the status to hand back. */
pp_status world_body_lookup(pp_world w, pp_body b, const char *fn, world **wd, body **bd)
{
    *wd = world_lookup(w, fn);
    if (!*wd)
        return PP_ERR_INVALID_HANDLE;
    *bd = body_lookup(*wd, b, fn);
    return *bd ? PP_OK : PP_ERR_INVALID_HANDLE;
}

body *body_lookup_out(pp_world w, pp_body b, const char *fn, const void *out, const char *out_name, world **wd,
                      pp_status *st)
{
    body *bd = NULL;
    if (!(*st = world_body_lookup(w, b, fn, wd, &bd)) && !out)
        *st = pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s is NULL", fn, out_name);
    return *st ? NULL : bd;
}

void body_update_pose_cache(body *bd)
{
    const pp_raster *r = &bd->raster;
    pp_aabb box = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    if (!raster_empty(r)) {
        /* Each corner is pos + R·(corner − pivot): x = pos.x + c·dx − s·dy, y = pos.y + s·dx + c·dy. Rounding
         * keeps order, so the corners' least x is the one from the least c·dx and the greatest s·dy, to the bit. */
        const double c = bd->cos_a, s = bd->sin_a;
        const double dx0 = r->x0 - bd->pivot.x, dx1 = r->x1 - bd->pivot.x;
        const double dy0 = r->y0 - bd->pivot.y, dy1 = r->y1 - bd->pivot.y;
        const double cx0 = c * dx0, cx1 = c * dx1, sx0 = s * dx0, sx1 = s * dx1;
        const double cy0 = c * dy0, cy1 = c * dy1, sy0 = s * dy0, sy1 = s * dy1;
        box.x0 = bd->pos.x + (dmin(cx0, cx1) - dmax(sy0, sy1));
        box.x1 = bd->pos.x + (dmax(cx0, cx1) - dmin(sy0, sy1));
        box.y0 = bd->pos.y + (dmin(sx0, sx1) + dmin(cy0, cy1));
        box.y1 = bd->pos.y + (dmax(sx0, sx1) + dmax(cy0, cy1));
#ifdef PP_CHECKS
        for (int k = 0; k < 4; k++) { /* every corner lies in the box */
            const double x = bd->pos.x + ((k & 1 ? cx1 : cx0) - (k & 2 ? sy1 : sy0));
            const double y = bd->pos.y + ((k & 1 ? sx1 : sx0) + (k & 2 ? cy1 : cy0));
            PP_ASSERT(!(x < box.x0 || x > box.x1 || y < box.y0 || y > box.y1));
        }
#endif
    }
    bd->aabb = box;
    body_update_com(bd);
}

void body_update_com(body *bd) { bd->com = body_com_of_pose(bd); }

/* A body is round when its inertia is within ROUND_INERTIA of a disc's of the same area (a pixel disc of
 * radius 3 px is 1.0145 of it, one of 16 px 1.0009, a square 1.047, an ellipse of aspect 1.2 1.017). */
#define ROUND_INERTIA 1.015

/* The radius of the disc a dynamic body's inertia matches, px, or 0 for a body that is not round. */
double body_round_radius(const body *bd)
{
    if (bd->type != PP_BODY_DYNAMIC || !(bd->mass.mass > 0))
        return 0;
    const double area = bd->mass.mass / bd->density; /* weighted pixels */
    return bd->mass.inertia <= ROUND_INERTIA * bd->mass.mass * area / (2 * PP_PI) ? sqrt(area / PP_PI) : 0;
}

void body_free(world *wd, body *bd)
{
    solver_body_destroy(wd->solver, &bd->sb);
    if (wd->gpu)
        gpu_narrow_forget(wd->gpu, &bd->raster);
    raster_free(&bd->raster);
    pp_free(bd->sprite);
    pp_free(bd);
}

pp_status body_check_surface(const char *fn, double friction, double restitution, double linear_damping,
                             double angular_damping)
{
    if (!(friction >= 0) || !isfinite(friction))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: friction must be finite and ≥ 0, got %g", fn, friction);
    if (!(restitution >= 0 && restitution <= 1))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: restitution must be in 0..1, got %g", fn, restitution);
    if (!(linear_damping >= 0 && angular_damping >= 0) || !isfinite(linear_damping) || !isfinite(angular_damping))
        return pp_fail(PP_ERR_INVALID_ARGUMENT,
                       "%s: linear_damping and angular_damping must be finite and ≥ 0, got %g and %g", fn, linear_damping,
                       angular_damping);
    return PP_OK;
}

bool body_speed_ok(dvec2 v, double w) { return hypot(v.x, v.y) <= PP_MAX_SPEED && fabs(w) <= PP_MAX_ANGULAR_SPEED; }

pp_status body_check_speed(const char *fn, const char *linear_name, dvec2 v, const char *angular_name, double w)
{
    if (body_speed_ok(v, w))
        return PP_OK;
    if (!(hypot(v.x, v.y) <= PP_MAX_SPEED))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s (%g, %g) px/s is faster than PP_MAX_SPEED (%g px/s)", fn,
                       linear_name, v.x, v.y, PP_MAX_SPEED);
    if (!(fabs(w) <= PP_MAX_ANGULAR_SPEED))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s %g rad/s is faster than PP_MAX_ANGULAR_SPEED (%g rad/s)", fn,
                       angular_name, w, PP_MAX_ANGULAR_SPEED);
    return PP_OK;
}

static pp_status check_body_def(const char *fn, const pp_body_def *d)
{
    if (d->struct_size != sizeof(pp_body_def))
        return pp_fail(PP_ERR_ABI, "%s: def->struct_size is %u, this library expects %u", fn,
                       (unsigned)d->struct_size, (unsigned)sizeof(pp_body_def));
    if ((uint32_t)d->type > PP_BODY_KINEMATIC)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: type %d is unknown", fn, (int)d->type);
    if (!finite2(d->position.x, d->position.y) || !isfinite(d->angle))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: position and angle must be finite", fn);
    if (d->custom_pivot && !finite2(d->pivot.x, d->pivot.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: pivot must be finite", fn);
    if (!finite2(d->linear_velocity.x, d->linear_velocity.y) || !isfinite(d->angular_velocity))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: linear_velocity and angular_velocity must be finite", fn);
    pp_status st = body_check_speed(fn, "linear_velocity", dv(d->linear_velocity.x, d->linear_velocity.y),
                                    "angular_velocity", d->angular_velocity);
    if (st)
        return st;
    if (!(d->density > 0) || !isfinite(d->density))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: density must be finite and > 0, got %g", fn, d->density);
    if ((st = body_check_surface(fn, d->friction, d->restitution, d->linear_damping, d->angular_damping)))
        return st;
    const double dl = hypot(d->one_way_direction.x, d->one_way_direction.y);
    if (d->one_way && !(dl > 0 && isfinite(dl)))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: one_way_direction must be finite and not zero", fn);
    return raster_check_def(fn, d);
}

/* Reserve a slot: the pool's next, or `want`, a restored slot that holds nothing. On failure nothing changes. */
static pp_status alloc_slot(world *wd, int64_t want, const char *fn, uint32_t *slot)
{
    if (want != BODY_ANY_SLOT) {
        *slot = (uint32_t)want;
        id_pool_claim(&wd->body_ids);
        return PP_OK;
    }
    switch (ID_POOL_TAKE(&wd->body_ids, PP_MAX_BODIES, wd->bodies, pp_realloc, slot)) {
    case ID_POOL_TAKEN:
        return PP_OK;
    case ID_POOL_FULL:
        return pp_fail(PP_ERR_LIMIT, "%s: the world already has %d bodies (PP_MAX_BODIES)", fn, PP_MAX_BODIES);
    default:
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d body slots", fn, (int)wd->body_ids.live + 1);
    }
}

PP_API pp_status pp_body_create(pp_world w, const pp_body_def *def, pp_body *out)
{
    world *wd = world_lookup(w, "pp_body_create");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!def || !out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_body_create: %s is NULL", def ? "out" : "def");
    body *bd = NULL;
    pp_status st = body_make(wd, def, BODY_ANY_SLOT, "pp_body_create", &bd);
    if (!st)
        *out = bd->handle;
    return st;
}

pp_status body_make(world *wd, const pp_body_def *def, int64_t want_slot, const char *fn, body **out)
{
    pp_status st = check_body_def(fn, def);
    if (st)
        return st;
    if (want_slot == BODY_ANY_SLOT && wd->body_ids.free_count == 0 && wd->body_ids.capacity >= PP_MAX_BODIES)
        return pp_fail(PP_ERR_LIMIT, "%s: the world already has %d bodies (PP_MAX_BODIES)", fn, PP_MAX_BODIES);
    if ((st = awake_reserve(wd, wd->body_ids.live + 1, fn)))
        return st;
    body *bd = pp_calloc(1, sizeof *bd);
    if (!bd)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory", fn);
    bd->awake_at = -1;
    bd->changed_at = -1;
    if ((st = raster_init(fn, &bd->raster, def))) {
        pp_free(bd);
        return st;
    }
    bd->type = def->type;
    if (def->rgba) {
        const size_t bytes = (size_t)def->width * (size_t)def->height * 4;
        if (!(bd->sprite = pp_malloc(bytes))) {
            body_free(wd, bd);
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for a %d × %d sprite", fn, (int)def->width,
                           (int)def->height);
        }
        memcpy(bd->sprite, def->rgba, bytes);
    }
    mass_sums_of_raster(&bd->sums, &bd->raster);
    if (def->type == PP_BODY_DYNAMIC && bd->raster.solid_count == 0)
        st = pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: a dynamic body needs solid pixels; the bitmap (%s) has none", fn,
                     def->mask ? "mask" : "rgba alpha");
    else if (def->type == PP_BODY_DYNAMIC && bd->sums.w == 0)
        st = pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: a dynamic body needs mass; its weights sum to zero", fn);
    if (st) {
        body_free(wd, bd);
        return st;
    }
    if (def->type != PP_BODY_STATIC)
        bd->mass = mass_from_sums(&bd->sums, bd->raster.width, bd->raster.height, def->density);
    bd->density = def->density;
    bd->friction = def->friction;
    bd->restitution = def->restitution;
    bd->linear_damping = def->linear_damping;
    bd->angular_damping = def->angular_damping;
    bd->category_bits = def->category_bits;
    bd->mask_bits = def->mask_bits;
    bd->fixed_rotation = def->fixed_rotation != 0;
    bd->detach_islands = def->detach_islands != 0;
    bd->bullet = def->bullet != 0;
    bd->is_sensor = def->is_sensor != 0;
    bd->one_way = def->one_way != 0;
    if (bd->one_way) /* unit length, so a snapshot writes back the direction it reads */
        bd->one_way_dir = dv_scale(dv(def->one_way_direction.x, def->one_way_direction.y),
                                   1.0 / hypot(def->one_way_direction.x, def->one_way_direction.y));
    else
        bd->one_way_dir = dv(0, -1);
    bd->user_data = def->user_data;
    bd->gravity_scale = 1;
    bd->pivot = def->custom_pivot ? dv(def->pivot.x, def->pivot.y) : dv(0.5 * def->width, 0.5 * def->height);
    bd->pos = dv(def->position.x, def->position.y);
    bd->angle = def->angle;
    angle_cos_sin(bd->angle, &bd->cos_a, &bd->sin_a);
    body_update_pose_cache(bd);

    if (def->type != PP_BODY_STATIC) {
        const solver_body_desc desc = {
            def->type, bd->mass.mass, bd->mass.inertia, body_com_world(bd), bd->angle,
            dv(def->linear_velocity.x, def->linear_velocity.y), def->fixed_rotation ? 0.0 : def->angular_velocity,
            bd->fixed_rotation, bd,
        };
        if ((st = solver_body_create(wd->solver, &desc, &bd->sb))) {
            body_free(wd, bd);
            return st;
        }
    }
    uint32_t slot = 0;
    if ((st = alloc_slot(wd, want_slot, fn, &slot))) {
        body_free(wd, bd);
        return st;
    }
    bd->index = slot;
    bd->handle.id = handle_make(HANDLE_BODY, wd->tag, slot, wd->body_ids.generations[slot]);
    wd->bodies[slot] = bd;
    bd->serial = wd->next_serial++;
    awake_add(wd, bd); /* its proxy is new */
    *out = bd;
    return PP_OK;
}

void body_unmake(world *wd, body *bd)
{
    const uint32_t slot = bd->index;
    awake_forget(wd, bd);
    forces_forget(wd, bd);
    body_free(wd, bd);
    wd->bodies[slot] = NULL;
    id_pool_untake(&wd->body_ids, slot);
    wd->next_serial--;
}

void body_remake_solver(world *wd, body *bd, pp_body_type type, bool fixed_rotation)
{
    solver_body_state s = {0};
    if (bd->sb.body) {
        solver_body_get_state(wd->solver, &bd->sb, &s);
        solver_body_destroy(wd->solver, &bd->sb);
    }
    bd->type = type;
    bd->fixed_rotation = fixed_rotation;
    bd->mass = type == PP_BODY_STATIC ? (pp_mass){0}
                                      : mass_from_sums(&bd->sums, bd->raster.width, bd->raster.height, bd->density);
    body_update_com(bd);
    if (type != PP_BODY_DYNAMIC) {
        forces_forget(wd, bd);
        bd->force = dv(0, 0), bd->torque = 0, bd->gravity_scale = 1;
    }
    if (type != PP_BODY_STATIC) {
        const solver_body_desc desc = {
            type, bd->mass.mass, bd->mass.inertia, body_com_world(bd), bd->angle, s.velocity,
            fixed_rotation ? 0.0 : s.angular_velocity, fixed_rotation, bd,
        };
        (void)solver_body_create(wd->solver, &desc, &bd->sb); /* ODE's creation cannot fail */
    }
    bd->slow_time = 0;
    carry_forget(wd, bd->index); /* a static body, now moving, or the reverse: its pairs are collided anew */
    bd->serial = wd->next_serial++; /* ODE's newest body: a snapshot remakes it last too */
    joint_body_changed(wd, bd);
    awake_moved(wd, bd); /* the broadphase hears of the new type; an awake body's queries see it anew */
}

void body_remove(world *wd, body *bd)
{
    const uint32_t slot = bd->index;
    const pp_body b = bd->handle;
    joint_body_removed(wd, bd);
    awake_forget(wd, bd);
    forces_forget(wd, bd);
    carry_forget(wd, slot);
    contact_table_body_removed(wd, b.id);
    body_free(wd, bd);
    wd->bodies[slot] = NULL;
    id_pool_release(&wd->body_ids, slot);
    /* Contacts of the last step may name this body; drop them so none is stale. */
    int32_t n = 0;
    for (int32_t i = 0; i < wd->contact_count; i++)
        if (wd->contacts[i].a.id != b.id && wd->contacts[i].b.id != b.id)
            wd->contacts[n++] = wd->contacts[i];
    wd->contact_count = n;
}

PP_API pp_status pp_body_destroy(pp_world w, pp_body b)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_destroy", &wd, &bd);
    if (st)
        return st;
    body_remove(wd, bd);
    return PP_OK;
}

BODY_GETTER(pp_body_get_position, pp_vec2, vec2_of(bd->pos))

BODY_GETTER(pp_body_get_angle, float, (float)bd->angle)

PP_API pp_status pp_body_set_transform(pp_world w, pp_body b, pp_vec2 position, float angle)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_set_transform", &wd, &bd);
    if (st)
        return st;
    if (!finite2(position.x, position.y) || !isfinite(angle))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_body_set_transform: position and angle must be finite");
    bd->pos = dv(position.x, position.y);
    bd->angle = bd->fixed_rotation ? bd->angle : angle;
    angle_cos_sin(bd->angle, &bd->cos_a, &bd->sin_a);
    body_update_pose_cache(bd);
    awake_moved(wd, bd);
    if (bd->sb.body) {
        solver_body_set_pose(wd->solver, &bd->sb, body_com_world(bd), bd->angle);
        awake_wake(wd, bd);
    }
    return PP_OK;
}

PP_API pp_status pp_body_get_velocity(pp_world w, pp_body b, pp_vec2 *linear, float *angular)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_get_velocity", &wd, &bd);
    if (st)
        return st;
    solver_body_state s = {0};
    if (bd->sb.body)
        solver_body_get_state(wd->solver, &bd->sb, &s);
    if (linear)
        *linear = (pp_vec2){(float)s.velocity.x, (float)s.velocity.y};
    if (angular)
        *angular = (float)s.angular_velocity;
    return PP_OK;
}

PP_API pp_status pp_body_set_velocity(pp_world w, pp_body b, pp_vec2 linear, float angular)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_set_velocity", &wd, &bd);
    if (st)
        return st;
    if (!finite2(linear.x, linear.y) || !isfinite(angular))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_body_set_velocity: linear and angular velocity must be finite");
    if ((st = body_check_speed("pp_body_set_velocity", "linear velocity", dv(linear.x, linear.y), "angular velocity",
                               angular)))
        return st;
    if (!bd->sb.body)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_body_set_velocity: a static body cannot move");
    solver_body_set_velocity(wd->solver, &bd->sb, dv(linear.x, linear.y), bd->fixed_rotation ? 0.0 : angular);
    awake_wake(wd, bd);
    return PP_OK;
}

void body_velocity_after_impulse(const world *wd, const body *bd, dvec2 impulse, dvec2 world_point, dvec2 *v,
                                 double *w)
{
    solver_body_state s;
    solver_body_get_state(wd->solver, &bd->sb, &s);
    const dvec2 r = dv_sub(world_point, s.com_world);
    *v = dv_add(s.velocity, dv_scale(impulse, 1.0 / bd->mass.mass));
    *w = bd->fixed_rotation ? 0.0 : s.angular_velocity + (r.x * impulse.y - r.y * impulse.x) / bd->mass.inertia;
}

PP_API pp_status pp_body_apply_impulse(pp_world w, pp_body b, pp_vec2 impulse, pp_vec2 world_point)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_apply_impulse", &wd, &bd);
    if (st)
        return st;
    if (!finite2(impulse.x, impulse.y) || !finite2(world_point.x, world_point.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_body_apply_impulse: impulse and world_point must be finite");
    if (bd->type != PP_BODY_DYNAMIC)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_body_apply_impulse: only dynamic bodies take impulses");
    dvec2 v;
    double wz;
    body_velocity_after_impulse(wd, bd, dv(impulse.x, impulse.y), dv(world_point.x, world_point.y), &v, &wz);
    /* Past the motion limits, refused as pp_body_set_velocity would refuse it (an impulse of 1e30 at 1e30 px from
     * a small body gave 2e55 rad/s, which ODE stepped to NaN; found by fuzz_api). */
    if ((st = body_check_speed("pp_body_apply_impulse", "the velocity the impulse gives,", v,
                               "the angular velocity the impulse gives,", wz)))
        return st;
    solver_body_set_velocity(wd->solver, &bd->sb, v, wz);
    awake_wake(wd, bd);
    return PP_OK;
}

PP_API pp_status pp_body_get_mass(pp_world w, pp_body b, float *mass, pp_vec2 *local_center, float *inertia)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_get_mass", &wd, &bd);
    if (st)
        return st;
    const dvec2 c = body_com_local(bd);
    if (mass)
        *mass = (float)bd->mass.mass;
    if (local_center)
        *local_center = (pp_vec2){(float)c.x, (float)c.y};
    if (inertia)
        *inertia = (float)bd->mass.inertia;
    return PP_OK;
}

PP_API pp_status pp_body_get_memory(pp_world w, pp_body b, int64_t *collision_bytes, int64_t *sprite_bytes)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_get_memory", &wd, &bd);
    if (st)
        return st;
    if (collision_bytes)
        *collision_bytes = raster_memory_bytes(&bd->raster);
    if (sprite_bytes)
        *sprite_bytes = bd->sprite ? 4 * (int64_t)bd->raster.width * bd->raster.height : 0;
    return PP_OK;
}

PP_API pp_status pp_body_is_awake(pp_world w, pp_body b, int32_t *awake)
{
    world *wd;
    pp_status st;
    body *bd = body_lookup_out(w, b, "pp_body_is_awake", awake, "awake", &wd, &st);
    if (!bd)
        return st;
    *awake = bd->sb.body ? solver_body_is_awake(&bd->sb) : 0;
    return PP_OK;
}

BODY_GETTER(pp_body_get_user_data, uint64_t, bd->user_data)

BODY_GETTER(pp_body_get_pivot, pp_vec2, vec2_of(bd->pivot))

BODY_GETTER(pp_body_get_type, pp_body_type, bd->type)

PP_API pp_status pp_body_read_rgba(pp_world w, pp_body b, uint8_t *out, int64_t capacity)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_read_rgba", &wd, &bd);
    if (st)
        return st;
    const pp_raster *r = &bd->raster;
    const int64_t need = (int64_t)r->width * r->height * 4;
    if (!out || capacity < need)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_body_read_rgba: out is NULL or capacity %lld < %lld bytes",
                       (long long)capacity, (long long)need);
    for (int32_t y = 0; y < r->height; y++)
        for (int32_t x = 0; x < r->width; x++) {
            const int64_t k = ((int64_t)y * r->width + x) * 4;
            const uint8_t gray = (uint8_t)raster_weight(r, x, y);
            const uint8_t look[4] = {gray, gray, gray, 255};
            if (!raster_solid(r, x, y))
                memset(out + k, 0, 4);
            else
                memcpy(out + k, bd->sprite ? bd->sprite + k : look, 4);
        }
    return PP_OK;
}

dvec2 body_point_velocity(const world *wd, const body *bd, dvec2 p)
{
    if (!bd->sb.body)
        return dv(0, 0);
    solver_body_state s;
    solver_body_get_state(wd->solver, &bd->sb, &s);
    const dvec2 r = dv_sub(p, s.com_world);
    return dv(s.velocity.x - s.angular_velocity * r.y, s.velocity.y + s.angular_velocity * r.x);
}
