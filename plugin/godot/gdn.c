/* The engine side of the Godot 3.2 adapter: binds the GDNative API tables and wraps the
 * handful of variant, string, array and dictionary calls the PhysPixWorld class needs. */
#include "gdn.h"

#include <stdio.h>

const godot_gdnative_core_api_struct *gdn;
const godot_gdnative_core_1_1_api_struct *gdn11;
const godot_gdnative_core_1_2_api_struct *gdn12;
const godot_gdnative_ext_nativescript_api_struct *gdn_ns;

bool gdn_bind(const godot_gdnative_core_api_struct *core, char *err, size_t err_size)
{
    gdn_unbind();
    if (!core || core->type != GDNATIVE_CORE || core->version.major != 1) {
        snprintf(err, err_size, "PhysPix needs the GDNative core API 1.x");
        return false;
    }
    /* Each minor version is its own struct of the functions it added, chained by `next`. */
    const godot_gdnative_core_1_1_api_struct *c11 = NULL;
    const godot_gdnative_core_1_2_api_struct *c12 = NULL;
    for (const godot_gdnative_api_struct *a = (const godot_gdnative_api_struct *)core; a; a = a->next) {
        if (a->version.major == 1 && a->version.minor == 1)
            c11 = (const godot_gdnative_core_1_1_api_struct *)a;
        if (a->version.major == 1 && a->version.minor == 2)
            c12 = (const godot_gdnative_core_1_2_api_struct *)a;
    }
    /* Extensions are found by what they are, not where they sit in the array. */
    const godot_gdnative_ext_nativescript_api_struct *ns = NULL;
    for (unsigned i = 0; i < core->num_extensions; i++)
        if (core->extensions[i]->type == GDNATIVE_EXT_NATIVESCRIPT)
            ns = (const godot_gdnative_ext_nativescript_api_struct *)core->extensions[i];
    if (!c11 || !c12 || !ns) {
        snprintf(err, err_size, "PhysPix needs GDNative core 1.1, 1.2 and NativeScript 1.0 (Godot 3.2 or later)");
        return false;
    }
    gdn = core;
    gdn11 = c11;
    gdn12 = c12;
    gdn_ns = ns;
    return true;
}

void gdn_unbind(void)
{
    gdn = NULL;
    gdn11 = NULL;
    gdn12 = NULL;
    gdn_ns = NULL;
}

const char *gdn_type_name(const godot_variant *v)
{
    static const char *const names[] = {
        "null", "bool", "int", "float", "String", "Vector2", "Rect2", "Vector3", "Transform2D", "Plane",
        "Quat", "AABB", "Basis", "Transform", "Color", "NodePath", "RID", "Object", "Dictionary", "Array",
        "PoolByteArray", "PoolIntArray", "PoolRealArray", "PoolStringArray", "PoolVector2Array",
        "PoolVector3Array", "PoolColorArray",
    };
    const int32_t t = gdn->godot_variant_get_type(v);
    return t >= 0 && t < (int32_t)(sizeof names / sizeof names[0]) ? names[t] : "an unknown type";
}

size_t gdn_string_to_utf8(const godot_variant *v, char *buf, size_t buf_size)
{
    godot_string s = gdn->godot_variant_as_string(v);
    godot_char_string cs = gdn->godot_string_utf8(&s);
    const int n = snprintf(buf, buf_size, "%s", gdn->godot_char_string_get_data(&cs));
    gdn->godot_char_string_destroy(&cs);
    gdn->godot_string_destroy(&s);
    return n < 0 ? 0 : (size_t)n;
}

void gdn_vector2_read(const godot_variant *v, float *x, float *y)
{
    const godot_vector2 g = gdn->godot_variant_as_vector2(v);
    *x = gdn->godot_vector2_get_x(&g);
    *y = gdn->godot_vector2_get_y(&g);
}

godot_variant gdn_nil(void)
{
    godot_variant r;
    gdn->godot_variant_new_nil(&r);
    return r;
}

godot_variant gdn_bool(bool b)
{
    godot_variant r;
    gdn->godot_variant_new_bool(&r, b);
    return r;
}

godot_variant gdn_int(int64_t i)
{
    godot_variant r;
    gdn->godot_variant_new_int(&r, i);
    return r;
}

godot_variant gdn_real(double x)
{
    godot_variant r;
    gdn->godot_variant_new_real(&r, x);
    return r;
}

godot_variant gdn_vector2(float x, float y)
{
    godot_vector2 g;
    gdn->godot_vector2_new(&g, x, y);
    godot_variant r;
    gdn->godot_variant_new_vector2(&r, &g);
    return r;
}

godot_variant gdn_transform2d(float angle, float x, float y)
{
    godot_vector2 origin;
    gdn->godot_vector2_new(&origin, x, y);
    godot_transform2d t;
    gdn->godot_transform2d_new(&t, angle, &origin);
    godot_variant r;
    gdn->godot_variant_new_transform2d(&r, &t);
    return r;
}

godot_variant gdn_string(const char *utf8)
{
    godot_string s = gdn->godot_string_chars_to_utf8(utf8);
    godot_variant r;
    gdn->godot_variant_new_string(&r, &s);
    gdn->godot_string_destroy(&s);
    return r;
}

void gdn_dict_put(godot_dictionary *dict, const char *key, godot_variant value)
{
    godot_variant k = gdn_string(key);
    gdn->godot_dictionary_set(dict, &k, &value);
    gdn->godot_variant_destroy(&k);
    gdn->godot_variant_destroy(&value);
}

void gdn_array_put(godot_array *array, godot_variant value)
{
    gdn->godot_array_append(array, &value);
    gdn->godot_variant_destroy(&value);
}

godot_variant gdn_dict_variant(godot_dictionary *dict)
{
    godot_variant r;
    gdn->godot_variant_new_dictionary(&r, dict);
    gdn->godot_dictionary_destroy(dict);
    return r;
}

godot_variant gdn_array_variant(godot_array *array)
{
    godot_variant r;
    gdn->godot_variant_new_array(&r, array);
    gdn->godot_array_destroy(array);
    return r;
}

bool gdn_call(godot_method_bind *mb, godot_object *obj, const godot_variant **args, int n, godot_variant *ret)
{
    godot_variant_call_error e = {0};
    *ret = gdn->godot_method_bind_call(mb, obj, args, n, &e);
    return e.error == 0;
}

void gdn_print_error(const char *function, const char *message, const char *file, int line)
{
    gdn->godot_print_error(message, function, file, line);
}
