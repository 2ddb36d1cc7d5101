/* tether — stacking (tt_collision_settings.stacking): mass scaling by
 * height, and, with anchored friction, particles held off the shapes they
 * lean on, in the batches' pair pushes. */
#include "collide_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Mass scaling by height (Müller, Heidelberger, Hennix and Ratcliff 2007,
 * "Position based dynamics", on stacking; Macklin, Müller, Chentanez and
 * Kim 2014, "Unified particle physics for real-time applications", section
 * 5.2). Gauss-Seidel sweeps split each pair's push by inverse mass, so in a
 * pile the weight of every layer above is pushed down as much as up, and a
 * few sweeps leave a deep pile sunk into itself (the reference pour at
 * 1 × 8: 17 % of a radius at rest). Here the lower particle of each entry
 * weighs 1 + k·u times its mass, u the height of the upper over the lower
 * along −g as a share of the radii sum (0 side by side, 1 one on top of the
 * other), for the sweeps and the pair's velocity pass alike (the same
 * weights in both, else the pass hands the upper's push back as speed).
 * The weights are this entry's, from the predicted positions, fixed for the
 * substep, pre-stabilisation's sweeps included (contact_detect.c); scalar
 * code and the lanes read
 * the same ka, kb, so the bits are the same. Not momentum-conserving between
 * the two (the lower one is heavier for this pair only), as in the papers.
 * Entries with a particle that leans on a shape (lc) go lane by lane.
 * False when off (k = 0 or no gravity): ka, kb are wa, wb. */
static bool weigh(tt__batches *B, const double *px, const double *py, tt_vec2 g, double k)
{
    B->ka = B->wa;
    B->kb = B->wb;
    const double gl = sqrt(g.x * g.x + g.y * g.y);
    if (!(k > 0.0) || !(gl > 0.0) || B->n == 0) return false; /* off, or no up */
    const double ux = -g.x / gl, uy = -g.y / gl;
    for (uint32_t e = 0; e < B->n; e++) {
        double sa = B->wa[e], sb = B->wb[e];
        const uint32_t a = B->a[e], b = B->b[e];
        if (a < B->np && B->rs[e] > 0.0) {
            const double u = ((px[b] - px[a]) * ux + (py[b] - py[a]) * uy) / B->rs[e]; /* b's height over a's */
            /* |u| up to 1, and the scale on the lower one, without branches: u's sign goes
             * either way entry after entry (the same bits, but a NaN's sign) */
            const double s = 1.0 / (1.0 + k * tt__min(1.0, fabs(u)));
            sa *= tt__pick(u > 0.0, s, 1.0);
            sb *= tt__pick(u > 0.0, 1.0, s);
        }
        B->sa[e] = sa;
        B->sb[e] = sb;
        if (B->lean && (B->lc[a] | B->lc[b])) B->solo[e / 4] |= TT__SOLO_LEAN;
    }
    B->ka = B->sa;
    B->kb = B->sb;
    return true;
}

/* Which particles lean on a shape: every shape or terrain contact of the
 * substep (within the contact margin), the normals of a particle's first
 * two. False on no memory. */
static bool lean(tt__batches *B, const tt__scontact *sc, uint32_t nsc)
{
    const uint32_t slots = B->np + 1; /* and the padding row */
    if (slots > B->ln_cap) {
        double *p = malloc((size_t)slots * (4 * sizeof(double) + 1));
        if (!p) return false;
        free(B->ln);
        B->ln = p;
        B->lc = (uint8_t *)(p + 4 * (size_t)slots);
        B->ln_cap = slots;
    }
    memset(B->lc, 0, slots);
    for (uint32_t k = 0; k < nsc; k++) {
        const uint32_t i = sc[k].a;
        if (i >= B->np || B->lc[i] == 2) continue;
        double *n = B->ln + 4 * (size_t)i + 2 * B->lc[i]++;
        n[0] = sc[k].nx;
        n[1] = sc[k].ny;
    }
    return true;
}

void tt__contacts_stack(tt_world *w, tt__collide *c)
{
    tt__batches *B = &c->scr.bat;
    B->lean = false;
    const double k = c->set.stacking;
    /* the hold with anchored friction only: without it a stacked pile held
     * off its walls never rests (docs/collisions.md "Particles against a shape") */
    if (k > 0.0 && c->scr.nsc && c->scr.anc.on) {
        B->lean = lean(B, c->scr.sc, c->scr.nsc);
        if (!B->lean) tt__step_oom(w, "stacking's shape contacts");
    }
    if (!weigh(B, w->px, w->py, w->gravity, k)) B->lean = false;
}
