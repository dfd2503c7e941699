/* World state in memory: a busy scene saved, stepped on, restored and stepped again retraces its steps bit for bit;
 * handles come back as they were; short buffers, changed or cut bytes and another world's bytes are refused with
 * the world unchanged; a loaded world is equal; the hash is the backend's business not, and sees an impulse. */
#include "helpers.h"

#include "hash.h" /* to make a changed state's checksum right (lib/core) */

#include <stddef.h>

PP_TEST_SUITE(state);

#define DT (1.0f / 60.0f)
#define CRATES 60

typedef struct busy {
    pp_world w;
    pp_body terrain;
    pp_body crates[CRATES];
    pp_joint joint;
} busy;

/* A 1200×300 terrain with three craters, 60 crates of 10-24 px raining on it, two of them joined by a revolute
 * joint, contact events on and a crater scheduled at 2 s (after the busy test's save at 1.67 s). */
static busy busy_scene(pp_backend backend)
{
    busy s;
    pp_world_def wd = pp_world_def_default();
    wd.backend = backend;
    wd.contact_events = 1;
    s.w = make_world_def(&wd);
    s.terrain = add_rect(s.w, body_def(PP_BODY_STATIC, 600, 650, 0), 1200, 300);
    for (int i = 0; i < 3; i++)
        PP_OK_OR_FAIL(pp_world_erase_circle(s.w, v2(250.0f + 350.0f * i, 500), 40.0f + 10.0f * i, NULL));
    for (int i = 0; i < CRATES; i++) {
        const int size = 10 + (i * 7) % 15;
        pp_body_def d = body_def(PP_BODY_DYNAMIC, 100.0f + (i % 20) * 50.0f, 200.0f - (i / 20) * 60.0f, 0.1f * (i % 5));
        s.crates[i] = add_rect(s.w, d, size, size + (i % 3) * 4);
    }
    pp_joint_def j = pp_joint_def_default(PP_JOINT_REVOLUTE);
    j.body_a = s.crates[0], j.body_b = s.crates[1];
    j.anchor_a = v2(125, 200);
    s.joint = make_joint(s.w, &j);
    const pp_timed_edit e = {.time = 2.0, .type = PP_EDIT_ERASE_CIRCLE, .center = {700, 520}, .radius = 30};
    PP_OK_OR_FAIL(pp_world_schedule_edit(s.w, &e));
    return s;
}

static uint64_t hash_of(pp_world w)
{
    uint64_t h = 0;
    PP_OK_OR_FAIL(pp_world_get_hash(w, &h));
    return h;
}

/* The state as a malloc'd buffer; its size into *size. */
static uint8_t *save(pp_world w, int64_t *size)
{
    cr_assert_eq(pp_world_save_state(w, NULL, 0, size), PP_ERR_LIMIT);
    uint8_t *buf = malloc((size_t)*size);
    cr_assert_not_null(buf);
    int64_t again = 0;
    PP_OK_OR_FAIL(pp_world_save_state(w, buf, *size, &again));
    cr_assert_eq(again, *size);
    return buf;
}

/* Every crate's position, angle and velocity after each of n steps. */
static void run(busy *s, int n, float *out)
{
    for (int k = 0; k < n; k++) {
        PP_OK_OR_FAIL(pp_world_step(s->w, DT));
        for (int i = 0; i < CRATES; i++, out += 5) {
            pp_vec2 p, v;
            float a, av;
            PP_OK_OR_FAIL(pp_body_get_position(s->w, s->crates[i], &p));
            PP_OK_OR_FAIL(pp_body_get_angle(s->w, s->crates[i], &a));
            PP_OK_OR_FAIL(pp_body_get_velocity(s->w, s->crates[i], &v, &av));
            out[0] = p.x, out[1] = p.y, out[2] = a, out[3] = v.x, out[4] = av;
        }
    }
}

