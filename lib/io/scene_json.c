/* The JSON reading layer shared by scene files and snapshots (see scene_json.h): the path-naming reader
 * and key checks, exact number printing, PNG bitmaps and whole-file parsing. The field tables and the
 * settings' parsers and writers are scene_fields.c's. */
#include "alloc.h"
#include "files.h"
#include "image.h"
#include "scene_json.h"
#include "status.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- reader layer ------------------------------------------------------------------------- */

pp_status json_fail(const json_ctx *c, pp_status st, const char *where, const char *key, const char *fmt, ...)
{
    char reason[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(reason, sizeof reason, fmt, ap);
    va_end(ap);
    const bool dot = where[0] && key && key[0];
    return pp_fail(st, "%s: '%s': %s%s%s: %s", c->fn, c->file, where, dot ? "." : "", key ? key : "", reason);
}

/* Re-raise the failure of a library call under a JSON path, without the call's own "fn: " prefix.
 * A rejected argument is the file's fault, so INVALID_ARGUMENT becomes FORMAT. */
pp_status json_fail_from_last(const json_ctx *c, pp_status st, const char *where, const char *key)
{
    char msg[512];
    const char *last = pp_last_error(), *colon = strstr(last, ": ");
    snprintf(msg, sizeof msg, "%s", colon ? colon + 2 : last);
    /* A file's bad value or a body it names that is not there is a fault of the file. */
    const bool files_fault = st == PP_ERR_INVALID_ARGUMENT || st == PP_ERR_INVALID_HANDLE;
    return json_fail(c, files_fault ? PP_ERR_FORMAT : st, where, key, "%s", msg);
}


static const char *const num_rule_text[] = {
    "expected a finite number", "expected a number > 0", "expected a number ≥ 0", "expected a number in 0..1"};

static bool num_rule_ok(double v, num_rule r)
{
    switch (r) {
    case NUM_POSITIVE: return v > 0;
    case NUM_NONNEG: return v >= 0;
    case NUM_UNIT: return v >= 0 && v <= 1;
    default: return true;
    }
}

/* A JSON number that is finite and, stored as a float, still finite and within the rule. */
static bool json_float(const cJSON *it, num_rule r, float *out)
{
    if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble) || fabs(it->valuedouble) > FLT_MAX)
        return false;
    const float f = (float)it->valuedouble;
    if (!num_rule_ok(f, r))
        return false;
    *out = f;
    return true;
}

pp_status read_float(const json_ctx *c, const cJSON *obj, const char *where, const char *key, num_rule r,
                            float *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (it && !json_float(it, r, out))
        return json_fail(c, PP_ERR_FORMAT, where, key, "%s", num_rule_text[r]);
    return PP_OK;
}

pp_status read_double(const json_ctx *c, const cJSON *obj, const char *where, const char *key, num_rule r,
                             double *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!it)
        return PP_OK;
    if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble) || !num_rule_ok(it->valuedouble, r))
        return json_fail(c, PP_ERR_FORMAT, where, key, "%s", num_rule_text[r]);
    *out = it->valuedouble;
    return PP_OK;
}

/* [x, y]: exactly two finite numbers. */
pp_status read_vec2(const json_ctx *c, const cJSON *obj, const char *where, const char *key, pp_vec2 *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!it)
        return PP_OK;
    pp_vec2 v;
    if (!cJSON_IsArray(it) || cJSON_GetArraySize(it) != 2 || !json_float(cJSON_GetArrayItem(it, 0), NUM_FINITE, &v.x) ||
        !json_float(cJSON_GetArrayItem(it, 1), NUM_FINITE, &v.y))
        return json_fail(c, PP_ERR_FORMAT, where, key, "expected [x, y], two finite numbers");
    *out = v;
    return PP_OK;
}

bool json_int(const cJSON *it, int64_t lo, int64_t hi, int64_t *out)
{
    if (!cJSON_IsNumber(it))
        return false;
    const double v = it->valuedouble;
    if (!(v >= (double)lo && v <= (double)hi) || v != floor(v))
        return false;
    *out = (int64_t)v;
    return true;
}

pp_status read_int(const json_ctx *c, const cJSON *obj, const char *where, const char *key, int64_t lo,
                          int64_t hi, int64_t *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (it && !json_int(it, lo, hi, out))
        return json_fail(c, PP_ERR_FORMAT, where, key, "expected an integer in %lld..%lld", (long long)lo,
                         (long long)hi);
    return PP_OK;
}

pp_status read_bool(const json_ctx *c, const cJSON *obj, const char *where, const char *key, uint32_t *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!it)
        return PP_OK;
    if (!cJSON_IsBool(it))
        return json_fail(c, PP_ERR_FORMAT, where, key, "expected true or false");
    *out = cJSON_IsTrue(it) ? 1u : 0u;
    return PP_OK;
}

