/* PhysPixWorld: a NativeScript class (base Reference) that gives GDScript one pp_world.
 * Owns the method table, the checking of every argument against it, the calls into PhysPix,
 * and the library's three entry points. Bodies are ints: the pp_body id's 64 bits. An id names its
 * world, so an int from before load_scene or load_snapshot replaced the object's world is refused by
 * PhysPix itself (PP_ERR_INVALID_HANDLE). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gdn.h"
#include "physpix.h"

#define CLASS_NAME "PhysPixWorld"
#define MAX_ARGS 6
#define PATH_SIZE 4096 /* a path argument's UTF-8 bytes, with the terminating NUL */

typedef struct world_inst {
    pp_world world;  /* id 0 if pp_world_create failed; every call then reports the stale handle */
    char error[512]; /* why the last call failed, "" if it succeeded */
} world_inst;

/* One argument after its type was checked, read as its spec letter says. */
typedef struct arg {
    const godot_variant *var;
    int64_t i;
    float f;
    pp_vec2 v;
    pp_body body;
    pp_body_type type;
    godot_object *object;
    const char *path; /* 'p': the call's path buffer, res:// and user:// made absolute */
} arg;

struct method_def;

/* One call of a method: who, which, and the checked arguments. */
typedef struct call {
    world_inst *self;
    const struct method_def *def;
    int argc;
    arg a[MAX_ARGS];
    char *path; /* PATH_SIZE bytes for the one path argument a method may have (not zeroed per call) */
} call;

typedef godot_variant (*method_fn)(call *c);

/* A GDScript-facing method. spec has one letter an argument, those after '|' optional:
 * i int, f float (an int is accepted), v Vector2, b body (int), t body type ("dynamic",
 * "static" or "kinematic"), M PoolByteArray, I Image, p path (String; res:// and user://
 * become filesystem paths through ProjectSettings.globalize_path, others are used as given),
 * m collision mask bits (int, 0..0xffffffff), o body options (Dictionary, see read_body_options), B bool. */
typedef struct method_def {
    const char *name;
    const char *spec;
    method_fn fn;
    const char *usage; /* quoted in error messages */
} method_def;

static const char *const EVENT_TYPE_NAMES[] = {
    [PP_EVENT_BODY_SPLIT] = "split",
    [PP_EVENT_BODY_DESTROYED] = "destroyed",
    [PP_EVENT_CONTACT_BEGIN] = "contact_begin",
    [PP_EVENT_CONTACT_END] = "contact_end",
    [PP_EVENT_SENSOR_BEGIN] = "sensor_begin",
    [PP_EVENT_SENSOR_END] = "sensor_end",
};

static const char *const BODY_TYPE_NAMES[] = {
    [PP_BODY_DYNAMIC] = "dynamic",
    [PP_BODY_STATIC] = "static",
    [PP_BODY_KINEMATIC] = "kinematic",
};

/* Image methods, looked up once at load; class tag to tell an Image from other objects. */
static struct {
    void *tag;
    godot_method_bind *get_width, *get_height, *get_format, *get_data, *convert, *duplicate;
} image_api;

/* ProjectSettings.globalize_path, looked up once at load; the singleton is asked for at each call. */
static godot_method_bind *globalize_path_mb;

/* ---- errors ---------------------------------------------------------------------------- */

/* fail() and ok() are macros so that the engine's "At: file:line" names the check that failed. */
#define fail(...) fail_at(__FILE__, __LINE__, __VA_ARGS__)
#define ok(c, status) ok_at(__FILE__, __LINE__, c, status)

static void record_error(world_inst *self, const char *method, const char *msg, const char *file, int line)
{
    char function[64];
    snprintf(function, sizeof function, CLASS_NAME ".%s", method);
    if (self)
        snprintf(self->error, sizeof self->error, "%s: %s", function, msg);
    gdn_print_error(function, msg, file, line);
}

