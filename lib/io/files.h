/* Opening the files a scene or snapshot names, and the folder steps of a snapshot save. Only regular files
 * are read (opened O_NONBLOCK and checked by fstat, so a FIFO or a device is refused at once, never waited
 * on); the paths a file names are read only from beneath its folder; a save works through directory
 * descriptors and never follows a link planted where it expects a folder. */
#ifndef PP_FILES_H
#define PP_FILES_H

#include <stdbool.h>
#include <stddef.h>

/* The first dir_len bytes of path (its folder; "." when 0) as a directory descriptor; -1 and errno. */
int files_open_folder(const char *path, size_t dir_len);
/* name (relative to dir_fd, or any path with AT_FDCWD) for reading, links followed, only if it is a regular
 * file: its descriptor, or -1 and errno (EINVAL for a file that is not regular). */
int files_open_regular(int dir_fd, const char *name);
/* The same, confined beneath dir_fd: -1 and EXDEV for an absolute name, a ".." component or a link that
 * leads outside; links that stay inside are followed. openat2's RESOLVE_BENEATH, else the walk below. */
int files_open_beneath(int dir_fd, const char *name);
/* files_open_beneath without openat2 (Linux before 5.6, or a sandbox refusing it): one component at a time,
 * each opened without following links, a link's text spliced in and checked; tests call it directly. */
int files_open_beneath_walk(int dir_fd, const char *name);
/* strerror, with EINVAL read as "not a regular file", which is what the opens above mean by it. */
const char *files_strerror(int err);

/* A new folder "<base>.tmp-XXXXXX" (mode 0700) in parent_fd, its name into name: its descriptor, opened
 * without following a link, or -1 and errno. */
int files_make_temp_folder(int parent_fd, const char *base, char *name, size_t size);
/* A new file name in dir_fd, for writing: never through a link, never over an existing entry; -1 and errno. */
int files_create(int dir_fd, const char *name);
/* Whether parent_fd's entry name is, not following a link, the folder that dir_fd is open on. */
bool files_is_folder(int parent_fd, const char *name, int dir_fd);
/* Remove parent_fd's entry name and everything in it, only if it is the folder dir_fd is open on; the
 * contents go through dir_fd, links unlinked, never followed. False if anything stayed. */
bool files_remove_folder(int parent_fd, const char *name, int dir_fd);

#endif
