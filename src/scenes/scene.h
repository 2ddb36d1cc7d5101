/* tether — scene descriptions: one plain list of rigid bodies and joints
 * that every consumer builds from (the bench, the tests, the runner, the
 * Box2D cross-check), so a scene is written once. tether builds it from
 * particles, lattice bodies and constraints (scene_tether.c); the bridge
 * builds Box2D bodies (src/box2d/). Not part of the installed API: the
 * scenes are the project's reference cases, not a game-facing format. */
#ifndef TETHER_SCENE_H
#define TETHER_SCENE_H

#include "tether.h"

#define TS_MAX_POLYGON 8 /* Box2D 2.4.1's b2_maxPolygonVertices: both engines must take every scene */
#define TS_GROUND (-1)   /* a joint's body index meaning "the static world" */
#define TS_MAX_BODIES 1000000u

typedef enum ts_shape {
    TS_CIRCLE = 0, /* radius */
    TS_BOX,        /* half extents, turned by angle */
    TS_POLYGON,    /* convex, counter-clockwise, local points */
    TS_EDGE        /* segment a–b, local; static only */
} ts_shape;

typedef enum ts_joint_kind {
    TS_REVOLUTE = 0, /* the two bodies share anchor_a and turn freely about it */
    TS_DISTANCE,     /* anchor_a on a and anchor_b on b keep their distance */
    TS_WELD          /* the two bodies keep their relative pose */
} ts_joint_kind;

/* One rigid body. Zero is a sensible start for every field but the shape's
 * size; ts_body_default() gives density 1, friction 0.3. */
typedef struct ts_body {
    ts_shape shape;
    bool dynamic;                       /* false: static (never moves) */
    tt_vec2 position;                   /* m, the shape's local origin (its centre for circles and boxes) */
    double angle;                       /* rad */
    tt_vec2 velocity;                   /* m/s of the centre */
    double spin;                        /* rad/s */
    double radius;                      /* m, circle */
    tt_vec2 half;                       /* m, box half extents */
    tt_vec2 a, b;                       /* m, edge ends (local) */
    tt_vec2 points[TS_MAX_POLYGON];     /* m, polygon (local, convex, CCW) */
    uint32_t count;                     /* polygon points, 3 … TS_MAX_POLYGON */
    double density;                     /* kg/m² (mass = density × area) */
    double friction;                    /* Coulomb μ; both engines take √(μa·μb) for a pair */
    double restitution;                 /* 0 … 1; both engines take the larger of a pair */
    bool fixed_rotation;                /* never turns: Box2D's fixedRotation (tether's particles turn only with spin) */
} ts_body;

typedef struct ts_joint {
    ts_joint_kind kind;
    int32_t a, b;                       /* body indices; a may be TS_GROUND */
    tt_vec2 anchor_a, anchor_b;         /* m, world points when made (anchor_b: distance only) */
} ts_joint;

typedef struct ts_scene {
    char name[32];
    tt_vec2 gravity;                    /* m/s² */
    double dt;                          /* s per step */
    uint32_t steps;                     /* how long the scene is meant to run */
    ts_body *bodies;
    uint32_t body_count, body_cap;
    ts_joint *joints;
    uint32_t joint_count, joint_cap;
} ts_scene;

/* A body, then the helpers that fill one in. */
ts_body ts_body_default(void);
ts_body ts_circle(bool dynamic, tt_vec2 at, double radius);
ts_body ts_box(bool dynamic, tt_vec2 at, double half_w, double half_h, double angle);

/* An empty scene: gravity (0, −10), dt 1/60, 60 steps. */
void ts_scene_init(ts_scene *s, const char *name);
void ts_scene_free(ts_scene *s);
/* The highest centre of a dynamic body, m (0 when there is none): where a fall in the scene starts from at most. */
double ts_scene_highest(const ts_scene *s);
/* A deep copy of src into dst (initialised here); false on no memory. */
bool ts_scene_copy(ts_scene *dst, const ts_scene *src);
/* Adds a copy; returns its index, or −1 on bad input or no memory (why in *why when not NULL). */
int32_t ts_scene_add_body(ts_scene *s, const ts_body *b, const char **why);
int32_t ts_scene_add_joint(ts_scene *s, const ts_joint *j, const char **why);
/* The checks ts_scene_add_body makes: NULL when b is fine, else why not. */
const char *ts_body_check(const ts_body *b);
/* Mass (kg) and moment of inertia about the centre of mass (kg·m²) of a dynamic body. */
double ts_body_mass(const ts_body *b);
double ts_body_inertia(const ts_body *b);

/* --- the project's named scenes (scene_library.c) -------------------------- */

/* The names, NULL-terminated: fall, pendulum, bounce, slope, spin, pyramid,
 * discs, pour, pour100k; "quick" variants are smaller or shorter (for tests). */
