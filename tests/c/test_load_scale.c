/* Loading and scheduling at scale, each once quadratic: a scene's names were looked up by scanning every
 * body (a 40,000-body scene took 97 s), a snapshot's free list was checked pair by pair, and each timed edit
 * was inserted by shifting the list. At 100,000 bodies (200,000 edits) the timeout catches a return to any
 * of them; the results are checked too: edits reach the bodies they name, and equal times keep their
 * scheduling order. */
#include "handle.h" /* handle_saved: a handle without its world */
#include "helpers.h"

PP_TEST_SUITE(load_scale);

#define DT (1.0f / 60.0f)
/* Bodies in the scene tests, and twice as many slots in the snapshot's: the sanitizers' build, several times
 * slower, halves them, still far past where the old scans ran out of time. */
#if defined(__SANITIZE_ADDRESS__)
#define N 50000
#else
#define N 100000
#endif
/* Edits scheduled in decreasing time: at 100,000, moving the old sorted array (twice 200 GB) could end
 * within the timeout on a machine with fast memory; 200,000 cannot, and cost 0.1 s now. */
#define EDITS 200000

static char dir[64];

static void dir_open(void)
{
    snprintf(dir, sizeof dir, "/tmp/pp_load_scale_XXXXXX");
    cr_assert(mkdtemp(dir), "mkdtemp failed");
}

static const char *at(const char *name)
{
    static char buf[512];
    snprintf(buf, sizeof buf, "%s/%s", dir, name);
    return buf;
}

static FILE *create(const char *name)
{
    FILE *f = fopen(at(name), "wb");
    cr_assert_not_null(f, "cannot create %s", at(name));
    return f;
}

static void finish(FILE *f)
{
    cr_assert(!ferror(f));
    cr_assert_eq(fclose(f), 0);
}

/* Body i: a 4 × 4 static box on a grid 8 px apart; edit k names body (k · 7919) mod N, a permutation. */
static float grid_x(int i) { return 8.0f * (float)(i % 500); }
static float grid_y(int i) { return 8.0f * (float)(i / 500); }
static int named(int k) { return (int)((long long)k * 7919 % N); }

static const int probe[] = {0, 1, 7919, N / 2 - 1, N / 2, N - 2, N - 1};
#define PROBES (int)(sizeof probe / sizeof probe[0])

static bool probed(int i)
{
    for (int p = 0; p < PROBES; p++)
        if (probe[p] == i)
            return true;
    return false;
}

/* The solid pixels of a 4 × 4 body. */
static int solid(pp_world w, pp_body b)
{
    uint8_t m[16];
    PP_OK_OR_FAIL(pp_body_read_mask(w, b, m, sizeof m));
    int n = 0;
    for (int i = 0; i < 16; i++)
        n += m[i] != 0;
    return n;
}

