/* Writes the generated part of the fuzz seed corpora (`make fuzz-seeds`): PNGs of every colour type, depth
 * and interlacing through libpng, and real snapshots of small worlds packed as fuzz_snapshot reads them.
 * The scene seeds are files copied by hand from tests and the demo; the API seeds are fixed byte streams. */
#include "fuzz_archive.h"
#include "physpix.h"

#include <dirent.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char out_root[512];

static void fail(const char *what)
{
    fprintf(stderr, "make_seeds: %s (%s)\n", what, pp_last_error());
    exit(1);
}

/* A w×h image of the given libpng colour type and depth, a gradient with a transparent corner. */
static void write_png(const char *name, int w, int h, int color, int depth, int interlace)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/fuzz_png/%s", out_root, name);
    FILE *f = fopen(path, "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (!f || !png || !info || setjmp(png_jmpbuf(png)))
        fail(path);
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, color,
                 interlace ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (color == PNG_COLOR_TYPE_PALETTE) {
        png_color pal[16];
        png_byte alpha[16];
        for (int i = 0; i < 16; i++)
            pal[i] = (png_color){(png_byte)(i * 16), (png_byte)(255 - i * 16), (png_byte)(i * 7)}, alpha[i] = (png_byte)(i * 17);
        const int n = 1 << (depth < 4 ? depth : 4);
        png_set_PLTE(png, info, pal, n);
        png_set_tRNS(png, info, alpha, n, NULL);
    }
    if (color == PNG_COLOR_TYPE_RGB) {
        png_color_16 key = {0, 0, 0, 0, 0};
        png_set_tRNS(png, info, NULL, 0, &key);
    }
    png_write_info(png, info);
    if (depth < 8)
        png_set_packing(png);
    if (depth == 16)
        png_set_swap(png); /* rows below are little-endian 16-bit samples */
    const int channels = color == PNG_COLOR_TYPE_RGBA ? 4 : color == PNG_COLOR_TYPE_RGB ? 3
                       : color == PNG_COLOR_TYPE_GRAY_ALPHA ? 2 : 1;
    const int bytes = depth == 16 ? 2 : 1;
    png_bytep image = calloc((size_t)w * h * channels * bytes, 1);
    png_bytep *rows = malloc((size_t)h * sizeof *rows);
    const int maxv = color == PNG_COLOR_TYPE_PALETTE && depth > 4 ? 15 : (1 << depth) - 1;
    for (int y = 0; y < h; y++) {
        rows[y] = image + (size_t)y * w * channels * bytes;
        for (int x = 0; x < w; x++)
            for (int c = 0; c < channels; c++) {
                int v = (x * 37 + y * 11 + c * 50) % (maxv + 1);
                if (c == channels - 1 && (channels == 4 || channels == 2))
                    v = (x + y < 3) ? 0 : maxv; /* alpha */
                if (bytes == 2) {
                    rows[y][(x * channels + c) * 2] = (png_byte)(v & 0xff);
                    rows[y][(x * channels + c) * 2 + 1] = (png_byte)(v >> 8);
                } else {
                    rows[y][x * channels + c] = (png_byte)v;
                }
            }
    }
    png_write_image(png, rows);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    fclose(f);
    free(rows);
    free(image);
}

/* Pack a snapshot folder's files into one fuzz_snapshot input. */
static void pack(const char *folder, const char *name)
{
    static uint8_t buf[1 << 16];
    size_t len = 0;
    DIR *d = opendir(folder);
    if (!d)
        fail(folder);
    /* world.json first, then the planes in name order, so the seed is stable. */
    char names[32][64];
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) && n < 32;)
        if (e->d_name[0] != '.')
            snprintf(names[n++], 64, "%.63s", e->d_name);
    closedir(d);
    qsort(names, (size_t)n, 64, (int (*)(const void *, const void *))strcmp);
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < n; i++) {
            if ((strcmp(names[i], "world.json") == 0) != (pass == 0))
                continue;
            char path[4096];
            static uint8_t data[1 << 16];
            snprintf(path, sizeof path, "%s/%s", folder, names[i]);
            FILE *f = fopen(path, "rb");
            const size_t k = f ? fread(data, 1, sizeof data, f) : 0;
            if (f)
                fclose(f);
            if (!(len = fuzz_archive_add(buf, len, sizeof buf, names[i], data, k)))
                fail("snapshot too big for a seed");
        }
    char path[4096];
    snprintf(path, sizeof path, "%s/fuzz_snapshot/%s", out_root, name);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(buf, 1, len, f) != len || fclose(f) != 0)
        fail(path);
}

