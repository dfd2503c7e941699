/* Misuse answered with the exact status and a message naming the argument; state left intact. */
#include "helpers.h"

PP_TEST_SUITE(misuse);

static pp_world misuse_world(void) { return make_world(0, 980); }

static pp_body misuse_box(pp_world w) { return add_rect(w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 8, 8); }

static int32_t body_count(pp_world w) {
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_get_bodies(w, NULL, 0, &n));
    return n;
}

Test(misuse, status_names_and_version) {
    cr_assert_str_eq(pp_status_name(PP_ERR_LIMIT), "PP_ERR_LIMIT");
    cr_assert_str_eq(pp_status_name(PP_OK), "PP_OK");
    cr_assert_str_eq(pp_status_name(PP_ERR_INVALID_ARGUMENT), "PP_ERR_INVALID_ARGUMENT");
    cr_assert_str_eq(pp_status_name(PP_ERR_INVALID_HANDLE), "PP_ERR_INVALID_HANDLE");
    cr_assert_str_eq(pp_status_name(PP_ERR_OUT_OF_MEMORY), "PP_ERR_OUT_OF_MEMORY");
    cr_assert_str_eq(pp_status_name(PP_ERR_IO), "PP_ERR_IO");
    cr_assert_str_eq(pp_status_name(PP_ERR_FORMAT), "PP_ERR_FORMAT");
    cr_assert_str_eq(pp_status_name(PP_ERR_UNSUPPORTED), "PP_ERR_UNSUPPORTED");
    cr_assert_str_eq(pp_status_name(PP_ERR_ABI), "PP_ERR_ABI");
    cr_assert_not_null(pp_status_name((pp_status)12345), "an unknown status must still have a name");
    cr_assert_not_null(pp_last_error());
    cr_assert_eq(pp_version(), PHYSPIX_VERSION_MAJOR * 10000u + PHYSPIX_VERSION_MINOR * 100u + PHYSPIX_VERSION_PATCH);
}

Test(misuse, defaults_are_documented_values) {
    pp_world_def wd = pp_world_def_default();
    cr_assert_eq(wd.struct_size, sizeof(pp_world_def));
    cr_assert_float_eq(wd.gravity.x, 0.0, 0.0);
    cr_assert_float_eq(wd.gravity.y, 980.0, 0.0);
    cr_assert_eq(wd.substeps, 4);
    cr_assert_eq(wd.solver_iterations, 20);
    cr_assert_eq(wd.normal_method, PP_NORMAL_AREA_GRADIENT);
    cr_assert_eq(wd.contact_mode, PP_CONTACT_MANIFOLD);
    cr_assert_eq(wd.backend, PP_BACKEND_AUTO);
    cr_assert_eq(wd.continuous, 1u);
    /* The balanced preset is the default, field for field. */
    const pp_world_def balanced = pp_world_def_preset(PP_PRESET_BALANCED);
    cr_assert(memcmp(&wd, &balanced, sizeof wd) == 0);
    pp_body_def bd = pp_body_def_default();
    cr_assert_eq(bd.struct_size, sizeof(pp_body_def));
    cr_assert_eq(bd.type, PP_BODY_DYNAMIC);
    cr_assert_float_eq(bd.density, 1.0, 0.0);
    cr_assert_float_eq(bd.friction, 0.6, 1e-6);
    cr_assert_float_eq(bd.restitution, 0.0, 0.0);
    cr_assert_eq(bd.category_bits, 1u);
    cr_assert_eq(bd.mask_bits, 0xffffffffu);
    cr_assert_eq(bd.alpha_threshold, 128u);
    cr_assert_null(bd.rgba);
    cr_assert_null(bd.mask);
    cr_assert_null(bd.weights);
    cr_assert_eq(bd.bullet, 0u);
}

