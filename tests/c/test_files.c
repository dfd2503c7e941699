/* Files a scene or snapshot names: a snapshot save never follows a symlink planted at its target, its
 * temporary or its old folder (a thread swaps them for links to a decoy folder during 200 saves, and the
 * decoy must come out untouched), an old snapshot is removed whole, PNG paths and snapshot planes are read
 * only from inside the folder of the file that names them (one message whatever the reason), and a FIFO
 * anywhere a file is read is refused at once instead of blocking the loader. */
#define _GNU_SOURCE /* renameat2 */
#include "helpers.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdatomic.h>
#include <sys/stat.h>
#include <sys/types.h>

PP_TEST_SUITE(files);

static char root[64];

static void root_open(void)
{
    snprintf(root, sizeof root, "/tmp/pp_files_XXXXXX");
    cr_assert(mkdtemp(root), "mkdtemp failed");
}

/* Remove root (remove_tree does not follow links). */
static void root_close(void) { remove_tree(root); }

/* root/<name> (in a static buffer of eight, so a call may use a few). */
static const char *at(const char *name)
{
    static char buf[8][512];
    static int k;
    k = (k + 1) % 8;
    snprintf(buf[k], sizeof buf[k], "%s/%s", root, name);
    return buf[k];
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    cr_assert(f, "cannot write %s", path);
    fputs(text, f);
    fclose(f);
}

static void write_png(const char *path, int w, int h)
{
    uint8_t px[16 * 16 * 4];
    cr_assert(w * h <= 16 * 16);
    memset(px, 255, sizeof px);
    PP_OK_OR_FAIL(pp_image_save(path, px, w, h));
}

/* A small world worth saving: a ground, two boxes, one weighted. */
static pp_world small_world(void)
{
    pp_world w = make_world(0, 980);
    add_rect(w, body_def(PP_BODY_STATIC, 100, 200, 0), 60, 8);
    add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 150, 0), 8, 8);
    uint8_t *m = rect_mask(6, 6), weights[36];
    for (int i = 0; i < 36; i++)
        weights[i] = (uint8_t)(10 + 7 * i);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 120, 150, 0);
    d.width = d.height = 6, d.mask = m, d.weights = weights;
    create_body_ok(w, &d);
    free(m);
    return w;
}

/* ---- the decoy: a folder that looks like a snapshot, whose files must never change ---------------- */

#define DECOY_FILES 12

static void decoy_make(const char *dir)
{
    cr_assert_eq(mkdir(dir, 0700), 0);
    char path[600], text[64];
    for (int i = 0; i < DECOY_FILES; i++) {
        if (i == 0)
            snprintf(path, sizeof path, "%s/world.json", dir);
        else
            snprintf(path, sizeof path, "%s/body%d_mask.png", dir, i - 1);
        snprintf(text, sizeof text, "decoy %d", i);
        write_text(path, text);
    }
}

/* Asserts the decoy holds exactly its files with their texts. */
static void decoy_check(const char *dir, const char *when)
{
    cr_assert_eq(count_entries(dir), DECOY_FILES, "%s: the decoy holds %d entries, not %d", when, count_entries(dir), DECOY_FILES);
    char path[600], want[64], got[64];
    for (int i = 0; i < DECOY_FILES; i++) {
        if (i == 0)
            snprintf(path, sizeof path, "%s/world.json", dir);
        else
            snprintf(path, sizeof path, "%s/body%d_mask.png", dir, i - 1);
        snprintf(want, sizeof want, "decoy %d", i);
        FILE *f = fopen(path, "rb");
        cr_assert(f, "%s: %s is gone", when, path);
        const size_t n = fread(got, 1, sizeof got - 1, f);
        fclose(f);
        got[n] = 0;
        cr_assert_str_eq(got, want, "%s: %s changed", when, path);
    }
}

/* ---- the swap during saves ------------------------------------------------------------------------ */

typedef struct swapper {
    char dir[96], slot[128], link[128], link2[128];
    atomic_int stop;
    atomic_long swaps;
} swapper;

/* Over and over: exchange the target folder with a link to the decoy, and any temporary or old folder
 * beside it (*.tmp-*) with another such link, then put them back. */
