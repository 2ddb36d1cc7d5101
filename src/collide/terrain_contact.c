/* tether — what contacts and queries ask of terrains: the distance band
 * sampled bilinearly with its gradient over two pixels (smooth enough that
 * a ball rolls down a pixel slope, not along its stairs), the particles'
 * contacts of a substep, the projection of one contact (a bounded search
 * out of the solid where the band is flat), bullets marched through the
 * band, and rays. The response is the shapes' own (contact_response.c). */
#include "terrain_internal.h"

#include <stdlib.h>

/* The band at pixel (x, y); outside the terrain, far. */
static inline double at(const tt__terrain *T, int x, int y)
{
    const tt_mask *m = T->m;
    if (x < 0 || y < 0 || x >= m->w || y >= m->h) return T->def.band;
    return T->sdf[(size_t)y * (size_t)m->w + (size_t)x];
}

/* A pixel index from a floored coordinate f of a side of n pixels: clamped
 * to just outside it first, where every index reads the band the same, so a
 * coordinate billions of pixels away (a big particle beside tiny pixels) is
 * never cast to an int it does not fit. */
static inline int pix(double f, int n) { return f < -2.0 ? -2 : f > n + 1.0 ? n + 1 : (int)f; }

/* floor(u), the same double, without the library call (x86-64 without
 * SSE4.1 has no instruction for it): a conversion to an integer and back
 * where u fits one, floor itself beyond. An integral u (−0 too) is u. */
static inline double ffloor(double u)
{
    if (!(fabs(u) < 4.5e15)) return floor(u);
    const double t = (double)(int64_t)u;
    return t > u ? t - 1.0 : t == u ? u : t;
}

/* Bilinear in pixel-centre coordinates (u, v). */
static double bilinear(const tt__terrain *T, double u, double v)
{
    const double fu = ffloor(u), fv = ffloor(v), a = u - fu, b = v - fv;
    const int x = pix(fu, T->m->w), y = pix(fv, T->m->h);
    const double s00 = at(T, x, y), s10 = at(T, x + 1, y), s01 = at(T, x, y + 1), s11 = at(T, x + 1, y + 1);
    return (s00 * (1.0 - a) + s10 * a) * (1.0 - b) + (s01 * (1.0 - a) + s11 * a) * b;
}

/* The same away from the border: every pixel it reads is inside, and u,
 * v ≥ 1, where truncation is ffloor's floor (the same double). */
static inline double bilinear_in(const tt__terrain *T, double u, double v)
{
    const int32_t iu = (int32_t)u, iv = (int32_t)v;
    const double fu = (double)iu, fv = (double)iv, a = u - fu, b = v - fv;
    const float *p = T->sdf + (size_t)iv * (size_t)T->m->w + (size_t)iu, *q = p + T->m->w;
    const double s00 = p[0], s10 = p[1], s01 = q[0], s11 = q[1];
    return (s00 * (1.0 - a) + s10 * a) * (1.0 - b) + (s01 * (1.0 - a) + s11 * a) * b;
}

double tt__terrain_sample(const tt__terrain *T, double x, double y, double *nx, double *ny)
{
    const double s = T->def.pixel, B = T->def.band, pad = (B + 2.0) * s;
    *nx = *ny = 0.0;
    if (!(x > T->lox - pad && x < T->hix + pad && y > T->loy - pad && y < T->hiy + pad)) return B * s;
    const double u = (x - T->def.origin.x) * T->inv - 0.5, v = (T->def.origin.y - y) * T->inv - 0.5;
    double d, gu, gv;
    /* the five samples read pixels within 2 of (u, v) (u ± 1 may round onto the next integer) */
    const double fu = ffloor(u), fv = ffloor(v);
    if (fu >= 2.0 && fu + 3.0 < T->m->w && fv >= 2.0 && fv + 3.0 < T->m->h) {
        d = bilinear_in(T, u, v);
        gu = bilinear_in(T, u + 1.0, v) - bilinear_in(T, u - 1.0, v);
        gv = bilinear_in(T, u, v + 1.0) - bilinear_in(T, u, v - 1.0);
    } else {
        d = bilinear(T, u, v);
        gu = bilinear(T, u + 1.0, v) - bilinear(T, u - 1.0, v);
        gv = bilinear(T, u, v + 1.0) - bilinear(T, u, v - 1.0);
    }
    const double g2 = gu * gu + gv * gv;
    if (g2 > 1e-12) {
        const double ig = 1.0 / sqrt(g2);
        *nx = gu * ig;
        *ny = -gv * ig; /* rows go down */
    }
    return d * s;
}