static void remove_folder(const char *folder)
{
    DIR *d = opendir(folder);
    char path[4096];
    for (struct dirent *e; d && (e = readdir(d));)
        if (e->d_name[0] != '.') {
            snprintf(path, sizeof path, "%s/%s", folder, e->d_name);
            unlink(path);
        }
    if (d)
        closedir(d);
    rmdir(folder);
}

static pp_body add_body(pp_world w, pp_body_type type, float x, float y, int bw, int bh, int sprite, int weights)
{
    uint8_t *rgba = malloc((size_t)bw * bh * 4), *wt = malloc((size_t)bw * bh);
    for (int i = 0; i < bw * bh; i++) {
        rgba[4 * i] = (uint8_t)(i * 13), rgba[4 * i + 1] = 90, rgba[4 * i + 2] = (uint8_t)i;
        rgba[4 * i + 3] = (i % bw + i / bw) % 5 ? 255 : 0;
        wt[i] = (uint8_t)(1 + i % 255);
    }
    pp_body_def d = pp_body_def_default();
    d.type = type, d.position = (pp_vec2){x, y}, d.width = bw, d.height = bh;
    d.rgba = sprite ? rgba : NULL;
    d.weights = weights ? wt : NULL;
    uint8_t *mask = NULL;
    if (!sprite) {
        mask = malloc((size_t)bw * bh);
        memset(mask, 1, (size_t)bw * bh);
        d.mask = mask;
    }
    d.user_data = 42;
    pp_body b;
    if (pp_body_create(w, &d, &b) != PP_OK)
        fail("body");
    free(rgba), free(wt), free(mask);
    return b;
}

static pp_world small_world(void)
{
    pp_world_def wd = pp_world_def_default();
    wd.backend = PP_BACKEND_CPU, wd.worker_threads = 1, wd.substeps = 2;
    pp_world w;
    if (pp_world_create(&wd, &w) != PP_OK)
        fail("world");
    return w;
}

static void save(pp_world w, const char *name)
{
    char folder[2048];
    snprintf(folder, sizeof folder, "%s/fuzz_snapshot/.tmp-%s", out_root, name);
    if (pp_world_save_snapshot(w, folder) != PP_OK)
        fail("save");
    pack(folder, name);
    remove_folder(folder);
    pp_world_destroy(w);
}