Test(state, a_restored_busy_scene_steps_again_bit_for_bit, .timeout = 120)
{
    busy s = busy_scene(PP_BACKEND_CPU);
    step_n(s.w, DT, 100);
    int64_t size = 0;
    uint8_t *st = save(s.w, &size);
    const uint64_t at_save = hash_of(s.w);
    int32_t events = 0, edits = 0;
    PP_OK_OR_FAIL(pp_world_get_events(s.w, NULL, 0, &events));
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(s.w, NULL, 0, &edits));
    cr_assert(events > 0 && edits == 1, "%d unread events and %d edits at the save: the state holds none", events, edits);
    float *first = malloc(sizeof(float) * 60 * CRATES * 5), *second = malloc(sizeof(float) * 60 * CRATES * 5);
    run(&s, 60, first);
    const uint64_t after_first = hash_of(s.w);
    cr_assert_neq(after_first, at_save, "60 steps changed nothing: the scene tests nothing");
    PP_OK_OR_FAIL(pp_world_restore_state(s.w, st, size));
    cr_assert_eq(hash_of(s.w), at_save, "the restored world hashes to %#llx, the saved one to %#llx",
                 (unsigned long long)hash_of(s.w), (unsigned long long)at_save);
    int32_t events_back = 0, edits_back = 0;
    PP_OK_OR_FAIL(pp_world_get_events(s.w, NULL, 0, &events_back));
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(s.w, NULL, 0, &edits_back));
    cr_assert(events_back == events && edits_back == 1, "%d events and %d edits back", events_back, edits_back);
    run(&s, 60, second);
    cr_assert_eq(hash_of(s.w), after_first);
    cr_assert(memcmp(first, second, sizeof(float) * 60 * CRATES * 5) == 0, "the poses differ after the restore");
    /* Restored twice over: the same again, and the moving crates did move. */
    PP_OK_OR_FAIL(pp_world_restore_state(s.w, st, size));
    run(&s, 60, second);
    cr_assert(memcmp(first, second, sizeof(float) * 60 * CRATES * 5) == 0);
    float moved = 0;
    for (int i = 0; i < 60 * CRATES * 5; i += 5)
        moved = fmaxf(moved, fabsf(first[i + 3]));
    cr_assert_gt(moved, 1.0f, "no crate moved in the 60 steps");
    free(first), free(second), free(st);
    pp_world_destroy(s.w);
}

Test(state, pixels_erased_after_the_save_come_back, .timeout = 60)
{
    busy s = busy_scene(PP_BACKEND_CPU);
    step_n(s.w, DT, 20);
    int64_t size = 0;
    uint8_t *st = save(s.w, &size);
    const uint64_t at_save = hash_of(s.w);
    int32_t changed = 0;
    PP_OK_OR_FAIL(pp_world_erase_circle(s.w, v2(600, 560), 60, &changed));
    cr_assert_gt(changed, 0);
    step_n(s.w, DT, 10);
    PP_OK_OR_FAIL(pp_world_restore_state(s.w, st, size));
    cr_assert_eq(hash_of(s.w), at_save);
    uint8_t *mask = malloc(1200 * 300);
    PP_OK_OR_FAIL(pp_body_read_mask(s.w, s.terrain, mask, 1200 * 300));
    cr_assert_neq(mask[60 * 1200 + 600], 0, "the crater's pixel is still erased after the restore");
    free(mask);
    free(st);
    pp_world_destroy(s.w);
}

