/* pp_world_move_character: a capsule the host owns, moved against the bodies' solid pixels. Each cast is exact: the
 * capsule's centre is a ray against every pixel square grown by the capsule (the square swept along the capsule's
 * segment, rounded by its radius); a move is a few casts, each hit a plane the rest of the motion slides along (as
 * Box2D's b2SolvePlanes), then a step over a ledge, a snap to the ground and a probe that finds the ground. The
 * ground's normal is the solid pixels' own (the direction away from their weighted centroid near the touch). The
 * casts read the edge pixels listed once a move; a walker's height then rides that exact contact smoothed. */
#include "alloc.h"
#include "awake.h"
#include "check.h"
#include "cover.h"
#include "status.h"

#include <string.h>

#define MOVER_SKIN 0.02       /* px kept between the capsule and the pixels after every cast */
#define MOVER_ITERATIONS 6    /* casts of one slide */
#define MOVER_PLANES 4        /* planes one slide keeps */
#define MOVER_PROBE 0.1       /* px below the capsule that still counts as standing */
#define MOVER_NORMAL_RADIUS 8 /* px around the touch whose pixels give the ground's normal */
/* A walker rides the pixels' exact contact smoothed: its height moves toward it by at most MOVER_RIDE_RATE, riding up
 * to MOVER_RIDE_SINK into the pixel centres (under the contract's half pixel) or MOVER_RIDE_FLOAT above the pixels,
 * so that ±1 px noise does not shake it. On ground sloping more than MOVER_RIDE_LEVEL (the pixel normal's slope on
 * ±1 px noise stays under 0.21) the rate grows by twice the excess slope times the travel, so that a slope is
 * followed, not sunk into. The next move starts again from the exact contact, looked for from MOVER_RIDE_LIFT above
 * (more than a ride sinks: the centres' half pixel, the sink and the skin). */
#define MOVER_RIDE_RATE 18.0  /* px/s: 0.3 px a frame at 60 Hz */
#define MOVER_RIDE_LEVEL 0.25 /* rise per px */
#define MOVER_RIDE_SINK 0.4   /* px */
#define MOVER_RIDE_FLOAT 1.5  /* px */
#define MOVER_RIDE_LIFT 1.5   /* px */

PP_API pp_character_def pp_character_def_default(void)
{
    pp_character_def d = {0};
    d.struct_size = sizeof d;
    d.radius = 8.0f;
    d.half_height = 8.0f;
    d.step_height = 4.0f;
    d.snap_distance = 4.0f;
    d.max_slope = 0.8f;
    d.mask_bits = 0xffffffffu;
    return d;
}

/* A candidate body with the capsule's grown pixel square in its bitmap frame: a convex polygon (the square swept
 * along the capsule's segment, counter-clockwise about a pixel's centre) rounded by the radius. */
typedef struct mover_body {
    const body *b;
    dvec2 v[8], n[8]; /* vertices and each edge's outward normal (edge k from v[k] to v[k+1]) */
    double len[8];
    int nv;
    int32_t first, count; /* its edge pixels in mover.px, row by row, within the move's reach */
} mover_body;

typedef struct mover_pixel {
    int32_t x, y;
} mover_pixel;

typedef struct mover {
    const world *wd;
    double r, hh;
    dvec2 up;
    mover_body *bodies;
    int32_t n;
    /* The candidates' edge pixels (solid with an empty neighbour: only they can be met first), found once a move
     * from the rows' bits; every cast reads them instead of the bitmaps. */
    mover_pixel *px;
    int32_t n_px, px_capacity;
    dvec2 lo, hi; /* the world box whose edge pixels px holds */
} mover;

typedef struct mover_hit {
    double t;          /* fraction of the motion before the touch */
    dvec2 normal;      /* world, out of the pixels */
    dvec2 point;       /* world, px */
    const body *b;
} mover_hit;

static double cross(dvec2 a, dvec2 b) { return a.x * b.y - a.y * b.x; }

