/* tether — pair contacts in batches of four, solved in vector lanes.
 * A pile's pairs come out of the grid cell by cell, so neighbouring pairs
 * share a particle and each waits for the last one's store: solved in that
 * order a sweep is one long dependency chain. Here a batch takes one pair
 * from each of four far-apart parts of the list; pairs that share no
 * particle commute, so four lanes solve them side by side and give the
 * scalar loop's result bit for bit (each lane does the scalar arithmetic;
 * simd.h). The layout is the solve order with and without vector lanes, so
 * a world gives the same result on every x86-64 processor. Anchored
 * friction runs in the same lanes (rub4), and with AVX-512 two batches at
 * a time in eight (batch8); the velocity pass of Verlet worlds runs in
 * lanes too (contact_batch_respond.c). */
#include "collide_internal.h"

#include <stdlib.h>
#include <string.h>

/* The pair list (the grid's order: row by row, bottom up) is cut into
 * TT__PARTS parts, bands of columns; batch t holds the t/2-th pair of parts
 * 0-3 (t even) or 4-7 (t odd). Each part keeps the grid's order, so a sweep
 * still carries a pile's weight up from the floor in one pass, and the order
 * stays the same from step to step but where pairs come and go. Both
 * matter: a planner that regrouped neighbouring pairs greedily (8 batches
 * open at a time) solved each step in a different order, and 10 000 circles
 * at 1 × 8 never came to rest (kinetic energy stuck at 0.05 J/kg after
 * 20 s). With bands of columns, as here, four jittered starts end at
 * 0.0008–0.0022 J/kg, the grid's own order without batches at 0.0018–0.0047
 * (bands of rows cut by pair count, which move with every pair: 0.0046 on
 * one start). The parts are far apart, so a batch's lanes seldom share a
 * particle (those batches go lane by lane), and consecutive batches come
 * from different parts, so one need not wait for the last one's stores. */

static bool reserve(tt__batches *B, uint32_t n)
{
    if (n <= B->cap) return true;
    uint32_t cap = B->cap ? B->cap : 1024;
    while (cap < n) cap = cap > UINT32_MAX / 2 ? n : cap * 2;
    /* one block: rs, lam, wa, wb, pre, sa, sb (doubles), then a and b, then solo */
    double *p = malloc((size_t)cap * (7 * sizeof(double) + 2 * sizeof(uint32_t)) + cap / 4);
    if (!p) return false;
    free(B->rs);
    B->rs = p;
    B->lam = p + cap;
    B->wa = p + 2 * (size_t)cap;
    B->wb = p + 3 * (size_t)cap;
    B->pre = p + 4 * (size_t)cap;
    B->sa = p + 5 * (size_t)cap;
    B->sb = p + 6 * (size_t)cap;
    B->a = (uint32_t *)(p + 7 * (size_t)cap);
    B->b = B->a + cap;
    B->solo = (uint8_t *)(B->b + cap);
    B->cap = cap;
    return true;
}

/* Where part k's pairs are: row y's run [runs[y·TT__PARTS + k], the next entry). */
typedef struct cursor {
    uint32_t y, p, end;
} cursor;

bool tt__batches_reserve(tt__batches *B, uint32_t np)
{
    if (np <= B->stamp_cap) return true;
    uint32_t *st = realloc(B->stamp, (size_t)np * sizeof *st);
    if (!st) return false;
    B->stamp = st;
    B->stamp_cap = np;
    B->mark = 0;
    return true;
}

