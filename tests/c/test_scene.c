/* Scene files: every documented field reaches the world (checked through physics and getters),
 * timed edits apply at their time, and each malformed file fails with its status and the exact
 * message naming the JSON path. Fixtures are written into a fresh temporary directory per test. */
#include "helpers.h"

#include <dirent.h>
#include <fcntl.h>
#include <unistd.h>

PP_TEST_SUITE(scene);

static char dir[64];

static void dir_open(void)
{
    snprintf(dir, sizeof dir, "/tmp/pp_scene_XXXXXX");
    cr_assert(mkdtemp(dir), "mkdtemp failed");
}

/* Remove the directory and the files the test wrote into it. */
static void dir_close(void) { remove_tree(dir); }

/* The fixture path of a file name (in a static buffer of four, so a call may use a few). */
static const char *at(const char *name)
{
    static char buf[4][512];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
    return buf[k];
}

static void write_text(const char *name, const char *text)
{
    FILE *f = fopen(at(name), "wb");
    cr_assert(f);
    fputs(text, f);
    fclose(f);
}

static void write_png(const char *name, const uint8_t *rgba, int w, int h)
{
    PP_OK_OR_FAIL(pp_image_save(at(name), rgba, w, h));
}

/* Load scene.json written from `json`; asserts success. */
static pp_world load_ok(const char *json)
{
    write_text("scene.json", json);
    pp_world w = {0};
    PP_OK_OR_FAIL(pp_world_load_scene(at("scene.json"), &w));
    cr_assert_neq(w.id, 0);
    return w;
}

/* Load scene.json written from `json`; asserts the status, the exact message after the file's prefix,
 * and that *out was left alone. */
static void expect_error(const char *json, pp_status want, const char *tail)
{
    write_text("scene.json", json);
    pp_world w = {0xABCDu};
    const pp_status st = pp_world_load_scene(at("scene.json"), &w);
    char msg[1024];
    snprintf(msg, sizeof msg, "pp_world_load_scene: '%s': %s", at("scene.json"), tail);
    cr_assert_eq(st, want, "%s -> %s, expected %s (%s)", json, pp_status_name(st), pp_status_name(want),
                 pp_last_error());
    cr_assert_str_eq(pp_last_error(), msg);
    cr_assert_eq(w.id, 0xABCDu, "out was written on failure");
}

/* The bodies of a world in creation order. */
static int32_t bodies_of(pp_world w, pp_body *out, int32_t capacity)
{
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, out, capacity, &n));
    return n;
}

static int32_t solid_count(pp_world w, pp_body b)
{
    int32_t bw = 0, bh = 0;
    PP_OK_OR_FAIL(pp_body_get_size(w, b, &bw, &bh));
    uint8_t *m = malloc((size_t)bw * (size_t)bh);
    cr_assert(m);
    PP_OK_OR_FAIL(pp_body_read_mask(w, b, m, (int64_t)bw * bh));
    int32_t n = 0;
    for (int32_t i = 0; i < bw * bh; i++)
        n += m[i] != 0;
    free(m);
    return n;
}

static pp_body_type type_of(pp_world w, pp_body b)
{
    pp_body_type t = PP_BODY_FORCE_U32;
    PP_OK_OR_FAIL(pp_body_get_type(w, b, &t));
    return t;
}

static float mass_of(pp_world w, pp_body b)
{
    float m = -1;
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, &m, NULL, NULL));
    return m;
}

/* The world position of the centre of mass. */
static pp_vec2 com_of(pp_world w, pp_body b)
{
    pp_vec2 c = {0, 0}, pivot = body_pos(w, b), pv = {0, 0};
    float a = body_angle(w, b);
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, NULL, &c, NULL));
    PP_OK_OR_FAIL(pp_body_get_pivot(w, b, &pv));
    const double dx = c.x - pv.x, dy = c.y - pv.y;
    return v2((float)(pivot.x + cos(a) * dx - sin(a) * dy), (float)(pivot.y + sin(a) * dx + cos(a) * dy));
}

#define NEAR(a, b, tol) cr_assert(fabs((double)(a) - (double)(b)) <= (tol), "%s = %.9g, expected %.9g", #a, (double)(a), (double)(b))

/* Fixture planes of the full scene. Sprite: alpha rises across the picture; alpha_threshold 100 keeps part. */
enum { SW = 6, SH = 5, WW = 5, WH = 3, TW = 8, TH = 4 };
static uint8_t sprite_alpha(int x, int y) { return (uint8_t)(x * 40 + y * 15); }
static uint8_t weight_at(int x, int y) { return (uint8_t)(10 * (x + 1) + 50 * y); }
/* Terrain mask: solid where red ≥ 128 and alpha ≥ 128; the other pixels miss one of the two. */
static void terrain_mask_px(int x, int y, uint8_t *px)
{
    const int kind = (x + 2 * y) % 3; /* 0 solid, 1 red low, 2 alpha low */
    px[0] = kind == 1 ? 127 : 200;
    px[1] = px[2] = 0;
    px[3] = kind == 2 ? 127 : 255;
}

