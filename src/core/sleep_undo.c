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
    if (s->scr.undo.cap >= s->cap) return true;
    double **d[] = {&s->scr.undo.rest, &s->scr.undo.held, &s->scr.undo.ax, &s->scr.undo.ay, &s->scr.undo.mx, &s->scr.undo.my};
    for (int k = 0; k < 6; k++) {
        double *p = realloc(*d[k], (size_t)s->cap * sizeof *p);
        if (!p) return false;
        *d[k] = p;
    }
    uint32_t *p = realloc(s->scr.undo.island, (size_t)s->cap * sizeof *p);
    if (!p) return false;
    s->scr.undo.island = p;
    s->scr.undo.cap = s->cap;
    return true;
}

void tt__sleep_undo_mark(tt_world *w, void *self)
{
    (void)w;
    tt__sleep *s = self;
    s->scr.undo.taken = false;
    s->scr.undo.asleep = s->asleep;
}

void tt__sleep_undo_take(tt_world *w, tt__sleep *s)
{
    const size_t n = tt__sleep_covered(w, s) < s->scr.undo.cap ? tt__sleep_covered(w, s) : s->scr.undo.cap;
    tt__undo_flags(w);
    tt__copy(s->scr.undo.rest, s->rest, n * sizeof *s->rest);
    tt__copy(s->scr.undo.held, s->held, n * sizeof *s->held);
    tt__copy(s->scr.undo.ax, s->ax, n * sizeof *s->ax);
    tt__copy(s->scr.undo.ay, s->ay, n * sizeof *s->ay);
    tt__copy(s->scr.undo.mx, s->mx, n * sizeof *s->mx);
    tt__copy(s->scr.undo.my, s->my, n * sizeof *s->my);
    tt__copy(s->scr.undo.island, s->island, n * sizeof *s->island);
    s->scr.undo.taken = true;
}

void tt__sleep_undo(tt_world *w, void *self)
{
    tt__sleep *s = self;
    s->asleep = s->scr.undo.asleep;
    s->nwake = 0;
    s->grid.built = false; /* who sleeps may be back as it was */
    if (!s->scr.undo.taken) return;
    const size_t n = tt__sleep_covered(w, s) < s->scr.undo.cap ? tt__sleep_covered(w, s) : s->scr.undo.cap;
    tt__copy(s->rest, s->scr.undo.rest, n * sizeof *s->rest);
    tt__copy(s->held, s->scr.undo.held, n * sizeof *s->held);
    tt__copy(s->ax, s->scr.undo.ax, n * sizeof *s->ax);
    tt__copy(s->ay, s->scr.undo.ay, n * sizeof *s->ay);
    tt__copy(s->mx, s->scr.undo.mx, n * sizeof *s->mx);
    tt__copy(s->my, s->scr.undo.my, n * sizeof *s->my);
    tt__copy(s->island, s->scr.undo.island, n * sizeof *s->island);
    s->scr.undo.taken = false;
}


void tt__sleep_scratch_free(tt_world *w, void *self)
{
    (void)w;
    tt__sleep *s = self;
    free(s->scr.undo.rest); free(s->scr.undo.held); free(s->scr.undo.ax); free(s->scr.undo.ay); free(s->scr.undo.mx); free(s->scr.undo.my); free(s->scr.undo.island);
    s->scr = (tt__sleep_scratch){0};
}
