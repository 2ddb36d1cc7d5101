/* tether — outlines as geometry: marching squares over a mask, giving
 * closed polylines, then Douglas-Peucker simplification.
 *
 * The boundary between set and clear pixels is followed along pixel edges
 * ("crack following"), keeping set pixels on the left of travel; the
 * marching-squares vertices are then the midpoints of consecutive boundary
 * edges (where the 0.5 level crosses between two pixel centres). Following
 * the cracks rather than visiting cells makes every loop come out closed
 * and in order with no stitching. Where two set pixels touch only at a
 * corner, the walk turns so that they stay one region (8-connectivity, as
 * the components use). A staircase becomes a straight slope, and a disc's
 * polygon loses only about half a pixel of area (each convex corner cuts
 * 1/8 pixel, each concave one adds 1/8). */
#include "mask_internal.h"

#include <stdlib.h>

/* Directions on screen (y down): right, down, left, up. */
static const int DX[4] = { 1, 0, -1, 0 }, DY[4] = { 0, 1, 0, -1 };

static int px(const tt_mask *m, int x, int y)
{
    return x >= 0 && y >= 0 && x < m->w && y < m->h && tt__mask_bit(m, x, y);
}

/* Pixels ahead-left and ahead-right of a walker at corner (x, y) facing d. */
static void ahead(const tt_mask *m, int x, int y, int d, int *l, int *r)
{
    /* the pixel whose top-left corner is (x, y) is (x, y); the four around the corner: */
    static const int LX[4] = { 0, 0, -1, -1 }, LY[4] = { -1, 0, 0, -1 };
    static const int RX[4] = { 0, -1, -1, 0 }, RY[4] = { 0, 0, -1, -1 };
    *l = px(m, x + LX[d], y + LY[d]);
    *r = px(m, x + RX[d], y + RY[d]);
}

typedef struct vbuf {
    tt_vec2 *p;
    uint32_t n, cap;
} vbuf;

static bool vpush(vbuf *b, double x, double y)
{
    if (b->n == b->cap) {
        uint32_t cap = b->cap ? b->cap * 2 : 64;
        tt_vec2 *p = realloc(b->p, cap * sizeof *p);
        if (!p) return false;
        b->p = p;
        b->cap = cap;
    }
    b->p[b->n++] = (tt_vec2){ x, y };
    return true;
}

/* Horizontal edge (x…x+1 on line y) and vertical edge (y…y+1 on line x) indices. */
static size_t hidx(const tt_mask *m, int x, int y) { return (size_t)y * (size_t)(m->w + 1) + (size_t)x; }

/* Walks the loop starting on the horizontal edge at (x, y) facing d (0 or 2),
 * marking horizontal edges in seen, pushing edge midpoints into out. */
static bool walk(const tt_mask *m, int x, int y, int d, unsigned char *seen, vbuf *out)
{
    const int x0 = x, y0 = y, d0 = d;
    do {
        if (d == 0 || d == 2) seen[hidx(m, d == 0 ? x : x - 1, y)] = 1;
        if (!vpush(out, x + DX[d] * 0.5, y + DY[d] * 0.5)) return false;
        x += DX[d];
        y += DY[d];
        int l, r;
        ahead(m, x, y, d, &l, &r);
        if (r) d = (d + 1) & 3;      /* right turn: also joins pixels touching at a corner */
        else if (!l) d = (d + 3) & 3; /* left turn */
    } while (x != x0 || y != y0 || d != d0);
    return true;
}

/* Squared distance from p to the line through a and b (to a when they coincide). */
static double dist2(tt_vec2 p, tt_vec2 a, tt_vec2 b)
{
    double ux = b.x - a.x, uy = b.y - a.y, vx = p.x - a.x, vy = p.y - a.y, l2 = ux * ux + uy * uy;
    if (l2 == 0) return vx * vx + vy * vy;
    double c = ux * vy - uy * vx;
    return c * c / l2;
}

/* Douglas-Peucker on p[i0..i1] (indices mod n), marking kept points; an explicit
 * stack, since a long outline would recurse as deep as it has points. */
static bool dp(const tt_vec2 *p, uint32_t n, uint32_t i0, uint32_t i1, double tol2, unsigned char *keep)
{
    uint32_t cap = 64, top = 0, *st = malloc(cap * 2 * sizeof *st);
    if (!st) return false;
    st[0] = i0;
    st[1] = i1;
    top = 1;
    while (top) {
        top--;
        uint32_t a = st[2 * top], b = st[2 * top + 1], best = a;
        double far = -1;
        for (uint32_t i = a + 1; i < b; i++) {
            double d2 = dist2(p[i % n], p[a % n], p[b % n]);
            if (d2 > far) { far = d2; best = i; }
        }
        if (best == a || far <= tol2) continue;
        keep[best % n] = 1;
        if (top + 2 > cap) {
            uint32_t *s2 = realloc(st, cap * 4 * sizeof *st);
            if (!s2) { free(st); return false; }
            st = s2;
            cap *= 2;
        }
        st[2 * top] = a; st[2 * top + 1] = best; top++;
        st[2 * top] = best; st[2 * top + 1] = b; top++;
    }
    free(st);
    return true;
}

