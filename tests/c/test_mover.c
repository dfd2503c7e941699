/* pp_world_move_character, each test a game loop at 60 Hz on a static terrain drawn pixel by pixel (bitmap
 * coordinates are world coordinates; y grows down, gravity 980 px/s² down): flat ground, random ±1 px bumps, 2 px
 * stairs, a wall, a 30° slope up and down, a 60° slope slid down, 5,000 and 20,000 px/s into thin walls, the ground
 * erased under it, a kinematic platform, the world unchanged, misuse. After every frame of every test the capsule
 * overlaps no solid pixel centre by more than 0.5 px. */
#include "helpers.h"

PP_TEST_SUITE(mover);

#define DT (1.0f / 60.0f)
#define G 980.0f

/* A terrain: one static body whose bitmap pixel (x, y) is world pixel (x, y). */
typedef struct terrain {
    pp_world w;
    pp_body body;
    uint8_t *mask;
    int width, height;
    pp_character_def def;
    int frames;
} terrain;

static void terrain_make(terrain *t, float gravity, int width, int height)
{
    *t = (terrain){.w = make_world(0, gravity), .width = width, .height = height, .def = pp_character_def_default()};
    t->mask = calloc((size_t)width * (size_t)height, 1);
    cr_assert_not_null(t->mask);
}

static void terrain_fill(terrain *t, int x0, int y0, int x1, int y1)
{
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++)
            if (x >= 0 && y >= 0 && x < t->width && y < t->height)
                t->mask[(size_t)y * t->width + x] = 1;
}

/* Every pixel whose centre lies below the surface y = top(x) (world px). */
static void terrain_ground(terrain *t, double (*top)(double x, const void *arg), const void *arg)
{
    for (int x = 0; x < t->width; x++)
        for (int y = 0; y < t->height; y++)
            if (y + 0.5 > top(x + 0.5, arg))
                t->mask[(size_t)y * t->width + x] = 1;
}

static void terrain_build(terrain *t)
{
    pp_body_def d = body_def(PP_BODY_STATIC, 0, 0, 0);
    d.custom_pivot = 1;
    d.pivot = v2(0, 0);
    d.width = t->width, d.height = t->height, d.mask = t->mask;
    t->body = create_body_ok(t->w, &d);
}

static void terrain_free(terrain *t)
{
    pp_world_destroy(t->w);
    free(t->mask);
}

/* How deep the capsule at p reaches past the nearest solid pixel centre (px; ≤ 0 when clear of all). */
static double overlap(const terrain *t, pp_vec2 p)
{
    const double r = t->def.radius, hh = t->def.half_height;
    double worst = -INFINITY;
    for (int y = (int)floor(p.y - hh - r - 1); y <= (int)ceil(p.y + hh + r + 1); y++)
        for (int x = (int)floor(p.x - r - 1); x <= (int)ceil(p.x + r + 1); x++) {
            if (x < 0 || y < 0 || x >= t->width || y >= t->height || !t->mask[(size_t)y * t->width + x])
                continue;
            const double cy = fmin(fmax(y + 0.5, p.y - hh), p.y + hh);
            worst = fmax(worst, r - hypot(x + 0.5 - p.x, y + 0.5 - cy));
        }
    return worst;
}

/* One frame: the move, the overlap check, the position kept. */
static pp_character_move frame(terrain *t, pp_vec2 *p, pp_vec2 v)
{
    pp_character_move m;
    memset(&m, 0x5a, sizeof m);
    PP_OK_OR_FAIL(pp_world_move_character(t->w, &t->def, *p, v, DT, &m));
    const double o = overlap(t, m.position);
    cr_assert(o <= 0.5, "frame %d: at (%g, %g) the capsule overlaps a pixel centre by %g px", t->frames, m.position.x,
              m.position.y, o);
    t->frames++;
    *p = m.position;
    return m;
}

/* A walker's velocity for the next frame: the walk asked for, gravity added to what the last move left. */
static pp_vec2 walk(float speed, const pp_character_move *m)
{
    const float vy = m->grounded && m->velocity.y > 0 ? 0 : m->velocity.y;
    return v2(speed, vy + G * DT);
}

/* The character's foot: the capsule's lowest point is p.y + half_height + radius. */
static float foot(const terrain *t) { return t->def.half_height + t->def.radius; }

