/* tether — the distance links' sweep: the scalar loop (Gauss-Seidel in
 * place, or Jacobi through tt__correct) and, for Gauss-Seidel, the vector
 * plan that solves blocks of links in SIMD lanes with the scalar loop's
 * result bit for bit. */
#include "constraint_internal.h"

#include <stdlib.h>
#include <string.h>

/* Link i's lo, hi, k or alpha changed: its copy follows (a stale plan is rebuilt whole). */
void tt__distance_hot_sync(tt__cgroup *g, uint32_t i)
{
    if (!g->scr.plan_ok) return;
    g->scr.h_lo[i] = g->dist[i].lo;
    g->scr.h_hi[i] = g->dist[i].hi;
    g->scr.h_k[i] = g->dist[i].k;
    g->scr.h_alpha[i] = g->dist[i].alpha;
}

/* Part of a sweep over the distance constraints: links [i, n), err the
 * largest error so far. Particle k is at px[k·st], py[k·st], im[k·st] (st = 1:
 * the world's arrays; 4: the solver's rows). `jacobi` and `st` are
 * constants at each call site, so each gets a lean loop. first: the
 * substep's first sweep. */
static inline __attribute__((always_inline)) double sweep_distance(tt_world *w, tt__cgroup *g, double h, bool jacobi, bool first,
                                                                   double *px, double *py, const double *im, size_t st,
                                                                   uint32_t i, uint32_t n, double err)
{
    const double inv_h2 = 1.0 / (h * h);
    const tt__dist *dist = g->dist;
    for (; i < n; i++) {
        const tt__dist *d = &dist[i];
        const uint32_t a = d->a, b = d->b;
        const size_t ia = a * st, ib = b * st;
        const double wa = im[ia], wb = im[ib], ws = wa + wb;
        if (ws == 0.0) continue;
        double dx = px[ib] - px[ia], dy = py[ib] - py[ia];
        double len = sqrt(dx * dx + dy * dy);
        double c = len < d->lo ? len - d->lo : len > d->hi ? len - d->hi : 0.0;
        if (c == 0.0) continue;
        double ac = fabs(c);
        if (ac > err) err = ac;
        if (len == 0.0) { /* one spot: no direction */
            /* Brought together by other constraints during the sweeps, they
             * get one from those; still together when the substep's sweeps
             * begin, they may never get one (two particles at rest), so b
             * parts to +x of a. */
            if (!first) continue;
            dx = 1.0;
            dy = 0.0;
            len = 1.0;
        }
        double s;
        if (d->alpha > 0.0) {
            double at = d->alpha * inv_h2, *lam = &g->dx[i].lambda;
            double dl = (-c - at * *lam) / (ws + at);
            *lam += dl;
            s = -dl / len;
        } else {
            s = d->k * c / (ws * len);
        }
        /* a moves toward b when stretched (c > 0), b toward a */
        double cx = s * dx, cy = s * dy;
        if (jacobi) {
            if (wa > 0.0) tt__correct(w, a, wa * cx, wa * cy);
            if (wb > 0.0) tt__correct(w, b, -wb * cx, -wb * cy);
        } else {
            px[ia] += wa * cx;
            py[ia] += wa * cy;
            px[ib] -= wb * cx;
            py[ib] -= wb * cy;
        }
    }
    return err;
}

/* ---- Gauss-Seidel in SIMD lanes -------------------------------------------
 * Consecutive links that share no particle commute, so a block of them solved
 * side by side gives the sequential loop's result bit for bit, as long as each
 * lane does the scalar arithmetic: the same IEEE operations in the same order
 * (these functions enable no FMA, and the build has -ffp-contract=off) with
 * every branch turned into a mask. The sweep works on the solver's rows
 * (x, y and inverse mass in one 32-byte row per particle) so a particle is
 * one load and one store, and reads the links' hot fields from arrays (h_*) so a
 * block's parameters are one vector load each. Measured on a 128² cloth at 10
 * sweeps (Zen 4, make bench, median of 5): the scalar loop 6.2 ms a step,
 * this 1.97 ms. */

