/* The JSON layer shared by scene files and snapshots (see scene_json.h): the path-naming reader,
 * the field tables, exact number printing, PNG bitmaps and whole-file parsing. */
#include "alloc.h"
#include "files.h"
#include "image.h"
#include "scene_json.h"
#include "status.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- reader layer ------------------------------------------------------------------------- */

pp_status json_fail(const json_ctx *c, pp_status st, const char *where, const char *key, const char *fmt, ...)
{
    char reason[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(reason, sizeof reason, fmt, ap);
    va_end(ap);
    const bool dot = where[0] && key && key[0];
    return pp_fail(st, "%s: '%s': %s%s%s: %s", c->fn, c->file, where, dot ? "." : "", key ? key : "", reason);
}

/* Re-raise the failure of a library call under a JSON path, without the call's own "fn: " prefix.
 * A rejected argument is the file's fault, so INVALID_ARGUMENT becomes FORMAT. */
pp_status json_fail_from_last(const json_ctx *c, pp_status st, const char *where, const char *key)
{
    char msg[512];
    const char *last = pp_last_error(), *colon = strstr(last, ": ");
    snprintf(msg, sizeof msg, "%s", colon ? colon + 2 : last);
    /* A file's bad value or a body it names that is not there is a fault of the file. */
    const bool files_fault = st == PP_ERR_INVALID_ARGUMENT || st == PP_ERR_INVALID_HANDLE;
    return json_fail(c, files_fault ? PP_ERR_FORMAT : st, where, key, "%s", msg);
}


static const char *const num_rule_text[] = {
    "expected a finite number", "expected a number > 0", "expected a number ≥ 0", "expected a number in 0..1"};

static bool num_rule_ok(double v, num_rule r)
{
    switch (r) {
    case NUM_POSITIVE: return v > 0;
    case NUM_NONNEG: return v >= 0;
    case NUM_UNIT: return v >= 0 && v <= 1;
    default: return true;
    }
}

/* A JSON number that is finite and, stored as a float, still finite and within the rule. */
static bool json_float(const cJSON *it, num_rule r, float *out)
{
    if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble) || fabs(it->valuedouble) > FLT_MAX)
        return false;
    const float f = (float)it->valuedouble;
    if (!num_rule_ok(f, r))
        return false;
    *out = f;
    return true;
}

pp_status read_float(const json_ctx *c, const cJSON *obj, const char *where, const char *key, num_rule r,
                            float *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (it && !json_float(it, r, out))
        return json_fail(c, PP_ERR_FORMAT, where, key, "%s", num_rule_text[r]);
    return PP_OK;
}

pp_status read_double(const json_ctx *c, const cJSON *obj, const char *where, const char *key, num_rule r,
                             double *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!it)
        return PP_OK;
    if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble) || !num_rule_ok(it->valuedouble, r))
        return json_fail(c, PP_ERR_FORMAT, where, key, "%s", num_rule_text[r]);
    *out = it->valuedouble;
    return PP_OK;
}

/* [x, y]: exactly two finite numbers. */
pp_status read_vec2(const json_ctx *c, const cJSON *obj, const char *where, const char *key, pp_vec2 *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!it)
        return PP_OK;
    pp_vec2 v;
    if (!cJSON_IsArray(it) || cJSON_GetArraySize(it) != 2 || !json_float(cJSON_GetArrayItem(it, 0), NUM_FINITE, &v.x) ||
        !json_float(cJSON_GetArrayItem(it, 1), NUM_FINITE, &v.y))
        return json_fail(c, PP_ERR_FORMAT, where, key, "expected [x, y], two finite numbers");
    *out = v;
    return PP_OK;
}

static bool json_int(const cJSON *it, int64_t lo, int64_t hi, int64_t *out)
{
    if (!cJSON_IsNumber(it))
        return false;
    const double v = it->valuedouble;
    if (!(v >= (double)lo && v <= (double)hi) || v != floor(v))
        return false;
    *out = (int64_t)v;
    return true;
}

