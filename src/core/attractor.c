/* tether — point attractors, the public calls: a softened 1/r² pull
 * (planets, magnets); the pull itself is attractor_pull.c, kept apart so
 * that the force loop does not depend on the API's error reporting. */
#include "internal.h"

tt_result tt_world_set_attractor(tt_world *w, uint32_t slot, tt_attractor a)
{
    TT_CHECK_WORLD(w, "tt_world_set_attractor");
    if (slot >= TT_MAX_ATTRACTORS)
        return tt__fail(w, TT_EINVAL, "tt_world_set_attractor: slot must be in [0, %d], got %u", TT_MAX_ATTRACTORS - 1, slot);
    if (!tt__vec_ok(a.center))
        return tt__fail(w, TT_EINVAL, "tt_world_set_attractor: center must be finite, |x| <= %g", TT_MAX_VALUE);
    if (!tt__in_range(a.strength, -TT_MAX_VALUE, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "tt_world_set_attractor: strength must be in [%g, %g], got %g", -TT_MAX_VALUE, TT_MAX_VALUE, a.strength);
    if (!tt__in_range(a.softening, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "tt_world_set_attractor: softening must be in [0, %g], got %g", TT_MAX_VALUE, a.softening);
    if (a.strength == 0.0) a = (tt_attractor){{0.0, 0.0}, 0.0, 0.0}; /* an unused slot is all zeros: one state, one hash */
    bool was = w->attractors[slot].strength != 0.0, is = a.strength != 0.0;
    w->attractors[slot] = a;
    w->attractors_used = w->attractors_used - was + is;
    return TT_OK;
}

tt_result tt_world_get_attractor(const tt_world *w, uint32_t slot, tt_attractor *out)
{
    TT_CHECK_WORLD(w, "tt_world_get_attractor");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_world_get_attractor: out is NULL");
    if (slot >= TT_MAX_ATTRACTORS)
        return tt__fail(w, TT_EINVAL, "tt_world_get_attractor: slot must be in [0, %d], got %u", TT_MAX_ATTRACTORS - 1, slot);
    *out = w->attractors[slot];
    return TT_OK;
}
