/* tether — the Box2D cross-check's driver: both engines built from one
 * scene and stepped in turns, each step timed on its own (so both see the
 * same machine load); the tables are crosscheck_print.c's. */
#include "box2d_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

double cc_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

cc_row *cc_add(cc_report *r, const char *scene, const char *measure, const char *unit)
{
    if (r->nrows >= CC_MAX_ROWS) return NULL;
    cc_row *row = &r->rows[r->nrows++];
    memset(row, 0, sizeof *row);
    snprintf(row->scene, sizeof row->scene, "%s", scene);
    snprintf(row->measure, sizeof row->measure, "%s", measure);
    snprintf(row->unit, sizeof row->unit, "%s", unit);
    row->expected = row->box2d = row->tether = NAN;
    return row;
}

cc_cost *cc_add_cost(cc_report *r, const char *scene, const char *setting)
{
    if (r->ncosts >= (int)(sizeof r->costs / sizeof r->costs[0])) return NULL;
    cc_cost *c = &r->costs[r->ncosts++];
    memset(c, 0, sizeof *c);
    snprintf(c->scene, sizeof c->scene, "%s", scene);
    snprintf(c->setting, sizeof c->setting, "%s", setting);
    return c;
}

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void cc_stats(double *v, int n, double *med, double *lo, double *hi)
{
    if (n <= 0) {
        *med = *lo = *hi = NAN;
        return;
    }
    qsort(v, (size_t)n, sizeof *v, by_value);
    *med = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    *lo = v[0];
    *hi = v[n - 1];
}

bool cc_pair_open(cc_pair *p, const ts_scene *s, const ts_tether_settings *set, const tb_world_def *def, const char **why)
{
    memset(p, 0, sizeof *p);
    if (!ts_scene_copy(&p->scene, s)) {
        *why = "out of memory";
        return false;
    }
    if (ts_tether_build(&p->scene, set, &p->tt, why) != TT_OK) {
        ts_scene_free(&p->scene);
        return false;
    }
    if (!(p->b2 = tb_scene_build(&p->scene, def, why))) {
        ts_tether_free(&p->tt);
        ts_scene_free(&p->scene);
        return false;
    }
    return true;
}

static bool grow_times(cc_pair *p, int need)
{
    double *a = realloc(p->t_tt, (size_t)need * sizeof *a);
    if (a) p->t_tt = a;
    double *b = realloc(p->t_b2, (size_t)need * sizeof *b);
    if (b) p->t_b2 = b;
    return a && b;
}

bool cc_pair_step(cc_pair *p, int steps, int block, const char **why)
{
    if (!grow_times(p, p->steps_done + steps)) {
        *why = "out of memory";
        return false;
    }
    const double dt = p->scene.dt;
    for (int s0 = 0; s0 < steps; s0 += block) {
        const int s1 = s0 + block < steps ? s0 + block : steps;
        for (int s = s0; s < s1; s++) {
            const double t0 = cc_now_ms();
            const bool good = tb_world_step(p->b2, dt);
            p->t_b2[p->steps_done + s] = cc_now_ms() - t0;
            if (!good) return *why = tb_last_error(), false;
        }
        for (int s = s0; s < s1; s++) {
            const double t0 = cc_now_ms();
            const tt_result r = tt_world_step(p->tt.world, dt);
            p->t_tt[p->steps_done + s] = cc_now_ms() - t0;
            if (r != TT_OK) return *why = tt_last_error(p->tt.world), false;
        }
    }
    p->steps_done += steps;
    return true;
}

void cc_pair_close(cc_pair *p)
{
    tb_world_destroy(p->b2);
    ts_tether_free(&p->tt);
    ts_scene_free(&p->scene);
    free(p->t_tt);
    free(p->t_b2);
    memset(p, 0, sizeof *p);
}
