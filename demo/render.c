/* The demo's software renderer. Sprites are drawn by inverse mapping: every image pixel in a body's
 * image-space bounding box is taken back into bitmap coordinates and samples the nearest texel, so a
 * rotated sprite has no holes. Shapes are filled by distance tests; PNG goes out through libphyspix. */
#include "render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int render_image_init(render_image *im, int32_t width, int32_t height)
{
    im->width = width, im->height = height;
    im->rgba = calloc((size_t)width * (size_t)height * 4, 1);
    return im->rgba != NULL;
}

void render_image_free(render_image *im)
{
    free(im->rgba);
    im->rgba = NULL;
}

pp_status render_image_save(const render_image *im, const char *path)
{
    return pp_image_save(path, im->rgba, im->width, im->height);
}

render_color render_sky_color(int32_t y, int32_t height)
{
    const float t = height > 1 ? (float)y / (float)(height - 1) : 0.0f; /* deep blue above, pale at the horizon */
    return (render_color){(uint8_t)(96 + 120 * t), (uint8_t)(150 + 85 * t), (uint8_t)(218 + 30 * t), 255};
}

void render_sky(render_image *im)
{
    for (int32_t y = 0; y < im->height; y++) {
        const render_color c = render_sky_color(y, im->height);
        uint8_t *row = im->rgba + (size_t)y * im->width * 4;
        for (int32_t x = 0; x < im->width; x++)
            memcpy(row + 4 * x, &c, 4);
    }
}

void render_fill(render_image *im, render_color c)
{
    for (int64_t i = 0; i < (int64_t)im->width * im->height; i++)
        memcpy(im->rgba + 4 * i, &c, 4);
}

pp_vec2 render_to_image(const pp_camera *cam, pp_vec2 w)
{
    return (pp_vec2){(w.x - cam->center.x) * cam->zoom + 0.5f * (float)cam->width,
                     (w.y - cam->center.y) * cam->zoom + 0.5f * (float)cam->height};
}

static void blend(uint8_t *p, const uint8_t *src)
{
    const unsigned a = src[3], na = 255 - a;
    for (int k = 0; k < 3; k++)
        p[k] = (uint8_t)((src[k] * a + p[k] * na + 127) / 255);
    p[3] = (uint8_t)(a + (p[3] * na + 127) / 255);
}

void render_pixel(render_image *im, int32_t x, int32_t y, render_color c)
{
    if (x >= 0 && y >= 0 && x < im->width && y < im->height)
        blend(im->rgba + ((size_t)y * im->width + x) * 4, &c.r);
}

/* Clip [lo, hi) to [0, n). */
static void clip(float lo, float hi, int32_t n, int32_t *a, int32_t *b)
{
    *a = lo < 0 ? 0 : lo > (float)n ? n : (int32_t)floorf(lo);
    *b = hi < 0 ? 0 : hi > (float)n ? n : (int32_t)ceilf(hi);
}

void render_sprite_draw(render_image *im, const pp_camera *cam, const render_sprite *s)
{
    const float c = cosf(s->angle), sn = sinf(s->angle), inv = 1.0f / cam->zoom;
    /* The bitmap's corners in the image bound the pixels to visit. */
    float x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int k = 0; k < 4; k++) {
        const float lx = (k & 1 ? (float)s->width : 0.0f) - s->pivot.x, ly = (k & 2 ? (float)s->height : 0.0f) - s->pivot.y;
        const pp_vec2 p = render_to_image(cam, (pp_vec2){s->position.x + c * lx - sn * ly, s->position.y + sn * lx + c * ly});
        x0 = fminf(x0, p.x), y0 = fminf(y0, p.y), x1 = fmaxf(x1, p.x), y1 = fmaxf(y1, p.y);
    }
    int32_t ix0, ix1, iy0, iy1;
    clip(x0, x1, im->width, &ix0, &ix1);
    clip(y0, y1, im->height, &iy0, &iy1);
    /* Bitmap coordinates are affine in the image pixel: each row starts from the exact mapping and steps along x. */
    const float dxx = c * inv, dxy = -sn * inv;
    for (int32_t y = iy0; y < iy1; y++) {
        const float wx = cam->center.x + ((float)ix0 + 0.5f - 0.5f * (float)cam->width) * inv - s->position.x;
        const float wy = cam->center.y + ((float)y + 0.5f - 0.5f * (float)cam->height) * inv - s->position.y;
        float lx = c * wx + sn * wy + s->pivot.x, ly = -sn * wx + c * wy + s->pivot.y;
        uint8_t *p = im->rgba + ((size_t)y * im->width + ix0) * 4;
        for (int32_t x = ix0; x < ix1; x++, p += 4, lx += dxx, ly += dxy) {
            if (lx < 0 || ly < 0 || lx >= (float)s->width || ly >= (float)s->height)
                continue;
            const uint8_t *t = s->rgba + ((size_t)(int32_t)ly * s->width + (int32_t)lx) * 4;
            if (t[3])
                blend(p, t);
        }
    }
}

