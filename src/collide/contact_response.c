/* tether — contact response, the group's relax (per sweep) and end (per
 * substep): projection to the nearest valid position, mass weighted
 * between particles, through tt__correct; then restitution and Coulomb
 * friction on velocities (Verlet: by moving x_old; others: v). */
#include "collide_internal.h"
#include "terrain_internal.h"
#include "core/spin.h"

/* --- friction ------------------------------------------------------------ */

/* Friction against shapes. With Verlet and symplectic Euler, whose
 * positions move by the velocity they end the substep with, Coulomb
 * friction is a position constraint solved in the sweeps beside the normal
 * projection (rub): the tangential slide since the substep began is undone
 * as far as the friction correction accumulated this substep (lt) stays
 * within μs·ln, ln the normal correction accumulated. Bounding accumulated
 * corrections, not one sweep's, lets the load carried through constraints
 * (the upper rows of a lattice block on a slope) be held by the contact
 * particles. The sweeps clamp at μs only: a contact dropping to μk mid-
 * sweep would pass its load to its neighbours and start them slipping in
 * cascade. A contact still at the bound and slipping when the sweeps end
 * slides: end gives back the (μs − μk)·ln it was held by too much.
 * Euler, leapfrog and RK4 move positions by a velocity that lags, so ln
 * under-measures the load; their friction stays in the velocity pass
 * (respond) as an impulse bounded by μ times the larger of Δvn and ln/h:
 * Δvn alone is the contact particle's own weight and misses what a body's
 * links bring down on it (a lattice block slid down a 15° slope at
 * μs = 0.5). Friction between two particles is bounded by μ·Δvn: grains
 * that cannot roll would otherwise stand in columns. */
static inline bool rub_in_sweeps(const tt_world *w, const tt__spin *sp)
{
    return (w->integrator == TT_VERLET || w->integrator == TT_SYMPLECTIC_EULER) && !sp; /* spin: contact_roll.c */
}

/* slide: relative tangential displacement since the substep began; returns the correction. */
static inline double rub(double slide, double ln, double mu, double *lt)
{
    double want = *lt - slide, lim = mu * ln;
    want = want > lim ? lim : want < -lim ? -lim : want;
    double d = want - *lt;
    *lt = want;
    return d;
}

/* The correction that turns the static bound into the kinetic one where
 * the contact slides: at the bound (float λ: a margin) and still slipping
 * after the sweeps (slide, the relative tangential displacement left, over
 * SLIP of what the bound held: a contact at its bound on a body that others
 * hold does not slip). Else 0. */
#define SLIP 0.1
static inline double unrub(double slide, double lt, double ln, double mus, double muk)
{
    return muk < mus && fabs(lt) >= 0.999 * mus * ln && fabs(slide) > SLIP * fabs(lt) ? lt * (muk / mus - 1.0) : 0.0;
}

/* Where each particle began the substep: Verlet's x_old, or the copy begin made. */
static inline const double *start_x(const tt_world *w, const tt__collide *c) { return w->integrator == TT_VERLET ? w->qx : c->sx0; }
static inline const double *start_y(const tt_world *w, const tt__collide *c) { return w->integrator == TT_VERLET ? w->qy : c->sy0; }

/* Velocity-pass static friction: undo the tangential part of the
 * particle's displacement in this substep relative to what it touches
 * (share s of it; (cx, cy) the shape's own motion there, 0 between
 * particles) and its relative tangential velocity vt. Verlet: moving x
 * does both. */
static inline void unslide(tt_world *w, const tt__collide *c, uint32_t i, double h, double nx, double ny, double s,
                           double vtx, double vty, double cx, double cy)
{
    if (w->integrator == TT_VERLET) {
        w->px[i] -= vtx * h * s;
        w->py[i] -= vty * h * s;
        return;
    }
    double dx = w->px[i] - c->sx0[i] - cx, dy = w->py[i] - c->sy0[i] - cy, dn = dx * nx + dy * ny;
    w->px[i] -= (dx - dn * nx) * s;
    w->py[i] -= (dy - dn * ny) * s;
    w->qx[i] -= vtx * s;
    w->qy[i] -= vty * s;
}

