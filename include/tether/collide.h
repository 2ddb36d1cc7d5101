/* tether — collisions: static and kinematic shapes, particle–particle and
 * particle–shape contacts (projection, bounce, friction), continuous
 * detection for bullets, queries and contact events.
 *
 * A world starts with collisions off and pays nothing for them. Creating a
 * shape switches on particle–shape contacts; tt_world_set_collision switches
 * on particle–particle contacts (settings.particles). Contacts are solved in
 * the same relaxation sweeps as constraints (see tt_world_def.iterations).
 *
 * Material rules (documented, like Box2D's): restitution of a contact is the
 * larger of the two; static and kinetic friction are the geometric means
 * sqrt(μa·μb). A contact bounces only when it approaches faster than the
 * restitution threshold (default 2·|g|·h, h the substep), so resting
 * contacts do not jitter. Friction is Coulomb: a contact whose tangential
 * speed is at most μs times its normal velocity change sticks (the slide of
 * that substep is undone); otherwise the tangential speed loses μk times it. */
#ifndef TETHER_COLLIDE_H
#define TETHER_COLLIDE_H

#include "particle.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Kinds of shape. Geometry is given in the shape's local frame and placed
/// by position + angle (world = position + R(angle)·local).
typedef enum tt_shape_type {
    TT_SHAPE_SEGMENT = 0, ///< segment a–b (two-sided)
    TT_SHAPE_CHAIN,       ///< polyline through points[0..count) (terrain); loop closes it
    TT_SHAPE_AABB,        ///< axis-aligned box from a (min corner) to b (max corner); angle must be 0
    TT_SHAPE_BOX,         ///< oriented box: centre 0, half_extents, turned by angle
    TT_SHAPE_CIRCLE,      ///< circle of radius around the local origin
    TT_SHAPE_CAPSULE,     ///< segment a–b with radius
    TT_SHAPE_POLYGON,     ///< convex polygon points[0..count), 3…TT_MAX_POLYGON_POINTS, either winding
    TT_SHAPE_TYPE_COUNT
} tt_shape_type;

#define TT_MAX_POLYGON_POINTS 64     ///< most vertices of a convex polygon
#define TT_MAX_CHAIN_POINTS 1000000  ///< most points of a chain
#define TT_MAX_SHAPES 1000000        ///< most live shapes per world

/// How a shape is made. Start from tt_shape_def_default().
typedef struct tt_shape_def {
    tt_shape_type type;      ///< default TT_SHAPE_SEGMENT
    tt_vec2 position;        ///< m, where the local origin goes; default (0, 0)
    double angle;            ///< rad, rotation of the local frame; default 0
    tt_vec2 a, b;            ///< m; segment/capsule ends, AABB min/max corners; default (0,0), (1,0)
    tt_vec2 half_extents;    ///< m, > 0, box half width/height; default (0.5, 0.5)
    double radius;           ///< m; circle (> 0) and capsule (≥ 0) radius; default 0.5
    const tt_vec2 *points;   ///< chain/polygon points (copied); default NULL
    uint32_t count;          ///< number of points; chain ≥ 2, polygon 3…64; default 0
    bool loop;               ///< chain: join the last point to the first; default false
    double restitution;      ///< bounce, 0…1; default 0
    double friction_static;  ///< μs ≥ 0; default 0.6
    double friction_kinetic; ///< μk ≥ 0; default 0.5
    uint16_t category;       ///< layer bits of the shape; default 0x0001
    uint16_t mask;           ///< layers it collides with; default 0xFFFF
    bool sensor;             ///< reports overlaps as events, never pushes; default false
    uint64_t user;           ///< your data; default 0
} tt_shape_def;

/// Broadphase used for particle–particle pairs.
typedef enum tt_broadphase {
    TT_BROADPHASE_GRID = 0, ///< uniform grid, counting sort, O(N) per substep (the default)
    TT_BROADPHASE_BRUTE     ///< every pair, O(N²): the reference, for tests and benchmarks
} tt_broadphase;

/// Which contact events a world gathers (bit set). Default 0: none, no cost.
enum {
    TT_EVENT_BEGIN = 1u << 0,   ///< a contact (or sensor overlap) started this step
    TT_EVENT_PERSIST = 1u << 1, ///< it existed last step and still does
    TT_EVENT_END = 1u << 2      ///< it existed last step and does not any more
};

