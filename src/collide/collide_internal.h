/* tether — private declarations of the collision feature: every file of
 * src/collide/ (the terrains' add terrain_internal.h). */
#ifndef TETHER_COLLIDE_INTERNAL_H
#define TETHER_COLLIDE_INTERNAL_H

#include "core/internal.h"
#include "core/pair_set.h"
#include "core/simd.h"
#include "core/stream.h" /* TT__ID */
#include "tether/collide.h"
#include "contact_anchor.h"

/* Candidate pairs are kept when their gap is under this fraction of the
 * radii sum, so pairs that close during the sweeps are solved at once. */
#define TT__CONTACT_MARGIN 0.1
/* Pre-stabilisation (contact_prestab.c) undoes only the overlap deeper
 * than this fraction of the radii sum: a pile at rest keeps its overlaps
 * under it (at 1 × 8 the reference pour's deepest at 20 s is 10 %) and is
 * left as it was (see contact_prestab.c for what no slop did). */
#define TT__PRESTAB_SLOP 0.1

/* Every shape becomes primitives: rounded segments (capsule; a circle has
 * a == b, a segment r == 0) or convex polygons (radius 0). */
enum { TT__PRIM_CAPSULE = 0, TT__PRIM_POLY = 1 };

typedef struct tt__prim {
    uint32_t shape;       /* shape slot */
    uint32_t kind;
    uint32_t v0, nv;      /* polygon: vertex range in verts/norms */
    double ax, ay, bx, by, r;
    double lox, loy, hix, hiy; /* bounding box, radius included */
} tt__prim;

/* Whether the primitive's bounding box meets the box [lo, hi]. */
static inline bool tt__prim_box_meets(const tt__prim *p, double lox, double loy, double hix, double hiy)
{
    return !(p->hix < lox || p->lox > hix || p->hiy < loy || p->loy > hiy);
}

typedef struct tt__shape {
    tt_shape_def def;     /* def.points is NULL: the points live in pts; def's transform is where the script put it */
    tt_vec2 *pts;
    bool alive;
    bool moved;           /* by the script since the last step: it moves from `from` to def's transform across
                           * the next step's substeps, a kinematic body whose contacts see its velocity */
    tt_vec2 from;         /* where the last step left it, and its angle */
    double from_angle;
    /* moved, during a step: its placement at the end of the last substep (0)
     * and of this one (1), and the turn between them */
    tt_vec2 at0, at1;
    double ang1, turn_c, turn_s;
    uint32_t prim0, vert0; /* its primitives and polygon vertices in the static index */
} tt__shape;

/* How far the point of shape s now at (x, y) moved in this substep (0 for
 * a shape the script did not move): where the contact drags a particle. */
static inline void tt__shape_carry(const tt__shape *s, double x, double y, double *dx, double *dy)
{
    if (!s->moved) {
        *dx = *dy = 0.0;
        return;
    }
    /* the point was at at0 + R(−turn)·((x, y) − at1) when the substep began */
    const double rx = x - s->at1.x, ry = y - s->at1.y;
    *dx = x - (s->at0.x + s->turn_c * rx + s->turn_s * ry);
    *dy = y - (s->at0.y - s->turn_s * rx + s->turn_c * ry);
}

/* Static index: a uniform grid over the primitives' boxes, built once and
 * rebuilt only when shapes are added, removed or moved. */
typedef struct tt__sgrid {
    double ox, oy, cs, inv;
    int32_t nx, ny;
    uint32_t *start, *items; /* CSR: cell → primitive indices */
    uint32_t *big, nbig;     /* primitives covering too many cells: always tested */
    uint32_t cap_cells, cap_items, cap_big;
} tt__sgrid;