bool tt__batches_plan(tt__batches *B, const tt__pair *pairs, uint32_t npairs, const uint32_t *runs, uint32_t nrows,
                      const double *inv, uint32_t np)
{
    B->n = 0;
    B->np = np;
    B->lean = false; /* until stacking's, after pre-stabilisation (contact_stack.c) */
    if (npairs == 0) return true;
    if (!tt__batches_reserve(B, np)) return false;
    uint32_t eq[TT__PARTS + 1], L = 0;
    for (uint32_t k = 0; runs && k < TT__PARTS; k++) {
        uint32_t len = 0;
        for (uint32_t y = 0; y < nrows; y++) len += runs[y * TT__PARTS + k + 1] - runs[y * TT__PARTS + k];
        if (len > L) L = len;
    }
    if (!runs || nrows == 0 || (uint64_t)L * TT__PARTS > 2 * (uint64_t)npairs + 64) {
        /* no bands, or bands so uneven that over half the lanes would pad: equal parts of the list */
        for (uint32_t k = 0; k <= TT__PARTS; k++) eq[k] = (uint32_t)((uint64_t)npairs * k / TT__PARTS);
        runs = eq;
        nrows = 1;
        L = eq[1];
        for (uint32_t k = 1; k < TT__PARTS; k++)
            if (eq[k + 1] - eq[k] > L) L = eq[k + 1] - eq[k];
    }
    cursor cur[TT__PARTS];
    for (uint32_t k = 0; k < TT__PARTS; k++) cur[k] = (cursor){0, runs[k], runs[k + 1]};
    if ((uint64_t)L * TT__PARTS > UINT32_MAX / 2 || !reserve(B, L * TT__PARTS)) return false;
    const uint32_t nb = L * TT__PARTS / 4;
    if (B->mark > UINT32_MAX - nb - 1 || B->mark == 0) { /* stamps from an earlier plan could look current */
        memset(B->stamp, 0, (size_t)np * sizeof *B->stamp);
        B->mark = 1;
    }
    /* locals: the stores below could otherwise alias B's fields */
    uint32_t *restrict A = B->a, *restrict Bb = B->b, *restrict stamp = B->stamp;
    double *restrict rs = B->rs, *restrict pre = B->pre, *restrict wa = B->wa, *restrict wb = B->wb;
    uint8_t *restrict solo = B->solo;
    memset(B->lam, 0, (size_t)nb * 4 * sizeof *B->lam);
    for (uint32_t t = 0; t < nb; t++) {
        const uint32_t s0 = (t % (TT__PARTS / 4)) * 4, id = B->mark + t;
        bool shared = false, prev = false;
        for (uint32_t s = s0; s < s0 + 4; s++) {
            cursor *c = &cur[s];
            while (c->p == c->end && c->y + 1 < nrows) { /* the part's run in the next row */
                c->y++;
                c->p = runs[c->y * TT__PARTS + s];
                c->end = runs[c->y * TT__PARTS + s + 1];
            }
            const uint32_t e = 4 * t + s - s0;
            if (c->p == c->end) { /* the part has no more: padding */
                A[e] = Bb[e] = np;
                rs[e] = pre[e] = wa[e] = wb[e] = 0.0;
                continue;
            }
            const tt__pair *pr = &pairs[c->p++];
            const uint32_t a = pr->a, b = pr->b;
            A[e] = a;
            Bb[e] = b;
            rs[e] = pr->rs;
            pre[e] = pr->rs * (1.0 - TT__PRESTAB_SLOP);
            wa[e] = inv[a];
            wb[e] = inv[b];
            shared |= stamp[a] == id || stamp[b] == id;
            prev |= (t & 1) && (stamp[a] == id - 1 || stamp[b] == id - 1);
            stamp[a] = stamp[b] = id;
        }
        solo[t] = (uint8_t)((shared ? TT__SOLO_SHARED : 0) | (prev ? TT__SOLO_PREV : 0));
    }
    B->mark += nb;
    B->n = 4 * nb;
    B->ka = B->wa;
    B->kb = B->wb;
    return true;
}

void tt__pair_apart(uint32_t a, uint32_t b, double *nx, double *ny)
{
    double ang = (double)(a * 2654435761u ^ b * 40503u) * (6.283185307179586 / 4294967296.0);
    *nx = cos(ang);
    *ny = sin(ang);
}

void tt__batches_anchor(tt__batches *B, const double *rxy, double *lt, const double *mu)
{
    B->arxy = rxy;
    B->alt = lt;
    B->amu = mu;
}

bool tt__batches_held(const tt__batches *B, uint32_t i, double *x, double *y)
{
    const uint8_t m = B->lc[i];
    if (m == 0) return false;
    const double *n = B->ln + 4 * (size_t)i;
    bool cut = false;
    for (uint8_t j = 0; j < m; j++) {
        const double dn = *x * n[2 * j] + *y * n[2 * j + 1];
        if (dn >= 0.0) continue;
        *x -= dn * n[2 * j];
        *y -= dn * n[2 * j + 1];
        cut = true;
    }
    if (m == 2 && cut && *x * n[0] + *y * n[1] < 0.0) *x = *y = 0.0; /* back into the first */
    return cut;
}

/* A pile leaning on a wall: the pair push splits each correction between
 * the two, and the share of a particle against the wall goes into the
 * wall, which pushes it back, last, into its neighbour. Gauss-Seidel then
 * needs many sweeps to carry the push along the pile; a few leave the
 * layers by the walls pressed into each other (the reference pour at 1 × 8
 * with stacking and anchored friction: 1.3–10.5 % of a radius, every such
 * pair by a wall; docs/collisions.md). So the particle moves only along the
 * wall, as if the wall took the rest (it does: it is static), and the
 * pair's correction is solved for the directions left:
 * C(xa, xb) = |xa − xb| − rs, each moving along its own direction. */
