/* Body handles carry their world: a body of one world used in another is PP_ERR_INVALID_HANDLE naming both
 * worlds, in every call that takes a body, and neither world changes; a handle kept from a destroyed world is
 * stale in the world that takes its slot; a loaded snapshot keeps slots and generations, not the world. */
#include "helpers.h"

#include "handle.h" /* handle_saved, world_id_slot: what stays the same across worlds */

PP_TEST_SUITE(handles);

#define BOX 16

/* A world with a box (slot 0) above a ground (slot 1): two of them give bodies alike but for their world. */
static pp_world box_world(pp_body *box, pp_body *ground)
{
    pp_world w = make_world(0, 980);
    *box = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), BOX, BOX);
    *ground = add_rect(w, body_def(PP_BODY_STATIC, 100, 130, 0), 200, 20);
    return w;
}

/* Everything a call could change in a world: poses, velocities, masses, pixels, edits, events. */
static uint64_t state_hash(pp_world w)
{
    uint64_t h = FNV_START;
    pp_body bodies[8];
    int32_t n = 0, edits = 0, events = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bodies, 8, &n));
    PP_OK_OR_FAIL(pp_world_get_scheduled_edits(w, NULL, 0, &edits));
    PP_OK_OR_FAIL(pp_world_get_events(w, NULL, 0, &events));
    const int32_t counts[3] = {n, edits, events};
    h = fnv1a(h, counts, sizeof counts);
    for (int32_t i = 0; i < n && i < 8; i++) {
        struct {
            pp_vec2 p, v;
            float a, av, mass;
            uint8_t mask[4];
        } s = {0};
        PP_OK_OR_FAIL(pp_body_get_position(w, bodies[i], &s.p));
        PP_OK_OR_FAIL(pp_body_get_angle(w, bodies[i], &s.a));
        PP_OK_OR_FAIL(pp_body_get_velocity(w, bodies[i], &s.v, &s.av));
        PP_OK_OR_FAIL(pp_body_get_mass(w, bodies[i], &s.mass, NULL, NULL));
        int32_t bw, bh;
        PP_OK_OR_FAIL(pp_body_get_size(w, bodies[i], &bw, &bh));
        uint8_t *mask = malloc((size_t)bw * bh);
        PP_OK_OR_FAIL(pp_body_read_mask(w, bodies[i], mask, (int64_t)bw * bh));
        for (int32_t k = 0; k < bw * bh; k++)
            s.mask[k % 4] ^= (uint8_t)(mask[k] + k);
        free(mask);
        h = fnv1a(h, &s, sizeof s);
    }
    return h;
}

/* Call number k (0..BODY_CALLS − 1) of every call that takes a body, with body b (and, where it takes two,
 * `mate`) in world w and arguments that would succeed for a body of w. */
#define BODY_CALLS 23
static pp_status body_call(int k, pp_world w, pp_body b, pp_body mate, const char **name)
{
    pp_vec2 v;
    float f;
    int32_t i32, i32b;
    int64_t i64;
    uint64_t u64;
    pp_body_type type;
    uint8_t pixels[BOX * BOX * 4] = {0};
    const uint8_t two[4] = {1, 1, 1, 1};
    pp_contact contacts[4];
    pp_collision_view view;
    const pp_timed_edit edit = {.time = 1, .type = PP_EDIT_ERASE_CIRCLE, .body = b, .center = {100, 100}, .radius = 3};
#define CALL(fn, ...) return *name = #fn, fn(__VA_ARGS__)
    switch (k) {
    case 0: CALL(pp_body_get_position, w, b, &v);
    case 1: CALL(pp_body_get_angle, w, b, &f);
    case 2: CALL(pp_body_set_transform, w, b, v2(30, 40), 0.5f);
    case 3: CALL(pp_body_get_velocity, w, b, &v, &f);
    case 4: CALL(pp_body_set_velocity, w, b, v2(50, 0), 1);
    case 5: CALL(pp_body_apply_impulse, w, b, v2(0, -1000), v2(104, 100));
    case 6: CALL(pp_body_get_mass, w, b, &f, &v, &f);
    case 7: CALL(pp_body_get_memory, w, b, &i64, &i64);
    case 8: CALL(pp_body_is_awake, w, b, &i32);
    case 9: CALL(pp_body_erase_circle, w, b, v2(100, 100), 4, &i32);
    case 10: CALL(pp_body_paint_circle, w, b, v2(100, 100), 4, 200, &i32);
    case 11: CALL(pp_body_write_pixels, w, b, 0, 0, 2, 2, two, NULL);
    case 12: CALL(pp_body_read_mask, w, b, pixels, sizeof pixels);
    case 13: CALL(pp_body_read_rgba, w, b, pixels, sizeof pixels);
    case 14: CALL(pp_body_get_size, w, b, &i32, &i32b);
    case 15: CALL(pp_body_get_user_data, w, b, &u64);
    case 16: CALL(pp_body_get_pivot, w, b, &v);
    case 17: CALL(pp_body_get_type, w, b, &type);
    case 18: CALL(pp_world_collide, w, b, mate, contacts, 4, &i32);
    case 19: CALL(pp_world_collide, w, mate, b, contacts, 4, &i32);
    case 20: CALL(pp_world_debug_collision, w, b, mate, NULL, NULL, 0, &view);
    case 21: CALL(pp_world_schedule_edit, w, &edit);
    case 22: CALL(pp_body_destroy, w, b); /* last: it would take the body away */
    default: cr_assert_fail("no call %d", k); return PP_OK;
    }
#undef CALL
}

