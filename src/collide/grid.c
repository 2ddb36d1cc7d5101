/* tether — the uniform-grid broadphase for particles. Each build is a
 * counting sort of the live particles into square cells at least one
 * largest diameter (plus the contact margin) wide, so touching particles sit
 * in the same or neighbouring cells. The grid spans the particles' bounding
 * box; when that would need too many cells (a few particles far away), it
 * spans mean ± 4σ instead and particles outside are clamped into the border
 * cells. Clamping keeps neighbours neighbours (it is monotone and moves no
 * pair of cells further apart), so no pair is ever missed, however far.
 * Arrays grow with the particle count and are reused: no per-step malloc. */
#include "collide_internal.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

/* Entries after the last sorted one: the vector test reads whole groups of four. */
#define TT__GRID_PAD 3
/* Most cells a grid may have, far above the 4 per particle it aims for. */
#define TT__GRID_MAX_CELLS 1073741824.0

static bool grow_n(tt__grid *g, uint32_t need)
{
    if (need <= g->cap_n) return true;
    uint32_t n = g->cap_n ? g->cap_n : 256;
    while (n < need) n = n > UINT32_MAX / 2 ? need : n * 2;
    void *p;
#define GROW(f, t, pad) if (!(p = realloc(g->f, ((size_t)n + pad) * sizeof(t)))) return false; g->f = p
    GROW(cell, uint32_t, 0); GROW(idx, uint32_t, TT__GRID_PAD); GROW(bits, uint8_t, 0); GROW(out_list, uint32_t, 0); GROW(list, uint32_t, 0);
    GROW(sx, double, TT__GRID_PAD); GROW(sy, double, TT__GRID_PAD); GROW(sr, double, TT__GRID_PAD);
#undef GROW
    g->cap_n = n;
    return true;
}

/* Cells across [lo, hi]: bounded while still a double, since a cell size
 * of 1e-300 asks for 1e302 of them (no int holds that), and at least one,
 * should a rounding ever invert the span. */
static int32_t cells_across(double lo, double hi, double inv)
{
    const double n = floor((hi - lo) * inv) + 1.0;
    return n >= 1.0 ? (int32_t)fmin(n, 1e9) : 1;
}

static void fit(tt__grid *g, double lox, double loy, double hix, double hiy)
{
    g->ox = lox;
    g->oy = loy;
    g->inv = 1.0 / g->cs;
    g->nx = cells_across(lox, hix, g->inv);
    g->ny = cells_across(loy, hiy, g->inv);
}

/* The counting sort of the live particles (list[0..n) when list is not
 * NULL, else slots 0..n) into the grid's ncell cells, laid out: each
 * particle's cell, the cells' starts, the sorted copies. */
