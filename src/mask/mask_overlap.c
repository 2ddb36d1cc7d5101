/* tether — overlap of mask B placed at (dx, dy) on mask A: whether (and
 * where first), how many pixels, which pixels, and the push-out normal.
 *
 * Each row of A meets B's row as whole 64-bit words: B's two words that
 * straddle A's word are shifted together (tt__mask_bword), so a 1024-pixel
 * row is 16 word operations whatever the offset. The word loops are built
 * twice, for processors with AVX2 and POPCNT and for any other (chosen on
 * first use by what the processor reports); both give the same integers. */
#include "mask_internal.h"

#include <math.h>
#include <string.h>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(TT_NO_SIMD)
#define TT__MASK_X86 1
/* gcc -O2 vectorizes only loops it need not peel; these need a scalar tail.
 * (target_clones("arch=haswell") is no use: its resolver asks whether the
 * processor IS a Haswell, so every later one got the slow clone.) */
#define TT__MASK_FAST __attribute__((target("avx2,popcnt,bmi2"), optimize("vect-cost-model=dynamic")))
#endif

static int floor_div64(int v)
{
    return v >= 0 ? v / 64 : -((-v + 63) / 64);
}

bool tt__mask_shift_of(tt__mask_shift *s, const tt_mask *a, const tt_mask *b, int dx, int dy)
{
    if (dx >= a->w || dy >= a->h || dx + b->w <= 0 || dy + b->h <= 0) return false;
    s->q = floor_div64(dx);
    s->r = (unsigned)(dx - 64 * s->q);
    s->k0 = s->q > 0 ? s->q : 0;
    s->k1 = floor_div64(dx + b->w - 1);
    if (s->k1 > a->stride - 1) s->k1 = a->stride - 1;
    s->ki0 = s->q + (s->r ? 1 : 0);
    s->ki1 = s->q + b->stride - 1;
    if (s->ki0 < s->k0) s->ki0 = s->k0;
    if (s->ki1 > s->k1) s->ki1 = s->k1;
    s->dy = dy;
    s->y0 = dy > 0 ? dy : 0;
    s->y1 = dy + b->h < a->h ? dy + b->h : a->h;
    return true;
}

enum { OP_ANY, OP_COUNT, OP_AND };

/* One row: A's words k0…k1 against B's row placed by s. OP_ANY returns the
 * OR of the ANDed words, OP_COUNT their pixel count, OP_AND stores them in
 * out (A's frame) and returns their OR. Inlined into each caller with op
 * constant, so each gets its own loop. */
static inline __attribute__((always_inline)) uint64_t row_op(int op, const uint64_t *restrict a,
                                                             const uint64_t *restrict b, uint64_t *restrict out,
                                                             int sb, const tt__mask_shift *s)
{
    uint64_t acc = 0;
    const int q = s->q;
    const unsigned r = s->r, l = 64 - r;
    for (int k = s->k0; k <= s->k1; k++) { /* the edge words before the interior */
        if (k == s->ki0 && s->ki0 <= s->ki1) break;
        uint64_t v = a[k] & tt__mask_bword(b, sb, s, k);
        if (op == OP_COUNT) acc += (uint64_t)__builtin_popcountll(v); else acc |= v;
        if (op == OP_AND) out[k] = v;
    }
    if (s->ki0 <= s->ki1) {
        const uint64_t *bj = b - q; /* bj[k] = B's word k − q */
        if (r == 0) {
            for (int k = s->ki0; k <= s->ki1; k++) {
                uint64_t v = a[k] & bj[k];
                if (op == OP_COUNT) acc += (uint64_t)__builtin_popcountll(v); else acc |= v;
                if (op == OP_AND) out[k] = v;
            }
        } else {
            for (int k = s->ki0; k <= s->ki1; k++) {
                uint64_t v = a[k] & ((bj[k - 1] >> l) | (bj[k] << r));
                if (op == OP_COUNT) acc += (uint64_t)__builtin_popcountll(v); else acc |= v;
                if (op == OP_AND) out[k] = v;
            }
        }
        for (int k = s->ki1 + 1; k <= s->k1; k++) { /* the edge word after it */
            uint64_t v = a[k] & tt__mask_bword(b, sb, s, k);
            if (op == OP_COUNT) acc += (uint64_t)__builtin_popcountll(v); else acc |= v;
            if (op == OP_AND) out[k] = v;
        }
    }
    return acc;
}

