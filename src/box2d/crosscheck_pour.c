/* tether — the reference pour in the cross-check: Box2D with sleeping and
 * continuous physics off (the fair pairing), Box2D at its defaults, and
 * tether at several settings, all stepped in one run in turns of 30 steps
 * (a turn keeps each engine's data in cache; step by step they would evict
 * each other), each step timed. Measured at 5 s and at the end (20 s).
 * Box2D at its defaults runs the first 5 s only in the full pour: its
 * continuous physics costs 4× its sleeping-off setting there (measured),
 * and would make most of the cross-check's time. */
#include "box2d_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BLOCK 30
#define MAX_TT 5

typedef struct pour_run {
    ts_scene scene;
    tb_world *b2[2];                /* sleeping off; Box2D's defaults */
    ts_tether tt[MAX_TT];
    ts_tether_settings set[MAX_TT];
    int ntt;
    int default_steps;              /* how long Box2D at its defaults runs */
    double *ms;                     /* per world (2 + ntt) and step */
    double *xy;
} pour_run;

static void pour_close(pour_run *p)
{
    for (int i = 0; i < 2; i++) tb_world_destroy(p->b2[i]);
    for (int i = 0; i < p->ntt; i++) ts_tether_free(&p->tt[i]);
    ts_scene_free(&p->scene);
    free(p->ms);
    free(p->xy);
}

static bool pour_open(pour_run *p, bool quick, const char **why)
{
    /* the last row of each: particles that turn (tt_world_def.spin) */
    static const uint32_t full[MAX_TT][3] = {{1, 8, 0}, {1, 16, 0}, {8, 8, 0}, {16, 8, 0}, {1, 8, 1}};
    static const uint32_t fast[3][3] = {{1, 8, 0}, {8, 8, 0}, {1, 8, 1}};
    memset(p, 0, sizeof *p);
    ts_scene_named(&p->scene, "pour", quick);
    tb_world_def d = tb_world_def_default();
    d.sleep = d.continuous = false;
    p->b2[0] = tb_scene_build(&p->scene, &d, why);
    p->b2[1] = p->b2[0] ? tb_scene_build(&p->scene, &(tb_world_def){{0, 0}, 8, 3, true, true}, why) : NULL;
    if (!p->b2[1]) return pour_close(p), false;
    const int n = quick ? 3 : MAX_TT;
    for (int k = 0; k < n; k++) {
        p->set[k] = ts_tether_settings_default();
        p->set[k].substeps = quick ? fast[k][0] : full[k][0];
        p->set[k].iterations = quick ? fast[k][1] : full[k][1];
        p->set[k].spin = (quick ? fast[k][2] : full[k][2]) != 0;
        if (ts_tether_build(&p->scene, &p->set[k], &p->tt[k], why) != TT_OK) return pour_close(p), false;
        p->ntt = k + 1;
    }
    p->default_steps = quick ? (int)p->scene.steps : (int)lround(5 / p->scene.dt);
    p->ms = calloc((size_t)(2 + n) * p->scene.steps, sizeof *p->ms);
    p->xy = malloc(2 * (size_t)p->scene.body_count * sizeof *p->xy);
    if (!p->ms || !p->xy) return *why = "out of memory", pour_close(p), false;
    return true;
}

/* One block of steps of world k (0, 1: Box2D; 2…: tether). */
static bool pour_block(pour_run *p, int k, int s0, int s1, const char **why)
{
    double *ms = p->ms + (size_t)k * p->scene.steps;
    for (int s = s0; s < s1; s++) {
        const double t0 = cc_now_ms();
        bool good = k < 2 ? tb_world_step(p->b2[k], p->scene.dt) : tt_world_step(p->tt[k - 2].world, p->scene.dt) == TT_OK;
        ms[s] = cc_now_ms() - t0;
        if (!good) return *why = k < 2 ? tb_last_error() : tt_last_error(p->tt[k - 2].world), false;
    }
    return true;
}

typedef struct { ts_pile pile; double ke; } pour_state;

static void measure(pour_run *p, int k, pour_state *out)
{
    const uint32_t n = p->scene.body_count - 3; /* bodies 0–2: the floor and the walls */
    if (k < 2) {
        tb_positions(p->b2[k], 3, (int)n, p->xy);
        out->ke = tb_scene_kinetic_per_kg(p->b2[k]);
    } else {
        tt_particles_get_positions(p->tt[k - 2].world, p->tt[k - 2].circles, n, p->xy);
        out->ke = ts_tether_kinetic_per_kg(&p->tt[k - 2]);
    }
    ts_pile_measure(p->xy, n, 0.5, &out->pile);
}

