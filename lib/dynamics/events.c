/* The event queue: contact, sensor, split and joint events queue inside a step or an edit, into room
 * reserved before anything changed, and wait there until the host reads them. */
#include "alloc.h"
#include "check.h"
#include "events.h"
#include "status.h"
#include "world.h"

#include <string.h>

pp_status world_reserve_events(world *wd, int32_t n, const char *fn)
{
    event_queue *q = &wd->events;
    if (!ARRAY_RESERVE(q->items, q->capacity, q->count + n))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d events", fn, (int)(q->count + n));
    return PP_OK;
}

void world_queue_event(world *wd, pp_event ev)
{
    event_queue *q = &wd->events;
    PP_ASSERT(q->count < q->capacity);
    q->items[q->count++] = ev;
}

void events_trim(world *wd)
{
    event_queue *q = &wd->events;
    const int32_t drop = q->count - PP_MAX_QUEUED_EVENTS;
    if (drop <= 0)
        return;
    memmove(q->items, q->items + drop, (size_t)PP_MAX_QUEUED_EVENTS * sizeof *q->items);
    q->count = PP_MAX_QUEUED_EVENTS;
    pp_log(1, "physpix: world %#llx dropped its %d oldest unread events (PP_MAX_QUEUED_EVENTS)",
           (unsigned long long)wd->handle.id, (int)drop);
}

void events_free(event_queue *q)
{
    pp_free(q->items);
    *q = (event_queue){0};
}

PP_API pp_status pp_world_get_events(pp_world w, pp_event *out, int32_t capacity, int32_t *count)
{
    pp_status st;
    world *wd = world_lookup_list(w, "pp_world_get_events", out, capacity, count, &st);
    if (!wd)
        return st;
    event_queue *q = &wd->events;
    const int32_t n = q->count < capacity ? q->count : capacity;
    if (n > 0) {
        memcpy(out, q->items, (size_t)n * sizeof *out);
        memmove(q->items, q->items + n, (size_t)(q->count - n) * sizeof *out);
    }
    *count = q->count;
    q->count -= n;
    return PP_OK;
}

PP_API pp_status pp_world_set_contact_events(pp_world w, uint32_t enabled)
{
    world *wd = world_lookup(w, "pp_world_set_contact_events");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    /* Off, the pairs recorded for events end silently (contact_table.c queues no END without it). */
    wd->def.contact_events = enabled != 0;
    return PP_OK;
}