static void write_full_scene_planes(int *sprite_solid, double *weight_sum, int *terrain_solid)
{
    uint8_t sprite[SW * SH * 4], weights[WW * WH * 4], tsprite[TW * TH * 4], tmask[TW * TH * 4];
    *sprite_solid = 0, *weight_sum = 0, *terrain_solid = 0;
    for (int y = 0; y < SH; y++)
        for (int x = 0; x < SW; x++) {
            uint8_t *p = sprite + (y * SW + x) * 4;
            p[0] = p[1] = p[2] = 90;
            p[3] = sprite_alpha(x, y);
            *sprite_solid += p[3] >= 100;
        }
    for (int y = 0; y < WH; y++)
        for (int x = 0; x < WW; x++) {
            uint8_t *p = weights + (y * WW + x) * 4;
            p[0] = weight_at(x, y), p[1] = 1, p[2] = 2, p[3] = 255; /* only red counts */
            *weight_sum += p[0];
        }
    for (int i = 0; i < TW * TH; i++) {
        tsprite[4 * i] = tsprite[4 * i + 1] = tsprite[4 * i + 2] = tsprite[4 * i + 3] = 255;
        terrain_mask_px(i % TW, i / TW, tmask + 4 * i);
        *terrain_solid += tmask[4 * i] >= 128 && tmask[4 * i + 3] >= 128;
    }
    write_png("sprite.png", sprite, SW, SH);
    write_png("weights.png", weights, WW, WH);
    write_png("terrain.png", tsprite, TW, TH);
    write_png("terrain_mask.png", tmask, TW, TH);
}

/* Every field set away from its default. The sprite's path is given through "%s" (a scene reads only
 * PNGs beneath its folder, so it is relative like the rest). */
static const char *full_scene_fmt =
    "{\n"
    "  \"world\": { \"gravity\": [30, 500], \"substeps\": 4, \"solver_iterations\": 7, \"exact_solver\": true,\n"
    "             \"backend\": \"cpu\", \"normal_method\": \"kernel\", \"contact_mode\": \"centroid\",\n"
    "             \"raster_stride\": 2, \"pixels_per_meter\": 50, \"contact_slop\": 0.5, \"contact_erp\": 0.3,\n"
    "             \"contact_cfm\": 1e-4, \"bounce_threshold\": 10, \"allow_sleep\": false,\n"
    "             \"sleep_linear_speed\": 3, \"sleep_angular_speed\": 0.1, \"sleep_time\": 1, \"continuous\": false,\n"
    "             \"max_correction_speed\": 150, \"worker_threads\": 3 },\n"
    "  \"camera\": { \"center\": [100, -50], \"zoom\": 2.5, \"width\": 640, \"height\": 360 },\n"
    "  \"bodies\": [\n"
    "    { \"name\": \"faller\", \"box\": [4, 4], \"position\": [1000, 0], \"angle\": 0.25, \"pivot\": [1, 3],\n"
    "      \"linear_velocity\": [5, -20], \"angular_velocity\": 0.5, \"density\": 2, \"user_data\": 9007199254740992 },\n"
    "    { \"name\": \"sprite\", \"type\": \"kinematic\", \"sprite\": \"%s\", \"alpha_threshold\": 100,\n"
    "      \"position\": [-500, 0], \"density\": 1.5, \"friction\": 0.1, \"restitution\": 0.5, \"linear_damping\": 0.2,\n"
    "      \"angular_damping\": 0.3, \"category_bits\": 6, \"mask_bits\": 4294967294, \"fixed_rotation\": true },\n"
    "    { \"name\": \"weighted\", \"box\": [5, 3], \"weights\": \"weights.png\", \"density\": 3, \"position\": [0, -2000] },\n"
    "    { \"name\": \"terrain\", \"type\": \"static\", \"sprite\": \"terrain.png\", \"mask\": \"terrain_mask.png\",\n"
    "      \"detach_islands\": true, \"position\": [-2000, 3000] }\n"
    "  ],\n"
    "  \"edits\": [ { \"time\": 2.0, \"type\": \"paint\", \"body\": \"terrain\", \"center\": [-2000, 3001], \"radius\": 3, \"weight\": 77 },\n"
    "             { \"time\": 1.0, \"type\": \"erase\", \"center\": [1, 2], \"radius\": 4 },\n"
    "             { \"time\": 1.0, \"body\": \"weighted\", \"center\": [0, -2000], \"radius\": 1.5 } ]\n"
    "}\n";

