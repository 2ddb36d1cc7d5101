/* tether — Lua binding of terrains (include/tether/terrain.h): carvable
 * pixel-mask ground in a world. Methods join the world class; every
 * argument is checked before the core is called. A terrain copies the mask
 * it is made from, so the Lua mask may be changed or collected at once;
 * w:terrain_mask gives a copy of the terrain's pixels back. */
#include "lua_common.h"
#include "lua_mask.h"

static const tl_range R_PIXEL = {1e-9, TT_MAX_VALUE, false};

static tt_terrain check_terrain(lua_State *L, tt_world *w, int arg)
{
    return tt_terrain_from_u64(tl_checkhandle(L, w, arg, TT_KIND_TERRAIN));
}

static const tl_opt terrain_opts[] = {
    TL_OPT_XY(tt_terrain_def, "origin", origin, &TL_R_COORD),
    TL_OPT_NUM(tt_terrain_def, "pixel", pixel, &R_PIXEL),
    TL_OPT_INT(tt_terrain_def, "band", band, 5, TT_TERRAIN_MAX_BAND),
    TL_SURFACE_OPTS(tt_terrain_def, ),
    TL_FILTER_OPTS(tt_terrain_def, ),
    TL_OPT_END,
};

/* w:terrain(m [, {origin = {x, y} (pixel (0, 0)'s top-left corner, m), pixel = 0.05 (m), band = 10 (pixels, 5…32),
 * restitution = 0, friction =, friction_static = 0.6, friction_kinetic = 0.5, category = 1, mask = 0xFFFF}]) → terrain */
static int w_terrain(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 3);
    tt_mask *m = tl_check_mask(L, 2);
    tt_terrain_def d = tt_terrain_def_default();
    tl_readopts(L, 3, terrain_opts, &d);
    m = tl_check_mask(L, 2); /* again: an option's metamethod may have run, but a mask is never freed under us */
    d.solid = m;
    tt_terrain t = tt_terrain_create(w, &d);
    if (t.gen == 0) tl_check_result(L, w, TT_EINVAL);
    tl_push_terrain(L, t);
    return 1;
}

static int w_remove_terrain(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tl_check_result(L, w, tt_terrain_destroy(w, check_terrain(L, w, 2)));
    return 0;
}

static int w_terrain_is_valid(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_pushboolean(L, tl_handle_is_live(L, w, 2, TT_KIND_TERRAIN));
    return 1;
}

static int w_terrain_count(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)tt_world_terrain_count(tl_check_world(L, 1)));
    return 1;
}

/* Circle painting: w:carve(t, x, y, r) and w:fill(t, x, y, r). */
static int paint_circle(lua_State *L, bool solid)
{
    tt_world *w = tl_check_world(L, 1);
    tt_terrain t = check_terrain(L, w, 2);
    tt_vec2 c = {tl_checknumber(L, 3, &TL_R_COORD), tl_checknumber(L, 4, &TL_R_COORD)};
    double r = tl_checknumber(L, 5, &TL_R_NONNEG);
    tl_check_result(L, w, tt_terrain_paint_circle(w, t, c, r, solid));
    return 0;
}
static int w_carve(lua_State *L) { return paint_circle(L, false); }
static int w_fill(lua_State *L) { return paint_circle(L, true); }

/* Mask painting: w:carve_mask(t, m, dx, dy) and w:fill_mask(t, m, dx, dy), m's pixel (0, 0) on the terrain's (dx, dy). */
static int paint_mask(lua_State *L, bool solid)
{
    tt_world *w = tl_check_world(L, 1);
    tt_terrain t = check_terrain(L, w, 2);
    tt_mask *m = tl_check_mask(L, 3);
    int dx = tl_check_offset(L, 4), dy = tl_check_offset(L, 5);
    tl_check_result(L, w, tt_terrain_paint_mask(w, t, m, dx, dy, solid));
    return 0;
}
static int w_carve_mask(lua_State *L) { return paint_mask(L, false); }
static int w_fill_mask(lua_State *L) { return paint_mask(L, true); }