pp_status read_string(const json_ctx *c, const cJSON *obj, const char *where, const char *key,
                             const char **out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!it)
        return PP_OK;
    if (!cJSON_IsString(it) || !it->valuestring[0])
        return json_fail(c, PP_ERR_FORMAT, where, key, "expected a non-empty string");
    *out = it->valuestring;
    return PP_OK;
}

/* An enum by name; names[v] is the name of value v ("" where v has none), NULL-terminated. */
pp_status read_enum(const json_ctx *c, const cJSON *obj, const char *where, const char *key,
                           const char *const *names, int32_t *out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!it)
        return PP_OK;
    for (int32_t v = 0; cJSON_IsString(it) && names[v]; v++)
        if (names[v][0] && strcmp(names[v], it->valuestring) == 0) {
            *out = v;
            return PP_OK;
        }
    char list[160] = "";
    for (int32_t v = 0; names[v]; v++)
        if (names[v][0])
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", list[0] ? ", " : "", names[v]);
    if (!cJSON_IsString(it))
        return json_fail(c, PP_ERR_FORMAT, where, key, "expected a string, one of %s", list);
    return json_fail(c, PP_ERR_FORMAT, where, key, "unknown value '%s' (expected one of %s)", it->valuestring, list);
}

/* An optional section: absent is fine, present must be an array or an object as asked. */
pp_status read_section(const json_ctx *c, const cJSON *obj, const char *where, const char *key, bool array,
                              const cJSON **out)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(obj, key);
    *out = NULL;
    if (it && (array ? !cJSON_IsArray(it) : !cJSON_IsObject(it)))
        return json_fail(c, PP_ERR_FORMAT, where, key, array ? "expected an array" : "expected an object");
    *out = it;
    return PP_OK;
}

/* Unknown keys are typos; a key twice is ambiguous. Allowed: the table's keys and `extra` (NULL-terminated). */
pp_status check_keys(const json_ctx *c, const cJSON *obj, const char *where, const field *t,
                            const char *const *extra)
{
    for (const cJSON *it = obj->child; it; it = it->next) {
        bool known = false;
        for (const field *f = t; f && f->key && !known; f++)
            known = strcmp(f->key, it->string) == 0;
        for (const char *const *x = extra; x && *x && !known; x++)
            known = strcmp(*x, it->string) == 0;
        if (!known)
            return json_fail(c, PP_ERR_FORMAT, where, it->string, "unknown key");
        for (const cJSON *o = obj->child; o != it; o = o->next)
            if (strcmp(o->string, it->string) == 0)
                return json_fail(c, PP_ERR_FORMAT, where, it->string, "duplicate key");
    }
    return PP_OK;
}

/* ---- writer: exact numbers ------------------------------------------------------------------- */

/* A number as the shortest text that reads back to the same float (or double): cJSON's own printer
 * accepts a 15-digit text within an epsilon of the value, which loses the last bit of a double. Raw items
 * print as they are, so an emitted object is for printing, not for reading in memory. */
cJSON *json_number(double v, bool single)
{
    char text[40];
    for (int digits = single ? 6 : 15; digits <= 17; digits++) {
        snprintf(text, sizeof text, "%.*g", digits, v);
        const double back = strtod(text, NULL);
        if (single ? (float)back == (float)v : back == v)
            break;
    }
    return cJSON_CreateRaw(text);
}

/* ---- bitmaps --------------------------------------------------------------------------------- */

void bitmap_free(bitmap *b)
{
    pp_free(b->rgba);
    pp_free(b->mask);
    pp_free(b->weights);
}

/* One message whatever the reason (missing, unreadable, not a regular file, outside the folder), so that a
 * file cannot probe what lies outside its folder. path is the file named, or NULL for the file itself. */
static pp_status cannot_open(const json_ctx *c, const char *where, const char *key, const char *path)
{
    static const char why[] = "missing, unreadable, not a regular file, or outside";
    const int n = c->dir_len ? (int)c->dir_len : 2;
    const char *folder = c->dir_len ? c->file : "./";
    if (!path)
        return pp_fail(PP_ERR_IO, "%s: '%s': cannot open: %s '%.*s'", c->fn, c->file, why, n, folder);
    return json_fail(c, PP_ERR_IO, where, key, "cannot open '%s': %s '%.*s'", path, why, n, folder);
}