Test(scene, every_field_arrives)
{
    dir_open();
    int sprite_solid, terrain_solid;
    double weight_sum;
    write_full_scene_planes(&sprite_solid, &weight_sum, &terrain_solid);
    char json[4096];
    snprintf(json, sizeof json, full_scene_fmt, "./sprite.png");
    pp_world w = load_ok(json);
    pp_body b[8];
    cr_assert_eq(bodies_of(w, b, 8), 4);
    const pp_body faller = b[0], sprite = b[1], weighted = b[2], terrain = b[3];

    /* The world's settings, each away from its default. */
    pp_world_def d;
    PP_OK_OR_FAIL(pp_world_get_def(w, &d));
    cr_assert(d.gravity.x == 30 && d.gravity.y == 500 && d.substeps == 4 && d.solver_iterations == 7 && d.exact_solver);
    cr_assert(d.backend == PP_BACKEND_CPU && d.normal_method == PP_NORMAL_KERNEL && d.contact_mode == PP_CONTACT_CENTROID);
    cr_assert(d.raster_stride == 2 && d.pixels_per_meter == 50 && d.contact_slop == 0.5f && d.contact_erp == 0.3f);
    cr_assert(d.contact_cfm == 1e-4f && d.bounce_threshold == 10 && !d.allow_sleep && d.sleep_linear_speed == 3);
    cr_assert(d.sleep_angular_speed == 0.1f && d.sleep_time == 1 && !d.continuous);
    cr_assert(d.max_correction_speed == 150 && d.worker_threads == 3);

    pp_camera cam;
    PP_OK_OR_FAIL(pp_world_get_camera(w, &cam));
    cr_assert(cam.center.x == 100 && cam.center.y == -50 && cam.zoom == 2.5f && cam.width == 640 && cam.height == 360);

    /* The faller: pose, pivot, velocities, mass (density · pixels), user data. */
    pp_vec2 p = body_pos(w, faller), pivot, v;
    float av;
    PP_OK_OR_FAIL(pp_body_get_pivot(w, faller, &pivot));
    PP_OK_OR_FAIL(pp_body_get_velocity(w, faller, &v, &av));
    uint64_t ud = 0;
    PP_OK_OR_FAIL(pp_body_get_user_data(w, faller, &ud));
    cr_assert(p.x == 1000 && p.y == 0 && body_angle(w, faller) == 0.25f && pivot.x == 1 && pivot.y == 3);
    cr_assert(v.x == 5 && v.y == -20 && av == 0.5f);
    cr_assert_eq(ud, 9007199254740992ull);
    cr_assert_eq(type_of(w, faller), PP_BODY_DYNAMIC);
    NEAR(mass_of(w, faller), 2 * 16, 1e-4);

    /* The sprite body: kinematic, solid where alpha ≥ 100, mass by that count. */
    cr_assert_eq(type_of(w, sprite), PP_BODY_KINEMATIC);
    cr_assert_eq(solid_count(w, sprite), sprite_solid);
    NEAR(mass_of(w, sprite), 1.5 * sprite_solid, 1e-4);
    /* The weighted box: mass is Σ red / 255 · density. */
    NEAR(mass_of(w, weighted), 3 * weight_sum / 255, 1e-4);
    /* The terrain: static, its mask (red and alpha ≥ 128) overriding the opaque sprite. */
    cr_assert_eq(type_of(w, terrain), PP_BODY_STATIC);
    cr_assert_eq(solid_count(w, terrain), terrain_solid);

    /* Edits in the order they will apply: by time, file order among equals. */
    pp_timed_edit e[4];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, e, 4, &n));
    cr_assert_eq(n, 3);
    cr_assert(e[0].time == 1.0 && e[0].type == PP_EDIT_ERASE_CIRCLE && e[0].body.id == 0 && e[0].center.x == 1 &&
              e[0].center.y == 2 && e[0].radius == 4);
    cr_assert(e[1].time == 1.0 && e[1].type == PP_EDIT_ERASE_CIRCLE && e[1].body.id == weighted.id &&
              e[1].center.x == 0 && e[1].center.y == -2000 && e[1].radius == 1.5f);
    cr_assert(e[2].time == 2.0 && e[2].type == PP_EDIT_PAINT_CIRCLE && e[2].body.id == terrain.id &&
              e[2].weight == 77 && e[2].center.x == -2000 && e[2].center.y == 3001 && e[2].radius == 3);

    /* Gravity, substeps and the initial velocities through a free flight of 30 steps: semi-implicit Euler in
     * 4 substeps per step gives x = x0 + v0·t + g·h²·N(N+1)/2 for N substeps of h. */
    const pp_vec2 c0 = com_of(w, faller);
    const float dt = 1.0f / 60;
    step_n(w, dt, 30);
    const double h = dt / 4.0, N = 120, t = N * h, fall = h * h * N * (N + 1) / 2;
    const pp_vec2 c1 = com_of(w, faller);
    NEAR(c1.x, c0.x + 5 * t + 30 * fall, 2e-3);
    NEAR(c1.y, c0.y - 20 * t + 500 * fall, 2e-3);
    NEAR(body_angle(w, faller), 0.25 + 0.5 * t, 1e-4);
    PP_OK_OR_FAIL(pp_world_destroy(w));
    dir_close();
}

