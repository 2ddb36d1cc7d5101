/* tether — debug draw of a world onto a canvas, through the public API only.
 *
 * Each kind of object is one function below, drawn bottom to top by
 * tt_canvas_draw_world; each reads its objects through their own public
 * listing calls, so the renderer needs no engine internals. */
#include "render_internal.h"

#include <math.h>
#include <stdlib.h>

tt_debug_draw tt_debug_draw_default(void)
{
    tt_debug_draw d;
    d.particles = true;
    d.springs = true;
    d.min_radius_px = 1.5;
    d.strain_full = 0.1;
    d.particle = (tt_color){235, 200, 90, 255};
    d.pinned = (tt_color){230, 70, 70, 255};
    d.constraints = true;
    d.shapes = true;
    d.constraint = (tt_color){120, 190, 230, 255};
    d.shape = (tt_color){150, 220, 150, 255};
    d.alpha = 1.0;
    return d;
}

/* Between where a particle was as the last step began and where it is:
 * at alpha 1 exactly where it is (the picture without interpolation). */
static double between(double prev, double now, double alpha)
{
    return alpha == 1.0 ? now : prev + alpha * (now - prev);
}

static tt_vec2 drawn_at(const tt_world *w, tt_particle p, double alpha, tt_vec2 now)
{
    tt_vec2 prev;
    if (alpha == 1.0 || tt_particle_get_previous_position(w, p, &prev) != TT_OK) return now;
    return (tt_vec2){between(prev.x, now.x, alpha), between(prev.y, now.y, alpha)};
}

/* Strain s (relative length change) → blue (compressed) · grey (rest) · red (stretched). */
static tt_color stress_color(double s, double full)
{
    double t = full > 0 ? s / full : 0;
    if (t > 1) t = 1;
    if (t < -1) t = -1;
    tt_color k = {150, 150, 160, 255};
    if (t > 0) {
        k.r = (uint8_t)(150 + 105 * t);
        k.g = (uint8_t)(150 - 110 * t);
        k.b = (uint8_t)(160 - 120 * t);
    } else if (t < 0) {
        k.r = (uint8_t)(150 + 110 * t);
        k.g = (uint8_t)(150 + 20 * t);
        k.b = (uint8_t)(160 - 95 * t);
    }
    return k;
}

/* springs */
static tt_result draw_springs(tt_canvas *c, const tt_world *w, const tt_debug_draw *o)
{
    tt_result r = TT_OK;
    uint32_t n = tt_world_list_springs(w, NULL, 0);
    tt_spring *s = malloc((size_t)n * sizeof *s + 1);
    if (!s) r = TT_ENOMEM;
    else {
        n = tt_world_list_springs(w, s, n);
        for (uint32_t i = 0; i < n && r == TT_OK; i++) {
            tt_spring_def d;
            tt_vec2 a, b;
            if (tt_spring_get_def(w, s[i], &d) != TT_OK || tt_particle_get_position(w, d.a, &a) != TT_OK ||
                tt_particle_get_position(w, d.b, &b) != TT_OK)
                continue;
            double len = hypot(a.x - b.x, a.y - b.y);
            double strain = d.rest_length > 0 ? (len - d.rest_length) / d.rest_length : 0;
            tt_color k = stress_color(strain, o->strain_full);
            r = tt_canvas_line2(c, drawn_at(w, d.a, o->alpha, a), drawn_at(w, d.b, o->alpha, b), k, k);
        }
        free(s);
    }
    return r;
}

/* distance constraints and pins, as segments read in bulk */
static tt_result draw_constraints(tt_canvas *c, const tt_world *w, const tt_debug_draw *o)
{
    tt_result r = TT_OK;
    uint32_t n = tt_world_read_constraint_lines(w, NULL, 0);
    double *xy = malloc(4 * (size_t)n * sizeof *xy + 1);
    if (!xy) r = TT_ENOMEM;
    else {
        n = tt_world_read_constraint_lines(w, xy, n);
        for (uint32_t i = 0; i < n && r == TT_OK; i++)
            r = tt_canvas_line2(c, (tt_vec2){xy[4 * i], xy[4 * i + 1]}, (tt_vec2){xy[4 * i + 2], xy[4 * i + 3]},
                                o->constraint, o->constraint);
        free(xy);
    }
    return r;
}

