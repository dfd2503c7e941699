/* The fuzz_snapshot input: a folder's files as records, [name length: 1 byte][name][data length: 2 bytes,
 * little-endian][data], repeated. Names are sanitised to [A-Za-z0-9_.-] with no leading dot; a record cut
 * short keeps what is there. make_seeds packs real snapshots this way. */
#ifndef FUZZ_ARCHIVE_H
#define FUZZ_ARCHIVE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define FUZZ_ARCHIVE_MAX_FILES 32
#define FUZZ_ARCHIVE_MAX_NAME 40

static inline void fuzz_archive_extract(const uint8_t *data, size_t size, const char *dir)
{
    size_t at = 0;
    for (int files = 0; at < size && files < FUZZ_ARCHIVE_MAX_FILES; files++) {
        size_t nlen = data[at++];
        if (nlen > size - at)
            nlen = size - at;
        char name[FUZZ_ARCHIVE_MAX_NAME + 1];
        size_t k = 0;
        for (size_t i = 0; i < nlen && k < FUZZ_ARCHIVE_MAX_NAME; i++) {
            const char ch = (char)data[at + i];
            const int ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
                           ch == '_' || ch == '-' || (ch == '.' && k > 0);
            if (ok)
                name[k++] = ch;
        }
        name[k] = '\0';
        at += nlen;
        size_t dlen = 0;
        if (size - at >= 2) {
            dlen = (size_t)data[at] | (size_t)data[at + 1] << 8;
            at += 2;
        } else {
            at = size;
        }
        if (dlen > size - at)
            dlen = size - at;
        if (k > 0) {
            char path[600];
            snprintf(path, sizeof path, "%s/%s", dir, name);
            FILE *f = fopen(path, "wb");
            if (f) {
                if (dlen)
                    fwrite(data + at, 1, dlen, f);
                fclose(f);
            }
        }
        at += dlen;
    }
}

/* Append one record to buf (capacity cap); returns the new length, or 0 when it does not fit. */
static inline size_t fuzz_archive_add(uint8_t *buf, size_t len, size_t cap, const char *name, const uint8_t *data,
                                      size_t dlen)
{
    const size_t nlen = strlen(name);
    if (nlen > 255 || dlen > 0xffff || len + 1 + nlen + 2 + dlen > cap)
        return 0;
    buf[len++] = (uint8_t)nlen;
    memcpy(buf + len, name, nlen), len += nlen;
    buf[len++] = (uint8_t)(dlen & 0xff), buf[len++] = (uint8_t)(dlen >> 8);
    memcpy(buf + len, data, dlen);
    return len + dlen;
}

#endif /* FUZZ_ARCHIVE_H */