/* Records and prints why the call failed; returns false so checks read `return cond || fail(...)`. */
__attribute__((format(printf, 4, 5))) static bool fail_at(const char *file, int line, call *c, const char *fmt, ...)
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
static bool ok_at(const char *file, int line, call *c, pp_status s)
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
    char singleton[] = "ProjectSettings";
    godot_object *settings = gdn->godot_global_get_singleton(singleton);
    if (!settings)
        return fail(c, "cannot globalize '%s': no ProjectSettings singleton (pass a filesystem path)", c->path);
    char given[PATH_SIZE];
    memcpy(given, c->path, n + 1);
    godot_variant in = gdn_string(given), out;
    const godot_variant *args[] = {&in};
    const bool called = gdn_call(globalize_path_mb, settings, args, 1, &out);
    const size_t m = called && gdn->godot_variant_get_type(&out) == GDN_STRING
                         ? gdn_string_to_utf8(&out, c->path, PATH_SIZE)
                         : 0;
    gdn->godot_variant_destroy(&out);
    gdn->godot_variant_destroy(&in);
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
    case 'm':
        if (t != GDN_INT)
            return wrong_type(c, i, "int (mask bits)");
        a->i = gdn->godot_variant_as_int(a->var);
        return (a->i >= 0 && a->i <= UINT32_MAX) ||
               fail(c, "argument %d, mask bits %lld, is outside 0..0xffffffff", i + 1, (long long)a->i);
    case 'o':
        return t == GDN_DICTIONARY || wrong_type(c, i, "Dictionary (body options)");
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
        if (t != GDN_OBJECT)
            return wrong_type(c, i, "Image");
        a->object = gdn->godot_variant_as_object(a->var);
        /* A freed object may still be a pointer, so ask the ObjectDB; anything but an Image would
         * crash get_data. */
        if (!a->object || !gdn11->godot_is_instance_valid(a->object))
            return fail(c, "argument %d is a freed or null object, expected Image", i + 1);
        if (!gdn12->godot_object_cast_to(a->object, image_api.tag))
            return wrong_type(c, i, "Image");
        return true;
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

/* One body option: the variant type its value must have and where it goes in the def. */
typedef struct body_option {
    const char *name;
    int32_t type; /* GDN_BOOL or GDN_VECTOR2 */
    size_t offset;
} body_option;

static const body_option BODY_OPTIONS[] = {
    {"is_sensor", GDN_BOOL, offsetof(pp_body_def, is_sensor)},
    {"one_way", GDN_BOOL, offsetof(pp_body_def, one_way)},
    {"one_way_direction", GDN_VECTOR2, offsetof(pp_body_def, one_way_direction)},
};

/* Sets the def fields an options Dictionary names (keys as in pp_body_def); an unknown key or a value of
 * the wrong type is refused, so a typo is not silently a default. */
static bool read_body_options(call *c, const godot_variant *var, pp_body_def *def)
{
    godot_dictionary dict = gdn->godot_variant_as_dictionary(var);
    godot_array keys = gdn->godot_dictionary_keys(&dict);
    bool good = true;
    for (int32_t k = 0, n = gdn->godot_array_size(&keys); good && k < n; k++) {
        godot_variant key = gdn->godot_array_get(&keys, k);
        char name[32] = "";
        const body_option *opt = NULL;
        const bool named = gdn->godot_variant_get_type(&key) == GDN_STRING &&
                           gdn_string_to_utf8(&key, name, sizeof name) < sizeof name;
        if (named)
            for (size_t i = 0; i < sizeof BODY_OPTIONS / sizeof BODY_OPTIONS[0]; i++)
                if (strcmp(name, BODY_OPTIONS[i].name) == 0)
                    opt = &BODY_OPTIONS[i];
        godot_variant value = gdn->godot_dictionary_get(&dict, &key);
        const int32_t t = gdn->godot_variant_get_type(&value);
        if (!opt) {
            good = fail(c, "options has the key \"%s\"; known keys are \"is_sensor\" (bool), \"one_way\" (bool) and "
                           "\"one_way_direction\" (Vector2)", name[0] ? name : gdn_type_name(&key));
        } else if (t != opt->type) {
            good = fail(c, "options[\"%s\"] is %s, expected %s", opt->name, gdn_type_name(&value),
                        opt->type == GDN_BOOL ? "bool" : "Vector2");
        } else if (opt->type == GDN_BOOL) {
            *(uint32_t *)((char *)def + opt->offset) = gdn->godot_variant_as_bool(&value) ? 1 : 0;
        } else {
            pp_vec2 *v = (pp_vec2 *)((char *)def + opt->offset);
            gdn_vector2_read(&value, &v->x, &v->y);
        }
        gdn->godot_variant_destroy(&value);
        gdn->godot_variant_destroy(&key);
    }
    gdn->godot_array_destroy(&keys);
    gdn->godot_dictionary_destroy(&dict);
    return good;
}

