/* Timed edits: a binary heap on (time, serial), so that scheduling and applying n edits cost n log n, in any
 * order; the step applies those due through the edit calls' own work (edit.c), under pp_world_step's name. */
#include "alloc.h"
#include "edit.h"
#include "status.h"
#include "timed_edits.h"
#include "world.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static bool edit_before(const timed_edit *a, const timed_edit *b)
{
    return a->edit.time < b->edit.time || (a->edit.time == b->edit.time && a->serial < b->serial);
}

static int edit_order(const void *a, const void *b)
{
    return edit_before(a, b) ? -1 : edit_before(b, a);
}

/* Add an edit into room already made. */
static void edits_push(timed_edits *q, const pp_timed_edit *e)
{
    timed_edit x = {*e, q->serial++};
    x.edit.reserved = 0;
    int32_t i = q->count++;
    /* Into an empty heap, or past every edit of a sorted one, it leaves the heap sorted. */
    q->in_order = i == 0 || (q->in_order && !edit_before(&x, &q->heap[i - 1]));
    for (; i > 0 && edit_before(&x, &q->heap[(i - 1) / 2]); i = (i - 1) / 2)
        q->heap[i] = q->heap[(i - 1) / 2];
    q->heap[i] = x;
}

/* Remove the next edit to apply, edits[0]. */
static void edits_pop(timed_edits *q)
{
    const int32_t n = --q->count;
    const timed_edit x = q->heap[n];
    int32_t i = 0;
    for (int32_t c; (c = 2 * i + 1) < n; i = c) {
        if (c + 1 < n && edit_before(&q->heap[c + 1], &q->heap[c]))
            c++;
        if (!edit_before(&q->heap[c], &x))
            break;
        q->heap[i] = q->heap[c];
    }
    q->heap[i] = x;
    q->in_order = n <= 1;
}

/* Sort the heap in place, which leaves it a heap; keys are unique, so the order is the same every run. */
static void edits_sort(timed_edits *q)
{
    if (!q->in_order)
        qsort(q->heap, (size_t)q->count, sizeof *q->heap, edit_order);
    q->in_order = true;
}

timed_edit *timed_edits_in_order(const timed_edits *q)
{
    timed_edit *copy = pp_malloc(((size_t)q->count + 1) * sizeof *copy);
    if (copy && q->count > 0) {
        memcpy(copy, q->heap, (size_t)q->count * sizeof *copy);
        if (!q->in_order)
            qsort(copy, (size_t)q->count, sizeof *copy, edit_order);
    }
    return copy;
}

pp_status timed_edits_apply_due(world *wd, float dt)
{
    timed_edits *q = &wd->edits;
    while (q->count > 0 && q->heap[0].edit.time < wd->time + 0.5 * dt) {
        const pp_timed_edit e = q->heap[0].edit;
        body *bd = e.body.id ? body_find(wd, e.body) : NULL;
        pp_status st = PP_OK;
        if (e.body.id && !bd)
            pp_log(1, "physpix: a timed edit at t = %g s skipped: its body is gone", e.time);
        else if (e.type == PP_EDIT_PAINT_CIRCLE)
            st = edit_paint_circle(wd, bd, e.center, e.radius, (uint8_t)e.weight, "pp_world_step", NULL);
        else
            st = edit_erase_circle(wd, bd, e.center, e.radius, "pp_world_step", NULL);
        if (st)
            return st;
        edits_pop(q);
    }
    return PP_OK;
}

static pp_status check_timed_edit(world *wd, const pp_timed_edit *e, const char *fn)
{
    if (!isfinite(e->time))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: time must be finite, got %g", fn, e->time);
    if (e->type != PP_EDIT_ERASE_CIRCLE && e->type != PP_EDIT_PAINT_CIRCLE)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: type %d is unknown", fn, (int)e->type);
    if (!isfinite(e->center.x) || !isfinite(e->center.y) || !(e->radius >= 0) || !isfinite(e->radius))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: center must be finite and radius finite and ≥ 0", fn);
    if (e->type == PP_EDIT_PAINT_CIRCLE && (e->weight < 1 || e->weight > 255))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: paint weight must be 1..255, got %u", fn, (unsigned)e->weight);
    if (e->type == PP_EDIT_PAINT_CIRCLE && e->body.id == 0)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: a paint edit needs a body", fn);
    if (e->body.id != 0 && !body_lookup(wd, e->body, fn))
        return PP_ERR_INVALID_HANDLE;
    return PP_OK;
}

pp_status timed_edits_schedule(world *wd, const pp_timed_edit *edit, const char *fn)
{
    timed_edits *q = &wd->edits;
    pp_status st = check_timed_edit(wd, edit, fn);
    if (st)
        return st;
    if (!ARRAY_RESERVE(q->heap, q->capacity, q->count + 1))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d edits", fn, (int)q->count + 1);
    edits_push(q, edit);
    return PP_OK;
}

void timed_edits_free(timed_edits *q)
{
    pp_free(q->heap);
    *q = (timed_edits){0};
}

PP_API pp_status pp_world_schedule_edit(pp_world w, const pp_timed_edit *edit)
{
    pp_status st;
    world *wd = world_lookup_out(w, "pp_world_schedule_edit", edit, "edit", &st);
    if (!wd)
        return st;
    return timed_edits_schedule(wd, edit, "pp_world_schedule_edit");
}

PP_API pp_status pp_world_get_scheduled_edits(pp_world w, pp_timed_edit *out, int32_t capacity, int32_t *count)
{
    pp_status st;
    world *wd = world_lookup_list(w, "pp_world_get_scheduled_edits", out, capacity, count, &st);
    if (!wd)
        return st;
    timed_edits *q = &wd->edits;
    const int32_t n = q->count < capacity ? q->count : capacity;
    if (n > 0)
        edits_sort(q);
    for (int32_t i = 0; i < n; i++)
        out[i] = q->heap[i].edit;
    *count = q->count;
    return PP_OK;
}
