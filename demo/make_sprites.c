/* The demo's sprites, drawn by code so they can be remade: a terrain with caves and a ravine, a plank
 * of the rope bridge over it, crates of three sizes, and a hammer with its weight mask (heavy head, light
 * handle). Usage: make_sprites DIR; writes DIR/<name>.png through pp_image_save. Fixed seed: same bytes. */
#include "physpix.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct rgb {
    int r, g, b;
} rgb;

typedef struct image {
    int w, h;
    uint8_t *px; /* RGBA8, rows top to bottom */
} image;

static uint32_t hash2(int x, int y)
{
    uint32_t h = (uint32_t)x * 0x8da6b343u ^ (uint32_t)y * 0xd8163841u ^ 0x9e3779b9u; /* fixed seed */
    h ^= h >> 13, h *= 0x85ebca6bu, h ^= h >> 16;
    return h;
}

/* Blotchy texture: one of `levels` shades per cell×cell block, so the PNG stays small. */
static int blotch(int x, int y, int cell, int levels) { return (int)(hash2(x / cell, y / cell) % (uint32_t)levels); }

static image image_new(int w, int h)
{
    image im = {w, h, calloc((size_t)w * h * 4, 1)};
    if (!im.px) {
        fprintf(stderr, "make_sprites: out of memory\n");
        exit(1);
    }
    return im;
}

static void put(image *im, int x, int y, rgb c, int shade, int alpha)
{
    uint8_t *p = im->px + ((size_t)y * im->w + x) * 4;
    const int v[3] = {c.r + shade, c.g + shade, c.b + shade};
    for (int k = 0; k < 3; k++)
        p[k] = (uint8_t)(v[k] < 0 ? 0 : v[k] > 255 ? 255 : v[k]);
    p[3] = (uint8_t)alpha;
}

static void save(const image *im, const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    const pp_status st = pp_image_save(path, im->px, im->w, im->h);
    if (st != PP_OK) {
        fprintf(stderr, "make_sprites: %s: %s\n", path, pp_last_error());
        exit(1);
    }
    printf("  %s (%d x %d)\n", path, im->w, im->h);
}

/* ---- terrain: 960 × 260, placed with its top at world y 280 ---- */

enum { TERRAIN_W = 960, TERRAIN_H = 260, PLATEAU = 62, RAVINE_L = 380, RAVINE_R = 580, FLOOR = 238 };

/* The first solid row of column x: flat plateaus either side of a ravine, hills at both edges. */
static double surface_row(int x)
{
    if (x < 80)
        return PLATEAU - 26.0 * (80 - x) / 80.0;
    if (x < RAVINE_L || (x >= RAVINE_R && x < 760))
        return PLATEAU;
    if (x < RAVINE_R) { /* steep walls, a rough floor */
        const double wall = fmin(x - RAVINE_L, RAVINE_R - x) / 14.0;
        return fmin(1.0, wall) * (FLOOR - PLATEAU) + PLATEAU - 4.0 * sin(x / 9.0) * fmin(1.0, wall);
    }
    return PLATEAU - 44.0 * exp(-pow((x - 850) / 55.0, 2)) + 3.0 * sin(x / 13.0);
}

/* Caves: ellipses with a wavy edge. */
static int in_cave(int x, int y)
{
    static const struct {
        double cx, cy, rx, ry;
    } caves[] = {{190, 128, 95, 38}, {700, 150, 78, 40}, {895, 190, 40, 22}, {60, 180, 36, 18}};
    for (size_t i = 0; i < sizeof caves / sizeof caves[0]; i++) {
        const double dx = (x - caves[i].cx) / caves[i].rx, dy = (y - caves[i].cy) / caves[i].ry;
        const double wobble = 1.0 + 0.08 * sin(x / 7.0 + (double)i) + 0.06 * sin(y / 5.0);
        if (dx * dx + dy * dy < wobble)
            return 1;
    }
    return 0;
}

static int terrain_solid(int x, int y) { return y >= surface_row(x) && !in_cave(x, y); }

/* Distance (px, up to 4) to the nearest empty pixel: shades the rims of caves and craters. */
static int rim(int x, int y)
{
    for (int d = 1; d <= 4; d++)
        for (int k = -d; k <= d; k++)
            if (!terrain_solid(x + k, y - d) || !terrain_solid(x + k, y + d) || !terrain_solid(x - d, y + k) ||
                !terrain_solid(x + d, y + k))
                return d;
    return 5;
}