Test(misuse, unknown_preset) {
    /* A preset the library does not know gives a def that every call refuses, with a message that says why. */
    const pp_preset unknown[] = {0, 4, (pp_preset)-1};
    for (int k = 0; k < 3; k++) {
        pp_world_def wd = pp_world_def_preset(unknown[k]);
        cr_assert_eq(wd.struct_size, 0u);
        pp_world w = {0x1234};
        EXPECT_ERR(pp_world_create(&wd, &w), PP_ERR_ABI, "struct_size is 0");
        char want[160];
        snprintf(want, sizeof want, "pp_world_create: def->struct_size is 0, this library expects %zu "
                 "(fill the def from pp_world_def_default or a known preset)", sizeof(pp_world_def));
        cr_assert_str_eq(pp_last_error(), want);
        cr_assert_eq(w.id, 0x1234u, "out was written on failure");
    }
    for (pp_preset p = PP_PRESET_FAST; p <= PP_PRESET_ACCURATE; p++) {
        pp_world_def wd = pp_world_def_preset(p);
        pp_world w;
        pp_world_def got;
        PP_OK_OR_FAIL(pp_world_create(&wd, &w));
        PP_OK_OR_FAIL(pp_world_get_def(w, &got));
        cr_assert(memcmp(&wd, &got, sizeof wd) == 0, "preset %d: the world runs with other settings", (int)p);
        PP_OK_OR_FAIL(pp_world_destroy(w));
        EXPECT_ERR(pp_world_get_def(w, &got), PP_ERR_INVALID_HANDLE, "world|handle");
    }
    pp_world w = misuse_world();
    EXPECT_ERR(pp_world_get_def(w, NULL), PP_ERR_INVALID_ARGUMENT, "out is NULL");
    pp_world_destroy(w);
}

Test(misuse, zero_and_stale_body_handles) {
    pp_world w = misuse_world();
    pp_body b = misuse_box(w);
    pp_body keep = misuse_box(w);
    pp_vec2 p;
    float a;
    pp_body zero = {0};
    EXPECT_ERR(pp_body_get_position(w, zero, &p), PP_ERR_INVALID_HANDLE, "body|handle");

    PP_OK_OR_FAIL(pp_body_destroy(w, b));
    cr_assert_eq(body_count(w), 1);
    EXPECT_ERR(pp_body_get_position(w, b, &p), PP_ERR_INVALID_HANDLE, "body|handle");
    EXPECT_ERR(pp_body_get_angle(w, b, &a), PP_ERR_INVALID_HANDLE, "body|handle");
    EXPECT_ERR(pp_body_set_transform(w, b, v2(0, 0), 0), PP_ERR_INVALID_HANDLE, "body|handle");
    EXPECT_ERR(pp_body_set_velocity(w, b, v2(0, 0), 0), PP_ERR_INVALID_HANDLE, "body|handle");
    EXPECT_ERR(pp_body_apply_impulse(w, b, v2(1, 0), v2(100, 100)), PP_ERR_INVALID_HANDLE, "body|handle");
    EXPECT_ERR(pp_body_get_mass(w, b, NULL, NULL, NULL), PP_ERR_INVALID_HANDLE, "body|handle");
    EXPECT_ERR(pp_body_destroy(w, b), PP_ERR_INVALID_HANDLE, "body|handle");
    int32_t n;
    pp_contact c;
    EXPECT_ERR(pp_world_collide(w, b, keep, &c, 1, &n), PP_ERR_INVALID_HANDLE, "body|handle");

    /* A new body reusing the freed slot must not revive the stale handle. */
    pp_body again = misuse_box(w);
    cr_assert_neq(again.id, b.id, "a new body got the destroyed body's id");
    EXPECT_ERR(pp_body_get_position(w, b, &p), PP_ERR_INVALID_HANDLE, "body|handle");
    PP_OK_OR_FAIL(pp_body_get_position(w, again, &p));
    PP_OK_OR_FAIL(pp_body_get_position(w, keep, &p));
    cr_assert_eq(body_count(w), 2);
    pp_world_destroy(w);
}