pp_status read_int(const json_ctx *c, const cJSON *obj, const char *where, const char *key, int64_t lo,
                          int64_t hi, int64_t *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (it && !json_int(it, lo, hi, out))
        return json_fail(c, PP_ERR_FORMAT, where, key, "expected an integer in %lld..%lld", (long long)lo,
                         (long long)hi);
    return PP_OK;
}

pp_status read_bool(const json_ctx *c, const cJSON *obj, const char *where, const char *key, uint32_t *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!it)
        return PP_OK;
    if (!cJSON_IsBool(it))
        return json_fail(c, PP_ERR_FORMAT, where, key, "expected true or false");
    *out = cJSON_IsTrue(it) ? 1u : 0u;
    return PP_OK;
}

pp_status read_string(const json_ctx *c, const cJSON *obj, const char *where, const char *key,
                             const char **out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!it)
        return PP_OK;
    if (!cJSON_IsString(it) || !it->valuestring[0])
        return json_fail(c, PP_ERR_FORMAT, where, key, "expected a non-empty string");
    *out = it->valuestring;
    return PP_OK;
}

/* An enum by name; names[v] is the name of value v ("" where v has none), NULL-terminated. */
pp_status read_enum(const json_ctx *c, const cJSON *obj, const char *where, const char *key,
                           const char *const *names, int32_t *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!it)
        return PP_OK;
    for (int32_t v = 0; cJSON_IsString(it) && names[v]; v++)
        if (names[v][0] && strcmp(names[v], it->valuestring) == 0) {
            *out = v;
            return PP_OK;
        }
    char list[160] = "";
    for (int32_t v = 0; names[v]; v++)
        if (names[v][0])
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", list[0] ? ", " : "", names[v]);
    if (!cJSON_IsString(it))
        return json_fail(c, PP_ERR_FORMAT, where, key, "expected a string, one of %s", list);
    return json_fail(c, PP_ERR_FORMAT, where, key, "unknown value '%s' (expected one of %s)", it->valuestring, list);
}

/* An optional section: absent is fine, present must be an array or an object as asked. */
pp_status read_section(const json_ctx *c, const cJSON *obj, const char *where, const char *key, bool array,
                              const cJSON **out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    *out = NULL;
    if (it && (array ? !cJSON_IsArray(it) : !cJSON_IsObject(it)))
        return json_fail(c, PP_ERR_FORMAT, where, key, array ? "expected an array" : "expected an object");
    *out = it;
    return PP_OK;
}

/* ---- field tables: one entry reads a field and writes it back --------------------------------- */



#define F_FLOAT(s, m, r) {#m, FK_FLOAT, offsetof(s, m), 4, r, 0, 0, NULL}
#define F_DOUBLE(s, m, r) {#m, FK_DOUBLE, offsetof(s, m), 8, r, 0, 0, NULL}
#define F_VEC2(s, m) {#m, FK_VEC2, offsetof(s, m), 8, NUM_FINITE, 0, 0, NULL}
#define F_BOOL(s, m) {#m, FK_BOOL, offsetof(s, m), 4, NUM_FINITE, 0, 0, NULL}
#define F_INT(s, m, lo, hi) {#m, FK_INT, offsetof(s, m), sizeof(((s *)0)->m), NUM_FINITE, lo, hi, NULL}
#define F_ENUM(s, m, names) {#m, FK_ENUM, offsetof(s, m), 4, NUM_FINITE, 0, 0, names}

static const char *const backend_names[] = {"auto", "cpu", "gpu", NULL};
static const char *const normal_names[] = {"area_gradient", "kernel", NULL};
static const char *const contact_names[] = {"manifold", "centroid", NULL};
static const char *const body_type_names[] = {"dynamic", "static", "kinematic", NULL};
const char *const joint_type_names[] = {"", "revolute", "prismatic", "distance", "weld", "mouse", NULL};
static const char *const edit_type_names[] = {"", "erase", "paint", NULL};

