/* tether — where each particle was when the last step began, kept only
 * while asked (tt_world_set_interpolation), so that a renderer can draw
 * between it and the current position by a clock's alpha. Verlet's x_old is
 * not that position: it spans one substep, and contacts, impulses and
 * velocity changes rewrite it as an encoding of the velocity; the other
 * integrators keep no position at all. One copy of the positions as each
 * step begins serves every integrator alike, for 16 bytes per particle and
 * one pass. What is kept is for drawing, not simulation state: it is
 * neither saved nor hashed, and it never changes a step. */
#include "internal.h"

#include <stdlib.h>

/* The arrays, holding the current positions; false on no memory. */
bool tt__interp_start(tt_world *w)
{
    const size_t cap = w->pcap ? w->pcap : 1;
    double *x = malloc(cap * sizeof *x), *y = malloc(cap * sizeof *y);
    if (!x || !y) {
        free(x);
        free(y);
        return false;
    }
    free(w->ox);
    free(w->oy);
    w->ox = x;
    w->oy = y;
    tt__interp_step_begin(w);
    return true;
}

void tt__interp_step_begin(tt_world *w)
{
    tt__copy(w->ox, w->px, (size_t)w->ppool.count * sizeof *w->ox);
    tt__copy(w->oy, w->py, (size_t)w->ppool.count * sizeof *w->oy);
}

void tt__interp_stop(tt_world *w)
{
    free(w->ox);
    free(w->oy);
    w->ox = w->oy = NULL;
}

tt_result tt_world_set_interpolation(tt_world *w, bool on)
{
    TT_CHECK_WORLD(w, "tt_world_set_interpolation");
    if (!on) tt__interp_stop(w);
    else if (!w->ox && !tt__interp_start(w)) return tt__fail(w, TT_ENOMEM, "tt_world_set_interpolation: out of memory");
    return TT_OK;
}

bool tt_world_get_interpolation(const tt_world *w) { return w && w->ox; }

tt_result tt_particle_get_previous_position(const tt_world *w, tt_particle p, tt_vec2 *out)
{
    tt_result r = tt__particle_check(w, p, "tt_particle_get_previous_position");
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "tt_particle_get_previous_position: out is NULL");
    const uint32_t i = p.index;
    *out = w->ox ? (tt_vec2){w->ox[i], w->oy[i]} : (tt_vec2){w->px[i], w->py[i]};
    return TT_OK;
}

uint32_t tt_world_read_previous_positions(const tt_world *w, double *xy, uint32_t cap)
{
    if (!w || !xy) return 0;
    const double *x = w->ox ? w->ox : w->px, *y = w->ox ? w->oy : w->py;
    uint32_t n = 0;
    for (uint32_t i = 0; i < w->ppool.count && n < cap; i++)
        if (w->flags[i] & TT__PF_ALIVE) {
            xy[2 * n] = x[i];
            xy[2 * n + 1] = y[i];
            n++;
        }
    return n;
}