/* The convex hull, counter-clockwise, of the square's corners moved by ±d (monotone chain over 8 points). */
static void grown_square(mover_body *mb, dvec2 d)
{
    dvec2 p[8];
    int k = 0;
    for (int s = -1; s <= 1; s += 2)
        for (int c = 0; c < 4; c++)
            p[k++] = dv((c & 1 ? 0.5 : -0.5) + s * d.x, (c & 2 ? 0.5 : -0.5) + s * d.y);
    for (int i = 1; i < 8; i++) /* sort by x, then y */
        for (int j = i; j > 0 && (p[j].x < p[j - 1].x || (p[j].x == p[j - 1].x && p[j].y < p[j - 1].y)); j--) {
            const dvec2 t = p[j];
            p[j] = p[j - 1], p[j - 1] = t;
        }
    dvec2 h[16];
    int m = 0;
    for (int i = 0; i < 8; i++) {
        while (m >= 2 && cross(dv_sub(h[m - 1], h[m - 2]), dv_sub(p[i], h[m - 2])) <= 1e-12)
            m--;
        h[m++] = p[i];
    }
    for (int i = 6, lo = m + 1; i >= 0; i--) {
        while (m >= lo && cross(dv_sub(h[m - 1], h[m - 2]), dv_sub(p[i], h[m - 2])) <= 1e-12)
            m--;
        h[m++] = p[i];
    }
    mb->nv = m - 1;
    for (int i = 0; i < mb->nv; i++) {
        const dvec2 e = dv_sub(h[i + 1], h[i]);
        mb->v[i] = h[i], mb->len[i] = dv_norm(e), mb->n[i] = dv_scale(dv(e.y, -e.x), 1 / mb->len[i]);
    }
}

/* The pixels of bd's solid bounds under the world box [lo, hi] (its corners mapped into the bitmap), inclusive, as
 * whole numbers in doubles; false when none. */
static bool pixel_box(const body *bd, dvec2 lo, dvec2 hi, double *ax, double *ay, double *bx, double *by)
{
    const pp_raster *r = &bd->raster;
    *ax = *ay = INFINITY, *bx = *by = -INFINITY;
    for (int c = 0; c < 4; c++) {
        const dvec2 q = body_world_to_local(bd, dv(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y));
        *ax = fmin(*ax, q.x), *ay = fmin(*ay, q.y), *bx = fmax(*bx, q.x), *by = fmax(*by, q.y);
    }
    *ax = fmax(floor(*ax), r->x0), *ay = fmax(floor(*ay), r->y0);
    *bx = fmin(ceil(*bx), r->x1 - 1.0), *by = fmin(ceil(*by), r->y1 - 1.0);
    return *ax <= *bx && *ay <= *by;
}

/* Append mb's edge pixels within the world box [lo, hi] to mv->px, row by row; false when out of memory. */
static bool collect_edges(mover *mv, mover_body *mb, dvec2 lo, dvec2 hi)
{
    const body *bd = mb->b;
    const pp_raster *r = &bd->raster;
    mb->first = mv->n_px, mb->count = 0;
    double ax, ay, bx, by;
    if (!pixel_box(bd, lo, hi, &ax, &ay, &bx, &by))
        return true;
    const int32_t x0 = (int32_t)ax, w = (int32_t)(bx - ax) + 1;
    if (w <= 62) { /* one word a row: each row read once, rolling down */
        uint64_t above = raster_row_bits(r, (int32_t)ay - 1, x0 - 1), row = raster_row_bits(r, (int32_t)ay, x0 - 1);
        for (int32_t y = (int32_t)ay; y <= (int32_t)by; y++) {
            const uint64_t below = raster_row_bits(r, y + 1, x0 - 1);
            for (uint64_t e = row ? raster_edge_bits_of(above, row, below, w) : 0; e; e &= e - 1) {
                if (!ARRAY_RESERVE(mv->px, mv->px_capacity, mv->n_px + 1))
                    return false;
                mv->px[mv->n_px++] = (mover_pixel){x0 + __builtin_ctzll(e), y};
                PP_ASSERT(raster_edge_pixel(r, mv->px[mv->n_px - 1].x, y));
            }
            above = row, row = below;
        }
        mb->count = mv->n_px - mb->first;
        return true;
    }
    for (int32_t y = (int32_t)ay; y <= (int32_t)by; y++) {
        if (r->row_count[y] == 0)
            continue;
        for (int32_t x = x0; x <= (int32_t)bx; x += 62) {
            const int32_t n = (int32_t)fmin(62, bx - x + 1);
            for (uint64_t e = raster_edge_bits(r, y, x, n); e; e &= e - 1) {
                if (!ARRAY_RESERVE(mv->px, mv->px_capacity, mv->n_px + 1))
                    return false;
                mv->px[mv->n_px++] = (mover_pixel){x + __builtin_ctzll(e), y};
            }
        }
    }
    mb->count = mv->n_px - mb->first;
    return true;
}

/* Where the ray q + t·D (bitmap frame, t in [0, *t)) first enters the grown square centred at c; *t, *n updated.
 * dlen is |D|. */
