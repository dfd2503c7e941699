/* pp_world_cast_body: a body's pixel squares swept along a translation, rotation held, against the other bodies'
 * squares. Two squares overlap over an open interval of travel, found exactly on the four axes that can separate
 * them (their bitmaps' axes); the earliest entry over the pairs is the hit. Only pixels with an empty neighbour
 * can touch first: each body's such pixels are swept against every pixel of the other, which also finds a body
 * lying wholly inside the other at the start. */
#include "alloc.h"
#include "awake.h"
#include "cover.h"
#include "joint.h"
#include "status.h"

/* Entries this close in travel (a fraction) touch together: a face landing flat touches along its whole width. */
#define CAST_TIE 1e-9

/* Squares closer than this count as touching, not overlapping, so that rounding does not stop a body resting
 * exactly on another from sliding along it. px. */
#define CAST_TOUCH 1e-7

/* A body's pixel grid in the world: bitmap pixel (x, y) has its centre at o + (x + ½)·ex + (y + ½)·ey. */
typedef struct cast_frame {
    dvec2 o, ex, ey;
} cast_frame;

static cast_frame frame_of(const body *bd)
{
    return (cast_frame){body_local_to_world(bd, dv(0, 0)), dv(bd->cos_a, bd->sin_a), dv(-bd->sin_a, bd->cos_a)};
}

static dvec2 pixel_centre(const cast_frame *f, int32_t x, int32_t y)
{
    return dv_add(f->o, dv_add(dv_scale(f->ex, x + 0.5), dv_scale(f->ey, y + 0.5)));
}

/* Half a pixel square's width along the unit axis n. */
static double half_width(const cast_frame *f, dvec2 n) { return 0.5 * (fabs(dv_dot(n, f->ex)) + fabs(dv_dot(n, f->ey))); }

typedef struct cast_state {
    const body *a;      /* the cast body */
    cast_frame fa;
    dvec2 T;            /* its translation, px */
    /* The candidate now: its frame, the axes that separate a square of each, and both squares' half widths. */
    const body *b;
    cast_frame fb;
    dvec2 axes[4];
    double ha[4], hb[4];
    int n_axes;
    /* The earliest entry so far (≤ 1): the body, the normal out of it, and where the squares entering then touch:
     * on the contact line n·p = level, over [lo, hi] along the tangent (−n.y, n.x); at the start, between two
     * overlapping squares' centres (ca, cb). */
    double t;
    const body *hit;
    dvec2 normal, ca, cb;
    double level, lo, hi;
} cast_state;

static void cast_candidate(cast_state *cs, const body *b)
{
    cs->b = b, cs->fb = frame_of(b);
    const dvec2 all[4] = {cs->fa.ex, cs->fa.ey, cs->fb.ex, cs->fb.ey};
    /* Squares turned by a multiple of 90° against each other share their axes. */
    const bool aligned = fabs(dv_dot(cs->fa.ex, cs->fb.ey)) < 1e-12 || fabs(dv_dot(cs->fa.ex, cs->fb.ex)) < 1e-12;
    cs->n_axes = aligned ? 2 : 4;
    for (int k = 0; k < cs->n_axes; k++)
        cs->axes[k] = all[k], cs->ha[k] = half_width(&cs->fa, all[k]), cs->hb[k] = half_width(&cs->fb, all[k]);
}

/* One side of the touch along the tangent u: the part of the square centred at c (frame f) that lies furthest
 * along dir, a corner or a side, as the interval [*lo, *hi] of its u coordinates. */
static void support(const cast_frame *f, dvec2 c, dvec2 dir, dvec2 u, double *lo, double *hi)
{
    dvec2 corner[4];
    double top = -INFINITY;
    for (int k = 0; k < 4; k++) {
        corner[k] = dv_add(c, dv_add(dv_scale(f->ex, k & 1 ? 0.5 : -0.5), dv_scale(f->ey, k & 2 ? 0.5 : -0.5)));
        top = fmax(top, dv_dot(dir, corner[k]));
    }
    *lo = INFINITY, *hi = -INFINITY;
    for (int k = 0; k < 4; k++)
        if (dv_dot(dir, corner[k]) >= top - 1e-9)
            *lo = fmin(*lo, dv_dot(u, corner[k])), *hi = fmax(*hi, dv_dot(u, corner[k]));
}

/* The square of the cast body's pixel centred at ca against the candidate's centred at cb: where their open
 * interiors first meet along the travel, if earlier than the hit so far. */
