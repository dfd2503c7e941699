/* Continuous collision. Contacts are found only at the start of a substep, so a body that moves
 * farther than its own thickness in one substep can pass through a thin wall unseen. After each
 * substep such a body's motion is swept: poses along its path, spaced at most half its thickness
 * apart (so no wall at least one pixel thick fits between two of them), are tested against the
 * rasters it could meet. At the first pose where its overlap with a body grows by more than one
 * pixel layer, refined by bisection to half a pixel of travel, the body is stopped; it keeps its
 * velocity, so the next substep's contact takes that velocity away (or bounces it) as usual. */
#include "alloc.h"
#include "awake.h"
#include "continuous.h"
#include "status.h"

#include <math.h>
#include <stdlib.h>

/* Overlap tests refine the hit pose until the travel left to resolve is below this, px. */
#define SWEEP_RESOLUTION 0.5
/* px: a body whose travel's cheap bound is this far under the spacing is under it however the two round. */
#define SWEEP_BOUND_SLACK 1e-6

/* A pose by its centre of mass, as ODE moves a body: the centre along a line, the angle evenly. */
typedef struct sweep {
    const body *bd;
    dvec2 com0, dcom;   /* px */
    double angle0, dangle;
    dvec2 com_local;    /* bitmap coordinates, px */
} sweep;

static void sweep_pose(const sweep *sw, double t, dvec2 *com, double *angle)
{
    *com = dv_add(sw->com0, dv_scale(sw->dcom, t));
    *angle = sw->angle0 + sw->dangle * t;
}

/* Solid pixels of the swept body at its pose at t whose centres fall in a solid pixel of `other`. */
static int64_t overlap_at(const sweep *sw, double t, const body *other)
{
    dvec2 com;
    double angle;
    sweep_pose(sw, t, &com, &angle);
    const pp_raster *r = &sw->bd->raster, *ro = &other->raster;
    const double c = cos(angle), s = sin(angle);
    /* Local pixel centre → world → other's bitmap, as one affine map stepped per pixel. */
    const double oc = other->cos_a, os = other->sin_a;
    const dvec2 dx = dv_unrot(dv(c, s), oc, os);
    /* Only the part of the swept body inside the other's world box can overlap it: that box's corners,
     * taken into the swept body's bitmap, bound the pixels worth testing. */
    double lx0 = INFINITY, ly0 = INFINITY, lx1 = -INFINITY, ly1 = -INFINITY;
    for (int k = 0; k < 4; k++) {
        const pp_aabb *box = &other->aabb;
        const dvec2 corner = dv(k & 1 ? box->x1 + 1 : box->x0 - 1, k & 2 ? box->y1 + 1 : box->y0 - 1);
        const dvec2 l = dv_add(dv_unrot(dv_sub(corner, com), c, s), sw->com_local);
        lx0 = dmin(lx0, l.x), ly0 = dmin(ly0, l.y), lx1 = dmax(lx1, l.x), ly1 = dmax(ly1, l.y);
    }
    /* Clamped on both sides: a box far off the bitmap gives bounds past int32 (UBSan, found by fuzz_snapshot). */
    const int32_t x0 = (int32_t)dmin(dmax(r->x0, floor(lx0)), r->x1), x1 = (int32_t)dmax(dmin(r->x1, ceil(lx1)), r->x0);
    const int32_t y0 = (int32_t)dmin(dmax(r->y0, floor(ly0)), r->y1), y1 = (int32_t)dmax(dmin(r->y1, ceil(ly1)), r->y0);
    int64_t n = 0;
    for (int32_t y = y0; y < y1; y++) {
        const dvec2 w = dv_add(com, dv_rot(dv_sub(dv(x0 + 0.5, y + 0.5), sw->com_local), c, s));
        dvec2 q = dv_add(dv_unrot(dv_sub(w, other->pos), oc, os), other->pivot);
        for (int32_t x = x0; x < x1; x++, q = dv_add(q, dx))
            if (raster_solid(r, x, y) && raster_solid_clamped(ro, (int32_t)floor(q.x), (int32_t)floor(q.y)))
                n++;
    }
    return n;
}

/* Fraction of the substep at which the swept body (`thin` px across) first hits `other`, or 1 for
 * no hit (or none before `before`). A hit is an overlap grown by a whole layer of pixels across
 * the body since the start, so sliding along a body it already touches is not one. */
static double first_hit(const sweep *sw, const body *other, int32_t thin, int32_t samples, double travel, double before)
{
    const int64_t limit = overlap_at(sw, 0.0, other) + thin - 1; /* a 1 px body hits on its first pixel in */
    for (int32_t k = 1; k <= samples; k++) {
        double hi = (double)k / samples;
        if (hi >= before)
            return 1.0;
        if (overlap_at(sw, hi, other) <= limit)
            continue;
        double lo = (double)(k - 1) / samples;
        while ((hi - lo) * travel > SWEEP_RESOLUTION) {
            const double mid = 0.5 * (lo + hi);
            if (overlap_at(sw, mid, other) > limit)
                hi = mid;
            else
                lo = mid;
        }
        return hi;
    }
    return 1.0;
}

/* A body sitting the substep out (island.c's spans) does not move in it: nothing to sweep. */
static bool sweeps(const world *wd, const body *bd)
{
    return bd && bd->type == PP_BODY_DYNAMIC && !bd->is_sensor && !raster_empty(&bd->raster) &&
           solver_body_is_awake(&bd->sb) && (wd->def.continuous || bd->bullet) &&
           wd->islands.span[bd->index] != SPAN_SKIP;
}