TT_INLINE void sort_into_cells(const tt_world *w, tt__grid *g, const uint32_t *list, uint32_t n)
{
    /* locals: the uint8_t stores below may alias any field of w or g */
    const uint16_t *flags = w->flags;
    const double *px = w->px, *py = w->py, *im = w->inv_mass;
    const float *rad = w->radius;
    const uint32_t m = g->n, ncell = g->ncell;
    uint32_t *start = g->start, *cell = g->cell, *idx = g->idx, *out_list = g->out_list, nout = 0;
    double *sx = g->sx, *sy = g->sy, *sr = g->sr;
    uint8_t *bits = g->bits;
    uint32_t npinned = 0;
    memset(start, 0, (size_t)ncell * sizeof *start);
    const double ox = g->ox, oy = g->oy, inv = g->inv;
    const int32_t nx = g->nx, ny = g->ny;
    for (uint32_t k = 0; k < n; k++) {
        const uint32_t i = list ? list[k] : k;
        if (!(flags[i] & TT__PF_ALIVE)) continue;
        int32_t cx = tt__cell_coord(px[i], ox, inv), cy = tt__cell_coord(py[i], oy, inv);
        bool out = cx < 0 || cy < 0 || cx >= nx || cy >= ny;
        if (TT_UNLIKELY(out)) {
            cx = cx < 0 ? 0 : cx >= nx ? nx - 1 : cx;
            cy = cy < 0 ? 0 : cy >= ny ? ny - 1 : cy;
            out_list[nout++] = i;
        }
        uint32_t c = (uint32_t)cy * (uint32_t)nx + (uint32_t)cx;
        cell[i] = c | (out ? 0x80000000u : 0u);
        start[c]++;
    }
    g->nout = nout;
    uint32_t sum = 0; /* start[c] becomes the end of cell c */
    for (uint32_t c = 0; c < ncell; c++) start[c] = sum += start[c];
    start[ncell] = m;
    /* scatter backwards, so each cell fills from its end and keeps slot order
     * (stable, deterministic); start[c] ends at cell c's beginning */
    for (uint32_t q = n; q-- > 0;) {
        const uint32_t i = list ? list[q] : q;
        if (!(flags[i] & TT__PF_ALIVE)) continue;
        uint32_t c = cell[i] & 0x7FFFFFFFu, k = --start[c];
        idx[k] = i;
        sx[k] = px[i];
        sy[k] = py[i];
        sr[k] = rad[i];
        bits[k] = (uint8_t)((cell[i] >> 31) | (im[i] == 0.0 ? TT__GRID_PINNED : 0));
        npinned += im[i] == 0.0;
    }
    g->npinned = npinned;
    for (uint32_t k = m; k < m + TT__GRID_PAD; k++) { /* read, never used */
        sx[k] = sy[k] = sr[k] = 0.0;
        idx[k] = 0;
    }
}

bool tt__grid_any_radius(const tt_world *w, uint32_t n)
{
    /* on bits, sixteen radii a round in the compiler's generic vectors: +0 is the one float of all-zero bits */
    typedef uint32_t v4u __attribute__((vector_size(16)));
    const float *rad = w->radius;
    v4u acc = {0, 0, 0, 0};
    uint32_t i = 0;
    for (; i + 16 <= n; i += 16) {
        v4u a, b, c, d;
        memcpy(&a, rad + i, sizeof a);
        memcpy(&b, rad + i + 4, sizeof b);
        memcpy(&c, rad + i + 8, sizeof c);
        memcpy(&d, rad + i + 12, sizeof d);
        acc |= (a | b) | (c | d);
    }
    uint32_t any = acc[0] | acc[1] | acc[2] | acc[3];
    for (; i < n; i++) {
        uint32_t b;
        memcpy(&b, rad + i, sizeof b);
        any |= b;
    }
    return any != 0;
}

/* The most cells a build over n particles can use (the limit below). */
static uint32_t max_cells(uint32_t n) { return (uint32_t)fmin(4.0 * n + 1024.0, TT__GRID_MAX_CELLS); }

bool tt__grid_reserve(tt__grid *g, uint32_t n)
{
    return grow_n(g, n ? n : 1) && tt__grow((void **)&g->start, &g->cap_cells, max_cells(n) + 1, sizeof *g->start);
}

uint32_t tt__grid_max_cells(uint32_t n) { return max_cells(n); }

/* The build over list[0..n), or over slots 0..n when list is NULL: one
 * copy of each, so the plain build pays nothing for the list. */