const field world_fields[] = {
    F_VEC2(pp_world_def, gravity),
    F_INT(pp_world_def, substeps, 1, 64),
    F_INT(pp_world_def, solver_iterations, 1, 1000),
    F_BOOL(pp_world_def, exact_solver),
    F_ENUM(pp_world_def, backend, backend_names),
    F_ENUM(pp_world_def, normal_method, normal_names),
    F_ENUM(pp_world_def, contact_mode, contact_names),
    {"raster_stride", FK_STRIDE, offsetof(pp_world_def, raster_stride), 4, NUM_FINITE, 1, 4, NULL},
    F_FLOAT(pp_world_def, pixels_per_meter, NUM_POSITIVE),
    F_FLOAT(pp_world_def, contact_slop, NUM_NONNEG),
    F_FLOAT(pp_world_def, contact_erp, NUM_UNIT),
    F_FLOAT(pp_world_def, contact_cfm, NUM_NONNEG),
    F_FLOAT(pp_world_def, bounce_threshold, NUM_NONNEG),
    F_BOOL(pp_world_def, allow_sleep),
    F_FLOAT(pp_world_def, sleep_linear_speed, NUM_NONNEG),
    F_FLOAT(pp_world_def, sleep_angular_speed, NUM_NONNEG),
    F_FLOAT(pp_world_def, sleep_time, NUM_NONNEG),
    F_BOOL(pp_world_def, continuous),
    F_FLOAT(pp_world_def, max_correction_speed, NUM_POSITIVE),
    F_INT(pp_world_def, worker_threads, 0, 16),
    F_BOOL(pp_world_def, contact_events),
    F_INT(pp_world_def, exact_island_rows, 0, PP_MAX_EXACT_ISLAND_ROWS),
    {NULL, FK_FLOAT, 0, 0, NUM_FINITE, 0, 0, NULL},
};

/* A body's settings: everything in pp_body_def but the bitmap. "pivot" also sets custom_pivot. */
const field body_fields[] = {
    F_ENUM(pp_body_def, type, body_type_names),
    F_VEC2(pp_body_def, position),
    F_FLOAT(pp_body_def, angle, NUM_FINITE),
    F_VEC2(pp_body_def, pivot),
    F_VEC2(pp_body_def, linear_velocity),
    F_FLOAT(pp_body_def, angular_velocity, NUM_FINITE),
    F_FLOAT(pp_body_def, density, NUM_POSITIVE),
    F_FLOAT(pp_body_def, friction, NUM_NONNEG),
    F_FLOAT(pp_body_def, restitution, NUM_UNIT),
    F_FLOAT(pp_body_def, linear_damping, NUM_NONNEG),
    F_FLOAT(pp_body_def, angular_damping, NUM_NONNEG),
    F_INT(pp_body_def, category_bits, 0, UINT32_MAX),
    F_INT(pp_body_def, mask_bits, 0, UINT32_MAX),
    F_BOOL(pp_body_def, fixed_rotation),
    F_INT(pp_body_def, alpha_threshold, 1, 255),
    F_BOOL(pp_body_def, detach_islands),
    F_BOOL(pp_body_def, bullet),
    F_BOOL(pp_body_def, is_sensor),
    F_BOOL(pp_body_def, one_way),
    F_VEC2(pp_body_def, one_way_direction),
    F_INT(pp_body_def, user_data, 0, JSON_MAX_EXACT_INT),
    {NULL, FK_FLOAT, 0, 0, NUM_FINITE, 0, 0, NULL},
};

/* A joint's settings but its type and bodies, which a scene gives by name. */
const field joint_fields[] = {
    F_VEC2(pp_joint_def, anchor_a),
    F_VEC2(pp_joint_def, anchor_b),
    F_VEC2(pp_joint_def, axis),
    F_BOOL(pp_joint_def, collide_connected),
    F_BOOL(pp_joint_def, enable_limit),
    F_FLOAT(pp_joint_def, lower, NUM_FINITE),
    F_FLOAT(pp_joint_def, upper, NUM_FINITE),
    F_BOOL(pp_joint_def, enable_motor),
    F_FLOAT(pp_joint_def, motor_speed, NUM_FINITE),
    F_FLOAT(pp_joint_def, max_motor_force, NUM_NONNEG),
    F_FLOAT(pp_joint_def, min_length, NUM_NONNEG),
    F_FLOAT(pp_joint_def, max_length, NUM_NONNEG),
    F_FLOAT(pp_joint_def, spring_hertz, NUM_NONNEG),
    F_FLOAT(pp_joint_def, spring_damping_ratio, NUM_NONNEG),
    F_FLOAT(pp_joint_def, max_force, NUM_NONNEG),
    F_FLOAT(pp_joint_def, break_force, NUM_NONNEG),
    F_INT(pp_joint_def, user_data, 0, JSON_MAX_EXACT_INT),
    {NULL, FK_FLOAT, 0, 0, NUM_FINITE, 0, 0, NULL},
};

