/* A pair whose intersection is a few pixels is a corner on a face (or a corner on a corner): the narrowphase's
 * normal, from the intersection raster alone, can lie far off the face (a flat card on a tilted card's top
 * corner: 28°, then 66°, and the flat slid off the corner). The normal is chosen again as separating axes
 * choose it for polygons: of the narrowphase's normal and either body's bitmap axes that lean from a to b, the
 * one along which the bodies' pixels within CORNER_RADIUS of the contact overlap least. A corner on a face
 * overlaps least along the face's normal: along any other axis the face's pixels reach past the corner.
 *
 * The window is what keeps a slope's normal: a slope, drawn in a terrain bitmap or not, is nearly flat across
 * a 3 px window, and there a tumbling box's own bottom face beat the slope's normal (27° off it on a 30°
 * slope); from 5 px on the slope's rise across the window outweighs the pixel steps. Pixels count as discs,
 * so that no body's axes are favoured by its squares' corners, and a face within 10° of the narrowphase's
 * normal is not tried: across the window (6 px × sin 10° = 1 px) the two cannot be told apart. Runs after
 * the backend-identical core, so CPU and GPU stay identical.
 *
 * A pair deeper than DEEP_DEPTH is chosen again the same way over a window that holds its overlap, with the
 * axes perpendicular to the narrowphase's normal tried too: two thin bodies pushed together end to end (a
 * card house's flats, built overlapping 25 px) have an area gradient that cancels across their thin axis and
 * points along them, and were pushed apart along their length, when across is the shallower way out. A
 * chosen face takes that overlap as the depth and, for a manifold, the intersection's ends along it. */
#include "corner.h"

#include <math.h>

#define CORNER_RADIUS 6.0
#define CORNER_MARGIN 0.1 /* px: the narrowphase's normal stays unless a face beats it by this */
#define COS_MIN_TURN 0.98480775301220806 /* cos 10°: a face nearer the narrowphase's normal is not tried */
#define DEEP_DEPTH 3.0  /* px: a pair deeper than this has its normal chosen again */
#define DEEP_REACH 40.0 /* px: the deep window's largest radius; a deeper pair keeps the narrowphase's normal */
#define SIN_PERP 0.17364817766693033 /* sin 10°: a deep pair's faces may lean this far back from perpendicular */
#define DEEP_AXES 9     /* the narrowphase's normal and both bodies' four axes */

/* A body's pixel centres within CORNER_RADIUS of the contact, as offsets from it in the body's bitmap frame: of
 * each row, only its first and last such pixel. A projection on a direction is monotone along a row in floating
 * point too (each rounded product and sum is), so a row's extreme projection is at one of its two ends. */
#define PATCH_REACH ((int32_t)CORNER_RADIUS)
typedef struct patch {
    const body *bd;
    int32_t n;                                   /* rows with a pixel */
    double dy[2 * PATCH_REACH + 1], dx0[2 * PATCH_REACH + 1], dx1[2 * PATCH_REACH + 1];
} patch;

/* Whether pixel x's centre, on a row dy from l, lies within CORNER_RADIUS of l. */
static bool in_reach(dvec2 l, int32_t x, double dy)
{
    const double dx = x + 0.5 - l.x;
    return dx * dx + dy * dy <= CORNER_RADIUS * CORNER_RADIUS;
}

/* Of each row, the pixels in reach are one run: the test's rounded steps are each monotone in x, so its sum falls
 * then rises along the row. The run's ends come from the test alone, then its solid ends from the row's bits. */
static void patch_gather(const body *bd, dvec2 p, patch *out)
{
    const dvec2 l = dv_add(bd->pivot, dv_unrot(dv_sub(p, bd->pos), bd->cos_a, bd->sin_a));
    const int32_t cx = (int32_t)floor(l.x), cy = (int32_t)floor(l.y), left = cx - PATCH_REACH;
    out->bd = bd, out->n = 0;
    for (int32_t y = cy - PATCH_REACH; y <= cy + PATCH_REACH; y++) {
        const double dy = y + 0.5 - l.y;
        uint64_t bits = raster_row_bits(&bd->raster, y, left) & (((uint64_t)2 << 2 * PATCH_REACH) - 1);
        if (!bits)
            continue;
        int32_t x0 = left, x1 = cx + PATCH_REACH;
        while (x0 <= x1 && !in_reach(l, x0, dy))
            x0++;
        while (x1 > x0 && !in_reach(l, x1, dy))
            x1--;
        if (x0 > x1)
            continue;
        bits &= (~(uint64_t)0 >> (63 - (x1 - left))) >> (x0 - left) << (x0 - left);
        if (!bits)
            continue;
        out->dy[out->n] = dy;
        out->dx0[out->n] = left + __builtin_ctzll(bits) + 0.5 - l.x;
        out->dx1[out->n++] = left + (63 - __builtin_clzll(bits)) + 0.5 - l.x;
    }
}

/* The extreme projection on world direction n (max, or min when !up) of the patch's pixels, each a disc of
 * half a pixel (no axis favoured), from the contact. */
