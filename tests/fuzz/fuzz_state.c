/* libFuzzer target: world state bytes through pp_world_restore_state and pp_world_load_state. A few small worlds
 * are saved once; an input picks one state and edits its bytes (overwrites, interesting words, cuts, insertions),
 * then the checksum is recomputed so that the edit reaches the parser, as a peer's buggy or hostile bytes would.
 * A refused restore must leave the world's hash as it was; accepted bytes are stepped, saved and destroyed. */
#include "fuzz_common.h"

#include "hash.h" /* the checksum the header carries (lib/core) */

/* The header's fields as lib/io/state.c lays them out: the checksum covers every byte after the first 24 (the
 * magic, itself and the seal, which the edited bytes keep: a seal for other bytes, so they are checked in full). */
#define STATE_CHECKSUM_AT 8
#define STATE_SUMMED 24
#define STATE_SIZE_AT 32
#define STATE_WORLD_AT 40
#define STATE_HEADER 48

/* Harness caps, not library limits: edited bytes past this size, and steps per accepted state. */
#define FUZZ_STATE_MAX_BYTES (4 << 20)
#define FUZZ_STATE_STEPS 3
#define FUZZ_STATE_WORLDS 4

static struct saved {
    pp_world w;
    uint8_t *bytes;
    int64_t size;
} saved[FUZZ_STATE_WORLDS];

static void must(pp_status st, const char *what)
{
    if (st != PP_OK) {
        fprintf(stderr, "fuzz_state: %s: %s\n", what, pp_last_error());
        abort();
    }
}

static uint8_t solid[256 * 256]; /* a full mask for every rectangle */

static pp_body rect(pp_world w, pp_body_type type, float x, float y, int32_t width, int32_t height)
{
    pp_body_def d = pp_body_def_default();
    d.type = type, d.position = (pp_vec2){x, y}, d.width = width, d.height = height, d.mask = solid;
    pp_body b = {0};
    must(pp_body_create(w, &d, &b), "body");
    return b;
}

static void save(int k)
{
    int64_t n = 0;
    pp_world_save_state(saved[k].w, NULL, 0, &n);
    saved[k].bytes = malloc((size_t)n);
    must(pp_world_save_state(saved[k].w, saved[k].bytes, n, &saved[k].size), "save");
}

/* Crates on a ground and on a big body (256 × 256 px, kept once by the world), joined crates, a sleeping crate,
 * contacts carried, a scheduled edit and unread contact events; saved after an edit of the big body, so that its
 * state holds changed bands. Variant 3 has destroyed a body and a joint (free slots). */
static void busy_world(int k)
{
    pp_world_def wd = pp_world_def_default();
    wd.contact_events = 1;
    must(pp_world_create(&wd, &saved[k].w), "world");
    pp_world w = saved[k].w;
    rect(w, PP_BODY_STATIC, 100, 200, 200, 20);
    const pp_body big = rect(w, PP_BODY_STATIC, 400, 330, 256, 256);
    pp_body crate[5];
    for (int i = 0; i < 5; i++)
        crate[i] = rect(w, PP_BODY_DYNAMIC, 30.0f + 30.0f * i + (i == 4 ? 300 : 0), 170, 12, 10 + 2 * i);
    pp_joint_def jd = pp_joint_def_default(PP_JOINT_REVOLUTE);
    jd.body_a = crate[0], jd.body_b = crate[1], jd.anchor_a = (pp_vec2){45, 170};
    pp_joint joint = {0};
    must(pp_joint_create(w, &jd, &joint), "joint");
    for (int i = 0; i < 20; i++)
        must(pp_world_step(w, 1.0f / 60), "step");
    must(pp_body_set_awake(w, crate[3], 0), "sleep");
    int64_t n = 0;
    pp_world_save_state(w, NULL, 0, &n); /* the big body's base kept: later edits are its changed bands */
    must(pp_world_erase_circle(w, (pp_vec2){420, 220}, 12, NULL), "erase");
    const pp_timed_edit e = {.time = 5.0, .type = PP_EDIT_PAINT_CIRCLE, .weight = 200, .body = big,
                             .center = {400, 300}, .radius = 6};
    must(pp_world_schedule_edit(w, &e), "schedule");
    if (k == 3) {
        must(pp_joint_destroy(w, joint), "joint destroy");
        must(pp_body_destroy(w, crate[2]), "body destroy");
    }
    must(pp_world_step(w, 1.0f / 60), "step");
}

