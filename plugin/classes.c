/* The plugin's classes, PhysPixWorld and PhysPixBody: one table entry per method (name, doc with units,
 * typed arguments, result) beside its implementation, each a thin call into the C ABI. Arguments
 * arrive checked against the table by plugin.c; what is left here is ranges, sizes and names. */
#include "plugin.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ARG(name, T) {name, PP_VARIANT_##T, 0, NULL}
#define BODY_ARG(name) {name, PP_VARIANT_OBJECT, 0, "PhysPixBody"}
/* The argument list as a static compound literal, and its length. */
#define ARGS(...)                                                                                      \
    .arg_count = (int32_t)(sizeof((const pp_plugin_arg[]){__VA_ARGS__}) / sizeof(pp_plugin_arg)),     \
    .args = (const pp_plugin_arg[]) { __VA_ARGS__ }
#define METHOD(fn, name_, ret_, doc_, ...) \
    {{.name = name_, .doc = doc_, .return_type = PP_VARIANT_##ret_, __VA_ARGS__}, fn}
#define RETURNS_BODY .return_class = "PhysPixBody"

/* ---- argument helpers ---- */

/* An INT argument that must lie in [lo, hi]; 0 and ret set to ERROR otherwise. */
static int int_in(const pp_variant *a, int64_t lo, int64_t hi, const char *what, int32_t *out, pp_variant *ret)
{
    if (a->as.integer < lo || a->as.integer > hi) {
        ret_error(ret, PP_ERR_INVALID_ARGUMENT, "%s must be in %lld..%lld, got %lld", what, (long long)lo,
                  (long long)hi, (long long)a->as.integer);
        return 0;
    }
    *out = (int32_t)a->as.integer;
    return 1;
}

/* A STRING argument that must be one of n names; its index, or -1 with ret set to ERROR naming the choices. */
static int name_index(const pp_variant *a, const char *const *names, int n, const char *what, pp_variant *ret)
{
    char known[160] = "";
    for (int i = 0; i < n; i++) {
        if (strcmp(a->as.string.data, names[i]) == 0)
            return i;
        snprintf(known + strlen(known), sizeof known - strlen(known), "%s\"%s\"", i ? (i + 1 < n ? ", " : " or ") : "",
                 names[i]);
    }
    ret_error(ret, PP_ERR_INVALID_ARGUMENT, "%s must be %s, got \"%s\"", what, known, a->as.string.data);
    return -1;
}

static int body_type_named(const pp_variant *a, const char *method, pp_body_type *out, pp_variant *ret)
{
    static const char *const names[] = {"dynamic", "static", "kinematic"}; /* in pp_body_type order */
    char what[96];
    snprintf(what, sizeof what, "%s: type", method);
    const int i = name_index(a, names, 3, what, ret);
    *out = (pp_body_type)i;
    return i >= 0;
}

/* Grow an array to hold n elements; 0 and ret set to ERROR on out of memory. */
static int reserve(void **items, int32_t *capacity, int32_t n, size_t size, pp_variant *ret)
{
    if (n <= *capacity)
        return 1;
    void *grown = realloc(*items, (size_t)n * size);
    if (!grown) {
        ret_error(ret, PP_ERR_OUT_OF_MEMORY, "out of memory growing a list to %d items", (int)n);
        return 0;
    }
    *items = grown;
    *capacity = n;
    return 1;
}

/* An index into a list of count items; 0 and ret set to ERROR when out of range. */
static int index_in(const pp_variant *a, int32_t count, const char *method, const char *list, pp_variant *ret)
{
    if (a->as.integer >= 0 && a->as.integer < count)
        return 1;
    ret_error(ret, PP_ERR_INVALID_ARGUMENT, "%s: index %lld is outside the %d %s read last", method,
              (long long)a->as.integer, (int)count, list);
    return 0;
}

static void ret_body(plugin_object *world_self, pp_body b, pp_variant *ret)
{
    if (b.id == 0)
        return; /* ret stays NIL */
    const uint64_t id = object_for_body(world_self->world_object, b);
    if (id)
        ret_object(ret, id);
    else
        ret_error(ret, PP_ERR_OUT_OF_MEMORY, "out of memory making a PhysPixBody object");
}

/* ---- PhysPixWorld ---- */

static void world_step(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.step";
    world_cache *c = self->cache;
    int32_t n = 0;
    if (ret_ok(ret, pp_world_step(self->world, (float)a[0].as.real), m) &&
        ret_ok(ret, pp_world_get_contacts(self->world, NULL, 0, &n), m) &&
        reserve((void **)&c->contacts, &c->contact_capacity, n, sizeof *c->contacts, ret))
        ret_ok(ret, pp_world_get_contacts(self->world, c->contacts, n, &c->contact_count), m);
}

/* Create a body from a def whose bitmap the caller filled, and answer its object. */
static void add_body(plugin_object *self, pp_body_def *d, const pp_variant *pos, const pp_variant *type,
                     const char *m, pp_variant *ret)
{
    pp_body b;
    d->position = pos->as.vec2;
    d->is_sensor = self->cache->is_sensor;
    d->one_way = self->cache->one_way;
    d->one_way_direction = self->cache->one_way_direction;
    if (body_type_named(type, m, &d->type, ret) && ret_ok(ret, pp_body_create(self->world, d, &b), m))
        ret_body(self, b, ret);
}

/* A plane given as bytes must be exactly width·height·channels long: the library cannot check it. */
static int plane_sized(const pp_variant *bytes, const pp_variant *w, const pp_variant *h, int channels,
                       const char *m, pp_body_def *d, pp_variant *ret)
{
    if (!int_in(w, 1, PP_MAX_BITMAP_SIDE, "width", &d->width, ret) ||
        !int_in(h, 1, PP_MAX_BITMAP_SIDE, "height", &d->height, ret))
        return 0;
    const int64_t need = (int64_t)d->width * d->height * channels;
    if (bytes->as.bytes.length != need) {
        ret_error(ret, PP_ERR_INVALID_ARGUMENT, "%s: %dx%d px needs %lld bytes, got %lld", m, (int)d->width,
                  (int)d->height, (long long)need, (long long)bytes->as.bytes.length);
        return 0;
    }
    return 1;
}

static void world_add_body(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_body_def d = pp_body_def_default();
    d.mask = a[0].as.bytes.data;
    if (plane_sized(&a[0], &a[1], &a[2], 1, "PhysPixWorld.add_body", &d, ret))
        add_body(self, &d, &a[3], &a[4], "PhysPixWorld.add_body", ret);
}

static void world_add_body_rgba(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_body_def d = pp_body_def_default();
    d.rgba = a[0].as.bytes.data;
    if (plane_sized(&a[0], &a[1], &a[2], 4, "PhysPixWorld.add_body_rgba", &d, ret))
        add_body(self, &d, &a[3], &a[4], "PhysPixWorld.add_body_rgba", ret);
}

static void world_add_body_png(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.add_body_png";
    pp_body_def d = pp_body_def_default();
    if (!ret_ok(ret, pp_image_info(a[0].as.string.data, &d.width, &d.height), m))
        return;
    const int64_t size = (int64_t)d.width * d.height * 4;
    uint8_t *rgba = malloc((size_t)size);
    if (!rgba) {
        ret_error(ret, PP_ERR_OUT_OF_MEMORY, "%s: out of memory for %lld bytes", m, (long long)size);
        return;
    }
    d.rgba = rgba;
    if (ret_ok(ret, pp_image_load(a[0].as.string.data, rgba, size, &d.width, &d.height), m))
        add_body(self, &d, &a[1], &a[2], m, ret);
    free(rgba);
}

static void world_erase_circle(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    int32_t changed = 0;
    if (ret_ok(ret, pp_world_erase_circle(self->world, a[0].as.vec2, (float)a[1].as.real, &changed),
               "PhysPixWorld.erase_circle"))
        ret_int(ret, changed);
}

static void world_get_body_count(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.get_body_count";
    world_cache *c = self->cache;
    int32_t n = 0;
    if (ret_ok(ret, pp_world_get_bodies(self->world, NULL, 0, &n), m) &&
        reserve((void **)&c->bodies, &c->body_capacity, n, sizeof *c->bodies, ret) &&
        ret_ok(ret, pp_world_get_bodies(self->world, c->bodies, n, &c->body_count), m))
        ret_int(ret, c->body_count);
}

/* Floats a body takes in get_body_states' packing: x, y, angle, vx, vy, angular velocity, awake (0 or 1). */
enum { STATE_FLOATS = 7 };

static void world_get_body_states(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.get_body_states";
    world_cache *c = self->cache;
    int32_t n = 0;
    if (!ret_ok(ret, pp_world_get_body_states(self->world, NULL, 0, &n), m) ||
        !reserve((void **)&c->states, &c->state_capacity, n, sizeof *c->states, ret) ||
        !ret_ok(ret, pp_world_get_body_states(self->world, c->states, n, &n), m))
        return;
    uint8_t *out = ret_bytes(ret, (int64_t)n * STATE_FLOATS * (int64_t)sizeof(float));
    for (int32_t i = 0; out && i < n; i++) {
        const pp_body_state *s = &c->states[i];
        const float f[STATE_FLOATS] = {s->position.x,        s->position.y,        s->angle, s->linear_velocity.x,
                                       s->linear_velocity.y, s->angular_velocity, (float)s->awake};
        memcpy(out + (size_t)i * sizeof f, f, sizeof f);
    }
}

static void world_get_body(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    if (index_in(&a[0], self->cache->body_count, "PhysPixWorld.get_body", "bodies", ret))
        ret_body(self, self->cache->bodies[a[0].as.integer], ret);
}

static void world_get_contact_count(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_int(ret, self->cache->contact_count);
}

/* The contact an index argument names, or NULL with ret set to ERROR. */
static const pp_contact *contact_at(plugin_object *self, const pp_variant *a, const char *m, pp_variant *ret)
{
    return index_in(a, self->cache->contact_count, m, "contacts", ret) ? &self->cache->contacts[a->as.integer]
                                                                         : NULL;
}

static void world_get_contact_point(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_contact *c = contact_at(self, &a[0], "PhysPixWorld.get_contact_point", ret);
    if (c)
        ret_vec2(ret, c->point);
}

static void world_get_contact_normal(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_contact *c = contact_at(self, &a[0], "PhysPixWorld.get_contact_normal", ret);
    if (c)
        ret_vec2(ret, c->normal);
}

static void world_get_contact_depth(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_contact *c = contact_at(self, &a[0], "PhysPixWorld.get_contact_depth", ret);
    if (c)
        ret_float(ret, c->depth);
}

static void world_get_contact_normal_impulse(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_contact *c = contact_at(self, &a[0], "PhysPixWorld.get_contact_normal_impulse", ret);
    if (c)
        ret_float(ret, c->normal_impulse);
}

static void world_get_contact_body_a(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_contact *c = contact_at(self, &a[0], "PhysPixWorld.get_contact_body_a", ret);
    if (c)
        ret_body(self, c->a, ret);
}

static void world_get_contact_body_b(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_contact *c = contact_at(self, &a[0], "PhysPixWorld.get_contact_body_b", ret);
    if (c)
        ret_body(self, c->b, ret);
}

static void world_get_event_count(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.get_event_count";
    world_cache *c = self->cache;
    int32_t n = 0;
    if (ret_ok(ret, pp_world_get_events(self->world, NULL, 0, &n), m) &&
        reserve((void **)&c->events, &c->event_capacity, n, sizeof *c->events, ret) &&
        ret_ok(ret, pp_world_get_events(self->world, c->events, n, &c->event_count), m))
        ret_int(ret, c->event_count);
}

static const pp_event *event_at(plugin_object *self, const pp_variant *a, const char *m, pp_variant *ret)
{
    return index_in(a, self->cache->event_count, m, "events", ret) ? &self->cache->events[a->as.integer] : NULL;
}

static void world_get_event_type(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    static const char *names[] = {"unknown",     "split",        "destroyed",  "contact_begin",
                                  "contact_end", "sensor_begin", "sensor_end", "joint_broken"}; /* pp_event_type order */
    const pp_event *e = event_at(self, &a[0], "PhysPixWorld.get_event_type", ret);
    if (e)
        ret_string(ret, (uint32_t)e->type < sizeof names / sizeof names[0] ? names[e->type] : "unknown");
}

static void world_get_event_point(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_event *e = event_at(self, &a[0], "PhysPixWorld.get_event_point", ret);
    if (e)
        ret_vec2(ret, e->point);
}

static void world_get_event_normal(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_event *e = event_at(self, &a[0], "PhysPixWorld.get_event_normal", ret);
    if (e)
        ret_vec2(ret, e->normal);
}

static void world_get_event_approach_speed(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_event *e = event_at(self, &a[0], "PhysPixWorld.get_event_approach_speed", ret);
    if (e)
        ret_float(ret, e->approach_speed);
}

static void world_get_event_body(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_event *e = event_at(self, &a[0], "PhysPixWorld.get_event_body", ret);
    if (e)
        ret_body(self, e->body, ret);
}

static void world_get_event_other(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_event *e = event_at(self, &a[0], "PhysPixWorld.get_event_other", ret);
    if (e)
        ret_body(self, e->other, ret);
}

static void world_get_event_joint(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_event *e = event_at(self, &a[0], "PhysPixWorld.get_event_joint", ret);
    if (e)
        ret_int(ret, (int64_t)e->joint.id);
}

/* ---- joints: ints (the pp_joint id), which the library checks ---- */

static pp_joint joint_of(const pp_variant *a)
{
    return (pp_joint){(uint64_t)a->as.integer};
}

/* A joint's body argument: a PhysPixBody, or this PhysPixWorld for the static world (a zero body). */
static int joint_body(plugin_object *self, const pp_variant *a, const char *what, pp_body *out, pp_variant *ret)
{
    const plugin_object *o = object_get(a->as.object); /* live: plugin.c checked it */
    *out = o->kind == OBJECT_BODY ? o->body : (pp_body){0};
    if (o->kind == OBJECT_BODY || o == self)
        return 1;
    ret_error(ret, PP_ERR_INVALID_ARGUMENT, "PhysPixWorld.add_joint: %s must be a PhysPixBody or this world (the static "
              "world), got another PhysPixWorld", what);
    return 0;
}

static void world_add_joint(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    static const char *const names[] = {"revolute", "prismatic", "distance", "weld", "mouse"}; /* from REVOLUTE = 1 */
    const char *m = "PhysPixWorld.add_joint";
    const world_cache *c = self->cache;
    const int type = name_index(&a[0], names, 5, "PhysPixWorld.add_joint: type", ret);
    if (type < 0)
        return;
    pp_joint_def d = pp_joint_def_default((pp_joint_type)(type + 1));
    if (c->has_joint_options) {
        d.collide_connected = c->joint_options.collide_connected;
        d.spring_hertz = c->joint_options.spring_hertz;
        d.spring_damping_ratio = c->joint_options.spring_damping_ratio;
        d.max_force = c->joint_options.max_force;
        d.break_force = c->joint_options.break_force;
    }
    d.anchor_a = a[3].as.vec2;
    d.anchor_b = a[4].as.vec2;
    d.axis = a[5].as.vec2;
    pp_joint j;
    if (joint_body(self, &a[1], "body_a", &d.body_a, ret) && joint_body(self, &a[2], "body_b", &d.body_b, ret) &&
        ret_ok(ret, pp_joint_create(self->world, &d, &j), m))
        ret_int(ret, (int64_t)j.id);
}

/* What add_joint gives the joints it makes from now on; checked when one is made. */
static void world_set_joint_options(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_joint_def *o = &self->cache->joint_options;
    o->collide_connected = a[0].as.boolean != 0;
    o->spring_hertz = (float)a[1].as.real;
    o->spring_damping_ratio = (float)a[2].as.real;
    o->max_force = (float)a[3].as.real;
    o->break_force = (float)a[4].as.real;
    self->cache->has_joint_options = 1;
}

static void world_destroy_joint(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_joint_destroy(self->world, joint_of(&a[0])), "PhysPixWorld.destroy_joint");
}

static void world_get_joint_force(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_vec2 f;
    if (ret_ok(ret, pp_joint_get_reaction(self->world, joint_of(&a[0]), &f, NULL), "PhysPixWorld.get_joint_force"))
        ret_vec2(ret, f);
}

static void world_get_joint_torque(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    float t;
    if (ret_ok(ret, pp_joint_get_reaction(self->world, joint_of(&a[0]), NULL, &t), "PhysPixWorld.get_joint_torque"))
        ret_float(ret, t);
}

static void world_get_joint_value(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    float v;
    if (ret_ok(ret, pp_joint_get_value(self->world, joint_of(&a[0]), &v, NULL), "PhysPixWorld.get_joint_value"))
        ret_float(ret, v);
}

static void world_get_joint_speed(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    float s;
    if (ret_ok(ret, pp_joint_get_value(self->world, joint_of(&a[0]), NULL, &s), "PhysPixWorld.get_joint_speed"))
        ret_float(ret, s);
}

static void world_set_joint_motor(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_joint_set_motor(self->world, joint_of(&a[0]), a[1].as.boolean, (float)a[2].as.real,
                                   (float)a[3].as.real),
           "PhysPixWorld.set_joint_motor");
}