Test(misuse, zero_and_destroyed_world_handles) {
    pp_world zero = {0};
    EXPECT_ERR(pp_world_step(zero, 1.0f / 60), PP_ERR_INVALID_HANDLE, "world|handle");
    EXPECT_ERR(pp_world_destroy(zero), PP_ERR_INVALID_HANDLE, "world|handle");

    pp_world w = misuse_world();
    pp_body b = misuse_box(w);
    PP_OK_OR_FAIL(pp_world_destroy(w));
    pp_vec2 p;
    int32_t n;
    EXPECT_ERR(pp_world_step(w, 1.0f / 60), PP_ERR_INVALID_HANDLE, "world|handle");
    EXPECT_ERR(pp_world_destroy(w), PP_ERR_INVALID_HANDLE, "world|handle");
    EXPECT_ERR(pp_body_get_position(w, b, &p), PP_ERR_INVALID_HANDLE, "world|handle");
    EXPECT_ERR(pp_world_get_bodies(w, NULL, 0, &n), PP_ERR_INVALID_HANDLE, "world|handle");
    EXPECT_ERR(pp_world_get_contacts(w, NULL, 0, &n), PP_ERR_INVALID_HANDLE, "world|handle");
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 0, 0, 0);
    uint8_t m[4] = {1, 1, 1, 1};
    d.width = d.height = 2;
    d.mask = m;
    pp_body nb;
    EXPECT_ERR(pp_body_create(w, &d, &nb), PP_ERR_INVALID_HANDLE, "world|handle");

    /* A new world does not revive the old handle, nor make its bodies valid. */
    pp_world w2 = misuse_world();
    cr_assert_neq(w2.id, w.id, "a new world got the destroyed world's id");
    EXPECT_ERR(pp_world_step(w, 1.0f / 60), PP_ERR_INVALID_HANDLE, "world|handle");
    PP_OK_OR_FAIL(pp_world_step(w2, 1.0f / 60));
    pp_world_destroy(w2);
}

Test(misuse, bad_dt) {
    pp_world w = misuse_world();
    pp_body b = misuse_box(w);
    pp_vec2 p0 = body_pos(w, b);
    const float bad[] = {NAN, INFINITY, -INFINITY, -1.0f / 60, 0.0f, -0.0f, 1.5f};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        EXPECT_ERR(pp_world_step(w, bad[i]), PP_ERR_INVALID_ARGUMENT, "dt");
    pp_vec2 p1 = body_pos(w, b);
    cr_assert(p0.x == p1.x && p0.y == p1.y, "a refused step moved the body from (%g, %g) to (%g, %g)", p0.x, p0.y,
              p1.x, p1.y);
    PP_OK_OR_FAIL(pp_world_step(w, 1.0f)); /* the documented upper bound is accepted */
    pp_world_destroy(w);
}

Test(misuse, non_finite_pose_and_velocity_in_create) {
    pp_world w = misuse_world();
    misuse_box(w);
    uint8_t m[16];
    memset(m, 1, sizeof m);
    pp_body_def ok = body_def(PP_BODY_DYNAMIC, 10, 10, 0);
    ok.width = ok.height = 4;
    ok.mask = m;
    pp_body b;
    pp_body_def d;

    d = ok, d.position.x = NAN;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "position");
    d = ok, d.position.y = INFINITY;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "position");
    d = ok, d.angle = NAN;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "angle");
    d = ok, d.linear_velocity.x = -INFINITY;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "velocity");
    d = ok, d.angular_velocity = NAN;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "angular");
    d = ok, d.custom_pivot = 1, d.pivot.x = NAN;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "pivot");
    d = ok, d.density = NAN;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "density");
    cr_assert_eq(body_count(w), 1, "failed creates changed the body count");
    PP_OK_OR_FAIL(pp_body_create(w, &ok, &b));
    cr_assert_eq(body_count(w), 2);
    pp_world_destroy(w);
}

