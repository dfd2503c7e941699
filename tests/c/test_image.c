/* PNG loading: every colour type and depth decodes to the same RGBA8 pixels, and broken or
 * oversized files give their status and a message, never a crash. Fixtures are written with libpng. */
#include "helpers.h"

#include <png.h>
#include <unistd.h>

PP_TEST_SUITE(image);

enum { W = 5, H = 3 };

/* The reference picture: gray levels g(x, y), alpha a(x, y). */
static uint8_t gray_at(int x, int y) { return (uint8_t)(x * 50 + y * 7); }
static uint8_t alpha_at(int x, int y) { return (uint8_t)((x + y) % 2 ? 255 : 0); }

/* Write a W×H PNG of the given colour type and depth whose pixels come from gray_at/alpha_at. */
static void write_png(const char *path, int color_type, int depth)
{
    FILE *f = fopen(path, "wb");
    cr_assert(f);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    png_set_IHDR(png, info, W, H, depth, color_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (color_type == PNG_COLOR_TYPE_PALETTE) {
        png_color pal[256];
        for (int i = 0; i < 256; i++)
            pal[i].red = pal[i].green = pal[i].blue = (png_byte)i;
        png_set_PLTE(png, info, pal, 256);
    }
    png_write_info(png, info);
    const int channels = color_type == PNG_COLOR_TYPE_RGBA ? 4 : color_type == PNG_COLOR_TYPE_RGB ? 3
                       : color_type == PNG_COLOR_TYPE_GRAY_ALPHA ? 2 : 1;
    const int bytes = depth / 8;
    uint8_t row[W * 4 * 2];
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++)
            for (int c = 0; c < channels; c++) {
                const int is_alpha = (channels == 2 && c == 1) || (channels == 4 && c == 3);
                const uint8_t v = is_alpha ? alpha_at(x, y) : gray_at(x, y);
                for (int k = 0; k < bytes; k++) /* 16-bit: v·257 is v in both bytes */
                    row[(x * channels + c) * bytes + k] = v;
            }
        png_write_row(png, row);
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    fclose(f);
}

static void expect_reference(const uint8_t *rgba, int has_alpha)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *p = rgba + (y * W + x) * 4;
            cr_assert(p[0] == gray_at(x, y) && p[1] == gray_at(x, y) && p[2] == gray_at(x, y),
                      "pixel (%d,%d) rgb %d %d %d, expected %d", x, y, p[0], p[1], p[2], gray_at(x, y));
            cr_assert_eq(p[3], has_alpha ? alpha_at(x, y) : 255, "pixel (%d,%d) alpha %d", x, y, p[3]);
        }
}

Test(image, every_colour_type_and_depth_decodes_to_the_same_rgba8)
{
    const struct { int type, depth, alpha; } kinds[] = {
        {PNG_COLOR_TYPE_GRAY, 8, 0},       {PNG_COLOR_TYPE_GRAY_ALPHA, 8, 1}, {PNG_COLOR_TYPE_RGB, 8, 0},
        {PNG_COLOR_TYPE_RGBA, 8, 1},       {PNG_COLOR_TYPE_PALETTE, 8, 0},    {PNG_COLOR_TYPE_RGBA, 16, 1},
        {PNG_COLOR_TYPE_GRAY, 16, 0},
    };
    char path[] = "/tmp/pp_image_XXXXXX";
    const int fd = mkstemp(path);
    cr_assert(fd >= 0);
    close(fd);
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
        write_png(path, kinds[i].type, kinds[i].depth);
        int32_t w = 0, h = 0;
        PP_OK_OR_FAIL(pp_image_info(path, &w, &h));
        cr_assert(w == W && h == H);
        uint8_t rgba[W * H * 4];
        memset(rgba, 0xAB, sizeof rgba);
        PP_OK_OR_FAIL(pp_image_load(path, rgba, sizeof rgba, &w, &h));
        expect_reference(rgba, kinds[i].alpha);
    }
    unlink(path);
}

