/* Analytic collision cases, shared by tests/c/test_normals.c and the accuracy benchmark: pairs
 * posed at a known overlap and collided with pp_world_collide (no stepping), each kept beside its
 * analytic normal and depth. Header-only (everything static inline), like tests/c/helpers.h, so
 * that the Criterion binary and the benchmark both include it without another object file. */
#ifndef PHYSPIX_ANALYTIC_H
#define PHYSPIX_ANALYTIC_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "physpix.h"

#define ANALYTIC_DISC_R 30        ///< disc radius of the circle–circle case, px
#define ANALYTIC_CIRCLE_DIRS 36   ///< directions of the circle–circle case
#define ANALYTIC_BOX_HALF 20      ///< half side of the box of the box–ground case, px
#define ANALYTIC_BOX_ANGLES 91    ///< box–ground angles, 0..90 whole degrees
#define ANALYTIC_GROUND_TOP 500.0 ///< y of the ground's top edge in the box–ground case, px
#define ANALYTIC_BOXBOX_POSES 90  ///< poses of the rotated box–box case, each collided both ways
#define ANALYTIC_PEN 3.0          ///< penetration of the analytic shapes in every case, px
#define ANALYTIC_MAX_CONTACTS 8   ///< contacts kept per pair (capacity handed to pp_world_collide)
#define ANALYTIC_MAX_PAIRS (2 * ANALYTIC_BOXBOX_POSES)

#define ANALYTIC_PI 3.14159265358979323846
#define ANALYTIC_RAD(d) ((d) * (ANALYTIC_PI / 180.0))

/// The three families of the accuracy bar (tests/bench/README.md, "The bars").
typedef enum analytic_family {
    ANALYTIC_CIRCLES,    ///< disc b around disc a at 36 directions
    ANALYTIC_BOX_GROUND, ///< a 40×40 box at every whole degree 0..90 sunk into a static ground (a = box)
    ANALYTIC_BOX_BOX,    ///< a 30×30 box's corner in a 60×60 box's face, 90 poses, each collided both ways
    ANALYTIC_FAMILY_COUNT
} analytic_family;

/// One collided pair: where its shapes were, what the analytic answer is, what the library said.
typedef struct analytic_pair {
    char what[80];           ///< names the pose, for messages
    pp_body a, b;            ///< the pair as collided, a first
    double a_x, a_y, a_angle;///< a's centre (px) and rotation (rad)
    double b_x, b_y, b_angle;///< b's centre (px) and rotation (rad)
    double nx, ny;           ///< analytic unit normal from a to b
    double depth;            ///< analytic penetration along it, px
    pp_status status;        ///< what pp_world_collide returned
    int32_t count;           ///< contacts it reported (the first ANALYTIC_MAX_CONTACTS are kept)
    pp_contact c[ANALYTIC_MAX_CONTACTS];
} analytic_pair;

/// Every pair of one family, collided in one world (destroyed before analytic_run returns).
typedef struct analytic_set {
    analytic_family family;
    int n;                   ///< pairs
    analytic_pair pair[ANALYTIC_MAX_PAIRS];
} analytic_set;

/// Name of a family, e.g. "circle-circle".
static inline const char *analytic_family_name(analytic_family f)
{
    static const char *const names[ANALYTIC_FAMILY_COUNT] = {"circle-circle", "box-ground", "box-box"};
    return (unsigned)f < ANALYTIC_FAMILY_COUNT ? names[f] : "?";
}

/// Angle between two 2D directions (need not be unit), degrees in [0, 180].
static inline double analytic_angle_deg(double ax, double ay, double bx, double by)
{
    return fabs(atan2(ax * by - ay * bx, ax * bx + ay * by) * (180.0 / ANALYTIC_PI));
}

/* A body from a def and a mask the caller fills; the library copies the mask. */
static inline pp_status analytic_body(pp_world w, pp_body_type type, double x, double y, int width, int height,
                                      const uint8_t *mask, pp_body *out)
{
    pp_body_def d = pp_body_def_default();
    d.type = type;
    d.position = (pp_vec2){(float)x, (float)y};
    d.width = width;
    d.height = height;
    d.mask = mask;
    return pp_body_create(w, &d, out);
}