static void world_set_joint_limits(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_joint_set_limits(self->world, joint_of(&a[0]), a[1].as.boolean, (float)a[2].as.real,
                                    (float)a[3].as.real),
           "PhysPixWorld.set_joint_limits");
}

static void world_set_joint_target(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_joint_set_target(self->world, joint_of(&a[0]), a[1].as.vec2), "PhysPixWorld.set_joint_target");
}

/* The two body arguments' handles; the library refuses a body of another world (PP_ERR_INVALID_HANDLE). */
static void pair_bodies(const pp_variant *a, pp_body *ba, pp_body *bb)
{
    *ba = object_get(a[0].as.object)->body, *bb = object_get(a[1].as.object)->body;
}

static void world_collide(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.collide";
    pp_body ba, bb;
    pair_bodies(a, &ba, &bb);
    /* Two contacts per pair in MANIFOLD mode: a first capacity that the second call rarely needs to grow. */
    world_cache *c = self->cache;
    int32_t n = 0;
    c->contact_count = 0;
    if (!reserve((void **)&c->contacts, &c->contact_capacity, 4, sizeof *c->contacts, ret) ||
        !ret_ok(ret, pp_world_collide(self->world, ba, bb, c->contacts, c->contact_capacity, &n), m))
        return;
    if (n > c->contact_capacity &&
        (!reserve((void **)&c->contacts, &c->contact_capacity, n, sizeof *c->contacts, ret) ||
         !ret_ok(ret, pp_world_collide(self->world, ba, bb, c->contacts, n, &n), m)))
        return;
    c->contact_count = n;
    ret_int(ret, n);
}

