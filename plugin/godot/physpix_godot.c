/* PhysPixWorld: a NativeScript class (base Reference) that gives GDScript one pp_world.
 * Owns the method table, the checking of every argument against it, the calls into PhysPix,
 * and the library's three entry points. Bodies and joints are ints: the pp_body or pp_joint id's 64 bits. An id
 * names its world, so an int from before load_scene or load_snapshot replaced the object's world is refused by
 * PhysPix itself (PP_ERR_INVALID_HANDLE). */
#include <float.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "adapter.h"

static const char *const EVENT_TYPE_NAMES[] = {
    [PP_EVENT_BODY_SPLIT] = "split",
    [PP_EVENT_BODY_DESTROYED] = "destroyed",
    [PP_EVENT_CONTACT_BEGIN] = "contact_begin",
    [PP_EVENT_CONTACT_END] = "contact_end",
    [PP_EVENT_SENSOR_BEGIN] = "sensor_begin",
    [PP_EVENT_SENSOR_END] = "sensor_end",
    [PP_EVENT_JOINT_BROKEN] = "joint_broken",
};

static const char *const BODY_TYPE_NAMES[] = {
    [PP_BODY_DYNAMIC] = "dynamic",
    [PP_BODY_STATIC] = "static",
    [PP_BODY_KINEMATIC] = "kinematic",
};

/* ProjectSettings.globalize_path, looked up once at load; the singleton is asked for at each call. */
static godot_method_bind *globalize_path_mb;

/* ---- errors ---------------------------------------------------------------------------- */

static void record_error(world_inst *self, const char *method, const char *msg, const char *file, int line)
{
    char function[64];
    snprintf(function, sizeof function, CLASS_NAME ".%s", method);
    if (self)
        snprintf(self->error, sizeof self->error, "%s: %s", function, msg);
    gdn_print_error(function, msg, file, line);
}

/* Records and prints why the call failed; returns false so checks read `return cond || fail(...)`. */
bool fail_at(const char *file, int line, call *c, const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    record_error(c->self, c->def->name, msg, file, line);
    return false;
}

/* True on PP_OK; otherwise records the status and PhysPix's own message. */
bool ok_at(const char *file, int line, call *c, pp_status s)
{
    return s == PP_OK || fail_at(file, line, c, "%s: %s", pp_status_name(s), pp_last_error());
}

/* ---- arguments ------------------------------------------------------------------------- */

static bool wrong_type(call *c, int i, const char *expected)
{
    return fail(c, "argument %d is %s, expected %s (usage: %s)", i + 1, gdn_type_name(c->a[i].var), expected,
                c->def->usage);
}

/* "/x", "\\server\x" or "C:/x". */
static bool is_absolute(const char *p)
{
    const bool drive = ((p[0] >= 'A' && p[0] <= 'Z') || (p[0] >= 'a' && p[0] <= 'z')) && p[1] == ':';
    return p[0] == '/' || p[0] == '\\' || (drive && (p[2] == '/' || p[2] == '\\'));
}

size_t globalize_path(const char *given, char *out, size_t size)
{
    char singleton[] = "ProjectSettings";
    godot_object *settings = gdn->godot_global_get_singleton(singleton);
    if (!settings)
        return 0;
    godot_variant in = gdn_string(given), result;
    const godot_variant *args[] = {&in};
    const bool called = gdn_call(globalize_path_mb, settings, args, 1, &result);
    const size_t m = called && gdn->godot_variant_get_type(&result) == GDN_STRING
                         ? gdn_string_to_utf8(&result, out, size)
                         : 0;
    gdn->godot_variant_destroy(&result);
    gdn->godot_variant_destroy(&in);
    return m;
}

/* A path argument into c->path: as given, or, for res:// and user://, through
 * ProjectSettings.globalize_path. That gives an absolute path where the project is a folder (the
 * editor, godot --path); in an exported game res:// is inside the .pck, which PhysPix cannot read,
 * and becomes a relative path, so a result that is not absolute is refused. */
static bool read_path(call *c, int i)
{
    const size_t n = gdn_string_to_utf8(c->a[i].var, c->path, PATH_SIZE);
    if (n == 0)
        return fail(c, "argument %d is an empty path (usage: %s)", i + 1, c->def->usage);
    if (n >= PATH_SIZE)
        return fail(c, "argument %d is a path of %zu bytes, at most %d", i + 1, n, PATH_SIZE - 1);
    c->a[i].path = c->path;
    if (strncmp(c->path, "res://", 6) != 0 && strncmp(c->path, "user://", 7) != 0)
        return true;
    char given[PATH_SIZE];
    memcpy(given, c->path, n + 1);
    const size_t m = globalize_path(given, c->path, PATH_SIZE);
    if (m == 0)
        return fail(c, "ProjectSettings.globalize_path(\"%s\") failed", given);
    if (m >= PATH_SIZE)
        return fail(c, "'%s' globalizes to a path of %zu bytes, at most %d", given, m, PATH_SIZE - 1);
    if (!is_absolute(c->path))
        return fail(c,
                    "'%s' globalizes to '%s', not a folder on disk (an exported game's res:// is inside its .pck, "
                    "which PhysPix cannot read: use user:// or a filesystem path)",
                    given, c->path);
    return true;
}