static void cast_pair(cast_state *cs, dvec2 ca, dvec2 cb)
{
    double enter = -INFINITY, leave = INFINITY;
    dvec2 normal = dv(0, 0);
    for (int k = 0; k < cs->n_axes; k++) {
        const dvec2 n = cs->axes[k];
        const double reach = cs->ha[k] + cs->hb[k] - CAST_TOUCH, g = dv_dot(n, dv_sub(ca, cb)), v = dv_dot(n, cs->T);
        if (fabs(v) < 1e-12) {
            if (fabs(g) >= reach)
                return;
            continue;
        }
        const double t0 = (-reach - g) / v, t1 = (reach - g) / v;
        if (fmin(t0, t1) > enter)
            enter = fmin(t0, t1), normal = v > 0 ? dv_scale(n, -1) : n;
        leave = fmin(leave, fmax(t0, t1));
        if (enter >= leave || enter > cs->t + CAST_TIE)
            return;
    }
    if (!(leave > 0))
        return;
    if (enter <= 0) { /* overlapping at the start: nothing comes earlier */
        cs->t = 0, cs->hit = cs->b, cs->normal = dv(0, 0), cs->ca = ca, cs->cb = cb;
        return;
    }
    const dvec2 u = dv(-normal.y, normal.x);
    double a0, a1, b0, b1;
    support(&cs->fa, dv_add(ca, dv_scale(cs->T, enter)), dv_scale(normal, -1), u, &a0, &a1);
    support(&cs->fb, cb, normal, u, &b0, &b1);
    const double lo = fmax(a0, b0), hi = fmin(a1, b1);
    if (enter < cs->t - CAST_TIE) {
        cs->t = enter, cs->hit = cs->b, cs->normal = normal, cs->lo = lo, cs->hi = hi;
        cs->level = dv_dot(normal, cb) + half_width(&cs->fb, normal);
    } else if (cs->hit == cs->b && dv_dot(normal, cs->normal) > 1 - 1e-12) {
        cs->lo = fmin(cs->lo, lo), cs->hi = fmax(cs->hi, hi);
    }
}

/* The columns and rows of r's solid bounds that the world box [lo, hi], grown by `grow` px, reaches in bd's
 * bitmap frame; false when none. */
static bool local_rect(const body *bd, dvec2 lo, dvec2 hi, double grow, int32_t *x0, int32_t *y0, int32_t *x1,
                       int32_t *y1)
{
    const pp_raster *r = &bd->raster;
    double ax = INFINITY, ay = INFINITY, bx = -INFINITY, by = -INFINITY;
    for (int k = 0; k < 4; k++) {
        const dvec2 q = body_world_to_local(bd, dv(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y));
        ax = fmin(ax, q.x), ay = fmin(ay, q.y), bx = fmax(bx, q.x), by = fmax(by, q.y);
    }
    ax = fmax(floor(ax - grow), r->x0), ay = fmax(floor(ay - grow), r->y0);
    bx = fmin(ceil(bx + grow), r->x1 - 1.0), by = fmin(ceil(by + grow), r->y1 - 1.0);
    if (!(ax <= bx && ay <= by))
        return false;
    *x0 = (int32_t)ax, *y0 = (int32_t)ay, *x1 = (int32_t)bx, *y1 = (int32_t)by;
    return true;
}

/* The pixels [*ia, *ib), within [lo, hi), whose squares meet the coordinates from a to b. */
static void span(double a, double b, int32_t lo, int32_t hi, int32_t *ia, int32_t *ib)
{
    *ia = (int32_t)fmin(fmax(floor(a), lo), hi), *ib = (int32_t)fmax(fmin(ceil(b), hi), lo);
}

/* Sweep the edge pixels of `mover` (the cast body or the candidate), moving by `rel` against the other, over every
 * solid pixel of `still` its square passes; each pair is tested as (cast body's square, candidate's square). */
