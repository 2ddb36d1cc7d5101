/* tether — the integrators. Positions and the second state array (x_old for
 * Verlet, velocity for the rest) advance by dt; pinned and removed particles
 * (inverse mass 0) are skipped. A particle whose new |x| or |v| passes
 * TT_DIVERGED is stopped where it was, so no Inf or NaN ever enters a world. */
#include "internal.h"

#include <stdlib.h>

static inline bool too_big(double a, double b) { return !(fabs(a) <= TT_DIVERGED && fabs(b) <= TT_DIVERGED); }

static double damping_factor(const tt_world *w, double dt)
{
    double f = 1.0 - w->damping * dt;
    return f > 0.0 ? f : 0.0;
}

/* Accelerations for this step: NULL when gravity is all there is. */
static bool accel(tt_world *w, const double *x, const double *y, const double *vx, const double *vy,
                  double **ax, double **ay)
{
    *ax = tt__scratch(w, TT_SCRATCH_AX);
    *ay = tt__scratch(w, TT_SCRATCH_AY);
    if (!*ax || !*ay) return false;
    tt__eval_accel(w, x, y, vx, vy, *ax, *ay);
    return true;
}

/* A velocity set exactly at time t starts with x + v·dt + a·dt²/2 (a
 * Taylor step), which makes Verlet exact for constant acceleration. */
static void verlet_fresh(tt_world *w, const double *ax, const double *ay)
{
    const double h = 0.5 * w->dt_prev * w->dt_prev;
    for (uint32_t k = 0; k < w->fresh_count; k++) {
        uint32_t i = w->fresh[k];
        if (!(w->flags[i] & TT__PF_FRESH)) continue;
        w->flags[i] &= (uint16_t)~TT__PF_FRESH;
        if (w->inv_mass[i] == 0.0) continue;
        w->qx[i] += (ax ? ax[i] : w->gravity.x) * h;
        w->qy[i] += (ay ? ay[i] : w->gravity.y) * h;
    }
    w->fresh_count = 0;
}

/* Verlet on the fixed-point lattice (fixed_point.c): x and x_old are
 * multiples of q, the displacement is x − x_old (exact) plus a·dt² rounded
 * to the lattice, so every sum below is exact and the step can be undone
 * bit for bit. x_old off the lattice (a velocity set since the last step),
 * a changed dt or damping round the whole displacement instead: the
 * positions stay on the lattice, that one step is not reversible (nor is
 * damping ever). A particle whose step would leave the range is stopped. */
static uint32_t verlet_fixed(tt_world *w, double dt, const double *ax, const double *ay)
{
    const uint32_t n = w->ppool.count;
    double *px = w->px, *py = w->py, *qx = w->qx, *qy = w->qy;
    const double q = w->fixed_point, range = tt__fixed_range(w), dmax = fmin(2 * range, TT_DIVERGED * dt);
    const double r = dt / w->dt_prev, f = damping_factor(w, dt), dt2 = 0.5 * dt * (dt + w->dt_prev);
    const bool exact = r == 1.0 && f == 1.0;
    uint32_t bad = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (w->inv_mass[i] == 0.0) continue;
        const double x = px[i], y = py[i], gx = ax ? ax[i] : w->gravity.x, gy = ay ? ay[i] : w->gravity.y;
        double dx, dy;
        if (exact) {
            dx = tt__fixed_snap(q, x - qx[i]) + tt__fixed_snap(q, gx * dt * dt);
            dy = tt__fixed_snap(q, y - qy[i]) + tt__fixed_snap(q, gy * dt * dt);
        } else {
            dx = tt__fixed_snap(q, ((x - qx[i]) * r + gx * dt2) * f);
            dy = tt__fixed_snap(q, ((y - qy[i]) * r + gy * dt2) * f);
        }
        const double nx = x + dx, ny = y + dy;
        qx[i] = x;
        qy[i] = y;
        /* |dx| ≤ 2·range keeps x + dx exact; an inexact dx is past 4·range, so it is caught too */
        if (TT_UNLIKELY(!(fabs(dx) <= dmax && fabs(dy) <= dmax && fabs(nx) <= range && fabs(ny) <= range))) { bad++; continue; }
        px[i] = nx;
        py[i] = ny;
    }
    return bad;
}


