/* tests/fuzz/fuzz_c_mask.c — wrappers of tether/mask.h, first half: the
 * pool of live masks, making and freeing masks (sizes 0, 1, thin and past
 * the limit; images with bad strides and thresholds; PNG files and damaged
 * PNG bytes) and the pixel calls. A refused call leaves its masks as they
 * were (count and a hash of every pixel); results meet the answers known
 * for them: a copy, a rotation by 0 and a scale to the same size equal the
 * source, a cleared mask counts 0, two inversions give the original back. */
#include "fuzz_c.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* --- the pool ------------------------------------------------------------------ */

const char *fz_mn(int slot)
{
    static char buf[4][16];
    static unsigned k;
    char *b = buf[k++ % 4];
    if (slot < 0) return "NULL";
    snprintf(b, 16, "m%d", slot);
    return b;
}

/* A mask of the pool (or NULL 3% of the time, or an empty slot's NULL:
 * a call must refuse it). */
tt_mask *fz_mask_pick(fz *f, int *slot)
{
    int s = fz_chance(f, 3) ? -1 : (int)fz_below(f, FZ_MASKS);
    if (slot) *slot = s;
    tt_mask *m = s >= 0 ? f->masks[s] : NULL;
    if (!m) {
        f->must_fail = true;
        f->why_must = "a NULL mask";
        if (slot) *slot = -1;
    }
    return m;
}

static void free_slot(fz *f, int s)
{
    if (f->mask_mem[s]) free(f->mask_mem[s]); /* tt_mask_init's: the caller frees the memory */
    else tt_mask_destroy(f->masks[s]);
    f->masks[s] = NULL;
    f->mask_mem[s] = NULL;
}

void fz_mask_free_all(fz *f)
{
    for (int s = 0; s < FZ_MASKS; s++) free_slot(f, s);
}

/* A mask a call made: checked for a sane size, then kept in a random slot
 * (too large ones are freed at once, so the pool stays quick to hash). */
void fz_mask_put(fz *f, tt_mask *m, const char *what)
{
    if (!m) return;
    int w = -1, h = -1;
    if (tt_mask_size(m, &w, &h) != TT_OK || w < 1 || h < 1 || w > TT_MASK_MAX_SIDE || h > TT_MASK_MAX_SIDE)
        fz_fail(f, "%s made a mask of size %d x %d", what, w, h);
    int64_t n = tt_mask_count(m);
    if (n < 0 || n > (int64_t)w * h) fz_fail(f, "%s made a %d x %d mask counting %lld", what, w, h, (long long)n);
    if ((int64_t)w * h > FZ_MASK_AREA) {
        tt_mask_destroy(m);
        return;
    }
    int s = (int)fz_below(f, FZ_MASKS);
    free_slot(f, s);
    f->masks[s] = m;
    fz_log_more(f, " (kept as m%d)", s);
}

/* FNV-1a over the size and every pixel. */
uint64_t fz_mask_sig(const tt_mask *m)
{
    int w = 0, h = 0;
    if (!m || tt_mask_size(m, &w, &h) != TT_OK) return 0;
    uint64_t x = 0xcbf29ce484222325ull;
    x = (x ^ (uint64_t)w) * 0x100000001b3ull;
    x = (x ^ (uint64_t)h) * 0x100000001b3ull;
    x = (x ^ (uint64_t)tt_mask_count(m)) * 0x100000001b3ull;
    for (int y = 0; y < h; y++)
        for (int i = 0; i < w; i++) x = (x ^ (uint64_t)(tt_mask_get(m, i, y) + 7)) * 0x100000001b3ull;
    return x;
}

void fz_mres(fz *f, tt_result r)
{
    fz_log_more(f, " -> %s", fz_res_name(r));
    if (r != TT_OK) fz_log_more(f, " \"%.200s\"", tt_mask_last_error());
    if ((unsigned)r > TT_ESTATE) fz_fail(f, "the call returned %d, not a tt_result", (int)r);
    if (r != TT_OK) f->failed = true;
}

