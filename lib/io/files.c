/* Opening the files a scene or snapshot names, confined to a folder and regular files only, and the
 * directory-descriptor steps of a snapshot save (see files.h). Linux: openat2, O_PATH, renameat2. */
#define _GNU_SOURCE /* O_PATH, syscall */
#include "files.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>
#ifdef SYS_openat2
#include <linux/openat2.h>
#endif

/* O_NONBLOCK: opening a FIFO for reading waits for a writer otherwise; fstat then refuses it. */
#define READ_FLAGS (O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC)

int files_open_folder(const char *path, size_t dir_len)
{
    char folder[PATH_MAX];
    if (dir_len >= sizeof folder) {
        errno = ENAMETOOLONG;
        return -1;
    }
    memcpy(folder, path, dir_len);
    folder[dir_len] = '\0';
    return open(dir_len ? folder : ".", O_PATH | O_DIRECTORY | O_CLOEXEC);
}

/* fd if it is a regular file, made blocking again; otherwise closed, with errno EINVAL. */
static int keep_regular(int fd)
{
    if (fd < 0)
        return -1;
    struct stat sb;
    const bool known = fstat(fd, &sb) == 0;
    if (!known || !S_ISREG(sb.st_mode)) {
        const int err = known ? EINVAL : errno;
        close(fd);
        errno = err;
        return -1;
    }
    const int fl = fcntl(fd, F_GETFL);
    if (fl >= 0)
        fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
    return fd;
}

int files_open_regular(int dir_fd, const char *name) { return keep_regular(openat(dir_fd, name, READ_FLAGS)); }

/* An absolute name or a ".." component, refused before any lookup. */
static bool climbs(const char *name)
{
    if (name[0] == '/')
        return true;
    for (const char *p = name; *p;) {
        const size_t n = strcspn(p, "/");
        if (n == 2 && p[0] == '.' && p[1] == '.')
            return true;
        for (p += n; *p == '/'; p++) {
        }
    }
    return false;
}

int files_open_beneath(int dir_fd, const char *name)
{
    if (climbs(name)) {
        errno = EXDEV;
        return -1;
    }
#ifdef SYS_openat2
    struct open_how how = {.flags = READ_FLAGS, .resolve = RESOLVE_BENEATH | RESOLVE_NO_MAGICLINKS};
    /* EAGAIN: a rename anywhere on the system raced a ".." step, and the kernel asks for a retry; after a few,
     * the walk (which needs no such guard) decides. */
    for (int attempt = 0; attempt < 8; attempt++) {
        const long fd = syscall(SYS_openat2, dir_fd, name, &how, sizeof how);
        /* ENOSYS before Linux 5.6; EPERM from a seccomp filter that does not know the call. */
        if (fd >= 0 || (errno != ENOSYS && errno != EPERM && errno != EAGAIN))
            return keep_regular((int)fd);
        if (errno != EAGAIN)
            break;
    }
#endif
    return files_open_beneath_walk(dir_fd, name);
}

enum { WALK_DEPTH = 64, WALK_LINKS = 40 }; /* folders deep, links followed (the kernel's own limit is 40) */

int files_open_beneath_walk(int dir_fd, const char *name)
{
    char path[PATH_MAX], spliced[PATH_MAX], target[PATH_MAX];
    if (climbs(name)) {
        errno = EXDEV;
        return -1;
    }
    if (snprintf(path, sizeof path, "%s", name) >= (int)sizeof path) {
        errno = ENAMETOOLONG;
        return -1;
    }
    /* dirs[] holds the folders walked into below dir_fd, so ".." (from a link's text) steps back up. */
    int dirs[WALK_DEPTH], depth = 0, links = 0, fd = -1, err = 0;
    for (char *p = path;;) {
        while (*p == '/')
            p++;
        if (!*p) {
            err = EISDIR; /* the name ends at a folder */
            break;
        }
        char *end = p + strcspn(p, "/");
        const bool last = *end == '\0';
        *end = '\0';
        const int cur = depth ? dirs[depth - 1] : dir_fd;
        const bool dot = strcmp(p, ".") == 0, dotdot = strcmp(p, "..") == 0;
        if (dotdot && depth == 0) {
            err = EXDEV; /* above dir_fd */
            break;
        }
        if (dot || dotdot) {
            if (dotdot)
                close(dirs[--depth]);
            if (last) {
                err = EISDIR;
                break;
            }
            p = end + 1;
            continue;
        }
        struct stat sb;
        if (fstatat(cur, p, &sb, AT_SYMLINK_NOFOLLOW) != 0) {
            err = errno;
            break;
        }
        if (S_ISLNK(sb.st_mode)) {
            /* The link's text replaces its name, relative to the folder that holds it. */
            const ssize_t n = ++links > WALK_LINKS ? -1 : readlinkat(cur, p, target, sizeof target - 1);
            if (n <= 0) {
                err = links > WALK_LINKS ? ELOOP : n == 0 ? ENOENT : errno;
                break;
            }
            target[n] = '\0';
            if (target[0] == '/') {
                err = EXDEV;
                break;
            }
            const char *rest = last ? "" : end + 1;
            if (snprintf(spliced, sizeof spliced, "%s%s%s", target, *rest ? "/" : "", rest) >= (int)sizeof spliced) {
                err = ENAMETOOLONG;
                break;
            }
            memcpy(path, spliced, strlen(spliced) + 1);
            p = path;
            continue;
        }
        if (last) {
            /* O_NOFOLLOW: a link put there since fstatat is refused (ELOOP), not followed. */
            fd = openat(cur, p, READ_FLAGS | O_NOFOLLOW);
            err = errno;
            break;
        }
        const int next = depth < WALK_DEPTH ? openat(cur, p, O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC) : -1;
        if (next < 0) {
            err = depth < WALK_DEPTH ? errno : ENAMETOOLONG;
            break;
        }
        dirs[depth++] = next;
        p = end + 1;
    }
    while (depth > 0)
        close(dirs[--depth]);
    if (fd < 0) {
        errno = err;
        return -1;
    }
    return keep_regular(fd);
}

