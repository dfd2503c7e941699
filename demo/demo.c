/* The PhysPix demo: loads the plugin through its manifest, runs demo/scene.json (caves, crates, a weighted
 * hammer, a rope bridge of jointed planks, timed explosions) only through the plugin's generic call, and renders it in software: frames,
 * a contact sheet and a debug view of one collision (the poster's Figure 1c), as PNG in build/demo/.
 * It exits 0 only if the physics it shows holds: a split, a crate fallen into a crater, nothing NaN. */
#include "debug_view.h"
#include "plugin_host.h"
#include "render.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define DT (1.0 / 60.0)
#define CRATE_TAG 100       /* user_data of the scene's crates: 100, 101, ... (a crate's pieces keep it) */
#define CRATER_FALL_PX 20.0 /* how far a crate must fall into a crater, and a split-off piece fall, px */

enum { SHEET_COLS = 4, SHEET_ROWS = 3, MAX_EDITS = 64, MAX_WATCH = 512 };

typedef struct options {
    double seconds;
    int every, overlay, quiet;
    const char *out, *scene, *manifest;
} options;

/* A scheduled explosion, and the crates that stood over it when it went off. */
typedef struct explosion {
    double time;
    pp_vec2 center;
    float radius;
    int armed; /* its crates are recorded */
} explosion;

/* A crate over an explosion (explosion ≥ 0), or a piece an edit split off (explosion −1), and its height then. */
typedef struct watch {
    uint64_t body;
    int64_t tag;
    int explosion;
    float y0;
} watch;

typedef struct demo {
    options opt;
    uint64_t world;
    pp_camera cam;
    explosion explosions[MAX_EDITS];
    int explosion_count;
    watch watches[MAX_WATCH];
    int watch_count;
    int64_t splits, destroyed, joints_broken, bodies_start;
    double step_ms, render_s;
    int steps, nan;
    render_image frame, sheet;
    debug_capture dbg;
} demo;

static host_plugin plugin;

static void host_log(int level, const char *message, void *user)
{
    if (level >= 2)
        fprintf(stderr, "[plugin] %s\n", message);
}

/* ---- calls through the plugin ---- */

static pp_variant try_call(uint64_t object, const char *method, const pp_variant *args, int argc)
{
    pp_variant ret;
    plugin.api.call(object, method, args, argc, &ret);
    return ret;
}

/* An ERROR result ends the demo: every call here is one the scene must answer. */
static pp_variant must_call(uint64_t object, const char *method, const pp_variant *args, int argc)
{
    pp_variant ret = try_call(object, method, args, argc);
    if (ret.type == PP_VARIANT_ERROR) {
        fprintf(stderr, "demo: %s failed (%s): %s\n", method, pp_status_name(ret.as.error.status), ret.as.error.message);
        plugin.api.variant_clear(&ret);
        host_plugin_unload(&plugin);
        exit(1);
    }
    return ret;
}

#define ARGV(...) ((const pp_variant[]){{.type = PP_VARIANT_NIL}, __VA_ARGS__} + 1)
#define ARGC(...) ((int)(sizeof((const pp_variant[]){{.type = PP_VARIANT_NIL}, __VA_ARGS__}) / sizeof(pp_variant)) - 1)
/* CALL(obj, "method", args...) and CALL0(obj, "method"). */
#define CALL(obj, method, ...) must_call(obj, method, ARGV(__VA_ARGS__), ARGC(__VA_ARGS__))
#define CALL0(obj, method) must_call(obj, method, NULL, 0)

static int is_static(uint64_t body)
{
    pp_variant t = CALL0(body, "get_type");
    const int s = strcmp(t.as.string.data, "static") == 0;
    plugin.api.variant_clear(&t);
    return s;
}

static const char *body_name(int64_t tag, char *buf, size_t size)
{
    static const char *names[] = {"body", "terrain", "bridge", "hammer"};
    if (tag >= CRATE_TAG)
        snprintf(buf, size, "crate %lld", (long long)(tag - CRATE_TAG + 1));
    else
        snprintf(buf, size, "%s", names[tag >= 0 && tag < 4 ? tag : 0]);
    return buf;
}