/* A default def at args[first] (position), args[first + 1] (type, default dynamic) and args[first + 2]
 * (options, default none); false if the options were refused. */
static bool body_def(call *c, int first, pp_body_def *def)
{
    *def = pp_body_def_default();
    def->position = c->a[first].v;
    def->type = c->argc > first + 1 ? c->a[first + 1].type : PP_BODY_DYNAMIC;
    return c->argc <= first + 2 || read_body_options(c, c->a[first + 2].var, def);
}

/* A body's int for GDScript (0 stays 0: "no body" in events). */
static godot_variant body_int(pp_body b)
{
    return gdn_int((int64_t)b.id);
}

static godot_variant create_body(call *c, const pp_body_def *def)
{
    pp_body b;
    return ok(c, pp_body_create(c->self->world, def, &b)) ? body_int(b) : gdn_nil();
}

/* Creates a body whose width × height plane (mask if rgba is false, else RGBA) is a PoolByteArray. */
static godot_variant create_body_from_pool(call *c, pp_body_def *def, const godot_variant *pool_var, bool rgba)
{
    godot_pool_byte_array pool = gdn->godot_variant_as_pool_byte_array(pool_var);
    const int64_t have = gdn->godot_pool_byte_array_size(&pool);
    const int64_t need = (int64_t)def->width * def->height * (rgba ? 4 : 1);
    godot_variant r = gdn_nil();
    /* An image with mipmaps carries the smaller levels after the first; only a short buffer is wrong. */
    if (rgba ? have < need : have != need) {
        fail(c, "%s has %lld bytes, expected %lld (%d × %d%s)", rgba ? "the image data" : "the mask",
             (long long)have, (long long)need, (int)def->width, (int)def->height, rgba ? " × 4" : "");
    } else {
        godot_pool_byte_array_read_access *rd = gdn->godot_pool_byte_array_read(&pool);
        const uint8_t *bytes = gdn->godot_pool_byte_array_read_access_ptr(rd);
        if (rgba)
            def->rgba = bytes;
        else
            def->mask = bytes;
        r = create_body(c, def);
        gdn->godot_pool_byte_array_read_access_destroy(rd);
    }
    gdn->godot_pool_byte_array_destroy(&pool);
    return r;
}

static bool bitmap_size_ok(call *c, int64_t w, int64_t h)
{
    return (w >= 1 && h >= 1 && w <= PP_MAX_BITMAP_SIDE && h <= PP_MAX_BITMAP_SIDE) ||
           fail(c, "a bitmap of %lld × %lld pixels; each side must be 1..%d", (long long)w, (long long)h,
                PP_MAX_BITMAP_SIDE);
}

static godot_variant add_body_mask(call *c)
{
    if (!bitmap_size_ok(c, c->a[1].i, c->a[2].i))
        return gdn_nil();
    pp_body_def def;
    if (!body_def(c, 3, &def))
        return gdn_nil();
    def.width = (int32_t)c->a[1].i;
    def.height = (int32_t)c->a[2].i;
    return create_body_from_pool(c, &def, c->a[0].var, false);
}

/* image.<getter>() as an int, -1 if the call failed. */
static int64_t image_int(godot_object *image, godot_method_bind *getter)
{
    godot_variant v;
    const int64_t r = gdn_call(getter, image, NULL, 0, &v) ? gdn->godot_variant_as_int(&v) : -1;
    gdn->godot_variant_destroy(&v);
    return r;
}

