/* The stability scenes as engine-neutral bodies (px, y down, rad): towers, pyramids, heavy on light, the
 * chain, the card houses, the arches (ours and Box2D v3's), the rolling disc, the bounce, the friction ramp and the wall shots. Every
 * engine builds its bodies from these numbers, so the peers get the same shapes, masses and materials. */
#include "stability.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define GROUND_W 1600.0  /* wide enough for the 20-row pyramid and the card house */
#define GROUND_H 40.0
#define SLOPE_L 1600.0   /* ramps and slopes: a long static box, turned */
#define SLOPE_T 40.0
#define SLOPE_START -600.0 /* where a body starts along the slope from its middle, px */
#define DEFAULT_FRICTION 0.6

/* A growable scene: bodies appended one at a time. */
static int add(stab_scene *s, const stab_body *b)
{
    if ((s->count & (s->count - 1)) == 0) { /* at 0, 1, 2, 4, ...: double */
        int cap = s->count ? 2 * s->count : 1;
        stab_body *grown = realloc(s->bodies, (size_t)cap * sizeof *grown);
        if (!grown)
            return -1;
        s->bodies = grown;
    }
    s->bodies[s->count++] = *b;
    return 0;
}

static stab_body box(double x, double y, double w, double h, double angle)
{
    stab_body b;
    memset(&b, 0, sizeof b);
    b.shape = STAB_BOX;
    b.x = x, b.y = y, b.w = w, b.h = h, b.angle = angle;
    b.density = 1.0;
    b.friction = DEFAULT_FRICTION;
    return b;
}

static stab_body disc(double x, double y, double r)
{
    stab_body b = box(x, y, 0, 0, 0);
    b.shape = STAB_DISC;
    b.radius = r;
    return b;
}

/* The static ground: a wide box whose top is at y = 0. */
static int add_ground(stab_scene *s, double friction)
{
    stab_body g = box(0, 0.5 * GROUND_H, GROUND_W, GROUND_H, 0);
    g.is_static = 1;
    g.friction = friction;
    s->ground_top = 0;
    return add(s, &g);
}

/* A static slope turned by `angle` (down the slope is (cos, sin)), centred on the origin; *n gets the top
 * face's outward normal. Returns the point of the top face SLOPE_START along it. */
static int add_slope(stab_scene *s, double angle, double friction, double *px, double *py, double *nx, double *ny)
{
    stab_body g = box(0, 0, SLOPE_L, SLOPE_T, angle);
    g.is_static = 1;
    g.friction = friction;
    *nx = sin(angle), *ny = -cos(angle);
    *px = cos(angle) * SLOPE_START + *nx * 0.5 * SLOPE_T;
    *py = sin(angle) * SLOPE_START + *ny * 0.5 * SLOPE_T;
    s->slope = angle;
    return add(s, &g);
}

/* n boxes of side `side` stacked exactly touching. */
static int build_tower(stab_scene *s, int n, int side)
{
    int rc = add_ground(s, DEFAULT_FRICTION);
    for (int i = 0; i < n && rc == 0; i++) {
        stab_body b = box(0, -(i + 0.5) * side, side, side, 0);
        rc = add(s, &b);
    }
    return rc;
}

/* rows of 16 px boxes at an 18 px pitch (2 px gaps), each row half a pitch in. */
static int build_pyramid(stab_scene *s, int rows, int unused)
{
    const double side = 16, pitch = 18;
    int rc = add_ground(s, DEFAULT_FRICTION);
    for (int k = 0; k < rows && rc == 0; k++)
        for (int j = 0; j < rows - k && rc == 0; j++) {
            stab_body b = box((j - 0.5 * (rows - k - 1)) * pitch, -(k + 0.5) * side, side, side, 0);
            rc = add(s, &b);
        }
    return rc;
}

/* `light` boxes of density 1 with one 16 px box of density `ratio` on top (tracked). */
static int build_heavy(stab_scene *s, int ratio, int light)
{
    int rc = build_tower(s, light + 1, 16);
    s->tracked = s->count - 1;
    if (rc == 0)
        s->bodies[s->tracked].density = ratio;
    return rc;
}