/* ---- options and files ---- */

static void usage(const char *argv0)
{
    fprintf(stderr,
            "usage: %s [--seconds S] [--every N] [--out DIR] [--scene PATH] [--manifest PATH] [--overlay] [--quiet]\n"
            "  --seconds S   simulated time to run (default 7.5)\n"
            "  --every N     render every Nth step of 1/60 s (default 3)\n"
            "  --out DIR     where frames, the contact sheet and the debug view go (default build/demo)\n"
            "  --scene PATH  the scene file (default demo/scene.json)\n"
            "  --overlay     draw contact points and normals\n"
            "  --quiet       no progress bar\n",
            argv0);
    exit(2);
}

static options parse_options(int argc, char **argv)
{
    options o = {7.5, 3, 0, 0, "build/demo", "demo/scene.json", "plugin/physpix.plugin"};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--overlay") == 0)
            o.overlay = 1;
        else if (strcmp(a, "--quiet") == 0)
            o.quiet = 1;
        else if (!v)
            usage(argv[0]);
        else if (strcmp(a, "--seconds") == 0)
            o.seconds = atof(v), i++;
        else if (strcmp(a, "--every") == 0)
            o.every = atoi(v), i++;
        else if (strcmp(a, "--out") == 0)
            o.out = v, i++;
        else if (strcmp(a, "--scene") == 0)
            o.scene = v, i++;
        else if (strcmp(a, "--manifest") == 0)
            o.manifest = v, i++;
        else
            usage(argv[0]);
    }
    if (!(o.seconds > 0 && o.seconds <= 600) || o.every < 1)
        usage(argv[0]);
    return o;
}

static int mkdir_p(const char *path)
{
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", path);
    for (char *p = buf + 1;; p++) {
        const char c = *p;
        if (c != '/' && c != 0)
            continue;
        *p = 0;
        if (mkdir(buf, 0755) != 0 && errno != EEXIST)
            return 0;
        if (!(*p = c))
            return 1;
    }
}

static void save_png(const render_image *im, const char *dir, const char *name)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (render_image_save(im, path) != PP_OK) {
        fprintf(stderr, "demo: cannot write %s: %s\n", path, pp_last_error());
        exit(1);
    }
}

/* ---- the scene ---- */

static void load_scene(demo *d)
{
    pp_variant made;
    plugin.api.object_create("PhysPixWorld", &made);
    if (made.type != PP_VARIANT_OBJECT) {
        fprintf(stderr, "demo: object_create failed: %s\n", made.as.error.message);
        exit(1);
    }
    d->world = made.as.object;
    CALL(d->world, "load_scene", V_STR(d->opt.scene));
    const pp_vec2 size = CALL0(d->world, "get_camera_size").as.vec2;
    d->cam = (pp_camera){CALL0(d->world, "get_camera_center").as.vec2, (float)CALL0(d->world, "get_camera_zoom").as.real,
                         (int32_t)size.x, (int32_t)size.y};
    const int64_t n = CALL0(d->world, "get_scheduled_edit_count").as.integer;
    for (int64_t i = 0; i < n && d->explosion_count < MAX_EDITS; i++) {
        pp_variant type = CALL(d->world, "get_scheduled_edit_type", V_INT(i));
        if (strcmp(type.as.string.data, "erase") == 0)
            d->explosions[d->explosion_count++] = (explosion){
                CALL(d->world, "get_scheduled_edit_time", V_INT(i)).as.real,
                CALL(d->world, "get_scheduled_edit_center", V_INT(i)).as.vec2,
                (float)CALL(d->world, "get_scheduled_edit_radius", V_INT(i)).as.real, 0};
        plugin.api.variant_clear(&type);
    }
    d->bodies_start = CALL0(d->world, "get_body_count").as.integer;
}

