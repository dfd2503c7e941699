/* libFuzzer target: PNG files through the public calls a host makes — pp_image_info, pp_image_load — then,
 * for a small image, a body made from its pixels and an encode/decode round trip through pp_image_save. */
#include "fuzz_common.h"

/* Decoding is linear in the area; past this the harness skips the decode to keep thousands of runs a second. */
#define FUZZ_PNG_MAX_DECODE_AREA (1 << 20)
/* Bodies and round trips for images up to this area. */
#define FUZZ_PNG_MAX_BODY_AREA (64 * 64)

static char in_path[300], out_path[300];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    fuzz_no_gpu();
    snprintf(in_path, sizeof in_path, "%s/in.png", fuzz_scratch());
    snprintf(out_path, sizeof out_path, "%s/out.png", fuzz_scratch());
    return 0;
}

static void make_body(const uint8_t *rgba, int32_t w, int32_t h)
{
    pp_world_def wd = pp_world_def_default();
    wd.backend = PP_BACKEND_CPU;
    wd.worker_threads = 1;
    pp_world world;
    FUZZ_CHECK(ST(pp_world_create(&wd, &world)) == PP_OK, "world");
    pp_body_def d = pp_body_def_default();
    d.type = (rgba[0] & 1) ? PP_BODY_STATIC : PP_BODY_DYNAMIC;
    d.width = w, d.height = h, d.rgba = rgba;
    d.alpha_threshold = 1 + rgba[1] % 255;
    pp_body b;
    const pp_status st = ST(pp_body_create(world, &d, &b));
    int32_t n = -1;
    ST(pp_world_get_bodies(world, NULL, 0, &n));
    FUZZ_CHECK(n == (st == PP_OK), "%d bodies after a create that returned %d", (int)n, (int)st);
    /* The only refusal of a decoded image: a dynamic body with no solid pixel. */
    FUZZ_CHECK(st == PP_OK || st == PP_ERR_INVALID_ARGUMENT, "body from a %dx%d image: %d", (int)w, (int)h, (int)st);
    if (st == PP_OK) {
        int32_t bw = 0, bh = 0;
        FUZZ_CHECK(ST(pp_body_get_size(world, b, &bw, &bh)) == PP_OK && bw == w && bh == h, "size");
        ST(pp_world_step(world, 1.0f / 60));
        FUZZ_CHECK(ST(pp_body_destroy(world, b)) == PP_OK, "destroy");
        FUZZ_CHECK(ST(pp_body_destroy(world, b)) == PP_ERR_INVALID_HANDLE, "second destroy");
    }
    FUZZ_CHECK(ST(pp_world_destroy(world)) == PP_OK, "world destroy");
}

/* Save and load again: RGBA8 in, RGBA8 out, bit for bit. */
static void round_trip(const uint8_t *rgba, int32_t w, int32_t h)
{
    FUZZ_CHECK(ST(pp_image_save(out_path, rgba, w, h)) == PP_OK, "save %dx%d", (int)w, (int)h);
    const size_t n = (size_t)w * h * 4;
    uint8_t *back = malloc(n);
    int32_t bw = 0, bh = 0;
    FUZZ_CHECK(ST(pp_image_load(out_path, back, (int64_t)n, &bw, &bh)) == PP_OK, "reload");
    FUZZ_CHECK(bw == w && bh == h && memcmp(back, rgba, n) == 0, "round trip changed the image");
    free(back);
}

/* The PNG CRC-32 (ISO 3309) of a chunk's type and data. */
static uint32_t png_crc(const uint8_t *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++)
            c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
    }
    return c ^ 0xffffffffu;
}

/* Give every whole chunk after the signature its right CRC, so that mutations reach the decoder instead of
 * stopping at the checksum (bad CRCs have their own tests in tests/c/test_image.c). */
static void fix_crcs(uint8_t *p, size_t size)
{
    for (size_t at = 8; at + 12 <= size;) {
        const size_t len = (size_t)p[at] << 24 | (size_t)p[at + 1] << 16 | (size_t)p[at + 2] << 8 | p[at + 3];
        if (len > size - at - 12)
            break;
        const uint32_t crc = png_crc(p + at + 4, len + 4);
        uint8_t *c = p + at + 8 + len;
        c[0] = (uint8_t)(crc >> 24), c[1] = (uint8_t)(crc >> 16), c[2] = (uint8_t)(crc >> 8), c[3] = (uint8_t)crc;
        at += len + 12;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    uint8_t *copy = malloc(size + 1);
    memcpy(copy, data, size);
    fix_crcs(copy, size);
    fuzz_write_file(in_path, copy, size);
    free(copy);
    int32_t w = -1, h = -1;
    const pp_status info = ST(pp_image_info(in_path, &w, &h));
    ST(pp_image_info(in_path, NULL, NULL));
    FUZZ_CHECK(info == PP_OK || info == PP_ERR_FORMAT || info == PP_ERR_LIMIT, "pp_image_info: %d", (int)info);
    if (info != PP_OK) {
        /* The load reads the same header: the same refusal. */
        int32_t lw = 0, lh = 0;
        FUZZ_CHECK(ST(pp_image_load(in_path, NULL, 0, &lw, &lh)) == info, "load and info disagree");
        return 0;
    }
    FUZZ_CHECK(w >= 1 && h >= 1 && w <= PP_MAX_BITMAP_SIDE && h <= PP_MAX_BITMAP_SIDE &&
                   (int64_t)w * h <= PP_MAX_BITMAP_AREA, "size %dx%d", (int)w, (int)h);
    /* A short buffer is refused before any pixel is written; NULL sizes are refused. */
    int32_t lw = 0, lh = 0;
    FUZZ_CHECK(ST(pp_image_load(in_path, NULL, 0, &lw, &lh)) == PP_ERR_INVALID_ARGUMENT && lw == w && lh == h,
               "capacity 0");
    FUZZ_CHECK(ST(pp_image_load(in_path, NULL, 0, NULL, &lh)) == PP_ERR_INVALID_ARGUMENT, "NULL width");
    const int64_t area = (int64_t)w * h;
    if (area > FUZZ_PNG_MAX_DECODE_AREA)
        return 0;
    const size_t need = (size_t)area * 4;
    uint8_t *rgba = malloc(need);
    FUZZ_CHECK(rgba != NULL, "malloc");
    FUZZ_CHECK(ST(pp_image_load(in_path, rgba, (int64_t)need - 1, &lw, &lh)) == PP_ERR_INVALID_ARGUMENT, "short");
    const pp_status st = ST(pp_image_load(in_path, rgba, (int64_t)need, &lw, &lh));
    FUZZ_CHECK(st == PP_OK || st == PP_ERR_FORMAT, "pp_image_load: %d", (int)st);
    if (st == PP_OK) {
        FUZZ_CHECK(lw == w && lh == h, "load says %dx%d, info %dx%d", (int)lw, (int)lh, (int)w, (int)h);
        if (area <= FUZZ_PNG_MAX_BODY_AREA) {
            make_body(rgba, w, h);
            round_trip(rgba, w, h);
        }
    }
    free(rgba);
    return 0;
}
