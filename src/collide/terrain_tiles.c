/* tether — a terrain's tile map: per TT__TILE × TT__TILE pixels, the least
 * value of the distance band in the tile. It spares the particles far from
 * every surface the terrain's per-particle test (contacts, each substep):
 * the cells of the particle grid that no tile near a surface reaches are
 * marked far, and a particle in a far cell is skipped with one byte load,
 * as the shapes' near cells do (contact_detect.c).
 *
 * Exact by construction: the per-particle test (terrain_contact.c) skips a
 * particle when (b − 1)·pixel > reach, b the band at the pixel holding its
 * centre (outside the terrain: band). A tile whose least value m passes
 * that test for the largest reach in the grid (rounding is monotone, so
 * every value ≥ m and every smaller reach passes it too) holds no pixel
 * that could give a contact; every other tile (solid ones too: a buried
 * particle is pushed out) marks the cells its pixels' boxes, grown by a
 * pixel (and far more than any rounding), reach. Cell coordinates are monotone in position, so a particle
 * whose pixel is in such a tile lands in a marked cell. The map is derived
 * from the band, updated with it (the tiles the changed box meets, so a
 * carve costs in proportion to its area), rebuilt on load, never saved. */
#include "terrain_internal.h"

#include <string.h>

static inline int mini(int a, int b) { return a < b ? a : b; }

typedef float f32v __attribute__((vector_size(16)));
typedef int32_t i32v __attribute__((vector_size(16)));

/* The least of the n floats at p (min is exact in any order). */
static inline float least(const float *p, int n)
{
    float m = INFINITY;
    int k = 0;
    if (n == TT__TILE) { /* a whole tile row: four floats at a time */
        f32v v;
        memcpy(&v, p, sizeof v);
        for (k = 4; k < TT__TILE; k += 4) {
            f32v q;
            memcpy(&q, p + k, sizeof q);
            const i32v lt = q < v;
            v = (f32v)(((i32v)q & lt) | ((i32v)v & ~lt));
        }
        for (int j = 0; j < 4; j++) m = v[j] < m ? v[j] : m;
    }
    for (; k < n; k++) m = p[k] < m ? p[k] : m;
    return m;
}

void tt__terrain_tiles_update(tt__terrain *T, int x0, int y0, int x1, int y1)
{
    const int w = T->m->w, h = T->m->h;
    const int tx0 = x0 >> TT__TILE_SHIFT, tx1 = x1 >> TT__TILE_SHIFT;
    const int ty0 = y0 >> TT__TILE_SHIFT, ty1 = y1 >> TT__TILE_SHIFT;
    for (int ty = ty0; ty <= ty1; ty++) {
        float *tile = T->tile + (size_t)ty * (size_t)T->tw;
        for (int tx = tx0; tx <= tx1; tx++) tile[tx] = INFINITY;
        const int ya = ty << TT__TILE_SHIFT, yb = mini(ya + TT__TILE, h);
        for (int y = ya; y < yb; y++) {
            const float *row = T->sdf + (size_t)y * (size_t)w;
            for (int tx = tx0; tx <= tx1; tx++) { /* whole tiles */
                const int xa = tx << TT__TILE_SHIFT;
                const float m = least(row + xa, mini(xa + TT__TILE, w) - xa);
                tile[tx] = m < tile[tx] ? m : tile[tx];
            }
        }
    }
}

/* A coordinate clamped into [lo, hi] before it becomes an int (NaN: lo). */
static inline int clampd(double v, int lo, int hi) { return !(v >= lo) ? lo : v > hi ? hi : (int)v; }

/* Marks the cells that T's near tiles reach. */
static void mark(const tt__terrain *T, const tt__grid *g, double reach, uint8_t *near)
{
    const double s = T->def.pixel, ox = T->def.origin.x, oy = T->def.origin.y, t = TT__TILE * s;
    const double gx1 = g->ox + g->nx * g->cs, gy1 = g->oy + g->ny * g->cs;
    /* a pixel, and far more than the rounding of a particle's pixel and of the grid's bounds */
    const double e = s + 1e-13 * (fabs(ox) + fabs(oy) + (T->m->w + T->m->h) * s + fabs(g->ox) + fabs(g->oy) + fabs(gx1) + fabs(gy1));
    /* the tiles that can hold the pixel of a particle inside the grid: its box, grown, in tiles */
    const int tx0 = clampd(floor((g->ox - e - ox) / t) - 1.0, 0, T->tw - 1), tx1 = clampd(floor((gx1 + e - ox) / t) + 1.0, 0, T->tw - 1);
    const int ty0 = clampd(floor((oy - gy1 - e) / t) - 1.0, 0, T->th - 1), ty1 = clampd(floor((oy - g->oy + e) / t) + 1.0, 0, T->th - 1);
    for (int ty = ty0; ty <= ty1; ty++) {
        const float *tile = T->tile + (size_t)ty * (size_t)T->tw;
        /* the tile row's pixel rows, as world y, grown by e */
        const int ya = ty << TT__TILE_SHIFT, yb = mini(ya + TT__TILE, T->m->h);
        int32_t cy0 = tt__cell_coord(oy - yb * s - e, g->oy, g->inv), cy1 = tt__cell_coord(oy - ya * s + e, g->oy, g->inv);
        if (cy1 < 0 || cy0 >= g->ny) continue;
        cy0 = cy0 < 0 ? 0 : cy0;
        cy1 = cy1 >= g->ny ? g->ny - 1 : cy1;
        for (int tx = tx0; tx <= tx1; tx++) {
            if (((double)tile[tx] - 1.0) * s > reach) continue; /* far: no pixel of it can give a contact */
            int tx2 = tx; /* a run of near tiles is one box */
            while (tx2 < tx1 && !(((double)tile[tx2 + 1] - 1.0) * s > reach)) tx2++;
            const int xa = tx << TT__TILE_SHIFT, xb = mini((tx2 + 1) << TT__TILE_SHIFT, T->m->w);
            int32_t cx0 = tt__cell_coord(ox + xa * s - e, g->ox, g->inv), cx1 = tt__cell_coord(ox + xb * s + e, g->ox, g->inv);
            tx = tx2;
            if (cx1 < 0 || cx0 >= g->nx) continue;
            cx0 = cx0 < 0 ? 0 : cx0;
            cx1 = cx1 >= g->nx ? g->nx - 1 : cx1;
            for (int32_t cy = cy0; cy <= cy1; cy++)
                memset(near + (size_t)cy * (size_t)g->nx + (size_t)cx0, 1, (size_t)(cx1 - cx0 + 1));
        }
    }
}

bool tt__terrain_near_cells(const tt__terrains *ts, const tt__grid *g, uint8_t *near, uint32_t cap)
{
    if (ts->no_tiles || g->ncell == 0 || g->ncell > cap) return false;
    const double r = g->rmax, reach = r + r * TT__CONTACT_MARGIN; /* as the test computes a particle's */
    for (uint32_t k = 0; k < ts->pool.count; k++) {
        const tt__terrain *T = &ts->t[k];
        /* outside the terrain the band reads band: a reach that passes no test there needs every particle tested */
        if (T->alive && !(((double)T->def.band - 1.0) * T->def.pixel > reach)) return false;
    }
    memset(near, 0, g->ncell);
    for (uint32_t k = 0; k < ts->pool.count; k++)
        if (ts->t[k].alive) mark(&ts->t[k], g, reach, near);
    return true;
}
