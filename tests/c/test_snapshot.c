/* Snapshots: a world saved mid-scene and loaded back steps on bit for bit as the original does (bodies
 * resting asleep and awake, a split body, a weighted body, a sprite, a timed edit still to come), the
 * folder appears whole or not at all, and broken snapshots are refused with their reason. */
#include "helpers.h"

#include "handle.h" /* handle_saved: a handle without its world, which a loaded world keeps */

#include <dirent.h>
#include <signal.h>
#include <sys/resource.h>

PP_TEST_SUITE(snapshot);

#define DT (1.0f / 60.0f)

/* Every live body's slot and generation (its handle but for the world), pose, velocity and sleep state, in slot
 * order. */
static uint64_t world_hash(pp_world w, uint64_t h)
{
    pp_body bodies[64];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 64, &n));
    cr_assert_leq(n, 64);
    h = fnv1a(h, &n, sizeof n);
    for (int32_t i = 0; i < n; i++) {
        pp_vec2 p, v;
        float a, av;
        int32_t awake;
        PP_OK_OR_FAIL(pp_body_get_position(w, bodies[i], &p));
        PP_OK_OR_FAIL(pp_body_get_angle(w, bodies[i], &a));
        PP_OK_OR_FAIL(pp_body_get_velocity(w, bodies[i], &v, &av));
        PP_OK_OR_FAIL(pp_body_is_awake(w, bodies[i], &awake));
        const uint64_t saved = handle_saved(bodies[i].id);
        h = fnv1a(h, &saved, sizeof saved);
        h = fnv1a(h, &p, sizeof p), h = fnv1a(h, &a, sizeof a), h = fnv1a(h, &v, sizeof v), h = fnv1a(h, &av, sizeof av);
        h = fnv1a(h, &awake, sizeof awake);
    }
    return h;
}

/* Step n times, hashing the world after each step. */
static uint64_t run_hashed(pp_world w, int n)
{
    uint64_t h = FNV_START;
    for (int i = 0; i < n; i++) {
        PP_OK_OR_FAIL(pp_world_step(w, DT));
        h = world_hash(w, h);
    }
    return h;
}

/* A ground with a detachable ledge, boxes of several sizes (one weighted, one with a sprite), a kinematic
 * paddle, a bar cut in two, and an explosion scheduled for later. */
static pp_world build_scene(void)
{
    pp_world w = make_world(0, 980);
    uint8_t *g = rect_mask(600, 40);
    pp_body_def d = body_def(PP_BODY_STATIC, 300, 420, 0);
    d.width = 600, d.height = 40, d.mask = g, d.detach_islands = 1;
    pp_body ground = create_body_ok(w, &d);
    free(g);
    static uint8_t weights[24 * 24], sprite[28 * 28 * 4];
    for (int i = 0; i < 24 * 24; i++)
        weights[i] = (uint8_t)(40 + (i % 24) * 9);
    for (int i = 0; i < 28 * 28; i++)
        sprite[4 * i] = (uint8_t)i, sprite[4 * i + 1] = 90, sprite[4 * i + 2] = (uint8_t)(i / 28), sprite[4 * i + 3] = 255;
    for (int i = 0; i < 8; i++) {
        const int size = 20 + 4 * (i % 3);
        uint8_t *m = rect_mask(size, size);
        d = body_def(PP_BODY_DYNAMIC, 120.0f + 45 * i + 7 * (i % 2), 360.0f - 40.0f * (i % 4), 0.1f * (i - 3));
        d.width = d.height = size, d.mask = m;
        d.weights = size == 24 ? weights : NULL;
        d.rgba = size == 28 ? sprite : NULL;
        d.angular_velocity = 0.5f * (i % 2 ? 1 : -1);
        d.user_data = 0xfeedface00000000ull + (uint64_t)i; /* over 2^53: must survive exactly */
        create_body_ok(w, &d);
        free(m);
    }
    uint8_t *bar = rect_mask(80, 10);
    d = body_def(PP_BODY_DYNAMIC, 420, 250, 0);
    d.width = 80, d.height = 10, d.mask = bar;
    pp_body b = create_body_ok(w, &d);
    free(bar);
    PP_OK_OR_FAIL(pp_body_erase_circle(w, b, v2(420, 250), 6, NULL)); /* splits it: a new slot, a bumped serial */
    uint8_t *paddle = rect_mask(40, 8);
    d = body_def(PP_BODY_KINEMATIC, 60, 300, 0);
    d.width = 40, d.height = 8, d.mask = paddle, d.linear_velocity = v2(30, 0), d.angular_velocity = 0.4f;
    create_body_ok(w, &d);
    free(paddle);
    const pp_timed_edit blast = {.time = 2.2, .type = PP_EDIT_ERASE_CIRCLE, .center = {300, 420}, .radius = 30};
    PP_OK_OR_FAIL(pp_world_schedule_edit(w, &blast));
    const pp_timed_edit fill = {.time = 2.5, .type = PP_EDIT_PAINT_CIRCLE, .weight = 200, .body = ground,
                                .center = {100, 395}, .radius = 8};
    PP_OK_OR_FAIL(pp_world_schedule_edit(w, &fill));
    return w;
}