static bool lean_push(const tt__batches *B, uint32_t k, double *X, double *Y, size_t st, double *pen)
{
    const uint32_t i = B->a[k], j = B->b[k];
    const size_t a = i * st, b = j * st;
    const double ia = B->ka[k], ib = B->kb[k];
    double dx = X[a] - X[b], dy = Y[a] - Y[b], t;
    if (!tt__pair_push(i, j, B->rs[k], ia + ib, &dx, &dy, pen, &t)) return false;
    double ax = dx, ay = dy, bx = -dx, by = -dy;
    const bool ha = tt__batches_held(B, i, &ax, &ay), hb = tt__batches_held(B, j, &bx, &by);
    if (ha || hb) {
        /* a moves by (ax, ay)·t·ia, b by (bx, by)·t·ib; the distance grows by t·wd/d */
        const double wd = ia * (ax * dx + ay * dy) - ib * (bx * dx + by * dy);
        if (!(wd > 0.0)) return true; /* neither can move: pressed, not pushed */
        t = *pen * sqrt(dx * dx + dy * dy) / wd;
    }
    X[a] += ax * (t * ia);
    Y[a] += ay * (t * ia);
    X[b] += bx * (t * ib);
    Y[b] += by * (t * ib);
    return true;
}

/* Entries [k0, k1) in order on positions X, Y, the particle i's at i·st:
 * the reference every vector lane reproduces. */
static double solve(const tt__batches *B, double *X, double *Y, size_t st, uint32_t k0, uint32_t k1, double err)
{
    for (uint32_t k = k0; k < k1; k++) {
        const size_t a = B->a[k] * st, b = B->b[k] * st;
        const double ia = B->ka[k], ib = B->kb[k], ws = ia + ib, rs = B->rs[k];
        if (ws == 0.0) continue; /* padding too */
        double dx = X[a] - X[b], dy = Y[a] - Y[b], pen, t;
        bool at_rs = false; /* pushed to contact along its own line: now rs apart */
        if (B->rub != 2 && B->lean && (B->lc[B->a[k]] | B->lc[B->b[k]])) {
            if (lean_push(B, k, X, Y, st, &pen)) {
                B->lam[k] += pen;
                if (pen > err) err = pen;
            }
        } else if (B->rub != 2 && tt__pair_push(B->a[k], B->b[k], rs, ws, &dx, &dy, &pen, &t)) {
            const double ca = t * ia, cb = t * ib;
            X[a] += dx * ca;
            Y[a] += dy * ca;
            X[b] -= dx * cb;
            Y[b] -= dy * cb;
            B->lam[k] += pen;
            if (pen > err) err = pen;
            at_rs = true;
        }
        if (!B->rub) continue;
        const double ex = X[a] - X[b], ey = Y[a] - Y[b], d = at_rs ? rs : sqrt(ex * ex + ey * ey);
        const double g = tt__anchored_rub(ex, ey, d, B->arxy + 2 * (size_t)k, B->amu[k], B->lam[k], ws, B->alt + k);
        if (g == 0.0) continue;
        const double ga = g * ia, gb = g * ib;
        X[a] += -ey * ga;
        Y[a] += ex * ga;
        X[b] -= -ey * gb;
        Y[b] -= ex * gb;
    }
    return err;
}

#ifdef TT_SIMD_X86
#define LO TT__LO
#define HI TT__HI
#define LANES TT__LANES

/* tt__anchored_rub of batch k's four entries, lane by lane, on the
 * positions after their push in pair form (a02: a's x, y of lanes 0 and
 * 2), d their distances as tt__anchored_rub takes them, lam the normal
 * corrections so far, ia, ib, ws the weights. */
