/* Pixels between Godot and PhysPix: bodies from an Image or a Texture of any format (converted to RGBA8 on a
 * copy, the caller's left as it was), and a body's mask and look read out as PoolByteArrays and written in.
 * A Texture with no readable image is refused with the reason, never made into a body of the wrong pixels. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "adapter.h"

/* Image.FORMAT_RGBA8 in Godot 3.2. */
#define IMAGE_FORMAT_RGBA8 5

/* Engine classes and methods, looked up once at load. */
static struct {
    void *image_tag, *texture_tag, *image_texture_tag;
    godot_method_bind *get_width, *get_height, *get_format, *get_data, *convert, *duplicate, *is_compressed,
        *decompress, *texture_get_data, *get_path;
} api;

static void *class_tag(const char *name)
{
    godot_string_name n;
    gdn->godot_string_name_new_data(&n, name);
    void *tag = gdn12->godot_get_class_tag(&n);
    gdn->godot_string_name_destroy(&n);
    return tag;
}

bool pixels_bind(char *err, size_t err_size)
{
    api.image_tag = class_tag("Image");
    api.texture_tag = class_tag("Texture");
    api.image_texture_tag = class_tag("ImageTexture");
    api.get_width = gdn->godot_method_bind_get_method("Image", "get_width");
    api.get_height = gdn->godot_method_bind_get_method("Image", "get_height");
    api.get_format = gdn->godot_method_bind_get_method("Image", "get_format");
    api.get_data = gdn->godot_method_bind_get_method("Image", "get_data");
    api.convert = gdn->godot_method_bind_get_method("Image", "convert");
    api.is_compressed = gdn->godot_method_bind_get_method("Image", "is_compressed");
    api.decompress = gdn->godot_method_bind_get_method("Image", "decompress");
    api.duplicate = gdn->godot_method_bind_get_method("Resource", "duplicate");
    api.get_path = gdn->godot_method_bind_get_method("Resource", "get_path");
    api.texture_get_data = gdn->godot_method_bind_get_method("Texture", "get_data");
    void *const all[] = {api.image_tag, api.texture_tag, api.image_texture_tag, api.get_width, api.get_height,
                         api.get_format, api.get_data, api.convert, api.is_compressed, api.decompress, api.duplicate,
                         api.get_path, api.texture_get_data};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        if (!all[i]) {
            snprintf(err, err_size, "the engine lacks an Image, Texture or Resource method PhysPix reads images with");
            return false;
        }
    return true;
}

static bool is_a(godot_object *object, void *tag)
{
    return gdn12->godot_object_cast_to(object, tag) != NULL;
}

bool pixels_is_image_or_texture(godot_object *object)
{
    return is_a(object, api.image_tag) || is_a(object, api.texture_tag);
}

/* object.<method>() into *ret (the caller destroys it); false if the call failed. */
static bool call0(godot_method_bind *mb, godot_object *object, godot_variant *ret)
{
    return gdn_call(mb, object, NULL, 0, ret);
}

/* object.<getter>() as an int, -1 if the call failed. */
static int64_t get_int(godot_object *object, godot_method_bind *getter)
{
    godot_variant v;
    const int64_t r = call0(getter, object, &v) ? gdn->godot_variant_as_int(&v) : -1;
    gdn->godot_variant_destroy(&v);
    return r;
}

/* Where an ImageTexture's image came from. One loaded from an image file has no image of its own under
 * godot3-server, only an 8×8 placeholder: either the file was never imported (imported files load as
 * StreamTexture) or there is no file at all, since load() of a missing image path gives such a texture too.
 * The two want different fixes (import the project, or correct the path), so they are told apart. */
typedef enum texture_source { TEXTURE_OWN, TEXTURE_UNIMPORTED, TEXTURE_MISSING } texture_source;

