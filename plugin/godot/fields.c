/* Dictionaries of def fields for PhysPixWorld: a world's settings (create, get_settings), a body's options
 * (add_body_mask, add_body_image), a joint's def (create_joint) and a character's (move_character). Keys are the C
 * field names; an unknown key or a value of the wrong type is refused, so a typo is never silently a default. Enums are the scene files' lower-case names. */
#include <stdio.h>
#include <string.h>

#include "adapter.h"
#include "../api/def_fields.h"

typedef enum field_kind { F_BOOL, F_FLOAT, F_INT, F_BITS, F_VEC2, F_ENUM, F_ID } field_kind;

/* One field: its key, what its value must be, and where it goes in the def. */
typedef struct field {
    const char *name;
    field_kind kind;
    size_t offset;
    const char *const *names; /* F_ENUM: the enum's names by value */
} field;

/* The defs' fields, and the enums' names, come from plugin/api/physpix_api.json (gen_api.py); the fields a
 * Dictionary must not set are listed there. set_field writes a kind's C type, so a field of another size is refused
 * here. */
enum { SIZE_BOOL = 4, SIZE_BITS = 4, SIZE_INT = 4, SIZE_FLOAT = 4, SIZE_ENUM = 4, SIZE_ID = 8, SIZE_VEC2 = 8 };
#define ROW(def, name, KIND, names) {#name, F_##KIND, offsetof(def, name), names},
#define SIZED(def, name, KIND) _Static_assert(sizeof(((def *)0)->name) == SIZE_##KIND, #def "." #name " is no " #KIND);
#define W(name, KIND, names) ROW(pp_world_def, name, KIND, names)
#define B(name, KIND, names) ROW(pp_body_def, name, KIND, names)
#define J(name, KIND, names) ROW(pp_joint_def, name, KIND, names)
#define C(name, KIND, names) ROW(pp_character_def, name, KIND, names)
static const field WORLD_FIELDS[] = {PP_WORLD_DEF_FIELDS(W)};
static const field BODY_FIELDS[] = {PP_BODY_DEF_FIELDS(B)}; /* "collision_mask" and "weights": body_special */
static const field JOINT_FIELDS[] = {PP_JOINT_DEF_FIELDS(J)}; /* bodies and user_data: ints, 0 the static world */
static const field CHARACTER_FIELDS[] = {PP_CHARACTER_DEF_FIELDS(C)};
#undef W
#undef B
#undef J
#undef C
#define W(name, KIND, names) SIZED(pp_world_def, name, KIND)
#define B(name, KIND, names) SIZED(pp_body_def, name, KIND)
#define J(name, KIND, names) SIZED(pp_joint_def, name, KIND)
#define C(name, KIND, names) SIZED(pp_character_def, name, KIND)
PP_WORLD_DEF_FIELDS(W)
PP_BODY_DEF_FIELDS(B)
PP_JOINT_DEF_FIELDS(J)
PP_CHARACTER_DEF_FIELDS(C)
#undef W
#undef B
#undef J
#undef C

static const char *kind_name(field_kind k)
{
    switch (k) {
    case F_BOOL: return "bool";
    case F_FLOAT: return "float";
    case F_INT: return "int";
    case F_BITS: return "int (bits, 0..0xffffffff)";
    case F_ID: return "int";
    case F_VEC2: return "Vector2";
    default: return "String";
    }
}

