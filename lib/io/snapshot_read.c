/* Loading a snapshot (pp_world_load_snapshot): world.json checked key by key, a new world made from its
 * settings, then the restore_* readers put back each section of its exact state (slots, bodies, edits,
 * events, touching and held pairs, joints), every bad value named by its JSON path. */
#include "alloc.h"
#include "camera.h"
#include "forces.h"
#include "handle.h"
#include "joint.h"
#include "scene_json.h"
#include "snapshot.h"
#include "status.h"
#include "world.h"

#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Exactly n finite doubles, none larger than a float: the API never sets more, and ODE, handed a velocity
 * of 1e211, stepped to NaN and aborted the process in dNormalize4 (found by fuzz_snapshot). */
static pp_status read_doubles(const json_ctx *c, const cJSON *obj, const char *where, const char *key, double *out,
                              int n)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    bool ok = cJSON_IsArray(it) && cJSON_GetArraySize(it) == n;
    for (int i = 0; ok && i < n; i++) {
        const cJSON *x = cJSON_GetArrayItem(it, i);
        ok = cJSON_IsNumber(x) && fabs(x->valuedouble) <= FLT_MAX;
        out[i] = ok ? x->valuedouble : 0;
    }
    return ok ? PP_OK : json_fail(c, PP_ERR_FORMAT, where, key, "expected %d finite numbers, each within ±%g", n, FLT_MAX);
}

/* A "0x…" handle; required unless optional, where absent gives 0. */
static pp_status read_handle(const json_ctx *c, const cJSON *obj, const char *where, const char *key, bool optional,
                             uint64_t *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    *out = 0;
    if (!it && optional)
        return PP_OK;
    char *end = NULL;
    if (cJSON_IsString(it) && strncmp(it->valuestring, "0x", 2) == 0) {
        errno = 0;
        *out = strtoull(it->valuestring + 2, &end, 16);
    }
    if (!end || *end || end == it->valuestring + 2 || errno)
        return json_fail(c, PP_ERR_FORMAT, where, key, "expected a handle, \"0x\" and hex digits");
    return PP_OK;
}

/* A body or joint handle as saved (handle.h), made one of the loaded world's, of that kind. */
static pp_status read_saved_handle(const json_ctx *c, const cJSON *obj, const char *where, const char *key,
                                   bool optional, const world *wd, handle_kind kind, uint64_t *out)
{
    uint64_t saved = 0;
    pp_status st = read_handle(c, obj, where, key, optional, &saved);
    if (!st && !handle_from_saved(saved, kind, wd->tag, out))
        st = json_fail(c, PP_ERR_FORMAT, where, key,
                       kind == HANDLE_JOINT ? "no joint handle has that slot and generation"
                                            : "no body handle has that slot and generation");
    return st;
}
static pp_status read_body_handle(const json_ctx *c, const cJSON *obj, const char *where, const char *key,
                                  bool optional, const world *wd, uint64_t *out)
{
    return read_saved_handle(c, obj, where, key, optional, wd, HANDLE_BODY, out);
}
static pp_status read_joint_handle(const json_ctx *c, const cJSON *obj, const char *where, const char *key,
                                   bool optional, const world *wd, uint64_t *out)
{
    return read_saved_handle(c, obj, where, key, optional, wd, HANDLE_JOINT, out);
}

static pp_status read_required_int(const json_ctx *c, const cJSON *obj, const char *where, const char *key,
                                   int64_t lo, int64_t hi, int64_t *out)
{
    if (!cJSON_GetObjectItemCaseSensitive(obj, key))
        return json_fail(c, PP_ERR_FORMAT, where, key, "missing");
    return read_int(c, obj, where, key, lo, hi, out);
}

