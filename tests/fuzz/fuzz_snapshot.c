/* libFuzzer target: snapshot folders through pp_world_load_snapshot. A snapshot is several files, so an input
 * is a small archive of them (fuzz_archive.h): world.json and the PNG planes, each as fuzzable as the other.
 * The seeds are real snapshots saved by pp_world_save_snapshot. A snapshot that loads is stepped, saved
 * again and loaded again. */
#include "fuzz_archive.h"
#include "fuzz_common.h"

/* Harness caps, not library limits: planes past this area are valid but slow to decode and step. */
#define FUZZ_SNAPSHOT_MAX_PLANE_AREA (128 * 128)
#define FUZZ_SNAPSHOT_STEPS 3

static char snap_dir[300], again_dir[300];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    fuzz_no_gpu();
    snprintf(snap_dir, sizeof snap_dir, "%s/snap", fuzz_scratch());
    snprintf(again_dir, sizeof again_dir, "%s/again", fuzz_scratch());
    return 0;
}

static int32_t body_count(pp_world w)
{
    int32_t n = -1;
    FUZZ_CHECK(ST(pp_world_get_bodies(w, NULL, 0, &n)) == PP_OK && n >= 0, "bodies");
    return n;
}

/* Every plane the archive holds is small enough to step quickly (a file that is no PNG is the library's). */
static int planes_small(const char *dir)
{
    DIR *d = opendir(dir);
    int ok = 1;
    char path[600];
    for (struct dirent *e; d && ok && (e = readdir(d));) {
        int32_t w = 0, h = 0;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (e->d_name[0] != '.' && pp_image_info(path, &w, &h) == PP_OK)
            ok = (int64_t)w * h <= FUZZ_SNAPSHOT_MAX_PLANE_AREA;
    }
    if (d)
        closedir(d);
    return ok;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_rm_tree(snap_dir);
    fuzz_rm_tree(again_dir);
    mkdir(snap_dir, 0700);
    fuzz_archive_extract(data, size, snap_dir);
    if (!planes_small(snap_dir))
        return 0;
    pp_world w = {0};
    const pp_status st = ST(pp_world_load_snapshot(snap_dir, &w));
    FUZZ_CHECK(st != PP_ERR_INVALID_HANDLE && st != PP_ERR_ABI, "pp_world_load_snapshot: %d", (int)st);
    if (st != PP_OK)
        return 0;
    for (int i = 0; i < FUZZ_SNAPSHOT_STEPS && !fuzz_too_fast(w); i++) {
        const pp_status s = ST(pp_world_step(w, 1.0f / 60));
        FUZZ_CHECK(s == PP_OK || s == PP_ERR_UNSUPPORTED || s == PP_ERR_OUT_OF_MEMORY, "step: %d", (int)s);
        int32_t n = 0;
        pp_event ev[4];
        ST(pp_world_get_events(w, ev, 4, &n));
        ST(pp_world_get_contacts(w, NULL, 0, &n));
    }
    /* What loaded saves and loads again, with the same bodies. */
    FUZZ_CHECK(ST(pp_world_save_snapshot(w, again_dir)) == PP_OK, "save the loaded world");
    pp_world w2 = {0};
    FUZZ_CHECK(ST(pp_world_load_snapshot(again_dir, &w2)) == PP_OK, "load what was saved");
    FUZZ_CHECK(body_count(w2) == body_count(w), "body counts differ after a save and load");
    FUZZ_CHECK(ST(pp_world_destroy(w2)) == PP_OK, "destroy");
    FUZZ_CHECK(ST(pp_world_destroy(w)) == PP_OK, "destroy");
    return 0;
}
