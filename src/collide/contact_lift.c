/* tether — the last part of the velocity pass: no contact throws what rests
 * on it upward faster than the contact itself allows, bottom to top.
 *
 * Velocity here comes from positions (Verlet's x − x_old; the other
 * integrators add what the sweeps moved), so when the sweeps push apart
 * particles that overlapped, the push becomes velocity. Each pair's own
 * velocity pass clamps the pair's relative speed to what the pair allows
 * (no more separation than before the sweeps, or its bounce), but a push
 * travels up a column or a pile from what holds it up, and the speed the
 * whole column then shares is relative to no pair: one velocity pass only
 * clamps it where the column meets the floor. Ten balls spawned 20 % into
 * each other in a column left the floor at 27 m/s, and a pile that one
 * substep's sweeps cannot hold boiled, layers thrown up by the overlap of
 * the layers under them, creating energy.
 *
 * So after the pass, touched pairs go in order of height along gravity
 * (a counting sort into bands), and in each the upper particle's speed
 * along their normal is brought within what the pair allows: away from the
 * lower one no faster than before the sweeps (or its bounce), towards it
 * not at all. Only the upper particle changes (the lower one is final by
 * then: "shock propagation", Guendelman et al. 2003, here for velocities
 * alone), and only ever toward rest: its speed along the normal moves
 * toward 0 and never past it, so the pass removes energy and never adds
 * it. A pair side by side is ordered like the rest (a tie keeps the list's
 * order); its own pass has already left it within what it allows, so there
 * this changes little. Measured on the reference pour at 1 × 8 (20 s):
 * leaving out pairs whose normal is more than 60° from "up" left the pile
 * rattling (KE 3.5e-2 J/kg at the end, against 3.9e-5 with every pair). */
#include "collide_internal.h"

/* The separation speed the pair allows, from its pre-solve relative normal
 * speed vn0: a bounce after an impact, else no more than it had. */
static inline double allowed(double vn0, double e, double thr)
{
    const double bounce = -e * vn0, kept = tt__max(vn0, 0.0);
    return vn0 < -thr ? bounce : kept;
}

static void lift_one(tt_world *w, tt__collide *c, uint32_t lo, uint32_t up, double thr)
{
    double nx = w->px[up] - w->px[lo], ny = w->py[up] - w->py[lo];
    const double d2 = nx * nx + ny * ny;
    /* a step can leave a position not finite here (the guard stops that particle after this
     * pass): an infinite one made its partner's normal, and so its velocity, NaN */
    if (!(d2 > 0.0 && d2 < INFINITY) || w->inv_mass[up] == 0.0) return;
    const double id = 1.0 / sqrt(d2);
    nx *= id;
    ny *= id;
    const tt_vec2 vu = tt__velocity(w, up), vl = tt__velocity(w, lo);
    const double un = vu.x * nx + vu.y * ny, ln = vl.x * nx + vl.y * ny;
    const double vn0 = (c->scr.vx0[up] - c->scr.vx0[lo]) * nx + (c->scr.vy0[up] - c->scr.vy0[lo]) * ny;
    const double ea = tt__mat(c, up, 0), eb = tt__mat(c, lo, 0);
    const double cap = tt__max(0.0, ln + allowed(vn0, tt__max(ea, eb), thr)); /* a lower one falling away does not pull the upper one down */
    const double floor = tt__min(ln, 0.0); /* nor does one rising push it up: it only stops its approach */
    /* un above cap: cap; else un, or floor where un is under it: a min and a
     * max (cap ≥ 0 ≥ floor: the same bits, NaN and signed zeros included) */
    const double to = tt__min(cap, tt__max(floor, un));
    if (to != un) tt__add_velocity(w, up, (to - un) * nx, (to - un) * ny);
}

/* Height along −gravity of particle i. */
static inline double height(const tt_world *w, double gx, double gy, uint32_t i) { return -(w->px[i] * gx + w->py[i] * gy); }