Test(image, broken_files_give_their_status_and_name_the_file)
{
    char path[] = "/tmp/pp_image_XXXXXX";
    const int fd = mkstemp(path);
    cr_assert(fd >= 0);
    close(fd);
    uint8_t rgba[W * H * 4];
    int32_t w, h;

    /* A short capacity is refused before decoding, and still reports the size. */
    write_png(path, PNG_COLOR_TYPE_RGBA, 8);
    cr_assert_eq(pp_image_load(path, rgba, W * H * 4 - 1, &w, &h), PP_ERR_INVALID_ARGUMENT);
    cr_assert(w == W && h == H && strstr(pp_last_error(), "needs 60 bytes"), "%s", pp_last_error());

    /* Truncated: the header survives, the image data does not. */
    FILE *f = fopen(path, "rb");
    uint8_t buf[4096];
    const size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    f = fopen(path, "wb");
    fwrite(buf, 1, n - 20, f);
    fclose(f);
    cr_assert_eq(pp_image_load(path, rgba, sizeof rgba, &w, &h), PP_ERR_FORMAT, "%s", pp_last_error());
    cr_assert(strstr(pp_last_error(), path), "%s", pp_last_error());

    /* Not a PNG at all, and an empty file. */
    f = fopen(path, "wb");
    fputs("GIF89a not a png", f);
    fclose(f);
    cr_assert_eq(pp_image_info(path, &w, &h), PP_ERR_FORMAT);
    cr_assert(msg_names(pp_last_error(), "signature"), "%s", pp_last_error());
    f = fopen(path, "wb");
    fclose(f);
    cr_assert_eq(pp_image_load(path, rgba, sizeof rgba, &w, &h), PP_ERR_FORMAT);

    /* A header declaring a side over PP_MAX_BITMAP_SIDE: LIMIT before any pixel is read. */
    f = fopen(path, "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    png_set_IHDR(png, info, PP_MAX_BITMAP_SIDE + 1, 1, 8, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    static uint8_t zero_row[PP_MAX_BITMAP_SIDE + 1];
    png_write_row(png, zero_row);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    fclose(f);
    cr_assert_eq(pp_image_info(path, &w, &h), PP_ERR_LIMIT, "%s", pp_last_error());
    cr_assert(strstr(pp_last_error(), "PP_MAX_BITMAP_SIDE"), "%s", pp_last_error());

    unlink(path);
    cr_assert_eq(pp_image_info(path, &w, &h), PP_ERR_IO);
    cr_assert(msg_names(pp_last_error(), "cannot open"), "%s", pp_last_error());
    cr_assert_eq(pp_image_info(NULL, &w, &h), PP_ERR_INVALID_ARGUMENT);
    cr_assert_eq(pp_image_load(path, NULL, 16, &w, &h), PP_ERR_INVALID_ARGUMENT);
}

/* A temporary file path; the caller unlinks it. */
static void temp_path(char *path)
{
    strcpy(path, "/tmp/pp_image_XXXXXX");
    const int fd = mkstemp(path);
    cr_assert(fd >= 0);
    close(fd);
}

Test(image, every_input_kind_round_trips_through_save_and_load)
{
    const struct { int type, depth; } kinds[] = {
        {PNG_COLOR_TYPE_GRAY, 8}, {PNG_COLOR_TYPE_GRAY_ALPHA, 8}, {PNG_COLOR_TYPE_RGB, 8}, {PNG_COLOR_TYPE_RGBA, 8},
        {PNG_COLOR_TYPE_PALETTE, 8}, {PNG_COLOR_TYPE_RGBA, 16}, {PNG_COLOR_TYPE_GRAY, 16},
    };
    char src[32], dst[32];
    temp_path(src);
    temp_path(dst);
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
        write_png(src, kinds[i].type, kinds[i].depth);
        uint8_t first[W * H * 4], second[W * H * 4];
        int32_t w, h;
        PP_OK_OR_FAIL(pp_image_load(src, first, sizeof first, &w, &h));
        PP_OK_OR_FAIL(pp_image_save(dst, first, w, h));
        memset(second, 0x5A, sizeof second);
        PP_OK_OR_FAIL(pp_image_load(dst, second, sizeof second, &w, &h));
        cr_assert(w == W && h == H);
        cr_assert_arr_eq(first, second, sizeof first, "kind %zu changed in a save/load round trip", i);
    }
    /* Every byte value in every channel survives, alpha included. */
    enum { N = 64 };
    uint8_t pix[N * N * 4], back[N * N * 4];
    for (int k = 0; k < N * N * 4; k++)
        pix[k] = (uint8_t)(k * 37 + k / 256);
    PP_OK_OR_FAIL(pp_image_save(dst, pix, N, N));
    int32_t w, h;
    PP_OK_OR_FAIL(pp_image_load(dst, back, sizeof back, &w, &h));
    cr_assert_arr_eq(pix, back, sizeof pix);
    unlink(src);
    unlink(dst);
}

