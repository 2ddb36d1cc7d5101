/* tests/fuzz/fuzz_c_check.c — after every step, everything the API can
 * say about a world is read back and must be finite: positions and
 * velocities (bounded by TT_DIVERGED too: the guard stops a particle there),
 * masses, stats, energy, memory, collision stats, constraint errors and
 * lines, spring lengths, composite centres and angles, contact and break
 * events. These reads are the fuzzer's own: they count no calls. */
#include "fuzz_c.h"

#include <math.h>
#include <stdlib.h>

void fz_finite(fz *f, double v, const char *what)
{
    if (!isfinite(v)) fz_fail(f, "%s is %s", what, fz_d(v));
}

void fz_finite_vec(fz *f, tt_vec2 v, const char *what)
{
    fz_finite(f, v.x, what);
    fz_finite(f, v.y, what);
}

static void bounded(fz *f, double v, const char *what, uint32_t i)
{
    if (!(fabs(v) <= TT_DIVERGED)) fz_fail(f, "%s of particle %u is %s (past TT_DIVERGED)", what, i, fz_d(v));
}

static void check_particles(fz *f, tt_world *w)
{
    uint32_t n = tt_world_particle_count(w);
    double *xy = malloc(2 * (size_t)(n ? n : 1) * sizeof *xy);
    tt_particle *ids = malloc((n ? n : 1) * sizeof *ids);
    if (!xy || !ids) abort();
    if (tt_world_read_positions(w, xy, n) != n || tt_world_list_particles(w, ids, n) != n)
        fz_fail(f, "the bulk reads disagree with tt_world_particle_count (%u)", n);
    for (uint32_t i = 0; i < n; i++) {
        bounded(f, xy[2 * i], "x", i);
        bounded(f, xy[2 * i + 1], "y", i);
        tt_vec2 v;
        double m, r;
        if (tt_particle_get_velocity(w, ids[i], &v) != TT_OK || tt_particle_get_mass(w, ids[i], &m) != TT_OK ||
            tt_particle_get_radius(w, ids[i], &r) != TT_OK)
            fz_fail(f, "a handle from tt_world_list_particles is refused: %s", tt_last_error(w));
        bounded(f, v.x, "velocity x", i);
        bounded(f, v.y, "velocity y", i);
        if (!(m >= TT_MIN_MASS && m <= TT_MAX_MASS)) fz_fail(f, "mass of particle %u is %s", i, fz_d(m));
        fz_finite(f, r, "a radius");
    }
    free(xy);
    free(ids);
}

static void check_stats(fz *f, tt_world *w)
{
    tt_stats st;
    tt_energy en;
    tt_memory mem;
    tt_collision_stats cs;
    if (tt_world_get_stats(w, &st) != TT_OK || tt_world_get_energy(w, &en) != TT_OK ||
        tt_world_get_memory(w, &mem) != TT_OK || tt_world_get_collision_stats(w, &cs) != TT_OK)
        fz_fail(f, "a stats read of a live world failed: %s", tt_last_error(w));
    fz_finite(f, st.time, "stats.time");
    fz_finite(f, st.step_ms, "stats.step_ms");
    for (int i = 0; i < TT_STAGE_COUNT; i++) fz_finite(f, st.stage_ms[i], "stats.stage_ms");
    fz_finite(f, st.max_error, "stats.max_error");
    if (st.particles != tt_world_particle_count(w)) fz_fail(f, "stats.particles is %u", st.particles);
    fz_finite(f, en.kinetic, "energy.kinetic");
    fz_finite(f, en.gravity, "energy.gravity");
    fz_finite(f, en.spring, "energy.spring");
    fz_finite(f, en.constraint, "energy.constraint");
    fz_finite(f, en.total, "energy.total");
    fz_finite(f, mem.bytes_per_particle, "memory.bytes_per_particle");
    fz_finite(f, cs.broadphase_bytes_per_particle, "collision stats broadphase_bytes_per_particle");
    fz_finite(f, cs.broadphase_ms, "collision stats broadphase_ms");
}

static void check_links(fz *f, tt_world *w)
{
    uint32_t nl = tt_world_read_constraint_lines(w, NULL, 0);
    double *xy = malloc(4 * (size_t)(nl ? nl : 1) * sizeof *xy);
    if (!xy) abort();
    if (tt_world_read_constraint_lines(w, xy, nl) != nl) fz_fail(f, "constraint line count changed between reads");
    for (uint32_t i = 0; i < 4 * nl; i++) fz_finite(f, xy[i], "a constraint line");
    free(xy);
    uint32_t ns = tt_world_list_springs(w, NULL, 0);
    tt_spring *sp = malloc((ns ? ns : 1) * sizeof *sp);
    if (!sp) abort();
    tt_world_list_springs(w, sp, ns);
    for (uint32_t i = 0; i < ns; i++) {
        double len;
        if (tt_spring_get_length(w, sp[i], &len) != TT_OK) fz_fail(f, "a listed spring is refused");
        fz_finite(f, len, "a spring length");
    }
    free(sp);
    const tt_break_event *be;
    uint32_t nb;
    if (tt_world_get_break_events(w, &be, &nb) != TT_OK) fz_fail(f, "tt_world_get_break_events failed");
    for (uint32_t i = 0; i < nb; i++) {
        fz_finite(f, be[i].length, "a break event's length");
        fz_finite(f, be[i].strain, "a break event's strain");
    }
    uint32_t ne;
    const tt_contact_event *ce = tt_world_get_contact_events(w, &ne);
    for (uint32_t i = 0; i < ne; i++) {
        fz_finite_vec(f, ce[i].point, "a contact event's point");
        fz_finite_vec(f, ce[i].normal, "a contact event's normal");
        fz_finite(f, ce[i].impulse, "a contact event's impulse");
    }
}

/* The constraints and composites this fuzzer knows of in the world (the
 * API lists neither): each one still live is read. */
static void check_known(fz *f, tt_world *w, const fz_world *s)
{
    const fz_hlist *cl = &s->live[TT_KIND_CONSTRAINT];
    for (uint32_t i = 0; i < cl->n; i++) {
        double v;
        if (tt_constraint_get_error(w, FZ_C(cl->h[i]), &v) == TT_OK) fz_finite(f, v, "a constraint's error");
    }
    const fz_hlist *co = &s->live[TT_KIND_COMPOSITE];
    for (uint32_t i = 0; i < co->n; i++) {
        tt_vec2 c;
        double a;
        if (tt_composite_get_center(w, FZ_CO(co->h[i]), &c) == TT_OK) fz_finite_vec(f, c, "a composite's centre");
        if (tt_composite_get_angle(w, FZ_CO(co->h[i]), &a) == TT_OK) fz_finite(f, a, "a composite's angle");
    }
}

void fz_check_world(fz *f, tt_world *w)
{
    check_particles(f, w);
    check_stats(f, w);
    check_links(f, w);
    check_known(f, w, &f->slots[f->cur]);
}