Test(misuse, non_finite_transform_and_velocity) {
    pp_world w = misuse_world();
    pp_body b = misuse_box(w);
    PP_OK_OR_FAIL(pp_body_set_transform(w, b, v2(50, 60), 0.25f));
    PP_OK_OR_FAIL(pp_body_set_velocity(w, b, v2(3, 4), 0.5f));

    EXPECT_ERR(pp_body_set_transform(w, b, v2(NAN, 0), 0), PP_ERR_INVALID_ARGUMENT, "position");
    EXPECT_ERR(pp_body_set_transform(w, b, v2(0, INFINITY), 0), PP_ERR_INVALID_ARGUMENT, "position");
    EXPECT_ERR(pp_body_set_transform(w, b, v2(0, 0), NAN), PP_ERR_INVALID_ARGUMENT, "angle");
    EXPECT_ERR(pp_body_set_velocity(w, b, v2(NAN, 0), 0), PP_ERR_INVALID_ARGUMENT, "velocity|linear");
    EXPECT_ERR(pp_body_set_velocity(w, b, v2(0, -INFINITY), 0), PP_ERR_INVALID_ARGUMENT, "velocity|linear");
    EXPECT_ERR(pp_body_set_velocity(w, b, v2(0, 0), INFINITY), PP_ERR_INVALID_ARGUMENT, "angular");
    EXPECT_ERR(pp_body_apply_impulse(w, b, v2(NAN, 0), v2(100, 100)), PP_ERR_INVALID_ARGUMENT, "impulse");
    EXPECT_ERR(pp_body_apply_impulse(w, b, v2(1, 0), v2(100, INFINITY)), PP_ERR_INVALID_ARGUMENT, "point");
    /* Finite, but giving a spin past a float (fuzz_api): refused, not handed to ODE. */
    EXPECT_ERR(pp_body_apply_impulse(w, b, v2(0, 1e30f), v2(1e30f, 60)), PP_ERR_INVALID_ARGUMENT, "PP_MAX_SPEED");

    /* Nothing changed. */
    pp_vec2 p = body_pos(w, b), v;
    float a = body_angle(w, b), av;
    PP_OK_OR_FAIL(pp_body_get_velocity(w, b, &v, &av));
    cr_assert(p.x == 50 && p.y == 60, "position now (%g, %g), want (50, 60)", p.x, p.y);
    cr_assert_float_eq(a, 0.25, 1e-6, "angle now %g, want 0.25", a);
    cr_assert_float_eq(v.x, 3, 1e-4, "velocity now (%g, %g), want (3, 4)", v.x, v.y);
    cr_assert_float_eq(v.y, 4, 1e-4, "velocity now (%g, %g), want (3, 4)", v.x, v.y);
    cr_assert_float_eq(av, 0.5, 1e-5, "angular velocity now %g, want 0.5", av);
    pp_world_destroy(w);
}

Test(misuse, wrong_struct_size) {
    pp_world_def wd = pp_world_def_default();
    pp_world w;
    wd.struct_size = sizeof(pp_world_def) - 4;
    EXPECT_ERR(pp_world_create(&wd, &w), PP_ERR_ABI, "struct_size");
    wd.struct_size = sizeof(pp_world_def) + 8;
    EXPECT_ERR(pp_world_create(&wd, &w), PP_ERR_ABI, "struct_size");
    wd.struct_size = 0;
    EXPECT_ERR(pp_world_create(&wd, &w), PP_ERR_ABI, "struct_size");

    w = misuse_world();
    uint8_t m[4] = {1, 1, 1, 1};
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 0, 0, 0);
    d.width = d.height = 2;
    d.mask = m;
    d.struct_size = sizeof(pp_body_def) - 8;
    pp_body b;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_ABI, "struct_size");
    cr_assert_eq(body_count(w), 0);
    pp_world_destroy(w);
}

Test(misuse, bitmap_size_limits_checked_before_reading) {
    pp_world w = misuse_world();
    /* A 4-byte buffer: the limit must be checked before the planes are read. */
    uint8_t tiny[4] = {1, 1, 1, 1};
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 0, 0, 0);
    d.mask = tiny;
    pp_body b;

    d.width = PP_MAX_BITMAP_SIDE + 1, d.height = 1;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_LIMIT, "width");
    d.width = 1, d.height = PP_MAX_BITMAP_SIDE + 1;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_LIMIT, "height");
    d.width = PP_MAX_BITMAP_SIDE, d.height = PP_MAX_BITMAP_SIDE; /* each side legal, area 4× too big */
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_LIMIT, "width|height|area");
    d.width = PP_MAX_BITMAP_SIDE, d.height = PP_MAX_BITMAP_AREA / PP_MAX_BITMAP_SIDE + 1;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_LIMIT, "width|height|area");
    d.width = INT32_MAX, d.height = INT32_MAX; /* would overflow a 32-bit product */
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_LIMIT, "width|height|area");
    /* Same with an rgba plane. */
    d.mask = NULL, d.rgba = tiny;
    d.width = PP_MAX_BITMAP_SIDE + 1, d.height = 1;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_LIMIT, "width");

    cr_assert_eq(body_count(w), 0);
    pp_world_destroy(w);
}

