/* Queries that read the world without stepping it: the narrowphase on one chosen pair. */
#include "status.h"
#include "world.h"

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
    if (np_pair_setup(&set, &va, &vb, &wd->pairs[0])) {
        pp_backend ran;
        if ((st = world_run_cores(wd, fn, 1, np_pair_cells(&wd->pairs[0]), &ran)))
            return st;
        np_pair_finish(&set, &va, &vb, &wd->pairs[0], &wd->cores[0], &r);
    }
    for (int32_t k = 0; k < r.count && k < capacity; k++) {
        out[k] = r.contacts[k];
        out[k].a = a;
        out[k].b = b;
    }
    *count = r.count;
    return PP_OK;
}