/* A static contact's material: its shape's, or its terrain's. */
static inline void static_material(const tt__collide *c, const tt__scontact *s, double *e, double *fs, double *fk)
{
    if (tt__prim_is_terrain(s->prim)) {
        tt__terrain_material(c, s->prim, e, fs, fk);
        return;
    }
    const tt_shape_def *sd = &c->shapes[c->prims[s->prim].shape].def;
    *e = sd->restitution;
    *fs = sd->friction_static;
    *fk = sd->friction_kinetic;
}

/* --- projection ----------------------------------------------------------- */

/* The normal of a contact has turned round since the contact began: when
 * another correction carried the centre through the shape (across a
 * segment or capsule's core, its projection inside it; past the middle of
 * a polygon), the shape's nearest side is the far one. hit becomes the push
 * back to the side the contact began on, along that side's normal, until
 * the particle clears. (Round a segment's end or a circle the normal may
 * turn legitimately: those are left alone.) */
static void uncross(const tt__collide *c, const tt__prim *p, double x, double y, double r, const tt__scontact *s,
                    tt__hit *hit)
{
    double far; /* the shape's extent along −n from the centre */
    if (p->kind == TT__PRIM_CAPSULE) {
        const double ex = p->bx - p->ax, ey = p->by - p->ay, l2 = ex * ex + ey * ey;
        const double t = l2 > 0.0 ? ((x - p->ax) * ex + (y - p->ay) * ey) / l2 : -1.0;
        if (!(t > 0.0 && t < 1.0)) return;
        const double da = (p->ax - x) * s->nx + (p->ay - y) * s->ny, db = (p->bx - x) * s->nx + (p->by - y) * s->ny;
        far = p->r + (da > db ? da : db);
    } else {
        const tt_vec2 *v = c->verts + p->v0;
        far = -INFINITY;
        for (uint32_t k = 0; k < p->nv; k++) {
            const double d = (v[k].x - x) * s->nx + (v[k].y - y) * s->ny;
            far = d > far ? d : far;
        }
    }
    hit->nx = s->nx;
    hit->ny = s->ny;
    hit->depth = r + far;
}

/* Units of a sweep: the pair contacts (batches of four when batched,
 * else pairs), then the static contacts, each in its order. */
static uint32_t pair_units(const tt__collide *c) { return c->scr.batched ? c->scr.bat.n / 4 : c->scr.npairs; }

uint32_t tt__contacts_units(const tt_world *w, const void *self)
{
    (void)w;
    const tt__collide *c = self;
    return pair_units(c) + c->scr.nsc;
}

/* Batches (contact_detect.c: Gauss-Seidel, several sweeps, particle pairs on) in vector lanes. */
bool tt__contacts_rows(const tt_world *w, const void *self)
{
    const tt__collide *c = self;
    return w->order == TT_GAUSS_SEIDEL && w->iterations > 1 && c->set.particles && tt__batches_want_rows(&c->scr.bat);
}

/* Whether pair k's friction is anchored this substep (contact_anchor.c):
 * the setting applies and the pair was slower than the bound before the
 * sweeps (faster ones keep the velocity pass's friction). */
static inline bool anchored_pair(const tt__collide *c, uint32_t k) { return c->scr.anc.on && c->scr.anc.slow[k]; }

/* Anchored friction of pair k (tt__anchored_rub), each side by its share
 * of the inverse masses. */
static void anchored_rub(tt_world *w, tt__collide *c, const tt__lay *L, uint32_t k, double ia, double ib)
{
    const tt__pair *p = &c->scr.pairs[k];
    const size_t st = L->st, a = p->a, b = p->b;
    const double ex = L->x[a * st] - L->x[b * st], ey = L->y[a * st] - L->y[b * st];
    const double g = tt__anchored_rub(ex, ey, sqrt(ex * ex + ey * ey), c->scr.anc.rxy + 2 * (size_t)k, c->scr.anc.mu[k],
                                      p->lambda, ia + ib, c->scr.anc.lt + k);
    if (g == 0.0) return;
    const double ga = g * ia, gb = g * ib;
    tt__correct(w, p->a, -ey * ga, ex * ga);
    tt__correct(w, p->b, ey * gb, -ex * gb);
}

/* Pairs [k0, k1) one by one, unbatched (Jacobi, a single sweep, no memory
 * for the batches), with anchored friction when it is on; pre-stabilisation's
 * sweeps too (scale: its slop, no friction). */
