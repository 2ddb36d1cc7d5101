/* tether — composites: helpers that make particles + constraints in one call
 * (rope, cloth, ragdoll, soft body, lattice rigid body) and keep their
 * handles under one composite handle, from which they are read back. */
#ifndef TETHER_COMPOSITE_H
#define TETHER_COMPOSITE_H

#include "constraint.h"

#ifdef __cplusplus
extern "C" {
#endif

/// What every composite shares: its particles and its links.
typedef struct tt_composite_common {
    double mass;        ///< kg per particle, > 0; default 1
    double radius;      ///< m per particle, ≥ 0; default 0
    double stiffness;   ///< [0, 1] of every distance link; default 1
    double compliance;  ///< m/N of every distance link, ≥ 0; default 0 (rigid by stiffness)
    bool collide;       ///< may particles joined by a link collide with each other? default false
} tt_composite_common;

/// A rope (or chain) from `start` to `finish`, `segments` links, segments + 1 particles.
typedef struct tt_rope_def {
    tt_composite_common common;
    tt_vec2 start, finish; ///< m; default (0, 0), (1, 0)
    uint32_t segments;  ///< 1 … 100 000; default 10
    bool pin_start;     ///< pin the first particle (infinite mass); default true
    bool pin_finish;    ///< pin the last particle; default false
    bool slack;         ///< links are TT_DISTANCE_MAX (the rope can go slack); default false (rigid links)
    double break_strain;///< see tt_distance_def; default 0 = never
} tt_rope_def;

/// Cloth: a grid of columns × rows particles, row 0 at the top (origin is its
/// top-left corner, rows go down), with structural links (neighbours), shear
/// links (diagonals) and bend links (every second particle).
typedef struct tt_cloth_def {
    tt_composite_common common;
    tt_vec2 origin;         ///< top-left corner, m; default (0, 0)
    double width, height;   ///< m, > 0; default 1, 1
    uint32_t columns, rows; ///< particles per row / column, 2 … 4096; default 16, 16
    double shear_stiffness; ///< [0, 1]; default 1 (0 = no shear links). In 2D a sheared grid is a rigid
                            ///< truss: at 1 a cloth pinned along an edge holds like a plate; ≤ 0.1 drapes
    double bend_stiffness;  ///< [0, 1]; default 0.5 (0 = no bend links)
    bool pin_top_corners;   ///< default true
    bool pin_top_row;       ///< every top-row particle pinned; default false
    double break_strain;    ///< structural and shear links tear past this strain; default 0 = never
    bool long_range;        ///< long-range attachments (Kim, Chentanez & Müller 2012): no unpinned particle gets
                            ///< farther from the cloth's pinned ones than in the rest shape (a "max" distance link
                            ///< to each pinned corner, or with a pinned top row to the particle atop its column),
                            ///< solved after the other links: a hanging cloth stops stretching under its own
                            ///< weight at the same sweeps. Hung from two corners, a particle near the line
                            ///< between them (where the corners' discs meet at under 30°) is also kept inside the
                            ///< circle through both corners and its rest spot (an angle limit at it, after the
                            ///< links): the top band does not sag between the pins. Not with break_strain (a torn
                            ///< piece would stay tied to the pins); default false
} tt_cloth_def;

/// A ragdoll of 11 particles, in this order: 0 head, 1 neck, 2 pelvis,
/// 3 left elbow, 4 left hand, 5 right elbow, 6 right hand, 7 left knee,
/// 8 left foot, 9 right knee, 10 right foot; distance links between the
/// bones and angle limits at neck, elbows, shoulders, hips and knees.
typedef struct tt_ragdoll_def {
    tt_composite_common common;
    tt_vec2 position;   ///< the pelvis, m; default (0, 0)
    double height;      ///< head to feet, m, > 0; default 1.8 (the figure stands upright)
    bool limits;        ///< add the angle limits; default true
} tt_ragdoll_def;

/// A soft body: a ring of `segments` particles around `center`, its edges
/// linked, its area kept at pressure × rest area.
typedef struct tt_soft_body_def {
    tt_composite_common common;
    tt_vec2 center;          ///< m; default (0, 0)
    double ring_radius;      ///< m, > 0; default 1 (common.radius is each particle's)
    uint32_t segments;       ///< 3 … 65 536; default 16
    double pressure;         ///< target area / rest area, > 0; default 1
    double area_stiffness;   ///< [0, 1]; default 1
    double area_compliance;  ///< ≥ 0; default 0
} tt_soft_body_def;

/// A lattice rigid body: a rectangle of columns × rows particles (or, when
/// `points` is set, a polygon of its vertices) braced so it stays rigid. It
/// collides through its particles: a radius of at least half the spacing
/// makes their discs touch, so nothing passes between them.
typedef struct tt_lattice_def {
    tt_composite_common common;
    tt_vec2 center;          ///< rectangle centre, m; default (0, 0)
    double width, height;    ///< rectangle size, m, > 0; default 1, 1
    double angle;            ///< rectangle rotation, rad; default 0
    uint32_t columns, rows;  ///< rectangle particles per row / column, 2 … 1024; default 2, 2
    const tt_vec2 *points;   ///< polygon vertices, m (world positions), as a polygon shape's: no point
                             ///< repeated, no three consecutive on a line (it may be concave); default NULL = rectangle
    uint32_t point_count;    ///< 3 … 64 when points is set; default 0
} tt_lattice_def;

TT_API tt_rope_def tt_rope_def_default(void);
TT_API tt_cloth_def tt_cloth_def_default(void);
TT_API tt_ragdoll_def tt_ragdoll_def_default(void);
TT_API tt_soft_body_def tt_soft_body_def_default(void);
TT_API tt_lattice_def tt_lattice_def_default(void);

/// Each makes its particles and constraints; the null handle on bad input
/// (a particle past TT_MAX_VALUE included), a world too full, or no memory,
/// and then the world is exactly as it was: nothing is left behind and the
/// next handles are those it would have handed out had the call never been
/// made (tt_last_error says why).
TT_API tt_composite tt_rope_create(tt_world *w, const tt_rope_def *def);
TT_API tt_composite tt_cloth_create(tt_world *w, const tt_cloth_def *def);
TT_API tt_composite tt_ragdoll_create(tt_world *w, const tt_ragdoll_def *def);
TT_API tt_composite tt_soft_body_create(tt_world *w, const tt_soft_body_def *def);
TT_API tt_composite tt_lattice_create(tt_world *w, const tt_lattice_def *def);

/// Removes the composite with every particle and constraint it still has.
TT_API tt_result tt_composite_destroy(tt_world *w, tt_composite c);
TT_API bool tt_composite_is_valid(const tt_world *w, tt_composite c);
/// Its particles in creation order (cloth: row by row from the top), up to cap
/// into out (may be NULL); *count gets the total. Handles of particles removed
/// since are stale.
TT_API tt_result tt_composite_get_particles(const tt_world *w, tt_composite c, tt_particle *out, uint32_t cap, uint32_t *count);
/// Its constraints in creation order, as above (torn links are stale).
TT_API tt_result tt_composite_get_constraints(const tt_world *w, tt_composite c, tt_constraint *out, uint32_t cap, uint32_t *count);
/// Centre of mass of its live particles, m.
TT_API tt_result tt_composite_get_center(const tt_world *w, tt_composite c, tt_vec2 *out);
/// Orientation: the rotation, rad in (−π, π], that best maps the rest shape
/// onto the current one (least squares over live particles, mass weighted).
TT_API tt_result tt_composite_get_angle(const tt_world *w, tt_composite c, double *out);
/// Live composites in the world.
TT_API uint32_t tt_world_composite_count(const tt_world *w);

#ifdef __cplusplus
}
#endif

#endif
