/* tether — sleeping's part of the step's undo (step_undo.c): a step that
 * runs out of memory is put back as it began; here only a waking in its first substep changes anything before
 * that can happen (falling asleep comes after the step, which no longer
 * fails then), so the copy is taken at the first waking. */
#include "sleep_internal.h"

#include <stdlib.h>

bool tt__sleep_undo_reserve(tt_world *w, void *self)
{
    (void)w;
    tt__sleep *s = self;
    if (s->undo.cap >= s->cap) return true;
    double **d[] = {&s->undo.rest, &s->undo.held, &s->undo.ax, &s->undo.ay};
    for (int k = 0; k < 4; k++) {
        double *p = realloc(*d[k], (size_t)s->cap * sizeof *p);
        if (!p) return false;
        *d[k] = p;
    }
    uint32_t *p = realloc(s->undo.island, (size_t)s->cap * sizeof *p);
    if (!p) return false;
    s->undo.island = p;
    s->undo.cap = s->cap;
    return true;
}

void tt__sleep_undo_mark(tt_world *w, void *self)
{
    (void)w;
    tt__sleep *s = self;
    s->undo.taken = false;
    s->undo.asleep = s->asleep;
}

void tt__sleep_undo_take(tt_world *w, tt__sleep *s)
{
    const size_t n = tt__sleep_covered(w, s) < s->undo.cap ? tt__sleep_covered(w, s) : s->undo.cap;
    tt__undo_flags(w);
    tt__copy(s->undo.rest, s->rest, n * sizeof *s->rest);
    tt__copy(s->undo.held, s->held, n * sizeof *s->held);
    tt__copy(s->undo.ax, s->ax, n * sizeof *s->ax);
    tt__copy(s->undo.ay, s->ay, n * sizeof *s->ay);
    tt__copy(s->undo.island, s->island, n * sizeof *s->island);
    s->undo.taken = true;
}

void tt__sleep_undo(tt_world *w, void *self)
{
    tt__sleep *s = self;
    s->asleep = s->undo.asleep;
    s->nwake = 0;
    s->grid.built = false; /* who sleeps may be back as it was */
    if (!s->undo.taken) return;
    const size_t n = tt__sleep_covered(w, s) < s->undo.cap ? tt__sleep_covered(w, s) : s->undo.cap;
    tt__copy(s->rest, s->undo.rest, n * sizeof *s->rest);
    tt__copy(s->held, s->undo.held, n * sizeof *s->held);
    tt__copy(s->ax, s->undo.ax, n * sizeof *s->ax);
    tt__copy(s->ay, s->undo.ay, n * sizeof *s->ay);
    tt__copy(s->island, s->undo.island, n * sizeof *s->island);
    s->undo.taken = false;
}