pp_status continuous_begin(world *wd)
{
    pp_status st = world_slot_array(wd, (void **)&wd->sweeps.from, &wd->sweeps.from_capacity, sizeof *wd->sweeps.from,
                                    "continuous collision");
    if (st || (st = world_slot_array(wd, (void **)&wd->sweeps.slots, &wd->sweeps.capacity, sizeof *wd->sweeps.slots,
                                     "continuous collision")))
        return st;
    wd->sweeps.count = 0;
    for (int32_t k = 0; k < wd->awake.count; k++) { /* in slot order: a bullet sees earlier sweeps' poses */
        const int32_t i = wd->awake.slots[k];
        const body *bd = wd->bodies[i];
        if (sweeps(wd, bd)) {
            wd->sweeps.from[i] = (continuous_pose){body_com_world(bd), bd->angle};
            wd->sweeps.slots[wd->sweeps.count++] = i;
        }
    }
    return PP_OK;
}

/* Whether a swept body can hit `o` at all: not a sensor, and a one-way platform only when the body moves
 * against its direction (onto it) and is not already in it, passing or standing. */
static bool stops(const world *wd, const body *bd, const body *o, dvec2 dcom)
{
    if (o->is_sensor)
        return false;
    if (!o->one_way)
        return true;
    const dvec2 d = dv_rot(o->one_way_dir, o->cos_a, o->sin_a);
    return dv_dot(dcom, d) < 0 && !contact_table_find(wd, bd->handle.id, o->handle.id);
}

/* The turn from angle a0 to a1 in (−π, π], rad: remainder's, without its call for a substep's turn (under π,
 * where remainder returns its argument exactly). */
static double turn_of(double a0, double a1)
{
    const double d = a1 - a0;
    return fabs(d) <= PP_PI ? d : remainder(d, 2 * PP_PI);
}

/* Sweep one body from its recorded pose to where the substep left it; stop it at its first hit. */
static pp_status sweep_body(world *wd, body *bd, const continuous_pose *from)
{
    const pp_raster *r = &bd->raster;
    sweep sw = {bd, from->com, dv_sub(body_com_world(bd), from->com), from->angle, turn_of(from->angle, bd->angle),
                body_com_local(bd)};
    const int32_t thin = (r->x1 - r->x0) < (r->y1 - r->y0) ? r->x1 - r->x0 : r->y1 - r->y0; /* ≥ 1: not empty */
    const double spacing = dmax(1.0, 0.5 * thin), move = sqrt(dv_dot(sw.dcom, sw.dcom));
    /* Most bodies move well under the spacing: the reach's bound by its axes (no root, never under it, and kept
     * clear of the test below by far more than rounding) answers without the corners. */
    const double rx = dmax(fabs(r->x0 - sw.com_local.x), fabs(r->x1 - sw.com_local.x));
    const double ry = dmax(fabs(r->y0 - sw.com_local.y), fabs(r->y1 - sw.com_local.y));
    if (move + fabs(sw.dangle) * (rx + ry) < spacing - SWEEP_BOUND_SLACK)
        return PP_OK;
    /* The farthest any solid pixel lies from the centre of mass bounds how far a point moves. */
    double reach2 = 0;
    for (int k = 0; k < 4; k++) {
        const dvec2 d = dv_sub(dv(k & 1 ? r->x1 : r->x0, k & 2 ? r->y1 : r->y0), sw.com_local);
        reach2 = dmax(reach2, dv_dot(d, d));
    }
    const double reach = sqrt(reach2), travel = move + fabs(sw.dangle) * reach;
    if (travel <= spacing)
        return PP_OK;
    const dvec2 end = dv_add(sw.com0, sw.dcom);
    const pp_aabb swept = {dmin(sw.com0.x, end.x) - reach, dmin(sw.com0.y, end.y) - reach,
                           dmax(sw.com0.x, end.x) + reach, dmax(sw.com0.y, end.y) + reach};
    const int32_t samples = (int32_t)dmin(ceil(travel / spacing), 1 << 20);
    /* In slot order: first_hit stops at the hit found so far, so the order decides among near-equal hits. */
    int32_t *near = NULL, n = 0;
    pp_status st = awake_bodies_in_box(wd, "pp_world_step", swept, &near, &n);
    if (st)
        return st;
    double t = 1.0;
    for (int32_t k = 0; k < n; k++) {
        const body *o = wd->bodies[near[k]];
        if (o == bd || raster_empty(&o->raster) || (o->type == PP_BODY_DYNAMIC && !bd->bullet))
            continue;
        if (!(bd->category_bits & o->mask_bits) || !(o->category_bits & bd->mask_bits) || !stops(wd, bd, o, sw.dcom))
            continue;
        t = dmin(t, first_hit(&sw, o, thin, samples, travel, t));
    }
    pp_free(near);
    if (t >= 1.0)
        return PP_OK;
    dvec2 com;
    sweep_pose(&sw, t, &com, &bd->angle);
    angle_cos_sin(bd->angle, &bd->cos_a, &bd->sin_a);
    bd->pos = dv_sub(com, dv_rot(dv_sub(sw.com_local, bd->pivot), bd->cos_a, bd->sin_a));
    body_update_pose_cache(bd);
    awake_moved(wd, bd); /* the next sweeps' queries see it where it stopped */
    solver_body_set_pose(wd->solver, &bd->sb, com, bd->angle);
    wd->stats.swept_stops++;
    return PP_OK;
}

pp_status continuous_end(world *wd)
{
    pp_status st = PP_OK;
    for (int32_t k = 0; k < wd->sweeps.count && !st; k++) {
        const int32_t i = wd->sweeps.slots[k];
        if (solver_body_is_awake(&wd->bodies[i]->sb))
            st = sweep_body(wd, wd->bodies[i], &wd->sweeps.from[i]);
    }
    return st;
}

void continuous_free(sweep_set *s)
{
    pp_free(s->from);
    pp_free(s->slots);
    *s = (sweep_set){0};
}