/* --- Verlet when few particles feel a force --------------------------------
 * The only forces are springs, between a few particles (a rope elsewhere in
 * a world of debris): everyone else is integrated with gravity alone, as in
 * a world without springs, and the springs' ends one by one. Bit for bit
 * what the general loop gives: a particle no spring reaches has
 * acceleration g + w·wind with the wind ±0, which is g + wind exactly for
 * an inverse mass w > 0, and the general loop's ×r and ×f are exact when
 * they are 1. */

static bool few_forces(const tt_world *w)
{
    return w->integrator == TT_VERLET && w->fixed_point == 0.0 && w->springs_alive > 0 && !w->attractors_used && !w->forces_pending &&
           w->wind.x == 0.0 && w->wind.y == 0.0 && (uint64_t)w->springs_alive * 64 <= w->ppool.count;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* The springs' ends, sorted, each once; their accelerations into ax, ay,
 * as tt__eval_accel makes them. Returns how many. */
static uint32_t ends_accel(tt_world *w, double *ax, double *ay)
{
    double t0 = tt__now_ms();
    uint32_t k = 0;
    for (uint32_t s = 0; s < w->spool.count; s++)
        if (w->springs[s].alive) w->scr.ends[k++] = w->springs[s].a, w->scr.ends[k++] = w->springs[s].b;
    qsort(w->scr.ends, k, sizeof *w->scr.ends, cmp_u32);
    uint32_t m = 0;
    for (uint32_t j = 0; j < k; j++)
        if (m == 0 || w->scr.ends[j] != w->scr.ends[m - 1]) w->scr.ends[m++] = w->scr.ends[j];
    const double *inv = w->inv_mass;
    for (uint32_t j = 0; j < m; j++) {
        const uint32_t i = w->scr.ends[j];
        if (inv[i] == 0.0) ax[i] = ay[i] = 0.0;
        else ax[i] = w->gravity.x + inv[i] * w->wind.x, ay[i] = w->gravity.y + inv[i] * w->wind.y;
    }
    tt__springs_accel(w, w->px, w->py, NULL, NULL, ax, ay);
    w->stats.force_evaluations++;
    w->stats.stage_ms[TT_STAGE_FORCES] += tt__now_ms() - t0;
    return m;
}

/* Whether |dx/dt| or |dy/dt| passes the guard, dividing only near it (lo: half the limit times dt). */
static inline bool too_fast(double dx, double dy, double dt, double lo)
{
    return !(fabs(dx) <= lo && fabs(dy) <= lo) && too_big(dx / dt, dy / dt);
}

/* Particles [i0, i1) under the constant acceleration (cx, cy)·dt2 = (gx, gy). */
static uint32_t verlet_span(tt_world *w, uint32_t i0, uint32_t i1, double gx, double gy, double r, double f, double dt)
{
    double *px = w->px, *py = w->py, *qx = w->qx, *qy = w->qy;
    const double *inv = w->inv_mass;
    const double lo = 0.5 * TT_DIVERGED * dt;
    uint32_t bad = 0;
#define TT__SPAN(DX, DY)                                                                     \
    for (uint32_t i = i0; i < i1; i++) {                                                     \
        if (inv[i] == 0.0) continue;                                                         \
        double x = px[i], y = py[i];                                                         \
        double dx = DX, dy = DY, nx = x + dx, ny = y + dy;                                   \
        qx[i] = x;                                                                           \
        qy[i] = y;                                                                           \
        if (TT_UNLIKELY(too_big(nx, ny) || too_fast(dx, dy, dt, lo))) { bad++; continue; }   \
        px[i] = nx;                                                                          \
        py[i] = ny;                                                                          \
    }
    if (r == 1.0 && f == 1.0) TT__SPAN((x - qx[i]) + gx, (y - qy[i]) + gy) /* constant dt, no damping */
    else TT__SPAN(((x - qx[i]) * r + gx) * f, ((y - qy[i]) * r + gy) * f)
#undef TT__SPAN
    return bad;
}

static uint32_t verlet_few(tt_world *w, double dt)
{
    double *ax = tt__scratch(w, TT_SCRATCH_AX), *ay = tt__scratch(w, TT_SCRATCH_AY);
    if (!ax || !ay) return 0; /* reserved before the step: not reached */
    const uint32_t m = ends_accel(w, ax, ay), *ends = w->scr.ends;
    const double *inv = w->inv_mass;
    const double cx = w->gravity.x + w->wind.x, cy = w->gravity.y + w->wind.y;
    for (uint32_t k = 0; k < w->fresh_count; k++) { /* as in verlet() */
        uint32_t i = w->fresh[k];
        if (!(w->flags[i] & TT__PF_FRESH)) continue;
        w->flags[i] &= (uint16_t)~TT__PF_FRESH;
        if (inv[i] == 0.0) continue;
        const bool end = bsearch(&i, ends, m, sizeof *ends, cmp_u32) != NULL;
        double h = 0.5 * w->dt_prev * w->dt_prev;
        w->qx[i] += (end ? ax[i] : cx) * h;
        w->qy[i] += (end ? ay[i] : cy) * h;
    }
    w->fresh_count = 0;
    const double r = dt / w->dt_prev, f = damping_factor(w, dt), dt2 = 0.5 * dt * (dt + w->dt_prev);
    uint32_t bad = 0, from = 0;
    for (uint32_t j = 0; j < m; j++) {
        const uint32_t i = ends[j];
        bad += verlet_span(w, from, i, cx * dt2, cy * dt2, r, f, dt);
        bad += verlet_span(w, i, i + 1, ax[i] * dt2, ay[i] * dt2, r, f, dt);
        from = i + 1;
    }
    return bad + verlet_span(w, from, w->ppool.count, cx * dt2, cy * dt2, r, f, dt);
}

static uint32_t verlet(tt_world *w, double dt, bool forces)
{
    if (forces && few_forces(w) && w->scr.ends_cap >= 2 * w->springs_alive) return verlet_few(w, dt);
    const uint32_t n = w->ppool.count;
    double *px = w->px, *py = w->py, *qx = w->qx, *qy = w->qy;
    const double *inv = w->inv_mass;
    const double gx = w->gravity.x, gy = w->gravity.y;
    double *ax = NULL, *ay = NULL;
    if (forces && !accel(w, px, py, NULL, NULL, &ax, &ay)) forces = false;
    verlet_fresh(w, forces ? ax : NULL, forces ? ay : NULL);
    if (w->fixed_point != 0.0) return verlet_fixed(w, dt, forces ? ax : NULL, forces ? ay : NULL);

    /* Time-corrected Verlet: with dt ≠ dt_prev, x + (x − x_old)·dt/dt_prev +
     * a·dt·(dt + dt_prev)/2 stays exact for constant acceleration. */
    const double r = dt / w->dt_prev, f = damping_factor(w, dt), dt2 = 0.5 * dt * (dt + w->dt_prev);
    uint32_t bad = 0;
    if (!forces && r == 1.0 && f == 1.0) {
        /* The common case, kept as lean as a bare loop: constant dt, gravity only. */
        const double gdx = gx * dt * dt, gdy = gy * dt * dt, dmax = TT_DIVERGED * dt;
        for (uint32_t i = 0; i < n; i++) {
            if (inv[i] == 0.0) continue;
            double x = px[i], y = py[i];
            double dx = (x - qx[i]) + gdx, dy = (y - qy[i]) + gdy; /* small terms first: g·dt² keeps its bits */
            double nx = x + dx, ny = y + dy;
            qx[i] = x;
            qy[i] = y;
            /* |v| = |dx|/dt is checked without the division: the loop stays lean */
            if (TT_UNLIKELY(too_big(nx, ny) || !(fabs(dx) <= dmax && fabs(dy) <= dmax))) { bad++; continue; }
            px[i] = nx;
            py[i] = ny;
        }
        return bad;
    }
    for (uint32_t i = 0; i < n; i++) {
        if (inv[i] == 0.0) continue;
        double x = px[i], y = py[i];
        double dx = ((x - qx[i]) * r + (forces ? ax[i] : gx) * dt2) * f;
        double dy = ((y - qy[i]) * r + (forces ? ay[i] : gy) * dt2) * f;
        double nx = x + dx, ny = y + dy;
        qx[i] = x;
        qy[i] = y;
        if (TT_UNLIKELY(too_big(nx, ny) || too_big(dx / dt, dy / dt))) { bad++; continue; }
        px[i] = nx;
        py[i] = ny;
    }
    return bad;
}

/* Writes the new state of particle i, or stops it where it was. */
static inline uint32_t commit(double *px, double *py, double *vx, double *vy, uint32_t i,
                              double nx, double ny, double nvx, double nvy)
{
    if (TT_UNLIKELY(too_big(nx, ny) || too_big(nvx, nvy))) {
        vx[i] = vy[i] = 0.0;
        return 1;
    }
    px[i] = nx;
    py[i] = ny;
    vx[i] = nvx;
    vy[i] = nvy;
    return 0;
}

static uint32_t euler(tt_world *w, double dt, bool forces, bool symplectic)
{
    const uint32_t n = w->ppool.count;
    double *px = w->px, *py = w->py, *vx = w->qx, *vy = w->qy;
    double *ax = NULL, *ay = NULL;
    if (forces && !accel(w, px, py, vx, vy, &ax, &ay)) return 0;
    const double *inv = w->inv_mass;
    const double gx = w->gravity.x, gy = w->gravity.y, f = damping_factor(w, dt);
    /* Symplectic Euler's velocity after a step is the mean over that step,
     * so the kick spans the middle of the last step to the middle of this
     * one: the mean of the two lengths. A change of dt (the caller's, or
     * substeps by speed) then keeps a constant acceleration's samples on
     * their parabola, where v += a·dt jumped by a·(dt − dt_prev)/2. One dt:
     * (dt + dt)/2 = dt, the same bits. Before the world's first step there
     * is no last step (dt_prev is the hint): the plain kick. */
    const double kick = symplectic && w->stats.steps > 0 ? 0.5 * (dt + w->dt_prev) : dt;
    uint32_t bad = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (inv[i] == 0.0) continue;
        double nvx = vx[i] + (forces ? ax[i] : gx) * kick, nvy = vy[i] + (forces ? ay[i] : gy) * kick;
        if (symplectic) { /* damp, then drift with the new velocity: Verlet's twin */
            nvx *= f;
            nvy *= f;
            bad += commit(px, py, vx, vy, i, px[i] + nvx * dt, py[i] + nvy * dt, nvx, nvy);
        } else {
            bad += commit(px, py, vx, vy, i, px[i] + vx[i] * dt, py[i] + vy[i] * dt, nvx * f, nvy * f);
        }
    }
    return bad;
}

