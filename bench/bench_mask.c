/* tether — pixel-mask overlap benchmark, C side: makes the masks every side
 * of the comparison uses (saved as PNGs into the output folder, so the Lua
 * and pygame runs read the very same pixels), and times the C calls and the
 * plain per-pixel reference on them. bench/mask_bench.lua then times the
 * same calls from Lua and pygame's beside them and prints the table. */
#include "bench.h"
#include "tether.h"

#include <stdlib.h>

static uint64_t rng = 0x853c49e6748fea9bu;
static uint64_t next64(void)
{
    rng ^= rng >> 12;
    rng ^= rng << 25;
    rng ^= rng >> 27;
    return rng * 0x2545F4914F6CDD1Du;
}

/* A random (half the pixels) or solid s×s mask and its pixels as bytes. */
static tt_mask *make(int s, bool solid, unsigned char *px)
{
    tt_mask *m = tt_mask_create(s, s, solid);
    for (int y = 0; y < s; y++)
        for (int x = 0; x < s; x++) {
            unsigned char v = solid ? 1 : (unsigned char)(next64() >> 63);
            px[y * s + x] = v;
            if (v) tt_mask_set(m, x, y, true);
        }
    return m;
}

/* The per-pixel reference: op 0 first point, 1 area, 2 overlap mask. */
static int64_t reference(int op, const unsigned char *a, const unsigned char *b, int s, int dx, int dy, unsigned char *out)
{
    int64_t n = 0;
    for (int y = 0; y < s; y++)
        for (int x = 0; x < s; x++) {
            int bx = x - dx, by = y - dy;
            int v = a[y * s + x] && bx >= 0 && by >= 0 && bx < s && by < s && b[by * s + bx];
            if (op == 0 && v) return (int64_t)y * s + x;
            if (op == 2) out[y * s + x] = (unsigned char)v;
            n += v;
        }
    return op == 0 ? -1 : n;
}

/* Median ns per call over 7 batches of calls taking ≥ 2 ms each. */
static double time_call(int op, bool ref, tt_mask *a, tt_mask *b, const unsigned char *pa, const unsigned char *pb, int s,
                        int dx, int dy, unsigned char *out)
{
    double t[7];
    long n = 1;
    volatile int64_t sink = 0;
    for (int r = 0; r < 7; r++) {
        double t0, dt;
        for (;;) {
            t0 = bench_now_ns();
            for (long i = 0; i < n; i++) {
                if (ref) sink += reference(op, pa, pb, s, dx, dy, out);
                else if (op == 0) { int x, y; sink += tt_mask_overlap(a, b, dx, dy, &x, &y); }
                else if (op == 1) sink += tt_mask_overlap_area(a, b, dx, dy);
                else tt_mask_destroy(tt_mask_overlap_mask(a, b, dx, dy));
            }
            dt = bench_now_ns() - t0;
            if (dt >= 2e6 || r > 0) break;
            n *= 4;
        }
        t[r] = dt / n;
    }
    (void)sink;
    return bench_median(t, 7);
}

static const char *const OPS[] = { "overlap", "overlap_area", "overlap_mask" };

void bench_mask(const char *dir)
{
    printf("\n== Pixel masks: overlap from C and the per-pixel reference (the Lua and pygame side: bench/mask_bench.lua) ==\n");
    printf("%-24s %-13s %12s %14s %8s\n", "masks", "call", "C ns", "per-pixel ns", "ratio");
    FILE *csv = bench_csv(dir, "mask_c.csv", "case,call,c_ns,reference_ns");
    static const int sizes[] = { 32, 128, 512, 1024 };
    unsigned char *pa = malloc(1024 * 1024), *pb = malloc(1024 * 1024), *out = malloc(1024 * 1024);
    char path[1024];
    for (int si = 0; si < 4; si++)
        for (int solid = 0; solid < 2; solid++) {
            int s = sizes[si];
            tt_mask *a = make(s, solid, pa), *b = make(s, solid, pb);
            const char *kind = solid ? "solid" : "random";
            snprintf(path, sizeof path, "%s/mask_%s_a_%d.png", dir, kind, s);
            tt_mask_save_png(a, path);
            snprintf(path, sizeof path, "%s/mask_%s_b_%d.png", dir, kind, s);
            tt_mask_save_png(b, path);
            for (int al = 0; al < 2; al++) {
                int dx = al ? 0 : 13, dy = 7; /* aligned: B's words sit on A's; unaligned: shifted within words */
                for (int op = 0; op < 3; op++) {
                    double c = time_call(op, false, a, b, pa, pb, s, dx, dy, out);
                    double r = time_call(op, true, a, b, pa, pb, s, dx, dy, out);
                    char name[64];
                    snprintf(name, sizeof name, "%s-%d-%s", kind, s, al ? "aligned" : "unaligned");
                    printf("%-24s %-13s %12.1f %14.1f %8.1f\n", name, OPS[op], c, r, r / c);
                    fprintf(csv, "%s,%s,%.2f,%.2f\n", name, OPS[op], c, r);
                }
            }
            tt_mask_destroy(a);
            tt_mask_destroy(b);
        }
    /* the worst case: a random 1024² mask against its complement shifted with each offset, so no bit is shared at
     * any of them and every call scans everything; the offset changes every call */
    rng = 0x853c49e6748fea9bu;
    tt_mask *a = make(1024, false, pa);
    snprintf(path, sizeof path, "%s/mask_worst.txt", dir);
    FILE *off = fopen(path, "w");
    for (int k = 0; k < 8; k++) {
        int dx = (int)(next64() % 61) - 30, dy = (int)(next64() % 61) - 30;
        if (off) fprintf(off, "%d %d\n", dx, dy);
        tt_mask *b = tt_mask_create(1024, 1024, true);
        for (int y = 0; y < 1024; y++)
            for (int x = 0; x < 1024; x++) {
                int ax = x + dx, ay = y + dy;
                if (ax >= 0 && ay >= 0 && ax < 1024 && ay < 1024 && pa[ay * 1024 + ax]) tt_mask_set(b, x, y, false);
            }
        if (tt_mask_overlap(a, b, dx, dy, NULL, NULL)) printf("mask bench: worst case %d shares a bit: BUG\n", k);
        snprintf(path, sizeof path, "%s/mask_worst_%d.png", dir, k);
        tt_mask_save_png(b, path);
        tt_mask_destroy(b);
    }
    if (off) fclose(off);
    snprintf(path, sizeof path, "%s/mask_worst_a.png", dir);
    tt_mask_save_png(a, path);
    tt_mask_destroy(a);
    fclose(csv);
    free(pa);
    free(pb);
    free(out);
}
