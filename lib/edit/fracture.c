/* Splitting a body after an edit: its solid pixels are grouped into 8-connected islands (pixels
 * touching at a corner hold together); the largest island keeps the body and its handle, each other
 * island becomes a new body moving as its material did (v + ω × r), with the parent's material and
 * filter. A static body's islands fall as dynamic bodies when its def asked for detach_islands. */
#include "alloc.h"
#include "awake.h"
#include "edit.h"
#include "forces.h"
#include "status.h"

#include <stdlib.h>
#include <string.h>

typedef struct island {
    int64_t pixels;
    int32_t x0, y0, x1, y1; /* bounds, bitmap coordinates */
} island;

/* Label the islands of the solid bounds (labels 1..n, 0 empty); returns n, or −1 without memory. */
static int32_t label_islands(const pp_raster *r, int32_t *label, int32_t *stack, island **out)
{
    const int32_t bw = r->x1 - r->x0, bh = r->y1 - r->y0;
    island *isl = NULL;
    int32_t n = 0, cap = 0;
    for (int32_t j = 0; j < bh; j++)
        for (int32_t i = 0; i < bw; i++) {
            if (label[(int64_t)j * bw + i] || !raster_solid(r, r->x0 + i, r->y0 + j))
                continue;
            if (!ARRAY_RESERVE(isl, cap, n + 1)) {
                pp_free(isl);
                return -1;
            }
            island *k = &isl[n++];
            *k = (island){0, i, j, i + 1, j + 1};
            int64_t top = 0;
            stack[top++] = (int32_t)((int64_t)j * bw + i);
            label[(int64_t)j * bw + i] = n;
            while (top > 0) { /* depth-first flood fill; each pixel is pushed once */
                const int32_t p = stack[--top], pi = p % bw, pj = p / bw;
                k->pixels++;
                k->x0 = pi < k->x0 ? pi : k->x0, k->x1 = pi >= k->x1 ? pi + 1 : k->x1;
                k->y0 = pj < k->y0 ? pj : k->y0, k->y1 = pj >= k->y1 ? pj + 1 : k->y1;
                for (int dj = -1; dj <= 1; dj++)
                    for (int di = -1; di <= 1; di++) {
                        const int32_t qi = pi + di, qj = pj + dj;
                        if (qi < 0 || qj < 0 || qi >= bw || qj >= bh)
                            continue;
                        const int64_t q = (int64_t)qj * bw + qi;
                        if (!label[q] && raster_solid(r, r->x0 + qi, r->y0 + qj)) {
                            label[q] = n;
                            stack[top++] = (int32_t)q;
                        }
                    }
            }
        }
    for (int32_t k = 0; k < n; k++) { /* to bitmap coordinates */
        isl[k].x0 += r->x0, isl[k].x1 += r->x0;
        isl[k].y0 += r->y0, isl[k].y1 += r->y0;
    }
    *out = isl;
    return n;
}

/* Island k as a new body at rest, posed where it lies in the parent; it moves once the split is committed. */
static pp_status make_child(world *wd, body *parent, const island *k, const uint8_t *mask, const uint8_t *weights,
                            const uint8_t *sprite, const char *fn, pp_body *out)
{
    const int32_t w = k->x1 - k->x0, h = k->y1 - k->y0;
    pp_body_def d = pp_body_def_default();
    d.type = parent->type == PP_BODY_STATIC ? PP_BODY_DYNAMIC : parent->type;
    const dvec2 centre = dv(k->x0 + 0.5 * w, k->y0 + 0.5 * h); /* the child's pivot, in the parent's bitmap */
    const dvec2 pos = dv_add(parent->pos, dv_rot(dv_sub(centre, parent->pivot), parent->cos_a, parent->sin_a));
    d.position = (pp_vec2){(float)pos.x, (float)pos.y};
    d.angle = (float)parent->angle;
    d.width = w, d.height = h, d.mask = mask, d.weights = weights, d.rgba = sprite;
    d.density = (float)parent->density, d.friction = (float)parent->friction;
    d.restitution = (float)parent->restitution;
    d.linear_damping = (float)parent->linear_damping, d.angular_damping = (float)parent->angular_damping;
    d.category_bits = parent->category_bits, d.mask_bits = parent->mask_bits;
    d.fixed_rotation = parent->fixed_rotation, d.detach_islands = parent->detach_islands;
    d.bullet = parent->bullet, d.is_sensor = parent->is_sensor, d.one_way = parent->one_way;
    d.one_way_direction = (pp_vec2){(float)parent->one_way_dir.x, (float)parent->one_way_dir.y};
    d.user_data = parent->user_data;
    body *child = NULL;
    pp_status st = body_make(wd, &d, BODY_ANY_SLOT, fn, &child);
    if (st)
        return st;
    *out = child->handle;
    /* The float position may sit a hair off; the pose is exact in double. */
    child->pos = pos;
    child->angle = parent->angle, child->cos_a = parent->cos_a, child->sin_a = parent->sin_a;
    body_update_pose_cache(child);
    if (child->type != PP_BODY_DYNAMIC || parent->gravity_scale == 1)
        return PP_OK;
    child->gravity_scale = parent->gravity_scale; /* a piece falls as its parent did */
    return forces_list(wd, child, fn); /* on failure the plan's cancel unmakes the child */
}