static void *swap_loop(void *arg)
{
    swapper *s = arg;
    char tmp[512];
    while (!atomic_load(&s->stop)) {
        if (renameat2(AT_FDCWD, s->slot, AT_FDCWD, s->link, RENAME_EXCHANGE) == 0) {
            atomic_fetch_add(&s->swaps, 1);
            for (volatile int i = 0; i < 200; i++) {
            }
            renameat2(AT_FDCWD, s->slot, AT_FDCWD, s->link, RENAME_EXCHANGE);
        }
        DIR *d = opendir(s->dir);
        for (struct dirent *e; d && (e = readdir(d));) {
            if (!strstr(e->d_name, ".tmp-"))
                continue;
            snprintf(tmp, sizeof tmp, "%s/%s", s->dir, e->d_name);
            if (renameat2(AT_FDCWD, tmp, AT_FDCWD, s->link2, RENAME_EXCHANGE) == 0) {
                atomic_fetch_add(&s->swaps, 1);
                for (volatile int i = 0; i < 200; i++) {
                }
                renameat2(AT_FDCWD, tmp, AT_FDCWD, s->link2, RENAME_EXCHANGE);
            }
        }
        if (d)
            closedir(d);
    }
    return NULL;
}

Test(files, a_symlink_swapped_in_during_saves_never_touches_the_folder_it_points_to, .timeout = 300)
{
    root_open();
    const char *decoy = at("decoy");
    decoy_make(decoy);
    swapper s = {0};
    snprintf(s.dir, sizeof s.dir, "%s/saves", root);
    cr_assert_eq(mkdir(s.dir, 0700), 0);
    snprintf(s.slot, sizeof s.slot, "%s/slot", s.dir);
    snprintf(s.link, sizeof s.link, "%s/link", s.dir);
    snprintf(s.link2, sizeof s.link2, "%s/link2", s.dir);
    cr_assert_eq(symlink(decoy, s.link), 0);
    cr_assert_eq(symlink(decoy, s.link2), 0);
    pp_world w = small_world();
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, s.slot));
    pthread_t t;
    cr_assert_eq(pthread_create(&t, NULL, swap_loop, &s), 0);
    int ok = 0, failed = 0;
    for (int i = 0; i < 200; i++) {
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
        const pp_status st = pp_world_save_snapshot(w, s.slot);
        cr_assert(st == PP_OK || st == PP_ERR_IO, "save %d: %s (%s)", i, pp_status_name(st), pp_last_error());
        ok += st == PP_OK, failed += st != PP_OK;
    }
    atomic_store(&s.stop, 1);
    pthread_join(t, NULL);
    cr_log_info("200 saves under %ld swaps: %d saved, %d refused", (long)atomic_load(&s.swaps), ok, failed);
    decoy_check(decoy, "after 200 saves with swaps");
    cr_assert_gt(atomic_load(&s.swaps), 0, "the swapping thread never swapped");
    pp_world_destroy(w);
    root_close();
}

Test(files, a_replaced_snapshot_holding_a_subfolder_or_a_link_is_removed_whole)
{
    root_open();
    const char *snap = at("snaps/slot"), *decoy = at("decoy");
    decoy_make(decoy);
    cr_assert_eq(mkdir(at("snaps"), 0700), 0);
    pp_world w = small_world();
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));
    /* Things a user or a tool left inside the old snapshot: a subfolder two deep, and links out. */
    char path[600];
    snprintf(path, sizeof path, "%s/extra", snap);
    cr_assert_eq(mkdir(path, 0700), 0);
    snprintf(path, sizeof path, "%s/extra/deeper", snap);
    cr_assert_eq(mkdir(path, 0700), 0);
    snprintf(path, sizeof path, "%s/extra/deeper/note.txt", snap);
    write_text(path, "note");
    snprintf(path, sizeof path, "%s/extra/to_decoy", snap);
    cr_assert_eq(symlink(decoy, path), 0);
    snprintf(path, sizeof path, "%s/decoy_file", snap);
    cr_assert_eq(symlink(at("decoy/world.json"), path), 0);
    PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));
    cr_assert_eq(count_entries(at("snaps")), 1, "the replaced snapshot left %d entries beside the new one",
                 count_entries(at("snaps")) - 1);
    snprintf(path, sizeof path, "%s/extra", snap);
    cr_assert_neq(access(path, F_OK), 0, "the new snapshot holds the old one's subfolder");
    decoy_check(decoy, "after replacing a snapshot that linked to it");
    pp_world back;
    PP_OK_OR_FAIL(pp_world_load_snapshot(snap, &back));
    pp_world_destroy(back);
    pp_world_destroy(w);
    root_close();
}

