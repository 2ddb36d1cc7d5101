/* tether — shapes: storage behind generational handles, their primitives in
 * world coordinates, and the static index (a uniform grid over primitive
 * boxes) built once and rebuilt only when a shape is added, removed or moved. */
#include "collide_internal.h"

#include <stdlib.h>
#include <string.h>

static const char *const type_names[TT_SHAPE_TYPE_COUNT] = {"segment", "chain", "aabb", "box", "circle", "capsule", "polygon"};

const char *tt_shape_type_name(tt_shape_type t)
{
    return (unsigned)t < TT_SHAPE_TYPE_COUNT ? type_names[t] : "unknown";
}

tt_shape_def tt_shape_def_default(void)
{
    tt_shape_def d;
    memset(&d, 0, sizeof d);
    d.type = TT_SHAPE_SEGMENT;
    d.b = (tt_vec2){1.0, 0.0};
    d.half_extents = (tt_vec2){0.5, 0.5};
    d.radius = 0.5;
    d.friction_static = 0.6;
    d.friction_kinetic = 0.5;
    d.category = 0x0001;
    d.mask = 0xFFFF;
    return d;
}

bool tt__grow(void **p, uint32_t *cap, uint32_t need, size_t elem)
{
    if (need <= *cap) return true;
    uint32_t n = *cap ? *cap : 16;
    while (n < need) n = n > UINT32_MAX / 2 ? need : n * 2;
    void *q = realloc(*p, (size_t)n * elem);
    if (!q) return false;
    *p = q;
    *cap = n;
    return true;
}

bool tt__shape_ok(const tt__collide *c, tt_shape s)
{
    return c && s.index < c->spool.count && s.gen != 0 && c->spool.gen[s.index] == s.gen && c->shapes[s.index].alive;
}

