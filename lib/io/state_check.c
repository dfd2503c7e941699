/* Checks of the records that world state bytes copy whole (state.c): the checksum only catches accidents, so a
 * peer's buggy or hostile bytes reach the reader, and every value the world would trust is checked here before any
 * is used. Each check answers what is wrong, or NULL. Records are copied out before they are read: the bytes need
 * not be aligned, and a bool is checked as a byte before it is read as a bool. */
#include "state.h"

#include "massprops.h"
#include "timed_edits.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

static bool finite_all(const double *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return false;
    return true;
}

/* A value a float holds (positions and velocities: the API reads them as floats). */
static bool in_float(double v) { return fabs(v) <= FLT_MAX; }

/* Whether every byte at these offsets of a record is a bool's 0 or 1. */
static bool bools_ok(const void *rec, const size_t *at, int n)
{
    for (int i = 0; i < n; i++)
        if (((const uint8_t *)rec)[at[i]] > 1)
            return false;
    return true;
}

static bool unit(double c, double s) { return fabs(c * c + s * s - 1) < 1e-6; }

/* An id of this kind whose slot is below capacity and carries its slot's generation. */
static bool id_ok(uint64_t id, handle_kind kind, const uint8_t *gens, int32_t capacity)
{
    const uint32_t slot = handle_slot(id);
    uint32_t gen;
    if (handle_kind_of(id) != kind || slot >= (uint32_t)capacity)
        return false;
    memcpy(&gen, gens + 4 * (int64_t)slot, 4);
    return gen == handle_gen(id);
}

const char *state_world_problem(const state_world *w)
{
    const contact_table_counts *t = &w->table;
    if (w->def.struct_size != sizeof(pp_world_def) || world_check_def(&w->def, "state"))
        return "its world settings are invalid";
    if (!isfinite(w->time))
        return "its time is not finite";
    if (((const uint8_t *)w)[offsetof(state_world, table.resting_stale)] > 1)
        return "its contact table's flags are invalid";
    if (t->gone < 0 || t->gone > t->awake || t->found_count < 0)
        return "its contact table's counts do not add up";
    if (w->body_count + w->body_free != w->body_capacity || w->joint_count + w->joint_free != w->joint_capacity)
        return "its slots are neither live nor free";
    return NULL;
}

const char *state_pool_problem(const uint8_t *gens, int32_t capacity, const uint8_t *free_slots, int32_t free_count,
                               uint8_t *mark)
{
    for (int32_t i = 0; i < capacity; i++) {
        uint32_t g;
        memcpy(&g, gens + 4 * (int64_t)i, 4);
        if (g < 1 || g > HANDLE_GEN_MAX)
            return "a slot's generation is out of range";
    }
    for (int32_t i = 0; i < free_count; i++) {
        uint32_t s;
        memcpy(&s, free_slots + 4 * (int64_t)i, 4);
        if (s >= (uint32_t)capacity || (mark && mark[s]))
            return "a free slot is out of range or free twice";
        if (mark)
            mark[s] = SLOT_FREE;
    }
    return NULL;
}

/* A body's planes as saved, or a big body's changed bands over its base: each row's count is its solid bits, no bit
 * lies past the width, every count is in range and the counts and bounds agree with the solid count. Then no scan
 * of the counts for the bounds runs off the arrays. */