/* A kinematic body with a sprite and a dynamic one with weights, in a world of its own settings. */
static void planes_world(int k)
{
    pp_world_def wd = pp_world_def_default();
    wd.gravity = (pp_vec2){0, 50};
    must(pp_world_create(&wd, &saved[k].w), "world");
    uint8_t rgba[16 * 8 * 4], weights[10 * 10];
    for (int i = 0; i < 16 * 8 * 4; i++)
        rgba[i] = (uint8_t)(i * 37);
    for (int i = 0; i < 10 * 10; i++)
        weights[i] = (uint8_t)(1 + i * 7);
    pp_body_def d = pp_body_def_default();
    d.type = PP_BODY_KINEMATIC, d.width = 16, d.height = 8, d.rgba = rgba, d.linear_velocity = (pp_vec2){5, 0};
    pp_body b;
    must(pp_body_create(saved[k].w, &d, &b), "sprite body");
    d = pp_body_def_default();
    d.position = (pp_vec2){0, -20}, d.width = 10, d.height = 10, d.mask = solid, d.weights = weights;
    must(pp_body_create(saved[k].w, &d, &b), "weighted body");
    for (int i = 0; i < 5; i++)
        must(pp_world_step(saved[k].w, 1.0f / 60), "step");
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    fuzz_no_gpu();
    memset(solid, 255, sizeof solid);
    busy_world(0);
    pp_world_def wd = pp_world_def_default();
    must(pp_world_create(&wd, &saved[1].w), "world"); /* empty */
    planes_world(2);
    busy_world(3);
    for (int k = 0; k < FUZZ_STATE_WORLDS; k++)
        save(k);
    return 0;
}

typedef struct input {
    const uint8_t *p;
    size_t n;
} input;

static uint8_t in8(input *r)
{
    if (!r->n)
        return 0;
    r->n--;
    return *r->p++;
}

static uint32_t in24(input *r)
{
    const uint32_t a = in8(r), b = in8(r);
    return a | b << 8 | (uint32_t)in8(r) << 16;
}

/* Words that sit on the edges of the checks: counts, sizes, ids, floats. */
static const uint32_t interesting[16] = {0,          1,          0xffffffffu, 0x7fffffffu, 0x80000000u, 2,
                                         0x10000,    0x3f800000, 0x7fc00000,  0xff800000,  16384,       16385,
                                         255,        256,        0x100000,    0x100001};

/* The input's edits of the state bytes (*buf, *size, room *cap). */
static void mutate(input *r, uint8_t **buf, int64_t *size, int64_t *cap)
{
    while (r->n) {
        const uint8_t c = in8(r);
        const uint32_t off = in24(r);
        const int64_t at = *size ? (int64_t)(off % (uint64_t)*size) : 0;
        const int n = (c >> 2) + 1;
        switch (c & 3) {
        case 0: /* overwrite n bytes */
            for (int i = 0; i < n && at + i < *size; i++)
                (*buf)[at + i] = in8(r);
            break;
        case 1: { /* an interesting word at an aligned offset */
            const int64_t a = at & ~(int64_t)3;
            const uint32_t v = interesting[(c >> 2) & 15];
            if (a + 4 <= *size)
                memcpy(*buf + a, &v, 4);
            break;
        }
        case 2: /* cut */
            *size = at;
            break;
        default: /* insert n bytes (at the end: extend) */
            if (*size + n > FUZZ_STATE_MAX_BYTES)
                break;
            if (*size + n > *cap) {
                *cap = (*size + n) * 2;
                *buf = realloc(*buf, (size_t)*cap);
            }
            memmove(*buf + at + n, *buf + at, (size_t)(*size - at));
            for (int i = 0; i < n; i++)
                (*buf)[at + i] = in8(r);
            *size += n;
        }
    }
}

static uint64_t hash_of(pp_world w)
{
    uint64_t h = 0;
    FUZZ_CHECK(ST(pp_world_get_hash(w, &h)) == PP_OK, "hash");
    return h;
}

static int32_t body_count(pp_world w)
{
    int32_t n = -1;
    FUZZ_CHECK(ST(pp_world_get_bodies(w, NULL, 0, &n)) == PP_OK && n >= 0, "bodies");
    return n;
}

