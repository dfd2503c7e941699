/* Queries that read the world without stepping it: the narrowphase on one chosen pair, and its
 * sampled grid for debug views. */
#include "alloc.h"
#include "status.h"
#include "world.h"

#include <stdlib.h>

PP_API pp_status pp_world_collide(pp_world w, pp_body a, pp_body b, pp_contact *out, int32_t capacity,
                                  int32_t *count)
{
    static const char *fn = "pp_world_collide";
    world *wd = world_lookup(w, fn);
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    const body *ba = body_lookup(wd, a, fn);
    if (!ba)
        return PP_ERR_INVALID_HANDLE;
    const body *bb = body_lookup(wd, b, fn);
    if (!bb)
        return PP_ERR_INVALID_HANDLE;
    pp_status st = pp_check_out_buffer(fn, out, capacity, count);
    if (st)
        return st;
    if (a.id == b.id)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: a and b are the same body", fn);
    /* The pair runs on the world's backend, so a query sees what a step would. */
    const np_settings set = world_np_settings(wd);
    const np_body va = body_np_view(ba), vb = body_np_view(bb);
    np_result r = {0};
    if ((st = world_reserve_pairs(wd, fn, 1)))
        return st;
    if (np_pair_setup(&set, &va, &vb, &wd->batch.pairs[0])) {
        pp_backend ran;
        int32_t threads;
        if ((st = world_run_cores(wd, fn, 0, 1, np_pair_cells(&wd->batch.pairs[0]), &ran, &threads)))
            return st;
        np_pair_finish(&set, &va, &vb, &wd->batch.pairs[0], &wd->batch.cores[0], &r);
    }
    for (int32_t k = 0; k < r.count && k < capacity; k++) {
        out[k] = r.contacts[k];
        out[k].a = a;
        out[k].b = b;
    }
    *count = r.count;
    return PP_OK;
}

/* Fill the view's geometry: the reference's grid mapped to the world, the normal from a to b. */
static void debug_view_of(const np_pair *p, const np_body *ref, const np_result *r, pp_collision_view *v)
{
    const dvec2 o = dv_add(ref->pos, dv_rot(dv_sub(np_grid_to_local(p, 0, 0), ref->pivot), ref->c, ref->s));
    const dvec2 sx = dv_rot(dv(p->s, 0), ref->c, ref->s), sy = dv_rot(dv(0, p->s), ref->c, ref->s);
    v->width = p->nx, v->height = p->ny;
    v->origin = (pp_vec2){(float)o.x, (float)o.y};
    v->step_x = (pp_vec2){(float)sx.x, (float)sx.y};
    v->step_y = (pp_vec2){(float)sy.x, (float)sy.y};
    v->normal = r->count ? r->contacts[0].normal : (pp_vec2){0, 0};
}

PP_API pp_status pp_world_debug_collision(pp_world w, pp_body a, pp_body b, uint8_t *cells, pp_vec2 *local_normals,
                                          int64_t capacity, pp_collision_view *view)
{
    static const char *fn = "pp_world_debug_collision";
    world *wd;
    body *ba, *bb;
    pp_status st = world_body_lookup(w, a, fn, &wd, &ba);
    if (st)
        return st;
    if (!(bb = body_lookup(wd, b, fn)))
        return PP_ERR_INVALID_HANDLE;
    if (!view || capacity < 0 || (capacity > 0 && !cells))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: view or cells is NULL, or capacity is negative", fn);
    if (a.id == b.id)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: a and b are the same body", fn);
    *view = (pp_collision_view){0};
    const np_settings set = world_np_settings(wd);
    const np_body va = body_np_view(ba), vb = body_np_view(bb);
    np_pair p;
    np_core core;
    np_result r = {0};
    if (!np_pair_setup(&set, &va, &vb, &p))
        return PP_OK; /* the boxes do not overlap: an empty grid */
    if ((st = narrow_cpu_core(&set, &p, &wd->scratch, &core)))
        return st;
    np_pair_finish(&set, &va, &vb, &p, &core, &r);
    debug_view_of(&p, p.swap ? &vb : &va, &r, view);
    const int64_t n = (int64_t)p.nx * p.ny;
    if (capacity < n)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: the grid has %lld cells, capacity is %lld", fn, (long long)n,
                       (long long)capacity);
    int32_t *kernel = pp_malloc((size_t)n * 2 * sizeof *kernel);
    if (!kernel)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %lld cells", fn, (long long)n);
    if ((st = narrow_cpu_debug(&p, &wd->scratch, cells, kernel)) == PP_OK) {
        /* Flags and kernels are the reference's: turn them into a's and b's, in world axes. */
        const np_body *ref = p.swap ? &vb : &va;
        const double sign = p.swap ? -1.0 : 1.0;
        for (int64_t k = 0; k < n; k++) {
            const uint8_t f = cells[k];
            cells[k] = p.swap ? (uint8_t)((f & 4) | (f & 1) << 1 | (f & 2) >> 1) : f;
            view->intersection += (f & 3) == 3;
            view->critical += (f & 4) != 0;
            if (local_normals) {
                dvec2 g = dv(kernel[2 * k], kernel[2 * k + 1]);
                const double len = sqrt(dv_dot(g, g));
                g = len > 0 ? dv_scale(dv_rot(g, ref->c, ref->s), sign / len) : dv(0, 0);
                local_normals[k] = (pp_vec2){(float)g.x, (float)g.y};
            }
        }
    }
    pp_free(kernel);
    return st;
}
