/* tether — the relaxation group's substep. solver.c owns the loop; this file
 * only says how one sweep corrects positions, through tt__correct so Jacobi
 * works too: begin, one sweep over every kind (the distance links through
 * distance_sweep.c), and the end of the substep (bounds friction, then
 * breaking). The geometry the kinds are measured with is here as well, next
 * to its hottest users, and the targets the script moves, which begin
 * advances each substep. */
#include "constraint_internal.h"

/* ---- geometry ------------------------------------------------------------- */

static double wrap_angle(double a)
{
    while (a > TT_PI) a -= 2 * TT_PI;
    while (a <= -TT_PI) a += 2 * TT_PI;
    return a;
}

double tt__constraint_angle_at(const tt_world *w, uint32_t a, uint32_t b, uint32_t c)
{
    double ux = w->px[a] - w->px[b], uy = w->py[a] - w->py[b];
    double vx = w->px[c] - w->px[b], vy = w->py[c] - w->py[b];
    return atan2(ux * vy - uy * vx, ux * vx + uy * vy);
}

/* Signed angle error: 0 inside [lo, hi], else the way back to the nearer bound. */
double tt__constraint_angle_error(double th, double lo, double hi)
{
    if (lo <= hi ? (th >= lo && th <= hi) : (th >= lo || th <= hi)) return 0.0; /* lo > hi: wraps through ±π */
    double el = wrap_angle(th - lo), eh = wrap_angle(th - hi);
    return fabs(el) < fabs(eh) ? el : eh;
}

double tt__constraint_polygon_area(const tt__lay *L, const uint32_t *p, uint32_t n)
{
    const double *X = L->x, *Y = L->y;
    const size_t st = L->st;
    double a = 0.0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t j = i + 1 == n ? 0 : i + 1;
        a += X[p[i] * st] * Y[p[j] * st] - X[p[j] * st] * Y[p[i] * st];
    }
    return 0.5 * a;
}

double tt__constraint_bounds_violation(const tt_world *w, const tt__gcon *c, uint32_t i, double x, double y, double *dx, double *dy)
{
    double r = w->radius[i];
    double x0 = c->v[0] + r, y0 = c->v[1] + r, x1 = c->v[2] - r, y1 = c->v[3] - r;
    *dx = *dy = 0.0;
    if (!c->outside) {
        if (x0 > x1) x0 = x1 = 0.5 * (c->v[0] + c->v[2]); /* a disc wider than the box: keep its centre in the middle */
        if (y0 > y1) y0 = y1 = 0.5 * (c->v[1] + c->v[3]);
        if (x < x0) *dx = x0 - x; else if (x > x1) *dx = x1 - x;
        if (y < y0) *dy = y0 - y; else if (y > y1) *dy = y1 - y;
        return fmax(fabs(*dx), fabs(*dy));
    }
    double ex0 = c->v[0] - r, ey0 = c->v[1] - r, ex1 = c->v[2] + r, ey1 = c->v[3] + r;
    if (!(x > ex0 && x < ex1 && y > ey0 && y < ey1)) return 0.0;
    double l = x - ex0, rr = ex1 - x, b = y - ey0, t = ey1 - y; /* push out through the nearest side */
    double m = fmin(fmin(l, rr), fmin(b, t));
    if (m == t) *dy = t;
    else if (m == b) *dy = -b;
    else if (m == l) *dx = -l;
    else *dx = rr;
    return m;
}

/* ---- targets the script moves ---------------------------------------------
 * A distance's length (reeling a rope) and a pin's anchor (dragging).
 * Corrected all at once, a moved target is a jump the first substep pays
 * alone: the particle moves S times too fast in it and stands still in the
 * others, so at 8 substeps a rope reeled in at 1 m/s throws its load at
 * 8 m/s. Instead the effective target goes linearly from where it was to
 * where the script put it across the substeps of the next step, and with a
 * max_rate (a winch) at most that far per second, over as many steps as it
 * takes. Only the constraints in the moving list pay: a world where nothing
 * moves runs as before, bit for bit. */

/* The effective target the sweeps use now. */
static void effective(const tt__cgroup *g, uint32_t slot, double out[2])
{
    const tt__cslot *s = &g->slots[slot];
    if (s->kind == TT_CONSTRAINT_DISTANCE) {
        const tt__dist *d = &g->dist[s->dense];
        out[0] = g->dx[s->dense].mode == TT_DISTANCE_MIN ? d->lo : d->hi;
        out[1] = 0.0;
    } else {
        out[0] = g->gen[s->dense].v[0];
        out[1] = g->gen[s->dense].v[1];
    }
}

