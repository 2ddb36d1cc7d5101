/* tether — private storage of the constraints feature, and what its files
 * share: constraints.c (the group's hook table), constraint_group.c (its
 * storage, slots, removal, the pairs its links keep apart), constraint_create.c, constraint_access.c, constraint_relax.c (with the
 * targets the script moves), distance_sweep.c, constraint_breaks.c, constraint_hash.c (the snapshot section); composites.c
 * (handles, queries), composite_builder.c, composite_kinds.c. */
#ifndef TETHER_CONSTRAINT_INTERNAL_H
#define TETHER_CONSTRAINT_INTERNAL_H

#include "core/internal.h"
#include "core/pair_set.h"
#include "core/simd.h"
#include "core/stream.h" /* TT__ID */
#include "tether/composite.h"

/* Distance constraints, the hot loop: dense, swap-removed, 40 bytes each.
 * The allowed length is [lo, hi]: rigid lo = hi, max-only lo = 0, min-only hi = ∞. */
typedef struct tt__dist {
    uint32_t a, b;
    double lo, hi;
    double k;      /* stiffness, [0, 1] */
    double alpha;  /* compliance, m/N; > 0 = XPBD */
} tt__dist;

/* The cold half of a distance constraint, parallel to tt__dist. */
typedef struct tt__dist_x {
    double lambda;       /* XPBD multiplier, reset every substep */
    double rest;         /* the length given at creation */
    double break_strain; /* 0 = never */
    uint32_t slot;       /* handle slot */
    uint8_t mode;
    bool collide;
} tt__dist_x;

/* Every other kind: dense, swap-removed. */
typedef struct tt__gcon {
    uint8_t kind;
    bool outside;      /* bounds */
    uint32_t slot;
    uint32_t n;        /* particles (bounds: 0 = all) */
    uint32_t p[3];     /* pin: p[0]; angle, collinear: a, b, c */
    uint32_t *list;    /* bounds, area: n slot indices (owned) */
    double k, alpha, lambda;
    double v[4];       /* pin: anchor; bounds: min, max; angle: min, max; area: rest, pressure */
    double friction;   /* bounds */
} tt__gcon;

typedef struct tt__cslot {
    uint8_t kind;      /* 0: free */
    uint32_t dense;    /* index into dist or gen */
    uint32_t mover;    /* 1 + its index in the group's moving list; 0: its target is where the script put it */
    double max_rate;   /* distance, pin: m/s a length or anchor change proceeds at; 0 = no limit. Here, not in
                        * dist_x or gcon, which the sweeps stride through, so nothing they read grows */
} tt__cslot;

/* A constraint whose target (a length, an anchor) the script moved and the
 * solver has not reached yet: the effective target, which the sweeps use,
 * goes from `at` to `end` across the substeps of the next step, so the
 * particles it drives move smoothly instead of jumping in the first. */
typedef struct tt__mover {
    uint32_t slot;
    double at[2];      /* the effective target when the coming step starts */
    double to[2];      /* where the script put it (what the getters return) */
    double end[2];     /* where this step ends: `to`, or as far toward it as max_rate allows */
} tt__mover;

/* What a step changes of the group, as the step began (constraint_undo.c,
 * for the step's undo in core/step_undo.c): the moving targets, copied at
 * the step's start, and the links with everything a break changes, copied
 * at the step's first break (most steps break nothing). Scratch. */
typedef struct tt__cundo {
    bool broke;           /* the links are copied: a link broke in this step */
    uint32_t nnew, nmoving;
    tt__mover *moving;
    double *eff;          /* per moving target: its constraint's lo, hi (distance) or anchor (pin) */
    uint32_t moving_cap, eff_cap;
    tt__dist *dist;
    tt__dist_x *dx;
    tt__cslot *slots;
    uint32_t *gen, *free_list, *refs, *pair_n;
    uint64_t *pair_key;
    uint32_t dist_cap, dx_cap, slot_cap, gen_cap, free_cap, refs_cap, key_cap, n_cap; /* of each array */
    uint32_t ndist, nbreakable, nxpbd, alive, free_count, pair_used, pair_cap;
} tt__cundo;

