/* Shared helpers of the C unit tests: worlds, rectangle and disc bodies, status checks,
 * angle arithmetic and small statistics. Everything is static inline, since every
 * test file under tests/c is linked into one Criterion binary. */
#ifndef PHYSPIX_TEST_HELPERS_H
#define PHYSPIX_TEST_HELPERS_H

#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <ctype.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "physpix.h"

/* Criterion's forked workers skip LeakSanitizer's exit-time check, so the sanitized build checks
 * for leaks explicitly after every test and prints any report; `make test-san` fails on a report.
 * (Criterion counts a test before its .fini runs, so failing here would not fail the test.) */
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
static inline void pp_test_leak_check(void) { __lsan_do_recoverable_leak_check(); }
#define PP_TEST_SUITE(name) TestSuite(name, .fini = pp_test_leak_check)
#else
#define PP_TEST_SUITE(name) TestSuite(name)
#endif

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define DEG2RAD(d) ((d) * (M_PI / 180.0))
#define RAD2DEG(r) ((r) * (180.0 / M_PI))

/* Asserts a call returned PP_OK, printing the status name and the last error otherwise. */
#define PP_OK_OR_FAIL(call)                                                                          \
    do {                                                                                             \
        pp_status st_ = (call);                                                                      \
        cr_assert_eq(st_, PP_OK, "%s -> %s (%s)", #call, pp_status_name(st_), pp_last_error());     \
    } while (0)

/* Case-insensitive: does `hay` contain one of the '|'-separated words of `alts`? */
static inline int msg_names(const char *hay, const char *alts) {
    char word[64];
    const char *p = alts;
    while (*p) {
        size_t n = 0;
        while (p[n] && p[n] != '|' && n < sizeof word - 1) {
            word[n] = (char)tolower((unsigned char)p[n]);
            n++;
        }
        word[n] = 0;
        for (const char *h = hay; *h; h++) {
            size_t k = 0;
            while (k < n && h[k] && tolower((unsigned char)h[k]) == word[k]) k++;
            if (n > 0 && k == n) return 1;
        }
        p += n;
        if (*p == '|') p++;
    }
    return 0;
}

/* Asserts a call failed with `want`, and that pp_last_error() names one of `words` ("a|b"). */
#define EXPECT_ERR(call, want, words)                                                                \
    do {                                                                                             \
        pp_status st_ = (call);                                                                      \
        const char *msg_ = pp_last_error();                                                          \
        cr_assert_eq(st_, (want), "%s -> %s, expected %s (msg: \"%s\")", #call, pp_status_name(st_), \
                     pp_status_name(want), msg_);                                                    \
        cr_assert(msg_ != NULL, "pp_last_error() returned NULL after %s", #call);                   \
        cr_assert(msg_names(msg_, (words)), "%s: pp_last_error() \"%s\" does not name %s", #call,    \
                  msg_, (words));                                                                    \
    } while (0)

static inline pp_vec2 v2(float x, float y) {
    pp_vec2 v = {x, y};
    return v;
}

/* A GPU world was refused (why: pp_last_error()): skip, with the reason, where the machine has no GLES 3.1 compute
 * context; fail where the context came up and one of the project's shaders did not compile or link (a skip there
 * would hide the bug). */
static inline void skip_without_gpu(const char *why) {
    cr_assert_null(strstr(why, "glsl/"), "a shader of the project failed: %s", why);
    fprintf(stderr, "gpu tests skipped: %s\n", why);
    cr_skip_test("no GLES 3.1 compute context: %s", why);
}

/* A world with the default settings but the given gravity. */
static inline pp_world make_world_def(const pp_world_def *d) {
    pp_world w = {0};
    PP_OK_OR_FAIL(pp_world_create(d, &w));
    cr_assert_neq(w.id, 0);
    return w;
}

static inline pp_world make_world(float gx, float gy) {
    pp_world_def d = pp_world_def_default();
    d.gravity = v2(gx, gy);
    return make_world_def(&d);
}

/* A body def with a type and a pose, everything else default, no bitmap yet. */
static inline pp_body_def body_def(pp_body_type type, float x, float y, float angle) {
    pp_body_def d = pp_body_def_default();
    d.type = type;
    d.position = v2(x, y);
    d.angle = angle;
    return d;
}

/* A width×height mask, every pixel solid. Caller frees. */
static inline uint8_t *rect_mask(int width, int height) {
    uint8_t *m = malloc((size_t)width * (size_t)height);
    cr_assert_not_null(m);
    memset(m, 1, (size_t)width * (size_t)height);
    return m;
}

/* Is pixel (i, j) of a 2r×2r bitmap inside the disc of radius r centred at (r, r)? By pixel centre. */
static inline int disc_pixel(int r, int i, int j) {
    double dx = i + 0.5 - r, dy = j + 0.5 - r;
    return dx * dx + dy * dy <= (double)r * r;
}

/* A 2r×2r mask of a disc of radius r rasterised by pixel centres; *count receives the solid pixels. */
static inline uint8_t *disc_mask(int r, int *count) {
    int n = 2 * r, c = 0;
    uint8_t *m = calloc((size_t)n * (size_t)n, 1);
    cr_assert_not_null(m);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++)
            if (disc_pixel(r, i, j)) {
                m[j * n + i] = 1;
                c++;
            }
    if (count) *count = c;
    return m;
}

/* Creates a body from a def whose bitmap is filled in; asserts success. */
static inline pp_body create_body_ok(pp_world w, const pp_body_def *d) {
    pp_body b = {0};
    PP_OK_OR_FAIL(pp_body_create(w, d, &b));
    cr_assert_neq(b.id, 0);
    return b;
}

/* Adds a solid width×height rectangle with the given def (bitmap fields are overwritten). */
static inline pp_body add_rect(pp_world w, pp_body_def d, int width, int height) {
    uint8_t *m = rect_mask(width, height);
    d.width = width;
    d.height = height;
    d.mask = m;
    d.rgba = NULL;
    pp_body b = create_body_ok(w, &d);
    free(m);
    return b;
}

/* Adds a disc of radius r (a 2r×2r bitmap; its centre is the default pivot). */
static inline pp_body add_disc(pp_world w, pp_body_def d, int r) {
    uint8_t *m = disc_mask(r, NULL);
    d.width = 2 * r;
    d.height = 2 * r;
    d.mask = m;
    d.rgba = NULL;
    pp_body b = create_body_ok(w, &d);
    free(m);
    return b;
}

static inline pp_vec2 body_pos(pp_world w, pp_body b) {
    pp_vec2 p = {0, 0};
    PP_OK_OR_FAIL(pp_body_get_position(w, b, &p));
    return p;
}

static inline float body_angle(pp_world w, pp_body b) {
    float a = 0;
    PP_OK_OR_FAIL(pp_body_get_angle(w, b, &a));
    return a;
}

static inline pp_vec2 body_vel(pp_world w, pp_body b) {
    pp_vec2 v = {0, 0};
    PP_OK_OR_FAIL(pp_body_get_velocity(w, b, &v, NULL));
    return v;
}

static inline void step_n(pp_world w, float dt, int n) {
    for (int i = 0; i < n; i++) PP_OK_OR_FAIL(pp_world_step(w, dt));
}

/* An angle folded into (-pi, pi]. */
static inline double wrap_angle(double a) {
    while (a > M_PI) a -= 2 * M_PI;
    while (a <= -M_PI) a += 2 * M_PI;
    return a;
}

/* Angle between two 2D directions (need not be unit), degrees in [0, 180]. */
static inline double angle_between_deg(double ax, double ay, double bx, double by) {
    return fabs(RAD2DEG(atan2(ax * by - ay * bx, ax * bx + ay * by)));
}

static inline int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The q-quantile (0..1) of n values, nearest rank; sorts v in place. */
static inline double quantile(double *v, int n, double q) {
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    int k = (int)ceil(q * n) - 1;
    if (k < 0) k = 0;
    if (k >= n) k = n - 1;
    return v[k];
}

/* FNV-1a's start value, and n bytes hashed onto h: the tests' hash of poses, states and contacts. */
#define FNV_START 1469598103934665603ull
static inline uint64_t fnv1a(uint64_t h, const void *data, size_t n) {
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

/* How many entries a folder holds, "." and ".." aside; -1 if it cannot be opened. */
static inline int count_entries(const char *dir) {
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    closedir(d);
    return n;
}

/* Remove a folder a test wrote, with everything in it. */
static inline void remove_tree(const char *dir) {
    DIR *d = opendir(dir);
    if (!d) return;
    char path[1024];
    for (struct dirent *e; (e = readdir(d));) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        if (snprintf(path, sizeof path, "%s/%s", dir, e->d_name) >= (int)sizeof path) continue;
        struct stat st;
        if (lstat(path, &st) == 0 && S_ISDIR(st.st_mode)) remove_tree(path); /* a link is removed, not followed */
        else unlink(path);
    }
    closedir(d);
    rmdir(dir);
}

/* Sleep off and the exact solver off (every pile of two or more dynamic bodies is a QuickStep stack), with
 * a static ground 800 × 40 px centred at x = 400 whose top is at y = ground_top. */
static inline pp_world quickstep_world(int32_t substeps, float ground_top) {
    pp_world_def d = pp_world_def_default();
    d.substeps = substeps;
    d.exact_island_rows = 0;
    d.allow_sleep = 0;
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 400, ground_top + 20, 0), 800, 40);
    return w;
}