/* The hammer's weight mask at work: its centre of mass sits in the heavy head, not mid-shape. */
static void report_hammer(demo *d)
{
    for (int64_t i = 0; i < d->bodies_start; i++) {
        const uint64_t b = CALL(d->world, "get_body", V_INT(i)).as.object;
        if (CALL0(b, "get_user_data").as.integer != 3)
            continue;
        const pp_vec2 c = CALL0(b, "get_center_of_mass").as.vec2, size = CALL0(b, "get_size").as.vec2;
        printf("  hammer: mass %.0f, centre of mass at (%.1f, %.1f) px of its %.0f x %.0f bitmap (head at the top)\n",
               CALL0(b, "get_mass").as.real, c.x, c.y, size.x, size.y);
    }
}

/* Before an explosion goes off, note every crate standing over it. */
static void arm_explosions(demo *d, double t)
{
    for (int e = 0; e < d->explosion_count; e++) {
        explosion *x = &d->explosions[e];
        if (x->armed || x->time >= t + 0.5 * DT) /* the library applies it at the step nearest its time */
            continue;
        x->armed = 1;
        const int64_t n = CALL0(d->world, "get_body_count").as.integer;
        for (int64_t i = 0; i < n && d->watch_count < MAX_WATCH; i++) {
            const uint64_t b = CALL(d->world, "get_body", V_INT(i)).as.object;
            const int64_t tag = CALL0(b, "get_user_data").as.integer;
            const pp_vec2 p = CALL0(b, "get_position").as.vec2;
            if (tag >= CRATE_TAG && fabsf(p.x - x->center.x) <= x->radius + 16 && p.y < x->center.y)
                d->watches[d->watch_count++] = (watch){b, tag, e, p.y};
        }
    }
}

static void read_events(demo *d)
{
    const int64_t n = CALL0(d->world, "get_event_count").as.integer;
    for (int64_t i = 0; i < n; i++) {
        pp_variant type = CALL(d->world, "get_event_type", V_INT(i));
        const char *what = type.as.string.data;
        d->destroyed += strcmp(what, "destroyed") == 0;
        d->joints_broken += strcmp(what, "joint_broken") == 0;
        if (strcmp(what, "split") == 0 && (d->splits++, d->watch_count < MAX_WATCH)) {
            const uint64_t piece = CALL(d->world, "get_event_other", V_INT(i)).as.object;
            d->watches[d->watch_count++] = (watch){piece, CALL0(piece, "get_user_data").as.integer, -1,
                                                   CALL0(piece, "get_position").as.vec2.y};
        }
        plugin.api.variant_clear(&type);
    }
}

/* ---- drawing a frame ---- */

static void draw_body(demo *d, render_image *im, uint64_t b)
{
    const pp_vec2 p = CALL0(b, "get_position").as.vec2, size = CALL0(b, "get_size").as.vec2;
    const float angle = (float)CALL0(b, "get_angle").as.real;
    if (!isfinite(p.x) || !isfinite(p.y) || !isfinite(angle))
        d->nan++;
    pp_variant rgba = CALL0(b, "get_rgba");
    const render_sprite s = {rgba.as.bytes.data, (int32_t)size.x, (int32_t)size.y, p, CALL0(b, "get_pivot").as.vec2,
                             angle};
    render_sprite_draw(im, &d->cam, &s);
    plugin.api.variant_clear(&rgba);
}

/* An explosion shows for a quarter second as a flash and a widening ring. */
static void draw_explosions(demo *d, render_image *im, double t)
{
    for (int e = 0; e < d->explosion_count; e++) {
        const explosion *x = &d->explosions[e];
        const double k = (t - x->time) / 0.25;
        if (k < 0 || k > 1)
            continue;
        const pp_vec2 c = render_to_image(&d->cam, x->center);
        const float r = x->radius * d->cam.zoom * (float)(1.0 + 0.8 * k);
        render_disc(im, c, r, 0, (render_color){255, 236, 150, (uint8_t)(170 * (1 - k))});
        render_disc(im, c, r, 5, (render_color){255, 120, 30, (uint8_t)(255 * (1 - k))});
    }
}

