/* The reference plugin host: loads PhysPix through its manifest (not by linking it), lists the
 * classes and methods the plugin declares, and drives a destruction scene only through the generic
 * call: a crate falls onto a terrain and rests, the terrain under it is blown away and it falls
 * again, a bar cut through its middle splits in two, and a lamp hung by a hinge from a cave's roof
 * drops when the roof pixel under the hinge is erased. Exits 0 only if the physics holds. */
#include "plugin_host.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DT (1.0 / 60.0)

static host_plugin plugin;
static int failures;

static void host_log(int level, const char *message, void *user)
{
    (void)user;
    fprintf(level >= 3 ? stderr : stdout, "[plugin] %s\n", message);
}

/* Call a method; an ERROR result is fatal for the scene. The caller clears STRING and BYTES results. */
static pp_variant host_call(uint64_t object, const char *method, const pp_variant *args, int argc)
{
    pp_variant ret;
    plugin.api.call(object, method, args, argc, &ret);
    if (ret.type == PP_VARIANT_ERROR) {
        fprintf(stderr, "host: %s failed (status %d): %s\n", method, (int)ret.as.error.status, ret.as.error.message);
        plugin.api.variant_clear(&ret);
        host_plugin_unload(&plugin);
        exit(1);
    }
    return ret;
}

/* CALL(obj, "method", args...): the argument list as an array, counted. */
#define CALL(obj, method, ...)                                                                        \
    host_call(obj, method, (const pp_variant[]){{.type = PP_VARIANT_NIL}, __VA_ARGS__} + 1,             \
              (int)(sizeof((const pp_variant[]){{.type = PP_VARIANT_NIL}, __VA_ARGS__}) / sizeof(pp_variant)) - 1)

static void expect(int ok, const char *what, double value)
{
    printf("  %-58s %10.3f  %s\n", what, value, ok ? "ok" : "FAILED");
    failures += !ok;
}

static void list_classes(void)
{
    const unsigned v = plugin.api.library_version;
    printf("plugin %s %u.%u.%u, interface %u, %d classes\n", plugin.api.name, v / 10000, v / 100 % 100, v % 100,
           (unsigned)plugin.api.interface_version, (int)plugin.api.class_count);
    for (int32_t i = 0; i < plugin.api.class_count; i++) {
        const pp_plugin_class *c = &plugin.api.classes[i];
        printf("class %s : %s%s — %s\n", c->name, c->base, c->instantiable ? "" : " (made by methods)", c->doc);
        for (int32_t k = 0; k < c->method_count; k++) {
            const pp_plugin_method *m = &c->methods[k];
            char sig[256] = "";
            for (int32_t a = 0; a < m->arg_count; a++)
                snprintf(sig + strlen(sig), sizeof sig - strlen(sig), "%s%s: %s", a ? ", " : "", m->args[a].name,
                         host_type_name(m->args[a].type));
            printf("  %s(%s) -> %s\n", m->name, sig, m->return_class ? m->return_class : host_type_name(m->return_type));
        }
    }
}

static void step_for(uint64_t world, double seconds)
{
    for (int i = 0; i < (int)lround(seconds / DT); i++)
        CALL(world, "step", V_FLOAT(DT));
}

/* Reads (and forgets) the pending events; returns how many are of the given type. */
static int64_t count_events(uint64_t world, const char *type_name)
{
    int64_t found = 0;
    const int64_t n = CALL(world, "get_event_count").as.integer;
    for (int64_t i = 0; i < n; i++) {
        pp_variant type = CALL(world, "get_event_type", V_INT(i));
        found += strcmp(type.as.string.data, type_name) == 0;
        plugin.api.variant_clear(&type);
    }
    return found;
}