static double flat_top(double x, const void *arg) { (void)x; return *(const double *)arg; }

Test(mover, on_flat_ground_it_walks_grounded_at_a_constant_height)
{
    terrain t;
    terrain_make(&t, G, 800, 400);
    const double top = 300;
    terrain_ground(&t, flat_top, &top);
    terrain_build(&t);
    pp_vec2 p = v2(100, (float)(top - foot(&t) - 0.01));
    const float y0 = p.y, speed = 120;
    pp_character_move m = {.grounded = 1};
    for (int i = 0; i < 180; i++) {
        m = frame(&t, &p, walk(speed, &m));
        cr_assert(m.grounded, "frame %d: not grounded at (%g, %g)", i, p.x, p.y);
        cr_assert(fabs(p.y - y0) <= 0.5, "frame %d: height %g, started at %g", i, p.y, y0);
        cr_assert(fabs(m.ground_normal.x) < 1e-3 && fabs(m.ground_normal.y + 1) < 1e-3, "normal (%g, %g)",
                  m.ground_normal.x, m.ground_normal.y);
        cr_assert_eq(m.ground_body.id, t.body.id);
    }
    const double want = speed * 180 * DT;
    cr_expect(fabs(p.x - 100 - want) <= 0.02 * want, "walked %g px, expected %g", p.x - 100, want);
    terrain_free(&t);
}

static double bumpy_top(double x, const void *arg)
{
    const int8_t *bump = arg;
    return 300 + bump[(int)x];
}

/* Ground with random ±1 px bumps: flat stretches of 4 to 12 px, each followed by a bump 1 px up or down, 3 to 12 px
 * wide. A walk at `speed` px/s over 780 px of them (right from x 100, or left from x 900 when negative): grounded
 * every frame, never stalled (each frame advances over half of speed·dt); the largest frame-to-frame vertical change
 * returned. */
static double walk_bumps(float speed)
{
    terrain t;
    terrain_make(&t, G, 1000, 400);
    int8_t bump[1000];
    uint32_t s = 12345;
    for (int x = 0; x < 1000;) {
        s = s * 1664525u + 1013904223u;
        for (int k = 0, n = 4 + (int)((s >> 24) % 9); k < n && x < 1000; k++)
            bump[x++] = 0;
        s = s * 1664525u + 1013904223u;
        for (int k = 0, n = 3 + (int)((s >> 24) % 10); k < n && x < 1000; k++)
            bump[x++] = (s >> 16) & 1 ? 1 : -1;
    }
    terrain_ground(&t, bumpy_top, bump);
    terrain_build(&t);
    pp_vec2 p = v2(speed > 0 ? 100 : 900, (float)(300 - foot(&t) - 0.01));
    pp_character_move m = {0};
    for (int i = 0; i < 30; i++) /* settle */
        m = frame(&t, &p, walk(0, &m));
    cr_assert(m.grounded, "settled on the bumps at (%g, %g)", p.x, p.y);
    double worst = 0;
    const int frames = (int)(780 / fabs(speed * DT));
    for (int i = 0; i < frames; i++) {
        const pp_vec2 before = p;
        m = frame(&t, &p, walk(speed, &m));
        cr_assert(m.grounded, "%g px/s, frame %d: not grounded at (%g, %g)", speed, i, p.x, p.y);
        cr_assert((p.x - before.x) / speed > 0.5 * DT, "%g px/s, frame %d: stalled at x %g (moved %g px)", speed, i,
                  p.x, p.x - before.x);
        worst = fmax(worst, fabs(p.y - before.y));
    }
    terrain_free(&t);
    return worst;
}

Test(mover, on_random_bumps_it_stays_grounded_without_jitter_or_stalls)
{
    /* A round bottom riding the pixel squares' corners would rise 1 px over √(2r − 1) ≈ 3.9 px of travel: 0.87 px in
     * a frame at 150 px/s. The ride smooths it at a platformer's walking speeds, both ways (0.3 px a frame at most
     * here: the ride's rate). */
    const float speeds[] = {150, 250, -150, -250};
    for (size_t k = 0; k < sizeof speeds / sizeof speeds[0]; k++) {
        const double jitter = walk_bumps(speeds[k]);
        cr_expect(jitter < 0.5, "at %g px/s the height changed by %g px in a frame", speeds[k], jitter);
    }
}

