/* tether — the accuracy measures beside every bench figure: overlap by a
 * grid over the particles (O(n), so 1 M particles can be measured every
 * step), link strain, kinetic energy per kg and energy drift. */
#include "bench_accuracy.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void bench_acc_init(bench_acc *a, tt_world *w, unsigned what, const tt_constraint *links, unsigned nlinks)
{
    memset(a, 0, sizeof *a);
    a->what = what;
    a->n = tt_world_particle_count(w);
    tt_particle *ps = malloc((a->n + 1) * sizeof *ps);
    a->r = malloc((a->n + 1) * sizeof *a->r);
    a->xy = malloc(2 * (a->n + 1) * sizeof *a->xy);
    tt_world_list_particles(w, ps, a->n);
    for (unsigned i = 0; i < a->n; i++) {
        tt_particle_get_radius(w, ps[i], &a->r[i]);
        double m = 0;
        bool pinned = false;
        tt_particle_get_mass(w, ps[i], &m);
        tt_particle_get_pinned(w, ps[i], &pinned);
        if (!pinned) a->mass += m;
    }
    free(ps);
    if (links && nlinks) {
        a->nlinks = nlinks;
        a->links = malloc(nlinks * sizeof *a->links);
        a->rest = malloc(nlinks * sizeof *a->rest);
        memcpy(a->links, links, nlinks * sizeof *links);
        for (unsigned i = 0; i < nlinks; i++) tt_distance_get_length(w, links[i], &a->rest[i]);
    }
    tt_energy e;
    tt_world_get_energy(w, &e);
    a->e_first = a->e_prev = e.total;
}

/* Cells as wide as the largest diameter: a circle's neighbours are in its
 * own and the 8 around it. Sorting cell keys keeps it allocation-light. */
typedef struct { unsigned long long key; unsigned i; } cell_item;

static int by_key(const void *p, const void *q)
{
    const cell_item *a = p, *b = q;
    return (a->key > b->key) - (a->key < b->key);
}

static unsigned long long key_of(long long cx, long long cy)
{
    return ((unsigned long long)(cx + (1LL << 31)) << 32) | (unsigned long long)(cy + (1LL << 31));
}

static long find(const cell_item *c, unsigned n, unsigned long long key)
{
    long lo = 0, hi = (long)n;
    while (lo < hi) {
        long mid = (lo + hi) / 2;
        if (c[mid].key < key) lo = mid + 1; else hi = mid;
    }
    return lo < (long)n && c[lo].key == key ? lo : -1;
}

static void overlaps(bench_acc *a, tt_world *w)
{
    const unsigned n = tt_world_read_positions(w, a->xy, a->n);
    double rmax = 0;
    for (unsigned i = 0; i < n; i++) rmax = fmax(rmax, a->r[i]);
    if (n < 2 || !(rmax > 0)) return;
    const double cell = 2 * rmax;
    cell_item *c = malloc(n * sizeof *c);
    for (unsigned i = 0; i < n; i++)
        c[i] = (cell_item){key_of((long long)floor(a->xy[2 * i] / cell), (long long)floor(a->xy[2 * i + 1] / cell)), i};
    qsort(c, n, sizeof *c, by_key);
    double deepest = 0, sum = 0;
    unsigned long pairs = 0;
    for (unsigned k = 0; k < n; k++) {
        const unsigned i = c[k].i;
        const long long cx = (long long)floor(a->xy[2 * i] / cell), cy = (long long)floor(a->xy[2 * i + 1] / cell);
        for (int dx = -1; dx <= 1; dx++)
            for (int dy = -1; dy <= 1; dy++) {
                long at = find(c, n, key_of(cx + dx, cy + dy));
                for (; at >= 0 && at < (long)n && c[at].key == key_of(cx + dx, cy + dy); at++) {
                    const unsigned j = c[at].i;
                    if (j <= i) continue;
                    const double ex = a->xy[2 * j] - a->xy[2 * i], ey = a->xy[2 * j + 1] - a->xy[2 * i + 1];
                    const double rr = a->r[i] + a->r[j], d2 = ex * ex + ey * ey;
                    if (d2 >= rr * rr) continue;
                    const double depth = (rr - sqrt(d2)) / fmin(a->r[i], a->r[j]);
                    deepest = fmax(deepest, depth);
                    sum += depth;
                    pairs++;
                }
            }
    }
    free(c);
    a->max_overlap = fmax(a->max_overlap, deepest);
    a->mean_overlap += pairs ? sum / (double)pairs : 0;
}

static void strains(bench_acc *a, tt_world *w)
{
    double sum = 0;
    for (unsigned k = 0; k < a->nlinks; k++) {
        tt_particle ps[2];
        uint32_t m;
        tt_constraint_get_particles(w, a->links[k], ps, 2, &m);
        tt_vec2 p, q;
        tt_particle_get_position(w, ps[0], &p);
        tt_particle_get_position(w, ps[1], &q);
        const double s = a->rest[k] > 0 ? fabs(hypot(p.x - q.x, p.y - q.y) / a->rest[k] - 1) : 0;
        sum += s;
        a->strain_max = fmax(a->strain_max, s);
    }
    if (a->nlinks) a->strain_mean = fmax(a->strain_mean, sum / a->nlinks);
}