const char *files_strerror(int err) { return err == EINVAL ? "not a regular file" : strerror(err); }

/* ---- saving ------------------------------------------------------------------------------------- */

int files_make_temp_folder(int parent_fd, const char *base, char *name, size_t size)
{
    static const char letters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    static _Atomic uint64_t counter;
    for (int attempt = 0; attempt < 100; attempt++) {
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        /* splitmix64 of the time, the process and a counter: a fresh name each try */
        uint64_t x = (uint64_t)ts.tv_nsec ^ ((uint64_t)ts.tv_sec << 30) ^ ((uint64_t)getpid() << 42) ^
                     (counter++ * 0x9e3779b97f4a7c15ull);
        x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
        x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
        x ^= x >> 31;
        char suffix[7];
        for (int i = 0; i < 6; i++, x /= 62)
            suffix[i] = letters[x % 62];
        suffix[6] = '\0';
        if (snprintf(name, size, "%s.tmp-%s", base, suffix) >= (int)size) {
            errno = ENAMETOOLONG;
            return -1;
        }
        if (mkdirat(parent_fd, name, 0700) == 0)
            return openat(parent_fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (errno != EEXIST)
            return -1;
    }
    return -1;
}

int files_create(int dir_fd, const char *name)
{
    return openat(dir_fd, name, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
}

bool files_is_folder(int parent_fd, const char *name, int dir_fd)
{
    struct stat entry, dir;
    return fstatat(parent_fd, name, &entry, AT_SYMLINK_NOFOLLOW) == 0 && fstat(dir_fd, &dir) == 0 &&
           S_ISDIR(entry.st_mode) && entry.st_dev == dir.st_dev && entry.st_ino == dir.st_ino;
}

/* Everything dir_fd holds, through dir_fd: a file or link unlinked, a folder emptied the same way and removed. */
static bool clear_folder(int dir_fd, int depth)
{
    const int list_fd = openat(dir_fd, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    DIR *d = list_fd >= 0 ? fdopendir(list_fd) : NULL;
    if (!d) {
        if (list_fd >= 0)
            close(list_fd);
        return false;
    }
    bool ok = true;
    for (struct dirent *e; (e = readdir(d));) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0 || unlinkat(dir_fd, e->d_name, 0) == 0)
            continue;
        /* unlink refuses a folder (EISDIR on Linux, EPERM in POSIX): empty it through its own descriptor. */
        const int sub = (errno == EISDIR || errno == EPERM) && depth < WALK_DEPTH
                            ? openat(dir_fd, e->d_name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC)
                            : -1;
        ok = sub >= 0 && clear_folder(sub, depth + 1) && unlinkat(dir_fd, e->d_name, AT_REMOVEDIR) == 0 && ok;
        if (sub >= 0)
            close(sub);
    }
    closedir(d);
    return ok;
}

bool files_remove_folder(int parent_fd, const char *name, int dir_fd)
{
    if (!files_is_folder(parent_fd, name, dir_fd))
        return false;
    const bool cleared = clear_folder(dir_fd, 0);
    /* AT_REMOVEDIR removes only an empty folder, whatever may have been put at the name meanwhile. */
    return cleared && unlinkat(parent_fd, name, AT_REMOVEDIR) == 0;
}
