/* JSON scenes: a world's settings, camera, bodies with PNG bitmaps, joints and timed edits naming bodies.
 * The reading itself is scene_json.c's and scene_fields.c's; every complaint names the JSON path of the
 * value at fault. */
#include "alloc.h"
#include "camera.h"
#include "joint.h"
#include "scene_json.h"
#include "status.h"
#include "timed_edits.h"
#include "world.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const body_extra_keys[] = {"name", "sprite", "mask", "weights", "box", NULL};

/* One body: its settings, its bitmap, made in the world. */
static pp_status parse_body(const json_ctx *c, const cJSON *obj, const char *where, world *wd, pp_body *out)
{
    if (!cJSON_IsObject(obj))
        return json_fail(c, PP_ERR_FORMAT, where, NULL, "expected an object");
    pp_body_def d = pp_body_def_default();
    const char *name = NULL;
    pp_status st = check_keys(c, obj, where, body_fields, body_extra_keys);
    if (st == PP_OK && (st = read_string(c, obj, where, "name", &name)) == PP_OK)
        st = parse_body_settings(c, obj, where, &d);
    bitmap b = {0};
    if (st == PP_OK && (st = parse_bitmap(c, obj, where, &b)) == PP_OK) {
        d.width = b.width, d.height = b.height;
        d.rgba = b.rgba, d.mask = b.mask, d.weights = b.weights;
        body *bd = NULL;
        if ((st = body_make(wd, &d, BODY_ANY_SLOT, c->fn, &bd)))
            st = json_fail_from_last(c, st, where, NULL);
        else
            *out = bd->handle;
    }
    bitmap_free(&b);
    return st;
}

/* Bodies by name, for edits; names point into the parsed JSON. A hash table over the names, at most half
 * full, keeps a scene's name checks and lookups linear in its size (scanning them was quadratic). */
typedef struct body_names {
    const char **names; /* NULL for an unnamed body */
    pp_body *bodies;
    int32_t *table;     /* open addressing, linear probing: 1 + a named body's index, 0 where empty */
    uint32_t mask;      /* the table's size − 1, a power of two */
} body_names;

/* FNV-1a, started from where the table lies: names crafted to collide do not collide in another run. The
 * lookups' results do not depend on it, only their cost. */
static uint32_t name_hash(const body_names *bn, const char *name)
{
    uint32_t h = 2166136261u ^ (uint32_t)((uintptr_t)bn->table >> 12);
    for (const unsigned char *p = (const unsigned char *)name; *p; p++)
        h = (h ^ *p) * 16777619u;
    return h;
}

/* The table entry holding name, or the empty one where it would go. */
static int32_t *name_entry(const body_names *bn, const char *name)
{
    for (uint32_t i = name_hash(bn, name) & bn->mask;; i = (i + 1) & bn->mask) {
        int32_t *e = &bn->table[i];
        if (*e == 0 || strcmp(bn->names[*e - 1], name) == 0)
            return e;
    }
}

static int32_t find_body(const body_names *bn, const char *name) { return *name_entry(bn, name) - 1; }

static pp_status parse_bodies(const json_ctx *c, const cJSON *arr, world *wd, body_names *bn)
{
    const int32_t n = arr ? cJSON_GetArraySize(arr) : 0;
    size_t size = 2;
    while (size < 2 * (size_t)n)
        size *= 2;
    bn->names = pp_calloc((size_t)n + 1, sizeof *bn->names);
    bn->bodies = pp_calloc((size_t)n + 1, sizeof *bn->bodies);
    bn->table = pp_calloc(size, sizeof *bn->table);
    bn->mask = (uint32_t)(size - 1);
    if (!bn->names || !bn->bodies || !bn->table)
        return json_fail(c, PP_ERR_OUT_OF_MEMORY, "bodies", NULL, "no memory for %d bodies", (int)n);
    int32_t i = 0;
    for (const cJSON *it = arr ? arr->child : NULL; it; it = it->next, i++) {
        char where[32];
        snprintf(where, sizeof where, "bodies[%d]", (int)i);
        pp_status st = parse_body(c, it, where, wd, &bn->bodies[i]);
        if (st)
            return st;
        const cJSON *name = cJSON_GetObjectItemCaseSensitive(it, "name");
        int32_t *entry = name ? name_entry(bn, name->valuestring) : NULL;
        if (entry && *entry)
            return json_fail(c, PP_ERR_FORMAT, where, "name", "'%s' is already the name of bodies[%d]",
                             name->valuestring, (int)(*entry - 1));
        bn->names[i] = name ? name->valuestring : NULL;
        if (entry)
            *entry = i + 1;
    }
    return PP_OK;
}

/* One timed edit; its "body" is a name among the scene's bodies. */
static pp_status parse_edit(const json_ctx *c, const cJSON *obj, const char *where, const body_names *bn,
                            pp_timed_edit *e)
{
    static const char *const extra[] = {"body", NULL};
    if (!cJSON_IsObject(obj))
        return json_fail(c, PP_ERR_FORMAT, where, NULL, "expected an object");
    memset(e, 0, sizeof *e);
    e->type = PP_EDIT_ERASE_CIRCLE;
    e->weight = 255;
    const char *name = NULL;
    pp_status st = check_keys(c, obj, where, edit_fields, extra);
    if (st == PP_OK && (st = read_fields(c, obj, where, edit_fields, e)) == PP_OK)
        st = read_string(c, obj, where, "body", &name);
    if (st)
        return st;
    if (e->type == PP_EDIT_ERASE_CIRCLE && cJSON_GetObjectItemCaseSensitive(obj, "weight"))
        return json_fail(c, PP_ERR_FORMAT, where, "weight", "only a paint edit has a weight");
    if (e->type == PP_EDIT_PAINT_CIRCLE && !name)
        return json_fail(c, PP_ERR_FORMAT, where, "body", "a paint edit needs a body");
    const int32_t i = name ? find_body(bn, name) : -1;
    if (name && i < 0)
        return json_fail(c, PP_ERR_FORMAT, where, "body", "no body is named '%s'", name);
    if (name)
        e->body = bn->bodies[i];
    return PP_OK;
}