static bool read_arg(call *c, int i, char letter)
{
    arg *a = &c->a[i];
    const int32_t t = gdn->godot_variant_get_type(a->var);
    switch (letter) {
    case 'i':
    case 'b':
        if (t != GDN_INT)
            return wrong_type(c, i, letter == 'b' ? "a body (int)" : "int");
        a->i = gdn->godot_variant_as_int(a->var);
        a->body.id = (uint64_t)a->i;
        return true;
    case 'j':
        if (t != GDN_INT)
            return wrong_type(c, i, "a joint (int)");
        a->joint.id = (uint64_t)gdn->godot_variant_as_int(a->var);
        return true;
    case 'm':
        if (t != GDN_INT)
            return wrong_type(c, i, "int (mask bits)");
        a->i = gdn->godot_variant_as_int(a->var);
        return (a->i >= 0 && a->i <= UINT32_MAX) ||
               fail(c, "argument %d, mask bits %lld, is outside 0..0xffffffff", i + 1, (long long)a->i);
    case 'o':
        return t == GDN_DICTIONARY || wrong_type(c, i, "Dictionary (body options)");
    case 'd':
        return t == GDN_DICTIONARY || wrong_type(c, i, "Dictionary (world settings)");
    case 'J':
        return t == GDN_DICTIONARY || wrong_type(c, i, "Dictionary (joint def)");
    case 'C':
        return t == GDN_DICTIONARY || wrong_type(c, i, "Dictionary (character def)");
    case 'B':
        if (t != GDN_BOOL)
            return wrong_type(c, i, "bool");
        a->i = gdn->godot_variant_as_bool(a->var);
        return true;
    case 'f':
        if (t != GDN_REAL && t != GDN_INT)
            return wrong_type(c, i, "float");
        a->f = (float)gdn->godot_variant_as_real(a->var);
        return true;
    case 'v':
        if (t != GDN_VECTOR2)
            return wrong_type(c, i, "Vector2");
        gdn_vector2_read(a->var, &a->v.x, &a->v.y);
        return true;
    case 't': {
        if (t != GDN_STRING)
            return wrong_type(c, i, "String");
        char name[16];
        gdn_string_to_utf8(a->var, name, sizeof name);
        for (size_t k = 0; k < sizeof BODY_TYPE_NAMES / sizeof BODY_TYPE_NAMES[0]; k++)
            if (BODY_TYPE_NAMES[k] && strcmp(name, BODY_TYPE_NAMES[k]) == 0) {
                a->type = (pp_body_type)k;
                return true;
            }
        return fail(c, "argument %d is \"%s\", expected \"dynamic\", \"static\" or \"kinematic\"", i + 1, name);
    }
    case 'M':
        return t == GDN_POOL_BYTE_ARRAY || wrong_type(c, i, "PoolByteArray");
    case 'p':
        return t == GDN_STRING ? read_path(c, i) : wrong_type(c, i, "String (a path)");
    case 'I':
        /* Null is most often a load() that failed: point at its path rather than name a type. */
        if (t == GDN_NIL)
            return fail(c, "argument %d is null, expected Image or Texture (did a load() fail? check its path)",
                        i + 1);
        if (t != GDN_OBJECT)
            return wrong_type(c, i, "Image or Texture");
        a->object = gdn->godot_variant_as_object(a->var);
        /* A freed object may still be a pointer, so ask the ObjectDB; any other class would crash get_data. */
        if (!a->object || !gdn11->godot_is_instance_valid(a->object))
            return fail(c, "argument %d is a freed or null object, expected Image or Texture", i + 1);
        return pixels_is_image_or_texture(a->object) || wrong_type(c, i, "Image or Texture");
    default:
        return fail(c, "internal error: bad spec letter '%c'", letter);
    }
}

static bool read_args(call *c, godot_variant **args)
{
    const char *spec = c->def->spec;
    const int required = (int)strcspn(spec, "|");
    const int total = (int)strlen(spec) - (spec[required] == '|');
    if (total > MAX_ARGS)
        return fail(c, "internal error: spec \"%s\" has more than %d arguments", spec, MAX_ARGS);
    if (c->argc < required || c->argc > total)
        return fail(c, "got %d argument%s (usage: %s)", c->argc, c->argc == 1 ? "" : "s", c->def->usage);
    for (int i = 0, k = 0; i < c->argc; k++) {
        if (spec[k] == '|')
            continue;
        c->a[i].var = args[i];
        if (!read_arg(c, i, spec[k]))
            return false;
        i++;
    }
    return true;
}