/* The band of height h: below nb by construction where h is finite; a
 * height that is not (a position the guard will stop) goes in the top
 * band, where taking it as an integer was undefined (the C API fuzzer). */
static inline uint32_t band_of(double h, double hmin, double scale, uint32_t nb)
{
    const double f = (h - hmin) * scale;
    return f < nb ? (uint32_t)f : nb - 1;
}

void tt__contacts_lift(tt_world *w, tt__collide *c, double thr)
{
    const double gl = sqrt(w->gravity.x * w->gravity.x + w->gravity.y * w->gravity.y);
    if (!(gl > 0.0)) return; /* no up */
    const double gx = w->gravity.x / gl, gy = w->gravity.y / gl;
    const bool bat = c->scr.batched;
    /* the touched pairs, lower particle first, and the bands' extent */
    uint32_t nt = 0;
    double hmin = INFINITY, hmax = -INFINITY, rsum = 0.0;
    /* one size for the three (bands ≤ pairs): the pair list's room, so they grow when it grows and a
     * world at steady state allocates nothing */
    const uint32_t want = (bat ? c->scr.bat.cap : c->scr.paircap) + 1;
    uint32_t cap2 = c->scr.lift_cap, cap3 = c->scr.lift_cap;
    if (!tt__grow((void **)&c->scr.lift_start, &cap2, want, sizeof *c->scr.lift_start) ||
        !tt__grow((void **)&c->scr.lift_order, &cap3, want, sizeof *c->scr.lift_order) ||
        !tt__grow((void **)&c->scr.lift, &c->scr.lift_cap, want, sizeof *c->scr.lift)) {
        tt__step_oom(w, "the bottom-up velocity pass");
        return;
    }
    for (uint32_t t = 0; t < c->scr.ntouch; t++) {
        const uint32_t k = c->scr.touch[t];
        uint32_t a, b;
        double rs;
        if (bat) a = c->scr.bat.a[k], b = c->scr.bat.b[k], rs = c->scr.bat.rs[k];
        else a = c->scr.pairs[k].a, b = c->scr.pairs[k].b, rs = c->scr.pairs[k].rs;
        const double ha = height(w, gx, gy, a), hb = height(w, gx, gy, b), hl = tt__min(ha, hb);
        const uint32_t lo = ha <= hb ? a : b; /* the upper one its complement: which is lower goes either way */
        c->scr.lift[nt++] = (tt__lift){lo, a ^ b ^ lo, hl};
        hmin = hl < hmin ? hl : hmin;
        hmax = hl > hmax ? hl : hmax;
        rsum += rs;
    }
    if (nt == 0) return;
    /* bands half a typical contact tall: a pair's lower particle sits in a band below its upper one's pairs */
    const double band = 0.5 * rsum / nt, spread = band > 0.0 ? (hmax - hmin) / band : 0.0;
    const uint32_t nb = !(spread < nt) ? nt : (uint32_t)spread + 1; /* compared first: a far pile's spread fits no integer */
    const double scale = hmax > hmin ? (nb - 1) / (hmax - hmin) * (1.0 - 1e-12) : 0.0;
    uint32_t *start = c->scr.lift_start, *order = c->scr.lift_order;
    for (uint32_t k = 0; k <= nb; k++) start[k] = 0;
    for (uint32_t k = 0; k < nt; k++) start[band_of(c->scr.lift[k].h, hmin, scale, nb) + 1]++;
    for (uint32_t k = 0; k < nb; k++) start[k + 1] += start[k];
    for (uint32_t k = 0; k < nt; k++) order[start[band_of(c->scr.lift[k].h, hmin, scale, nb)]++] = k;
    for (uint32_t k = 0; k < nt; k++) lift_one(w, c, c->scr.lift[order[k]].lo, c->scr.lift[order[k]].up, thr);
}
