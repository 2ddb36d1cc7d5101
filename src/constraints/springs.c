/* tether — force-based linear springs with damping. */
#include "core/internal.h"

#include <stdlib.h>
#include <string.h>

tt_spring_def tt_spring_def_default(void)
{
    tt_spring_def d;
    memset(&d, 0, sizeof d);
    d.stiffness = 100.0;
    d.damping = 0.0;
    d.rest_length = -1.0;
    return d;
}

static bool spring_ok(const tt_world *w, tt_spring s)
{
    return w && s.index < w->spool.count && s.gen != 0 && w->spool.gen[s.index] == s.gen &&
           w->springs[s.index].alive;
}

static tt_result spring_check(const tt_world *w, tt_spring s, const char *fn)
{
    if (!w) return tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn);
    if (!spring_ok(w, s))
        return tt__fail(w, TT_ESTALE, "%s: stale spring handle (index %u, generation %u)", fn, s.index, s.gen);
    return TT_OK;
}

static double distance(const tt_world *w, uint32_t a, uint32_t b)
{
    double dx = w->px[a] - w->px[b], dy = w->py[a] - w->py[b];
    return sqrt(dx * dx + dy * dy);
}

tt_spring tt_spring_create(tt_world *w, const tt_spring_def *d)
{
    const char *fn = "tt_spring_create";
    tt_spring none = {0, 0};
    if (!w) { tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn); return none; }
    if (!d) { tt__fail(w, TT_EINVAL, "%s: def is NULL", fn); return none; }
    if (tt__particle_check(w, d->a, fn) != TT_OK || tt__particle_check(w, d->b, fn) != TT_OK) return none;
    if (d->a.index == d->b.index) { tt__fail(w, TT_EINVAL, "%s: a spring needs two distinct particles", fn); return none; }
    if (!tt__in_range(d->stiffness, 0.0, TT_MAX_VALUE)) { tt__fail(w, TT_EINVAL, "%s: stiffness must be in [0, %g], got %g", fn, TT_MAX_VALUE, d->stiffness); return none; }
    if (!tt__in_range(d->damping, 0.0, TT_MAX_VALUE)) { tt__fail(w, TT_EINVAL, "%s: damping must be in [0, %g], got %g", fn, TT_MAX_VALUE, d->damping); return none; }
    if (!(d->rest_length == -1.0 || tt__in_range(d->rest_length, 0.0, TT_MAX_VALUE))) {
        tt__fail(w, TT_EINVAL, "%s: rest_length must be -1 (current distance) or in [0, %g], got %g", fn, TT_MAX_VALUE, d->rest_length);
        return none;
    }
    /* room first: a slot taken and given back would age its generation, and
     * a pool grown past the records would send the hash to a record not there */
    uint32_t need = w->spool.free_count ? w->spool.count : w->spool.count + 1;
    if (need > w->scap) {
        uint32_t cap = w->scap ? w->scap * 2 : 64;
        tt__spring *sp = realloc(w->springs, (size_t)cap * sizeof *sp);
        if (!sp) { tt__fail(w, TT_ENOMEM, "%s: out of memory", fn); return none; }
        w->springs = sp;
        w->scap = cap;
    }
    bool grew;
    uint32_t i = tt__pool_alloc(&w->spool, UINT32_MAX - 1, &grew);
    if (i == UINT32_MAX) { tt__fail(w, TT_ENOMEM, "%s: out of memory", fn); return none; }
    tt__spring *s = &w->springs[i];
    s->a = d->a.index;
    s->b = d->b.index;
    s->k = d->stiffness;
    s->c = d->damping;
    s->rest = d->rest_length < 0.0 ? distance(w, s->a, s->b) : d->rest_length;
    s->alive = true;
    w->springs_alive++;
    tt__sleep_touch(w, s->a); /* a new spring changes what rests */
    tt__sleep_touch(w, s->b);
    return (tt_spring){i, w->spool.gen[i]};
}