TT_INLINE bool build(tt_world *w, tt__grid *g, double min_cell, double wide, const uint32_t *list, uint32_t n)
{
    const uint32_t slots = w->ppool.count;
    g->epoch = UINT64_MAX;
    if (!grow_n(g, slots ? slots : 1)) return false;
    const uint16_t *flags = w->flags, *cat = w->category, *msk = w->mask;
    const double *px = w->px, *py = w->py;
    const float *rad = w->radius;
    double lox = INFINITY, loy = INFINITY, hix = -INFINITY, hiy = -INFINITY, rmax = 0.0;
    uint32_t m = 0;
    uint16_t cat_or = 0, cat_and = 0xFFFF, mask_or = 0, mask_and = 0xFFFF;
    for (uint32_t k = 0; k < n; k++) {
        const uint32_t i = list ? list[k] : k;
        if (!(flags[i] & TT__PF_ALIVE)) continue;
        double x = px[i], y = py[i];
        double r = rad[i];
        cat_or |= cat[i]; cat_and &= cat[i];
        mask_or |= msk[i]; mask_and &= msk[i];
        lox = x < lox ? x : lox; hix = x > hix ? x : hix; /* not fmin/fmax: those are library calls here */
        loy = y < loy ? y : loy; hiy = y > hiy ? y : hiy;
        rmax = r > rmax ? r : rmax;
        m++;
    }
    g->n = m;
    g->nout = 0;
    g->rmax = rmax;
    g->one_layer = cat_or == cat_and && mask_or == mask_and && (cat_and & mask_and);
    if (m == 0) {
        g->nx = g->ny = 0;
        g->ncell = 0;
        return true;
    }
    double ex = hix - lox, ey = hiy - loy;
    double cs = fmax(min_cell, 2.0 * rmax * (1.0 + TT__CONTACT_MARGIN));
    if (!(cs > 0.0)) cs = fmax(sqrt(fmax(ex * ey, ex * ex + ey * ey) / m), 1e-6); /* points only: about one per cell */
    cs = fmax(cs, DBL_MIN); /* 1 / 4.9e-324 is inf, and inf · 0 a NaN cell */
    g->cs0 = cs;
    g->extent = fmax(fmax(fabs(lox), fabs(hix)), fmax(fabs(loy), fabs(hiy)));
    if (wide != 1.0 && cs * wide < TT_MAX_VALUE) cs *= wide;
    /* The bound keeps nx·ny, and ncell + 1, inside a uint32_t whatever m is. */
    const double limit = max_cells(m);
    g->cs = cs;
    fit(g, lox, loy, hix, hiy);
    if ((double)g->nx * g->ny > limit) { /* a few particles far away: a second pass for the spread */
        double sx = 0, sy = 0, sxx = 0, syy = 0;
        for (uint32_t k = 0; k < n; k++) {
            const uint32_t i = list ? list[k] : k;
            if (!(flags[i] & TT__PF_ALIVE)) continue;
            double x = px[i], y = py[i];
            sx += x; sy += y; sxx += x * x; syy += y * y;
        }
        /* The mean of equal coordinates can round past them, which would
         * put the whole row outside a grid of no rows: keep it in the box. */
        double mx = fmin(fmax(sx / m, lox), hix), my = fmin(fmax(sy / m, loy), hiy);
        double dx = 4.0 * sqrt(fmax(sxx / m - mx * mx, 0.0)), dy = 4.0 * sqrt(fmax(syy / m - my * my, 0.0));
        double rlx = fmax(lox, mx - dx), rhx = fmin(hix, mx + dx), rly = fmax(loy, my - dy), rhy = fmin(hiy, my + dy);
        fit(g, rlx, rly, rhx, rhy);
        while ((double)g->nx * g->ny > limit) { /* sparse and wide: coarser cells */
            g->cs *= 1.5;
            fit(g, rlx, rly, rhx, rhy);
        }
    }
    const uint32_t ncell = (uint32_t)g->nx * (uint32_t)g->ny;
    if (!tt__grow((void **)&g->start, &g->cap_cells, ncell + 1, sizeof *g->start)) return false;
    g->ncell = ncell;
    sort_into_cells(w, g, list, n);
    return true;
}

bool tt__grid_build(tt_world *w, tt__grid *g, double min_cell) { return build(w, g, min_cell, 1.0, NULL, w->ppool.count); }

bool tt__grid_build_wide(tt_world *w, tt__grid *g, double min_cell, double wide)
{
    return build(w, g, min_cell, wide, NULL, w->ppool.count);
}

bool tt__grid_build_list(tt_world *w, tt__grid *g, double min_cell, uint32_t n)
{
    return build(w, g, min_cell, 1.0, g->list, n);
}

