/* tether — narrowphase: a circle (a particle) against one primitive, rays
 * against primitives and circles, primitives against boxes. Every test
 * gives the contact normal (from the shape to the particle), the depth and
 * hence the nearest valid position x + n·depth, as the seed asks. */
#include "collide_internal.h"

/* Closest point to (x, y) on the segment a–b. */
static void closest_on_segment(double ax, double ay, double bx, double by, double x, double y, double *qx, double *qy)
{
    double ex = bx - ax, ey = by - ay, l2 = ex * ex + ey * ey;
    double t = l2 > 0.0 ? ((x - ax) * ex + (y - ay) * ey) / l2 : 0.0;
    if (t < 0.0) t = 0.0;
    if (t > 1.0) t = 1.0;
    *qx = ax + ex * t;
    *qy = ay + ey * t;
}

void tt__circle_vs_prim(const tt__collide *c, const tt__prim *p, double x, double y, double r, tt__hit *out)
{
    if (p->kind == TT__PRIM_CAPSULE) {
        double qx, qy;
        closest_on_segment(p->ax, p->ay, p->bx, p->by, x, y, &qx, &qy);
        double dx = x - qx, dy = y - qy, d = sqrt(dx * dx + dy * dy);
        if (d > 0.0) {
            out->nx = dx / d;
            out->ny = dy / d;
        } else { /* centre on the core segment: its left normal (or up for a point) */
            double ex = p->bx - p->ax, ey = p->by - p->ay, l = sqrt(ex * ex + ey * ey);
            out->nx = l > 0.0 ? -ey / l : 0.0;
            out->ny = l > 0.0 ? ex / l : 1.0;
        }
        out->depth = r + p->r - d;
        return;
    }
    const tt_vec2 *v = c->verts + p->v0, *n = c->norms + p->v0;
    double smax = -INFINITY;
    uint32_t kmax = 0;
    for (uint32_t k = 0; k < p->nv; k++) {
        double s = n[k].x * (x - v[k].x) + n[k].y * (y - v[k].y);
        if (s > smax) {
            smax = s;
            kmax = k;
        }
    }
    if (smax <= 0.0) { /* centre inside: out through the nearest face */
        out->nx = n[kmax].x;
        out->ny = n[kmax].y;
        out->depth = r - smax;
        return;
    }
    if (smax > r + r + 1e-300) { /* far: the face distance is a lower bound of the gap */
        out->nx = n[kmax].x;
        out->ny = n[kmax].y;
        out->depth = r - smax;
        return;
    }
    double best = INFINITY, bx = 0, by = 0;
    for (uint32_t k = 0; k < p->nv; k++) {
        const tt_vec2 a = v[k], b = v[k + 1 == p->nv ? 0 : k + 1];
        double qx, qy;
        closest_on_segment(a.x, a.y, b.x, b.y, x, y, &qx, &qy);
        double d2 = (x - qx) * (x - qx) + (y - qy) * (y - qy);
        if (d2 < best) {
            best = d2;
            bx = qx;
            by = qy;
        }
    }
    double d = sqrt(best);
    if (d > 0.0) {
        out->nx = (x - bx) / d;
        out->ny = (y - by) / d;
    } else {
        out->nx = n[kmax].x;
        out->ny = n[kmax].y;
    }
    out->depth = r - d;
}

bool tt__ray_vs_circle(double ox, double oy, double dx, double dy, double cx, double cy, double r, double tmax,
                       double *t, double *nx, double *ny)
{
    double fx = ox - cx, fy = oy - cy;
    double a = dx * dx + dy * dy, b = fx * dx + fy * dy, cc = fx * fx + fy * fy - r * r;
    if (cc <= 0.0) { /* starts inside */
        double l = sqrt(a);
        *t = 0.0;
        *nx = l > 0.0 ? -dx / l : 0.0;
        *ny = l > 0.0 ? -dy / l : 1.0;
        return true;
    }
    if (a == 0.0 || b >= 0.0) return false;
    double disc = b * b - a * cc;
    if (disc < 0.0) return false;
    double tt = (-b - sqrt(disc)) / a;
    if (tt < 0.0 || tt > tmax) return false;
    *t = tt;
    double hx = ox + dx * tt - cx, hy = oy + dy * tt - cy, l = sqrt(hx * hx + hy * hy);
    *nx = l > 0.0 ? hx / l : 0.0;
    *ny = l > 0.0 ? hy / l : 1.0;
    return true;
}