Test(state, handles_made_after_the_save_go_stale_and_destroyed_ones_live_again, .timeout = 60)
{
    busy s = busy_scene(PP_BACKEND_CPU);
    step_n(s.w, DT, 10);
    int64_t size = 0;
    uint8_t *st = save(s.w, &size);
    const uint64_t at_save = hash_of(s.w);
    float y0 = body_pos(s.w, s.crates[5]).y;
    const pp_body late = add_rect(s.w, body_def(PP_BODY_DYNAMIC, 40, 40, 0), 8, 8);
    PP_OK_OR_FAIL(pp_body_destroy(s.w, s.crates[5]));
    PP_OK_OR_FAIL(pp_joint_destroy(s.w, s.joint));
    step_n(s.w, DT, 5);
    PP_OK_OR_FAIL(pp_world_restore_state(s.w, st, size));
    cr_assert_eq(hash_of(s.w), at_save);
    pp_vec2 p;
    EXPECT_ERR(pp_body_get_position(s.w, late, &p), PP_ERR_INVALID_HANDLE, "pp_body_get_position");
    PP_OK_OR_FAIL(pp_body_get_position(s.w, s.crates[5], &p));
    cr_assert_eq(p.y, y0);
    float value = 0;
    PP_OK_OR_FAIL(pp_joint_get_value(s.w, s.joint, &value, NULL));
    /* The world goes on as it would have: a body made now takes the handle the late one had. */
    const pp_body again = add_rect(s.w, body_def(PP_BODY_DYNAMIC, 40, 40, 0), 8, 8);
    cr_assert_eq(again.id, late.id);
    free(st);
    pp_world_destroy(s.w);
}

Test(state, a_short_buffer_gives_the_size, .timeout = 30)
{
    busy s = busy_scene(PP_BACKEND_CPU);
    int64_t size = -1;
    uint8_t small[64];
    EXPECT_ERR(pp_world_save_state(s.w, small, sizeof small, &size), PP_ERR_LIMIT, "pp_world_save_state");
    cr_assert_gt(size, 1200 * 300 / 8, "the state (%lld bytes) cannot hold the terrain's mask", (long long)size);
    uint8_t *buf = malloc((size_t)size);
    EXPECT_ERR(pp_world_save_state(s.w, buf, size - 1, &size), PP_ERR_LIMIT, "pp_world_save_state");
    int64_t got = 0;
    PP_OK_OR_FAIL(pp_world_save_state(s.w, buf, size, &got));
    cr_assert_eq(got, size);
    EXPECT_ERR(pp_world_save_state(s.w, buf, size, NULL), PP_ERR_INVALID_ARGUMENT, "pp_world_save_state");
    free(buf);
    pp_world_destroy(s.w);
}

/* The busy scene on the CPU after 30 steps, and its state. */
static uint8_t *busy_saved(busy *s, int64_t *size)
{
    *s = busy_scene(PP_BACKEND_CPU);
    step_n(s->w, DT, 30);
    return save(s->w, size);
}

Test(state, changed_or_cut_bytes_are_refused_and_change_nothing, .timeout = 60)
{
    busy s;
    int64_t size = 0;
    uint8_t *st = busy_saved(&s, &size);
    step_n(s.w, DT, 10);
    const uint64_t now = hash_of(s.w);
    const int64_t flips[] = {0, 12, 24, 48, size / 3, size / 2, size - 1}; /* magic, checksum, version, world */
    for (size_t i = 0; i < sizeof flips / sizeof flips[0]; i++) {
        st[flips[i]] ^= 0x10;
        EXPECT_ERR(pp_world_restore_state(s.w, st, size), PP_ERR_FORMAT, "pp_world_restore_state");
        st[flips[i]] ^= 0x10;
        cr_assert_eq(hash_of(s.w), now, "a refused restore (byte %lld) changed the world", (long long)flips[i]);
    }
    EXPECT_ERR(pp_world_restore_state(s.w, st, size - 8), PP_ERR_FORMAT, "pp_world_restore_state");
    EXPECT_ERR(pp_world_restore_state(s.w, st, 10), PP_ERR_FORMAT, "pp_world_restore_state");
    EXPECT_ERR(pp_world_restore_state(s.w, NULL, size), PP_ERR_INVALID_ARGUMENT, "pp_world_restore_state");
    pp_world loaded = {0};
    EXPECT_ERR(pp_world_load_state(st, size / 2, &loaded), PP_ERR_FORMAT, "pp_world_load_state");
    cr_assert_eq(hash_of(s.w), now);
    /* The seal is not the state: a changed one costs the bytes their trust, and the checks pass them. */
    PP_OK_OR_FAIL(pp_world_restore_state(s.w, st, size));
    const uint64_t saved = hash_of(s.w);
    cr_assert_neq(saved, now);
    step_n(s.w, DT, 10);
    st[20] ^= 0x10;
    PP_OK_OR_FAIL(pp_world_restore_state(s.w, st, size));
    cr_assert_eq(hash_of(s.w), saved, "bytes restored with a changed seal differ from the sealed ones");
    free(st);
    pp_world_destroy(s.w);
}