static inline pp_status analytic_rect(pp_world w, pp_body_type type, double x, double y, int width, int height,
                                      pp_body *out)
{
    uint8_t *m = malloc((size_t)width * (size_t)height);
    if (!m)
        return PP_ERR_OUT_OF_MEMORY;
    memset(m, 1, (size_t)width * (size_t)height);
    pp_status st = analytic_body(w, type, x, y, width, height, m, out);
    free(m);
    return st;
}

/* A disc of radius r in a 2r×2r bitmap, pixels in by their centres (as tests/c/helpers.h's disc_mask). */
static inline pp_status analytic_disc(pp_world w, double x, double y, int r, pp_body *out)
{
    const int n = 2 * r;
    uint8_t *m = calloc((size_t)n * (size_t)n, 1);
    if (!m)
        return PP_ERR_OUT_OF_MEMORY;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double dx = i + 0.5 - r, dy = j + 0.5 - r;
            m[j * n + i] = dx * dx + dy * dy <= (double)r * r;
        }
    pp_status st = analytic_body(w, PP_BODY_DYNAMIC, x, y, n, n, m, out);
    free(m);
    return st;
}

/* Collide a posed pair and record it with its analytic answer. */
static inline void analytic_collide(pp_world w, analytic_set *s, pp_body a, pp_body b, double nx, double ny)
{
    analytic_pair *p = &s->pair[s->n++];
    p->a = a;
    p->b = b;
    p->nx = nx;
    p->ny = ny;
    p->depth = ANALYTIC_PEN;
    p->count = 0;
    p->status = pp_world_collide(w, a, b, p->c, ANALYTIC_MAX_CONTACTS, &p->count);
}

/* Disc b around disc a at 36 directions, overlapping by PEN px. */
static inline pp_status analytic_circles(pp_world w, analytic_set *s)
{
    const double ax = 400.0, ay = 400.0, d = 2.0 * ANALYTIC_DISC_R - ANALYTIC_PEN;
    pp_body a, b;
    pp_status st;
    if ((st = analytic_disc(w, ax, ay, ANALYTIC_DISC_R, &a)) || (st = analytic_disc(w, 0, 0, ANALYTIC_DISC_R, &b)))
        return st;
    for (int k = 0; k < ANALYTIC_CIRCLE_DIRS; k++) {
        const double th = ANALYTIC_RAD(10.0 * k + 3.0); /* off the axes, so no direction is pixel-aligned by luck */
        const double ux = cos(th), uy = sin(th), bx = ax + d * ux, by = ay + d * uy;
        if ((st = pp_body_set_transform(w, b, (pp_vec2){(float)bx, (float)by}, (float)(0.1 * k))))
            return st;
        analytic_pair *p = &s->pair[s->n];
        snprintf(p->what, sizeof p->what, "circles at %.0f deg", 10.0 * k + 3.0);
        p->a_x = ax, p->a_y = ay, p->a_angle = 0;
        p->b_x = bx, p->b_y = by, p->b_angle = 0.1 * k;
        analytic_collide(w, s, a, b, ux, uy);
    }
    return PP_OK;
}

/* A 40×40 box at 0..90° sunk PEN px into a wide static ground; a = box, b = ground. */
static inline pp_status analytic_box_ground(pp_world w, analytic_set *s)
{
    const double top = ANALYTIC_GROUND_TOP;
    pp_body ground, box;
    pp_status st;
    if ((st = analytic_rect(w, PP_BODY_STATIC, 1000, top + 50, 2000, 100, &ground)) ||
        (st = analytic_rect(w, PP_BODY_DYNAMIC, 0, 0, 2 * ANALYTIC_BOX_HALF, 2 * ANALYTIC_BOX_HALF, &box)))
        return st;
    for (int deg = 0; deg < ANALYTIC_BOX_ANGLES; deg++) {
        const double a = ANALYTIC_RAD((double)deg);
        const double h = ANALYTIC_BOX_HALF * (fabs(cos(a)) + fabs(sin(a)));
        const double x = 1000.0 + 0.37 * deg, y = top - h + ANALYTIC_PEN; /* sub-pixel offsets vary with the angle */
        if ((st = pp_body_set_transform(w, box, (pp_vec2){(float)x, (float)y}, (float)a)))
            return st;
        analytic_pair *p = &s->pair[s->n];
        snprintf(p->what, sizeof p->what, "box at %d deg", deg);
        p->a_x = x, p->a_y = y, p->a_angle = a;
        p->b_x = 1000, p->b_y = top + 50, p->b_angle = 0;
        analytic_collide(w, s, box, ground, 0.0, 1.0);
    }
    return PP_OK;
}