void render_rect(render_image *im, int32_t x, int32_t y, int32_t w, int32_t h, render_color c)
{
    for (int32_t j = y; j < y + h; j++)
        for (int32_t i = x; i < x + w; i++)
            render_pixel(im, i, j, c);
}

/* Fill the pixels of a box whose centres pass `inside`. */
typedef int (*inside_fn)(const float *shape, float x, float y);

static void fill_shape(render_image *im, float x0, float y0, float x1, float y1, const float *shape, inside_fn inside,
                       render_color c)
{
    int32_t ix0, ix1, iy0, iy1;
    clip(x0, x1, im->width, &ix0, &ix1);
    clip(y0, y1, im->height, &iy0, &iy1);
    for (int32_t y = iy0; y < iy1; y++)
        for (int32_t x = ix0; x < ix1; x++)
            if (inside(shape, (float)x + 0.5f, (float)y + 0.5f))
                render_pixel(im, x, y, c);
}

/* shape: ax, ay, bx, by, half thickness. */
static int in_segment(const float *s, float x, float y)
{
    const float dx = s[2] - s[0], dy = s[3] - s[1], len2 = dx * dx + dy * dy;
    float t = len2 > 0 ? ((x - s[0]) * dx + (y - s[1]) * dy) / len2 : 0.0f;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    const float ex = s[0] + t * dx - x, ey = s[1] + t * dy - y;
    return ex * ex + ey * ey <= s[4] * s[4];
}

void render_line(render_image *im, pp_vec2 a, pp_vec2 b, float thickness, render_color c)
{
    const float h = fmaxf(0.5f, 0.5f * thickness), s[5] = {a.x, a.y, b.x, b.y, h};
    fill_shape(im, fminf(a.x, b.x) - h, fminf(a.y, b.y) - h, fmaxf(a.x, b.x) + h, fmaxf(a.y, b.y) + h, s, in_segment,
               c);
}

/* shape: cx, cy, outer radius, inner radius. */
static int in_ring(const float *s, float x, float y)
{
    const float d2 = (x - s[0]) * (x - s[0]) + (y - s[1]) * (y - s[1]);
    return d2 <= s[2] * s[2] && d2 >= s[3] * s[3];
}

void render_disc(render_image *im, pp_vec2 center, float radius, float ring, render_color c)
{
    const float s[4] = {center.x, center.y, radius, ring > 0 ? fmaxf(0.0f, radius - ring) : 0.0f};
    fill_shape(im, center.x - radius, center.y - radius, center.x + radius, center.y + radius, s, in_ring, c);
}

void render_arrow(render_image *im, pp_vec2 a, pp_vec2 b, float thickness, float head, render_color c)
{
    render_line(im, a, b, thickness, c);
    const float dx = b.x - a.x, dy = b.y - a.y, len = sqrtf(dx * dx + dy * dy);
    if (len <= 0)
        return;
    const float ux = dx / len, uy = dy / len, k = 0.45f; /* the head's half-angle, ~24° */
    for (int side = -1; side <= 1; side += 2) {
        const float hx = -ux * cosf(k) + side * -uy * sinf(k), hy = -uy * cosf(k) + side * ux * sinf(k);
        render_line(im, b, (pp_vec2){b.x + head * hx, b.y + head * hy}, thickness, c);
    }
}