static void mnull(fz *f, const tt_mask *m)
{
    fz_log_more(f, " -> %s", m ? "mask" : "NULL");
    if (!m) {
        f->failed = true;
        fz_log_more(f, " \"%.200s\"", tt_mask_last_error());
    }
}

static void unchanged(fz *f, const tt_mask *m, uint64_t before, const char *what)
{
    if (m && fz_mask_sig(m) != before) fz_fail(f, "%s changed its mask's pixels", what);
}

/* A side: mostly small, now and then 1, thin and long, or out of range. */
static int side(fz *f)
{
    unsigned r = fz_below(f, 100);
    if (r < 70) return 1 + (int)fz_below(f, 96);
    if (r < 80) return 1;
    if (r < 90) return 100 + (int)fz_below(f, 3000);
    static const int bad[] = { 0, -1, -100000, TT_MASK_MAX_SIDE + 1, INT_MAX, INT_MIN, TT_MASK_MAX_SIDE, 2 };
    return bad[fz_below(f, sizeof bad / sizeof bad[0])];
}

static bool side_ok(int s) { return s >= 1 && s <= TT_MASK_MAX_SIDE; }

/* A pixel coordinate of a side: inside mostly, its neighbours, or far off. */
int fz_mask_coord(fz *f, int n)
{
    unsigned r = fz_below(f, 100);
    if (r < 80 && n > 0) return (int)fz_below(f, (uint32_t)n);
    if (r < 92) return r & 1 ? -1 : n;
    static const int far[] = { INT_MIN, INT_MAX, -1000000000, 1000000000, -2, 16384 };
    return far[fz_below(f, sizeof far / sizeof far[0])];
}

/* An offset of B (side nb) on A (side na): overlapping mostly, else far. */
int fz_mask_offset(fz *f, int na, int nb)
{
    unsigned r = fz_below(f, 100);
    if (r < 85) return -nb + (int)fz_below(f, (uint32_t)(na + nb + 1));
    static const int far[] = { INT_MIN, INT_MAX, TT_MASK_MAX_OFFSET, -TT_MASK_MAX_OFFSET, TT_MASK_MAX_OFFSET + 1,
                               -TT_MASK_MAX_OFFSET - 1, 0, 1 << 30 };
    return far[fz_below(f, sizeof far / sizeof far[0])];
}

int fz_mask_w(const tt_mask *m)
{
    int w = 0;
    tt_mask_size(m, &w, NULL);
    return w;
}

int fz_mask_h(const tt_mask *m)
{
    int h = 0;
    tt_mask_size(m, NULL, &h);
    return h;
}

/* --- making and freeing ------------------------------------------------------------ */

static void c_mask_last_error(fz *f)
{
    fz_log(f, "tt_mask_last_error()");
    FZ_HIT(f, tt_mask_last_error);
    if (!tt_mask_last_error()) fz_fail(f, "tt_mask_last_error returned NULL");
}

static void c_mask_create(fz *f)
{
    int w = side(f), h = side(f);
    bool filled = fz_chance(f, 50);
    if ((int64_t)w * h > (1 << 22) && fz_chance(f, 90)) h = 1; /* the largest only now and then */
    if (!side_ok(w) || !side_ok(h)) {
        f->must_fail = true;
        f->why_must = "a side out of range";
    }
    fz_log(f, "tt_mask_create(%d, %d, %d)", w, h, filled);
    FZ_HIT(f, tt_mask_create);
    tt_mask *m = tt_mask_create(w, h, filled);
    mnull(f, m);
    if (m && tt_mask_count(m) != (filled ? (int64_t)w * h : 0))
        fz_fail(f, "a new mask counts %lld", (long long)tt_mask_count(m));
    fz_mask_put(f, m, "tt_mask_create");
}

static void c_mask_destroy(fz *f)
{
    int s = fz_chance(f, 10) ? -1 : (int)fz_below(f, FZ_MASKS);
    fz_log(f, "tt_mask_destroy(%s)", fz_mn(s >= 0 && f->masks[s] ? s : -1));
    FZ_HIT(f, tt_mask_destroy);
    if (s < 0 || !f->masks[s]) tt_mask_destroy(NULL);
    else free_slot(f, s); /* a tt_mask_init mask's memory is freed instead */
}

