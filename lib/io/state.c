/* World state in memory (pp_world_save_state, _restore_state, _load_state): the world as flat bytes, for rollback
 * and undo. The bytes copy the records the world keeps (bodies, joints, the contact table, events, edits) as they
 * are in memory, so this build reads only its own; a header with a checksum guards them. A restore into the world
 * that saved them copies them back over the live records when its bodies and joints are the ones saved; else it
 * builds the saved world apart and swaps it in, so that any failure leaves the world as it was. */
#include "alloc.h"
#include "awake.h"
#include "check.h"
#include "hash.h"
#include "joint.h"
#include "state.h"
#include "status.h"
#include "world.h"

#include <stdatomic.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

_Static_assert(offsetof(state_header, version) == STATE_SUMMED, "the checksum covers all but the magic, itself and the seal");


static uint32_t layout_code(void)
{
    const uint32_t sizes[] = {sizeof(state_header), sizeof(state_world), sizeof(state_body), sizeof(state_joint),
                              sizeof(contact_record), sizeof(pp_contact), sizeof(pp_event), sizeof(timed_edit)};
    return (uint32_t)hash_bytes(HASH_START, sizes, sizeof sizes);
}

/* A world's seal key: unlike the checksum, which anyone can compute, it is in no bytes, so bytes changed and
 * summed again (a peer's bug, a fuzzer) do not pass for the world's own. Not a defence against someone who studies
 * many states the world saved. */
static uint64_t new_state_key(const world *wd)
{
    static _Atomic uint64_t made;
    struct timespec t = {0};
    timespec_get(&t, TIME_UTC);
    const uint64_t v[4] = {(uint64_t)(uintptr_t)wd, atomic_fetch_add(&made, 1), (uint64_t)t.tv_sec,
                           (uint64_t)t.tv_nsec};
    return hash_bytes(HASH_START, v, sizeof v) | 1;
}

/* The seal world wd puts on bytes of this header: a keyed hash of their checksum and saving world. */
static uint64_t seal_of(const world *wd, const state_header *h)
{
    const uint64_t v[3] = {h->checksum, h->world, wd->state_key};
    return hash_bytes(wd->state_key, v, sizeof v);
}

/* Bytes of a body's planes. */
static int64_t bits_bytes(const pp_raster *r) { return (int64_t)r->height * r->words_per_row * 8; }
static int64_t plane_bytes(const pp_raster *r) { return (int64_t)r->width * r->height; }
static int64_t tile_bytes(const pp_raster *r) { return (int64_t)r->tiles_x * r->tiles_y; }
static const state_base *base_of(const world *wd, uint64_t serial)
{
    for (int32_t i = 0; wd && i < wd->base_count; i++)
        if (wd->bases[i].serial == serial)
            return &wd->bases[i];
    return NULL;
}

static void base_free(state_base *b)
{
    pp_free(b->bits), pp_free(b->weights), pp_free(b->rows), pp_free(b->tiles), pp_free(b->sprite);
    *b = (state_base){0};
}

/* A copy of n bytes, or NULL (n 0 gives NULL too). */
static void *dup_bytes(const void *p, int64_t n)
{
    void *q = p && n > 0 ? pp_malloc((size_t)n) : NULL;
    if (q)
        memcpy(q, p, (size_t)n);
    return q;
}

/* The world keeps r's planes (and sprite) as the base of the body `serial`; changed bands are counted from now
 * when `bands` is NULL, else they are these. */
static pp_status keep_base(world *wd, uint64_t serial, const pp_raster *r, const uint8_t *sprite, const char *fn,
                           uint8_t **bands)
{
    state_base b = {serial, dup_bytes(r->bits, bits_bytes(r)), dup_bytes(r->weights, r->weights ? plane_bytes(r) : 0),
                    dup_bytes(r->row_count, (int64_t)r->height * 4), dup_bytes(r->tile_count, tile_bytes(r)),
                    dup_bytes(sprite, sprite ? 4 * plane_bytes(r) : 0)};
    *bands = pp_calloc((size_t)r->tiles_y, 1);
    if (!b.bits || (r->weights && !b.weights) || !b.rows || !b.tiles || (sprite && !b.sprite) || !*bands ||
        !ARRAY_RESERVE(wd->bases, wd->base_capacity, wd->base_count + 1)) {
        base_free(&b);
        pp_free(*bands);
        *bands = NULL;
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory to keep a %d × %d body's pixels", fn, (int)r->width,
                       (int)r->height);
    }
    wd->bases[wd->base_count++] = b;
    return PP_OK;
}

/* Before a save: every big body without a base gets one, its bands unchanged. Nothing seen changes on failure. */
static pp_status keep_bases(world *wd, const char *fn)
{
    for (int32_t i = 0; i < wd->body_ids.capacity; i++) {
        body *bd = wd->bodies[i];
        if (!bd || bd->raster.changed_bands || (int64_t)bd->raster.width * bd->raster.height < STATE_BASE_PIXELS)
            continue;
        uint8_t *bands = NULL;
        if (base_of(wd, bd->serial)) { /* kept already: a body built again by a restore */
            if (!(bands = pp_calloc((size_t)bd->raster.tiles_y, 1)))
                return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory", fn);
            memset(bands, 1, (size_t)bd->raster.tiles_y); /* unknown: every band saved */
        } else {
            pp_status st = keep_base(wd, bd->serial, &bd->raster, bd->sprite, fn, &bands);
            if (st)
                return st;
        }
        bd->raster.changed_bands = bands;
    }
    return PP_OK;
}

/* ---- writing ------------------------------------------------------------------------------------------- */

/* Where the bytes go: counted only while p is NULL. */
typedef struct sink {
    uint8_t *p;
    int64_t at;
} sink;

static void put(sink *s, const void *v, int64_t n)
{
    if (s->p && n > 0) {
        memcpy(s->p + s->at, v, (size_t)n);
        memset(s->p + s->at + n, 0, (size_t)(pad8(n) - n));
    }
    s->at += pad8(n);
}

