/* tether — the velocity pass of the batches' pairs (contact_batch.c) in
 * vector lanes: contact_response.c's pair_end for Verlet worlds, lane by
 * lane the same arithmetic in the same order, so the bits are the same. */
#include "collide_internal.h"

#include <string.h>

#ifdef TT_SIMD_X86
#define LO TT__LO
#define HI TT__HI
#define LANES TT__LANES

/* respond's Coulomb friction, lane by lane, for respond4 below: r the
 * relative velocity and n the normal in pair form, vn the normal speed,
 * change the normal velocity change (Δvn). A lane sticks (tangential
 * velocity within μs·Δvn: st gets it, to undo as a slide) or slides (dv
 * loses μk·Δvn of it). */
TT_AVX2 TT_INLINE void friction4(__m256d mus, __m256d muk, __m256d r02, __m256d r13, __m256d n02, __m256d n13, __m256d vn,
                                 __m256d change, __m256d act, __m256d *dv02, __m256d *dv13, __m256d *st02, __m256d *st13)
{
    const __m256d one = _mm256_set1_pd(1.0);
    const __m256d t02 = _mm256_sub_pd(r02, _mm256_mul_pd(LO(vn), n02)), t13 = _mm256_sub_pd(r13, _mm256_mul_pd(HI(vn), n13));
    const __m256d t2 = LANES(_mm256_mul_pd(t02, t02), _mm256_mul_pd(t13, t13));
    const __m256d lim = _mm256_mul_pd(mus, change);
    const __m256d stick = _mm256_cmp_pd(t2, _mm256_mul_pd(lim, lim), _CMP_LE_OQ);
    const __m256d tl = _mm256_sqrt_pd(t2), mc = _mm256_mul_pd(muk, change);
    const __m256d slides = _mm256_andnot_pd(stick, act);
    const __m256d f = _mm256_div_pd(_mm256_blendv_pd(tl, mc, _mm256_cmp_pd(mc, tl, _CMP_LT_OQ)), _mm256_blendv_pd(one, tl, slides));
    *dv02 = _mm256_blendv_pd(_mm256_sub_pd(*dv02, _mm256_mul_pd(t02, LO(f))), *dv02, LO(stick));
    *dv13 = _mm256_blendv_pd(_mm256_sub_pd(*dv13, _mm256_mul_pd(t13, HI(f))), *dv13, HI(stick));
    *st02 = _mm256_and_pd(t02, LO(stick));
    *st13 = _mm256_and_pd(t13, HI(stick));
}

/* friction4 with the world's materials or, with particle materials, each
 * entry's. Lanes with no friction at all skip it, as respond returns
 * before it (its arithmetic with μ = 0 could turn a −0 velocity change
 * into +0); so do the rubbed lanes (anchored friction: the sweeps'). */
TT_AVX2 TT_INLINE void friction_lanes(const tt__batches *B, uint32_t k, const tt__respond_in *in, __m256d rubbed, __m256d r02,
                                      __m256d r13, __m256d n02, __m256d n13, __m256d vn, __m256d change, __m256d act,
                                      __m256d *dv02, __m256d *dv13, __m256d *st02, __m256d *st13)
{
    const __m256d zero = _mm256_setzero_pd();
    __m256d mus, muk, rough;
    if (!in->mat) {
        if (in->mus == 0.0 && in->muk == 0.0) return;
        mus = _mm256_set1_pd(in->mus);
        muk = _mm256_set1_pd(in->muk);
        if (!_mm256_movemask_pd(rubbed)) {
            friction4(mus, muk, r02, r13, n02, n13, vn, change, act, dv02, dv13, st02, st13);
            return;
        }
        rough = _mm256_andnot_pd(rubbed, act);
    } else {
        mus = _mm256_loadu_pd(B->me + B->cap + k);
        muk = _mm256_loadu_pd(B->me + 2 * (size_t)B->cap + k);
        const __m256d none = _mm256_and_pd(_mm256_cmp_pd(mus, zero, _CMP_EQ_OQ), _mm256_cmp_pd(muk, zero, _CMP_EQ_OQ));
        rough = _mm256_andnot_pd(_mm256_or_pd(none, rubbed), act);
    }
    if (!_mm256_movemask_pd(rough)) return;
    __m256d f02 = *dv02, f13 = *dv13;
    friction4(mus, muk, r02, r13, n02, n13, vn, change, act, &f02, &f13, st02, st13);
    *dv02 = _mm256_blendv_pd(*dv02, f02, LO(rough));
    *dv13 = _mm256_blendv_pd(*dv13, f13, HI(rough));
    *st02 = _mm256_and_pd(*st02, LO(rough));
    *st13 = _mm256_and_pd(*st13, HI(rough));
}