static void c_mask_copy(fz *f)
{
    tt_mask *m = fz_mask_pick(f, NULL);
    uint64_t before = fz_mask_sig(m);
    fz_log(f, "tt_mask_copy(m)");
    FZ_HIT(f, tt_mask_copy);
    tt_mask *c = tt_mask_copy(m);
    mnull(f, c);
    unchanged(f, m, before, "tt_mask_copy");
    if (c && fz_mask_sig(c) != before) fz_fail(f, "a copy differs from its mask");
    fz_mask_put(f, c, "tt_mask_copy");
}

static void c_mask_footprint(fz *f)
{
    int w = side(f), h = side(f);
    fz_log(f, "tt_mask_footprint(%d, %d)", w, h);
    FZ_HIT(f, tt_mask_footprint);
    size_t n = tt_mask_footprint(w, h);
    fz_log_more(f, " -> %zu", n);
    if (!side_ok(w) || !side_ok(h) ? n != 0 : n < ((size_t)w * (size_t)h + 7) / 8)
        fz_fail(f, "tt_mask_footprint(%d, %d) is %zu", w, h, n);
}

static void c_mask_init(fz *f)
{
    int w = side(f), h = side(f);
    if ((int64_t)w * h > FZ_MASK_AREA) h = 1;
    size_t need = tt_mask_footprint(w, h);
    size_t size = need;
    unsigned how = fz_below(f, 10); /* 0: too small, 1: misaligned, 2: NULL memory */
    if (how == 0 && size) size--;
    unsigned char *mem = malloc(need + 16);
    if (!mem) abort();
    void *at = how == 1 ? mem + 4 : how == 2 ? NULL : mem;
    if (how <= 2 || !need) {
        f->must_fail = true;
        f->why_must = "bad memory or size";
    }
    fz_log(f, "tt_mask_init(%s, %zu, %d, %d)", how == 1 ? "mem + 4" : at ? "mem" : "NULL", size, w, h);
    FZ_HIT(f, tt_mask_init);
    tt_mask *m = tt_mask_init(at, how == 1 ? need : size, w, h);
    mnull(f, m);
    if (m && tt_mask_count(m) != 0) fz_fail(f, "tt_mask_init made a mask that is not clear");
    if (!m || (void *)m != (void *)at) {
        if (m && (void *)m != at) fz_fail(f, "tt_mask_init put the mask outside the memory given");
        free(mem);
        return;
    }
    fz_mask_put(f, m, "tt_mask_init");
    for (int s = 0; s < FZ_MASKS; s++)
        if (f->masks[s] == m) f->mask_mem[s] = mem;
}

static void c_mask_copy_into(fz *f)
{
    int sd, ss;
    tt_mask *dst = fz_mask_pick(f, &sd);
    tt_mask *src = fz_chance(f, 15) ? dst : fz_mask_pick(f, &ss);
    if (src == dst) ss = sd;
    tt_mask *fresh = NULL;
    if (src && fz_chance(f, 50)) { /* a destination of the right size */
        fresh = tt_mask_create(fz_mask_w(src), fz_mask_h(src), fz_chance(f, 50));
        dst = fresh;
        sd = 9;
    }
    f->must_fail = !dst || !src; /* the picks' verdict, for the final pair */
    uint64_t bd = fz_mask_sig(dst), bs = fz_mask_sig(src);
    fz_log(f, "tt_mask_copy_into(%s, %s)", fresh ? "fresh" : fz_mn(sd), fz_mn(ss));
    FZ_HIT(f, tt_mask_copy_into);
    tt_result r = tt_mask_copy_into(dst, src);
    fz_mres(f, r);
    if (r != TT_OK) unchanged(f, dst, bd, "a refused tt_mask_copy_into");
    else if (fz_mask_sig(dst) != bs) fz_fail(f, "tt_mask_copy_into made no copy");
    if (src != dst) unchanged(f, src, bs, "tt_mask_copy_into's source");
    tt_mask_destroy(fresh);
}

