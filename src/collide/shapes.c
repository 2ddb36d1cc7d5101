/* tether — shapes: storage behind generational handles, and the calls that
 * make, read and change them. Their definitions' defaults and checks are in
 * collide_defs.c; their primitives in world coordinates, the static index
 * over them and the storage's freeing and size in static_index.c; their
 * outlines in shape_outline.c. */
#include "collide_internal.h"

#include <stdlib.h>
#include <string.h>

bool tt__shape_ok(const tt__collide *c, tt_shape s)
{
    return c && s.index < c->spool.count && s.gen != 0 && c->spool.gen[s.index] == s.gen && c->shapes[s.index].alive;
}

tt_shape tt_shape_create(tt_world *w, const tt_shape_def *def)
{
    tt_shape none = {0, 0};
    if (!w) { tt__fail(NULL, TT_EINVAL, "tt_shape_create: world is NULL"); return none; }
    if (tt__shape_check_def(w, def, "tt_shape_create") != TT_OK) return none;
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
                     ? tt__pool_alloc(&c->spool, TT_MAX_SHAPES, &grew) : UINT32_MAX;
    if (i == UINT32_MAX) {
        free(pts);
        if (!had) tt__group_remove_id(w, TT__COLL_ID);
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
    s->from = def->position;
    s->from_angle = def->angle;
    c->shapes_alive++;
    c->dirty = true;
    return (tt_shape){i, c->spool.gen[i]};
}

static void drop_records(tt__collide *c, uint64_t lo_mask, uint64_t match)
{
    uint32_t k = 0;
    for (uint32_t j = 0; j < c->nprev; j++)
        if ((c->prev[j].key & lo_mask) != match) c->prev[k++] = c->prev[j];
    c->nprev = k;
}

tt_result tt_shape_destroy(tt_world *w, tt_shape s)
{
    TT__SHAPE_CHECK("tt_shape_destroy");
    free(sh->pts);
    sh->pts = NULL;
    sh->alive = false;
    tt__pool_free(&c->spool, s.index);
    c->shapes_alive--;
    c->dirty = true;
    /* its contacts of the last step will never END: drop them (key: bit 63 shape, bits 32..62 shape slot) */
    drop_records(c, 0xFFFFFFFF00000000ull, (1ull << 63) | ((uint64_t)s.index << 32));
    return TT_OK;
}

bool tt_shape_is_valid(const tt_world *w, tt_shape s) { return w && tt__shape_ok(tt__collide_peek(w), s); }

tt_result tt_shape_set_transform(tt_world *w, tt_shape s, tt_vec2 position, double angle)
{
    TT__SHAPE_CHECK("tt_shape_set_transform");
    if (!tt__vec_ok(position)) return tt__fail(w, TT_EINVAL, "tt_shape_set_transform: position must be finite, |x| <= %g", TT_MAX_VALUE);
    if (!tt__in_range(angle, -TT_MAX_VALUE, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "tt_shape_set_transform: angle must be finite");
    if (sh->def.type == TT_SHAPE_AABB && angle != 0.0) return tt__fail(w, TT_EINVAL, "tt_shape_set_transform: an aabb cannot be turned (angle must be 0)");
    if (!sh->moved) { /* the first move since the last step: the path starts where that step left it */
        sh->from = sh->def.position;
        sh->from_angle = sh->def.angle;
    }
    sh->def.position = position;
    sh->def.angle = angle;
    sh->moved = true;
    c->any_moved = true;
    c->dirty = true;
    return TT_OK;
}

tt_result tt_shape_get_transform(const tt_world *w, tt_shape s, tt_vec2 *position, double *angle)
{
    TT__SHAPE_CHECK("tt_shape_get_transform");
    if (!position || !angle) return tt__fail(w, TT_EINVAL, "tt_shape_get_transform: out is NULL");
    *position = sh->def.position;
    *angle = sh->def.angle;
    return TT_OK;
}

tt_result tt_shape_set_material(tt_world *w, tt_shape s, double e, double fs, double fk)
{
    TT__SHAPE_CHECK("tt_shape_set_material");
    tt_result r = tt__material_check(w, e, fs, fk, TT_MAX_VALUE, "tt_shape_set_material");
    if (r != TT_OK) return r;
    sh->def.restitution = e;
    sh->def.friction_static = fs;
    sh->def.friction_kinetic = fk;
    return TT_OK;
}

tt_result tt_shape_set_filter(tt_world *w, tt_shape s, uint16_t category, uint16_t mask)
{
    TT__SHAPE_CHECK("tt_shape_set_filter");
    sh->def.category = category;
    sh->def.mask = mask;
    return TT_OK;
}

tt_result tt_shape_set_sensor(tt_world *w, tt_shape s, bool sensor)
{
    TT__SHAPE_CHECK("tt_shape_set_sensor");
    sh->def.sensor = sensor;
    return TT_OK;
}

tt_result tt_shape_get_type(const tt_world *w, tt_shape s, tt_shape_type *out)
{
    TT__SHAPE_CHECK("tt_shape_get_type");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_shape_get_type: out is NULL");
    *out = sh->def.type;
    return TT_OK;
}

tt_result tt_shape_get_user(const tt_world *w, tt_shape s, uint64_t *out)
{
    TT__SHAPE_CHECK("tt_shape_get_user");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_shape_get_user: out is NULL");
    *out = sh->def.user;
    return TT_OK;
}

uint32_t tt_world_shape_count(const tt_world *w)
{
    const tt__collide *c = w ? tt__collide_peek(w) : NULL;
    return c ? c->shapes_alive : 0;
}

tt_result tt_shape_get_aabb(const tt_world *w, tt_shape s, tt_vec2 *lo, tt_vec2 *hi)
{
    TT__SHAPE_CHECK("tt_shape_get_aabb");
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

tt_result tt_shape_get_sensor(const tt_world *w, tt_shape s, bool *out)
{
    TT__SHAPE_CHECK("tt_shape_get_sensor");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_shape_get_sensor: out is NULL");
    *out = sh->def.sensor;
    return TT_OK;
}