TT_AVX2 TT_INLINE void rub4(const tt__batches *B, uint32_t k, __m256d d, __m256d lam, __m256d ia, __m256d ib, __m256d ws,
                            __m256d *a02, __m256d *a13, __m256d *b02, __m256d *b13)
{
    const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0), sign = _mm256_set1_pd(-0.0);
    const __m256d e02 = _mm256_sub_pd(*a02, *b02), e13 = _mm256_sub_pd(*a13, *b13);
    const __m256d mu = _mm256_loadu_pd(B->amu + k);
    const __m256d act = _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(mu, zero, _CMP_GT_OQ), _mm256_cmp_pd(lam, zero, _CMP_GT_OQ)),
                                      _mm256_cmp_pd(d, zero, _CMP_GT_OQ));
    if (!_mm256_movemask_pd(act)) return;
    const __m256d neg = _mm256_set_pd(0.0, -0.0, 0.0, -0.0);
    const __m256d p02 = _mm256_xor_pd(_mm256_permute_pd(e02, 5), neg), p13 = _mm256_xor_pd(_mm256_permute_pd(e13, 5), neg); /* −ey, ex */
    const __m256d r01 = _mm256_loadu_pd(B->arxy + 2 * (size_t)k), r23 = _mm256_loadu_pd(B->arxy + 2 * (size_t)k + 4);
    const __m256d r02 = _mm256_permute2f128_pd(r01, r23, 0x20), r13 = _mm256_permute2f128_pd(r01, r23, 0x31);
    const __m256d cr = LANES(_mm256_mul_pd(_mm256_sub_pd(e02, r02), p02), _mm256_mul_pd(_mm256_sub_pd(e13, r13), p13));
    /* lanes out of play divide by 1 (no exception the scalar code would not raise) */
    const __m256d dd = _mm256_blendv_pd(one, d, act);
    const __m256d id = _mm256_div_pd(one, dd), iw = _mm256_div_pd(one, _mm256_blendv_pd(one, _mm256_mul_pd(d, ws), act));
    const __m256d slide = _mm256_mul_pd(cr, id), lim = _mm256_mul_pd(mu, lam);
    const __m256d lt = _mm256_loadu_pd(B->alt + k), want = _mm256_sub_pd(lt, slide), nlim = _mm256_xor_pd(lim, sign);
    __m256d got = _mm256_blendv_pd(want, nlim, _mm256_cmp_pd(want, nlim, _CMP_LT_OQ));
    got = _mm256_blendv_pd(got, lim, _mm256_cmp_pd(want, lim, _CMP_GT_OQ));
    _mm256_storeu_pd(B->alt + k, _mm256_blendv_pd(lt, got, act));
    const __m256d g = _mm256_mul_pd(_mm256_sub_pd(got, lt), iw);
    const __m256d app = _mm256_and_pd(act, _mm256_cmp_pd(g, zero, _CMP_NEQ_UQ));
    const __m256d ga = _mm256_mul_pd(g, ia), gb = _mm256_mul_pd(g, ib);
    *a02 = _mm256_blendv_pd(*a02, _mm256_add_pd(*a02, _mm256_mul_pd(p02, LO(ga))), LO(app));
    *a13 = _mm256_blendv_pd(*a13, _mm256_add_pd(*a13, _mm256_mul_pd(p13, HI(ga))), HI(app));
    *b02 = _mm256_blendv_pd(*b02, _mm256_sub_pd(*b02, _mm256_mul_pd(p02, LO(gb))), LO(app));
    *b13 = _mm256_blendv_pd(*b13, _mm256_sub_pd(*b13, _mm256_mul_pd(p13, HI(gb))), HI(app));
}

/* One batch in "pair form" (as distance_sweep.c: a ymm holds (x, y) of lanes
 * 0 and 2, or of 1 and 3) on the solver's rows pk. Returns false, touching
 * nothing, when an active lane has two particles on one centre: the scalar
 * code takes that batch. */