/* A refusal: a status for bad bytes, a message naming the call. UNSUPPORTED: settings asking for the GPU. */
static void refused(pp_status st, const char *fn)
{
    FUZZ_CHECK(st == PP_ERR_FORMAT || st == PP_ERR_INVALID_ARGUMENT || st == PP_ERR_OUT_OF_MEMORY ||
                   st == PP_ERR_LIMIT || st == PP_ERR_UNSUPPORTED,
               "%s: %d", fn, (int)st);
    FUZZ_CHECK(strncmp(pp_last_error(), fn, strlen(fn)) == 0, "%s: the message does not name the call", fn);
}

/* Accepted bytes make a world that steps, reads out and saves. */
static void use(pp_world w)
{
    for (int i = 0; i < FUZZ_STATE_STEPS && !fuzz_too_fast(w); i++) {
        const pp_status s = ST(pp_world_step(w, 1.0f / 60));
        /* LIMIT: a step past what a float holds is refused and undone, as from any valid state. */
        FUZZ_CHECK(s == PP_OK || s == PP_ERR_UNSUPPORTED || s == PP_ERR_OUT_OF_MEMORY || s == PP_ERR_LIMIT, "step: %d",
                   (int)s);
        int32_t n = 0;
        pp_event ev[4];
        ST(pp_world_get_events(w, ev, 4, &n));
        ST(pp_world_get_contacts(w, NULL, 0, &n));
    }
    int64_t n = 0;
    FUZZ_CHECK(ST(pp_world_save_state(w, NULL, 0, &n)) == PP_ERR_LIMIT && n > 0, "size of the state");
    uint8_t *again = malloc((size_t)n);
    FUZZ_CHECK(ST(pp_world_save_state(w, again, n, &n)) == PP_OK, "save what was restored");
    FUZZ_CHECK(ST(pp_world_restore_state(w, again, n)) == PP_OK, "restore what was saved");
    free(again);
}

/* Input: the state (byte 0), flags (byte 1: 1 step the target first, 2 destroy a body of it first, 4 keep the
 * size field as edited), then edits of 4 bytes each (kind and length, a 24-bit offset) and their bytes. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    input r = {data, size};
    const struct saved *s = &saved[in8(&r) % FUZZ_STATE_WORLDS];
    const uint8_t flags = in8(&r);
    /* The target: a world loaded from the state, so that each input starts from the same one. */
    pp_world w = {0};
    FUZZ_CHECK(ST(pp_world_load_state(s->bytes, s->size, &w)) == PP_OK, "load the saved state");
    if (flags & 1)
        FUZZ_CHECK(ST(pp_world_step(w, 1.0f / 60)) == PP_OK, "step");
    if (flags & 2 && body_count(w) > 0) {
        pp_body b;
        int32_t n = 1;
        FUZZ_CHECK(ST(pp_world_get_bodies(w, &b, 1, &n)) == PP_OK, "bodies");
        FUZZ_CHECK(ST(pp_body_destroy(w, b)) == PP_OK, "destroy");
    }
    int64_t n = s->size, cap = s->size + 64;
    uint8_t *buf = malloc((size_t)cap);
    memcpy(buf, s->bytes, (size_t)n);
    memcpy(buf + STATE_WORLD_AT, &w.id, 8); /* the bytes as the target's own, so that they reach its parser */
    mutate(&r, &buf, &n, &cap);
    if (n >= STATE_HEADER) {
        const uint64_t total = (uint64_t)n;
        if (!(flags & 4))
            memcpy(buf + STATE_SIZE_AT, &total, 8);
        const uint64_t sum = hash_bytes(HASH_START, buf + STATE_SUMMED, (size_t)n - STATE_SUMMED);
        memcpy(buf + STATE_CHECKSUM_AT, &sum, 8);
    }

    pp_world loaded = {0};
    const pp_status ls = ST(pp_world_load_state(buf, n, &loaded));
    if (ls == PP_OK) {
        use(loaded);
        FUZZ_CHECK(ST(pp_world_destroy(loaded)) == PP_OK, "destroy");
    } else {
        refused(ls, "pp_world_load_state");
    }

    const uint64_t before = hash_of(w);
    const int32_t bodies = body_count(w);
    const pp_status rs = ST(pp_world_restore_state(w, buf, n));
    if (rs == PP_OK) {
        use(w);
    } else {
        refused(rs, "pp_world_restore_state");
        FUZZ_CHECK(hash_of(w) == before && body_count(w) == bodies, "a refused restore changed the world");
    }
    free(buf);
    FUZZ_CHECK(ST(pp_world_destroy(w)) == PP_OK, "destroy");
    return 0;
}
