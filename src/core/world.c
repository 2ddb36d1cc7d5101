/* tether — the world: creation, settings, the step pipeline, stats. */
#include "internal.h"
#include "spin.h"

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *tt_version(void) { return TT_VERSION_STRING; }

const char *tt_result_string(tt_result r)
{
    switch (r) {
    case TT_OK: return "ok";
    case TT_EINVAL: return "invalid argument";
    case TT_ESTALE: return "stale handle";
    case TT_ENOMEM: return "out of memory or over a limit";
    case TT_ESTATE: return "not valid in this state";
    }
    return "unknown result";
}

static const char *const integrator_names[TT_INTEGRATOR_COUNT] = {
    "euler", "symplectic_euler", "leapfrog", "verlet", "rk4"};

const char *tt_integrator_name(tt_integrator i)
{
    return (unsigned)i < TT_INTEGRATOR_COUNT ? integrator_names[i] : "unknown";
}

tt_result tt_integrator_from_name(const char *name, tt_integrator *out)
{
    if (!name || !out) return tt__fail(NULL, TT_EINVAL, "tt_integrator_from_name: NULL argument");
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++)
        if (strcmp(name, integrator_names[i]) == 0) {
            *out = (tt_integrator)i;
            return TT_OK;
        }
    return tt__fail(NULL, TT_EINVAL, "invalid integrator '%s', expected one of: 'euler', "
                    "'symplectic_euler', 'leapfrog', 'verlet', 'rk4'", name);
}

tt_world_def tt_world_def_default(void)
{
    tt_world_def d;
    memset(&d, 0, sizeof d);
    d.gravity = (tt_vec2){0.0, -9.81};
    d.integrator = TT_VERLET;
    d.damping = 0.0;
    d.wind = (tt_vec2){0.0, 0.0};
    d.dt_hint = 1.0 / 60.0;
    d.capacity = 0;
    d.max_particles = 1u << 24;
    d.substeps = 1;
    d.max_substeps = TT__MAX_SUBSTEPS_DEFAULT;
    d.iterations = 10;
    d.tolerance = 1e-6;
    d.order = TT_GAUSS_SEIDEL;
    d.sleep = true;
    d.sleep_speed = 0.01; /* Box2D's linear sleep tolerance; a 1 cm rest window with sleep_time (sleep_rest.c rest_one) */
    d.sleep_time = 1.0;
    return d;
}

static tt_result check_dt(const tt_world *w, double dt, const char *fn)
{
    if (!(dt >= TT_MIN_DT && dt <= TT_MAX_DT))
        return tt__fail(w, TT_EINVAL, "%s: dt must be in [%g, %g] s, got %g", fn, TT_MIN_DT, TT_MAX_DT, dt);
    return TT_OK;
}

