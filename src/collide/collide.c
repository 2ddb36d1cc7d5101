/* tether — the public collision settings (tether/collide.h): the world's
 * settings and statistics, per-particle materials and bullets, and the
 * pairs switched off (a set of core/pair_set.h); and the pair sweep mode
 * the tests force. Their defaults are in collide_defs.c. These calls make
 * the collision state on first use (tt__collide_get), so they sit above
 * the contacts group and its stages. */
#include "collide_internal.h"

#include <stdlib.h>
#include <string.h>

/* --- public settings ------------------------------------------------------- */

tt_result tt_world_set_collision(tt_world *w, const tt_collision_settings *s)
{
    const char *fn = "tt_world_set_collision";
    TT_CHECK_WORLD(w, fn);
    if (!s) return tt__fail(w, TT_EINVAL, "%s: settings are NULL", fn);
    if (s->broadphase != TT_BROADPHASE_GRID && s->broadphase != TT_BROADPHASE_BRUTE)
        return tt__fail(w, TT_EINVAL, "%s: unknown broadphase %d", fn, (int)s->broadphase);
    if (!tt__in_range(s->cell_size, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: cell_size must be in [0, %g], got %g", fn, TT_MAX_VALUE, s->cell_size);
    if (!tt__in_range(s->restitution, 0.0, 1.0)) return tt__fail(w, TT_EINVAL, "%s: restitution must be in [0, 1], got %g", fn, s->restitution);
    if (!tt__in_range(s->friction_static, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: friction_static must be in [0, %g], got %g", fn, TT_MAX_VALUE, s->friction_static);
    if (!tt__in_range(s->friction_kinetic, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: friction_kinetic must be in [0, %g], got %g", fn, TT_MAX_VALUE, s->friction_kinetic);
    if (!tt__in_range(s->restitution_threshold, -TT_MAX_VALUE, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: restitution_threshold must be finite (< 0 = auto)", fn);
    if (s->events & ~7u) return tt__fail(w, TT_EINVAL, "%s: events must be a set of TT_EVENT_BEGIN|PERSIST|END, got 0x%x", fn, s->events);
    if (!tt__in_range(s->stacking, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: stacking must be in [0, %g], got %g", fn, TT_MAX_VALUE, s->stacking);
    if (!tt__in_range(s->warm_start, 0.0, 1.0)) return tt__fail(w, TT_EINVAL, "%s: warm_start must be in [0, 1], got %g", fn, s->warm_start);
    tt__collide *c = tt__collide_get(w, true, fn);
    if (!c) return TT_ENOMEM;
    c->set = *s;
    c->clear_ok = false; /* contact_skip.c: the cell and reach may have changed */
    c->set.restitution_threshold = s->restitution_threshold < 0.0 ? -1.0 : s->restitution_threshold;
    if (!s->events) c->nprev = 0;
    if (!s->anchored_friction) tt__anchors_clear(&c->anc);
    if (s->warm_start == 0.0) tt__anchors_cool(&c->anc); /* kept only while on: a world saved without it is the same */
    return TT_OK;
}

tt_result tt_world_get_collision(const tt_world *w, tt_collision_settings *out)
{
    TT_CHECK_WORLD(w, "tt_world_get_collision");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_world_get_collision: out is NULL");
    const tt__collide *c = tt__collide_peek(w);
    if (c) *out = c->set;
    else {
        *out = tt_collision_settings_default();
        out->particles = false;
    }
    return TT_OK;
}

tt_result tt_world_get_collision_stats(const tt_world *w, tt_collision_stats *out)
{
    TT_CHECK_WORLD(w, "tt_world_get_collision_stats");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_world_get_collision_stats: out is NULL");
    memset(out, 0, sizeof *out);
    const tt__collide *c = tt__collide_peek(w);
    if (!c) return TT_OK;
    out->shapes = c->shapes_alive;
    out->pair_contacts = c->scr.npairs;
    out->shape_contacts = c->scr.nsc;
    out->cells = c->cells_used;
    out->static_rebuilds = c->static_rebuilds;
    out->broadphase_bytes = tt__grid_bytes(&c->scr.grid);
    out->broadphase_bytes_per_particle = c->scr.grid.n ? (double)out->broadphase_bytes / c->scr.grid.n : 0.0;
    out->total_bytes = tt__contacts_memory(w, c);
    out->broadphase_ms = c->bp_step == w->stats.steps - 1 ? c->bp_ms : 0.0; /* 0 when the last step found no pairs */
    return TT_OK;
}

/* --- per particle ------------------------------------------------------------ */

tt_result tt_particle_set_material(tt_world *w, tt_particle p, double e, double fs, double fk)
{
    const char *fn = "tt_particle_set_material";
    tt_result r = tt__particle_check(w, p, fn);
    if (r == TT_OK) r = tt__material_check(w, e, fs, fk, TT__PARTICLE_MAX_FRICTION, fn);
    if (r != TT_OK) return r;
    tt__collide *c = tt__collide_get(w, true, fn);
    if (!c) return TT_ENOMEM;
    if (c->matcap < w->pcap) {
        float *m = realloc(c->mat, (size_t)w->pcap * 3 * sizeof *m);
        if (!m) return tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        for (size_t k = (size_t)c->matcap * 3; k < (size_t)w->pcap * 3; k++) m[k] = -1.0f;
        c->mat = m;
        c->matcap = w->pcap;
    }
    c->mat[3 * (size_t)p.index] = (float)e;
    c->mat[3 * (size_t)p.index + 1] = (float)fs;
    c->mat[3 * (size_t)p.index + 2] = (float)fk;
    return TT_OK;
}

tt_result tt_particle_get_material(const tt_world *w, tt_particle p, double *e, double *fs, double *fk)
{
    const char *fn = "tt_particle_get_material";
    tt_result r = tt__particle_check(w, p, fn);
    if (r != TT_OK) return r;
    if (!e || !fs || !fk) return tt__fail(w, TT_EINVAL, "%s: out is NULL", fn);
    const tt__collide *c = tt__collide_peek(w);
    if (!c) {
        tt_collision_settings d = tt_collision_settings_default();
        *e = d.restitution;
        *fs = d.friction_static;
        *fk = d.friction_kinetic;
        return TT_OK;
    }
    *e = tt__mat(c, p.index, 0);
    *fs = tt__mat(c, p.index, 1);
    *fk = tt__mat(c, p.index, 2);
    return TT_OK;
}

tt_result tt_particle_set_bullet(tt_world *w, tt_particle p, bool bullet)
{
    const char *fn = "tt_particle_set_bullet";
    tt_result r = tt__particle_check(w, p, fn);
    if (r != TT_OK) return r;
    tt__collide *c = tt__collide_get(w, bullet, fn);
    if (!c) return bullet ? TT_ENOMEM : TT_OK;
    if (!bullet && (!c->bullet || p.index >= c->bulletcap)) return TT_OK;
    if (c->bulletcap < w->pcap) {
        uint8_t *b = realloc(c->bullet, w->pcap);
        if (!b) return tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        memset(b + c->bulletcap, 0, w->pcap - c->bulletcap);
        c->bullet = b;
        int32_t *q = realloc(c->ccd_prim, (size_t)w->pcap * sizeof *q);
        if (!q) return tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        for (uint32_t k = c->bulletcap; k < w->pcap; k++) q[k] = -1;
        c->ccd_prim = q;
        c->bulletcap = w->pcap;
    }
    if (c->bullet[p.index] != bullet) c->nbullets += bullet ? 1 : (uint32_t)-1;
    c->bullet[p.index] = bullet;
    c->ccd_prim[p.index] = -1;
    return TT_OK;
}

tt_result tt_particle_get_bullet(const tt_world *w, tt_particle p, bool *out)
{
    tt_result r = tt__particle_check(w, p, "tt_particle_get_bullet");
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "tt_particle_get_bullet: out is NULL");
    const tt__collide *c = tt__collide_peek(w);
    *out = c && c->bullet && p.index < c->bulletcap && c->bullet[p.index];
    return TT_OK;
}

tt_result tt_world_set_pair_collision(tt_world *w, tt_particle a, tt_particle b, bool enabled)
{
    const char *fn = "tt_world_set_pair_collision";
    tt_result r = tt__particle_check(w, a, fn);
    if (r == TT_OK) r = tt__particle_check(w, b, fn);
    if (r != TT_OK) return r;
    if (a.index == b.index) return tt__fail(w, TT_EINVAL, "%s: a and b are the same particle", fn);
    tt__collide *c = tt__collide_get(w, !enabled, fn);
    if (!c) return enabled ? TT_OK : TT_ENOMEM;
    const bool present = tt__pair_set_has(&c->excl, a.index, b.index);
    if (enabled && present) tt__pair_set_remove(&c->excl, a.index, b.index);
    else if (!enabled && !present && !tt__pair_set_add(&c->excl, a.index, b.index))
        return tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
    return TT_OK;
}

/* --- for tests ---------------------------------------------------------- */

bool tt__contacts_set_simd(tt_world *w, tt__simd_mode mode)
{
    if (mode != TT__SIMD_AUTO && mode != TT__SIMD_SCALAR && tt__simd_kind((uint8_t)mode) == TT__SIMD_SCALAR) return false;
    tt__collide *c = tt__collide_get(w, true, "tt__contacts_set_simd");
    if (!c) return false;
    c->scr.bat.simd = (uint8_t)mode;
    return true;
}
