/* pp_world_debug_draw: the world's physics as line segments for a host to draw. Bodies come from the broadphase
 * and the awake set (awake_bodies_in_box), so a view of part of a large world reads only what it shows; each
 * body's outline is its raster's cached one (collide/outline.c), rebuilt only after an edit. */
#include "alloc.h"
#include "awake.h"
#include "joint.h"
#include "outline.h"
#include "status.h"
#include "world.h"

#include <float.h>

/* The segments being written: up to capacity of them, all counted. */
typedef struct seg_out {
    pp_debug_segment *out;
    int32_t capacity;
    int64_t count;
    pp_aabb view;
} seg_out;

static void put(seg_out *o, dvec2 a, dvec2 b, uint32_t rgba, pp_debug_kind kind, pp_body owner)
{
    if (o->count < o->capacity)
        o->out[o->count] = (pp_debug_segment){vec2_of(a), vec2_of(b), rgba, kind, owner};
    o->count++;
}

static bool in_view(const seg_out *o, dvec2 p)
{
    return p.x >= o->view.x0 && p.x <= o->view.x1 && p.y >= o->view.y0 && p.y <= o->view.y1;
}

static dvec2 to_world(const body *bd, dvec2 local)
{
    return dv_add(bd->pos, dv_rot(dv_sub(local, bd->pivot), bd->cos_a, bd->sin_a));
}

/* A body's colour by its state; the header lists the precedence. */
static uint32_t state_color(const body *bd)
{
    if (bd->is_sensor)
        return PP_DEBUG_COLOR_SENSOR;
    if (bd->type == PP_BODY_STATIC)
        return PP_DEBUG_COLOR_STATIC;
    if (!awake_mover(bd))
        return PP_DEBUG_COLOR_ASLEEP;
    return bd->type == PP_BODY_KINEMATIC ? PP_DEBUG_COLOR_KINEMATIC : PP_DEBUG_COLOR_AWAKE;
}

/* The outline's runs whose world bounds meet the view, turned with the body. */
static void put_outline(seg_out *o, const body *bd, const raster_outline *ol, uint32_t rgba)
{
    const double c = bd->cos_a, s = bd->sin_a;
    const dvec2 origin = to_world(bd, dv(0, 0)); /* bitmap (0, 0) in the world; then x·(c, s) + y·(−s, c) */
    for (int32_t k = 0; k < ol->count; k++) {
        const outline_run *r = &ol->runs[k];
        const dvec2 a = dv(origin.x + r->ax * c - r->ay * s, origin.y + r->ax * s + r->ay * c);
        const dvec2 b = dv(origin.x + r->bx * c - r->by * s, origin.y + r->bx * s + r->by * c);
        if (fmin(a.x, b.x) <= o->view.x1 && fmax(a.x, b.x) >= o->view.x0 && fmin(a.y, b.y) <= o->view.y1 &&
            fmax(a.y, b.y) >= o->view.y0)
            put(o, a, b, rgba, PP_DEBUG_OUTLINE, bd->handle);
    }
}

static void put_body(seg_out *o, const world *wd, const body *bd, uint32_t flags, const raster_outline *ol)
{
    const uint32_t rgba = state_color(bd);
    if (ol)
        put_outline(o, bd, ol, rgba);
    if (flags & PP_DEBUG_DRAW_AABBS) {
        const pp_aabb *x = &bd->aabb;
        const dvec2 p[4] = {dv(x->x0, x->y0), dv(x->x1, x->y0), dv(x->x1, x->y1), dv(x->x0, x->y1)};
        for (int k = 0; k < 4; k++)
            put(o, p[k], p[(k + 1) & 3], rgba, PP_DEBUG_AABB, bd->handle);
    }
    const dvec2 com = body_com_world(bd);
    if (flags & PP_DEBUG_DRAW_CENTERS) {
        const double len = PP_DEBUG_AXIS_LENGTH;
        put(o, com, dv_add(com, dv(len * bd->cos_a, len * bd->sin_a)), PP_DEBUG_COLOR_AXIS_X, PP_DEBUG_CENTER,
            bd->handle);
        put(o, com, dv_add(com, dv(-len * bd->sin_a, len * bd->cos_a)), PP_DEBUG_COLOR_AXIS_Y, PP_DEBUG_CENTER,
            bd->handle);
    }
    if ((flags & PP_DEBUG_DRAW_VELOCITIES) && bd->sb.body) {
        const dvec2 v = body_point_velocity(wd, bd, com);
        put(o, com, dv_add(com, dv_scale(v, PP_DEBUG_VELOCITY_TIME)), PP_DEBUG_COLOR_VELOCITY, PP_DEBUG_VELOCITY,
            bd->handle);
    }
}