static godot_variant add_body_image(call *c)
{
    godot_object *image = c->a[0].object;
    const int64_t w = image_int(image, image_api.get_width), h = image_int(image, image_api.get_height);
    if (!bitmap_size_ok(c, w, h))
        return gdn_nil();
    godot_variant copy = gdn_nil(), data = gdn_nil(), r = gdn_nil();
    const int64_t format = image_int(image, image_api.get_format);
    if (format != GDN_IMAGE_FORMAT_RGBA8) {
        /* Convert a copy, so the caller's image stays as it was; `copy` holds its reference. */
        gdn->godot_variant_destroy(&copy);
        if (!gdn_call(image_api.duplicate, image, NULL, 0, &copy)) {
            fail(c, "Image.duplicate() failed");
            goto done;
        }
        image = gdn->godot_variant_as_object(&copy);
        godot_variant fmt = gdn_int(GDN_IMAGE_FORMAT_RGBA8), ignored;
        const godot_variant *args[] = {&fmt};
        gdn_call(image_api.convert, image, args, 1, &ignored);
        gdn->godot_variant_destroy(&ignored);
        gdn->godot_variant_destroy(&fmt);
        if (image_int(image, image_api.get_format) != GDN_IMAGE_FORMAT_RGBA8) {
            fail(c, "cannot convert an image of format %lld to RGBA8 (a compressed image? decompress() it)",
                 (long long)format);
            goto done;
        }
    }
    gdn->godot_variant_destroy(&data);
    if (!gdn_call(image_api.get_data, image, NULL, 0, &data)) {
        fail(c, "Image.get_data() failed");
        goto done;
    }
    pp_body_def def;
    if (!body_def(c, 1, &def))
        goto done;
    def.width = (int32_t)w;
    def.height = (int32_t)h;
    r = create_body_from_pool(c, &def, &data, true);
done:
    gdn->godot_variant_destroy(&data);
    gdn->godot_variant_destroy(&copy);
    return r;
}

static godot_variant destroy_body(call *c)
{
    ok(c, pp_body_destroy(c->self->world, c->a[0].body));
    return gdn_nil();
}

/* ---- stepping and reading state -------------------------------------------------------- */

static godot_variant step(call *c)
{
    ok(c, pp_world_step(c->self->world, c->a[0].f));
    return gdn_nil();
}

static godot_variant get_position(call *c)
{
    pp_vec2 p;
    return ok(c, pp_body_get_position(c->self->world, c->a[0].body, &p)) ? gdn_vector2(p.x, p.y) : gdn_nil();
}

static godot_variant get_angle(call *c)
{
    float a;
    return ok(c, pp_body_get_angle(c->self->world, c->a[0].body, &a)) ? gdn_real(a) : gdn_nil();
}

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

static godot_variant get_linear_velocity(call *c)
{
    pp_vec2 v;
    return ok(c, pp_body_get_velocity(c->self->world, c->a[0].body, &v, NULL)) ? gdn_vector2(v.x, v.y) : gdn_nil();
}

static godot_variant get_angular_velocity(call *c)
{
    float w;
    return ok(c, pp_body_get_velocity(c->self->world, c->a[0].body, NULL, &w)) ? gdn_real(w) : gdn_nil();
}

static godot_variant set_velocity(call *c)
{
    ok(c, pp_body_set_velocity(c->self->world, c->a[0].body, c->a[1].v, c->a[2].f));
    return gdn_nil();
}

static godot_variant apply_impulse(call *c)
{
    ok(c, pp_body_apply_impulse(c->self->world, c->a[0].body, c->a[1].v, c->a[2].v));
    return gdn_nil();
}

static godot_variant get_mass(call *c)
{
    float m;
    return ok(c, pp_body_get_mass(c->self->world, c->a[0].body, &m, NULL, NULL)) ? gdn_real(m) : gdn_nil();
}

/* ---- edits ----------------------------------------------------------------------------- */

static godot_variant erase_circle(call *c)
{
    int32_t n;
    return ok(c, pp_body_erase_circle(c->self->world, c->a[0].body, c->a[1].v, c->a[2].f, &n)) ? gdn_int(n)
                                                                                                  : gdn_nil();
}

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