static void temp_dir(char *path)
{
    strcpy(path, "/tmp/pp_snapshot_XXXXXX");
    cr_assert_not_null(mkdtemp(path));
}

Test(snapshot, a_loaded_world_continues_bit_for_bit, .timeout = 120)
{
    char dir[64], snap[96];
    temp_dir(dir);
    snprintf(snap, sizeof snap, "%s/save1", dir);
    pp_world w = build_scene();
    /* 1.5 s: the early boxes have landed and some sleep; the blast at 2.2 s is still to come. */
    run_hashed(w, 90);
    int32_t asleep = 0, nb = 0;
    pp_body bodies[64];
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 64, &nb));
    for (int32_t i = 0; i < nb; i++) {
        int32_t awake;
        pp_body_type type;
        PP_OK_OR_FAIL(pp_body_is_awake(w, bodies[i], &awake));
        PP_OK_OR_FAIL(pp_body_get_type(w, bodies[i], &type));
        asleep += type == PP_BODY_DYNAMIC && !awake;
    }
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));
    cr_assert_eq(count_entries(dir), 1, "only the snapshot folder is left beside it, no temporary");

    pp_world back;
    PP_OK_OR_FAIL(pp_world_load_snapshot(snap, &back));
    cr_assert_eq(world_hash(back, 0), world_hash(w, 0), "the loaded state differs before stepping");
    /* The loaded bodies are in the same slots, but their handles name the loaded world. */
    pp_body loaded[64];
    int32_t nl = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(back, loaded, 64, &nl));
    cr_assert_eq(nl, nb);
    const uint64_t h_orig = run_hashed(w, 180), h_back = run_hashed(back, 180);
    cr_log_info("snapshot: %d bodies (%d asleep) at save; continuation hash %016llx", (int)nb, (int)asleep,
                (unsigned long long)h_orig);
    cr_assert_eq(h_back, h_orig, "continuing from the snapshot gives %016llx, the original %016llx",
                 (unsigned long long)h_back, (unsigned long long)h_orig);
    /* Not vacuous: bodies slept at the save, and the scheduled blast split the ground afterwards. */
    cr_assert_gt(asleep, 0, "no body slept by the save: the sleep state went untested");
    pp_event ev[16];
    int32_t ne = 0, splits = 0;
    PP_OK_OR_FAIL(pp_world_get_events(back, ev, 16, &ne));
    for (int32_t i = 0; i < ne && i < 16; i++)
        splits += ev[i].type == PP_EVENT_BODY_SPLIT;
    cr_assert_gt(splits, 1, "the split at build time and the later blast should both show");
    EXPECT_ERR(pp_body_get_user_data(back, bodies[1], &(uint64_t){0}), PP_ERR_INVALID_HANDLE, "belongs to world");
    uint64_t user;
    PP_OK_OR_FAIL(pp_body_get_user_data(back, loaded[1], &user));
    cr_assert_eq(user, 0xfeedface00000000ull);
    pp_world_destroy(w);
    pp_world_destroy(back);
    remove_tree(dir);
}

