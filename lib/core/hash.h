/* One 64-bit hash of bytes for the whole library: the world's state hash (pp_world_get_hash), the state bytes'
 * checksum and the step transaction's PP_CHECKS fingerprint. Four lanes of 8-byte words, so that a terrain's
 * mask hashes at memory speed; not cryptographic. */
#ifndef PP_HASH_H
#define PP_HASH_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define HASH_START 0xcbf29ce484222325ull

static inline uint64_t hash_lane(uint64_t h, uint64_t w)
{
    h = (h ^ w) * 0x9e3779b97f4a7c15ull;
    return h ^ (h >> 29);
}

/* n bytes hashed onto h; the same bytes give the same value on any machine of the same byte order. */
static inline uint64_t hash_bytes(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    uint64_t lane[4] = {h, h ^ 0x5851f42d4c957f2dull, h ^ 0x14057b7ef767814full, h ^ 0x2545f4914f6cdd1dull};
    size_t i = 0;
    for (; i + 32 <= n; i += 32)
        for (int k = 0; k < 4; k++) {
            uint64_t w;
            memcpy(&w, p + i + 8 * k, 8);
            lane[k] = hash_lane(lane[k], w);
        }
    for (; i + 8 <= n; i += 8) {
        uint64_t w;
        memcpy(&w, p + i, 8);
        lane[0] = hash_lane(lane[0], w);
    }
    uint64_t tail = n; /* the length too, so that trailing zero bytes count */
    for (size_t k = 0; i < n; i++, k++)
        tail ^= (uint64_t)p[i] << (8 * k);
    h = hash_lane(lane[0], tail);
    for (int k = 1; k < 4; k++)
        h = hash_lane(h, lane[k]);
    return h;
}

/* One value hashed onto h by its bytes (a plain value without padding). */
#define HASH_VALUE(h, v) ((h) = hash_bytes((h), &(v), sizeof(v)))

#endif
