/* Saving a snapshot (pp_world_save_snapshot): the writers of world.json's sections and of each body's PNG
 * planes, the check that every number can be saved, and the folder steps, from the temporary folder to the
 * rename that puts it in place (snapshot.h says what a snapshot is). */
#define _GNU_SOURCE /* renameat2 */
#include "alloc.h"
#include "camera.h"
#include "files.h"
#include "handle.h"
#include "joint.h"
#include "image.h"
#include "scene_json.h"
#include "snapshot.h"
#include "status.h"
#include "world.h"

#include <errno.h>
#include <fcntl.h>
#include <float.h>
#include <inttypes.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

const char *const event_names[] = {"",           "split",        "destroyed",  "contact_begin",
                                   "contact_end", "sensor_begin", "sensor_end", "joint_broken", NULL};

static bool add(cJSON *obj, const char *key, cJSON *item)
{
    if (!item || !cJSON_AddItemToObject(obj, key, item)) {
        cJSON_Delete(item);
        return false;
    }
    return true;
}

static cJSON *json_doubles(const double *v, int n)
{
    cJSON *arr = cJSON_CreateArray();
    for (int i = 0; arr && i < n; i++) {
        cJSON *x = json_number(v[i], false);
        if (!x || !cJSON_AddItemToArray(arr, x)) {
            cJSON_Delete(x);
            cJSON_Delete(arr);
            return NULL;
        }
    }
    return arr;
}

/* Handles as hex text: 64-bit ids do not fit a JSON number exactly. A body's is saved without its world. */
static cJSON *json_handle(uint64_t id)
{
    char text[24];
    snprintf(text, sizeof text, "0x%016" PRIx64, id);
    return cJSON_CreateString(text);
}

/* The temporary folder a snapshot is written into: every file is made through its descriptor. */
typedef struct save_dir {
    int fd;
    const char *shown; /* its path, for messages */
} save_dir;

/* A new file of the folder (never through a link, never over an entry); its path for messages into shown. */
static int create_file(const save_dir *dir, const char *name, char *shown, size_t size)
{
    snprintf(shown, size, "%s/%s", dir->shown, name);
    const int fd = files_create(dir->fd, name);
    if (fd < 0)
        pp_fail(PP_ERR_IO, "pp_world_save_snapshot: cannot create '%s': %s", shown, strerror(errno));
    return fd;
}

/* Flush a written file to disk and close it; st is how the writing went. */
static pp_status close_file(int fd, const char *shown, pp_status st)
{
    if (st == PP_OK && fsync(fd) != 0)
        st = pp_fail(PP_ERR_IO, "pp_world_save_snapshot: cannot flush '%s' to disk: %s", shown, strerror(errno));
    if (close(fd) != 0 && st == PP_OK)
        st = pp_fail(PP_ERR_IO, "pp_world_save_snapshot: cannot write '%s': %s", shown, strerror(errno));
    return st;
}

static pp_status write_png(const save_dir *dir, const char *name, const uint8_t *rgba, int32_t w, int32_t h)
{
    char shown[PATH_MAX + NAME_MAX + 64];
    const int fd = create_file(dir, name, shown, sizeof shown);
    if (fd < 0)
        return PP_ERR_IO;
    return close_file(fd, shown, image_save_fd(fd, "pp_world_save_snapshot", shown, rgba, w, h));
}

