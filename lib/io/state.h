/* The layout of world state bytes (state.c), shared with the checks of their records (state_check.c). */
#ifndef PP_STATE_H
#define PP_STATE_H

#include "joint.h"
#include "world.h"

#define STATE_MAGIC "PPSTATE"
#define STATE_VERSION 2u
#define STATE_SUMMED 24 /* the bytes after the magic, the checksum and the seal */

typedef struct state_header {
    char magic[8];
    uint64_t checksum;       /* hash.h's over every byte from STATE_SUMMED on */
    uint64_t seal;           /* the checksum keyed by the saving world's state_key: bytes it wrote, unchanged */
    uint32_t version;
    uint32_t layout;         /* the sizes of the records copied whole: another build's bytes are another format */
    uint64_t size;           /* the whole state, bytes */
    uint64_t world;          /* the handle id of the world saved */
} state_header;

/* The world's own values; its arrays follow in the order of write_state. */
typedef struct state_world {
    pp_world_def def;
    pp_step_stats stats;
    double time;
    uint64_t solver_steps, next_serial, substep_serial, pixel_clock, next_attach, edit_serial;
    contact_table_counts table;
    int32_t body_capacity, body_free, body_count;
    int32_t joint_capacity, joint_free, joint_count;
    int32_t contact_count, event_count, edit_count, forced_count;
    uint32_t edits_in_order;
} state_world;

/* A body: its record with the pointers zeroed, its ODE state, then its planes (bits, weights, row, column and tile
 * counts, sprite); a big body's (has_base) as its changed-band flags, each changed band's rows of the planes, and
 * its column counts, the rest being the world's state_base. */
typedef struct state_body {
    body b;
    solver_exact_state ode;
    uint32_t has_weights, has_sprite, has_base, reserved;
} state_body;

/* Bodies of this many pixels or more are kept once by the world (state_base) and saved by their changed bands: a
 * terrain's untouched pixels are not copied into every state. */
#define STATE_BASE_PIXELS (1 << 16)

typedef struct state_joint {
    joint j;                 /* sj zeroed */
    double feedback[6];
} state_joint;

/* One body record: its head copied out and its planes found. */
typedef struct body_view {
    state_body h;
    const uint8_t *bits, *weights, *rows, *cols, *tiles, *sprite;
    const uint8_t *bands, *band_data; /* has_base: the changed-band flags, and the first changed band's planes */
} body_view;

static inline int64_t pad8(int64_t n) { return (n + 7) & ~(int64_t)7; }

/* Rows of band b (the last may be cut by the bitmap). */
static inline int32_t band_rows(const pp_raster *r, int32_t b)
{
    const int32_t y = b << RASTER_TILE_SHIFT;
    return r->height - y < RASTER_TILE ? r->height - y : RASTER_TILE;
}

/* What state_check.c marks of each body slot while it checks the bytes. */
enum { SLOT_BODY = 1, SLOT_FORCED = 2, SLOT_FREE = 4, SLOT_LISTED = 8 };

/* What is wrong with the saved world's values, or NULL. */
const char *state_world_problem(const state_world *w);
/* What is wrong with an id pool's generations and free slots, or NULL; marks the free slots SLOT_FREE in mark (capacity
 * bytes) unless it is NULL. */
const char *state_pool_problem(const uint8_t *gens, int32_t capacity, const uint8_t *free_slots, int32_t free_count,
                               uint8_t *mark);
/* What is wrong with a body record (gens: the body slots' generations), or NULL; base: a big body's kept planes
 * where known; ppm: the state's pixels per metre. A sound record's planes and counts agree, so the raster never
 * runs off its arrays, and its solver state lies within its bitmap's reach of its pose. */
const char *state_body_problem(const body_view *v, const uint8_t *gens, int32_t capacity, const state_base *base,
                               double ppm);
/* What is wrong with a joint record (gens: the joint slots' generations), or NULL. */
const char *state_joint_problem(const state_joint *sj, const uint8_t *gens, int32_t capacity);
/* What is wrong with the contacts, touching pairs, carry order, events, edits and forced bodies, or NULL. live: per
 * body slot, the SLOT_* marks; keys: room for the touching pairs' count. */
const char *state_arrays_problem(const state_world *w, uint8_t *live, const uint8_t *gens, const uint8_t *contacts,
                                 const uint8_t *records, const uint8_t *order, const uint8_t *events,
                                 const uint8_t *edits, const uint8_t *forced, uint64_t *keys);

#endif