typedef struct tt__composite {
    bool alive;
    uint32_t np, nc, ccap;
    tt_particle *parts;
    tt_constraint *cons;
    double *rest;      /* 2·np: rest offsets from the rest centre of mass */
} tt__composite;

/* What the sweeps and the step work in: neither saved nor hashed, and its
 * loss between two steps (tt__cgroup_scratch_free) changes nothing
 * (tests/core/test_scratch.c): the group's reserve sizes it again and the
 * plan is rebuilt while plan_ok is false. Between steps nnew is 0. */
typedef struct tt__cscratch {
    /* Gauss-Seidel vector plan: the links in order as pairs (scalar run
     * length, vector block count), each block plan_w consecutive links that
     * share no particle, so solving them side by side equals the sequential
     * loop bit for bit. Rebuilt on the next sweep after the a, b list changes. */
    uint32_t *plan, *stamp; /* stamp: per particle, 1 + the last link naming it (build scratch) */
    uint32_t nplan, plan_cap, plan_w, plan_np, stamp_cap; /* plan_np: 1 + the largest particle named */
    /* the plan's copy of the links' hot fields, one array each, by dense
     * index (setters keep it current); ra, rb: 4·a, 4·b (offsets in the solver's rows) */
    double *h_lo, *h_hi, *h_k, *h_alpha;
    uint32_t *h_ra, *h_rb;
    uint32_t hot_cap;
    bool plan_ok;
    double *grad;      /* gradients of an area constraint: room for the largest */
    uint32_t grad_cap;
    tt_break_event *ev_new; /* break events gathered during the step, published after it */
    uint32_t nnew, cap_new;
    tt__cundo undo;    /* the group as the step began (constraint_undo.c) */
} tt__cscratch;

/* State: what constraint_hash.c saves (pool, slots, links and their cold
 * halves but lambda, the other kinds, moving targets, published break
 * events, composites). Everything else here is derived (counts, refs,
 * excluded pairs) or per-step scratch (scr), rebuilt after a restore.
 * lambda (tt__dist_x, tt__gcon), the XPBD multiplier, is scratch too: begin
 * zeroes it every substep before a sweep reads it, and nothing else reads
 * it; it stays inside the links the sweeps stride through, which a
 * separate array would make them read twice over. */
typedef struct tt__cgroup {
    tt__pool pool;
    tt__cslot *slots;
    uint32_t slot_cap, alive;

    tt__dist *dist;
    tt__dist_x *dx;
    uint32_t ndist, dist_cap, dx_cap, nbreakable, nxpbd;

    tt__gcon *gen;
    uint32_t ngen, gen_cap;

    tt__pair_set pairs;   /* pairs joined by a link with collide = false, one reference per link */

    /* break events published by the last step (gathered in scr.ev_new) */
    tt_break_event *ev_pub;
    uint32_t npub, cap_pub;

    uint8_t simd;      /* tt__simd_mode */

    uint32_t *refs;    /* per particle slot: how many constraint entries name it (0: removal skips the scan) */
    uint32_t refs_cap;

    tt__mover *moving; /* only the constraints whose target moves: nothing else pays */
    uint32_t nmoving, moving_cap;

    tt__cscratch scr;  /* what the sweeps and the step work in: not state */

    /* composites (composites.c) */
    tt__pool cpool;
    tt__composite *comps;
    uint32_t comp_cap, comps_alive;
} tt__cgroup;

static const double TT_PI = 3.14159265358979323846;

/* ---- the group and its storage (constraint_group.c; made in constraints.c) -- */

#define TT__CONS_ID TT__ID('C', 'O', 'N', 'S') /* its snapshot section, and how its files find it */
extern const tt__group_ops tt__constraints_ops;
/* The group of w, or NULL: found by its id, so no part names the ops table. */
static inline tt__cgroup *tt__cgroup_find(const tt_world *w) { return w ? (tt__cgroup *)tt__group_find_id(w, TT__CONS_ID) : NULL; }
static inline const tt__cgroup *tt__cgroup_peek(const tt_world *w) { return tt__cgroup_find(w); }
/* The group of w, made and registered on first use (constraints.c; NULL on no memory). */
tt__cgroup *tt__cgroup_make(tt_world *w);
/* Takes the group back when the failing call that made it was its first use
 * (had: whether it was there before the call). */