Test(files, a_link_at_the_target_is_not_followed)
{
    root_open();
    const char *decoy = at("decoy");
    decoy_make(decoy);
    cr_assert_eq(symlink(decoy, at("slot")), 0);
    pp_world w = small_world();
    EXPECT_ERR(pp_world_save_snapshot(w, at("slot")), PP_ERR_IO, "not a snapshot");
    decoy_check(decoy, "after a save at a link to it");
    struct stat sb;
    cr_assert(lstat(at("slot"), &sb) == 0 && S_ISLNK(sb.st_mode), "the link is gone");
    cr_assert_eq(count_entries(root), 2, "a refused save left its temporary folder");
    pp_world_destroy(w);
    root_close();
}

/* ---- confinement ---------------------------------------------------------------------------------- */

/* A scene in root/scene/ whose one body's sprite is `png`; asserts PP_ERR_IO with the one message. */
static void scene_png_refused(const char *png, const char *shown)
{
    char json[800], want[1600];
    snprintf(json, sizeof json, "{ \"bodies\": [ { \"sprite\": \"%s\" } ] }", png);
    write_text(at("scene/scene.json"), json);
    pp_world w = {0xABCDu};
    const pp_status st = pp_world_load_scene(at("scene/scene.json"), &w);
    cr_assert_eq(st, PP_ERR_IO, "'%s' -> %s (%s)", png, pp_status_name(st), pp_last_error());
    snprintf(want, sizeof want,
             "pp_world_load_scene: '%s': bodies[0].sprite: cannot open '%s': missing, unreadable, not a regular "
             "file, or outside '%s/'",
             at("scene/scene.json"), shown, at("scene"));
    cr_assert_str_eq(pp_last_error(), want);
    cr_assert_eq(w.id, 0xABCDu, "out was written on failure");
}

static void scene_png_loads(const char *png, int32_t want_w)
{
    char json[800];
    snprintf(json, sizeof json, "{ \"bodies\": [ { \"sprite\": \"%s\" } ] }", png);
    write_text(at("scene/scene.json"), json);
    pp_world w = {0};
    PP_OK_OR_FAIL(pp_world_load_scene(at("scene/scene.json"), &w));
    pp_body b;
    int32_t n = 0, bw = 0, bh = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, &b, 1, &n));
    cr_assert_eq(n, 1);
    PP_OK_OR_FAIL(pp_body_get_size(w, b, &bw, &bh));
    cr_assert_eq(bw, want_w, "'%s' loaded a %d px wide body, not %d", png, (int)bw, (int)want_w);
    pp_world_destroy(w);
}

/* root/scene/ with in.png (4 px wide), sub/deep.png (5 px) and links; root/out.png (3 px) and out.txt. */
static void confinement_fixture(void)
{
    root_open();
    cr_assert_eq(mkdir(at("scene"), 0700), 0);
    cr_assert_eq(mkdir(at("scene/sub"), 0700), 0);
    write_png(at("scene/in.png"), 4, 4);
    write_png(at("scene/sub/deep.png"), 5, 5);
    write_png(at("out.png"), 3, 3);
    write_text(at("out.txt"), "not a png, outside");
    cr_assert_eq(symlink("../out.png", at("scene/up_link.png")), 0);
    cr_assert_eq(symlink(at("out.png"), at("scene/abs_link.png")), 0);
    cr_assert_eq(symlink("sub", at("scene/sub_link")), 0);
    cr_assert_eq(symlink("..", at("scene/sub/parent")), 0);
    cr_assert_eq(symlink("../in.png", at("scene/sub/up_inside.png")), 0);
    cr_assert_eq(symlink("sub/deep.png", at("scene/alias.png")), 0);
    cr_assert_eq(symlink("../../out.png", at("scene/sub/up_out.png")), 0);
}

