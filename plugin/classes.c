/* The plugin's classes, PhysPixWorld and PhysPixBody. Their method tables (name, doc with units, typed arguments,
 * result) and the wrappers of the regular methods are generated into classes_gen.h from plugin/api/physpix_api.json;
 * here are the methods written by hand. Arguments arrive checked against the table by plugin.c; what is left here
 * is ranges, sizes and names. */
#include "plugin.h"

#include <float.h>
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
    char width[96], height[96]; /* each checked in 64 bits before anything multiplies it */
    snprintf(width, sizeof width, "%s: width", m);
    snprintf(height, sizeof height, "%s: height", m);
    if (!int_in(w, 1, PP_MAX_BITMAP_SIDE, width, &d->width, ret) ||
        !int_in(h, 1, PP_MAX_BITMAP_SIDE, height, &d->height, ret))
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
    static const char *const names[] = {"revolute", "prismatic", "distance", "weld", "mouse", "wheel", "motor"}; /* from REVOLUTE = 1 */
    const char *m = "PhysPixWorld.add_joint";
    const world_cache *c = self->cache;
    const int type = name_index(&a[0], names, 7, "PhysPixWorld.add_joint: type", ret);
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

/* ---- raycasts, casts, queries and explosions ---- */

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

static void world_explode(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.explode";
    pp_explosion_def d = pp_explosion_def_default();
    d.position = a[0].as.vec2;
    d.radius = (float)a[1].as.real, d.falloff = (float)a[2].as.real;
    d.impulse_per_length = (float)a[3].as.real, d.erase_radius = (float)a[4].as.real;
    int32_t erased = 0;
    if (mask_bits(&a[5], m, &d.mask_bits, ret) && mask_bits(&a[6], m, &d.erase_mask_bits, ret) &&
        ret_ok(ret, pp_world_explode(self->world, &d, &erased), m))
        ret_int(ret, erased);
}

/* ---- the character mover ---- */

/* What move_character moves from now on; the library checks the fields at each move. */
static void world_set_character_options(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_character_def d = pp_character_def_default();
    d.radius = (float)a[0].as.real, d.half_height = (float)a[1].as.real, d.step_height = (float)a[2].as.real;
    d.snap_distance = (float)a[3].as.real, d.max_slope = (float)a[4].as.real;
    if (mask_bits(&a[5], "PhysPixWorld.set_character_options", &d.mask_bits, ret)) {
        self->cache->character = d;
        self->cache->has_character = 1;
    }
}

/* The end position; the rest of the move stays in the cache for get_character_*. A failed move leaves it as it was. */
static void world_move_character(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    world_cache *c = self->cache;
    const pp_character_def d = c->has_character ? c->character : pp_character_def_default();
    pp_character_move m;
    if (ret_ok(ret, pp_world_move_character(self->world, &d, a[0].as.vec2, a[1].as.vec2, (float)a[2].as.real, &m),
               "PhysPixWorld.move_character")) {
        c->moved = m;
        ret_vec2(ret, m.position);
    }
}

static void world_get_character_velocity(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_vec2(ret, self->cache->moved.velocity);
}

static void world_is_character_grounded(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_bool(ret, self->cache->moved.grounded != 0);
}

static void world_get_character_ground_normal(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_vec2(ret, self->cache->moved.ground_normal);
}

static void world_get_character_ground_body(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_body(self, self->cache->moved.ground_body, ret);
}

static void world_get_character_ground_velocity(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_vec2(ret, self->cache->moved.ground_velocity);
}

static void world_get_character_surfaces(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_int(ret, self->cache->moved.surfaces);
}

/* Every hit of the segment into the cache, nearest first; get_ray_* read the one select_ray_hit picks. */
static void world_raycast_all(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.raycast_all";
    world_cache *c = self->cache;
    uint32_t mask;
    int32_t n = 0;
    c->ray_hit_count = 0;
    c->ray = (pp_raycast_hit){0};
    if (mask_bits(&a[2], m, &mask, ret) &&
        ret_ok(ret, pp_world_raycast_all(self->world, a[0].as.vec2, a[1].as.vec2, mask, NULL, 0, &n), m) &&
        reserve((void **)&c->ray_hits, &c->ray_hit_capacity, n, sizeof *c->ray_hits, ret) &&
        ret_ok(ret, pp_world_raycast_all(self->world, a[0].as.vec2, a[1].as.vec2, mask, c->ray_hits, n, &n), m)) {
        c->ray_hit_count = n;
        ret_int(ret, n);
    }
}