/* The state's world settings as they lie in the bytes (lib/io/state.c: the 48-byte header, then the def). */
#define STATE_DEF_AT 48

/* Bytes changed by a peer, with their checksum made right again (hash.h's over every byte after the first 24: the
 * magic, the checksum and the seal, which is left as the world made it and so no longer fits). */
static void set_field(uint8_t *st, int64_t size, size_t at, const void *value, size_t n)
{
    memcpy(st + at, value, n);
    const uint64_t sum = hash_bytes(HASH_START, st + 24, (size_t)size - 24);
    memcpy(st + 8, &sum, 8);
}

Test(state, wrong_values_with_a_right_checksum_are_refused_and_change_nothing, .timeout = 60)
{
    busy s;
    int64_t size = 0;
    uint8_t *st = busy_saved(&s, &size);
    step_n(s.w, DT, 10);
    const uint64_t now = hash_of(s.w);
    const int32_t zero = 0;
    const float nan = NAN;
    const size_t substeps = STATE_DEF_AT + offsetof(pp_world_def, substeps);
    const size_t ppm = STATE_DEF_AT + offsetof(pp_world_def, pixels_per_meter);
    int32_t was_substeps;
    float was_ppm;
    memcpy(&was_substeps, st + substeps, 4), memcpy(&was_ppm, st + ppm, 4);
    set_field(st, size, substeps, &zero, 4);
    EXPECT_ERR(pp_world_restore_state(s.w, st, size), PP_ERR_FORMAT, "pp_world_restore_state");
    pp_world loaded = {0};
    EXPECT_ERR(pp_world_load_state(st, size, &loaded), PP_ERR_FORMAT, "pp_world_load_state");
    set_field(st, size, substeps, &was_substeps, 4);
    set_field(st, size, ppm, &nan, 4);
    EXPECT_ERR(pp_world_restore_state(s.w, st, size), PP_ERR_FORMAT, "pp_world_restore_state");
    cr_assert_eq(hash_of(s.w), now, "a refused restore changed the world");
    set_field(st, size, ppm, &was_ppm, 4);
    PP_OK_OR_FAIL(pp_world_restore_state(s.w, st, size)); /* the bytes as saved, checksum and all */
    free(st);
    pp_world_destroy(s.w);
}

Test(state, settings_changed_in_the_bytes_make_the_world_anew, .timeout = 60)
{
    busy s;
    int64_t size = 0;
    uint8_t *st = busy_saved(&s, &size);
    const int32_t iterations = 7; /* the solver is made with them: not copied over the live world's */
    set_field(st, size, STATE_DEF_AT + offsetof(pp_world_def, solver_iterations), &iterations, 4);
    PP_OK_OR_FAIL(pp_world_restore_state(s.w, st, size));
    pp_world loaded = {0};
    PP_OK_OR_FAIL(pp_world_load_state(st, size, &loaded));
    step_n(s.w, DT, 10);
    step_n(loaded, DT, 10);
    cr_assert_eq(hash_of(s.w), hash_of(loaded), "the restored world goes as a world loaded from the same bytes");
    free(st);
    pp_world_destroy(loaded);
    pp_world_destroy(s.w);
}

Test(state, a_kinematic_body_of_another_density_restores, .timeout = 30)
{
    pp_world_def wd = pp_world_def_default();
    pp_world w = make_world_def(&wd);
    const pp_body k = add_rect(w, body_def(PP_BODY_KINEMATIC, 50, 50, 0), 10, 10);
    PP_OK_OR_FAIL(pp_body_set_density(w, k, 3)); /* its mass waits for a change of type: still a valid state */
    int64_t size = 0;
    uint8_t *st = save(w, &size);
    step_n(w, DT, 3);
    PP_OK_OR_FAIL(pp_world_restore_state(w, st, size));
    free(st);
    pp_world_destroy(w);
}