/* A ray exactly along a segment of no radius: parallel to both faces, and
 * no end circles, so the general test lets it through. It meets the nearer
 * end point (at once when it starts between them), the normal facing the
 * ray, as a capsule's end cap does as its radius goes to 0. */
static bool ray_along_segment(double ox, double oy, double dx, double dy, double ax, double ay, double bx, double by,
                              double tmax, double *t, double *nx, double *ny)
{
    const double dd = dx * dx + dy * dy;
    const double ta = ((ax - ox) * dx + (ay - oy) * dy) / dd, tb = ((bx - ox) * dx + (by - oy) * dy) / dd;
    const double tnear = fmin(ta, tb), tfar = fmax(ta, tb);
    if (tfar < 0.0) return false; /* behind the start */
    const double tt = tnear > 0.0 ? tnear : 0.0;
    if (tt > tmax) return false;
    const double dl = sqrt(dd);
    *t = tt;
    *nx = -dx / dl;
    *ny = -dy / dl;
    return true;
}

/* Ray against a rounded segment a–b of radius r: the two offset faces and the end circles. */
static bool ray_vs_capsule(double ox, double oy, double dx, double dy, double ax, double ay, double bx, double by,
                           double r, double tmax, double *t, double *nx, double *ny)
{
    bool hit = false;
    double best = tmax, tx, nnx, nny;
    double ex = bx - ax, ey = by - ay, l = sqrt(ex * ex + ey * ey);
    /* exactly on the line: tested on the raw products, since the unit
     * direction below rounds and would make the faces graze it instead */
    if (r == 0.0 && l > 0.0 && (dx != 0.0 || dy != 0.0) && dx * ey == dy * ex && (ox - ax) * ey == (oy - ay) * ex)
        return ray_along_segment(ox, oy, dx, dy, ax, ay, bx, by, tmax, t, nx, ny);
    if (l > 0.0) {
        double ux = ex / l, uy = ey / l;
        /* inside the straight part at the start? */
        double s0 = (ox - ax) * ux + (oy - ay) * uy, h0 = -(ox - ax) * uy + (oy - ay) * ux;
        if (s0 >= 0.0 && s0 <= l && fabs(h0) <= r) {
            double dl = sqrt(dx * dx + dy * dy);
            *t = 0.0;
            *nx = dl > 0.0 ? -dx / dl : 0.0;
            *ny = dl > 0.0 ? -dy / dl : 1.0;
            return true;
        }
        for (int side = -1; side <= 1; side += 2) {
            double mx = -uy * side, my = ux * side; /* face normal */
            double den = dx * mx + dy * my;
            if (den >= 0.0) continue;
            double dist0 = (ox - ax) * mx + (oy - ay) * my;
            if (dist0 < r) continue;
            double tt = (r - dist0) / den;
            if (tt < 0.0 || tt > best) continue;
            double px = ox + dx * tt - ax, py = oy + dy * tt - ay, s = px * ux + py * uy;
            if (s < 0.0 || s > l) continue;
            best = tt;
            *nx = mx;
            *ny = my;
            hit = true;
        }
    }
    if (r > 0.0 || l == 0.0) {
        if (tt__ray_vs_circle(ox, oy, dx, dy, ax, ay, r, best, &tx, &nnx, &nny) && (!hit || tx < best)) {
            best = tx;
            *nx = nnx;
            *ny = nny;
            hit = true;
        }
        if (l > 0.0 && tt__ray_vs_circle(ox, oy, dx, dy, bx, by, r, best, &tx, &nnx, &nny) && (!hit || tx < best)) {
            best = tx;
            *nx = nnx;
            *ny = nny;
            hit = true;
        }
    }
    if (hit) *t = best;
    return hit;
}