/* A 30×30 box B, turned by rel = 5..85° relative to a 60×60 box A, its corner PEN px into A's
 * right face, for A at 0..89°: the analytic normal is A's face normal n = R(alpha)·(1, 0).
 * Each pose is collided both ways: (A, B) must give n, (B, A) must give -n. */
static inline pp_status analytic_box_box(pp_world w, analytic_set *s)
{
    const double ax = 500.0, ay = 500.0;
    pp_body A, B;
    pp_status st;
    if ((st = analytic_rect(w, PP_BODY_DYNAMIC, ax, ay, 60, 60, &A)) ||
        (st = analytic_rect(w, PP_BODY_DYNAMIC, 0, 0, 30, 30, &B)))
        return st;
    for (int deg = 0; deg < ANALYTIC_BOXBOX_POSES; deg++) {
        const double rel = ANALYTIC_RAD(5.0 + (deg * 37) % 81), hb = 15.0 * (cos(rel) + sin(rel));
        const double al = ANALYTIC_RAD((double)deg), c = cos(al), sn = sin(al);
        const double lx = 30.0 + hb - ANALYTIC_PEN, ly = 4.0 - 0.1 * deg; /* in A's frame */
        const double bx = ax + c * lx - sn * ly, by = ay + sn * lx + c * ly;
        if ((st = pp_body_set_transform(w, A, (pp_vec2){(float)ax, (float)ay}, (float)al)) ||
            (st = pp_body_set_transform(w, B, (pp_vec2){(float)bx, (float)by}, (float)(al + rel))))
            return st;
        for (int swap = 0; swap < 2; swap++) {
            analytic_pair *p = &s->pair[s->n];
            snprintf(p->what, sizeof p->what, "box-box at %d deg, relative %d deg%s", deg, 5 + (deg * 37) % 81,
                     swap ? ", swapped" : "");
            const double sign = swap ? -1.0 : 1.0;
            p->a_x = swap ? bx : ax, p->a_y = swap ? by : ay, p->a_angle = swap ? al + rel : al;
            p->b_x = swap ? ax : bx, p->b_y = swap ? ay : by, p->b_angle = swap ? al : al + rel;
            analytic_collide(w, s, swap ? B : A, swap ? A : B, sign * c, sign * sn);
        }
    }
    return PP_OK;
}

/// Pose and collide every pair of a family in a new world made from def; PP_OK unless the set-up failed
/// (each pair's own pp_world_collide status is in its record).
static inline pp_status analytic_run(analytic_family family, const pp_world_def *def, analytic_set *out)
{
    out->family = family;
    out->n = 0;
    pp_world w;
    pp_status st = pp_world_create(def, &w);
    if (st)
        return st;
    switch (family) {
    case ANALYTIC_CIRCLES: st = analytic_circles(w, out); break;
    case ANALYTIC_BOX_GROUND: st = analytic_box_ground(w, out); break;
    case ANALYTIC_BOX_BOX: st = analytic_box_box(w, out); break;
    default: st = PP_ERR_INVALID_ARGUMENT; break;
    }
    pp_status st2 = pp_world_destroy(w);
    return st ? st : st2;
}

/// Append the normal error (degrees) of each kept contact of a pair to normal_err, and return the depth
/// error of the pair: |deepest contact's depth − analytic depth|, px.
static inline double analytic_errors(const analytic_pair *p, double *normal_err, int *n_normal)
{
    double deepest = 0;
    const int n = p->count < ANALYTIC_MAX_CONTACTS ? p->count : ANALYTIC_MAX_CONTACTS;
    for (int k = 0; k < n; k++) {
        normal_err[(*n_normal)++] = analytic_angle_deg(p->c[k].normal.x, p->c[k].normal.y, p->nx, p->ny);
        if (p->c[k].depth > deepest)
            deepest = p->c[k].depth;
    }
    return fabs(deepest - p->depth);
}

#endif /* PHYSPIX_ANALYTIC_H */