/* An array of integers in lo..hi, allocated; *n receives the count. */
static pp_status read_int_array(const json_ctx *c, const cJSON *obj, const char *key, int64_t lo, int64_t hi,
                                uint32_t **out, int32_t *n)
{
    const cJSON *arr = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!cJSON_IsArray(arr) || cJSON_GetArraySize(arr) > PP_MAX_BODIES)
        return json_fail(c, PP_ERR_FORMAT, "", key, "expected an array of at most %d integers", PP_MAX_BODIES);
    *n = cJSON_GetArraySize(arr);
    *out = pp_calloc((size_t)*n + 1, sizeof **out);
    if (!*out)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory", c->fn);
    int32_t i = 0;
    for (const cJSON *x = arr->child; x; x = x->next, i++) {
        const double v = cJSON_IsNumber(x) ? x->valuedouble : -1;
        if (!(v >= (double)lo && v <= (double)hi) || v != (double)(int64_t)v)
            return json_fail(c, PP_ERR_FORMAT, key, "", "[%d]: expected an integer in %lld..%lld", (int)i,
                             (long long)lo, (long long)hi);
        (*out)[i] = (uint32_t)v;
    }
    return PP_OK;
}

/* The slot table as saved, with no body in it yet: generations, and free slots that exist. */
static pp_status restore_slots(const json_ctx *c, const cJSON *root, world *wd)
{
    uint32_t *gens = NULL, *list = NULL;
    int32_t n = 0, n_free = 0;
    pp_status st = read_int_array(c, root, "generations", 1, HANDLE_GEN_MAX, &gens, &n);
    if (!st)
        st = read_int_array(c, root, "free_slots", 0, n - 1, &list, &n_free);
    /* The pool's stack holds the slots once each: a longer list cannot be one (it overran the stack). */
    if (!st && n_free > n)
        st = json_fail(c, PP_ERR_FORMAT, "free_slots", "", "lists %d slots of %d", (int)n_free, (int)n);
    if (!st && (!(wd->bodies = pp_calloc((size_t)n + 1, sizeof *wd->bodies)) ||
                !id_pool_restore(&wd->body_ids, gens, n, list, n_free, pp_realloc)))
        st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d body slots", c->fn, (int)n);
    pp_free(gens);
    pp_free(list);
    return st;
}

/* Each free slot holds no body and is listed once (each marked as seen, so that a long list is checked in
 * one pass). */
static pp_status check_free_list(const json_ctx *c, const world *wd)
{
    const id_pool *ids = &wd->body_ids;
    uint8_t *seen = pp_calloc((size_t)ids->capacity + 1, 1);
    if (!seen)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d body slots", c->fn, (int)ids->capacity);
    pp_status st = PP_OK;
    for (int32_t i = 0; st == PP_OK && i < ids->free_count; i++) {
        const uint32_t slot = ids->free_slots[i];
        const bool twice = seen[slot];
        seen[slot] = 1;
        if (twice || wd->bodies[slot])
            st = json_fail(c, PP_ERR_FORMAT, "free_slots", "", "[%d]: slot %u is %s", (int)i, (unsigned)slot,
                           twice ? "listed twice" : "in use");
    }
    pp_free(seen);
    return st;
}

static const char *const body_snapshot_keys[] = {"handle", "serial", "sprite", "mask", "weights", "state", NULL};
static const char *const state_keys[] = {"pose", "user_data", "slow_time", "ode", "awake", "forces", NULL};

/* The exact state over a body made from its settings and planes. */
static pp_status restore_state(const json_ctx *c, const cJSON *obj, const char *where, world *wd, body *bd)
{
    const cJSON *state;
    char at[64];
    snprintf(at, sizeof at, "%s.state", where);
    pp_status st = read_section(c, obj, where, "state", false, &state);
    if (!st && !state)
        st = json_fail(c, PP_ERR_FORMAT, where, "state", "missing");
    if (st || (st = check_keys(c, state, at, NULL, state_keys)))
        return st;
    double pose[5], ode[6];
    uint64_t user = 0;
    uint32_t awake = 1;
    if ((st = read_doubles(c, state, at, "pose", pose, 5)) || (st = read_handle(c, state, at, "user_data", false, &user)) ||
        (st = read_double(c, state, at, "slow_time", NUM_NONNEG, &bd->slow_time)) ||
        (bd->sb.body && ((st = read_doubles(c, state, at, "ode", ode, 6)) || (st = read_bool(c, state, at, "awake", &awake)))))
        return st;
    bd->pos = dv(pose[0], pose[1]);
    bd->angle = pose[2];
    angle_cos_sin(bd->angle, &bd->cos_a, &bd->sin_a);
    bd->pivot = dv(pose[3], pose[4]);
    bd->user_data = user;
    body_update_pose_cache(bd);
    if (bd->sb.body) {
        const solver_exact_state s = {ode[0], ode[1], ode[2], ode[3], ode[4], ode[5], awake != 0};
        solver_body_restore(&bd->sb, &s);
    }
    if (!cJSON_GetObjectItemCaseSensitive(state, "forces"))
        return PP_OK;
    double forces[4];
    if ((st = read_doubles(c, state, at, "forces", forces, 4)))
        return st;
    if (bd->type != PP_BODY_DYNAMIC)
        return json_fail(c, PP_ERR_FORMAT, at, "forces", "only a dynamic body takes forces");
    if (!(fabs(forces[3]) <= PP_MAX_GRAVITY_SCALE))
        return json_fail(c, PP_ERR_FORMAT, at, "forces", "a gravity scale past PP_MAX_GRAVITY_SCALE");
    bd->force = dv(forces[0], forces[1]), bd->torque = forces[2], bd->gravity_scale = forces[3];
    return forces_list(wd, bd, "pp_world_load_snapshot");
}