/* Particle grid: counting sort of the live particles into cells. */
enum {
    TT__GRID_OUTSIDE = 1, /* centre outside the grid (clamped into a border cell) */
    TT__GRID_PINNED = 2   /* inverse mass 0 */
};
typedef struct tt__grid {
    double ox, oy, cs, inv, rmax;
    double cs0, extent;           /* the cell a build asked for before widening; the largest |coordinate| */
    int32_t nx, ny;
    uint32_t ncell, n;            /* cells, particles sorted */
    uint32_t npinned;             /* of them with inverse mass 0 (pinned or asleep) */
    uint32_t *start;              /* ncell + 1 */
    uint32_t *cell;               /* per gathered particle: its (clamped) cell */
    uint32_t *idx;                /* sorted: particle slot */
    double *sx, *sy, *sr;         /* sorted copies of position and radius */
    uint8_t *bits;                /* sorted: TT__GRID_OUTSIDE, TT__GRID_PINNED */
    bool one_layer;               /* every particle has the same category and mask, and they match */
    uint32_t *out_list, nout;     /* particle slots outside the grid */
    uint32_t *list;               /* cap_n: the slots a listed build sorts (grid_awake.c) */
    uint32_t *cand, cand_cap;     /* scratch: sleepers within reach of an awake particle, found per awake one */
    uint32_t cap_cells, cap_n;
    uint64_t epoch;               /* w->epoch the grid reflects (queries), or UINT64_MAX */
} tt__grid;

/* Parts the pair list is cut into for batches (contact_batch.c). */
#define TT__PARTS 8

typedef struct tt__pair { /* 16 bytes: hundreds of thousands are written every substep */
    uint32_t a, b;
    float rs;             /* radii sum (the radii are floats already) */
    float lambda;         /* normal correction applied this substep, m */
} tt__pair;

#include "contact_batch.h"

/* Forces w's pair sweep mode (tests compare them bit for bit); false when
 * this build or processor lacks it (collide.c). */
bool tt__contacts_set_simd(tt_world *w, tt__simd_mode mode);

typedef struct tt__scontact {
    uint32_t a, prim;
    double nx, ny, lambda; /* normal, normal correction accumulated this substep (m) */
    double lambda_t, mu;  /* friction correction along (−ny, nx) this substep (m), |lambda_t| ≤ mu·lambda; μs */
    double cx, cy;        /* how far the shape moved at the contact this substep (tt__shape_carry; 0: it did not) */
    uint32_t ccd;         /* found by the swept test: velocity restarts from the pre-solve one */
} tt__scontact;

typedef struct tt__lift {   /* a touched pair for the bottom-up pass (contact_lift.c) */
    uint32_t lo, up;      /* its lower and upper particle along gravity */
    double h;             /* the lower one's height */
} tt__lift;

typedef struct tt__record {  /* one contact of the step, for events */
    uint64_t key;
    tt_contact_event ev;
} tt__record;

/* What a step changes of the collision state besides the particles, as
 * the step began (contact_undo.c): the end positions the next substep
 * starts from (velocity integrators, while valid) and contact_skip.c's and
 * contact_reach.c's bounds with the epochs they hold for. Scratch. */
typedef struct tt__collide_undo {
    double *sx0, *sy0;
    uint32_t cap;
    tt__anchors anc;      /* the anchors as the step began (their slots unused) */
    bool ends;            /* sx0, sy0 hold the end positions */
    uint64_t s_epoch, clear_epoch, reach_epoch;
    uint32_t s_count, probe_wait, probe_fails, reach_n;
    bool clear_ok, quiet_last;
    double clear_gap, clear_used, clear_scale;
    uint8_t reach_side;
    float reach_rmax;
} tt__collide_undo;

/* What the substeps and the step work in: neither saved nor hashed, and
 * its loss between two steps (tt__contacts_scratch_free) changes nothing
 * (tests/core/test_scratch.c): contacts_reserve sizes it again before a
 * step, each substep's detection writes it before the sweeps and the
 * velocity pass read it, and after_step reads the last substep's before
 * the step returns. Between steps the counts still describe the last
 * substep (collision stats), and grid holds the queries' grid while its
 * epoch is the world's (UINT64_MAX: none). */
