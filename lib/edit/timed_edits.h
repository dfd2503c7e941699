/* Timed edits (pp_world_schedule_edit): erases and paints that wait for the step they fall due in, kept
 * in a binary heap so that scheduling and applying n edits cost n log n, in any order (timed_edits.c). */
#ifndef PP_TIMED_EDITS_H
#define PP_TIMED_EDITS_H

#include "physpix.h"

#include <stdbool.h>
#include <stdint.h>

typedef struct world world;

/* A pending edit and when it was scheduled: among equal times, the earlier scheduled applies first. */
typedef struct timed_edit {
    pp_timed_edit edit;
    uint64_t serial;
} timed_edit;

typedef struct timed_edits {
    timed_edit *heap;        /* on (time, serial), the next to apply first */
    int32_t count, capacity;
    uint64_t serial;         /* the next scheduled edit's */
    bool in_order;           /* the heap is sorted, as pp_world_get_scheduled_edits lists it */
} timed_edits;

/* Check an edit (finite time and circle, a known type, a live body where it names one) and add it;
 * failures name fn. */
pp_status timed_edits_schedule(world *wd, const pp_timed_edit *edit, const char *fn);
/* Apply, in order, the edits due at a step of dt seconds that starts now: those nearer this step than the
 * next, or earlier. Each leaves the queue once applied; one that fails is tried again by the next step. */
pp_status timed_edits_apply_due(world *wd, float dt);
/* The pending edits in the order they apply, a copy the caller frees; NULL when out of memory. */
timed_edit *timed_edits_in_order(const timed_edits *q);
void timed_edits_free(timed_edits *q);

#endif