static void make_terrain(const char *dir)
{
    const rgb grass = {78, 158, 58}, dirt = {140, 98, 60}, rock = {112, 106, 100};
    image im = image_new(TERRAIN_W, TERRAIN_H);
    for (int y = 0; y < TERRAIN_H; y++)
        for (int x = 0; x < TERRAIN_W; x++) {
            if (!terrain_solid(x, y))
                continue;
            const double depth = y - surface_row(x);
            const int tex = blotch(x, y, 6, 3) * 8 - 8, edge = rim(x, y);
            const int cave_rim = edge < 5 && depth > 8 ? (edge - 5) * 8 : 0;
            if (depth < 6)
                put(&im, x, y, grass, tex + (depth < 2 ? 20 : 0), 255);
            else if (depth < 40 + 10 * sin(x / 31.0))
                put(&im, x, y, dirt, tex + cave_rim, 255);
            else
                put(&im, x, y, rock, tex + cave_rim - (blotch(x, y, 3, 17) == 0 ? 30 : 0), 255);
        }
    save(&im, dir, "terrain.png");
    free(im.px);
}

/* ---- plank: one board of the rope bridge (28 × 10), its joints 1 px in from each end; pale, so that it shows
 * against the ravine's walls in the contact sheet's quarter-size frames ---- */

static void make_plank(const char *dir)
{
    enum { W = 28, H = 10 };
    const rgb plank = {226, 186, 118}, gap = {120, 80, 40};
    image im = image_new(W, H);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const int edge = y == 0 || y == H - 1 || x == 0 || x == W - 1;
            put(&im, x, y, edge ? gap : plank, edge ? 0 : blotch(x, y, 4, 3) * 6 - (y == 1 ? 0 : 6), 255);
        }
    save(&im, dir, "plank.png");
    free(im.px);
}

/* ---- crates ---- */

static void make_crate(const char *dir, int size, const char *name)
{
    const rgb wood = {176, 124, 62}, dark = {96, 62, 30}, line = {138, 94, 46};
    const int border = size / 10 + 1;
    image im = image_new(size, size);
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            const int edge = x < border || y < border || x >= size - border || y >= size - border;
            const int brace = abs(x - y) <= border / 2 + 1; /* the diagonal board */
            const rgb c = edge ? dark : brace ? line : (y % 8 == 0 ? line : wood);
            put(&im, x, y, c, edge ? 0 : blotch(x, y, 3, 3) * 6, 255);
        }
    save(&im, dir, name);
    free(im.px);
}

/* ---- hammer: head 48 × 20 over a handle 8 × 56; weights 255 in the head, 20 in the handle ---- */

static void make_hammer(const char *dir)
{
    enum { W = 48, H = 76, HEAD = 20, HANDLE_X = 20, HANDLE_W = 8 };
    const rgb steel = {128, 134, 146}, grip = {150, 98, 48};
    image im = image_new(W, H), weights = image_new(W, H);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const int head = y < HEAD, handle = x >= HANDLE_X && x < HANDLE_X + HANDLE_W;
            if (!head && !handle)
                continue;
            const int shine = head ? (y < 4 ? 40 : y > HEAD - 4 ? -30 : 0) : (x == HANDLE_X + 2 ? 24 : 0);
            put(&im, x, y, head ? steel : grip, shine + (head ? 0 : (y % 12 == 0) * -30), 255);
            const int w = head ? 255 : 20;
            put(&weights, x, y, (rgb){w, w, w}, 0, 255);
        }
    save(&im, dir, "hammer.png");
    save(&weights, dir, "hammer_weights.png");
    free(im.px);
    free(weights.px);
}

/* ---- the car (issue 41): a body 56 × 14 and wheels 18 px across, a pale hub so that their turning shows ---- */

static void make_car(const char *dir)
{
    enum { W = 56, H = 14, D = 18 };
    const rgb paint = {200, 54, 46}, glass = {150, 200, 230}, tyre = {40, 40, 44}, hub = {200, 200, 206};
    image body = image_new(W, H), wheel = image_new(D, D);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const int cab = y < 6 && (x < 12 || x >= 34); /* the cab's roof is the middle: its corners are cut */
            if (cab)
                continue;
            const int window = y >= 1 && y < 5 && x >= 16 && x < 30;
            put(&body, x, y, window ? glass : paint, y == H - 1 || x == 0 || x == W - 1 ? -60 : 0, 255);
        }
    for (int y = 0; y < D; y++)
        for (int x = 0; x < D; x++) {
            const double dx = x + 0.5 - D / 2.0, dy = y + 0.5 - D / 2.0, r = sqrt(dx * dx + dy * dy);
            if (r > D / 2.0)
                continue;
            const int spoke = r < 6 && (abs((int)floor(dx)) < 1 || abs((int)floor(dy)) < 1);
            put(&wheel, x, y, r < 4 || spoke ? hub : tyre, 0, 255);
        }
    save(&body, dir, "car.png");
    save(&wheel, dir, "wheel.png");
    free(body.px);
    free(wheel.px);
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "demo";
    printf("make_sprites: writing the demo's sprites to %s/\n", dir);
    make_terrain(dir);
    make_plank(dir);
    make_crate(dir, 24, "crate_small.png");
    make_crate(dir, 32, "crate.png");
    make_crate(dir, 40, "crate_big.png");
    make_hammer(dir);
    make_car(dir);
    return 0;
}
