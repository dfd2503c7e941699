/* The pair map (pair_map.h). */
#include "pair_map.h"
#include "alloc.h"
#include "check.h"

#define PAIR_MAP_MIN 64

/* Fibonacci hashing: the product's high bits, spread over the slots. */
static int32_t home_of(uint64_t key, int32_t capacity)
{
    return (int32_t)((key * 0x9e3779b97f4a7c15ull) >> 32) & (capacity - 1);
}

/* The key's slot, or the empty slot where it would go. */
static int32_t slot_of(const pair_map *m, uint64_t key)
{
    const int32_t mask = m->capacity - 1;
    for (int32_t h = home_of(key, m->capacity);; h = (h + 1) & mask)
        if (m->slots[h].value < 0 || m->slots[h].key == key)
            return h;
}

bool pair_map_reserve(pair_map *m, int32_t n)
{
    if ((int64_t)2 * n <= m->capacity)
        return true;
    int32_t cap = PAIR_MAP_MIN;
    while (cap < 2 * n)
        cap *= 2;
    pair_map grown = {pp_malloc((size_t)cap * sizeof *grown.slots), cap, 0};
    if (!grown.slots)
        return false;
    for (int32_t h = 0; h < cap; h++)
        grown.slots[h].value = -1;
    for (int32_t h = 0; h < m->capacity; h++)
        if (m->slots[h].value >= 0)
            pair_map_set(&grown, m->slots[h].key, m->slots[h].value);
    pp_free(m->slots);
    *m = grown;
    return true;
}

int32_t pair_map_get(const pair_map *m, uint64_t key) { return m->capacity ? m->slots[slot_of(m, key)].value : -1; }

void pair_map_set(pair_map *m, uint64_t key, int32_t value)
{
    PP_ASSERT(m->capacity > 0 && value >= 0);
    pair_map_entry *e = &m->slots[slot_of(m, key)];
    m->count += e->value < 0;
    PP_ASSERT(2 * m->count <= m->capacity);
    e->key = key, e->value = value;
}

void pair_map_remove(pair_map *m, uint64_t key)
{
    const int32_t mask = m->capacity - 1;
    int32_t hole = slot_of(m, key);
    PP_ASSERT(m->slots[hole].value >= 0);
    for (int32_t h = (hole + 1) & mask; m->slots[h].value >= 0; h = (h + 1) & mask) {
        const int32_t home = home_of(m->slots[h].key, m->capacity);
        /* It may fill the hole unless its home lies cyclically in (hole, h]. */
        const bool stays = hole <= h ? (home > hole && home <= h) : (home > hole || home <= h);
        if (!stays) {
            m->slots[hole] = m->slots[h];
            hole = h;
        }
    }
    m->slots[hole].value = -1;
    m->count--;
}

void pair_map_clear(pair_map *m)
{
    for (int32_t h = 0; m->count > 0 && h < m->capacity; h++)
        m->slots[h].value = -1;
    m->count = 0;
}

void pair_map_free(pair_map *m)
{
    pp_free(m->slots);
    *m = (pair_map){0};
}