#ifdef TT__MASK_X86
#include <immintrin.h>

/* Pixel counts of each 64-bit lane (Mula's nibble table: AVX2 has no popcount). */
TT__MASK_FAST static inline __attribute__((always_inline)) __m256i popcount4(__m256i v)
{
    const __m256i lut = _mm256_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4, 0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3,
                                         2, 3, 3, 4);
    const __m256i nib = _mm256_set1_epi8(0x0f);
    __m256i lo = _mm256_shuffle_epi8(lut, _mm256_and_si256(v, nib));
    __m256i hi = _mm256_shuffle_epi8(lut, _mm256_and_si256(_mm256_srli_epi16(v, 4), nib));
    return _mm256_sad_epu8(_mm256_add_epi8(lo, hi), _mm256_setzero_si256());
}

/* row_op with the interior four words at a time. */
TT__MASK_FAST static inline __attribute__((always_inline)) uint64_t row_op_avx2(int op, const uint64_t *restrict a,
                                                                               const uint64_t *restrict b,
                                                                               uint64_t *restrict out, int sb,
                                                                               const tt__mask_shift *s)
{
    if (s->ki0 > s->ki1 || s->ki1 - s->ki0 < 3) return row_op(op, a, b, out, sb, s);
    uint64_t acc = 0;
    const unsigned r = s->r;
    const uint64_t *bj = b - s->q;
    for (int k = s->k0; k < s->ki0; k++) { /* the edge word before the interior */
        uint64_t v = a[k] & tt__mask_bword(b, sb, s, k);
        if (op == OP_COUNT) acc += (uint64_t)__builtin_popcountll(v); else acc |= v;
        if (op == OP_AND) out[k] = v;
    }
    const __m128i cr = _mm_cvtsi32_si128((int)r), cl = _mm_cvtsi32_si128((int)(64 - r));
    __m256i vacc = _mm256_setzero_si256();
    int k = s->ki0;
    for (; k + 3 <= s->ki1; k += 4) {
        __m256i hi = _mm256_loadu_si256((const __m256i *)(bj + k)), bw = hi;
        if (r) bw = _mm256_or_si256(_mm256_srl_epi64(_mm256_loadu_si256((const __m256i *)(bj + k - 1)), cl),
                                    _mm256_sll_epi64(hi, cr));
        __m256i v = _mm256_and_si256(_mm256_loadu_si256((const __m256i *)(a + k)), bw);
        if (op == OP_COUNT) vacc = _mm256_add_epi64(vacc, popcount4(v));
        else vacc = _mm256_or_si256(vacc, v);
        if (op == OP_AND) _mm256_storeu_si256((__m256i *)(out + k), v);
    }
    uint64_t lanes[4];
    _mm256_storeu_si256((__m256i *)lanes, vacc);
    acc = op == OP_COUNT ? acc + lanes[0] + lanes[1] + lanes[2] + lanes[3] : acc | lanes[0] | lanes[1] | lanes[2] | lanes[3];
    for (; k <= s->k1; k++) { /* the interior's last words and the edge word after it */
        uint64_t v = a[k] & (k <= s->ki1 ? (r ? (bj[k - 1] >> (64 - r)) | (bj[k] << r) : bj[k]) : tt__mask_bword(b, sb, s, k));
        if (op == OP_COUNT) acc += (uint64_t)__builtin_popcountll(v); else acc |= v;
        if (op == OP_AND) out[k] = v;
    }
    return acc;
}
#endif

/* Masks at most 64 pixels wide, the usual sprite: one word per row each, so
 * B's row lands on A's one word as B's word shifted (dx in −63…63 here). */
static inline uint64_t narrow_word(uint64_t b, int dx)
{
    return dx >= 0 ? b << dx : b >> -dx;
}