static tt_result material_check(const tt_world *w, double e, double fs, double fk, const char *fn)
{
    if (!tt__in_range(e, 0.0, 1.0)) return tt__fail(w, TT_EINVAL, "%s: restitution must be in [0, 1], got %g", fn, e);
    if (!tt__in_range(fs, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: static friction must be in [0, %g], got %g", fn, TT_MAX_VALUE, fs);
    if (!tt__in_range(fk, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: kinetic friction must be in [0, %g], got %g", fn, TT_MAX_VALUE, fk);
    return TT_OK;
}

static double cross3(tt_vec2 o, tt_vec2 a, tt_vec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

uint32_t tt__polygon_fault(const tt_vec2 *pts, uint32_t n, bool convex)
{
    double sign = 0.0;
    for (uint32_t k = 0; k < n; k++) {
        double cr = cross3(pts[k], pts[(k + 1) % n], pts[(k + 2) % n]);
        if (cr == 0.0 || (convex && sign != 0.0 && (cr > 0.0) != (sign > 0.0))) return (k + 1) % n;
        sign = cr;
    }
    /* a convex outline cannot come back to a point; any other can, beyond its neighbours */
    for (uint32_t j = 0; !convex && j < n; j++)
        for (uint32_t i = 0; i < j; i++)
            if (pts[i].x == pts[j].x && pts[i].y == pts[j].y) return j;
    return n;
}

static tt_result check_def(const tt_world *w, const tt_shape_def *d)
{
    const char *fn = "tt_shape_create";
    if (!d) return tt__fail(w, TT_EINVAL, "%s: def is NULL", fn);
    if ((unsigned)d->type >= TT_SHAPE_TYPE_COUNT) return tt__fail(w, TT_EINVAL, "%s: unknown shape type %d", fn, (int)d->type);
    if (!tt__vec_ok(d->position)) return tt__fail(w, TT_EINVAL, "%s: position must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    if (!tt__in_range(d->angle, -TT_MAX_VALUE, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: angle must be finite", fn);
    if (!tt__vec_ok(d->a) || !tt__vec_ok(d->b)) return tt__fail(w, TT_EINVAL, "%s: a and b must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    tt_result r = material_check(w, d->restitution, d->friction_static, d->friction_kinetic, fn);
    if (r != TT_OK) return r;
    switch (d->type) {
    case TT_SHAPE_AABB:
        if (!(d->a.x <= d->b.x && d->a.y <= d->b.y)) return tt__fail(w, TT_EINVAL, "%s: aabb needs a <= b (min and max corners)", fn);
        if (d->angle != 0.0) return tt__fail(w, TT_EINVAL, "%s: an aabb cannot be turned (angle must be 0); use a box", fn);
        break;
    case TT_SHAPE_BOX:
        if (!(d->half_extents.x > 0.0 && d->half_extents.y > 0.0 && tt__vec_ok(d->half_extents)))
            return tt__fail(w, TT_EINVAL, "%s: box half_extents must be in (0, %g]", fn, TT_MAX_VALUE);
        break;
    case TT_SHAPE_CIRCLE:
        if (!(d->radius > 0.0 && d->radius <= TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: circle radius must be in (0, %g], got %g", fn, TT_MAX_VALUE, d->radius);
        break;
    case TT_SHAPE_CAPSULE:
        if (!tt__in_range(d->radius, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: capsule radius must be in [0, %g], got %g", fn, TT_MAX_VALUE, d->radius);
        break;
    case TT_SHAPE_CHAIN:
    case TT_SHAPE_POLYGON: {
        bool poly = d->type == TT_SHAPE_POLYGON;
        uint32_t lo = poly ? 3 : 2, hi = poly ? TT_MAX_POLYGON_POINTS : TT_MAX_CHAIN_POINTS;
        if (!d->points || d->count < lo || d->count > hi)
            return tt__fail(w, TT_EINVAL, "%s: %s needs points and count in [%u, %u], got %u", fn, type_names[d->type], lo, hi, d->count);
        for (uint32_t k = 0; k < d->count; k++)
            if (!tt__vec_ok(d->points[k])) return tt__fail(w, TT_EINVAL, "%s: point %u must be finite, |x| <= %g", fn, k, TT_MAX_VALUE);
        uint32_t bad = poly ? tt__polygon_fault(d->points, d->count, true) : d->count;
        if (bad < d->count)
            return tt__fail(w, TT_EINVAL, "%s: polygon must be convex with no repeated or collinear points (at point %u)", fn, bad);
        break;
    }
    default: break;
    }
    return TT_OK;
}

tt_shape tt_shape_create(tt_world *w, const tt_shape_def *def)
{
    tt_shape none = {0, 0};
    if (!w) { tt__fail(NULL, TT_EINVAL, "tt_shape_create: world is NULL"); return none; }
    if (check_def(w, def) != TT_OK) return none;
    tt_vec2 *pts = NULL;
    uint32_t npts = (def->type == TT_SHAPE_CHAIN || def->type == TT_SHAPE_POLYGON) ? def->count : 0;
    if (npts) {
        pts = malloc((size_t)npts * sizeof *pts);
        if (!pts) { tt__fail(w, TT_ENOMEM, "tt_shape_create: out of memory"); return none; }
        memcpy(pts, def->points, (size_t)npts * sizeof *pts);
    }
    /* a collision group registered here goes again if the shape cannot be
     * made: a failed call leaves the world as it was */
    const bool had = tt__collide_peek(w) != NULL;
    tt__collide *c = tt__collide_get(w, true, "tt_shape_create");
    if (!c) { free(pts); return none; }
    if (c->shapes_alive >= TT_MAX_SHAPES) {
        free(pts);
        tt__fail(w, TT_ENOMEM, "tt_shape_create: the world has %u shapes, the most allowed", TT_MAX_SHAPES);
        return none;
    }
    bool grew;
    uint32_t need = c->spool.free_count ? c->spool.count : c->spool.count + 1;
    uint32_t i = tt__grow((void **)&c->shapes, &c->shcap, need, sizeof *c->shapes)
                     ? tt_pool_alloc(&c->spool, TT_MAX_SHAPES, &grew) : UINT32_MAX;
    if (i == UINT32_MAX) {
        free(pts);
        if (!had) tt__group_remove(w, &tt__contacts_ops);
        tt__fail(w, TT_ENOMEM, "tt_shape_create: out of memory");
        return none;
    }
    tt__shape *s = &c->shapes[i];
    s->def = *def;
    s->def.points = NULL;
    s->def.count = npts;
    s->pts = pts;
    s->alive = true;
    s->moved = false;
    c->shapes_alive++;
    c->dirty = true;
    return (tt_shape){i, c->spool.gen[i]};
}

#define SHAPE_CHECK(fn)                                                                       \
    if (!w) return tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn);                       \
    tt__collide *c = tt__collide_peek(w);                                                     \
    if (!tt__shape_ok(c, s))                                                                  \
        return tt__fail(w, TT_ESTALE, "%s: stale shape handle (index %u, generation %u)", fn, s.index, s.gen); \
    tt__shape *sh = &c->shapes[s.index]

static void drop_records(tt__collide *c, uint64_t lo_mask, uint64_t match)
{
    uint32_t k = 0;
    for (uint32_t j = 0; j < c->nprev; j++)
        if ((c->prev[j].key & lo_mask) != match) c->prev[k++] = c->prev[j];
    c->nprev = k;
}

tt_result tt_shape_destroy(tt_world *w, tt_shape s)
{
    SHAPE_CHECK("tt_shape_destroy");
    free(sh->pts);
    sh->pts = NULL;
    sh->alive = false;
    tt_pool_free(&c->spool, s.index);
    c->shapes_alive--;
    c->dirty = true;
    /* its contacts of the last step will never END: drop them (key: bit 63 shape, bits 32..62 shape slot) */
    drop_records(c, 0xFFFFFFFF00000000ull, (1ull << 63) | ((uint64_t)s.index << 32));
    return TT_OK;
}

bool tt_shape_is_valid(const tt_world *w, tt_shape s) { return w && tt__shape_ok(tt__collide_peek(w), s); }

tt_result tt_shape_set_transform(tt_world *w, tt_shape s, tt_vec2 position, double angle)
{
    SHAPE_CHECK("tt_shape_set_transform");
    if (!tt__vec_ok(position)) return tt__fail(w, TT_EINVAL, "tt_shape_set_transform: position must be finite, |x| <= %g", TT_MAX_VALUE);
    if (!tt__in_range(angle, -TT_MAX_VALUE, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "tt_shape_set_transform: angle must be finite");
    if (sh->def.type == TT_SHAPE_AABB && angle != 0.0) return tt__fail(w, TT_EINVAL, "tt_shape_set_transform: an aabb cannot be turned (angle must be 0)");
    sh->def.position = position;
    sh->def.angle = angle;
    sh->moved = true;
    c->any_moved = true;
    c->dirty = true;
    return TT_OK;
}

tt_result tt_shape_get_transform(const tt_world *w, tt_shape s, tt_vec2 *position, double *angle)
{
    SHAPE_CHECK("tt_shape_get_transform");
    if (!position || !angle) return tt__fail(w, TT_EINVAL, "tt_shape_get_transform: out is NULL");
    *position = sh->def.position;
    *angle = sh->def.angle;
    return TT_OK;
}

tt_result tt_shape_set_material(tt_world *w, tt_shape s, double e, double fs, double fk)
{
    SHAPE_CHECK("tt_shape_set_material");
    tt_result r = material_check(w, e, fs, fk, "tt_shape_set_material");
    if (r != TT_OK) return r;
    sh->def.restitution = e;
    sh->def.friction_static = fs;
    sh->def.friction_kinetic = fk;
    return TT_OK;
}

tt_result tt_shape_set_filter(tt_world *w, tt_shape s, uint16_t category, uint16_t mask)
{
    SHAPE_CHECK("tt_shape_set_filter");
    sh->def.category = category;
    sh->def.mask = mask;
    return TT_OK;
}

tt_result tt_shape_set_sensor(tt_world *w, tt_shape s, bool sensor)
{
    SHAPE_CHECK("tt_shape_set_sensor");
    sh->def.sensor = sensor;
    return TT_OK;
}

tt_result tt_shape_get_type(const tt_world *w, tt_shape s, tt_shape_type *out)
{
    SHAPE_CHECK("tt_shape_get_type");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_shape_get_type: out is NULL");
    *out = sh->def.type;
    return TT_OK;
}

tt_result tt_shape_get_user(const tt_world *w, tt_shape s, uint64_t *out)
{
    SHAPE_CHECK("tt_shape_get_user");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_shape_get_user: out is NULL");
    *out = sh->def.user;
    return TT_OK;
}

uint32_t tt_world_shape_count(const tt_world *w)
{
    const tt__collide *c = w ? tt__collide_peek(w) : NULL;
    return c ? c->shapes_alive : 0;
}

/* --- primitives --------------------------------------------------------- */

static tt_vec2 place(const tt_shape_def *d, tt_vec2 p)
{
    double cs = cos(d->angle), sn = sin(d->angle);
    return (tt_vec2){d->position.x + cs * p.x - sn * p.y, d->position.y + sn * p.x + cs * p.y};
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

/* A convex polygon from world points, turned counter-clockwise, with outward normals. */
static bool add_poly(tt__collide *c, uint32_t shape, const tt_vec2 *pts, uint32_t n)
{
    if (!tt__grow((void **)&c->verts, &c->vertcap, c->nvert + n, sizeof *c->verts)) return false;
    if (!tt__grow((void **)&c->norms, &c->normcap, c->vertcap, sizeof *c->norms)) return false;
    double area = 0.0;
    for (uint32_t k = 0; k < n; k++) area += pts[k].x * pts[(k + 1) % n].y - pts[(k + 1) % n].x * pts[k].y;
    tt__prim *p = new_prim(c, shape);
    if (!p) return false;
    p->kind = TT__PRIM_POLY;
    p->v0 = c->nvert;
    p->nv = n;
    tt_vec2 *v = c->verts + c->nvert;
    for (uint32_t k = 0; k < n; k++) v[k] = pts[area >= 0.0 ? k : n - 1 - k];
    p->lox = p->hix = v[0].x;
    p->loy = p->hiy = v[0].y;
    for (uint32_t k = 0; k < n; k++) {
        tt_vec2 a = v[k], b = v[(k + 1) % n];
        double ex = b.x - a.x, ey = b.y - a.y, l = sqrt(ex * ex + ey * ey);
        c->norms[c->nvert + k] = (tt_vec2){ey / l, -ex / l};
        p->lox = fmin(p->lox, a.x); p->hix = fmax(p->hix, a.x);
        p->loy = fmin(p->loy, a.y); p->hiy = fmax(p->hiy, a.y);
    }
    c->nvert += n;
    return true;
}

static bool shape_prims(tt__collide *c, uint32_t i)
{
    const tt__shape *s = &c->shapes[i];
    const tt_shape_def *d = &s->def;
    switch (d->type) {
    case TT_SHAPE_SEGMENT: return add_capsule(c, i, place(d, d->a), place(d, d->b), 0.0);
    case TT_SHAPE_CAPSULE: return add_capsule(c, i, place(d, d->a), place(d, d->b), d->radius);
    case TT_SHAPE_CIRCLE: { tt_vec2 o = place(d, (tt_vec2){0, 0}); return add_capsule(c, i, o, o, d->radius); }
    case TT_SHAPE_CHAIN: {
        uint32_t segs = d->loop ? d->count : d->count - 1;
        for (uint32_t k = 0; k < segs; k++)
            if (!add_capsule(c, i, place(d, s->pts[k]), place(d, s->pts[(k + 1) % d->count]), 0.0)) return false;
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
        for (int k = 0; k < 4; k++) q[k] = place(d, q[k]);
        if (q[0].x == q[1].x && q[0].y == q[1].y) return add_capsule(c, i, q[0], q[2], 0.0); /* degenerate aabb: a segment */
        if (q[1].x == q[2].x && q[1].y == q[2].y) return add_capsule(c, i, q[0], q[1], 0.0);
        return add_poly(c, i, q, 4);
    }
    case TT_SHAPE_POLYGON: {
        tt_vec2 q[TT_MAX_POLYGON_POINTS];
        for (uint32_t k = 0; k < d->count; k++) q[k] = place(d, s->pts[k]);
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

tt_result tt__shapes_rebuild(tt_world *w, tt__collide *c)
{
    c->nprim = 0;
    c->nvert = 0;
    for (uint32_t i = 0; i < c->spool.count; i++)
        if (c->shapes[i].alive && !shape_prims(c, i)) return tt__fail(w, TT_ENOMEM, "collisions: out of memory for shapes");
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

tt_result tt_shape_get_aabb(const tt_world *w, tt_shape s, tt_vec2 *lo, tt_vec2 *hi)
{
    SHAPE_CHECK("tt_shape_get_aabb");
    (void)sh;
    if (!lo || !hi) return tt__fail(w, TT_EINVAL, "tt_shape_get_aabb: out is NULL");
    if (c->dirty && tt__shapes_rebuild((tt_world *)w, c) != TT_OK) return TT_ENOMEM;
    *lo = (tt_vec2){INFINITY, INFINITY};
    *hi = (tt_vec2){-INFINITY, -INFINITY};
    for (uint32_t k = 0; k < c->nprim; k++) {
        const tt__prim *p = &c->prims[k];
        if (p->shape != s.index) continue;
        lo->x = fmin(lo->x, p->lox); lo->y = fmin(lo->y, p->loy);
        hi->x = fmax(hi->x, p->hix); hi->y = fmax(hi->y, p->hiy);
    }
    return TT_OK;
}

void tt__shapes_free(tt__collide *c)
{
    for (uint32_t i = 0; i < c->spool.count; i++) free(c->shapes[i].pts);
    free(c->shapes);
    tt_pool_destroy(&c->spool);
    free(c->prims); free(c->verts); free(c->norms);
    free(c->sgrid.start); free(c->sgrid.items); free(c->sgrid.big);
    free(c->pstamp); free(c->sstamp);
}

size_t tt__shapes_bytes(const tt__collide *c)
{
    size_t b = (size_t)c->shcap * sizeof(tt__shape) + tt_pool_bytes(&c->spool);
    for (uint32_t i = 0; i < c->spool.count; i++)
        if (c->shapes[i].alive) b += (size_t)c->shapes[i].def.count * sizeof(tt_vec2);
    b += (size_t)c->primcap * sizeof(tt__prim) + ((size_t)c->vertcap + c->normcap) * sizeof(tt_vec2);
    b += ((size_t)c->sgrid.cap_cells + c->sgrid.cap_items + c->sgrid.cap_big) * sizeof(uint32_t);
    b += ((size_t)c->pstamp_cap + c->sstamp_cap) * sizeof(uint32_t);
    return b;
}

uint32_t tt_world_list_shapes(const tt_world *w, tt_shape *out, uint32_t cap)
{
    const tt__collide *c = w ? tt__collide_peek(w) : NULL;
    if (!c) return 0;
    uint32_t n = 0;
    for (uint32_t i = 0; i < c->spool.count; i++) {
        if (!c->shapes[i].alive) continue;
        if (out && n < cap) out[n] = (tt_shape){i, c->spool.gen[i]};
        n++;
    }
    return n;
}

/* Appends the world position of local point p (shape placed by pos + R(angle)). */
static void put(tt_vec2 *out, uint32_t cap, uint32_t *n, const tt_shape_def *d, double x, double y)
{
    if (out && *n < cap) {
        double cs = cos(d->angle), sn = sin(d->angle);
        out[*n] = (tt_vec2){d->position.x + cs * x - sn * y, d->position.y + sn * x + cs * y};
    }
    (*n)++;
}

/* A half circle of `segs` steps around centre (cx, cy) from angle a0. */
static void arc(tt_vec2 *out, uint32_t cap, uint32_t *n, const tt_shape_def *d, double cx, double cy, double r,
                double a0, double sweep, int segs)
{
    for (int k = 0; k <= segs; k++) {
        double a = a0 + sweep * k / segs;
        put(out, cap, n, d, cx + r * cos(a), cy + r * sin(a));
    }
}

tt_result tt_shape_get_outline(const tt_world *w, tt_shape s, tt_vec2 *out, uint32_t cap, uint32_t *count, bool *closed)
{
    SHAPE_CHECK("tt_shape_get_outline");
    if (!count || !closed) return tt__fail(w, TT_EINVAL, "tt_shape_get_outline: out is NULL");
    const tt_shape_def *d = &sh->def;
    uint32_t n = 0;
    *closed = true;
    switch (d->type) {
    case TT_SHAPE_SEGMENT:
        put(out, cap, &n, d, d->a.x, d->a.y);
        put(out, cap, &n, d, d->b.x, d->b.y);
        *closed = false;
        break;
    case TT_SHAPE_CHAIN:
        for (uint32_t k = 0; k < d->count; k++) put(out, cap, &n, d, sh->pts[k].x, sh->pts[k].y);
        *closed = d->loop;
        break;
    case TT_SHAPE_AABB:
        put(out, cap, &n, d, d->a.x, d->a.y);
        put(out, cap, &n, d, d->b.x, d->a.y);
        put(out, cap, &n, d, d->b.x, d->b.y);
        put(out, cap, &n, d, d->a.x, d->b.y);
        break;
    case TT_SHAPE_BOX: {
        double hx = d->half_extents.x, hy = d->half_extents.y;
        put(out, cap, &n, d, -hx, -hy);
        put(out, cap, &n, d, hx, -hy);
        put(out, cap, &n, d, hx, hy);
        put(out, cap, &n, d, -hx, hy);
        break;
    }
    case TT_SHAPE_CIRCLE:
        arc(out, cap, &n, d, 0, 0, d->radius, 0, 2 * M_PI * 31 / 32, 31);
        break;
    case TT_SHAPE_CAPSULE: {
        double ang = atan2(d->b.y - d->a.y, d->b.x - d->a.x);
        arc(out, cap, &n, d, d->b.x, d->b.y, d->radius, ang - M_PI / 2, M_PI, 12);
        arc(out, cap, &n, d, d->a.x, d->a.y, d->radius, ang + M_PI / 2, M_PI, 12);
        break;
    }
    case TT_SHAPE_POLYGON:
        for (uint32_t k = 0; k < d->count; k++) put(out, cap, &n, d, sh->pts[k].x, sh->pts[k].y);
        break;
    default:
        break;
    }
    *count = n;
    return TT_OK;
}

tt_result tt_shape_get_sensor(const tt_world *w, tt_shape s, bool *out)
{
    SHAPE_CHECK("tt_shape_get_sensor");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_shape_get_sensor: out is NULL");
    *out = sh->def.sensor;
    return TT_OK;
}
