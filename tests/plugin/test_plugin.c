/* The engine-plugin interface as a host sees it: the manifest and its malformed forms, refusal of a
 * newer host, struct-size checks, the levels, and every method of every class called with the
 * right argument types (the declared result comes back) and with each argument of a wrong type
 * (INVALID_ARGUMENT naming the argument). Built with ASan+UBSan; LSan checks after each test. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "plugin_host.h"

#include <criterion/criterion.h>
#include <dirent.h>
#include <dlfcn.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
static void leak_check(void) { __lsan_do_recoverable_leak_check(); }
#else
static void leak_check(void) {}
#endif

#define V_BOOL(x) ((pp_variant){.type = PP_VARIANT_BOOL, .as.boolean = (x)})

static const char *const MANIFEST = "plugin/physpix.plugin";
static char last_log[1024];

static void capture_log(int level, const char *message, void *user)
{
    (void)level, (void)user;
    snprintf(last_log, sizeof last_log, "%s", message);
}

static pp_host_interface host_v(uint32_t version)
{
    return (pp_host_interface){sizeof(pp_host_interface), version, "test host", capture_log, NULL};
}

/* Write a manifest whose [libraries] entry is `library` (absolute), with the given configuration lines. */
static void write_manifest(const char *path, const char *configuration, const char *library)
{
    FILE *f = fopen(path, "w");
    cr_assert(f);
    fprintf(f, "[configuration]\n%s\n[libraries]\n%s = \"%s\"\n", configuration, HOST_PLATFORM, library);
    fclose(f);
}

static const char *plugin_path(void)
{
    static char path[PATH_MAX];
    cr_assert(realpath("build/libphyspix_plugin.so", path), "build/libphyspix_plugin.so is missing; run make all");
    return path;
}

/* ---- manifests ---- */

TestSuite(manifest, .fini = leak_check);

Test(manifest, the_shipped_manifest_names_the_entry_and_the_library)
{
    host_manifest m;
    char err[512] = "";
    cr_assert_eq(host_manifest_read(MANIFEST, "linux.x86_64", &m, err, sizeof err), PP_OK, "%s", err);
    cr_assert_str_eq(m.entry_symbol, PP_PLUGIN_ENTRY_SYMBOL);
    cr_assert_eq(m.compatibility_minimum, 1);
    cr_assert_str_eq(m.library, "plugin/../build/libphyspix_plugin.so", "library paths are relative to the manifest");
}

Test(manifest, malformed_manifests_name_the_file_the_line_and_the_fault)
{
    const struct {
        const char *text;
        pp_status status;
        const char *says;
    } cases[] = {
        {"[configuration\nentry_symbol = x\n", PP_ERR_FORMAT, ":1: malformed section header"},
        {"[configuration]\nentry_symbol\n", PP_ERR_FORMAT, ":2: expected key = value"},
        {"[configuration]\ncompatibility_minimum = 1\n[libraries]\nlinux.x86_64 = a.so\n", PP_ERR_FORMAT,
         "has no entry_symbol"},
        {"[configuration]\nentry_symbol = e\n[libraries]\nlinux.x86_64 = a.so\n", PP_ERR_FORMAT,
         "compatibility_minimum must be an interface version"},
        {"[configuration]\nentry_symbol = e\ncompatibility_minimum = \"1.x\"\n", PP_ERR_FORMAT, "got '1.x'"},
        {"[configuration]\nentry_symbol = e\ncompatibility_minimum = 1\n[libraries]\nwindows.x86_64 = a.dll\n",
         PP_ERR_UNSUPPORTED, "no library for platform linux.x86_64"},
    };
    char path[] = "/tmp/pp_manifest_XXXXXX";
    close(mkstemp(path));
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        FILE *f = fopen(path, "w");
        fputs(cases[i].text, f);
        fclose(f);
        host_manifest m;
        char err[512] = "";
        cr_assert_eq(host_manifest_read(path, "linux.x86_64", &m, err, sizeof err), cases[i].status, "case %zu: %s", i,
                     err);
        cr_assert(strstr(err, cases[i].says) && strstr(err, path), "case %zu: '%s' should say '%s'", i, err,
                  cases[i].says);
    }
    unlink(path);
    char err[512];
    host_manifest m;
    cr_assert_eq(host_manifest_read(path, "linux.x86_64", &m, err, sizeof err), PP_ERR_IO);
    cr_assert(strstr(err, "cannot open"), "%s", err);
}

/* ---- loading and refusal ---- */

TestSuite(load, .fini = leak_check);

Test(load, a_missing_library_or_entry_symbol_is_refused_with_the_reason)
{
    char path[] = "/tmp/pp_manifest_XXXXXX";
    close(mkstemp(path));
    const pp_host_interface host = host_v(PP_PLUGIN_INTERFACE_VERSION);
    host_plugin p;
    char err[1024];

    write_manifest(path, "entry_symbol = pp_plugin_entry\ncompatibility_minimum = 1", "/nonexistent/libx.so");
    cr_assert_eq(host_plugin_load(path, &host, &p, err, sizeof err), PP_ERR_IO);
    cr_assert(strstr(err, "cannot load /nonexistent/libx.so"), "%s", err);

    write_manifest(path, "entry_symbol = no_such_entry\ncompatibility_minimum = 1", plugin_path());
    cr_assert_eq(host_plugin_load(path, &host, &p, err, sizeof err), PP_ERR_FORMAT);
    cr_assert(strstr(err, "has no entry symbol 'no_such_entry'"), "%s", err);

    /* The manifest asks for a newer interface than this host implements. */
    write_manifest(path, "entry_symbol = pp_plugin_entry\ncompatibility_minimum = 2", plugin_path());
    cr_assert_eq(host_plugin_load(path, &host, &p, err, sizeof err), PP_ERR_UNSUPPORTED);
    cr_assert(strstr(err, "needs plugin interface 2 or newer; this host implements 1"), "%s", err);
    cr_assert_null(p.library);
    unlink(path);
}

Test(load, a_host_built_for_a_newer_interface_is_refused_with_a_clear_message)
{
    const pp_host_interface newer = host_v(PP_PLUGIN_INTERFACE_VERSION + 1);
    host_plugin p;
    char err[1024];
    cr_assert_eq(host_plugin_load(MANIFEST, &newer, &p, err, sizeof err), PP_ERR_UNSUPPORTED, "%s", err);
    cr_assert(strstr(last_log, "implements plugin interface version 1; host 'test host' was built for version 2: "
                               "use a newer PhysPix plugin"),
              "log: %s", last_log);
    cr_assert_null(p.library, "nothing stays loaded");
}

Test(load, struct_sizes_that_do_not_match_are_an_abi_error)
{
    host_plugin p;
    char err[1024];
    pp_host_interface host = host_v(PP_PLUGIN_INTERFACE_VERSION);
    host.struct_size -= 8;
    cr_assert_eq(host_plugin_load(MANIFEST, &host, &p, err, sizeof err), PP_ERR_ABI, "%s", err);

    /* A host whose plugin-interface struct is smaller than the plugin's. */
    host = host_v(PP_PLUGIN_INTERFACE_VERSION);
    cr_assert_eq(host_plugin_load(MANIFEST, &host, &p, err, sizeof err), PP_OK, "%s", err);
    pp_plugin_interface small = {.struct_size = sizeof small - 8};
    pp_plugin_entry_fn entry;
    *(void **)&entry = dlsym(p.library, PP_PLUGIN_ENTRY_SYMBOL);
    cr_assert_eq(entry(&host, &small), PP_ERR_ABI);
    host_plugin_unload(&p);
}

/* ---- the loaded plugin ---- */

static host_plugin plugin;

static void load_plugin(void)
{
    const pp_host_interface host = host_v(PP_PLUGIN_INTERFACE_VERSION);
    char err[1024];
    cr_assert_eq(host_plugin_load(MANIFEST, &host, &plugin, err, sizeof err), PP_OK, "%s", err);
}

static void unload_plugin(void)
{
    host_plugin_unload(&plugin);
    leak_check();
}

static pp_variant call(uint64_t obj, const char *method, const pp_variant *args, int argc)
{
    pp_variant ret;
    plugin.api.call(obj, method, args, argc, &ret);
    return ret;
}

static void expect_error(pp_variant *ret, pp_status status, const char *says)
{
    cr_assert_eq(ret->type, PP_VARIANT_ERROR, "expected an error saying '%s', got type %d", says, ret->type);
    cr_assert_eq(ret->as.error.status, status, "status %d for '%s'", ret->as.error.status, ret->as.error.message);
    cr_assert(strstr(ret->as.error.message, says), "'%s' should say '%s'", ret->as.error.message, says);
    plugin.api.variant_clear(ret);
    cr_assert_eq(ret->type, PP_VARIANT_NIL);
}

static uint64_t ok_object(pp_variant v)
{
    cr_assert_eq(v.type, PP_VARIANT_OBJECT, "expected an object, got type %d (%s)", v.type,
                 v.type == PP_VARIANT_ERROR ? v.as.error.message : "");
    return v.as.object;
}

enum { BOX = 20, GROUND_W = 200, GROUND_H = 20 };
static uint8_t box_mask[BOX * BOX], box_rgba[BOX * BOX * 4], ground_mask[GROUND_W * GROUND_H];

/* A world with a static ground and a box resting on it (1 px deep, so the first step has contacts);
 * a 60×6 bar beside it is cut in two, so one split event is pending. */
static uint64_t make_scene(uint64_t *box, uint64_t *ground)
{
    memset(box_mask, 1, sizeof box_mask);
    memset(box_rgba, 0xff, sizeof box_rgba);
    memset(ground_mask, 1, sizeof ground_mask);
    pp_variant made;
    plugin.api.object_create("PhysPixWorld", &made);
    const uint64_t w = ok_object(made);
    *ground = ok_object(call(w, "add_body",
                             (pp_variant[]){V_BYTES(ground_mask, sizeof ground_mask), V_INT(GROUND_W), V_INT(GROUND_H),
                                            V_VEC2(100, 110), V_STR("static")},
                             5));
    *box = ok_object(call(w, "add_body",
                          (pp_variant[]){V_BYTES(box_mask, sizeof box_mask), V_INT(BOX), V_INT(BOX), V_VEC2(50, 91),
                                         V_STR("dynamic")},
                          5));
    static uint8_t bar[60 * 6];
    memset(bar, 1, sizeof bar);
    const uint64_t b = ok_object(call(w, "add_body",
                                      (pp_variant[]){V_BYTES(bar, sizeof bar), V_INT(60), V_INT(6), V_VEC2(150, 40),
                                                     V_STR("dynamic")},
                                      5));
    pp_variant cut = call(b, "erase_circle", (pp_variant[]){V_VEC2(150, 40), V_FLOAT(4)}, 2);
    cr_assert(cut.type == PP_VARIANT_INT && cut.as.integer > 0);
    return w;
}

/* Right arguments for each method, by name; every declared method must have an entry. */
typedef struct recipe {
    const char *method;
    pp_variant args[7];
} recipe;

static int find_recipe(const recipe *r, int n, const char *method)
{
    for (int i = 0; i < n; i++)
        if (strcmp(r[i].method, method) == 0)
            return i;
    return -1;
}

/* A variant of a type other than t, for the wrong-type calls. */
static pp_variant wrong_for(pp_variant_type t, uint64_t other_class_object)
{
    switch (t) {
    case PP_VARIANT_STRING: return V_INT(3);
    case PP_VARIANT_OBJECT: return V_INT(3);
    case PP_VARIANT_INT: return V_FLOAT(3.5); /* FLOAT is not narrowed to INT */
    case PP_VARIANT_FLOAT: return V_STR("3.5");
    case PP_VARIANT_VEC2: return V_FLOAT(1);
    case PP_VARIANT_BYTES: return V_OBJ(other_class_object);
    default: return V_VEC2(1, 1);
    }
}

/* Remove a snapshot folder the tests wrote: its files, then itself. */
static void remove_snapshot(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    char path[PATH_MAX];
    for (struct dirent *e; (e = readdir(d));)
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
            unlink(path);
        }
    closedir(d);
    rmdir(dir);
}