/* Stairs from x = 200: `count` steps, each `rise` px up and `run` px long; then level. */
typedef struct stairs {
    double rise, run;
    int count;
} stairs;

static double stairs_top(double x, const void *arg)
{
    const stairs *s = arg;
    const int k = x < 200 ? 0 : (int)fmin((x - 200) / s->run + 1, s->count);
    return 300 - s->rise * k;
}

/* A walk at 100 px/s from x 100 for `frames` frames up the stairs, with this step_height; where it ends. */
static pp_character_move walk_stairs(const stairs *s, float step_height, int frames, pp_vec2 *p)
{
    terrain t;
    terrain_make(&t, G, 600, 400);
    terrain_ground(&t, stairs_top, s);
    terrain_build(&t);
    t.def.step_height = step_height;
    *p = v2(100, (float)(300 - foot(&t) - 0.01));
    pp_character_move m = {.grounded = 1};
    for (int i = 0; i < frames; i++)
        m = frame(&t, p, walk(100, &m));
    terrain_free(&t);
    return m;
}

Test(mover, it_climbs_stairs_of_2_px_steps)
{
    const stairs s = {2, 12, 15};
    pp_vec2 p;
    const pp_character_move m = walk_stairs(&s, 4, 240, &p);
    const float top = 270 - 16; /* the top, less the default capsule's foot */
    cr_expect(p.x > 420 && fabs(p.y - top) <= 0.5 && m.grounded, "at (%g, %g) grounded %u, the top is y 270", p.x,
              p.y, m.grounded);
}

Test(mover, it_steps_up_4_px_ledges_with_step_height_4_and_not_without_steps)
{
    const stairs s = {4, 24, 6};
    pp_vec2 p;
    pp_character_move m = walk_stairs(&s, 4, 300, &p);
    cr_expect(p.x > 400 && fabs(p.y - (276 - 16)) <= 0.5 && m.grounded, "at (%g, %g) grounded %u, the top is y 276",
              p.x, p.y, m.grounded);
    /* Without steps a 4 px ledge is a wall: the capsule's round bottom climbs by itself only ledges up to
     * r(1 − cos max_slope) = 2.4 px, whose corner is no steeper than max_slope. Stopped with its lower disc (radius
     * 8) on the first ledge's corner (200, 296). */
    m = walk_stairs(&s, 0, 300, &p);
    const double touch = 200 - sqrt(8 * 8 - 4 * 4);
    cr_expect(fabs(p.x - touch) <= 0.5 && m.grounded, "at (%g, %g): not stopped at x %g by the first 4 px ledge", p.x,
              p.y, touch);
}

Test(mover, a_12_px_wall_stops_it_touching)
{
    terrain t;
    terrain_make(&t, G, 600, 400);
    const double top = 300;
    terrain_ground(&t, flat_top, &top);
    terrain_fill(&t, 300, 288, 320, 300);
    terrain_build(&t);
    pp_vec2 p = v2(200, (float)(top - foot(&t) - 0.01));
    pp_character_move m = {.grounded = 1};
    for (int i = 0; i < 120; i++)
        m = frame(&t, &p, walk(150, &m));
    const double gap = 300 - (p.x + t.def.radius);
    cr_expect(gap >= -0.5 && gap <= 0.5, "stopped %g px from the wall", gap);
    cr_expect(m.grounded && fabs(p.y - (top - foot(&t))) <= 0.5, "at (%g, %g) grounded %u", p.x, p.y, m.grounded);
    cr_expect(fabs(m.velocity.x) < 1e-3, "velocity into the wall %g px/s", m.velocity.x);
    terrain_free(&t);
}

/* Level at y 400 to x 200, rising at `slope` to x 200 + run, level again. */
typedef struct slope_arg {
    double angle, run;
} slope_arg;

static double slope_top(double x, const void *arg)
{
    const slope_arg *s = arg;
    return 400 - tan(s->angle) * fmin(fmax(x - 200, 0), s->run);
}

