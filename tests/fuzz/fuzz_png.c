/* tests/fuzz/fuzz_png.c — a seeded fuzzer of the mask PNG loader
 * (tt_mask_load_png_memory), run by `make fuzz` after the Lua API fuzzer:
 *   build/fuzz_png SECONDS SEED
 * Seeds are small PNGs of every colour type and bit depth libpng writes,
 * interlaced or not, with palettes and tRNS; each round damages one (bit
 * flips, bytes set to edge values, truncation, spliced bytes, header fields
 * changed) and, half of the time, recomputes every chunk's CRC so that the
 * damage reaches the decoder instead of stopping at the checksum. A mask
 * that comes back must be whole: its size within the limits, its count
 * within its area, the bits past its width clear (its inverse counts the
 * rest). A crash or a sanitizer report is the failure it looks for; the
 * last input is kept in build/fuzz/png-last.bin for replay. Ends with
 * "N passed, M failed" like the tests. */
#include "tether.h"

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static uint64_t rng;
static uint32_t rnd(uint32_t n)
{
    rng ^= rng >> 12;
    rng ^= rng << 25;
    rng ^= rng >> 27;
    return (uint32_t)((rng * 0x2545F4914F6CDD1Du) >> 33) % n;
}

typedef struct buf {
    uint8_t *p;
    size_t n, cap;
} buf;

static void put(buf *b, const void *d, size_t n)
{
    if (b->n + n > b->cap) {
        b->cap = (b->n + n) * 2;
        b->p = realloc(b->p, b->cap);
        if (!b->p) { fprintf(stderr, "fuzz_png: out of memory\n"); exit(2); }
    }
    memcpy(b->p + b->n, d, n);
    b->n += n;
}

static void write_cb(png_structp png, png_bytep d, size_t n) { put(png_get_io_ptr(png), d, n); }
static void flush_cb(png_structp png) { (void)png; }

/* A PNG of random pixels: colour type, depth, interlace, palette and tRNS picked at random. */
static buf make_seed(void)
{
    static const int types[] = { PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                 PNG_COLOR_TYPE_RGB_ALPHA, PNG_COLOR_TYPE_PALETTE };
    int type = types[rnd(5)];
    volatile int depth; /* read after setjmp */
    if (type == PNG_COLOR_TYPE_GRAY) depth = (int[]){ 1, 2, 4, 8, 16 }[rnd(5)];
    else if (type == PNG_COLOR_TYPE_PALETTE) depth = (int[]){ 1, 2, 4, 8 }[rnd(4)];
    else depth = rnd(2) ? 8 : 16;
    int w = 1 + (int)rnd(70), h = 1 + (int)rnd(40);
    buf b = { NULL, 0, 0 };
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    size_t rowbytes = ((size_t)w * 8 * 8 + 7) / 8; /* ample for any type and depth */
    uint8_t *row = malloc(rowbytes);
    if (setjmp(png_jmpbuf(png))) { fprintf(stderr, "fuzz_png: libpng refused to write a seed\n"); exit(2); }
    png_set_write_fn(png, &b, write_cb, flush_cb);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, type, rnd(3) == 0 ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (type == PNG_COLOR_TYPE_PALETTE) {
        png_color pal[256];
        png_byte alpha[256];
        int n = 1 << depth;
        for (int i = 0; i < n; i++) { pal[i] = (png_color){ (png_byte)rnd(256), (png_byte)rnd(256), (png_byte)rnd(256) }; alpha[i] = (png_byte)rnd(256); }
        png_set_PLTE(png, info, pal, n);
        if (rnd(2)) png_set_tRNS(png, info, alpha, n, NULL);
    } else if ((type == PNG_COLOR_TYPE_GRAY || type == PNG_COLOR_TYPE_RGB) && rnd(2)) {
        png_color_16 key = { 0, (png_uint_16)rnd(1u << (depth > 8 ? 8 : depth)), 0, 0, 0 };
        key.red = key.green = key.blue = key.gray;
        png_set_tRNS(png, info, NULL, 0, &key);
    }
    png_write_info(png, info);
    int passes = png_set_interlace_handling(png);
    for (int p = 0; p < passes; p++)
        for (int y = 0; y < h; y++) {
            for (size_t i = 0; i < rowbytes; i++) row[i] = (uint8_t)(rnd(4) ? rnd(256) : 0);
            png_write_row(png, row);
        }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(row);
    return b;
}

static uint32_t crc32_of(const uint8_t *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return ~c;
}

