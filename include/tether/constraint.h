/* tether — position constraints: distance, pin, bounds, angle, area, collinear.
 *
 * Constraints move particles directly (position based dynamics): every
 * relaxation sweep of tt_world_step corrects positions, and velocities follow
 * (Verlet implies them; the other integrators get (x − x_before)/h). Each
 * constraint is either stiff-by-fraction (stiffness k in [0, 1]: the fraction
 * of its error removed per sweep, so the result depends on iterations and dt)
 * or compliant (XPBD, compliance α > 0 in the inverse of the constraint's
 * stiffness unit — m/N for distance and pin — which behaves the same for any
 * iteration count and dt; Macklin et al. 2016). Inverse masses weigh every
 * correction: a pinned particle never moves, a heavy one moves less. */
#ifndef TETHER_CONSTRAINT_H
#define TETHER_CONSTRAINT_H

#include "world.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Kinds of constraint.
typedef enum tt_constraint_kind {
    TT_CONSTRAINT_DISTANCE = 1, ///< |xa − xb| = length (or ≤, or ≥)
    TT_CONSTRAINT_PIN,          ///< a particle held at an anchor point the script may move
    TT_CONSTRAINT_BOUNDS,       ///< particles kept inside (or outside) an axis-aligned box
    TT_CONSTRAINT_ANGLE,        ///< the angle at b from (a − b) to (c − b) kept within [min, max]
    TT_CONSTRAINT_AREA,         ///< a polygon of particles keeps pressure × rest area
    TT_CONSTRAINT_COLLINEAR     ///< b kept on the line through a and c
} tt_constraint_kind;

/// What a distance constraint enforces.
typedef enum tt_distance_mode {
    TT_DISTANCE_RIGID = 0, ///< |xa − xb| = length (a rod)
    TT_DISTANCE_MAX,       ///< |xa − xb| ≤ length (a rope: goes slack)
    TT_DISTANCE_MIN        ///< |xa − xb| ≥ length (a strut that only pushes)
} tt_distance_mode;

/// A distance constraint. Start from tt_distance_def_default().
typedef struct tt_distance_def {
    tt_particle a, b;       ///< two distinct live particles
    tt_distance_mode mode;  ///< default TT_DISTANCE_RIGID
    double length;          ///< rest length, m, ≥ 0; default −1 = the distance between a and b when made
    double stiffness;       ///< fraction of the error removed per sweep, [0, 1]; default 1 (ignored when compliance > 0)
    double compliance;      ///< XPBD compliance, m/N, ≥ 0; default 0 (rigid by stiffness)
    double break_strain;    ///< breaks when |xa − xb| > length·(1 + break_strain) after a substep; ≥ 0; default 0 = never
    bool collide;           ///< may a and b collide with each other? default false
    double max_rate;        ///< winch: m/s a length change proceeds at, at most, ≥ 0; default 0 = no limit (see tt_constraint_set_max_rate)
} tt_distance_def;

/// A pin: the particle is pulled to `anchor`. Start from tt_pin_def_default().
typedef struct tt_pin_def {
    tt_particle particle;   ///< a live particle
    bool anchor_here;       ///< true: the anchor is the particle's position when made; default true
    tt_vec2 anchor;         ///< m, used when anchor_here is false; default (0, 0)
    double stiffness;       ///< [0, 1]; default 1
    double compliance;      ///< m/N, ≥ 0; default 0
    double max_rate;        ///< m/s the anchor travels at, at most, ≥ 0; default 0 = no limit (see tt_constraint_set_max_rate)
} tt_pin_def;

/// Bounds: each particle's disc (its radius) kept inside, or outside, the box
/// [min, max]. Start from tt_bounds_def_default().
typedef struct tt_bounds_def {
    const tt_particle *particles; ///< the particles; NULL with count 0 = every particle of the world, now and later
    uint32_t count;               ///< number of particles; default 0
    tt_vec2 min, max;             ///< box corners, m; min < max on both axes; default (−10, −10), (10, 10)
    bool outside;                 ///< false: keep inside (a container); true: keep out (a solid block); default false
    double friction;              ///< [0, 1]: fraction of the sliding velocity removed per substep in contact; default 0
} tt_bounds_def;

/// Angle limit at b. The angle is measured from (a − b) to (c − b),
/// counter-clockwise positive, in (−π, π]. Start from tt_angle_def_default().
typedef struct tt_angle_def {
    tt_particle a, b, c;    ///< three distinct live particles
    double min, max;        ///< rad in [−π, π], used when use_current is false (min > max: the range wraps through ±π); default −π, π
    bool use_current;       ///< true: min = max = the angle when made, min/max ignored; default true
    double stiffness;       ///< [0, 1]; default 1
    double compliance;      ///< rad/(N·m), ≥ 0; default 0
} tt_angle_def;

/// Area of a polygon of particles (counter-clockwise for a positive area).
/// Start from tt_area_def_default().
typedef struct tt_area_def {
    const tt_particle *particles; ///< 3 … 65 536 distinct live particles, in polygon order
    uint32_t count;               ///< default 0 (must be set)
    double area;                  ///< rest area, m² (signed: CCW positive), used when use_current is false; default 0
    bool use_current;             ///< true: rest area = the polygon's area when made; default true
    double pressure;              ///< target = pressure × rest area, > 0; default 1 (> 1 inflates)
    double stiffness;             ///< [0, 1]; default 1
    double compliance;            ///< m²/(N·m) (area per unit generalised force), ≥ 0; default 0
} tt_area_def;