static void ray_grown(const mover_body *mb, double r, dvec2 q, dvec2 D, double dlen, dvec2 c, double *t, dvec2 *n)
{
    const dvec2 p = dv_sub(q, c);
    /* The deepest face's distance bounds the distance to the polygon from below: a ray that cannot close it to r
     * meets nothing (most pixels of a cast's box). */
    double side[8], deepest = -INFINITY;
    int deep_k = 0;
    for (int k = 0; k < mb->nv; k++) {
        side[k] = dv_dot(mb->n[k], dv_sub(p, mb->v[k]));
        if (side[k] > deepest)
            deepest = side[k], deep_k = k;
    }
    if (deepest - dlen * *t >= r)
        return;
    /* Inside already (deeper than rounding): a touch at 0 unless the motion leaves it. */
    if (deepest < r - 1e-7) {
        dvec2 out = mb->n[deep_k];
        if (deepest > 0) { /* near a vertex or an edge outside the polygon: the nearest feature's direction */
            double best = INFINITY;
            dvec2 f_best = out;
            int k_best = deep_k;
            for (int k = 0; k < mb->nv; k++) {
                const dvec2 e = dv(-mb->n[k].y, mb->n[k].x), w = dv_sub(p, mb->v[k]);
                const double u = dmin(dmax(dv_dot(w, e), 0), mb->len[k]);
                const dvec2 f = dv_sub(w, dv_scale(e, u));
                const double dist2 = dv_dot(f, f);
                if (dist2 < best)
                    best = dist2, f_best = f, k_best = k;
            }
            if (best >= (r - 1e-7) * (r - 1e-7))
                goto outside;
            const double dist = sqrt(best);
            out = dist > 0 ? dv_scale(f_best, 1 / dist) : mb->n[k_best];
        }
        if (dv_dot(out, D) < 0)
            *t = 0, *n = out;
        return;
    }
outside:;
    const double a = dv_dot(D, D);
    for (int k = 0; k < mb->nv; k++) {
        const double dn = dv_dot(mb->n[k], D);
        if (dn < 0) { /* the edge's face, moved out by r */
            const double te = (r - side[k]) / dn;
            if (te >= 0 && te < *t) {
                const dvec2 e = dv(-mb->n[k].y, mb->n[k].x);
                const double u = dv_dot(e, dv_sub(dv_add(p, dv_scale(D, te)), mb->v[k]));
                if (u >= 0 && u <= mb->len[k])
                    *t = te, *n = mb->n[k];
            }
        }
        /* The vertex's disc. */
        const dvec2 w = dv_sub(p, mb->v[k]);
        const double b = dv_dot(w, D);
        if (b < 0 && a > 0) {
            const double disc = b * b - a * (dv_dot(w, w) - r * r);
            if (disc > 0) {
                const double tv = (-b - sqrt(disc)) / a;
                if (tv >= 0 && tv < *t)
                    *t = tv, *n = dv_scale(dv_add(w, dv_scale(D, tv)), 1 / r);
            }
        }
    }
}