/* ---- bodies ---------------------------------------------------------------------------- */

godot_variant body_int(pp_body b)
{
    return gdn_int((int64_t)b.id);
}

godot_variant make_body(call *c, int first, pp_body_def *def)
{
    def->position = c->a[first].v;
    def->type = c->argc > first + 1 ? c->a[first + 1].type : PP_BODY_DYNAMIC;
    body_planes planes = {NULL, NULL};
    pp_body b;
    const bool made = (c->argc <= first + 2 || fields_body_def(c, c->a[first + 2].var, def, &planes)) &&
                      ok(c, pp_body_create(c->self->world, def, &b));
    free(planes.mask);
    free(planes.weights);
    return made ? body_int(b) : gdn_nil();
}

bool bitmap_size_ok(call *c, int64_t w, int64_t h)
{
    return (w >= 1 && h >= 1 && w <= PP_MAX_BITMAP_SIDE && h <= PP_MAX_BITMAP_SIDE) ||
           fail(c, "a bitmap of %lld × %lld pixels; each side must be 1..%d", (long long)w, (long long)h,
                PP_MAX_BITMAP_SIDE);
}

static godot_variant add_body_mask(call *c)
{
    if (!bitmap_size_ok(c, c->a[1].i, c->a[2].i))
        return gdn_nil();
    pp_body_def def = pp_body_def_default();
    def.width = (int32_t)c->a[1].i;
    def.height = (int32_t)c->a[2].i;
    godot_pool_byte_array pool = gdn->godot_variant_as_pool_byte_array(c->a[0].var);
    const int64_t have = gdn->godot_pool_byte_array_size(&pool), need = (int64_t)def.width * def.height;
    godot_variant r = gdn_nil();
    if (have != need) {
        fail(c, "the mask has %lld bytes, expected %lld (%d × %d)", (long long)have, (long long)need, (int)def.width,
             (int)def.height);
    } else {
        godot_pool_byte_array_read_access *rd = gdn->godot_pool_byte_array_read(&pool);
        def.mask = gdn->godot_pool_byte_array_read_access_ptr(rd);
        r = make_body(c, 3, &def);
        gdn->godot_pool_byte_array_read_access_destroy(rd);
    }
    gdn->godot_pool_byte_array_destroy(&pool);
    return r;
}

/* ---- stepping and reading state -------------------------------------------------------- */

/* The pose as a Transform2D: it maps (bitmap point − pivot) to the world. */
static godot_variant get_transform(call *c)
{
    pp_vec2 p;
    float a;
    if (!ok(c, pp_body_get_position(c->self->world, c->a[0].body, &p)) ||
        !ok(c, pp_body_get_angle(c->self->world, c->a[0].body, &a)))
        return gdn_nil();
    return gdn_transform2d(a, p.x, p.y);
}

/* ---- runtime properties and forces ------------------------------------------------------- */

/* A call that returns nothing: nil either way, the error (if any) recorded. */
static godot_variant done(call *c, pp_status s)
{
    ok(c, s);
    return gdn_nil();
}

static godot_variant set_filter(call *c)
{
    return done(c, pp_body_set_filter(c->self->world, c->a[0].body, (uint32_t)c->a[1].i, (uint32_t)c->a[2].i));
}

static godot_variant get_type(call *c)
{
    pp_body_type t;
    return ok(c, pp_body_get_type(c->self->world, c->a[0].body, &t)) ? gdn_string(BODY_TYPE_NAMES[t]) : gdn_nil();
}

/* Bitmap size, px, as a Vector2 (a Sprite's texture size). */
static godot_variant get_size(call *c)
{
    int32_t w, h;
    return ok(c, pp_body_get_size(c->self->world, c->a[0].body, &w, &h)) ? gdn_vector2((float)w, (float)h)
                                                                          : gdn_nil();
}

/* ---- joints ------------------------------------------------------------------------------ */

static godot_variant create_joint(call *c)
{
    pp_joint_def def;
    pp_joint j;
    return fields_joint_def(c, c->a[0].var, &def) && ok(c, pp_joint_create(c->self->world, &def, &j))
               ? gdn_int((int64_t)j.id)
               : gdn_nil();
}

/* {force: Vector2 (mass·px/s²), torque (mass·px²/s²)} on body_b in the last substep. */
static godot_variant get_joint_reaction(call *c)
{
    pp_vec2 f;
    float torque;
    if (!ok(c, pp_joint_get_reaction(c->self->world, c->a[0].joint, &f, &torque)))
        return gdn_nil();
    godot_dictionary d;
    gdn->godot_dictionary_new(&d);
    gdn_dict_put(&d, "force", gdn_vector2(f.x, f.y));
    gdn_dict_put(&d, "torque", gdn_real(torque));
    return gdn_dict_variant(&d);
}

