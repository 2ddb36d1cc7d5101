/* tether — the reference pour onto a mask bowl (issue 19): the reference
 * pour's circles (ts_scene_pour's grid and material, lifted clear of the
 * rim) falling into a terrain of 0.1 m pixels whose floor is an arc of
 * radius 0.8 × the width between vertical walls. Shared by the bench (the
 * 10 000-circle pour) and the tests (a smaller one), with the figures both
 * report. Public API only, as the rest of the scenes. */
#include "scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PIXEL 0.1 /* m */

/* The arc's radius: the floor is a circle of it through (0, 0), centre above. */
static double arc_radius(double width) { return 0.8 * width; }

/* The bowl's pixels: solid below the arc and beyond the walls, from y = −2
 * to top; the mask's pixel (0, 0) at (−width/2 − 2, top). */
static tt_mask *bowl_mask(double width, double top)
{
    const double h = width / 2, R = arc_radius(width);
    const int mw = (int)ceil((width + 4) / PIXEL), mh = (int)ceil((top + 2) / PIXEL);
    tt_mask *m = tt_mask_create(mw, mh, false);
    if (!m) return NULL;
    for (int py = 0; py < mh; py++) {
        const double y = top - (py + 0.5) * PIXEL; /* the row's pixel centres */
        /* free where |x| < half: inside the walls and above the arc */
        double half = y < 0 ? 0 : y >= R ? h : fmin(h, sqrt(R * R - (R - y) * (R - y)));
        const int a = (int)ceil((-half + h + 2) / PIXEL - 0.5), b = (int)floor((half + h + 2) / PIXEL - 0.5);
        if (a > b) {
            tt_mask_fill_rect(m, 0, py, mw, 1, true);
        } else {
            tt_mask_fill_rect(m, 0, py, a, 1, true);
            tt_mask_fill_rect(m, b + 1, py, mw - b - 1, 1, true);
        }
    }
    return m;
}

/* The arc's height at the walls (the rim); the circles start half a radius above it. */
static double rim(double width)
{
    const double h = width / 2, R = arc_radius(width);
    return R - sqrt(R * R - h * h);
}

tt_result ts_bowl_build(uint32_t n, double width, ts_bowl *b, const char **why)
{
    memset(b, 0, sizeof *b);
    const double h = width / 2, lift = rim(width) + 0.5;
    double top;
    tt_result r = ts_tether_pour_circles(n, width, lift, "bowl", &b->t, &top, &b->steps, why);
    if (r != TT_OK) return r;
    if (b->t.circle_count) tt_particle_get_radius(b->t.world, b->t.circles[0], &b->radius);
    tt_mask *m = bowl_mask(width, top);
    tt_terrain_def td = tt_terrain_def_default();
    td.solid = m;
    td.pixel = PIXEL;
    td.origin = (tt_vec2){-h - 2, top};
    td.friction_static = td.friction_kinetic = 0.3;
    b->terrain = m ? tt_terrain_create(b->t.world, &td) : (tt_terrain){0, 0};
    tt_mask_destroy(m);
    if (!b->terrain.gen) {
        if (why) *why = "out of memory";
        ts_tether_free(&b->t);
        return TT_ENOMEM;
    }
    return TT_OK;
}

static bool edge(ts_scene *s, double ax, double ay, double bx, double by, const char **why)
{
    ts_body e = ts_body_default();
    e.shape = TS_EDGE;
    e.a = (tt_vec2){ax, ay};
    e.b = (tt_vec2){bx, by};
    return ts_scene_add_body(s, &e, why) >= 0;
}

bool ts_scene_bowl(ts_scene *s, uint32_t n, double width, uint32_t edges, bool fixed_rotation, const char **why)
{
    if (edges < 1 || edges > 100000 || !(width >= 3.3 && width <= 1e6)) {
        if (why) *why = "ts_scene_bowl: edges must be in [1, 100000] and width in [3.3, 1e6]";
        ts_scene_init(s, "bowl");
        return false;
    }
    const double h = width / 2, R = arc_radius(width), y0 = rim(width), half = asin(h / R);
    double top;
    if (!ts_scene_pour_lifted(s, n, width, y0 + 0.5, "bowl", &top, why)) return false;
    for (uint32_t i = 0; i < s->body_count; i++) s->bodies[i].fixed_rotation = fixed_rotation;
    bool ok = edge(s, -h, top, -h, y0, why) && edge(s, h, y0, h, top, why);
    for (uint32_t i = 0; i < edges && ok; i++) {
        /* the arc's points from −half to +half by index, so both ends are exact */
        const double t0 = half * (2.0 * i / edges - 1), t1 = half * (2.0 * (i + 1) / edges - 1);
        ok = edge(s, R * sin(t0), R - R * cos(t0), R * sin(t1), R - R * cos(t1), why);
    }
    if (!ok) ts_scene_free(s);
    return ok;
}

void ts_bowl_free(ts_bowl *b)
{
    ts_tether_free(&b->t);
    memset(b, 0, sizeof *b);
}

void ts_bowl_measure(const ts_bowl *b, ts_bowl_figures *out)
{
    const uint32_t n = b->t.circle_count;
    tt_world *w = b->t.world;
    double *xy = malloc(2 * (size_t)(n ? n : 1) * sizeof *xy);
    out->kinetic = ts_tether_kinetic_per_kg(&b->t);
    out->penetration = 0;
    out->inside = 0;
    for (uint32_t i = 0; i < n; i++) {
        tt_vec2 x;
        tt_particle_get_position(w, b->t.circles[i], &x);
        bool solid = false;
        double d = 0;
        tt_terrain_is_solid(w, b->terrain, x, &solid);
        tt_terrain_distance(w, b->terrain, x, &d, NULL);
        out->inside += solid;
        out->penetration = fmax(out->penetration, (b->radius - d) / b->radius);
        if (xy) xy[2 * i] = x.x, xy[2 * i + 1] = x.y;
    }
    ts_pile pile;
    ts_pile_measure(xy, xy ? n : 0, b->radius, &pile);
    out->max_overlap = pile.max_overlap;
    out->mean_overlap = pile.mean_overlap;
    free(xy);
}
