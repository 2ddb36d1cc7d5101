/* tether — scene descriptions: bodies and joints kept in growing arrays,
 * checked on the way in so neither engine's builder meets a bad body. */
#include "scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ts_body ts_body_default(void)
{
    ts_body b;
    memset(&b, 0, sizeof b);
    b.density = 1.0;
    b.friction = 0.3;
    return b;
}

ts_body ts_circle(bool dynamic, tt_vec2 at, double radius)
{
    ts_body b = ts_body_default();
    b.shape = TS_CIRCLE;
    b.dynamic = dynamic;
    b.position = at;
    b.radius = radius;
    return b;
}

ts_body ts_box(bool dynamic, tt_vec2 at, double half_w, double half_h, double angle)
{
    ts_body b = ts_body_default();
    b.shape = TS_BOX;
    b.dynamic = dynamic;
    b.position = at;
    b.half = (tt_vec2){half_w, half_h};
    b.angle = angle;
    return b;
}

void ts_scene_init(ts_scene *s, const char *name)
{
    memset(s, 0, sizeof *s);
    snprintf(s->name, sizeof s->name, "%s", name ? name : "");
    s->gravity = (tt_vec2){0, -10};
    s->dt = 1.0 / 60;
    s->steps = 60;
}

void ts_scene_free(ts_scene *s)
{
    free(s->bodies);
    free(s->joints);
    s->bodies = NULL;
    s->joints = NULL;
    s->body_count = s->body_cap = s->joint_count = s->joint_cap = 0;
}

double ts_scene_highest(const ts_scene *s)
{
    double top = 0.0;
    for (uint32_t i = 0; i < s->body_count; i++)
        if (s->bodies[i].dynamic && s->bodies[i].position.y > top) top = s->bodies[i].position.y;
    return top;
}

bool ts_scene_copy(ts_scene *dst, const ts_scene *src)
{
    *dst = *src;
    dst->bodies = malloc((size_t)(src->body_count + 1) * sizeof *dst->bodies);
    dst->joints = malloc((size_t)(src->joint_count + 1) * sizeof *dst->joints);
    if (!dst->bodies || !dst->joints) {
        ts_scene_free(dst);
        return false;
    }
    if (src->body_count) memcpy(dst->bodies, src->bodies, (size_t)src->body_count * sizeof *dst->bodies);
    if (src->joint_count) memcpy(dst->joints, src->joints, (size_t)src->joint_count * sizeof *dst->joints);
    dst->body_cap = src->body_count + 1;
    dst->joint_cap = src->joint_count + 1;
    return true;
}

static bool finite_vec(tt_vec2 v) { return isfinite(v.x) && isfinite(v.y) && fabs(v.x) <= 1e9 && fabs(v.y) <= 1e9; }

/* Twice the signed area of a polygon: positive when counter-clockwise. */
static double twice_area(const tt_vec2 *p, uint32_t n)
{
    double a = 0;
    for (uint32_t i = 0; i < n; i++) {
        const tt_vec2 u = p[i], v = p[(i + 1) % n];
        a += u.x * v.y - u.y * v.x;
    }
    return a;
}

static const char *check_polygon(const ts_body *b)
{
    if (b->count < 3 || b->count > TS_MAX_POLYGON) return "a polygon needs 3 to 8 points";
    for (uint32_t i = 0; i < b->count; i++) {
        if (!finite_vec(b->points[i])) return "polygon points must be finite";
        const tt_vec2 p = b->points[i], q = b->points[(i + 1) % b->count], r = b->points[(i + 2) % b->count];
        /* every turn to the left: convex and counter-clockwise, as Box2D needs */
        if ((q.x - p.x) * (r.y - q.y) - (q.y - p.y) * (r.x - q.x) <= 1e-12) return "a polygon must be convex and counter-clockwise";
    }
    return NULL;
}

