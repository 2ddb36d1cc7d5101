/* tether — private declarations shared by the engine's source files. */
#ifndef TETHER_INTERNAL_H
#define TETHER_INTERNAL_H

#include "tether.h"
#include "pool.h"

#include <math.h>
#include <string.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#if defined(__GNUC__)
#define TT_UNLIKELY(x) __builtin_expect(!!(x), 0)
#define TT_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define TT_UNLIKELY(x) (x)
#define TT_PRINTF(a, b)
#endif

/* Particle flags. */
enum {
    TT__PF_ALIVE = 1u << 0,
    TT__PF_PINNED = 1u << 1,
    TT__PF_FRESH = 1u << 2, /* Verlet: velocity was set exactly; first step starts with a·dt²/2 */
    TT__PF_ASLEEP = 1u << 3 /* sleep.c: at rest, held as if pinned (inverse mass 0) until woken */
};

typedef struct tt__spring {
    uint32_t a, b;
    double rest, k, c;
    bool alive;
} tt__spring;

/* Scratch arrays, allocated the first time an integrator needs them. */
enum { TT_SCRATCH_AX, TT_SCRATCH_AY, TT_SCRATCH_RK4_FIRST, TT_SCRATCH_COUNT = TT_SCRATCH_RK4_FIRST + 8 };

/* A group of position constraints swept by the relaxation loop: the
 * constraints feature and the collision feature each register one (or more)
 * the first time a world uses them, so a world that uses neither pays nothing.
 * Groups are swept in rank order (deterministic). Only relax is
 * required. A group moves particles only through tt__correct (or, for
 * Gauss-Seidel only, its block's layout), so the same code serves
 * Gauss-Seidel and Jacobi. */
/* The order groups relax in, whatever order a script first used them in:
 * constraints, then contacts, so non-penetration has the last word in every
 * sweep (README "Solver order"). Ties (tests' own groups) keep their order. */
enum { TT__RANK_TEST = 0, TT__RANK_CONSTRAINTS = 10, TT__RANK_CONTACTS = 20 };

struct tt__sink;
struct tt__source;

/* The positions the sweeps work on, owned by the solver (solver.c):
 * particle i is at x[i·st], y[i·st], its inverse mass at im[i·st]. st = 4:
 * the solver's rows (simd.h: x, y, w, w per particle, and one more row of
 * zeros past the last particle for vector lanes that pad); st = 1: the
 * world's own px, py, inv_mass. Between the sweeps the world's arrays are
 * the truth; during them only this is. */
typedef struct tt__lay {
    double *x, *y;
    const double *im;
    size_t st;
} tt__lay;

/* One call of a group's relax: its units [u0, u1) (constraints, contact
 * batches...: what `units` counts), in their order, on the positions lay.
 * first: the substep's first sweep. */
typedef struct tt__block {
    double h;
    const tt__lay *lay;
    uint32_t u0, u1;
    bool first;
} tt__block;

