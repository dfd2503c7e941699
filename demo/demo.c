/* PhysPix console demo: eight 32 px boxes and a disc fall onto an 800 × 40 ground bitmap with
 * a bump, a pit and a hole; the scene runs 5 simulated seconds at 1/60 s, printing every body's
 * pose once per simulated second and what the steps cost. Public API only. */
#include "physpix.h"

#include <stdio.h>
#include <string.h>

#define DT (1.0f / 60.0f)
#define STEPS_PER_SECOND 60
#define SECONDS 5
#define PI_F 3.14159265f

enum { GROUND_W = 800, GROUND_H = 40, GROUND_SURFACE = 16, BOX = 32, DISC = 40, MAX_BODIES = 16 };

/// A body of the scene with the name the demo prints.
typedef struct demo_body {
    const char *name;
    pp_body handle;
} demo_body;

typedef struct demo_scene {
    pp_world world;
    demo_body bodies[MAX_BODIES];
    int count;
} demo_scene;

/* Prints the failure and returns nonzero, so call sites read `if (failed(st, "...")) ...`. */
static int failed(pp_status st, const char *what)
{
    if (st == PP_OK)
        return 0;
    fprintf(stderr, "demo: %s failed: %s: %s\n", what, pp_status_name(st), pp_last_error());
    return 1;
}

/* The ground: solid below local row 16, a half-disc bump rising to the top of the bitmap,
 * a 60 px pit 14 px deep, and a closed hole of radius 6 inside the slab. */
static void paint_ground(uint8_t *mask)
{
    for (int y = 0; y < GROUND_H; y++) {
        for (int x = 0; x < GROUND_W; x++) {
            float px = (float)x + 0.5f, py = (float)y + 0.5f;
            int solid = y >= GROUND_SURFACE;
            float bx = px - 220.0f, by = py - (float)GROUND_SURFACE;
            if (bx * bx + by * by <= 14.0f * 14.0f)
                solid = 1;                                   /* bump */
            if (x >= 440 && x < 500 && y < GROUND_SURFACE + 14)
                solid = 0;                                   /* pit */
            float hx = px - 650.0f, hy = py - 30.0f;
            if (hx * hx + hy * hy <= 6.0f * 6.0f)
                solid = 0;                                   /* hole */
            mask[y * GROUND_W + x] = (uint8_t)solid;
        }
    }
}

/* A disc sprite: opaque inside the circle, transparent outside, so the alpha threshold
 * decides the collision shape. */
static void paint_disc(uint8_t *rgba)
{
    const float r = DISC * 0.5f;
    for (int y = 0; y < DISC; y++) {
        for (int x = 0; x < DISC; x++) {
            float dx = (float)x + 0.5f - r, dy = (float)y + 0.5f - r;
            uint8_t *p = &rgba[(y * DISC + x) * 4];
            int inside = dx * dx + dy * dy <= r * r;
            p[0] = 230, p[1] = 120, p[2] = 40;
            p[3] = inside ? 255 : 0;
        }
    }
}

static int add_body(demo_scene *s, const char *name, const pp_body_def *def)
{
    if (s->count == MAX_BODIES) {
        fprintf(stderr, "demo: too many bodies\n");
        return 1;
    }
    demo_body *b = &s->bodies[s->count];
    b->name = name;
    if (failed(pp_body_create(s->world, def, &b->handle), "pp_body_create"))
        return 1;
    s->count++;
    return 0;
}

static int build_scene(demo_scene *s)
{
    static uint8_t ground[GROUND_W * GROUND_H], box[BOX * BOX], disc[DISC * DISC * 4];
    paint_ground(ground);
    memset(box, 1, sizeof box);
    paint_disc(disc);

    pp_body_def def = pp_body_def_default();
    def.type = PP_BODY_STATIC;
    def.width = GROUND_W;
    def.height = GROUND_H;
    def.mask = ground;
    def.position = (pp_vec2){GROUND_W * 0.5f, 400.0f + GROUND_H * 0.5f}; /* top edge at y = 400 */
    if (add_body(s, "ground", &def))
        return 1;

    /* x, drop height above the surface (y = 416) and angle of each box; the third lands on
     * the bump, the sixth over the pit. */
    static const struct { const char *name; float x, height, angle_deg; } boxes[] = {
        {"box0", 80, 60, 0},   {"box1", 150, 120, 20}, {"box2", 222, 200, -35}, {"box3", 300, 90, 45},
        {"box4", 380, 250, 0}, {"box5", 470, 150, 10}, {"box6", 560, 300, -60}, {"box7", 720, 40, 5},
    };
    for (size_t i = 0; i < sizeof boxes / sizeof boxes[0]; i++) {
        def = pp_body_def_default();
        def.width = BOX;
        def.height = BOX;
        def.mask = box;
        def.position = (pp_vec2){boxes[i].x, 416.0f - boxes[i].height};
        def.angle = boxes[i].angle_deg * PI_F / 180.0f;
        def.user_data = i;
        if (add_body(s, boxes[i].name, &def))
            return 1;
    }

    def = pp_body_def_default();
    def.width = DISC;
    def.height = DISC;
    def.rgba = disc;
    def.position = (pp_vec2){640.0f, 100.0f};
    def.linear_velocity = (pp_vec2){-60.0f, 0.0f};
    def.restitution = 0.3f;
    return add_body(s, "disc", &def);
}