double tt__pairs_sweep(tt_world *w, tt__collide *c, const tt__lay *L, uint32_t k0, uint32_t k1, double scale)
{
    const double *inv = w->inv_mass, *X = L->x, *Y = L->y;
    const size_t st = L->st;
    const bool anchored = c->scr.anc.on && scale == 1.0, push = c->scr.anc.pass != TT__PASS_FRICTION;
    double err = 0.0;
    for (uint32_t k = k0; k < k1; k++) {
        tt__pair *p = &c->scr.pairs[k];
        const uint32_t a = p->a, b = p->b;
        const double ia = inv[a], ib = inv[b], ws = ia + ib;
        if (ws == 0.0) continue;
        double dx = X[a * st] - X[b * st], dy = Y[a * st] - Y[b * st], pen, t;
        if (push && tt__pair_push(a, b, p->rs * scale, ws, &dx, &dy, &pen, &t)) {
            tt__correct(w, a, dx * t * ia, dy * t * ia);
            tt__correct(w, b, -dx * t * ib, -dy * t * ib);
            p->lambda += (float)pen;
            if (pen > err) err = pen;
        }
        if (anchored) anchored_rub(w, c, L, k, ia, ib);
    }
    return err;
}

double tt__contacts_relax(tt_world *w, void *self, const tt__block *blk)
{
    tt__collide *c = self;
    const tt__lay *L = blk->lay;
    const uint32_t np = pair_units(c), p1 = blk->u1 < np ? blk->u1 : np;
    double err = 0.0;
    const uint8_t pass = c->scr.anc.pass;
    /* the warm start: every pair, in the substep's first block, before any block sweeps (the
     * same bits for any split into blocks); its pushes count as the first sweep's error in
     * every block: they moved particles (the guard looks) */
    if (blk->first && blk->u0 == 0)
        c->scr.anc.warm = pass == TT__PASS_ALL && c->scr.anc.on && c->set.warm_start > 0.0 && np ? tt__contacts_warm(w, c, L, 0, np) : 0.0;
    if (blk->first && pass == TT__PASS_ALL) err = c->scr.anc.warm;
    if (blk->u0 < p1 && pass != TT__PASS_SHAPES) {
        c->scr.bat.rub = c->scr.anc.on ? (pass == TT__PASS_FRICTION ? 2 : 1) : 0;
        const double e = c->scr.batched ? tt__batches_sweep(&c->scr.bat, L, blk->u0, p1) : tt__pairs_sweep(w, c, L, blk->u0, p1, 1.0);
        err = e > err ? e : err;
        c->scr.bat.rub = 0; /* pre-stabilisation's sweeps have none */
    }
    const double *X = L->x, *Y = L->y;
    const size_t st = L->st;
    const double *sx = start_x(w, c), *sy = start_y(w, c);
    const bool fr = rub_in_sweeps(w, tt__spin_peek(w));
    const uint32_t s0 = blk->u0 > np ? blk->u0 - np : 0, s1 = blk->u1 > np ? blk->u1 - np : 0;
    for (uint32_t k = s0; k < s1 && k < c->scr.nsc; k++) {
        tt__scontact *s = &c->scr.sc[k];
        const uint32_t a = s->a;
        tt__hit hit;
        if (tt__prim_is_terrain(s->prim)) {
            tt__terrain_hit(c, s->prim, X[a * st], Y[a * st], w->radius[a], &hit);
        } else {
            tt__circle_vs_prim(c, &c->prims[s->prim], X[a * st], Y[a * st], w->radius[a], &hit);
            if (hit.nx * s->nx + hit.ny * s->ny < 0.0) uncross(c, &c->prims[s->prim], X[a * st], Y[a * st], w->radius[a], s, &hit);
        }
        if (hit.depth > 0.0 && pass != TT__PASS_FRICTION) {
            tt__correct(w, a, hit.nx * hit.depth, hit.ny * hit.depth);
            s->nx = hit.nx;
            s->ny = hit.ny;
            if (s->lambda == 0.0) {
                double se, sfs, sfk;
                static_material(c, s, &se, &sfs, &sfk);
                s->mu = sqrt(tt__mat(c, a, 1) * sfs);
            }
            s->lambda += hit.depth;
            if (hit.depth > err) err = hit.depth;
        }
        if (s->lambda == 0.0 || s->ccd || !fr || pass == TT__PASS_SHAPES) continue; /* a sweep's contact gets its friction with its restart, in end */
        const double tx = -s->ny, ty = s->nx;
        double f = rub((X[a * st] - sx[a] - s->cx) * tx + (Y[a * st] - sy[a] - s->cy) * ty, s->lambda, s->mu, &s->lambda_t);
        if (f != 0.0) tt__correct(w, a, tx * f, ty * f);
    }
    return err;
}