Test(misuse, bad_width_height_and_planes) {
    pp_world w = misuse_world();
    uint8_t m[16];
    memset(m, 1, sizeof m);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 0, 0, 0);
    d.mask = m;
    pp_body b;

    d.width = 0, d.height = 4;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "width");
    d.width = -4, d.height = 4;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "width");
    d.width = 4, d.height = 0;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "height");
    d.width = 4, d.height = -1;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "height");

    /* No rgba and no mask: no shape. Weights alone are not a shape. */
    d.width = d.height = 4;
    d.mask = NULL;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "mask|rgba|bitmap|plane");
    d.weights = m;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "mask|rgba|bitmap|plane");
    cr_assert_eq(body_count(w), 0);
    pp_world_destroy(w);
}

Test(misuse, dynamic_body_without_mass) {
    pp_world w = misuse_world();
    uint8_t empty[16] = {0}, full[16], zero_w[16] = {0};
    memset(full, 1, sizeof full);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 0, 0, 0);
    d.width = d.height = 4;
    pp_body b;

    d.mask = empty; /* no solid pixel */
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "solid|mass|pixel|empty");
    uint8_t rgba[64] = {0}; /* fully transparent sprite */
    d.mask = NULL, d.rgba = rgba;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "solid|mass|pixel|empty");
    d.rgba = NULL, d.mask = full, d.weights = zero_w; /* solid but weightless */
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "weight|mass");
    d.weights = NULL, d.density = 0.0f;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "density|mass");
    d.density = -1.0f;
    EXPECT_ERR(pp_body_create(w, &d, &b), PP_ERR_INVALID_ARGUMENT, "density");
    cr_assert_eq(body_count(w), 0);

    /* The same full mask with density 1 is fine. */
    d.density = 1.0f;
    b = create_body_ok(w, &d);
    cr_assert_eq(body_count(w), 1);
    pp_world_destroy(w);
}

Test(misuse, null_out_pointers) {
    pp_world_def wd = pp_world_def_default();
    EXPECT_ERR(pp_world_create(&wd, NULL), PP_ERR_INVALID_ARGUMENT, "out");
    pp_world w;
    EXPECT_ERR(pp_world_create(NULL, &w), PP_ERR_INVALID_ARGUMENT, "def");

    w = misuse_world();
    pp_body b = misuse_box(w);
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 0, 0, 0);
    uint8_t m[4] = {1, 1, 1, 1};
    d.width = d.height = 2;
    d.mask = m;
    EXPECT_ERR(pp_body_create(w, &d, NULL), PP_ERR_INVALID_ARGUMENT, "out");
    pp_body nb;
    EXPECT_ERR(pp_body_create(w, NULL, &nb), PP_ERR_INVALID_ARGUMENT, "def");
    cr_assert_eq(body_count(w), 1);
    EXPECT_ERR(pp_body_get_position(w, b, NULL), PP_ERR_INVALID_ARGUMENT, "out");
    EXPECT_ERR(pp_body_get_angle(w, b, NULL), PP_ERR_INVALID_ARGUMENT, "out");
    EXPECT_ERR(pp_body_get_user_data(w, b, NULL), PP_ERR_INVALID_ARGUMENT, "out");
    EXPECT_ERR(pp_body_is_awake(w, b, NULL), PP_ERR_INVALID_ARGUMENT, "out|awake");
    EXPECT_ERR(pp_world_get_stats(w, NULL), PP_ERR_INVALID_ARGUMENT, "out");
    EXPECT_ERR(pp_world_get_bodies(w, NULL, 0, NULL), PP_ERR_INVALID_ARGUMENT, "count");
    EXPECT_ERR(pp_world_get_contacts(w, NULL, 0, NULL), PP_ERR_INVALID_ARGUMENT, "count");
    /* Both velocity pointers and all mass pointers may be NULL. */
    PP_OK_OR_FAIL(pp_body_get_velocity(w, b, NULL, NULL));
    PP_OK_OR_FAIL(pp_body_get_mass(w, b, NULL, NULL, NULL));
    pp_world_destroy(w);
}