typedef struct tt__group_ops {
    const char *name;
    int rank;             /* TT__RANK_*: groups run in increasing rank */
    tt_stage begin_stage; /* where begin's time is booked (TT_STAGE_COLLIDE for detection) */
    /* before a step changes anything: size what the step will need from the
     * world's counts, so running out of memory fails the step with the
     * world as it was; false on no memory */
    bool (*reserve)(tt_world *w, void *self);
    /* once per substep after integration, before the sweeps (detection, rest data) */
    /* relax may be NULL for a group without sweeps (sleep.c): the solve then runs as if it were absent */
    void (*begin)(tt_world *w, void *self, double h);
    /* Part of a sweep: units [b->u0, b->u1) of the group, moved on b->lay
     * only (reads through it, writes through tt__correct or it); returns
     * the largest error seen before correcting, m. The solver calls it for
     * consecutive blocks that together cover [0, units) once a sweep, in
     * order, so any split into blocks gives the same result bit for bit
     * (tests/core/test_blocks.c); a group keeps nothing per block. */
    double (*relax)(tt_world *w, void *self, const tt__block *b);
    /* optional: how many units a sweep relaxes (read once a sweep, after
     * begin); NULL: the group is one unit, relaxed in one call */
    uint32_t (*units)(const tt_world *w, const void *self);
    /* optional: set when the group reads and writes positions only through
     * the block's layout; true when its vector sweeps want the solver's
     * rows (st = 4) this step (asked before the step, to size them, and
     * before each substep's sweeps). The solver packs
     * rows only when every group with sweeps has this hook and one says
     * true. */
    bool (*rows)(const tt_world *w, const void *self);
    /* once per substep right after the last sweep, the world's arrays the
     * positions again */
    void (*sweeps_done)(tt_world *w, void *self);
    /* once per substep after the sweeps and the velocity fix-up (restitution, friction, breaking) */
    void (*end)(tt_world *w, void *self, double h);
    /* the guard stopped particle index after end (solver.c): what end took
     * from its position follows it to where it was stopped */
    void (*stopped)(tt_world *w, void *self, uint32_t index);
    /* after the whole step, outside every loop: gather events (booked as TT_STAGE_EVENTS) */
    void (*after_step)(tt_world *w, void *self);
    void (*particle_removed)(tt_world *w, void *self, uint32_t index); /* drop what refers to it */
    /* Snapshots (snapshot.c): the group's persistent state is its section
     * of the stream, id four ASCII letters (TT__ID). save writes it (and is
     * what the world hash covers); load reads it into a new self for w,
     * whose particles are already loaded, validating every field and
     * rebuilding what is derived, or returns NULL with the source failed.
     * Per-step scratch is neither saved nor hashed. A group without save
     * makes the world unsaveable (tests' own groups). */
    uint32_t id;
    void (*save)(const tt_world *w, const void *self, struct tt__sink *s);
    void *(*load)(tt_world *w, struct tt__source *src);
    /* optional: true while the group is as it was made, nothing set (a query
     * makes the collision state for its grid): it is then saved and hashed
     * as absent, which it is equivalent to, so reading a world never
     * changes its hash */
    bool (*idle)(const tt_world *w, const void *self);
    /* optional, per substep after begin: true when begin found nothing to
     * relax (no contact), so its sweeps, sweeps_done and end would move
     * nothing and change no world state; a Verlet substep whose groups are
     * all quiet skips them (tt__solve) */
    bool (*quiet)(const tt_world *w, const void *self);
    /* Out of memory inside a step (step_undo.c): the step stops and the
     * world goes back to where it began, so every group that changes state
     * in a step can put it back. fallible (optional): whether this step can
     * run out of memory in the group (the contacts' arrays follow the
     * contacts, which no count known before the step bounds); a world whose
     * groups all say no keeps no copy, and calls none of the others.
     * undo_reserve, before the step: room for the copies (false on no
     * memory). undo_mark, at the step's start: notes what undo needs (or
     * arms a copy taken at the first change, for changes most steps do not
     * make); undo puts the group as it was at undo_mark, allocating nothing.
     * after_reserve: room for what after_step writes, before any group's
     * after_step runs, so that no after_step can fail. */
    bool (*fallible)(const tt_world *w, const void *self);
    bool (*undo_reserve)(tt_world *w, void *self);
    void (*undo_mark)(tt_world *w, void *self);
    void (*undo)(tt_world *w, void *self);
    bool (*after_reserve)(tt_world *w, void *self);
    size_t (*memory)(const tt_world *w, const void *self);             /* bytes held */
    /* optional: frees the group's per-step scratch between two steps (the
     * next step's reserve sizes it again), changing nothing else: what the
     * test of the split (tests/core/test_scratch.c) drops */
    void (*scratch_free)(tt_world *w, void *self);
    void (*destroy)(tt_world *w, void *self);
} tt__group_ops;

