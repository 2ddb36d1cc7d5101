/* tether — continuous detection for bullets: each bullet's motion over the
 * substep, from where it started (Verlet: x_old; others: x − v·h) to where
 * the integrator put it, is swept as a circle against the static shapes.
 * At the first hit the particle stops at the time of impact and the contact
 * is handed to the solver, which bounces it with the velocity it had before
 * the cut. Slow scenes mark no bullet and never come here. The same sweep
 * guards the solver's corrections (contact_response.c, sweeps_done). */
#include "collide_internal.h"
#include "terrain_internal.h"

typedef struct sweep_ctx {
    tt_world *w;
    tt__collide *c;
    uint32_t i;
    double x0, y0, dx, dy, r;
    double best, nx, ny;
    int32_t prim;
} sweep_ctx;

static void sweep_visit(void *ctx, uint32_t k)
{
    sweep_ctx *s = ctx;
    const tt__collide *c = s->c;
    const tt__prim *p = &c->prims[k];
    const tt_shape_def *sd = &c->shapes[p->shape].def;
    if (sd->sensor || !tt__shape_filter(s->w, sd, s->i)) return;
    tt__hit hit;
    tt__circle_vs_prim(c, p, s->x0, s->y0, s->r, &hit);
    if (hit.depth > -1e-9 * (1.0 + s->r)) return; /* touching at the start: the discrete test has it */
    double t, nx, ny;
    if (tt__ray_vs_prim(c, p, s->x0, s->y0, s->dx, s->dy, s->r, s->best, &t, &nx, &ny) && t < s->best &&
        nx * s->dx + ny * s->dy < 0.0) {
        s->best = t;
        s->nx = nx;
        s->ny = ny;
        s->prim = (int32_t)k;
    }
}

int32_t tt__sweep_static(tt_world *w, tt__collide *c, uint32_t i, double x0, double y0, double x1, double y1,
                         double *t, double *nx, double *ny)
{
    const double dx = x1 - x0, dy = y1 - y0, r = w->radius[i];
    if (dx == 0.0 && dy == 0.0) return -1;
    sweep_ctx s = {w, c, i, x0, y0, dx, dy, r, 1.0, 0.0, 0.0, -1};
    tt__sgrid_query(c, fmin(x0, x1) - r, fmin(y0, y1) - r, fmax(x0, x1) + r, fmax(y0, y1) + r, sweep_visit, &s);
    *t = s.best;
    *nx = s.nx;
    *ny = s.ny;
    return s.prim;
}

void tt__ccd(tt_world *w, tt__collide *c, double h)
{
    const uint32_t n = w->ppool.count < c->bulletcap ? w->ppool.count : c->bulletcap;
    const bool verlet = w->integrator == TT_VERLET;
    for (uint32_t i = 0; i < n; i++) {
        c->ccd_prim[i] = -1;
        if (!c->bullet[i] || w->inv_mass[i] == 0.0) continue;
        double x1 = w->px[i], y1 = w->py[i];
        double x0 = verlet ? w->qx[i] : x1 - w->qx[i] * h, y0 = verlet ? w->qy[i] : y1 - w->qy[i] * h;
        double t = 1.0, nx = 0.0, ny = 0.0;
        int32_t prim = c->nprim ? tt__sweep_static(w, c, i, x0, y0, x1, y1, &t, &nx, &ny) : -1;
        if (c->terr) { /* terrains, marched up to the shapes' hit */
            const int32_t tp = tt__terrain_sweep(w, c, i, x0, y0, x1, y1, &t, &nx, &ny);
            prim = tp >= 0 ? tp : prim;
        }
        if (prim < 0) continue;
        w->px[i] = x0 + (x1 - x0) * t;
        w->py[i] = y0 + (y1 - y0) * t;
        c->ccd_prim[i] = prim;
        if (c->scr.nsc == c->scr.sccap && !tt__grow((void **)&c->scr.sc, &c->scr.sccap, c->scr.nsc + 1, sizeof *c->scr.sc)) {
            tt__step_oom(w, "a bullet's contact");
            continue;
        }
        double cx = 0.0, cy = 0.0;
        const double r = w->radius[i];
        if (!tt__prim_is_terrain((uint32_t)prim))
            tt__shape_carry(&c->shapes[c->prims[prim].shape], w->px[i] - nx * r, w->py[i] - ny * r, &cx, &cy);
        c->scr.sc[c->scr.nsc++] = (tt__scontact){i, (uint32_t)prim, nx, ny, 0.0, 0.0, 0.0, cx, cy, 1};
    }
}
