/* Editing pixels at any moment: erase, paint, write, read, and the world's explosion. Mass sums
 * and bounds follow from the changed pixels alone; the pose (pivot) does not move, the ODE body
 * moves to the new centre of mass with the velocity its material already had; the GPU mirror
 * rewrites only the dirty rows; bodies nearby wake; a body cut apart splits (fracture.c). */
#include "edit.h"
#include "status.h"

#include <stdlib.h>

void edit_pixel(body *bd, edit_span *e, int32_t x, int32_t y, bool solid, uint32_t weight)
{
    pp_raster *r = &bd->raster;
    const bool was = raster_solid(r, x, y);
    const uint32_t old = raster_weight(r, x, y);
    if (!r->weights)
        weight = 255; /* no plane: every pixel weighs 255 (callers add one before other weights) */
    if (was == solid && (!solid || old == weight))
        return;
    if (was)
        mass_sums_pixel(&bd->sums, r->width, r->height, x, y, old, -1);
    if (solid)
        mass_sums_pixel(&bd->sums, r->width, r->height, x, y, weight, +1);
    raster_write(r, x, y, solid, weight);
    e->removed |= was && !solid;
    const bool first = e->changed++ == 0;
    if (first || x < e->x0) e->x0 = x;
    if (first || x >= e->x1) e->x1 = x + 1;
    if (first || y < e->y0) e->y0 = y;
    if (first || y >= e->y1) e->y1 = y + 1;
}

void edit_update_solver_body(world *wd, body *bd)
{
    solver_body_state s;
    solver_body_get_state(wd->solver, &bd->sb, &s);
    bd->mass = mass_from_sums(&bd->sums, bd->raster.width, bd->raster.height, bd->density);
    const dvec2 com = body_com_world(bd), r = dv_sub(com, s.com_world);
    const dvec2 v = dv_add(s.velocity, dv(-s.angular_velocity * r.y, s.angular_velocity * r.x));
    solver_body_set_mass(wd->solver, &bd->sb, bd->mass.mass, bd->mass.inertia);
    solver_body_set_pose(wd->solver, &bd->sb, com, bd->angle);
    solver_body_set_velocity(wd->solver, &bd->sb, v, s.angular_velocity);
    solver_body_wake(&bd->sb);
}

static bool boxes_overlap(pp_aabb a, pp_aabb b) { return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1; }

/* Bodies whose box comes within this many pixels of an edited pixel wake: one resting on the edited
 * pixels overlaps them already; the margin catches one just touching them, after rounding. */
#define EDIT_WAKE_MARGIN 2.0

/* The world box of the edited pixels, grown by the margin. */
static pp_aabb edited_region(const body *bd, const edit_span *e)
{
    pp_aabb box = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 4; k++) {
        const dvec2 l = dv((k & 1 ? e->x1 + EDIT_WAKE_MARGIN : e->x0 - EDIT_WAKE_MARGIN) - bd->pivot.x,
                           (k & 2 ? e->y1 + EDIT_WAKE_MARGIN : e->y0 - EDIT_WAKE_MARGIN) - bd->pivot.y);
        const dvec2 w = dv_add(bd->pos, dv_rot(l, bd->cos_a, bd->sin_a));
        box.x0 = fmin(box.x0, w.x), box.y0 = fmin(box.y0, w.y);
        box.x1 = fmax(box.x1, w.x), box.y1 = fmax(box.y1, w.y);
    }
    return box;
}

/* Wake every body that may rest on, or now overlap, the edited pixels. Only those: a crater deep
 * in a large terrain leaves the bodies sleeping on its surface asleep. */
static void wake_around(world *wd, pp_aabb region)
{
    for (int32_t i = 0; i < wd->body_capacity; i++) {
        body *o = wd->bodies[i];
        if (o && o->sb.body && boxes_overlap(o->aabb, region))
            solver_body_wake(&o->sb);
    }
}