/* ---- raycasts and queries ---- */

/* A collision filter argument: the 32 bits pp_world_raycast and the queries take. */
static int mask_bits(const pp_variant *a, const char *m, uint32_t *out, pp_variant *ret)
{
    if (a->as.integer < 0 || a->as.integer > UINT32_MAX) {
        ret_error(ret, PP_ERR_INVALID_ARGUMENT, "%s: mask must be in 0..%u, got %lld", m, UINT32_MAX,
                  (long long)a->as.integer);
        return 0;
    }
    *out = (uint32_t)a->as.integer;
    return 1;
}

static void world_raycast(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.raycast";
    world_cache *c = self->cache;
    uint32_t mask;
    int32_t hit = 0;
    c->ray = (pp_raycast_hit){0};
    if (mask_bits(&a[2], m, &mask, ret) &&
        ret_ok(ret, pp_world_raycast(self->world, a[0].as.vec2, a[1].as.vec2, mask, &c->ray, &hit), m)) {
        if (!hit)
            c->ray = (pp_raycast_hit){0};
        ret_bool(ret, hit);
    }
}

static void world_get_ray_body(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_body(self, self->cache->ray.body, ret);
}

static void world_get_ray_point(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_vec2(ret, self->cache->ray.point);
}

static void world_get_ray_normal(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_vec2(ret, self->cache->ray.normal);
}

static void world_get_ray_fraction(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_float(ret, self->cache->ray.fraction);
}

/* The three queries share one shape once their region is bound; these adapt it. */
typedef pp_status (*query_fn)(pp_world w, const pp_variant *a, uint32_t mask, pp_body *out, int32_t capacity,
                              int32_t *count);
static pp_status query_point(pp_world w, const pp_variant *a, uint32_t mask, pp_body *out, int32_t cap, int32_t *n)
{
    return pp_world_query_point(w, a[0].as.vec2, mask, out, cap, n);
}

static pp_status query_aabb(pp_world w, const pp_variant *a, uint32_t mask, pp_body *out, int32_t cap, int32_t *n)
{
    return pp_world_query_aabb(w, a[0].as.vec2, a[1].as.vec2, mask, out, cap, n);
}