static void draw_contacts(demo *d, render_image *im)
{
    const int64_t n = CALL0(d->world, "get_contact_count").as.integer;
    for (int64_t i = 0; i < n; i++) {
        const pp_vec2 p = render_to_image(&d->cam, CALL(d->world, "get_contact_point", V_INT(i)).as.vec2);
        const pp_vec2 nrm = CALL(d->world, "get_contact_normal", V_INT(i)).as.vec2;
        render_line(im, p, (pp_vec2){p.x + 16 * nrm.x, p.y + 16 * nrm.y}, 1.5f, (render_color){255, 230, 40, 255});
        render_disc(im, p, 3, 0, (render_color){230, 30, 30, 255});
    }
}

static void draw_frame(demo *d, render_image *im, double t)
{
    render_sky(im);
    const int64_t n = CALL0(d->world, "get_body_count").as.integer;
    for (int pass = 0; pass < 2; pass++) /* the static scenery first, what moves over it */
        for (int64_t i = 0; i < n; i++) {
            const uint64_t b = CALL(d->world, "get_body", V_INT(i)).as.object;
            if (is_static(b) == (pass == 0))
                draw_body(d, im, b);
        }
    draw_explosions(d, im, t);
    if (d->opt.overlay)
        draw_contacts(d, im);
    char label[64];
    snprintf(label, sizeof label, "T = %.2f S", t);
    render_text(im, 13, 13, 3, label, (render_color){0, 0, 0, 120});
    render_text(im, 12, 12, 3, label, (render_color){255, 255, 255, 255});
}

/* ---- the contact sheet: SHEET_COLS × SHEET_ROWS thumbnails, each a SHEET_COLS-th of a frame's side ---- */

/* Frame f goes into the sheet's cells whose evenly spaced frame index it is. */
static void sheet_add(demo *d, int f, int frames, double t)
{
    const int cells = SHEET_COLS * SHEET_ROWS, cw = d->frame.width / SHEET_COLS, ch = d->frame.height / SHEET_COLS;
    for (int k = 0; k < cells; k++) {
        if ((int)lround((double)k * (frames - 1) / (cells - 1)) != f)
            continue;
        const int x = k % SHEET_COLS * cw, y = k / SHEET_COLS * ch;
        render_thumbnail(&d->sheet, x, y, cw, ch, &d->frame);
        render_rect(&d->sheet, x, y, cw, 1, (render_color){20, 20, 24, 255});
        render_rect(&d->sheet, x, y, 1, ch, (render_color){20, 20, 24, 255});
        char label[32];
        snprintf(label, sizeof label, "%.2f S", t);
        render_text(&d->sheet, x + 5, y + 5, 2, label, (render_color){255, 255, 255, 255});
    }
}

/* ---- the collision debug view (the poster's Figure 1c) ---- */

/* Rate a pair's grid: a large intersection beside cells of each body alone, with a slanted normal, makes
 * the clearest picture; a thin band along a flat contact the dullest. */
static double debug_score(const pp_variant *cells, int32_t w, int32_t h, pp_vec2 n)
{
    int64_t only[4] = {0}, critical = 0;
    for (int64_t i = 0; i < cells->as.bytes.length; i++) {
        only[cells->as.bytes.data[i] & 3]++;
        critical += (cells->as.bytes.data[i] & PP_CELL_CRITICAL) != 0;
    }
    if (w > 120 || h > 120 || critical == 0 || !only[PP_CELL_A] || !only[PP_CELL_B])
        return 0;
    const double interior = (double)(only[PP_CELL_A | PP_CELL_B] - critical);
    return pow((double)critical + 4.0 * interior, 0.75) * (0.25 + 4.0 * fabs(n.x * n.y));
}