static void world_select_ray_hit(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    world_cache *c = self->cache;
    if (index_in(&a[0], c->ray_hit_count, "PhysPixWorld.select_ray_hit", "hits raycast_all found", ret))
        c->ray = c->ray_hits[a[0].as.integer];
}

static void world_cast_body(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.cast_body";
    world_cache *c = self->cache;
    uint32_t mask;
    int32_t hit = 0;
    c->ray = (pp_raycast_hit){0};
    if (mask_bits(&a[2], m, &mask, ret) &&
        ret_ok(ret, pp_world_cast_body(self->world, object_get(a[0].as.object)->body, a[1].as.vec2, mask, &c->ray,
                                       &hit), m))
        ret_bool(ret, hit);
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
    c->moved = (pp_character_move){0}; /* its ground body was the old world's */
}

/* Replace this object's world by one made from settings (JSON: "preset", then pp_world_def fields by name). */
static void world_create(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.create";
    pp_world_def def;
    pp_world made;
    char why[256];
    const pp_status st = settings_read(a[0].as.string.data, &def, why, sizeof why);
    if (st != PP_OK)
        ret_error(ret, st, "%s: %s", m, why);
    else if (ret_ok(ret, pp_world_create(&def, &made), m))
        world_replace(self, made); /* on failure the old world stays as it was */
}

static void world_get_settings(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_world_def def;
    if (ret_ok(ret, pp_world_get_def(self->world, &def), "PhysPixWorld.get_settings"))
        settings_ret(&def, ret);
}

static void world_load_scene(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_world loaded;
    if (ret_ok(ret, pp_world_load_scene(a[0].as.string.data, &loaded), "PhysPixWorld.load_scene"))
        world_replace(self, loaded); /* on failure the old world stays as it was */
}

static void world_load_snapshot(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_world loaded;
    if (ret_ok(ret, pp_world_load_snapshot(a[0].as.string.data, &loaded), "PhysPixWorld.load_snapshot"))
        world_replace(self, loaded);
}

static void world_save_state(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.save_state";
    int64_t size = 0;
    const pp_status st = pp_world_save_state(self->world, NULL, 0, &size);
    if (st != PP_ERR_LIMIT && !ret_ok(ret, st, m))
        return;
    uint8_t *out = ret_bytes(ret, size);
    if (out)
        ret_ok(ret, pp_world_save_state(self->world, out, size, &size), m);
}

static void world_restore_state(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    ret_ok(ret, pp_world_restore_state(self->world, a[0].as.bytes.data, a[0].as.bytes.length), "PhysPixWorld.restore_state");
}

static void world_load_state(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_world loaded;
    if (ret_ok(ret, pp_world_load_state(a[0].as.bytes.data, a[0].as.bytes.length, &loaded), "PhysPixWorld.load_state"))
        world_replace(self, loaded); /* on failure the old world stays as it was */
}

