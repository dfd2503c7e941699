/* The Chipmunk 7 peer: Chipmunk has no units or up, so it takes PhysPix's frame as it is (px, y down, the
 * same angle sense). It mixes materials by product where PhysPix uses sqrt(fa·fb) and max(ea, eb): each
 * shape gets sqrt of its friction, and static shapes elasticity 1 with dynamic ones their own, so a
 * body–ground pair gets the body's restitution (no scene bounces two dynamic bodies). No CCD, no sleep. */
#include "peers.h"

#include <chipmunk/chipmunk.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* A Chipmunk space of a scene: one body and one shape per scene body. */
typedef struct cp_scene {
    cpSpace *space;
    cpBody **bodies;
    cpShape **shapes;
    int count;
} cp_scene;

/* Area of a polygon, px² (either winding). */
static double poly_area(const stab_body *b)
{
    double a = 0;
    for (int i = 0; i < b->nverts; i++) {
        const int j = (i + 1) % b->nverts;
        a += b->vx[i] * b->vy[j] - b->vx[j] * b->vy[i];
    }
    return fabs(0.5 * a);
}

/* Mass = density × area and the inertia of the analytic shape about its centre. */
static void shape_mass(const stab_body *b, double *m, double *inertia, cpVect *verts)
{
    if (b->shape == STAB_DISC) {
        *m = b->density * CP_PI * b->radius * b->radius;
        *inertia = cpMomentForCircle(*m, 0, b->radius, cpvzero);
    } else if (b->shape == STAB_BOX) {
        *m = b->density * b->w * b->h;
        *inertia = cpMomentForBox(*m, b->w, b->h);
    } else {
        *m = b->density * poly_area(b);
        *inertia = cpMomentForPoly(*m, b->nverts, verts, cpvzero, 0); /* about the origin, the centroid */
    }
}

static cpShape *make_shape(cpBody *body, const stab_body *b, const cpVect *verts)
{
    if (b->shape == STAB_DISC)
        return cpCircleShapeNew(body, b->radius, cpvzero);
    if (b->shape == STAB_BOX)
        return cpBoxShapeNew(body, b->w, b->h, 0);
    return cpPolyShapeNew(body, b->nverts, verts, cpTransformIdentity, 0);
}

static void destroy(void *p)
{
    cp_scene *w = p;
    for (int i = 0; i < w->count; i++) {
        cpSpaceRemoveShape(w->space, w->shapes[i]);
        cpShapeFree(w->shapes[i]);
        cpSpaceRemoveBody(w->space, w->bodies[i]);
        cpBodyFree(w->bodies[i]);
    }
    cpSpaceFree(w->space);
    free(w->bodies);
    free(w->shapes);
    free(w);
}

/* Pose first, then the shape: a static body's shapes are indexed where they are added. */
static void add_body(cp_scene *w, const stab_body *b)
{
    cpVect verts[STAB_MAX_VERTS];
    for (int i = 0; i < b->nverts; i++)
        verts[i] = cpv(b->vx[i], b->vy[i]);
    double m, inertia;
    shape_mass(b, &m, &inertia, verts);
    cpBody *body = b->is_static ? cpBodyNewStatic() : cpBodyNew(m, inertia);
    cpBodySetPosition(body, cpv(b->x, b->y));
    cpBodySetAngle(body, b->angle);
    if (!b->is_static)
        cpBodySetVelocity(body, cpv(b->vel_x, b->vel_y));
    cpSpaceAddBody(w->space, body);
    cpShape *shape = make_shape(body, b, verts);
    cpShapeSetFriction(shape, sqrt(b->friction));
    cpShapeSetElasticity(shape, b->is_static ? 1.0 : b->restitution);
    cpSpaceAddShape(w->space, shape);
    w->bodies[w->count] = body;
    w->shapes[w->count++] = shape;
}

static void *create(const stab_engine *e, const stab_scene *s)
{
    cp_scene *w = calloc(1, sizeof *w);
    if (!w)
        return NULL;
    w->space = cpSpaceNew();
    w->bodies = calloc((size_t)s->count, sizeof *w->bodies);
    w->shapes = calloc((size_t)s->count, sizeof *w->shapes);
    if (!w->bodies || !w->shapes) {
        fprintf(stderr, "bench_stability: out of memory for a Chipmunk space\n");
        destroy(w);
        return NULL;
    }
    cpSpaceSetGravity(w->space, cpv(0, STAB_GRAVITY));
    cpSpaceSetIterations(w->space, e->iterations);
    for (int i = 0; i < s->count; i++)
        add_body(w, &s->bodies[i]);
    return w;
}

static int step(void *p)
{
    cpSpaceStep(((cp_scene *)p)->space, STAB_DT);
    return 0;
}

static void pose(void *p, int i, stab_pose *out)
{
    const cpBody *b = ((cp_scene *)p)->bodies[i];
    const cpVect v = cpBodyGetPosition(b);
    *out = (stab_pose){v.x, v.y, cpBodyGetAngle(b)};
}

static void mass(void *p, int i, double *m, double *inertia)
{
    const cpBody *b = ((cp_scene *)p)->bodies[i];
    *m = cpBodyGetMass(b);
    *inertia = cpBodyGetMoment(b);
}

stab_engine stab_engine_chipmunk(int iterations)
{
    stab_engine e = {.create = create, .step = step, .pose = pose, .mass = mass, .destroy = destroy};
    snprintf(e.name, sizeof e.name, "Chipmunk %d it%d", CP_VERSION_MAJOR, iterations);
    e.iterations = iterations;
    return e;
}

const char *stab_chipmunk_version(void)
{
    /* Debian's Chipmunk is a debug build that prints a banner on its first space: let it come out here,
     * before the table, and not inside it. */
    cpSpaceFree(cpSpaceNew());
    return cpVersionString;
}
