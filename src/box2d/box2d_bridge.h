/* tether — the Box2D 2.4.1 bridge: a C interface to the rigid-body engine
 * used as tether's cross-check (box2d_bridge.cpp, the project's only C++).
 * Only libtether_box2d and the tether_box2d Lua module link it, so
 * libtether.so and tether.so never need Box2D or libstdc++.
 * Every call checks its input and fails softly (NULL, −1 or false) with
 * the reason in tb_last_error(); nothing reaches a Box2D assertion. */
#ifndef TETHER_BOX2D_BRIDGE_H
#define TETHER_BOX2D_BRIDGE_H

#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tb_world tb_world;

typedef struct tb_world_def {
    double gravity[2];            /* m/s²; default (0, −10) */
    int velocity_iterations;      /* 1 … 1000; default 8 */
    int position_iterations;      /* 1 … 1000; default 3 */
    bool sleep;                   /* bodies at rest fall asleep; default true (Box2D's default) */
    bool continuous;              /* time of impact for fast bodies; default true (Box2D's default) */
} tb_world_def;

typedef enum tb_shape { TB_CIRCLE = 0, TB_BOX, TB_POLYGON, TB_EDGE } tb_shape;
typedef enum tb_joint { TB_REVOLUTE = 0, TB_DISTANCE, TB_WELD } tb_joint;
#define TB_GROUND (-1)            /* a joint's body index meaning the static world */
#define TB_MAX_POLYGON 8          /* b2_maxPolygonVertices */

typedef struct tb_body_def {
    tb_shape shape;
    bool dynamic;
    double position[2], angle;    /* m, rad: the body's origin */
    double velocity[2], spin;     /* m/s of the centre of mass, rad/s */
    double radius;                /* circle, m; default 0.5 */
    double half[2];               /* box half extents, m; default (0.5, 0.5) */
    double a[2], b[2];            /* edge ends, local, m; static only */
    double points[2 * TB_MAX_POLYGON]; /* polygon, local, convex, counter-clockwise */
    int count;                    /* polygon points, 3 … 8 */
    double density;               /* kg/m²; default 1 */
    double friction;              /* default 0.3 (Box2D mixes √(μa·μb)) */
    double restitution;           /* 0 … 1; default 0 (Box2D mixes the larger) */
    bool fixed_rotation;          /* the body never turns (as tether's particles); default false */
} tb_body_def;

typedef struct tb_body_state {
    double position[2];           /* m, centre of mass */
    double angle;                 /* rad */
    double velocity[2];           /* m/s of the centre of mass */
    double spin;                  /* rad/s */
    double mass, inertia;         /* kg, kg·m² about the centre of mass (0 for static) */
    bool awake;
} tb_body_state;

tb_world_def tb_world_def_default(void);
tb_body_def tb_body_def_default(void);
tb_world *tb_world_create(const tb_world_def *def);
void tb_world_destroy(tb_world *w);                            /* NULL is fine */
bool tb_world_set(tb_world *w, const tb_world_def *def);       /* iterations, sleep, continuous, gravity */
/* The body's index (0, 1, … in creation order), or −1. */
int tb_body_create(tb_world *w, const tb_body_def *def);
/* A joint between bodies a (may be TB_GROUND) and b (dynamic) at world
 * anchors (anchor_b used by distance joints only); its index, or −1. */
int tb_joint_create(tb_world *w, tb_joint kind, int a, int b, const double anchor_a[2], const double anchor_b[2]);
/* One step of dt s (0 < dt ≤ 10). */
bool tb_world_step(tb_world *w, double dt);
bool tb_body_state_get(const tb_world *w, int body, tb_body_state *out);
/* Centres of the bodies [first, first + n) into xy (2n doubles). */
bool tb_positions(const tb_world *w, int first, int n, double *xy);
int tb_world_body_count(const tb_world *w);
/* Σ ½ m v² + ½ I ω² over the dynamic bodies, J; and their mass, kg. */
double tb_world_kinetic_energy(const tb_world *w);
double tb_world_mass(const tb_world *w);
/* Why the last call failed (per thread); "" when none. */
const char *tb_last_error(void);

#ifdef __cplusplus
}
#endif

#endif