static const char *planes_problem(const body_view *v, const state_base *base)
{
    const pp_raster *r = &v->h.b.raster;
    const uint64_t pad = r->width % 64 ? ~(uint64_t)0 << (r->width % 64) : 0;
    int64_t rows_total = 0, cols_total = 0, tiles_total = 0;
    const uint8_t *p = v->band_data;
    for (int32_t b = 0; b < r->tiles_y; b++) {
        const int32_t n = band_rows(r, b), y0 = b << RASTER_TILE_SHIFT;
        const uint8_t *bits, *rows, *tiles;
        if (!v->h.has_base) {
            bits = v->bits + (int64_t)y0 * r->words_per_row * 8;
            rows = v->rows + (int64_t)y0 * 4, tiles = v->tiles + (int64_t)b * r->tiles_x;
        } else if (v->bands[b]) {
            bits = p;
            p += pad8((int64_t)n * r->words_per_row * 8) + (v->h.has_weights ? pad8((int64_t)n * r->width) : 0);
            rows = p, p += pad8((int64_t)n * 4);
            tiles = p, p += pad8(r->tiles_x);
        } else if (base) { /* the base's band, as the world keeps it */
            for (int32_t y = 0; y < n; y++)
                rows_total += base->rows[y0 + y];
            for (int32_t x = 0; x < r->tiles_x; x++)
                tiles_total += base->tiles[(int64_t)b * r->tiles_x + x];
            continue;
        } else { /* no base known: the restore refuses the body */
            return NULL;
        }
        for (int32_t y = 0; y < n; y++) {
            int64_t solid = 0;
            int32_t count;
            for (int32_t k = 0; k < r->words_per_row; k++) {
                uint64_t word;
                memcpy(&word, bits + ((int64_t)y * r->words_per_row + k) * 8, 8);
                if (k == r->words_per_row - 1 && (word & pad))
                    return "a row has bits past its width";
                solid += __builtin_popcountll(word);
            }
            memcpy(&count, rows + 4 * (int64_t)y, 4);
            if (count != solid)
                return "a row's count is not its solid pixels";
            rows_total += count;
        }
        for (int32_t x = 0; x < r->tiles_x; x++)
            if ((tiles_total += tiles[x], tiles[x] > RASTER_TILE * RASTER_TILE))
                return "a tile's count is out of range";
    }
    int32_t first = -1, last = -1;
    for (int32_t x = 0; x < r->width; x++) {
        int32_t count;
        memcpy(&count, v->cols + 4 * (int64_t)x, 4);
        if (count < 0 || count > r->height)
            return "a column's count is out of range";
        cols_total += count;
        if (count && first < 0)
            first = x;
        if (count)
            last = x;
    }
    if (rows_total != r->solid_count || cols_total != r->solid_count || tiles_total != r->solid_count)
        return "its pixel counts do not add up";
    const bool empty = r->x0 >= r->x1;
    if (r->solid_count == 0 ? !empty
                            : empty || r->x0 != first || r->x1 != last + 1 || r->y0 < 0 || r->y0 >= r->y1 ||
                                  r->y1 > r->height)
        return "its solid bounds are not its pixels'";
    return NULL;
}

/* Whether a moving body's ODE centre of mass lies within its bitmap's reach of where its pose puts it (island.c's
 * reach): the solver steps only what the library could have made. One far off, with the rest of its ODE state
 * zeroed, passed every other check and aborted ODE (dNormalize4) at the first step. */
static bool ode_within_reach(const body *b, const solver_exact_state *ode, double ppm)
{
    if (b->type == PP_BODY_STATIC)
        return true;
    const dvec2 com = body_com_of_pose(b), off = dv_sub(dv(ode->px * ppm, ode->py * ppm), com);
    const double reach = 1.0 + (double)b->raster.width + (double)b->raster.height;
    return dv_dot(off, off) <= reach * reach;
}

const char *state_body_problem(const body_view *v, const uint8_t *gens, int32_t capacity, const state_base *base,
                               double ppm)
{
    static const size_t bools[] = {
        offsetof(state_body, b.fixed_rotation), offsetof(state_body, b.detach_islands), offsetof(state_body, b.bullet),
        offsetof(state_body, b.is_sensor), offsetof(state_body, b.one_way), offsetof(state_body, b.forced),
        offsetof(state_body, ode.enabled),
    };
    const body *b = &v->h.b;
    if (!bools_ok(&v->h, bools, (int)(sizeof bools / sizeof *bools)))
        return "a flag is neither 0 nor 1";
    if (b->raster.solid_count < 0 || b->raster.solid_count > (int64_t)b->raster.width * b->raster.height)
        return "its solid count is out of range";
    if (!id_ok(b->handle.id, HANDLE_BODY, gens, capacity) || b->index != handle_slot(b->handle.id))
        return "its handle is not its slot's";
    if ((uint32_t)b->type > PP_BODY_KINEMATIC)
        return "its type is unknown";
    const double values[] = {
        b->mass.mass, b->mass.cx, b->mass.cy, b->mass.inertia, b->density, b->friction, b->restitution,
        b->linear_damping, b->angular_damping, b->pivot.x, b->pivot.y, b->pos.x, b->pos.y, b->angle, b->cos_a,
        b->sin_a, b->slow_time, b->one_way_dir.x, b->one_way_dir.y, b->force.x, b->force.y, b->torque,
        b->gravity_scale, v->h.ode.px, v->h.ode.py, v->h.ode.rotation_angle, v->h.ode.vx, v->h.ode.vy, v->h.ode.wz,
    };
    if (!finite_all(values, (int)(sizeof values / sizeof *values)))
        return "a value is not finite";
    if (!in_float(b->pos.x) || !in_float(b->pos.y) || !in_float(b->angle))
        return "its pose is past what a float holds";
    if (!unit(b->cos_a, b->sin_a))
        return "its rotation is not a unit";
    const double box[] = {b->aabb.x0, b->aabb.y0, b->aabb.x1, b->aabb.y1};
    if (!finite_all(box, 4))
        return "its bounds are not finite";
    if (!(b->density > 0) || b->friction < 0 || b->restitution < 0 || b->linear_damping < 0 ||
        b->angular_damping < 0 || b->slow_time < 0)
        return "a setting is out of range";
    if (b->one_way && !unit(b->one_way_dir.x, b->one_way_dir.y))
        return "its one-way direction is not a unit";
    /* A dynamic body's mass is its pixels' (ODE refuses a body without one; a kinematic body's mass waits for a
     * change of type), and a dynamic body of no pixels is destroyed. */
    const pp_mass m = b->type == PP_BODY_DYNAMIC
                          ? mass_from_sums(&b->sums, b->raster.width, b->raster.height, b->density) : b->mass;
    if (b->sums.w < 0 || b->sums.w > 255 * b->raster.solid_count || memcmp(&m, &b->mass, sizeof m) != 0)
        return "its mass is not its pixels'";
    if (b->type == PP_BODY_DYNAMIC && (!(b->mass.mass > 0) || !(b->mass.inertia > 0) || b->raster.solid_count == 0))
        return "a dynamic body without mass";
    if (!ode_within_reach(b, &v->h.ode, ppm))
        return "its solver state is far from its pose";
    return planes_problem(v, base);
}

