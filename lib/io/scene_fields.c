/* The field tables (world, body, joint, camera, timed edit): one entry reads a field of a def and writes it
 * back exactly; and the settings' parsers and writers built on them. The reader and the file are
 * scene_json.c's. */
#include "scene_json.h"

#include <stdio.h>
#include <string.h>

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
const char *const joint_type_names[] = {"", "revolute", "prismatic", "distance", "weld", "mouse", "wheel", "motor", NULL};
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
    F_FLOAT(pp_joint_def, target, NUM_FINITE),
    F_FLOAT(pp_joint_def, angular_hertz, NUM_NONNEG),
    F_FLOAT(pp_joint_def, angular_damping_ratio, NUM_NONNEG),
    F_FLOAT(pp_joint_def, break_torque, NUM_NONNEG),
    F_VEC2(pp_joint_def, linear_offset),
    F_FLOAT(pp_joint_def, angular_offset, NUM_FINITE),
    F_FLOAT(pp_joint_def, max_torque, NUM_NONNEG),
    F_FLOAT(pp_joint_def, correction_factor, NUM_NONNEG),
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

/* ---- settings -------------------------------------------------------------------------------- */

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
