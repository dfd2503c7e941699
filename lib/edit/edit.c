/* Editing pixels at any moment: erase, paint, write, read, and the world's erase. Mass sums
 * and bounds follow from the changed pixels alone; the pose (pivot) does not move, the ODE body
 * moves to the new centre of mass with the velocity its material already had; the GPU mirror
 * rewrites only the dirty rows; bodies nearby wake; a body cut apart splits (fracture.c). */
#include "alloc.h"
#include "awake.h"
#include "cover.h"
#include "edit.h"
#include "joint.h"
#include "status.h"

#include <stdlib.h>

void edit_pixel(body *bd, edit_span *e, int32_t x, int32_t y, bool solid, uint32_t weight)
{
    pp_raster *r = &bd->raster;
    const bool was = raster_solid(r, x, y);
    const uint32_t old = raster_weight(r, x, y);
    if (!r->weights)
        weight = 255; /* no plane: every pixel weighs 255 (callers add one before other weights) */
    if (was == solid && (!solid || old == weight))
        return;
    if (was)
        mass_sums_pixel(&bd->sums, r->width, r->height, x, y, old, -1);
    if (solid)
        mass_sums_pixel(&bd->sums, r->width, r->height, x, y, weight, +1);
    raster_write(r, x, y, solid, weight);
    e->removed |= was && !solid;
    const bool first = e->changed++ == 0;
    if (first || x < e->x0) e->x0 = x;
    if (first || x >= e->x1) e->x1 = x + 1;
    if (first || y < e->y0) e->y0 = y;
    if (first || y >= e->y1) e->y1 = y + 1;
}

void edit_update_solver_body(world *wd, body *bd)
{
    solver_body_state s;
    solver_body_get_state(wd->solver, &bd->sb, &s);
    bd->mass = mass_from_sums(&bd->sums, bd->raster.width, bd->raster.height, bd->density);
    body_update_com(bd);
    const dvec2 com = body_com_world(bd), r = dv_sub(com, s.com_world);
    const dvec2 v = dv_add(s.velocity, dv(-s.angular_velocity * r.y, s.angular_velocity * r.x));
    solver_body_set_mass(wd->solver, &bd->sb, bd->mass.mass, bd->mass.inertia);
    solver_body_set_pose(wd->solver, &bd->sb, com, bd->angle);
    solver_body_set_velocity(wd->solver, &bd->sb, v, s.angular_velocity);
    awake_wake(wd, bd);
    joint_body_changed(wd, bd);
}

/* Bodies whose box comes within this many pixels of an edited pixel wake: one resting on the edited
 * pixels overlaps them already; the margin catches one just touching them, after rounding. */
#define EDIT_WAKE_MARGIN 2.0

/* The world box of the edited pixels, grown by the margin. */
static pp_aabb edited_region(const body *bd, const edit_span *e)
{
    pp_aabb box = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 4; k++) {
        const dvec2 l = dv((k & 1 ? e->x1 + EDIT_WAKE_MARGIN : e->x0 - EDIT_WAKE_MARGIN) - bd->pivot.x,
                           (k & 2 ? e->y1 + EDIT_WAKE_MARGIN : e->y0 - EDIT_WAKE_MARGIN) - bd->pivot.y);
        const dvec2 w = dv_add(bd->pos, dv_rot(l, bd->cos_a, bd->sin_a));
        box.x0 = fmin(box.x0, w.x), box.y0 = fmin(box.y0, w.y);
        box.x1 = fmax(box.x1, w.x), box.y1 = fmax(box.y1, w.y);
    }
    return box;
}

/* Wake every body that may rest on, or now overlap, the edited pixels. Only those: a crater deep
 * in a large terrain leaves the bodies sleeping on its surface asleep. */
static void wake_around(world *wd, pp_aabb region) { awake_wake_in_box(wd, region); }

/* A body's part of one edit call. Everything that can fail (room for events, the split's new bodies)
 * happens between the pixel writes and the commit, and a failure puts the pixels back: an edit call
 * is made whole or not at all. */
typedef struct edit_job {
    body *bd;
    edit_span e;
    int32_t x0, y0, x1, y1; /* the rectangle saved before the writes, bitmap px */
    uint8_t *saved;         /* its pixels then: solid, and the weight after them where the body has a plane */
    pp_mass_sums sums;      /* the mass sums then */
    fracture_plan plan;
    const char *fn;         /* the call the user made, for messages */
} edit_job;

