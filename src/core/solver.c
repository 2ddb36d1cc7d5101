/* tether — the relaxation solver: sweeps every registered group of position
 * constraints (constraints, contacts) until the largest error is under the
 * tolerance or the iteration budget is spent, then fixes velocities for the
 * integrators that store them. Verlet needs no fix: its velocity is implied
 * by the corrected positions. */
#include "internal.h"

#include <stdlib.h>
#include <string.h>

int tt__group_add(tt_world *w, const tt__group_ops *ops, void *self)
{
    if (w->group_count == TT_MAX_GROUPS) return -1;
    w->groups[w->group_count] = (tt__group){ops, self};
    return w->group_count++;
}

void *tt__group_find(const tt_world *w, const tt__group_ops *ops)
{
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops == ops) return w->groups[g].self;
    return NULL;
}

void tt__group_remove(tt_world *w, const tt__group_ops *ops)
{
    for (int g = 0; g < w->group_count; g++) {
        if (w->groups[g].ops != ops) continue;
        tt__group gone = w->groups[g];
        memmove(&w->groups[g], &w->groups[g + 1], (size_t)(w->group_count - g - 1) * sizeof w->groups[0]);
        w->group_count--;
        if (gone.ops->destroy) gone.ops->destroy(w, gone.self);
        return;
    }
}

static bool grow_to(void **p, size_t elem, uint32_t n)
{
    void *q = realloc(*p, elem * (n ? n : 1));
    if (!q) return false;
    *p = q;
    return true;
}

/* Jacobi accumulators, zeroed; false (and Gauss-Seidel is used) if no memory. */
static bool jacobi_arrays(tt_world *w)
{
    uint32_t n = w->ppool.count;
    if (w->jcap < n) {
        if (!grow_to((void **)&w->jx, sizeof(double), w->pcap) || !grow_to((void **)&w->jy, sizeof(double), w->pcap) ||
            !grow_to((void **)&w->jn, sizeof(uint32_t), w->pcap))
            return false;
        w->jcap = w->pcap;
    }
    memset(w->jx, 0, n * sizeof(double));
    memset(w->jy, 0, n * sizeof(double));
    memset(w->jn, 0, n * sizeof(uint32_t));
    return true;
}

static void jacobi_apply(tt_world *w)
{
    const uint32_t n = w->ppool.count;
    for (uint32_t i = 0; i < n; i++) {
        if (!w->jn[i]) continue;
        double s = 1.0 / w->jn[i];
        w->px[i] += w->jx[i] * s;
        w->py[i] += w->jy[i] * s;
        w->jx[i] = w->jy[i] = 0.0;
        w->jn[i] = 0;
    }
}

void tt__solve(tt_world *w, double h)
{
    if (w->group_count == 0) return;
    for (int g = 0; g < w->group_count; g++) {
        const tt__group_ops *ops = w->groups[g].ops;
        if (!ops->begin) continue;
        double tb = tt__now_ms();
        ops->begin(w, w->groups[g].self, h);
        w->stats.stage_ms[ops->begin_stage] += tt__now_ms() - tb;
    }
    double t0 = tt__now_ms();
    const uint32_t n = w->ppool.count;
    /* Velocity integrators learn about corrections from the positions before the sweeps. */
    bool fix = w->integrator != TT_VERLET;
    if (fix && w->bcap < n) {
        if (grow_to((void **)&w->bx, sizeof(double), w->pcap) && grow_to((void **)&w->by, sizeof(double), w->pcap))
            w->bcap = w->pcap;
        else
            fix = false;
    }
    if (fix) {
        memcpy(w->bx, w->px, n * sizeof(double));
        memcpy(w->by, w->py, n * sizeof(double));
    }
    bool jacobi = w->order == TT_JACOBI && jacobi_arrays(w);
    if (!jacobi && w->jn) { /* tt__correct reads jn to pick the mode */
        free(w->jx); free(w->jy); free(w->jn);
        w->jx = w->jy = NULL;
        w->jn = NULL;
        w->jcap = 0;
    }
    double err = 0.0;
    uint32_t it = 0;
    while (it < w->iterations) {
        err = 0.0;
        for (int g = 0; g < w->group_count; g++) {
            double e = w->groups[g].ops->relax(w, w->groups[g].self, h);
            if (e > err) err = e;
        }
        if (jacobi) jacobi_apply(w);
        it++;
        if (err <= w->tolerance) break;
    }
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->sweeps_done) w->groups[g].ops->sweeps_done(w, w->groups[g].self);
    w->stats.iterations += it;
    w->stats.max_error = err;
    if (fix) {
        const double inv_h = 1.0 / h;
        for (uint32_t i = 0; i < n; i++) {
            if (w->inv_mass[i] == 0.0) continue;
            w->qx[i] += (w->px[i] - w->bx[i]) * inv_h;
            w->qy[i] += (w->py[i] - w->by[i]) * inv_h;
        }
    }
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->end) w->groups[g].ops->end(w, w->groups[g].self, h);
    w->stats.stage_ms[TT_STAGE_SOLVE] += tt__now_ms() - t0;
}

void tt__solver_after_step(tt_world *w)
{
    for (int g = 0; g < w->group_count; g++) {
        if (!w->groups[g].ops->after_step) continue;
        double t0 = tt__now_ms();
        w->groups[g].ops->after_step(w, w->groups[g].self);
        w->stats.stage_ms[TT_STAGE_EVENTS] += tt__now_ms() - t0;
    }
}

void tt__solver_particle_removed(tt_world *w, uint32_t index)
{
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->particle_removed) w->groups[g].ops->particle_removed(w, w->groups[g].self, index);
}

uint64_t tt__solver_hash(const tt_world *w, uint64_t h)
{
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->hash) h = w->groups[g].ops->hash(w, w->groups[g].self, h);
    return h;
}

size_t tt__solver_memory(const tt_world *w)
{
    size_t bytes = (size_t)w->jcap * (2 * sizeof(double) + sizeof(uint32_t)) + (size_t)w->bcap * 2 * sizeof(double);
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->memory) bytes += w->groups[g].ops->memory(w, w->groups[g].self);
    return bytes;
}

void tt__solver_free(tt_world *w)
{
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->destroy) w->groups[g].ops->destroy(w, w->groups[g].self);
    w->group_count = 0;
    free(w->jx); free(w->jy); free(w->jn);
    free(w->bx); free(w->by);
}