/* The first touch of the capsule moved from p by d, or hit->b NULL. */
static void capsule_cast(const mover *mv, dvec2 p, dvec2 d, mover_hit *hit)
{
    *hit = (mover_hit){.t = 1.0};
    const double rx = mv->r + 1.5, ry = mv->r + mv->hh + 1.5;
    const dvec2 lo = dv(fmin(p.x, p.x + d.x) - rx, fmin(p.y, p.y + d.y) - ry);
    const dvec2 hi = dv(fmax(p.x, p.x + d.x) + rx, fmax(p.y, p.y + d.y) + ry);
    PP_ASSERT(lo.x >= mv->lo.x && lo.y >= mv->lo.y && hi.x <= mv->hi.x && hi.y <= mv->hi.y);
    for (int32_t k = 0; k < mv->n; k++) {
        const mover_body *mb = &mv->bodies[k];
        const body *bd = mb->b;
        if (bd->aabb.x0 > hi.x || bd->aabb.x1 < lo.x || bd->aabb.y0 > hi.y || bd->aabb.y1 < lo.y)
            continue;
        double ax, ay, bx, by;
        if (!pixel_box(bd, lo, hi, &ax, &ay, &bx, &by))
            continue;
        const dvec2 q = body_world_to_local(bd, p), D = dv_unrot(d, bd->cos_a, bd->sin_a);
        const double dlen = sqrt(dv_dot(D, D));
        double t = hit->t;
        dvec2 n = dv(0, 0);
        int32_t hx = 0, hy = 0;
        const mover_pixel *px = mv->px + mb->first, *end = px + mb->count;
        int32_t a = 0, z = mb->count; /* the first at or past row ay */
        while (a < z) {
            const int32_t mid = a + (z - a) / 2;
            if (px[mid].y < ay)
                a = mid + 1;
            else
                z = mid;
        }
        /* A body whose columns run along the capsule (unrotated, or by half turns): per row, only the pixels within
         * the capsule-and-square's half width of the path (the least gap over the path, as if its every point were
         * the nearest) can be met. */
        const bool upright = bd->sin_a == 0;
        int32_t row = INT32_MIN;
        double row_x0 = ax, row_x1 = bx;
        for (px += a; px < end && px->y <= by; px++) {
            if (upright && px->y != row) {
                row = px->y;
                const double y0 = dmin(q.y, q.y + D.y * t), y1 = dmax(q.y, q.y + D.y * t), cy = row + 0.5;
                const double e = dmax(0, dmax(y0 - cy, cy - y1) - mv->hh - 0.5);
                const double hw = e < mv->r ? 0.5 + sqrt(mv->r * mv->r - e * e) + 1e-6 : -1;
                row_x0 = dmax(ax, dmin(q.x, q.x + D.x * t) - hw - 0.5), row_x1 = dmin(bx, dmax(q.x, q.x + D.x * t) + hw - 0.5);
            }
            if (px->x < row_x0 || px->x > row_x1)
                continue;
            const double before = t;
            ray_grown(mb, mv->r, q, D, dlen, dv(px->x + 0.5, px->y + 0.5), &t, &n);
            if (t < before)
                hx = px->x, hy = px->y;
        }
        if (t < hit->t || (t == hit->t && !hit->b && t < 1.0)) {
            const dvec2 nw = dv_rot(n, bd->cos_a, bd->sin_a);
            /* The touch: the capsule's point furthest against the normal (on a flat side, level with the pixel). */
            const dvec2 at = dv_add(p, dv_scale(d, t)), centre = body_local_to_world(bd, dv(hx + 0.5, hy + 0.5));
            const double along = fabs(nw.y) > 1e-6 ? (nw.y > 0 ? -mv->hh : mv->hh) : fmin(fmax(centre.y - at.y, -mv->hh), mv->hh);
            *hit = (mover_hit){t, nw, dv_sub(dv_add(at, dv(0, along)), dv_scale(nw, mv->r)), bd};
        }
    }
}

/* The first δ at which the point w − δ·D comes within rr of the segment {s·a : |s| ≤ hh} (a unit), or INFINITY. */
static double point_capsule(dvec2 w, dvec2 D, dvec2 a, double hh, double rr)
{
    double first = INFINITY;
    for (int e = -1; e <= 1; e += 2) { /* the end discs */
        const dvec2 c = dv_sub(w, dv_scale(a, e * hh));
        const double A = dv_dot(D, D), B = -dv_dot(c, D), C = dv_dot(c, c) - rr * rr, disc = B * B - A * C;
        if (A > 0 && disc >= 0) {
            const double t = (-B - sqrt(disc)) / A;
            if (t >= 0 && t < first)
                first = t;
        }
    }
    const dvec2 nrm = dv(-a.y, a.x);
    const double u0 = dv_dot(w, nrm), du = dv_dot(D, nrm);
    for (int e = -1; e <= 1 && du != 0; e += 2) { /* the sides */
        const double t = (u0 - e * rr) / du, along = dv_dot(dv_sub(w, dv_scale(D, t)), a);
        if (t >= 0 && t < first && fabs(along) <= hh)
            first = t;
    }
    return first;
}

/* How far the capsule at p moves by `dir` (unit), up to max, before its axis comes within rr of a solid pixel's
 * centre; p clear of them by rr. Only edge pixels' centres can be met first (an inner one has a neighbour nearer). */