/* One body into the slot its handle names; bodies come in creation order, so ODE's list is rebuilt. */
static pp_status restore_body(const json_ctx *c, const cJSON *obj, const char *where, world *wd, uint64_t *serial)
{
    if (!cJSON_IsObject(obj))
        return json_fail(c, PP_ERR_FORMAT, where, NULL, "expected an object");
    pp_body_def d = pp_body_def_default();
    uint64_t id = 0;
    int64_t ser = 0;
    bitmap bm = {0};
    pp_status st = check_keys(c, obj, where, body_fields, body_snapshot_keys);
    if (st || (st = parse_body_settings(c, obj, where, &d)) ||
        (st = read_body_handle(c, obj, where, "handle", false, wd, &id)) ||
        (st = read_required_int(c, obj, where, "serial", (int64_t)*serial, JSON_MAX_EXACT_INT, &ser)))
        return st;
    const uint32_t slot = handle_slot(id);
    if (!id_pool_current(&wd->body_ids, slot, handle_gen(id)) || wd->bodies[slot])
        return json_fail(c, PP_ERR_FORMAT, where, "handle", "no free slot of that generation");
    if ((st = parse_bitmap(c, obj, where, &bm))) {
        bitmap_free(&bm); /* parse_bitmap leaves what it loaded to the caller (a leak found by fuzz_snapshot) */
        return st;
    }
    d.width = bm.width, d.height = bm.height, d.rgba = bm.rgba, d.mask = bm.mask, d.weights = bm.weights;
    body *bd = NULL;
    st = body_make(wd, &d, slot, c->fn, &bd);
    bitmap_free(&bm);
    if (st)
        return json_fail_from_last(c, st, where, NULL);
    bd->serial = (uint64_t)ser;
    *serial = (uint64_t)ser + 1;
    return restore_state(c, obj, where, wd, bd);
}

static pp_status restore_bodies(const json_ctx *c, const cJSON *root, world *wd)
{
    const cJSON *arr;
    pp_status st = read_section(c, root, "", "bodies", true, &arr);
    uint64_t serial = 0;
    int32_t i = 0;
    char where[32];
    for (const cJSON *it = arr ? arr->child : NULL; it && st == PP_OK; it = it->next, i++) {
        snprintf(where, sizeof where, "bodies[%d]", (int)i);
        st = restore_body(c, it, where, wd, &serial);
    }
    return st;
}

static pp_status restore_edits(const json_ctx *c, const cJSON *root, world *wd)
{
    static const char *const extra[] = {"body", NULL};
    const cJSON *arr;
    pp_status st = read_section(c, root, "", "edits", true, &arr);
    int32_t i = 0;
    char where[32];
    for (const cJSON *it = arr ? arr->child : NULL; it && st == PP_OK; it = it->next, i++) {
        snprintf(where, sizeof where, "edits[%d]", (int)i);
        pp_timed_edit e = {0};
        if (!(st = check_keys(c, it, where, edit_fields, extra)) && !(st = read_fields(c, it, where, edit_fields, &e)) &&
            !(st = read_body_handle(c, it, where, "body", true, wd, &e.body.id)) &&
            (st = timed_edits_schedule(wd, &e, c->fn)))
            st = json_fail_from_last(c, st, where, NULL);
    }
    return st;
}