/* Room for the plan of n links over particles [0, np). */
static bool plan_reserve(tt__cgroup *g, uint32_t n, uint32_t np, uint32_t W)
{
    if (!tt__grow((void **)&g->scr.stamp, &g->scr.stamp_cap, np, sizeof *g->scr.stamp) ||
        !tt__grow((void **)&g->scr.plan, &g->scr.plan_cap, 2 * (n / W + 1), sizeof *g->scr.plan))
        return false;
    if (n > g->scr.hot_cap) { /* one block: four double arrays, then two uint32 ones */
        uint32_t cap = n > UINT32_MAX / 2 ? n : n + n / 2;
        double *h = malloc((size_t)cap * (4 * sizeof(double) + 2 * sizeof(uint32_t)));
        if (!h) return false;
        free(g->scr.h_lo);
        g->scr.h_lo = h;
        g->scr.h_hi = h + cap;
        g->scr.h_k = h + 2 * (size_t)cap;
        g->scr.h_alpha = h + 3 * (size_t)cap;
        g->scr.h_ra = (uint32_t *)(h + 4 * (size_t)cap);
        g->scr.h_rb = g->scr.h_ra + cap;
        g->scr.hot_cap = cap;
    }
    return true;
}

/* In a plan's block count: the run's links are all rigid. */
#define PLAN_RIGID 0x80000000u

/* Greedy in one pass. A block gathers consecutive links until W share no
 * particle, and a run of blocks (one plan segment) goes on while each block
 * also shares none with the D − 1 before it, so a kernel may load a block
 * before it stores the previous ones. A link naming a particle of link k:
 * k in the block: the links up to k go to a scalar run, a new run starts
 * after k; k in an earlier block: a new run starts with this block. */
static bool plan_build(tt__cgroup *g, uint32_t W, uint32_t D)
{
    const uint32_t n = g->ndist;
    uint32_t np = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t m = g->dist[i].a > g->dist[i].b ? g->dist[i].a : g->dist[i].b;
        if (m >= np) np = m + 1;
    }
    if (!plan_reserve(g, n, np, W)) return false;
    /* stamp[p]: 1 + the last link naming p; done: links planned; r, s: first link of the run, of the block */
    uint32_t *stamp = g->scr.stamp, *plan = g->scr.plan, m = 0, done = 0, r = 0, s = 0;
    memset(stamp, 0, (size_t)np * sizeof *stamp);
    for (uint32_t j = 0; j < n; j++) {
        const tt__dist *d = &g->dist[j];
        const uint32_t a = d->a, b = d->b;
        g->scr.h_lo[j] = d->lo;
        g->scr.h_hi[j] = d->hi;
        g->scr.h_k[j] = d->k;
        g->scr.h_alpha[j] = d->alpha;
        g->scr.h_ra[j] = 4 * a; /* indices < 2^24 (TT_HANDLE_MAX_SLOTS): no overflow */
        g->scr.h_rb[j] = 4 * b;
        const uint32_t lim = s - r >= (D - 1) * W ? s - (D - 1) * W : r; /* j must share no particle with [lim, j) */
        uint32_t k1 = stamp[a] > stamp[b] ? stamp[a] : stamp[b];
        if (a == b) k1 = j + 1; /* never made, but then no lane may hold it */
        if (k1 > lim) r = k1 > s ? (s = k1) : s;
        stamp[a] = stamp[b] = j + 1;
        if (j + 1 - s < W) continue;
        uint32_t rigid = PLAN_RIGID; /* a run is all rigid links (lo = hi for good) or not */
        for (uint32_t q = s; q <= j; q++)
            if (g->dx[q].mode != TT_DISTANCE_RIGID) rigid = 0;
        if (s == done && r < s && m > 0 && (plan[m - 1] & PLAN_RIGID) == rigid) {
            plan[m - 1]++; /* the run goes on */
        } else {
            plan[m++] = s - done;
            plan[m++] = 1 | rigid;
        }
        done = s = j + 1;
    }
    if (done < n) {
        plan[m++] = n - done;
        plan[m++] = 0;
    }
    g->scr.nplan = m;
    g->scr.plan_w = W;
    g->scr.plan_np = np;
    g->scr.plan_ok = true;
    return true;
}