/* The body's pixel stamp, a new one when its raster changed since the last. */
static uint64_t body_stamp(world *wd, body *bd)
{
    if (bd->pixel_stamp == 0 || bd->stamp_version != bd->raster.version) {
        bd->pixel_stamp = ++wd->pixel_clock;
        bd->stamp_version = bd->raster.version;
    }
    return bd->pixel_stamp;
}

static void write_body(sink *s, world *wd, body *bd)
{
    const pp_raster *r = &bd->raster;
    if (s->p) {
        body_stamp(wd, bd);
        state_body h = {.b = *bd, .has_weights = r->weights != NULL, .has_sprite = bd->sprite != NULL,
                        .has_base = r->changed_bands != NULL};
        h.b.raster.bits = NULL, h.b.raster.weights = NULL, h.b.raster.row_count = h.b.raster.col_count = NULL;
        h.b.raster.tile_count = NULL, h.b.raster.outline = NULL, h.b.raster.changed_bands = NULL, h.b.sprite = NULL;
        h.b.sb.body = h.b.sb.plane = NULL;
        if (bd->sb.body)
            solver_body_save(&bd->sb, &h.ode);
        put(s, &h, sizeof h);
    } else {
        s->at += pad8(sizeof(state_body));
    }
    if (r->changed_bands) {
        put(s, r->changed_bands, r->tiles_y);
        for (int32_t b = 0; b < r->tiles_y; b++) {
            if (!r->changed_bands[b])
                continue;
            const int64_t y = (int64_t)b << RASTER_TILE_SHIFT, n = band_rows(r, b);
            put(s, r->bits + y * r->words_per_row, n * r->words_per_row * 8);
            if (r->weights)
                put(s, r->weights + y * r->width, n * r->width);
            put(s, r->row_count + y, n * 4);
            put(s, r->tile_count + (int64_t)b * r->tiles_x, r->tiles_x);
        }
        put(s, r->col_count, (int64_t)r->width * 4);
        return;
    }
    put(s, r->bits, bits_bytes(r));
    if (r->weights)
        put(s, r->weights, plane_bytes(r));
    put(s, r->row_count, (int64_t)r->height * 4);
    put(s, r->col_count, (int64_t)r->width * 4);
    put(s, r->tile_count, tile_bytes(r));
    if (bd->sprite)
        put(s, bd->sprite, 4 * plane_bytes(r));
}

static void write_pool(sink *s, const id_pool *p)
{
    put(s, p->generations, (int64_t)p->capacity * 4);
    put(s, p->free_slots, (int64_t)p->free_count * 4);
}

/* Everything, in the order read_view reads it; bodies and joints in slot order. */
static void write_state(sink *s, world *wd)
{
    const contact_table *t = &wd->table;
    state_header h = {.version = STATE_VERSION, .layout = layout_code(), .world = wd->handle.id};
    memcpy(h.magic, STATE_MAGIC, sizeof STATE_MAGIC);
    put(s, &h, sizeof h);
    state_world v = {
        .def = wd->def, .stats = wd->stats, .time = wd->time, .solver_steps = solver_get_steps(wd->solver),
        .next_serial = wd->next_serial, .substep_serial = wd->islands.substep_serial, .pixel_clock = 0,
        .next_attach = wd->joints.next_attach, .edit_serial = wd->edits.serial,
        .body_capacity = wd->body_ids.capacity, .body_free = wd->body_ids.free_count, .body_count = wd->body_ids.live,
        .joint_capacity = wd->joints.ids.capacity, .joint_free = wd->joints.ids.free_count,
        .joint_count = wd->joints.ids.live, .contact_count = wd->contact_count, .event_count = wd->events.count,
        .edit_count = wd->edits.count, .forced_count = wd->forced.count, .edits_in_order = wd->edits.in_order,
    };
    contact_table_get_counts(wd, &v.table);
    const int64_t world_at = s->at;
    put(s, &v, sizeof v);
    write_pool(s, &wd->body_ids);
    write_pool(s, &wd->joints.ids);
    for (int32_t i = 0; i < wd->body_ids.capacity; i++)
        if (wd->bodies[i])
            write_body(s, wd, wd->bodies[i]);
    for (int32_t i = 0; i < wd->joints.ids.capacity; i++) {
        const joint *jt = wd->joints.items[i];
        if (!jt)
            continue;
        state_joint sj = {.j = *jt};
        memset(&sj.j.sj, 0, sizeof sj.j.sj);
        solver_joint_feedback(&jt->sj, sj.feedback);
        put(s, &sj, sizeof sj);
    }
    put(s, wd->contacts, (int64_t)wd->contact_count * (int64_t)sizeof(pp_contact));
    put(s, t->records, (int64_t)t->count * (int64_t)sizeof(contact_record));
    put(s, t->carry_order, (int64_t)t->carry_count * 4);
    put(s, wd->events.items, (int64_t)wd->events.count * (int64_t)sizeof(pp_event));
    put(s, wd->edits.heap, (int64_t)wd->edits.count * (int64_t)sizeof(timed_edit));
    put(s, wd->forced.slots, (int64_t)wd->forced.count * 4);
    if (s->p) { /* the clock after the stamps the bodies took */
        v.pixel_clock = wd->pixel_clock;
        memcpy(s->p + world_at, &v, sizeof v);
    }
}

PP_API pp_status pp_world_save_state(pp_world w, void *buffer, int64_t capacity, int64_t *size)
{
    static const char *fn = "pp_world_save_state";
    world *wd = world_lookup(w, fn);
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!size)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: size is NULL", fn);
    if (capacity < 0 || (capacity > 0 && !buffer))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: buffer is NULL with capacity %lld, or capacity is negative", fn,
                       (long long)capacity);
    pp_status st = keep_bases(wd, fn);
    if (st)
        return st;
    if (!wd->state_key)
        wd->state_key = new_state_key(wd);
    sink count = {NULL, 0};
    write_state(&count, wd);
    *size = count.at;
    if (capacity < count.at)
        return pp_fail(PP_ERR_LIMIT, "%s: the state takes %lld bytes, the buffer holds %lld", fn, (long long)count.at,
                       (long long)capacity);
    sink out = {buffer, 0};
    write_state(&out, wd);
    state_header h;
    memcpy(&h, buffer, sizeof h);
    h.size = (uint64_t)out.at;
    memcpy(buffer, &h, sizeof h);
    h.checksum = hash_bytes(HASH_START, (const uint8_t *)buffer + STATE_SUMMED, (size_t)out.at - STATE_SUMMED);
    h.seal = seal_of(wd, &h);
    memcpy(buffer, &h, sizeof h);
    return PP_OK;
}