Test(files, a_scene_reads_pngs_only_from_inside_its_folder)
{
    confinement_fixture();
    char shown[600];
    /* An absolute path, even one naming a file inside the folder. */
    scene_png_refused(at("out.png"), at("out.png"));
    scene_png_refused(at("scene/in.png"), at("scene/in.png"));
    /* A ".." component, even one that comes back in. */
    snprintf(shown, sizeof shown, "%s/../out.png", at("scene"));
    scene_png_refused("../out.png", shown);
    snprintf(shown, sizeof shown, "%s/sub/../in.png", at("scene"));
    scene_png_refused("sub/../in.png", shown);
    /* Links leading out: relative, absolute, through a linked folder. */
    snprintf(shown, sizeof shown, "%s/up_link.png", at("scene"));
    scene_png_refused("up_link.png", shown);
    snprintf(shown, sizeof shown, "%s/abs_link.png", at("scene"));
    scene_png_refused("abs_link.png", shown);
    snprintf(shown, sizeof shown, "%s/sub/up_out.png", at("scene"));
    scene_png_refused("sub/up_out.png", shown);
    snprintf(shown, sizeof shown, "%s/sub/parent/../out.png", at("scene"));
    scene_png_refused("sub/parent/../out.png", shown);
    /* Inside: a subfolder, a link to a file inside, a link that climbs but stays inside, a linked folder. */
    scene_png_loads("in.png", 4);
    scene_png_loads("sub/deep.png", 5);
    scene_png_loads("./sub//deep.png", 5);
    scene_png_loads("alias.png", 5);
    scene_png_loads("sub/up_inside.png", 4);
    scene_png_loads("sub_link/deep.png", 5);
    scene_png_loads("sub/parent/in.png", 4);
    root_close();
}

/* A scene cannot tell a missing file from one outside that exists, or from a non-PNG outside. */
Test(files, missing_and_outside_get_the_same_message)
{
    confinement_fixture();
    char shown[600];
    snprintf(shown, sizeof shown, "%s/../out.txt", at("scene"));
    scene_png_refused("../out.txt", shown);
    snprintf(shown, sizeof shown, "%s/../no_such.txt", at("scene"));
    scene_png_refused("../no_such.txt", shown);
    snprintf(shown, sizeof shown, "%s/missing.png", at("scene"));
    scene_png_refused("missing.png", shown);
    /* A folder inside is not a regular file. */
    snprintf(shown, sizeof shown, "%s/sub", at("scene"));
    scene_png_refused("sub", shown);
    /* Unreadable (only meaningful when not root, who reads anything). */
    if (geteuid() != 0) {
        write_png(at("scene/locked.png"), 2, 2);
        cr_assert_eq(chmod(at("scene/locked.png"), 0), 0);
        snprintf(shown, sizeof shown, "%s/locked.png", at("scene"));
        scene_png_refused("locked.png", shown);
    }
    root_close();
}

/* A snapshot whose first mask plane is renamed `plane` in world.json; asserts the refusal. */
static void snapshot_plane_refused(pp_world w, const char *plane, const char *shown)
{
    const char *snap = at("snap");
    remove_tree(snap);
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));
    char json[600], to[600], want[1600];
    snprintf(json, sizeof json, "%s/world.json", snap);
    snprintf(to, sizeof to, "\"%s\"", plane);
    patch_file(json, "\"body0_mask.png\"", to);
    pp_world out = {0xABCDu};
    const pp_status st = pp_world_load_snapshot(snap, &out);
    cr_assert_eq(st, PP_ERR_IO, "'%s' -> %s (%s)", plane, pp_status_name(st), pp_last_error());
    snprintf(want, sizeof want,
             "pp_world_load_snapshot: '%s': bodies[0].mask: cannot open '%s': missing, unreadable, not a regular "
             "file, or outside '%s/'",
             json, shown, snap);
    cr_assert_str_eq(pp_last_error(), want);
    cr_assert_eq(out.id, 0xABCDu);
}