/* The child moves as the parent's material where it lies: v + ω × r. */
static void set_child_motion(world *wd, const body *parent, body *child)
{
    if (!child->sb.body)
        return;
    dvec2 v = dv(0, 0);
    double omega = 0;
    if (parent->sb.body) {
        solver_body_state s;
        solver_body_get_state(wd->solver, &parent->sb, &s);
        const dvec2 r = dv_sub(body_com_world(child), s.com_world);
        v = dv_add(s.velocity, dv(-s.angular_velocity * r.y, s.angular_velocity * r.x));
        omega = s.angular_velocity;
    }
    solver_body_set_pose(wd->solver, &child->sb, body_com_world(child), child->angle);
    solver_body_set_velocity(wd->solver, &child->sb, v, child->fixed_rotation ? 0.0 : omega);
}

/* Island k's pixels in bitmaps of its own bounds; false without memory. */
static bool island_bitmaps(const body *bd, const fracture_plan *p, int32_t k, uint8_t **mask, uint8_t **weights,
                           uint8_t **sprite)
{
    const pp_raster *r = &bd->raster;
    const island *is = &p->islands[k];
    const int32_t w = is->x1 - is->x0, h = is->y1 - is->y0;
    *mask = pp_calloc((size_t)w * h, 1);
    *weights = r->weights ? pp_calloc((size_t)w * h, 1) : NULL;
    *sprite = bd->sprite ? pp_calloc((size_t)w * h, 4) : NULL;
    if (!*mask || (r->weights && !*weights) || (bd->sprite && !*sprite))
        return false;
    for (int32_t y = is->y0; y < is->y1; y++)
        for (int32_t x = is->x0; x < is->x1; x++) {
            if (p->label[(int64_t)(y - p->by) * p->bw + (x - p->bx)] != k + 1)
                continue;
            const int64_t c = (int64_t)(y - is->y0) * w + (x - is->x0);
            (*mask)[c] = 1;
            if (*weights)
                (*weights)[c] = (uint8_t)raster_weight(r, x, y);
            if (*sprite)
                memcpy(*sprite + 4 * c, bd->sprite + 4 * ((int64_t)y * r->width + x), 4);
        }
    return true;
}

