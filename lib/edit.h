/* Pixel edits shared by the edit calls (edit.c) and fracture (fracture.c). */
#ifndef PP_EDIT_H
#define PP_EDIT_H

#include "world.h"

/* What a batch of pixel writes did to one body. */
typedef struct edit_span {
    int32_t changed;    /* pixels whose mask bit or weight changed */
    int32_t x0, x1;     /* columns touched, [x0, x1) */
    int32_t y0, y1;     /* rows touched, [y0, y1) */
    bool removed;       /* some solid pixel became empty (the body may have come apart) */
} edit_span;

/* Write one pixel, keeping the body's mass sums exact. */
void edit_pixel(body *bd, edit_span *e, int32_t x, int32_t y, bool solid, uint32_t weight);

/* After the pixels of a dynamic or kinematic body changed: new mass and inertia, the ODE body moved
 * to the new centre of mass with the velocity the material there already had, awake. */
void edit_update_solver_body(world *wd, body *bd);

/* Split a body whose solid pixels form several 8-connected islands (fracture.c). */
pp_status fracture_split(world *wd, body *bd);

#endif
