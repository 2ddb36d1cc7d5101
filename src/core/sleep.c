/* tether — sleeping: particles at rest stop costing anything.
 *
 * Regions are islands: particles joined by contacts (the last substep's
 * particle pairs), springs and multi-particle constraints (distance, angle,
 * area, collinear), found by union-find. Pinned particles, shapes, pins and
 * bounds join nothing: they do not move, so they carry no motion from one
 * particle to another. An island falls asleep when every particle in it has
 * rested for sleep_time (sleep_rest.c: a window of sleep_speed·sleep_time
 * that a rattle stays in, a creep leaves slowly and a swing leaves
 * fast); it wakes whole. Islands
 * rather than grid cells: a cell boundary cuts a pile in two, and the awake
 * half would lean on a frozen half that ought to give way; an island is
 * everything that can push on everything else, so nothing in it is left
 * leaning on a sleeper (Box2D sleeps by islands for the same reason).
 *
 * A sleeping particle is stored as a pinned one is (inverse mass 0, its
 * velocity zero), flagged TT__PF_ASLEEP, its mass kept: the integrator, shape
 * detection and every relaxation sweep skip it, and the grid makes no pair
 * of two sleepers, with no test of their own in any of those loops. An
 * awake particle still meets a sleeper in the grid: that pair wakes the
 * sleeper's island at the end of the step (for that one step the sleeper
 * held like the ground). What the script does to a sleeping particle wakes
 * its island first; a shape the script moves wakes what lies along its
 * path before the step detects anything; tt__sleep_wake_aabb wakes a box
 * (terrain carving, explosions). Waking starts a particle from rest where it
 * slept: nothing jumps.
 *
 * The feature is a solver group without sweeps (rank after contacts): its
 * hooks are the step's, its section of the snapshot ('SLEP') holds the
 * settings, each particle's time at rest, anchor and island, so a restored world
 * falls asleep and wakes exactly as the original would. */
#include "internal.h"
#include "stream.h"
#include "collide/collide_internal.h"
#include "sleep_internal.h"
#include "constraints/constraint_internal.h"

#include <stdlib.h>

enum { TT__RANK_SLEEP = 15 }; /* begin before the contacts detect: woken particles are detected this substep */


static const tt__group_ops sleep_ops;

static tt__sleep *peek(const tt_world *w) { return (tt__sleep *)tt__group_find(w, &sleep_ops); }

static bool reserve(tt_world *w, void *self) { return tt__sleep_grow(self, w->ppool.count ? w->ppool.count : 1); }

static inline bool dynamic(const tt_world *w, uint32_t i)
{
    return (w->flags[i] & (TT__PF_ALIVE | TT__PF_PINNED)) == TT__PF_ALIVE;
}


static void wake_one(tt_world *w, tt__sleep *s, uint32_t i)
{
    if (w->scr.undo.on && !s->scr.undo.taken) tt__sleep_undo_take(w, s);
    s->island[i] = 0;
    s->rest[i] = s->held[i] = 0.0;
    s->ax[i] = s->mx[i] = w->px[i];
    s->ay[i] = s->my[i] = w->py[i];
    w->flags[i] &= (uint16_t)~TT__PF_ASLEEP;
    w->inv_mass[i] = 1.0 / w->mass[i];
    s->asleep--;
}

/* Wakes sleeper i's island: its ring of members, so the cost is the
 * island's, not the world's. The ring closes at i; a member no longer of
 * the island (none, while the rings hold) ends it too. */
static void wake_island(tt_world *w, tt__sleep *s, uint32_t i)
{
    const uint32_t k = s->island[i], n = tt__sleep_covered(w, s);
    for (uint32_t j = i; k && j < n && s->island[j] == k;) {
        const uint32_t next = s->ring[j];
        wake_one(w, s, j);
        j = next;
    }
}

/* Wakes the islands listed in s->wake. */
static void wake_listed(tt_world *w, tt__sleep *s)
{
    for (uint32_t k = 0; k < s->nwake; k++) wake_island(w, s, (uint32_t)s->wake[k]); /* one listed twice is awake by then */
    s->nwake = 0;
}

/* Lists sleeper i's island to wake; woken at once, alone, when the list
 * cannot grow. */
