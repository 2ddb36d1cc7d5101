/* tether — a terrain's distance band: per pixel, the signed distance to the
 * boundary of the solid pixels, in pixels, clamped to ±band. The raw
 * distance is exact: the Euclidean distance to the nearest pixel of the
 * other state, less half a pixel. It is a function of the pixels within
 * band of it and nothing else, so an update of the changed box grown by
 * the band (and the blur) gives what a rebuild gives, by construction.
 *
 * Cost follows the changed area, and each step is a few operations per
 * pixel on 16 pixels at once: the pixels are read as 64-bit words; each
 * column's distance to the nearest pixel of each state comes from a sweep
 * down and one up (bytes, clamped at band + 1); only pixels with a pixel of
 * the other state within band rows and columns (those words grown
 * sideways) search along their row for the nearest column's, the others
 * are ±band at once; the search stops at the first dx no pixel can gain
 * from. The blur is a box of running sums in fixed point: integer sums are
 * exact in any order, so a sum started anywhere gives what one started at
 * the terrain's edge gives.
 *
 * A carve of a radius-20-pixel crater at the default band: about 0.39 M
 * instructions (callgrind), 2.56 M with Danielsson's propagation and a
 * blur in floats before. */
#include "terrain_internal.h"

#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/* The band is blurred by a box of 2·BLUR + 1 pixels each way (7: at 5 a
 * frictionless ball on a 30° pixel slope lost 4.7 % of g·sin θ to the
 * remaining bumps, at 7 1.4 %, at 40° 6.1 % and 2.3 %): a straight
 * surface's distance is linear and a box keeps it, while the bumps of its
 * pixel stairs are averaged away, so the gradient turns smoothly along a
 * slope. */
#define BLUR 3
#define TAPS (2 * BLUR + 1)
/* Raw distances in 1/2^16 pixel: ±32 pixels times 49 taps fits an int32. */
#define QBITS 16

typedef struct region {
    int x0, y0, w, h;
} region;

typedef struct regions_t {
    region R; /* read: pixels (a ring outside the terrain included) */
    region E; /* raw distances: W grown by the blur, within the terrain */
    region W; /* written */
} regions_t;

static inline int clampi(int v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : v; }

/* The regions an update of pixels [x0, x1] × [y0, y1] reads and writes. */
static void regions(const tt__terrain *T, int x0, int y0, int x1, int y1, regions_t *g)
{
    const tt_mask *m = T->m;
    const int B = T->def.band;
    /* written: the change grown by the band (a pixel further than B + 0.5
     * is none of a raw distance's business) and the blur; raw: by the blur
     * again; read: by the band */
    const int wx0 = clampi(x0 - B - BLUR, 0, m->w - 1), wx1 = clampi(x1 + B + BLUR, 0, m->w - 1);
    const int wy0 = clampi(y0 - B - BLUR, 0, m->h - 1), wy1 = clampi(y1 + B + BLUR, 0, m->h - 1);
    g->W = (region){wx0, wy0, wx1 - wx0 + 1, wy1 - wy0 + 1};
    const int ex0 = clampi(wx0 - BLUR, 0, m->w - 1), ex1 = clampi(wx1 + BLUR, 0, m->w - 1);
    const int ey0 = clampi(wy0 - BLUR, 0, m->h - 1), ey1 = clampi(wy1 + BLUR, 0, m->h - 1);
    g->E = (region){ex0, ey0, ex1 - ex0 + 1, ey1 - ey0 + 1};
    /* a ring outside the terrain is read too: it is empty, the solid border's
     * nearest free pixel (no pixel beyond the ring is nearer to one inside) */
    const int rx0 = ex0 - B < -1 ? -1 : ex0 - B, ry0 = ey0 - B < -1 ? -1 : ey0 - B;
    const int rx1 = ex1 + B > m->w ? m->w : ex1 + B, ry1 = ey1 + B > m->h ? m->h : ey1 + B;
    g->R = (region){rx0, ry0, rx1 - rx0 + 1, ry1 - ry0 + 1};
}

