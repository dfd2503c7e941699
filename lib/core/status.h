/* Status codes with a thread-local message, and the process-wide log hook. */
#ifndef PP_STATUS_H
#define PP_STATUS_H

#include "physpix.h"

/* Record a failure for pp_last_error() and return the status, so call sites read
 * `return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_step: dt must be > 0, got %g", dt);`. */
pp_status pp_fail(pp_status status, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The last failure's message put under the call the user made ("fn: ..."), for a part that does not know
 * it (the broadphase, the narrowphase); a message that already names a call is kept. Returns status. */
pp_status pp_fail_in(const char *fn, pp_status status);

/* Check a caller-owned output buffer (out, capacity, count) as every list call takes it. */
pp_status pp_check_out_buffer(const char *fn, const void *out, int32_t capacity, const int32_t *count);

/* Check a world box lower..upper (px) as the box queries take it: finite, lower not past upper. */
pp_status pp_check_box(const char *fn, pp_vec2 lower, pp_vec2 upper);

/* Send a line to the host's log hook, if one is installed. */
void pp_log(int level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