/* w:terrain_mask(t [, into]) → a copy of the terrain's pixels (into: a mask of the same size, overwritten) */
static int w_terrain_mask(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_terrain t = check_terrain(L, w, 2);
    const tt_mask *m;
    tl_check_result(L, w, tt_terrain_get_mask(w, t, &m));
    int mw, mh;
    tt_mask_size(m, &mw, &mh);
    if (!lua_isnoneornil(L, 3)) {
        tl_mask_ud *u = tl_check_mask_ud(L, 3);
        int iw, ih;
        tt_mask_size(u->m, &iw, &ih);
        if (iw != mw || ih != mh) tl_argerror(L, 3, "mask of %dx%d expected (the terrain's size), got %dx%d", mw, mh, iw, ih);
        tt_mask_copy_into(u->m, m);
        u->version++;
        lua_settop(L, 3);
        return 1;
    }
    tl_mask_ud *u = tl_push_mask(L, mw, mh);
    tt_mask_copy_into(u->m, m);
    return 1;
}

/* w:terrain_place(t) → origin x, origin y, pixel */
static int w_terrain_place(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_mask_place p;
    tl_check_result(L, w, tt_terrain_get_place(w, check_terrain(L, w, 2), &p));
    lua_pushnumber(L, p.origin.x);
    lua_pushnumber(L, p.origin.y);
    lua_pushnumber(L, p.pixel);
    return 3;
}

/* w:terrain_distance(t, x, y) → signed distance (m, negative inside, clamped to the band), nx, ny */
static int w_terrain_distance(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_terrain t = check_terrain(L, w, 2);
    tt_vec2 p = {tl_checknumber(L, 3, &TL_R_COORD), tl_checknumber(L, 4, &TL_R_COORD)}, n;
    double d;
    tl_check_result(L, w, tt_terrain_distance(w, t, p, &d, &n));
    lua_pushnumber(L, d);
    lua_pushnumber(L, n.x);
    lua_pushnumber(L, n.y);
    return 3;
}

/* w:terrain_solid(t, x, y) → whether the point lies in a solid pixel */
static int w_terrain_solid(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_terrain t = check_terrain(L, w, 2);
    tt_vec2 p = {tl_checknumber(L, 3, &TL_R_COORD), tl_checknumber(L, 4, &TL_R_COORD)};
    bool s;
    tl_check_result(L, w, tt_terrain_is_solid(w, t, p, &s));
    lua_pushboolean(L, s);
    return 1;
}

/* w:set_terrain_material(t, restitution, friction_static [, friction_kinetic = friction_static]) */
static int w_set_terrain_material(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_terrain t = check_terrain(L, w, 2);
    double e = tl_checknumber(L, 3, &TL_R_UNIT), fs = tl_checknumber(L, 4, &TL_R_NONNEG);
    double fk = tl_optnumber(L, 5, &TL_R_NONNEG, fs);
    tl_check_result(L, w, tt_terrain_set_material(w, t, e, fs, fk));
    return 0;
}

static const luaL_Reg terrain_methods[] = {
    {"terrain", w_terrain},
    {"remove_terrain", w_remove_terrain},
    {"terrain_is_valid", w_terrain_is_valid},
    {"terrain_count", w_terrain_count},
    {"carve", w_carve},
    {"fill", w_fill},
    {"carve_mask", w_carve_mask},
    {"fill_mask", w_fill_mask},
    {"terrain_mask", w_terrain_mask},
    {"terrain_place", w_terrain_place},
    {"terrain_distance", w_terrain_distance},
    {"terrain_solid", w_terrain_solid},
    {"set_terrain_material", w_set_terrain_material},
    {NULL, NULL},
};

void tl_terrain_register(lua_State *L)
{
    tl_world_add_methods(L, terrain_methods);
}