typedef struct tt__group {
    const tt__group_ops *ops;
    void *self;
} tt__group;

enum { TT_MAX_GROUPS = 8 };

/* A replay journal recording a world (journal.c): the step calls it
 * through these, so that the world's code does not depend on the
 * journal's (which steps worlds to replay them). */
typedef struct tt__journal_hooks {
    void (*before)(tt_journal *j, tt_world *w);                 /* at a step's start, after its checks */
    void (*after)(tt_journal *j, const tt_world *w, double dt); /* at its end */
    void (*gone)(tt_journal *j);                                /* the world is being destroyed */
} tt__journal_hooks;

/* The step's undo (step_undo.c): what a step changes of the world, as it
 * was when the step began, so that running out of memory inside the step
 * can put the world back. Positions and velocity state are copied at the
 * step's start (only in a world where some group is fallible); flags and
 * inverse masses, which few steps change, at their first change. Not
 * state: never saved or hashed. */
typedef struct tt__undo {
    bool on;              /* this step keeps a copy (undo_mark ran) */
    bool flags_taken;     /* flags and inv_mass are copied */
    double *px, *py, *qx, *qy;
    uint16_t *flags;
    double *inv_mass;
    uint32_t cap;         /* slots in each array */
    tt_stats stats;
    double dt_prev;
    uint32_t fresh_count;
} tt__undo;

/* What a step works in, apart from the world's state: neither saved,
 * hashed nor restored (a restore keeps the world's own), sized before each
 * step from the world's counts and rewritten before it is read, so that
 * its loss between two steps (tt__world_scratch_free) changes nothing
 * (tests/core/test_scratch.c). Between steps undo.on is false. */
typedef struct tt__world_scratch {
    double *buf[TT_SCRATCH_COUNT]; /* integrators' arrays (tt__scratch) */
    uint32_t buf_cap[TT_SCRATCH_COUNT];
    double *jx, *jy;      /* Jacobi: summed corrections per particle (only while sweeping Jacobi) */
    uint32_t *jn;         /* Jacobi: how many corrections each particle got */
    uint32_t jcap;
    double *bx, *by;      /* positions before the sweeps: the velocity fix-up and the guard's fallback */
    uint32_t bcap;
    double *rows;         /* the sweeps' rows (tt__lay, st = 4): particles and the padding row */
    uint32_t rows_cap;
    tt__lay lay;          /* where positions are during the sweeps (tt__solve sets it) */
    uint64_t packs;       /* rows packed or unpacked since the world was made: what tests count */
    uint32_t *ends, ends_cap; /* integrate.c: the springs' ends, when few particles feel a force */
    const char *step_oom; /* what memory was refused inside the step (tt__step_oom), NULL: none */
    uint32_t substep;     /* the substep tt_world_step is in, 0…nsub − 1: groups' begin hooks read it */
    uint32_t nsub;        /* the substeps of the step being run: w->substeps, or more by travel.c */
    double step_h;        /* the substep length of the step being reserved and run (reserve hooks read it) */
    tt__undo undo;        /* the world as the step began (step_undo.c) */
} tt__world_scratch;

/* What of a world is state (saved, restored, hashed) and what is per-step
 * scratch (rebuilt) is decided in one place per part: snapshot.c's
 * save_settings/save_particles/save_springs for this struct, each group's
 * save hook for its own. A new persistent field is written there, or it
 * is not state. */
struct tt_world {
    /* settings */
    tt_vec2 gravity, wind;
    double damping;
    tt_integrator integrator;
    double dt_prev;       /* dt of the last step (dt_hint before the first): Verlet's x_old is x − v·dt_prev */
    uint32_t max_particles;
    uint32_t tag;         /* 1…255: the high byte of every handle generation this world hands out */
    double fixed_point;   /* 0, or the quantum every position is a multiple of (fixed_point.c) */