/* Decode the PNG named by obj[key], a path beneath the file's folder. */
static pp_status load_png(const json_ctx *c, const cJSON *obj, const char *where, const char *key, uint8_t **rgba,
                          int32_t *w, int32_t *h)
{
    const char *name = NULL;
    pp_status st = read_string(c, obj, where, key, &name);
    if (st)
        return st;
    /* The path as the host would write it, for messages: an absolute name as it is. */
    const size_t dir = name[0] == '/' ? 0 : c->dir_len;
    char *path = pp_malloc(dir + strlen(name) + 1);
    if (!path)
        return json_fail(c, PP_ERR_OUT_OF_MEMORY, where, key, "no memory");
    memcpy(path, c->file, dir);
    strcpy(path + dir, name);
    const int fd = files_open_beneath(c->dir_fd, name);
    if (fd < 0) {
        st = cannot_open(c, where, key, path);
    } else {
        st = image_load_fd(fd, "pp_image_load", path, rgba, w, h);
        close(fd);
        if (st)
            st = json_fail_from_last(c, st, where, key);
    }
    pp_free(path);
    return st;
}

/* A second plane must cover the bitmap exactly. */
static pp_status check_plane_size(const json_ctx *c, const char *where, const char *key, int32_t w, int32_t h,
                                  const bitmap *b, const char *what)
{
    if (w == b->width && h == b->height)
        return PP_OK;
    return json_fail(c, PP_ERR_FORMAT, where, key, "%dx%d px, but the %s is %dx%d px", (int)w, (int)h, what,
                     (int)b->width, (int)b->height);
}

/* "box": [w, h], a solid rectangle. */
static pp_status load_box(const json_ctx *c, const cJSON *box, const char *where, bitmap *b)
{
    int64_t w, h;
    if (!cJSON_IsArray(box) || cJSON_GetArraySize(box) != 2 ||
        !json_int(cJSON_GetArrayItem(box, 0), 1, PP_MAX_BITMAP_SIDE, &w) ||
        !json_int(cJSON_GetArrayItem(box, 1), 1, PP_MAX_BITMAP_SIDE, &h))
        return json_fail(c, PP_ERR_FORMAT, where, "box", "expected [width, height], integers in 1..%d",
                         PP_MAX_BITMAP_SIDE);
    if (w * h > PP_MAX_BITMAP_AREA)
        return json_fail(c, PP_ERR_LIMIT, where, "box", "%lldx%lld px is over PP_MAX_BITMAP_AREA (%d)", (long long)w,
                         (long long)h, PP_MAX_BITMAP_AREA);
    if (!(b->mask = pp_malloc((size_t)(w * h))))
        return json_fail(c, PP_ERR_OUT_OF_MEMORY, where, "box", "no memory for %lldx%lld px", (long long)w,
                         (long long)h);
    memset(b->mask, 1, (size_t)(w * h));
    b->width = (int32_t)w, b->height = (int32_t)h;
    return PP_OK;
}

/* "mask": solid where red ≥ 128 and alpha ≥ 128. */
static pp_status load_mask(const json_ctx *c, const cJSON *obj, const char *where, bitmap *b)
{
    uint8_t *px = NULL;
    int32_t w, h;
    pp_status st = load_png(c, obj, where, "mask", &px, &w, &h);
    if (st == PP_OK && b->rgba)
        st = check_plane_size(c, where, "mask", w, h, b, "sprite");
    if (st == PP_OK && !(b->mask = pp_malloc((size_t)w * (size_t)h)))
        st = json_fail(c, PP_ERR_OUT_OF_MEMORY, where, "mask", "no memory");
    if (st == PP_OK) {
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
            b->mask[i] = px[4 * i] >= 128 && px[4 * i + 3] >= 128;
        b->width = w, b->height = h;
    }
    pp_free(px);
    return st;
}

/* "weights": the red channel is each pixel's weight. */
static pp_status load_weights(const json_ctx *c, const cJSON *obj, const char *where, bitmap *b)
{
    uint8_t *px = NULL;
    int32_t w, h;
    pp_status st = load_png(c, obj, where, "weights", &px, &w, &h);
    if (st == PP_OK)
        st = check_plane_size(c, where, "weights", w, h, b, "bitmap");
    if (st == PP_OK && !(b->weights = pp_malloc((size_t)w * (size_t)h)))
        st = json_fail(c, PP_ERR_OUT_OF_MEMORY, where, "weights", "no memory");
    if (st == PP_OK)
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
            b->weights[i] = px[4 * i];
    pp_free(px);
    return st;
}