TestSuite(methods, .init = load_plugin, .fini = unload_plugin);

Test(methods, every_method_answers_right_types_with_its_result_and_wrong_types_with_the_argument_named)
{
    uint64_t box, ground;
    const uint64_t world = make_scene(&box, &ground);
    char png[PATH_MAX], scene[PATH_MAX];
    cr_assert(realpath("tests/plugin/crate16.png", png));
    cr_assert(realpath("tests/plugin/scene.json", scene));
    char snap[64];
    snprintf(snap, sizeof snap, "/tmp/pp_plugin_snapshot_%d", (int)getpid());
    uint64_t scratch_box, scratch_ground;
    const uint64_t scratch = make_scene(&scratch_box, &scratch_ground);
    /* A hinge for the joint getters and setters, a mouse joint for set_joint_target, a weld for destroy_joint, a
     * motor joint for set_joint_offsets. */
    int64_t joints[4];
    const char *const kinds[4] = {"revolute", "mouse", "weld", "motor"};
    for (int i = 0; i < 4; i++) {
        pp_variant j = call(world, "add_joint",
                            (pp_variant[]){V_STR(kinds[i]), V_OBJ(world), V_OBJ(box), V_VEC2(50, 91),
                                           V_VEC2(0, 0), V_VEC2(1, 0)},
                            6);
        cr_assert_eq(j.type, PP_VARIANT_INT, "add_joint(%s): %s", kinds[i], j.type == PP_VARIANT_ERROR ? j.as.error.message : "");
        joints[i] = j.as.integer;
    }
    /* The motor joint keeps the box where the hinge holds it. */
    call(world, "set_joint_offsets", (pp_variant[]){V_INT(joints[3]), V_VEC2(50, 91), V_FLOAT(0)}, 3);
    /* The world's state now, for restore_state (and load_state on the scratch world). */
    pp_variant saved = call(world, "save_state", NULL, 0);
    cr_assert_eq(saved.type, PP_VARIANT_BYTES);
    const int64_t state_size = saved.as.bytes.length;
    uint8_t *state = malloc((size_t)state_size);
    memcpy(state, saved.as.bytes.data, (size_t)state_size);
    plugin.api.variant_clear(&saved);
    const recipe world_recipes[] = {
        {"step", {V_FLOAT(1.0 / 60)}},
        {"add_body", {V_BYTES(box_mask, sizeof box_mask), V_INT(BOX), V_INT(BOX), V_VEC2(20, 20), V_STR("static")}},
        {"add_body_rgba", {V_BYTES(box_rgba, sizeof box_rgba), V_INT(BOX), V_INT(BOX), V_VEC2(20, 60), V_STR("kinematic")}},
        {"add_body_png", {V_STR(png), V_VEC2(180, 20), V_STR("dynamic")}},
        {"erase_circle", {V_VEC2(1000, 1000), V_FLOAT(3)}},
        {"get_body_count", {{0}}},
        {"get_body", {V_INT(0)}},
        {"get_contact_count", {{0}}},
        {"get_contact_point", {V_INT(0)}},
        {"get_contact_normal", {V_INT(0)}},
        {"get_contact_depth", {V_INT(0)}},
        {"get_contact_normal_impulse", {V_INT(0)}},
        {"get_contact_body_a", {V_INT(0)}},
        {"get_contact_body_b", {V_INT(0)}},
        {"get_event_count", {{0}}},
        {"get_event_type", {V_INT(0)}},
        {"get_event_body", {V_INT(0)}},
        {"get_event_other", {V_INT(0)}},
        {"get_event_point", {V_INT(0)}},
        {"get_event_normal", {V_INT(0)}},
        {"get_event_approach_speed", {V_INT(0)}},
        {"get_event_joint", {V_INT(0)}},
        {"add_joint", {V_STR("revolute"), V_OBJ(world), V_OBJ(box), V_VEC2(50, 91), V_VEC2(0, 0), V_VEC2(1, 0)}},
        {"set_joint_options", {V_BOOL(0), V_FLOAT(0), V_FLOAT(0), V_FLOAT(0), V_FLOAT(0)}},
        {"destroy_joint", {V_INT(joints[2])}},
        {"get_joint_force", {V_INT(joints[0])}},
        {"get_joint_torque", {V_INT(joints[0])}},
        {"get_joint_value", {V_INT(joints[0])}},
        {"get_joint_speed", {V_INT(joints[0])}},
        {"set_joint_motor", {V_INT(joints[0]), V_BOOL(1), V_FLOAT(1), V_FLOAT(1e6)}},
        {"set_joint_limits", {V_INT(joints[0]), V_BOOL(1), V_FLOAT(-0.5), V_FLOAT(0.5)}},
        {"set_joint_target", {V_INT(joints[1]), V_VEC2(50, 91)}},
        {"set_joint_spring", {V_INT(joints[0]), V_FLOAT(2), V_FLOAT(0.5), V_FLOAT(0.1)}},
        {"set_joint_offsets", {V_INT(joints[3]), V_VEC2(50, 91), V_FLOAT(0)}},
        {"raycast", {V_VEC2(100, 0), V_VEC2(100, 200), V_INT(0xffffffff)}},
        {"get_ray_body", {{0}}},
        {"get_ray_point", {{0}}},
        {"get_ray_normal", {{0}}},
        {"get_ray_fraction", {{0}}},
        {"raycast_all", {V_VEC2(100, 0), V_VEC2(100, 200), V_INT(0xffffffff)}},
        {"select_ray_hit", {V_INT(0)}},
        {"cast_body", {V_OBJ(box), V_VEC2(0, 30), V_INT(0xffffffff)}},
        {"explode", {V_VEC2(1000, 1000), V_FLOAT(3), V_FLOAT(1), V_FLOAT(10), V_FLOAT(2), V_INT(0xffffffff), V_INT(0xffffffff)}},
        {"query_point", {V_VEC2(50, 91), V_INT(0xffffffff)}},
        {"query_aabb", {V_VEC2(0, 0), V_VEC2(200, 200), V_INT(1)}},
        {"query_circle", {V_VEC2(50, 91), V_FLOAT(5), V_INT(1)}},
        {"get_query_body", {V_INT(0)}},
        {"set_body_options", {V_BOOL(0), V_BOOL(0), V_VEC2(0, -1)}},
        {"set_contact_events", {V_BOOL(0)}},
        {"set_character_options", {V_FLOAT(6), V_FLOAT(4), V_FLOAT(4), V_FLOAT(4), V_FLOAT(0.8), V_INT(0xffffffff)}},
        {"move_character", {V_VEC2(100, 40), V_VEC2(60, 0), V_FLOAT(1.0 / 60)}},
        {"get_character_velocity", {{0}}},
        {"is_character_grounded", {{0}}},
        {"get_character_ground_normal", {{0}}},
        {"get_character_ground_body", {{0}}},
        {"get_character_ground_velocity", {{0}}},
        {"get_character_surfaces", {{0}}},
        {"collide", {V_OBJ(box), V_OBJ(ground)}},
        {"get_step_ms", {{0}}},
        {"load_scene", {V_STR(scene)}}, /* on a scratch world: it replaces the world's bodies */
        {"save_snapshot", {V_STR(snap)}},
        {"load_snapshot", {V_STR(snap)}}, /* on the scratch world too, after save_snapshot wrote it */
        {"get_time", {{0}}},
        {"save_state", {{0}}},
        {"restore_state", {V_BYTES(state, state_size)}},
        {"load_state", {V_BYTES(state, state_size)}}, /* on the scratch world: it replaces the world */
        {"get_hash", {{0}}},
        {"get_camera_center", {{0}}},
        {"get_camera_zoom", {{0}}},
        {"get_camera_size", {{0}}},
        {"schedule_erase", {V_FLOAT(10), V_VEC2(1000, 1000), V_FLOAT(3)}},
        {"get_scheduled_edit_count", {{0}}},
        {"get_scheduled_edit_time", {V_INT(0)}},
        {"get_scheduled_edit_type", {V_INT(0)}},
        {"get_scheduled_edit_center", {V_INT(0)}},
        {"get_scheduled_edit_radius", {V_INT(0)}},
        {"debug_collision", {V_OBJ(box), V_OBJ(ground)}},
        {"get_debug_size", {{0}}},
        {"get_debug_origin", {{0}}},
        {"get_debug_step_x", {{0}}},
        {"get_debug_step_y", {{0}}},
        {"get_debug_normal", {{0}}},
        {"get_debug_local_normals", {{0}}},
        {"debug_draw", {V_INT(63)}},
        {"get_joint_anchor_a", {V_INT(joints[0])}},
        {"get_joint_anchor_b", {V_INT(joints[0])}},
        {"get_body_states", {{0}}},
        {"create", {V_STR("{\"preset\": \"fast\", \"gravity\": [0, 500]}")}}, /* on the scratch world */
        {"get_settings", {{0}}},
        {"set_gravity", {V_VEC2(0, 980)}},
    };
    const recipe body_recipes[] = {
        {"get_position", {{0}}},
        {"get_angle", {{0}}},
        {"set_transform", {V_VEC2(50, 91), V_FLOAT(0)}},
        {"get_velocity", {{0}}},
        {"get_angular_velocity", {{0}}},
        {"set_velocity", {V_VEC2(0, 0), V_INT(0)}}, /* an INT is accepted where FLOAT is declared */
        {"apply_impulse", {V_VEC2(1, 0), V_VEC2(50, 91)}},
        {"get_mass", {{0}}},
        {"get_center_of_mass", {{0}}},
        {"get_inertia", {{0}}},
        {"is_awake", {{0}}},
        {"erase_circle", {V_VEC2(1000, 1000), V_FLOAT(2)}},
        {"paint_circle", {V_VEC2(1000, 1000), V_FLOAT(2), V_INT(255)}},
        {"read_mask", {{0}}},
        {"read_weights", {{0}}},
        {"get_size", {{0}}},
        {"get_world", {{0}}},
        {"get_pivot", {{0}}},
        {"get_type", {{0}}},
        {"get_rgba", {{0}}},
        {"get_user_data", {{0}}},
        {"set_type", {V_STR("dynamic")}},
        {"set_fixed_rotation", {V_BOOL(0)}},
        {"set_friction", {V_FLOAT(0.6)}},
        {"set_restitution", {V_FLOAT(0)}},
        {"set_density", {V_FLOAT(1)}},
        {"set_gravity_scale", {V_FLOAT(1)}},
        {"set_damping", {V_FLOAT(0), V_FLOAT(0)}},
        {"set_awake", {V_BOOL(1)}},
        {"apply_force", {V_VEC2(1, 0), V_VEC2(50, 91)}},
        {"apply_torque", {V_FLOAT(1)}},
        {"apply_angular_impulse", {V_FLOAT(1)}},
        {"set_filter", {V_INT(1), V_INT(0xffffffff)}},
        {"get_friction", {{0}}},
        {"get_restitution", {{0}}},
        {"get_density", {{0}}},
        {"get_gravity_scale", {{0}}},
        {"get_fixed_rotation", {{0}}},
    };
    const struct {
        const char *cls;
        uint64_t object, other;
        const recipe *recipes;
        int count;
    } targets[] = {
        {"PhysPixWorld", world, box, world_recipes, (int)(sizeof world_recipes / sizeof world_recipes[0])},
        {"PhysPixBody", box, world, body_recipes, (int)(sizeof body_recipes / sizeof body_recipes[0])},
    };
    int calls = 0;
    for (int t = 0; t < 2; t++) {
        const pp_plugin_class *c = host_plugin_class(&plugin, targets[t].cls);
        cr_assert_not_null(c, "no class %s", targets[t].cls);
        cr_assert_eq(c->method_count, targets[t].count, "%s: a method without a recipe, or a stale recipe", c->name);
        for (int32_t k = 0; k < c->method_count; k++) {
            const pp_plugin_method *m = &c->methods[k];
            const int r = find_recipe(targets[t].recipes, targets[t].count, m->name);
            cr_assert(r >= 0, "%s.%s has no recipe", c->name, m->name);
            const pp_variant *right = targets[t].recipes[r].args;
            const bool replaces = strcmp(m->name, "load_scene") == 0 || strcmp(m->name, "load_snapshot") == 0 ||
                                  strcmp(m->name, "create") == 0 || strcmp(m->name, "load_state") == 0;
            const uint64_t object = replaces ? scratch : targets[t].object;

            /* Each argument of a wrong type: INVALID_ARGUMENT naming its position, name and type. */
            for (int32_t i = 0; i < m->arg_count; i++) {
                pp_variant args[7];
                memcpy(args, right, sizeof args);
                args[i] = wrong_for(m->args[i].type, targets[t].other);
                char says[256];
                snprintf(says, sizeof says, "%s.%s: argument %d (%s) must be %s", c->name, m->name, (int)i + 1,
                         m->args[i].name, host_type_name(m->args[i].type));
                pp_variant ret = call(object, m->name, args, m->arg_count);
                expect_error(&ret, PP_ERR_INVALID_ARGUMENT, says);
                calls++;
            }
            /* One argument too many. */
            pp_variant extra[8];
            memcpy(extra, right, sizeof(pp_variant) * 7);
            extra[m->arg_count] = V_INT(1);
            pp_variant ret = call(object, m->name, extra, m->arg_count + 1);
            expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "takes");

            /* The right arguments: the declared result type (an OBJECT result may be nil: no such body). */
            ret = call(object, m->name, right, m->arg_count);
            cr_assert(ret.type == m->return_type || (m->return_type == PP_VARIANT_OBJECT && ret.type == PP_VARIANT_NIL),
                      "%s.%s returned type %d (%s), declared %d", c->name, m->name, ret.type,
                      ret.type == PP_VARIANT_ERROR ? ret.as.error.message : "", m->return_type);
            plugin.api.variant_clear(&ret);
            calls += 2;
        }
    }
    pp_variant ret = call(world, "no_such_method", NULL, 0);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "PhysPixWorld has no method 'no_such_method'");
    cr_log_info("%d calls checked", calls + 1);
    remove_snapshot(snap);
    free(state);
}

