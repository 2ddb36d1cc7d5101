/* tether — substeps by speed (tt_world_def.max_travel). A contact is found
 * and solved from where its particles are at the substep's start, so one
 * that crosses half a diameter in a substep meets its neighbours too late:
 * a column landing at 80 m/s, 1.3 m a step with radius 0.5, sinks into
 * itself (the 100 k pour at 1 × 8 collapses: circles on one centre, a mean
 * overlap of 20 % of a radius over the run). Substeps keep each move short,
 * but a fixed count is paid every step, also while the scene rests; this
 * asks for them only in the steps where something is fast relative to what
 * it can meet (a world falling as one, nothing near, is not). The count is
 * read from the world's state as the step begins (the same state gives the
 * same count, so replays, snapshots and journals step alike) and a larger
 * one is a time-corrected Verlet step like any change of dt. */
#include "core/internal.h"
#include "tether/collide.h"
#include "tether/terrain.h"

#include <math.h>

/* Whether a step can find contacts: particle contacts on, or a shape or a
 * terrain. Substeps by speed is for contacts, so a world without them runs
 * its set substeps however fast it is (and can run backwards). */
bool tt__world_collides(const tt_world *w)
{
    tt_collision_settings cs;
    return tt_world_shape_count(w) > 0 || tt_world_terrain_count(w) > 0 ||
           (tt_world_get_collision(w, &cs) == TT_OK && cs.particles);
}

/* What a particle can meet this step, as velocities: a box that holds the
 * velocity of every movable particle with a radius (when particle contacts
 * are on), and 0 for what stands still: pinned and sleeping particles, and
 * shapes and terrain within reach of the particles' box. */
typedef struct motion {
    double vlx, vly, vhx, vhy; /* the movable particles' velocity box */
    double plx, ply, phx, phy; /* the movable particles' box */
    float rmin, rmax;          /* their radii */
    bool held;                 /* some particle with a radius cannot move */
} motion;

static inline bool counts(const tt_world *w, uint32_t i)
{
    return (w->flags[i] & TT__PF_ALIVE) && w->radius[i] > 0.0f;
}

/* Comparisons, not fmin/fmax (library calls without -ffast-math): a NaN is never taken in. */
static inline void take_in(double *lx, double *ly, double *hx, double *hy, double x, double y)
{
    *lx = x < *lx ? x : *lx, *hx = x > *hx ? x : *hx;
    *ly = y < *ly ? y : *ly, *hy = y > *hy ? y : *hy;
}

/* Velocity i as the step begins: Verlet's (x − x_old) times 1/dt_prev (s), or the velocity kept. */
static inline tt_vec2 speed_of(const tt_world *w, uint32_t i, bool verlet, double s)
{
    return verlet ? (tt_vec2){(w->px[i] - w->qx[i]) * s, (w->py[i] - w->qy[i]) * s} : (tt_vec2){w->qx[i], w->qy[i]};
}

static motion measure(const tt_world *w, bool verlet, double s)
{
    motion m = {INFINITY, INFINITY, -INFINITY, -INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, INFINITY, 0.0f, false};
    for (uint32_t i = 0; i < w->ppool.count; i++) {
        if (!counts(w, i)) continue;
        if (w->inv_mass[i] == 0.0) { /* pinned or asleep */
            m.held = true;
            continue;
        }
        const tt_vec2 v = speed_of(w, i, verlet, s);
        take_in(&m.vlx, &m.vly, &m.vhx, &m.vhy, v.x, v.y);
        take_in(&m.plx, &m.ply, &m.phx, &m.phy, w->px[i], w->py[i]);
        m.rmin = w->radius[i] < m.rmin ? w->radius[i] : m.rmin;
        m.rmax = w->radius[i] > m.rmax ? w->radius[i] : m.rmax;
    }
    return m;
}

static inline double farthest(double v, double lo, double hi)
{
    const double a = fabs(v - lo), b = fabs(v - hi);
    return a > b ? a : b;
}

/* The substeps the step of dt runs: w->substeps, or more where contacts
 * can be found and a movable, awake particle with a radius would travel
 * farther than max_travel radii in one relative to anything it can meet
 * (the other particles, or what stands still): its farthest from the
 * velocity box, times dt, plus |g|·dt²/2, at most max_substeps. Relative,
 * so a scene falling as one, with nothing near, pays nothing. One pass
 * over the particles; a second only when the box is wide enough for some
 * particle to need more than the setting. */
uint32_t tt__travel_substeps(tt_world *w, double dt)
{
    const uint32_t base = w->substeps;
    if (w->max_travel == 0.0 || w->max_substeps <= base || !tt__world_collides(w)) return base;
    tt_collision_settings cs;
    const bool pairs = tt_world_get_collision(w, &cs) == TT_OK && cs.particles, verlet = w->integrator == TT_VERLET;
    const double s = verlet ? 1.0 / w->dt_prev : 1.0;
    const motion m = measure(w, verlet, s);
    if (!(m.plx <= m.phx && m.ply <= m.phy)) return base; /* nothing movable with a radius (or every position NaN) */
    const double fall = 0.5 * sqrt(w->gravity.x * w->gravity.x + w->gravity.y * w->gravity.y) * dt * dt;
    /* the fastest is no faster than the box's farthest corner from 0 */
    const double cx = farthest(0.0, m.vlx, m.vhx), cy = farthest(0.0, m.vly, m.vhy);
    const double reach = (double)m.rmax + sqrt(cx * cx + cy * cy) * dt + fall;
    /* the box of what can be met: the particles' velocities with particle contacts, 0 for what stands still */
    double lx = pairs ? m.vlx : INFINITY, ly = pairs ? m.vly : INFINITY, hx = pairs ? m.vhx : -INFINITY, hy = pairs ? m.vhy : -INFINITY;
    if ((pairs && m.held) || tt__statics_within(w, m.plx - reach, m.ply - reach, m.phx + reach, m.phy + reach))
        take_in(&lx, &ly, &hx, &hy, 0.0, 0.0);
    if (!(lx <= hx)) return base; /* nothing to meet */
    /* no particle is farther from that box than the box round it and the particles' is wide: below the
     * setting, one pass was enough */
    const double dx = fmax(hx, m.vhx) - fmin(lx, m.vlx), dy = fmax(hy, m.vhy) - fmin(ly, m.vly);
    if ((sqrt(dx * dx + dy * dy) * dt + fall) / (double)m.rmin <= w->max_travel * base) return base;
    double need = 0.0; /* the largest travel over the step, in radii */
    for (uint32_t i = 0; i < w->ppool.count; i++) {
        if (!counts(w, i) || w->inv_mass[i] == 0.0) continue;
        const tt_vec2 v = speed_of(w, i, verlet, s);
        const double fx = farthest(v.x, lx, hx), fy = farthest(v.y, ly, hy);
        const double r = (sqrt(fx * fx + fy * fy) * dt + fall) / (double)w->radius[i];
        need = r > need ? r : need;
    }
    const double n = ceil(need / w->max_travel); /* need ≤ 2·TT_DIVERGED·dt/r: finite, or +inf for r tiny */
    if (!(n < (double)w->max_substeps)) return w->max_substeps;
    return n > (double)base ? (uint32_t)n : base;
}
