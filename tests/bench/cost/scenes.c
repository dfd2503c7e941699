/* The step-cost scenes as engine-neutral data: the rain of 32 px crates into a walled pit, and the destruction
 * scene's terrain bitmap, crates and crater centres. */
#include "cost.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define FRICTION 0.6 /* the stability scenes' default */

enum { RAIN_COLS = 20 };
#define RAIN_SIDE 32.0
#define RAIN_PITCH 35.0 /* 3 px between columns */
#define PIT_W 720.0     /* inside the walls: 20 columns at RAIN_PITCH with their row shifts, 8 px to spare */
#define WALL_T 40.0
#define DROP 40.0       /* the lowest row's bottom above the ground, px */

static stab_body box(double x, double y, double w, double h, double angle, int is_static)
{
    stab_body b;
    memset(&b, 0, sizeof b);
    b.shape = STAB_BOX;
    b.x = x, b.y = y, b.w = w, b.h = h, b.angle = angle;
    b.density = 1.0;
    b.friction = FRICTION;
    b.is_static = is_static;
    return b;
}

int cost_rain_build(int crates, stab_scene *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "rain%d", crates);
    out->kind = STAB_STACK;
    out->tracked = -1;
    const int rows = (crates + RAIN_COLS - 1) / RAIN_COLS;
    /* Rows 2, 3 or 4 px apart, shifted by up to 3 px and turned by up to 0.03 rad (a turned crate still
     * clears its neighbours), so that the pile does not land as a lattice. */
    double height = DROP;
    for (int r = 0; r < rows; r++)
        height += RAIN_SIDE + 2 + r % 3;
    out->bodies = malloc((size_t)(crates + 3) * sizeof *out->bodies);
    if (!out->bodies)
        return -1;
    const double wall_h = height + 64, wall_x = 0.5 * (PIT_W + WALL_T);
    out->bodies[out->count++] = box(0, 20, PIT_W + 2 * WALL_T, 40, 0, 1);
    out->bodies[out->count++] = box(-wall_x, -0.5 * wall_h, WALL_T, wall_h, 0, 1);
    out->bodies[out->count++] = box(wall_x, -0.5 * wall_h, WALL_T, wall_h, 0, 1);
    double bottom = -DROP;
    for (int r = 0; r < rows; r++) {
        const double shift = ((r * 3) % 5 - 2) * 1.5;
        for (int c = 0; c < RAIN_COLS && out->count < crates + 3; c++) {
            const double angle = ((c * 7 + r * 3) % 7 - 3) * 0.01;
            out->bodies[out->count++] = box((c - 0.5 * (RAIN_COLS - 1)) * RAIN_PITCH + shift, bottom - 0.5 * RAIN_SIDE,
                                            RAIN_SIDE, RAIN_SIDE, angle, 0);
        }
        bottom -= RAIN_SIDE + 2 + r % 3;
    }
    return 0;
}

/* The surface's height at x: the middle row with two gentle waves, slopes under 12°. */
static double surface(double x)
{
    return 0.5 * COST_TERRAIN_H + 16 * sin(2 * PI * x / 1024) + 4 * sin(2 * PI * x / 256 + 1);
}

int cost_destruction_build(cost_destruction *out)
{
    memset(out, 0, sizeof *out);
    out->terrain = malloc((size_t)COST_TERRAIN_W * COST_TERRAIN_H);
    out->top = malloc(COST_TERRAIN_W * sizeof *out->top);
    out->crates.bodies = malloc(COST_CRATES * sizeof *out->crates.bodies);
    if (!out->terrain || !out->top || !out->crates.bodies) {
        cost_destruction_free(out);
        return -1;
    }
    for (int i = 0; i < COST_TERRAIN_W; i++) {
        const double s = surface(i + 0.5);
        out->top[i] = COST_TERRAIN_H;
        for (int j = COST_TERRAIN_H - 1; j >= 0; j--) {
            const int solid = j + 0.5 >= s;
            out->terrain[(size_t)j * COST_TERRAIN_W + (size_t)i] = (uint8_t)solid;
            if (solid)
                out->top[i] = j;
        }
    }
    snprintf(out->crates.name, sizeof out->crates.name, "destruction");
    out->crates.tracked = -1;
    /* 40 px apart, sides 16..32 px, each 1 px above the highest surface under it. */
    for (int k = 0; k < COST_CRATES; k++) {
        const double side = 16 + (k * 7) % 17, x = 44 + 40 * k;
        int high = COST_TERRAIN_H;
        for (int i = (int)(x - 0.5 * side); i < (int)(x + 0.5 * side); i++)
            high = out->top[i] < high ? out->top[i] : high;
        out->crates.bodies[out->crates.count++] = box(x, high - 0.5 * side - 1, side, side, 0, 0);
    }
    return 0;
}

void cost_destruction_free(cost_destruction *d)
{
    free(d->terrain);
    free(d->top);
    stab_scene_free(&d->crates);
    memset(d, 0, sizeof *d);
}

void cost_crater(const cost_destruction *d, int k, double *x, double *y)
{
    /* 17 is prime to 50: every crate once a pass, neighbours far apart; each pass 24 px deeper. */
    const stab_body *c = &d->crates.bodies[(k * 17) % d->crates.count];
    const double depth = d->top[(int)c->x] + 24.0 * (k / d->crates.count);
    *x = c->x;
    *y = depth < COST_TERRAIN_H - 2 * COST_CRATER_R ? depth : COST_TERRAIN_H - 2 * COST_CRATER_R;
}

pp_world_def cost_world_def(int sleep)
{
    pp_world_def def = pp_world_def_preset(PP_PRESET_BALANCED);
    def.allow_sleep = (uint32_t)sleep;
    def.backend = PP_BACKEND_CPU;
    def.worker_threads = 1;
    def.gravity = (pp_vec2){0.0f, (float)STAB_GRAVITY};
    return def;
}