/* Before ids named their world, world A's box and world B's had one id, and every call below answered PP_OK
 * on A's box; pp_body_destroy destroyed it. */
Test(handles, a_body_of_another_world_is_refused_by_every_call)
{
    pp_body a_box, a_ground, b_box, b_ground;
    pp_world a = box_world(&a_box, &a_ground), b = box_world(&b_box, &b_ground);
    cr_assert_eq(handle_saved(a_box.id), handle_saved(b_box.id), "the two boxes should differ only in their world");
    step_n(a, 1.0f / 60, 3);
    step_n(b, 1.0f / 60, 5);
    const uint64_t ha = state_hash(a), hb = state_hash(b);
    char a_id[24], b_id[24];
    snprintf(a_id, sizeof a_id, "%#llx", (unsigned long long)a.id);
    snprintf(b_id, sizeof b_id, "%#llx", (unsigned long long)b.id);
    const char *name;
    for (int k = 0; k < BODY_CALLS; k++) {
        const pp_status st = body_call(k, a, b_box, a_ground, &name);
        const char *msg = pp_last_error();
        cr_assert_eq(st, PP_ERR_INVALID_HANDLE, "%s with world B's box in world A: %s (%s)", name, pp_status_name(st),
                     msg);
        cr_assert(strstr(msg, name) && strstr(msg, "belongs to world") && strstr(msg, b_id) && strstr(msg, a_id),
                  "%s: \"%s\" should name the call and both worlds (%s, %s)", name, msg, b_id, a_id);
    }
    cr_assert_eq(state_hash(a), ha, "a refused call changed world A");
    cr_assert_eq(state_hash(b), hb, "a refused call changed world B");
    /* Each call works with the handle of its own world. */
    for (int k = 0; k < BODY_CALLS; k++)
        if (k != 20) /* debug_collision with no room for the cells answers INVALID_ARGUMENT after filling the view */
            cr_assert_eq(body_call(k, a, a_box, a_ground, &name), PP_OK, "%s: %s", name, pp_last_error());
    PP_OK_OR_FAIL(pp_world_destroy(a));
    PP_OK_OR_FAIL(pp_world_destroy(b));
}

/* A host that replaces its world twice (as the plugin's and Godot's load_scene do) gets the first world's
 * slot back; a body handle kept from the first world is stale there, not the new world's body in its slot. */