/* CRC-32 of PNG chunks (ISO 3309), so a test can forge a header that passes the CRC check. */
static uint32_t crc32_png(const uint8_t *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++)
            c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1)));
    }
    return c ^ 0xffffffffu;
}

static void put_be32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24), p[1] = (uint8_t)(v >> 16), p[2] = (uint8_t)(v >> 8), p[3] = (uint8_t)v;
}

/* Rewrite the IHDR of a PNG written by write_png to declare width × height, with a valid CRC. */
static void forge_ihdr(const char *path, uint32_t width, uint32_t height)
{
    uint8_t buf[4096];
    FILE *f = fopen(path, "rb");
    const size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    /* Signature (8), then IHDR: length (4), "IHDR" (4), data (13), CRC (4). */
    cr_assert(memcmp(buf + 12, "IHDR", 4) == 0);
    put_be32(buf + 16, width);
    put_be32(buf + 20, height);
    put_be32(buf + 29, crc32_png(buf + 12, 17));
    f = fopen(path, "wb");
    fwrite(buf, 1, n, f);
    fclose(f);
}

Test(image, corrupt_headers_and_chunks_give_format_or_limit)
{
    char path[32];
    temp_path(path);
    uint8_t rgba[W * H * 4];
    int32_t w, h;

    /* A flipped bit in the image data's CRC: the data decodes, the CRC check fails. */
    write_png(path, PNG_COLOR_TYPE_RGBA, 8);
    uint8_t buf[4096];
    FILE *f = fopen(path, "rb");
    const size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    uint8_t *idat = NULL;
    for (size_t k = 8; k + 4 <= n && !idat; k++)
        idat = memcmp(buf + k, "IDAT", 4) == 0 ? buf + k : NULL;
    cr_assert(idat);
    const uint32_t len = (uint32_t)idat[-4] << 24 | (uint32_t)idat[-3] << 16 | (uint32_t)idat[-2] << 8 | idat[-1];
    idat[4 + len] ^= 0x10;
    f = fopen(path, "wb");
    fwrite(buf, 1, n, f);
    fclose(f);
    EXPECT_ERR(pp_image_load(path, rgba, sizeof rgba, &w, &h), PP_ERR_FORMAT, "CRC");

    /* A zero-sized image is malformed. */
    write_png(path, PNG_COLOR_TYPE_RGBA, 8);
    forge_ihdr(path, 0, H);
    EXPECT_ERR(pp_image_info(path, &w, &h), PP_ERR_FORMAT, "width");

    /* Each side within PP_MAX_BITMAP_SIDE but the area over PP_MAX_BITMAP_AREA: LIMIT from the header,
     * before anything the size of the image is allocated. */
    write_png(path, PNG_COLOR_TYPE_RGBA, 8);
    forge_ihdr(path, PP_MAX_BITMAP_SIDE, PP_MAX_BITMAP_SIDE);
    EXPECT_ERR(pp_image_load(path, rgba, sizeof rgba, &w, &h), PP_ERR_LIMIT, "PP_MAX_BITMAP_AREA");

    /* A declared size at PNG's own limit (2^31 − 1). */
    write_png(path, PNG_COLOR_TYPE_RGBA, 8);
    forge_ihdr(path, 0x7fffffffu, 0x7fffffffu);
    EXPECT_ERR(pp_image_info(path, &w, &h), PP_ERR_LIMIT, "PP_MAX_BITMAP_SIDE");
    unlink(path);
}

Test(image, save_refuses_bad_arguments_and_unwritable_paths)
{
    uint8_t px[4] = {1, 2, 3, 4};
    EXPECT_ERR(pp_image_save(NULL, px, 1, 1), PP_ERR_INVALID_ARGUMENT, "NULL");
    EXPECT_ERR(pp_image_save("/tmp/x.png", NULL, 1, 1), PP_ERR_INVALID_ARGUMENT, "NULL");
    EXPECT_ERR(pp_image_save("/tmp/x.png", px, 0, 1), PP_ERR_INVALID_ARGUMENT, "at least");
    EXPECT_ERR(pp_image_save("/tmp/x.png", px, -3, 1), PP_ERR_INVALID_ARGUMENT, "at least");
    EXPECT_ERR(pp_image_save("/tmp/x.png", px, PP_MAX_BITMAP_SIDE + 1, 1), PP_ERR_LIMIT, "PP_MAX_BITMAP_SIDE");
    EXPECT_ERR(pp_image_save("/nonexistent-dir/x.png", px, 1, 1), PP_ERR_IO, "cannot create");
}
