/* The backend-independent halves of the narrowphase: setting a pair up (reference body, grid,
 * fixed-point sampling steps) and turning its integer core into contacts. Floating point lives
 * here only, on the CPU, so the backends differ in nothing but who computes the core. */
#include "narrowphase.h"

#include <limits.h>
#include <stdlib.h>

static int64_t bounds_area(const pp_raster *r) { return (int64_t)(r->x1 - r->x0) * (r->y1 - r->y0); }

/* llround(x), without its call for the set-up's fixed-point steps: x − trunc(x) is exact below 2^52. */
static int64_t round_away(double x)
{
    if (!(fabs(x) < 0x1p52))
        return llround(x);
    const int64_t i = (int64_t)x;
    const double f = x - (double)i;
    return i + (f >= 0.5) - (f <= -0.5);
}

/* A box in reference-local coordinates, px. */
typedef struct local_box {
    double lo_x, lo_y, hi_x, hi_y;
} local_box;

/* The other body's solid bounds in reference-local coordinates, as a box: M, t map reference-local to
 * other-local (q = M·l + t). */
static local_box other_box(const pp_raster *rb, double mc, double ms, dvec2 t)
{
    local_box b = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    const double cx[2] = {rb->x0, rb->x1}, cy[2] = {rb->y0, rb->y1};
    for (int k = 0; k < 4; k++) {
        const dvec2 l = dv_unrot(dv_sub(dv(cx[k & 1], cy[k >> 1]), t), mc, ms);
        b.lo_x = dmin(b.lo_x, l.x), b.hi_x = dmax(b.hi_x, l.x);
        b.lo_y = dmin(b.lo_y, l.y), b.hi_y = dmax(b.hi_y, l.y);
    }
    return b;
}

/* M = R(θA − θB) and t = pivotB + R(−θB)(posA − posB) − M·pivotA, which map A-local to B-local: q = M·l + t. */
static void relative_map(const np_body *A, const np_body *B, double *mc, double *ms, dvec2 *t)
{
    *mc = A->c * B->c + A->s * B->s, *ms = A->s * B->c - A->c * B->s;
    const dvec2 d = dv_unrot(dv_sub(A->pos, B->pos), B->c, B->s);
    *t = dv_sub(dv_add(B->pivot, d), dv_rot(A->pivot, *mc, *ms));
}

/* The rectangle of the reference grid where the two bodies can overlap, the other's box `ob` in reference-local
 * coordinates; false when empty. */
static bool overlap_grid(const pp_raster *ra, local_box ob, int32_t stride, np_pair *p)
{
    const double lo_x = ob.lo_x, lo_y = ob.lo_y, hi_x = ob.hi_x, hi_y = ob.hi_y;
    /* A margin of one cell plus one pixel so unit shifts of the other body stay inside. */
    const double margin = stride + 1;
    /* Clamped on both sides: a pair far apart (pp_world_collide takes any pair) gives bounds past int64
     * (UBSan, found by fuzz_api). */
    const int64_t X0 = (int64_t)dmin(dmax(ra->x0, floor(lo_x - margin)), ra->x1),
                  X1 = (int64_t)dmax(dmin(ra->x1, ceil(hi_x + margin)), ra->x0);
    const int64_t Y0 = (int64_t)dmin(dmax(ra->y0, floor(lo_y - margin)), ra->y1),
                  Y1 = (int64_t)dmax(dmin(ra->y1, ceil(hi_y + margin)), ra->y0);
    if (X0 >= X1 || Y0 >= Y1)
        return false;
    p->s = stride;
    p->off = stride / 2;
    const int64_t i0 = ceil_div(X0 - p->off, stride), i1 = floor_div(X1 - 1 - p->off, stride);
    const int64_t j0 = ceil_div(Y0 - p->off, stride), j1 = floor_div(Y1 - 1 - p->off, stride);
    if (i1 < i0 || j1 < j0)
        return false;
    p->i0 = (int32_t)i0, p->j0 = (int32_t)j0;
    p->nx = (int32_t)(i1 - i0 + 1), p->ny = (int32_t)(j1 - j0 + 1);
    return true;
}

