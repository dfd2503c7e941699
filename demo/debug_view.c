/* The Figure 1c view: the part of a pair's grid around its intersection, drawn as large as fits, with the
 * legend below. The grid's axes are the reference body's, so a world normal is drawn in grid coordinates. */
#include "debug_view.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* A grid direction of a world vector: the grid's axes are the reference body's, one cell a step. */
static pp_vec2 to_grid(const debug_capture *c, pp_vec2 v)
{
    const float lx = hypotf(c->step_x.x, c->step_x.y), ly = hypotf(c->step_y.x, c->step_y.y);
    return (pp_vec2){(v.x * c->step_x.x + v.y * c->step_x.y) / (lx * lx),
                     (v.x * c->step_y.x + v.y * c->step_y.y) / (ly * ly)};
}

render_color debug_cell_color(uint8_t f)
{
    if (f & PP_CELL_CRITICAL)
        return (render_color){236, 64, 52, 255};
    if ((f & (PP_CELL_A | PP_CELL_B)) == (PP_CELL_A | PP_CELL_B))
        return (render_color){246, 196, 60, 255};
    if (f & PP_CELL_A)
        return (render_color){84, 132, 220, 255};
    if (f & PP_CELL_B)
        return (render_color){110, 170, 90, 255};
    return (render_color){44, 48, 58, 255};
}

/* The legend names only the colours the window shows (a view whose every intersection cell is critical has
 * no plain intersection colour), and the bodies by the names in the title. */
static void draw_legend(render_image *im, int32_t y, const debug_capture *c, const uint8_t shown[4])
{
    char first[96] = "FIRST BODY", second[96] = "SECOND BODY";
    const char *sep = strstr(c->what, " / ");
    if (c->cells && sep) {
        snprintf(first, sizeof first, "%.*s", (int)(sep - c->what), c->what);
        snprintf(second, sizeof second, "%s", sep + 3);
    }
    const struct {
        uint8_t flags;
        const char *text;
    } items[] = {{PP_CELL_A, first}, {PP_CELL_B, second}, {PP_CELL_A | PP_CELL_B, "INTERSECTION"},
                 {PP_CELL_CRITICAL, "CRITICAL"}};
    int32_t x = 20;
    for (size_t i = 0; i < sizeof items / sizeof items[0]; i++) {
        if (!shown[i])
            continue;
        render_rect(im, x, y, 16, 16, debug_cell_color(items[i].flags));
        render_text(im, x + 24, y + 3, 2, items[i].text, (render_color){230, 230, 230, 255});
        x += 40 + 8 * (int32_t)strlen(items[i].text);
    }
    render_line(im, (pp_vec2){(float)x, y + 8.0f}, (pp_vec2){x + 20.0f, y + 8.0f}, 2, (render_color){255, 255, 255, 255});
    render_text(im, x + 28, y + 3, 2, "LOCAL NORMAL", (render_color){230, 230, 230, 255});
    x += 28 + 8 * 12 + 16;
    render_arrow(im, (pp_vec2){(float)x, y + 8.0f}, (pp_vec2){x + 26.0f, y + 8.0f}, 3, 8, (render_color){240, 80, 240, 255});
    render_text(im, x + 34, y + 3, 2, "GLOBAL NORMAL", (render_color){230, 230, 230, 255});
}

/* The part of the grid drawn: the intersection with a margin of cells around it, as large as fits. */
typedef struct grid_window {
    int32_t i0, j0, w, h; /* cells */
    int32_t cs, x0, y0;   /* cell side and the window's top-left corner, image px */
} grid_window;

static grid_window debug_window(const debug_capture *c, int32_t left, int32_t top, int32_t avail_w, int32_t avail_h)
{
    int32_t i0 = c->width, j0 = c->height, i1 = 0, j1 = 0;
    for (int32_t j = 0; j < c->height; j++)
        for (int32_t i = 0; i < c->width; i++)
            if ((c->cells[(size_t)j * c->width + i] & 3) == 3)
                i0 = i < i0 ? i : i0, j0 = j < j0 ? j : j0, i1 = i + 1 > i1 ? i + 1 : i1, j1 = j + 1 > j1 ? j + 1 : j1;
    const int32_t m = 8 + ((i1 - i0) > (j1 - j0) ? (i1 - i0) : (j1 - j0)) / 2;
    grid_window g;
    g.i0 = i0 - m < 0 ? 0 : i0 - m, g.j0 = j0 - m < 0 ? 0 : j0 - m;
    g.w = (i1 + m > c->width ? c->width : i1 + m) - g.i0, g.h = (j1 + m > c->height ? c->height : j1 + m) - g.j0;
    g.cs = avail_w / g.w < avail_h / g.h ? avail_w / g.w : avail_h / g.h;
    g.cs = g.cs < 1 ? 1 : g.cs > 48 ? 48 : g.cs;
    g.x0 = left + (avail_w - g.cs * g.w) / 2, g.y0 = top + (avail_h - g.cs * g.h) / 2;
    return g;
}