Test(mover, a_30_degree_slope_is_walked_up_and_down_grounded)
{
    terrain t;
    terrain_make(&t, G, 900, 500);
    const slope_arg s = {DEG2RAD(30), 400};
    terrain_ground(&t, slope_top, &s);
    terrain_build(&t);
    const double nx = -sin(s.angle), ny = -cos(s.angle); /* out of the slope */
    pp_vec2 p = v2(120, (float)(400 - foot(&t) - 0.01));
    pp_character_move m = {.grounded = 1};
    int on_slope = 0;
    for (int i = 0; i < 600 && p.x < 700; i++) {
        m = frame(&t, &p, walk(120, &m));
        cr_assert(m.grounded, "up, frame %d: not grounded at (%g, %g)", i, p.x, p.y);
        if (p.x > 230 && p.x < 200 + s.run - 30) {
            on_slope++;
            const double err = RAD2DEG(acos(fmin(1, m.ground_normal.x * nx + m.ground_normal.y * ny)));
            cr_assert(err <= 3, "up, frame %d at x %g: ground normal (%g, %g) is %g° off the slope's", i, p.x,
                      m.ground_normal.x, m.ground_normal.y, err);
        }
    }
    cr_assert(p.x >= 700 && on_slope > 100, "walked up to x %g", p.x);
    for (int i = 0; i < 360 && p.x > 120; i++) {
        m = frame(&t, &p, walk(-200, &m));
        cr_assert(m.grounded, "down, frame %d: not grounded at (%g, %g)", i, p.x, p.y);
        if (p.x > 230 && p.x < 200 + s.run - 30) {
            const double err = RAD2DEG(acos(fmin(1, m.ground_normal.x * nx + m.ground_normal.y * ny)));
            cr_assert(err <= 3, "down, frame %d at x %g: ground normal (%g, %g) is %g° off the slope's", i, p.x,
                      m.ground_normal.x, m.ground_normal.y, err);
        }
    }
    cr_expect(p.x <= 120 && fabs(p.y - (400 - foot(&t))) <= 0.5, "walked down to (%g, %g)", p.x, p.y);
    terrain_free(&t);
}

Test(mover, a_60_degree_slope_is_slid_down)
{
    terrain t;
    terrain_make(&t, G, 900, 800);
    const slope_arg s = {DEG2RAD(60), 300};
    terrain_ground(&t, slope_top, &s);
    terrain_build(&t);
    /* Dropped onto the slope's middle (its surface at x 350 is y 400 − 150·tan 60°). */
    pp_vec2 p = v2(350, (float)(400 - 150 * tan(s.angle) - foot(&t) - 30));
    const pp_vec2 p0 = p;
    pp_character_move m = {0};
    int grounded = 0;
    for (int i = 0; i < 60; i++) {
        m = frame(&t, &p, walk(0, &m));
        grounded += m.grounded != 0;
    }
    cr_expect_eq(grounded, 0, "grounded on a 60° slope in %d frames", grounded);
    cr_expect(p.x < p0.x - 20 && p.y > p0.y + 40, "from (%g, %g) to (%g, %g): not slid down the slope", p0.x, p0.y,
              p.x, p.y);
    terrain_free(&t);
}

Test(mover, at_5000_px_per_s_a_4_px_wall_stops_it)
{
    terrain t;
    terrain_make(&t, 0, 1200, 200);
    terrain_fill(&t, 600, 0, 604, 200);
    terrain_build(&t);
    pp_vec2 p = v2(100.3f, 100);
    for (int i = 0; i < 30; i++) {
        const pp_character_move m = frame(&t, &p, v2(5000, 0));
        cr_assert(p.x + t.def.radius <= 600.5, "frame %d: at x %g, through the wall's face at 600", i, p.x);
        (void)m;
    }
    cr_expect(p.x + t.def.radius >= 599.5, "stopped %g px short of the wall", 600 - p.x - t.def.radius);
    terrain_free(&t);
}

Test(mover, at_20000_px_per_s_a_4_px_floor_stops_it)
{
    terrain t;
    terrain_make(&t, 0, 200, 2400);
    terrain_fill(&t, 0, 2000, 200, 2004);
    terrain_build(&t);
    pp_vec2 p = v2(100, 50.7f);
    pp_character_move m = {0};
    for (int i = 0; i < 30; i++) {
        m = frame(&t, &p, v2(0, 20000));
        cr_assert(p.y + foot(&t) <= 2000.5, "frame %d: at y %g, through the floor's top at 2000", i, p.y);
    }
    cr_expect(p.y + foot(&t) >= 1999.5 && m.grounded, "stopped %g px above the floor, grounded %u",
              2000 - p.y - foot(&t), m.grounded);
    terrain_free(&t);
}

