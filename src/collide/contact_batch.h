/* tether — pair contacts in batches of four (contact_batch.c): the layout
 * the Gauss-Seidel sweeps and the velocity pass run in vector lanes, and
 * the one pair projection both pair sweeps do. Included by
 * collide_internal.h after the pair type. */
#ifndef TETHER_CONTACT_BATCH_H
#define TETHER_CONTACT_BATCH_H

/* Pair contacts in batches of four, one from each of four parts of the
 * pair list (contact_batch.c): the order Gauss-Seidel solves them in when a
 * substep sweeps more than once, the same with and without vector lanes. */
typedef struct tt__batches {
    uint32_t *a, *b;      /* particle slots, 4 per batch; padding lanes name np */
    double *rs, *lam;     /* radii sum; normal correction accumulated this substep, m */
    double *pre;          /* radii sum less the pre-stabilisation slop (TT__PRESTAB_SLOP) */
    double *wa, *wb;      /* inverse masses of a and b (0: padding), beside the entry the sweeps read them with */
    double *sa, *sb;      /* stacking's weights of a and b (tt__contacts_stack) */
    const double *ka, *kb; /* the weights the sweeps use: wa, wb, or sa, sb with stacking */
    uint32_t n, cap;      /* entries (a multiple of 4), room */
    uint8_t *solo;        /* per batch, TT__SOLO_*: its lanes go one by one, in scalar code */
    uint32_t *stamp;      /* planner: per particle slot, the last batch (+ mark) naming it */
    uint32_t stamp_cap, mark;
    double *xy;           /* the velocity pass's xy rows (simd.h) of particles [0, np) and the padding row np */
    uint32_t xy_cap, np;  /* np: the particle count the plan was made for; the sweeps' padding row */
    double *q, *v0;       /* the velocity pass's xy rows: x_old, y_old; pre-solve vx, vy */
    uint32_t q_cap, v0_cap;
    double *me;           /* the velocity pass with particle materials: per entry e, μs, μk (3 arrays of cap) */
    uint32_t me_cap;
    uint8_t simd;         /* tt__simd_mode */
    uint8_t rub;          /* anchored friction in the sweeps: 0 none, 1 after each push, 2 alone (its extra passes) */
    const double *arxy, *amu; /* anchored friction per entry (contact_anchor.h): anchor (x, y), static friction or 0 */
    double *alt;          /* its friction so far */
    double *ln;           /* stacking: per particle slot, the normals (x, y, x, y) of the first two shapes it leans on */
    uint8_t *lc;          /* how many shapes it leans on (0, 1, 2: two or more); ln_cap slots, the padding row's 0 */
    uint32_t ln_cap;
    bool lean;            /* this substep's pushes keep particles off the shapes they lean on (ln, lc) */
} tt__batches;

/* Why a batch goes lane by lane (solo): its lanes share a particle; a
 * lane's particle leans on a shape (stacking, contact_stack.c), a push the
 * lanes do not do (contact_batch.c's lean_push). The velocity pass only
 * minds the first. And, on an odd batch, why it is not solved beside the
 * one before in eight lanes: it shares a particle with it (PREV). */
#define TT__SOLO_SHARED 1
#define TT__SOLO_LEAN 2
#define TT__SOLO_PREV 4

/* Direction (x, y) of particle i's share of a push, less what would take
 * it into a shape it leans on (stacking's hold, lc and ln); wedged between
 * two, nothing. Whether any was taken. */
bool tt__batches_held(const tt__batches *B, uint32_t i, double *x, double *y);

#ifdef TT_SIMD_X86
/* Pair form (a ymm holding x, y of lanes 0 and 2, or of 1 and 3):
 * a per-lane vector's lanes 0, 2 and 1, 3 spread to it, and the per-lane
 * sums of a pair-form product's x and y parts. */
#define TT__LO(v) _mm256_unpacklo_pd((v), (v))
#define TT__HI(v) _mm256_unpackhi_pd((v), (v))
#define TT__LANES(x02, x13) _mm256_add_pd(_mm256_unpacklo_pd((x02), (x13)), _mm256_unpackhi_pd((x02), (x13)))
#endif

/* Lays pairs [0, npairs) out in batches. Part k is, for each of nrows
 * rows, pairs [runs[y·TT__PARTS + k], runs[y·TT__PARTS + k + 1]); runs NULL:
 * TT__PARTS equal parts. inv: the particles' inverse masses, which stay
 * as they are until the substep ends. False on no memory. */