Test(handles, a_handle_of_a_destroyed_world_is_stale_in_the_world_that_takes_its_slot)
{
    pp_body old_box, old_ground, box, ground;
    pp_world first = box_world(&old_box, &old_ground);
    PP_OK_OR_FAIL(pp_world_destroy(first));
    pp_world next = box_world(&box, &ground);
    cr_assert_eq(world_id_slot(next.id), world_id_slot(first.id), "the new world should take the freed slot");
    cr_assert_eq(handle_saved(box.id), handle_saved(old_box.id), "the bodies should differ only in their world");
    EXPECT_ERR(pp_body_get_position(next, old_box, &(pp_vec2){0}), PP_ERR_INVALID_HANDLE, "no longer exists");
    EXPECT_ERR(pp_body_destroy(next, old_box), PP_ERR_INVALID_HANDLE, "no longer exists");
    EXPECT_ERR(pp_body_set_velocity(next, old_box, v2(10, 0), 0), PP_ERR_INVALID_HANDLE, "no longer exists");
    cr_assert(body_vel(next, box).x == 0, "the new world's box was moved");
    EXPECT_ERR(pp_body_get_position(next, (pp_body){0}, &(pp_vec2){0}), PP_ERR_INVALID_HANDLE, "null");
    PP_OK_OR_FAIL(pp_body_destroy(next, box));
    EXPECT_ERR(pp_body_get_position(next, box, &(pp_vec2){0}), PP_ERR_INVALID_HANDLE, "null, destroyed or stale");
    PP_OK_OR_FAIL(pp_world_destroy(next));
}

/* w saved as a snapshot in a new folder made from the template `dir` (remove_tree it after) and loaded again. */
static pp_world saved_and_loaded(pp_world w, char *dir)
{
    char snap[64];
    cr_assert_not_null(mkdtemp(dir));
    snprintf(snap, sizeof snap, "%s/snap", dir);
    PP_OK_OR_FAIL(pp_world_save_snapshot(w, snap));
    pp_world l;
    PP_OK_OR_FAIL(pp_world_load_snapshot(snap, &l));
    return l;
}

/* A loaded snapshot keeps each body's slot and generation (a destroyed body's slot included), in the same
 * order; its handles name the loaded world, so the saved world's are refused there. */
Test(handles, a_loaded_snapshot_keeps_slots_and_generations_but_not_the_world)
{
    pp_world w = make_world(0, 980);
    pp_body made[4];
    for (int i = 0; i < 4; i++)
        made[i] = add_rect(w, body_def(PP_BODY_DYNAMIC, 40.0f * i, 0, 0), 8, 8);
    PP_OK_OR_FAIL(pp_body_destroy(w, made[1]));
    made[1] = add_rect(w, body_def(PP_BODY_DYNAMIC, 40, 0, 0), 8, 8); /* slot 1 again, generation 2 */
    cr_assert_eq(handle_gen(made[1].id), 2);
    char dir[] = "/tmp/pp_handles_XXXXXX";
    const pp_world l = saved_and_loaded(w, dir);
    pp_body loaded[4];
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(l, loaded, 4, &n));
    cr_assert_eq(n, 4);
    for (int i = 0; i < 4; i++) {
        cr_assert_eq(handle_saved(loaded[i].id), handle_saved(made[i].id), "body %d changed slot or generation", i);
        cr_assert_neq(loaded[i].id, made[i].id, "body %d's handle does not name the loaded world", i);
        cr_assert(body_pos(l, loaded[i]).x == body_pos(w, made[i]).x);
        EXPECT_ERR(pp_body_get_position(l, made[i], &(pp_vec2){0}), PP_ERR_INVALID_HANDLE, "belongs to world");
        EXPECT_ERR(pp_body_get_position(w, loaded[i], &(pp_vec2){0}), PP_ERR_INVALID_HANDLE, "belongs to world");
    }
    PP_OK_OR_FAIL(pp_world_destroy(w));
    PP_OK_OR_FAIL(pp_world_destroy(l));
    remove_tree(dir);
}

/* A world's first body (a box) and first joint (a hinge from the static world to it): both take slot 0. */
static pp_world box_and_hinge(pp_body *box, pp_joint *j, pp_joint_def *d)
{
    pp_world w = make_world(0, 980);
    *box = add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), BOX, BOX);
    *d = pp_joint_def_default(PP_JOINT_REVOLUTE);
    d->body_b = *box;
    d->anchor_a = v2(100, 92);
    PP_OK_OR_FAIL(pp_joint_create(w, d, j));
    return w;
}

/* A world's first body and first joint both take slot 0 of their tables. Before ids carried their kind the two
 * had one id: pp_joint_destroy(w, (pp_joint){body.id}) answered PP_OK and removed the joint. */
