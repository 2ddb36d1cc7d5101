/* tether — the units (batch entries, else pairs) that touched in the
 * sweeps, listed once at the start of the velocity pass (contacts_end).
 * The passes after the sweeps (anchors' keep, unrub, the pair pass, the
 * lift, the speed cap) walk the list without a branch a unit on whether it
 * touched. A third of the reference pour's units did not, in no order a
 * branch predicts; walking the list, the pour at 1 × 4 ran 8 % faster
 * (3.76–3.90 against 4.01–4.31 ms/step, alternated), with the same bits.
 * Room as the pair list's: none grows in a step with no pairs to find
 * (contact_undo.c's bound). */
#include "collide_internal.h"

bool tt__contacts_touched(tt_world *w, tt__collide *c)
{
    tt__collide_scratch *s = &c->scr;
    const uint32_t m = s->batched ? s->bat.n : s->npairs;
    s->ntouch = 0;
    if (m == 0) return true;
    if (!tt__grow((void **)&s->touch, &s->touch_cap, (s->batched ? s->bat.cap : s->paircap) + 1, sizeof *s->touch)) {
        tt__step_oom(w, "the velocity pass");
        return false;
    }
    uint32_t n = 0;
    if (s->batched) {
        for (uint32_t k = 0; k < m; k++) {
            s->touch[n] = k;
            n += (s->bat.lam[k] > 0.0) & (s->bat.a[k] < s->bat.np); /* &, not &&: no branch */
        }
    } else {
        for (uint32_t k = 0; k < m; k++) {
            s->touch[n] = k;
            n += s->pairs[k].lambda > 0.0f;
        }
    }
    s->ntouch = n;
    return true;
}