#ifdef TT_SIMD_X86
static double max_lanes(const double *e, int n)
{
    double r = 0.0;
    for (int j = 0; j < n; j++)
        if (e[j] > r) r = e[j];
    return r;
}

/* What a kernel reads: the rows, the hot arrays and the cold halves, all
 * from the run's first link on. */
typedef struct kern_in {
    double *pk;
    const double *lo, *hi, *k, *alpha;
    const uint32_t *ra, *rb;
    tt__dist_x *x;
    double inv_h2;
    bool apart; /* the substep's first sweep: links of length 0 part their particles */
} kern_in;

/* Four links a block, in "pair form": a ymm holds (x, y) of two particles,
 * those of links 0, 2 or of links 1, 3, and another their (w, w), from two
 * rows with two permutes; the lengths, c and s come out in link order with one
 * unpack, and go back to pairs with another (fewer shuffles than transposing
 * rows into x, y, w vectors). Two stages, software-pipelined: stage 1 of
 * block t (loads up to the sqrt) is issued before stage 2 of block t − 1 (the
 * rest, ending in the stores), which the plan allows by keeping adjacent
 * blocks apart, so the processor's window need not hold a block's whole
 * load → sqrt → division → store chain. On a 128² cloth: 3.0 ms a step with
 * transposed lanes in a plain loop (AVX2), 2.3 / 2.5 ms like this (AVX-512VL /
 * AVX2 builds; before rigid runs and rows kept across sweeps). */
typedef struct stage1 {
    __m256d pa02, pa13, pb02, pb13, wa02, wa13, wb02, wb13, d02, d13, len;
} stage1;

TT_AVX2 TT_INLINE void stage1_run(stage1 *o, const kern_in *in, uint32_t i)
{
    const double *pk = in->pk;
    const uint32_t *ra = in->ra + i, *rb = in->rb + i;
    tt__rows_load2(pk, ra[0], ra[2], &o->pa02, &o->wa02);
    tt__rows_load2(pk, ra[1], ra[3], &o->pa13, &o->wa13);
    tt__rows_load2(pk, rb[0], rb[2], &o->pb02, &o->wb02);
    tt__rows_load2(pk, rb[1], rb[3], &o->pb13, &o->wb13);
    o->d02 = _mm256_sub_pd(o->pb02, o->pa02); /* dx0 dy0 dx2 dy2 */
    o->d13 = _mm256_sub_pd(o->pb13, o->pa13);
    const __m256d q02 = _mm256_mul_pd(o->d02, o->d02), q13 = _mm256_mul_pd(o->d13, o->d13);
    /* unpacklo: dx² of links 0 1 2 3, unpackhi: dy²; then dx² + dy² as the scalar adds them */
    o->len = _mm256_sqrt_pd(_mm256_add_pd(_mm256_unpacklo_pd(q02, q13), _mm256_unpackhi_pd(q02, q13)));
}

