/* The scene run with PhysPix raster bodies, through the public API only: each box is a
 * solid mask of its size (a terrain's top rows empty); after the untimed settling steps,
 * every pp_world_step is timed on its own. */
#include "bench.h"
#include "physpix.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int check(pp_status st, const char *what)
{
    if (st == PP_OK)
        return 0;
    fprintf(stderr, "bench: %s failed: %s: %s\n", what, pp_status_name(st), pp_last_error());
    return -1;
}

/* One all-solid mask large enough for every box of the scene, shared by the defs
 * (the library copies the planes, and reads only width × height of it). */
static uint8_t *solid_mask_for(const bench_scene *scene)
{
    size_t largest = 1;
    for (int i = 0; i < scene->count; i++) {
        size_t area = (size_t)scene->boxes[i].w * (size_t)scene->boxes[i].h;
        if (area > largest)
            largest = area;
    }
    uint8_t *mask = malloc(largest);
    if (mask)
        memset(mask, 1, largest);
    return mask;
}

static int create_bodies(pp_world w, const bench_scene *scene, const bench_settings *set, pp_body *bodies)
{
    uint8_t *mask = solid_mask_for(scene);
    if (!mask) {
        fprintf(stderr, "bench: out of memory for the masks\n");
        return -1;
    }
    int rc = 0;
    for (int i = 0; i < scene->count && rc == 0; i++) {
        const bench_box *box = &scene->boxes[i];
        pp_body_def def = pp_body_def_default();
        def.type = box->is_static ? PP_BODY_STATIC : PP_BODY_DYNAMIC;
        def.position = (pp_vec2){(float)box->x, (float)box->y};
        def.angle = (float)box->angle;
        def.width = box->w;
        def.height = box->h;
        def.mask = mask;
        def.density = (float)set->density;
        def.friction = (float)set->friction;
        def.restitution = (float)set->restitution;
        def.user_data = (uint64_t)i;
        /* A terrain's sky: clear its top rows for this body only, then make them solid again. */
        size_t sky = (size_t)box->empty_top * (size_t)box->w;
        memset(mask, 0, sky);
        rc = check(pp_body_create(w, &def, &bodies[i]), "pp_body_create");
        memset(mask, 1, sky);
    }
    free(mask);
    return rc;
}

/* Untimed steps until the scene's settle count, or until nothing is awake when it asks. */
static int settle(pp_world w, const bench_scene *scene, const bench_settings *set, int *settled)
{
    pp_step_stats stats = {0};
    *settled = 0;
    while (*settled < scene->settle_steps) {
        if (check(pp_world_step(w, (float)set->dt), "pp_world_step") != 0 ||
            check(pp_world_get_stats(w, &stats), "pp_world_get_stats") != 0)
            return -1;
        ++*settled;
        if (scene->settle_to_sleep && stats.awake_bodies == 0)
            break;
    }
    return 0;
}

int bench_run_physpix(const bench_scene *scene, const bench_settings *set, bench_run *out)
{
    pp_world_def wdef = pp_world_def_default();
    wdef.allow_sleep = set->allow_sleep != 0; /* the one world knob the benches vary */
    pp_world w = {0};
    if (check(pp_world_create(&wdef, &w), "pp_world_create") != 0)
        return -1;

    pp_body *bodies = calloc((size_t)scene->count, sizeof *bodies);
    int rc = bodies ? create_bodies(w, scene, set, bodies) : -1;
    if (!bodies)
        fprintf(stderr, "bench: out of memory for the body handles\n");
    if (rc == 0)
        rc = settle(w, scene, set, &out->settled);

    double contacts = 0.0, pairs = 0.0, phase[3] = {0.0, 0.0, 0.0};
    pp_step_stats stats = {0};
    out->awake_max = 0;
    for (int s = 0; s < scene->steps && rc == 0; s++) {
        double t0 = bench_now_ms();
        pp_status st = pp_world_step(w, (float)set->dt);
        out->step_ms[s] = bench_now_ms() - t0;
        rc = check(st, "pp_world_step");
        if (rc == 0)
            rc = check(pp_world_get_stats(w, &stats), "pp_world_get_stats");
        contacts += stats.contacts;
        pairs += stats.pairs;
        phase[0] += stats.broadphase_ms;
        phase[1] += stats.narrowphase_ms;
        if (out->narrow_ms)
            out->narrow_ms[s] = stats.narrowphase_ms;
        phase[2] += stats.solver_ms;
        if (stats.awake_bodies > out->awake_max)
            out->awake_max = stats.awake_bodies;
    }

    if (rc == 0) {
        for (int k = 0; k < 3; k++)
            out->phase_ms[k] = phase[k] / scene->steps;
        out->contacts_mean = contacts / scene->steps;
        out->pairs_mean = pairs / scene->steps;
        out->awake_end = stats.awake_bodies;
        out->backend = (int)stats.backend;
        out->tracked_drop = 0.0;
        out->lost = 0;
        for (int i = 0; i < scene->count && rc == 0; i++) {
            if (scene->boxes[i].is_static)
                continue;
            pp_vec2 p;
            rc = check(pp_body_get_position(w, bodies[i], &p), "pp_body_get_position");
            out->lost += p.y > scene->ground_top;
            if (i == scene->tracked)
                out->tracked_drop = p.y - scene->boxes[i].y;
        }
    }

    free(bodies);
    if (check(pp_world_destroy(w), "pp_world_destroy") != 0)
        rc = -1;
    return rc;
}
