/* tether — the collision state's part of the step's undo (core/step_undo.c):
 * a step that runs out of memory for its contacts is put back as it began.
 * The particles are the world's to put back; what the step changes here
 * besides scratch is the end positions the velocity integrators start the
 * next substep from, and the bounds contact_skip.c and contact_reach.c keep
 * with the epoch they hold for. The contact records of the failed step are
 * dropped; the events published by the last step were not touched (that
 * happens after the step, which no longer fails then). */
#include "collide_internal.h"
#include "core/spin.h"

#include <stdlib.h>

/* Whether begin detects anything that may make the contact arrays grow
 * inside the step; contacts_bound reserved the rest. */
bool tt__contacts_fallible(const tt_world *w, const void *self)
{
    (void)w;
    const tt__collide *c = self;
    return (tt__contacts_detect_any(c) && !c->scr.bounded) || c->set.anchored_friction; /* the anchors change */
}

/* Whether no radius is above zero (its bits): then no pair can be found,
 * whatever the broadphase. Radii change only between steps and bump the
 * epoch (after_step carries the answer past the step's own bump), so the
 * scan runs once, not per substep. */
bool tt__contacts_points_only(const tt_world *w, tt__collide *c, uint32_t n)
{
    if (c->radii_epoch != w->epoch || c->radii_n != n) {
        c->radii_any = tt__grid_any_radius(w, n);
        c->radii_epoch = w->epoch;
        c->radii_n = n;
    }
    return !c->radii_any;
}

/* The step cannot run out of memory inside, so takes no copies (a world
 * whose contacts group only detects pays for the copies otherwise, 32
 * bytes a particle a step), when every buffer a substep may grow has its
 * room already:
 * - pairs: none can be found when pairs are off or every radius is zero
 *   (detect_pairs then builds no grid, probes nothing and plans no batch),
 *   nor in a step contact_skip.c's bound holds through (c->step_clear);
 * - shape contacts: the static index visits a primitive at most once per
 *   particle and query (its stamps), and detect_shapes queries once per
 *   particle a substep, so a substep makes at most n·nprim; room for that
 *   is made here while it is small (one primitive: 72 bytes a particle,
 *   address space the contacts write only where they occur, against the
 *   copies' 42 that are written every step);
 * - particles that turn list their contacts' friction (contact_roll.c):
 *   room for as many as the lists above have room for;
 * - the bottom-up pass (pairs on) grows to the pair list's room + 1, which
 *   cannot grow in such a step: it must have that room already; the
 *   velocity pass's list of touched pairs (contact_touched.c) grows only
 *   when there are pairs;
 * - events (records grow per contact), bullets' sweeps and terrains have no
 *   such bound: they keep the copies.
 * The other groups make room for all they can need before the step (the
 * constraints' break events; sleeping wakes without its list when that
 * cannot grow), and the events after the step need nrec + nprev = 0. */
bool tt__contacts_bound(tt_world *w, tt__collide *c, uint32_t n)
{
    c->scr.bounded = false;
    if (c->set.events || c->nbullets || c->terr || c->nprim > 1) return true;
    if (c->set.particles && (!(tt__contacts_points_only(w, c, n) || c->step_clear) || (c->nprim && c->scr.lift_cap <= c->scr.paircap)))
        return true;
    if (c->nprim && (!tt__grow((void **)&c->scr.sc, &c->scr.sccap, n ? n : 1, sizeof *c->scr.sc) ||
                     (tt__spin_peek(w) && !tt__roll_room(c))))
        return true; /* no room for all: the copies then, or the undo's own reserve fails the step */
    c->scr.bounded = true;
    return true;
}

static bool ends_valid(const tt_world *w, const tt__collide *c)
{
    return w->integrator != TT_VERLET && c->sx0 && c->s_epoch == w->epoch && c->s_count == w->ppool.count;
}

bool tt__contacts_undo_reserve(tt_world *w, void *self)
{
    tt__collide *c = self;
    tt__collide_undo *u = &c->scr.undo;
    if (!tt__anchors_room(&u->anc, c->anc.n)) return false;
    if (w->integrator == TT_VERLET || u->cap >= w->pcap) return true;
    double *x = realloc(u->sx0, (size_t)w->pcap * sizeof *x);
    if (!x) return false;
    u->sx0 = x;
    double *y = realloc(u->sy0, (size_t)w->pcap * sizeof *y);
    if (!y) return false;
    u->sy0 = y;
    u->cap = w->pcap;
    return true;
}

void tt__contacts_undo_mark(tt_world *w, void *self)
{
    tt__collide *c = self;
    tt__collide_undo *u = &c->scr.undo;
    u->ends = ends_valid(w, c) && u->cap >= c->s_count;
    if (u->ends) {
        tt__copy(u->sx0, c->sx0, (size_t)c->s_count * sizeof *u->sx0);
        tt__copy(u->sy0, c->sy0, (size_t)c->s_count * sizeof *u->sy0);
    }
    u->s_epoch = c->s_epoch;
    u->s_count = c->s_count;
    u->clear_ok = c->clear_ok;
    u->quiet_last = c->quiet_last;
    u->clear_gap = c->clear_gap;
    u->clear_used = c->clear_used;
    u->clear_scale = c->clear_scale;
    u->clear_epoch = c->clear_epoch;
    u->probe_wait = c->probe_wait;
    u->probe_fails = c->probe_fails;
    u->reach_side = c->reach_side;
    u->reach_rmax = c->reach_rmax;
    u->reach_n = c->reach_n;
    u->reach_epoch = c->reach_epoch;
    (void)tt__anchors_copy(&u->anc, &c->anc); /* reserve made the room */
}

void tt__contacts_undo(tt_world *w, void *self)
{
    (void)w;
    tt__collide *c = self;
    const tt__collide_undo *u = &c->scr.undo;
    if (u->ends) {
        tt__copy(c->sx0, u->sx0, (size_t)u->s_count * sizeof *c->sx0);
        tt__copy(c->sy0, u->sy0, (size_t)u->s_count * sizeof *c->sy0);
    }
    c->s_epoch = u->s_epoch;
    c->s_count = u->s_count;
    c->clear_ok = u->clear_ok;
    c->quiet_last = u->quiet_last;
    c->clear_gap = u->clear_gap;
    c->clear_used = u->clear_used;
    c->clear_scale = u->clear_scale;
    c->clear_epoch = u->clear_epoch;
    c->probe_wait = u->probe_wait;
    c->probe_fails = u->probe_fails;
    c->reach_side = u->reach_side;
    c->reach_rmax = u->reach_rmax;
    c->reach_n = u->reach_n;
    c->reach_epoch = u->reach_epoch;
    tt__anchors_restore(&c->anc, &u->anc);
    c->scr.nrec = 0;
    c->scr.npairs = 0; /* sleep.c reads the last substep's pairs after a step: this one's are gone */
    c->scr.nsc = 0;
    c->scr.grid.epoch = UINT64_MAX; /* built from the undone positions: a query builds its own */
    /* the moved shapes' primitives were placed along the path: the static
     * index is rebuilt for the whole path before the next step, as after a load */
    if (c->any_moved) c->dirty = true;
}