Test(scene, missing_keys_take_the_defaults)
{
    dir_open();
    pp_world fresh = make_world(0, 980);
    pp_camera want, got;
    PP_OK_OR_FAIL(pp_world_get_camera(fresh, &want));
    PP_OK_OR_FAIL(pp_world_destroy(fresh));

    pp_world w = load_ok("{}");
    pp_body b[2];
    cr_assert_eq(bodies_of(w, b, 2), 0);
    PP_OK_OR_FAIL(pp_world_get_camera(w, &got));
    cr_assert(memcmp(&want, &got, sizeof want) == 0);
    PP_OK_OR_FAIL(pp_world_destroy(w));

    w = load_ok("{ \"bodies\": [ { \"box\": [6, 4] } ], \"edits\": [ {} ] }");
    cr_assert_eq(bodies_of(w, b, 2), 1);
    pp_vec2 pivot, v;
    PP_OK_OR_FAIL(pp_body_get_pivot(w, b[0], &pivot));
    cr_assert(body_pos(w, b[0]).x == 0 && body_pos(w, b[0]).y == 0 && body_angle(w, b[0]) == 0);
    cr_assert(pivot.x == 3 && pivot.y == 2);
    cr_assert_eq(type_of(w, b[0]), PP_BODY_DYNAMIC);
    NEAR(mass_of(w, b[0]), 24, 1e-4);
    pp_timed_edit e;
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, &e, 1, &n));
    cr_assert(n == 1 && e.time == 0 && e.type == PP_EDIT_ERASE_CIRCLE && e.body.id == 0 && e.radius == 0);
    /* Default gravity: one step of 0.1 s gives the centre of mass 98 px/s downward. */
    PP_OK_OR_FAIL(pp_world_step(w, 0.1f));
    PP_OK_OR_FAIL(pp_body_get_velocity(w, b[0], &v, NULL));
    NEAR(v.x, 0, 1e-4);
    NEAR(v.y, 98, 1e-3);
    PP_OK_OR_FAIL(pp_world_destroy(w));
    dir_close();
}

/* Pixels of a w×h bitmap whose centres lie within r of local point (cx, cy). */
static int pixels_within(int w, int h, double cx, double cy, double r)
{
    int n = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            n += (i + 0.5 - cx) * (i + 0.5 - cx) + (j + 0.5 - cy) * (j + 0.5 - cy) <= r * r;
    return n;
}

Test(scene, a_preset_gives_the_starting_values_and_keys_override_them)
{
    dir_open();
    const char *names[] = {"fast", "balanced", "accurate"};
    const pp_preset presets[] = {PP_PRESET_FAST, PP_PRESET_BALANCED, PP_PRESET_ACCURATE};
    for (int k = 0; k < 3; k++) {
        char json[256];
        snprintf(json, sizeof json, "{ \"world\": { \"contact_erp\": 0.5, \"preset\": \"%s\" } }", names[k]);
        pp_world w = load_ok(json);
        pp_world_def want = pp_world_def_preset(presets[k]), got;
        want.contact_erp = 0.5f; /* a key overrides the preset wherever it stands in the object */
        PP_OK_OR_FAIL(pp_world_get_def(w, &got));
        cr_assert(memcmp(&want, &got, sizeof want) == 0, "preset %s: the world's settings differ", names[k]);
        PP_OK_OR_FAIL(pp_world_destroy(w));
    }
    expect_error("{ \"world\": { \"preset\": \"quick\" } }", PP_ERR_FORMAT,
                 "world.preset: unknown value 'quick' (expected one of fast, balanced, accurate)");
    dir_close();
}

Test(scene, a_bullet_stops_at_a_thin_dynamic_wall)
{
    /* A 4 px box at 5,000 px/s crosses an 8 px dynamic wall in one substep unless it is a bullet. */
    dir_open();
    for (int bullet = 0; bullet <= 1; bullet++) {
        char json[512];
        snprintf(json, sizeof json,
                 "{ \"world\": { \"gravity\": [0, 0], \"substeps\": 2 },"
                 "  \"bodies\": [ { \"box\": [8, 200], \"position\": [500, 100], \"density\": 100 },"
                 "    { \"box\": [4, 4], \"position\": [100, 100], \"linear_velocity\": [5000, 0], \"bullet\": %s } ] }",
                 bullet ? "true" : "false");
        pp_world w = load_ok(json);
        pp_body b[2];
        cr_assert_eq(bodies_of(w, b, 2), 2);
        step_n(w, 1.0f / 60, 30);
        const float x = body_pos(w, b[1]).x;
        if (bullet)
            cr_assert_lt(x, body_pos(w, b[0]).x, "the bullet ended at x %.1f, past the wall", x);
        else
            cr_assert_gt(x, 1000, "without bullet the box ended at x %.1f", x);
        PP_OK_OR_FAIL(pp_world_destroy(w));
    }
    dir_close();
}

