/* The one slot pool behind every handle kind (lib/core/id_pool.h, header-only): the order slots come out in,
 * generations that make old handles stale, the exact undo of a take, a full pool and a failed growth. */
#include "helpers.h"

#include "id_pool.h"

#include <stdlib.h>

PP_TEST_SUITE(id_pool);

static int reallocs_left = -1; /* -1: never fail */

static void *test_realloc(void *ptr, size_t size)
{
    if (reallocs_left == 0)
        return NULL;
    if (reallocs_left > 0)
        reallocs_left--;
    return realloc(ptr, size);
}

static void test_free(void *ptr) { free(ptr); }

Test(id_pool, slots_come_out_lowest_first_and_the_last_freed_is_taken_again)
{
    id_pool p = {0};
    int *items = NULL;
    uint32_t slot;
    for (uint32_t k = 0; k < 3; k++) {
        cr_assert_eq(ID_POOL_TAKE(&p, 1000, items, test_realloc, &slot), ID_POOL_TAKEN);
        cr_assert_eq(slot, k, "take %u gave slot %u", k, slot);
        cr_assert(id_pool_current(&p, slot, 1));
    }
    cr_assert_eq(p.capacity, 64);
    cr_assert_eq(p.live, 3);
    for (int32_t i = 0; i < p.capacity; i++)
        cr_assert_eq(items[i], 0, "a new slot's item is zeroed");
    id_pool_release(&p, 0);
    id_pool_release(&p, 2);
    cr_assert_eq(p.live, 1);
    cr_assert(!id_pool_current(&p, 0, 1), "a freed slot's old handle is stale");
    cr_assert(id_pool_current(&p, 0, 2));
    cr_assert_eq(ID_POOL_TAKE(&p, 1000, items, test_realloc, &slot), ID_POOL_TAKEN);
    cr_assert_eq(slot, 2, "the slot freed last comes back first");
    cr_assert_eq(ID_POOL_TAKE(&p, 1000, items, test_realloc, &slot), ID_POOL_TAKEN);
    cr_assert_eq(slot, 0);
    cr_assert_eq(ID_POOL_TAKE(&p, 1000, items, test_realloc, &slot), ID_POOL_TAKEN);
    cr_assert_eq(slot, 3, "then the lowest never used");
    cr_assert(!id_pool_current(&p, 64, 1), "a slot past the pool is never current");
    id_pool_free(&p, test_free);
    free(items);
}

Test(id_pool, an_untake_puts_the_slot_back_exactly)
{
    id_pool p = {0};
    void **items = NULL;
    uint32_t a, b;
    cr_assert_eq(ID_POOL_TAKE(&p, 1000, items, test_realloc, &a), ID_POOL_TAKEN);
    cr_assert_eq(ID_POOL_TAKE(&p, 1000, items, test_realloc, &b), ID_POOL_TAKEN);
    const int32_t free_before = p.free_count;
    id_pool_untake(&p, b);
    cr_assert_eq(p.generations[b], 1, "an untake keeps the generation");
    cr_assert_eq(p.free_count, free_before + 1);
    cr_assert_eq(p.live, 1);
    uint32_t again;
    cr_assert_eq(ID_POOL_TAKE(&p, 1000, items, test_realloc, &again), ID_POOL_TAKEN);
    cr_assert_eq(again, b, "the same slot comes out next");
    id_pool_free(&p, test_free);
    free(items);
}

Test(id_pool, generations_wrap_to_one_and_never_reach_zero)
{
    id_pool p = {0};
    char *items = NULL;
    uint32_t slot;
    cr_assert_eq(ID_POOL_TAKE(&p, 1000, items, test_realloc, &slot), ID_POOL_TAKEN);
    p.generations[slot] = HANDLE_GEN_MAX;
    id_pool_release(&p, slot);
    cr_assert_eq(p.generations[slot], 1);
    id_pool_free(&p, test_free);
    free(items);
}

Test(id_pool, a_full_pool_and_a_failed_growth_change_nothing)
{
    id_pool p = {0};
    double *items = NULL;
    uint32_t slot;
    for (int k = 0; k < 64; k++)
        cr_assert_eq(ID_POOL_TAKE(&p, 100, items, test_realloc, &slot), ID_POOL_TAKEN);
    for (int fail_after = 0; fail_after < 3; fail_after++) { /* generations, free stack, items */
        reallocs_left = fail_after;
        cr_assert_eq(ID_POOL_TAKE(&p, 100, items, test_realloc, &slot), ID_POOL_NO_MEMORY);
        reallocs_left = -1;
        cr_assert_eq(p.capacity, 64);
        cr_assert_eq(p.free_count, 0);
        cr_assert_eq(p.live, 64);
    }
    for (int k = 64; k < 100; k++) /* grows to the cap, 100, not 128 */
        cr_assert_eq(ID_POOL_TAKE(&p, 100, items, test_realloc, &slot), ID_POOL_TAKEN);
    cr_assert_eq(p.capacity, 100);
    cr_assert_eq(ID_POOL_TAKE(&p, 100, items, test_realloc, &slot), ID_POOL_FULL);
    cr_assert_eq(p.live, 100);
    id_pool_free(&p, test_free);
    free(items);
}

Test(id_pool, a_fixed_pool_is_full_once_every_slot_is_taken)
{
    uint32_t gens[4], free_slots[4];
    id_pool p;
    id_pool_init_fixed(&p, gens, free_slots, 4);
    uint32_t slot;
    for (uint32_t k = 0; k < 4; k++) {
        cr_assert(id_pool_take_free(&p, &slot));
        cr_assert_eq(slot, k);
    }
    cr_assert(!id_pool_take_free(&p, &slot));
    id_pool_release(&p, 1);
    cr_assert(id_pool_take_free(&p, &slot));
    cr_assert_eq(slot, 1);
    cr_assert_eq(gens[1], 2);
}