static pp_vec2 cell_center(const grid_window *g, int32_t i, int32_t j)
{
    return (pp_vec2){g->x0 + (i - g->i0 + 0.5f) * g->cs, g->y0 + (j - g->j0 + 0.5f) * g->cs};
}

/* Cells in their colours, each critical cell's kernel normal as a short line. */
static void draw_cells(render_image *im, const debug_capture *c, const grid_window *g)
{
    const int32_t gap = g->cs >= 6;
    for (int32_t j = g->j0; j < g->j0 + g->h; j++)
        for (int32_t i = g->i0; i < g->i0 + g->w; i++)
            render_rect(im, g->x0 + (i - g->i0) * g->cs, g->y0 + (j - g->j0) * g->cs, g->cs - gap, g->cs - gap,
                        debug_cell_color(c->cells[(size_t)j * c->width + i]));
    for (int32_t j = g->j0; j < g->j0 + g->h; j++)
        for (int32_t i = g->i0; i < g->i0 + g->w; i++) {
            const pp_vec2 n = to_grid(c, c->normals[(size_t)j * c->width + i]), a = cell_center(g, i, j);
            const float len = hypotf(n.x, n.y), reach = 0.9f * (float)(g->cs > 5 ? g->cs : 5);
            if ((c->cells[(size_t)j * c->width + i] & PP_CELL_CRITICAL) && len > 0)
                render_line(im, a, (pp_vec2){a.x + reach * n.x / len, a.y + reach * n.y / len}, g->cs >= 8 ? 2 : 1,
                            (render_color){255, 255, 255, 230});
        }
}

/* The global normal as a long arrow from the intersection's centroid. */
static void draw_global_normal(render_image *im, const debug_capture *c, const grid_window *g, float length)
{
    double sx = 0, sy = 0, count = 0;
    for (int32_t j = 0; j < c->height; j++)
        for (int32_t i = 0; i < c->width; i++)
            if ((c->cells[(size_t)j * c->width + i] & 3) == 3) {
                const pp_vec2 p = cell_center(g, i, j);
                sx += p.x, sy += p.y, count++;
            }
    const pp_vec2 n = to_grid(c, c->normal);
    const float len = hypotf(n.x, n.y);
    if (count == 0 || len <= 0)
        return;
    const pp_vec2 a = {(float)(sx / count), (float)(sy / count)};
    render_arrow(im, a, (pp_vec2){a.x + length * n.x / len, a.y + length * n.y / len}, 5, 22,
                 (render_color){240, 80, 240, 255});
}

/* Which legend colours the window shows: first body, second, plain intersection, critical. */
static void shown_colours(const debug_capture *c, const grid_window *g, uint8_t shown[4])
{
    for (int32_t j = g->j0; j < g->j0 + g->h; j++)
        for (int32_t i = g->i0; i < g->i0 + g->w; i++) {
            const uint8_t f = c->cells[(size_t)j * c->width + i];
            if (f & PP_CELL_CRITICAL)
                shown[3] = 1;
            else if (f & 3)
                shown[(f & 3) - 1] = 1;
        }
}

void debug_view_title(const debug_capture *c, char *out, size_t size)
{
    if (!c->cells) {
        snprintf(out, size, "NO PAIR WAS IN CONTACT");
        return;
    }
    /* The picture is a window on the pair's grid: say how much of it, so the count matches what is drawn. */
    const grid_window g = debug_window(c, 0, 0, 1, 1);
    snprintf(out, size, "COLLISION AT T = %.2f S: %s, %d X %d OF %d X %d CELLS", c->time, c->what, (int)g.w, (int)g.h,
             (int)c->width, (int)c->height);
}

void debug_view_draw(render_image *im, const debug_capture *c)
{
    render_fill(im, (render_color){24, 26, 32, 255});
    char title[200];
    debug_view_title(c, title, sizeof title);
    render_text(im, 20, 14, 2, title, (render_color){240, 240, 240, 255});
    uint8_t shown[4] = {0};
    if (c->cells) {
        const grid_window g = debug_window(c, 20, 40, im->width - 40, im->height - 90);
        shown_colours(c, &g, shown);
        draw_cells(im, c, &g);
        draw_global_normal(im, c, &g, 0.3f * (float)(im->height - 90));
    }
    draw_legend(im, im->height - 30, c, shown);
}