tt_world *tt_world_create(const tt_world_def *def)
{
    tt_world_def d = def ? *def : tt_world_def_default();
    const char *fn = "tt_world_create";
    if (!tt__vec_ok(d.gravity)) { tt__fail(NULL, TT_EINVAL, "%s: gravity must be finite, |g| <= %g", fn, TT_MAX_VALUE); return NULL; }
    if (!tt__vec_ok(d.wind)) { tt__fail(NULL, TT_EINVAL, "%s: wind must be finite, |f| <= %g", fn, TT_MAX_VALUE); return NULL; }
    if (!tt__in_range(d.damping, 0.0, TT_MAX_VALUE)) { tt__fail(NULL, TT_EINVAL, "%s: damping must be in [0, %g], got %g", fn, TT_MAX_VALUE, d.damping); return NULL; }
    if ((unsigned)d.integrator >= TT_INTEGRATOR_COUNT) { tt__fail(NULL, TT_EINVAL, "%s: unknown integrator %d", fn, (int)d.integrator); return NULL; }
    if (check_dt(NULL, d.dt_hint, fn) != TT_OK) return NULL;
    if (d.max_particles == 0 || d.max_particles > TT_HANDLE_MAX_SLOTS) { tt__fail(NULL, TT_EINVAL, "%s: max_particles must be in [1, 2^24]", fn); return NULL; }
    if (d.substeps < 1 || d.substeps > TT_MAX_SUBSTEPS) { tt__fail(NULL, TT_EINVAL, "%s: substeps must be in [1, %d], got %u", fn, TT_MAX_SUBSTEPS, d.substeps); return NULL; }
    if (!tt__in_range(d.max_travel, 0.0, TT_MAX_VALUE)) { tt__fail(NULL, TT_EINVAL, "%s: max_travel must be in [0, %g], got %g", fn, TT_MAX_VALUE, d.max_travel); return NULL; }
    if (d.max_substeps == 0) d.max_substeps = TT__MAX_SUBSTEPS_DEFAULT; /* a def zeroed by hand, from before the field */
    if (d.max_substeps > TT_MAX_SUBSTEPS) { tt__fail(NULL, TT_EINVAL, "%s: max_substeps must be in [1, %d] (0: %u), got %u", fn, TT_MAX_SUBSTEPS, TT__MAX_SUBSTEPS_DEFAULT, d.max_substeps); return NULL; }
    if (d.iterations < 1 || d.iterations > TT_MAX_ITERATIONS) { tt__fail(NULL, TT_EINVAL, "%s: iterations must be in [1, %d], got %u", fn, TT_MAX_ITERATIONS, d.iterations); return NULL; }
    if (!tt__in_range(d.tolerance, 0.0, TT_MAX_VALUE)) { tt__fail(NULL, TT_EINVAL, "%s: tolerance must be in [0, %g], got %g", fn, TT_MAX_VALUE, d.tolerance); return NULL; }
    if (d.order != TT_GAUSS_SEIDEL && d.order != TT_JACOBI) { tt__fail(NULL, TT_EINVAL, "%s: unknown solver order %d", fn, (int)d.order); return NULL; }
    if (d.sleep && !(tt__in_range(d.sleep_speed, 0.0, TT_MAX_VALUE) && tt__in_range(d.sleep_time, 0.0, TT_MAX_VALUE))) { tt__fail(NULL, TT_EINVAL, "%s: sleep_speed and sleep_time must be in [0, %g]", fn, TT_MAX_VALUE); return NULL; }
    if (d.fixed_point != 0.0 && !tt__fixed_quantum_ok(d.fixed_point)) { tt__fail(NULL, TT_EINVAL, "%s: fixed_point must be 0 (off) or a power of two 2^-k, k = 1…60, got %g", fn, d.fixed_point); return NULL; }
    if (d.fixed_point != 0.0 && d.integrator != TT_VERLET) { tt__fail(NULL, TT_EINVAL, "%s: fixed_point needs the 'verlet' integrator (the others keep a velocity, not a position on the lattice)", fn); return NULL; }
    if (d.capacity > d.max_particles) { tt__fail(NULL, TT_EINVAL, "%s: capacity %u is over max_particles %u", fn, d.capacity, d.max_particles); return NULL; }

    tt_world *w = calloc(1, sizeof *w);
    if (!w) { tt__fail(NULL, TT_ENOMEM, "%s: out of memory", fn); return NULL; }
    /* Worlds take tags 1…TT_POOL_MAX_TAG in turn; handles carry it, so a
     * handle used on the wrong world is refused as stale. Not simulation
     * state: hashes mask it. */
    static atomic_uint next_tag;
    w->tag = atomic_fetch_add(&next_tag, 1) % TT_POOL_MAX_TAG + 1;
    w->ppool.tag = w->spool.tag = w->tag;
    w->springs_detach = tt__springs_detach;
    w->gravity = d.gravity;
    w->wind = d.wind;
    w->damping = d.damping;
    w->integrator = d.integrator;
    w->dt_prev = d.dt_hint;
    w->max_particles = d.max_particles;
    w->substeps = d.substeps;
    w->max_travel = d.max_travel;
    w->max_substeps = d.max_substeps;
    w->iterations = d.iterations;
    w->tolerance = d.tolerance;
    w->order = d.order;
    w->fixed_point = d.fixed_point;
    if (d.capacity && tt__particles_reserve(w, d.capacity) != TT_OK) {
        tt__fail(NULL, TT_ENOMEM, "%s: cannot reserve %u particles", fn, d.capacity);
        tt_world_destroy(w);
        return NULL;
    }
    if (d.sleep && !tt__sleep_enable(w, d.sleep_speed, d.sleep_time)) {
        tt__fail(NULL, TT_ENOMEM, "%s: out of memory for sleeping", fn);
        tt_world_destroy(w);
        return NULL;
    }
    if (d.spin && !tt__spin_enable(w)) {
        tt__fail(NULL, TT_ENOMEM, "%s: out of memory for spin", fn);
        tt_world_destroy(w);
        return NULL;
    }
    return w;
}

void tt_world_destroy(tt_world *w)
{
    if (!w) return;
    if (w->journal) w->journal_hooks->gone(w->journal);
    tt__solver_free(w);
    tt__particles_free(w);
    tt__springs_free(w);
    tt__world_scratch_free(w);
    free(w);
}