/* The positions of every body of a world object, in its body order. */
static int positions_of(uint64_t world, pp_vec2 *out, int capacity)
{
    const int n = (int)call(world, "get_body_count", NULL, 0).as.integer;
    cr_assert_leq(n, capacity);
    for (int i = 0; i < n; i++)
        out[i] = call(ok_object(call(world, "get_body", (pp_variant[]){V_INT(i)}, 1)), "get_position", NULL, 0).as.vec2;
    return n;
}

Test(methods, a_snapshot_saved_and_loaded_through_the_plugin_continues_exactly)
{
    uint64_t box, ground;
    const uint64_t world = make_scene(&box, &ground);
    char snap[64];
    snprintf(snap, sizeof snap, "/tmp/pp_plugin_snapshot_b%d", (int)getpid());
    for (int i = 0; i < 30; i++)
        call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    pp_variant ret = call(world, "save_snapshot", (pp_variant[]){V_STR(snap)}, 1);
    cr_assert_eq(ret.type, PP_VARIANT_NIL, "%s", ret.type == PP_VARIANT_ERROR ? ret.as.error.message : "");
    pp_variant made;
    plugin.api.object_create("PhysPixWorld", &made);
    const uint64_t back = ok_object(made);
    ret = call(back, "load_snapshot", (pp_variant[]){V_STR(snap)}, 1);
    cr_assert_eq(ret.type, PP_VARIANT_NIL, "%s", ret.type == PP_VARIANT_ERROR ? ret.as.error.message : "");
    for (int i = 0; i < 90; i++) {
        call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
        call(back, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    }
    pp_vec2 a[8], b[8];
    const int na = positions_of(world, a, 8), nb = positions_of(back, b, 8);
    cr_assert(na == 4 && nb == na, "%d and %d bodies (ground, box, the bar's two halves)", na, nb);
    cr_assert(memcmp(a, b, sizeof(pp_vec2) * (size_t)na) == 0, "the loaded world drifted from the original");
    ret = call(back, "load_snapshot", (pp_variant[]){V_STR("/nonexistent/snap")}, 1);
    expect_error(&ret, PP_ERR_IO, "PhysPixWorld.load_snapshot");
    cr_assert_eq(call(back, "get_body_count", NULL, 0).as.integer, 4, "a failed load leaves the world as it was");
    remove_snapshot(snap);
}

Test(methods, a_state_saved_in_memory_restores_loads_and_hashes_through_the_plugin)
{
    uint64_t box, ground;
    const uint64_t world = make_scene(&box, &ground);
    for (int i = 0; i < 20; i++)
        call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    pp_variant saved = call(world, "save_state", NULL, 0);
    cr_assert_eq(saved.type, PP_VARIANT_BYTES, "%s", saved.type == PP_VARIANT_ERROR ? saved.as.error.message : "");
    const int64_t hash = call(world, "get_hash", NULL, 0).as.integer;
    pp_vec2 a[8], b[8];
    for (int i = 0; i < 40; i++)
        call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    const int na = positions_of(world, a, 8);
    cr_assert_neq(call(world, "get_hash", NULL, 0).as.integer, hash);
    pp_variant ret = call(world, "restore_state", &saved, 1);
    cr_assert_eq(ret.type, PP_VARIANT_NIL, "%s", ret.type == PP_VARIANT_ERROR ? ret.as.error.message : "");
    cr_assert_eq(call(world, "get_hash", NULL, 0).as.integer, hash);
    for (int i = 0; i < 40; i++)
        call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    cr_assert(positions_of(world, b, 8) == na && memcmp(a, b, sizeof(pp_vec2) * (size_t)na) == 0,
              "the restored world went another way");
    pp_variant made;
    plugin.api.object_create("PhysPixWorld", &made);
    const uint64_t back = ok_object(made);
    ret = call(back, "load_state", &saved, 1);
    cr_assert_eq(ret.type, PP_VARIANT_NIL, "%s", ret.type == PP_VARIANT_ERROR ? ret.as.error.message : "");
    cr_assert_eq(call(back, "get_hash", NULL, 0).as.integer, hash);
    uint8_t cut[64];
    memcpy(cut, saved.as.bytes.data, sizeof cut);
    ret = call(world, "restore_state", (pp_variant[]){V_BYTES(cut, sizeof cut)}, 1);
    expect_error(&ret, PP_ERR_FORMAT, "PhysPixWorld.restore_state");
    plugin.api.variant_clear(&saved);
}

Test(methods, bodies_made_through_the_plugin_have_the_mass_of_their_pixels_and_fall)
{
    uint64_t box, ground;
    const uint64_t world = make_scene(&box, &ground);
    cr_assert_eq(call(box, "get_mass", NULL, 0).as.real, BOX * BOX, "mass = solid pixels × density 1");
    char png[PATH_MAX];
    cr_assert(realpath("tests/plugin/crate16.png", png));
    const uint64_t crate =
        ok_object(call(world, "add_body_png", (pp_variant[]){V_STR(png), V_VEC2(180, 20), V_STR("dynamic")}, 3));
    cr_assert_eq(call(crate, "get_mass", NULL, 0).as.real, 16 * 16, "the opaque 16×16 PNG crate");
    const pp_vec2 size = call(crate, "get_size", NULL, 0).as.vec2;
    cr_assert(size.x == 16 && size.y == 16);

    /* The box overlaps the ground by 1 px: collide gives the manifold's two points, normal +y (box → ground). */
    cr_assert_eq(call(world, "collide", (pp_variant[]){V_OBJ(box), V_OBJ(ground)}, 2).as.integer, 2);
    for (int i = 0; i < 2; i++) {
        const pp_vec2 n = call(world, "get_contact_normal", (pp_variant[]){V_INT(i)}, 1).as.vec2;
        const double depth = call(world, "get_contact_depth", (pp_variant[]){V_INT(i)}, 1).as.real;
        cr_assert(fabs(n.x) < 1e-6 && fabs(n.y - 1) < 1e-6, "normal (%g, %g)", n.x, n.y);
        cr_assert(fabs(depth - 1.0) <= 0.5, "depth %g px for a 1 px overlap", depth);
        cr_assert_eq(call(world, "get_contact_body_a", (pp_variant[]){V_INT(i)}, 1).as.object, box);
    }

    pp_variant mask = call(box, "read_mask", NULL, 0);
    cr_assert_eq(mask.type, PP_VARIANT_BYTES);
    cr_assert_eq(mask.as.bytes.length, BOX * BOX);
    cr_assert_eq(memcmp(mask.as.bytes.data, box_mask, BOX * BOX), 0, "read_mask gives back the mask");
    plugin.api.variant_clear(&mask);
    /* Pixel (0, 0) of the box at (50, 91), pivot at its centre, has its centre at (40.5, 81.5): paint it 51. */
    cr_assert_eq(call(box, "paint_circle", (pp_variant[]){V_VEC2(40.5, 81.5), V_FLOAT(0.4), V_INT(51)}, 3).as.integer, 1);
    pp_variant weights = call(box, "read_weights", NULL, 0);
    cr_assert_eq(weights.type, PP_VARIANT_BYTES);
    cr_assert_eq(weights.as.bytes.length, BOX * BOX);
    int heavy = 0;
    for (int k = 1; k < BOX * BOX; k++)
        heavy += weights.as.bytes.data[k] == 255;
    cr_assert(weights.as.bytes.data[0] == 51 && heavy == BOX * BOX - 1, "read_weights: %d then %d of 255",
              weights.as.bytes.data[0], heavy);
    plugin.api.variant_clear(&weights);
    cr_assert(fabs(call(box, "get_mass", NULL, 0).as.real - (BOX * BOX - 1 + 51.0 / 255)) < 1e-4, "mass %g",
              call(box, "get_mass", NULL, 0).as.real);

    /* The PNG crate falls freely: N = 60 semi-implicit Euler substeps of h = 1/240 s (15 steps, 4 substeps
     * each, the default) move it g·h²·N(N+1)/2 with g = 980 px/s². */
    for (int i = 0; i < 15; i++)
        call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    const double fallen = call(crate, "get_position", NULL, 0).as.vec2.y - 20.0, h = 1.0 / 240;
    cr_assert(fabs(fallen - 980 * h * h * 60 * 61 / 2) < 0.01, "fell %.4f px, the integrator gives %.4f", fallen,
              980 * h * h * 60 * 61 / 2);
    /* The same body keeps one object id: the box read back through get_body is the box. */
    const int64_t n = call(world, "get_body_count", NULL, 0).as.integer;
    int found = 0;
    for (int64_t i = 0; i < n; i++)
        found += call(world, "get_body", (pp_variant[]){V_INT(i)}, 1).as.object == box;
    cr_assert_eq(found, 1);
}

Test(methods, misuse_of_objects_and_levels_gets_a_status_and_a_message)
{
    uint64_t box, ground;
    const uint64_t world = make_scene(&box, &ground);
    pp_variant ret;
    plugin.api.object_create("PhysPixBody", &ret);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "PhysPixBody is made by PhysPixWorld.add_body*");
    plugin.api.object_create("Nope", &ret);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "no class named 'Nope'");
    plugin.api.object_create(NULL, &ret);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "no class named '(null)'");

    ret = call(world, "step", (pp_variant[]){V_FLOAT(NAN)}, 1);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "PhysPixWorld.step: pp_world_step: dt");
    ret = call(world, "add_body", (pp_variant[]){V_BYTES(box_mask, 10), V_INT(BOX), V_INT(BOX), V_VEC2(0, 0), V_STR("dynamic")}, 5);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "20x20 px needs 400 bytes, got 10");
    ret = call(world, "add_body", (pp_variant[]){V_BYTES(box_mask, sizeof box_mask), V_INT(BOX), V_INT(BOX), V_VEC2(0, 0), V_STR("floating")}, 5);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "type must be \"dynamic\", \"static\" or \"kinematic\", got \"floating\"");
    ret = call(world, "add_body", (pp_variant[]){V_BYTES(NULL, 400), V_INT(BOX), V_INT(BOX), V_VEC2(0, 0), V_STR("dynamic")}, 5);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "argument 1 (mask) has no data");
    ret = call(world, "add_body", (pp_variant[]){V_BYTES(box_mask, 0), V_INT(-5), V_INT(BOX), V_VEC2(0, 0), V_STR("dynamic")}, 5);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "width must be in 1..16384, got -5");
    ret = call(world, "add_body_png", (pp_variant[]){V_STR("/nonexistent.png"), V_VEC2(0, 0), V_STR("dynamic")}, 3);
    expect_error(&ret, PP_ERR_IO, "cannot open '/nonexistent.png'");
    ret = call(world, "collide", (pp_variant[]){V_OBJ(world), V_OBJ(box)}, 2);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "argument 1 (a) must be a live PhysPixBody object");
    uint64_t other_box, other_ground;
    const uint64_t other = make_scene(&other_box, &other_ground);
    ret = call(world, "collide", (pp_variant[]){V_OBJ(box), V_OBJ(other_ground)}, 2);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "belongs to world");
    ret = call(world, "debug_collision", (pp_variant[]){V_OBJ(other_box), V_OBJ(ground)}, 2);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "pp_world_debug_collision: body");
    plugin.api.object_destroy(other, &ret);
    ret = call(world, "get_contact_point", (pp_variant[]){V_INT(1000)}, 1);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "index 1000 is outside");
    ret = call(box, "paint_circle", (pp_variant[]){V_VEC2(50, 91), V_FLOAT(3), V_INT(0)}, 3);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "weight must be in 1..255, got 0");

    /* Destroying a body makes its object stale; destroying the world takes its bodies' objects along. */
    plugin.api.object_destroy(box, &ret);
    cr_assert_eq(ret.type, PP_VARIANT_NIL);
    ret = call(box, "get_position", NULL, 0);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "is null, destroyed or stale");
    plugin.api.object_destroy(box, &ret);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "object_destroy");
    plugin.api.object_destroy(world, &ret);
    cr_assert_eq(ret.type, PP_VARIANT_NIL);
    ret = call(ground, "get_mass", NULL, 0);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "is null, destroyed or stale");
    ret = call(0, "get_mass", NULL, 0);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "object 0 is null");

    /* Below the SCENE level the classes are closed; re-initialising restores them. Worlds left alive
     * at deinitialize are destroyed there (LSan would see them otherwise). */
    make_scene(&box, &ground);
    plugin.api.deinitialize(PP_PLUGIN_LEVEL_SCENE);
    plugin.api.object_create("PhysPixWorld", &ret);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "usable after initialize(PP_PLUGIN_LEVEL_SCENE)");
    ret = call(box, "get_mass", NULL, 0);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "usable after initialize");
    cr_assert_eq(plugin.api.initialize(PP_PLUGIN_LEVEL_EDITOR), PP_ERR_INVALID_ARGUMENT, "levels go up one at a time");
    cr_assert_eq(plugin.api.initialize(PP_PLUGIN_LEVEL_SCENE), PP_OK);
    ret = call(box, "get_mass", NULL, 0);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "stale");
}

