/* tether — particle pairs on, none near: the grid is not built again while
 * no two particles can have come within reach.
 *
 * When a substep had no contact at all, the next one first probes: a grid
 * with cells twice as wide, and a walk that looks for any two particles
 * (filters aside: layers, pins and sleep can change without a move) nearer
 * than their contact reach rs·(1 + margin) plus a gap, the cell the
 * ordinary build would use. Pairs in cells two apart are more than a wide
 * cell apart, so none is nearer than reach + gap. While the substeps after
 * move every particle only by integration (Verlet, no other group with
 * sweeps, no contact to push, no bullet, nothing moved or added by the
 * script: the world epoch), two particles close in on each other by at most
 * the spread of their displacements (x − x_old): its extents, summed over
 * the substeps, bound it. Below the gap (with room for rounding) no pair
 * can exist, which is what the ordinary build would find: results are
 * unchanged. A world falling as one never spreads and probes once; a probe
 * that finds something near waits longer each time before the next. The
 * probe itself runs in contact_detect.c (the grid is its business).
 *
 * Before a step under gravity alone (plain Verlet, constant dt, no damping,
 * no force, no shape, no fresh velocity), one pass over x and x − x_old
 * bounds the spreads of the whole step in advance: each substep adds the
 * same g·h² to every displacement, so their box only shifts, widened by the
 * rounding of x + d (relative to the largest |x|), and by the displacements
 * of particles held (pinned, asleep, removed: they may wake and start from
 * rest). When that bound holds through the last substep, the step finds no
 * pair whatever it does: no substep measures anything, and nothing can grow
 * inside the step, so the step's undo copies nothing (contact_undo.c). */
#include "collide_internal.h"

#include <float.h>

enum { PROBE_WAIT_MAX = 64 };

static bool eligible(const tt_world *w, const tt__collide *c)
{
    if (w->integrator != TT_VERLET || c->nbullets || c->set.broadphase != TT_BROADPHASE_GRID) return false;
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].self != c && w->groups[g].ops->relax) return false;
    return true;
}

typedef struct span {
    double lx, hx, ly, hy; /* the extents of x − x_old */
    double big;            /* the largest |x| or |y| */
    bool nan, held;        /* held: some particle has inverse mass 0 */
} span;

#ifdef TT_SIMD_X86
/* measure(), four particles at a time; returns how far it got. */
TT_AVX2 static uint32_t measure_avx2(const tt_world *w, uint32_t n, span *s)
{
    __m256d lx = _mm256_set1_pd(INFINITY), hx = _mm256_set1_pd(-INFINITY), ly = lx, hy = hx, nan = _mm256_setzero_pd();
    __m256d big = _mm256_setzero_pd(), held = nan;
    const __m256d sign = _mm256_set1_pd(-0.0), zero = nan;
    uint32_t i = 0;
    for (; i + 4 <= n; i += 4) {
        const __m256d x = _mm256_loadu_pd(w->px + i), y = _mm256_loadu_pd(w->py + i);
        const __m256d dx = _mm256_sub_pd(x, _mm256_loadu_pd(w->qx + i)), dy = _mm256_sub_pd(y, _mm256_loadu_pd(w->qy + i));
        lx = _mm256_min_pd(lx, dx), hx = _mm256_max_pd(hx, dx);
        ly = _mm256_min_pd(ly, dy), hy = _mm256_max_pd(hy, dy);
        nan = _mm256_or_pd(nan, _mm256_cmp_pd(dx, dy, _CMP_UNORD_Q));
        big = _mm256_max_pd(big, _mm256_max_pd(_mm256_andnot_pd(sign, x), _mm256_andnot_pd(sign, y)));
        held = _mm256_or_pd(held, _mm256_cmp_pd(_mm256_loadu_pd(w->inv_mass + i), zero, _CMP_EQ_OQ));
    }
    double t[5][4];
    _mm256_storeu_pd(t[0], lx), _mm256_storeu_pd(t[1], hx), _mm256_storeu_pd(t[2], ly), _mm256_storeu_pd(t[3], hy);
    _mm256_storeu_pd(t[4], big);
    for (int k = 0; k < 4; k++) {
        s->lx = fmin(s->lx, t[0][k]), s->hx = fmax(s->hx, t[1][k]);
        s->ly = fmin(s->ly, t[2][k]), s->hy = fmax(s->hy, t[3][k]);
        s->big = fmax(s->big, t[4][k]);
    }
    s->nan |= _mm256_movemask_pd(nan) != 0;
    s->held |= _mm256_movemask_pd(held) != 0;
    return i;
}
#endif

/* The extents of every displacement, the largest coordinate, and whether
 * some particle is held. A NaN displacement sets nan (then a NaN |x| too). */
static span measure(const tt_world *w, uint32_t n)
{
    span s = {INFINITY, -INFINITY, INFINITY, -INFINITY, 0.0, false, false};
    uint32_t i = 0;
#ifdef TT_SIMD_X86
    if (tt__simd_kind(TT__SIMD_AUTO) != TT__SIMD_SCALAR) i = measure_avx2(w, n, &s);
#endif
    for (; i < n; i++) {
        const double dx = w->px[i] - w->qx[i], dy = w->py[i] - w->qy[i];
        s.nan |= dx != dx || dy != dy;
        s.lx = fmin(s.lx, dx), s.hx = fmax(s.hx, dx);
        s.ly = fmin(s.ly, dy), s.hy = fmax(s.hy, dy);
        s.big = fmax(s.big, fmax(fabs(w->px[i]), fabs(w->py[i])));
        s.held |= w->inv_mass[i] == 0.0;
    }
    return s;
}

