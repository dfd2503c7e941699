/* The event queue: what steps and edits report, read by the host with pp_world_get_events (events.c). */
#ifndef PP_EVENTS_H
#define PP_EVENTS_H

#include "physpix.h"

#include <stdint.h>

typedef struct world world;

/* Events since the host last read them, oldest first. */
typedef struct event_queue {
    pp_event *items;
    int32_t count, capacity;
} event_queue;

/* Room for n more events, so that the n world_queue_event calls after it cannot fail; failures name fn. */
pp_status world_reserve_events(world *wd, int32_t n, const char *fn);
/* Queue an event into room reserved (checked by PP_ASSERT). */
void world_queue_event(world *wd, pp_event ev);
/* Drop the oldest unread events beyond PP_MAX_QUEUED_EVENTS, with a log line; a step does it before it
 * saves anything, so the step's undo never sees it. */
void events_trim(world *wd);
void events_free(event_queue *q);

#endif