/* Four 16 px boxes of density 1, 10, 100, 1000 from the bottom up; the top one is tracked. */
static int build_chain(stab_scene *s, int unused_a, int unused_b)
{
    int rc = build_tower(s, 4, 16);
    for (int i = 0; i < 4 && rc == 0; i++)
        s->bodies[1 + i].density = pow(10.0, i);
    s->tracked = s->count - 1;
    return rc;
}

/* A card house: `levels` rows of A-shaped tents of two 2 × 32 px cards leaning at ±15° from vertical, and flat
 * cards bridging neighbouring apexes, each resting on the near outer top corner of both (0.6 px to spare);
 * the next row's tents stand centred on those flat cards. A tent's cards overlap 0.8 px at the apex (each is
 * 0.4 px in from corner-on-corner contact), so that they press into each other instead of balancing on their
 * corners. Friction 1. So built (`cardhouse4`) it collapses in every engine of bench_stability within 0.25 s: the
 * flats barely reach the corners. `wide`: each flat spans its two tents (`cardhouse2w`, `3w`, `4w`). */
static int build_card_house(stab_scene *s, int levels, int wide)
{
    const double len = 32, t = 2, phi = 15 * PI / 180, mu = 1.0, overhang = 1.0, lean_in = 0.4;
    const double c = cos(phi), sn = sin(phi);
    const double dx = 0.5 * t * c + 0.5 * len * sn - lean_in; /* a card's centre from its tent's axis */
    const double rise = t * sn + len * c;                      /* tent base to its outer top corners */
    const double pitch = len + 2 * t * c - 2 * overhang;       /* tent axes apart */
    int rc = add_ground(s, mu);
    double base = 0, x0 = -0.5 * (levels - 1) * pitch;
    for (int k = 0; k < levels && rc == 0; k++) {
        const int tents = levels - k;
        const double cy = base - (0.5 * t * sn + 0.5 * len * c);
        for (int i = 0; i < tents && rc == 0; i++) {
            const double ax = x0 + i * pitch;
            stab_body left = box(ax - dx, cy, t, len, phi), right = box(ax + dx, cy, t, len, -phi);
            left.friction = right.friction = mu;
            rc = add(s, &left);
            if (rc == 0)
                rc = add(s, &right);
        }
        const double top = base - rise;
        for (int i = 0; i + 1 < tents && rc == 0; i++) {
            /* wide: the flat spans its tents, its ends 0.25 px short of their axes (1.3 px past the corners) */
            stab_body flat = box(x0 + (i + 0.5) * pitch, top - 0.5 * t, wide ? pitch - 0.5 : len, t, 0);
            flat.friction = mu;
            rc = add(s, &flat);
        }
        base = top - t;
        x0 += 0.5 * pitch;
    }
    return rc;
}

/* A convex polygon given by its world vertices (px, y down), as a body about its centroid. */
static stab_body polygon(const double *px, const double *py, int n)
{
    double area = 0, cx = 0, cy = 0;
    for (int i = 0; i < n; i++) {
        const int j = (i + 1) % n;
        const double cr = px[i] * py[j] - px[j] * py[i];
        area += 0.5 * cr;
        cx += (px[i] + px[j]) * cr;
        cy += (py[i] + py[j]) * cr;
    }
    cx /= 6 * area, cy /= 6 * area;
    stab_body b = box(cx, cy, 0, 0, 0);
    b.shape = STAB_POLY;
    b.nverts = n;
    for (int i = 0; i < n; i++)
        b.vx[i] = px[i] - cx, b.vy[i] = py[i] - cy;
    return b;
}

/* One voussoir: the trapezoid between angles a0 and a1 (from the +x axis, upward) of the ring from r_in to
 * r_out about (0, 0). */