/* The other body is sampled through 16.16 fixed-point affine steps from one rounded origin,
 * so every backend reads the same pixels. */
static void sampling_steps(np_pair *p, double mc, double ms, dvec2 t)
{
    const double one = (double)(1 << NP_FIX_BITS);
    const dvec2 l0 = np_grid_to_local(p, -NP_RING, -NP_RING);
    const dvec2 q0 = dv_add(dv_rot(l0, mc, ms), t);
    p->qx0 = round_away(q0.x * one), p->qy0 = round_away(q0.y * one);
    p->dix = round_away(mc * p->s * one), p->diy = round_away(ms * p->s * one);
    p->djx = round_away(-ms * p->s * one), p->djy = round_away(mc * p->s * one);
    /* The plane's corners bound every sample point (the map is affine). With bitmaps of at most
     * 16384 px the points stay within about ±20000 px, so this guard for the GPU's 32-bit 16.16
     * (headroom for q − ½ pixel) does not trip; a pair that tripped it would run on the CPU. */
    const int64_t ex = p->nx + 2 * NP_RING - 1, ey = p->ny + 2 * NP_RING - 1;
    const int64_t lim = ((int64_t)1 << 31) - ((int64_t)1 << NP_FIX_BITS);
    p->fits_int32 = true;
    for (int k = 0; k < 4; k++) {
        const int64_t i = (k & 1) ? ex : 0, j = (k >> 1) ? ey : 0;
        const int64_t qx = p->qx0 + i * p->dix + j * p->djx, qy = p->qy0 + i * p->diy + j * p->djy;
        p->fits_int32 &= qx > -lim && qx < lim && qy > -lim && qy < lim;
    }
}

/* Whether any inner cell can be in both bodies: the count needs one, and a pair with none has no contact
 * (the grid's margin is for the normal's unit shifts, which matter only where the bodies meet). Adjacent
 * bodies (a pile's crates side by side, their boxes sharing an edge) are dropped here, before any raster is
 * read. On the other body's axes the test is exact: the samples' fixed-point points are an affine map of the
 * cell indices, so the grid's corners bound their pixels. On the reference's axes, its cell centres against
 * the other's box, with the fixed-point steps' rounding as tolerance. */
static bool cells_can_meet(const np_pair *p, local_box ob)
{
    const pp_raster *rb = p->rb;
    int64_t lx = INT64_MAX, ly = INT64_MAX, hx = INT64_MIN, hy = INT64_MIN;
    for (int k = 0; k < 4; k++) {
        const int64_t i = NP_RING + ((k & 1) ? p->nx - 1 : 0), j = NP_RING + ((k >> 1) ? p->ny - 1 : 0);
        const int64_t qx = (p->qx0 + i * p->dix + j * p->djx) >> NP_FIX_BITS;
        const int64_t qy = (p->qy0 + i * p->diy + j * p->djy) >> NP_FIX_BITS;
        lx = qx < lx ? qx : lx, hx = qx > hx ? qx : hx;
        ly = qy < ly ? qy : ly, hy = qy > hy ? qy : hy;
    }
    if (hx < rb->x0 || lx >= rb->x1 || hy < rb->y0 || ly >= rb->y1)
        return false;
    const double lo_x = ob.lo_x, lo_y = ob.lo_y, hi_x = ob.hi_x, hi_y = ob.hi_y;
    /* Each rounded step (and the origin) is off by at most 2^-17 px a component, and a sample point adds up to
     * nx + ny + 4·RING of them: tol is over √2 times that, the most it moves along any axis. */
    const double tol = (double)(p->nx + p->ny + 2 * NP_RING + 1) / (1 << NP_FIX_BITS) + 1e-9;
    const dvec2 c0 = np_grid_to_local(p, 0, 0), c1 = np_grid_to_local(p, p->nx - 1, p->ny - 1);
    if (!(c1.x >= lo_x - tol && c0.x <= hi_x + tol && c1.y >= lo_y - tol && c0.y <= hi_y + tol))
        return false;
    /* The reference's pixels whose centres lie in that box: none solid (a crate over a crater in a terrain, whose
     * own box is the terrain's), no cell in both. */
    return raster_rect_state(p->ra, (int64_t)ceil(lo_x - tol - 0.5), (int64_t)ceil(lo_y - tol - 0.5),
                             (int64_t)floor(hi_x + tol - 0.5) + 1, (int64_t)floor(hi_y + tol - 0.5) + 1) != RASTER_EMPTY;
}