/* A BEGIN event's point, normal and approach speed (other events have none). */
static pp_status restore_event_contact(const json_ctx *c, const cJSON *obj, const char *where, pp_event *ev)
{
    if (ev->type != PP_EVENT_CONTACT_BEGIN && ev->type != PP_EVENT_SENSOR_BEGIN)
        return PP_OK;
    double point[2], normal[2];
    pp_status st = read_doubles(c, obj, where, "point", point, 2);
    if (st || (st = read_doubles(c, obj, where, "normal", normal, 2)) ||
        (st = read_float(c, obj, where, "approach_speed", NUM_NONNEG, &ev->approach_speed)))
        return st;
    ev->point = (pp_vec2){(float)point[0], (float)point[1]};
    ev->normal = (pp_vec2){(float)normal[0], (float)normal[1]};
    return PP_OK;
}

static pp_status restore_events(const json_ctx *c, const cJSON *root, world *wd)
{
    static const char *const keys[] = {"type", "body", "other", "point", "normal", "approach_speed", "joint", NULL};
    const cJSON *arr;
    pp_status st = read_section(c, root, "", "events", true, &arr);
    int32_t i = 0;
    char where[32];
    for (const cJSON *it = arr ? arr->child : NULL; it && st == PP_OK; it = it->next, i++) {
        snprintf(where, sizeof where, "events[%d]", (int)i);
        int32_t type = 0;
        pp_event ev = {0};
        if (!(st = check_keys(c, it, where, NULL, keys)) && !(st = read_enum(c, it, where, "type", event_names, &type)) &&
            !(st = read_body_handle(c, it, where, "body", false, wd, &ev.body.id)) &&
            !(st = read_body_handle(c, it, where, "other", false, wd, &ev.other.id)) &&
            !(st = read_joint_handle(c, it, where, "joint", true, wd, &ev.joint.id))) {
            ev.type = (pp_event_type)type;
            if (!type)
                st = json_fail(c, PP_ERR_FORMAT, where, "type", "missing");
            else if (!(st = restore_event_contact(c, it, where, &ev)) && !(st = world_reserve_events(wd, 1, c->fn)))
                world_queue_event(wd, ev);
        }
    }
    return st;
}

/* n numbers, each finite as a float, from a JSON array of exactly n; false for anything else. */
static bool read_numbers(const cJSON *arr, int n, double *v)
{
    bool ok = cJSON_IsArray(arr) && cJSON_GetArraySize(arr) == n;
    for (int i = 0; ok && i < n; i++) {
        const cJSON *x = cJSON_GetArrayItem(arr, i);
        ok = cJSON_IsNumber(x) && fabs(x->valuedouble) <= FLT_MAX;
        v[i] = ok ? x->valuedouble : 0;
    }
    return ok;
}

/* A saved contact's first numbers: point, unit normal, depth, a count of pixels, impulse. */
static bool saved_contact_ok(const double *v)
{
    return fabs(hypot(v[2], v[3]) - 1) < 1e-3 && v[5] >= 0 && v[5] <= INT32_MAX && v[5] == floor(v[5]);
}

static pp_contact saved_contact(pp_body a, pp_body b, const double *v)
{
    return (pp_contact){a, b, {(float)v[0], (float)v[1]}, {(float)v[2], (float)v[3]}, (float)v[4], (int32_t)v[5],
                        (float)v[6], 0};
}