/* Issue 24: a hinge in the plugin host. A 10×60 rod hung 25 px above its centre from a static beam swings with
 * the period of a physical pendulum, 2π√((I + m·d²)/(m·g·d)); erasing the beam's pixel under the hinge breaks it
 * (joint_broken with the joint and both bodies) and the rod falls; misuse is refused with the reason. */
Test(methods, a_hinge_swings_with_the_physical_pendulum_period_and_breaks_when_its_pixel_is_erased)
{
    pp_variant made;
    plugin.api.object_create("PhysPixWorld", &made);
    const uint64_t world = ok_object(made);
    static uint8_t beam_mask[100 * 10], rod_mask[10 * 60];
    memset(beam_mask, 1, sizeof beam_mask);
    memset(rod_mask, 1, sizeof rod_mask);
    const uint64_t beam = ok_object(call(world, "add_body",
                                         (pp_variant[]){V_BYTES(beam_mask, sizeof beam_mask), V_INT(100), V_INT(10),
                                                        V_VEC2(200, 100), V_STR("static")},
                                         5));
    const uint64_t rod = ok_object(call(world, "add_body",
                                        (pp_variant[]){V_BYTES(rod_mask, sizeof rod_mask), V_INT(10), V_INT(60),
                                                       V_VEC2(200, 129), V_STR("dynamic")},
                                        5));
    const double d = 25;
    pp_variant j = call(world, "add_joint",
                        (pp_variant[]){V_STR("revolute"), V_OBJ(beam), V_OBJ(rod), V_VEC2(200, 129 - d), V_VEC2(0, 0),
                                       V_VEC2(1, 0)},
                        6);
    cr_assert_eq(j.type, PP_VARIANT_INT, "%s", j.type == PP_VARIANT_ERROR ? j.as.error.message : "");
    const pp_variant hinge = V_INT(j.as.integer);
    call(rod, "set_velocity", (pp_variant[]){V_VEC2(-0.2 * d, 0), V_FLOAT(0.2)}, 2);

    /* The mean time between upward zero crossings of the hinge angle. */
    double prev = call(world, "get_joint_value", &hinge, 1).as.real, first = -1, last = -1;
    int swings = -1;
    for (int k = 1; k <= 600; k++) {
        call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
        const double v = call(world, "get_joint_value", &hinge, 1).as.real;
        if (prev < 0 && v >= 0) {
            last = (k - 1 + prev / (prev - v)) / 60;
            first = first < 0 ? last : first;
            swings++;
        }
        prev = v;
    }
    const double m = call(rod, "get_mass", NULL, 0).as.real, inertia = call(rod, "get_inertia", NULL, 0).as.real;
    const double period = (last - first) / swings, analytic = 2 * M_PI * sqrt((inertia + m * d * d) / (m * 980 * d));
    cr_log_info("plugin hinge pendulum: period %.4f s over %d swings, analytic %.4f s", period, swings, analytic);
    cr_assert(swings >= 3 && fabs(period / analytic - 1) < 0.02, "period %.4f s over %d swings, analytic %.4f s", period,
              swings, analytic);
    const pp_vec2 f = call(world, "get_joint_force", &hinge, 1).as.vec2;
    cr_assert(fabs(f.y) > 0.9 * m * 980 && fabs(f.y) < 1.1 * m * 980, "the hinge carries the rod: %g vs m·g %g", f.y,
              m * 980);

    pp_variant ret = call(world, "set_joint_target", (pp_variant[]){hinge, V_VEC2(0, 0)}, 2);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "PhysPixWorld.set_joint_target: pp_joint_set_target: only mouse");
    ret = call(world, "add_joint",
               (pp_variant[]){V_STR("hinge"), V_OBJ(world), V_OBJ(rod), V_VEC2(0, 0), V_VEC2(0, 0), V_VEC2(1, 0)}, 6);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT,
                 "type must be \"revolute\", \"prismatic\", \"distance\", \"weld\", \"mouse\", \"wheel\" or \"motor\", got "
                 "\"hinge\"");
    pp_variant other_made;
    plugin.api.object_create("PhysPixWorld", &other_made);
    const uint64_t other = ok_object(other_made);
    ret = call(world, "add_joint",
               (pp_variant[]){V_STR("weld"), V_OBJ(other), V_OBJ(rod), V_VEC2(0, 0), V_VEC2(0, 0), V_VEC2(1, 0)}, 6);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "body_a must be a PhysPixBody or this world");
    plugin.api.object_destroy(other, &ret);

    /* The erase takes the beam's pixels around the anchor: the hinge breaks and its int goes stale. */
    call(beam, "erase_circle", (pp_variant[]){V_VEC2(200, 129 - d), V_FLOAT(3)}, 2);
    const int64_t n = call(world, "get_event_count", NULL, 0).as.integer;
    int broken = 0;
    for (int64_t i = 0; i < n; i++) {
        pp_variant type = call(world, "get_event_type", (pp_variant[]){V_INT(i)}, 1);
        if (strcmp(type.as.string.data, "joint_broken") == 0) {
            broken++;
            cr_assert_eq(call(world, "get_event_joint", (pp_variant[]){V_INT(i)}, 1).as.integer, hinge.as.integer);
            cr_assert_eq(call(world, "get_event_body", (pp_variant[]){V_INT(i)}, 1).as.object, beam);
            cr_assert_eq(call(world, "get_event_other", (pp_variant[]){V_INT(i)}, 1).as.object, rod);
        }
        plugin.api.variant_clear(&type);
    }
    cr_assert_eq(broken, 1, "one joint_broken among %lld events", (long long)n);
    ret = call(world, "get_joint_value", &hinge, 1);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "PhysPixWorld.get_joint_value");
    const double y0 = call(rod, "get_position", NULL, 0).as.vec2.y;
    for (int k = 0; k < 30; k++)
        call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    cr_assert(call(rod, "get_position", NULL, 0).as.vec2.y > y0 + 50, "the rod fell from %g", y0);
}

/* Issue 41 through the plugin: a wheel joint's sag under gravity is m·g/k = g/ω², and a motor joint takes a crate
 * to the offsets set_joint_offsets gives it. */
Test(methods, a_wheel_sags_by_its_spring_and_a_motor_joint_takes_a_crate_to_its_offsets)
{
    pp_variant made;
    plugin.api.object_create("PhysPixWorld", &made);
    const uint64_t world = ok_object(made);
    static uint8_t mask[20 * 20];
    memset(mask, 1, sizeof mask);
    const uint64_t hub = ok_object(call(world, "add_body",
                                        (pp_variant[]){V_BYTES(mask, sizeof mask), V_INT(20), V_INT(20), V_VEC2(200, 200),
                                                       V_STR("dynamic")},
                                        5));
    const uint64_t crate = ok_object(call(world, "add_body",
                                          (pp_variant[]){V_BYTES(mask, sizeof mask), V_INT(20), V_INT(20),
                                                         V_VEC2(400, 200), V_STR("dynamic")},
                                          5));
    const double hz = 2, sag = 980 / pow(2 * M_PI * hz, 2);
    call(world, "set_joint_options", (pp_variant[]){V_BOOL(0), V_FLOAT(hz), V_FLOAT(0.7), V_FLOAT(0), V_FLOAT(0)}, 5);
    pp_variant j = call(world, "add_joint",
                        (pp_variant[]){V_STR("wheel"), V_OBJ(world), V_OBJ(hub), V_VEC2(200, 200), V_VEC2(200, 200),
                                       V_VEC2(0, 1)},
                        6);
    cr_assert_eq(j.type, PP_VARIANT_INT, "%s", j.type == PP_VARIANT_ERROR ? j.as.error.message : "");
    const pp_variant wheel = V_INT(j.as.integer);
    call(world, "set_joint_options", (pp_variant[]){V_BOOL(0), V_FLOAT(0), V_FLOAT(0), V_FLOAT(0), V_FLOAT(0)}, 5);
    j = call(world, "add_joint",
             (pp_variant[]){V_STR("motor"), V_OBJ(world), V_OBJ(crate), V_VEC2(0, 0), V_VEC2(0, 0), V_VEC2(1, 0)}, 6);
    cr_assert_eq(j.type, PP_VARIANT_INT, "%s", j.type == PP_VARIANT_ERROR ? j.as.error.message : "");
    const pp_variant motor = V_INT(j.as.integer);
    pp_variant ret = call(world, "set_joint_offsets", (pp_variant[]){motor, V_VEC2(450, 150), V_FLOAT(0.3)}, 3);
    cr_assert_eq(ret.type, PP_VARIANT_NIL, "%s", ret.type == PP_VARIANT_ERROR ? ret.as.error.message : "");
    for (int k = 0; k < 240; k++)
        call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    const double value = call(world, "get_joint_value", &wheel, 1).as.real;
    const pp_vec2 p = call(crate, "get_position", NULL, 0).as.vec2;
    const double angle = call(crate, "get_angle", NULL, 0).as.real;
    cr_log_info("plugin wheel sag %.4f px (m·g/k %.4f); motor joint crate at (%.3f, %.3f), %.4f rad", value, sag, p.x,
                p.y, angle);
    cr_assert(fabs(value / sag - 1) < 0.03, "sag %g px, m·g/k %g px", value, sag);
    cr_assert(hypot(p.x - 450, p.y - 150) < 0.5 && fabs(angle - 0.3) < 0.01, "crate at (%g, %g), %g rad", p.x, p.y,
              angle);
    ret = call(world, "set_joint_offsets", (pp_variant[]){wheel, V_VEC2(0, 0), V_FLOAT(0)}, 3);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "PhysPixWorld.set_joint_offsets: pp_joint_set_offsets: only motor");
    ret = call(world, "set_joint_spring", (pp_variant[]){wheel, V_FLOAT(-1), V_FLOAT(0), V_FLOAT(0)}, 4);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "hertz");
    plugin.api.object_destroy(world, &ret);
}

