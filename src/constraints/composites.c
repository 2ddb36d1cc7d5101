/* tether — composites: rope, cloth, ragdoll, soft body and lattice body, made
 * of particles and constraints through the public calls, and kept under one
 * generational handle so a script can read them back, move them as one
 * (centre of mass, orientation) and remove them. */
#include "constraint_internal.h"

#include <stdlib.h>
#include <string.h>

#define NONE ((tt_composite){0, 0})

/* ---- building ------------------------------------------------------------ */

/* A builder places every particle first and checks them all (and that they
 * fit) before it makes the first, so bad input changes nothing. Running out
 * of memory half way is undone whole: what was made is removed and the pools
 * are put back, so the next handles are those of a world that never saw the
 * call. */
typedef struct spot {
    tt_vec2 at;
    bool pinned;
} spot;

typedef struct builder {
    tt_world *w;
    const char *fn;
    tt__composite c;
    tt_composite_common k;
    spot *spots;            /* where each particle goes, in order */
    uint32_t nspots;
    /* the world before its first change, for undo */
    tt_pool_mark pmark, cmark;
    uint32_t fresh_count;
    bool had_group;         /* the constraint group was there before */
    bool failed;
} builder;

static tt_result check_common(tt_world *w, const tt_composite_common *k, const char *fn)
{
    if (!tt__in_range(k->mass, TT_MIN_MASS, TT_MAX_MASS))
        return tt__fail(w, TT_EINVAL, "%s: mass must be in [%g, %g] kg, got %g", fn, TT_MIN_MASS, TT_MAX_MASS, k->mass);
    if (!tt__in_range(k->radius, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "%s: radius must be in [0, %g], got %g", fn, TT_MAX_VALUE, k->radius);
    if (!tt__in_range(k->stiffness, 0.0, 1.0))
        return tt__fail(w, TT_EINVAL, "%s: stiffness must be in [0, 1], got %g", fn, k->stiffness);
    if (!tt__in_range(k->compliance, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "%s: compliance must be in [0, %g], got %g", fn, TT_MAX_VALUE, k->compliance);
    return TT_OK;
}

static void release(builder *b)
{
    free(b->spots);
    free(b->c.parts);
    free(b->c.cons);
    free(b->c.rest);
}

/* The builder's own memory; the world is not touched yet. */
static bool begin(builder *b, tt_world *w, const tt_composite_common *k, uint32_t particles, const char *fn)
{
    memset(b, 0, sizeof *b);
    b->w = w;
    b->fn = fn;
    b->k = *k;
    b->spots = malloc((size_t)particles * sizeof *b->spots);
    b->c.parts = malloc((size_t)particles * sizeof *b->c.parts);
    b->c.rest = malloc((size_t)particles * 2 * sizeof(double));
    if (!b->spots || !b->c.parts || !b->c.rest) {
        release(b);
        tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        return false;
    }
    return true;
}

static void place(builder *b, double x, double y, bool pinned)
{
    b->spots[b->nspots++] = (spot){{x, y}, pinned};
}

/* Undoes everything made since spawn began changing the world. */
static void undo(builder *b)
{
    tt_world *w = b->w;
    for (uint32_t i = 0; i < b->c.nc; i++)
        if (tt_constraint_is_valid(w, b->c.cons[i])) tt_constraint_destroy(w, b->c.cons[i]);
    for (uint32_t i = 0; i < b->c.np; i++) tt_particle_destroy(w, b->c.parts[i]);
    /* removal bumped generations and reordered free lists: put both back */
    tt__cgroup *g = tt__cgroup_get(w, false);
    if (g) {
        for (uint32_t i = 0; i < b->c.nc; i++) tt_pool_unalloc(&g->pool, b->cmark, i, b->c.cons[i].index, b->c.cons[i].gen);
        tt_pool_rewind(&g->pool, b->cmark);
    }
    for (uint32_t i = 0; i < b->c.np; i++) tt_pool_unalloc(&w->ppool, b->pmark, i, b->c.parts[i].index, b->c.parts[i].gen);
    tt_pool_rewind(&w->ppool, b->pmark);
    w->fresh_count = b->fresh_count;
    tt__cgroup_unmake(w, b->had_group);
    release(b);
}

/* Room for the composite's record, made before anything else so it cannot fail last. */
static bool reserve_record(tt__cgroup *g)
{
    uint32_t need = g->cpool.free_count ? g->cpool.count : g->cpool.count + 1;
    if (need <= g->comp_cap) return true;
    uint32_t cap = g->comp_cap ? g->comp_cap * 2 : 16;
    tt__composite *q = realloc(g->comps, (size_t)cap * sizeof *q);
    if (!q) return false;
    g->comps = q;
    g->comp_cap = cap;
    return true;
}

/* Checks every placed particle, then makes them all; false (and nothing left
 * behind) when one is out of range, they do not fit, or memory runs out. */
static bool spawn(builder *b)
{
    tt_world *w = b->w;
    for (uint32_t i = 0; i < b->nspots; i++)
        if (!tt__vec_ok(b->spots[i].at)) {
            tt__fail(w, TT_EINVAL, "%s: particle %u would be at (%.17g, %.17g), past the largest coordinate %g", b->fn, i,
                     b->spots[i].at.x, b->spots[i].at.y, TT_MAX_VALUE);
            release(b);
            return false;
        }
    if (b->nspots > tt__particle_room(w)) {
        tt__fail(w, TT_ENOMEM, "%s: the world is full (max_particles %u)", b->fn, w->max_particles);
        release(b);
        return false;
    }
    b->pmark = tt_pool_mark_now(&w->ppool);
    b->fresh_count = w->fresh_count;
    b->had_group = tt__cgroup_peek(w) != NULL;
    tt__cgroup *g = tt__cgroup_get(w, true); /* made here, it starts empty: a mark like any other */
    if (g) b->cmark = tt_pool_mark_now(&g->pool);
    if (!g || !reserve_record(g)) {
        tt__fail(w, TT_ENOMEM, "%s: out of memory", b->fn);
        undo(b);
        return false;
    }
    tt_particle_def pd = tt_particle_def_default();
    pd.mass = b->k.mass;
    pd.radius = b->k.radius;
    for (uint32_t i = 0; i < b->nspots; i++) {
        pd.position = b->spots[i].at;
        pd.pinned = b->spots[i].pinned;
        tt_particle p = tt_particle_create(w, &pd);
        if (p.gen == 0) { /* out of memory: tt_particle_create said so */
            undo(b);
            return false;
        }
        b->c.parts[b->c.np++] = p;
    }
    return true;
}

/* Room for one more constraint handle, made before the constraint so every
 * constraint made is on the list undo walks. */
static bool con_room(builder *b)
{
    if (b->failed) return false;
    if (b->c.nc < b->c.ccap) return true;
    uint32_t cap = b->c.ccap ? b->c.ccap * 2 : 32;
    tt_constraint *q = realloc(b->c.cons, (size_t)cap * sizeof *q);
    if (!q) {
        tt__fail(b->w, TT_ENOMEM, "%s: out of memory", b->fn);
        b->failed = true;
        return false;
    }
    b->c.cons = q;
    b->c.ccap = cap;
    return true;
}

static void add_constraint(builder *b, tt_constraint h)
{
    if (h.gen == 0) b->failed = true; /* out of memory: the create call said so */
    else b->c.cons[b->c.nc++] = h;
}

/* A distance link between builder particles i and j. */
static void link(builder *b, uint32_t i, uint32_t j, double stiffness, tt_distance_mode mode, double break_strain)
{
    if (!con_room(b)) return;
    tt_distance_def d = tt_distance_def_default();
    d.a = b->c.parts[i];
    d.b = b->c.parts[j];
    d.mode = mode;
    d.stiffness = stiffness;
    d.compliance = b->k.compliance;
    d.collide = b->k.collide;
    d.break_strain = break_strain;
    add_constraint(b, tt_distance_create(b->w, &d));
}

static void limit(builder *b, uint32_t i, uint32_t j, uint32_t k, double lo, double hi)
{
    if (!con_room(b)) return;
    tt_angle_def d = tt_angle_def_default();
    d.a = b->c.parts[i];
    d.b = b->c.parts[j];
    d.c = b->c.parts[k];
    d.use_current = false;
    d.min = lo;
    d.max = hi;
    d.stiffness = b->k.stiffness;
    add_constraint(b, tt_angle_create(b->w, &d));
}

/* Stores the composite (or undoes everything when a step failed). */
static tt_composite finish(builder *b)
{
    tt_world *w = b->w;
    tt__cgroup *g = tt__cgroup_get(w, false);
    bool grew;
    uint32_t s = b->failed ? UINT32_MAX : tt_pool_alloc(&g->cpool, UINT32_MAX - 1, &grew);
    if (s == UINT32_MAX) {
        if (!b->failed) tt__fail(w, TT_ENOMEM, "%s: out of memory", b->fn);
        undo(b);
        return NONE;
    }
    /* rest shape: offsets from the centre of mass as made */
    double m = 0, cx = 0, cy = 0;
    for (uint32_t i = 0; i < b->c.np; i++) {
        uint32_t p = b->c.parts[i].index;
        m += w->mass[p];
        cx += w->mass[p] * w->px[p];
        cy += w->mass[p] * w->py[p];
    }
    cx /= m;
    cy /= m;
    for (uint32_t i = 0; i < b->c.np; i++) {
        uint32_t p = b->c.parts[i].index;
        b->c.rest[2 * i] = w->px[p] - cx;
        b->c.rest[2 * i + 1] = w->py[p] - cy;
    }
    free(b->spots);
    b->c.alive = true;
    g->comps[s] = b->c;
    g->comps_alive++;
    return (tt_composite){s, g->cpool.gen[s]};
}

/* ---- defaults -------------------------------------------------------------- */

static tt_composite_common common_default(void)
{
    tt_composite_common k;
    memset(&k, 0, sizeof k);
    k.mass = 1.0;
    k.stiffness = 1.0;
    return k;
}

tt_rope_def tt_rope_def_default(void)
{
    tt_rope_def d;
    memset(&d, 0, sizeof d);
    d.common = common_default();
    d.end = (tt_vec2){1, 0};
    d.segments = 10;
    d.pin_start = true;
    return d;
}

tt_cloth_def tt_cloth_def_default(void)
{
    tt_cloth_def d;
    memset(&d, 0, sizeof d);
    d.common = common_default();
    d.width = d.height = 1.0;
    d.columns = d.rows = 16;
    d.shear_stiffness = 1.0;
    d.bend_stiffness = 0.5;
    d.pin_top_corners = true;
    return d;
}

tt_ragdoll_def tt_ragdoll_def_default(void)
{
    tt_ragdoll_def d;
    memset(&d, 0, sizeof d);
    d.common = common_default();
    d.height = 1.8;
    d.limits = true;
    return d;
}

tt_soft_body_def tt_soft_body_def_default(void)
{
    tt_soft_body_def d;
    memset(&d, 0, sizeof d);
    d.common = common_default();
    d.radius = 1.0;
    d.segments = 16;
    d.pressure = 1.0;
    d.area_stiffness = 1.0;
    return d;
}

tt_lattice_def tt_lattice_def_default(void)
{
    tt_lattice_def d;
    memset(&d, 0, sizeof d);
    d.common = common_default();
    d.width = d.height = 1.0;
    d.columns = d.rows = 2;
    return d;
}

/* ---- the five builders ------------------------------------------------------- */

#define START(fn)                                                                         \
    if (!w) { tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn); return NONE; }          \
    if (!d) { tt__fail(w, TT_EINVAL, "%s: def is NULL", fn); return NONE; }               \
    if (check_common(w, &d->common, fn) != TT_OK) return NONE

static bool positive(tt_world *w, double v, const char *fn, const char *what)
{
    if (v > 0.0 && v <= TT_MAX_VALUE) return true;
    tt__fail(w, TT_EINVAL, "%s: %s must be in (0, %g], got %g", fn, what, TT_MAX_VALUE, v);
    return false;
}

static bool unit(tt_world *w, double v, const char *fn, const char *what)
{
    if (tt__in_range(v, 0.0, 1.0)) return true;
    tt__fail(w, TT_EINVAL, "%s: %s must be in [0, 1], got %g", fn, what, v);
    return false;
}

static bool strain_ok(tt_world *w, double v, const char *fn)
{
    if (tt__in_range(v, 0.0, TT_MAX_VALUE)) return true;
    tt__fail(w, TT_EINVAL, "%s: break_strain must be in [0, %g] (0 = never), got %g", fn, TT_MAX_VALUE, v);
    return false;
}

tt_composite tt_rope_create(tt_world *w, const tt_rope_def *d)
{
    const char *fn = "tt_rope_create";
    START(fn);
    if (!tt__vec_ok(d->start) || !tt__vec_ok(d->end)) { tt__fail(w, TT_EINVAL, "%s: start and end must be finite", fn); return NONE; }
    if (d->segments < 1 || d->segments > 100000) { tt__fail(w, TT_EINVAL, "%s: segments must be in [1, 100000], got %u", fn, d->segments); return NONE; }
    if (!strain_ok(w, d->break_strain, fn)) return NONE;
    builder b;
    if (!begin(&b, w, &d->common, d->segments + 1, fn)) return NONE;
    for (uint32_t i = 0; i <= d->segments; i++) {
        double t = (double)i / d->segments;
        place(&b, d->start.x + (d->end.x - d->start.x) * t, d->start.y + (d->end.y - d->start.y) * t,
              (i == 0 && d->pin_start) || (i == d->segments && d->pin_end));
    }
    if (!spawn(&b)) return NONE;
    for (uint32_t i = 0; i < d->segments; i++)
        link(&b, i, i + 1, d->common.stiffness, d->slack ? TT_DISTANCE_MAX : TT_DISTANCE_RIGID, d->break_strain);
    return finish(&b);
}

tt_composite tt_cloth_create(tt_world *w, const tt_cloth_def *d)
{
    const char *fn = "tt_cloth_create";
    START(fn);
    if (!tt__vec_ok(d->origin)) { tt__fail(w, TT_EINVAL, "%s: origin must be finite", fn); return NONE; }
    if (!positive(w, d->width, fn, "width") || !positive(w, d->height, fn, "height")) return NONE;
    if (d->columns < 2 || d->columns > 4096 || d->rows < 2 || d->rows > 4096) {
        tt__fail(w, TT_EINVAL, "%s: columns and rows must be in [2, 4096], got %u x %u", fn, d->columns, d->rows);
        return NONE;
    }
    if (!unit(w, d->shear_stiffness, fn, "shear_stiffness") || !unit(w, d->bend_stiffness, fn, "bend_stiffness") ||
        !strain_ok(w, d->break_strain, fn))
        return NONE;
    const uint32_t C = d->columns, R = d->rows;
    builder b;
    if (!begin(&b, w, &d->common, C * R, fn)) return NONE;
    const double sx = d->width / (C - 1), sy = d->height / (R - 1);
    for (uint32_t r = 0; r < R; r++)
        for (uint32_t c = 0; c < C; c++) {
            bool pin = r == 0 && (d->pin_top_row || (d->pin_top_corners && (c == 0 || c == C - 1)));
            place(&b, d->origin.x + c * sx, d->origin.y - r * sy, pin);
        }
    if (!spawn(&b)) return NONE;
#define P(r, c) ((r) * C + (c))
    const double ks = d->common.stiffness, bs = d->break_strain;
    /* Links are made in passes whose members share no particle (red-black
     * order): consecutive Gauss-Seidel corrections are then independent and
     * the processor overlaps them (measured on a 128² cloth: 9.5 → 6.0 ms
     * per step at 10 sweeps, against row-major order). */
    for (uint32_t pass = 0; pass < 2; pass++) /* structural, horizontal */
        for (uint32_t r = 0; r < R; r++)
            for (uint32_t c = pass; c + 1 < C; c += 2) link(&b, P(r, c), P(r, c + 1), ks, TT_DISTANCE_RIGID, bs);
    for (uint32_t pass = 0; pass < 2; pass++) /* structural, vertical */
        for (uint32_t r = pass; r + 1 < R; r += 2)
            for (uint32_t c = 0; c < C; c++) link(&b, P(r, c), P(r + 1, c), ks, TT_DISTANCE_RIGID, bs);
    const double ss = d->shear_stiffness, bb = d->bend_stiffness;
    if (ss > 0)
        for (uint32_t pass = 0; pass < 8; pass++) /* "\" then "/" diagonals; row and column parity */
            for (uint32_t r = (pass >> 1) & 1; r + 1 < R; r += 2)
                for (uint32_t c = pass & 1; c + 1 < C; c += 2) {
                    if (pass < 4) link(&b, P(r, c), P(r + 1, c + 1), ss, TT_DISTANCE_RIGID, bs);
                    else link(&b, P(r, c + 1), P(r + 1, c), ss, TT_DISTANCE_RIGID, bs);
                }
    if (bb > 0) {
        for (uint32_t pass = 0; pass < 2; pass++) /* c mod 4 in {0, 1}, then {2, 3}: disjoint pairs */
            for (uint32_t r = 0; r < R; r++)
                for (uint32_t c = 0; c + 2 < C; c++)
                    if ((c % 4 >= 2) == (pass == 1)) link(&b, P(r, c), P(r, c + 2), bb, TT_DISTANCE_RIGID, bs);
        for (uint32_t pass = 0; pass < 2; pass++)
            for (uint32_t r = 0; r + 2 < R; r++)
                if ((r % 4 >= 2) == (pass == 1))
                    for (uint32_t c = 0; c < C; c++) link(&b, P(r, c), P(r + 2, c), bb, TT_DISTANCE_RIGID, bs);
    }
#undef P
    return finish(&b);
}

tt_composite tt_ragdoll_create(tt_world *w, const tt_ragdoll_def *d)
{
    const char *fn = "tt_ragdoll_create";
    START(fn);
    if (!tt__vec_ok(d->position)) { tt__fail(w, TT_EINVAL, "%s: position must be finite", fn); return NONE; }
    if (!positive(w, d->height, fn, "height")) return NONE;
    /* A 1.65 m stick figure (head centre to feet), scaled to `height`. */
    static const double body[11][2] = {
        {0, 0.75},        {0, 0.5},          {0, 0},          /* head, neck, pelvis */
        {-0.15, 0.22},    {-0.2, -0.05},                       /* left elbow, hand */
        {0.15, 0.22},     {0.2, -0.05},                        /* right elbow, hand */
        {-0.1, -0.45},    {-0.1, -0.9},                        /* left knee, foot */
        {0.1, -0.45},     {0.1, -0.9},                         /* right knee, foot */
    };
    static const uint8_t bones[][2] = {{0, 1}, {1, 2}, {0, 2}, {1, 3}, {3, 4}, {1, 5}, {5, 6},
                                       {2, 7}, {7, 8}, {2, 9}, {9, 10}, {3, 5}, {7, 9}};
    const double s = d->height / 1.65;
    builder b;
    if (!begin(&b, w, &d->common, 11, fn)) return NONE;
    for (int i = 0; i < 11; i++) place(&b, d->position.x + body[i][0] * s, d->position.y + body[i][1] * s, false);
    if (!spawn(&b)) return NONE;
    for (size_t i = 0; i < sizeof bones / sizeof bones[0]; i++) {
        /* the elbow-to-elbow and knee-to-knee struts only push: they keep limbs apart */
        bool strut = i >= 11;
        link(&b, bones[i][0], bones[i][1], d->common.stiffness, strut ? TT_DISTANCE_MIN : TT_DISTANCE_RIGID, 0.0);
    }
    if (d->limits) {
        const double deg = TT_PI / 180;
        limit(&b, 4, 3, 1, 20 * deg, TT_PI);    /* left elbow: bends one way only */
        limit(&b, 1, 5, 6, 20 * deg, TT_PI);    /* right elbow, mirrored */
        limit(&b, 8, 7, 2, 30 * deg, TT_PI);    /* left knee */
        limit(&b, 2, 9, 10, 30 * deg, TT_PI);   /* right knee, mirrored */
        limit(&b, 1, 2, 7, 100 * deg, -150 * deg); /* left hip: a range through ±π */
        limit(&b, 9, 2, 1, 100 * deg, -150 * deg); /* right hip, mirrored */
    }
    return finish(&b);
}

tt_composite tt_soft_body_create(tt_world *w, const tt_soft_body_def *d)
{
    const char *fn = "tt_soft_body_create";
    START(fn);
    if (!tt__vec_ok(d->center)) { tt__fail(w, TT_EINVAL, "%s: center must be finite", fn); return NONE; }
    if (!positive(w, d->radius, fn, "radius") || !positive(w, d->pressure, fn, "pressure")) return NONE;
    if (d->segments < 3 || d->segments > 65536) { tt__fail(w, TT_EINVAL, "%s: segments must be in [3, 65536], got %u", fn, d->segments); return NONE; }
    if (!unit(w, d->area_stiffness, fn, "area_stiffness")) return NONE;
    if (!tt__in_range(d->area_compliance, 0.0, TT_MAX_VALUE)) { tt__fail(w, TT_EINVAL, "%s: area_compliance must be in [0, %g]", fn, TT_MAX_VALUE); return NONE; }
    const uint32_t n = d->segments;
    builder b;
    if (!begin(&b, w, &d->common, n, fn)) return NONE;
    for (uint32_t i = 0; i < n; i++) {
        double a = 2 * TT_PI * i / n;
        place(&b, d->center.x + d->radius * cos(a), d->center.y + d->radius * sin(a), false);
    }
    if (!spawn(&b)) return NONE;
    for (uint32_t i = 0; i < n; i++) link(&b, i, (i + 1) % n, d->common.stiffness, TT_DISTANCE_RIGID, 0.0);
    if (con_room(&b)) {
        tt_area_def ad = tt_area_def_default();
        ad.particles = b.c.parts;
        ad.count = n;
        ad.pressure = d->pressure;
        ad.stiffness = d->area_stiffness;
        ad.compliance = d->area_compliance;
        add_constraint(&b, tt_area_create(w, &ad));
    }
    return finish(&b);
}

tt_composite tt_lattice_create(tt_world *w, const tt_lattice_def *d)
{
    const char *fn = "tt_lattice_create";
    START(fn);
    builder b;
    if (d->points) {
        const uint32_t n = d->point_count;
        if (n < 3 || n > 64) { tt__fail(w, TT_EINVAL, "%s: point_count must be in [3, 64], got %u", fn, n); return NONE; }
        for (uint32_t i = 0; i < n; i++)
            if (!tt__vec_ok(d->points[i])) { tt__fail(w, TT_EINVAL, "%s: points[%u] must be finite", fn, i); return NONE; }
        uint32_t bad = tt__polygon_fault(d->points, n, false);
        if (bad < n) {
            tt__fail(w, TT_EINVAL, "%s: points must make a polygon with no repeated or collinear points (at point %u)", fn, bad);
            return NONE;
        }
        if (!begin(&b, w, &d->common, n, fn)) return NONE;
        for (uint32_t i = 0; i < n; i++) place(&b, d->points[i].x, d->points[i].y, false);
        if (!spawn(&b)) return NONE;
        for (uint32_t i = 0; i < n; i++) /* every pair: rigid for any polygon */
            for (uint32_t j = i + 1; j < n; j++) link(&b, i, j, d->common.stiffness, TT_DISTANCE_RIGID, 0.0);
        return finish(&b);
    }
    if (!tt__vec_ok(d->center)) { tt__fail(w, TT_EINVAL, "%s: center must be finite", fn); return NONE; }
    if (!positive(w, d->width, fn, "width") || !positive(w, d->height, fn, "height")) return NONE;
    if (!tt__in_range(d->angle, -TT_MAX_VALUE, TT_MAX_VALUE)) { tt__fail(w, TT_EINVAL, "%s: angle must be finite", fn); return NONE; }
    if (d->columns < 2 || d->columns > 1024 || d->rows < 2 || d->rows > 1024) {
        tt__fail(w, TT_EINVAL, "%s: columns and rows must be in [2, 1024], got %u x %u", fn, d->columns, d->rows);
        return NONE;
    }
    const uint32_t C = d->columns, R = d->rows;
    if (!begin(&b, w, &d->common, C * R, fn)) return NONE;
    const double ca = cos(d->angle), sa = sin(d->angle);
    for (uint32_t r = 0; r < R; r++)
        for (uint32_t c = 0; c < C; c++) {
            double lx = -0.5 * d->width + d->width * c / (C - 1), ly = -0.5 * d->height + d->height * r / (R - 1);
            place(&b, d->center.x + ca * lx - sa * ly, d->center.y + sa * lx + ca * ly, false);
        }
    if (!spawn(&b)) return NONE;
#define P(r, c) ((r) * C + (c))
    const double k = d->common.stiffness;
    for (uint32_t r = 0; r < R; r++)
        for (uint32_t c = 0; c < C; c++) {
            if (c + 1 < C) link(&b, P(r, c), P(r, c + 1), k, TT_DISTANCE_RIGID, 0.0);
            if (r + 1 < R) link(&b, P(r, c), P(r + 1, c), k, TT_DISTANCE_RIGID, 0.0);
            if (c + 1 < C && r + 1 < R) {
                link(&b, P(r, c), P(r + 1, c + 1), k, TT_DISTANCE_RIGID, 0.0);
                link(&b, P(r, c + 1), P(r + 1, c), k, TT_DISTANCE_RIGID, 0.0);
            }
            if (c + 2 < C) link(&b, P(r, c), P(r, c + 2), k, TT_DISTANCE_RIGID, 0.0);
            if (r + 2 < R) link(&b, P(r, c), P(r + 2, c), k, TT_DISTANCE_RIGID, 0.0);
        }
    /* the long diagonals brace a many-celled lattice against slow shear */
    if (C * R > 4) {
        link(&b, P(0, 0), P(R - 1, C - 1), k, TT_DISTANCE_RIGID, 0.0);
        link(&b, P(0, C - 1), P(R - 1, 0), k, TT_DISTANCE_RIGID, 0.0);
    }
#undef P
    return finish(&b);
}

/* ---- reading back --------------------------------------------------------------- */

/* Slots with a record (a slot taken when growing the records failed has none). */
static uint32_t comp_slots(const tt__cgroup *g) { return g->cpool.count < g->comp_cap ? g->cpool.count : g->comp_cap; }

static tt_result comp_check(const tt_world *w, tt_composite c, const char *fn, const tt__composite **out)
{
    if (!w) return tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn);
    const tt__cgroup *g = tt__cgroup_peek(w);
    if (!g || c.gen == 0 || c.index >= comp_slots(g) || g->cpool.gen[c.index] != c.gen || !g->comps[c.index].alive)
        return tt__fail(w, TT_ESTALE, "%s: stale composite handle (index %u, generation %u)", fn, c.index, c.gen);
    *out = &g->comps[c.index];
    return TT_OK;
}

