/* tether — queries through the broadphase: raycast (a cell walk over the
 * static index and the particle grid, stopping at the first hit), point and
 * box queries (the cells they cover). The particle grid is rebuilt on the
 * first query after particles moved (the world's epoch), never per query. */
#include "collide_internal.h"
#include "terrain_internal.h"

#include <stdlib.h>
#include <string.h>

static tt__collide *ready(tt_world *w, const char *fn)
{
    tt__collide *c = tt__collide_get(w, true, fn);
    if (!c) return NULL;
    if (c->dirty && tt__shapes_rebuild(w, c) != TT_OK) return NULL;
    if (c->scr.grid.epoch != w->epoch) {
        if (!tt__grid_build(w, &c->scr.grid, c->set.cell_size)) {
            tt__fail(w, TT_ENOMEM, "%s: out of memory for the particle grid", fn);
            return NULL;
        }
        c->scr.grid.epoch = w->epoch;
    }
    uint32_t need = c->spool.count ? c->spool.count : 1;
    if (c->sstamp_cap < need) {
        uint32_t *q = realloc(c->sstamp, (size_t)need * sizeof *q);
        if (!q) {
            tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
            return NULL;
        }
        memset(q + c->sstamp_cap, 0, (size_t)(need - c->sstamp_cap) * sizeof *q);
        c->sstamp = q;
        c->sstamp_cap = need;
    }
    if (++c->sstamp_id == 0) {
        memset(c->sstamp, 0, (size_t)c->sstamp_cap * sizeof *c->sstamp);
        c->sstamp_id = 1;
    }
    return c;
}

/* Walks the cells of a grid crossed by o + t·d, t in [0, 1], clipped to the
 * grid's rectangle grown by pad; fn gets each cell (possibly out of range)
 * and the t at which the ray enters it, and returns false to stop. */
typedef bool (*cell_fn)(void *ctx, int32_t cx, int32_t cy, double te);

static void walk(double ox, double oy, double cs, int32_t nx, int32_t ny, double pad, double x0, double y0, double dx,
                 double dy, cell_fn fn, void *ctx)
{
    double t0 = 0.0, t1 = 1.0;
    const double lo[2] = {ox - pad, oy - pad}, hi[2] = {ox + nx * cs + pad, oy + ny * cs + pad};
    const double o[2] = {x0, y0}, d[2] = {dx, dy};
    for (int k = 0; k < 2; k++) {
        if (d[k] == 0.0) {
            if (o[k] < lo[k] || o[k] > hi[k]) return;
            continue;
        }
        double ta = (lo[k] - o[k]) / d[k], tb = (hi[k] - o[k]) / d[k];
        if (ta > tb) { double s = ta; ta = tb; tb = s; }
        if (ta > t0) t0 = ta;
        if (tb < t1) t1 = tb;
        if (t0 > t1) return;
    }
    const double inv = 1.0 / cs;
    int32_t cx = tt__cell_coord(x0 + dx * t0, ox, inv), cy = tt__cell_coord(y0 + dy * t0, oy, inv);
    int32_t stx = dx > 0.0 ? 1 : -1, sty = dy > 0.0 ? 1 : -1;
    double tdx = dx != 0.0 ? cs / fabs(dx) : INFINITY, tdy = dy != 0.0 ? cs / fabs(dy) : INFINITY;
    double tmx = dx > 0.0 ? (ox + (cx + 1) * cs - x0) / dx : dx < 0.0 ? (ox + cx * cs - x0) / dx : INFINITY;
    double tmy = dy > 0.0 ? (oy + (cy + 1) * cs - y0) / dy : dy < 0.0 ? (oy + cy * cs - y0) / dy : INFINITY;
    double te = t0;
    int64_t guard = 4 * ((int64_t)nx + ny) + 16;
    while (guard-- > 0) {
        if (!fn(ctx, cx, cy, te)) return;
        if (tmx < tmy) {
            te = tmx;
            cx += stx;
            tmx += tdx;
        } else {
            te = tmy;
            cy += sty;
            tmy += tdy;
        }
        if (te > t1) return;
    }
}

typedef struct ray_ctx {
    tt_world *w;
    tt__collide *c;
    double ox, oy, dx, dy;
    uint16_t mask;
    tt_ray_hit *best;
} ray_ctx;

static void ray_prim(ray_ctx *r, uint32_t k)
{
    tt__collide *c = r->c;
    if (c->pstamp[k] == c->stamp) return;
    c->pstamp[k] = c->stamp;
    const tt__prim *p = &c->prims[k];
    const tt__shape *sh = &c->shapes[p->shape];
    if (sh->def.sensor || !(sh->def.category & r->mask)) return;
    double t, nx, ny;
    if (!tt__ray_vs_prim(c, p, r->ox, r->oy, r->dx, r->dy, 0.0, r->best->fraction, &t, &nx, &ny)) return;
    if (r->best->hit && t >= r->best->fraction) return;
    r->best->hit = true;
    r->best->fraction = t;
    r->best->normal = (tt_vec2){nx, ny};
    r->best->shape = (tt_shape){p->shape, c->spool.gen[p->shape]};
    r->best->particle = (tt_particle){0, 0};
}