static void snapshots(void)
{
    /* A ground, two crates resting on it (one with a sprite and weights), stepped; an edit pending. */
    pp_world w = small_world();
    add_body(w, PP_BODY_STATIC, 40, 60, 64, 8, 0, 0);
    add_body(w, PP_BODY_DYNAMIC, 30, 48, 8, 8, 1, 1);
    add_body(w, PP_BODY_DYNAMIC, 50, 40, 6, 10, 0, 0);
    for (int i = 0; i < 10; i++)
        pp_world_step(w, 1.0f / 60);
    pp_timed_edit e = {0};
    e.time = 1.0, e.type = PP_EDIT_ERASE_CIRCLE, e.center = (pp_vec2){40, 60}, e.radius = 5;
    pp_world_schedule_edit(w, &e);
    save(w, "resting");

    /* A destroyed body (a free slot), a split static body (an unread event), a kinematic bullet. */
    w = small_world();
    pp_body g = add_body(w, PP_BODY_STATIC, 40, 60, 32, 6, 0, 0);
    pp_body gone = add_body(w, PP_BODY_DYNAMIC, 10, 10, 4, 4, 0, 0);
    pp_body_destroy(w, gone);
    pp_body k = add_body(w, PP_BODY_KINEMATIC, 20, 20, 5, 5, 1, 0);
    pp_body_set_velocity(w, k, (pp_vec2){30, 0}, 0.5f);
    pp_body_erase_circle(w, g, (pp_vec2){40, 60}, 3, NULL);
    pp_world_step(w, 1.0f / 60);
    save(w, "slots_events");

    /* Contact events unread, a sensor overlapped, a box passing up through a one-way platform: touching pairs. */
    pp_world_def wd = pp_world_def_default();
    wd.backend = PP_BACKEND_CPU, wd.worker_threads = 1, wd.substeps = 2, wd.contact_events = 1;
    if (pp_world_create(&wd, &w) != PP_OK)
        fail("world");
    uint8_t solid[64 * 8];
    memset(solid, 1, sizeof solid);
    pp_body_def d = pp_body_def_default();
    d.mask = solid, d.type = PP_BODY_STATIC;
    d.position = (pp_vec2){40, 60}, d.width = 64, d.height = 8;
    pp_body b;
    pp_body_create(w, &d, &b);
    d.position = (pp_vec2){40, 30}, d.width = 20, d.height = 4, d.one_way = 1;
    pp_body_create(w, &d, &b);
    d.position = (pp_vec2){70, 45}, d.width = 10, d.height = 10, d.one_way = 0, d.is_sensor = 1;
    pp_body_create(w, &d, &b);
    d.type = PP_BODY_DYNAMIC, d.is_sensor = 0, d.width = d.height = 6;
    d.position = (pp_vec2){40, 40}, d.linear_velocity = (pp_vec2){0, -150};
    pp_body_create(w, &d, &b);
    d.position = (pp_vec2){70, 50}, d.linear_velocity = (pp_vec2){0, 0};
    pp_body_create(w, &d, &b);
    for (int i = 0; i < 4; i++)
        pp_world_step(w, 1.0f / 60);
    save(w, "touching");

    /* A pendulum on a hinge to the world, a prismatic pair and a rope, mid-swing: the joint tables and frames. */
    w = small_world();
    pp_body bob = add_body(w, PP_BODY_DYNAMIC, 40, 40, 6, 6, 0, 0);
    pp_body cart = add_body(w, PP_BODY_DYNAMIC, 20, 20, 8, 4, 0, 0);
    pp_body load = add_body(w, PP_BODY_DYNAMIC, 20, 40, 4, 4, 0, 0);
    pp_body_set_velocity(w, bob, (pp_vec2){20, 0}, 0);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    jd.body_b = bob, jd.anchor_a = (pp_vec2){40, 20};
    pp_joint j;
    if (pp_joint_create(w, &jd, &j) != PP_OK)
        fail("hinge");
    jd = pp_joint_def_default(PP_JOINT_PRISMATIC);
    jd.body_b = cart, jd.anchor_a = jd.anchor_b = (pp_vec2){20, 20}, jd.enable_limit = 1, jd.lower = -5, jd.upper = 5;
    if (pp_joint_create(w, &jd, &j) != PP_OK)
        fail("slider");
    jd = pp_joint_def_default(PP_JOINT_DISTANCE);
    jd.body_a = cart, jd.body_b = load, jd.anchor_a = (pp_vec2){20, 20}, jd.anchor_b = (pp_vec2){20, 40};
    jd.max_length = 25, jd.break_force = 1e9f;
    if (pp_joint_create(w, &jd, &j) != PP_OK)
        fail("rope");
    for (int i = 0; i < 6; i++)
        pp_world_step(w, 1.0f / 60);
    save(w, "joints");

    /* An empty world with another camera. */
    w = small_world();
    pp_camera cam = {{10, 10}, 2, 64, 48};
    pp_world_set_camera(w, &cam);
    save(w, "empty");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: make_seeds CORPUS_DIR\n");
        return 2;
    }
    snprintf(out_root, sizeof out_root, "%s", argv[1]);
    char dir[600];
    snprintf(dir, sizeof dir, "%s/fuzz_png", out_root), mkdir(dir, 0755);
    snprintf(dir, sizeof dir, "%s/fuzz_snapshot", out_root), mkdir(dir, 0755);
    write_png("rgba8.png", 9, 7, PNG_COLOR_TYPE_RGBA, 8, 0);
    write_png("rgb8_trns.png", 8, 6, PNG_COLOR_TYPE_RGB, 8, 0);
    write_png("gray1.png", 13, 5, PNG_COLOR_TYPE_GRAY, 1, 0);
    write_png("gray8.png", 6, 6, PNG_COLOR_TYPE_GRAY, 8, 0);
    write_png("gray16.png", 5, 4, PNG_COLOR_TYPE_GRAY, 16, 0);
    write_png("gray_alpha8.png", 7, 7, PNG_COLOR_TYPE_GRAY_ALPHA, 8, 0);
    write_png("palette4_trns.png", 11, 6, PNG_COLOR_TYPE_PALETTE, 4, 0);
    write_png("palette2.png", 6, 3, PNG_COLOR_TYPE_PALETTE, 2, 0);
    write_png("rgba16.png", 5, 5, PNG_COLOR_TYPE_RGBA, 16, 0);
    write_png("rgba8_interlaced.png", 10, 9, PNG_COLOR_TYPE_RGBA, 8, 1);
    write_png("palette8_interlaced.png", 12, 10, PNG_COLOR_TYPE_PALETTE, 8, 1);
    write_png("one_pixel.png", 1, 1, PNG_COLOR_TYPE_RGBA, 8, 0);
    snapshots();
    return 0;
}