static uint32_t get32(const uint8_t *p) { return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]; }
static void put32(uint8_t *p, uint32_t v) { p[0] = (uint8_t)(v >> 24); p[1] = (uint8_t)(v >> 16); p[2] = (uint8_t)(v >> 8); p[3] = (uint8_t)v; }

/* Recomputes the CRC of every chunk whose length still fits in the data. */
static void fix_crcs(uint8_t *p, size_t n)
{
    for (size_t c = 8; c + 12 <= n;) {
        size_t len = get32(p + c);
        if (len > n - c - 12) break;
        put32(p + c + 8 + len, crc32_of(p + c + 4, 4 + len));
        c += 12 + len;
    }
}

static void mutate(uint8_t *p, size_t *n)
{
    static const uint8_t edge[] = { 0, 1, 0x7f, 0x80, 0xfe, 0xff };
    for (int k = 1 + (int)rnd(4); k > 0 && *n > 0; k--) {
        size_t at = rnd((uint32_t)*n);
        switch (rnd(6)) {
        case 0: p[at] ^= (uint8_t)(1u << rnd(8)); break;
        case 1: p[at] = edge[rnd(6)]; break;
        case 2: *n = at; break;                                            /* truncated */
        case 3: if (at + 4 <= *n) put32(p + at, rnd(2) ? 0x7fffffffu : rnd(70000)); break; /* a length or size */
        case 4: if (*n >= 24) put32(p + 16 + 4 * rnd(2), rnd(2) ? (uint32_t)rnd(20000) : 0x80000000u); break; /* IHDR w/h */
        default: { size_t from = rnd((uint32_t)*n), len = rnd(16); /* bytes copied from elsewhere */
            if (from + len <= *n && at + len <= *n) memmove(p + at, p + from, len); }
        }
    }
    if (rnd(2)) fix_crcs(p, *n);
}

/* A mask that came back is whole; returns false (with a message) if not. */
static bool check(tt_mask *m)
{
    int w, h;
    if (tt_mask_size(m, &w, &h) != TT_OK || w < 1 || h < 1 || w > TT_MASK_MAX_SIDE || h > TT_MASK_MAX_SIDE) {
        printf("fuzz_png: a mask of size %d x %d came back\n", w, h);
        return false;
    }
    int64_t c = tt_mask_count(m), area = (int64_t)w * h;
    tt_mask_invert(m);
    if (c < 0 || c > area || tt_mask_count(m) != area - c) {
        printf("fuzz_png: %d x %d mask counts %lld, its inverse %lld\n", w, h, (long long)c, (long long)tt_mask_count(m));
        return false;
    }
    return true;
}

int main(int argc, char **argv)
{
    double seconds = argc > 1 ? atof(argv[1]) : 10;
    uint64_t seed = argc > 2 ? strtoull(argv[2], NULL, 10) : (uint64_t)time(NULL);
    const char *last = argc > 3 ? argv[3] : NULL;
    rng = seed * 0x9E3779B97F4A7C15u + 1;
    /* One file for the whole run, rewritten in place: truncating it to zero
     * for each input made ext4 flush it to disk every time (auto_da_alloc),
     * and the run waited on the disk more than it fuzzed. What write() put
     * in the page cache survives a crash of this process. */
    FILE *f = last ? fopen(last, "wb") : NULL;
    clock_t start = clock();
    long rounds = 0, loaded = 0;
    bool ok = true;
    while (ok && (double)(clock() - start) / CLOCKS_PER_SEC < seconds) {
        buf b = make_seed();
        for (int k = 0; k < 50 && ok; k++, rounds++) {
            uint8_t *d = malloc(b.n);
            size_t n = b.n;
            memcpy(d, b.p, n);
            if (k) mutate(d, &n); /* the first of each seed as written: it must load */
            if (f) {
                rewind(f);
                fwrite(d, 1, n, f);
                fflush(f);
                if (ftruncate(fileno(f), (off_t)n) != 0) { fclose(f); f = NULL; }
            }
            tt_mask *m = tt_mask_load_png_memory(d, n, (int)rnd(255));
            if (!m && k == 0) {
                printf("fuzz_png: an undamaged seed was refused: %s\n", tt_mask_last_error());
                ok = false;
            }
            if (m) { loaded++; ok = check(m); }
            tt_mask_destroy(m);
            free(d);
        }
        free(b.p);
    }
    if (f) fclose(f);
    printf("fuzz_png: %ld inputs in %.1f s, seed %llu, %ld loaded as masks\n", rounds,
           (double)(clock() - start) / CLOCKS_PER_SEC, (unsigned long long)seed, loaded);
    printf("%d passed, %d failed\n", ok ? 1 : 0, ok ? 0 : 1);
    return ok ? 0 : 1;
}
