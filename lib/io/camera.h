/* The camera a host frames a world with (pp_world_get_camera): renderer state, kept beside the physics
 * world rather than in it, and carried by scenes and snapshots (camera.c). */
#ifndef PP_CAMERA_H
#define PP_CAMERA_H

#include "physpix.h"

typedef struct world world;

/* The world's camera: the last set, or the default (centre (480, 270) px, zoom 1, 960 × 540 px). */
pp_camera camera_of(const world *wd);
/* Check a camera (finite centre, finite zoom > 0, a size within 1..PP_MAX_BITMAP_SIDE px) and give it to
 * the world; failures name fn. */
pp_status camera_set(const world *wd, const pp_camera *c, const char *fn);

#endif