/* np_pair_grid, and the other body's box in reference-local coordinates in *ob. */
static bool pair_grid(const np_settings *set, const np_body *a, const np_body *b, np_pair *p, local_box *ob)
{
    if (raster_empty(a->raster) || raster_empty(b->raster))
        return false;
    /* The larger body is the reference: its own boundary stays exact on its own grid (a flat ground
     * gives an exact normal), and the grid is still bounded by the smaller body's box. */
    p->swap = bounds_area(b->raster) > bounds_area(a->raster);
    const np_body *A = p->swap ? b : a, *B = p->swap ? a : b;
    p->ra = A->raster, p->rb = B->raster;

    double mc, ms;
    dvec2 t;
    relative_map(A, B, &mc, &ms, &t);
    *ob = other_box(p->rb, mc, ms, t);
    if (!overlap_grid(p->ra, *ob, set->stride, p))
        return false;
    sampling_steps(p, mc, ms, t);
    return true;
}

/* A symmetric overlap has no preferred side: the line between the bodies, for a pair that is kept. */
static void fallback_normal(const np_body *a, const np_body *b, np_pair *p)
{
    const np_body *A = p->swap ? b : a, *B = p->swap ? a : b;
    dvec2 n = dv_unrot(dv_sub(B->pos, A->pos), A->c, A->s);
    if (n.x == 0 && n.y == 0)
        n = dv(0, 1);
    p->fallback_n = dv_scale(n, 1.0 / sqrt(dv_dot(n, n)));
    p->fallback_nqx = (int32_t)round_away(p->fallback_n.x * NP_NORMAL_ONE);
    p->fallback_nqy = (int32_t)round_away(p->fallback_n.y * NP_NORMAL_ONE);
}

bool np_pair_grid(const np_settings *set, const np_body *a, const np_body *b, np_pair *p)
{
    local_box ob;
    if (!pair_grid(set, a, b, p, &ob))
        return false;
    fallback_normal(a, b, p);
    return true;
}

bool np_pair_setup(const np_settings *set, const np_body *a, const np_body *b, np_pair *p)
{
    local_box ob;
    if (!pair_grid(set, a, b, p, &ob) || !cells_can_meet(p, ob))
        return false; /* most candidates of a pile: boxes side by side */
    fallback_normal(a, b, p);
    return true;
}

/* round(2^14·a/√r2) for 0 ≤ a ≤ √r2 < 2^15.5, exactly: the k with (2k−1)²·r2 ≤ 2^30·a² < (2k+1)²·r2.
 * The float guess is only a start; the GPU twin (glsl/common.glsl) makes the same tests. */
static int32_t round_unit_q14(uint32_t a, uint32_t r2)
{
    const uint64_t target = (uint64_t)a * a << 30;
    int64_t k = (int64_t)(NP_NORMAL_ONE * (double)a / sqrt((double)r2) + 0.5);
    k = k < 0 ? 0 : k > NP_NORMAL_ONE ? NP_NORMAL_ONE : k;
    while (k > 0 && (uint64_t)((2 * k - 1) * (2 * k - 1)) * r2 > target)
        k--;
    while ((uint64_t)((2 * k + 1) * (2 * k + 1)) * r2 <= target)
        k++;
    return (int32_t)k;
}

void np_quantize_normal(int64_t gx, int64_t gy, int32_t *nqx, int32_t *nqy)
{
    uint64_t ax = gx < 0 ? 0 - (uint64_t)gx : (uint64_t)gx, ay = gy < 0 ? 0 - (uint64_t)gy : (uint64_t)gy;
    const uint64_t m = ax > ay ? ax : ay;
    const int msb = 63 - __builtin_clzll(m);
    const int shift = msb > 14 ? msb - 14 : 0;
    ax >>= shift, ay >>= shift;
    const uint32_t r2 = (uint32_t)(ax * ax + ay * ay);
    const int32_t kx = round_unit_q14((uint32_t)ax, r2), ky = round_unit_q14((uint32_t)ay, r2);
    *nqx = gx < 0 ? -kx : kx;
    *nqy = gy < 0 ? -ky : ky;
}

