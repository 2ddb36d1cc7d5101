/* tether — the relaxation solver: sweeps every registered group of position
 * constraints (constraints, contacts) until the largest error is under the
 * tolerance or the iteration budget is spent, then fixes velocities for the
 * integrators that store them. Verlet needs no fix: its velocity is implied
 * by the corrected positions. */
#include "internal.h"
#include "simd.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static bool grow_to(void **p, size_t elem, uint32_t n)
{
    void *q = realloc(*p, elem * (n ? n : 1));
    if (!q) return false;
    *p = q;
    return true;
}

/* Jacobi accumulators, zeroed (tt__solver_reserve sized them). */
static void jacobi_zero(tt_world *w)
{
    uint32_t n = w->ppool.count;
    tt__zero(w->scr.jx, n * sizeof(double));
    tt__zero(w->scr.jy, n * sizeof(double));
    tt__zero(w->scr.jn, n * sizeof(uint32_t));
}

/* ---- the sweeps' layout ----------------------------------------------------
 * The solver owns where positions are while the groups sweep: the world's
 * own arrays, or rows (simd.h) packed once before the first sweep and
 * unpacked once after the last, which the vector sweeps of every group
 * (distance links, contact batches) read and write in place. A group moves
 * positions through its block's layout only, so no group can read a stale
 * copy, and no group packs its own. */

/* Every group with sweeps reads positions through the layout (has `rows`). */
static bool rows_possible(const tt_world *w)
{
    for (int g = 0; g < w->group_count; g++) {
        const tt__group_ops *ops = w->groups[g].ops;
        if (ops->relax && !ops->rows) return false;
    }
    return true;
}

/* Rows this step: Gauss-Seidel (Jacobi's averaging goes through the
 * world's arrays), every group reads through the layout, one wants them. */
static bool rows_wanted(const tt_world *w)
{
    if (w->order != TT_GAUSS_SEIDEL || !rows_possible(w)) return false;
    for (int g = 0; g < w->group_count; g++) {
        const tt__group_ops *ops = w->groups[g].ops;
        if (ops->relax && ops->rows(w, w->groups[g].self)) return true;
    }
    return false;
}

static void lay_begin(tt_world *w)
{
    const uint32_t n = w->ppool.count;
    if (rows_wanted(w) && w->scr.rows_cap > n) { /* tt__solver_reserve made the room */
        double *r = w->scr.rows;
        tt__rows_pack(r, w->px, w->py, w->inv_mass, n);
        memset(r + 4 * (size_t)n, 0, 4 * sizeof *r); /* the padding row: no mass, at the origin */
        w->scr.lay = (tt__lay){r, r + 1, r + 2, 4};
        w->scr.packs++;
    } else {
        w->scr.lay = (tt__lay){w->px, w->py, w->inv_mass, 1};
    }
}

static void lay_end(tt_world *w)
{
    if (w->scr.lay.st == 4) {
        tt__rows_unpack(w->scr.rows, w->px, w->py, w->ppool.count);
        w->scr.packs++;
    }
    w->scr.lay = (tt__lay){0};
}

/* One sweep: the groups in rank order, each in w->blocks consecutive
 * blocks of its units (one by default); returns the largest error and
 * notes in *moved whether some block found one. */
static double sweep(tt_world *w, double h, bool first, bool *moved)
{
    const uint32_t k = w->blocks > 1 ? w->blocks : 1;
    double err = 0.0;
    for (int g = 0; g < w->group_count; g++) {
        const tt__group_ops *ops = w->groups[g].ops;
        if (!ops->relax) continue;
        /* a group without units is one unit: one block */
        const uint32_t n = ops->units ? ops->units(w, w->groups[g].self) : 1, kg = ops->units ? k : 1;
        for (uint32_t b = 0; b < kg; b++) {
            const tt__block blk = {h, &w->scr.lay, (uint32_t)((uint64_t)n * b / kg), (uint32_t)((uint64_t)n * (b + 1) / kg), first};
            if (blk.u0 == blk.u1) continue;
            const double e = ops->relax(w, w->groups[g].self, &blk);
            *moved |= e != 0.0;
            if (e > err) err = e;
        }
    }
    return err;
}

bool tt__solver_reserve(tt_world *w)
{
    if (w->group_count == 0) return true;
    const uint32_t n = w->ppool.count;
    const bool sweeps = tt__groups_relaxing(w) > 0; /* sleeping's group alone needs no sweep arrays */
    if (sweeps && w->order == TT_JACOBI && w->scr.jcap < n) {
        if (!grow_to((void **)&w->scr.jx, sizeof(double), w->pcap) || !grow_to((void **)&w->scr.jy, sizeof(double), w->pcap) ||
            !grow_to((void **)&w->scr.jn, sizeof(uint32_t), w->pcap))
            return false;
        w->scr.jcap = w->pcap;
    }
    if (sweeps && w->scr.bcap < n) { /* every integrator: the guard's start of the substep */
        if (!grow_to((void **)&w->scr.bx, sizeof(double), w->pcap) || !grow_to((void **)&w->scr.by, sizeof(double), w->pcap))
            return false;
        w->scr.bcap = w->pcap;
    }
    if (sweeps && rows_wanted(w) && !tt__rows_reserve(&w->scr.rows, &w->scr.rows_cap, n + 1)) return false;
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->reserve && !w->groups[g].ops->reserve(w, w->groups[g].self)) return false;
    return true;
}