Test(mover, with_the_ground_erased_under_it_it_falls)
{
    terrain t;
    terrain_make(&t, G, 600, 400);
    const double top = 300;
    terrain_ground(&t, flat_top, &top);
    terrain_build(&t);
    pp_vec2 p = v2(300, (float)(top - foot(&t) - 0.01));
    pp_character_move m = {.grounded = 1};
    for (int i = 0; i < 10; i++)
        m = frame(&t, &p, walk(0, &m));
    cr_assert(m.grounded);
    const float y0 = p.y;
    int32_t changed = 0;
    PP_OK_OR_FAIL(pp_world_erase_circle(t.w, v2(300, 300), 40, &changed));
    cr_assert(changed > 0);
    for (int y = 0; y < t.height; y++) /* the test's copy of the pixels, for the overlap check */
        for (int x = 0; x < t.width; x++)
            if (hypot(x + 0.5 - 300, y + 0.5 - 300) <= 40)
                t.mask[(size_t)y * t.width + x] = 0;
    int fell_at = -1;
    for (int i = 0; i < 10 && fell_at < 0; i++) {
        m = frame(&t, &p, walk(0, &m));
        if (!m.grounded && p.y > y0 + 1)
            fell_at = i;
    }
    cr_expect(fell_at >= 0, "still at y %g (from %g), grounded %u after 10 frames", p.y, y0, m.grounded);
    terrain_free(&t);
}

Test(mover, on_a_kinematic_platform_the_ground_velocity_is_the_platforms)
{
    terrain t;
    terrain_make(&t, G, 100, 100); /* no terrain: the platform is the ground */
    terrain_build(&t);
    pp_body_def d = body_def(PP_BODY_KINEMATIC, 400, 300, 0);
    d.linear_velocity = v2(50, -10);
    pp_body platform = add_rect(t.w, d, 120, 10); /* its top at y 295 */
    pp_vec2 p = v2(410, (float)(295 - foot(&t) - 0.01));
    pp_character_move m;
    PP_OK_OR_FAIL(pp_world_move_character(t.w, &t.def, p, v2(0, 0), DT, &m));
    cr_assert(m.grounded);
    cr_expect_eq(m.ground_body.id, platform.id);
    cr_expect(fabs(m.ground_velocity.x - 50) < 1e-3 && fabs(m.ground_velocity.y + 10) < 1e-3,
              "ground velocity (%g, %g)", m.ground_velocity.x, m.ground_velocity.y);
    terrain_free(&t);
}

Test(mover, sensors_and_filtered_bodies_do_not_block)
{
    terrain t;
    terrain_make(&t, 0, 100, 100);
    terrain_build(&t);
    pp_body_def d = body_def(PP_BODY_STATIC, 300, 100, 0);
    d.is_sensor = 1;
    add_rect(t.w, d, 10, 100);
    d = body_def(PP_BODY_STATIC, 350, 100, 0);
    d.category_bits = 2;
    add_rect(t.w, d, 10, 100);
    t.def.mask_bits = ~2u;
    pp_character_move m;
    PP_OK_OR_FAIL(pp_world_move_character(t.w, &t.def, v2(200, 100), v2(12000, 0), 1.0f / 60, &m));
    cr_expect(fabs(m.position.x - 400) < 1e-3 && m.surfaces == 0, "ended at x %g after %d surfaces", m.position.x,
              m.surfaces);
    t.def.mask_bits = 0xffffffffu;
    PP_OK_OR_FAIL(pp_world_move_character(t.w, &t.def, v2(200, 100), v2(12000, 0), 1.0f / 60, &m));
    cr_expect(m.position.x + t.def.radius <= 345 && m.position.x + t.def.radius > 344.5 && m.surfaces >= 1,
              "stopped at x %g by the filtered-in wall at 345", m.position.x);
    terrain_free(&t);
}

