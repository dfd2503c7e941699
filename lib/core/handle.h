/* How handle ids pack their kinds, slots and generations, in one place, so that every kind of handle (worlds,
 * bodies, joints) is made and checked alike. Header-only: the plugin and tests read it too.
 *
 * Bits 61–62 of every id say what it is a handle of (handle_kind), so a joint handle passed as a body, or a
 * body's as a joint, is known for what it is, not taken for the other table's object in the same slot. Bit 63
 * stays 0: every id is a positive int64, as GDScript's and the plugin's ints hold it.
 * A world id is (kind << 61) | (generation << 32) | (slot + 1). An id of something in a world (a body, a
 * joint) names its world:
 *   bits  0–19  its slot in the world             (PP_MAX_BODIES = 2^20 slots)
 *   bits 20–31  the world's slot                  (PP_MAX_WORLDS = 4096)
 *   bits 32–39  the world's generation, low 8 bits
 *   bits 40–60  its own generation, 1..2^21 − 1   (never 0, so id 0 is never valid)
 *   bits 61–62  its kind                          (never 0 either)
 * Bits 20–39 are the world's tag. The generation bits make a handle from a destroyed world stale in the
 * next world that takes its slot, as happens when a host replaces its world by a loaded one twice.
 * A snapshot stores such an id without its world or kind, as (generation << 32) | (slot + 1): the layout ids
 * had before they named their world, so the file format did not change; the loader knows which kind each
 * stored handle is and gives it back. */
#ifndef PP_HANDLE_H
#define PP_HANDLE_H

#include "physpix.h"

#include <stdbool.h>
#include <stdint.h>

#define HANDLE_SLOT_BITS 20
#define HANDLE_WORLD_SLOT_BITS 12
#define HANDLE_TAG_BITS 20 /* world slot and 8 bits of the world's generation */
#define HANDLE_GEN_BITS 21
#define HANDLE_GEN_MAX ((1u << HANDLE_GEN_BITS) - 1)
#define HANDLE_KIND_SHIFT 61

/* What a handle is a handle of; 0 is no kind, so that no valid id is 0. */
typedef enum handle_kind { HANDLE_NONE = 0, HANDLE_WORLD = 1, HANDLE_BODY = 2, HANDLE_JOINT = 3 } handle_kind;

_Static_assert(PP_MAX_BODIES <= 1 << HANDLE_SLOT_BITS, "a body slot must fit bits 0-19");
_Static_assert(PP_MAX_WORLDS <= 1 << HANDLE_WORLD_SLOT_BITS, "a world slot must fit bits 20-31");
_Static_assert(HANDLE_SLOT_BITS + HANDLE_TAG_BITS + HANDLE_GEN_BITS == HANDLE_KIND_SHIFT, "the kind takes bits 61-62");

/* HANDLE_NONE for an id with bit 63 set, which no handle has. */
static inline handle_kind handle_kind_of(uint64_t id)
{
    return id >> HANDLE_KIND_SHIFT <= HANDLE_JOINT ? (handle_kind)(id >> HANDLE_KIND_SHIFT) : HANDLE_NONE;
}
/* Whether an id is a handle of a kind other than `kind` (not merely stale or made up), and which, for messages. */
static inline bool handle_is_other_kind(uint64_t id, handle_kind kind)
{
    return handle_kind_of(id) != HANDLE_NONE && handle_kind_of(id) != kind;
}
static inline const char *handle_kind_name(uint64_t id)
{
    static const char *names[] = {"no", "a world", "a body", "a joint"};
    return names[handle_kind_of(id)];
}

/* The id of a slot in a table of worlds (or of the plugin's objects) of this kind. */
static inline uint64_t slot_id_make(handle_kind kind, uint32_t slot, uint32_t gen)
{
    return (uint64_t)kind << HANDLE_KIND_SHIFT | (uint64_t)gen << 32 | (slot + 1);
}
static inline uint64_t world_id_make(uint32_t slot, uint32_t gen) { return slot_id_make(HANDLE_WORLD, slot, gen); }
/* UINT32_MAX for id 0, so a range check refuses it. */
static inline uint32_t world_id_slot(uint64_t id) { return (uint32_t)id - 1; }
static inline uint32_t world_id_gen(uint64_t id) { return (uint32_t)(id >> 32) & ((1u << (HANDLE_KIND_SHIFT - 32)) - 1); }

/* The tag that a world's objects carry. */
static inline uint32_t world_tag(uint32_t slot, uint32_t gen) { return slot | (gen & 0xffu) << HANDLE_WORLD_SLOT_BITS; }
static inline uint32_t tag_world_slot(uint32_t tag) { return tag & ((1u << HANDLE_WORLD_SLOT_BITS) - 1); }

static inline uint64_t handle_make(handle_kind kind, uint32_t tag, uint32_t slot, uint32_t gen)
{
    return (uint64_t)kind << HANDLE_KIND_SHIFT | (uint64_t)gen << (HANDLE_SLOT_BITS + HANDLE_TAG_BITS) |
           (uint64_t)tag << HANDLE_SLOT_BITS | slot;
}
static inline uint32_t handle_slot(uint64_t id) { return (uint32_t)id & ((1u << HANDLE_SLOT_BITS) - 1); }
static inline uint32_t handle_tag(uint64_t id) { return (uint32_t)(id >> HANDLE_SLOT_BITS) & ((1u << HANDLE_TAG_BITS) - 1); }
static inline uint32_t handle_gen(uint64_t id) { return (uint32_t)(id >> (HANDLE_SLOT_BITS + HANDLE_TAG_BITS)) & HANDLE_GEN_MAX; }

/* The generation a slot gets when its object is destroyed: 1..HANDLE_GEN_MAX, around again. */
static inline uint32_t handle_next_gen(uint32_t gen) { return gen >= HANDLE_GEN_MAX ? 1 : gen + 1; }

/* An id as a snapshot stores it, without its world; 0 stays 0. */
static inline uint64_t handle_saved(uint64_t id)
{
    return id ? (uint64_t)handle_gen(id) << 32 | (handle_slot(id) + 1) : 0;
}

/* A stored id back in the world with this tag, as a handle of this kind; false (and *id 0) if no id has that
 * form. 0 gives 0. */
static inline bool handle_from_saved(uint64_t saved, handle_kind kind, uint32_t tag, uint64_t *id)
{
    const uint32_t slot = (uint32_t)saved - 1, gen = (uint32_t)(saved >> 32);
    *id = 0;
    if (saved == 0)
        return true;
    if (slot >= PP_MAX_BODIES || gen == 0 || gen > HANDLE_GEN_MAX)
        return false;
    *id = handle_make(kind, tag, slot, gen);
    return true;
}

#endif