/* ---- reading ------------------------------------------------------------------------------------------- */

typedef struct reader {
    const uint8_t *p;
    int64_t at, size;
} reader;

/* The next n bytes, or NULL past the end. */
static const uint8_t *take(reader *s, int64_t n)
{
    if (n < 0 || pad8(n) > s->size - s->at)
        return NULL;
    const uint8_t *p = s->p + s->at;
    s->at += pad8(n);
    return p;
}

/* The bytes checked and their sections found; nothing of a world is changed while reading. */
typedef struct state_view {
    state_world w;
    uint64_t world;
    const uint8_t *base;     /* the bytes */
    const uint8_t *body_gens, *body_free, *joint_gens, *joint_free;
    int64_t bodies_at, joints_at;
    const uint8_t *contacts, *records, *carry, *events, *edits, *forced;
    bool same;               /* the live world holds exactly the bodies and joints saved: copied in place */
    bool sealed;             /* the live world wrote these bytes (its seal): records sound, ids carry its tag */
} state_view;

static bool read_body(reader *s, body_view *v)
{
    const uint8_t *p = take(s, sizeof v->h);
    if (!p)
        return false;
    memcpy(&v->h, p, sizeof v->h);
    const pp_raster *r = &v->h.b.raster;
    if (r->width <= 0 || r->height <= 0 || r->width > PP_MAX_BITMAP_SIDE || r->height > PP_MAX_BITMAP_SIDE ||
        r->words_per_row != (r->width + 63) / 64 || r->tiles_x != (r->width + RASTER_TILE - 1) / RASTER_TILE ||
        r->tiles_y != (r->height + RASTER_TILE - 1) / RASTER_TILE)
        return false;
    if (v->h.has_base) {
        v->bits = v->weights = v->rows = v->tiles = v->sprite = NULL;
        if (!(v->bands = take(s, r->tiles_y)))
            return false;
        v->band_data = s->p + s->at;
        for (int32_t b = 0; b < r->tiles_y; b++) {
            const int64_t n = band_rows(r, b);
            if (v->bands[b] && (!take(s, n * r->words_per_row * 8) || (v->h.has_weights && !take(s, n * r->width)) ||
                                !take(s, n * 4) || !take(s, r->tiles_x)))
                return false;
        }
        return (v->cols = take(s, (int64_t)r->width * 4)) != NULL;
    }
    v->bits = take(s, bits_bytes(r));
    v->weights = v->h.has_weights ? take(s, plane_bytes(r)) : NULL;
    v->rows = take(s, (int64_t)r->height * 4);
    v->cols = take(s, (int64_t)r->width * 4);
    v->tiles = take(s, tile_bytes(r));
    v->sprite = v->h.has_sprite ? take(s, 4 * plane_bytes(r)) : NULL;
    return v->bits && v->rows && v->cols && v->tiles && (v->weights || !v->h.has_weights) &&
           (v->sprite || !v->h.has_sprite);
}

static bool count_ok(int32_t n, int32_t max) { return n >= 0 && n <= max; }

/* Whether a live body is the one saved, with the same structure: its values and planes can be copied over it. */
static bool body_same(const world *wd, const body_view *v)
{
    const body *sv = &v->h.b;
    const uint32_t slot = handle_slot(sv->handle.id);
    const body *bd = slot < (uint32_t)wd->body_ids.capacity ? wd->bodies[slot] : NULL;
    return bd && bd->handle.id == sv->handle.id && bd->type == sv->type && bd->fixed_rotation == sv->fixed_rotation &&
           bd->raster.width == sv->raster.width && bd->raster.height == sv->raster.height &&
           (bd->raster.weights != NULL) == (v->h.has_weights != 0) && (bd->sprite != NULL) == (v->h.has_sprite != 0) &&
           bd->serial == sv->serial && (bd->raster.changed_bands != NULL) == (v->h.has_base != 0) &&
           (!v->h.has_base || base_of(wd, bd->serial));
}

/* A live joint that is the one saved and attached as then: only its feedback differs. */
static bool joint_same(const world *wd, const state_joint *sj)
{
    const uint32_t slot = handle_slot(sj->j.handle.id);
    const joint *jt = slot < (uint32_t)wd->joints.ids.capacity ? wd->joints.items[slot] : NULL;
    return jt && memcmp(jt, &sj->j, offsetof(joint, sj)) == 0;
}

/* Every record's values checked (state_check.c), with the world that keeps big bodies' bases; nothing is used
 * before. */
static pp_status check_records(const char *fn, const state_view *v, const world *keeper)
{
    const state_world *w = &v->w;
    const char *why = state_world_problem(w);
    if (why)
        return pp_fail(PP_ERR_FORMAT, "%s: the state is invalid: %s", fn, why);
    uint8_t *marks = pp_calloc((size_t)w->body_capacity + (size_t)w->joint_capacity + 1, 1);
    uint64_t *keys = pp_malloc(((size_t)w->table.count + 1) * sizeof *keys);
    if (!marks || !keys) {
        pp_free(marks), pp_free(keys);
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory to check a state of %d bodies", fn, (int)w->body_count);
    }
    uint8_t *joint_marks = marks + w->body_capacity;
    const char *what = "its slots";
    why = state_pool_problem(v->body_gens, w->body_capacity, v->body_free, w->body_free, marks);
    if (!why)
        why = state_pool_problem(v->joint_gens, w->joint_capacity, v->joint_free, w->joint_free, joint_marks);
    reader s = {v->base, v->bodies_at, v->joints_at};
    for (int32_t i = 0; !why && i < w->body_count; i++) {
        body_view b;
        read_body(&s, &b);
        const uint32_t slot = handle_slot(b.h.b.handle.id);
        what = "a body";
        why = state_body_problem(&b, v->body_gens, w->body_capacity,
                                 b.h.has_base ? base_of(keeper, b.h.b.serial) : NULL, w->def.pixels_per_meter);
        if (!why && marks[slot])
            why = "its slot is free or taken twice";
        if (!why)
            marks[slot] = SLOT_BODY | (((const uint8_t *)&b.h)[offsetof(state_body, b.forced)] ? SLOT_FORCED : 0);
    }
    for (int32_t i = 0; !why && i < w->joint_count; i++) {
        state_joint sj;
        memcpy(&sj, v->base + v->joints_at + (int64_t)i * pad8(sizeof sj), sizeof sj);
        what = "a joint";
        why = state_joint_problem(&sj, v->joint_gens, w->joint_capacity);
        if (!why && joint_marks[sj.j.index])
            why = "its slot is free or taken twice";
        if (!why)
            joint_marks[sj.j.index] = SLOT_BODY;
    }
    if (!why) {
        what = "its contacts, events or edits";
        why = state_arrays_problem(w, marks, v->body_gens, v->contacts, v->records, v->carry, v->events, v->edits,
                                   v->forced, keys);
    }
    pp_free(marks), pp_free(keys);
    return why ? pp_fail(PP_ERR_FORMAT, "%s: the state is invalid: %s: %s", fn, what, why) : PP_OK;
}