/* One body's planes as PNG files: mask (opaque white where solid), weights (gray), sprite. */
static pp_status write_planes(const save_dir *dir, const body *bd, cJSON *obj)
{
    const pp_raster *r = &bd->raster;
    const size_t n = (size_t)r->width * (size_t)r->height;
    uint8_t *rgba = pp_malloc(n * 4);
    if (!rgba)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_save_snapshot: no memory for a %d × %d body", (int)r->width,
                       (int)r->height);
    pp_status st = PP_OK;
    char name[48];
    for (int plane = 0; plane < 3 && st == PP_OK; plane++) {
        static const char *const kinds[] = {"mask", "weights", "sprite"};
        if ((plane == 1 && !r->weights) || (plane == 2 && !bd->sprite))
            continue;
        for (int32_t y = 0; y < r->height; y++)
            for (int32_t x = 0; x < r->width; x++) {
                uint8_t *p = rgba + 4 * ((size_t)y * r->width + x);
                const uint8_t v = plane == 0 ? (raster_solid(r, x, y) ? 255 : 0) : (uint8_t)raster_weight(r, x, y);
                p[0] = p[1] = p[2] = v;
                p[3] = plane == 0 ? v : 255;
            }
        snprintf(name, sizeof name, "body%u_%s.png", (unsigned)bd->index, kinds[plane]);
        st = write_png(dir, name, plane == 2 ? bd->sprite : rgba, r->width, r->height);
        if (st == PP_OK && !add(obj, kinds[plane], cJSON_CreateString(name)))
            st = pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_save_snapshot: no memory");
    }
    pp_free(rgba);
    return st;
}

/* A body: its settings as a scene writes them, its planes, and its exact state. */
static pp_status write_body(const save_dir *dir, const body *bd, cJSON *arr)
{
    pp_body_def d = pp_body_def_default();
    d.type = bd->type;
    d.position = (pp_vec2){(float)bd->pos.x, (float)bd->pos.y};
    d.angle = (float)bd->angle;
    d.custom_pivot = 1;
    d.pivot = (pp_vec2){(float)bd->pivot.x, (float)bd->pivot.y};
    d.density = (float)bd->density, d.friction = (float)bd->friction, d.restitution = (float)bd->restitution;
    d.linear_damping = (float)bd->linear_damping, d.angular_damping = (float)bd->angular_damping;
    d.category_bits = bd->category_bits, d.mask_bits = bd->mask_bits;
    d.fixed_rotation = bd->fixed_rotation, d.detach_islands = bd->detach_islands;
    d.bullet = bd->bullet, d.is_sensor = bd->is_sensor, d.one_way = bd->one_way;
    d.one_way_direction = (pp_vec2){(float)bd->one_way_dir.x, (float)bd->one_way_dir.y};
    cJSON *obj = body_settings_to_json(&d);
    if (!obj || !cJSON_AddItemToArray(arr, obj)) {
        cJSON_Delete(obj);
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_save_snapshot: no memory");
    }
    cJSON *state = cJSON_CreateObject();
    const double pose[5] = {bd->pos.x, bd->pos.y, bd->angle, bd->pivot.x, bd->pivot.y};
    bool ok = add(obj, "handle", json_handle(handle_saved(bd->handle.id))) &&
              add(obj, "serial", json_number((double)bd->serial, false)) &&
              add(obj, "state", state) && add(state, "pose", json_doubles(pose, 5)) &&
              add(state, "user_data", json_handle(bd->user_data)) && add(state, "slow_time", json_number(bd->slow_time, false));
    if (ok && bd->sb.body) {
        solver_exact_state s;
        solver_body_save(&bd->sb, &s);
        const double ode[6] = {s.px, s.py, s.rotation_angle, s.vx, s.vy, s.wz};
        ok = add(state, "ode", json_doubles(ode, 6)) && add(state, "awake", cJSON_CreateBool(s.enabled));
    }
    if (ok && bd->forced) { /* only then, so that a snapshot without forces is as before */
        const double forces[4] = {bd->force.x, bd->force.y, bd->torque, bd->gravity_scale};
        ok = add(state, "forces", json_doubles(forces, 4));
    }
    if (!ok)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "pp_world_save_snapshot: no memory");
    return write_planes(dir, bd, obj);
}

static int joint_state(const joint *jt, double *v)
{
    const double s[JOINT_STATE_DOUBLES] = {
        jt->local_a.x, jt->local_a.y, jt->local_b.x, jt->local_b.y, jt->axis_local.x, jt->axis_local.y, jt->ref,
        jt->length, jt->slider_offset, jt->frame_a.x, jt->frame_a.y, jt->frame_b.x, jt->frame_b.y, jt->frame_axis.x,
        jt->frame_axis.y, jt->frame_angle, jt->at_a.px, jt->at_a.py, jt->at_a.rotation_angle, jt->at_b.px,
        jt->at_b.py, jt->at_b.rotation_angle, 0, 0, 0, 0, 0, 0, jt->pinned_a, jt->pinned_b, 0,
    };
    memcpy(v, s, sizeof s);
    solver_joint_feedback(&jt->sj, v + 22);
    return JOINT_STATE_DOUBLES - 1;
}