static bool ray_shape_cell(void *ctx, int32_t cx, int32_t cy, double te)
{
    ray_ctx *r = ctx;
    const tt__sgrid *g = &r->c->sgrid;
    if (r->best->hit && te > r->best->fraction) return false;
    for (int32_t y = cy - 1; y <= cy + 1; y++)
        for (int32_t x = cx - 1; x <= cx + 1; x++) {
            if (x < 0 || y < 0 || x >= g->nx || y >= g->ny) continue;
            uint32_t cell = (uint32_t)y * (uint32_t)g->nx + (uint32_t)x;
            for (uint32_t j = g->start[cell]; j < g->start[cell + 1]; j++) ray_prim(r, g->items[j]);
        }
    return true;
}

static void ray_particle(ray_ctx *r, uint32_t i)
{
    const tt_world *w = r->w;
    if (!(w->flags[i] & TT__PF_ALIVE) || !(w->category[i] & r->mask)) return;
    double t, nx, ny;
    if (!tt__ray_vs_circle(r->ox, r->oy, r->dx, r->dy, w->px[i], w->py[i], w->radius[i], r->best->fraction, &t, &nx, &ny)) return;
    if (r->best->hit && (t > r->best->fraction || (t == r->best->fraction && r->best->particle.gen && i > r->best->particle.index))) return;
    r->best->hit = true;
    r->best->fraction = t;
    r->best->normal = (tt_vec2){nx, ny};
    r->best->particle = (tt_particle){i, w->ppool.gen[i]};
    r->best->shape = (tt_shape){0, 0};
}

static bool ray_particle_cell(void *ctx, int32_t cx, int32_t cy, double te)
{
    ray_ctx *r = ctx;
    const tt__grid *g = &r->c->scr.grid;
    if (r->best->hit && te > r->best->fraction) return false;
    for (int32_t y = cy - 1; y <= cy + 1; y++)
        for (int32_t x = cx - 1; x <= cx + 1; x++) {
            if (x < 0 || y < 0 || x >= g->nx || y >= g->ny) continue;
            uint32_t cell = (uint32_t)y * (uint32_t)g->nx + (uint32_t)x;
            for (uint32_t j = g->start[cell]; j < g->start[cell + 1]; j++) ray_particle(r, g->idx[j]);
        }
    return true;
}