#define R(i) (4 * (size_t)(i)) /* particle i's row in pk */
TT_AVX2 TT_INLINE bool batch(double *pk, const tt__batches *B, uint32_t k, __m256d *err)
{
    const uint32_t *A = B->a + k, *Bb = B->b + k;
    const __m256d pa02 = tt__rows_loadxy2(pk, R(A[0]), R(A[2])), pa13 = tt__rows_loadxy2(pk, R(A[1]), R(A[3]));
    const __m256d pb02 = tt__rows_loadxy2(pk, R(Bb[0]), R(Bb[2])), pb13 = tt__rows_loadxy2(pk, R(Bb[1]), R(Bb[3]));
    const __m256d zero = _mm256_setzero_pd();
    const __m256d d02 = _mm256_sub_pd(pa02, pb02), d13 = _mm256_sub_pd(pa13, pb13); /* dx0 dy0 dx2 dy2 */
    const __m256d q02 = _mm256_mul_pd(d02, d02), q13 = _mm256_mul_pd(d13, d13);
    const __m256d d2 = _mm256_add_pd(_mm256_unpacklo_pd(q02, q13), _mm256_unpackhi_pd(q02, q13)); /* lanes 0 1 2 3 */
    const __m256d wa = _mm256_loadu_pd(B->ka + k), wb = _mm256_loadu_pd(B->kb + k);
    const __m256d ws = _mm256_add_pd(wa, wb), rs = _mm256_loadu_pd(B->rs + k);
    const __m256d act = _mm256_and_pd(_mm256_cmp_pd(ws, zero, _CMP_NEQ_UQ), _mm256_cmp_pd(d2, _mm256_mul_pd(rs, rs), _CMP_LT_OQ));
    /* no early exit when no lane is in contact: in a pile that branch is a coin toss, and a
     * mispredicted one costs more than the arithmetic (the blends keep every value) */
    if (_mm256_movemask_pd(_mm256_and_pd(act, _mm256_cmp_pd(d2, zero, _CMP_EQ_OQ)))) return false;
    const __m256d d = _mm256_sqrt_pd(d2), pen = _mm256_sub_pd(rs, d), one = _mm256_set1_pd(1.0);
    /* a lane out of contact divides by 1: no division by zero the scalar code would not do */
    const __m256d t = _mm256_div_pd(pen, _mm256_blendv_pd(one, _mm256_mul_pd(ws, d), act));
    /* lane by lane x_a + dx·t·w_a as x_a − dx·(t·(−w_a)), the same rounding; a lane out of
     * contact subtracts +0, which leaves any x as it was (adding 0 would turn −0 into +0) */
    const __m256d sign = _mm256_set1_pd(-0.0);
    const __m256d ca = _mm256_mul_pd(t, _mm256_xor_pd(wa, sign)), cb = _mm256_mul_pd(t, wb);
    const __m256d u02 = _mm256_unpacklo_pd(act, act), u13 = _mm256_unpackhi_pd(act, act);
    __m256d na02 = _mm256_sub_pd(pa02, _mm256_and_pd(_mm256_mul_pd(d02, _mm256_unpacklo_pd(ca, ca)), u02));
    __m256d na13 = _mm256_sub_pd(pa13, _mm256_and_pd(_mm256_mul_pd(d13, _mm256_unpackhi_pd(ca, ca)), u13));
    __m256d nb02 = _mm256_sub_pd(pb02, _mm256_and_pd(_mm256_mul_pd(d02, _mm256_unpacklo_pd(cb, cb)), u02));
    __m256d nb13 = _mm256_sub_pd(pb13, _mm256_and_pd(_mm256_mul_pd(d13, _mm256_unpackhi_pd(cb, cb)), u13));
    const __m256d got = _mm256_and_pd(pen, act); /* lam ≥ +0 stays as it was plus +0 */
    const __m256d lam = _mm256_add_pd(_mm256_loadu_pd(B->lam + k), got);
    _mm256_storeu_pd(B->lam + k, lam);
    *err = _mm256_max_pd(*err, got);
    if (B->rub) rub4(B, k, _mm256_blendv_pd(d, rs, act), lam, wa, wb, ws, &na02, &na13, &nb02, &nb13);
    tt__rows_store2(pk, R(A[0]), R(A[2]), na02);
    tt__rows_store2(pk, R(A[1]), R(A[3]), na13);
    tt__rows_store2(pk, R(Bb[0]), R(Bb[2]), nb02);
    tt__rows_store2(pk, R(Bb[1]), R(Bb[3]), nb13);
    return true;
}

/* Eight lanes (AVX-512F): batches t and t + 1 in pair form on zmm, lanes
 * 0–3 of t and 4–7 of t + 1, each lane the arithmetic of batch and rub4
 * above, with mask registers for their blends. */
#define LO8(v) _mm512_unpacklo_pd((v), (v))
#define HI8(v) _mm512_unpackhi_pd((v), (v))
#define LANES8(x02, x13) _mm512_add_pd(_mm512_unpacklo_pd((x02), (x13)), _mm512_unpackhi_pd((x02), (x13)))

/* A lane mask as the pair form's: lanes 0, 2, 4, 6 (x and y each), or 1, 3, 5, 7. */
static inline __mmask8 pm02(__mmask8 m) { return (__mmask8)((m & 0x55u) * 3u); }
static inline __mmask8 pm13(__mmask8 m) { return (__mmask8)(((unsigned)m >> 1 & 0x55u) * 3u); }

TT_AVX512 TT_INLINE __m512d xor8(__m512d a, __m512d b)
{
    return _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(a), _mm512_castpd_si512(b)));
}

/* (x, y) of the particles I[0], I[2], I[4], I[6], and back. */
TT_AVX512 TT_INLINE __m512d load8(const double *pk, const uint32_t *I)
{
    const __m256d lo = tt__rows_loadxy2(pk, R(I[0]), R(I[2])), hi = tt__rows_loadxy2(pk, R(I[4]), R(I[6]));
    return _mm512_insertf64x4(_mm512_castpd256_pd512(lo), hi, 1);
}

TT_AVX512 TT_INLINE void store8(double *pk, const uint32_t *I, __m512d v)
{
    tt__rows_store2(pk, R(I[0]), R(I[2]), _mm512_castpd512_pd256(v));
    tt__rows_store2(pk, R(I[4]), R(I[6]), _mm512_extractf64x4_pd(v, 1));
}