/* A joint: its def as a scene writes it, its type, handle and bodies, and its exact state. */
static bool write_joint(const joint *jt, cJSON *arr)
{
    double v[JOINT_STATE_DOUBLES];
    const int n = joint_state(jt, v);
    cJSON *obj = fields_to_json(joint_fields, &jt->def);
    if (!obj || !cJSON_AddItemToArray(arr, obj)) {
        cJSON_Delete(obj);
        return false;
    }
    return add(obj, "type", cJSON_CreateString(joint_type_names[jt->def.type])) &&
           add(obj, "handle", json_handle(handle_saved(jt->handle.id))) &&
           (!jt->def.body_a.id || add(obj, "body_a", json_handle(handle_saved(jt->def.body_a.id)))) &&
           (!jt->def.body_b.id || add(obj, "body_b", json_handle(handle_saved(jt->def.body_b.id)))) &&
           add(obj, "state", json_doubles(v, n)) && add(obj, "dirty", cJSON_CreateBool(jt->dirty));
}

static int by_attach(const void *a, const void *b)
{
    const uint64_t x = (*(const joint *const *)a)->attach_order, y = (*(const joint *const *)b)->attach_order;
    return (x > y) - (x < y);
}

/* The joint table and the joints in the order they were last attached, the order ODE lists each body's joints
 * in; nothing for a world that never had one, so that its snapshot reads as before joints. */
static bool write_joints(const world *wd, cJSON *root)
{
    const joint_table *t = &wd->joints;
    if (t->ids.capacity == 0)
        return true;
    cJSON *gens = cJSON_CreateArray(), *free_slots = cJSON_CreateArray(), *arr = cJSON_CreateArray();
    joint **live = pp_malloc(((size_t)t->ids.live + 1) * sizeof *live);
    bool ok = gens && free_slots && arr && live;
    int32_t n = 0;
    for (int32_t i = 0; ok && i < t->ids.capacity; i++) {
        ok = cJSON_AddItemToArray(gens, json_number(t->ids.generations[i], false));
        if (t->items[i])
            live[n++] = t->items[i];
    }
    for (int32_t i = 0; ok && i < t->ids.free_count; i++)
        ok = cJSON_AddItemToArray(free_slots, json_number(t->ids.free_slots[i], false));
    if (ok)
        qsort(live, (size_t)n, sizeof *live, by_attach);
    for (int32_t i = 0; ok && i < n; i++)
        ok = write_joint(live[i], arr);
    pp_free(live);
    if (!ok) {
        cJSON_Delete(gens), cJSON_Delete(free_slots), cJSON_Delete(arr);
        return false;
    }
    /* Each add is made (and frees its item if it fails), so that nothing leaks. */
    const bool g = add(root, "joint_generations", gens), f = add(root, "joint_free_slots", free_slots);
    const bool j = add(root, "joints", arr);
    return g && f && j;
}

static int by_serial(const void *a, const void *b)
{
    const uint64_t x = (*(const body *const *)a)->serial, y = (*(const body *const *)b)->serial;
    return (x > y) - (x < y);
}

/* The slot tables, so handles and future slots come out as they would have. */
static bool write_slots(const world *wd, cJSON *root)
{
    cJSON *gens = cJSON_CreateArray(), *free_slots = cJSON_CreateArray();
    bool ok = gens && free_slots;
    for (int32_t i = 0; ok && i < wd->body_ids.capacity; i++)
        ok = cJSON_AddItemToArray(gens, json_number(wd->body_ids.generations[i], false));
    for (int32_t i = 0; ok && i < wd->body_ids.free_count; i++)
        ok = cJSON_AddItemToArray(free_slots, json_number(wd->body_ids.free_slots[i], false));
    if (!ok) {
        cJSON_Delete(gens);
        cJSON_Delete(free_slots);
        return false;
    }
    return add(root, "generations", gens) && add(root, "free_slots", free_slots);
}