tt_result tt_world_raycast(tt_world *w, tt_vec2 from, tt_vec2 to, uint16_t mask, tt_ray_hit *out)
{
    const char *fn = "tt_world_raycast";
    TT_CHECK_WORLD(w, fn);
    if (!out) return tt__fail(w, TT_EINVAL, "%s: out is NULL", fn);
    if (!tt__vec_ok(from) || !tt__vec_ok(to)) return tt__fail(w, TT_EINVAL, "%s: from and to must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    memset(out, 0, sizeof *out);
    out->fraction = 1.0;
    tt__collide *c = ready(w, fn);
    if (!c) return TT_ENOMEM;
    ray_ctx r = {w, c, from.x, from.y, to.x - from.x, to.y - from.y, mask, out};
    if (c->nprim) {
        if (++c->stamp == 0) {
            memset(c->pstamp, 0, (size_t)c->nprim * sizeof *c->pstamp);
            c->stamp = 1;
        }
        for (uint32_t k = 0; k < c->sgrid.nbig; k++) ray_prim(&r, c->sgrid.big[k]);
        const tt__sgrid *g = &c->sgrid;
        if (g->nx) walk(g->ox, g->oy, g->cs, g->nx, g->ny, g->cs, r.ox, r.oy, r.dx, r.dy, ray_shape_cell, &r);
    }
    const tt__grid *g = &c->scr.grid;
    if (g->n) {
        for (uint32_t k = 0; k < g->nout; k++) ray_particle(&r, g->out_list[k]);
        walk(g->ox, g->oy, g->cs, g->nx, g->ny, g->cs, r.ox, r.oy, r.dx, r.dy, ray_particle_cell, &r);
    }
    if (c->terr) tt__terrain_raycast(w, c, from, to, mask, out);
    if (!out->hit) out->fraction = 1.0;
    else out->point = (tt_vec2){from.x + r.dx * out->fraction, from.y + r.dy * out->fraction};
    return TT_OK;
}

/* --- point and box queries --------------------------------------------------- */

typedef struct area_ctx {
    tt_world *w;
    tt__collide *c;
    double lox, loy, hix, hiy;
    bool point;
    uint16_t mask;
    tt_shape *shapes;
    uint32_t scap, ns;
} area_ctx;

static void area_prim(void *ctx, uint32_t k)
{
    area_ctx *a = ctx;
    tt__collide *c = a->c;
    const tt__prim *p = &c->prims[k];
    if (c->sstamp[p->shape] == c->sstamp_id || !(c->shapes[p->shape].def.category & a->mask)) return;
    bool in;
    if (a->point) {
        tt__hit hit;
        tt__circle_vs_prim(c, p, a->lox, a->loy, 0.0, &hit);
        in = hit.depth >= 0.0;
    } else {
        in = tt__prim_vs_aabb(c, p, a->lox, a->loy, a->hix, a->hiy);
    }
    if (!in) return;
    c->sstamp[p->shape] = c->sstamp_id;
    if (a->ns < a->scap) a->shapes[a->ns] = (tt_shape){p->shape, c->spool.gen[p->shape]};
    a->ns++;
}

static bool particle_in(const tt_world *w, uint32_t i, const area_ctx *a)
{
    if (!(w->flags[i] & TT__PF_ALIVE) || !(w->category[i] & a->mask)) return false;
    double x = w->px[i], y = w->py[i], r = w->radius[i];
    double dx = x < a->lox ? a->lox - x : x > a->hix ? x - a->hix : 0.0;
    double dy = y < a->loy ? a->loy - y : y > a->hiy ? y - a->hiy : 0.0;
    return dx * dx + dy * dy <= r * r;
}

static tt_result area(tt_world *w, const char *fn, double lox, double loy, double hix, double hiy, bool point, uint16_t mask,
                      tt_particle *particles, uint32_t pcap, uint32_t *np, tt_shape *shapes, uint32_t scap, uint32_t *ns)
{
    if ((pcap && !particles) || (scap && !shapes)) return tt__fail(w, TT_EINVAL, "%s: an output array is NULL with a capacity > 0", fn);
    tt__collide *c = ready(w, fn);
    if (!c) return TT_ENOMEM;
    area_ctx a = {w, c, lox, loy, hix, hiy, point, mask, shapes, scap, 0};
    tt__sgrid_query(c, lox, loy, hix, hiy, area_prim, &a);
    uint32_t count = 0;
    const tt__grid *g = &c->scr.grid;
    if (g->n) {
        const double m = g->rmax;
        int32_t x0 = tt__cell_coord(lox - m, g->ox, g->inv), x1 = tt__cell_coord(hix + m, g->ox, g->inv);
        int32_t y0 = tt__cell_coord(loy - m, g->oy, g->inv), y1 = tt__cell_coord(hiy + m, g->oy, g->inv);
        if (x0 < 0) x0 = 0;
        if (y0 < 0) y0 = 0;
        if (x1 >= g->nx) x1 = g->nx - 1;
        if (y1 >= g->ny) y1 = g->ny - 1;
        for (int32_t y = y0; y <= y1; y++)
            for (int32_t x = x0; x <= x1; x++) {
                uint32_t cell = (uint32_t)y * (uint32_t)g->nx + (uint32_t)x;
                for (uint32_t j = g->start[cell]; j < g->start[cell + 1]; j++) {
                    if (g->bits[j] & TT__GRID_OUTSIDE) continue; /* tested below, once */
                    uint32_t i = g->idx[j];
                    if (!particle_in(w, i, &a)) continue;
                    if (count < pcap) particles[count] = (tt_particle){i, w->ppool.gen[i]};
                    count++;
                }
            }
        for (uint32_t k = 0; k < g->nout; k++) {
            uint32_t i = g->out_list[k];
            if (!particle_in(w, i, &a)) continue;
            if (count < pcap) particles[count] = (tt_particle){i, w->ppool.gen[i]};
            count++;
        }
    }
    if (np) *np = count;
    if (ns) *ns = a.ns;
    return TT_OK;
}

tt_result tt_world_query_point(tt_world *w, tt_vec2 p, uint16_t mask, tt_particle *particles, uint32_t pcap,
                               uint32_t *np, tt_shape *shapes, uint32_t scap, uint32_t *ns)
{
    const char *fn = "tt_world_query_point";
    TT_CHECK_WORLD(w, fn);
    if (!tt__vec_ok(p)) return tt__fail(w, TT_EINVAL, "%s: point must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    return area(w, fn, p.x, p.y, p.x, p.y, true, mask, particles, pcap, np, shapes, scap, ns);
}

tt_result tt_world_query_aabb(tt_world *w, tt_vec2 lo, tt_vec2 hi, uint16_t mask, tt_particle *particles, uint32_t pcap,
                              uint32_t *np, tt_shape *shapes, uint32_t scap, uint32_t *ns)
{
    const char *fn = "tt_world_query_aabb";
    TT_CHECK_WORLD(w, fn);
    if (!tt__vec_ok(lo) || !tt__vec_ok(hi)) return tt__fail(w, TT_EINVAL, "%s: corners must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    if (!(lo.x <= hi.x && lo.y <= hi.y)) return tt__fail(w, TT_EINVAL, "%s: lo must be <= hi on both axes", fn);
    return area(w, fn, lo.x, lo.y, hi.x, hi.y, false, mask, particles, pcap, np, shapes, scap, ns);
}