/* Velocity Verlet, kick-drift-kick: forces at both ends of the step. A
 * particle the guard stops goes back to where the step began, which the
 * drift cannot be undone to exactly (x + v·dt − v·dt loses x when v·dt is
 * huge): with gravity alone each particle is done in one pass, with forces
 * the start positions are kept aside. */
static uint32_t leapfrog_constant(tt_world *w, double dt)
{
    const uint32_t n = w->ppool.count;
    double *px = w->px, *py = w->py, *vx = w->qx, *vy = w->qy;
    const double *inv = w->inv_mass;
    const double gx = w->gravity.x, gy = w->gravity.y;
    const double h = 0.5 * dt, f = damping_factor(w, dt);
    uint32_t bad = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (inv[i] == 0.0) continue;
        double hvx = vx[i] + gx * h, hvy = vy[i] + gy * h;
        bad += commit(px, py, vx, vy, i, px[i] + hvx * dt, py[i] + hvy * dt, (hvx + gx * h) * f, (hvy + gy * h) * f);
    }
    return bad;
}

static uint32_t leapfrog(tt_world *w, double dt, bool forces)
{
    if (!forces) return leapfrog_constant(w, dt);
    const uint32_t n = w->ppool.count;
    double *px = w->px, *py = w->py, *vx = w->qx, *vy = w->qy;
    double *ax, *ay;
    double *sx = tt__scratch(w, TT_SCRATCH_RK4_FIRST), *sy = tt__scratch(w, TT_SCRATCH_RK4_FIRST + 1);
    if (!sx || !sy || !accel(w, px, py, vx, vy, &ax, &ay)) return 0;
    const double *inv = w->inv_mass;
    const double h = 0.5 * dt, f = damping_factor(w, dt);
    for (uint32_t i = 0; i < n; i++) {
        sx[i] = px[i];
        sy[i] = py[i];
        if (inv[i] == 0.0) continue;
        vx[i] += ax[i] * h;
        vy[i] += ay[i] * h;
        px[i] += vx[i] * dt;
        py[i] += vy[i] * dt;
    }
    tt__eval_accel(w, px, py, vx, vy, ax, ay);
    uint32_t bad = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (inv[i] == 0.0) continue;
        double nvx = (vx[i] + ax[i] * h) * f, nvy = (vy[i] + ay[i] * h) * f;
        if (TT_UNLIKELY(too_big(px[i], py[i]) || too_big(nvx, nvy))) {
            px[i] = sx[i];
            py[i] = sy[i];
            vx[i] = vy[i] = 0.0;
            bad++;
            continue;
        }
        vx[i] = nvx;
        vy[i] = nvy;
    }
    return bad;
}