Test(mover, a_hundred_moves_change_nothing_in_the_world)
{
    terrain t;
    terrain_make(&t, G, 600, 400);
    const double top = 300;
    terrain_ground(&t, flat_top, &top);
    terrain_fill(&t, 300, 288, 320, 300);
    terrain_build(&t);
    uint64_t before = 0, after = 0;
    PP_OK_OR_FAIL(pp_world_get_hash(t.w, &before));
    pp_vec2 p = v2(200, (float)(top - foot(&t) - 0.01));
    pp_character_move m = {.grounded = 1};
    for (int i = 0; i < 100; i++)
        m = frame(&t, &p, walk(150, &m));
    PP_OK_OR_FAIL(pp_world_get_hash(t.w, &after));
    cr_expect_eq(before, after, "hash %llx before, %llx after", (unsigned long long)before, (unsigned long long)after);
    terrain_free(&t);
}

Test(mover, misuse_is_refused_with_a_status_and_a_message)
{
    pp_world w = make_world(0, G);
    const pp_character_def good = pp_character_def_default();
    pp_character_def d = good;
    pp_character_move m;
    const pp_vec2 p = v2(0, 0), v = v2(10, 0);
    EXPECT_ERR(pp_world_move_character(w, NULL, p, v, DT, &m), PP_ERR_INVALID_ARGUMENT, "pp_world_move_character");
    EXPECT_ERR(pp_world_move_character(w, &d, p, v, DT, NULL), PP_ERR_INVALID_ARGUMENT, "out");
    d.struct_size = 4;
    EXPECT_ERR(pp_world_move_character(w, &d, p, v, DT, &m), PP_ERR_ABI, "struct_size");
    d = good, d.radius = 0;
    EXPECT_ERR(pp_world_move_character(w, &d, p, v, DT, &m), PP_ERR_INVALID_ARGUMENT, "radius");
    d = good, d.radius = NAN;
    EXPECT_ERR(pp_world_move_character(w, &d, p, v, DT, &m), PP_ERR_INVALID_ARGUMENT, "radius");
    d = good, d.half_height = -1;
    EXPECT_ERR(pp_world_move_character(w, &d, p, v, DT, &m), PP_ERR_INVALID_ARGUMENT, "half_height");
    d = good, d.step_height = -1;
    EXPECT_ERR(pp_world_move_character(w, &d, p, v, DT, &m), PP_ERR_INVALID_ARGUMENT, "step_height");
    d = good, d.snap_distance = INFINITY;
    EXPECT_ERR(pp_world_move_character(w, &d, p, v, DT, &m), PP_ERR_INVALID_ARGUMENT, "snap_distance");
    d = good, d.max_slope = 2;
    EXPECT_ERR(pp_world_move_character(w, &d, p, v, DT, &m), PP_ERR_INVALID_ARGUMENT, "max_slope");
    EXPECT_ERR(pp_world_move_character(w, &good, v2(NAN, 0), v, DT, &m), PP_ERR_INVALID_ARGUMENT, "position");
    EXPECT_ERR(pp_world_move_character(w, &good, p, v2(0, INFINITY), DT, &m), PP_ERR_INVALID_ARGUMENT, "velocity");
    EXPECT_ERR(pp_world_move_character(w, &good, p, v2(2e6f, 0), DT, &m), PP_ERR_INVALID_ARGUMENT, "PP_MAX_SPEED");
    EXPECT_ERR(pp_world_move_character(w, &good, p, v, -DT, &m), PP_ERR_INVALID_ARGUMENT, "dt");
    EXPECT_ERR(pp_world_move_character(w, &good, p, v, NAN, &m), PP_ERR_INVALID_ARGUMENT, "dt");
    /* Every message names the call. */
    EXPECT_ERR(pp_world_move_character(w, &good, p, v, NAN, &m), PP_ERR_INVALID_ARGUMENT, "pp_world_move_character");
    PP_OK_OR_FAIL(pp_world_move_character(w, &good, p, v, 0, &m));
    cr_expect(m.position.x == 0 && m.position.y == 0 && !m.grounded, "dt 0 moves nothing");
    pp_world_destroy(w);
    EXPECT_ERR(pp_world_move_character(w, &good, p, v, DT, &m), PP_ERR_INVALID_HANDLE, "pp_world_move_character");
    EXPECT_ERR(pp_world_move_character((pp_world){0}, &good, p, v, DT, &m), PP_ERR_INVALID_HANDLE, "world");
}