static pp_status query_circle(pp_world w, const pp_variant *a, uint32_t mask, pp_body *out, int32_t cap, int32_t *n)
{
    return pp_world_query_circle(w, a[0].as.vec2, (float)a[1].as.real, mask, out, cap, n);
}

/* Run a query into the cache (its mask is argument mask_arg) and answer how many bodies it found. */
static void run_query(plugin_object *self, const pp_variant *a, int mask_arg, query_fn fn, const char *m,
                      pp_variant *ret)
{
    world_cache *c = self->cache;
    uint32_t mask;
    int32_t n = 0;
    c->found_count = 0;
    if (mask_bits(&a[mask_arg], m, &mask, ret) && ret_ok(ret, fn(self->world, a, mask, NULL, 0, &n), m) &&
        reserve((void **)&c->found, &c->found_capacity, n, sizeof *c->found, ret) &&
        ret_ok(ret, fn(self->world, a, mask, c->found, n, &c->found_count), m)) {
        if (c->found_count > n)
            c->found_count = n;
        ret_int(ret, c->found_count);
    }
}

static void world_query_point(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    run_query(self, a, 1, query_point, "PhysPixWorld.query_point", ret);
}

static void world_query_aabb(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    run_query(self, a, 2, query_aabb, "PhysPixWorld.query_aabb", ret);
}

static void world_query_circle(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    run_query(self, a, 2, query_circle, "PhysPixWorld.query_circle", ret);
}

static void world_get_query_body(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    if (index_in(&a[0], self->cache->found_count, "PhysPixWorld.get_query_body", "bodies a query found", ret))
        ret_body(self, self->cache->found[a[0].as.integer], ret);
}

static void world_set_contact_events(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_world_set_contact_events(self->world, a[0].as.boolean), "PhysPixWorld.set_contact_events");
}

/* The sensor and one-way settings of the bodies add_body* make from now on; checked when one is made. */
static void world_set_body_options(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    world_cache *c = self->cache;
    c->is_sensor = a[0].as.boolean != 0;
    c->one_way = a[1].as.boolean != 0;
    c->one_way_direction = a[2].as.vec2;
}

static void world_get_step_ms(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_step_stats s;
    if (ret_ok(ret, pp_world_get_stats(self->world, &s), "PhysPixWorld.get_step_ms"))
        ret_float(ret, s.total_ms);
}

/* Replace this object's world by the scene's; its old bodies' objects become stale. */
/* Put a newly loaded world in place of the object's; the old bodies' objects go stale. */
static void world_replace(plugin_object *self, pp_world loaded)
{
    world_cache *c = self->cache;
    for (int32_t i = 0; i < c->body_object_capacity; i++)
        object_free(c->body_objects[i]);
    pp_world_destroy(self->world);
    self->world = loaded;
    c->contact_count = c->event_count = c->body_count = c->edit_count = c->found_count = 0;
    c->debug_view = (pp_collision_view){0};
    c->ray = (pp_raycast_hit){0};
}

static void world_load_scene(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_world loaded;
    if (ret_ok(ret, pp_world_load_scene(a[0].as.string.data, &loaded), "PhysPixWorld.load_scene"))
        world_replace(self, loaded); /* on failure the old world stays as it was */
}

static void world_save_snapshot(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_world_save_snapshot(self->world, a[0].as.string.data), "PhysPixWorld.save_snapshot");
}

static void world_load_snapshot(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_world loaded;
    if (ret_ok(ret, pp_world_load_snapshot(a[0].as.string.data, &loaded), "PhysPixWorld.load_snapshot"))
        world_replace(self, loaded);
}

static void world_get_time(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    double t;
    if (ret_ok(ret, pp_world_get_time(self->world, &t), "PhysPixWorld.get_time"))
        ret_float(ret, t);
}

static int camera_of(plugin_object *self, const char *m, pp_camera *cam, pp_variant *ret)
{
    return ret_ok(ret, pp_world_get_camera(self->world, cam), m);
}

static void world_get_camera_center(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_camera cam;
    if (camera_of(self, "PhysPixWorld.get_camera_center", &cam, ret))
        ret_vec2(ret, cam.center);
}

static void world_get_camera_zoom(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_camera cam;
    if (camera_of(self, "PhysPixWorld.get_camera_zoom", &cam, ret))
        ret_float(ret, cam.zoom);
}

static void world_get_camera_size(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_camera cam;
    if (camera_of(self, "PhysPixWorld.get_camera_size", &cam, ret))
        ret_vec2(ret, (pp_vec2){(float)cam.width, (float)cam.height});
}

static void world_schedule_erase(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_timed_edit e = {.time = a[0].as.real, .type = PP_EDIT_ERASE_CIRCLE, .center = a[1].as.vec2,
                             .radius = (float)a[2].as.real};
    ret_ok(ret, pp_world_schedule_edit(self->world, &e), "PhysPixWorld.schedule_erase");
}

static void world_get_scheduled_edit_count(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.get_scheduled_edit_count";
    world_cache *c = self->cache;
    int32_t n = 0;
    if (ret_ok(ret, pp_world_get_scheduled_edits(self->world, NULL, 0, &n), m) &&
        reserve((void **)&c->edits, &c->edit_capacity, n, sizeof *c->edits, ret) &&
        ret_ok(ret, pp_world_get_scheduled_edits(self->world, c->edits, n, &c->edit_count), m))
        ret_int(ret, c->edit_count);
}

static const pp_timed_edit *edit_at(plugin_object *self, const pp_variant *a, const char *m, pp_variant *ret)
{
    return index_in(a, self->cache->edit_count, m, "scheduled edits", ret) ? &self->cache->edits[a->as.integer]
                                                                            : NULL;
}

static void world_get_scheduled_edit_time(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_timed_edit *e = edit_at(self, &a[0], "PhysPixWorld.get_scheduled_edit_time", ret);
    if (e)
        ret_float(ret, e->time);
}

static void world_get_scheduled_edit_type(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_timed_edit *e = edit_at(self, &a[0], "PhysPixWorld.get_scheduled_edit_type", ret);
    if (e)
        ret_string(ret, e->type == PP_EDIT_PAINT_CIRCLE ? "paint" : "erase");
}

static void world_get_scheduled_edit_center(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_timed_edit *e = edit_at(self, &a[0], "PhysPixWorld.get_scheduled_edit_center", ret);
    if (e)
        ret_vec2(ret, e->center);
}

static void world_get_scheduled_edit_radius(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_timed_edit *e = edit_at(self, &a[0], "PhysPixWorld.get_scheduled_edit_radius", ret);
    if (e)
        ret_float(ret, e->radius);
}