/* With dx = 0 and rows of the same width, the rows B covers are one run of
 * words in each mask: one "row" of them all, with none of the per-row
 * set-up that dominates narrow masks. Fills f for it. */
static inline bool contiguous(const tt_mask *a, const tt_mask *b, const tt__mask_shift *s, tt__mask_shift *f)
{
    if (s->q != 0 || s->r != 0 || a->stride != b->stride) return false;
    *f = *s;
    f->k0 = f->ki0 = 0;
    f->k1 = f->ki1 = (s->y1 - s->y0) * a->stride - 1;
    return true;
}

/* Rows of at most four words, the same width in both masks, B shifted by
 * less than a word (q = 0 or −1): the covered rows again as one run, each
 * word taking its neighbour's bits except across a row's edge (the masks
 * m0, m1 drop those), so narrow masks pay no per-row set-up. op as row_op. */
static inline __attribute__((always_inline)) uint64_t stream_op(int op, const uint64_t *restrict a,
                                                                const uint64_t *restrict b, uint64_t *restrict out,
                                                                int n, int S, const tt__mask_shift *s)
{
    const unsigned r = s->r, l = 64 - r;
    uint64_t acc = 0;
    for (int i = 0, k = 0; i < n; i++) {
        uint64_t v;
        if (s->q == 0) { /* B's words k − 1 and k; none before the row's first */
            uint64_t prev = k ? b[i - 1] : 0;
            v = a[i] & ((b[i] << r) | (prev >> l));
        } else { /* B's words k and k + 1; none after the row's last */
            uint64_t next = k + 1 < S ? b[i + 1] : 0;
            v = a[i] & ((b[i] >> l) | (next << r));
        }
        if (op == OP_COUNT) acc += (uint64_t)__builtin_popcountll(v); else acc |= v;
        if (op == OP_AND) out[i] = v;
        k = k + 1 == S ? 0 : k + 1;
    }
    return acc;
}

static inline bool streamable(const tt_mask *a, const tt_mask *b, const tt__mask_shift *s)
{
    return a->stride == b->stride && a->stride <= 4 && s->r != 0 && (s->q == 0 || s->q == -1);
}

/* The three whole-overlap loops, built once per target by KERNELS(suffix, attributes). */
#define KERNELS(sfx, ATTR, ROW)                                                                                      \
    ATTR static int first_row_##sfx(const tt_mask *a, const tt_mask *b, const tt__mask_shift *s)                \
    {                                                                                                            \
        for (int y = s->y0; y < s->y1; y++)                                                                      \
            if (ROW(OP_ANY, tt__mask_row(a, y), tt__mask_row(b, y - s->dy), NULL, b->stride, s)) return y;  \
        return -1;                                                                                               \
    }                                                                                                            \
    ATTR static int64_t count_all_##sfx(const tt_mask *a, const tt_mask *b, const tt__mask_shift *s)            \
    {                                                                                                            \
        uint64_t n = 0;                                                                                          \
        if (a->stride == 1 && b->stride == 1) { /* narrow masks: see narrow_word */                             \
            int dx = s->q * 64 + (int)s->r;                                                                      \
            for (int y = s->y0; y < s->y1; y++)                                                                  \
                n += (uint64_t)__builtin_popcountll(a->bits[y] & narrow_word(b->bits[y - s->dy], dx));          \
            return (int64_t)n;                                                                                   \
        }                                                                                                        \
        tt__mask_shift f;                                                                                        \
        if (contiguous(a, b, s, &f))                                                                             \
            return (int64_t)ROW(OP_COUNT, tt__mask_row(a, s->y0), tt__mask_row(b, s->y0 - s->dy), NULL, f.k1 + 1, &f); \
        if (streamable(a, b, s))                                                                                 \
            return (int64_t)stream_op(OP_COUNT, tt__mask_row(a, s->y0), tt__mask_row(b, s->y0 - s->dy), NULL,   \
                                      (s->y1 - s->y0) * a->stride, a->stride, s);                                \
        for (int y = s->y0; y < s->y1; y++)                                                                      \
            n += ROW(OP_COUNT, tt__mask_row(a, y), tt__mask_row(b, y - s->dy), NULL, b->stride, s);         \
        return (int64_t)n;                                                                                       \
    }                                                                                                            \
    ATTR static void and_all_##sfx(const tt_mask *a, const tt_mask *b, const tt__mask_shift *s, tt_mask *out)   \
    {                                                                                                            \
        tt__mask_shift f;                                                                                        \
        if (contiguous(a, b, s, &f)) {                                                                           \
            ROW(OP_AND, tt__mask_row(a, s->y0), tt__mask_row(b, s->y0 - s->dy), tt__mask_row(out, s->y0), f.k1 + 1, &f); \
            return;                                                                                              \
        }                                                                                                        \
        if (streamable(a, b, s)) {                                                                               \
            stream_op(OP_AND, tt__mask_row(a, s->y0), tt__mask_row(b, s->y0 - s->dy), tt__mask_row(out, s->y0),  \
                      (s->y1 - s->y0) * a->stride, a->stride, s);                                                \
            return;                                                                                              \
        }                                                                                                        \
        for (int y = s->y0; y < s->y1; y++)                                                                      \
            ROW(OP_AND, tt__mask_row(a, y), tt__mask_row(b, y - s->dy), tt__mask_row(out, y), b->stride, s);    \
    }

