/* tether — particles that turn (tt_world_def.spin): the group that keeps
 * each particle's angle and angular velocity, advances the angle after
 * each step, puts the angular velocity back when a step runs out of
 * memory, and saves both as the 'SPIN' section of the snapshot (what the
 * world hash covers). The group has no sweeps: the solver runs as if it
 * were absent, and only the contacts' friction changes the angular
 * velocity (collide/contact_roll.c). Worlds without the option never make
 * it, so their streams and hashes are those of the builds before it. */
#include "spin.h"

#include <stdlib.h>

enum { TT__RANK_SPIN = 25, SPIN_VERSION = 1 };

#define TWO_PI 6.283185307179586

/* Arrays grown to need slots, the new ones zero (a particle starts still). */
static bool grow(tt__spin *s, uint32_t need)
{
    if (need <= s->cap) return true;
    double *a = realloc(s->angle, (size_t)need * sizeof *a);
    if (!a) return false;
    s->angle = a;
    double *o = realloc(s->omega, (size_t)need * sizeof *o);
    if (!o) return false;
    s->omega = o;
    tt__zero(a + s->cap, (size_t)(need - s->cap) * sizeof *a);
    tt__zero(o + s->cap, (size_t)(need - s->cap) * sizeof *o);
    s->cap = need;
    return true;
}

static bool reserve(tt_world *w, void *self) { return grow(self, w->pcap); }

/* The angle follows the step's last angular velocity (the friction of each
 * substep changed it), kept in [−π, π] so that it keeps its precision; a
 * spin past TT_DIVERGED stops, as a particle's velocity does. Sleepers keep
 * theirs. */
static void after_step(tt_world *w, void *self)
{
    tt__spin *s = self;
    const double dt = w->dt_prev * w->scr.nsub;
    const uint32_t n = w->ppool.count < s->cap ? w->ppool.count : s->cap;
    for (uint32_t i = 0; i < n; i++) {
        if (s->omega[i] == 0.0 || (w->flags[i] & (TT__PF_ALIVE | TT__PF_ASLEEP)) != TT__PF_ALIVE) continue;
        if (!(fabs(s->omega[i]) <= TT_DIVERGED)) {
            s->omega[i] = 0.0;
            w->stats.diverged++;
            continue;
        }
        s->angle[i] = remainder(s->angle[i] + s->omega[i] * dt, TWO_PI);
    }
}

static void particle_removed(tt_world *w, void *self, uint32_t i)
{
    (void)w;
    tt__spin *s = self;
    if (i < s->cap) s->angle[i] = s->omega[i] = 0.0;
}

/* The step's undo: only the contacts' end changes omega inside a step (the
 * angle moves in after_step, which no longer fails), so omega is copied. */
static bool undo_reserve(tt_world *w, void *self)
{
    (void)w;
    tt__spin *s = self;
    if (s->undo_cap >= s->cap) return true;
    double *p = realloc(s->undo_omega, (size_t)s->cap * sizeof *p);
    if (!p) return false;
    s->undo_omega = p;
    s->undo_cap = s->cap;
    return true;
}

static void undo_mark(tt_world *w, void *self)
{
    (void)w;
    tt__spin *s = self;
    tt__copy(s->undo_omega, s->omega, (size_t)(s->cap < s->undo_cap ? s->cap : s->undo_cap) * sizeof *s->omega);
}

static void undo(tt_world *w, void *self)
{
    (void)w;
    tt__spin *s = self;
    tt__copy(s->omega, s->undo_omega, (size_t)(s->cap < s->undo_cap ? s->cap : s->undo_cap) * sizeof *s->omega);
}

/* The undo copy is scratch (undo_mark writes it before undo reads it): freed
 * between two steps, the next step's undo_reserve makes it again. */
static void scratch_free(tt_world *w, void *self)
{
    (void)w;
    tt__spin *s = self;
    free(s->undo_omega);
    s->undo_omega = NULL;
    s->undo_cap = 0;
}

/* The section: its version, the slot count, then each slot's angle and
 * angular velocity (removed slots hold zeros). */
static void save(const tt_world *w, const void *self, tt__sink *snk)
{
    const tt__spin *s = self;
    const uint32_t n = w->ppool.count;
    tt__put_u32(snk, SPIN_VERSION);
    tt__put_u32(snk, n);
    for (uint32_t i = 0; i < n; i++) {
        tt__put_f64(snk, i < s->cap ? s->angle[i] : 0.0);
        tt__put_f64(snk, i < s->cap ? s->omega[i] : 0.0);
    }
}

static size_t memory(const tt_world *w, const void *self)
{
    (void)w;
    const tt__spin *s = self;
    return sizeof *s + ((size_t)s->cap * 2 + s->undo_cap) * sizeof(double);
}

