/* tether — the step's undo: running out of memory inside a step fails the
 * step with the world as it was before it.
 *
 * Most of what a step needs is sized before it from the world's counts
 * (the groups' reserve hooks); what follows the number of contacts has no
 * such bound and may still have to grow inside the step. So a world where
 * that can happen (a group says it is fallible) keeps, for the step, what
 * the step changes: the particles' positions and velocity state copied at
 * its start (32 bytes a particle), their flags and inverse masses copied at
 * the first change (waking, a fresh velocity: most steps make none), the
 * counters, and each group's own (undo_mark / undo). Memory refused inside
 * the step (tt__step_oom) stops it after the substep it is in, and
 * tt__undo_restore puts everything back, allocating nothing. The copies
 * are per-step scratch: never saved or hashed. */
#include "internal.h"

#include <stdlib.h>

static bool fallible(const tt_world *w)
{
    for (int g = 0; g < w->group_count; g++) {
        const tt__group_ops *ops = w->groups[g].ops;
        if (ops->fallible && ops->fallible(w, w->groups[g].self)) return true;
    }
    return false;
}

static bool grow_arrays(tt__undo *u, uint32_t cap)
{
    if (u->cap >= cap) return true;
    double **d[] = {&u->px, &u->py, &u->qx, &u->qy, &u->inv_mass};
    for (size_t k = 0; k < sizeof d / sizeof d[0]; k++) {
        double *p = realloc(*d[k], (size_t)cap * sizeof *p);
        if (!p) return false;
        *d[k] = p;
    }
    uint16_t *f = realloc(u->flags, (size_t)cap * sizeof *f);
    if (!f) return false;
    u->flags = f;
    u->cap = cap;
    return true;
}

bool tt__undo_reserve(tt_world *w)
{
    tt__undo *u = &w->scr.undo;
    u->on = false;
    if (!fallible(w)) return true;
    if (!grow_arrays(u, w->pcap)) return false;
    for (int g = 0; g < w->group_count; g++) {
        const tt__group_ops *ops = w->groups[g].ops;
        if (ops->undo_reserve && !ops->undo_reserve(w, w->groups[g].self)) return false;
    }
    return true;
}

void tt__undo_mark(tt_world *w)
{
    tt__undo *u = &w->scr.undo;
    u->on = false;
    u->flags_taken = false;
    if (!fallible(w)) return; /* tt__undo_reserve made the room */
    const size_t n = (size_t)w->ppool.count * sizeof(double);
    tt__copy(u->px, w->px, n);
    tt__copy(u->py, w->py, n);
    tt__copy(u->qx, w->qx, n);
    tt__copy(u->qy, w->qy, n);
    u->stats = w->stats;
    u->dt_prev = w->dt_prev;
    u->fresh_count = w->fresh_count;
    u->on = true;
    if (w->fresh_count) tt__undo_take_flags(w); /* the integrator clears the fresh flags */
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->undo_mark) w->groups[g].ops->undo_mark(w, w->groups[g].self);
}

void tt__undo_take_flags(tt_world *w)
{
    tt__undo *u = &w->scr.undo;
    tt__copy(u->flags, w->flags, (size_t)w->ppool.count * sizeof *u->flags);
    tt__copy(u->inv_mass, w->inv_mass, (size_t)w->ppool.count * sizeof *u->inv_mass);
    u->flags_taken = true;
}

bool tt__undo_after_reserve(tt_world *w)
{
    for (int g = 0; g < w->group_count; g++) {
        const tt__group_ops *ops = w->groups[g].ops;
        if (ops->after_reserve && !ops->after_reserve(w, w->groups[g].self)) return false;
    }
    return true;
}

void tt__undo_restore(tt_world *w)
{
    tt__undo *u = &w->scr.undo;
    if (!u->on) return;
    const size_t n = (size_t)w->ppool.count * sizeof(double);
    tt__copy(w->px, u->px, n);
    tt__copy(w->py, u->py, n);
    tt__copy(w->qx, u->qx, n);
    tt__copy(w->qy, u->qy, n);
    if (u->flags_taken) {
        tt__copy(w->flags, u->flags, (size_t)w->ppool.count * sizeof *w->flags);
        tt__copy(w->inv_mass, u->inv_mass, n);
    }
    w->stats = u->stats;
    w->dt_prev = u->dt_prev;
    w->fresh_count = u->fresh_count;
    for (int g = w->group_count; g-- > 0;)
        if (w->groups[g].ops->undo) w->groups[g].ops->undo(w, w->groups[g].self);
    u->on = false;
}

void tt__undo_free(tt_world *w)
{
    tt__undo *u = &w->scr.undo;
    free(u->px); free(u->py); free(u->qx); free(u->qy);
    free(u->flags); free(u->inv_mass);
    *u = (tt__undo){0};
}

size_t tt__undo_bytes(const tt_world *w)
{
    return (size_t)w->scr.undo.cap * (5 * sizeof(double) + sizeof(uint16_t));
}