/* Check the header and find every section; with `live`, also decide whether the bytes copy over it in place. */
static pp_status read_view(const char *fn, const void *buffer, int64_t size, const world *live, state_view *v)
{
    state_header h;
    if (!buffer || size < (int64_t)sizeof h)
        return pp_fail(buffer ? PP_ERR_FORMAT : PP_ERR_INVALID_ARGUMENT, "%s: %s", fn,
                       buffer ? "the bytes are too short to be a state" : "buffer is NULL");
    memcpy(&h, buffer, sizeof h);
    if (memcmp(h.magic, STATE_MAGIC, sizeof STATE_MAGIC) != 0)
        return pp_fail(PP_ERR_FORMAT, "%s: the bytes are not a world state", fn);
    if (h.version != STATE_VERSION || h.layout != layout_code())
        return pp_fail(PP_ERR_FORMAT, "%s: the state is of format version %u (layout %#x); this build reads %u (%#x)",
                       fn, (unsigned)h.version, (unsigned)h.layout, STATE_VERSION, (unsigned)layout_code());
    if (h.size != (uint64_t)size)
        return pp_fail(PP_ERR_FORMAT, "%s: the state is %lld bytes, %lld were given (truncated or padded)", fn,
                       (long long)h.size, (long long)size);
    if (hash_bytes(HASH_START, (const uint8_t *)buffer + STATE_SUMMED, (size_t)size - STATE_SUMMED) != h.checksum)
        return pp_fail(PP_ERR_FORMAT, "%s: the state's checksum does not match: the bytes were changed", fn);
    if (live && h.world != live->handle.id)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: the state was saved from world %#llx, not %#llx", fn,
                       (unsigned long long)h.world, (unsigned long long)live->handle.id);
    *v = (state_view){.world = h.world, .base = buffer};
    reader s = {buffer, pad8(sizeof h), size};
    const uint8_t *p = take(&s, sizeof v->w);
    bool ok = p != NULL;
    if (ok)
        memcpy(&v->w, p, sizeof v->w);
    const state_world *w = &v->w;
    ok = ok && count_ok(w->body_capacity, PP_MAX_BODIES) && count_ok(w->body_free, w->body_capacity) &&
         count_ok(w->body_count, w->body_capacity - w->body_free) && count_ok(w->joint_capacity, PP_MAX_BODIES) &&
         count_ok(w->joint_free, w->joint_capacity) && count_ok(w->joint_count, w->joint_capacity - w->joint_free) &&
         count_ok(w->contact_count, INT32_MAX / 2) && count_ok(w->table.count, INT32_MAX / 2) &&
         count_ok(w->table.awake, w->table.count) && count_ok(w->table.carry_count, w->table.count) &&
         count_ok(w->event_count, INT32_MAX / 2) && count_ok(w->edit_count, INT32_MAX / 2) &&
         count_ok(w->forced_count, w->body_count);
    ok = ok && (v->body_gens = take(&s, (int64_t)w->body_capacity * 4)) &&
         (v->body_free = take(&s, (int64_t)w->body_free * 4)) && (v->joint_gens = take(&s, (int64_t)w->joint_capacity * 4)) &&
         (v->joint_free = take(&s, (int64_t)w->joint_free * 4));
    v->bodies_at = s.at;
    for (int32_t i = 0; ok && i < w->body_count; i++) {
        body_view b;
        ok = read_body(&s, &b) && handle_slot(b.h.b.handle.id) < (uint32_t)w->body_capacity;
    }
    v->joints_at = s.at;
    for (int32_t i = 0; ok && i < w->joint_count; i++)
        ok = take(&s, sizeof(state_joint)) != NULL;
    ok = ok && (v->contacts = take(&s, (int64_t)w->contact_count * (int64_t)sizeof(pp_contact))) &&
         (v->records = take(&s, (int64_t)w->table.count * (int64_t)sizeof(contact_record))) &&
         (v->carry = take(&s, (int64_t)w->table.carry_count * 4)) &&
         (v->events = take(&s, (int64_t)w->event_count * (int64_t)sizeof(pp_event))) &&
         (v->edits = take(&s, (int64_t)w->edit_count * (int64_t)sizeof(timed_edit))) &&
         (v->forced = take(&s, (int64_t)w->forced_count * 4)) && s.at == size;
    if (!ok)
        return pp_fail(PP_ERR_FORMAT, "%s: the state's sections do not add up", fn);
    /* Bytes the live world sealed are bytes it wrote: their records were sound, and the bases they use are kept. */
    v->sealed = live && live->state_key && h.seal == seal_of(live, &h);
#ifdef PP_CHECKS
    const bool checked = true; /* and asserted to pass: what the seal stands for */
#else
    const bool checked = !v->sealed;