/* 3×5 glyphs, rows top to bottom, '#' lit. S has a full middle stroke: drawn as a thin diagonal it read as a
 * slash at caption size, and with square corners it would be a 5. */
static const char *glyph(char ch)
{
    static const struct {
        char ch;
        const char *rows;
    } font[] = {
        {'0', "#### ## ## ####"}, {'1', " # ##  #  # ###"}, {'2', "###  #####  ###"}, {'3', "###  ####  ####"},
        {'4', "# ## ####  #  #"}, {'5', "####  ###  ####"}, {'6', "####  #### ####"}, {'7', "###  #  # #  # "},
        {'8', "#### ##### ####"}, {'9', "#### ####  ####"}, {'A', " # # ##### ## #"}, {'B', "## # ### # ### "},
        {'C', " ###  #  #   ##"}, {'D', "## # ## ## ### "}, {'E', "####  ## #  ###"}, {'F', "####  ## #  #  "},
        {'G', " ###  # ## # ##"}, {'H', "# ## ##### ## #"}, {'I', "### #  #  # ###"}, {'J', "  #  #  ## # # "},
        {'K', "# ## ### # ## #"}, {'L', "#  #  #  #  ###"}, {'M', "# ######## ## #"}, {'N', "## # ## ## ## #"},
        {'O', " # # ## ## # # "}, {'P', "## # ### #  #  "}, {'Q', " # # ## ###  ##"}, {'R', "## # ### # ## #"},
        {'S', " ###  ###  ### "}, {'T', "### #  #  #  # "}, {'U', "# ## ## ## ####"}, {'V', "# ## ## ## # # "},
        {'W', "# ## ######## #"}, {'X', "# ## # # # ## #"}, {'Y', "# ## # #  #  # "}, {'Z', "###  # # #  ###"},
        {'.', "             # "}, {':', "    #     #    "}, {'=', "   ###   ###   "}, {'-', "      ###      "},
        {'/', "  #  # # #  #  "}, {'(', " # #  #  #   # "}, {')', " #   #  #  # # "}, {'+', "    # ### #    "},
        {'%', "# #  # # #  # #"}, {',', "          # #  "},
    };
    if (ch >= 'a' && ch <= 'z')
        ch = (char)(ch - 'a' + 'A');
    for (size_t i = 0; i < sizeof font / sizeof font[0]; i++)
        if (font[i].ch == ch)
            return font[i].rows;
    return NULL; /* a space, or a sign the font lacks */
}

void render_text(render_image *im, int32_t x, int32_t y, int32_t scale, const char *text, render_color c)
{
    for (; *text; text++, x += 4 * scale) {
        const char *rows = glyph(*text);
        for (int k = 0; rows && k < 15 && rows[k]; k++)
            if (rows[k] == '#')
                render_rect(im, x + (k % 3) * scale, y + (k / 3) * scale, scale, scale, c);
    }
}

void render_thumbnail(render_image *dst, int32_t x, int32_t y, int32_t w, int32_t h, const render_image *src)
{
    for (int32_t v = 0; v < h; v++) {
        const int32_t sy0 = (int32_t)((int64_t)v * src->height / h), sy1 = (int32_t)((int64_t)(v + 1) * src->height / h);
        for (int32_t u = 0; u < w; u++) {
            const int32_t sx0 = (int32_t)((int64_t)u * src->width / w), sx1 = (int32_t)((int64_t)(u + 1) * src->width / w);
            uint32_t sum[4] = {0}, n = 0;
            for (int32_t sy = sy0; sy < (sy1 > sy0 ? sy1 : sy0 + 1); sy++)
                for (int32_t sx = sx0; sx < (sx1 > sx0 ? sx1 : sx0 + 1); sx++, n++)
                    for (int k = 0; k < 4; k++)
                        sum[k] += src->rgba[((size_t)sy * src->width + sx) * 4 + k];
            const render_color c = {(uint8_t)(sum[0] / n), (uint8_t)(sum[1] / n), (uint8_t)(sum[2] / n), 255};
            if (x + u >= 0 && y + v >= 0 && x + u < dst->width && y + v < dst->height)
                memcpy(dst->rgba + ((size_t)(y + v) * dst->width + x + u) * 4, &c, 4);
        }
    }
}