static texture_source texture_source_of(godot_object *texture, char *path, size_t path_size)
{
    if (!is_a(texture, api.image_texture_tag))
        return TEXTURE_OWN;
    godot_variant v;
    path[0] = '\0';
    if (call0(api.get_path, texture, &v))
        gdn_string_to_utf8(&v, path, path_size);
    gdn->godot_variant_destroy(&v);
    static const char *const exts[] = {".png", ".jpg", ".jpeg", ".webp", ".bmp", ".tga", ".svg", ".hdr", ".exr"};
    const size_t n = strlen(path);
    bool image_file = false;
    for (size_t i = 0; i < sizeof exts / sizeof exts[0]; i++) {
        const size_t e = strlen(exts[i]);
        image_file |= n > e && strcasecmp(path + n - e, exts[i]) == 0;
    }
    if (!image_file)
        return TEXTURE_OWN;
    char file[PATH_SIZE];
    const bool godot_path = strncmp(path, "res://", 6) == 0 || strncmp(path, "user://", 7) == 0;
    const size_t m =
        godot_path ? globalize_path(path, file, sizeof file) : (size_t)snprintf(file, sizeof file, "%s", path);
    struct stat st;
    return m > 0 && m < sizeof file && stat(file, &st) != 0 && errno == ENOENT ? TEXTURE_MISSING : TEXTURE_UNIMPORTED;
}

/* The RGBA8 bytes (a PoolByteArray in *data) and size of an Image or a Texture's image. *hold keeps a
 * converted copy alive; the caller destroys *data and *hold. */
static bool rgba_of(call *c, godot_object *object, godot_variant *data, godot_variant *hold, int64_t *w, int64_t *h)
{
    *data = gdn_nil();
    *hold = gdn_nil();
    godot_object *image = object;
    if (!is_a(object, api.image_tag)) {
        char path[512];
        const texture_source source = texture_source_of(object, path, sizeof path);
        if (source == TEXTURE_MISSING)
            return fail(c, "the texture '%s' does not exist: no file at that path, so load() gave an empty "
                           "placeholder (check the path)", path);
        if (source == TEXTURE_UNIMPORTED)
            return fail(c, "the texture '%s' was never imported, so it has no image (only an 8×8 placeholder): open "
                           "the project in the Godot editor once (or run godot3 -e --quit), or load the file with "
                           "Image.load()", path);
        gdn->godot_variant_destroy(hold);
        if (!call0(api.texture_get_data, object, hold) || gdn->godot_variant_get_type(hold) != GDN_OBJECT ||
            !(image = gdn->godot_variant_as_object(hold)))
            return fail(c, "the texture has no readable image (Texture.get_data() is null: a texture that is not "
                           "kept in memory, or an unimported resource)");
    }
    *w = get_int(image, api.get_width);
    *h = get_int(image, api.get_height);
    if (!bitmap_size_ok(c, *w, *h))
        return false;
    const int64_t format = get_int(image, api.get_format);
    if (format != IMAGE_FORMAT_RGBA8) {
        /* Convert a copy: the caller's image, or the texture's, stays as it was. */
        godot_variant copy;
        if (!call0(api.duplicate, image, &copy)) {
            gdn->godot_variant_destroy(&copy);
            return fail(c, "Image.duplicate() failed");
        }
        gdn->godot_variant_destroy(hold);
        *hold = copy;
        image = gdn->godot_variant_as_object(hold);
        godot_variant ignored, fmt = gdn_int(IMAGE_FORMAT_RGBA8);
        if (get_int(image, api.is_compressed) == 1) {
            call0(api.decompress, image, &ignored);
            gdn->godot_variant_destroy(&ignored);
        }
        const godot_variant *args[] = {&fmt};
        gdn_call(api.convert, image, args, 1, &ignored);
        gdn->godot_variant_destroy(&ignored);
        gdn->godot_variant_destroy(&fmt);
        if (get_int(image, api.get_format) != IMAGE_FORMAT_RGBA8)
            return fail(c, "cannot convert an image of format %lld to RGBA8", (long long)format);
    }
    return call0(api.get_data, image, data) || fail(c, "Image.get_data() failed");
}

