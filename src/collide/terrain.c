/* tether — terrains: storage, freeing, the world rectangle, and the hook
 * every carve and fill ends in. The distance band contacts read is made in
 * terrain_band.c; the public calls are in terrain_api.c. */
#include "terrain_internal.h"

#include <stdlib.h>
#include <string.h>

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

bool tt__terrain_alloc(tt__terrain *T)
{
    const size_t w = (size_t)T->m->w, h = (size_t)T->m->h;
    T->tw = (int)((w + TT__TILE - 1) >> TT__TILE_SHIFT);
    T->th = (int)((h + TT__TILE - 1) >> TT__TILE_SHIFT);
    T->sdf = malloc(w * h * sizeof *T->sdf);
    T->tile = malloc((size_t)T->tw * (size_t)T->th * sizeof *T->tile);
    if (T->sdf && T->tile) return true;
    free(T->sdf);
    free(T->tile);
    T->sdf = T->tile = NULL;
    return false;
}

void tt__terrain_free_one(tt__terrain *T)
{
    tt_mask_destroy(T->m);
    free(T->sdf);
    free(T->tile);
    T->m = NULL;
    T->sdf = T->tile = NULL;
    T->alive = false;
}

void tt__terrains_free(tt__terrains *ts)
{
    if (!ts) return;
    for (uint32_t i = 0; i < ts->pool.count; i++)
        if (ts->t[i].alive) tt__terrain_free_one(&ts->t[i]);
    tt__pool_destroy(&ts->pool);
    free(ts->t);
    free(ts->scr.buf);
    free(ts);
}

size_t tt__terrains_bytes(const tt__terrains *ts)
{
    if (!ts) return 0;
    size_t b = sizeof *ts + tt__pool_bytes(&ts->pool) + (size_t)ts->cap * sizeof *ts->t + ts->scr.cap;
    for (uint32_t i = 0; i < ts->pool.count; i++) {
        const tt__terrain *T = &ts->t[i];
        if (T->alive)
            b += tt_mask_footprint(T->m->w, T->m->h) + (size_t)T->m->w * (size_t)T->m->h * sizeof(float) +
                 (size_t)T->tw * (size_t)T->th * sizeof(float);
    }
    return b;
}

void tt__terrain_changed(tt_world *w, double lox, double loy, double hix, double hiy)
{
    /* what rested on the old ground (or under the new) is no longer at rest */
    tt__sleep_wake_aabb(w, lox, loy, hix, hiy);
}