Test(snapshot, saving_over_a_snapshot_replaces_it_and_other_folders_are_refused)
{
    char dir[64], snap[96], other[96], keep[128];
    temp_dir(dir);
    snprintf(snap, sizeof snap, "%s/slot", dir);
    snprintf(other, sizeof other, "%s/photos", dir);
    pp_world w = build_scene();
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));
    run_hashed(w, 30);
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap)); /* over the first */
    cr_assert_eq(count_entries(dir), 1, "the old snapshot and the temporary are gone");
    pp_world back;
    PP_OK_OR_FAIL(pp_world_load_snapshot(snap, &back));
    double t = 0;
    PP_OK_OR_FAIL(pp_world_get_time(back, &t));
    cr_assert(fabs(t - 0.5) < 1e-6, "the second save (t = 0.5 s) is the one kept, got t = %g", t);
    pp_world_destroy(back);

    mkdir(other, 0700);
    snprintf(keep, sizeof keep, "%s/holiday.jpg", other);
    FILE *f = fopen(keep, "w");
    fputs("precious", f);
    fclose(f);
    EXPECT_ERR(pp_world_save_snapshot(w, other), PP_ERR_IO, "not a snapshot");
    cr_assert_eq(count_entries(other), 1, "the folder that is not a snapshot was touched");
    cr_assert_eq(count_entries(dir), 2, "a refused save left its temporary behind");
    EXPECT_ERR(pp_world_save_snapshot(w, "/nonexistent-dir/snap"), PP_ERR_IO, "'/nonexistent-dir' does not exist");
    EXPECT_ERR(pp_world_save_snapshot(w, NULL), PP_ERR_INVALID_ARGUMENT, "NULL");
    pp_world_destroy(w);
    EXPECT_ERR(pp_world_save_snapshot(w, snap), PP_ERR_INVALID_HANDLE, "stale");
    remove_tree(dir);
}

/* A save never creates the folder's parent; the message names that parent, the part of the path to fix. */
Test(snapshot, a_save_whose_parent_folder_is_missing_names_the_parent)
{
    char dir[64], snap[160], parent[128], file[96], under_file[128];
    temp_dir(dir);
    snprintf(parent, sizeof parent, "%s/missing/deeper", dir);
    snprintf(snap, sizeof snap, "%s/snap/", parent); /* a trailing slash is still the folder "snap" */
    pp_world w = build_scene();
    EXPECT_ERR(pp_world_save_snapshot(w, snap), PP_ERR_IO, "does not exist");
    char want[192];
    snprintf(want, sizeof want, "its parent folder '%s' does not exist", parent);
    cr_assert(strstr(pp_last_error(), want), "\"%s\" does not name the parent '%s'", pp_last_error(), parent);
    cr_assert_eq(count_entries(dir), 0, "a failed save created something");

    snprintf(file, sizeof file, "%s/notes.txt", dir);
    FILE *f = fopen(file, "w");
    fclose(f);
    snprintf(under_file, sizeof under_file, "%s/snap", file);
    EXPECT_ERR(pp_world_save_snapshot(w, under_file), PP_ERR_IO, "is not a folder");
    cr_assert(strstr(pp_last_error(), file), "\"%s\" does not name '%s'", pp_last_error(), file);

    snprintf(snap, sizeof snap, "%s/snap", dir); /* and where the parent exists, the save succeeds */
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));
    pp_world_destroy(w);
    remove_tree(dir);
}

/* A timed edit whose body was destroyed before it came due is a no-op, and one scheduled before time 0 is
 * due at once; the snapshot still loads (the fuzzer found snapshots with either that could not be loaded). */