/* Inner-cell coordinates of a contact point on a strip: along n the middle of its intersection
 * cells' projections, along t the strip's centre (t = strip) moved by `end` strip widths. */
static dvec2 strip_point(int32_t strip, double end, int32_t pmin, int32_t pmax, int32_t nqx, int32_t nqy)
{
    const double v = 0.5 * ((double)pmin + pmax) / NP_NORMAL_ONE; /* along n */
    const double u = (double)strip + end;                          /* along t */
    const double q = (double)NP_NORMAL_ONE;
    return dv((nqx * v - nqy * u) / q, (nqy * v + nqx * u) / q);
}

void np_pair_finish(const np_settings *set, const np_body *a, const np_body *b, const np_pair *p,
                    const np_core *core, np_result *out)
{
    out->count = 0;
    if (core->count == 0)
        return;
    const np_body *A = p->swap ? b : a;
    dvec2 n = p->fallback_n;
    if (core->gx != 0 || core->gy != 0) {
        n = dv((double)core->gx, (double)core->gy);
        n = dv_scale(n, 1.0 / sqrt(dv_dot(n, n)));
    }

    /* Contact points in inner-cell coordinates, with their depths in pixels. */
    const double cell = p->s / 256.0;
    dvec2 pts[2];
    double depth[2];
    if (set->contact_mode == PP_CONTACT_CENTROID || core->first == core->last) {
        pts[0] = set->contact_mode == PP_CONTACT_CENTROID
                     ? dv((double)core->sx / core->count, (double)core->sy / core->count)
                     : strip_point(core->tmin + core->first, 0.0, core->first_min, core->first_max, core->nqx,
                                   core->nqy);
        depth[0] = core->cover_all * cell;
        out->count = 1;
    } else {
        /* The two ends along the tangent, on the outer edges of the first and last strips so that
         * they span the whole patch (a box on flat ground: its two bottom corners), each as deep
         * as the deepest strip of its half. */
        pts[0] = strip_point(core->tmin + core->first, -0.5, core->first_min, core->first_max, core->nqx, core->nqy);
        pts[1] = strip_point(core->tmin + core->last, 0.5, core->last_min, core->last_max, core->nqx, core->nqy);
        depth[0] = core->cover_lo * cell;
        depth[1] = core->cover_hi * cell;
        out->count = 2;
    }

    const dvec2 nw = dv_rot(n, A->c, A->s);
    const double sign = p->swap ? -1.0 : 1.0;
    for (int32_t k = 0; k < out->count; k++) {
        const dvec2 l = np_grid_to_local(p, pts[k].x, pts[k].y);
        const dvec2 w = dv_add(A->pos, dv_rot(dv_sub(l, A->pivot), A->c, A->s));
        pp_contact *c = &out->contacts[k];
        *c = (pp_contact){0}; /* reserved is zero, as the header says, not what the caller's stack held */
        c->point = (pp_vec2){(float)w.x, (float)w.y};
        c->normal = (pp_vec2){(float)(sign * nw.x), (float)(sign * nw.y)};
        c->depth = (float)depth[k];
        c->pixel_count = (int32_t)(core->count * p->s * p->s);
    }
}

pp_status narrow_cpu_collide(const np_settings *set, const np_body *a, const np_body *b, np_scratch *scratch,
                             np_result *out)
{
    out->count = 0;
    out->samples = 0;
    np_pair p;
    if (!np_pair_setup(set, a, b, &p))
        return PP_OK;
    np_core core;
    const pp_status st = narrow_cpu_core(set, &p, scratch, &core);
    if (st)
        return st;
    out->samples = np_pair_cells(&p);
    np_pair_finish(set, a, b, &p, &core, out);
    return PP_OK;
}