/* Writes one value into the def at f->offset; false (with the reason recorded) if it does not fit. */
static bool set_field(call *c, const char *what, const field *f, const godot_variant *value, void *def)
{
    char *at = (char *)def + f->offset;
    const int32_t t = gdn->godot_variant_get_type(value);
    const bool number = t == GDN_INT || t == GDN_REAL;
    bool good = false;
    switch (f->kind) {
    case F_BOOL:
        if ((good = t == GDN_BOOL))
            *(uint32_t *)at = gdn->godot_variant_as_bool(value) ? 1 : 0;
        break;
    case F_FLOAT:
        if ((good = number))
            *(float *)at = (float)gdn->godot_variant_as_real(value);
        break;
    case F_INT: {
        const int64_t i = t == GDN_INT ? gdn->godot_variant_as_int(value) : 0;
        if ((good = t == GDN_INT && i >= INT32_MIN && i <= INT32_MAX))
            *(int32_t *)at = (int32_t)i;
        break;
    }
    case F_BITS: {
        const int64_t i = t == GDN_INT ? gdn->godot_variant_as_int(value) : -1;
        if ((good = i >= 0 && i <= UINT32_MAX))
            *(uint32_t *)at = (uint32_t)i;
        break;
    }
    case F_ID:
        if ((good = t == GDN_INT))
            *(uint64_t *)at = (uint64_t)gdn->godot_variant_as_int(value);
        break;
    case F_VEC2:
        if ((good = t == GDN_VECTOR2)) {
            pp_vec2 *v = (pp_vec2 *)at;
            gdn_vector2_read(value, &v->x, &v->y);
        }
        break;
    case F_ENUM: {
        char name[32] = "";
        if (t == GDN_STRING)
            gdn_string_to_utf8(value, name, sizeof name);
        for (int k = 0; f->names[k]; k++)
            if (f->names[k][0] && strcmp(name, f->names[k]) == 0) {
                *(int32_t *)at = k;
                return true;
            }
        char known[96] = "";
        for (int k = 0; f->names[k]; k++)
            if (f->names[k][0])
                snprintf(known + strlen(known), sizeof known - strlen(known), "%s\"%s\"", known[0] ? ", " : "",
                         f->names[k]);
        return fail(c, "%s[\"%s\"] is %s%s%s, expected one of %s", what, f->name, gdn_type_name(value),
                    name[0] ? " " : "", name, known);
    }
    }
    return good || fail(c, "%s[\"%s\"] is %s, expected %s", what, f->name, gdn_type_name(value), kind_name(f->kind));
}

static const field *find_field(const field *fields, size_t n, const char *name)
{
    for (size_t i = 0; i < n; i++)
        if (strcmp(name, fields[i].name) == 0)
            return &fields[i];
    return NULL;
}

/* Called for a key before the table; returns 1 if it handled the key, 0 if not, -1 if it refused the value. */
typedef int (*special_fn)(call *c, const char *key, const godot_variant *value, void *def, void *extra);

/* Sets every field a Dictionary names. */
static bool read_fields(call *c, const godot_variant *var, const char *what, const field *fields, size_t n, void *def,
                        special_fn special, void *extra)
{
    godot_dictionary dict = gdn->godot_variant_as_dictionary(var);
    godot_array keys = gdn->godot_dictionary_keys(&dict);
    bool good = true;
    for (int32_t k = 0, count = gdn->godot_array_size(&keys); good && k < count; k++) {
        godot_variant key = gdn->godot_array_get(&keys, k);
        godot_variant value = gdn->godot_dictionary_get(&dict, &key);
        char name[32] = "";
        const bool named = gdn->godot_variant_get_type(&key) == GDN_STRING &&
                           gdn_string_to_utf8(&key, name, sizeof name) < sizeof name;
        const int handled = named && special ? special(c, name, &value, def, extra) : 0;
        const field *f = named && handled == 0 ? find_field(fields, n, name) : NULL;
        if (handled < 0)
            good = false;
        else if (handled == 0 && !f)
            good = fail(c, "%s has the key \"%s\", which is no %s field (keys are the C def's field names)", what,
                        name[0] ? name : gdn_type_name(&key), what);
        else if (f)
            good = set_field(c, what, f, &value, def);
        gdn->godot_variant_destroy(&value);
        gdn->godot_variant_destroy(&key);
    }
    gdn->godot_array_destroy(&keys);
    gdn->godot_dictionary_destroy(&dict);
    return good;
}

/* The key read before the others (extra names it); here it is only skipped. */
static int skip_leading(call *c, const char *key, const godot_variant *value, void *def, void *extra)
{
    return strcmp(key, extra) == 0;
}

/* The enum that picks a def's defaults ("preset", a joint's "type"), read before the other keys into *out;
 * 0 if absent, 1 if read, -1 if refused. */
static int read_leading(call *c, const godot_variant *var, const char *what, const field *f, int32_t *out)
{
    godot_dictionary dict = gdn->godot_variant_as_dictionary(var);
    godot_variant key = gdn_string(f->name);
    int found = 0;
    if (gdn->godot_dictionary_has(&dict, &key)) {
        godot_variant value = gdn->godot_dictionary_get(&dict, &key);
        found = set_field(c, what, f, &value, out) ? 1 : -1;
        gdn->godot_variant_destroy(&value);
    }
    gdn->godot_variant_destroy(&key);
    gdn->godot_dictionary_destroy(&dict);
    return found;
}