bool tt_composite_is_valid(const tt_world *w, tt_composite c)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    return g && c.gen != 0 && c.index < comp_slots(g) && g->cpool.gen[c.index] == c.gen && g->comps[c.index].alive;
}

tt_result tt_composite_destroy(tt_world *w, tt_composite c)
{
    const tt__composite *cc;
    tt_result r = comp_check(w, c, "tt_composite_destroy", &cc);
    if (r != TT_OK) return r;
    tt__cgroup *g = tt__cgroup_get(w, false);
    tt__composite *k = &g->comps[c.index];
    for (uint32_t i = 0; i < k->nc; i++)
        if (tt_constraint_is_valid(w, k->cons[i])) tt_constraint_destroy(w, k->cons[i]);
    for (uint32_t i = 0; i < k->np; i++)
        if (tt_particle_is_valid(w, k->parts[i])) tt_particle_destroy(w, k->parts[i]);
    free(k->parts);
    free(k->cons);
    free(k->rest);
    memset(k, 0, sizeof *k);
    tt_pool_free(&g->cpool, c.index);
    g->comps_alive--;
    return TT_OK;
}

tt_result tt_composite_get_particles(const tt_world *w, tt_composite c, tt_particle *out, uint32_t cap, uint32_t *count)
{
    const tt__composite *k;
    tt_result r = comp_check(w, c, "tt_composite_get_particles", &k);
    if (r != TT_OK) return r;
    for (uint32_t i = 0; out && i < k->np && i < cap; i++) out[i] = k->parts[i];
    if (count) *count = k->np;
    return TT_OK;
}

