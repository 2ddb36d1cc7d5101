/* tether — the static index: every shape as primitives in world
 * coordinates, and a uniform grid over primitive boxes, built once and
 * rebuilt only when a shape is added, removed or moved; and the freeing
 * and size of the shapes' storage with it (the group's destroy and memory
 * hooks, contacts.c, use them). */
#include "collide_internal.h"

#include <string.h>

/* --- primitives --------------------------------------------------------- */

/* Where a shape stands: its def's transform, or a point of its path. */
typedef struct placement {
    tt_vec2 at;
    double cs, sn;
} placement;

static placement placed_at(tt_vec2 at, double angle) { return (placement){at, cos(angle), sin(angle)}; }

static tt_vec2 place(const placement *t, tt_vec2 p)
{
    return (tt_vec2){t->at.x + t->cs * p.x - t->sn * p.y, t->at.y + t->sn * p.x + t->cs * p.y};
}

static tt__prim *new_prim(tt__collide *c, uint32_t shape)
{
    if (!tt__grow((void **)&c->prims, &c->primcap, c->nprim + 1, sizeof *c->prims)) return NULL;
    tt__prim *p = &c->prims[c->nprim++];
    memset(p, 0, sizeof *p);
    p->shape = shape;
    return p;
}

static bool add_capsule(tt__collide *c, uint32_t shape, tt_vec2 a, tt_vec2 b, double r)
{
    tt__prim *p = new_prim(c, shape);
    if (!p) return false;
    p->kind = TT__PRIM_CAPSULE;
    p->ax = a.x; p->ay = a.y; p->bx = b.x; p->by = b.y; p->r = r;
    p->lox = fmin(a.x, b.x) - r; p->hix = fmax(a.x, b.x) + r;
    p->loy = fmin(a.y, b.y) - r; p->hiy = fmax(a.y, b.y) + r;
    return true;
}

/* The length of edge (ex, ey), 0 only when it has none: where its squares
 * underflow (a box of half extents 1e-300) it is measured scaled by 2^600,
 * exactly, so every other edge gets the same bits as before. */
static double edge_length(double *ex, double *ey)
{
    const double l = sqrt(*ex * *ex + *ey * *ey);
    if (l >= 0x1p-500) return l;
    *ex *= 0x1p600;
    *ey *= 0x1p600;
    return sqrt(*ex * *ex + *ey * *ey);
}

/* A polygon whose corners meet (a tiny box far out, a zero-size aabb) has
 * an edge with no direction: it is the segment between its two corners
 * furthest apart (a point when they all meet), a capsule of radius 0. */
static bool add_collapsed(tt__collide *c, uint32_t shape, const tt_vec2 *pts, uint32_t n)
{
    uint32_t i0 = 0, j0 = 0;
    double best = -1.0;
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = i + 1; j < n; j++) {
            const double dx = pts[j].x - pts[i].x, dy = pts[j].y - pts[i].y, d = dx * dx + dy * dy;
            if (d > best) best = d, i0 = i, j0 = j;
        }
    return add_capsule(c, shape, pts[i0], pts[j0], 0.0);
}

/* A convex polygon from world points, turned counter-clockwise, with
 * outward normals. The corners and normals are written past the last
 * polygon's first (room nobody reads until nvert grows), so a polygon with
 * an edge of no length goes to add_collapsed before any primitive is made. */