typedef struct tt__collide_scratch {
    tt__grid grid;        /* the particle grid: the substep's pairs, or a query's */
    double *vx0, *vy0;    /* pre-solve velocity per particle slot (this substep) */
    uint32_t vcap;
    double *gx0, *gy0;    /* positions before the sweeps (shapes present): the guard against pushes through walls */
    uint32_t gcap;
    bool guard;           /* gx0, gy0 hold this substep's */
    double *px0, *py0;    /* pre-stabilisation's copy of the start positions (contact_prestab.c) */
    uint32_t pcap;
    struct tt__roll_contact *roll; /* particles that turn: this substep's contacts with friction (contact_roll.c) */
    uint32_t nroll, roll_cap;
    tt__lift *lift;       /* the bottom-up velocity pass's scratch: touched pairs, band starts, their order */
    uint32_t *lift_start, *lift_order;
    uint32_t lift_cap;    /* of all three */
    uint32_t *touch;      /* the units (batch entries, else pairs) that touched in the sweeps, ascending (end) */
    uint32_t ntouch, touch_cap;
    /* contacts of the current substep */
    tt__pair *pairs;
    uint32_t npairs, paircap;
    uint32_t *runs;       /* the grid's pairs by row and band of columns: row y, band k from runs[y·TT__PARTS + k] */
    uint32_t runs_cap, nrows; /* nrows: rows in runs (0: none) */
    uint8_t *near;        /* per particle-grid cell: a static primitive is within reach (this substep; then, the
                           * shapes done, a terrain surface: terrain_tiles.c) */
    uint32_t near_cap;
    tt__batches bat;
    bool batched;         /* this substep's pairs are solved from bat */
    tt__scontact *sc;
    uint32_t nsc, sccap;
    tt__record *rec;      /* the step's contacts, merged into the state's prev after it (the buffers swap) */
    uint32_t nrec, reccap;
    bool bounded;         /* the step about to run has room for all it can need: no undo (contacts_bound) */
    tt__collide_undo undo;
    tt__anchor_scratch anc; /* anchored friction this substep (contact_anchor.h) */
} tt__collide_scratch;

/* State: what contacts.c saves (settings, shapes, materials, bullets,
 * switched-off pairs, the last step's records and events, and the last
 * substep's end positions while valid). The rest is derived: the
 * primitives and static index (rebuilt while dirty), the sizing peaks, and
 * the bounds contact_skip.c, contact_reach.c and contact_undo.c keep with
 * the epoch they hold for (zero: none; a restored world starts without);
 * or per-step scratch (scr). */
