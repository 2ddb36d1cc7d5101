/* tether — whether any particle can reach a static shape this substep: a
 * world with shapes far from every particle (a level's walls off screen, a
 * shape 1e6 m away) then prepares nothing for them (contact_detect.c).
 *
 * The full answer is a bounding box of every particle against the static
 * index. Most substeps need less: the static shapes lie on one side of the
 * particles (left, right, below or above), and the side that separated them
 * last time nearly always does again, so the one extreme of one coordinate
 * on that side is read first (a vector max or min over one array, under an
 * instruction a particle), and the box only when that does not separate. A
 * NaN position cannot touch anything: every extreme ignores it. */
#include "collide_internal.h"
#include "terrain_internal.h"

#ifdef __SSE2__
#include <emmintrin.h>
#endif

enum { SIDE_LEFT, SIDE_RIGHT, SIDE_BELOW, SIDE_ABOVE }; /* where the particles lie, seen from the shapes */

#ifdef TT_SIMD_X86
/* Largest (hi) or smallest of v[0..n), sixteen at a time; *done says how far. */
TT_AVX2 static double extreme_avx2(const double *v, uint32_t n, bool hi, uint32_t *done)
{
    __m256d a = _mm256_set1_pd(hi ? -INFINITY : INFINITY), b = a, c = a, d = a;
    uint32_t i = 0;
    if (hi)
        for (; i + 16 <= n; i += 16) { /* a NaN in the first operand gives the second */
            a = _mm256_max_pd(_mm256_loadu_pd(v + i), a);
            b = _mm256_max_pd(_mm256_loadu_pd(v + i + 4), b);
            c = _mm256_max_pd(_mm256_loadu_pd(v + i + 8), c);
            d = _mm256_max_pd(_mm256_loadu_pd(v + i + 12), d);
        }
    else
        for (; i + 16 <= n; i += 16) {
            a = _mm256_min_pd(_mm256_loadu_pd(v + i), a);
            b = _mm256_min_pd(_mm256_loadu_pd(v + i + 4), b);
            c = _mm256_min_pd(_mm256_loadu_pd(v + i + 8), c);
            d = _mm256_min_pd(_mm256_loadu_pd(v + i + 12), d);
        }
    double t[16];
    _mm256_storeu_pd(t, a);
    _mm256_storeu_pd(t + 4, b);
    _mm256_storeu_pd(t + 8, c);
    _mm256_storeu_pd(t + 12, d);
    double e = t[0];
    for (int k = 1; k < 16; k++) e = hi ? fmax(e, t[k]) : fmin(e, t[k]);
    *done = i;
    return e;
}

TT_AVX2 static float max_radius_avx2(const float *r, uint32_t n, uint32_t *done)
{
    __m256 a = _mm256_setzero_ps(), b = a, c = a, d = a;
    uint32_t i = 0;
    for (; i + 32 <= n; i += 32) {
        a = _mm256_max_ps(_mm256_loadu_ps(r + i), a);
        b = _mm256_max_ps(_mm256_loadu_ps(r + i + 8), b);
        c = _mm256_max_ps(_mm256_loadu_ps(r + i + 16), c);
        d = _mm256_max_ps(_mm256_loadu_ps(r + i + 24), d);
    }
    float t[8];
    _mm256_storeu_ps(t, _mm256_max_ps(_mm256_max_ps(a, b), _mm256_max_ps(c, d)));
    float m = 0.0f;
    for (int k = 0; k < 8; k++) m = fmaxf(m, t[k]);
    *done = i;
    return m;
}
#endif

static bool wide(void)
{
#ifdef TT_SIMD_X86
    return tt__simd_kind(TT__SIMD_AUTO) != TT__SIMD_SCALAR;
#else
    return false;
#endif
}

/* min and max are exact, so every path gives the same extreme. */
static double extreme(const double *v, uint32_t n, bool hi)
{
    uint32_t i = 0;
    double e = hi ? -INFINITY : INFINITY;
#ifdef TT_SIMD_X86
    if (wide()) e = extreme_avx2(v, n, hi, &i);
#endif
    for (; i < n; i++) e = hi ? fmax(e, v[i]) : fmin(e, v[i]);
    return e;
}

static float max_radius(const float *r, uint32_t n)
{
    uint32_t i = 0;
    float m = 0.0f;
#ifdef TT_SIMD_X86
    if (wide()) m = max_radius_avx2(r, n, &i);
#endif
    for (; i < n; i++) m = fmaxf(m, r[i]);
    return m;
}