static godot_variant world_erase_circle(call *c)
{
    int32_t n;
    return ok(c, pp_world_erase_circle(c->self->world, c->a[0].v, c->a[1].f, &n)) ? gdn_int(n) : gdn_nil();
}

/* ---- lists: bodies, contacts, events --------------------------------------------------- */

/* The three pp list readers share one shape; these adapt their typed out-pointer to void *. */
typedef pp_status (*list_fn)(pp_world w, void *out, int32_t capacity, int32_t *count);
static pp_status list_bodies(pp_world w, void *out, int32_t cap, int32_t *n)
{
    return pp_world_get_bodies(w, out, cap, n);
}

static pp_status list_contacts(pp_world w, void *out, int32_t cap, int32_t *n)
{
    return pp_world_get_contacts(w, out, cap, n);
}

static pp_status list_events(pp_world w, void *out, int32_t cap, int32_t *n)
{
    return pp_world_get_events(w, out, cap, n);
}

/* The whole list in a malloc'd array (a count first, then the items); *n is -1 on failure. */
static void *read_list(call *c, list_fn fn, size_t item_size, int32_t *n)
{
    int32_t total = 0;
    *n = -1;
    if (!ok(c, fn(c->self->world, NULL, 0, &total)))
        return NULL;
    void *items = total > 0 ? malloc(item_size * (size_t)total) : NULL;
    if (total > 0 && !items) {
        fail(c, "out of memory for %d items", (int)total);
        return NULL;
    }
    const int32_t capacity = total;
    if (total > 0 && !ok(c, fn(c->self->world, items, capacity, &total))) {
        free(items);
        return NULL;
    }
    *n = total < capacity ? total : capacity;
    return items;
}

static godot_variant get_bodies(call *c)
{
    int32_t n;
    pp_body *bodies = read_list(c, list_bodies, sizeof *bodies, &n);
    if (n < 0)
        return gdn_nil();
    godot_array out;
    gdn->godot_array_new(&out);
    for (int32_t i = 0; i < n; i++)
        gdn_array_put(&out, body_int(bodies[i]));
    free(bodies);
    return gdn_array_variant(&out);
}

static godot_variant get_contacts(call *c)
{
    int32_t n;
    pp_contact *cs = read_list(c, list_contacts, sizeof *cs, &n);
    if (n < 0)
        return gdn_nil();
    godot_array out;
    gdn->godot_array_new(&out);
    for (int32_t i = 0; i < n; i++) {
        godot_dictionary d;
        gdn->godot_dictionary_new(&d);
        gdn_dict_put(&d, "a", body_int(cs[i].a));
        gdn_dict_put(&d, "b", body_int(cs[i].b));
        gdn_dict_put(&d, "point", gdn_vector2(cs[i].point.x, cs[i].point.y));
        gdn_dict_put(&d, "normal", gdn_vector2(cs[i].normal.x, cs[i].normal.y));
        gdn_dict_put(&d, "depth", gdn_real(cs[i].depth));
        gdn_dict_put(&d, "pixel_count", gdn_int(cs[i].pixel_count));
        gdn_dict_put(&d, "normal_impulse", gdn_real(cs[i].normal_impulse));
        gdn_array_put(&out, gdn_dict_variant(&d));
    }
    free(cs);
    return gdn_array_variant(&out);
}

static godot_variant get_events(call *c)
{
    int32_t n;
    pp_event *es = read_list(c, list_events, sizeof *es, &n);
    if (n < 0)
        return gdn_nil();
    godot_array out;
    gdn->godot_array_new(&out);
    for (int32_t i = 0; i < n; i++) {
        const uint32_t t = (uint32_t)es[i].type;
        godot_dictionary d;
        gdn->godot_dictionary_new(&d);
        gdn_dict_put(&d, "type", gdn_string(t < sizeof EVENT_TYPE_NAMES / sizeof EVENT_TYPE_NAMES[0] &&
                                                    EVENT_TYPE_NAMES[t]
                                                ? EVENT_TYPE_NAMES[t]
                                                : "unknown"));
        gdn_dict_put(&d, "body", body_int(es[i].body));
        gdn_dict_put(&d, "other", body_int(es[i].other));
        gdn_dict_put(&d, "point", gdn_vector2(es[i].point.x, es[i].point.y));
        gdn_dict_put(&d, "normal", gdn_vector2(es[i].normal.x, es[i].normal.y));
        gdn_dict_put(&d, "approach_speed", gdn_real(es[i].approach_speed));
        gdn_array_put(&out, gdn_dict_variant(&d));
    }
    free(es);
    return gdn_array_variant(&out);
}