/* Issue 39: a world's first body and first joint share slot 0 of their tables; a body object passed as a joint
 * int, or a joint int passed as a body object, is refused saying what it is, and neither goes away. */
Test(methods, a_body_is_not_a_joint_and_a_joint_is_not_a_body)
{
    pp_variant made;
    plugin.api.object_create("PhysPixWorld", &made);
    const uint64_t world = ok_object(made);
    memset(box_mask, 1, sizeof box_mask);
    const uint64_t box = ok_object(call(world, "add_body",
                                        (pp_variant[]){V_BYTES(box_mask, sizeof box_mask), V_INT(BOX), V_INT(BOX),
                                                       V_VEC2(100, 100), V_STR("dynamic")},
                                        5));
    pp_variant j = call(world, "add_joint",
                        (pp_variant[]){V_STR("revolute"), V_OBJ(world), V_OBJ(box), V_VEC2(100, 92), V_VEC2(0, 0),
                                       V_VEC2(1, 0)},
                        6);
    cr_assert_eq(j.type, PP_VARIANT_INT, "%s", j.type == PP_VARIANT_ERROR ? j.as.error.message : "");
    const pp_variant box_as_joint = V_INT((int64_t)box), joint_as_box = V_OBJ((uint64_t)j.as.integer);
    pp_variant ret = call(world, "destroy_joint", &box_as_joint, 1);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "is a body handle, not a joint");
    ret = call(world, "get_joint_value", &box_as_joint, 1);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "is a body handle, not a joint");
    ret = call(world, "add_joint",
               (pp_variant[]){V_STR("weld"), V_OBJ(world), joint_as_box, V_VEC2(100, 92), V_VEC2(0, 0), V_VEC2(1, 0)}, 6);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "argument 3 (body_b) must be a live plugin object; it is a joint handle");
    ret = call(joint_as_box.as.object, "get_position", NULL, 0);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "it is a joint handle (an int)");
    plugin.api.object_destroy(joint_as_box.as.object, &ret);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "object_destroy: object");
    /* Both still answer as what they are. */
    cr_assert_eq(call(world, "get_joint_value", (pp_variant[]){V_INT(j.as.integer)}, 1).type, PP_VARIANT_FLOAT);
    cr_assert_eq(call(box, "get_position", NULL, 0).type, PP_VARIANT_VEC2);
    plugin.api.object_destroy(world, &ret);
}

/* Issue 39: each pixel call fed huge, negative and 32-bit-wrapping ints (2^32 + 16 would wrap to 16) is refused
 * naming the call and the argument, and makes nothing; so is a plane whose byte count no bitmap has. */
Test(methods, pixel_calls_refuse_huge_and_negative_sizes_and_weights)
{
    uint64_t box, ground;
    const uint64_t world = make_scene(&box, &ground);
    const int64_t bodies = call(world, "get_body_count", NULL, 0).as.integer;
    static const int64_t bad[] = {INT64_MAX, INT64_MIN, -1, 0, 4294967312LL, 2147483648LL, -2147483649LL};
    static const char *const adds[] = {"add_body", "add_body_rgba"};
    char says[128];
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        const pp_variant n = V_INT(bad[k]), four = V_INT(4);
        for (int add = 0; add < 2; add++)
            for (int side = 0; side < 2; side++) {
                pp_variant ret = call(world, adds[add],
                                      (pp_variant[]){V_BYTES(box_rgba, 16 << 2 * add), side ? four : n, side ? n : four,
                                                     V_VEC2(0, 0), V_STR("dynamic")},
                                      5);
                snprintf(says, sizeof says, "PhysPixWorld.%s: %s must be in 1..%d, got %lld", adds[add],
                         side ? "height" : "width", PP_MAX_BITMAP_SIDE, (long long)bad[k]);
                expect_error(&ret, PP_ERR_INVALID_ARGUMENT, says);
            }
        pp_variant ret = call(box, "paint_circle", (pp_variant[]){V_VEC2(50, 91), V_FLOAT(3), n}, 3);
        snprintf(says, sizeof says, "PhysPixBody.paint_circle: weight must be in 1..255, got %lld", (long long)bad[k]);
        expect_error(&ret, PP_ERR_INVALID_ARGUMENT, says);
    }
    pp_variant ret = call(world, "add_body",
                          (pp_variant[]){V_BYTES(box_mask, INT64_MAX), V_INT(BOX), V_INT(BOX), V_VEC2(0, 0),
                                         V_STR("dynamic")},
                          5);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "needs 400 bytes, got 9223372036854775807");
    ret = call(world, "add_body_rgba",
               (pp_variant[]){V_BYTES(box_rgba, -1), V_INT(BOX), V_INT(BOX), V_VEC2(0, 0), V_STR("dynamic")}, 5);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "argument 1 (rgba) has no data");
    cr_assert_eq(call(world, "get_body_count", NULL, 0).as.integer, bodies, "a refused call made a body");
    plugin.api.object_destroy(world, &ret);
}

/* The body of a loaded scene whose user_data is `tag`. */
static uint64_t body_tagged(uint64_t world, int64_t tag)
{
    const int64_t n = call(world, "get_body_count", NULL, 0).as.integer;
    for (int64_t i = 0; i < n; i++) {
        const uint64_t b = ok_object(call(world, "get_body", (pp_variant[]){V_INT(i)}, 1));
        if (call(b, "get_user_data", NULL, 0).as.integer == tag)
            return b;
    }
    cr_assert_fail("no body with user_data %lld", (long long)tag);
    return 0;
}

Test(methods, a_scene_loads_through_the_plugin_with_its_camera_edits_sprites_and_debug_view)
{
    uint64_t box, ground;
    const uint64_t world = make_scene(&box, &ground);
    char scene[PATH_MAX];
    cr_assert(realpath("tests/plugin/scene.json", scene));
    pp_variant ret = call(world, "load_scene", (pp_variant[]){V_STR("/nonexistent/scene.json")}, 1);
    expect_error(&ret, PP_ERR_IO, "PhysPixWorld.load_scene");
    cr_assert_eq(call(box, "get_mass", NULL, 0).type, PP_VARIANT_FLOAT, "a failed load leaves the world as it was");
    ret = call(world, "load_scene", (pp_variant[]){V_STR(scene)}, 1);
    cr_assert_eq(ret.type, PP_VARIANT_NIL, "%s", ret.type == PP_VARIANT_ERROR ? ret.as.error.message : "");
    ret = call(box, "get_mass", NULL, 0);
    expect_error(&ret, PP_ERR_INVALID_HANDLE, "stale");

    cr_assert_eq(call(world, "get_body_count", NULL, 0).as.integer, 2);
    const uint64_t floor_ = body_tagged(world, 7), crate = body_tagged(world, 8);
    pp_variant type = call(floor_, "get_type", NULL, 0);
    cr_assert_str_eq(type.as.string.data, "static");
    plugin.api.variant_clear(&type);
    const pp_vec2 pivot = call(crate, "get_pivot", NULL, 0).as.vec2, centre = call(world, "get_camera_center", NULL, 0).as.vec2;
    const pp_vec2 size = call(world, "get_camera_size", NULL, 0).as.vec2;
    cr_assert(pivot.x == 8 && pivot.y == 8, "pivot (%g, %g): the bitmap centre", pivot.x, pivot.y);
    cr_assert(centre.x == 100 && centre.y == 60 && size.x == 400 && size.y == 240);
    cr_assert_eq(call(world, "get_camera_zoom", NULL, 0).as.real, 2);

    pp_variant rgba = call(crate, "get_rgba", NULL, 0);
    cr_assert_eq(rgba.as.bytes.length, 16 * 16 * 4);
    cr_assert_eq(rgba.as.bytes.data[3], 255, "the opaque crate's sprite");
    plugin.api.variant_clear(&rgba);

    /* The crate overlaps the ground by 1 px: the debug grid holds both bodies, an intersection of critical
     * cells, and the global normal is collide's. */
    pp_variant cells = call(world, "debug_collision", (pp_variant[]){V_OBJ(crate), V_OBJ(floor_)}, 2);
    cr_assert_eq(cells.type, PP_VARIANT_BYTES, "%s", cells.type == PP_VARIANT_ERROR ? cells.as.error.message : "");
    const pp_vec2 grid = call(world, "get_debug_size", NULL, 0).as.vec2;
    cr_assert_eq(cells.as.bytes.length, (int64_t)grid.x * (int64_t)grid.y);
    int64_t both = 0, critical = 0;
    for (int64_t i = 0; i < cells.as.bytes.length; i++) {
        both += (cells.as.bytes.data[i] & (PP_CELL_A | PP_CELL_B)) == (PP_CELL_A | PP_CELL_B);
        critical += (cells.as.bytes.data[i] & PP_CELL_CRITICAL) != 0;
    }
    plugin.api.variant_clear(&cells);
    cr_assert(both >= 16 && critical > 0 && critical <= both, "%lld intersection cells, %lld critical", (long long)both,
              (long long)critical);
    const pp_vec2 n = call(world, "get_debug_normal", NULL, 0).as.vec2;
    cr_assert(fabs(n.x) < 1e-3 && fabs(n.y - 1) < 1e-3, "normal (%g, %g)", n.x, n.y);
    pp_variant normals = call(world, "get_debug_local_normals", NULL, 0);
    cr_assert_eq(normals.as.bytes.length, (int64_t)grid.x * (int64_t)grid.y * 8, "two floats a cell");
    plugin.api.variant_clear(&normals);

    /* The scene's erase is pending until its time; then the crate falls into the crater. */
    cr_assert_eq(call(world, "get_scheduled_edit_count", NULL, 0).as.integer, 1);
    cr_assert_eq(call(world, "get_scheduled_edit_time", (pp_variant[]){V_INT(0)}, 1).as.real, 0.5);
    cr_assert_eq(call(world, "get_scheduled_edit_radius", (pp_variant[]){V_INT(0)}, 1).as.real, 20);
    const double y0 = call(crate, "get_position", NULL, 0).as.vec2.y;
    for (int i = 0; i < 60; i++)
        call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    cr_assert(fabs(call(world, "get_time", NULL, 0).as.real - 60 * (double)(float)(1.0 / 60)) < 1e-9,
              "the sum of the steps' dt, s");
    cr_assert_eq(call(world, "get_scheduled_edit_count", NULL, 0).as.integer, 0, "the edit applied");
    cr_assert(call(crate, "get_position", NULL, 0).as.vec2.y - y0 > 5, "the crate fell into the crater");
}

/* ---- issue 10: raycasts, queries, sensors, contact events and impulses, one-way platforms ---- */

static uint64_t new_world(void)
{
    pp_variant made;
    plugin.api.object_create("PhysPixWorld", &made);
    return ok_object(made);
}

static uint64_t add_rect(uint64_t world, int w, int h, pp_vec2 position, const char *type)
{
    static uint8_t solid[200 * 40];
    memset(solid, 1, sizeof solid);
    cr_assert_leq(w * h, (int)sizeof solid);
    return ok_object(call(world, "add_body",
                          (pp_variant[]){V_BYTES(solid, w * h), V_INT(w), V_INT(h), V_VEC2(position.x, position.y),
                                         V_STR(type)},
                          5));
}