godot_variant add_body_image(call *c)
{
    godot_variant data, hold, r = gdn_nil();
    int64_t w = 0, h = 0;
    if (rgba_of(c, c->a[0].object, &data, &hold, &w, &h)) {
        godot_pool_byte_array pool = gdn->godot_variant_as_pool_byte_array(&data);
        /* An image with mipmaps carries the smaller levels after the first; only a short buffer is wrong. */
        if (gdn->godot_pool_byte_array_size(&pool) < w * h * 4) {
            fail(c, "the image data has %d bytes, expected %lld (%lld × %lld × 4)",
                 (int)gdn->godot_pool_byte_array_size(&pool), (long long)(w * h * 4), (long long)w, (long long)h);
        } else {
            godot_pool_byte_array_read_access *rd = gdn->godot_pool_byte_array_read(&pool);
            pp_body_def def = pp_body_def_default();
            def.width = (int32_t)w;
            def.height = (int32_t)h;
            def.rgba = gdn->godot_pool_byte_array_read_access_ptr(rd);
            r = make_body(c, 1, &def);
            gdn->godot_pool_byte_array_read_access_destroy(rd);
        }
        gdn->godot_pool_byte_array_destroy(&pool);
    }
    gdn->godot_variant_destroy(&data);
    gdn->godot_variant_destroy(&hold);
    return r;
}

bool pixels_plane(call *c, const godot_variant *src, const char *what, const pp_body_def *def, bool mask,
                  uint8_t **out)
{
    const int64_t n = (int64_t)def->width * def->height;
    const int32_t t = gdn->godot_variant_get_type(src);
    godot_object *object = t == GDN_OBJECT ? gdn->godot_variant_as_object(src) : NULL;
    if (t != GDN_POOL_BYTE_ARRAY &&
        !(object && gdn11->godot_is_instance_valid(object) && pixels_is_image_or_texture(object)))
        return fail(c, "options[\"%s\"] is %s, expected PoolByteArray, Image or Texture", what, gdn_type_name(src));
    godot_variant data, hold;
    int64_t w = def->width, h = def->height;
    if (t == GDN_POOL_BYTE_ARRAY) {
        gdn->godot_variant_new_copy(&data, src);
        hold = gdn_nil();
    } else if (!rgba_of(c, object, &data, &hold, &w, &h)) {
        gdn->godot_variant_destroy(&data);
        gdn->godot_variant_destroy(&hold);
        return false;
    }
    godot_pool_byte_array pool = gdn->godot_variant_as_pool_byte_array(&data);
    const int64_t have = gdn->godot_pool_byte_array_size(&pool), need = object ? n * 4 : n;
    bool good = false;
    if (object && (w != def->width || h != def->height || have < need))
        fail(c, "options[\"%s\"] is an image of %lld × %lld pixels, the body's bitmap %d × %d", what, (long long)w,
             (long long)h, (int)def->width, (int)def->height);
    else if (!object && have != need)
        fail(c, "options[\"%s\"] has %lld bytes, expected %lld (%d × %d)", what, (long long)have, (long long)need,
             (int)def->width, (int)def->height);
    else if (!(*out = malloc((size_t)n)))
        fail(c, "out of memory for a %s of %lld bytes", what, (long long)n);
    else
        good = true;
    if (good) {
        godot_pool_byte_array_read_access *rd = gdn->godot_pool_byte_array_read(&pool);
        const uint8_t *p = gdn->godot_pool_byte_array_read_access_ptr(rd);
        if (!object)
            memcpy(*out, p, (size_t)n);
        for (int64_t i = 0; object && i < n; i++) {
            const uint8_t *px = p + 4 * i;
            const uint8_t bright = px[0] > px[1] ? (px[0] > px[2] ? px[0] : px[2]) : (px[1] > px[2] ? px[1] : px[2]);
            (*out)[i] = mask ? (px[3] >= def->alpha_threshold && bright >= 128) : px[0];
        }
        gdn->godot_pool_byte_array_read_access_destroy(rd);
    }
    gdn->godot_pool_byte_array_destroy(&pool);
    gdn->godot_variant_destroy(&data);
    gdn->godot_variant_destroy(&hold);
    return good;
}

/* pp_body_read_mask, _read_weights and _read_rgba: a whole bitmap plane into out. */
typedef pp_status (*read_fn)(pp_world w, pp_body b, uint8_t *out, int64_t capacity);