/* Anchored friction's extra passes (contact_anchor.c), after the sweeps
 * (positions back in the world's arrays): friction alone twice, then
 * shapes' pushes alone. */
static void anchored_passes(tt_world *w, tt__collide *c)
{
    if (!c->scr.anc.on) return;
    const tt__lay L = {w->px, w->py, w->inv_mass, 1}, kept = w->scr.lay;
    w->scr.lay = L;
    const tt__block b = {c->scr.anc.h, &L, 0, tt__contacts_units(w, c), false};
    c->scr.anc.pass = TT__PASS_FRICTION;
    (void)tt__contacts_relax(w, c, &b);
    (void)tt__contacts_relax(w, c, &b);
    c->scr.anc.pass = TT__PASS_SHAPES;
    (void)tt__contacts_relax(w, c, &b);
    c->scr.anc.pass = TT__PASS_ALL;
    w->scr.lay = kept;
}

/* After the last sweep (the solver has the positions back in the world's
 * arrays): anchored friction's passes, then the guard. A particle carried by the corrections (another particle's
 * push-out, a constraint) into a static shape it had no contact with when
 * the substep began would stay in it, unresolved, and could cross a thin
 * one in the next substep (balls spawned into each other in the Galton
 * demo left through its slanted walls). Its path through the sweeps is
 * swept against the shapes, and it stops where it would first touch one.
 * A move within the contact margin cannot reach a shape it had no contact
 * with; shapes it touched at the start are skipped by the sweep (a contact
 * keeps it on its side: relax, uncross). */
void tt__contacts_sweeps_done(tt_world *w, void *self)
{
    tt__collide *c = self;
    anchored_passes(w, c);
    const uint32_t n = w->ppool.count;
    if (!c->nprim || !c->scr.guard || c->scr.gcap < n) return;
    for (uint32_t i = 0; i < n; i++) {
        const double dx = w->px[i] - c->scr.gx0[i], dy = w->py[i] - c->scr.gy0[i], r = w->radius[i];
        const double m = r * TT__CONTACT_MARGIN;
        if (dx * dx + dy * dy <= m * m || w->inv_mass[i] == 0.0) continue;
        const double x0 = c->scr.gx0[i], y0 = c->scr.gy0[i], x1 = w->px[i], y1 = w->py[i];
        if (!tt__sgrid_near(c, fmin(x0, x1) - r, fmin(y0, y1) - r, fmax(x0, x1) + r, fmax(y0, y1) + r)) continue;
        double t, nx, ny;
        if (tt__sweep_static(w, c, i, x0, y0, x1, y1, &t, &nx, &ny) < 0) continue;
        w->px[i] = x0 + dx * t;
        w->py[i] = y0 + dy * t;
    }
}

/* --- velocity pass -------------------------------------------------------- */

/* Normal target for relative velocity v (pre-solve v0) along n: restitution
 * for an impact, else no approach. Between two particles the projection's
 * push gives no separating speed beyond what the pair had before the sweeps
 * (settled): a deep pile that the sweeps cannot hold in one substep would
 * otherwise boil, each layer thrown up by the overlap it was pushed out of.
 * With μ > 0 also Coulomb friction (particle pairs; shapes with Euler,
 * leapfrog, RK4; a sweep's contact whose velocity restarts here): static
 * (tangential v under μs·Δvn) writes the tangential velocity to undo into
 * stick, kinetic reduces it by μk·Δvn; Δvn is at least load (a shape
 * contact's ln/h, above; 0 between particles). */