static void step_n(uint64_t world, int n)
{
    for (int i = 0; i < n; i++) {
        pp_variant ret = call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
        cr_assert_eq(ret.type, PP_VARIANT_NIL, "%s", ret.type == PP_VARIANT_ERROR ? ret.as.error.message : "");
    }
}

/* The type name of the index-th event read by the last get_event_count, in buf. */
static const char *event_type(uint64_t world, int64_t i, char *buf, size_t size)
{
    pp_variant t = call(world, "get_event_type", (pp_variant[]){V_INT(i)}, 1);
    cr_assert_eq(t.type, PP_VARIANT_STRING);
    snprintf(buf, size, "%s", t.as.string.data);
    plugin.api.variant_clear(&t);
    return buf;
}

Test(methods, a_ray_meets_the_top_face_of_a_static_box_and_queries_find_it)
{
    const uint64_t world = new_world();
    const uint64_t ground = add_rect(world, 200, 40, (pp_vec2){100, 120}, "static"); /* top y = 100 */
    pp_variant hit = call(world, "raycast", (pp_variant[]){V_VEC2(105, 0), V_VEC2(105, 200), V_INT(0xffffffff)}, 3);
    cr_assert(hit.type == PP_VARIANT_BOOL && hit.as.boolean == 1, "%s",
              hit.type == PP_VARIANT_ERROR ? hit.as.error.message : "a miss");
    const pp_vec2 p = call(world, "get_ray_point", NULL, 0).as.vec2, n = call(world, "get_ray_normal", NULL, 0).as.vec2;
    cr_assert(fabs(p.x - 105) <= 0.5 && fabs(p.y - 100) <= 0.5, "point (%g, %g), the face is y = 100", p.x, p.y);
    cr_assert(fabs(n.x) < 1e-3 && fabs(n.y + 1) < 1e-3, "normal (%g, %g), expected (0, -1)", n.x, n.y);
    cr_assert(fabs(call(world, "get_ray_fraction", NULL, 0).as.real - 0.5) <= 0.5 / 200);
    cr_assert_eq(call(world, "get_ray_body", NULL, 0).as.object, ground);

    /* A miss, and a mask that excludes the ground's category (1): nil body, zero point. */
    hit = call(world, "raycast", (pp_variant[]){V_VEC2(0, 0), V_VEC2(300, 0), V_INT(0xffffffff)}, 3);
    cr_assert(hit.type == PP_VARIANT_BOOL && hit.as.boolean == 0);
    cr_assert_eq(call(world, "get_ray_body", NULL, 0).type, PP_VARIANT_NIL);
    hit = call(world, "raycast", (pp_variant[]){V_VEC2(105, 0), V_VEC2(105, 200), V_INT(2)}, 3);
    cr_assert(hit.type == PP_VARIANT_BOOL && hit.as.boolean == 0);
    pp_variant ret = call(world, "raycast", (pp_variant[]){V_VEC2(0, 0), V_VEC2(1, 0), V_INT(-1)}, 3);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "PhysPixWorld.raycast: mask must be in 0..4294967295, got -1");

    const uint64_t box = add_rect(world, 20, 20, (pp_vec2){40, 50}, "dynamic"); /* 30..50, 40..60 */
    cr_assert_eq(call(world, "query_point", (pp_variant[]){V_VEC2(45.5, 55.5), V_INT(0xffffffff)}, 2).as.integer, 1);
    cr_assert_eq(call(world, "get_query_body", (pp_variant[]){V_INT(0)}, 1).as.object, box);
    cr_assert_eq(call(world, "query_aabb", (pp_variant[]){V_VEC2(0, 0), V_VEC2(300, 300), V_INT(1)}, 3).as.integer, 2);
    cr_assert_eq(call(world, "query_circle", (pp_variant[]){V_VEC2(100, 80), V_FLOAT(10), V_INT(1)}, 3).as.integer, 0);
    cr_assert_eq(call(world, "query_circle", (pp_variant[]){V_VEC2(100, 95), V_FLOAT(10), V_INT(1)}, 3).as.integer, 1);
    cr_assert_eq(call(world, "get_query_body", (pp_variant[]){V_INT(0)}, 1).as.object, ground);
    ret = call(world, "get_query_body", (pp_variant[]){V_INT(1)}, 1);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "index 1 is outside the 1 bodies a query found");
    /* Erased pixels are not found. */
    cr_assert_gt(call(box, "erase_circle", (pp_variant[]){V_VEC2(45, 55), V_FLOAT(4)}, 2).as.integer, 0);
    cr_assert_eq(call(world, "query_point", (pp_variant[]){V_VEC2(45.5, 55.5), V_INT(1)}, 2).as.integer, 0);
    plugin.api.object_destroy(world, &ret);
}

/* Contact events switched on in a world the plugin made: a box landing on the ground begins one contact. */
Test(methods, contact_events_switch_on_in_a_plugin_world)
{
    const uint64_t world = new_world();
    add_rect(world, 200, 20, (pp_vec2){100, 100}, "static"); /* top y 90 */
    add_rect(world, 10, 10, (pp_vec2){100, 60}, "dynamic");
    cr_assert_eq(call(world, "set_contact_events", (pp_variant[]){V_BOOL(1)}, 1).type, PP_VARIANT_NIL);
    int begins = 0;
    for (int k = 0; k < 60; k++) {
        step_n(world, 1);
        const int64_t n = call(world, "get_event_count", NULL, 0).as.integer;
        for (int64_t i = 0; i < n; i++) {
            char type[16];
            event_type(world, i, type, sizeof type);
            begins += strcmp(type, "contact_begin") == 0;
        }
    }
    cr_assert_eq(begins, 1, "the landing begins one contact, got %d", begins);
    pp_variant ret;
    plugin.api.object_destroy(world, &ret);
}

Test(methods, a_ball_falls_freely_through_a_sensor_that_reports_begin_then_end)
{
    const uint64_t world = new_world();
    cr_assert_eq(call(world, "set_body_options", (pp_variant[]){V_BOOL(1), V_BOOL(0), V_VEC2(0, -1)}, 3).type,
                 PP_VARIANT_NIL);
    const uint64_t sensor = add_rect(world, 200, 20, (pp_vec2){100, 100}, "static"); /* y 90..110 */
    call(world, "set_body_options", (pp_variant[]){V_BOOL(0), V_BOOL(0), V_VEC2(0, -1)}, 3);
    const uint64_t ball = add_rect(world, 8, 8, (pp_vec2){100, 40}, "dynamic");
    char seen[8][16];
    int n_seen = 0;
    for (int k = 1; k <= 45; k++) {
        step_n(world, 1);
        const double vy = call(ball, "get_velocity", NULL, 0).as.vec2.y, free_fall = 980.0 * k / 60;
        cr_assert(fabs(vy - free_fall) <= 0.01 * free_fall, "step %d: vy %g, free fall %g", k, vy, free_fall);
        const int64_t n = call(world, "get_event_count", NULL, 0).as.integer;
        for (int64_t i = 0; i < n && n_seen < 8; i++) {
            event_type(world, i, seen[n_seen], sizeof seen[0]);
            cr_assert_eq(call(world, "get_event_body", (pp_variant[]){V_INT(i)}, 1).as.object, sensor);
            cr_assert_eq(call(world, "get_event_other", (pp_variant[]){V_INT(i)}, 1).as.object, ball);
            if (strcmp(seen[n_seen], "sensor_begin") == 0) {
                const double speed = call(world, "get_event_approach_speed", (pp_variant[]){V_INT(i)}, 1).as.real;
                cr_assert(fabs(speed - vy) <= 980.0 / 60 + 1, "approach %g px/s, the ball falls at %g", speed, vy);
                const pp_vec2 nrm = call(world, "get_event_normal", (pp_variant[]){V_INT(i)}, 1).as.vec2;
                cr_assert(nrm.y < -0.95, "normal (%g, %g): from the sensor up to the ball", nrm.x, nrm.y);
            }
            n_seen++;
        }
    }
    cr_assert_gt(call(ball, "get_position", NULL, 0).as.vec2.y, 130, "the ball fell through");
    cr_assert_eq(n_seen, 2, "%d events", n_seen);
    cr_assert_str_eq(seen[0], "sensor_begin");
    cr_assert_str_eq(seen[1], "sensor_end");
    pp_variant ret;
    plugin.api.object_destroy(world, &ret);
}

/* A scene file in /tmp from its JSON text; path receives its name. */
static void write_scene(char *path, size_t size, const char *json)
{
    snprintf(path, size, "/tmp/pp_plugin_scene_%d.json", (int)getpid());
    FILE *f = fopen(path, "w");
    cr_assert(f);
    fputs(json, f);
    fclose(f);
}

Test(methods, a_scene_with_contact_events_reports_the_landing_and_its_impulses_carry_the_weight)
{
    /* The box's bottom starts 60 px above the ground's top (y = 100). */
    char path[64];
    write_scene(path, sizeof path,
                "{ \"world\": { \"contact_events\": true, \"allow_sleep\": false, \"backend\": \"cpu\" },\n"
                "  \"bodies\": [ { \"type\": \"static\", \"box\": [200, 40], \"position\": [100, 120] },\n"
                "              { \"type\": \"dynamic\", \"box\": [20, 20], \"position\": [100, 30],\n"
                "                \"restitution\": 0, \"user_data\": 1 } ] }\n");
    const uint64_t world = new_world();
    pp_variant ret = call(world, "load_scene", (pp_variant[]){V_STR(path)}, 1);
    unlink(path);
    cr_assert_eq(ret.type, PP_VARIANT_NIL, "%s", ret.type == PP_VARIANT_ERROR ? ret.as.error.message : "");
    const uint64_t box = body_tagged(world, 1);
    double begin_speed = -1;
    for (int k = 0; k < 180; k++) {
        step_n(world, 1);
        const int64_t n = call(world, "get_event_count", NULL, 0).as.integer;
        for (int64_t i = 0; i < n; i++) {
            char t[16];
            if (strcmp(event_type(world, i, t, sizeof t), "contact_begin") == 0) {
                cr_assert_lt(begin_speed, 0, "one contact_begin");
                begin_speed = call(world, "get_event_approach_speed", (pp_variant[]){V_INT(i)}, 1).as.real;
            }
        }
    }
    const double expected = sqrt(2 * 980.0 * 60);
    cr_assert(fabs(begin_speed - expected) <= 0.05 * expected, "approach %g px/s, sqrt(2 g h) = %g", begin_speed,
              expected);

    /* At rest the contacts of the last substep hold the box's weight over one substep (1/240 s). */
    double sum = 0;
    const int steps = 30;
    for (int k = 0; k < steps; k++) {
        step_n(world, 1);
        const int64_t n = call(world, "get_contact_count", NULL, 0).as.integer;
        cr_assert_gt(n, 0);
        for (int64_t i = 0; i < n; i++)
            sum += call(world, "get_contact_normal_impulse", (pp_variant[]){V_INT(i)}, 1).as.real;
    }
    const double weight = call(box, "get_mass", NULL, 0).as.real * 980.0 / 240;
    cr_assert(fabs(sum / steps - weight) <= 0.02 * weight, "mean impulse %g, m g h = %g", sum / steps, weight);
    plugin.api.object_destroy(world, &ret);
}