typedef struct tt__collide {
    tt_collision_settings set;
    /* shapes */
    tt__pool spool;
    tt__shape *shapes;
    uint32_t shcap, shapes_alive;
    bool dirty;
    tt__prim *prims;
    uint32_t nprim, primcap;
    tt_vec2 *verts, *norms;
    uint32_t nvert, vertcap, normcap;
    tt__sgrid sgrid;
    uint32_t *pstamp, pstamp_cap, stamp; /* per primitive: dedupe while visiting several cells */
    uint32_t *sstamp, sstamp_cap, sstamp_id; /* per shape slot */
    uint32_t static_rebuilds;
    double bp_ms;         /* broadphase time of step bp_step (w->stats.steps while it runs), ms */
    uint64_t bp_step;
    bool any_moved;       /* some shape's moved flag is set */
    double *sx0, *sy0;    /* velocity integrators: position at the start of the substep (Verlet has x_old) */
    uint32_t scap, s_count;
    uint64_t s_epoch;     /* the world epoch at which sx0/sy0 hold the last substep's end positions */
    float *mat;           /* per slot: restitution, μs, μk (−1 = world default); NULL until used */
    uint32_t matcap;
    uint8_t *bullet;      /* NULL until used */
    uint32_t bulletcap, nbullets;
    int32_t *ccd_prim;    /* per slot: primitive hit by the sweep this substep, −1 none (bullets only) */
    tt__pair_set excl;    /* particle pairs the script switched off (one reference each), ordered: saved in order */
    uint32_t pair_peak, sc_peak; /* the most pairs and shape contacts a substep has had: reserve makes room for more */
    /* events: the last step's records (what the next step's begin, persist and end compare with) */
    tt__record *prev;
    uint32_t nprev, prevcap;
    tt_contact_event *events;
    uint32_t nevents, evcap;
    uint32_t rec_peak, ev_peak; /* the last step's records (before merging) and events: reserve makes room for more */
    uint32_t cells_used;
    /* contact_skip.c: after a probe found no two particles within reach + clear_gap, the relative
     * displacement since (clear_used) bounds how near they can have come */
    bool clear_ok, quiet_last;    /* quiet_last: the last substep had no contact */
    double clear_gap, clear_used, clear_scale;
    uint64_t clear_epoch;         /* the world epoch the bound holds for */
    uint32_t probe_wait, probe_fails;
    /* contact_skip.c, before the step: the bound holds through every substep of step step_at (stats.steps),
     * with clear_used = step_used after its last; no substep measures anything then */
    bool step_clear;
    uint64_t step_at;
    double step_used;
    uint8_t reach_side;   /* the side of the static shapes the particles last lay on (contact_reach.c) */
    float reach_rmax;     /* contact_reach.c: the largest radius, read at reach_epoch over reach_n particles */
    uint32_t reach_n;
    uint64_t reach_epoch;
    /* contact_undo.c: whether some radius is not zero (tt__grid_any_radius), read at radii_epoch over
     * radii_n particles */
    bool radii_any;
    uint32_t radii_n;
    uint64_t radii_epoch;
    struct tt__terrains *terr; /* terrains (terrain_internal.h); NULL until the world's first */
    tt__anchors anc;      /* anchored friction's anchors (empty unless set.anchored_friction) */
    tt__collide_scratch scr; /* what the substeps and the step work in: not state */
} tt__collide;

/* The contacts group's hook table and the collision state's accessor
 * (contacts.c). The table names every stage, so the files that make the
 * state (the public calls: collide.c, shapes.c, query.c, terrain_api.c)
 * sit above the stages; the stages and helpers find an existing state by
 * the group's id (tt__collide_peek), never through the table, so no file
 * the table uses depends on it back. */
#define TT__COLL_ID TT__ID('C', 'O', 'L', 'L') /* its snapshot section, and how its files find it */
extern const tt__group_ops tt__contacts_ops;
/* The collision state of w, made and registered on first use when create is true. */
tt__collide *tt__collide_get(tt_world *w, bool create, const char *fn);
/* The velocity pass's last part: touched pairs bottom-up along gravity, the
 * upper particle's speed away cut to what the pair allows (contact_lift.c). */
void tt__contacts_lift(tt_world *w, tt__collide *c, double thr);
/* Then each particle in a touched pair slowed to the largest pre-sweep speed
 * of itself and its touched partners (contact_cap.c). */
void tt__contacts_cap(tt_world *w, tt__collide *c);
/* The units that touched, into scr.touch (contact_touched.c); false on no memory (the step is undone). */
bool tt__contacts_touched(tt_world *w, tt__collide *c);

/* Moves particle i by (dx, dy) after the sweeps, its velocity with it. */
static inline void tt__contact_shift(tt_world *w, uint32_t i, double dx, double dy, double h)
{
    w->px[i] += dx;
    w->py[i] += dy;
    if (w->integrator != TT_VERLET) {
        w->qx[i] += dx / h;
        w->qy[i] += dy / h;
    }
}

/* Friction at the contact point of particles that turn (contact_roll.c):
 * particle a against particle b (UINT32_MAX: a shape or terrain moving at
 * (ux, uy) there), n from b to a, wa and wb the inverse-mass shares,
 * load the normal velocity change Coulomb's bound takes, m/s. */
struct tt__spin;
typedef struct tt__roll_contact {
    uint32_t a, b;
    double nx, ny, ux, uy, wa, wb, mus, muk, load;
    double acc; /* the velocity change given so far this substep (0 when listed) */
} tt__roll_contact;
/* Lists a contact for tt__roll_solve (room made by tt__roll_room). */
static inline void tt__roll_add(tt__collide *c, const tt__roll_contact *k) { c->scr.roll[c->scr.nroll++] = *k; }
/* Room for every contact the substep can list (the pair and shape contact
 * lists' room: it grows only when they grow, so a world at steady state
 * allocates nothing), none listed; false on no memory. */