tt_result tt_composite_get_constraints(const tt_world *w, tt_composite c, tt_constraint *out, uint32_t cap, uint32_t *count)
{
    const tt__composite *k;
    tt_result r = comp_check(w, c, "tt_composite_get_constraints", &k);
    if (r != TT_OK) return r;
    for (uint32_t i = 0; out && i < k->nc && i < cap; i++) out[i] = k->cons[i];
    if (count) *count = k->nc;
    return TT_OK;
}

/* Mass-weighted centres, now and at rest, over the live particles. */
static double centres(const tt_world *w, const tt__composite *k, double c[2], double r0[2])
{
    double m = 0;
    c[0] = c[1] = r0[0] = r0[1] = 0;
    for (uint32_t i = 0; i < k->np; i++) {
        if (!tt_particle_is_valid(w, k->parts[i])) continue;
        uint32_t p = k->parts[i].index;
        double mi = w->mass[p];
        m += mi;
        c[0] += mi * w->px[p];
        c[1] += mi * w->py[p];
        r0[0] += mi * k->rest[2 * i];
        r0[1] += mi * k->rest[2 * i + 1];
    }
    if (m > 0) {
        c[0] /= m; c[1] /= m; r0[0] /= m; r0[1] /= m;
    }
    return m;
}

/* The checks both readers below share, then the centres of mass now (cc) and at rest (r0). */
static tt_result comp_frame(const tt_world *w, tt_composite c, const char *fn, const void *out,
                            const tt__composite **k, double cc[2], double r0[2])
{
    tt_result r = comp_check(w, c, fn, k);
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "%s: out is NULL", fn);
    if (centres(w, *k, cc, r0) == 0) return tt__fail(w, TT_ESTATE, "%s: the composite has no particles left", fn);
    return TT_OK;
}