/* The raster samples the last step tested. */
static inline int64_t pixels_tested(pp_world w) {
    pp_step_stats s;
    PP_OK_OR_FAIL(pp_world_get_stats(w, &s));
    return s.pixels_tested;
}

/* Save w to a snapshot in a fresh temporary folder, load it back and remove the folder: the loaded world. */
static inline pp_world snapshot_round_trip(pp_world w) {
    char dir[] = "/tmp/pp_snapshot_XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, dir));
    pp_world back = {0};
    PP_OK_OR_FAIL(pp_world_load_snapshot(dir, &back));
    remove_tree(dir);
    return back;
}

/* Replace the first `from` in path's text by `to`. */
static inline void patch_file(const char *path, const char *from, const char *to) {
    static char text[1 << 20], out[1 << 20];
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s", path);
    const size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    char *at = strstr(text, from);
    cr_assert_not_null(at, "'%s' not in %s", from, path);
    snprintf(out, sizeof out, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
    f = fopen(path, "wb");
    cr_assert_not_null(f, "cannot write %s", path);
    fputs(out, f);
    fclose(f);
}

/* Replace the first `from` in a snapshot folder's world.json by `to`. */
static inline void patch_json(const char *snap, const char *from, const char *to) {
    char path[160];
    snprintf(path, sizeof path, "%s/world.json", snap);
    patch_file(path, from, to);
}

/* A joint from its def; the test fails if the call does. */
static inline pp_joint make_joint(pp_world w, const pp_joint_def *d) {
    pp_joint j = {0};
    PP_OK_OR_FAIL(pp_joint_create(w, d, &j));
    cr_assert_neq(j.id, 0);
    return j;
}

/* pp_joint_get_value's value, its speed into *speed when not NULL. */
static inline float joint_value(pp_world w, pp_joint j, float *speed) {
    float v = 0, s = 0;
    PP_OK_OR_FAIL(pp_joint_get_value(w, j, &v, &s));
    if (speed)
        *speed = s;
    return v;
}

/* Distance between two points, px. */
static inline double dist(pp_vec2 a, pp_vec2 b) { return hypot(a.x - b.x, a.y - b.y); }

/* Write text to a new file `name` in the folder dir. */
static inline void write_file(const char *dir, const char *name, const char *text) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f, "could not write %s", path);
    fputs(text, f);
    fclose(f);
}

#endif /* PHYSPIX_TEST_HELPERS_H */