    /* particles: struct of arrays indexed by slot; a slot keeps its index for life */
    tt__pool ppool;
    uint32_t pcap;        /* slots allocated in each array */
    uint32_t alive;
    double *px, *py;      /* position */
    double *qx, *qy;      /* Verlet: previous position; every other integrator: velocity */
    double *inv_mass;     /* 0 when pinned or removed: the integrator and solvers skip it */
    double *mass;         /* kept while pinned */
    float *radius;
    uint16_t *flags, *category, *mask;
    /* optional arrays: NULL until a feature first needs them */
    double *fx, *fy;      /* force accumulator (apply_force) */
    bool forces_pending;  /* some force was applied since the last step */
    uint64_t *user;
    double *ox, *oy;      /* interpolation.c: positions as the last step began; NULL while not asked for */
    uint32_t *fresh;      /* Verlet particles whose velocity was set exactly since the last step */
    uint32_t fresh_count, fresh_cap;

    /* relaxation solver (solver.c) */
    uint32_t substeps, iterations;
    double max_travel;    /* travel.c: radii a particle may move in a substep; 0: off */
    uint32_t max_substeps;
    double tolerance;
    tt_solver_order order;
    uint32_t blocks;      /* debug: each group's sweep in this many blocks (0, 1: one); same results */
    tt__group groups[TT_MAX_GROUPS];
    int group_count;

    /* springs */
    tt__pool spool;
    tt__spring *springs;
    uint32_t scap, springs_alive;
    /* Removing a particle reaches its springs through this (set by
     * tt_world_create), so particles.c does not depend on springs.c. */
    void (*springs_detach)(tt_world *w, uint32_t particle);

    /* point attractors (attractor.c): a slot is in use while its strength is not 0 */
    tt_attractor attractors[TT_MAX_ATTRACTORS];
    uint32_t attractors_used; /* slots in use: the force loop skips them all at 0 */

    /* the journal recording this world (NULL: none, the usual case); not
     * state: a restore keeps it, and it is in no stream */
    tt_journal *journal;
    const tt__journal_hooks *journal_hooks;

    tt__world_scratch scr; /* the step's scratch, not state */

    tt_stats stats;
    uint64_t epoch;       /* bumped when particles appear, move or change radius outside a step, and by each step (query caches) */
    char error[256];
};

/* The step's scratch freed, the world's and every group's (their
 * scratch_free hooks): the next step sizes it again (world.c). */
void tt__world_scratch_free(tt_world *w);

/* A new world from a stream (snapshot.c), its epoch given: a world that is
 * to take another's place (tt__world_take) needs a later epoch than that
 * one's, set before its sections load (they key caches on it); NULL with
 * the reason in why. */
tt_world *tt__world_parse(const void *data, size_t size, uint64_t epoch, char *why, size_t whylen);
/* w becomes fresh (a world of its own, freed here), in place: w keeps its
 * address, its error message and its journal (snapshot.c). */
void tt__world_take(tt_world *w, tt_world *fresh);

/* Errors: set the message, return the code. */
tt_result tt__fail(const tt_world *w, tt_result code, const char *fmt, ...) TT_PRINTF(3, 4);
#define TT_CHECK_WORLD(w, fn) \
    do { if (!(w)) return tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn); } while (0)

static inline bool tt__finite(double x) { return x - x == 0.0; }
static inline bool tt__in_range(double x, double lo, double hi) { return x >= lo && x <= hi; }
static inline bool tt__vec_ok(tt_vec2 v) { return fabs(v.x) <= TT_MAX_VALUE && fabs(v.y) <= TT_MAX_VALUE; }
/* memcpy and memset through a NULL pointer are undefined even for 0 bytes,
 * and a world that never had particles has NULL arrays: every copy or
 * clear whose length is a particle count goes through these. */
