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

/* The rest test, on the particle's position smoothed over
 * TT__SLEEP_SMOOTH_TIME (each step of dt it moves dt/TT__SLEEP_SMOOTH_TIME of the way to the
 * particle, all of it in a step that long: an oscillator stepped at
 * ω·dt = 2.8, six steps a period, is a motion, not a jitter). A
 * particle rests while that stays within a window of
 * L = sleep_speed·sleep_time of its anchor (where its present stretch
 * began); when it leaves, the anchor moves there, and the stretch it ends
 * keeps its rest if its mean speed over it was under sleep_speed (so it
 * lasted sleep_time or more; one long step that jumps far does not), else
 * its rest starts again. Measured (README "Sleeping"), this tells the kinds
 * of slow motion apart:
 * - a rattle (a loose particle in the cavity of a settled pile, 0.1–0.5
 *   m/s) stays inside a cage of 1 cm for ever: it rests, where a test on
 *   the last step's speed keeps the pile awake for ever;
 * - a jitter (a jammed particle of a settled pile that the sweeps push up
 *   to 2 cm one way and back the next step, for ever: 7–31 of the
 *   reference pour's 10 000 from 25 to 60 s since the speed cap, on the
 *   starts measured) left the window every step, and the pile never slept;
 *   smoothed, it moves a seventh as far;
 * - creep (the deep pile compacting, 0.2 mm/s after 50 s) leaves any window
 *   in the end, but slowly: its stretches are long and keep their rest,
 *   where restarting the rest on each exit kept a few of 10 000 particles
 *   resting less than sleep_time at any moment, and the pile awake;
 * - a swing dwells near a turning point within a window L for only about
 *   2·sqrt(2L/a) (a its acceleration there), then leaves it in a stretch
 *   shorter than sleep_time: it never rests long. With the defaults (1 cm,
 *   1 s) a 1 m pendulum swinging 2 cm or more, a 4 m one swinging 5 cm, a
 *   particle at the top of its throw or a ball rolling at 1 cm/s or more
 *   stay awake; a swing whose whole arc fits in the window is at rest.
 * Smoothing over a few steps, not over sleep_time: an anchor that only
 * followed the particle smoothed over sleep_time trailed a slide from rest
 * at 1.5 sleep_speed by less than L for 1.1 s (τ·ln 3), and it slept
 * (tests/core/test_sleep.c).
 * A particle that turns (tt_world_def.spin) with its rim faster than
 * sleep_speed does not rest where it stands: asleep, its angle would stop
 * while it still reported its spin. */
static void rest_one(tt_world *w, tt__sleep *s, uint32_t i, double dt, bool *ready)
{
    if (i >= w->ppool.count || s->seen[i] == s->tick) return; /* (made since the last step: none of its arrays) */
    const uint64_t was = s->seen[i];
    s->seen[i] = s->tick;
    if (w->inv_mass[i] == 0.0) return; /* asleep, pinned or removed */
    if (was + 1 != s->tick) { /* free since it was last held: its rest starts here */
        s->rest[i] = s->held[i] = 0.0;
        s->ax[i] = s->mx[i] = w->px[i];
        s->ay[i] = s->my[i] = w->py[i];
        return;
    }
    const double f = dt < TT__SLEEP_SMOOTH_TIME ? dt / TT__SLEEP_SMOOTH_TIME : 1.0;
    const double mx = s->mx[i] += f * (w->px[i] - s->mx[i]);
    const double my = s->my[i] += f * (w->py[i] - s->my[i]);
    const double dx = mx - s->ax[i], dy = my - s->ay[i], d2 = dx * dx + dy * dy;
    const double lim = s->speed * s->time;
    const bool out = d2 > lim * lim;
    const tt__spin *sp = s->scr.spin;
    const bool turning = sp && i < sp->cap && fabs(sp->omega[i]) * w->radius[i] > s->speed;
    s->held[i] += dt;
    const double slow = s->speed * s->held[i]; /* out at a mean speed under sleep_speed: its stretch lasted sleep_time or more */
    if (!turning && (!out || d2 <= slow * slow)) {
        s->rest[i] += dt;
        *ready |= s->rest[i] >= s->time;
    } else {
        s->rest[i] = 0.0;
    }
    if (out) {
        s->held[i] = 0.0;
        s->ax[i] = mx;
        s->ay[i] = my;
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