static void consider_pair(demo *d, uint64_t a, uint64_t b, double t)
{
    pp_variant cells = CALL(d->world, "debug_collision", V_OBJ(a), V_OBJ(b));
    const pp_vec2 size = CALL0(d->world, "get_debug_size").as.vec2, n = CALL0(d->world, "get_debug_normal").as.vec2;
    const int32_t w = (int32_t)size.x, h = (int32_t)size.y;
    const int64_t ta = CALL0(a, "get_user_data").as.integer, tb = CALL0(b, "get_user_data").as.integer;
    /* The poster's case, a loose body on the terrain, is preferred to any other pair. */
    const int on_terrain = (ta == 1 && tb >= 3) || (tb == 1 && ta >= 3);
    const double score = debug_score(&cells, w, h, n) * (on_terrain ? 10.0 : 1.0);
    if (score <= d->dbg.score) {
        plugin.api.variant_clear(&cells);
        return;
    }
    pp_variant normals = CALL0(d->world, "get_debug_local_normals");
    debug_capture *c = &d->dbg;
    free(c->cells);
    free(c->normals);
    c->cells = malloc((size_t)w * h), c->normals = malloc((size_t)w * h * sizeof(pp_vec2));
    if (!c->cells || !c->normals) {
        fprintf(stderr, "demo: out of memory\n");
        exit(1);
    }
    memcpy(c->cells, cells.as.bytes.data, (size_t)w * h);
    memcpy(c->normals, normals.as.bytes.data, (size_t)w * h * sizeof(pp_vec2));
    c->width = w, c->height = h, c->normal = n, c->time = t, c->score = score;
    c->step_x = CALL0(d->world, "get_debug_step_x").as.vec2, c->step_y = CALL0(d->world, "get_debug_step_y").as.vec2;
    char na[32], nb[32];
    snprintf(c->what, sizeof c->what, "%s / %s", body_name(ta, na, sizeof na), body_name(tb, nb, sizeof nb));
    plugin.api.variant_clear(&cells);
    plugin.api.variant_clear(&normals);
}

/* Look at the pairs in contact now (each pair once; at most a few a frame). */
static void capture_debug(demo *d, double t)
{
    const int64_t n = CALL0(d->world, "get_contact_count").as.integer;
    uint64_t last_a = 0, last_b = 0;
    int tried = 0;
    for (int64_t i = 0; i < n && tried < 6; i++) {
        const uint64_t a = CALL(d->world, "get_contact_body_a", V_INT(i)).as.object;
        const uint64_t b = CALL(d->world, "get_contact_body_b", V_INT(i)).as.object;
        if ((a == last_a && b == last_b) || !a || !b)
            continue;
        last_a = a, last_b = b, tried++;
        consider_pair(d, a, b, t);
    }
}

static void write_debug_view(demo *d)
{
    render_image im;
    if (!render_image_init(&im, d->cam.width, d->cam.height)) {
        fprintf(stderr, "demo: out of memory\n");
        exit(1);
    }
    debug_view_draw(&im, &d->dbg);
    save_png(&im, d->opt.out, "collision_debug.png");
    render_image_free(&im);
}

/* ---- the run ---- */

/* A bar redrawn in place on a terminal; a line every tenth of the run otherwise. */
static void progress(const demo *d, int step, int steps, double t)
{
    const int tty = isatty(STDOUT_FILENO), pct = (int)(100L * step / steps);
    if (d->opt.quiet || (tty ? step % 6 != 0 && step != steps : step * 10 / steps == (step - 1) * 10 / steps))
        return;
    const int64_t bodies = CALL0(d->world, "get_body_count").as.integer;
    if (tty) {
        char bar[41];
        for (int i = 0; i < 40; i++)
            bar[i] = i < pct * 40 / 100 ? '#' : '.';
        bar[40] = 0;
        printf("\r  [%s] %3d%%  t %5.2f s  %3lld bodies  %2lld splits", bar, pct, t, (long long)bodies,
               (long long)d->splits);
        if (step == steps)
            printf("\n");
        fflush(stdout);
    } else {
        printf("  %3d%%  t %5.2f s  %lld bodies  %lld splits\n", pct, t, (long long)bodies, (long long)d->splits);
    }
}

