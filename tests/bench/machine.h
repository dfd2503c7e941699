/* The machine a benchmark ran on, for the first lines of its table. */
#ifndef PP_BENCH_MACHINE_H
#define PP_BENCH_MACHINE_H

#include <stdio.h>
#include <string.h>

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
