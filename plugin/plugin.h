/* Private to the engine plugin: the object table shared by the dispatcher (plugin.c) and the
 * class methods (classes.c), and the variant helpers both use. */
#ifndef PP_PLUGIN_PRIVATE_H
#define PP_PLUGIN_PRIVATE_H

#include "physpix_plugin.h"

#include <stddef.h>

typedef enum object_kind { OBJECT_FREE = 0, OBJECT_WORLD, OBJECT_BODY } object_kind;

/* What a world object keeps between calls: the lists its indexed getters read. */
typedef struct world_cache {
    pp_contact *contacts; /* of the last step */
    int32_t contact_count, contact_capacity;
    pp_event *events; /* read by the last get_event_count */
    int32_t event_count, event_capacity;
    pp_body *bodies; /* read by the last get_body_count */
    int32_t body_count, body_capacity;
    pp_body_state *states; /* get_body_states' scratch */
    int32_t state_capacity;
    uint64_t *body_objects; /* body slot → the object wrapping it, so a body keeps one object id */
    int32_t body_object_capacity;
    pp_timed_edit *edits; /* read by the last get_scheduled_edit_count */
    int32_t edit_count, edit_capacity;
    pp_collision_view debug_view; /* of the last debug_collision */
    pp_vec2 *debug_normals;       /* its local normals, one per cell */
    int64_t debug_capacity;
    pp_raycast_hit ray; /* of the last raycast or cast_body, or the hit select_ray_hit chose; zero for a miss */
    pp_raycast_hit *ray_hits; /* of the last raycast_all, nearest first */
    int32_t ray_hit_count, ray_hit_capacity;
    pp_body *found;     /* bodies of the last query_* */
    int32_t found_count, found_capacity;
    uint32_t is_sensor, one_way; /* set_body_options: what add_body* give the bodies they make */
    pp_vec2 one_way_direction;
    pp_joint_def joint_options; /* set_joint_options: what add_joint gives its joints, once has_joint_options */
    uint32_t has_joint_options;
    pp_character_def character; /* set_character_options: the capsule move_character moves, once has_character */
    uint32_t has_character;
    pp_character_move moved; /* of the last move_character; zero before one */
} world_cache;

/* One slot of the table; ids are (kind << 61) | (generation << 32) | (slot + 1) (handle.h's slot_id_make, the
 * kind a world's or a body's), so a stale id, or a joint int in its place, is detected. */
typedef struct plugin_object {
    object_kind kind;      /* OBJECT_FREE in a free slot */
    pp_world world;        /* both kinds */
    pp_body body;          /* BODY */
    uint64_t world_object; /* the world object it belongs to (a world: itself) */
    world_cache *cache;    /* WORLD */
} plugin_object;

/* A method's description (public) and implementation; args arrive checked and converted. */
typedef void (*method_fn)(plugin_object *self, const pp_variant *args, pp_variant *ret);
typedef struct method_def {
    pp_plugin_method desc;
    method_fn fn;
} method_def;

typedef struct class_def {
    pp_plugin_class desc; /* desc.methods is filled from `methods` at start-up */
    object_kind kind;
    const method_def *methods;
} class_def;

enum { CLASS_WORLD = 0, CLASS_BODY = 1, CLASS_COUNT = 2 };
extern const class_def plugin_classes[CLASS_COUNT];

/* The object table (plugin.c). */
plugin_object *object_get(uint64_t id);
uint64_t object_new(object_kind kind, plugin_object **out);
void object_free(uint64_t id);
uint64_t object_for_body(uint64_t world_object, pp_body body); /* 0 on out of memory */

/* Results (plugin.c). The error forms copy their message; a failed library call adds pp_last_error(). */
void ret_int(pp_variant *ret, int64_t v);
void ret_float(pp_variant *ret, double v);
void ret_bool(pp_variant *ret, int v);
void ret_vec2(pp_variant *ret, pp_vec2 v);
void ret_object(pp_variant *ret, uint64_t id);
void ret_string(pp_variant *ret, const char *s);
uint8_t *ret_bytes(pp_variant *ret, int64_t length); /* NULL (and ret an ERROR) on out of memory */
void ret_error(pp_variant *ret, pp_status status, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* PP_OK: leaves ret alone and returns 1; otherwise ret becomes ERROR "<method>: <pp_last_error()>", returns 0. */
int ret_ok(pp_variant *ret, pp_status status, const char *method);

/* settings.c: a world's settings as JSON text (a scene file's "world" object: "preset", then pp_world_def fields).
 * settings_read: PP_OK with *out set, or PP_ERR_INVALID_ARGUMENT and why ("settings.<key>: ..."). settings_ret:
 * the def as such a JSON object, a STRING result (or an ERROR on out of memory). */
pp_status settings_read(const char *json, pp_world_def *out, char *why, size_t why_size);
void settings_ret(const pp_world_def *def, pp_variant *ret);

#endif
