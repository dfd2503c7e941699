/* The JSON layer shared by scene files (scene.c) and snapshots (snapshot_write.c, snapshot_read.c): a reader
 * that names the JSON path of every bad value and PNG bitmaps named by a file's keys (scene_json.c), and field
 * tables that read a struct and write it back exactly (scene_fields.c). Only these files see cJSON. */
#ifndef PP_SCENE_JSON_H
#define PP_SCENE_JSON_H

#include "physpix.h"

#include <cjson/cJSON.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Largest integer a JSON number (a double) holds exactly: 2^53. */
#define JSON_MAX_EXACT_INT 9007199254740992LL

/* Who is reading which file: every message starts "<fn>: '<file>': ". The PNG paths a file names are read
 * only from beneath its folder (include/physpix.h, above pp_world_load_scene). */
typedef struct json_ctx {
    const char *fn;
    const char *file;
    size_t dir_len;    /* length of file's directory prefix, '/' included; 0 when it has none */
    int dir_fd;        /* that folder, opened by parse_json (-1 before); json_done closes it */
    bool confine_file; /* the file itself must lie beneath its folder too (a snapshot's world.json) */
} json_ctx;

typedef enum num_rule { NUM_FINITE, NUM_POSITIVE, NUM_NONNEG, NUM_UNIT } num_rule;

/* Fail with "<fn>: '<file>': <where>.<key>: <reason>"; where or key may be empty. */
pp_status json_fail(const json_ctx *c, pp_status st, const char *where, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
/* Re-raise the last library failure under a JSON path; INVALID_ARGUMENT becomes FORMAT. */
pp_status json_fail_from_last(const json_ctx *c, pp_status st, const char *where, const char *key);

/* Readers of one optional key: absent leaves *out as it was; a bad value fails with its path. */
pp_status read_float(const json_ctx *c, const cJSON *obj, const char *where, const char *key, num_rule r, float *out);
pp_status read_double(const json_ctx *c, const cJSON *obj, const char *where, const char *key, num_rule r,
                      double *out);
pp_status read_vec2(const json_ctx *c, const cJSON *obj, const char *where, const char *key, pp_vec2 *out);
pp_status read_int(const json_ctx *c, const cJSON *obj, const char *where, const char *key, int64_t lo, int64_t hi,
                   int64_t *out);
pp_status read_bool(const json_ctx *c, const cJSON *obj, const char *where, const char *key, uint32_t *out);
pp_status read_string(const json_ctx *c, const cJSON *obj, const char *where, const char *key, const char **out);
pp_status read_enum(const json_ctx *c, const cJSON *obj, const char *where, const char *key, const char *const *names,
                    int32_t *out);
pp_status read_section(const json_ctx *c, const cJSON *obj, const char *where, const char *key, bool array,
                       const cJSON **out);
/* Whether it is a number holding an integer in lo..hi, which it stores in *out; no failure recorded. */
bool json_int(const cJSON *it, int64_t lo, int64_t hi, int64_t *out);

typedef enum field_kind { FK_FLOAT, FK_DOUBLE, FK_VEC2, FK_BOOL, FK_INT, FK_STRIDE, FK_ENUM } field_kind;

typedef struct field {
    const char *key;
    field_kind kind;
    size_t offset;
    size_t size;              /* FK_INT: 4 (int32_t/uint32_t) or 8 (uint64_t) */
    num_rule rule;            /* FK_FLOAT, FK_DOUBLE */
    int64_t lo, hi;           /* FK_INT */
    const char *const *names; /* FK_ENUM */
} field;

extern const field world_fields[], body_fields[], camera_fields[], edit_fields[], joint_fields[];
/* pp_joint_type by index ("" at 0, which is none). */
extern const char *const joint_type_names[];

/* Read every field of a table present in obj into the struct at s; absent fields keep their value. */
pp_status read_fields(const json_ctx *c, const cJSON *obj, const char *where, const field *t, void *s);
/* Fail on keys outside the table and `extra` (NULL-terminated), and on a key given twice. */
pp_status check_keys(const json_ctx *c, const cJSON *obj, const char *where, const field *t, const char *const *extra);
/* A raw number item of the shortest text that reads back to the same float (single) or double. */
cJSON *json_number(double v, bool single);
/* A new object of a table's fields of s, for printing (its numbers are raw); NULL without memory. */
cJSON *fields_to_json(const field *t, const void *s);

pp_status parse_world_def(const json_ctx *c, const cJSON *obj, const char *where, pp_world_def *d);
cJSON *world_def_to_json(const pp_world_def *d);
pp_status parse_camera(const json_ctx *c, const cJSON *obj, const char *where, pp_camera *cam);
cJSON *camera_to_json(const pp_camera *cam);
/* A body's settings over *d (the caller checks keys); "pivot" sets custom_pivot. */
pp_status parse_body_settings(const json_ctx *c, const cJSON *obj, const char *where, pp_body_def *d);
cJSON *body_settings_to_json(const pp_body_def *d);
/* A joint's "type" (required) and settings over its type's defaults; keys outside joint_fields must be in extra
 * (NULL-terminated, "type" among them); the caller reads its bodies. */
pp_status parse_joint_def(const json_ctx *c, const cJSON *obj, const char *where, const char *const *extra,
                          pp_joint_def *d);
/* A timed edit's fields, without a weight when it erases; the caller adds its body. */
cJSON *edit_to_json(const pp_timed_edit *e);

/* The planes of one body's bitmap, owned until the body is made. */
typedef struct bitmap {
    int32_t width, height;
    uint8_t *rgba, *mask, *weights;
} bitmap;

void bitmap_free(bitmap *b);
/* The bitmap of obj's "sprite", "mask", "weights" (PNG paths beneath the file's folder) or "box". */
pp_status parse_bitmap(const json_ctx *c, const cJSON *obj, const char *where, bitmap *b);

/* Open the file's folder, then read and parse the whole file; a syntax error names its line. */
pp_status parse_json(json_ctx *c, cJSON **root);
/* Free what parse_json made: the tree (may be NULL) and the folder's descriptor. */
void json_done(json_ctx *c, cJSON *root);

#endif