static void jacobi_apply(tt_world *w)
{
    const uint32_t n = w->ppool.count;
    for (uint32_t i = 0; i < n; i++) {
        if (!w->scr.jn[i]) continue;
        double s = 1.0 / w->scr.jn[i];
        w->px[i] += w->scr.jx[i] * s;
        w->py[i] += w->scr.jy[i] * s;
        w->scr.jx[i] = w->scr.jy[i] = 0.0;
        w->scr.jn[i] = 0;
    }
}

/* True when some particle may be past the guard: two particles at a time
 * in the compiler's generic vectors (GCC and clang, any target), so a world
 * where nothing diverges pays about one read of its positions and velocity
 * state per substep. Verlet's velocity is (x − x_old)/h, compared as
 * |x − x_old| against TT_DIVERGED·h. The test is on bits: for doubles of
 * the same sign the bit patterns order like the values, and NaN's is above
 * Inf's, so lim − |v| (as integers) is negative exactly when |v| > lim or v
 * is NaN; the signs are OR-ed and read once at the end. */
typedef double tt__v2d __attribute__((vector_size(16)));
typedef int64_t tt__v2l __attribute__((vector_size(16)));

static inline tt__v2d load2(const double *p)
{
    tt__v2d v;
    memcpy(&v, p, sizeof v);
    return v;
}

static inline tt__v2l excess(tt__v2d v, tt__v2l lim)
{
    const tt__v2l abs_mask = {INT64_MAX, INT64_MAX};
    return lim - ((tt__v2l)v & abs_mask);
}

static inline int64_t bits_of(double d)
{
    int64_t b;
    memcpy(&b, &d, sizeof b);
    return b;
}

/* The limit on the velocity state: Verlet's |x − x_old| is |v|·h. */
static inline double velocity_limit(const tt_world *w, double h)
{
    return w->integrator == TT_VERLET ? TT_DIVERGED * h : TT_DIVERGED;
}

/* Particle i, one at a time: the scan's tail and the stopping pass. */
static inline bool past_guard(const tt_world *w, uint32_t i, bool verlet, double vmax)
{
    double x = w->px[i], y = w->py[i];
    double vx = verlet ? x - w->qx[i] : w->qx[i], vy = verlet ? y - w->qy[i] : w->qy[i];
    return !(fabs(x) <= TT_DIVERGED && fabs(y) <= TT_DIVERGED && fabs(vx) <= vmax && fabs(vy) <= vmax);
}

static bool any_past_guard(const tt_world *w, double h)
{
    const uint32_t n = w->ppool.count;
    const double *px = w->px, *py = w->py, *qx = w->qx, *qy = w->qy;
    const bool verlet = w->integrator == TT_VERLET;
    const double vmax = velocity_limit(w, h);
    const tt__v2l L = {bits_of(TT_DIVERGED), bits_of(TT_DIVERGED)}, V = {bits_of(vmax), bits_of(vmax)};
    tt__v2l acc = {0, 0};
    uint32_t i = 0;
    if (verlet) {
        for (; i + 2 <= n; i += 2) {
            tt__v2d x = load2(px + i), y = load2(py + i);
            acc |= excess(x, L) | excess(y, L) | excess(x - load2(qx + i), V) | excess(y - load2(qy + i), V);
        }
    } else {
        for (; i + 2 <= n; i += 2)
            acc |= excess(load2(px + i), L) | excess(load2(py + i), L) | excess(load2(qx + i), V) |
                   excess(load2(qy + i), V);
    }
    bool any = (acc[0] | acc[1]) < 0;
    for (; i < n; i++) any |= past_guard(w, i, verlet, vmax);
    return any;
}

/* The integrators stop a particle that passes TT_DIVERGED; constraints and
 * contacts can push one past it too (a pin dragged 1e12 m in one substep, a
 * tiny mass between stiff links), so the same rule holds after the sweeps:
 * the particle is stopped where the sweeps began (bx/by: Verlet's start of
 * the substep, where the integrator put the others). */
static void guard(tt_world *w, double h)
{
    if (!any_past_guard(w, h)) return;
    const uint32_t n = w->ppool.count;
    const bool verlet = w->integrator == TT_VERLET;
    const double vmax = velocity_limit(w, h);
    for (uint32_t i = 0; i < n; i++) {
        if (w->inv_mass[i] == 0.0 || !past_guard(w, i, verlet, vmax)) continue;
        if (verlet) { /* stopped: x_old = x, at the start Verlet's x_old had before the velocity passes */
            w->px[i] = w->qx[i] = w->scr.bx[i];
            w->py[i] = w->qy[i] = w->scr.by[i];
        } else {
            w->px[i] = w->scr.bx[i];
            w->py[i] = w->scr.by[i];
            w->qx[i] = w->qy[i] = 0.0;
        }
        for (int g = 0; g < w->group_count; g++)
            if (w->groups[g].ops->stopped) w->groups[g].ops->stopped(w, w->groups[g].self, i);
        w->stats.diverged++;
    }
}

