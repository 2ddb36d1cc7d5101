/* tether — the seven small scenes of the cross-check: each run in both
 * engines, measured step by step against the analytic answer where there
 * is one, and timed over several runs. Box2D: 8 velocity / 3 position
 * iterations, sleeping off, continuous physics on; tether: r->small
 * (by default 1 substep, 8 iterations, boxes as 4 × 4 lattices). */
#include "box2d_scene.h"

#include <math.h>
#include <string.h>

static tb_world_def small_def(void)
{
    tb_world_def d = tb_world_def_default();
    d.sleep = false;
    return d;
}

static void state(const cc_pair *p, uint32_t body, ts_state *b2, ts_state *tt)
{
    tb_scene_state(p->b2, body, b2);
    ts_tether_state(&p->tt, body, tt);
}

bool cc_run_small(cc_report *r, const ts_scene *s, bool timed, cc_probe probe, void *ctx, const char **why)
{
    const ts_tether_settings set = r->small;
    const tb_world_def def = small_def();
    double b2[50], tt[50];
    const int runs = !timed ? 1 : r->runs < 50 ? r->runs : 50, steps = (int)s->steps;
    for (int k = 0; k < runs; k++) {
        cc_pair p;
        if (!cc_pair_open(&p, s, &set, &def, why)) return false;
        for (int i = 0; i < steps; i++) {
            if (!cc_pair_step(&p, 1, 1, why)) return cc_pair_close(&p), false;
            if (k == 0 && probe) probe(&p, i + 1, ctx);
        }
        b2[k] = tt[k] = 0;
        for (int i = 0; i < steps; i++) {
            b2[k] += p.t_b2[i] / steps;
            tt[k] += p.t_tt[i] / steps;
        }
        cc_pair_close(&p);
    }
    cc_cost *c = timed ? cc_add_cost(r, s->name, "") : NULL;
    if (c) {
        snprintf(c->setting, sizeof c->setting, "%ux%u lattice %u%s vs b2 8/3 no sleep", set.substeps, set.iterations, set.lattice,
                 set.anchored ? " anch" : "");
        cc_stats(b2, runs, &c->box2d_med, &c->box2d_min, &c->box2d_max);
        cc_stats(tt, runs, &c->tether_med, &c->tether_min, &c->tether_max);
        c->runs = runs;
        c->steps = steps;
    }
    return true;
}

void cc_put(cc_report *r, const char *scene, const char *measure, const char *unit, double expected, double b2, double tt)
{
    cc_row *w = cc_add(r, scene, measure, unit);
    if (!w) return;
    snprintf(w->setting, sizeof w->setting, "%ux%u L%u%s", r->small.substeps, r->small.iterations, r->small.lattice,
             r->small.anchored ? " anchored" : "");
    w->expected = expected;
    w->box2d = b2;
    w->tether = tt;
}

/* --- 1. fall ---------------------------------------------------------------- */

typedef struct { ts_state b2[2], tt[2]; } fall_ctx;

static void fall_probe(const cc_pair *p, int step, void *ctx)
{
    fall_ctx *f = ctx;
    if (step != (int)p->scene.steps) return;
    for (uint32_t i = 0; i < 2; i++) state(p, i, &f->b2[i], &f->tt[i]);
}

bool cc_fall(cc_report *r, const char **why)
{
    ts_scene s;
    ts_scene_named(&s, "fall", r->quick);
    fall_ctx f;
    memset(&f, 0, sizeof f);
    const bool good = cc_run_small(r, &s, true, fall_probe, &f, why);
    const double t = s.steps * s.dt, g = -s.gravity.y, drop = 0.5 * g * t * t;
    const ts_body *thrown = &s.bodies[1];
    if (good) {
        cc_put(r, "fall", "dropped box: fall in 1 s", "m", drop, 10 - f.b2[0].position.y, 10 - f.tt[0].position.y);
        cc_put(r, "fall", "thrown box: x at 1 s", "m", thrown->position.x + thrown->velocity.x * t, f.b2[1].position.x, f.tt[1].position.x);
        cc_put(r, "fall", "thrown box: rise in 1 s", "m", thrown->velocity.y * t - drop, f.b2[1].position.y - 10, f.tt[1].position.y - 10);
    }
    ts_scene_free(&s);
    return good;
}

/* --- 2. pendulum ------------------------------------------------------------ */

typedef struct {
    double last_x[2], cross[2][4], cross_last[2];
    int crossings[2];
    double amp_first[2], amp_last[2];
} pend_ctx;

/* Upward zero crossings of the bob's x (interpolated) give the period;
 * the largest swing in the first and the last 2 s, its decay. */
static void pend_probe(const cc_pair *p, int step, void *ctx)
{
    pend_ctx *c = ctx;
    ts_state st[2];
    state(p, 0, &st[0], &st[1]);
    const double t = step * p->scene.dt, end = p->scene.steps * p->scene.dt;
    for (int e = 0; e < 2; e++) {
        const double x = st[e].position.x, ang = fabs(atan2(x, 2 - st[e].position.y));
        if (step > 1 && c->last_x[e] < 0 && x >= 0) {
            const double tc = t - p->scene.dt * x / (x - c->last_x[e]);
            if (c->crossings[e] < 4) c->cross[e][c->crossings[e]] = tc;
            c->crossings[e]++;
            c->cross_last[e] = tc;
        }
        c->last_x[e] = x;
        if (t <= 2) c->amp_first[e] = fmax(c->amp_first[e], ang);
        if (t > end - 2) c->amp_last[e] = fmax(c->amp_last[e], ang);
    }
}

/* The period of a simple pendulum at amplitude a: 2π√(L/g) / AGM(1, cos(a/2)). */
static double pendulum_period(double L, double g, double a)
{
    double x = 1, y = cos(a / 2);
    for (int i = 0; i < 30; i++) {
        const double m = 0.5 * (x + y);
        y = sqrt(x * y);
        x = m;
    }
    return 2 * M_PI * sqrt(L / g) / x;
}

bool cc_pendulum(cc_report *r, const char **why)
{
    ts_scene s;
    ts_scene_named(&s, "pendulum", r->quick);
    pend_ctx c;
    memset(&c, 0, sizeof c);
    const bool good = cc_run_small(r, &s, true, pend_probe, &c, why);
    if (good) {
        /* over the first three swings the amplitudes still match; over the
         * whole run each engine's damping lowers its amplitude, and so its period */
        double T[2], T3[2];
        for (int e = 0; e < 2; e++) {
            T[e] = c.crossings[e] > 1 ? (c.cross_last[e] - c.cross[e][0]) / (c.crossings[e] - 1) : NAN;
            T3[e] = c.crossings[e] > 3 ? (c.cross[e][3] - c.cross[e][0]) / 3 : NAN;
        }
        cc_put(r, "pendulum", "period, first 3 swings (30 deg)", "s", pendulum_period(1, 10, 30 * M_PI / 180), T3[0], T3[1]);
        char m[48];
        snprintf(m, sizeof m, "period over %.0f s", s.steps * s.dt);
        cc_put(r, "pendulum", m, "s", NAN, T[0], T[1]);
        snprintf(m, sizeof m, "swing after %.0f s / first swing", s.steps * s.dt);
        cc_put(r, "pendulum", m, "", 1, c.amp_last[0] / c.amp_first[0], c.amp_last[1] / c.amp_first[1]);
    }
    ts_scene_free(&s);
    return good;
}