/// Collinear: b kept on the line through a and c. Start from tt_collinear_def_default().
typedef struct tt_collinear_def {
    tt_particle a, b, c;    ///< three distinct live particles
    double stiffness;       ///< [0, 1]; default 1
    double compliance;      ///< ≥ 0; default 0
} tt_collinear_def;

/// A distance constraint broke during the last step (cloth tearing).
typedef struct tt_break_event {
    tt_constraint constraint; ///< the constraint, now removed (its handle is stale)
    tt_particle a, b;         ///< its two particles
    double length;            ///< |xa − xb| when it broke, m
    double strain;            ///< length / rest − 1 when it broke; TT_MAX_VALUE for a zero-length link (unbounded)
} tt_break_event;

/// The defaults documented on each field.
TT_API tt_distance_def tt_distance_def_default(void);
TT_API tt_pin_def tt_pin_def_default(void);
TT_API tt_bounds_def tt_bounds_def_default(void);
TT_API tt_angle_def tt_angle_def_default(void);
TT_API tt_area_def tt_area_def_default(void);
TT_API tt_collinear_def tt_collinear_def_default(void);

/// Adds a constraint; the null handle on bad input (tt_last_error says why).
TT_API tt_constraint tt_distance_create(tt_world *w, const tt_distance_def *def);
TT_API tt_constraint tt_pin_create(tt_world *w, const tt_pin_def *def);
TT_API tt_constraint tt_bounds_create(tt_world *w, const tt_bounds_def *def);
TT_API tt_constraint tt_angle_create(tt_world *w, const tt_angle_def *def);
TT_API tt_constraint tt_area_create(tt_world *w, const tt_area_def *def);
TT_API tt_constraint tt_collinear_create(tt_world *w, const tt_collinear_def *def);

/// Removes a constraint; its handle goes stale. Removing a particle removes
/// the constraints on it (a bounds constraint only forgets that particle).
TT_API tt_result tt_constraint_destroy(tt_world *w, tt_constraint c);
/// True if c names a live constraint of w.
TT_API bool tt_constraint_is_valid(const tt_world *w, tt_constraint c);
TT_API tt_result tt_constraint_get_kind(const tt_world *w, tt_constraint c, tt_constraint_kind *out);
/// Current error, in the constraint's unit: m (distance, pin, bounds: the
/// largest violation, collinear: distance of b from the line), rad (angle),
/// m² (area). 0 when satisfied.
TT_API tt_result tt_constraint_get_error(const tt_world *w, tt_constraint c, double *out);
/// Particles of the constraint (bounds over every particle: 0), up to cap
/// into out (may be NULL); *count gets the total.
TT_API tt_result tt_constraint_get_particles(const tt_world *w, tt_constraint c, tt_particle *out, uint32_t cap, uint32_t *count);
/// [0, 1]; not for bounds.
TT_API tt_result tt_constraint_set_stiffness(tt_world *w, tt_constraint c, double stiffness);
/// ≥ 0 (0 = use stiffness); not for bounds.
TT_API tt_result tt_constraint_set_compliance(tt_world *w, tt_constraint c, double compliance);
/// Distance constraints: rest length, m, ≥ 0. A new length is not a jump:
/// the length the solver uses goes linearly from the old one to the new one
/// across the substeps of the next step (substep s of S: old + (new − old)·(s+1)/S,
/// exactly the new one in the last), so reeling a rope in at v m/s moves its
/// load at v m/s in every substep, whatever the substep count. With a
/// max_rate the change takes as many steps as that rate needs. The getter
/// returns the length set, at once.
TT_API tt_result tt_distance_set_length(tt_world *w, tt_constraint c, double length);
TT_API tt_result tt_distance_get_length(const tt_world *w, tt_constraint c, double *out);
/// Pins: move the anchor (drag with the mouse), m. Like a distance's length,
/// the anchor travels there across the substeps of the next step (or at
/// max_rate); the getter returns the anchor set, at once.
TT_API tt_result tt_pin_set_anchor(tt_world *w, tt_constraint c, tt_vec2 anchor);
TT_API tt_result tt_pin_get_anchor(const tt_world *w, tt_constraint c, tt_vec2 *out);
/// A winch: distance constraints and pins only. A change of length
/// (tt_distance_set_length) or anchor (tt_pin_set_anchor) then proceeds at
/// most `rate` m/s (of length, or of anchor travel), carried over as many
/// steps as it needs; ≥ 0, default 0 = no limit (the whole change in the next
/// step). A new rate applies from the next step, to a change under way too.
TT_API tt_result tt_constraint_set_max_rate(tt_world *w, tt_constraint c, double rate);
TT_API tt_result tt_constraint_get_max_rate(const tt_world *w, tt_constraint c, double *out);
/// Bounds: move or resize the box, m (min < max).
TT_API tt_result tt_bounds_set_box(tt_world *w, tt_constraint c, tt_vec2 min, tt_vec2 max);

/// Live constraints in the world.
TT_API uint32_t tt_world_constraint_count(const tt_world *w);
/// Bulk for drawing: segments of every distance constraint, then every pin
/// (particle → anchor), as x1, y1, x2, y2 into xy (4·cap doubles); returns the
/// number of segments there are (may be more than cap; xy may be NULL to count).
TT_API uint32_t tt_world_read_constraint_lines(const tt_world *w, double *xy, uint32_t cap);
/// Break events of the last step: *events points at *count events, valid
/// until the next step.
TT_API tt_result tt_world_get_break_events(const tt_world *w, const tt_break_event **events, uint32_t *count);

#ifdef __cplusplus
}
#endif

#endif