static bool write_edits_and_events(const world *wd, cJSON *root)
{
    cJSON *edits = cJSON_CreateArray(), *events = cJSON_CreateArray();
    timed_edit *order = timed_edits_in_order(&wd->edits);
    bool ok = edits && events && order;
    for (int32_t i = 0; ok && i < wd->edits.count; i++) {
        /* An edit whose body is gone would only be skipped when due, and pp_world_schedule_edit refuses its
         * handle on load: saving it made a snapshot that could not be loaded (found by fuzz_api). */
        if (order[i].edit.body.id != 0 && !body_find(wd, order[i].edit.body))
            continue;
        /* pp_world_schedule_edit takes a time before 0 (due at once), world.json's reader does not (fuzz_api).
         * At 0 it is as due, and the list's order, which loading keeps among equal times, is unchanged. */
        pp_timed_edit ed = order[i].edit;
        ed.time = ed.time < 0 ? 0 : ed.time;
        cJSON *e = edit_to_json(&ed);
        ok = e && cJSON_AddItemToArray(edits, e) &&
             (ed.body.id == 0 || add(e, "body", json_handle(handle_saved(ed.body.id))));
    }
    pp_free(order);
    for (int32_t i = 0; ok && i < wd->events.count; i++) {
        const pp_event *ev = &wd->events.items[i];
        cJSON *e = cJSON_CreateObject();
        ok = e && cJSON_AddItemToArray(events, e) && add(e, "type", cJSON_CreateString(event_names[ev->type])) &&
             add(e, "body", json_handle(handle_saved(ev->body.id))) &&
             add(e, "other", json_handle(handle_saved(ev->other.id)));
        if (ok && ev->type == PP_EVENT_JOINT_BROKEN)
            ok = add(e, "joint", json_handle(handle_saved(ev->joint.id)));
        if (ok && (ev->type == PP_EVENT_CONTACT_BEGIN || ev->type == PP_EVENT_SENSOR_BEGIN)) {
            const double point[2] = {ev->point.x, ev->point.y}, normal[2] = {ev->normal.x, ev->normal.y};
            ok = add(e, "point", json_doubles(point, 2)) && add(e, "normal", json_doubles(normal, 2)) &&
                 add(e, "approach_speed", json_number(ev->approach_speed, true));
        }
    }
    if (!ok)
        cJSON_Delete(edits);
    if (!ok || !add(root, "edits", edits)) { /* add deletes what it could not add */
        cJSON_Delete(events);
        return false;
    }
    return add(root, "events", events);
}

/* The contact table's pairs, in its order, which the next substep's events and one-way platforms compare with,
 * each with its manifold (a sleeping pair lists it). A pair whose body is gone ends at the next substep: it is
 * not written, and so ends silently. */
static bool write_touching(const world *wd, cJSON *root)
{
    const contact_table *ts = &wd->table;
    cJSON *arr = cJSON_CreateArray();
    bool ok = arr != NULL;
    for (int32_t i = 0; ok && i < ts->count; i++) {
        const contact_record *t = &ts->records[i];
        if (t->flags & CT_GONE)
            continue;
        cJSON *e = cJSON_CreateObject(), *points = NULL;
        ok = e && cJSON_AddItemToArray(arr, e) && add(e, "a", json_handle(handle_saved(t->a))) &&
             add(e, "b", json_handle(handle_saved(t->b))) &&
             add(e, "flags", json_number(t->flags, false)) && add(e, "anchor", json_doubles(t->anchor, 3)) &&
             add(e, "points", points = cJSON_CreateArray());
        for (int32_t k = 0; ok && k < t->point_count; k++) {
            const pp_contact *p = &t->points[k];
            const double v[SAVED_CONTACT_NUMBERS] = {p->point.x, p->point.y, p->normal.x, p->normal.y, p->depth,
                                                     p->pixel_count, p->normal_impulse};
            cJSON *nums = json_doubles(v, SAVED_CONTACT_NUMBERS);
            ok = nums && cJSON_AddItemToArray(points, nums);
            if (!ok)
                cJSON_Delete(nums);
        }
    }
    if (!ok)
        cJSON_Delete(arr);
    return ok && add(root, "touching", arr);
}

