/* tether — the five composite kinds (rope, cloth, ragdoll, soft body,
 * lattice body): their defs' defaults, their checks, and where each puts its
 * particles and links, through the builder of composite_builder.c. */
#include "constraint_internal.h"

#include <string.h>

#define NONE ((tt_composite){0, 0})

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
    d.finish = (tt_vec2){1, 0};
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
    d.ring_radius = 1.0;
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
    if (!tt__vec_ok(d->start) || !tt__vec_ok(d->finish)) { tt__fail(w, TT_EINVAL, "%s: start and finish must be finite", fn); return NONE; }
    if (d->segments < 1 || d->segments > 100000) { tt__fail(w, TT_EINVAL, "%s: segments must be in [1, 100000], got %u", fn, d->segments); return NONE; }
    if (!strain_ok(w, d->break_strain, fn)) return NONE;
    tt__builder b;
    if (!tt__builder_begin(&b, w, &d->common, d->segments + 1, fn)) return NONE;
    for (uint32_t i = 0; i <= d->segments; i++) {
        double t = (double)i / d->segments;
        tt__builder_place(&b, d->start.x + (d->finish.x - d->start.x) * t, d->start.y + (d->finish.y - d->start.y) * t,
              (i == 0 && d->pin_start) || (i == d->segments && d->pin_finish));
    }
    if (!tt__builder_spawn(&b)) return NONE;
    for (uint32_t i = 0; i < d->segments; i++)
        tt__builder_link(&b, i, i + 1, d->common.stiffness, d->slack ? TT_DISTANCE_MAX : TT_DISTANCE_RIGID, d->break_strain);
    return tt__builder_finish(&b);
}

/* The cloth's long-range attachments: a "max" link from each unpinned
 * particle to each pinned corner, or with a pinned top row to the pinned
 * particle atop its column, the nearest. In the plane the rest distance is
 * the geodesic one. Made last, so the sweeps solve them last.
 *
 * Hung from two corners, the two discs a particle is kept in meet at its
 * rest spot at an angle θ (π less the angle the two corners subtend there): near the line between the corners θ is small (0 on the top
 * row), and projecting in turn on two nearly tangent circles closes only
 * 1 − cos θ of a sag per projection, so the top band sagged between the pins
 * (a 128² cloth at 4 sweeps: 15 mm at the top middle; its links compressed
 * 10 % at rest, 16 % in the first swing). There a third attachment holds the
 * particle inside the circle through both corners and its rest spot, whose
 * normal at the rest spot is near vertical: the angle at the particle
 * between the corners (inscribed in that circle) may not close below its
 * rest value; above the corners' line, inside the same circle, it may (the
 * range wraps through ±π: [π + φ0, φ0], φ0 the rest angle, −π on the top
 * row, where the circle is the line). Only where θ < 30°: below that its
 * cost (an atan2 a sweep) buys nothing measurable (the 128² cloth: 1.7 %
 * max at 30°, as at 60° and 90°; 4.1 % at 20°; 1 398 limits at 30°). */
