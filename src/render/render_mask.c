/* tether — masks shown as images: one texel per mask pixel, so the
 * renderer draws a mask as it draws any image (tt_canvas_image), stretched
 * over the world rectangle the mask covers, pixels kept sharp (the
 * renderer's textures use nearest filtering). */
#include "render_internal.h"

#include <string.h>

/* Writes m's pixels into rgba (w·h·4 bytes, rows top to bottom). */
static void paint(uint8_t *rgba, const tt_mask *m, int w, int h, tt_color on, tt_color off)
{
    const uint8_t a[4] = { on.r, on.g, on.b, on.a }, b[4] = { off.r, off.g, off.b, off.a };
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) memcpy(rgba + 4 * ((size_t)y * w + x), tt_mask_get(m, x, y) == 1 ? a : b, 4);
}

tt_image *tt_image_from_mask(const tt_mask *m, tt_color on, tt_color off)
{
    int w, h;
    if (tt_mask_size(m, &w, &h) != TT_OK) return NULL;
    tt_image *img = tt_image_create(w, h);
    if (img) paint(tt_image_pixels(img), m, w, h, on, off);
    return img;
}

tt_result tt_image_paint_mask(tt_image *img, const tt_mask *m, tt_color on, tt_color off)
{
    int w, h, iw, ih;
    if (!img || tt_mask_size(m, &w, &h) != TT_OK) return TT_EINVAL;
    tt_image_size(img, &iw, &ih);
    if (iw != w || ih != h) return TT_EINVAL;
    paint(tt_image_pixels(img), m, w, h, on, off);
    tt_image_touch(img);
    return TT_OK;
}