static void run_scene(void)
{
    enum { TW = 640, TH = 160, SURFACE = 60, CRATE = 24, BAR_W = 120, BAR_H = 8, LAMP = 8 };
    static uint8_t terrain[TW * TH], crate_rgba[CRATE * CRATE * 4], bar[BAR_W * BAR_H], lamp_mask[LAMP * LAMP];
    for (int y = 0; y < TH; y++) /* ground below row 60 with a closed cave under x 400..520 */
        for (int x = 0; x < TW; x++)
            terrain[y * TW + x] = y >= SURFACE && !(x >= 400 && x < 520 && y >= 90 && y < 130);
    memset(crate_rgba, 0xff, sizeof crate_rgba); /* opaque: every pixel solid */
    memset(bar, 1, sizeof bar);
    memset(lamp_mask, 1, sizeof lamp_mask);
    const double ground_top = 400.0 - TH / 2.0 + SURFACE; /* terrain pivot at its centre, (320, 400) */

    pp_variant made;
    plugin.api.object_create("PhysPixWorld", &made);
    if (made.type != PP_VARIANT_OBJECT) {
        fprintf(stderr, "host: object_create failed: %s\n", made.as.error.message);
        plugin.api.variant_clear(&made);
        failures++;
        return;
    }
    const uint64_t world = made.as.object;
    const uint64_t ground = CALL(world, "add_body", V_BYTES(terrain, sizeof terrain), V_INT(TW), V_INT(TH),
                                 V_VEC2(320, 400), V_STR("static")).as.object;
    const uint64_t crate = CALL(world, "add_body_rgba", V_BYTES(crate_rgba, sizeof crate_rgba), V_INT(CRATE),
                                V_INT(CRATE), V_VEC2(200, 300), V_STR("dynamic")).as.object;
    const uint64_t barb = CALL(world, "add_body", V_BYTES(bar, sizeof bar), V_INT(BAR_W), V_INT(BAR_H),
                               V_VEC2(460, ground_top - BAR_H / 2.0 - 1), V_STR("dynamic")).as.object;
    /* The lamp hangs 10 px below the centre of the cave roof's last row (terrain row 89). */
    const pp_vec2 roof = {440, 400.0 - TH / 2.0 + 89.5};
    const uint64_t lamp = CALL(world, "add_body", V_BYTES(lamp_mask, sizeof lamp_mask), V_INT(LAMP), V_INT(LAMP),
                               V_VEC2(roof.x, roof.y + 10), V_STR("dynamic")).as.object;
    CALL(world, "add_joint", V_STR("revolute"), V_OBJ(ground), V_OBJ(lamp), V_VEC2(roof.x, roof.y), V_VEC2(0, 0),
         V_VEC2(1, 0));

    printf("scene: terrain %dx%d (top at y %.0f), crate %d px, bar %dx%d\n", TW, TH, ground_top, CRATE, BAR_W, BAR_H);
    expect(CALL(crate, "get_mass").as.real == CRATE * CRATE, "crate mass = its pixel count (density 1)",
           CALL(crate, "get_mass").as.real);

    step_for(world, 0.6); /* landed (awake or asleep, its pair lists its contacts) */
    const int64_t contacts = CALL(world, "get_contact_count").as.integer;
    const pp_vec2 n = contacts > 0 ? CALL(world, "get_contact_normal", V_INT(0)).as.vec2 : (pp_vec2){0, 0};
    expect(contacts > 0 && fabs(hypot(n.x, n.y) - 1.0) < 1e-3, "contacts of the last step, with unit normals",
           (double)contacts);
    step_for(world, 1.4);
    const pp_vec2 rest = CALL(crate, "get_position").as.vec2, v = CALL(crate, "get_velocity").as.vec2;
    expect(fabs(rest.y + CRATE / 2.0 - ground_top) < 1.5, "crate rests: bottom − terrain top, px",
           rest.y + CRATE / 2.0 - ground_top);
    expect(hypot(v.x, v.y) < 5.0, "crate rests: speed, px/s", hypot(v.x, v.y));

    const int64_t erased = CALL(ground, "erase_circle", V_VEC2(rest.x, ground_top), V_FLOAT(30)).as.integer;
    step_for(world, 0.5);
    const pp_vec2 fell = CALL(crate, "get_position").as.vec2;
    expect(erased > 0 && fell.y - rest.y > 10.0, "crater under the crate: it falls, px in 0.5 s", fell.y - rest.y);

    count_events(world, ""); /* forget what came before the cut */
    const int64_t before = CALL(world, "get_body_count").as.integer;
    const pp_vec2 mid = CALL(barb, "get_position").as.vec2;
    CALL(barb, "erase_circle", V_VEC2(mid.x, mid.y), V_FLOAT(5));
    const int64_t splits = count_events(world, "split"), after = CALL(world, "get_body_count").as.integer;
    expect(splits == 1 && after == before + 1, "bar cut through its middle: split events", (double)splits);
    step_for(world, 0.5);

    const double hung = CALL(lamp, "get_position").as.vec2.y;
    expect(fabs(hung - roof.y - 10) < 0.5, "lamp on a hinge under the cave roof: drop in 2.5 s, px", hung - roof.y - 10);
    CALL(ground, "erase_circle", V_VEC2(roof.x, roof.y), V_FLOAT(3));
    const int64_t broken = count_events(world, "joint_broken");
    step_for(world, 0.5);
    const double dropped = CALL(lamp, "get_position").as.vec2.y - hung;
    expect(broken == 1 && dropped > 10, "the hinge's roof pixel erased: joint_broken, lamp falls, px", dropped);
    printf("  step cost %.3f ms (last step)\n", CALL(world, "get_step_ms").as.real);

    pp_variant done;
    plugin.api.object_destroy(world, &done);
    plugin.api.call(crate, "get_position", NULL, 0, &done); /* the world took its bodies with it */
    expect(done.type == PP_VARIANT_ERROR && done.as.error.status == PP_ERR_INVALID_HANDLE,
           "a body of a destroyed world answers INVALID_HANDLE", done.as.error.status);
    plugin.api.variant_clear(&done);
}

int main(int argc, char **argv)
{
    const char *manifest = argc > 1 ? argv[1] : "plugin/physpix.plugin";
    const pp_host_interface host = {sizeof host, PP_PLUGIN_INTERFACE_VERSION, "physpix reference host", host_log, NULL};
    char err[1024];
    if (host_plugin_load(manifest, &host, &plugin, err, sizeof err) != PP_OK) {
        fprintf(stderr, "host: %s\n", err);
        return 1;
    }
    list_classes();
    run_scene();
    host_plugin_unload(&plugin);
    printf("host scene: %s\n", failures ? "FAILED" : "PASS");
    return failures ? 1 : 0;
}
