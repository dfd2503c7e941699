/* Mass, centre of mass and inertia of a raster, kept as exact integer running sums so an
 * edit updates them from the changed pixels alone. Each pixel is a unit square. */
#ifndef PP_MASSPROPS_H
#define PP_MASSPROPS_H

#include "raster.h"

#include <stdint.h>

/* Sums over solid pixels of weight w at centre-relative doubled coordinates
 * u = 2x + 1 − width, v = 2y + 1 − height (integers, so the sums are exact). */
typedef struct pp_mass_sums {
    int64_t w, wu, wv, wuu, wvv;
} pp_mass_sums;

typedef struct pp_mass {
    double mass;     /* density × Σ weight / 255, mass units */
    double cx, cy;   /* centre of mass in bitmap coordinates, px */
    double inertia;  /* about the centre of mass, mass·px² */
} pp_mass;

void mass_sums_of_raster(pp_mass_sums *s, const pp_raster *r);

/* Add (sign = +1) or remove (sign = −1) one pixel of weight w at (x, y). */
static inline void mass_sums_pixel(pp_mass_sums *s, int32_t width, int32_t height, int32_t x, int32_t y,
                                   uint32_t w, int sign)
{
    const int64_t u = 2 * (int64_t)x + 1 - width, v = 2 * (int64_t)y + 1 - height;
    const int64_t sw = sign * (int64_t)w;
    s->w += sw;
    s->wu += sw * u;
    s->wv += sw * v;
    s->wuu += sw * u * u;
    s->wvv += sw * v * v;
}

pp_mass mass_from_sums(const pp_mass_sums *s, int32_t width, int32_t height, double density);

#endif