/* An RGBA image of w×h with random alpha runs, rows stride apart. */
static uint8_t *image(fz *f, int w, int h, size_t stride)
{
    size_t n = stride * (size_t)(h - 1) + 4 * (size_t)w;
    uint8_t *p = malloc(n);
    if (!p) abort();
    uint8_t a = 0;
    for (size_t i = 0; i < n; i++) {
        if (i % 4 == 3 && fz_chance(f, 10)) a = (uint8_t)fz_rand(f);
        p[i] = i % 4 == 3 ? a : (uint8_t)(fz_below(f, 4) * 85);
    }
    return p;
}

/* Draws an image's size, stride and threshold (a threshold of t is valid in [0, hi]). */
static bool image_args(fz *f, int *w, int *h, size_t *stride, int *t, int hi)
{
    *w = fz_chance(f, 90) ? 1 + (int)fz_below(f, 64) : side(f);
    *h = fz_chance(f, 90) ? 1 + (int)fz_below(f, 64) : side(f);
    if ((int64_t)*w * *h > FZ_MASK_AREA) *w = *h = 0;
    bool ok = side_ok(*w) && side_ok(*h);
    *stride = ok ? 4 * (size_t)*w + (fz_chance(f, 50) ? 0 : fz_below(f, 16)) : 4;
    if (ok && fz_chance(f, 5)) { /* too short a stride */
        *stride = fz_below(f, 4 * (uint32_t)*w);
        ok = false;
    }
    *t = fz_chance(f, 90) ? (int)fz_below(f, (uint32_t)hi + 1) : (int[]){ -1, hi + 1, INT_MAX, INT_MIN }[fz_below(f, 4)];
    return ok && *t >= 0 && *t <= hi;
}

static void c_mask_from_rgba(fz *f)
{
    int w, h, t;
    size_t stride;
    bool ok = image_args(f, &w, &h, &stride, &t, 254);
    uint8_t *img = side_ok(w) && side_ok(h) && stride >= 4 ? image(f, w, h, stride) : NULL;
    if (!ok || !img) {
        f->must_fail = true;
        f->why_must = "a bad image";
    }
    fz_log(f, "tt_mask_from_rgba(%s, %d, %d, %zu, %d)", img ? "img" : "NULL", w, h, stride, t);
    FZ_HIT(f, tt_mask_from_rgba);
    tt_mask *m = tt_mask_from_rgba(img, w, h, stride, t);
    mnull(f, m);
    for (int k = 0; m && k < 8; k++) {
        int x = (int)fz_below(f, (uint32_t)w), y = (int)fz_below(f, (uint32_t)h);
        if (tt_mask_get(m, x, y) != (img[(size_t)y * stride + 4 * (size_t)x + 3] > t))
            fz_fail(f, "tt_mask_from_rgba: pixel (%d, %d) does not follow its alpha", x, y);
    }
    free(img);
    fz_mask_put(f, m, "tt_mask_from_rgba");
}

static void c_mask_from_color(fz *f)
{
    int w, h, tol;
    size_t stride;
    bool ok = image_args(f, &w, &h, &stride, &tol, 255);
    uint8_t *img = side_ok(w) && side_ok(h) && stride >= 4 ? image(f, w, h, stride) : NULL;
    uint8_t key[3] = { (uint8_t)(fz_below(f, 4) * 85), (uint8_t)(fz_below(f, 4) * 85), (uint8_t)(fz_below(f, 4) * 85) };
    bool nokey = fz_chance(f, 3), invert = fz_chance(f, 50);
    if (!ok || !img || nokey) {
        f->must_fail = true;
        f->why_must = "a bad image or key";
    }
    fz_log(f, "tt_mask_from_color(%s, %d, %d, %zu, %s, %d, %d)", img ? "img" : "NULL", w, h, stride,
           nokey ? "NULL" : "key", tol, invert);
    FZ_HIT(f, tt_mask_from_color);
    tt_mask *m = tt_mask_from_color(img, w, h, stride, nokey ? NULL : key, tol, invert);
    mnull(f, m);
    for (int k = 0; m && k < 8; k++) {
        int x = (int)fz_below(f, (uint32_t)w), y = (int)fz_below(f, (uint32_t)h);
        const uint8_t *p = img + (size_t)y * stride + 4 * (size_t)x;
        bool match = abs(p[0] - key[0]) <= tol && abs(p[1] - key[1]) <= tol && abs(p[2] - key[2]) <= tol;
        if (tt_mask_get(m, x, y) != (match != invert))
            fz_fail(f, "tt_mask_from_color: pixel (%d, %d) does not follow its colour", x, y);
    }
    free(img);
    fz_mask_put(f, m, "tt_mask_from_color");
}

