/* The world's hash (pp_world_get_hash): 64 bits over what the next steps depend on, field by field (no pointer,
 * padding, GPU mirror or stamp of this process), handles without their world's tag, so that two worlds with
 * the same future hash alike in any process and on either backend. */
#include "hash.h"
#include "joint.h"
#include "world.h"

#define MIX HASH_VALUE

static uint64_t saved(uint64_t id)
{
    return handle_saved(id) | (uint64_t)handle_kind_of(id) << 61;
}

static uint64_t mix_contact(uint64_t h, const pp_contact *c)
{
    const uint64_t a = saved(c->a.id), b = saved(c->b.id);
    MIX(h, a), MIX(h, b), MIX(h, c->point), MIX(h, c->normal), MIX(h, c->depth), MIX(h, c->pixel_count);
    return MIX(h, c->normal_impulse);
}

static uint64_t mix_pool(uint64_t h, const id_pool *p)
{
    MIX(h, p->capacity), MIX(h, p->free_count);
    h = hash_bytes(h, p->generations, (size_t)p->capacity * 4);
    return hash_bytes(h, p->free_slots, (size_t)p->free_count * 4);
}

static uint64_t mix_body(uint64_t h, const world *wd, const body *bd)
{
    const uint64_t id = saved(bd->handle.id);
    const uint8_t flags[] = {bd->fixed_rotation, bd->detach_islands, bd->bullet, bd->is_sensor, bd->one_way, bd->forced};
    MIX(h, id), MIX(h, bd->serial), MIX(h, bd->type), MIX(h, bd->pos), MIX(h, bd->angle), MIX(h, bd->pivot);
    MIX(h, bd->mass), MIX(h, bd->density), MIX(h, bd->friction), MIX(h, bd->restitution);
    MIX(h, bd->linear_damping), MIX(h, bd->angular_damping), MIX(h, bd->category_bits), MIX(h, bd->mask_bits);
    MIX(h, flags), MIX(h, bd->one_way_dir), MIX(h, bd->force), MIX(h, bd->torque), MIX(h, bd->gravity_scale);
    MIX(h, bd->slow_time), MIX(h, bd->sat_out), MIX(h, bd->behind), MIX(h, bd->joint_count), MIX(h, bd->aabb);
    if (bd->sb.body) {
        solver_exact_state s;
        solver_body_save(&bd->sb, &s);
        const uint8_t enabled = s.enabled;
        MIX(h, s.px), MIX(h, s.py), MIX(h, s.rotation_angle), MIX(h, s.vx), MIX(h, s.vy), MIX(h, s.wz);
        MIX(h, enabled);
    }
    const pp_raster *r = &bd->raster;
    MIX(h, r->width), MIX(h, r->height), MIX(h, r->solid_count), MIX(h, r->x0), MIX(h, r->y0), MIX(h, r->x1);
    MIX(h, r->y1);
    h = hash_bytes(h, r->bits, (size_t)r->height * (size_t)r->words_per_row * 8);
    if (r->weights)
        h = hash_bytes(h, r->weights, (size_t)r->width * (size_t)r->height);
    (void)wd;
    return h;
}

static uint64_t mix_joint(uint64_t h, const joint *jt)
{
    pp_joint_def d = jt->def;
    d.body_a.id = saved(d.body_a.id), d.body_b.id = saved(d.body_b.id);
    const uint64_t id = saved(jt->handle.id);
    const uint8_t flags[] = {jt->pinned_a, jt->pinned_b, jt->dirty};
    double feedback[6];
    solver_joint_feedback(&jt->sj, feedback);
    MIX(h, id), MIX(h, d), MIX(h, jt->local_a), MIX(h, jt->local_b), MIX(h, flags), MIX(h, jt->axis_local);
    MIX(h, jt->ref), MIX(h, jt->length), MIX(h, jt->slider_offset), MIX(h, jt->attach_order), MIX(h, jt->frame_a);
    MIX(h, jt->frame_b), MIX(h, jt->frame_axis), MIX(h, jt->frame_angle), MIX(h, feedback);
    const double at[6] = {jt->at_a.px, jt->at_a.py, jt->at_a.rotation_angle, jt->at_b.px, jt->at_b.py,
                          jt->at_b.rotation_angle};
    return MIX(h, at);
}