static stab_body voussoir(double r_in, double r_out, double a0, double a1)
{
    const double px[4] = {r_in * cos(a0), r_out * cos(a0), r_out * cos(a1), r_in * cos(a1)};
    const double py[4] = {-r_in * sin(a0), -r_out * sin(a0), -r_out * sin(a1), -r_in * sin(a1)};
    return polygon(px, py, 4);
}

/* A semicircular arch of `blocks` voussoirs, inner radius 80 px, outer 110 px, standing on the ground. */
static int build_arch(stab_scene *s, int blocks, int unused)
{
    const double mu = 0.7;
    int rc = add_ground(s, mu);
    for (int k = 0; k < blocks && rc == 0; k++) {
        stab_body b = voussoir(80, 110, PI * k / blocks, PI * (k + 1) / blocks);
        b.friction = mu;
        rc = add(s, &b);
    }
    return rc;
}

/* Box2D v3's Card House (samples/sample_stacking.cpp, from PEEL) with its lengths ×5 at 100 px a metre, so
 * 500 px for each of its metres, and cards 2 px thick (its 0.002 m would be 1 px): `levels` rows of tents of
 * two 200 × 2 px cards at ±25°, a 175 px pitch, flats 125 px from each tent's start, friction 0.7. Neighbouring
 * flats overlap 25 px end to end, as they do in Box2D. Centred on x = 0. It stands while no card moves 20 px. */
static int build_card_house_v3(stab_scene *s, int levels, int unused)
{
    const double scale = 500, mu = 0.7, card_h = 0.2, phi = 25 * PI / 180;
    const double centre = 0.5 * (levels - 1) * 0.35 + 0.0875; /* m: the middle tent's axis */
    s->max_move = 20;
    s->seconds = 30;
    int rc = add_ground(s, mu);
    double y = card_h - 0.02, z0 = 0;
    for (int nb = levels; nb > 0 && rc == 0; nb--) {
        double z = z0;
        for (int i = 0; i < nb && rc == 0; i++) {
            if (i != nb - 1) {
                /* Box2D's card turned by 90°: the same 200 × 2 px box, unturned */
                stab_body flat = box((z + 0.25 - centre) * scale, -(y + card_h - 0.015) * scale, 200, 2, 0);
                flat.friction = mu;
                rc = add(s, &flat);
            }
            /* y up becomes y down, and Box2D's -25° (top toward +x) becomes +25° */
            stab_body left = box((z - centre) * scale, -y * scale, 2, 200, phi);
            stab_body right = box((z + 0.175 - centre) * scale, -y * scale, 2, 200, -phi);
            left.friction = right.friction = mu;
            if (rc == 0)
                rc = add(s, &left);
            if (rc == 0)
                rc = add(s, &right);
            z += 0.35;
        }
        y += 2 * card_h - 0.03;
        z0 += 0.175;
    }
    return rc;
}

/* Box2D v3's Arch (samples/sample_stacking.cpp) at 100 px a metre: 8 blocks a side between its two curves of
 * 9 points (scaled by 0.25), a keystone, and four 400 × 100 px slabs stacked on it; friction 0.6, the ground
 * included. About 1200 px wide and 1500 px tall. It stands while no block moves 50 px. */