static void render_step(demo *d, int frame, int frames, double t)
{
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    draw_frame(d, &d->frame, t);
    char name[64];
    snprintf(name, sizeof name, "frame_%04d.png", frame);
    save_png(&d->frame, d->opt.out, name);
    sheet_add(d, frame, frames, t);
    clock_gettime(CLOCK_MONOTONIC, &b);
    d->render_s += (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
}

static void run(demo *d)
{
    const int steps = (int)lround(d->opt.seconds / DT), frames = steps / d->opt.every + 1;
    if (!render_image_init(&d->frame, d->cam.width, d->cam.height) ||
        !render_image_init(&d->sheet, d->cam.width / SHEET_COLS * SHEET_COLS, d->cam.height / SHEET_COLS * SHEET_ROWS)) {
        fprintf(stderr, "demo: out of memory for %d x %d frames\n", (int)d->cam.width, (int)d->cam.height);
        exit(1);
    }
    render_step(d, 0, frames, 0.0);
    for (int step = 1; step <= steps; step++) {
        arm_explosions(d, CALL0(d->world, "get_time").as.real);
        CALL(d->world, "step", V_FLOAT(DT));
        d->step_ms += CALL0(d->world, "get_step_ms").as.real;
        d->steps++;
        read_events(d);
        const double t = CALL0(d->world, "get_time").as.real;
        if (t > 0.2) /* the pairs of every step compete for the debug view; settling contacts first */
            capture_debug(d, t);
        if (step % d->opt.every == 0)
            render_step(d, step / d->opt.every, frames, t);
        progress(d, step, steps, t);
    }
    save_png(&d->sheet, d->opt.out, "contact_sheet.png");
    write_debug_view(d);
    printf("  %d frames of %d x %d in %s/ (frame_0000.png .. frame_%04d.png), contact_sheet.png (%d x %d), "
           "collision_debug.png\n",
           frames, (int)d->cam.width, (int)d->cam.height, d->opt.out, frames - 1, (int)d->sheet.width,
           (int)d->sheet.height);
}

/* ---- figures and checks ---- */

/* The largest fall of a crate that stood over each explosion; the best over all of them. */
static double report_craters(demo *d)
{
    double best = 0;
    for (int e = 0; e < d->explosion_count; e++) {
        const explosion *x = &d->explosions[e];
        if (!x->armed)
            continue;
        double fall = 0;
        int64_t who = -1;
        for (int w = 0; w < d->watch_count; w++) {
            if (d->watches[w].explosion != e)
                continue;
            pp_variant p = try_call(d->watches[w].body, "get_position", NULL, 0);
            if (p.type == PP_VARIANT_VEC2 && p.as.vec2.y - d->watches[w].y0 > fall)
                fall = p.as.vec2.y - d->watches[w].y0, who = d->watches[w].tag;
            plugin.api.variant_clear(&p); /* an error: the crate was blown away */
        }
        char name[32];
        printf("  explosion %d at t %.2f s, (%.0f, %.0f) r %.0f px: ", e + 1, x->time, x->center.x, x->center.y,
               x->radius);
        if (who >= 0)
            printf("%s fell %.1f px into the crater\n", body_name(who, name, sizeof name), fall);
        else
            printf("no crate stood over it\n");
        best = fall > best ? fall : best;
    }
    return best;
}

/* How far each piece an edit split off has fallen since; the largest fall. */
static double report_pieces(demo *d)
{
    double best = 0;
    int shown = 0;
    for (int w = 0; w < d->watch_count; w++) {
        const watch *x = &d->watches[w];
        if (x->explosion >= 0)
            continue;
        pp_variant p = try_call(x->body, "get_position", NULL, 0);
        const double fall = p.type == PP_VARIANT_VEC2 ? p.as.vec2.y - x->y0 : 0.0;
        plugin.api.variant_clear(&p);
        char name[32];
        if (shown++ < 8)
            printf("  a piece of the %s split off and fell %.1f px\n", body_name(x->tag, name, sizeof name), fall);
        best = fall > best ? fall : best;
    }
    return best;
}

static int all_finite(demo *d)
{
    const int64_t n = CALL0(d->world, "get_body_count").as.integer;
    int ok = d->nan == 0;
    for (int64_t i = 0; i < n; i++) {
        const uint64_t b = CALL(d->world, "get_body", V_INT(i)).as.object;
        const pp_vec2 p = CALL0(b, "get_position").as.vec2, v = CALL0(b, "get_velocity").as.vec2;
        ok &= isfinite(p.x) && isfinite(p.y) && isfinite(v.x) && isfinite(v.y);
    }
    return ok;
}

static int report(demo *d, double wall_s)
{
    const double fall = report_craters(d), piece = report_pieces(d);
    const double last = d->explosion_count ? d->explosions[d->explosion_count - 1].time : 0;
    const int finite = all_finite(d), reached = d->opt.seconds >= last + 0.5;
    printf("  bodies: %lld at the start, %lld at the end; %lld splits, %lld bodies destroyed, %lld joints broken\n",
           (long long)d->bodies_start, (long long)CALL0(d->world, "get_body_count").as.integer, (long long)d->splits,
           (long long)d->destroyed, (long long)d->joints_broken);
    printf("  steps: %d of 1/60 s, %.3f ms a step on average; rendering and PNG %.2f s; run %.2f s\n", d->steps,
           d->steps ? d->step_ms / d->steps : 0.0, d->render_s, wall_s);
    int ok = finite;
    printf("  check: no NaN in any pose or velocity: %s\n", finite ? "ok" : "FAILED");
    if (reached) {
        printf("  check: at least one split, and a piece fell >= %.0f px (%.1f px): %s\n", CRATER_FALL_PX, piece,
               d->splits >= 1 && piece >= CRATER_FALL_PX ? "ok" : "FAILED");
        printf("  check: a crate fell >= %.0f px into a crater (%.1f px): %s\n", CRATER_FALL_PX, fall,
               fall >= CRATER_FALL_PX ? "ok" : "FAILED");
        ok &= d->splits >= 1 && piece >= CRATER_FALL_PX && fall >= CRATER_FALL_PX;
    } else {
        printf("  checks of splits and craters skipped: the run ends before the last explosion (t %.2f s)\n", last);
    }
    printf("demo: %s\n", ok ? "PASS" : "FAILED");
    return ok;
}

int main(int argc, char **argv)
{
    static demo d;
    d.opt = parse_options(argc, argv);
    const pp_host_interface host = {sizeof host, PP_PLUGIN_INTERFACE_VERSION, "physpix demo", host_log, NULL};
    char err[1024];
    if (host_plugin_load(d.opt.manifest, &host, &plugin, err, sizeof err) != PP_OK) {
        fprintf(stderr, "demo: %s\n", err);
        return 1;
    }
    if (!mkdir_p(d.opt.out)) {
        fprintf(stderr, "demo: cannot make %s: %s\n", d.opt.out, strerror(errno));
        return 1;
    }
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    load_scene(&d);
    printf("demo: %s, %.2f s at 1/60 s, every %d steps rendered at %d x %d, %d explosions\n", d.opt.scene,
           d.opt.seconds, d.opt.every, (int)d.cam.width, (int)d.cam.height, d.explosion_count);
    report_hammer(&d);
    run(&d);
    clock_gettime(CLOCK_MONOTONIC, &b);
    const int ok = report(&d, (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec));
    free(d.dbg.cells);
    free(d.dbg.normals);
    render_image_free(&d.frame);
    render_image_free(&d.sheet);
    host_plugin_unload(&plugin);
    return ok ? 0 : 1;
}