tt_result tt_composite_get_center(const tt_world *w, tt_composite c, tt_vec2 *out)
{
    const tt__composite *k;
    double cc[2], r0[2];
    tt_result r = comp_frame(w, c, "tt_composite_get_center", out, &k, cc, r0);
    if (r != TT_OK) return r;
    *out = (tt_vec2){cc[0], cc[1]};
    return TT_OK;
}

tt_result tt_composite_get_angle(const tt_world *w, tt_composite c, double *out)
{
    const tt__composite *k;
    double cc[2], r0[2];
    tt_result r = comp_frame(w, c, "tt_composite_get_angle", out, &k, cc, r0);
    if (r != TT_OK) return r;
    double sc = 0, ss = 0; /* Σ m (q·p), Σ m (q×p): q rest offset, p current offset */
    for (uint32_t i = 0; i < k->np; i++) {
        if (!tt_particle_is_valid(w, k->parts[i])) continue;
        uint32_t p = k->parts[i].index;
        double qx = k->rest[2 * i] - r0[0], qy = k->rest[2 * i + 1] - r0[1];
        double px = w->px[p] - cc[0], py = w->py[p] - cc[1], m = w->mass[p];
        sc += m * (qx * px + qy * py);
        ss += m * (qx * py - qy * px);
    }
    *out = atan2(ss, sc);
    return TT_OK;
}