/// World collision settings. Start from tt_collision_settings_default().
typedef struct tt_collision_settings {
    bool particles;                ///< particle–particle contacts; default true (once the settings are set)
    tt_broadphase broadphase;      ///< default TT_BROADPHASE_GRID
    double cell_size;              ///< grid cell, m, ≥ 0; default 0 = auto (largest diameter × 1.1); smaller values are raised to that
    double restitution;            ///< particles' default bounce, 0…1; default 0
    double friction_static;        ///< particles' default μs ≥ 0; default 0.6
    double friction_kinetic;       ///< particles' default μk ≥ 0; default 0.5
    double restitution_threshold;  ///< m/s, approach speed below which nothing bounces; default −1 = auto 2·|g|·h
    uint32_t events;               ///< TT_EVENT_* bits to gather; default 0
    double stacking;               ///< mass scaling by height for piles, 0…TT_MAX_VALUE: in a pair contact the lower
                                   ///< particle weighs 1 + stacking·u times its mass, u (0…1) how far the pair's normal
                                   ///< points along −gravity (Gauss-Seidel with iterations ≥ 2 only); with anchored
                                   ///< friction, a particle within reach of a shape is pushed by its pairs only along
                                   ///< the shape (together, with warm_start 0.75, at 1 × 4 the 10 000-circle pour rests
                                   ///< under 1 % from every start tried); 2 holds the
                                   ///< 10 000-circle pour under 1 % overlap at 1 × 8 (docs/collisions.md); default 0 = off
    bool anchored_friction;        ///< static friction between particles held from substep to substep: a pair that does
                                   ///< not slip keeps the relative position it stuck at, so piles and stacks of circles
                                   ///< stand (a 10-row pyramid, a pour in a bowl); slow pairs only (under the restitution
                                   ///< threshold), Verlet or symplectic Euler, Gauss-Seidel, particles that do not turn.
                                   ///< With stacking 2 the pour rests from every start tried. About 1.5–1.7× the step
                                   ///< time of a pile.
                                   ///< A pile settling can gain energy (docs/collisions.md). Default false
    double warm_start;             ///< with anchored friction: 0…1, the share of a resting pair's normal correction of
                                   ///< its last substep that is applied before the sweeps, so a pile's weight is held
                                   ///< from the first sweep and the sweeps only correct what changed (resting pairs
                                   ///< only: slower than the restitution threshold). With stacking 2 and 0.75 the
                                   ///< 10 000-circle pour rests under 1 % overlap at 1 × 4 (docs/collisions.md "Warm
                                   ///< start"). Default 0 = off
} tt_collision_settings;

/// One contact event, delivered after the step (see tt_world_get_contact_events).
typedef struct tt_contact_event {
    uint32_t kind;      ///< TT_EVENT_BEGIN, TT_EVENT_PERSIST or TT_EVENT_END
    bool sensor;        ///< the shape is a sensor (an overlap, no push)
    tt_particle a;      ///< the particle
    tt_particle b;      ///< the other particle, or null for a shape contact
    tt_shape shape;     ///< the shape, or null for a particle pair
    tt_vec2 point;      ///< m, contact point on a's surface (last substep it touched)
    tt_vec2 normal;     ///< unit, pointing from b (or the shape) towards a
    double impulse;     ///< N·s, estimate of the normal impulse of the step (0 for END and sensors)
    tt_terrain terrain; ///< the terrain of a terrain contact (shape and b null), else null
} tt_contact_event;

/// First hit of a ray (tt_world_raycast).
typedef struct tt_ray_hit {
    bool hit;           ///< false: nothing on the segment
    tt_particle particle; ///< the particle hit, or null
    tt_shape shape;     ///< the shape hit, or null
    tt_vec2 point;      ///< m, where the ray meets the surface
    tt_vec2 normal;     ///< unit surface normal there, facing the ray
    double fraction;    ///< 0…1 along from → to
    tt_terrain terrain; ///< the terrain hit, or null
} tt_ray_hit;

/// Collision counters of the last step and memory of the collision feature.
typedef struct tt_collision_stats {
    uint32_t shapes;            ///< live shapes
    uint32_t pair_contacts;     ///< particle pairs found by the broadphase (last substep, incl. margin)
    uint32_t shape_contacts;    ///< particle–shape contacts (last substep)
    uint32_t cells;             ///< cells of the grid the last substep found its pairs in; 0 when it built none
    uint32_t static_rebuilds;   ///< times the static index was built since creation
    size_t broadphase_bytes;    ///< particle grid arrays, bytes
    double broadphase_bytes_per_particle; ///< broadphase_bytes / particles in the grid
    size_t total_bytes;         ///< everything the collision feature holds
    double broadphase_ms;       ///< particle grid build and pair search in the last step (all substeps), ms
} tt_collision_stats;

