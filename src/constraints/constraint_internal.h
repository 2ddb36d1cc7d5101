/* tether — private storage of the constraints feature, shared by
 * constraints.c (storage, API, relaxation) and composites.c. */
#ifndef TETHER_CONSTRAINT_INTERNAL_H
#define TETHER_CONSTRAINT_INTERNAL_H

#include "core/internal.h"
#include "core/simd.h"
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
} tt__cslot;

typedef struct tt__composite {
    bool alive;
    uint32_t np, nc, ccap;
    tt_particle *parts;
    tt_constraint *cons;
    double *rest;      /* 2·np: rest offsets from the rest centre of mass */
} tt__composite;

typedef struct tt__cgroup {
    tt_pool pool;
    tt__cslot *slots;
    uint32_t slot_cap, alive;

    tt__dist *dist;
    tt__dist_x *dx;
    uint32_t ndist, dist_cap, dx_cap, nbreakable, nxpbd;

    tt__gcon *gen;
    uint32_t ngen, gen_cap;

    /* pairs (min, max) that must not collide, with how many constraints say so */
    uint64_t *pair_key;
    uint32_t *pair_n;
    uint32_t pair_cap, pair_used;

    /* break events: gathered during the step, published after it */
    tt_break_event *ev_new, *ev_pub;
    uint32_t nnew, npub, cap_new, cap_pub;

    /* Gauss-Seidel vector plan: the links in order as pairs (scalar run
     * length, vector block count), each block plan_w consecutive links that
     * share no particle, so solving them side by side equals the sequential
     * loop bit for bit. Rebuilt on the next sweep after the a, b list changes. */
    uint32_t *plan, *stamp; /* stamp: per particle, 1 + the last link naming it (build scratch) */
    uint32_t nplan, plan_cap, plan_w, plan_np, stamp_cap; /* plan_np: 1 + the largest particle named */
    double *pk;        /* the vector sweep's copy of x, y, inverse mass: 4 doubles per particle */
    uint32_t pk_cap;   /* particles */
    /* the plan's copy of the links' hot fields, one array each, by dense
     * index (setters keep it current); ra, rb: 4·a, 4·b (row offsets in pk) */
    double *h_lo, *h_hi, *h_k, *h_alpha;
    uint32_t *h_ra, *h_rb;
    uint32_t hot_cap;
    bool plan_ok;
    bool pk_live;      /* pk holds the positions, w->px/py are stale until sweeps_done */
    bool first_sweep;  /* the substep's first: linked particles on one spot part (group_begin sets it) */
    uint8_t simd;      /* tt__simd_mode */

    uint32_t *refs;    /* per particle slot: how many constraint entries name it (0: removal skips the scan) */
    uint32_t refs_cap;

    double *grad;      /* scratch gradients for area constraints */
    uint32_t grad_cap;

    /* composites (composites.c) */
    tt_pool cpool;
    tt__composite *comps;
    uint32_t comp_cap, comps_alive;
} tt__cgroup;

/* Sets w's mode; false (and no change) when this build or processor lacks it. */
bool tt__constraints_set_simd(tt_world *w, tt__simd_mode mode);

/* The group of w, made and registered on first use when create is true (NULL on no memory). */
tt__cgroup *tt__cgroup_get(tt_world *w, bool create);
const tt__cgroup *tt__cgroup_peek(const tt_world *w);
/* Takes the group back when the failing call that made it was its first use
 * (had: whether it was there before the call). */
void tt__cgroup_unmake(tt_world *w, bool had);
void tt__composites_free(tt__cgroup *g);
size_t tt__composites_memory(const tt__cgroup *g);
uint64_t tt__composites_hash(const tt__cgroup *g, uint64_t h);

#endif