const char *ts_body_check(const ts_body *b)
{
    if (!b) return "body is NULL";
    if (!finite_vec(b->position) || !finite_vec(b->velocity)) return "position and velocity must be finite (|x| <= 1e9)";
    if (!isfinite(b->angle) || !isfinite(b->spin)) return "angle and spin must be finite";
    if (!(b->friction >= 0 && b->friction <= 1e3)) return "friction must be in [0, 1000]";
    if (!(b->restitution >= 0 && b->restitution <= 1)) return "restitution must be in [0, 1]";
    if (b->dynamic && !(b->density > 0 && b->density <= 1e9)) return "a dynamic body's density must be in (0, 1e9]";
    switch (b->shape) {
    case TS_CIRCLE:
        return b->radius > 0 && b->radius <= 1e6 ? NULL : "a circle's radius must be in (0, 1e6]";
    case TS_BOX:
        return b->half.x > 0 && b->half.y > 0 && finite_vec(b->half) ? NULL : "a box's half extents must be > 0 and finite";
    case TS_POLYGON:
        return check_polygon(b);
    case TS_EDGE:
        if (b->dynamic) return "an edge can only be static";
        if (!finite_vec(b->a) || !finite_vec(b->b)) return "edge ends must be finite";
        return hypot(b->b.x - b->a.x, b->b.y - b->a.y) > 1e-6 ? NULL : "an edge must be longer than 1e-6";
    }
    return "unknown shape";
}

static bool grow(void **p, uint32_t *cap, uint32_t need, size_t size)
{
    if (need <= *cap) return true;
    uint32_t c = *cap ? *cap : 16;
    while (c < need) c *= 2;
    void *q = realloc(*p, (size_t)c * size);
    if (!q) return false;
    *p = q;
    *cap = c;
    return true;
}

int32_t ts_scene_add_body(ts_scene *s, const ts_body *b, const char **why)
{
    const char *bad = ts_body_check(b);
    if (!bad && s->body_count >= TS_MAX_BODIES) bad = "too many bodies";
    if (!bad && !grow((void **)&s->bodies, &s->body_cap, s->body_count + 1, sizeof *s->bodies)) bad = "out of memory";
    if (bad) {
        if (why) *why = bad;
        return -1;
    }
    s->bodies[s->body_count] = *b;
    return (int32_t)s->body_count++;
}

int32_t ts_scene_add_joint(ts_scene *s, const ts_joint *j, const char **why)
{
    const char *bad = NULL;
    const int32_t n = (int32_t)s->body_count;
    if (!j) bad = "joint is NULL";
    else if (j->kind > TS_WELD) bad = "unknown joint kind";
    else if (j->a < TS_GROUND || j->a >= n || j->b < 0 || j->b >= n) bad = "joint bodies must be earlier bodies (a may be ground, -1)";
    else if (j->a == j->b) bad = "a joint needs two different bodies";
    else if (!s->bodies[j->b].dynamic) bad = "a joint's body b must be dynamic";
    else if (!finite_vec(j->anchor_a) || !finite_vec(j->anchor_b)) bad = "anchors must be finite";
    else if (!grow((void **)&s->joints, &s->joint_cap, s->joint_count + 1, sizeof *s->joints)) bad = "out of memory";
    if (bad) {
        if (why) *why = bad;
        return -1;
    }
    s->joints[s->joint_count] = *j;
    return (int32_t)s->joint_count++;
}

static double area(const ts_body *b)
{
    switch (b->shape) {
    case TS_CIRCLE: return M_PI * b->radius * b->radius;
    case TS_BOX: return 4 * b->half.x * b->half.y;
    case TS_POLYGON: return 0.5 * twice_area(b->points, b->count);
    case TS_EDGE: return 0;
    }
    return 0;
}

double ts_body_mass(const ts_body *b) { return b->dynamic ? b->density * area(b) : 0; }

double ts_body_inertia(const ts_body *b)
{
    const double m = ts_body_mass(b);
    switch (b->shape) {
    case TS_CIRCLE: return 0.5 * m * b->radius * b->radius;
    case TS_BOX: return m * (b->half.x * b->half.x + b->half.y * b->half.y) / 3;
    case TS_POLYGON: {
        /* triangles fanned from the origin, then moved to the centroid (parallel axes) */
        double I = 0, cx = 0, cy = 0, A = 0;
        for (uint32_t i = 0; i < b->count; i++) {
            const tt_vec2 p = b->points[i], q = b->points[(i + 1) % b->count];
            const double c = p.x * q.y - p.y * q.x;
            A += c / 2;
            cx += c * (p.x + q.x) / 6;
            cy += c * (p.y + q.y) / 6;
            I += c * (p.x * p.x + p.x * q.x + q.x * q.x + p.y * p.y + p.y * q.y + q.y * q.y) / 12;
        }
        cx /= A;
        cy /= A;
        return b->density * I - m * (cx * cx + cy * cy);
    }
    case TS_EDGE: return 0;
    }
    return 0;
}
