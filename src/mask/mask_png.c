/* tether — masks from and to PNG files (libpng's simplified API). A file
 * that libpng refuses (bad signature, CRC, truncated data, absurd size) is
 * refused with libpng's reason; nothing is half made. */
#include "mask_internal.h"

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Reads the started image im into a new mask (frees im either way). */
static tt_mask *finish(const char *fn, const char *what, png_image *im, int threshold)
{
    if (im->width < 1 || im->height < 1 || im->width > TT_MASK_MAX_SIDE || im->height > TT_MASK_MAX_SIDE) {
        tt__mask_fail(TT_EINVAL, "%s: %s is %u x %u, outside 1…%d on a side", fn, what, im->width, im->height,
                      TT_MASK_MAX_SIDE);
        png_image_free(im);
        return NULL;
    }
    /* grey + alpha is all a mask needs: half the memory of RGBA */
    im->format = PNG_FORMAT_GA;
    size_t stride = (size_t)im->width * 2;
    uint8_t *ga = malloc(stride * im->height);
    if (!ga) {
        tt__mask_fail(TT_ENOMEM, "%s: out of memory for %s", fn, what);
        png_image_free(im);
        return NULL;
    }
    tt_mask *m = NULL;
    if (!png_image_finish_read(im, NULL, ga, (png_int_32)stride, NULL))
        tt__mask_fail(TT_EINVAL, "%s: %s: %s", fn, what, im->message);
    else if ((m = tt__mask_alloc(fn, (int)im->width, (int)im->height)) != NULL)
        for (int y = 0; y < m->h; y++)
            for (int x = 0; x < m->w; x++)
                if (ga[(size_t)y * stride + 2 * (size_t)x + 1] > threshold) tt__mask_put(m, x, y, true);
    png_image_free(im);
    free(ga);
    return m;
}

static bool check_threshold(const char *fn, int threshold)
{
    if (threshold >= 0 && threshold <= 254) return true;
    tt__mask_fail(TT_EINVAL, "%s: threshold %d outside 0…254", fn, threshold);
    return false;
}

tt_mask *tt_mask_load_png(const char *path, int threshold)
{
    const char *fn = "tt_mask_load_png";
    if (!path) {
        tt__mask_fail(TT_EINVAL, "%s: path is NULL", fn);
        return NULL;
    }
    if (!check_threshold(fn, threshold)) return NULL;
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&im, path)) {
        tt__mask_fail(TT_EINVAL, "%s: '%s': %s", fn, path, im.message);
        png_image_free(&im);
        return NULL;
    }
    char what[160];
    snprintf(what, sizeof what, "'%s'", path);
    return finish(fn, what, &im, threshold);
}

tt_mask *tt_mask_load_png_memory(const void *data, size_t size, int threshold)
{
    const char *fn = "tt_mask_load_png_memory";
    if (!data) {
        tt__mask_fail(TT_EINVAL, "%s: data is NULL", fn);
        return NULL;
    }
    if (!check_threshold(fn, threshold)) return NULL;
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&im, data, size)) {
        tt__mask_fail(TT_EINVAL, "%s: %s", fn, im.message);
        png_image_free(&im);
        return NULL;
    }
    return finish(fn, "the PNG data", &im, threshold);
}

tt_result tt_mask_save_png(const tt_mask *m, const char *path)
{
    if (!m || !path) return tt__mask_fail(TT_EINVAL, "tt_mask_save_png: %s is NULL", m ? "path" : "mask");
    uint8_t *ga = malloc((size_t)m->w * (size_t)m->h * 2);
    if (!ga) return tt__mask_fail(TT_ENOMEM, "tt_mask_save_png: out of memory");
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++) {
            uint8_t v = tt__mask_bit(m, x, y) ? 255 : 0;
            ga[2 * ((size_t)y * (size_t)m->w + (size_t)x)] = v;
            ga[2 * ((size_t)y * (size_t)m->w + (size_t)x) + 1] = v;
        }
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    im.width = (png_uint_32)m->w;
    im.height = (png_uint_32)m->h;
    im.format = PNG_FORMAT_GA;
    int ok = png_image_write_to_file(&im, path, 0, ga, 0, NULL);
    free(ga);
    if (!ok) {
        tt_result r = tt__mask_fail(TT_EINVAL, "tt_mask_save_png: '%s': %s", path, im.message);
        png_image_free(&im);
        return r;
    }
    return TT_OK;
}