const field camera_fields[] = {
    F_VEC2(pp_camera, center),
    F_FLOAT(pp_camera, zoom, NUM_POSITIVE),
    F_INT(pp_camera, width, 1, PP_MAX_BITMAP_SIDE),
    F_INT(pp_camera, height, 1, PP_MAX_BITMAP_SIDE),
    {NULL, FK_FLOAT, 0, 0, NUM_FINITE, 0, 0, NULL},
};

/* A timed edit but its body, which a scene names and a handle cannot. */
const field edit_fields[] = {
    F_DOUBLE(pp_timed_edit, time, NUM_NONNEG),
    F_ENUM(pp_timed_edit, type, edit_type_names),
    F_VEC2(pp_timed_edit, center),
    F_FLOAT(pp_timed_edit, radius, NUM_NONNEG),
    F_INT(pp_timed_edit, weight, 1, 255),
    {NULL, FK_FLOAT, 0, 0, NUM_FINITE, 0, 0, NULL},
};

static void store_int(void *p, size_t size, int64_t v)
{
    if (size == 8) {
        const uint64_t u = (uint64_t)v;
        memcpy(p, &u, 8);
    } else {
        const uint32_t u = (uint32_t)v; /* int32_t fields hold small non-negative values: same bits */
        memcpy(p, &u, 4);
    }
}

/* Every integer field is non-negative, so uint32_t and int32_t read alike. */
static int64_t load_int(const void *p, size_t size)
{
    if (size == 8) {
        uint64_t u;
        memcpy(&u, p, 8);
        return (int64_t)u;
    }
    uint32_t u;
    memcpy(&u, p, 4);
    return (int64_t)u;
}

/* Read every field of a table present in obj into the struct at s; absent fields keep their value. */
pp_status read_fields(const json_ctx *c, const cJSON *obj, const char *where, const field *t, void *s)
{
    pp_status st = PP_OK;
    for (; t->key && st == PP_OK; t++) {
        char *p = (char *)s + t->offset;
        int64_t i = 0;
        int32_t e;
        switch (t->kind) {
        case FK_FLOAT: st = read_float(c, obj, where, t->key, t->rule, (float *)p); break;
        case FK_DOUBLE: st = read_double(c, obj, where, t->key, t->rule, (double *)p); break;
        case FK_VEC2: st = read_vec2(c, obj, where, t->key, (pp_vec2 *)p); break;
        case FK_BOOL: st = read_bool(c, obj, where, t->key, (uint32_t *)p); break;
        case FK_INT:
            if (cJSON_GetObjectItemCaseSensitive(obj, t->key) && !(st = read_int(c, obj, where, t->key, t->lo, t->hi, &i)))
                store_int(p, t->size, i);
            break;
        case FK_STRIDE: {
            const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, t->key);
            if (it && (!json_int(it, 1, 4, &i) || i == 3))
                st = json_fail(c, PP_ERR_FORMAT, where, t->key, "expected 1, 2 or 4");
            else if (it)
                store_int(p, 4, i);
            break;
        }
        case FK_ENUM:
            e = -1;
            if (!(st = read_enum(c, obj, where, t->key, t->names, &e)) && e >= 0)
                memcpy(p, &e, 4);
            break;
        }
    }
    return st;
}

/* Unknown keys are typos; a key twice is ambiguous. Allowed: the table's keys and `extra` (NULL-terminated). */
pp_status check_keys(const json_ctx *c, const cJSON *obj, const char *where, const field *t,
                            const char *const *extra)
{
    for (const cJSON *it = obj->child; it; it = it->next) {
        bool known = false;
        for (const field *f = t; f && f->key && !known; f++)
            known = strcmp(f->key, it->string) == 0;
        for (const char *const *x = extra; x && *x && !known; x++)
            known = strcmp(*x, it->string) == 0;
        if (!known)
            return json_fail(c, PP_ERR_FORMAT, where, it->string, "unknown key");
        for (const cJSON *o = obj->child; o != it; o = o->next)
            if (strcmp(o->string, it->string) == 0)
                return json_fail(c, PP_ERR_FORMAT, where, it->string, "duplicate key");
    }
    return PP_OK;
}