static void rows_for(cc_report *r, const char *setting, const pour_state b[2], const pour_state t[2], bool has_tether)
{
    static const char *when[2] = {"5 s", "20 s"};
    for (int i = 0; i < 2; i++) {
        const struct { const char *what, *unit; double b, t; bool end_only; } m[5] = {
            {"pile height", "m", b[i].pile.height, t[i].pile.height, false},
            {"max overlap", "r", b[i].pile.max_overlap, t[i].pile.max_overlap, true},
            {"mean overlap", "r", b[i].pile.mean_overlap, t[i].pile.mean_overlap, true},
            {"contacts per circle", "1", b[i].pile.contacts, t[i].pile.contacts, true},
            {"kinetic energy", "J/kg", b[i].ke, t[i].ke, false}};
        for (int j = 0; j < 5; j++) {
            if ((m[j].end_only && i == 0) || (!has_tether && isnan(m[j].b))) continue;
            char what[48];
            snprintf(what, sizeof what, "%s at %s", m[j].what, when[i]);
            cc_row *w = cc_add(r, "pour", what, m[j].unit);
            if (!w) return;
            snprintf(w->setting, sizeof w->setting, "%s", setting);
            w->box2d = m[j].b;
            w->tether = has_tether ? m[j].t : NAN;
        }
    }
}

/* Mean ms/step over the run, and the range of its blocks' means. */
static void block_stats(const double *ms, int steps, double *mean, double *lo, double *hi)
{
    *mean = 0;
    *lo = INFINITY;
    *hi = -INFINITY;
    for (int s0 = 0; s0 < steps; s0 += BLOCK) {
        double b = 0;
        const int s1 = s0 + BLOCK < steps ? s0 + BLOCK : steps;
        for (int s = s0; s < s1; s++) b += ms[s] / (s1 - s0);
        *lo = fmin(*lo, b);
        *hi = fmax(*hi, b);
        *mean += b * (s1 - s0) / steps;
    }
}

static void report(cc_report *r, pour_run *p, pour_state st[][2])
{
    const int steps = (int)p->scene.steps;
    const size_t stride = p->scene.steps;
    for (int k = 0; k < p->ntt; k++) {
        char set[24];
        snprintf(set, sizeof set, "%ux%u%s", p->set[k].substeps, p->set[k].iterations, p->set[k].spin ? " spin" : "");
        rows_for(r, set, st[0], st[2 + k], true);
        cc_cost *c = cc_add_cost(r, "pour", set);
        if (!c) continue;
        snprintf(c->setting, sizeof c->setting, "%s vs b2 no sleep, no CCD", set);
        block_stats(p->ms, steps, &c->box2d_med, &c->box2d_min, &c->box2d_max);
        block_stats(p->ms + (2 + k) * stride, steps, &c->tether_med, &c->tether_min, &c->tether_max);
        c->runs = 1;
        c->steps = steps;
    }
    if (p->default_steps < steps) st[1][1] = (pour_state){{NAN, NAN, NAN, 0, NAN}, NAN};
    rows_for(r, "b2 defaults", st[1], st[1], false);
    cc_cost *c = cc_add_cost(r, "pour", "");
    if (c) {
        snprintf(c->setting, sizeof c->setting, "b2 defaults (sleep, CCD), %.0f s", p->default_steps * p->scene.dt);
        block_stats(p->ms + stride, p->default_steps, &c->box2d_med, &c->box2d_min, &c->box2d_max);
        c->tether_med = c->tether_min = c->tether_max = NAN;
        c->runs = 1;
        c->steps = p->default_steps;
    }
}

bool cc_pour(cc_report *r, const char **why)
{
    pour_run p;
    if (!pour_open(&p, r->quick, why)) return false;
    pour_state st[2 + MAX_TT][2];
    const int steps = (int)p.scene.steps, worlds = 2 + p.ntt, at5 = (int)lround(5 / p.scene.dt);
    for (int s0 = 0; s0 < steps; s0 += BLOCK) {
        const int s1 = s0 + BLOCK < steps ? s0 + BLOCK : steps;
        for (int k = 0; k < worlds; k++) {
            if (k == 1 && s0 >= p.default_steps) continue;
            if (!pour_block(&p, k, s0, s1, why)) return pour_close(&p), false;
            if (s1 == at5) measure(&p, k, &st[k][0]);
            if (s1 == steps && (k != 1 || s1 <= p.default_steps)) measure(&p, k, &st[k][1]);
        }
    }
    report(r, &p, st);
    pour_close(&p);
    return true;
}
