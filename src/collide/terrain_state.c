/* tether — terrains in the snapshot stream: appended to the contacts
 * section ("COLL") after everything else, and only when the world has had
 * a terrain, so a world without terrains writes (and hashes) what it always
 * did, and a stream written before terrains existed still loads. Each live
 * terrain writes its settings and its pixels, row words as the mask holds
 * them; the distance band and its tile map are derived and rebuilt on load. Then the terrain
 * of each of the last step's contact records and events (the event record
 * the contacts section writes has no field for it, and other worlds'
 * streams stay as they were). */
#include "terrain_internal.h"
#include "core/stream.h"

#include <stdlib.h>
#include <string.h>

/* 2: the terrain handles of the last step's contact records and events
 * follow the terrains (1 had none: its events load without them). */
#define VERSION 2u

void tt__terrains_save(const tt__collide *c, tt__sink *s)
{
    const tt__terrains *ts = c->terr;
    tt__put_u32(s, TT__ID('T', 'E', 'R', 'R'));
    tt__put_u32(s, VERSION);
    tt__put_pool(s, &ts->pool);
    for (uint32_t i = 0; i < ts->pool.count; i++) {
        const tt__terrain *T = &ts->t[i];
        tt__put_u8(s, T->alive);
        if (!T->alive) continue;
        const tt_terrain_def *d = &T->def;
        tt__put(s, &d->origin, sizeof d->origin);
        tt__put_f64(s, d->pixel);
        tt__put_u32(s, (uint32_t)d->band);
        tt__put_f64(s, d->restitution);
        tt__put_f64(s, d->friction_static);
        tt__put_f64(s, d->friction_kinetic);
        tt__put_u16(s, d->category);
        tt__put_u16(s, d->mask);
        tt__put_u64(s, d->user);
        tt__put_u32(s, (uint32_t)T->m->w);
        tt__put_u32(s, (uint32_t)T->m->h);
        tt__put(s, T->m->bits, (size_t)T->m->h * (size_t)T->m->stride * sizeof *T->m->bits);
    }
    for (uint32_t k = 0; k < c->nprev; k++) {
        tt__put_u32(s, c->prev[k].ev.terrain.index);
        tt__put_gen(s, c->prev[k].ev.terrain.gen);
    }
    for (uint32_t k = 0; k < c->nevents; k++) {
        tt__put_u32(s, c->events[k].terrain.index);
        tt__put_gen(s, c->events[k].terrain.gen);
    }
}

/* One live terrain into T (zeroed); false with the source failed. */
static bool load_one(tt__terrains *ts, tt__terrain *T, tt__source *s)
{
    tt_terrain_def d;
    memset(&d, 0, sizeof d); /* every field but solid is read below */
    d.origin.x = tt__get_num(s, -TT_MAX_VALUE, TT_MAX_VALUE, "terrain origin");
    d.origin.y = tt__get_num(s, -TT_MAX_VALUE, TT_MAX_VALUE, "terrain origin");
    d.pixel = tt__get_num(s, 1e-9, TT_MAX_VALUE, "terrain pixel");
    const uint32_t band = tt__get_u32(s);
    d.restitution = tt__get_num(s, 0.0, 1.0, "terrain restitution");
    d.friction_static = tt__get_num(s, 0.0, TT_MAX_VALUE, "terrain static friction");
    d.friction_kinetic = tt__get_num(s, 0.0, TT_MAX_VALUE, "terrain kinetic friction");
    d.category = tt__get_u16(s);
    d.mask = tt__get_u16(s);
    d.user = tt__get_u64(s);
    const uint32_t w = tt__get_u32(s), h = tt__get_u32(s);
    if (s->failed) return false;
    if (band < 5 || band > TT_TERRAIN_MAX_BAND) return tt__src_fail(s, "terrain band %u", band);
    if (w < 1 || h < 1 || w > TT_MASK_MAX_SIDE || h > TT_MASK_MAX_SIDE) return tt__src_fail(s, "terrain size %ux%u", w, h);
    if (d.pixel * (w > h ? w : h) > TT_MAX_VALUE) return tt__src_fail(s, "terrain pixel %g", d.pixel);
    d.band = (int)band;
    tt_mask *m = tt_mask_create((int)w, (int)h, false);
    if (!m) return tt__src_fail(s, "out of memory");
    const size_t bytes = (size_t)m->h * (size_t)m->stride * sizeof *m->bits;
    const void *bits = tt__get_span(s, bytes);
    if (!bits) {
        tt_mask_destroy(m);
        return false;
    }
    memcpy(m->bits, bits, bytes);
    /* the bits past w in each row stay zero (every mask loop counts on it) */
    const uint64_t tail = (w & 63) ? ~((1ull << (w & 63)) - 1) : 0;
    for (uint32_t y = 0; y < h && tail; y++)
        if (tt__mask_row(m, (int)y)[m->stride - 1] & tail) {
            tt_mask_destroy(m);
            return tt__src_fail(s, "terrain row %u has bits past its width", y);
        }
    T->m = m;
    T->def = d;
    if (!tt__terrain_alloc(T) || !tt__terrain_update(ts, T, 0, 0, (int)w - 1, (int)h - 1)) {
        tt__terrain_free_one(T);
        return tt__src_fail(s, "out of memory");
    }
    tt__terrain_place(T);
    T->alive = true;
    return true;
}