/* A touching pair's manifold (its "points"; absent before sleeping pairs kept theirs). */
static pp_status restore_manifold(const json_ctx *c, const cJSON *it, const char *where, contact_record *t)
{
    const cJSON *points = cJSON_GetObjectItemCaseSensitive(it, "points");
    if (!points)
        return PP_OK;
    if (!cJSON_IsArray(points) || cJSON_GetArraySize(points) > PP_MAX_CONTACTS_PER_PAIR)
        return json_fail(c, PP_ERR_FORMAT, where, "points", "expected at most %d contacts", PP_MAX_CONTACTS_PER_PAIR);
    for (const cJSON *p = points->child; p; p = p->next) {
        double v[SAVED_CONTACT_NUMBERS];
        if (!read_numbers(p, SAVED_CONTACT_NUMBERS, v) || !saved_contact_ok(v))
            return json_fail(c, PP_ERR_FORMAT, where, "points",
                             "expected contacts of %d finite numbers: point, unit normal, depth, pixel count, impulse",
                             SAVED_CONTACT_NUMBERS);
        t->points[t->point_count++] = saved_contact((pp_body){t->a}, (pp_body){t->b}, v);
    }
    return PP_OK;
}

/* The touching pairs; absent in snapshots from before contact events. */
static pp_status restore_touching(const json_ctx *c, const cJSON *root, world *wd)
{
    static const char *const keys[] = {"a", "b", "flags", "anchor", "points", NULL};
    const cJSON *arr;
    pp_status st = read_section(c, root, "", "touching", true, &arr);
    const int32_t n = arr ? cJSON_GetArraySize(arr) : 0;
    if (st || n == 0)
        return st;
    char where[32];
    int32_t i = 0;
    for (const cJSON *it = arr->child; it && st == PP_OK; it = it->next, i++) {
        snprintf(where, sizeof where, "touching[%d]", (int)i);
        contact_record rec = {0}, *t = &rec;
        int64_t flags = 0;
        if (!(st = check_keys(c, it, where, NULL, keys)) &&
            !(st = read_body_handle(c, it, where, "a", false, wd, &t->a)) &&
            !(st = read_body_handle(c, it, where, "b", false, wd, &t->b)))
            st = read_required_int(c, it, where, "flags", 0, CT_SAVED_FLAGS, &flags);
        t->flags = (uint32_t)flags;
        /* Before friction anchors, only pairs with events, sensors or one-way bodies were kept, and every
         * contact pair kept with events on had begun. Such a pair anchors at the next substep. */
        const bool anchored = cJSON_GetObjectItemCaseSensitive(it, "anchor") != NULL;
        if (!st && anchored)
            st = read_doubles(c, it, where, "anchor", t->anchor, 3);
        else if (!st) {
            t->flags |= CT_UNANCHORED;
            if (wd->def.contact_events && !(t->flags & (CT_SENSOR | CT_PASSING)))
                t->flags |= CT_BEGUN;
        }
        /* the table keys a pair by its slots, a's the lower */
        if (!st && (t->a == 0 || t->b == 0))
            st = json_fail(c, PP_ERR_FORMAT, where, t->a ? "b" : "a", "expected a body, not 0");
        if (!st && handle_slot(t->a) >= handle_slot(t->b))
            st = json_fail(c, PP_ERR_FORMAT, where, "a", "must be in a lower slot than b");
        if (!st && !(st = restore_manifold(c, it, where, t)) && (t->flags & (CT_SENSOR | CT_PASSING)) && t->point_count)
            st = json_fail(c, PP_ERR_FORMAT, where, "points", "a sensor's or passing pair has no contacts");
        if (!st)
            st = contact_table_add(wd, t, c->fn, where);
    }
    return st;
}

/* One held pair's contacts, in order, into its record's carried contacts; the poses their bodies had, which every
 * contact of a pair shares. */
static pp_status restore_held_contacts(const json_ctx *c, const cJSON *arr, const char *where, contact_record *r)
{
    int32_t k = 0;
    char at[64];
    for (const cJSON *it = arr->child; it; it = it->next, k++) {
        snprintf(at, sizeof at, "%s.contacts[%d]", where, (int)k);
        double v[HELD_NUMBERS];
        /* A saved contact, then rotations as cosines and sines: anything else is no held contact. */
        const bool ok = read_numbers(it, HELD_NUMBERS, v) && saved_contact_ok(v) &&
                        fabs(hypot(v[11], v[12]) - 1) < 1e-6 && fabs(hypot(v[13], v[14]) - 1) < 1e-6;
        if (!ok)
            return json_fail(c, PP_ERR_FORMAT, at, NULL,
                             "expected %d finite numbers: point, unit normal, depth, pixel count, impulse, two centres "
                             "of mass, two (cos, sin) pairs",
                             HELD_NUMBERS);
        const carried_pose q = {dv(v[7], v[8]), dv(v[9], v[10]), v[11], v[12], v[13], v[14]};
        if (k > 0 && memcmp(&q, &r->carry_pose, sizeof q) != 0)
            return json_fail(c, PP_ERR_FORMAT, at, NULL,
                             "expected the centres of mass and rotations of the pair's first contact");
        r->carry_pose = q;
        r->carry_points[k] = saved_contact((pp_body){r->a}, (pp_body){r->b}, v);
    }
    r->carry_count = (int8_t)k;
    contact_table_locate_carried(r);
    return PP_OK;
}