static uint32_t rk4_constant(tt_world *w, double dt)
{
    const uint32_t n = w->ppool.count;
    double *px = w->px, *py = w->py, *vx = w->qx, *vy = w->qy;
    const double gx = w->gravity.x, gy = w->gravity.y, f = damping_factor(w, dt);
    const double hx = 0.5 * gx * dt * dt, hy = 0.5 * gy * dt * dt;
    uint32_t bad = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (w->inv_mass[i] == 0.0) continue;
        bad += commit(px, py, vx, vy, i, px[i] + vx[i] * dt + hx, py[i] + vy[i] * dt + hy,
                      (vx[i] + gx * dt) * f, (vy[i] + gy * dt) * f);
    }
    return bad;
}

/* With gravity alone the four stages collapse to x + v·dt + g·dt²/2, which
 * is what is computed then. */
static uint32_t rk4(tt_world *w, double dt, bool forces)
{
    if (!forces) return rk4_constant(w, dt);
    const uint32_t n = w->ppool.count;
    double *px = w->px, *py = w->py, *vx = w->qx, *vy = w->qy;
    double *s[8];
    for (int k = 0; k < 8; k++)
        if (!(s[k] = tt__scratch(w, TT_SCRATCH_RK4_FIRST + k))) return 0;
    double *tx = s[0], *ty = s[1], *tvx = s[2], *tvy = s[3]; /* stage state */
    double *sx = s[4], *sy = s[5], *svx = s[6], *svy = s[7]; /* weighted sums */
    double *ax, *ay;
    if (!accel(w, px, py, vx, vy, &ax, &ay)) return 0;
    const double *inv = w->inv_mass;
    const double h = 0.5 * dt;
    for (uint32_t i = 0; i < n; i++) {
        sx[i] = vx[i];
        sy[i] = vy[i];
        svx[i] = ax[i];
        svy[i] = ay[i];
        tx[i] = px[i] + vx[i] * h;
        ty[i] = py[i] + vy[i] * h;
        tvx[i] = vx[i] + ax[i] * h;
        tvy[i] = vy[i] + ay[i] * h;
    }
    for (int stage = 2; stage <= 3; stage++) {
        tt__eval_accel(w, tx, ty, tvx, tvy, ax, ay);
        double step = stage == 2 ? h : dt;
        for (uint32_t i = 0; i < n; i++) {
            double kvx = tvx[i], kvy = tvy[i];
            sx[i] += 2.0 * kvx;
            sy[i] += 2.0 * kvy;
            svx[i] += 2.0 * ax[i];
            svy[i] += 2.0 * ay[i];
            tx[i] = px[i] + kvx * step;
            ty[i] = py[i] + kvy * step;
            tvx[i] = vx[i] + ax[i] * step;
            tvy[i] = vy[i] + ay[i] * step;
        }
    }
    tt__eval_accel(w, tx, ty, tvx, tvy, ax, ay);
    const double sixth = dt / 6.0, f = damping_factor(w, dt);
    uint32_t bad = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (inv[i] == 0.0) continue;
        bad += commit(px, py, vx, vy, i, px[i] + sixth * (sx[i] + tvx[i]), py[i] + sixth * (sy[i] + tvy[i]),
                      (vx[i] + sixth * (svx[i] + ax[i])) * f, (vy[i] + sixth * (svy[i] + ay[i])) * f);
    }
    return bad;
}