static void set_effective(tt__cgroup *g, uint32_t slot, const double v[2])
{
    const tt__cslot *s = &g->slots[slot];
    if (s->kind == TT_CONSTRAINT_DISTANCE) {
        tt__dist *d = &g->dist[s->dense];
        uint8_t mode = g->dx[s->dense].mode;
        d->lo = mode == TT_DISTANCE_MAX ? 0.0 : v[0];
        d->hi = mode == TT_DISTANCE_MIN ? INFINITY : v[0];
        tt__distance_hot_sync(g, s->dense);
    } else {
        g->gen[s->dense].v[0] = v[0];
        g->gen[s->dense].v[1] = v[1];
    }
}

bool tt__target_move(tt__cgroup *g, uint32_t slot, const double to[2])
{
    uint32_t k = g->slots[slot].mover;
    if (k) {
        g->moving[k - 1].to[0] = to[0];
        g->moving[k - 1].to[1] = to[1];
        return true;
    }
    double now[2];
    effective(g, slot, now);
    if (now[0] == to[0] && now[1] == to[1]) return true; /* set where it is: nothing to move */
    if (!tt__grow((void **)&g->moving, &g->moving_cap, g->nmoving + 1, sizeof *g->moving)) return false;
    g->moving[g->nmoving] = (tt__mover){slot, {now[0], now[1]}, {to[0], to[1]}, {now[0], now[1]}};
    g->slots[slot].mover = ++g->nmoving;
    return true;
}

/* Where this step of dt ends: the target itself, assigned (not reached by
 * adding, which would leave rounding), unless max_rate holds it back. */
static void plan(const tt__cgroup *g, tt__mover *m, double dt)
{
    double rate = g->slots[m->slot].max_rate;
    double dx = m->to[0] - m->at[0], dy = m->to[1] - m->at[1], far = hypot(dx, dy), reach = rate * dt;
    if (rate == 0.0 || far <= reach) {
        m->end[0] = m->to[0];
        m->end[1] = m->to[1];
    } else {
        m->end[0] = m->at[0] + dx * (reach / far);
        m->end[1] = m->at[1] + dy * (reach / far);
    }
}

void tt__targets_substep(tt_world *w, tt__cgroup *g, double h)
{
    const uint32_t s = w->scr.substep, n = w->scr.nsub;
    const bool last = s + 1 == n;
    const double f = (double)(s + 1) / n;
    for (uint32_t k = g->nmoving; k-- > 0;) { /* backwards: an arrived one is swapped out */
        tt__mover *m = &g->moving[k];
        if (s == 0) plan(g, m, h * n);
        if (!last) {
            double v[2] = {m->at[0] + (m->end[0] - m->at[0]) * f, m->at[1] + (m->end[1] - m->at[1]) * f};
            set_effective(g, m->slot, v);
            continue;
        }
        set_effective(g, m->slot, m->end); /* exactly the end: the substeps' fractions do not add up to it */
        m->at[0] = m->end[0];
        m->at[1] = m->end[1];
        if (m->end[0] == m->to[0] && m->end[1] == m->to[1]) tt__target_forget(g, g->moving[k].slot);
    }
}

/* ---- the relaxation group -------------------------------------------------- */

void tt__cgroup_begin(tt_world *w, void *self, double h)
{
    tt__cgroup *g = self;
    if (g->nmoving) tt__targets_substep(w, g, h);
    if (g->nxpbd)
        for (uint32_t i = 0; i < g->ndist; i++) g->dx[i].lambda = 0.0;
    for (uint32_t i = 0; i < g->ngen; i++) g->gen[i].lambda = 0.0;
}

/* PBD / XPBD step of a scalar constraint C with gradients grad[2k] over particles idx[k]. */
static void solve_scalar(tt_world *w, tt__gcon *c, const uint32_t *idx, uint32_t n, const double *grad, double C, double h)
{
    double denom = 0.0;
    for (uint32_t k = 0; k < n; k++)
        denom += w->inv_mass[idx[k]] * (grad[2 * k] * grad[2 * k] + grad[2 * k + 1] * grad[2 * k + 1]);
    if (!(denom > 1e-300)) return;
    double dl;
    if (c->alpha > 0.0) {
        double at = c->alpha / (h * h);
        dl = (-C - at * c->lambda) / (denom + at);
        c->lambda += dl;
    } else {
        dl = -c->k * C / denom;
    }
    for (uint32_t k = 0; k < n; k++) {
        double m = w->inv_mass[idx[k]];
        if (m > 0.0) tt__correct(w, idx[k], m * grad[2 * k] * dl, m * grad[2 * k + 1] * dl);
    }
}

