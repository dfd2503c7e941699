/* The step transaction: what pp_world_step saves before it changes anything, and how a failed step puts it
 * back. Bodies are saved once a step, on first change; the pair lists are swapped back, not copied. */
#include "alloc.h"
#include "awake.h"
#include "check.h"
#include "joint.h"
#include "status.h"
#include "step_undo.h"
#include "world.h"

#include <string.h>

#ifdef PP_CHECKS
static uint64_t mix(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++)
        h = (h ^ b[i]) * 0x100000001b3ull;
    return h;
}
#define MIX(h, v) ((h) = mix((h), &(v), sizeof(v)))

/* FNV-1a over what a step saves: each body's pose, bounds, sleep clock and ODE state, the contacts, the
 * touching and resting pairs, the events queued, the stats and the solver's step count. */
static uint64_t fingerprint(const world *wd)
{
    uint64_t h = 0xcbf29ce484222325ull;
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
    for (int32_t k = 0; k < wd->touch.count; k++)
        MIX(h, wd->touch.pairs[k].a), MIX(h, wd->touch.pairs[k].b);
    for (int32_t k = 0; k < wd->touch.resting_count; k++)
        MIX(h, wd->touch.resting[k].a), MIX(h, wd->touch.resting[k].b);
    const uint64_t steps = solver_get_steps(wd->solver);
    MIX(h, wd->contact_count), MIX(h, wd->touch.count), MIX(h, wd->touch.resting_count), MIX(h, wd->events.count);
    MIX(h, wd->stats.pairs), MIX(h, wd->stats.contacts), MIX(h, steps);
    return h;
}
#endif

/* Save a movable body's part of the step, once a step. */
static void save_body(step_undo *u, const body *bd)
{
    PP_ASSERT(bd->index < (uint32_t)u->body_capacity);
    step_saved_body *sv = &u->bodies[bd->index];
    if (!bd->sb.body || sv->step == u->step)
        return;
    sv->step = u->step;
    solver_body_save(&bd->sb, &sv->ode);
    sv->pos = bd->pos, sv->angle = bd->angle, sv->cos_a = bd->cos_a, sv->sin_a = bd->sin_a;
    sv->slow_time = bd->slow_time, sv->aabb = bd->aabb;
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
    if (!ARRAY_RESERVE(u->contacts, u->contact_capacity, wd->contact_count))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to start a step of %d bodies",
                       (int)wd->body_ids.live);
    u->step++;
    for (int32_t k = 0; k < wd->awake.count; k++) {
        const body *bd = wd->bodies[wd->awake.slots[k]];
        if (awake_mover(bd))
            save_body(u, bd);
    }
    if (wd->contact_count > 0)
        memcpy(u->contacts, wd->contacts, (size_t)wd->contact_count * sizeof *u->contacts);
    u->contact_count = wd->contact_count;
    u->touch_saved = u->resting_saved = false; /* saved by touch_end before it first changes them */
    u->event_count = wd->events.count;
    u->stats = wd->stats;
    u->solver_steps = solver_get_steps(wd->solver);
#ifdef PP_CHECKS
    u->fingerprint = fingerprint(wd);
#endif
    return carry_save(wd);
}

pp_status step_save_touching(world *wd, bool resting)
{
    step_undo *u = &wd->undo;
    bool *saved = resting ? &u->resting_saved : &u->touch_saved;
    touch **copy = resting ? &u->resting : &u->touching;
    int32_t *copy_count = resting ? &u->resting_count : &u->touch_count;
    int32_t *copy_cap = resting ? &u->resting_capacity : &u->touch_capacity;
    const touch *list = resting ? wd->touch.resting : wd->touch.pairs;
    const int32_t n = resting ? wd->touch.resting_count : wd->touch.count;
    if (*saved)
        return PP_OK;
    if (!ARRAY_RESERVE(*copy, *copy_cap, n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_step: no memory to save %d touching pairs", (int)n);
    if (n > 0)
        memcpy(*copy, list, (size_t)n * sizeof **copy);
    *copy_count = n;
    *saved = true;
    return PP_OK;
}

void step_save_contact_bodies(world *wd)
{
    for (int32_t k = 0; k < wd->contact_count; k++) {
        save_body(&wd->undo, body_of(wd, wd->contacts[k].a));
        save_body(&wd->undo, body_of(wd, wd->contacts[k].b));
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
    PP_ASSERT(u->body_capacity >= wd->body_ids.capacity && u->contact_count <= wd->contact_capacity &&
              u->event_count <= wd->events.count);
    for (int32_t i = 0; i < wd->body_ids.capacity; i++) {
        body *bd = wd->bodies[i];
        const step_saved_body *sv = &u->bodies[i];
        if (!bd || sv->step != u->step)
            continue;
        solver_body_restore(&bd->sb, &sv->ode);
        bd->pos = sv->pos, bd->angle = sv->angle, bd->cos_a = sv->cos_a, bd->sin_a = sv->sin_a;
        bd->slow_time = sv->slow_time, bd->aabb = sv->aabb;
    }
    if (u->contact_count > 0)
        memcpy(wd->contacts, u->contacts, (size_t)u->contact_count * sizeof *wd->contacts);
    wd->contact_count = u->contact_count;
    wd->stats = u->stats;
    solver_set_steps(wd->solver, u->solver_steps);
    /* The saved pairs become the world's, its buffer the next save's: nothing to allocate. */
    if (u->touch_saved) {
        touch *list = wd->touch.pairs;
        const int32_t cap = wd->touch.capacity;
        wd->touch.pairs = u->touching, wd->touch.count = u->touch_count, wd->touch.capacity = u->touch_capacity;
        u->touching = list, u->touch_capacity = cap;
    }
    if (u->resting_saved) {
        touch *list = wd->touch.resting;
        const int32_t cap = wd->touch.resting_capacity;
        wd->touch.resting = u->resting, wd->touch.resting_count = u->resting_count;
        wd->touch.resting_capacity = u->resting_capacity;
        u->resting = list, u->resting_capacity = cap;
    }
    wd->events.count = u->event_count;
    carry_restore(wd);
    awake_rebuild(wd); /* poses and sleep came back behind the set's back */
    PP_ASSERT(fingerprint(wd) == u->fingerprint);
}

void step_undo_free(step_undo *u)
{
    pp_free(u->bodies);
    pp_free(u->contacts);
    pp_free(u->touching);
    pp_free(u->resting);
    *u = (step_undo){0};
}
