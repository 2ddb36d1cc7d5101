/* tether — contacts: the collision group of the relaxation loop.
 *   begin  (per substep)  detection: bullets' sweeps, the particle grid and
 *                          its pairs, particles against the static index;
 *   relax  (per sweep)     projection to the nearest valid position, mass
 *                          weighted between particles, through tt__correct;
 *   end    (per substep)   restitution and Coulomb friction on velocities
 *                          (Verlet: by moving x_old; others: v);
 *   after_step             contact events, gathered as arrays.
 * Registered the first time a world gets a shape or collision settings, so
 * a world without collisions pays nothing. */
#include "collide_internal.h"

#include <stdlib.h>
#include <string.h>

tt_collision_settings tt_collision_settings_default(void)
{
    tt_collision_settings s;
    memset(&s, 0, sizeof s);
    s.particles = true;
    s.broadphase = TT_BROADPHASE_GRID;
    s.cell_size = 0.0;
    s.restitution = 0.0;
    s.friction_static = 0.6;
    s.friction_kinetic = 0.5;
    s.restitution_threshold = -1.0;
    s.events = 0;
    return s;
}

/* --- filter: the one place deciding whether two particles may collide ---- */

static bool excluded(const tt__collide *c, uint64_t key)
{
    uint32_t lo = 0, hi = c->nexcl;
    while (lo < hi) {
        uint32_t mid = (lo + hi) / 2;
        if (c->excl[mid] < key) lo = mid + 1;
        else hi = mid;
    }
    return lo < c->nexcl && c->excl[lo] == key;
}

static inline uint64_t pair_key(uint32_t a, uint32_t b)
{
    return a < b ? ((uint64_t)a << 32) | b : ((uint64_t)b << 32) | a;
}

bool tt__pair_excluded(const tt__collide *c, uint32_t a, uint32_t b)
{
    return excluded(c, pair_key(a, b));
}

/* --- friction ------------------------------------------------------------ */

static inline double mat(const tt__collide *c, uint32_t i, int k)
{
    if (c->mat && i < c->matcap && c->mat[3 * (size_t)i + k] >= 0.0f) return c->mat[3 * (size_t)i + k];
    return k == 0 ? c->set.restitution : k == 1 ? c->set.friction_static : c->set.friction_kinetic;
}

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
 * (respond) as an impulse bounded by μ·Δvn, as does friction between two
 * particles: grains that cannot roll would otherwise stand in columns. */
