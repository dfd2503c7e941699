/* Status names, the thread-local last-error message, the log hook, the version. */
#include "status.h"

#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static _Thread_local char last_error[512];
/* The hook may be swapped on one thread while another world logs: fn and user are read and written
 * together under the lock (a data race otherwise, found by make check-tsan); the hook runs outside it. */
static pthread_mutex_t log_lock = PTHREAD_MUTEX_INITIALIZER;
static pp_log_fn log_fn;
static void *log_user;

pp_status pp_fail(pp_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(last_error, sizeof last_error, fmt, ap);
    va_end(ap);
    return status;
}

pp_status pp_fail_in(const char *fn, pp_status status)
{
    if (strncmp(last_error, "pp_", 3) == 0)
        return status;
    char inner[sizeof last_error];
    memcpy(inner, last_error, sizeof inner);
    return pp_fail(status, "%s: %s", fn, inner);
}

pp_status pp_check_out_buffer(const char *fn, const void *out, int32_t capacity, const int32_t *count)
{
    if (!count)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: count is NULL", fn);
    if (capacity < 0)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: capacity is negative (%d)", fn, (int)capacity);
    if (capacity > 0 && !out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: out is NULL with capacity %d", fn, (int)capacity);
    return PP_OK;
}

pp_status pp_check_box(const char *fn, pp_vec2 lower, pp_vec2 upper)
{
    if (!isfinite(lower.x) || !isfinite(lower.y) || !isfinite(upper.x) || !isfinite(upper.y))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: lower and upper must be finite, got (%g, %g) and (%g, %g)", fn,
                       lower.x, lower.y, upper.x, upper.y);
    if (lower.x > upper.x || lower.y > upper.y)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: lower (%g, %g) must not exceed upper (%g, %g)", fn, lower.x,
                       lower.y, upper.x, upper.y);
    return PP_OK;
}

void pp_log(int level, const char *fmt, ...)
{
    pthread_mutex_lock(&log_lock);
    const pp_log_fn fn = log_fn;
    void *const user = log_user;
    pthread_mutex_unlock(&log_lock);
    if (!fn)
        return;
    char line[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    fn(level, line, user);
}

PP_API void pp_set_log_hook(pp_log_fn fn, void *user)
{
    pthread_mutex_lock(&log_lock);
    log_fn = fn;
    log_user = user;
    pthread_mutex_unlock(&log_lock);
}

PP_API const char *pp_last_error(void) { return last_error; }

PP_API uint32_t pp_version(void)
{
    return PHYSPIX_VERSION_MAJOR * 10000u + PHYSPIX_VERSION_MINOR * 100u + PHYSPIX_VERSION_PATCH;
}

PP_API const char *pp_status_name(pp_status status)
{
    switch (status) {
    case PP_OK: return "PP_OK";
    case PP_ERR_INVALID_ARGUMENT: return "PP_ERR_INVALID_ARGUMENT";
    case PP_ERR_INVALID_HANDLE: return "PP_ERR_INVALID_HANDLE";
    case PP_ERR_OUT_OF_MEMORY: return "PP_ERR_OUT_OF_MEMORY";
    case PP_ERR_IO: return "PP_ERR_IO";
    case PP_ERR_FORMAT: return "PP_ERR_FORMAT";
    case PP_ERR_UNSUPPORTED: return "PP_ERR_UNSUPPORTED";
    case PP_ERR_LIMIT: return "PP_ERR_LIMIT";
    case PP_ERR_ABI: return "PP_ERR_ABI";
    default: return "PP_STATUS_UNKNOWN";
    }
}