/* The held pairs, each a touching pair's record; absent in snapshots from before pairs were held from step to
 * step. */
static pp_status restore_held(const json_ctx *c, const cJSON *root, world *wd)
{
    static const char *const keys[] = {"a", "b", "stack", "contacts", NULL};
    const cJSON *arr;
    pp_status st = read_section(c, root, "", "held", true, &arr);
    const int32_t n = arr ? cJSON_GetArraySize(arr) : 0;
    if (st || n == 0)
        return st;
    if (wd->def.substeps < 2) /* one substep carries nothing: such a world never holds a pair */
        return json_fail(c, PP_ERR_FORMAT, "held", NULL, "expected none in a world of one substep");
    if ((st = contact_table_reserve_carried(wd, n, c->fn)))
        return st;
    char where[32];
    int32_t i = 0;
    for (const cJSON *it = arr->child; it && st == PP_OK; it = it->next, i++) {
        snprintf(where, sizeof where, "held[%d]", (int)i);
        uint64_t a = 0, b = 0;
        const cJSON *stack = cJSON_GetObjectItemCaseSensitive(it, "stack");
        const cJSON *points = cJSON_GetObjectItemCaseSensitive(it, "contacts");
        if ((st = check_keys(c, it, where, NULL, keys)) || (st = read_body_handle(c, it, where, "a", false, wd, &a)) ||
            (st = read_body_handle(c, it, where, "b", false, wd, &b)))
            break;
        const bool live = body_find(wd, (pp_body){a}) && body_find(wd, (pp_body){b});
        const int32_t at = live && handle_slot(a) < handle_slot(b)
                               ? contact_table_lookup(wd, handle_slot(a), handle_slot(b)) : -1;
        const contact_record *r = at >= 0 ? &wd->table.records[at] : NULL;
        if (!live || handle_slot(a) >= handle_slot(b))
            st = json_fail(c, PP_ERR_FORMAT, where, "a", "expected two live bodies, a in the lower slot");
        else if (!r || (r->flags & (CT_SENSOR | CT_PASSING)))
            st = json_fail(c, PP_ERR_FORMAT, where, NULL, "expected a pair in \"touching\" that makes contacts");
        else if (r->carried)
            st = json_fail(c, PP_ERR_FORMAT, "held", NULL, "a pair is held twice");
        else if (!cJSON_IsBool(stack))
            st = json_fail(c, PP_ERR_FORMAT, where, "stack", "expected true or false");
        else if (!cJSON_IsArray(points) || cJSON_GetArraySize(points) < 1 ||
                 cJSON_GetArraySize(points) > PP_MAX_CONTACTS_PER_PAIR)
            st = json_fail(c, PP_ERR_FORMAT, where, "contacts", "expected 1 to %d contacts", PP_MAX_CONTACTS_PER_PAIR);
        if (st)
            break;
        contact_table_carry(wd, at);
        contact_record *e = contact_table_edit(wd, at);
        e->carry_last = (int8_t)(wd->def.substeps - 1);
        e->carry_flags = CARRY_HELD | (cJSON_IsTrue(stack) ? CARRY_STACK : 0);
        st = restore_held_contacts(c, points, where, e);
    }
    return st;
}