static int build_arch_v3(stab_scene *s, int unused_a, int unused_b)
{
    static const double ps1[9][2] = {{16.0, 0.0},
                                     {14.93803712795643, 5.133601056842984},
                                     {13.79871746027416, 10.24928069555078},
                                     {12.56252963284711, 15.34107019122473},
                                     {11.20040987372525, 20.39856541571217},
                                     {9.66521217819836, 25.40369899225096},
                                     {7.87179930638133, 30.3179337000085},
                                     {5.635199558196225, 35.03820717801641},
                                     {2.405937953536585, 39.09554102558315}};
    static const double ps2[9][2] = {{24.0, 0.0},
                                     {22.33619528222415, 6.02299846205841},
                                     {20.54936888969905, 12.00964361211476},
                                     {18.60854610798073, 17.9470321677465},
                                     {16.46769273811807, 23.81367936585418},
                                     {14.05325025774858, 29.57079353071012},
                                     {11.23551045834022, 35.13775818285372},
                                     {7.752568160730571, 40.30450679009583},
                                     {3.016931552701656, 44.28891593799322}};
    const double k = 0.25 * 100, mu = 0.6; /* px a unit of the sample's points; y turns down */
    s->max_move = 50;
    s->seconds = 30;
    int rc = add_ground(s, mu);
    for (int side = 1; side >= -1 && rc == 0; side -= 2)
        for (int i = 0; i < 8 && rc == 0; i++) {
            const double px[4] = {side * ps1[i][0] * k, side * ps2[i][0] * k, side * ps2[i + 1][0] * k, side * ps1[i + 1][0] * k};
            const double py[4] = {-ps1[i][1] * k, -ps2[i][1] * k, -ps2[i + 1][1] * k, -ps1[i + 1][1] * k};
            stab_body b = polygon(px, py, 4);
            b.friction = mu;
            rc = add(s, &b);
        }
    const double kx[4] = {ps1[8][0] * k, ps2[8][0] * k, -ps2[8][0] * k, -ps1[8][0] * k};
    const double ky[4] = {-ps1[8][1] * k, -ps2[8][1] * k, -ps2[8][1] * k, -ps1[8][1] * k};
    stab_body key = polygon(kx, ky, 4);
    key.friction = mu;
    if (rc == 0)
        rc = add(s, &key);
    for (int i = 0; i < 4 && rc == 0; i++) {
        stab_body slab = box(0, -(0.5 + 0.25 * ps2[8][1] + i) * 100, 400, 100, 0);
        slab.friction = mu;
        rc = add(s, &slab);
    }
    return rc;
}

/* A disc of radius r on a static 20° slope, friction 1, at rest and touching. */
static int build_roll(stab_scene *s, int r, int unused)
{
    double px, py, nx, ny;
    s->kind = STAB_ROLL;
    s->seconds = 1.5;
    int rc = add_slope(s, 20 * PI / 180, 1.0, &px, &py, &nx, &ny);
    stab_body d = disc(px + nx * r, py + ny * r, r);
    d.friction = 1.0;
    s->tracked = s->count;
    return rc ? rc : add(s, &d);
}

/* A ball of radius 16 px and restitution percent/100, its bottom 200 px above the ground (restitution 0),
 * measured over `bounces` rebounds (0: the first). */
static int build_bounce(stab_scene *s, int percent, int bounces)
{
    s->kind = STAB_BOUNCE;
    s->drop = 200;
    s->bounces = bounces;
    s->seconds = bounces > 1 ? 1.5 * bounces : 2.0; /* a 200 px rebound is 1.28 s */
    int rc = add_ground(s, DEFAULT_FRICTION);
    stab_body ball = disc(0, -s->drop - 16, 16);
    ball.restitution = percent / 100.0;
    s->tracked = s->count;
    return rc ? rc : add(s, &ball);
}

/* A 16 px box at rest on a static ramp of `degrees`, both of friction 0.5. */
static int build_ramp(stab_scene *s, int degrees, int unused)
{
    double px, py, nx, ny;
    const double a = degrees * PI / 180;
    s->kind = STAB_RAMP;
    s->mu = 0.5;
    s->seconds = tan(a) < s->mu ? 2.0 : 1.5;
    int rc = add_slope(s, a, s->mu, &px, &py, &nx, &ny);
    stab_body b = box(px + nx * 8, py + ny * 8, 16, 16, a);
    b.friction = s->mu;
    s->tracked = s->count;
    return rc ? rc : add(s, &b);
}

/* An 8 px box shot along +x at `speed` px/s at a static wall 8 px thick and 200 px tall on the ground,
 * from 296 px in front of it, halfway up. */