/* The pairs held from step to step (carry.h), in their order: the next step carries them uncollided. */
static bool write_held(const world *wd, cJSON *root)
{
    const contact_table *t = &wd->table;
    cJSON *arr = cJSON_CreateArray();
    bool ok = arr != NULL;
    for (int32_t i = 0; ok && i < t->carry_count; i++) {
        if (t->carry_order[i] < 0)
            continue; /* ended: a step never leaves one (carry_end_step packs the order) */
        const contact_record *r = &t->records[t->carry_order[i]];
        const carried_pose *q = &r->carry_pose;
        cJSON *e = cJSON_CreateObject(), *points = NULL;
        ok = e && cJSON_AddItemToArray(arr, e) && add(e, "a", json_handle(handle_saved(r->a))) &&
             add(e, "b", json_handle(handle_saved(r->b))) &&
             add(e, "stack", cJSON_CreateBool((r->carry_flags & CARRY_STACK) != 0)) &&
             add(e, "contacts", points = cJSON_CreateArray());
        for (int32_t k = 0; ok && k < r->carry_count; k++) {
            const pp_contact *c = &r->carry_points[k];
            const double v[HELD_NUMBERS] = {c->point.x, c->point.y, c->normal.x, c->normal.y, c->depth,
                                            c->pixel_count, c->normal_impulse, q->com_a.x, q->com_a.y,
                                            q->com_b.x, q->com_b.y, q->cos_a, q->sin_a, q->cos_b, q->sin_b};
            cJSON *nums = json_doubles(v, HELD_NUMBERS);
            ok = nums && cJSON_AddItemToArray(points, nums);
            if (!ok)
                cJSON_Delete(nums);
        }
    }
    if (!ok)
        cJSON_Delete(arr);
    return ok && add(root, "held", arr);
}

/* Whether world.json can hold every number (JSON has no inf or NaN) and the loader would take it back (its
 * poses, velocities and event points are within ±FLT_MAX); PP_ERR_LIMIT naming the first that is not. */
static pp_status check_savable(const world *wd)
{
    static const char *fn = "pp_world_save_snapshot";
    for (int32_t i = 0; i < wd->joints.ids.capacity; i++) {
        const joint *jt = wd->joints.items[i];
        double v[JOINT_STATE_DOUBLES];
        for (int k = 0; jt && k < joint_state(jt, v); k++)
            if (!(fabs(v[k]) <= FLT_MAX))
                return pp_fail(PP_ERR_LIMIT, "%s: joint %#llx holds %g, which a snapshot cannot; nothing was written",
                               fn, (unsigned long long)jt->handle.id, v[k]);
    }
    for (int32_t i = 0; i < wd->body_ids.capacity; i++) {
        const body *bd = wd->bodies[i];
        if (!bd)
            continue;
        solver_exact_state s = {0};
        if (bd->sb.body)
            solver_body_save(&bd->sb, &s);
        const double v[] = {bd->pos.x, bd->pos.y, bd->angle, bd->pivot.x, bd->pivot.y, s.px, s.py, s.rotation_angle,
                            s.vx, s.vy, s.wz, bd->slow_time};
        for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
            if (!(fabs(v[k]) <= FLT_MAX))
                return pp_fail(PP_ERR_LIMIT, "%s: body %#llx has a %s of %g, which a snapshot cannot hold; nothing "
                               "was written", fn, (unsigned long long)bd->handle.id,
                               k < 5 ? "pose" : k < 11 ? "solver state" : "sleep timer", v[k]);
    }
    for (int32_t i = 0; i < wd->events.count; i++) {
        const pp_event *e = &wd->events.items[i];
        const float v[] = {e->point.x, e->point.y, e->normal.x, e->normal.y, e->approach_speed};
        for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
            if (!isfinite(v[k]))
                return pp_fail(PP_ERR_LIMIT, "%s: event %d has a number that is not finite (%g); nothing was written",
                               fn, (int)i, v[k]);
    }
    if (!isfinite(wd->time))
        return pp_fail(PP_ERR_LIMIT, "%s: the world's time is %g s; nothing was written", fn, wd->time);
    return PP_OK;
}