const char *state_joint_problem(const state_joint *sj, const uint8_t *gens, int32_t capacity)
{
    static const size_t bools[] = {offsetof(state_joint, j.pinned_a), offsetof(state_joint, j.pinned_b),
                                   offsetof(state_joint, j.dirty)};
    const joint *j = &sj->j;
    if (!bools_ok(sj, bools, 3))
        return "a flag is neither 0 nor 1";
    if (!id_ok(j->handle.id, HANDLE_JOINT, gens, capacity) || j->index != handle_slot(j->handle.id))
        return "its handle is not its slot's";
    if (j->def.struct_size != sizeof(pp_joint_def))
        return "its def is of another size";
    const double values[] = {
        j->local_a.x, j->local_a.y, j->local_b.x, j->local_b.y, j->axis_local.x, j->axis_local.y, j->ref, j->length,
        j->slider_offset, j->frame_a.x, j->frame_a.y, j->frame_b.x, j->frame_b.y, j->frame_axis.x, j->frame_axis.y,
        j->frame_angle, j->at_a.px, j->at_a.py, j->at_a.rotation_angle, j->at_a.vx, j->at_a.vy, j->at_a.wz,
        j->at_b.px, j->at_b.py, j->at_b.rotation_angle, j->at_b.vx, j->at_b.vy, j->at_b.wz,
    };
    if (!finite_all(values, (int)(sizeof values / sizeof *values)) || !finite_all(sj->feedback, 6))
        return "a value is not finite";
    return NULL;
}

/* A body of the state: a body id of a slot the state fills, with its generation. */
static bool body_ok(uint64_t id, const uint8_t *live, const uint8_t *gens, int32_t capacity)
{
    return id_ok(id, HANDLE_BODY, gens, capacity) && (live[handle_slot(id)] & SLOT_BODY);
}

static bool contact_ok(const pp_contact *c, uint64_t a, uint64_t b)
{
    const double values[] = {c->point.x, c->point.y, c->normal.x, c->normal.y, c->depth, c->normal_impulse};
    return c->a.id == a && c->b.id == b && finite_all(values, 6) && c->pixel_count >= 0;
}