/* Can removing pixels split this body? */
static bool may_split(const body *bd)
{
    return bd->type == PP_BODY_DYNAMIC || (bd->type == PP_BODY_STATIC && bd->detach_islands);
}

/* Before writing [x0, x1) × [y0, y1) (clipped here): room for a destroyed event, and, if the writes may remove
 * pixels, the pixels to put back should the edit fail after them: the body's split, or, with `others` (an erase of
 * every body), a later body's job (a static terrain's crater is taken back as a crate's failed split is). */
static pp_status job_begin(world *wd, body *bd, int64_t x0, int64_t y0, int64_t x1, int64_t y1, bool removes,
                           bool others, const char *fn, edit_job *j, int32_t *events)
{
    const pp_raster *r = &bd->raster;
    *j = (edit_job){.bd = bd, .sums = bd->sums, .fn = fn};
    *events += 1 + (removes ? bd->joint_count : 0); /* destroyed, and each joint an anchor's pixels may break */
    pp_status st = world_reserve_events(wd, *events, fn);
    if (st || !removes || !(others || may_split(bd)))
        return st;
    j->x0 = (int32_t)(x0 > 0 ? x0 : 0), j->y0 = (int32_t)(y0 > 0 ? y0 : 0);
    j->x1 = (int32_t)(x1 < r->width ? x1 : r->width), j->y1 = (int32_t)(y1 < r->height ? y1 : r->height);
    if (j->x0 >= j->x1 || j->y0 >= j->y1)
        return PP_OK;
    const int64_t n = (int64_t)(j->x1 - j->x0) * (j->y1 - j->y0);
    if (!(j->saved = pp_malloc((size_t)n * (r->weights ? 2 : 1))))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory to save %lld pixels before an edit", fn, (long long)n);
    int64_t k = 0;
    for (int32_t y = j->y0; y < j->y1; y++)
        for (int32_t x = j->x0; x < j->x1; x++, k++) {
            j->saved[k] = raster_solid(r, x, y);
            if (r->weights)
                j->saved[n + k] = (uint8_t)raster_weight(r, x, y);
        }
    return PP_OK;
}

/* Nothing left to simulate: no pixels, or a dynamic body without mass. */
static bool job_destroys(const edit_job *j)
{
    return j->bd->raster.solid_count == 0 || (j->bd->type == PP_BODY_DYNAMIC && j->bd->sums.w <= 0);
}

/* Put the pixels back as job_begin saw them; bounds only grew meanwhile, so they are right again. */
static void job_cancel(world *wd, edit_job *j)
{
    fracture_cancel(wd, &j->plan);
    pp_raster *r = &j->bd->raster;
    const int64_t n = (int64_t)(j->x1 - j->x0) * (j->y1 - j->y0);
    int64_t k = 0;
    for (int32_t y = j->y0; j->saved && y < j->y1; y++)
        for (int32_t x = j->x0; x < j->x1; x++, k++)
            raster_write(r, x, y, j->saved[k] != 0, r->weights ? j->saved[n + k] : 255u);
    j->bd->sums = j->sums;
    pp_free(j->saved);
    j->saved = NULL;
}

/* After the writes: a body that came apart gets its pieces made, or the writes are taken back. */
static pp_status job_prepare(world *wd, edit_job *j, int32_t *events)
{
    if (j->e.changed == 0 || !j->e.removed || !may_split(j->bd) || job_destroys(j))
        return PP_OK;
    pp_status st = fracture_prepare(wd, j->bd, &j->plan, j->fn, events);
    if (st)
        job_cancel(wd, j);
    return st;
}

/* Bring the body up to date; it may be destroyed or split here. Cannot fail. The bodies around the edited
 * pixels are woken here, or, where *woken is not NULL, that region is added to it for the caller to wake once. */