static int print_masses(const demo_scene *s)
{
    printf("%-7s %9s %16s %12s\n", "body", "mass", "centre (bitmap)", "inertia");
    for (int i = 1; i < s->count; i++) {
        float mass, inertia;
        pp_vec2 c;
        if (failed(pp_body_get_mass(s->world, s->bodies[i].handle, &mass, &c, &inertia), "pp_body_get_mass"))
            return 1;
        printf("%-7s %9.1f   (%5.2f, %5.2f) %12.0f\n", s->bodies[i].name, mass, c.x, c.y, inertia);
    }
    return 0;
}

/* Degrees for printing, with values that round to zero shown as 0.00 rather than -0.00. */
static float degrees(float radians)
{
    float d = radians * 180.0f / PI_F;
    return d > -0.005f && d < 0.005f ? 0.0f : d;
}

static int print_poses(const demo_scene *s, float t)
{
    printf("\nt = %.2f s\n%-7s %9s %9s %9s %6s\n", t, "body", "x px", "y px", "angle°", "awake");
    for (int i = 1; i < s->count; i++) {
        pp_vec2 p;
        float angle;
        int32_t awake;
        pp_body b = s->bodies[i].handle;
        if (failed(pp_body_get_position(s->world, b, &p), "pp_body_get_position") ||
            failed(pp_body_get_angle(s->world, b, &angle), "pp_body_get_angle") ||
            failed(pp_body_is_awake(s->world, b, &awake), "pp_body_is_awake"))
            return 1;
        printf("%-7s %9.2f %9.2f %9.2f %6s\n", s->bodies[i].name, p.x, p.y, degrees(angle), awake ? "yes" : "no");
    }
    return 0;
}

/* Running sums of one second's step stats, printed as means. */
typedef struct stats_sum {
    double broadphase, narrowphase, solver, total;
    long contacts;
    int steps;
} stats_sum;

static void stats_add(stats_sum *sum, const pp_step_stats *st)
{
    sum->broadphase += st->broadphase_ms;
    sum->narrowphase += st->narrowphase_ms;
    sum->solver += st->solver_ms;
    sum->total += st->total_ms;
    sum->contacts += st->contacts;
    sum->steps++;
}

static void print_stats(const stats_sum *sum, const pp_step_stats *last)
{
    double n = sum->steps;
    printf("steps: %.4f ms broadphase + %.4f ms narrowphase + %.4f ms solver = %.4f ms total (mean of %d)\n",
           sum->broadphase / n, sum->narrowphase / n, sum->solver / n, sum->total / n, sum->steps);
    printf("       %.1f contacts a step on average; last step: %d pairs, %d contacts, %d of %d bodies awake, "
           "%lld pixels tested, %s backend\n",
           (double)sum->contacts / n, last->pairs, last->contacts, last->awake_bodies, last->bodies,
           (long long)last->pixels_tested, last->backend == PP_BACKEND_GPU ? "GPU" : "CPU");
}

static int run(demo_scene *s)
{
    if (build_scene(s) || print_masses(s) || print_poses(s, 0.0f))
        return 1;
    for (int second = 1; second <= SECONDS; second++) {
        stats_sum sum = {0};
        pp_step_stats st;
        for (int i = 0; i < STEPS_PER_SECOND; i++) {
            if (failed(pp_world_step(s->world, DT), "pp_world_step") ||
                failed(pp_world_get_stats(s->world, &st), "pp_world_get_stats"))
                return 1;
            stats_add(&sum, &st);
        }
        if (print_poses(s, (float)second))
            return 1;
        print_stats(&sum, &st);
    }
    return 0;
}

int main(void)
{
    uint32_t v = pp_version();
    printf("PhysPix %u.%u.%u demo: 8 boxes and a disc on an %d x %d ground, dt 1/60 s, %d s\n\n", v / 10000,
           v / 100 % 100, v % 100, GROUND_W, GROUND_H, SECONDS);

    pp_world_def wdef = pp_world_def_default();
    demo_scene scene = {0};
    if (failed(pp_world_create(&wdef, &scene.world), "pp_world_create"))
        return 1;
    int rc = run(&scene);
    if (failed(pp_world_destroy(scene.world), "pp_world_destroy"))
        rc = 1;
    return rc;
}
