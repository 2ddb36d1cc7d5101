/* tether — the registry of solver groups (the features a world uses:
 * constraints, contacts, sleeping), apart from the solver that sweeps them
 * so that a feature can register itself without depending on the step. */
#include "internal.h"

#include <string.h>

int tt__group_add(tt_world *w, const tt__group_ops *ops, void *self)
{
    if (w->group_count == TT_MAX_GROUPS) return -1;
    int at = w->group_count;
    while (at > 0 && w->groups[at - 1].ops->rank > ops->rank) {
        w->groups[at] = w->groups[at - 1];
        at--;
    }
    w->groups[at] = (tt__group){ops, self};
    w->group_count++;
    return at;
}

void *tt__group_find(const tt_world *w, const tt__group_ops *ops)
{
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops == ops) return w->groups[g].self;
    return NULL;
}

void *tt__group_find_id(const tt_world *w, uint32_t id)
{
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->id == id) return w->groups[g].self;
    return NULL;
}

void tt__group_remove_id(tt_world *w, uint32_t id)
{
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->id == id) {
            tt__group_remove(w, w->groups[g].ops);
            return;
        }
}

void tt__group_remove(tt_world *w, const tt__group_ops *ops)
{
    for (int g = 0; g < w->group_count; g++) {
        if (w->groups[g].ops != ops) continue;
        tt__group gone = w->groups[g];
        memmove(&w->groups[g], &w->groups[g + 1], (size_t)(w->group_count - g - 1) * sizeof w->groups[0]);
        w->group_count--;
        if (gone.ops->destroy) gone.ops->destroy(w, gone.self);
        return;
    }
}