/* The pair's sampled grid as cell flags (PP_CELL_*); the view and local normals stay for the get_debug_* calls. */
static void world_debug_collision(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.debug_collision";
    world_cache *c = self->cache;
    pp_body ba, bb;
    c->debug_view = (pp_collision_view){0};
    pair_bodies(a, &ba, &bb);
    /* A first call with no room fills the view, which sizes the second. */
    pp_collision_view v = {0};
    pp_status st = pp_world_debug_collision(self->world, ba, bb, NULL, NULL, 0, &v);
    const int64_t cells = (int64_t)v.width * v.height;
    if (st != PP_OK && !(st == PP_ERR_INVALID_ARGUMENT && cells > 0)) {
        ret_ok(ret, st, m);
        return;
    }
    if (cells > c->debug_capacity) {
        pp_vec2 *grown = realloc(c->debug_normals, (size_t)cells * sizeof *grown);
        if (!grown) {
            ret_error(ret, PP_ERR_OUT_OF_MEMORY, "%s: out of memory for %lld cells", m, (long long)cells);
            return;
        }
        c->debug_normals = grown, c->debug_capacity = cells;
    }
    uint8_t *flags = ret_bytes(ret, cells);
    if (!flags)
        return;
    if (!ret_ok(ret, pp_world_debug_collision(self->world, ba, bb, flags, c->debug_normals, cells, &v), m)) {
        free(flags); /* ret now holds the error, not the bytes */
        return;
    }
    c->debug_view = v;
}

static void world_get_debug_size(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_collision_view *v = &self->cache->debug_view;
    ret_vec2(ret, (pp_vec2){(float)v->width, (float)v->height});
}

static void world_get_debug_origin(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_vec2(ret, self->cache->debug_view.origin);
}

static void world_get_debug_step_x(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_vec2(ret, self->cache->debug_view.step_x);
}

static void world_get_debug_step_y(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_vec2(ret, self->cache->debug_view.step_y);
}

static void world_get_debug_normal(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_vec2(ret, self->cache->debug_view.normal);
}

static void world_get_debug_local_normals(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const pp_collision_view *v = &self->cache->debug_view;
    const int64_t size = (int64_t)v->width * v->height * (int64_t)sizeof(pp_vec2);
    uint8_t *out = ret_bytes(ret, size);
    if (out && size > 0)
        memcpy(out, self->cache->debug_normals, (size_t)size);
}

