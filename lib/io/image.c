/* PNG in and out, through libpng: every input kind (gray, gray+alpha, RGB, RGBA, palette, 1–16 bit)
 * normalised to RGBA8 by libpng's own transforms. Sizes are checked against the bitmap limits
 * from the header alone, before any large allocation. */
#include "alloc.h"
#include "files.h"
#include "image.h"
#include "status.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <png.h>
#include <setjmp.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* One decode or encode in progress; libpng's error handler longjmps back with its message kept here. */
typedef struct png_session {
    png_structp png;
    png_infop info;
    FILE *file;
    char error[160];
    char warning[160]; /* libpng's last warning, often the detail behind its error */
    bool out_of_memory; /* an allocation for libpng failed: its error means OOM, not a bad file */
} png_session;

/* libpng allocates through the library's allocator too. */
static png_voidp session_alloc(png_structp png, png_alloc_size_t size)
{
    void *p = pp_malloc(size);
    if (!p)
        ((png_session *)png_get_mem_ptr(png))->out_of_memory = true;
    return p;
}

static void session_free(png_structp png, png_voidp ptr) { pp_free(ptr); }

static void session_error(png_structp png, png_const_charp msg)
{
    png_session *r = png_get_error_ptr(png);
    snprintf(r->error, sizeof r->error, "%s", msg);
    png_longjmp(png, 1);
}

static void session_warning(png_structp png, png_const_charp msg)
{
    png_session *r = png_get_error_ptr(png);
    snprintf(r->warning, sizeof r->warning, "%s", msg);
}

static void reader_close(png_session *r)
{
    if (r->png)
        png_destroy_read_struct(&r->png, r->info ? &r->info : NULL, NULL);
    if (r->file)
        fclose(r->file);
}

/* path opened for reading if it is a regular file: a FIFO would block the decoder forever. */
static int open_input(const char *fn, const char *path)
{
    const int fd = files_open_regular(AT_FDCWD, path);
    if (fd < 0)
        pp_fail(PP_ERR_IO, "%s: cannot open '%s': %s", fn, path, files_strerror(errno));
    return fd;
}

/* Read the file open on fd (a copy of the descriptor, which the session closes) and check its signature;
 * the caller sets the jump point before reading further. */
static pp_status reader_open(png_session *r, const char *fn, const char *path, int fd)
{
    const int own = fcntl(fd, F_DUPFD_CLOEXEC, 0);
    r->file = own >= 0 ? fdopen(own, "rb") : NULL;
    if (!r->file) {
        if (own >= 0)
            close(own);
        return pp_fail(PP_ERR_IO, "%s: cannot read '%s': %s", fn, path, strerror(errno));
    }
    png_byte sig[8];
    if (fread(sig, 1, sizeof sig, r->file) != sizeof sig || png_sig_cmp(sig, 0, sizeof sig) != 0)
        return pp_fail(PP_ERR_FORMAT, "%s: '%s' is not a PNG file (bad signature)", fn, path);
    r->png = png_create_read_struct_2(PNG_LIBPNG_VER_STRING, r, session_error, session_warning, r, session_alloc,
                                      session_free);
    r->info = r->png ? png_create_info_struct(r->png) : NULL;
    if (!r->info)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: cannot allocate the PNG decoder", fn);
    png_init_io(r->png, r->file);
    png_set_sig_bytes(r->png, sizeof sig);
    /* Let libpng accept any valid size so that reader_header, not libpng, says LIMIT with our numbers. */
    png_set_user_limits(r->png, PNG_UINT_31_MAX, PNG_UINT_31_MAX);
    /* Only the chunks that make the pixels are read (IHDR, PLTE, tRNS, IDAT); the other ancillary ones are
     * skipped unread. Debian's libpng 1.6.39 allocates a text, profile or palette-suggestion chunk's declared
     * length before refusing it: a 115-byte file declaring a 1.7 GB sPLT took 1.7 GB (found by fuzz_png). */
    static const png_byte unused[] = "bKGD\0cHRM\0eXIf\0gAMA\0hIST\0iCCP\0iTXt\0oFFs\0pCAL\0pHYs\0sBIT\0sCAL\0sPLT\0"
                                     "sRGB\0tEXt\0tIME\0zTXt";
    if (setjmp(png_jmpbuf(r->png))) /* the list is allocated: libpng reports no memory by png_error */
        return pp_fail(r->out_of_memory ? PP_ERR_OUT_OF_MEMORY : PP_ERR_FORMAT, "%s: cannot set up the decoder for '%s': %s",
                       fn, path, r->error);
    png_set_keep_unknown_chunks(r->png, PNG_HANDLE_CHUNK_NEVER, unused, (int)(sizeof unused / 5));
    return PP_OK;
}