static inline __attribute__((always_inline)) void respond(double vx, double vy, double v0x, double v0y, double nx,
                                                         double ny, double e, bool settled, double mus, double muk,
                                                         double thr, double load, double *dvx, double *dvy,
                                                         double *stick_x, double *stick_y, double *dvn)
{
    const double vn0 = v0x * nx + v0y * ny, vn = vx * nx + vy * ny;
    /* no approach: vn ≥ 0; settled: nor more separation than before, min(vn, max(vn0, 0)) */
    const double up = vn > 0.0 ? vn : 0.0, up0 = vn0 > 0.0 ? vn0 : 0.0;
    const double target = vn0 < -thr ? -e * vn0 : settled && up > up0 ? up0 : up;
    double change = target - vn0;
    if (change < 0.0) change = 0.0;
    *dvn = change;
    *dvx = (target - vn) * nx;
    *dvy = (target - vn) * ny;
    *stick_x = *stick_y = 0.0;
    if (mus == 0.0 && muk == 0.0) return;
    const double n = change > load ? change : load;
    const double tx = vx - vn * nx, ty = vy - vn * ny, t2 = tx * tx + ty * ty, lim = mus * n;
    if (t2 <= lim * lim) { /* squared: no root for the common sticking contact */
        *stick_x = tx;
        *stick_y = ty;
    } else {
        const double tl = sqrt(t2), f = (muk * n < tl ? muk * n : tl) / tl;
        *dvx -= tx * f;
        *dvy -= ty * f;
    }
}

/* An anchored pair still slipping at its bound when the sweeps end slides
 * on μk: it gets back the (μs − μk)·λ it was held by too much, each side its
 * share (as a shape contact does, shape_end). */
static void anchored_unrub(tt_world *w, tt__collide *c, uint32_t k, double h)
{
    uint32_t a, b;
    double lam;
    if (!tt__anc_unit(c, k, &a, &b, &lam) || !c->scr.anc.slow[k] || !(lam > 0.0)) return;
    /* unrub's own test of the bound first: a pile at rest has almost no pair at it, and the rest
     * (positions, a root, the pair's kinetic friction) is then not needed */
    if (!(fabs(c->scr.anc.lt[k]) >= 0.999 * c->scr.anc.mu[k] * lam)) return;
    const double ia = w->inv_mass[a], ib = w->inv_mass[b], ws = ia + ib;
    const double ex = w->px[a] - w->px[b], ey = w->py[a] - w->py[b], d = sqrt(ex * ex + ey * ey);
    if (!(d > 0.0) || ws == 0.0) return;
    const double *r = c->scr.anc.rxy + 2 * (size_t)k;
    const double tx = -ey / d, ty = ex / d, slide = (ex - r[0]) * tx + (ey - r[1]) * ty;
    const double f = unrub(slide, c->scr.anc.lt[k], lam, c->scr.anc.mu[k], tt__pair_mu(c, a, b, 2));
    if (f == 0.0) return;
    tt__contact_shift(w, a, tx * f * ia / ws, ty * f * ia / ws, h);
    tt__contact_shift(w, b, -tx * f * ib / ws, -ty * f * ib / ws, h);
}

/* Velocity pass of a pair that touched this substep; the normal (b to a)
 * from where the sweeps left the pair; rubbed: its friction was solved in
 * the sweeps (anchored), none here. */
