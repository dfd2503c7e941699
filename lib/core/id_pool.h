/* The one pool of handle slots behind every kind of handle: worlds, bodies, joints and the plugin's objects.
 * A pool hands out slots and keeps each slot's generation, which its handles carry (handle.h), so a
 * destroyed object's handle is known stale. Free slots are a stack with the lowest slot on top: creation
 * order is slot order, and the slot freed last is taken first. The objects themselves stay in their owner's
 * array, which id_pool_take grows with the pool. Header-only: the plugin keeps its objects in one too. */
#ifndef PP_ID_POOL_H
#define PP_ID_POOL_H

#include "handle.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

typedef struct id_pool {
    uint32_t *generations;   /* by slot, 1..HANDLE_GEN_MAX: what a live handle of the slot carries */
    uint32_t *free_slots;    /* a stack; the next slot to hand out on top */
    int32_t capacity, free_count;
    int32_t live;            /* slots taken */
} id_pool;

/* The allocator a pool grows with: the library's pp_realloc, or the plugin's realloc. */
typedef void *(*id_pool_realloc)(void *ptr, size_t size);

typedef enum { ID_POOL_TAKEN, ID_POOL_FULL, ID_POOL_NO_MEMORY } id_pool_result;

/* The generation a handle of `slot` must carry to be live; false past the pool's slots. */
static inline bool id_pool_current(const id_pool *p, uint32_t slot, uint32_t gen)
{
    return slot < (uint32_t)p->capacity && p->generations[slot] == gen;
}

/* A pool over caller-owned arrays of `capacity` slots, every one free (generation 1, slot 0 on top). */
static inline void id_pool_init_fixed(id_pool *p, uint32_t *generations, uint32_t *free_slots, int32_t capacity)
{
    *p = (id_pool){generations, free_slots, capacity, 0, 0};
    for (int32_t i = capacity - 1; i >= 0; i--) {
        generations[i] = 1;
        free_slots[p->free_count++] = (uint32_t)i;
    }
}

/* Double the pool's slots (from 64, at most `max`) and the owner's `items` (item_size bytes a slot, the new
 * ones zeroed) with them; the new slots are free, the lowest on top. False, the pool unchanged, without
 * memory (an array already grown keeps its extra room). */
static inline bool id_pool_grow(id_pool *p, int32_t max, void **items, size_t item_size, id_pool_realloc re)
{
    const int32_t old = p->capacity, cap = old == 0 ? 64 : old > max / 2 ? max : 2 * old;
    uint32_t *gens = re(p->generations, (size_t)cap * sizeof *gens);
    if (gens)
        p->generations = gens;
    uint32_t *free_slots = gens ? re(p->free_slots, (size_t)cap * sizeof *free_slots) : NULL;
    if (free_slots)
        p->free_slots = free_slots;
    void *grown = free_slots ? re(*items, (size_t)cap * item_size) : NULL;
    if (!grown)
        return false;
    *items = grown;
    memset((char *)grown + (size_t)old * item_size, 0, (size_t)(cap - old) * item_size);
    for (int32_t i = cap - 1; i >= old; i--) {
        p->generations[i] = 1;
        p->free_slots[p->free_count++] = (uint32_t)i;
    }
    p->capacity = cap;
    return true;
}

/* Take the free slot on top into *slot; false when none is free (a fixed pool is full). */
static inline bool id_pool_take_free(id_pool *p, uint32_t *slot)
{
    if (p->free_count == 0)
        return false;
    *slot = p->free_slots[--p->free_count];
    p->live++;
    return true;
}

/* Take the free slot on top into *slot, growing the pool and `items` first when none is free: FULL when
 * `max` slots are taken, NO_MEMORY when they cannot grow; neither changes anything. */
static inline id_pool_result id_pool_take(id_pool *p, int32_t max, void **items, size_t item_size,
                                          id_pool_realloc re, uint32_t *slot)
{
    if (p->free_count == 0 && p->capacity >= max)
        return ID_POOL_FULL;
    if (p->free_count == 0 && !id_pool_grow(p, max, items, item_size, re))
        return ID_POOL_NO_MEMORY;
    return id_pool_take_free(p, slot) ? ID_POOL_TAKEN : ID_POOL_FULL;
}

/* id_pool_take with the item size taken from the owner's array type. */
#define ID_POOL_TAKE(pool, max, items, re, slot) \
    id_pool_take((pool), (max), (void **)&(items), sizeof *(items), (re), (slot))

/* Free a slot: its generation moves on, so its handles go stale, and it goes on top of the free stack. */
static inline void id_pool_release(id_pool *p, uint32_t slot)
{
    p->generations[slot] = handle_next_gen(p->generations[slot]);
    p->free_slots[p->free_count++] = slot;
    p->live--;
}

/* Undo the latest id_pool_take of `slot` exactly: back on top, its generation as it was. */
static inline void id_pool_untake(id_pool *p, uint32_t slot)
{
    p->free_slots[p->free_count++] = slot;
    p->live--;
}

/* A pool as a snapshot saved it: the generations of `capacity` slots and the free stack, bottom first (the
 * caller checked both). No slot counts live until its owner claims it. False without memory; what was
 * allocated stays for id_pool_free. */
static inline bool id_pool_restore(id_pool *p, const uint32_t *generations, int32_t capacity,
                                   const uint32_t *free_slots, int32_t free_count, id_pool_realloc re)
{
    uint32_t *gens = re(p->generations, ((size_t)capacity + 1) * sizeof *gens);
    if (gens)
        p->generations = gens;
    uint32_t *stack = gens ? re(p->free_slots, ((size_t)capacity + 1) * sizeof *stack) : NULL;
    if (!stack)
        return false;
    p->free_slots = stack;
    if (capacity > 0)
        memcpy(gens, generations, (size_t)capacity * sizeof *gens);
    if (free_count > 0)
        memcpy(stack, free_slots, (size_t)free_count * sizeof *stack);
    p->capacity = capacity, p->free_count = free_count, p->live = 0;
    return true;
}

/* Count one more live slot: a restored one, neither free nor live, that its owner fills again. */
static inline void id_pool_claim(id_pool *p) { p->live++; }

/* Free a grown pool's arrays (not a fixed one's) with the owner's free function. */
static inline void id_pool_free(id_pool *p, void (*fr)(void *ptr))
{
    fr(p->generations);
    fr(p->free_slots);
    *p = (id_pool){0};
}

#endif