static void attach_to_pins(tt__builder *b, const tt_cloth_def *d)
{
    const uint32_t C = d->columns, R = d->rows;
    for (uint32_t i = C; i < R * C; i++) { /* every row but the top one: nothing there is pinned */
        if (d->pin_top_row) {
            tt__builder_link(b, i % C, i, 1.0, TT_DISTANCE_MAX, 0.0);
        } else if (d->pin_top_corners) {
            tt__builder_link(b, 0, i, 1.0, TT_DISTANCE_MAX, 0.0);
            tt__builder_link(b, C - 1, i, 1.0, TT_DISTANCE_MAX, 0.0);
        }
    }
    if (d->pin_top_row || !d->pin_top_corners) return;
    for (uint32_t c = 1; c + 1 < C; c++) { /* the top row's own unpinned particles */
        tt__builder_link(b, 0, c, 1.0, TT_DISTANCE_MAX, 0.0);
        tt__builder_link(b, C - 1, c, 1.0, TT_DISTANCE_MAX, 0.0);
    }
    const double sx = d->width / (C - 1), sy = d->height / (R - 1);
    for (uint32_t i = 0; i < R * C; i++) {
        const uint32_t r = i / C, c = i % C;
        if (c == 0 || c == C - 1) continue; /* a corner, or straight below one: θ ≥ 90° */
        const double theta = atan2(r * sy, c * sx) + atan2(r * sy, (C - 1 - c) * sx);
        if (theta < TT_PI / 6) tt__builder_limit(b, 0, i, C - 1, theta, theta - TT_PI, 1.0);
    }
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
    if (d->long_range && d->break_strain > 0) {
        tt__fail(w, TT_EINVAL, "%s: long_range ties every particle to the pins, so a torn piece could not fall: not with break_strain", fn);
        return NONE;
    }
    const uint32_t C = d->columns, R = d->rows;
    tt__builder b;
    if (!tt__builder_begin(&b, w, &d->common, C * R, fn)) return NONE;
    const double sx = d->width / (C - 1), sy = d->height / (R - 1);
    for (uint32_t r = 0; r < R; r++)
        for (uint32_t c = 0; c < C; c++) {
            bool pin = r == 0 && (d->pin_top_row || (d->pin_top_corners && (c == 0 || c == C - 1)));
            tt__builder_place(&b, d->origin.x + c * sx, d->origin.y - r * sy, pin);
        }
    if (!tt__builder_spawn(&b)) return NONE;
#define P(r, c) ((r) * C + (c))
    const double ks = d->common.stiffness, bs = d->break_strain;
    /* Links are made in passes whose members share no particle (red-black
     * order): consecutive Gauss-Seidel corrections are then independent and
     * the processor overlaps them (measured on a 128² cloth: 9.5 → 6.0 ms
     * per step at 10 sweeps, against row-major order). */
    for (uint32_t pass = 0; pass < 2; pass++) /* structural, horizontal */
        for (uint32_t r = 0; r < R; r++)
            for (uint32_t c = pass; c + 1 < C; c += 2) tt__builder_link(&b, P(r, c), P(r, c + 1), ks, TT_DISTANCE_RIGID, bs);
    for (uint32_t pass = 0; pass < 2; pass++) /* structural, vertical */
        for (uint32_t r = pass; r + 1 < R; r += 2)
            for (uint32_t c = 0; c < C; c++) tt__builder_link(&b, P(r, c), P(r + 1, c), ks, TT_DISTANCE_RIGID, bs);
    const double ss = d->shear_stiffness, bb = d->bend_stiffness;
    if (ss > 0)
        for (uint32_t pass = 0; pass < 8; pass++) /* "\" then "/" diagonals; row and column parity */
            for (uint32_t r = (pass >> 1) & 1; r + 1 < R; r += 2)
                for (uint32_t c = pass & 1; c + 1 < C; c += 2) {
                    if (pass < 4) tt__builder_link(&b, P(r, c), P(r + 1, c + 1), ss, TT_DISTANCE_RIGID, bs);
                    else tt__builder_link(&b, P(r, c + 1), P(r + 1, c), ss, TT_DISTANCE_RIGID, bs);
                }
    if (bb > 0) {
        for (uint32_t pass = 0; pass < 2; pass++) /* c mod 4 in {0, 1}, then {2, 3}: disjoint pairs */
            for (uint32_t r = 0; r < R; r++)
                for (uint32_t c = 0; c + 2 < C; c++)
                    if ((c % 4 >= 2) == (pass == 1)) tt__builder_link(&b, P(r, c), P(r, c + 2), bb, TT_DISTANCE_RIGID, bs);
        for (uint32_t pass = 0; pass < 2; pass++)
            for (uint32_t r = 0; r + 2 < R; r++)
                if ((r % 4 >= 2) == (pass == 1))
                    for (uint32_t c = 0; c < C; c++) tt__builder_link(&b, P(r, c), P(r + 2, c), bb, TT_DISTANCE_RIGID, bs);
    }
#undef P
    if (d->long_range) attach_to_pins(&b, d);
    return tt__builder_finish(&b);
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
    tt__builder b;
    if (!tt__builder_begin(&b, w, &d->common, 11, fn)) return NONE;
    for (int i = 0; i < 11; i++) tt__builder_place(&b, d->position.x + body[i][0] * s, d->position.y + body[i][1] * s, false);
    if (!tt__builder_spawn(&b)) return NONE;
    for (size_t i = 0; i < sizeof bones / sizeof bones[0]; i++) {
        /* the elbow-to-elbow and knee-to-knee struts only push: they keep limbs apart */
        bool strut = i >= 11;
        tt__builder_link(&b, bones[i][0], bones[i][1], d->common.stiffness, strut ? TT_DISTANCE_MIN : TT_DISTANCE_RIGID, 0.0);
    }
    if (d->limits) {
        const double deg = TT_PI / 180, ks = d->common.stiffness;
        tt__builder_limit(&b, 4, 3, 1, 20 * deg, TT_PI, ks);    /* left elbow: bends one way only */
        tt__builder_limit(&b, 1, 5, 6, 20 * deg, TT_PI, ks);    /* right elbow, mirrored */
        tt__builder_limit(&b, 8, 7, 2, 30 * deg, TT_PI, ks);    /* left knee */
        tt__builder_limit(&b, 2, 9, 10, 30 * deg, TT_PI, ks);   /* right knee, mirrored */
        tt__builder_limit(&b, 1, 2, 7, 100 * deg, -150 * deg, ks); /* left hip: a range through ±π */
        tt__builder_limit(&b, 9, 2, 1, 100 * deg, -150 * deg, ks); /* right hip, mirrored */
    }
    return tt__builder_finish(&b);
}