void tt__world_scratch_free(tt_world *w)
{
    tt__world_scratch *s = &w->scr;
    for (int k = 0; k < TT_SCRATCH_COUNT; k++) free(s->buf[k]);
    free(s->jx); free(s->jy); free(s->jn);
    free(s->bx); free(s->by); free(s->rows);
    free(s->ends);
    tt__undo_free(w);
    *s = (tt__world_scratch){0};
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->scratch_free) w->groups[g].ops->scratch_free(w, w->groups[g].self);
}

/* The pipeline, top to bottom. Each stage runs only if the world uses it;
 * later features (collide, solve, events) slot in at the marked places. */
tt_result tt_world_step(tt_world *w, double dt)
{
    TT_CHECK_WORLD(w, "tt_world_step");
    tt_result r = check_dt(w, dt, "tt_world_step");
    if (r != TT_OK) return r;
    /* the world as the calls left it, before the step's own preparations touch it */
    if (w->journal) w->journal_hooks->before(w->journal, w);
    /* Everything the step's counts call for, before anything changes. */
    const uint32_t nsub = w->scr.nsub = tt__travel_substeps(w, dt);
    const double h = w->scr.step_h = dt / nsub;
    if (!tt__integrate_reserve(w) || !tt__solver_reserve(w) || !tt__undo_reserve(w))
        return tt__fail(w, TT_ENOMEM, "tt_world_step: out of memory before the step; the world is as it was");
    w->scr.step_oom = NULL;
    tt__undo_mark(w); /* what the step changes, where it may run out of memory half way */
    if (w->ox && !w->scr.undo.on) tt__interp_step_begin(w);

    double t0 = tt__now_ms();
    memset(w->stats.stage_ms, 0, sizeof w->stats.stage_ms);
    w->stats.force_evaluations = 0;
    w->stats.diverged = 0;
    w->stats.iterations = 0;
    w->stats.max_error = 0.0;

    for (uint32_t s = 0; s < nsub; s++) {
        w->scr.substep = s;
        tt__integrate(w, h); /* forces are evaluated inside, as often as the integrator needs */
        w->dt_prev = h;      /* from here on x − x_old spans h: velocity reads inside the solve are exact */
        tt__solve(w, h);     /* detect → relax → velocity pass; nothing when no group is registered */
        if (w->fixed_point != 0.0 && w->group_count) tt__fixed_after_solve(w);
        if (w->scr.step_oom) break; /* the rest would be undone */
    }
    if (!w->scr.step_oom && !tt__undo_after_reserve(w)) tt__step_oom(w, "the step's events");
    if (w->scr.step_oom) {
        tt__undo_restore(w);
        return tt__fail(w, TT_ENOMEM, "tt_world_step: out of memory inside the step for %s; the world is as it "
                        "was before the step", w->scr.step_oom);
    }
    if (w->ox && w->scr.undo.on) { /* the positions as the step began, kept in the undo */
        tt__copy(w->ox, w->scr.undo.px, (size_t)w->ppool.count * sizeof *w->ox);
        tt__copy(w->oy, w->scr.undo.py, (size_t)w->ppool.count * sizeof *w->oy);
    }
    w->scr.undo.on = false; /* nothing after this can fail */
    tt__solver_after_step(w); /* events, gathered outside every loop */

    if (w->forces_pending) {
        tt__zero(w->fx, (size_t)w->ppool.count * sizeof *w->fx);
        tt__zero(w->fy, (size_t)w->ppool.count * sizeof *w->fy);
        w->forces_pending = false;
    }
    w->stats.steps++;
    w->stats.time += dt;
    w->stats.substeps = nsub;
    w->epoch++;
    w->stats.step_ms = tt__now_ms() - t0;
    if (w->journal) w->journal_hooks->after(w->journal, w, dt);
    if (w->stats.diverged)
        tt__fail(w, TT_OK, "tt_world_step: %u particle(s) passed |x| or |v| > %g and were stopped",
                 w->stats.diverged, TT_DIVERGED);
    return TT_OK;
}

tt_result tt_world_set_gravity(tt_world *w, tt_vec2 g)
{
    TT_CHECK_WORLD(w, "tt_world_set_gravity");
    if (!tt__vec_ok(g)) return tt__fail(w, TT_EINVAL, "tt_world_set_gravity: gravity must be finite, |g| <= %g", TT_MAX_VALUE);
    w->gravity = g;
    return TT_OK;
}

tt_vec2 tt_world_get_gravity(const tt_world *w) { return w ? w->gravity : (tt_vec2){0, 0}; }

