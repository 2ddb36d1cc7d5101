/* tether — sleeping's rest test (sleep.c has the islands and waking): each
 * step, every particle something held in the step is tested, once.
 *
 * The holders are the last substep's contacts (pairs, shapes, terrain),
 * which change every step, and the springs and constraints, which do not:
 * a cloth's 97 000 links hold its 16 000 particles, and walking the links
 * every step to find them cost a falling cloth more than a third of its
 * step. So the particles springs and constraints hold are listed once, and
 * listed again only after a spring or constraint slot was made or freed
 * (the pools count those changes: a removal, a break, a failed call's
 * rollback, a step's undo). Bounds hold every particle of theirs, or every
 * particle, which changes as particles come and go: they are walked each
 * step (past 8 of them, everything is walked each step). Which particle
 * is tested first changes nothing: each test reads and writes that
 * particle's own state alone. What holds what is here too: sleep.c joins
 * its islands by the same holders. */
#include "internal.h"
#include "sleep_internal.h"
#include "spin.h"
#include "collide/collide_internal.h"
#include "constraints/constraint_internal.h"

/* The particles of constraint slot s of g (distance, angle, area,
 * collinear; pins and bounds hold to the world, not to a particle): fills
 * out (up to 3, or the area's list) and returns how many. */
uint32_t tt__sleep_constraint_parts(const tt__cgroup *g, uint32_t slot, uint32_t out[3], const uint32_t **list)
{
    const tt__cslot *cs = &g->slots[slot];
    *list = NULL;
    if (cs->kind == TT_CONSTRAINT_DISTANCE) {
        out[0] = g->dist[cs->dense].a;
        out[1] = g->dist[cs->dense].b;
        return 2;
    }
    const tt__gcon *c = &g->gen[cs->dense];
    if (c->kind == TT_CONSTRAINT_ANGLE || c->kind == TT_CONSTRAINT_COLLINEAR) {
        out[0] = c->p[0], out[1] = c->p[1], out[2] = c->p[2];
        return 3;
    }
    if (c->kind == TT_CONSTRAINT_AREA) {
        *list = c->list;
        return c->n;
    }
    if (c->kind == TT_CONSTRAINT_PIN) { /* a moving pin drags its particle: wakes it, joins nothing */
        out[0] = c->p[0];
        return 1;
    }
    return 0;
}

/* The rest test. Each particle's anchor follows it, smoothed: every step
 * it moves dt/sleep_time of the way to the particle (an exponential mean
 * over about sleep_time); the particle rests while it stays within a window
 * of L = sleep_speed·sleep_time of that anchor, and when it leaves, the
 * anchor is dragged after it to the window's edge and its rest starts
 * again. Measured (README "Sleeping"), this tells the kinds of slow motion
 * apart:
 * - a particle drifting at a steady u trails its anchor by u·sleep_time: it
 *   rests when u is under sleep_speed, so creep (a deep pile compacting,
 *   0.2 mm/s after 50 s) rests, and a ball rolling at 1 cm/s or more does
 *   not;
 * - a rattle (a loose particle in the cavity of a settled pile, 0.1–0.5
 *   m/s in a cage of 1 cm) and a jitter (a jammed particle that the sweeps
 *   push one way and back the next step, up to 1.9 cm, 10–14 of the
 *   reference pour's 10 000 for ever since the speed cap) keep the anchor
 *   near their middle: they rest while they stay within L of it;
 * - a swing leaves the window around its smoothed centre unless its
 *   amplitude is under about L: a 1 m pendulum swinging 2 cm, a 4 m one
 *   swinging 5 cm, a particle at the top of its throw, a ball rolling from
 *   rest down a 1° slope never stay in it for sleep_time.
 * An anchor set where a stretch began (the test before this one) let a
 * jitter over 1 cm leave it every step: the reference pour never slept.
 * A particle that turns (tt_world_def.spin) with its rim faster than
 * sleep_speed does not rest where it stands: asleep, its angle would stop
 * while it still reported its spin. held counts the time since the anchor
 * was last dragged or set. */
static void rest_one(tt_world *w, tt__sleep *s, uint32_t i, double dt, bool *ready)
{
    if (i >= w->ppool.count || s->seen[i] == s->tick) return; /* (made since the last step: none of its arrays) */
    const uint64_t was = s->seen[i];
    s->seen[i] = s->tick;
    if (w->inv_mass[i] == 0.0) return; /* asleep, pinned or removed */
    const double x = w->px[i], y = w->py[i];
    if (was + 1 != s->tick) { /* free since it was last held: its rest starts here */
        s->rest[i] = s->held[i] = 0.0;
        s->ax[i] = x;
        s->ay[i] = y;
        return;
    }
    const double lim = s->speed * s->time, f = dt < s->time ? dt / s->time : 1.0;
    const double ex = s->ax[i] + f * (x - s->ax[i]), ey = s->ay[i] + f * (y - s->ay[i]);
    const double dx = x - ex, dy = y - ey, d2 = dx * dx + dy * dy;
    const tt__spin *sp = s->scr.spin;
    const bool turning = sp && i < sp->cap && fabs(sp->omega[i]) * w->radius[i] > s->speed;
    s->held[i] += dt;
    if (d2 > lim * lim) { /* left the window: the anchor dragged to its edge */
        const double k = lim / sqrt(d2);
        s->ax[i] = x - dx * k;
        s->ay[i] = y - dy * k;
        s->rest[i] = s->held[i] = 0.0;
        return;
    }
    s->ax[i] = ex;
    s->ay[i] = ey;
    if (turning) {
        s->rest[i] = 0.0;
    } else {
        s->rest[i] += dt;
        *ready |= s->rest[i] >= s->time;
    }
}