Test(scene, timed_edits_apply_at_their_time)
{
    dir_open();
    /* A 40×20 static box centred on (100, 100): local = world − (100, 100) + (20, 10). The paint goes into
     * a 10×10 box whose left half the mask leaves empty. */
    uint8_t m[10 * 10 * 4];
    for (int i = 0; i < 100; i++)
        m[4 * i] = m[4 * i + 1] = m[4 * i + 2] = m[4 * i + 3] = (i % 10) >= 5 ? 255 : 0;
    write_png("half.png", m, 10, 10);
    pp_world w = load_ok("{ \"bodies\": ["
                         "  { \"name\": \"ground\", \"type\": \"static\", \"box\": [40, 20], \"position\": [100, 100] },"
                         "  { \"name\": \"half\", \"type\": \"static\", \"mask\": \"half.png\", \"position\": [300, 100] } ],"
                         "  \"edits\": [ { \"time\": 0.5, \"type\": \"erase\", \"center\": [100.3, 100.2], \"radius\": 5 },"
                         "               { \"time\": 0.5, \"type\": \"paint\", \"body\": \"half\", \"center\": [297, 100],"
                         "                 \"radius\": 2.5, \"weight\": 9 } ] }");
    pp_body b[2];
    cr_assert_eq(bodies_of(w, b, 2), 2);
    const int erased = pixels_within(40, 20, 20.3, 10.2, 5), painted = pixels_within(5, 10, 2, 5, 2.5);
    cr_assert(erased > 60 && painted > 10);
    cr_assert_eq(solid_count(w, b[0]), 800);
    cr_assert_eq(solid_count(w, b[1]), 50);

    const float dt = 1.0f / 60;
    step_n(w, dt, 29); /* the 30th step starts at 29/60 s, nearer that than 0.5 s */
    int32_t pending = 0;
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, NULL, 0, &pending));
    cr_assert_eq(pending, 2);
    cr_assert_eq(solid_count(w, b[0]), 800);
    step_n(w, dt, 2);
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, NULL, 0, &pending));
    cr_assert_eq(pending, 0);
    cr_assert_eq(solid_count(w, b[0]), 800 - erased);
    cr_assert_eq(solid_count(w, b[1]), 50 + painted);
    PP_OK_OR_FAIL(pp_world_destroy(w));
    dir_close();
}

Test(scene, detach_islands_lets_an_erase_drop_the_island_it_cuts_off)
{
    dir_open();
    /* An erase across the whole height of a 40×10 static bar, 8 px from its left end. */
    const char *fmt = "{ \"bodies\": [ { \"type\": \"static\", \"box\": [40, 10], \"position\": [100, 100],"
                      "  \"detach_islands\": %s } ],"
                      "  \"edits\": [ { \"time\": 0, \"center\": [88, 100], \"radius\": 6 } ] }";
    for (int detach = 0; detach <= 1; detach++) {
        char json[512];
        snprintf(json, sizeof json, fmt, detach ? "true" : "false");
        pp_world w = load_ok(json);
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
        pp_body b[4];
        const int32_t n = bodies_of(w, b, 4);
        cr_assert_eq(n, detach ? 2 : 1, "detach_islands %d: %d bodies", detach, (int)n);
        cr_assert_eq(type_of(w, b[0]), PP_BODY_STATIC);
        if (detach)
            cr_assert_eq(type_of(w, b[1]), PP_BODY_DYNAMIC);
        PP_OK_OR_FAIL(pp_world_destroy(w));
    }
    dir_close();
}

Test(scene, a_scene_path_without_a_directory_reads_its_pngs_from_the_working_directory)
{
    dir_open();
    uint8_t px[3 * 2 * 4];
    memset(px, 255, sizeof px);
    write_png("solid.png", px, 3, 2);
    write_text("bare.json", "{ \"bodies\": [ { \"mask\": \"solid.png\" } ] }");
    cr_assert_eq(chdir(dir), 0);
    pp_world w = {0};
    PP_OK_OR_FAIL(pp_world_load_scene("bare.json", &w));
    pp_body b;
    cr_assert_eq(bodies_of(w, &b, 1), 1);
    cr_assert_eq(solid_count(w, b), 6);
    PP_OK_OR_FAIL(pp_world_destroy(w));
    dir_close();
}

/* ---- failures ------------------------------------------------------------------------------------ */

Test(scene, null_arguments)
{
    pp_world w = {7};
    EXPECT_ERR(pp_world_load_scene(NULL, &w), PP_ERR_INVALID_ARGUMENT, "path");
    cr_assert_str_eq(pp_last_error(), "pp_world_load_scene: path is NULL");
    EXPECT_ERR(pp_world_load_scene("x.json", NULL), PP_ERR_INVALID_ARGUMENT, "out");
    cr_assert_str_eq(pp_last_error(), "pp_world_load_scene: out is NULL");
    cr_assert_eq(w.id, 7);
}

Test(scene, unreadable_files)
{
    dir_open();
    char want[600];
    pp_world w = {7};
    cr_assert_eq(pp_world_load_scene(at("none.json"), &w), PP_ERR_IO);
    snprintf(want, sizeof want, "pp_world_load_scene: '%s': cannot open: No such file or directory", at("none.json"));
    cr_assert_str_eq(pp_last_error(), want);
    cr_assert_eq(pp_world_load_scene(dir, &w), PP_ERR_IO);
    snprintf(want, sizeof want, "pp_world_load_scene: '%s': cannot open: not a regular file", dir);
    cr_assert_str_eq(pp_last_error(), want);
    /* One byte over PP_MAX_SCENE_BYTES: a sparse file, refused from its size before anything is read. */
    const int fd = open(at("huge.json"), O_CREAT | O_WRONLY, 0644);
    cr_assert(fd >= 0 && ftruncate(fd, PP_MAX_SCENE_BYTES + 1) == 0);
    close(fd);
    cr_assert_eq(pp_world_load_scene(at("huge.json"), &w), PP_ERR_LIMIT);
    snprintf(want, sizeof want, "pp_world_load_scene: '%s' is 67108865 bytes, over PP_MAX_SCENE_BYTES (67108864)",
             at("huge.json"));
    cr_assert_str_eq(pp_last_error(), want);
    cr_assert_eq(w.id, 7);
    dir_close();
}