/* pair_end's Verlet arithmetic (contact_response.c, with respond), lane by lane in
 * the same order, in pair form on xy rows: positions, (x_old, y_old) and
 * the pre-solve (vx, vy). The normal from the final positions,
 * restitution or no approach (settled: no more separation than before the
 * sweeps), Coulomb friction (sticking undoes the tangential slide, sliding
 * removes μk·Δvn), then x moved by the slide undone and x_old by the
 * velocity change. Per-lane values (link order 0 1 2 3) come from pair form
 * with one unpack, as in the sweep kernel. Returns false, touching nothing,
 * when an active lane has two particles on one centre. */
TT_AVX2 TT_INLINE bool respond4(const tt__batches *B, uint32_t k, const tt__respond_in *in, double dtp)
{
    const __m256d zero = _mm256_setzero_pd(), sign = _mm256_set1_pd(-0.0);
    const __m256d lam = _mm256_loadu_pd(B->lam + k);
    const __m256d live = _mm256_cmp_pd(lam, zero, _CMP_GT_OQ);
    if (!_mm256_movemask_pd(live)) return true;
    double *xy = B->xy, *q = B->q;
    const double *v0 = B->v0;
    const uint32_t *A = B->a + k, *Bb = B->b + k;
    const __m256d pa02 = tt__xy_load2(xy, A[0], A[2]), pa13 = tt__xy_load2(xy, A[1], A[3]);
    const __m256d pb02 = tt__xy_load2(xy, Bb[0], Bb[2]), pb13 = tt__xy_load2(xy, Bb[1], Bb[3]);
    const __m256d ia = _mm256_loadu_pd(B->ka + k), ib = _mm256_loadu_pd(B->kb + k), ws = _mm256_add_pd(ia, ib);
    const __m256d act = _mm256_and_pd(live, _mm256_cmp_pd(ws, zero, _CMP_NEQ_UQ));
    const int m = _mm256_movemask_pd(act);
    if (!m) return true;
    const __m256d d02 = _mm256_sub_pd(pa02, pb02), d13 = _mm256_sub_pd(pa13, pb13);
    const __m256d s02 = _mm256_mul_pd(d02, d02), s13 = _mm256_mul_pd(d13, d13);
    const __m256d d2 = _mm256_add_pd(_mm256_unpacklo_pd(s02, s13), _mm256_unpackhi_pd(s02, s13));
    if (_mm256_movemask_pd(_mm256_and_pd(act, _mm256_cmp_pd(d2, zero, _CMP_NGT_UQ)))) return false; /* one centre */
    const __m256d qa02 = tt__xy_load2(q, A[0], A[2]), qa13 = tt__xy_load2(q, A[1], A[3]);
    const __m256d qb02 = tt__xy_load2(q, Bb[0], Bb[2]), qb13 = tt__xy_load2(q, Bb[1], Bb[3]);
    const __m256d va02 = tt__xy_load2(v0, A[0], A[2]), va13 = tt__xy_load2(v0, A[1], A[3]);
    const __m256d vb02 = tt__xy_load2(v0, Bb[0], Bb[2]), vb13 = tt__xy_load2(v0, Bb[1], Bb[3]);
    const __m256d e = in->mat ? _mm256_loadu_pd(B->me + k) : _mm256_set1_pd(in->e); /* the world's, or the entries' */
    const __m256d one = _mm256_set1_pd(1.0), dt = _mm256_set1_pd(dtp), idt = _mm256_set1_pd(1.0 / dtp);
    /* lanes out of play divide by 1 (no exception the scalar code would not raise) */
    const __m256d iws = _mm256_div_pd(one, _mm256_blendv_pd(one, ws, act)), wa = _mm256_mul_pd(ia, iws), wb = _mm256_mul_pd(ib, iws);
    const __m256d id = _mm256_div_pd(one, _mm256_sqrt_pd(_mm256_blendv_pd(one, d2, act)));
    const __m256d n02 = _mm256_mul_pd(d02, LO(id)), n13 = _mm256_mul_pd(d13, HI(id));
    /* relative velocity ((xa − xa_old) − (xb − xb_old))·(1/dt), as pair_end; and before the sweeps */
    const __m256d r02 = _mm256_mul_pd(_mm256_sub_pd(_mm256_sub_pd(pa02, qa02), _mm256_sub_pd(pb02, qb02)), idt);
    const __m256d r13 = _mm256_mul_pd(_mm256_sub_pd(_mm256_sub_pd(pa13, qa13), _mm256_sub_pd(pb13, qb13)), idt);
    const __m256d o02 = _mm256_sub_pd(va02, vb02), o13 = _mm256_sub_pd(va13, vb13);
    const __m256d vn0 = LANES(_mm256_mul_pd(o02, n02), _mm256_mul_pd(o13, n13));
    const __m256d vn = LANES(_mm256_mul_pd(r02, n02), _mm256_mul_pd(r13, n13));
    const __m256d up = _mm256_and_pd(vn, _mm256_cmp_pd(vn, zero, _CMP_GT_OQ));
    const __m256d up0 = _mm256_and_pd(vn0, _mm256_cmp_pd(vn0, zero, _CMP_GT_OQ));
    __m256d target = _mm256_blendv_pd(up, up0, _mm256_cmp_pd(up, up0, _CMP_GT_OQ));
    target = _mm256_blendv_pd(target, _mm256_mul_pd(_mm256_xor_pd(e, sign), vn0),
                              _mm256_cmp_pd(vn0, _mm256_set1_pd(-in->thr), _CMP_LT_OQ));
    __m256d change = _mm256_sub_pd(target, vn0);
    change = _mm256_blendv_pd(change, zero, _mm256_cmp_pd(change, zero, _CMP_LT_OQ));
    const __m256d tv = _mm256_sub_pd(target, vn);
    __m256d dv02 = _mm256_mul_pd(LO(tv), n02), dv13 = _mm256_mul_pd(HI(tv), n13), st02 = zero, st13 = zero;
    const uint8_t *rb = in->rubbed ? in->rubbed + k : NULL;
    const __m256d rubbed = rb ? _mm256_cmp_pd(_mm256_set_pd(rb[3], rb[2], rb[1], rb[0]), zero, _CMP_NEQ_OQ) : zero;
    friction_lanes(B, k, in, rubbed, r02, r13, n02, n13, vn, change, act, &dv02, &dv13, &st02, &st13);
    /* a lane slid (its stick velocity is not zero): x moves back; both components of a lane agree */
    const __m256d z02 = _mm256_cmp_pd(st02, zero, _CMP_NEQ_UQ), z13 = _mm256_cmp_pd(st13, zero, _CMP_NEQ_UQ);
    const __m256d m02 = LO(act), m13 = HI(act);
    const __m256d sl02 = _mm256_and_pd(_mm256_or_pd(z02, _mm256_permute_pd(z02, 5)), m02);
    const __m256d sl13 = _mm256_and_pd(_mm256_or_pd(z13, _mm256_permute_pd(z13, 5)), m13);
    const __m256d h = _mm256_set1_pd(in->h);
    const __m256d wa02l = LO(wa), wa13l = HI(wa), wb02l = LO(wb), wb13l = HI(wb);
    const __m256d hs02 = _mm256_mul_pd(st02, h), hs13 = _mm256_mul_pd(st13, h);
    const __m256d nhs02 = _mm256_mul_pd(_mm256_xor_pd(st02, sign), h), nhs13 = _mm256_mul_pd(_mm256_xor_pd(st13, sign), h);
    tt__xy_store2(xy, A[0], A[2], _mm256_blendv_pd(pa02, _mm256_sub_pd(pa02, _mm256_mul_pd(hs02, wa02l)), sl02));
    tt__xy_store2(xy, A[1], A[3], _mm256_blendv_pd(pa13, _mm256_sub_pd(pa13, _mm256_mul_pd(hs13, wa13l)), sl13));
    tt__xy_store2(xy, Bb[0], Bb[2], _mm256_blendv_pd(pb02, _mm256_sub_pd(pb02, _mm256_mul_pd(nhs02, wb02l)), sl02));
    tt__xy_store2(xy, Bb[1], Bb[3], _mm256_blendv_pd(pb13, _mm256_sub_pd(pb13, _mm256_mul_pd(nhs13, wb13l)), sl13));
    const __m256d qa02n = _mm256_sub_pd(qa02, _mm256_mul_pd(_mm256_mul_pd(dv02, wa02l), dt));
    const __m256d qa13n = _mm256_sub_pd(qa13, _mm256_mul_pd(_mm256_mul_pd(dv13, wa13l), dt));
    const __m256d qb02n = _mm256_sub_pd(qb02, _mm256_mul_pd(_mm256_mul_pd(_mm256_xor_pd(dv02, sign), wb02l), dt));
    const __m256d qb13n = _mm256_sub_pd(qb13, _mm256_mul_pd(_mm256_mul_pd(_mm256_xor_pd(dv13, sign), wb13l), dt));
    tt__xy_store2(q, A[0], A[2], _mm256_blendv_pd(qa02, qa02n, m02));
    tt__xy_store2(q, A[1], A[3], _mm256_blendv_pd(qa13, qa13n, m13));
    tt__xy_store2(q, Bb[0], Bb[2], _mm256_blendv_pd(qb02, qb02n, m02));
    tt__xy_store2(q, Bb[1], Bb[3], _mm256_blendv_pd(qb13, qb13n, m13));
    return true;
}
#undef LO
#undef HI
#undef LANES

