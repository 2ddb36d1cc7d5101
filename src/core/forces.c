/* tether — force evaluation: gravity, wind, applied forces, springs → accelerations. */
#include "internal.h"

bool tt__has_forces(const tt_world *w)
{
    return w->springs_alive > 0 || w->attractors_used > 0 || w->forces_pending || w->wind.x != 0.0 || w->wind.y != 0.0;
}

/* Accelerations at state (x, v) into (ax, ay). vx == NULL means Verlet:
 * velocity is the backward difference (x − x_old)/dt_prev. */
void tt__eval_accel(tt_world *w, const double *x, const double *y, const double *vx, const double *vy,
                    double *ax, double *ay)
{
    double t0 = tt__now_ms();
    const uint32_t n = w->ppool.count;
    const double *inv = w->inv_mass;
    const double gx = w->gravity.x, gy = w->gravity.y;
    const double wx = w->wind.x, wy = w->wind.y;
    const bool user = w->forces_pending;
    for (uint32_t i = 0; i < n; i++) {
        if (inv[i] == 0.0) {
            ax[i] = ay[i] = 0.0;
            continue;
        }
        double fx = wx, fy = wy;
        if (user) {
            fx += w->fx[i];
            fy += w->fy[i];
        }
        ax[i] = gx + inv[i] * fx;
        ay[i] = gy + inv[i] * fy;
    }
    if (w->attractors_used) tt__attractors_accel(w, x, y, ax, ay);
    tt__springs_accel(w, x, y, vx, vy, ax, ay);
    w->stats.force_evaluations++;
    w->stats.stage_ms[TT_STAGE_FORCES] += tt__now_ms() - t0;
}

/* Every spring's pull added to the accelerations of its two ends, in slot order. */
void tt__springs_accel(const tt_world *w, const double *x, const double *y, const double *vx, const double *vy,
                       double *ax, double *ay)
{
    const double *inv = w->inv_mass;
    const double inv_dt = 1.0 / w->dt_prev;
    for (uint32_t s = 0; s < w->spool.count; s++) {
        const tt__spring *sp = &w->springs[s];
        if (!sp->alive) continue;
        uint32_t a = sp->a, b = sp->b;
        double dx = x[a] - x[b], dy = y[a] - y[b];
        double len = sqrt(dx * dx + dy * dy);
        if (!(len > 0.0)) continue; /* coincident ends: no direction to push along */
        double nx = dx / len, ny = dy / len;
        double f = -sp->k * (len - sp->rest);
        if (sp->c != 0.0) {
            double rvx, rvy;
            if (vx) {
                rvx = vx[a] - vx[b];
                rvy = vy[a] - vy[b];
            } else {
                rvx = ((x[a] - w->qx[a]) - (x[b] - w->qx[b])) * inv_dt;
                rvy = ((y[a] - w->qy[a]) - (y[b] - w->qy[b])) * inv_dt;
            }
            f -= sp->c * (rvx * nx + rvy * ny);
        }
        ax[a] += inv[a] * f * nx;
        ay[a] += inv[a] * f * ny;
        ax[b] -= inv[b] * f * nx;
        ay[b] -= inv[b] * f * ny;
    }
}