static void destroy(tt_world *w, void *self)
{
    (void)w;
    tt__spin *s = self;
    if (!s) return;
    free(s->angle);
    free(s->omega);
    free(s->undo_omega);
    free(s);
}

static void *load(tt_world *w, tt__source *src)
{
    tt__spin *s = calloc(1, sizeof *s);
    if (!s || !grow(s, w->pcap ? w->pcap : 1)) {
        destroy(w, s);
        tt__src_fail(src, "out of memory for the spin state");
        return NULL;
    }
    const uint32_t version = tt__get_u32(src), n = tt__get_u32(src);
    if (!src->failed && version != SPIN_VERSION) tt__src_fail(src, "spin: version %u (this build reads %u)", version, SPIN_VERSION);
    if (!src->failed && n != w->ppool.count) tt__src_fail(src, "spin: %u slots for %u particles", n, w->ppool.count);
    for (uint32_t i = 0; i < n && !src->failed; i++) {
        s->angle[i] = tt__get_num(src, -TWO_PI / 2, TWO_PI / 2, "spin: angle");
        s->omega[i] = tt__get_num(src, -TT_DIVERGED, TT_DIVERGED, "spin: angular velocity");
        if (!(w->flags[i] & TT__PF_ALIVE) && (s->angle[i] != 0.0 || s->omega[i] != 0.0))
            tt__src_fail(src, "spin: removed particle %u turns", i);
    }
    if (src->failed) {
        destroy(w, s);
        return NULL;
    }
    return s;
}

static const tt__group_ops spin_ops = {
    .name = "spin", .rank = TT__RANK_SPIN,
    .begin_stage = TT_STAGE_SOLVE,
    .reserve = reserve,
    .after_step = after_step,
    .undo_reserve = undo_reserve,
    .undo_mark = undo_mark,
    .undo = undo,
    .particle_removed = particle_removed,
    .id = TT__SPIN_ID,
    .save = save,
    .load = load,
    .memory = memory,
    .scratch_free = scratch_free,
    .destroy = destroy,
};

/* Known to the snapshot reader before any world turns its particles. */
__attribute__((constructor)) static void register_feature(void) { tt__feature_register(&spin_ops); }

bool tt__spin_enable(tt_world *w)
{
    if (tt__spin_peek(w)) return true;
    tt__spin *s = calloc(1, sizeof *s);
    if (!s || !grow(s, w->pcap ? w->pcap : 1) || tt__group_add(w, &spin_ops, s) < 0) {
        destroy(w, s);
        return false;
    }
    return true;
}

/* --- public calls ----------------------------------------------------------- */

/* The spin state for particle p of w into *out, or the error. */
static tt_result checked(const tt_world *w, tt_particle p, const char *fn, tt__spin **out)
{
    tt_result r = tt__particle_check(w, p, fn);
    if (r != TT_OK) return r;
    if (!(*out = tt__spin_peek(w))) return tt__fail(w, TT_ESTATE, "%s: the world's particles do not turn (tt_world_def.spin)", fn);
    return TT_OK;
}

/* Particle p's angle (angle true) or spin into *out. */
static tt_result get(const tt_world *w, tt_particle p, double *out, bool angle, const char *fn)
{
    tt__spin *s;
    tt_result r = checked(w, p, fn, &s);
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "%s: out is NULL", fn);
    *out = p.index >= s->cap ? 0.0 : angle ? s->angle[p.index] : s->omega[p.index];
    return TT_OK;
}

tt_result tt_particle_get_angle(const tt_world *w, tt_particle p, double *out)
{
    return get(w, p, out, true, "tt_particle_get_angle");
}

tt_result tt_particle_get_spin(const tt_world *w, tt_particle p, double *out)
{
    return get(w, p, out, false, "tt_particle_get_spin");
}

tt_result tt_particle_set_spin(tt_world *w, tt_particle p, double spin)
{
    tt__spin *s;
    tt_result r = checked(w, p, "tt_particle_set_spin", &s);
    if (r != TT_OK) return r;
    if (!tt__in_range(spin, -TT_MAX_VALUE, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "tt_particle_set_spin: spin must be finite, |spin| <= %g rad/s, got %g", TT_MAX_VALUE, spin);
    /* as set_velocity: a pinned particle never moves (turning, it would drive what touches it
     * with energy no one counts); a point has no rim to turn */
    if (w->flags[p.index] & TT__PF_PINNED) return tt__fail(w, TT_ESTATE, "tt_particle_set_spin: the particle is pinned");
    if (spin != 0.0 && !(w->radius[p.index] > 0.0))
        return tt__fail(w, TT_ESTATE, "tt_particle_set_spin: the particle is a point (radius 0): it does not turn");
    if (!grow(s, w->pcap)) return tt__fail(w, TT_ENOMEM, "tt_particle_set_spin: out of memory");
    tt__sleep_touch(w, p.index);
    s->omega[p.index] = spin;
    return TT_OK;
}
