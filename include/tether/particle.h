/* tether — particles: create, read, move, push. */
#ifndef TETHER_PARTICLE_H
#define TETHER_PARTICLE_H

#include "world.h"

#ifdef __cplusplus
extern "C" {
#endif

/// How a particle is made. Start from tt_particle_def_default().
typedef struct tt_particle_def {
    tt_vec2 position;  ///< m; default (0, 0)
    tt_vec2 velocity;  ///< m/s; default (0, 0)
    double mass;       ///< kg, > 0; default 1
    double radius;     ///< m, ≥ 0 (0 = a point); default 0 — used by collisions and drawing
    bool pinned;       ///< infinite mass: never moved by forces, impulses or constraints; default false
    uint16_t category; ///< collision layer bits this particle is on; default 0x0001
    uint16_t mask;     ///< layers it collides with; default 0xFFFF
    uint64_t user;     ///< your data (an entity id, an index); default 0
} tt_particle_def;

/// What a teleport does to velocity.
typedef enum tt_move_mode {
    TT_MOVE_KEEP_VELOCITY = 0, ///< velocity is kept (Verlet: x_old moves with x)
    TT_MOVE_RESET_VELOCITY     ///< velocity becomes 0
} tt_move_mode;

/// The defaults documented on each tt_particle_def field.
TT_API tt_particle_def tt_particle_def_default(void);
/// Adds a particle; the null handle on bad input or when full (tt_last_error says why).
TT_API tt_particle tt_particle_create(tt_world *w, const tt_particle_def *def);
/// Removes a particle and every spring attached to it. Its handle goes stale.
TT_API tt_result tt_particle_destroy(tt_world *w, tt_particle p);
/// True if p names a live particle of w.
TT_API bool tt_particle_is_valid(const tt_world *w, tt_particle p);

TT_API tt_result tt_particle_get_position(const tt_world *w, tt_particle p, tt_vec2 *out);
/// Kinematic move (teleport): no force, no collision sweep; see tt_move_mode.
TT_API tt_result tt_particle_set_position(tt_world *w, tt_particle p, tt_vec2 pos, tt_move_mode mode);
/// Velocity, m/s. Verlet reports the backward difference (x − x_old)/dt.
TT_API tt_result tt_particle_get_velocity(const tt_world *w, tt_particle p, tt_vec2 *out);
/// Sets velocity exactly (pinned particles: TT_ESTATE, they never move).
TT_API tt_result tt_particle_set_velocity(tt_world *w, tt_particle p, tt_vec2 v);
/// Angle, rad in [−π, π], counter-clockwise, of a world made with tt_world_def.spin (else TT_ESTATE).
TT_API tt_result tt_particle_get_angle(const tt_world *w, tt_particle p, double *out);
/// Angular velocity, rad/s, counter-clockwise (tt_world_def.spin; else TT_ESTATE).
TT_API tt_result tt_particle_get_spin(const tt_world *w, tt_particle p, double *out);
/// Sets the angular velocity, rad/s, |spin| ≤ TT_MAX_VALUE (tt_world_def.spin; else TT_ESTATE). A pinned
/// particle and a point (radius 0) do not turn: TT_ESTATE (pinning, or a radius set to 0, stops a spin).
TT_API tt_result tt_particle_set_spin(tt_world *w, tt_particle p, double spin);
TT_API tt_result tt_particle_get_mass(const tt_world *w, tt_particle p, double *out);
/// kg, > 0. The mass is kept while pinned and comes back on unpin.
TT_API tt_result tt_particle_set_mass(tt_world *w, tt_particle p, double mass);
TT_API tt_result tt_particle_get_pinned(const tt_world *w, tt_particle p, bool *out);
/// Whether the particle sleeps (world sleeping on, its island at rest). Any
/// call that changes it wakes its island.
TT_API tt_result tt_particle_get_asleep(const tt_world *w, tt_particle p, bool *out);
/// Pinning stops the particle where it is (velocity 0).
TT_API tt_result tt_particle_set_pinned(tt_world *w, tt_particle p, bool pinned);
TT_API tt_result tt_particle_get_radius(const tt_world *w, tt_particle p, double *out);
TT_API tt_result tt_particle_set_radius(tt_world *w, tt_particle p, double radius); ///< m, ≥ 0
TT_API tt_result tt_particle_get_filter(const tt_world *w, tt_particle p, uint16_t *category, uint16_t *mask);
TT_API tt_result tt_particle_set_filter(tt_world *w, tt_particle p, uint16_t category, uint16_t mask);
TT_API tt_result tt_particle_get_user(const tt_world *w, tt_particle p, uint64_t *out);
TT_API tt_result tt_particle_set_user(tt_world *w, tt_particle p, uint64_t user);

/// Adds a force (N) for the next step only; forces add up and are cleared after it.
TT_API tt_result tt_particle_apply_force(tt_world *w, tt_particle p, tt_vec2 f);
/// Instant velocity change Δv = impulse / mass (N·s). Pinned: no effect.
TT_API tt_result tt_particle_apply_impulse(tt_world *w, tt_particle p, tt_vec2 impulse);

/// Live particles in the world.
TT_API uint32_t tt_world_particle_count(const tt_world *w);
/// Bulk: writes up to `cap` live handles in slot order into out (may be NULL
/// to count); returns the number of live particles.
TT_API uint32_t tt_world_list_particles(const tt_world *w, tt_particle *out, uint32_t cap);
/// Bulk: positions of up to `cap` live particles in slot order (the order of
/// tt_world_list_particles) into xy as x0, y0, x1, y1, …; returns how many.
TT_API uint32_t tt_world_read_positions(const tt_world *w, double *xy, uint32_t cap);
/// Bulk, as tt_world_read_positions: where each particle was as the last step
/// began, kept while tt_world_set_interpolation is on (the current position
/// when it is off, and for a particle made or moved by the script since).
/// Drawn at previous + alpha·(current − previous), with a clock's alpha
/// (tt_clock_alpha), motion is smooth between fixed steps.
TT_API uint32_t tt_world_read_previous_positions(const tt_world *w, double *xy, uint32_t cap);
/// The same for one particle.
TT_API tt_result tt_particle_get_previous_position(const tt_world *w, tt_particle p, tt_vec2 *out);
/// Bulk: positions of n given particles into xy (2n doubles). Stops at the first stale handle.
TT_API tt_result tt_particles_get_positions(const tt_world *w, const tt_particle *ids, uint32_t n, double *xy);
/// Bulk kinematic move of n given particles (2n finite doubles). Validates everything before changing anything.
TT_API tt_result tt_particles_set_positions(tt_world *w, const tt_particle *ids, uint32_t n, const double *xy, tt_move_mode mode);

#ifdef __cplusplus
}
#endif

#endif