static const method_def world_methods[] = {
    METHOD(world_step, "step", NIL, "advance the world by dt seconds (0 < dt <= 1)", ARGS(ARG("dt", FLOAT))),
    METHOD(world_add_body, "add_body", OBJECT,
           "add a body from a collision mask (width*height bytes, non-zero solid) at a world position, px",
           ARGS(ARG("mask", BYTES), ARG("width", INT), ARG("height", INT), ARG("position", VEC2),
                ARG("type", STRING)),
           RETURNS_BODY),
    METHOD(world_add_body_rgba, "add_body_rgba", OBJECT,
           "add a body from an RGBA8 sprite (alpha >= 128 solid) at a world position, px",
           ARGS(ARG("rgba", BYTES), ARG("width", INT), ARG("height", INT), ARG("position", VEC2),
                ARG("type", STRING)),
           RETURNS_BODY),
    METHOD(world_add_body_png, "add_body_png", OBJECT, "add a body from a PNG sprite file at a world position, px",
           ARGS(ARG("path", STRING), ARG("position", VEC2), ARG("type", STRING)), RETURNS_BODY),
    METHOD(world_erase_circle, "erase_circle", INT,
           "erase every body's pixels within radius (px) of a world point (px); returns pixels erased",
           ARGS(ARG("center", VEC2), ARG("radius", FLOAT))),
    METHOD(world_get_body_count, "get_body_count", INT, "read the live bodies; returns how many", .arg_count = 0),
    METHOD(world_get_body_states, "get_body_states", BYTES,
           "every live body's state in get_body_count's order, 7 little-endian float32 each: x, y (pivot, px), angle "
           "(rad), vx, vy (px/s), angular velocity (rad/s), awake (0 or 1)",
           .arg_count = 0),
    METHOD(world_get_body, "get_body", OBJECT, "the index-th body read by get_body_count",
           ARGS(ARG("index", INT)), RETURNS_BODY),
    METHOD(world_get_contact_count, "get_contact_count", INT, "contacts of the last step (or collide)",
           .arg_count = 0),
    METHOD(world_get_contact_point, "get_contact_point", VEC2, "world contact point, px", ARGS(ARG("index", INT))),
    METHOD(world_get_contact_normal, "get_contact_normal", VEC2, "unit normal from body a to body b",
           ARGS(ARG("index", INT))),
    METHOD(world_get_contact_depth, "get_contact_depth", FLOAT, "penetration along the normal, px",
           ARGS(ARG("index", INT))),
    METHOD(world_get_contact_normal_impulse, "get_contact_normal_impulse", FLOAT,
           "impulse the solver applied along the normal in the last substep, mass*px/s (0 after collide)",
           ARGS(ARG("index", INT))),
    METHOD(world_get_contact_body_a, "get_contact_body_a", OBJECT, "first body of a contact", ARGS(ARG("index", INT)),
           RETURNS_BODY),
    METHOD(world_get_contact_body_b, "get_contact_body_b", OBJECT, "second body of a contact",
           ARGS(ARG("index", INT)), RETURNS_BODY),
    METHOD(world_get_event_count, "get_event_count", INT, "read (and forget) the pending events; returns how many",
           .arg_count = 0),
    METHOD(world_get_event_type, "get_event_type", STRING,
           "\"split\", \"destroyed\", \"contact_begin\", \"contact_end\", \"sensor_begin\", \"sensor_end\" or "
           "\"joint_broken\"",
           ARGS(ARG("index", INT))),
    METHOD(world_get_event_body, "get_event_body", OBJECT,
           "the body an event happened to (split: the parent; sensor_*: the sensor)", ARGS(ARG("index", INT)),
           RETURNS_BODY),
    METHOD(world_get_event_other, "get_event_other", OBJECT,
           "split: the new body; destroyed: nil; contact_*, sensor_*: the other body of the pair",
           ARGS(ARG("index", INT)), RETURNS_BODY),
    METHOD(world_get_event_point, "get_event_point", VEC2,
           "contact_begin, sensor_begin: world point of the first contact, px; else zero", ARGS(ARG("index", INT))),
    METHOD(world_get_event_normal, "get_event_normal", VEC2,
           "contact_begin, sensor_begin: unit normal from the event's body to its other; else zero",
           ARGS(ARG("index", INT))),
    METHOD(world_get_event_approach_speed, "get_event_approach_speed", FLOAT,
           "contact_begin, sensor_begin: speed at which the pair closed along the normal, px/s; else zero",
           ARGS(ARG("index", INT))),
    METHOD(world_get_event_joint, "get_event_joint", INT, "joint_broken: the joint (now stale); else 0",
           ARGS(ARG("index", INT))),
    METHOD(world_add_joint, "add_joint", INT,
           "join two bodies (a PhysPixBody, or this world for the static world): type \"revolute\", \"prismatic\", "
           "\"distance\", \"weld\" or \"mouse\", anchors in world px now, a prismatic's axis; returns the joint (int)",
           ARGS(ARG("type", STRING), ARG("body_a", OBJECT), ARG("body_b", OBJECT), ARG("anchor_a", VEC2),
                ARG("anchor_b", VEC2), ARG("axis", VEC2))),
    METHOD(world_set_joint_options, "set_joint_options", NIL,
           "give later add_joint joints these (until called, each type's defaults): spring Hz (0 rigid) and damping "
           "ratio, a mouse joint's max_force and break_force (mass*px/s^2, 0 none)",
           ARGS(ARG("collide_connected", BOOL), ARG("spring_hertz", FLOAT), ARG("spring_damping_ratio", FLOAT),
                ARG("max_force", FLOAT), ARG("break_force", FLOAT))),
    METHOD(world_destroy_joint, "destroy_joint", NIL, "destroy a joint; its int goes stale", ARGS(ARG("joint", INT))),
    METHOD(world_get_joint_force, "get_joint_force", VEC2, "force the joint put on body_b in the last substep, mass*px/s^2",
           ARGS(ARG("joint", INT))),
    METHOD(world_get_joint_torque, "get_joint_torque", FLOAT,
           "torque the joint put on body_b in the last substep, mass*px^2/s^2", ARGS(ARG("joint", INT))),
    METHOD(world_get_joint_value, "get_joint_value", FLOAT,
           "revolute: angle since creation, rad; prismatic: translation, px; distance: length, px; else 0",
           ARGS(ARG("joint", INT))),
    METHOD(world_get_joint_speed, "get_joint_speed", FLOAT, "the rate of get_joint_value, rad/s or px/s",
           ARGS(ARG("joint", INT))),
    METHOD(world_set_joint_motor, "set_joint_motor", NIL,
           "revolute, prismatic: switch the motor; speed rad/s or px/s, max_force >= 0 (a torque for revolute)",
           ARGS(ARG("joint", INT), ARG("enabled", BOOL), ARG("speed", FLOAT), ARG("max_force", FLOAT))),
    METHOD(world_set_joint_limits, "set_joint_limits", NIL,
           "revolute (rad, -pi..pi), prismatic (px), distance (min and max length, px): switch and set the limits",
           ARGS(ARG("joint", INT), ARG("enabled", BOOL), ARG("lower", FLOAT), ARG("upper", FLOAT))),
    METHOD(world_set_joint_target, "set_joint_target", NIL, "mouse: move the target, world px",
           ARGS(ARG("joint", INT), ARG("target", VEC2))),
    METHOD(world_raycast, "raycast", BOOL,
           "cast a segment between world points (px) against bodies whose category meets mask (0..2^32-1; "
           "sensors skipped); whether it met a solid pixel, which get_ray_* describe",
           ARGS(ARG("from", VEC2), ARG("to", VEC2), ARG("mask", INT))),
    METHOD(world_get_ray_body, "get_ray_body", OBJECT, "the body the last raycast hit; nil if it missed",
           .arg_count = 0, RETURNS_BODY),
    METHOD(world_get_ray_point, "get_ray_point", VEC2,
           "world point where the last ray entered the first solid pixel, px; zero if it missed", .arg_count = 0),
    METHOD(world_get_ray_normal, "get_ray_normal", VEC2,
           "unit surface normal at the last ray's hit, out of the body; zero if it missed", .arg_count = 0),
    METHOD(world_get_ray_fraction, "get_ray_fraction", FLOAT,
           "where along from -> to the last ray's hit lies, 0..1; zero if it missed", .arg_count = 0),
    METHOD(world_query_point, "query_point", INT,
           "find the bodies (category meeting mask, sensors skipped) with a solid pixel whose square contains a "
           "world point (px); returns how many, read with get_query_body",
           ARGS(ARG("point", VEC2), ARG("mask", INT))),
    METHOD(world_query_aabb, "query_aabb", INT,
           "as query_point, for solid pixel centres in the world box [lower, upper], px",
           ARGS(ARG("lower", VEC2), ARG("upper", VEC2), ARG("mask", INT))),
    METHOD(world_query_circle, "query_circle", INT,
           "as query_point, for solid pixel centres within radius (px) of a world point (px)",
           ARGS(ARG("center", VEC2), ARG("radius", FLOAT), ARG("mask", INT))),
    METHOD(world_get_query_body, "get_query_body", OBJECT, "the index-th body the last query_* found, in slot order",
           ARGS(ARG("index", INT)), RETURNS_BODY),
    METHOD(world_set_contact_events, "set_contact_events", NIL,
           "queue contact_begin and contact_end events (default false); pairs touching then begin at the next step",
           ARGS(ARG("enabled", BOOL))),
    METHOD(world_set_body_options, "set_body_options", NIL,
           "make later add_body* bodies sensors and/or one-way platforms that bodies land on from one_way_direction "
           "(bitmap axes, length > 0; default false, false, (0, -1): from above)",
           ARGS(ARG("is_sensor", BOOL), ARG("one_way", BOOL), ARG("one_way_direction", VEC2))),
    METHOD(world_collide, "collide", INT,
           "run the narrowphase on two bodies at their current poses; returns how many contacts, which replace "
           "the list get_contact_* read",
           ARGS(BODY_ARG("a"), BODY_ARG("b"))),
    METHOD(world_get_step_ms, "get_step_ms", FLOAT, "wall time of the last step, milliseconds", .arg_count = 0),
    METHOD(world_load_scene, "load_scene", NIL,
           "replace this object's world by a JSON scene file's (PNG paths relative to it); the old bodies' "
           "objects become stale",
           ARGS(ARG("path", STRING))),
    METHOD(world_save_snapshot, "save_snapshot", NIL,
           "write the whole world into a new folder (world.json and PNG planes), atomically", ARGS(ARG("folder", STRING))),
    METHOD(world_load_snapshot, "load_snapshot", NIL,
           "replace this object's world by a snapshot's, which steps on exactly as the saved one; the old bodies' "
           "objects become stale",
           ARGS(ARG("folder", STRING))),
    METHOD(world_get_time, "get_time", FLOAT, "simulated time since the world was made, s", .arg_count = 0),
    METHOD(world_get_camera_center, "get_camera_center", VEC2, "world point at the image centre, px",
           .arg_count = 0),
    METHOD(world_get_camera_zoom, "get_camera_zoom", FLOAT, "image px per world px", .arg_count = 0),
    METHOD(world_get_camera_size, "get_camera_size", VEC2, "image width and height, image px", .arg_count = 0),
    METHOD(world_schedule_erase, "schedule_erase", NIL,
           "erase every body's pixels within radius (px) of a world point (px) at a world time (s)",
           ARGS(ARG("time", FLOAT), ARG("center", VEC2), ARG("radius", FLOAT))),
    METHOD(world_get_scheduled_edit_count, "get_scheduled_edit_count", INT,
           "read the edits still pending, in the order they apply; returns how many", .arg_count = 0),
    METHOD(world_get_scheduled_edit_time, "get_scheduled_edit_time", FLOAT, "when an edit applies, world time, s",
           ARGS(ARG("index", INT))),
    METHOD(world_get_scheduled_edit_type, "get_scheduled_edit_type", STRING, "\"erase\" or \"paint\"",
           ARGS(ARG("index", INT))),
    METHOD(world_get_scheduled_edit_center, "get_scheduled_edit_center", VEC2, "an edit's circle centre, world px",
           ARGS(ARG("index", INT))),
    METHOD(world_get_scheduled_edit_radius, "get_scheduled_edit_radius", FLOAT, "an edit's circle radius, px",
           ARGS(ARG("index", INT))),
    METHOD(world_debug_collision, "debug_collision", BYTES,
           "a pair's sampled grid, width*height bytes of flags (1 first body, 2 second, 4 critical), rows "
           "along the grid's y; the get_debug_* calls describe it",
           ARGS(BODY_ARG("a"), BODY_ARG("b"))),
    METHOD(world_get_debug_size, "get_debug_size", VEC2, "the last debug grid's width and height, cells",
           .arg_count = 0),
    METHOD(world_get_debug_origin, "get_debug_origin", VEC2, "world position of the centre of cell (0, 0), px",
           .arg_count = 0),
    METHOD(world_get_debug_step_x, "get_debug_step_x", VEC2, "world offset from a cell to the next along x, px",
           .arg_count = 0),
    METHOD(world_get_debug_step_y, "get_debug_step_y", VEC2, "world offset from a cell to the next along y, px",
           .arg_count = 0),
    METHOD(world_get_debug_normal, "get_debug_normal", VEC2, "the pair's global normal from a to b; zero apart",
           .arg_count = 0),
    METHOD(world_get_debug_local_normals, "get_debug_local_normals", BYTES,
           "each cell's local kernel normal as two native floats (x, y), world axes; zero off the critical cells",
           .arg_count = 0),
};

