/* A range for every number (issue 39): each numeric argument and def field the API description gives a range is
 * fed its boundary values (tests/c/ranges_gen.h, generated from plugin/api/physpix_api.json's "ranges"): inside
 * is PP_OK, outside PP_ERR_INVALID_ARGUMENT (or the range's "past_max" status) with a message naming the argument,
 * on a fresh small world each time.
 * Where a limit depends on the body (an impulse's on its mass, a capacity on its size), the entry's "tested_as" gives
 * what it comes to on the fixture. An argument left out would be listed with a reason in "ranges"."untested". */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "helpers.h"
#include "physpix.h"

PP_TEST_SUITE(ranges);

/* A default world holding a 16 px dynamic box `b` at (100, 100) (weight 255, density 1: mass 256), a 16 px static
 * box `other` at (300, 100) and, for the joint fixtures, a revolute, prismatic or mouse joint holding b at its
 * centre (the motor fixture: a motor joint on b); the image fixture adds a 2 × 2 PNG at `path` in a fresh temporary folder. */
typedef struct range_fixture {
    pp_world w;
    pp_body b, other;
    pp_joint j;
    uint8_t mask[8 * 8];
    uint8_t rgba[8 * 8 * 4];
    uint8_t strip[PP_MAX_BITMAP_SIDE]; /* solid, for the body_def_strip fixture only */
    char dir[32], path[64];            /* the image fixture's folder and its 2 × 2 PNG */
} range_fixture;

/* What a const pixel argument reads (a mask or RGBA rows): ones, enough for a PP_MAX_BITMAP_SIDE × 1 image. */
static uint8_t range_plane[PP_MAX_BITMAP_SIDE * 4];

static pp_world_def range_world_def(range_fixture *f)
{
    (void)f;
    return pp_world_def_default();
}

static pp_status range_try_world_def(range_fixture *f, const pp_world_def *d)
{
    (void)f;
    pp_world w = {0};
    pp_status st = pp_world_create(d, &w);
    if (st == PP_OK)
        PP_OK_OR_FAIL(pp_world_destroy(w));
    return st;
}

static pp_body_def range_body_def(range_fixture *f)
{
    pp_body_def d = body_def(PP_BODY_DYNAMIC, 200, 300, 0);
    d.width = d.height = 8;
    d.mask = f->mask;
    return d;
}

static pp_status range_try_body_def(range_fixture *f, const pp_body_def *d)
{
    pp_body b = {0};
    return pp_body_create(f->w, d, &b);
}

static pp_joint_def range_joint_def(range_fixture *f)
{
    pp_joint_def d = pp_joint_def_default(PP_JOINT_REVOLUTE);
    d.body_b = f->b;
    d.anchor_a = v2(100, 100);
    return d;
}

static pp_status range_try_joint_def(range_fixture *f, const pp_joint_def *d)
{
    pp_joint j = {0};
    return pp_joint_create(f->w, d, &j);
}

/* A body drawn from an opaque 8 × 8 sprite, no mask: its alpha_threshold is checked. */
static pp_body_def range_body_def_sprite(range_fixture *f)
{
    pp_body_def d = range_body_def(f);
    d.mask = NULL;
    d.rgba = f->rgba;
    return d;
}

static pp_status range_try_body_def_sprite(range_fixture *f, const pp_body_def *d) { return range_try_body_def(f, d); }

/* A 1 × 1 body whose mask holds PP_MAX_BITMAP_SIDE solid bytes: a width or a height up to the limit, the other 1,
 * reads within it. */
static pp_body_def range_body_def_strip(range_fixture *f)
{
    pp_body_def d = range_body_def(f);
    d.width = d.height = 1;
    d.mask = f->strip;
    return d;
}

static pp_status range_try_body_def_strip(range_fixture *f, const pp_body_def *d) { return range_try_body_def(f, d); }

/* A prismatic joint holding b to the world along x. */
static pp_joint_def range_prismatic_def(range_fixture *f)
{
    pp_joint_def d = pp_joint_def_default(PP_JOINT_PRISMATIC);
    d.body_b = f->b;
    d.anchor_a = d.anchor_b = v2(100, 100);
    return d;
}

static pp_status range_try_prismatic_def(range_fixture *f, const pp_joint_def *d) { return range_try_joint_def(f, d); }

/* A rope from the world point (100, 50) to b's centre. */
static pp_joint_def range_distance_def(range_fixture *f)
{
    pp_joint_def d = pp_joint_def_default(PP_JOINT_DISTANCE);
    d.body_b = f->b;
    d.anchor_a = v2(100, 50);
    d.anchor_b = v2(100, 100);
    return d;
}

static pp_status range_try_distance_def(range_fixture *f, const pp_joint_def *d) { return range_try_joint_def(f, d); }

static pp_camera range_camera(range_fixture *f)
{
    pp_camera c;
    PP_OK_OR_FAIL(pp_world_get_camera(f->w, &c));
    return c;
}