static void remove_png(void);

/* The fuzzer's PNG file (one per process, removed at exit; a sanitizer's
 * abort leaves it). */
static const char *png_path(void)
{
    static char path[64];
    if (!path[0]) {
        snprintf(path, sizeof path, "/tmp/fuzz_c_mask_%ld.png", (long)getpid());
        atexit(remove_png);
    }
    return path;
}

static void remove_png(void) { remove(png_path()); }

/* The PNG bytes of m (tt_mask_save_png through the file; NULL if it failed). */
static unsigned char *png_bytes(const tt_mask *m, size_t *n)
{
    *n = 0;
    if (tt_mask_save_png(m, png_path()) != TT_OK) return NULL;
    FILE *fp = fopen(png_path(), "rb");
    if (!fp) return NULL;
    fseek(fp, 0, SEEK_END);
    long len = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    unsigned char *b = len > 0 ? malloc((size_t)len) : NULL;
    if (b && fread(b, 1, (size_t)len, fp) != (size_t)len) {
        free(b);
        b = NULL;
    }
    fclose(fp);
    if (b) *n = (size_t)len;
    return b;
}

static void c_mask_save_png(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    if (m && (int64_t)fz_mask_w(m) * fz_mask_h(m) > 20000 && fz_chance(f, 80)) m = NULL, s = -1, f->must_fail = true;
    unsigned where = fz_below(f, 10);
    const char *path = where < 7 ? png_path() : where == 7 ? NULL : where == 8 ? "/nonexistent-dir/x.png" : "/tmp";
    if (where >= 7) {
        f->must_fail = true;
        f->why_must = "a path that cannot be written";
    }
    uint64_t before = fz_mask_sig(m);
    fz_log(f, "tt_mask_save_png(%s, \"%s\")", fz_mn(s), path ? path : "(NULL)");
    FZ_HIT(f, tt_mask_save_png);
    fz_mres(f, tt_mask_save_png(m, path));
    unchanged(f, m, before, "tt_mask_save_png");
}

static void c_mask_load_png(fz *f)
{
    unsigned where = fz_below(f, 10);
    const char *path = where < 7 ? png_path() : where == 7 ? NULL : where == 8 ? "/nonexistent-dir/x.png" : "/tmp";
    int t = fz_chance(f, 90) ? (int)fz_below(f, 255) : (int[]){ -1, 255, INT_MAX }[fz_below(f, 3)];
    if (where >= 7 || t < 0 || t > 254) {
        f->must_fail = true;
        f->why_must = "a bad path or threshold";
    }
    fz_log(f, "tt_mask_load_png(\"%s\", %d)", path ? path : "(NULL)", t);
    FZ_HIT(f, tt_mask_load_png);
    tt_mask *m = tt_mask_load_png(path, t);
    mnull(f, m);
    fz_mask_put(f, m, "tt_mask_load_png");
}

/* Flips bits, cuts short or overwrites a run of the bytes, now and then. */
static void damage(fz *f, unsigned char *b, size_t *n)
{
    if (!*n || !fz_chance(f, 60)) return;
    switch (fz_below(f, 3)) {
    case 0: *n = fz_below(f, (uint32_t)*n); break;
    case 1:
        for (unsigned k = 1 + fz_below(f, 6); k > 0; k--) b[fz_below(f, (uint32_t)*n)] ^= (unsigned char)(1u << fz_below(f, 8));
        break;
    default: {
        size_t at = fz_below(f, (uint32_t)*n);
        for (size_t i = at; i < *n && i < at + 8; i++) b[i] = (unsigned char)fz_rand(f);
    }
    }
}