void bench_acc_step(bench_acc *a, tt_world *w)
{
    a->steps++;
    if (a->what & ACC_OVERLAP) overlaps(a, w);
    if (a->what & ACC_STRETCH) strains(a, w);
    tt_energy e;
    tt_world_get_energy(w, &e);
    a->ke_per_kg = a->mass > 0 ? e.kinetic / a->mass : 0;
    /* the scale a rise is measured against: the energy the scene moves
     * between its stores, so a total near zero does not magnify noise */
    const double scale = fabs(e.kinetic) + fabs(e.gravity) + fabs(e.spring) + fabs(e.constraint) + fabs(e.attractor);
    a->e_scale = fmax(a->e_scale, scale);
    if (a->what & ACC_ENERGY && a->e_scale > 0) a->worst_rise = fmax(a->worst_rise, (e.total - a->e_prev) / a->e_scale);
    a->e_prev = a->e_last = e.total;
}

void bench_acc_free(bench_acc *a)
{
    free(a->r);
    free(a->xy);
    free(a->links);
    free(a->rest);
    memset(a, 0, sizeof *a);
}

const char *bench_acc_flags(const bench_acc *a, char *buf, size_t n)
{
    buf[0] = 0;
    if ((a->what & ACC_OVERLAP) && a->max_overlap > ACC_MAX_OVERLAP) strncat(buf, "COLLAPSE ", n - strlen(buf) - 1);
    if ((a->what & ACC_STRETCH) && a->strain_mean > ACC_MEAN_STRAIN) strncat(buf, "STRETCH ", n - strlen(buf) - 1);
    if ((a->what & ACC_ENERGY) && a->worst_rise > ACC_ENERGY_RISE) strncat(buf, "ENERGY+ ", n - strlen(buf) - 1);
    size_t len = strlen(buf);
    if (len) buf[len - 1] = 0; else snprintf(buf, n, "ok");
    return buf;
}

void bench_acc_head(void)
{
    printf("   accuracy over the whole run (%%r: of a radius; flags: max overlap > %.0f %%r, mean |strain| > %.0f %%, energy up > %.0f %% in a step)\n",
           100 * ACC_MAX_OVERLAP, 100 * ACC_MEAN_STRAIN, 100 * ACC_ENERGY_RISE);
}

static void fmt(char *b, size_t n, bool on, const char *f, double v)
{
    if (on) snprintf(b, n, f, v); else snprintf(b, n, "-");
}

void bench_acc_print(const bench_acc *a)
{
    char mo[32], me[32], sm[32], sx[32], dr[32], fl[64];
    fmt(mo, sizeof mo, a->what & ACC_OVERLAP, "%.1f%%r", 100 * a->max_overlap);
    fmt(me, sizeof me, a->what & ACC_OVERLAP, "%.2f%%r", a->steps ? 100 * a->mean_overlap / a->steps : 0);
    fmt(sm, sizeof sm, a->what & ACC_STRETCH, "%.3f%%", 100 * a->strain_mean);
    fmt(sx, sizeof sx, a->what & ACC_STRETCH, "%.2f%%", 100 * a->strain_max);
    fmt(dr, sizeof dr, a->what & ACC_ENERGY, "%+.2f%%", 100 * a->worst_rise);
    printf("   -> overlap max %s mean %s | KE %.2e J/kg | strain mean %s max %s | worst step energy rise %s | %s\n", mo, me,
           a->ke_per_kg, sm, sx, dr, bench_acc_flags(a, fl, sizeof fl));
}

void bench_acc_csv(FILE *f, const bench_acc *a)
{
    char fl[64];
    const double drift = a->e_scale > 0 ? (a->e_last - a->e_first) / a->e_scale : 0;
    fprintf(f, "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%s", a->what & ACC_OVERLAP ? a->max_overlap : NAN,
            a->what & ACC_OVERLAP && a->steps ? a->mean_overlap / a->steps : NAN, a->ke_per_kg,
            a->what & ACC_STRETCH ? a->strain_mean : NAN, a->what & ACC_STRETCH ? a->strain_max : NAN, drift,
            a->what & ACC_ENERGY ? a->worst_rise : NAN, bench_acc_flags(a, fl, sizeof fl));
}

tt_constraint *bench_acc_composite_links(const tt_world *w, tt_composite c, unsigned *n)
{
    uint32_t nc = 0;
    tt_composite_get_constraints(w, c, NULL, 0, &nc);
    tt_constraint *cs = malloc((nc + 1) * sizeof *cs);
    tt_composite_get_constraints(w, c, cs, nc, &nc);
    unsigned k = 0;
    for (uint32_t i = 0; i < nc; i++) {
        tt_constraint_kind kind;
        if (tt_constraint_get_kind(w, cs[i], &kind) == TT_OK && kind == TT_CONSTRAINT_DISTANCE) cs[k++] = cs[i];
    }
    *n = k;
    return cs;
}
