/* Masks and PNG files: a round trip, every colour type libpng converts,
 * and damaged files (flipped bytes, truncations, absurd sizes) refused with
 * a message and no mask. */
#include "test.h"
#include "tether.h"

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A PNG in memory of a w×h image in format (a PNG_FORMAT_…), pixel i's channels all i·37 mod 256. */
static void *png_of(int w, int h, png_uint_32 format, size_t *size)
{
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    im.width = (png_uint_32)w;
    im.height = (png_uint_32)h;
    im.format = format;
    size_t n = PNG_IMAGE_SIZE(im);
    uint8_t *px = malloc(n);
    for (size_t i = 0; i < n; i++) px[i] = (uint8_t)((i / PNG_IMAGE_PIXEL_CHANNELS(format)) * 37);
    png_alloc_size_t len = 0;
    png_image_write_to_memory(&im, NULL, &len, 0, px, 0, NULL);
    void *buf = malloc(len);
    if (!png_image_write_to_memory(&im, buf, &len, 0, px, 0, NULL)) len = 0;
    free(px);
    *size = len;
    return buf;
}

TEST(mask_png_round_trip)
{
    tt_mask *m = tt_mask_create(131, 67, false);
    ENSURE_OK(tt_mask_fill_circle(m, 60, 30, 25, true));
    ENSURE_OK(tt_mask_set(m, 130, 66, true));
    ENSURE_OK(tt_mask_set(m, 0, 0, true));
    char path[64];
    snprintf(path, sizeof path, "/tmp/tether-mask-roundtrip-%ld.png", (long)getpid());
    ENSURE_OK(tt_mask_save_png(m, path));
    tt_mask *back = tt_mask_load_png(path, 127);
    remove(path);
    ENSURE(back != NULL);
    int w, h;
    ENSURE_OK(tt_mask_size(back, &w, &h));
    ENSURE(w == 131 && h == 67);
    ENSURE(tt_mask_count(back) == tt_mask_count(m));
    ENSURE(tt_mask_overlap_area(back, m, 0, 0) == tt_mask_count(m)); /* the same pixels, not just as many */
    ENSURE(tt_mask_save_png(m, "/nonexistent-dir/x.png") == TT_EINVAL);
    ENSURE(strstr(tt_mask_last_error(), "tt_mask_save_png") != NULL);
    ENSURE(tt_mask_save_png(NULL, path) == TT_EINVAL);
    tt_mask_destroy(back);
    tt_mask_destroy(m);
}

TEST(mask_png_every_format_by_alpha)
{
    static const png_uint_32 formats[] = { PNG_FORMAT_GRAY, PNG_FORMAT_GA, PNG_FORMAT_RGB, PNG_FORMAT_RGBA,
                                           PNG_FORMAT_LINEAR_Y, PNG_FORMAT_LINEAR_RGB_ALPHA };
    for (int f = 0; f < 6; f++) {
        size_t n;
        void *png = png_of(10, 7, formats[f], &n);
        ENSURE(n > 0);
        tt_mask *m = tt_mask_load_png_memory(png, n, 127);
        free(png);
        ENSURE(m != NULL);
        int64_t c = tt_mask_count(m);
        if (formats[f] & PNG_FORMAT_FLAG_ALPHA) ENSURE(c > 10 && c < 60); /* alpha i·37 mod 256 > 127 about half the time */
        else ENSURE(c == 70);                                            /* no alpha: opaque */
        tt_mask_destroy(m);
    }
}

static uint32_t crc(const uint8_t *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return ~c;
}

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24); p[1] = (uint8_t)(v >> 16); p[2] = (uint8_t)(v >> 8); p[3] = (uint8_t)v;
}

TEST(mask_png_damaged_files_refused)
{
    size_t n;
    uint8_t *png = png_of(40, 30, PNG_FORMAT_RGBA, &n);
    uint8_t *bad = malloc(n);
    ENSURE(png && n > 60);
    /* truncated anywhere: refused (the last 12 bytes are IEND, which libpng does not need) */
    for (size_t cut = 0; cut + 12 < n; cut += (cut < 64 ? 1 : 7)) {
        tt_mask *m = tt_mask_load_png_memory(png, cut, 127);
        if (m) { tt_test_fail(__FILE__, __LINE__, "truncated to %zu of %zu bytes: accepted", cut, n); tt_mask_destroy(m); return; }
        ENSURE(strstr(tt_mask_last_error(), "tt_mask_load_png_memory: ") != NULL);
    }
    /* a flipped byte in the signature or in a critical chunk's name, data or CRC: refused
     * (ancillary chunks, such as the sRGB the writer adds, may be dropped with a warning) */
    for (size_t at = 0; at + 12 < n; at++) {
        size_t c = 8; /* the chunk holding byte at */
        while (at >= 8 && c + 12 <= n && at >= c + 12 + ((size_t)png[c] << 24 | png[c + 1] << 16 | png[c + 2] << 8 | png[c + 3]))
            c += 12 + ((size_t)png[c] << 24 | png[c + 1] << 16 | png[c + 2] << 8 | png[c + 3]);
        bool critical = at < 8 || (at >= c + 4 && png[c + 4] >= 'A' && png[c + 4] <= 'Z');
        if (!critical || (at > 200 && at % 5)) continue;
        memcpy(bad, png, n);
        bad[at] ^= 0x10;
        tt_mask *m = tt_mask_load_png_memory(bad, n, 127);
        if (m) { tt_test_fail(__FILE__, __LINE__, "byte %zu flipped: accepted", at); tt_mask_destroy(m); return; }
    }
    /* a well-formed header (CRC right) claiming more than the limit on a side */
    memcpy(bad, png, n);
    put32(bad + 16, TT_MASK_MAX_SIDE + 1);
    put32(bad + 29, crc(bad + 12, 17));
    ENSURE(tt_mask_load_png_memory(bad, n, 127) == NULL);
    ENSURE(strstr(tt_mask_last_error(), "outside 1") != NULL);
    ENSURE(tt_mask_load_png("/nonexistent/file.png", 127) == NULL);
    ENSURE(strstr(tt_mask_last_error(), "/nonexistent/file.png") != NULL);
    ENSURE(tt_mask_load_png("Makefile", 127) == NULL); /* not a PNG */
    ENSURE(tt_mask_load_png(NULL, 127) == NULL);
    ENSURE(tt_mask_load_png_memory(png, n, 255) == NULL);
    ENSURE(tt_mask_load_png_memory(NULL, 5, 0) == NULL);
    free(bad);
    free(png);
}
