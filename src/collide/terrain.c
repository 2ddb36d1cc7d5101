/* tether — terrains: storage, the public calls, carving and filling, and
 * the distance band each contact reads. The band is a signed distance per
 * pixel to the boundary of the solid pixels, in pixels, clamped to ±band:
 * the nearest pixel of the other state found by vector propagation
 * (Danielsson's two passes), less half a pixel. A change of pixels moves
 * the clamped distance only within band of them, and those distances
 * depend only on pixels within band again: an update reads the changed box
 * grown by 2·band and writes it grown by band, whatever the terrain's size. */
#include "terrain_internal.h"

#include <stdlib.h>
#include <string.h>

#define FAR 0x3FFF /* no opposite pixel found (yet) */

bool tt__terrain_ok(const tt__collide *c, tt_terrain t)
{
    const tt__terrains *ts = c ? c->terr : NULL;
    return ts && t.index < ts->pool.count && t.gen != 0 && ts->pool.gen[t.index] == t.gen && ts->t[t.index].alive;
}

void tt__terrain_place(tt__terrain *T)
{
    const double s = T->def.pixel;
    T->inv = 1.0 / s;
    T->lox = T->def.origin.x;
    T->hix = T->def.origin.x + T->m->w * s;
    T->hiy = T->def.origin.y;
    T->loy = T->def.origin.y - T->m->h * s;
}

/* Pixel (x, y)'s state; outside the terrain empty. */
static inline int state(const tt_mask *m, int x, int y)
{
    return x >= 0 && y >= 0 && x < m->w && y < m->h ? tt__mask_bit(m, x, y) : 0;
}

typedef struct region {
    int x0, y0, w, h; /* the region read */
} region;

/* A pixel's best vector so far, kept in registers while its neighbours are
 * offered (d: its squared length, INT32_MAX for none). */
typedef struct best {
    int x, y;
    int32_t d;
} best;

static inline best load(const int16_t *vx, const int16_t *vy, size_t k)
{
    best b = {vx[k], vy[k], INT32_MAX};
    if (vx[k] != FAR) b.d = b.x * b.x + b.y * b.y;
    return b;
}

/* Neighbour n, (ox, oy) away, offered to a pixel of state sk. */
static inline void offer(best *b, const uint8_t *st, const int16_t *vx, const int16_t *vy, size_t n, uint8_t sk, int ox,
                         int oy)
{
    int cx, cy;
    if (st[n] != sk) {
        cx = ox;
        cy = oy;
    } else {
        if (vx[n] == FAR) return;
        cx = vx[n] + ox;
        cy = vy[n] + oy;
    }
    const int32_t d = cx * cx + cy * cy;
    if (d < b->d) {
        b->x = cx;
        b->y = cy;
        b->d = d;
    }
}

static inline void store(int16_t *vx, int16_t *vy, size_t k, best b)
{
    vx[k] = (int16_t)b.x;
    vy[k] = (int16_t)b.y;
}

/* Danielsson's two passes over the region: every pixel's vector to the
 * nearest pixel of the other state (approximately). Row passes offer the
 * row above (below) and the left (right) neighbour, then a pass the other
 * way offers the right (left) one. */
static void propagate(const region *R, const uint8_t *st, int16_t *vx, int16_t *vy)
{
    const int w = R->w, h = R->h;
    for (int y = 0; y < h; y++) {
        const size_t row = (size_t)y * (size_t)w;
        for (int x = 0; x < w; x++) {
            const size_t k = row + (size_t)x;
            const uint8_t sk = st[k];
            best b = load(vx, vy, k);
            if (x > 0) offer(&b, st, vx, vy, k - 1, sk, -1, 0);
            if (y > 0) {
                offer(&b, st, vx, vy, k - (size_t)w, sk, 0, -1);
                if (x > 0) offer(&b, st, vx, vy, k - (size_t)w - 1, sk, -1, -1);
                if (x < w - 1) offer(&b, st, vx, vy, k - (size_t)w + 1, sk, 1, -1);
            }
            store(vx, vy, k, b);
        }
        for (int x = w - 2; x >= 0; x--) {
            const size_t k = row + (size_t)x;
            best b = load(vx, vy, k);
            offer(&b, st, vx, vy, k + 1, st[k], 1, 0);
            store(vx, vy, k, b);
        }
    }
    for (int y = h - 1; y >= 0; y--) {
        const size_t row = (size_t)y * (size_t)w;
        for (int x = w - 1; x >= 0; x--) {
            const size_t k = row + (size_t)x;
            const uint8_t sk = st[k];
            best b = load(vx, vy, k);
            if (x < w - 1) offer(&b, st, vx, vy, k + 1, sk, 1, 0);
            if (y < h - 1) {
                offer(&b, st, vx, vy, k + (size_t)w, sk, 0, 1);
                if (x < w - 1) offer(&b, st, vx, vy, k + (size_t)w + 1, sk, 1, 1);
                if (x > 0) offer(&b, st, vx, vy, k + (size_t)w - 1, sk, -1, 1);
            }
            store(vx, vy, k, b);
        }
        for (int x = 1; x < w; x++) {
            const size_t k = row + (size_t)x;
            best b = load(vx, vy, k);
            offer(&b, st, vx, vy, k - 1, st[k], -1, 0);
            store(vx, vy, k, b);
        }
    }
}

