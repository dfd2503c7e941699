/* The engine plugin's entry, initialisation levels, object table and generic call: arguments are
 * checked against the class table (count, type, object class) before any method runs, and every
 * failure comes back as an ERROR variant with a status and a message. One lock serialises calls. */
#include "plugin.h"

#include "handle.h" /* the library's id layout (lib/), for the body slot that indexes body_objects */
#include "id_pool.h" /* the library's slot pool (lib/, header-only), for the object table */

#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_ARGS = 8 };

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static pp_host_log_fn host_log;
static void *host_user;
static int level_reached = -1; /* highest initialised level, -1 before CORE */
static plugin_object *objects; /* by slot of object_ids */
static id_pool object_ids;
static pp_plugin_class public_classes[CLASS_COUNT];
static pp_plugin_method public_methods[CLASS_COUNT][96];

static void logf_host(int level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void logf_host(int level, const char *fmt, ...)
{
    if (!host_log)
        return;
    char line[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    host_log(level, line, host_user);
}

/* ---- results ---- */

static const char oom_message[] = "PhysPix: out of memory";

void ret_int(pp_variant *ret, int64_t v) { *ret = (pp_variant){.type = PP_VARIANT_INT, .as.integer = v}; }
void ret_float(pp_variant *ret, double v) { *ret = (pp_variant){.type = PP_VARIANT_FLOAT, .as.real = v}; }
void ret_bool(pp_variant *ret, int v) { *ret = (pp_variant){.type = PP_VARIANT_BOOL, .as.boolean = v != 0}; }
void ret_vec2(pp_variant *ret, pp_vec2 v) { *ret = (pp_variant){.type = PP_VARIANT_VEC2, .as.vec2 = v}; }
void ret_object(pp_variant *ret, uint64_t id) { *ret = (pp_variant){.type = PP_VARIANT_OBJECT, .as.object = id}; }

void ret_error(pp_variant *ret, pp_status status, const char *fmt, ...)
{
    char line[640];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    const char *copy = strdup(line);
    if (!copy) /* still a message the host can show; variant_clear knows not to free it */
        copy = oom_message, status = PP_ERR_OUT_OF_MEMORY;
    *ret = (pp_variant){.type = PP_VARIANT_ERROR, .as.error = {status, 0, copy}};
}

int ret_ok(pp_variant *ret, pp_status status, const char *method)
{
    if (status == PP_OK)
        return 1;
    ret_error(ret, status, "%s: %s", method, pp_last_error());
    return 0;
}

void ret_string(pp_variant *ret, const char *s)
{
    char *copy = strdup(s);
    if (copy)
        *ret = (pp_variant){.type = PP_VARIANT_STRING, .as.string = {copy, (int64_t)strlen(copy)}};
    else
        ret_error(ret, PP_ERR_OUT_OF_MEMORY, "out of memory copying a string");
}

uint8_t *ret_bytes(pp_variant *ret, int64_t length)
{
    uint8_t *data = malloc(length > 0 ? (size_t)length : 1);
    if (!data) {
        ret_error(ret, PP_ERR_OUT_OF_MEMORY, "out of memory allocating %lld bytes", (long long)length);
        return NULL;
    }
    *ret = (pp_variant){.type = PP_VARIANT_BYTES, .as.bytes = {data, length}};
    return data;
}

static void variant_clear(pp_variant *v)
{
    if (!v)
        return;
    if (v->type == PP_VARIANT_STRING)
        free((void *)v->as.string.data);
    else if (v->type == PP_VARIANT_BYTES)
        free((void *)v->as.bytes.data);
    else if (v->type == PP_VARIANT_ERROR && v->as.error.message != oom_message)
        free((void *)v->as.error.message);
    *v = (pp_variant){.type = PP_VARIANT_NIL};
}

/* ---- the object table ---- */

/* Object ids carry the kind of handle their object wraps (handle.h), so that a joint int passed as an object
 * is known for one. */
static handle_kind object_handle_kind(object_kind kind) { return kind == OBJECT_WORLD ? HANDLE_WORLD : HANDLE_BODY; }

static uint64_t object_id(uint32_t slot)
{
    return slot_id_make(object_handle_kind(objects[slot].kind), slot, object_ids.generations[slot]);
}

plugin_object *object_get(uint64_t id)
{
    const uint32_t slot = world_id_slot(id), gen = world_id_gen(id);
    if (!id_pool_current(&object_ids, slot, gen) || objects[slot].kind == OBJECT_FREE ||
        handle_kind_of(id) != object_handle_kind(objects[slot].kind))
        return NULL;
    return &objects[slot];
}

uint64_t object_new(object_kind kind, plugin_object **out)
{
    uint32_t slot = 0;
    if (ID_POOL_TAKE(&object_ids, INT32_MAX, objects, realloc, &slot) != ID_POOL_TAKEN)
        return 0;
    plugin_object *o = &objects[slot];
    *o = (plugin_object){.kind = kind};
    *out = o;
    return object_id(slot);
}

static void world_cache_free(world_cache *c)
{
    if (!c)
        return;
    free(c->contacts);
    free(c->events);
    free(c->bodies);
    free(c->states);
    free(c->body_objects);
    free(c->edits);
    free(c->debug_normals);
    free(c->found);
    free(c->ray_hits);
    free(c);
}

/* Release a slot (and a world's body objects); the physics objects are the caller's business. */
void object_free(uint64_t id)
{
    plugin_object *o = object_get(id);
    if (!o)
        return;
    if (o->kind == OBJECT_WORLD && o->cache) {
        for (int32_t i = 0; i < o->cache->body_object_capacity; i++)
            object_free(o->cache->body_objects[i]);
        world_cache_free(o->cache);
    } else if (o->kind == OBJECT_BODY) {
        plugin_object *w = object_get(o->world_object);
        const uint32_t bslot = handle_slot(o->body.id);
        if (w && bslot < (uint32_t)w->cache->body_object_capacity && w->cache->body_objects[bslot] == id)
            w->cache->body_objects[bslot] = 0;
    }
    o->kind = OBJECT_FREE;
    o->cache = NULL;
    id_pool_release(&object_ids, (uint32_t)(o - objects));
}

uint64_t object_for_body(uint64_t world_object, pp_body body)
{
    plugin_object *w = object_get(world_object);
    const uint32_t bslot = handle_slot(body.id);
    world_cache *c = w->cache;
    if (bslot >= (uint32_t)c->body_object_capacity) {
        int32_t n = c->body_object_capacity ? c->body_object_capacity : 16;
        while ((uint32_t)n <= bslot)
            n *= 2;
        uint64_t *grown = realloc(c->body_objects, (size_t)n * sizeof *grown);
        if (!grown)
            return 0;
        memset(grown + c->body_object_capacity, 0, (size_t)(n - c->body_object_capacity) * sizeof *grown);
        c->body_objects = grown;
        c->body_object_capacity = n;
    }
    const plugin_object *known = object_get(c->body_objects[bslot]);
    if (known && known->body.id == body.id)
        return c->body_objects[bslot];
    plugin_object *o;
    const uint64_t id = object_new(OBJECT_BODY, &o);
    if (!id)
        return 0;
    w = object_get(world_object); /* object_new may have moved the table */
    o->world = w->world;
    o->body = body;
    o->world_object = world_object;
    c->body_objects[bslot] = id;
    return id;
}

/* ---- levels, create, destroy, call ---- */

static pp_status plugin_initialize(pp_plugin_level level)
{
    pthread_mutex_lock(&lock);
    pp_status st = PP_OK;
    if ((int)level != level_reached + 1) {
        logf_host(3, "PhysPix: initialize(%d) out of order; levels go up one at a time from CORE (reached %d)",
                  (int)level, level_reached);
        st = PP_ERR_INVALID_ARGUMENT;
    } else {
        level_reached = (int)level;
        if (level == PP_PLUGIN_LEVEL_SCENE)
            logf_host(1, "PhysPix %u.%u.%u: classes PhysPixWorld and PhysPixBody ready", PHYSPIX_VERSION_MAJOR,
                      PHYSPIX_VERSION_MINOR, PHYSPIX_VERSION_PATCH);
    }
    pthread_mutex_unlock(&lock);
    return st;
}

static void plugin_deinitialize(pp_plugin_level level)
{
    pthread_mutex_lock(&lock);
    if ((int)level == level_reached) {
        if (level == PP_PLUGIN_LEVEL_SCENE) { /* the host may not have destroyed everything */
            for (int32_t i = 0; i < object_ids.capacity; i++)
                if (objects[i].kind == OBJECT_WORLD) {
                    pp_world_destroy(objects[i].world);
                    object_free(object_id((uint32_t)i));
                }
        }
        if (level == PP_PLUGIN_LEVEL_CORE) {
            free(objects);
            objects = NULL;
            id_pool_free(&object_ids, free);
        }
        level_reached = (int)level - 1;
    }
    pthread_mutex_unlock(&lock);
}

static const class_def *class_named(const char *name)
{
    for (int i = 0; name && i < CLASS_COUNT; i++)
        if (strcmp(plugin_classes[i].desc.name, name) == 0)
            return &plugin_classes[i];
    return NULL;
}

static const class_def *class_of(object_kind kind) { return &plugin_classes[kind == OBJECT_WORLD ? CLASS_WORLD : CLASS_BODY]; }

static int scene_ready(pp_variant *ret)
{
    if (level_reached >= PP_PLUGIN_LEVEL_SCENE)
        return 1;
    ret_error(ret, PP_ERR_INVALID_ARGUMENT, "PhysPix: classes are usable after initialize(PP_PLUGIN_LEVEL_SCENE)");
    return 0;
}

static void create_world(pp_variant *ret)
{
    plugin_object *o;
    world_cache *cache = calloc(1, sizeof *cache);
    const uint64_t id = cache ? object_new(OBJECT_WORLD, &o) : 0;
    if (!id) {
        free(cache);
        ret_error(ret, PP_ERR_OUT_OF_MEMORY, "object_create: out of memory");
        return;
    }
    cache->one_way_direction = pp_body_def_default().one_way_direction;
    o->cache = cache;
    o->world_object = id;
    const pp_world_def def = pp_world_def_default();
    if (ret_ok(ret, pp_world_create(&def, &o->world), "PhysPixWorld.create"))
        ret_object(ret, id);
    else
        object_free(id);
}

static void plugin_object_create(const char *class_name, pp_variant *ret)
{
    if (!ret)
        return;
    pthread_mutex_lock(&lock);
    const class_def *c = class_named(class_name);
    if (!scene_ready(ret)) {
    } else if (!c) {
        ret_error(ret, PP_ERR_INVALID_ARGUMENT, "object_create: no class named '%s' (PhysPixWorld, PhysPixBody)",
                  class_name ? class_name : "(null)");
    } else if (!c->desc.instantiable) {
        ret_error(ret, PP_ERR_INVALID_ARGUMENT, "object_create: %s is made by PhysPixWorld.add_body*, not created",
                  c->desc.name);
    } else {
        create_world(ret);
    }
    pthread_mutex_unlock(&lock);
}

static void plugin_object_destroy(uint64_t id, pp_variant *ret)
{
    if (!ret)
        return;
    pthread_mutex_lock(&lock);
    plugin_object *o = object_get(id);
    if (!scene_ready(ret)) {
    } else if (!o) {
        ret_error(ret, PP_ERR_INVALID_HANDLE, "object_destroy: object %#llx is null, destroyed or stale",
                  (unsigned long long)id);
    } else {
        /* A body an edit already destroyed is gone: releasing its object is all that is left. */
        const int is_world = o->kind == OBJECT_WORLD;
        const pp_status st = is_world ? pp_world_destroy(o->world) : pp_body_destroy(o->world, o->body);
        object_free(id);
        *ret = (pp_variant){.type = PP_VARIANT_NIL};
        if (is_world)
            ret_ok(ret, st, "PhysPixWorld.destroy");
    }
    pthread_mutex_unlock(&lock);
}

static const char *type_name(pp_variant_type t)
{
    static const char *names[] = {"nil", "bool", "int", "float", "vec2", "string", "bytes", "object", "error"};
    return (uint32_t)t < sizeof names / sizeof names[0] ? names[t] : "unknown";
}

/* What an error about an id that is no object adds when the id is a joint's (an int, not an object). */
static const char *joint_note(uint64_t id)
{
    return handle_kind_of(id) == HANDLE_JOINT ? "; it is a joint handle (an int)" : "";
}

/* Check one argument and convert INT to FLOAT; 0 and ret set to ERROR if it does not fit. */
static int check_arg(const char *cls, const pp_plugin_method *m, int i, const pp_variant *in, pp_variant *out,
                     pp_variant *ret)
{
    const pp_plugin_arg *a = &m->args[i];
    *out = *in;
    if (in->type == PP_VARIANT_INT && a->type == PP_VARIANT_FLOAT)
        *out = (pp_variant){.type = PP_VARIANT_FLOAT, .as.real = (double)in->as.integer};
    else if (in->type != a->type) {
        ret_error(ret, PP_ERR_INVALID_ARGUMENT, "%s.%s: argument %d (%s) must be %s, got %s", cls, m->name, i + 1,
                  a->name, type_name(a->type), type_name(in->type));
        return 0;
    }
    if ((in->type == PP_VARIANT_STRING && !in->as.string.data) ||
        (in->type == PP_VARIANT_BYTES && in->as.bytes.length > 0 && !in->as.bytes.data) ||
        (in->type == PP_VARIANT_BYTES && in->as.bytes.length < 0)) {
        ret_error(ret, PP_ERR_INVALID_ARGUMENT, "%s.%s: argument %d (%s) has no data", cls, m->name, i + 1, a->name);
        return 0;
    }
    if (a->type == PP_VARIANT_OBJECT) {
        const plugin_object *o = object_get(in->as.object);
        if (!o || (a->class_name && strcmp(class_of(o->kind)->desc.name, a->class_name) != 0)) {
            ret_error(ret, o ? PP_ERR_INVALID_ARGUMENT : PP_ERR_INVALID_HANDLE,
                      "%s.%s: argument %d (%s) must be a live %s object%s", cls, m->name, i + 1, a->name,
                      a->class_name ? a->class_name : "plugin", o ? "" : joint_note(in->as.object));
            return 0;
        }
    }
    return 1;
}

static void plugin_call(uint64_t id, const char *method, const pp_variant *args, int32_t argc, pp_variant *ret)
{
    if (!ret)
        return;
    pthread_mutex_lock(&lock);
    plugin_object *o = object_get(id);
    const class_def *c = o ? class_of(o->kind) : NULL;
    const method_def *m = NULL;
    for (int32_t i = 0; c && method && i < c->desc.method_count; i++)
        if (strcmp(c->methods[i].desc.name, method) == 0)
            m = &c->methods[i];
    pp_variant checked[MAX_ARGS];
    if (!scene_ready(ret)) {
    } else if (!o) {
        ret_error(ret, PP_ERR_INVALID_HANDLE, "call %s: object %#llx is null, destroyed or stale%s",
                  method ? method : "(null)", (unsigned long long)id, joint_note(id));
    } else if (!m) {
        ret_error(ret, PP_ERR_INVALID_ARGUMENT, "%s has no method '%s'", c->desc.name, method ? method : "(null)");
    } else if (argc != m->desc.arg_count || (argc > 0 && !args)) {
        ret_error(ret, PP_ERR_INVALID_ARGUMENT, "%s.%s takes %d argument%s, got %d", c->desc.name, m->desc.name,
                  m->desc.arg_count, m->desc.arg_count == 1 ? "" : "s", (int)argc);
    } else {
        int ok = 1;
        for (int32_t i = 0; ok && i < argc; i++)
            ok = check_arg(c->desc.name, &m->desc, i, &args[i], &checked[i], ret);
        if (ok) {
            *ret = (pp_variant){.type = PP_VARIANT_NIL};
            m->fn(o, checked, ret);
        }
    }
    pthread_mutex_unlock(&lock);
}

PP_API pp_status pp_plugin_entry(const pp_host_interface *host, pp_plugin_interface *out)
{
    if (!host || !out)
        return PP_ERR_INVALID_ARGUMENT;
    if (host->struct_size != sizeof *host || out->struct_size != sizeof *out)
        return PP_ERR_ABI; /* the host's log cannot be trusted at an unknown layout */
    host_log = host->log;
    host_user = host->user;
    if (host->interface_version != PP_PLUGIN_INTERFACE_VERSION) {
        logf_host(3,
                  "PhysPix plugin implements plugin interface version %d; host '%s' was built for version %u%s",
                  PP_PLUGIN_INTERFACE_VERSION, host->host_name ? host->host_name : "(unnamed)",
                  (unsigned)host->interface_version,
                  host->interface_version > PP_PLUGIN_INTERFACE_VERSION ? ": use a newer PhysPix plugin" : "");
        return PP_ERR_UNSUPPORTED;
    }
    for (int i = 0; i < CLASS_COUNT; i++) {
        const class_def *c = &plugin_classes[i];
        if (c->desc.method_count > (int32_t)(sizeof public_methods[i] / sizeof public_methods[i][0]))
            return PP_ERR_LIMIT; /* a class table outgrew its public copy: a build error in spirit */
        for (int32_t k = 0; k < c->desc.method_count; k++)
            public_methods[i][k] = c->methods[k].desc;
        public_classes[i] = c->desc;
        public_classes[i].methods = public_methods[i];
    }
    *out = (pp_plugin_interface){
        .struct_size = sizeof *out,
        .interface_version = PP_PLUGIN_INTERFACE_VERSION,
        .name = "PhysPix",
        .library_version = pp_version(),
        .minimum_level = PP_PLUGIN_LEVEL_SCENE,
        .initialize = plugin_initialize,
        .deinitialize = plugin_deinitialize,
        .class_count = CLASS_COUNT,
        .classes = public_classes,
        .object_create = plugin_object_create,
        .object_destroy = plugin_object_destroy,
        .call = plugin_call,
        .variant_clear = variant_clear,
    };
    return PP_OK;
}