static inline void pair_end(tt_world *w, tt__collide *c, uint32_t a, uint32_t b, double ia, double ib, double lam, double h,
                            double thr, bool events, tt__spin *sp, bool rubbed)
{
    double ws = ia + ib;
    if (ws == 0.0) return;
    const double iws = 1.0 / ws, wa = ia * iws, wb = ib * iws;
    double nx = w->px[a] - w->px[b], ny = w->py[a] - w->py[b], d2 = nx * nx + ny * ny;
    if (d2 > 0.0) {
        const double id = 1.0 / sqrt(d2);
        nx *= id;
        ny *= id;
    } else {
        tt__pair_apart(a, b, &nx, &ny);
    }
    double mus = rubbed ? 0.0 : tt__pair_mu(c, a, b, 1);
    double muk = rubbed ? 0.0 : tt__pair_mu(c, a, b, 2);
    double rvx, rvy; /* velocity of a relative to b; Verlet: the displacements' difference times 1/dt */
    if (w->integrator == TT_VERLET) {
        const double idt = 1.0 / w->dt_prev;
        rvx = ((w->px[a] - w->qx[a]) - (w->px[b] - w->qx[b])) * idt;
        rvy = ((w->py[a] - w->qy[a]) - (w->py[b] - w->qy[b])) * idt;
    } else {
        rvx = w->qx[a] - w->qx[b];
        rvy = w->qy[a] - w->qy[b];
    }
    double ea = tt__mat(c, a, 0), eb = tt__mat(c, b, 0), e = ea > eb ? ea : eb;
    double dvx, dvy, sx, sy, dvn;
    respond(rvx, rvy, c->scr.vx0[a] - c->scr.vx0[b], c->scr.vy0[a] - c->scr.vy0[b], nx, ny, e, true, sp ? 0.0 : mus, sp ? 0.0 : muk, thr,
            0.0, &dvx, &dvy, &sx, &sy, &dvn);
    if (sx != 0.0 || sy != 0.0) { /* both sides slid; each undoes its own share of the slide */
        unslide(w, c, a, h, nx, ny, wa, sx, sy, 0.0, 0.0);
        unslide(w, c, b, h, nx, ny, wb, -sx, -sy, 0.0, 0.0);
    }
    tt__add_velocity(w, a, dvx * wa, dvy * wa);
    tt__add_velocity(w, b, -dvx * wb, -dvy * wb);
    if (sp && (mus != 0.0 || muk != 0.0))
        tt__roll_add(c, &(tt__roll_contact){a, b, nx, ny, 0.0, 0.0, wa, wb, mus, muk, fmax(dvn, lam / h), 0.0});
    if (events)
        tt__record_contact(w, c, tt__pair_key(a, b), a < b ? a : b, a < b ? b : a, UINT32_MAX, false, a < b ? nx : -nx,
                           a < b ? ny : -ny, dvn / (w->inv_mass[a] + w->inv_mass[b]));
}

typedef struct pair_ctx {
    tt_world *w;
    tt__collide *c;
    double h, thr;
    tt__spin *sp;
} pair_ctx;

/* Batch entry k through pair_end (no events: the vector pass runs without them). */
static void pair_one(void *ctx, uint32_t k)
{
    pair_ctx *p = ctx;
    const tt__batches *B = &p->c->scr.bat;
    pair_end(p->w, p->c, B->a[k], B->b[k], B->ka[k], B->kb[k], B->lam[k], p->h, p->thr, false, p->sp, anchored_pair(p->c, k));
}

/* A bounce off a still surface, placed in time. The velocity pass alone
 * turns the normal velocity around at the end of the substep, with the
 * particle where the sweeps left it, on the surface: the time between the
 * impact and the end of the substep is lost, and a ball rebounds short of
 * e²·h (−51 % from 0.1 m at e = 0.2, 1/60 s). With Verlet and symplectic
 * Euler the samples of a free flight lie on its parabola, and the velocity
 * after a substep is the parabola's mean over it, so the impact is found
 * exactly: from the height a above the surface at the substep's start and
 * the mean normal velocity vbar over it (the pre-solve one), under
 * gravity's normal part gn, the particle meets the surface at t* with
 * speed v*; it leaves with −e·v* and flies the rest of the substep,
 * τ = h − t*. The particle is put where that flight ends (dn along the
 * normal) with the flight's mean velocity over the substep (*vn). False,
 * leaving the velocity pass as it was, when there is no such flight: no
 * bounce (e = 0, or the flight would end under the surface), or no root. */
static bool bounce_in_time(double a, double vbar, double gn, double e, double h, double *dn, double *vn)
{
    const double vk = vbar - 0.5 * gn * h; /* the normal velocity at the substep's start */
    double t = 0.0;
    if (a > 0.0) {
        const double disc = vk * vk - 2.0 * gn * a, den = -vk + sqrt(disc > 0.0 ? disc : 0.0);
        if (!(den > 0.0)) return false;
        t = 2.0 * a / den; /* the first root of a + vk·t + gn·t²/2 = 0, without cancellation */
    }
    if (!(t <= h)) return false;
    const double vstar = vk + gn * t, tau = h - t;
    const double y = -e * vstar * tau + 0.5 * gn * tau * tau, v = -e * vstar + gn * tau;
    if (!(y >= 0.0) || !(vstar < 0.0)) return false;
    *dn = y;
    *vn = v - 0.5 * gn * h;
    return true;
}