Test(load_scale, a_large_scene_of_named_bodies_and_edits_naming_them, .timeout = 10)
{
    dir_open();
    FILE *f = create("scene.json");
    fprintf(f, "{\"world\": {\"backend\": \"cpu\"}, \"bodies\": [\n");
    for (int i = 0; i < N; i++)
        fprintf(f, "{\"name\": \"body%d\", \"type\": \"static\", \"box\": [4, 4], \"position\": [%g, %g]}%s\n", i,
                grid_x(i), grid_y(i), i + 1 < N ? "," : "");
    fprintf(f, "], \"edits\": [\n");
    /* A disc of radius 1 at the body's centre takes its 4 middle pixels. The probed bodies' edits are due at
     * the first step, the others much later (each edit looks at every body to wake those near it). */
    for (int k = 0; k < N; k++)
        fprintf(f, "{\"time\": %d, \"body\": \"body%d\", \"center\": [%g, %g], \"radius\": 1}%s\n",
                probed(named(k)) ? 0 : 100, named(k), grid_x(named(k)), grid_y(named(k)), k + 1 < N ? "," : "");
    fprintf(f, "]}\n");
    finish(f);

    pp_world w;
    PP_OK_OR_FAIL(pp_world_load_scene(at("scene.json"), &w));
    pp_body *bodies = malloc(N * sizeof *bodies);
    pp_timed_edit *edits = malloc(N * sizeof *edits);
    cr_assert(bodies && edits);
    int32_t nb = 0, ne = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, N, &nb));
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, edits, N, &ne));
    cr_assert_eq(nb, N);
    cr_assert_eq(ne, N);
    /* Bodies come in file order (slot order); every edit holds the handle of the body it names, the one at
     * its centre, and each body is named once. */
    bool *seen = calloc(N, sizeof *seen);
    cr_assert_not_null(seen);
    for (int k = 0; k < N; k++) {
        const int i = (int)(edits[k].center.x / 8) + 500 * (int)(edits[k].center.y / 8);
        cr_assert(i >= 0 && i < N && !seen[i], "edit %d: body%d named twice", k, i);
        seen[i] = true;
        cr_assert_eq(edits[k].body.id, bodies[i].id, "the edit naming body%d holds another body", i);
    }
    free(seen);
    for (int p = 0; p < PROBES; p++)
        cr_assert_eq(solid(w, bodies[probe[p]]), 16);
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, NULL, 0, &ne));
    cr_assert_eq(ne, N - PROBES, "%d edits still pending", (int)ne);
    for (int p = 0; p < PROBES; p++)
        cr_assert_eq(solid(w, bodies[probe[p]]), 12, "body%d was not erased once", probe[p]);
    cr_assert_eq(solid(w, bodies[2]), 16, "body2, which no due edit names, was erased");
    free(bodies);
    free(edits);
    pp_world_destroy(w);
    remove_tree(dir);
}

/* A twin name is still found, with the body that had it first. */
Test(load_scale, a_name_given_twice_among_many_is_refused, .timeout = 10)
{
    dir_open();
    FILE *f = create("scene.json");
    fprintf(f, "{\"bodies\": [\n");
    for (int i = 0; i < N; i++)
        fprintf(f, "{\"name\": \"body%d\", \"type\": \"static\", \"box\": [1, 1]},\n", i);
    fprintf(f, "{\"name\": \"body%d\", \"box\": [1, 1]}]}\n", N / 3);
    finish(f);
    pp_world w = {777};
    char words[96];
    snprintf(words, sizeof words, "bodies[%d].name: 'body%d' is already the name of bodies[%d]", N, N / 3, N / 3);
    EXPECT_ERR(pp_world_load_scene(at("scene.json"), &w), PP_ERR_FORMAT, words);
    cr_assert_eq(w.id, 777);
    remove_tree(dir);
}

/* Edit i carries i in its centre's x, so the order it comes back in can be checked. */
static int index_of(const pp_timed_edit *e) { return (int)(-1000.0f - e->center.x); }

/* Pairs of equal time, decreasing: edit i is in group (EDITS − 1 − i) / 2, the groups DT / (EDITS / 2) apart,
 * so half of them are due at the first step and the rest at the second. In applying order, position p holds
 * group p / 2, the pair's earlier-scheduled edit first: edit EDITS − 2 − 2·(p / 2) + p % 2. */
static double group_time(int i) { return (double)((EDITS - 1 - i) / 2) * ((double)DT / (EDITS / 2)); }
static int expected_index(int p) { return EDITS - 2 - 2 * (p / 2) + p % 2; }

