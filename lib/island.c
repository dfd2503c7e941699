/* ODE steps one method per world, so the islands are chosen here and solver_step hides the others
 * while each method runs. An island is what ODE's own walk will find: bodies with ODE bodies (dynamic
 * or kinematic) joined by contacts; static bodies join nothing. The exact solver takes an island of two
 * or more dynamic bodies (where QuickStep's unfinished solve lets stacks sag, creep and crush light
 * bodies) up to exact_island_rows; a lone body is QuickStep's either way, as it always was. */
#include "island.h"

/* Constraint rows a contact costs: the normal and one in-plane friction row. */
enum { ROWS_PER_CONTACT = 2, ROWS_PER_FIXED_ROTATION = 4 };

static bool within_reach(const world *wd, const body *bd)
{
    solver_body_state s;
    solver_body_get_state(wd->solver, &bd->sb, &s);
    const double reach = 1.0 + (double)bd->raster.width + (double)bd->raster.height;
    return dv_norm(dv_sub(s.com_world, body_com_world(bd))) <= reach;
}

pp_status island_plan(world *wd, solver_islands *out)
{
    *out = (solver_islands){0};
    if (wd->body_capacity == 0)
        return PP_OK;
    pp_status st = world_slot_array(wd, (void **)&wd->group, &wd->group_capacity, 2 * sizeof *wd->group,
                                    "the islands");
    if (st || (st = world_slot_array(wd, (void **)&wd->island_bodies, &wd->island_capacity,
                                     sizeof *wd->island_bodies, "the islands")) ||
        (st = world_slot_array(wd, (void **)&wd->island_kind, &wd->island_kind_capacity, 1, "the islands")))
        return st;
    /* Per root: the island's rows (the group array's second half) and its dynamic bodies. */
    int32_t *parent = wd->group, *rows = wd->group + wd->group_capacity;
    int32_t *dynamic = (int32_t *)wd->island_bodies; /* scratch until the lists are written */
    PP_ASSERT(sizeof *wd->island_bodies >= sizeof *dynamic);
    for (int32_t i = 0; i < wd->body_capacity; i++) {
        const body *bd = wd->bodies[i];
        parent[i] = i;
        rows[i] = bd && bd->fixed_rotation ? ROWS_PER_FIXED_ROTATION : 0;
        dynamic[i] = bd && bd->type == PP_BODY_DYNAMIC;
    }
    for (int32_t k = 0; k < wd->contact_count; k++) {
        const body *a = body_of(wd, wd->contacts[k].a), *b = body_of(wd, wd->contacts[k].b);
        int32_t ra = a->sb.body ? world_group_root(parent, (int32_t)a->index) : -1;
        int32_t rb = b->sb.body ? world_group_root(parent, (int32_t)b->index) : -1;
        if (ra >= 0 && rb >= 0 && ra != rb) {
            parent[ra] = rb;
            rows[rb] += rows[ra];
            dynamic[rb] += dynamic[ra];
        }
        rows[rb >= 0 ? rb : ra] += ROWS_PER_CONTACT;
    }
    /* An island with a body whose ODE centre of mass is far outside its bitmap (a snapshot can hold one,
     * fuzz_snapshot: 9e17 m) stays on QuickStep: the exact solver's lever arms would end in NaN and ODE's
     * abort in dNormalize4, where QuickStep's non-finite result is caught and the step undone. */
    for (int32_t i = 0; i < wd->body_capacity; i++)
        if (wd->bodies[i] && wd->bodies[i]->sb.body && !within_reach(wd, wd->bodies[i]))
            dynamic[world_group_root(parent, i)] = INT32_MIN / 2;
    for (int32_t i = 0; i < wd->body_capacity; i++) {
        const int32_t r = world_group_root(parent, i);
        wd->island_kind[i] = !wd->bodies[i] || !wd->bodies[i]->sb.body ? ISLAND_NONE
                             : dynamic[r] < 2                         ? ISLAND_QUICK_ALONE
                             : ISLAND_QUICK_STACK;
    }
    /* An island is stepped if any of its bodies is awake (ODE wakes the rest); mark those roots. */
    for (int32_t i = 0; i < wd->body_capacity; i++) {
        const body *bd = wd->bodies[i];
        if (bd && bd->sb.body && solver_body_is_awake(&bd->sb))
            rows[world_group_root(parent, i)] |= INT32_MIN;
    }
    /* Exact islands fill the array from the front, QuickStep's awake bodies from the back. */
    const int32_t limit = wd->def.exact_island_rows;
    solver_body **list = wd->island_bodies;
    int32_t n_exact = 0, n_quick = 0;
    for (int32_t i = 0; i < wd->body_capacity; i++) {
        body *bd = wd->bodies[i];
        if (!bd || !bd->sb.body)
            continue;
        const int32_t r = rows[world_group_root(parent, i)];
        if (r >= 0)
            continue; /* asleep */
        if (wd->def.exact_solver || (wd->island_kind[i] == ISLAND_QUICK_STACK && (r & INT32_MAX) <= limit)) {
            wd->island_kind[i] = ISLAND_EXACT;
            list[n_exact++] = &bd->sb;
        }
        else if (solver_body_is_awake(&bd->sb))
            list[wd->body_capacity - 1 - n_quick++] = &bd->sb;
    }
    *out = (solver_islands){list, n_exact, list + wd->body_capacity - n_quick, n_quick};
    return PP_OK;
}