static inline bool rub_in_sweeps(const tt_world *w)
{
    return w->integrator == TT_VERLET || w->integrator == TT_SYMPLECTIC_EULER;
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

/* Moves particle i by (dx, dy) after the sweeps, its velocity with it. */
static inline void shift(tt_world *w, uint32_t i, double dx, double dy, double h)
{
    w->px[i] += dx;
    w->py[i] += dy;
    if (w->integrator != TT_VERLET) {
        w->qx[i] += dx / h;
        w->qy[i] += dy / h;
    }
}

/* Velocity-pass static friction: undo the tangential part of the
 * particle's displacement in this substep (share s of it) and its
 * tangential velocity vt. Verlet: moving x does both. */
static inline void unslide(tt_world *w, const tt__collide *c, uint32_t i, double h, double nx, double ny, double s,
                           double vtx, double vty)
{
    if (w->integrator == TT_VERLET) {
        w->px[i] -= vtx * h * s;
        w->py[i] -= vty * h * s;
        return;
    }
    double dx = w->px[i] - c->sx0[i], dy = w->py[i] - c->sy0[i], dn = dx * nx + dy * ny;
    w->px[i] -= (dx - dn * nx) * s;
    w->py[i] -= (dy - dn * ny) * s;
    w->qx[i] -= vtx * s;
    w->qy[i] -= vty * s;
}

/* --- events -------------------------------------------------------------- */

static void record(tt_world *w, tt__collide *c, uint64_t key, uint32_t a, uint32_t b, uint32_t shape, bool sensor,
                   double nx, double ny, double impulse)
{
    if (!tt__grow((void **)&c->rec, &c->reccap, c->nrec + 1, sizeof *c->rec)) return; /* no memory: the event is lost */
    tt__record *r = &c->rec[c->nrec++];
    memset(r, 0, sizeof *r);
    r->key = key;
    r->ev.sensor = sensor;
    r->ev.a = (tt_particle){a, w->ppool.gen[a]};
    if (b != UINT32_MAX) r->ev.b = (tt_particle){b, w->ppool.gen[b]};
    if (shape != UINT32_MAX) r->ev.shape = (tt_shape){shape, c->spool.gen[shape]};
    double ra = w->radius[a];
    r->ev.point = (tt_vec2){w->px[a] - nx * ra, w->py[a] - ny * ra};
    r->ev.normal = (tt_vec2){nx, ny};
    r->ev.impulse = impulse;
}

static inline uint64_t shape_key(uint32_t shape, uint32_t a) { return (1ull << 63) | ((uint64_t)shape << 32) | a; }

/* --- detection ------------------------------------------------------------ */

typedef struct detect_ctx {
    tt_world *w;
    tt__collide *c;
    uint32_t i;
    double x, y, r, margin;
    bool ok;
} detect_ctx;

static void detect_visit(void *ctx, uint32_t k)
{
    detect_ctx *d = ctx;
    tt__collide *c = d->c;
    const tt__prim *p = &c->prims[k];
    const tt_shape_def *sd = &c->shapes[p->shape].def;
    if (!tt__shape_filter(d->w, sd, d->i)) return;
    if (c->ccd_prim && d->i < c->bulletcap && c->ccd_prim[d->i] == (int32_t)k) return; /* the sweep has it */
    tt__hit hit;
    tt__circle_vs_prim(c, p, d->x, d->y, d->r, &hit);
    if (sd->sensor) {
        if (hit.depth > 0.0 && c->set.events)
            record(d->w, c, shape_key(p->shape, d->i), d->i, UINT32_MAX, p->shape, true, hit.nx, hit.ny, 0.0);
        return;
    }
    if (hit.depth <= -d->margin) return;
    if (c->nsc == c->sccap && !tt__grow((void **)&c->sc, &c->sccap, c->nsc + 1, sizeof *c->sc)) {
        d->ok = false;
        return;
    }
    c->sc[c->nsc++] = (tt__scontact){d->i, k, hit.nx, hit.ny, 0.0, 0.0, 0.0, 0};
}

/* Marks the cells of the particle grid, just built, (c->near) a particle
 * centred in could touch a static primitive: each primitive's box grown by
 * the largest radius and the margin, clamped into the grid as particles are
 * (clamping is monotone, so a particle outside still lands in a marked cell).
 * One byte load then spares most particles the static test. False on no
 * memory. */
static bool grid_near_shapes(tt__collide *c)
{
    const tt__grid *g = &c->grid;
    if (g->ncell == 0) return false;
    if (g->ncell > c->near_cap) {
        uint8_t *p = realloc(c->near, g->ncell);
        if (!p) return false;
        c->near = p;
        c->near_cap = g->ncell;
    }
    memset(c->near, 0, g->ncell);
    const double grow = g->rmax * (1.0 + TT__CONTACT_MARGIN);
    for (uint32_t k = 0; k < c->nprim; k++) {
        const tt__prim *p = &c->prims[k];
        int32_t x0 = tt__cell_coord(p->lox - grow, g->ox, g->inv), x1 = tt__cell_coord(p->hix + grow, g->ox, g->inv);
        int32_t y0 = tt__cell_coord(p->loy - grow, g->oy, g->inv), y1 = tt__cell_coord(p->hiy + grow, g->oy, g->inv);
        x0 = x0 < 0 ? 0 : x0 >= g->nx ? g->nx - 1 : x0;
        x1 = x1 < 0 ? 0 : x1 >= g->nx ? g->nx - 1 : x1;
        y0 = y0 < 0 ? 0 : y0 >= g->ny ? g->ny - 1 : y0;
        y1 = y1 < 0 ? 0 : y1 >= g->ny ? g->ny - 1 : y1;
        for (int32_t y = y0; y <= y1; y++)
            memset(c->near + (size_t)y * (size_t)g->nx + (size_t)x0, 1, (size_t)(x1 - x0 + 1));
    }
    return true;
}

/* A pair of per-particle arrays grown to hold n (to the world's capacity
 * at once); false, the old ones kept, on no memory. */
static bool grow_xy(const tt_world *w, double **x, double **y, uint32_t *cap, uint32_t n)
{
    if (*cap >= n) return true;
    const uint32_t want = w->pcap > n ? w->pcap : n;
    double *a = realloc(*x, (size_t)want * sizeof *a);
    if (!a) return false;
    *x = a;
    double *b = realloc(*y, (size_t)want * sizeof *b);
    if (!b) return false;
    *y = b;
    *cap = want;
    return true;
}

static void begin(tt_world *w, void *self, double h)
{
    tt__collide *c = self;
    c->npairs = 0;
    c->nsc = 0;
    c->batched = false;
    c->guard = false; /* until this substep's start positions are copied */
    if (c->dirty && tt__shapes_rebuild(w, c) != TT_OK) c->nprim = 0;
    bool pairs = c->set.particles;
    if (!pairs && c->nprim == 0) return;
    const uint32_t n = w->ppool.count;
    /* pre-solve velocities: what restitution and friction measure against */
    if (!grow_xy(w, &c->vx0, &c->vy0, &c->vcap, n)) return;
    if (w->integrator == TT_VERLET) {
        const double inv_h = 1.0 / h;
        for (uint32_t i = 0; i < n; i++) {
            c->vx0[i] = (w->px[i] - w->qx[i]) * inv_h;
            c->vy0[i] = (w->py[i] - w->qy[i]) * inv_h;
        }
    } else {
        tt__copy(c->vx0, w->qx, (size_t)n * sizeof *c->vx0);
        tt__copy(c->vy0, w->qy, (size_t)n * sizeof *c->vy0);
    }
    if (w->integrator != TT_VERLET) {
        if (!grow_xy(w, &c->sx0, &c->sy0, &c->scap, n)) return;
        /* the last substep's end positions, unless something moved or appeared since: then x − v·h */
        if (!(c->s_epoch == w->epoch && c->s_count == n)) {
            /* where each integrator started the substep, exact under gravity alone */
            double k = w->integrator == TT_SYMPLECTIC_EULER ? 0.0 : w->integrator == TT_EULER ? 1.0 : 0.5;
            double gx = k * w->gravity.x * h * h, gy = k * w->gravity.y * h * h;
            for (uint32_t i = 0; i < n; i++) {
                c->sx0[i] = w->px[i] - w->qx[i] * h + gx;
                c->sy0[i] = w->py[i] - w->qy[i] * h + gy;
            }
        }
    }
    if (c->nbullets && c->nprim) tt__ccd(w, c, h);
    bool grid_built = false; /* this substep: its cells can filter the static test */
    if (pairs) {
        bool ok;
        c->nrows = 0;
        const double t0 = tt__now_ms();
        if (c->bp_step != w->stats.steps) { /* the step's first substep */
            c->bp_step = w->stats.steps;
            c->bp_ms = 0.0;
        }
        if (c->set.broadphase == TT_BROADPHASE_BRUTE) {
            ok = tt__brute_pairs(w, c);
            c->grid.epoch = UINT64_MAX;
        } else {
            ok = tt__grid_build(w, &c->grid, c->set.cell_size) && tt__grid_pairs(w, c);
            c->cells_used = c->grid.ncell;
            grid_built = ok;
        }
        c->bp_ms += tt__now_ms() - t0;
        if (!ok) tt__fail(w, TT_ENOMEM, "collisions: out of memory for contacts; some were skipped this step");
        /* batches pay for their planning from the second sweep on */
        c->batched = w->order == TT_GAUSS_SEIDEL && w->iterations > 1 &&
                     tt__batches_plan(&c->bat, c->pairs, c->npairs, c->runs, c->nrows, w->inv_mass, n);
    }
    if (c->nprim) {
        detect_ctx d = {w, c, 0, 0, 0, 0, 0, true};
        const uint8_t *near = grid_built && grid_near_shapes(c) ? c->near : NULL;
        for (uint32_t i = 0; i < n; i++) {
            if (w->inv_mass[i] == 0.0) continue; /* pinned or removed: shapes never push them */
            if (near && !near[c->grid.cell[i] & 0x7FFFFFFFu]) continue; /* its cell is far from every shape */
            double r = w->radius[i], m = r * TT__CONTACT_MARGIN;
            d.i = i;
            d.x = w->px[i];
            d.y = w->py[i];
            d.r = r;
            d.margin = m;
            /* fast path: no primitive's box near the particle (most particles, most steps) */
            if (!tt__sgrid_near(c, d.x - r - m, d.y - r - m, d.x + r + m, d.y + r + m)) continue;
            tt__sgrid_query(c, d.x - r - m, d.y - r - m, d.x + r + m, d.y + r + m, detect_visit, &d);
            if (!d.ok) {
                tt__fail(w, TT_ENOMEM, "collisions: out of memory for contacts; some were skipped this step");
                break;
            }
        }
        /* where the sweeps start from, for the guard in sweeps_done */
        if (n && grow_xy(w, &c->gx0, &c->gy0, &c->gcap, n)) {
            memcpy(c->gx0, w->px, (size_t)n * sizeof *c->gx0);
            memcpy(c->gy0, w->py, (size_t)n * sizeof *c->gy0);
            c->guard = true;
        }
    }
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

/* Moves particle i by (dx, dy) on positions X, Y (stride st): the rows
 * while the batches keep them, else through tt__correct (Jacobi). */
static inline void move(tt_world *w, double *X, double *Y, size_t st, uint32_t i, double dx, double dy)
{
    if (st == 1) {
        tt__correct(w, i, dx, dy);
    } else {
        X[i * st] += dx;
        Y[i * st] += dy;
    }
}

static double relax(tt_world *w, void *self, double h)
{
    (void)h;
    tt__collide *c = self;
    double err = 0.0;
    double *X = w->px, *Y = w->py;
    size_t st = 1;
    if (c->batched) { /* Gauss-Seidel, several sweeps */
        err = tt__batches_sweep(w, &c->bat, w->group_count == 1); /* rows kept while nothing else sweeps */
        if (c->bat.live) {
            X = c->bat.xy;
            Y = c->bat.xy + 1;
            st = 2;
        }
    } else {
        const double *inv = w->inv_mass;
        for (uint32_t k = 0; k < c->npairs; k++) {
            tt__pair *p = &c->pairs[k];
            const uint32_t a = p->a, b = p->b;
            const double ia = inv[a], ib = inv[b], ws = ia + ib;
            if (ws == 0.0) continue;
            double dx = X[a] - X[b], dy = Y[a] - Y[b], pen, t;
            if (!tt__pair_push(a, b, p->rs, ws, &dx, &dy, &pen, &t)) continue;
            tt__correct(w, a, dx * t * ia, dy * t * ia);
            tt__correct(w, b, -dx * t * ib, -dy * t * ib);
            p->lambda += (float)pen;
            if (pen > err) err = pen;
        }
    }
    const double *sx = start_x(w, c), *sy = start_y(w, c);
    const bool fr = rub_in_sweeps(w);
    for (uint32_t k = 0; k < c->nsc; k++) {
        tt__scontact *s = &c->sc[k];
        const uint32_t a = s->a;
        tt__hit hit;
        tt__circle_vs_prim(c, &c->prims[s->prim], X[a * st], Y[a * st], w->radius[a], &hit);
        if (hit.nx * s->nx + hit.ny * s->ny < 0.0) uncross(c, &c->prims[s->prim], X[a * st], Y[a * st], w->radius[a], s, &hit);
        if (hit.depth > 0.0) {
            move(w, X, Y, st, a, hit.nx * hit.depth, hit.ny * hit.depth);
            s->nx = hit.nx;
            s->ny = hit.ny;
            if (s->lambda == 0.0) s->mu = sqrt(mat(c, a, 1) * c->shapes[c->prims[s->prim].shape].def.friction_static);
            s->lambda += hit.depth;
            if (hit.depth > err) err = hit.depth;
        }
        if (s->lambda == 0.0 || s->ccd || !fr) continue; /* a sweep's contact gets its friction with its restart, in end */
        const double tx = -s->ny, ty = s->nx;
        double f = rub((X[a * st] - sx[a]) * tx + (Y[a * st] - sy[a]) * ty, s->lambda, s->mu, &s->lambda_t);
        if (f != 0.0) move(w, X, Y, st, a, tx * f, ty * f);
    }
    return err;
}

/* After the last sweep: the positions back from the batches' rows, then
 * the guard. A particle carried by the corrections (another particle's
 * push-out, a constraint) into a static shape it had no contact with when
 * the substep began would stay in it, unresolved, and could cross a thin
 * one in the next substep (balls spawned into each other in the Galton
 * demo left through its slanted walls). Its path through the sweeps is
 * swept against the shapes, and it stops where it would first touch one.
 * A move within the contact margin cannot reach a shape it had no contact
 * with; shapes it touched at the start are skipped by the sweep (a contact
 * keeps it on its side: relax, uncross). */
static void sweeps_done(tt_world *w, void *self)
{
    tt__collide *c = self;
    tt__batches_release(w, &c->bat);
    const uint32_t n = w->ppool.count;
    if (!c->nprim || !c->guard || c->gcap < n) return;
    for (uint32_t i = 0; i < n; i++) {
        const double dx = w->px[i] - c->gx0[i], dy = w->py[i] - c->gy0[i], r = w->radius[i];
        const double m = r * TT__CONTACT_MARGIN;
        if (dx * dx + dy * dy <= m * m || w->inv_mass[i] == 0.0) continue;
        const double x0 = c->gx0[i], y0 = c->gy0[i], x1 = w->px[i], y1 = w->py[i];
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
 * Shapes moved by the script since the last step keep the push: a paddle
 * moved into a ball throws it.
 * With μ > 0 also Coulomb friction (particle pairs; shapes with Euler,
 * leapfrog, RK4; a sweep's contact whose velocity restarts here): static
 * (tangential v under μs·Δvn) writes the tangential velocity to undo into
 * stick, kinetic reduces it by μk·Δvn. */
static inline __attribute__((always_inline)) void respond(double vx, double vy, double v0x, double v0y, double nx,
                                                         double ny, double e, bool settled, double mus, double muk,
                                                         double thr, double *dvx, double *dvy, double *stick_x,
                                                         double *stick_y, double *dvn)
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
    const double tx = vx - vn * nx, ty = vy - vn * ny, t2 = tx * tx + ty * ty, lim = mus * change;
    if (t2 <= lim * lim) { /* squared: no root for the common sticking contact */
        *stick_x = tx;
        *stick_y = ty;
    } else {
        const double tl = sqrt(t2), f = (muk * change < tl ? muk * change : tl) / tl;
        *dvx -= tx * f;
        *dvy -= ty * f;
    }
}

/* Velocity pass of a pair that touched this substep; the normal (b to a)
 * from where the sweeps left the pair. */
static inline void pair_end(tt_world *w, tt__collide *c, uint32_t a, uint32_t b, double h, double thr, bool events)
{
    const double *inv = w->inv_mass;
    double ia = inv[a], ib = inv[b], ws = ia + ib;
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
    double mus = c->mat ? sqrt(mat(c, a, 1) * mat(c, b, 1)) : c->set.friction_static;
    double muk = c->mat ? sqrt(mat(c, a, 2) * mat(c, b, 2)) : c->set.friction_kinetic;
    double rvx, rvy; /* velocity of a relative to b; Verlet: the displacements' difference times 1/dt */
    if (w->integrator == TT_VERLET) {
        const double idt = 1.0 / w->dt_prev;
        rvx = ((w->px[a] - w->qx[a]) - (w->px[b] - w->qx[b])) * idt;
        rvy = ((w->py[a] - w->qy[a]) - (w->py[b] - w->qy[b])) * idt;
    } else {
        rvx = w->qx[a] - w->qx[b];
        rvy = w->qy[a] - w->qy[b];
    }
    double ea = mat(c, a, 0), eb = mat(c, b, 0), e = ea > eb ? ea : eb;
    double dvx, dvy, sx, sy, dvn;
    respond(rvx, rvy, c->vx0[a] - c->vx0[b], c->vy0[a] - c->vy0[b], nx, ny, e, true, mus, muk, thr, &dvx, &dvy, &sx, &sy,
            &dvn);
    if (sx != 0.0 || sy != 0.0) { /* both sides slid; each undoes its own share of the slide */
        unslide(w, c, a, h, nx, ny, wa, sx, sy);
        unslide(w, c, b, h, nx, ny, wb, -sx, -sy);
    }
    tt__add_velocity(w, a, dvx * wa, dvy * wa);
    tt__add_velocity(w, b, -dvx * wb, -dvy * wb);
    if (events) record(w, c, pair_key(a, b), a < b ? a : b, a < b ? b : a, UINT32_MAX, false, a < b ? nx : -nx,
                       a < b ? ny : -ny, dvn / ws);
}

typedef struct pair_ctx {
    tt_world *w;
    tt__collide *c;
    double h, thr;
} pair_ctx;

/* Batch entry k through pair_end (no events: the vector pass runs without them). */
static void pair_one(void *ctx, uint32_t k)
{
    pair_ctx *p = ctx;
    pair_end(p->w, p->c, p->c->bat.a[k], p->c->bat.b[k], p->h, p->thr, false);
}

static void end(tt_world *w, void *self, double h)
{
    tt__collide *c = self;
    const double g = sqrt(w->gravity.x * w->gravity.x + w->gravity.y * w->gravity.y);
    const double thr = c->set.restitution_threshold >= 0.0 ? c->set.restitution_threshold : 2.0 * g * h;
    const bool events = c->set.events != 0, fr = rub_in_sweeps(w);
    const double *inv = w->inv_mass;
    if (c->batched) {
        tt__batches *B = &c->bat;
        /* four pairs at once where pair_end's arithmetic is the same for all (Verlet, world materials) */
        const tt__respond_in in = {c->vx0, c->vy0, c->set.restitution, c->set.friction_static, c->set.friction_kinetic, thr, h};
        pair_ctx pc = {w, c, h, thr};
        if (!(w->integrator == TT_VERLET && !c->mat && !events && tt__batches_respond(w, B, &in, pair_one, &pc)))
            for (uint32_t k = 0; k < B->n; k++)
                if (B->lam[k] > 0.0) pair_end(w, c, B->a[k], B->b[k], h, thr, events);
    } else {
        for (uint32_t k = 0; k < c->npairs; k++)
            if (c->pairs[k].lambda > 0.0f) pair_end(w, c, c->pairs[k].a, c->pairs[k].b, h, thr, events);
    }
    for (uint32_t k = 0; k < c->nsc; k++) {
        const tt__scontact *s = &c->sc[k];
        if (s->lambda <= 0.0 && !s->ccd) continue;
        const uint32_t a = s->a;
        if (inv[a] == 0.0) continue;
        const tt_shape_def *sd = &c->shapes[c->prims[s->prim].shape].def;
        double mus = sqrt(mat(c, a, 1) * sd->friction_static), muk = sqrt(mat(c, a, 2) * sd->friction_kinetic);
        double vx, vy;
        if (s->ccd) { /* the sweep cut the substep's motion short: restart from the velocity before it */
            vx = c->vx0[a];
            vy = c->vy0[a];
            if (w->integrator == TT_VERLET) {
                w->qx[a] = w->px[a] - vx * h;
                w->qy[a] = w->py[a] - vy * h;
            } else {
                w->qx[a] = vx;
                w->qy[a] = vy;
            }
        } else {
            if (fr) {
                double slide = (w->px[a] - start_x(w, c)[a]) * -s->ny + (w->py[a] - start_y(w, c)[a]) * s->nx;
                double d = unrub(slide, s->lambda_t, s->lambda, mus, muk);
                if (d != 0.0) shift(w, a, -s->ny * d, s->nx * d, h);
                mus = muk = 0.0;
            }
            tt_vec2 v = tt__velocity(w, a);
            vx = v.x;
            vy = v.y;
        }
        double ea = mat(c, a, 0), e = ea > sd->restitution ? ea : sd->restitution;
        double dvx, dvy, sx, sy, dvn;
        respond(vx, vy, c->vx0[a], c->vy0[a], s->nx, s->ny, e, !c->shapes[c->prims[s->prim].shape].moved, mus, muk, thr, &dvx, &dvy, &sx, &sy, &dvn);
        if (s->ccd) {
            dvx -= sx;
            dvy -= sy;
        } else if (sx != 0.0 || sy != 0.0) {
            unslide(w, c, a, h, s->nx, s->ny, 1.0, sx, sy);
        }
        tt__add_velocity(w, a, dvx, dvy);
        if (events) {
            uint32_t shape = c->prims[s->prim].shape;
            record(w, c, shape_key(shape, a), a, UINT32_MAX, shape, false, s->nx, s->ny, dvn / inv[a]);
        }
    }
    if (w->integrator != TT_VERLET && c->sx0 && c->scap >= w->ppool.count) {
        tt__copy(c->sx0, w->px, (size_t)w->ppool.count * sizeof *c->sx0);
        tt__copy(c->sy0, w->py, (size_t)w->ppool.count * sizeof *c->sy0);
        c->s_count = w->ppool.count;
        c->s_epoch = w->epoch; /* after_step moves it past the step's own bump */
    }
}

/* --- events after the step ------------------------------------------------ */

static int cmp_record(const void *x, const void *y)
{
    const tt__record *a = x, *b = y;
    if (a->key != b->key) return a->key < b->key ? -1 : 1;
    return a < b ? -1 : a > b; /* never equal pointers; keeps the order of the substeps */
}

static bool push_event(tt__collide *c, const tt_contact_event *ev, uint32_t kind)
{
    if (!(c->set.events & kind)) return true;
    if (!tt__grow((void **)&c->events, &c->evcap, c->nevents + 1, sizeof *c->events)) return false;
    c->events[c->nevents] = *ev;
    c->events[c->nevents].kind = kind;
    if (kind == TT_EVENT_END) c->events[c->nevents].impulse = 0.0;
    c->nevents++;
    return true;
}

static void after_step(tt_world *w, void *self)
{
    tt__collide *c = self;
    if (c->any_moved) {
        for (uint32_t i = 0; i < c->spool.count; i++) c->shapes[i].moved = false;
        c->any_moved = false;
    }
    /* the step bumps the epoch once after this: end positions stay valid through it, not through a teleport */
    if (c->s_epoch == w->epoch) c->s_epoch = w->epoch + 1;
    c->nevents = 0;
    if (!c->set.events) {
        c->nrec = 0;
        c->nprev = 0;
        return;
    }
    /* one record per contact: sorted by key; substeps merged (impulses add up, the last geometry stays) */
    if (c->nrec > 1) qsort(c->rec, c->nrec, sizeof *c->rec, cmp_record);
    uint32_t m = 0;
    for (uint32_t k = 0; k < c->nrec; k++) {
        if (m && c->rec[m - 1].key == c->rec[k].key) {
            double imp = c->rec[m - 1].ev.impulse + c->rec[k].ev.impulse;
            c->rec[m - 1] = c->rec[k];
            c->rec[m - 1].ev.impulse = imp;
        } else {
            c->rec[m++] = c->rec[k];
        }
    }
    c->nrec = m;
    uint32_t i = 0, j = 0;
    while (i < c->nrec || j < c->nprev) {
        if (j == c->nprev || (i < c->nrec && c->rec[i].key < c->prev[j].key)) {
            push_event(c, &c->rec[i++].ev, TT_EVENT_BEGIN);
        } else if (i == c->nrec || c->prev[j].key < c->rec[i].key) {
            push_event(c, &c->prev[j++].ev, TT_EVENT_END);
        } else {
            push_event(c, &c->rec[i++].ev, TT_EVENT_PERSIST);
            j++;
        }
    }
    /* this step's set becomes the previous one */
    tt__record *t = c->prev;
    uint32_t tc = c->prevcap;
    c->prev = c->rec;
    c->prevcap = c->reccap;
    c->nprev = c->nrec;
    c->rec = t;
    c->reccap = tc;
    c->nrec = 0;
}

const tt_contact_event *tt_world_get_contact_events(const tt_world *w, uint32_t *count)
{
    const tt__collide *c = w ? tt__collide_peek(w) : NULL;
    if (count) *count = c ? c->nevents : 0;
    return c && c->nevents ? c->events : NULL;
}

/* --- bookkeeping ----------------------------------------------------------- */

static void particle_removed(tt_world *w, void *self, uint32_t i)
{
    (void)w;
    tt__collide *c = self;
    if (c->mat && i < c->matcap) c->mat[3 * (size_t)i] = c->mat[3 * (size_t)i + 1] = c->mat[3 * (size_t)i + 2] = -1.0f;
    if (c->bullet && i < c->bulletcap && c->bullet[i]) {
        c->bullet[i] = 0;
        c->nbullets--;
    }
    if (c->ccd_prim && i < c->bulletcap) c->ccd_prim[i] = -1;
    uint32_t k = 0;
    for (uint32_t j = 0; j < c->nexcl; j++)
        if ((uint32_t)(c->excl[j] >> 32) != i && (uint32_t)c->excl[j] != i) c->excl[k++] = c->excl[j];
    c->nexcl = k;
    k = 0;
    for (uint32_t j = 0; j < c->nprev; j++) {
        uint64_t key = c->prev[j].key;
        bool hit = (uint32_t)key == i || (!(key >> 63) && (uint32_t)(key >> 32) == i);
        if (!hit) c->prev[k++] = c->prev[j];
    }
    c->nprev = k;
}

static uint64_t hash(const tt_world *w, const void *self, uint64_t h)
{
    const tt__collide *c = self;
    const tt_collision_settings *s = &c->set;
    uint32_t flags = (uint32_t)s->particles | ((uint32_t)s->broadphase << 1) | (s->events << 8);
    h = tt__fnv(h, &flags, sizeof flags);
    h = tt__fnv(h, &s->cell_size, sizeof s->cell_size);
    h = tt__fnv(h, &s->restitution, sizeof s->restitution);
    h = tt__fnv(h, &s->friction_static, sizeof s->friction_static);
    h = tt__fnv(h, &s->friction_kinetic, sizeof s->friction_kinetic);
    h = tt__fnv(h, &s->restitution_threshold, sizeof s->restitution_threshold);
    for (uint32_t i = 0; i < c->spool.count; i++) {
        const tt__shape *sh = &c->shapes[i];
        if (!sh->alive) continue;
        const tt_shape_def *d = &sh->def;
        uint32_t f = (uint32_t)d->type | ((uint32_t)d->sensor << 8) | ((uint32_t)d->category << 16);
        h = tt__fnv(h, &i, sizeof i);
        h = tt__fnv(h, &f, sizeof f);
        h = tt__fnv(h, &d->mask, sizeof d->mask);
        h = tt__fnv(h, &d->position, sizeof d->position);
        h = tt__fnv(h, &d->angle, sizeof d->angle);
        h = tt__fnv(h, &d->restitution, sizeof d->restitution);
        h = tt__fnv(h, &d->friction_static, sizeof d->friction_static);
        h = tt__fnv(h, &d->friction_kinetic, sizeof d->friction_kinetic);
    }
    if (c->nexcl) h = tt__fnv(h, c->excl, (size_t)c->nexcl * sizeof *c->excl);
    uint32_t n = w->ppool.count;
    if (c->mat) h = tt__fnv(h, c->mat, (size_t)(n < c->matcap ? n : c->matcap) * 3 * sizeof *c->mat);
    if (c->bullet) h = tt__fnv(h, c->bullet, (size_t)(n < c->bulletcap ? n : c->bulletcap));
    return h;
}

static size_t memory(const tt_world *w, const void *self)
{
    (void)w;
    const tt__collide *c = self;
    size_t b = sizeof *c + tt__shapes_bytes(c) + tt__grid_bytes(&c->grid);
    b += ((size_t)c->vcap + c->scap + c->gcap) * 2 * sizeof(double);
    b += (size_t)c->matcap * 3 * sizeof(float) + (size_t)c->bulletcap * (1 + sizeof(int32_t));
    b += (size_t)c->exclcap * sizeof(uint64_t);
    b += (size_t)c->paircap * sizeof(tt__pair) + (size_t)c->sccap * sizeof(tt__scontact) + tt__batches_bytes(&c->bat);
    b += (size_t)c->runs_cap * sizeof *c->runs + c->near_cap;
    b += ((size_t)c->reccap + c->prevcap) * sizeof(tt__record) + (size_t)c->evcap * sizeof(tt_contact_event);
    return b;
}

static void destroy(tt_world *w, void *self)
{
    (void)w;
    tt__collide *c = self;
    tt__shapes_free(c);
    tt__grid_free(&c->grid);
    free(c->vx0); free(c->vy0); free(c->sx0); free(c->sy0); free(c->gx0); free(c->gy0);
    free(c->mat); free(c->bullet); free(c->ccd_prim);
    free(c->excl);
    free(c->pairs); free(c->sc); free(c->runs); free(c->near);
    tt__batches_free(&c->bat);
    free(c->rec); free(c->prev); free(c->events);
    free(c);
}

const tt__group_ops tt__contacts_ops = {
    .name = "contacts", .rank = TT__RANK_CONTACTS,
    .begin_stage = TT_STAGE_COLLIDE,
    .begin = begin,
    .relax = relax,
    .sweeps_done = sweeps_done,
    .end = end,
    .after_step = after_step,
    .particle_removed = particle_removed,
    .hash = hash,
    .memory = memory,
    .destroy = destroy,
};

tt__collide *tt__collide_get(tt_world *w, bool create, const char *fn)
{
    tt__collide *c = tt__collide_peek(w);
    if (c || !create) return c;
    c = calloc(1, sizeof *c);
    if (!c) {
        tt__fail(w, TT_ENOMEM, "%s: out of memory for collisions", fn);
        return NULL;
    }
    c->set = tt_collision_settings_default();
    c->set.particles = false; /* until tt_world_set_collision says otherwise */
    c->grid.epoch = UINT64_MAX;
    c->spool.tag = w->tag; /* shape handles carry the world's tag, like particles */
    if (tt__group_add(w, &tt__contacts_ops, c) < 0) {
        free(c);
        tt__fail(w, TT_ENOMEM, "%s: no room for another relaxation group (%d)", fn, TT_MAX_GROUPS);
        return NULL;
    }
    return c;
}

/* --- public settings ------------------------------------------------------- */

tt_result tt_world_set_collision(tt_world *w, const tt_collision_settings *s)
{
    const char *fn = "tt_world_set_collision";
    TT_CHECK_WORLD(w, fn);
    if (!s) return tt__fail(w, TT_EINVAL, "%s: settings are NULL", fn);
    if (s->broadphase != TT_BROADPHASE_GRID && s->broadphase != TT_BROADPHASE_BRUTE)
        return tt__fail(w, TT_EINVAL, "%s: unknown broadphase %d", fn, (int)s->broadphase);
    if (!tt__in_range(s->cell_size, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: cell_size must be in [0, %g], got %g", fn, TT_MAX_VALUE, s->cell_size);
    if (!tt__in_range(s->restitution, 0.0, 1.0)) return tt__fail(w, TT_EINVAL, "%s: restitution must be in [0, 1], got %g", fn, s->restitution);
    if (!tt__in_range(s->friction_static, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: friction_static must be in [0, %g], got %g", fn, TT_MAX_VALUE, s->friction_static);
    if (!tt__in_range(s->friction_kinetic, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: friction_kinetic must be in [0, %g], got %g", fn, TT_MAX_VALUE, s->friction_kinetic);
    if (!tt__in_range(s->restitution_threshold, -TT_MAX_VALUE, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: restitution_threshold must be finite (< 0 = auto)", fn);
    if (s->events & ~7u) return tt__fail(w, TT_EINVAL, "%s: events must be a set of TT_EVENT_BEGIN|PERSIST|END, got 0x%x", fn, s->events);
    tt__collide *c = tt__collide_get(w, true, fn);
    if (!c) return TT_ENOMEM;
    c->set = *s;
    c->set.restitution_threshold = s->restitution_threshold < 0.0 ? -1.0 : s->restitution_threshold;
    if (!s->events) c->nprev = 0;
    return TT_OK;
}

tt_result tt_world_get_collision(const tt_world *w, tt_collision_settings *out)
{
    TT_CHECK_WORLD(w, "tt_world_get_collision");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_world_get_collision: out is NULL");
    const tt__collide *c = tt__collide_peek(w);
    if (c) *out = c->set;
    else {
        *out = tt_collision_settings_default();
        out->particles = false;
    }
    return TT_OK;
}

tt_result tt_world_get_collision_stats(const tt_world *w, tt_collision_stats *out)
{
    TT_CHECK_WORLD(w, "tt_world_get_collision_stats");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_world_get_collision_stats: out is NULL");
    memset(out, 0, sizeof *out);
    const tt__collide *c = tt__collide_peek(w);
    if (!c) return TT_OK;
    out->shapes = c->shapes_alive;
    out->pair_contacts = c->npairs;
    out->shape_contacts = c->nsc;
    out->cells = c->grid.ncell;
    out->static_rebuilds = c->static_rebuilds;
    out->broadphase_bytes = tt__grid_bytes(&c->grid);
    out->broadphase_bytes_per_particle = c->grid.n ? (double)out->broadphase_bytes / c->grid.n : 0.0;
    out->total_bytes = memory(w, c);
    out->broadphase_ms = c->bp_step == w->stats.steps - 1 ? c->bp_ms : 0.0; /* 0 when the last step found no pairs */
    return TT_OK;
}

/* --- per particle ------------------------------------------------------------ */

tt_result tt_particle_set_material(tt_world *w, tt_particle p, double e, double fs, double fk)
{
    const char *fn = "tt_particle_set_material";
    tt_result r = tt__particle_check(w, p, fn);
    if (r != TT_OK) return r;
    if (!tt__in_range(e, 0.0, 1.0)) return tt__fail(w, TT_EINVAL, "%s: restitution must be in [0, 1], got %g", fn, e);
    if (!tt__in_range(fs, 0.0, 1e30)) return tt__fail(w, TT_EINVAL, "%s: static friction must be >= 0 and finite, got %g", fn, fs);
    if (!tt__in_range(fk, 0.0, 1e30)) return tt__fail(w, TT_EINVAL, "%s: kinetic friction must be >= 0 and finite, got %g", fn, fk);
    tt__collide *c = tt__collide_get(w, true, fn);
    if (!c) return TT_ENOMEM;
    if (c->matcap < w->pcap) {
        float *m = realloc(c->mat, (size_t)w->pcap * 3 * sizeof *m);
        if (!m) return tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        for (size_t k = (size_t)c->matcap * 3; k < (size_t)w->pcap * 3; k++) m[k] = -1.0f;
        c->mat = m;
        c->matcap = w->pcap;
    }
    c->mat[3 * (size_t)p.index] = (float)e;
    c->mat[3 * (size_t)p.index + 1] = (float)fs;
    c->mat[3 * (size_t)p.index + 2] = (float)fk;
    return TT_OK;
}

tt_result tt_particle_get_material(const tt_world *w, tt_particle p, double *e, double *fs, double *fk)
{
    const char *fn = "tt_particle_get_material";
    tt_result r = tt__particle_check(w, p, fn);
    if (r != TT_OK) return r;
    if (!e || !fs || !fk) return tt__fail(w, TT_EINVAL, "%s: out is NULL", fn);
    const tt__collide *c = tt__collide_peek(w);
    if (!c) {
        tt_collision_settings d = tt_collision_settings_default();
        *e = d.restitution;
        *fs = d.friction_static;
        *fk = d.friction_kinetic;
        return TT_OK;
    }
    *e = mat(c, p.index, 0);
    *fs = mat(c, p.index, 1);
    *fk = mat(c, p.index, 2);
    return TT_OK;
}

tt_result tt_particle_set_bullet(tt_world *w, tt_particle p, bool bullet)
{
    const char *fn = "tt_particle_set_bullet";
    tt_result r = tt__particle_check(w, p, fn);
    if (r != TT_OK) return r;
    tt__collide *c = tt__collide_get(w, bullet, fn);
    if (!c) return bullet ? TT_ENOMEM : TT_OK;
    if (!bullet && (!c->bullet || p.index >= c->bulletcap)) return TT_OK;
    if (c->bulletcap < w->pcap) {
        uint8_t *b = realloc(c->bullet, w->pcap);
        if (!b) return tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        memset(b + c->bulletcap, 0, w->pcap - c->bulletcap);
        c->bullet = b;
        int32_t *q = realloc(c->ccd_prim, (size_t)w->pcap * sizeof *q);
        if (!q) return tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        for (uint32_t k = c->bulletcap; k < w->pcap; k++) q[k] = -1;
        c->ccd_prim = q;
        c->bulletcap = w->pcap;
    }
    if (c->bullet[p.index] != bullet) c->nbullets += bullet ? 1 : (uint32_t)-1;
    c->bullet[p.index] = bullet;
    c->ccd_prim[p.index] = -1;
    return TT_OK;
}

tt_result tt_particle_get_bullet(const tt_world *w, tt_particle p, bool *out)
{
    tt_result r = tt__particle_check(w, p, "tt_particle_get_bullet");
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "tt_particle_get_bullet: out is NULL");
    const tt__collide *c = tt__collide_peek(w);
    *out = c && c->bullet && p.index < c->bulletcap && c->bullet[p.index];
    return TT_OK;
}

tt_result tt_world_set_pair_collision(tt_world *w, tt_particle a, tt_particle b, bool enabled)
{
    const char *fn = "tt_world_set_pair_collision";
    tt_result r = tt__particle_check(w, a, fn);
    if (r == TT_OK) r = tt__particle_check(w, b, fn);
    if (r != TT_OK) return r;
    if (a.index == b.index) return tt__fail(w, TT_EINVAL, "%s: a and b are the same particle", fn);
    tt__collide *c = tt__collide_get(w, !enabled, fn);
    if (!c) return enabled ? TT_OK : TT_ENOMEM;
    uint64_t key = pair_key(a.index, b.index);
    uint32_t lo = 0, hi = c->nexcl;
    while (lo < hi) {
        uint32_t mid = (lo + hi) / 2;
        if (c->excl[mid] < key) lo = mid + 1;
        else hi = mid;
    }
    bool present = lo < c->nexcl && c->excl[lo] == key;
    if (enabled && present) {
        memmove(c->excl + lo, c->excl + lo + 1, (size_t)(c->nexcl - lo - 1) * sizeof *c->excl);
        c->nexcl--;
    } else if (!enabled && !present) {
        if (!tt__grow((void **)&c->excl, &c->exclcap, c->nexcl + 1, sizeof *c->excl)) return tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        memmove(c->excl + lo + 1, c->excl + lo, (size_t)(c->nexcl - lo) * sizeof *c->excl);
        c->excl[lo] = key;
        c->nexcl++;
    }
    return TT_OK;
}