tt_result tt_world_set_wind(tt_world *w, tt_vec2 f)
{
    TT_CHECK_WORLD(w, "tt_world_set_wind");
    if (!tt__vec_ok(f)) return tt__fail(w, TT_EINVAL, "tt_world_set_wind: wind must be finite, |f| <= %g", TT_MAX_VALUE);
    w->wind = f;
    return TT_OK;
}

tt_vec2 tt_world_get_wind(const tt_world *w) { return w ? w->wind : (tt_vec2){0, 0}; }

tt_result tt_world_set_damping(tt_world *w, double damping)
{
    TT_CHECK_WORLD(w, "tt_world_set_damping");
    if (!tt__in_range(damping, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "tt_world_set_damping: damping must be in [0, %g], got %g", TT_MAX_VALUE, damping);
    w->damping = damping;
    return TT_OK;
}

double tt_world_get_damping(const tt_world *w) { return w ? w->damping : 0.0; }

tt_result tt_world_set_integrator(tt_world *w, tt_integrator i)
{
    TT_CHECK_WORLD(w, "tt_world_set_integrator");
    if ((unsigned)i >= TT_INTEGRATOR_COUNT)
        return tt__fail(w, TT_EINVAL, "tt_world_set_integrator: unknown integrator %d", (int)i);
    if (i == w->integrator) return TT_OK;
    if (w->fixed_point != 0.0)
        return tt__fail(w, TT_ESTATE, "tt_world_set_integrator: a fixed_point world keeps the 'verlet' integrator (the others keep a velocity, not a position on the lattice)");
    tt__convert_state(w, w->integrator, i);
    w->integrator = i;
    return TT_OK;
}

tt_integrator tt_world_get_integrator(const tt_world *w) { return w ? w->integrator : TT_VERLET; }

tt_result tt_world_set_substeps(tt_world *w, uint32_t substeps)
{
    TT_CHECK_WORLD(w, "tt_world_set_substeps");
    if (substeps < 1 || substeps > TT_MAX_SUBSTEPS)
        return tt__fail(w, TT_EINVAL, "tt_world_set_substeps: substeps must be in [1, %d], got %u", TT_MAX_SUBSTEPS, substeps);
    w->substeps = substeps;
    return TT_OK;
}

uint32_t tt_world_get_substeps(const tt_world *w) { return w ? w->substeps : 1; }

tt_result tt_world_set_travel(tt_world *w, double max_travel, uint32_t max_substeps)
{
    TT_CHECK_WORLD(w, "tt_world_set_travel");
    if (!tt__in_range(max_travel, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "tt_world_set_travel: max_travel must be in [0, %g], got %g", TT_MAX_VALUE, max_travel);
    if (max_substeps < 1 || max_substeps > TT_MAX_SUBSTEPS)
        return tt__fail(w, TT_EINVAL, "tt_world_set_travel: max_substeps must be in [1, %d], got %u", TT_MAX_SUBSTEPS, max_substeps);
    w->max_travel = max_travel;
    w->max_substeps = max_substeps;
    return TT_OK;
}

double tt_world_get_travel(const tt_world *w, uint32_t *max_substeps)
{
    if (max_substeps) *max_substeps = w ? w->max_substeps : TT__MAX_SUBSTEPS_DEFAULT;
    return w ? w->max_travel : 0.0;
}

tt_result tt_world_set_iterations(tt_world *w, uint32_t iterations)
{
    TT_CHECK_WORLD(w, "tt_world_set_iterations");
    if (iterations < 1 || iterations > TT_MAX_ITERATIONS)
        return tt__fail(w, TT_EINVAL, "tt_world_set_iterations: iterations must be in [1, %d], got %u", TT_MAX_ITERATIONS, iterations);
    w->iterations = iterations;
    return TT_OK;
}

uint32_t tt_world_get_iterations(const tt_world *w) { return w ? w->iterations : 10; }

tt_result tt_world_set_tolerance(tt_world *w, double tolerance)
{
    TT_CHECK_WORLD(w, "tt_world_set_tolerance");
    if (!tt__in_range(tolerance, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "tt_world_set_tolerance: tolerance must be in [0, %g], got %g", TT_MAX_VALUE, tolerance);
    w->tolerance = tolerance;
    return TT_OK;
}

double tt_world_get_tolerance(const tt_world *w) { return w ? w->tolerance : 1e-6; }

tt_result tt_world_set_solver_order(tt_world *w, tt_solver_order order)
{
    TT_CHECK_WORLD(w, "tt_world_set_solver_order");
    if (order != TT_GAUSS_SEIDEL && order != TT_JACOBI)
        return tt__fail(w, TT_EINVAL, "tt_world_set_solver_order: unknown order %d", (int)order);
    w->order = order;
    return TT_OK;
}

tt_solver_order tt_world_get_solver_order(const tt_world *w) { return w ? w->order : TT_GAUSS_SEIDEL; }

tt_result tt_world_set_sleep(tt_world *w, bool on, double speed, double time)
{
    TT_CHECK_WORLD(w, "tt_world_set_sleep");
    if (!on) {
        tt__sleep_disable(w);
        return TT_OK;
    }
    if (!tt__in_range(speed, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "tt_world_set_sleep: speed must be in [0, %g], got %g", TT_MAX_VALUE, speed);
    if (!tt__in_range(time, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "tt_world_set_sleep: time must be in [0, %g], got %g", TT_MAX_VALUE, time);
    if (!tt__sleep_enable(w, speed, time)) return tt__fail(w, TT_ENOMEM, "tt_world_set_sleep: out of memory");
    return TT_OK;
}

bool tt_world_get_sleep(const tt_world *w, double *speed, double *time)
{
    double s = 0.0, t = 0.0;
    bool on = w && tt__sleep_get(w, &s, &t);
    if (speed) *speed = s;
    if (time) *time = t;
    return on;
}

tt_result tt_world_get_stats(const tt_world *w, tt_stats *out)
{
    TT_CHECK_WORLD(w, "tt_world_get_stats");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_world_get_stats: out is NULL");
    *out = w->stats;
    out->particles = w->alive;
    out->springs = w->springs_alive;
    out->sleeping = tt__sleep_count(w);
    return TT_OK;
}

tt_result tt_world_get_energy(const tt_world *w, tt_energy *out)
{
    TT_CHECK_WORLD(w, "tt_world_get_energy");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_world_get_energy: out is NULL");
    double ke = 0.0, pe = 0.0;
    for (uint32_t i = 0; i < w->ppool.count; i++) {
        if ((w->flags[i] & (TT__PF_ALIVE | TT__PF_PINNED)) != TT__PF_ALIVE) continue; /* pinned or removed (a sleeper counts) */
        tt_vec2 v = tt__velocity(w, i);
        double m = w->mass[i];
        ke += 0.5 * m * (v.x * v.x + v.y * v.y);
        pe -= m * (w->gravity.x * w->px[i] + w->gravity.y * w->py[i]);
    }
    const tt__spin *sp = tt__spin_peek(w); /* a turning disc's own: ½·(m r²/2)·ω² */
    for (uint32_t i = 0; sp && i < w->ppool.count && i < sp->cap; i++)
        if ((w->flags[i] & (TT__PF_ALIVE | TT__PF_PINNED)) == TT__PF_ALIVE && sp->omega[i] != 0.0)
            ke += 0.25 * w->mass[i] * (double)w->radius[i] * w->radius[i] * sp->omega[i] * sp->omega[i];
    out->kinetic = ke;
    out->gravity = pe;
    out->spring = tt__springs_energy(w);
    out->constraint = tt__constraints_energy(w);
    out->attractor = tt__attractors_energy(w);
    out->total = ke + pe + out->spring + out->constraint + out->attractor;
    return TT_OK;
}

tt_result tt_world_get_memory(const tt_world *w, tt_memory *out)
{
    TT_CHECK_WORLD(w, "tt_world_get_memory");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_world_get_memory: out is NULL");
    /* x, y, x_old|vx, y_old|vy, inverse mass, mass, radius, flags, category, mask */
    size_t per = 6 * sizeof(double) + sizeof(float) + 3 * sizeof(uint16_t);
    if (w->fx) per += 2 * sizeof(double);
    if (w->user) per += sizeof(uint64_t);
    if (w->ox) per += 2 * sizeof(double);
    size_t particles = per * w->pcap + tt__pool_bytes(&w->ppool);
    size_t total = sizeof *w + particles;
    for (int k = 0; k < TT_SCRATCH_COUNT; k++) total += (size_t)w->scr.buf_cap[k] * sizeof(double);
    total += (size_t)w->fresh_cap * sizeof(uint32_t) + (size_t)w->scr.ends_cap * sizeof(uint32_t);
    total += (size_t)w->scap * sizeof(tt__spring) + tt__pool_bytes(&w->spool);
    total += tt__solver_memory(w) + tt__undo_bytes(w);
    out->total = total;
    out->particles = particles;
    out->capacity = w->pcap;
    out->bytes_per_particle = w->pcap ? (double)particles / w->pcap : (double)per;
    return TT_OK;
}