/* {value, speed}: a hinge's angle (rad, rad/s), a slider's translation or a distance (px, px/s). */
static godot_variant get_joint_value(call *c)
{
    float value, speed;
    if (!ok(c, pp_joint_get_value(c->self->world, c->a[0].joint, &value, &speed)))
        return gdn_nil();
    godot_dictionary d;
    gdn->godot_dictionary_new(&d);
    gdn_dict_put(&d, "value", gdn_real(value));
    gdn_dict_put(&d, "speed", gdn_real(speed));
    return gdn_dict_variant(&d);
}

/* {anchor_a, anchor_b}: world px at the bodies' current poses (the static world's: its point; mouse: the target). */
static godot_variant get_joint_anchors(call *c)
{
    pp_vec2 a, b;
    if (!ok(c, pp_joint_get_anchors(c->self->world, c->a[0].joint, &a, &b)))
        return gdn_nil();
    godot_dictionary d;
    gdn->godot_dictionary_new(&d);
    gdn_dict_put(&d, "anchor_a", gdn_vector2(a.x, a.y));
    gdn_dict_put(&d, "anchor_b", gdn_vector2(b.x, b.y));
    return gdn_dict_variant(&d);
}

/* ---- edits ----------------------------------------------------------------------------- */

static godot_variant paint_circle(call *c)
{
    const int64_t weight = c->a[3].i;
    int32_t n;
    if (weight < 1 || weight > 255) {
        fail(c, "weight is %lld, expected 1..255", (long long)weight);
        return gdn_nil();
    }
    return ok(c, pp_body_paint_circle(c->self->world, c->a[0].body, c->a[1].v, c->a[2].f, (uint8_t)weight, &n))
               ? gdn_int(n)
               : gdn_nil();
}

/* ---- lists: bodies, contacts, events --------------------------------------------------- */

/* The pp list readers share one shape once the call's arguments are bound; these adapt their typed out-pointer to
 * void *. */
typedef pp_status (*list_fn)(const call *c, void *out, int32_t capacity, int32_t *count);
static pp_status list_bodies(const call *c, void *out, int32_t cap, int32_t *n)
{
    return pp_world_get_bodies(c->self->world, out, cap, n);
}

static pp_status list_contacts(const call *c, void *out, int32_t cap, int32_t *n)
{
    return pp_world_get_contacts(c->self->world, out, cap, n);
}

static pp_status list_events(const call *c, void *out, int32_t cap, int32_t *n)
{
    return pp_world_get_events(c->self->world, out, cap, n);
}

static pp_status list_states(const call *c, void *out, int32_t cap, int32_t *n)
{
    return pp_world_get_body_states(c->self->world, out, cap, n);
}

static pp_status list_joints(const call *c, void *out, int32_t cap, int32_t *n)
{
    return pp_world_get_joints(c->self->world, out, cap, n);
}

/* The whole list in a malloc'd array (a count first, then the items); *n is -1 on failure. */
static void *read_list(call *c, list_fn fn, size_t item_size, int32_t *n)
{
    int32_t total = 0;
    *n = -1;
    if (!ok(c, fn(c, NULL, 0, &total)))
        return NULL;
    void *items = total > 0 ? malloc(item_size * (size_t)total) : NULL;
    if (total > 0 && !items) {
        fail(c, "out of memory for %d items", (int)total);
        return NULL;
    }
    const int32_t capacity = total;
    if (total > 0 && !ok(c, fn(c, items, capacity, &total))) {
        free(items);
        return NULL;
    }
    *n = total < capacity ? total : capacity;
    return items;
}

/* One list item as a variant. */
typedef godot_variant (*item_fn)(const void *item);

/* Whether a list item goes into the Array (NULL: all do). */
typedef bool (*keep_fn)(const void *item);

/* The whole list fn reads as an Array of one variant an item; nil on failure. */
static godot_variant list_array(call *c, list_fn fn, size_t item_size, item_fn to_variant, keep_fn keep)
{
    int32_t n;
    char *items = read_list(c, fn, item_size, &n);
    if (n < 0)
        return gdn_nil();
    godot_array out;
    gdn->godot_array_new(&out);
    for (int32_t i = 0; i < n; i++)
        if (!keep || keep(items + (size_t)i * item_size))
            gdn_array_put(&out, to_variant(items + (size_t)i * item_size));
    free(items);
    return gdn_array_variant(&out);
}

static godot_variant body_item(const void *item)
{
    return body_int(*(const pp_body *)item);
}

