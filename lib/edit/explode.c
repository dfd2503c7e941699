/* Explosions: an erase, then one impulse on each dynamic body near the centre by Box2D v3's b2World_Explode rule,
 * on pixels: impulse per length of the body's solid extent across the blast, at its solid pixel nearest the
 * centre, falling off linearly with that pixel's distance. */
#include "alloc.h"
#include "awake.h"
#include "cover.h"
#include "edit.h"
#include "status.h"

PP_API pp_explosion_def pp_explosion_def_default(void)
{
    pp_explosion_def d = {0};
    d.struct_size = sizeof d;
    d.impulse_per_length = PP_EXPLOSION_IMPULSE_PER_LENGTH;
    d.mask_bits = d.erase_mask_bits = ~0u;
    return d;
}

static pp_status check_explosion(const char *fn, const pp_explosion_def *d)
{
    if (!d)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: def is NULL", fn);
    if (d->struct_size != sizeof *d)
        return pp_fail(PP_ERR_ABI, "%s: def->struct_size is %u, this library expects %u (use pp_explosion_def_default)",
                       fn, (unsigned)d->struct_size, (unsigned)sizeof *d);
    if (!finite2(d->position.x, d->position.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: def->position must be finite, got (%g, %g)", fn, d->position.x,
                       d->position.y);
    const float v[4] = {d->radius, d->falloff, d->impulse_per_length, d->erase_radius};
    static const char *const names[4] = {"radius", "falloff", "impulse_per_length", "erase_radius"};
    for (int k = 0; k < 4; k++)
        if (!(v[k] >= 0) || !isfinite(v[k]))
            return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: def->%s must be finite and ≥ 0, got %g", fn, names[k], v[k]);
    return PP_OK;
}

/* Distance from v to the interval [a, a + 1], px. */
static double cell_gap(double v, int32_t a) { return fmax(0.0, fmax(a - v, v - (a + 1.0))); }

/* The solid pixel of r whose square lies nearest the bitmap point c: *near receives the nearest point of that
 * square, *dist its distance (px); false without pixels. Rows outward from c's, stopping where a row cannot be
 * nearer; in each row the nearest solid pixel on either side of c. */
static bool nearest_pixel(const pp_raster *r, dvec2 c, dvec2 *near, double *dist)
{
    if (raster_empty(r))
        return false;
    const int32_t cy = (int32_t)fmin(fmax(floor(c.y), r->y0), r->y1 - 1);
    const int32_t cx = (int32_t)fmin(fmax(floor(c.x), r->x0), r->x1 - 1);
    double best = INFINITY;
    for (int32_t k = 0;; k++) {
        bool further = false;
        for (int side = k == 0; side < 2; side++) {
            const int32_t y = side ? cy + k : cy - k;
            if (y < r->y0 || y >= r->y1 || cell_gap(c.y, y) >= best)
                continue;
            further = true;
            if (r->row_count[y] == 0)
                continue;
            const int32_t xs[2] = {raster_row_prev(r, y, cx), raster_row_next(r, y, cx)};
            for (int i = 0; i < 2; i++) {
                if (xs[i] < 0 || xs[i] >= r->width)
                    continue;
                const double d = hypot(cell_gap(c.x, xs[i]), cell_gap(c.y, y));
                if (d < best)
                    best = d, *near = dv(fmin(fmax(c.x, xs[i]), xs[i] + 1.0), fmin(fmax(c.y, y), y + 1.0));
            }
        }
        if (!further)
            break;
    }
    *dist = best;
    return isfinite(best);
}

/* The length of the solid pixels' squares projected on the unit bitmap direction u, px: each row's ends suffice. */
static double solid_extent(const pp_raster *r, dvec2 u)
{
    double lo = INFINITY, hi = -INFINITY;
    for (int32_t y = r->y0; y < r->y1; y++) {
        if (r->row_count[y] == 0)
            continue;
        const double xs[2] = {raster_row_next(r, y, r->x0), raster_row_prev(r, y, r->x1 - 1) + 1.0};
        for (int k = 0; k < 4; k++) {
            const double p = u.x * xs[k & 1] + u.y * (y + (k >> 1));
            lo = fmin(lo, p), hi = fmax(hi, p);
        }
    }
    return hi > lo ? hi - lo : 0.0;
}

/* The largest k in [0, 1] for which v0 + k·dv and w0 + k·dw stay within PP_MAX_SPEED and PP_MAX_ANGULAR_SPEED
 * (k = 0 does: the body's own velocity), kept a hair inside for rounding. */
static double within_limits(dvec2 v0, dvec2 dv_, double w0, double dw)
{
    double k = 1;
    const double a = dv_dot(dv_, dv_), b = dv_dot(v0, dv_), c = dv_dot(v0, v0) - (double)PP_MAX_SPEED * PP_MAX_SPEED;
    if (a > 0)
        k = fmin(k, (-b + sqrt(fmax(0.0, b * b - a * c))) / a);
    if (dw != 0)
        k = fmin(k, (PP_MAX_ANGULAR_SPEED - (dw > 0 ? w0 : -w0)) / fabs(dw));
    return k < 1 ? fmax(0.0, k * (1 - 1e-6)) : 1;
}

/* Give a dynamic body the impulse J (mass·px/s) at the world point p, scaled down where the whole of it would pass
 * the speed limits, and wake it. */
static void push_capped(world *wd, body *bd, dvec2 J, dvec2 p)
{
    dvec2 v0, v;
    double w0, w;
    body_velocity_after_impulse(wd, bd, dv(0, 0), p, &v0, &w0);
    body_velocity_after_impulse(wd, bd, J, p, &v, &w);
    if (!body_speed_ok(v, w)) {
        const double k = within_limits(v0, dv_sub(v, v0), w0, w - w0);
        v = dv_add(v0, dv_scale(dv_sub(v, v0), k)), w = w0 + k * (w - w0);
    }
    solver_body_set_velocity(wd->solver, &bd->sb, v, w);
    awake_wake(wd, bd);
}

/* One body's push, if the blast reaches it. */
static void push_body(world *wd, body *bd, const pp_explosion_def *def)
{
    if (bd->type != PP_BODY_DYNAMIC || !(bd->category_bits & def->mask_bits))
        return;
    const dvec2 centre = dv(def->position.x, def->position.y);
    dvec2 near = {0, 0};
    double dist;
    if (!nearest_pixel(&bd->raster, body_world_to_local(bd, centre), &near, &dist))
        return;
    const double radius = def->radius;
    const double s = dist <= radius ? 1.0 : def->falloff > 0 ? 1.0 - (dist - radius) / def->falloff : 0.0;
    if (!(s > 0) || def->impulse_per_length == 0)
        return;
    const dvec2 p = body_local_to_world(bd, near);
    dvec2 dir = dv_sub(p, centre);
    if (dv_norm(dir) < 1e-9) /* the centre is in a solid pixel: away from the centre of mass */
        dir = dv_sub(body_com_world(bd), centre);
    const double len = dv_norm(dir);
    if (!(len > 1e-9))
        return;
    dir = dv_scale(dir, 1.0 / len);
    const double across = solid_extent(&bd->raster, dv_unrot(dv(-dir.y, dir.x), bd->cos_a, bd->sin_a));
    push_capped(wd, bd, dv_scale(dir, (double)def->impulse_per_length * across * s), p);
}

/* Room for the list of the bodies a blast pushes, made before its erase is committed, so that running out of
 * memory leaves nothing erased: a slot for every body there is then, pieces included. */
typedef struct blast_room {
    int32_t *slots;
    const char *fn;
} blast_room;

static pp_status blast_reserve(world *wd, void *user)
{
    blast_room *room = user;
    const int32_t n = wd->body_ids.capacity;
    if (n > 0 && !(room->slots = pp_malloc((size_t)n * sizeof *room->slots)))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for a list of %d bodies", room->fn, (int)n);
    return PP_OK;
}

PP_API pp_status pp_world_explode(pp_world w, const pp_explosion_def *def, int32_t *changed)
{
    static const char *fn = "pp_world_explode";
    world *wd = world_lookup(w, fn);
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    pp_status st = check_explosion(fn, def);
    if (st)
        return st;
    blast_room room = {NULL, fn};
    int32_t erased = 0;
    st = def->erase_radius > 0 ? edit_erase_world(wd, def->position, def->erase_radius, def->erase_mask_bits, fn,
                                                  &erased, blast_reserve, &room)
                               : blast_reserve(wd, &room);
    if (st)
        return st;
    if (changed)
        *changed = erased;
    /* After the erase, so that the pieces it split off are found too. */
    const double reach = (double)def->radius + def->falloff;
    const pp_aabb box = {def->position.x - reach - 1, def->position.y - reach - 1, def->position.x + reach + 1,
                         def->position.y + reach + 1};
    const int32_t n = room.slots ? awake_slots_in_box(wd, box, room.slots) : 0;
    for (int32_t k = 0; k < n; k++)
        push_body(wd, wd->bodies[room.slots[k]], def);
    pp_free(room.slots);
    return PP_OK;
}