Test(load_scale, edits_scheduled_in_decreasing_time_keep_their_order, .timeout = 10)
{
    pp_world w = make_world(0, 0);
    uint8_t *m = rect_mask(200, 40);
    pp_body_def d = body_def(PP_BODY_STATIC, 100, 100, 0); /* its top-left pixel at world (0, 80) */
    d.width = 200, d.height = 40, d.mask = m;
    pp_body slab = create_body_ok(w, &d);
    free(m);
    for (int i = 0; i < EDITS; i++) {
        /* Erases of every body, far from the slab. */
        const pp_timed_edit e = {.time = group_time(i), .type = PP_EDIT_ERASE_CIRCLE,
                                 .center = {-1000.0f - (float)i, -1000.0f}, .radius = 1};
        PP_OK_OR_FAIL(pp_world_schedule_edit(w, &e));
    }
    /* Four more at time 0, after the pair there: an erase then a paint (a hole refilled), a paint then an
     * erase (a hole), on the slab. */
    const pp_timed_edit erase_a = {.type = PP_EDIT_ERASE_CIRCLE, .body = slab, .center = {50, 100}, .radius = 6};
    const pp_timed_edit paint_a = {.type = PP_EDIT_PAINT_CIRCLE, .weight = 255, .body = slab, .center = {50, 100},
                                   .radius = 6};
    pp_timed_edit paint_b = paint_a, erase_b = erase_a;
    paint_b.center.x = erase_b.center.x = 150;
    const pp_timed_edit *last[] = {&erase_a, &paint_a, &paint_b, &erase_b};
    for (int k = 0; k < 4; k++)
        PP_OK_OR_FAIL(pp_world_schedule_edit(w, last[k]));

    const int total = EDITS + 4;
    pp_timed_edit *list = malloc((size_t)total * sizeof *list);
    cr_assert_not_null(list);
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, list, total, &n));
    cr_assert_eq(n, total);
    cr_assert(index_of(&list[0]) == EDITS - 2 && index_of(&list[1]) == EDITS - 1, "the first pair at time 0");
    for (int k = 0; k < 4; k++)
        cr_assert(list[2 + k].body.id == slab.id && list[2 + k].type == last[k]->type &&
                      list[2 + k].center.x == last[k]->center.x,
                  "the slab's edits at time 0 come after the pair, as scheduled (position %d)", 2 + k);
    for (int p = 2; p < EDITS; p++)
        cr_assert_eq(index_of(&list[p + 4]), expected_index(p), "position %d", p + 4);

    /* The first step applies those before dt/2; what remains is still listed in order. */
    int due = 0;
    for (int i = 0; i < EDITS; i++)
        due += group_time(i) < 0.5 * (double)DT;
    cr_assert(due > EDITS / 3 && due < 2 * EDITS / 3, "%d due at the first step", due);
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, list, total, &n));
    cr_assert_eq(n, EDITS - due);
    for (int p = 0; p < n; p++)
        cr_assert_eq(index_of(&list[p]), expected_index(due + p), "position %d after the first step", p);
    uint8_t mask[200 * 40];
    PP_OK_OR_FAIL(pp_body_read_mask(w, slab, mask, sizeof mask));
    cr_assert_eq(mask[20 * 200 + 50], 1, "the erase at (50, 100) was not refilled by the paint after it");
    cr_assert_eq(mask[20 * 200 + 150], 0, "the paint at (150, 100) was not erased by the erase after it");
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, NULL, 0, &n));
    cr_assert_eq(n, 0);
    free(list);
    pp_world_destroy(w);
}

/* A snapshot saved after a step applied some edits and another was scheduled among the rest (the heap not
 * sorted then) lists them as the world does: by time, equal times in scheduling order. */