/* A cross at a contact point pp_world_get_contacts lists, and its normal (world_each_contact's visit). */
static void put_contact(const pp_contact *c, void *user)
{
    seg_out *o = user;
    const dvec2 p = dv(c->point.x, c->point.y), n = dv(c->normal.x, c->normal.y);
    if (!in_view(o, p))
        return;
    const double h = PP_DEBUG_CROSS_SIZE;
    put(o, dv(p.x - h, p.y), dv(p.x + h, p.y), PP_DEBUG_COLOR_CONTACT, PP_DEBUG_CONTACT, c->a);
    put(o, dv(p.x, p.y - h), dv(p.x, p.y + h), PP_DEBUG_COLOR_CONTACT, PP_DEBUG_CONTACT, c->a);
    put(o, p, dv_add(p, dv_scale(n, PP_DEBUG_NORMAL_LENGTH)), PP_DEBUG_COLOR_NORMAL, PP_DEBUG_NORMAL, c->a);
}

static void put_joints(seg_out *o, world *wd)
{
    const joint_table *t = &wd->joints;
    for (int32_t i = 0; i < t->ids.capacity; i++) {
        const joint *jt = t->items[i];
        if (!jt)
            continue;
        const body *a = joint_body_a(wd, jt), *b = joint_body_b(wd, jt);
        dvec2 pa, pb;
        joint_anchors(wd, jt, &pa, &pb);
        if (!in_view(o, pa) && !in_view(o, pb))
            continue;
        put(o, pa, pb, PP_DEBUG_COLOR_JOINT, PP_DEBUG_JOINT, jt->def.body_b);
        if (a)
            put(o, body_com_world(a), pa, PP_DEBUG_COLOR_JOINT, PP_DEBUG_JOINT, a->handle);
        if (b)
            put(o, body_com_world(b), pb, PP_DEBUG_COLOR_JOINT, PP_DEBUG_JOINT, b->handle);
    }
}

PP_API pp_status pp_world_debug_draw(pp_world w, uint32_t flags, pp_vec2 lower, pp_vec2 upper, pp_debug_segment *out,
                                     int32_t capacity, int32_t *count)
{
    static const char *fn = "pp_world_debug_draw";
    pp_status st;
    world *wd = world_lookup_list(w, fn, out, capacity, count, &st);
    if (!wd)
        return st;
    if (flags & ~PP_DEBUG_DRAW_ALL)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: flags 0x%x has bits outside PP_DEBUG_DRAW_ALL (0x%x)", fn,
                       (unsigned)flags, (unsigned)PP_DEBUG_DRAW_ALL);
    if ((st = pp_check_box(fn, lower, upper)))
        return st;
    seg_out o = {out, capacity, 0, {lower.x, lower.y, upper.x, upper.y}};
    int32_t *near = NULL, n_near = 0;
    const uint32_t body_flags = PP_DEBUG_DRAW_OUTLINES | PP_DEBUG_DRAW_AABBS | PP_DEBUG_DRAW_CENTERS |
                                PP_DEBUG_DRAW_VELOCITIES;
    if ((flags & body_flags) && (st = awake_bodies_in_box(wd, fn, o.view, &near, &n_near)))
        return st;
    /* Everything that can fail first (the outlines), so that a failure writes nothing; the most segments that
     * could be written must fit the count. */
    int64_t most = 0;
    for (int32_t k = 0; k < n_near; k++) {
        body *bd = wd->bodies[near[k]];
        const raster_outline *ol = NULL;
        if ((flags & PP_DEBUG_DRAW_OUTLINES) && (st = raster_outline_get(fn, &bd->raster, &ol))) {
            pp_free(near);
            return st;
        }
        most += (ol ? ol->count : 0) + 7;
    }
    if (flags & PP_DEBUG_DRAW_CONTACTS)
        most += 3 * ((int64_t)wd->contact_count + PP_MAX_CONTACTS_PER_PAIR * (int64_t)wd->table.count);
    if (flags & PP_DEBUG_DRAW_JOINTS)
        most += 3 * (int64_t)wd->joints.ids.capacity;
    if (most > INT32_MAX) {
        pp_free(near);
        return pp_fail(PP_ERR_LIMIT, "%s: up to %lld segments could meet the box, over a count's INT32_MAX; draw a "
                       "smaller box", fn, (long long)most);
    }
    for (int32_t k = 0; k < n_near; k++) {
        const body *bd = wd->bodies[near[k]];
        put_body(&o, wd, bd, flags, (flags & PP_DEBUG_DRAW_OUTLINES) ? bd->raster.outline : NULL);
    }
    pp_free(near);
    if (flags & PP_DEBUG_DRAW_CONTACTS)
        world_each_contact(wd, put_contact, &o);
    if (flags & PP_DEBUG_DRAW_JOINTS)
        put_joints(&o, wd);
    *count = (int32_t)o.count;
    return PP_OK;
}
