/* The machine a benchmark ran on, for the first lines of its table, and the clock and sort
 * order every benchmark measures with. */
#ifndef PP_BENCH_MACHINE_H
#define PP_BENCH_MACHINE_H

#include <stdio.h>
#include <string.h>
#include <time.h>

/// Monotonic clock, milliseconds.
static inline double bench_clock_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/// qsort order of doubles, ascending.
static inline int bench_cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/// The CPU's model name from /proc/cpuinfo into out (n bytes), or "unknown".
static inline void bench_cpu_model(char *out, size_t n)
{
    char line[512];
    snprintf(out, n, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    while (f && fgets(line, sizeof line, f)) {
        char *colon = strchr(line, ':');
        if (strncmp(line, "model name", 10) == 0 && colon) {
            snprintf(out, n, "%s", colon + 2);
            out[strcspn(out, "\n")] = '\0';
            break;
        }
    }
    if (f)
        fclose(f);
}

#endif