static double patch_extent(const patch *pa, dvec2 n, bool up)
{
    const dvec2 u = dv_unrot(n, pa->bd->cos_a, pa->bd->sin_a);
    double best = up ? -INFINITY : INFINITY;
    for (int32_t i = 0; i < pa->n; i++) {
        const double q0 = pa->dx0[i] * u.x + pa->dy[i] * u.y + (up ? 0.5 : -0.5);
        const double q1 = pa->dx1[i] * u.x + pa->dy[i] * u.y + (up ? 0.5 : -0.5);
        best = up ? dmax(best, dmax(q0, q1)) : dmin(best, dmin(q0, q1));
    }
    return best;
}

/* How far a's patch reaches past b's along n (from a to b). */
static double patch_overlap(const patch *a, const patch *b, dvec2 n)
{
    return patch_extent(a, n, true) - patch_extent(b, n, false);
}

/* The narrowphase's normal of r's first contact, from a to b. */
static dvec2 raster_normal(const np_result *r)
{
    return dv(r->contacts[0].normal.x, r->contacts[0].normal.y);
}

/* The mean of r's contact points. */
static dvec2 contact_middle(const np_result *r)
{
    dvec2 p = dv(0, 0);
    for (int32_t k = 0; k < r->count; k++)
        p = dv_add(p, dv(r->contacts[k].point.x, r->contacts[k].point.y));
    return dv_scale(p, 1.0 / r->count);
}

