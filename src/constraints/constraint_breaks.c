/* tether — break events: links stretched past their break strain are
 * removed at the end of a substep, each with an event; the events gathered
 * during a step are published after it, for scripts to read until the next. */
#include "constraint_internal.h"

static bool event_push(tt__cgroup *g, tt_break_event e)
{
    if (!tt__grow((void **)&g->scr.ev_new, &g->scr.cap_new, g->scr.nnew + 1, sizeof *g->scr.ev_new)) return false;
    g->scr.ev_new[g->scr.nnew++] = e;
    return true;
}

/* Before a step: the distance sweep's plan, and room for every breakable
 * link to break in it, an event and a free slot each, so breaking never
 * runs out of memory. */
bool tt__cgroup_reserve(tt_world *w, void *self)
{
    tt__cgroup *g = self;
    if (!tt__distance_plan_reserve(w, g)) return false;
    if (!g->scr.grad_cap && !tt__cgroup_grad_reserve(g)) return false; /* the scratch was freed */
    if (!g->nbreakable) return true;
    return tt__grow((void **)&g->scr.ev_new, &g->scr.cap_new, g->scr.nnew + g->nbreakable, sizeof *g->scr.ev_new) &&
           tt__pool_reserve_free(&g->pool, g->nbreakable);
}

/* Called at the end of each substep, after the bounds' friction. */
void tt__cgroup_break_links(tt_world *w, tt__cgroup *g)
{
    if (!g->nbreakable) return;
    /* Backwards, so the element swapped into a removed place was already checked. */
    for (uint32_t i = g->ndist; i-- > 0;) {
        const tt__dist *d = &g->dist[i];
        const tt__dist_x *x = &g->dx[i];
        if (x->break_strain <= 0.0) continue;
        double len = tt__constraint_dist_of(w, d->a, d->b), rest = x->mode == TT_DISTANCE_MIN ? d->lo : d->hi;
        if (!(len > rest * (1.0 + x->break_strain))) continue;
        /* A denormal rest overflows len / rest: the strain is as unbounded as a zero rest's. */
        tt_break_event e = {tt__cgroup_handle(g, x->slot), tt__cgroup_particle(w, d->a), tt__cgroup_particle(w, d->b),
                            len, rest > 0.0 ? fmin(len / rest - 1.0, TT_MAX_VALUE) : TT_MAX_VALUE};
        if (w->scr.undo.on && !g->scr.undo.broke) tt__cgroup_undo_links(w, g);
        if (!event_push(g, e)) tt__step_oom(w, "break events");
        tt__cgroup_dist_remove(g, i);
    }
}

void tt__cgroup_after_step(tt_world *w, void *self)
{
    (void)w;
    tt__cgroup *g = self;
    /* publish: the gathered list becomes the readable one, the old one is reused */
    tt_break_event *e = g->ev_pub;
    uint32_t cap = g->cap_pub;
    g->ev_pub = g->scr.ev_new;
    g->cap_pub = g->scr.cap_new;
    g->npub = g->scr.nnew;
    g->scr.ev_new = e;
    g->scr.cap_new = cap;
    g->scr.nnew = 0;
}

tt_result tt_world_get_break_events(const tt_world *w, const tt_break_event **events, uint32_t *count)
{
    TT_CHECK_WORLD(w, "tt_world_get_break_events");
    if (!events || !count) return tt__fail(w, TT_EINVAL, "tt_world_get_break_events: NULL argument");
    const tt__cgroup *g = tt__cgroup_peek(w);
    *events = g ? g->ev_pub : NULL;
    *count = g ? g->npub : 0;
    return TT_OK;
}