/* A number as the shortest text that reads back to the same float (or double): cJSON's own printer
 * accepts a 15-digit text within an epsilon of the value, which loses the last bit of a double. Raw items
 * print as they are, so an emitted object is for printing, not for reading in memory. */
cJSON *json_number(double v, bool single)
{
    char text[40];
    for (int digits = single ? 6 : 15; digits <= 17; digits++) {
        snprintf(text, sizeof text, "%.*g", digits, v);
        const double back = strtod(text, NULL);
        if (single ? (float)back == (float)v : back == v)
            break;
    }
    return cJSON_CreateRaw(text);
}

static cJSON *json_vec2(const pp_vec2 *v)
{
    cJSON *arr = cJSON_CreateArray();
    if (!arr || !cJSON_AddItemToArray(arr, json_number(v->x, true)) ||
        !cJSON_AddItemToArray(arr, json_number(v->y, true))) {
        cJSON_Delete(arr);
        return NULL;
    }
    return arr;
}

/* Write every field of a table from the struct at s into obj; false without memory. */
static bool write_fields(cJSON *obj, const field *t, const void *s)
{
    for (; t->key; t++) {
        const char *p = (const char *)s + t->offset;
        cJSON *v = NULL;
        char text[24];
        switch (t->kind) {
        case FK_FLOAT: v = json_number(*(const float *)p, true); break;
        case FK_DOUBLE: v = json_number(*(const double *)p, false); break;
        case FK_VEC2: v = json_vec2((const pp_vec2 *)p); break;
        case FK_BOOL: v = cJSON_CreateBool(*(const uint32_t *)p != 0); break;
        case FK_INT:
        case FK_STRIDE:
            snprintf(text, sizeof text, "%lld", (long long)load_int(p, t->size));
            v = cJSON_CreateRaw(text);
            break;
        case FK_ENUM: {
            int32_t e, n = 0;
            memcpy(&e, p, 4);
            while (t->names[n])
                n++;
            v = cJSON_CreateString(e >= 0 && e < n ? t->names[e] : "");
            break;
        }
        }
        if (!v || !cJSON_AddItemToObject(obj, t->key, v)) {
            cJSON_Delete(v);
            return false;
        }
    }
    return true;
}

/* A new object holding a table's fields of s; NULL without memory. */
cJSON *fields_to_json(const field *t, const void *s)
{
    cJSON *obj = cJSON_CreateObject();
    if (obj && !write_fields(obj, t, s)) {
        cJSON_Delete(obj);
        return NULL;
    }
    return obj;
}

/* ---- settings and bitmaps -------------------------------------------------------------------------- */

/* World settings over *d (start from pp_world_def_default()). */
/* "preset" names the starting values (pp_world_def_preset); the other keys override them. */
pp_status parse_world_def(const json_ctx *c, const cJSON *obj, const char *where, pp_world_def *d)
{
    static const char *const extra[] = {"preset", NULL};
    static const char *const preset_names[] = {"", "fast", "balanced", "accurate", NULL};
    int32_t preset = -1;
    pp_status st = check_keys(c, obj, where, world_fields, extra);
    if (st || (st = read_enum(c, obj, where, "preset", preset_names, &preset)))
        return st;
    if (preset > 0)
        *d = pp_world_def_preset((pp_preset)preset);
    return read_fields(c, obj, where, world_fields, d);
}

/* The inverse of parse_world_def: every field, so the default of a later version cannot change a saved world. */
cJSON *world_def_to_json(const pp_world_def *d)
{
    return fields_to_json(world_fields, d);
}

pp_status parse_camera(const json_ctx *c, const cJSON *obj, const char *where, pp_camera *cam)
{
    pp_status st = check_keys(c, obj, where, camera_fields, NULL);
    return st ? st : read_fields(c, obj, where, camera_fields, cam);
}

