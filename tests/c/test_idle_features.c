/* A scene pays only for what it uses: a CPU-backend world never loads EGL, however big its batches,
 * and a world that never needs more than one thread starts none. */
#include "helpers.h"

#include <dirent.h>

PP_TEST_SUITE(idle_features);

/* Is a library whose name holds `name` mapped into this process? */
static int mapped(const char *name) {
    char line[1024];
    int found = 0;
    FILE *f = fopen("/proc/self/maps", "r");
    cr_assert_not_null(f);
    while (fgets(line, sizeof line, f)) found |= strstr(line, name) != NULL;
    fclose(f);
    return found;
}

/* Threads of this process, from /proc/self/task. */
static int thread_count(void) {
    DIR *d = opendir("/proc/self/task");
    cr_assert_not_null(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) n += e->d_name[0] != '.';
    closedir(d);
    return n;
}

/* Crates piling on a terrain: big enough batches for AUTO to look for a GPU and for worker threads. */
static pp_world pile(pp_backend backend, int32_t worker_threads, int crates) {
    pp_world_def d = pp_world_def_default();
    d.backend = backend;
    d.worker_threads = worker_threads;
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 600, 700, 0), 1200, 100);
    for (int i = 0; i < crates; i++)
        add_rect(w, body_def(PP_BODY_DYNAMIC, 100.0f + 50.0f * (i % 20), 620.0f - 50.0f * (i / 20), 0.1f * (i % 3)), 40, 40);
    return w;
}

Test(idle_features, a_cpu_world_never_loads_egl) {
    cr_assert(!mapped("libEGL"), "libEGL is mapped before any world exists: the test cannot tell");
    pp_world w = pile(PP_BACKEND_CPU, 0, 200);
    int64_t cells = 0;
    for (int k = 0; k < 60; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
        pp_step_stats st;
        PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
        cells = st.pixels_tested > cells ? st.pixels_tested : cells;
    }
    /* Non-vacuous: an AUTO world would have looked for a GPU at batches this big (20,000 cells). */
    cr_assert_gt(cells, 20000, "the pile tested only %lld cells a step", (long long)cells);
    cr_assert(!mapped("libEGL"), "a CPU-backend world loaded libEGL");
    pp_world_destroy(w);
}

Test(idle_features, small_batches_start_no_threads) {
    const int before = thread_count();
    pp_world w = pile(PP_BACKEND_CPU, 4, 3);
    int32_t most = 0, touching = 0;
    for (int k = 0; k < 60; k++) {
        PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
        pp_step_stats st;
        PP_OK_OR_FAIL(pp_world_get_stats(w, &st));
        most = st.threads > most ? st.threads : most;
        touching = st.contacts > touching ? st.contacts : touching;
    }
    cr_assert_geq(touching, 6, "the three crates never all touched the ground (%d contacts)", touching);
    cr_assert_eq(most, 1, "three crates ran on %d threads", most);
    cr_assert_eq(thread_count(), before, "three crates started %d threads", thread_count() - before);
    pp_world_destroy(w);

    /* And a big pile does start them: the count above could see them. */
    w = pile(PP_BACKEND_CPU, 4, 200);
    for (int k = 0; k < 30; k++) PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60.0f));
    cr_assert_eq(thread_count(), before + 3, "a 200-crate pile with worker_threads 4 has %d extra threads",
                 thread_count() - before);
    pp_world_destroy(w);
    cr_assert_eq(thread_count(), before, "pp_world_destroy left %d threads", thread_count() - before);
}

Test(idle_features, a_body_without_weights_stores_no_weight_plane) {
    pp_world w = make_world(0, 0);
    enum { S = 1024 };
    uint8_t *mask = rect_mask(S, S), *weights = malloc((size_t)S * S);
    cr_assert_not_null(weights);
    memset(weights, 200, (size_t)S * S);
    pp_body_def d = body_def(PP_BODY_STATIC, 0, 0, 0);
    d.width = d.height = S;
    d.mask = mask;
    const pp_body plain = create_body_ok(w, &d);
    d.weights = weights;
    const pp_body weighted = create_body_ok(w, &d);
    int64_t plain_bytes, weighted_bytes, sprite_bytes;
    PP_OK_OR_FAIL(pp_body_get_memory(w, plain, &plain_bytes, &sprite_bytes));
    PP_OK_OR_FAIL(pp_body_get_memory(w, weighted, &weighted_bytes, NULL));
    const double bpp = 8.0 * (double)plain_bytes / ((double)S * S);
    cr_log_info("1024² mask: %.3f bits per pixel; with weights %.3f", bpp, 8.0 * (double)weighted_bytes / ((double)S * S));
    cr_assert_eq(sprite_bytes, 0, "a body made from a mask keeps a %lld-byte sprite", (long long)sprite_bytes);
    /* One bit of mask a pixel, plus counts per row, column and tile: well under two bits. */
    cr_assert(bpp >= 1.0 && bpp < 1.25, "a mask without weights takes %.3f bits per pixel", bpp);
    cr_assert_eq(weighted_bytes - plain_bytes, (int64_t)S * S, "the weight plane takes %lld bytes, not one a pixel",
                 (long long)(weighted_bytes - plain_bytes));

    /* Painting weight 255 onto a body without weights keeps it without a plane; another weight makes one. */
    int32_t changed;
    PP_OK_OR_FAIL(pp_body_paint_circle(w, plain, v2(0, 0), 4, 255, &changed));
    int64_t after;
    PP_OK_OR_FAIL(pp_body_get_memory(w, plain, &after, NULL));
    cr_assert_eq(after, plain_bytes);
    PP_OK_OR_FAIL(pp_body_paint_circle(w, plain, v2(0, 0), 4, 100, &changed));
    PP_OK_OR_FAIL(pp_body_get_memory(w, plain, &after, NULL));
    cr_assert_eq(after, plain_bytes + (int64_t)S * S);

    PP_OK_OR_FAIL(pp_body_destroy(w, weighted));
    cr_assert_eq(pp_body_get_memory(w, weighted, &after, NULL), PP_ERR_INVALID_HANDLE);
    free(mask);
    free(weights);
    pp_world_destroy(w);
}