TT_AVX2 TT_INLINE __m256d stage2_run(const stage1 *o, const kern_in *in, uint32_t i, __m256d err, bool xpbd, bool rigid)
{
    const __m256d zero = _mm256_setzero_pd(), sign = _mm256_set1_pd(-0.0);
    double *pk = in->pk;
    const uint32_t *ra = in->ra + i, *rb = in->rb + i;
    const __m256d wa02 = o->wa02, wa13 = o->wa13, wb02 = o->wb02, wb13 = o->wb13;
    const __m256d ws = _mm256_add_pd(_mm256_blend_pd(wa02, wa13, 0xA), _mm256_blend_pd(wb02, wb13, 0xA));
    /* c = min(len − lo, 0) + max(len − hi, 0) is the scalar's three cases bit
     * for bit: lo <= hi, so one term is +0, and min/max give the 0 for NaN.
     * Rigid (lo = hi): len − lo, NaN for NaN, which the ordered c != 0 below
     * turns off as the scalar's c = 0 would. */
    const __m256d c = rigid ? _mm256_sub_pd(o->len, _mm256_loadu_pd(in->lo + i))
                            : _mm256_add_pd(_mm256_min_pd(_mm256_sub_pd(o->len, _mm256_loadu_pd(in->lo + i)), zero),
                                            _mm256_max_pd(_mm256_sub_pd(o->len, _mm256_loadu_pd(in->hi + i)), zero));
    /* as the scalar loop skips: ws == 0, c == 0 (no error) */
    const __m256d act = _mm256_and_pd(_mm256_cmp_pd(ws, zero, _CMP_NEQ_UQ), _mm256_cmp_pd(c, zero, _CMP_NEQ_OQ));
    err = _mm256_max_pd(err, _mm256_and_pd(_mm256_andnot_pd(sign, c), act)); /* |c| of an active lane: >= 0, not NaN */
    __m256d len = o->len, d02 = o->d02, d13 = o->d13; /* the divisor and direction below */
    const __m256d one = _mm256_and_pd(act, _mm256_cmp_pd(len, zero, _CMP_EQ_OQ));
    if (TT_UNLIKELY(in->apart && _mm256_movemask_pd(one))) { /* the scalar's direction for two particles on one spot */
        const __m256d unit = _mm256_setr_pd(1.0, 0.0, 1.0, 0.0);
        len = _mm256_blendv_pd(len, _mm256_set1_pd(1.0), one);
        d02 = _mm256_blendv_pd(d02, unit, _mm256_unpacklo_pd(one, one));
        d13 = _mm256_blendv_pd(d13, unit, _mm256_unpackhi_pd(one, one));
    }
    /* length 0 left (not the first sweep): error, no move */
    const __m256d upd = _mm256_and_pd(act, _mm256_cmp_pd(len, zero, _CMP_NEQ_UQ));
    __m256d s = _mm256_div_pd(_mm256_mul_pd(_mm256_loadu_pd(in->k + i), c), _mm256_mul_pd(ws, len));
    if (xpbd) {
        const __m256d alpha = _mm256_loadu_pd(in->alpha + i);
        const __m256d xp = _mm256_and_pd(upd, _mm256_cmp_pd(alpha, zero, _CMP_GT_OQ));
        if (_mm256_movemask_pd(xp)) {
            tt__dist_x *x = in->x + i;
            __m256d lam = _mm256_set_pd(x[3].lambda, x[2].lambda, x[1].lambda, x[0].lambda);
            const __m256d at = _mm256_mul_pd(alpha, _mm256_set1_pd(in->inv_h2));
            const __m256d dl = _mm256_div_pd(_mm256_sub_pd(_mm256_xor_pd(c, sign), _mm256_mul_pd(at, lam)), _mm256_add_pd(ws, at));
            lam = _mm256_blendv_pd(lam, _mm256_add_pd(lam, dl), xp);
            const __m128d l01 = _mm256_castpd256_pd128(lam), l23 = _mm256_extractf128_pd(lam, 1);
            _mm_storel_pd(&x[0].lambda, l01);
            _mm_storeh_pd(&x[1].lambda, l01);
            _mm_storel_pd(&x[2].lambda, l23);
            _mm_storeh_pd(&x[3].lambda, l23);
            s = _mm256_blendv_pd(s, _mm256_div_pd(_mm256_xor_pd(dl, sign), len), xp); /* −v: the sign bit */
        }
    }
    /* back to pairs: (s·dx, s·dy) as the scalar's cx, cy; x + w·cx, as it adds */
    const __m256d c02 = _mm256_mul_pd(_mm256_unpacklo_pd(s, s), d02), c13 = _mm256_mul_pd(_mm256_unpackhi_pd(s, s), d13);
    __m256d na02 = _mm256_add_pd(o->pa02, _mm256_mul_pd(wa02, c02)), na13 = _mm256_add_pd(o->pa13, _mm256_mul_pd(wa13, c13));
    __m256d nb02 = _mm256_sub_pd(o->pb02, _mm256_mul_pd(wb02, c02)), nb13 = _mm256_sub_pd(o->pb13, _mm256_mul_pd(wb13, c13));
    if (_mm256_movemask_pd(upd) != 15) { /* a lane that must not move keeps its old value (old + 0 could turn −0 into +0) */
        const __m256d u02 = _mm256_unpacklo_pd(upd, upd), u13 = _mm256_unpackhi_pd(upd, upd);
        na02 = _mm256_blendv_pd(o->pa02, na02, u02);
        na13 = _mm256_blendv_pd(o->pa13, na13, u13);
        nb02 = _mm256_blendv_pd(o->pb02, nb02, u02);
        nb13 = _mm256_blendv_pd(o->pb13, nb13, u13);
    }
    tt__rows_store2(pk, ra[0], ra[2], na02);
    tt__rows_store2(pk, ra[1], ra[3], na13);
    tt__rows_store2(pk, rb[0], rb[2], nb02);
    tt__rows_store2(pk, rb[1], rb[3], nb13);
    return err;
}