static inline const tt__terrain *terrain_of(const tt__collide *c, uint32_t code)
{
    return &c->terr->t[code & ~TT__PRIM_TERRAIN];
}

/* The radius a terrain sees: at most band − 4 pixels (the band is exact
 * to 3 pixels short of its clamp, the blur's reach, and the gradient reads
 * a pixel further). */
static inline double seen_radius(const tt__terrain *T, double r)
{
    const double lim = (T->def.band - 4) * T->def.pixel;
    return r < lim ? r : lim;
}

/* Deep in the solid, where the band is flat: the nearest pixel within 2·band
 * whose distance is not clamped (the way out), or straight up. */
static void search_out(const tt__terrain *T, double x, double y, double r, tt__hit *out)
{
    const double s = T->def.pixel, B = T->def.band;
    const double cu = (x - T->def.origin.x) * T->inv, cv = (T->def.origin.y - y) * T->inv;
    const int px = pix(floor(cu), T->m->w), py = pix(floor(cv), T->m->h);
    for (int k = 1; k <= 2 * (int)B; k++) {
        double best = INFINITY, bx = 0.0, by = 0.0;
        for (int j = -k; j <= k; j++)
            for (int i = -k; i <= k; i++) {
                if (i != -k && i != k && j != -k && j != k) continue; /* the ring only */
                if (at(T, px + i, py + j) <= 1.0 - B) continue;
                const double dx = px + i + 0.5 - cu, dy = py + j + 0.5 - cv, d2 = dx * dx + dy * dy;
                if (d2 < best) { best = d2; bx = dx; by = dy; }
            }
        if (best < INFINITY) {
            const double d = sqrt(best);
            out->nx = bx / d;
            out->ny = -by / d;
            out->depth = r + d * s;
            return;
        }
    }
    out->nx = 0.0;
    out->ny = 1.0;
    out->depth = r + 2.0 * B * s;
}

void tt__terrain_hit(const tt__collide *c, uint32_t code, double x, double y, double r, tt__hit *out)
{
    const tt__terrain *T = terrain_of(c, code);
    r = seen_radius(T, r);
    double nx, ny, d = tt__terrain_sample(T, x, y, &nx, &ny);
    if (nx == 0.0 && ny == 0.0) {
        if (d < 0.0) {
            search_out(T, x, y, r, out);
            return;
        }
        ny = 1.0; /* far outside: no contact whichever way */
    }
    out->nx = nx;
    out->ny = ny;
    out->depth = r - d;
}

void tt__terrain_material(const tt__collide *c, uint32_t code, double *e, double *fs, double *fk)
{
    const tt__terrain *T = terrain_of(c, code);
    *e = T->def.restitution;
    *fs = T->def.friction_static;
    *fk = T->def.friction_kinetic;
}

tt_terrain tt__terrain_handle(const tt__collide *c, uint32_t code)
{
    const uint32_t i = code & ~TT__PRIM_TERRAIN;
    return (tt_terrain){i, c->terr->pool.gen[i]};
}

static inline bool filter(const tt_world *w, const tt__terrain *T, uint32_t a)
{
    return (w->category[a] & T->def.mask) && (T->def.category & w->mask[a]);
}