/* The pair list while it is filled: kept in locals, because every store
 * through c->scr.pairs could alias c->scr.npairs and force a reload per pair. */
typedef struct emit {
    tt__pair *p;
    uint32_t n, cap;
} emit;

static bool emit_grow(tt__collide *c, emit *e)
{
    c->scr.npairs = e->n;
    if (!tt__grow((void **)&c->scr.pairs, &c->scr.paircap, e->n + 1, sizeof *c->scr.pairs)) return false;
    e->p = c->scr.pairs;
    e->cap = c->scr.paircap;
    return true;
}

TT_INLINE bool push_pair(tt__collide *c, emit *e, uint32_t a, uint32_t b, double rs)
{
    if (TT_UNLIKELY(e->n == e->cap) && !emit_grow(c, e)) return false;
    tt__pair *p = &e->p[e->n++];
    p->a = a;
    p->b = b;
    p->rs = (float)rs;
    p->lambda = 0.0f;
    return true;
}

/* A hit of sorted particle a (slot; kbits its flags) with sorted j: the
 * filter, then the list. plain: nothing but two pinned particles can exclude
 * a pair (one layer, no exclusions), so the full filter is skipped. */
TT_INLINE bool hit(tt_world *w, tt__collide *c, emit *e, const uint32_t *idx, const uint8_t *gbits, bool plain,
                   uint32_t a, uint8_t kbits, uint32_t j, double rs)
{
    uint32_t b = idx[j];
    if (plain ? kbits & gbits[j] & TT__GRID_PINNED : !tt__pair_filter(w, c, a, b)) return true;
    return push_pair(c, e, a, b, rs);
}

/* Whether every sorted particle in [a, b) has inverse mass 0. A world
 * mostly pinned or asleep asks it per cell: a neighbourhood of such
 * particles makes no pair (both filters refuse two of them), so its
 * distance tests are skipped, which changes no result. */
TT_INLINE bool all_pinned(const uint8_t *bits, uint32_t a, uint32_t b)
{
    for (uint32_t k = a; k < b; k++)
        if (!(bits[k] & TT__GRID_PINNED)) return false;
    return true;
}

/* Pairs of sorted particle k with the sorted range [j0, j1), in j order. */
TT_INLINE bool range_scalar(tt_world *w, tt__collide *c, emit *e, const tt__grid *g, bool plain, uint32_t k,
                            uint32_t j0, uint32_t j1)
{
    const double *sx = g->sx, *sy = g->sy, *sr = g->sr;
    const uint32_t *idx = g->idx; /* read once: the pair stores could alias them */
    const uint8_t *gbits = g->bits;
    const double x = sx[k], y = sy[k], r = sr[k];
    const uint32_t a = idx[k];
    const uint8_t kbits = gbits[k];
    for (uint32_t j = j0; j < j1; j++) {
        double dx = x - sx[j], dy = y - sy[j], rs = r + sr[j];
        if (dx * dx + dy * dy >= rs * rs * TT__MARGIN2 || rs == 0.0) continue;
        if (!hit(w, c, e, idx, gbits, plain, a, kbits, j, rs)) return false;
    }
    return true;
}

#ifdef TT_SIMD_X86

/* As range_scalar, four candidates at a time: the same operations in the
 * same order per lane (no FMA), so the same pairs. The sorted arrays carry
 * padding, so the last group's loads stay inside. NGE_UQ and NEQ_UQ keep the
 * scalar test's NaN behaviour (a NaN distance is a pair). */