Test(scene, invalid_json_names_the_line)
{
    dir_open();
    expect_error("{\n  \"world\": {\n    \"substeps\": 2,\n    \"gravity\": [0 980]\n  }\n}\n", PP_ERR_FORMAT,
                 "line 4: invalid JSON");
    expect_error("", PP_ERR_FORMAT, "line 1: invalid JSON");
    expect_error("{}\n\n{}", PP_ERR_FORMAT, "line 3: invalid JSON");
    expect_error("{ \"bodies\": [\n  { \"box\": [1, 1], },\n] }", PP_ERR_FORMAT, "line 2: invalid JSON");
    dir_close();
}

Test(scene, wrong_types)
{
    dir_open();
    expect_error("[]", PP_ERR_FORMAT, "(root): expected an object");
    expect_error("{ \"world\": [] }", PP_ERR_FORMAT, "world: expected an object");
    expect_error("{ \"camera\": 1 }", PP_ERR_FORMAT, "camera: expected an object");
    expect_error("{ \"bodies\": {} }", PP_ERR_FORMAT, "bodies: expected an array");
    expect_error("{ \"edits\": null }", PP_ERR_FORMAT, "edits: expected an array");
    expect_error("{ \"world\": { \"substeps\": \"2\" } }", PP_ERR_FORMAT, "world.substeps: expected an integer in 1..64");
    expect_error("{ \"world\": { \"gravity\": [0] } }", PP_ERR_FORMAT, "world.gravity: expected [x, y], two finite numbers");
    expect_error("{ \"world\": { \"gravity\": [0, \"down\"] } }", PP_ERR_FORMAT,
                 "world.gravity: expected [x, y], two finite numbers");
    expect_error("{ \"world\": { \"exact_solver\": 1 } }", PP_ERR_FORMAT, "world.exact_solver: expected true or false");
    expect_error("{ \"world\": { \"backend\": 1 } }", PP_ERR_FORMAT,
                 "world.backend: expected a string, one of auto, cpu, gpu");
    expect_error("{ \"bodies\": [ 3 ] }", PP_ERR_FORMAT, "bodies[0]: expected an object");
    expect_error("{ \"bodies\": [ { \"box\": [1, 1], \"name\": 5 } ] }", PP_ERR_FORMAT,
                 "bodies[0].name: expected a non-empty string");
    expect_error("{ \"bodies\": [ { \"sprite\": true } ] }", PP_ERR_FORMAT, "bodies[0].sprite: expected a non-empty string");
    expect_error("{ \"bodies\": [ { \"box\": [1, 1], \"angle\": \"0\" } ] }", PP_ERR_FORMAT,
                 "bodies[0].angle: expected a finite number");
    expect_error("{ \"edits\": [ [] ] }", PP_ERR_FORMAT, "edits[0]: expected an object");
    dir_close();
}