static godot_variant contact_item(const void *item)
{
    const pp_contact *ct = item;
    godot_dictionary d;
    gdn->godot_dictionary_new(&d);
    gdn_dict_put(&d, "a", body_int(ct->a));
    gdn_dict_put(&d, "b", body_int(ct->b));
    gdn_dict_put(&d, "point", gdn_vector2(ct->point.x, ct->point.y));
    gdn_dict_put(&d, "normal", gdn_vector2(ct->normal.x, ct->normal.y));
    gdn_dict_put(&d, "depth", gdn_real(ct->depth));
    gdn_dict_put(&d, "pixel_count", gdn_int(ct->pixel_count));
    gdn_dict_put(&d, "normal_impulse", gdn_real(ct->normal_impulse));
    return gdn_dict_variant(&d);
}

static godot_variant event_item(const void *item)
{
    const pp_event *e = item;
    const uint32_t t = (uint32_t)e->type;
    const bool named = t < sizeof EVENT_TYPE_NAMES / sizeof EVENT_TYPE_NAMES[0] && EVENT_TYPE_NAMES[t];
    godot_dictionary d;
    gdn->godot_dictionary_new(&d);
    gdn_dict_put(&d, "type", gdn_string(named ? EVENT_TYPE_NAMES[t] : "unknown"));
    gdn_dict_put(&d, "body", body_int(e->body));
    gdn_dict_put(&d, "other", body_int(e->other));
    gdn_dict_put(&d, "point", gdn_vector2(e->point.x, e->point.y));
    gdn_dict_put(&d, "normal", gdn_vector2(e->normal.x, e->normal.y));
    gdn_dict_put(&d, "approach_speed", gdn_real(e->approach_speed));
    gdn_dict_put(&d, "joint", gdn_int((int64_t)e->joint.id));
    return gdn_dict_variant(&d);
}

/* A body's pose and motion: what a host reads each frame to move its nodes. */
static godot_variant state_item(const void *item)
{
    const pp_body_state *st = item;
    godot_dictionary d;
    gdn->godot_dictionary_new(&d);
    gdn_dict_put(&d, "body", body_int(st->body));
    gdn_dict_put(&d, "position", gdn_vector2(st->position.x, st->position.y));
    gdn_dict_put(&d, "angle", gdn_real(st->angle));
    gdn_dict_put(&d, "linear_velocity", gdn_vector2(st->linear_velocity.x, st->linear_velocity.y));
    gdn_dict_put(&d, "angular_velocity", gdn_real(st->angular_velocity));
    gdn_dict_put(&d, "awake", gdn_bool(st->awake != 0));
    return gdn_dict_variant(&d);
}

static godot_variant get_bodies(call *c)
{
    return list_array(c, list_bodies, sizeof(pp_body), body_item, NULL);
}

static godot_variant get_contacts(call *c)
{
    return list_array(c, list_contacts, sizeof(pp_contact), contact_item, NULL);
}

/* pp_world_debug_draw as an Array of {a, b, rgba, kind, body}: flags (default every one), and the view box
 * lower..upper (default everything; upper alone defaults to everything past lower). */
static godot_variant debug_draw(call *c)
{
    const uint32_t flags = c->argc > 0 ? (uint32_t)c->a[0].i : PP_DEBUG_DRAW_ALL;
    const pp_vec2 lo = c->argc > 1 ? c->a[1].v : (pp_vec2){-FLT_MAX, -FLT_MAX};
    const pp_vec2 hi = c->argc > 2 ? c->a[2].v : (pp_vec2){FLT_MAX, FLT_MAX};
    int32_t n = 0;
    if (!ok(c, pp_world_debug_draw(c->self->world, flags, lo, hi, NULL, 0, &n)))
        return gdn_nil();
    pp_debug_segment *segs = n > 0 ? malloc(sizeof *segs * (size_t)n) : NULL;
    if (n > 0 && !segs) {
        fail(c, "out of memory for %d segments", (int)n);
        return gdn_nil();
    }
    const int32_t capacity = n;
    if (n > 0 && !ok(c, pp_world_debug_draw(c->self->world, flags, lo, hi, segs, capacity, &n))) {
        free(segs);
        return gdn_nil();
    }
    godot_array out;
    gdn->godot_array_new(&out);
    for (int32_t i = 0; i < n && i < capacity; i++) {
        const pp_debug_segment *g = &segs[i];
        godot_dictionary d;
        gdn->godot_dictionary_new(&d);
        gdn_dict_put(&d, "a", gdn_vector2(g->a.x, g->a.y));
        gdn_dict_put(&d, "b", gdn_vector2(g->b.x, g->b.y));
        gdn_dict_put(&d, "rgba", gdn_int(g->rgba));
        gdn_dict_put(&d, "kind", gdn_int(g->kind));
        gdn_dict_put(&d, "body", body_int(g->body));
        gdn_array_put(&out, gdn_dict_variant(&d));
    }
    free(segs);
    return gdn_array_variant(&out);
}

static godot_variant joint_item(const void *item)
{
    return gdn_int((int64_t)((const pp_joint *)item)->id);
}