cJSON *camera_to_json(const pp_camera *cam)
{
    return fields_to_json(camera_fields, cam);
}

/* A body's settings over *d; the caller checks keys, since a body object holds more (bitmap, name). */
pp_status parse_body_settings(const json_ctx *c, const cJSON *obj, const char *where, pp_body_def *d)
{
    pp_status st = read_fields(c, obj, where, body_fields, d);
    if (st == PP_OK && cJSON_GetObjectItemCaseSensitive(obj, "pivot"))
        d->custom_pivot = 1;
    return st;
}

/* The inverse of parse_body_settings; "pivot" only when the def has a custom pivot. */
cJSON *body_settings_to_json(const pp_body_def *d)
{
    cJSON *obj = fields_to_json(body_fields, d);
    if (obj && !d->custom_pivot)
        cJSON_DeleteItemFromObjectCaseSensitive(obj, "pivot");
    return obj;
}

/* A timed edit's fields, without a weight when it erases; the caller adds its body. */
cJSON *edit_to_json(const pp_timed_edit *e)
{
    cJSON *obj = fields_to_json(edit_fields, e);
    if (obj && e->type != PP_EDIT_PAINT_CIRCLE)
        cJSON_DeleteItemFromObjectCaseSensitive(obj, "weight");
    return obj;
}


void bitmap_free(bitmap *b)
{
    pp_free(b->rgba);
    pp_free(b->mask);
    pp_free(b->weights);
}

/* One message whatever the reason (missing, unreadable, not a regular file, outside the folder), so that a
 * file cannot probe what lies outside its folder. path is the file named, or NULL for the file itself. */
static pp_status cannot_open(const json_ctx *c, const char *where, const char *key, const char *path)
{
    static const char why[] = "missing, unreadable, not a regular file, or outside";
    const int n = c->dir_len ? (int)c->dir_len : 2;
    const char *folder = c->dir_len ? c->file : "./";
    if (!path)
        return pp_fail(PP_ERR_IO, "%s: '%s': cannot open: %s '%.*s'", c->fn, c->file, why, n, folder);
    return json_fail(c, PP_ERR_IO, where, key, "cannot open '%s': %s '%.*s'", path, why, n, folder);
}

/* Decode the PNG named by obj[key], a path beneath the file's folder. */
static pp_status load_png(const json_ctx *c, const cJSON *obj, const char *where, const char *key, uint8_t **rgba,
                          int32_t *w, int32_t *h)
{
    const char *name = NULL;
    pp_status st = read_string(c, obj, where, key, &name);
    if (st)
        return st;
    /* The path as the host would write it, for messages: an absolute name as it is. */
    const size_t dir = name[0] == '/' ? 0 : c->dir_len;
    char *path = pp_malloc(dir + strlen(name) + 1);
    if (!path)
        return json_fail(c, PP_ERR_OUT_OF_MEMORY, where, key, "no memory");
    memcpy(path, c->file, dir);
    strcpy(path + dir, name);
    const int fd = files_open_beneath(c->dir_fd, name);
    if (fd < 0) {
        st = cannot_open(c, where, key, path);
    } else {
        st = image_load_fd(fd, "pp_image_load", path, rgba, w, h);
        close(fd);
        if (st)
            st = json_fail_from_last(c, st, where, key);
    }
    pp_free(path);
    return st;
}

/* A second plane must cover the bitmap exactly. */
static pp_status check_plane_size(const json_ctx *c, const char *where, const char *key, int32_t w, int32_t h,
                                  const bitmap *b, const char *what)
{
    if (w == b->width && h == b->height)
        return PP_OK;
    return json_fail(c, PP_ERR_FORMAT, where, key, "%dx%d px, but the %s is %dx%d px", (int)w, (int)h, what,
                     (int)b->width, (int)b->height);
}