static void job_commit(world *wd, edit_job *j, pp_aabb *woken)
{
    body *bd = j->bd;
    const edit_span *e = &j->e;
    pp_free(j->saved);
    if (e->changed == 0)
        return;
    raster_edit_done(&bd->raster, e->y0, e->y1);
    const pp_aabb region = edited_region(bd, e);
    /* Held contacts near the edit are the old pixels'. A static body's centre of mass does not move with its
     * pixels, and unless it splits they change only in the region; a movable body's moves, and so do the
     * carried points measured from it. */
    if (!bd->sb.body && j->plan.count <= 1)
        carry_forget_near(wd, bd->index, region);
    else
        carry_forget(wd, bd->index);
    body_update_pose_cache(bd);
    awake_moved(wd, bd); /* new bounds, even for a static body */
    if (woken)
        *woken = (pp_aabb){fmin(woken->x0, region.x0), fmin(woken->y0, region.y0), fmax(woken->x1, region.x1),
                           fmax(woken->y1, region.y1)};
    else
        wake_around(wd, region);
    if (e->removed && bd->joint_count > 0)
        joint_edit_done(wd, bd, &j->plan);
    if (job_destroys(j)) {
        const pp_body gone = bd->handle;
        body_remove(wd, bd);
        world_queue_event(wd, (pp_event){.type = PP_EVENT_BODY_DESTROYED, .body = gone}); /* room reserved */
        return;
    }
    if (bd->sb.body)
        edit_update_solver_body(wd, bd);
    fracture_commit(wd, bd, &j->plan);
}

static pp_status check_circle(const char *fn, pp_vec2 c, float radius)
{
    if (!finite2(c.x, c.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: world_center must be finite", fn);
    if (!(radius >= 0) || !isfinite(radius))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: radius must be finite and ≥ 0, got %g", fn, radius);
    return PP_OK;
}

/* Set every pixel of [x0, x1) × [y0, y1) whose centre is within r of the body-local point c (cover.h). */
static void circle_write(body *bd, edit_span *e, dvec2 c, double r, int32_t x0, int32_t y0, int32_t x1, int32_t y1,
                         bool solid, uint32_t weight)
{
    /* Clamped on both sides: a circle far off the bitmap gives bounds past int32 (UBSan, found by fuzz_api). */
    const double top = fmin(fmax(y0, floor(c.y - r)), y1), bottom = fmax(fmin(y1, ceil(c.y + r)), y0);
    for (int32_t y = (int32_t)top; y < (int32_t)bottom; y++) {
        double a, b;
        if (!circle_row_span(c, r, y, &a, &b))
            continue;
        const int32_t xa = (int32_t)fmin(fmax(x0, a), x1), xb = (int32_t)fmax(fmin(x1 - 1, b), x0 - 1);
        for (int32_t x = xa; x <= xb; x++)
            edit_pixel(bd, e, x, y, solid, weight);
    }
}

static dvec2 world_to_local(const body *bd, pp_vec2 p) { return body_world_to_local(bd, dv(p.x, p.y)); }

/* Erase a circle from one body, up to the commit. */
static pp_status erase_circle(world *wd, body *bd, pp_vec2 center, float radius, bool others, const char *fn,
                              edit_job *j, int32_t *events)
{
    const pp_raster *r = &bd->raster;
    const dvec2 c = world_to_local(bd, center);
    /* The pixels circle_write may touch, with a pixel to spare, within the solid bounds. */
    const double x0 = fmax(r->x0, floor(c.x - radius) - 1), y0 = fmax(r->y0, floor(c.y - radius) - 1);
    const double x1 = fmin(r->x1, ceil(c.x + radius) + 1), y1 = fmin(r->y1, ceil(c.y + radius) + 1);
    const bool touches = !raster_empty(r) && x0 < x1 && y0 < y1;
    pp_status st = job_begin(wd, bd, touches ? (int64_t)x0 : 0, touches ? (int64_t)y0 : 0, touches ? (int64_t)x1 : 0,
                             touches ? (int64_t)y1 : 0, touches, others, fn, j, events);
    if (st)
        return st;
    if (touches)
        circle_write(bd, &j->e, c, radius, r->x0, r->y0, r->x1, r->y1, false, 0);
    return job_prepare(wd, j, events);
}

PP_API pp_status pp_body_erase_circle(pp_world w, pp_body b, pp_vec2 world_center, float radius, int32_t *changed)
{
    static const char *fn = "pp_body_erase_circle";
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, fn, &wd, &bd);
    return st ? st : edit_erase_circle(wd, bd, world_center, radius, fn, changed);
}

PP_API pp_status pp_world_erase_circle(pp_world w, pp_vec2 world_center, float radius, int32_t *changed)
{
    static const char *fn = "pp_world_erase_circle";
    world *wd = world_lookup(w, fn);
    return wd ? edit_erase_circle(wd, NULL, world_center, radius, fn, changed) : PP_ERR_INVALID_HANDLE;
}

PP_API pp_status pp_body_paint_circle(pp_world w, pp_body b, pp_vec2 world_center, float radius, uint8_t weight,
                                      int32_t *changed)
{
    static const char *fn = "pp_body_paint_circle";
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, fn, &wd, &bd);
    return st ? st : edit_paint_circle(wd, bd, world_center, radius, weight, fn, changed);
}