TT_AVX512 TT_INLINE void rub8(const tt__batches *B, uint32_t k, __m512d d, __m512d lam, __m512d ia, __m512d ib, __m512d ws,
                              __m512d *a02, __m512d *a13, __m512d *b02, __m512d *b13)
{
    const __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1.0), sign = _mm512_set1_pd(-0.0);
    const __m512d e02 = _mm512_sub_pd(*a02, *b02), e13 = _mm512_sub_pd(*a13, *b13);
    const __m512d mu = _mm512_loadu_pd(B->amu + k);
    const __mmask8 act = _mm512_cmp_pd_mask(mu, zero, _CMP_GT_OQ) & _mm512_cmp_pd_mask(lam, zero, _CMP_GT_OQ) &
                         _mm512_cmp_pd_mask(d, zero, _CMP_GT_OQ);
    if (!act) return;
    const __m512d neg = _mm512_set_pd(0.0, -0.0, 0.0, -0.0, 0.0, -0.0, 0.0, -0.0);
    const __m512d p02 = xor8(_mm512_permute_pd(e02, 0x55), neg), p13 = xor8(_mm512_permute_pd(e13, 0x55), neg); /* −ey, ex */
    const __m512d r0 = _mm512_loadu_pd(B->arxy + 2 * (size_t)k), r1 = _mm512_loadu_pd(B->arxy + 2 * (size_t)k + 8);
    const __m512d r02 = _mm512_shuffle_f64x2(r0, r1, _MM_SHUFFLE(2, 0, 2, 0)), r13 = _mm512_shuffle_f64x2(r0, r1, _MM_SHUFFLE(3, 1, 3, 1));
    const __m512d cr = LANES8(_mm512_mul_pd(_mm512_sub_pd(e02, r02), p02), _mm512_mul_pd(_mm512_sub_pd(e13, r13), p13));
    const __m512d id = _mm512_div_pd(one, _mm512_mask_blend_pd(act, one, d));
    const __m512d iw = _mm512_div_pd(one, _mm512_mask_blend_pd(act, one, _mm512_mul_pd(d, ws)));
    const __m512d slide = _mm512_mul_pd(cr, id), lim = _mm512_mul_pd(mu, lam);
    const __m512d lt = _mm512_loadu_pd(B->alt + k), want = _mm512_sub_pd(lt, slide), nlim = xor8(lim, sign);
    __m512d got = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(want, nlim, _CMP_LT_OQ), want, nlim);
    got = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(want, lim, _CMP_GT_OQ), got, lim);
    _mm512_storeu_pd(B->alt + k, _mm512_mask_blend_pd(act, lt, got));
    const __m512d g = _mm512_mul_pd(_mm512_sub_pd(got, lt), iw);
    const __mmask8 app = act & _mm512_cmp_pd_mask(g, zero, _CMP_NEQ_UQ);
    const __m512d ga = _mm512_mul_pd(g, ia), gb = _mm512_mul_pd(g, ib);
    *a02 = _mm512_mask_add_pd(*a02, pm02(app), *a02, _mm512_mul_pd(p02, LO8(ga)));
    *a13 = _mm512_mask_add_pd(*a13, pm13(app), *a13, _mm512_mul_pd(p13, HI8(ga)));
    *b02 = _mm512_mask_sub_pd(*b02, pm02(app), *b02, _mm512_mul_pd(p02, LO8(gb)));
    *b13 = _mm512_mask_sub_pd(*b13, pm13(app), *b13, _mm512_mul_pd(p13, HI8(gb)));
}

/* Entries k … k + 7 (batches k/4 and k/4 + 1, sharing no particle) as
 * batch does four; false, touching nothing, when an active lane has two
 * particles on one centre. */