static double sink_room(const mover *mv, dvec2 p, dvec2 dir, double max, double rr)
{
    const double rx = rr + 1.5, ry = rr + mv->hh + 1.5;
    const dvec2 e = dv_add(p, dv_scale(dir, max));
    const dvec2 lo = dv(dmin(p.x, e.x) - rx, dmin(p.y, e.y) - ry), hi = dv(dmax(p.x, e.x) + rx, dmax(p.y, e.y) + ry);
    PP_ASSERT(lo.x >= mv->lo.x && lo.y >= mv->lo.y && hi.x <= mv->hi.x && hi.y <= mv->hi.y);
    double room = max;
    for (int32_t k = 0; k < mv->n; k++) {
        const mover_body *mb = &mv->bodies[k];
        const body *bd = mb->b;
        if (bd->aabb.x0 > hi.x || bd->aabb.x1 < lo.x || bd->aabb.y0 > hi.y || bd->aabb.y1 < lo.y)
            continue;
        double ax = INFINITY, ay = INFINITY, bx = -INFINITY, by = -INFINITY;
        for (int c = 0; c < 4; c++) {
            const dvec2 q = body_world_to_local(bd, dv(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y));
            ax = dmin(ax, q.x), ay = dmin(ay, q.y), bx = dmax(bx, q.x), by = dmax(by, q.y);
        }
        const dvec2 q = body_world_to_local(bd, p), D = dv_unrot(dir, bd->cos_a, bd->sin_a);
        const dvec2 a = dv_unrot(dv(0, 1), bd->cos_a, bd->sin_a);
        const mover_pixel *px = mv->px + mb->first, *end = px + mb->count;
        for (; px < end && px->y <= by; px++)
            if (px->y >= ay - 1 && px->x >= ax - 1 && px->x <= bx)
                room = dmin(room, point_capsule(dv(px->x + 0.5 - q.x, px->y + 0.5 - q.y), D, a, mv->hh, rr));
    }
    return room;
}

/* Move from *p by d until a touch, stopping MOVER_SKIN short of it; the part of d moved. */
static double advance(const mover *mv, dvec2 *p, dvec2 d, mover_hit *hit)
{
    capsule_cast(mv, *p, d, hit);
    if (!hit->b) {
        *p = dv_add(*p, d);
        return 1.0;
    }
    const double len = dv_norm(d), into = len > 0 ? -dv_dot(d, hit->normal) / len : 1;
    const double t = len > 0 ? fmax(0, hit->t - MOVER_SKIN / (len * fmax(into, 0.1))) : 0;
    *p = dv_add(*p, dv_scale(d, t));
    return t;
}

/* The ground's own normal at a world point of body bd: away from the weighted centroid of its solid pixels near it. */
static dvec2 pixel_normal(const body *bd, dvec2 point, dvec2 fallback)
{
    const pp_raster *r = &bd->raster;
    const dvec2 c = body_world_to_local(bd, point);
    const double R = MOVER_NORMAL_RADIUS;
    const int32_t y0 = (int32_t)fmax(floor(c.y - R), r->y0), y1 = (int32_t)fmin(ceil(c.y + R), r->y1 - 1.0);
    const int32_t x0 = (int32_t)fmax(floor(c.x - R), r->x0), x1 = (int32_t)fmin(ceil(c.x + R), r->x1 - 1.0);
    double sx = 0, sy = 0;
    PP_ASSERT(x1 - x0 < 63);
    for (int32_t y = y0; y <= y1; y++) {
        if (r->row_count[y] == 0 || x0 > x1)
            continue;
        for (uint64_t m = raster_row_bits(r, y, x0) & (((uint64_t)2 << (x1 - x0)) - 1); m; m &= m - 1) {
            const int32_t x = x0 + __builtin_ctzll(m);
            const double dx = x + 0.5 - c.x, dy = y + 0.5 - c.y, w = 1 - (dx * dx + dy * dy) / (R * R);
            if (w > 0)
                sx += w * w * dx, sy += w * w * dy;
        }
    }
    const dvec2 n = dv_rot(dv(-sx, -sy), bd->cos_a, bd->sin_a);
    const double len = dv_norm(n);
    return len > 1e-9 ? dv_scale(n, 1 / len) : fallback;
}

/* Project v onto the planes' cone (v·n ≥ 0 for each): cyclic projections, then zero if one still cuts in. */
static dvec2 clip_planes(dvec2 v, const dvec2 *planes, int np)
{
    for (int it = 0; it < 16; it++) {
        bool changed = false;
        for (int k = 0; k < np; k++) {
            const double s = dv_dot(v, planes[k]);
            if (s < 0)
                v = dv_sub(v, dv_scale(planes[k], s)), changed = true;
        }
        if (!changed)
            return v;
    }
    for (int k = 0; k < np; k++)
        if (dv_dot(v, planes[k]) < -1e-9)
            return dv(0, 0);
    return v;
}

typedef struct slide_result {
    dvec2 p, v;
    int32_t surfaces;
    bool wall; /* met ground steeper than max_slope while walking */
} slide_result;