/* Erase from every body the blast's box meets whose category_bits meet mask_bits: every body's writes and pieces
 * first, in slot order, then every commit, so a failure takes them all back. Pieces made on the way are not on the
 * list. */
static pp_status erase_everywhere(world *wd, pp_vec2 world_center, float radius, uint32_t mask_bits, const char *fn,
                                  int32_t *changed, edit_before_commit before_commit, void *user)
{
    const pp_aabb blast = {world_center.x - radius, world_center.y - radius, world_center.x + radius,
                           world_center.y + radius};
    int32_t *hit = NULL, n_hit = 0;
    pp_status st = awake_bodies_in_box(wd, fn, blast, &hit, &n_hit);
    if (st)
        return st;
    edit_job *jobs = n_hit > 0 ? pp_malloc((size_t)n_hit * sizeof *jobs) : NULL;
    if (n_hit > 0 && !jobs) {
        pp_free(hit);
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d bodies", fn, (int)n_hit);
    }
    int32_t n = 0, events = 0;
    const bool others = n_hit > 1 || before_commit; /* something may fail after a job: it must be taken back */
    for (int32_t k = 0; k < n_hit && !st; k++)
        if ((wd->bodies[hit[k]]->category_bits & mask_bits) &&
            (st = erase_circle(wd, wd->bodies[hit[k]], world_center, radius, others, fn, &jobs[n], &events)) == PP_OK)
            n++;
    pp_free(hit);
    if (!st && before_commit)
        st = before_commit(wd, user);
    if (st) {
        while (n > 0)
            job_cancel(wd, &jobs[--n]);
        pp_free(jobs);
        return st;
    }
    /* One wake over every body's edited region, not one a body: each wake visits the changed list, which every
     * edited body has joined (65,536 one-pixel bodies erased at once took seconds). */
    int32_t erased = 0;
    pp_aabb woken = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (int32_t k = 0; k < n; k++) {
        erased += jobs[k].e.changed;
        job_commit(wd, &jobs[k], &woken);
    }
    if (woken.x0 <= woken.x1)
        wake_around(wd, woken);
    pp_free(jobs);
    if (changed)
        *changed = erased;
    return PP_OK;
}

pp_status edit_erase_circle(world *wd, body *bd, pp_vec2 world_center, float radius, const char *fn, int32_t *changed)
{
    pp_status st = check_circle(fn, world_center, radius);
    if (st || !bd)
        return st ? st : erase_everywhere(wd, world_center, radius, ~0u, fn, changed, NULL, NULL);
    edit_job j;
    int32_t events = 0;
    if ((st = erase_circle(wd, bd, world_center, radius, false, fn, &j, &events)))
        return st;
    if (changed)
        *changed = j.e.changed;
    job_commit(wd, &j, NULL);
    return PP_OK;
}

pp_status edit_erase_world(world *wd, pp_vec2 world_center, float radius, uint32_t mask_bits, const char *fn,
                           int32_t *changed, edit_before_commit before_commit, void *user)
{
    pp_status st = check_circle(fn, world_center, radius);
    return st ? st : erase_everywhere(wd, world_center, radius, mask_bits, fn, changed, before_commit, user);
}

