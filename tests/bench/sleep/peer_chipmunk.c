/* The Chipmunk 7 peer of bench_sleep: the same crates, platform and boxes in PhysPix's frame (px, y down),
 * at its default 10 iterations, sleeping after PhysPix's 0.5 s under 5 px/s. */
#include "peer.h"

#include <chipmunk/chipmunk.h>

#include <stdlib.h>
#include <time.h>

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* A box body and its shape, kept in the lists for freeing; returns the body. */
static cpBody *add_box(cpSpace *space, cpBody **bodies, cpShape **shapes, int *n, int dynamic, double w, double h,
                       double x, double y)
{
    cpBody *b = dynamic ? cpBodyNew(w * h, cpMomentForBox(w * h, w, h)) : cpBodyNewStatic();
    cpBodySetPosition(b, cpv(x, y));
    if (dynamic)
        cpSpaceAddBody(space, b);
    cpShape *sh = cpSpaceAddShape(space, cpBoxShapeNew(b, w, h, 0));
    cpShapeSetFriction(sh, 0.7746); /* sqrt(0.6): Chipmunk multiplies the two */
    bodies[*n] = b, shapes[*n] = sh, ++*n;
    return b;
}

static int awake_count(cpBody *const *bodies, int n)
{
    int awake = 0;
    for (int i = 0; i < n; i++)
        awake += cpBodyGetType(bodies[i]) == CP_BODY_TYPE_DYNAMIC && !cpBodyIsSleeping(bodies[i]);
    return awake;
}

double sleep_chipmunk_ms(const sleep_scene *s, int blocks, int *awake)
{
    const int cap = s->crates + s->movers + 2;
    cpBody **bodies = malloc((size_t)cap * sizeof *bodies);
    cpShape **shapes = malloc((size_t)cap * sizeof *shapes);
    double *ms = malloc((size_t)blocks * sizeof *ms);
    if (!bodies || !shapes || !ms) {
        free(bodies), free(shapes), free(ms);
        return -1;
    }
    cpSpace *space = cpSpaceNew();
    cpSpaceSetGravity(space, cpv(0, 980));
    cpSpaceSetSleepTimeThreshold(space, 0.5);
    cpSpaceSetIdleSpeedThreshold(space, 5.0);
    const double dt = 1.0 / 60.0;
    int n = 0;
    if (s->crates > 0) {
        add_box(space, bodies, shapes, &n, 0, s->floor_w, s->floor_h, 0.5 * s->floor_w, s->floor_top + 0.5 * s->floor_h);
        const int cols = (s->crates + s->stack - 1) / s->stack;
        for (int i = 0; i < s->crates; i++)
            add_box(space, bodies, shapes, &n, 1, s->crate, s->crate,
                    0.5 * s->floor_w + (i / s->stack - (cols - 1) * 0.5) * s->pitch,
                    s->floor_top - 0.5 * s->crate - (i % s->stack) * s->crate);
        for (int k = 0; k < 600 && (k == 0 || awake_count(bodies, n) > 0); k++)
            cpSpaceStep(space, dt);
    }
    const int first_mover = n + (s->movers > 0);
    if (s->movers > 0) {
        add_box(space, bodies, shapes, &n, 0, 400, 16, 300, s->platform_top + 8);
        for (int i = 0; i < s->movers; i++)
            add_box(space, bodies, shapes, &n, 1, 16, 16, 150 + 40.0 * i, s->platform_top - 60);
    }
    int step = 0;
    for (int b = 0; b < blocks; b++) {
        double spent = 0;
        for (int k = 0; k < s->block; k++, step++) {
            if (step % 30 == 0)
                for (int i = first_mover; i < n; i++) {
                    cpBodyActivate(bodies[i]);
                    cpBodySetVelocity(bodies[i], cpv(0, -300));
                }
            const double t0 = now_ms();
            cpSpaceStep(space, dt);
            spent += now_ms() - t0;
        }
        ms[b] = spent / s->block;
    }
    qsort(ms, (size_t)blocks, sizeof *ms, cmp_double);
    const double median = ms[blocks / 2];
    *awake = awake_count(bodies, n);
    for (int i = 0; i < n; i++) {
        cpSpaceRemoveShape(space, shapes[i]);
        cpShapeFree(shapes[i]);
        if (cpBodyGetType(bodies[i]) == CP_BODY_TYPE_DYNAMIC)
            cpSpaceRemoveBody(space, bodies[i]);
        cpBodyFree(bodies[i]);
    }
    cpSpaceFree(space);
    free(bodies), free(shapes), free(ms);
    return median;
}