static inline void tt__copy(void *dst, const void *src, size_t bytes)
{
    if (bytes) memcpy(dst, src, bytes);
}
static inline void tt__zero(void *dst, size_t bytes)
{
    if (bytes) memset(dst, 0, bytes);
}
/* a > b ? a : b and a < b ? a : b, the same bits (NaN and signed zeros
 * included: SSE2's maxsd and minsd are defined as these), without the
 * branch the compiler may make of the conditional: in the velocity passes
 * the comparisons go either way pair after pair, and a mispredicted branch
 * cost more than the arithmetic. */
static inline double tt__max(double a, double b)
{
#ifdef __SSE2__
    return _mm_cvtsd_f64(_mm_max_sd(_mm_set_sd(a), _mm_set_sd(b)));
#else
    return a > b ? a : b;
#endif
}
static inline double tt__min(double a, double b)
{
#ifdef __SSE2__
    return _mm_cvtsd_f64(_mm_min_sd(_mm_set_sd(a), _mm_set_sd(b)));
#else
    return a < b ? a : b;
#endif
}
/* c ? a : b, without a branch (as tt__max). */
static inline double tt__pick(bool c, double a, double b)
{
#ifdef __SSE2__
    const __m128d m = _mm_castsi128_pd(_mm_set1_epi64x(-(long long)c));
    return _mm_cvtsd_f64(_mm_or_pd(_mm_and_pd(m, _mm_set_sd(a)), _mm_andnot_pd(m, _mm_set_sd(b))));
#else
    return c ? a : b;
#endif
}
double tt__now_ms(void);
/* *p grown to hold need elements of elem bytes (doubling, at least 16):
 * false, and *p and *cap as they were, when memory runs out. */
bool tt__grow(void **p, uint32_t *cap, uint32_t need, size_t elem);

/* Particles. */
tt_result tt__particles_reserve(tt_world *w, uint32_t cap);
void tt__particles_free(tt_world *w);
bool tt__particle_ok(const tt_world *w, tt_particle p);
tt_result tt__particle_check(const tt_world *w, tt_particle p, const char *fn);
void tt__mark_fresh(tt_world *w, uint32_t i);
/* How many more particles the world can hold (free slots and room to grow). */
uint32_t tt__particle_room(const tt_world *w);
static inline tt_vec2 tt__velocity(const tt_world *w, uint32_t i)
{
    if (w->integrator == TT_VERLET)
        return (tt_vec2){(w->px[i] - w->qx[i]) / w->dt_prev, (w->py[i] - w->qy[i]) / w->dt_prev};
    return (tt_vec2){w->qx[i], w->qy[i]};
}
void tt__set_velocity(tt_world *w, uint32_t i, tt_vec2 v);
/* Velocity change Δv, as an impulse makes it (Verlet: x_old moves by Δv·dt_prev; no fresh start). */
static inline void tt__add_velocity(tt_world *w, uint32_t i, double dvx, double dvy)
{
    if (w->integrator == TT_VERLET) {
        w->qx[i] -= dvx * w->dt_prev;
        w->qy[i] -= dvy * w->dt_prev;
    } else {
        w->qx[i] += dvx;
        w->qy[i] += dvy;
    }
}
double *tt__scratch(tt_world *w, int which);
/* Step memory (integrate.c, solver.c): the arrays the step will use, sized
 * before it changes anything; false on no memory. */
bool tt__integrate_reserve(tt_world *w);
bool tt__solver_reserve(tt_world *w);
/* Memory refused inside a step: noted (the first says the most); the step
 * stops after the substep it is in and the world is put back as the step
 * began (step_undo.c), and tt_world_step returns TT_ENOMEM. */
void tt__step_oom(tt_world *w, const char *what);

/* The step's undo (step_undo.c). reserve: room for the copies, before the
 * step (false on no memory); mark: at the step's start; flags: before the
 * step's first change of a flag or an inverse mass (cheap when done);
 * after_reserve: the groups' after_reserve hooks; restore: the world as
 * the step began; free: its memory. */