static void spring_kill(tt_world *w, uint32_t i)
{
    w->springs[i].alive = false;
    tt__sleep_touch(w, w->springs[i].a);
    tt__sleep_touch(w, w->springs[i].b);
    tt__pool_free(&w->spool, i);
    w->springs_alive--;
}

tt_result tt_spring_destroy(tt_world *w, tt_spring s)
{
    tt_result r = spring_check(w, s, "tt_spring_destroy");
    if (r != TT_OK) return r;
    spring_kill(w, s.index);
    return TT_OK;
}

bool tt_spring_is_valid(const tt_world *w, tt_spring s) { return spring_ok(w, s); }

tt_result tt_spring_get_def(const tt_world *w, tt_spring s, tt_spring_def *out)
{
    tt_result r = spring_check(w, s, "tt_spring_get_def");
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "tt_spring_get_def: out is NULL");
    const tt__spring *sp = &w->springs[s.index];
    out->a = (tt_particle){sp->a, w->ppool.gen[sp->a]};
    out->b = (tt_particle){sp->b, w->ppool.gen[sp->b]};
    out->stiffness = sp->k;
    out->damping = sp->c;
    out->rest_length = sp->rest;
    return TT_OK;
}

/* The three setters share one check; the field is picked by its offset. */
static tt_result set_field(tt_world *w, tt_spring s, double v, size_t offset, const char *fn, const char *what)
{
    tt_result r = spring_check(w, s, fn);
    if (r != TT_OK) return r;
    if (!tt__in_range(v, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "%s: %s must be in [0, %g], got %g", fn, what, TT_MAX_VALUE, v);
    *(double *)((char *)&w->springs[s.index] + offset) = v;
    return TT_OK;
}

tt_result tt_spring_set_stiffness(tt_world *w, tt_spring s, double k)
{
    return set_field(w, s, k, offsetof(tt__spring, k), "tt_spring_set_stiffness", "stiffness");
}

tt_result tt_spring_set_damping(tt_world *w, tt_spring s, double c)
{
    return set_field(w, s, c, offsetof(tt__spring, c), "tt_spring_set_damping", "damping");
}

tt_result tt_spring_set_rest_length(tt_world *w, tt_spring s, double l)
{
    return set_field(w, s, l, offsetof(tt__spring, rest), "tt_spring_set_rest_length", "rest length");
}

tt_result tt_spring_get_length(const tt_world *w, tt_spring s, double *out)
{
    tt_result r = spring_check(w, s, "tt_spring_get_length");
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "tt_spring_get_length: out is NULL");
    *out = distance(w, w->springs[s.index].a, w->springs[s.index].b);
    return TT_OK;
}

uint32_t tt_world_spring_count(const tt_world *w) { return w ? w->springs_alive : 0; }

uint32_t tt_world_list_springs(const tt_world *w, tt_spring *out, uint32_t cap)
{
    if (!w) return 0;
    uint32_t k = 0;
    for (uint32_t i = 0; i < w->spool.count && out && k < cap; i++)
        if (w->springs[i].alive) out[k++] = (tt_spring){i, w->spool.gen[i]};
    return w->springs_alive;
}

void tt__springs_detach(tt_world *w, uint32_t particle)
{
    for (uint32_t i = 0; i < w->spool.count; i++) {
        tt__spring *s = &w->springs[i];
        if (s->alive && (s->a == particle || s->b == particle)) spring_kill(w, i);
    }
}

double tt__springs_energy(const tt_world *w)
{
    double e = 0.0;
    for (uint32_t i = 0; i < w->spool.count; i++) {
        const tt__spring *s = &w->springs[i];
        if (!s->alive) continue;
        double stretch = distance(w, s->a, s->b) - s->rest;
        e += 0.5 * s->k * stretch * stretch;
    }
    return e;
}

void tt__springs_free(tt_world *w)
{
    free(w->springs);
    w->springs = NULL;
    tt__pool_destroy(&w->spool);
}
