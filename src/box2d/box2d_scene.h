/* tether — scene descriptions (src/scenes/) built in Box2D, and the
 * cross-check that runs each named scene in both engines. */
#ifndef TETHER_BOX2D_SCENE_H
#define TETHER_BOX2D_SCENE_H

#include "box2d/box2d_bridge.h"
#include "scenes/scene.h"

#include <stdio.h>

/* Builds s in a new Box2D world with def's iterations, sleeping and
 * continuous physics (gravity is the scene's); NULL with *why on failure. */
tb_world *tb_scene_build(const ts_scene *s, const tb_world_def *def, const char **why);
bool tb_scene_state(const tb_world *w, uint32_t body, ts_state *out);
double tb_scene_kinetic_per_kg(const tb_world *w);

/* --- the cross-check (crosscheck.c, crosscheck_scenes.c) ------------------ */

#define CC_MAX_ROWS 128

/* One line of the table: a measure in both engines. */
typedef struct cc_row {
    char scene[16];
    char measure[48];
    char setting[24];   /* tether's substeps × iterations (and lattice), or "" */
    double expected;    /* the analytic answer, NAN when there is none */
    double box2d, tether;
    char unit[8];
} cc_row;

/* Cost of one scene in both engines: ms per step, timing only the step. */
typedef struct cc_cost {
    char scene[16], setting[48];
    double box2d_med, box2d_min, box2d_max;
    double tether_med, tether_min, tether_max;
    int runs, steps;
} cc_cost;

typedef struct cc_report {
    cc_row rows[CC_MAX_ROWS];
    int nrows;
    cc_cost costs[16];
    int ncosts;
    bool quick;
    int runs;            /* timed runs of each small scene */
    ts_tether_settings small; /* tether's setting for the seven small scenes; default 1 × 8, lattice 4 */
} cc_report;

double cc_now_ms(void);
/* Adds a row and returns it (NULL when the table is full). */
cc_row *cc_add(cc_report *r, const char *scene, const char *measure, const char *unit);
cc_cost *cc_add_cost(cc_report *r, const char *scene, const char *setting);
/* Runs the named scene (or every scene for NULL / "all") into r; false on an
 * unknown name or a failure, with the reason in *why. */
bool cc_run(cc_report *r, const char *scene, const char **why);
/* Prints the tables and writes crosscheck.csv and crosscheck.md into dir
 * (may be NULL); load_before: the load average when the run began. */
void cc_print(const cc_report *r, FILE *out, const char *dir, const char *load_before);
/* The load average, "1min 5min 15min", into buf. */
void cc_load(char *buf, size_t n);
/* The command line: crosscheck [--quick] [--out DIR] [SCENE]; an exit status. */
int tb_crosscheck_main(int argc, char **argv);

/* The scenes, each filling rows and costs (crosscheck_scenes.c, crosscheck_pour.c). */
bool cc_fall(cc_report *r, const char **why);
bool cc_pendulum(cc_report *r, const char **why);
bool cc_bounce(cc_report *r, const char **why);
bool cc_slope(cc_report *r, const char **why);
bool cc_spin(cc_report *r, const char **why);
bool cc_pyramid(cc_report *r, const char **why);
bool cc_discs(cc_report *r, const char **why);
bool cc_pour(cc_report *r, const char **why);

/* Both engines built from one scene, stepped in turns with each step timed. */
typedef struct cc_pair {
    ts_scene scene;
    ts_tether tt;
    tb_world *b2;
    double *t_tt, *t_b2; /* ms of each step */
    int steps_done;
} cc_pair;
/* The pair works on its own copy of s. */
bool cc_pair_open(cc_pair *p, const ts_scene *s, const ts_tether_settings *set, const tb_world_def *def, const char **why);
/* Steps both engines `steps` times, alternating blocks of `block` steps. */
bool cc_pair_step(cc_pair *p, int steps, int block, const char **why);
void cc_pair_close(cc_pair *p);
/* Called after every step of a probed run. */
typedef void (*cc_probe)(const cc_pair *p, int step, void *ctx);
/* Runs s (r->runs times when timed, else once; the first run probed after
 * every step), the engines alternating step by step; when timed, adds the
 * cost: median and range of the runs' mean ms/step. */
bool cc_run_small(cc_report *r, const ts_scene *s, bool timed, cc_probe probe, void *ctx, const char **why);
/* Adds a row measured at r->small. */
void cc_put(cc_report *r, const char *scene, const char *measure, const char *unit, double expected, double b2, double tt);
/* Median, min and max of v[0..n) (sorted in place). */
void cc_stats(double *v, int n, double *med, double *lo, double *hi);

#endif
