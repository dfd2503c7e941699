/* Snapshots: a world's whole state in a folder, world.json plus PNG planes, written under a temporary
 * name and swapped in by rename, so a crash never leaves half a snapshot. Everything is saved exactly
 * (doubles printed to read back bit for bit, ODE's state as it was set, the slot tables and the bodies'
 * creation order, which ODE's body list follows), so a loaded world steps on as the saved one would. */
#define _GNU_SOURCE /* renameat2 */
#include "alloc.h"
#include "camera.h"
#include "forces.h"
#include "files.h"
#include "handle.h"
#include "joint.h"
#include "image.h"
#include "scene_json.h"
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

#define SNAPSHOT_FORMAT "physpix-snapshot"
#define SNAPSHOT_VERSION 1

static const char *const event_names[] = {"",           "split",        "destroyed",  "contact_begin",
                                          "contact_end", "sensor_begin", "sensor_end", "joint_broken", NULL};

/* ---- writing ------------------------------------------------------------------------------------ */

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

/* A joint's state beyond its def, in the order write_joint saves it: local anchors (4), axis in a (2), ref, length,
 * slider offset, the last attach's frame (7) and ODE poses (6), ODE's feedback (6), pinned flags (2). */
enum { JOINT_STATE_DOUBLES = 31 };

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

/* The pairs touching at the last substep, which the next one's events and one-way platforms compare with:
 * the touching and the resting ones, merged in their one sorted order. */
static bool write_touching(const world *wd, cJSON *root)
{
    cJSON *arr = cJSON_CreateArray();
    bool ok = arr != NULL;
    for (int32_t i = 0, j = 0; ok && i + j < wd->touch_count + wd->resting_count;) {
        const bool from_touching =
            j == wd->resting_count || (i < wd->touch_count && touch_order(&wd->touching[i], &wd->resting[j]) < 0);
        const touch *t = from_touching ? &wd->touching[i++] : &wd->resting[j++];
        cJSON *e = cJSON_CreateObject();
        ok = e && cJSON_AddItemToArray(arr, e) && add(e, "a", json_handle(handle_saved(t->a))) &&
             add(e, "b", json_handle(handle_saved(t->b))) &&
             add(e, "flags", json_number(t->flags, false)) && add(e, "anchor", json_doubles(t->anchor, 3));
    }
    if (!ok)
        cJSON_Delete(arr);
    return ok && add(root, "touching", arr);
}

/* A held pair's contact as 15 numbers: point, normal, depth, pixel count, impulse, then both bodies' centres of
 * mass and rotations when the raster found it. */
enum { HELD_NUMBERS = 15 };