/* Bring the body up to date after a batch of writes; it may be destroyed or split here. */
static pp_status commit_edit(world *wd, body *bd, const edit_span *e)
{
    if (e->changed == 0)
        return PP_OK;
    raster_edit_done(&bd->raster, e->y0, e->y1);
    body_update_pose_cache(bd);
    wake_around(wd, edited_region(bd, e));
    /* Nothing left to simulate: no pixels, or a dynamic body without mass. */
    if (bd->raster.solid_count == 0 || (bd->type == PP_BODY_DYNAMIC && bd->sums.w <= 0)) {
        const pp_body gone = bd->handle;
        body_remove(wd, bd);
        return world_push_event(wd, PP_EVENT_BODY_DESTROYED, gone, (pp_body){0});
    }
    if (bd->sb.body)
        edit_update_solver_body(wd, bd);
    if (e->removed && (bd->type == PP_BODY_DYNAMIC || (bd->type == PP_BODY_STATIC && bd->detach_islands)))
        return fracture_split(wd, bd);
    return PP_OK;
}

static pp_status check_circle(const char *fn, pp_vec2 c, float radius)
{
    if (!finite2(c.x, c.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: world_center must be finite", fn);
    if (!(radius >= 0) || !isfinite(radius))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: radius must be finite and ≥ 0, got %g", fn, radius);
    return PP_OK;
}

/* Set every pixel of [x0, x1) × [y0, y1) whose centre is within r of the body-local point c. */
static void circle_write(body *bd, edit_span *e, dvec2 c, double r, int32_t x0, int32_t y0, int32_t x1, int32_t y1,
                         bool solid, uint32_t weight)
{
    /* Clamped on both sides: a circle far off the bitmap gives bounds past int32 (UBSan, found by fuzz_api). */
    const double top = fmin(fmax(y0, floor(c.y - r)), y1), bottom = fmax(fmin(y1, ceil(c.y + r)), y0);
    for (int32_t y = (int32_t)top; y < (int32_t)bottom; y++) {
        const double dy = y + 0.5 - c.y, h2 = r * r - dy * dy;
        if (h2 < 0)
            continue;
        const double h = sqrt(h2);
        const int32_t xa = (int32_t)fmin(fmax(x0, ceil(c.x - h - 0.5)), x1),
                      xb = (int32_t)fmax(fmin(x1 - 1, floor(c.x + h - 0.5)), x0 - 1);
        for (int32_t x = xa; x <= xb; x++)
            edit_pixel(bd, e, x, y, solid, weight);
    }
}

static dvec2 world_to_local(const body *bd, pp_vec2 p)
{
    return dv_add(bd->pivot, dv_unrot(dv_sub(dv(p.x, p.y), bd->pos), bd->cos_a, bd->sin_a));
}

static pp_status erase_circle(world *wd, body *bd, pp_vec2 center, float radius, int32_t *changed)
{
    edit_span e = {0};
    const pp_raster *r = &bd->raster;
    if (!raster_empty(r))
        circle_write(bd, &e, world_to_local(bd, center), radius, r->x0, r->y0, r->x1, r->y1, false, 0);
    *changed += e.changed;
    return commit_edit(wd, bd, &e);
}

PP_API pp_status pp_body_erase_circle(pp_world w, pp_body b, pp_vec2 world_center, float radius, int32_t *changed)
{
    static const char *fn = "pp_body_erase_circle";
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, fn, &wd, &bd);
    if (st || (st = check_circle(fn, world_center, radius)))
        return st;
    int32_t n = 0;
    st = erase_circle(wd, bd, world_center, radius, &n);
    if (changed)
        *changed = n;
    return st;
}

PP_API pp_status pp_world_erase_circle(pp_world w, pp_vec2 world_center, float radius, int32_t *changed)
{
    static const char *fn = "pp_world_erase_circle";
    world *wd = world_lookup(w, fn);
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    pp_status st = check_circle(fn, world_center, radius);
    if (st)
        return st;
    const pp_aabb blast = {world_center.x - radius, world_center.y - radius, world_center.x + radius,
                           world_center.y + radius};
    int32_t n = 0;
    /* Bodies made by a split during the loop are islands outside the circle: no need to visit them. */
    const int32_t bodies = wd->body_capacity;
    for (int32_t i = 0; i < bodies && !st; i++) {
        body *bd = wd->bodies[i];
        if (bd && boxes_overlap(bd->aabb, blast))
            st = erase_circle(wd, bd, world_center, radius, &n);
    }
    if (changed)
        *changed = n;
    return st;
}

PP_API pp_status pp_body_paint_circle(pp_world w, pp_body b, pp_vec2 world_center, float radius, uint8_t weight,
                                      int32_t *changed)
{
    static const char *fn = "pp_body_paint_circle";
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, fn, &wd, &bd);
    if (st || (st = check_circle(fn, world_center, radius)))
        return st;
    if (weight == 0)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: weight must be 1..255 (0 would paint massless pixels)", fn);
    if (weight != 255 && (st = raster_ensure_weights(&bd->raster)))
        return st;
    edit_span e = {0};
    circle_write(bd, &e, world_to_local(bd, world_center), radius, 0, 0, bd->raster.width, bd->raster.height, true,
                 weight);
    if (changed)
        *changed = e.changed;
    return commit_edit(wd, bd, &e);
}

