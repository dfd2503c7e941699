/* Which pixels of a body a world shape covers: the rules the edits (edit.c) and the queries
 * (raycast.c) share, so that pp_world_query_circle names exactly the bodies pp_world_erase_circle
 * would change. */
#ifndef PP_COVER_H
#define PP_COVER_H

#include "world.h"

/* A world point in the body's bitmap coordinates, px. */
static inline dvec2 body_world_to_local(const body *bd, dvec2 p)
{
    return dv_add(bd->pivot, dv_unrot(dv_sub(p, bd->pos), bd->cos_a, bd->sin_a));
}

/* A bitmap point of the body in the world, px. */
static inline dvec2 body_local_to_world(const body *bd, dvec2 p)
{
    return dv_add(bd->pos, dv_rot(dv_sub(p, bd->pivot), bd->cos_a, bd->sin_a));
}

/* The columns [*xa, *xb] of row y whose pixel centres lie within r of the bitmap point c (the circle
 * rule of the edits); false when the row misses the circle. The bounds are unclamped doubles. */
static inline bool circle_row_span(dvec2 c, double r, int32_t y, double *xa, double *xb)
{
    const double dy = y + 0.5 - c.y, h2 = r * r - dy * dy;
    if (h2 < 0)
        return false;
    const double h = sqrt(h2);
    *xa = ceil(c.x - h - 0.5), *xb = floor(c.x + h - 0.5);
    return true;
}

#endif