Test(files, a_snapshot_reads_planes_only_from_inside_its_folder)
{
    root_open();
    write_png(at("out.png"), 8, 8);
    pp_world w = make_world(0, 980);
    add_rect(w, body_def(PP_BODY_STATIC, 100, 200, 0), 8, 8);
    char shown[600];
    snapshot_plane_refused(w, at("out.png"), at("out.png"));
    snprintf(shown, sizeof shown, "%s/../out.png", at("snap"));
    snapshot_plane_refused(w, "../out.png", shown);
    /* A plane replaced by a link out. */
    remove_tree(at("snap"));
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, at("snap")));
    cr_assert_eq(unlink(at("snap/body0_mask.png")), 0);
    cr_assert_eq(symlink("../out.png", at("snap/body0_mask.png")), 0);
    pp_world out = {0xABCDu};
    EXPECT_ERR(pp_world_load_snapshot(at("snap"), &out), PP_ERR_IO, "bodies[0].mask: cannot open");
    cr_assert(strstr(pp_last_error(), at("snap/body0_mask.png")), "%s", pp_last_error());
    /* world.json itself a link out. */
    write_text(at("world.json"), "{}");
    cr_assert_eq(unlink(at("snap/world.json")), 0);
    cr_assert_eq(symlink("../world.json", at("snap/world.json")), 0);
    EXPECT_ERR(pp_world_load_snapshot(at("snap"), &out), PP_ERR_IO, "cannot open");
    cr_assert(strstr(pp_last_error(), at("snap/world.json")), "%s", pp_last_error());
    cr_assert_eq(out.id, 0xABCDu);
    /* A link inside that stays inside is read. */
    remove_tree(at("snap"));
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, at("snap")));
    cr_assert_eq(rename(at("snap/body0_mask.png"), at("snap/real.png")), 0);
    cr_assert_eq(symlink("real.png", at("snap/body0_mask.png")), 0);
    PP_OK_OR_FAIL(pp_world_load_snapshot(at("snap"), &out));
    pp_world_destroy(out);
    pp_world_destroy(w);
    root_close();
}

/* ---- FIFOs: refused at once, never waited on --------------------------------------------------------- */

Test(files, a_fifo_as_the_scene_file_is_refused_at_once, .timeout = 10)
{
    root_open();
    cr_assert_eq(mkfifo(at("scene.json"), 0600), 0);
    pp_world w = {7};
    cr_assert_eq(pp_world_load_scene(at("scene.json"), &w), PP_ERR_IO, "%s", pp_last_error());
    char want[600];
    snprintf(want, sizeof want, "pp_world_load_scene: '%s': cannot open: not a regular file", at("scene.json"));
    cr_assert_str_eq(pp_last_error(), want);
    cr_assert_eq(w.id, 7);
    root_close();
}

Test(files, a_fifo_as_a_png_path_is_refused_at_once, .timeout = 10)
{
    root_open();
    cr_assert_eq(mkdir(at("scene"), 0700), 0);
    cr_assert_eq(mkfifo(at("scene/pipe.png"), 0600), 0);
    char shown[600];
    snprintf(shown, sizeof shown, "%s/pipe.png", at("scene"));
    scene_png_refused("pipe.png", shown);
    root_close();
}

Test(files, a_fifo_as_a_snapshot_plane_or_world_json_is_refused_at_once, .timeout = 10)
{
    root_open();
    pp_world w = small_world();
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, at("snap")));
    cr_assert_eq(unlink(at("snap/body1_mask.png")), 0);
    cr_assert_eq(mkfifo(at("snap/body1_mask.png"), 0600), 0);
    pp_world out = {7};
    EXPECT_ERR(pp_world_load_snapshot(at("snap"), &out), PP_ERR_IO, "bodies[1].mask: cannot open");
    cr_assert_eq(unlink(at("snap/world.json")), 0);
    cr_assert_eq(mkfifo(at("snap/world.json"), 0600), 0);
    EXPECT_ERR(pp_world_load_snapshot(at("snap"), &out), PP_ERR_IO, "cannot open");
    cr_assert_eq(out.id, 7);
    pp_world_destroy(w);
    root_close();
}