Test(state, bytes_of_another_world_are_refused, .timeout = 60)
{
    busy a = busy_scene(PP_BACKEND_CPU), b = busy_scene(PP_BACKEND_CPU);
    int64_t size = 0;
    uint8_t *st = save(a.w, &size);
    const uint64_t hb = hash_of(b.w);
    EXPECT_ERR(pp_world_restore_state(b.w, st, size), PP_ERR_INVALID_ARGUMENT, "pp_world_restore_state");
    cr_assert_eq(hash_of(b.w), hb);
    cr_assert_eq(hash_of(a.w), hb, "two worlds built alike hash alike");
    free(st);
    pp_world_destroy(a.w);
    pp_world_destroy(b.w);
}

Test(state, a_loaded_world_is_equal_and_has_the_same_future, .timeout = 120)
{
    busy s = busy_scene(PP_BACKEND_CPU);
    step_n(s.w, DT, 100);
    int64_t size = 0;
    uint8_t *st = save(s.w, &size);
    pp_world copy = {0};
    PP_OK_OR_FAIL(pp_world_load_state(st, size, &copy));
    cr_assert_neq(copy.id, s.w.id);
    cr_assert_eq(hash_of(copy), hash_of(s.w));
    step_n(s.w, DT, 60);
    step_n(copy, DT, 60);
    cr_assert_eq(hash_of(copy), hash_of(s.w), "the loaded world went another way");
    /* Its own bytes are its own: the original refuses them. */
    int64_t size2 = 0;
    uint8_t *st2 = save(copy, &size2);
    EXPECT_ERR(pp_world_restore_state(s.w, st2, size2), PP_ERR_INVALID_ARGUMENT, "pp_world_restore_state");
    free(st), free(st2);
    pp_world_destroy(copy);
    pp_world_destroy(s.w);
}

/* A big body's untouched pixels stay in the world that saved the state: its bytes load while that world exists.
 * A world of small bodies only is whole in its bytes. */
Test(state, a_big_terrains_state_loads_while_its_world_exists, .timeout = 60)
{
    busy s = busy_scene(PP_BACKEND_CPU);
    step_n(s.w, DT, 10);
    int64_t size = 0;
    uint8_t *st = save(s.w, &size);
    /* A small crater adds its band of 8 rows to the state, not the terrain's 45 kB of mask. */
    pp_world probe = {0};
    PP_OK_OR_FAIL(pp_world_load_state(st, size, &probe));
    int64_t grown = 0;
    PP_OK_OR_FAIL(pp_world_erase_circle(probe, v2(420, 502), 2, NULL));
    cr_assert_eq(pp_world_save_state(probe, NULL, 0, &grown), PP_ERR_LIMIT);
    cr_assert(grown > size && grown - size < 4096, "a 2 px crater took the state from %lld to %lld bytes",
              (long long)size, (long long)grown);
    pp_world_destroy(probe);
    pp_world copy = {0};
    PP_OK_OR_FAIL(pp_world_load_state(st, size, &copy));
    pp_world_destroy(s.w);
    pp_world again = {0};
    EXPECT_ERR(pp_world_load_state(st, size, &again), PP_ERR_INVALID_ARGUMENT, "pp_world_load_state");
    /* The copy keeps the pixels itself: its own bytes load after it is gone. */
    int64_t size2 = 0;
    uint8_t *st2 = save(copy, &size2);
    const uint64_t h = hash_of(copy);
    pp_world third = {0};
    PP_OK_OR_FAIL(pp_world_load_state(st2, size2, &third));
    cr_assert_eq(hash_of(third), h);
    pp_world_destroy(third);
    free(st), free(st2);

    pp_world small = make_world(0, 980);
    add_rect(small, body_def(PP_BODY_STATIC, 200, 300, 0), 400, 40);
    add_rect(small, body_def(PP_BODY_DYNAMIC, 200, 200, 0), 16, 16);
    step_n(small, DT, 10);
    uint8_t *st3 = save(small, &size);
    const uint64_t hs = hash_of(small);
    pp_world_destroy(small);
    PP_OK_OR_FAIL(pp_world_load_state(st3, size, &small));
    cr_assert_eq(hash_of(small), hs);
    pp_world_destroy(small);
    pp_world_destroy(copy);
    free(st3);
}