Test(load_scale, a_snapshot_keeps_the_pending_edits_in_order, .timeout = 10)
{
    enum { M = 2000 };
    pp_world w = make_world(0, 0);
    for (int i = 0; i < M; i++) {
        /* 50 times, 0 to 4.9 dt, scrambled: each is shared by 40 edits. */
        const pp_timed_edit e = {.time = (double)((i * 37) % 50) * (double)DT / 10, .type = PP_EDIT_ERASE_CIRCLE,
                                 .center = {-1000.0f - (float)i, -1000.0f}, .radius = 1};
        PP_OK_OR_FAIL(pp_world_schedule_edit(w, &e));
    }
    PP_OK_OR_FAIL(pp_world_step(w, DT));
    const pp_timed_edit mid = {.time = 2.05 * (double)DT, .type = PP_EDIT_ERASE_CIRCLE,
                               .center = {-1000.0f - M, -1000.0f}, .radius = 1};
    PP_OK_OR_FAIL(pp_world_schedule_edit(w, &mid));
    dir_open();
    char snap[96];
    snprintf(snap, sizeof snap, "%s/snap", dir);
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));

    pp_timed_edit *before = malloc((M + 1) * sizeof *before), *after = malloc((M + 1) * sizeof *after);
    cr_assert(before && after);
    int32_t n = 0, n2 = 0;
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, before, M + 1, &n));
    cr_assert_eq(n, M + 1 - M / 10, "the edits at 0 to 0.4 dt applied");
    for (int p = 1; p < n; p++)
        cr_assert(before[p - 1].time < before[p].time ||
                      (before[p - 1].time == before[p].time && index_of(&before[p - 1]) < index_of(&before[p])),
                  "position %d is out of order", p);
    pp_world loaded;
    PP_OK_OR_FAIL(pp_world_load_snapshot(snap, &loaded));
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(loaded, after, M + 1, &n2));
    cr_assert_eq(n2, n);
    for (int p = 0; p < n; p++)
        cr_assert(after[p].time == before[p].time && index_of(&after[p]) == index_of(&before[p]),
                  "position %d differs after the snapshot", p);
    free(before);
    free(after);
    pp_world_destroy(loaded);
    pp_world_destroy(w);
    remove_tree(dir);
}

/* world.json of one static box in slot 0 of 2N slots; free_slots lists every other slot, last first, with
 * `extra` (a slot listed again, or one in use) before the last when it is not negative. */
static void write_free_slot_snapshot(int extra)
{
    static const uint8_t white[4] = {255, 255, 255, 255};
    PP_OK_OR_FAIL(pp_image_save(at("mask.png"), white, 1, 1));
    FILE *f = create("world.json");
    fprintf(f, "{\"format\": \"physpix-snapshot\", \"version\": 1, \"time\": 0, \"solver_steps\": 0, "
               "\"next_serial\": 1,\n \"generations\": [");
    for (int s = 0; s < 2 * N; s++)
        fprintf(f, "%s1", s ? ", " : "");
    fprintf(f, "],\n \"free_slots\": [");
    for (int s = 2 * N - 1; s > 1; s--)
        fprintf(f, "%d, ", s);
    if (extra >= 0)
        fprintf(f, "%d, ", extra);
    fprintf(f, "1],\n \"edits\": [], \"events\": [], \"bodies\": [{\"type\": \"static\", \"handle\": "
               "\"0x0000000100000001\", \"serial\": 0, \"state\": {\"pose\": [0, 0, 0, 0.5, 0.5], \"user_data\": "
               "\"0x0\", \"slow_time\": 0}, \"mask\": \"mask.png\"}]}\n");
    finish(f);
}

Test(load_scale, a_snapshot_with_many_free_slots, .timeout = 10)
{
    dir_open();
    write_free_slot_snapshot(-1);
    pp_world w = {777};
    PP_OK_OR_FAIL(pp_world_load_snapshot(dir, &w));
    /* The next body takes the slot on top of the list, its last: slot 1, generation 1. */
    uint8_t one = 1;
    pp_body_def d = body_def(PP_BODY_STATIC, 10, 10, 0);
    d.width = d.height = 1, d.mask = &one;
    cr_assert_eq(handle_saved(create_body_ok(w, &d).id), (1ull << 32) | 2u);
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, NULL, 0, &n));
    cr_assert_eq(n, 2);
    pp_world_destroy(w);

    pp_world untouched = {777};
    char words[96];
    write_free_slot_snapshot(1);
    snprintf(words, sizeof words, "free_slots: [%d]: slot 1 is listed twice", 2 * N - 1);
    EXPECT_ERR(pp_world_load_snapshot(dir, &untouched), PP_ERR_FORMAT, words);
    write_free_slot_snapshot(0);
    snprintf(words, sizeof words, "free_slots: [%d]: slot 0 is in use", 2 * N - 2);
    EXPECT_ERR(pp_world_load_snapshot(dir, &untouched), PP_ERR_FORMAT, words);
    cr_assert_eq(untouched.id, 777);
    remove_tree(dir);
}
