/* tether — base types shared by every part of the public API. */
#ifndef TETHER_BASE_H
#define TETHER_BASE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define TT_VERSION_MAJOR 0
#define TT_VERSION_MINOR 1
#define TT_VERSION_PATCH 0
#define TT_VERSION_STRING "0.1.0"

#if defined(_WIN32)
#define TT_API __declspec(dllexport)
#elif defined(__GNUC__)
#define TT_API __attribute__((visibility("default")))
#else
#define TT_API
#endif

/// Documented limits, enforced at every public entry point.
#define TT_MAX_VALUE 1e12       ///< largest |coordinate|, |velocity|, |force|, |impulse|, stiffness, …
#define TT_MIN_MASS 1e-9        ///< smallest particle mass, kg
#define TT_MAX_MASS 1e9         ///< largest particle mass, kg
#define TT_MIN_DT 1e-9          ///< smallest step, s (below it 1/dt and velocities lose meaning)
#define TT_MAX_DT 10.0          ///< largest step, s
#define TT_MIN_COMPLIANCE 1e-12 ///< smallest non-zero compliance (stiffness TT_MAX_VALUE), m/N; 0 = rigid
#define TT_MAX_SUBSTEPS 1000    ///< most substeps per step
#define TT_MAX_ITERATIONS 10000 ///< most relaxation sweeps per substep
#define TT_DIVERGED 1e15        ///< a particle whose |x| or |v| passes this in a step (integrating, relaxing or
                                ///< colliding) is stopped where it was at the start of the substep (stats.diverged)

