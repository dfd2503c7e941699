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
 * the backend-identical core, so CPU and GPU stay identical. */
#include "corner.h"

#include <math.h>

#define CORNER_PIXELS 3
#define CORNER_RADIUS 6.0
#define CORNER_MARGIN 0.1 /* px: the narrowphase's normal stays unless a face beats it by this */
#define COS_MIN_TURN 0.98480775301220806 /* cos 10°: a face nearer the narrowphase's normal is not tried */

/* A body's pixel centres within CORNER_RADIUS of the contact, as offsets from it in the body's bitmap frame. */
#define PATCH_REACH ((int32_t)CORNER_RADIUS)
typedef struct patch {
    const body *bd;
    int32_t n;
    double dx[(2 * PATCH_REACH + 1) * (2 * PATCH_REACH + 1)], dy[(2 * PATCH_REACH + 1) * (2 * PATCH_REACH + 1)];
} patch;

static void patch_gather(const body *bd, dvec2 p, patch *out)
{
    const dvec2 l = dv_add(bd->pivot, dv_unrot(dv_sub(p, bd->pos), bd->cos_a, bd->sin_a));
    const int32_t cx = (int32_t)floor(l.x), cy = (int32_t)floor(l.y);
    out->bd = bd, out->n = 0;
    for (int32_t y = cy - PATCH_REACH; y <= cy + PATCH_REACH; y++)
        for (int32_t x = cx - PATCH_REACH; x <= cx + PATCH_REACH; x++) {
            const double dx = x + 0.5 - l.x, dy = y + 0.5 - l.y;
            if (dx * dx + dy * dy <= CORNER_RADIUS * CORNER_RADIUS && raster_solid_clamped(&bd->raster, x, y))
                out->dx[out->n] = dx, out->dy[out->n++] = dy;
        }
}

/* The extreme projection on world direction n (max, or min when !up) of the patch's pixels, each a disc of
 * half a pixel (no axis favoured), from the contact. */
static double patch_extent(const patch *pa, dvec2 n, bool up)
{
    const dvec2 u = dv_unrot(n, pa->bd->cos_a, pa->bd->sin_a);
    double best = up ? -INFINITY : INFINITY;
    for (int32_t i = 0; i < pa->n; i++) {
        const double q = pa->dx[i] * u.x + pa->dy[i] * u.y + (up ? 0.5 : -0.5);
        best = up ? dmax(best, q) : dmin(best, q);
    }
    return best;
}

/* How far a's patch reaches past b's along n (from a to b). */
static double patch_overlap(const patch *a, const patch *b, dvec2 n)
{
    return patch_extent(a, n, true) - patch_extent(b, n, false);
}

void corner_normal(const body *a, const body *b, np_result *r)
{
    if (r->count == 0 || r->contacts[0].pixel_count > CORNER_PIXELS)
        return;
    const dvec2 n0 = dv(r->contacts[0].normal.x, r->contacts[0].normal.y); /* from a to b */
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
    dvec2 p = dv(0, 0);
    for (int32_t k = 0; k < r->count; k++)
        p = dv_add(p, dv(r->contacts[k].point.x, r->contacts[k].point.y));
    p = dv_scale(p, 1.0 / r->count);
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
