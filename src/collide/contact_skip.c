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
 * probe itself runs in contact_detect.c (the grid is its business). */
#include "collide_internal.h"

enum { PROBE_WAIT_MAX = 64 };

static bool eligible(const tt_world *w, const tt__collide *c)
{
    if (w->integrator != TT_VERLET || c->nbullets || c->set.broadphase != TT_BROADPHASE_GRID) return false;
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].self != c && w->groups[g].ops->relax) return false;
    return true;
}

typedef struct span {
    double lx, hx, ly, hy;
    bool nan;
} span;

#ifdef TT_SIMD_X86
/* The extents of (x − x_old), four particles at a time; returns how far it got. */
TT_AVX2 static uint32_t spread_avx2(const tt_world *w, uint32_t n, span *s)
{
    __m256d lx = _mm256_set1_pd(INFINITY), hx = _mm256_set1_pd(-INFINITY), ly = lx, hy = hx, nan = _mm256_setzero_pd();
    uint32_t i = 0;
    for (; i + 4 <= n; i += 4) {
        const __m256d dx = _mm256_sub_pd(_mm256_loadu_pd(w->px + i), _mm256_loadu_pd(w->qx + i));
        const __m256d dy = _mm256_sub_pd(_mm256_loadu_pd(w->py + i), _mm256_loadu_pd(w->qy + i));
        lx = _mm256_min_pd(lx, dx), hx = _mm256_max_pd(hx, dx);
        ly = _mm256_min_pd(ly, dy), hy = _mm256_max_pd(hy, dy);
        nan = _mm256_or_pd(nan, _mm256_cmp_pd(dx, dy, _CMP_UNORD_Q));
    }
    double t[4][4];
    _mm256_storeu_pd(t[0], lx), _mm256_storeu_pd(t[1], hx), _mm256_storeu_pd(t[2], ly), _mm256_storeu_pd(t[3], hy);
    for (int k = 0; k < 4; k++) {
        s->lx = fmin(s->lx, t[0][k]), s->hx = fmax(s->hx, t[1][k]);
        s->ly = fmin(s->ly, t[2][k]), s->hy = fmax(s->hy, t[3][k]);
    }
    s->nan |= _mm256_movemask_pd(nan) != 0;
    return i;
}
#endif

/* How much nearer any two particles can have come this substep: the
 * diagonal of the box round every displacement (INFINITY for a NaN). */
static double spread(const tt_world *w, uint32_t n)
{
    span s = {INFINITY, -INFINITY, INFINITY, -INFINITY, false};
    uint32_t i = 0;
#ifdef TT_SIMD_X86
    if (tt__simd_kind(TT__SIMD_AUTO) != TT__SIMD_SCALAR) i = spread_avx2(w, n, &s);
#endif
    for (; i < n; i++) {
        const double dx = w->px[i] - w->qx[i], dy = w->py[i] - w->qy[i];
        s.nan |= dx != dx || dy != dy;
        s.lx = fmin(s.lx, dx), s.hx = fmax(s.hx, dx);
        s.ly = fmin(s.ly, dy), s.hy = fmax(s.hy, dy);
    }
    if (s.nan) return INFINITY;
    return n ? hypot(s.hx - s.lx, s.hy - s.ly) : 0.0;
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
        c->clear_used += spread(w, n);
        if (c->clear_used * (1.0 + 1e-9) + 1e-12 * (c->clear_scale + c->clear_used) < c->clear_gap) return TT__PAIRS_NONE;
    }
    c->clear_ok = false;
    if (!c->quiet_last) return TT__PAIRS_BUILD;
    if (c->probe_wait) {
        c->probe_wait--;
        return TT__PAIRS_BUILD;
    }
    return TT__PAIRS_PROBE;
}
