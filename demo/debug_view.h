/* The demo's debug view of one collision, after the PhysPix poster's Figure 1c: a pair's sampled grid
 * zoomed around its intersection, cells coloured by which body is solid there, each critical cell's
 * local normal as a short line and the pair's global normal as a long arrow. */
#ifndef PP_DEMO_DEBUG_VIEW_H
#define PP_DEMO_DEBUG_VIEW_H

#include "render.h"

#include <stddef.h>

/// A pair's grid as PhysPixWorld.debug_collision and the get_debug_* calls give it.
typedef struct debug_capture {
    uint8_t *cells;                 ///< width·height PP_CELL_* flags; NULL: no pair was captured
    pp_vec2 *normals;               ///< width·height local normals, world axes (zero off the critical cells)
    int32_t width, height;          ///< cells
    pp_vec2 step_x, step_y, normal; ///< the grid's axes (world px a cell) and the global normal from a to b
    double time, score;             ///< when it was taken, s; how telling it is (the demo's choice)
    char what[96];                  ///< the pair's names, for the title
} debug_capture;

/// The colour of a cell with these flags (first body, second body, intersection, critical, empty).
render_color debug_cell_color(uint8_t flags);
/// The view's title: the time (s), the pair, and the cells drawn of the pair's grid; size bytes at most.
void debug_view_title(const debug_capture *c, char *out, size_t size);
/// Draw the view over the whole image: title, legend, the zoomed grid and the normals.
void debug_view_draw(render_image *im, const debug_capture *c);

#endif
