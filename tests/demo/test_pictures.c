/* The README's picture against a fresh render (make test-pictures): demo/contact_sheet.png, committed, and the
 * contact sheet the same default demo run just wrote. The demo is deterministic (the same build, gcc or clang,
 * -O2 or -march=native, renders it byte for byte), so the tolerance only absorbs a renderer's rounding: a pixel
 * counts as changed when a channel moves by more than PICTURE_CHANNEL_SLACK levels, and at most
 * PICTURE_CHANGED_PER_MILLE of the pixels may change. A change of the physics moves bodies and fails it: gravity
 * 980 -> 981 px/s² alone changes 2,695 pixels of 388,800 by more than 32 levels, against 388 allowed. The paths
 * come from the environment; on failure a picture of the changed pixels is written beside the fresh one. */
#include <physpix.h>

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { PICTURE_CHANNEL_SLACK = 32, PICTURE_CHANGED_PER_MILLE = 1 };

typedef struct picture {
    int32_t width, height;
    uint8_t *rgba;
} picture;

static const char *env(const char *name)
{
    const char *v = getenv(name);
    cr_assert(v && *v, "%s is not set: run this test through `make test-pictures`", name);
    return v;
}

static picture load(const char *path)
{
    picture p = {0, 0, NULL};
    cr_assert_eq(pp_image_info(path, &p.width, &p.height), PP_OK, "%s: %s", path, pp_last_error());
    const int64_t bytes = (int64_t)p.width * p.height * 4;
    p.rgba = malloc((size_t)bytes);
    cr_assert_not_null(p.rgba);
    cr_assert_eq(pp_image_load(path, p.rgba, bytes, &p.width, &p.height), PP_OK, "%s: %s", path, pp_last_error());
    return p;
}

/* Pixels whose largest channel difference passes the slack; marks them red in diff (when not NULL). */
static int64_t changed_pixels(const picture *a, const picture *b, uint8_t *diff)
{
    int64_t changed = 0;
    for (int64_t i = 0; i < (int64_t)a->width * a->height; i++) {
        int worst = 0;
        for (int c = 0; c < 4; c++) {
            const int d = abs((int)a->rgba[4 * i + c] - (int)b->rgba[4 * i + c]);
            worst = d > worst ? d : worst;
        }
        const int hit = worst > PICTURE_CHANNEL_SLACK;
        changed += hit;
        if (diff) {
            const uint8_t grey = (uint8_t)(a->rgba[4 * i] / 4 + 160);
            const uint8_t px[4] = {hit ? 255 : grey, hit ? 0 : grey, hit ? 0 : grey, 255};
            memcpy(diff + 4 * i, px, 4);
        }
    }
    return changed;
}

Test(pictures, the_committed_contact_sheet_matches_a_fresh_render)
{
    const char *committed_path = env("PP_PICTURE_COMMITTED"), *fresh_path = env("PP_PICTURE_FRESH");
    picture committed = load(committed_path), fresh = load(fresh_path);
    cr_assert(committed.width == fresh.width && committed.height == fresh.height,
              "%s is %d x %d, a fresh render %d x %d: run `make pictures` and commit it", committed_path,
              committed.width, committed.height, fresh.width, fresh.height);
    const int64_t pixels = (int64_t)fresh.width * fresh.height, allowed = pixels * PICTURE_CHANGED_PER_MILLE / 1000;
    const int64_t changed = changed_pixels(&committed, &fresh, NULL);
    if (changed > allowed) {
        char diff_path[4096];
        snprintf(diff_path, sizeof diff_path, "%s.diff.png", fresh_path);
        uint8_t *diff = malloc((size_t)pixels * 4);
        cr_assert_not_null(diff);
        changed_pixels(&committed, &fresh, diff);
        cr_expect_eq(pp_image_save(diff_path, diff, fresh.width, fresh.height), PP_OK, "%s", pp_last_error());
        free(diff);
        cr_assert_fail("%s differs from a fresh render (%s) in %lld pixels, %lld allowed (changed pixels in red: "
                       "%s): if the change is meant, run `make pictures` and commit %s",
                       committed_path, fresh_path, (long long)changed, (long long)allowed, diff_path, committed_path);
    }
    free(committed.rgba);
    free(fresh.rgba);
}

/* The comparison itself: a crate's worth of pixels moved is seen, a renderer's rounding is not. */
Test(pictures, the_comparison_sees_a_moved_body_and_ignores_rounding)
{
    picture fresh = load(env("PP_PICTURE_FRESH"));
    const int64_t bytes = (int64_t)fresh.width * fresh.height * 4;
    picture rounded = {fresh.width, fresh.height, malloc((size_t)bytes)};
    cr_assert_not_null(rounded.rgba);
    for (int64_t i = 0; i < bytes; i++) /* every channel off by up to the slack, as another rounding might be */
        rounded.rgba[i] = (uint8_t)(fresh.rgba[i] < 128 ? fresh.rgba[i] + PICTURE_CHANNEL_SLACK
                                                        : fresh.rgba[i] - PICTURE_CHANNEL_SLACK);
    cr_assert_eq(changed_pixels(&fresh, &rounded, NULL), 0);
    picture moved = {fresh.width, fresh.height, rounded.rgba};
    memcpy(moved.rgba, fresh.rgba, (size_t)bytes);
    const int32_t side = 24; /* a small crate, in black, in the middle of the sheet */
    for (int32_t y = fresh.height / 2; y < fresh.height / 2 + side; y++)
        for (int32_t x = fresh.width / 2; x < fresh.width / 2 + side; x++)
            memset(moved.rgba + ((int64_t)y * fresh.width + x) * 4, 0, 3);
    const int64_t seen = changed_pixels(&fresh, &moved, NULL);
    cr_assert(seen > side * side / 2 && seen <= side * side, "a %d px square painted black changed %lld pixels", side,
              (long long)seen);
    free(fresh.rgba);
    free(moved.rgba);
}
