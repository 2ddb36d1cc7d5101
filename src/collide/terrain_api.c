/* tether — terrains' public calls: making and removing them, carving and
 * filling (circles, masks), materials, reading them back, and the point and
 * box query that lists them. */
#include "terrain_internal.h"

#include <stdlib.h>
#include <string.h>

tt_terrain_def tt_terrain_def_default(void)
{
    tt_terrain_def d;
    memset(&d, 0, sizeof d);
    d.pixel = 0.05;
    d.band = 10;
    d.friction_static = 0.6;
    d.friction_kinetic = 0.5;
    d.category = 0x0001;
    d.mask = 0xFFFF;
    return d;
}

static tt_result check_def(const tt_world *w, const tt_terrain_def *d, const char *fn)
{
    if (!d) return tt__fail(w, TT_EINVAL, "%s: def is NULL", fn);
    if (!d->solid) return tt__fail(w, TT_EINVAL, "%s: def.solid (the mask) is NULL", fn);
    if (!tt__vec_ok(d->origin)) return tt__fail(w, TT_EINVAL, "%s: origin must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    int mw, mh;
    tt_mask_size(d->solid, &mw, &mh);
    const double side = (mw > mh ? mw : mh);
    if (!(d->pixel > 0.0) || !(d->pixel * side <= TT_MAX_VALUE) || !(d->pixel >= 1e-9))
        return tt__fail(w, TT_EINVAL, "%s: pixel must be in [1e-9, %g / side] m, got %g", fn, TT_MAX_VALUE, d->pixel);
    if (d->band < 5 || d->band > TT_TERRAIN_MAX_BAND)
        return tt__fail(w, TT_EINVAL, "%s: band must be in [5, %d] pixels, got %d", fn, TT_TERRAIN_MAX_BAND, d->band);
    return tt__material_check(w, d->restitution, d->friction_static, d->friction_kinetic, TT_MAX_VALUE, fn);
}

/* Makes slot i's terrain from def; false on no memory (nothing kept). */
static bool build(tt__terrains *ts, tt__terrain *T, const tt_terrain_def *def)
{
    memset(T, 0, sizeof *T);
    T->m = tt_mask_copy(def->solid);
    if (!T->m) return false;
    T->def = *def;
    T->def.solid = NULL;
    if (!tt__terrain_alloc(T) || !tt__terrain_update(ts, T, 0, 0, T->m->w - 1, T->m->h - 1)) {
        tt__terrain_free_one(T);
        return false;
    }
    tt__terrain_place(T);
    T->alive = true;
    return true;
}

tt_terrain tt_terrain_create(tt_world *w, const tt_terrain_def *def)
{
    const tt_terrain none = {0, 0};
    const char *fn = "tt_terrain_create";
    if (!w) { tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn); return none; }
    if (check_def(w, def, fn) != TT_OK) return none;
    const bool had = tt__collide_peek(w) != NULL;
    tt__collide *c = tt__collide_get(w, true, fn);
    if (!c) return none;
    const bool had_terr = c->terr != NULL;
    if (!c->terr) {
        c->terr = calloc(1, sizeof *c->terr);
        if (c->terr) c->terr->pool.tag = w->tag;
    }
    tt__terrains *ts = c->terr;
    uint32_t i = UINT32_MAX;
    if (ts && ts->alive < TT_MAX_TERRAINS) {
        bool grew;
        uint32_t need = ts->pool.free_count ? ts->pool.count : ts->pool.count + 1;
        if (tt__grow((void **)&ts->t, &ts->cap, need, sizeof *ts->t)) {
            tt__pool_mark mark = tt__pool_mark_now(&ts->pool);
            i = tt__pool_alloc(&ts->pool, TT_MAX_TERRAINS, &grew);
            if (i != UINT32_MAX && !build(ts, &ts->t[i], def)) {
                tt__pool_rewind(&ts->pool, mark);
                i = UINT32_MAX;
            }
        }
    }
    if (i == UINT32_MAX) { /* a failed call leaves the world as it was */
        if (!had_terr) {
            tt__terrains_free(c->terr);
            c->terr = NULL;
        }
        if (!had) tt__group_remove(w, &tt__contacts_ops);
        tt__fail(w, TT_ENOMEM, ts && ts->alive >= TT_MAX_TERRAINS ? "%s: the world has the most terrains allowed"
                                                                    : "%s: out of memory", fn);
        return none;
    }
    ts->alive++;
    return (tt_terrain){i, ts->pool.gen[i]};
}

