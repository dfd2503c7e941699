/* Pairs that touch from one substep to the next, every one of them: what contact and sensor events
 * report, what a one-way platform remembers of a body passing through it, and each pair's friction
 * anchor. */
#ifndef PP_TOUCH_H
#define PP_TOUCH_H

#include "math2d.h"
#include "narrowphase.h"

#include <stdbool.h>
#include <stdint.h>

struct world;
struct body;

/* What a pair is to the world while it touches. */
enum {
    TOUCH_SENSOR = 1,   /* one body is a sensor: events, no contacts */
    TOUCH_SENSOR_B = 2, /* with TOUCH_SENSOR: the sensor is b */
    TOUCH_PASSING = 4,  /* a one-way platform let the other body in from the wrong side: no contacts until they part */
    TOUCH_BEGUN = 8,    /* its PP_EVENT_CONTACT_BEGIN was queued: its END will be */
    TOUCH_UNANCHORED = 16, /* loaded from a snapshot without anchors: anchors at its next substep */
    TOUCH_FLAGS = 31,   /* every flag */
};

/* One touching pair: a is the body in the lower slot (the broadphase's order). */
typedef struct touch {
    uint64_t a, b;     /* body handle ids */
    uint32_t flags;    /* TOUCH_* */
    uint32_t reserved;
    double anchor[3];  /* b's pivot and angle in a's frame when the pair last held still: px, px, rad */
} touch;

/* Every touching pair of a world, awake or resting (touch.c). */
typedef struct touch_set {
    touch *pairs;            /* touching at the last substep with a body awake, sorted */
    int32_t count, capacity;
    touch *resting;          /* touching with every body asleep (or static), sorted; no substep visits them */
    int32_t resting_count, resting_capacity;
    touch *next;             /* the substep's list being built */
    int32_t next_count, next_capacity;
    touch *resting_next;     /* scratch for the resting pairs' merge */
    int32_t resting_next_capacity;
    bool body_gone;          /* a body was removed since the last touch_end: its pairs end there */
    bool resting_stale;      /* a body entered the awake set since the last touch_end: resting pairs are reviewed */
} touch_set;

void touch_free(touch_set *t);

/* Start a substep's list. */
void touch_begin(struct world *wd);

/* A pair the narrowphase found touching (r->count > 0): record it, queue its BEGIN event if it is new,
 * and say whether its contacts go to the solver (not for sensors or a passing one-way pair). */
pp_status touch_pair(struct world *wd, const struct body *a, const struct body *b, const np_result *r, bool *keep);

/* After every pair: queue the END of each recorded pair that no longer touches, unless neither body
 * was awake to be tested (a sleeping stack still touches), and make the substep's list current. */
pp_status touch_end(struct world *wd);

/* How far b's material point at world point p has moved relative to a since the pair's anchor, px:
 * the slip that static friction has let through and the solver should undo. */
dvec2 touch_anchor_slip(const touch *t, const struct body *a, const struct body *b, dvec2 p);

/* The recorded pair of two bodies (either order), or NULL. */
const touch *touch_find(const struct world *wd, uint64_t x, uint64_t y);

/* Sort a list into the order touch_find searches (for a snapshot's list). */
void touch_sort(touch *list, int32_t n);

/* That order: negative, zero or positive as p comes before, with or after q. */
int touch_order(const touch *p, const touch *q);

#endif