static bool add_poly(tt__collide *c, uint32_t shape, const tt_vec2 *pts, uint32_t n)
{
    if (!tt__grow((void **)&c->verts, &c->vertcap, c->nvert + n, sizeof *c->verts)) return false;
    if (!tt__grow((void **)&c->norms, &c->normcap, c->vertcap, sizeof *c->norms)) return false;
    double area = 0.0;
    for (uint32_t k = 0; k < n; k++) area += pts[k].x * pts[(k + 1) % n].y - pts[(k + 1) % n].x * pts[k].y;
    tt_vec2 *v = c->verts + c->nvert, *nrm = c->norms + c->nvert;
    for (uint32_t k = 0; k < n; k++) v[k] = pts[area >= 0.0 ? k : n - 1 - k];
    for (uint32_t k = 0; k < n; k++) {
        double ex = v[(k + 1) % n].x - v[k].x, ey = v[(k + 1) % n].y - v[k].y;
        const double l = edge_length(&ex, &ey);
        if (!(l > 0.0)) return add_collapsed(c, shape, pts, n);
        nrm[k] = (tt_vec2){ey / l, -ex / l};
    }
    tt__prim *p = new_prim(c, shape);
    if (!p) return false;
    p->kind = TT__PRIM_POLY;
    p->v0 = c->nvert;
    p->nv = n;
    p->lox = p->hix = v[0].x;
    p->loy = p->hiy = v[0].y;
    for (uint32_t k = 0; k < n; k++) {
        p->lox = fmin(p->lox, v[k].x); p->hix = fmax(p->hix, v[k].x);
        p->loy = fmin(p->loy, v[k].y); p->hiy = fmax(p->hiy, v[k].y);
    }
    c->nvert += n;
    return true;
}

static bool shape_prims(tt__collide *c, uint32_t i, const placement *t)
{
    const tt__shape *s = &c->shapes[i];
    const tt_shape_def *d = &s->def;
    switch (d->type) {
    case TT_SHAPE_SEGMENT: return add_capsule(c, i, place(t, d->a), place(t, d->b), 0.0);
    case TT_SHAPE_CAPSULE: return add_capsule(c, i, place(t, d->a), place(t, d->b), d->radius);
    case TT_SHAPE_CIRCLE: { tt_vec2 o = place(t, (tt_vec2){0, 0}); return add_capsule(c, i, o, o, d->radius); }
    case TT_SHAPE_CHAIN: {
        uint32_t segs = d->loop ? d->count : d->count - 1;
        for (uint32_t k = 0; k < segs; k++)
            if (!add_capsule(c, i, place(t, s->pts[k]), place(t, s->pts[(k + 1) % d->count]), 0.0)) return false;
        return true;
    }
    case TT_SHAPE_AABB:
    case TT_SHAPE_BOX: {
        tt_vec2 q[4];
        if (d->type == TT_SHAPE_AABB) {
            tt_vec2 lo = d->a, hi = d->b;
            q[0] = (tt_vec2){lo.x, lo.y}; q[1] = (tt_vec2){hi.x, lo.y}; q[2] = (tt_vec2){hi.x, hi.y}; q[3] = (tt_vec2){lo.x, hi.y};
        } else {
            double hx = d->half_extents.x, hy = d->half_extents.y;
            q[0] = (tt_vec2){-hx, -hy}; q[1] = (tt_vec2){hx, -hy}; q[2] = (tt_vec2){hx, hy}; q[3] = (tt_vec2){-hx, hy};
        }
        for (int k = 0; k < 4; k++) q[k] = place(t, q[k]);
        if (q[0].x == q[1].x && q[0].y == q[1].y) return add_capsule(c, i, q[0], q[2], 0.0); /* degenerate aabb: a segment */
        if (q[1].x == q[2].x && q[1].y == q[2].y) return add_capsule(c, i, q[0], q[1], 0.0);
        return add_poly(c, i, q, 4);
    }
    case TT_SHAPE_POLYGON: {
        tt_vec2 q[TT_MAX_POLYGON_POINTS];
        for (uint32_t k = 0; k < d->count; k++) q[k] = place(t, s->pts[k]);
        return add_poly(c, i, q, d->count);
    }
    default: return true;
    }
}

/* --- static index ------------------------------------------------------- */

static void cell_range(const tt__sgrid *g, double lox, double loy, double hix, double hiy,
                       int32_t *x0, int32_t *y0, int32_t *x1, int32_t *y1)
{
    *x0 = tt__cell_coord(lox, g->ox, g->inv); *x1 = tt__cell_coord(hix, g->ox, g->inv);
    *y0 = tt__cell_coord(loy, g->oy, g->inv); *y1 = tt__cell_coord(hiy, g->oy, g->inv);
    if (*x0 < 0) *x0 = 0;
    if (*y0 < 0) *y0 = 0;
    if (*x1 >= g->nx) *x1 = g->nx - 1;
    if (*y1 >= g->ny) *y1 = g->ny - 1;
}