bool tt__roll_room(tt__collide *c);
/* The listed contacts' friction, solved together in rounds. */
void tt__roll_solve(tt_world *w, tt__collide *c, struct tt__spin *sp, double h);
static inline tt__collide *tt__collide_peek(const tt_world *w)
{
    return (tt__collide *)tt__group_find_id(w, TT__COLL_ID);
}

/* Whether a substep has anything to detect (particle pairs on, a shape or
 * a terrain): the stages below prepare, detect and keep end positions only
 * then. State alone decides it, never which arrays an earlier step made. */
static inline bool tt__contacts_detect_any(const tt__collide *c)
{
    return c->set.particles || c->nprim || c->terr;
}

/* The stages of the contacts group (contacts.c registers them): detection
 * (contact_detect.c), projection and the velocity pass
 * (contact_response.c), events after the step (contact_events.c). */
bool tt__contacts_reserve(tt_world *w, void *self);
void tt__contacts_begin(tt_world *w, void *self, double h);
double tt__contacts_relax(tt_world *w, void *self, const tt__block *b);
uint32_t tt__contacts_units(const tt_world *w, const void *self);
bool tt__contacts_rows(const tt_world *w, const void *self);
/* One Gauss-Seidel sweep over pairs [k0, k1) of the substep, unbatched, on
 * positions L, each pair's radii sum times scale; returns the deepest
 * overlap it met (contact_response.c). */
double tt__pairs_sweep(tt_world *w, tt__collide *c, const tt__lay *L, uint32_t k0, uint32_t k1, double scale);
/* Pre-stabilisation: the overlap the substep starts with is undone on the
 * start positions and the predicted ones alike, so it makes no velocity
 * (contact_prestab.c). After detection, in begin. */
void tt__contacts_prestab(tt_world *w, tt__collide *c, uint32_t n);
/* Stacking (tt_collision_settings.stacking, contact_stack.c): the batches'
 * weights for the sweeps and the velocity pass, and which particles lean
 * on a shape. After pre-stabilisation, in begin. */
void tt__contacts_stack(tt_world *w, tt__collide *c);
/* Warm start (tt_collision_settings.warm_start, contact_warm.c): units
 * [u0, u1)' resting pairs pushed by a share of their last substep's normal
 * correction, on positions L; the largest push. In the first sweep, before
 * any pair's push. */
double tt__contacts_warm(tt_world *w, tt__collide *c, const tt__lay *L, uint32_t u0, uint32_t u1);
void tt__contacts_sweeps_done(tt_world *w, void *self);
void tt__contacts_end(tt_world *w, void *self, double h);
void tt__contacts_stopped(tt_world *w, void *self, uint32_t i);
void tt__contacts_after_step(tt_world *w, void *self);
size_t tt__contacts_memory(const tt_world *w, const void *self);
/* The step's undo (contact_undo.c; tt__group_ops), and the room for the
 * events after_step publishes (contact_events.c). contacts_bound, last in
 * contacts_reserve: room for every contact the step can make where that is
 * bounded and small, then nothing needs undoing (c->scr.bounded); never fails
 * the reserve (false only for the reserve's own failures, none here). */
bool tt__contacts_fallible(const tt_world *w, const void *self);
bool tt__contacts_bound(tt_world *w, tt__collide *c, uint32_t n);
bool tt__contacts_undo_reserve(tt_world *w, void *self);
void tt__contacts_undo_mark(tt_world *w, void *self);
void tt__contacts_undo(tt_world *w, void *self);
bool tt__contacts_after_reserve(tt_world *w, void *self);
void tt__contacts_destroy(tt_world *w, void *self);
/* Frees the per-step scratch (tt__group_ops.scratch_free). */
void tt__contacts_scratch_free(tt_world *w, void *self);
/* The group's section of the snapshot stream (contacts.c). */
void tt__contacts_save(const tt_world *w, const void *self, struct tt__sink *s);
void *tt__contacts_load(tt_world *w, struct tt__source *s);