/* Groups as they were made, nothing set (a query's collision state), and
 * groups without sweeps (sleeping): the substep is that of a world without
 * them, stats included. */
static bool all_idle(const tt_world *w)
{
    for (int g = 0; g < w->group_count; g++) {
        const tt__group_ops *ops = w->groups[g].ops;
        if (ops->relax && (!ops->idle || !ops->idle(w, w->groups[g].self))) return false;
    }
    return true;
}

/* After the begins: no group with sweeps has anything to relax this
 * substep (collisions on, nothing touching). Verlet only: the other
 * integrators' velocity fix would still turn a velocity of -0 into +0, and
 * their contacts keep the substep's end positions for the next. */
static bool all_quiet(const tt_world *w)
{
    if (w->integrator != TT_VERLET) return false;
    for (int g = 0; g < w->group_count; g++) {
        const tt__group_ops *ops = w->groups[g].ops;
        if (ops->relax && (!ops->quiet || !ops->quiet(w, w->groups[g].self))) return false;
    }
    return true;
}

void tt__solve(tt_world *w, double h)
{
    if (w->group_count == 0 || all_idle(w)) return;
    for (int g = 0; g < w->group_count; g++) {
        const tt__group_ops *ops = w->groups[g].ops;
        if (!ops->begin) continue;
        double tb = tt__now_ms();
        ops->begin(w, w->groups[g].self, h);
        w->stats.stage_ms[ops->begin_stage] += tt__now_ms() - tb;
    }
    if (all_quiet(w)) { /* what the sweeps would report: one sweep, no error, nothing moved */
        w->stats.iterations += 1;
        w->stats.max_error = 0.0;
        return;
    }
    double t0 = tt__now_ms();
    const uint32_t n = w->ppool.count;
    /* Where each particle starts the sweeps, kept in bx/by: velocity
     * integrators learn their corrections from it, and the guard stops a
     * particle there. Verlet's x_old holds the substep's start too, but a
     * bounds constraint's friction and the contacts' velocity pass rewrite it
     * from a position that may be the very one that passed the guard, so
     * Verlet keeps its own copy. */
    const bool verlet = w->integrator == TT_VERLET, fix = !verlet;
    tt__copy(w->scr.bx, verlet ? w->qx : w->px, n * sizeof(double));
    tt__copy(w->scr.by, verlet ? w->qy : w->py, n * sizeof(double));
    const bool jacobi = w->order == TT_JACOBI;
    if (jacobi) jacobi_zero(w);
    if (!jacobi && w->scr.jn) { /* tt__correct reads jn to pick the mode */
        free(w->scr.jx); free(w->scr.jy); free(w->scr.jn);
        w->scr.jx = w->scr.jy = NULL;
        w->scr.jn = NULL;
        w->scr.jcap = 0;
    }
    double err = 0.0;
    uint32_t it = 0;
    bool moved = false; /* some sweep found an error (or a NaN) to correct */
    lay_begin(w);
    while (it < w->iterations) {
        err = sweep(w, h, it == 0, &moved);
        if (jacobi) jacobi_apply(w);
        it++;
        if (err <= w->tolerance) break;
    }
    lay_end(w);
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->sweeps_done) w->groups[g].ops->sweeps_done(w, w->groups[g].self);
    w->stats.iterations += it;
    w->stats.max_error = err;
    if (fix) {
        const double inv_h = 1.0 / h;
        for (uint32_t i = 0; i < n; i++) {
            if (w->inv_mass[i] == 0.0) continue;
            w->qx[i] += (w->px[i] - w->scr.bx[i]) * inv_h;
            w->qy[i] += (w->py[i] - w->scr.by[i]) * inv_h;
        }
    }
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->end) w->groups[g].ops->end(w, w->groups[g].self, h);
    /* Sweeps that found nothing to correct moved nothing, and the velocity
     * passes only act where they did (or slow a bullet's sweep down): the
     * integrator's own guard has seen every particle then. A world whose
     * groups are idle (collisions on, nothing touching) skips the scan. */
    if (moved) guard(w, h);
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

size_t tt__solver_memory(const tt_world *w)
{
    size_t bytes = (size_t)w->scr.jcap * (2 * sizeof(double) + sizeof(uint32_t)) + (size_t)w->scr.bcap * 2 * sizeof(double) +
                   (size_t)w->scr.rows_cap * 4 * sizeof(double);
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->memory) bytes += w->groups[g].ops->memory(w, w->groups[g].self);
    return bytes;
}

void tt__solver_free(tt_world *w)
{
    for (int g = 0; g < w->group_count; g++)
        if (w->groups[g].ops->destroy) w->groups[g].ops->destroy(w, w->groups[g].self);
    w->group_count = 0;
}
