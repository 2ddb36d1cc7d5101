/* tether — the cross-check's front: which scenes run, the command line,
 * and the tables: measures (expected, Box2D, tether, their difference,
 * each engine's error against the analytic answer) and costs (ms per step,
 * timing only the step, and the ratio). */
#include "box2d_scene.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef bool (*cc_scene_fn)(cc_report *, const char **);
static const struct {
    const char *name;
    cc_scene_fn fn;
} scenes[] = {{"fall", cc_fall},   {"pendulum", cc_pendulum}, {"bounce", cc_bounce}, {"slope", cc_slope},
              {"spin", cc_spin},   {"pyramid", cc_pyramid},   {"discs", cc_discs},       {"pour", cc_pour}};

bool cc_run(cc_report *r, const char *scene, const char **why)
{
    const bool all = !scene || !strcmp(scene, "all");
    bool found = false;
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        if (!all && strcmp(scene, scenes[i].name)) continue;
        found = true;
        if (!scenes[i].fn(r, why)) return false;
    }
    if (!found) *why = "unknown scene (fall, pendulum, bounce, slope, spin, pyramid, discs, pour, all)";
    return found;
}

static void fmt(char *buf, size_t n, double v)
{
    if (isnan(v)) snprintf(buf, n, "-");
    else if (v != 0 && (fabs(v) < 1e-3 || fabs(v) >= 1e5)) snprintf(buf, n, "%.2e", v);
    else snprintf(buf, n, "%.4g", v);
}

/* One measure as text: expected, Box2D, tether, difference, the two errors. */
static void row_cells(const cc_row *w, char c[6][24])
{
    fmt(c[0], 24, w->expected);
    fmt(c[1], 24, w->box2d);
    fmt(c[2], 24, w->tether);
    fmt(c[3], 24, w->tether - w->box2d);
    if (!isnan(w->expected) && w->expected != 0 && !isnan(w->box2d)) snprintf(c[4], 24, "%+.2f %%", 100 * (w->box2d - w->expected) / fabs(w->expected));
    else snprintf(c[4], 24, "-");
    if (!isnan(w->expected) && w->expected != 0 && !isnan(w->tether)) snprintf(c[5], 24, "%+.2f %%", 100 * (w->tether - w->expected) / fabs(w->expected));
    else snprintf(c[5], 24, "-");
}

static void cost_cells(const cc_cost *c, char out[3][48])
{
    snprintf(out[0], 48, "%.3f (%.3f-%.3f)", c->box2d_med, c->box2d_min, c->box2d_max);
    if (isnan(c->tether_med)) snprintf(out[1], 48, "-");
    else snprintf(out[1], 48, "%.3f (%.3f-%.3f)", c->tether_med, c->tether_min, c->tether_max);
    if (isnan(c->tether_med)) snprintf(out[2], 48, "-");
    else snprintf(out[2], 48, "%.2fx", c->box2d_med / c->tether_med);
}

void cc_load(char *buf, size_t n)
{
    FILE *f = fopen("/proc/loadavg", "r");
    double a = NAN, b = NAN, c = NAN;
    if (f) {
        if (fscanf(f, "%lf %lf %lf", &a, &b, &c) != 3) a = NAN;
        fclose(f);
    }
    snprintf(buf, n, "%.2f %.2f %.2f", a, b, c);
}

static void print_terminal(const cc_report *r, FILE *out)
{
    fprintf(out, "%-9s %-34s %-15s %10s %10s %10s %10s %10s %10s %s\n", "scene", "measure", "tether at", "expected", "Box2D",
            "tether", "difference", "Box2D err", "tether err", "unit");
    for (int i = 0; i < r->nrows; i++) {
        const cc_row *w = &r->rows[i];
        char c[6][24];
        row_cells(w, c);
        fprintf(out, "%-9s %-34s %-15s %10s %10s %10s %10s %10s %10s %s\n", w->scene, w->measure, w->setting, c[0], c[1], c[2], c[3],
                c[4], c[5], w->unit);
    }
    fprintf(out, "\n%-9s %-38s %-26s %-26s %8s %s\n", "scene", "setting", "Box2D ms/step", "tether ms/step", "ratio", "runs x steps");
    for (int i = 0; i < r->ncosts; i++) {
        const cc_cost *c = &r->costs[i];
        char t[3][48];
        cost_cells(c, t);
        fprintf(out, "%-9s %-38s %-26s %-26s %8s %d x %d\n", c->scene, c->setting, t[0], t[1], t[2], c->runs, c->steps);
    }
}

static FILE *open_in(const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) fprintf(stderr, "crosscheck: cannot write %s: %s\n", path, strerror(errno));
    return f;
}