#endif
    pp_status st = checked ? check_records(fn, v, live ? live : world_find(h.world)) : PP_OK;
    PP_ASSERT(!v->sealed || st != PP_ERR_FORMAT);
    if (st || !live)
        return st;
    /* Checked: whether the records copy over the live ones in place, in a world made with the same settings (but
     * those set since, which set_arrays sets): else the saved world is made apart, with its own solver. */
    pp_world_def def = live->def;
    def.gravity = w->def.gravity, def.contact_events = w->def.contact_events;
    v->same = memcmp(&def, &w->def, sizeof def) == 0 && live->body_ids.live == w->body_count &&
              live->joints.ids.live == w->joint_count &&
              live->body_ids.capacity >= w->body_capacity && live->joints.ids.capacity >= w->joint_capacity;
    s.at = v->bodies_at;
    for (int32_t i = 0; v->same && i < w->body_count; i++) {
        body_view b;
        read_body(&s, &b);
        v->same = body_same(live, &b);
    }
    for (int32_t i = 0; v->same && i < w->joint_count; i++) {
        state_joint sj;
        memcpy(&sj, v->base + v->joints_at + (int64_t)i * pad8(sizeof sj), sizeof sj);
        v->same = joint_same(live, &sj);
    }
    return PP_OK;
}

/* ---- copying in ---------------------------------------------------------------------------------------- */

/* A saved id in the world with tag `tag`. */
static uint64_t retag(uint64_t id, uint32_t tag)
{
    return id ? handle_make(handle_kind_of(id), tag, handle_slot(id), handle_gen(id)) : 0;
}

static void retag_contact(pp_contact *c, uint32_t tag)
{
    c->a.id = retag(c->a.id, tag), c->b.id = retag(c->b.id, tag);
}

/* memcpy of n bytes, none from a NULL array when there are none. */
static void copy(void *to, const void *from, size_t n)
{
    if (n > 0)
        memcpy(to, from, n);
}

/* Room for the world's arrays the state fills; nothing changes on failure. */
static pp_status reserve_arrays(world *wd, const state_world *w, const char *fn)
{
    pp_status st = contact_table_reserve_state(wd, w->table.count, w->table.carry_count, fn);
    if (!st && (!ARRAY_RESERVE(wd->contacts, wd->contact_capacity, w->contact_count) ||
                !ARRAY_RESERVE(wd->events.items, wd->events.capacity, w->event_count) ||
                !ARRAY_RESERVE(wd->edits.heap, wd->edits.capacity, w->edit_count) ||
                !ARRAY_RESERVE(wd->forced.slots, wd->forced.capacity, w->forced_count)))
        st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for the state's contacts, events and edits", fn);
    return st;
}

/* The ids in the arrays set_arrays copied (contacts, the table's records, events, edits) into the world with tag
 * `tag`; bytes the world sealed hold its own tag already. */
static void retag_arrays(world *wd, const state_world *w, uint32_t tag)
{
    for (int32_t i = 0; i < w->contact_count; i++)
        retag_contact(&wd->contacts[i], tag);
    for (int32_t i = 0; i < w->table.count; i++) {
        contact_record *r = &wd->table.records[i];
        r->a = retag(r->a, tag), r->b = retag(r->b, tag);
        for (int k = 0; k < PP_MAX_CONTACTS_PER_PAIR; k++)
            retag_contact(&r->points[k], tag), retag_contact(&r->carry_points[k], tag);
    }
    for (int32_t i = 0; i < w->event_count; i++) {
        pp_event *e = &wd->events.items[i];
        e->body.id = retag(e->body.id, tag), e->other.id = retag(e->other.id, tag), e->joint.id = retag(e->joint.id, tag);
    }
    for (int32_t i = 0; i < w->edit_count; i++)
        wd->edits.heap[i].edit.body.id = retag(wd->edits.heap[i].edit.body.id, tag);
}

/* The world's arrays and values from the state (room reserved); ids into the world with `tag`. Cannot fail. */
static void set_arrays(world *wd, const state_view *v, uint32_t tag)
{
    const state_world *w = &v->w;
    copy(wd->contacts, v->contacts, (size_t)w->contact_count * sizeof(pp_contact));
    wd->contact_count = w->contact_count;
    contact_record *records = wd->table.records; /* copied in place and retagged, then taken as they are */
    copy(records, v->records, (size_t)w->table.count * sizeof *records);
    copy(wd->events.items, v->events, (size_t)w->event_count * sizeof(pp_event));
    copy(wd->edits.heap, v->edits, (size_t)w->edit_count * sizeof(timed_edit));
    if (!v->sealed || tag != world_tag(world_id_slot(v->world), world_id_gen(v->world)))
        retag_arrays(wd, w, tag);
    contact_table_set_state(wd, &w->table, records, (const int32_t *)v->carry);
    wd->events.count = w->event_count;
    wd->edits.count = w->edit_count, wd->edits.serial = w->edit_serial, wd->edits.in_order = w->edits_in_order != 0;
    copy(wd->forced.slots, v->forced, (size_t)w->forced_count * 4);
    wd->forced.count = w->forced_count;
    if (wd->def.gravity.x != w->def.gravity.x || wd->def.gravity.y != w->def.gravity.y)
        solver_set_gravity(wd->solver, dv(w->def.gravity.x, w->def.gravity.y));
    wd->def = w->def;
    wd->stats = w->stats;
    wd->time = w->time;
    solver_set_steps(wd->solver, w->solver_steps);
    wd->next_serial = w->next_serial;
    wd->islands.substep_serial = w->substep_serial;
    wd->joints.next_attach = w->next_attach;
    wd->pixel_clock = wd->pixel_clock > w->pixel_clock ? wd->pixel_clock : w->pixel_clock;
    wd->carry.active = false;
    awake_rebuild(wd); /* poses and sleep came back behind the awake set's back */
    contact_table_validate(wd);
}

/* A pool's generations and free stack as saved, over one at least as large (its arrays keep their room). */
static void set_pool(id_pool *p, const uint8_t *gens, int32_t capacity, const uint8_t *free_slots, int32_t free_count,
                     int32_t live)
{
    if (capacity > 0)
        memcpy(p->generations, gens, (size_t)capacity * 4);
    if (free_count > 0)
        memcpy(p->free_slots, free_slots, (size_t)free_count * 4);
    p->capacity = capacity, p->free_count = free_count, p->live = live;
}