/* The kinds below read positions on the sweeps' layout L (X(i), Y(i)). */
#define X(i) L->x[(size_t)(i) * L->st]
#define Y(i) L->y[(size_t)(i) * L->st]

static double relax_pin(tt_world *w, const tt__lay *L, tt__gcon *c, double h)
{
    uint32_t i = c->p[0];
    double dx = X(i) - c->v[0], dy = Y(i) - c->v[1], len = sqrt(dx * dx + dy * dy);
    if (len == 0.0) return 0.0;
    double g[2] = {dx / len, dy / len};
    if (w->inv_mass[i] > 0.0) solve_scalar(w, c, &i, 1, g, len, h);
    return len;
}

static double relax_bounds_one(tt_world *w, const tt__lay *L, const tt__gcon *c, uint32_t i)
{
    if (w->inv_mass[i] == 0.0) return 0.0;
    double dx, dy, e = tt__constraint_bounds_violation(w, c, i, X(i), Y(i), &dx, &dy);
    if (e > 0.0) tt__correct(w, i, dx, dy);
    return e;
}

static double relax_bounds(tt_world *w, const tt__lay *L, const tt__gcon *c)
{
    double e = 0.0;
    if (c->n) {
        for (uint32_t k = 0; k < c->n; k++) e = fmax(e, relax_bounds_one(w, L, c, c->list[k]));
    } else {
        for (uint32_t i = 0; i < w->ppool.count; i++) e = fmax(e, relax_bounds_one(w, L, c, i));
    }
    return e;
}

static double relax_angle(tt_world *w, const tt__lay *L, tt__gcon *c, double h)
{
    uint32_t a = c->p[0], b = c->p[1], cc = c->p[2];
    double ux = X(a) - X(b), uy = Y(a) - Y(b);
    double vx = X(cc) - X(b), vy = Y(cc) - Y(b);
    double uu = ux * ux + uy * uy, vv = vx * vx + vy * vy;
    if (uu == 0.0 || vv == 0.0) return 0.0;
    double C = tt__constraint_angle_error(atan2(ux * vy - uy * vx, ux * vx + uy * vy), c->v[0], c->v[1]);
    if (C == 0.0) return 0.0;
    /* θ = φ(v) − φ(u): ∂θ/∂a = (u_y, −u_x)/|u|², ∂θ/∂c = (−v_y, v_x)/|v|², ∂θ/∂b = −(both) */
    double ga[2] = {uy / uu, -ux / uu}, gc[2] = {-vy / vv, vx / vv};
    double grad[6] = {ga[0], ga[1], -ga[0] - gc[0], -ga[1] - gc[1], gc[0], gc[1]};
    solve_scalar(w, c, c->p, 3, grad, C, h);
    return fabs(C) * sqrt(fmax(uu, vv)); /* as an arc length, m */
}

static double relax_area(tt_world *w, const tt__lay *L, tt__cgroup *g, tt__gcon *c, double h)
{
    const uint32_t n = c->n, *p = c->list;
    double *grad = g->scr.grad, perim = 0.0;
    for (uint32_t k = 0; k < n; k++) {
        uint32_t prev = p[k == 0 ? n - 1 : k - 1], next = p[k + 1 == n ? 0 : k + 1];
        grad[2 * k] = 0.5 * (Y(next) - Y(prev));
        grad[2 * k + 1] = 0.5 * (X(prev) - X(next));
        perim += tt__constraint_dist_on(L, p[k], next);
    }
    double C = tt__constraint_polygon_area(L, p, n) - c->v[0] * c->v[1];
    if (C == 0.0) return 0.0;
    solve_scalar(w, c, p, n, grad, C, h);
    return perim > 0.0 ? fabs(C) / perim : fabs(C); /* the mean normal move that fixes it, m */
}

static double relax_collinear(tt_world *w, const tt__lay *L, tt__gcon *c, double h)
{
    uint32_t a = c->p[0], b = c->p[1], cc = c->p[2];
    double d1x = X(b) - X(a), d1y = Y(b) - Y(a);
    double d2x = X(cc) - X(a), d2y = Y(cc) - Y(a);
    double C = d1x * d2y - d1y * d2x, len = sqrt(d2x * d2x + d2y * d2y);
    if (C == 0.0) return 0.0;
    double gb[2] = {d2y, -d2x}, gcc[2] = {-d1y, d1x};
    double grad[6] = {-gb[0] - gcc[0], -gb[1] - gcc[1], gb[0], gb[1], gcc[0], gcc[1]};
    solve_scalar(w, c, c->p, 3, grad, C, h);
    return len > 0.0 ? fabs(C) / len : fabs(C);
}