PP_API pp_status pp_body_write_pixels(pp_world w, pp_body b, int32_t x, int32_t y, int32_t width, int32_t height,
                                      const uint8_t *mask, const uint8_t *weights)
{
    static const char *fn = "pp_body_write_pixels";
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, fn, &wd, &bd);
    if (st)
        return st;
    if (!mask)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: mask is NULL", fn);
    if (width <= 0 || height <= 0)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: width and height must be > 0, got %d × %d", fn, (int)width,
                       (int)height);
    const pp_raster *r = &bd->raster;
    /* Clip to the bitmap; a rectangle wholly outside is a mistake, not an empty edit. */
    const int64_t cx0 = x > 0 ? x : 0, cy0 = y > 0 ? y : 0;
    const int64_t cx1 = (int64_t)x + width < r->width ? (int64_t)x + width : r->width;
    const int64_t cy1 = (int64_t)y + height < r->height ? (int64_t)y + height : r->height;
    if (cx0 >= cx1 || cy0 >= cy1)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: the %d × %d rectangle at (%d, %d) is outside the %d × %d bitmap", fn,
                       (int)width, (int)height, (int)x, (int)y, (int)r->width, (int)r->height);
    if (weights && (st = raster_ensure_weights(&bd->raster)))
        return st;
    edit_span e = {0};
    for (int64_t py = cy0; py < cy1; py++)
        for (int64_t px = cx0; px < cx1; px++) {
            const int64_t k = (py - y) * width + (px - x);
            edit_pixel(bd, &e, (int32_t)px, (int32_t)py, mask[k] != 0, weights ? weights[k] : 255u);
        }
    return commit_edit(wd, bd, &e);
}

PP_API pp_status pp_body_read_mask(pp_world w, pp_body b, uint8_t *out, int64_t capacity)
{
    static const char *fn = "pp_body_read_mask";
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, fn, &wd, &bd);
    if (st)
        return st;
    const pp_raster *r = &bd->raster;
    const int64_t need = (int64_t)r->width * r->height;
    if (!out || capacity < need)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: out must hold width × height = %lld bytes, got %s%lld", fn,
                       (long long)need, out ? "" : "NULL with capacity ", (long long)capacity);
    for (int32_t y = 0; y < r->height; y++)
        for (int32_t x = 0; x < r->width; x++)
            out[(int64_t)y * r->width + x] = raster_solid(r, x, y);
    return PP_OK;
}

PP_API pp_status pp_body_get_size(pp_world w, pp_body b, int32_t *width, int32_t *height)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_get_size", &wd, &bd);
    if (st)
        return st;
    if (width)
        *width = bd->raster.width;
    if (height)
        *height = bd->raster.height;
    return PP_OK;
}
