/* The engine side of the Godot 3.2 adapter: the GDNative API tables found at load time,
 * and small helpers that turn variants into C values and C values into variants.
 * Nothing here knows about PhysPix. */
#ifndef PHYSPIX_GDN_H
#define PHYSPIX_GDN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "gdnative_api_structs.h" /* generated from GODOT_API_JSON */

#define GDN_EXPORT __attribute__((visibility("default")))

/* What the engine hands godot_gdnative_init. Not part of gdnative_api.json; this is the
 * layout of Godot 3.2's gdnative.h, and only api_struct and the two report hooks are used. */
typedef struct godot_gdnative_init_options {
    bool in_editor;
    uint64_t core_api_hash;
    uint64_t editor_api_hash;
    uint64_t no_api_hash;
    void (*report_version_mismatch)(const godot_object *library, const char *what,
                                    godot_gdnative_api_version want, godot_gdnative_api_version have);
    void (*report_loading_error)(const godot_object *library, const char *what);
    godot_object *gd_native_library;
    const godot_gdnative_core_api_struct *api_struct;
    const godot_string *active_library_path;
} godot_gdnative_init_options;
_Static_assert(offsetof(godot_gdnative_init_options, api_struct) == 56, "init options layout of Godot 3.2");

/* What the engine hands godot_gdnative_terminate (also from gdnative.h). */
typedef struct godot_gdnative_terminate_options {
    bool in_editor;
} godot_gdnative_terminate_options;

/* Godot 3.2's godot_variant_type values the adapter checks. */
enum {
    GDN_NIL = 0,
    GDN_BOOL = 1,
    GDN_INT = 2,
    GDN_REAL = 3,
    GDN_STRING = 4,
    GDN_VECTOR2 = 5,
    GDN_OBJECT = 17,
    GDN_DICTIONARY = 18,
    GDN_POOL_BYTE_ARRAY = 20,
};

/* The API tables; valid between a successful gdn_bind and godot_gdnative_terminate. */
extern const godot_gdnative_core_api_struct *gdn;       /* core 1.0 */
extern const godot_gdnative_core_1_1_api_struct *gdn11; /* core 1.1: is_instance_valid */
extern const godot_gdnative_core_1_2_api_struct *gdn12; /* core 1.2: class tags */
extern const godot_gdnative_ext_nativescript_api_struct *gdn_ns;

/* Finds core 1.1 and 1.2 along the core's `next` chain and NativeScript by its `type` field;
 * on failure writes why into err and leaves the tables NULL. */
bool gdn_bind(const godot_gdnative_core_api_struct *core, char *err, size_t err_size);
void gdn_unbind(void);

/* Name of a variant's type as GDScript spells it ("int", "Vector2", ...). */
const char *gdn_type_name(const godot_variant *v);

/* Copies a String variant into buf as UTF-8, truncated to buf_size - 1 bytes; returns the whole
 * string's length in bytes, so a result >= buf_size means it was truncated. */
size_t gdn_string_to_utf8(const godot_variant *v, char *buf, size_t buf_size);

/* Reads a Vector2 into two floats. */
void gdn_vector2_read(const godot_variant *v, float *x, float *y);

/* New variants; the caller owns the result (the engine takes it when it is returned). */
godot_variant gdn_nil(void);
godot_variant gdn_bool(bool b);
godot_variant gdn_int(int64_t i);
godot_variant gdn_real(double r);
godot_variant gdn_vector2(float x, float y);
godot_variant gdn_transform2d(float angle, float x, float y);
godot_variant gdn_string(const char *utf8);

/* dict[key] = value, then destroys value: lets a caller build a Dictionary in one line a field. */
void gdn_dict_put(godot_dictionary *dict, const char *key, godot_variant value);
/* array.append(value), then destroys value. */
void gdn_array_put(godot_array *array, godot_variant value);
/* Wraps a Dictionary or an Array in a variant and destroys the original reference. */
godot_variant gdn_dict_variant(godot_dictionary *dict);
godot_variant gdn_array_variant(godot_array *array);

/* obj.method(args...) through a method bind; false (and ret nil) if the call failed. */
bool gdn_call(godot_method_bind *mb, godot_object *obj, const godot_variant **args, int n, godot_variant *ret);

/* Prints an error the way the engine does ("ERROR: function: message", then "At: file:line"). */
void gdn_print_error(const char *function, const char *message, const char *file, int line);

#endif
