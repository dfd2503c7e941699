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

/* Erase a circle (world px) from bd, or from every body it touches when bd is NULL; paint one into bd with
 * a weight 1..255. The edit calls' work on a world and body already looked up; failures name `fn`. */
pp_status edit_erase_circle(world *wd, body *bd, pp_vec2 world_center, float radius, const char *fn, int32_t *changed);
/* Called once every body's erase is written and its pieces made, before any is committed: a failure there takes
 * the whole erase back. */
typedef pp_status (*edit_before_commit)(world *wd, void *user);
/* Erase a circle from every body whose category_bits meet mask_bits (an explosion's erase); before_commit may be
 * NULL. */
pp_status edit_erase_world(world *wd, pp_vec2 world_center, float radius, uint32_t mask_bits, const char *fn,
                           int32_t *changed, edit_before_commit before_commit, void *user);
pp_status edit_paint_circle(world *wd, body *bd, pp_vec2 world_center, float radius, uint8_t weight, const char *fn,
                            int32_t *changed);

/* A split found but not yet made: the pieces exist as bodies, the parent still holds their pixels. */
typedef struct fracture_plan {
    int32_t *label;          /* island of each pixel of the frame, 1..count; 0 empty */
    int32_t bx, by, bw, bh;  /* the frame: the parent's solid bounds when labelled */
    struct island *islands;
    int32_t count, keep;     /* islands; the one that stays the parent */
    pp_body *children;       /* by island; zero for the kept one and for massless dust */
} fracture_plan;

/* Find the 8-connected islands of a body just edited and make a body of each but the largest;
 * everything that can fail happens here, and a failure leaves the world as it was. Adds the events
 * the split will send to *events and reserves room for all of them. (fracture.c) */
pp_status fracture_prepare(world *wd, body *bd, fracture_plan *p, const char *fn, int32_t *events);

/* Make the split: move the pieces' pixels out of the parent, set them moving, send the events. */
void fracture_commit(world *wd, body *bd, fracture_plan *p);

/* The island of a prepared split holding bitmap pixel (x, y) of the parent, and that island's top-left
 * corner in the parent's bitmap (a piece's bitmap starts there); false for an empty pixel or none split. */
bool fracture_island_at(const fracture_plan *p, int32_t x, int32_t y, int32_t *k, dvec2 *origin);

/* Take a prepared split back: the pieces go as if never made. */
void fracture_cancel(world *wd, fracture_plan *p);

#endif
