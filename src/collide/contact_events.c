/* tether — contact events: each contact of a step recorded as it is
 * solved, merged per pair after the step and compared with the previous
 * step's set, giving BEGIN, PERSIST and END events as arrays. */
#include "collide_internal.h"
#include "terrain_internal.h"

#include <stdlib.h>
#include <string.h>

void tt__record_contact(tt_world *w, tt__collide *c, uint64_t key, uint32_t a, uint32_t b, uint32_t shape, bool sensor,
                        double nx, double ny, double impulse)
{
    if (!tt__grow((void **)&c->scr.rec, &c->scr.reccap, c->scr.nrec + 1, sizeof *c->scr.rec)) {
        tt__step_oom(w, "contact events");
        return;
    }
    tt__record *r = &c->scr.rec[c->scr.nrec++];
    memset(r, 0, sizeof *r);
    r->key = key;
    r->ev.sensor = sensor;
    r->ev.a = (tt_particle){a, w->ppool.gen[a]};
    if (b != UINT32_MAX) r->ev.b = (tt_particle){b, w->ppool.gen[b]};
    if (shape != UINT32_MAX && tt__prim_is_terrain(shape)) r->ev.terrain = tt__terrain_handle(c, shape);
    else if (shape != UINT32_MAX) r->ev.shape = (tt_shape){shape, c->spool.gen[shape]};
    double ra = w->radius[a];
    r->ev.point = (tt_vec2){w->px[a] - nx * ra, w->py[a] - ny * ra};
    r->ev.normal = (tt_vec2){nx, ny};
    r->ev.impulse = impulse;
}

/* --- events after the step ------------------------------------------------ */

static int cmp_record(const void *x, const void *y)
{
    const tt__record *a = x, *b = y;
    if (a->key != b->key) return a->key < b->key ? -1 : 1;
    return a < b ? -1 : a > b; /* never equal pointers; keeps the order of the substeps */
}

static void push_event(tt_world *w, tt__collide *c, const tt_contact_event *ev, uint32_t kind)
{
    if (!(c->set.events & kind)) return;
    if (!tt__grow((void **)&c->events, &c->evcap, c->nevents + 1, sizeof *c->events)) {
        tt__step_oom(w, "contact events"); /* after_reserve made the room: never here */
        return;
    }
    c->events[c->nevents] = *ev;
    c->events[c->nevents].kind = kind;
    if (kind == TT_EVENT_END) c->events[c->nevents].impulse = 0.0;
    c->nevents++;
}

/* Room for every event after_step can publish: a begin or persist per
 * record, an end per record of the last step. */
bool tt__contacts_after_reserve(tt_world *w, void *self)
{
    (void)w;
    tt__collide *c = self;
    if (!c->set.events) return true;
    return tt__grow((void **)&c->events, &c->evcap, c->scr.nrec + c->nprev, sizeof *c->events);
}

void tt__contacts_after_step(tt_world *w, void *self)
{
    tt__collide *c = self;
    if (c->any_moved) tt__shapes_arrived(c);
    /* the step bumps the epoch once after this: end positions stay valid through it, not through a teleport */
    if (c->s_epoch == w->epoch) c->s_epoch = w->epoch + 1;
    if (c->clear_ok && c->clear_epoch == w->epoch) c->clear_epoch = w->epoch + 1; /* contact_skip.c's bound, likewise */
    if (c->reach_epoch == w->epoch) c->reach_epoch = w->epoch + 1; /* and contact_reach.c's largest radius */
    if (c->radii_epoch == w->epoch) c->radii_epoch = w->epoch + 1; /* and contact_undo.c's radii above zero */
    c->nevents = 0;
    if (!c->set.events) {
        c->scr.nrec = 0;
        c->nprev = 0;
        return;
    }
    c->rec_peak = c->scr.nrec;
    /* one record per contact: sorted by key; substeps merged (impulses add up, the last geometry stays) */
    if (c->scr.nrec > 1) qsort(c->scr.rec, c->scr.nrec, sizeof *c->scr.rec, cmp_record);
    uint32_t m = 0;
    for (uint32_t k = 0; k < c->scr.nrec; k++) {
        if (m && c->scr.rec[m - 1].key == c->scr.rec[k].key) {
            double imp = c->scr.rec[m - 1].ev.impulse + c->scr.rec[k].ev.impulse;
            c->scr.rec[m - 1] = c->scr.rec[k];
            c->scr.rec[m - 1].ev.impulse = imp;
        } else {
            c->scr.rec[m++] = c->scr.rec[k];
        }
    }
    c->scr.nrec = m;
    uint32_t i = 0, j = 0;
    while (i < c->scr.nrec || j < c->nprev) {
        if (j == c->nprev || (i < c->scr.nrec && c->scr.rec[i].key < c->prev[j].key)) {
            push_event(w, c, &c->scr.rec[i++].ev, TT_EVENT_BEGIN);
        } else if (i == c->scr.nrec || c->prev[j].key < c->scr.rec[i].key) {
            push_event(w, c, &c->prev[j++].ev, TT_EVENT_END);
        } else {
            push_event(w, c, &c->scr.rec[i++].ev, TT_EVENT_PERSIST);
            j++;
        }
    }
    /* this step's set becomes the previous one */
    tt__record *t = c->prev;
    uint32_t tc = c->prevcap;
    c->prev = c->scr.rec;
    c->prevcap = c->scr.reccap;
    c->nprev = c->scr.nrec;
    c->scr.rec = t;
    c->scr.reccap = tc;
    c->scr.nrec = 0;
    c->ev_peak = c->nevents;
}

const tt_contact_event *tt_world_get_contact_events(const tt_world *w, uint32_t *count)
{
    const tt__collide *c = w ? tt__collide_peek(w) : NULL;
    if (count) *count = c ? c->nevents : 0;
    return c && c->nevents ? c->events : NULL;
}