/* The scratch of one update, carved from ts->scr.buf. */
typedef struct scratch_t {
    int nw;             /* words per row of R */
    size_t gw;          /* bytes per row of g: 64·nw and PAD each side */
    uint64_t *bits;     /* R's pixels, R.h rows of nw words, bit i = pixel R.x0 + i */
    uint8_t *sb;        /* the same as bytes, 0xFF solid, R.h rows of 64·nw */
    uint8_t *g[2];      /* per pixel of E's rows (R's columns, PAD each side): rows to the nearest empty
                         * [0] / solid [1] pixel in its column, B + 1: none within B */
    uint8_t *run[2];    /* the same for one row, as the sweeps down and up the columns carry it */
    uint64_t *near[4];  /* a row's pixels with an empty [0, 1] / solid [2, 3] pixel within B rows and
                         * columns (two buffers each: their rows grow sideways from one into the other) */
    uint64_t *need;     /* a row's pixels with one of the other state so near */
    int32_t *raw;       /* one row of E, from RAW0 on (before it and after it: its edge pixels, as the
                         * blur reads them at the terrain's border, and a block's overhang) */
    int32_t *hs;        /* E.h rows of W's width (hs_width): sums across */
    int32_t *col;       /* the same for one row: sums down */
} scratch_t;

/* Pixels searched together, and the padding of g each side (≥ the band
 * and a block's overhang, a multiple of 16). */
#define LANES 16
#define PAD 48
#define RAW0 (BLUR + 1)

static size_t align16(size_t n) { return (n + 15) & ~(size_t)15; }

/* A row of sums across: W's width rounded up to whole vectors of 4. */
static inline int hs_width(const region *W) { return (W->w + 3) & ~3; }

/* Lays the scratch out (base NULL: only counts); its size in bytes. */
static size_t layout(const regions_t *g, unsigned char *base, scratch_t *s)
{
    const size_t nw = ((size_t)g->R.w + 63) / 64, gw = 64 * nw + 2 * PAD, eh = (size_t)g->E.h;
    const size_t rh = (size_t)g->R.h, hw = (size_t)hs_width(&g->W);
    const size_t sizes[] = {nw * rh * 8, 64 * nw * rh, gw * eh, gw * eh, 64 * nw, 64 * nw,
                            nw * 8, nw * 8, nw * 8, nw * 8, nw * 8,
                            ((size_t)g->E.w + LANES + 2 * RAW0) * 4, eh * hw * 4, hw * 4};
    void **slots[] = {(void **)&s->bits, (void **)&s->sb, (void **)&s->g[0], (void **)&s->g[1],
                      (void **)&s->run[0], (void **)&s->run[1], (void **)&s->near[0], (void **)&s->near[1],
                      (void **)&s->near[2], (void **)&s->near[3], (void **)&s->need,
                      (void **)&s->raw, (void **)&s->hs, (void **)&s->col};
    size_t at = 0;
    for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) {
        if (base) *slots[k] = base + at;
        at += align16(sizes[k]);
    }
    s->nw = (int)nw;
    s->gw = gw;
    return at;
}

bool tt__terrain_reserve(tt__terrains *ts, const tt__terrain *T, int x0, int y0, int x1, int y1)
{
    regions_t g;
    scratch_t s;
    regions(T, x0, y0, x1, y1, &g);
    const size_t n = layout(&g, NULL, &s);
    if (ts->scr.cap >= n) return true;
    void *p = realloc(ts->scr.buf, n);
    if (!p) return false;
    ts->scr.buf = p;
    ts->scr.cap = n;
    return true;
}

/* 64 pixels of row y from pixel x on (x may be −1); outside the mask empty. */
static inline uint64_t word_at(const tt_mask *m, int y, int x)
{
    if (y < 0 || y >= m->h) return 0;
    const uint64_t *row = tt__mask_row(m, y);
    const int q = (x + 64) / 64 - 1;
    const unsigned r = (unsigned)(x + 64) & 63u;
    const uint64_t lo = q >= 0 && q < m->stride ? row[q] : 0;
    if (!r) return lo;
    const uint64_t hi = q + 1 >= 0 && q + 1 < m->stride ? row[q + 1] : 0;
    return (lo >> r) | (hi << (64 - r));
}

