/* The PhysPix side of the stability benchmark: each engine-neutral body becomes a raster (a pixel is solid
 * when its centre lies inside the shape), and an engine row steps a world of a preset with sleep off.
 * Only the public API. */
#include "stability.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int check(pp_status st, const char *what)
{
    if (st == PP_OK)
        return 0;
    fprintf(stderr, "bench_stability: %s failed: %s: %s\n", what, pp_status_name(st), pp_last_error());
    return -1;
}

/* Whether local point (x, y) lies inside the body's shape (on an edge counts). */
static int inside(const stab_body *b, double x, double y)
{
    if (b->shape == STAB_BOX)
        return fabs(x) <= 0.5 * b->w && fabs(y) <= 0.5 * b->h;
    if (b->shape == STAB_DISC)
        return x * x + y * y <= b->radius * b->radius;
    int pos = 0, neg = 0; /* convex: the point is on one side of every edge */
    for (int i = 0; i < b->nverts; i++) {
        const int j = (i + 1) % b->nverts;
        const double cr = (b->vx[j] - b->vx[i]) * (y - b->vy[i]) - (b->vy[j] - b->vy[i]) * (x - b->vx[i]);
        pos += cr > 0, neg += cr < 0;
    }
    return pos == 0 || neg == 0;
}

/* The shape's local bounds, px. */
static void local_bounds(const stab_body *b, double *x0, double *y0, double *x1, double *y1)
{
    if (b->shape == STAB_POLY) {
        *x0 = *x1 = b->vx[0], *y0 = *y1 = b->vy[0];
        for (int i = 1; i < b->nverts; i++) {
            *x0 = fmin(*x0, b->vx[i]), *x1 = fmax(*x1, b->vx[i]);
            *y0 = fmin(*y0, b->vy[i]), *y1 = fmax(*y1, b->vy[i]);
        }
        return;
    }
    const double hx = b->shape == STAB_DISC ? b->radius : 0.5 * b->w;
    const double hy = b->shape == STAB_DISC ? b->radius : 0.5 * b->h;
    *x0 = -hx, *y0 = -hy, *x1 = hx, *y1 = hy;
}

uint8_t *stab_body_mask(const stab_body *b, int32_t *w, int32_t *h, pp_vec2 *pivot)
{
    double x0, y0, x1, y1;
    local_bounds(b, &x0, &y0, &x1, &y1);
    /* Whole pixels of the local frame: a box of integer sides is exactly its bitmap. */
    const double ox = floor(x0), oy = floor(y0);
    *w = (int32_t)ceil(x1 - ox), *h = (int32_t)ceil(y1 - oy);
    *pivot = (pp_vec2){(float)-ox, (float)-oy};
    uint8_t *mask = malloc((size_t)*w * (size_t)*h);
    for (int32_t j = 0; mask && j < *h; j++)
        for (int32_t i = 0; i < *w; i++)
            mask[(size_t)j * (size_t)*w + (size_t)i] = (uint8_t)inside(b, ox + i + 0.5, oy + j + 0.5);
    return mask;
}

int stab_physpix_add_bodies(pp_world w, const stab_scene *s, pp_body *bodies)
{
    for (int i = 0; i < s->count; i++) {
        const stab_body *b = &s->bodies[i];
        pp_body_def d = pp_body_def_default();
        uint8_t *mask = stab_body_mask(b, &d.width, &d.height, &d.pivot);
        if (!mask) {
            fprintf(stderr, "bench_stability: out of memory for a mask\n");
            return -1;
        }
        d.type = b->is_static ? PP_BODY_STATIC : PP_BODY_DYNAMIC;
        d.position = (pp_vec2){(float)b->x, (float)b->y};
        d.angle = (float)b->angle;
        d.custom_pivot = 1;
        d.mask = mask;
        d.density = (float)b->density;
        d.friction = (float)b->friction;
        d.restitution = (float)b->restitution;
        d.linear_velocity = (pp_vec2){(float)b->vel_x, (float)b->vel_y};
        /* `bullet` stays off: `continuous` (on in every preset) already sweeps fast bodies against walls. */
        const int rc = check(pp_body_create(w, &d, &bodies[i]), "pp_body_create");
        free(mask);
        if (rc != 0)
            return -1;
    }
    return 0;
}

/* One PhysPix world of a scene. */
typedef struct px_world {
    pp_world w;
    pp_body *bodies;
} px_world;

static void px_destroy(void *p)
{
    px_world *pw = p;
    if (pw->w.id)
        (void)check(pp_world_destroy(pw->w), "pp_world_destroy");
    free(pw->bodies);
    free(pw);
}

static void *px_create(const stab_engine *e, const stab_scene *s)
{
    px_world *pw = calloc(1, sizeof *pw);
    if (!pw)
        return NULL;
    pp_world_def def = e->world_def;
    def.gravity = (pp_vec2){0.0f, (float)STAB_GRAVITY};
    pw->bodies = calloc((size_t)s->count, sizeof *pw->bodies);
    if (!pw->bodies || check(pp_world_create(&def, &pw->w), "pp_world_create") != 0 ||
        stab_physpix_add_bodies(pw->w, s, pw->bodies) != 0) {
        px_destroy(pw);
        return NULL;
    }
    return pw;
}

static int px_step(void *p)
{
    return check(pp_world_step(((px_world *)p)->w, (float)STAB_DT), "pp_world_step");
}

static void px_pose(void *p, int i, stab_pose *out)
{
    px_world *pw = p;
    pp_vec2 pos = {NAN, NAN};
    float angle = NAN;
    (void)check(pp_body_get_position(pw->w, pw->bodies[i], &pos), "pp_body_get_position");
    (void)check(pp_body_get_angle(pw->w, pw->bodies[i], &angle), "pp_body_get_angle");
    *out = (stab_pose){pos.x, pos.y, angle};
}

static void px_mass(void *p, int i, double *m, double *inertia)
{
    px_world *pw = p;
    float mass = NAN, in = NAN;
    (void)check(pp_body_get_mass(pw->w, pw->bodies[i], &mass, NULL, &in), "pp_body_get_mass");
    *m = mass, *inertia = in;
}

stab_engine stab_engine_physpix_def(const char *name, const pp_world_def *def)
{
    stab_engine e = {.create = px_create, .step = px_step, .pose = px_pose, .mass = px_mass, .destroy = px_destroy};
    snprintf(e.name, sizeof e.name, "%s", name);
    e.world_def = *def;
    e.iterations = def->solver_iterations;
    return e;
}

stab_engine stab_engine_physpix(pp_preset preset)
{
    pp_world_def def = pp_world_def_preset(preset);
    def.allow_sleep = 0; /* the solver alone must hold the stacks */
    const char *name = preset == PP_PRESET_FAST       ? "PhysPix FAST"
                       : preset == PP_PRESET_ACCURATE ? "PhysPix ACCURATE"
                                                      : "PhysPix BALANCED";
    return stab_engine_physpix_def(name, &def);
}
