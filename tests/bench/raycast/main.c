/* Raycasts and queries per second: a 4096×2048 hilly terrain with caves (a static body, about half
 * solid) under 1,000 crates of 16–32 px. Short 64 px rays (bullets), rays across the whole map, rays
 * straight down onto the terrain, circle (r 32) and box (64×64) queries at random points, and a character's move
 * (pp_world_move_character, a frame at 150 px/s on the surface; "hits": grounded after it), and the same move on a
 * plain terrain (a 2048×1024 bitmap, its lower half solid, alone in its world); the best of three runs of each,
 * printed as a table and written as CSV.
 *
 *   bench_raycast [--csv PATH] [--scale F] [--only KIND]   (F multiplies the counts, 1 by default; KIND: one row's
 *   name, e.g. "move_character flat", as under callgrind)
 */
#include "../machine.h"
#include "physpix.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TW 4096
#define TH 2048
#define TOP 1000.0f /* world y of the terrain bitmap's top edge */
#define CRATES 1000
#define PI 3.14159265358979323846

static void check(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "bench_raycast: %s: %s (%s)\n", what, pp_status_name(st), pp_last_error());
        exit(1);
    }
}

static uint64_t seed = 12345;

static double rnd(void)
{
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(seed >> 11) / 9007199254740992.0;
}

/* Bitmap row of the terrain's surface at column x: rolling hills round mid-height. */
static double surface(int x)
{
    const double u = x / (double)TW;
    return TH * 0.4 + 260 * sin(2 * PI * 1.3 * u) + 120 * sin(2 * PI * 4.7 * u + 1.0) + 40 * sin(2 * PI * 17 * u);
}

static uint8_t *terrain_mask(void)
{
    uint8_t *m = malloc((size_t)TW * TH);
    for (int y = 0; y < TH; y++)
        for (int x = 0; x < TW; x++)
            m[(size_t)y * TW + x] = y >= surface(x);
    /* Caves: 150 elliptical pockets below the surface. */
    for (int k = 0; k < 150; k++) {
        const double cx = TW * rnd(), rx = 20 + 60 * rnd(), ry = 10 + 30 * rnd();
        const double cy = surface((int)cx) + 60 + (TH - surface((int)cx) - 80) * rnd();
        for (int y = (int)fmax(0, cy - ry); y < (int)fmin(TH, cy + ry + 1); y++)
            for (int x = (int)fmax(0, cx - rx); x < (int)fmin(TW, cx + rx + 1); x++) {
                const double u = (x - cx) / rx, v = (y - cy) / ry;
                if (u * u + v * v <= 1)
                    m[(size_t)y * TW + x] = 0;
            }
    }
    return m;
}

enum { SHORT, LONG, DOWN, CIRCLE, BOX, MOVE, MOVE_FLAT, KINDS };
static const char *kind_name[KINDS] = {"short 64 px", "across the map", "straight down", "query_circle r32",
                                       "query_aabb 64x64", "move_character", "move_character flat"};

#define FW 2048
#define FH 1024

/* The plain terrain's world: one static 2048×1024 body whose rows from FH / 2 down are solid, its top-left at (0, 0). */
static pp_world flat_world(void)
{
    pp_world_def wd = pp_world_def_default();
    wd.backend = PP_BACKEND_CPU;
    pp_world w;
    check(pp_world_create(&wd, &w), "pp_world_create");
    uint8_t *mask = calloc((size_t)FW * FH, 1);
    memset(mask + (size_t)FW * (FH / 2), 1, (size_t)FW * (FH / 2));
    pp_body_def d = pp_body_def_default();
    d.type = PP_BODY_STATIC, d.width = FW, d.height = FH, d.mask = mask;
    d.position = (pp_vec2){FW / 2.0f, FH / 2.0f};
    pp_body b;
    check(pp_body_create(w, &d, &b), "plain terrain");
    free(mask);
    return w;
}

/* Run n casts or queries of one kind from a fixed seed; returns the hits. */
static int64_t run(pp_world w, int kind, int n)
{
    int64_t hits = 0;
    seed = 777 + (uint64_t)kind;
    pp_body found[64];
    for (int i = 0; i < n; i++) {
        const float x = (float)(TW * rnd()), y = (float)(TOP - 300 + (TH + 300) * rnd());
        pp_raycast_hit h;
        int32_t hit = 0;
        if (kind == SHORT) {
            const double a = 2 * PI * rnd();
            check(pp_world_raycast(w, (pp_vec2){x, y}, (pp_vec2){x + 64 * (float)cos(a), y + 64 * (float)sin(a)},
                                   0xffffffffu, &h, &hit),
                  "raycast");
        } else if (kind == LONG) {
            const float y1 = (float)(TOP - 300 + (TH + 300) * rnd());
            check(pp_world_raycast(w, (pp_vec2){0, y}, (pp_vec2){TW, y1}, 0xffffffffu, &h, &hit), "raycast");
        } else if (kind == DOWN) {
            check(pp_world_raycast(w, (pp_vec2){x, TOP - 400}, (pp_vec2){x, TOP + TH}, 0xffffffffu, &h, &hit),
                  "raycast");
        } else if (kind == CIRCLE) {
            check(pp_world_query_circle(w, (pp_vec2){x, y}, 32, 0xffffffffu, found, 64, &hit), "query_circle");
        } else if (kind == MOVE) { /* a frame of a default character walking at 150 px/s just over the ground */
            const pp_character_def c = pp_character_def_default();
            const int cx = 20 + (int)((TW - 40) * rnd());
            const pp_vec2 at = {(float)cx, (float)(TOP + surface(cx) - 16.5)}, v = {rnd() < 0.5 ? -150.0f : 150.0f, 16};
            pp_character_move m;
            check(pp_world_move_character(w, &c, at, v, 1.0f / 60, &m), "move_character");
            hit = (int32_t)m.grounded;
        } else if (kind == MOVE_FLAT) { /* on the plain terrain, standing on its surface (y FH / 2) */
            const pp_character_def c = pp_character_def_default();
            const pp_vec2 at = {(float)(20 + (FW - 40) * rnd()), FH / 2 - 16.01f}, v = {rnd() < 0.5 ? -150.0f : 150.0f, 16};
            pp_character_move m;
            check(pp_world_move_character(w, &c, at, v, 1.0f / 60, &m), "move_character");
            hit = (int32_t)m.grounded;
        } else {
            check(pp_world_query_aabb(w, (pp_vec2){x - 32, y - 32}, (pp_vec2){x + 32, y + 32}, 0xffffffffu, found, 64,
                                      &hit),
                  "query_aabb");
        }
        hits += hit > 0;
    }
    return hits;
}