TT_AVX512 TT_INLINE bool batch8(double *pk, const tt__batches *B, uint32_t k, __m512d *err)
{
    const uint32_t *A = B->a + k, *Bb = B->b + k;
    const __m512d pa02 = load8(pk, A), pa13 = load8(pk, A + 1), pb02 = load8(pk, Bb), pb13 = load8(pk, Bb + 1);
    const __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1.0), sign = _mm512_set1_pd(-0.0);
    const __m512d d02 = _mm512_sub_pd(pa02, pb02), d13 = _mm512_sub_pd(pa13, pb13);
    const __m512d q02 = _mm512_mul_pd(d02, d02), q13 = _mm512_mul_pd(d13, d13);
    const __m512d d2 = _mm512_add_pd(_mm512_unpacklo_pd(q02, q13), _mm512_unpackhi_pd(q02, q13));
    const __m512d wa = _mm512_loadu_pd(B->ka + k), wb = _mm512_loadu_pd(B->kb + k);
    const __m512d ws = _mm512_add_pd(wa, wb), rs = _mm512_loadu_pd(B->rs + k);
    const __mmask8 act = _mm512_cmp_pd_mask(ws, zero, _CMP_NEQ_UQ) & _mm512_cmp_pd_mask(d2, _mm512_mul_pd(rs, rs), _CMP_LT_OQ);
    if (act & _mm512_cmp_pd_mask(d2, zero, _CMP_EQ_OQ)) return false;
    const __m512d d = _mm512_sqrt_pd(d2), pen = _mm512_sub_pd(rs, d);
    const __m512d t = _mm512_div_pd(pen, _mm512_mask_blend_pd(act, one, _mm512_mul_pd(ws, d)));
    const __m512d ca = _mm512_mul_pd(t, xor8(wa, sign)), cb = _mm512_mul_pd(t, wb);
    const __mmask8 u02 = pm02(act), u13 = pm13(act);
    __m512d na02 = _mm512_sub_pd(pa02, _mm512_maskz_mov_pd(u02, _mm512_mul_pd(d02, LO8(ca))));
    __m512d na13 = _mm512_sub_pd(pa13, _mm512_maskz_mov_pd(u13, _mm512_mul_pd(d13, HI8(ca))));
    __m512d nb02 = _mm512_sub_pd(pb02, _mm512_maskz_mov_pd(u02, _mm512_mul_pd(d02, LO8(cb))));
    __m512d nb13 = _mm512_sub_pd(pb13, _mm512_maskz_mov_pd(u13, _mm512_mul_pd(d13, HI8(cb))));
    const __m512d got = _mm512_maskz_mov_pd(act, pen);
    const __m512d lam = _mm512_add_pd(_mm512_loadu_pd(B->lam + k), got);
    _mm512_storeu_pd(B->lam + k, lam);
    *err = _mm512_max_pd(*err, got);
    if (B->rub) rub8(B, k, _mm512_mask_blend_pd(act, d, rs), lam, wa, wb, ws, &na02, &na13, &nb02, &nb13);
    store8(pk, A, na02);
    store8(pk, A + 1, na13);
    store8(pk, Bb, nb02);
    store8(pk, Bb + 1, nb13);
    return true;
}

#undef LO8
#undef HI8
#undef LANES8

#undef R

/* The largest of err and e's lanes. */
TT_AVX2 TT_INLINE double max_of(__m256d e, double err)
{
    double l[4];
    _mm256_storeu_pd(l, e);
    for (int j = 0; j < 4; j++)
        if (l[j] > err) err = l[j];
    return err;
}

#define SOLO (TT__SOLO_SHARED | TT__SOLO_LEAN) /* the flags that send a batch lane by lane */

/* Batches [t0, t1) on the rows pk. */
TT_AVX2 TT_INLINE double batches_run(tt__batches *B, double *pk, uint32_t t0, uint32_t t1)
{
    double err = 0.0;
    __m256d e = _mm256_setzero_pd();
    for (uint32_t k = 4 * t0; k < 4 * t1; k += 4)
        if ((B->solo[k / 4] & SOLO) || !batch(pk, B, k, &e)) err = solve(B, pk, pk + 1, 4, k, k + 4, err);
    return max_of(e, err);
}

/* The same code for AVX2. */
TT_AVX2 static double run_avx2(tt__batches *B, double *pk, uint32_t t0, uint32_t t1) { return batches_run(B, pk, t0, t1); }

/* AVX-512: four lanes, as AVX2, with AVX-512VL's 32 registers; with
 * anchored friction (rub), batches t and t + 1 (t even) side by side in
 * eight lanes (batch8: the same arithmetic on zmm) when neither goes lane
 * by lane and they share no particle (TT__SOLO_PREV): then their entries
 * commute, and solving them together is solving t, then t + 1, bit for
 * bit. Measured on the reference pour (600 steps, alternating, five
 * pairs): with stacking 2 and anchored friction at 1 × 12, 5.53 (5.32–5.56)
 * → 5.27 (5.13–5.39) ms/step; without the rub, eight lanes were slower
 * (the default 1 × 8: 2.93–3.01 → 3.08–3.15), the loads, stores and
 * shuffles being the same per entry and the rub's arithmetic what the
 * wider lanes save. */
TT_AVX512 static double run_avx512(tt__batches *B, double *pk, uint32_t t0, uint32_t t1)
{
    if (!B->rub) return batches_run(B, pk, t0, t1);
    double err = 0.0;
    __m256d e = _mm256_setzero_pd();
    __m512d e8 = _mm512_setzero_pd();
    for (uint32_t t = t0; t < t1;) {
        if (!(t & 1) && t + 1 < t1 && !(B->solo[t] | B->solo[t + 1]) && batch8(pk, B, 4 * t, &e8)) {
            t += 2;
            continue;
        }
        if ((B->solo[t] & SOLO) || !batch(pk, B, 4 * t, &e)) err = solve(B, pk, pk + 1, 4, 4 * t, 4 * t + 4, err);
        t++;
    }
    e = _mm256_max_pd(e, _mm256_max_pd(_mm512_castpd512_pd256(e8), _mm512_extractf64x4_pd(e8, 1)));
    return max_of(e, err);
}

/* Anchored friction alone (rub 2) on xy rows: each batch's lanes rubbed as
 * after their push; batches whose lanes share a particle go lane by lane. */