/* Byte k of the result: 0xFF where bit k of b is set. */
static inline uint64_t spread(unsigned b)
{
    uint64_t x = b;
    x = (x | x << 28) & 0x0000000F0000000Full;
    x = (x | x << 14) & 0x0003000300030003ull;
    x = (x | x << 7) & 0x0101010101010101ull;
    return x * 0xFF;
}

static void read_bits(const tt_mask *m, const region *R, const scratch_t *s, const uint64_t *spread8)
{
    const unsigned tail = (unsigned)R->w & 63u;
    for (int y = 0; y < R->h; y++) {
        uint64_t *row = s->bits + (size_t)y * (size_t)s->nw;
        uint8_t *sb = s->sb + (size_t)y * 64 * (size_t)s->nw;
        for (int j = 0; j < s->nw; j++) {
            row[j] = word_at(m, R->y0 + y, R->x0 + 64 * j);
            if (tail && j == s->nw - 1) row[j] &= ((uint64_t)1 << tail) - 1;
            for (int q = 0; q < 8; q++) memcpy(sb + 64 * j + 8 * q, &spread8[(row[j] >> (8 * q)) & 0xFFu], 8);
        }
    }
}

/* Bit k of the result: byte k of x is below n (bytes below 128, n ≤ 128). */
static inline unsigned below(uint64_t x, unsigned n)
{
    const uint64_t t = ((x + 0x0101010101010101ull * (128 - n)) >> 7) & 0x0101010101010101ull; /* 1: ≥ n */
    return (unsigned)(((t ^ 0x0101010101010101ull) * 0x0102040810204080ull) >> 56);
}

typedef int8_t i8x16 __attribute__((vector_size(16)));

static inline i8x16 load16(const uint8_t *p)
{
    i8x16 v;
    memcpy(&v, p, sizeof v);
    return v;
}

/* One row of a sweep: the runs (distance down the column to the nearest
 * pixel of each state) one row further, onto R's row ly; into E's row ey
 * too (up: the smaller of the two), unless ey < 0. */
static void sweep_row(const scratch_t *s, int ly, int B, int ey, bool up)
{
    const uint8_t *own = s->sb + (size_t)ly * 64 * (size_t)s->nw;
    const i8x16 far = (i8x16){0} + (int8_t)(B + 1), one = (i8x16){0} + 1;
    uint8_t *run0 = s->run[0], *run1 = s->run[1];
    uint8_t *g0 = ey >= 0 ? s->g[0] + (size_t)ey * s->gw + PAD : NULL, *g1 = g0 ? s->g[1] + (size_t)ey * s->gw + PAD : NULL;
    for (int k = 0; k < 4 * s->nw; k++) {
        const i8x16 solid = load16(own + 16 * k);
        /* a pixel of the state is 0 away, the others one more than the row before, at most far */
        i8x16 r0 = load16(run0 + 16 * k) + one, r1 = load16(run1 + 16 * k) + one;
        r0 = (r0 + (i8x16)(r0 > far)) & solid;
        r1 = (r1 + (i8x16)(r1 > far)) & ~solid;
        memcpy(run0 + 16 * k, &r0, 16);
        memcpy(run1 + 16 * k, &r1, 16);
        if (!g0) continue;
        if (up) {
            const i8x16 o0 = load16(g0 + 16 * k), o1 = load16(g1 + 16 * k);
            const i8x16 l0 = (i8x16)(r0 < o0), l1 = (i8x16)(r1 < o1);
            r0 = (r0 & l0) | (o0 & ~l0);
            r1 = (r1 & l1) | (o1 & ~l1);
        }
        memcpy(g0 + 16 * k, &r0, 16);
        memcpy(g1 + 16 * k, &r1, 16);
    }
}

/* g for E's rows: down the columns, then up (a pixel's nearest of a state
 * in its column is the nearer of the one above and the one below). Rows
 * beyond R are none (R holds every row within B of E, or the ring). */