/* The terrains of the last step's records (each must name the live terrain
 * its key names, or none when its key names no terrain) and events. */
static bool load_handles(const tt__collide *c, tt__source *s)
{
    for (uint32_t k = 0; k < c->nprev; k++) {
        tt_terrain *t = &c->prev[k].ev.terrain;
        t->index = tt__get_u32(s);
        t->gen = tt__get_u32(s);
        const uint64_t key = c->prev[k].key;
        const bool terr = (key >> 62) == 3;
        const uint32_t slot = (uint32_t)(key >> 32) & 0x3FFFFFFFu;
        if (s->failed) return false;
        if (terr ? t->index != slot || !tt__terrain_ok(c, *t) : t->index || t->gen)
            return tt__src_fail(s, "contact record %u: terrain %u", k, t->index);
    }
    for (uint32_t k = 0; k < c->nevents; k++) { /* published: may name a terrain removed since */
        c->events[k].terrain.index = tt__get_u32(s);
        c->events[k].terrain.gen = tt__get_u32(s);
    }
    return !s->failed;
}

bool tt__terrains_load(tt_world *w, tt__collide *c, tt__source *s)
{
    if (tt__get_u32(s) != TT__ID('T', 'E', 'R', 'R')) return tt__src_fail(s, "terrains: bad marker");
    const uint32_t version = tt__get_u32(s);
    if (version != 1 && version != VERSION) return tt__src_fail(s, "terrains: unknown version");
    tt__terrains *ts = calloc(1, sizeof *ts);
    if (!ts) return tt__src_fail(s, "out of memory");
    c->terr = ts; /* freed with c on failure */
    if (!tt__get_pool(s, &ts->pool, TT_MAX_TERRAINS, w->tag, "terrains")) return false;
    const uint32_t n = ts->pool.count;
    if (n > s->len - s->at) return tt__src_fail(s, "terrains: %u slots are more than the stream holds", n);
    if (!(ts->t = calloc(n ? n : 1, sizeof *ts->t))) return tt__src_fail(s, "out of memory");
    ts->cap = n ? n : 1;
    for (uint32_t i = 0; i < n; i++) {
        const bool alive = tt__get_bool(s, "terrain alive");
        if (s->failed) return false;
        if (!alive) continue;
        if (!load_one(ts, &ts->t[i], s)) return false;
        ts->alive++;
    }
    /* a live slot must be out of the free list, a dead one in it or retired: the pool decides handles */
    for (uint32_t k = 0; k < ts->pool.free_count; k++)
        if (ts->t[ts->pool.free_list[k]].alive) return tt__src_fail(s, "terrains: a live slot is free");
    if (version >= 2) return load_handles(c, s);
    for (uint32_t k = 0; k < c->nprev; k++) /* version 1: the terrain a record's key names */
        if ((c->prev[k].key >> 62) == 3) {
            const uint32_t slot = (uint32_t)(c->prev[k].key >> 32) & 0x3FFFFFFFu;
            if (slot >= n || !ts->t[slot].alive) return tt__src_fail(s, "contact record %u: terrain %u", k, slot);
            c->prev[k].ev.terrain = (tt_terrain){slot, ts->pool.gen[slot]};
        }
    return !s->failed;
}
