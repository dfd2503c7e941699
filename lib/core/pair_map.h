/* A map from a pair of body slots (a << 32 | b) to an index: open addressing with linear probing, at most half
 * full, deletion by shifting back (no tombstones). The contact table finds its records by it, the carried
 * pairs theirs. It grows only through pair_map_reserve, so a set after a reserve cannot fail. */
#ifndef PP_PAIR_MAP_H
#define PP_PAIR_MAP_H

#include <stdbool.h>
#include <stdint.h>

typedef struct pair_map_entry {
    uint64_t key;
    int32_t value;           /* −1: the slot is empty */
    int32_t reserved;
} pair_map_entry;

typedef struct pair_map {
    pair_map_entry *slots;   /* a power of two of them, or none */
    int32_t capacity;
    int32_t count;           /* keys held */
} pair_map;

/* The key of a pair of slots. */
static inline uint64_t pair_key(uint32_t a, uint32_t b) { return (uint64_t)a << 32 | b; }

/* Room for n keys (capacity at least 2n), rehashing what it holds; false, with nothing changed, without memory. */
bool pair_map_reserve(pair_map *m, int32_t n);
/* The key's value, or −1. */
int32_t pair_map_get(const pair_map *m, uint64_t key);
/* Set the key's value (a new key needs room reserved). */
void pair_map_set(pair_map *m, uint64_t key, int32_t value);
/* Take a present key out. */
void pair_map_remove(pair_map *m, uint64_t key);
/* Empty it, keeping its room (free when it holds nothing). */
void pair_map_clear(pair_map *m);
void pair_map_free(pair_map *m);

#endif