#ifdef PP_TEST_PRIVATE
#include "world.h" /* the contact table's records: a held pair's carried frames */

#include <string.h>

/* Where n bytes equal to what first appear in the buffer, or NULL. */
static uint8_t *find_bytes(uint8_t *buf, size_t size, const void *what, size_t n)
{
    for (size_t i = 0; i + n <= size; i++)
        if (!memcmp(buf + i, what, n))
            return buf + i;
    return NULL;
}

/* A world without sleep: a ground 800 px wide whose top is at y = 500, and boxes of 32 px to put on it. */
static pp_world ground_world(void)
{
    pp_world_def d = pp_world_def_default();
    d.allow_sleep = 0;
    d.gravity = v2(0, 980);
    pp_world w = make_world_def(&d);
    add_rect(w, body_def(PP_BODY_STATIC, 400, 520, 0), 800, 40);
    return w;
}

/* The world loaded from bytes st, changed since `clean` was loaded from them, steps 30 steps to clean's hash. Frees
 * st and both worlds. */
static void steps_as_the_clean_bytes(pp_world clean, uint8_t *st, int64_t size, const char *what)
{
    pp_world changed = {0};
    PP_OK_OR_FAIL(pp_world_load_state(st, size, &changed));
    step_n(clean, DT, 30);
    step_n(changed, DT, 30);
    cr_assert_eq(hash_of(changed), hash_of(clean), "%s", what);
    free(st);
    pp_world_destroy(clean);
    pp_world_destroy(changed);
}

/* Loaded bytes give a held pair's carried contacts and poses; each point's place in the bodies' frames is derived
 * from them again (contact_table_locate_carried), never taken from the bytes, which hold it too. */
Test(state, a_held_pairs_frames_come_from_its_carried_contacts_not_the_bytes, .timeout = 60)
{
    pp_world w = ground_world();
    add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 484, 0), 32, 32);
    step_n(w, DT, 60); /* settled: its pair with the ground is held from step to step */
    const world *wd = world_lookup(w, "test");
    const contact_record *held = NULL;
    for (int32_t i = 0; i < wd->table.count && !held; i++)
        held = wd->table.records[i].carried ? &wd->table.records[i] : NULL;
    cr_assert_not_null(held, "no pair is held after a second at rest");
    int64_t size = 0;
    uint8_t *st = save(w, &size);
    const size_t n = (size_t)held->carry_count * sizeof held->carry_local[0];
    uint8_t *at = find_bytes(st, (size_t)size, held->carry_local, n);
    cr_assert_not_null(at, "the state holds the pair's carried frames as the world does");
    pp_world clean = {0};
    PP_OK_OR_FAIL(pp_world_load_state(st, size, &clean));
    for (size_t k = 0; k < n; k += sizeof(double)) { /* each coordinate 5 px off, the checksum made right */
        double x;
        memcpy(&x, at + k, sizeof x);
        x += 5;
        set_field(st, size, (size_t)(at - st) + k, &x, sizeof x);
    }
    steps_as_the_clean_bytes(clean, st, size, "frames taken from the bytes moved the held pair's contacts");
    pp_world_destroy(w);
}

/* A stack's friction anchor holds b's pose in a's frame (an angle) and that angle's cos and sin, which the bytes
 * hold too: they are derived from the angle again (anchor_turn), never taken from the bytes. The fuzzer's state
 * had them at (3.2e-5, -0.042) for an angle of -0.042 rad: the pair kept that anchor, whose slip put its contacts
 * 8 px from it (a PP_CHECKS assertion in set_anchor stopped it). */