static godot_variant get_joints(call *c)
{
    return list_array(c, list_joints, sizeof(pp_joint), joint_item, NULL);
}

static godot_variant get_events(call *c)
{
    return list_array(c, list_events, sizeof(pp_event), event_item, NULL);
}

static bool state_awake(const void *item)
{
    return ((const pp_body_state *)item)->awake != 0;
}

/* Awake bodies only, on request: a frame's node updates then cost what moves, not what sleeps or is static. */
static godot_variant get_body_states(call *c)
{
    const bool awake_only = c->argc > 0 && c->a[0].i;
    return list_array(c, list_states, sizeof(pp_body_state), state_item, awake_only ? state_awake : NULL);
}

/* ---- raycasts, casts, queries and explosions ------------------------------------------ */

/* The optional mask argument at index i: all bits when it is left out. */
static uint32_t mask_arg(const call *c, int i)
{
    return c->argc > i ? (uint32_t)c->a[i].i : 0xffffffffu;
}

/* A hit as {body, point, normal, fraction}. */
static godot_variant hit_item(const void *item)
{
    const pp_raycast_hit *h = item;
    godot_dictionary d;
    gdn->godot_dictionary_new(&d);
    gdn_dict_put(&d, "body", body_int(h->body));
    gdn_dict_put(&d, "point", gdn_vector2(h->point.x, h->point.y));
    gdn_dict_put(&d, "normal", gdn_vector2(h->normal.x, h->normal.y));
    gdn_dict_put(&d, "fraction", gdn_real(h->fraction));
    return gdn_dict_variant(&d);
}

/* The nearest solid pixel on the segment as a hit, or nil (a miss or an error). */
static godot_variant raycast(call *c)
{
    pp_raycast_hit h;
    int32_t hit = 0;
    if (!ok(c, pp_world_raycast(c->self->world, c->a[0].v, c->a[1].v, mask_arg(c, 2), &h, &hit)) || !hit)
        return gdn_nil();
    return hit_item(&h);
}

/* Where a body swept along a translation first touches another, as a hit, or nil (free all the way, or an error). */
static godot_variant cast_body(call *c)
{
    pp_raycast_hit h;
    int32_t hit = 0;
    if (!ok(c, pp_world_cast_body(c->self->world, c->a[0].body, c->a[1].v, mask_arg(c, 2), &h, &hit)) || !hit)
        return gdn_nil();
    return hit_item(&h);
}

/* The list calls of the segment and the regions, their arguments bound. */
static pp_status list_ray_hits(const call *c, void *out, int32_t cap, int32_t *n)
{
    return pp_world_raycast_all(c->self->world, c->a[0].v, c->a[1].v, mask_arg(c, 2), out, cap, n);
}

static pp_status list_at_point(const call *c, void *out, int32_t cap, int32_t *n)
{
    return pp_world_query_point(c->self->world, c->a[0].v, mask_arg(c, 1), out, cap, n);
}

static pp_status list_in_box(const call *c, void *out, int32_t cap, int32_t *n)
{
    return pp_world_query_aabb(c->self->world, c->a[0].v, c->a[1].v, mask_arg(c, 2), out, cap, n);
}

static pp_status list_in_circle(const call *c, void *out, int32_t cap, int32_t *n)
{
    return pp_world_query_circle(c->self->world, c->a[0].v, c->a[1].f, mask_arg(c, 2), out, cap, n);
}

/* Every body the segment enters, as an Array of hits nearest first, or nil on failure. */
static godot_variant raycast_all(call *c)
{
    return list_array(c, list_ray_hits, sizeof(pp_raycast_hit), hit_item, NULL);
}

/* The bodies a query finds as an Array of body ints (in slot order), or nil on failure. */
static godot_variant query_point(call *c)
{
    return list_array(c, list_at_point, sizeof(pp_body), body_item, NULL);
}

static godot_variant query_aabb(call *c)
{
    return list_array(c, list_in_box, sizeof(pp_body), body_item, NULL);
}

static godot_variant query_circle(call *c)
{
    return list_array(c, list_in_circle, sizeof(pp_body), body_item, NULL);
}

/* The blast's erase and pushes; the pixels erased, or nil on failure. Arguments left out keep
 * pp_explosion_def_default's values. */
static godot_variant explode(call *c)
{
    pp_explosion_def d = pp_explosion_def_default();
    d.position = c->a[0].v;
    d.radius = c->a[1].f;
    if (c->argc > 2)
        d.falloff = c->a[2].f;
    if (c->argc > 3)
        d.impulse_per_length = c->a[3].f;
    if (c->argc > 4)
        d.erase_radius = c->a[4].f;
    d.mask_bits = mask_arg(c, 5);
    d.erase_mask_bits = mask_arg(c, 6);
    int32_t erased = 0;
    return ok(c, pp_world_explode(c->self->world, &d, &erased)) ? gdn_int(erased) : gdn_nil();
}