/* Cast and slide: d from p, the velocity v losing what each plane met takes. A steep plane met while walking
 * (not rising of its own) does not lift the character: its normal counts level. */
static slide_result slide(const mover *mv, double cos_slope, dvec2 p, dvec2 d, dvec2 v, const mover_hit *touching)
{
    slide_result s = {p, v, 0, false};
    dvec2 planes[MOVER_PLANES];
    int np = 0;
    const bool rising = dv_dot(d, mv->up) > 1e-9;
    for (int it = 0; it < MOVER_ITERATIONS && dv_norm(d) > 1e-7; it++) {
        mover_hit hit;
        double moved;
        /* A touch p already rests on (a skin away) that d goes into: the first cast's answer, known. */
        if (it == 0 && touching && touching->b && -dv_dot(d, touching->normal) > MOVER_SKIN)
            hit = *touching, moved = 0;
        else
            moved = advance(mv, &s.p, d, &hit);
        if (!hit.b)
            break;
        s.surfaces++;
        dvec2 n = hit.normal;
        const double nu = dv_dot(n, mv->up);
        if (nu > -1e-9 && nu < cos_slope && !rising) {
            const dvec2 level = dv_sub(n, dv_scale(mv->up, nu));
            const double l = dv_norm(level);
            const dvec2 rest = dv_scale(d, 1 - moved), along = dv_sub(rest, dv_scale(n, dv_dot(rest, n)));
            /* Sliding along the real slope would lift it: a wall instead. */
            if (l > 1e-9 && dv_dot(along, mv->up) > 1e-9 && dv_dot(rest, level) < 0) {
                n = dv_scale(level, 1 / l);
                s.wall = true;
            }
        }
        if (np == MOVER_PLANES)
            memmove(planes, planes + 1, sizeof planes[0] * (MOVER_PLANES - 1)), np--;
        planes[np++] = n;
        if (n.x != hit.normal.x || n.y != hit.normal.y) {
            if (np == MOVER_PLANES)
                memmove(planes, planes + 1, sizeof planes[0] * (MOVER_PLANES - 1)), np--;
            planes[np++] = hit.normal;
        }
        d = clip_planes(dv_scale(d, 1 - moved), planes, np);
        s.v = clip_planes(s.v, planes, np);
    }
    return s;
}

typedef struct ground {
    const body *b;
    dvec2 normal, point;
} ground;

/* The ground a cast down met: its body, its pixels' normal and the touch; b NULL when none or not walkable. */
static ground ground_of(const mover *mv, double cos_slope, const mover_hit *hit_)
{
    const mover_hit hit = *hit_;
    if (!hit.b || dv_dot(hit.normal, mv->up) <= 0)
        return (ground){0};
    const dvec2 n = pixel_normal(hit.b, hit.point, hit.normal);
    if (dv_dot(n, mv->up) < cos_slope)
        return (ground){0};
    return (ground){hit.b, n, hit.point};
}

/* The walkable ground within `depth` below p. */
static ground find_ground(const mover *mv, double cos_slope, dvec2 p, double depth)
{
    mover_hit hit;
    capsule_cast(mv, p, dv_scale(mv->up, -depth), &hit);
    return ground_of(mv, cos_slope, &hit);
}

static pp_status check_def(const pp_character_def *def, const char *fn)
{
    if (def->struct_size != sizeof(pp_character_def))
        return pp_fail(PP_ERR_ABI, "%s: def->struct_size is %u, this library expects %u", fn,
                       (unsigned)def->struct_size, (unsigned)sizeof(pp_character_def));
    const struct {
        const char *name;
        float value, max;
        bool positive;
    } f[] = {{"radius", def->radius, 1e6f, true},          {"half_height", def->half_height, 1e6f, false},
             {"step_height", def->step_height, 1e6f, false}, {"snap_distance", def->snap_distance, 1e6f, false},
             {"max_slope", def->max_slope, (float)(PP_PI / 2), false}};
    for (size_t k = 0; k < sizeof f / sizeof f[0]; k++)
        if (!isfinite(f[k].value) || f[k].value < 0 || (f[k].positive && f[k].value == 0) || f[k].value > f[k].max)
            return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: def->%s must be %s and at most %g, got %g", fn, f[k].name,
                           f[k].positive ? "> 0" : "≥ 0", f[k].max, f[k].value);
    return PP_OK;
}