bool fields_world_def(call *c, const godot_variant *var, pp_world_def *out)
{
    const field f = {"preset", F_ENUM, 0, pp_preset_names};
    int32_t preset = 0;
    const int found = read_leading(c, var, "settings", &f, &preset);
    *out = found == 1 ? pp_world_def_preset((pp_preset)preset) : pp_world_def_default();
    return found >= 0 && read_fields(c, var, "settings", WORLD_FIELDS, sizeof WORLD_FIELDS / sizeof WORLD_FIELDS[0],
                                     out, skip_leading, (void *)f.name);
}

bool fields_joint_def(call *c, const godot_variant *var, pp_joint_def *out)
{
    const field f = {"type", F_ENUM, 0, pp_joint_type_names};
    int32_t type = 0;
    const int found = read_leading(c, var, "joint", &f, &type);
    if (found == 0)
        return fail(c, "joint has no \"type\" (\"revolute\", \"prismatic\", \"distance\", \"weld\", \"mouse\", \"wheel\" or "
                       "\"motor\")");
    *out = pp_joint_def_default((pp_joint_type)type);
    return found > 0 && read_fields(c, var, "joint", JOINT_FIELDS, sizeof JOINT_FIELDS / sizeof JOINT_FIELDS[0], out,
                                    skip_leading, (void *)f.name);
}

bool fields_character_def(call *c, const godot_variant *var, pp_character_def *def)
{
    return read_fields(c, var, "character", CHARACTER_FIELDS, sizeof CHARACTER_FIELDS / sizeof CHARACTER_FIELDS[0],
                       def, NULL, NULL);
}

godot_variant fields_world_dict(const pp_world_def *def)
{
    godot_dictionary d;
    gdn->godot_dictionary_new(&d);
    for (size_t i = 0; i < sizeof WORLD_FIELDS / sizeof WORLD_FIELDS[0]; i++) {
        const field *f = &WORLD_FIELDS[i];
        const char *at = (const char *)def + f->offset;
        godot_variant v;
        switch (f->kind) {
        case F_BOOL: v = gdn_bool(*(const uint32_t *)at != 0); break;
        case F_FLOAT: v = gdn_real(*(const float *)at); break;
        case F_VEC2: v = gdn_vector2(((const pp_vec2 *)at)->x, ((const pp_vec2 *)at)->y); break;
        case F_ENUM: {
            const int32_t k = *(const int32_t *)at;
            int n = 0;
            while (f->names[n])
                n++;
            v = gdn_string(k >= 0 && k < n ? f->names[k] : "unknown");
            break;
        }
        default: v = gdn_int(*(const int32_t *)at); break;
        }
        gdn_dict_put(&d, f->name, v);
    }
    return gdn_dict_variant(&d);
}

/* The options' plane sources, kept until every field is read (the mask needs alpha_threshold). */
typedef struct plane_sources {
    godot_variant mask, weights;
    bool has_mask, has_weights;
} plane_sources;

/* "pivot" sets custom_pivot too; "collision_mask" and "weights" are planes, read once the fields are. */
static int body_special(call *c, const char *key, const godot_variant *value, void *vdef, void *extra)
{
    pp_body_def *def = vdef;
    plane_sources *src = extra;
    if (strcmp(key, "pivot") == 0) {
        def->custom_pivot = 1;
        return 0; /* the table reads the value */
    }
    const bool mask = strcmp(key, "collision_mask") == 0;
    if (!mask && strcmp(key, "weights") != 0)
        return 0;
    bool *has = mask ? &src->has_mask : &src->has_weights;
    godot_variant *keep = mask ? &src->mask : &src->weights;
    if (*has)
        gdn->godot_variant_destroy(keep);
    gdn->godot_variant_new_copy(keep, value);
    *has = true;
    return 1;
}

bool fields_body_def(call *c, const godot_variant *var, pp_body_def *def, body_planes *planes)
{
    *planes = (body_planes){NULL, NULL};
    plane_sources src = {.has_mask = false, .has_weights = false};
    bool good = read_fields(c, var, "options", BODY_FIELDS, sizeof BODY_FIELDS / sizeof BODY_FIELDS[0], def,
                            body_special, &src);
    if (src.has_mask) {
        good = good && pixels_plane(c, &src.mask, "collision_mask", def, true, &planes->mask);
        def->mask = planes->mask;
        gdn->godot_variant_destroy(&src.mask);
    }
    if (src.has_weights) {
        good = good && pixels_plane(c, &src.weights, "weights", def, false, &planes->weights);
        def->weights = planes->weights;
        gdn->godot_variant_destroy(&src.weights);
    }
    return good;
}