enum { BIG_CELLS = 4096 };

/* A moved shape's primitives where the script put it, each box grown to
 * hold the primitive where the path starts too: the index then holds the
 * whole path, and each substep only re-places the primitives. */
static bool moved_prims(tt__collide *c, uint32_t i)
{
    tt__shape *s = &c->shapes[i];
    const placement to = placed_at(s->def.position, s->def.angle), from = placed_at(s->from, s->from_angle);
    if (!shape_prims(c, i, &to)) return false;
    const uint32_t end = c->nprim, vend = c->nvert;
    if (!shape_prims(c, i, &from)) return false; /* after them, for their boxes */
    for (uint32_t k = s->prim0; k < end; k++) {
        tt__prim *p = &c->prims[k];
        const tt__prim *q = &c->prims[end + (k - s->prim0)];
        p->lox = fmin(p->lox, q->lox); p->loy = fmin(p->loy, q->loy);
        p->hix = fmax(p->hix, q->hix); p->hiy = fmax(p->hiy, q->hiy);
    }
    c->nprim = end;
    c->nvert = vend;
    return true;
}

tt_result tt__shapes_rebuild(tt_world *w, tt__collide *c)
{
    c->nprim = 0;
    c->nvert = 0;
    for (uint32_t i = 0; i < c->spool.count; i++) {
        tt__shape *s = &c->shapes[i];
        if (!s->alive) continue;
        s->prim0 = c->nprim;
        s->vert0 = c->nvert;
        const placement t = placed_at(s->def.position, s->def.angle);
        if (!(s->moved ? moved_prims(c, i) : shape_prims(c, i, &t)))
            return tt__fail(w, TT_ENOMEM, "collisions: out of memory for shapes");
    }
    tt__sgrid *g = &c->sgrid;
    g->nbig = 0;
    if (c->nprim == 0) {
        g->nx = g->ny = 0;
        c->dirty = false;
        c->static_rebuilds++;
        return TT_OK;
    }
    double lox = INFINITY, loy = INFINITY, hix = -INFINITY, hiy = -INFINITY;
    for (uint32_t k = 0; k < c->nprim; k++) {
        lox = fmin(lox, c->prims[k].lox); loy = fmin(loy, c->prims[k].loy);
        hix = fmax(hix, c->prims[k].hix); hiy = fmax(hiy, c->prims[k].hiy);
    }
    /* About 16 cells per primitive (at least 4096, at most 2^20), square cells. */
    double ex = fmax(hix - lox, 1e-9), ey = fmax(hiy - loy, 1e-9);
    double cells = fmin(fmax(16.0 * c->nprim, 4096.0), 1048576.0);
    double cs = sqrt(ex * ey / cells);
    cs = fmax(cs, fmax(ex, ey) / 4096.0);
    g->cs = cs;
    g->inv = 1.0 / cs;
    g->ox = lox;
    g->oy = loy;
    g->nx = (int32_t)fmin(ex * g->inv + 1.0, 4096.0);
    g->ny = (int32_t)fmin(ey * g->inv + 1.0, 4096.0);
    uint32_t ncell = (uint32_t)g->nx * (uint32_t)g->ny;
    if (!tt__grow((void **)&g->start, &g->cap_cells, ncell + 1, sizeof *g->start))
        return tt__fail(w, TT_ENOMEM, "collisions: out of memory for the static index");
    memset(g->start, 0, (ncell + 1) * sizeof *g->start);
    /* count, then fill (CSR); primitives spanning too many cells go to the big list */
    for (int pass = 0; pass < 2; pass++) {
        g->nbig = 0;
        for (uint32_t k = 0; k < c->nprim; k++) {
            const tt__prim *p = &c->prims[k];
            int32_t x0, y0, x1, y1;
            cell_range(g, p->lox, p->loy, p->hix, p->hiy, &x0, &y0, &x1, &y1);
            if ((int64_t)(x1 - x0 + 1) * (y1 - y0 + 1) > BIG_CELLS) {
                if (pass == 1) {
                    if (!tt__grow((void **)&g->big, &g->cap_big, g->nbig + 1, sizeof *g->big))
                        return tt__fail(w, TT_ENOMEM, "collisions: out of memory for the static index");
                    g->big[g->nbig] = k;
                }
                g->nbig++;
                continue;
            }
            for (int32_t y = y0; y <= y1; y++)
                for (int32_t x = x0; x <= x1; x++) {
                    uint32_t cell = (uint32_t)y * (uint32_t)g->nx + (uint32_t)x;
                    if (pass == 0) g->start[cell + 1]++;
                    else g->items[g->start[cell]++] = k;
                }
        }
        if (pass == 0) {
            for (uint32_t k = 0; k < ncell; k++) g->start[k + 1] += g->start[k];
            if (!tt__grow((void **)&g->items, &g->cap_items, g->start[ncell] + 1, sizeof *g->items))
                return tt__fail(w, TT_ENOMEM, "collisions: out of memory for the static index");
        }
    }
    /* the fill pass advanced each start to the next cell's: shift back */
    for (uint32_t k = ncell; k > 0; k--) g->start[k] = g->start[k - 1];
    g->start[0] = 0;
    if (!tt__grow((void **)&c->pstamp, &c->pstamp_cap, c->nprim, sizeof *c->pstamp))
        return tt__fail(w, TT_ENOMEM, "collisions: out of memory for the static index");
    memset(c->pstamp, 0, (size_t)c->nprim * sizeof *c->pstamp);
    c->stamp = 0;
    c->dirty = false;
    c->static_rebuilds++;
    return TT_OK;
}