/* ---- raycasts and queries ------------------------------------------------------------- */

/* The optional mask argument at index i: all bits when it is left out. */
static uint32_t mask_arg(const call *c, int i)
{
    return c->argc > i ? (uint32_t)c->a[i].i : 0xffffffffu;
}

/* {body, point, normal, fraction} of the nearest solid pixel on the segment, or nil (a miss or an error). */
static godot_variant raycast(call *c)
{
    pp_raycast_hit h;
    int32_t hit = 0;
    if (!ok(c, pp_world_raycast(c->self->world, c->a[0].v, c->a[1].v, mask_arg(c, 2), &h, &hit)) || !hit)
        return gdn_nil();
    godot_dictionary d;
    gdn->godot_dictionary_new(&d);
    gdn_dict_put(&d, "body", body_int(h.body));
    gdn_dict_put(&d, "point", gdn_vector2(h.point.x, h.point.y));
    gdn_dict_put(&d, "normal", gdn_vector2(h.normal.x, h.normal.y));
    gdn_dict_put(&d, "fraction", gdn_real(h.fraction));
    return gdn_dict_variant(&d);
}

/* A query's region once its arguments are bound; the three adapt the pp calls to it. */
typedef pp_status (*query_fn)(const call *c, uint32_t mask, pp_body *out, int32_t capacity, int32_t *count);
static pp_status query_point_fn(const call *c, uint32_t mask, pp_body *out, int32_t cap, int32_t *n)
{
    return pp_world_query_point(c->self->world, c->a[0].v, mask, out, cap, n);
}

static pp_status query_aabb_fn(const call *c, uint32_t mask, pp_body *out, int32_t cap, int32_t *n)
{
    return pp_world_query_aabb(c->self->world, c->a[0].v, c->a[1].v, mask, out, cap, n);
}

static pp_status query_circle_fn(const call *c, uint32_t mask, pp_body *out, int32_t cap, int32_t *n)
{
    return pp_world_query_circle(c->self->world, c->a[0].v, c->a[1].f, mask, out, cap, n);
}

/* The bodies a query finds as an Array of body ints (in slot order), or nil on failure. */
static godot_variant run_query(call *c, query_fn fn, uint32_t mask)
{
    int32_t total = 0;
    if (!ok(c, fn(c, mask, NULL, 0, &total)))
        return gdn_nil();
    pp_body *found = total > 0 ? malloc(sizeof *found * (size_t)total) : NULL;
    if (total > 0 && !found) {
        fail(c, "out of memory for %d bodies", (int)total);
        return gdn_nil();
    }
    const int32_t capacity = total;
    if (total > 0 && !ok(c, fn(c, mask, found, capacity, &total))) {
        free(found);
        return gdn_nil();
    }
    godot_array out;
    gdn->godot_array_new(&out);
    for (int32_t i = 0; i < total && i < capacity; i++)
        gdn_array_put(&out, body_int(found[i]));
    free(found);
    return gdn_array_variant(&out);
}

static godot_variant query_point(call *c)
{
    return run_query(c, query_point_fn, mask_arg(c, 1));
}

static godot_variant query_aabb(call *c)
{
    return run_query(c, query_aabb_fn, mask_arg(c, 2));
}