/// The defaults documented on each tt_shape_def field.
TT_API tt_shape_def tt_shape_def_default(void);
/// Adds a shape; the null handle on bad input (tt_last_error says why). Switches on particle–shape contacts.
TT_API tt_shape tt_shape_create(tt_world *w, const tt_shape_def *def);
/// Removes a shape; its handle goes stale. Safe at any time between steps (also while reading events).
TT_API tt_result tt_shape_destroy(tt_world *w, tt_shape s);
/// True if s names a live shape of w.
TT_API bool tt_shape_is_valid(const tt_world *w, tt_shape s);
/// Kinematic move: new position (m) and angle (rad). The shape travels
/// there across the substeps of the next step, at the speed that takes, so
/// what rests on it is carried (friction) and what it meets is pushed at
/// that speed, not thrown by a jump. Calls between two steps keep the first
/// starting point; the getter returns the target at once.
TT_API tt_result tt_shape_set_transform(tt_world *w, tt_shape s, tt_vec2 position, double angle);
TT_API tt_result tt_shape_get_transform(const tt_world *w, tt_shape s, tt_vec2 *position, double *angle);
/// Restitution 0…1, μs ≥ 0, μk ≥ 0.
TT_API tt_result tt_shape_set_material(tt_world *w, tt_shape s, double restitution, double friction_static, double friction_kinetic);
TT_API tt_result tt_shape_set_filter(tt_world *w, tt_shape s, uint16_t category, uint16_t mask);
TT_API tt_result tt_shape_set_sensor(tt_world *w, tt_shape s, bool sensor);
TT_API tt_result tt_shape_get_type(const tt_world *w, tt_shape s, tt_shape_type *out);
TT_API tt_result tt_shape_get_user(const tt_world *w, tt_shape s, uint64_t *out);
/// Bounding box of the shape in world coordinates, m.
TT_API tt_result tt_shape_get_aabb(const tt_world *w, tt_shape s, tt_vec2 *lo, tt_vec2 *hi);
/// Live shapes.
TT_API uint32_t tt_world_shape_count(const tt_world *w);
/// Whether the shape is a sensor (reports overlaps, never pushes).
TT_API tt_result tt_shape_get_sensor(const tt_world *w, tt_shape s, bool *out);
/// Bulk: writes up to cap live shape handles in slot order into out (may be NULL to count); returns how many live.
TT_API uint32_t tt_world_list_shapes(const tt_world *w, tt_shape *out, uint32_t cap);
/// The shape's outline in world coordinates, for drawing: up to cap points into out
/// (may be NULL to count), *count = points in the outline (circles and capsule ends as
/// 32/26 points), *closed = whether the last point joins the first (false for segments and open chains).
TT_API tt_result tt_shape_get_outline(const tt_world *w, tt_shape s, tt_vec2 *out, uint32_t cap, uint32_t *count, bool *closed);
/// Name of a shape type ("segment", "chain", "aabb", "box", "circle", "capsule", "polygon").
TT_API const char *tt_shape_type_name(tt_shape_type t);

/// The defaults documented on each tt_collision_settings field.
TT_API tt_collision_settings tt_collision_settings_default(void);
/// Sets the collision settings (switches collisions on for this world).
TT_API tt_result tt_world_set_collision(tt_world *w, const tt_collision_settings *s);
/// Current settings; a world without collisions reports the defaults with particles = false.
TT_API tt_result tt_world_get_collision(const tt_world *w, tt_collision_settings *out);
/// Counters and memory (see tt_collision_stats).
TT_API tt_result tt_world_get_collision_stats(const tt_world *w, tt_collision_stats *out);

/// Per-particle material (overrides the world defaults): restitution 0…1, μs ≥ 0, μk ≥ 0.
TT_API tt_result tt_particle_set_material(tt_world *w, tt_particle p, double restitution, double friction_static, double friction_kinetic);
TT_API tt_result tt_particle_get_material(const tt_world *w, tt_particle p, double *restitution, double *friction_static, double *friction_kinetic);
/// Bullet: continuous detection against shapes (swept circle) for this particle; default false.
TT_API tt_result tt_particle_set_bullet(tt_world *w, tt_particle p, bool bullet);
TT_API tt_result tt_particle_get_bullet(const tt_world *w, tt_particle p, bool *out);
/// Switches collisions between two particles off (enabled = false) or back on; default on.
TT_API tt_result tt_world_set_pair_collision(tt_world *w, tt_particle a, tt_particle b, bool enabled);

/// Contact events of the last step, in a deterministic order; *count gets
/// their number. Valid until the next tt_world_step; removing or moving
/// particles and shapes while reading them is safe (handles may go stale).
TT_API const tt_contact_event *tt_world_get_contact_events(const tt_world *w, uint32_t *count);

/// First particle or shape whose category meets `mask` along the segment
/// from → to. Particles count as circles, sensors are skipped; a ray that
/// starts inside something reports it at fraction 0.
TT_API tt_result tt_world_raycast(tt_world *w, tt_vec2 from, tt_vec2 to, uint16_t mask, tt_ray_hit *out);
/// Particles (circles) and shapes that contain point p. Writes up to pcap
/// particles and scap shapes (arrays may be NULL with cap 0); *np and *ns get the full counts.
TT_API tt_result tt_world_query_point(tt_world *w, tt_vec2 p, uint16_t mask, tt_particle *particles, uint32_t pcap,
                                      uint32_t *np, tt_shape *shapes, uint32_t scap, uint32_t *ns);
/// Particles whose circle overlaps the box lo–hi and shapes whose geometry overlaps it; as tt_world_query_point.
TT_API tt_result tt_world_query_aabb(tt_world *w, tt_vec2 lo, tt_vec2 hi, uint16_t mask, tt_particle *particles,
                                     uint32_t pcap, uint32_t *np, tt_shape *shapes, uint32_t scap, uint32_t *ns);

#ifdef __cplusplus
}
#endif

#endif
