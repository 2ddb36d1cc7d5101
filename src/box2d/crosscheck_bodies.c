/* tether — the cross-check's scenes of bodies in contact or spinning:
 * bounce, slope, spin, the pyramid of boxes and the pyramid of discs (see
 * crosscheck_scenes.c for the settings both engines run at). */
#include "box2d_scene.h"

#include <math.h>
#include <string.h>

static void both(const cc_pair *p, uint32_t body, ts_state st[2])
{
    tb_scene_state(p->b2, body, &st[0]);
    ts_tether_state(&p->tt, body, &st[1]);
}

/* --- 3. bounce -------------------------------------------------------------- */

typedef struct {
    double last_y[2], peak[2][2];
    int bounces[2];
    bool rising[2];
} bounce_ctx;

/* A rebound starts when the bottom, having gone down, goes up again; its
 * height is the highest point before it goes down. */
static void bounce_probe(const cc_pair *p, int step, void *ctx)
{
    bounce_ctx *c = ctx;
    ts_state st[2];
    both(p, 1, st);
    for (int e = 0; e < 2; e++) {
        const double y = st[e].position.y - 0.5;
        if (step > 1) {
            if (!c->rising[e] && y > c->last_y[e] + 1e-4 && c->last_y[e] < 0.05) c->rising[e] = true;
            if (c->rising[e] && y < c->last_y[e] - 1e-4) {
                if (c->bounces[e] < 2) c->peak[e][c->bounces[e]] = c->last_y[e];
                c->bounces[e]++;
                c->rising[e] = false;
            }
        }
        c->last_y[e] = y;
    }
}

bool cc_bounce(cc_report *r, const char **why)
{
    ts_scene s;
    ts_scene_named(&s, "bounce", r->quick);
    bounce_ctx c;
    memset(&c, 0, sizeof c);
    const bool good = cc_run_small(r, &s, true, bounce_probe, &c, why);
    if (good) {
        cc_put(r, "bounce", "1st rebound, bottom height (e^2 h)", "m", 0.5, c.peak[0][0], c.peak[1][0]);
        cc_put(r, "bounce", "2nd rebound (e^4 h)", "m", 0.125, c.peak[0][1], c.peak[1][1]);
    }
    ts_scene_free(&s);
    return good;
}

/* --- 4. slope --------------------------------------------------------------- */

typedef struct { double d[2], angle; } slope_ctx;

/* Distance slid down the slope at the end of the run. */
static void slope_probe(const cc_pair *p, int step, void *ctx)
{
    slope_ctx *c = ctx;
    if (step != (int)p->scene.steps) return;
    ts_state st[2];
    both(p, 1, st);
    const ts_body *b = &p->scene.bodies[1];
    for (int e = 0; e < 2; e++)
        c->d[e] = -((st[e].position.x - b->position.x) * cos(c->angle) + (st[e].position.y - b->position.y) * sin(c->angle));
}

static bool slide(cc_report *r, double degrees, int steps, bool timed, slope_ctx *c, const char **why)
{
    ts_scene s;
    ts_scene_slope(&s, degrees, 0.5);
    s.steps = (uint32_t)steps;
    memset(c, 0, sizeof *c);
    c->angle = degrees * M_PI / 180;
    /* only the first slope is timed: the sweep repeats the same cost */
    const bool good = cc_run_small(r, &s, timed, slope_probe, c, why);
    ts_scene_free(&s);
    return good;
}

bool cc_slope(cc_report *r, const char **why)
{
    slope_ctx c;
    const double mu = 0.5, g = 10;
    if (!slide(r, 20, 120, true, &c, why)) return false;
    cc_put(r, "slope", "slid in 2 s at 20 deg, mu 0.5 (sticks)", "m", NAN, c.d[0], c.d[1]);
    const double a = 35 * M_PI / 180, acc = g * (sin(a) - mu * cos(a));
    if (!slide(r, 35, 120, false, &c, why)) return false;
    cc_put(r, "slope", "slid in 2 s at 35 deg, mu 0.5", "m", 0.5 * acc * 4, c.d[0], c.d[1]);
    /* the steepest slope where the box still holds (moves < 1 cm in 1 s), to 1 degree */
    double held[2] = {NAN, NAN};
    for (int deg = 20; deg <= 34; deg++) {
        if (!slide(r, deg, 60, false, &c, why)) return false;
        for (int e = 0; e < 2; e++)
            if (c.d[e] < 0.01 && (isnan(held[e]) || held[e] == deg - 1)) held[e] = deg;
    }
    cc_put(r, "slope", "steepest slope held 1 s (atan mu)", "deg", atan(mu) * 180 / M_PI, held[0], held[1]);
    return true;
}

/* --- 5. spin ---------------------------------------------------------------- */

typedef struct { double angle[2], last[2], L0[2], L1[2]; } spin_ctx;