bool tt__undo_reserve(tt_world *w);
void tt__undo_mark(tt_world *w);
void tt__undo_take_flags(tt_world *w);
static inline void tt__undo_flags(tt_world *w)
{
    if (TT_UNLIKELY(w->scr.undo.on && !w->scr.undo.flags_taken)) tt__undo_take_flags(w);
}
bool tt__undo_after_reserve(tt_world *w);
void tt__undo_restore(tt_world *w);
void tt__undo_free(tt_world *w);
size_t tt__undo_bytes(const tt_world *w);

/* Springs. */
void tt__springs_detach(tt_world *w, uint32_t particle);
double tt__springs_energy(const tt_world *w);
double tt__constraints_energy(const tt_world *w); /* constraint_access.c: Σ ½ C²/α over compliant constraints */
void tt__springs_free(tt_world *w);

/* Solver (solver.c). */
/* Registers a group; returns its slot or -1 when full. The world owns self
 * from then on (destroy is called with it). */
int tt__group_add(tt_world *w, const tt__group_ops *ops, void *self);
/* The group registered with ops, or NULL. */
void *tt__group_find(const tt_world *w, const tt__group_ops *ops);
/* Groups with sweeps (relax): a group without (sleeping's) moves no
 * particle, so the fast paths for "nothing else sweeps" ignore it. */
static inline int tt__groups_relaxing(const tt_world *w)
{
    int k = 0;
    for (int g = 0; g < w->group_count; g++) k += w->groups[g].ops->relax != NULL;
    return k;
}
/* Unregisters and destroys the group registered with ops, if any: a call
 * that registered it and then failed takes it back, since a group, even
 * empty, is swept and hashed. */
void tt__group_remove(tt_world *w, const tt__group_ops *ops);
/* The same by the group's section id (ops->id): a feature's files find
 * their group without naming its ops table, which names them all. */
void *tt__group_find_id(const tt_world *w, uint32_t id);
void tt__group_remove_id(tt_world *w, uint32_t id);
void tt__solve(tt_world *w, double h);
void tt__solver_after_step(tt_world *w);
void tt__solver_particle_removed(tt_world *w, uint32_t index);
size_t tt__solver_memory(const tt_world *w);
void tt__solver_free(tt_world *w);
/* Moves particle i by (dx, dy), weighted by the caller: in place under
 * Gauss-Seidel, accumulated for averaging under Jacobi. Pinned particles
 * (inverse mass 0) must not be passed a non-zero move. */
static inline void tt__correct(tt_world *w, uint32_t i, double dx, double dy)
{
    if (w->scr.jn && w->order == TT_JACOBI) {
        w->scr.jx[i] += dx;
        w->scr.jy[i] += dy;
        w->scr.jn[i]++;
    } else {
        const size_t at = i * w->scr.lay.st;
        w->scr.lay.x[at] += dx;
        w->scr.lay.y[at] += dy;
    }
}
/* Constraints (constraint_group.c): true when a constraint joining particle slots
 * a and b says they must not collide (O(1); the collision stage asks). */
bool tt__constraint_pair_excluded(const tt_world *w, uint32_t a, uint32_t b);
/* Whether any constraint keeps its particles from colliding (else the test above is always false). */
bool tt__constraint_pairs_any(const tt_world *w);

/* Sleeping (sleep.c). A world that never turns it on has no sleep group
 * and pays nothing. */
bool tt__sleep_enable(tt_world *w, double speed, double time); /* false on no memory */
void tt__sleep_disable(tt_world *w);                          /* wakes everything */
bool tt__sleep_get(const tt_world *w, double *speed, double *time); /* false: off */
uint32_t tt__sleep_count(const tt_world *w);
/* Wakes particle i's island if it sleeps: every call that changes a particle
 * calls it first (after its checks), so a sleeper never misses a change. */