Test(state, a_pairs_anchor_turn_comes_from_its_angle_not_the_bytes, .timeout = 60)
{
    pp_world w = ground_world();
    const pp_body low = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 484, 0), 32, 32);
    const pp_body top = add_rect(w, body_def(PP_BODY_DYNAMIC, 404, 452, 0), 32, 32);
    step_n(w, DT, 60); /* settled: the boxes' pair keeps its anchor */
    const world *wd = world_lookup(w, "test");
    const contact_record *pair = contact_table_find(wd, low.id, top.id);
    cr_assert_not_null(pair, "the boxes touch");
    int64_t size = 0;
    uint8_t *st = save(w, &size);
    uint8_t *at = find_bytes(st, (size_t)size, &pair->anchor_cos, 2 * sizeof(double));
    cr_assert_not_null(at, "the state holds the anchor's cos and sin as the world does");
    pp_world clean = {0};
    PP_OK_OR_FAIL(pp_world_load_state(st, size, &clean));
    const double wrong[2] = {3.2370036324904466e-05, pair->anchor_sin}; /* unit no longer, as the fuzzer's */
    set_field(st, size, (size_t)(at - st), wrong, sizeof wrong);
    steps_as_the_clean_bytes(clean, st, size, "an anchor turned by the bytes moved the stack");
    pp_world_destroy(w);
}
#endif

Test(state, the_hash_sees_any_impulse, .timeout = 30)
{
    busy s = busy_scene(PP_BACKEND_CPU);
    step_n(s.w, DT, 10);
    const uint64_t h = hash_of(s.w);
    cr_assert_eq(hash_of(s.w), h, "the hash changes by being read");
    PP_OK_OR_FAIL(pp_body_apply_impulse(s.w, s.crates[7], v2(0, -1e-3f), body_pos(s.w, s.crates[7])));
    cr_assert_neq(hash_of(s.w), h, "an impulse left the hash as it was");
    pp_world_destroy(s.w);
}

/* The GPU makes the CPU's decisions, so the same scene hashes the same after the same steps. */
Test(state, the_hash_is_the_same_on_the_gpu, .timeout = 300)
{
    pp_world_def d = pp_world_def_default();
    d.backend = PP_BACKEND_GPU;
    pp_world probe = {0};
    const pp_status st = pp_world_create(&d, &probe);
    if (st != PP_OK) {
        cr_assert_eq(st, PP_ERR_UNSUPPORTED, "a failed GPU world must say UNSUPPORTED, got %s", pp_status_name(st));
        fprintf(stderr, "state gpu hash skipped: %s\n", pp_last_error());
        cr_skip_test("no GLES 3.1 compute context: %s", pp_last_error());
    }
    pp_world_destroy(probe);
    busy c = busy_scene(PP_BACKEND_CPU), g = busy_scene(PP_BACKEND_GPU);
    step_n(c.w, DT, 60);
    step_n(g.w, DT, 60);
    /* A crater undone by a restore on each: the GPU's copy of the terrain takes the restored rows. */
    busy *both[2] = {&c, &g};
    for (int i = 0; i < 2; i++) {
        int64_t size = 0;
        uint8_t *bytes = save(both[i]->w, &size);
        PP_OK_OR_FAIL(pp_world_erase_circle(both[i]->w, v2(420, 500), 20, NULL));
        step_n(both[i]->w, DT, 5);
        PP_OK_OR_FAIL(pp_world_restore_state(both[i]->w, bytes, size));
        step_n(both[i]->w, DT, 30);
        free(bytes);
    }
    pp_step_stats stats;
    PP_OK_OR_FAIL(pp_world_get_stats(g.w, &stats));
    cr_assert_eq(stats.backend, PP_BACKEND_GPU);
    cr_assert_eq(hash_of(c.w), hash_of(g.w), "CPU %#llx, GPU %#llx", (unsigned long long)hash_of(c.w),
                 (unsigned long long)hash_of(g.w));
    pp_world_destroy(c.w);
    pp_world_destroy(g.w);
}