uint32_t tt_world_composite_count(const tt_world *w)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    return g ? g->comps_alive : 0;
}

/* ---- group hooks ------------------------------------------------------------------ */


void tt__composites_free(tt__cgroup *g)
{
    for (uint32_t i = 0; i < comp_slots(g); i++) {
        free(g->comps[i].parts);
        free(g->comps[i].cons);
        free(g->comps[i].rest);
    }
    free(g->comps);
    tt_pool_destroy(&g->cpool);
}

size_t tt__composites_memory(const tt__cgroup *g)
{
    size_t b = (size_t)g->comp_cap * sizeof(tt__composite) + tt_pool_bytes(&g->cpool);
    for (uint32_t i = 0; i < comp_slots(g); i++) {
        const tt__composite *k = &g->comps[i];
        if (!k->alive) continue;
        b += (size_t)k->np * (sizeof(tt_particle) + 2 * sizeof(double)) + (size_t)k->ccap * sizeof(tt_constraint);
    }
    return b;
}

uint64_t tt__composites_hash(const tt__cgroup *g, uint64_t h)
{
    h = tt__fnv(h, &g->comps_alive, sizeof g->comps_alive);
    for (uint32_t i = 0; i < comp_slots(g); i++) {
        const tt__composite *k = &g->comps[i];
        if (!k->alive) continue;
        h = tt__fnv(h, &i, sizeof i);
        for (uint32_t j = 0; j < k->np; j++) { /* indices and generations, without the world's tag */
            uint32_t v[2] = {k->parts[j].index, k->parts[j].gen & TT_POOL_GEN_MASK};
            h = tt__fnv(h, v, sizeof v);
        }
        for (uint32_t j = 0; j < k->nc; j++) {
            uint32_t v[2] = {k->cons[j].index, k->cons[j].gen & TT_POOL_GEN_MASK};
            h = tt__fnv(h, v, sizeof v);
        }
    }
    return h;
}