tt_composite tt_soft_body_create(tt_world *w, const tt_soft_body_def *d)
{
    const char *fn = "tt_soft_body_create";
    START(fn);
    if (!tt__vec_ok(d->center)) { tt__fail(w, TT_EINVAL, "%s: center must be finite", fn); return NONE; }
    if (!positive(w, d->ring_radius, fn, "ring_radius") || !positive(w, d->pressure, fn, "pressure")) return NONE;
    if (d->segments < 3 || d->segments > 65536) { tt__fail(w, TT_EINVAL, "%s: segments must be in [3, 65536], got %u", fn, d->segments); return NONE; }
    if (!unit(w, d->area_stiffness, fn, "area_stiffness")) return NONE;
    if (!tt__in_range(d->area_compliance, 0.0, TT_MAX_VALUE)) { tt__fail(w, TT_EINVAL, "%s: area_compliance must be in [0, %g]", fn, TT_MAX_VALUE); return NONE; }
    const uint32_t n = d->segments;
    tt__builder b;
    if (!tt__builder_begin(&b, w, &d->common, n, fn)) return NONE;
    for (uint32_t i = 0; i < n; i++) {
        double a = 2 * TT_PI * i / n;
        tt__builder_place(&b, d->center.x + d->ring_radius * cos(a), d->center.y + d->ring_radius * sin(a), false);
    }
    if (!tt__builder_spawn(&b)) return NONE;
    for (uint32_t i = 0; i < n; i++) tt__builder_link(&b, i, (i + 1) % n, d->common.stiffness, TT_DISTANCE_RIGID, 0.0);
    if (tt__builder_con_room(&b)) {
        tt_area_def ad = tt_area_def_default();
        ad.particles = b.c.parts;
        ad.count = n;
        ad.pressure = d->pressure;
        ad.stiffness = d->area_stiffness;
        ad.compliance = d->area_compliance;
        tt__builder_add_constraint(&b, tt_area_create(w, &ad));
    }
    return tt__builder_finish(&b);
}