/* Velocity pass of a shape contact that touched this substep (or a
 * bullet's sweep hit). Restitution and friction act on the velocity
 * relative to the shape where it meets the particle: a kinematic shape
 * (moved by the script) carries what rests on it and throws what it hits
 * at its own speed. */
static void shape_end(tt_world *w, tt__collide *c, const tt__scontact *s, double h, double thr, bool events, tt__spin *sp)
{
    const uint32_t a = s->a;
    double se, sfs, sfk;
    static_material(c, s, &se, &sfs, &sfk);
    double mus = sqrt(tt__mat(c, a, 1) * sfs), muk = sqrt(tt__mat(c, a, 2) * sfk);
    const double ux = s->cx / h, uy = s->cy / h; /* the shape's velocity at the contact */
    const bool in_time = w->integrator == TT_VERLET || w->integrator == TT_SYMPLECTIC_EULER; /* see bounce_in_time */
    const double above = in_time && !s->ccd ? (start_x(w, c)[a] - w->px[a]) * s->nx + (start_y(w, c)[a] - w->py[a]) * s->ny : 0.0;
    double vx, vy;
    if (s->ccd) { /* the sweep cut the substep's motion short: restart from the velocity before it */
        vx = c->scr.vx0[a];
        vy = c->scr.vy0[a];
        if (w->integrator == TT_VERLET) {
            w->qx[a] = w->px[a] - vx * h;
            w->qy[a] = w->py[a] - vy * h;
        } else {
            w->qx[a] = vx;
            w->qy[a] = vy;
        }
    } else {
        if (rub_in_sweeps(w, sp)) {
            double slide = (w->px[a] - start_x(w, c)[a] - s->cx) * -s->ny + (w->py[a] - start_y(w, c)[a] - s->cy) * s->nx;
            double d = unrub(slide, s->lambda_t, s->lambda, mus, muk);
            if (d != 0.0) tt__contact_shift(w, a, -s->ny * d, s->nx * d, h);
            mus = muk = 0.0;
        }
        tt_vec2 v = tt__velocity(w, a);
        vx = v.x;
        vy = v.y;
    }
    double ea = tt__mat(c, a, 0), e = ea > se ? ea : se;
    double dvx, dvy, sx, sy, dvn;
    const bool roll = sp && !s->ccd && (mus != 0.0 || muk != 0.0); /* a sweep's restart keeps its plain friction */
    respond(vx - ux, vy - uy, c->scr.vx0[a] - ux, c->scr.vy0[a] - uy, s->nx, s->ny, e, true, roll ? 0.0 : mus, roll ? 0.0 : muk,
            thr, s->lambda / h, &dvx, &dvy, &sx, &sy, &dvn);
    if (s->ccd) {
        dvx -= sx;
        dvy -= sy;
    } else if (sx != 0.0 || sy != 0.0) {
        unslide(w, c, a, h, s->nx, s->ny, 1.0, sx, sy, s->cx, s->cy);
    }
    tt__add_velocity(w, a, dvx, dvy);
    if (roll)
        tt__roll_add(c, &(tt__roll_contact){a, UINT32_MAX, s->nx, s->ny, ux, uy, 1.0, 0.0, mus, muk, fmax(dvn, s->lambda / h), 0.0});
    const double vn0 = c->scr.vx0[a] * s->nx + c->scr.vy0[a] * s->ny;
    double dn, vn;

    if (in_time && e > 0.0 && vn0 < -thr && !s->ccd && s->cx == 0.0 && s->cy == 0.0 &&
        bounce_in_time(above, vn0, w->gravity.x * s->nx + w->gravity.y * s->ny, e, h, &dn, &vn)) {
        /* respond left the normal velocity at −e·vn0 (> 0 here); the flight replaces it */
        tt__contact_shift(w, a, dn * s->nx, dn * s->ny, h);
        const double now = -e * vn0 + dn / h; /* shift carried the velocity along */
        tt__add_velocity(w, a, (vn - now) * s->nx, (vn - now) * s->ny);
    }
    if (events) {
        /* a terrain's key: bits 63 and 62, its slot in 32..61 (shape slots never reach bit 62) */
        const bool terr = tt__prim_is_terrain(s->prim);
        uint32_t shape = terr ? s->prim : c->prims[s->prim].shape;
        tt__record_contact(w, c, terr ? (3ull << 62) | ((uint64_t)(s->prim & ~TT__PRIM_TERRAIN) << 32) | a : tt__shape_key(shape, a),
                           a, UINT32_MAX, shape, false, s->nx, s->ny, dvn / w->inv_mass[a]);
    }
}