/* Rows and world arrays agree again for batch k's particles: to the world
 * (to_world) before the scalar code takes the batch, back after. */
static void sync_batch(tt_world *w, tt__batches *B, uint32_t k, bool to_world)
{
    for (uint32_t j = k; j < k + 4; j++) {
        const uint32_t ids[2] = {B->a[j], B->b[j]};
        for (int s = 0; s < 2; s++) {
            const uint32_t i = ids[s];
            if (i >= B->np) continue; /* padding */
            double *p = B->xy + 2 * (size_t)i, *q = B->q + 2 * (size_t)i;
            if (to_world) {
                w->px[i] = p[0], w->py[i] = p[1], w->qx[i] = q[0], w->qy[i] = q[1];
            } else {
                p[0] = w->px[i], p[1] = w->py[i], q[0] = w->qx[i], q[1] = w->qy[i];
            }
        }
    }
}

TT_AVX2 TT_INLINE void respond_run(tt_world *w, tt__batches *B, const tt__respond_in *in, void (*one)(void *, uint32_t),
                                   void *ctx)
{
    const double dtp = w->dt_prev;
    for (uint32_t k = 0; k < B->n; k += 4) {
        if (!(B->solo[k / 4] & TT__SOLO_SHARED) && respond4(B, k, in, dtp)) continue;
        sync_batch(w, B, k, true);
        for (uint32_t j = k; j < k + 4; j++)
            if (B->lam[j] > 0.0) one(ctx, j);
        sync_batch(w, B, k, false);
    }
}