/* Anchored friction (contact_anchor.c; the table's own calls in
 * contact_anchor.h): whether it applies this substep; each pair's anchor
 * (begin, after detection; h the substep); the touching pairs' anchors
 * into the table (keep, in end). */
bool tt__anchors_on(const tt_world *w, const tt__collide *c);
void tt__anchors_begin(tt_world *w, tt__collide *c, uint32_t n, double h);
void tt__anchors_keep(tt_world *w, tt__collide *c);

/* Keys of a step's contacts: a particle pair, or a shape and a particle
 * (bit 63 set, the shape slot in bits 32..62). */
static inline uint64_t tt__pair_key(uint32_t a, uint32_t b)
{
    /* the lower slot picked, the higher one its complement: no branch (which of a pair is the lower
     * goes either way pair after pair) */
    const uint32_t lo = a < b ? a : b, hi = a ^ b ^ lo;
    return ((uint64_t)lo << 32) | hi;
}
static inline uint64_t tt__shape_key(uint32_t shape, uint32_t a) { return (1ull << 63) | ((uint64_t)shape << 32) | a; }
/* Records one contact of the substep for the step's events (contact_events.c). */
void tt__record_contact(tt_world *w, tt__collide *c, uint64_t key, uint32_t a, uint32_t b, uint32_t shape, bool sensor,
                        double nx, double ny, double impulse);

/* Particle i's material k (0 restitution, 1 static friction, 2 kinetic):
 * its own where tt_particle_set_material gave one, else the world's. */
static inline double tt__mat(const tt__collide *c, uint32_t i, int k)
{
    if (c->mat && i < c->matcap && c->mat[3 * (size_t)i + k] >= 0.0f) return c->mat[3 * (size_t)i + k];
    return k == 0 ? c->set.restitution : k == 1 ? c->set.friction_static : c->set.friction_kinetic;
}
/* A particle pair's friction k (1 static, 2 kinetic): the geometric mean of the two. */
static inline double tt__pair_mu(const tt__collide *c, uint32_t a, uint32_t b, int k)
{
    return c->mat ? sqrt(tt__mat(c, a, k) * tt__mat(c, b, k)) : k == 1 ? c->set.friction_static : c->set.friction_kinetic;
}

/* Anchored friction's units (contact_anchor.c): the batch entries when the
 * substep batches its pairs (in their order, padding included), else the
 * pairs. */
static inline uint32_t tt__anc_units(const tt__collide *c) { return c->scr.batched ? c->scr.bat.n : c->scr.npairs; }
/* Unit k's particles and its normal correction so far; false for a batch's padding. */
static inline bool tt__anc_unit(const tt__collide *c, uint32_t k, uint32_t *a, uint32_t *b, double *lam)
{
    if (c->scr.batched) {
        *a = c->scr.bat.a[k], *b = c->scr.bat.b[k], *lam = c->scr.bat.lam[k];
        return *a < c->scr.bat.np;
    }
    *a = c->scr.pairs[k].a, *b = c->scr.pairs[k].b, *lam = c->scr.pairs[k].lambda;
    return true;
}

/* Filters: the one place that decides whether two particles may collide
 * (layers, two pinned, switched-off pairs, particles joined by a constraint
 * that does not let them collide; both sets of pairs are core/pair_set.h's). */
static inline bool tt__pair_filter(const tt_world *w, const tt__collide *c, uint32_t a, uint32_t b)
{
    if (!((w->category[a] & w->mask[b]) && (w->category[b] & w->mask[a]))) return false;
    if (w->inv_mass[a] == 0.0 && w->inv_mass[b] == 0.0) return false;
    if (c->excl.used && tt__pair_set_contains(&c->excl, a, b)) return false;
    if (tt__constraint_pair_excluded(w, a, b)) return false;
    return true;
}
static inline bool tt__shape_filter(const tt_world *w, const tt_shape_def *d, uint32_t a)
{
    return (w->category[a] & d->mask) && (d->category & w->mask[a]);
}