void tt__sleep_touch(tt_world *w, uint32_t i);
/* Wakes every island with a sleeper whose circle meets the box: for what
 * changes a region (terrain carved, an explosion, a shape placed). */
void tt__sleep_wake_aabb(tt_world *w, double lox, double loy, double hix, double hiy);
/* Calls visit(ctx, a, j) for each particle a of list[0..n) that can move
 * (awake ones) and each sleeper j that may lie within (r_a + r_j)·f of it
 * (a superset, from the sleepers' grid: the caller tests); false on no
 * memory. */
bool tt__sleep_reach(tt_world *w, const uint32_t *list, uint32_t n, double f,
                     void (*visit)(void *ctx, uint32_t a, uint32_t j), void *ctx);
/* After a load: no particle sleeps in a world without the sleep section. */
bool tt__sleep_loaded_ok(const tt_world *w);

/* Geometry shared by the polygon shape and the lattice composite
 * (collide/collide_defs.c): the vertex at which pts[0..n) (n >= 3) stops being a
 * polygon's outline (a point repeated, three consecutive points on a line,
 * with `convex` a turn against the winding), or n when none does. */
uint32_t tt__polygon_fault(const tt_vec2 *pts, uint32_t n, bool convex);

/* Positions as the last step began, for drawing (interpolation.c): a
 * particle made or moved since then was where it is now. */
bool tt__interp_start(tt_world *w); /* false on no memory */
void tt__interp_step_begin(tt_world *w);
void tt__interp_stop(tt_world *w);
static inline void tt__interp_moved(tt_world *w, uint32_t i)
{
    if (!w->ox) return;
    w->ox[i] = w->px[i];
    w->oy[i] = w->py[i];
}

/* Fixed-point positions (fixed_point.c). The nearest multiple of q to v
 * (q a power of two, so v/q and m·q are exact). */
static inline double tt__fixed_snap(double q, double v) { return round(v / q) * q; }
bool tt__fixed_quantum_ok(double q);
/* travel.c: the substeps a step of dt runs (tt_world_def.max_travel); the
 * cap a world has unless told (tt_world_def.max_substeps 0 or unsaved). */
#define TT__MAX_SUBSTEPS_DEFAULT 8u
uint32_t tt__travel_substeps(tt_world *w, double dt);
/* Whether a shape or terrain lies within the box (collide/contact_reach.c; brings the static index up to date). */
bool tt__statics_within(tt_world *w, double lox, double loy, double hix, double hiy);
/* Whether a step can find contacts: particle contacts on, a shape or a terrain (travel.c). */
bool tt__world_collides(const tt_world *w);
double tt__fixed_range(const tt_world *w);                /* 2^51·q: the largest |coordinate| */
bool tt__fixed_in_range(const tt_world *w, tt_vec2 p);   /* true when off */
tt_vec2 tt__fixed_snap_vec(const tt_world *w, tt_vec2 p); /* p when off */
tt_result tt__fixed_check(const tt_world *w, tt_vec2 p, const char *fn);
void tt__fixed_after_solve(tt_world *w);
bool tt__fixed_loaded_ok(const tt_world *w);

/* Forces and integration (integrate.c / forces.c). */
bool tt__has_forces(const tt_world *w);
void tt__eval_accel(tt_world *w, const double *x, const double *y, const double *vx, const double *vy,
                    double *ax, double *ay);
/* The springs' share of tt__eval_accel, added into (ax, ay). */
void tt__springs_accel(const tt_world *w, const double *x, const double *y, const double *vx, const double *vy,
                       double *ax, double *ay);
void tt__integrate(tt_world *w, double dt);
/* Point attractors (attractor.c): add their pull at (x, y) to (ax, ay); their potential, J. */
void tt__attractors_accel(const tt_world *w, const double *x, const double *y, double *ax, double *ay);
double tt__attractors_energy(const tt_world *w);
void tt__convert_state(tt_world *w, tt_integrator from, tt_integrator to);

#endif