/* A character's capsule (pp_character_def fields by name; those left out keep pp_character_def_default's) moved from
 * position along velocity × delta: {position, velocity, grounded, ground_normal, ground_body, ground_velocity,
 * surfaces}, or nil on failure. */
static godot_variant move_character(call *c)
{
    pp_character_def d = pp_character_def_default();
    pp_character_move m;
    if ((c->argc > 3 && !fields_character_def(c, c->a[3].var, &d)) ||
        !ok(c, pp_world_move_character(c->self->world, &d, c->a[0].v, c->a[1].v, c->a[2].f, &m)))
        return gdn_nil();
    godot_dictionary r;
    gdn->godot_dictionary_new(&r);
    gdn_dict_put(&r, "position", gdn_vector2(m.position.x, m.position.y));
    gdn_dict_put(&r, "velocity", gdn_vector2(m.velocity.x, m.velocity.y));
    gdn_dict_put(&r, "grounded", gdn_bool(m.grounded != 0));
    gdn_dict_put(&r, "ground_normal", gdn_vector2(m.ground_normal.x, m.ground_normal.y));
    gdn_dict_put(&r, "ground_body", body_int(m.ground_body));
    gdn_dict_put(&r, "ground_velocity", gdn_vector2(m.ground_velocity.x, m.ground_velocity.y));
    gdn_dict_put(&r, "surfaces", gdn_int(m.surfaces));
    return gdn_dict_variant(&r);
}

/* ---- scenes, snapshots, clock and camera ---------------------------------------------- */

/* Puts a newly loaded world in place of the object's; the old one's body ints go stale. */
static godot_variant replace_world(call *c, pp_world loaded)
{
    if (c->self->world.id)
        pp_world_destroy(c->self->world);
    c->self->world = loaded;
    return gdn_bool(true);
}

/* A fresh world from settings (a preset, then pp_world_def fields): NativeScript's new() takes no arguments. */
static godot_variant create(call *c)
{
    pp_world_def def;
    pp_world made;
    if (c->argc > 0 && !fields_world_def(c, c->a[0].var, &def))
        return gdn_nil();
    if (c->argc == 0)
        def = pp_world_def_default();
    return ok(c, pp_world_create(&def, &made)) ? replace_world(c, made) : gdn_nil();
}

static godot_variant get_settings(call *c)
{
    pp_world_def def;
    return ok(c, pp_world_get_def(c->self->world, &def)) ? fields_world_dict(&def) : gdn_nil();
}

static godot_variant load_scene(call *c)
{
    pp_world loaded;
    /* On failure the library creates nothing and the old world stays as it was. */
    return ok(c, pp_world_load_scene(c->a[0].path, &loaded)) ? replace_world(c, loaded) : gdn_nil();
}

static godot_variant save_snapshot(call *c)
{
    return ok(c, pp_world_save_snapshot(c->self->world, c->a[0].path)) ? gdn_bool(true) : gdn_nil();
}

static godot_variant load_snapshot(call *c)
{
    pp_world loaded;
    return ok(c, pp_world_load_snapshot(c->a[0].path, &loaded)) ? replace_world(c, loaded) : gdn_nil();
}

static godot_variant save_state(call *c)
{
    int64_t size = 0;
    const pp_status st = pp_world_save_state(c->self->world, NULL, 0, &size);
    if (st != PP_ERR_LIMIT && !ok(c, st))
        return gdn_nil();
    godot_pool_byte_array pool;
    gdn->godot_pool_byte_array_new(&pool);
    gdn->godot_pool_byte_array_resize(&pool, (int32_t)size);
    godot_pool_byte_array_write_access *wr = gdn->godot_pool_byte_array_write(&pool);
    const bool saved = ok(c, pp_world_save_state(c->self->world, gdn->godot_pool_byte_array_write_access_ptr(wr), size,
                                                 &size));
    gdn->godot_pool_byte_array_write_access_destroy(wr);
    godot_variant r = gdn_nil();
    if (saved)
        gdn->godot_variant_new_pool_byte_array(&r, &pool);
    gdn->godot_pool_byte_array_destroy(&pool);
    return r;
}

/* The state bytes of argument 0 handed to fn (restore or load); its status. */
static bool with_state_bytes(call *c, bool load, pp_world *loaded)
{
    godot_pool_byte_array pool = gdn->godot_variant_as_pool_byte_array(c->a[0].var);
    godot_pool_byte_array_read_access *rd = gdn->godot_pool_byte_array_read(&pool);
    const uint8_t *p = gdn->godot_pool_byte_array_read_access_ptr(rd);
    const int64_t n = gdn->godot_pool_byte_array_size(&pool);
    const bool done = ok(c, load ? pp_world_load_state(p, n, loaded) : pp_world_restore_state(c->self->world, p, n));
    gdn->godot_pool_byte_array_read_access_destroy(rd);
    gdn->godot_pool_byte_array_destroy(&pool);
    return done;
}