bool tt__terrain_detect(tt_world *w, tt__collide *c, uint32_t n, bool grid_built)
{
    const tt__terrains *ts = c->terr;
    /* the grid's cells no terrain's surface reaches (terrain_tiles.c; the shapes are done with near) */
    const tt__grid *g = &c->scr.grid;
    const uint8_t *near = grid_built && tt__terrain_near_cells(ts, g, c->scr.near, c->scr.near_cap) ? c->scr.near : NULL;
    const uint32_t *cell = g->cell; /* locals: the calls below could change any field */
    const double *im = w->inv_mass;
    for (uint32_t i = 0; i < n; i++) {
        if (im[i] == 0.0) continue;
        if (near && !(cell[i] >> 31) && !near[cell[i]]) continue; /* inside the grid, in a far cell */
        const double x = w->px[i], y = w->py[i], r = w->radius[i], m = r * TT__CONTACT_MARGIN, reach = r + m;
        for (uint32_t k = 0; k < ts->pool.count; k++) {
            const tt__terrain *T = &ts->t[k];
            if (!T->alive || x < T->lox - reach || x > T->hix + reach || y < T->loy - reach || y > T->hiy + reach ||
                !filter(w, T, i))
                continue;
            /* the band at the nearest pixel centre: within a pixel of the sample, whose slope is at most 1 */
            const double u = (x - T->def.origin.x) * T->inv, v = (T->def.origin.y - y) * T->inv;
            if ((at(T, pix(ffloor(u), T->m->w), pix(ffloor(v), T->m->h)) - 1.0) * T->def.pixel > reach) continue;
            const uint32_t code = TT__PRIM_TERRAIN | k;
            if (c->ccd_prim && i < c->bulletcap && c->ccd_prim[i] == (int32_t)code) continue; /* the sweep has it */
            tt__hit hit;
            tt__terrain_hit(c, code, x, y, r, &hit);
            if (hit.depth <= -m) continue;
            if (!tt__grow((void **)&c->scr.sc, &c->scr.sccap, c->scr.nsc + 1, sizeof *c->scr.sc)) return false;
            c->scr.sc[c->scr.nsc++] = (tt__scontact){i, code, hit.nx, hit.ny, 0.0, 0.0, 0.0, 0.0, 0.0, 0};
        }
    }
    return true;
}

/* Sphere tracing of o + t·d, t in [0, tmax], for a circle of radius r
 * against T: the first t where the distance falls to r (false: none, or
 * touching at the start). Steps are the distance left (less a tenth for
 * the band's error), at least a quarter pixel. */
static bool march(const tt__terrain *T, double ox, double oy, double dx, double dy, double r, double tmax, bool inside_hits,
                  double *t, double *nx, double *ny)
{
    const double len = sqrt(dx * dx + dy * dy), s = T->def.pixel;
    if (!(len > 0.0)) return false;
    double tt = 0.0, gx, gy;
    double d = tt__terrain_sample(T, ox, oy, &gx, &gy) - r;
    if (d <= 0.0) {
        if (!inside_hits) return false; /* touching at the start: the discrete test has it */
        *t = 0.0;
        *nx = gx;
        *ny = gy;
        return true;
    }
    for (uint32_t it = 0; it < 1000000; it++) {
        double step = 0.9 * d;
        step = step > 0.25 * s ? step : 0.25 * s;
        tt += step / len;
        if (tt > tmax) return false;
        d = tt__terrain_sample(T, ox + dx * tt, oy + dy * tt, &gx, &gy) - r;
        if (d <= 0.0) {
            *t = tt;
            *nx = gx;
            *ny = gy;
            return gx * dx + gy * dy < 0.0 || (gx == 0.0 && gy == 0.0);
        }
    }
    return false;
}

int32_t tt__terrain_sweep(tt_world *w, const tt__collide *c, uint32_t i, double x0, double y0, double x1, double y1,
                          double *t, double *nx, double *ny)
{
    const tt__terrains *ts = c->terr;
    int32_t best = -1;
    double bt = *t;
    for (uint32_t k = 0; k < ts->pool.count; k++) {
        const tt__terrain *T = &ts->t[k];
        if (!T->alive || !filter(w, T, i)) continue;
        double tk, gx, gy;
        if (march(T, x0, y0, x1 - x0, y1 - y0, seen_radius(T, w->radius[i]), bt, false, &tk, &gx, &gy) && tk < bt) {
            bt = tk;
            *nx = gx;
            *ny = gy;
            best = (int32_t)(TT__PRIM_TERRAIN | k);
        }
    }
    *t = bt;
    return best;
}

void tt__terrain_raycast(const tt_world *w, const tt__collide *c, tt_vec2 from, tt_vec2 to, uint16_t mask,
                         tt_ray_hit *out)
{
    (void)w;
    const tt__terrains *ts = c->terr;
    double bt = out->hit ? out->fraction : 1.0;
    for (uint32_t k = 0; k < ts->pool.count; k++) {
        const tt__terrain *T = &ts->t[k];
        if (!T->alive || !(T->def.category & mask)) continue;
        double tk, gx, gy;
        if (march(T, from.x, from.y, to.x - from.x, to.y - from.y, 0.0, bt, true, &tk, &gx, &gy) &&
            (tk < bt || !out->hit)) {
            bt = tk;
            out->hit = true;
            out->fraction = tk;
            out->particle = (tt_particle){0, 0};
            out->shape = (tt_shape){0, 0};
            out->terrain = (tt_terrain){k, ts->pool.gen[k]};
            out->normal = (tt_vec2){gx, gy};
        }
    }
}