Test(handles, a_body_handle_is_not_a_joint_and_a_joint_handle_is_not_a_body)
{
    pp_body box;
    pp_joint j;
    pp_joint_def d;
    pp_world w = box_and_hinge(&box, &j, &d);
    cr_assert_eq(handle_slot(j.id), handle_slot(box.id), "the first joint and the first body should share a slot");
    const pp_joint box_as_joint = {box.id};
    const pp_body joint_as_body = {j.id};
    pp_vec2 v;
    float f;
    EXPECT_ERR(pp_joint_destroy(w, box_as_joint), PP_ERR_INVALID_HANDLE, "is a body handle, not a joint");
    EXPECT_ERR(pp_joint_get_reaction(w, box_as_joint, &v, &f), PP_ERR_INVALID_HANDLE, "is a body handle, not a joint");
    EXPECT_ERR(pp_joint_set_motor(w, box_as_joint, 1, 1, 1), PP_ERR_INVALID_HANDLE, "is a body handle, not a joint");
    EXPECT_ERR(pp_body_destroy(w, joint_as_body), PP_ERR_INVALID_HANDLE, "is a joint handle, not a body");
    EXPECT_ERR(pp_body_get_position(w, joint_as_body, &v), PP_ERR_INVALID_HANDLE, "is a joint handle, not a body");
    EXPECT_ERR(pp_body_set_velocity(w, joint_as_body, v2(10, 0), 0), PP_ERR_INVALID_HANDLE, "is a joint handle");
    d.body_b = joint_as_body;
    EXPECT_ERR(pp_joint_create(w, &d, &(pp_joint){0}), PP_ERR_INVALID_HANDLE, "is a joint handle, not a body");
    EXPECT_ERR(pp_world_step((pp_world){box.id}, 1.0f / 60), PP_ERR_INVALID_HANDLE, "is a body handle, not a world");
    EXPECT_ERR(pp_body_get_position(w, (pp_body){w.id}, &v), PP_ERR_INVALID_HANDLE, "is a world handle, not a body");
    /* Both are still there, and each works as what it is. */
    int32_t bodies = 0, joints = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, NULL, 0, &bodies));
    PP_OK_OR_FAIL(pp_world_get_joints(w, NULL, 0, &joints));
    cr_assert(bodies == 1 && joints == 1, "a refused call removed something: %d bodies, %d joints", bodies, joints);
    cr_assert(body_vel(w, box).x == 0, "a refused call moved the box");
    PP_OK_OR_FAIL(pp_joint_destroy(w, j));
    PP_OK_OR_FAIL(pp_body_destroy(w, box));
    PP_OK_OR_FAIL(pp_world_destroy(w));
}

/* A loaded snapshot's handles keep their kinds: its joint is a joint and its body a body. */
Test(handles, a_loaded_snapshot_keeps_the_kinds_of_its_handles)
{
    pp_body box;
    pp_joint j;
    pp_joint_def d;
    pp_world w = box_and_hinge(&box, &j, &d);
    char dir[] = "/tmp/pp_handles_XXXXXX";
    const pp_world l = saved_and_loaded(w, dir);
    pp_body lb;
    pp_joint lj;
    int32_t n = 0;
    PP_OK_OR_FAIL(pp_world_get_bodies(l, &lb, 1, &n));
    PP_OK_OR_FAIL(pp_world_get_joints(l, &lj, 1, &n));
    pp_vec2 v;
    PP_OK_OR_FAIL(pp_body_get_position(l, lb, &v));
    PP_OK_OR_FAIL(pp_joint_get_reaction(l, lj, &v, NULL));
    EXPECT_ERR(pp_joint_destroy(l, (pp_joint){lb.id}), PP_ERR_INVALID_HANDLE, "is a body handle, not a joint");
    EXPECT_ERR(pp_body_destroy(l, (pp_body){lj.id}), PP_ERR_INVALID_HANDLE, "is a joint handle, not a body");
    PP_OK_OR_FAIL(pp_world_destroy(w));
    PP_OK_OR_FAIL(pp_world_destroy(l));
    remove_tree(dir);
}