/* world.json's top level, then every body in creation order. */
static pp_status write_world(const save_dir *dir, const world *wd, cJSON *root)
{
    static const char *fn = "pp_world_save_snapshot";
    const pp_camera cam = camera_of(wd);
    bool ok = add(root, "format", cJSON_CreateString(SNAPSHOT_FORMAT)) &&
              add(root, "version", json_number(SNAPSHOT_VERSION, false)) &&
              add(root, "world", world_def_to_json(&wd->def)) && add(root, "camera", camera_to_json(&cam)) &&
              add(root, "time", json_number(wd->time, false)) &&
              add(root, "solver_steps", json_number((double)solver_get_steps(wd->solver), false)) &&
              add(root, "next_serial", json_number((double)wd->next_serial, false)) && write_slots(wd, root) &&
              write_edits_and_events(wd, root) && write_touching(wd, root) && write_held(wd, root) &&
              write_joints(wd, root);
    body **live = ok ? pp_malloc(((size_t)wd->body_ids.live + 1) * sizeof *live) : NULL;
    cJSON *arr = live ? cJSON_CreateArray() : NULL;
    if (!live || !add(root, "bodies", arr)) {
        pp_free(live);
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory", fn);
    }
    int32_t n = 0;
    for (int32_t i = 0; i < wd->body_ids.capacity; i++)
        if (wd->bodies[i])
            live[n++] = wd->bodies[i];
    qsort(live, (size_t)n, sizeof *live, by_serial);
    pp_status st = PP_OK;
    for (int32_t i = 0; i < n && st == PP_OK; i++)
        st = write_body(dir, live[i], arr);
    pp_free(live);
    return st;
}

static pp_status write_text(const save_dir *dir, const char *name, const char *text)
{
    char shown[PATH_MAX + NAME_MAX + 64];
    const int fd = create_file(dir, name, shown, sizeof shown);
    if (fd < 0)
        return PP_ERR_IO;
    pp_status st = PP_OK;
    for (size_t done = 0, n = strlen(text); done < n && st == PP_OK;) {
        const ssize_t k = write(fd, text + done, n - done);
        if (k > 0)
            done += (size_t)k;
        else if (k == 0 || errno != EINTR)
            st = pp_fail(PP_ERR_IO, "pp_world_save_snapshot: cannot write '%s': %s", shown, strerror(errno));
    }
    return close_file(fd, shown, st);
}

/* Put the finished folder (tmp in parent, open on tmp_fd) in place as base: a rename, or over an older
 * snapshot an exchange, then the old one's removal. Everything goes through parent and the folders'
 * descriptors, so a link planted at base, tmp or the old folder is never followed. */