static void columns(const regions_t *rg, int B, const scratch_t *s)
{
    const region *R = &rg->R, *E = &rg->E;
    for (int e = 0; e < E->h; e++) /* beyond R's columns: empty, no solid within B */
        for (int st = 0; st < 2; st++) {
            uint8_t *g = s->g[st] + (size_t)e * s->gw;
            memset(g, st ? B + 1 : 0, PAD);
            memset(g + s->gw - PAD, st ? B + 1 : 0, PAD);
        }
    for (int up = 0; up < 2; up++) {
        memset(s->run[0], B + 1, 64 * (size_t)s->nw);
        memset(s->run[1], B + 1, 64 * (size_t)s->nw);
        for (int k = 0; k < R->h; k++) {
            const int ly = up ? R->h - 1 - k : k, ey = R->y0 + ly - E->y0;
            if (up && ey < 0) break;
            sweep_row(s, ly, B, ey < E->h ? ey : -1, up);
        }
    }
}

/* near[st] for E's row ey: pixels with one of state st within B rows (its
 * g), grown sideways by at least B pixels (more only costs a search). */
static const uint64_t *near_row(const scratch_t *s, int ey, int st, int B)
{
    const int nw = s->nw;
    const uint8_t *g = s->g[st] + (size_t)ey * s->gw + PAD;
    uint64_t *a = s->near[2 * st], *t = s->near[2 * st + 1];
    for (int j = 0; j < nw; j++) {
        uint64_t w = 0;
#if defined(__SSE2__)
        const __m128i far = _mm_set1_epi8((char)(B + 1));
        for (int q = 0; q < 4; q++) {
            const __m128i x = _mm_loadu_si128((const __m128i *)(const void *)(g + 64 * j + 16 * q));
            w |= (uint64_t)(unsigned)_mm_movemask_epi8(_mm_cmplt_epi8(x, far)) << (16 * q);
        }
#else
        for (int q = 0; q < 8; q++) {
            uint64_t x;
            memcpy(&x, g + 64 * j + 8 * q, 8);
            w |= (uint64_t)below(x, (unsigned)B + 1) << (8 * q);
        }
#endif
        a[j] = w;
    }
    for (int r = 0; r < B; r = 2 * r + 1) {
        const unsigned k = (unsigned)r + 1;
        for (int j = 0; j < nw; j++) {
            uint64_t x = a[j] | (a[j] << k) | (a[j] >> k);
            if (j > 0) x |= a[j - 1] >> (64 - k);
            if (j + 1 < nw) x |= a[j + 1] << (64 - k);
            t[j] = x;
        }
        uint64_t *swap = a;
        a = t;
        t = swap;
    }
    return a;
}

/* LANES bits of words w from bit i on. */
static inline unsigned lanes_at(const uint64_t *w, int nw, int i)
{
    const int j = i >> 6;
    const unsigned r = (unsigned)i & 63u;
    uint64_t x = w[j] >> r;
    if (r > 64 - LANES && j + 1 < nw) x |= w[j + 1] << (64 - r);
    return (unsigned)x & ((1u << LANES) - 1);
}

typedef int32_t i32v __attribute__((vector_size(16)));
typedef float f32v __attribute__((vector_size(16)));

/* The squared distances of LANES pixels (those set in on; the others 0) to
 * the nearest pixel of one state, g being each column's (the pixels' own
 * at g[0]): along the row, dx growing until no lane can do better (at most
 * 33² + 32², within an int16). Exact integers: the SSE2 code (every x86-64
 * has it) and the portable one give the same. */