void tt__shapes_place_moved(const tt_world *w, tt__collide *c)
{
    if (!c->any_moved) return;
    const uint32_t n = c->nprim, nv = c->nvert;
    /* the end of substep k of m lies (k + 1)/m along the path; the last ends exactly where the script said */
    const double f = (double)(w->scr.substep + 1) / (double)w->scr.nsub;
    for (uint32_t i = 0; i < c->spool.count; i++) {
        tt__shape *s = &c->shapes[i];
        if (!s->alive || !s->moved) continue;
        const tt_vec2 to = s->def.position;
        const double ang0 = w->scr.substep == 0 ? s->from_angle : s->ang1;
        s->at0 = w->scr.substep == 0 ? s->from : s->at1;
        if (w->scr.substep + 1 >= w->scr.nsub) {
            s->at1 = to;
            s->ang1 = s->def.angle;
        } else {
            s->at1 = (tt_vec2){s->from.x + (to.x - s->from.x) * f, s->from.y + (to.y - s->from.y) * f};
            s->ang1 = s->from_angle + (s->def.angle - s->from_angle) * f;
        }
        s->turn_c = cos(s->ang1 - ang0);
        s->turn_s = sin(s->ang1 - ang0);
        /* rewritten in place: the same primitives and vertices, so nothing grows */
        const placement t = placed_at(s->at1, s->ang1);
        c->nprim = s->prim0;
        c->nvert = s->vert0;
        shape_prims(c, i, &t);
    }
    c->nprim = n;
    c->nvert = nv;
}

/* After a step that carried moved shapes: their primitives' boxes still
 * hold the whole path, and the index is built for them. The next step
 * rebuilds it for where the shapes now rest, as a world loaded from a
 * snapshot of this one does: the index decides the order shape contacts
 * are found and solved in, so both must be the same. */
void tt__shapes_arrived(tt__collide *c)
{
    c->dirty = true;
    for (uint32_t i = 0; i < c->spool.count; i++) {
        tt__shape *s = &c->shapes[i];
        s->from = s->def.position;
        s->from_angle = s->def.angle;
        s->moved = false;
    }
    c->any_moved = false;
}

