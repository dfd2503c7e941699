/* The step transaction: what pp_world_step saves before it changes anything, and how a failed step puts it
 * back. Bodies are saved once a step, on first change; the contact table logs its own changes. */
#include "alloc.h"
#include "awake.h"
#include "check.h"
#include "hash.h"
#include "joint.h"
#include "status.h"
#include "step_undo.h"
#include "world.h"

#include <string.h>

#ifdef PP_CHECKS
#define MIX HASH_VALUE

/* hash.h's hash over what a step saves: each body's pose, bounds, sleep clock and ODE state, the contacts, the
 * contact table's pairs, the events queued, the stats and the solver's step count. */
static uint64_t fingerprint(const world *wd)
{
    uint64_t h = HASH_START;
    for (int32_t i = 0; i < wd->body_ids.capacity; i++) {
        const body *bd = wd->bodies[i];
        if (!bd)
            continue;
        MIX(h, bd->pos), MIX(h, bd->angle), MIX(h, bd->slow_time), MIX(h, bd->aabb);
        if (!bd->sb.body)
            continue;
        solver_body_state s;
        solver_body_get_state(wd->solver, &bd->sb, &s);
        MIX(h, s.com_world), MIX(h, s.angle), MIX(h, s.velocity), MIX(h, s.angular_velocity), MIX(h, s.awake);
    }
    for (int32_t k = 0; k < wd->contact_count; k++) {
        const pp_contact *c = &wd->contacts[k];
        MIX(h, c->a.id), MIX(h, c->b.id), MIX(h, c->point), MIX(h, c->normal), MIX(h, c->depth);
    }
    for (int32_t k = 0; k < wd->table.count; k++)
        MIX(h, wd->table.records[k]);
    for (int32_t k = 0; k < wd->table.carry_count; k++)
        MIX(h, wd->table.carry_order[k]);
    const uint64_t steps = solver_get_steps(wd->solver);
    MIX(h, wd->contact_count), MIX(h, wd->table.count), MIX(h, wd->table.awake), MIX(h, wd->events.count);
    MIX(h, wd->stats.pairs), MIX(h, wd->stats.contacts), MIX(h, steps);
    return h;
}
#endif

/* Save a movable body's part of the step (the first time). */
static void save_body_now(step_undo *u, const body *bd, step_saved_body *sv)
{
    sv->step = u->step;
    solver_body_save(&bd->sb, &sv->ode);
    sv->pos = bd->pos, sv->angle = bd->angle, sv->cos_a = bd->cos_a, sv->sin_a = bd->sin_a;
    sv->slow_time = bd->slow_time, sv->aabb = bd->aabb;
}

/* Save a movable body's part of the step, once a step: most calls find it saved. */
static inline void save_body(step_undo *u, const body *bd)
{
    PP_ASSERT(bd->index < (uint32_t)u->body_capacity);
    step_saved_body *sv = &u->bodies[bd->index];
    if (bd->sb.body && sv->step != u->step)
        save_body_now(u, bd, sv);
}

pp_status step_save(world *wd)
{
    step_undo *u = &wd->undo;
    const int32_t saved = u->body_capacity;
    if (!ARRAY_RESERVE(u->bodies, u->body_capacity, wd->body_ids.capacity))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to start a step of %d bodies",
                       (int)wd->body_ids.live);
    if (u->body_capacity > saved) /* step 0: never saved */
        memset(u->bodies + saved, 0, (size_t)(u->body_capacity - saved) * sizeof *u->bodies);
    u->step++;
    for (int32_t k = 0; k < wd->awake.count; k++) {
        const body *bd = wd->bodies[wd->awake.slots[k]];
        if (awake_mover(bd))
            save_body(u, bd);
    }
    u->contact_count = wd->contact_count;
    u->contacts_taken = false;
    u->event_count = wd->events.count;
    u->stats = wd->stats;
    u->solver_steps = solver_get_steps(wd->solver);
#ifdef PP_CHECKS
    u->fingerprint = fingerprint(wd);
#endif
    return contact_table_save(wd);
}

static void swap_contacts(world *wd)
{
    step_undo *u = &wd->undo;
    pp_contact *const array = u->contacts;
    const int32_t capacity = u->contact_capacity;
    u->contacts = wd->contacts, u->contact_capacity = wd->contact_capacity;
    wd->contacts = array, wd->contact_capacity = capacity;
}

void step_take_contacts(world *wd)
{
    if (wd->undo.contacts_taken)
        return;
    PP_ASSERT(wd->contact_count == wd->undo.contact_count);
    swap_contacts(wd);
    wd->undo.contacts_taken = true;
}

void step_save_contact_bodies(world *wd)
{
    for (int32_t n = 0; n < wd->table.run_count; n++) {
        save_body(&wd->undo, wd->bodies[wd->table.runs[n].a]);
        save_body(&wd->undo, wd->bodies[wd->table.runs[n].b]);
    }
    for (int32_t i = 0; wd->joints.ids.live > 0 && i < wd->joints.ids.capacity; i++) {
        const joint *jt = wd->joints.items[i];
        const body *a = jt ? joint_body_a(wd, jt) : NULL, *b = jt ? joint_body_b(wd, jt) : NULL;
        if (a)
            save_body(&wd->undo, a);
        if (b)
            save_body(&wd->undo, b);
    }
}

/* The buffers it restores into are at least as large as when saved. */
void step_restore(world *wd)
{
    step_undo *u = &wd->undo;
    PP_ASSERT(u->body_capacity >= wd->body_ids.capacity && u->event_count <= wd->events.count);
    for (int32_t i = 0; i < wd->body_ids.capacity; i++) {
        body *bd = wd->bodies[i];
        const step_saved_body *sv = &u->bodies[i];
        if (!bd || sv->step != u->step)
            continue;
        solver_body_restore(&bd->sb, &sv->ode);
        bd->pos = sv->pos, bd->angle = sv->angle, bd->cos_a = sv->cos_a, bd->sin_a = sv->sin_a;
        bd->slow_time = sv->slow_time, bd->aabb = sv->aabb;
        body_update_com(bd);
    }
    if (u->contacts_taken) /* else the step wrote none */
        swap_contacts(wd);
    u->contacts_taken = false;
    wd->contact_count = u->contact_count;
    wd->stats = u->stats;
    solver_set_steps(wd->solver, u->solver_steps);
    contact_table_restore(wd);
    wd->events.count = u->event_count;
    wd->carry.active = false;
    awake_rebuild(wd); /* poses and sleep came back behind the set's back */
    contact_table_validate(wd);
    PP_ASSERT(fingerprint(wd) == u->fingerprint);
}

void step_commit(world *wd) { contact_table_commit(wd); }

void step_undo_free(step_undo *u)
{
    pp_free(u->bodies);
    pp_free(u->contacts);
    *u = (step_undo){0};
}