/* Read the header; LIMIT for sizes over the bitmap limits, before anything is allocated for the pixels. */
static pp_status reader_header(png_session *r, const char *fn, const char *path, int32_t *w, int32_t *h)
{
    png_read_info(r->png, r->info);
    const png_uint_32 pw = png_get_image_width(r->png, r->info), ph = png_get_image_height(r->png, r->info);
    if (pw > PP_MAX_BITMAP_SIDE || ph > PP_MAX_BITMAP_SIDE || (uint64_t)pw * ph > PP_MAX_BITMAP_AREA)
        return pp_fail(PP_ERR_LIMIT, "%s: '%s' is %ux%u px, over PP_MAX_BITMAP_SIDE (%d) or PP_MAX_BITMAP_AREA (%d)",
                       fn, path, (unsigned)pw, (unsigned)ph, PP_MAX_BITMAP_SIDE, PP_MAX_BITMAP_AREA);
    *w = (int32_t)pw;
    *h = (int32_t)ph;
    return PP_OK;
}

/* A libpng failure: the file is malformed (truncated, bad CRC, bad header). */
static pp_status reader_failure(const png_session *r, const char *fn, const char *path)
{
    if (r->out_of_memory)
        return pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory to decode '%s'", fn, path);
    if (r->warning[0])
        return pp_fail(PP_ERR_FORMAT, "%s: '%s' is malformed: %s (%s)", fn, path, r->error, r->warning);
    return pp_fail(PP_ERR_FORMAT, "%s: '%s' is malformed: %s", fn, path, r->error);
}

PP_API pp_status pp_image_info(const char *path, int32_t *width, int32_t *height)
{
    if (!path)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_image_info: path is NULL");
    const int fd = open_input("pp_image_info", path);
    if (fd < 0)
        return PP_ERR_IO;
    png_session r = {0};
    int32_t w = 0, h = 0;
    pp_status st = reader_open(&r, "pp_image_info", path, fd);
    close(fd);
    if (st == PP_OK) {
        if (setjmp(png_jmpbuf(r.png)))
            st = reader_failure(&r, "pp_image_info", path);
        else
            st = reader_header(&r, "pp_image_info", path, &w, &h);
    }
    reader_close(&r);
    if (st == PP_OK) {
        if (width)
            *width = w;
        if (height)
            *height = h;
    }
    return st;
}

/* Decode the image: into out (capacity bytes), or, when owned is given, into a new buffer left there. */
static pp_status reader_pixels(png_session *r, const char *fn, const char *path, uint8_t *out, int64_t capacity,
                               uint8_t **owned, int32_t *width, int32_t *height)
{
    png_bytep *volatile rows = NULL; /* volatile: read after a longjmp */
    uint8_t *volatile buf = NULL;
    pp_status st;
    if (setjmp(png_jmpbuf(r->png))) {
        st = reader_failure(r, fn, path);
    } else if ((st = reader_header(r, fn, path, width, height)) == PP_OK) {
        const int64_t need = (int64_t)*width * *height * 4;
        if (owned && !(buf = pp_malloc((size_t)need))) {
            st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory for %d x %d px", fn, (int)*width, (int)*height);
        } else if (!owned && capacity < need) {
            st = pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: '%s' needs %lld bytes, capacity is %lld", fn, path,
                         (long long)need, (long long)capacity);
        } else {
            uint8_t *const pixels = owned ? buf : out;
            /* Every colour type and depth becomes RGBA8. */
            png_set_expand(r->png);
            png_set_strip_16(r->png);
            png_set_gray_to_rgb(r->png);
            png_set_add_alpha(r->png, 0xff, PNG_FILLER_AFTER);
            png_set_interlace_handling(r->png);
            png_read_update_info(r->png, r->info);
            rows = pp_malloc((size_t)*height * sizeof *rows);
            if (!rows) {
                st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: cannot allocate %d row pointers", fn, (int)*height);
            } else {
                for (int32_t y = 0; y < *height; y++)
                    rows[y] = pixels + (size_t)y * (size_t)*width * 4;
                png_read_image(r->png, rows);
                png_read_end(r->png, NULL);
            }
        }
    }
    pp_free(rows);
    if (owned && st == PP_OK)
        *owned = buf;
    else
        pp_free(buf);
    return st;
}

PP_API pp_status pp_image_load(const char *path, uint8_t *out_rgba, int64_t capacity, int32_t *width, int32_t *height)
{
    const char *fn = "pp_image_load";
    if (!width || !height)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: width or height is NULL", fn);
    if (capacity < 0 || (capacity > 0 && !out_rgba))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: out_rgba is NULL or capacity negative (%lld)", fn,
                       (long long)capacity);
    if (!path)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: path is NULL", fn);
    const int fd = open_input(fn, path);
    if (fd < 0)
        return PP_ERR_IO;
    png_session r = {0};
    pp_status st = reader_open(&r, fn, path, fd);
    close(fd);
    if (st == PP_OK)
        st = reader_pixels(&r, fn, path, out_rgba, capacity, NULL, width, height);
    reader_close(&r);
    return st;
}