/* Grid (grid.c). Two particles within (r_a + r_b)·(1 + margin) make a pair:
 * its square's factor. */
#define TT__MARGIN2 ((1.0 + TT__CONTACT_MARGIN) * (1.0 + TT__CONTACT_MARGIN))
/* No particle (removed ones too: conservative), grown by the largest radius
 * and the margin, can reach a static primitive this substep. */
bool tt__shapes_out_of_reach(const tt_world *w, tt__collide *c, uint32_t n);
bool tt__grid_build(tt_world *w, tt__grid *g, double min_cell);
/* As tt__grid_build with cells wide times as wide (contact_skip.c's probe). */
bool tt__grid_build_wide(tt_world *w, tt__grid *g, double min_cell, double wide);
/* As tt__grid_build over the slots g->list[0..n) only, in that order. */
bool tt__grid_build_list(tt_world *w, tt__grid *g, double min_cell, uint32_t n);
/* The substep's pair grid and its pairs (grid_awake.c): over every particle,
 * or, while some sleep, over the awake ones and the sleepers within contact
 * reach of one; the same pair set either way. False on no memory. */
bool tt__grid_detect(tt_world *w, tt__collide *c);
/* After a build: whether two particles (filters aside) are nearer than their
 * contact reach plus gap, for gap up to the widening's extra width. */
bool tt__grid_any_near(const tt__grid *g, double gap);
/* Particle pairs on and none near for a while (contact_skip.c): whether
 * this substep provably has no pair (no grid built), should probe for that
 * (a grid twice as wide, tt__grid_any_near; the outcome told to
 * tt__pairs_probed: clear, and whether it bounds anything), or builds. */
typedef enum { TT__PAIRS_BUILD, TT__PAIRS_NONE, TT__PAIRS_PROBE } tt__pair_plan;
tt__pair_plan tt__pairs_skip(tt_world *w, tt__collide *c, uint32_t n);
void tt__pairs_probed(tt_world *w, tt__collide *c, bool clear, bool bound, double gap, double scale);
/* Before the step (contacts_reserve): whether the bound holds through the
 * whole step, read from the positions as it begins (c->step_clear). */
void tt__pairs_plan_step(tt_world *w, tt__collide *c, uint32_t n);
/* Whether no radius is above zero, as tt__grid_any_radius reads it, kept
 * per world epoch (contact_undo.c): no pair can be found then. */
bool tt__contacts_points_only(const tt_world *w, tt__collide *c, uint32_t n);
/* Whether some particle among the first n has a radius other than +0: a
 * pair needs one (two radius-0 particles never collide), so a world of
 * points skips its grid. About half an instruction a particle. */
bool tt__grid_any_radius(const tt_world *w, uint32_t n);
/* Room for a build over n particles, whatever their spread (the cells are
 * bounded by tt__grid_max_cells); false on no memory. */
bool tt__grid_reserve(tt__grid *g, uint32_t n);
uint32_t tt__grid_max_cells(uint32_t n);
/* Appends candidate pairs (gap < margin) to c->scr.pairs; false on no memory. */
bool tt__grid_pairs(tt_world *w, tt__collide *c);
void tt__grid_free(tt__grid *g);
size_t tt__grid_bytes(const tt__grid *g);
static inline int32_t tt__cell_coord(double v, double o, double inv)
{
    double f = (v - o) * inv;
    if (f >= 0.0 && f < 1e9) return (int32_t)f; /* truncation is floor here, and much cheaper */
    f = floor(f);
    if (f > 1e9) return 1000000000;
    if (!(f >= -1e9)) return -1000000000; /* NaN too: never converted */
    return (int32_t)f;
}
/* Brute force (broadphase_brute.c): the same candidate set, every pair tested. */
bool tt__brute_pairs(tt_world *w, tt__collide *c);