Test(files, pp_image_load_and_info_refuse_a_fifo_or_a_device_at_once, .timeout = 10)
{
    root_open();
    cr_assert_eq(mkfifo(at("pipe.png"), 0600), 0);
    uint8_t px[64];
    int32_t w = 0, h = 0;
    char want[600];
    snprintf(want, sizeof want, "pp_image_load: cannot open '%s': not a regular file", at("pipe.png"));
    cr_assert_eq(pp_image_load(at("pipe.png"), px, sizeof px, &w, &h), PP_ERR_IO, "%s", pp_last_error());
    cr_assert_str_eq(pp_last_error(), want);
    snprintf(want, sizeof want, "pp_image_info: cannot open '%s': not a regular file", at("pipe.png"));
    cr_assert_eq(pp_image_info(at("pipe.png"), &w, &h), PP_ERR_IO, "%s", pp_last_error());
    cr_assert_str_eq(pp_last_error(), want);
    EXPECT_ERR(pp_image_info("/dev/zero", &w, &h), PP_ERR_IO, "not a regular file");
    EXPECT_ERR(pp_image_load(root, px, sizeof px, &w, &h), PP_ERR_IO, "not a regular file");
    root_close();
}

/* ---- the fallback without openat2 (the library's objects only: the shared library exports pp_* alone) --- */

#ifdef PP_TEST_PRIVATE
#include "files.h"

/* files_open_beneath_walk, which kernels before Linux 5.6 get, allows and refuses what openat2 does. */
Test(files, the_walk_without_openat2_confines_as_openat2_does, .timeout = 10)
{
    confinement_fixture();
    cr_assert_eq(symlink("loop.png", at("scene/loop.png")), 0);
    cr_assert_eq(mkfifo(at("scene/pipe.png"), 0600), 0);
    const int dir = open(at("scene"), O_RDONLY | O_DIRECTORY);
    cr_assert(dir >= 0);
    static const struct { const char *name; int inside; int outside; } cases[] = {
        {"in.png", 1, 0}, {"sub/deep.png", 1, 0}, {"./sub//deep.png", 1, 0}, {"alias.png", 1, 0},
        {"sub/up_inside.png", 1, 0}, {"sub_link/deep.png", 1, 0}, {"sub/parent/in.png", 1, 0},
        {"../out.png", 0, 1}, {"sub/../in.png", 0, 1}, {"up_link.png", 0, 1}, {"abs_link.png", 0, 1},
        {"sub/up_out.png", 0, 1}, {"/etc/passwd", 0, 1}, {"missing.png", 0, 0}, {"sub", 0, 0}, {"sub/", 0, 0},
        {".", 0, 0}, {"in.png/", 0, 0}, {"loop.png", 0, 0}, {"pipe.png", 0, 0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        errno = 0;
        const int a = files_open_beneath(dir, cases[i].name), a_err = errno;
        errno = 0;
        const int b = files_open_beneath_walk(dir, cases[i].name), b_err = errno;
        cr_assert_eq(a >= 0, cases[i].inside, "openat2: '%s' -> %d (%s)", cases[i].name, a, strerror(a_err));
        cr_assert_eq(b >= 0, cases[i].inside, "walk: '%s' -> %d (%s)", cases[i].name, b, strerror(b_err));
        if (cases[i].outside)
            cr_assert(a_err == EXDEV && b_err == EXDEV, "'%s': %s and %s, not EXDEV", cases[i].name,
                      strerror(a_err), strerror(b_err));
        if (a >= 0 && b >= 0) {
            struct stat sa, sb;
            cr_assert(fstat(a, &sa) == 0 && fstat(b, &sb) == 0);
            cr_assert(sa.st_ino == sb.st_ino && sa.st_dev == sb.st_dev, "'%s': two different files", cases[i].name);
        }
        if (a >= 0)
            close(a);
        if (b >= 0)
            close(b);
    }
    close(dir);
    root_close();
}
#endif