static pp_status range_try_camera(range_fixture *f, const pp_camera *c) { return pp_world_set_camera(f->w, c); }

static pp_timed_edit range_timed_edit(range_fixture *f)
{
    (void)f;
    return (pp_timed_edit){.time = 1, .type = PP_EDIT_ERASE_CIRCLE, .center = {0, 0}, .radius = 1};
}

static pp_status range_try_timed_edit(range_fixture *f, const pp_timed_edit *e)
{
    return pp_world_schedule_edit(f->w, e);
}

/* A blast beside b: its left face is 12 px from the centre, within the radius. */
static pp_explosion_def range_explosion_def(range_fixture *f)
{
    (void)f;
    pp_explosion_def d = pp_explosion_def_default();
    d.position = v2(80, 100);
    d.radius = 16;
    d.falloff = 8;
    return d;
}

static pp_status range_try_explosion_def(range_fixture *f, const pp_explosion_def *d)
{
    return pp_world_explode(f->w, d, NULL);
}

#include "ranges_gen.h"

/* The C name of a case's argument: "pp_body_def.pivot.x" -> "pivot". */
static const char *arg_name(const char *arg, char name[64])
{
    snprintf(name, 64, "%s", strchr(arg, '.') + 1);
    char *component = strchr(name, '.');
    if (component)
        *component = 0;
    return name;
}

static void fixture_make(range_fixture *f, int kind)
{
    memset(f, 0, sizeof *f);
    memset(f->mask, 1, sizeof f->mask);
    memset(f->rgba, 255, sizeof f->rgba);
    if (kind == RANGE_BODY_DEF_STRIP)
        memset(f->strip, 1, sizeof f->strip);
    if (!range_plane[0])
        memset(range_plane, 1, sizeof range_plane);
    if (kind == RANGE_IMAGE) {
        snprintf(f->dir, sizeof f->dir, "/tmp/pp_ranges_XXXXXX");
        cr_assert_not_null(mkdtemp(f->dir));
        snprintf(f->path, sizeof f->path, "%s/range.png", f->dir);
        PP_OK_OR_FAIL(pp_image_save(f->path, range_plane, 2, 2));
    }
    f->w = make_world(0, 980);
    f->b = add_rect(f->w, body_def(PP_BODY_DYNAMIC, 100, 100, 0), 16, 16);
    f->other = add_rect(f->w, body_def(PP_BODY_STATIC, 300, 100, 0), 16, 16);
    if (kind == RANGE_MOTOR) {
        pp_joint_def d = pp_joint_def_default(PP_JOINT_MOTOR);
        d.body_b = f->b;
        PP_OK_OR_FAIL(pp_joint_create(f->w, &d, &f->j));
    }
    if (kind == RANGE_REVOLUTE || kind == RANGE_MOUSE || kind == RANGE_PRISMATIC) {
        pp_joint_def d = kind == RANGE_MOUSE       ? pp_joint_def_default(PP_JOINT_MOUSE)
                         : kind == RANGE_PRISMATIC ? range_prismatic_def(f)
                                                   : pp_joint_def_default(PP_JOINT_REVOLUTE);
        d.body_b = f->b;
        d.anchor_a = v2(100, 100);
        PP_OK_OR_FAIL(pp_joint_create(f->w, &d, &f->j));
    }
}

Test(ranges, every_boundary_value_of_every_ranged_argument_gets_the_status_its_range_gives)
{
    const int n = (int)(sizeof range_cases / sizeof *range_cases);
    int wrong = 0, unnamed = 0;
    char name[64];
    for (int i = 0; i < n; i++) {
        const range_case *c = &range_cases[i];
        range_fixture f;
        fixture_make(&f, c->fixture);
        const pp_status st = range_feed(&f, c->target, c->value);
        if (st != c->want) {
            cr_log_error("%s = %a (%g): %s, want %s (%s)", c->arg, c->value, c->value, pp_status_name(st),
                         pp_status_name(c->want), pp_last_error());
            wrong++;
        } else if (st == PP_ERR_INVALID_ARGUMENT && !strstr(pp_last_error(), arg_name(c->arg, name))) {
            cr_log_error("%s = %g: the message does not name %s: %s", c->arg, c->value, name, pp_last_error());
            unnamed++;
        }
        PP_OK_OR_FAIL(pp_world_destroy(f.w));
        if (f.dir[0]) {
            remove(f.path);
            cr_assert_eq(rmdir(f.dir), 0, "%s: the image fixture's folder is left", c->arg);
        }
    }
    cr_assert_eq(unnamed, 0, "%d refusals do not name their argument (see the log)", unnamed);
    cr_assert_eq(wrong, 0, "%d of %d boundary cases got another status (see the log)", wrong, n);
    cr_assert_gt(n, 1000, "the generated table has only %d cases", n);
}