#ifdef __cplusplus
extern "C" {
#endif

/// Result of every call that can fail. TT_OK is 0; the world's last-error
/// string (tt_last_error) says what went wrong in words.
typedef enum tt_result {
    TT_OK = 0,
    TT_EINVAL,   ///< an argument is out of its documented range, NaN or Inf
    TT_ESTALE,   ///< a handle names a removed (or never created) object
    TT_ENOMEM,   ///< an allocation failed or a documented limit was reached
    TT_ESTATE    ///< the call is not valid in the world's current state
} tt_result;

/// A 2D vector. Units are the caller's; metres are recommended.
typedef struct tt_vec2 {
    double x, y;
} tt_vec2;

/// Handles. Every object is named by a generational handle: the index of its
/// slot and the slot's generation when the object was made. A removed
/// object's handle stays stale forever (the generation moves on; a slot
/// whose generation would wrap is retired, never reused). The all-zero
/// handle is null. All handle types live here, one struct each, so C code
/// cannot pass one kind where another is expected.
///
/// The generation field holds the world's tag above a reuse counter. Worlds
/// take tags 1…1023 in turn, so a handle of one world is refused by every
/// world created after it until 1022 more worlds have been created.
///
/// As one integer (tt_*_to_u64, what Lua sees and what a game may store or
/// key a table by) a handle carries its kind and stays below 2^53, so it is
/// exact as an IEEE double (LuaJIT, JSON):
///
///     bits 52…50  kind          (tt_kind: 1…6; 0 is never a handle)
///     bits 49…40  world tag     (TT_HANDLE_TAG_BITS)
///     bits 39…24  reuse counter (TT_HANDLE_GEN_BITS: a slot retires after
///                               65 535 removals)
///     bits 23…0   slot index    (TT_HANDLE_INDEX_BITS: at most 2^24 slots
///                               of each kind per world)
///
/// Decoding an integer of another kind (or no handle at all) gives the null
/// handle, which every call refuses as stale.
#define TT_HANDLE_INDEX_BITS 24
#define TT_HANDLE_GEN_BITS 16
#define TT_HANDLE_TAG_BITS 10
#define TT_HANDLE_KIND_BITS 3
#define TT_HANDLE_MAX_SLOTS (1u << TT_HANDLE_INDEX_BITS)

/// The kind of object a handle names.
typedef enum tt_kind {
    TT_KIND_NONE = 0,   ///< not a handle
    TT_KIND_PARTICLE,
    TT_KIND_SPRING,
    TT_KIND_CONSTRAINT,
    TT_KIND_SHAPE,
    TT_KIND_COMPOSITE,
    TT_KIND_TERRAIN      ///< a pixel-mask terrain (see tether/terrain.h)
} tt_kind;

/// A particle (see tether/particle.h).
typedef struct tt_particle {
    uint32_t index;
    uint32_t gen;
} tt_particle;

/// A force-based spring between two particles (see tether/spring.h).
typedef struct tt_spring {
    uint32_t index;
    uint32_t gen;
} tt_spring;

/// A position constraint (see tether/constraint.h).
typedef struct tt_constraint {
    uint32_t index;
    uint32_t gen;
} tt_constraint;

/// A static or kinematic collision shape (see tether/collide.h).
typedef struct tt_shape {
    uint32_t index;
    uint32_t gen;
} tt_shape;

/// A composite: a group of particles and constraints made as one (see
/// tether/composite.h).
typedef struct tt_composite {
    uint32_t index;
    uint32_t gen;
} tt_composite;

/// A carvable pixel-mask terrain (see tether/terrain.h).
typedef struct tt_terrain {
    uint32_t index;
    uint32_t gen;
} tt_terrain;

#define TT__HANDLE_KIND_SHIFT (TT_HANDLE_INDEX_BITS + TT_HANDLE_GEN_BITS + TT_HANDLE_TAG_BITS)

/// The kind of the handle written as u (TT_KIND_NONE if u is no handle).
static inline tt_kind tt_handle_kind(uint64_t u)
{
    uint64_t k = u >> TT__HANDLE_KIND_SHIFT; /* ≥ 8 from 2^53 up */
    return k >= TT_KIND_PARTICLE && k <= TT_KIND_TERRAIN ? (tt_kind)k : TT_KIND_NONE;
}

/* Packing runs once per handle in every bulk read, so it is kept to a few
 * branch-free instructions. A struct whose index or generation is past its
 * budget (it would spill into the next field and name another object), or
 * the null handle, packs to 0. */
static inline uint64_t tt__handle_pack(tt_kind k, uint32_t index, uint32_t gen)
{
    uint64_t u = ((uint64_t)k << TT__HANDLE_KIND_SHIFT) | ((uint64_t)gen << TT_HANDLE_INDEX_BITS) | index;
    uint32_t spill = (index >> TT_HANDLE_INDEX_BITS) | ((gen - 1u) >> (TT_HANDLE_GEN_BITS + TT_HANDLE_TAG_BITS));
    return spill == 0 ? u : 0;
}
/* Bits above the kind make u >> TT__HANDLE_KIND_SHIFT differ from k too. */
static inline void tt__handle_unpack(uint64_t u, tt_kind k, uint32_t *index, uint32_t *gen)
{
    bool ok = u >> TT__HANDLE_KIND_SHIFT == (uint64_t)k;
    *index = ok ? (uint32_t)(u & (TT_HANDLE_MAX_SLOTS - 1)) : 0;
    *gen = ok ? (uint32_t)(u >> TT_HANDLE_INDEX_BITS) & ((1u << (TT_HANDLE_GEN_BITS + TT_HANDLE_TAG_BITS)) - 1) : 0;
}

#define TT__HANDLE_U64(T, K)                                                                     \
    static inline uint64_t T##_to_u64(T h) { return tt__handle_pack(K, h.index, h.gen); }        \
    static inline T T##_from_u64(uint64_t u) { T h; tt__handle_unpack(u, K, &h.index, &h.gen); return h; }
/// Handles to and from one integer (0 for the null handle or a handle out of
/// the budget; from an integer of another kind, the null handle).
TT__HANDLE_U64(tt_particle, TT_KIND_PARTICLE)
TT__HANDLE_U64(tt_spring, TT_KIND_SPRING)
TT__HANDLE_U64(tt_constraint, TT_KIND_CONSTRAINT)
TT__HANDLE_U64(tt_shape, TT_KIND_SHAPE)
TT__HANDLE_U64(tt_composite, TT_KIND_COMPOSITE)
TT__HANDLE_U64(tt_terrain, TT_KIND_TERRAIN)
#undef TT__HANDLE_U64

/// Time integrators. Chosen per world and switchable between steps; a
/// switch keeps each particle's position and velocity.
typedef enum tt_integrator {
    TT_EULER = 0,         ///< explicit Euler: x += v·dt with the old v; order 1, gains energy
    TT_SYMPLECTIC_EULER,  ///< semi-implicit Euler: v += a·dt, then x += v·dt (after a change of dt, a·(dt + dt_prev)/2); order 1, bounded energy
    TT_LEAPFROG,          ///< velocity Verlet (kick-drift-kick), two force evaluations; order 2
    TT_VERLET,            ///< position Verlet, v implied by (x − x_old)/dt; order 2; the default
    TT_RK4,               ///< classic Runge-Kutta 4, four force evaluations; order 4 (force-only scenes)
    TT_INTEGRATOR_COUNT
} tt_integrator;

/// Name of an integrator ("euler", "symplectic_euler", "leapfrog", "verlet", "rk4").
TT_API const char *tt_integrator_name(tt_integrator i);
/// Parses a name as above into *out; TT_EINVAL if unknown.
TT_API tt_result tt_integrator_from_name(const char *name, tt_integrator *out);
/// A short English description of a result code.
TT_API const char *tt_result_string(tt_result r);
/// The library version string, e.g. "0.1.0".
TT_API const char *tt_version(void);

#ifdef __cplusplus
}
#endif

#endif