/* How much nearer any two particles can have come this substep: the
 * diagonal of the box round every displacement (INFINITY for a NaN). */
static double spread(const tt_world *w, uint32_t n)
{
    const span s = measure(w, n);
    if (s.nan) return INFINITY;
    return n ? hypot(s.hx - s.lx, s.hy - s.ly) : 0.0;
}

/* Whether two particles whose gap has closed by at most used are still
 * apart, with room for the rounding of the spreads summed into it. */
static bool still_clear(const tt__collide *c, double used)
{
    return used * (1.0 + 1e-9) + 1e-12 * (c->clear_scale + used) < c->clear_gap;
}

void tt__pairs_probed(tt_world *w, tt__collide *c, bool clear, bool bound, double gap, double scale)
{
    if (!clear) { /* something near: wait longer each time before the next probe */
        c->probe_fails = c->probe_fails * 2 + 1 < PROBE_WAIT_MAX ? c->probe_fails * 2 + 1 : PROBE_WAIT_MAX;
        c->probe_wait = c->probe_fails;
        return;
    }
    c->probe_fails = 0;
    c->clear_ok = bound;
    c->clear_gap = gap;
    c->clear_used = 0.0;
    c->clear_scale = scale;
    c->clear_epoch = w->epoch;
}

tt__pair_plan tt__pairs_skip(tt_world *w, tt__collide *c, uint32_t n)
{
    if (!eligible(w, c)) {
        c->clear_ok = false;
        return TT__PAIRS_BUILD;
    }
    if (c->clear_ok && w->epoch == c->clear_epoch) {
        if (c->step_clear && c->step_at == w->stats.steps) { /* tt__pairs_plan_step: the step is clear */
            if (w->scr.substep + 1 == w->scr.nsub) c->clear_used = c->step_used;
            return TT__PAIRS_NONE;
        }
        c->clear_used += spread(w, n);
        if (still_clear(c, c->clear_used)) return TT__PAIRS_NONE;
    }
    c->clear_ok = false;
    if (!c->quiet_last) return TT__PAIRS_BUILD;
    if (c->probe_wait) {
        c->probe_wait--;
        return TT__PAIRS_BUILD;
    }
    return TT__PAIRS_PROBE;
}

/* Substep k of the step (1…S) moves particle i by d_i + k·G + e, d_i its
 * displacement x − x_old as the step begins, G = g·h² the same for all and
 * |e| ≤ k·err (below); a held particle that wakes starts from rest: 0 to
 * k·G. So the box of substep k's displacements is the first's shifted,
 * widened by 2(k + 1)·err (once more for the rounding of x − x_old), and
 * for held particles stretched to hold 0 and k·G. */
static double step_spread(const span *s, double gx, double gy, double err, uint32_t k)
{
    double wx = s->hx - s->lx, wy = s->hy - s->ly;
    if (s->held) {
        wx = fmax(s->hx, 0.0) - fmin(s->lx, 0.0) + k * fabs(gx);
        wy = fmax(s->hy, 0.0) - fmin(s->ly, 0.0) + k * fabs(gy);
    }
    return hypot(wx + 2.0 * (k + 1) * err, wy + 2.0 * (k + 1) * err);
}

void tt__pairs_plan_step(tt_world *w, tt__collide *c, uint32_t n)
{
    const double h = w->scr.step_h;
    c->step_clear = false;
    if (!eligible(w, c) || !c->clear_ok || !c->quiet_last || w->epoch != c->clear_epoch) return;
    /* the integrator's lean loop every substep, and nothing else moves a particle: no contact, no wake by a shape */
    if (c->nprim || c->terr || c->any_moved || tt__has_forces(w) || w->damping != 0.0 || w->fixed_point != 0.0 ||
        w->fresh_count || h != w->dt_prev)
        return;
    const span s = measure(w, n);
    if (s.nan || n == 0) return;
    const uint32_t steps = w->scr.nsub;
    const double gx = w->gravity.x * h * h, gy = w->gravity.y * h * h; /* as the integrator rounds it */
    /* |d| ≤ a + 1 all step, |x| ≤ xm, so x − x_old, + G and x + d round by at most err a substep
     * (u·(|d| + |d + G| + |x + d|), with room); err·steps < 1 keeps the 1 m assumed */
    const double a = fmax(fmax(-s.lx, s.hx) + steps * fabs(gx), fmax(-s.ly, s.hy) + steps * fabs(gy));
    const double xm = s.big + steps * (a + 1.0);
    const double err = 2.0 * DBL_EPSILON * (xm + 8.0 * (a + 1.0));
    /* far from the divergence guard, which would stop a particle (a move the bound does not see) */
    if (!(a >= 0.0 && xm < 0.1 * TT_DIVERGED && a + 1.0 < 0.1 * TT_DIVERGED * h && err * steps < 0.5)) return;
    double used = c->clear_used;
    for (uint32_t k = 1; k <= steps; k++) used += step_spread(&s, gx, gy, err, k);
    if (!still_clear(c, used)) return;
    c->step_clear = true;
    c->step_at = w->stats.steps;
    c->step_used = used;
}