Test(misuse, null_buffer_with_capacity_or_negative_capacity) {
    pp_world w = misuse_world();
    pp_body a = misuse_box(w), b = misuse_box(w);
    int32_t n = -1;
    EXPECT_ERR(pp_world_get_bodies(w, NULL, 4, &n), PP_ERR_INVALID_ARGUMENT, "out|capacity");
    EXPECT_ERR(pp_world_get_contacts(w, NULL, 4, &n), PP_ERR_INVALID_ARGUMENT, "out|capacity");
    EXPECT_ERR(pp_world_collide(w, a, b, NULL, 4, &n), PP_ERR_INVALID_ARGUMENT, "out|capacity");
    pp_body arr[2];
    pp_contact c[2];
    EXPECT_ERR(pp_world_get_bodies(w, arr, -1, &n), PP_ERR_INVALID_ARGUMENT, "capacity");
    EXPECT_ERR(pp_world_get_contacts(w, c, -1, &n), PP_ERR_INVALID_ARGUMENT, "capacity");
    EXPECT_ERR(pp_world_collide(w, a, b, c, 2, NULL), PP_ERR_INVALID_ARGUMENT, "count");
    pp_world_destroy(w);
}

Test(misuse, documented_ranges) {
    pp_world_def wd = pp_world_def_default();
    pp_world w;
    pp_world_def d;
    d = wd, d.substeps = 65;
    EXPECT_ERR(pp_world_create(&d, &w), PP_ERR_INVALID_ARGUMENT, "substeps");
    d = wd, d.substeps = -1;
    EXPECT_ERR(pp_world_create(&d, &w), PP_ERR_INVALID_ARGUMENT, "substeps");
    d = wd, d.solver_iterations = 1001;
    EXPECT_ERR(pp_world_create(&d, &w), PP_ERR_INVALID_ARGUMENT, "solver_iterations|iterations");
    d = wd, d.raster_stride = 3;
    EXPECT_ERR(pp_world_create(&d, &w), PP_ERR_INVALID_ARGUMENT, "raster_stride|stride");
    d = wd, d.contact_erp = 1.5f;
    EXPECT_ERR(pp_world_create(&d, &w), PP_ERR_INVALID_ARGUMENT, "erp");
    d = wd, d.gravity.y = NAN;
    EXPECT_ERR(pp_world_create(&d, &w), PP_ERR_INVALID_ARGUMENT, "gravity");
    d = wd, d.normal_method = (pp_normal_method)7;
    EXPECT_ERR(pp_world_create(&d, &w), PP_ERR_INVALID_ARGUMENT, "normal");
    d = wd, d.contact_mode = (pp_contact_mode)7;
    EXPECT_ERR(pp_world_create(&d, &w), PP_ERR_INVALID_ARGUMENT, "contact_mode|mode");
    w = make_world_def(&wd);

    uint8_t m[4] = {1, 1, 1, 1};
    pp_body_def ok = body_def(PP_BODY_DYNAMIC, 0, 0, 0);
    ok.width = ok.height = 2;
    ok.mask = m;
    pp_body_def bd;
    pp_body b;
    bd = ok, bd.friction = -0.1f;
    EXPECT_ERR(pp_body_create(w, &bd, &b), PP_ERR_INVALID_ARGUMENT, "friction");
    bd = ok, bd.restitution = 1.5f;
    EXPECT_ERR(pp_body_create(w, &bd, &b), PP_ERR_INVALID_ARGUMENT, "restitution");
    bd = ok, bd.restitution = -0.5f;
    EXPECT_ERR(pp_body_create(w, &bd, &b), PP_ERR_INVALID_ARGUMENT, "restitution");
    bd = ok, bd.type = (pp_body_type)9;
    EXPECT_ERR(pp_body_create(w, &bd, &b), PP_ERR_INVALID_ARGUMENT, "type");
    bd = ok, bd.alpha_threshold = 256, bd.mask = NULL, bd.rgba = (const uint8_t *)"\xff\xff\xff\xff\xff\xff\xff\xff"
                                                                                  "\xff\xff\xff\xff\xff\xff\xff\xff";
    EXPECT_ERR(pp_body_create(w, &bd, &b), PP_ERR_INVALID_ARGUMENT, "alpha_threshold|alpha");
    cr_assert_eq(body_count(w), 0);
    pp_world_destroy(w);
}