void tt__contacts_end(tt_world *w, void *self, double h)
{
    tt__collide *c = self;
    if (!tt__contacts_touched(w, c)) return; /* the step is undone */
    tt__anchors_keep(w, c);
    const double g = sqrt(w->gravity.x * w->gravity.x + w->gravity.y * w->gravity.y);
    const double thr = c->set.restitution_threshold >= 0.0 ? c->set.restitution_threshold : 2.0 * g * h;
    const bool events = c->set.events != 0;
    const double *inv = w->inv_mass;
    tt__spin *sp = tt__spin_peek(w);
    if (sp && !tt__roll_room(c)) {
        tt__step_oom(w, "the friction of particles that turn");
        sp = NULL; /* this substep without friction; the step is undone */
    }
    if (c->scr.batched) {
        tt__batches *B = &c->scr.bat;
        /* four pairs at once where pair_end's arithmetic is the same for all (Verlet, no events, no spin) */
        const tt__respond_in in = {c->scr.vx0, c->scr.vy0, c->set.restitution, c->set.friction_static, c->set.friction_kinetic, thr, h,
                                   c->mat ? c : NULL, c->scr.anc.on ? c->scr.anc.slow : NULL};
        pair_ctx pc = {w, c, h, thr, sp};
        for (uint32_t t = 0; c->scr.anc.on && t < c->scr.ntouch; t++) anchored_unrub(w, c, c->scr.touch[t], h); /* all before the lanes take the positions */
        if (!(w->integrator == TT_VERLET && !events && !sp && tt__batches_respond(w, B, &in, pair_one, &pc)))
            for (uint32_t t = 0; t < c->scr.ntouch; t++) {
                const uint32_t k = c->scr.touch[t];
                pair_end(w, c, B->a[k], B->b[k], B->ka[k], B->kb[k], B->lam[k], h, thr, events, sp, anchored_pair(c, k));
            }
    } else {
        for (uint32_t t = 0; t < c->scr.ntouch; t++) {
            const uint32_t k = c->scr.touch[t], a = c->scr.pairs[k].a, b = c->scr.pairs[k].b;
            const bool rubbed = anchored_pair(c, k);
            if (rubbed) anchored_unrub(w, c, k, h);
            pair_end(w, c, a, b, inv[a], inv[b], c->scr.pairs[k].lambda, h, thr, events, sp, rubbed);
        }
    }
    for (uint32_t k = 0; k < c->scr.nsc; k++)
        if ((c->scr.sc[k].lambda > 0.0 || c->scr.sc[k].ccd) && inv[c->scr.sc[k].a] != 0.0) shape_end(w, c, &c->scr.sc[k], h, thr, events, sp);
    if (c->set.particles) tt__contacts_lift(w, c, thr);
    if (c->set.particles) tt__contacts_cap(w, c);
    if (sp) tt__roll_solve(w, c, sp, h);
    /* kept only where the substep detects: then reserve made the arrays, whatever earlier steps did
     * (one whose shapes are gone since still has them; a world loaded from its stream has not) */
    if (w->integrator != TT_VERLET && tt__contacts_detect_any(c) && c->sx0 && c->scap >= w->ppool.count) {
        tt__copy(c->sx0, w->px, (size_t)w->ppool.count * sizeof *c->sx0);
        tt__copy(c->sy0, w->py, (size_t)w->ppool.count * sizeof *c->sy0);
        c->s_count = w->ppool.count;
        c->s_epoch = w->epoch; /* after_step moves it past the step's own bump */
    }
}

/* The guard stopped particle i after the end above took the substep's end
 * positions: the next substep starts it where it was stopped, not where the
 * guard refused it to go (up to 1e20 m: a snapshot then held an end
 * position its own loader refused). */
void tt__contacts_stopped(tt_world *w, void *self, uint32_t i)
{
    tt__collide *c = self;
    if (w->integrator == TT_VERLET || !c->sx0 || i >= c->s_count || c->s_epoch != w->epoch) return;
    c->sx0[i] = w->px[i];
    c->sy0[i] = w->py[i];
}