#undef X
#undef Y

/* Units: the distance links in order, then the other kinds in theirs. */
uint32_t tt__cgroup_units(const tt_world *w, const void *self)
{
    (void)w;
    const tt__cgroup *g = self;
    return g->ndist + g->ngen;
}

bool tt__cgroup_rows(const tt_world *w, const void *self) { return tt__distance_wants_rows(w, self); }

double tt__cgroup_relax(tt_world *w, void *self, const tt__block *b)
{
    tt__cgroup *g = self;
    const bool jacobi = w->scr.jn && w->order == TT_JACOBI;
    const uint32_t nd = g->ndist, d1 = b->u1 < nd ? b->u1 : nd;
    double err = 0.0;
    if (b->u0 < d1) err = jacobi ? tt__distance_sweep_jacobi(w, g, b, b->u0, d1) : tt__distance_sweep_gs(w, g, b, b->u0, d1);
    const uint32_t g0 = b->u0 > nd ? b->u0 - nd : 0, g1 = b->u1 > nd ? b->u1 - nd : 0;
    for (uint32_t i = g0; i < g1 && i < g->ngen; i++) {
        tt__gcon *c = &g->gen[i];
        double e = 0.0;
        switch (c->kind) {
        case TT_CONSTRAINT_PIN: e = relax_pin(w, b->lay, c, b->h); break;
        case TT_CONSTRAINT_BOUNDS: e = relax_bounds(w, b->lay, c); break;
        case TT_CONSTRAINT_ANGLE: e = relax_angle(w, b->lay, c, b->h); break;
        case TT_CONSTRAINT_AREA: e = relax_area(w, b->lay, g, c, b->h); break;
        case TT_CONSTRAINT_COLLINEAR: e = relax_collinear(w, b->lay, c, b->h); break;
        }
        if (e > err) err = e;
    }
    return err;
}

/* Friction of one particle touching a bounds wall: the tangential part of its
 * velocity (Verlet: of x − x_old) shrinks by the friction fraction. */
static void bounds_friction(tt_world *w, const tt__gcon *c, uint32_t i)
{
    if (w->inv_mass[i] == 0.0) return;
    const double eps = 1e-9 * (1.0 + fabs(w->px[i]) + fabs(w->py[i]));
    double r = w->radius[i], x = w->px[i], y = w->py[i];
    bool on_x, on_y; /* touching a wall normal to x (so sliding along y), or normal to y */
    if (!c->outside) {
        on_x = x <= c->v[0] + r + eps || x >= c->v[2] - r - eps;
        on_y = y <= c->v[1] + r + eps || y >= c->v[3] - r - eps;
    } else {
        bool in_x = x >= c->v[0] - r - eps && x <= c->v[2] + r + eps;
        bool in_y = y >= c->v[1] - r - eps && y <= c->v[3] + r + eps;
        if (!in_x || !in_y) return;
        on_x = fabs(x - (c->v[0] - r)) <= eps || fabs(x - (c->v[2] + r)) <= eps;
        on_y = fabs(y - (c->v[1] - r)) <= eps || fabs(y - (c->v[3] + r)) <= eps;
    }
    double keep = 1.0 - c->friction;
    bool verlet = w->integrator == TT_VERLET;
    if (on_y) { /* sliding along x */
        if (verlet) w->qx[i] = x - (x - w->qx[i]) * keep;
        else w->qx[i] *= keep;
    }
    if (on_x) {
        if (verlet) w->qy[i] = y - (y - w->qy[i]) * keep;
        else w->qy[i] *= keep;
    }
}

void tt__cgroup_end(tt_world *w, void *self, double h)
{
    (void)h;
    tt__cgroup *g = self;
    for (uint32_t i = 0; i < g->ngen; i++) {
        const tt__gcon *c = &g->gen[i];
        if (c->kind != TT_CONSTRAINT_BOUNDS || c->friction == 0.0) continue;
        if (c->n) {
            for (uint32_t k = 0; k < c->n; k++) bounds_friction(w, c, c->list[k]);
        } else {
            for (uint32_t p = 0; p < w->ppool.count; p++) bounds_friction(w, c, p);
        }
    }
    tt__cgroup_break_links(w, g);
}