bool tt__integrate_reserve(tt_world *w)
{
    if (!tt__has_forces(w)) return true; /* gravity alone needs no arrays */
    if (w->ppool.count == 0) return true; /* nothing to integrate: no arrays (tt__scratch gives NULL for none) */
    if (few_forces(w) && w->scr.ends_cap < 2 * w->springs_alive) {
        uint32_t *e = realloc(w->scr.ends, (size_t)w->spool.count * 2 * sizeof *e);
        if (!e) return false;
        w->scr.ends = e;
        w->scr.ends_cap = 2 * w->spool.count;
    }
    const int stages = w->integrator == TT_RK4 ? 8 : w->integrator == TT_LEAPFROG ? 2 : 0;
    if (!tt__scratch(w, TT_SCRATCH_AX) || !tt__scratch(w, TT_SCRATCH_AY)) return false;
    for (int k = 0; k < stages; k++)
        if (!tt__scratch(w, TT_SCRATCH_RK4_FIRST + k)) return false;
    return true;
}

void tt__integrate(tt_world *w, double dt)
{
    double t0 = tt__now_ms(), forces_before = w->stats.stage_ms[TT_STAGE_FORCES];
    bool forces = tt__has_forces(w);
    uint32_t bad;
    switch (w->integrator) {
    case TT_VERLET: bad = verlet(w, dt, forces); break;
    case TT_EULER: bad = euler(w, dt, forces, false); break;
    case TT_SYMPLECTIC_EULER: bad = euler(w, dt, forces, true); break;
    case TT_LEAPFROG: bad = leapfrog(w, dt, forces); break;
    case TT_RK4: bad = rk4(w, dt, forces); break;
    default: bad = 0; break;
    }
    w->stats.diverged += bad;
    /* the forces evaluated inside this call are their own stage: only this call's share is taken out */
    w->stats.stage_ms[TT_STAGE_INTEGRATE] += fmax(0.0, tt__now_ms() - t0 - (w->stats.stage_ms[TT_STAGE_FORCES] - forces_before));
}

/* Switching integrator keeps every particle's velocity: Verlet's x_old and
 * the others' v are two encodings of the same thing. */
void tt__convert_state(tt_world *w, tt_integrator from, tt_integrator to)
{
    if ((from == TT_VERLET) == (to == TT_VERLET)) return;
    const uint32_t n = w->ppool.count;
    const double dt = w->dt_prev;
    if (from == TT_VERLET) {
        for (uint32_t i = 0; i < n; i++) {
            w->qx[i] = (w->px[i] - w->qx[i]) / dt;
            w->qy[i] = (w->py[i] - w->qy[i]) / dt;
            w->flags[i] &= (uint16_t)~TT__PF_FRESH;
        }
        w->fresh_count = 0;
        w->integrator = to;
        return;
    }
    w->integrator = to;
    for (uint32_t i = 0; i < n; i++) {
        if (!(w->flags[i] & TT__PF_ALIVE)) continue;
        tt__set_velocity(w, i, (tt_vec2){w->qx[i], w->qy[i]});
    }
}
