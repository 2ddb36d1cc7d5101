/* tether — PNG files through libpng: frames out, images in. */
#include "render_internal.h"

#include <errno.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static tt_result write_png(const char *path, const uint8_t *rgba, int width, int height, size_t stride, bool bottom_up,
                           char *err, size_t n)
{
    if (!path || !rgba || width < 1 || height < 1 || stride < (size_t)width * 4) {
        tt__errf(err, n, "tt_png_write: bad arguments");
        return TT_EINVAL;
    }
    FILE *f = fopen(path, "wb");
    if (!f) {
        tt__errf(err, n, "tt_png_write: cannot open '%s': %s", path, strerror(errno));
        return TT_EINVAL;
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    png_bytep *rows = malloc((size_t)height * sizeof *rows);
    if (!png || !info || !rows) {
        png_destroy_write_struct(&png, &info);
        free(rows);
        fclose(f);
        tt__errf(err, n, "tt_png_write: out of memory");
        return TT_ENOMEM;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        free(rows);
        fclose(f);
        tt__errf(err, n, "tt_png_write: libpng failed writing '%s'", path);
        return TT_EINVAL;
    }
    png_init_io(png, f);
    png_set_compression_level(png, 3); /* frames: fast beats small */
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    for (int y = 0; y < height; y++)
        rows[y] = (png_bytep)(rgba + (size_t)(bottom_up ? height - 1 - y : y) * stride);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(rows);
    if (fclose(f) != 0) {
        tt__errf(err, n, "tt_png_write: cannot finish '%s': %s", path, strerror(errno));
        return TT_EINVAL;
    }
    return TT_OK;
}

tt_result tt_png_write(const char *path, const uint8_t *rgba, int width, int height, size_t stride, bool bottom_up,
                       char *err, size_t n)
{
    char dummy[8];
    return write_png(path, rgba, width, height, stride, bottom_up, err ? err : dummy, err ? n : sizeof dummy);
}

tt_image *tt_image_load_png(const char *path, char *err, size_t n)
{
    char dummy[8];
    if (!err) { err = dummy; n = sizeof dummy; }
    if (!path) { tt__errf(err, n, "tt_image_load_png: path is NULL"); return NULL; }
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&im, path)) {
        tt__errf(err, n, "tt_image_load_png: '%s': %s", path, im.message);
        return NULL;
    }
    im.format = PNG_FORMAT_RGBA;
    if (im.width < 1 || im.height < 1 || im.width > 16384 || im.height > 16384) {
        tt__errf(err, n, "tt_image_load_png: '%s' is %u x %u, more than 16384 on a side", path, im.width, im.height);
        png_image_free(&im);
        return NULL;
    }
    tt_image *img = tt_image_create((int)im.width, (int)im.height);
    if (!img) {
        tt__errf(err, n, "tt_image_load_png: out of memory");
        png_image_free(&im);
        return NULL;
    }
    if (!png_image_finish_read(&im, NULL, img->rgba, 0, NULL)) {
        tt__errf(err, n, "tt_image_load_png: '%s': %s", path, im.message);
        png_image_free(&im);
        tt_image_destroy(img);
        return NULL;
    }
    return img;
}