static bool scratch(tt__terrains *ts, size_t n)
{
    if (ts->scap >= n) return true;
    int16_t *a = realloc(ts->vx, n * sizeof *a);
    if (!a) return false;
    ts->vx = a;
    int16_t *b = realloc(ts->vy, n * sizeof *b);
    if (!b) return false;
    ts->vy = b;
    uint8_t *c = realloc(ts->st, n);
    if (!c) return false;
    ts->st = c;
    ts->scap = n;
    return true;
}

static inline int clampi(int v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : v; }

/* The band is blurred by a box of 2·BLUR + 1 pixels each way (7: at 5 a
 * frictionless ball on a 30° pixel slope lost 4.7 % of g·sin θ to the
 * remaining bumps, at 7 1.4 %, at 40° 6.1 % and 2.3 %): a straight
 * surface's distance is linear and a box keeps it, while the bumps of its
 * pixel stairs (the nearest pixel hopping from one stair to the next) are
 * averaged away, so the gradient turns smoothly along a slope. */
#define BLUR 3

typedef struct regions_t {
    region R; /* read: states and vectors (a ring outside the terrain included) */
    region E; /* raw distances: W grown by the blur, within the terrain */
    region W; /* written */
} regions_t;

/* The regions an update of pixels [x0, x1] × [y0, y1] reads and writes. */
static void regions(const tt__terrain *T, int x0, int y0, int x1, int y1, regions_t *g)
{
    const tt_mask *m = T->m;
    const int B = T->def.band;
    /* written: the change grown by the band and the blur; raw: by the blur again; read: by the band again */
    const int wx0 = clampi(x0 - B - BLUR, 0, m->w - 1), wx1 = clampi(x1 + B + BLUR, 0, m->w - 1);
    const int wy0 = clampi(y0 - B - BLUR, 0, m->h - 1), wy1 = clampi(y1 + B + BLUR, 0, m->h - 1);
    g->W = (region){wx0, wy0, wx1 - wx0 + 1, wy1 - wy0 + 1};
    const int ex0 = clampi(wx0 - BLUR, 0, m->w - 1), ex1 = clampi(wx1 + BLUR, 0, m->w - 1);
    const int ey0 = clampi(wy0 - BLUR, 0, m->h - 1), ey1 = clampi(wy1 + BLUR, 0, m->h - 1);
    g->E = (region){ex0, ey0, ex1 - ex0 + 1, ey1 - ey0 + 1};
    /* a ring outside the terrain is read too: it is empty, the solid border's nearest free pixel */
    const int rx0 = ex0 - B - 1 < -1 ? -1 : ex0 - B - 1, ry0 = ey0 - B - 1 < -1 ? -1 : ey0 - B - 1;
    const int rx1 = ex1 + B + 1 > m->w ? m->w : ex1 + B + 1, ry1 = ey1 + B + 1 > m->h ? m->h : ey1 + B + 1;
    g->R = (region){rx0, ry0, rx1 - rx0 + 1, ry1 - ry0 + 1};
}

static bool fscratch(tt__terrains *ts, size_t n)
{
    if (ts->fcap >= n) return true;
    float *a = realloc(ts->fa, n * sizeof *a);
    if (!a) return false;
    ts->fa = a;
    float *b = realloc(ts->fb, n * sizeof *b);
    if (!b) return false;
    ts->fb = b;
    ts->fcap = n;
    return true;
}

bool tt__terrain_reserve(tt__terrains *ts, const tt__terrain *T, int x0, int y0, int x1, int y1)
{
    regions_t g;
    regions(T, x0, y0, x1, y1, &g);
    return scratch(ts, (size_t)g.R.w * (size_t)g.R.h) && fscratch(ts, (size_t)g.E.w * (size_t)g.E.h);
}

/* Raw distances over E from the vectors over R. */
static void raw(const tt__terrains *ts, const regions_t *g, int B)
{
    const region *R = &g->R, *E = &g->E;
    for (int y = 0; y < E->h; y++)
        for (int x = 0; x < E->w; x++) {
            const size_t k = (size_t)(E->y0 + y - R->y0) * (size_t)R->w + (size_t)(E->x0 + x - R->x0);
            double d = B;
            if (ts->vx[k] != FAR) {
                d = sqrt((double)(ts->vx[k] * ts->vx[k] + ts->vy[k] * ts->vy[k])) - 0.5;
                d = d > B ? B : d;
            }
            ts->fa[(size_t)y * (size_t)E->w + (size_t)x] = (float)(ts->st[k] ? -d : d);
        }
}