KERNELS(any, , row_op)
#ifdef TT__MASK_X86
KERNELS(fast, TT__MASK_FAST, row_op_avx2)
#endif

/* Whether the fast loops run here: asked once (the answer never changes). */
static bool fast(void)
{
#ifdef TT__MASK_X86
    static int known = -1;
    if (known < 0) known = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt") && __builtin_cpu_supports("bmi2");
    return known;
#else
    return false;
#endif
}

#ifdef TT__MASK_X86
#define PICK(fn) (fast() ? fn##_fast : fn##_any)
#else
#define PICK(fn) fn##_any
#endif

static bool narrow(const tt_mask *a, const tt_mask *b)
{
    return a->stride == 1 && b->stride == 1;
}

static int first_row(const tt_mask *a, const tt_mask *b, const tt__mask_shift *s)
{
    if (narrow(a, b)) {
        int dx = s->q * 64 + (int)s->r;
        for (int y = s->y0; y < s->y1; y++)
            if (a->bits[y] & narrow_word(b->bits[y - s->dy], dx)) return y;
        return -1;
    }
    return PICK(first_row)(a, b, s);
}

static int64_t count_all(const tt_mask *a, const tt_mask *b, const tt__mask_shift *s)
{
    return PICK(count_all)(a, b, s);
}

static void and_all(const tt_mask *a, const tt_mask *b, const tt__mask_shift *s, tt_mask *out) { PICK(and_all)(a, b, s, out); }

static tt_result check_pair(const char *fn, const tt_mask *a, const tt_mask *b, int dx, int dy)
{
    if (!a || !b) return tt__mask_fail(TT_EINVAL, "%s: mask %s is NULL", fn, a ? "b" : "a");
    return tt__mask_check_offset(fn, dx, dy);
}

bool tt_mask_overlap(const tt_mask *a, const tt_mask *b, int dx, int dy, int *x, int *y)
{
    tt__mask_shift s;
    if (check_pair("tt_mask_overlap", a, b, dx, dy) != TT_OK) return false;
    if (!tt__mask_shift_of(&s, a, b, dx, dy)) return false;
    int row = first_row(a, b, &s);
    if (row < 0) return false;
    if (x || y) {
        const uint64_t *ar = tt__mask_row(a, row), *br = tt__mask_row(b, row - dy);
        for (int k = s.k0; k <= s.k1; k++) {
            uint64_t v = ar[k] & tt__mask_bword(br, b->stride, &s, k);
            if (!v) continue;
            if (x) *x = k * 64 + __builtin_ctzll(v);
            if (y) *y = row;
            break;
        }
    }
    return true;
}