/* Bytes [skip, skip + len) of the plane fn reads (n bytes in all) as a PoolByteArray; nil if the read fails. */
static godot_variant read_pool(call *c, read_fn fn, int64_t n, int64_t skip, int64_t len)
{
    godot_pool_byte_array pool;
    gdn->godot_pool_byte_array_new(&pool);
    gdn->godot_pool_byte_array_resize(&pool, (int32_t)len);
    godot_pool_byte_array_write_access *wr = gdn->godot_pool_byte_array_write(&pool);
    uint8_t *out = gdn->godot_pool_byte_array_write_access_ptr(wr);
    /* PhysPix reads whole bitmaps: a part goes through a scratch buffer. */
    const bool part = len < n;
    uint8_t *all = part ? malloc((size_t)n) : out;
    const bool read = all ? ok(c, fn(c->self->world, c->a[0].body, all, n))
                          : fail(c, "out of memory for %lld bytes", (long long)n);
    if (read && part)
        memcpy(out, all + skip, (size_t)len);
    if (part)
        free(all);
    gdn->godot_pool_byte_array_write_access_destroy(wr);
    godot_variant r = gdn_nil();
    if (read)
        gdn->godot_variant_new_pool_byte_array(&r, &pool);
    gdn->godot_pool_byte_array_destroy(&pool);
    return r;
}

/* The body's bitmap size, or false with the reason recorded. */
static bool body_size(call *c, int32_t *w, int32_t *h)
{
    return ok(c, pp_body_get_size(c->self->world, c->a[0].body, w, h));
}

/* A one-byte-a-pixel plane whole. */
static godot_variant read_byte_plane(call *c, read_fn fn)
{
    int32_t w, h;
    return body_size(c, &w, &h) ? read_pool(c, fn, (int64_t)w * h, 0, (int64_t)w * h) : gdn_nil();
}

godot_variant read_mask(call *c)
{
    return read_byte_plane(c, pp_body_read_mask);
}

godot_variant read_weights(call *c)
{
    return read_byte_plane(c, pp_body_read_weights);
}

godot_variant read_rgba(call *c)
{
    int32_t w, h;
    if (!body_size(c, &w, &h))
        return gdn_nil();
    const int64_t y = c->argc > 1 ? c->a[1].i : 0, rows = c->argc > 2 ? c->a[2].i : h - y;
    /* Checked without y + rows, which overflows for rows near INT64_MAX (a crash before issue 39). */
    if (y < 0 || y >= h || rows < 1 || rows > h - y) {
        fail(c, "%lld rows from row %lld are outside the bitmap's rows 0..%d", (long long)rows, (long long)y,
             (int)h - 1);
        return gdn_nil();
    }
    return read_pool(c, pp_body_read_rgba, (int64_t)w * h * 4, y * w * 4, rows * w * 4);
}

godot_variant write_pixels(call *c)
{
    const int64_t x = c->a[1].i, y = c->a[2].i, w = c->a[3].i, h = c->a[4].i;
    if (!bitmap_size_ok(c, w, h) || x < INT32_MIN || x > INT32_MAX || y < INT32_MIN || y > INT32_MAX)
        return gdn_nil();
    godot_pool_byte_array planes[2];
    godot_pool_byte_array_read_access *rd[2] = {NULL, NULL};
    const uint8_t *bytes[2] = {NULL, NULL};
    const int n = c->argc > 6 ? 2 : 1;
    bool good = true;
    for (int k = 0; k < n; k++) {
        planes[k] = gdn->godot_variant_as_pool_byte_array(c->a[5 + k].var);
        const int64_t have = gdn->godot_pool_byte_array_size(&planes[k]);
        if (good && have != w * h)
            good = fail(c, "the %s has %lld bytes, expected %lld (%lld × %lld)", k ? "weights" : "mask",
                        (long long)have, (long long)(w * h), (long long)w, (long long)h);
        rd[k] = gdn->godot_pool_byte_array_read(&planes[k]);
        bytes[k] = gdn->godot_pool_byte_array_read_access_ptr(rd[k]);
    }
    good = good && ok(c, pp_body_write_pixels(c->self->world, c->a[0].body, (int32_t)x, (int32_t)y, (int32_t)w,
                                              (int32_t)h, bytes[0], bytes[1]));
    for (int k = 0; k < n; k++) {
        gdn->godot_pool_byte_array_read_access_destroy(rd[k]);
        gdn->godot_pool_byte_array_destroy(&planes[k]);
    }
    return good ? gdn_bool(true) : gdn_nil();
}