bool tt__sgrid_near(const tt__collide *c, double lox, double loy, double hix, double hiy)
{
    const tt__sgrid *g = &c->sgrid;
    if (c->nprim == 0) return false;
    for (uint32_t k = 0; k < g->nbig; k++)
        if (tt__prim_box_meets(&c->prims[g->big[k]], lox, loy, hix, hiy)) return true;
    if (g->nx == 0) return false;
    if (hix < g->ox || hiy < g->oy || lox > g->ox + g->nx * g->cs || loy > g->oy + g->ny * g->cs) return false;
    int32_t x0, y0, x1, y1;
    cell_range(g, lox, loy, hix, hiy, &x0, &y0, &x1, &y1);
    for (int32_t y = y0; y <= y1; y++) { /* the cells of a row are contiguous in items */
        const uint32_t row = (uint32_t)y * (uint32_t)g->nx;
        for (uint32_t j = g->start[row + (uint32_t)x0]; j < g->start[row + (uint32_t)x1 + 1]; j++)
            if (tt__prim_box_meets(&c->prims[g->items[j]], lox, loy, hix, hiy)) return true;
    }
    return false;
}

void tt__sgrid_query(tt__collide *c, double lox, double loy, double hix, double hiy, tt__prim_visit visit, void *ctx)
{
    const tt__sgrid *g = &c->sgrid;
    if (c->nprim == 0) return;
    if (++c->stamp == 0) { /* wrapped: clear the marks */
        memset(c->pstamp, 0, (size_t)c->nprim * sizeof *c->pstamp);
        c->stamp = 1;
    }
    for (uint32_t k = 0; k < g->nbig; k++) {
        const tt__prim *p = &c->prims[g->big[k]];
        if (!tt__prim_box_meets(p, lox, loy, hix, hiy)) continue;
        c->pstamp[g->big[k]] = c->stamp;
        visit(ctx, g->big[k]);
    }
    if (g->nx == 0) return;
    if (hix < g->ox || hiy < g->oy || lox > g->ox + g->nx * g->cs || loy > g->oy + g->ny * g->cs) return;
    int32_t x0, y0, x1, y1;
    cell_range(g, lox, loy, hix, hiy, &x0, &y0, &x1, &y1);
    for (int32_t y = y0; y <= y1; y++)
        for (int32_t x = x0; x <= x1; x++) {
            uint32_t cell = (uint32_t)y * (uint32_t)g->nx + (uint32_t)x;
            for (uint32_t j = g->start[cell]; j < g->start[cell + 1]; j++) {
                uint32_t k = g->items[j];
                if (c->pstamp[k] == c->stamp) continue;
                c->pstamp[k] = c->stamp;
                const tt__prim *p = &c->prims[k];
                if (!tt__prim_box_meets(p, lox, loy, hix, hiy)) continue;
                visit(ctx, k);
            }
        }
}

/* --- storage ------------------------------------------------------------ */

void tt__shapes_free(tt__collide *c)
{
    /* a load that ran out of memory may leave the pool read and the array not made */
    for (uint32_t i = 0; c->shapes && i < c->spool.count; i++) free(c->shapes[i].pts);
    free(c->shapes);
    tt__pool_destroy(&c->spool);
    free(c->prims); free(c->verts); free(c->norms);
    free(c->sgrid.start); free(c->sgrid.items); free(c->sgrid.big);
    free(c->pstamp); free(c->sstamp);
}

size_t tt__shapes_bytes(const tt__collide *c)
{
    size_t b = (size_t)c->shcap * sizeof(tt__shape) + tt__pool_bytes(&c->spool);
    for (uint32_t i = 0; i < c->spool.count; i++)
        if (c->shapes[i].alive) b += (size_t)c->shapes[i].def.count * sizeof(tt_vec2);
    b += (size_t)c->primcap * sizeof(tt__prim) + ((size_t)c->vertcap + c->normcap) * sizeof(tt_vec2);
    b += ((size_t)c->sgrid.cap_cells + c->sgrid.cap_items + c->sgrid.cap_big) * sizeof(uint32_t);
    b += ((size_t)c->pstamp_cap + c->sstamp_cap) * sizeof(uint32_t);
    return b;
}