/* Shapes (shapes.c; their definitions: collide_defs.c; primitives, the
 * static index and the storage's memory: static_index.c). */
tt_result tt__shapes_rebuild(tt_world *w, tt__collide *c);
/* What tt_shape_create accepts (a snapshot's shapes pass the same test). */
tt_result tt__shape_check_def(const tt_world *w, const tt_shape_def *d, const char *fn);
/* A restitution in [0, 1] and frictions in [0, max_friction]: every
 * public call that takes a material checks it here (shapes and terrains up
 * to TT_MAX_VALUE, particles up to TT__PARTICLE_MAX_FRICTION). */
tt_result tt__material_check(const tt_world *w, double e, double fs, double fk, double max_friction, const char *fn);
/* tt_particle_set_material has always taken friction up to 1e30, more than
 * shapes take; the stream reader takes what the setter takes. */
#define TT__PARTICLE_MAX_FRICTION 1e30
/* Places the shapes the script moved where they are at the end of the
 * world's current substep, on their way from `from` to their def's
 * transform (the static index holds their whole path: no rebuild). */
void tt__shapes_place_moved(const tt_world *w, tt__collide *c);
/* After a step: the moved shapes have arrived. */
void tt__shapes_arrived(tt__collide *c);
void tt__shapes_free(tt__collide *c);
size_t tt__shapes_bytes(const tt__collide *c);
/* Calls visit for each primitive whose cell range meets the box (each at most once per call). */
typedef void (*tt__prim_visit)(void *ctx, uint32_t prim);
void tt__sgrid_query(tt__collide *c, double lox, double loy, double hix, double hiy, tt__prim_visit visit, void *ctx);
/* Whether some primitive's box meets the box: the cheap test before a
 * query (most particles, most steps, are near no shape). */
bool tt__sgrid_near(const tt__collide *c, double lox, double loy, double hix, double hiy);
bool tt__shape_ok(const tt__collide *c, tt_shape s);
/* Opens a public call on shape s of world w (shapes.c, shape_outline.c):
 * fails on a NULL world or a stale handle, else leaves c, the collision
 * state, and sh, the shape. */
#define TT__SHAPE_CHECK(fn)                                                                   \
    if (!w) return tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn);                       \
    tt__collide *c = tt__collide_peek(w);                                                     \
    if (!tt__shape_ok(c, s))                                                                  \
        return tt__fail(w, TT_ESTALE, "%s: stale shape handle (index %u, generation %u)", fn, s.index, s.gen); \
    tt__shape *sh = &c->shapes[s.index]

/* Narrowphase (narrowphase.c). depth > 0 is penetration; the nearest valid
 * position is (x, y) + n·depth. Always filled (depth may be negative). */
typedef struct tt__hit {
    double nx, ny, depth;
} tt__hit;
void tt__circle_vs_prim(const tt__collide *c, const tt__prim *p, double x, double y, double r, tt__hit *out);
/* Ray o + t·d, t in [0, tmax], against the primitive inflated by rr; the first t and the normal. */
bool tt__ray_vs_prim(const tt__collide *c, const tt__prim *p, double ox, double oy, double dx, double dy,
                     double rr, double tmax, double *t, double *nx, double *ny);
bool tt__ray_vs_circle(double ox, double oy, double dx, double dy, double cx, double cy, double r, double tmax,
                       double *t, double *nx, double *ny);
bool tt__prim_vs_aabb(const tt__collide *c, const tt__prim *p, double lox, double loy, double hix, double hiy);

/* Continuous detection (ccd.c): sweeps bullets from their start to their
 * position, stops them at the first static hit and records the contact. */
void tt__ccd(tt_world *w, tt__collide *c, double h);
/* Particle i swept as a circle from (x0, y0) to (x1, y1) against the static
 * shapes it does not touch at the start: the first primitive hit (−1: none),
 * at fraction *t of the way, with normal (*nx, *ny). */
int32_t tt__sweep_static(tt_world *w, tt__collide *c, uint32_t i, double x0, double y0, double x1, double y1,
                         double *t, double *nx, double *ny);

#endif
