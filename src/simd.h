/* tether — what the SIMD sweeps share (constraints.c, contact_batch.c):
 * the runtime choice of vector width, and "rows": a packed copy of x, y and
 * inverse mass, one 32-byte row (x, y, w, w) per particle, so a particle is
 * one vector load and one store. Kernels that give bit-identical results to
 * their scalar loops do the scalar arithmetic lane by lane (no FMA: the
 * build has -ffp-contract=off and these targets enable none). */
#ifndef TT_SIMD_H
#define TT_SIMD_H

#include <stdbool.h>
#include <stdint.h>

/* Which sweep runs: AUTO picks the widest the processor has; the others
 * force one (tests compare them bit for bit). */
typedef enum tt__simd_mode { TT__SIMD_AUTO, TT__SIMD_SCALAR, TT__SIMD_AVX2, TT__SIMD_AVX512 } tt__simd_mode;

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(TT_NO_SIMD)
#define TT_SIMD_X86 1
#include <immintrin.h>
#define TT_AVX2 __attribute__((target("avx2")))
#define TT_AVX512 __attribute__((target("avx2,avx512f,avx512vl")))
#define TT_INLINE static inline __attribute__((always_inline))
#endif

/* The mode m runs as on this processor and build: TT__SIMD_SCALAR when it has none. */
uint8_t tt__simd_kind(uint8_t m);

/* Room for rows of particles [0, np), 32-byte aligned; *pk, *cap updated. */
bool tt__rows_reserve(double **pk, uint32_t *cap, uint32_t np);
/* x, y, inverse mass of particles [0, np) into rows, and x, y back. */
void tt__rows_pack(double *pk, const double *px, const double *py, const double *im, uint32_t np);
void tt__rows_unpack(const double *pk, double *px, double *py, uint32_t np);

#endif