/* tether's angle comes in (−π, π]: unwrapped step by step. */
static void spin_probe(const cc_pair *p, int step, void *ctx)
{
    spin_ctx *c = ctx;
    ts_state st[2];
    both(p, 0, st);
    for (int e = 0; e < 2; e++) {
        double d = st[e].angle - c->last[e];
        d -= 2 * M_PI * floor((d + M_PI) / (2 * M_PI));
        c->angle[e] += d;
        c->last[e] = st[e].angle;
        if (step == 1) c->L0[e] = st[e].momentum;
        c->L1[e] = st[e].momentum;
    }
}

bool cc_spin(cc_report *r, const char **why)
{
    ts_scene s;
    ts_scene_named(&s, "spin", r->quick);
    spin_ctx c;
    memset(&c, 0, sizeof c);
    const ts_body *b = &s.bodies[0];
    const double t = s.steps * s.dt, L = ts_body_inertia(b) * b->spin;
    const bool good = cc_run_small(r, &s, true, spin_probe, &c, why);
    if (good) {
        cc_put(r, "spin", "turned in 2 s (w t)", "rad", b->spin * t, c.angle[0], c.angle[1]);
        cc_put(r, "spin", "angular momentum after 1 step", "kg m2/s", L, c.L0[0], c.L0[1]);
        cc_put(r, "spin", "angular momentum at 2 s / after 1 step", "", 1, c.L1[0] / c.L0[0], c.L1[1] / c.L0[1]);
    }
    ts_scene_free(&s);
    return good;
}

/* --- 6. pyramid ------------------------------------------------------------- */

typedef struct { double drift[2], rise[2], turn[2]; } pyramid_ctx;

static void pyramid_probe(const cc_pair *p, int step, void *ctx)
{
    pyramid_ctx *c = ctx;
    const uint32_t top = p->scene.body_count - 1;
    for (uint32_t i = 1; i <= top; i++) {
        ts_state st[2];
        both(p, i, st);
        for (int e = 0; e < 2; e++) {
            const double a = fabs(remainder(st[e].angle, M_PI / 2)) * 180 / M_PI;
            c->turn[e] = fmax(c->turn[e], a);
            if (i == top && step == (int)p->scene.steps) {
                c->drift[e] = fabs(st[e].position.x - p->scene.bodies[top].position.x);
                c->rise[e] = st[e].position.y - p->scene.bodies[top].position.y;
            }
        }
    }
}

bool cc_pyramid(cc_report *r, const char **why)
{
    ts_scene s;
    ts_scene_named(&s, "pyramid", r->quick);
    pyramid_ctx c;
    memset(&c, 0, sizeof c);
    const bool good = cc_run_small(r, &s, true, pyramid_probe, &c, why);
    if (good) {
        char m[48];
        snprintf(m, sizeof m, "top box sideways drift at %.0f s", s.steps * s.dt);
        cc_put(r, "pyramid", m, "m", 0, c.drift[0], c.drift[1]);
        snprintf(m, sizeof m, "top box height change at %.0f s", s.steps * s.dt);
        cc_put(r, "pyramid", m, "m", 0, c.rise[0], c.rise[1]);
        cc_put(r, "pyramid", "largest box rotation, any step", "deg", 0, c.turn[0], c.turn[1]);
    }
    ts_scene_free(&s);
    return good;
}

/* --- 7. the pyramid of discs ------------------------------------------------ */

typedef struct {
    double spread[2], sink[2];
} discs_ctx;

/* At the end: how much farther apart the bottom row's two end discs are
 * (the pyramid wedging its base apart), and how far the top disc sank. */
static void discs_probe(const cc_pair *p, int step, void *ctx)
{
    discs_ctx *c = ctx;
    if (step != (int)p->scene.steps) return;
    const ts_body *b = p->scene.bodies;
    const uint32_t top = p->scene.body_count - 1;
    uint32_t right = 1; /* the bottom row: bodies 1 … right, at the start's lowest height */
    while (right + 1 <= top && b[right + 1].position.y == b[1].position.y) right++;
    ts_state l[2], r[2], t[2];
    both(p, 1, l);
    both(p, right, r);
    both(p, top, t);
    for (int e = 0; e < 2; e++) {
        c->spread[e] = (r[e].position.x - l[e].position.x) - (b[right].position.x - b[1].position.x);
        c->sink[e] = b[top].position.y - t[e].position.y;
    }
}

bool cc_discs(cc_report *r, const char **why)
{
    ts_scene s;
    ts_scene_named(&s, "discs", r->quick);
    discs_ctx c;
    memset(&c, 0, sizeof c);
    const bool good = cc_run_small(r, &s, true, discs_probe, &c, why);
    if (good) {
        char m[48];
        snprintf(m, sizeof m, "base spread at %.0f s", s.steps * s.dt);
        cc_put(r, "discs", m, "m", 0, c.spread[0], c.spread[1]);
        snprintf(m, sizeof m, "top disc sunk at %.0f s", s.steps * s.dt);
        cc_put(r, "discs", m, "m", 0, c.sink[0], c.sink[1]);
    }
    ts_scene_free(&s);
    return good;
}
