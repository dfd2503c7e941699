/* A world's settings as JSON text, the plugin's stand-in for a dictionary: the keys of a scene file's "world"
 * object ("preset" first, then any pp_world_def field by name), read into a def and written back. The field
 * list is generated from plugin/api/physpix_api.json (api/def_fields.h). The only plugin file with cJSON. */
#include "plugin.h"

#include "api/def_fields.h"

#include <cjson/cJSON.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum kind { K_BOOL, K_INT, K_FLOAT, K_VEC2, K_ENUM } kind;

typedef struct field {
    const char *name;
    kind kind;
    size_t offset;
    const char *const *names; /* K_ENUM: the values' names, indexed by value, NULL-terminated */
} field;

#define FIELD(name_, KIND, names_) {#name_, K_##KIND, offsetof(pp_world_def, name_), names_},
static const field FIELDS[] = {PP_WORLD_DEF_FIELDS(FIELD)};
#undef FIELD
enum { FIELD_COUNT = (int)(sizeof FIELDS / sizeof FIELDS[0]) };

/* `"a", "b" or "c"` of a names array (skipping the "" of values with no name). */
static void name_list(const char *const *names, char *out, size_t size)
{
    int n = 0, k = 0;
    while (names[n])
        n++;
    out[0] = '\0';
    for (int i = 0; i < n; i++)
        if (names[i][0]) {
            const char *sep = k == 0 ? "" : (i + 1 < n ? ", " : " or ");
            snprintf(out + strlen(out), size - strlen(out), "%s\"%s\"", sep, names[i]);
            k++;
        }
}

/* A number a float holds: finite and within ±FLT_MAX. */
static int float_value(const cJSON *it, float *out)
{
    if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble) || fabs(it->valuedouble) > FLT_MAX)
        return 0;
    *out = (float)it->valuedouble;
    return 1;
}

static int enum_value(const cJSON *it, const char *const *names, int32_t *out)
{
    for (int32_t i = 0; cJSON_IsString(it) && names[i]; i++)
        if (names[i][0] && strcmp(it->valuestring, names[i]) == 0) {
            *out = i;
            return 1;
        }
    return 0;
}

/* Writes one value into the def; 0 with why set when it does not fit the field. */
static int read_field(const field *f, const cJSON *it, pp_world_def *def, char *why, size_t why_size)
{
    char *at = (char *)def + f->offset;
    const char *want = NULL;
    char names[160];
    switch (f->kind) {
    case K_BOOL:
        if (cJSON_IsBool(it))
            *(uint32_t *)at = cJSON_IsTrue(it) ? 1u : 0u;
        else
            want = "true or false";
        break;
    case K_INT:
        if (cJSON_IsNumber(it) && it->valuedouble == floor(it->valuedouble) && fabs(it->valuedouble) <= INT32_MAX)
            *(int32_t *)at = (int32_t)it->valuedouble;
        else
            want = "an integer";
        break;
    case K_FLOAT:
        if (!float_value(it, (float *)at))
            want = "a finite number (within a float's range)";
        break;
    case K_VEC2: {
        pp_vec2 *v = (pp_vec2 *)at;
        if (!cJSON_IsArray(it) || cJSON_GetArraySize(it) != 2 || !float_value(cJSON_GetArrayItem(it, 0), &v->x) ||
            !float_value(cJSON_GetArrayItem(it, 1), &v->y))
            want = "[x, y], two finite numbers";
        break;
    }
    case K_ENUM:
        if (!enum_value(it, f->names, (int32_t *)at)) {
            name_list(f->names, names, sizeof names);
            want = names;
        }
        break;
    }
    if (want)
        snprintf(why, why_size, "settings.%s: expected %s", f->name, want);
    return want == NULL;
}

static const field *field_named(const char *name)
{
    for (int i = 0; i < FIELD_COUNT; i++)
        if (strcmp(FIELDS[i].name, name) == 0)
            return &FIELDS[i];
    return NULL;
}