extern const char *const ts_scene_names[];
/* Builds the named scene into s (initialised here); false on an unknown name. */
bool ts_scene_named(ts_scene *s, const char *name, bool quick);

/* The reference pour: n circles of radius 0.5 from a staggered grid 1.1
 * apart (floor(width/1.1) − 1 per row, odd rows offset 0.05, the lowest row
 * at y = 0.55) into a box `width` wide (floor top at y = 0, walls to y = 400),
 * g = 10, dt = 1/60, friction 0.3 on circles and walls, restitution 0, 20 s.
 * (10 000, 100) is the reference pour, (100 000, 316) the 100 k pour. */
void ts_scene_pour(ts_scene *s, uint32_t n, double width);
/* The reference pour's n circles alone (its box left out for the caller's
 * container: scene_bowl.c, scene_floor.c), lifted by lift m, into s
 * (initialised here) named name; *top is 5 m above the highest centre.
 * False on no memory (s then empty), the reason in *why. */
bool ts_scene_pour_lifted(ts_scene *s, uint32_t n, double width, double lift, const char *name, double *top,
                          const char **why);
/* A 1 × 1 box of friction mu resting on a static slope of `degrees`. */
void ts_scene_slope(ts_scene *s, double degrees, double mu);

/* --- the hung cloth (scene_cloth.c) ----------------------------------------- */

/* An n × n cloth 2 cm apart, 1 g a particle, hanging under default gravity
 * from its top row or its two top corners, the world at tolerance 0 (every
 * sweep runs: fixed work); ts_hung_cloth_default() gives n = 128, Gauss-Seidel,
 * 1 substep, 10 sweeps, top row, no long-range attachments. */
typedef struct ts_hung_cloth {
    uint32_t n;                         /* particles along a side, at least 2 */
    tt_solver_order order;
    uint32_t substeps, iterations;
    bool top_row;                       /* false: the two top corners */
    bool long_range;                    /* tt_cloth_def.long_range */
} ts_hung_cloth;
ts_hung_cloth ts_hung_cloth_default(void);
/* A new world holding the cloth (its handle in *cloth when not NULL); NULL
 * when it cannot be made. */
tt_world *ts_hung_cloth_build(const ts_hung_cloth *d, tt_composite *cloth);

/* --- particles on a square lattice (scene_grid.c) ------------------------ */

/* count particles row by row from the cell at `corner` (its lower-left
 * corner), `columns` to a row, each at the centre of its spacing × spacing
 * cell: x = corner.x + spacing·(0.5 + i mod columns), likewise y by rows.
 * Radius `radius`, or `big_radius` for every big_every-th (0: none) from
 * the first; the other fields tt_particle_def_default()'s. */
typedef struct ts_grid {
    uint32_t count, columns;
    tt_vec2 corner;                     /* m */
    double spacing;                     /* m */
    double radius, big_radius;          /* m */
    uint32_t big_every;
} ts_grid;
ts_grid ts_grid_default(void);          /* none yet: 1 column, spacing 1, radius 0.5 */
/* Adds the particles to w in order; returns how many were made (fewer only
 * when the world refused one, e.g. out of capacity). */
uint32_t ts_grid_add(tt_world *w, const ts_grid *g);

/* A cloth that catches balls: an n × n cloth 2 cm apart (1 g and radius
 * 1 cm a particle) hung from its two top corners, and `balls` circles
 * (radius 2 cm, 10 g) in a staggered grid 5 cm apart from 10 cm above its
 * top edge, falling onto it under default gravity: distance links and
 * particle contacts relaxed in the same sweeps. Gauss-Seidel, 1 substep,
 * tolerance 0 (every sweep runs). */
typedef struct ts_cloth_catch {
    uint32_t n;          /* cloth particles along a side, at least 2 */
    uint32_t balls;
    uint32_t iterations; /* sweeps per step */
} ts_cloth_catch;
/* A new world holding the scene (the cloth's handle in *cloth when not
 * NULL; its particles are slots [0, n²)); NULL when it cannot be made. */
tt_world *ts_cloth_catch_build(const ts_cloth_catch *d, tt_composite *cloth);

/* --- measures shared by the bench and the cross-check (scene_metrics.c) --- */

typedef struct ts_pile {
    double height;       /* m, fill level: median over 2r-wide columns of each column's highest circle top */
    double max_overlap;  /* deepest overlap of two circles, fraction of a radius */
    double mean_overlap; /* mean over overlapping pairs, fraction of a radius */
    uint32_t overlapping;/* pairs closer than two radii */
    double contacts;     /* per circle: twice the pairs within 1 % of a radius of touching, over n (how densely it packs) */
} ts_pile;
/* Circles of equal radius r at centres xy (2n doubles; reordered on the way);
 * NaN measures for r ≤ 0 or no xy. */
void ts_pile_measure(double *xy, uint32_t n, double r, ts_pile *out);

/* --- the tether side (scene_tether.c) ------------------------------------- */