bool tt__ray_vs_prim(const tt__collide *c, const tt__prim *p, double ox, double oy, double dx, double dy,
                     double rr, double tmax, double *t, double *nx, double *ny)
{
    if (p->kind == TT__PRIM_CAPSULE)
        return ray_vs_capsule(ox, oy, dx, dy, p->ax, p->ay, p->bx, p->by, p->r + rr, tmax, t, nx, ny);
    const tt_vec2 *v = c->verts + p->v0, *n = c->norms + p->v0;
    /* Cyrus–Beck clipping against the polygon itself. */
    double tin = 0.0, tout = tmax;
    int face = -1;
    bool inside = true, miss = false;
    for (uint32_t k = 0; k < p->nv && !miss; k++) {
        double num = n[k].x * (ox - v[k].x) + n[k].y * (oy - v[k].y); /* > 0 outside this face */
        double den = n[k].x * dx + n[k].y * dy;
        if (num > 0.0) inside = false;
        if (den == 0.0) {
            if (num > 0.0) miss = true;
            continue;
        }
        double tt = -num / den;
        if (den < 0.0) {
            if (tt > tin) { tin = tt; face = (int)k; }
        } else if (tt < tout) {
            tout = tt;
        }
        if (tin > tout) miss = true;
    }
    bool hit = false;
    double best = tmax;
    if (inside) {
        double dl = sqrt(dx * dx + dy * dy);
        *t = 0.0;
        *nx = dl > 0.0 ? -dx / dl : 0.0;
        *ny = dl > 0.0 ? -dy / dl : 1.0;
        return true;
    }
    if (!miss && face >= 0 && tin <= tmax) {
        best = tin;
        *nx = n[face].x;
        *ny = n[face].y;
        hit = true;
    }
    if (rr > 0.0) { /* the rounded rim: each edge as a capsule of radius rr */
        for (uint32_t k = 0; k < p->nv; k++) {
            const tt_vec2 a = v[k], b = v[k + 1 == p->nv ? 0 : k + 1];
            double tt, mx, my;
            if (ray_vs_capsule(ox, oy, dx, dy, a.x, a.y, b.x, b.y, rr, best, &tt, &mx, &my) && (!hit || tt < best)) {
                best = tt;
                *nx = mx;
                *ny = my;
                hit = true;
            }
        }
    }
    if (hit) *t = best;
    return hit;
}

/* Squared distance from a point to a box. */
static double point_box_d2(double x, double y, double lox, double loy, double hix, double hiy)
{
    double dx = x < lox ? lox - x : x > hix ? x - hix : 0.0;
    double dy = y < loy ? loy - y : y > hiy ? y - hiy : 0.0;
    return dx * dx + dy * dy;
}

static bool segment_meets_box(double ax, double ay, double bx, double by, double lox, double loy, double hix, double hiy)
{
    double t0 = 0.0, t1 = 1.0, d[2] = {bx - ax, by - ay}, o[2] = {ax, ay}, lo[2] = {lox, loy}, hi[2] = {hix, hiy};
    for (int k = 0; k < 2; k++) {
        if (d[k] == 0.0) {
            if (o[k] < lo[k] || o[k] > hi[k]) return false;
            continue;
        }
        double ta = (lo[k] - o[k]) / d[k], tb = (hi[k] - o[k]) / d[k];
        if (ta > tb) { double s = ta; ta = tb; tb = s; }
        if (ta > t0) t0 = ta;
        if (tb < t1) t1 = tb;
        if (t0 > t1) return false;
    }
    return true;
}

bool tt__prim_vs_aabb(const tt__collide *c, const tt__prim *p, double lox, double loy, double hix, double hiy)
{
    if (!tt__prim_box_meets(p, lox, loy, hix, hiy)) return false;
    if (p->kind == TT__PRIM_CAPSULE) {
        if (segment_meets_box(p->ax, p->ay, p->bx, p->by, lox, loy, hix, hiy)) return true;
        double r2 = p->r * p->r, best = fmin(point_box_d2(p->ax, p->ay, lox, loy, hix, hiy),
                                            point_box_d2(p->bx, p->by, lox, loy, hix, hiy));
        const double cx[4] = {lox, hix, hix, lox}, cy[4] = {loy, loy, hiy, hiy};
        for (int k = 0; k < 4; k++) {
            double qx, qy;
            closest_on_segment(p->ax, p->ay, p->bx, p->by, cx[k], cy[k], &qx, &qy);
            best = fmin(best, (qx - cx[k]) * (qx - cx[k]) + (qy - cy[k]) * (qy - cy[k]));
        }
        return best <= r2;
    }
    /* Separating axes: the box's two (already passed above) and the polygon's normals. */
    const tt_vec2 *v = c->verts + p->v0, *n = c->norms + p->v0;
    const double cx[4] = {lox, hix, hix, lox}, cy[4] = {loy, loy, hiy, hiy};
    for (uint32_t k = 0; k < p->nv; k++) {
        double best = INFINITY;
        for (int j = 0; j < 4; j++) best = fmin(best, n[k].x * (cx[j] - v[k].x) + n[k].y * (cy[j] - v[k].y));
        if (best > 0.0) return false;
    }
    return true;
}