Test(methods, a_body_launched_from_below_passes_through_a_one_way_platform_and_lands_on_it)
{
    const uint64_t world = new_world();
    call(world, "set_body_options", (pp_variant[]){V_BOOL(0), V_BOOL(1), V_VEC2(0, -1)}, 3);
    add_rect(world, 200, 10, (pp_vec2){100, 100}, "static"); /* top y = 95 */
    call(world, "set_body_options", (pp_variant[]){V_BOOL(0), V_BOOL(0), V_VEC2(0, -1)}, 3);
    const uint64_t box = add_rect(world, 16, 16, (pp_vec2){100, 200}, "dynamic");
    call(box, "set_velocity", (pp_variant[]){V_VEC2(0, -sqrt(2 * 980.0 * 200)), V_FLOAT(0)}, 2);
    double top = 200;
    for (int k = 0; k < 300; k++) {
        step_n(world, 1);
        top = fmin(top, call(box, "get_position", NULL, 0).as.vec2.y);
    }
    const pp_vec2 p = call(box, "get_position", NULL, 0).as.vec2;
    cr_assert_lt(top, 95 - 8 - 50, "rose to y = %g: it must pass up through the platform", top);
    cr_assert(fabs(p.y - (95 - 8)) <= 1.5, "ended at y = %g, resting on the platform is %d", p.y, 95 - 8);

    /* A zero direction is refused when the body is made. */
    call(world, "set_body_options", (pp_variant[]){V_BOOL(0), V_BOOL(1), V_VEC2(0, 0)}, 3);
    static uint8_t one = 1;
    pp_variant ret = call(world, "add_body", (pp_variant[]){V_BYTES(&one, 1), V_INT(1), V_INT(1), V_VEC2(0, 0),
                                                           V_STR("static")}, 5);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "one_way_direction");
    plugin.api.object_destroy(world, &ret);
}

Test(methods, runtime_setters_through_the_plugin_make_a_box_kinematic_float_and_stop_it_turning)
{
    uint64_t box, ground;
    const uint64_t world = make_scene(&box, &ground);
    /* In the air above the ground and left of the bar, clear of both for the whole test. */
    cr_assert_eq(call(box, "set_transform", (pp_variant[]){V_VEC2(30, 15), V_FLOAT(0)}, 2).type, PP_VARIANT_NIL);
    cr_assert_eq(call(box, "set_type", (pp_variant[]){V_STR("kinematic")}, 1).type, PP_VARIANT_NIL);
    cr_assert_eq(call(box, "set_velocity", (pp_variant[]){V_VEC2(30, 0), V_FLOAT(1)}, 2).type, PP_VARIANT_NIL);
    cr_assert_eq(call(box, "set_fixed_rotation", (pp_variant[]){V_BOOL(1)}, 1).type, PP_VARIANT_NIL);
    const pp_vec2 p0 = call(box, "get_position", NULL, 0).as.vec2;
    const double a0 = call(box, "get_angle", NULL, 0).as.real;
    for (int i = 0; i < 60; i++)
        call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    const pp_vec2 p1 = call(box, "get_position", NULL, 0).as.vec2;
    cr_assert_float_eq(p1.x - p0.x, 30, 1e-2, "a kinematic box moves 30 px in a second: %g", p1.x - p0.x);
    cr_assert_float_eq(p1.y, p0.y, 1e-3, "and does not fall: %g then %g", p0.y, p1.y);
    cr_assert_eq(call(box, "get_angle", NULL, 0).as.real, a0, "its rotation is held");
    pp_variant type = call(box, "get_type", NULL, 0);
    cr_assert_str_eq(type.as.string.data, "kinematic");
    plugin.api.variant_clear(&type);
    /* Dynamic again with gravity scale 0: it keeps its velocity and floats. */
    cr_assert_eq(call(box, "set_type", (pp_variant[]){V_STR("dynamic")}, 1).type, PP_VARIANT_NIL);
    cr_assert_eq(call(box, "set_gravity_scale", (pp_variant[]){V_FLOAT(0)}, 1).type, PP_VARIANT_NIL);
    for (int i = 0; i < 30; i++)
        call(world, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    cr_assert_float_eq(call(box, "get_position", NULL, 0).as.vec2.y, p1.y, 1e-3, "gravity scale 0 floats");
    pp_variant bad = call(box, "set_type", (pp_variant[]){V_STR("floating")}, 1);
    expect_error(&bad, PP_ERR_INVALID_ARGUMENT, "PhysPixBody.set_type: type must be");
    bad = call(box, "set_density", (pp_variant[]){V_FLOAT(-1)}, 1);
    expect_error(&bad, PP_ERR_INVALID_ARGUMENT, "PhysPixBody.set_density");
}

Test(methods, body_states_come_in_one_call_in_get_body_counts_order)
{
    uint64_t box, ground;
    const uint64_t world = make_scene(&box, &ground);
    cr_assert_eq(call(box, "set_velocity", (pp_variant[]){V_VEC2(12, -3), V_FLOAT(0.5)}, 2).type, PP_VARIANT_NIL);
    const int n = (int)call(world, "get_body_count", NULL, 0).as.integer;
    pp_variant states = call(world, "get_body_states", NULL, 0);
    cr_assert_eq(states.type, PP_VARIANT_BYTES);
    cr_assert_eq(states.as.bytes.length, (int64_t)n * 7 * (int64_t)sizeof(float), "%d bodies, %lld bytes", n,
                 (long long)states.as.bytes.length);
    for (int i = 0; i < n; i++) {
        float f[7];
        memcpy(f, states.as.bytes.data + (size_t)i * sizeof f, sizeof f);
        const uint64_t b = ok_object(call(world, "get_body", (pp_variant[]){V_INT(i)}, 1));
        const pp_vec2 p = call(b, "get_position", NULL, 0).as.vec2, v = call(b, "get_velocity", NULL, 0).as.vec2;
        cr_assert(f[0] == p.x && f[1] == p.y && f[2] == (float)call(b, "get_angle", NULL, 0).as.real,
                  "body %d: pose (%g, %g, %g)", i, f[0], f[1], f[2]);
        cr_assert(f[3] == v.x && f[4] == v.y && f[5] == (float)call(b, "get_angular_velocity", NULL, 0).as.real,
                  "body %d: velocity (%g, %g, %g)", i, f[3], f[4], f[5]);
        cr_assert_eq(f[6], call(b, "is_awake", NULL, 0).as.boolean ? 1.0f : 0.0f, "body %d: awake %g", i, f[6]);
        if (b == box)
            cr_assert(f[3] == 12.0f && f[4] == -3.0f && f[5] == 0.5f, "the box's set velocity");
    }
    plugin.api.variant_clear(&states);
}

Test(methods, debug_draw_packs_each_segment_as_four_floats_and_two_words)
{
    uint64_t box, ground;
    const uint64_t world = make_scene(&box, &ground);
    const int n = (int)call(world, "get_body_count", NULL, 0).as.integer;
    pp_variant segs = call(world, "debug_draw", (pp_variant[]){V_INT(2)}, 1); /* AABBs: 4 sides a body */
    cr_assert_eq(segs.type, PP_VARIANT_BYTES, "%s", segs.type == PP_VARIANT_ERROR ? segs.as.error.message : "");
    cr_assert_eq(segs.as.bytes.length, (int64_t)n * 4 * 24, "%d bodies, %lld bytes", n, (long long)segs.as.bytes.length);
    for (int i = 0; i < 4 * n; i++) {
        uint32_t u[2];
        memcpy(u, segs.as.bytes.data + (size_t)i * 24 + 16, sizeof u);
        cr_assert_eq(u[1], 2u, "segment %d: kind %u", i, u[1]);
    }
    /* The ground, in the first slot: 200×20 about (100, 110), its top side first; static's colour. */
    float f[4];
    uint32_t rgba;
    memcpy(f, segs.as.bytes.data, sizeof f);
    memcpy(&rgba, segs.as.bytes.data + 16, sizeof rgba);
    cr_assert(f[0] == 0 && f[1] == 100 && f[2] == 200 && f[3] == 100, "(%g, %g) -> (%g, %g)", f[0], f[1], f[2], f[3]);
    cr_assert_eq(rgba, 0x7FE57FFFu);
    plugin.api.variant_clear(&segs);
    pp_variant bad = call(world, "debug_draw", (pp_variant[]){V_INT(64)}, 1);
    expect_error(&bad, PP_ERR_INVALID_ARGUMENT, "flags");
    bad = call(world, "debug_draw", (pp_variant[]){V_INT(-1)}, 1);
    expect_error(&bad, PP_ERR_INVALID_ARGUMENT, "flags");
    /* A joint's anchors: the hinge's two are the point it was made at. */
    const pp_variant j = call(world, "add_joint", (pp_variant[]){V_STR("revolute"), V_OBJ(world), V_OBJ(box),
                                                              V_VEC2(50, 91), V_VEC2(0, 0), V_VEC2(1, 0)}, 6);
    cr_assert_eq(j.type, PP_VARIANT_INT);
    const pp_vec2 a = call(world, "get_joint_anchor_a", (pp_variant[]){V_INT(j.as.integer)}, 1).as.vec2;
    const pp_vec2 b = call(world, "get_joint_anchor_b", (pp_variant[]){V_INT(j.as.integer)}, 1).as.vec2;
    cr_assert(a.x == 50 && a.y == 91 && fabsf(b.x - 50) < 1e-4f && fabsf(b.y - 91) < 1e-4f, "(%g, %g), (%g, %g)",
              a.x, a.y, b.x, b.y);
}

/* A STRING result's text, cleared; "" for any other result. */
static void text_of(pp_variant v, char *out, size_t size)
{
    snprintf(out, size, "%s", v.type == PP_VARIANT_STRING ? v.as.string.data : "");
    plugin.api.variant_clear(&v);
}

static pp_variant create_with(uint64_t world, const char *settings)
{
    return call(world, "create", (pp_variant[]){V_STR(settings)}, 1);
}

Test(methods, settings_given_at_creation_hold_and_read_back)
{
    pp_variant made;
    plugin.api.object_create("PhysPixWorld", &made);
    const uint64_t w = ok_object(made);
    pp_variant r = create_with(w, "{\"preset\": \"fast\", \"gravity\": [0, 0], \"substeps\": 2, \"backend\": \"cpu\", "
                                  "\"allow_sleep\": false, \"contact_slop\": 0.5}");
    cr_assert_eq(r.type, PP_VARIANT_NIL, "%s", r.type == PP_VARIANT_ERROR ? r.as.error.message : "");
    memset(box_mask, 1, sizeof box_mask);
    const uint64_t box = ok_object(call(
        w, "add_body", (pp_variant[]){V_BYTES(box_mask, sizeof box_mask), V_INT(BOX), V_INT(BOX), V_VEC2(50, 50),
                                      V_STR("dynamic")}, 5));
    for (int i = 0; i < 60; i++)
        call(w, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    const pp_vec2 p = call(box, "get_position", NULL, 0).as.vec2;
    cr_assert(p.x == 50 && p.y == 50, "without gravity a lone box stays put: (%g, %g)", p.x, p.y);
    cr_assert(call(box, "is_awake", NULL, 0).as.boolean, "allow_sleep false: still awake after 1 s at rest");
    char text[1024], again[1024];
    text_of(call(w, "get_settings", NULL, 0), text, sizeof text);
    const char *const expect[] = {"\"gravity\":[0,0]", "\"substeps\":2", "\"solver_iterations\":10", "\"backend\":\"cpu\"",
                                  "\"allow_sleep\":false", "\"contact_slop\":0.5", "\"normal_method\":\"area_gradient\""};
    for (size_t i = 0; i < sizeof expect / sizeof expect[0]; i++)
        cr_assert(strstr(text, expect[i]), "get_settings '%s' should hold %s (the fast preset, then the keys)", text,
                  expect[i]);
    /* What get_settings writes, create reads: the same settings come back. */
    cr_assert_eq(create_with(w, text).type, PP_VARIANT_NIL);
    text_of(call(w, "get_settings", NULL, 0), again, sizeof again);
    cr_assert_str_eq(again, text);
    /* The default settings: the body falls 0.5·980·t² px. */
    cr_assert_eq(create_with(w, "{}").type, PP_VARIANT_NIL);
    pp_variant stale = call(box, "get_position", NULL, 0);
    expect_error(&stale, PP_ERR_INVALID_HANDLE, "destroyed or stale"); /* create replaced the world */
    const uint64_t faller = ok_object(call(
        w, "add_body", (pp_variant[]){V_BYTES(box_mask, sizeof box_mask), V_INT(BOX), V_INT(BOX), V_VEC2(50, 50),
                                      V_STR("dynamic")}, 5));
    for (int i = 0; i < 30; i++)
        call(w, "step", (pp_variant[]){V_FLOAT(1.0 / 60)}, 1);
    cr_assert_float_eq(call(faller, "get_position", NULL, 0).as.vec2.y, 50 + 0.5 * 980 * 0.25, 2.0, "free fall");
}

Test(methods, bad_settings_get_invalid_argument_naming_the_key_and_leave_the_world_as_it_was)
{
    pp_variant made;
    plugin.api.object_create("PhysPixWorld", &made);
    const uint64_t w = ok_object(made);
    cr_assert_eq(create_with(w, "{\"substeps\": 3}").type, PP_VARIANT_NIL);
    const struct {
        const char *settings, *says;
    } cases[] = {
        {"{\"substepz\": 2}", "PhysPixWorld.create: settings.substepz: unknown key"},
        {"{\"substeps\": 2.5}", "settings.substeps: expected an integer"},
        {"{\"allow_sleep\": 1}", "settings.allow_sleep: expected true or false"},
        {"{\"gravity\": [0]}", "settings.gravity: expected [x, y], two finite numbers"},
        {"{\"contact_slop\": 1e39}", "settings.contact_slop: expected a finite number"},
        {"{\"contact_erp\": NaN}", "settings: invalid JSON"},
        {"{\"backend\": \"gpx\"}", "settings.backend: expected \"auto\", \"cpu\" or \"gpu\""},
        {"{\"preset\": \"slow\"}", "settings.preset: expected \"fast\", \"balanced\" or \"accurate\""},
        {"{\"substeps\": 2, \"substeps\": 4}", "settings.substeps: given twice"},
        {"[1, 2]", "settings: expected a JSON object"},
        {"{\"substeps\": 99}", "PhysPixWorld.create: pp_world_create: substeps must be 1..64, got 99"},
        {"{\"contact_slop\": -1}", "pp_world_create: contact_slop must be finite"},
    };
    char text[1024];
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        pp_variant r = create_with(w, cases[i].settings);
        expect_error(&r, PP_ERR_INVALID_ARGUMENT, cases[i].says);
        text_of(call(w, "get_settings", NULL, 0), text, sizeof text);
        cr_assert(strstr(text, "\"substeps\":3"), "case %zu: a refused create keeps the world: %s", i, text);
    }
}

/* Every PhysPixBody method of a body an edit destroyed is PP_ERR_INVALID_HANDLE named after the method: the generated
 * wrappers pass the library's refusal on (get_world, which needs no body, aside). */
Test(methods, every_body_method_refuses_a_body_an_edit_destroyed)
{
    uint64_t box, ground;
    const uint64_t world = make_scene(&box, &ground);
    /* Erased whole, the body is gone but its object stays (object_destroy would free the object too). */
    cr_assert_eq(call(ground, "erase_circle", (pp_variant[]){V_VEC2(100, 110), V_FLOAT(500)}, 2).type, PP_VARIANT_INT);
    const pp_plugin_class *c = host_plugin_class(&plugin, "PhysPixBody");
    int refused = 0;
    for (int32_t k = 0; k < c->method_count; k++) {
        const pp_plugin_method *m = &c->methods[k];
        pp_variant args[6];
        for (int32_t i = 0; i < m->arg_count; i++)
            args[i] = m->args[i].type == PP_VARIANT_STRING ? V_STR("dynamic")
                      : m->args[i].type == PP_VARIANT_VEC2 ? V_VEC2(1, 1)
                      : m->args[i].type == PP_VARIANT_BOOL ? V_BOOL(1)
                      : m->args[i].type == PP_VARIANT_FLOAT ? V_FLOAT(1)
                                                             : V_INT(1);
        pp_variant r = call(ground, m->name, args, m->arg_count);
        if (strcmp(m->name, "get_world") == 0) {
            cr_assert_eq(r.type, PP_VARIANT_OBJECT);
            cr_assert_eq(r.as.object, world);
            continue;
        }
        char says[96];
        snprintf(says, sizeof says, "PhysPixBody.%s: ", m->name);
        cr_assert_eq(r.type, PP_VARIANT_ERROR, "%s of a destroyed body gave type %d", m->name, r.type);
        expect_error(&r, PP_ERR_INVALID_HANDLE, says);
        refused++;
    }
    cr_assert_eq(refused, c->method_count - 1);
}

/* ---- issue 44: explosions and casts ---- */

Test(methods, explode_pushes_a_box_away_and_casts_find_the_ground_and_every_body_on_a_ray)
{
    const uint64_t world = new_world();
    const uint64_t ground = add_rect(world, 200, 40, (pp_vec2){100, 120}, "static"); /* top y = 100 */
    const uint64_t box = add_rect(world, 20, 20, (pp_vec2){100, 50}, "dynamic");    /* 90..110, 40..60 */
    /* Dropped 100 px, the box stops after 40 on the ground, its normal up. */
    pp_variant hit = call(world, "cast_body", (pp_variant[]){V_OBJ(box), V_VEC2(0, 100), V_INT(0xffffffff)}, 3);
    cr_assert(hit.type == PP_VARIANT_BOOL && hit.as.boolean == 1);
    cr_assert(fabs(call(world, "get_ray_fraction", NULL, 0).as.real * 100 - 40) <= 1.0 / 16);
    const pp_vec2 n = call(world, "get_ray_normal", NULL, 0).as.vec2;
    cr_assert(fabs(n.x) < 1e-6 && fabs(n.y + 1) < 1e-6, "normal (%g, %g)", n.x, n.y);
    cr_assert_eq(call(world, "get_ray_body", NULL, 0).as.object, ground);
    /* A ray down through both: the box first. */
    cr_assert_eq(call(world, "raycast_all", (pp_variant[]){V_VEC2(100, 0), V_VEC2(100, 200), V_INT(0xffffffff)}, 3)
                     .as.integer, 2);
    call(world, "select_ray_hit", (pp_variant[]){V_INT(1)}, 1);
    cr_assert_eq(call(world, "get_ray_body", NULL, 0).as.object, ground);
    pp_variant ret = call(world, "select_ray_hit", (pp_variant[]){V_INT(2)}, 1);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "index 2 is outside the 2 hits raycast_all found");
    /* A blast 10 px left of the box, with a crater in the ground: the box leaves to the right, the ground stays. */
    ret = call(world, "explode",
               (pp_variant[]){V_VEC2(80, 50), V_FLOAT(30), V_FLOAT(0), V_FLOAT(100), V_FLOAT(0), V_INT(0xffffffff),
                              V_INT(0xffffffff)},
               7);
    cr_assert_eq(ret.type, PP_VARIANT_INT, "%s", ret.type == PP_VARIANT_ERROR ? ret.as.error.message : "");
    step_n(world, 1);
    cr_assert_gt(call(box, "get_velocity", NULL, 0).as.vec2.x, 0);
    ret = call(world, "explode",
               (pp_variant[]){V_VEC2(80, 100), V_FLOAT(10), V_FLOAT(0), V_FLOAT(100), V_FLOAT(6), V_INT(0xffffffff),
                              V_INT(0xffffffff)},
               7);
    cr_assert_gt(ret.as.integer, 0, "the crater's pixels");
    ret = call(world, "explode",
               (pp_variant[]){V_VEC2(80, 100), V_FLOAT(-1), V_FLOAT(0), V_FLOAT(100), V_FLOAT(0), V_INT(0xffffffff),
                              V_INT(0xffffffff)},
               7);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "PhysPixWorld.explode");
    plugin.api.object_destroy(world, &ret);
}