tt_composite tt_lattice_create(tt_world *w, const tt_lattice_def *d)
{
    const char *fn = "tt_lattice_create";
    START(fn);
    tt__builder b;
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
        if (!tt__builder_begin(&b, w, &d->common, n, fn)) return NONE;
        for (uint32_t i = 0; i < n; i++) tt__builder_place(&b, d->points[i].x, d->points[i].y, false);
        if (!tt__builder_spawn(&b)) return NONE;
        for (uint32_t i = 0; i < n; i++) /* every pair: rigid for any polygon */
            for (uint32_t j = i + 1; j < n; j++) tt__builder_link(&b, i, j, d->common.stiffness, TT_DISTANCE_RIGID, 0.0);
        return tt__builder_finish(&b);
    }
    if (!tt__vec_ok(d->center)) { tt__fail(w, TT_EINVAL, "%s: center must be finite", fn); return NONE; }
    if (!positive(w, d->width, fn, "width") || !positive(w, d->height, fn, "height")) return NONE;
    if (!tt__in_range(d->angle, -TT_MAX_VALUE, TT_MAX_VALUE)) { tt__fail(w, TT_EINVAL, "%s: angle must be finite", fn); return NONE; }
    if (d->columns < 2 || d->columns > 1024 || d->rows < 2 || d->rows > 1024) {
        tt__fail(w, TT_EINVAL, "%s: columns and rows must be in [2, 1024], got %u x %u", fn, d->columns, d->rows);
        return NONE;
    }
    const uint32_t C = d->columns, R = d->rows;
    if (!tt__builder_begin(&b, w, &d->common, C * R, fn)) return NONE;
    const double ca = cos(d->angle), sa = sin(d->angle);
    for (uint32_t r = 0; r < R; r++)
        for (uint32_t c = 0; c < C; c++) {
            double lx = -0.5 * d->width + d->width * c / (C - 1), ly = -0.5 * d->height + d->height * r / (R - 1);
            tt__builder_place(&b, d->center.x + ca * lx - sa * ly, d->center.y + sa * lx + ca * ly, false);
        }
    if (!tt__builder_spawn(&b)) return NONE;
#define P(r, c) ((r) * C + (c))
    const double k = d->common.stiffness;
    for (uint32_t r = 0; r < R; r++)
        for (uint32_t c = 0; c < C; c++) {
            if (c + 1 < C) tt__builder_link(&b, P(r, c), P(r, c + 1), k, TT_DISTANCE_RIGID, 0.0);
            if (r + 1 < R) tt__builder_link(&b, P(r, c), P(r + 1, c), k, TT_DISTANCE_RIGID, 0.0);
            if (c + 1 < C && r + 1 < R) {
                tt__builder_link(&b, P(r, c), P(r + 1, c + 1), k, TT_DISTANCE_RIGID, 0.0);
                tt__builder_link(&b, P(r, c + 1), P(r + 1, c), k, TT_DISTANCE_RIGID, 0.0);
            }
            if (c + 2 < C) tt__builder_link(&b, P(r, c), P(r, c + 2), k, TT_DISTANCE_RIGID, 0.0);
            if (r + 2 < R) tt__builder_link(&b, P(r, c), P(r + 2, c), k, TT_DISTANCE_RIGID, 0.0);
        }
    /* the long diagonals brace a many-celled lattice against slow shear */
    if (C * R > 4) {
        tt__builder_link(&b, P(0, 0), P(R - 1, C - 1), k, TT_DISTANCE_RIGID, 0.0);
        tt__builder_link(&b, P(0, C - 1), P(R - 1, 0), k, TT_DISTANCE_RIGID, 0.0);
    }
#undef P
    return tt__builder_finish(&b);
}
