/* Every allocation the library makes itself goes through here, so a host's allocator (pp_set_allocator)
 * sees it and a test can make any one of them fail. ODE and cJSON keep their own allocators. */
#ifndef PP_ALLOC_H
#define PP_ALLOC_H

#include <stddef.h>

/* malloc, calloc (overflow-checked), realloc and free through the installed pp_allocator. */
void *pp_malloc(size_t size);
void *pp_calloc(size_t count, size_t size);
void *pp_realloc(void *ptr, size_t size);
void pp_free(void *ptr);

#endif
