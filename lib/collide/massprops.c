/* Mass properties from pixel sums: I = Σ m_p (|p − c|² + 1/6) for unit squares, so a solid
 * w × h rectangle gets exactly m(w² + h²)/12. */
#include "massprops.h"

#include <string.h>

void mass_sums_of_raster(pp_mass_sums *s, const pp_raster *r)
{
    memset(s, 0, sizeof *s);
    for (int32_t y = r->y0; y < r->y1; y++)
        for (int32_t x = r->x0; x < r->x1; x++)
            if (raster_solid(r, x, y))
                mass_sums_pixel(s, r->width, r->height, x, y, raster_weight(r, x, y), +1);
}

pp_mass mass_from_sums(const pp_mass_sums *s, int32_t width, int32_t height, double density)
{
    pp_mass m = {0};
    if (s->w <= 0)
        return m;
    const double k = density / 255.0; /* mass of one unit of weight */
    const double W = (double)s->w;
    const double mu = s->wu / W, mv = s->wv / W; /* doubled, centre-relative */
    m.mass = k * W;
    m.cx = 0.5 * (width + mu);
    m.cy = 0.5 * (height + mv);
    /* Σ w(u² + v²)/4 − W|c|² about the centre of mass, plus 1/6 per unit of weight for the square. */
    const double second = 0.25 * ((double)s->wuu + (double)s->wvv) - 0.25 * W * (mu * mu + mv * mv);
    m.inertia = k * (second + W / 6.0);
    return m;
}