TT_AVX2 TT_INLINE void rubs_run(tt__batches *B, double *xy)
{
    for (uint32_t k = 0; k < B->n; k += 4) {
        if (B->solo[k / 4] & TT__SOLO_SHARED) {
            (void)solve(B, xy, xy + 1, 2, k, k + 4, 0.0);
            continue;
        }
        const uint32_t *A = B->a + k, *Bb = B->b + k;
        __m256d a02 = tt__xy_load2(xy, A[0], A[2]), a13 = tt__xy_load2(xy, A[1], A[3]);
        __m256d b02 = tt__xy_load2(xy, Bb[0], Bb[2]), b13 = tt__xy_load2(xy, Bb[1], Bb[3]);
        const __m256d wa = _mm256_loadu_pd(B->ka + k), wb = _mm256_loadu_pd(B->kb + k);
        const __m256d e02 = _mm256_sub_pd(a02, b02), e13 = _mm256_sub_pd(a13, b13);
        const __m256d d = _mm256_sqrt_pd(LANES(_mm256_mul_pd(e02, e02), _mm256_mul_pd(e13, e13)));
        rub4(B, k, d, _mm256_loadu_pd(B->lam + k), wa, wb, _mm256_add_pd(wa, wb), &a02, &a13, &b02, &b13);
        tt__xy_store2(xy, A[0], A[2], a02);
        tt__xy_store2(xy, A[1], A[3], a13);
        tt__xy_store2(xy, Bb[0], Bb[2], b02);
        tt__xy_store2(xy, Bb[1], Bb[3], b13);
    }
}

TT_AVX2 static void rubs_avx2(tt__batches *B, double *xy) { rubs_run(B, xy); }
TT_AVX512 static void rubs_avx512(tt__batches *B, double *xy) { rubs_run(B, xy); }

#undef LO
#undef HI
#undef LANES

#endif

bool tt__batches_want_rows(const tt__batches *B) { return tt__simd_kind(B->simd) != TT__SIMD_SCALAR; }

/* A friction-alone pass over every batch on the world's arrays (st 1), in
 * lanes on xy rows packed for it; false when there are no lanes here (or no
 * memory for the rows): then the caller's scalar pass gives the same bits. */
static bool rubs(tt__batches *B, const tt__lay *L, uint32_t t0, uint32_t t1)
{
#ifdef TT_SIMD_X86
    const uint8_t kind = tt__simd_kind(B->simd);
    const uint32_t np = B->np;
    if (kind == TT__SIMD_SCALAR || L->st != 1 || t0 != 0 || t1 != B->n / 4 || !tt__xy_reserve(&B->xy, &B->xy_cap, np + 1))
        return false;
    tt__xy_pack(B->xy, L->x, L->y, np);
    B->xy[2 * (size_t)np] = B->xy[2 * (size_t)np + 1] = 0.0; /* padding */
    if (kind == TT__SIMD_AVX512) rubs_avx512(B, B->xy);
    else rubs_avx2(B, B->xy);
    tt__xy_unpack(B->xy, L->x, L->y, np);
    return true;
#else
    (void)B, (void)L, (void)t0, (void)t1;
    return false;
#endif
}

double tt__batches_sweep(tt__batches *B, const tt__lay *L, uint32_t t0, uint32_t t1)
{
    if (B->rub == 2 && rubs(B, L, t0, t1)) return 0.0;
    const uint8_t kind = tt__simd_kind(B->simd);
    if (kind == TT__SIMD_SCALAR || L->st != 4 || B->rub == 2) return solve(B, L->x, L->y, L->st, 4 * t0, 4 * t1, 0.0);
#ifdef TT_SIMD_X86
    /* the rows' padding row (np, past the last particle) is zero: no mass, never active */
    return kind == TT__SIMD_AVX512 ? run_avx512(B, L->x, t0, t1) : run_avx2(B, L->x, t0, t1);
#else
    return 0.0; /* never reached: no vector kind without TT_SIMD_X86 */
#endif
}

void tt__batches_free(tt__batches *B)
{
    free(B->rs);
    free(B->stamp);
    free(B->xy);
    free(B->q);
    free(B->v0);
    free(B->me);
    free(B->ln);
    memset(B, 0, sizeof *B);
}

size_t tt__batches_bytes(const tt__batches *B)
{
    return (size_t)B->cap * (7 * sizeof(double) + 2 * sizeof(uint32_t)) + B->cap / 4 + (size_t)B->stamp_cap * sizeof(uint32_t) +
           ((size_t)B->xy_cap + B->q_cap + B->v0_cap) * 2 * sizeof(double) + (size_t)B->me_cap * 3 * sizeof(double) +
           (size_t)B->ln_cap * (4 * sizeof(double) + 1);
}