/* A run of nb blocks, each apart from the one before; returns the largest error. */
TT_AVX2 TT_INLINE double run_pairs(const kern_in *in_, uint32_t nb, bool xpbd, bool rigid)
{
    const kern_in local = *in_, *in = &local; /* fields stay in registers: no store can reach them */
    __m256d err = _mm256_setzero_pd();
    stage1 A, B; /* unrolled by two so both stay in registers */
    stage1_run(&A, in, 0);
    uint32_t t = 1;
    for (; t + 1 < nb; t += 2) {
        stage1_run(&B, in, 4 * t);
        err = stage2_run(&A, in, 4 * t - 4, err, xpbd, rigid);
        stage1_run(&A, in, 4 * t + 4);
        err = stage2_run(&B, in, 4 * t, err, xpbd, rigid);
    }
    if (t < nb) {
        stage1_run(&B, in, 4 * t);
        err = stage2_run(&A, in, 4 * t - 4, err, xpbd, rigid);
        err = stage2_run(&B, in, 4 * t, err, xpbd, rigid);
    } else {
        err = stage2_run(&A, in, 4 * t - 4, err, xpbd, rigid);
    }
    double e[4];
    _mm256_storeu_pd(e, err);
    return max_lanes(e, 4);
}

/* The same code for AVX2, and with AVX-512VL for its 32 registers (fewer
 * spills); each with and without the XPBD branch, for rigid runs or not. */
typedef double (*run_fn)(const kern_in *, uint32_t);
#define TT_RUNS(T, name)                                                                             \
    T static double name##_gg(const kern_in *in, uint32_t nb) { return run_pairs(in, nb, false, false); } \
    T static double name##_gr(const kern_in *in, uint32_t nb) { return run_pairs(in, nb, false, true); }  \
    T static double name##_xg(const kern_in *in, uint32_t nb) { return run_pairs(in, nb, true, false); }  \
    T static double name##_xr(const kern_in *in, uint32_t nb) { return run_pairs(in, nb, true, true); }
TT_RUNS(TT_AVX2, run_avx2)
TT_RUNS(TT_AVX512, run_avx512)
#undef TT_RUNS
static const run_fn runs_avx2[4] = {run_avx2_gg, run_avx2_gr, run_avx2_xg, run_avx2_xr};
static const run_fn runs_avx512[4] = {run_avx512_gg, run_avx512_gr, run_avx512_xg, run_avx512_xr};

/* Links [u0, u1) of a run of vector blocks [v0, v0 + 4·nb): the whole
 * blocks inside in lanes, the links of a block cut by u0 or u1 through the
 * scalar loop on the rows (the same result, link by link in order). */
TT_AVX2 static double run_part(tt_world *w, tt__cgroup *g, const tt__block *b, run_fn run, uint32_t v0, uint32_t nb, uint32_t u0,
                               uint32_t u1, double err)
{
    double *pk = b->lay->x;
    const uint32_t lo = u0 > v0 ? u0 : v0, hi = u1 < v0 + 4 * nb ? u1 : v0 + 4 * nb;
    if (lo >= hi) return err;
    uint32_t a = v0 + (lo - v0 + 3) / 4 * 4, e = v0 + (hi - v0) / 4 * 4; /* whole blocks: [a, e) */
    if (a > hi) a = hi;
    err = sweep_distance(w, g, b->h, false, b->first, pk, pk + 1, pk + 2, 4, lo, a, err);
    if (a < e) {
        const kern_in in = {pk, g->scr.h_lo + a, g->scr.h_hi + a, g->scr.h_k + a, g->scr.h_alpha + a, g->scr.h_ra + a, g->scr.h_rb + a,
                            g->dx + a, 1.0 / (b->h * b->h), b->first};
        const double m = run(&in, (e - a) / 4);
        if (m > err) err = m; /* a max: the order it is taken in does not matter */
    }
    return sweep_distance(w, g, b->h, false, b->first, pk, pk + 1, pk + 2, 4, a > e ? a : e, hi, err);
}