static int by_u64(const void *x, const void *y)
{
    const uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

/* The touching pairs and the carry order: what contact_table_validate asserts, checked. keys: room for count. */
static const char *table_problem(const state_world *w, const uint8_t *live, const uint8_t *gens,
                                 const uint8_t *records, const uint8_t *order, uint64_t *keys)
{
    const contact_table_counts *t = &w->table;
    int32_t gone = 0, keyed = 0, carried = 0;
    for (int32_t i = 0; i < t->count; i++) {
        contact_record r;
        memcpy(&r, records + (int64_t)i * (int64_t)sizeof r, sizeof r);
        if (r.point_count < 0 || r.point_count > PP_MAX_CONTACTS_PER_PAIR || r.carry_count < 0 ||
            r.carry_count > PP_MAX_CONTACTS_PER_PAIR || r.carried < 0 || r.carried > t->carry_count ||
            (r.flags & ~(uint32_t)(CT_SAVED_FLAGS | CT_GONE)) || (r.carry_flags & ~15u) || r.carry_last < 0 ||
            r.carry_last >= w->def.substeps)
            return "a touching pair's counts or flags are out of range";
        const double values[] = {r.anchor[0], r.anchor[1], r.anchor[2], r.anchor_cos, r.anchor_sin,
                                 r.carry_pose.com_a.x, r.carry_pose.com_a.y, r.carry_pose.com_b.x,
                                 r.carry_pose.com_b.y, r.carry_pose.cos_a, r.carry_pose.sin_a, r.carry_pose.cos_b,
                                 r.carry_pose.sin_b};
        if (!finite_all(values, (int)(sizeof values / sizeof *values)))
            return "a touching pair's values are not finite";
        carried += r.carried != 0;
        if (r.flags & CT_GONE) { /* ended at the next substep; its bodies may be gone */
            if (i >= t->awake || r.carried)
                return "an ended pair is out of place";
            gone++;
            continue;
        }
        if (!body_ok(r.a, live, gens, w->body_capacity) || !body_ok(r.b, live, gens, w->body_capacity) ||
            handle_slot(r.a) >= handle_slot(r.b))
            return "a touching pair is not of two bodies of the state, the first in the lower slot";
        if ((r.flags & (CT_SENSOR | CT_PASSING)) && (r.point_count || r.carried))
            return "a sensor's or passing pair has contacts";
        for (int k = 0; k < r.point_count; k++)
            if (!contact_ok(&r.points[k], r.a, r.b))
                return "a touching pair's contact is not its bodies' or not finite";
        for (int k = 0; k < r.carry_count; k++)
            if (!contact_ok(&r.carry_points[k], r.a, r.b))
                return "a carried contact is not its pair's bodies' or not finite";
        keys[keyed++] = (uint64_t)handle_slot(r.a) << 32 | handle_slot(r.b);
    }
    if (gone != t->gone)
        return "the count of ended pairs is wrong";
    qsort(keys, (size_t)keyed, sizeof *keys, by_u64);
    for (int32_t i = 1; i < keyed; i++)
        if (keys[i] == keys[i - 1])
            return "a pair touches twice";
    for (int32_t k = 0; k < t->carry_count; k++) {
        int32_t i;
        memcpy(&i, order + 4 * (int64_t)k, 4);
        if (i == -1)
            continue;
        contact_record r;
        if (i < 0 || i >= t->count)
            return "the carry order names no pair";
        memcpy(&r, records + (int64_t)i * (int64_t)sizeof r, sizeof r);
        if (r.carried != k + 1 || r.carry_count < 1 || (r.flags & (CT_GONE | CT_SENSOR | CT_PASSING)))
            return "the carry order and the carried pairs disagree";
        carried--;
    }
    return carried ? "a carried pair is not in the carry order" : NULL;
}

const char *state_arrays_problem(const state_world *w, uint8_t *live, const uint8_t *gens, const uint8_t *contacts,
                                 const uint8_t *records, const uint8_t *order, const uint8_t *events,
                                 const uint8_t *edits, const uint8_t *forced, uint64_t *keys)
{
    for (int32_t i = 0; i < w->contact_count; i++) {
        pp_contact c;
        memcpy(&c, contacts + (int64_t)i * (int64_t)sizeof c, sizeof c);
        if (!body_ok(c.a.id, live, gens, w->body_capacity) || !body_ok(c.b.id, live, gens, w->body_capacity) ||
            !contact_ok(&c, c.a.id, c.b.id))
            return "a contact is not of two bodies of the state, or not finite";
    }
    const char *why = table_problem(w, live, gens, records, order, keys);
    if (why)
        return why;
    for (int32_t i = 0; i < w->event_count; i++) {
        pp_event e;
        memcpy(&e, events + (int64_t)i * (int64_t)sizeof e, sizeof e);
        if ((uint32_t)e.type < PP_EVENT_BODY_SPLIT || (uint32_t)e.type > PP_EVENT_JOINT_BROKEN)
            return "an event's type is unknown";
    }
    for (int32_t i = 0; i < w->edit_count; i++) {
        timed_edit t;
        memcpy(&t, edits + (int64_t)i * (int64_t)sizeof t, sizeof t);
        const pp_timed_edit *e = &t.edit;
        const bool erase = e->type == PP_EDIT_ERASE_CIRCLE;
        if (!isfinite(e->time) || !isfinite(e->center.x) || !isfinite(e->center.y) || !(e->radius >= 0) ||
            !isfinite(e->radius) || (!erase && e->type != PP_EDIT_PAINT_CIRCLE) ||
            (!erase && (e->weight < 1 || e->weight > 255)) || e->reserved || t.serial >= w->edit_serial ||
            (e->body.id ? !body_ok(e->body.id, live, gens, w->body_capacity) : !erase))
            return "a scheduled edit is invalid";
    }
    for (int32_t i = 0; i < w->forced_count; i++) {
        uint32_t s;
        memcpy(&s, forced + 4 * (int64_t)i, 4);
        if (s >= (uint32_t)w->body_capacity || live[s] != (SLOT_BODY | SLOT_FORCED))
            return "a forced body is not a forced body of the state, or is listed twice";
        live[s] |= SLOT_LISTED;
    }
    for (int32_t s = 0; s < w->body_capacity; s++)
        if (live[s] == (SLOT_BODY | SLOT_FORCED))
            return "a forced body is not listed";
    return NULL;
}