/* One joint as write_joint saved it, into its slot of the restored table; attach_order counts the file's order. */
static pp_status restore_joint(const json_ctx *c, const cJSON *obj, const char *where, world *wd, uint64_t order)
{
    static const char *const extra[] = {"type", "handle", "body_a", "body_b", "state", "dirty", NULL};
    uint64_t id = 0;
    uint32_t dirty = 0;
    double v[JOINT_STATE_DOUBLES];
    pp_joint_def d;
    pp_status st;
    if ((st = parse_joint_def(c, obj, where, extra, &d)) ||
        (st = read_joint_handle(c, obj, where, "handle", false, wd, &id)) ||
        (st = read_body_handle(c, obj, where, "body_a", true, wd, &d.body_a.id)) ||
        (st = read_body_handle(c, obj, where, "body_b", true, wd, &d.body_b.id)) ||
        (st = read_doubles(c, obj, where, "state", v, JOINT_STATE_DOUBLES - 1)) ||
        (st = read_bool(c, obj, where, "dirty", &dirty)))
        return st;
    const joint_table *t = &wd->joints;
    const uint32_t slot = handle_slot(id);
    if (!id_pool_current(&t->ids, slot, handle_gen(id)) || t->items[slot])
        return json_fail(c, PP_ERR_FORMAT, where, "handle", "no free joint slot of that generation");
    if ((st = joint_check_def(wd, c->fn, &d)) ||
        (st = joint_check_anchors(c->fn, d.body_a.id ? body_of(wd, d.body_a) : NULL, dv(v[0], v[1]),
                                  d.body_b.id ? body_of(wd, d.body_b) : NULL, dv(v[2], v[3]))))
        return json_fail_from_last(c, st, where, NULL);
    joint *jt = pp_calloc(1, sizeof *jt);
    if (!jt)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for a joint", c->fn);
    *jt = (joint){
        .index = slot, .handle = {id}, .def = d, .local_a = dv(v[0], v[1]), .local_b = dv(v[2], v[3]),
        .pinned_a = v[28] != 0, .pinned_b = v[29] != 0, .axis_local = dv(v[4], v[5]), .ref = v[6], .length = v[7],
        .slider_offset = v[8], .dirty = dirty != 0, .attach_order = order, .frame_a = dv(v[9], v[10]),
        .frame_b = dv(v[11], v[12]), .frame_axis = dv(v[13], v[14]), .frame_angle = v[15],
        .at_a = {.px = v[16], .py = v[17], .rotation_angle = v[18]}, .at_b = {.px = v[19], .py = v[20], .rotation_angle = v[21]},
    };
    if ((st = joint_restore(wd, jt, v + 22, c->fn)))
        pp_free(jt);
    return st;
}

/* The joint table and the joints; absent in snapshots of worlds that never had one. */
static pp_status restore_joints(const json_ctx *c, const cJSON *root, world *wd)
{
    const cJSON *arr;
    pp_status st = read_section(c, root, "", "joints", true, &arr);
    if (st || !cJSON_GetObjectItemCaseSensitive(root, "joint_generations"))
        return st;
    uint32_t *gens = NULL, *free_slots = NULL;
    int32_t n = 0, n_free = 0;
    uint8_t *seen = NULL;
    if (!(st = read_int_array(c, root, "joint_generations", 1, HANDLE_GEN_MAX, &gens, &n)) &&
        !(st = read_int_array(c, root, "joint_free_slots", 0, n - 1, &free_slots, &n_free))) {
        if (!(seen = pp_calloc((size_t)n + 1, 1)))
            st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d joint slots", c->fn, (int)n);
        for (int32_t i = 0; !st && i < n_free; i++)
            if (seen[free_slots[i]]++)
                st = json_fail(c, PP_ERR_FORMAT, "joint_free_slots", "", "[%d]: slot %u is listed twice", (int)i,
                               (unsigned)free_slots[i]);
    }
    if (!st)
        st = joint_table_restore(wd, gens, n, free_slots, n_free, c->fn);
    int32_t i = 0;
    char where[32];
    for (const cJSON *it = arr ? arr->child : NULL; it && st == PP_OK; it = it->next, i++) {
        snprintf(where, sizeof where, "joints[%d]", (int)i);
        st = restore_joint(c, it, where, wd, (uint64_t)i);
    }
    for (int32_t k = 0; st == PP_OK && k < n_free; k++)
        if (wd->joints.items[free_slots[k]])
            st = json_fail(c, PP_ERR_FORMAT, "joint_free_slots", "", "[%d]: slot %u holds a joint", (int)k,
                           (unsigned)free_slots[k]);
    wd->joints.next_attach = (uint64_t)i;
    pp_free(seen), pp_free(gens), pp_free(free_slots);
    return st;
}

