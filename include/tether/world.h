/* tether — the world: owner of all simulation state, and its step. */
#ifndef TETHER_WORLD_H
#define TETHER_WORLD_H

#include "base.h"

#ifdef __cplusplus
extern "C" {
#endif

/// The world. Owns every particle, spring and (later) constraint and shape.
/// All simulation state lives inside it: two worlds never share anything.
typedef struct tt_world tt_world;

/// Order of the relaxation sweeps over position constraints and contacts.
typedef enum tt_solver_order {
    TT_GAUSS_SEIDEL = 0, ///< in place, one constraint after another: converges in fewer iterations
    TT_JACOBI            ///< every correction from the same positions, averaged per particle, then applied
} tt_solver_order;

/// How a world is made. Start from tt_world_def_default() and change fields.
typedef struct tt_world_def {
    tt_vec2 gravity;          ///< acceleration, m/s²; default (0, −9.81)
    tt_integrator integrator; ///< default TT_VERLET
    double damping;           ///< velocity damping, 1/s: v *= 1 − damping·dt each step; default 0; ≥ 0
    tt_vec2 wind;             ///< uniform force on every particle, N; default (0, 0)
    double dt_hint;           ///< the step you expect to use, s; default 1/60. Verlet turns a velocity set
                              ///< before the first step into x_old with it (any later dt is still exact)
    uint32_t capacity;        ///< particles to reserve up front; default 0 (grows on demand)
    uint32_t max_particles;   ///< hard limit on live + removed-slot particles, ≤ 2^24 (the handle budget); default 2^24 = 16 777 216
    uint32_t substeps;        ///< each step runs this many substeps of dt/substeps; default 1; 1…1000
    double max_travel;        ///< 0 (default): every step runs `substeps`. Else a step runs more substeps, up to
                              ///< max_substeps, where a particle would move more than max_travel times its radius
                              ///< in one relative to what it can meet (other particles, pinned or sleeping ones,
                              ///< shapes and terrain within reach; its speed as the step begins, plus gravity's over the step): a scene pays
                              ///< for substeps only while something is fast (a pour landing, a shot). Only where
                              ///< contacts can be found (particle contacts, a shape, a terrain). 0…TT_MAX_VALUE
    uint32_t max_substeps;    ///< the most substeps max_travel may ask for; default 8; 1…1000 (0: 8; below `substeps`: `substeps`)
    uint32_t iterations;      ///< most relaxation sweeps per substep; default 10; 1…10 000
    double tolerance;         ///< sweeps stop once the largest constraint error is ≤ this, m; default 1e-6; ≥ 0
    tt_solver_order order;    ///< default TT_GAUSS_SEIDEL
    bool sleep;               ///< particles at rest fall asleep by islands and cost nothing until woken; default true
    double sleep_speed;       ///< a particle rests while its position, smoothed over 1/15 s, stays within sleep_speed·sleep_time of where it was, or leaves it slower than this, m/s; default 0.01; 0…TT_MAX_VALUE
    double sleep_time;        ///< an island sleeps once all of it rested this long, s; default 1; 0…TT_MAX_VALUE
    double fixed_point;       ///< 0 (default): positions are plain doubles. Else the quantum q, m, a power of two 2^-k
                              ///< (k = 1…60; TT_FIXED_POINT_QUANTUM = 2^-32 is a good choice): every position is kept
                              ///< a multiple of q within |x| ≤ 2^51·q (2^19 m = 524 288 m for 2^-32), so position
                              ///< Verlet runs backwards bit for bit (tt_world_reverse). Positions given are rounded
                              ///< to the nearest multiple; one outside the range is refused. Needs TT_VERLET.
    bool spin;                ///< particles turn: each is a solid disc (I = m·r²/2) with an angle and an angular
                              ///< velocity, and contact friction acts at the contact point, shared between its
                              ///< translation and its spin (README "Particles that turn"); default false
} tt_world_def;

/// The fixed-point quantum to use when in doubt: 2^-32 m (0.23 nm), range ±2^19 m.
#define TT_FIXED_POINT_QUANTUM (1.0 / 4294967296.0)

/// Pipeline stages timed by the world (milliseconds of the last step).
/// A stage the world does not use is skipped outright and reads 0.
typedef enum tt_stage {
    TT_STAGE_FORCES = 0, ///< user forces, wind, springs → accelerations
    TT_STAGE_INTEGRATE,  ///< the integrator's update of positions/velocities
    TT_STAGE_COLLIDE,    ///< detection: broadphase + narrowphase
    TT_STAGE_SOLVE,      ///< relaxation sweeps over constraints and contacts, and the velocity pass
    TT_STAGE_EVENTS,     ///< gathering contact and break events for the script
    TT_STAGE_COUNT
} tt_stage;

/// Counters of the last step, read with tt_world_get_stats.
typedef struct tt_stats {
    uint64_t steps;                      ///< steps taken since creation
    double time;                         ///< simulated time, s (sum of dt)
    uint32_t particles;                  ///< live particles
    uint32_t springs;                    ///< live springs
    double step_ms;                      ///< wall time of the last step, ms
    double stage_ms[TT_STAGE_COUNT];     ///< wall time per stage of the last step, ms
    uint32_t force_evaluations;          ///< force evaluations in the last step (1 Euler…4 RK4; 0 when nothing but gravity)
    uint32_t diverged;                   ///< particles stopped in the last step because |x| or |v| passed TT_DIVERGED
    uint32_t iterations;                 ///< relaxation sweeps run in the last step (all substeps)
    uint32_t substeps;                   ///< substeps the last step ran (more than the setting where max_travel asked); 0 before the first
    double max_error;                    ///< largest constraint/contact error left after the last sweep, m (0 if none)
    uint32_t sleeping;                   ///< particles asleep now (0 while sleeping is off)
} tt_stats;

/// Mechanical energy of the world now, J. Computed on request (O(n)), so a
/// world that never asks never pays. Pinned particles count no energy.
typedef struct tt_energy {
    double kinetic;   ///< Σ ½ m |v|², and Σ ¼ m r² ω² where particles turn (tt_world_def.spin)
    double gravity;   ///< Σ −m g·x (zero at the origin)
    double spring;    ///< Σ ½ k (|xa − xb| − rest)²
    double constraint;///< Σ ½ C²/α over compliant (XPBD) constraints: what they store as springs of stiffness 1/α
    double attractor; ///< Σ −m·strength/√(r² + softening²) over point attractors (tt_world_set_attractor)
    double total;     ///< the sum of the five
} tt_energy;

/// Memory held by a world, bytes.
typedef struct tt_memory {
    size_t total;             ///< everything the world allocated
    size_t particles;         ///< particle arrays at their current capacity
    uint32_t capacity;        ///< particle slots allocated
    double bytes_per_particle;///< particle arrays / capacity (core arrays plus any optional ones in use)
} tt_memory;

/// The defaults documented on each tt_world_def field.
TT_API tt_world_def tt_world_def_default(void);
/// Makes a world; NULL on bad input or no memory (tt_last_error(NULL) says why).
TT_API tt_world *tt_world_create(const tt_world_def *def);
/// Frees a world and everything in it. NULL is allowed.
TT_API void tt_world_destroy(tt_world *w);

/// Advances the world by dt seconds (0 < dt ≤ 10, finite). Per substep, in order:
/// forces → integrate → detect (collisions) → relax (constraints and contacts,
/// up to `iterations` sweeps) → velocity pass → events. Stages a world does not use are skipped.
/// Forces applied with tt_particle_apply_force are used for this step, then cleared.
/// Memory: everything the step needs that follows from the world's counts
/// (particles, links, shapes) is allocated before it changes anything, and
/// a world at steady state allocates nothing per step. Running out of
/// memory fails the step with TT_ENOMEM and the world exactly as it was
/// before it (its hash, and every step after): before the step, or inside
/// it when more contacts than ever before need more room (tt_last_error
/// says which and for what). The same step may then be tried again. A world
/// whose contacts may need more room inside a step (particle pairs with some
/// radius above 0, events, bullets, terrain, more than one shape, or a chain
/// of more than one segment) keeps, for this, room for a copy of what a step changes
/// (42 bytes a particle; positions and velocities, 32 of them, are copied as
/// each step begins, flags and inverse masses only by a step that wakes a
/// sleeper or starts a set velocity). Other worlds with collisions need no
/// copy: a lone shape has room for a contact per particle instead
/// (72 bytes a particle, written only where contacts occur).
TT_API tt_result tt_world_step(tt_world *w, double dt);

TT_API tt_result tt_world_set_gravity(tt_world *w, tt_vec2 g);      ///< m/s², finite
TT_API tt_vec2 tt_world_get_gravity(const tt_world *w);
TT_API tt_result tt_world_set_wind(tt_world *w, tt_vec2 f);         ///< N per particle, finite
TT_API tt_vec2 tt_world_get_wind(const tt_world *w);
TT_API tt_result tt_world_set_damping(tt_world *w, double damping); ///< 1/s, finite, ≥ 0
TT_API double tt_world_get_damping(const tt_world *w);
/// Switches integrator between steps; every particle keeps its velocity.
/// TT_ESTATE in a fixed_point world (it keeps TT_VERLET).
TT_API tt_result tt_world_set_integrator(tt_world *w, tt_integrator i);
TT_API tt_integrator tt_world_get_integrator(const tt_world *w);
/// The fixed-point quantum of the world (tt_world_def.fixed_point), m; 0 when positions are plain doubles.
/// It is set when the world is made and kept for life (a snapshot carries it).
TT_API double tt_world_get_fixed_point(const tt_world *w);

/// Substeps per step (1…1000): at equal cost, more substeps beat more iterations.
TT_API tt_result tt_world_set_substeps(tt_world *w, uint32_t substeps);
TT_API uint32_t tt_world_get_substeps(const tt_world *w);
/// Substeps by speed (tt_world_def.max_travel): max_travel in radii per substep
/// (finite, ≥ 0; 0 switches it off), max_substeps 1…1000. It acts only where
/// contacts can be found (particle contacts, a shape, a terrain).
TT_API tt_result tt_world_set_travel(tt_world *w, double max_travel, uint32_t max_substeps);
/// max_travel (0: off); max_substeps (may be NULL) gets the cap.
TT_API double tt_world_get_travel(const tt_world *w, uint32_t *max_substeps);
/// Most relaxation sweeps per substep (1…10 000).
TT_API tt_result tt_world_set_iterations(tt_world *w, uint32_t iterations);
TT_API uint32_t tt_world_get_iterations(const tt_world *w);
/// Sweeps stop early once the largest error is ≤ tolerance (m, finite, ≥ 0).
TT_API tt_result tt_world_set_tolerance(tt_world *w, double tolerance);
TT_API double tt_world_get_tolerance(const tt_world *w);
TT_API tt_result tt_world_set_solver_order(tt_world *w, tt_solver_order order);
TT_API tt_solver_order tt_world_get_solver_order(const tt_world *w);
/// Sleeping on or off, with its thresholds (speed m/s, time s; both finite,
/// ≥ 0; ignored when off). Turning it off wakes every sleeper.
TT_API tt_result tt_world_set_sleep(tt_world *w, bool on, double speed, double time);
/// Whether sleeping is on; speed and time (may be NULL) get its thresholds.
TT_API bool tt_world_get_sleep(const tt_world *w, double *speed, double *time);

/// Point attractors a world holds (slots 0 … TT_MAX_ATTRACTORS − 1).
#define TT_MAX_ATTRACTORS 8
/// A point attractor (a planet, a magnet): every movable particle at distance
/// r from `center` accelerates towards it by strength·r/(r² + softening²)^(3/2)
/// m/s², whatever its mass (a negative strength repels). Softening keeps the
/// pull finite near the centre (Plummer softening; 0: the exact 1/r² law,
/// with no pull at the centre itself). Potential per kg: −strength/√(r² + softening²).
typedef struct tt_attractor {
    tt_vec2 center;   ///< m, finite
    double strength;  ///< G·M, m³/s², |strength| ≤ TT_MAX_VALUE; 0 switches the slot off
    double softening; ///< m, finite, ≥ 0
} tt_attractor;
/// Sets slot `slot` (0 … TT_MAX_ATTRACTORS − 1); strength 0 clears it. The
/// pull is a force like any other: every integrator sees it at its own stages.
TT_API tt_result tt_world_set_attractor(tt_world *w, uint32_t slot, tt_attractor a);
/// The attractor in `slot` (strength 0 when unused).
TT_API tt_result tt_world_get_attractor(const tt_world *w, uint32_t slot, tt_attractor *out);

/// Radial explosion: every movable particle within `radius` of `center` gets
/// an impulse of `impulse`·(1 − d/radius) N·s pointing away from the centre.
/// A particle exactly at the centre is left alone (no direction).
TT_API tt_result tt_world_explode(tt_world *w, tt_vec2 center, double radius, double impulse);

/// Keeps (on) or drops (off) where every particle was as each step begins,
/// for drawing between steps (tt_world_read_previous_positions): 16 bytes
/// per particle and one copy of the positions per step while on; default
/// off. Any integrator (Verlet's previous position is not that one: it spans
/// a substep and contacts rewrite it). Not simulation state: neither saved
/// nor hashed, and a restore keeps it on, from the restored positions.
TT_API tt_result tt_world_set_interpolation(tt_world *w, bool on);
/// Whether the world keeps the previous positions (tt_world_set_interpolation).
TT_API bool tt_world_get_interpolation(const tt_world *w);

/// Stats of the last step (see tt_stats).
TT_API tt_result tt_world_get_stats(const tt_world *w, tt_stats *out);
/// Energy now (see tt_energy).
TT_API tt_result tt_world_get_energy(const tt_world *w, tt_energy *out);
/// Memory now (see tt_memory).
TT_API tt_result tt_world_get_memory(const tt_world *w, tt_memory *out);
/// 64-bit hash of the world's state: of the stream tt_world_save writes
/// (its body), with the world tag left out, so two worlds built alike hash
/// alike. Equal hashes ⇔ same state, for determinism checks.
TT_API uint64_t tt_world_hash(const tt_world *w);

/// Snapshots: the whole state of a world (settings, counters, particles,
/// springs, constraints and their moving targets, composites, shapes,
/// collision settings, contact records of the last step and events, handle
/// pools with their free lists and generations) as a versioned byte stream
/// with a checksum, in this machine's byte order. Per-step scratch (grids,
/// batches, caches) is not in it and is rebuilt. Writes the stream into
/// buf[0..cap) and its size into *size (may be NULL); with cap too small
/// (buf NULL and cap 0 to ask) it sets *size, returns TT_ENOMEM and leaves
/// buf[0..cap) partly written, never past cap. One pass, no allocation.
TT_API tt_result tt_world_save(const tt_world *w, void *buf, size_t cap, size_t *size);
/// Makes w bit-exactly the saved world, in place (w keeps its address):
/// stepping both gives the same states. The world then has the saved
/// world's tag, so handles saved with the game stay valid. A truncated,
/// corrupted, foreign or other-version stream is refused (TT_EINVAL,
/// tt_last_error says why) and w is left unchanged: the stream is read and
/// checked whole into new memory before anything of w changes.
TT_API tt_result tt_world_restore(tt_world *w, const void *data, size_t size);
/// A new world from a stream (a saved game); NULL when refused
/// (tt_last_error(NULL) says why). It takes the saved world's tag: handles
/// saved with the game work in it, and if the saving world still lives,
/// each accepts the other's handles.
TT_API tt_world *tt_world_load(const void *data, size_t size);
/// Snapshot files: the stream behind a file header (a signature, the file
/// format version, the engine version that wrote it, the length) and a
/// checksum of both. Written to path.tmp, then renamed over path, so a
/// failed save leaves the old file whole. TT_EINVAL when the path cannot be
/// written (tt_last_error says why).
TT_API tt_result tt_world_save_file(const tt_world *w, const char *path);
/// Makes w the world saved in the file, as tt_world_restore. A file that
/// cannot be read, is not a tether file, of another format version,
/// truncated, padded or corrupted is refused (TT_EINVAL, tt_last_error
/// names the file and says why) and w is left unchanged.
TT_API tt_result tt_world_restore_file(tt_world *w, const char *path);
/// A new world from a file, as tt_world_load; NULL when refused
/// (tt_last_error(NULL) says why).
TT_API tt_world *tt_world_load_file(const char *path);

/// Time reversal: swaps every particle's position and previous position,
/// so that the next steps (of the same dt) run the motion backwards: N steps,
/// reverse, N steps comes back to the start (to rounding: see the README).
/// Only for position Verlet with forces alone (gravity, wind, undamped
/// springs, applied forces); TT_ESTATE naming what prevents it otherwise
/// (another integrator, damping, constraints, collisions, spring damping, a
/// velocity set since the last step), the world unchanged. In a world with
/// fixed_point positions (tt_world_def) the round trip is exact, bit for bit,
/// as long as dt stays the same.
TT_API tt_result tt_world_reverse(tt_world *w);

/// The last error raised by a call on this world, or by tt_world_create when
/// w is NULL (per thread). "" when none.
TT_API const char *tt_last_error(const tt_world *w);

#ifdef __cplusplus
}
#endif

#endif