pp_status image_load_fd(int fd, const char *fn, const char *path, uint8_t **rgba, int32_t *width, int32_t *height)
{
    png_session r = {0};
    pp_status st = reader_open(&r, fn, path, fd);
    if (st == PP_OK)
        st = reader_pixels(&r, fn, path, NULL, 0, rgba, width, height);
    reader_close(&r);
    return st;
}

/* A new file beside path, named path.tmp-<pid>-<n>, created with the process's usual permissions; its
 * name goes to tmp. Returns the descriptor, or -1. */
static int create_beside(const char *path, char *tmp, size_t size)
{
    static _Atomic unsigned counter;
    for (int attempt = 0; attempt < 16; attempt++) {
        if (snprintf(tmp, size, "%s.tmp-%ld-%u", path, (long)getpid(), counter++) >= (int)size)
            return -1;
        const int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0 || errno != EEXIST)
            return fd;
    }
    return -1;
}

/* Encode into wr->file, which the caller opened and closes. */
static pp_status writer_encode(png_session *wr, const char *fn, const char *path, const uint8_t *rgba, int32_t width,
                               int32_t height)
{
    pp_status st;
    wr->png = png_create_write_struct_2(PNG_LIBPNG_VER_STRING, wr, session_error, session_warning, wr, session_alloc,
                                        session_free);
    wr->info = wr->png ? png_create_info_struct(wr->png) : NULL;
    if (!wr->info) {
        st = pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: cannot allocate the PNG encoder", fn);
    } else if (setjmp(png_jmpbuf(wr->png))) {
        st = wr->out_of_memory ? pp_fail(PP_ERR_OUT_OF_MEMORY, "%s: no memory to encode '%s'", fn, path)
                               : pp_fail(PP_ERR_IO, "%s: cannot write '%s': %s", fn, path, wr->error);
    } else {
        png_init_io(wr->png, wr->file);
        png_set_IHDR(wr->png, wr->info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGBA,
                     PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_write_info(wr->png, wr->info);
        for (int32_t y = 0; y < height; y++)
            png_write_row(wr->png, rgba + (size_t)y * (size_t)width * 4);
        png_write_end(wr->png, NULL);
        st = PP_OK;
    }
    if (wr->png)
        png_destroy_write_struct(&wr->png, wr->info ? &wr->info : NULL);
    return st;
}

PP_API pp_status pp_image_save(const char *path, const uint8_t *rgba, int32_t width, int32_t height)
{
    const char *fn = "pp_image_save";
    if (!path || !rgba)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: path or rgba is NULL", fn);
    if (width < 1 || height < 1)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: width × height %d × %d must be at least 1 × 1 px", fn, (int)width, (int)height);
    if (width > PP_MAX_BITMAP_SIDE || height > PP_MAX_BITMAP_SIDE || (int64_t)width * height > PP_MAX_BITMAP_AREA)
        return pp_fail(PP_ERR_LIMIT, "%s: %dx%d px is over PP_MAX_BITMAP_SIDE (%d) or PP_MAX_BITMAP_AREA (%d)", fn,
                       (int)width, (int)height, PP_MAX_BITMAP_SIDE, PP_MAX_BITMAP_AREA);
    /* Written beside the file and renamed over it only when whole: a failed save keeps the old file. */
    char tmp[PATH_MAX];
    const int fd = create_beside(path, tmp, sizeof tmp);
    png_session wr = {0};
    wr.file = fd >= 0 ? fdopen(fd, "wb") : NULL;
    if (!wr.file) {
        if (fd >= 0) {
            close(fd);
            unlink(tmp);
        }
        return pp_fail(PP_ERR_IO, "%s: cannot create '%s'", fn, path);
    }
    pp_status st = writer_encode(&wr, fn, path, rgba, width, height);
    if (fclose(wr.file) != 0 && st == PP_OK)
        st = pp_fail(PP_ERR_IO, "%s: cannot write '%s': %s", fn, path, strerror(errno));
    if (st == PP_OK && rename(tmp, path) != 0)
        st = pp_fail(PP_ERR_IO, "%s: cannot write '%s': %s", fn, path, strerror(errno));
    if (st)
        unlink(tmp);
    return st;
}

pp_status image_save_fd(int fd, const char *fn, const char *path, const uint8_t *rgba, int32_t width, int32_t height)
{
    const int own = fcntl(fd, F_DUPFD_CLOEXEC, 0);
    png_session wr = {0};
    wr.file = own >= 0 ? fdopen(own, "wb") : NULL;
    if (!wr.file) {
        if (own >= 0)
            close(own);
        return pp_fail(PP_ERR_IO, "%s: cannot write '%s': %s", fn, path, strerror(errno));
    }
    pp_status st = writer_encode(&wr, fn, path, rgba, width, height);
    if (fclose(wr.file) != 0 && st == PP_OK)
        st = pp_fail(PP_ERR_IO, "%s: cannot write '%s': %s", fn, path, strerror(errno));
    return st;
}