static uint64_t mix_record(uint64_t h, const contact_record *r)
{
    const uint64_t a = saved(r->a), b = saved(r->b);
    const int8_t carried[] = {r->carry_count, r->carry_last, (int8_t)r->carry_flags};
    MIX(h, a), MIX(h, b), MIX(h, r->flags), MIX(h, r->found), MIX(h, r->anchor), MIX(h, r->anchor_cos);
    MIX(h, r->anchor_sin), MIX(h, r->point_count), MIX(h, r->carried), MIX(h, carried), MIX(h, r->carry_pose);
    for (int k = 0; k < r->point_count && k < PP_MAX_CONTACTS_PER_PAIR; k++)
        h = mix_contact(h, &r->points[k]);
    for (int k = 0; k < r->carry_count && k < PP_MAX_CONTACTS_PER_PAIR; k++)
        h = mix_contact(h, &r->carry_points[k]);
    return h;
}

static uint64_t world_hash(const world *wd)
{
    uint64_t h = HASH_START;
    const uint64_t steps = solver_get_steps(wd->solver);
    pp_world_def def = wd->def;
    def.backend = PP_BACKEND_AUTO, def.worker_threads = 0; /* the same future on either, on any threads */
    MIX(h, def), MIX(h, wd->time), MIX(h, steps), MIX(h, wd->next_serial), MIX(h, wd->islands.substep_serial);
    MIX(h, wd->joints.next_attach), MIX(h, wd->table.substep);
    h = mix_pool(h, &wd->body_ids);
    h = mix_pool(h, &wd->joints.ids);
    for (int32_t i = 0; i < wd->body_ids.capacity; i++)
        if (wd->bodies[i])
            h = mix_body(h, wd, wd->bodies[i]);
    for (int32_t i = 0; i < wd->joints.ids.capacity; i++)
        if (wd->joints.items[i])
            h = mix_joint(h, wd->joints.items[i]);
    MIX(h, wd->contact_count);
    for (int32_t i = 0; i < wd->contact_count; i++)
        h = mix_contact(h, &wd->contacts[i]);
    const contact_table *t = &wd->table;
    MIX(h, t->count), MIX(h, t->awake), MIX(h, t->gone), MIX(h, t->carry_count);
    for (int32_t i = 0; i < t->count; i++)
        h = mix_record(h, &t->records[i]);
    h = hash_bytes(h, t->carry_order, (size_t)t->carry_count * 4);
    MIX(h, wd->events.count);
    for (int32_t i = 0; i < wd->events.count; i++) {
        const pp_event *e = &wd->events.items[i];
        const uint64_t ids[3] = {saved(e->body.id), saved(e->other.id), saved(e->joint.id)};
        MIX(h, e->type), MIX(h, ids), MIX(h, e->point), MIX(h, e->normal), MIX(h, e->approach_speed);
    }
    MIX(h, wd->edits.count), MIX(h, wd->edits.serial);
    for (int32_t i = 0; i < wd->edits.count; i++) {
        const timed_edit *e = &wd->edits.heap[i];
        const uint64_t id = saved(e->edit.body.id);
        MIX(h, e->edit.time), MIX(h, e->edit.type), MIX(h, e->edit.weight), MIX(h, id), MIX(h, e->edit.center);
        MIX(h, e->edit.radius), MIX(h, e->serial);
    }
    return hash_bytes(h, wd->forced.slots, (size_t)wd->forced.count * 4);
}

WORLD_GETTER(pp_world_get_hash, uint64_t, world_hash(wd))
