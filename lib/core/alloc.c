/* The process-wide allocator: malloc by default, or the host's from pp_set_allocator. */
#include "alloc.h"
#include "status.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int32_t world_live_count(void); /* world.c */

static void *sys_alloc(uint64_t size, void *user) { return malloc((size_t)size); }
static void *sys_realloc(void *ptr, uint64_t size, void *user) { return realloc(ptr, (size_t)size); }
static void sys_free(void *ptr, void *user) { free(ptr); }

static pp_allocator current = {sys_alloc, sys_realloc, sys_free, NULL};

PP_API pp_status pp_set_allocator(const pp_allocator *a)
{
    if (a && (!a->alloc || !a->realloc || !a->free))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_set_allocator: alloc, realloc and free must all be set");
    /* Memory from one allocator must go back to the same one. */
    const int32_t live = world_live_count();
    if (live > 0)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_set_allocator: %d worlds exist; set the allocator before creating any",
                       (int)live);
    current = a ? *a : (pp_allocator){sys_alloc, sys_realloc, sys_free, NULL};
    return PP_OK;
}

/* Zero bytes is asked as one, so that NULL always means out of memory. */
void *pp_malloc(size_t size) { return current.alloc(size ? size : 1, current.user); }

void *pp_calloc(size_t count, size_t size)
{
    if (size && count > SIZE_MAX / size)
        return NULL;
    const size_t bytes = count * size;
    void *p = pp_malloc(bytes);
    if (p)
        memset(p, 0, bytes > 0 ? bytes : 1);
    return p;
}

void *pp_realloc(void *ptr, size_t size) { return current.realloc(ptr, size ? size : 1, current.user); }

void pp_free(void *ptr)
{
    if (ptr)
        current.free(ptr, current.user);
}

bool array_grow(void **items, int32_t *capacity, int32_t n, size_t size)
{
    int32_t cap = *capacity > 0 ? *capacity : 64;
    while (cap < n)
        cap = cap <= INT32_MAX / 2 ? 2 * cap : n;
    void *p = pp_realloc(*items, (size_t)cap * size);
    if (!p)
        return false;
    *items = p;
    *capacity = cap;
    return true;
}