Test(scene, out_of_range_values)
{
    dir_open();
    expect_error("{ \"bodies\": [ { \"box\": [1, 1] }, { \"box\": [1, 1] }, { \"box\": [1, 1] },"
                 "  { \"box\": [1, 1], \"density\": 0 } ] }",
                 PP_ERR_FORMAT, "bodies[3].density: expected a number > 0");
    expect_error("{ \"bodies\": [ { \"box\": [1, 1], \"density\": 1e39 } ] }", PP_ERR_FORMAT,
                 "bodies[0].density: expected a number > 0");
    expect_error("{ \"bodies\": [ { \"box\": [1, 1], \"restitution\": 1.5 } ] }", PP_ERR_FORMAT,
                 "bodies[0].restitution: expected a number in 0..1");
    expect_error("{ \"bodies\": [ { \"box\": [1, 1], \"friction\": -0.1 } ] }", PP_ERR_FORMAT,
                 "bodies[0].friction: expected a number ≥ 0");
    expect_error("{ \"bodies\": [ { \"box\": [1, 1], \"alpha_threshold\": 0 } ] }", PP_ERR_FORMAT,
                 "bodies[0].alpha_threshold: expected an integer in 1..255");
    expect_error("{ \"bodies\": [ { \"box\": [1, 1], \"category_bits\": 4294967296 } ] }", PP_ERR_FORMAT,
                 "bodies[0].category_bits: expected an integer in 0..4294967295");
    expect_error("{ \"bodies\": [ { \"box\": [1, 1], \"mask_bits\": 1.5 } ] }", PP_ERR_FORMAT,
                 "bodies[0].mask_bits: expected an integer in 0..4294967295");
    expect_error("{ \"bodies\": [ { \"box\": [1, 1], \"user_data\": -1 } ] }", PP_ERR_FORMAT,
                 "bodies[0].user_data: expected an integer in 0..9007199254740992");
    expect_error("{ \"bodies\": [ { \"box\": [0, 1] } ] }", PP_ERR_FORMAT,
                 "bodies[0].box: expected [width, height], integers in 1..16384");
    expect_error("{ \"bodies\": [ { \"box\": [16384, 16384] } ] }", PP_ERR_LIMIT,
                 "bodies[0].box: 16384x16384 px is over PP_MAX_BITMAP_AREA (67108864)");
    expect_error("{ \"world\": { \"substeps\": 65 } }", PP_ERR_FORMAT, "world.substeps: expected an integer in 1..64");
    expect_error("{ \"world\": { \"solver_iterations\": 0 } }", PP_ERR_FORMAT,
                 "world.solver_iterations: expected an integer in 1..1000");
    expect_error("{ \"world\": { \"raster_stride\": 3 } }", PP_ERR_FORMAT, "world.raster_stride: expected 1, 2 or 4");
    expect_error("{ \"world\": { \"contact_erp\": 2 } }", PP_ERR_FORMAT, "world.contact_erp: expected a number in 0..1");
    expect_error("{ \"world\": { \"pixels_per_meter\": 0 } }", PP_ERR_FORMAT,
                 "world.pixels_per_meter: expected a number > 0");
    expect_error("{ \"world\": { \"sleep_time\": -1 } }", PP_ERR_FORMAT, "world.sleep_time: expected a number ≥ 0");
    expect_error("{ \"world\": { \"gravity\": [0, 1e300] } }", PP_ERR_FORMAT,
                 "world.gravity: expected [x, y], two finite numbers");
    expect_error("{ \"camera\": { \"zoom\": 0 } }", PP_ERR_FORMAT, "camera.zoom: expected a number > 0");
    expect_error("{ \"camera\": { \"width\": 16385 } }", PP_ERR_FORMAT, "camera.width: expected an integer in 1..16384");
    expect_error("{ \"edits\": [ { \"time\": -1 } ] }", PP_ERR_FORMAT, "edits[0].time: expected a number ≥ 0");
    expect_error("{ \"edits\": [ { \"radius\": -1 } ] }", PP_ERR_FORMAT, "edits[0].radius: expected a number ≥ 0");
    expect_error("{ \"bodies\": [ { \"name\": \"a\", \"box\": [1, 1] } ],"
                 "  \"edits\": [ { \"type\": \"paint\", \"body\": \"a\", \"weight\": 256 } ] }",
                 PP_ERR_FORMAT, "edits[0].weight: expected an integer in 1..255");
    dir_close();
}

Test(scene, unknown_and_duplicate_keys)
{
    dir_open();
    expect_error("{ \"bodies\": [ { \"box\": [1, 1] }, { \"box\": [1, 1] }, { \"box\": [1, 1], \"densty\": 2 } ] }",
                 PP_ERR_FORMAT, "bodies[2].densty: unknown key");
    expect_error("{ \"bodys\": [] }", PP_ERR_FORMAT, "bodys: unknown key");
    expect_error("{ \"world\": { \"gravity_y\": 9 } }", PP_ERR_FORMAT, "world.gravity_y: unknown key");
    expect_error("{ \"camera\": { \"scale\": 2 } }", PP_ERR_FORMAT, "camera.scale: unknown key");
    expect_error("{ \"edits\": [ { \"at\": 1 } ] }", PP_ERR_FORMAT, "edits[0].at: unknown key");
    expect_error("{ \"bodies\": [ { \"box\": [1, 1], \"density\": 1, \"density\": 2 } ] }", PP_ERR_FORMAT,
                 "bodies[0].density: duplicate key");
    dir_close();
}

Test(scene, unknown_enum_strings)
{
    dir_open();
    expect_error("{ \"bodies\": [ { \"box\": [1, 1], \"type\": \"dynamo\" } ] }", PP_ERR_FORMAT,
                 "bodies[0].type: unknown value 'dynamo' (expected one of dynamic, static, kinematic)");
    expect_error("{ \"world\": { \"backend\": \"GPU\" } }", PP_ERR_FORMAT,
                 "world.backend: unknown value 'GPU' (expected one of auto, cpu, gpu)");
    expect_error("{ \"world\": { \"normal_method\": \"sobel\" } }", PP_ERR_FORMAT,
                 "world.normal_method: unknown value 'sobel' (expected one of area_gradient, kernel)");
    expect_error("{ \"world\": { \"contact_mode\": \"points\" } }", PP_ERR_FORMAT,
                 "world.contact_mode: unknown value 'points' (expected one of manifold, centroid)");
    expect_error("{ \"edits\": [ { \"type\": \"fill\" } ] }", PP_ERR_FORMAT,
                 "edits[0].type: unknown value 'fill' (expected one of erase, paint)");
    dir_close();
}

