/* tether — the SIMD sweeps' shared parts: width dispatch and particle rows. */
#include "simd.h"

#include <stdlib.h>

uint8_t tt__simd_kind(uint8_t m)
{
#ifdef TT_SIMD_X86
    const bool avx2 = __builtin_cpu_supports("avx2"), avx512 = avx2 && __builtin_cpu_supports("avx512vl");
    switch (m) {
    case TT__SIMD_AUTO: return avx512 ? TT__SIMD_AVX512 : avx2 ? TT__SIMD_AVX2 : TT__SIMD_SCALAR;
    case TT__SIMD_AVX2: return avx2 ? TT__SIMD_AVX2 : TT__SIMD_SCALAR;
    case TT__SIMD_AVX512: return avx512 ? TT__SIMD_AVX512 : TT__SIMD_SCALAR;
    default: return TT__SIMD_SCALAR;
    }
#else
    (void)m;
    return TT__SIMD_SCALAR;
#endif
}

static bool reserve(double **pk, uint32_t *cap, uint32_t np, size_t width)
{
    if (np <= *cap) return true;
    double *p = aligned_alloc(32, (size_t)np * width * sizeof(double)); /* the contents are made by the sweeps */
    if (!p) return false;
    free(*pk);
    *pk = p;
    *cap = np;
    return true;
}

bool tt__rows_reserve(double **pk, uint32_t *cap, uint32_t np) { return reserve(pk, cap, np, 4); }
bool tt__xy_reserve(double **xy, uint32_t *cap, uint32_t np) { return reserve(xy, cap, np + (np & 1), 2); }

/* The vector parts below copy whole groups of four and return where they
 * stopped; the public functions finish (or, without vectors, do) the rest
 * one particle at a time. Rows are only made where a vector sweep runs, so
 * AVX2 is there. */
#ifdef TT_SIMD_X86
TT_AVX2 static uint32_t pack_avx2(double *pk, const double *px, const double *py, const double *im, uint32_t np)
{
    uint32_t i = 0;
    for (; i + 4 <= np; i += 4) {
        const __m256d x = _mm256_loadu_pd(px + i), y = _mm256_loadu_pd(py + i), m = _mm256_loadu_pd(im + i);
        const __m256d t0 = _mm256_unpacklo_pd(x, y), t1 = _mm256_unpackhi_pd(x, y); /* x0 y0 x2 y2 | x1 y1 x3 y3 */
        const __m256d u0 = _mm256_unpacklo_pd(m, m), u1 = _mm256_unpackhi_pd(m, m); /* w0 w0 w2 w2 | w1 w1 w3 w3 */
        _mm256_store_pd(pk + 4 * (size_t)i, _mm256_permute2f128_pd(t0, u0, 0x20));
        _mm256_store_pd(pk + 4 * (size_t)i + 4, _mm256_permute2f128_pd(t1, u1, 0x20));
        _mm256_store_pd(pk + 4 * (size_t)i + 8, _mm256_permute2f128_pd(t0, u0, 0x31));
        _mm256_store_pd(pk + 4 * (size_t)i + 12, _mm256_permute2f128_pd(t1, u1, 0x31));
    }
    return i;
}

TT_AVX2 static uint32_t unpack_avx2(const double *pk, double *px, double *py, uint32_t np)
{
    uint32_t i = 0;
    for (; i + 4 <= np; i += 4) {
        const double *r = pk + 4 * (size_t)i;
        const __m256d t0 = _mm256_permute2f128_pd(_mm256_load_pd(r), _mm256_load_pd(r + 8), 0x20);      /* x0 y0 x2 y2 */
        const __m256d t1 = _mm256_permute2f128_pd(_mm256_load_pd(r + 4), _mm256_load_pd(r + 12), 0x20); /* x1 y1 x3 y3 */
        _mm256_storeu_pd(px + i, _mm256_unpacklo_pd(t0, t1));
        _mm256_storeu_pd(py + i, _mm256_unpackhi_pd(t0, t1));
    }
    return i;
}

TT_AVX2 static uint32_t xy_pack_avx2(double *xy, const double *a, const double *b, uint32_t np)
{
    uint32_t i = 0;
    for (; i + 4 <= np; i += 4) {
        const __m256d va = _mm256_loadu_pd(a + i), vb = _mm256_loadu_pd(b + i);
        const __m256d lo = _mm256_unpacklo_pd(va, vb), hi = _mm256_unpackhi_pd(va, vb); /* a0 b0 a2 b2 | a1 b1 a3 b3 */
        _mm256_store_pd(xy + 2 * (size_t)i, _mm256_permute2f128_pd(lo, hi, 0x20));
        _mm256_store_pd(xy + 2 * (size_t)i + 4, _mm256_permute2f128_pd(lo, hi, 0x31));
    }
    return i;
}

TT_AVX2 static uint32_t xy_unpack_avx2(const double *xy, double *a, double *b, uint32_t np)
{
    uint32_t i = 0;
    for (; i + 4 <= np; i += 4) {
        const __m256d r0 = _mm256_load_pd(xy + 2 * (size_t)i), r1 = _mm256_load_pd(xy + 2 * (size_t)i + 4);
        const __m256d lo = _mm256_permute2f128_pd(r0, r1, 0x20), hi = _mm256_permute2f128_pd(r0, r1, 0x31);
        _mm256_storeu_pd(a + i, _mm256_unpacklo_pd(lo, hi));
        _mm256_storeu_pd(b + i, _mm256_unpackhi_pd(lo, hi));
    }
    return i;
}
#endif

void tt__rows_pack(double *pk, const double *px, const double *py, const double *im, uint32_t np)
{
    uint32_t i = 0;
#ifdef TT_SIMD_X86
    i = pack_avx2(pk, px, py, im, np);
#endif
    for (; i < np; i++) {
        double *r = pk + 4 * (size_t)i;
        r[0] = px[i];
        r[1] = py[i];
        r[2] = r[3] = im[i];
    }
}

void tt__rows_unpack(const double *pk, double *px, double *py, uint32_t np)
{
    uint32_t i = 0;
#ifdef TT_SIMD_X86
    i = unpack_avx2(pk, px, py, np);
#endif
    for (; i < np; i++) {
        px[i] = pk[4 * (size_t)i];
        py[i] = pk[4 * (size_t)i + 1];
    }
}

void tt__xy_pack(double *xy, const double *a, const double *b, uint32_t np)
{
    uint32_t i = 0;
#ifdef TT_SIMD_X86
    i = xy_pack_avx2(xy, a, b, np);
#endif
    for (; i < np; i++) xy[2 * (size_t)i] = a[i], xy[2 * (size_t)i + 1] = b[i];
}

void tt__xy_unpack(const double *xy, double *a, double *b, uint32_t np)
{
    uint32_t i = 0;
#ifdef TT_SIMD_X86
    i = xy_unpack_avx2(xy, a, b, np);
#endif
    for (; i < np; i++) a[i] = xy[2 * (size_t)i], b[i] = xy[2 * (size_t)i + 1];
}