/* Opens a public call on terrain t: leaves c and T, or fails. */
#define TERRAIN_CHECK(fn)                                                                                     \
    if (!w) return tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn);                                       \
    tt__collide *c = tt__collide_peek(w);                                                                     \
    if (!tt__terrain_ok(c, t))                                                                                \
        return tt__fail(w, TT_ESTALE, "%s: stale terrain handle (index %u, generation %u)", fn, t.index, t.gen); \
    tt__terrain *T = &c->terr->t[t.index]

tt_result tt_terrain_destroy(tt_world *w, tt_terrain t)
{
    TERRAIN_CHECK("tt_terrain_destroy");
    tt__terrain_free_one(T);
    tt__pool_free(&c->terr->pool, t.index);
    c->terr->alive--;
    /* its contacts of the last step will never END: drop them */
    const uint64_t match = (3ull << 62) | ((uint64_t)t.index << 32);
    uint32_t k = 0;
    for (uint32_t j = 0; j < c->nprev; j++)
        if ((c->prev[j].key & 0xFFFFFFFF00000000ull) != match) c->prev[k++] = c->prev[j];
    c->nprev = k;
    return TT_OK;
}

bool tt_terrain_is_valid(const tt_world *w, tt_terrain t) { return w && tt__terrain_ok(tt__collide_peek(w), t); }

uint32_t tt_world_terrain_count(const tt_world *w)
{
    const tt__collide *c = w ? tt__collide_peek(w) : NULL;
    return c && c->terr ? c->terr->alive : 0;
}

/* After pixels [x0, x1] × [y0, y1] changed: the band, and the hook. */
static tt_result changed(tt_world *w, tt__collide *c, tt__terrain *T, int x0, int y0, int x1, int y1, const char *fn)
{
    if (x0 > x1) return TT_OK; /* nothing changed */
    (void)fn;
    tt__terrain_update(c->terr, T, x0, y0, x1, y1); /* reserved before the first pixel changed */
    const double s = T->def.pixel, B = T->def.band;
    tt__terrain_changed(w, T->def.origin.x + (x0 - B) * s, T->def.origin.y - (y1 + 1 + B) * s,
                        T->def.origin.x + (x1 + 1 + B) * s, T->def.origin.y - (y0 - B) * s);
    return TT_OK;
}

/* Whether pixel (x, y)'s centre lies in the circle (cu, cv, rp), in pixels. */
static inline bool inside(double cu, double cv, double rp, int x, int y)
{
    const double dx = x + 0.5 - cu, dy = y + 0.5 - cv;
    return !(dx * dx + dy * dy > rp * rp);
}

/* Row y's pixels in the circle, within [fx0, fx1]: [*a, *b], or false. The
 * square root only guesses the ends; the test above decides them. */
static bool span(double cu, double cv, double rp, int y, int fx0, int fx1, int *a, int *b)
{
    const double dy = y + 0.5 - cv, h2 = rp * rp - dy * dy;
    const double h = h2 > 0.0 ? sqrt(h2) : 0.0;
    int lo = (int)fmax(fmin(floor(cu - h - 0.5), fx1), fx0), hi = (int)fmax(fmin(ceil(cu + h - 0.5), fx1), fx0);
    while (lo > fx0 && inside(cu, cv, rp, lo - 1, y)) lo--;
    while (lo <= hi && !inside(cu, cv, rp, lo, y)) lo++;
    while (hi < fx1 && inside(cu, cv, rp, hi + 1, y)) hi++;
    while (hi >= lo && !inside(cu, cv, rp, hi, y)) hi--;
    *a = lo;
    *b = hi;
    return lo <= hi;
}

/* Sets (solid) or clears pixels [a, b] of a row's words; the first and last
 * that changed into *lo, *hi, or false when none did. */
static bool put_span(uint64_t *row, int a, int b, bool solid, int *lo, int *hi)
{
    *lo = INT32_MAX;
    *hi = -1;
    for (int j = a >> 6; j <= b >> 6; j++) {
        const int s0 = j == a >> 6 ? a & 63 : 0, s1 = j == b >> 6 ? b & 63 : 63;
        const uint64_t mask = (s1 == 63 ? ~(uint64_t)0 : ((uint64_t)1 << (s1 + 1)) - 1) & ~(((uint64_t)1 << s0) - 1);
        const uint64_t flip = mask & (solid ? ~row[j] : row[j]);
        if (!flip) continue;
        row[j] ^= flip;
        if (*lo == INT32_MAX) *lo = 64 * j + __builtin_ctzll(flip);
        *hi = 64 * j + 63 - __builtin_clzll(flip);
    }
    return *hi >= 0;
}