Test(scene, bitmap_rules)
{
    dir_open();
    uint8_t px[4 * 4 * 4];
    memset(px, 255, sizeof px);
    write_png("four.png", px, 4, 4);
    write_png("three_by_two.png", px, 3, 2);
    memset(px, 0, sizeof px);
    write_png("empty.png", px, 4, 4);
    expect_error("{ \"bodies\": [ { \"name\": \"a\", \"weights\": \"four.png\" } ] }", PP_ERR_FORMAT,
                 "bodies[0]: needs a bitmap: sprite, mask or box");
    expect_error("{ \"bodies\": [ { \"box\": [4, 4], \"sprite\": \"four.png\" } ] }", PP_ERR_FORMAT,
                 "bodies[0].box: cannot be combined with sprite or mask");
    expect_error("{ \"bodies\": [ { \"sprite\": \"four.png\", \"mask\": \"three_by_two.png\" } ] }", PP_ERR_FORMAT,
                 "bodies[0].mask: 3x2 px, but the sprite is 4x4 px");
    expect_error("{ \"bodies\": [ { \"box\": [4, 4], \"weights\": \"three_by_two.png\" } ] }", PP_ERR_FORMAT,
                 "bodies[0].weights: 3x2 px, but the bitmap is 4x4 px");
    expect_error("{ \"bodies\": [ { \"mask\": \"empty.png\" } ] }", PP_ERR_FORMAT,
                 "bodies[0]: a dynamic body needs solid pixels; the bitmap (mask) has none");
    dir_close();
}

Test(scene, names_and_edit_references)
{
    dir_open();
    expect_error("{ \"bodies\": [ { \"name\": \"a\", \"box\": [1, 1] }, { \"box\": [1, 1] },"
                 "  { \"name\": \"a\", \"box\": [1, 1] } ] }",
                 PP_ERR_FORMAT, "bodies[2].name: 'a' is already the name of bodies[0]");
    expect_error("{ \"bodies\": [ { \"name\": \"a\", \"box\": [1, 1] } ],"
                 "  \"edits\": [ { \"body\": \"a\" }, { \"body\": \"nobody\" } ] }",
                 PP_ERR_FORMAT, "edits[1].body: no body is named 'nobody'");
    expect_error("{ \"edits\": [ { \"type\": \"paint\", \"weight\": 3 } ] }", PP_ERR_FORMAT,
                 "edits[0].body: a paint edit needs a body");
    expect_error("{ \"edits\": [ { \"type\": \"erase\", \"weight\": 3 } ] }", PP_ERR_FORMAT,
                 "edits[0].weight: only a paint edit has a weight");
    dir_close();
}

Test(scene, broken_pngs_keep_their_status_under_the_json_path)
{
    dir_open();
    char tail[600];
    snprintf(tail, sizeof tail,
             "bodies[0].sprite: cannot open '%s': missing, unreadable, not a regular file, or outside '%s/'",
             at("terrain.png"), dir);
    expect_error("{ \"bodies\": [ { \"sprite\": \"terrain.png\" } ] }", PP_ERR_IO, tail);
    write_text("junk.png", "this is not a PNG file at all");
    snprintf(tail, sizeof tail, "bodies[0].mask: '%s' is not a PNG file (bad signature)", at("junk.png"));
    expect_error("{ \"bodies\": [ { \"mask\": \"junk.png\" } ] }", PP_ERR_FORMAT, tail);
    /* An absolute path is refused as if missing, even to a file inside the folder (tests/c/test_files.c has
     * every confinement case). */
    snprintf(tail, sizeof tail,
             "bodies[0].weights: cannot open '%s': missing, unreadable, not a regular file, or outside '%s/'",
             at("junk.png"), dir);
    char json[600];
    snprintf(json, sizeof json, "{ \"bodies\": [ { \"box\": [2, 2], \"weights\": \"%s\" } ] }", at("junk.png"));
    expect_error(json, PP_ERR_IO, tail);
    /* A PNG cut short: libpng's complaint, under the same prefix. */
    uint8_t px[16 * 16 * 4];
    for (size_t i = 0; i < sizeof px; i++)
        px[i] = (uint8_t)(i * 37);
    write_png("whole.png", px, 16, 16);
    FILE *f = fopen(at("whole.png"), "rb");
    cr_assert(f);
    uint8_t bytes[4096];
    const size_t n = fread(bytes, 1, sizeof bytes, f);
    fclose(f);
    f = fopen(at("cut.png"), "wb");
    fwrite(bytes, 1, n / 2, f);
    fclose(f);
    write_text("scene.json", "{ \"bodies\": [ { \"sprite\": \"cut.png\" } ] }");
    pp_world w = {7};
    cr_assert_eq(pp_world_load_scene(at("scene.json"), &w), PP_ERR_FORMAT, "%s", pp_last_error());
    snprintf(tail, sizeof tail, "pp_world_load_scene: '%s': bodies[0].sprite: '%s' is malformed: ", at("scene.json"),
             at("cut.png"));
    cr_assert(strncmp(pp_last_error(), tail, strlen(tail)) == 0, "%s", pp_last_error());
    cr_assert_eq(w.id, 7);
    dir_close();
}