/* The box blur of the raw distances into T's band over W: rows, then
 * columns; at the terrain's border the edge pixel stands for those beyond. */
static void blur(const tt__terrains *ts, tt__terrain *T, const regions_t *g)
{
    const region *E = &g->E, *W = &g->W;
    const float *fa = ts->fa;
    float *fb = ts->fb; /* rows of E, columns of W */
    const double inv = 1.0 / (2 * BLUR + 1);
    const int ex1 = E->x0 + E->w - 1, ey1 = E->y0 + E->h - 1;
    /* away from the terrain's border no tap is clamped: the same sums, without the clamps */
    const bool xin = W->x0 - BLUR >= E->x0 && W->x0 + W->w - 1 + BLUR <= ex1;
    const bool yin = W->y0 - BLUR >= E->y0 && W->y0 + W->h - 1 + BLUR <= ey1;
    for (int y = 0; y < E->h; y++) {
        const float *in = fa + (size_t)y * (size_t)E->w - E->x0;
        float *out = fb + (size_t)y * (size_t)W->w - W->x0;
        for (int x = W->x0; x < W->x0 + W->w; x++) {
            double sum = 0.0;
            if (xin)
                for (int k = -BLUR; k <= BLUR; k++) sum += in[x + k];
            else
                for (int k = -BLUR; k <= BLUR; k++) sum += in[clampi(x + k, E->x0, ex1)];
            out[x] = (float)(sum * inv);
        }
    }
    for (int y = W->y0; y < W->y0 + W->h; y++) {
        float *out = T->sdf + (size_t)y * (size_t)T->m->w;
        const float *rows[2 * BLUR + 1];
        for (int k = -BLUR; k <= BLUR; k++)
            rows[k + BLUR] = fb + (size_t)((yin ? y + k : clampi(y + k, E->y0, ey1)) - E->y0) * (size_t)W->w - W->x0;
        for (int x = W->x0; x < W->x0 + W->w; x++) {
            double sum = 0.0;
            for (int k = 0; k <= 2 * BLUR; k++) sum += rows[k][x];
            out[x] = (float)(sum * inv);
        }
    }
}

bool tt__terrain_update(tt__terrains *ts, tt__terrain *T, int x0, int y0, int x1, int y1)
{
    const tt_mask *m = T->m;
    regions_t g;
    regions(T, x0, y0, x1, y1, &g);
    const region R = g.R;
    const size_t n = (size_t)R.w * (size_t)R.h;
    if (!scratch(ts, n) || !fscratch(ts, (size_t)g.E.w * (size_t)g.E.h)) return false;
    for (int y = 0; y < R.h; y++) {
        uint8_t *row = ts->st + (size_t)y * (size_t)R.w;
        for (int x = 0; x < R.w; x++) row[x] = (uint8_t)state(m, R.x0 + x, R.y0 + y);
    }
    for (size_t k = 0; k < n; k++) ts->vx[k] = ts->vy[k] = FAR;
    propagate(&R, ts->st, ts->vx, ts->vy);
    raw(ts, &g, T->def.band);
    blur(ts, T, &g);
    return true;
}

void tt__terrain_free_one(tt__terrain *T)
{
    tt_mask_destroy(T->m);
    free(T->sdf);
    T->m = NULL;
    T->sdf = NULL;
    T->alive = false;
}

void tt__terrains_free(tt__terrains *ts)
{
    if (!ts) return;
    for (uint32_t i = 0; i < ts->pool.count; i++)
        if (ts->t[i].alive) tt__terrain_free_one(&ts->t[i]);
    tt_pool_destroy(&ts->pool);
    free(ts->t);
    free(ts->vx);
    free(ts->vy);
    free(ts->st);
    free(ts->fa);
    free(ts->fb);
    free(ts);
}

size_t tt__terrains_bytes(const tt__terrains *ts)
{
    if (!ts) return 0;
    size_t b = sizeof *ts + tt_pool_bytes(&ts->pool) + (size_t)ts->cap * sizeof *ts->t + ts->scap * 5 + ts->fcap * 2 * sizeof(float);
    for (uint32_t i = 0; i < ts->pool.count; i++) {
        const tt__terrain *T = &ts->t[i];
        if (T->alive) b += tt_mask_footprint(T->m->w, T->m->h) + (size_t)T->m->w * (size_t)T->m->h * sizeof(float);
    }
    return b;
}

void tt__terrain_changed(tt_world *w, double lox, double loy, double hix, double hiy)
{
    /* Sleeping (issue 22) wakes the particles in this rectangle here. Until
     * then nothing rests without being tested every substep. */
    (void)w; (void)lox; (void)loy; (void)hix; (void)hiy;
}
