/* A pair whose intersection is a few pixels is a corner on a face (or a corner on a corner): the narrowphase's
 * normal, from the intersection raster alone, can lie far off the face (a flat card on a tilted card's top
 * corner: 28°, then 66°, and the flat slid off the corner). The normal is chosen again as separating axes
 * choose it for polygons: of the narrowphase's normal and either body's bitmap axes that lean from a to b, the
 * one along which the bodies' pixels within CORNER_RADIUS of the contact overlap least. A corner on a face
 * overlaps least along the face's normal: along any other axis the face's pixels reach past the corner.
 *
 * The window is what keeps a slope's normal: a slope, drawn in a terrain bitmap or not, is nearly flat across
 * a 3 px window, and there a tumbling box's own bottom face beat the slope's normal (27° off it on a 30°
 * slope); from 5 px on the slope's rise across the window outweighs the pixel steps. Runs after the
 * backend-identical core, so CPU and GPU stay identical. */
#include "corner.h"

#include <math.h>

#define CORNER_PIXELS 3
#define CORNER_RADIUS 6.0
#define CORNER_MARGIN 0.1 /* px: the narrowphase's normal stays unless a face beats it by this */
#define COS_MIN_TURN 0.98480775301220806 /* cos 10°: a face nearer the narrowphase's normal is not tried */

static dvec2 to_bitmap(const body *bd, dvec2 p)
{
    return dv_add(bd->pivot, dv_unrot(dv_sub(p, bd->pos), bd->cos_a, bd->sin_a));
}

/* The extreme projection on world direction n (max, or min when !up) of bd's pixel squares whose centres lie
 * within CORNER_RADIUS of world point p; false when there are none. */
static bool patch_extent(const body *bd, dvec2 p, dvec2 n, bool up, double *out)
{
    const pp_raster *r = &bd->raster;
    const dvec2 l = to_bitmap(bd, p);
    const dvec2 u = dv_unrot(n, bd->cos_a, bd->sin_a);
    const int32_t reach = (int32_t)ceil(CORNER_RADIUS), cx = (int32_t)floor(l.x), cy = (int32_t)floor(l.y);
    bool any = false;
    double best = 0;
    for (int32_t y = cy - reach; y <= cy + reach; y++)
        for (int32_t x = cx - reach; x <= cx + reach; x++) {
            const double dx = x + 0.5 - l.x, dy = y + 0.5 - l.y;
            if (dx * dx + dy * dy > CORNER_RADIUS * CORNER_RADIUS || !raster_solid_clamped(r, x, y))
                continue;
            const double q = dx * u.x + dy * u.y + (up ? 0.5 : -0.5);
            if (!any || (up ? q > best : q < best))
                best = q, any = true;
        }
    *out = best + dv_dot(p, n); /* q was measured from p (l in the bitmap) */
    return any;
}

/* How far a's patch reaches past b's along n (from a to b); false when a patch is empty. */
static bool patch_overlap(const body *a, const body *b, dvec2 p, dvec2 n, double *pen)
{
    double hi, lo;
    if (!patch_extent(a, p, n, true, &hi) || !patch_extent(b, p, n, false, &lo))
        return false;
    *pen = hi - lo;
    return true;
}

void corner_normal(const body *a, const body *b, np_result *r)
{
    if (r->count == 0 || r->contacts[0].pixel_count > CORNER_PIXELS)
        return;
    dvec2 p = dv(0, 0);
    for (int32_t k = 0; k < r->count; k++)
        p = dv_add(p, dv(r->contacts[k].point.x, r->contacts[k].point.y));
    p = dv_scale(p, 1.0 / r->count);
    const dvec2 n0 = dv(r->contacts[0].normal.x, r->contacts[0].normal.y); /* from a to b */
    double pen0;
    if (!patch_overlap(a, b, p, n0, &pen0))
        return;
    double best = pen0;
    dvec2 n = n0;
    static const int32_t axes[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    for (int side = 0; side < 2; side++) {
        const body *bd = side ? b : a;
        for (int k = 0; k < 4; k++) {
            dvec2 m = dv_rot(dv(axes[k][0], axes[k][1]), bd->cos_a, bd->sin_a); /* outward from bd */
            if (side)
                m = dv_scale(m, -1.0);
            double pen;
            if (dv_dot(m, n0) > 0 && dv_dot(m, n0) < COS_MIN_TURN && patch_overlap(a, b, p, m, &pen) &&
                pen < best)
                best = pen, n = m;
        }
    }
    if (!(best < pen0 - CORNER_MARGIN))
        return;
    for (int32_t k = 0; k < r->count; k++)
        r->contacts[k].normal = (pp_vec2){(float)n.x, (float)n.y};
}
