/* Every allocation the library makes itself goes through here, so a host's allocator (pp_set_allocator)
 * sees it and a test can make any one of them fail. ODE and cJSON keep their own allocators. */
#ifndef PP_ALLOC_H
#define PP_ALLOC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* malloc, calloc (overflow-checked), realloc and free through the installed pp_allocator. */
void *pp_malloc(size_t size);
void *pp_calloc(size_t count, size_t size);
void *pp_realloc(void *ptr, size_t size);
void pp_free(void *ptr);

/* array_reserve's growth, when n items do not fit. */
bool array_grow(void **items, int32_t *capacity, int32_t n, size_t size);
/* Room for n items of `size` bytes in *items, whose room is *capacity items: doubled from 64 until n fit;
 * false, with nothing changed, without memory. Every array the library grows grows through it. Inline: most
 * calls find the room there (every pass of every substep asks). */
static inline bool array_reserve(void **items, int32_t *capacity, int32_t n, size_t size)
{
    return n <= *capacity || array_grow(items, capacity, n, size);
}
/* array_reserve with the item size taken from the array's own type. */
#define ARRAY_RESERVE(items, capacity, n) array_reserve((void **)&(items), &(capacity), (n), sizeof *(items))

#endif