int main(int argc, char **argv)
{
    const char *csv_path = NULL;
    double scale = 1;
    const char *only = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--csv") && i + 1 < argc)
            csv_path = argv[++i];
        else if (!strcmp(argv[i], "--scale") && i + 1 < argc)
            scale = atof(argv[++i]);
        else if (!strcmp(argv[i], "--only") && i + 1 < argc)
            only = argv[++i];
        else {
            fprintf(stderr, "usage: bench_raycast [--csv PATH] [--scale F] [--only KIND]\n");
            return 2;
        }
    }
    pp_world_def wd = pp_world_def_default();
    wd.backend = PP_BACKEND_CPU;
    pp_world w;
    check(pp_world_create(&wd, &w), "pp_world_create");
    uint8_t *mask = terrain_mask();
    int64_t solid = 0;
    for (size_t k = 0; k < (size_t)TW * TH; k++)
        solid += mask[k];
    pp_body_def d = pp_body_def_default();
    d.type = PP_BODY_STATIC, d.width = TW, d.height = TH, d.mask = mask;
    d.position = (pp_vec2){TW / 2.0f, TOP + TH / 2.0f};
    pp_body terrain;
    check(pp_body_create(w, &d, &terrain), "terrain");
    free(mask);
    /* Crates scattered over the surface, from resting on it to 300 px above it, at any angle. */
    uint8_t box[32 * 32];
    memset(box, 1, sizeof box);
    for (int i = 0; i < CRATES; i++) {
        pp_body_def bd = pp_body_def_default();
        bd.width = 16 + (int)(17 * rnd()), bd.height = 16 + (int)(17 * rnd()), bd.mask = box;
        const int x = 20 + (int)((TW - 40) * rnd());
        bd.position = (pp_vec2){(float)x, (float)(TOP + surface(x) - 24 - 300 * rnd())};
        bd.angle = (float)(2 * PI * rnd());
        pp_body b;
        check(pp_body_create(w, &bd, &b), "crate");
    }
    const int counts[KINDS] = {200000, 20000, 100000, 100000, 100000, 50000, 50000};
    const pp_world flat = flat_world();
    char cpu[256];
    bench_cpu_model(cpu, sizeof cpu);
    printf("raycasts and queries: a %d x %d terrain (%.0f%% solid, caves), %d crates of 16-32 px; best of 3 runs\n",
           TW, TH, 100.0 * solid / ((double)TW * TH), CRATES);
    printf("machine: %s\n", cpu);
    printf("%-20s %8s %9s %12s %11s %7s\n", "kind", "rays", "seconds", "rays/s", "mean us", "hits %");
    FILE *f = NULL;
    if (csv_path && !(f = fopen(csv_path, "w"))) {
        perror(csv_path);
        return 1;
    }
    if (f)
        fprintf(f, "kind,rays,seconds,rays_per_s,mean_us,hit_pct\n");
    for (int k = 0; k < KINDS; k++) {
        if (only && strcmp(only, kind_name[k]))
            continue;
        const int n = (int)fmax(1, counts[k] * scale);
        double best = INFINITY;
        int64_t hits = 0;
        for (int rep = 0; rep < 3; rep++) {
            const double t0 = bench_clock_ms();
            hits = run(k == MOVE_FLAT ? flat : w, k, n);
            best = fmin(best, (bench_clock_ms() - t0) / 1e3);
        }
        printf("%-20s %8d %9.3f %12.0f %11.3f %7.1f\n", kind_name[k], n, best, n / best, best * 1e6 / n,
               100.0 * hits / n);
        if (f)
            fprintf(f, "%s,%d,%.6f,%.1f,%.4f,%.2f\n", kind_name[k], n, best, n / best, best * 1e6 / n, 100.0 * hits / n);
    }
    if (f) {
        fclose(f);
        printf("wrote %s\n", csv_path);
    }
    check(pp_world_destroy(w), "pp_world_destroy");
    check(pp_world_destroy(flat), "pp_world_destroy");
    return 0;
}