/* Simplifies the closed loop in b in place: anchors at point 0 and the point
 * farthest from it, each half simplified, at least three points kept. */
static bool simplify(vbuf *b, double tol)
{
    uint32_t n = b->n, far = 0;
    unsigned char *keep = calloc(n, 1);
    if (!keep) return false;
    double best = -1;
    for (uint32_t i = 1; i < n; i++) {
        double dx = b->p[i].x - b->p[0].x, dy = b->p[i].y - b->p[0].y;
        if (dx * dx + dy * dy > best) { best = dx * dx + dy * dy; far = i; }
    }
    keep[0] = keep[far] = 1;
    bool ok = dp(b->p, n, 0, far, tol * tol, keep) && dp(b->p, n, far, n, tol * tol, keep);
    uint32_t k = 0;
    for (uint32_t i = 0; i < n; i++) k += keep[i];
    if (ok && k < 3) { /* a sliver: keep its point farthest from the anchors' line too */
        uint32_t w = 0;
        double wd = -1;
        for (uint32_t i = 1; i < n; i++) {
            double d2 = dist2(b->p[i], b->p[0], b->p[far]);
            if (i != far && d2 > wd) { wd = d2; w = i; }
        }
        keep[w] = 1;
    }
    k = 0;
    for (uint32_t i = 0; i < n; i++)
        if (keep[i]) b->p[k++] = b->p[i];
    b->n = k;
    free(keep);
    return ok;
}

void tt_mask_polylines_free(tt_mask_polyline *lines, uint32_t count)
{
    if (!lines) return;
    for (uint32_t i = 0; i < count; i++) free(lines[i].points);
    free(lines);
}

/* Appends b (its buffer handed over) to the list. */
static bool add_line(tt_mask_polyline **lines, uint32_t *n, uint32_t *cap, vbuf *b)
{
    if (*n == *cap) {
        uint32_t c = *cap ? *cap * 2 : 8;
        tt_mask_polyline *l = realloc(*lines, c * sizeof *l);
        if (!l) return false;
        *lines = l;
        *cap = c;
    }
    (*lines)[(*n)++] = (tt_mask_polyline){ b->p, b->n };
    *b = (vbuf){ NULL, 0, 0 };
    return true;
}

/* Every loop, found from its horizontal edges not yet walked (each loop has some). */
static bool trace_all(const tt_mask *m, double tol, unsigned char *seen, tt_mask_polyline **lines, uint32_t *n)
{
    uint32_t cap = 0;
    vbuf b = { NULL, 0, 0 };
    for (int y = 0; y <= m->h; y++)
        for (int x = 0; x < m->w; x++) {
            int above = px(m, x, y - 1), below = px(m, x, y);
            if (above == below || seen[hidx(m, x, y)]) continue;
            bool ok = below ? walk(m, x + 1, y, 2, seen, &b) : walk(m, x, y, 0, seen, &b);
            if (!ok || !simplify(&b, tol) || !add_line(lines, n, &cap, &b)) {
                free(b.p);
                return false;
            }
        }
    return true;
}

tt_result tt_mask_polylines(const tt_mask *m, double tolerance, tt_mask_polyline **lines, uint32_t *count)
{
    const char *fn = "tt_mask_polylines";
    if (!m || !lines || !count) return tt__mask_fail(TT_EINVAL, "%s: %s is NULL", fn, !m ? "mask" : !lines ? "lines" : "count");
    if (!(tolerance >= 0 && tolerance <= 1e6))
        return tt__mask_fail(TT_EINVAL, "%s: tolerance %g outside 0…1e6 pixels", fn, tolerance);
    *lines = NULL;
    *count = 0;
    unsigned char *seen = calloc((size_t)(m->w + 1) * (size_t)(m->h + 1), 1);
    if (!seen) return tt__mask_fail(TT_ENOMEM, "%s: out of memory", fn);
    bool ok = trace_all(m, tolerance, seen, lines, count);
    free(seen);
    if (!ok) {
        tt_mask_polylines_free(*lines, *count);
        *lines = NULL;
        *count = 0;
        return tt__mask_fail(TT_ENOMEM, "%s: out of memory", fn);
    }
    return TT_OK;
}