/* Every particle's box (removed ones too: conservative): SSE2, two at a time. */
static void particle_box(const tt_world *w, uint32_t n, double *lox, double *loy, double *hix, double *hiy)
{
    uint32_t i = 0;
    *lox = *loy = INFINITY;
    *hix = *hiy = -INFINITY;
#ifdef __SSE2__
    __m128d lx = _mm_set1_pd(INFINITY), hx = _mm_set1_pd(-INFINITY), ly = lx, hy = hx;
    for (; i + 2 <= n; i += 2) {
        const __m128d x = _mm_loadu_pd(w->px + i), y = _mm_loadu_pd(w->py + i);
        lx = _mm_min_pd(x, lx);
        hx = _mm_max_pd(x, hx);
        ly = _mm_min_pd(y, ly);
        hy = _mm_max_pd(y, hy);
    }
    double t[2];
    _mm_storeu_pd(t, lx), *lox = fmin(t[0], t[1]);
    _mm_storeu_pd(t, hx), *hix = fmax(t[0], t[1]);
    _mm_storeu_pd(t, ly), *loy = fmin(t[0], t[1]);
    _mm_storeu_pd(t, hy), *hiy = fmax(t[0], t[1]);
#endif
    for (; i < n; i++) {
        *lox = fmin(*lox, w->px[i]); *hix = fmax(*hix, w->px[i]);
        *loy = fmin(*loy, w->py[i]); *hiy = fmax(*hiy, w->py[i]);
    }
}

/* The box round the static index: its grid and the primitives too big for
 * it (tt__sgrid_near finds nothing outside these). False when it is empty. */
static bool static_box(const tt__collide *c, double *lox, double *loy, double *hix, double *hiy)
{
    const tt__sgrid *g = &c->sgrid;
    *lox = *loy = INFINITY;
    *hix = *hiy = -INFINITY;
    if (g->nx > 0) {
        *lox = g->ox, *loy = g->oy;
        *hix = g->ox + g->nx * g->cs, *hiy = g->oy + g->ny * g->cs;
    }
    for (uint32_t k = 0; k < g->nbig; k++) {
        const tt__prim *p = &c->prims[g->big[k]];
        *lox = fmin(*lox, p->lox), *loy = fmin(*loy, p->loy);
        *hix = fmax(*hix, p->hix), *hiy = fmax(*hiy, p->hiy);
    }
    return *lox <= *hix && *loy <= *hiy;
}

/* Whether the particles' extreme e on side s, grown by m, stays clear of
 * the static box (a NaN extreme, every position NaN, is clear). */
static bool clear_of(int s, double e, double m, const double sb[4])
{
    switch (s) {
    case SIDE_LEFT: return !(e + m >= sb[0]);
    case SIDE_RIGHT: return !(e - m <= sb[2]);
    case SIDE_BELOW: return !(e + m >= sb[1]);
    default: return !(e - m <= sb[3]);
    }
}

bool tt__shapes_out_of_reach(const tt_world *w, tt__collide *c, uint32_t n)
{
    if (n == 0) return true;
    double sb[4];
    if (!static_box(c, &sb[0], &sb[1], &sb[2], &sb[3])) return true;
    if (c->reach_epoch != w->epoch || c->reach_n != n) { /* radii change only between steps, and bump the epoch */
        c->reach_rmax = max_radius(w->radius, n);
        c->reach_epoch = w->epoch;
        c->reach_n = n;
    }
    const double m = c->reach_rmax * (1.0 + TT__CONTACT_MARGIN);
    const int s = c->reach_side;
    const double *v = s == SIDE_LEFT || s == SIDE_RIGHT ? w->px : w->py;
    if (clear_of(s, extreme(v, n, s == SIDE_LEFT || s == SIDE_BELOW), m, sb)) return true;
    double lox, loy, hix, hiy;
    particle_box(w, n, &lox, &loy, &hix, &hiy);
    if (!(lox <= hix && loy <= hiy)) return true; /* every position NaN */
    const double e[4] = {hix, lox, hiy, loy};
    for (int k = 0; k < 4; k++)
        if (clear_of(k, e[k], m, sb)) {
            c->reach_side = (uint8_t)k; /* first next time */
            return true;
        }
    return !tt__sgrid_near(c, lox - m, loy - m, hix + m, hiy + m);
}

/* For substeps by speed (core/travel.c), before the step: whether a shape
 * or terrain lies within the box. The index is brought up to date first
 * (as the step's detection would), so the answer is the same for a world
 * and its reloaded copy; without memory for that, as if one did. */
bool tt__statics_within(tt_world *w, double lox, double loy, double hix, double hiy)
{
    tt__collide *c = tt__collide_peek(w);
    if (!c) return false;
    if (c->dirty && tt__shapes_rebuild(w, c) != TT_OK) return true;
    if (tt__sgrid_near(c, lox, loy, hix, hiy)) return true;
    for (uint32_t i = 0; c->terr && i < c->terr->pool.count; i++) {
        const tt__terrain *T = &c->terr->t[i];
        if (T->alive && T->lox <= hix && lox <= T->hix && T->loy <= hiy && loy <= T->hiy) return true;
    }
    return false;
}
