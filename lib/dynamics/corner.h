/* A corner resting on a face, and a deep overlap: the normal of a pair that meets through a few pixels, or
 * deeper than a few pixels, chosen again from the two bodies' faces (see corner.c). */
#ifndef PP_CORNER_H
#define PP_CORNER_H

#include "world.h"

/* A pair meeting through at most this many pixels is a corner on a face (or on a corner). */
#define CORNER_PIXELS 3

/* Where r's pair meets through at most CORNER_PIXELS pixels, turn its normals to the face of a or b along
 * which the two overlap least, when that beats the narrowphase's normal; points and depths stay. Where it is
 * deeper than DEEP_DEPTH, the same over a window holding the overlap, perpendicular faces included; a face
 * chosen there brings its overlap as the depth and the intersection's ends along it as the points. */
void corner_normal(const body *a, const body *b, np_result *r);

#endif
