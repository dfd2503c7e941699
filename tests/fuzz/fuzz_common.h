/* Shared by the libFuzzer targets: a per-process scratch folder (in /dev/shm when there is one), files in
 * and out of it, and the checks every target makes on a returned status. Public API only. */
#ifndef FUZZ_COMMON_H
#define FUZZ_COMMON_H

#include "physpix.h"

#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv);

/* A check that cannot fail if the library is right: print what broke and abort, which libFuzzer reports. */
#define FUZZ_CHECK(cond, ...)                                                                                          \
    do {                                                                                                               \
        if (!(cond)) {                                                                                                 \
            fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);                                   \
            fprintf(stderr, __VA_ARGS__);                                                                              \
            fprintf(stderr, " (last error: %s)\n", pp_last_error());                                                   \
            abort();                                                                                                   \
        }                                                                                                              \
    } while (0)

/* Every status is one of the enum's values, has a name, and leaves a message string behind. */
static inline pp_status fuzz_status(pp_status st, const char *call)
{
    FUZZ_CHECK((int)st >= PP_OK && (int)st <= PP_ERR_ABI, "%s returned %d", call, (int)st);
    FUZZ_CHECK(pp_status_name(st) != NULL, "%s", call);
    FUZZ_CHECK(pp_last_error() != NULL, "%s", call);
    return st;
}
#define ST(call) fuzz_status((call), #call)

static char fuzz_dir[256];

/* Remove a folder and everything in it (no symlinks are followed: lstat). */
static inline void fuzz_rm_tree(const char *path)
{
    struct stat sb;
    if (lstat(path, &sb) != 0)
        return;
    if (S_ISDIR(sb.st_mode)) {
        DIR *d = opendir(path);
        if (d) {
            char child[1024];
            for (struct dirent *e; (e = readdir(d));) {
                if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
                    continue;
                snprintf(child, sizeof child, "%s/%s", path, e->d_name);
                fuzz_rm_tree(child);
            }
            closedir(d);
        }
        rmdir(path);
    } else {
        unlink(path);
    }
}

static void fuzz_cleanup(void)
{
    if (fuzz_dir[0])
        fuzz_rm_tree(fuzz_dir);
}

/* The process's scratch folder, made once; removed at exit. */
static inline const char *fuzz_scratch(void)
{
    if (!fuzz_dir[0]) {
        struct stat sb;
        const char *base = stat("/dev/shm", &sb) == 0 && S_ISDIR(sb.st_mode) && access("/dev/shm", W_OK) == 0
                               ? "/dev/shm"
                               : (getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
        snprintf(fuzz_dir, sizeof fuzz_dir, "%s/physpix-fuzz-XXXXXX", base);
        if (!mkdtemp(fuzz_dir)) {
            perror("mkdtemp");
            abort();
        }
        atexit(fuzz_cleanup);
    }
    return fuzz_dir;
}

static inline void fuzz_write_file(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f || (size && fwrite(data, 1, size, f) != size) || fclose(f) != 0) {
        perror(path);
        abort();
    }
}

/* Harness cap, not a library limit: a body moving faster than this (any finite speed is valid) makes the
 * continuous sweep test up to 2^20 poses a substep, seconds a step under ASan. Targets do not step such worlds. */
#define FUZZ_MAX_SPEED 1e6         /* px/s */
#define FUZZ_MAX_ANGULAR_SPEED 1e4 /* rad/s */

static inline int fuzz_too_fast(pp_world w)
{
    int32_t n = 0;
    if (pp_world_get_bodies(w, NULL, 0, &n) != PP_OK || n <= 0)
        return 0;
    pp_body *b = malloc((size_t)n * sizeof *b);
    int fast = 0;
    if (pp_world_get_bodies(w, b, n, &n) == PP_OK)
        for (int32_t i = 0; i < n && !fast; i++) {
            pp_vec2 v = {0, 0};
            float av = 0;
            pp_body_get_velocity(w, b[i], &v, &av);
            fast = !(fabsf(v.x) <= FUZZ_MAX_SPEED && fabsf(v.y) <= FUZZ_MAX_SPEED && fabsf(av) <= FUZZ_MAX_ANGULAR_SPEED);
        }
    free(b);
    return fast;
}

/* The GPU backend is never used while fuzzing: a scene or snapshot asking for it gets PP_ERR_UNSUPPORTED. */
static inline void fuzz_no_gpu(void) { setenv("PHYSPIX_LIBEGL", "/nonexistent/libEGL-fuzz.so", 1); }

#endif /* FUZZ_COMMON_H */
