/* The demo's software renderer: RGBA8 images, a sky, sprites drawn at their poses through a camera,
 * lines, discs, a 3×5 pixel font, box-filtered thumbnails, and PNG out through pp_image_save. */
#ifndef PP_DEMO_RENDER_H
#define PP_DEMO_RENDER_H

#include "physpix.h"

/// An RGBA8 image, rows top to bottom.
typedef struct render_image {
    int32_t width, height; ///< px
    uint8_t *rgba;         ///< width·height·4 bytes, owned
} render_image;

/// A colour with its opacity, 0..255 each.
typedef struct render_color {
    uint8_t r, g, b, a;
} render_color;

/// A body's look and pose: bitmap coordinates map to the world by position + R(angle)·(local − pivot).
typedef struct render_sprite {
    const uint8_t *rgba;   ///< width·height·4 bytes
    int32_t width, height; ///< px
    pp_vec2 position;      ///< world position of the pivot, px
    pp_vec2 pivot;         ///< bitmap coordinates, px
    float angle;           ///< radians
} render_sprite;

/// Allocate a width×height image (transparent black); 0 on out of memory.
int render_image_init(render_image *im, int32_t width, int32_t height);
void render_image_free(render_image *im);
/// Write the image as PNG; PP_OK or the library's status.
pp_status render_image_save(const render_image *im, const char *path);

/// The sky's colour on image row y of an image `height` rows high (opaque): the background of every frame.
render_color render_sky_color(int32_t y, int32_t height);
/// Fill the image with the sky gradient.
void render_sky(render_image *im);
/// Fill the image with one colour.
void render_fill(render_image *im, render_color c);

/// World point → image point (px, continuous) through the camera.
pp_vec2 render_to_image(const pp_camera *cam, pp_vec2 world);
/// Draw a sprite at its pose: each image pixel in its bounding box samples the bitmap (nearest), alpha-blended.
void render_sprite_draw(render_image *im, const pp_camera *cam, const render_sprite *s);

/// Blend one pixel (clipped).
void render_pixel(render_image *im, int32_t x, int32_t y, render_color c);
/// An axis-aligned filled rectangle, image px (clipped).
void render_rect(render_image *im, int32_t x, int32_t y, int32_t w, int32_t h, render_color c);
/// A line of the given thickness (image px) between image points.
void render_line(render_image *im, pp_vec2 a, pp_vec2 b, float thickness, render_color c);
/// A filled disc, or a ring of the given width when ring > 0 (image px).
void render_disc(render_image *im, pp_vec2 center, float radius, float ring, render_color c);
/// An arrow from a to b with a head `head` px long.
void render_arrow(render_image *im, pp_vec2 a, pp_vec2 b, float thickness, float head, render_color c);
/// Text in a 3×5 pixel font scaled by `scale` (digits, A–Z, a few signs; lower case drawn as upper).
void render_text(render_image *im, int32_t x, int32_t y, int32_t scale, const char *text, render_color c);

/// Downscale src into the rectangle (x, y, w, h) of dst by averaging the source pixels each covers.
void render_thumbnail(render_image *dst, int32_t x, int32_t y, int32_t w, int32_t h, const render_image *src);

#endif
