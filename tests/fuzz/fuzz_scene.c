/* libFuzzer target: scene files through pp_world_load_scene. The input is scene.json in a folder that also
 * holds small valid PNGs under the names the seeds use; a scene that loads is stepped through its edits and
 * every result a host reads (bodies, contacts, events, stats) is read and checked. */
#include "fuzz_common.h"

#include <cjson/cJSON.h>

/* Harness caps, not library limits: a box within PP_MAX_BITMAP_* is valid but a 16384² one takes seconds to
 * fill and step. Inputs asking for more solid box area than this in total are skipped. */
#define FUZZ_SCENE_MAX_BOX_AREA (1 << 17)
#define FUZZ_SCENE_MAX_STEPS 8

static char scene_dir[300], scene_path[320];

static void save_png(const char *name, int32_t w, int32_t h, int pattern)
{
    uint8_t *px = malloc((size_t)w * h * 4);
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++) {
            uint8_t *p = px + 4 * ((size_t)y * w + x);
            const int solid = pattern == 0 ? 1 : pattern == 1 ? y >= h / 3 : pattern == 2 ? (x + y) % 3 != 0 : pattern != 4;
            p[0] = pattern == 3 ? (uint8_t)(40 + 200 * x / w) : 200; /* pattern 3: a weights plane */
            p[1] = (uint8_t)(x * 16), p[2] = (uint8_t)(y * 16);
            p[3] = solid ? 255 : 0;
        }
    char path[400];
    snprintf(path, sizeof path, "%s/%s", scene_dir, name);
    FUZZ_CHECK(pp_image_save(path, px, w, h) == PP_OK, "%s", path);
    free(px);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    fuzz_no_gpu();
    snprintf(scene_dir, sizeof scene_dir, "%s/scene", fuzz_scratch());
    mkdir(scene_dir, 0700);
    snprintf(scene_path, sizeof scene_path, "%s/scene.json", scene_dir);
    /* The names demo/scene.json and tests/plugin/scene.json use, at small sizes. */
    save_png("terrain.png", 96, 24, 1);
    save_png("terrain_mask.png", 96, 24, 2);
    save_png("bridge.png", 40, 6, 0);
    save_png("hammer.png", 10, 18, 2);
    save_png("hammer_weights.png", 10, 18, 3);
    save_png("crate.png", 8, 8, 0);
    save_png("crate_small.png", 6, 6, 0);
    save_png("crate_big.png", 12, 12, 0);
    save_png("crate16.png", 16, 16, 0);
    save_png("empty.png", 4, 4, 4);
    /* And those of tests/c/test_scene.c. */
    save_png("sprite.png", 8, 6, 2);
    save_png("weights.png", 5, 3, 3);
    save_png("half.png", 10, 10, 1);
    save_png("solid.png", 6, 6, 0);
    return 0;
}

/* The solid area the scene's boxes ask for, or -1 when it does not parse (the library will refuse it). */
static int64_t box_area(const char *text, size_t len)
{
    cJSON *root = cJSON_ParseWithLength(text, len);
    if (!root)
        return -1;
    int64_t total = 0;
    const cJSON *bodies = cJSON_GetObjectItemCaseSensitive(root, "bodies");
    for (const cJSON *b = cJSON_IsArray(bodies) ? bodies->child : NULL; b; b = b->next) {
        const cJSON *box = cJSON_GetObjectItemCaseSensitive(b, "box");
        if (!cJSON_IsArray(box) || cJSON_GetArraySize(box) != 2)
            continue;
        const double w = cJSON_GetArrayItem(box, 0)->valuedouble, h = cJSON_GetArrayItem(box, 1)->valuedouble;
        if (w >= 1 && h >= 1 && w <= PP_MAX_BITMAP_SIDE && h <= PP_MAX_BITMAP_SIDE && w * h <= PP_MAX_BITMAP_AREA)
            total += (int64_t)(w * h);
    }
    cJSON_Delete(root);
    return total;
}

static void read_results(pp_world w)
{
    int32_t n = -1, m = -1;
    FUZZ_CHECK(ST(pp_world_get_bodies(w, NULL, 0, &n)) == PP_OK && n >= 0, "bodies");
    pp_body *bodies = malloc(((size_t)n + 1) * sizeof *bodies);
    FUZZ_CHECK(ST(pp_world_get_bodies(w, bodies, n, &m)) == PP_OK && m == n, "bodies again");
    for (int32_t i = 0; i < n; i++) {
        pp_vec2 p;
        int32_t bw, bh;
        FUZZ_CHECK(ST(pp_body_get_position(w, bodies[i], &p)) == PP_OK, "position of body %d", (int)i);
        FUZZ_CHECK(ST(pp_body_get_size(w, bodies[i], &bw, &bh)) == PP_OK && bw >= 1 && bh >= 1, "size");
    }
    free(bodies);
    pp_step_stats stats;
    FUZZ_CHECK(ST(pp_world_get_stats(w, &stats)) == PP_OK, "stats");
    FUZZ_CHECK(ST(pp_world_get_contacts(w, NULL, 0, &n)) == PP_OK && n >= 0, "contacts");
    pp_contact *contacts = malloc(((size_t)n + 1) * sizeof *contacts);
    FUZZ_CHECK(ST(pp_world_get_contacts(w, contacts, n, &m)) == PP_OK && m == n, "contacts again");
    free(contacts);
    pp_event ev[8];
    for (int k = 0; k < 64; k++) { /* drain in chunks */
        FUZZ_CHECK(ST(pp_world_get_events(w, ev, 8, &n)) == PP_OK && n >= 0, "events");
        if (n <= 8)
            break;
    }
    FUZZ_CHECK(ST(pp_world_get_events(w, NULL, 0, &n)) == PP_OK && n == 0, "events left: %d", (int)n);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (box_area((const char *)data, size) > FUZZ_SCENE_MAX_BOX_AREA)
        return 0;
    fuzz_write_file(scene_path, data, size);
    pp_world w = {0};
    const pp_status st = ST(pp_world_load_scene(scene_path, &w));
    FUZZ_CHECK(st != PP_ERR_INVALID_HANDLE && st != PP_ERR_ABI, "pp_world_load_scene: %d", (int)st);
    if (st != PP_OK)
        return 0;
    read_results(w);
    for (int i = 0; i < FUZZ_SCENE_MAX_STEPS && !fuzz_too_fast(w); i++) {
        /* Two ordinary steps, then long ones towards the next pending edit so the scene's edits run. */
        float dt = 1.0f / 60;
        if (i >= 2) {
            pp_timed_edit next;
            int32_t n = 0;
            double t = 0;
            FUZZ_CHECK(ST(pp_world_get_scheduled_edits(w, &next, 1, &n)) == PP_OK, "edits");
            if (n == 0)
                break;
            ST(pp_world_get_time(w, &t));
            dt = (float)(next.time - t);
            dt = dt > 1 ? 1 : dt < 1.0f / 60 ? 1.0f / 60 : dt;
        }
        const pp_status s = ST(pp_world_step(w, dt));
        FUZZ_CHECK(s == PP_OK || s == PP_ERR_OUT_OF_MEMORY || s == PP_ERR_UNSUPPORTED, "step: %d", (int)s);
        read_results(w);
    }
    FUZZ_CHECK(ST(pp_world_destroy(w)) == PP_OK, "destroy");
    FUZZ_CHECK(ST(pp_world_destroy(w)) == PP_ERR_INVALID_HANDLE, "destroyed twice");
    return 0;
}