static void write_files(const cc_report *r, const char *dir, const char *load_before, const char *load_after)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "crosscheck: cannot make %s: %s\n", dir, strerror(errno));
        return;
    }
    FILE *csv = open_in(dir, "crosscheck.csv"), *md = open_in(dir, "crosscheck.md");
    if (csv) fprintf(csv, "scene,measure,setting,expected,box2d,tether,unit\n");
    if (md)
        fprintf(md, "Load average before / after: %s / %s%s\n\n| scene | measure | tether at | expected | Box2D | tether | difference | Box2D err | tether err | unit |\n"
                    "|---|---|---|---|---|---|---|---|---|---|\n", load_before, load_after, r->quick ? " (quick)" : "");
    for (int i = 0; i < r->nrows; i++) {
        const cc_row *w = &r->rows[i];
        char c[6][24];
        row_cells(w, c);
        if (csv) fprintf(csv, "%s,%s,%s,%.9g,%.9g,%.9g,%s\n", w->scene, w->measure, w->setting, w->expected, w->box2d, w->tether, w->unit);
        if (md) fprintf(md, "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", w->scene, w->measure, w->setting, c[0], c[1], c[2], c[3], c[4], c[5], w->unit);
    }
    if (md) fprintf(md, "\n| scene | setting | Box2D ms/step | tether ms/step | ratio | runs x steps |\n|---|---|---|---|---|---|\n");
    if (csv) fprintf(csv, "\nscene,setting,box2d_ms_median,box2d_ms_min,box2d_ms_max,tether_ms_median,tether_ms_min,tether_ms_max,runs,steps\n");
    for (int i = 0; i < r->ncosts; i++) {
        const cc_cost *c = &r->costs[i];
        char t[3][48];
        cost_cells(c, t);
        if (md) fprintf(md, "| %s | %s | %s | %s | %s | %d x %d |\n", c->scene, c->setting, t[0], t[1], t[2], c->runs, c->steps);
        if (csv)
            fprintf(csv, "%s,%s,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%d,%d\n", c->scene, c->setting, c->box2d_med, c->box2d_min, c->box2d_max,
                    c->tether_med, c->tether_min, c->tether_max, c->runs, c->steps);
    }
    if (csv) fclose(csv);
    if (md) fclose(md);
    printf("crosscheck: %s/crosscheck.csv, %s/crosscheck.md\n", dir, dir);
}

void cc_print(const cc_report *r, FILE *out, const char *dir, const char *load_before)
{
    char after[64];
    cc_load(after, sizeof after);
    print_terminal(r, out);
    fprintf(out, "load average (1, 5, 15 min) before: %s, after: %s; 2 shared cores%s\n", load_before, after,
            r->quick ? "; quick mode (smaller pour, fewer runs)" : "");
    if (dir) write_files(r, dir, load_before, after);
}

static int usage(FILE *f, int status)
{
    fprintf(f, "usage: tether crosscheck [--quick] [--runs N] [--tether SxI] [--lattice N] [--anchored] [--out DIR] [SCENE]\n"
               "Runs SCENE (fall, pendulum, bounce, slope, spin, pyramid, discs, pour; default all) in tether and in\n"
               "Box2D 2.4.1 and prints the comparison; --out DIR also writes crosscheck.csv and crosscheck.md.\n"
               "--quick: the 1 000-circle pour and 2 timed runs (for tests); --runs N: timed runs of each small scene (1..50, default 5);\n"
               "--tether SxI: tether's substeps x iterations in the small scenes (default 1x8); --lattice N: particles along a box's\n"
               "shorter side (2..64, default 4); --anchored: tether's small scenes with anchored friction between particles.\n"
               "The pour always runs its own list of settings.\n");
    return status;
}

int tb_crosscheck_main(int argc, char **argv)
{
    cc_report *r = calloc(1, sizeof *r);
    const char *scene = NULL, *dir = NULL, *why = "";
    if (!r) return fprintf(stderr, "crosscheck: out of memory\n"), 1;
    r->runs = 5;
    r->small = ts_tether_settings_default();
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--quick")) r->quick = true, r->runs = 2;
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) dir = argv[++i];
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc) r->runs = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--tether") && i + 1 < argc) {
            if (sscanf(argv[++i], "%ux%u", &r->small.substeps, &r->small.iterations) != 2) return free(r), usage(stderr, 2);
        } else if (!strcmp(argv[i], "--lattice") && i + 1 < argc) r->small.lattice = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--anchored")) r->small.anchored = true;
        else if (!strcmp(argv[i], "--help")) return free(r), usage(stdout, 0);
        else if (argv[i][0] == '-' || scene) return free(r), usage(stderr, 2);
        else scene = argv[i];
    }
    if (r->runs < 1 || r->runs > 50) return free(r), usage(stderr, 2);
    char before[64];
    cc_load(before, sizeof before);
    const bool good = cc_run(r, scene, &why);
    if (good) cc_print(r, stdout, dir, before);
    else fprintf(stderr, "crosscheck: %s\n", why);
    free(r);
    return good ? 0 : 1;
}