typedef struct ts_tether_settings {
    uint32_t substeps, iterations;      /* the world's; default 1 and 8 */
    uint32_t lattice;                   /* particles along a box's shorter side, 2 … 64; default 4 */
    bool spin;                          /* particles turn (tt_world_def.spin); default false */
    bool anchored;                      /* tt_collision_settings.anchored_friction; default false */
} ts_tether_settings;

/* What each body became: a particle (dynamic circle), a lattice composite
 * (dynamic box or polygon) or a shape (static body). */
typedef struct ts_tether_body {
    tt_particle particle;
    tt_composite composite;
    tt_shape shape;
    double angle0;                      /* rad, the body's angle when built (a lattice reads its turn from there) */
} ts_tether_body;

typedef struct ts_tether {
    tt_world *world;
    ts_tether_body *body;               /* one per scene body, in order */
    uint32_t count;
    tt_particle *circles;               /* the dynamic circles' particles, in body order */
    uint32_t circle_count;
    double mass;                        /* kg, of the dynamic bodies */
} ts_tether;

/* State of one body, read the same way from either engine. */
typedef struct ts_state {
    tt_vec2 position;                   /* m, centre of mass */
    double angle;                       /* rad */
    tt_vec2 velocity;                   /* m/s of the centre of mass */
    double spin;                        /* rad/s */
    double momentum;                    /* kg·m²/s, angular momentum about the centre of mass */
} ts_state;

ts_tether_settings ts_tether_settings_default(void);
/* The reference pour's n circles (ts_scene_pour(n, width)) without their
 * box, lifted by lift, built at the default settings into t; *top is 5 m
 * above the highest centre, *steps the pour's length. For the builders that give the pour a terrain
 * or a chain instead (scene_bowl.c, scene_floor.c). */
tt_result ts_tether_pour_circles(uint32_t n, double width, double lift, const char *name, ts_tether *t, double *top,
                                 uint32_t *steps, const char **why);
/* Builds s into a new world (t->world); TT_OK, or an error with the reason in *why. */
tt_result ts_tether_build(const ts_scene *s, const ts_tether_settings *set, ts_tether *t, const char **why);
void ts_tether_free(ts_tether *t);
tt_result ts_tether_state(const ts_tether *t, uint32_t body, ts_state *out);
/* Kinetic energy per kg of the dynamic bodies, J/kg. */
double ts_tether_kinetic_per_kg(const ts_tether *t);
/* A jittered start: each circle moved by up to ±amount in x and in y
 * (uniform, its own generator from seed), velocity reset; seed 0 leaves
 * the start as built. The bowl's tests and bench share it. */
tt_result ts_tether_jitter(ts_tether *t, uint64_t seed, double amount);

/* --- the reference pour onto a mask bowl (scene_bowl.c) ------------------- */

typedef struct ts_bowl {
    ts_tether t;                        /* the world and its circles */
    tt_terrain terrain;                 /* the bowl: 0.1 m pixels, an arc of radius 0.8 × width between walls */
    double radius;                      /* m, of the circles */
    uint32_t steps;                     /* 20 s */
} ts_bowl;

typedef struct ts_bowl_figures {
    double kinetic;                     /* J/kg of the circles */
    double penetration;                 /* deepest of a circle into the bowl, fraction of a radius (≤ 0: none) */
    double max_overlap, mean_overlap;   /* of two circles, fraction of a radius (ts_pile_measure) */
    uint32_t inside;                    /* circles whose centre lies in a solid pixel */
} ts_bowl_figures;

/* The reference pour's n circles (ts_scene_pour(n, width): grid, radius,
 * friction 0.3, g = 10, dt = 1/60), lifted clear of the rim, above a mask
 * bowl as wide as its box; TT_OK, or an error with the reason in *why. */
tt_result ts_bowl_build(uint32_t n, double width, ts_bowl *b, const char **why);
/* The same pour and bowl as a scene for Box2D: the circles at ts_bowl_build's
 * positions (fixed_rotation as given) and the bowl as static edges, `edges`
 * along the arc (1 … 100 000) and one up each wall, friction 0.3; false on
 * bad input or no memory, the reason in *why. */
bool ts_scene_bowl(ts_scene *s, uint32_t n, double width, uint32_t edges, bool fixed_rotation, const char **why);
void ts_bowl_free(ts_bowl *b);
void ts_bowl_measure(const ts_bowl *b, ts_bowl_figures *out);

/* --- the reference pour into a U floor (scene_floor.c) ------------------- */

/* The reference pour's n circles (ts_scene_pour(n, width)) into a U whose
 * floor top is y = 0 and inner walls ±width/2, reaching 5 m above the
 * highest circle: a chain shape (mask false) or a mask terrain of 0.1 m
 * pixels, both friction 0.3; TT_OK, or an error with the reason in *why. */
tt_result ts_floor_build(uint32_t n, double width, bool mask, ts_tether *t, const char **why);

#endif