#if defined(__SSE2__)
static void search(const uint8_t *g, unsigned on, int B, int16_t out[LANES])
{
    const __m128i z = _mm_setzero_si128();
    const __m128i m = _mm_set_epi64x((long long)spread(on >> 8), (long long)spread(on & 0xFFu));
    const __m128i a = _mm_and_si128(_mm_loadu_si128((const __m128i *)(const void *)g), m);
    const __m128i alo = _mm_unpacklo_epi8(a, z), ahi = _mm_unpackhi_epi8(a, z);
    __m128i lo = _mm_mullo_epi16(alo, alo), hi = _mm_mullo_epi16(ahi, ahi);
    for (int dx = 1; dx <= B; dx++) {
        const __m128i d2 = _mm_set1_epi16((short)(dx * dx));
        if (!_mm_movemask_epi8(_mm_or_si128(_mm_cmpgt_epi16(lo, d2), _mm_cmpgt_epi16(hi, d2)))) break;
        const __m128i n = _mm_min_epu8(_mm_loadu_si128((const __m128i *)(const void *)(g - dx)),
                                       _mm_loadu_si128((const __m128i *)(const void *)(g + dx)));
        const __m128i nlo = _mm_unpacklo_epi8(n, z), nhi = _mm_unpackhi_epi8(n, z);
        lo = _mm_min_epi16(lo, _mm_add_epi16(d2, _mm_mullo_epi16(nlo, nlo)));
        hi = _mm_min_epi16(hi, _mm_add_epi16(d2, _mm_mullo_epi16(nhi, nhi)));
    }
    _mm_storeu_si128((__m128i *)(void *)out, lo);
    _mm_storeu_si128((__m128i *)(void *)(out + 8), hi);
}
#else
static void search(const uint8_t *g, unsigned on, int B, int16_t out[LANES])
{
    int best[LANES], most = 0;
    for (int k = 0; k < LANES; k++) {
        best[k] = (on >> k) & 1u ? g[k] * g[k] : 0;
        most = best[k] > most ? best[k] : most;
    }
    for (int dx = 1; dx <= B && dx * dx < most; dx++) {
        most = 0;
        for (int k = 0; k < LANES; k++) {
            const int n = g[k - dx] < g[k + dx] ? g[k - dx] : g[k + dx], c = dx * dx + n * n;
            best[k] = c < best[k] ? c : best[k];
            most = best[k] > most ? best[k] : most;
        }
    }
    for (int k = 0; k < LANES; k++) out[k] = (int16_t)best[k];
}
#endif

/* The raw distances of E's row y, in 1/2^QBITS pixel. */
static void raw_row(const tt__terrains *ts, const regions_t *rg, int y, int B, const scratch_t *s)
{
    const region *R = &rg->R, *E = &rg->E;
    const int ly = y - R->y0, ey = y - E->y0, nw = s->nw;
    const uint64_t *ne = near_row(s, ey, 0, B), *ns = near_row(s, ey, 1, B);
    const uint64_t *row = s->bits + (size_t)ly * (size_t)nw;
    for (int j = 0; j < nw; j++) s->need[j] = (row[j] & ne[j]) | (~row[j] & ns[j]);
    const uint8_t *ge = s->g[0] + (size_t)ey * s->gw + PAD, *gs = s->g[1] + (size_t)ey * s->gw + PAD;
    const int32_t far = B << QBITS;
    for (int x = 0; x < E->w; x += LANES) {
        const int i = E->x0 + x - R->x0;
        const unsigned solid = lanes_at(row, nw, i), need = lanes_at(s->need, nw, i);
        int32_t *out = s->raw + RAW0 + x;
        if (!need) {
            for (int k = 0; k < LANES; k++) out[k] = (solid >> k) & 1u ? -far : far;
            continue;
        }
        /* solid pixels look for the nearest empty one, empty pixels for a solid one */
        int16_t be[LANES] = {0}, bs[LANES] = {0};
        if (need & solid) search(ge + i, need & solid, B, be);
        if (need & ~solid) search(gs + i, need & ~solid, B, bs);
        for (int k = 0; k < LANES; k++) {
            const int32_t r = (need >> k) & 1u ? ts->scr.lut[be[k] + bs[k]] : far;
            out[k] = (solid >> k) & 1u ? -r : r;
        }
    }
}

/* Sums across of one raw row (E's) over W's columns; at the terrain's
 * border the edge pixel stands for those beyond. */