/* The bitmap from "sprite", "mask", "weights" and "box"; on failure the caller frees what was loaded. */
pp_status parse_bitmap(const json_ctx *c, const cJSON *obj, const char *where, bitmap *b)
{
    const bool sprite = cJSON_GetObjectItemCaseSensitive(obj, "sprite") != NULL;
    const bool mask = cJSON_GetObjectItemCaseSensitive(obj, "mask") != NULL;
    const cJSON *box = cJSON_GetObjectItemCaseSensitive(obj, "box");
    if (box && (sprite || mask))
        return json_fail(c, PP_ERR_FORMAT, where, "box", "cannot be combined with sprite or mask");
    if (!box && !sprite && !mask)
        return json_fail(c, PP_ERR_FORMAT, where, NULL, "needs a bitmap: sprite, mask or box");
    pp_status st = box ? load_box(c, box, where, b) : PP_OK;
    if (st == PP_OK && sprite)
        st = load_png(c, obj, where, "sprite", &b->rgba, &b->width, &b->height);
    if (st == PP_OK && mask)
        st = load_mask(c, obj, where, b);
    if (st == PP_OK && cJSON_GetObjectItemCaseSensitive(obj, "weights"))
        st = load_weights(c, obj, where, b);
    return st;
}

/* ---- the file ------------------------------------------------------------------------------------ */

/* The whole file, NUL-terminated; LIMIT past PP_MAX_SCENE_BYTES, from its size before reading. */
static pp_status read_text(const json_ctx *c, char **out, size_t *len)
{
    const char *leaf = c->file + c->dir_len;
    const int fd = c->confine_file ? files_open_beneath(c->dir_fd, leaf) : files_open_regular(c->dir_fd, leaf);
    FILE *f = fd >= 0 ? fdopen(fd, "rb") : NULL;
    if (!f) {
        const int err = errno;
        if (fd >= 0)
            close(fd);
        return c->confine_file ? cannot_open(c, "", NULL, NULL)
                               : pp_fail(PP_ERR_IO, "%s: '%s': cannot open: %s", c->fn, c->file, files_strerror(err));
    }
    struct stat sb;
    if (fstat(fileno(f), &sb) == 0 && sb.st_size > PP_MAX_SCENE_BYTES) {
        fclose(f);
        return pp_fail(PP_ERR_LIMIT, "%s: '%s' is %lld bytes, over PP_MAX_SCENE_BYTES (%d)", c->fn, c->file,
                       (long long)sb.st_size, PP_MAX_SCENE_BYTES);
    }
    size_t n = 0, cap = 0;
    char *buf = NULL;
    pp_status st = PP_OK;
    for (;;) {
        if (n + 1 >= cap) {
            cap = cap ? 2 * cap : 1 << 16;
            char *p = pp_realloc(buf, cap);
            if (!p) {
                st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: '%s': no memory for %zu bytes", c->fn, c->file, cap);
                break;
            }
            buf = p;
        }
        const size_t got = fread(buf + n, 1, cap - 1 - n, f);
        n += got;
        if (n > PP_MAX_SCENE_BYTES) {
            st = pp_fail(PP_ERR_LIMIT, "%s: '%s' is over PP_MAX_SCENE_BYTES (%d)", c->fn, c->file, PP_MAX_SCENE_BYTES);
            break;
        }
        if (got == 0) {
            if (ferror(f))
                st = pp_fail(PP_ERR_IO, "%s: '%s': cannot read: %s", c->fn, c->file, strerror(errno));
            break;
        }
    }
    fclose(f);
    if (st) {
        pp_free(buf);
        return st;
    }
    buf[n] = '\0';
    *out = buf;
    *len = n;
    return PP_OK;
}

/* Open the folder, then parse the file from it; a syntax error names its line. */
pp_status parse_json(json_ctx *c, cJSON **root)
{
    *root = NULL;
    if ((c->dir_fd = files_open_folder(c->file, c->dir_len)) < 0)
        return c->confine_file ? cannot_open(c, "", NULL, NULL)
                               : pp_fail(PP_ERR_IO, "%s: '%s': cannot open: %s", c->fn, c->file, files_strerror(errno));
    char *text = NULL;
    size_t len = 0;
    pp_status st = read_text(c, &text, &len);
    if (st)
        return st;
    const char *end = NULL;
    *root = cJSON_ParseWithLengthOpts(text, len + 1, &end, 1);
    /* The parser stops at a NUL inside the file too: that is an error there. */
    if (!*root || end != text + len) {
        int line = 1;
        for (const char *p = text; end && p < end; p++)
            line += *p == '\n';
        st = pp_fail(PP_ERR_FORMAT, "%s: '%s': line %d: invalid JSON", c->fn, c->file, line);
        cJSON_Delete(*root);
        *root = NULL;
    }
    pp_free(text);
    return st;
}

void json_done(json_ctx *c, cJSON *root)
{
    cJSON_Delete(root);
    if (c->dir_fd >= 0)
        close(c->dir_fd);
    c->dir_fd = -1;
}