/* ---- PhysPixBody ---- */

static void body_get_position(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_vec2 p;
    if (ret_ok(ret, pp_body_get_position(self->world, self->body, &p), "PhysPixBody.get_position"))
        ret_vec2(ret, p);
}

static void body_get_angle(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    float angle;
    if (ret_ok(ret, pp_body_get_angle(self->world, self->body, &angle), "PhysPixBody.get_angle"))
        ret_float(ret, angle);
}

static void body_set_transform(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_body_set_transform(self->world, self->body, a[0].as.vec2, (float)a[1].as.real),
           "PhysPixBody.set_transform");
}

static void body_get_velocity(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_vec2 v;
    if (ret_ok(ret, pp_body_get_velocity(self->world, self->body, &v, NULL), "PhysPixBody.get_velocity"))
        ret_vec2(ret, v);
}

static void body_get_angular_velocity(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    float w;
    if (ret_ok(ret, pp_body_get_velocity(self->world, self->body, NULL, &w), "PhysPixBody.get_angular_velocity"))
        ret_float(ret, w);
}

static void body_set_velocity(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_body_set_velocity(self->world, self->body, a[0].as.vec2, (float)a[1].as.real),
           "PhysPixBody.set_velocity");
}

static void body_apply_impulse(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_body_apply_impulse(self->world, self->body, a[0].as.vec2, a[1].as.vec2),
           "PhysPixBody.apply_impulse");
}

static void body_get_mass(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    float mass;
    if (ret_ok(ret, pp_body_get_mass(self->world, self->body, &mass, NULL, NULL), "PhysPixBody.get_mass"))
        ret_float(ret, mass);
}

static void body_get_center_of_mass(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_vec2 c;
    if (ret_ok(ret, pp_body_get_mass(self->world, self->body, NULL, &c, NULL), "PhysPixBody.get_center_of_mass"))
        ret_vec2(ret, c);
}

static void body_get_inertia(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    float inertia;
    if (ret_ok(ret, pp_body_get_mass(self->world, self->body, NULL, NULL, &inertia), "PhysPixBody.get_inertia"))
        ret_float(ret, inertia);
}

static void body_is_awake(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    int32_t awake;
    if (ret_ok(ret, pp_body_is_awake(self->world, self->body, &awake), "PhysPixBody.is_awake"))
        ret_bool(ret, awake);
}

static void body_erase_circle(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    int32_t changed;
    if (ret_ok(ret, pp_body_erase_circle(self->world, self->body, a[0].as.vec2, (float)a[1].as.real, &changed),
               "PhysPixBody.erase_circle"))
        ret_int(ret, changed);
}

static void body_paint_circle(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    int32_t weight, changed;
    if (int_in(&a[2], 1, 255, "PhysPixBody.paint_circle: weight", &weight, ret) &&
        ret_ok(ret,
               pp_body_paint_circle(self->world, self->body, a[0].as.vec2, (float)a[1].as.real, (uint8_t)weight,
                                    &changed),
               "PhysPixBody.paint_circle"))
        ret_int(ret, changed);
}

static void body_read_mask(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixBody.read_mask";
    int32_t w, h;
    if (!ret_ok(ret, pp_body_get_size(self->world, self->body, &w, &h), m))
        return;
    const int64_t size = (int64_t)w * h;
    uint8_t *mask = ret_bytes(ret, size);
    if (mask && !ret_ok(ret, pp_body_read_mask(self->world, self->body, mask, size), m))
        free(mask); /* ret now holds the error, not the bytes */
}

static void body_get_size(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    int32_t w, h;
    if (ret_ok(ret, pp_body_get_size(self->world, self->body, &w, &h), "PhysPixBody.get_size"))
        ret_vec2(ret, (pp_vec2){(float)w, (float)h});
}

static void body_get_world(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_object(ret, self->world_object);
}

static void body_get_pivot(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_vec2 p;
    if (ret_ok(ret, pp_body_get_pivot(self->world, self->body, &p), "PhysPixBody.get_pivot"))
        ret_vec2(ret, p);
}

static void body_get_type(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    static const char *names[] = {"dynamic", "static", "kinematic"}; /* in pp_body_type order */
    pp_body_type t;
    if (ret_ok(ret, pp_body_get_type(self->world, self->body, &t), "PhysPixBody.get_type"))
        ret_string(ret, (uint32_t)t < 3 ? names[t] : "unknown");
}

static void body_get_rgba(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixBody.get_rgba";
    int32_t w, h;
    if (!ret_ok(ret, pp_body_get_size(self->world, self->body, &w, &h), m))
        return;
    const int64_t size = (int64_t)w * h * 4;
    uint8_t *rgba = ret_bytes(ret, size);
    if (rgba && !ret_ok(ret, pp_body_read_rgba(self->world, self->body, rgba, size), m))
        free(rgba); /* ret now holds the error, not the bytes */
}

static void body_get_user_data(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    uint64_t u;
    if (ret_ok(ret, pp_body_get_user_data(self->world, self->body, &u), "PhysPixBody.get_user_data"))
        ret_int(ret, (int64_t)u);
}