static void list_wake(tt_world *w, tt__sleep *s, uint32_t i)
{
    const uint64_t k = s->island[i];
    for (uint32_t j = 0; j < s->nwake && j < 8; j++)
        if (s->wake[s->nwake - 1 - j] >> 32 == k) return; /* the common repeat: the same island again */
    if (s->nwake == s->wake_cap && s->nwake) { /* full of repeats? each island once: no more than sleepers */
        qsort(s->wake, s->nwake, sizeof *s->wake, tt__sleep_cmp_u64);
        uint32_t m = 1;
        for (uint32_t j = 1; j < s->nwake; j++)
            if (s->wake[j] >> 32 != s->wake[m - 1] >> 32) s->wake[m++] = s->wake[j];
        s->nwake = m;
    }
    if (s->nwake == s->wake_cap) {
        uint32_t cap = s->wake_cap ? s->wake_cap * 2 : 16;
        uint64_t *p = realloc(s->wake, (size_t)cap * sizeof *p);
        if (!p) {
            wake_island(w, s, i);
            return;
        }
        s->wake = p;
        s->wake_cap = cap;
    }
    s->wake[s->nwake++] = k << 32 | i;
}

void tt__sleep_touch(tt_world *w, uint32_t i)
{
    if (!(w->flags[i] & TT__PF_ASLEEP)) return;
    tt__sleep *s = peek(w);
    if (s) wake_island(w, s, i);
}

typedef struct box_ctx {
    tt_world *w;
    tt__sleep *s;
    double lox, loy, hix, hiy;
} box_ctx;

static void wake_if_touching(void *ctx, uint32_t i)
{
    const box_ctx *b = ctx;
    const double r = b->w->radius[i], x = b->w->px[i], y = b->w->py[i];
    if (x + r >= b->lox && x - r <= b->hix && y + r >= b->loy && y - r <= b->hiy) list_wake(b->w, b->s, i);
}

/* The sleepers near the box come from the sleepers' grid (sleep_grid.c):
 * a box far from every sleeper costs a few cells, not a pass over the
 * world; without memory for the grid, the pass. */
void tt__sleep_wake_aabb(tt_world *w, double lox, double loy, double hix, double hiy)
{
    tt__sleep *s = peek(w);
    if (!s || s->asleep == 0) return;
    box_ctx b = {w, s, lox, loy, hix, hiy};
    if (!tt__sleep_grid_visit(w, s, lox, loy, hix, hiy, wake_if_touching, &b))
        for (uint32_t i = 0; i < tt__sleep_covered(w, s); i++)
            if (s->island[i]) wake_if_touching(&b, i);
    wake_listed(w, s);
}

bool tt__sleep_reach(tt_world *w, const uint32_t *list, uint32_t n, double f,
                     void (*visit)(void *ctx, uint32_t a, uint32_t j), void *ctx)
{
    tt__sleep *s = peek(w);
    return !s || s->asleep == 0 || tt__sleep_grid_reach(w, s, list, n, f, visit, ctx);
}

uint32_t tt__sleep_count(const tt_world *w)
{
    const tt__sleep *s = peek(w);
    return s ? s->asleep : 0;
}

/* The other features' state, read through the snapshot registry so that
 * this file names none of their symbols (they call tt__sleep_touch). */
/* Before the first substep detects anything: what a moved shape sweeps
 * over (its primitives' boxes hold the whole path then), and what a
 * constraint whose target the script moved drives, wake. */
static void begin(tt_world *w, void *self, double h)
{
    (void)h;
    tt__sleep *s = self;
    if (w->scr.substep != 0 || s->asleep == 0) return;
    const tt__collide *c = tt__collide_peek(w);
    if (c && c->any_moved)
        for (uint32_t k = 0; k < c->nprim; k++) {
            const tt__prim *p = &c->prims[k];
            if (c->shapes[p->shape].moved) tt__sleep_wake_aabb(w, p->lox, p->loy, p->hix, p->hiy);
        }
    const tt__cgroup *g = tt__cgroup_peek(w);
    for (uint32_t k = 0; g && k < g->nmoving; k++) {
        uint32_t ids[3];
        const uint32_t *list;
        uint32_t n = tt__sleep_constraint_parts(g, g->moving[k].slot, ids, &list);
        for (uint32_t j = 0; j < n; j++) tt__sleep_touch(w, list ? list[j] : ids[j]);
    }
}