Test(snapshot, edits_on_a_destroyed_body_or_before_time_0_do_not_break_the_snapshot)
{
    char dir[64], snap[96];
    temp_dir(dir);
    snprintf(snap, sizeof snap, "%s/slot", dir);
    pp_world w = make_world(0, 980);
    pp_body a = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 8, 8);
    add_rect(w, body_def(PP_BODY_STATIC, 100, 200, 0), 40, 8);
    pp_timed_edit e = {.time = 1.0, .type = PP_EDIT_ERASE_CIRCLE, .body = a, .center = {100, 100}, .radius = 3};
    PP_OK_OR_FAIL(pp_world_schedule_edit(w, &e));
    e.body = (pp_body){0}, e.time = -1.0;
    PP_OK_OR_FAIL(pp_world_schedule_edit(w, &e));
    PP_OK_OR_FAIL(pp_body_destroy(w, a));
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));
    pp_world back;
    PP_OK_OR_FAIL(pp_world_load_snapshot(snap, &back));
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(back, NULL, 0, &n));
    cr_assert_eq(n, 1, "the edit on every body is kept, the one on the destroyed body dropped: %d", (int)n);
    PP_OK_OR_FAIL(pp_world_get_bodies(back, NULL, 0, &n));
    cr_assert_eq(n, 1);
    pp_world_destroy(back);
    pp_world_destroy(w);
    remove_tree(dir);
}

/* Replace the first occurrence of `from` in the snapshot's world.json by `to`. */
/* Files may grow to `bytes` at most from here on (RLIMIT_FSIZE); a write past it fails with EFBIG. */
static void limit_file_size(rlim_t bytes)
{
    struct rlimit lim;
    cr_assert_eq(getrlimit(RLIMIT_FSIZE, &lim), 0);
    lim.rlim_cur = bytes;
    cr_assert_eq(setrlimit(RLIMIT_FSIZE, &lim), 0);
}

/* The disk fills while a snapshot is written: the save fails with PP_ERR_IO, the snapshot saved before
 * is still there and loads to the state it was saved in, and nothing is left beside it. */
Test(snapshot, a_save_that_fails_part_way_keeps_the_previous_snapshot)
{
    signal(SIGXFSZ, SIG_IGN); /* a write past the limit returns EFBIG instead of ending the process */
    char dir[64], snap[96];
    temp_dir(dir);
    snprintf(snap, sizeof snap, "%s/snap", dir);
    pp_world w = build_scene();
    step_n(w, DT, 30);
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));
    const uint64_t saved = world_hash(w, 0);
    const int files = count_entries(snap);
    /* A noisy weight plane makes a body whose PNG cannot fit under the limit. */
    uint8_t *mask = rect_mask(256, 256), *weights = malloc(256 * 256);
    uint32_t x = 2463534242u; /* xorshift: noise that deflate cannot shrink */
    for (int i = 0; i < 256 * 256; i++) {
        x ^= x << 13, x ^= x >> 17, x ^= x << 5;
        weights[i] = (uint8_t)(1 + x % 255);
    }
    pp_body_def d = body_def(PP_BODY_STATIC, 300, 900, 0);
    d.width = d.height = 256, d.mask = mask, d.weights = weights;
    create_body_ok(w, &d);
    free(mask), free(weights);
    step_n(w, DT, 10);

    limit_file_size(16 * 1024);
    EXPECT_ERR(pp_world_save_snapshot(w, snap), PP_ERR_IO, "cannot write|File too large");
    limit_file_size(RLIM_INFINITY);
    cr_assert_eq(count_entries(snap), files, "the old snapshot lost or gained files");
    cr_assert_eq(count_entries(dir), 1, "the failed save left %d entries beside the snapshot", count_entries(dir) - 1);
    pp_world back = {0};
    PP_OK_OR_FAIL(pp_world_load_snapshot(snap, &back));
    cr_assert_eq(world_hash(back, 0), saved, "the snapshot no longer loads to the state it was saved in");
    PP_OK_OR_FAIL(pp_world_destroy(back));
    PP_OK_OR_FAIL(pp_world_destroy(w));
    remove_tree(dir);
}