/* Links [u0, u1) by the plan: its scalar runs (on the rows, through the
 * scalar loop itself) and vector runs; runs[2·xpbd + rigid]. */
TT_AVX2 static double sweep_planned(tt_world *w, tt__cgroup *g, const tt__block *b, const run_fn *runs, uint32_t u0, uint32_t u1)
{
    double *pk = b->lay->x;
    const int xpbd = g->nxpbd > 0; /* else no lane has alpha > 0: the kernels without that branch */
    double err = 0.0;
    uint32_t i = 0;
    for (uint32_t k = 0; k < g->scr.nplan && i < u1; k += 2) {
        const uint32_t ns = g->scr.plan[k], nb = g->scr.plan[k + 1] & ~PLAN_RIGID;
        const uint32_t lo = u0 > i ? u0 : i, hi = u1 < i + ns ? u1 : i + ns;
        if (lo < hi) err = sweep_distance(w, g, b->h, false, b->first, pk, pk + 1, pk + 2, 4, lo, hi, err);
        i += ns;
        if (!nb) continue;
        err = run_part(w, g, b, runs[2 * xpbd + (g->scr.plan[k + 1] >= PLAN_RIGID)], i, nb, u0, u1, err);
        i += 4 * nb;
    }
    return err;
}
#endif

/* The plan wanted at the next sweep, before a step: its arrays are then in
 * place, so a plan redone inside the step (links broke: fewer of them)
 * allocates nothing. */
bool tt__distance_plan_reserve(tt_world *w, tt__cgroup *g)
{
    if (w->order != TT_GAUSS_SEIDEL || tt__simd_kind(g->simd) == TT__SIMD_SCALAR || g->ndist < 8) return true;
    return (g->scr.plan_ok && g->scr.plan_w == 4) || plan_build(g, 4, 2);
}

bool tt__distance_wants_rows(const tt_world *w, const tt__cgroup *g)
{
    return w->order == TT_GAUSS_SEIDEL && tt__simd_kind(g->simd) != TT__SIMD_SCALAR && g->ndist >= 8;
}

double tt__distance_sweep_gs(tt_world *w, tt__cgroup *g, const tt__block *b, uint32_t u0, uint32_t u1)
{
    const tt__lay *L = b->lay;
    uint8_t kind = tt__simd_kind(g->simd);
    if (kind != TT__SIMD_SCALAR && g->ndist >= 8 && !(g->scr.plan_ok && g->scr.plan_w == 4) && !plan_build(g, 4, 2))
        kind = TT__SIMD_SCALAR;
    if (kind == TT__SIMD_SCALAR || g->ndist < 8 || L->st != 4) {
        if (L->st == 4) /* the rows without lanes: plan refused (no memory) */
            return sweep_distance(w, g, b->h, false, b->first, L->x, L->x + 1, L->x + 2, 4, u0, u1, 0.0);
        return sweep_distance(w, g, b->h, false, b->first, L->x, L->y, L->im, 1, u0, u1, 0.0);
    }
#ifdef TT_SIMD_X86
    return sweep_planned(w, g, b, kind == TT__SIMD_AVX512 ? runs_avx512 : runs_avx2, u0, u1);
#else
    return 0.0;
#endif
}

double tt__distance_sweep_jacobi(tt_world *w, tt__cgroup *g, const tt__block *b, uint32_t u0, uint32_t u1)
{
    return sweep_distance(w, g, b->h, true, b->first, b->lay->x, b->lay->y, b->lay->im, 1, u0, u1, 0.0); /* Jacobi: st = 1 */
}