/* A joint's "body_a" or "body_b": a body's name, absent for the static world. */
static pp_status read_joint_body(const json_ctx *c, const cJSON *obj, const char *where, const char *key,
                                 const body_names *bn, pp_body *out)
{
    const char *name = NULL;
    pp_status st = read_string(c, obj, where, key, &name);
    const int32_t i = !st && name ? find_body(bn, name) : -1;
    if (!st && name && i < 0)
        st = json_fail(c, PP_ERR_FORMAT, where, key, "no body is named '%s'", name);
    *out = i >= 0 ? bn->bodies[i] : (pp_body){0};
    return st;
}

/* One joint: "type" (required), bodies by name, the pp_joint_def fields. */
static pp_status parse_joint(const json_ctx *c, const cJSON *obj, const char *where, world *wd, const body_names *bn)
{
    static const char *const extra[] = {"type", "body_a", "body_b", NULL};
    pp_joint_def d;
    joint *jt;
    pp_status st;
    if ((st = parse_joint_def(c, obj, where, extra, &d)) ||
        (st = read_joint_body(c, obj, where, "body_a", bn, &d.body_a)) ||
        (st = read_joint_body(c, obj, where, "body_b", bn, &d.body_b)))
        return st;
    if ((st = joint_make(wd, &d, c->fn, &jt)))
        return json_fail_from_last(c, st, where, NULL);
    return PP_OK;
}

/* One timed edit, scheduled in the world. */
static pp_status add_edit(const json_ctx *c, const cJSON *obj, const char *where, world *wd, const body_names *bn)
{
    pp_timed_edit e;
    pp_status st = parse_edit(c, obj, where, bn, &e);
    if (st == PP_OK && (st = timed_edits_schedule(wd, &e, c->fn)))
        st = json_fail_from_last(c, st, where, NULL);
    return st;
}

/* Each item of the array section `key` by `one`, named "<key>[i]" in messages. */
static pp_status parse_each(const json_ctx *c, const cJSON *arr, const char *key, world *wd, const body_names *bn,
                            pp_status (*one)(const json_ctx *, const cJSON *, const char *, world *, const body_names *))
{
    int32_t i = 0;
    for (const cJSON *it = arr ? arr->child : NULL; it; it = it->next, i++) {
        char where[32];
        snprintf(where, sizeof where, "%s[%d]", key, (int)i);
        pp_status st = one(c, it, where, wd, bn);
        if (st)
            return st;
    }
    return PP_OK;
}

/* World, camera, bodies, joints, edits, in that order, into a new world; nothing is left behind on failure. */
static pp_status build_scene(const json_ctx *c, const cJSON *root, pp_world *out)
{
    static const char *const top_keys[] = {"world", "camera", "bodies", "joints", "edits", NULL};
    if (!cJSON_IsObject(root))
        return json_fail(c, PP_ERR_FORMAT, "(root)", NULL, "expected an object");
    const cJSON *wobj, *cobj, *bodies, *joints, *edits;
    pp_status st = check_keys(c, root, "", NULL, top_keys);
    if (st || (st = read_section(c, root, "", "world", false, &wobj)) ||
        (st = read_section(c, root, "", "camera", false, &cobj)) ||
        (st = read_section(c, root, "", "bodies", true, &bodies)) ||
        (st = read_section(c, root, "", "joints", true, &joints)) ||
        (st = read_section(c, root, "", "edits", true, &edits)))
        return st;
    pp_world_def d = pp_world_def_default();
    if (wobj && (st = parse_world_def(c, wobj, "world", &d)))
        return st;
    world *wd = NULL;
    if ((st = world_make(&d, c->fn, &wd)))
        return json_fail_from_last(c, st, "world", NULL);
    pp_camera cam = camera_of(wd);
    body_names bn = {0};
    if (cobj && (st = parse_camera(c, cobj, "camera", &cam)) == PP_OK && (st = camera_set(wd, &cam, c->fn)))
        st = json_fail_from_last(c, st, "camera", NULL);
    if (st == PP_OK && (st = parse_bodies(c, bodies, wd, &bn)) == PP_OK &&
        (st = parse_each(c, joints, "joints", wd, &bn, parse_joint)) == PP_OK)
        st = parse_each(c, edits, "edits", wd, &bn, add_edit);
    pp_free(bn.names);
    pp_free(bn.bodies);
    pp_free(bn.table);
    if (st) {
        world_free(wd);
        return st;
    }
    *out = wd->handle;
    return PP_OK;
}

PP_API pp_status pp_world_load_scene(const char *path, pp_world *out)
{
    if (!path || !out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_load_scene: %s is NULL", path ? "out" : "path");
    const char *slash = strrchr(path, '/');
    json_ctx c = {"pp_world_load_scene", path, slash ? (size_t)(slash - path) + 1 : 0, -1, false};
    cJSON *root = NULL;
    pp_status st = parse_json(&c, &root);
    if (st == PP_OK)
        st = build_scene(&c, root, out);
    json_done(&c, root);
    return st;
}