/* The same for one image: a failed pp_image_save keeps the file it would have replaced. */
Test(snapshot, an_image_save_that_fails_keeps_the_old_file)
{
    signal(SIGXFSZ, SIG_IGN);
    char dir[64], path[96];
    temp_dir(dir);
    snprintf(path, sizeof path, "%s/a.png", dir);
    uint8_t small[4 * 4 * 4], *noise = malloc(512 * 512 * 4), back[4 * 4 * 4];
    for (int i = 0; i < 4 * 4 * 4; i++)
        small[i] = (uint8_t)(i * 7);
    uint32_t x = 2463534242u; /* xorshift: noise that deflate cannot shrink */
    for (int i = 0; i < 512 * 512 * 4; i++) {
        x ^= x << 13, x ^= x >> 17, x ^= x << 5;
        noise[i] = (uint8_t)x;
    }
    PP_OK_OR_FAIL(pp_image_save(path, small, 4, 4));
    limit_file_size(16 * 1024);
    EXPECT_ERR(pp_image_save(path, noise, 512, 512), PP_ERR_IO, "cannot write");
    limit_file_size(RLIM_INFINITY);
    int32_t w = 0, h = 0;
    PP_OK_OR_FAIL(pp_image_load(path, back, (int64_t)sizeof back, &w, &h));
    cr_assert(w == 4 && h == 4 && memcmp(back, small, sizeof small) == 0, "the old image changed");
    cr_assert_eq(count_entries(dir), 1, "the failed save left its temporary file");
    free(noise);
    remove_tree(dir);
}

Test(snapshot, broken_snapshots_are_refused_with_their_reason)
{
    char dir[64], snap[96], path[160];
    temp_dir(dir);
    snprintf(snap, sizeof snap, "%s/s", dir);
    pp_world w = build_scene(), out = {12345};
    const pp_world untouched = out;
    EXPECT_ERR(pp_world_load_snapshot(snap, &out), PP_ERR_IO, "cannot open");
    EXPECT_ERR(pp_world_load_snapshot(NULL, &out), PP_ERR_INVALID_ARGUMENT, "NULL");
    EXPECT_ERR(pp_world_load_snapshot(snap, NULL), PP_ERR_INVALID_ARGUMENT, "NULL");
    const struct { const char *from, *to; pp_status st; const char *words; } cases[] = {
        {"\"physpix-snapshot\"", "\"physpix-scene\"", PP_ERR_FORMAT, "format: expected \"physpix-snapshot\""},
        {"\"version\":\t1", "\"version\":\t2", PP_ERR_UNSUPPORTED, "reads version 1"},
        {"\"handle\":\t\"0x", "\"handle\":\t\"zz", PP_ERR_FORMAT, "bodies[0].handle: expected a handle"},
        {"\"generations\":\t[", "\"generations\":\t[0, ", PP_ERR_FORMAT, "generations"},
        {"\"pose\":\t[", "\"pose\":\t[1, ", PP_ERR_FORMAT, "bodies[0].state.pose: expected 5 finite numbers"},
        {"\"density\":\t1", "\"density\":\t-1", PP_ERR_FORMAT, "density: expected a number > 0"},
        {"\"slow_time\"", "\"slow_tim\"", PP_ERR_FORMAT, "slow_tim: unknown key"},
        {"{", "[", PP_ERR_FORMAT, "invalid JSON"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        remove_tree(snap);
        PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));
        patch_json(snap, cases[i].from, cases[i].to);
        EXPECT_ERR(pp_world_load_snapshot(snap, &out), cases[i].st, cases[i].words);
        cr_assert_eq(out.id, untouched.id, "case %zu: a failed load wrote *out", i);
    }
    /* A plane PNG cut short keeps the PNG loader's status, under the body's JSON path. */
    remove_tree(snap);
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));
    snprintf(path, sizeof path, "%s/body1_mask.png", snap);
    cr_assert_eq(truncate(path, 40), 0);
    EXPECT_ERR(pp_world_load_snapshot(snap, &out), PP_ERR_FORMAT, "bodies[1].mask");
    cr_assert_eq(out.id, untouched.id);
    pp_world_destroy(w);
    remove_tree(dir);
}
