/* PP_ASSERT: an internal invariant (room reserved before it is used, an array grown before it is indexed),
 * checked only where PP_CHECKS is defined — the sanitizer and fuzz builds — so that the fuzzers report a
 * broken invariant where it breaks, not only the crash it may cause later. A release build compiles it out;
 * bad input never reaches one (that gets a status). */
#ifndef PP_CHECK_H
#define PP_CHECK_H

#ifdef PP_CHECKS
#include <stdio.h>
#include <stdlib.h>

#define PP_ASSERT(cond)                                                                                \
    ((cond) ? (void)0                                                                                  \
            : (fprintf(stderr, "%s:%d: PP_ASSERT(%s) failed\n", __FILE__, __LINE__, #cond), abort()))
#define PP_CHECKS_ON 1
#else
#define PP_ASSERT(cond) ((void)0)
#define PP_CHECKS_ON 0 /* a cache finds its value again and checks it only where this is 1 */
#endif

#endif
