/* tether — what the SIMD sweeps share (distance_sweep.c, contact_batch.c):
 * the runtime choice of vector width, and "rows": a packed copy of x, y and
 * inverse mass, one 32-byte row (x, y, w, w) per particle, so a particle is
 * one vector load and one store (the solver's layout for the sweeps,
 * solver.c); or "xy rows", (x, y) alone in 16 bytes, for the contacts'
 * velocity pass after the sweeps.
 * Kernels that give bit-identical results to their scalar loops do the
 * scalar arithmetic lane by lane (no FMA: the build has -ffp-contract=off
 * and these targets enable none). */
#ifndef TT_SIMD_H
#define TT_SIMD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Which sweep runs: AUTO picks the widest the processor has; the others
 * force one (tests compare them bit for bit). */
typedef enum tt__simd_mode { TT__SIMD_AUTO, TT__SIMD_SCALAR, TT__SIMD_AVX2, TT__SIMD_AVX512 } tt__simd_mode;

#define TT_INLINE static inline __attribute__((always_inline))

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(TT_NO_SIMD)
#define TT_SIMD_X86 1
#include <immintrin.h>
#define TT_AVX2 __attribute__((target("avx2")))
#define TT_AVX512 __attribute__((target("avx2,avx512f,avx512vl")))

/* Rows at offsets r0, r1 (4·slot) into p = (x, y) of both and w = (w, w) of both. */
TT_AVX2 TT_INLINE void tt__rows_load2(const double *pk, size_t r0, size_t r1, __m256d *p, __m256d *w)
{
    const __m256d a = _mm256_load_pd(pk + r0), b = _mm256_load_pd(pk + r1);
    *p = _mm256_permute2f128_pd(a, b, 0x20);
    *w = _mm256_permute2f128_pd(a, b, 0x31);
}

/* The (x, y) pairs at offsets r0, r1 of rows (4·slot) or xy rows (2·slot)
 * into (x0, y0, x1, y1): the second half goes in with a load-and-insert,
 * no lane-crossing shuffle. */
TT_AVX2 TT_INLINE __m256d tt__rows_loadxy2(const double *pk, size_t r0, size_t r1)
{
    return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_load_pd(pk + r0)), _mm_load_pd(pk + r1), 1);
}

/* (x0, y0, x1, y1) back at offsets r0, r1 (a row's w stays): stores the
 * size of the loads, so the next load of either is served from its store. */
TT_AVX2 TT_INLINE void tt__rows_store2(double *pk, size_t r0, size_t r1, __m256d v)
{
    _mm_store_pd(pk + r0, _mm256_castpd256_pd128(v));
    _mm_store_pd(pk + r1, _mm256_extractf128_pd(v, 1));
}

/* The same on xy rows by particle: i0, i1 at offsets 2·i0, 2·i1. */
TT_AVX2 TT_INLINE __m256d tt__xy_load2(const double *xy, size_t i0, size_t i1) { return tt__rows_loadxy2(xy, 2 * i0, 2 * i1); }
TT_AVX2 TT_INLINE void tt__xy_store2(double *xy, size_t i0, size_t i1, __m256d v) { tt__rows_store2(xy, 2 * i0, 2 * i1, v); }
#endif

/* The mode m runs as on this processor and build: TT__SIMD_SCALAR when it has none. */
uint8_t tt__simd_kind(uint8_t m);

/* Room for rows of particles [0, np), 32-byte aligned; *pk, *cap updated. */
bool tt__rows_reserve(double **pk, uint32_t *cap, uint32_t np);
/* x, y, inverse mass of particles [0, np) into rows, and x, y back. */
void tt__rows_pack(double *pk, const double *px, const double *py, const double *im, uint32_t np);
void tt__rows_unpack(const double *pk, double *px, double *py, uint32_t np);

/* Room for xy rows [0, np), 16-byte aligned; a, b of [0, np) into them and back. */
bool tt__xy_reserve(double **xy, uint32_t *cap, uint32_t np);
void tt__xy_pack(double *xy, const double *a, const double *b, uint32_t np);
void tt__xy_unpack(const double *xy, double *a, double *b, uint32_t np);

#endif