static void world_get_hash(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    uint64_t h = 0;
    if (ret_ok(ret, pp_world_get_hash(self->world, &h), "PhysPixWorld.get_hash"))
        ret_int(ret, (int64_t)h);
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

/* Six 32-bit words a segment: a.x, a.y, b.x, b.y (floats), rgba, kind. */
enum { DEBUG_WORDS = 6 };

static void world_debug_draw(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixWorld.debug_draw";
    int32_t n = 0;
    const pp_vec2 lo = {-FLT_MAX, -FLT_MAX}, hi = {FLT_MAX, FLT_MAX};
    if (a[0].as.integer < 0 || a[0].as.integer > UINT32_MAX) {
        ret_error(ret, PP_ERR_INVALID_ARGUMENT, "%s: flags must be in 0..%u, got %lld", m, UINT32_MAX,
                  (long long)a[0].as.integer);
        return;
    }
    const uint32_t flags = (uint32_t)a[0].as.integer;
    if (!ret_ok(ret, pp_world_debug_draw(self->world, flags, lo, hi, NULL, 0, &n), m))
        return;
    pp_debug_segment *segs = n > 0 ? malloc((size_t)n * sizeof *segs) : NULL;
    if (n > 0 && !segs) {
        ret_error(ret, PP_ERR_OUT_OF_MEMORY, "%s: out of memory for %d segments", m, (int)n);
        return;
    }
    const int32_t capacity = n;
    if (!ret_ok(ret, pp_world_debug_draw(self->world, flags, lo, hi, segs, capacity, &n), m)) {
        free(segs);
        return;
    }
    n = n < capacity ? n : capacity;
    uint8_t *out = ret_bytes(ret, (int64_t)n * DEBUG_WORDS * 4);
    for (int32_t i = 0; out && i < n; i++) {
        const pp_debug_segment *s = &segs[i];
        const float f[4] = {s->a.x, s->a.y, s->b.x, s->b.y};
        const uint32_t u[2] = {s->rgba, (uint32_t)s->kind};
        memcpy(out + (size_t)i * DEBUG_WORDS * 4, f, sizeof f);
        memcpy(out + (size_t)i * DEBUG_WORDS * 4 + sizeof f, u, sizeof u);
    }
    free(segs);
}


/* ---- PhysPixBody ---- */

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

/* A whole bitmap plane of width*height bytes per pixel (pp_body_read_mask, _read_weights, _read_rgba) into ret. */
static void body_read_plane(plugin_object *self, pp_variant *ret, const char *m, int bytes_per_pixel,
                            pp_status (*read)(pp_world, pp_body, uint8_t *, int64_t))
{
    int32_t w, h;
    if (!ret_ok(ret, pp_body_get_size(self->world, self->body, &w, &h), m))
        return;
    const int64_t size = (int64_t)w * h * bytes_per_pixel;
    uint8_t *plane = ret_bytes(ret, size);
    if (plane && !ret_ok(ret, read(self->world, self->body, plane, size), m))
        free(plane); /* ret now holds the error, not the bytes */
}

static void body_read_mask(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    body_read_plane(self, ret, "PhysPixBody.read_mask", 1, pp_body_read_mask);
}

static void body_read_weights(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    body_read_plane(self, ret, "PhysPixBody.read_weights", 1, pp_body_read_weights);
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

static void body_get_type(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    static const char *names[] = {"dynamic", "static", "kinematic"}; /* in pp_body_type order */
    pp_body_type t;
    if (ret_ok(ret, pp_body_get_type(self->world, self->body, &t), "PhysPixBody.get_type"))
        ret_string(ret, (uint32_t)t < 3 ? names[t] : "unknown");
}

static void body_get_rgba(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    body_read_plane(self, ret, "PhysPixBody.get_rgba", 4, pp_body_read_rgba);
}

static void body_set_type(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    pp_body_type t;
    if (body_type_named(&a[0], "PhysPixBody.set_type", &t, ret))
        ret_ok(ret, pp_body_set_type(self->world, self->body, t), "PhysPixBody.set_type");
}


static void body_set_filter(plugin_object *self, const pp_variant *a, pp_variant *ret)
{
    const char *m = "PhysPixBody.set_filter";
    uint32_t category, mask;
    if (mask_bits(&a[0], m, &category, ret) && mask_bits(&a[1], m, &mask, ret))
        ret_ok(ret, pp_body_set_filter(self->world, self->body, category, mask), m);
}

/* world_methods and body_methods, and the wrappers of the regular methods. */
#include "classes_gen.h"

const class_def plugin_classes[CLASS_COUNT] = {
    [CLASS_WORLD] = {{.name = "PhysPixWorld", .base = "RefCounted", .doc = "a PhysPix world: default settings, or a scene file's (load_scene)",
                      .instantiable = 1, .method_count = (int32_t)(sizeof world_methods / sizeof world_methods[0])},
                     OBJECT_WORLD, world_methods},
    [CLASS_BODY] = {{.name = "PhysPixBody", .base = "RefCounted",
                     .doc = "a body of a PhysPixWorld, made by its add_body* methods",
                     .method_count = (int32_t)(sizeof body_methods / sizeof body_methods[0])},
                    OBJECT_BODY, body_methods},
};
