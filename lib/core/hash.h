/* One 64-bit hash of bytes for the whole library: the world's state hash (pp_world_get_hash), the state bytes'
 * checksum and the step transaction's PP_CHECKS fingerprint. xxHash's XXH3 (Debian's libxxhash-dev), inlined from
 * its header so that the library needs no xxHash at run time; it hashes a terrain's mask at memory speed. Not
 * cryptographic. */
#ifndef PP_HASH_H
#define PP_HASH_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define XXH_INLINE_ALL
#include <xxhash.h>

#define HASH_START 0xcbf29ce484222325ull

/* n bytes hashed onto h: XXH3 seeded with h, the same value on every machine and whatever its vector units. */
static inline uint64_t hash_bytes(uint64_t h, const void *data, size_t n)
{
    return XXH3_64bits_withSeed(n ? data : "", n, h); /* no NULL, not even for no bytes */
}

/* One value hashed onto h by its bytes (a plain value without padding). */
#define HASH_VALUE(h, v) ((h) = hash_bytes((h), &(v), sizeof(v)))

#endif