static void c_mask_load_png_memory(fz *f)
{
    tt_mask *src = fz_mask_pick(f, NULL);
    if (src && (int64_t)fz_mask_w(src) * fz_mask_h(src) > 20000) src = NULL;
    f->must_fail = false;
    size_t n = 0, whole;
    unsigned char *b = src ? png_bytes(src, &n) : NULL;
    whole = n;
    if (b) damage(f, b, &n);
    int t = fz_chance(f, 90) ? (int)fz_below(f, 255) : (int[]){ -1, 255, INT_MAX }[fz_below(f, 3)];
    if (!b || t < 0 || t > 254) {
        f->must_fail = true;
        f->why_must = "no bytes or a bad threshold";
    }
    fz_log(f, "tt_mask_load_png_memory(%s, %zu, %d)", b ? (n == whole ? "png" : "damaged png") : "NULL", n, t);
    FZ_HIT(f, tt_mask_load_png_memory);
    tt_mask *m = tt_mask_load_png_memory(b, n, t);
    mnull(f, m);
    if (m && n == whole && fz_mask_sig(m) != fz_mask_sig(src))
        fz_fail(f, "a mask loaded from its own PNG bytes differs from it");
    free(b);
    fz_mask_put(f, m, "tt_mask_load_png_memory");
}

static void c_mask_rotated(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    unsigned r = fz_below(f, 100);
    double a = r < 20 ? 0.0 : r < 40 ? (double)fz_below(f, 8) * (M_PI / 2) : r < 90 ? fz_real(f, -7, 7) : fz_nasty(f);
    if (!(fabs(a) <= 1e6)) {
        f->must_fail = true;
        f->why_must = "an angle out of range";
    }
    uint64_t before = fz_mask_sig(m);
    fz_log(f, "tt_mask_rotated(%s, %s)", fz_mn(s), fz_d(a));
    FZ_HIT(f, tt_mask_rotated);
    tt_mask *out = tt_mask_rotated(m, a);
    mnull(f, out);
    unchanged(f, m, before, "tt_mask_rotated");
    if (out && a == 0 && fz_mask_sig(out) != before) fz_fail(f, "a mask rotated by 0 differs from it");
    fz_mask_put(f, out, "tt_mask_rotated");
}

static void c_mask_scaled(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    bool same = m && fz_chance(f, 20);
    int w = same ? fz_mask_w(m) : side(f), h = same ? fz_mask_h(m) : side(f);
    if ((int64_t)w * h > FZ_MASK_AREA && fz_chance(f, 90)) h = 1;
    if (!side_ok(w) || !side_ok(h)) {
        f->must_fail = true;
        f->why_must = "a side out of range";
    }
    uint64_t before = fz_mask_sig(m);
    fz_log(f, "tt_mask_scaled(%s, %d, %d)", fz_mn(s), w, h);
    FZ_HIT(f, tt_mask_scaled);
    tt_mask *out = tt_mask_scaled(m, w, h);
    mnull(f, out);
    unchanged(f, m, before, "tt_mask_scaled");
    if (out && same && fz_mask_sig(out) != before) fz_fail(f, "a mask scaled to its own size differs from it");
    fz_mask_put(f, out, "tt_mask_scaled");
}

const fz_entry fz_mask_entries[] = {
    { "tt_mask_last_error", c_mask_last_error, 1 },
    { "tt_mask_create", c_mask_create, 3 },
    { "tt_mask_destroy", c_mask_destroy, 1 },
    { "tt_mask_copy", c_mask_copy, 1 },
    { "tt_mask_footprint", c_mask_footprint, 1 },
    { "tt_mask_init", c_mask_init, 1 },
    { "tt_mask_copy_into", c_mask_copy_into, 1 },
    { "tt_mask_from_rgba", c_mask_from_rgba, 2 },
    { "tt_mask_from_color", c_mask_from_color, 1 },
    { "tt_mask_load_png", c_mask_load_png, 1 },
    { "tt_mask_load_png_memory", c_mask_load_png_memory, 2 },
    { "tt_mask_save_png", c_mask_save_png, 1 },
    { "tt_mask_rotated", c_mask_rotated, 2 },
    { "tt_mask_scaled", c_mask_scaled, 1 },
    { NULL, NULL, 0 },
};