/* Band b's planes from the bytes at p (has_weights: with weights) into r; the bytes after them. */
static const uint8_t *band_in(pp_raster *r, int32_t b, const uint8_t *p, bool has_weights)
{
    const int64_t y = (int64_t)b << RASTER_TILE_SHIFT, n = band_rows(r, b);
    memcpy(r->bits + y * r->words_per_row, p, (size_t)(n * r->words_per_row * 8));
    p += pad8(n * r->words_per_row * 8);
    if (has_weights) {
        memcpy(r->weights + y * r->width, p, (size_t)(n * r->width));
        p += pad8(n * r->width);
    }
    memcpy(r->row_count + y, p, (size_t)n * 4);
    p += pad8(n * 4);
    memcpy(r->tile_count + (int64_t)b * r->tiles_x, p, (size_t)r->tiles_x);
    return p + pad8(r->tiles_x);
}

/* Band b's planes from the base (no weight plane there: every weight 255). */
static void band_from_base(pp_raster *r, const state_base *base, int32_t b)
{
    const int64_t y = (int64_t)b << RASTER_TILE_SHIFT, n = band_rows(r, b);
    memcpy(r->bits + y * r->words_per_row, base->bits + y * r->words_per_row, (size_t)(n * r->words_per_row * 8));
    if (r->weights && base->weights)
        memcpy(r->weights + y * r->width, base->weights + y * r->width, (size_t)(n * r->width));
    else if (r->weights)
        memset(r->weights + y * r->width, 255, (size_t)(n * r->width));
    memcpy(r->row_count + y, base->rows + y, (size_t)n * 4);
    memcpy(r->tile_count + (int64_t)b * r->tiles_x, base->tiles + (int64_t)b * r->tiles_x, (size_t)r->tiles_x);
}

/* A big body's planes as saved: its bands changed in the state from the bytes, those changed only since from the
 * base, the rest as they are; then its column counts and band flags as saved. */
static void set_bands(pp_raster *r, const state_base *base, const body_view *v)
{
    const uint8_t *p = v->band_data;
    for (int32_t b = 0; b < r->tiles_y; b++)
        if (v->bands[b])
            p = band_in(r, b, p, v->h.has_weights);
        else if (r->changed_bands[b])
            band_from_base(r, base, b);
    memcpy(r->col_count, v->cols, (size_t)r->width * 4);
    raster_mark_dirty(r, 0, r->height); /* the GPU mirror; the band flags are set after it */
    memcpy(r->changed_bands, v->bands, (size_t)r->tiles_y);
}

/* The saved body's values over the live record bd, which keeps what the world holds by address; its planes are
 * copied when its pixels are not the saved ones. */
static void set_body(world *wd, body *bd, const body_view *v, uint32_t tag)
{
    const body live = *bd;
    const bool same_pixels = body_stamp(wd, bd) == v->h.b.pixel_stamp;
    *bd = v->h.b;
    bd->handle.id = retag(bd->handle.id, tag);
    pp_raster *r = &bd->raster;
    r->bits = live.raster.bits, r->weights = live.raster.weights, r->row_count = live.raster.row_count;
    r->col_count = live.raster.col_count, r->tile_count = live.raster.tile_count, r->outline = live.raster.outline;
    r->gpu_word = live.raster.gpu_word, r->dirty_y0 = live.raster.dirty_y0, r->dirty_y1 = live.raster.dirty_y1;
    r->version = live.raster.version;
    bd->sprite = live.sprite;
    bd->sb.body = live.sb.body, bd->sb.plane = live.sb.plane;
    body_update_com(bd); /* from the saved pose and mass, not the saved bytes */
    bd->awake_at = live.awake_at, bd->changed_at = live.changed_at;
    bd->stamp_version = live.stamp_version;
    r->changed_bands = live.raster.changed_bands;
    bd->joint_count = live.joint_count; /* the joints are the live ones, or counted again as they are made */
    if (same_pixels) { /* the live pixels stay, and what is counted of them */
        r->solid_count = live.raster.solid_count;
        r->x0 = live.raster.x0, r->y0 = live.raster.y0, r->x1 = live.raster.x1, r->y1 = live.raster.y1;
    }
    if (!same_pixels && v->h.has_base) {
        set_bands(r, base_of(wd, bd->serial), v);
    } else if (!same_pixels) {
        memcpy(r->bits, v->bits, (size_t)bits_bytes(r));
        if (r->weights)
            memcpy(r->weights, v->weights, (size_t)plane_bytes(r));
        memcpy(r->row_count, v->rows, (size_t)r->height * 4);
        memcpy(r->col_count, v->cols, (size_t)r->width * 4);
        memcpy(r->tile_count, v->tiles, (size_t)tile_bytes(r));
        raster_mark_dirty(r, 0, r->height);
    }
    if (!same_pixels)
        bd->stamp_version = ++r->version; /* what is derived from the bits (the outline) is made again */
    if (!bd->sb.body)
        return;
    if (live.mass.mass != bd->mass.mass || live.mass.inertia != bd->mass.inertia)
        solver_body_set_mass(wd->solver, &bd->sb, bd->mass.mass, bd->mass.inertia);
    solver_body_restore(&bd->sb, &v->h.ode);
}

/* The bytes over the world that saved them, whose bodies and joints are the ones saved (v->same). */
static pp_status restore_in_place(world *wd, const state_view *v, const char *fn)
{
    pp_status st = reserve_arrays(wd, &v->w, fn);
    if (st)
        return st;
    set_pool(&wd->body_ids, v->body_gens, v->w.body_capacity, v->body_free, v->w.body_free, v->w.body_count);
    set_pool(&wd->joints.ids, v->joint_gens, v->w.joint_capacity, v->joint_free, v->w.joint_free, v->w.joint_count);
    reader s = {v->base, v->bodies_at, v->joints_at};
    for (int32_t i = 0; i < v->w.body_count; i++) {
        body_view b;
        read_body(&s, &b);
        set_body(wd, wd->bodies[handle_slot(b.h.b.handle.id)], &b, wd->tag);
    }
    for (int32_t i = 0; i < v->w.joint_count; i++) {
        state_joint sj;
        memcpy(&sj, v->base + v->joints_at + (int64_t)i * pad8(sizeof sj), sizeof sj);
        solver_joint_set_feedback(&wd->joints.items[handle_slot(sj.j.handle.id)]->sj, sj.feedback);
    }
    set_arrays(wd, v, wd->tag);
    return PP_OK;
}