pp_status fracture_prepare(world *wd, body *bd, fracture_plan *p, const char *fn, int32_t *events)
{
    const pp_raster *r = &bd->raster;
    *p = (fracture_plan){.bx = r->x0, .by = r->y0, .bw = r->x1 - r->x0, .bh = r->y1 - r->y0};
    const int64_t area = (int64_t)(r->x1 - r->x0) * (r->y1 - r->y0);
    p->label = pp_calloc((size_t)area, sizeof *p->label);
    int32_t *stack = pp_malloc((size_t)area * sizeof *stack);
    p->count = p->label && stack ? label_islands(r, p->label, stack, &p->islands) : -1;
    pp_free(stack);
    if (p->count < 0) {
        p->count = 0;
        fracture_cancel(wd, p);
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory to find the islands of a %lld-pixel body", fn, (long long)area);
    }
    if (p->count < 2)
        return PP_OK;
    for (int32_t k = 1; k < p->count; k++) /* the largest island stays; the first found on a tie */
        p->keep = p->islands[k].pixels > p->islands[p->keep].pixels ? k : p->keep;
    if (!(p->children = pp_calloc((size_t)p->count, sizeof *p->children))) {
        fracture_cancel(wd, p);
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory to split a body into %d", fn, (int)p->count);
    }
    pp_status st = PP_OK;
    for (int32_t k = 0; k < p->count && !st; k++) {
        if (k == p->keep)
            continue;
        uint8_t *mask, *weights, *sprite;
        if (!island_bitmaps(bd, p, k, &mask, &weights, &sprite))
            st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for a %d × %d island", fn,
                         (int)(p->islands[k].x1 - p->islands[k].x0), (int)(p->islands[k].y1 - p->islands[k].y0));
        else if ((st = make_child(wd, bd, &p->islands[k], mask, weights, sprite, fn, &p->children[k])) == PP_ERR_INVALID_ARGUMENT)
            st = PP_OK; /* a massless island (all weights zero) is dust: it just goes */
        else if (st == PP_OK)
            ++*events;
        pp_free(mask);
        pp_free(weights);
        pp_free(sprite);
    }
    if (st == PP_OK) /* and one for the parent, which goes if the island it keeps is massless */
        st = world_reserve_events(wd, ++*events, fn);
    if (st)
        fracture_cancel(wd, p);
    return st;
}

void fracture_commit(world *wd, body *bd, fracture_plan *p)
{
    if (p->count >= 2) {
        /* Move every other island's pixels out of the parent; the children have them already. */
        pp_raster *r = &bd->raster;
        edit_span e = {0};
        for (int32_t j = 0; j < p->bh; j++)
            for (int32_t i = 0; i < p->bw; i++) {
                const int32_t l = p->label[(int64_t)j * p->bw + i];
                if (l && l != p->keep + 1)
                    edit_pixel(bd, &e, p->bx + i, p->by + j, false, 0);
            }
        for (int32_t k = 0; k < p->count; k++)
            if (p->children[k].id) {
                set_child_motion(wd, bd, body_of(wd, p->children[k]));
                world_queue_event(wd, (pp_event){.type = PP_EVENT_BODY_SPLIT, .body = bd->handle,
                                                 .other = p->children[k]}); /* room reserved */
            }
        raster_edit_done(r, e.y0, e.y1);
        if (bd->type == PP_BODY_DYNAMIC && bd->sums.w <= 0) {
            /* The largest island, which the parent keeps, can be massless (all weights zero): it goes, as a
             * body an edit leaves without mass does; ODE aborts on a zero mass (found by fuzz_api). */
            const pp_body gone = bd->handle;
            body_remove(wd, bd);
            world_queue_event(wd, (pp_event){.type = PP_EVENT_BODY_DESTROYED, .body = gone}); /* room reserved */
        } else {
            body_update_pose_cache(bd);
            awake_moved(wd, bd); /* new bounds, even for a static body */
            if (bd->sb.body)
                edit_update_solver_body(wd, bd);
        }
    }
    p->count = 0; /* the children stay */
    fracture_cancel(wd, p);
}

bool fracture_island_at(const fracture_plan *p, int32_t x, int32_t y, int32_t *k, dvec2 *origin)
{
    if (p->count < 2 || x < p->bx || y < p->by || x >= p->bx + p->bw || y >= p->by + p->bh)
        return false;
    const int32_t l = p->label[(int64_t)(y - p->by) * p->bw + (x - p->bx)];
    if (l == 0)
        return false;
    *k = l - 1;
    *origin = dv(p->islands[l - 1].x0, p->islands[l - 1].y0);
    return true;
}

void fracture_cancel(world *wd, fracture_plan *p)
{
    for (int32_t k = p->count - 1; k >= 0; k--) /* newest first, so slots and serials come back in order */
        if (p->children && p->children[k].id)
            body_unmake(wd, body_of(wd, p->children[k]));
    pp_free(p->children);
    pp_free(p->label);
    pp_free(p->islands);
    *p = (fracture_plan){0};
}