static godot_variant restore_state(call *c)
{
    return with_state_bytes(c, false, NULL) ? gdn_bool(true) : gdn_nil();
}

static godot_variant load_state(call *c)
{
    pp_world loaded;
    return with_state_bytes(c, true, &loaded) ? replace_world(c, loaded) : gdn_nil();
}

static godot_variant get_hash(call *c)
{
    uint64_t h = 0;
    return ok(c, pp_world_get_hash(c->self->world, &h)) ? gdn_int((int64_t)h) : gdn_nil();
}

static godot_variant get_camera(call *c)
{
    pp_camera cam;
    if (!ok(c, pp_world_get_camera(c->self->world, &cam)))
        return gdn_nil();
    godot_dictionary d;
    gdn->godot_dictionary_new(&d);
    gdn_dict_put(&d, "center", gdn_vector2(cam.center.x, cam.center.y));
    gdn_dict_put(&d, "zoom", gdn_real(cam.zoom));
    gdn_dict_put(&d, "size", gdn_vector2((float)cam.width, (float)cam.height));
    return gdn_dict_variant(&d);
}

static godot_variant get_last_error(call *c)
{
    return gdn_string(c->self->error);
}

/* ---- the class ------------------------------------------------------------------------- */

/* METHODS, and the wrappers of the regular methods (those that call one PhysPix function). */
#include "methods_gen.h"

/* Every method comes through here: count and types are checked before the handler runs. */
static godot_variant dispatch(godot_object *instance, void *method_data, void *user_data, int argc,
                              godot_variant **args)
{
    char path[PATH_SIZE];
    call c = {.self = user_data, .def = method_data, .argc = argc, .path = path};
    if (!c.self) {
        record_error(NULL, c.def->name, "this PhysPixWorld has no instance data (out of memory when it was made)",
                     __FILE__, __LINE__);
        return gdn_nil();
    }
    /* get_last_error reports the call before it; every other call starts with a clean slate. */
    if (c.def->fn != get_last_error)
        c.self->error[0] = '\0';
    return read_args(&c, args) ? c.def->fn(&c) : gdn_nil();
}

static void *world_new(godot_object *instance, void *method_data)
{
    world_inst *self = calloc(1, sizeof *self);
    if (!self) {
        record_error(NULL, "new", "out of memory", __FILE__, __LINE__);
        return NULL;
    }
    const pp_world_def def = pp_world_def_default();
    if (pp_world_create(&def, &self->world) != PP_OK) {
        char msg[300];
        snprintf(msg, sizeof msg, "pp_world_create: %s", pp_last_error());
        record_error(self, "new", msg, __FILE__, __LINE__);
    }
    return self;
}

static void world_free(godot_object *instance, void *method_data, void *user_data)
{
    world_inst *self = user_data;
    if (self && self->world.id)
        pp_world_destroy(self->world);
    free(self);
}

static bool bind_engine_api(char *err, size_t err_size)
{
    if (!pixels_bind(err, err_size))
        return false;
    globalize_path_mb = gdn->godot_method_bind_get_method("ProjectSettings", "globalize_path");
    if (globalize_path_mb)
        return true;
    snprintf(err, err_size, "the engine has no ProjectSettings.globalize_path");
    return false;
}

GDN_EXPORT void godot_gdnative_init(godot_gdnative_init_options *options)
{
    char err[256] = "";
    if (pp_version() / 10000 != PHYSPIX_VERSION_MAJOR)
        snprintf(err, sizeof err, "libphyspix.so is version %u, this adapter was built for major %d",
                 (unsigned)pp_version(), PHYSPIX_VERSION_MAJOR);
    else if (gdn_bind(options->api_struct, err, sizeof err) && bind_engine_api(err, sizeof err))
        return;
    gdn_unbind();
    options->report_loading_error(options->gd_native_library, err);
}

GDN_EXPORT void godot_gdnative_terminate(godot_gdnative_terminate_options *options)
{
    gdn_unbind();
}

GDN_EXPORT void godot_nativescript_init(void *handle)
{
    if (!gdn)
        return; /* godot_gdnative_init already reported why */
    const godot_instance_create_func create = {world_new, NULL, NULL};
    const godot_instance_destroy_func destroy = {world_free, NULL, NULL};
    gdn_ns->godot_nativescript_register_class(handle, CLASS_NAME, "Reference", create, destroy);
    const godot_method_attributes attributes = {0};
    for (size_t i = 0; i < sizeof METHODS / sizeof METHODS[0]; i++) {
        const godot_instance_method method = {dispatch, (void *)&METHODS[i], NULL};
        gdn_ns->godot_nativescript_register_method(handle, CLASS_NAME, METHODS[i].name, attributes, method);
    }
}