/* The runtime setters: one C call each, their errors named after the plugin method. */
#define BODY_SET_FLOAT(name_, call_)                                                                  \
    static void body_##name_(plugin_object *self, const pp_variant *a, pp_variant *ret)              \
    {                                                                                                 \
        ret_ok(ret, call_(self->world, self->body, (float)a[0].as.real), "PhysPixBody." #name_);      \
    }
BODY_SET_FLOAT(set_friction, pp_body_set_friction)
BODY_SET_FLOAT(set_restitution, pp_body_set_restitution)
BODY_SET_FLOAT(set_density, pp_body_set_density)
BODY_SET_FLOAT(set_gravity_scale, pp_body_set_gravity_scale)
BODY_SET_FLOAT(apply_torque, pp_body_apply_torque)

static void body_set_type(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_body_type t;
    if (body_type_named(&a[0], "PhysPixBody.set_type", &t, ret))
        ret_ok(ret, pp_body_set_type(self->world, self->body, t), "PhysPixBody.set_type");
}

static void body_set_fixed_rotation(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_body_set_fixed_rotation(self->world, self->body, a[0].as.boolean != 0), "PhysPixBody.set_fixed_rotation");
}

static void body_set_awake(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_body_set_awake(self->world, self->body, a[0].as.boolean != 0), "PhysPixBody.set_awake");
}

static void body_set_damping(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_body_set_damping(self->world, self->body, (float)a[0].as.real, (float)a[1].as.real),
           "PhysPixBody.set_damping");
}

static void body_apply_force(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_body_apply_force(self->world, self->body, a[0].as.vec2, a[1].as.vec2), "PhysPixBody.apply_force");
}

static const method_def body_methods[] = {
    METHOD(body_get_position, "get_position", VEC2, "world position of the pivot, px", .arg_count = 0),
    METHOD(body_get_angle, "get_angle", FLOAT, "rotation, radians", .arg_count = 0),
    METHOD(body_set_transform, "set_transform", NIL, "teleport: pivot to position (px), rotation to angle (radians)",
           ARGS(ARG("position", VEC2), ARG("angle", FLOAT))),
    METHOD(body_get_velocity, "get_velocity", VEC2, "velocity of the centre of mass, px/s", .arg_count = 0),
    METHOD(body_get_angular_velocity, "get_angular_velocity", FLOAT, "angular velocity, rad/s", .arg_count = 0),
    METHOD(body_set_velocity, "set_velocity", NIL, "set linear (px/s) and angular (rad/s) velocity",
           ARGS(ARG("linear", VEC2), ARG("angular", FLOAT))),
    METHOD(body_apply_impulse, "apply_impulse", NIL, "apply an impulse (mass*px/s) at a world point (px)",
           ARGS(ARG("impulse", VEC2), ARG("point", VEC2))),
    METHOD(body_get_mass, "get_mass", FLOAT, "mass, mass units (density x weighted solid pixels)", .arg_count = 0),
    METHOD(body_get_center_of_mass, "get_center_of_mass", VEC2, "centre of mass in bitmap coordinates, px",
           .arg_count = 0),
    METHOD(body_get_inertia, "get_inertia", FLOAT, "moment of inertia about the centre of mass, mass*px^2",
           .arg_count = 0),
    METHOD(body_is_awake, "is_awake", BOOL, "whether the body is awake", .arg_count = 0),
    METHOD(body_erase_circle, "erase_circle", INT,
           "erase pixels within radius (px) of a world point (px); returns pixels erased",
           ARGS(ARG("center", VEC2), ARG("radius", FLOAT))),
    METHOD(body_paint_circle, "paint_circle", INT,
           "make pixels within radius (px) of a world point (px) solid with weight 1..255; returns pixels changed",
           ARGS(ARG("center", VEC2), ARG("radius", FLOAT), ARG("weight", INT))),
    METHOD(body_read_mask, "read_mask", BYTES, "the collision mask, width*height bytes (1 solid), rows top to bottom",
           .arg_count = 0),
    METHOD(body_get_size, "get_size", VEC2, "bitmap width and height, px", .arg_count = 0),
    METHOD(body_get_world, "get_world", OBJECT, "the PhysPixWorld the body lives in", .arg_count = 0,
           .return_class = "PhysPixWorld"),
    METHOD(body_get_pivot, "get_pivot", VEC2, "the pivot in bitmap coordinates, px", .arg_count = 0),
    METHOD(body_get_type, "get_type", STRING, "\"dynamic\", \"static\" or \"kinematic\"", .arg_count = 0),
    METHOD(body_get_rgba, "get_rgba", BYTES,
           "the body's look, width*height*4 bytes RGBA8: its sprite where solid, transparent elsewhere",
           .arg_count = 0),
    METHOD(body_get_user_data, "get_user_data", INT, "the host's value from the body's def (a scene's user_data)",
           .arg_count = 0),
    METHOD(body_set_type, "set_type", NIL,
           "\"dynamic\", \"static\" or \"kinematic\": the pose stays, a moving body keeps its velocity",
           ARGS(ARG("type", STRING))),
    METHOD(body_set_fixed_rotation, "set_fixed_rotation", NIL, "hold the rotation (true) or free it",
           ARGS(ARG("fixed", BOOL))),
    METHOD(body_set_friction, "set_friction", NIL, "Coulomb friction coefficient, >= 0", ARGS(ARG("friction", FLOAT))),
    METHOD(body_set_restitution, "set_restitution", NIL, "restitution, 0..1", ARGS(ARG("restitution", FLOAT))),
    METHOD(body_set_density, "set_density", NIL, "mass per solid pixel, > 0: mass and inertia follow",
           ARGS(ARG("density", FLOAT))),
    METHOD(body_set_gravity_scale, "set_gravity_scale", NIL, "scale of the world's gravity on the body (dynamic)",
           ARGS(ARG("scale", FLOAT))),
    METHOD(body_set_damping, "set_damping", NIL, "velocity decay, 1/s, linear and angular",
           ARGS(ARG("linear", FLOAT), ARG("angular", FLOAT))),
    METHOD(body_set_awake, "set_awake", NIL, "wake the body (true) or put it to sleep now (false)",
           ARGS(ARG("awake", BOOL))),
    METHOD(body_apply_force, "apply_force", NIL, "a force (mass*px/s^2) at a world point (px) through the next step",
           ARGS(ARG("force", VEC2), ARG("point", VEC2))),
    METHOD(body_apply_torque, "apply_torque", NIL, "a torque (mass*px^2/s^2) through the next step",
           ARGS(ARG("torque", FLOAT))),
};

const class_def plugin_classes[CLASS_COUNT] = {
    [CLASS_WORLD] = {{.name = "PhysPixWorld", .base = "RefCounted", .doc = "a PhysPix world: default settings, or a scene file's (load_scene)",
                      .instantiable = 1, .method_count = (int32_t)(sizeof world_methods / sizeof world_methods[0])},
                     OBJECT_WORLD, world_methods},
    [CLASS_BODY] = {{.name = "PhysPixBody", .base = "RefCounted",
                     .doc = "a body of a PhysPixWorld, made by its add_body* methods",
                     .method_count = (int32_t)(sizeof body_methods / sizeof body_methods[0])},
                    OBJECT_BODY, body_methods},
};