/* shapes, as outlines under the particles */
static tt_result draw_shapes(tt_canvas *c, const tt_world *w, const tt_debug_draw *o)
{
    tt_result r = TT_OK;
    uint32_t n = tt_world_list_shapes(w, NULL, 0);
    tt_shape *ids = malloc((size_t)n * sizeof *ids + 1);
    tt_vec2 *pts = NULL;
    uint32_t cap = 0;
    if (!ids) r = TT_ENOMEM;
    else n = tt_world_list_shapes(w, ids, n);
    for (uint32_t i = 0; ids && i < n && r == TT_OK; i++) {
        uint32_t count;
        bool closed;
        if (tt_shape_get_outline(w, ids[i], NULL, 0, &count, &closed) != TT_OK || count == 0) continue;
        if (count > cap) {
            tt_vec2 *p = realloc(pts, (size_t)count * sizeof *p);
            if (!p) { r = TT_ENOMEM; break; }
            pts = p;
            cap = count;
        }
        tt_shape_get_outline(w, ids[i], pts, cap, &count, &closed);
        bool sensor = false;
        tt_shape_get_sensor(w, ids[i], &sensor);
        tt_color k = o->shape;
        if (sensor) k.a = (uint8_t)(k.a / 3);
        for (uint32_t j = 0; j + 1 < count && r == TT_OK; j++) r = tt_canvas_line2(c, pts[j], pts[j + 1], k, k);
        if (closed && count > 2 && r == TT_OK) r = tt_canvas_line2(c, pts[count - 1], pts[0], k, k);
    }
    free(pts);
    free(ids);
    return r;
}

/* particles: positions in bulk, radius and pinned state per handle */
static tt_result draw_particles(tt_canvas *c, const tt_world *w, const tt_debug_draw *o)
{
    tt_result r = TT_OK;
    uint32_t n = tt_world_particle_count(w);
    tt_particle *ids = malloc(((size_t)n + 1) * sizeof *ids);
    double *xy = malloc((2 * (size_t)n + 2) * sizeof *xy);
    double *was = o->alpha != 1.0 ? malloc((2 * (size_t)n + 2) * sizeof *was) : NULL;
    if (!ids || !xy || (o->alpha != 1.0 && !was)) {
        r = TT_ENOMEM;
    } else {
        n = tt_world_list_particles(w, ids, n);
        tt_world_read_positions(w, xy, n);
        if (was) {
            tt_world_read_previous_positions(w, was, n);
            for (uint32_t i = 0; i < 2 * n; i++) xy[i] = between(was[i], xy[i], o->alpha);
        }
        double minr = o->min_radius_px / c->zoom;
        for (uint32_t i = 0; i < n; i++) {
            double rad = 0;
            bool pinned = false;
            tt_particle_get_radius(w, ids[i], &rad);
            tt_particle_get_pinned(w, ids[i], &pinned);
            c->color = pinned ? o->pinned : o->particle;
            if (rad < minr) rad = minr;
            r = tt_canvas_circle(c, (tt_vec2){xy[2 * i], xy[2 * i + 1]}, rad, true);
            if (r != TT_OK) break;
        }
    }
    free(ids);
    free(xy);
    free(was);
    return r;
}

tt_result tt_canvas_draw_world(tt_canvas *c, const tt_world *w, const tt_debug_draw *opts)
{
    const char *fn = "tt_canvas_draw_world";
    if (!c) return TT_EINVAL;
    if (!w) {
        tt__errf(c->error, sizeof c->error, "%s: world is NULL", fn);
        return TT_EINVAL;
    }
    tt_debug_draw o = opts ? *opts : tt_debug_draw_default();
    if (!(o.min_radius_px >= 0 && o.min_radius_px <= 1000) || !(o.strain_full > 0 && o.strain_full <= 1e6)) {
        tt__errf(c->error, sizeof c->error, "%s: min_radius_px must be in [0, 1000] and strain_full in (0, 1e6]", fn);
        return TT_EINVAL;
    }
    if (!(o.alpha >= 0 && o.alpha <= 1)) {
        tt__errf(c->error, sizeof c->error, "%s: alpha must be in [0, 1], got %g", fn, o.alpha);
        return TT_EINVAL;
    }
    tt_layer layer = c->layer;
    tt_color color = c->color;
    c->layer = TT_LAYER_WORLD;
    tt_result r = TT_OK;
    if (o.springs && tt_world_spring_count(w) > 0) r = draw_springs(c, w, &o);
    if (o.constraints && r == TT_OK && tt_world_constraint_count(w) > 0) r = draw_constraints(c, w, &o);
    if (o.shapes && r == TT_OK && tt_world_shape_count(w) > 0) r = draw_shapes(c, w, &o);
    if (o.particles && r == TT_OK) r = draw_particles(c, w, &o);
    c->layer = layer;
    c->color = color;
    if (r == TT_ENOMEM) tt__errf(c->error, sizeof c->error, "%s: out of memory", fn);
    return r;
}