static pp_status publish(int parent, const char *tmp, int tmp_fd, const char *base, const char *dest,
                         const char *tmp_shown)
{
    static const char *fn = "pp_world_save_snapshot";
    if (!files_is_folder(parent, tmp, tmp_fd))
        return pp_fail(PP_ERR_IO, "%s: '%s' was replaced while it was written; not saved", fn, tmp_shown);
    /* The parent is flushed after a rename so the new name survives a crash; best effort, the save is done. */
    if (renameat(parent, tmp, parent, base) == 0) {
        fsync(parent);
        return PP_OK;
    }
    if (errno != EEXIST && errno != ENOTEMPTY && errno != ENOTDIR && errno != EISDIR)
        return pp_fail(PP_ERR_IO, "%s: cannot rename '%s' to '%s': %s", fn, tmp_shown, dest, strerror(errno));
    /* Something is there: replaced only if it is a folder, not a link, holding a regular world.json. */
    const int old = openat(parent, base, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    struct stat sb;
    if (old < 0 || fstatat(old, "world.json", &sb, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(sb.st_mode)) {
        if (old >= 0)
            close(old);
        return pp_fail(PP_ERR_IO, "%s: '%s' exists and is not a snapshot; refusing to replace it", fn, dest);
    }
    pp_status st = PP_OK;
    if (renameat2(parent, tmp, parent, base, RENAME_EXCHANGE) != 0) {
        st = pp_fail(PP_ERR_IO, "%s: cannot replace '%s': %s", fn, dest, strerror(errno));
    } else if (!files_is_folder(parent, tmp, old)) {
        /* base was swapped for something else since the check: put that back, and the caller removes ours. */
        renameat2(parent, tmp, parent, base, RENAME_EXCHANGE);
        st = pp_fail(PP_ERR_IO, "%s: '%s' changed while it was being replaced; left as it was", fn, dest);
    } else {
        fsync(parent);
        if (!files_remove_folder(parent, tmp, old))
            pp_log(2, "physpix: %s: the snapshot replaced at '%s' was not removed whole; what is left is '%s'", fn,
                   dest, tmp_shown);
    }
    close(old);
    return st;
}

PP_API pp_status pp_world_save_snapshot(pp_world w, const char *folder)
{
    static const char *fn = "pp_world_save_snapshot";
    world *wd = world_lookup(w, fn);
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!folder || !folder[0])
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: folder is NULL or empty", fn);
    pp_status st = check_savable(wd); /* before the old snapshot or anything beside it is touched */
    if (st)
        return st;
    char dest[PATH_MAX], parent_path[PATH_MAX], tmp[NAME_MAX + 1], tmp_shown[PATH_MAX + NAME_MAX + 2];
    if (snprintf(dest, sizeof dest, "%s", folder) >= (int)sizeof dest)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: folder path is too long", fn);
    for (size_t n = strlen(dest); n > 1 && dest[n - 1] == '/'; n--)
        dest[n - 1] = '\0';
    /* The folder is the entry base of its parent, and every step below works from the parent's descriptor. */
    const char *slash = strrchr(dest, '/'), *base = slash ? slash + 1 : dest;
    if (!base[0] || strcmp(base, ".") == 0 || strcmp(base, "..") == 0)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: '%s' does not name a folder to create", fn, folder);
    if (slash)
        snprintf(parent_path, sizeof parent_path, "%.*s", slash == dest ? 1 : (int)(slash - dest), dest);
    else
        strcpy(parent_path, ".");
    /* The parent is never created: a mistyped path would otherwise grow a tree of folders. Saying which
     * folder is missing tells the user what to create (or fix) without guessing from the whole path. */
    const int parent = open(parent_path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (parent < 0)
        return pp_fail(PP_ERR_IO, "%s: cannot save '%s': its parent folder '%s' %s", fn, folder, parent_path,
                       errno == ENOENT ? "does not exist" : errno == ENOTDIR ? "is not a folder" : strerror(errno));
    const int tmp_fd = files_make_temp_folder(parent, base, tmp, sizeof tmp);
    if (tmp_fd < 0) {
        st = pp_fail(PP_ERR_IO, "%s: cannot create a folder beside '%s': %s", fn, dest, strerror(errno));
        close(parent);
        return st;
    }
    snprintf(tmp_shown, sizeof tmp_shown, "%.*s%s", (int)(base - dest), dest, tmp);
    const save_dir dir = {tmp_fd, tmp_shown};
    cJSON *root = cJSON_CreateObject();
    st = root ? write_world(&dir, wd, root) : pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory", fn);
    char *text = st == PP_OK ? cJSON_Print(root) : NULL;
    if (st == PP_OK && !text)
        st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory to print world.json", fn);
    if (st == PP_OK)
        st = write_text(&dir, "world.json", text);
    if (st == PP_OK && fsync(tmp_fd) != 0)
        st = pp_fail(PP_ERR_IO, "%s: cannot flush '%s' to disk: %s", fn, tmp_shown, strerror(errno));
    if (st == PP_OK)
        st = publish(parent, tmp, tmp_fd, base, dest, tmp_shown);
    if (st)
        files_remove_folder(parent, tmp, tmp_fd); /* only if what is at tmp is still the folder written */
    close(tmp_fd);
    close(parent);
    cJSON_free(text);
    cJSON_Delete(root);
    return st;
}
