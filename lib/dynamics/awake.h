/* The awake set: the bodies a substep must visit. It holds every awake dynamic or kinematic body, and any
 * body whose pose or pixels changed since the last substep (its broadphase proxy is stale); a sleeping or
 * static body leaves it once its proxy is refreshed. Every per-body pass of the step walks this set, not
 * the body table, so a sleeping world steps without visiting its bodies. */
#ifndef PP_AWAKE_H
#define PP_AWAKE_H

#include "world.h"

/* Room for every live body and one more, so that awake_add cannot fail; call before creating a body. */
pp_status awake_reserve(world *wd, int32_t n, const char *fn);

/* List a body (if not listed): it is awake, or its proxy must be refreshed. */
void awake_add(world *wd, body *bd);

/* Wake a movable body's ODE body and list it. */
void awake_wake(world *wd, body *bd);

/* A listed body was put to sleep: until the next refresh it is in no tree leaf, and awake_wake_in_box must
 * still find it. */
void awake_slept(world *wd, body *bd);

/* A body's box changed outside a substep's solve (an edit, a teleport, a new type, a stop by a sweep): list
 * it, and let the box queries see it where it is now. */
void awake_moved(world *wd, body *bd);

/* Bodies moved in a substep's solve: the box queries' index of awake bodies is rebuilt when next asked. */
static inline void awake_index_stale(world *wd) { wd->awake.by_x_valid = false; }

/* Wake every movable body whose world box meets `box` (closed). An awake mover needs no waking, so this visits
 * the tree's leaves and the bodies listed or put to sleep since the last refresh, never the whole awake set:
 * an edit costs what is near it. */
void awake_wake_in_box(world *wd, pp_aabb box);

/* Forget a body that is being removed: out of the set, its slot's proxy dead. */
void awake_forget(world *wd, body *bd);

/* List every live body again (after a step is undone, which restores poses behind the set's back). */
void awake_rebuild(world *wd);

/* At a substep's start: refresh the listed bodies' proxies and tree leaves, drop those now asleep or static, sort the rest
 * by slot (the order every pass visits them in) and count the awake movers into wd->awake_movers. */
pp_status awake_refresh(world *wd);

/* After awake_refresh, with an awake mover: the broadphase's pairs at substep k of a step of dt s. The first
 * substep searches with each awake mover's box grown over the step (its velocity, turn and gravity's reach)
 * and keeps those candidates; the later ones take their pairs from them (broadphase_find_later_pairs). */
pp_status awake_find_pairs(world *wd, int32_t k, double dt);

/* Call visit for each live body whose world box meets `box` (closed), in no set order, until it returns false:
 * the tree's leaves find the bodies it holds up to date, an index of the awake movers by x (built at most once
 * a substep, when asked) and the changed list the rest, so a query costs what is near it. Cannot fail. */
void awake_each_in_box(world *wd, pp_aabb box, bool (*visit)(world *wd, body *bd, void *user), void *user);

/* The live bodies whose world box meets `box` (closed), in slot order, as a list the caller frees with pp_free:
 * awake_each_in_box's. PP_ERR_OUT_OF_MEMORY names `fn`. */
pp_status awake_bodies_in_box(world *wd, const char *fn, pp_aabb box, int32_t **slots, int32_t *n);
/* The same list into `slots`, which holds room for wd->body_ids.capacity of them; returns how many. Cannot fail. */
int32_t awake_slots_in_box(world *wd, pp_aabb box, int32_t *slots);

/* Whether a listed body is an awake movable body (the set may still hold one that fell asleep this substep). */
void awake_free(awake_set *a);

static inline bool awake_mover(const body *bd) { return bd->sb.body && solver_body_is_awake(&bd->sb); }

#endif