TT_AVX2 TT_INLINE bool range_avx2(tt_world *w, tt__collide *c, emit *e, const tt__grid *g, bool plain,
                                  uint32_t k, uint32_t j0, uint32_t j1)
{
    const double *sx = g->sx, *sy = g->sy, *sr = g->sr;
    const uint32_t *idx = g->idx; /* read once: the pair stores could alias them */
    const uint8_t *gbits = g->bits;
    const double r = sr[k];
    const uint32_t a = idx[k];
    const uint8_t kbits = gbits[k];
    const __m256d x = _mm256_set1_pd(sx[k]), y = _mm256_set1_pd(sy[k]), vr = _mm256_set1_pd(r);
    const __m256d f = _mm256_set1_pd(TT__MARGIN2), zero = _mm256_setzero_pd();
    for (uint32_t j = j0; j < j1; j += 4) {
        __m256d dx = _mm256_sub_pd(x, _mm256_loadu_pd(sx + j)), dy = _mm256_sub_pd(y, _mm256_loadu_pd(sy + j));
        __m256d rs = _mm256_add_pd(vr, _mm256_loadu_pd(sr + j));
        __m256d d2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
        __m256d lim = _mm256_mul_pd(_mm256_mul_pd(rs, rs), f);
        __m256d m = _mm256_and_pd(_mm256_cmp_pd(d2, lim, _CMP_NGE_UQ), _mm256_cmp_pd(rs, zero, _CMP_NEQ_UQ));
        unsigned bits = (unsigned)_mm256_movemask_pd(m);
        /* the last group's lanes past j1 masked off: min(j1 − j, 4) in bit operations, no branch */
        const uint32_t left = j1 - j, lanes = left ^ ((4u ^ left) & -(uint32_t)(left > 4u));
        bits &= (1u << lanes) - 1u;
        while (bits) {
            uint32_t jj = j + (uint32_t)__builtin_ctz(bits);
            bits &= bits - 1;
            if (!hit(w, c, e, idx, gbits, plain, a, kbits, jj, r + sr[jj])) return false;
        }
    }
    return true;
}
#endif

/* Every cell in row-major order: first each particle with the rest of its
 * cell and the cell E (contiguous), then each with NW, N, NE (contiguous in
 * the sorted order too): the forward half of the neighbourhood. Notes where
 * each row's TT__PARTS bands of columns start in the list (c->scr.runs, for
 * contact batches). One copy per kernel and filter, so both are fixed
 * inside the loops. */
#define TT__WALK(name, attr, range, plain)                                                              \
    attr static bool name(tt_world *w, tt__collide *c, const tt__grid *g)                               \
    {                                                                                                   \
        const int32_t nx = g->nx, ny = g->ny;                                                           \
        const uint32_t *st = g->start;                                                                  \
        const bool mostly_pinned = g->npinned > g->n / 2;                                               \
        emit e = {c->scr.pairs, c->scr.npairs, c->scr.paircap};                                                     \
        bool ok = true;                                                                                 \
        for (int32_t y = 0; y < ny && ok; y++) {                                                        \
            const uint32_t row = (uint32_t)y * (uint32_t)nx;                                            \
            uint32_t *run = c->scr.runs + (size_t)y * TT__PARTS, part = 0;                                  \
            for (int32_t x = 0; x < nx && ok; x++) {                                                    \
                while (part < TT__PARTS && (uint64_t)x * TT__PARTS >= (uint64_t)part * (uint32_t)nx)    \
                    run[part++] = e.n;                                                                  \
                const uint32_t cell = row + (uint32_t)x;                                                \
                const uint32_t k0 = st[cell], k1 = st[cell + 1];                                        \
                if (k0 == k1) continue;                                                                 \
                const uint32_t e1 = x + 1 < nx ? st[cell + 2] : k1;                                     \
                const uint32_t up = cell + (uint32_t)nx;                                                \
                const uint32_t u0 = y + 1 < ny ? st[x > 0 ? up - 1 : up] : 0;                           \
                const uint32_t u1 = y + 1 < ny ? st[(x + 1 < nx ? up + 1 : up) + 1] : 0;                \
                if (mostly_pinned && all_pinned(g->bits, k0, e1) && all_pinned(g->bits, u0, u1))        \
                    continue; /* every pair here is two pinned (or sleeping) particles: none is made */ \
                for (uint32_t k = k0; k < k1 && ok; k++) ok = range(w, c, &e, g, plain, k, k + 1, e1);  \
                if (y + 1 < ny)                                                                         \
                    for (uint32_t k = k0; k < k1 && ok; k++) ok = range(w, c, &e, g, plain, k, u0, u1); \
            }                                                                                           \
            while (part < TT__PARTS) run[part++] = e.n;                                                 \
        }                                                                                               \
        c->scr.runs[(size_t)ny * TT__PARTS] = e.n;                                                          \
        c->scr.nrows = ok ? (uint32_t)ny : 0;                                                               \
        c->scr.npairs = e.n;                                                                                \
        return ok;                                                                                      \
    }