pp_status edit_paint_circle(world *wd, body *bd, pp_vec2 world_center, float radius, uint8_t weight, const char *fn,
                            int32_t *changed)
{
    pp_status st = check_circle(fn, world_center, radius);
    if (st)
        return st;
    if (weight == 0)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: weight must be 1..255 (0 would paint massless pixels)", fn);
    if (weight != 255 && (st = raster_ensure_weights(fn, &bd->raster)))
        return st;
    edit_job j;
    int32_t events = 0;
    if ((st = job_begin(wd, bd, 0, 0, 0, 0, false, false, fn, &j, &events)))
        return st;
    circle_write(bd, &j.e, world_to_local(bd, world_center), radius, 0, 0, bd->raster.width, bd->raster.height, true,
                 weight);
    if (changed)
        *changed = j.e.changed;
    job_commit(wd, &j, NULL);
    return PP_OK;
}

PP_API pp_status pp_body_write_pixels(pp_world w, pp_body b, int32_t x, int32_t y, int32_t width, int32_t height,
                                      const uint8_t *mask, const uint8_t *weights)
{
    static const char *fn = "pp_body_write_pixels";
    world *wd;
    pp_status st;
    body *bd = body_lookup_out(w, b, fn, mask, "mask", &wd, &st);
    if (!bd)
        return st;
    if (width <= 0 || height <= 0)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: width and height must be > 0, got %d × %d", fn, (int)width,
                       (int)height);
    const pp_raster *r = &bd->raster;
    /* Clip to the bitmap; a rectangle wholly outside is a mistake, not an empty edit. */
    const int64_t cx0 = x > 0 ? x : 0, cy0 = y > 0 ? y : 0;
    const int64_t cx1 = (int64_t)x + width < r->width ? (int64_t)x + width : r->width;
    const int64_t cy1 = (int64_t)y + height < r->height ? (int64_t)y + height : r->height;
    if (cx0 >= cx1 || cy0 >= cy1)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: the %d × %d rectangle at (%d, %d) is outside the %d × %d bitmap", fn,
                       (int)width, (int)height, (int)x, (int)y, (int)r->width, (int)r->height);
    if (weights && (st = raster_ensure_weights(fn, &bd->raster)))
        return st;
    edit_job j;
    int32_t events = 0;
    if ((st = job_begin(wd, bd, cx0, cy0, cx1, cy1, true, false, fn, &j, &events)))
        return st;
    for (int64_t py = cy0; py < cy1; py++)
        for (int64_t px = cx0; px < cx1; px++) {
            const int64_t k = (py - y) * width + (px - x);
            edit_pixel(bd, &j.e, (int32_t)px, (int32_t)py, mask[k] != 0, weights ? weights[k] : 255u);
        }
    if ((st = job_prepare(wd, &j, &events)))
        return st;
    job_commit(wd, &j, NULL);
    return PP_OK;
}

/* One byte a pixel into out, rows top to bottom: 1 where solid (the mask) or the solid pixels' weights. The plane
 * may keep a byte under an empty pixel; it weighs nothing, so it reads 0. */
static pp_status read_plane(pp_world w, pp_body b, uint8_t *out, int64_t capacity, bool weights, const char *fn)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, fn, &wd, &bd);
    if (st)
        return st;
    const pp_raster *r = &bd->raster;
    const int64_t need = (int64_t)r->width * r->height;
    if (!out || capacity < need)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: out must hold width × height = %lld bytes, got %scapacity %lld", fn,
                       (long long)need, out ? "" : "NULL with ", (long long)capacity);
    for (int32_t y = 0; y < r->height; y++)
        for (int32_t x = 0; x < r->width; x++) {
            const bool solid = raster_solid(r, x, y);
            out[(int64_t)y * r->width + x] = (uint8_t)(weights && solid ? raster_weight(r, x, y) : solid);
        }
    return PP_OK;
}

PP_API pp_status pp_body_read_mask(pp_world w, pp_body b, uint8_t *out, int64_t capacity)
{
    return read_plane(w, b, out, capacity, false, "pp_body_read_mask");
}

PP_API pp_status pp_body_read_weights(pp_world w, pp_body b, uint8_t *out, int64_t capacity)
{
    return read_plane(w, b, out, capacity, true, "pp_body_read_weights");
}

PP_API pp_status pp_body_get_size(pp_world w, pp_body b, int32_t *width, int32_t *height)
{
    world *wd;
    body *bd;
    pp_status st = world_body_lookup(w, b, "pp_body_get_size", &wd, &bd);
    if (st)
        return st;
    if (width)
        *width = bd->raster.width;
    if (height)
        *height = bd->raster.height;
    return PP_OK;
}