/* The world's own state: settings, camera, clock, solver steps, slots, bodies, edits, events. */
static pp_status restore_world(const json_ctx *c, const cJSON *root, world *wd)
{
    pp_camera cam = camera_of(wd);
    int64_t steps = 0, serial = 0;
    const cJSON *cobj;
    pp_status st = read_section(c, root, "", "camera", false, &cobj);
    if (st || (cobj && (st = parse_camera(c, cobj, "camera", &cam))))
        return st;
    if ((st = camera_set(wd, &cam, c->fn)))
        return json_fail_from_last(c, st, "camera", NULL);
    if ((st = read_double(c, root, "", "time", NUM_NONNEG, &wd->time)) ||
        (st = read_required_int(c, root, "", "solver_steps", 0, JSON_MAX_EXACT_INT, &steps)) ||
        (st = read_required_int(c, root, "", "next_serial", 0, JSON_MAX_EXACT_INT, &serial)) ||
        (st = restore_slots(c, root, wd)) || (st = restore_bodies(c, root, wd)) || (st = check_free_list(c, wd)) ||
        (st = restore_edits(c, root, wd)) || (st = restore_events(c, root, wd)) || (st = restore_touching(c, root, wd)) ||
        (st = restore_held(c, root, wd)) || (st = restore_joints(c, root, wd)))
        return st;
    solver_set_steps(wd->solver, (uint64_t)steps);
    wd->next_serial = (uint64_t)serial;
    return PP_OK;
}

static pp_status build_snapshot(const json_ctx *c, const cJSON *root, pp_world *out)
{
    static const char *const top_keys[] = {"format", "version", "world", "camera", "time", "solver_steps", "next_serial",
                                           "generations", "free_slots", "edits", "events", "touching", "held", "bodies",
                                           "joint_generations", "joint_free_slots", "joints", NULL};
    if (!cJSON_IsObject(root))
        return json_fail(c, PP_ERR_FORMAT, "(root)", NULL, "expected an object");
    const char *format = NULL;
    int64_t version = 0;
    const cJSON *wobj;
    pp_status st = check_keys(c, root, "", NULL, top_keys);
    if (st || (st = read_string(c, root, "", "format", &format)) ||
        (st = read_required_int(c, root, "", "version", 0, INT32_MAX, &version)) ||
        (st = read_section(c, root, "", "world", false, &wobj)))
        return st;
    if (!format || strcmp(format, SNAPSHOT_FORMAT) != 0)
        return json_fail(c, PP_ERR_FORMAT, "", "format", "expected \"%s\"", SNAPSHOT_FORMAT);
    if (version != SNAPSHOT_VERSION)
        return json_fail(c, PP_ERR_UNSUPPORTED, "", "version", "%lld; this library reads version %d",
                         (long long)version, SNAPSHOT_VERSION);
    pp_world_def d = pp_world_def_default();
    if (wobj && (st = parse_world_def(c, wobj, "world", &d)))
        return st;
    world *wd = NULL;
    if ((st = world_make(&d, c->fn, &wd)))
        return json_fail_from_last(c, st, "world", NULL);
    if ((st = restore_world(c, root, wd))) {
        world_free(wd);
        return st;
    }
    *out = wd->handle;
    return PP_OK;
}

PP_API pp_status pp_world_load_snapshot(const char *folder, pp_world *out)
{
    if (!folder || !out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_load_snapshot: %s is NULL", folder ? "out" : "folder");
    char file[PATH_MAX];
    if (snprintf(file, sizeof file, "%s/world.json", folder) >= (int)sizeof file)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_load_snapshot: folder path is too long");
    json_ctx c = {"pp_world_load_snapshot", file, strlen(folder) + 1, -1, true};
    cJSON *root = NULL;
    pp_status st = parse_json(&c, &root);
    if (st == PP_OK)
        st = build_snapshot(&c, root, out);
    json_done(&c, root);
    return st;
}