/* The pairs held from step to step (carry.h), in their order: the next step carries them uncollided. */
static bool write_held(const world *wd, cJSON *root)
{
    const carry *c = &wd->carry;
    cJSON *arr = cJSON_CreateArray();
    bool ok = arr != NULL;
    for (int32_t i = 0; ok && i < c->pair_count; i++) {
        const carried_pair *p = &c->pairs[i];
        const carried_contact *first = &c->contacts[p->first];
        cJSON *e = cJSON_CreateObject(), *points = NULL;
        ok = e && cJSON_AddItemToArray(arr, e) && add(e, "a", json_handle(handle_saved(first->c.a.id))) &&
             add(e, "b", json_handle(handle_saved(first->c.b.id))) && add(e, "stack", cJSON_CreateBool(p->stack)) &&
             add(e, "contacts", points = cJSON_CreateArray());
        for (int32_t k = 0; ok && k < p->count; k++) {
            const carried_contact *cc = &first[k];
            const double v[HELD_NUMBERS] = {cc->c.point.x, cc->c.point.y, cc->c.normal.x, cc->c.normal.y, cc->c.depth,
                                            cc->c.pixel_count, cc->c.normal_impulse, cc->com_a.x, cc->com_a.y,
                                            cc->com_b.x, cc->com_b.y, cc->cos_a, cc->sin_a, cc->cos_b, cc->sin_b};
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
    const int parent = open(parent_path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    const int tmp_fd = parent >= 0 ? files_make_temp_folder(parent, base, tmp, sizeof tmp) : -1;
    if (tmp_fd < 0) {
        st = pp_fail(PP_ERR_IO, "%s: cannot create a folder beside '%s': %s", fn, dest, strerror(errno));
        if (parent >= 0)
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

/* ---- reading ------------------------------------------------------------------------------------ */

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

/* A body handle as saved (handle.h), made one of the loaded world's. */
static pp_status read_body_handle(const json_ctx *c, const cJSON *obj, const char *where, const char *key,
                                  bool optional, const world *wd, uint64_t *out)
{
    uint64_t saved = 0;
    pp_status st = read_handle(c, obj, where, key, optional, &saved);
    if (!st && !handle_from_saved(saved, wd->tag, out))
        st = json_fail(c, PP_ERR_FORMAT, where, key, "no body handle has that slot and generation");
    return st;
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
    bd->angle = pose[2], bd->cos_a = cos(pose[2]), bd->sin_a = sin(pose[2]);
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
            !(st = read_body_handle(c, it, where, "joint", true, wd, &ev.joint.id))) {
            ev.type = (pp_event_type)type;
            if (!type)
                st = json_fail(c, PP_ERR_FORMAT, where, "type", "missing");
            else if (!(st = restore_event_contact(c, it, where, &ev)) && !(st = world_reserve_events(wd, 1, c->fn)))
                world_queue_event(wd, ev);
        }
    }
    return st;
}

/* The touching pairs; absent in snapshots from before contact events. */
static pp_status restore_touching(const json_ctx *c, const cJSON *root, world *wd)
{
    static const char *const keys[] = {"a", "b", "flags", "anchor", NULL};
    const cJSON *arr;
    pp_status st = read_section(c, root, "", "touching", true, &arr);
    const int32_t n = arr ? cJSON_GetArraySize(arr) : 0;
    if (st || n == 0)
        return st;
    if (!ARRAY_RESERVE(wd->touching, wd->touch_capacity, n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d touching pairs", c->fn, (int)n);
    char where[32];
    int32_t i = 0;
    for (const cJSON *it = arr->child; it && st == PP_OK; it = it->next, i++) {
        snprintf(where, sizeof where, "touching[%d]", (int)i);
        touch *t = &wd->touching[i];
        int64_t flags = 0;
        if (!(st = check_keys(c, it, where, NULL, keys)) &&
            !(st = read_body_handle(c, it, where, "a", false, wd, &t->a)) &&
            !(st = read_body_handle(c, it, where, "b", false, wd, &t->b)))
            st = read_required_int(c, it, where, "flags", 0, TOUCH_FLAGS, &flags);
        t->flags = (uint32_t)flags, t->reserved = 0;
        /* Before friction anchors, only pairs with events, sensors or one-way bodies were kept, and every
         * contact pair kept with events on had begun. Such a pair anchors at the next substep. */
        const bool anchored = cJSON_GetObjectItemCaseSensitive(it, "anchor") != NULL;
        if (!st && anchored)
            st = read_doubles(c, it, where, "anchor", t->anchor, 3);
        else if (!st) {
            t->flags |= TOUCH_UNANCHORED;
            if (wd->def.contact_events && !(t->flags & (TOUCH_SENSOR | TOUCH_PASSING)))
                t->flags |= TOUCH_BEGUN;
        }
        /* touch_find expects a in the lower slot */
        if (!st && (t->a == 0 || t->b == 0))
            st = json_fail(c, PP_ERR_FORMAT, where, t->a ? "b" : "a", "expected a body, not 0");
        if (!st && handle_slot(t->a) > handle_slot(t->b))
            st = json_fail(c, PP_ERR_FORMAT, where, "a", "must be in a lower slot than b");
    }
    if (st)
        return st;
    wd->touch_count = n;
    touch_sort(wd->touching, n);
    return PP_OK;
}

/* One held pair's contacts, in order, into the carry's arrays (room made). */
static pp_status restore_held_contacts(const json_ctx *c, const cJSON *arr, const char *where, world *wd,
                                       pp_body a, pp_body b)
{
    carry *cy = &wd->carry;
    int32_t k = 0;
    char at[64];
    for (const cJSON *it = arr->child; it; it = it->next, k++) {
        snprintf(at, sizeof at, "%s.contacts[%d]", where, (int)k);
        double v[HELD_NUMBERS];
        bool ok = cJSON_IsArray(it) && cJSON_GetArraySize(it) == HELD_NUMBERS;
        for (int i = 0; ok && i < HELD_NUMBERS; i++) {
            const cJSON *x = cJSON_GetArrayItem(it, i);
            ok = cJSON_IsNumber(x) && fabs(x->valuedouble) <= FLT_MAX;
            v[i] = ok ? x->valuedouble : 0;
        }
        /* A unit normal, a count of pixels, rotations as cosines and sines: anything else is no saved contact. */
        ok = ok && fabs(hypot(v[2], v[3]) - 1) < 1e-3 && v[5] >= 0 && v[5] <= INT32_MAX && v[5] == floor(v[5]) &&
             fabs(hypot(v[11], v[12]) - 1) < 1e-6 && fabs(hypot(v[13], v[14]) - 1) < 1e-6;
        if (!ok)
            return json_fail(c, PP_ERR_FORMAT, at, NULL,
                             "expected %d finite numbers: point, unit normal, depth, pixel count, impulse, two centres "
                             "of mass, two (cos, sin) pairs",
                             HELD_NUMBERS);
        carried_contact *cc = &cy->contacts[cy->contact_count++];
        cc->c = (pp_contact){a, b, {(float)v[0], (float)v[1]}, {(float)v[2], (float)v[3]}, (float)v[4],
                             (int32_t)v[5], (float)v[6], 0};
        cc->com_a = dv(v[7], v[8]), cc->com_b = dv(v[9], v[10]);
        cc->cos_a = v[11], cc->sin_a = v[12], cc->cos_b = v[13], cc->sin_b = v[14];
    }
    return PP_OK;
}

/* The held pairs; absent in snapshots from before pairs were held from step to step. */
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
    carry *cy = &wd->carry;
    if (!ARRAY_RESERVE(cy->pairs, cy->pair_capacity, n) ||
        !ARRAY_RESERVE(cy->by_slots, cy->by_slots_capacity, n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d held pairs", c->fn, (int)n);
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
        if (!body_find(wd, (pp_body){a}) || !body_find(wd, (pp_body){b}) || handle_slot(a) >= handle_slot(b))
            st = json_fail(c, PP_ERR_FORMAT, where, "a", "expected two live bodies, a in the lower slot");
        else if (!cJSON_IsBool(stack))
            st = json_fail(c, PP_ERR_FORMAT, where, "stack", "expected true or false");
        else if (!cJSON_IsArray(points) || cJSON_GetArraySize(points) < 1 ||
                 cJSON_GetArraySize(points) > PP_MAX_CONTACTS_PER_PAIR)
            st = json_fail(c, PP_ERR_FORMAT, where, "contacts", "expected 1 to %d contacts", PP_MAX_CONTACTS_PER_PAIR);
        if (st)
            break;
        const int32_t first = cy->contact_count;
        if (!ARRAY_RESERVE(cy->contacts, cy->contact_capacity, first + cJSON_GetArraySize(points))) {
            st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d held pairs", c->fn, (int)n);
            break;
        }
        if ((st = restore_held_contacts(c, points, where, wd, (pp_body){a}, (pp_body){b})))
            break;
        cy->pairs[cy->pair_count++] = (carried_pair){handle_slot(a), handle_slot(b), first, cy->contact_count - first,
                                                     (int32_t)wd->def.substeps - 1, false, false, true,
                                                     cJSON_IsTrue(stack)};
    }
    if (!st && !carry_index(cy))
        st = json_fail(c, PP_ERR_FORMAT, "held", NULL, "a pair is held twice");
    if (st)
        cy->pair_count = cy->contact_count = 0;
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
        (st = read_body_handle(c, obj, where, "handle", false, wd, &id)) ||
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
    if ((st = joint_restore(wd, jt, v + 22)))
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
        st = joint_table_restore(wd, gens, n, free_slots, n_free);
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
