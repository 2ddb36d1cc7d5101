/* tether — the point attractors' pull and potential: a force that every
 * integrator evaluates at its own stages, so that orbits measure the
 * integrators (the atlas's Kepler scene), not a shortcut. */
#include "internal.h"

void tt__attractors_accel(const tt_world *w, const double *x, const double *y, double *ax, double *ay)
{
    const uint32_t n = w->ppool.count;
    for (int k = 0; k < TT_MAX_ATTRACTORS; k++) {
        const tt_attractor *a = &w->attractors[k];
        if (a->strength == 0.0) continue;
        const double e2 = a->softening * a->softening;
        for (uint32_t i = 0; i < n; i++) {
            if (w->inv_mass[i] == 0.0) continue;
            double dx = a->center.x - x[i], dy = a->center.y - y[i];
            double d2 = dx * dx + dy * dy + e2;
            if (!(d2 > 0.0)) continue; /* at an unsoftened centre: no direction to pull along */
            double s = a->strength / (d2 * sqrt(d2));
            ax[i] += s * dx;
            ay[i] += s * dy;
        }
    }
}

double tt__attractors_energy(const tt_world *w)
{
    double e = 0.0;
    for (int k = 0; k < TT_MAX_ATTRACTORS; k++) {
        const tt_attractor *a = &w->attractors[k];
        if (a->strength == 0.0) continue;
        const double e2 = a->softening * a->softening;
        for (uint32_t i = 0; i < w->ppool.count; i++) {
            if (w->inv_mass[i] == 0.0) continue;
            double dx = a->center.x - w->px[i], dy = a->center.y - w->py[i];
            double d2 = dx * dx + dy * dy + e2;
            if (d2 > 0.0) e -= w->mass[i] * a->strength / sqrt(d2);
        }
    }
    return e;
}