void tt__cgroup_unmake(tt_world *w, bool had);
bool tt__cgroup_slot_new(tt__cgroup *g, uint8_t kind, uint32_t dense, uint32_t *out);
bool tt__cgroup_refs_reserve(const tt_world *w, tt__cgroup *g);
void tt__cgroup_gen_refs(tt__cgroup *g, const tt__gcon *c, int delta);
void tt__cgroup_dist_remove(tt__cgroup *g, uint32_t d);
void tt__cgroup_slot_remove(tt__cgroup *g, uint32_t s);
void tt__cgroup_particle_removed(tt_world *w, void *self, uint32_t index);
size_t tt__cgroup_memory(const tt_world *w, const void *self);
void tt__cgroup_scratch_free(tt_world *w, void *self);
bool tt__cgroup_grad_reserve(tt__cgroup *g); /* room for the largest area's gradients; false on no memory */
static inline tt_constraint tt__cgroup_handle(const tt__cgroup *g, uint32_t slot)
{
    return (tt_constraint){slot, g->pool.gen[slot]};
}
static inline tt_particle tt__cgroup_particle(const tt_world *w, uint32_t i) { return (tt_particle){i, w->ppool.gen[i]}; }

/* ---- checks the setters share with the creating calls (constraint_create.c) */
tt_result tt__constraint_check_compliance(const tt_world *w, double alpha, const char *fn);
tt_result tt__constraint_check_rate(const tt_world *w, double rate, const char *fn);
tt_result tt__constraint_check_box(const tt_world *w, tt_vec2 lo, tt_vec2 hi, const char *fn);

/* ---- geometry (constraint_relax.c, beside the sweeps that use it most) ----- */
static inline double tt__constraint_dist_of(const tt_world *w, uint32_t a, uint32_t b)
{
    double dx = w->px[b] - w->px[a], dy = w->py[b] - w->py[a];
    return sqrt(dx * dx + dy * dy);
}
/* The same on positions L (the sweeps'). */
static inline double tt__constraint_dist_on(const tt__lay *L, uint32_t a, uint32_t b)
{
    double dx = L->x[b * L->st] - L->x[a * L->st], dy = L->y[b * L->st] - L->y[a * L->st];
    return sqrt(dx * dx + dy * dy);
}
double tt__constraint_angle_at(const tt_world *w, uint32_t a, uint32_t b, uint32_t c);
double tt__constraint_angle_error(double th, double lo, double hi);
double tt__constraint_polygon_area(const tt__lay *L, const uint32_t *p, uint32_t n);
/* How far particle i at (x, y) is on the wrong side of bounds c; (*dx, *dy): the move that fixes it. */
double tt__constraint_bounds_violation(const tt_world *w, const tt__gcon *c, uint32_t i, double x, double y, double *dx, double *dy);

/* ---- the group's hooks (tt__group_ops), registered by constraints.c -------- */
void tt__cgroup_begin(tt_world *w, void *self, double h);                  /* constraint_relax.c */
double tt__cgroup_relax(tt_world *w, void *self, const tt__block *b);      /* constraint_relax.c */
uint32_t tt__cgroup_units(const tt_world *w, const void *self);             /* constraint_relax.c */
bool tt__cgroup_rows(const tt_world *w, const void *self);                  /* constraint_relax.c */
void tt__cgroup_end(tt_world *w, void *self, double h);                    /* constraint_relax.c */
void tt__cgroup_after_step(tt_world *w, void *self);                        /* constraint_breaks.c */
/* the group's section of the snapshot stream (constraint_hash.c) */
void tt__cgroup_save(const tt_world *w, const void *self, struct tt__sink *s);
void *tt__cgroup_load(tt_world *w, struct tt__source *s);
void tt__cgroup_destroy(tt_world *w, void *self); /* constraints.c */
bool tt__cgroup_reserve(tt_world *w, void *self);                           /* constraint_breaks.c */