/* "box": [w, h], a solid rectangle. */
static pp_status load_box(const json_ctx *c, const cJSON *box, const char *where, bitmap *b)
{
    int64_t w, h;
    if (!cJSON_IsArray(box) || cJSON_GetArraySize(box) != 2 ||
        !json_int(cJSON_GetArrayItem(box, 0), 1, PP_MAX_BITMAP_SIDE, &w) ||
        !json_int(cJSON_GetArrayItem(box, 1), 1, PP_MAX_BITMAP_SIDE, &h))
        return json_fail(c, PP_ERR_FORMAT, where, "box", "expected [width, height], integers in 1..%d",
                         PP_MAX_BITMAP_SIDE);
    if (w * h > PP_MAX_BITMAP_AREA)
        return json_fail(c, PP_ERR_LIMIT, where, "box", "%lldx%lld px is over PP_MAX_BITMAP_AREA (%d)", (long long)w,
                         (long long)h, PP_MAX_BITMAP_AREA);
    if (!(b->mask = pp_malloc((size_t)(w * h))))
        return json_fail(c, PP_ERR_OUT_OF_MEMORY, where, "box", "no memory for %lldx%lld px", (long long)w,
                         (long long)h);
    memset(b->mask, 1, (size_t)(w * h));
    b->width = (int32_t)w, b->height = (int32_t)h;
    return PP_OK;
}

/* "mask": solid where red ≥ 128 and alpha ≥ 128. */
static pp_status load_mask(const json_ctx *c, const cJSON *obj, const char *where, bitmap *b)
{
    uint8_t *px = NULL;
    int32_t w, h;
    pp_status st = load_png(c, obj, where, "mask", &px, &w, &h);
    if (st == PP_OK && b->rgba)
        st = check_plane_size(c, where, "mask", w, h, b, "sprite");
    if (st == PP_OK && !(b->mask = pp_malloc((size_t)w * (size_t)h)))
        st = json_fail(c, PP_ERR_OUT_OF_MEMORY, where, "mask", "no memory");
    if (st == PP_OK) {
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
            b->mask[i] = px[4 * i] >= 128 && px[4 * i + 3] >= 128;
        b->width = w, b->height = h;
    }
    pp_free(px);
    return st;
}

/* "weights": the red channel is each pixel's weight. */
static pp_status load_weights(const json_ctx *c, const cJSON *obj, const char *where, bitmap *b)
{
    uint8_t *px = NULL;
    int32_t w, h;
    pp_status st = load_png(c, obj, where, "weights", &px, &w, &h);
    if (st == PP_OK)
        st = check_plane_size(c, where, "weights", w, h, b, "bitmap");
    if (st == PP_OK && !(b->weights = pp_malloc((size_t)w * (size_t)h)))
        st = json_fail(c, PP_ERR_OUT_OF_MEMORY, where, "weights", "no memory");
    if (st == PP_OK)
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
            b->weights[i] = px[4 * i];
    pp_free(px);
    return st;
}

/* The bitmap from "sprite", "mask", "weights" and "box"; on failure the caller frees what was loaded. */
pp_status parse_bitmap(const json_ctx *c, const cJSON *obj, const char *where, bitmap *b)
{
    const bool sprite = cJSON_GetObjectItemCaseSensitive(obj, "sprite") != NULL;
    const bool mask = cJSON_GetObjectItemCaseSensitive(obj, "mask") != NULL;
    const cJSON *box = cJSON_GetObjectItemCaseSensitive(obj, "box");
    if (box && (sprite || mask))
        return json_fail(c, PP_ERR_FORMAT, where, "box", "cannot be combined with sprite or mask");
    if (!box && !sprite && !mask)
        return json_fail(c, PP_ERR_FORMAT, where, NULL, "needs a bitmap: sprite, mask or box");
    pp_status st = box ? load_box(c, box, where, b) : PP_OK;
    if (st == PP_OK && sprite)
        st = load_png(c, obj, where, "sprite", &b->rgba, &b->width, &b->height);
    if (st == PP_OK && mask)
        st = load_mask(c, obj, where, b);
    if (st == PP_OK && cJSON_GetObjectItemCaseSensitive(obj, "weights"))
        st = load_weights(c, obj, where, b);
    return st;
}

/* ---- the file ------------------------------------------------------------------------------------ */