tt_result tt_terrain_paint_circle(tt_world *w, tt_terrain t, tt_vec2 centre, double radius, bool solid)
{
    const char *fn = "tt_terrain_paint_circle";
    TERRAIN_CHECK(fn);
    if (!tt__vec_ok(centre)) return tt__fail(w, TT_EINVAL, "%s: centre must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    if (!tt__in_range(radius, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "%s: radius must be in [0, %g], got %g", fn, TT_MAX_VALUE, radius);
    tt_mask *m = T->m;
    const double cu = (centre.x - T->def.origin.x) * T->inv, cv = (T->def.origin.y - centre.y) * T->inv;
    const double rp = radius * T->inv;
    /* pixel centres (x + 0.5, y + 0.5) within rp of (cu, cv), clamped before any conversion */
    const double fx0 = fmax(floor(cu - rp), 0.0), fx1 = fmin(ceil(cu + rp), m->w - 1.0);
    const double fy0 = fmax(floor(cv - rp), 0.0), fy1 = fmin(ceil(cv + rp), m->h - 1.0);
    int x0 = m->w, y0 = m->h, x1 = -1, y1 = -1; /* what changed */
    if (fx0 <= fx1 && fy0 <= fy1) {
        if (!tt__terrain_reserve(c->terr, T, (int)fx0, (int)fy0, (int)fx1, (int)fy1))
            return tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        for (int y = (int)fy0; y <= (int)fy1; y++) {
            int a, b;
            if (!span(cu, cv, rp, y, (int)fx0, (int)fx1, &a, &b)) continue;
            int lo, hi;
            if (!put_span(tt__mask_row(m, y), a, b, solid, &lo, &hi)) continue;
            x0 = lo < x0 ? lo : x0; x1 = hi > x1 ? hi : x1;
            y0 = y < y0 ? y : y0; y1 = y > y1 ? y : y1;
        }
    }
    return changed(w, c, T, x0, y0, x1, y1, fn);
}

tt_result tt_terrain_paint_mask(tt_world *w, tt_terrain t, const tt_mask *src, int dx, int dy, bool solid)
{
    const char *fn = "tt_terrain_paint_mask";
    TERRAIN_CHECK(fn);
    if (!src) return tt__fail(w, TT_EINVAL, "%s: mask is NULL", fn);
    if (dx < -TT_MASK_MAX_OFFSET || dx > TT_MASK_MAX_OFFSET || dy < -TT_MASK_MAX_OFFSET || dy > TT_MASK_MAX_OFFSET)
        return tt__fail(w, TT_EINVAL, "%s: offset must be within ±%d", fn, TT_MASK_MAX_OFFSET);
    tt_mask *m = T->m;
    /* the part of src that lands on the terrain, in terrain pixels */
    const int fx0 = dx > 0 ? dx : 0, fy0 = dy > 0 ? dy : 0;
    const int fx1 = (int)fmin((double)dx + src->w - 1, m->w - 1.0), fy1 = (int)fmin((double)dy + src->h - 1, m->h - 1.0);
    int x0 = m->w, y0 = m->h, x1 = -1, y1 = -1;
    if (fx0 <= fx1 && fy0 <= fy1) {
        if (!tt__terrain_reserve(c->terr, T, fx0, fy0, fx1, fy1)) return tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        for (int y = fy0; y <= fy1; y++)
            for (int x = fx0; x <= fx1; x++) {
                if (!tt__mask_bit(src, x - dx, y - dy) || tt__mask_bit(m, x, y) == (int)solid) continue;
                tt__mask_put(m, x, y, solid);
                x0 = x < x0 ? x : x0; x1 = x > x1 ? x : x1;
                y0 = y < y0 ? y : y0; y1 = y > y1 ? y : y1;
            }
    }
    return changed(w, c, T, x0, y0, x1, y1, fn);
}

tt_result tt_terrain_get_mask(const tt_world *w, tt_terrain t, const tt_mask **out)
{
    TERRAIN_CHECK("tt_terrain_get_mask");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_terrain_get_mask: out is NULL");
    *out = T->m;
    return TT_OK;
}

tt_result tt_terrain_get_place(const tt_world *w, tt_terrain t, tt_mask_place *out)
{
    TERRAIN_CHECK("tt_terrain_get_place");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_terrain_get_place: out is NULL");
    *out = (tt_mask_place){T->def.origin, T->def.pixel};
    return TT_OK;
}

tt_result tt_terrain_set_material(tt_world *w, tt_terrain t, double restitution, double friction_static,
                                  double friction_kinetic)
{
    TERRAIN_CHECK("tt_terrain_set_material");
    tt_result r = tt__material_check(w, restitution, friction_static, friction_kinetic, TT_MAX_VALUE,
                                     "tt_terrain_set_material");
    if (r != TT_OK) return r;
    T->def.restitution = restitution;
    T->def.friction_static = friction_static;
    T->def.friction_kinetic = friction_kinetic;
    return TT_OK;
}

tt_result tt_terrain_get_user(const tt_world *w, tt_terrain t, uint64_t *out)
{
    TERRAIN_CHECK("tt_terrain_get_user");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_terrain_get_user: out is NULL");
    *out = T->def.user;
    return TT_OK;
}

tt_result tt_terrain_distance(const tt_world *w, tt_terrain t, tt_vec2 p, double *distance, tt_vec2 *normal)
{
    TERRAIN_CHECK("tt_terrain_distance");
    if (!tt__vec_ok(p)) return tt__fail(w, TT_EINVAL, "tt_terrain_distance: point must be finite, |x| <= %g", TT_MAX_VALUE);
    double nx, ny, d = tt__terrain_sample(T, p.x, p.y, &nx, &ny);
    if (distance) *distance = d;
    if (normal) *normal = (tt_vec2){nx, ny};
    return TT_OK;
}

tt_result tt_terrain_is_solid(const tt_world *w, tt_terrain t, tt_vec2 p, bool *out)
{
    TERRAIN_CHECK("tt_terrain_is_solid");
    if (!tt__vec_ok(p)) return tt__fail(w, TT_EINVAL, "tt_terrain_is_solid: point must be finite, |x| <= %g", TT_MAX_VALUE);
    if (!out) return tt__fail(w, TT_EINVAL, "tt_terrain_is_solid: out is NULL");
    const double u = floor((p.x - T->def.origin.x) * T->inv), v = floor((T->def.origin.y - p.y) * T->inv);
    *out = u >= 0 && v >= 0 && u < T->m->w && v < T->m->h && tt__mask_bit(T->m, (int)u, (int)v);
    return TT_OK;
}

/* Whether a solid pixel of T (closed squares) meets the world box lo–hi. */
static bool solid_in_box(const tt__terrain *T, tt_vec2 lo, tt_vec2 hi)
{
    const tt_mask *m = T->m;
    /* pixel u's square [u, u + 1] meets [a, b] when ceil(a) − 1 ≤ u ≤ floor(b); clamped before any cast */
    const double u0 = fmax(ceil((lo.x - T->def.origin.x) * T->inv) - 1.0, 0.0);
    const double u1 = fmin(floor((hi.x - T->def.origin.x) * T->inv), m->w - 1.0);
    const double v0 = fmax(ceil((T->def.origin.y - hi.y) * T->inv) - 1.0, 0.0);
    const double v1 = fmin(floor((T->def.origin.y - lo.y) * T->inv), m->h - 1.0);
    if (!(u0 <= u1 && v0 <= v1)) return false;
    const int a = (int)u0, b = (int)u1;
    for (int y = (int)v0; y <= (int)v1; y++) {
        const uint64_t *row = tt__mask_row(m, y);
        for (int j = a >> 6; j <= b >> 6; j++) {
            const int s0 = j == a >> 6 ? a & 63 : 0, s1 = j == b >> 6 ? b & 63 : 63;
            const uint64_t span = (s1 == 63 ? ~(uint64_t)0 : ((uint64_t)1 << (s1 + 1)) - 1) & ~(((uint64_t)1 << s0) - 1);
            if (row[j] & span) return true;
        }
    }
    return false;
}

tt_result tt_world_query_terrains(const tt_world *w, tt_vec2 lo, tt_vec2 hi, uint16_t mask, tt_terrain *out,
                                  uint32_t cap, uint32_t *n)
{
    const char *fn = "tt_world_query_terrains";
    if (!w) return tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn);
    if (!tt__vec_ok(lo) || !tt__vec_ok(hi)) return tt__fail(w, TT_EINVAL, "%s: lo and hi must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    if (hi.x < lo.x || hi.y < lo.y) return tt__fail(w, TT_EINVAL, "%s: hi must be >= lo", fn);
    if (cap && !out) return tt__fail(w, TT_EINVAL, "%s: out is NULL with a capacity > 0", fn);
    const tt__collide *c = tt__collide_peek(w);
    uint32_t count = 0;
    for (uint32_t i = 0; c && c->terr && i < c->terr->pool.count; i++) {
        const tt__terrain *T = &c->terr->t[i];
        if (!T->alive || !(T->def.category & mask) || !solid_in_box(T, lo, hi)) continue;
        if (count < cap) out[count] = (tt_terrain){i, c->terr->pool.gen[i]};
        count++;
    }
    if (n) *n = count;
    return TT_OK;
}