static void sweep(cast_state *cs, const body *mover, const body *still, dvec2 rel)
{
    const bool mover_is_a = mover == cs->a;
    const cast_frame *fm = mover_is_a ? &cs->fa : &cs->fb;
    const pp_raster *rm = &mover->raster, *rs = &still->raster;
    /* Mover pixels that can reach still's box within the travel left. */
    const dvec2 go = dv_scale(rel, cs->t);
    const pp_aabb sb = still->aabb;
    int32_t mx0, my0, mx1, my1;
    if (!local_rect(mover, dv(fmin(sb.x0, sb.x0 - go.x), fmin(sb.y0, sb.y0 - go.y)),
                    dv(fmax(sb.x1, sb.x1 - go.x), fmax(sb.y1, sb.y1 - go.y)), 2, &mx0, &my0, &mx1, &my1))
        return;
    const double h = 0.5 * (fabs(mover->cos_a * still->cos_a + mover->sin_a * still->sin_a) +
                            fabs(mover->sin_a * still->cos_a - mover->cos_a * still->sin_a)) + 1e-6;
    for (int32_t y = my0; y <= my1 && cs->t > 0; y++) {
        if (rm->row_count[y] == 0)
            continue;
        for (int32_t x = raster_row_next(rm, y, mx0); x <= mx1 && cs->t > 0; x = raster_row_next(rm, y, x + 1)) {
            if (!raster_edge_pixel(rm, x, y))
                continue;
            /* The still pixels the square's path meets, from the travel left. */
            const dvec2 cw = pixel_centre(fm, x, y), p0 = body_world_to_local(still, cw);
            const dvec2 p1 = body_world_to_local(still, dv_add(cw, dv_scale(rel, cs->t)));
            int32_t xa, ya, xb, yb;
            span(fmin(p0.x, p1.x) - h, fmax(p0.x, p1.x) + h, rs->x0, rs->x1, &xa, &xb);
            span(fmin(p0.y, p1.y) - h, fmax(p0.y, p1.y) + h, rs->y0, rs->y1, &ya, &yb);
            for (int32_t sy = ya; sy < yb && cs->t > 0; sy++) {
                if (rs->row_count[sy] == 0)
                    continue;
                for (int32_t sx = raster_row_next(rs, sy, xa); sx < xb && cs->t > 0;
                     sx = raster_row_next(rs, sy, sx + 1)) {
                    const dvec2 co = pixel_centre(mover_is_a ? &cs->fb : &cs->fa, sx, sy);
                    cast_pair(cs, mover_is_a ? cw : co, mover_is_a ? co : cw);
                }
            }
        }
    }
}

/* Would the cast body b meet o at all: not itself, not a sensor, and its filter, the call's and its joints let it. */
static bool cast_meets(const world *wd, const body *b, const body *o, uint32_t mask_bits)
{
    return o != b && !o->is_sensor && !raster_empty(&o->raster) && (o->category_bits & mask_bits) &&
           (b->category_bits & o->mask_bits) && (o->category_bits & b->mask_bits) && !joint_keeps_apart(wd, b, o);
}

PP_API pp_status pp_world_cast_body(pp_world w, pp_body b, pp_vec2 translation, uint32_t mask_bits,
                                    pp_raycast_hit *out, int32_t *hit)
{
    static const char *fn = "pp_world_cast_body";
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, fn, &wd, &bd);
    if (st)
        return st;
    if (!out || !hit)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s is NULL", fn, out ? "hit" : "out");
    if (!finite2(translation.x, translation.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: translation must be finite, got (%g, %g)", fn, translation.x,
                       translation.y);
    *out = (pp_raycast_hit){0};
    *hit = 0;
    if (raster_empty(&bd->raster))
        return PP_OK;
    cast_state cs = {.a = bd, .fa = frame_of(bd), .T = dv(translation.x, translation.y), .t = 1.0};
    const pp_aabb a = bd->aabb;
    const pp_aabb swept = {fmin(a.x0, a.x0 + cs.T.x) - 2, fmin(a.y0, a.y0 + cs.T.y) - 2, fmax(a.x1, a.x1 + cs.T.x) + 2,
                           fmax(a.y1, a.y1 + cs.T.y) + 2};
    int32_t *near = NULL, n = 0;
    if ((st = awake_bodies_in_box(wd, fn, swept, &near, &n)))
        return st;
    /* In slot order, keeping the first of equal entries. */
    for (int32_t k = 0; k < n && cs.t > 0; k++) {
        const body *o = wd->bodies[near[k]];
        if (!cast_meets(wd, bd, o, mask_bits))
            continue;
        cast_candidate(&cs, o);
        sweep(&cs, bd, o, cs.T);
        sweep(&cs, o, bd, dv_scale(cs.T, -1));
    }
    pp_free(near);
    if (!cs.hit)
        return PP_OK;
    dvec2 p, nrm = cs.normal;
    if (cs.t > 0) {
        p = dv_add(dv_scale(nrm, cs.level), dv_scale(dv(-nrm.y, nrm.x), 0.5 * (cs.lo + cs.hi)));
    } else { /* overlapping at the start: between the two squares, the normal against the travel */
        p = dv_scale(dv_add(cs.ca, cs.cb), 0.5);
        const double len = dv_norm(cs.T);
        nrm = len > 0 ? dv_scale(cs.T, -1 / len) : dv(0, 0);
    }
    *out = (pp_raycast_hit){cs.hit->handle, vec2_of(p), vec2_of(nrm), (float)cs.t, 0};
    *hit = 1;
    return PP_OK;
}