TT_AVX2 static void respond_avx2(tt_world *w, tt__batches *B, const tt__respond_in *in, void (*one)(void *, uint32_t), void *ctx)
{
    respond_run(w, B, in, one, ctx);
}
TT_AVX512 static void respond_avx512(tt_world *w, tt__batches *B, const tt__respond_in *in, void (*one)(void *, uint32_t),
                                     void *ctx)
{
    respond_run(w, B, in, one, ctx);
}
#endif

/* Each touched entry's materials as pair_end takes them (the larger
 * restitution, the geometric means of the frictions), into B->me. Only
 * those: the lanes of the others are masked out of every result, so what
 * an earlier step left there (finite: the array is zeroed when it grows)
 * changes nothing, and a third of the entries cost nothing here. */
static bool entry_materials(tt__batches *B, const tt__collide *c)
{
    const uint32_t had = B->me_cap;
    if (!tt__grow((void **)&B->me, &B->me_cap, B->cap, 3 * sizeof *B->me)) return false;
    if (B->me_cap != had) memset(B->me, 0, (size_t)B->me_cap * 3 * sizeof *B->me);
    double *E = B->me, *S = B->me + B->cap, *K = B->me + 2 * (size_t)B->cap;
    for (uint32_t t = 0; t < c->scr.ntouch; t++) {
        const uint32_t k = c->scr.touch[t], a = B->a[k], b = B->b[k];
        E[k] = tt__max(tt__mat(c, a, 0), tt__mat(c, b, 0));
        S[k] = sqrt(tt__mat(c, a, 1) * tt__mat(c, b, 1));
        K[k] = sqrt(tt__mat(c, a, 2) * tt__mat(c, b, 2));
    }
    return true;
}

bool tt__batches_respond(tt_world *w, tt__batches *B, const tt__respond_in *in, void (*one)(void *, uint32_t), void *ctx)
{
#ifdef TT_SIMD_X86
    const uint8_t kind = tt__simd_kind(B->simd);
    const uint32_t np = B->np;
    if (kind == TT__SIMD_SCALAR || !tt__xy_reserve(&B->xy, &B->xy_cap, np + 1) ||
        !tt__xy_reserve(&B->q, &B->q_cap, np + 1) || !tt__xy_reserve(&B->v0, &B->v0_cap, np + 1) ||
        (in->mat && !entry_materials(B, in->mat)))
        return false;
    tt__xy_pack(B->xy, w->px, w->py, np);
    tt__xy_pack(B->q, w->qx, w->qy, np);
    tt__xy_pack(B->v0, in->vx0, in->vy0, np);
    for (int j = 0; j < 2; j++) B->xy[2 * (size_t)np + j] = B->q[2 * (size_t)np + j] = B->v0[2 * (size_t)np + j] = 0.0; /* padding */
    if (kind == TT__SIMD_AVX512) respond_avx512(w, B, in, one, ctx);
    else respond_avx2(w, B, in, one, ctx);
    tt__xy_unpack(B->xy, w->px, w->py, np);
    tt__xy_unpack(B->q, w->qx, w->qy, np);
    return true;
#else
    (void)w, (void)B, (void)in, (void)one, (void)ctx;
    return false;
#endif
}