/* Tests i if nothing did this step; true when it did (i is then listed). */
static bool rest_new(tt_world *w, tt__sleep *s, uint32_t i, double dt, bool *ready)
{
    if (i >= w->ppool.count || s->seen[i] == s->tick) return false;
    rest_one(w, s, i, dt, ready);
    return true;
}

static bool holders_valid(const tt_world *w, const tt__sleep *s, const tt__cgroup *g)
{
    return s->holders.ok && s->holders.group == (const void *)g && s->holders.spring_changes == w->spool.changes &&
           (!g || s->holders.cons_changes == g->pool.changes);
}

static void list_new(tt_world *w, tt__sleep *s, uint32_t i, double dt, bool *ready, bool *keep)
{
    if (!rest_new(w, s, i, dt, ready)) return;
    if (s->holders.list && s->holders.n < s->cap) s->holders.list[s->holders.n++] = i;
    else *keep = false;
}

/* Bounds slot k holds every particle of its list, or every particle. */
static void bounds_one(tt_world *w, tt__sleep *s, const tt__cgroup *g, uint32_t k, double dt, bool *ready)
{
    const tt__gcon *b = &g->gen[g->slots[k].dense];
    const uint32_t n = b->n ? b->n : w->ppool.count;
    for (uint32_t j = 0; j < n; j++) rest_new(w, s, b->n ? b->list[j] : j, dt, ready);
}

/* Tests what the springs and constraints hold, walking them, and lists it
 * (the list's room is the per-slot arrays', made before the step: every
 * particle at most once). Too many bounds to keep: no list. */
static void holders_walk(tt_world *w, tt__sleep *s, const tt__cgroup *g, double dt, bool *ready)
{
    s->holders.n = s->holders.nbounds = 0;
    bool keep = true;
    for (uint32_t k = 0; k < w->spool.count; k++)
        if (w->springs[k].alive) list_new(w, s, w->springs[k].a, dt, ready, &keep), list_new(w, s, w->springs[k].b, dt, ready, &keep);
    for (uint32_t k = 0; g && k < g->pool.count; k++) {
        if (!g->slots[k].kind) continue;
        const tt__gcon *b = g->slots[k].kind == TT_CONSTRAINT_DISTANCE ? NULL : &g->gen[g->slots[k].dense];
        if (b && b->kind == TT_CONSTRAINT_BOUNDS) {
            if (s->holders.nbounds < sizeof s->holders.bounds / sizeof s->holders.bounds[0]) {
                s->holders.bounds[s->holders.nbounds++] = k; /* tested below, with the listed ones */
            } else {
                keep = false;
                bounds_one(w, s, g, k, dt, ready);
            }
            continue;
        }
        uint32_t ids[3];
        const uint32_t *list;
        uint32_t n = tt__sleep_constraint_parts(g, k, ids, &list);
        for (uint32_t j = 0; j < n; j++) list_new(w, s, list ? list[j] : ids[j], dt, ready, &keep);
    }
    s->holders.group = g;
    s->holders.spring_changes = w->spool.changes;
    s->holders.cons_changes = g ? g->pool.changes : 0;
    s->holders.ok = keep;
}


/* Only what something holds can rest: a free particle under gravity never
 * does, and testing it would make one spring elsewhere cost a pass over
 * every particle (the pay-only table). */
void tt__sleep_rest_held(tt_world *w, tt__sleep *s, double dt, bool *ready)
{
    s->tick++;
    s->scr.spin = tt__spin_peek(w);
    const tt__cgroup *g = tt__cgroup_peek(w);
    if (holders_valid(w, s, g)) {
        for (uint32_t k = 0; k < s->holders.n; k++) rest_new(w, s, s->holders.list[k], dt, ready);
    } else {
        holders_walk(w, s, g, dt, ready);
    }
    for (uint32_t k = 0; k < s->holders.nbounds; k++) bounds_one(w, s, g, s->holders.bounds[k], dt, ready);
    const tt__collide *c = tt__collide_peek(w);
    for (uint32_t k = 0; c && k < c->scr.npairs; k++) {
        rest_new(w, s, c->scr.pairs[k].a, dt, ready);
        rest_new(w, s, c->scr.pairs[k].b, dt, ready);
    }
    for (uint32_t k = 0; c && k < c->scr.nsc; k++) rest_new(w, s, c->scr.sc[k].a, dt, ready);
}