static int build_shot(stab_scene *s, int speed, int unused)
{
    s->kind = STAB_SHOT;
    s->seconds = 1.0;
    s->wall_x0 = 400, s->wall_x1 = 408;
    int rc = add_ground(s, DEFAULT_FRICTION);
    stab_body wall = box(0.5 * (s->wall_x0 + s->wall_x1), -100, s->wall_x1 - s->wall_x0, 200, 0);
    wall.is_static = 1;
    stab_body b = box(100, -100, 8, 8, 0);
    b.vel_x = speed;
    b.bullet = 1;
    if (rc == 0)
        rc = add(s, &wall);
    s->tracked = s->count;
    return rc ? rc : add(s, &b);
}

typedef struct scene_entry {
    const char *name;
    int (*build)(stab_scene *s, int a, int b);
    int a, b;
} scene_entry;

static const scene_entry scenes[] = {
    {"tower10_16", build_tower, 10, 16},
    {"tower20_16", build_tower, 20, 16},
    {"tower10_32", build_tower, 10, 32},
    {"tower20_32", build_tower, 20, 32},
    {"pyramid10", build_pyramid, 10, 0},
    {"pyramid20", build_pyramid, 20, 0},
    {"heavy100_on1", build_heavy, 100, 1},
    {"heavy100_on2", build_heavy, 100, 2},
    {"heavy100_on3", build_heavy, 100, 3},
    {"heavy1000_on1", build_heavy, 1000, 1},
    {"heavy1000_on2", build_heavy, 1000, 2},
    {"heavy1000_on3", build_heavy, 1000, 3},
    {"chain", build_chain, 0, 0},
    {"cardhouse4", build_card_house, 4, 0},
    {"cardhouse2w", build_card_house, 2, 1},
    {"cardhouse3w", build_card_house, 3, 1},
    {"cardhouse4w", build_card_house, 4, 1},
    {"arch11", build_arch, 11, 0},
    {"cardhouse_v3", build_card_house_v3, 5, 0},
    {"cardhouse_v3_3", build_card_house_v3, 3, 0},
    {"arch_v3", build_arch_v3, 0, 0},
    {"roll16", build_roll, 16, 0},
    {"roll32", build_roll, 32, 0},
    {"bounce_e0.5", build_bounce, 50, 0},
    {"bounce_e1", build_bounce, 100, 0},
    {"bounce10_e1", build_bounce, 100, 10},
    {"ramp20", build_ramp, 20, 0},
    {"ramp35", build_ramp, 35, 0},
    {"shot2000", build_shot, 2000, 0},
    {"shot5000", build_shot, 5000, 0},
    {"shot10000", build_shot, 10000, 0},
};
#define NSCENES (int)(sizeof scenes / sizeof scenes[0])

int stab_scene_count(void)
{
    return NSCENES;
}

const char *stab_scene_name(int i)
{
    return i >= 0 && i < NSCENES ? scenes[i].name : NULL;
}

int stab_scene_find(const char *name)
{
    for (int i = 0; name && i < NSCENES; i++)
        if (strcmp(scenes[i].name, name) == 0)
            return i;
    return -1;
}

int stab_scene_build(int i, stab_scene *out)
{
    memset(out, 0, sizeof *out);
    if (i < 0 || i >= NSCENES)
        return -1;
    snprintf(out->name, sizeof out->name, "%s", scenes[i].name);
    out->kind = STAB_STACK;
    out->tracked = -1;
    if (scenes[i].build(out, scenes[i].a, scenes[i].b) != 0) {
        stab_scene_free(out);
        return -1;
    }
    return 0;
}

void stab_scene_free(stab_scene *s)
{
    free(s->bodies);
    s->bodies = NULL;
    s->count = 0;
}

double stab_body_size(const stab_body *b)
{
    if (b->shape == STAB_DISC)
        return 2 * b->radius;
    if (b->shape == STAB_BOX)
        return b->w > b->h ? b->w : b->h;
    double longest = 0;
    for (int i = 0; i < b->nverts; i++) {
        const int j = (i + 1) % b->nverts;
        const double d = hypot(b->vx[j] - b->vx[i], b->vy[j] - b->vy[i]);
        longest = d > longest ? d : longest;
    }
    return longest;
}