PP_API pp_status pp_world_move_character(pp_world w, const pp_character_def *def, pp_vec2 position, pp_vec2 velocity,
                                         float dt, pp_character_move *out)
{
    static const char *fn = "pp_world_move_character";
    world *wd = world_lookup(w, fn);
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!def || !out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: %s is NULL", fn, def ? "out" : "def");
    pp_status st = check_def(def, fn);
    if (st)
        return st;
    if (!finite2(position.x, position.y) || !finite2(velocity.x, velocity.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: position and velocity must be finite, got (%g, %g) and (%g, %g)",
                       fn, position.x, position.y, velocity.x, velocity.y);
    if (!(hypot(velocity.x, velocity.y) <= PP_MAX_SPEED))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: velocity (%g, %g) px/s is over PP_MAX_SPEED (%g px/s)", fn,
                       velocity.x, velocity.y, PP_MAX_SPEED);
    if (!(dt >= 0 && dt <= 1))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: dt must be in [0, 1] s, got %g", fn, dt);

    const dvec2 g = dv(wd->def.gravity.x, wd->def.gravity.y);
    const double gl = dv_norm(g);
    mover mv = {.wd = wd, .r = def->radius, .hh = def->half_height, .up = gl > 0 ? dv_scale(g, -1 / gl) : dv(0, -1)};
    const double cos_slope = cos(def->max_slope) - 1e-6;
    const dvec2 p0 = dv(position.x, position.y), v0 = dv(velocity.x, velocity.y), d = dv_scale(v0, dt);

    /* Every body the whole move can reach: the motion, a step up and a snap down, the capsule and a pixel. */
    const double reach = def->radius + def->half_height + def->step_height + def->snap_distance + MOVER_NORMAL_RADIUS + 2;
    /* What the casts reach: the capsule's bound around the motion, a step up or a snap down, and a pixel. */
    const double cast_reach = def->radius + def->half_height + fmax(def->step_height, def->snap_distance) +
                              MOVER_RIDE_LIFT + MOVER_RIDE_FLOAT + MOVER_PROBE + 3;
    /* Slides turn the motion but never lengthen it: every cast stays within |d| of the start (the ride's lift or
     * drop from p0), and a step or a snap. */
    const double go = dv_norm(d) + cast_reach;
    /* Under vertical gravity the lifts, drops, steps and snaps keep to the column: sideways, the motion and a disc. */
    const double go_x = mv.up.x == 0 ? dv_norm(d) + def->radius + 3 : go;
    mv.lo = dv(p0.x - go_x, p0.y - go), mv.hi = dv(p0.x + go_x, p0.y + go);
    const pp_aabb box = {fmin(p0.x, p0.x + d.x) - reach, fmin(p0.y, p0.y + d.y) - reach, fmax(p0.x, p0.x + d.x) + reach,
                         fmax(p0.y, p0.y + d.y) + reach};
    int32_t *near = NULL, n_near = 0;
    if ((st = awake_bodies_in_box(wd, fn, box, &near, &n_near)))
        return st;
    mv.bodies = n_near ? pp_malloc((size_t)n_near * sizeof *mv.bodies) : NULL;
    if (n_near && !mv.bodies) {
        pp_free(near);
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: out of memory for %d candidate bodies", fn, (int)n_near);
    }
    for (int32_t k = 0; k < n_near; k++) {
        const body *o = wd->bodies[near[k]];
        if (o->is_sensor || raster_empty(&o->raster) || !(o->category_bits & def->mask_bits))
            continue;
        mover_body *mb = &mv.bodies[mv.n++];
        mb->b = o;
        grown_square(mb, dv_unrot(dv(0, def->half_height), o->cos_a, o->sin_a));
        if (!collect_edges(&mv, mb, mv.lo, mv.hi)) {
            pp_free(near), pp_free(mv.bodies), pp_free(mv.px);
            return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: out of memory for the pixels near the character", fn);
        }
    }
    pp_free(near);

    /* A walker (not rising) may ride up to MOVER_RIDE_SINK into the pixels or MOVER_RIDE_FLOAT above them: its move
     * starts from the exact contact under it. */
    const bool walking = dv_dot(v0, mv.up) <= 1e-9;
    dvec2 e0 = p0;
    ground start = {0};
    mover_hit under = {0};
    if (walking) {
        /* A cast down is never stopped by pixels it starts in and leaves (a ceiling's): no cast up first. */
        dvec2 q = dv_add(p0, dv_scale(mv.up, MOVER_RIDE_LIFT));
        advance(&mv, &q, dv_scale(mv.up, -(MOVER_RIDE_LIFT + MOVER_RIDE_FLOAT + MOVER_PROBE)), &under);
        if ((start = ground_of(&mv, cos_slope, &under)).b)
            e0 = q;
        else
            under.b = NULL;
    } else {
        start = find_ground(&mv, cos_slope, p0, MOVER_PROBE);
    }
    slide_result s = slide(&mv, cos_slope, e0, d, v0, &under);

    /* A ledge: up by step_height, the level part of the motion, down again onto walkable ground. */
    const dvec2 level = dv_sub(d, dv_scale(mv.up, dv_dot(d, mv.up)));
    if (start.b && s.wall && def->step_height > 0 && dv_dot(d, mv.up) <= 1e-9 && dv_norm(level) > 1e-7) {
        dvec2 q = e0;
        mover_hit hit;
        advance(&mv, &q, dv_scale(mv.up, def->step_height), &hit);
        const double rose = dv_dot(dv_sub(q, e0), mv.up);
        slide_result t = slide(&mv, cos_slope, q, level, v0, NULL);
        dvec2 down = t.p;
        advance(&mv, &down, dv_scale(mv.up, -(rose + MOVER_PROBE)), &hit);
        const dvec2 lu = dv_scale(level, 1 / dv_norm(level));
        /* Climbing the rest of a taller ledge by its rounded corner is no step. */
        if (hit.b && dv_dot(dv_sub(down, e0), mv.up) <= def->step_height + 0.05 &&
            find_ground(&mv, cos_slope, down, MOVER_PROBE).b &&
            dv_dot(dv_sub(down, e0), lu) > dv_dot(dv_sub(s.p, e0), lu) + 1e-3) {
            t.p = down, t.surfaces += s.surfaces;
            s = t;
        }
    }

    /* Walking over a bump or up a slope does not launch the character: no rise it did not ask for. */
    const double rise = dv_dot(s.v, mv.up);
    if (start.b && walking && rise > 0)
        s.v = dv_sub(s.v, dv_scale(mv.up, rise));

    ground end = find_ground(&mv, cos_slope, s.p, MOVER_PROBE);
    /* Keep to the ground: a grounded character not rising snaps down to ground within snap_distance. */
    if (!end.b && start.b && def->snap_distance > 0 && walking) {
        dvec2 q = s.p;
        mover_hit hit;
        advance(&mv, &q, dv_scale(mv.up, -def->snap_distance), &hit);
        const ground there = hit.b ? find_ground(&mv, cos_slope, q, MOVER_PROBE) : (ground){0};
        if (there.b)
            s.p = q, end = there, s.surfaces++;
    }

    /* The ride: from the host's height toward the exact contact by at most MOVER_RIDE_RATE (descending as fast as
     * the motion asks), floating at most MOVER_RIDE_FLOAT above it (no ceiling crossed), sinking no deeper than
     * MOVER_RIDE_SINK into the pixel centres. */
    if (walking && start.b && end.b) {
        const double h0 = dv_dot(p0, mv.up), he = dv_dot(s.p, mv.up), nu = dv_dot(end.normal, mv.up);
        const dvec2 went = dv_sub(s.p, e0);
        const double travel = dv_norm(dv_sub(went, dv_scale(mv.up, dv_dot(went, mv.up))));
        const double slope = sqrt(dmax(0, 1 - nu * nu)) / nu; /* nu ≥ cos max_slope > 0: walkable */
        const double lim = MOVER_RIDE_RATE * dt + 2 * dmax(slope - MOVER_RIDE_LEVEL, 0) * travel;
        double h = h0 + dmin(dmax(he - h0, dmin(-lim, dv_dot(d, mv.up))), lim);
        h = dmin(h, he + MOVER_RIDE_FLOAT);
        if (h < he) {
            h = he - sink_room(&mv, s.p, dv_scale(mv.up, -1), he - h, dmax(mv.r - MOVER_RIDE_SINK, 0.5 * mv.r));
        } else if (h > he) {
            dvec2 q = s.p;
            mover_hit hit;
            advance(&mv, &q, dv_scale(mv.up, h - he), &hit);
            h = dv_dot(q, mv.up);
        }
        s.p = dv_add(s.p, dv_scale(mv.up, h - he));
    }
    pp_free(mv.bodies);
    pp_free(mv.px);

    *out = (pp_character_move){.position = vec2_of(s.p), .velocity = vec2_of(s.v), .surfaces = s.surfaces};
    if (end.b) {
        out->grounded = 1;
        out->ground_normal = vec2_of(end.normal);
        out->ground_body = end.b->handle;
        out->ground_velocity = vec2_of(body_point_velocity(wd, end.b, end.point));
    }
    return PP_OK;
}