Test(misuse, zero_count_fields_mean_default) {
    /* physpix.h: "Zero in a count field means its default." */
    pp_world_def wd = pp_world_def_default();
    pp_world w;
    pp_world_def d;
    d = wd, d.substeps = 0;
    PP_OK_OR_FAIL(pp_world_create(&d, &w));
    pp_world_destroy(w);
    d = wd, d.solver_iterations = 0;
    PP_OK_OR_FAIL(pp_world_create(&d, &w));
    pp_world_destroy(w);
    d = wd, d.raster_stride = 0;
    PP_OK_OR_FAIL(pp_world_create(&d, &w));
    pp_world_destroy(w);
}

Test(misuse, impulse_on_static_body) {
    pp_world w = misuse_world();
    pp_body s = add_rect(w, body_def(PP_BODY_STATIC, 100, 100, 0), 10, 10);
    EXPECT_ERR(pp_body_apply_impulse(w, s, v2(100, 0), v2(100, 100)), PP_ERR_INVALID_ARGUMENT, "dynamic|static");
    pp_vec2 p = body_pos(w, s);
    cr_assert(p.x == 100 && p.y == 100);
    pp_world_destroy(w);
}

Test(misuse, contacts_and_bodies_capacity_semantics) {
    pp_world w = misuse_world();
    pp_body ground = add_rect(w, body_def(PP_BODY_STATIC, 400, 500, 0), 800, 40);
    pp_body box = add_rect(w, body_def(PP_BODY_DYNAMIC, 400, 466, 0), 32, 32); /* 2 px into the ground */
    PP_OK_OR_FAIL(pp_world_step(w, 1.0f / 60));

    int32_t total = -1;
    PP_OK_OR_FAIL(pp_world_get_contacts(w, NULL, 0, &total));
    cr_assert_geq(total, 1, "a box sunk into the ground made %d contacts", total);
    cr_assert_leq(total, 2, "one MANIFOLD pair made %d contacts", total);

    pp_contact c[4];
    memset(c, 0xAB, sizeof c);
    int32_t n = -1;
    PP_OK_OR_FAIL(pp_world_get_contacts(w, c, 1, &n));
    cr_assert_eq(n, total, "count with capacity 1 is %d, total %d", n, total);
    /* Only one item written: the second stays as we filled it. */
    unsigned char pattern[sizeof(pp_contact)];
    memset(pattern, 0xAB, sizeof pattern);
    cr_assert(memcmp(&c[1], pattern, sizeof pattern) == 0, "wrote past capacity 1");
    PP_OK_OR_FAIL(pp_world_get_contacts(w, c, 4, &n));
    cr_assert_eq(n, total);
    for (int k = 0; k < n; k++) {
        int ab = c[k].a.id == box.id && c[k].b.id == ground.id;
        int ba = c[k].a.id == ground.id && c[k].b.id == box.id;
        cr_assert(ab || ba, "contact %d is not between the box and the ground", k);
        double want_ny = ab ? 1.0 : -1.0; /* from a to b */
        cr_assert_lt(angle_between_deg(c[k].normal.x, c[k].normal.y, 0, want_ny), 2.0, "contact %d normal (%g, %g)",
                     k, c[k].normal.x, c[k].normal.y);
    }

    pp_body bs[3];
    memset(bs, 0, sizeof bs);
    PP_OK_OR_FAIL(pp_world_get_bodies(w, NULL, 0, &n));
    cr_assert_eq(n, 2);
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bs, 1, &n));
    cr_assert_eq(n, 2, "count with capacity 1 is %d, total 2", n);
    cr_assert(bs[0].id == box.id || bs[0].id == ground.id);
    cr_assert_eq(bs[1].id, 0, "wrote past capacity 1");
    PP_OK_OR_FAIL(pp_world_get_bodies(w, bs, 3, &n));
    cr_assert_eq(n, 2);
    cr_assert((bs[0].id == box.id && bs[1].id == ground.id) || (bs[0].id == ground.id && bs[1].id == box.id));
    cr_assert_eq(bs[2].id, 0);
    pp_world_destroy(w);
}
