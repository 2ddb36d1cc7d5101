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

/// Generational handles: index of a slot + the slot's generation when the
/// object was made. A removed object's handle stays stale forever (the
/// generation moved on; a slot whose generation would wrap is retired).
/// The generation's high byte is a tag of the world (worlds take tags 1…255
/// in turn), so a handle used on another world is refused as stale unless the
/// two worlds share a tag. The all-zero handle is null.
typedef struct tt_particle {
    uint32_t index;
    uint32_t gen;
} tt_particle;

/// A force-based spring between two particles (see tether/spring.h).
typedef struct tt_spring {
    uint32_t index;
    uint32_t gen;
} tt_spring;

/// Handles as one 64-bit integer (gen in the high half): what Lua sees.
static inline uint64_t tt_particle_to_u64(tt_particle p) { return ((uint64_t)p.gen << 32) | p.index; }
static inline tt_particle tt_particle_from_u64(uint64_t u) { tt_particle p; p.index = (uint32_t)u; p.gen = (uint32_t)(u >> 32); return p; }
static inline uint64_t tt_spring_to_u64(tt_spring s) { return ((uint64_t)s.gen << 32) | s.index; }
static inline tt_spring tt_spring_from_u64(uint64_t u) { tt_spring s; s.index = (uint32_t)u; s.gen = (uint32_t)(u >> 32); return s; }

/// Time integrators. Chosen per world and switchable between steps; a
/// switch keeps each particle's position and velocity.
typedef enum tt_integrator {
    TT_EULER = 0,         ///< explicit Euler: x += v·dt with the old v; order 1, gains energy
    TT_SYMPLECTIC_EULER,  ///< semi-implicit Euler: v += a·dt, then x += v·dt; order 1, bounded energy
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