/* ---- the distance links' sweep (distance_sweep.c) -------------------------- */
/* Sets w's mode; false (and no change) when this build or processor lacks it. */
bool tt__constraints_set_simd(tt_world *w, tt__simd_mode mode);
void tt__distance_hot_sync(tt__cgroup *g, uint32_t i);
bool tt__distance_plan_reserve(tt_world *w, tt__cgroup *g);
bool tt__distance_wants_rows(const tt_world *w, const tt__cgroup *g);
double tt__distance_sweep_gs(tt_world *w, tt__cgroup *g, const tt__block *b, uint32_t u0, uint32_t u1);
double tt__distance_sweep_jacobi(tt_world *w, tt__cgroup *g, const tt__block *b, uint32_t u0, uint32_t u1);

/* ---- targets the script moves (constraint_relax.c) ----------------------- */
/* Moves slot's target (a distance's length in to[0], a pin's anchor) to `to`
 * over the next step(s); false on no memory (nothing changed). */
bool tt__target_move(tt__cgroup *g, uint32_t slot, const double to[2]);
/* Once per substep from begin: sets every moving target's effective value. */
void tt__targets_substep(tt_world *w, tt__cgroup *g, double h);
/* The slot's constraint goes: forget its move. */
void tt__target_forget(tt__cgroup *g, uint32_t slot); /* constraint_group.c */

/* ---- the step's undo (constraint_undo.c) --------------------------------- */
bool tt__cgroup_undo_reserve(tt_world *w, void *self);
void tt__cgroup_undo_mark(tt_world *w, void *self);
void tt__cgroup_undo(tt_world *w, void *self);
/* Before the step's first break: the links as the step began. */
void tt__cgroup_undo_links(tt_world *w, tt__cgroup *g);
void tt__cgroup_undo_free(tt__cgroup *g);
size_t tt__cgroup_undo_bytes(const tt__cgroup *g);

/* ---- breaking (constraint_breaks.c) ---------------------------------------- */
void tt__cgroup_break_links(tt_world *w, tt__cgroup *g);

/* ---- composites' storage (constraint_group.c) ------------------------ */
/* Composite slots in use (the pool may count past the array after a failed grow). */
static inline uint32_t tt__comp_slots(const tt__cgroup *g) { return g->cpool.count < g->comp_cap ? g->cpool.count : g->comp_cap; }
void tt__composites_free(tt__cgroup *g);
size_t tt__composites_memory(const tt__cgroup *g);

/* ---- composites: the builder (composite_builder.c), used by composite_kinds.c */

/* A builder places every particle first and checks them all (and that they
 * fit) before it makes the first, so bad input changes nothing. Running out
 * of memory half way is undone whole: what was made is removed and the pools
 * are put back, so the next handles are those of a world that never saw the
 * call. */
typedef struct tt__spot {
    tt_vec2 at;
    bool pinned;
} tt__spot;

typedef struct tt__builder {
    tt_world *w;
    const char *fn;
    tt__composite c;
    tt_composite_common k;
    tt__spot *spots;        /* where each particle goes, in order */
    uint32_t nspots;
    /* the world before its first change, for undo */
    tt__pool_mark pmark, cmark;
    uint32_t fresh_count;
    uint64_t epoch;         /* particles made and removed moved it on: caches keyed by it would be stale */
    bool had_group;         /* the constraint group was there before */
    bool failed;
} tt__builder;

bool tt__builder_begin(tt__builder *b, tt_world *w, const tt_composite_common *k, uint32_t particles, const char *fn);
void tt__builder_place(tt__builder *b, double x, double y, bool pinned);
bool tt__builder_spawn(tt__builder *b);
bool tt__builder_con_room(tt__builder *b);
void tt__builder_add_constraint(tt__builder *b, tt_constraint h);
void tt__builder_link(tt__builder *b, uint32_t i, uint32_t j, double stiffness, tt_distance_mode mode, double break_strain);
void tt__builder_limit(tt__builder *b, uint32_t i, uint32_t j, uint32_t k, double lo, double hi, double stiffness);
tt_composite tt__builder_finish(tt__builder *b);

#endif