/* The def the "preset" key starts from (the default one without it); 0 with why set for a bad preset. */
static int start_def(const cJSON *root, pp_world_def *def, char *why, size_t why_size)
{
    const cJSON *p = cJSON_GetObjectItemCaseSensitive(root, "preset");
    int32_t preset = PP_PRESET_BALANCED;
    if (p && !enum_value(p, pp_preset_names, &preset)) {
        char names[96];
        name_list(pp_preset_names, names, sizeof names);
        snprintf(why, why_size, "settings.preset: expected %s", names);
        return 0;
    }
    *def = pp_world_def_preset((pp_preset)preset);
    return 1;
}

/* Every key but "preset" into the def, refusing unknown and repeated keys. */
static int read_keys(const cJSON *root, pp_world_def *def, char *why, size_t why_size)
{
    for (const cJSON *it = root->child; it; it = it->next) {
        for (const cJSON *before = root->child; before != it; before = before->next)
            if (strcmp(before->string, it->string) == 0) {
                snprintf(why, why_size, "settings.%s: given twice", it->string);
                return 0;
            }
        if (strcmp(it->string, "preset") == 0)
            continue;
        const field *f = field_named(it->string);
        if (!f) {
            snprintf(why, why_size, "settings.%s: unknown key (keys are \"preset\" and pp_world_def's fields)",
                     it->string);
            return 0;
        }
        if (!read_field(f, it, def, why, why_size))
            return 0;
    }
    return 1;
}

pp_status settings_read(const char *json, pp_world_def *out, char *why, size_t why_size)
{
    cJSON *root = cJSON_Parse(json);
    pp_status st = PP_ERR_INVALID_ARGUMENT;
    pp_world_def def;
    if (!root)
        snprintf(why, why_size, "settings: invalid JSON (expected an object such as {\"gravity\": [0, 0]})");
    else if (!cJSON_IsObject(root))
        snprintf(why, why_size, "settings: expected a JSON object such as {\"gravity\": [0, 0]}");
    else if (start_def(root, &def, why, why_size) && read_keys(root, &def, why, why_size))
        st = PP_OK;
    cJSON_Delete(root);
    if (st == PP_OK)
        *out = def;
    return st;
}

static cJSON *field_json(const field *f, const pp_world_def *def)
{
    const char *at = (const char *)def + f->offset;
    switch (f->kind) {
    case K_BOOL: return cJSON_CreateBool(*(const uint32_t *)at != 0);
    case K_INT: return cJSON_CreateNumber(*(const int32_t *)at);
    case K_FLOAT: return cJSON_CreateNumber(*(const float *)at);
    case K_VEC2: {
        const float xy[2] = {((const pp_vec2 *)at)->x, ((const pp_vec2 *)at)->y};
        return cJSON_CreateFloatArray(xy, 2);
    }
    case K_ENUM: {
        const int32_t v = *(const int32_t *)at;
        int n = 0;
        while (f->names[n])
            n++;
        return cJSON_CreateString(v >= 0 && v < n ? f->names[v] : "unknown");
    }
    }
    return NULL;
}

void settings_ret(const pp_world_def *def, pp_variant *ret)
{
    cJSON *root = cJSON_CreateObject();
    int whole = root != NULL;
    for (int i = 0; whole && i < FIELD_COUNT; i++) {
        cJSON *v = field_json(&FIELDS[i], def);
        whole = v && cJSON_AddItemToObject(root, FIELDS[i].name, v);
        if (!whole)
            cJSON_Delete(v);
    }
    char *text = whole ? cJSON_PrintUnformatted(root) : NULL;
    cJSON_Delete(root);
    if (text)
        ret_string(ret, text);
    else
        ret_error(ret, PP_ERR_OUT_OF_MEMORY, "PhysPixWorld.get_settings: out of memory writing the settings");
    cJSON_free(text);
}