int64_t tt_mask_overlap_area(const tt_mask *a, const tt_mask *b, int dx, int dy)
{
    tt__mask_shift s;
    if (check_pair("tt_mask_overlap_area", a, b, dx, dy) != TT_OK) return -1;
    return tt__mask_shift_of(&s, a, b, dx, dy) ? count_all(a, b, &s) : 0;
}

/* Writes every word of out (A's size): zero where B does not reach. */
static void overlap_into(tt_mask *out, const tt_mask *a, const tt_mask *b, int dx, int dy)
{
    tt__mask_shift s;
    size_t row = (size_t)a->stride * sizeof(uint64_t);
    if (!tt__mask_shift_of(&s, a, b, dx, dy)) {
        memset(out->bits, 0, (size_t)a->h * row);
        return;
    }
    memset(out->bits, 0, (size_t)s.y0 * row);
    memset(tt__mask_row(out, s.y1), 0, (size_t)(a->h - s.y1) * row);
    for (int y = s.y0; y < s.y1; y++) {
        uint64_t *o = tt__mask_row(out, y);
        for (int k = 0; k < s.k0; k++) o[k] = 0;
        for (int k = s.k1 + 1; k < a->stride; k++) o[k] = 0;
    }
    and_all(a, b, &s, out);
}

tt_mask *tt_mask_overlap_mask(const tt_mask *a, const tt_mask *b, int dx, int dy)
{
    if (check_pair("tt_mask_overlap_mask", a, b, dx, dy) != TT_OK) return NULL;
    /* every word written once, not cleared first and then written */
    tt_mask *out = tt__mask_alloc_raw("tt_mask_overlap_mask", a->w, a->h);
    if (out) overlap_into(out, a, b, dx, dy);
    return out;
}

tt_result tt_mask_overlap_mask_into(tt_mask *out, const tt_mask *a, const tt_mask *b, int dx, int dy)
{
    const char *fn = "tt_mask_overlap_mask_into";
    tt_result r = check_pair(fn, a, b, dx, dy);
    if (r != TT_OK) return r;
    if (!out) return tt__mask_fail(TT_EINVAL, "%s: out is NULL", fn);
    if (out == a || out == b) return tt__mask_fail(TT_EINVAL, "%s: out is one of the masks", fn);
    if (out->w != a->w || out->h != a->h)
        return tt__mask_fail(TT_EINVAL, "%s: out is %d x %d, a is %d x %d", fn, out->w, out->h, a->w, a->h);
    overlap_into(out, a, b, dx, dy);
    return TT_OK;
}

/* Area at an offset that may step one past the documented limit. */
static int64_t area_at(const tt_mask *a, const tt_mask *b, int64_t dx, int64_t dy)
{
    tt__mask_shift s;
    if (dx > TT_MASK_MAX_OFFSET || dx < -TT_MASK_MAX_OFFSET || dy > TT_MASK_MAX_OFFSET || dy < -TT_MASK_MAX_OFFSET)
        return 0; /* that far out nothing overlaps */
    return tt__mask_shift_of(&s, a, b, (int)dx, (int)dy) ? count_all(a, b, &s) : 0;
}

tt_result tt_mask_overlap_normal(const tt_mask *a, const tt_mask *b, int dx, int dy, tt_vec2 *out)
{
    tt_result r = check_pair("tt_mask_overlap_normal", a, b, dx, dy);
    if (r != TT_OK) return r;
    if (!out) return tt__mask_fail(TT_EINVAL, "tt_mask_overlap_normal: out is NULL");
    *out = (tt_vec2){ 0, 0 };
    if (area_at(a, b, dx, dy) == 0) return TT_OK;
    /* moving B towards +x adds overlap where A lies to B's right: push it the other way */
    double gx = (double)(area_at(a, b, (int64_t)dx + 1, dy) - area_at(a, b, (int64_t)dx - 1, dy));
    double gy = (double)(area_at(a, b, dx, (int64_t)dy + 1) - area_at(a, b, dx, (int64_t)dy - 1));
    double len = sqrt(gx * gx + gy * gy);
    if (len > 0) *out = (tt_vec2){ -gx / len, -gy / len };
    return TT_OK;
}
