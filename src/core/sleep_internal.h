/* tether — sleeping's state, shared by sleep.c (the feature) and
 * sleep_undo.c (its part of the step's undo). */
#ifndef TT_SLEEP_INTERNAL_H
#define TT_SLEEP_INTERNAL_H

#include "internal.h"

/* The rest test's smoothing (sleep_rest.c): each step of dt the smoothed
 * position moves f = dt/TT__SLEEP_SMOOTH_TIME of the way to the particle
 * (all of it in steps that long or longer), a quarter at 60 Hz, so a jitter
 * that goes one way and back the next step moves it a seventh as far
 * (f/(2 − f)), while a swing, slow beside a step, is left nearly as it is
 * (computed on its path over 20 s: a 4 m pendulum swinging 5 cm stays in
 * the window at most 0.98 s at a time, smoothed or not; 1 m and 10 m ones
 * within 0.05 s of that too). The reference pour, sleeping on, as built and
 * jittered by 0.05 m (seeds 1-5): asleep within 35-55 s on all six at a
 * quarter a step, on three of six by 60 s at a half. */
#define TT__SLEEP_SMOOTH_TIME (1.0 / 15.0) /* s: a motion of a few steps at 60 Hz, not a few steps of any length */

/* Where the sleepers lie (sleep_grid.c): built at the first query after
 * one fell asleep; a counting sort of the sleepers' slots by cell. */
typedef struct tt__sleep_grid {
    bool built;
    uint32_t m;           /* sleepers listed */
    double ox, oy, inv, rmax;
    double hx, hy;        /* the sleepers' centres lie in [ox, hx] × [oy, hy] */
    int32_t nx, ny;
    uint32_t *start, *idx;
    uint32_t cap_cells, cap;
} tt__sleep_grid;

/* What the step works in: neither saved nor hashed, and its loss between
 * two steps (tt__sleep_scratch_free) changes nothing
 * (tests/core/test_scratch.c): the step's undo reserve sizes it again, and
 * the undo mark sets its flags before the step reads them. */
typedef struct tt__sleep_scratch {
    /* the step's undo (step_undo.c): the per-slot state as the step began,
     * copied at the step's first waking */
    struct {
        bool taken;
        uint32_t asleep, cap;
        double *rest, *held, *ax, *ay, *mx, *my;
        uint32_t *island;
    } undo;
    const struct tt__spin *spin; /* the rest pass's: particles that turn (NULL: they do not), set as it begins */
} tt__sleep_scratch;

typedef struct tt__sleep {
    double speed, time;   /* m/s: the mean speed under which a particle rests; s at rest before its island sleeps */
    uint32_t next_island; /* ids are never reused while anything sleeps under them */
    uint32_t asleep;
    uint32_t cap;
    double *rest;         /* per slot: seconds at rest (awake particles) */
    double *held;         /* per slot: seconds since its anchor was set (awake particles) */
    double *ax, *ay;      /* per slot: its anchor, where its present stretch began (awake particles) */
    double *mx, *my;      /* per slot: its position smoothed over TT__SLEEP_SMOOTH_TIME, what the rest test reads (awake particles) */
    uint32_t *island;     /* per slot: 0 awake, else the island it sleeps in */
    uint32_t *ring;       /* per slot: the next sleeper of its island, round to the first (sleepers only) */
    uint64_t *seen;       /* per slot: the last step (tick) something held it: a contact, spring or constraint */
    uint64_t tick;        /* steps since sleeping went on, from 2 (0 in seen: never held) */
    uint32_t *parent;     /* union-find scratch */
    double *minrest;      /* per root: the least time at rest in its island */
    uint64_t *wake;       /* islands to wake at the end of the step: (island << 32) | one sleeper of it */
    uint32_t nwake, wake_cap;
    /* The particles springs and constraints hold (bounds aside), each once:
     * scratch, rebuilt when a spring or constraint slot was made or freed
     * since (sleep_rest.c). */
    struct {
        uint32_t *list, n;         /* cap: the per-slot arrays' */
        uint32_t bounds[8], nbounds; /* the bounds constraints' slots, walked each step */
        const void *group;         /* the constraint group it was made from */
        uint64_t cons_changes, spring_changes;
        bool ok;
    } holders;
    tt__sleep_grid grid;
    tt__sleep_scratch scr; /* what the step works in: not state */
} tt__sleep;

/* Slots the arrays cover: particles made since the last step lie past
 * them, and none of those sleeps. */
static inline uint32_t tt__sleep_covered(const tt_world *w, const tt__sleep *s)
{
    return w->ppool.count < s->cap ? w->ppool.count : s->cap;
}

struct tt__cgroup;
/* The particles of constraint slot s of g that it holds (sleep_rest.c): fills
 * out (up to 3, or *list for an area) and returns how many. */
uint32_t tt__sleep_constraint_parts(const struct tt__cgroup *g, uint32_t slot, uint32_t out[3], const uint32_t **list);
/* The rest test of every particle something held in the last step; *ready
 * when one has rested sleep_time (sleep_rest.c). */
void tt__sleep_rest_held(tt_world *w, tt__sleep *s, double dt, bool *ready);
/* The arrays grown to cover n slots; the state freed (sleep_state.c). */
bool tt__sleep_grow(tt__sleep *s, uint32_t n);
/* Each island's sleepers linked into its ring, from the islands alone (a
 * loaded state); false on no memory (sleep_state.c). */
bool tt__sleep_link_rings(const tt_world *w, tt__sleep *s);
/* qsort's order of uint64_t keys (sleep_state.c). */
int tt__sleep_cmp_u64(const void *a, const void *b);
void tt__sleep_destroy(tt_world *w, void *self);
/* Its section of the snapshot (sleep_stream.c). */
void tt__sleep_save(const tt_world *w, const void *self, struct tt__sink *snk);
void *tt__sleep_load(tt_world *w, struct tt__source *src);

/* Calls visit(ctx, i) for each sleeper i whose cell lies within its largest
 * radius of the box (a superset of those touching it, each once); false,
 * having visited none, when the grid cannot be built (no memory). */
bool tt__sleep_grid_visit(const tt_world *w, tt__sleep *s, double lox, double loy, double hix, double hiy,
                          void (*visit)(void *ctx, uint32_t i), void *ctx);

/* Calls visit(ctx, a, j) for each awake particle a of list[0..n) that can
 * move and each sleeper j whose cell lies within (r_a + r_j)·f of it (a
 * superset of those nearer than that); false on no memory. */
bool tt__sleep_grid_reach(const tt_world *w, tt__sleep *s, const uint32_t *list, uint32_t n, double f,
                          void (*visit)(void *ctx, uint32_t a, uint32_t j), void *ctx);

/* The step's undo hooks (sleep_undo.c). */
bool tt__sleep_undo_reserve(tt_world *w, void *self);
void tt__sleep_undo_mark(tt_world *w, void *self);
void tt__sleep_undo(tt_world *w, void *self);
/* Copies the per-slot state before the step's first waking changes it. */
void tt__sleep_undo_take(tt_world *w, tt__sleep *s);
/* Frees the step's scratch (tt__group_ops.scratch_free). */
void tt__sleep_scratch_free(tt_world *w, void *self);

#endif