static void across(const regions_t *rg, int32_t *raw, int32_t *out)
{
    const region *E = &rg->E, *W = &rg->W;
    for (int k = 0; k < RAW0; k++) {
        raw[k] = raw[RAW0];
        raw[RAW0 + E->w + k] = raw[RAW0 + E->w - 1];
    }
    const int32_t *in = raw + RAW0 + (W->x0 - E->x0); /* W's first pixel */
    int32_t sum = 0;
    for (int k = -BLUR; k <= BLUR; k++) sum += in[k];
    for (int x = 0; x < W->w; x++) {
        out[x] = sum;
        sum += in[x + BLUR + 1] - in[x - BLUR];
    }
    for (int x = W->w; x < hs_width(W); x++) out[x] = 0; /* whole vectors are summed down */
}

/* Sums down the columns of the sums across, into T's band over W. */
static void down(tt__terrain *T, const regions_t *rg, const scratch_t *s)
{
    const region *E = &rg->E, *W = &rg->W;
    const int ey1 = E->y0 + E->h - 1, ww = hs_width(W), n4 = W->w / 4;
    const f32v scale = (f32v){0} + (float)(1.0 / ((double)TAPS * TAPS * (1 << QBITS)));
#define HS(y) (s->hs + (size_t)(clampi((y), E->y0, ey1) - E->y0) * (size_t)ww)
    i32v *col = (i32v *)(void *)s->col;
    memset(col, 0, (size_t)ww * sizeof *s->col);
    for (int k = -BLUR; k <= BLUR; k++) {
        const i32v *h = (const i32v *)(const void *)HS(W->y0 + k);
        for (int x = 0; x < ww / 4; x++) col[x] += h[x];
    }
    for (int y = W->y0; y < W->y0 + W->h; y++) {
        float *out = T->sdf + (size_t)y * (size_t)T->m->w + W->x0;
        const i32v *add = (const i32v *)(const void *)HS(y + BLUR + 1), *sub = (const i32v *)(const void *)HS(y - BLUR);
        for (int x = 0; x < n4; x++) {
            const f32v f = __builtin_convertvector(col[x], f32v) * scale;
            memcpy(out + 4 * x, &f, sizeof f);
        }
        for (int x = 4 * n4; x < W->w; x++) out[x] = (float)s->col[x] * scale[0];
        for (int x = 0; x < ww / 4; x++) col[x] += add[x] - sub[x];
    }
#undef HS
}

/* The raw distance of a squared distance n (in pixels²), in 1/2^QBITS pixel. */
static void make_lut(tt__terrains *ts, int B)
{
    if (ts->scr.lut_band == B) return;
    for (int n = 0; n < (int)(sizeof ts->scr.lut / sizeof *ts->scr.lut); n++) {
        const double d = sqrt((double)n) - 0.5;
        ts->scr.lut[n] = d >= B ? B << QBITS : (int32_t)floor(d * (1 << QBITS) + 0.5);
    }
    ts->scr.lut_band = B;
    for (unsigned b = 0; b < 256; b++) ts->scr.spread8[b] = spread(b);
}

bool tt__terrain_update(tt__terrains *ts, tt__terrain *T, int x0, int y0, int x1, int y1)
{
    regions_t g;
    scratch_t s;
    const int B = T->def.band;
    regions(T, x0, y0, x1, y1, &g);
    if (!tt__terrain_reserve(ts, T, x0, y0, x1, y1)) return false;
    layout(&g, ts->scr.buf, &s);
    make_lut(ts, B);
    read_bits(T->m, &g.R, &s, ts->scr.spread8);
    columns(&g, B, &s);
    for (int y = g.E.y0; y < g.E.y0 + g.E.h; y++) {
        raw_row(ts, &g, y, B, &s);
        across(&g, s.raw, s.hs + (size_t)(y - g.E.y0) * (size_t)hs_width(&g.W));
    }
    down(T, &g, &s);
    tt__terrain_tiles_update(T, g.W.x0, g.W.y0, g.W.x0 + g.W.w - 1, g.W.y0 + g.W.h - 1);
    return true;
}