TT__WALK(walk_plain, , range_scalar, true)
TT__WALK(walk_full, , range_scalar, false)
#ifdef TT_SIMD_X86
TT__WALK(walk_plain_avx2, TT_AVX2, range_avx2, true)
TT__WALK(walk_full_avx2, TT_AVX2, range_avx2, false)
#endif

bool tt__grid_pairs(tt_world *w, tt__collide *c)
{
    const tt__grid *g = &c->scr.grid;
    c->scr.nrows = 0;
    if (!tt__grow((void **)&c->scr.runs, &c->scr.runs_cap, (uint32_t)g->ny * TT__PARTS + 1, sizeof *c->scr.runs)) return false;
    const bool plain = g->one_layer && c->excl.used == 0 && !tt__constraint_pairs_any(w);
#ifdef TT_SIMD_X86
    if (tt__simd_kind(TT__SIMD_AUTO) != TT__SIMD_SCALAR) return plain ? walk_plain_avx2(w, c, g) : walk_full_avx2(w, c, g);
#endif
    return plain ? walk_plain(w, c, g) : walk_full(w, c, g);
}

/* Whether sorted particle k and some j in [j0, j1) are nearer than their
 * contact reach plus gap (a NaN distance is near). */
static bool near_range(const tt__grid *g, uint32_t k, uint32_t j0, uint32_t j1, double gap)
{
    const double x = g->sx[k], y = g->sy[k], r = g->sr[k];
    for (uint32_t j = j0; j < j1; j++) {
        const double dx = x - g->sx[j], dy = y - g->sy[j], reach = (r + g->sr[j]) * (1.0 + TT__CONTACT_MARGIN) + gap;
        if (!(dx * dx + dy * dy >= reach * reach)) return true;
    }
    return false;
}

bool tt__grid_any_near(const tt__grid *g, double gap)
{
    const int32_t nx = g->nx, ny = g->ny;
    const uint32_t *st = g->start;
    for (int32_t y = 0; y < ny; y++)
        for (int32_t x = 0; x < nx; x++) { /* the walk's neighbourhood: the rest of the cell, E, then NW, N, NE */
            const uint32_t cell = (uint32_t)y * (uint32_t)nx + (uint32_t)x, k0 = st[cell], k1 = st[cell + 1];
            if (k0 == k1) continue;
            const uint32_t e1 = x + 1 < nx ? st[cell + 2] : k1, up = cell + (uint32_t)nx;
            const uint32_t u0 = y + 1 < ny ? st[x > 0 ? up - 1 : up] : 0;
            const uint32_t u1 = y + 1 < ny ? st[(x + 1 < nx ? up + 1 : up) + 1] : 0;
            for (uint32_t k = k0; k < k1; k++)
                if (near_range(g, k, k + 1, e1, gap) || near_range(g, k, u0, u1, gap)) return true;
        }
    return false;
}

void tt__grid_free(tt__grid *g)
{
    free(g->start); free(g->cell); free(g->idx);
    free(g->sx); free(g->sy); free(g->sr);
    free(g->bits); free(g->out_list); free(g->list); free(g->cand);
    memset(g, 0, sizeof *g);
}

size_t tt__grid_bytes(const tt__grid *g)
{
    return ((size_t)g->cap_cells + g->cand_cap) * sizeof(uint32_t) +
           (size_t)g->cap_n * (4 * sizeof(uint32_t) + 3 * sizeof(double) + sizeof(uint8_t));
}