/* The last substep's particle pairs between a sleeper and an awake
 * particle wake the sleeper's island. */
static void wake_touched(tt_world *w, tt__sleep *s)
{
    const tt__collide *c = tt__collide_peek(w);
    if (!c || s->asleep == 0) return;
    for (uint32_t k = 0; k < c->scr.npairs; k++) {
        uint32_t a = c->scr.pairs[k].a, b = c->scr.pairs[k].b;
        if (a >= w->ppool.count || b >= w->ppool.count) continue;
        uint32_t ia = s->island[a], ib = s->island[b];
        if (!ia == !ib) continue; /* both awake or both asleep */
        uint32_t other = ia ? b : a;
        if (!dynamic(w, other)) continue; /* a pinned particle wakes nothing */
        list_wake(w, s, ia ? a : b);
    }
    wake_listed(w, s);
}

static uint32_t find(uint32_t *parent, uint32_t i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

/* Joins the islands of a and b, the smaller root winning (deterministic);
 * sleepers, pinned and removed particles join nothing. */
static void unite(const tt_world *w, tt__sleep *s, uint32_t a, uint32_t b)
{
    if (a >= w->ppool.count || b >= w->ppool.count) return;
    if (!dynamic(w, a) || !dynamic(w, b) || s->island[a] || s->island[b]) return;
    uint32_t ra = find(s->parent, a), rb = find(s->parent, b);
    if (ra < rb) s->parent[rb] = ra;
    else if (rb < ra) s->parent[ra] = rb;
}

static void unite_all(const tt_world *w, tt__sleep *s)
{
    const tt__collide *c = tt__collide_peek(w);
    for (uint32_t k = 0; c && k < c->scr.npairs; k++) unite(w, s, c->scr.pairs[k].a, c->scr.pairs[k].b);
    for (uint32_t k = 0; k < w->spool.count; k++)
        if (w->springs[k].alive) unite(w, s, w->springs[k].a, w->springs[k].b);
    const tt__cgroup *g = tt__cgroup_peek(w);
    for (uint32_t k = 0; g && k < g->pool.count; k++) {
        if (!g->slots[k].kind) continue;
        uint32_t ids[3];
        const uint32_t *list;
        uint32_t n = tt__sleep_constraint_parts(g, k, ids, &list);
        for (uint32_t j = 1; j < n; j++) unite(w, s, list ? list[0] : ids[0], list ? list[j] : ids[j]);
    }
}

static void fall_asleep(tt_world *w, tt__sleep *s, uint32_t i, uint32_t island)
{
    s->island[i] = island;
    s->rest[i] = s->held[i] = 0.0;
    s->mx[i] = w->px[i]; /* where it sleeps: what a stream of a layout without it loads */
    s->my[i] = w->py[i];
    w->flags[i] |= TT__PF_ASLEEP;
    w->inv_mass[i] = 0.0;
    s->grid.built = false;
    if (w->integrator == TT_VERLET) {
        w->qx[i] = w->px[i];
        w->qy[i] = w->py[i];
    } else {
        w->qx[i] = w->qy[i] = 0.0;
    }
    s->asleep++;
}

/* Islands whose every particle rested long enough fall asleep. */
static void settle(tt_world *w, tt__sleep *s)
{
    const uint32_t n = w->ppool.count;
    for (uint32_t i = 0; i < n; i++) {
        s->parent[i] = i;
        s->minrest[i] = INFINITY;
    }
    unite_all(w, s);
    for (uint32_t i = 0; i < n; i++) {
        if (!dynamic(w, i) || s->island[i]) continue;
        uint32_t r = find(s->parent, i);
        const double rest = s->seen[i] == s->tick ? s->rest[i] : 0.0; /* nothing held it: in flight, not at rest */
        if (rest < s->minrest[r]) s->minrest[r] = rest;
    }
    /* island ids in slot order of their roots: the same world sleeps the same way */
    for (uint32_t i = 0; i < n; i++) {
        if (!dynamic(w, i) || s->island[i]) continue;
        uint32_t r = find(s->parent, i);
        if (!(s->minrest[r] >= s->time || s->minrest[r] < 0.0)) continue; /* < 0: its root's id, below */
        if (r == i) { /* roots come first in slot order: the smaller index wins every union */
            if (s->next_island == UINT32_MAX) s->next_island = 1;
            s->minrest[r] = -(double)s->next_island++; /* the root's id, kept where its time was */
        }
        fall_asleep(w, s, i, (uint32_t)-s->minrest[r]);
        s->ring[i] = r == i ? i : s->ring[r]; /* into the root's ring, after the root */
        s->ring[r] = i;
    }
}

/* Whether anything can hold a particle at rest: contacts, constraints or
 * springs. Without them a particle at rest is one in free flight with no
 * gravity, whose step costs what its rest test would: a plain world (on by
 * default) pays nothing for sleeping. */
static bool anything_holds(const tt_world *w)
{
    if (w->springs_alive) return true;
    for (int g = 0; g < w->group_count; g++) {
        const tt__group_ops *ops = w->groups[g].ops;
        if (ops->relax && !(ops->idle && ops->idle(w, w->groups[g].self))) return true;
    }
    return false; /* (a query's idle collision state holds nothing: reading a world keeps its hash) */
}

static void after_step(tt_world *w, void *self)
{
    tt__sleep *s = self;
    wake_touched(w, s);
    if (!anything_holds(w)) return;
    bool ready = false;
    tt__sleep_rest_held(w, s, w->dt_prev * w->scr.nsub, &ready);
    if (ready) settle(w, s);
}

static void particle_removed(tt_world *w, void *self, uint32_t i)
{
    tt__sleep *s = self;
    tt__sleep_touch(w, i); /* what rested on it falls */
    if (i < s->cap) s->rest[i] = s->held[i] = 0.0;
}

static size_t memory(const tt_world *w, const void *self)
{
    (void)w;
    const tt__sleep *s = self;
    return sizeof *s + (size_t)s->cap * (7 * sizeof(double) + sizeof(uint64_t) + 3 * sizeof(uint32_t)) + (size_t)s->wake_cap * sizeof(uint64_t) +
           (size_t)s->scr.undo.cap * (6 * sizeof(double) + sizeof(uint32_t)) +
           ((size_t)s->grid.cap_cells + s->grid.cap) * sizeof(uint32_t);
}

static const tt__group_ops sleep_ops = {
    .name = "sleep", .rank = TT__RANK_SLEEP,
    .begin_stage = TT_STAGE_COLLIDE,
    .reserve = reserve,
    .begin = begin,
    .after_step = after_step,
    .undo_reserve = tt__sleep_undo_reserve,
    .undo_mark = tt__sleep_undo_mark,
    .undo = tt__sleep_undo,
    .scratch_free = tt__sleep_scratch_free,
    .particle_removed = particle_removed,
    .id = TT__ID('S', 'L', 'E', 'P'),
    .save = tt__sleep_save,
    .load = tt__sleep_load,
    .memory = memory,
    .destroy = tt__sleep_destroy,
};

__attribute__((constructor)) static void register_feature(void) { tt__feature_register(&sleep_ops); }

bool tt__sleep_enable(tt_world *w, double speed, double time)
{
    tt__sleep *s = peek(w);
    if (!s) {
        s = calloc(1, sizeof *s);
        if (!s || !tt__sleep_grow(s, w->ppool.count ? w->ppool.count : 1) || tt__group_add(w, &sleep_ops, s) < 0) {
            tt__sleep_destroy(w, s);
            return false;
        }
        s->next_island = 1;
        s->tick = 2;
    }
    s->speed = speed;
    s->time = time;
    return true;
}

void tt__sleep_disable(tt_world *w)
{
    tt__sleep *s = peek(w);
    if (!s) return;
    for (uint32_t i = 0; i < tt__sleep_covered(w, s) && s->asleep; i++)
        if (s->island[i]) wake_one(w, s, i);
    tt__group_remove(w, &sleep_ops);
}

bool tt__sleep_get(const tt_world *w, double *speed, double *time)
{
    const tt__sleep *s = peek(w);
    if (s) *speed = s->speed, *time = s->time;
    return s != NULL;
}

bool tt__sleep_loaded_ok(const tt_world *w)
{
    if (peek(w)) return true;
    for (uint32_t i = 0; i < w->ppool.count; i++)
        if (w->flags[i] & TT__PF_ASLEEP) return false;
    return true;
}