/* The whole file, NUL-terminated; LIMIT past PP_MAX_SCENE_BYTES, from its size before reading. */
static pp_status read_text(const json_ctx *c, char **out, size_t *len)
{
    const char *leaf = c->file + c->dir_len;
    const int fd = c->confine_file ? files_open_beneath(c->dir_fd, leaf) : files_open_regular(c->dir_fd, leaf);
    FILE *f = fd >= 0 ? fdopen(fd, "rb") : NULL;
    if (!f) {
        const int err = errno;
        if (fd >= 0)
            close(fd);
        return c->confine_file ? cannot_open(c, "", NULL, NULL)
                               : pp_fail(PP_ERR_IO, "%s: '%s': cannot open: %s", c->fn, c->file, files_strerror(err));
    }
    struct stat sb;
    if (fstat(fileno(f), &sb) == 0 && sb.st_size > PP_MAX_SCENE_BYTES) {
        fclose(f);
        return pp_fail(PP_ERR_LIMIT, "%s: '%s' is %lld bytes, over PP_MAX_SCENE_BYTES (%d)", c->fn, c->file,
                       (long long)sb.st_size, PP_MAX_SCENE_BYTES);
    }
    size_t n = 0, cap = 0;
    char *buf = NULL;
    pp_status st = PP_OK;
    for (;;) {
        if (n + 1 >= cap) {
            cap = cap ? 2 * cap : 1 << 16;
            char *p = pp_realloc(buf, cap);
            if (!p) {
                st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: '%s': no memory for %zu bytes", c->fn, c->file, cap);
                break;
            }
            buf = p;
        }
        const size_t got = fread(buf + n, 1, cap - 1 - n, f);
        n += got;
        if (n > PP_MAX_SCENE_BYTES) {
            st = pp_fail(PP_ERR_LIMIT, "%s: '%s' is over PP_MAX_SCENE_BYTES (%d)", c->fn, c->file, PP_MAX_SCENE_BYTES);
            break;
        }
        if (got == 0) {
            if (ferror(f))
                st = pp_fail(PP_ERR_IO, "%s: '%s': cannot read: %s", c->fn, c->file, strerror(errno));
            break;
        }
    }
    fclose(f);
    if (st) {
        pp_free(buf);
        return st;
    }
    buf[n] = '\0';
    *out = buf;
    *len = n;
    return PP_OK;
}

/* Open the folder, then parse the file from it; a syntax error names its line. */
pp_status parse_json(json_ctx *c, cJSON **root)
{
    *root = NULL;
    if ((c->dir_fd = files_open_folder(c->file, c->dir_len)) < 0)
        return c->confine_file ? cannot_open(c, "", NULL, NULL)
                               : pp_fail(PP_ERR_IO, "%s: '%s': cannot open: %s", c->fn, c->file, files_strerror(errno));
    char *text = NULL;
    size_t len = 0;
    pp_status st = read_text(c, &text, &len);
    if (st)
        return st;
    const char *end = NULL;
    *root = cJSON_ParseWithLengthOpts(text, len + 1, &end, 1);
    /* The parser stops at a NUL inside the file too: that is an error there. */
    if (!*root || end != text + len) {
        int line = 1;
        for (const char *p = text; end && p < end; p++)
            line += *p == '\n';
        st = pp_fail(PP_ERR_FORMAT, "%s: '%s': line %d: invalid JSON", c->fn, c->file, line);
        cJSON_Delete(*root);
        *root = NULL;
    }
    pp_free(text);
    return st;
}

void json_done(json_ctx *c, cJSON *root)
{
    cJSON_Delete(root);
    if (c->dir_fd >= 0)
        close(c->dir_fd);
    c->dir_fd = -1;
}

pp_status parse_joint_def(const json_ctx *c, const cJSON *obj, const char *where, const char *const *extra,
                          pp_joint_def *d)
{
    if (!cJSON_IsObject(obj))
        return json_fail(c, PP_ERR_FORMAT, where, NULL, "expected an object");
    int32_t type = 0;
    pp_status st = check_keys(c, obj, where, joint_fields, extra);
    if (st || (st = read_enum(c, obj, where, "type", joint_type_names, &type)))
        return st;
    if (!type)
        return json_fail(c, PP_ERR_FORMAT, where, "type", "missing");
    *d = pp_joint_def_default((pp_joint_type)type);
    return read_fields(c, obj, where, joint_fields, d);
}