/* ---- building a world from the bytes ------------------------------------------------------------------- */

typedef struct order_entry {
    uint64_t key;            /* a body's serial, a joint's attach order */
    int64_t at;              /* its record's offset in the bytes */
} order_entry;

static int by_key(const void *x, const void *y)
{
    const uint64_t a = ((const order_entry *)x)->key, b = ((const order_entry *)y)->key;
    return (a > b) - (a < b);
}

/* A body's whole planes as saved: its record's, or a big body's base with the saved bands over it; NULL bits
 * without memory. The caller frees both. */
static void whole_planes(const body_view *v, const state_base *base, uint64_t **bits, uint8_t **weights)
{
    const pp_raster *r = &v->h.b.raster;
    *bits = pp_malloc((size_t)bits_bytes(r));
    *weights = v->h.has_weights ? pp_malloc((size_t)plane_bytes(r)) : NULL;
    if (!*bits || (v->h.has_weights && !*weights))
        return;
    if (!v->h.has_base) {
        memcpy(*bits, v->bits, (size_t)bits_bytes(r));
        if (*weights)
            memcpy(*weights, v->weights, (size_t)plane_bytes(r));
        return;
    }
    memcpy(*bits, base->bits, (size_t)bits_bytes(r));
    if (*weights && base->weights)
        memcpy(*weights, base->weights, (size_t)plane_bytes(r));
    else if (*weights)
        memset(*weights, 255, (size_t)plane_bytes(r));
    const uint8_t *p = v->band_data;
    for (int32_t b = 0; b < r->tiles_y; b++) {
        if (!v->bands[b])
            continue;
        const int64_t y = (int64_t)b << RASTER_TILE_SHIFT, n = band_rows(r, b);
        memcpy(*bits + y * r->words_per_row, p, (size_t)(n * r->words_per_row * 8));
        p += pad8(n * r->words_per_row * 8);
        if (*weights) {
            memcpy(*weights + y * r->width, p, (size_t)(n * r->width));
            p += pad8(n * r->width);
        }
        p += pad8(n * 4) + pad8(r->tiles_x);
    }
}

/* A body made from its record into its slot, then given the saved values. A big body's base is the world
 * `source`'s (the one that saved the bytes), and wd keeps a copy of it when `copy_bases`. */
static pp_status build_body(world *wd, const body_view *v, const world *source, bool copy_bases, const char *fn)
{
    const body *sv = &v->h.b;
    const pp_raster *r = &sv->raster;
    const state_base *base = v->h.has_base ? base_of(source, sv->serial) : NULL;
    if (v->h.has_base && !base)
        return pp_fail(PP_ERR_INVALID_ARGUMENT,
                       "%s: the state holds only the changed pixels of its %d × %d body, and the world that saved it, "
                       "which keeps the rest, is gone", fn, (int)r->width, (int)r->height);
    uint64_t *bits = NULL;
    uint8_t *weights = NULL, *mask = pp_malloc((size_t)plane_bytes(r));
    if (mask)
        whole_planes(v, base, &bits, &weights);
    pp_status st = PP_OK;
    if (!mask || !bits || (v->h.has_weights && !weights))
        st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for a %d × %d body", fn, (int)r->width, (int)r->height);
    for (int32_t y = 0; !st && y < r->height; y++)
        for (int32_t x = 0; x < r->width; x++)
            mask[(int64_t)y * r->width + x] = (bits[(int64_t)y * r->words_per_row + (x >> 6)] >> (x & 63)) & 1u ? 255 : 0;
    pp_body_def d = pp_body_def_default();
    d.type = sv->type, d.width = r->width, d.height = r->height, d.mask = mask, d.weights = weights;
    d.rgba = base ? base->sprite : v->sprite, d.density = (float)sv->density, d.fixed_rotation = sv->fixed_rotation;
    const uint32_t slot = handle_slot(sv->handle.id);
    body *bd = NULL;
    if (!st && (!id_pool_current(&wd->body_ids, slot, handle_gen(sv->handle.id)) || wd->bodies[slot]))
        st = pp_fail(PP_ERR_FORMAT, "%s: body slot %u is taken twice", fn, (unsigned)slot);
    if (!st)
        st = body_make(wd, &d, slot, fn, &bd);
    pp_free(mask), pp_free(bits), pp_free(weights);
    uint8_t *bands = NULL;
    if (!st && base && copy_bases && !base_of(wd, sv->serial)) { /* a loaded world keeps its own copy */
        const pp_raster kept = {.width = r->width, .height = r->height, .words_per_row = r->words_per_row,
                                .bits = base->bits, .weights = base->weights, .row_count = base->rows,
                                .tiles_x = r->tiles_x, .tiles_y = r->tiles_y, .tile_count = base->tiles};
        st = keep_base(wd, sv->serial, &kept, base->sprite, fn, &bands);
    } else if (!st && base && !(bands = pp_malloc((size_t)r->tiles_y))) {
        st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory", fn);
    }
    if (st)
        return st; /* a body made is freed with the world being built */
    if (bands)
        memcpy(bands, v->bands, (size_t)r->tiles_y);
    bd->raster.changed_bands = bands;
    bd->pixel_stamp = sv->pixel_stamp; /* the pixels made are the saved ones */
    bd->stamp_version = bd->raster.version;
    set_body(wd, bd, v, wd->tag);
    bd->joint_count = 0; /* counted again as the joints are made */
    return PP_OK;
}

