/* PNG through a descriptor the caller opened (a scene's PNGs and a snapshot's planes, opened by files.h):
 * image.c's libpng reader and writer without their own open. The descriptor stays the caller's; fn and
 * path name the call and the file in messages. */
#ifndef PP_IMAGE_H
#define PP_IMAGE_H

#include "physpix.h"

/* Decode the PNG open on fd into a new RGBA8 buffer (*rgba, pp_free it), as pp_image_load does. */
pp_status image_load_fd(int fd, const char *fn, const char *path, uint8_t **rgba, int32_t *width, int32_t *height);
/* Encode RGBA8 rows (top to bottom, width·4 bytes apart) as a PNG into fd, as pp_image_save does. */
pp_status image_save_fd(int fd, const char *fn, const char *path, const uint8_t *rgba, int32_t width, int32_t height);

#endif