static godot_variant query_circle(call *c)
{
    return run_query(c, query_circle_fn, mask_arg(c, 2));
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

static godot_variant set_contact_events(call *c)
{
    ok(c, pp_world_set_contact_events(c->self->world, c->a[0].i != 0));
    return gdn_nil();
}

static godot_variant get_time(call *c)
{
    double t;
    return ok(c, pp_world_get_time(c->self->world, &t)) ? gdn_real(t) : gdn_nil();
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

static const method_def METHODS[] = {
    {"add_body_mask", "Miiv|to", add_body_mask,
     "add_body_mask(mask: PoolByteArray, width: int, height: int, position: Vector2, type: String = \"dynamic\","
     " options: Dictionary = {}) -> int"},
    {"add_body_image", "Iv|to", add_body_image,
     "add_body_image(image: Image, position: Vector2, type: String = \"dynamic\", options: Dictionary = {}) -> int"},
    {"destroy_body", "b", destroy_body, "destroy_body(body: int)"},
    {"step", "f", step, "step(dt: float)"},
    {"get_transform", "b", get_transform, "get_transform(body: int) -> Transform2D"},
    {"get_position", "b", get_position, "get_position(body: int) -> Vector2"},
    {"get_angle", "b", get_angle, "get_angle(body: int) -> float"},
    {"get_linear_velocity", "b", get_linear_velocity, "get_linear_velocity(body: int) -> Vector2"},
    {"get_angular_velocity", "b", get_angular_velocity, "get_angular_velocity(body: int) -> float"},
    {"set_velocity", "bvf", set_velocity, "set_velocity(body: int, linear: Vector2, angular: float)"},
    {"apply_impulse", "bvv", apply_impulse, "apply_impulse(body: int, impulse: Vector2, point: Vector2)"},
    {"get_mass", "b", get_mass, "get_mass(body: int) -> float"},
    {"erase_circle", "bvf", erase_circle, "erase_circle(body: int, center: Vector2, radius: float) -> int"},
    {"paint_circle", "bvfi", paint_circle,
     "paint_circle(body: int, center: Vector2, radius: float, weight: int) -> int"},
    {"world_erase_circle", "vf", world_erase_circle, "world_erase_circle(center: Vector2, radius: float) -> int"},
    {"get_bodies", "", get_bodies, "get_bodies() -> Array"},
    {"get_contacts", "", get_contacts, "get_contacts() -> Array"},
    {"get_events", "", get_events, "get_events() -> Array"},
    {"raycast", "vv|m", raycast, "raycast(from: Vector2, to: Vector2, mask: int = 0xffffffff) -> Dictionary or null"},
    {"query_point", "v|m", query_point, "query_point(point: Vector2, mask: int = 0xffffffff) -> Array"},
    {"query_aabb", "vv|m", query_aabb, "query_aabb(lower: Vector2, upper: Vector2, mask: int = 0xffffffff) -> Array"},
    {"query_circle", "vf|m", query_circle,
     "query_circle(center: Vector2, radius: float, mask: int = 0xffffffff) -> Array"},
    {"load_scene", "p", load_scene, "load_scene(path: String) -> bool"},
    {"save_snapshot", "p", save_snapshot, "save_snapshot(folder: String) -> bool"},
    {"load_snapshot", "p", load_snapshot, "load_snapshot(folder: String) -> bool"},
    {"get_time", "", get_time, "get_time() -> float"},
    {"set_contact_events", "B", set_contact_events, "set_contact_events(enabled: bool)"},
    {"get_camera", "", get_camera, "get_camera() -> Dictionary"},
    {"get_last_error", "", get_last_error, "get_last_error() -> String"},
};

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
    godot_string_name name;
    gdn->godot_string_name_new_data(&name, "Image");
    image_api.tag = gdn12->godot_get_class_tag(&name);
    gdn->godot_string_name_destroy(&name);
    image_api.get_width = gdn->godot_method_bind_get_method("Image", "get_width");
    image_api.get_height = gdn->godot_method_bind_get_method("Image", "get_height");
    image_api.get_format = gdn->godot_method_bind_get_method("Image", "get_format");
    image_api.get_data = gdn->godot_method_bind_get_method("Image", "get_data");
    image_api.convert = gdn->godot_method_bind_get_method("Image", "convert");
    image_api.duplicate = gdn->godot_method_bind_get_method("Resource", "duplicate");
    if (!image_api.tag || !image_api.get_width || !image_api.get_height || !image_api.get_format ||
        !image_api.get_data || !image_api.convert || !image_api.duplicate) {
        snprintf(err, err_size, "the engine has no Image class with get_width/get_height/get_format/get_data/convert");
        return false;
    }
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
