/* tether — composites: rope, cloth, ragdoll, soft body and lattice body, made
 * of particles and constraints through the public calls, and kept under one
 * generational handle so a script can read them back, move them as one
 * (centre of mass, orientation) and remove them. This file holds the
 * handle's reads, removal and the group's hooks; composite_builder.c makes
 * them, composite_kinds.c says how each kind is laid out. */
#include "constraint_internal.h"

#include <stdlib.h>
#include <string.h>

/* ---- reading back --------------------------------------------------------------- */

/* Slots with a record (a slot taken when growing the records failed has none). */

static tt_result comp_check(const tt_world *w, tt_composite c, const char *fn, const tt__composite **out)
{
    if (!w) return tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn);
    const tt__cgroup *g = tt__cgroup_peek(w);
    if (!g || c.gen == 0 || c.index >= tt__comp_slots(g) || g->cpool.gen[c.index] != c.gen || !g->comps[c.index].alive)
        return tt__fail(w, TT_ESTALE, "%s: stale composite handle (index %u, generation %u)", fn, c.index, c.gen);
    *out = &g->comps[c.index];
    return TT_OK;
}

bool tt_composite_is_valid(const tt_world *w, tt_composite c)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    return g && c.gen != 0 && c.index < tt__comp_slots(g) && g->cpool.gen[c.index] == c.gen && g->comps[c.index].alive;
}

tt_result tt_composite_destroy(tt_world *w, tt_composite c)
{
    const tt__composite *cc;
    tt_result r = comp_check(w, c, "tt_composite_destroy", &cc);
    if (r != TT_OK) return r;
    tt__cgroup *g = tt__cgroup_find(w);
    tt__composite *k = &g->comps[c.index];
    for (uint32_t i = 0; i < k->nc; i++)
        if (tt_constraint_is_valid(w, k->cons[i])) tt_constraint_destroy(w, k->cons[i]);
    for (uint32_t i = 0; i < k->np; i++)
        if (tt_particle_is_valid(w, k->parts[i])) tt_particle_destroy(w, k->parts[i]);
    free(k->parts);
    free(k->cons);
    free(k->rest);
    memset(k, 0, sizeof *k);
    tt__pool_free(&g->cpool, c.index);
    g->comps_alive--;
    return TT_OK;
}

tt_result tt_composite_get_particles(const tt_world *w, tt_composite c, tt_particle *out, uint32_t cap, uint32_t *count)
{
    const tt__composite *k;
    tt_result r = comp_check(w, c, "tt_composite_get_particles", &k);
    if (r != TT_OK) return r;
    for (uint32_t i = 0; out && i < k->np && i < cap; i++) out[i] = k->parts[i];
    if (count) *count = k->np;
    return TT_OK;
}

tt_result tt_composite_get_constraints(const tt_world *w, tt_composite c, tt_constraint *out, uint32_t cap, uint32_t *count)
{
    const tt__composite *k;
    tt_result r = comp_check(w, c, "tt_composite_get_constraints", &k);
    if (r != TT_OK) return r;
    for (uint32_t i = 0; out && i < k->nc && i < cap; i++) out[i] = k->cons[i];
    if (count) *count = k->nc;
    return TT_OK;
}

/* Mass-weighted centres, now and at rest, over the live particles. */
static double centres(const tt_world *w, const tt__composite *k, double c[2], double r0[2])
{
    double m = 0;
    c[0] = c[1] = r0[0] = r0[1] = 0;
    for (uint32_t i = 0; i < k->np; i++) {
        if (!tt_particle_is_valid(w, k->parts[i])) continue;
        uint32_t p = k->parts[i].index;
        double mi = w->mass[p];
        m += mi;
        c[0] += mi * w->px[p];
        c[1] += mi * w->py[p];
        r0[0] += mi * k->rest[2 * i];
        r0[1] += mi * k->rest[2 * i + 1];
    }
    if (m > 0) {
        c[0] /= m; c[1] /= m; r0[0] /= m; r0[1] /= m;
    }
    return m;
}

/* The checks both readers below share, then the centres of mass now (cc) and at rest (r0). */
static tt_result comp_frame(const tt_world *w, tt_composite c, const char *fn, const void *out,
                            const tt__composite **k, double cc[2], double r0[2])
{
    tt_result r = comp_check(w, c, fn, k);
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "%s: out is NULL", fn);
    if (centres(w, *k, cc, r0) == 0) return tt__fail(w, TT_ESTATE, "%s: the composite has no particles left", fn);
    return TT_OK;
}

tt_result tt_composite_get_center(const tt_world *w, tt_composite c, tt_vec2 *out)
{
    const tt__composite *k;
    double cc[2], r0[2];
    tt_result r = comp_frame(w, c, "tt_composite_get_center", out, &k, cc, r0);
    if (r != TT_OK) return r;
    *out = (tt_vec2){cc[0], cc[1]};
    return TT_OK;
}

tt_result tt_composite_get_angle(const tt_world *w, tt_composite c, double *out)
{
    const tt__composite *k;
    double cc[2], r0[2];
    tt_result r = comp_frame(w, c, "tt_composite_get_angle", out, &k, cc, r0);
    if (r != TT_OK) return r;
    double sc = 0, ss = 0; /* Σ m (q·p), Σ m (q×p): q rest offset, p current offset */
    for (uint32_t i = 0; i < k->np; i++) {
        if (!tt_particle_is_valid(w, k->parts[i])) continue;
        uint32_t p = k->parts[i].index;
        double qx = k->rest[2 * i] - r0[0], qy = k->rest[2 * i + 1] - r0[1];
        double px = w->px[p] - cc[0], py = w->py[p] - cc[1], m = w->mass[p];
        sc += m * (qx * px + qy * py);
        ss += m * (qx * py - qy * px);
    }
    *out = atan2(ss, sc);
    return TT_OK;
}

uint32_t tt_world_composite_count(const tt_world *w)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    return g ? g->comps_alive : 0;
}

/* ---- group hooks ------------------------------------------------------------------ */