static void corner_pixels(const body *a, const body *b, np_result *r)
{
    const dvec2 n0 = raster_normal(r); /* from a to b */
    static const int32_t axes[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    dvec2 faces[8];
    int32_t nf = 0;
    for (int side = 0; side < 2; side++) {
        const body *bd = side ? b : a;
        for (int k = 0; k < 4; k++) {
            const dvec2 m = dv_scale(dv_rot(dv(axes[k][0], axes[k][1]), bd->cos_a, bd->sin_a), side ? -1.0 : 1.0);
            if (dv_dot(m, n0) > 0 && dv_dot(m, n0) < COS_MIN_TURN) /* leaning from a to b, not n0 itself */
                faces[nf++] = m;
        }
    }
    if (nf == 0)
        return;
    const dvec2 p = contact_middle(r);
    patch pa, pb;
    patch_gather(a, p, &pa);
    patch_gather(b, p, &pb);
    if (pa.n == 0 || pb.n == 0)
        return;
    const double pen0 = patch_overlap(&pa, &pb, n0);
    double best = pen0;
    dvec2 n = n0;
    for (int32_t k = 0; k < nf; k++) {
        const double pen = patch_overlap(&pa, &pb, faces[k]);
        if (pen < best)
            best = pen, n = faces[k];
    }
    if (!(best < pen0 - CORNER_MARGIN))
        return;
    for (int32_t k = 0; k < r->count; k++)
        r->contacts[k].normal = (pp_vec2){(float)n.x, (float)n.y};
}

/* A deep window: bd's solid pixel centres within `radius` of world point p, visited as offsets from p in bd's
 * bitmap frame. */
typedef struct window {
    const body *bd;
    dvec2 l;                /* p in bd's bitmap frame */
    double radius;
    int32_t x0, y0, x1, y1; /* the pixels to visit, inclusive, clipped to bd's solid bounds */
} window;

static window window_at(const body *bd, dvec2 p, double radius)
{
    window w = {.bd = bd, .radius = radius};
    w.l = dv_add(bd->pivot, dv_unrot(dv_sub(p, bd->pos), bd->cos_a, bd->sin_a));
    const int32_t reach = (int32_t)ceil(radius), cx = (int32_t)floor(w.l.x), cy = (int32_t)floor(w.l.y);
    const pp_raster *r = &bd->raster;
    w.x0 = cx - reach > r->x0 ? cx - reach : r->x0, w.x1 = cx + reach < r->x1 - 1 ? cx + reach : r->x1 - 1;
    w.y0 = cy - reach > r->y0 ? cy - reach : r->y0, w.y1 = cy + reach < r->y1 - 1 ? cy + reach : r->y1 - 1;
    return w;
}

/* Whether pixel (x, y) of the window's body is solid and within it; *d gets its centre's offset from p. */
static bool window_pixel(const window *w, int32_t x, int32_t y, dvec2 *d)
{
    *d = dv(x + 0.5 - w->l.x, y + 0.5 - w->l.y);
    return dv_dot(*d, *d) <= w->radius * w->radius && raster_solid(&w->bd->raster, x, y);
}

/* The window's largest (up) or least projection on each of n world directions, pixels as discs of half a
 * pixel, from p; false when the window holds no pixel. */
static bool window_extents(const window *w, const dvec2 *dirs, int32_t n, bool up, double *out)
{
    dvec2 u[DEEP_AXES];
    for (int32_t k = 0; k < n; k++)
        u[k] = dv_unrot(dirs[k], w->bd->cos_a, w->bd->sin_a), out[k] = up ? -INFINITY : INFINITY;
    bool any = false;
    for (int32_t y = w->y0; y <= w->y1; y++)
        for (int32_t x = w->x0; x <= w->x1; x++) {
            dvec2 d;
            if (!window_pixel(w, x, y, &d))
                continue;
            any = true;
            for (int32_t k = 0; k < n; k++) {
                const double q = d.x * u[k].x + d.y * u[k].y + (up ? 0.5 : -0.5);
                out[k] = up ? dmax(out[k], q) : dmin(out[k], q);
            }
        }
    return any;
}

/* The ends along world tangent t of the intersection in a's window (a's pixels whose centres lie in b's
 * solid pixels), at the middle of its extent along n; false when the window holds none. */
static bool window_ends(const window *wa, const body *b, dvec2 p, dvec2 n, dvec2 t, dvec2 ends[2])
{
    const body *a = wa->bd;
    const dvec2 ua = dv_unrot(n, a->cos_a, a->sin_a), va = dv_unrot(t, a->cos_a, a->sin_a);
    double t0 = INFINITY, t1 = -INFINITY, n0 = INFINITY, n1 = -INFINITY;
    for (int32_t y = wa->y0; y <= wa->y1; y++)
        for (int32_t x = wa->x0; x <= wa->x1; x++) {
            dvec2 d;
            if (!window_pixel(wa, x, y, &d))
                continue;
            const dvec2 wp = dv_add(p, dv_rot(d, a->cos_a, a->sin_a));
            const dvec2 q = dv_add(b->pivot, dv_unrot(dv_sub(wp, b->pos), b->cos_a, b->sin_a));
            if (!raster_solid_clamped(&b->raster, (int32_t)floor(q.x), (int32_t)floor(q.y)))
                continue;
            const double along = d.x * va.x + d.y * va.y, across = d.x * ua.x + d.y * ua.y;
            t0 = dmin(t0, along), t1 = dmax(t1, along), n0 = dmin(n0, across), n1 = dmax(n1, across);
        }
    if (!(t0 <= t1))
        return false;
    const dvec2 mid = dv_add(p, dv_scale(n, 0.5 * (n0 + n1)));
    ends[0] = dv_add(mid, dv_scale(t, t0 - 0.5));
    ends[1] = dv_add(mid, dv_scale(t, t1 + 0.5));
    return true;
}

static void deep_pair(const body *a, const body *b, double depth, np_result *r)
{
    const double radius = depth + CORNER_RADIUS;
    if (radius > DEEP_REACH)
        return;
    const dvec2 n0 = raster_normal(r);
    static const int32_t axes[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    dvec2 dirs[DEEP_AXES];
    int32_t nd = 0;
    dirs[nd++] = n0;
    for (int side = 0; side < 2; side++) {
        const body *bd = side ? b : a;
        for (int k = 0; k < 4; k++) {
            const dvec2 m = dv_scale(dv_rot(dv(axes[k][0], axes[k][1]), bd->cos_a, bd->sin_a), side ? -1.0 : 1.0);
            if (dv_dot(m, n0) > -SIN_PERP && dv_dot(m, n0) < COS_MIN_TURN) /* perpendicular ones too */
                dirs[nd++] = m;
        }
    }
    if (nd == 1)
        return;
    const dvec2 p = contact_middle(r);
    const window wa = window_at(a, p, radius), wb = window_at(b, p, radius);
    double hi[DEEP_AXES], lo[DEEP_AXES];
    if (!window_extents(&wa, dirs, nd, true, hi) || !window_extents(&wb, dirs, nd, false, lo))
        return;
    const double pen0 = hi[0] - lo[0];
    int32_t best = 0;
    for (int32_t k = 1; k < nd; k++)
        if (hi[k] - lo[k] < hi[best] - lo[best])
            best = k;
    const double pen = hi[best] - lo[best];
    if (best == 0 || !(pen < pen0 - CORNER_MARGIN))
        return;
    const dvec2 n = dirs[best], t = dv(-n.y, n.x);
    dvec2 ends[2];
    if (r->count == 2 && window_ends(&wa, b, p, n, t, ends))
        for (int32_t k = 0; k < 2; k++)
            r->contacts[k].point = (pp_vec2){(float)ends[k].x, (float)ends[k].y};
    for (int32_t k = 0; k < r->count; k++) {
        r->contacts[k].normal = (pp_vec2){(float)n.x, (float)n.y};
        r->contacts[k].depth = (float)dmax(pen, 0.0);
    }
}

void corner_normal(const body *a, const body *b, np_result *r)
{
    if (r->count == 0)
        return;
    if (r->contacts[0].pixel_count <= CORNER_PIXELS) {
        corner_pixels(a, b, r);
        return;
    }
    double depth = 0;
    for (int32_t k = 0; k < r->count; k++)
        depth = dmax(depth, r->contacts[k].depth);
    if (depth > DEEP_DEPTH)
        deep_pair(a, b, depth, r);
}