/* Room for the stamps of np particles (the rest follows the pairs). */
bool tt__batches_reserve(tt__batches *B, uint32_t np);
bool tt__batches_plan(tt__batches *B, const tt__pair *pairs, uint32_t npairs, const uint32_t *runs, uint32_t nrows,
                      const double *inv, uint32_t np);
/* Batches [t0, t1) of a Gauss-Seidel sweep on positions L (in vector
 * lanes on the solver's rows, st = 4); returns the deepest overlap seen. */
double tt__batches_sweep(tt__batches *B, const tt__lay *L, uint32_t t0, uint32_t t1);
/* Anchored friction's per-entry arrays (contact_anchor.c), which the sweeps read when rub is set. */
void tt__batches_anchor(tt__batches *B, const double *rxy, double *lt, const double *mu);
/* Anchored friction of one pair (contact_anchor.c), after its push:
 * (ex, ey) = xa − xb, d its length as the caller knows it (a pair pushed
 * to contact: rs, which the push left it at up to rounding; else
 * sqrt(ex² + ey²)), r its anchor (x, y), mu·lam the bound, ws > 0 the
 * weights' sum, lt its friction so far (updated). Its slide from the anchor
 * is undone as far as lt stays within the bound. Returns g: a moves by
 * (−ey, ex)·(g·ia), b by −(−ey, ex)·(g·ib); 0 for no move. Both pair sweeps
 * and the vector lanes (contact_batch.c) do this arithmetic. The sweep is
 * one chain of dependent pairs, so d is not taken again after the push,
 * and the two divisions are reciprocals the processor works out while the
 * slide is still being computed: a square root and two divisions off the
 * chain of every anchored pair. */
static inline double tt__anchored_rub(double ex, double ey, double d, const double *r, double mu, double lam, double ws, double *lt)
{
    if (!(mu > 0.0 && lam > 0.0 && d > 0.0)) return 0.0;
    const double id = 1.0 / d, iw = 1.0 / (d * ws);
    const double slide = ((ex - r[0]) * -ey + (ey - r[1]) * ex) * id, lim = mu * lam;
    double want = *lt - slide;
    want = want > lim ? lim : want < -lim ? -lim : want;
    const double f = want - *lt;
    *lt = want;
    return f * iw;
}
/* The batches' sweep runs in vector lanes when the solver packs rows. */
bool tt__batches_want_rows(const tt__batches *B);
/* What the velocity pass of a batch reads besides the world. */
typedef struct tt__respond_in {
    const double *vx0, *vy0; /* pre-solve velocities */
    double e, mus, muk, thr; /* the world's materials; restitution threshold */
    double h;                /* substep */
    const struct tt__collide *mat; /* particles have their own materials (tt__mat): the pair's, entry by entry; else NULL */
    const uint8_t *rubbed;   /* anchored friction: per entry, its friction was the sweeps' (none here); else NULL */
} tt__respond_in;
/* The velocity pass of the batches' pairs in vector lanes, as
 * contact_response.c's pair_end does it lane by lane for Verlet; one(ctx,
 * entry) takes the batches the lanes cannot (solo, two particles on one
 * centre) through pair_end. False, touching nothing, when there are no
 * vector lanes here: then the caller runs pair_end on every pair. */
bool tt__batches_respond(tt_world *w, tt__batches *B, const tt__respond_in *in, void (*one)(void *, uint32_t), void *ctx);
void tt__batches_free(tt__batches *B);
size_t tt__batches_bytes(const tt__batches *B);
/* The same-centre direction of pair (a, b): fixed and deterministic. */
void tt__pair_apart(uint32_t a, uint32_t b, double *nx, double *ny);
/* Pair (a, b)'s overlap, (dx, dy) = xa − xb, rs the radii sum, ws > 0 the
 * inverse-mass sum: false when apart. Else pen, the overlap, and t: a moves
 * by (dx, dy)·t·ia, b by −(dx, dy)·t·ib; on one centre (dx, dy) becomes the
 * pair's fixed direction. The one projection both pair sweeps do. */
static inline bool tt__pair_push(uint32_t a, uint32_t b, double rs, double ws, double *dx, double *dy, double *pen,
                                 double *t)
{
    const double d2 = *dx * *dx + *dy * *dy;
    if (!(d2 < rs * rs)) return false;
    if (d2 > 0.0) {
        const double d = sqrt(d2);
        *pen = rs - d;
        *t = *pen / (ws * d);
    } else {
        tt__pair_apart(a, b, dx, dy);
        *pen = rs;
        *t = *pen / ws;
    }
    return true;
}

#endif