/* The saved world into wd, a world just made from the saved settings, its ids carrying wd->tag. */
static pp_status build(world *wd, const state_view *v, const world *source, bool copy_bases, const char *fn)
{
    const state_world *w = &v->w;
    const uint8_t *base = v->base;
    wd->bodies = pp_calloc((size_t)w->body_capacity + 1, sizeof *wd->bodies);
    pp_status st = PP_OK;
    if (!wd->bodies || !id_pool_restore(&wd->body_ids, (const uint32_t *)v->body_gens, w->body_capacity,
                                        (const uint32_t *)v->body_free, w->body_free, pp_realloc))
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d body slots", fn, (int)w->body_capacity);
    order_entry *order = pp_malloc(((size_t)w->body_count + (size_t)w->joint_count + 1) * sizeof *order);
    if (!order)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d bodies", fn, (int)w->body_count);
    reader s = {base, v->bodies_at, v->joints_at};
    for (int32_t i = 0; i < w->body_count; i++) {
        body_view b;
        const int64_t at = s.at;
        read_body(&s, &b);
        order[i] = (order_entry){b.h.b.serial, at};
    }
    qsort(order, (size_t)w->body_count, sizeof *order, by_key); /* ODE's bodies made in creation order */
    for (int32_t i = 0; !st && i < w->body_count; i++) {
        body_view b;
        s.at = order[i].at;
        read_body(&s, &b);
        st = build_body(wd, &b, source, copy_bases, fn);
    }
    if (!st && w->joint_capacity > 0)
        st = joint_table_restore(wd, (const uint32_t *)v->joint_gens, w->joint_capacity,
                                 (const uint32_t *)v->joint_free, w->joint_free, fn);
    if (!st && w->joint_capacity > 0) {
        for (int32_t i = 0; i < w->joint_count; i++) {
            const int64_t at = v->joints_at + (int64_t)i * pad8(sizeof(state_joint));
            state_joint sj;
            memcpy(&sj, base + at, sizeof sj);
            order[i] = (order_entry){sj.j.attach_order, at};
        }
        qsort(order, (size_t)w->joint_count, sizeof *order, by_key); /* ODE lists a body's joints by attach order */
        for (int32_t i = 0; !st && i < w->joint_count; i++) {
            joint *jt = pp_calloc(1, sizeof *jt);
            if (!jt) {
                st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for a joint", fn);
                break;
            }
            state_joint sj;
            memcpy(&sj, base + order[i].at, sizeof sj);
            *jt = sj.j;
            jt->handle.id = retag(jt->handle.id, wd->tag);
            jt->def.body_a.id = retag(jt->def.body_a.id, wd->tag), jt->def.body_b.id = retag(jt->def.body_b.id, wd->tag);
            const uint32_t slot = handle_slot(jt->handle.id);
            if (!id_pool_current(&wd->joints.ids, slot, handle_gen(jt->handle.id)) || wd->joints.items[slot])
                st = pp_fail(PP_ERR_FORMAT, "%s: joint slot %u is taken twice", fn, (unsigned)slot);
            else if (joint_check_def(wd, fn, &jt->def)) { /* its def's message, as corrupt bytes */
                char why[512];
                snprintf(why, sizeof why, "%s", pp_last_error());
                st = pp_fail(PP_ERR_FORMAT, "%s (a joint of the state)", why);
            }
            if (st || (st = joint_restore(wd, jt, sj.feedback, fn)))
                pp_free(jt);
        }
    }
    pp_free(order);
    if (!st)
        st = reserve_arrays(wd, w, fn);
    if (!st)
        set_arrays(wd, v, wd->tag);
    return st;
}

/* A new world holding the state, its ids carrying `tag` (-1: its own; 0 is a tag too); big bodies' bases from
 * `source`, copied unless the world is to be swapped into source (tag not -1). */
static pp_status build_world(const state_view *v, int64_t tag, const world *source, const char *fn, world **out)
{
    pp_world_def d = v->w.def;
    world *wd = NULL;
    pp_status st = world_make(&d, fn, &wd);
    if (st)
        return st;
    const uint32_t own = wd->tag;
    if (tag >= 0)
        wd->tag = (uint32_t)tag;
    if ((st = build(wd, v, source, tag < 0, fn))) {
        wd->tag = own;
        world_free(wd);
        return st;
    }
    *out = wd;
    return PP_OK;
}

PP_API pp_status pp_world_restore_state(pp_world w, const void *buffer, int64_t size)
{
    static const char *fn = "pp_world_restore_state";
    world *wd = world_lookup(w, fn);
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    state_view v;
    pp_status st = read_view(fn, buffer, size, wd, &v);
    if (st)
        return st;
    if (v.same)
        return restore_in_place(wd, &v, fn);
    /* Bodies or joints were made, destroyed or changed since: the saved world is built apart and swapped in. */
    world *built = NULL;
    if ((st = build_world(&v, wd->tag, wd, fn, &built)))
        return st;
    world old = *wd;
    state_base *own = built->bases; /* none: it used wd's */
    const int32_t own_count = built->base_count, own_capacity = built->base_capacity;
    const uint32_t slot = built->slot;
    const uint32_t tag = world_tag(built->slot, world_id_gen(built->handle.id));
    const pp_world handle = built->handle;
    *wd = *built;
    wd->slot = old.slot, wd->tag = old.tag, wd->handle = old.handle;
    wd->pixel_clock = old.pixel_clock > wd->pixel_clock ? old.pixel_clock : wd->pixel_clock;
    wd->bases = old.bases, wd->base_count = old.base_count, wd->base_capacity = old.base_capacity; /* kept on */
    wd->state_key = old.state_key; /* its sealed bytes stay its own */
    *built = old;
    built->slot = slot, built->tag = tag, built->handle = handle;
    built->bases = own, built->base_count = own_count, built->base_capacity = own_capacity;
    world_free(built);
    return PP_OK;
}

PP_API pp_status pp_world_load_state(const void *buffer, int64_t size, pp_world *out)
{
    static const char *fn = "pp_world_load_state";
    if (!out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: out is NULL", fn);
    state_view v;
    pp_status st = read_view(fn, buffer, size, NULL, &v);
    world *wd = NULL;
    /* Big bodies' untouched pixels are kept by the world that saved the bytes, if it still exists. */
    const world *source = st ? NULL : world_find(v.world);
    if (!st && !(st = build_world(&v, -1, source, fn, &wd)))
        *out = wd->handle;
    return st;
}