/* set_character_options: a capsule of this radius (px) with half_height 4 px, step_height and snap_distance 4 px,
 * max_slope 0.8 rad. */
static pp_variant character_options(uint64_t world, double radius, int64_t mask)
{
    return call(world, "set_character_options",
                (pp_variant[]){V_FLOAT(radius), V_FLOAT(4), V_FLOAT(4), V_FLOAT(4), V_FLOAT(0.8), V_INT(mask)}, 6);
}

Test(methods, a_character_walks_grounded_on_flat_ground_and_bad_options_get_the_librarys_error)
{
    const uint64_t world = new_world();
    const uint64_t ground = add_rect(world, 200, 40, (pp_vec2){100, 120}, "static"); /* top y = 100 */
    /* A capsule of radius 6 px and half_height 4 px: its foot 10 px below its position. */
    character_options(world, 6, 0xffffffff);
    const double y0 = 100 - 10 - 0.01, speed = 120, dt = 1.0 / 60;
    pp_vec2 p = {40, (float)y0};
    double vy = 0;
    for (int i = 0; i < 60; i++) {
        pp_variant ret = call(world, "move_character", (pp_variant[]){V_VEC2(p.x, p.y), V_VEC2(speed, vy + 980 * dt),
                                                                      V_FLOAT(dt)}, 3);
        cr_assert_eq(ret.type, PP_VARIANT_VEC2, "%s", ret.type == PP_VARIANT_ERROR ? ret.as.error.message : "");
        p = ret.as.vec2;
        cr_assert(call(world, "is_character_grounded", NULL, 0).as.boolean, "frame %d: in the air at (%g, %g)", i,
                  p.x, p.y);
        cr_assert(fabs(p.y - y0) <= 0.5, "frame %d: height %g, started at %g", i, p.y, y0);
        const pp_vec2 n = call(world, "get_character_ground_normal", NULL, 0).as.vec2;
        cr_assert(fabs(n.x) < 1e-3 && fabs(n.y + 1) < 1e-3, "normal (%g, %g)", n.x, n.y);
        cr_assert_eq(call(world, "get_character_ground_body", NULL, 0).as.object, ground);
        const pp_vec2 gv = call(world, "get_character_ground_velocity", NULL, 0).as.vec2;
        cr_assert(gv.x == 0 && gv.y == 0, "a static ground's velocity (%g, %g)", gv.x, gv.y);
        vy = 0; /* grounded: the ground took the fall */
    }
    cr_assert(fabs(p.x - 40 - speed) <= 0.02 * speed, "walked %g px in 1 s at %g px/s", p.x - 40, speed);
    /* A mask that misses the ground's category: it falls through, meeting nothing. */
    character_options(world, 6, 0);
    const pp_vec2 fell = call(world, "move_character", (pp_variant[]){V_VEC2(p.x, p.y), V_VEC2(0, 600), V_FLOAT(0.1)},
                              3).as.vec2;
    cr_assert(fabs(fell.y - p.y - 60) < 1e-3 && !call(world, "is_character_grounded", NULL, 0).as.boolean);
    cr_assert_eq(call(world, "get_character_surfaces", NULL, 0).as.integer, 0);
    cr_assert_eq(call(world, "get_character_ground_body", NULL, 0).type, PP_VARIANT_NIL);
    /* Bad options are the library's to refuse, at the move; a bad mask is the plugin's. */
    pp_variant ret = character_options(world, 0, 0xffffffff);
    cr_assert_eq(ret.type, PP_VARIANT_NIL, "the options are checked at the move");
    ret = call(world, "move_character", (pp_variant[]){V_VEC2(0, 0), V_VEC2(1, 0), V_FLOAT(dt)}, 3);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT,
                 "PhysPixWorld.move_character: pp_world_move_character: def->radius must be > 0");
    ret = character_options(world, 6, -1);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "PhysPixWorld.set_character_options: mask must be in");
    ret = call(world, "move_character", (pp_variant[]){V_VEC2(0, 0), V_VEC2(1, 0), V_FLOAT(dt)}, 3);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "def->radius"); /* the refused options changed nothing */
    character_options(world, 6, 0xffffffff);
    ret = call(world, "move_character", (pp_variant[]){V_VEC2(0, 0), V_VEC2(1, 0), V_FLOAT(-1)}, 3);
    expect_error(&ret, PP_ERR_INVALID_ARGUMENT, "PhysPixWorld.move_character: pp_world_move_character: dt");
    plugin.api.object_destroy(world, &ret);
}
